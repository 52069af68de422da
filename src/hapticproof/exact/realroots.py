"""Exact real-root isolation and sign decisions for univariate rational polynomials.

Every "for all w" question of the toolkit ends here: a polynomial in ``c = cos(wT)`` on
``[-1, 1]`` or in ``x = w**2`` on ``[0, oo)``. Roots are isolated exactly by Descartes' rule of
signs with bisection (the Vincent–Collins–Akritas method) on python-flint integer polynomials,
so an answer is a proof: an isolating interval with rational endpoints contains exactly one root,
and a sign is decided by exact rational evaluation.

>>> import flint
>>> p = flint.fmpq_poly([-1, 0, 2])          # 2c**2 - 1, roots +-1/sqrt(2)
>>> [r.approx(10) for r in real_roots(p, -1, 1)]
['-0.7071067812', '0.7071067812']
>>> nonnegative_on(p, -1, 1)
NonnegativeResult(holds=False, witness=0)
"""

from __future__ import annotations

import contextlib
import math
from collections.abc import Iterator
from dataclasses import dataclass
from fractions import Fraction
from typing import Any

import flint
import mpmath
import sympy as sp

from hapticproof.core.errors import DerivationError

__all__ = [
    "flint_precision",
    "ball_spectral_radius",
    "RealRoot",
    "NonnegativeResult",
    "Minimum",
    "as_fmpq_poly",
    "as_fmpq",
    "real_roots",
    "sign_at",
    "nonnegative_on",
    "minimise_rational",
    "cauchy_bound",
]

Number = int | Fraction | flint.fmpq | sp.Rational


def as_fmpq(value: Any) -> flint.fmpq:
    """Exact conversion of an integer/rational (Python, SymPy or flint) to ``flint.fmpq``."""
    if isinstance(value, flint.fmpq):
        return value
    if isinstance(value, (int, flint.fmpz)):
        return flint.fmpq(value)
    if isinstance(value, Fraction):
        return flint.fmpq(value.numerator, value.denominator)
    value = sp.nsimplify(value) if isinstance(value, float) else sp.sympify(value)
    if not value.is_Rational:
        raise TypeError(f"not an exact rational: {value!r}")
    return flint.fmpq(int(value.p), int(value.q))


def to_rational(value: flint.fmpq) -> sp.Rational:
    """``flint.fmpq`` -> ``sympy.Rational``."""
    return sp.Rational(int(value.p), int(value.q))


def as_fmpq_poly(poly: Any, var: sp.Symbol | None = None) -> flint.fmpq_poly:
    """Convert a polynomial with rational coefficients to ``flint.fmpq_poly``.

    Accepts flint polynomials, ``sympy.Poly`` (univariate), SymPy expressions (give ``var``
    when the expression has several symbols) and coefficient lists (lowest degree first).

    >>> import sympy as sp
    >>> c = sp.Symbol('c')
    >>> as_fmpq_poly(c**2/2 - 3, c)
    1/2*x^2 + (-3)
    """
    if isinstance(poly, flint.fmpq_poly):
        return poly
    if isinstance(poly, flint.fmpz_poly):
        return flint.fmpq_poly(poly)
    if isinstance(poly, (list, tuple)):
        return flint.fmpq_poly([as_fmpq(a) for a in poly])
    if not isinstance(poly, sp.Poly):
        expr = sp.sympify(poly)
        gens = [var] if var is not None else sorted(expr.free_symbols, key=str)
        if len(gens) > 1:
            raise ValueError(f"several symbols in {expr}; name the variable")
        if not gens:
            return flint.fmpq_poly([as_fmpq(expr)])
        poly = sp.Poly(expr, *gens)
    if len(poly.gens) != 1:
        raise ValueError("expected a univariate polynomial")
    coeffs = poly.all_coeffs()[::-1]
    return flint.fmpq_poly([as_fmpq(a) for a in coeffs])


def _primitive_int(p: flint.fmpq_poly) -> flint.fmpz_poly:
    """Integer polynomial with the same roots and the same sign (denominator is positive)."""
    return p.numer()


