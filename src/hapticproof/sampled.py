"""Exact sampled-data loops: zero-order hold by the matrix exponential, spectral stability.

A *scene* is a frozen value object describing one sampled-data loop: continuous devices
(mass ``m``, damping ``b``), their port terminations (an operator or environment impedance
``Z(s)``, free, or clamped), a sampler, a discrete controller ``H(z)`` / ``C(z)``, integer delays
``z**-n`` and a zero-order hold. Three scenes are provided:

* :class:`SingleUser` -- HVE paper (000), Fig. 4a: a device on a virtual wall
  ``H(z) = K + B(z-1)/(Tz)`` with an optional operator ``Z_h(s)`` (Fig. 8 uses ``-z_a + 1/s``);
* :class:`MultiUser` -- HVE paper, Fig. 6/7 and eqs. (37)-(39), (56): ``m`` devices coupled to
  ground and to each other, per-user delays ``n_i`` and operators;
* :class:`Teleoperator` -- teleoperator paper (002), Fig. 2 and eqs. (1)-(7): master and slave
  coupled by position-error controllers, with free, clamped or impedance terminations.

Each scene assembles a :class:`Loop` (continuous plant matrices, discrete controller, ports),
which is discretised **exactly**: ``expm([[A, B], [0, 0]] T) = [[Phi, Gamma], [0, I]]`` gives
the sample-to-sample map of the plant under a zero-order hold, so the discrete closed-loop
matrix is exact up to rounding; no small-step integration is involved. Two precisions are
offered: ``"float"`` (float64, :func:`scipy.linalg.expm`) for speed and ``"mp"`` (mpmath at
``dps`` digits, default 50) as the high-precision reference.

Sign conventions (derived from the mechanics, not copied from the printed equations):

* every device obeys ``m dv/dt = f - b v - u`` where ``f`` is the force its port termination
  applies and ``u`` the held controller force, so a controller with positive DC gain is
  restoring: ``u = H(z) x`` for the virtual wall (HVE (14)-(16));
* a termination of impedance ``Z(s)`` applies ``f = f_ext - Z(s) v`` (HVE Fig. 4b, teleoperator
  (2)); ``Z_h(s) = -z_a + 1/s`` gives ``m dv/dt = f_ext - (b - z_a) v - x - u``;
* teleoperator: with ``e = alpha x_m - x_s`` (002 (6), (31)) the master force is
  ``u_m = C_m(z) e = alpha C(z) e`` and the slave force ``u_s = -C_s(z) e = -C(z) e``. These are
  the forces of the discrete "spring" ``C(z) e**2 / 2`` on both robots, hence restoring. The
  printed (7) has both signs flipped and (13) flips only the master's; neither is restoring
  with (1)'s ``f_h - f_m`` convention.

A free device (no termination stiffness, no ground coupling) has a rigid-body translation mode:
an eigenvalue exactly 1 that no controller gain moves (the free teleoperator, or an m-user HVE
without ground couplings). It is removed exactly by a change of coordinates before eigenvalues
are taken (:func:`closed_loop_matrix`), so "stable" means every other mode is strictly inside
the unit circle.

>>> scene = SingleUser(m=0.015, b=0.02, T=0.001, K=30)
>>> round(spectral_radius(scene), 6), is_stable(scene)
(0.999833, True)
>>> is_stable(SingleUser(m=0.015, b=0.02, T=0.001, K=50))
False
"""

from __future__ import annotations

import functools
import math
import re
from collections.abc import Iterable, Mapping, Sequence
from dataclasses import dataclass
from fractions import Fraction
from typing import Any, Literal, Union

import flint
import mpmath
import numpy as np
import scipy.linalg
import sympy as sp

from hapticproof.errors import DerivationError, InputFormatError, SceneError
from hapticproof.realroots import ball_spectral_radius, flint_precision

__all__ = [
    "Impedance",
    "Clamped",
    "CLAMPED",
    "DiscreteTF",
    "SingleUser",
    "MultiUser",
    "Teleoperator",
    "Scene",
    "Loop",
    "Port",
    "to_fraction",
    "discretize",
    "closed_loop_matrix",
    "closed_loop_matrices",
    "spectral_radius",
    "spectral_radii",
    "is_stable",
    "free_device_boundary",
]

Precision = Literal["float", "mp"]
Number = Union[int, float, Fraction, sp.Rational]


