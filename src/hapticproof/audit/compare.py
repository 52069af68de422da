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
from collections.abc import Callable, Iterable, Mapping
from dataclasses import dataclass
from typing import Any

import sympy as sp

from hapticproof.exact.canonical import cancel as exact_cancel
from hapticproof.core.errors import HapticproofError
from hapticproof.core.evidence import Decision, Evidence, Finding, Method, Outcome, Verdict
from hapticproof.core.naming import marked
from hapticproof.core.symbols import c as C_SYM
from hapticproof.exact.canonical import Sampler, canonical_rational, certified_nonzero, evaluate_at, is_identically_zero
from hapticproof.exact.evaluator import relation_at

__all__ = ["Bound", "find_difference", "compare_expressions", "NotABound", "SignCondition", "as_sign_condition", "compare_sign_conditions", "as_bound", "as_lower_bound", "compare_bounds", "sign_on_box", "relation"]


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
        va, vb = evaluate_at(a, point), evaluate_at(b, point)
        if va is None or vb is None or va.free_symbols or vb.free_symbols:
            continue
        if certified_nonzero(va - vb):
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
        f"{what} differs from the derived one: {marked(printed_value)} vs {marked(derived_value)} at the witness"
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
        return sp.srepr(expr.applyfunc(lambda e: exact_cancel(e)))
    return sp.srepr(sp.expand(expr) if isinstance(expr, sp.Expr) else expr)


def _short(expr: Any, limit: int = 120) -> str | None:
    """``sstr`` of a simplified expression when it is short enough for a one-sentence detail."""
    try:
        value = sp.factor(exact_cancel(sp.together(expr))) if isinstance(expr, sp.Expr) else expr
    except (sp.PolynomialError, TypeError, ValueError):
        value = expr
    text = marked(value)
    return text if len(text) <= limit else None


@dataclass(frozen=True, slots=True)
class SignCondition:
    """A printed or derived inequality normalised to ``expr op 0`` with ``op`` in
    ``>``, ``>=``, ``=``, ``!=`` (``a < b`` becomes ``b - a > 0``)."""

    expr: sp.Expr
    op: str

    def holds(self, point: Mapping[sp.Symbol, Any]) -> bool | None:
        value = evaluate_at(self.expr, point)
        if value is None or value.free_symbols or not value.is_real:
            return None
        return {">": value > 0, ">=": value >= 0, "=": value == 0, "!=": value != 0}[self.op]

    def __str__(self) -> str:
        return f"{marked(self.expr)} {self.op} 0"


