r"""Exact real-rational matrices of ``s`` and their Hermitian parts on the imaginary axis.

The continuous-time counterpart of :mod:`unitcircle` for *matrices*: entries are ratios of
``flint.fmpq_poly`` in ``s`` (rational coefficients), so every operation is exact and fast.

* **Hermitian part.** For a real-rational ``Z(s)`` the Hermitian part at ``s = jw`` is
  ``(Z(jw) + Z(jw)^H)/2 = Phi(jw)`` with the para-Hermitian ``Phi(s) = (Z(s) + Z(-s)^T)/2``.
  Multiplying ``Phi`` by the scalar ``L(s) L(-s)`` (``L`` the lcm of the denominators; it equals
  ``|L(jw)|**2 >= 0`` on the axis) gives a polynomial matrix whose principal minors are even
  polynomials in ``s``: with ``s**2 = -x`` they are exact polynomials in ``x = w**2`` on
  ``[0, oo)`` (:func:`hermitian_minors`).
* **PSD over frequency.** A Hermitian matrix is PSD iff *all* its principal minors are >= 0,
  equivalently iff the coefficients ``E_k`` of its characteristic polynomial (sums of the
  principal minors of order ``k``) are all >= 0 -- never the leading minors alone
  (:func:`decide_psd`, decisions by root isolation with an exact rational witness ``x``).
* **Poles.** Imaginary-axis poles are found exactly (``gcd`` of the real and imaginary parts
  of the denominator on ``s = jw``); the other poles are placed in the open half planes by
  certified complex root isolation (:func:`pole_report`).

>>> import sympy as sp
>>> from hapticproof.symbols import s
>>> Z = RationalMatrix.from_sympy(sp.Matrix([[1/(s + 1), 0], [0, 2/(s + 2)]]))
>>> minors = hermitian_minors(Z)
>>> decide_psd(minors).decision.value
'proved'
"""

from __future__ import annotations

import itertools
import math
from collections.abc import Iterable, Mapping, Sequence
from dataclasses import dataclass
from fractions import Fraction
from typing import Any

import flint
import sympy as sp

from hapticproof.errors import InputFormatError
from hapticproof.evidence import Decision, Evidence, Method, Outcome
from hapticproof.realroots import as_fmpq, real_roots, to_rational
from hapticproof.symbols import s as S_SYM
from hapticproof.certify import canonical_fraction

__all__ = [
    "RationalFunction",
    "RationalMatrix",
    "poly_det",
    "principal_minors",
    "even_to_x",
    "HermitianMinors",
    "hermitian_minors",
    "minors_from_polynomial_matrix",
    "decide_psd",
    "decide_nonnegative",
    "rational_frequency",
    "AxisPole",
    "PoleReport",
    "pole_report",
    "rhp_roots",
    "HalflineMinimum",
    "minimise_halfline",
    "matrix_psd",
]

_ONE = flint.fmpq_poly([1])
_ZERO = flint.fmpq_poly([])
_NEG_S = flint.fmpq_poly([0, -1])


def _fmpq_poly(poly: sp.Poly) -> flint.fmpq_poly:
    coeffs = poly.all_coeffs()[::-1]
    try:
        return flint.fmpq_poly([as_fmpq(poly.domain.to_sympy(a)) for a in coeffs])
    except TypeError as err:
        raise InputFormatError(f"non-rational coefficient in {poly.as_expr()} (give numbers, not symbols)") from err


def _to_expr(p: flint.fmpq_poly, var: sp.Symbol) -> sp.Expr:
    return sp.Add(*[to_rational(a) * var**i for i, a in enumerate(p.coeffs())])


def _reflect(p: flint.fmpq_poly) -> flint.fmpq_poly:
    """``p(-s)``."""
    return p(_NEG_S) if p.degree() > 0 else p


# ---------------------------------------------------------------------------------------------
# scalar rational functions
# ---------------------------------------------------------------------------------------------