# --------------------------------------------------------------------------------------------
# numbers
# --------------------------------------------------------------------------------------------
def to_fraction(value: Any, name: str = "value") -> Fraction:
    """Convert a real number exactly to a :class:`~fractions.Fraction`.

    Floats are taken at their binary value (as :func:`hapticproof.evidence.exact` does),
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


def _as_float(value: Any) -> float:
    if isinstance(value, float):
        return value
    return float(to_fraction(value))


def _as_mp(value: Any) -> mpmath.mpf:
    if isinstance(value, mpmath.mpf):
        return value
    frac = to_fraction(value)
    return mpmath.mpf(frac.numerator) / frac.denominator


class _Field:
    """Arithmetic of one precision: float64 arrays or object arrays of mpmath numbers."""

    __slots__ = ("name", "dtype", "num")

    def __init__(self, name: Precision):
        if name not in ("float", "mp"):
            raise SceneError(f"precision must be 'float' or 'mp', got {name!r}")
        self.name = name
        self.dtype = float if name == "float" else object
        self.num = _as_float if name == "float" else _as_mp

    def zeros(self, rows: int, cols: int) -> np.ndarray:
        out = np.zeros((rows, cols), dtype=self.dtype)
        if self.dtype is object:
            out[...] = mpmath.mpf(0)
        return out

    def eye(self, n: int) -> np.ndarray:
        out = self.zeros(n, n)
        for i in range(n):
            out[i, i] = self.num(1)
        return out


def _check_positive(name: str, value: Any) -> None:
    if to_fraction(value, name) <= 0:
        raise SceneError(f"{name} must be positive, got {value}")


def _check_delay(name: str, value: Any) -> None:
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
_ALLOWED_EXPRESSION = re.compile(r"^[A-Za-z0-9_.+\-*/()^ \t]*$")
_IDENTIFIER = re.compile(r"[A-Za-z_][A-Za-z0-9_]*")


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
        _split_impedance(self._exact_num(), self._exact_den())  # validates the structure

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
        accepted; anything else raises :class:`~hapticproof.errors.InputFormatError`.

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
        return _split_impedance(self._exact_num(), self._exact_den())[2]

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
    if not _ALLOWED_EXPRESSION.match(text):
        raise InputFormatError(
            f"impedance {text!r}: only numbers, s, parameter names, + - * / ^ and () allowed"
        )
    names = dict(params)
    for ident in _IDENTIFIER.findall(text):
        if ident != "s" and ident not in names:
            known = ", ".join(sorted(names)) or "none"
            raise InputFormatError(
                f"impedance {text!r}: unknown name {ident!r} (use s and --param names: {known})"
            )
    from hapticproof.expr import read_expression   # the one reader of user expressions

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
def _split_impedance(num: tuple[Fraction, ...], den: tuple[Fraction, ...]):
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
        _check_positive("T", T)
        k, b, t = to_fraction(K, "K"), to_fraction(B, "B"), to_fraction(T, "T")
        return cls((k + b / t, -b / t), (Fraction(1), Fraction(0)))

    def __call__(self, z: complex) -> complex:
        num = np.polyval([float(to_fraction(c)) for c in self.num], z)
        den = np.polyval([float(to_fraction(c)) for c in self.den], z)
        return complex(num / den)


# --------------------------------------------------------------------------------------------
# discrete state-space algebra (controllers, delays)
# --------------------------------------------------------------------------------------------
@dataclass(frozen=True, slots=True, eq=False)
class _SS:
    """Discrete state space ``x+ = a x + b y, u = c x + d y`` in one precision."""

    a: np.ndarray
    b: np.ndarray
    c: np.ndarray
    d: np.ndarray


def _static(d: np.ndarray, field: _Field) -> _SS:
    rows, cols = d.shape
    return _SS(field.zeros(0, 0), field.zeros(0, cols), field.zeros(rows, 0), d)


def _series(first: _SS, second: _SS, field: _Field) -> _SS:
    n1, n2 = first.a.shape[0], second.a.shape[0]
    a = field.zeros(n1 + n2, n1 + n2)
    a[:n1, :n1] = first.a
    a[n1:, :n1] = second.b @ first.c
    a[n1:, n1:] = second.a
    b = np.vstack([first.b, second.b @ first.d]) if n1 + n2 else field.zeros(0, first.b.shape[1])
    c = np.hstack([second.d @ first.c, second.c])
    return _SS(a, b, c, second.d @ first.d)


def _diag(systems: Sequence[_SS], field: _Field) -> _SS:
    ns = [s.a.shape[0] for s in systems]
    ins = [s.b.shape[1] for s in systems]
    outs = [s.c.shape[0] for s in systems]
    n, ni, no = sum(ns), sum(ins), sum(outs)
    a, b, c, d = field.zeros(n, n), field.zeros(n, ni), field.zeros(no, n), field.zeros(no, ni)
    i = j = k = 0
    for s, dn, di, do in zip(systems, ns, ins, outs):
        a[i : i + dn, i : i + dn] = s.a
        b[i : i + dn, j : j + di] = s.b
        c[k : k + do, i : i + dn] = s.c
        d[k : k + do, j : j + di] = s.d
        i, j, k = i + dn, j + di, k + do
    return _SS(a, b, c, d)


def _delay(n: int, field: _Field) -> _SS:
    """``z**-n`` on one channel as a shift register (no state when ``n = 0``)."""
    if n == 0:
        return _static(field.eye(1), field)
    a = field.zeros(n, n)
    for i in range(1, n):
        a[i, i - 1] = field.num(1)
    b, c = field.zeros(n, 1), field.zeros(1, n)
    b[0, 0] = field.num(1)
    c[0, n - 1] = field.num(1)
    return _SS(a, b, c, field.zeros(1, 1))


def _tf_ss(tf: DiscreteTF, field: _Field) -> _SS:
    """Controllable canonical realisation of a proper SISO ``H(z)``."""
    num = [field.num(c) for c in tf.num]
    den = [field.num(c) for c in tf.den]
    lead = den[0]
    den = [c / lead for c in den]
    num = [field.num(0)] * (len(den) - len(num)) + [c / lead for c in num]
    n = len(den) - 1
    d = field.zeros(1, 1)
    d[0, 0] = num[0]
    if n == 0:
        return _static(d, field)
    a, b, c = field.zeros(n, n), field.zeros(n, 1), field.zeros(1, n)
    for i in range(n):
        a[0, i] = -den[i + 1]
        c[0, i] = num[i + 1] - num[0] * den[i + 1]
    for i in range(1, n):
        a[i, i - 1] = field.num(1)
    b[0, 0] = field.num(1)
    return _SS(a, b, c, d)


def _wall_ss(K: Any, B: Any, T: Any, field: _Field) -> _SS:
    """``K + B(z-1)/(Tz)``; static when ``B = 0`` (no spurious state)."""
    k, b, t = field.num(K), field.num(B), field.num(T)
    if to_fraction(B) == 0:
        d = field.zeros(1, 1)
        d[0, 0] = k
        return _static(d, field)
    a, bb, c, d = field.zeros(1, 1), field.zeros(1, 1), field.zeros(1, 1), field.zeros(1, 1)
    bb[0, 0] = field.num(1)
    c[0, 0] = -b / t
    d[0, 0] = k + b / t
    return _SS(a, bb, c, d)


# --------------------------------------------------------------------------------------------
# continuous devices and the assembled loop
# --------------------------------------------------------------------------------------------
@dataclass(frozen=True, slots=True, eq=False)
class Port:
    """A port: its force (over ``[state; u; w]``) and velocity (over ``state``) rows.

    ``force . velocity`` is the power flowing from the termination into the system, so
    ``E(t) = int f v dt`` is the energy the system has absorbed (teleoperator (8)).
    """

    name: str
    force: np.ndarray
    velocity: np.ndarray


@dataclass(frozen=True, slots=True, eq=False)
class Loop:
    """An assembled sampled-data loop in one precision.

    Continuous plant ``dxi/dt = a xi + bu u + bw w`` with held controller forces ``u``
    (one per device) and exogenous port forces ``w``; sampled outputs ``y = c xi``
    (device positions); discrete controller ``ctrl`` from ``y`` to ``u`` (delays included).
    """

    T: Any
    a: np.ndarray
    bu: np.ndarray
    bw: np.ndarray
    c: np.ndarray
    ctrl: _SS
    ports: tuple[Port, ...]
    positions: np.ndarray
    velocities: np.ndarray
    rigid: np.ndarray | None
    precision: str

    @property
    def plant_order(self) -> int:
        return self.a.shape[0]

    @property
    def order(self) -> int:
        return self.a.shape[0] + self.ctrl.a.shape[0]


@dataclass(frozen=True, slots=True, eq=False)
class _Device:
    a: np.ndarray
    bu: np.ndarray  # (n, 1)
    bw: np.ndarray  # (n, 1)
    position: np.ndarray  # (1, n)
    velocity: np.ndarray  # (1, n)
    force: np.ndarray  # (1, n + 2): over [state, u, w]


def _device(m: Any, b: Any, term: Termination, field: _Field) -> _Device:
    """One device ``m dv/dt = f - b v - u`` with port force ``f = w - Z(s) v``."""
    one = field.num(1)
    if isinstance(term, Clamped):
        force = field.zeros(1, 2)
        force[0, 0] = one  # the clamp's reaction balances the controller force
        z = field.zeros(0, 1)
        return _Device(field.zeros(0, 0), z, z, field.zeros(1, 0), field.zeros(1, 0), force)
    if term is None:
        q1 = q0 = k = Fraction(0)
        sp_num, sp_den = (Fraction(0),), (Fraction(1),)
    else:
        q1, q0, k, sp_num, sp_den = _split_impedance(term._exact_num(), term._exact_den())
    nz = len(sp_den) - 1 if any(c != 0 for c in sp_num) else 0
    n = 2 + nz
    m_eff = field.num(to_fraction(m) + q1)
    if to_fraction(m) + q1 <= 0:
        raise SceneError("device mass plus the termination's mass term must be positive")
    b_eff = field.num(b) + field.num(q0)
    kk = field.num(k)
    # termination force (without w) as a row over the state: k x + q0 v + Csp xi
    a = field.zeros(n, n)
    term_row = field.zeros(1, n)
    term_row[0, 0] = kk
    term_row[0, 1] = field.num(q0)
    a[0, 1] = one
    if nz:
        den = [field.num(c) for c in sp_den]
        num = [field.num(0)] * (len(sp_den) - len(sp_num)) + [field.num(c) for c in sp_num]
        for i in range(nz):
            a[2, 2 + i] = -den[i + 1]
            term_row[0, 2 + i] = num[i + 1]
        for i in range(1, nz):
            a[2 + i, 2 + i - 1] = one
        a[2, 1] = one  # the strictly proper part is driven by the velocity
    a[1, 0] = -kk / m_eff
    a[1, 1] = -b_eff / m_eff
    for i in range(nz):
        a[1, 2 + i] = -term_row[0, 2 + i] / m_eff
    bu, bw = field.zeros(n, 1), field.zeros(n, 1)
    bu[1, 0] = -one / m_eff
    bw[1, 0] = one / m_eff
    position, velocity = field.zeros(1, n), field.zeros(1, n)
    position[0, 0] = one
    velocity[0, 1] = one
    # f = w - q1 dv/dt - (k x + q0 v + Csp xi)
    q1f = field.num(q1)
    force = field.zeros(1, n + 2)
    force[0, :n] = -q1f * a[1, :] - term_row[0, :]
    force[0, n] = -q1f * bu[1, 0]
    force[0, n + 1] = one - q1f * bw[1, 0]
    return _Device(a, bu, bw, position, velocity, force)


def _assemble(
    T: Any,
    devices: Sequence[_Device],
    names: Sequence[str],
    ctrl: _SS,
    field: _Field,
    rigid_pattern: Sequence[Any] | None,
) -> Loop:
    sizes = [d.a.shape[0] for d in devices]
    n, nd = sum(sizes), len(devices)
    a, bu, bw = field.zeros(n, n), field.zeros(n, nd), field.zeros(n, nd)
    pos, vel = field.zeros(nd, n), field.zeros(nd, n)
    ports = []
    offset = 0
    for i, (dev, size) in enumerate(zip(devices, sizes)):
        sl = slice(offset, offset + size)
        a[sl, sl] = dev.a
        bu[sl, i : i + 1] = dev.bu
        bw[sl, i : i + 1] = dev.bw
        pos[i, sl] = dev.position[0]
        vel[i, sl] = dev.velocity[0]
        force = field.zeros(1, n + 2 * nd)
        force[0, sl] = dev.force[0, :size]
        force[0, n + i] = dev.force[0, size]
        force[0, n + nd + i] = dev.force[0, size + 1]
        ports.append(Port(names[i], force[0], vel[i].copy()))
        offset += size
    rigid = None
    if rigid_pattern is not None:
        rigid = _rigid_vector(pos, [field.num(p) for p in rigid_pattern], ctrl, field)
    return Loop(field.num(T), a, bu, bw, pos.copy(), ctrl, tuple(ports), pos, vel, rigid, field.name)


def _rigid_vector(pos: np.ndarray, pattern: list, ctrl: _SS, field: _Field) -> np.ndarray:
    """Closed-loop eigenvector (eigenvalue 1) of a rigid translation the controller ignores.

    The caller has checked exactly that the controller's output is zero for this constant
    position pattern; the controller states then settle at ``(I - Ac) eta = Bc y``.
    """
    xi = pos.T @ np.array(pattern, dtype=field.dtype)
    y = pos @ xi
    nc = ctrl.a.shape[0]
    if not nc:
        return xi
    lhs = field.eye(nc) - ctrl.a
    rhs = ctrl.b @ y
    if field.name == "float":
        eta = np.linalg.lstsq(lhs.astype(float), rhs.astype(float), rcond=None)[0]
    else:
        sol = mpmath.qr_solve(mpmath.matrix(lhs.tolist()), mpmath.matrix(rhs.tolist()))[0]
        eta = np.array([sol[i] for i in range(nc)], dtype=object)
    return np.concatenate([xi, eta])


def _free(term: Termination) -> bool:
    """The termination exerts no static force on a displaced device (no spring, no clamp)."""
    return term is None or (isinstance(term, Impedance) and term.stiffness == 0)


# --------------------------------------------------------------------------------------------
# scenes
# --------------------------------------------------------------------------------------------
def _check_termination(name: str, term: Any) -> None:
    if term is not None and not isinstance(term, (Impedance, Clamped)):
        raise SceneError(f"{name} must be an Impedance, CLAMPED or None, got {term!r}")


@dataclass(frozen=True, slots=True)
class SingleUser:
    """A single-user haptic device on a discrete virtual environment (HVE paper Fig. 4a).

    ``m dv/dt = f_h - b v - u``, ``u = z**-n H(z) x*`` through a zero-order hold, with
    ``H(z) = K + B(z-1)/(Tz)`` unless ``environment`` is given, and ``f_h = f_ext - Z_h(s) v``.

    Parameters
    ----------
    m, b : number
        Device mass (> 0) and damping.
    T : number
        Sampling period (> 0).
    K, B : number
        Virtual wall stiffness and damping (ignored when ``environment`` is given).
    delay : int
        Delay ``n = t_d / T`` in samples (>= 0).
    operator : Impedance, optional
        Operator impedance ``Z_h(s)``; ``None`` is the free device (Colgate, Gil).
    environment : DiscreteTF, optional
        A general virtual environment ``H(z)``.

    Examples
    --------
    HVE Fig. 8a at T = 1 ms, z_a = 0.5 b:

    >>> scene = SingleUser(m=0.015, b=0.02, T=0.001, K=15, operator=Impedance.active_spring(0.01))
    >>> is_stable(scene), is_stable(SingleUser(m=0.015, b=0.02, T=0.001, K=25,
    ...                                        operator=Impedance.active_spring(0.01)))
    (True, False)
    """

    m: Any
    b: Any
    T: Any
    K: Any = 0
    B: Any = 0
    delay: int = 0
    operator: Impedance | None = None
    environment: DiscreteTF | None = None

    def __post_init__(self) -> None:
        _check_positive("m", self.m)
        _check_positive("T", self.T)
        for name in ("b", "K", "B"):
            to_fraction(getattr(self, name), name)
        _check_delay("delay", self.delay)
        if self.operator is not None and not isinstance(self.operator, Impedance):
            raise SceneError(f"operator must be an Impedance or None, got {self.operator!r}")
        if self.environment is not None and not isinstance(self.environment, DiscreteTF):
            raise SceneError("environment must be a DiscreteTF or None")

    def loop(self, precision: Precision = "float") -> Loop:
        """Assemble the loop matrices in the given precision."""
        field = _Field(precision)
        if self.environment is None:
            h = _wall_ss(self.K, self.B, self.T, field)
        else:
            h = _tf_ss(self.environment, field)
        ctrl = _series(h, _delay(int(self.delay), field), field)
        device = _device(self.m, self.b, self.operator, field)
        return _assemble(self.T, [device], ["operator"], ctrl, field, self._rigid_pattern())

    def _rigid_pattern(self) -> tuple | None:
        """Exact test: a free device whose environment has zero DC gain keeps a rigid mode."""
        if not _free(self.operator):
            return None
        if self.environment is None:
            dc_zero = to_fraction(self.K) == 0
        else:
            num = sum(to_fraction(c) for c in self.environment.num)
            dc_zero = num == 0 and sum(to_fraction(c) for c in self.environment.den) != 0
        return (1,) if dc_zero else None


def _matrix(values: Any, size: int, name: str) -> tuple[tuple, ...]:
    rows = tuple(tuple(row) for row in values)
    if len(rows) != size or any(len(r) != size for r in rows):
        raise SceneError(f"{name} must be a {size}x{size} matrix")
    for i in range(size):
        if to_fraction(rows[i][i], name) != 0:
            raise SceneError(f"{name} must have a zero diagonal")
        for j in range(size):
            if to_fraction(rows[i][j], name) != to_fraction(rows[j][i], name):
                raise SceneError(f"{name} must be symmetric")
    return rows


@dataclass(frozen=True, slots=True)
class MultiUser:
    """An m-user haptic virtual environment (HVE paper Fig. 6/7, eqs. (37)-(39), (56)).

    Device ``i``: ``m_i dv_i/dt = f_hi - b_i v_i - u_i`` with
    ``u_i = z**-n_i sum_j H_ij(z) x_j*``, ``H_ii = K_0i + sum_k K_ik + (B_0i + sum_k B_ik)
    (z-1)/(Tz)`` and ``H_ij = -(K_ij + B_ij (z-1)/(Tz))``.

    Parameters
    ----------
    masses, dampings : tuple of numbers
        ``m_i > 0`` and ``b_i``.
    T : number
        Sampling period.
    ground_stiffness, ground_damping : tuple of numbers
        ``K_0i`` and ``B_0i``.
    coupling_stiffness, coupling_damping : tuple of tuples
        Symmetric ``K_ij`` and ``B_ij`` with zero diagonal (any graph).
    delays : tuple of int
        ``n_i`` in samples.
    operators : tuple of Impedance or None
        Per-user operator impedances.

    Examples
    --------
    HVE Fig. 8d (dual user, ``K_01 = K_02 = K_12 = K/2``) at T = 1 ms:

    >>> scene = MultiUser.uniform(2, m=0.015, b=0.01822, T=0.001, K=20)
    >>> scene.coupling_stiffness
    ((0, 10), (10, 0))
    >>> is_stable(scene)
    True
    """

    masses: tuple
    dampings: tuple
    T: Any
    ground_stiffness: tuple
    ground_damping: tuple
    coupling_stiffness: tuple
    coupling_damping: tuple
    delays: tuple
    operators: tuple

    def __post_init__(self) -> None:
        users = len(self.masses)
        if users < 1:
            raise SceneError("a multi-user scene needs at least one user")
        for name in ("masses", "dampings", "ground_stiffness", "ground_damping", "delays", "operators"):
            value = tuple(getattr(self, name))
            object.__setattr__(self, name, value)
            if len(value) != users:
                raise SceneError(f"{name} must have one entry per user ({users})")
        for i in range(users):
            _check_positive(f"m_{i + 1}", self.masses[i])
            to_fraction(self.dampings[i], f"b_{i + 1}")
            to_fraction(self.ground_stiffness[i], f"K_0{i + 1}")
            to_fraction(self.ground_damping[i], f"B_0{i + 1}")
            _check_delay(f"n_{i + 1}", self.delays[i])
            _check_termination(f"operator {i + 1}", self.operators[i])
        _check_positive("T", self.T)
        object.__setattr__(
            self, "coupling_stiffness", _matrix(self.coupling_stiffness, users, "K_ij")
        )
        object.__setattr__(self, "coupling_damping", _matrix(self.coupling_damping, users, "B_ij"))

    @classmethod
    def uniform(
        cls,
        users: int,
        m: Any,
        b: Any,
        T: Any,
        K: Any,
        B: Any = 0,
        delay: int = 0,
        operator: Termination = None,
    ) -> MultiUser:
        """Identical users, every ground and pairwise coupling ``K/2`` and ``B/2``.

        This is the HVE paper's Fig. 8d/e setting (``K_01 = K_02 = K_12 = K/2``).
        """
        if isinstance(users, bool) or not isinstance(users, int) or users < 1:
            raise SceneError(f"users must be a positive integer, got {users!r}")
        half_k, half_b = _half(K, "K"), _half(B, "B")
        off = lambda v: tuple(tuple(0 if i == j else v for j in range(users)) for i in range(users))  # noqa: E731
        return cls(
            masses=(m,) * users,
            dampings=(b,) * users,
            T=T,
            ground_stiffness=(half_k,) * users,
            ground_damping=(half_b,) * users,
            coupling_stiffness=off(half_k),
            coupling_damping=off(half_b),
            delays=(delay,) * users,
            operators=(operator,) * users,
        )

    @property
    def users(self) -> int:
        return len(self.masses)

    def stiffness_matrix(self) -> list[list[Fraction]]:
        """``K_ii = K_0i + sum_k K_ik``, ``K_ij = -K_ij`` (exact)."""
        return _laplacian(self.ground_stiffness, self.coupling_stiffness)

    def damping_matrix(self) -> list[list[Fraction]]:
        """``B_ii = B_0i + sum_k B_ik``, ``B_ij = -B_ij`` (exact)."""
        return _laplacian(self.ground_damping, self.coupling_damping)

    def loop(self, precision: Precision = "float") -> Loop:
        field = _Field(precision)
        users = self.users
        kmat, bmat = self.stiffness_matrix(), self.damping_matrix()
        t = field.num(self.T)
        k_arr = np.array([[field.num(v) for v in row] for row in kmat], dtype=field.dtype)
        b_arr = np.array([[field.num(v) for v in row] for row in bmat], dtype=field.dtype)
        if any(v != 0 for row in bmat for v in row):
            # u = (K + B/T) x_k - (B/T) x_{k-1}: the state holds the previous positions
            h = _SS(field.zeros(users, users), field.eye(users), -b_arr / t, k_arr + b_arr / t)
        else:
            h = _static(k_arr, field)
        delays = _diag([_delay(int(n), field) for n in self.delays], field)
        ctrl = _series(h, delays, field)
        devices = [
            _device(self.masses[i], self.dampings[i], self.operators[i], field) for i in range(users)
        ]
        names = [f"operator {i + 1}" for i in range(users)]
        grounded = any(sum(row) != 0 for row in kmat) or not all(map(_free, self.operators))
        return _assemble(self.T, devices, names, ctrl, field, None if grounded else (1,) * users)


def _half(value: Any, name: str) -> Any:
    """``value / 2`` keeping the caller's number type (floats stay floats, exact stays exact)."""
    if isinstance(value, (float, np.floating)):
        return float(value) / 2
    frac = to_fraction(value, name) / 2
    if isinstance(value, sp.Basic):
        return sp.Rational(frac.numerator, frac.denominator)
    return frac.numerator if frac.denominator == 1 else frac


