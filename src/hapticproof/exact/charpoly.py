"""Constant Hermitian matrices, exactly: characteristic polynomials over the rationals or the
Gaussian rationals, and positive semidefiniteness by the signs of their coefficients."""

from __future__ import annotations

import itertools
from dataclasses import dataclass
from typing import Any

import flint
import numpy as np
import sympy as sp

from hapticproof.exact.realroots import as_fmpq

__all__ = ["PsdTest", "is_psd"]


def _as_gaussian_matrix(matrix: Any) -> tuple[list[list[flint.fmpq]], list[list[flint.fmpq]]]:
    """Real and imaginary parts (exact rationals) of a numeric matrix."""
    M = sp.Matrix(matrix)
    re = [[as_fmpq(sp.re(sp.nsimplify(v) if isinstance(v, float) else v)) for v in M.row(i)] for i in range(M.rows)]
    im = [[as_fmpq(sp.im(sp.nsimplify(v) if isinstance(v, float) else v)) for v in M.row(i)] for i in range(M.rows)]
    return re, im


def _charpoly_hermitian(re: list[list[flint.fmpq]], im: list[list[flint.fmpq]]) -> list[flint.fmpq]:
    """``E_0..E_m`` of the Hermitian matrix ``re + j im`` (exact).

    Complex case: the real embedding ``[[A, -B], [B, A]]`` has characteristic polynomial
    ``p(lambda)**2`` (``p`` is real for a Hermitian matrix), so ``p`` is its exact square root.
    """
    m = len(re)
    if all(v == 0 for row in im for v in row):
        cp = flint.fmpq_mat(re).charpoly() if m else flint.fmpq_poly([1])
    else:
        big = [[flint.fmpq(0)] * (2 * m) for _ in range(2 * m)]
        for i in range(m):
            for j in range(m):
                big[i][j] = big[i + m][j + m] = re[i][j]
                big[i][j + m] = -im[i][j]
                big[i + m][j] = im[i][j]
        cp = flint.fmpq_mat(big).charpoly().sqrt()
        if cp.coeffs()[-1] < 0:
            cp = -cp
    coeffs = cp.coeffs() + [flint.fmpq(0)] * (m + 1 - len(cp.coeffs()))
    # det(lambda I - M) = sum_k (-1)^k E_k lambda^(m-k)
    return [(-1) ** k * coeffs[m - k] for k in range(m + 1)]


@dataclass(frozen=True, slots=True)
class PsdTest:
    """Exact PSD test of a numeric Hermitian matrix.

    ``coefficients`` are ``E_0..E_m``; ``failing`` is the first ``k`` with ``E_k < 0`` and
    ``minor`` a principal submatrix (index tuple, 0-based) with a negative determinant when
    the matrix is small enough to search (``None`` otherwise).
    """

    holds: bool
    coefficients: tuple[sp.Rational, ...]
    failing: int | None = None
    minor: tuple[tuple[int, ...], sp.Expr] | None = None
    min_eigenvalue: float | None = None


def is_psd(matrix: Any, search_minor: bool = True) -> PsdTest:
    """Exact positive semidefiniteness of a numeric Hermitian matrix (rational or Gaussian
    rational entries) by the signs of its characteristic-polynomial coefficients.

    >>> t = is_psd([[0, 0], [0, -1]])
    >>> t.holds, t.failing, t.minor
    (False, 1, ((1,), -1))
    >>> is_psd([[2, 1], [1, 2]]).holds, is_psd(sp.Matrix([[1, sp.I], [-sp.I, 1]])).holds
    (True, True)
    """
    M = sp.Matrix(matrix)
    if M.rows != M.cols:
        raise ValueError("a PSD test needs a square matrix")
    if any(sp.simplify(M[i, j] - sp.conjugate(M[j, i])) != 0 for i in range(M.rows) for j in range(i, M.rows)):
        raise ValueError("the matrix is not Hermitian")
    re, im = _as_gaussian_matrix(M)
    coeffs = _charpoly_hermitian(re, im)
    failing = next((k for k, e in enumerate(coeffs) if e < 0), None)
    minor = None
    if failing is not None and search_minor and M.rows <= 10:
        for size in range(1, M.rows + 1):
            for subset in itertools.combinations(range(M.rows), size):
                value = sp.nsimplify(M.extract(list(subset), list(subset)).det())
                if sp.re(value) < 0:
                    minor = (subset, sp.re(value))
                    break
            if minor:
                break
    return PsdTest(failing is None, tuple(sp.Rational(int(e.p), int(e.q)) for e in coeffs), failing, minor,
                   _least_eigenvalue(M))


def _least_eigenvalue(M: sp.Matrix) -> float | None:
    """A float diagnostic (the decision above is exact): ``None`` when the entries leave the
    float range (1e300 couplings) or LAPACK does not converge."""
    if not M.rows:
        return 0.0
    values = np.array(M.evalf(30).tolist(), dtype=complex)
    if not np.all(np.isfinite(values)):
        return None
    try:
        return float(np.min(np.linalg.eigvalsh(values)))
    except np.linalg.LinAlgError:
        return None


def _integer_charpoly(rows: list[list[flint.fmpq]]) -> list[flint.fmpq]:
    """Characteristic polynomial coefficients (lowest degree first) of a rational matrix, via
    the integer matrix ``D X`` (flint's multi-modular ``fmpz_mat`` charpoly is much faster)."""
    n = len(rows)
    if n == 0:
        return [flint.fmpq(1)]
    D = flint.fmpz(1)
    for row in rows:
        for v in row:
            D = D * v.q // D.gcd(v.q)
    ints = flint.fmpz_mat([[int(v * D) for v in row] for row in rows])
    cp = ints.charpoly().coeffs()
    # det(lambda I - D X) = D^n det(lambda/D I - X): coefficient of lambda^k carries D^(n-k)
    return [flint.fmpq(cp[k], 1) / flint.fmpq(D) ** (n - k) for k in range(n + 1)]


def charpoly_sq(re: list[list[flint.fmpq]], sim: list[list[flint.fmpq]] | None, q2: flint.fmpq) -> list[flint.fmpq]:
    """``E_0..E_m`` of ``A + j q S`` from ``A``, ``S`` and ``q**2`` only (all rational).

    The real embedding ``[[A, -qS], [qS, A]]`` is similar (by ``diag(I, qI)``) to
    ``[[A, -q^2 S], [S, A]]``, whose characteristic polynomial is ``p(lambda)**2``.
    """
    m = len(re)
    if sim is None or all(v == 0 for row in sim for v in row):
        coeffs = _integer_charpoly(re)
    else:
        big = [[flint.fmpq(0)] * (2 * m) for _ in range(2 * m)]
        for i in range(m):
            for j in range(m):
                big[i][j] = big[i + m][j + m] = re[i][j]
                big[i][j + m] = -q2 * sim[i][j]
                big[i + m][j] = sim[i][j]
        cp = flint.fmpq_poly(_integer_charpoly(big)).sqrt()
        if cp.coeffs()[-1] < 0:
            cp = -cp
        coeffs = cp.coeffs()
    coeffs = list(coeffs) + [flint.fmpq(0)] * (m + 1 - len(coeffs))
    return [(-1) ** k * coeffs[m - k] for k in range(m + 1)]
