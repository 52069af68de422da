"""Continuous impedances and discrete transfer functions given by exact coefficients: the
terminations and controllers of sampled-data loops, read from text, with their shortage of
passivity."""

from __future__ import annotations

import functools
import math
import re
from collections.abc import Iterable, Mapping
from dataclasses import dataclass
from fractions import Fraction
from typing import Any, Literal, Union

import mpmath
import numpy as np
import sympy as sp

from hapticproof.core.errors import DerivationError, InputFormatError, SceneError

__all__ = ["Impedance", "Clamped", "CLAMPED", "DiscreteTF", "to_fraction"]


#: ``"exact"`` assembles loops from :class:`~fractions.Fraction` entries (certified ball routes start there).
Precision = Literal["float", "mp", "exact"]


Number = Union[int, float, Fraction, sp.Rational]


# --------------------------------------------------------------------------------------------
# numbers
# --------------------------------------------------------------------------------------------
def to_fraction(value: Any, name: str = "value") -> Fraction:
    """Convert a real number exactly to a :class:`~fractions.Fraction`.

    Floats are taken at their binary value (as :func:`hapticproof.core.evidence.exact` does),
    decimal strings and SymPy rationals exactly.

    >>> to_fraction(0.5), to_fraction("0.015"), to_fraction(sp.Rational(1, 3))
    (Fraction(1, 2), Fraction(3, 200), Fraction(1, 3))
    """
    if isinstance(value, bool):
        raise SceneError(f"{name} must be a number, got {value!r}")
    if isinstance(value, Fraction):
        return value
    if isinstance(value, (int, np.integer)):
        return Fraction(int(value))
    if isinstance(value, (float, np.floating)):
        if not math.isfinite(value):
            raise SceneError(f"{name} must be finite, got {value!r}")
        return Fraction(float(value))
    if isinstance(value, mpmath.mpf):
        if not mpmath.isfinite(value):
            raise SceneError(f"{name} must be finite, got {value!r}")
        sign, man, exp, _ = value._mpf_
        return (-1 if sign else 1) * Fraction(int(man)) * Fraction(2) ** int(exp)
    if isinstance(value, sp.Basic):
        if value.is_Rational:
            return Fraction(int(value.p), int(value.q))
        if value.is_Float:
            rational = sp.Rational(value)
            return Fraction(int(rational.p), int(rational.q))
        if value.is_number and value.is_real:
            return Fraction(float(value))
        raise SceneError(f"{name} must be a real number, got {value!r}")
    if isinstance(value, str):
        try:
            return Fraction(value.strip())
        except (ValueError, ZeroDivisionError) as err:
            raise SceneError(f"{name} must be a number, got {value!r}") from err
    raise SceneError(f"{name} must be a real number, got {value!r}")


def as_float(value: Any) -> float:
    if isinstance(value, float):
        return value
    return float(to_fraction(value))


def as_mp(value: Any) -> mpmath.mpf:
    if isinstance(value, mpmath.mpf):
        return value
    frac = to_fraction(value)
    return mpmath.mpf(frac.numerator) / frac.denominator


class NumberField:
    """Arithmetic of one precision: float64 arrays, object arrays of mpmath numbers, or object
    arrays of exact fractions (``"exact"``: the loop as the scene defines it, no rounding)."""

    __slots__ = ("name", "dtype", "num")

    def __init__(self, name: Precision):
        if name not in ("float", "mp", "exact"):
            raise SceneError(f"precision must be 'float', 'mp' or 'exact', got {name!r}")
        self.name = name
        self.dtype = float if name == "float" else object
        self.num = {"float": as_float, "mp": as_mp, "exact": to_fraction}[name]

    def zeros(self, rows: int, cols: int) -> np.ndarray:
        out = np.zeros((rows, cols), dtype=self.dtype)
        if self.dtype is object:
            out[...] = mpmath.mpf(0) if self.name == "mp" else Fraction(0)
        return out

    def eye(self, n: int) -> np.ndarray:
        out = self.zeros(n, n)
        for i in range(n):
            out[i, i] = self.num(1)
        return out


def check_positive(name: str, value: Any) -> None:
    if to_fraction(value, name) <= 0:
        raise SceneError(f"{name} must be positive, got {value}")


