r"""The exact arithmetic of the independent checker and its definition-level judge.

Gaussian rationals ``a + j b`` (exact), polynomials read from a certificate's JSON, Horner
evaluation of a transfer function at a point, determinants and the characteristic
coefficients of Hermitian matrices (Faddeev-LeVerrier), Sturm sequences, and the root location
of a polynomial relative to the imaginary axis and the unit circle by the bilinear map and a
Routh-Hurwitz array (after the axis roots are removed as the real roots of ``gcd(Re R(jw),
Im R(jw))``). Nothing here imports the decision kernel: :mod:`hapticproof.exact.checker` and
:mod:`hapticproof.exact.judge` share it.

>>> z = Gaussian(Fraction(3, 5), Fraction(4, 5))
>>> value = eval_transfer({"num": ["1", "1"], "den": ["-1", "1"]}, z)     # (z + 1)/(z - 1) on the circle
>>> value.re, value.im
(Fraction(0, 1), Fraction(-2, 1))
>>> has_root_outside(json_poly(["-2", "1"]), "disk"), has_root_outside(json_poly(["1", "1"]), "halfplane")
(True, False)
"""

from __future__ import annotations

import os
import re
from fractions import Fraction
from collections.abc import Iterator, Mapping
from typing import Any

import flint

__all__ = ["MAX_DEGREE", "MAX_WORK", "CheckFailed", "CheckSkipped", "certificates", "is_kind", "max_degree", "max_work", "budget", "spend",
           "size_of",
           "exact_q", "json_poly", "as_fmpq", "value_at",
           "Gaussian", "horner", "eval_transfer", "normalise", "Sturm", "determinant", "bilinear", "axis_gcd",
           "count_with_multiplicity", "cauchy_bound", "routh_hurwitz", "charpoly_coefficients", "has_root_outside",
           "is_proper"]


#: Sturm sequences above this degree are not computed (the certificate is reported as not
#: re-verified rather than taking minutes); ``HAPTICPROOF_CHECK_MAX_DEGREE`` overrides it.
MAX_DEGREE = 600

class CheckFailed(Exception):
    """A certificate or a judged verdict that does not hold (the reason is the message)."""


class CheckSkipped(Exception):
    """Not re-verified (a degree above the limit): the reason is the message."""


_KIND = re.compile(r"[a-z][a-z0-9]*(?:-[a-z0-9]+)*")


def is_kind(value: Any) -> bool:
    """Whether ``value`` names a kind (a certificate's or a judge's: lower-case words joined by
    ``-``); a sentence under the same key is a note, not an object to check.

    >>> is_kind("chebyshev-sign"), is_kind("slope matrix PSD: ...")
    (True, False)
    """
    return isinstance(value, str) and _KIND.fullmatch(value) is not None


def max_degree() -> int:
    return int(os.environ.get("HAPTICPROOF_CHECK_MAX_DEGREE", MAX_DEGREE))


#: The work one certificate or judge object may cost, in units of (degree x coefficient bits)
#: of the polynomials the Sturm sequences and Routh arrays build (about a second or two on one
#: core): a degree-599 polynomial of random two-digit coefficients costs 1.7e9 (over a minute)
#: and is "not re-verified" after the first 1e8, genuine certificates of delays up to ~250
#: samples stay below it. ``HAPTICPROOF_CHECK_MAX_WORK`` overrides it.
MAX_WORK = 10**8

_BUDGET: list[int] = []


def max_work() -> int:
    return int(os.environ.get("HAPTICPROOF_CHECK_MAX_WORK", MAX_WORK))


class budget:
    """A work budget (:data:`MAX_WORK`) for the checks inside the ``with`` block; past it,
    :func:`spend` raises :class:`CheckSkipped` (the certificate is not re-verified: never
    success)."""

    def __enter__(self) -> None:
        _BUDGET.append(max_work())

    def __exit__(self, *exc: object) -> None:
        _BUDGET.pop()


def spend(units: int) -> None:
    """Count ``units`` of work against the budget in force (none outside :class:`budget`)."""
    if _BUDGET:
        _BUDGET[-1] -= units
        if _BUDGET[-1] < 0:
            raise CheckSkipped(f"the exact arithmetic grew above the checker's work limit of {max_work():.3g} "
                               "(HAPTICPROOF_CHECK_MAX_WORK)")


def size_of(p: flint.fmpq_poly) -> int:
    """``degree x bits`` of a polynomial (its largest numerator or denominator)."""
    coeffs = p.coeffs()
    if not coeffs:
        return 0
    return max(1, p.degree()) * max(max(int(a.p).bit_length(), int(a.q).bit_length()) for a in coeffs)


