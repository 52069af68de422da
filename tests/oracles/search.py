r"""Search oracle for absolute stability: passive terminations that destabilise an n-port.

An n-port ``Z(s)`` (no poles in ``Re s > 0``) terminated by passive ``T = blockdiag(T_k)`` is
unstable when ``det(Z + T)`` has a zero in ``Re s > 0``. The search works at one frequency
``w0`` where ``Z(jw0)`` is active:

* every port block but one (``k``) gets a constant passive value ``X_b = P_b + j S_b``
  (``P_b`` PSD), chosen (Nelder-Mead) to make the input impedance ``Z_in`` seen at block ``k``
  as active as possible: minimise ``Re mu`` over the eigenvalues ``mu`` of ``W^-1 Z_in(jw0)``
  for a PSD shape ``W`` of block ``k``;
* block ``k`` gets ``t(s) W`` with the series resonator ``t(s) = R + L s + 1/(C s)``,
  ``t(jw0) = -mu - delta`` (``delta = -Re mu/2 > 0``, so ``R = -Re mu/2 > 0``) and a large
  ``L``: then ``mu(s) + t(s)`` has a zero near ``s = jw0 + delta/t'(jw0)``, ``t' = 2L + Im mu/w0
  > 0``, in the right half plane;
* the other blocks are realised as ``P_b + Q_b s + R_b/s`` (``Q_b``, ``R_b`` the positive and
  negative parts of ``S_b``, scaled), all rounded to rationals and checked PSD exactly.

A few plain random RLC terminations are tried as well. Every candidate is verified *exactly*:
with each row of ``Z + T`` multiplied by the lcm of its denominators (no root in ``Re s > 0``:
poles of ``Z`` and of ``T``), the number of right-half-plane zeros of the determinant is the
number of sign changes of the first column of its Routh array over the rationals (regular
arrays only); the zero itself is located with mpmath ``polyroots`` for the report. A ``no``
therefore carries exact passive terminations and an exactly certified unstable coupling; a
failed search is ``uncertain`` (it proves nothing).
"""

from __future__ import annotations

import math
from fractions import Fraction
from typing import Any, Sequence

import mpmath
import numpy as np
import scipy.optimize as so
import sympy as sp

from .continuous import S, RationalMatrix, positive_real_matrix, psd_exact
from .polys import to_fraction
from .result import NO, UNCERTAIN, YES, OracleResult

__all__ = ["port_blocks", "routh_rhp_count", "rhp_zeros", "check_termination", "find_destabilizing_termination"]


def port_blocks(n: int, ports: Sequence[int] | None) -> list[tuple[int, ...]]:
    if ports is None:
        return [(i,) for i in range(n)]
    out, start = [], 0
    for p in ports:
        out.append(tuple(range(start, start + p)))
        start += p
    if start != n:
        raise ValueError("port sizes do not add up")
    return out


# ---------------------------------------------------------------------------------------------
# exact verification
# ---------------------------------------------------------------------------------------------


def routh_rhp_count(coeffs: Sequence[Fraction]) -> int | None:
    """Number of roots in ``Re s > 0`` of a real polynomial (highest first), from the Routh
    array over the rationals; None when the array is singular (a zero first-column entry).
    Roots at ``s = 0`` are divided out first.

    >>> routh_rhp_count([Fraction(1), Fraction(-1)]), routh_rhp_count([Fraction(1), Fraction(3), Fraction(2)])
    (1, 0)
    """
    c = [to_fraction(x) for x in coeffs]
    while len(c) > 1 and c[0] == 0:
        c = c[1:]
    while len(c) > 1 and c[-1] == 0:
        c = c[:-1]
    if len(c) <= 1:
        return 0
    rows = [c[0::2], c[1::2]]
    width = len(rows[0])
    rows = [r + [Fraction(0)] * (width - len(r)) for r in rows]
    first = [rows[0][0], rows[1][0]]
    if rows[1][0] == 0:
        return None
    for _ in range(len(c) - 2):
        a, b = rows[-2], rows[-1]
        new = [(b[0] * a[j + 1] - a[0] * b[j + 1]) / b[0] for j in range(width - 1)] + [Fraction(0)]
        if new[0] == 0:
            return None
        rows.append(new)
        first.append(new[0])
    return sum(1 for x, y in zip(first, first[1:]) if (x > 0) != (y > 0))


