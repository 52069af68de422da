r"""Matrix positive-realness on the unit circle: residue matrices, Hermitian parts, principal
minors and exact positive-semidefiniteness decisions.

Definition 2 of the HVE paper for an ``m x m`` real-rational ``G(z)`` asks for poles in the
closed unit disk, simple unit-circle poles with positive semidefinite residue matrices, and

.. math:: M(e^{j\theta}) = G(e^{j\theta}) + G^T(e^{-j\theta}) \succeq 0 \quad \forall \theta .

**Representation.** On ``|z| = 1``, ``G^T(1/z)`` is the conjugate transpose of ``G(z)``, so
``M`` is Hermitian: ``M = (A(c) + j \sin\theta\, S(c)) / d(c)`` with ``c = cos(theta)``, ``A``
real symmetric (``A_ij = Re G_ij + Re G_ji``), ``S`` real antisymmetric
(``S_ij = (Im G_ij - Im G_ji)/sin(theta)``) and ``d > 0`` a common denominator
(:class:`HermitianPart`). ``S = 0`` when ``G`` is symmetric (equal delays, reciprocal
couplings): then ``M`` is real and every computation is entrywise in ``c``. With unequal
delays ``S != 0``; a principal minor ``det(A_I + j q S_I)`` (``q = sin theta``) is real and
even in ``q`` (``(A + jqS)^T = A - jqS``), so with ``q^2 = 1 - c^2`` it is again a polynomial
in ``c`` -- the minors are self-reciprocal, hence rational in ``c``. The code keeps the
``j``- and ``q``-parts during the expansion and checks that they cancel.

**PSD is decided by all principal minors, by the characteristic-polynomial coefficients or by
eigenvalues, never by leading minors alone.** For a Hermitian matrix with characteristic
polynomial ``det(lambda I - M) = sum_k (-1)^k E_k lambda^(m-k)`` (``E_k`` = sum of the ``k x k``
principal minors), ``M >= 0`` iff every ``E_k >= 0`` (its roots are real; Descartes). Hence
"``M(c) >= 0`` for all ``c`` in ``[-1, 1]``" is "each ``E_k(c) >= 0`` on ``[-1, 1]``": ``m``
univariate non-negativity questions, settled exactly by root isolation
(:mod:`hapticproof.exact.realroots`) with a rational witness ``c`` when one fails. Leading principal
minors certify definiteness only when they are all *positive*; with zeros they accept
indefinite matrices (:func:`shortcut_failure`).

Symbolic minors live in python-flint's ``fmpq_mpoly`` rings (:class:`PolyRing`): the
parameters and ``c`` are ring generators, so a ``5 x 5`` determinant with 35 free parameters
takes a fraction of a second in C rather than minutes of SymPy ``simplify``.

>>> import sympy as sp
>>> from hapticproof.core.symbols import z
>>> G = sp.Matrix([[1 + 1/(z - 1), -1/(z - 1)], [-1/(z - 1), 1 + 1/(z - 1)]])
>>> H = hermitian_part_matrix(G)
>>> H.is_symmetric, [m.expr() for m in principal_minors(H).values()]
(True, [1, 1, 0])
>>> decide_psd_on_circle(H).outcome.decision.value
'proved'
"""

from __future__ import annotations

import itertools
from collections.abc import Iterable, Mapping, Sequence
from dataclasses import dataclass, field
from fractions import Fraction
from typing import Any

import flint
import numpy as np
import sympy as sp

from hapticproof.exact.canonical import cancel as exact_cancel
from hapticproof.core.evidence import Decision, Evidence, Method, Outcome
from hapticproof.exact.evaluator import rational_program
from hapticproof.exact.realroots import as_fmpq, real_roots
from hapticproof.core.symbols import c as C_SYM
from hapticproof.core.symbols import z as Z_SYM
from hapticproof.exact.unitcircle import hermitian_part_rational, imaginary_part_rational
from hapticproof.exact.charpoly import charpoly_sq, is_psd

__all__ = ["PolyRing", "HermitianPart", "Minor", "ResidueMatrix", "CircleDecision", "ShortcutFailure", "leading_minors", "leading_minor_shortcut", "shortcut_failure", "nonnegative_certificate", "residue_matrices", "hermitian_part_matrix", "principal_minors", "characteristic_coefficients", "decide_psd_on_circle", "affine_worst_case", "leading_minor_counterexample", "min_eigenvalue"]


