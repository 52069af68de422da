r"""The one exact transfer matrix: rational functions of ``z`` or ``s`` over Q or Q(parameters).

A :class:`TransferMatrix` is a matrix (a scalar is 1 x 1) of :class:`~hapticproof.exact.rational.RationalFunction`
entries in a transfer variable -- ``z`` (discrete time: the unit circle is the boundary) or ``s``
(continuous time: the imaginary axis) -- and any number of named parameters. Like python-control's
``LTI`` objects it carries its own structure as methods (:meth:`~TransferMatrix.poles`,
:meth:`~TransferMatrix.excess`, :meth:`~TransferMatrix.on_boundary`, :meth:`~TransferMatrix.hermitian`,
:meth:`~TransferMatrix.inverse`, ...), and it converts to and from SymPy, python-control and JSON.

The transfer variable has an internal name (``$z`` or ``$s``, see :mod:`~hapticproof.exact.boundaryvalue`),
so a parameter may be called ``z``, ``s``, ``c`` or ``x`` without meaning anything more.

>>> import sympy as sp
>>> K, B, T, b, z = sp.symbols("K B T b z")
>>> H = TransferMatrix.from_sympy(K + B*(z - 1)/(T*z), z)
>>> Ginv = b + H * TransferMatrix.from_sympy(T/(z - 1), z)            # forward difference
>>> Ginv.to_sympy({"z": z})
(B*z - B + K*T*z + b*z**2 - b*z)/(z**2 - z)
>>> Ginv.hermitian_part().to_sympy()                                   # Re G^-1 on the circle, c = cos(wT)
Matrix([[B*c - K*T/2 + b]])
>>> sorted(Ginv.parameters)
['B', 'K', 'T', 'b']
"""

from __future__ import annotations

from collections.abc import Iterable, Mapping, Sequence
from dataclasses import dataclass
from fractions import Fraction
from typing import Any

import flint
import sympy as sp

from hapticproof.exact.boundaryvalue import AXIS, C_NAME, CIRCLE, S_NAME, X_NAME, Z_NAME, BoundaryValue
from hapticproof.exact.rational import RationalFunction, as_fraction, to_fmpq

__all__ = ["TransferMatrix", "BoundaryMatrix", "VARIABLES", "DISCRETE", "CONTINUOUS"]

DISCRETE, CONTINUOUS = "discrete", "continuous"
#: The transfer variable's printed name for each time domain, and its internal name.
VARIABLES = {DISCRETE: ("z", Z_NAME), CONTINUOUS: ("s", S_NAME)}


def _domain_of(variable: str) -> str:
    if variable in ("z", Z_NAME, DISCRETE):
        return DISCRETE
    if variable in ("s", S_NAME, CONTINUOUS):
        return CONTINUOUS
    raise ValueError(f"the transfer variable is z (discrete) or s (continuous), not {variable!r}")


def _lcm(polys: Iterable[flint.fmpq_poly]) -> flint.fmpq_poly:
    out = flint.fmpq_poly([1])
    for p in polys:
        if p.degree() > 0:
            out = out * p / out.gcd(p)
    return out


