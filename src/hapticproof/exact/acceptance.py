r"""What ``hapticproof check`` accepts: a verdict backed by evidence that the checker re-verified
**and** that is about the object the verdict is about (part of the checker: imports only
``core`` and the checker's own modules).

Re-verifying a certificate shows that it is true; it does not show that it is the certificate
of *this* report. A hostile author keeps genuine certificates and changes what they are
attached to: a sign certificate whose interval was shrunk to where the polynomial is
positive, a certificate of another transfer function, a definition object that was dropped, a
witness whose ``omega_T`` is another angle than its ``c`` and ``z``. This module holds what a
report shows against what its evidence is about:

* :func:`claim_of` -- what an entry claims (its verdict or decision; ``undecided`` and
  ``symbolic`` claim nothing): a claim without a certificate or judge object is **unbacked**;
* :func:`derive_binding` -- a ``derive`` report that shows ``G_inverse`` and a ``proved`` or
  ``disproved`` verdict carries its ``positive-real`` definition object; every certificate that
  names a transfer function names the report's ``G^{-1}`` (exactly), every pole certificate is
  about its denominator, the sign certificate of a scalar ``G^{-1}`` is tied to ``Re G^{-1}``
  (its ``c``-form is proved equal to it), and the ``G_inverse`` shown is that ``G^{-1}``,
  exactly as a rational function;
* :func:`audit_binding` -- an audit entry's judge object fits its verdict: a confirmed condition
  judged at sample points shows no counterexample, a counterexample is shown where the judge
  holds one, and no confirmed entry carries its own exact recheck's disproof;
* :func:`witness_problems` -- every displayed point of the circle is one point: ``|z| = 1``,
  ``c = Re z`` and ``omega_T`` the angle of ``z``.

(The whole range of ``c`` or ``x`` and the known kinds are checked with each certificate:
:func:`hapticproof.exact.checker.check_certificate`.)

>>> witness_problems({"witness": {"c": "-1", "z": ["-1", "0"], "omega_T": "pi"}})
[]
>>> witness_problems({"witness": {"c": "-1", "z": ["-1", "0"], "omega_T": "pi/2"}})
['the displayed omega_T = pi/2 is not the angle of z = -1 + 0j (cos 0, sin 1)']
"""

from __future__ import annotations

import re
from collections.abc import Iterator, Mapping
from fractions import Fraction
from typing import Any

import flint

from hapticproof.core.naming import witness_keys
from hapticproof.exact.checkarith import (
    CheckFailed,
    CheckSkipped,
    Gaussian,
    budget,
    certificates,
    charpoly_coefficients,
    exact_q,
    has_root_outside,
    is_kind,
    is_proper,
    json_poly,
    max_degree,
    Sturm,
)

__all__ = ["CLAIMLESS", "angle", "audit_binding", "claim_of", "decision_problems", "definition_proof", "differing_entry", "derive_binding", "factored_transfers",
           "rational_of", "residue_matrix", "teleoperator_bounds", "unbound_verdict",
           "same_transfer", "witness_problems"]

#: Verdicts and decisions that claim nothing (no evidence needed to show them).
CLAIMLESS = frozenset({"undecided", "symbolic"})

#: Fields only a derive report of a wall or of m users shows (about its ``G^{-1}``).
_DERIVED_KEYS = frozenset({"G_inverse", "hermitian_part", "approximation", "residues", "poles", "worst_case", "minimiser",
                           "minimum", "users", "delays", "delay", "residue_at_1", "worst_case_condition", "worst_c"})

#: The condition of a scalar derive report that a sign certificate decides.
_SIGN_CONDITION = "Re G^-1 >= 0 for all w"


def claim_of(entry: Any) -> str | None:
    """The verdict or decision an entry shows, ``None`` when it claims nothing.

    >>> claim_of({"verdict": "confirmed"}), claim_of({"decision": "undecided"}), claim_of({"name": "x"})
    ('confirmed', None, None)
    """
    if not isinstance(entry, Mapping):
        return None
    for key in ("verdict", "decision"):
        value = entry.get(key)
        if isinstance(value, str):
            return None if value in CLAIMLESS else value
    return None


def _walk(node: Any, key: str) -> Iterator[Any]:
    """Every value under ``key`` inside a JSON value."""
    if isinstance(node, Mapping):
        for k, value in node.items():
            if k == key:
                yield value
            yield from _walk(value, key)
    elif isinstance(node, list):
        for value in node:
            yield from _walk(value, key)


def _exact_list(coeffs: Any) -> list[Fraction]:
    values = [exact_q(v) for v in coeffs]
    while values and values[-1] == 0:
        values.pop()
    return values


def same_transfer(a: Any, b: Any) -> bool:
    """The same transfer function or matrix (exact coefficients; trailing zeros ignored).

    >>> same_transfer({"variable": "z", "num": ["1", "0"], "den": ["-1", "1"]}, {"num": ["1"], "den": ["-1", "1"]})
    True
    """
    if not isinstance(a, Mapping) or not isinstance(b, Mapping):
        return False
    if a.get("variable", "z") != b.get("variable", "z"):
        return False
    if "entries" in a or "entries" in b:
        ra, rb = a.get("entries"), b.get("entries")
        if not isinstance(ra, list) or not isinstance(rb, list) or len(ra) != len(rb):
            return False
        return all(isinstance(x, list) and isinstance(y, list) and len(x) == len(y) and
                   all(same_transfer(e, f) for e, f in zip(x, y)) for x, y in zip(ra, rb))
    return _exact_list(a["num"]) == _exact_list(b["num"]) and _exact_list(a["den"]) == _exact_list(b["den"]) \
        and a.get("factor") == b.get("factor")


def _poles(transfer: Mapping[str, Any]) -> flint.fmpq_poly:
    """The denominator of ``G^{-1}`` in lowest terms (a matrix: the lcm of its entries')."""
    cells = [e for row in transfer["entries"] for e in row] if "entries" in transfer else [transfer]
    out = flint.fmpq_poly([1])
    for cell in cells:
        num, den = json_poly(cell["num"]), json_poly(cell["den"])
        reduced = den / num.gcd(den) if not num.is_zero() else flint.fmpq_poly([1])
        out = out * reduced / out.gcd(reduced)
    return out


def _proportional(p: flint.fmpq_poly, q: flint.fmpq_poly) -> bool:
    if p.is_zero() or q.is_zero():
        return p.is_zero() and q.is_zero()
    quotient, remainder = divmod(p, q)
    return remainder.is_zero() and quotient.degree() == 0