@contextlib.contextmanager
def flint_precision(bits: int) -> Iterator[None]:
    """Run a block with python-flint's ball arithmetic at ``bits`` of working precision.

    >>> with flint_precision(200):
    ...     flint.ctx.prec
    200
    """
    old = flint.ctx.prec
    flint.ctx.prec = bits
    try:
        yield
    finally:
        flint.ctx.prec = old


def ball_spectral_radius(matrix: flint.acb_mat) -> flint.arb | None:
    """An enclosure of ``max |eigenvalue|`` from isolating eigenvalue balls (``acb_mat.eig``)
    at the current precision; ``None`` when the balls do not isolate the eigenvalues (clusters:
    retry with more bits, or fall back to a floating-point method).

    >>> radius = ball_spectral_radius(flint.acb_mat([[0, 2], [-2, 0]]))     # eigenvalues +-2j
    >>> radius.overlaps(flint.arb(2)), radius.rad() < 1e-10
    (True, True)
    """
    try:
        eig = matrix.eig()
    except ValueError:
        return None
    radius = flint.arb(0)
    for value in eig:
        radius = radius.max(abs(value))
    return radius


def sign_at(p: flint.fmpq_poly | flint.fmpz_poly, point: Number) -> int:
    """Exact sign of ``p(point)``.

    A ball evaluation decides it whenever the ball excludes zero (certified); only then-unclear
    cases pay for exact rational arithmetic, whose numbers grow with the degree times the
    point's denominator size.

    >>> sign_at(flint.fmpq_poly([-1, 0, 2]), Fraction(1, 2))
    -1
    """
    point = as_fmpq(point)
    if p.degree() > 8:
        integer = p.numer() if isinstance(p, flint.fmpq_poly) else p
        with flint_precision(integer.height_bits() + int(point.q).bit_length() + int(point.p).bit_length() + 64):
            value = flint.arb_poly(integer)(flint.arb(point))
        if value > 0:
            return 1
        if value < 0:
            return -1
    exact = p(point)
    return (exact > 0) - (exact < 0)


