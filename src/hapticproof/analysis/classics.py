r"""Classic sampled-data haptic conditions, derived by the toolkit from their models.

Each classic result is *derived* here from the model it is about and kept next to its
published statement (:class:`Source`), so that any printed condition can be compared with the
literature (``derivations/classics.py`` audits the published statements against these
derivations).

**Colgate & Schenkel (1997).** A 1-DOF display with physical damping ``b``, sampler, ZOH and a
discrete environment ``H(z)`` is passive iff

.. math:: b \ge \frac{T}{2}\,\frac{1}{1 - \cos\omega T}\,\Re\{(1 - e^{-j\omega T}) H(e^{j\omega T})\}
          \quad \forall\, \omega \in (0, \pi/T),

which for the virtual wall ``H(z) = K + B(z-1)/(Tz)`` is ``b > KT/2 + |B|``. The right-hand
side is an exact rational function of ``c = cos(wT)`` (:func:`colgate_bound`). It is derived
independently by :func:`leak_bound` from the sampled model: the ZOH of the impulse sampler is
the Laplace transform of the unit pulse (:func:`zoh_transfer`), which gives the energy-leak
kernel ``C(w) = -(1 - e^{-jwT}) H/T`` of the sampled force, and the alias sum
``sum_n 1/(w + n w_s)^2 = T^2/(2(1 - c))`` (:func:`alias_weight`, checked with mpmath) bounds the
aliased energy by Cauchy-Schwarz. The same chain gives the teleoperator bounds
(:mod:`hapticproof.analysis.teleoperator`).

**Gil, Avello, Rubio & Florez (2004).** Closed-loop stability of the device on the wall by
Routh-Hurwitz / Jury: the exact characteristic polynomial and boundary live in
:mod:`hapticproof.analysis.boundary`; :func:`leading_order_boundary` expands the exact polynomial on the
unit circle in the small-damping limit ``alpha, delta, beta -> 0`` (``theta ~ sqrt(beta)``) and
finds the crossing ``beta* = 2(alpha + delta)/(2n + 1) + ...``, i.e. Gil's
``b + B > KT/2`` (``n = 0``) and **Gil, Sanchez, Hulin, Preusche & Hirzinger (2009)**'s delayed
linear condition ``K(T/2 + t_d) < b + B`` (any ``n``; a continuous operator spring ``k_h``
drops out at this order, which is what Minsky et al.'s condition with an operator is compared
with). :func:`gil_sufficiency_region` gives the exact region of ``(alpha, delta)`` where the
linear condition is sufficient (to first order: ``B <= b/6``).

>>> import sympy as sp
>>> from hapticproof.systems.singleuser import SYMBOLS, virtual_wall
>>> K, B, T = SYMBOLS["K"], SYMBOLS["B"], SYMBOLS["T"]
>>> sp.expand(colgate_bound(virtual_wall(K, B, T), T))
-B*c + K*T/2
>>> colgate_wall()
b >= K*T/2 + Abs(B)
"""

from __future__ import annotations

from dataclasses import dataclass
from functools import lru_cache
from typing import Any

import mpmath
import sympy as sp

from hapticproof.exact.canonical import cancel as exact_cancel
from hapticproof.core.errors import DerivationError
from hapticproof.systems.singleuser import SYMBOLS
from hapticproof.core.symbols import c as C_SYM
from hapticproof.core.symbols import z as Z_SYM
from hapticproof.exact.unitcircle import hermitian_part

__all__ = [
    "Source",
    "COLGATE_SCHENKEL_1997",
    "GIL_2004",
    "GIL_2009",
    "MINSKY_1990",
    "LLEWELLYN_1952",
    "SOURCES",
    "colgate_bound",
    "zoh_transfer",
    "sampling_kernel",
    "alias_weight",
    "check_alias_weight",
    "leak_bound",
    "colgate_wall",
    "LeadingOrder",
    "leading_order_boundary",
    "gil_linear_condition",
    "gil_sufficiency_region",
    "OPERATOR",
]

K, B, b, T, t_d = (SYMBOLS[name] for name in ("K", "B", "b", "T", "t_d"))
#: Operator mass, damping and stiffness (Minsky et al., HVE paper eq. 2).
OPERATOR = {name: sp.Symbol(name, positive=True) for name in ("m_h", "b_h", "k_h")}