def _about_poles(cert: Mapping[str, Any], cond: Mapping[str, Any], poles: flint.fmpq_poly) -> bool:
    """A roots certificate is about the poles of ``G^{-1}``: its polynomial is their denominator
    (up to a constant), or -- for a proof that no pole is outside or that the boundary poles are
    simple (an m-user ``G^{-1}`` decided by its kernels' denominator) -- a multiple of it."""
    p = json_poly(cert["polynomial"])
    if _proportional(p, poles):
        return True
    if p.is_zero() or cond.get("decision") != "proved":
        return False
    return (p % poles).is_zero()


def derive_binding(report: Mapping[str, Any]) -> list[str]:
    """What a ``derive`` report's certificates and displays are about, against its ``G^{-1}``."""
    problems: list[str] = []
    verdict = report.get("verdict")
    definition = report.get("definition")
    conditions = report.get("conditions")
    if verdict in ("proved", "disproved") and not conditions:
        return [f"the verdict {verdict!r} is shown with no condition to back it (its conditions were removed)"]
    if _DERIVED_KEYS & set(report) and verdict in ("proved", "disproved") and \
            not (isinstance(definition, Mapping) and definition.get("judge") == "positive-real") and \
            unbound_verdict(report) is None:
        return [(f"the verdict {verdict!r} carries no positive-real definition object: nothing ties it to G^-1 "
                 "(a report whose definition was removed)")]
    if not isinstance(definition, Mapping) or not isinstance(definition.get("transfer"), Mapping):
        return problems
    transfer = definition["transfer"]
    scalar = "num" in transfer
    poles = _poles(transfer)
    for cond in report.get("conditions") or []:
        if not isinstance(cond, Mapping):
            continue
        name = str(cond.get("name"))
        for cert in certificates(cond):
            kind = cert["certificate"]
            named = "transfer" in cert and kind != "infinity" or kind == "infinity" and scalar
            if named and not same_transfer(cert.get("transfer"), transfer):
                problems.append(f"{name}: the {kind} certificate is about another transfer function than the report's G^-1")
            if kind == "roots" and cert.get("domain") == "disk" and not _about_poles(cert, cond, poles):
                problems.append(f"{name}: the roots certificate is not about the denominator of the report's G^-1")
        if scalar and name == _SIGN_CONDITION and cond.get("decision") in ("proved", "disproved"):
            signs = [c for c in certificates(cond) if c["certificate"] in ("sign", "chebyshev-sign")]
            if not signs:
                problems.append(f"{name}: no sign certificate decides it")
            for cert in signs:
                if not ("transfer" in cert and "numerator" in cert and "denominator" in cert):
                    problems.append(f"{name}: the sign certificate is not tied to Re G^-1 (no transfer function and "
                                    "c-form to compare): its polynomial may be any polynomial")
            problems += _shown_minimum(report, cond)
    if scalar:
        problems += _shown_inverse(report, transfer)
        if definition.get("domain") == "disk":
            problems += shown_poles(report, transfer)
    if verdict == "proved" or definition.get("decision") == "proved":
        problems += definition_proof(report)
    return problems


def unbound_verdict(report: Mapping[str, Any]) -> str | None:
    """Why a derive report's verdict is about a ``G^{-1}`` the checker holds no object of, when
    the report says so itself: a symbolic scene (its ``G_inverse`` reads with parameters) or an
    m-user scene decided by its modes. Such a verdict is never accepted as re-verified (re-derive
    it); ``None`` otherwise (a numeric report must carry its definition object)."""
    if isinstance(report.get("definition"), Mapping) or report.get("verdict") not in ("proved", "disproved"):
        return None
    if report.get("by_modes") is True and isinstance(report.get("modes"), list):
        return "an m-user scene decided by its modes carries no G^-1 matrix to bind its verdict to: re-derive it (--full)"
    shown = report.get("G_inverse")
    try:
        rational_of(shown, max_degree())
    except ValueError as err:
        if str(err) == "it has parameters":
            return "a symbolic scene's verdict (its G^-1 has parameters): not re-verifiable by the checker, re-derive it"
    except (TypeError, ArithmeticError, RecursionError):
        pass
    return None