def _laplacian(ground: tuple, coupling: tuple) -> list[list[Fraction]]:
    n = len(ground)
    out = [[Fraction(0)] * n for _ in range(n)]
    for i in range(n):
        out[i][i] = to_fraction(ground[i]) + sum(to_fraction(coupling[i][k]) for k in range(n))
        for j in range(n):
            if j != i:
                out[i][j] = -to_fraction(coupling[i][j])
    return out


@dataclass(frozen=True, slots=True)
class Teleoperator:
    """A position-error-based sampled-data teleoperator (teleoperator paper Fig. 2, (1)-(7)).

    Master and slave: ``m_m dv_m/dt = f_h - b_m v_m - u_m`` and
    ``m_s dv_s/dt = f_e - b_s v_s - u_s`` with ``u_m = alpha C(z) e*``, ``u_s = -C(z) e*``
    through zero-order holds, ``e = alpha x_m - x_s`` ((30)-(31); ``alpha = 1`` is (6), (17)),
    and ``C(z) = K + B(z-1)/(Tz)`` (33) unless ``controller`` is given. ``delay`` is a
    communication delay in samples on the remote position (0 in the paper).

    Parameters
    ----------
    m_m, m_s, b_m, b_s : number
        Masses (> 0) and dampings.
    T, K, B, alpha : number
        Sampling period, PD gains, position scaling.
    master, slave : Impedance, CLAMPED or None
        Terminations; ``None`` is free motion (zero impedance).
    controller : DiscreteTF, optional
        A general ``C(z)``.
    delay : int
        Communication delay in samples.

    Examples
    --------
    Free/free (FF) teleoperator of the paper's Fig. 3 at T = 15 ms (Table I):

    >>> tele = Teleoperator.symmetric(m=0.015, b=0.01822, T=0.015, K=1.0)
    >>> is_stable(tele), is_stable(Teleoperator.symmetric(m=0.015, b=0.01822, T=0.015, K=2.0))
    (True, False)
    """

    m_m: Any
    m_s: Any
    b_m: Any
    b_s: Any
    T: Any
    K: Any = 0
    B: Any = 0
    alpha: Any = 1
    master: Termination = None
    slave: Termination = None
    controller: DiscreteTF | None = None
    delay: int = 0

    def __post_init__(self) -> None:
        for name in ("m_m", "m_s", "T"):
            _check_positive(name, getattr(self, name))
        for name in ("b_m", "b_s", "K", "B", "alpha"):
            to_fraction(getattr(self, name), name)
        if to_fraction(self.alpha) == 0:
            raise SceneError("alpha must be non-zero")
        _check_termination("master", self.master)
        _check_termination("slave", self.slave)
        _check_delay("delay", self.delay)
        if self.controller is not None and not isinstance(self.controller, DiscreteTF):
            raise SceneError("controller must be a DiscreteTF or None")

    @classmethod
    def symmetric(cls, m: Any, b: Any, T: Any, K: Any = 0, B: Any = 0, **kwargs: Any) -> Teleoperator:
        """Identical master and slave robots (the paper's simulations and experiments)."""
        return cls(m_m=m, m_s=m, b_m=b, b_s=b, T=T, K=K, B=B, **kwargs)

    def loop(self, precision: Precision = "float") -> Loop:
        field = _Field(precision)
        one = field.num(1)
        al = field.num(self.alpha)
        n = int(self.delay)
        # y = [x_m, x_s] -> [x_m, x_s, z^-n x_m, z^-n x_s]
        split = _SS(
            field.zeros(0, 0), field.zeros(0, 2), field.zeros(4, 0),
            np.array([[one, 0], [0, one], [one, 0], [0, one]], dtype=field.dtype),
        )
        delayed = _diag(
            [_static(field.eye(2), field), _delay(n, field), _delay(n, field)], field
        )
        # e_m = alpha x_m - z^-n x_s (seen by the master), e_s = alpha z^-n x_m - x_s
        errors = _static(np.array([[al, 0, 0, -one], [0, -one, al, 0]], dtype=field.dtype), field)
        if self.controller is None:
            c_one = _wall_ss(self.K, self.B, self.T, field)
        else:
            c_one = _tf_ss(self.controller, field)
        gains = _static(np.array([[al, 0], [0, -one]], dtype=field.dtype), field)
        ctrl = split
        for stage in (delayed, errors, _diag([c_one, c_one], field), gains):
            ctrl = _series(ctrl, stage, field)
        devices = [
            _device(self.m_m, self.b_m, self.master, field),
            _device(self.m_s, self.b_s, self.slave, field),
        ]
        # e = alpha x_m - x_s vanishes on the translation (1, alpha): a rigid mode unless a
        # termination holds its robot in place
        free = _free(self.master) and _free(self.slave)
        return _assemble(
            self.T, devices, ["master", "slave"], ctrl, field, (1, self.alpha) if free else None
        )


