r"""Stability of sampled-data haptic loops from the definition, with rigorous bounds: the roots of
the exact characteristic polynomial of the sample-to-sample map (no code of the package under test).

Every device obeys ``m_i dv_i/dt = -b_i v_i - u_i`` between samples, ``u_i`` the force held by
a zero-order hold. The controller is the HVE paper's (Fig. 6/7, eqs. 37-39) in a general form
``u_i[k] = sum_j Kmat_ij x_j[k - n_ij] + Bmat_ij (x_j[k - n_ij] - x_j[k - n_ij - 1]) / T``: a
single user is ``Kmat = (K)``, ``Bmat = (B)``, ``n = (n)``; m users have ``Kmat = diag(K_0) +
L_K``, ``Bmat = diag(B_0) + L_B`` (``L`` the weighted Laplacians of the couplings), ``n_ij =
n_i``; the PEB teleoperator with ``e = alpha x_m - x_s`` and ``C(z) = K + B(z-1)/(Tz)`` is
``Kmat = K [[alpha^2, -alpha], [-alpha, 1]]``, ``Bmat`` likewise with ``B`` (teleoperator paper
(6), (7)), a communication delay on the remote position only (``n = [[0, n], [n, 0]]``).

How it is decided (the loop is asymptotically stable iff every eigenvalue is strictly inside the
unit circle; ``rho = 1`` is *not* stable):

* the one-sample map of a device is written in closed form (``p = e^{-b T / m}``; ``b = 0`` is
  the exact limit), in interval arithmetic (``mpmath.iv``), or in exact rationals when every
  ``b_i = 0``;
* the characteristic polynomial of the whole map by Berkowitz's division-free algorithm in the
  same arithmetic (every coefficient an interval that certainly holds the exact one);
* ``z = 1``: a fixed state is at rest (``v = 0``), with every past position equal to the current
  one and no force, ``Kmat x = 0``: the exact multiplicity of the eigenvalue 1 is at least ``d =
  dim ker Kmat`` (computed over Q), and ``(z - 1)^d`` is divided out of the polynomial;
* the rest by the Schur-Cohn test in Marden's form: with ``f_0 = f``, ``f_{j+1} = a_0 f_j -
  a_top f_j^*`` and ``delta_j`` the constant term of ``f_j``, if no product ``P_k = delta_1 ...
  delta_k`` is zero, ``f`` has no root on the circle and as many inside as there are negative
  ``P_k`` (Marden, *Geometry of polynomials*, Thm. 43.1). A ``delta`` whose interval holds 0
  doubles the precision, then gives up (``uncertain``).

>>> r = loop_stability([1], [1], "1/10", [[1]], [[0]], [[0]])
>>> r.verdict, r.details["kind"]
('yes', 'stable')
>>> r = loop_stability([1], [1], "1/10", [[0]], [[0]], [[0]])        # K = 0: z = 1 exactly
>>> r.verdict, r.details["kind"], r.details["at_one"]
('no', 'marginal', 1)
>>> loop_stability([1], [0], "1/10", [[0]], [[0]], [[0]]).details["kind"]   # a free mass: Jordan block
'unstable'
"""

from __future__ import annotations

from fractions import Fraction
from typing import Any

import mpmath

from .result import NO, UNCERTAIN, YES, OracleResult

__all__ = ["loop_stability", "characteristic_polynomial", "inside_count", "kernel_dimension",
           "multi_user_matrices", "uniform_matrices", "teleoperator_matrices"]

#: Working precision of the interval arithmetic (bits), doubled on an undecided sign up to ``MAX_BITS``.
BITS, MAX_BITS = 256, 2048


class _Exact:
    """Exact rational arithmetic (every ``b_i = 0``)."""

    def num(self, q: Fraction) -> Fraction:
        return Fraction(q)

    def sign(self, v: Fraction) -> int | None:
        return (v > 0) - (v < 0) if v != 0 else None


class _Interval:
    """``mpmath.iv`` intervals at the current precision: an entry holds the exact number."""

    def num(self, q: Fraction) -> Any:
        q = Fraction(q)
        return mpmath.iv.mpf(q.numerator) / q.denominator

    def sign(self, v: Any) -> int | None:
        if v.a > 0:
            return 1
        if v.b < 0:
            return -1
        return None


def _device(ar: Any, m: Fraction, b: Fraction, T: Fraction) -> tuple[list, list]:
    """``[x; v] -> [x; v]`` and the force column of one device over one period (closed form)."""
    if b == 0:
        return ([[ar.num(1), ar.num(T)], [ar.num(0), ar.num(1)]], [ar.num(-T * T / (2 * m)), ar.num(-T / m)])
    p = mpmath.iv.exp(ar.num(-b * T / m))
    one_minus = 1 - p
    return ([[ar.num(1), ar.num(m / b) * one_minus], [ar.num(0), p]],
            [-(ar.num(T / b) - ar.num(m / (b * b)) * one_minus), -(one_minus / ar.num(b))])


