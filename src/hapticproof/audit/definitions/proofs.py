r"""Proofs that a printed bound is sufficient or necessary for a condition at every frequency.

The exact condition of a property is often "``F_k(p, t) >= 0`` for every ``t``" (``t = c`` in
``[-1, 1]`` on the unit circle, ``x = omega^2`` in ``[0, oo)`` on the axis) with no closed form
in the parameters ``p``. A printed lower bound ``v >= g(p)`` is then

* **sufficient** when every ``F_k`` is nondecreasing in ``v`` and ``F_k(g, p, t) >= 0`` for all
  ``t`` and every admissible ``p`` -- proved by :func:`nonnegative`: the numerator, expanded in
  the parameters, is a sum of parameter monomials that are non-negative under the stated signs
  times polynomials in ``t`` that the kernel proves non-negative on the interval, over a
  denominator of the same kind;
* **necessary** when at an end ``t0`` of the interval (``t -> oo`` included) one ``F_k(v, p, t0)``
  is a positive multiple of ``v - g``: the exact condition at ``t0`` is the printed bound.

Both are proofs, never samples; when neither applies the caller decides on instances.

>>> import sympy as sp
>>> K, T, B = sp.symbols("K T B", nonnegative=True)
>>> b, c = sp.Symbol("b", real=True), sp.Symbol("c", real=True)
>>> F = b - K*T/2 - K*T*c + B*(2*c**2 - 1)              # Re G^-1 of a wall delayed one sample
>>> sufficient(b, 3*K*T/2 + B, [F], c, -1, 1), necessary(b, 3*K*T/2 - B, [F], c, -1, 1)
(True, True)
"""

from __future__ import annotations

from collections.abc import Iterable, Mapping, Sequence
from typing import Any

import flint
import sympy as sp

from hapticproof.exact.kernel import decide_sign
from hapticproof.core.evidence import Decision

__all__ = ["nonnegative", "sufficient", "necessary", "lower_bound", "implies", "lower_bounds", "intervals", "chart"]


def _monomial_nonnegative(monomial: tuple[int, ...], symbols: Sequence[sp.Symbol]) -> bool:
    return all(e % 2 == 0 or sym.is_nonnegative for e, sym in zip(monomial, symbols))


def _poly_nonnegative(poly: sp.Poly, t: sp.Symbol, lo: Any, hi: Any) -> bool:
    """A polynomial in ``t`` with parameter coefficients ``>= 0`` on ``[lo, hi]`` by groups."""
    params = [g for g in poly.gens if g != t]
    if not params:
        coeffs = [sp.Rational(c) for c in sp.Poly(poly.as_expr(), t).all_coeffs()[::-1]]
        p = flint.fmpq_poly([flint.fmpq(int(c.p), int(c.q)) for c in coeffs])
        return decide_sign(p, lo, hi, variable="t").decision == Decision.PROVED
    grouped = sp.Poly(poly.as_expr(), *params)
    for monomial, coeff in grouped.terms():
        if not _monomial_nonnegative(monomial, params):
            return False
        coeff = sp.sympify(coeff)
        if coeff.free_symbols - {t}:
            return False
        cp = sp.Poly(coeff, t)
        values = [sp.Rational(c) for c in cp.all_coeffs()[::-1]]
        p = flint.fmpq_poly([flint.fmpq(int(c.p), int(c.q)) for c in values])
        if decide_sign(p, lo, hi, variable="t").decision != Decision.PROVED:
            return False
    return True


def nonnegative(expr: Any, t: sp.Symbol, lo: Any, hi: Any) -> bool:
    """See :func:`_nonnegative`; anything outside polynomial arithmetic (``Min``, ``|x|``) is "not proved"."""
    try:
        return _nonnegative(expr, t, lo, hi)
    except (sp.PolynomialError, sp.polys.polyerrors.CoercionFailed, TypeError, ValueError):
        return False


