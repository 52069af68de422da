r"""Continuous designs made discrete, exactly: ``C(s) -> C(z)`` for a sampling period ``T``.

A designer writes a controller or virtual environment in ``s`` -- PD ``K + B*s``, PID with a
filtered derivative ``K + K_i/s + K_d*s/(tau*s + 1)``, a lead-lag ``K*(s + a)/(s + p)`` -- and
chooses how it is implemented:

========== ====================================================================================
forward    ``s = (z - 1)/T`` (forward Euler)
backward   ``s = (z - 1)/(T z)`` (backward Euler; the papers' PD ``K + B(z-1)/(Tz)``)
tustin     ``s = 2(z - 1)/(T(z + 1))`` (bilinear)
zoh        step invariance ``C(z) = (1 - z^{-1}) Z{C(s)/s}`` (proper ``C`` only)
matched    poles and finite zeros ``s_i -> e^{s_i T}``; zeros at infinity -> ``z = -1``
           (Franklin, Powell & Workman, *Digital Control*, Sec. 6.3.3); a pole excess of an
           improper ``C`` (PD) is placed at ``z = 0``; the gain matches the lowest-order term
           of the expansion at ``s = 0`` <-> ``z = 1`` (the DC gain when finite)
========== ====================================================================================

The three substitutions are exact rational maps. ZOH and matched bring ``e^{s_i T}``: exact
SymPy numbers, transcendental unless ``s_i = 0`` (they are shown as they are; an exact
passivity decision needs rational coefficients, see :func:`is_rational`). The tests compare
forward/backward/Tustin with :mod:`sympy.physics.control` (``forward_diff``,
``backward_diff``, ``bilinear``) and ZOH with SciPy's ``cont2discrete``; matched keeps ZOH's
poles and the continuous DC gain.

>>> from hapticproof.core.expr import read_expression
>>> pd = read_expression("K + B*s", "s")
>>> discretize(pd, "backward")
B*(z - 1)/(T*z) + K
>>> discretize(read_expression("K + K_i/s", "s"), "tustin")
K + K_i*T*(z + 1)/(2*(z - 1))
>>> discretize(read_expression("1/(s + 2)", "s"), "zoh", T=1)
-(1 - exp(2))*exp(-2)/(2*(z - exp(-2)))
"""

from __future__ import annotations

from typing import Any

import sympy as sp

from hapticproof.core.errors import SceneError
from hapticproof.core.symbols import s as S_SYM
from hapticproof.core.symbols import z as Z_SYM
from hapticproof.systems.choices import METHODS  # the methods, in the order of the table above

__all__ = ["METHODS", "discretize", "is_rational", "split_improper"]


_T = sp.Symbol("T", positive=True)


def _check(expr: Any, method: str) -> sp.Expr:
    if method not in METHODS:
        raise SceneError(f"unknown discretisation {method!r}; choose one of {', '.join(METHODS)}")
    expr = sp.sympify(expr)
    if Z_SYM in expr.free_symbols:
        raise SceneError(f"the continuous design must be an expression in s, not z: {sp.sstr(expr)}")
    if not expr.is_rational_function(S_SYM):
        raise SceneError(f"the continuous design must be a rational function of s: {sp.sstr(expr)}")
    return expr


def _tidy(expr: sp.Expr) -> sp.Expr:
    """Each term of a partial sum over a common denominator in z (readable, exact)."""
    return sp.Add(*[sp.factor(sp.together(t)) if t.has(Z_SYM) else t for t in sp.Add.make_args(sp.expand(expr, deep=False))])