Scene = Union[SingleUser, MultiUser, Teleoperator]


# --------------------------------------------------------------------------------------------
# exact discretisation and the closed loop
# --------------------------------------------------------------------------------------------
def discretize(a: Any, b: Any, T: Any, precision: Precision = "float", dps: int = 50):
    """Exact zero-order-hold discretisation ``(Phi, Gamma)`` of ``dx/dt = a x + b u``.

    ``expm([[a, b], [0, 0]] T) = [[Phi, Gamma], [0, I]]`` with ``Phi = e^{aT}`` and
    ``Gamma = int_0^T e^{a s} ds b`` (Van Loan). ``precision="mp"`` uses mpmath at ``dps``
    digits and returns mpmath matrices.

    >>> Phi, Gamma = discretize([[0, 1], [0, -2]], [[0], [1]], 0.1)
    >>> np.round(Phi, 6).tolist(), np.round(Gamma.ravel(), 8).tolist()
    ([[1.0, 0.090635], [0.0, 0.818731]], [0.00468269, 0.09063462])
    """
    if precision == "float":
        a_arr = np.asarray(a, dtype=float)
        b_arr = np.asarray(b, dtype=float).reshape(a_arr.shape[0], -1)
        n, m = b_arr.shape
        aug = np.zeros((n + m, n + m))
        aug[:n, :n], aug[:n, n:] = a_arr, b_arr
        e = scipy.linalg.expm(aug * _as_float(T))
        return e[:n, :n], e[:n, n:]
    with mpmath.workdps(dps):
        a_m = mpmath.matrix([[_as_mp(v) for v in row] for row in np.asarray(a, dtype=object)])
        b_obj = np.asarray(b, dtype=object).reshape(a_m.rows, -1)
        n, m = b_obj.shape
        aug = mpmath.zeros(n + m, n + m)
        for i in range(n):
            for j in range(n):
                aug[i, j] = a_m[i, j]
            for j in range(m):
                aug[i, n + j] = _as_mp(b_obj[i, j])
        e = mpmath.expm(aug * _as_mp(T))
        return e[:n, :n], e[:n, n : n + m]