def closed_loop(ar: Any, masses: list, dampings: list, T: Any, Kmat: list, Bmat: list, delays: list) -> list:
    """The sample-to-sample matrix over ``[x_1, v_1, ..., x_m, v_m, x[k-1], ..., x[k-N-1]]``
    (each past block one position per user, ``N`` the largest delay)."""
    users = len(masses)
    T = Fraction(T)
    N = max(max(row) for row in delays)
    n = 2 * users
    size = n + users * (N + 1)
    zero = ar.num(0)

    def position(j: int, lag: int) -> int:
        return 2 * j if lag == 0 else n + (lag - 1) * users + j

    # the held force u_i as a row over the state
    U = [[zero] * size for _ in range(users)]
    for i in range(users):
        for j in range(users):
            k, b, lag = Fraction(Kmat[i][j]), Fraction(Bmat[i][j]), int(delays[i][j])
            if k == 0 and b == 0:
                continue
            U[i][position(j, lag)] = U[i][position(j, lag)] + ar.num(k + b / T)
            U[i][position(j, lag + 1)] = U[i][position(j, lag + 1)] - ar.num(b / T)
    M = [[zero] * size for _ in range(size)]
    for i in range(users):
        phi, gamma = _device(ar, Fraction(masses[i]), Fraction(dampings[i]), T)
        for r in range(2):
            for c in range(2):
                M[2 * i + r][2 * i + c] = M[2 * i + r][2 * i + c] + phi[r][c]
            for c in range(size):
                M[2 * i + r][c] = M[2 * i + r][c] + gamma[r] * U[i][c]
    one = ar.num(1)
    for j in range(users):                       # x[k] moves to x[k-1], x[k-l] to x[k-l-1]
        M[n + j][2 * j] = one
        for lag in range(1, N + 1):
            M[n + lag * users + j][n + (lag - 1) * users + j] = one
    return M


def characteristic_polynomial(M: list) -> list:
    """``det(z I - M)`` by Berkowitz's algorithm (no division), coefficients highest degree first.

    >>> characteristic_polynomial([[Fraction(1), Fraction(2)], [Fraction(3), Fraction(4)]])
    [Fraction(1, 1), Fraction(-5, 1), Fraction(-2, 1)]
    """
    size = len(M)
    if size == 0:
        return [1]
    one = M[0][0] ** 0
    vec = [one, -M[0][0]]
    for r in range(1, size):
        row, col, a = M[r][:r], [M[i][r] for i in range(r)], M[r][r]
        toeplitz = [one, -a]
        X = col
        for _ in range(r):
            toeplitz.append(-sum((row[i] * X[i] for i in range(r)), 0 * a))
            X = [sum((M[i][k] * X[k] for k in range(r)), 0 * a) for i in range(r)]
        vec = [sum((toeplitz[i - j] * vec[j] for j in range(min(i, r) + 1) if i - j < len(toeplitz)), 0 * a)
               for i in range(r + 2)]
    return vec


def _divide_by_z_minus_one(coeffs: list) -> tuple[list, Any]:
    """Synthetic division, highest degree first: quotient and remainder."""
    out = [coeffs[0]]
    for c in coeffs[1:]:
        out.append(c + out[-1])
    return out[:-1], out[-1]


def inside_count(ar: Any, coeffs: list) -> int | None:
    """The number of roots strictly inside the unit circle of a real polynomial (highest degree
    first) by Marden's Schur-Cohn products, or ``None`` when a product's sign is not certain
    (a root on or near the circle, or too little precision).

    >>> inside_count(_Exact(), [Fraction(1), Fraction(-7, 2), Fraction(3, 2)])      # roots 3 and 1/2
    1
    >>> inside_count(_Exact(), [Fraction(1), Fraction(-5, 2), Fraction(1)]) is None  # 2 and 1/2: a singular case
    True
    """
    f = list(reversed(coeffs))                   # a_0 ... a_deg
    count, product = 0, 1
    while len(f) > 1:
        deg = len(f) - 1
        g = [f[0] * f[k] - f[deg] * f[deg - k] for k in range(deg)]
        s = ar.sign(g[0])
        if s is None:
            return None
        product *= s
        count += product < 0
        f = g
    return count


def kernel_dimension(matrix: list) -> int:
    """``dim ker`` of a rational matrix (Gaussian elimination over Q)."""
    rows = [[Fraction(v) for v in row] for row in matrix]
    size = len(rows[0]) if rows else 0
    rank = 0
    for c in range(size):
        pivot = next((r for r in range(rank, len(rows)) if rows[r][c] != 0), None)
        if pivot is None:
            continue
        rows[rank], rows[pivot] = rows[pivot], rows[rank]
        for r in range(len(rows)):
            if r != rank and rows[r][c] != 0:
                f = rows[r][c] / rows[rank][c]
                rows[r] = [x - f * y for x, y in zip(rows[r], rows[rank])]
        rank += 1
    return size - rank