@dataclass(frozen=True)
class PolyRing:
    """``Q[c]`` (no parameters: elements are ``flint.fmpq_poly``) or ``Q[p_1, ..., p_k, c]``
    (elements are ``flint.fmpq_mpoly``).

    >>> a = sp.Symbol('a', positive=True)
    >>> R = PolyRing.over((a,))
    >>> p = R.from_expr(a*C_SYM**2 - sp.Rational(1, 2))
    >>> R.to_expr(p * R.c)
    a*c**3 - c/2
    >>> PolyRing.over(()).from_expr(3*C_SYM - 1)
    3*x + (-1)
    """

    params: tuple[sp.Symbol, ...] = ()
    var: sp.Symbol = C_SYM
    ctx: Any = field(default=None, compare=False, repr=False)

    def __post_init__(self) -> None:
        if self.params and self.ctx is None:
            names = tuple(f"x{i}" for i in range(len(self.params))) + ("c",)
            object.__setattr__(self, "ctx", flint.fmpq_mpoly_ctx.get(names, "lex"))

    @classmethod
    def over(cls, params: Iterable[sp.Symbol], var: sp.Symbol = C_SYM) -> PolyRing:
        """The ring over the given parameters (sorted by name; ``var`` is excluded)."""
        unique = sorted({p for p in params if p != var}, key=lambda s: s.name)
        return cls(tuple(unique), var)

    @property
    def numeric(self) -> bool:
        return not self.params

    @property
    def symbols(self) -> tuple[sp.Symbol, ...]:
        return (*self.params, self.var)

    def constant(self, value: Any) -> Any:
        q = as_fmpq(value)
        return flint.fmpq_poly([q]) if self.numeric else self.ctx.constant(q)

    @property
    def zero(self) -> Any:
        return self.constant(0)

    @property
    def one(self) -> Any:
        return self.constant(1)

    @property
    def c(self) -> Any:
        return flint.fmpq_poly([0, 1]) if self.numeric else self.ctx.gens()[-1]

    def gen(self, symbol: sp.Symbol) -> Any:
        if symbol == self.var:
            return self.c
        return self.ctx.gens()[self.params.index(symbol)]

    def from_expr(self, expr: Any) -> Any:
        """A polynomial SymPy expression in the ring's symbols (rational coefficients).

        The expression tree is evaluated in the ring itself (:mod:`hapticproof.exact.evaluator`:
        flint products of sums, no SymPy ``expand``); other expressions (a denominator, a
        float) go through ``expand`` and ``Poly``."""
        expr = sp.sympify(expr)
        program = rational_program(expr)
        if program is not None and program.polynomial and set(program.symbols) <= set(self.symbols):
            gens = {self.var: self.c}
            if not self.numeric:
                gens.update(zip(self.params, self.ctx.gens()))
            value = program.run(gens)
            return value if not isinstance(value, flint.fmpq) else self.constant(value)
        expr = sp.expand(expr)
        stray = expr.free_symbols - set(self.symbols)
        if stray:
            raise ValueError(f"symbols {sorted(map(str, stray))} are not in the ring")
        if self.numeric:
            poly = sp.Poly(expr, self.var)
            return flint.fmpq_poly([as_fmpq(a) for a in poly.all_coeffs()[::-1]])
        poly = sp.Poly(expr, *self.symbols)
        return self.ctx.from_dict({monom: as_fmpq(coeff) for monom, coeff in poly.terms()})

    def from_c_poly(self, p: flint.fmpq_poly) -> Any:
        """Lift a numeric polynomial in ``c`` into the ring."""
        if self.numeric:
            return p
        nvars = len(self.params) + 1
        terms = {}
        for k, a in enumerate(p.coeffs()):
            if a != 0:
                monom = [0] * nvars
                monom[-1] = k
                terms[tuple(monom)] = a
        return self.ctx.from_dict(terms) if terms else self.ctx.constant(0)

    def to_expr(self, p: Any) -> sp.Expr:
        """Back to SymPy (only for display and tests: large minors are slow to convert)."""
        if self.numeric:
            return sp.Add(*[sp.Rational(int(a.p), int(a.q)) * self.var**k for k, a in enumerate(p.coeffs()) if a != 0])
        out = []
        for monom, a in p.to_dict().items():
            term = sp.Rational(int(a.p), int(a.q))
            for sym, e in zip(self.symbols, monom):
                if e:
                    term *= sym**e
            out.append(term)
        return sp.Add(*out)

    def c_degree(self, p: Any) -> int:
        if self.numeric:
            return max(p.degree(), 0)
        return 0 if p.is_zero() else int(p.degrees()[-1])

    def substitute(self, p: Any, values: Mapping[sp.Symbol, Any]) -> Any:
        """Substitute exact values for parameters (and possibly ``c``)."""
        if self.numeric:
            if self.var in values:
                return flint.fmpq_poly([p(as_fmpq(values[self.var]))])
            return p
        mapping = {f"x{i}": as_fmpq(values[s]) for i, s in enumerate(self.params) if s in values}
        if self.var in values:
            mapping["c"] = as_fmpq(values[self.var])
        return p.subs(mapping) if mapping else p

    def to_c_poly(self, p: Any) -> flint.fmpq_poly:
        """An element without parameters as ``fmpq_poly`` in ``c``."""
        if self.numeric:
            return p
        coeffs: dict[int, flint.fmpq] = {}
        for monom, a in p.to_dict().items():
            if any(monom[:-1]):
                raise ValueError("the polynomial still has parameters")
            coeffs[monom[-1]] = a
        top = max(coeffs, default=0)
        return flint.fmpq_poly([coeffs.get(k, flint.fmpq(0)) for k in range(top + 1)])

    def nonnegative_coefficients(self, p: Any) -> bool:
        """All coefficients >= 0 (numeric: in the monomial basis of ``c``)."""
        coeffs = p.coeffs()
        return all(a >= 0 for a in coeffs)


def leading_minors(matrix: Any) -> list[sp.Expr]:
    """Leading principal minors ``det M[:k, :k]``, ``k = 1..m`` (exact)."""
    M = sp.Matrix(matrix)
    return [sp.simplify(M[:k, :k].det()) for k in range(1, M.rows + 1)]