@dataclass(frozen=True, slots=True)
class RealRoot:
    """A real root of ``poly`` isolated in ``[lo, hi]`` (``lo == hi`` for an exact rational root).

    ``poly`` is the squarefree integer factor that vanishes at the root; ``multiplicity`` is the
    root's multiplicity in the polynomial it was isolated from.
    """

    lo: flint.fmpq
    hi: flint.fmpq
    poly: flint.fmpz_poly
    multiplicity: int = 1

    @property
    def is_exact(self) -> bool:
        return self.lo == self.hi

    def refine(self, width: Number) -> RealRoot:
        """Shrink the isolating interval until ``hi - lo <= width``.

        Bisection with exact signs to a moderate width, then Newton's iteration in ball
        arithmetic; the final interval is accepted only after two exact sign evaluations
        certify that it still brackets the root (else bisection continues).
        """
        width = as_fmpq(width)
        lo, hi = self.lo, self.hi
        if lo == hi or hi - lo <= width:
            return self
        coarse = max(width, (hi - lo) / 2**8)
        lo, hi = self._bisect(lo, hi, coarse)
        if lo != hi and hi - lo > width:
            newton = self._newton(lo, hi, width)
            lo, hi = newton if newton is not None else self._bisect(lo, hi, width)
        return RealRoot(lo, hi, self.poly, self.multiplicity)

    def _bisect(self, lo: flint.fmpq, hi: flint.fmpq, width: flint.fmpq) -> tuple[flint.fmpq, flint.fmpq]:
        s_lo = sign_at(self.poly, lo)
        while hi - lo > width:
            mid = (lo + hi) / 2
            s_mid = sign_at(self.poly, mid)
            if s_mid == 0:
                return mid, mid
            if s_mid == s_lo:
                lo = mid
            else:
                hi = mid
        return lo, hi

    def _newton(self, lo: flint.fmpq, hi: flint.fmpq, width: flint.fmpq) -> tuple[flint.fmpq, flint.fmpq] | None:
        """Newton in ball arithmetic from the midpoint, then an exact bracket check."""
        inverse = 1 / width
        target_bits = max(1, int(inverse.p).bit_length() - int(inverse.q).bit_length() + 2)
        poly = flint.fmpq_poly(self.poly)
        deriv = poly.derivative()
        with flint_precision(target_bits + 2 * self.poly.height_bits() + 64):
            P, D = flint.arb_poly(poly), flint.arb_poly(deriv)
            x = flint.arb((lo + hi) / 2)
            for _ in range(2 * int(math.log2(target_bits + 2)) + 6):
                step = P(x) / D(x)
                if not step.is_finite():
                    return None
                x = flint.arb(x.mid()) - flint.arb(step.mid())
            centre = _dyadic(x, target_bits + 4)
        half = width / 2
        a, b = max(lo, centre - half), min(hi, centre + half)
        if a >= b:
            return None
        s_a, s_b = sign_at(self.poly, a), sign_at(self.poly, b)
        if s_a == 0:
            return a, a
        if s_b == 0:
            return b, b
        return (a, b) if s_a != s_b else None

    def ball(self, bits: int = 64) -> flint.arb:
        """An ``arb`` ball containing the root, radius at most ``2**-bits`` (relative to 1)."""
        r = self.refine(flint.fmpq(1, 2**bits))
        mid = (r.lo + r.hi) / 2
        rad = (r.hi - r.lo) / 2
        return flint.arb(mid) + flint.arb(0, flint.arb(rad).upper())

    def midpoint(self, bits: int = 64) -> sp.Rational:
        """A rational point within ``2**-bits`` of the root."""
        r = self.refine(flint.fmpq(1, 2**bits))
        return to_rational((r.lo + r.hi) / 2)

    def approx(self, digits: int = 15) -> str:
        """Decimal approximation with ``digits`` significant digits (correctly bounded)."""
        bits = int(digits * 3.33) + 16
        value = to_rational(self.lo) if self.is_exact else self.midpoint(bits)
        with mpmath.workdps(digits + 5):
            return mpmath.nstr(mpmath.mpf(value.p) / value.q, digits)

    def as_sympy(self) -> sp.Expr:
        """The exact root as a SymPy number (rational, or ``CRootOf`` of its factor)."""
        if self.is_exact:
            return to_rational(self.lo)
        c = sp.Dummy("c")
        roots = sp.Poly([int(a) for a in reversed(self.poly.coeffs())], c).real_roots()
        lo, hi = to_rational(self.lo), to_rational(self.hi)
        inside = [r for r in roots if bool(r >= lo) and bool(r <= hi)]
        if len(inside) != 1:  # pragma: no cover - isolation guarantees one root
            raise ArithmeticError("isolating interval does not hold exactly one root")
        return inside[0]

    def __str__(self) -> str:
        if self.is_exact:
            return str(self.lo)
        return f"root in [{self.lo}, {self.hi}] (~{self.approx(12)})"


def _sign_variations(coeffs: list[flint.fmpz]) -> int:
    count = 0
    previous = 0
    for a in coeffs:
        if a == 0:
            continue
        s = 1 if a > 0 else -1
        if previous and s != previous:
            count += 1
        previous = s
    return count


_SHIFT = flint.fmpz_poly([1, 1])


def _descartes_01(q: flint.fmpz_poly, degree: int) -> int:
    """Upper bound (exact when 0 or 1) on the number of roots of ``q`` in the open (0, 1)."""
    coeffs = q.coeffs()
    coeffs += [flint.fmpz(0)] * (degree + 1 - len(coeffs))
    reversed_q = flint.fmpz_poly(coeffs[::-1])
    return _sign_variations(reversed_q(_SHIFT).coeffs())


def _halve(q: flint.fmpz_poly, degree: int) -> flint.fmpz_poly:
    """``2**degree * q(x/2)``: maps the left half of (0, 1) onto (0, 1)."""
    coeffs = q.coeffs()
    return flint.fmpz_poly([a * 2 ** (degree - i) for i, a in enumerate(coeffs)])