def _nonnegative(expr: Any, t: sp.Symbol, lo: Any, hi: Any) -> bool:
    r"""``expr(p, t) >= 0`` for every ``t`` in ``[lo, hi]`` (``hi = None``: ``oo``) and every ``p``
    the symbols' signs allow, proved by groups (see the module doc); ``False`` means "not proved".

    >>> a = sp.Symbol("a", positive=True)
    >>> c = sp.Symbol("c", real=True)
    >>> nonnegative(a*(1 - c) + a**2*c**2, c, -1, 1), nonnegative(a*c, c, -1, 1)
    (True, False)
    """
    expr = sp.cancel(sp.together(sp.sympify(expr)))
    num, den = sp.fraction(expr)
    gens = sorted(expr.free_symbols, key=str)
    if t not in gens:
        gens.append(t)
    try:
        pn = sp.Poly(sp.expand(num), *gens)
        pd = sp.Poly(sp.expand(den), *gens)
    except sp.PolynomialError:
        return False
    # num/den >= 0 wherever it is defined (den != 0) when both have one sign by groups
    if _poly_nonnegative(pn, t, lo, hi) and _poly_nonnegative(pd, t, lo, hi):
        return True
    if _poly_nonnegative(-pn, t, lo, hi) and _poly_nonnegative(-pd, t, lo, hi):
        return True
    return False


def lower_bound(condition: Any, candidates: Iterable[sp.Symbol]) -> tuple[sp.Symbol, sp.Expr] | None:
    """``(v, g)`` when the printed condition is ``v >= g`` (or ``v > g``, or any affine form with
    a provably positive coefficient of ``v``) for one of ``candidates``."""
    from hapticproof.audit.compare import NotABound, as_bound

    for v in candidates:
        try:
            bound = as_bound(condition, v)
        except (NotABound, TypeError, ValueError):
            continue
        if bound.lower:
            return v, bound.bound
    return None


def lower_bounds(condition: Any, candidates: Iterable[sp.Symbol]) -> dict[sp.Symbol, sp.Expr] | None:
    r"""Lower bounds ``{v: g}`` on distinct variables when the printed condition is a conjunction
    of them, ``\min(v_1, v_2) \ge g`` included; ``None`` otherwise."""
    parts = list(condition.args) if isinstance(condition, sp.And) else [condition]
    out: dict[sp.Symbol, sp.Expr] = {}
    candidates = list(candidates)
    for part in parts:
        if isinstance(part, sp.core.relational.Relational) and isinstance(part.lhs, sp.Min) and part.rel_op in (">", ">="):
            for arg in part.lhs.args:
                if not arg.is_Symbol or arg in out:
                    return None
                out[arg] = part.rhs
            continue
        found = lower_bound(part, [c for c in candidates if c not in out])
        if found is None:
            return None
        out[found[0]] = found[1]
    return out or None


def sufficient(v: sp.Symbol | Mapping[sp.Symbol, Any], g: Any, forms: Sequence[Any], t: sp.Symbol, lo: Any, hi: Any) -> bool:
    """``v >= g`` (or every bound of a mapping ``{v: g}``) implies every ``form >= 0`` on the
    interval: each form nondecreasing in ``v`` and non-negative at ``v = g``, or non-negative at
    ``v = g + w`` for every ``w >= 0`` (see the module doc)."""
    bounds = dict(v) if isinstance(v, Mapping) else {v: g}
    for F in forms:
        F = sp.sympify(F)
        if _monotone_at_bounds(F, bounds, t, lo, hi):
            continue
        shifted = F.subs({var: bound + sp.Symbol(f"w_{k}", nonnegative=True) for k, (var, bound) in enumerate(bounds.items())},
                         simultaneous=True)
        if not nonnegative(shifted, t, lo, hi):
            return False
    return True


def _monotone_at_bounds(F: sp.Expr, bounds: Mapping[sp.Symbol, Any], t: sp.Symbol, lo: Any, hi: Any) -> bool:
    for var in bounds:
        if var in F.free_symbols and not nonnegative(sp.diff(F, var), t, lo, hi):
            return False
    return nonnegative(F.subs(dict(bounds), simultaneous=True), t, lo, hi)


def _primitive(expr: Any) -> sp.Expr:
    """``expr`` divided by the positive content of its rational coefficients (``2x - 4y`` -> ``x - 2y``)."""
    expr = sp.expand(sp.sympify(expr))
    if expr.is_number or not expr.free_symbols or expr.has(sp.Min, sp.Max, sp.Abs):
        return expr
    content, _ = sp.Poly(expr, *sorted(expr.free_symbols, key=str)).primitive()
    content = abs(sp.Rational(content)) if sp.sympify(content).is_Rational else 1
    return sp.expand(expr / content) if content else expr