def leading_minor_shortcut(matrix: Any) -> bool:
    """The flawed test of HVE Definition 3: "PSD if all leading principal minors are >= 0".

    >>> leading_minor_shortcut([[0, 0], [0, -1]])
    True
    """
    return all(sp.re(v) >= 0 for v in leading_minors(matrix))


@dataclass(frozen=True, slots=True)
class ShortcutFailure:
    """A matrix the leading-minor shortcut accepts although it is not PSD."""

    matrix: sp.Matrix
    leading: tuple[sp.Expr, ...]
    negative_minor: tuple[tuple[int, ...], sp.Expr]
    min_eigenvalue: float

    def to_json(self) -> dict[str, Any]:
        from hapticproof.core.evidence import to_jsonable

        return to_jsonable({"matrix": self.matrix, "leading_minors": self.leading,
                            "negative_principal_minor": {"rows": [i + 1 for i in self.negative_minor[0]],
                                                         "value": self.negative_minor[1]},
                            "min_eigenvalue": self.min_eigenvalue})


def shortcut_failure(matrix: Any) -> ShortcutFailure | None:
    """If the leading-minor shortcut accepts ``matrix`` but it is not PSD, the evidence.

    >>> f = shortcut_failure([[0, 0], [0, -1]])
    >>> f.leading, f.negative_minor
    ((0, 0), ((1,), -1))
    >>> shortcut_failure([[1, 0], [0, 1]]) is None
    True
    """
    M = sp.Matrix(matrix)
    if not leading_minor_shortcut(M):
        return None
    test = is_psd(M)
    if test.holds:
        return None
    return ShortcutFailure(sp.ImmutableMatrix(M), tuple(leading_minors(M)), test.minor, test.min_eigenvalue)


def nonnegative_certificate(ring: PolyRing, p: Any) -> bool:
    """Proof that ``p >= 0`` for non-negative parameters: every coefficient is >= 0 and every
    parameter is non-negative by assumption (``c`` must not occur).

    >>> a, b = sp.symbols('a b', nonnegative=True)
    >>> R = PolyRing.over((a, b))
    >>> nonnegative_certificate(R, R.from_expr(a*b + 2*a**2)), nonnegative_certificate(R, R.from_expr(a - b))
    (True, False)
    """
    if p.is_zero():
        return True
    if ring.c_degree(p) > 0:
        return False
    if not all(s.is_nonnegative for s in ring.params):
        return False
    return ring.nonnegative_coefficients(p)


@dataclass(frozen=True, slots=True)
class ResidueMatrix:
    """Residue matrix ``R = lim (z - z0) G(z)`` at a unit-circle pole ``z0``; Definition 2
    needs the pole simple and ``R/z0`` Hermitian PSD (``outcome``)."""

    pole: sp.Expr
    matrix: sp.ImmutableMatrix
    scaled: sp.ImmutableMatrix
    outcome: Outcome


def _unit_circle_poles(G: sp.Matrix, z: sp.Symbol) -> list[tuple[sp.Expr, int]]:
    """Unit-circle poles of the entries and their largest multiplicity."""
    found: dict[sp.Expr, int] = {}
    for entry in G:
        den = sp.fraction(exact_cancel(sp.together(entry)))[1]
        for root, mult in sp.roots(sp.Poly(den, z)).items():
            gap = sp.simplify(sp.expand(root * sp.conjugate(root)) - 1)
            if gap == 0:
                found[root] = max(found.get(root, 0), mult)
    return sorted(found.items(), key=lambda kv: sp.default_sort_key(kv[0]))


def psd_outcome(matrix: sp.Matrix, what: str) -> Outcome:
    """PSD decision of a constant matrix: exact when numeric, principal minors otherwise."""
    M = sp.Matrix(matrix)
    if M.free_symbols:
        from hapticproof.core.limits import check_minors

        check_minors(M.rows, what)    # symbolic: decided by its principal minors, counted first
    if any(sp.simplify(M[i, j] - sp.conjugate(M[j, i])) != 0 for i in range(M.rows) for j in range(M.rows)):
        return Outcome(Decision.DISPROVED, Evidence(Method.CANONICAL_FORM, facts={"matrix": M}), f"{what} is not Hermitian")
    if not M.free_symbols:
        test = is_psd(M)
        facts = {"E_k": test.coefficients}
        if test.holds:
            return Outcome(Decision.PROVED, Evidence(Method.CANONICAL_FORM, facts=facts), f"{what} is PSD (all E_k >= 0)")
        return Outcome(Decision.DISPROVED, Evidence(Method.CANONICAL_FORM, witness={"principal_minor": test.minor}, facts=facts),
                       f"{what} is not PSD")
    ring = PolyRing.over(M.free_symbols)
    H = HermitianPart(ring, tuple(tuple(ring.from_expr(v) for v in M.row(i)) for i in range(M.rows)), None, ring.one)
    minors = principal_minors(H)
    certified = all(nonnegative_certificate(ring, mn.num) for mn in minors.values())
    facts = {"principal_minors": {str(tuple(i + 1 for i in k)): mn.expr() for k, mn in minors.items()}}
    if certified:
        return Outcome(Decision.PROVED, Evidence(Method.STRUCTURAL, facts=facts),
                       f"{what} is PSD: every principal minor is a polynomial with non-negative coefficients "
                       "in non-negative parameters")
    conditions = [sp.Ge(mn.expr(), 0, evaluate=False) for mn in minors.values() if not nonnegative_certificate(ring, mn.num)]
    return Outcome(Decision.SYMBOLIC, Evidence(Method.CANONICAL_FORM, facts={**facts, "conditions": conditions}),
                   f"{what} is PSD iff its principal minors are >= 0")


