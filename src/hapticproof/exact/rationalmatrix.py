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
  (:func:`decide_psd`). Every sign question goes to the decision kernel
  (:mod:`hapticproof.exact.kernel`), which answers with a certificate that the independent checker
  re-verifies; a disproof carries a rational frequency ``w`` and the exact matrix there.
* **Poles.** One root certificate of the lcm of the denominators places every pole: exact
  imaginary-axis roots with multiplicities, a certified count in ``Re s > 0``
  (:func:`pole_report`, :func:`hapticproof.exact.kernel.locate_roots`).

>>> import sympy as sp
>>> from hapticproof.core.symbols import s
>>> Z = RationalMatrix.from_sympy(sp.Matrix([[1/(s + 1), 0], [0, 2/(s + 2)]]))
>>> minors = hermitian_minors(Z)
>>> decide_psd(minors).decision.value
'proved'
"""

from __future__ import annotations

import itertools
import math
from collections.abc import Callable, Iterable, Mapping, Sequence
from dataclasses import dataclass
from typing import Any

import flint
import sympy as sp

from hapticproof.exact import kernel
from hapticproof.exact.canonical import canonical_fraction
from hapticproof.core.errors import InputFormatError
from hapticproof.core.evidence import Decision, Evidence, Method, Outcome
from hapticproof.exact.kernel import BoundaryRoot, RootCertificate, locate_roots, poly_json
from hapticproof.exact.realroots import as_fmpq, real_roots, to_rational
from hapticproof.core.symbols import s as S_SYM

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
    "constant_psd",
    "AxisPole",
    "PoleReport",
    "pole_report",
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

    def axis_value(self, omega: Any) -> tuple[flint.fmpq, flint.fmpq]:
        """Exact ``(Re, Im)`` of ``f(j w)`` at a rational ``w`` (``ZeroDivisionError`` at a pole).

        >>> RationalFunction.from_sympy(1/(S_SYM + 1)).axis_value(1)      # 1/(1 + j) = (1 - j)/2
        (1/2, -1/2)
        """
        w = as_fmpq(omega)
        nr, ni = (part(w) for part in axis_parts(self.num))
        dr, di = (part(w) for part in axis_parts(self.den))
        mod2 = dr * dr + di * di
        if mod2 == 0:
            raise ZeroDivisionError(f"pole at s = j*{omega}")
        return (nr * dr + ni * di) / mod2, (ni * dr - nr * di) / mod2

    def axis_form(self) -> tuple[flint.fmpq_poly, flint.fmpq_poly, flint.fmpq_poly]:
        """``(a, b, d)``: polynomials in ``x = w**2`` with ``Re f(jw) = a/d``, ``Im f(jw) = w b/d``
        and ``d = |den(jw)|**2 >= 0`` (zero only at imaginary-axis poles).

        >>> a, b, d = RationalFunction.from_sympy(9/(S_SYM + 3)).axis_form()
        >>> [p.coeffs() for p in (a, b, d)]            # Re = 27/(x + 9), Im = -9 w/(x + 9)
        [[27], [-9], [9, 1]]
        """
        nr, ni = axis_parts(self.num)
        dr, di = axis_parts(self.den)
        even = nr * dr + ni * di
        odd = ni * dr - nr * di
        d = dr * dr + di * di
        odd_over_w = flint.fmpq_poly(odd.coeffs()[1:]) if not odd.is_zero() else _ZERO
        return even_to_x(even, "omega"), even_to_x(odd_over_w, "omega"), even_to_x(d, "omega")

    def to_json(self) -> dict[str, list[str]]:
        """``{'num': [...], 'den': [...]}``: exact coefficients, lowest degree first."""
        return {"num": poly_json(self.num), "den": poly_json(self.den)}

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

    def axis_value(self, omega: Any) -> sp.Matrix:
        """The exact matrix ``Z(j w)`` at a rational ``w`` (Gaussian rationals)."""
        out = []
        for row in self.rows:
            values = []
            for e in row:
                re, im = e.axis_value(omega)
                values.append(to_rational(re) + sp.I * to_rational(im))
            out.append(values)
        return sp.Matrix(out)

    def hermitian_at(self, omega: Any) -> sp.Matrix:
        """``Z(jw) + Z(jw)^H`` exactly at a rational ``w``.

        >>> RationalMatrix.from_sympy(sp.Matrix([[1, 3], [0, 1]])).hermitian_at(1)
        Matrix([
        [2, 3],
        [3, 2]])
        """
        M = self.axis_value(omega)
        return (M + M.H).applyfunc(sp.expand)

    def transfer_json(self) -> dict[str, Any]:
        """The matrix for the independent checker: ``{'variable': 's', 'entries': [[{num, den}]]}``."""
        return {"variable": "s", "entries": [[e.to_json() for e in row] for row in self.rows]}

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
    from hapticproof.core.limits import check_minors

    n = len(rows)
    orders = range(1, n + 1) if orders is None else orders
    check_minors(n, "principal minors", orders)         # counted before one is computed
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
    minor is defined. ``evaluate`` (optional) returns the exact matrix ``Z(jw) + Z(jw)^H`` at a
    witness ``{'x', 'omega'}`` and ``transfer`` the original matrix for the independent checker
    (:func:`hapticproof.exact.kernel.decide_psd`).
    """

    n: int
    minors: Mapping[tuple[int, ...], flint.fmpq_poly]
    scale: Mapping[int, flint.fmpq_poly]
    evaluate: Callable[[Mapping[str, Any]], sp.Matrix | None] | None = None
    transfer: Mapping[str, Any] | None = None

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
    P: Sequence[Sequence[flint.fmpq_poly]], scale: flint.fmpq_poly, variable: str,
    evaluate: Callable[[Mapping[str, Any]], sp.Matrix | None] | None = None,
    transfer: Mapping[str, Any] | None = None,
) -> HermitianMinors:
    """Hermitian minors from a polynomial matrix ``P = scale * H`` whose minors are even in
    ``variable`` (``'s'`` for a para-Hermitian ``Phi(s)``, ``'omega'`` for a real symmetric
    matrix function of ``w``); ``scale`` is the (even) scalar, >= 0 on the axis."""
    n = len(P)
    raw = principal_minors(P)
    minors = {k: even_to_x(v, variable) for k, v in raw.items()}
    base = even_to_x(scale, variable)
    return HermitianMinors(n, minors, {k: base**k for k in range(1, n + 1)}, evaluate, transfer)


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
    return minors_from_polynomial_matrix(Phi, scale2, "s", evaluate=_hermitian_evaluator(Z), transfer=Z.transfer_json())