def discretize(expr: Any, method: str, T: Any = _T) -> sp.Expr:
    """``C(z)`` of a continuous ``C(s)`` by ``method`` (one of :data:`METHODS`), exact.

    >>> from hapticproof.core.expr import read_expression
    >>> discretize(read_expression("1 + s", "s"), "matched", T=sp.Rational(1, 10))
    -(z - exp(-1/10))*exp(1/10)/(z*(1 - exp(1/10)))
    """
    expr = _check(expr, method)
    T = sp.sympify(T)
    if method in ("forward", "backward", "tustin"):
        image = {"forward": (Z_SYM - 1) / T, "backward": (Z_SYM - 1) / (T * Z_SYM),
                 "tustin": 2 * (Z_SYM - 1) / (T * (Z_SYM + 1))}[method]
        parts = [t.subs(S_SYM, image) for t in sp.Add.make_args(sp.expand(expr))]
        if method == "forward" or len(parts) > 1:
            return _combine_like(parts)
        return parts[0]
    if method == "zoh":
        return _zoh(expr, T)
    return _matched(expr, T)


def _combine_like(parts: list[sp.Expr]) -> sp.Expr:
    """Sum of the substituted terms, terms sharing a denominator collected (``K + B(z-1)/(Tz)``)."""
    groups: dict[sp.Expr, list[sp.Expr]] = {}
    for part in parts:
        num, den = sp.fraction(sp.together(part))
        key = sp.factor(den) if den.has(Z_SYM) else sp.Integer(1)
        groups.setdefault(key, []).append(sp.factor(num) / (den / key) if den.has(Z_SYM) else part)
    out = sp.Integer(0)
    for den, nums in groups.items():
        total = sp.Add(*nums)
        out += sp.factor(total) / den if den != 1 else total
    return out


def split_improper(expr: Any, s: sp.Symbol = S_SYM) -> tuple[sp.Expr, sp.Expr]:
    """``C = polynomial part + strictly proper part`` (exact, ``sp.div`` of the fraction).

    >>> split_improper(sp.Integer(3) + 2*S_SYM + 1/(S_SYM + 1))
    (2*s + 3, 1/(s + 1))
    """
    num, den = sp.fraction(sp.cancel(sp.together(sp.sympify(expr))))
    q, r = sp.div(sp.Poly(num, s), sp.Poly(den, s))
    return q.as_expr(), sp.cancel(r.as_expr() / den)


def _poles(den: sp.Poly) -> dict[sp.Expr, int]:
    roots = sp.roots(den)
    if sum(roots.values()) != den.degree():
        raise SceneError(f"the poles of the continuous design are not available in closed form ({den.as_expr()})")
    return roots


def _laurent_terms(F: sp.Expr, s: sp.Symbol) -> list[tuple[sp.Expr, int, sp.Expr]]:
    """Partial fractions ``F = sum c/(s - p)^k`` of a strictly proper rational ``F``: ``(p, k, c)``."""
    _, den = sp.fraction(sp.cancel(sp.together(F)))
    den_poly = sp.Poly(den, s)
    out = []
    for p, mult in _poles(den_poly).items():
        rest = sp.cancel(F * (s - p) ** mult)
        for k in range(mult, 0, -1):
            order = mult - k
            coeff = sp.diff(rest, s, order).subs(s, p) / sp.factorial(order) if order else rest.subs(s, p)
            coeff = sp.simplify(coeff)
            if coeff != 0:
                out.append((p, k, coeff))
    return out


def _z_of_pole(p: sp.Expr, k: int, T: sp.Expr) -> sp.Expr:
    """``Z{t^(k-1) e^(p t)/(k-1)!}`` sampled at ``t = jT``: ``d^(k-1)/dp^(k-1) [z/(z - e^(pT))]/(k-1)!``."""
    q = sp.Dummy("q")
    base = Z_SYM / (Z_SYM - sp.exp(q * T))
    return sp.simplify((sp.diff(base, q, k - 1) / sp.factorial(k - 1)).subs(q, p))


def _zoh(expr: sp.Expr, T: sp.Expr) -> sp.Expr:
    polynomial, proper = split_improper(expr)
    if sp.Poly(polynomial, S_SYM).degree() > 0:
        raise SceneError(f"ZOH needs a proper C(s) (no pure derivative): {sp.sstr(expr)}; filter the derivative "
                         "(K_d*s/(tau*s + 1)) or use forward, backward, tustin or matched")
    total = sp.Integer(0)
    for p, k, coeff in _laurent_terms(proper / S_SYM + polynomial / S_SYM, S_SYM):
        total += coeff * _z_of_pole(p, k, T)
    result = sp.cancel(sp.together((1 - 1 / Z_SYM) * total))
    return _tidy_exp(result)


