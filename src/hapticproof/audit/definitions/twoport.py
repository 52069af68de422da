r"""A condition written in a general two-port's entries, against Llewellyn's criterion.

"A two-port is absolutely stable if and only if ``\Re z_{11} \ge 0``, ``\Re z_{22} \ge 0`` and
``2\Re z_{11}\Re z_{22} - \Re(z_{12}z_{21}) - |z_{12}z_{21}| \ge 0`` for all ``\omega``" is a
statement about every two-port, not about one the paper defines: its entries are complex numbers
at each frequency (the pole conditions on ``z_{11}``, ``z_{22}`` are in the words). The printed
condition is compared with Llewellyn's at one frequency, over the eight real unknowns:

* **proved** when each inequality of one is a positive multiple of an inequality of the other
  (``\eta \ge 1`` is the third inequality divided by ``|z_{12} z_{21}| > 0``), square roots reduced
  by :mod:`.radicals`;
* **disproved** by a constant two-port (a resistive network, negative resistances allowed: a
  system like any other) where one holds and the other does not, evaluated exactly.

The criterion has the same form in any immittance or hybrid description (``y``, ``h``, ``g``).

>>> import sympy as sp
>>> z11, z12, z21, z22 = sp.symbols("z_11 z_12 z_21 z_22")
>>> eta = (2*sp.re(z11)*sp.re(z22) - sp.re(z12*z21)) / sp.Abs(z12*z21)
>>> llewellyn_finding(eta >= 1, "z", "iff").verdict.value
'wrong'
"""

from __future__ import annotations

import random
from typing import Any

import sympy as sp

from hapticproof.audit.definitions.ports import two_port_entry
from hapticproof.audit.definitions.radicals import positive_multiple
from hapticproof.core.evidence import Evidence, Finding, Method, Verdict

__all__ = ["llewellyn_finding", "criterion"]

#: entries with a rational modulus (products too): the criterion's moduli stay rational
_VALUES = [sp.Integer(0), sp.Integer(1), sp.Integer(-1), sp.Integer(2), sp.Rational(1, 2), sp.Rational(-1, 2),
           sp.Integer(3), sp.Integer(-3), sp.I, -sp.I, sp.Rational(3, 5) + sp.Rational(4, 5) * sp.I,
           sp.Rational(4, 5) - sp.Rational(3, 5) * sp.I, sp.Rational(-3, 5) + sp.Rational(4, 5) * sp.I, 2 * sp.I,
           sp.Rational(-4, 5) - sp.Rational(3, 5) * sp.I]
_TRIES = 600


def criterion(letter: str) -> list[Any]:
    """Llewellyn's three inequalities in the entries written with ``letter`` (complex symbols)."""
    e = {(i, j): sp.Symbol(f"{letter}_{i}{j}") for i in (1, 2) for j in (1, 2)}
    product = e[1, 2] * e[2, 1]
    return [sp.GreaterThan(sp.re(e[1, 1]), 0), sp.GreaterThan(sp.re(e[2, 2]), 0),
            sp.GreaterThan(2 * sp.re(e[1, 1]) * sp.re(e[2, 2]) - sp.re(product) - sp.Abs(product), 0)]


def llewellyn_finding(printed: Any, letter: str, strength: str) -> Finding:
    """The printed condition (a relation or a conjunction) on a general two-port's entries written
    with ``letter``, claimed ``strength`` (``iff``, ``sufficient``, ``necessary``) for absolute
    stability."""
    links = _links(printed, letter)
    canonical = criterion(letter)
    real = _real_unknowns(letter)
    sufficient = _covers(canonical, links, real)        # each of Llewellyn's is one of the printed
    necessary = _covers(links, canonical, real)         # each printed is one of Llewellyn's
    facts = {"object": f"a general two-port ({letter}-parameters)", "property": "absolutely-stable", "strength": strength,
             "exact_method": "Llewellyn's criterion at each frequency"}
    witness_not_sufficient, witness_not_necessary = _counterexamples(links, canonical, letter,
                                                                    need_sufficient=not sufficient,
                                                                    need_necessary=not necessary)
    what = "the printed condition on a general two-port"
    if strength in ("iff", "sufficient") and witness_not_sufficient:
        return _wrong(what, "not sufficient", witness_not_sufficient, "it holds but Llewellyn's criterion fails", facts)
    if strength in ("iff", "necessary") and witness_not_necessary and not (strength == "iff" and sufficient):
        return _wrong(what, "not necessary", witness_not_necessary, "Llewellyn's criterion holds but it fails", facts)
    if strength == "iff" and sufficient and witness_not_necessary:
        return Finding(Verdict.CONSERVATIVE, f"{what} implies Llewellyn's criterion (each of its inequalities is printed) "
                       f"but is stronger than it: {_where(witness_not_necessary)} the two-port is absolutely stable and the "
                       "printed condition fails", Evidence(Method.COUNTEREXAMPLE, witness=witness_not_necessary, facts=facts))
    if strength == "sufficient" and sufficient:
        if necessary:
            return _proved(what, "is Llewellyn's criterion, so sufficient (and necessary)", facts)
        if witness_not_necessary:
            return Finding(Verdict.CONSERVATIVE, f"{what} implies Llewellyn's criterion (each of its inequalities is printed) "
                           f"and is strictly stronger: {_where(witness_not_necessary)} the printed condition fails on an "
                           "absolutely stable two-port", Evidence(Method.COUNTEREXAMPLE, witness=witness_not_necessary,
                                                                  facts=facts))
        return _proved(what, "implies Llewellyn's criterion (each of its inequalities is printed)", facts)
    if strength == "necessary" and necessary:
        return _proved(what, "follows from Llewellyn's criterion (each printed inequality is one of its own, up to a "
                       "positive factor)", facts)
    if strength == "iff" and sufficient and necessary:
        return _proved(what, "is Llewellyn's criterion: each inequality is one of the criterion's up to a positive factor, "
                       "and each of the criterion's is printed", facts)
    return Finding(Verdict.UNDECIDED, f"{what}: neither shown equivalent to Llewellyn's criterion nor separated from it "
                   f"on {_TRIES} constant two-ports", Evidence(Method.INSTANCES, facts=facts))


