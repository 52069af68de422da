r"""Passivity of the sampled-data position-error-based teleoperator (teleoperator paper, Fig. 2).

Master and slave robots ``m_i dv_i/dt = f - b_i v_i - u_i`` are coupled by discrete controllers
through samplers and zero-order holds. With scaled controllers ``C_m = alpha C``, ``C_s = C``
(eq. 30; ``alpha = 1`` is eq. 17) and the error ``e = alpha x_m - x_s`` (eq. 31), the sampled
forces are those of one discrete "spring" ``C(z)`` on ``e``, so the energy-leak analysis of
Colgate & Schenkel applies to the error coordinate (:func:`hapticproof.analysis.classics.leak_bound`):

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

from dataclasses import dataclass
from typing import Any

import flint
import sympy as sp

from hapticproof.analysis.classics import leak_bound
from hapticproof.core.evidence import Decision, Evidence, Method, Outcome
from hapticproof.core.lazy import stage
from hapticproof.analysis.positivereal import symbolic_minimum
from hapticproof.exact.conditions import Condition, combine
from hapticproof.exact.realroots import as_fmpq, as_fmpq_poly, minimise_rational, real_roots
from hapticproof.core.symbols import c as C_SYM
from hapticproof.core.symbols import z as Z_SYM
from hapticproof.systems.teleoperator import TeleoperatorScene

__all__ = ["Bounds", "TeleWorstCase", "bounds", "worst_case", "passivity", "passivity_conditions", "margin_transfer", "error_coordinate_damping"]


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


def bound_parameters(scene: TeleoperatorScene) -> set[sp.Symbol]:
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
    from hapticproof.exact.kernel import decide_rational_sign, locate_roots, transfer_json
    from hapticproof.exact.unitcircle import circle_real_part

    if bound_parameters(scene):
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