@dataclass(frozen=True, slots=True)
class Source:
    """A published classic result: who, where, and the statement as published (LaTeX).

    ``equation`` is the equation number in the source when it was checked against the
    publication; ``None`` when the statement is recorded from its standard citation (the full
    text was not available offline), which ``note`` says.
    """

    key: str
    authors: str
    title: str
    venue: str
    year: int
    statement: str
    equation: str | None = None
    note: str = ""

    def __str__(self) -> str:
        return f"{self.authors}, '{self.title}', {self.venue}, {self.year}"

    def citation(self) -> str:
        """One-line citation (with the equation number when known)."""
        where = f", eq. ({self.equation})" if self.equation else ""
        return f"{self}{where}"


#: Colgate's passivity condition (frequency form; the virtual-wall form is ``b > KT/2 + |B|``).
COLGATE_SCHENKEL_1997 = Source(
    "colgate-schenkel-1997",
    "J. E. Colgate and G. G. Schenkel",
    "Passivity of a class of sampled-data systems: application to haptic interfaces",
    "Journal of Robotic Systems 14(1):37-47",
    1997,
    r"b > \frac{T}{2}\frac{1}{1-\cos\omega T}\operatorname{Re}\{(1-e^{-j\omega T})H(e^{j\omega T})\}",
    note="for 0 < omega < pi/T; virtual-wall form b > KT/2 + |B|; statements recorded from the standard citation "
    "(HVE [3], teleoperator [7])",
)
#: Gil et al.'s Routh-Hurwitz small-damping stability condition.
GIL_2004 = Source(
    "gil-2004",
    "J. J. Gil, A. Avello, A. Rubio and J. Florez",
    "Stability analysis of a 1 DOF haptic interface using the Routh-Hurwitz criterion",
    "IEEE Transactions on Control Systems Technology 12(4):583-588",
    2004,
    r"b > \frac{KT}{2} - B",
    note="valid for small virtual damping (as quoted by HVE eq. 4 and the teleoperator paper's introduction); "
    "normalised parameters alpha = bT/m, delta = BT/m, beta = KT^2/m",
)
#: Gil et al.'s delayed linear condition.
GIL_2009 = Source(
    "gil-2009",
    "J. J. Gil, E. Sanchez, T. Hulin, C. Preusche and G. Hirzinger",
    "Stability boundary for haptic rendering: influence of damping and delay",
    "ASME Journal of Computing and Information Science in Engineering 9(1):011005 (also ICRA 2007)",
    2009,
    r"K < \frac{b + B}{\frac{T}{2} + t_d}",
    note="the 'linear condition' under short delays, fast sampling and low damping (abstract); HVE eq. 5 quotes it",
)
#: Minsky et al.'s condition with an operator, as quoted by the HVE paper.
MINSKY_1990 = Source(
    "minsky-1990",
    "M. Minsky, M. Ouh-young, O. Steele, F. P. Brooks Jr. and M. Behensky",
    "Feeling and seeing: issues in force display",
    "Proceedings of the 1990 Symposium on Interactive 3D Graphics (I3D '90), 235-241",
    1990,
    r"B+b+b_h > \frac{(K+k_h)T}{2}",
    note="experimental condition with operator mass m_h, damping b_h and stiffness k_h, as quoted by HVE eq. (2)",
)
#: Llewellyn's absolute-stability criterion for two-ports.
LLEWELLYN_1952 = Source(
    "llewellyn-1952",
    "F. B. Llewellyn",
    "Some fundamental properties of transmission systems",
    "Proceedings of the IRE 40(3):271-283",
    1952,
    r"\operatorname{Re} p_{11} \ge 0, \quad \operatorname{Re} p_{22} \ge 0, \quad "
    r"2\operatorname{Re} p_{11}\operatorname{Re} p_{22} - \operatorname{Re}(p_{12}p_{21}) - |p_{12}p_{21}| \ge 0",
    note="plus: p_11 and p_22 have no poles in the open right half-plane, imaginary-axis poles simple with "
    "positive real residues",
)
SOURCES = {src.key: src for src in (COLGATE_SCHENKEL_1997, GIL_2004, GIL_2009, MINSKY_1990, LLEWELLYN_1952)}


# ---------------------------------------------------------------------------------------------
# Colgate & Schenkel
# ---------------------------------------------------------------------------------------------