def residue_matrices(G: Any, z: sp.Symbol = Z_SYM) -> list[ResidueMatrix]:
    """Residue matrices of ``G`` at its poles on ``|z| = 1`` and their PSD decision.

    >>> K1, K2, T = sp.symbols('K_1 K_2 T', positive=True)
    >>> from hapticproof.core.symbols import z
    >>> G = sp.Matrix([[(K1 + K2)*T/(z - 1), -K2*T/(z - 1)], [-K2*T/(z - 1), K2*T/(z - 1)]])
    >>> (r,) = residue_matrices(G)
    >>> r.pole, r.matrix.tolist(), r.outcome.decision.value
    (1, [[T*(K_1 + K_2), -K_2*T], [-K_2*T, K_2*T]], 'proved')
    """
    G = sp.Matrix(G)
    out = []
    for pole, mult in _unit_circle_poles(G, z):
        if mult > 1:
            outcome = Outcome(Decision.DISPROVED, Evidence(Method.CANONICAL_FORM, facts={"pole": pole, "multiplicity": mult}),
                              f"the unit-circle pole z = {pole} is not simple")
            out.append(ResidueMatrix(pole, sp.ImmutableMatrix(G * sp.nan), sp.ImmutableMatrix(G * sp.nan), outcome))
            continue
        R = G.applyfunc(lambda e: sp.factor(exact_cancel((z - pole) * e).subs(z, pole)))
        scaled = (R / pole).applyfunc(sp.simplify)
        out.append(ResidueMatrix(pole, sp.ImmutableMatrix(R), sp.ImmutableMatrix(scaled),
                                 psd_outcome(scaled, f"the residue matrix at z = {pole} (divided by z0)")))
    return out


@dataclass(frozen=True)
class HermitianPart:
    """``M(theta) = (A(c) + j sin(theta) S(c)) / den(c)`` on the unit circle.

    ``A`` (symmetric) and ``S`` (antisymmetric, ``None`` when zero) hold ring elements of
    ``ring``; ``den`` is positive on ``(-1, 1)`` wherever ``M`` is finite (a product of squared
    moduli), so the sign of a minor is that of its numerator.
    """

    ring: PolyRing
    A: tuple[tuple[Any, ...], ...]
    S: tuple[tuple[Any, ...], ...] | None
    den: Any

    def __post_init__(self) -> None:
        m = len(self.A)
        if any(len(row) != m for row in self.A):
            raise ValueError("A must be square")
        if self.S is not None:
            if all(v.is_zero() for row in self.S for v in row):
                object.__setattr__(self, "S", None)
            elif len(self.S) != m or any(len(row) != m for row in self.S):
                raise ValueError("S must have the shape of A")

    @property
    def size(self) -> int:
        return len(self.A)

    @property
    def is_symmetric(self) -> bool:
        """True when ``M`` is real (``S = 0``): entrywise computation in ``c``."""
        return self.S is None

    @property
    def is_numeric(self) -> bool:
        return self.ring.numeric

    def matrix(self, sin_symbol: sp.Symbol | None = None) -> sp.Matrix:
        """``M`` as a SymPy matrix in ``c`` (and ``sin_symbol`` for ``sin(theta)``)."""
        q = sin_symbol if sin_symbol is not None else sp.sqrt(1 - self.ring.var**2)
        den = self.ring.to_expr(self.den)
        m = self.size
        S = self.S
        return sp.Matrix(m, m, lambda i, j: (self.ring.to_expr(self.A[i][j])
                                             + (sp.I * q * self.ring.to_expr(S[i][j]) if S is not None else 0)) / den)

    def subs(self, values: Mapping[sp.Symbol, Any]) -> HermitianPart:
        """Exact values for some or all parameters (all: a numeric part in ``Q[c]``)."""
        remaining = tuple(p for p in self.ring.params if p not in values)
        target = PolyRing(remaining, self.ring.var)

        def move(p: Any) -> Any:
            value = self.ring.substitute(p, values)
            if target.numeric:
                return self.ring.to_c_poly(value)
            if remaining == self.ring.params:
                return value
            return target.from_expr(self.ring.to_expr(value))

        A = tuple(tuple(move(v) for v in row) for row in self.A)
        S = None if self.S is None else tuple(tuple(move(v) for v in row) for row in self.S)
        return HermitianPart(target, A, S, move(self.den))

    def at(self, c_value: Any, sin_value: Any = None) -> sp.Matrix:
        """Exact numeric matrix at a rational ``c`` (``sin(theta) = sqrt(1-c^2)`` unless given)."""
        if not self.is_numeric:
            raise ValueError("substitute the parameters first")
        cq = as_fmpq(c_value)
        den = self.den(cq)
        q = sp.sqrt(1 - sp.Rational(c_value) ** 2) if sin_value is None else sp.Rational(sin_value)

        def val(p: flint.fmpq_poly) -> sp.Rational:
            v = p(cq) / den
            return sp.Rational(int(v.p), int(v.q))

        m = self.size
        return sp.Matrix(m, m, lambda i, j: val(self.A[i][j]) + (sp.I * q * val(self.S[i][j]) if self.S is not None else 0))

    def evaluate(self, theta: float) -> np.ndarray:
        """Floating-point ``M(e^{j theta})`` (for independent eigenvalue cross-checks)."""
        if not self.is_numeric:
            raise ValueError("substitute the parameters first")
        cval, qval = float(np.cos(theta)), float(np.sin(theta))

        def f(p: flint.fmpq_poly) -> float:
            return sum(float(a) * cval**k for k, a in enumerate(p.coeffs()))

        den = f(self.den)
        m = self.size
        out = np.zeros((m, m), dtype=complex)
        for i in range(m):
            for j in range(m):
                out[i, j] = f(self.A[i][j]) / den
                if self.S is not None:
                    out[i, j] += 1j * qval * f(self.S[i][j]) / den
        return out

    def c_degree(self) -> int:
        """Degree bound of the entries in ``c`` (``S`` counts one more for ``sin theta``)."""
        deg = max((self.ring.c_degree(v) for row in self.A for v in row), default=0)
        if self.S is not None:
            deg = max(deg, max(self.ring.c_degree(v) for row in self.S for v in row) + 1)
        return deg