def check_delay(name: str, value: Any) -> None:
    if isinstance(value, bool) or not isinstance(value, (int, np.integer, sp.Integer)):
        raise SceneError(f"{name} must be an integer number of samples, got {value!r}")
    if int(value) < 0:
        raise SceneError(f"{name} must be >= 0 samples, got {value}")


def _coefficients(values: Iterable[Any], name: str) -> tuple:
    coeffs = tuple(values)
    for c in coeffs:
        to_fraction(c, name)
    # leading zeros carry no meaning and would break the degree bookkeeping
    while len(coeffs) > 1 and to_fraction(coeffs[0]) == 0:
        coeffs = coeffs[1:]
    if not coeffs:
        raise SceneError(f"{name} needs at least one coefficient")
    return coeffs


# --------------------------------------------------------------------------------------------
# transfer functions
# --------------------------------------------------------------------------------------------
ALLOWED_EXPRESSION = re.compile(r"^[A-Za-z0-9_.+\-*/()^ \t]*$")


IDENTIFIER = re.compile(r"[A-Za-z_][A-Za-z0-9_]*")


@dataclass(frozen=True, slots=True)
class Impedance:
    """A real-rational port impedance ``Z(s) = num(s)/den(s)`` (force per velocity).

    Coefficients are in descending powers of ``s``. ``Z`` may be improper by one degree (a
    mass term ``q s``) and may have a simple pole at ``s = 0`` (a spring ``k/s``); the rest
    must be a strictly proper rational function without a pole at 0.

    Parameters
    ----------
    num, den : tuple of numbers
        Numerator and denominator coefficients (ints, floats, Fractions or SymPy rationals).

    Examples
    --------
    The HVE paper's least-passive active operator ``-z_a + 1/s`` (Section 4):

    >>> Z = Impedance.active_spring(0.01)
    >>> Z(1j)
    (-0.01-1j)
    >>> float(Z.shortage_of_passivity())
    0.01
    """

    num: tuple
    den: tuple

    def __post_init__(self) -> None:
        object.__setattr__(self, "num", _coefficients(self.num, "impedance numerator"))
        object.__setattr__(self, "den", _coefficients(self.den, "impedance denominator"))
        if all(to_fraction(c) == 0 for c in self.den):
            raise SceneError("impedance denominator must not be zero")
        split_impedance(self._exact_num(), self._exact_den())  # validates the structure

    @classmethod
    def zero(cls) -> Impedance:
        """The free termination ``Z = 0`` (no force)."""
        return cls((0,), (1,))

    @classmethod
    def active_spring(cls, z_a: Number, stiffness: Number = 1) -> Impedance:
        """``Z(s) = -z_a + k/s``: shortage of passivity ``z_a`` plus a spring (HVE Fig. 8)."""
        return cls((-to_fraction(z_a, "z_a"), to_fraction(stiffness, "stiffness")), (1, 0))

    @classmethod
    def spring_damper(cls, damping: Number, stiffness: Number = 0) -> Impedance:
        """``Z(s) = d + k/s``: a passive first-order termination (a hand or a soft wall)."""
        d, k = to_fraction(damping, "damping"), to_fraction(stiffness, "stiffness")
        return cls((d, k), (1, 0)) if k else cls((d,), (1,))

    @classmethod
    def from_expression(cls, text: str, params: Mapping[str, Any] | None = None) -> Impedance:
        """Parse a small rational expression in ``s`` such as ``"-z_a + 1/s"``.

        Only ``s``, the names in ``params``, numbers, ``+ - * / ^ **`` and parentheses are
        accepted; anything else raises :class:`~hapticproof.core.errors.InputFormatError`.

        >>> Impedance.from_expression("-z_a + 1/s", {"z_a": sp.Rational(1, 100)})
        Impedance(num=(Fraction(-1, 100), Fraction(1, 1)), den=(Fraction(1, 1), Fraction(0, 1)))
        """
        return _parse_impedance(text, tuple(sorted((params or {}).items())))

    def _exact_num(self) -> tuple[Fraction, ...]:
        return tuple(to_fraction(c) for c in self.num)

    def _exact_den(self) -> tuple[Fraction, ...]:
        return tuple(to_fraction(c) for c in self.den)

    def __call__(self, s: complex) -> complex:
        num = np.polyval([float(c) for c in self._exact_num()], s)
        den = np.polyval([float(c) for c in self._exact_den()], s)
        return complex(num / den)

    @property
    def stiffness(self) -> Fraction:
        """Residue ``k`` of the pole at ``s = 0`` (the termination's static stiffness)."""
        return split_impedance(self._exact_num(), self._exact_den())[2]

    def shortage_of_passivity(self) -> sp.Expr:
        """``z_a = max(0, -inf_w Re Z(jw))``, exact (HVE Definition 4, Fig. 3c).

        >>> Impedance.spring_damper(2, 5).shortage_of_passivity()
        0
        """
        return _shortage(self._exact_num(), self._exact_den())