def colgate_bound(H: Any, T: Any, z: sp.Symbol = Z_SYM, var: sp.Symbol = C_SYM) -> sp.Expr:
    r"""Colgate & Schenkel's lower bound on ``b`` at frequency ``c = cos(wT)``:
    ``T/(2(1 - c)) Re{(1 - z^{-1}) H(z)}`` on ``|z| = 1`` (an exact rational function of ``c``).

    >>> from hapticproof.core.symbols import z
    >>> colgate_bound(3 + 0*z, sp.Rational(1, 10))          # a pure spring K = 3, T = 0.1
    3/20
    """
    numerator = hermitian_part(sp.sympify(H) * (1 - 1 / z), z, var)
    return exact_cancel(sp.sympify(T) * numerator / (2 * (1 - var)))


@lru_cache(maxsize=4)
def zoh_transfer(s: sp.Symbol = sp.Symbol("s"), T: sp.Symbol = T) -> sp.Expr:
    r"""The zero-order hold of an impulse sampler ``x^* = sum_k x(kT) delta(t - kT)``: the
    Laplace transform of the unit pulse of width ``T`` (derived with SymPy).

    >>> zoh_transfer()
    1/s - exp(-T*s)/s
    """
    t = sp.Symbol("t", positive=True)
    return sp.laplace_transform(sp.Heaviside(t) - sp.Heaviside(t - T), t, s, noconds=True)


def sampling_kernel(H: Any, T: Any = T, z: sp.Symbol = Z_SYM) -> sp.Expr:
    r"""The kernel ``C(w)`` of the sampled force (teleoperator paper eq. 14): with the derived
    ZOH, the force ``F = ZOH(jw) H X^*`` and ``X^* = (1/T) sum_n V(jw + jn w_s)/(jw + jn w_s)``
    give ``int F V^c dw = int C(w) sum_n ... [V/(jw)]^c dw`` with ``C = -jw ZOH(jw) H/T``,
    returned as a function of ``z = e^{jwT}``.

    >>> from hapticproof.core.symbols import z
    >>> sp.factor(sampling_kernel(2, sp.Rational(1, 10)))
    -20*(z - 1)/z
    """
    s = sp.Symbol("s")
    jw_zoh = sp.expand(s * zoh_transfer(s, sp.sympify(T) if not isinstance(T, sp.Symbol) else T))
    # e^{-sT} = 1/z on the unit circle
    in_z = jw_zoh.subs(sp.exp(-sp.sympify(T) * s), 1 / z)
    if in_z.has(s):  # pragma: no cover - the pulse transform is s-free after multiplying by s
        raise ValueError("unexpected ZOH form")
    return exact_cancel(-in_z * sp.sympify(H) / sp.sympify(T))


def alias_weight(T: Any = T, var: sp.Symbol = C_SYM) -> sp.Expr:
    r"""``sum_{n} 1/(w + n w_s)^2 = (T/2)^2 / sin^2(wT/2) = T^2/(2(1 - c))``, ``w_s = 2 pi/T``.

    The partial-fraction expansion of ``pi^2/sin^2(pi x)``; :func:`check_alias_weight` checks it
    against a 30-digit sum at given points.

    >>> alias_weight(1)
    1/(2 - 2*c)
    """
    return sp.sympify(T) ** 2 / (2 * (1 - var))


def check_alias_weight(points: list[tuple[Any, Any]], digits: int = 30) -> float:
    """Largest relative difference between :func:`alias_weight` and ``mpmath.nsum`` of the
    alias series at the given ``(omega, T)`` points (raises nothing; returns the error).

    >>> check_alias_weight([(1, "0.1"), ("0.3", 2)]) < 1e-25
    True
    """
    worst = 0.0
    with mpmath.workdps(digits + 10):
        for omega, period in points:
            w = mpmath.mpf(sp.Rational(omega).p) / sp.Rational(omega).q
            Tm = mpmath.mpf(sp.Rational(period).p) / sp.Rational(period).q
            ws = 2 * mpmath.pi / Tm
            series = mpmath.nsum(lambda k: 1 / (w + k * ws) ** 2, [-mpmath.inf, mpmath.inf])
            closed = Tm**2 / (2 * (1 - mpmath.cos(w * Tm)))
            worst = max(worst, float(abs(series - closed) / closed))
    return worst