def as_sign_condition(relation: sp.Basic) -> SignCondition:
    """Normalise a relation to ``expr op 0``.

    >>> a, b = sp.symbols('a b')
    >>> str(as_sign_condition(sp.Lt(a, b))), str(as_sign_condition(sp.Ge(a, 2*b)))
    ('-a + b > 0', 'a - 2*b >= 0')
    """
    if relation in (sp.true, sp.false):
        return SignCondition(sp.Integer(1 if relation is sp.true else -1), ">")
    if not isinstance(relation, sp.core.relational.Relational):
        raise NotABound(f"not a relation: {marked(relation)}")
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
        ratio = exact_cancel(sp.together(p.expr / d.expr)) if d.expr != 0 else None
        if same_kind and ratio is not None and ratio != 0 and not ratio.free_symbols:
            return Finding(Verdict.CONFIRMED, f"{what} is the derived condition {d} up to the factor {marked(ratio)}{suffix}",
                           Evidence(Method.CANONICAL_FORM, facts={**facts, "printed_form": derived_form}), derived=derived)
    else:
        ratio = exact_cancel(sp.together(p.expr / d.expr)) if d.expr != 0 else None
        sign = _provable_sign(ratio) if ratio is not None and ratio != 0 else None
        if sign is not None:
            if sign > 0:
                strictness = "" if p.op == d.op else f"; compared up to the boundary ({p.op} vs {d.op})"
                return Finding(
                    Verdict.CONFIRMED,
                    f"{what} is the derived condition {d} multiplied by {marked(ratio)} > 0{strictness}{suffix}",
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
    values = {"printed_value": evaluate_at(p.expr, witness), "derived_value": evaluate_at(d.expr, witness)}
    how = ("it holds at the witness where the derived condition fails" if witness is printed_holds_only
           else "it fails at the witness where the derived condition holds")
    reversed_ = " (the relation is reversed)" if facts.get("ratio") is not None else ""
    return Finding(
        on_mismatch,
        f"{what} ({p}) is not the derived condition ({d}){reversed_}: {how} (values {marked(values['printed_value'])} "
        f"and {marked(values['derived_value'])}){suffix}",
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
        return f"{self.var} {op} {marked(self.bound)}"


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
    hapticproof.audit.compare.NotABound: the condition is identically False
    """
    if condition in (sp.true, sp.false) or isinstance(condition, (bool, sp.logic.boolalg.BooleanAtom)):
        raise NotABound(f"the condition is identically {bool(condition)}")
    if not isinstance(condition, sp.core.relational.Relational):
        raise NotABound(f"not an inequality: {marked(condition)}")
    if isinstance(condition, (sp.StrictGreaterThan, sp.GreaterThan)):
        expr = condition.lhs - condition.rhs
    elif isinstance(condition, (sp.StrictLessThan, sp.LessThan)):
        expr = condition.rhs - condition.lhs
    else:
        raise NotABound(f"an equation, not an inequality: {marked(condition)}")
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
        raise NotABound(f"the sign of the coefficient {marked(coeff)} of {var} is not fixed by the assumptions")
    bound = -rest / coeff
    bound = canonical_rational(bound) if bound.is_rational_function() else exact_cancel(bound)
    return Bound(var, bound, strict, sign > 0)


def as_lower_bound(condition: sp.Basic, var: sp.Symbol) -> Bound:
    """:func:`as_bound`, and :class:`NotABound` ("it is an upper bound, ...") unless the
    condition bounds ``var`` from below (the reading every comparison of quoted bounds needs)."""
    bound = as_bound(condition, var)
    if not bound.lower:
        raise NotABound(f"it is an upper bound, {bound}")
    return bound


def _signs_seen(expr: sp.Expr, tries: int = 12) -> set[int]:
    """Signs (-1, 0, +1) ``expr`` takes at a few exact points that satisfy every assumption of
    its symbols (points where it is undefined are skipped). A sign seen refutes a proof of the
    opposite one: SymPy's assumptions are sound, so ``is_positive`` cannot hold for an
    expression (or any form of it) that is ``<= 0`` at a point of its domain."""
    symbols = sorted(expr.free_symbols, key=str)
    if not all(isinstance(s, sp.Symbol) for s in symbols):
        return set()
    # SymPy's own assumptions only: a marker a symbol carries (``parameter``, kept apart from a
    # helper of the same name) says nothing of its values
    facts = {s: [(f"is_{k}", v) for k, v in s.assumptions0.items() if hasattr(sp.S.One, f"is_{k}")]
             for s in symbols}
    seen: set[int] = set()
    for point in Sampler(symbols, seed=3).draw(tries):
        if not all(getattr(point[s], name) == v for s in symbols for name, v in facts[s]):
            continue            # outside a symbol's domain (e.g. 0 for a nonzero symbol)
        value = evaluate_at(expr, point)
        if value is not None and value.is_Rational:
            seen.add(1 if value > 0 else (-1 if value < 0 else 0))
    return seen


def relation(kind: type, lhs: Any, rhs: Any) -> sp.Basic:
    """``kind(lhs, rhs)`` (``sp.Gt``, ``sp.Ge``, ``sp.Lt``, ``sp.Le``) exactly as SymPy builds it.

    When ``lhs - rhs`` is seen to take both signs at exact points of its domain, SymPy's
    evaluation cannot decide the relation (its assumptions are sound) and returns it
    unevaluated: that object is built directly, without SymPy's sign queries on what may be
    a large expression (a determinant of parameters).

    >>> x, y = sp.symbols('x y', positive=True)
    >>> relation(sp.Gt, x - y, 0) == sp.Gt(x - y, 0), relation(sp.Gt, x + y, 0)
    (True, True)
    """
    seen = _signs_seen(sp.sympify(lhs - rhs)) if isinstance(lhs - rhs, sp.Expr) else set()
    if {-1, 1} <= seen:
        return kind(lhs, rhs, evaluate=False)
    return kind(lhs, rhs)


def _provable_sign(expr: sp.Expr) -> int | None:
    """+1 / -1 when ``expr`` is provably positive / negative under the symbols' assumptions.

    An expression seen to be zero, or of both signs, at exact points of its domain has neither
    sign provably (:func:`_signs_seen`): that is settled before any ``factor``.

    >>> x, y = sp.symbols('x y', positive=True)
    >>> _provable_sign((x + y)**2 / (x*y)), _provable_sign(-x/(1 + y)), _provable_sign(x - y)
    (1, -1, None)
    """
    seen = _signs_seen(expr)
    if 0 in seen or {-1, 1} <= seen:
        return None
    for form in (expr, sp.factor(expr), exact_cancel(expr)):
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
    # a corner seen negative (positive) at an exact point of its domain is not provably >= 0 (<= 0)
    seen = [_signs_seen(v) if v.free_symbols else set() for v in corners]
    if not any(-1 in signs for signs in seen) and all(sp.factor(v).is_nonnegative for v in corners):
        return 1
    if not any(1 in signs for signs in seen) and all(sp.factor(v).is_nonpositive for v in corners):
        return -1
    return None


def _domain_floor(var: sp.Symbol) -> sp.Expr | None:
    """Lowest admissible value of ``var`` (0 for a non-negative or positive symbol)."""
    return sp.Integer(0) if var.is_nonnegative else None


def _holds(condition: sp.Basic, point: Mapping[sp.Symbol, Any]) -> bool | None:
    """Truth of a condition at an exact point (None when it cannot be decided)."""
    fast = relation_at(condition, point)
    if fast is not None:
        return fast
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
    exact_text = f"{var} {'>=' if not e.strict else '>'} {marked(e.bound)}"
    try:
        p = as_bound(printed, var)
    except NotABound as err:
        return _compare_general(printed, None, e, var, err.reason, on_weaker=on_weaker, box=box, verify=verify,
                                corrected=corrected, what=what, suffix=suffix, tries=tries, exact=exact)
    if not p.lower:
        return _compare_general(printed, p, e, var, f"it is an upper bound, {p}", on_weaker=on_weaker, box=box,
                                verify=verify, corrected=corrected, what=what, suffix=suffix, tries=tries, exact=exact)
    raw = p.bound - e.bound
    difference = canonical_rational(raw) if raw.is_rational_function() else exact_cancel(sp.together(raw))
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
        d = evaluate_at(difference, point)
        eb = evaluate_at(e.bound, point)
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
            f"{what} implies the exact condition (its bound exceeds the exact one by {marked(difference)} >= 0) but not conversely{strictness}{suffix}",
            Evidence(Method.ENDPOINT_ANALYSIS, witness=witness, facts=facts),
            derived=exact,
        )
    return Finding(
        Verdict.UNDECIDED,
        f"{what}: the sign of the bound difference {marked(difference)} was not settled and no witness was found in {tries} exact samples{suffix}",
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
    exact_text = f"{var} {'>=' if not e.strict else '>'} {marked(e.bound)}"
    form = _printed_form(None, printed) if p is None else _printed_form(p, printed)
    free = printed.free_symbols if isinstance(printed, sp.Basic) else set()
    symbols = sorted((set(free) | e.bound.free_symbols) - {var}, key=str)
    weaker = stronger = None
    for point in Sampler(symbols, seed=11, ranges=dict(box or {})).draw(tries):
        eb = evaluate_at(e.bound, point)
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
            pb = evaluate_at(p.bound, point)
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