def _proved(what: str, how: str, facts: dict[str, Any]) -> Finding:
    return Finding(Verdict.CONFIRMED, f"{what} {how} (at each frequency; the pole conditions are in the words)",
                   Evidence(Method.CANONICAL_FORM, facts=facts))


def _wrong(what: str, failure: str, witness: dict[str, str], how: str, facts: dict[str, Any]) -> Finding:
    return Finding(Verdict.WRONG, f"{what} is {failure}: {_where(witness)} {how}",
                   Evidence(Method.COUNTEREXAMPLE, witness=witness, facts=facts))


def _where(witness: dict[str, str]) -> str:
    return "for the constant two-port " + ", ".join(f"{k} = {v}" for k, v in witness.items())


def _links(printed: Any, letter: str) -> list[Any]:
    """The printed relations, entries as complex symbols."""
    links = list(printed.args) if isinstance(printed, sp.And) else [printed]
    out = []
    for link in links:
        table = {s: sp.Symbol(s.name) for s in link.free_symbols if two_port_entry(s.name, {letter})}
        out.append(link.xreplace(table))
    return out


def _real_unknowns(letter: str) -> dict[sp.Symbol, sp.Expr]:
    out = {}
    for i in (1, 2):
        for j in (1, 2):
            name = f"{letter}_{i}{j}"
            out[sp.Symbol(name)] = sp.Symbol(f"{name}'re", real=True) + sp.I * sp.Symbol(f"{name}'im", real=True)
    return out


def _form(link: Any, real: dict[sp.Symbol, sp.Expr]) -> tuple[sp.Expr, bool] | None:
    """``(g, strict)`` with the relation ``g >= 0`` (``> 0``) in the real unknowns."""
    op = getattr(link, "rel_op", None)
    if op in (">=", ">"):
        g = link.lhs - link.rhs
    elif op in ("<=", "<"):
        g = link.rhs - link.lhs
    else:
        return None
    return sp.sympify(g).xreplace(real), op in (">", "<")


def _covers(targets: list[Any], sources: list[Any], real: dict[sp.Symbol, sp.Expr]) -> bool:
    """Each target relation is a positive multiple of some source relation (same strictness)."""
    forms = [_form(s, real) for s in sources]
    for target in targets:
        t = _form(target, real)
        if t is None:
            return False
        if not any(f is not None and f[1] == t[1] and positive_multiple(t[0], f[0]) for f in forms):
            return False
    return True


def _complex_text(v: sp.Expr) -> str:
    re_part, im_part = v.as_real_imag()
    if im_part == 0:
        return str(re_part)
    imaginary = f"{abs(im_part)}j" if abs(im_part) != 1 else "j"
    if re_part == 0:
        return ("-" if im_part < 0 else "") + imaginary
    return f"{re_part} {'-' if im_part < 0 else '+'} {imaginary}"


def _holds(links: list[Any], point: dict[sp.Symbol, sp.Expr]) -> bool | None:
    for link in links:
        sides = [sp.sympify(side).xreplace(point) for side in (link.lhs, link.rhs)]
        if any(side.has(sp.zoo, sp.nan, sp.oo) or not side.is_real for side in sides):
            return None                         # undefined there (eta with z_12 z_21 = 0)
        value = link.func(*sides)
        if value not in (sp.true, sp.false):
            value = sp.simplify(value)
            if value not in (sp.true, sp.false):
                return None
        if value is sp.false:
            return False
    return True


def _counterexamples(links: list[Any], canonical: list[Any], letter: str, *, need_sufficient: bool, need_necessary: bool
                     ) -> tuple[dict[str, str] | None, dict[str, str] | None]:
    """Constant two-ports where the printed condition holds and the criterion fails (not
    sufficient), and where the criterion holds and the printed condition fails (not necessary)."""
    rng = random.Random(5)
    symbols = [sp.Symbol(f"{letter}_{i}{j}") for i in (1, 2) for j in (1, 2)]
    not_sufficient = not_necessary = None
    for _ in range(_TRIES if (need_sufficient or need_necessary) else 0):
        point = {s: rng.choice(_VALUES) for s in symbols}
        printed, exact = _holds(links, point), _holds(canonical, point)
        if printed is None or exact is None:
            continue
        shown = {s.name: _complex_text(v) for s, v in point.items()}
        if need_sufficient and not_sufficient is None and printed and not exact:
            not_sufficient = shown
        if need_necessary and not_necessary is None and exact and not printed:
            not_necessary = shown
        if (not_sufficient or not need_sufficient) and (not_necessary or not need_necessary):
            break
    return not_sufficient, not_necessary