def _det_numerator(matrix: sp.Matrix, s: sp.Symbol) -> list[Fraction]:
    """Coefficients of ``det(A)`` where row ``i`` of ``A`` is row ``i`` of ``matrix`` times the lcm
    of its denominators (so ``det(matrix) = det(A) / prod(lcm_i)``)."""
    n = matrix.rows
    rows = []
    for i in range(n):
        fr = [sp.fraction(sp.cancel(sp.together(matrix[i, j]))) for j in range(n)]
        dens = [sp.Poly(d, s, domain=sp.QQ) for _, d in fr]
        lcm = dens[0]
        for d in dens[1:]:
            lcm = lcm.lcm(d)
        rows.append([sp.Poly(num, s, domain=sp.QQ) * lcm.quo(d) for (num, _), d in zip(fr, dens)])

    def det(rs: list[list[sp.Poly]], cols: tuple[int, ...]) -> sp.Poly:
        if len(rs) == 1:
            return rs[0][cols[0]]
        total = sp.Poly(0, s, domain=sp.QQ)
        for k, col in enumerate(cols):
            if rs[0][col].is_zero:
                continue
            rest = cols[:k] + cols[k + 1:]
            term = rs[0][col] * det(rs[1:], rest)
            total = total + term if k % 2 == 0 else total - term
        return total

    poly = det(rows, tuple(range(n)))
    return [to_fraction(c) for c in poly.all_coeffs()]


def rhp_zeros(matrix: sp.Matrix, s: sp.Symbol = S) -> tuple[int | None, list[complex]]:
    """(exact count of zeros of the row-scaled ``det`` in ``Re s > 0`` or None, their locations)."""
    coeffs = _det_numerator(matrix, s)
    count = routh_rhp_count(coeffs)
    located: list[complex] = []
    if count != 0:
        c = list(coeffs)
        while len(c) > 1 and c[-1] == 0:
            c = c[:-1]
        if len(c) > 1:
            with mpmath.workdps(50):
                try:
                    roots = mpmath.polyroots([mpmath.mpf(q.numerator) / q.denominator for q in c],
                                             maxsteps=400, extraprec=200)
                except mpmath.libmp.libhyper.NoConvergence:
                    roots = []
                located = [complex(r) for r in roots if mpmath.re(r) > 1e-30 * max(1, abs(r))]
    return count, sorted(located, key=lambda r: -r.real)


def _terminated(Z: sp.Matrix, terminations: Sequence[sp.Matrix], blocks) -> sp.Matrix:
    total = sp.Matrix(Z)
    for blk, T in zip(blocks, terminations):
        T = sp.Matrix(T)
        for a, i in enumerate(blk):
            for b, j in enumerate(blk):
                total[i, j] = total[i, j] + T[a, b]
    return total


