r"""The small-gain route to the sampled-data condition (HVE paper Section 3.1.2, after Colgate &
Schenkel): derived objects and the identities that connect them.

* The operator-plus-device admittance ``Y = 1/(ms + b + Z_h)`` with ``Z_h + ms`` having real part
  ``>= -z_a`` lies in the disk ``R_1`` with diameter ``[0, 1/(b - z_a)]`` (the Möbius image of the
  half-plane ``Re p >= 0`` under ``p -> 1/(beta + p)``, ``beta = b - z_a > 0``):
  ``|beta + p|^2 - |beta - p|^2 = 4 beta Re p``.
* ``G_T^*(jw) = -(1 - e^{-jwT})/T * sum_k Y_k/(w + k w_s)^2`` is a convex combination of points
  of ``R_1`` scaled by ``sum_k 1/(w + k w_s)^2 = T^2 / (2(1 - cos wT))`` (partial fractions of
  ``csc^2``), hence in ``r(jw) R_1`` with ``r(jw) = e^{-jw t_d} (T/2)(e^{-jwT} - 1)/(1 - cos wT)``.
* ``M = -1 + 2 beta G/r`` maps ``r R_1`` onto the closed unit disk, and solving
  ``1 + M N = 0 <=> 1 + H G = 0`` gives ``N = rH/(2 beta + rH)``.
* ``|N| < 1 <=> beta + Re(rH) > 0`` because ``|2 beta + w|^2 - |w|^2 = 4 beta (beta + Re w)``;
  and since ``1/(z - 1) = -(1 - z^{-1})/(2(1 - cos wT))`` on ``|z| = 1``, ``beta + Re(rH)`` is
  exactly the forward-difference Hermitian part ``Re G^{-1}`` with ``b - z_a``: the two methods of
  the paper give the same condition at every frequency.

>>> import sympy as sp
>>> w, T, t_d = sp.symbols('omega T t_d', positive=True)
>>> sp.simplify(region_factor(w, T, t_d) - sp.exp(-sp.I*w*t_d)*T/2*(sp.exp(-sp.I*w*T) - 1)/(1 - sp.cos(w*T)))
0
"""

from __future__ import annotations

import mpmath
import sympy as sp

__all__ = [
    "weights_sum",
    "check_weights_sum",
    "region_factor",
    "disk_map",
    "lft_partner",
    "small_gain_margin",
    "disk_identity",
]


def weights_sum(omega: sp.Expr, T: sp.Expr) -> sp.Expr:
    """``sum_k 1/(w + 2 pi k/T)^2 = T^2/(2(1 - cos wT))`` (closed form)."""
    return T**2 / (2 * (1 - sp.cos(omega * T)))


def check_weights_sum(points: int = 5, digits: int = 30) -> float:
    """Compare the closed form with a direct mpmath sum (Richardson-accelerated) at ``points``
    frequencies; returns the largest relative difference.

    >>> check_weights_sum(3) < 1e-20
    True
    """
    worst = 0.0
    with mpmath.workdps(digits):
        for k in range(1, points + 1):
            T = mpmath.mpf(1) / (k + 2)
            w = mpmath.mpf(k) / 3
            ws = 2 * mpmath.pi / T
            direct = mpmath.nsum(lambda j: 1 / (w + j * ws) ** 2, [-mpmath.inf, mpmath.inf])
            closed = T**2 / (2 * (1 - mpmath.cos(w * T)))
            worst = max(worst, float(abs(direct - closed) / closed))
    return worst


def region_factor(omega: sp.Expr, T: sp.Expr, t_d: sp.Expr) -> sp.Expr:
    """``r(jw)``: ``G_T^*(jw) in r(jw) R_1`` (the delay ``e^{-jw t_d}`` included)."""
    j = sp.I
    return -sp.exp(-j * omega * t_d) * (1 - sp.exp(-j * omega * T)) / T * weights_sum(omega, T)


def disk_map(G: sp.Expr, r: sp.Expr, beta: sp.Expr) -> sp.Expr:
    """``M = (G/r - rho)/rho`` with ``rho = 1/(2 beta)``: the affine map of ``r R_1`` onto the
    unit disk (centre ``r rho``, radius ``|r| rho``)."""
    rho = 1 / (2 * beta)
    return sp.simplify((G / r - rho) / rho)


def lft_partner(M_of_G: sp.Expr, G: sp.Symbol, H: sp.Expr) -> sp.Expr:
    """``N`` such that ``1 + M N`` vanishes exactly where ``1 + H G`` does: solve
    ``M = M(G)`` for ``G`` and substitute into ``1 + H G = 0 <=> 1 + M N = 0``."""
    M = sp.Symbol("M_")
    (G_of_M,) = sp.solve(sp.Eq(M, M_of_G), G)
    # 1 + H G(M) = A + B M  =>  1 + (B/A) M = 0
    expanded = sp.expand(1 + H * G_of_M)
    A = expanded.subs(M, 0)
    B = sp.expand(expanded - A).coeff(M)
    return sp.simplify(B / A)


def small_gain_margin(beta: sp.Expr, w: sp.Expr) -> sp.Expr:
    """``|2 beta + w|^2 - |w|^2``, which equals ``4 beta (beta + Re w)`` (so ``|w/(2 beta + w)| < 1``
    iff ``beta + Re w > 0`` for ``beta > 0``)."""
    return sp.expand(sp.Abs(2 * beta + w) ** 2 - sp.Abs(w) ** 2)


def disk_identity() -> sp.Expr:
    """``|beta + p|^2 - |beta - p|^2 - 4 beta Re p`` for real ``beta`` and complex ``p`` (zero)."""
    beta = sp.Symbol("beta", real=True)
    x, y = sp.symbols("x y", real=True)
    p = x + sp.I * y
    return sp.expand(sp.Abs(beta + p) ** 2 - sp.Abs(beta - p) ** 2 - 4 * beta * sp.re(p))