@dataclass(frozen=True, slots=True)
class TransferMatrix:
    """An exact rational transfer matrix (see the module doc). ``domain`` is ``discrete``
    (variable ``z``) or ``continuous`` (variable ``s``); ``entries`` are rows of rational functions
    in the internal transfer variable and the parameters."""

    entries: tuple[tuple[RationalFunction, ...], ...]
    domain: str = DISCRETE

    def __post_init__(self) -> None:
        if self.domain not in (DISCRETE, CONTINUOUS):
            raise ValueError(f"domain must be {DISCRETE!r} or {CONTINUOUS!r}")
        rows = tuple(tuple(self._entry(e) for e in row) for row in self.entries)
        if not rows or not rows[0] or any(len(r) != len(rows[0]) for r in rows):
            raise ValueError("a transfer matrix needs rows of one common, non-zero length")
        object.__setattr__(self, "entries", rows)

    @staticmethod
    def _entry(e: Any) -> RationalFunction:
        return e if isinstance(e, RationalFunction) else RationalFunction.constant(e)

    # -- construction ---------------------------------------------------------------------------

    @property
    def variable(self) -> str:
        """The internal name of the transfer variable (``$z`` or ``$s``)."""
        return VARIABLES[self.domain][1]

    @classmethod
    def scalar(cls, value: RationalFunction | Any, domain: str = DISCRETE) -> TransferMatrix:
        return cls(((value,),), domain)

    @classmethod
    def identity(cls, n: int, domain: str = DISCRETE) -> TransferMatrix:
        return cls(tuple(tuple(1 if i == j else 0 for j in range(n)) for i in range(n)), domain)

    @classmethod
    def transfer_variable(cls, domain: str = DISCRETE) -> TransferMatrix:
        """``z`` or ``s`` itself, as a 1 x 1 matrix."""
        return cls.scalar(RationalFunction.variable(VARIABLES[domain][1]), domain)

    @classmethod
    def from_sympy(cls, value: Any, variable: Any = "z") -> TransferMatrix:
        """A SymPy expression or matrix in ``variable`` (a symbol or its name, ``z`` or ``s``).

        Other symbols are parameters, known by name. A coefficient that is not an exact rational
        function (a float, ``sqrt(2)``, ``exp(-s)``) is refused (:class:`~hapticproof.exact.rational.NotRationalError`).

        >>> s = sp.Symbol("s")
        >>> TransferMatrix.from_sympy(sp.Matrix([[1/(s + 1), 0], [0, s]]), s).shape
        (2, 2)
        """
        name = variable.name if isinstance(variable, sp.Symbol) else str(variable)
        domain = _domain_of(name)
        internal = VARIABLES[domain][1]
        matrix = value if isinstance(value, sp.MatrixBase) else sp.Matrix([[sp.sympify(value)]])
        rename = {sym: sp.Symbol(internal) for sym in matrix.free_symbols if sym.name == name}
        rows = []
        for i in range(matrix.rows):
            rows.append(tuple(RationalFunction.from_sympy(matrix[i, j].xreplace(rename)) for j in range(matrix.cols)))
        return cls(tuple(rows), domain)

    @classmethod
    def from_polynomials(cls, entries: Sequence[Sequence[tuple[flint.fmpq_poly, flint.fmpq_poly]]], domain: str = DISCRETE
                         ) -> TransferMatrix:
        """Numeric entries given as ``(num, den)`` pairs of ``flint.fmpq_poly``."""
        name = VARIABLES[domain][1]
        return cls(tuple(tuple(RationalFunction.from_polynomials(n, d, name) for n, d in row) for row in entries), domain)

    # -- structure ------------------------------------------------------------------------------

    @property
    def shape(self) -> tuple[int, int]:
        return len(self.entries), len(self.entries[0])

    @property
    def is_scalar(self) -> bool:
        return self.shape == (1, 1)

    @property
    def is_square(self) -> bool:
        return self.shape[0] == self.shape[1]

    def __getitem__(self, index: tuple[int, int]) -> RationalFunction:
        i, j = index
        return self.entries[i][j]

    def scalar_value(self) -> RationalFunction:
        if not self.is_scalar:
            raise ValueError(f"a {self.shape[0]} x {self.shape[1]} matrix is not a scalar")
        return self.entries[0][0]

    @property
    def parameters(self) -> frozenset[str]:
        """The parameter names the entries depend on (the transfer variable excluded)."""
        out: set[str] = set()
        for row in self.entries:
            for e in row:
                out |= e.names
        return frozenset(out - {self.variable})

    @property
    def is_numeric(self) -> bool:
        """No parameters: every coefficient is a rational number."""
        return not self.parameters

    def polynomials(self) -> tuple[tuple[tuple[flint.fmpq_poly, flint.fmpq_poly], ...], ...]:
        """Entries of a numeric matrix as coprime ``(num, den)`` pairs of ``flint.fmpq_poly`` (``den`` monic)."""
        if not self.is_numeric:
            raise ValueError(f"the matrix has parameters ({', '.join(sorted(self.parameters))}): give them values first")
        return tuple(tuple(e.univariate(self.variable) for e in row) for row in self.entries)

    def denominator(self) -> flint.fmpq_poly:
        """The least common multiple of the entries' denominators (numeric matrices), monic."""
        return _lcm(d for row in self.polynomials() for _, d in row)

    def excess(self) -> int:
        """``max over entries of deg num - deg den``: ``> 0`` means a pole at infinity
        (improper); generic degrees when there are parameters (a leading coefficient that
        vanishes for special values is the caller's question).

        >>> z = sp.Symbol("z")
        >>> TransferMatrix.from_sympy(z**2/(z - 1), z).excess(), TransferMatrix.from_sympy(1/(z - 1), z).excess()
        (1, -1)
        """
        out = None
        for row in self.entries:
            for e in row:
                if e.is_zero:
                    continue
                n, d = e.degrees(self.variable)
                out = n - d if out is None else max(out, n - d)
        return out if out is not None else -(10 ** 9)

    # -- algebra ----------------------------------------------------------------------------------

    def _other(self, other: Any) -> TransferMatrix:
        if isinstance(other, TransferMatrix):
            if other.domain != self.domain:
                raise ValueError("a discrete and a continuous transfer matrix do not combine")
            return other
        if isinstance(other, RationalFunction):
            value = other
        elif isinstance(other, sp.Basic):
            return TransferMatrix.from_sympy(other, VARIABLES[self.domain][0])
        else:
            value = RationalFunction.constant(other)
        n = self.shape[0] if self.is_square else 1
        if n == 1:
            return TransferMatrix.scalar(value, self.domain)
        return TransferMatrix(tuple(tuple(value if i == j else 0 for j in range(n)) for i in range(n)), self.domain)

    def _broadcast(self, other: TransferMatrix) -> tuple[TransferMatrix, TransferMatrix]:
        if self.shape == other.shape:
            return self, other
        if other.is_scalar:
            return self, TransferMatrix(tuple(tuple(other.entries[0][0] if i == j else 0 for j in range(self.shape[1]))
                                              for i in range(self.shape[0])), self.domain)
        if self.is_scalar:
            return other._broadcast(self)[::-1]
        raise ValueError(f"shapes {self.shape} and {other.shape} do not match")

    def __add__(self, other: Any) -> TransferMatrix:
        a, b = self._broadcast(self._other(other))
        return TransferMatrix(tuple(tuple(x + y for x, y in zip(ra, rb)) for ra, rb in zip(a.entries, b.entries)), self.domain)

    __radd__ = __add__

    def __neg__(self) -> TransferMatrix:
        return TransferMatrix(tuple(tuple(-x for x in row) for row in self.entries), self.domain)

    def __sub__(self, other: Any) -> TransferMatrix:
        return self + (-self._other(other))

    def __rsub__(self, other: Any) -> TransferMatrix:
        return self._other(other) - self

    def __mul__(self, other: Any) -> TransferMatrix:
        o = self._other(other)
        if o.is_scalar and not self.is_scalar:
            v = o.entries[0][0]
            return TransferMatrix(tuple(tuple(x * v for x in row) for row in self.entries), self.domain)
        if self.is_scalar and not o.is_scalar:
            return o * self
        return self @ o

    __rmul__ = __mul__

    def __matmul__(self, other: TransferMatrix) -> TransferMatrix:
        o = self._other(other)
        n, k = self.shape
        k2, m = o.shape
        if k != k2:
            raise ValueError(f"cannot multiply a {n} x {k} by a {k2} x {m} matrix")
        rows = []
        for i in range(n):
            row = []
            for j in range(m):
                acc = RationalFunction.constant(0)
                for t in range(k):
                    a, b = self.entries[i][t], o.entries[t][j]
                    if not a.is_zero and not b.is_zero:
                        acc = acc + a * b
                row.append(acc)
            rows.append(tuple(row))
        return TransferMatrix(tuple(rows), self.domain)

    def __truediv__(self, other: Any) -> TransferMatrix:
        return self * self._other(other).inverse()

    def __rtruediv__(self, other: Any) -> TransferMatrix:
        return self._other(other) * self.inverse()

    def __pow__(self, k: int) -> TransferMatrix:
        if not self.is_square:
            raise ValueError("powers of a non-square matrix")
        if k < 0:
            return self.inverse() ** (-k)
        out = TransferMatrix.identity(self.shape[0], self.domain)
        for _ in range(k):
            out = out @ self
        return out

    def __eq__(self, other: object) -> bool:
        if not isinstance(other, TransferMatrix):
            return NotImplemented
        return self.domain == other.domain and self.entries == other.entries

    def __hash__(self) -> int:
        return hash((self.domain, self.entries))

    def transpose(self) -> TransferMatrix:
        return TransferMatrix(tuple(zip(*self.entries)), self.domain)

    def submatrix(self, rows: Sequence[int], cols: Sequence[int] | None = None) -> TransferMatrix:
        cols = rows if cols is None else cols
        return TransferMatrix(tuple(tuple(self.entries[i][j] for j in cols) for i in rows), self.domain)

    def determinant(self) -> RationalFunction:
        """The determinant, by fraction-free elimination over the field of rational functions."""
        if not self.is_square:
            raise ValueError("the determinant of a non-square matrix")
        a = [list(row) for row in self.entries]
        n = len(a)
        det = RationalFunction.constant(1)
        for k in range(n):
            pivot = next((i for i in range(k, n) if not a[i][k].is_zero), None)
            if pivot is None:
                return RationalFunction.constant(0)
            if pivot != k:
                a[k], a[pivot] = a[pivot], a[k]
                det = -det
            det = det * a[k][k]
            for i in range(k + 1, n):
                if a[i][k].is_zero:
                    continue
                f = a[i][k] / a[k][k]
                a[i] = [x - f * y for x, y in zip(a[i], a[k])]
        return det

    def inverse(self) -> TransferMatrix:
        """The inverse (Gauss-Jordan over the field; ``ZeroDivisionError`` when singular).

        >>> s = sp.Symbol("s")
        >>> TransferMatrix.from_sympy(sp.Matrix([[s, 1], [0, 2]]), s).inverse().to_sympy({"s": s})
        Matrix([
        [1/s, -1/(2*s)],
        [  0,      1/2]])
        """
        if not self.is_square:
            raise ValueError("the inverse of a non-square matrix")
        n = self.shape[0]
        a = [list(row) + [RationalFunction.constant(1 if i == j else 0) for j in range(n)] for i, row in enumerate(self.entries)]
        for k in range(n):
            pivot = next((i for i in range(k, n) if not a[i][k].is_zero), None)
            if pivot is None:
                raise ZeroDivisionError("the matrix is singular (its determinant is identically zero)")
            a[k], a[pivot] = a[pivot], a[k]
            p = a[k][k]
            a[k] = [x / p for x in a[k]]
            for i in range(n):
                if i != k and not a[i][k].is_zero:
                    f = a[i][k]
                    a[i] = [x - f * y for x, y in zip(a[i], a[k])]
        return TransferMatrix(tuple(tuple(row[n:]) for row in a), self.domain)

    def subs(self, values: Mapping[str, Any]) -> TransferMatrix:
        """Numbers or rational functions for parameters (by name)."""
        return TransferMatrix(tuple(tuple(e.subs(values) for e in row) for row in self.entries), self.domain)

    def paraconjugate(self) -> TransferMatrix:
        """``G(1/z)^T`` (discrete) or ``G(-s)^T`` (continuous): the adjoint on the boundary."""
        v = self.variable
        flip = (lambda e: e.reflect(v)) if self.domain == DISCRETE else (lambda e: e.mirror(v))
        return TransferMatrix(tuple(tuple(flip(e) for e in row) for row in zip(*self.entries)), self.domain)

    # -- the boundary -----------------------------------------------------------------------------

    def on_boundary(self) -> BoundaryMatrix:
        """Every entry at ``z = e^{j theta}`` or ``s = j omega`` (:class:`BoundaryMatrix`)."""
        boundary = CIRCLE if self.domain == DISCRETE else AXIS
        return BoundaryMatrix(tuple(tuple(BoundaryValue.evaluate(e, self.variable, boundary) for e in row)
                                    for row in self.entries))

    def hermitian_part(self) -> BoundaryMatrix:
        """``(G + G^H)/2`` on the boundary: real entries rational in ``c`` (``x``) on the diagonal,
        ``r`` times rational functions in the imaginary parts off it.

        The ``to_sympy`` of the result writes ``c = cos(theta)`` or ``x = omega^2``, ``r`` for
        ``sin(theta)`` or ``omega``."""
        if not self.is_square:
            raise ValueError("the Hermitian part of a non-square matrix")
        values = self.on_boundary().entries
        n = self.shape[0]
        half = RationalFunction.constant(Fraction(1, 2))
        return BoundaryMatrix(tuple(tuple((values[i][j] + values[j][i].conjugate()) * half for j in range(n)) for i in range(n)))

    # -- poles ------------------------------------------------------------------------------------

    def poles(self) -> Any:
        """Where the poles of a numeric matrix lie (the roots of :meth:`denominator`): the kernel's
        :class:`~hapticproof.exact.kernel.RootCertificate` (inside / on / outside the unit circle, or
        left / on / right of the imaginary axis, with boundary multiplicities)."""
        from hapticproof.exact.kernel import locate_roots

        return locate_roots(self.denominator(), "disk" if self.domain == DISCRETE else "halfplane")

    # -- evaluation -------------------------------------------------------------------------------

    def at(self, point: Any) -> list[list[Fraction]]:
        """Exact value at a rational point of a numeric matrix."""
        p = to_fmpq(point)
        out = []
        for row in self.polynomials():
            values = []
            for n, d in row:
                dv = d(p)
                if dv == 0:
                    raise ZeroDivisionError(f"{VARIABLES[self.domain][0]} = {point} is a pole")
                values.append(as_fraction(n(p) / dv))
            out.append(values)
        return out

    def at_gaussian(self, re: Fraction, im: Fraction) -> list[list[tuple[Fraction, Fraction]]]:
        """Exact value at ``re + j im`` of a numeric matrix, each entry as ``(Re, Im)``."""
        return [[e.gaussian(self.variable, Fraction(re), Fraction(im)) for e in row] for row in self.entries]

    # -- conversion -------------------------------------------------------------------------------

    def symbols(self, symbols: Mapping[str, sp.Symbol] | None = None) -> dict[str, sp.Symbol]:
        """The SymPy symbols of the conversion: the transfer variable as ``z`` or ``s`` unless
        ``symbols`` names it (by its printed name) otherwise."""
        symbols = dict(symbols or {})
        printed = VARIABLES[self.domain][0]
        out = {name: sym for name, sym in symbols.items() if name != printed}
        out[self.variable] = symbols.get(printed, sp.Symbol(printed))
        return out

    def to_sympy(self, symbols: Mapping[str, sp.Symbol] | None = None) -> Any:
        """A SymPy expression (1 x 1) or matrix; ``symbols`` maps names to SymPy symbols."""
        table = self.symbols(symbols)
        rows = [[e.to_sympy(table) for e in row] for row in self.entries]
        return rows[0][0] if self.is_scalar else sp.Matrix(rows)

    def to_json(self) -> dict[str, Any]:
        """Plain JSON: the domain and the entries (:meth:`RationalFunction.to_json`)."""
        return {"domain": self.domain, "entries": [[e.to_json() for e in row] for row in self.entries]}

    @classmethod
    def from_json(cls, data: Mapping[str, Any]) -> TransferMatrix:
        """Inverse of :meth:`to_json` (shapes checked).

        >>> z = sp.Symbol("z")
        >>> G = TransferMatrix.from_sympy((z + 1)/(z - sp.Rational(1, 2)), z)
        >>> TransferMatrix.from_json(G.to_json()) == G
        True
        """
        if not isinstance(data, Mapping) or data.get("domain") not in (DISCRETE, CONTINUOUS):
            raise ValueError("a transfer matrix needs a domain, 'discrete' or 'continuous'")
        rows = data.get("entries")
        if not isinstance(rows, list) or not rows or not all(isinstance(r, list) for r in rows):
            raise ValueError("a transfer matrix needs entries: a list of rows")
        return cls(tuple(tuple(RationalFunction.from_json(e) for e in row) for row in rows), data["domain"])

    def to_control(self, dt: Any = True) -> Any:
        """A python-control ``TransferFunction`` of a numeric matrix (floats: for simulation and
        plotting only; every decision here is made on the exact matrix). ``dt`` is the sampling
        period of a discrete matrix (``True``: unspecified)."""
        import control

        rows = self.polynomials()
        num = [[[float(as_fraction(a)) for a in reversed(n.coeffs())] or [0.0] for n, _ in row] for row in rows]
        den = [[[float(as_fraction(a)) for a in reversed(d.coeffs())] for _, d in row] for row in rows]
        if self.is_scalar:
            num, den = num[0][0], den[0][0]
        return control.tf(num, den, dt if self.domain == DISCRETE else 0)

    @classmethod
    def from_control(cls, sys: Any) -> TransferMatrix:
        """A python-control ``TransferFunction`` or ``StateSpace`` at the exact binary values of its
        float coefficients (a state space through its exact resolvent ``C (vI - A)^-1 B + D``).

        >>> import control
        >>> G = TransferMatrix.from_control(control.tf([1, 0.5], [1, -1], 0.001))
        >>> G.domain, G.to_sympy()
        ('discrete', (z + 1/2)/(z - 1))
        """
        domain = DISCRETE if getattr(sys, "dt", 0) not in (0, None) else CONTINUOUS
        if hasattr(sys, "A") and hasattr(sys, "B"):
            v = TransferMatrix.transfer_variable(domain)
            A = TransferMatrix(tuple(tuple(_float(x) for x in row) for row in sys.A), domain) if sys.A.size else None
            B = TransferMatrix(tuple(tuple(_float(x) for x in row) for row in sys.B), domain) if sys.B.size else None
            C = TransferMatrix(tuple(tuple(_float(x) for x in row) for row in sys.C), domain) if sys.C.size else None
            D = TransferMatrix(tuple(tuple(_float(x) for x in row) for row in sys.D), domain)
            if A is None:
                return D
            n = A.shape[0]
            resolvent = (TransferMatrix.identity(n, domain) * v.scalar_value() - A).inverse()
            return C @ resolvent @ B + D
        name = VARIABLES[domain][1]
        rows = []
        for i in range(len(sys.num)):
            row = []
            for j in range(len(sys.num[i])):
                num = [_float(x) for x in reversed(list(sys.num[i][j]))]
                den = [_float(x) for x in reversed(list(sys.den[i][j]))]
                row.append(RationalFunction.from_polynomials(num, den, name))
            rows.append(tuple(row))
        return cls(tuple(rows), domain)