def leak_bound(H: Any, T: Any = T, z: sp.Symbol = Z_SYM, var: sp.Symbol = C_SYM) -> sp.Expr:
    r"""Lower bound on the device damping that absorbs the sampled force's energy leak:
    ``-Re C(w) * sum_n 1/(w + n w_s)^2`` with the derived kernel (:func:`sampling_kernel`) and
    alias weight (:func:`alias_weight`); where ``Re C >= 0`` the aliased term is itself
    non-negative and the bound is not needed (it is then <= 0). Equals :func:`colgate_bound`.

    >>> from hapticproof.systems.singleuser import virtual_wall
    >>> sp.expand(leak_bound(virtual_wall(K, B, T)))
    -B*c + K*T/2
    """
    kernel = sampling_kernel(H, T, z)
    return exact_cancel(-hermitian_part(kernel, z, var) * alias_weight(T, var))


def colgate_wall(K: Any = K, B: Any = sp.Symbol("B", real=True), T: Any = T, b: Any = b) -> sp.Basic:
    r"""Colgate's virtual-wall condition derived: the supremum over ``c`` in ``[-1, 1]`` of the
    bound ``KT/2 - Bc`` for a virtual damping ``B`` of either sign (endpoint analysis):
    ``b >= KT/2 + |B|``.

    >>> colgate_wall(B=SYMBOLS["B"])             # B >= 0: the HVE paper's (3)
    b >= B + K*T/2
    """
    from hapticproof.analysis.positivereal import symbolic_minimum
    from hapticproof.systems.singleuser import virtual_wall

    wc = symbolic_minimum(sp.expand(b - leak_bound(virtual_wall(K, B, T), T)))
    cond = wc.condition
    return sp.Ge(b, sp.expand(b - cond.lhs + cond.rhs), evaluate=False) if isinstance(cond, sp.Ge) else cond


# ---------------------------------------------------------------------------------------------
# Gil et al.: small-damping expansion of the exact boundary
# ---------------------------------------------------------------------------------------------


@dataclass(frozen=True, slots=True)
class LeadingOrder:
    r"""Leading order of the exact boundary as ``alpha, delta, beta (, kappa) -> 0``.

    With ``alpha = eps a``, ``delta = eps d``, ``beta = eps g``, operator stiffness
    ``kappa = k_h T^2/M = eps q`` and ``theta = sqrt(eps) w``: ``frequency`` is ``w^2`` at the
    crossing, ``critical`` the critical ``g``; ``condition`` is the stability condition in
    physical symbols (``t_d = nT``; ``b`` includes the operator damping ``b_h`` when present).
    """

    n: Any
    operator: bool
    frequency: sp.Expr
    critical: sp.Expr
    condition: sp.Basic


_A, _D, _G, _Q, _W = sp.symbols("a d g q w", positive=True)
_E = sp.Symbol("epsilon_sqrt", positive=True)


def _truncate(expr: sp.Expr, order: int) -> sp.Expr:
    expr = sp.expand(expr)
    return sp.Add(*[expr.coeff(_E, k) * _E**k for k in range(order + 1)])


def _exp_series(x: sp.Expr, order: int) -> sp.Expr:
    return sp.Add(*[(sp.I * x * _E) ** k / sp.factorial(k) for k in range(order + 1)])


