"""Exact real-rational functions of one variable, evaluated numerically.

Coefficients are exact :class:`fractions.Fraction` (SymPy is used only as a computer-algebra
system: ``cancel`` to remove common factors, square-free factorisation for pole multiplicities).
Values are computed with mpmath at a chosen precision (for anything decisive) or with numpy in
double precision (only to screen a frequency grid for candidates).

>>> import sympy as sp
>>> x = sp.Symbol('x')
>>> F = RationalFunction.from_expr((x**2 - 1)/(x - 1)**2, x)
>>> F.num, F.den
([Fraction(1, 1), Fraction(1, 1)], [Fraction(1, 1), Fraction(-1, 1)])
>>> [(complex(r), m) for r, m in F.poles()]
[((1+0j), 1)]
"""

from __future__ import annotations

from fractions import Fraction
from functools import lru_cache
from typing import Any, Sequence

import mpmath
import numpy as np
import sympy as sp

from .result import OracleFailure

__all__ = ["RationalFunction", "to_fraction", "poly_roots", "mpf_of"]


def to_fraction(value: Any) -> Fraction:
    """An exact Fraction from an int, Fraction or SymPy rational (floats are refused)."""
    if isinstance(value, Fraction):
        return value
    if isinstance(value, int):
        return Fraction(value)
    value = sp.sympify(value)
    if not value.is_Rational:
        raise TypeError(f"{value!r} is not an exact rational")
    return Fraction(int(value.p), int(value.q))


def mpf_of(q: Fraction) -> mpmath.mpf:
    """The Fraction at the current mpmath precision."""
    return mpmath.mpf(q.numerator) / q.denominator


def _trim(coeffs: list[Fraction]) -> list[Fraction]:
    i = 0
    while i < len(coeffs) - 1 and coeffs[i] == 0:
        i += 1
    return coeffs[i:] or [Fraction(0)]


def poly_roots(coeffs: Sequence[Fraction], dps: int) -> list[mpmath.mpc]:
    """All complex roots of a polynomial with exact coefficients (highest first), at ``dps``
    digits. Meant for square-free polynomials (simple roots converge to full precision)."""
    coeffs = _trim(list(coeffs))
    deg = len(coeffs) - 1
    if deg <= 0:
        return []
    with mpmath.workdps(dps + 20):
        if deg == 1:
            return [mpmath.mpc(-mpf_of(coeffs[1]) / mpf_of(coeffs[0]))]
        c = [mpf_of(q) for q in coeffs]
        for steps in (100 + 20 * deg, 2000 + 200 * deg):
            try:
                roots = mpmath.polyroots(c, maxsteps=steps, extraprec=3 * dps + 20 * deg)
                return [mpmath.mpc(r) for r in roots]
            except mpmath.libmp.libhyper.NoConvergence:
                continue
    raise OracleFailure(f"polyroots did not converge for a degree {deg} polynomial")