def _float(x: Any) -> Fraction:
    """A float (or int) at its exact binary value; NaN and infinities are refused."""
    f = float(x)
    if f != f or f in (float("inf"), float("-inf")):
        raise ValueError(f"{x!r} is not a finite number")
    return Fraction(f)


@dataclass(frozen=True, slots=True)
class BoundaryMatrix:
    """A matrix of :class:`~hapticproof.exact.boundaryvalue.BoundaryValue` entries: a transfer
    matrix's values on the unit circle or the imaginary axis."""

    entries: tuple[tuple[BoundaryValue, ...], ...]

    @property
    def shape(self) -> tuple[int, int]:
        return len(self.entries), len(self.entries[0])

    @property
    def domain(self) -> str:
        return self.entries[0][0].domain

    def to_sympy(self, symbols: Mapping[str, sp.Symbol] | None = None) -> sp.Matrix:
        """Entries as SymPy expressions in ``c`` (or ``x``), ``r`` and ``I``."""
        table = dict(symbols or {})
        t = table.get("c" if self.domain == CIRCLE else "x") or sp.Symbol("c" if self.domain == CIRCLE else "x")
        r = table.get("r") or sp.Symbol("r")
        names = {**table, C_NAME: t, X_NAME: t}

        def one(v: BoundaryValue) -> sp.Expr:
            parts = [(v.re0, 1), (v.re1, r), (v.im0, sp.I), (v.im1, sp.I * r)]
            return sp.Add(*[f.to_sympy(names) * k for f, k in parts if not f.is_zero])

        return sp.Matrix([[one(v) for v in row] for row in self.entries])