def _closed_loop_from(loop: Loop, phi: np.ndarray, gamma: np.ndarray) -> np.ndarray:
    """``[[Phi + Gamma D C, Gamma Cc], [Bc C, Ac]]`` over ``[xi; eta]``."""
    ctrl = loop.ctrl
    n, nc = loop.a.shape[0], ctrl.a.shape[0]
    dtype = float if loop.precision == "float" else object
    out = np.zeros((n + nc, n + nc), dtype=dtype)
    out[:n, :n] = phi + gamma @ ctrl.d @ loop.c
    out[:n, n:] = gamma @ ctrl.c
    out[n:, :n] = ctrl.b @ loop.c
    out[n:, n:] = ctrl.a
    return out


def _deflate(matrix: np.ndarray, rigid: np.ndarray) -> np.ndarray:
    """Remove the rigid-body eigenvalue 1 exactly: similarity ``P^-1 A P``, drop a row/column.

    ``P = I + (w - e_a) e_a^T`` maps ``e_a`` to the eigenvector ``w`` (``w_a = 1``), so column
    ``a`` of ``P^-1 A P`` is ``e_a`` and the other eigenvalues are those of the rest.
    """
    idx = int(np.argmax([abs(v) for v in rigid]))
    w = rigid / rigid[idx]
    d = w.copy()
    d[idx] = d[idx] - 1
    ap = matrix.copy()
    ap[:, idx] = ap[:, idx] + matrix @ d
    out = ap - np.outer(d, ap[idx, :])
    keep = [i for i in range(matrix.shape[0]) if i != idx]
    return out[np.ix_(keep, keep)]