def _entry_parts(entry: sp.Expr, z: sp.Symbol, var: sp.Symbol) -> tuple[sp.Expr, sp.Expr]:
    """``Re F`` and ``Im F / sin(theta)`` of a scalar real-rational ``F`` as expressions in c."""
    if sp.sympify(entry) == 0:
        return sp.Integer(0), sp.Integer(0)
    return hermitian_part_rational(entry, z, var).expr(), imaginary_part_rational(entry, z, var).expr()


def hermitian_part_matrix(G: Any, z: sp.Symbol = Z_SYM, var: sp.Symbol = C_SYM) -> HermitianPart:
    """The Hermitian part ``G(z) + G^T(1/z)`` of a real-rational matrix on ``|z| = 1``.

    The generic route: each entry's real and imaginary parts by the scalar maps of
    :mod:`hapticproof.exact.unitcircle`, combined as ``A_ij = Re G_ij + Re G_ji`` and
    ``S_ij = (Im G_ij - Im G_ji)/sin(theta)``, over a common positive denominator.

    >>> from hapticproof.core.symbols import z
    >>> G = sp.Matrix([[1, 1/z], [0, 1]])        # non-symmetric: M_12 = e^{-j theta}
    >>> H = hermitian_part_matrix(G)
    >>> H.is_symmetric, H.matrix(sp.Symbol('q'))[0, 1]
    (False, c - I*q)
    """
    G = sp.Matrix(G)
    if G.rows != G.cols:
        raise ValueError("G must be square")
    m = G.rows
    parts = [[_entry_parts(G[i, j], z, var) for j in range(m)] for i in range(m)]
    A_expr = [[exact_cancel(sp.together(parts[i][j][0] + parts[j][i][0])) for j in range(m)] for i in range(m)]
    S_expr = [[exact_cancel(sp.together(parts[i][j][1] - parts[j][i][1])) for j in range(m)] for i in range(m)]
    dens: list[sp.Expr] = []
    for e in itertools.chain.from_iterable(A_expr + S_expr):
        d = sp.fraction(e)[1]
        if d != 1 and not any(sp.expand(d - other) == 0 for other in dens):
            # a constant sign is all that matters: keep the denominator as produced (|Q|^2 > 0)
            dens.append(d)
    den = sp.Mul(*dens)
    params = set().union(*(e.free_symbols for e in itertools.chain.from_iterable(A_expr + S_expr))) | den.free_symbols
    ring = PolyRing.over(params - {var}, var)

    def numer(e: sp.Expr) -> Any:
        return ring.from_expr(exact_cancel(e * den))

    A = tuple(tuple(numer(A_expr[i][j]) for j in range(m)) for i in range(m))
    S = tuple(tuple(numer(S_expr[i][j]) for j in range(m)) for i in range(m))
    den_el = ring.from_expr(den)
    # the denominators are squared moduli; normalise a negative constant factor away
    probe = ring.substitute(den_el, {s: 1 for s in ring.params} | {var: 0}).coeffs()
    if probe and probe[0] < 0:
        A = tuple(tuple(-v for v in row) for row in A)
        S = tuple(tuple(-v for v in row) for row in S)
        den_el = -den_el
    return HermitianPart(ring, A, S, den_el)


class _Real:
    """Arithmetic of real entries (ring elements)."""

    def __init__(self, ring: PolyRing):
        self.zero = ring.zero

    @staticmethod
    def is_zero(x: Any) -> bool:
        return x.is_zero()

    @staticmethod
    def mul(x: Any, y: Any) -> Any:
        return x * y

    @staticmethod
    def add(x: Any, y: Any) -> Any:
        return x + y

    @staticmethod
    def neg(x: Any) -> Any:
        return -x


