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

from hapticproof.errors import HapticproofError
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
    "NotABound",
    "SignCondition",
    "as_sign_condition",
    "compare_sign_conditions",
    "as_bound",
    "as_lower_bound",
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
    printed, derived = sp.sympify(printed), sp.sympify(derived)
    if is_identically_zero(printed - derived):
        return Finding(
            Verdict.CONFIRMED,
            f"{what} equals the derived one identically (difference cancels to 0){suffix}",
            Evidence(Method.CANONICAL_FORM, facts={"printed_form": ("equals the derived", _canonical_text(derived))}),
            derived=derived,
        )
    form = ("reads", _canonical_text(printed))
    diff = find_difference(printed, derived, symbols)
    if diff is None:
        return Finding(
            Verdict.UNDECIDED,
            f"{what} and the derived one do not cancel symbolically, and no differing rational point was found{suffix}",
            Evidence(Method.CANONICAL_FORM, instances=200, facts={"printed_form": form}),
            derived=derived,
            corrected=corrected,
        )
    printed_value, derived_value = diff["values"]
    gap = _short(printed - derived)
    return Finding(
        on_mismatch,
        f"{what} differs from the derived one: {sp.sstr(printed_value)} vs {sp.sstr(derived_value)} at the witness"
        f"{f' (printed - derived = {gap})' if gap else ''}{suffix}",
        Evidence(
            Method.COUNTEREXAMPLE,
            witness={str(k): v for k, v in diff["point"].items()},
            facts={"printed_value": printed_value, "derived_value": derived_value, "printed_form": form},
        ),
        derived=derived,
        corrected=corrected,
    )


def _canonical_text(expr: Any) -> str:
    """A canonical spelling of an expression (for comparing what two displays say)."""
    expr = sp.sympify(expr)
    try:
        if isinstance(expr, sp.Expr) and expr.free_symbols and expr.is_rational_function():
            return sp.srepr(canonical_rational(expr))
    except (sp.PolynomialError, TypeError, ValueError):
        pass
    if isinstance(expr, sp.MatrixBase):
        return sp.srepr(expr.applyfunc(lambda e: sp.cancel(e)))
    return sp.srepr(sp.expand(expr) if isinstance(expr, sp.Expr) else expr)


def _short(expr: Any, limit: int = 120) -> str | None:
    """``sstr`` of a simplified expression when it is short enough for a one-sentence detail."""
    try:
        value = sp.factor(sp.cancel(sp.together(expr))) if isinstance(expr, sp.Expr) else expr
    except (sp.PolynomialError, TypeError, ValueError):
        value = expr
    text = sp.sstr(value)
    return text if len(text) <= limit else None


@dataclass(frozen=True, slots=True)
class SignCondition:
    """A printed or derived inequality normalised to ``expr op 0`` with ``op`` in
    ``>``, ``>=``, ``=``, ``!=`` (``a < b`` becomes ``b - a > 0``)."""

    expr: sp.Expr
    op: str

    def holds(self, point: Mapping[sp.Symbol, Any]) -> bool | None:
        value = _evaluate(self.expr, point)
        if value is None or value.free_symbols or not value.is_real:
            return None
        return {">": value > 0, ">=": value >= 0, "=": value == 0, "!=": value != 0}[self.op]

    def __str__(self) -> str:
        return f"{sp.sstr(self.expr)} {self.op} 0"


def as_sign_condition(relation: sp.Basic) -> SignCondition:
    """Normalise a relation to ``expr op 0``.

    >>> a, b = sp.symbols('a b')
    >>> str(as_sign_condition(sp.Lt(a, b))), str(as_sign_condition(sp.Ge(a, 2*b)))
    ('-a + b > 0', 'a - 2*b >= 0')
    """
    if relation in (sp.true, sp.false):
        return SignCondition(sp.Integer(1 if relation is sp.true else -1), ">")
    if not isinstance(relation, sp.core.relational.Relational):
        raise NotABound(f"not a relation: {sp.sstr(relation)}")
    lhs, rhs = relation.lhs, relation.rhs
    if isinstance(relation, sp.StrictGreaterThan):
        return SignCondition(lhs - rhs, ">")
    if isinstance(relation, sp.GreaterThan):
        return SignCondition(lhs - rhs, ">=")
    if isinstance(relation, sp.StrictLessThan):
        return SignCondition(rhs - lhs, ">")
    if isinstance(relation, sp.LessThan):
        return SignCondition(rhs - lhs, ">=")
    if isinstance(relation, sp.Ne):
        return SignCondition(lhs - rhs, "!=")
    return SignCondition(lhs - rhs, "=")