#: Rows of a constant matrix whose characteristic coefficients the checker recomputes
#: (Faddeev-LeVerrier over exact rationals costs m^4 operations: a report from anyone may hold
#: a matrix of any size); a larger one is "not re-verified".
MAX_MATRIX = 32


def max_matrix() -> int:
    return int(os.environ.get("HAPTICPROOF_CHECK_MAX_MATRIX", MAX_MATRIX))


# ---------------------------------------------------------------------------------------------
# exact numbers
# ---------------------------------------------------------------------------------------------


def certificates(node: Any) -> Iterator[dict]:
    """Every certificate object (a dict with a ``certificate`` kind, :func:`is_kind`) inside a
    JSON value.

    >>> [c["certificate"] for c in certificates({"a": [{"certificate": "sign"}, {"certificate": "a note."}]})]
    ['sign']
    """
    if isinstance(node, Mapping):
        if is_kind(node.get("certificate")):
            yield node
            return
        for value in node.values():
            yield from certificates(value)
    elif isinstance(node, list):
        for value in node:
            yield from certificates(value)


def exact_q(text: Any) -> Fraction:
    """An exact number as a report writes it (``"3/7"``, ``"1e-3"``), within the digit limit:
    ``1e999999999`` from a stranger's file is never built."""
    if isinstance(text, (int, Fraction)) and not isinstance(text, bool):
        return Fraction(text)
    if not isinstance(text, str):
        raise TypeError(f"expected an exact number as text, got {type(text).__name__}")
    from hapticproof.core.limits import check_number_text

    if not text.isascii():
        raise ValueError("not a number (digits 0-9)")
    for part in text.split("/"):
        check_number_text(part, "certificate")
    return Fraction(text)


def json_poly(coeffs: list) -> flint.fmpq_poly:
    return flint.fmpq_poly([flint.fmpq(v.numerator, v.denominator) for v in map(exact_q, coeffs)])


def as_fmpq(v: Fraction) -> flint.fmpq:
    return flint.fmpq(v.numerator, v.denominator)


def value_at(p: flint.fmpq_poly, x: Fraction) -> Fraction:
    r = p(as_fmpq(x))
    return Fraction(int(r.p), int(r.q))


class Gaussian:
    """Gaussian rationals ``a + j b`` (exact)."""

    __slots__ = ("re", "im")

    def __init__(self, re: Fraction, im: Fraction = Fraction(0)):
        self.re, self.im = Fraction(re), Fraction(im)

    def __add__(self, o: Gaussian) -> Gaussian:
        return Gaussian(self.re + o.re, self.im + o.im)

    def __sub__(self, o: Gaussian) -> Gaussian:
        return Gaussian(self.re - o.re, self.im - o.im)

    def __mul__(self, o: Gaussian) -> Gaussian:
        return Gaussian(self.re * o.re - self.im * o.im, self.re * o.im + self.im * o.re)

    def __truediv__(self, o: Gaussian) -> Gaussian:
        d = o.re * o.re + o.im * o.im
        if d == 0:
            raise ZeroDivisionError
        return Gaussian((self.re * o.re + self.im * o.im) / d, (self.im * o.re - self.re * o.im) / d)

    def conj(self) -> Gaussian:
        return Gaussian(self.re, -self.im)

    def is_zero(self) -> bool:
        return self.re == 0 and self.im == 0


def horner(coeffs: list[Fraction], z: Gaussian) -> Gaussian:
    acc = Gaussian(Fraction(0))
    for a in reversed(coeffs):
        acc = acc * z + Gaussian(a)
    return acc


def eval_transfer(entry: dict, z: Gaussian) -> Gaussian:
    num = [exact_q(v) for v in entry["num"]]
    den = [exact_q(v) for v in entry["den"]]
    d = horner(den, z)
    if d.is_zero():
        raise CheckFailed("the witness is a pole of the transfer function")
    value = horner(num, z) / d
    if "factor" in entry:                    # a Gaussian-rational constant factor (e.g. j)
        value = value * Gaussian(exact_q(entry["factor"][0]), exact_q(entry["factor"][1]))
    return value


# ---------------------------------------------------------------------------------------------
# Sturm sequences
# ---------------------------------------------------------------------------------------------


def normalise(p: flint.fmpq_poly) -> flint.fmpq_poly:
    """Divide by a positive constant (|leading coefficient|): signs are unchanged."""
    lead = p.coeffs()[-1]
    return p / abs(lead)