@dataclass(frozen=True, slots=True, eq=False)
class RationalFunction:
    """``num(s)/den(s)`` with rational coefficients, in lowest terms with a monic denominator.

    >>> f = RationalFunction.from_sympy(2/(S_SYM + 1)) + RationalFunction.constant(1)
    >>> f.expr()
    (s + 3)/(s + 1)
    """

    num: flint.fmpq_poly
    den: flint.fmpq_poly

    def __post_init__(self) -> None:
        if self.den.is_zero():
            raise ZeroDivisionError("zero denominator")

    @classmethod
    def make(cls, num: flint.fmpq_poly, den: flint.fmpq_poly) -> RationalFunction:
        """Reduce to lowest terms with a monic denominator."""
        if den.is_zero():
            raise ZeroDivisionError("zero denominator")
        if num.is_zero():
            return cls(_ZERO, _ONE)
        g = num.gcd(den)
        if g.degree() > 0:
            num, den = num // g, den // g
        lead = den.coeffs()[-1]
        if lead != 1:
            num, den = num / lead, den / lead
        return cls(num, den)

    @classmethod
    def constant(cls, value: Any) -> RationalFunction:
        return cls(flint.fmpq_poly([as_fmpq(value)]), _ONE)

    @classmethod
    def from_sympy(cls, expr: Any, s: sp.Symbol = S_SYM) -> RationalFunction:
        """From a SymPy rational function of ``s`` with rational coefficients."""
        expr = sp.sympify(expr)
        extra = expr.free_symbols - {s}
        if extra:
            raise InputFormatError(f"entry {expr} has symbols other than {s}: {sorted(map(str, extra))}")
        num, den = canonical_fraction(expr)
        return cls.make(_fmpq_poly(sp.Poly(num, s)), _fmpq_poly(sp.Poly(den, s)))

    def is_zero(self) -> bool:
        return self.num.is_zero()

    def __add__(self, other: RationalFunction) -> RationalFunction:
        if self.den == other.den:
            return RationalFunction.make(self.num + other.num, self.den)
        return RationalFunction.make(self.num * other.den + other.num * self.den, self.den * other.den)

    def __neg__(self) -> RationalFunction:
        return RationalFunction(-self.num, self.den)

    def __sub__(self, other: RationalFunction) -> RationalFunction:
        return self + (-other)

    def __mul__(self, other: RationalFunction) -> RationalFunction:
        return RationalFunction.make(self.num * other.num, self.den * other.den)

    def __truediv__(self, other: RationalFunction) -> RationalFunction:
        if other.is_zero():
            raise ZeroDivisionError("division by the zero function")
        return RationalFunction.make(self.num * other.den, self.den * other.num)

    def scale(self, value: Any) -> RationalFunction:
        return RationalFunction.make(self.num * as_fmpq(value), self.den)

    def __eq__(self, other: object) -> bool:
        return isinstance(other, RationalFunction) and self.num == other.num and self.den == other.den

    __hash__ = None  # type: ignore[assignment]

    def reflect(self) -> RationalFunction:
        """``f(-s)``."""
        return RationalFunction.make(_reflect(self.num), _reflect(self.den))

    def expr(self, s: sp.Symbol = S_SYM) -> sp.Expr:
        """The function as a SymPy expression."""
        return _to_expr(self.num, s) / _to_expr(self.den, s)

    def at(self, point: Any) -> sp.Expr:
        """Exact value at a rational point (``ZeroDivisionError`` at a pole)."""
        q = as_fmpq(point)
        d = self.den(q)
        if d == 0:
            raise ZeroDivisionError(f"pole at s = {point}")
        return to_rational(self.num(q) / d)

    def complex_at(self, point: complex, dps: int = 30) -> Any:
        """Value at a complex point with mpmath (``dps`` digits)."""
        import mpmath

        with mpmath.workdps(dps):
            z = mpmath.mpc(point)
            num = mpmath.polyval([mpmath.mpf(int(a.p)) / int(a.q) for a in reversed(self.num.coeffs())] or [0], z)
            den = mpmath.polyval([mpmath.mpf(int(a.p)) / int(a.q) for a in reversed(self.den.coeffs())], z)
            return num / den

    @property
    def relative_degree(self) -> int:
        """``deg den - deg num`` (``+oo`` stands for the zero function as a large number)."""
        if self.num.is_zero():
            return 10**9
        return self.den.degree() - self.num.degree()


# ---------------------------------------------------------------------------------------------
# matrices
# ---------------------------------------------------------------------------------------------


