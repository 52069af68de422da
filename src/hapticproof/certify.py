r"""Certify printed results against derived ones: identities, bounds and exact witnesses.

Two comparisons cover most printed equations:

* :func:`compare_expressions` — printed expression vs derived expression: ``confirmed`` when
  their difference cancels to zero (canonical form), otherwise an exact rational point where
  they differ.
* :func:`compare_bounds` — printed condition vs exact condition, both solved for one design
  variable (``b > bound``): equal bounds are ``confirmed``; a larger printed bound is
  ``conservative`` (proved from the parameters' sign assumptions) and a smaller one is not
  sufficient, shown by exact parameters where the printed condition holds and the exact one
  fails. Witnesses can be re-checked by an independent exact decision (``verify``).

Conditions are compared up to their boundary: the papers write ``>`` where positive-realness
gives ``>=``; a strictness difference alone is reported in the detail, not as a defect.

>>> import sympy as sp
>>> K, T, b = sp.symbols('K T b', positive=True)
>>> B = sp.Symbol('B', nonnegative=True)
>>> f = compare_bounds(sp.Gt(b, K*T/2 + B), sp.Ge(b, K*T/2 + B), b)
>>> f.verdict.value, f.evidence.method
('confirmed', 'canonical-form')
>>> g = compare_bounds(sp.Gt(b + B, K*T/2), sp.Ge(b, K*T/2 + B), b)
>>> g.verdict.value, sorted(g.evidence.witness)
('wrong', ['B', 'K', 'T', 'b'])
"""

from __future__ import annotations

import itertools
import random
from collections.abc import Callable, Iterable, Iterator, Mapping
from dataclasses import dataclass
from typing import Any

import sympy as sp
from sympy.core.evalf import PrecisionExhausted
from sympy.polys.fields import sfield

from hapticproof.evidence import Decision, Evidence, Finding, Method, Outcome, Verdict
from hapticproof.symbols import c as C_SYM

__all__ = [
    "Sampler",
    "Bound",
    "is_identically_zero",
    "canonical_rational",
    "canonical_fraction",
    "find_difference",
    "compare_expressions",
    "as_bound",
    "compare_bounds",
    "sign_on_box",
]

_NICE = [sp.Integer(1), sp.Integer(2), sp.Rational(1, 2), sp.Integer(3), sp.Rational(1, 3), sp.Integer(5),
         sp.Rational(2, 3), sp.Integer(10), sp.Rational(1, 10), sp.Rational(7, 4), sp.Rational(3, 7)]


class Sampler:
    """Exact rational values for symbols, respecting their SymPy assumptions.

    ``positive`` symbols get values in (0, oo), ``nonnegative`` in [0, oo), ``integer`` ones
    integers, and the symbol ``c`` (``cos wT``) values in [-1, 1]. Explicit ``ranges`` override.
    Deterministic for a given seed: a few "nice" values first, then random rationals.

    >>> K = sp.Symbol('K', positive=True)
    >>> n = sp.Symbol('n', integer=True, nonnegative=True)
    >>> values = Sampler([K, n, C_SYM], seed=1).draw(3)
    >>> all(v[K] > 0 and v[n].is_integer and -1 <= v[C_SYM] <= 1 for v in values)
    True
    """

    def __init__(
        self,
        symbols: Iterable[sp.Symbol],
        seed: int = 0,
        ranges: Mapping[sp.Symbol, tuple[Any, Any]] | None = None,
    ):
        self.symbols = sorted(set(symbols), key=str)
        self.ranges = dict(ranges or {})
        self._rng = random.Random(seed)

    def _value(self, symbol: sp.Symbol, position: int, index: int) -> sp.Rational:
        rng = self._rng
        if symbol in self.ranges:
            lo, hi = (sp.Rational(v) for v in self.ranges[symbol])
            if symbol.is_integer:
                return sp.Integer(rng.randint(int(lo), int(hi)))
            if index == 0:
                return (lo + hi) / 2
            return lo + (hi - lo) * sp.Rational(rng.randint(0, 1000), 1000)
        if symbol == C_SYM:
            if index < len(_NICE):
                return [sp.Rational(1, 2), sp.Integer(-1), sp.Integer(1), sp.Integer(0)][index % 4]
            return sp.Rational(rng.randint(-60, 60), 60)
        if symbol.is_integer:
            low = 0 if symbol.is_nonnegative else (1 if symbol.is_positive else -6)
            return sp.Integer(1 + index % 3 if index < len(_NICE) else rng.randint(low, 12))
        if index == 0:
            value = sp.Integer(1)
        elif index < 4 * len(_NICE):
            value = _NICE[(index + 3 * position) % len(_NICE)]
        else:
            value = sp.Rational(rng.randint(1, 400), rng.randint(1, 60))
        if symbol.is_positive:
            return value
        if symbol.is_nonnegative:
            return sp.Integer(0) if index % 7 == 3 else value
        return value if (index + position) % 2 == 0 else -value

    def __iter__(self) -> Iterator[dict[sp.Symbol, sp.Rational]]:
        for index in itertools.count():
            yield {s: self._value(s, k, index) for k, s in enumerate(self.symbols)}

    def draw(self, count: int) -> list[dict[sp.Symbol, sp.Rational]]:
        return list(itertools.islice(iter(self), count))


