r"""Passivity of the sampled-data position-error-based teleoperator (teleoperator paper, Fig. 2).

Master and slave robots ``m_i dv_i/dt = f - b_i v_i - u_i`` are coupled by discrete controllers
through samplers and zero-order holds. With scaled controllers ``C_m = alpha C``, ``C_s = C``
(eq. 30; ``alpha = 1`` is eq. 17) and the error ``e = alpha x_m - x_s`` (eq. 31), the sampled
forces are those of one discrete "spring" ``C(z)`` on ``e``, so the energy-leak analysis of
Colgate & Schenkel applies to the error coordinate (:func:`hapticproof.classics.leak_bound`):

* the aliased energy of the sampled spring is at least ``-L(c) |alpha V_m - V_s|^2`` with
  ``L = T/(2(1 - c)) Re{(1 - z^{-1}) C}`` (Cauchy-Schwarz with the alias weight);
* ``|alpha a - b|^2 <= (alpha + 1)(alpha |a|^2 + |b|^2)`` (the difference is
  ``alpha |a + b|^2``) splits it between the robots, so the teleoperator is passive if

.. math:: b_m \ge (\alpha + 1)\, L_{C_m}(c), \qquad b_s \ge (\alpha + 1)\, L_{C_s}(c)
          \quad \forall c \in [-1, 1],

which is the paper's (32), and (29) at ``alpha = 1`` (twice Colgate's bound). The split is one
choice: the least damping the two robots can offer the error coordinate is the series value
``h = b_m b_s/(b_m + alpha^2 b_s)`` (:func:`error_coordinate_damping`), and ``h >= L`` is
already sufficient; (32) implies it and coincides with it iff ``b_m = alpha b_s``.

Bounds are exact rational functions of ``c = cos(wT)`` for any real-rational ``C(z)``; their
worst case over frequency is exact (root isolation) for numeric controllers and by endpoint
analysis for the symbolic PD controller (33).

>>> scene = TeleoperatorScene.pd(alpha=1)
>>> sp.expand(bounds(scene).master)                                   # eq. (34)
-2*B*c + K*T
>>> worst_case(scene).condition                                        # eq. (35)
(b_m >= 2*B + K*T) & (b_s >= 2*B + K*T)
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass, replace
from functools import lru_cache
from typing import Any

import flint
import sympy as sp

from hapticproof.classics import leak_bound
from hapticproof.errors import InputFormatError, SceneError
from hapticproof.evidence import Decision, Evidence, Method, Outcome, exact
from hapticproof.lazy import stage
from hapticproof.positivereal import symbolic_minimum
from hapticproof.positivereal import Condition, combine
from hapticproof.realroots import as_fmpq, as_fmpq_poly, minimise_rational, real_roots
from hapticproof.scene import SYMBOLS
from hapticproof.symbols import c as C_SYM
from hapticproof.symbols import z as Z_SYM

__all__ = [
    "TELE_SYMBOLS",
    "pd_controller",
    "filtered_pd_controller",
    "discretize_pd",
    "parse_controller",
    "TeleoperatorScene",
    "Bounds",
    "TeleWorstCase",
    "bounds",
    "worst_case",
    "passivity",
    "passivity_conditions",
    "margin_transfer",
    "error_coordinate_damping",
]

#: Symbols of the teleoperator paper (dampings and masses positive, B >= 0 derivative gain).
TELE_SYMBOLS: dict[str, sp.Symbol] = {
    "K": SYMBOLS["K"],
    "B": SYMBOLS["B"],
    "T": SYMBOLS["T"],
    "b": SYMBOLS["b"],
    "b_m": sp.Symbol("b_m", positive=True),
    "b_s": sp.Symbol("b_s", positive=True),
    "m_m": sp.Symbol("m_m", positive=True),
    "m_s": sp.Symbol("m_s", positive=True),
    "alpha": sp.Symbol("alpha", positive=True),
    "a": sp.Symbol("a", nonnegative=True),
}


def pd_controller(K: Any = TELE_SYMBOLS["K"], B: Any = TELE_SYMBOLS["B"], T: Any = TELE_SYMBOLS["T"],
                  z: sp.Symbol = Z_SYM) -> sp.Expr:
    """The PD controller of eq. (33), ``K + B(z-1)/(Tz)``: the backward difference of ``K + Bs``.

    >>> pd_controller(2, 1, sp.Rational(1, 10))
    2 + 10*(z - 1)/z
    """
    K, B, T = (sp.sympify(v) for v in (K, B, T))
    return K + B * (z - 1) / (T * z)


def filtered_pd_controller(K: Any = TELE_SYMBOLS["K"], B: Any = TELE_SYMBOLS["B"], T: Any = TELE_SYMBOLS["T"],
                           a: Any = TELE_SYMBOLS["a"], z: sp.Symbol = Z_SYM) -> sp.Expr:
    """PD with a first-order low-pass on the derivative, ``K + B(1 - a)(z - 1)/(T(z - a))``
    (``0 <= a < 1``; ``a = 0`` is eq. 33).

    >>> sp.simplify(filtered_pd_controller(a=0) - pd_controller())
    0
    """
    K, B, T, a = (sp.sympify(v) for v in (K, B, T, a))
    return K + B * (1 - a) * (z - 1) / (T * (z - a))


@lru_cache(maxsize=32)   # pure; the audit and the tests ask for the same few
def discretize_pd(method: str, K: Any = TELE_SYMBOLS["K"], B: Any = TELE_SYMBOLS["B"],
                  T: Any = TELE_SYMBOLS["T"], z: sp.Symbol = Z_SYM) -> sp.Expr:
    """Discretise ``K + Bs`` with :mod:`sympy.physics.control` (``'backward'``, ``'forward'`` or
    ``'bilinear'``) and return ``C(z)``.

    >>> sp.simplify(discretize_pd("backward") - pd_controller())
    0
    >>> sp.factor(discretize_pd("bilinear", 1, 1, 2))
    2*z/(z + 1)
    """
    from sympy.physics.control import TransferFunction, backward_diff, bilinear, forward_diff

    methods = {"backward": backward_diff, "forward": forward_diff, "bilinear": bilinear}
    if method not in methods:
        raise SceneError(f"unknown discretisation {method!r}; choose one of {', '.join(methods)}")
    s = sp.Symbol("s")
    K, B, T = (sp.sympify(v) for v in (K, B, T))
    num, den = methods[method](TransferFunction(K + B * s, 1, s), T)
    top = max(len(num), len(den)) - 1
    as_poly = lambda coeffs: sum(c * z ** (len(coeffs) - 1 - i) for i, c in enumerate(coeffs))  # noqa: E731
    return sp.cancel(as_poly(num) * z ** (top - len(num) + 1) / (as_poly(den) * z ** (top - len(den) + 1)))


def parse_controller(text: str, params: Mapping[str, Any] | None = None) -> sp.Expr:
    """A user's controller ``C(z)`` from text such as ``"K + B*(z-1)/(T*z)"`` (read by
    :func:`hapticproof.expr.read_expression`: exact decimals, any parameter names).

    Names given in ``params`` get those exact values; the others stay symbolic (the teleoperator
    symbols ``K``, ``B``, ``T``, ``a``, ``alpha``... with their signs).

    >>> parse_controller("K + B*(z - 1)/(T*z)", {"K": 2, "B": "0.01", "T": "0.001"})
    2 + 10*(z - 1)/z
    """
    from hapticproof.expr import read_expression

    if not isinstance(text, str) or not text.strip():
        raise InputFormatError(f"controller {text!r}: give C(z) as an expression in z")
    expr = read_expression(text, "z", where="controller", symbols=TELE_SYMBOLS)
    values = {sym: exact(params[sym.name]) for sym in expr.free_symbols if params and sym.name in params}
    expr = expr.subs(values)
    if not isinstance(expr, sp.Expr) or not expr.is_rational_function(Z_SYM):
        raise InputFormatError(f"controller {text!r} must be a rational function of z")
    return expr


@dataclass(frozen=True, slots=True, weakref_slot=True)
class TeleoperatorScene:
    """A sampled-data PEB teleoperator: robots, sampling period, controller and scaling.

    Parameters
    ----------
    m_m, m_s, b_m, b_s : expr
        Masses and dampings (positive when numeric). The masses do not enter the passivity
        bounds (they store energy losslessly) and may be ``None``; the stability checks
        (:meth:`to_sampled`) need them.
    T : expr
        Sampling period.
    C : expr
        ``C(z) = C_s(z)``, any real-rational function of ``z``; ``C_m = alpha C`` (eq. 30).
    alpha : expr
        Position scaling (eq. 31); ``1`` gives equal controllers (eq. 17).
    """

    m_m: Any
    m_s: Any
    b_m: Any
    b_s: Any
    T: Any
    C: Any
    alpha: Any = 1

    def __post_init__(self) -> None:
        from hapticproof.expr import normalise_variables

        for name in ("m_m", "m_s", "b_m", "b_s", "T", "alpha"):
            value = getattr(self, name)
            if value is None and name in ("m_m", "m_s"):
                continue                      # masses are optional: they do not enter the bounds
            value = value if isinstance(value, sp.Basic) and not value.is_number else exact(value)
            object.__setattr__(self, name, value)
            if value.is_number and not value > 0:
                raise SceneError(f"{name} must be positive, got {value}")
        C = normalise_variables(self.C, "z", "C(z)")
        if not C.is_rational_function(Z_SYM):
            raise SceneError(f"C(z) must be a rational function of z, got {C}")
        num, den = sp.fraction(sp.cancel(sp.together(C)))
        if sp.Poly(num, Z_SYM).degree() > sp.Poly(den, Z_SYM).degree():
            raise SceneError("C(z) must be proper (causal)")
        object.__setattr__(self, "C", C)

    @classmethod
    def pd(cls, K: Any = None, B: Any = None, T: Any = None, alpha: Any = 1, *, m_m: Any = None,
           m_s: Any = None, b_m: Any = None, b_s: Any = None) -> TeleoperatorScene:
        """The paper's scene with the PD controller (33); unspecified values stay symbolic."""
        sym = TELE_SYMBOLS
        T = sym["T"] if T is None else exact(T)
        C = pd_controller(sym["K"] if K is None else exact(K), sym["B"] if B is None else exact(B), T)
        return cls(sym["m_m"] if m_m is None else m_m, sym["m_s"] if m_s is None else m_s,
                   sym["b_m"] if b_m is None else b_m, sym["b_s"] if b_s is None else b_s, T, C,
                   sym["alpha"] if alpha is None else alpha)

    @classmethod
    def symmetric(cls, m: Any, b: Any, T: Any, C: Any, alpha: Any = 1) -> TeleoperatorScene:
        """Identical robots (the paper's simulations and experiments)."""
        return cls(m, m, b, b, T, C, alpha)

    @property
    def C_m(self) -> sp.Expr:
        return self.alpha * self.C

    @property
    def C_s(self) -> sp.Expr:
        return self.C

    def _repr_latex_(self) -> str:
        from hapticproof.latex import scene_latex

        return "$" + scene_latex(self) + "$"

    @property
    def parameters(self) -> set[sp.Symbol]:
        out: set[sp.Symbol] = set()
        for value in (self.m_m, self.m_s, self.b_m, self.b_s, self.T, self.C, self.alpha):
            if value is not None:
                out |= sp.sympify(value).free_symbols
        return out - {Z_SYM}

    @property
    def controller_is_numeric(self) -> bool:
        return not ((sp.sympify(self.C).free_symbols - {Z_SYM}) | self.T.free_symbols | self.alpha.free_symbols)

    def with_values(self, **values: Any) -> TeleoperatorScene:
        """Substitute exact values for symbols by name.

        >>> TeleoperatorScene.pd().with_values(K=1, B=0, T="0.001").C
        1
        """
        by_name = {s.name: s for s in self.parameters}
        mapping = {}
        for key, value in values.items():
            if key not in by_name:
                raise SceneError(f"unknown parameter {key!r}; the scene has {sorted(by_name)}")
            mapping[by_name[key]] = exact(value)
        sub = lambda v: None if v is None else sp.sympify(v).subs(mapping)  # noqa: E731
        return replace(self, m_m=sub(self.m_m), m_s=sub(self.m_s), b_m=sub(self.b_m), b_s=sub(self.b_s),
                       T=sub(self.T), C=sub(self.C), alpha=sub(self.alpha))

    def to_sampled(self, master: Any = None, slave: Any = None) -> Any:
        """The numeric scene as a :class:`hapticproof.sampled.Teleoperator` (exact ZOH loop)."""
        from hapticproof.sampled import DiscreteTF, Teleoperator

        if self.parameters:
            raise SceneError(f"the scene has free parameters {sorted(map(str, self.parameters))}")
        if self.m_m is None or self.m_s is None:
            raise SceneError("the sampled-data loop needs the masses m_m and m_s")
        num, den = sp.fraction(sp.cancel(sp.together(self.C)))
        pn, pd = sp.Poly(num, Z_SYM), sp.Poly(den, Z_SYM)
        tf = DiscreteTF(tuple(pn.all_coeffs()), tuple(pd.all_coeffs()))
        return Teleoperator(m_m=self.m_m, m_s=self.m_s, b_m=self.b_m, b_s=self.b_s, T=self.T,
                            alpha=self.alpha, master=master, slave=slave, controller=tf)