def _isolate_open_01(q: flint.fmpz_poly) -> list[tuple[Fraction, Fraction]]:
    """Isolating intervals (in (0, 1)) for the roots of squarefree ``q`` in the open (0, 1).

    Returns (lo, hi) pairs; lo == hi marks an exact dyadic root.
    """
    degree = q.degree()
    out: list[tuple[Fraction, Fraction]] = []
    # stack of (polynomial on (0,1), k, c): the node stands for (c/2^k, (c+1)/2^k)
    stack = [(q, 0, 0)]
    while stack:
        poly, k, c = stack.pop()
        variations = _descartes_01(poly, degree)
        if variations == 0:
            continue
        if variations == 1:
            out.append((Fraction(c, 2**k), Fraction(c + 1, 2**k)))
            continue
        left = _halve(poly, degree)
        right = left(_SHIFT)
        # the midpoint is a root exactly when right(0) == 0
        if right.coeffs() and right.coeffs()[0] == 0:
            out.append((Fraction(2 * c + 1, 2 ** (k + 1)),) * 2)
            right = flint.fmpz_poly(right.coeffs()[1:])
            # left(1) is the same root; remove it from the left child too
            left = flint.fmpz_poly(_divide_by_x_minus_1(left.coeffs()))
        stack.append((right, k + 1, 2 * c + 1))
        stack.append((left, k + 1, 2 * c))
    out.sort()
    return out


def _divide_by_x_minus_1(coeffs: list[flint.fmpz]) -> list[flint.fmpz]:
    """Synthetic division by (x - 1) of a polynomial known to vanish at 1."""
    n = len(coeffs) - 1
    quotient = [flint.fmpz(0)] * n
    carry = flint.fmpz(0)
    for i in range(n, 0, -1):
        carry = coeffs[i] + carry
        quotient[i - 1] = carry
    return quotient


def _map_interval(p: flint.fmpq_poly, lo: flint.fmpq, hi: flint.fmpq) -> flint.fmpz_poly:
    """Integer polynomial q with q(t) proportional (positively) to p(lo + (hi - lo) t)."""
    return p(flint.fmpq_poly([lo, hi - lo])).numer()


def _squarefree_factors(p: flint.fmpq_poly) -> list[tuple[flint.fmpz_poly, int]]:
    _, factors = p.numer().factor_squarefree()
    return [(f, m) for f, m in factors if f.degree() > 0]


def cauchy_bound(p: flint.fmpq_poly) -> flint.fmpq:
    """A rational bound ``R`` with every real root of ``p`` in ``[-R, R]``.

    >>> cauchy_bound(flint.fmpq_poly([-6, 1, 1]))   # roots 2 and -3
    7
    """
    coeffs = p.numer().coeffs()
    lead = abs(coeffs[-1])
    bound = max((abs(a) for a in coeffs[:-1]), default=flint.fmpz(0))
    return flint.fmpq(1) + flint.fmpq(bound, lead)


def real_roots(p: Any, lo: Number | None, hi: Number | None, var: sp.Symbol | None = None) -> list[RealRoot]:
    """All real roots of ``p`` in the closed interval ``[lo, hi]``, isolated exactly.

    ``lo`` / ``hi`` may be ``None`` for an unbounded side (a Cauchy bound is used). Each root
    appears once, with its multiplicity.

    >>> roots = real_roots(flint.fmpq_poly([0, -1, 0, 1]) ** 2, -1, 1)   # (c**3 - c)**2
    >>> [(r.approx(5), r.is_exact, r.multiplicity) for r in roots]
    [('-1.0', True, 2), ('0.0', True, 2), ('1.0', True, 2)]
    """
    p = as_fmpq_poly(p, var)
    if p.is_zero():
        raise ValueError("the zero polynomial has every point as a root")
    if lo is None or hi is None:
        bound = cauchy_bound(p)
        lo = -bound if lo is None else lo
        hi = bound if hi is None else hi
    lo_q, hi_q = as_fmpq(lo), as_fmpq(hi)
    if lo_q > hi_q:
        raise ValueError("empty interval")
    roots: list[RealRoot] = []
    for factor, multiplicity in _squarefree_factors(p):
        for piece in _split_rational_roots(factor):
            roots.extend(_roots_of_squarefree(piece, multiplicity, lo_q, hi_q))
    return _separate(roots)


#: Factors up to this degree are fully factored so that rational roots come out exact.
_FACTOR_DEGREE = 40