def compare_sign_conditions(
    printed: sp.Basic,
    derived: sp.Basic,
    *,
    on_mismatch: Verdict = Verdict.WRONG,
    what: str = "the printed condition",
    corrected: str | None = None,
    note: str = "",
    tries: int = 300,
    ranges: Mapping[sp.Symbol, tuple[Any, Any]] | None = None,
) -> Finding:
    """Compare two conditions ``P op 0`` and ``D op' 0`` as conditions on all their symbols.

    ``confirmed`` when ``P = r D`` with ``r`` provably positive and the same relation (up to
    strictness: ``>`` vs ``>=`` is reported, not a defect), or ``r`` provably negative and the
    opposite relation; otherwise ``on_mismatch`` with an exact point where one holds and the
    other fails (found by exact sampling), or ``undecided``. A reversed relation (``P < 0`` for
    ``D > 0``) is never confirmed. ``evidence.facts["printed_form"]`` is the derived condition for
    a confirmed finding (proved equivalent) and the printed one otherwise.

    >>> K, T = sp.symbols('K T', positive=True)
    >>> compare_sign_conditions(sp.Gt(2*K*T, 0, evaluate=False), sp.Gt(K*T, 0, evaluate=False)).verdict.value
    'confirmed'
    >>> f = compare_sign_conditions(sp.Lt(K*T, 0, evaluate=False), sp.Gt(K*T, 0, evaluate=False))
    >>> f.verdict.value, sorted(f.evidence.witness)
    ('wrong', ['K', 'T'])
    """
    p, d = as_sign_condition(printed), as_sign_condition(derived)
    suffix = f" ({note})" if note else ""
    derived_form = ("equivalent to", d.op, _canonical_text(d.expr))
    facts: dict[str, Any] = {"printed": str(p), "derived": str(d)}
    if p.op in ("=", "!=") or d.op in ("=", "!="):
        same_kind = (p.op in ("=",)) == (d.op in ("=",))
        ratio = sp.cancel(sp.together(p.expr / d.expr)) if d.expr != 0 else None
        if same_kind and ratio is not None and ratio != 0 and not ratio.free_symbols:
            return Finding(Verdict.CONFIRMED, f"{what} is the derived condition {d} up to the factor {sp.sstr(ratio)}{suffix}",
                           Evidence(Method.CANONICAL_FORM, facts={**facts, "printed_form": derived_form}), derived=derived)
    else:
        ratio = sp.cancel(sp.together(p.expr / d.expr)) if d.expr != 0 else None
        sign = _provable_sign(ratio) if ratio is not None and ratio != 0 else None
        if sign is not None:
            if sign > 0:
                strictness = "" if p.op == d.op else f"; compared up to the boundary ({p.op} vs {d.op})"
                return Finding(
                    Verdict.CONFIRMED,
                    f"{what} is the derived condition {d} multiplied by {sp.sstr(ratio)} > 0{strictness}{suffix}",
                    Evidence(Method.CANONICAL_FORM, facts={**facts, "ratio": ratio, "printed_form": derived_form}),
                    derived=derived)
            facts["ratio"] = ratio
    symbols = sorted(p.expr.free_symbols | d.expr.free_symbols, key=str)
    printed_holds_only = derived_holds_only = None
    for point in Sampler(symbols, seed=5, ranges=dict(ranges or {})).draw(tries):
        hp, hd = p.holds(point), d.holds(point)
        if hp is None or hd is None:
            continue
        if hp and not hd and printed_holds_only is None:
            printed_holds_only = point
        if hd and not hp and derived_holds_only is None:
            derived_holds_only = point
        if printed_holds_only is not None and derived_holds_only is not None:
            break
    facts["printed_form"] = ("reads", p.op, _canonical_text(p.expr))
    witness = printed_holds_only if printed_holds_only is not None else derived_holds_only
    if witness is None:
        return Finding(Verdict.UNDECIDED,
                       f"{what} ({p}) is not a positive multiple of the derived condition ({d}), and no point where one "
                       f"holds and the other fails was found in {tries} exact samples{suffix}",
                       Evidence(Method.INSTANCES, instances=tries, facts=facts), derived=derived, corrected=corrected)
    values = {"printed_value": _evaluate(p.expr, witness), "derived_value": _evaluate(d.expr, witness)}
    how = ("it holds at the witness where the derived condition fails" if witness is printed_holds_only
           else "it fails at the witness where the derived condition holds")
    reversed_ = " (the relation is reversed)" if facts.get("ratio") is not None else ""
    return Finding(
        on_mismatch,
        f"{what} ({p}) is not the derived condition ({d}){reversed_}: {how} (values {sp.sstr(values['printed_value'])} "
        f"and {sp.sstr(values['derived_value'])}){suffix}",
        Evidence(Method.COUNTEREXAMPLE, witness={str(k): v for k, v in witness.items()}, facts={**facts, **values}),
        derived=derived, corrected=corrected)