def shown_poles(report: Mapping[str, Any], transfer: Mapping[str, Any]) -> list[str]:
    """The ``poles``, ``residues`` and ``minimiser`` a scalar report shows, re-derived from its
    ``G^{-1}``: a rational pole is a root of its denominator in lowest terms of the multiplicity
    and location shown, every rational root is shown, a residue shown at ``z0 = +-1`` is
    ``Res`` (or ``Res/z0``) of ``G^{-1}`` there, and the minimiser is a ``c`` in ``[-1, 1]``.

    >>> wall = {"variable": "z", "num": ["-1", "3", "1"], "den": ["0", "-1", "1"]}
    >>> shown_poles({"poles": [{"z": "1", "multiplicity": 1, "location": "outside"}]}, wall)
    ['the pole shown at z = 1 is on the unit circle, not outside', 'the pole z = 0 of G^-1 is not shown']
    """
    problems: list[str] = []
    num, den = json_poly(transfer["num"]), json_poly(transfer["den"])
    if not num.is_zero():
        g = num.gcd(den)
        num, den = num / g, den / g
    shown = report.get("poles")
    if isinstance(shown, list):
        seen, algebraic = set(), 0
        for pole in shown:
            if not isinstance(pole, Mapping):
                continue
            try:
                z0 = exact_q(pole.get("z"))
            except (TypeError, ValueError, ZeroDivisionError):
                problems += _algebraic_pole(pole, den)    # shown by its decimal approximation
                algebraic += 1
                continue
            seen.add(z0)
            factor = flint.fmpq_poly([-flint.fmpq(z0.numerator, z0.denominator), 1])
            order, rest = 0, den
            while rest.degree() > 0:
                quotient, remainder = divmod(rest, factor)
                if not remainder.is_zero():
                    break
                order, rest = order + 1, quotient
            if order == 0:
                problems.append(f"the pole shown at z = {pole.get('z')} is not a pole of G^-1")
                continue
            if pole.get("multiplicity") != order:
                problems.append(f"the pole shown at z = {pole.get('z')} has multiplicity {order}, not "
                                f"{str(pole.get('multiplicity'))[:20]}")
            where = "inside" if abs(z0) < 1 else "on" if abs(z0) == 1 else "outside"
            if pole.get("location") != where:
                problems.append(f"the pole shown at z = {pole.get('z')} is {'on the unit circle' if where == 'on' else where}, "
                                f"not {str(pole.get('location'))[:20]}")
        missing = [z0 for z0 in _rational_roots(den) if z0 not in seen]
        problems += [f"the pole z = {z0} of G^-1 is not shown" for z0 in missing]
        distinct = (den / den.gcd(den.derivative())).degree() if den.degree() > 0 else 0
        if len(seen) + algebraic + len(missing) != distinct:
            problems.append(f"{len(seen) + algebraic} poles are shown, G^-1 has {distinct} distinct poles")
    residues = report.get("residues")
    for residue in residues if isinstance(residues, list) else ():
        try:
            z0 = exact_q(residue.get("z"))
        except (TypeError, ValueError, ZeroDivisionError, AttributeError):
            problems.append(f"the residue shown at z0 = {str(residue.get('z') if isinstance(residue, Mapping) else residue)[:40]} "
                            "is at no rational pole of G^-1 on the circle (an algebraic pole's residue is not shown)")
            continue
        if abs(z0) != 1 or den(flint.fmpq(z0.numerator, z0.denominator)) != 0:
            problems.append(f"the residue shown at z0 = {z0} is at no pole of G^-1 on the unit circle")
            continue
        if den.derivative()(flint.fmpq(z0.numerator, z0.denominator)) == 0:
            if residue.get("condition") == "proved":       # a multiple pole on the circle: never a positive residue
                problems.append(f"the residue condition at the multiple pole z0 = {z0} is shown 'proved'")
            continue
        try:
            value = exact_q(residue.get("residue"))
        except (TypeError, ValueError, ZeroDivisionError, AttributeError):
            problems.append(f"the residue shown at the simple pole z0 = {z0} cannot be read")
            continue
        own = residue_matrix([transfer], transfer, z0)[0][0]
        if value not in (own, own * z0):
            problems.append(f"the residue shown at z0 = {z0} is {residue.get('residue')}, G^-1 has Res/z0 = {own}")
        expected = "proved" if own >= 0 else "disproved"
        if residue.get("condition") in ("proved", "disproved") and residue.get("condition") != expected:
            problems.append(f"the residue condition at z0 = {z0} is shown {residue.get('condition')!r}, "
                            f"Res/z0 = {own} makes it {expected!r}")
    worst = report.get("worst_case")
    sign = next((c for c in report.get("conditions") or [] if isinstance(c, Mapping) and c.get("name") == _SIGN_CONDITION), None)
    if worst is not None and worst not in ("True", "False", True, False) and sign is not None and \
            sign.get("decision") in ("proved", "disproved"):
        problems.append(f"the worst case shown ({str(worst)[:40]!r}) is no truth value: the worst case of a numeric "
                        "G^-1 is True or False")
    if worst in ("True", "False", True, False) and sign is not None and sign.get("decision") in ("proved", "disproved"):
        if (str(worst) == "True") != (sign.get("decision") == "proved"):
            problems.append(f"the worst case shown ({worst}) contradicts the decision of {_SIGN_CONDITION} "
                            f"({sign.get('decision')})")
    try:
        at = exact_q(report.get("minimiser"))
    except (TypeError, ValueError, ZeroDivisionError):
        at = None
    if at is not None and not -1 <= at <= 1:
        problems.append(f"the minimiser shown c = {report.get('minimiser')} is not a point of the circle (|c| > 1)")
    return problems


def _algebraic_pole(pole: Mapping[str, Any], den: flint.fmpq_poly) -> list[str]:
    """A pole shown by its decimals (``{"approx": "0.5 - 0.2887*I"}``): within ``1e-9`` of an
    irrational root of the denominator, of that root's multiplicity and location."""
    shown = pole.get("z")
    text = shown.get("approx") if isinstance(shown, Mapping) else None
    if not isinstance(text, str) or len(text) > 200:
        return [f"the pole shown at z = {str(shown)[:40]} is neither a rational number nor a decimal approximation"]
    try:            # "0.5 - 0.2887*I", "-0.7071*I", "0.5": Python's complex() reads it (never evaluates)
        point = complex(text.replace("*I", "j").replace(" ", ""))
    except ValueError:
        return [f"the pole shown at z = {text[:40]} cannot be read"]
    if den.degree() > max_degree():
        raise CheckSkipped(f"a denominator of degree {den.degree()} is above the checker's limit")
    g = den.gcd(den.derivative())
    square_free = den / g if g.degree() > 0 else den
    for root in square_free.complex_roots():
        z = root[0]
        if abs(complex(z.real.mid(), z.imag.mid()) - point) < 1e-9:
            order = _root_order(den, z)
            where = "inside" if (abs(z) < 1) is True else "outside" if (abs(z) > 1) is True else "on"
            problems = []
            if pole.get("multiplicity") != order:
                problems.append(f"the pole shown at z = {text[:40]} has multiplicity {order}, not {pole.get('multiplicity')}")
            if pole.get("location") != where:
                problems.append(f"the pole shown at z = {text[:40]} is {where}, not {str(pole.get('location'))[:20]}")
            return problems
    return [f"the pole shown at z = {text[:40]} is not a pole of G^-1"]


def _root_order(p: flint.fmpq_poly, z: Any) -> int:
    """The multiplicity of the root (a ball) ``z`` of ``p``: derivatives that contain 0 there."""
    order, q = 0, p
    while q.degree() > 0 and flint.acb_poly(q)(z).contains(0):
        order, q = order + 1, q.derivative()
    return order


def _rational_roots(p: flint.fmpq_poly) -> list[Fraction]:
    """The rational roots of ``p`` (from its factors of degree one)."""
    if p.degree() <= 0:
        return []
    _, factors = p.numer().factor()
    out = []
    for factor, _ in factors:
        if factor.degree() == 1:
            a, b = factor.coeffs()
            out.append(Fraction(-int(a), int(b)))
    return sorted(out)