def _hermitian_evaluator(Z: RationalMatrix) -> Callable[[Mapping[str, Any]], sp.Matrix | None]:
    def evaluate(witness: Mapping[str, Any]) -> sp.Matrix | None:
        if "omega" not in witness:
            return None
        try:
            return Z.hermitian_at(witness["omega"])
        except ZeroDivisionError:  # pragma: no cover - a witness is never an axis pole
            return None

    return evaluate


# ---------------------------------------------------------------------------------------------
# decisions (all through the decision kernel, with certificates)
# ---------------------------------------------------------------------------------------------


def decide_psd(minors: HermitianMinors, what: str = "Z(jw) + Z(jw)^H") -> Outcome:
    """Decide exactly whether the Hermitian matrix function is PSD for every ``w`` (every ``x >= 0``).

    The ``n`` characteristic-polynomial coefficients ``E_k`` (sums of the principal minors of
    order ``k``, scaled by ``scale**k >= 0``) are decided by the decision kernel
    (:func:`hapticproof.exact.kernel.decide_psd`) on the whole half line ``[0, oo)`` -- ``x = 0``
    and the stretch before the first root included. Necessary and sufficient; the leading
    minors alone are not. A disproof carries a rational frequency ``w`` where some ``E_k < 0``,
    the exact matrix there and a negative principal minor; the certificate lets the independent
    checker re-verify it (:mod:`hapticproof.exact.checker`).

    >>> Z = RationalMatrix.from_sympy(sp.Matrix([[1 - 2/(S_SYM + 1) + 10/(S_SYM + 10**4)]]))
    >>> out = decide_psd(hermitian_minors(Z))          # Re Z(j0) = -0.999
    >>> out.decision.value, out.witness
    ('disproved', {'x': 0, 'omega': 0})
    """
    coefficients = [minors.coefficient(k) for k in range(1, minors.n + 1)]
    return kernel.decide_psd(coefficients, 0, None, "x", scale=minors.scale[1], evaluate=minors.evaluate,
                             transfer=minors.transfer, what=what)