def check_termination(Z: Any, terminations: Sequence[Any], ports: Sequence[int] | None = None,
                      s: sp.Symbol = S) -> OracleResult:
    """Is ``terminations`` (one matrix per port block) a valid instability certificate for ``Z``?

    ``yes``: every termination is not found non-passive by :func:`positive_real_matrix` and
    ``det(Z + T)`` has a zero in ``Re s > 0`` (exact Routh count); ``no``: a termination is not
    positive real, or there is no such zero (exact count 0); ``uncertain`` otherwise.
    """
    Z = sp.Matrix(Z)
    blocks = port_blocks(Z.rows, ports)
    for k, T in enumerate(terminations):
        pr = positive_real_matrix(sp.Matrix(T), s)
        if pr.verdict == NO:
            return OracleResult(NO, f"termination {k} is not positive real: {pr.reason}", details={"termination": k})
    count, located = rhp_zeros(_terminated(Z, terminations, blocks), s)
    if count is None and not located:
        return OracleResult(UNCERTAIN, "singular Routh array and no right-half-plane zero located")
    if count == 0:
        return OracleResult(NO, "det(Z + T) has no zero in Re s > 0 (exact Routh count)")
    zero = located[0] if located else None
    return OracleResult(YES, f"det(Z + T) has {count if count is not None else 'some'} zero(s) in Re s > 0"
                        + (f", e.g. s ~ {zero:.6g}" if zero is not None else ""),
                        margin=zero.real if zero is not None else None, where={"zero": zero})


# ---------------------------------------------------------------------------------------------
# the search
# ---------------------------------------------------------------------------------------------


def _rat(x: float, digits: int = 10) -> Fraction:
    if x == 0 or not math.isfinite(x):
        return Fraction(0)
    e = digits - 1 - math.floor(math.log10(abs(x)))
    return Fraction(round(x * 10.0**e)) / Fraction(10) ** e if e >= 0 else Fraction(round(x / 10.0**-e)) * Fraction(10) ** -e


def _rat_psd(A: np.ndarray) -> list[list[Fraction]]:
    """Rational symmetric rounding of a PSD matrix, lifted by a tiny multiple of I until PSD exactly."""
    A = (A + A.T) / 2
    p = A.shape[0]
    size = float(np.abs(A).max()) if A.size else 0.0
    for lift in (0.0, 1e-9, 1e-6):
        M = [[_rat(float(A[i, j]) + (lift * size if i == j else 0.0)) for j in range(p)] for i in range(p)]
        M = [[M[min(i, j)][max(i, j)] for j in range(p)] for i in range(p)]
        if psd_exact(M)[0]:
            return M
    raise ArithmeticError("could not round to a PSD rational matrix")


def _sym(M: list[list[Fraction]]) -> sp.Matrix:
    return sp.Matrix(len(M), len(M), lambda i, j: sp.Rational(M[i][j].numerator, M[i][j].denominator))