def definition_proof(report: Mapping[str, Any]) -> list[str]:
    r"""What a ``proved`` verdict of discrete positive realness (Definition 2) needs, re-derived
    from the report's own ``G^{-1}`` (its definition object) -- never from what the report says
    about it: (i) ``G^{-1}`` proper, (ii) no pole in ``|z| > 1`` (Routh-Hurwitz after the
    bilinear map), (iii) the unit-circle poles simple with (iv) ``Res/z_0`` (a residue matrix)
    Hermitian PSD, computed here at ``z_0 = +-1`` (a pole elsewhere on the circle is algebraic:
    not re-derived, never success), and (v) the Hermitian part PSD on the whole circle: a sign
    certificate of ``Re G^{-1}`` (a ``psd`` certificate of a matrix) that holds over the whole
    range of ``c`` and names this ``G^{-1}``. (The certificate itself is re-verified with the
    report's others.) A negative worst case shown with the proof is refused.

    >>> wall = {"num": ["-1", "3", "1"], "den": ["0", "-1", "1"]}        # (z^2 + 3z - 1)/(z^2 - z)
    >>> report = {"verdict": "proved", "conditions": [], "definition": {"judge": "positive-real", "domain": "disk",
    ...           "decision": "proved", "transfer": dict(wall, variable="z")}}
    >>> definition_proof(report)
    ['Re G^-1 >= 0 for all w: no sign certificate of Re G^-1 over the whole circle backs the proof']
    """
    definition = report.get("definition")
    if not isinstance(definition, Mapping) or definition.get("judge") != "positive-real":
        return []
    transfer = definition.get("transfer")
    if not isinstance(transfer, Mapping):
        return ["the proof's definition object carries no transfer function"]
    if definition.get("domain") != "disk":
        return []                          # continuous definitions: decided by their certificates
    scalar = "num" in transfer
    problems: list[str] = []
    with budget():
        try:
            problems += _poles_of_proof(transfer)
        except CheckSkipped as skip:
            problems.append(f"the pole conditions of the proof are not re-derived: {skip}")
        except (CheckFailed, ValueError, ZeroDivisionError) as err:
            problems.append(f"the pole conditions of the proof cannot be re-derived ({str(err)[:120]})")
    signs = []
    for cond in report.get("conditions") or []:
        if not isinstance(cond, Mapping) or cond.get("decision") != "proved":
            continue
        for cert in certificates(cond):
            kind = cert["certificate"]
            if not cert.get("holds") is True or not same_transfer(cert.get("transfer"), transfer):
                continue
            if scalar and kind in ("sign", "chebyshev-sign") and "numerator" in cert and "denominator" in cert:
                signs.append(cert)
            if not scalar and kind == "psd":
                signs.append(cert)
    if not signs:
        what = "psd certificate of G^-1 + G^-H" if not scalar else "sign certificate of Re G^-1"
        problems.append(f"{_SIGN_CONDITION}: no {what} over the whole circle backs the proof")
    for where in (report, *[c for c in report.get("conditions") or [] if isinstance(c, Mapping)]):
        try:
            low = exact_q(where.get("minimum"))
        except (TypeError, ValueError, ZeroDivisionError):
            continue
        if low < 0:
            problems.append(f"the minimum shown {where.get('minimum')} is negative, but the verdict is 'proved'")
            break
    return problems


def _poles_of_proof(transfer: Mapping[str, Any]) -> list[str]:
    """Conditions (i)-(iv) of Definition 2 from ``G^{-1}`` itself."""
    cells = [e for row in transfer["entries"] for e in row] if "entries" in transfer else [transfer]
    if any(len(cell["num"]) > max_degree() + 1 or len(cell["den"]) > max_degree() + 1 for cell in cells):
        raise CheckSkipped(f"a degree above the checker's limit of {max_degree()}")
    problems = []
    if not all(is_proper(json_poly(c["num"]), json_poly(c["den"])) for c in cells):
        problems.append("poles in |z| <= 1: G^-1 has a pole at z = oo (not proper)")
    poles = _poles(transfer)
    if has_root_outside(poles, "disk"):
        return problems + ["poles in |z| <= 1: G^-1 has a pole outside the unit circle"]
    # no pole outside: the poles on the circle are the common roots of p and its reversal
    reverse = flint.fmpq_poly(list(reversed(poles.coeffs())))
    circle = poles.gcd(reverse) if poles.degree() > 0 else flint.fmpq_poly([1])
    if circle.degree() > 0 and circle.gcd(circle.derivative()).degree() > 0:
        return problems + ["unit-circle poles simple: G^-1 has a multiple pole on the unit circle"]
    rest = circle
    for z0 in (Fraction(1), Fraction(-1)):
        factor = flint.fmpq_poly([-z0.numerator, 1])
        quotient, remainder = divmod(rest, factor)
        if not remainder.is_zero():
            continue
        rest = quotient
        residue = residue_matrix(cells, transfer, z0)
        m = len(residue)
        if any(residue[i][j] != residue[j][i] for i in range(m) for j in range(m)):
            problems.append(f"Res/z0 >= 0 at unit-circle poles: the residue matrix at z0 = {z0} is not Hermitian")
        elif not all(e >= 0 for e in charpoly_coefficients([[Gaussian(v) for v in row] for row in residue])):
            problems.append(f"Res/z0 >= 0 at unit-circle poles: the residue at z0 = {z0} is not PSD (re-derived from G^-1)")
    if rest.degree() > 0:
        problems.append("Res/z0 >= 0 at unit-circle poles: G^-1 has algebraic poles on the unit circle whose residues "
                        "the checker cannot re-derive (not re-verified)")
    return problems


def residue_matrix(cells: list, transfer: Mapping[str, Any], z0: Fraction) -> list[list[Fraction]]:
    """``Res_{z0} G^{-1} / z0`` entry by entry (a 1 x 1 matrix of a scalar ``G^{-1}``)."""
    point = flint.fmpq(z0.numerator, z0.denominator)
    factor = flint.fmpq_poly([-point, 1])

    def one(cell: Mapping[str, Any]) -> Fraction:
        num, den = json_poly(cell["num"]), json_poly(cell["den"])
        if num.is_zero():
            return Fraction(0)
        g = num.gcd(den)
        num, den = num / g, den / g
        quotient, remainder = divmod(den, factor)
        if not remainder.is_zero():
            return Fraction(0)
        value = num(point) / quotient(point) / point
        return Fraction(int(value.p), int(value.q))

    if "entries" in transfer:
        return [[one(cell) for cell in row] for row in transfer["entries"]]
    return [[one(transfer)]]


def _shown_minimum(report: Mapping[str, Any], cond: Mapping[str, Any]) -> list[str]:
    """The worst case shown agrees with the sign decision: not negative when ``Re G^-1 >= 0`` is
    proved, at most the value at the disproof's witness when it is disproved."""
    out = []
    try:
        value = exact_q(((cond.get("evidence") or {}).get("facts") or {}).get("value"))
    except (TypeError, ValueError, ZeroDivisionError):
        value = None
    form = next(((json_poly(c["numerator"]), json_poly(c["denominator"])) for c in certificates(cond)
                 if c["certificate"] == "sign" and "numerator" in c and "denominator" in c), None)
    for where in (report, cond):
        shown = where.get("minimum")
        try:
            low = exact_q(shown)
        except (TypeError, ValueError, ZeroDivisionError):     # none, or a ball of a long delay's worst case
            if shown is not None and not (isinstance(shown, str) and _BALL.fullmatch(shown)):
                out.append(f"the minimum shown {str(shown)[:40]!r} is neither an exact number nor a ball")
            elif shown is not None and form is not None:
                out += _ball_of_form(form, shown, where.get("minimiser"))
            elif form is not None and where.get("minimiser") is not None:
                out += _minimiser_of_form(form, where.get("minimiser"))
            continue
        if cond.get("decision") == "proved" and low < 0:
            out.append(f"the minimum shown {shown} is negative, but Re G^-1 >= 0 is proved")
        if cond.get("decision") == "disproved" and value is not None and low > value:
            out.append(f"the minimum shown {shown} is above Re G^-1 = {value} at the disproof's witness")
        if form is not None:
            out += _minimum_of_form(form, low, where.get("minimiser"), shown)
    return out