@dataclass(frozen=True, slots=True)
class Bounds:
    """Per-robot lower bounds on the dampings at frequency ``c`` (eq. 29/32), exact in ``c``;
    ``leak`` is Colgate's bound of ``C`` on the error coordinate (``L`` above)."""

    master: sp.Expr
    slave: sp.Expr
    leak: sp.Expr


@dataclass(frozen=True, slots=True)
class TeleWorstCase:
    """Worst case over ``c`` in ``[-1, 1]`` of the bounds: ``sup_master``/``sup_slave`` (exact
    numbers or arb balls when numeric; expressions when symbolic), the maximisers, and the
    passivity condition on ``b_m`` and ``b_s``."""

    sup_master: Any
    sup_slave: Any
    maximiser: Any
    condition: sp.Basic


@stage("teleoperator_bounds")
def bounds(scene: TeleoperatorScene) -> Bounds:
    """The bounds of eq. (32) (eq. 29 at ``alpha = 1``) for the scene's controller.

    >>> sc = TeleoperatorScene.pd(K=1, B=0, T=sp.Rational(1, 100), alpha=2)
    >>> bounds(sc).master, bounds(sc).slave                  # (alpha+1) alpha KT/2, (alpha+1) KT/2
    (3/100, 3/200)
    """
    leak = sp.cancel(leak_bound(scene.C, scene.T))
    weight = scene.alpha + 1
    return Bounds(sp.cancel(weight * scene.alpha * leak), sp.cancel(weight * leak), leak)