def is_identically_zero(expr: sp.Expr) -> bool:
    """Exact zero test of a rational (or trigonometric-polynomial) expression.

    Canonical forms are tried from cheapest to dearest: rational functions over Q (``cancel``),
    over Q with algebraic numbers such as sqrt(2) (``cancel`` with ``extension``), polynomials
    in ``sin``/``cos`` of one angle (reduced modulo ``sin^2 + cos^2 - 1``), and only then
    ``simplify``, which a numeric probe at a rational point spares non-zero expressions (the
    probe comes last: on the audit's mostly-zero differences it costs more than it saves).

    >>> x = sp.Symbol('x')
    >>> is_identically_zero((x**2 - 1)/(x - 1) - x - 1), is_identically_zero(sp.sin(x)**2 + sp.cos(x)**2 - 1)
    (True, True)
    >>> is_identically_zero(sp.sqrt(2)*x/(sp.sqrt(2) + 1) - x*(2 - sp.sqrt(2)))
    True
    """
    expr = sp.sympify(expr)
    if expr == 0:
        return True
    if expr.is_rational_function():
        return canonical_rational(expr) == 0  # a canonical form for rational functions over Q
    if sp.cancel(sp.together(expr)) == 0:
        return True
    if not expr.has(sp.Function, sp.exp):
        return sp.cancel(sp.together(expr), extension=True) == 0
    reduced = _single_angle_form(expr)
    if reduced is not None:
        return reduced == 0
    if _probe_nonzero(expr):
        return False
    if expr.has(sp.sin, sp.cos, sp.exp):
        return sp.simplify(sp.expand_trig(expr)) == 0
    return sp.simplify(expr) == 0


def canonical_rational(expr: sp.Expr) -> sp.Expr:
    """Canonical (cancelled) form of a rational function over Q, as an expression.

    An element of the rational function field over its own symbols: cheaper than ``cancel``,
    whose term-factoring preprocessing dominates on large sums.

    >>> x, y = sp.symbols('x y')
    >>> canonical_rational((x**2 - y**2)/(x - y) - y)
    x
    >>> canonical_rational(sp.Float(0.75)), canonical_rational(sp.Float(0.686844161539459)).is_Rational
    (3/4, True)
    """
    expr = sp.sympify(expr)
    if not expr.free_symbols:
        # a float is read exactly, by its binary value (nsimplify could return radicals)
        return sp.Rational(expr) if expr.is_Float else sp.cancel(expr)
    _, element = sfield(expr)
    return element.as_expr()


def canonical_fraction(expr: sp.Expr) -> tuple[sp.Expr, sp.Expr]:
    """Cancelled numerator and denominator of a rational function over Q (see
    :func:`canonical_rational`); falls back to ``cancel`` for other expressions.

    >>> x = sp.Symbol('x')
    >>> canonical_fraction(1/(x - 1) + 1)
    (x, x - 1)
    """
    expr = sp.sympify(expr)
    if expr.free_symbols and expr.is_rational_function():
        _, element = sfield(expr)
        return element.numer.as_expr(), element.denom.as_expr()
    return sp.fraction(sp.cancel(sp.together(expr)))