class _Search:
    def __init__(self, Zm: RationalMatrix, blocks, rng, restarts: int = 1):
        self.Zm, self.blocks, self.rng, self.restarts = Zm, blocks, rng, restarts

    @staticmethod
    def _block_value(params: np.ndarray, p: int, sigma: float) -> np.ndarray:
        if p == 1:
            a, b = params
            return np.array([[sigma * math.exp(max(min(a, 40), -40)) + 1j * sigma * b]])
        a1, a2, c, b1, b2, b3 = params
        L = np.array([[math.exp(max(min(a1, 40), -40)), 0.0], [c, math.exp(max(min(a2, 40), -40))]])
        return sigma * (L @ L.T) + 1j * sigma * np.array([[b1, b2], [b2, b3]])

    @staticmethod
    def _shape(params: np.ndarray, p: int) -> np.ndarray:
        if p == 1:
            return np.eye(1)
        phi, r = params
        R = np.array([[math.cos(phi), -math.sin(phi)], [math.sin(phi), math.cos(phi)]])
        return R @ np.diag([1.0, math.exp(max(min(r, 8), -8))]) @ R.T

    def _split(self, k):
        blk = list(self.blocks[k])
        others = [b for i, b in enumerate(self.blocks) if i != k]
        sizes = [(len(b), 2 if len(b) == 1 else 6) for b in others]
        return blk, others, sizes, (0 if len(blk) == 1 else 2)

    def _unpack(self, x, k, sigma):
        blk, others, sizes, nshape = self._split(k)
        W = self._shape(x[:nshape], len(blk))
        pos, X = nshape, []
        for p, npar in sizes:
            X.append(self._block_value(x[pos:pos + npar], p, sigma))
            pos += npar
        return W, X

    def _mu(self, Zw: np.ndarray, k: int, W: np.ndarray, X: list[np.ndarray]):
        blk, others, _, _ = self._split(k)
        o = [i for b in others for i in b]
        Zoo = Zw[np.ix_(o, o)].copy()
        pos = 0
        for b, Xb in zip(others, X):
            Zoo[pos:pos + len(b), pos:pos + len(b)] += Xb
            pos += len(b)
        Zin = Zw[np.ix_(blk, blk)] - Zw[np.ix_(blk, o)] @ np.linalg.solve(Zoo, Zw[np.ix_(o, blk)])
        mus = np.linalg.eigvals(np.linalg.solve(W, Zin))
        return mus[np.argmin(mus.real)]

    def optimise(self, w0: float, k: int):
        Zw = self.Zm.np_at(np.array([w0]))[0]
        sigma = float(np.abs(Zw).max()) or 1.0
        _, _, sizes, nshape = self._split(k)
        dim = nshape + sum(npar for _, npar in sizes)

        def objective(x):
            try:
                W, X = self._unpack(x, k, sigma)
                with np.errstate(all="ignore"):
                    mu = self._mu(Zw, k, W, X)
                value = mu.real / sigma
                return value if math.isfinite(value) else 1e3
            except np.linalg.LinAlgError:
                return 1e3

        starts = [np.zeros(dim)] + [self.rng.normal(scale=2.0, size=dim) for _ in range(self.restarts)]
        best = None
        for x0 in starts:
            res = so.minimize(objective, x0, method="Nelder-Mead", options={"maxiter": 80 * dim, "xatol": 1e-8, "fatol": 1e-12})
            if best is None or res.fun < best.fun:
                best = res
            if best.fun < -1e-2:
                break
        return best.fun, best.x, sigma

    def build(self, w0: float, k: int, x: np.ndarray, sigma: float, gamma: float):
        W, X = self._unpack(x, k, sigma)
        Zw = self.Zm.np_at(np.array([w0]))[0]
        mu = self._mu(Zw, k, W, X)
        blk, others, _, _ = self._split(k)
        terms: dict[int, sp.Matrix] = {}
        s = S
        for b, Xb in zip(others, X):
            P = Xb.real
            ev, V = np.linalg.eigh((Xb.imag + Xb.imag.T) / 2)
            Q = (V * np.maximum(ev, 0)) @ V.T / w0
            R = (V * np.maximum(-ev, 0)) @ V.T * w0
            Tb = _sym(_rat_psd(P)) + _sym(_rat_psd(Q)) * s + _sym(_rat_psd(R)) / s
            terms[self.blocks.index(b)] = Tb
        Rr = -mu.real / 2
        L = gamma * abs(mu) / w0
        C = 1.0 / (w0 * (L * w0 + mu.imag))
        Rq, Lq, Cq = _rat(Rr), _rat(L), _rat(C)
        if Rq <= 0 or Lq <= 0 or Cq <= 0:
            return None
        Wq = _sym(_rat_psd(W))
        t = sp.Rational(Rq.numerator, Rq.denominator) + sp.Rational(Lq.numerator, Lq.denominator) * s \
            + 1 / (sp.Rational(Cq.numerator, Cq.denominator) * s)
        terms[k] = t * Wq
        return [terms[i] for i in range(len(self.blocks))]