def _sup_numeric(expr: sp.Expr) -> tuple[Any, Any]:
    """Exact supremum of a numeric rational function of ``c`` on ``[-1, 1]``."""
    num, den = sp.fraction(sp.cancel(sp.together(expr)))
    pn, pd = as_fmpq_poly(sp.expand(num), C_SYM), as_fmpq_poly(sp.expand(den), C_SYM)
    if pd.degree() > 0 and real_roots(pd, -1, 1):
        return sp.oo, None  # the controller has unit-circle poles: no finite damping suffices
    m = minimise_rational(-pn, pd, -1, 1)
    value = -m.exact if m.exact is not None else -m.value
    return value, m.argmin


@stage("teleoperator_worst_case")
def worst_case(scene: TeleoperatorScene) -> TeleWorstCase:
    """Worst case over frequency of the bounds (exact): root isolation for a numeric controller,
    endpoint analysis for a symbolic one (affine or concave in ``c``).

    >>> wc = worst_case(TeleoperatorScene.pd(K=2, B=sp.Rational(1, 100), T=sp.Rational(1, 1000)))
    >>> wc.sup_master, wc.maximiser                          # KT + 2B at c = -1
    (11/500, -1)
    """
    bd = bounds(scene)
    b_m, b_s = scene.b_m, scene.b_s
    if scene.controller_is_numeric:
        sup_m, arg = _sup_numeric(bd.master)
        sup_s, _ = _sup_numeric(bd.slave)
        cond = sp.And(sp.Ge(b_m, sup_m), sp.Ge(b_s, sup_s)) if isinstance(sup_m, sp.Basic) else None
        return TeleWorstCase(sup_m, sup_s, arg, cond)
    out = []
    for bound, damping in ((bd.master, b_m), (bd.slave, b_s)):
        wc = symbolic_minimum(sp.expand(-bound))   # min of -bound = -sup
        sup = sp.expand(-wc.minimum) if wc.minimum is not None else sp.Function("sup_c")(bound)
        out.append((sup, wc.minimiser, sp.Ge(damping, sup)))
    return TeleWorstCase(out[0][0], out[1][0], out[0][1], sp.And(out[0][2], out[1][2]))