class RationalFunction:
    """``num/den`` with exact coefficients (highest power first), coprime, ``den`` monic."""

    def __init__(self, num: Sequence[Fraction], den: Sequence[Fraction]):
        num, den = _trim([to_fraction(c) for c in num]), _trim([to_fraction(c) for c in den])
        if den == [0]:
            raise ZeroDivisionError("zero denominator")
        lead = den[0]
        self.num = [c / lead for c in num]
        self.den = [c / lead for c in den]
        self._np = (np.array([float(c) for c in self.num]), np.array([float(c) for c in self.den]))
        self._mp_cache: dict[int, tuple] = {}

    # -- construction ---------------------------------------------------------------------------
    @classmethod
    def from_expr(cls, expr: Any, var: sp.Symbol) -> RationalFunction:
        """Cancel common factors exactly and read the coefficients."""
        num, den = sp.fraction(sp.together(sp.sympify(expr)))
        N = sp.Poly(num, var, domain=sp.QQ)
        D = sp.Poly(den, var, domain=sp.QQ)
        g = N.gcd(D)
        if g.degree() > 0:
            N, D = N.quo(g), D.quo(g)
        return cls([to_fraction(c) for c in N.all_coeffs()], [to_fraction(c) for c in D.all_coeffs()])

    def expr(self, var: sp.Symbol) -> sp.Expr:
        n = sum(sp.Rational(c.numerator, c.denominator) * var**k for k, c in enumerate(reversed(self.num)))
        d = sum(sp.Rational(c.numerator, c.denominator) * var**k for k, c in enumerate(reversed(self.den)))
        return n / d

    # -- structure ------------------------------------------------------------------------------
    @property
    def is_zero(self) -> bool:
        return self.num == [0]

    @property
    def relative_degree(self) -> int:
        """``deg den - deg num`` (negative: a pole at infinity)."""
        return (len(self.den) - 1) - (len(self.num) - 1) if not self.is_zero else 10**9

    def den_poly(self, var: sp.Symbol) -> sp.Poly:
        return sp.Poly([sp.Rational(c.numerator, c.denominator) for c in self.den], var, domain=sp.QQ)

    def poles(self, dps: int = 50) -> list[tuple[mpmath.mpc, int]]:
        """Finite poles with multiplicities (square-free factorisation, then roots)."""
        return _poles(tuple(self.den), dps)

    def polynomial_part(self) -> list[Fraction]:
        """Quotient of ``num`` by ``den`` (highest first), exactly."""
        num, den = list(self.num), self.den
        dn, dd = len(num) - 1, len(den) - 1
        if dn < dd:
            return [Fraction(0)]
        quotient = []
        for k in range(dn - dd + 1):
            q = num[k] / den[0]
            quotient.append(q)
            for i in range(len(den)):
                num[k + i] -= q * den[i]
        return quotient

    # -- evaluation -----------------------------------------------------------------------------
    def _mp(self):
        dps = mpmath.mp.dps
        if dps not in self._mp_cache:
            self._mp_cache[dps] = ([mpf_of(c) for c in self.num], [mpf_of(c) for c in self.den])
        return self._mp_cache[dps]

    def mp(self, x: Any) -> mpmath.mpc:
        """Value at ``x`` at the current mpmath precision."""
        n, d = self._mp()
        return mpmath.polyval(n, x) / mpmath.polyval(d, x)

    def mp_parts(self, x: Any) -> tuple[Any, Any]:
        n, d = self._mp()
        return mpmath.polyval(n, x), mpmath.polyval(d, x)

    def np(self, x: np.ndarray) -> np.ndarray:
        """Double-precision values (screening only)."""
        n, d = self._np
        with np.errstate(all="ignore"):
            return np.polyval(n, x) / np.polyval(d, x)

    def c(self, x: complex) -> complex:
        """Double-precision value at one point (plain Horner; screening and refinement only)."""
        n, d = self._np
        a = 0j
        for coef in n:
            a = a * x + coef
        b = 0j
        for coef in d:
            b = b * x + coef
        return a / b if b != 0 else complex("nan")

    def residue(self, pole: Any) -> mpmath.mpc:
        """Residue at a *simple* pole: ``num(p)/den'(p)`` at the current precision."""
        n, d = self._mp()
        dd = [c * (len(d) - 1 - k) for k, c in enumerate(d[:-1])]
        return mpmath.polyval(n, pole) / mpmath.polyval(dd, pole)

    def __repr__(self) -> str:
        return f"RationalFunction({[str(c) for c in self.num]}, {[str(c) for c in self.den]})"


@lru_cache(maxsize=4096)
def _poles(den: tuple[Fraction, ...], dps: int) -> list[tuple[mpmath.mpc, int]]:
    x = sp.Symbol("x")
    D = sp.Poly([sp.Rational(c.numerator, c.denominator) for c in den], x, domain=sp.QQ)
    out = []
    for factor, multiplicity in D.sqf_list()[1]:
        coeffs = [to_fraction(c) for c in factor.all_coeffs()]
        for r in poly_roots(coeffs, dps):
            out.append((r, int(multiplicity)))
    return out