class _Hermitian:
    """Arithmetic of ``(u0 + q v0) + j (u1 + q v1)`` with ``q^2 = 1 - c^2``, ``j^2 = -1``."""

    def __init__(self, ring: PolyRing):
        z = ring.zero
        self.zero = (z, z, z, z)
        self.s = ring.one - ring.c * ring.c

    @staticmethod
    def is_zero(x: tuple) -> bool:
        return all(p.is_zero() for p in x)

    def _qmul(self, a: Any, b: Any, a2: Any, b2: Any) -> tuple[Any, Any]:
        return a * a2 + self.s * (b * b2), a * b2 + b * a2

    def mul(self, x: tuple, y: tuple) -> tuple:
        r0, r1 = self._qmul(x[0], x[1], y[0], y[1])      # X0 Y0
        s0, s1 = self._qmul(x[2], x[3], y[2], y[3])      # X1 Y1
        t0, t1 = self._qmul(x[0], x[1], y[2], y[3])      # X0 Y1
        u0, u1 = self._qmul(x[2], x[3], y[0], y[1])      # X1 Y0
        return (r0 - s0, r1 - s1, t0 + u0, t1 + u1)

    @staticmethod
    def add(x: tuple, y: tuple) -> tuple:
        return tuple(a + b for a, b in zip(x, y))

    @staticmethod
    def neg(x: tuple) -> tuple:
        return tuple(-a for a in x)


@dataclass(frozen=True, slots=True)
class Minor:
    """A principal minor: ``num(c) / den(c)**size`` (``num`` a ring element)."""

    subset: tuple[int, ...]
    num: Any
    ring: PolyRing
    den: Any

    @property
    def size(self) -> int:
        return len(self.subset)

    def expr(self) -> sp.Expr:
        """As a SymPy expression (numerator over ``den**size``)."""
        den = self.ring.to_expr(self.den)
        return self.ring.to_expr(self.num) / den**self.size


def _minor_engine(H: HermitianPart):
    m = H.size
    if H.S is None:
        alg: Any = _Real(H.ring)
        entry = [[H.A[i][j] for j in range(m)] for i in range(m)]
    else:
        alg = _Hermitian(H.ring)
        zero = H.ring.zero
        entry = [[(H.A[i][j], zero, zero, H.S[i][j]) for j in range(m)] for i in range(m)]
    memo: dict[tuple[tuple[int, ...], tuple[int, ...]], Any] = {}

    def minor(rows: tuple[int, ...], cols: tuple[int, ...]) -> Any:
        if not rows:
            return H.ring.one if H.S is None else (H.ring.one, H.ring.zero, H.ring.zero, H.ring.zero)
        key = (rows, cols)
        found = memo.get(key)
        if found is not None:
            return found
        r0, rest = rows[0], rows[1:]
        total = alg.zero
        for t, col in enumerate(cols):
            a = entry[r0][col]
            if alg.is_zero(a):
                continue
            term = alg.mul(a, minor(rest, cols[:t] + cols[t + 1:]))
            total = alg.add(total, term if t % 2 == 0 else alg.neg(term))
        memo[key] = total
        return total

    return alg, minor


def principal_minors(
    H: HermitianPart, subsets: Iterable[Sequence[int]] | None = None, sizes: Iterable[int] | None = None
) -> dict[tuple[int, ...], Minor]:
    """All principal minors of ``M`` (or the given ``subsets``/``sizes``), exact in ``c``.

    Entrywise and real when ``M`` is symmetric; with unequal delays the ``j``- and
    ``sin``-parts are carried and checked to cancel (the minors of a Hermitian matrix are real
    and, being even in ``sin theta``, polynomials in ``c``). Subsets are 0-based tuples.

    >>> from hapticproof.core.symbols import z
    >>> G = sp.Matrix([[2, 1/z], [0, 2]])
    >>> [(k, m.expr()) for k, m in principal_minors(hermitian_part_matrix(G)).items()]
    [((0,), 4), ((1,), 4), ((0, 1), 15)]
    """
    from hapticproof.core.limits import check_minors

    m = H.size
    if subsets is None:
        wanted = sorted(set(sizes)) if sizes is not None else range(1, m + 1)
        check_minors(m, "principal minors", wanted)     # counted before one is computed
        subsets = [s for k in wanted for s in itertools.combinations(range(m), k)]
    alg, minor = _minor_engine(H)
    out: dict[tuple[int, ...], Minor] = {}
    for subset in subsets:
        subset = tuple(sorted(subset))
        value = minor(subset, subset)
        if H.S is not None:
            u0, v0, u1, v1 = value
            if not (v0.is_zero() and u1.is_zero() and v1.is_zero()):
                raise ArithmeticError(f"principal minor {subset} is not real and even in sin(theta)")
            value = u0
        out[subset] = Minor(subset, value, H.ring, H.den)
    return out


