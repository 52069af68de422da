"""Root counts relative to the unit circle or the imaginary axis without numerics, for the
decision kernel's root location (:func:`hapticproof.exact.kernel.locate_roots`) when ball
arithmetic would need thousands of bits (a pole at ``1 + 1e-300``): pairs of reciprocal
(mirrored) roots and the exact Routh array.

>>> import flint
>>> exact_split(flint.fmpz_poly([10**60 + 1, -2 * 10**60, 10**60]), 0, "disk")   # (z - 1)^2 + 1e-60
(0, 2)
>>> routh_right(flint.fmpq_poly([6, 11, 6, 1]))                 # (s + 1)(s + 2)(s + 3)
0
"""

from __future__ import annotations

from fractions import Fraction

import flint


__all__ = ["routh_right", "exact_split", "approximate_outside"]


def routh_right(p: flint.fmpq_poly) -> int | None:
    """Roots of ``p`` in ``Re s > 0`` (with multiplicity) by the exact Routh array: the sign
    changes of its first column; ``None`` in a singular case (a zero pivot: roots on or
    symmetric about the imaginary axis), where the caller falls back to ball arithmetic."""
    coeffs = [Fraction(int(a.p), int(a.q)) for a in p.coeffs()][::-1]   # highest first
    degree = len(coeffs) - 1
    if degree <= 0:
        return 0
    width = degree // 2 + 1
    rows = [coeffs[0::2] + [Fraction(0)] * (width - len(coeffs[0::2])),
            coeffs[1::2] + [Fraction(0)] * (width - len(coeffs[1::2]))]
    for _ in range(degree - 1):
        a, b = rows[-2], rows[-1]
        if b[0] == 0:
            return None
        rows.append([(b[0] * a[k + 1] - a[0] * b[k + 1]) / b[0] for k in range(width - 1)] + [Fraction(0)])
    column = [row[0] for row in rows[:degree + 1]]
    if any(v == 0 for v in column):
        return None
    return sum(1 for x, y in zip(column, column[1:]) if (x > 0) != (y > 0))


def exact_split(f: flint.fmpz_poly, known_on: int, domain: str) -> tuple[int, int] | None:
    """``(inside, outside)`` of the irreducible ``f`` without numerics: a self-reciprocal (disk)
    or even/odd (half-plane) factor has its other roots in pairs ``r, 1/r`` (``r, -r``), half on
    each side; any other factor has none on the boundary, and the Routh array of its bilinear
    image (``z = (1 + s)/(1 - s)``: ``|z| > 1 <=> Re s > 0``) or of itself counts them."""
    d = f.degree()
    if known_on > 0:
        return (d - known_on) // 2, (d - known_on) // 2
    g = flint.fmpq_poly(f)
    if domain == "disk":
        one_plus, one_minus = flint.fmpq_poly([1, 1]), flint.fmpq_poly([1, -1])
        g = sum((a * one_plus**k * one_minus ** (d - k) for k, a in enumerate(g.coeffs()) if a != 0), flint.fmpq_poly([]))
        if g.degree() != d:                    # a root at z = -1 (s = oo): not an irreducible factor of degree > 1
            return None
    right = routh_right(g)
    return None if right is None else (d - right, right)


def approximate_outside(f: flint.fmpz_poly, outside: int, domain: str) -> list[complex]:
    """Where the ``outside`` roots lie, roughly (for messages only): mpmath roots at 30 digits,
    the largest moduli (or real parts); none when they do not converge quickly (clusters)."""
    import mpmath

    coeffs = [int(c) for c in f.coeffs()][::-1]
    with mpmath.workdps(30):
        try:
            roots = mpmath.polyroots([mpmath.mpf(c) for c in coeffs], maxsteps=60, extraprec=60)
        except (mpmath.libmp.NoConvergence, ZeroDivisionError):
            return []
        points = [complex(float(mpmath.re(r)), float(mpmath.im(r))) for r in roots]
    key = abs if domain == "disk" else (lambda w: w.real)
    return sorted(points, key=key, reverse=True)[:outside]