def _bound_parameters(scene: TeleoperatorScene) -> set[sp.Symbol]:
    """The parameters the passivity bound depends on (the masses store energy losslessly and
    do not enter it)."""
    out: set[sp.Symbol] = set()
    for value in (scene.b_m, scene.b_s, scene.T, scene.C, scene.alpha):
        out |= sp.sympify(value).free_symbols
    return out - {Z_SYM}


def _fmpq_poly(expr: sp.Expr) -> flint.fmpq_poly:
    return as_fmpq_poly(sp.Poly(sp.expand(expr), Z_SYM).as_expr() if sp.expand(expr).free_symbols else sp.expand(expr), Z_SYM)


def margin_transfer(scene: TeleoperatorScene, robot: str) -> tuple[flint.fmpq_poly, flint.fmpq_poly]:
    """``F(z) = b - w T C(z)/(1 - z)`` (``w = alpha(alpha + 1)`` for the master, ``alpha + 1`` for
    the slave) as polynomials: on the unit circle ``Re F = b - bound(c)`` (eq. 32), because
    ``T/(1 - cos wT) Re{(1 - e^{-jwT}) C} = 2T Re{C(z)/(1 - z)}``.

    >>> sc = TeleoperatorScene.pd(K=2, B=0, T=sp.Rational(1, 10), m_m=1, m_s=1, b_m=1, b_s=1)
    >>> margin_transfer(sc, "slave")                 # 1 - 2*(1/10)*2/(1 - z)
    (x + (-3/5), x + (-1))
    """
    weight = scene.alpha * (scene.alpha + 1) if robot == "master" else scene.alpha + 1
    damping = scene.b_m if robot == "master" else scene.b_s
    num, den = sp.fraction(sp.cancel(sp.together(scene.C)))
    cn, cd = _fmpq_poly(num), _fmpq_poly(den)
    one_minus_z = flint.fmpq_poly([1, -1])
    P = as_fmpq(damping) * one_minus_z * cd - as_fmpq(weight * scene.T) * cn
    Q = one_minus_z * cd
    g = P.gcd(Q) if not P.is_zero() else Q
    P, Q = P / g, Q / g
    lead = Q.coeffs()[-1]
    return P / lead, Q / lead