def _split_rational_roots(factor: flint.fmpz_poly) -> list[flint.fmpz_poly]:
    """Split off the linear factors (rational roots) of a low-degree squarefree factor."""
    if factor.degree() <= 1 or factor.degree() > _FACTOR_DEGREE:
        return [factor]
    _, irreducible = factor.factor()
    linear = [f for f, _ in irreducible if f.degree() == 1]
    if not linear:
        return [factor]
    rest = flint.fmpz_poly(1)
    for f, _ in irreducible:
        if f.degree() > 1:
            rest *= f
    return linear + ([rest] if rest.degree() > 0 else [])


def _separate(roots: list[RealRoot]) -> list[RealRoot]:
    """Sort roots of coprime factors, refining until their intervals are disjoint."""
    roots = sorted(roots, key=lambda r: (r.lo, r.hi))
    changed = True
    while changed:
        changed = False
        for i in range(len(roots) - 1):
            a, b = roots[i], roots[i + 1]
            if a.hi > b.lo or (a.hi == b.lo and not (a.is_exact and b.is_exact)):
                # distinct roots: halving both intervals eventually separates them
                if not a.is_exact:
                    roots[i] = a.refine((a.hi - a.lo) / 2)
                if not b.is_exact:
                    roots[i + 1] = b.refine((b.hi - b.lo) / 2)
                changed = True
        roots.sort(key=lambda r: (r.lo, r.hi))
    return roots


def _deflate(factor: flint.fmpz_poly, root: flint.fmpq) -> flint.fmpz_poly:
    """Divide out the linear factor of a rational root (exact)."""
    quotient, remainder = divmod(factor, flint.fmpz_poly([-root.p, root.q]))
    if remainder != 0:
        raise DerivationError(f"{root} is not a root of the factor")
    return quotient


def _roots_of_squarefree(
    factor: flint.fmpz_poly, multiplicity: int, lo: flint.fmpq, hi: flint.fmpq
) -> list[RealRoot]:
    exact_roots: list[flint.fmpq] = []
    intervals: list[tuple[flint.fmpq, flint.fmpq]] = []
    if factor.degree() == 1:
        a0, a1 = factor.coeffs()
        root = flint.fmpq(-a0, a1)
        return [RealRoot(root, root, factor, multiplicity)] if lo <= root <= hi else []
    if lo == hi:
        if factor(lo) == 0:
            exact_roots.append(lo)
    else:
        q = _map_interval(flint.fmpq_poly(factor), lo, hi)
        coeffs = q.coeffs()
        if coeffs[0] == 0:  # root at lo
            exact_roots.append(lo)
            coeffs = coeffs[1:]
        if sum(coeffs) == 0:  # root at hi
            exact_roots.append(hi)
            coeffs = _divide_by_x_minus_1(coeffs)
        q = flint.fmpz_poly(coeffs)
        if q.degree() > 0:
            width = hi - lo
            for a, b in _isolate_open_01(q):
                a_q = lo + width * flint.fmpq(a.numerator, a.denominator)
                b_q = lo + width * flint.fmpq(b.numerator, b.denominator)
                if a_q == b_q:
                    exact_roots.append(a_q)
                else:
                    intervals.append((a_q, b_q))
    # Refinement needs a polynomial that does not vanish at interval ends, which may be
    # exact roots of the same factor: divide those out.
    reduced = factor
    for root in exact_roots:
        reduced = _deflate(reduced, root)
    roots = [RealRoot(r, r, factor, multiplicity) for r in exact_roots]
    roots += [RealRoot(a, b, reduced, multiplicity) for a, b in intervals]
    return roots


def _squarefree_part(p: flint.fmpq_poly) -> flint.fmpz_poly:
    out = flint.fmpz_poly(1)
    for factor, _ in _squarefree_factors(p):
        out *= factor
    return out


def _gap_points(
    roots: list[RealRoot], lo: flint.fmpq | None, hi: flint.fmpq | None
) -> list[flint.fmpq]:
    """One rational point strictly inside each gap between consecutive roots (and the ends).

    ``roots`` are the disjoint isolated roots of one squarefree polynomial, sorted.
    """
    points: list[flint.fmpq] = [end for end in (lo, hi) if end is not None]
    previous: flint.fmpq | None = lo  # right edge of the last root (or the interval's start)
    for root in roots:
        # shrink an interval that touches the previous edge, so the gap has an interior
        while previous is not None and not root.is_exact and root.lo <= previous:
            root = root.refine((root.hi - root.lo) / 2)
        if previous is None:
            points.append(root.lo - 1)
        elif previous < root.lo:
            points.append((previous + root.lo) / 2)
        previous = root.hi
    if previous is None:
        points.append(flint.fmpq(0))
    elif hi is None:
        points.append(previous + 1)
    elif previous < hi:
        points.append((previous + hi) / 2)
    return points