@dataclass(frozen=True, slots=True)
class Bound:
    """A condition solved for one variable: ``var > bound`` (``lower``, ``strict``), ``var >= bound``
    (``lower``), or, with ``lower=False``, the upper bounds ``var < bound`` / ``var <= bound``."""

    var: sp.Symbol
    bound: sp.Expr
    strict: bool
    lower: bool = True

    def __str__(self) -> str:
        op = (">" if self.strict else ">=") if self.lower else ("<" if self.strict else "<=")
        return f"{self.var} {op} {sp.sstr(self.bound)}"


class NotABound(ValueError):
    """The condition is not a bound on the variable (no inequality, not affine in it, the
    variable absent, or a coefficient of unknown sign); ``reason`` says which."""

    def __init__(self, reason: str):
        super().__init__(reason)
        self.reason = reason


def as_bound(condition: sp.Basic, var: sp.Symbol) -> Bound:
    """Solve a condition that is affine in ``var``: a lower bound when the coefficient of ``var``
    is provably positive, an upper bound when it is provably negative.

    Raises :class:`NotABound` for anything else: ``True``/``False`` (a relation that evaluated),
    an equation, a condition without ``var`` or not affine in it, or a coefficient whose sign
    depends on the parameters.

    >>> K, T, b, za = sp.symbols('K T b z_a', positive=True)
    >>> as_bound(sp.Gt(b - za, K*T/2), b)
    Bound(var=b, bound=K*T/2 + z_a, strict=True, lower=True)
    >>> str(as_bound(sp.Lt(b, K*T), b)), str(as_bound(sp.Ge(K, 2*b), b))
    ('b < K*T', 'b <= K/2')
    >>> as_bound(sp.Gt(b, b), b)
    Traceback (most recent call last):
    ...
    hapticproof.certify.NotABound: the condition is identically False
    """
    if condition in (sp.true, sp.false) or isinstance(condition, (bool, sp.logic.boolalg.BooleanAtom)):
        raise NotABound(f"the condition is identically {bool(condition)}")
    if not isinstance(condition, sp.core.relational.Relational):
        raise NotABound(f"not an inequality: {sp.sstr(condition)}")
    if isinstance(condition, (sp.StrictGreaterThan, sp.GreaterThan)):
        expr = condition.lhs - condition.rhs
    elif isinstance(condition, (sp.StrictLessThan, sp.LessThan)):
        expr = condition.rhs - condition.lhs
    else:
        raise NotABound(f"an equation, not an inequality: {sp.sstr(condition)}")
    strict = isinstance(condition, (sp.StrictGreaterThan, sp.StrictLessThan))
    expr = sp.expand(expr)
    if var not in expr.free_symbols:
        raise NotABound(f"{var} does not occur in it")
    coeff = sp.expand(sp.diff(expr, var))
    if coeff.has(var):
        raise NotABound(f"it is not affine in {var}")
    rest = sp.expand(expr - coeff * var)
    if rest.has(var):
        raise NotABound(f"it is not affine in {var}")
    if coeff.is_zero:
        raise NotABound(f"{var} cancels out of it")
    sign = _provable_sign(coeff)
    if sign is None:
        raise NotABound(f"the sign of the coefficient {sp.sstr(coeff)} of {var} is not fixed by the assumptions")
    bound = -rest / coeff
    bound = canonical_rational(bound) if bound.is_rational_function() else sp.cancel(bound)
    return Bound(var, bound, strict, sign > 0)