@functools.lru_cache(maxsize=256)
def _parse_impedance(text: str, params: tuple[tuple[str, Any], ...]) -> Impedance:
    if not isinstance(text, str) or not text.strip():
        raise InputFormatError("the impedance expression is empty")
    if not ALLOWED_EXPRESSION.match(text):
        raise InputFormatError(
            f"impedance {text!r}: only numbers, s, parameter names, + - * / ^ and () allowed"
        )
    names = dict(params)
    for ident in IDENTIFIER.findall(text):
        if ident != "s" and ident not in names:
            known = ", ".join(sorted(names)) or "none"
            raise InputFormatError(
                f"impedance {text!r}: unknown name {ident!r} (use s and --param names: {known})"
            )
    from hapticproof.core.expr import read_expression  # the one reader of user expressions

    s = sp.Symbol("s")
    expr = read_expression(text, "s", where=f"impedance {text!r}")
    expr = expr.xreplace({sym: sp.Rational(to_fraction(names[sym.name], sym.name).numerator,
                                           to_fraction(names[sym.name]).denominator)
                          for sym in expr.free_symbols if sym.name in names})
    if not isinstance(expr, sp.Expr) or expr.free_symbols - {s}:
        raise InputFormatError(f"impedance {text!r} must be a rational function of s")
    num, den = sp.fraction(sp.cancel(sp.together(expr)))
    try:
        pnum, pden = sp.Poly(num, s), sp.Poly(den, s)
    except sp.PolynomialError as err:
        raise InputFormatError(f"impedance {text!r} must be a rational function of s") from err
    if not all(c.is_Rational for c in pnum.all_coeffs() + pden.all_coeffs()):
        raise InputFormatError(f"impedance {text!r} must have real rational coefficients")
    lead = pden.LC()  # monic denominator: one canonical form per impedance
    to_frac = lambda c: Fraction(int((c / lead).p), int((c / lead).q))  # noqa: E731
    try:
        return Impedance(
            tuple(to_frac(c) for c in pnum.all_coeffs()), tuple(to_frac(c) for c in pden.all_coeffs())
        )
    except SceneError as err:
        raise InputFormatError(f"impedance {text!r}: {err}") from err


def _poly_divmod(num: list[Fraction], den: list[Fraction]) -> tuple[list[Fraction], list[Fraction]]:
    """Exact polynomial division (descending coefficients)."""
    num = list(num)
    quotient: list[Fraction] = []
    while len(num) >= len(den):
        q = num[0] / den[0]
        quotient.append(q)
        for i in range(len(den)):
            num[i] -= q * den[i]
        num.pop(0)
    return quotient or [Fraction(0)], num or [Fraction(0)]


@functools.lru_cache(maxsize=512)
def split_impedance(num: tuple[Fraction, ...], den: tuple[Fraction, ...]):
    """``Z = q1 s + q0 + k/s + Zsp(s)``; returns (q1, q0, k, sp_num, sp_den) exactly.

    ``Zsp`` is strictly proper with ``sp_den`` monic and ``sp_den(0) != 0``.
    """
    num, den = list(num), list(den)
    while len(den) > 1 and len(num) > 1 and den[-1] == 0 and num[-1] == 0:
        num.pop()  # cancel a common factor s
        den.pop()
    lead = den[0]
    num = [c / lead for c in num]
    den = [c / lead for c in den]
    quotient, rem = _poly_divmod(num, den)
    if len(quotient) > 2:
        raise SceneError("impedance may be improper by at most one degree (a mass term)")
    q1, q0 = (quotient if len(quotient) == 2 else [Fraction(0)] + quotient)
    # strip the pole at s = 0: den = s**j * den1
    j = 0
    den1 = den[:]
    while len(den1) > 1 and den1[-1] == 0:
        den1.pop()
        j += 1
    if j > 1:
        raise SceneError("impedance may have at most a simple pole at s = 0 (a spring)")
    k = Fraction(0)
    rem = rem[:]
    if j == 1:
        # rem/(s den1) = k/s + r1/den1 with k = rem(0)/den1(0)
        k = rem[-1] / den1[-1]
        padded = [Fraction(0)] * (len(den1) - len(rem)) + rem
        diff = [a - k * b for a, b in zip(padded, den1)]
        if diff[-1] != 0:
            raise DerivationError("the spring term did not split off the impedance")
        rem = diff[:-1] or [Fraction(0)]
        den = den1
    while len(rem) > 1 and rem[0] == 0:
        rem = rem[1:]
    if all(c == 0 for c in rem):
        return q1, q0, k, (Fraction(0),), (Fraction(1),)
    return q1, q0, k, tuple(rem), tuple(den)