def _real_embedding(M: sp.Matrix) -> tuple[flint.fmpq_mat, bool]:
    """``M`` (Gaussian-rational Hermitian) as a rational symmetric matrix with the same PSD-ness:
    ``M`` itself when real, else ``[[X, -Y], [Y, X]]`` for ``M = X + jY``."""
    n = M.rows
    re = [[as_fmpq(sp.re(M[i, j])) for j in range(n)] for i in range(n)]
    im = [[as_fmpq(sp.im(M[i, j])) for j in range(n)] for i in range(n)]
    if all(v == 0 for row in im for v in row):
        return flint.fmpq_mat(n, n, [v for row in re for v in row]), False
    big = [[re[i % n][j % n] if (i < n) == (j < n) else (-im[i][j - n] if i < n else im[i - n][j])
            for j in range(2 * n)] for i in range(2 * n)]
    return flint.fmpq_mat(2 * n, 2 * n, [v for row in big for v in row]), True


def constant_psd(M: Any, what: str = "the matrix") -> Outcome:
    """Exact PSD decision of a constant Hermitian matrix with (Gaussian) rational entries, through
    the decision kernel: its characteristic coefficients ``E_k`` are constants whose sign
    certificates the checker re-verifies; a disproof records the matrix and a negative
    principal minor. A complex ``M = X + jY`` is decided on ``[[X, -Y], [Y, X]]`` (same
    eigenvalues, each twice).

    >>> constant_psd(sp.Matrix([[0, 0], [0, -1]])).decision.value    # leading minors 0, 0: not PSD
    'disproved'
    >>> constant_psd(sp.Matrix([[1, sp.I], [-sp.I, 1]])).decision.value
    'proved'
    """
    M = sp.Matrix(M)
    if M.rows != M.cols:
        raise ValueError("a PSD test needs a square matrix")
    if any(sp.simplify(M[i, j] - sp.conjugate(M[j, i])) != 0 for i in range(M.rows) for j in range(i, M.rows)):
        return Outcome(Decision.DISPROVED, Evidence(Method.CANONICAL_FORM, facts={"matrix": M}), f"{what} is not Hermitian")
    real, embedded = _real_embedding(M)
    size = real.nrows()
    char = real.charpoly().coeffs()          # det(l I - M) = sum c_i l^i
    coefficients = [flint.fmpq_poly([char[size - k] * (-1) ** k]) for k in range(1, size + 1)]
    matrix = sp.Matrix(size, size, lambda i, j: to_rational(real[i, j]))
    out = kernel.decide_psd(coefficients, 0, 1, "t", evaluate=lambda witness: matrix, what=what)
    facts = dict(out.evidence.facts)
    facts["matrix"] = M
    if embedded:
        facts["real_form"] = "[[Re M, -Im M], [Im M, Re M]]"
    if out.decision == Decision.PROVED:
        return Outcome(Decision.PROVED, Evidence(Method.CANONICAL_FORM, facts=facts), f"{what} is PSD (every E_k >= 0)")
    minor = facts.get("negative_principal_minor")
    return Outcome(Decision.DISPROVED, Evidence(Method.CANONICAL_FORM, witness={"negative_principal_minor": minor}, facts=facts),
                   f"{what} is not PSD" + (f" (principal minor {minor['rows']} = {minor['value']} < 0)" if minor else ""))


def matrix_psd(M: sp.Matrix) -> tuple[bool, dict[str, Any]]:
    """Exact PSD test of a constant Hermitian SymPy matrix: ``(holds, negative principal minors)``.

    (Gaussian) rational entries are decided by :func:`constant_psd` (the decision kernel);
    algebraic entries (square roots of Youla's ``Z'``), which the rational kernel cannot take,
    by exact SymPy principal minors.

    >>> matrix_psd(sp.Matrix([[0, 0], [0, -1]]))[0]      # leading minors 0, 0 but not PSD
    False
    >>> matrix_psd(sp.Matrix([[1, sp.sqrt(2)], [sp.sqrt(2), 2]]))[0]
    True
    """
    M = sp.Matrix(M)
    if all(sp.re(v).is_Rational and sp.im(v).is_Rational for v in M):
        out = constant_psd(M)
        if out.decision == Decision.PROVED:
            return True, {}
        minor = out.evidence.facts.get("negative_principal_minor")
        return False, ({str([i - 1 for i in minor["rows"]]): minor["value"]} if minor else {"hermitian": False})
    from hapticproof.core.limits import check_minors

    n = M.rows
    check_minors(n, "principal minors")
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