def as_lower_bound(condition: sp.Basic, var: sp.Symbol) -> Bound:
    """:func:`as_bound`, and :class:`NotABound` ("it is an upper bound, ...") unless the
    condition bounds ``var`` from below (the reading every comparison of quoted bounds needs)."""
    bound = as_bound(condition, var)
    if not bound.lower:
        raise NotABound(f"it is an upper bound, {bound}")
    return bound


def _provable_sign(expr: sp.Expr) -> int | None:
    """+1 / -1 when ``expr`` is provably positive / negative under the symbols' assumptions."""
    for form in (expr, sp.factor(expr), sp.cancel(expr)):
        if form.is_positive:
            return 1
        if form.is_negative:
            return -1
    return None


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


def _domain_floor(var: sp.Symbol) -> sp.Expr | None:
    """Lowest admissible value of ``var`` (0 for a non-negative or positive symbol)."""
    return sp.Integer(0) if var.is_nonnegative else None


def _holds(condition: sp.Basic, point: Mapping[sp.Symbol, Any]) -> bool | None:
    """Truth of a condition at an exact point (None when it cannot be decided)."""
    try:
        value = condition.xreplace(dict(point)) if isinstance(condition, sp.Basic) else condition
        if isinstance(value, sp.core.relational.Relational):
            value = value.func(*value.args)
        if value in (sp.true, sp.false):
            return bool(value)
        if isinstance(value, bool):
            return value
        if isinstance(value, sp.core.relational.Relational):
            lhs, rhs = (sp.nsimplify(sp.N(x, 60)) if not x.is_Rational else x for x in (value.lhs, value.rhs))
            return bool(value.func(lhs, rhs)) if lhs.is_number and rhs.is_number else None
    except (TypeError, ValueError, ZeroDivisionError):
        return None
    return None


def _printed_form(p: Bound | None, printed: sp.Basic, always: bool = False) -> Any:
    """The canonical form of what was read (for equivalence of mutated displays)."""
    if always:
        return ("holds for every admissible value",)
    if p is not None:
        return ("bound", str(p.var), ">" if p.lower else "<", p.strict, sp.srepr(p.bound))
    return ("condition", sp.srepr(printed))