@lru_cache(maxsize=8)
def leading_order_boundary(n: Any = SYMBOLS["n"], operator: bool = False) -> LeadingOrder:
    r"""Expand the exact sampled loop on the unit circle and solve its two lowest orders.

    The ZOH transition matrix ``exp([[0, 1, 0], [-q eps, -a eps, -1], [0, 0, 0]])`` (scaled
    states ``x``, ``T v``; input ``u T^2/M``) is expanded in ``sqrt(eps)`` (the generator is
    nilpotent at ``eps = 0``, so the series is finite at each order), the loop
    ``z^{n+1} det(zI - Phi) = ((g + d) eps z - d eps) N(z)`` is evaluated at
    ``z = e^{j w sqrt(eps)}``, and the real ``eps`` and imaginary ``eps^{3/2}`` coefficients are
    solved for ``w^2`` and ``g``. ``n`` may be a symbol: ``z^{n+1}`` enters through
    ``exp(j (n+1) w sqrt(eps))``, polynomial in ``n`` at each order, so the result holds for
    every integer ``n``.

    >>> lo = leading_order_boundary(0)
    >>> lo.frequency, lo.critical
    (g, 2*a + 2*d)
    >>> leading_order_boundary(operator=True).condition
    B + b + b_h > K*(T/2 + t_d)
    """
    order = 3
    q = _Q if operator else sp.Integer(0)
    X = sp.Matrix([[0, 1, 0], [-q * _E**2, -_A * _E**2, -1], [0, 0, 0]])
    E = sp.eye(3)
    term = sp.eye(3)
    for k in range(1, 2 * order + 2):
        term = (term * X / k).applyfunc(lambda v: _truncate(v, order))
        E += term
    phi, gamma = E[:2, :2], E[:2, 2]
    zs = sp.Symbol("zeta")
    M = zs * sp.eye(2) - phi
    den = M.det()
    num = (M.adjugate() * gamma)[0]
    zval = _exp_series(_W, order)
    poly = _exp_series((sp.sympify(n) + 1) * _W, order) * den.subs(zs, zval) - (
        (_G + _D) * _E**2 * zval - _D * _E**2
    ) * num.subs(zs, zval)
    poly = _truncate(poly, order)
    low, high = sp.expand(poly.coeff(_E, 2)), sp.expand(poly.coeff(_E, 3))
    if sp.im(low) != 0 or sp.re(high) != 0:
        raise DerivationError("the lowest orders of the expansion are not real/imaginary as expected")
    (freq,) = sp.solve(low, _W**2)
    (crit,) = sp.solve(sp.expand(sp.im(high) / _W).subs(_W**2, freq), _G)
    # back to physical symbols: g (2n+1) = 2 (a + d)  <=>  K (T/2 + nT) = b + B  (+ b_h)
    damping = b + OPERATOR["b_h"] if operator else b
    delay = t_d if isinstance(n, sp.Symbol) else sp.sympify(n) * T
    ratio = sp.simplify(crit * (2 * sp.sympify(n) + 1) / (2 * (_A + _D)))
    if ratio != 1:
        raise DerivationError(f"unexpected leading order {crit}")
    condition = sp.Gt(damping + B, K * (T / 2 + delay), evaluate=False)
    return LeadingOrder(n, operator, freq, crit, condition)


@lru_cache(maxsize=8)
def gil_linear_condition(n: Any = 0) -> sp.Basic:
    """The linear condition in physical symbols, from :func:`leading_order_boundary`:
    ``b + B > KT/2`` (Gil et al. 2004) for ``n = 0``, ``b + B > K(T/2 + t_d)`` (Gil et al. 2009)
    for a symbolic delay.

    >>> gil_linear_condition(0)
    B + b > K*T/2
    """
    lo = leading_order_boundary(n)
    return sp.Gt(lo.condition.lhs, sp.expand(lo.condition.rhs), evaluate=False)


@lru_cache(maxsize=1)
def gil_sufficiency_region() -> tuple[sp.Basic, sp.Expr]:
    r"""Where the linear condition ``beta < 2(alpha + delta)`` is sufficient for stability
    (``n = 0``): the exact region ``2(alpha + delta) <= min(complex, flip)``, ``lower <= 0`` and
    ``delta l_0 < alpha^2`` in ``(alpha, delta, p = e^{-alpha})``, and the first-order
    expansion of ``beta*/(2(alpha + delta))`` (``1 + alpha/6 - delta + ...``: sufficient to
    first order iff ``delta <= alpha/6``, i.e. ``B <= b/6``).

    >>> region, expansion = gil_sufficiency_region()
    >>> expansion
    alpha/6 - delta + 1
    """
    from hapticproof.analysis.boundary import ALPHA, DELTA, P, closed_form_boundary

    cf = closed_form_boundary()
    linear = 2 * (ALPHA + DELTA)
    region = sp.And(sp.Le(linear, cf.complex_pair), sp.Le(linear, cf.flip), sp.Le(cf.lower, 0), sp.Gt(cf.damping, 0))
    eps = sp.Symbol("eps", positive=True)
    # p = e^{-alpha} by its Taylor polynomial (enough terms for two orders of the ratio)
    taylor = sp.Add(*[(-eps * ALPHA) ** k / sp.factorial(k) for k in range(8)])
    ratio = exact_cancel((cf.complex_pair / linear).subs({ALPHA: eps * ALPHA, DELTA: eps * DELTA}).subs(P, taylor))
    num, den = (sp.Poly(part, eps) for part in sp.fraction(ratio))
    low = min(min(m[0] for m in num.monoms()), min(m[0] for m in den.monoms()))
    n0, n1 = num.coeff_monomial(eps**low), num.coeff_monomial(eps ** (low + 1))
    d0, d1 = den.coeff_monomial(eps**low), den.coeff_monomial(eps ** (low + 1))
    expansion = sp.expand(exact_cancel(n0 / d0 + (n1 * d0 - n0 * d1) / d0**2))
    return region, expansion
