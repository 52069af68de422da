r"""Exact sampled-data stability boundary of a 1-DOF haptic device on a virtual wall.

The device (mass ``m``, damping ``b``) is driven through a zero-order hold by the delayed virtual
wall ``z^{-n} H(z)``, ``H(z) = K + B(z-1)/(Tz)`` (Gil, Avello, Rubio & Florez, IEEE TCST 12(4),
2004; HVE paper Fig. 4a without operator). With the normalised parameters

.. math:: \alpha = \frac{bT}{m}, \quad \delta = \frac{BT}{m}, \quad \beta = \frac{KT^2}{m},
          \quad p = e^{-\alpha},

the ZOH equivalent of ``1/(s(ms + b))`` is ``(m/b^2)(l_1 z + l_0)/((z-1)(z-p))`` with
``l_1 = \alpha + p - 1`` and ``l_0 = 1 - p - \alpha p`` (both positive for ``alpha > 0``), so
``1 + z^{-n} H(z) G(z) = 0`` has the characteristic polynomial

.. math:: P(z) = \alpha^2 z^{n+1}(z-1)(z-p) + ((\beta + \delta) z - \delta)(l_1 z + l_0)

of degree ``n + 3`` (:func:`characteristic_polynomial`; :func:`derive_characteristic_polynomial`
re-derives it from the model). The loop is stable iff every root is strictly inside the unit
circle.

* ``n = 0``: ``P`` is a cubic whose coefficients are affine in ``beta``; Jury's conditions are
  affine in ``beta`` too, so the critical stiffness has a **closed form**
  (:func:`closed_form_boundary`): the complex-pair bound
  ``beta < alpha(alpha + delta)(1 - p)(alpha^2 - delta l_0) / (l_0 (alpha^2 + delta l_1))``,
  the flip bound (``z = -1``), a lower bound that matters only for large ``delta``, and the
  stiffness-independent damping limit ``delta l_0 < alpha^2`` (larger virtual damping
  destabilises the wall for every ``K``). With ``delta = 0`` this is the free-device formula
  ``K* = (b/T) alpha (1 - p)/(1 - p - alpha p)``.
* ``n >= 1``: a **certified numeric value** (:func:`critical_stiffness`): the crossings of the
  unit circle are the roots of ``Im(A(z) C(1/z)) = sin(theta) V(c)`` with ``P = A + beta C``,
  isolated with arb balls (``p = e^{-alpha}`` is an arb enclosure), and stability between
  crossings is decided by certified root enclosures of ``P``.

:func:`certified_spectral_radius` is an independent certified check of any loop (also with a
continuous operator ``m_h s + b_h + k_h/s``): the exact ZOH transition matrix is enclosed by
``arb_mat.exp`` and its eigenvalues by ``acb_mat.eig``.

>>> cs = critical_stiffness(m="0.015", b="0.02", T="0.001")
>>> cs.mode, round(cs.value, 6)                      # free device: K* = 40.008891
('complex', 40.008891)
>>> round(critical_stiffness(m="0.015", b="0.02", T="0.001", B="0.002", n=2).value, 6)
8.80344
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass, field
from functools import lru_cache
from typing import Any

import flint
import sympy as sp

from hapticproof.core.errors import DerivationError, SceneError
from hapticproof.core.evidence import Decision, Evidence, Method, Outcome, exact
from hapticproof.exact.realroots import ball_spectral_radius, flint_precision
from hapticproof.core.symbols import z as Z_SYM

__all__ = [
    "ALPHA",
    "DELTA",
    "BETA",
    "P",
    "Normalised",
    "Operator",
    "characteristic_polynomial",
    "derive_characteristic_polynomial",
    "jury_cubic",
    "ClosedFormBoundary",
    "closed_form_boundary",
    "CriticalStiffness",
    "critical_stiffness",
    "linear_critical_beta",
    "certified_stable",
    "crossings",
    "stable_between",
    "certified_spectral_radius",
    "arb_interval",
    "arb_midpoint",
]

#: Normalised damping ``bT/m``, virtual damping ``BT/m``, stiffness ``KT^2/m`` (Gil et al. 2004)
#: and the pole ``p = e^{-alpha}`` of the sampled device.
ALPHA = sp.Symbol("alpha", positive=True)
DELTA = sp.Symbol("delta", nonnegative=True)
BETA = sp.Symbol("beta", positive=True)
P = sp.Symbol("p", positive=True)


def _rational(value: Any, name: str) -> sp.Rational:
    try:
        out = exact(value)
    except (TypeError, ValueError, ZeroDivisionError) as err:
        raise SceneError(f"{name}: {value!r} is not a number") from err
    if not out.is_Rational:
        raise SceneError(f"{name} must be a rational number (got {out})")
    return out


def arb_of(value: Any) -> flint.arb:
    """An exact number as an exact (zero-radius) arb ball."""
    q = sp.Rational(value)
    return flint.arb(flint.fmpq(int(q.p), int(q.q)))


def _exact_value(value: flint.arb) -> sp.Rational:
    """The exact rational value of an exact arb number (``man * 2**exp``)."""
    man, exp_ = value.man_exp()
    return sp.Integer(int(man)) * sp.Integer(2) ** int(exp_)


def arb_interval(ball: flint.arb) -> tuple[sp.Rational, sp.Rational]:
    """Exact rational end points ``(lo, hi)`` of an arb ball (midpoint and radius are exact
    binary numbers, so no rounding at the current precision is involved).

    >>> lo, hi = arb_interval(flint.arb(2) / 3)
    >>> lo < sp.Rational(2, 3) < hi
    True
    """
    mid, rad = _exact_value(ball.mid()), _exact_value(ball.rad())
    return mid - rad, mid + rad


def arb_midpoint(ball: flint.arb) -> sp.Rational:
    """The exact midpoint of an arb ball as a rational.

    >>> arb_midpoint(flint.arb("0.5"))
    1/2
    """
    return _exact_value(ball.mid())


# ---------------------------------------------------------------------------------------------
# parameters
# ---------------------------------------------------------------------------------------------


@dataclass(frozen=True, slots=True)
class Normalised:
    """Gil et al.'s normalised parameters ``alpha = bT/m``, ``delta = BT/m``, ``beta = KT^2/m``.

    >>> Normalised.from_physical(m="0.015", b="0.02", T="0.001", K=30)
    Normalised(alpha=1/750, delta=0, beta=1/500)
    """

    alpha: sp.Rational
    delta: sp.Rational
    beta: sp.Rational | None = None

    def __post_init__(self) -> None:
        if not self.alpha > 0:
            raise SceneError(f"alpha = bT/m must be positive, got {self.alpha}")
        if self.delta < 0:
            raise SceneError(f"delta = BT/m must be non-negative, got {self.delta}")

    @classmethod
    def from_physical(cls, m: Any, b: Any, T: Any, K: Any = None, B: Any = 0) -> Normalised:
        m_, b_, T_, B_ = (_rational(v, k) for v, k in ((m, "m"), (b, "b"), (T, "T"), (B, "B")))
        if m_ <= 0 or T_ <= 0:
            raise SceneError("m and T must be positive")
        beta = None if K is None else _rational(K, "K") * T_**2 / m_
        return cls(b_ * T_ / m_, B_ * T_ / m_, beta)


@dataclass(frozen=True, slots=True)
class Operator:
    """A continuous operator ``Z_h(s) = m_h s + b_h + k_h/s`` attached to the device (HVE (2)).

    >>> Operator(1, 2, 3).impedance().num
    (1, 2, 3)
    """

    mass: Any = 0
    damping: Any = 0
    stiffness: Any = 0

    def __post_init__(self) -> None:
        for name in ("mass", "damping", "stiffness"):
            value = _rational(getattr(self, name), name)
            if value < 0:
                raise SceneError(f"operator {name} must be non-negative, got {value}")
            object.__setattr__(self, name, value)

    def impedance(self) -> Any:
        """The same operator as a :class:`hapticproof.systems.impedance.Impedance` (for cross-checks)."""
        from hapticproof.systems.impedance import Impedance

        return Impedance((self.mass, self.damping, self.stiffness), (1, 0))


# ---------------------------------------------------------------------------------------------
# the characteristic polynomial
# ---------------------------------------------------------------------------------------------


def characteristic_polynomial(n: int = 0, alpha: Any = ALPHA, delta: Any = DELTA, beta: Any = BETA,
                              p: Any = P, z: sp.Symbol = Z_SYM) -> sp.Poly:
    r"""``P(z) = alpha^2 z^{n+1}(z-1)(z-p) + ((beta+delta) z - delta)(l_1 z + l_0)``.

    >>> characteristic_polynomial(0, p=sp.Rational(1, 2), alpha=1, delta=0, beta=1).as_expr()
    z**3 - z**2 + z/2
    """
    if int(n) != n or n < 0:
        raise SceneError(f"the delay n must be a non-negative integer, got {n}")
    l1 = alpha + p - 1
    l0 = 1 - p - alpha * p
    expr = alpha**2 * z ** (int(n) + 1) * (z - 1) * (z - p) + ((beta + delta) * z - delta) * (l1 * z + l0)
    return sp.Poly(sp.expand(expr), z)


def _zoh_position_plant(m: sp.Expr, b: sp.Expr, T: sp.Expr, s: sp.Symbol, z: sp.Symbol) -> sp.Expr:
    """``(1 - z^-1) Z{1/(s^2 (m s + b))}`` from partial fractions and the table
    ``1/s^2 -> Tz/(z-1)^2``, ``1/s -> z/(z-1)``, ``1/(s+a) -> z/(z - e^{-aT})``."""
    out = sp.Integer(0)
    for term in sp.Add.make_args(sp.apart(1 / (s**2 * (m * s + b)), s)):
        num, den = sp.fraction(sp.factor(term))
        den_poly = sp.Poly(den, s)
        if den_poly.degree() == 2 and den_poly.as_expr() == den_poly.LC() * s**2:
            out += num / den_poly.LC() * T * z / (z - 1) ** 2
        elif den_poly.degree() == 1 and den_poly.TC() == 0:
            out += num / den_poly.LC() * z / (z - 1)
        elif den_poly.degree() == 1:
            pole = -den_poly.TC() / den_poly.LC()
            out += num / den_poly.LC() * z / (z - sp.exp(pole * T))
        else:  # pragma: no cover - the plant has only these terms
            raise ValueError(f"unexpected partial fraction {term}")
    return sp.cancel((1 - 1 / z) * out)


def derive_characteristic_polynomial(n: int = 0, z: sp.Symbol = Z_SYM) -> sp.Poly:
    """Re-derive ``P(z)`` from the model: ZOH equivalent of the device by partial fractions,
    ``1 + z^{-n} H(z) G(z) = 0`` with ``H = K + B(z-1)/(Tz)``, then ``b = alpha m/T``,
    ``B = delta m/T``, ``K = beta m/T^2`` and ``e^{-alpha} = p``; normalised to the leading
    coefficient ``alpha^2``.

    >>> sp.expand(derive_characteristic_polynomial(1).as_expr() - characteristic_polynomial(1).as_expr())
    0
    """
    m, T = sp.symbols("m T", positive=True)
    s = sp.Symbol("s")
    b, B, K = ALPHA * m / T, DELTA * m / T, BETA * m / T**2
    G = _zoh_position_plant(m, b, T, s, z)
    H = K + B * (z - 1) / (T * z)
    num, _ = sp.fraction(sp.cancel(sp.together(1 + z ** (-int(n)) * H * G)))
    num = sp.expand(sp.powsimp(sp.expand(num)).subs(sp.exp(-ALPHA), P))
    poly = sp.Poly(num, z)
    return sp.Poly(sp.expand(poly.as_expr() * ALPHA**2 / poly.LC()), z)


def jury_cubic(poly: sp.Poly) -> tuple[sp.Expr, ...]:
    r"""Jury's conditions for a real cubic ``a_3 z^3 + a_2 z^2 + a_1 z + a_0`` with ``a_3 > 0``:
    all roots are strictly inside the unit circle iff every returned expression is positive:
    ``P(1)``, ``-P(-1)``, ``a_3 - a_0``, ``a_3 + a_0``, and
    ``a_3^2 - a_0^2 \mp (a_3 a_1 - a_0 a_2)``.

    >>> w = sp.Symbol('w')
    >>> [sp.sign(c) for c in jury_cubic(sp.Poly((w - sp.Rational(1, 2))**3, w))]
    [1, 1, 1, 1, 1, 1]
    """
    a3, a2, a1, a0 = poly.all_coeffs()
    one, minus = poly.eval(1), poly.eval(-1)
    inner = a3 * a1 - a0 * a2
    return (sp.expand(one), sp.expand(-minus), sp.expand(a3 - a0), sp.expand(a3 + a0),
            sp.expand(a3**2 - a0**2 - inner), sp.expand(a3**2 - a0**2 + inner))


# ---------------------------------------------------------------------------------------------
# n = 0: closed form
# ---------------------------------------------------------------------------------------------


@dataclass(frozen=True, slots=True)
class ClosedFormBoundary:
    r"""The exact stability region of the undelayed wall in ``(alpha, delta, beta)``.

    Stable iff ``damping > 0`` and ``max(0, lower) < beta < min(complex_pair, flip)``; each
    bound is the solution of one Jury condition (affine in ``beta``). Expressions are in
    ``alpha``, ``delta`` and ``p = e^{-alpha}``.
    """

    complex_pair: sp.Expr
    flip: sp.Expr
    lower: sp.Expr
    damping: sp.Expr

    def critical_beta(self) -> sp.Expr:
        """``min(complex_pair, flip)`` (the complex pair binds except for large ``alpha``)."""
        return sp.Min(self.complex_pair, self.flip)

    def values(self, alpha: Any, delta: Any, bits: int = 128) -> dict[str, flint.arb]:
        """Certified arb enclosures of the four expressions at rational ``alpha``, ``delta``."""
        with flint_precision(bits):
            a, d = arb_of(alpha), arb_of(delta)
            p = (-a).exp()
            out = {}
            for name in ("complex_pair", "flip", "lower", "damping"):
                out[name] = _arb_eval(getattr(self, name), {ALPHA: a, DELTA: d, P: p})
            return out


@lru_cache(maxsize=64)
def _lambdified(expr: sp.Expr, symbols: tuple[sp.Symbol, ...]) -> Any:
    return sp.lambdify(list(symbols), expr, modules=[{"Min": min, "Max": max}])


def _arb_eval(expr: sp.Expr, values: dict) -> flint.arb:
    """Evaluate a rational expression in the given symbols with arb arithmetic."""
    return _lambdified(expr, tuple(values))(*values.values())


@lru_cache(maxsize=1)
def closed_form_boundary() -> ClosedFormBoundary:
    """Solve Jury's conditions of the undelayed cubic for ``beta`` (derived, not typed in).

    >>> cf = closed_form_boundary()
    >>> sp.factor(cf.complex_pair.subs(DELTA, 0))       # alpha^2 (1 - p)/(1 - p - alpha p)
    alpha**2*(p - 1)/(alpha*p + p - 1)
    """
    one, minus, _, _, inner_minus, inner_plus = jury_cubic(characteristic_polynomial(0))
    solutions = []
    for cond in (inner_minus, minus, inner_plus):
        poly = sp.Poly(cond, BETA)
        if poly.degree() != 1:
            raise DerivationError("Jury conditions of the undelayed wall should be affine in beta")
        solutions.append(sp.factor(-poly.TC() / poly.LC()))
    complex_pair, flip, lower = solutions
    # P(1) = alpha beta (1 - p): positive for every beta > 0
    if sp.expand(one - ALPHA * BETA * (1 - P)) != 0:
        raise DerivationError("P(1) should be alpha beta (1 - p)")
    a3, _, _, a0 = characteristic_polynomial(0).all_coeffs()
    return ClosedFormBoundary(complex_pair, flip, lower, sp.factor(a3 + a0))


# ---------------------------------------------------------------------------------------------
# the critical stiffness
# ---------------------------------------------------------------------------------------------


@dataclass(frozen=True, slots=True)
class CriticalStiffness:
    """The stiffness at which the wall first loses stability as ``K`` grows from 0.

    ``beta`` and ``K`` are certified arb enclosures (``K = beta m/T^2``); ``lower`` is the lower
    end of the stable interval (``0`` unless a large virtual damping destabilises soft walls);
    ``mode`` is ``'complex'`` (a complex pair crosses the unit circle), ``'flip'`` (a real root
    crosses at ``z = -1``) or ``'unstable'`` (no stiffness stabilises the loop: then ``beta``
    and ``K`` are zero balls); ``method`` is ``'closed-form'`` or ``'crossing'``.
    """

    m: sp.Rational
    b: sp.Rational
    T: sp.Rational
    B: sp.Rational
    n: int
    beta: flint.arb
    K: flint.arb
    lower: flint.arb
    mode: str
    method: str
    crossings: tuple[flint.arb, ...] = field(default=())

    @property
    def value(self) -> float:
        """``K*`` as a float (midpoint of the certified ball)."""
        return float(arb_midpoint(self.K))

    def to_json(self) -> dict[str, Any]:
        return {
            "m": str(self.m), "b": str(self.b), "T": str(self.T), "B": str(self.B), "n": self.n,
            "K": self.K.str(30), "beta": self.beta.str(30), "lower_beta": self.lower.str(20),
            "mode": self.mode, "method": self.method,
        }


def closed_form_stiffness(norm: Normalised, bits: int) -> tuple[flint.arb, flint.arb, str]:
    """The critical stiffness from the closed-form boundary of the undelayed wall (certified by ball arithmetic)."""
    vals = closed_form_boundary().values(norm.alpha, norm.delta, bits)
    with flint_precision(bits):
        zero = flint.arb(0)
        if not vals["damping"] > 0:
            if vals["damping"] <= 0:
                return zero, zero, "unstable"
            raise ArithmeticError("damping limit not decided at this precision")
        comp, flip = vals["complex_pair"], vals["flip"]
        if comp < flip:
            upper, mode = comp, "complex"
        elif flip < comp:
            upper, mode = flip, "flip"
        else:
            raise ArithmeticError("complex and flip bounds not separated at this precision")
        lower = vals["lower"] if vals["lower"] > 0 else zero
        if not (lower < upper):
            if lower >= upper:
                return zero, zero, "unstable"
            raise ArithmeticError("stable interval not decided at this precision")
        return upper, lower, mode


def _poly_arb(coeffs: Sequence[Any]) -> flint.arb_poly:
    return flint.arb_poly(list(coeffs))


def wall_parts(norm: Normalised, n: int) -> tuple[list, list, flint.arb]:
    """Ascending arb coefficients of ``A`` and ``C`` with ``P = A + beta C``."""
    a, d = arb_of(norm.alpha), arb_of(norm.delta)
    p = (-a).exp()
    l1, l0 = a + p - 1, 1 - p - a * p
    # A = a^2 z^{n+1} (z^2 - (1+p) z + p) + d (z - 1)(l1 z + l0)
    A = [flint.arb(0)] * (n + 4)
    A[n + 1] += a * a * p
    A[n + 2] -= a * a * (1 + p)
    A[n + 3] += a * a
    A[0] -= d * l0
    A[1] += d * (l0 - l1)
    A[2] += d * l1
    C = [flint.arb(0), l0, l1]
    return A, C, p


def laurent_product(f: Sequence[flint.arb], g: Sequence[flint.arb]) -> dict[int, flint.arb]:
    """Coefficients of ``f(z) g(1/z)``."""
    out: dict[int, flint.arb] = {}
    for i, fi in enumerate(f):
        for j, gj in enumerate(g):
            out[i - j] = out.get(i - j, flint.arb(0)) + fi * gj
    return out


def chebyshev_sum(coeffs: dict[int, flint.arb], kind: str) -> flint.arb_poly:
    """A Laurent polynomial on the circle as a polynomial in ``c``: the ``z^k + z^-k`` pairs as
    ``2 T_k(c)`` (``kind='T'``, real part) or the ``z^k - z^-k`` pairs as ``U_{k-1}(c)`` (``'U'``)."""
    top = max(abs(k) for k in coeffs) if coeffs else 0
    total = flint.arb_poly([coeffs.get(0, flint.arb(0))] if kind == "T" else [0])
    for k in range(1, top + 1):
        if kind == "T":
            weight = coeffs.get(k, flint.arb(0)) + coeffs.get(-k, flint.arb(0))
            basis = flint.fmpz_poly.chebyshev_t(k)
        else:
            weight = coeffs.get(k, flint.arb(0)) - coeffs.get(-k, flint.arb(0))
            basis = flint.fmpz_poly.chebyshev_u(k - 1)
        total += flint.arb_poly([flint.arb(int(c)) for c in basis.coeffs()]) * weight
    return total


def real_roots_inside(V: flint.arb_poly, bits: int) -> list[flint.arb]:
    """Certified real roots of ``V`` in the open interval (-1, 1), as arb balls."""
    try:
        roots = flint.acb_poly(V).roots(tol=flint.arb(2) ** (-(bits // 2)))
    except ValueError as err:        # not converged at this precision (or a repeated root)
        raise ArithmeticError(str(err)) from None
    out = []
    for r in roots:
        im = r.imag
        if not im.contains(0):
            continue  # certified non-real
        lo, hi = flint.arb(r.real.lower()), flint.arb(r.real.upper())
        s_lo, s_hi = V(lo), V(hi)
        if not ((s_lo < 0 and s_hi > 0) or (s_lo > 0 and s_hi < 0)):
            raise ArithmeticError("a near-real root of the crossing polynomial was not certified")
        # a sign change of the real polynomial on the real segment of the (isolating) ball: the
        # ball's only root is real
        re = r.real
        if re < 1 and re > -1:
            out.append(re)
        elif re > 1 or re < -1:
            continue
        else:
            raise ArithmeticError("a crossing root was not separated from c = +-1")
    return out


def stable_at(norm: Normalised, n: int, beta: sp.Rational, bits: int) -> bool | None:
    """Certified: every root of ``P`` strictly inside the unit circle (True), some root
    strictly outside (False), or undecided (None)."""
    A, C, _ = wall_parts(norm, n)
    coeffs = list(A)
    b = arb_of(beta)
    for i, c in enumerate(C):
        coeffs[i] = coeffs[i] + b * c
    if norm.delta == 0:
        coeffs = coeffs[1:]  # exact factor z (the controller has no state)
    try:
        roots = flint.acb_poly(coeffs).roots(tol=flint.arb(2) ** (-(bits // 2)))
    except ValueError:
        return None
    moduli = [abs(r) for r in roots]
    if all(m < 1 for m in moduli):
        return True
    if any(m > 1 for m in moduli):
        return False
    return None


def crossings(norm: Normalised, n: int, bits: int) -> list[tuple[flint.arb, str]]:
    """The stiffnesses ``beta > 0`` where a root of the delayed wall's characteristic polynomial
    meets the unit circle: a complex pair (``"complex"``, at a root in (-1, 1) of the cross term's
    U-series) or a real root through ``z = -1`` (``"flip"``); sorted and certified apart (an
    ``ArithmeticError`` asks for more precision)."""
    A, C, _ = wall_parts(norm, n)
    cross = laurent_product(A, C)
    V = chebyshev_sum(cross, "U")
    R = chebyshev_sum(cross, "T")
    Q = chebyshev_sum(laurent_product(C, C), "T")
    candidates: list[tuple[flint.arb, str]] = []
    for c in real_roots_inside(V, bits):
        beta = -R(c) / Q(c)
        if beta > 0:
            candidates.append((beta, "complex"))
        elif not beta < 0:
            raise ArithmeticError("sign of a crossing stiffness not decided")
    a_m1 = sum((coef * (-1) ** k for k, coef in enumerate(A)), flint.arb(0))
    c_m1 = sum((coef * (-1) ** k for k, coef in enumerate(C)), flint.arb(0))
    flip = -a_m1 / c_m1
    if flip > 0:
        candidates.append((flip, "flip"))
    candidates.sort(key=lambda bc: float(bc[0].mid()))
    for (x, _), (y, _) in zip(candidates, candidates[1:]):
        if not x < y:
            raise ArithmeticError("crossing stiffnesses not separated at this precision")
    return candidates


def stable_between(norm: Normalised, n: int, edges: Sequence[flint.arb], bits: int) -> list[bool]:
    """Certified stability in each gap of the sorted crossings ``edges``: (0, e_1), (e_1, e_2),
    ..., (e_last, oo), tested at a rational point inside each gap."""
    bounds = [flint.arb(0), *edges]
    stable_gaps = []
    for i, lo in enumerate(bounds):
        lo_q = arb_interval(lo)[1]
        test = (lo_q + arb_interval(bounds[i + 1])[0]) / 2 if i + 1 < len(bounds) else 2 * lo_q + 1
        verdict = stable_at(norm, n, test, bits)
        if verdict is None:
            raise ArithmeticError("stability between crossings not certified")
        stable_gaps.append(verdict)
    return stable_gaps


def _crossing_stiffness(norm: Normalised, n: int, bits: int) -> tuple[flint.arb, flint.arb, str, tuple]:
    candidates = crossings(norm, n, bits)
    found = tuple(c for c, _ in candidates)
    stable_gaps = stable_between(norm, n, found, bits)
    edges = [flint.arb(0), *found]
    zero = flint.arb(0)
    for i, stable in enumerate(stable_gaps):
        if stable:
            if i + 1 >= len(edges):
                raise ArithmeticError("stable for arbitrarily large stiffness: not a wall loop")
            return candidates[i][0], edges[i] if i else zero, candidates[i][1], found
    return zero, zero, "unstable", found


def critical_stiffness(m: Any, b: Any, T: Any, B: Any = 0, n: int = 0, bits: int = 160) -> CriticalStiffness:
    """Certified critical stiffness ``K*`` of the device on ``z^{-n}(K + B(z-1)/(Tz))``.

    ``n = 0`` uses the closed form (:func:`closed_form_boundary`), ``n >= 1`` the certified
    crossing analysis; both evaluate ``p = e^{-alpha}`` as an arb ball of ``bits`` bits.

    >>> cs = critical_stiffness(m=1, b=1, T="0.01", B=300)        # delta = 3: too much damping
    >>> cs.mode
    'unstable'
    """
    norm = Normalised.from_physical(m, b, T, None, B)
    if int(n) != n or n < 0:
        raise SceneError(f"the delay n must be a non-negative integer, got {n}")
    n = int(n)
    m_, b_, T_, B_ = (_rational(v, k) for v, k in ((m, "m"), (b, "b"), (T, "T"), (B, "B")))
    scale = m_ / T_**2
    for attempt in range(4):
        precision = bits * 2**attempt
        try:
            with flint_precision(precision):
                if n == 0:
                    beta, lower, mode = closed_form_stiffness(norm, precision)
                    method, crossings = "closed-form", ()
                else:
                    beta, lower, mode, crossings = _crossing_stiffness(norm, n, precision)
                    method = "crossing"
                K = beta * arb_of(scale)
            return CriticalStiffness(m_, b_, T_, B_, n, beta, K, lower, mode, method, crossings)
        except ArithmeticError:
            continue
    raise ArithmeticError("critical stiffness not certified (increase bits)")


def linear_critical_beta(alpha: Any = ALPHA, delta: Any = DELTA, n: int = 0) -> sp.Expr:
    """Gil et al.'s linear condition in normalised form: ``beta < 2(alpha + delta)/(2n + 1)``,
    i.e. ``K (T/2 + t_d) < b + B`` with ``t_d = nT`` (the leading order of the exact boundary;
    see :mod:`hapticproof.analysis.classics`).

    >>> linear_critical_beta(sp.Rational(1, 100), 0, 0)
    1/50
    """
    return 2 * (sp.sympify(alpha) + sp.sympify(delta)) / (2 * int(n) + 1)


# ---------------------------------------------------------------------------------------------
# certified spectral radius of the loop (independent of the polynomial route)
# ---------------------------------------------------------------------------------------------


def _closed_loop_arb(m: sp.Rational, b: sp.Rational, T: sp.Rational, K: sp.Rational, B: sp.Rational,
                     n: int, operator: Operator | None) -> flint.arb_mat:
    op = operator or Operator()
    M, bb, k = m + op.mass, b + op.damping, op.stiffness
    # augmented generator [[A, Bu], [0, 0]] T with A = [[0, 1], [-k/M, -b/M]], Bu = [0, -1/M]
    gen = flint.arb_mat([
        [0, arb_of(T), 0],
        [arb_of(-k * T / M), arb_of(-bb * T / M), arb_of(-T / M)],
        [0, 0, 0],
    ])
    E = gen.exp()
    size = n + 3
    rows = [[flint.arb(0)] * size for _ in range(size)]
    # u_k = (K + B/T) x_{k-n} - (B/T) x_{k-n-1}; state [x_k, v_k, x_{k-1}, ..., x_{k-n-1}]
    u = [flint.arb(0)] * size
    now = 0 if n == 0 else 2 + n - 1
    u[now] += arb_of(K + B / T)
    u[2 + n] -= arb_of(B / T)
    for i in range(2):
        for j in range(2):
            rows[i][j] = E[i, j]
        for j in range(size):
            rows[i][j] += E[i, 2] * u[j]
    rows[2][0] = flint.arb(1)
    for i in range(3, size):
        rows[i][i - 1] = flint.arb(1)
    return flint.arb_mat(rows)


def certified_spectral_radius(m: Any, b: Any, T: Any, K: Any, B: Any = 0, n: int = 0,
                              operator: Operator | None = None, bits: int = 128) -> flint.arb:
    """Certified enclosure of the spectral radius of the sampled closed loop.

    The ZOH transition matrix ``exp([[A, Bu], [0, 0]] T)`` is enclosed by ``arb_mat.exp`` and
    the eigenvalues by ``acb_mat.eig`` (isolating balls); the device may carry a continuous
    operator ``m_h s + b_h + k_h/s``.

    >>> rho = certified_spectral_radius(m="0.015", b="0.02", T="0.001", K=30)
    >>> rho < 1, round(float(rho.mid()), 6)
    (True, 0.999833)
    """
    m_, b_, T_, K_, B_ = (_rational(v, k) for v, k in ((m, "m"), (b, "b"), (T, "T"), (K, "K"), (B, "B")))
    if m_ <= 0 or T_ <= 0:
        raise SceneError("m and T must be positive")
    for attempt in range(4):
        with flint_precision(bits * 2**attempt):
            radius = ball_spectral_radius(flint.acb_mat(_closed_loop_arb(m_, b_, T_, K_, B_, int(n), operator)))
            if radius is not None:
                return radius
    raise ArithmeticError("eigenvalues not isolated; raise bits")


def certified_stable(m: Any, b: Any, T: Any, K: Any, B: Any = 0, n: int = 0,
                     operator: Operator | None = None) -> Outcome:
    """``proved`` (every eigenvalue of the loop strictly inside the unit circle), ``disproved``
    (one outside, or one exactly on it: ``rho = 1`` is not stable) or ``undecided``: the one
    decision of :func:`hapticproof.analysis.sampled.decide_stability`, with the certified spectral
    radius (:func:`certified_spectral_radius`, an independent route) as evidence.

    >>> certified_stable(m=1, b=1, T="0.01", K=1, B=300).decision.value     # delta = 3
    'disproved'
    >>> certified_stable(m=1, b=1, T="0.01", K=0, B=1).reason[:40]           # no position feedback: rho = 1
    'z = 1 is an exact eigenvalue of the clos'
    """
    from hapticproof.analysis.sampled import decide_stability
    from hapticproof.systems.loops import SingleUser

    witness = {"m": exact(m), "b": exact(b), "T": exact(T), "K": exact(K), "B": exact(B), "n": int(n)}
    if operator is not None:
        witness.update({"m_h": operator.mass, "b_h": operator.damping, "k_h": operator.stiffness})
    scene = SingleUser(m=witness["m"], b=witness["b"], T=witness["T"], K=witness["K"], B=witness["B"], delay=int(n),
                       operator=None if operator is None else operator.impedance())
    decision = decide_stability(scene)
    facts: dict[str, Any] = {}
    try:
        rho = certified_spectral_radius(m, b, T, K, B, n, operator)
        facts["spectral_radius"] = rho.str(20)
    except ArithmeticError:
        rho = None                               # eigenvalues clustered on the circle: no isolating balls
    if decision.stable is True:
        return Outcome(Decision.PROVED, Evidence(Method.INTERVAL_ARITHMETIC, facts=facts | {"parameters": witness}),
                       f"certified spectral radius {rho.str(10)} < 1" if rho is not None else decision.reason)
    if decision.stable is False:
        if decision.fixed_points or decision.verdict != "unstable":       # rho = 1 exactly: say how
            facts["stability"] = decision.verdict
            facts["fixed_points"] = [[str(v) for v in vec] for vec in decision.fixed_points]
        reason = (f"certified spectral radius {rho.str(10)} > 1" if rho is not None and rho > 1 and decision.verdict == "unstable"
                  and not decision.fixed_points else decision.reason)
        return Outcome(Decision.DISPROVED, Evidence(Method.INTERVAL_ARITHMETIC, witness=witness, facts=facts), reason)
    return Outcome(Decision.UNDECIDED, Evidence(Method.INTERVAL_ARITHMETIC, facts=facts), decision.reason)