def closed_loop_matrix(
    scene: Scene, precision: Precision = "float", dps: int = 50, deflate: bool = True
) -> Any:
    """The exact discrete closed-loop matrix of ``scene`` (sample to sample).

    State ``[plant states; controller and delay states]``. With ``deflate`` the rigid-body
    translation mode (eigenvalue exactly 1 of a free, ungrounded system) is removed.
    ``precision="mp"`` returns an :class:`mpmath.matrix` computed at ``dps`` digits.

    >>> closed_loop_matrix(SingleUser(m=1, b=1, T=0.1, K=1, delay=2)).shape
    (4, 4)
    """
    if precision == "float":
        loop = scene.loop("float")
        phi, gamma = discretize(loop.a, loop.bu, loop.T)
        out = _closed_loop_from(loop, phi, gamma)
        if deflate and loop.rigid is not None:
            out = _deflate(out, loop.rigid)
        return out
    with mpmath.workdps(dps):
        loop = scene.loop("mp")
        phi, gamma = discretize(loop.a, loop.bu, loop.T, precision="mp", dps=dps)
        phi_o = np.array(phi.tolist(), dtype=object).reshape(loop.a.shape)
        gamma_o = np.array(gamma.tolist(), dtype=object).reshape(loop.bu.shape)
        out = _closed_loop_from(loop, phi_o, gamma_o)
        if deflate and loop.rigid is not None:
            out = _deflate(out, loop.rigid)
        return mpmath.matrix(out.tolist())