def passivity_conditions(scene: TeleoperatorScene) -> list[Condition]:
    """The decided conditions of the passivity criterion (32) for a scene: the controller has no
    pole outside the unit circle (the criterion presumes a stable controller), and each robot's
    damping exceeds its bound at every frequency (exact; a witness frequency when it fails).
    Symbolic parameters of the bound give the conditions symbolically."""
    from hapticproof.kernel import decide_rational_sign, locate_roots, transfer_json
    from hapticproof.unitcircle import circle_real_part

    if _bound_parameters(scene):
        wc = worst_case(scene)
        conds = []
        for robot, sup, damping in (("master", wc.sup_master, scene.b_m), ("slave", wc.sup_slave, scene.b_s)):
            conds.append(Condition(f"{robot}: b >= bound(c) for all w",
                                   Outcome(Decision.SYMBOLIC, Evidence(Method.ENDPOINT_ANALYSIS, facts={"supremum": sup}),
                                           f"{sp.sstr(damping)} >= {sp.sstr(sup)}")))
        return conds
    num, den = sp.fraction(sp.cancel(sp.together(scene.C)))
    roots = locate_roots(_fmpq_poly(den), "disk")
    if roots.outside:
        where = ", ".join(f"z ~ {complex(p):.6g}".replace("+0j", "").replace("(", "").replace(")", "") for p in roots.outside_points[:3])
        poles = Outcome(Decision.DISPROVED, Evidence(Method.ROOT_ISOLATION, witness={"pole": where}, facts={"certificate": roots}),
                        f"C(z) has {roots.outside} pole(s) outside the unit circle ({where}): the controller is unstable, "
                        "the criterion (32) presumes a stable controller")
    else:
        on = [r.label() for r in roots.boundary]
        poles = Outcome(Decision.PROVED, Evidence(Method.ROOT_ISOLATION, facts={"certificate": roots}),
                        "no controller pole outside the unit circle" + (f" (on it: {', '.join(on)})" if on else ""))
    conds = [Condition("controller poles in |z| <= 1", poles)]
    for robot in ("master", "slave"):
        P, Q = margin_transfer(scene, robot)
        N, D = circle_real_part(P, Q)
        out = decide_rational_sign(N, D, -1, 1, "c", f"b_{robot[0]} - bound", transfer=transfer_json(P, Q), transfer_den=Q)
        conds.append(Condition(f"{robot}: b_{robot[0]} >= bound(c) for all w", out))
    return conds