def characteristic_coefficients(H: HermitianPart, method: str = "auto") -> list[Any]:
    """Numerators of ``E_0..E_m`` (``E_k = num_k / den**k``): sums of the ``k x k``
    principal minors.

    ``method='minors'`` sums principal minors (symbolic parameters allowed);
    ``method='interpolation'`` (numeric only) evaluates ``M`` at rational points of the unit
    circle, takes exact characteristic polynomials (flint) and interpolates each coefficient
    in ``c`` -- ``O(m^3)`` work per point instead of ``2^m`` minors.

    >>> from hapticproof.core.symbols import z
    >>> G = sp.Matrix([[2, 1/z], [0, 2]])
    >>> H = hermitian_part_matrix(G)
    >>> characteristic_coefficients(H, 'minors') == characteristic_coefficients(H, 'interpolation')
    True
    """
    if method == "auto":
        method = "interpolation" if H.is_numeric and H.size > 6 else "minors"
    if method == "minors":
        ring = H.ring
        sums = [ring.one] + [ring.zero] * H.size
        for subset, mn in principal_minors(H).items():
            sums[len(subset)] = sums[len(subset)] + mn.num
        return sums
    if not H.is_numeric:
        raise ValueError("interpolation needs numeric parameters")
    return _coefficients_by_interpolation(H)