@dataclass(frozen=True, slots=True, eq=False)
class RationalMatrix:
    """An ``n x m`` matrix of :class:`RationalFunction` entries (exact, immutable).

    >>> Z = RationalMatrix.from_sympy(sp.Matrix([[1, 1/S_SYM], [0, S_SYM]]))
    >>> Z.shape, Z.transpose().to_sympy()
    ((2, 2), Matrix([
    [  1, 0],
    [1/s, s]]))
    """

    rows: tuple[tuple[RationalFunction, ...], ...]

    def __post_init__(self) -> None:
        if not self.rows or not self.rows[0]:
            raise ValueError("empty matrix")
        width = len(self.rows[0])
        if any(len(r) != width for r in self.rows):
            raise ValueError("ragged matrix")

    @classmethod
    def from_sympy(cls, matrix: Any, s: sp.Symbol = S_SYM) -> RationalMatrix:
        """From a SymPy matrix (or nested lists) of rational functions of ``s``."""
        M = sp.Matrix(matrix)
        return cls(tuple(tuple(RationalFunction.from_sympy(M[i, j], s) for j in range(M.cols)) for i in range(M.rows)))

    @classmethod
    def from_entries(cls, entries: Sequence[Sequence[RationalFunction]]) -> RationalMatrix:
        return cls(tuple(tuple(row) for row in entries))

    @classmethod
    def zeros(cls, n: int, m: int | None = None) -> RationalMatrix:
        zero = RationalFunction(_ZERO, _ONE)
        return cls(tuple(tuple(zero for _ in range(m or n)) for _ in range(n)))

    @property
    def shape(self) -> tuple[int, int]:
        return len(self.rows), len(self.rows[0])

    def __getitem__(self, index: tuple[int, int]) -> RationalFunction:
        i, j = index
        return self.rows[i][j]

    def to_sympy(self, s: sp.Symbol = S_SYM) -> sp.Matrix:
        return sp.Matrix([[e.expr(s) for e in row] for row in self.rows])

    def transpose(self) -> RationalMatrix:
        n, m = self.shape
        return RationalMatrix(tuple(tuple(self.rows[i][j] for i in range(n)) for j in range(m)))

    def reflect(self) -> RationalMatrix:
        """``Z(-s)``."""
        return RationalMatrix(tuple(tuple(e.reflect() for e in row) for row in self.rows))

    def __add__(self, other: RationalMatrix) -> RationalMatrix:
        if self.shape != other.shape:
            raise ValueError("shape mismatch")
        return RationalMatrix(tuple(tuple(a + b for a, b in zip(r, q)) for r, q in zip(self.rows, other.rows)))

    def __sub__(self, other: RationalMatrix) -> RationalMatrix:
        return self + other.map(lambda e: -e)

    def __matmul__(self, other: RationalMatrix) -> RationalMatrix:
        n, k = self.shape
        k2, m = other.shape
        if k != k2:
            raise ValueError("shape mismatch")
        out = []
        for i in range(n):
            row = []
            for j in range(m):
                acc = RationalFunction(_ZERO, _ONE)
                for t in range(k):
                    a, b = self.rows[i][t], other.rows[t][j]
                    if not a.is_zero() and not b.is_zero():
                        acc = acc + a * b
                row.append(acc)
            out.append(tuple(row))
        return RationalMatrix(tuple(out))

    def map(self, func) -> RationalMatrix:
        return RationalMatrix(tuple(tuple(func(e) for e in row) for row in self.rows))

    def submatrix(self, rows: Sequence[int], cols: Sequence[int] | None = None) -> RationalMatrix:
        cols = rows if cols is None else cols
        return RationalMatrix(tuple(tuple(self.rows[i][j] for j in cols) for i in rows))

    def is_symmetric(self) -> bool:
        n, m = self.shape
        return n == m and all(self.rows[i][j] == self.rows[j][i] for i in range(n) for j in range(i + 1, n))

    def denominator_lcm(self) -> flint.fmpq_poly:
        """Monic lcm of all entry denominators."""
        lcm = _ONE
        for row in self.rows:
            for e in row:
                if e.den.degree() > 0:
                    lcm = lcm * e.den // lcm.gcd(e.den)
        return lcm / lcm.coeffs()[-1]

    def polynomial(self) -> tuple[list[list[flint.fmpq_poly]], flint.fmpq_poly]:
        """``(P, L)`` with ``Z = P / L``, ``P`` a polynomial matrix and ``L`` the lcm above."""
        L = self.denominator_lcm()
        return [[e.num * (L // e.den) for e in row] for row in self.rows], L

    def determinant(self) -> RationalFunction:
        """Exact determinant (fraction-free elimination on the polynomial form)."""
        n, m = self.shape
        if n != m:
            raise ValueError("determinant of a non-square matrix")
        P, L = self.polynomial()
        return RationalFunction.make(poly_det(P), L**n)

    def minor(self, rows: Sequence[int], cols: Sequence[int]) -> RationalFunction:
        return self.submatrix(rows, cols).determinant()

    def inverse(self) -> RationalMatrix:
        """Exact inverse by adjugate over the polynomial form (``ZeroDivisionError`` if singular)."""
        n, m = self.shape
        if n != m:
            raise ValueError("inverse of a non-square matrix")
        P, L = self.polynomial()
        det = poly_det(P)
        if det.is_zero():
            raise ZeroDivisionError("singular rational matrix")
        out = []
        for i in range(n):
            row = []
            for j in range(n):
                # (P^-1)_{ij} = (-1)^{i+j} det P[without row j, col i] / det P ; Z^-1 = L P^-1
                rest_rows = [r for r in range(n) if r != j]
                rest_cols = [c for c in range(n) if c != i]
                cof = poly_det([[P[r][c] for c in rest_cols] for r in rest_rows]) if n > 1 else _ONE
                sign = -1 if (i + j) % 2 else 1
                row.append(RationalFunction.make(cof * L * sign, det))
            out.append(tuple(row))
        return RationalMatrix(tuple(out))

    def complex_at(self, point: complex, dps: int = 30):
        """The matrix at a complex point (mpmath matrix)."""
        import mpmath

        with mpmath.workdps(dps):
            return mpmath.matrix([[e.complex_at(point, dps) for e in row] for row in self.rows])

    def numpy_at(self, point: complex):
        """The matrix at a complex point in double precision (numpy)."""
        import numpy as np

        out = np.empty(self.shape, dtype=complex)
        for i, row in enumerate(self.rows):
            for j, e in enumerate(row):
                num = [float(a) for a in e.num.coeffs()][::-1] or [0.0]
                den = [float(a) for a in e.den.coeffs()][::-1]
                out[i, j] = np.polyval(num, point) / np.polyval(den, point)
        return out


# ---------------------------------------------------------------------------------------------
# determinants and principal minors of polynomial matrices
# ---------------------------------------------------------------------------------------------


def poly_det(rows: Sequence[Sequence[flint.fmpq_poly]]) -> flint.fmpq_poly:
    """Determinant of a square polynomial matrix by Bareiss' fraction-free elimination.

    >>> p = flint.fmpq_poly
    >>> poly_det([[p([0, 1]), p([1])], [p([1]), p([0, 1])]])      # s**2 - 1
    x^2 + (-1)
    """
    n = len(rows)
    if n == 0:
        return _ONE
    M = [list(r) for r in rows]
    sign = 1
    prev = _ONE
    for k in range(n - 1):
        if M[k][k].is_zero():
            pivot = next((i for i in range(k + 1, n) if not M[i][k].is_zero()), None)
            if pivot is None:
                return _ZERO
            M[k], M[pivot] = M[pivot], M[k]
            sign = -sign
        pkk = M[k][k]
        for i in range(k + 1, n):
            mik = M[i][k]
            row_i, row_k = M[i], M[k]
            for j in range(k + 1, n):
                value = row_i[j] * pkk - mik * row_k[j]
                row_i[j] = value // prev if prev != _ONE else value
        prev = pkk
    return M[n - 1][n - 1] if sign > 0 else -M[n - 1][n - 1]


def principal_minors(
    rows: Sequence[Sequence[flint.fmpq_poly]], orders: Iterable[int] | None = None
) -> dict[tuple[int, ...], flint.fmpq_poly]:
    """All principal minors (index tuple -> determinant) of a square polynomial matrix.

    >>> p = flint.fmpq_poly
    >>> m = principal_minors([[p([2]), p([1])], [p([1]), p([2])]])
    >>> [(k, str(v)) for k, v in sorted(m.items())]
    [((0,), '2'), ((0, 1), '3'), ((1,), '2')]
    """
    n = len(rows)
    orders = range(1, n + 1) if orders is None else orders
    out = {}
    for k in orders:
        for subset in itertools.combinations(range(n), k):
            out[subset] = poly_det([[rows[i][j] for j in subset] for i in subset])
    return out


def even_to_x(p: flint.fmpq_poly, variable: str = "s") -> flint.fmpq_poly:
    """An even polynomial in ``s`` (``s**2 = -x``) or in ``w`` (``w**2 = x``) as a polynomial in ``x``.

    >>> even_to_x(flint.fmpq_poly([1, 0, 3]), "s").coeffs()    # 1 + 3 s**2 = 1 - 3x
    [1, -3]
    """
    coeffs = p.coeffs()
    if any(c != 0 for c in coeffs[1::2]):
        raise ArithmeticError("expected an even polynomial")
    sign = -1 if variable == "s" else 1
    return flint.fmpq_poly([c * (sign**k) for k, c in enumerate(coeffs[0::2])])


@dataclass(frozen=True, slots=True, eq=False)
class HermitianMinors:
    """Principal minors of the Hermitian part of a matrix function on ``s = jw``, in ``x = w**2``.

    ``minors[S](x)`` equals ``scale[len(S)](x)`` times the true minor of order ``|S|`` of
    ``(Z(jw) + Z(jw)^H)/2``; every ``scale[k]`` is >= 0 on ``[0, oo)`` and vanishes only at
    imaginary-axis poles (where the Hermitian part is undefined), so signs agree wherever the
    minor is defined.
    """

    n: int
    minors: Mapping[tuple[int, ...], flint.fmpq_poly]
    scale: Mapping[int, flint.fmpq_poly]

    def coefficient(self, k: int) -> flint.fmpq_poly:
        """``E_k``: the sum of the principal minors of order ``k`` (scaled by ``scale[k]``)."""
        acc = _ZERO
        for subset, value in self.minors.items():
            if len(subset) == k:
                acc = acc + value
        return acc

    def true_minor(self, subset: tuple[int, ...], x_value: Any) -> sp.Expr:
        """The exact minor of the Hermitian part at a rational ``x`` (not an axis pole)."""
        q = as_fmpq(x_value)
        scale = self.scale[len(subset)](q)
        if scale == 0:
            raise ZeroDivisionError(f"x = {x_value} is an imaginary-axis pole")
        return to_rational(self.minors[subset](q) / scale)

    def leading(self, k: int) -> flint.fmpq_poly:
        return self.minors[tuple(range(k))]


def minors_from_polynomial_matrix(
    P: Sequence[Sequence[flint.fmpq_poly]], scale: flint.fmpq_poly, variable: str
) -> HermitianMinors:
    """Hermitian minors from a polynomial matrix ``P = scale * H`` whose minors are even in
    ``variable`` (``'s'`` for a para-Hermitian ``Phi(s)``, ``'omega'`` for a real symmetric
    matrix function of ``w``); ``scale`` is the (even) scalar, >= 0 on the axis."""
    n = len(P)
    raw = principal_minors(P)
    minors = {k: even_to_x(v, variable) for k, v in raw.items()}
    base = even_to_x(scale, variable)
    return HermitianMinors(n, minors, {k: base**k for k in range(1, n + 1)})


def hermitian_minors(Z: RationalMatrix) -> HermitianMinors:
    """Principal minors of ``(Z(jw) + Z(jw)^H)/2`` for a real-rational square ``Z``, in ``x``.

    >>> Z = RationalMatrix.from_sympy(sp.Matrix([[1/(S_SYM + 1)]]))
    >>> str(hermitian_minors(Z).minors[(0,)])       # Re 1/(1 + jw) = 1/(1 + x); scale 1 + x
    '1'
    """
    n, m = Z.shape
    if n != m:
        raise ValueError("the Hermitian part needs a square matrix")
    P, L = Z.polynomial()
    Lm = _reflect(L)
    # 2 Phi(s) L(s) L(-s) = P(s) L(-s) + P(-s)^T L(s), since P(-s) = L(-s) Z(-s)
    Phi = [[(P[i][j] * Lm + _reflect(P[j][i]) * L) / 2 for j in range(n)] for i in range(n)]
    scale2 = L * Lm  # = |L(jw)|^2 on the axis
    return minors_from_polynomial_matrix(Phi, scale2, "s")


# ---------------------------------------------------------------------------------------------
# decisions on [0, oo)
# ---------------------------------------------------------------------------------------------


def _negative_interval(p: flint.fmpq_poly, lo: Any, hi: Any) -> tuple[flint.fmpq, flint.fmpq | None] | None:
    """An open interval ``(a, b)`` inside ``[lo, hi]`` (``hi`` None: unbounded) on which ``p < 0``.

    The real roots of the squarefree part are isolated and refined to a small relative width;
    ``p`` has constant sign on each gap between consecutive isolating intervals.
    """
    if p.is_zero():
        return None
    lo_q = as_fmpq(lo)
    hi_q = None if hi is None else as_fmpq(hi)
    sqf = flint.fmpq_poly(1)
    for f, _ in p.numer().factor_squarefree()[1]:
        sqf *= flint.fmpq_poly(f)
    roots = []
    for r in real_roots(sqf, lo_q, hi_q):
        scale = abs(r.lo) + abs(r.hi) + 1
        roots.append(r.refine(scale / 10**6))
    edges: list[tuple[flint.fmpq, flint.fmpq | None]] = []
    left = lo_q
    for r in roots:
        if left < r.lo:
            edges.append((left, r.lo))
        left = r.hi
    if hi_q is None:
        edges.append((left, None))
    elif left < hi_q:
        edges.append((left, hi_q))
    for a, b in edges:
        mid = a + 1 if b is None else (a + b) / 2
        if p(mid) < 0:
            return a, b
    return None


def rational_frequency(p: flint.fmpq_poly, interval: tuple[flint.fmpq, flint.fmpq | None]) -> sp.Rational | None:
    """The simplest rational ``w`` (smallest denominator first) with ``p(w**2) < 0`` and ``w**2`` in
    the open ``interval`` of ``x`` where ``p < 0`` (exactly checked)."""
    a, b = interval
    lo = math.sqrt(max(float(a), 0.0))
    hi = math.sqrt(float(b)) if b is not None else 2 * lo + 1.0
    for den in (1, 2, 4, 5, 10, 20, 100, 1000, 10**4, 10**6, 10**9):
        start = math.floor(lo * den)
        for num in range(start, start + 4):
            w = Fraction(num, den)
            if not lo < w < hi and not (b is None and w > lo):
                continue
            q = flint.fmpq(w.numerator, w.denominator)
            x = q * q
            if x > a and (b is None or x < b) and p(x) < 0:
                return sp.Rational(w.numerator, w.denominator)
    return None


def decide_nonnegative(p: flint.fmpq_poly, what: str = "polynomial") -> Outcome:
    """Exact decision of ``p(x) >= 0`` on ``[0, oo)`` with a rational witness ``x`` (and a rational
    frequency ``w`` when one is found quickly).

    >>> decide_nonnegative(flint.fmpq_poly([1, -2, 1])).decision.value      # (x - 1)**2
    'proved'
    >>> out = decide_nonnegative(flint.fmpq_poly([-1, 1]))                   # x - 1
    >>> out.decision.value, out.witness['x'] < 1
    ('disproved', True)
    """
    if p.is_zero():
        return Outcome(Decision.PROVED, Evidence(Method.CANONICAL_FORM, facts={what: "identically 0"}),
                       f"{what} is identically zero")
    gap = _negative_interval(p, 0, None)
    if gap is None:
        touches = [r for r in real_roots(p, 0, None)]
        facts = {"zeros_in_x": [str(r) for r in touches]} if touches else {}
        return Outcome(Decision.PROVED, Evidence(Method.ROOT_ISOLATION, facts=facts),
                       f"{what} >= 0 for all x = w^2 >= 0")
    a, b = gap
    x0 = (a + b) / 2 if b is not None else a + 1
    witness: dict[str, Any] = {"x": to_rational(x0)}
    w = rational_frequency(p, gap)
    if w is not None:
        witness["omega"] = w
        witness["x"] = w**2
    value = to_rational(p(as_fmpq(witness["x"])))
    return Outcome(Decision.DISPROVED, Evidence(Method.ROOT_ISOLATION, witness=witness, facts={f"{what}(x)": value}),
                   f"{what} < 0 at x = {witness['x']}")


def decide_psd(minors: HermitianMinors, method: str = "charpoly") -> Outcome:
    """Decide exactly whether the Hermitian matrix function is PSD for every ``w`` (every ``x >= 0``).

    ``method='charpoly'`` decides the ``n`` characteristic-polynomial coefficients ``E_k``
    (sums of principal minors of order ``k``); ``'principal'`` decides every principal minor.
    Both are necessary and sufficient; the leading minors alone are not. A disproof carries a
    rational ``x`` (and ``w`` when rational) and the exact negative minors there.
    """
    if method not in ("charpoly", "principal"):
        raise ValueError("method must be 'charpoly' or 'principal'")
    items = (
        [((k,), minors.coefficient(k)) for k in range(1, minors.n + 1)]
        if method == "charpoly"
        else [(subset, value) for subset, value in sorted(minors.minors.items(), key=lambda kv: (len(kv[0]), kv[0]))]
    )
    for key, poly in items:
        label = f"E_{key[0]}" if method == "charpoly" else f"minor{list(key)}"
        out = decide_nonnegative(poly, label)
        if out.decision == Decision.DISPROVED:
            x0 = out.witness["x"]
            negative = {}
            try:
                for subset in minors.minors:
                    value = minors.true_minor(subset, x0)
                    if value < 0:
                        negative[str(list(subset))] = value
            except ZeroDivisionError:
                pass
            facts = dict(out.evidence.facts)
            facts["negative_principal_minors"] = negative
            return Outcome(Decision.DISPROVED, Evidence(Method.ROOT_ISOLATION, witness=out.witness, facts=facts),
                           f"the Hermitian part is not PSD at x = w^2 = {x0} ({label} < 0)")
    return Outcome(Decision.PROVED,
                   Evidence(Method.ROOT_ISOLATION, facts={"method": method, "checked": len(items)}),
                   f"the Hermitian part is PSD for every real w ({len(items)} polynomials in x = w^2 decided)")


def matrix_psd(M: sp.Matrix) -> tuple[bool, dict[str, Any]]:
    """Exact PSD test of a constant Hermitian SymPy matrix by all principal minors.

    >>> matrix_psd(sp.Matrix([[0, 0], [0, -1]]))[0]      # leading minors 0, 0 but not PSD
    False
    """
    n = M.rows
    bad = {}
    for k in range(1, n + 1):
        for subset in itertools.combinations(range(n), k):
            value = sp.nsimplify(sp.expand(M.extract(list(subset), list(subset)).det()))
            value = sp.simplify(value)
            if value.is_negative or (value.is_real is not False and value.is_number and sp.N(value, 50) < 0):
                bad[str(list(subset))] = value
    return (not bad), bad


# ---------------------------------------------------------------------------------------------
# poles
# ---------------------------------------------------------------------------------------------


def _axis_parts(p: flint.fmpq_poly) -> tuple[flint.fmpq_poly, flint.fmpq_poly]:
    """``p(jw) = pr(w) + j pi(w)`` with real polynomials ``pr, pi`` in ``w``."""
    re_c, im_c = [], []
    for k, c in enumerate(p.coeffs()):
        unit = [1, 1j, -1, -1j][k % 4]
        if unit.real:
            re_c.append((k, c * int(unit.real)))
        else:
            im_c.append((k, c * int(unit.imag)))
    def build(terms):
        if not terms:
            return _ZERO
        coeffs = [flint.fmpq(0)] * (max(k for k, _ in terms) + 1)
        for k, c in terms:
            coeffs[k] = c
        return flint.fmpq_poly(coeffs)
    return build(re_c), build(im_c)


@dataclass(frozen=True, slots=True)
class AxisPole:
    """A pole on the imaginary axis: ``kind`` ``'zero'`` (s = 0), ``'pair'`` (``s**2 + a``, a > 0
    rational), ``'other'`` (an irreducible even factor of higher degree) or ``'infinity'``."""

    kind: str
    a: sp.Rational | None = None
    factor: str = ""

    def label(self) -> str:
        if self.kind == "zero":
            return "s = 0"
        if self.kind == "pair":
            return f"s = +-j*sqrt({self.a})"
        if self.kind == "infinity":
            return "s = oo"
        return f"roots of {self.factor}"


def _axis_factors(den: flint.fmpq_poly) -> list[tuple[flint.fmpz_poly, int]]:
    """Irreducible factors of ``den`` (with multiplicity) whose roots lie on the imaginary axis."""
    if den.degree() <= 0:
        return []
    pr, pi = _axis_parts(den)
    g = pr.gcd(pi) if not pi.is_zero() else pr
    if g.degree() <= 0:
        return []
    out = []
    _, factors = den.numer().factor()
    for f, mult in factors:
        fq = flint.fmpq_poly(f)
        fr, fi = _axis_parts(fq)
        gf = fr.gcd(fi) if not fi.is_zero() else fr
        if gf.degree() > 0:
            out.append((f, mult))
    return out


def rhp_roots(p: flint.fmpq_poly, prec: int = 64) -> list[tuple[Any, int]]:
    """Roots of ``p`` in the open right half plane, certified (acb balls with Re > 0).

    Imaginary-axis roots are removed exactly first, so every other root's real part is nonzero
    and ball arithmetic decides its sign after enough refinement.

    >>> [float(r.real.mid()) for r, m in rhp_roots(flint.fmpq_poly([-2, 1, 1]))]   # (s - 1)(s + 2)
    [1.0]
    """
    if p.degree() <= 0:
        return []
    core = p.numer()
    for f, mult in _axis_factors(p):
        for _ in range(mult):
            core = core // f
    if core.degree() <= 0:
        return []
    old = flint.ctx.prec
    try:
        precision = prec
        while True:
            flint.ctx.prec = precision
            roots = core.complex_roots()
            if all(r.real > 0 or r.real < 0 for r, _ in roots):
                return [(r, m) for r, m in roots if r.real > 0]
            precision *= 2
            if precision > 1 << 16:  # pragma: no cover - would need a root on the axis
                raise ArithmeticError("could not separate roots from the imaginary axis")
    finally:
        flint.ctx.prec = old


@dataclass(frozen=True, slots=True)
class PoleReport:
    """Where the poles of a rational matrix lie.

    ``rhp`` lists ``(entry, approximate root)`` for certified open-RHP poles; ``axis`` maps each
    imaginary-axis pole to its maximal multiplicity over the entries; ``improper`` the largest
    excess ``deg num - deg den`` (a pole at infinity of that order when positive).
    """

    rhp: tuple[tuple[tuple[int, int], complex], ...]
    axis: tuple[tuple[AxisPole, int], ...]
    improper: int

    @property
    def stable(self) -> bool:
        return not self.rhp

    @property
    def axis_simple(self) -> bool:
        return all(m == 1 for _, m in self.axis) and self.improper <= 1


def pole_report(Z: RationalMatrix) -> PoleReport:
    """Poles of every entry: certified RHP poles, exact imaginary-axis poles, pole at infinity.

    >>> Z = RationalMatrix.from_sympy(sp.Matrix([[1/S_SYM, 1/(S_SYM**2 + 4)], [0, S_SYM]]))
    >>> rep = pole_report(Z)
    >>> [(p.label(), m) for p, m in rep.axis], rep.improper, rep.stable
    ([('s = 0', 1), ('s = +-j*sqrt(4)', 1)], 1, True)
    """
    rhp = []
    axis: dict[str, tuple[AxisPole, int]] = {}
    improper = -(10**9)
    n, m = Z.shape
    seen_dens: dict[str, tuple[list, list]] = {}
    for i in range(n):
        for j in range(m):
            e = Z.rows[i][j]
            if e.is_zero():
                continue
            improper = max(improper, e.num.degree() - e.den.degree())
            key = str(e.den)
            if key not in seen_dens:
                roots = [(complex(float(r.real.mid()), float(r.imag.mid()))) for r, _ in rhp_roots(e.den)]
                axes = []
                for f, mult in _axis_factors(e.den):
                    fq = flint.fmpq_poly(f)
                    if f.degree() == 1:
                        pole = AxisPole("zero")
                    elif f.degree() == 2 and f.coeffs()[1] == 0:
                        c0, _, c2 = f.coeffs()
                        pole = AxisPole("pair", sp.Rational(int(c0), int(c2)))
                    else:
                        pole = AxisPole("other", factor=str(fq))
                    axes.append((pole, mult))
                seen_dens[key] = (roots, axes)
            roots, axes = seen_dens[key]
            for r in roots:
                rhp.append(((i, j), r))
            for pole, mult in axes:
                label = pole.label()
                if label not in axis or axis[label][1] < mult:
                    axis[label] = (pole, mult)
    return PoleReport(tuple(rhp), tuple(axis.values()), max(improper, 0) if improper > -(10**9) else 0)


# ---------------------------------------------------------------------------------------------
# exact minimum of a rational function on [0, oo)
# ---------------------------------------------------------------------------------------------


@dataclass(frozen=True, slots=True)
class HalflineMinimum:
    """Minimum of ``num/den`` over ``x >= 0``: ``argmin`` is a rational, a RealRoot or ``oo``
    (the infimum is the limit at infinity); ``value`` is an arb ball; ``exact`` when rational."""

    argmin: Any
    value: Any
    exact: sp.Expr | None

    def argmin_float(self) -> float:
        if self.argmin == sp.oo:
            return math.inf
        if hasattr(self.argmin, "approx"):
            return float(self.argmin.approx(17))
        return float(self.argmin)


def minimise_halfline(num: flint.fmpq_poly, den: flint.fmpq_poly, bits: int = 128) -> HalflineMinimum:
    """Exact minimiser of ``num(x)/den(x)`` on ``[0, oo)``; ``den`` must not vanish there.

    Candidates: ``x = 0``, the real roots of ``num' den - num den'`` in ``(0, oo)`` and the limit
    at infinity; they are compared with certified ball arithmetic.

    >>> m = minimise_halfline(flint.fmpq_poly([1, -2, 1]), flint.fmpq_poly([1, 0, 1]))  # (x-1)^2/(x^2+1)
    >>> m.argmin, m.exact
    (1, 0)
    """
    if den.is_zero():
        raise ZeroDivisionError("zero denominator")
    if den.degree() > 0 and real_roots(den, 0, None):
        raise ValueError("the denominator vanishes on [0, oo)")
    deriv = num.derivative() * den - num * den.derivative()
    candidates: list[Any] = [flint.fmpq(0)]
    if not deriv.is_zero() and deriv.degree() > 0:
        for r in real_roots(deriv, 0, None):
            candidates.append(r.lo if r.is_exact else r)
    # limit at infinity
    dn, dd = num.degree() if not num.is_zero() else -1, den.degree()
    if num.is_zero():
        limit = flint.arb(0)
    elif dn < dd:
        limit = flint.arb(0)
    elif dn == dd:
        limit = flint.arb(num.coeffs()[-1] / den.coeffs()[-1])
    else:
        lead = num.coeffs()[-1] / den.coeffs()[-1]
        limit = flint.arb("inf") if lead > 0 else flint.arb("-inf")
    old = flint.ctx.prec
    try:
        prec = 64
        while True:
            flint.ctx.prec = prec + 32
            values = []
            for cand in candidates:
                point = cand.ball(prec) if hasattr(cand, "ball") else flint.arb(cand)
                values.append(num.numer()(point) / flint.arb(num.denom()) / (den.numer()(point) / flint.arb(den.denom())))
            values.append(limit)
            finite = [v for v in values if v.is_finite()]
            best = min(range(len(values)), key=lambda i: values[i].mid() if values[i].is_finite() else (math.inf if values[i] > 0 else -math.inf))
            decided = all(i == best or not (values[i] < values[best]) for i in range(len(values)))
            if (decided and (not values[best].is_finite() or values[best].rad() < flint.arb(2) ** (-bits // 2))) or prec > 4 * bits or not finite:
                break
            prec *= 2
    finally:
        flint.ctx.prec = old
    if best == len(candidates):
        return HalflineMinimum(sp.oo, values[best], None)
    chosen = candidates[best]
    if hasattr(chosen, "ball"):
        return HalflineMinimum(chosen, values[best], None)
    q = chosen
    return HalflineMinimum(to_rational(q), values[best], to_rational(num(q) / den(q)))