#: A ball ``[mid +/- rad]`` (a long delay's worst case, by interval arithmetic).
_BALL = re.compile(r"\[?-?\d+(?:\.\d+)?(?:e[-+]?\d+)? \+/- \d+(?:\.\d+)?(?:e[-+]?\d+)?\]?")


def _minimum_of_form(form: tuple[flint.fmpq_poly, flint.fmpq_poly], low: Fraction, at: Any, shown: Any) -> list[str]:
    """The minimum shown is ``Re G^-1 = N(c)/D(c)`` (the sign certificate's c-form, tied to
    ``G^-1``) at the minimiser shown, and no value of ``Re G^-1`` on ``[-1, 1]`` is below it."""
    num, den = form
    try:
        c = exact_q(at)
    except (TypeError, ValueError, ZeroDivisionError):
        return [f"the minimum shown {str(shown)[:40]} has no minimiser c in [-1, 1] to be read"]
    if not -1 <= c <= 1:
        return [f"the minimiser shown c = {str(at)[:40]} is not in [-1, 1]"]
    q = flint.fmpq(c.numerator, c.denominator)
    if den(q) == 0:
        return []                                # a pole of Re G^-1 on the circle: no finite minimum there
    value = num(q) / den(q)
    if value != flint.fmpq(low.numerator, low.denominator):
        return [f"the minimum shown {str(shown)[:40]} is not Re G^-1 = {value} at the minimiser shown c = {at}"]
    if _at_least(form, low) is False:
        return [f"the minimum shown {str(shown)[:40]} is not the minimum: Re G^-1 is below it somewhere in c in [-1, 1]"]
    return []


def _at_least(form: tuple[flint.fmpq_poly, flint.fmpq_poly], low: Fraction) -> bool | None:
    """Whether ``N(c)/D(c) >= low`` for every ``c`` in ``[-1, 1]`` (exact); ``None`` when ``D``
    vanishes there (poles on the circle: the infimum is not at a point)."""
    num, den = form
    if den.degree() > 0 and not _sign_fixed_on(den, Fraction(-1), Fraction(1)):
        return None
    sign = 1 if den(0) > 0 else -1
    return _nonnegative_on((num - den * flint.fmpq(low.numerator, low.denominator)) * sign, Fraction(-1), Fraction(1))


def _minimiser_of_form(form: tuple[flint.fmpq_poly, flint.fmpq_poly], at: Any) -> list[str]:
    """A minimiser shown without its minimum: ``Re G^-1`` there is its minimum over ``[-1, 1]``."""
    num, den = form
    try:
        c = exact_q(at)
    except (TypeError, ValueError, ZeroDivisionError):
        return [f"the minimiser shown {str(at)[:40]!r} is no exact c"]
    q = flint.fmpq(c.numerator, c.denominator)
    if not -1 <= c <= 1 or den(q) == 0:
        return [] if -1 <= c <= 1 else [f"the minimiser shown c = {str(at)[:40]} is not in [-1, 1]"]
    value = num(q) / den(q)
    return _minimum_of_form(form, Fraction(int(value.p), int(value.q)), at, at)


def _ball_of_form(form: tuple[flint.fmpq_poly, flint.fmpq_poly], shown: str, at: Any) -> list[str]:
    """A minimum shown as a ball ``[m +/- r]``: ``Re G^-1 >= m - r`` on ``[-1, 1]`` (exact), and at
    the minimiser shown (when it is exact) it is at most ``m + r``."""
    mid, _, rad = shown.strip("[]").partition("+/-")
    m, r = Fraction(mid.strip()), Fraction(rad.strip())
    num, den = form
    low = m - r
    bounded = _at_least(form, low)
    if bounded is None:
        return []                                # poles on the circle: no finite minimum to bound
    if not bounded:
        return [f"the minimum shown {shown[:40]} is not a bound of Re G^-1: it is below {low} somewhere in [-1, 1]"]
    try:
        c = exact_q(at)
    except (TypeError, ValueError, ZeroDivisionError):
        return []                                # an irrational minimiser (a ball too): the lower bound is all
    q = flint.fmpq(c.numerator, c.denominator)
    if -1 <= c <= 1 and den(q) != 0 and num(q) / den(q) > flint.fmpq((m + r).numerator, (m + r).denominator):
        return [f"the minimum shown {shown[:40]} is below Re G^-1 at the minimiser shown c = {at}"]
    return []


def _odd_part(p: flint.fmpq_poly) -> flint.fmpq_poly:
    """The product of the squarefree factors of ``p`` of odd multiplicity (Yun): where ``p``
    changes sign."""
    out, i = flint.fmpq_poly([1]), 1
    g = p.gcd(p.derivative())
    c = p / g
    d = p.derivative() / g - c.derivative()
    while c.degree() > 0:
        a = c.gcd(d)
        if i % 2 == 1:
            out = out * a
        c = c / a
        d = d / a - c.derivative()
        i += 1
    return out


def _sign_fixed_on(p: flint.fmpq_poly, a: Fraction, b: Fraction) -> bool:
    """``p`` has no root in the closed interval ``[a, b]``."""
    if p(flint.fmpq(a.numerator, a.denominator)) == 0 or p(flint.fmpq(b.numerator, b.denominator)) == 0:
        return False
    return Sturm(p).count_open(a, b) == 0


def _nonnegative_on(p: flint.fmpq_poly, a: Fraction, b: Fraction) -> bool:
    """``p >= 0`` on ``[a, b]``, exactly: no root of odd multiplicity inside and ``p >= 0`` at a
    point that is no root."""
    if p.is_zero():
        return True
    odd = _odd_part(p)
    if odd.degree() > 0 and Sturm(odd).count_open(a, b) > 0:
        return False
    for k in range(2, p.degree() + 4):              # a point of (a, b) that is no root of p
        x = a + (b - a) / k
        value = p(flint.fmpq(x.numerator, x.denominator))
        if value != 0:
            return value > 0
    return True