def _recheck(verify: Callable | None, point: dict, facts: dict) -> str | None:
    """Re-check a not-sufficient witness by the independent decision; the reason it failed, or None."""
    if verify is None:
        return None
    try:
        check = verify(point)
    except (HapticproofError, ArithmeticError, TypeError, ValueError) as err:
        # e.g. a bound with a constant like cos(1) puts b at an irrational value: no exact scene
        facts["recheck"] = f"{type(err).__name__}: {err}"
        return f"the witness {point} could not be re-checked exactly ({err})"
    facts["recheck"] = check.to_json()
    if check.decision != Decision.DISPROVED:
        return f"the witness {point} was not confirmed by the exact decision ({check.reason})"
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
    """Compare a printed condition with the exact one, a lower bound on ``var``.

    ``exact`` must be necessary and sufficient (e.g. the derived worst-case condition). The
    verdict is ``confirmed`` (same bound, or both conditions hold for every admissible ``var``),
    ``conservative`` (printed bound provably >= exact: sufficient, not necessary) or
    ``on_weaker`` (the printed condition holds somewhere the exact one fails; the witness is
    exact parameters with ``var`` where the exact condition fails). The printed relation is
    read for what it says: an upper bound (``b < X``, or a negative coefficient of ``b``), a
    relation that evaluated to ``True``/``False``, or one without ``b`` is never equivalent to
    a lower bound; such a condition gets ``on_weaker`` with a witness when it holds where the
    exact one fails, ``wrong`` when it holds for no admissible ``var``, else ``undecided``.
    ``verify``, if given, re-checks a not-sufficient witness by an independent exact decision
    (e.g. root isolation of the numeric scene); a witness it does not confirm gives
    ``undecided``. ``evidence.facts["printed_form"]`` is the canonical form of the printed
    condition.

    >>> K, T, b = sp.symbols('K T b', positive=True)
    >>> compare_bounds(sp.Lt(b, K*T/2), sp.Ge(b, K*T/2), b).verdict.value
    'wrong'
    >>> compare_bounds(sp.Gt(b + K*T, 0, evaluate=False), sp.Ge(b, -K*T, evaluate=False), b).verdict.value
    'confirmed'
    """
    e = as_bound(exact, var)
    if not e.lower:
        raise ValueError(f"the exact condition must be a lower bound on {var}: {exact}")
    floor = _domain_floor(var)
    suffix = f" ({note})" if note else ""
    exact_text = f"{var} {'>=' if not e.strict else '>'} {sp.sstr(e.bound)}"
    try:
        p = as_bound(printed, var)
    except NotABound as err:
        return _compare_general(printed, None, e, var, err.reason, on_weaker=on_weaker, box=box, verify=verify,
                                corrected=corrected, what=what, suffix=suffix, tries=tries, exact=exact)
    if not p.lower:
        return _compare_general(printed, p, e, var, f"it is an upper bound, {p}", on_weaker=on_weaker, box=box,
                                verify=verify, corrected=corrected, what=what, suffix=suffix, tries=tries, exact=exact)
    raw = p.bound - e.bound
    difference = canonical_rational(raw) if raw.is_rational_function() else sp.cancel(sp.together(raw))
    strictness = "" if p.strict == e.strict else f"; compared up to the boundary ({'>' if p.strict else '>='} vs {'>' if e.strict else '>='})"
    symbols = sorted((p.bound.free_symbols | e.bound.free_symbols) - {var}, key=str)
    form = _printed_form(p, printed)
    # a condition every admissible value satisfies reads as True (its canonical form on the box)
    always = floor is not None and sign_on_box(e.bound - floor, box) == -1
    if always and sign_on_box(p.bound - floor, box) == -1:
        form = _printed_form(None, printed, always=True)
    if is_identically_zero(difference):
        return Finding(
            Verdict.CONFIRMED,
            f"{what} is equivalent to the exact condition {exact_text}{strictness}{suffix}",
            Evidence(Method.CANONICAL_FORM, facts={"printed_bound": p.bound, "exact_bound": e.bound, "printed_form": form}),
            derived=exact,
        )
    if always:
        # the exact condition holds for every admissible value of var
        if sign_on_box(p.bound - floor, box) == -1:
            return Finding(
                Verdict.CONFIRMED,
                f"{what} ({p}) and the exact condition ({exact_text}) both hold for every admissible {var} "
                f"(both bounds are <= {floor}){suffix}",
                Evidence(Method.ENDPOINT_ANALYSIS, facts={"printed_bound": p.bound, "exact_bound": e.bound,
                                                          "printed_form": _printed_form(None, printed, always=True)}),
                derived=exact,
            )
    sign = sign_on_box(difference, box)
    ranges = dict(box or {})
    weaker = None
    stronger = None
    for point in Sampler(symbols, seed=7, ranges=ranges).draw(tries):
        d = _evaluate(difference, point)
        eb = _evaluate(e.bound, point)
        if d is None or eb is None or not d.is_real or not eb.is_real:
            continue
        if d < 0 and weaker is None and (floor is None or eb > floor):
            weaker = point
        if d > 0 and stronger is None:
            stronger = point
        if weaker is not None and (stronger is not None or sign is not None):
            break
    if weaker is not None:
        point = dict(weaker)
        low = p.bound.xreplace(weaker)
        if floor is not None:
            low = sp.Max(low, floor)
        point[var] = sp.nsimplify((low + e.bound.xreplace(weaker)) / 2)
        facts: dict[str, Any] = {
            "printed_bound": p.bound.xreplace(weaker),
            "exact_bound": e.bound.xreplace(weaker),
            "printed_holds": True,
            "exact_holds": False,
            "printed_form": form,
        }
        failure = _recheck(verify, point, facts)
        if failure is not None:
            return Finding(Verdict.UNDECIDED, f"{what}: {failure}{suffix}",
                           Evidence(Method.COUNTEREXAMPLE, witness={str(k): v for k, v in point.items()}, facts=facts),
                           derived=exact, corrected=corrected)
        region = " for all parameters" if sign == -1 else " in part of the parameter space"
        return Finding(
            on_weaker,
            f"{what} ({p}) is weaker than the exact condition {exact_text}{region}: it holds at the witness where the "
            f"exact condition fails{suffix}",
            Evidence(Method.COUNTEREXAMPLE, witness={str(k): v for k, v in point.items()}, facts=facts),
            derived=exact,
            corrected=corrected,
        )
    if sign == 1:
        witness = None
        facts = {"printed_bound": p.bound, "exact_bound": e.bound, "difference": difference, "printed_form": form}
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
        Evidence(Method.INSTANCES, instances=tries, facts={"difference": difference, "printed_form": form}),
        derived=exact,
        corrected=corrected,
    )