def axis_parts(p: flint.fmpq_poly) -> tuple[flint.fmpq_poly, flint.fmpq_poly]:
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


def _axis_pole(root: BoundaryRoot) -> AxisPole:
    f = root.factor
    if root.value is not None:
        return AxisPole("zero")
    coeffs = f.coeffs()
    if f.degree() == 2 and coeffs[1] == 0:
        return AxisPole("pair", sp.Rational(int(coeffs[0]), int(coeffs[2])))
    return AxisPole("other", factor=str(flint.fmpq_poly(f)))


@dataclass(frozen=True, slots=True)
class PoleReport:
    """Where the poles of a rational matrix lie.

    ``rhp`` lists ``(entry, approximate root)`` for certified open-RHP poles; ``axis`` maps each
    imaginary-axis pole to its maximal multiplicity over the entries; ``improper`` the largest
    excess ``deg num - deg den`` (a pole at infinity of that order when positive);
    ``certificate`` is the decision kernel's root certificate of the lcm of the denominators
    (:func:`hapticproof.exact.kernel.locate_roots`, re-verified by Routh-Hurwitz in the checker).
    """

    rhp: tuple[tuple[tuple[int, int], complex], ...]
    axis: tuple[tuple[AxisPole, int], ...]
    improper: int
    certificate: RootCertificate | None = None
    #: the kernel's decision at ``s = oo`` (:func:`hapticproof.exact.infinity.decide_infinity`):
    #: at most a simple pole with a Hermitian PSD residue, with an exact witness when not
    infinity: Any = None

    @property
    def stable(self) -> bool:
        return not self.rhp

    @property
    def axis_simple(self) -> bool:
        return all(m == 1 for _, m in self.axis) and self.improper <= 1


def pole_report(Z: RationalMatrix) -> PoleReport:
    """Poles of every entry: certified RHP poles, exact imaginary-axis poles, pole at infinity.

    One root certificate of the lcm ``L`` of the entry denominators decides them all (an
    axis pole's multiplicity in ``L`` is its largest multiplicity in an entry).

    >>> Z = RationalMatrix.from_sympy(sp.Matrix([[1/S_SYM, 1/(S_SYM**2 + 4)], [0, S_SYM]]))
    >>> rep = pole_report(Z)
    >>> [(p.label(), m) for p, m in rep.axis], rep.improper, rep.stable
    ([('s = 0', 1), ('s = +-j*sqrt(4)', 1)], 1, True)
    """
    from hapticproof.exact.infinity import decide_infinity

    n, m = Z.shape
    improper = max((e.num.degree() - e.den.degree() for row in Z.rows for e in row if not e.is_zero()), default=0)
    infinity = decide_infinity([[(e.num, e.den) for e in row] for row in Z.rows], "halfplane", "Z") if n == m else None
    L = Z.denominator_lcm()
    if L.degree() <= 0:
        return PoleReport((), (), max(improper, 0), None, infinity)
    cert = locate_roots(L, "halfplane")
    rhp: list[tuple[tuple[int, int], complex]] = []
    if cert.outside:
        seen: dict[str, tuple[complex, ...]] = {}
        for i in range(n):
            for j in range(m):
                e = Z.rows[i][j]
                if e.den.degree() <= 0:
                    continue
                key = str(e.den)
                if key not in seen:
                    seen[key] = locate_roots(e.den, "halfplane").outside_points
                rhp += [((i, j), complex(p)) for p in seen[key]]
    axis: dict[str, tuple[AxisPole, int]] = {}
    for r in sorted(cert.boundary, key=lambda r: (r.value is None, r.factor.degree(), str(r.factor))):
        pole = _axis_pole(r)
        if pole.label() not in axis or axis[pole.label()][1] < r.multiplicity:
            axis[pole.label()] = (pole, r.multiplicity)
    return PoleReport(tuple(rhp), tuple(axis.values()), max(improper, 0), cert, infinity)


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