def _numeric(report: Mapping[str, Any]) -> bool:
    """A report about a numeric ``G^{-1}`` (which then has its definition object): a certificate
    names a transfer function with numbers, or the ``G_inverse`` shown has no parameter. (A
    symbolic ``G^{-1}`` has no definition object; its decisions rest on their certificates.)"""
    if any("transfer" in cert for cert in certificates(report.get("conditions"))):
        return True
    shown = report.get("G_inverse")
    if isinstance(shown, list):
        return False                    # a matrix shown entry by entry: its certificates say whether it is numeric
    try:
        rational_of(shown, 10**6)
    except (ValueError, TypeError, ArithmeticError, RecursionError):
        return False
    return True


def _shown_inverse(report: Mapping[str, Any], transfer: Mapping[str, Any]) -> list[str]:
    """The ``G_inverse`` shown, read as a rational function of ``z``, is the definition's ``G^{-1}``
    (an identity of polynomials, exact)."""
    if "G_inverse" not in report:
        return []
    shown = report["G_inverse"]
    try:
        num, den = rational_of(shown, max(len(transfer["num"]), len(transfer["den"])))
    except (ValueError, TypeError, ArithmeticError, RecursionError) as err:
        return [f"the G^-1 shown cannot be read as a rational function of z ({str(err)[:120]})"]
    tn, td = json_poly(transfer["num"]), json_poly(transfer["den"])
    if num * td != tn * den:
        return ["the G^-1 shown is not the report's G^-1(z) (it differs as a rational function of z)"]
    return []


def rational_of(text: Any, degree: int, variable: str = "z") -> tuple[flint.fmpq_poly, flint.fmpq_poly]:
    """``text`` read (never evaluated) by the toolkit's expression reader as ``num/den`` in
    ``variable`` (``z`` or ``s``) with rational coefficients, its degree bounded by that of the
    transfer function."""
    import sympy as sp

    from hapticproof.core.errors import HapticproofError
    from hapticproof.core.expr import read_expression
    from hapticproof.core.limits import current, raised

    if not isinstance(text, str) or len(text) > 20_000:
        raise ValueError("not a short expression")
    try:
        # the report's own G^-1 bounds the degree and the powers of z its display may hold (a
        # delay of 2000 samples is written z**2000)
        with raised(degree=max(current().degree, degree + 8), exponent=max(current().exponent, degree + 8)):
            expr = read_expression(text, variable)
    except HapticproofError as err:
        raise ValueError(str(err)) from None
    z = sp.Symbol(variable)
    if expr.free_symbols - {z}:
        raise ValueError("it has parameters")
    num, den = sp.fraction(sp.together(expr))

    def poly(e: Any) -> flint.fmpq_poly:
        p = sp.Poly(e, z)
        if p.degree() > degree + 8:
            raise ValueError("its degree is above that of G^-1")
        coeffs = [sp.Rational(c) for c in reversed(p.all_coeffs())]
        return flint.fmpq_poly([flint.fmpq(int(c.p), int(c.q)) for c in coeffs])

    return poly(num), poly(den)


def differing_entry(shown: Any, cells: list, variable: str = "z") -> tuple[int, int] | None:
    """The first entry ``(i, j)`` (1-based) where a matrix shown entry by entry as text differs
    from the transfer matrix ``cells`` (``{"num", "den"}`` per entry) as a rational function of
    ``variable``; ``None`` when they are the same. A shown value that is not a matrix of the same
    size raises :class:`ValueError`.

    >>> differing_entry([["1/(z - 1)"]], [[{"num": ["1"], "den": ["-1", "1"]}]]), differing_entry([["z"]], [[{"num": ["1"], "den": ["1"]}]])
    (None, (1, 1))
    """
    m = len(cells)
    if not (isinstance(shown, list) and len(shown) == m and all(isinstance(r, list) and len(r) == m for r in shown)):
        raise ValueError(f"the matrix shown is not {m} x {m}")
    for i in range(m):
        for j in range(m):
            cell = cells[i][j]
            num, den = rational_of(shown[i][j], max(len(cell["num"]), len(cell["den"])), variable)
            if num * json_poly(cell["den"]) != json_poly(cell["num"]) * den:
                return i + 1, j + 1
    return None


def audit_binding(entry: Mapping[str, Any]) -> list[str]:
    """An audit entry's judge object against its verdict and its displayed witness: a condition
    judged ``holds-passive`` (a confirmed display, judged at sample points) needs its samples
    and shows no counterexample; a judged counterexample (``holds-not-passive``,
    ``fails-passive``, ``differ``) is shown; a claim the judge does not know is refused."""
    evidence = entry.get("evidence") if isinstance(entry.get("evidence"), Mapping) else {}
    facts = evidence.get("facts") if isinstance(evidence.get("facts"), Mapping) else {}
    recheck = facts.get("recheck")
    if entry.get("verdict") in ("confirmed", "conservative") and isinstance(recheck, Mapping) and \
            recheck.get("decision") == "disproved":
        return [(f"the verdict {entry['verdict']!r} is shown with the entry's own exact recheck disproving passivity "
                 "at its witness (a counterexample relabelled)")]
    obj = facts.get("judge")
    if not isinstance(obj, Mapping):
        return []
    kind, claim = obj.get("judge"), obj.get("claim")
    claims = {"condition": ("holds-passive", "holds-not-passive", "fails-passive"), "circle-identity": ("equal", "differ")}
    if kind not in claims:
        return [f"the judge object ({str(kind)[:40]!r}) judges no printed display: it does not back the verdict "
                f"{str(entry.get('verdict'))[:40]!r}"]
    if claim not in claims[kind]:
        return [f"the judge object's claim {str(claim)[:40]!r} is not one the {kind} judge knows"]
    shown = evidence.get("witness")
    counterexample = claim in ("holds-not-passive", "fails-passive", "differ")
    verdict = entry.get("verdict")
    if verdict == "confirmed" and counterexample or verdict in ("wrong", "typo") and not counterexample:
        return [f"the verdict {verdict!r} is not what the judge object's claim {claim!r} says"]
    if counterexample and not shown:
        return [f"the judge holds a counterexample ({claim}) but the entry shows no witness"]
    if not counterexample and shown:
        return [f"a confirmed claim ({claim}) is shown with a counterexample witness"]
    if claim == "holds-passive" and not (isinstance(obj.get("samples"), list) and obj["samples"]):
        return ["a confirmed condition is judged at no sample point"]
    return []


# ---------------------------------------------------------------------------------------------
# displayed points of the circle
# ---------------------------------------------------------------------------------------------