def find_destabilizing_termination(Z: Any, ports: Sequence[int] | None = None, s: sp.Symbol = S, *,
                                   seed: int = 0, frequencies: Sequence[float] | None = None,
                                   max_frequencies: int = 3, random_tries: int = 4, restarts: int = 1) -> OracleResult:
    """``no`` (with exact passive terminations and the right-half-plane zero they create) or
    ``uncertain``; see the module docstring."""
    Zs = sp.Matrix(Z).subs(s, S) if s != S else sp.Matrix(Z)
    Zm = RationalMatrix(Zs, S)
    n = Zm.n
    blocks = port_blocks(n, ports)
    rng = np.random.default_rng(seed)
    with mpmath.workdps(50):
        for ij, r, _ in Zm.poles():
            if r.real > 1e-40 * max(1, abs(r)):
                return OracleResult(NO, f"open-circuit unstable: entry {ij} has a pole at s ~ {complex(r):.6g}",
                                    where={"pole": complex(r)}, details={"terminations": None})
    if frequencies is None:
        feats = Zm.features()
        lo = math.floor(math.log10(min(feats))) - 2 if feats else -3
        hi = math.ceil(math.log10(max(feats))) + 2 if feats else 3
        grid = np.logspace(max(lo, -8), min(hi, 8), 41)
        Zw = Zm.np_at(grid)
        M = Zw + np.conj(np.transpose(Zw, (0, 2, 1)))
        ok = np.all(np.isfinite(M), axis=(1, 2))
        score = np.full(len(grid), np.inf)
        score[ok] = np.linalg.eigvalsh(M[ok])[:, 0] / np.maximum(np.abs(M[ok]).max(axis=(1, 2)), 1e-300)
        order = [i for i in np.argsort(score) if score[i] < 0][:max_frequencies]
        frequencies = [float(grid[i]) for i in order]
    tried = 0
    search = _Search(Zm, blocks, rng, restarts)
    for w0 in frequencies:
        for k in range(len(blocks)):
            value, x, sigma = search.optimise(w0, k)
            if value > -1e-7:
                continue
            for gamma in (3.0, 30.0, 300.0):
                try:
                    terms = search.build(w0, k, x, sigma, gamma)
                except (ArithmeticError, np.linalg.LinAlgError):
                    terms = None
                if terms is None:
                    continue
                tried += 1
                result = _verify(Zs, terms, blocks)
                if result is not None:
                    return result
    # plain random RLC terminations
    scale = float(np.nanmax(np.abs(Zm.np_at(np.array([1.0]))))) or 1.0
    for _ in range(random_tries):
        terms = []
        for blk in blocks:
            p = len(blk)
            A = rng.normal(size=(p, p))
            Wq = _sym(_rat_psd(A @ A.T + 0.1 * np.eye(p)))
            R, L, C = (_rat(scale * 10 ** rng.uniform(-3, 1)), _rat(scale * 10 ** rng.uniform(-3, 1)),
                       _rat(10 ** rng.uniform(-3, 1) / scale))
            kind = rng.integers(0, 4)
            r_, l_, c_ = (sp.Rational(v.numerator, v.denominator) for v in (R, L, C))
            t = [r_, r_ + 1 / (c_ * S), r_ + l_ * S + 1 / (c_ * S), r_ / (1 + r_ * c_ * S)][kind]
            terms.append(t * Wq)
        tried += 1
        result = _verify(Zs, terms, blocks)
        if result is not None:
            return result
    return OracleResult(UNCERTAIN, f"no destabilising passive termination found ({tried} candidates verified)",
                        details={"frequencies": list(frequencies)})


def _verify(Zs: sp.Matrix, terms: list[sp.Matrix], blocks) -> OracleResult | None:
    if any(e.has(sp.zoo, sp.oo, sp.nan) for T in terms for e in T):
        return None          # a candidate rounded to a zero capacitance: not a termination
    count, located = rhp_zeros(_terminated(Zs, terms, blocks), S)
    if count:
        zero = located[0] if located else None
        return OracleResult(NO, f"passive terminations put {count} zero(s) of det(Z + T) in Re s > 0"
                            + (f" (s ~ {zero:.6g})" if zero is not None else ""),
                            margin=-(zero.real if zero is not None else 0.0), where={"zero": zero},
                            details={"terminations": terms})
    return None
