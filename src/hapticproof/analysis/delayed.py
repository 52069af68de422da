r"""Exact worst cases of the delayed virtual wall (forward difference, HVE paper eqs. 22-27).

With ``theta = wT`` and an integer delay ``n``,

.. math:: \Re G^{-1}(e^{j\theta}) = b - z_a - \frac{KT}{2} - KT \sum_{k=1}^{n} \cos k\theta
          + B \cos((n+1)\theta),

because ``Re[z^{-n}/(z-1)] = -sin((n+1/2)theta)/(2 sin(theta/2)) = -(1/2 + sum_{k=1}^n cos k theta)``
(the Dirichlet kernel, a geometric sum). Hence, for every ``n``:

* ``B = 0``: every ``cos k theta <= 1`` with equality at ``theta -> 0``, so the exact worst case
  is ``b - z_a >= KT/2 + KTn`` (``= KT/2 + K t_d``), attained as ``c -> 1`` — a structural proof;
* ``B >= 0``: ``b - z_a >= KT/2 + KTn + B`` is sufficient (termwise bound), exact for ``n = 0``;
* ``B > 0, n >= 1``: the minimum stays at ``c -> 1`` (so ``b - z_a + B >= KT/2 + KTn`` is exact)
  iff ``B <= kappa_n KT`` with
  ``kappa_n = min_c (n - D_n(c)) / (1 - T_{n+1}(c))`` — computed here to a certified bracket.

>>> small_damping_threshold(1).lo, small_damping_threshold(1).hi
(1/4, 1/4)
"""

from __future__ import annotations

from dataclasses import dataclass

import flint
import sympy as sp

from hapticproof.core.errors import DerivationError
from hapticproof.exact.realroots import as_fmpq, nonnegative_on
from hapticproof.core.symbols import c as C_SYM

__all__ = ["dirichlet_sum", "delayed_wall_hermitian", "check_dirichlet_identity", "Threshold", "small_damping_threshold"]


def dirichlet_sum(n: int) -> flint.fmpq_poly:
    """``D_n(c) = sum_{k=1}^{n} T_k(c)`` (``= sum cos k theta``) as an exact polynomial."""
    total = flint.fmpq_poly([0])
    for k in range(1, n + 1):
        total += flint.fmpq_poly(flint.fmpz_poly.chebyshev_t(k))
    return total


def delayed_wall_hermitian(n: int, b, K, T, B, z_a=0) -> sp.Expr:
    """The closed form above as a SymPy expression in ``c`` (for integer ``n``)."""
    D = sum((sp.chebyshevt(k, C_SYM) for k in range(1, n + 1)), sp.Integer(0))
    return sp.expand(b - z_a - K * T / 2 - K * T * D + B * sp.chebyshevt(n + 1, C_SYM))


def check_dirichlet_identity(n_max: int = 30) -> int:
    """Verify the closed form against the toolkit's exact Hermitian part of
    ``b - z_a + z^{-n}(K + B(z-1)/(Tz)) T/(z-1)`` for ``n = 0..n_max``; returns the number of
    instances (raises ``AssertionError`` on a mismatch).

    ``G^{-1}`` is affine in ``(b - z_a, K, B)`` for fixed ``T`` and ``T`` enters only through
    ``KT`` (``B(z-1)/(Tz) * T/(z-1) = B/z``), so exact agreement at the points
    ``(b, K, B) = (1, 0, 0), (0, 1, 0), (0, 0, 1)`` with two values of ``T`` proves the identity
    for all parameters; the comparison runs on exact flint polynomials.

    >>> check_dirichlet_identity(5)
    6
    """
    from hapticproof.analysis.positivereal import hermitian
    from hapticproof.systems.singleuser import SingleUserScene

    points = [(1, 0, 0, 1), (0, 1, 0, 1), (0, 0, 1, 1), (0, 1, 0, sp.Rational(1, 3)), (0, 0, 1, sp.Rational(1, 3))]
    for n in range(n_max + 1):
        for b, K, B, T in points:
            form = hermitian(SingleUserScene.virtual_wall(K=K, B=B, b=b, T=T, delay=n)).numeric()
            kt = as_fmpq(K * T)
            expected = flint.fmpq_poly([b - kt / 2]) - kt * dirichlet_sum(n) \
                + B * flint.fmpq_poly(flint.fmpz_poly.chebyshev_t(n + 1))
            if form.num != expected * form.den:
                raise DerivationError(f"the closed form of the delay-{n} Hermitian part does not match")
    return n_max + 1


@dataclass(frozen=True, slots=True)
class Threshold:
    """A certified bracket ``lo <= kappa_n <= hi``: ``B = lo*KT`` keeps the worst case at
    ``c -> 1`` (proved), ``B`` above ``hi*KT`` does not (witness ``c``)."""

    n: int
    lo: sp.Rational
    hi: sp.Rational
    witness_c: sp.Rational | None


def _keeps_minimum_at_one(n: int, kappa: flint.fmpq):
    """Is ``(n - D_n(c)) - kappa (1 - T_{n+1}(c)) >= 0`` on [-1, 1]?"""
    p = flint.fmpq_poly([n]) - dirichlet_sum(n) - kappa * (
        flint.fmpq_poly([1]) - flint.fmpq_poly(flint.fmpz_poly.chebyshev_t(n + 1))
    )
    return nonnegative_on(p, -1, 1)


def small_damping_threshold(n: int, bits: int = 40) -> Threshold:
    """Certified bracket of ``kappa_n`` (``n >= 1``) to ``2**-bits``.

    The limit ``c -> 1`` of the ratio is ``sum k^2/(n+1)^2 = n(2n+1)/(6(n+1))``, an upper
    bound; bisection with exact non-negativity decisions closes the bracket, and a rational
    value that is exactly the threshold is recognised.
    """
    if n < 1:
        raise ValueError("n must be >= 1 (for n = 0 every B > 0 moves the minimum to c = -1)")
    hi = flint.fmpq(n * (2 * n + 1), 6 * (n + 1))
    witness = None
    if _keeps_minimum_at_one(n, hi).holds:
        return Threshold(n, sp.Rational(int(hi.p), int(hi.q)), sp.Rational(int(hi.p), int(hi.q)), None)
    lo = flint.fmpq(0)
    width = flint.fmpq(1, 2**bits)
    while hi - lo > width:
        mid = (lo + hi) / 2
        result = _keeps_minimum_at_one(n, mid)
        if result.holds:
            lo = mid
        else:
            hi, witness = mid, result.witness
    return Threshold(n, sp.Rational(int(lo.p), int(lo.q)), sp.Rational(int(hi.p), int(hi.q)), witness)