def factored_transfers(node: Any) -> list[str]:
    """Transfer functions in ``z`` that carry a constant ``factor``: no report writes one (only a
    network's entries in ``s`` do), and the poles and residues of the certificates are read
    without it -- a factor would turn a negative residue positive unseen."""
    stack: list[tuple[Any, str]] = [(node, "z")]       # (a part, the variable of the transfer around it)
    while stack:
        item, variable = stack.pop()
        if isinstance(item, Mapping):
            variable = item["variable"] if isinstance(item.get("variable"), str) else variable
            if "factor" in item and "num" in item and variable == "z":
                return ["a transfer function of z carries a 'factor' that no report writes (its residues and poles "
                        "are read without it)"]
            stack.extend((v, variable) for v in item.values())
        elif isinstance(item, list):
            stack.extend((v, variable) for v in item)
    return []


def witness_problems(node: Any, keys: Mapping[str, str] | None = None) -> list[str]:
    """Every displayed witness inside ``node`` that names a point of the circle twice: ``z``
    (``[re, im]``) on the unit circle, ``c = Re z``, ``omega_T`` the angle of ``z`` (or, without
    ``z``, ``cos(omega_T) = c``) -- ``c`` and ``omega_T`` as the report names them (``keys``:
    :func:`~hapticproof.core.naming.witness_keys`, ``gamma`` and ``omega*h``)."""
    keys = witness_keys() if keys is None else keys
    problems: list[str] = []
    for witness in _walk(node, "witness"):
        if not isinstance(witness, Mapping):
            continue
        try:
            problems += _one_point(witness, keys["c"], keys["omega_T"])
        except (ValueError, TypeError, ZeroDivisionError, ArithmeticError) as err:
            problems.append(f"a displayed witness cannot be read ({type(err).__name__}: {str(err)[:80]})")
    return problems


def _one_point(witness: Mapping[str, Any], cos: str, angle_key: str) -> list[str]:
    z = witness.get("z")
    point = [exact_q(v) for v in z] if isinstance(z, list) and len(z) == 2 else None
    if point is not None and (cos not in witness or angle_key not in witness):
        # every point of the circle a report shows names its c and angle: under other keys than
        # the report's notation gives, they would be read by no one
        missing = [key for key in (cos, angle_key) if key not in witness]
        return [f"the witness shows z but not {' and '.join(missing)} (the keys the report's notation gives "
                "its point of the circle)"]
    c = exact_q(witness[cos]) if cos in witness and isinstance(witness[cos], str) and (point or angle_key in witness) \
        else None
    out = []
    if point is not None and (c is not None or angle_key in witness):
        if point[0] ** 2 + point[1] ** 2 != 1:
            out.append(f"the displayed z = {z[0]} + {z[1]}j is not on the unit circle")
        if c is not None and c != point[0]:
            out.append(f"the displayed {cos} = {witness[cos]} is not Re z = {z[0]}")
    if angle_key in witness and (point is not None or c is not None):
        import mpmath

        shown = witness[angle_key]
        with mpmath.workdps(60):
            if isinstance(shown, Mapping) and "exact" not in shown:       # only a decimal: to its digits
                theta, tolerance = angle(str(shown.get("approx"))), mpmath.mpf(10) ** -12
            else:
                theta = angle(shown["exact"] if isinstance(shown, Mapping) else shown)
                tolerance = mpmath.mpf(10) ** -40
            cos_value, sin = mpmath.cos(theta), mpmath.sin(theta)
            re = point[0] if point is not None else c
            bad = abs(cos_value - mpmath.mpf(re.numerator) / re.denominator) > tolerance
            if point is not None:
                bad = bad or abs(sin - mpmath.mpf(point[1].numerator) / point[1].denominator) > tolerance
            if bad:
                where = f"z = {z[0]} + {z[1]}j" if point is not None else f"{cos} = {witness[cos]}"
                out.append(f"the displayed {angle_key} = {str(shown)[:40]} is not the angle of {where} "
                           f"(cos {_short(cos_value)}, sin {_short(sin)})")
    return out


def _short(value: Any) -> str:
    text = f"{float(value):.6f}".rstrip("0").rstrip(".")
    return "0" if text in ("-0", "") else text


_ANGLE_TOKEN = re.compile(r"\s*(?:(\d+(?:\.\d*)?(?:[eE][+-]?\d+)?)|(pi|atan|acos|asin|sqrt|cos|sin)|(\*\*|[-+*/()]))")


def angle(text: Any) -> Any:
    """An angle as a report writes it (``pi``, ``pi/2``, ``2*atan(1/12)``): numbers, ``pi``,
    ``+ - * / **``, parentheses and ``atan``, ``acos``, ``asin``, ``sqrt``, ``cos``, ``sin`` --
    read by a small parser of its own and evaluated with mpmath (never by ``eval``).

    >>> import mpmath
    >>> float(angle("2*atan(1/2)")) == float(2 * mpmath.atan(mpmath.mpf(1) / 2))
    True
    """
    import mpmath

    from hapticproof.core.limits import check_number_text

    if isinstance(text, (int, float)) and not isinstance(text, bool):
        return mpmath.mpf(text)
    if not isinstance(text, str) or len(text) > 200:
        raise ValueError("an angle is a short text")
    tokens, k = [], 0
    while k < len(text.rstrip()):
        m = _ANGLE_TOKEN.match(text, k)
        if m is None or m.end() == k:
            raise ValueError(f"unexpected {text[k:k + 10]!r} in the angle")
        if m.group(1):
            check_number_text(m.group(1), "omega_T")
        tokens.append(m.group(1) or m.group(2) or m.group(3))
        k = m.end()
    position = [0]

    def peek() -> str | None:
        return tokens[position[0]] if position[0] < len(tokens) else None

    def take(expected: str | None = None) -> str:
        token = peek()
        if token is None or (expected is not None and token != expected):
            raise ValueError("the angle is not an expression")
        position[0] += 1
        return token

    functions = {"atan": mpmath.atan, "acos": mpmath.acos, "asin": mpmath.asin, "sqrt": mpmath.sqrt,
                 "cos": mpmath.cos, "sin": mpmath.sin}

    def atom() -> Any:
        token = take()
        if token == "(":
            value = expression()
            take(")")
            return value
        if token == "pi":
            return +mpmath.pi
        if token in functions:
            take("(")
            value = expression()
            take(")")
            return functions[token](value)
        if token in ("-", "+"):
            value = factor()
            return -value if token == "-" else value
        if token[0].isdigit():
            return mpmath.mpf(token)
        raise ValueError("the angle is not an expression")

    def factor() -> Any:
        base = atom()
        if peek() == "**":
            take()
            exponent = factor()
            if abs(exponent) > 64:
                raise ValueError("an exponent above 64 in an angle")
            return base ** exponent
        return base

    def term() -> Any:
        value = factor()
        while peek() in ("*", "/"):
            op = take()
            other = factor()
            value = value * other if op == "*" else value / other
        return value

    def expression() -> Any:
        value = term()
        while peek() in ("+", "-"):
            op = take()
            other = term()
            value = value + other if op == "+" else value - other
        return value

    value = expression()
    if peek() is not None:
        raise ValueError("the angle is not an expression")
    return value