@dataclass(frozen=True, slots=True)
class NonnegativeResult:
    """Whether a polynomial is >= 0 on an interval; ``witness`` is a rational point where it
    is negative (when it is not), re-checked by exact evaluation."""

    holds: bool
    witness: sp.Rational | None = None
    touches_zero: tuple[RealRoot, ...] = ()

    def __repr__(self) -> str:
        return f"NonnegativeResult(holds={self.holds}, witness={self.witness})"


def nonnegative_on(p: Any, lo: Number | None, hi: Number | None, var: sp.Symbol | None = None,
                   touching: bool = True) -> NonnegativeResult:
    """Decide exactly whether ``p >= 0`` on ``[lo, hi]`` (``None`` = unbounded side).

    When it fails, the witness is a rational point where ``p < 0``. When it holds, the roots
    in the interval (where ``p`` touches zero) are returned, unless ``touching=False`` (a
    certificate that only needs the decision skips that second isolation).

    >>> nonnegative_on(flint.fmpq_poly([1, -2, 1]), -1, 1)       # (c - 1)**2
    NonnegativeResult(holds=True, witness=None)
    >>> nonnegative_on(flint.fmpq_poly([-1, 0, 1]), 0, None)     # x**2 - 1 on [0, oo)
    NonnegativeResult(holds=False, witness=0)
    """
    p = as_fmpq_poly(p, var)
    if p.is_zero():
        return NonnegativeResult(True)
    lo_q = as_fmpq(lo) if lo is not None else None
    hi_q = as_fmpq(hi) if hi is not None else None
    if p.degree() == 0:
        holds = p.coeffs()[0] >= 0
        return NonnegativeResult(holds, None if holds else to_rational(lo_q if lo_q is not None else hi_q if hi_q is not None else flint.fmpq(0)))
    # p changes sign only at roots of its squarefree part, whose isolated roots are disjoint
    sqf = flint.fmpq_poly(_squarefree_part(p))
    roots = real_roots(sqf, lo_q, hi_q)
    for point in _gap_points(roots, lo_q, hi_q):
        if p(point) < 0:
            return NonnegativeResult(False, to_rational(point))
    return NonnegativeResult(True, None, tuple(real_roots(p, lo_q, hi_q)) if touching else ())


@dataclass(frozen=True, slots=True)
class Minimum:
    """The exact minimum of a rational function on an interval.

    ``argmin`` is an exact rational endpoint or an isolated :class:`RealRoot` of the derivative's
    numerator; ``value`` is an ``arb`` ball certified to contain the minimum value; ``exact`` is
    the exact minimum as a SymPy number when the minimiser is rational.
    """

    argmin: sp.Rational | RealRoot
    value: flint.arb
    exact: sp.Expr | None

    def argmin_approx(self, digits: int = 15) -> str:
        if isinstance(self.argmin, RealRoot):
            return self.argmin.approx(digits)
        return str(sp.N(self.argmin, digits))


def _arb_eval(p: flint.fmpq_poly, point: flint.arb) -> flint.arb:
    return p.numer()(point) / flint.arb(p.denom())


#: Up to this total degree every stationary point is isolated; above it the minimum is
#: localised on a ball-arithmetic grid and certified by one non-negativity proof.
_EXHAUSTIVE_DEGREE = 24


def _dyadic(value: flint.arb, bits: int) -> flint.fmpq:
    """The ball's midpoint rounded to a dyadic rational with ``bits`` fractional bits."""
    scaled = value.mid() * flint.arb(2) ** bits
    return flint.fmpq(int(scaled.floor().unique_fmpz()), 2**bits)


def _floor_to(value: flint.fmpq, grain: flint.fmpq) -> flint.fmpq:
    return grain * int((value / grain).floor())