def closed_loop_matrices(scenes: Sequence[Scene]) -> list[np.ndarray]:
    """Float closed-loop matrices of many scenes, with one batched ``expm`` per plant size."""
    loops = [s.loop("float") for s in scenes]
    out: list[np.ndarray | None] = [None] * len(loops)
    groups: dict[tuple[int, int], list[int]] = {}
    for i, lp in enumerate(loops):
        groups.setdefault(lp.bu.shape, []).append(i)
    for (n, m), idx in groups.items():
        aug = np.zeros((len(idx), n + m, n + m))
        for k, i in enumerate(idx):
            aug[k, :n, :n] = loops[i].a
            aug[k, :n, n:] = loops[i].bu
            aug[k] *= _as_float(loops[i].T)
        expd = scipy.linalg.expm(aug)
        for k, i in enumerate(idx):
            mat = _closed_loop_from(loops[i], expd[k, :n, :n], expd[k, :n, n:])
            if loops[i].rigid is not None:
                mat = _deflate(mat, loops[i].rigid)
            out[i] = mat
    return out  # type: ignore[return-value]


def spectral_radius(scene: Scene, precision: Precision = "float", dps: int = 50) -> Any:
    """Largest eigenvalue modulus of the (deflated) closed loop; ``< 1`` means stable.

    >>> float(spectral_radius(SingleUser(m=1, b=1, T=0.1, K=1), precision="mp", dps=30)) < 1
    True
    """
    if precision == "float":
        return float(np.max(np.abs(np.linalg.eigvals(closed_loop_matrix(scene)))))
    with mpmath.workdps(dps):
        mat = closed_loop_matrix(scene, "mp", dps)
        if mat.rows == 0:
            return mpmath.mpf(0)
        radius = _ball_spectral_radius(mat, dps)
        if radius is not None:
            return radius
        eig = mpmath.eig(mat, left=False, right=False)
        return max(abs(v) for v in eig)