def passivity(scene: TeleoperatorScene) -> Outcome:
    """Decide the passivity condition (32) for a scene whose bound is numeric (exact, with a
    witness frequency when it fails; the masses need not be given), or return it symbolically.

    >>> sc = TeleoperatorScene.pd(K=1, B=0, T=sp.Rational(15, 1000), b_m="0.01822", b_s="0.01822")
    >>> passivity(sc).decision.value, passivity(sc).witness          # KT = 0.015 < b: passive
    ('proved', None)
    >>> unstable = TeleoperatorScene(1, 1, 1, 1, sp.Rational(1, 100), 2 / (Z_SYM - 3))
    >>> passivity(unstable).decision.value
    'disproved'
    """
    return combine(passivity_conditions(scene), subject="the teleoperator", holds="passive by (32)")


def error_coordinate_damping(scene: TeleoperatorScene) -> sp.Expr:
    """The least damping the robots offer the error coordinate ``alpha x_m - x_s``:
    ``min {b_m |a|^2 + b_s |b|^2 : alpha a - b = e} = b_m b_s/(b_m + alpha^2 b_s) |e|^2``;
    ``h >= L(c)`` for all ``c`` is sufficient for passivity and implied by (32).

    >>> error_coordinate_damping(TeleoperatorScene.pd(alpha=1))
    b_m*b_s/(b_m + b_s)
    """
    return sp.cancel(scene.b_m * scene.b_s / (scene.b_m + scene.alpha**2 * scene.b_s))