def _ceil_to(value: flint.fmpq, grain: flint.fmpq) -> flint.fmpq:
    return grain * int((value / grain).ceil())


def arb_to_fmpq(value: flint.arb) -> flint.fmpq:
    """The midpoint of an arb ball as an exact rational (its mantissa and binary exponent)."""
    man, exp = value.mid().man_exp()
    return flint.fmpq(man) * (flint.fmpq(2) ** int(exp) if exp >= 0 else flint.fmpq(1, 2 ** int(-exp)))


def minimise_rational(
    num: Any, den: Any, lo: Number, hi: Number, var: sp.Symbol | None = None, bits: int = 200
) -> Minimum:
    """Exact minimum of ``num/den`` over the closed interval ``[lo, hi]``.

    ``den`` must not vanish on ``[lo, hi]`` (cancel removable singularities first). The
    minimiser is an endpoint or a root of ``num' den - num den'``. For low degrees every such
    root is isolated and the candidates are compared with certified ball arithmetic; for high
    degrees (long delays) the minimum is localised on a ball-arithmetic grid, the derivative's
    roots are isolated only there, and global optimality is *proved* by one exact
    non-negativity test of ``num - m den`` with ``m`` just below the candidate minimum (falling
    back to the exhaustive method if that proof fails).

    >>> m = minimise_rational(flint.fmpq_poly([0, -1, 0, 1]), flint.fmpq_poly([1]), -1, 1)
    >>> m.argmin_approx(8), m.exact                       # c**3 - c: min at 1/sqrt(3)
    ('0.57735027', None)
    """
    num = as_fmpq_poly(num, var)
    den = as_fmpq_poly(den, var)
    lo_q, hi_q = as_fmpq(lo), as_fmpq(hi)
    if den.degree() > 0 and any(True for _ in real_roots(den, lo_q, hi_q)):
        raise ValueError("the denominator vanishes on the interval")
    if lo_q < hi_q and num.degree() + den.degree() > 4:   # low degrees: isolating everything is cheaper
        found = _endpoint_minimum(num, den, lo_q, hi_q)
        if found is not None:
            return found
    if num.degree() + den.degree() > _EXHAUSTIVE_DEGREE and lo_q < hi_q:
        found = _localised_minimum(num, den, lo_q, hi_q, bits)
        if found is not None:
            return found
    candidates: list[flint.fmpq | RealRoot] = [lo_q, hi_q]
    deriv = num.derivative() * den - num * den.derivative()
    if not deriv.is_zero() and deriv.degree() > 0:
        candidates.extend(r if not r.is_exact else r.lo for r in real_roots(deriv, lo_q, hi_q))
    return _best_candidate(num, den, candidates, bits)


def _ball_quotients(num: flint.fmpq_poly, den: flint.fmpq_poly, points: list[flint.fmpq]) -> list[flint.arb]:
    """Balls enclosing ``num/den`` at exact rational points (the monomial form loses about the
    coefficients' height in bits to cancellation, so that much precision is added)."""
    height = max(num.numer().height_bits(), den.numer().height_bits())
    with flint_precision(64 + height):
        balls = [flint.arb(p) for p in points]
        nums = flint.arb_poly(num).evaluate(balls, algorithm="iter")
        dens = flint.arb_poly(den).evaluate(balls, algorithm="iter")
        return [a / b for a, b in zip(nums, dens)]


def _endpoint_minimum(num: flint.fmpq_poly, den: flint.fmpq_poly, lo: flint.fmpq, hi: flint.fmpq) -> Minimum | None:
    """The minimum when it sits at an endpoint (often: the worst case at ``c = -1`` or ``1``).

    One exact non-negativity test of ``num - m den`` with ``m`` the smaller endpoint value proves
    it; a ball-arithmetic sample that lies below ``m`` rules the shortcut out first, so an
    interior minimum costs a cheap screen, not a failed proof. ``None`` when not proved."""
    value, point = min(((num(p) / den(p), p) for p in (lo, hi)), key=lambda vp: vp[0])
    count = max(16, 2 * max(num.degree(), den.degree(), 1))
    samples = [lo + (hi - lo) * flint.fmpq(k, count) for k in range(1, count)]
    if any(q.is_finite() and arb_to_fmpq(q.upper()) < value for q in _ball_quotients(num, den, samples)):
        return None
    sign = 1 if den(lo) > 0 else -1
    if not nonnegative_on(sign * (num - value * den), lo, hi, touching=False).holds:
        return None
    return Minimum(to_rational(point), flint.arb(value), to_rational(value))