class Sturm:
    """Sturm sequence of a squarefree polynomial: distinct real roots in open intervals."""

    def __init__(self, p: flint.fmpq_poly):
        if p.degree() > max_degree():
            raise CheckSkipped(f"degree {p.degree()} above the checker's limit {max_degree()} (HAPTICPROOF_CHECK_MAX_DEGREE)")
        g = p.gcd(p.derivative()) if p.degree() > 0 else flint.fmpq_poly([1])
        q = p / g if g.degree() > 0 else p            # squarefree, same distinct roots
        self.q = normalise(q) if q.degree() >= 0 and not q.is_zero() else q
        seq = [self.q]
        if self.q.degree() > 0:
            seq.append(normalise(self.q.derivative()))
            while seq[-1].degree() > 0:
                spend(size_of(seq[-1]))
                r = seq[-2] % seq[-1]
                if r.is_zero():
                    break
                seq.append(normalise(-r))
        self.seq = seq

    def _variations(self, x: Fraction | None) -> int:
        signs = []
        for p in self.seq:
            if x is None:  # +oo: signs of the leading coefficients
                value = p.coeffs()[-1] if not p.is_zero() else 0
            else:
                value = p(as_fmpq(x))
            if value != 0:
                signs.append(value > 0)
        return sum(1 for a, b in zip(signs, signs[1:]) if a != b)

    def count_open(self, a: Fraction, b: Fraction | None) -> int:
        """Distinct real roots in the open ``(a, b)`` (``b=None``: ``(a, oo)``)."""
        q = self.q
        if q.degree() <= 0:
            return 0
        # make both ends non-roots by deflating exact rational roots there
        shift = 0
        for end in (a, b):
            if end is not None and q(as_fmpq(end)) == 0:
                shift += 1
        if shift:
            reduced = q
            for end in (a, b):
                if end is not None and reduced(as_fmpq(end)) == 0:
                    reduced = reduced / flint.fmpq_poly([-as_fmpq(end), 1])
            return Sturm(reduced).count_open(a, b)
        return self._variations(a) - self._variations(b)



def determinant(M: list[list[Gaussian]]) -> Gaussian:
    """Exact determinant by Gaussian elimination over the Gaussian rationals."""
    A = [row[:] for row in M]
    n = len(A)
    det = Gaussian(Fraction(1))
    for k in range(n):
        pivot = next((i for i in range(k, n) if not A[i][k].is_zero()), None)
        if pivot is None:
            return Gaussian(Fraction(0))
        if pivot != k:
            A[k], A[pivot] = A[pivot], A[k]
            det = Gaussian(Fraction(0)) - det
        det = det * A[k][k]
        for i in range(k + 1, n):
            factor = A[i][k] / A[k][k]
            for j in range(k, n):
                A[i][j] = A[i][j] - factor * A[k][j]
    return det



def bilinear(p: flint.fmpq_poly) -> flint.fmpq_poly:
    """``(1 - s)^d p((1 + s)/(1 - s))``: the unit disk to the left half plane."""
    d = p.degree()
    one_plus, one_minus = flint.fmpq_poly([1, 1]), flint.fmpq_poly([1, -1])
    out = flint.fmpq_poly([])
    for k, a in enumerate(p.coeffs()):
        if a != 0:
            out += a * one_plus**k * one_minus ** (d - k)
    return out


def axis_gcd(p: flint.fmpq_poly) -> flint.fmpq_poly:
    """``gcd(Re p(jw), Im p(jw))`` as a real polynomial in ``w``."""
    re, im = [], []
    for k, a in enumerate(p.coeffs()):
        unit = k % 4            # j^k = 1, j, -1, -j
        re.append(a if unit == 0 else -a if unit == 2 else flint.fmpq(0))
        im.append(a if unit == 1 else -a if unit == 3 else flint.fmpq(0))
    pr, pi = flint.fmpq_poly(re), flint.fmpq_poly(im)
    if pi.is_zero():
        return pr
    if pr.is_zero():
        return pi
    return pr.gcd(pi)


def count_with_multiplicity(g: flint.fmpq_poly) -> tuple[int, bool]:
    """Real roots of ``g`` counted with multiplicity, and whether all of them are simple."""
    total = 0
    simple = True
    level = 0
    while g.degree() > 0:
        distinct = Sturm(g).count_open(-cauchy_bound(g), cauchy_bound(g))
        if level > 0 and distinct > 0:
            simple = False
        total += distinct
        g = g.gcd(g.derivative())
        level += 1
    return total, simple


def cauchy_bound(p: flint.fmpq_poly) -> Fraction:
    coeffs = [Fraction(int(a.p), int(a.q)) for a in p.coeffs()]
    lead = abs(coeffs[-1])
    return 1 + max((abs(a) for a in coeffs[:-1]), default=Fraction(0)) / lead