def _tidy_exp(expr: sp.Expr) -> sp.Expr:
    """``num(z)/den(z)`` with a monic denominator and simplified coefficients."""
    num, den = sp.fraction(sp.cancel(sp.together(expr)))
    pn, pd = sp.Poly(num, Z_SYM), sp.Poly(den, Z_SYM)
    lead = pd.LC()
    tidy = lambda poly: sum((sp.simplify(c / lead) * Z_SYM**k  # noqa: E731
                             for (k,), c in poly.terms()), sp.Integer(0))
    numerator, denominator = tidy(pn), tidy(pd)
    return numerator / denominator


def _matched(expr: sp.Expr, T: sp.Expr) -> sp.Expr:
    num, den = sp.fraction(sp.cancel(sp.together(expr)))
    pn, pd = sp.Poly(num, S_SYM), sp.Poly(den, S_SYM)
    zeros = _poles(pn) if pn.degree() > 0 else {}
    poles = _poles(pd) if pd.degree() > 0 else {}
    excess = pd.degree() - pn.degree()          # zeros at infinity (> 0) or missing poles (< 0)
    order = zeros.get(sp.Integer(0), 0) - poles.get(sp.Integer(0), 0)
    zrest, prest = sp.Integer(1), sp.Integer(1)
    for q, mult in zeros.items():
        if q != 0:
            zrest *= (Z_SYM - sp.exp(q * T)) ** mult
    for p, mult in poles.items():
        if p != 0:
            prest *= (Z_SYM - sp.exp(p * T)) ** mult
    if excess > 0:
        zrest *= (Z_SYM + 1) ** excess
    elif excess < 0:
        prest *= Z_SYM ** (-excess)
    # the lowest-order term at s = 0: C(s) ~ lead s^order; C(z) ~ g (z-1)^order zrest(1)/prest(1)
    # with z - 1 ~ sT
    n0 = sp.Poly(num, S_SYM).as_expr() / S_SYM ** max(order, 0) if order > 0 else num
    d0 = sp.Poly(den, S_SYM).as_expr() / S_SYM ** max(-order, 0) if order < 0 else den
    lead = sp.cancel(n0).subs(S_SYM, 0) / sp.cancel(d0).subs(S_SYM, 0)
    shape = zrest.subs(Z_SYM, 1) / prest.subs(Z_SYM, 1)
    if shape == 0:
        raise SceneError(f"matched: cannot match the gain of {sp.sstr(expr)} at s = 0")
    gain = sp.simplify(lead / (T**order * shape))
    return gain * (Z_SYM - 1) ** order * zrest / prest


def is_rational(expr: Any, variable: sp.Symbol = Z_SYM) -> bool:
    """True when ``expr`` is a rational function of ``variable`` with rational-function
    coefficients in the parameters (no ``e^{pT}`` of ZOH or matched with numeric poles).

    >>> is_rational(sp.exp(-sp.Rational(1, 2)) / Z_SYM), is_rational(1 / (Z_SYM - sp.Rational(1, 2)))
    (False, True)
    >>> is_rational(sp.sin(sp.Rational(1, 10**9)) * (Z_SYM - 1) / (Z_SYM**2 + 1))        # ZOH of a resonator
    False
    """
    expr = sp.sympify(expr)
    # no e^{pT}, nor the sin/cos of a ZOH of resonant poles, no pi, E or j among the coefficients
    return not expr.has(sp.exp) and not expr.has(sp.Float) and not expr.atoms(sp.Function) and \
        not expr.atoms(sp.NumberSymbol) and not expr.has(sp.I) and expr.is_rational_function(variable) and \
        all(a.is_Rational for a in expr.atoms(sp.Number))