def _best_candidate(num: flint.fmpq_poly, den: flint.fmpq_poly, candidates: list, bits: int) -> Minimum:
    """The candidate with the smallest value, by adaptive refinement: every candidate starts
    with a coarse ball; those whose value ball lies above the best one are dropped, and only
    the survivors are refined further (precision doubles each round)."""

    def value(cand: flint.fmpq | RealRoot, width_bits: int) -> flint.arb:
        point = cand.ball(width_bits) if isinstance(cand, RealRoot) else flint.arb(cand)
        return _arb_eval(num, point) / _arb_eval(den, point)

    height = max(num.numer().height_bits(), den.numer().height_bits())
    active = list(range(len(candidates)))
    width_bits = 16
    old_prec = flint.ctx.prec
    try:
        while True:
            flint.ctx.prec = 64 + height + width_bits
            values = {i: value(candidates[i], width_bits) for i in active}
            best = min(active, key=lambda i: values[i].mid())
            best_value = values[best]
            active = [i for i in active if i == best or not (values[i] > best_value)]
            if (len(active) == 1 and best_value.rad() < flint.arb(2) ** (-bits // 2)) or width_bits >= 4 * (bits + height):
                break
            width_bits *= 2
    finally:
        flint.ctx.prec = old_prec
    chosen = candidates[best]
    if isinstance(chosen, RealRoot):
        return Minimum(chosen, best_value, None)
    exact_value = to_rational(num(chosen) / den(chosen))
    return Minimum(to_rational(chosen), best_value, exact_value)


def _localised_minimum(
    num: flint.fmpq_poly, den: flint.fmpq_poly, lo: flint.fmpq, hi: flint.fmpq, bits: int, keep: int = 4
) -> Minimum | None:
    """Grid localisation + exact isolation in brackets + a global non-negativity certificate."""
    degree = max(num.degree(), den.degree())
    count = max(64, 4 * degree)
    mid, half = (lo + hi) / 2, (hi - lo) / 2
    # Chebyshev points of [lo, hi], as exact rationals (ends included), sorted ascending
    points = sorted({lo, hi} | {
        mid + half * arb_to_fmpq(flint.arb(math.cos(math.pi * (k + 0.5) / count))) for k in range(count)
    })
    values = [float(q.mid()) for q in _ball_quotients(num, den, points)]
    last = len(points) - 1
    local = [i for i in range(len(points)) if (i == 0 or values[i] <= values[i - 1]) and (i == last or values[i] <= values[i + 1])]
    local.sort(key=lambda i: values[i])
    deriv = num.derivative() * den - num * den.derivative()
    candidates: list[flint.fmpq | RealRoot] = [lo, hi]
    # brackets rounded outward to dyadics fine enough for the grid (small denominators keep the
    # mapped polynomials of the exact isolation small)
    grain = flint.fmpq(1, 2 ** (2 * max(degree, 2).bit_length() + 8))
    for i in local[:keep]:
        a = max(lo, _floor_to(points[max(i - 1, 0)], grain))
        b = min(hi, _ceil_to(points[min(i + 1, last)], grain))
        if not deriv.is_zero() and deriv.degree() > 0:
            candidates.extend(r if not r.is_exact else r.lo for r in real_roots(deriv, a, b))
    found = _best_candidate(num, den, candidates, bits)
    # certificate: num - m*den >= 0 on [lo, hi] for m just below the candidate minimum
    margin = abs(arb_to_fmpq(found.value.mid())) * flint.fmpq(1, 2**60) + flint.fmpq(1, 2 ** (bits // 2))
    m_low = arb_to_fmpq(found.value.lower()) - margin
    sign = 1 if den(lo) > 0 else -1
    if nonnegative_on(sign * (num - m_low * den), lo, hi, touching=False).holds:
        return found
    return None