@functools.lru_cache(maxsize=256)
def _shortage(num: tuple[Fraction, ...], den: tuple[Fraction, ...]) -> sp.Expr:
    w = sp.Symbol("w", nonnegative=True)
    s = sp.I * w
    to_rat = lambda c: sp.Rational(c.numerator, c.denominator)  # noqa: E731
    n = sum(to_rat(c) * s ** (len(num) - 1 - i) for i, c in enumerate(num))
    d = sum(to_rat(c) * s ** (len(den) - 1 - i) for i, c in enumerate(den))
    re_part = sp.cancel(sp.re(sp.expand(n * sp.conjugate(d))) / sp.expand(d * sp.conjugate(d)))
    candidates = [sp.limit(re_part, w, 0, "+"), sp.limit(re_part, w, sp.oo)]
    critical = sp.Poly(sp.numer(sp.together(sp.diff(re_part, w))), w)
    for root in sp.Poly(critical, w).real_roots() if critical.degree() > 0 else []:
        if root > 0:
            candidates.append(re_part.subs(w, root))
    finite = [c for c in candidates if c.is_finite]
    low = sp.Min(*finite) if finite else sp.Integer(0)
    return sp.Max(0, -low)


@dataclass(frozen=True, slots=True)
class Clamped:
    """A clamped (infinitely stiff) termination: the device cannot move (teleoperator FC)."""


#: The clamped termination.
CLAMPED = Clamped()


Termination = Union[Impedance, Clamped, None]


@dataclass(frozen=True, slots=True)
class DiscreteTF:
    """A proper real-rational discrete transfer function ``H(z) = num(z)/den(z)``.

    Coefficients are in descending powers of ``z``; exact rationals or floats.

    Examples
    --------
    The virtual wall ``K + B(z-1)/(Tz)`` (HVE (16), teleoperator (33)):

    >>> H = DiscreteTF.virtual_wall(K=2, B=sp.Rational(1, 100), T=sp.Rational(1, 1000))
    >>> H.num, H.den
    ((Fraction(12, 1), Fraction(-10, 1)), (Fraction(1, 1), Fraction(0, 1)))
    >>> H(1.0)
    (2+0j)
    """

    num: tuple
    den: tuple

    def __post_init__(self) -> None:
        object.__setattr__(self, "num", _coefficients(self.num, "numerator"))
        object.__setattr__(self, "den", _coefficients(self.den, "denominator"))
        if to_fraction(self.den[0]) == 0:
            raise SceneError("H(z) denominator must not be zero")
        if len(self.num) > len(self.den):
            raise SceneError("H(z) must be proper (causal): deg num <= deg den")

    @classmethod
    def virtual_wall(cls, K: Number, B: Number, T: Number) -> DiscreteTF:
        """``H(z) = K + B(z-1)/(Tz) = ((K + B/T) z - B/T) / z`` with exact coefficients."""
        check_positive("T", T)
        k, b, t = to_fraction(K, "K"), to_fraction(B, "B"), to_fraction(T, "T")
        return cls((k + b / t, -b / t), (Fraction(1), Fraction(0)))

    def __call__(self, z: complex) -> complex:
        num = np.polyval([float(to_fraction(c)) for c in self.num], z)
        den = np.polyval([float(to_fraction(c)) for c in self.den], z)
        return complex(num / den)