def implies(p: Any, q: Any, multipliers: Sequence[Any] = ()) -> bool:
    """``p >= 0`` implies ``q >= 0`` for every admissible parameter value: ``mu q - lam p`` is
    non-negative by groups for some non-negative monomials ``mu > 0`` and ``lam >= 0`` of degree
    at most one in the parameters (a small Positivstellensatz certificate).

    >>> b1, b2, g = sp.symbols("b_1 b_2 g", positive=True)
    >>> implies(b1*b2 - (b1 + b2)*g, b1 - g)
    True
    """
    p, q = _primitive(p), _primitive(q)
    free = sorted((p.free_symbols | q.free_symbols), key=str)
    positive = [s for s in free if s.is_positive]
    nonneg = [s for s in free if s.is_nonnegative]
    dummy = sp.Dummy("t", real=True)
    for mu in [sp.Integer(1), *positive, *multipliers]:
        for lam in [sp.Integer(1), sp.Integer(0), *nonneg, *multipliers]:
            if nonnegative(sp.expand(mu * q - lam * p) + 0 * dummy, dummy, 0, 1):
                return True
    return False


def necessary(v: sp.Symbol, g: Any, forms: Sequence[Any], t: sp.Symbol, lo: Any, hi: Any) -> bool:
    """At an end of the interval one form is a positive multiple of ``v - g``."""
    ends = [lo] + ([hi] if hi is not None else [sp.oo])
    for F in forms:
        F = sp.sympify(F)
        if v not in F.free_symbols:
            continue
        for t0 in ends:
            value = sp.limit(F, t, t0) if t0 in (sp.oo, -sp.oo) else sp.cancel(F.subs(t, t0))
            if value.has(sp.oo, -sp.oo, sp.zoo, sp.nan):
                continue
            ratio = sp.cancel(sp.together(value / (v - g)))
            if ratio.free_symbols & {v}:
                continue
            if ratio.is_positive or (ratio.is_number and ratio > 0):
                return True
            if sp.factor(ratio).is_positive:
                return True
    return False


def intervals(relations: Iterable[Any]) -> dict[sp.Symbol, tuple[Any, Any]]:
    """Bounds ``{x: (lo, hi)}`` (``None``: unbounded) that relations such as ``a < 1``,
    ``0 <= a``, ``-1 <= a <= 1`` or ``Abs(a) <= 1`` state about single symbols."""
    out: dict[sp.Symbol, list[Any]] = {}

    def put(sym: sp.Symbol, lo: Any = None, hi: Any = None) -> None:
        cur = out.setdefault(sym, [None, None])
        if lo is not None and (cur[0] is None or lo > cur[0]):
            cur[0] = lo
        if hi is not None and (cur[1] is None or hi < cur[1]):
            cur[1] = hi

    stack = list(relations)
    while stack:
        r = stack.pop()
        if isinstance(r, sp.And):
            stack += list(r.args)
            continue
        if not isinstance(r, sp.core.relational.Relational) or r.rel_op not in ("<", "<=", ">", ">="):
            continue
        lhs, rhs = (r.lhs, r.rhs) if r.rel_op in ("<", "<=") else (r.rhs, r.lhs)       # lhs <= rhs
        if lhs.is_Symbol and rhs.is_number:
            put(lhs, hi=rhs)
        elif rhs.is_Symbol and lhs.is_number:
            put(rhs, lo=lhs)
        elif isinstance(lhs, sp.Abs) and lhs.args[0].is_Symbol and rhs.is_number:
            put(lhs.args[0], lo=-rhs, hi=rhs)
    for sym in list(out):
        if sym.is_nonnegative and (out[sym][0] is None or out[sym][0] < 0):
            out[sym][0] = sp.Integer(0)
    return {k: (v[0], v[1]) for k, v in out.items() if v[0] is not None or v[1] is not None}


def chart(ranges: Mapping[sp.Symbol, tuple[Any, Any]]) -> dict[sp.Symbol, sp.Expr]:
    """A change of variables onto non-negative symbols that covers each range: ``x = (lo + hi u)/(1 + u)``
    for ``[lo, hi)``, ``x = lo + u`` for ``[lo, oo)``, ``x = hi - u`` for ``(-oo, hi]`` (``u >= 0``), so
    that the grouped proofs see the signs of ``hi - x`` and ``x - lo``.

    >>> a = sp.Symbol("a", real=True)
    >>> chart({a: (-1, 1)})[a]
    (u_a - 1)/(u_a + 1)
    """
    out = {}
    for sym, (lo, hi) in ranges.items():
        u = sp.Symbol(f"u_{sym.name}", nonnegative=True)
        if lo is not None and hi is not None:
            out[sym] = (lo + hi * u) / (1 + u)
        elif lo is not None:
            out[sym] = lo + u
        else:
            out[sym] = hi - u
    return out