def _coefficients_by_interpolation(H: HermitianPart) -> list[flint.fmpq_poly]:
    m = H.size
    degree = H.c_degree()
    npts = m * degree + 1
    # any distinct points will do (sin(theta) enters only through sin^2 = 1 - c^2): small
    # integers keep the matrices integral up to the parameters' denominators
    xs = [flint.fmpq(k - npts // 2) for k in range(npts)]
    values: list[list[flint.fmpq]] = []
    for cval in xs:
        re = [[H.A[i][j](cval) for j in range(m)] for i in range(m)]
        sim = [[H.S[i][j](cval) for j in range(m)] for i in range(m)] if H.S is not None else None
        values.append(charpoly_sq(re, sim, 1 - cval * cval))
    V = flint.fmpq_mat([[x**k for k in range(npts)] for x in xs])
    Y = flint.fmpq_mat([[values[r][k] for k in range(m + 1)] for r in range(npts)])
    X = V.solve(Y)
    return [flint.fmpq_poly([X[r, k] for r in range(npts)]) for k in range(m + 1)]


@dataclass(frozen=True, slots=True)
class CircleDecision:
    """``M(c) >= 0`` for all ``c`` in ``[lo, hi]``: the decision with its evidence.

    ``failing`` is the ``k`` of the first ``E_k`` that goes negative and ``witness`` a rational
    ``c`` where it does (``M(witness)`` is then not PSD); ``touches`` lists, per ``k``, the
    points where ``E_k`` touches zero when the decision is ``proved``.
    """

    outcome: Outcome
    coefficients: tuple[flint.fmpq_poly, ...]
    failing: int | None = None
    witness: sp.Rational | None = None

    @property
    def decision(self) -> Decision:
        return self.outcome.decision


def decide_psd_on_circle(H: HermitianPart, lo: Any = -1, hi: Any = 1, method: str = "auto",
                         transfer: Any = None) -> CircleDecision:
    """Exact decision of ``M(c) >= 0`` on ``[lo, hi]`` (numeric parameters) by the decision
    kernel (:func:`hapticproof.exact.kernel.decide_psd`): every characteristic coefficient ``E_k(c)``
    is decided with a certificate. A failure comes with a rational point ``z0`` of the circle,
    the exact matrix there and a negative principal minor; ``transfer`` (the transfer matrix as
    polynomials, see :func:`hapticproof.exact.kernel.transfer_json`) lets the checker recompute it.

    >>> from hapticproof.core.symbols import z
    >>> G = sp.Matrix([[2 + 1/(z - 1), -1/(z - 1)], [-1/(z - 1), 2 + 1/(z - 1)]])
    >>> d = decide_psd_on_circle(hermitian_part_matrix(G))
    >>> d.decision.value
    'proved'
    """
    from hapticproof.exact.kernel import decide_psd

    if not H.is_numeric:
        raise ValueError("decide_psd_on_circle needs numeric parameters (use subs)")
    coeffs = characteristic_coefficients(H, method)

    def evaluate(witness: Mapping[str, Any]) -> sp.Matrix | None:
        if "z" not in witness:
            return None
        c0, s0 = witness["z"]
        return H.at(sp.Rational(c0.numerator, c0.denominator), sp.Rational(s0.numerator, s0.denominator))

    scale = H.den if H.den.degree() > 0 else None
    outcome = decide_psd(coeffs[1:], lo, hi, "c", scale=scale, evaluate=evaluate, transfer=transfer, what="M(c)")
    if outcome.decision == Decision.DISPROVED:
        witness = outcome.witness["c"]
        return CircleDecision(outcome, tuple(coeffs), outcome.evidence.facts["failing_k"], witness)
    return CircleDecision(outcome, tuple(coeffs))


@dataclass(frozen=True, slots=True)
class AffineWorstCase:
    """``M(c) = M0 + c M1`` with a definite ``M1``: the worst case is an endpoint (Loewner
    order) and ``M(c) >= 0`` for all ``c`` iff ``M(endpoint) >= 0``.

    ``minors`` are the principal minors of ``M(endpoint)`` (ring elements, ``c``-free); the
    exact condition is that all of them are ``>= 0``.
    """

    endpoint: int
    slope_certificate: str
    matrix: HermitianPart
    minors: dict[tuple[int, ...], Minor]

    def conditions(self) -> list[sp.Basic]:
        return [sp.Ge(mn.expr(), 0, evaluate=False) for mn in self.minors.values()]


def affine_worst_case(H: HermitianPart) -> AffineWorstCase | None:
    """For a real ``M`` affine in ``c`` whose slope matrix is certified PSD (or NSD) -- every
    principal minor a non-negative-coefficient polynomial in non-negative parameters -- the
    endpoint ``c = -1`` (or ``+1``) is the worst case; ``None`` when that structure is absent.

    >>> B, b = sp.symbols('B b', nonnegative=True)
    >>> from hapticproof.core.symbols import z
    >>> M = sp.Matrix([[b + B/z, 0], [0, b + B/z]])
    >>> wc = affine_worst_case(hermitian_part_matrix(M))
    >>> wc.endpoint, [str(cnd) for cnd in wc.conditions()][:1]
    (-1, ['-2*B + 2*b >= 0'])
    """
    if H.S is not None or H.ring.c_degree(H.den) > 0:
        return None
    if any(H.ring.c_degree(v) > 1 for row in H.A for v in row):
        return None
    ring = H.ring
    m = H.size
    if ring.numeric:
        slope_vals = [[v.coeffs()[1] if v.degree() >= 1 else flint.fmpq(0) for v in row] for row in H.A]
        M1 = sp.Matrix(m, m, lambda i, j: sp.Rational(int(slope_vals[i][j].p), int(slope_vals[i][j].q)))
        for sign, endpoint in ((1, -1), (-1, 1)):
            if is_psd(sign * M1, search_minor=False).holds:
                at = _at_endpoint(H, endpoint)
                return AffineWorstCase(endpoint, "slope matrix PSD (exact)" if sign > 0 else "slope matrix NSD (exact)",
                                       at, principal_minors(at))
        return None
    # symbolic: slope = coefficient of c
    slope = tuple(tuple(_c_coefficient(ring, v) for v in row) for row in H.A)
    for sign, endpoint in ((1, -1), (-1, 1)):
        S1 = HermitianPart(ring, tuple(tuple(sign * v for v in row) for row in slope), None, ring.one)
        if all(nonnegative_certificate(ring, mn.num) for mn in principal_minors(S1).values()):
            at = _at_endpoint(H, endpoint)
            text = ("slope matrix PSD: its principal minors are polynomials with non-negative coefficients "
                    "in non-negative parameters")
            return AffineWorstCase(endpoint, text if sign > 0 else text.replace("PSD", "NSD (negated)"), at, principal_minors(at))
    return None


def _c_coefficient(ring: PolyRing, p: Any) -> Any:
    """Coefficient of ``c`` in an element of degree <= 1 in ``c``."""
    terms = {monom[:-1] + (0,): a for monom, a in p.to_dict().items() if monom[-1] == 1}
    return ring.ctx.from_dict(terms) if terms else ring.zero


def _at_endpoint(H: HermitianPart, endpoint: int) -> HermitianPart:
    ring = H.ring

    def sub(p: Any) -> Any:
        value = ring.substitute(p, {ring.var: endpoint})
        return value

    return HermitianPart(ring, tuple(tuple(sub(v) for v in row) for row in H.A), None, sub(H.den))


def leading_minor_counterexample(H: HermitianPart) -> tuple[sp.Rational, ShortcutFailure] | None:
    """A rational ``c`` at which the leading-minor shortcut accepts ``M(c)`` although ``M(c)``
    is not PSD, or ``None``. Candidates are the exact rational zeros of the leading minors in
    ``[-1, 1]`` (the shortcut can only fail where a leading minor vanishes) and the endpoints.

    >>> from hapticproof.core.symbols import z
    >>> G = sp.Matrix([[sp.Rational(1, 2) + 2/(z - 1) + 1/z, -(1/(z - 1) + 1/z)],
    ...                [-(1/(z - 1) + 1/z), sp.Rational(1, 4) + 2/(z - 1) + 1/z]])
    >>> c0, failure = leading_minor_counterexample(hermitian_part_matrix(G))
    >>> c0, failure.leading, failure.negative_minor
    (1/2, (0, 0), ((1,), -1/2))
    """
    if not H.is_numeric:
        raise ValueError("substitute the parameters first")
    m = H.size
    lead = principal_minors(H, subsets=[tuple(range(k)) for k in range(1, m + 1)])
    candidates: set[sp.Rational] = {sp.Integer(-1), sp.Integer(1)}
    for mn in lead.values():
        if mn.num.is_zero():
            continue
        for root in real_roots(mn.num, -1, 1):
            if root.is_exact:
                candidates.add(sp.Rational(int(root.lo.p), int(root.lo.q)))
    for c0 in sorted(candidates):
        if H.S is not None and abs(c0) != 1:
            continue  # sin(theta) irrational: exact matrix not rational
        failure = shortcut_failure(H.at(c0, 0 if abs(c0) == 1 else None))
        if failure is not None:
            return c0, failure
    return None


def min_eigenvalue(H: HermitianPart, theta: float) -> float:
    """Smallest eigenvalue of ``M(e^{j theta})`` in floating point (independent numerics)."""
    return float(np.min(np.linalg.eigvalsh(H.evaluate(theta))))


def _fraction(value: flint.fmpq) -> Fraction:  # pragma: no cover - convenience
    return Fraction(int(value.p), int(value.q))