def _probe_nonzero(expr: sp.Expr) -> bool:
    """True when the expression is certainly non-zero at a rational point: evaluated with
    ``strict=True``, so every digit is correct or evalf raises (an exact zero always raises, as
    zero has no relative accuracy) and the probe then proves nothing."""
    symbols = sorted(expr.free_symbols, key=str)
    point = {s: sp.Rational(7 + 3 * k, 11 + 2 * k) for k, s in enumerate(symbols)}
    try:
        value = sp.N(expr.xreplace(point), 30, strict=True)
    except (TypeError, ValueError, ZeroDivisionError, PrecisionExhausted):
        return False
    if not value.is_number or value.has(sp.zoo, sp.nan, sp.oo, -sp.oo):
        return False
    return abs(value) > sp.Float("1e-20")


def _single_angle_form(expr: sp.Expr) -> sp.Expr | None:
    """Rewrite a polynomial in sin/cos of integer multiples of one angle in the canonical ring
    Q(params, c)[s]/(s^2 + c^2 - 1); ``None`` when the expression has other functions."""
    trig = [f for f in expr.atoms(sp.Function) if isinstance(f, (sp.sin, sp.cos))]
    if not trig or expr.atoms(sp.Function) - set(trig) or expr.has(sp.exp):
        return None
    args = {f.args[0] for f in trig}
    base = None
    for a in args:
        coeff, rest = a.as_coeff_Mul()
        if not coeff.is_Integer:
            return None
        if base is None:
            base = rest
        elif rest != base:
            return None
    cs, sn = sp.Dummy("c"), sp.Dummy("s")
    expanded = sp.expand_trig(expr).subs({sp.cos(base): cs, sp.sin(base): sn})
    if expanded.has(sp.sin, sp.cos):
        return None
    num, den = sp.fraction(sp.together(expanded))

    def reduce(p: sp.Expr) -> sp.Expr:
        poly = sp.Poly(sp.expand(p), sn)
        out = sp.Integer(0)
        for (power,), coeff in poly.terms():
            out += coeff * (1 - cs**2) ** (power // 2) * sn ** (power % 2)
        return sp.expand(out)

    reduced_den = reduce(den)
    if reduced_den == 0:
        return None
    return sp.cancel(reduce(num) / reduced_den)


def _evaluate(expr: sp.Expr, values: Mapping[sp.Symbol, Any]) -> sp.Expr | None:
    """Exact value at a point (rational when the expression is rational; exact transcendental
    numbers such as ``cos(1)`` otherwise, which compare correctly through evalf)."""
    try:
        value = sp.sympify(expr).xreplace(dict(values))
        if value.has(sp.zoo, sp.nan, sp.oo, -sp.oo):
            return None
        if not value.is_Rational and not value.free_symbols:
            value = sp.cancel(value)
        return None if value.has(sp.zoo, sp.nan) else value
    except (ZeroDivisionError, TypeError):
        return None


def _nonzero(value: sp.Expr) -> bool:
    """Certified ``value != 0`` for an exact number (evalf with increasing precision)."""
    if value.is_Rational:
        return value != 0
    for digits in (30, 100):
        approx = sp.N(value, digits)
        if approx.is_number and abs(approx) > sp.Float(10) ** (-digits // 2):
            return True
    return sp.simplify(value) != 0


def find_difference(
    a: sp.Expr, b: sp.Expr, symbols: Iterable[sp.Symbol] | None = None, tries: int = 200, seed: int = 0
) -> dict[str, Any] | None:
    """Exact rational point where ``a`` and ``b`` differ (both finite), or ``None``.

    >>> x = sp.Symbol('x', positive=True)
    >>> find_difference(x**2, x + 2)['values']
    (1, 3)
    """
    a, b = sp.sympify(a), sp.sympify(b)
    symbols = list(symbols) if symbols is not None else sorted(a.free_symbols | b.free_symbols, key=str)
    for point in Sampler(symbols, seed).draw(tries):
        va, vb = _evaluate(a, point), _evaluate(b, point)
        if va is None or vb is None or va.free_symbols or vb.free_symbols:
            continue
        if _nonzero(va - vb):
            return {"point": point, "values": (va, vb)}
    return None


def compare_expressions(
    printed: sp.Expr,
    derived: sp.Expr,
    *,
    symbols: Iterable[sp.Symbol] | None = None,
    on_mismatch: Verdict = Verdict.TYPO,
    what: str = "the printed expression",
    corrected: str | None = None,
    note: str = "",
) -> Finding:
    """``confirmed`` if ``printed - derived`` cancels to zero; otherwise ``on_mismatch`` with an
    exact point where they differ.

    >>> x = sp.Symbol('x')
    >>> compare_expressions(x**2 - 1, (x - 1)*(x + 1)).verdict.value
    'confirmed'
    >>> f = compare_expressions(2*x, x, corrected='x')
    >>> f.verdict.value, f.evidence.witness
    ('typo', {'x': 1})
    """
    suffix = f" ({note})" if note else ""
    if is_identically_zero(sp.sympify(printed) - sp.sympify(derived)):
        return Finding(
            Verdict.CONFIRMED,
            f"{what} equals the derived one identically (difference cancels to 0){suffix}",
            Evidence(Method.CANONICAL_FORM),
            derived=derived,
        )
    diff = find_difference(printed, derived, symbols)
    if diff is None:
        return Finding(
            Verdict.UNDECIDED,
            f"{what} and the derived one do not cancel symbolically, and no differing rational point was found{suffix}",
            Evidence(Method.CANONICAL_FORM, instances=200),
            derived=derived,
            corrected=corrected,
        )
    printed_value, derived_value = diff["values"]
    return Finding(
        on_mismatch,
        f"{what} differs from the derived one: {sp.sstr(printed_value)} vs {sp.sstr(derived_value)} at the witness{suffix}",
        Evidence(
            Method.COUNTEREXAMPLE,
            witness={str(k): v for k, v in diff["point"].items()},
            facts={"printed_value": printed_value, "derived_value": derived_value},
        ),
        derived=derived,
        corrected=corrected,
    )


@dataclass(frozen=True, slots=True)
class Bound:
    """A condition solved for one variable: ``var > bound`` (``strict``) or ``var >= bound``."""

    var: sp.Symbol
    bound: sp.Expr
    strict: bool


def as_bound(condition: sp.Basic, var: sp.Symbol) -> Bound:
    """Solve a condition that is affine in ``var`` with a positive coefficient for ``var``.

    >>> K, T, b, za = sp.symbols('K T b z_a', positive=True)
    >>> as_bound(sp.Gt(b - za, K*T/2), b)
    Bound(var=b, bound=K*T/2 + z_a, strict=True)
    """
    if not isinstance(condition, sp.core.relational.Relational):
        raise TypeError(f"not an inequality: {condition}")
    if isinstance(condition, (sp.StrictLessThan, sp.LessThan)):
        condition = condition.reversed
    if not isinstance(condition, (sp.StrictGreaterThan, sp.GreaterThan)):
        raise TypeError(f"not an inequality: {condition}")
    expr = sp.expand(condition.lhs - condition.rhs)
    poly = sp.Poly(expr, var)
    if poly.degree() != 1:
        raise ValueError(f"condition is not affine in {var}: {condition}")
    coeff = poly.coeff_monomial(var)
    rest = sp.expand(expr - coeff * var)
    if not coeff.is_positive:
        raise ValueError(f"coefficient of {var} is not provably positive: {coeff}")
    bound = -rest / coeff
    return Bound(var, canonical_rational(bound) if bound.is_rational_function() else sp.cancel(bound),
                 isinstance(condition, sp.StrictGreaterThan))


def sign_on_box(expr: sp.Expr, box: Mapping[sp.Symbol, tuple[Any, Any]] | None = None) -> int | None:
    """Provable sign of ``expr`` under the symbols' assumptions (+1: >= 0, -1: <= 0), or None.

    Symbols in ``box`` range over closed intervals; ``expr`` must be affine in each of them
    (checked at the box's corners, which is exact for multi-affine expressions). ``c`` is
    always boxed to ``[-1, 1]``.
    """
    expr = sp.expand(expr)
    box = dict(box or {})
    if C_SYM in expr.free_symbols:
        box.setdefault(C_SYM, (-1, 1))
    boxed = [s for s in box if s in expr.free_symbols]
    for s in boxed:
        if sp.Poly(expr, s).degree() > 1:
            return None
    corners = [expr.subs(dict(zip(boxed, corner))) for corner in itertools.product(*(box[s] for s in boxed))]
    if all(sp.factor(v).is_nonnegative for v in corners):
        return 1
    if all(sp.factor(v).is_nonpositive for v in corners):
        return -1
    return None


def compare_bounds(
    printed: sp.Basic,
    exact: sp.Basic,
    var: sp.Symbol,
    *,
    on_weaker: Verdict = Verdict.WRONG,
    box: Mapping[sp.Symbol, tuple[Any, Any]] | None = None,
    verify: Callable[[dict[sp.Symbol, sp.Expr]], Outcome] | None = None,
    corrected: str | None = None,
    what: str = "the printed condition",
    note: str = "",
    tries: int = 400,
) -> Finding:
    """Compare a printed condition with the exact one, both solved for ``var``.

    ``exact`` must be necessary and sufficient (e.g. the derived worst-case condition). The
    verdict is ``confirmed`` (same bound), ``conservative`` (printed bound provably >= exact:
    sufficient, not necessary) or ``on_weaker`` (the printed bound is below the exact one
    somewhere: the printed condition holds where the exact one fails; the witness is exact
    parameters with ``var`` between the two bounds). ``verify``, if given, re-checks a witness
    by an independent exact decision (e.g. root isolation of the numeric scene) and must
    return a ``disproved`` outcome for a not-sufficient witness.
    """
    p, e = as_bound(printed, var), as_bound(exact, var)
    raw = p.bound - e.bound
    difference = canonical_rational(raw) if raw.is_rational_function() else sp.cancel(sp.together(raw))
    suffix = f" ({note})" if note else ""
    strictness = "" if p.strict == e.strict else f"; compared up to the boundary ({'>' if p.strict else '>='} vs {'>' if e.strict else '>='})"
    symbols = sorted((p.bound.free_symbols | e.bound.free_symbols) - {var}, key=str)
    if is_identically_zero(difference):
        return Finding(
            Verdict.CONFIRMED,
            f"{what} is equivalent to the exact condition {var} {'>=' if not e.strict else '>'} {sp.sstr(e.bound)}{strictness}{suffix}",
            Evidence(Method.CANONICAL_FORM, facts={"printed_bound": p.bound, "exact_bound": e.bound}),
            derived=exact,
        )
    sign = sign_on_box(difference, box)
    ranges = dict(box or {})
    weaker = None
    stronger = None
    for point in Sampler(symbols, seed=7, ranges=ranges).draw(tries):
        d = _evaluate(difference, point)
        if d is None or not d.is_real:
            continue
        if d < 0 and weaker is None:
            weaker = point
        if d > 0 and stronger is None:
            stronger = point
        if weaker is not None and (stronger is not None or sign is not None):
            break
    if weaker is not None:
        point = dict(weaker)
        point[var] = sp.nsimplify((p.bound.xreplace(weaker) + e.bound.xreplace(weaker)) / 2)
        facts: dict[str, Any] = {
            "printed_bound": p.bound.xreplace(weaker),
            "exact_bound": e.bound.xreplace(weaker),
            "printed_holds": True,
            "exact_holds": False,
        }
        method = Method.COUNTEREXAMPLE
        if verify is not None:
            check = verify(point)
            if check.decision != Decision.DISPROVED:
                raise AssertionError(f"witness {point} not confirmed by the exact decision: {check.reason}")
            facts["recheck"] = check.to_json()
        region = " for all parameters" if sign == -1 else " in part of the parameter space"
        return Finding(
            on_weaker,
            f"{what} is weaker than the exact condition{region}: it holds at the witness where the exact condition fails{suffix}",
            Evidence(method, witness={str(k): v for k, v in point.items()}, facts=facts),
            derived=exact,
            corrected=corrected,
        )
    if sign == 1:
        witness = None
        facts = {"printed_bound": p.bound, "exact_bound": e.bound, "difference": difference}
        if stronger is not None:
            witness = dict(stronger)
            witness[var] = sp.nsimplify((p.bound.xreplace(stronger) + e.bound.xreplace(stronger)) / 2)
            witness = {str(k): v for k, v in witness.items()}
        return Finding(
            Verdict.CONSERVATIVE,
            f"{what} implies the exact condition (its bound exceeds the exact one by {sp.sstr(difference)} >= 0) but not conversely{strictness}{suffix}",
            Evidence(Method.ENDPOINT_ANALYSIS, witness=witness, facts=facts),
            derived=exact,
        )
    return Finding(
        Verdict.UNDECIDED,
        f"{what}: the sign of the bound difference {sp.sstr(difference)} was not settled and no witness was found in {tries} exact samples{suffix}",
        Evidence(Method.INSTANCES, instances=tries, facts={"difference": difference}),
        derived=exact,
        corrected=corrected,
    )