def _decide(ar: Any, masses: list, dampings: list, T: Any, Kmat: list, Bmat: list, delays: list, d: int) -> dict:
    chi = characteristic_polynomial(closed_loop(ar, masses, dampings, T, Kmat, Bmat, delays))
    at_one = d
    for _ in range(d):
        chi, _remainder = _divide_by_z_minus_one(chi)      # (z - 1)^d divides chi exactly
    if isinstance(ar, _Exact):                              # the exact multiplicity of z = 1
        while len(chi) > 1:
            quotient, remainder = _divide_by_z_minus_one(chi)
            if remainder != 0:
                break
            chi, at_one = quotient, at_one + 1
    degree = len(chi) - 1
    inside = inside_count(ar, chi)
    return {"degree": degree + at_one, "at_one": d, "algebraic_at_one": at_one, "inside": inside,
            "rest": degree}


def loop_stability(masses: list, dampings: list, T: Any, Kmat: list, Bmat: list, delays: list) -> OracleResult:
    """``yes`` (every eigenvalue strictly inside the unit circle, certified), ``no`` (``z = 1`` an
    exact eigenvalue, or a root certainly outside) or ``uncertain``.

    ``details``: ``kind`` (``"stable"``, ``"marginal"`` -- rho = 1, the eigenvalue 1 semisimple and
    every other root strictly inside --, ``"unstable"`` -- a root outside, or a Jordan block at 1 --,
    or ``"not stable"`` when only ``z = 1`` is certain), ``at_one`` (``dim ker Kmat``, the fixed
    states), ``outside`` (roots outside, when counted) and ``bits``.
    """
    d = kernel_dimension(Kmat)
    exact = all(Fraction(b) == 0 for b in dampings)
    bits = BITS
    while True:
        if exact:
            info = _decide(_Exact(), masses, dampings, T, Kmat, Bmat, delays, d)
        else:
            saved, mpmath.iv.prec = mpmath.iv.prec, bits
            try:
                info = _decide(_Interval(), masses, dampings, T, Kmat, Bmat, delays, d)
            finally:
                mpmath.iv.prec = saved
        if info["inside"] is not None or exact or bits >= MAX_BITS:
            break
        bits *= 2
    details = {"at_one": d, "bits": 0 if exact else bits}
    inside, rest = info["inside"], info["rest"]
    jordan = info["algebraic_at_one"] > d
    if jordan:
        details |= {"kind": "unstable", "outside": None}
        return OracleResult(NO, f"z = 1 is an eigenvalue of multiplicity {info['algebraic_at_one']} with {d} fixed "
                                "state(s): a Jordan block on the circle", details=details)
    if inside is None:
        if d:
            details |= {"kind": "not stable", "outside": None}
            return OracleResult(NO, f"z = 1 is an exact eigenvalue ({d} fixed state(s)); the others not located",
                                details=details)
        details |= {"kind": None, "outside": None}
        return OracleResult(UNCERTAIN, f"a root within the interval noise of the circle at {bits} bits", details=details)
    outside = rest - inside
    details["outside"] = outside
    if outside:
        details["kind"] = "unstable"
        return OracleResult(NO, f"{outside} root(s) outside the unit circle", details=details)
    if d:
        details["kind"] = "marginal"
        return OracleResult(NO, f"z = 1 is a semisimple eigenvalue ({d} fixed state(s)), every other root strictly "
                                "inside: rho = 1", details=details)
    details["kind"] = "stable"
    return OracleResult(YES, "every root of the characteristic polynomial strictly inside the unit circle",
                        details=details)


def multi_user_matrices(ground_K: list, ground_B: list, coupling_K: list, coupling_B: list) -> tuple[list, list]:
    """``Kmat = diag(K_0) + L_K``, ``Bmat = diag(B_0) + L_B`` (``L`` the weighted Laplacians)."""
    users = len(ground_K)

    def laplacian(ground: list, weights: list) -> list:
        return [[Fraction(ground[i]) + sum(Fraction(weights[i][k]) for k in range(users) if k != i) if i == j
                 else -Fraction(weights[i][j]) for j in range(users)] for i in range(users)]
    return laplacian(ground_K, coupling_K), laplacian(ground_B, coupling_B)


def uniform_matrices(users: int, K0: Any, B0: Any, K: Any, B: Any) -> tuple[list, list]:
    """Every ground ``K_0``, ``B_0`` and every pair coupled by ``K``, ``B`` (the complete graph)."""
    full = lambda v: [[0 if i == j else v for j in range(users)] for i in range(users)]  # noqa: E731
    return multi_user_matrices([K0] * users, [B0] * users, full(K), full(B))


def teleoperator_matrices(K: Any, B: Any, alpha: Any = 1) -> tuple[list, list]:
    """The PEB teleoperator's forces ``u_m = alpha C e``, ``u_s = -C e`` with ``e = alpha x_m - x_s``."""
    a = Fraction(alpha)
    shape = [[a * a, -a], [-a, Fraction(1)]]
    return ([[Fraction(K) * v for v in row] for row in shape], [[Fraction(B) * v for v in row] for row in shape])