def routh_hurwitz(p: flint.fmpq_poly) -> bool:
    """All roots in the open left half plane: the exact Routh array has ``degree + 1`` rows and
    a positive first column (a zero pivot means no)."""
    coeffs = [Fraction(int(a.p), int(a.q)) for a in p.coeffs()][::-1]   # highest first
    if coeffs[0] < 0:
        coeffs = [-a for a in coeffs]
    degree = len(coeffs) - 1
    if degree == 0:
        return True
    if any(a <= 0 for a in coeffs):         # necessary: every coefficient positive
        return False
    width = degree // 2 + 1
    top = coeffs[0::2] + [Fraction(0)] * (width - len(coeffs[0::2]))
    below = coeffs[1::2] + [Fraction(0)] * (width - len(coeffs[1::2]))
    rows = [top, below]
    for _ in range(degree - 1):
        a, b = rows[-2], rows[-1]
        if b[0] <= 0:
            return False
        spend(width * max(max(v.numerator.bit_length(), v.denominator.bit_length()) for v in b))
        rows.append([(b[0] * a[k + 1] - a[0] * b[k + 1]) / b[0] for k in range(width - 1)] + [Fraction(0)])
    return all(row[0] > 0 for row in rows)



def charpoly_coefficients(M: list[list[Gaussian]]) -> list[Fraction]:
    """``E_1..E_m`` (sums of principal minors) by Faddeev-LeVerrier over the Gaussian rationals."""
    m = len(M)
    identity = [[Gaussian(Fraction(int(i == j))) for j in range(m)] for i in range(m)]
    Mk = [row[:] for row in identity]
    coeffs = [Gaussian(Fraction(1))]        # det(lambda I - M) = sum c_k lambda^(m-k)
    for k in range(1, m + 1):
        AM = [[sum((M[i][t] * Mk[t][j] for t in range(m)), Gaussian(Fraction(0))) for j in range(m)] for i in range(m)]
        trace = sum((AM[i][i] for i in range(m)), Gaussian(Fraction(0)))
        ck = Gaussian(-trace.re / k, -trace.im / k)
        coeffs.append(ck)
        Mk = [[AM[i][j] + (identity[i][j] * ck) for j in range(m)] for i in range(m)]
    # E_k = (-1)^k c_k, real for a Hermitian matrix
    return [(-1) ** k * coeffs[k].re for k in range(1, m + 1)]


def has_root_outside(p: flint.fmpq_poly, domain: str = "disk") -> bool:
    """Whether ``p`` has a root strictly outside the closed unit disk (``disk``) or in the open
    right half plane (``halfplane``): the bilinear map for the disk, the imaginary-axis roots and
    mirror pairs removed as the roots of ``gcd(Re R(jw), Im R(jw))``, then a Routh-Hurwitz array.
    Roots at ``z = 0`` and ``z = -1`` (the bilinear map's infinity) are not outside."""
    if p.degree() <= 0:
        return False
    coeffs = p.coeffs()
    zeros = next(k for k, a in enumerate(coeffs) if a != 0)
    core = flint.fmpq_poly(coeffs[zeros:])
    R = bilinear(core) if domain == "disk" else core
    if R.degree() <= 0:
        return False
    g = axis_gcd(R)
    if g.degree() > 0:
        # g's roots: real w0 (axis roots) and mirror pairs +-s0 (one of each pair in Re s > 0)
        axis, _ = count_with_multiplicity(g)
        if g.degree() > axis:
            return True
        parity = next(k for k, a in enumerate(g.coeffs()) if a != 0) % 2
        A = flint.fmpq_poly([a * (-1) ** ((k - parity) // 2) if k % 2 == parity else 0 for k, a in enumerate(g.coeffs())])
        R, remainder = divmod(R, A)
        if not remainder.is_zero():
            raise CheckFailed("the axis factor does not divide the polynomial")
    return R.degree() > 0 and not routh_hurwitz(R)


def is_proper(num: flint.fmpq_poly, den: flint.fmpq_poly, excess: int = 0) -> bool:
    """``deg num <= deg den + excess`` after cancelling their common factor (a pole at infinity
    of order above ``excess`` otherwise): ``excess = 0`` for ``F(z)`` analytic at ``z = oo``,
    ``1`` for ``Z(s)`` (a simple pole at ``s = oo`` is allowed)."""
    if num.is_zero():
        return True
    g = num.gcd(den)
    return (num / g).degree() <= (den / g).degree() + excess