# ---------------------------------------------------------------------------------------------
# a decision against its own evidence, at every depth
# ---------------------------------------------------------------------------------------------


def _owncertificates(node: Any) -> Iterator[Mapping[str, Any]]:
    """The certificates a decision carries itself (not those of the decisions nested in it)."""
    if isinstance(node, Mapping):
        if is_kind(node.get("certificate")):
            yield node
        for key, value in node.items():
            if not (isinstance(value, Mapping) and "decision" in value) and key != "conditions":
                yield from _owncertificates(value)
    elif isinstance(node, list):
        for value in node:
            if not (isinstance(value, Mapping) and "decision" in value):
                yield from _owncertificates(value)


def _nested_decisions(node: Mapping[str, Any]) -> list[str]:
    """The decisions of the conditions a decision is the conjunction of (``conditions`` beside it
    or among its facts)."""
    facts = node.get("evidence", {}).get("facts") if isinstance(node.get("evidence"), Mapping) else None
    for conditions in (node.get("conditions"), facts.get("conditions") if isinstance(facts, Mapping) else None):
        if isinstance(conditions, list) and conditions and all(isinstance(c, Mapping) and "decision" in c for c in conditions):
            return [c["decision"] for c in conditions]
    return []


def decision_problems(node: Any, where: str = "report") -> list[str]:
    """Every ``decision`` in a report held against its own evidence, at any depth: a ``proved``
    decision whose own certificate does not hold, a ``disproved`` one whose certificates all hold,
    a conjunction ``proved`` with a condition not proved (or ``disproved`` with none disproved),
    and a ``scaled_residue`` shown beside a residue certificate that says another value.

    >>> cert = {"certificate": "sign", "holds": False}
    >>> decision_problems({"decision": "proved", "evidence": {"facts": {"certificate": cert}}})
    ["report: the decision 'proved' is shown, but its own sign certificate does not hold"]
    """
    out: list[str] = []
    if isinstance(node, list):
        for value in node:
            out += decision_problems(value, where)
        return out
    if not isinstance(node, Mapping):
        return out
    name = str(node.get("name", where))[:60]
    decision = node.get("decision")
    if decision in ("proved", "disproved"):
        certs = list(_owncertificates({k: v for k, v in node.items() if k != "decision"}))
        holding = [c["holds"] for c in certs if isinstance(c.get("holds"), bool)]
        if decision == "proved" and False in holding:
            kind = next(c["certificate"] for c in certs if c.get("holds") is False)
            out.append(f"{name}: the decision 'proved' is shown, but its own {kind} certificate does not hold")
        if decision == "disproved" and holding and all(holding) and len(holding) == len(certs):   # (roots: no 'holds')
            out.append(f"{name}: the decision 'disproved' is shown, but every certificate of its own holds")
        nested = _nested_decisions(node)
        if decision == "proved" and any(d != "proved" for d in nested):
            out.append(f"{name}: the decision 'proved' is shown, but not every condition of it is proved")
        if decision == "disproved" and nested and "disproved" not in nested:
            out.append(f"{name}: the decision 'disproved' is shown, but none of its conditions is disproved")
    facts = node.get("facts")
    if isinstance(facts, Mapping) and "scaled_residue" in facts and isinstance(facts.get("certificate"), Mapping) and \
            "scaled" in facts["certificate"]:
        try:
            if exact_q(facts["scaled_residue"]) != exact_q(facts["certificate"]["scaled"]):
                out.append(f"{name}: the residue shown ({str(facts['scaled_residue'])[:30]}) is not its certificate's")
        except (TypeError, ValueError, ZeroDivisionError):
            out.append(f"{name}: the residue shown cannot be read")
    for key, value in node.items():
        if isinstance(value, (Mapping, list)) and key != "definition":
            out += decision_problems(value, name if "name" in node else where)
    return out


def teleoperator_bounds(report: Mapping[str, Any]) -> list[str]:
    """A teleoperator's ``sup_master``/``sup_slave`` and ``maximiser``: the damping ``b`` of its
    (D) certificate minus the minimum over ``c`` of the (32) certificate's ``c``-form ``b - bound(c)``
    (exact, :func:`_minimum_of_form`), taken at the maximiser shown."""
    conditions = report.get("conditions")
    paper = report.get("criterion_32")
    if not isinstance(conditions, list) or not isinstance(paper, Mapping) or not isinstance(paper.get("conditions"), list):
        return []
    damping = next((c for c in conditions if isinstance(c, Mapping) and str(c.get("name", "")).startswith("(D)")), None)
    facts = ((damping or {}).get("evidence") or {}).get("facts") if isinstance(damping, Mapping) else None
    if not isinstance(facts, Mapping):
        return []
    out = []
    for side, key, cert_key in (("master", "sup_master", "certificate"), ("slave", "sup_slave", "slave")):
        shown, cert = report.get(key), facts.get(cert_key)
        cond = next((c for c in paper["conditions"] if isinstance(c, Mapping)
                     and str(c.get("name", "")).startswith(f"(32) {side}")), None)
        form_cert = next((c for c in certificates(cond) if "numerator" in c and "denominator" in c), None) if cond else None
        if shown is None or not isinstance(cert, Mapping) or form_cert is None:
            continue
        b = json_poly(cert["polynomial"])
        if b.degree() > 0:
            continue                                   # a damping that varies: no one number to hold against
        try:
            sup = exact_q(str(shown))
        except (TypeError, ValueError, ZeroDivisionError):
            out.append(f"the {key} shown ({str(shown)[:30]}) cannot be read")
            continue
        value = b.coeffs()[0] if b.degree() == 0 else flint.fmpq(0)
        low = Fraction(int(value.p), int(value.q)) - sup
        form = (json_poly(form_cert["numerator"]), json_poly(form_cert["denominator"]))
        out += [problem.replace("the minimum shown", f"the {key} shown").replace("Re G^-1", f"b_{side[0]} - bound(c)")
                for problem in _minimum_of_form(form, low, report.get("maximiser"), shown)]
    return out