def _ball_spectral_radius(mat: mpmath.matrix, dps: int) -> mpmath.mpf | None:
    """Spectral radius of an mpmath matrix from python-flint's isolating eigenvalue balls.

    Some 40x faster than ``mpmath.eig`` at 30 digits and certified for the matrix as given
    (its entries are already rounded to ``dps`` digits); ``None`` when the balls do not isolate
    the eigenvalues (clusters), and the caller falls back to ``mpmath.eig``."""
    with flint_precision(int(dps * 3.33) + 32):
        radius = ball_spectral_radius(
            flint.acb_mat([[flint.acb(mat[i, j]) for j in range(mat.cols)] for i in range(mat.rows)]))
        return None if radius is None else mpmath.mpf(radius.mid().str(dps + 5, radius=False))


def spectral_radii(scenes: Sequence[Scene]) -> np.ndarray:
    """Spectral radii of many scenes: batched ``expm`` and batched eigenvalues (float64).

    >>> rho = spectral_radii([SingleUser(m=0.015, b=0.02, T=0.001, K=k) for k in (10, 60)])
    >>> (rho < 1).tolist()
    [True, False]
    """
    mats = closed_loop_matrices(scenes)
    out = np.empty(len(mats))
    groups: dict[int, list[int]] = {}
    for i, mat in enumerate(mats):
        groups.setdefault(mat.shape[0], []).append(i)
    for size, idx in groups.items():
        if size == 0:
            out[idx] = 0.0
            continue
        stack = np.stack([mats[i] for i in idx])
        out[idx] = np.max(np.abs(np.linalg.eigvals(stack)), axis=-1)
    return out


def is_stable(scene: Scene) -> bool:
    """Whether every (non-rigid) closed-loop eigenvalue is strictly inside the unit circle."""
    return spectral_radius(scene) < 1


def free_device_boundary(m: Any, b: Any, T: Any, precision: Precision = "float", dps: int = 50) -> Any:
    """Closed-form stability boundary ``K*`` of the free device on ``H = K`` (B = 0, n = 0).

    With ``a = b/m``, ``alpha = a T`` and ``p = e^{-alpha}`` the ZOH equivalent of
    ``1/(s (m s + b))`` is ``G(z) = (m/b^2) ((alpha + p - 1) z + (1 - p - alpha p)) /
    ((z - 1)(z - p))``, so the loop ``1 + K G(z) = 0`` has the quadratic characteristic
    polynomial ``z^2 + a1 z + a0`` with (``kappa = K m / b^2``)
    ``a1 = -(1 + p) + kappa (alpha + p - 1)`` and ``a0 = p + kappa (1 - p - alpha p)``.
    Jury: ``P(1) = kappa alpha (1 - p) > 0`` for every ``K > 0``; ``a0 < 1`` and ``P(-1) > 0``
    give

    ``K* = (b^2/m) min( (1 - p)/(1 - p - alpha p),
    2 (1 + p)/(alpha (1 + p) - 2 (1 - p)) )``

    i.e. ``K* = (b/T) alpha (1 - e^-alpha)/(1 - (1 + alpha) e^-alpha)`` while the complex pair
    leaves first (small ``alpha``; ``K* -> 2b/T (1 + alpha/6 + ...)``, Gil's ``b > KT/2``),
    and the flip (``z = -1``) bound for large ``alpha``. The stable set in ``K > 0`` is the
    single interval ``(0, K*)``: both bounds are linear upper bounds in ``kappa``.

    >>> round(free_device_boundary(0.015, 0.02, 0.001), 6)
    40.008891
    """
    if precision == "float":
        # 1 - p - alpha p ~ alpha^2/2 cancels catastrophically in float64: evaluate at 30 digits
        return float(free_device_boundary(m, b, T, precision="mp", dps=30))
    with mpmath.workdps(dps):
        m_, b_, t_ = _as_mp(m), _as_mp(b), _as_mp(T)
        alpha = b_ * t_ / m_
        p = mpmath.exp(-alpha)
        bound1 = (1 - p) / (1 - p - alpha * p)
        c2 = alpha * (1 + p) - 2 * (1 - p)
        bound2 = 2 * (1 + p) / c2 if c2 > 0 else mpmath.inf
        return b_ * b_ / m_ * min(bound1, bound2)