def _compare_general(
    printed: sp.Basic, p: Bound | None, e: Bound, var: sp.Symbol, reason: str, *, on_weaker: Verdict,
    box: Mapping[sp.Symbol, tuple[Any, Any]] | None, verify: Callable | None, corrected: str | None, what: str,
    suffix: str, tries: int, exact: sp.Basic,
) -> Finding:
    """A printed condition that is not a lower bound on ``var``, against the exact lower bound:
    search exact points where it holds and the exact condition fails (and conversely)."""
    floor = _domain_floor(var)
    exact_text = f"{var} {'>=' if not e.strict else '>'} {sp.sstr(e.bound)}"
    form = _printed_form(None, printed) if p is None else _printed_form(p, printed)
    free = printed.free_symbols if isinstance(printed, sp.Basic) else set()
    symbols = sorted((set(free) | e.bound.free_symbols) - {var}, key=str)
    weaker = stronger = None
    for point in Sampler(symbols, seed=11, ranges=dict(box or {})).draw(tries):
        eb = _evaluate(e.bound, point)
        if eb is None or not eb.is_real or eb.free_symbols:
            continue
        below: list[sp.Expr] = []
        if floor is None:
            below = [eb - 1, eb - sp.Rational(1, 10), eb - 10]
        elif eb > floor:
            below = [floor + (eb - floor) * sp.Rational(k, 8) for k in (1, 4, 7)]
        above = [eb + sp.Rational(1, 10), eb + 1, 2 * abs(eb) + 10]
        if floor is not None:
            above = [v if v > floor else floor + sp.Rational(1, 10) for v in above]
        if p is not None:
            pb = _evaluate(p.bound, point)
            if pb is not None and pb.is_real and not pb.free_symbols:
                for v in (pb - sp.Rational(1, 10), pb + sp.Rational(1, 10)):
                    if (floor is None or v > floor) and v < eb:
                        below.append(v)
                    if v > eb and (floor is None or v > floor):
                        above.append(v)
        if weaker is None:
            for v in below:
                if _holds(printed, {**point, var: v}) is True:
                    weaker = {**point, var: v}
                    break
        if stronger is None:
            for v in above:
                if _holds(printed, {**point, var: v}) is False:
                    stronger = {**point, var: v}
                    break
        if weaker is not None and stronger is not None:
            break
    described = f"{what} is not a lower bound on {var} ({reason})"
    if weaker is not None:
        facts: dict[str, Any] = {"exact_bound": e.bound.xreplace({k: v for k, v in weaker.items() if k != var}),
                                 "printed_holds": True, "exact_holds": False, "printed_form": form, "reading": reason}
        failure = _recheck(verify, dict(weaker), facts)
        witness = {str(k): v for k, v in weaker.items()}
        if failure is not None:
            return Finding(Verdict.UNDECIDED, f"{described}: {failure}{suffix}",
                           Evidence(Method.COUNTEREXAMPLE, witness=witness, facts=facts), derived=exact, corrected=corrected)
        return Finding(on_weaker, f"{described}: it holds at the witness where the exact condition {exact_text} fails{suffix}",
                       Evidence(Method.COUNTEREXAMPLE, witness=witness, facts=facts), derived=exact, corrected=corrected)
    never = printed is sp.false or (p is not None and not p.lower and floor is not None
                                    and sign_on_box(p.bound - floor, box) == -1)
    if never:
        witness = {str(k): v for k, v in stronger.items()} if stronger is not None else None
        return Finding(Verdict.WRONG, f"{described}: it holds for no admissible {var}, while the exact condition "
                       f"{exact_text} holds at the witness{suffix}",
                       Evidence(Method.COUNTEREXAMPLE, witness=witness, facts={"never_holds": True, "printed_form": form,
                                                                                "reading": reason}),
                       derived=exact, corrected=corrected)
    witness = {str(k): v for k, v in stronger.items()} if stronger is not None else None
    return Finding(
        Verdict.UNDECIDED,
        f"{described}: it is not equivalent to the exact condition {exact_text}"
        + (" (it fails at the witness where the exact one holds)" if witness else "")
        + f", and no point where it holds and the exact one fails was found in {tries} exact samples{suffix}",
        Evidence(Method.INSTANCES, instances=tries, witness=witness, facts={"printed_form": form, "reading": reason}),
        derived=exact, corrected=corrected,
    )
