r"""Passivity of the sampled-data position-error-based teleoperator (teleoperator paper, Fig. 2):
the exact decision, and the paper's criterion (29)/(32) as the sufficient condition it is.

**Model** (eqs. 1, 5, 30, 31; the restoring sign convention of the paper's analysis, its PD
example and experiments -- (7) as printed, combined with (1), would be a negative spring)::

    m_m dv_m/dt = f_m - b_m v_m - u_m,    u_m(t) = alpha y_k
    m_s dv_s/dt = f_s - b_s v_s - u_s,    u_s(t) = -y_k          for kT <= t < (k + 1)T
    e_k = alpha x_m(kT) - x_s(kT),        y = C(z) e   (discrete, causal, from rest)

so ``C_m = alpha C`` and ``C_s = C`` act on the error ``e = alpha x_m - x_s``. The two-port
``(f_m, f_s) -> (v_m, v_s)`` is *passive* when ``W(t) = int_0^t f_m v_m + f_s v_s >= 0`` for
every input and every ``t``, from rest (eq. 8).

**Theorem** (exact passivity). Let ``T > 0``, ``alpha`` real, ``C = P/Q`` proper and in
lowest terms (an improper ``C`` is non-causal: the loop of Fig. 2 does not exist and the scene
refuses it), ``h = b_m b_s/(b_m + alpha^2 b_s)`` (``h = b_s`` when ``b_m = alpha^2 b_s = 0``)
and Colgate's leak ``L(c) = T/(2(1 - c)) Re{(1 - z^-1) C(z)} = -T Re{C(z)/(z - 1)}``,
``z = e^{jwT}``, ``c = cos wT``. The teleoperator is passive, for every choice of the masses,
if and only if

* (D)  ``b_m >= 0`` and ``b_s >= 0``;
* (P1) ``C`` has no pole in ``|z| > 1``;
* (P2) ``C`` has no pole at ``z = 1`` (integral action is never passive);
* (P3) ``C(1) >= 0`` (the DC stiffness);
* (P4) every other pole ``z0`` of ``C`` on ``|z| = 1`` is simple with
  ``rho = Res(C, z0)/(z0 (z0 - 1))`` real and ``> 0``;
* (P5) ``h >= L(c)`` for every ``c`` in ``[-1, 1]`` where ``L`` is finite.

Equivalently: (D) and ``H(z) = h/T + C(z)/(z - 1)`` is discrete positive real; indeed
``T Re H(e^{jwT}) = h - L(c)``, ``Res(H, 1) = C(1)`` and ``Res(H, z0)/z0 = rho``.

*Proof.* (1) Energy balance. Multiplying each robot equation by its velocity,
``W = KE + int (b_m v_m^2 + b_s v_s^2) + int (u_m v_m + u_s v_s)``; on a period the controller
power is ``y_k e'(t)`` and the force is held, so its work is exactly ``y_k d_k`` with
``d_k = e_{k+1} - e_k``. (2) Reduction. For ``b_m, b_s >= 0``,
``min {b_m a^2 + b_s b^2 : alpha a - b = 1} = h`` (Lagrange; attained at
``(a, b) ~ (alpha b_s, -b_m)``), and ``int_period e'^2 >= d_k^2/T`` (Cauchy-Schwarz, equality
for constant ``e'``). With ``KE >= 0`` this gives ``W(NT) >= Q_N(d) = sum_k (h/T) d_k^2 + y_k
d_k``, and at intermediate times ``W(NT + tau) >= Q_{N+1}(d, delta)``. Conversely, the
velocities ``(v_m, v_s) = (alpha b_s, -b_m) w(t)/(b_m + alpha^2 b_s)`` with ``e' = w`` close to
``d_k/T`` on each period and ``w = 0`` at both ends, driven by the forces
``f_i = m_i v_i' + b_i v_i + u_i`` (admissible for any masses), realise ``Q_N(d) + O(eps)``
with ``KE(NT) = 0``. So under (D): passive iff ``Q_N(d) >= 0`` for all ``N`` and ``d``. (D) is
necessary: a negative damping supplies energy through the rigid motion ``v_s = alpha v_m``
(controller silent) or through the error motion of least dissipation. (3) Toeplitz form.
``G = C/(z - 1) = sum_{n>=1} g_n z^-n`` is strictly proper and ``Q_N(d) = d^T S_N d`` with the
symmetric Toeplitz ``S_N = [s_{j-k}]``, ``s_0 = h/T``, ``s_n = g_|n|/2``. By Caratheodory-Toeplitz
(Riesz-Herglotz), ``S_N >= 0`` for all ``N`` iff ``F(zeta) = s_0 + 2 sum s_n zeta^n = H(1/zeta)``
has ``Re F >= 0`` in the unit disc, i.e. iff ``H`` is positive real (``Re F(zeta) = (1 -
|zeta|^2) lim x^* S_N x`` gives one direction, the Herglotz measure the other). (4) A rational
``H`` analytic at infinity is positive real iff it has no pole in ``|z| > 1``, its unit-circle
poles are simple with ``Res/z0 > 0`` (a pole of order ``k`` makes ``H`` sweep an angle ``k pi``
just outside the circle) and ``Re H >= 0`` on the circle (subtract the lossless parts and use
the minimum principle). (5) The poles of ``H`` are those of ``C`` and ``z = 1``: a pole of ``C``
at 1 gives a multiple pole of ``H`` (P2), otherwise ``Res(H, 1) = C(1)`` (P3, no pole when
``C(1) = 0``), ``Res(H, z0)/z0 = rho`` (P4), poles outside (P1), and ``T Re H = h - L`` (P5). ∎

Consequences: the masses never enter; nothing is strict (the boundary is passive); a negative
spring ``C = K < 0`` is never passive (``Q_n -> C(1) E^2/2 < 0`` for a slow displacement),
whatever (32) says; ``alpha <= 0`` is decided like any other scaling (only ``alpha^2`` enters
``h``); a robot without damping (``h = 0``) is passive only with ``C = 0``. For the PD
controller (33) ``L = KT/2 - Bc``: passive iff ``K >= 0`` and ``h >= KT/2 + |B|``.

**The paper's criterion.** (32) is ``b_m >= (alpha + 1) alpha L(c)`` and ``b_s >= (alpha + 1)
L(c)`` (eq. 29 at ``alpha = 1``): the split ``|alpha a - b|^2 <= (alpha + 1)(alpha |a|^2 +
|b|^2)`` of the leak between the robots (the difference is ``alpha |a + b|^2``, so it needs
``alpha >= 0``). With ``p = b_m/(alpha(alpha + 1))``, ``q = b_s/(alpha + 1)``, ``1/h =
(1/(alpha + 1))/q + (alpha/(alpha + 1))/p``: ``h`` is a weighted harmonic mean, ``h >= min(p,
q)``, equal iff ``b_m = alpha b_s``. So for ``alpha > 0`` (32) implies (P5) and coincides with it
iff ``b_m = alpha b_s``; it says nothing about (P1)-(P4), so on its own it is not even
sufficient (``C = K < 0`` passes it). :func:`criterion_conditions` decides it exactly as
printed; a failed (32) is never a disproof of passivity.

Every numeric decision goes through the kernel (:mod:`hapticproof.exact.kernel`): the poles of
``C`` by certified root location, the residues of ``H`` at the unit-circle poles, the sign of
``h - L(c) = Re(h + T C(z)/(z - 1))`` on ``[-1, 1]`` by root isolation, each with a certificate
that ``hapticproof check`` re-verifies (a disproof of (P5) is re-evaluated at its point of the
circle in the original transfer function).

>>> d = passivity(TeleoperatorScene.pd(K=-5, B=0, T="0.001", b_m="0.03", b_s="0.05"))
>>> d.decision.value, d.reason                                        # issue 18: a negative spring
('disproved', 'the teleoperator is not passive: (P3) C(1) >= 0: C(1) = -5 < 0: the discrete spring stores C(1) e^2/2 < 0 after a slow displacement')
>>> passivity(TeleoperatorScene.pd(K=2, B=0, T=sp.Rational(1, 3), b_m=10, b_s=sp.Rational(3, 7))).decision.value
'proved'
>>> sp.expand(bounds(TeleoperatorScene.pd(alpha=1)).master)            # eq. (34)
-2*B*c + K*T
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

import flint
import sympy as sp

from hapticproof.analysis.classics import leak_bound
from hapticproof.analysis.positivereal import named_conditions, pole_location_outcome, poles_of, symbolic_minimum, unit_circle_residues
from hapticproof.core.evidence import Decision, Evidence, Method, Outcome
from hapticproof.core.lazy import stage
from hapticproof.core.naming import DEFAULT
from hapticproof.core.symbols import c as C_SYM
from hapticproof.core.symbols import z as Z_SYM
from hapticproof.exact.conditions import Condition, combine
from hapticproof.exact.realroots import as_fmpq, as_fmpq_poly, minimise_rational, real_roots, to_rational
from hapticproof.systems.teleoperator import TeleoperatorScene

__all__ = ["Bounds", "TeleWorstCase", "CONDITIONS", "bounds", "worst_case", "passivity", "passivity_conditions",
           "criterion", "criterion_conditions", "exact_condition", "margin_transfer", "error_coordinate_damping",
           "energy_transfer", "bound_parameters"]

#: the conditions of the theorem, in order (key, statement)
CONDITIONS = (
    ("D", "b_m >= 0 and b_s >= 0"),
    ("P1", "no pole of C in |z| > 1"),
    ("P2", "no pole of C at z = 1 (no integral action)"),
    ("P3", "C(1) >= 0"),
    ("P4", "other unit-circle poles of C simple, Res(C,z0)/(z0(z0-1)) > 0"),
    ("P5", "h >= L(c) for all c in [-1, 1]"),
)


def _name(key: str) -> str:
    return f"({key}) {dict(CONDITIONS)[key]}"


@dataclass(frozen=True, slots=True)
class Bounds:
    """Per-robot lower bounds on the dampings at frequency ``c`` of the paper's (32) (eq. 29 at
    ``alpha = 1``), exact in ``c``; ``leak`` is Colgate's ``L(c)`` of ``C`` on the error
    coordinate."""

    master: sp.Expr
    slave: sp.Expr
    leak: sp.Expr


@dataclass(frozen=True, slots=True)
class TeleWorstCase:
    """Worst case over ``c`` in ``[-1, 1]`` of the bounds of (32): ``sup_master``/``sup_slave``
    (exact numbers or arb balls when numeric; expressions when symbolic), the maximisers, and
    the condition (32) on ``b_m`` and ``b_s`` (sufficient only, see the module docstring)."""

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
    """Worst case over frequency of the bounds of (32) (exact): root isolation for a numeric
    controller, endpoint analysis for a symbolic one (affine or concave in ``c``).

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
        wc = symbolic_minimum(sp.expand(-bound), names=scene.naming())   # min of -bound = -sup
        sup = sp.expand(-wc.minimum) if wc.minimum is not None else sp.Function("sup_c")(bound)
        out.append((sup, wc.minimiser, sp.Ge(damping, sup)))
    return TeleWorstCase(out[0][0], out[1][0], out[0][1], sp.And(out[0][2], out[1][2]))


def bound_parameters(scene: TeleoperatorScene) -> set[sp.Symbol]:
    """The parameters the passivity decision depends on (the masses store energy losslessly and
    do not enter it)."""
    out: set[sp.Symbol] = set()
    for value in (scene.b_m, scene.b_s, scene.T, scene.C, scene.alpha):
        out |= sp.sympify(value).free_symbols
    return out - {Z_SYM}


def _fmpq_poly(expr: sp.Expr) -> flint.fmpq_poly:
    return as_fmpq_poly(sp.Poly(sp.expand(expr), Z_SYM).as_expr() if sp.expand(expr).free_symbols else sp.expand(expr), Z_SYM)


def _controller(scene: TeleoperatorScene) -> tuple[flint.fmpq_poly, flint.fmpq_poly]:
    """``C = P/Q`` coprime, ``Q`` monic (numeric controller)."""
    num, den = sp.fraction(sp.cancel(sp.together(scene.C)))
    P, Q = _fmpq_poly(num), _fmpq_poly(den)
    if P.is_zero():
        return P, flint.fmpq_poly([1])
    g = P.gcd(Q)
    P, Q = P / g, Q / g
    lead = Q.coeffs()[-1]
    return P / lead, Q / lead


def margin_transfer(scene: TeleoperatorScene, robot: str) -> tuple[flint.fmpq_poly, flint.fmpq_poly]:
    """``F(z) = b - w T C(z)/(1 - z)`` (``w = alpha(alpha + 1)`` for the master, ``alpha + 1`` for
    the slave) as polynomials: on the unit circle ``Re F = b - bound(c)`` of (32), because
    ``T/(1 - cos wT) Re{(1 - e^{-jwT}) C} = 2T Re{C(z)/(1 - z)}``.

    >>> sc = TeleoperatorScene.pd(K=2, B=0, T=sp.Rational(1, 10), m_m=1, m_s=1, b_m=1, b_s=1)
    >>> margin_transfer(sc, "slave")                 # 1 - 2*(1/10)*2/(1 - z)
    (x + (-3/5), x + (-1))
    """
    weight = scene.alpha * (scene.alpha + 1) if robot == "master" else scene.alpha + 1
    damping = scene.b_m if robot == "master" else scene.b_s
    cn, cd = _controller(scene)
    one_minus_z = flint.fmpq_poly([1, -1])
    P = as_fmpq(damping) * one_minus_z * cd - as_fmpq(weight * scene.T) * cn
    Q = one_minus_z * cd
    g = P.gcd(Q) if not P.is_zero() else Q
    P, Q = P / g, Q / g
    lead = Q.coeffs()[-1]
    return P / lead, Q / lead


def error_coordinate_damping(scene: TeleoperatorScene) -> sp.Expr:
    """``h``: the least damping the robots offer the error coordinate ``alpha x_m - x_s``,
    ``min {b_m a^2 + b_s b^2 : alpha a - b = 1} = b_m b_s/(b_m + alpha^2 b_s)`` (``b_s`` when
    ``b_m = alpha^2 b_s = 0``); ``h >= L(c)`` for all ``c`` is condition (P5).

    >>> error_coordinate_damping(TeleoperatorScene.pd(alpha=1))
    b_m*b_s/(b_m + b_s)
    >>> error_coordinate_damping(TeleoperatorScene.pd(alpha=0, b_m=0, b_s=sp.Rational(1, 10)))
    1/10
    """
    den = scene.b_m + scene.alpha**2 * scene.b_s
    if sp.sympify(den).is_zero:
        return scene.b_s
    return sp.cancel(scene.b_m * scene.b_s / den)


def energy_transfer(scene: TeleoperatorScene) -> tuple[flint.fmpq_poly, flint.fmpq_poly]:
    """``T H(z) = h + T C(z)/(z - 1)`` (numeric scene with ``b_m, b_s >= 0``) as coprime
    polynomials: on the circle its real part is ``h - L(c)`` (condition P5), its poles are those
    of ``C`` and ``z = 1`` (module docstring, step 5).

    >>> energy_transfer(TeleoperatorScene.pd(K=2, B=0, T=sp.Rational(1, 3), b_m=10, b_s=sp.Rational(3, 7)))
    (30/73*x + 56/219, x + (-1))
    """
    P, Q = _controller(scene)
    h = as_fmpq(error_coordinate_damping(scene))
    T = as_fmpq(scene.T)
    zm1 = flint.fmpq_poly([-1, 1])
    num, den = h * zm1 * Q + T * P, zm1 * Q
    if num.is_zero():
        return num, flint.fmpq_poly([1])
    g = num.gcd(den)
    num, den = num / g, den / g
    lead = den.coeffs()[-1]
    return num / lead, den / lead


# ---------------------------------------------------------------------------------------------
# the exact decision, numeric scenes: every condition through the kernel
# ---------------------------------------------------------------------------------------------


def _damping_condition(scene: TeleoperatorScene) -> Outcome:
    from hapticproof.exact.kernel import decide_sign

    # a constant polynomial (t plays no role) on [0, 1]: the sign certificate the checker re-verifies
    outs = {name: decide_sign(flint.fmpq_poly([as_fmpq(value)]), 0, 1, variable="t", label=name)
            for name, value in (("b_m", scene.b_m), ("b_s", scene.b_s))}
    facts = {"certificate": outs["b_m"].evidence.facts["certificate"],
             "slave": outs["b_s"].evidence.facts["certificate"]}
    bad = [name for name, out in outs.items() if out.decision != Decision.PROVED]
    if not bad:
        return Outcome(Decision.PROVED, Evidence(Method.CANONICAL_FORM, facts=facts),
                       f"b_m = {sp.sstr(scene.b_m)} >= 0, b_s = {sp.sstr(scene.b_s)} >= 0")
    return Outcome(Decision.DISPROVED, Evidence(Method.CANONICAL_FORM, witness={n: getattr(scene, n) for n in bad}, facts=facts),
                   f"{' and '.join(f'{n} = {sp.sstr(getattr(scene, n))}' for n in bad)} < 0: a negative damping supplies energy "
                   "(the rigid motion v_s = alpha v_m, controller silent, or the error motion of least dissipation)")


def _numeric_conditions(scene: TeleoperatorScene) -> list[Condition]:
    from hapticproof.exact.kernel import BoundaryRoot, decide_rational_sign, locate_roots, residue_outcome, transfer_json
    from hapticproof.exact.unitcircle import circle_real_part

    damping = _damping_condition(scene)
    out = [Condition(_name("D"), damping)]
    P, Q = _controller(scene)
    # H = h/T + C/(z - 1) with the residues Res(H, z0)/z0 = rho; its numerator does not depend on
    # h at the unit-circle poles of C, so any h >= 0 serves the residues
    h_for_poles = as_fmpq(error_coordinate_damping(scene)) if damping.decision == Decision.PROVED else flint.fmpq(0)
    T = as_fmpq(scene.T)
    zm1 = flint.fmpq_poly([-1, 1])
    PH, QH = h_for_poles / T * zm1 * Q + P, zm1 * Q
    if not PH.is_zero():
        g = PH.gcd(QH)
        PH, QH = PH / g, QH / g
    roots = locate_roots(Q, "disk")
    facts = {"certificate": roots}
    if roots.outside:
        where = ", ".join(f"z ~ {complex(p):.6g}".replace("+0j", "").replace("(", "").replace(")", "") for p in roots.outside_points[:3])
        p1 = Outcome(Decision.DISPROVED, Evidence(Method.ROOT_ISOLATION, witness={"pole": where}, facts=facts),
                     f"C has {roots.outside} pole(s) outside the unit circle ({where}): its impulse response grows and "
                     "a pair of impulses far apart supplies energy")
    else:
        p1 = Outcome(Decision.PROVED, Evidence(Method.ROOT_ISOLATION, facts=facts),
                     f"no pole of C outside the unit circle ({roots.inside} inside, "
                     f"{sum(r.multiplicity * (1 if r.value is not None else 2) for r in roots.boundary)} on it)")
    out.append(Condition(_name("P1"), p1))
    at_one = [r for r in roots.boundary if r.value is not None and r.value == 1]
    if at_one:
        order = at_one[0].multiplicity
        p2 = Outcome(Decision.DISPROVED, Evidence(Method.ROOT_ISOLATION, witness={"pole": 1, "order": order}, facts=facts),
                     f"C has a pole of order {order} at z = 1 (integral action): H = h/T + C/(z - 1) has a pole of order "
                     f"{order + 1} there; holding the error and releasing it returns unbounded energy")
        p3 = Outcome(Decision.UNDECIDED, Evidence(Method.CANONICAL_FORM), "not applicable: C(1) is infinite (see P2)")
    else:
        p2 = Outcome(Decision.PROVED, Evidence(Method.ROOT_ISOLATION, facts=facts), "Q(1) != 0: no pole of C at z = 1")
        dc = P(1) / Q(1)
        if dc == 0:
            from hapticproof.exact.kernel import decide_sign

            zero = decide_sign(flint.fmpq_poly([dc]), 0, 1, variable="t", label="C(1)")
            p3 = Outcome(Decision.PROVED, Evidence(Method.CANONICAL_FORM, facts={**zero.evidence.facts, "C(1)": to_rational(dc)}),
                         "C(1) = 0: H has no pole at z = 1")
        else:
            res = residue_outcome(PH, QH, BoundaryRoot(1, sp.Integer(1)))
            verb = ">= 0" if dc > 0 else "< 0"
            p3 = Outcome(res.decision, Evidence(res.evidence.method, witness=None if dc > 0 else {"C(1)": to_rational(dc)},
                                                facts=res.evidence.facts),
                         f"C(1) = {sp.sstr(to_rational(dc))} {verb}" +
                         ("" if dc > 0 else ": the discrete spring stores C(1) e^2/2 < 0 after a slow displacement"))
    out += [Condition(_name("P2"), p2), Condition(_name("P3"), p3)]
    bad, good = [], []
    for r in roots.boundary:
        if r.value is not None and r.value == 1:
            continue
        if r.multiplicity > 1:
            bad.append(Outcome(Decision.DISPROVED, Evidence(Method.ROOT_ISOLATION, witness={"pole": r.label(),
                                                                                             "multiplicity": r.multiplicity},
                                                            facts=facts),
                               f"the unit-circle pole {r.label()} of C has multiplicity {r.multiplicity}"))
            continue
        res = residue_outcome(PH, QH, r)
        (good if res.decision == Decision.PROVED else bad).append(res)
    if bad:
        first = bad[0]
        p4 = Outcome(first.decision, first.evidence, f"rho = Res(H, z0)/z0: {first.reason}")
    elif good:
        p4 = Outcome(Decision.PROVED, Evidence(Method.CANONICAL_FORM, facts={"residues": good}),
                     "rho = Res(H, z0)/z0 > 0: " + "; ".join(o.reason for o in good))
    else:
        p4 = Outcome(Decision.PROVED, Evidence(Method.ROOT_ISOLATION, facts=facts), "no other unit-circle pole of C")
    out.append(Condition(_name("P4"), p4))
    if damping.decision != Decision.PROVED:
        p5 = Outcome(Decision.UNDECIDED, Evidence(Method.CANONICAL_FORM), "not evaluated: a negative damping already decides")
    else:
        FP, FQ = energy_transfer(scene)
        N, D = circle_real_part(FP, FQ)
        p5 = decide_rational_sign(N, D, -1, 1, "c", "h - L", transfer=transfer_json(FP, FQ), transfer_den=FQ)
        p5 = Outcome(p5.decision, p5.evidence, p5.reason + f" (h = {sp.sstr(error_coordinate_damping(scene))})")
    out.append(Condition(_name("P5"), p5))
    return out


# ---------------------------------------------------------------------------------------------
# symbolic scenes: the same conditions as conditions on the parameters
# ---------------------------------------------------------------------------------------------


def _sign(value: Any, what: str, strict: bool = False, names: Any = DEFAULT) -> Outcome:
    """The sign of ``value`` (``what``: its name in the toolkit's words, printed in ``names``)."""
    value = sp.cancel(sp.sympify(value))
    ok = value.is_positive if strict else value.is_nonnegative
    rel = ">" if strict else ">="
    what = names.words(what)
    if ok:
        return Outcome(Decision.PROVED, Evidence(Method.CANONICAL_FORM, facts={"value": value}), f"{what} = {names.text(value)} {rel} 0")
    if (value.is_nonpositive if strict else value.is_negative):
        return Outcome(Decision.DISPROVED, Evidence(Method.CANONICAL_FORM, witness={"value": value}),
                       f"{what} = {names.text(value)} is not {rel} 0")
    condition = sp.Gt(value, 0) if strict else sp.Ge(value, 0)
    return Outcome(Decision.SYMBOLIC, Evidence(Method.CANONICAL_FORM, facts={"condition": condition}),
                   f"{names.text(condition)}")


def _symbolic_conditions(scene: TeleoperatorScene) -> list[Condition]:
    names = scene.naming()
    dm, ds = _sign(scene.b_m, "b_m", names=names), _sign(scene.b_s, "b_s", names=names)
    parts = [o for o in (dm, ds) if o.decision != Decision.PROVED]
    if not parts:
        damping = Outcome(Decision.PROVED, Evidence(Method.CANONICAL_FORM), names.words("b_m, b_s >= 0 by their assumptions"))
    elif any(o.decision == Decision.DISPROVED for o in parts):
        damping = next(o for o in parts if o.decision == Decision.DISPROVED)
    else:
        cond = sp.And(*[o.evidence.facts["condition"] for o in parts])
        damping = Outcome(Decision.SYMBOLIC, Evidence(Method.CANONICAL_FORM, facts={"condition": cond}), names.text(cond))
    out = [Condition(_name("D"), damping)]
    C = sp.cancel(sp.together(scene.C))
    poles = poles_of(C)
    p1 = pole_location_outcome(poles, of=" of C")
    unknown = [p for p in poles if p.location == "unknown"]        # (P2) and (P4) undecided with them
    at_one = [p for p in poles if p.location == "on" and sp.simplify(p.value - 1) == 0]
    out.append(Condition(_name("P1"), p1))
    if at_one:
        out.append(Condition(_name("P2"), Outcome(Decision.DISPROVED, Evidence(Method.CANONICAL_FORM,
                                                                                witness={"pole": 1, "order": at_one[0].multiplicity}),
                                                  "C has a pole at z = 1 (integral action)")))
        out.append(Condition(_name("P3"), Outcome(Decision.UNDECIDED, Evidence(Method.CANONICAL_FORM),
                                                  "not applicable: C(1) is infinite (see P2)")))
    else:
        p2 = Outcome(Decision.PROVED if not unknown else Decision.UNDECIDED, Evidence(Method.CANONICAL_FORM),
                     "no pole of C at z = 1" if not unknown else "the poles of C depend on the parameters")
        out += [Condition(_name("P2"), p2), Condition(_name("P3"), _sign(C.subs(Z_SYM, 1), "C(1)", names=names))]
    others = [p for p in poles if p.location == "on" and sp.simplify(p.value - 1) != 0]
    if any(p.multiplicity > 1 for p in others):
        p4 = Outcome(Decision.DISPROVED, Evidence(Method.CANONICAL_FORM), "a unit-circle pole of C is not simple")
    elif others:
        G = sp.cancel(C / (Z_SYM - 1))
        res = [r for r in unit_circle_residues(G, [p for p in poles_of(G) if p.location == "on"]) if sp.simplify(r.pole - 1) != 0]
        worst = min(res, key=lambda r: {Decision.DISPROVED: 0, Decision.UNDECIDED: 1, Decision.SYMBOLIC: 2,
                                        Decision.PROVED: 3}[r.outcome.decision])
        p4 = Outcome(worst.outcome.decision, worst.outcome.evidence, "rho = Res(C,z0)/(z0(z0-1)): " + worst.outcome.reason)
    else:
        p4 = Outcome(Decision.PROVED if not unknown else Decision.UNDECIDED, Evidence(Method.CANONICAL_FORM),
                     "no other unit-circle pole of C" if not unknown else "the poles of C depend on the parameters")
    out.append(Condition(_name("P4"), p4))
    out.append(Condition(_name("P5"), _symbolic_leak(scene)))
    return out


def _symbolic_leak(scene: TeleoperatorScene) -> Outcome:
    """(P5) ``h >= sup_c L(c)``: the exact supremum of a numeric ``L``, or endpoint analysis (in
    the scene's names: ``h``, ``L`` and ``c`` as its naming prints them)."""
    names = scene.naming()
    w, t = names.words, names.text
    h = error_coordinate_damping(scene)
    leak = bounds(scene).leak
    if not (sp.sympify(leak).free_symbols - {C_SYM}):
        sup, where = _sup_numeric(leak)
        if sup == sp.oo:
            return Outcome(Decision.DISPROVED, Evidence(Method.ROOT_ISOLATION), w("L(c) is unbounded on [-1, 1]"))
        if not isinstance(sup, sp.Basic):
            return Outcome(Decision.SYMBOLIC, Evidence(Method.ROOT_ISOLATION, facts={"supremum": sup}),
                           w("h >= sup L") + f" = {sup.str(12) if hasattr(sup, 'str') else sup} (an algebraic number)")
        cond = sp.Ge(h, sup)
        return _sign(h - sup, "h - sup L", names=names) if not cond.free_symbols else \
            Outcome(Decision.SYMBOLIC, Evidence(Method.ROOT_ISOLATION, facts={"condition": cond}),
                    f"{t(cond)} ({w('sup L at c')} = {where})")
    wc = symbolic_minimum(sp.expand(-leak), names=names)              # min of -L = -sup L
    if wc.minimum is None:
        return Outcome(Decision.SYMBOLIC, Evidence(Method.ENDPOINT_ANALYSIS, facts={"condition": sp.Ge(h, sp.Function("sup_c")(leak))}),
                       w("h >= sup_c L(c)") + f" ({wc.outcome.reason})")
    sup = sp.expand(-wc.minimum)
    cond = sp.Ge(h, sup)
    if cond in (sp.true, sp.false):
        decision = Decision.PROVED if cond is sp.true else Decision.DISPROVED
        return Outcome(decision, Evidence(Method.ENDPOINT_ANALYSIS, facts={"condition": cond}),
                       w("h >= sup L") + f" = {t(sup)} is {cond}")
    return Outcome(Decision.SYMBOLIC, Evidence(Method.ENDPOINT_ANALYSIS, facts={"condition": cond, "supremum": sup}),
                   f"{t(cond)} ({w('L(c)')} = {t(leak)} is largest at {w('c')} = {t(wc.minimiser)})"
                   if wc.minimiser is not None else f"{t(cond)} ({w('sup of L(c)')} = {t(leak)}: {wc.outcome.reason})")


@stage("teleoperator_conditions")
def passivity_conditions(scene: TeleoperatorScene) -> list[Condition]:
    """The conditions (D), (P1)-(P5) of the theorem (module docstring), each decided: exactly
    with certificates for a numeric scene, as conditions on the parameters otherwise.

    >>> sc = TeleoperatorScene(1, 1, sp.Rational(1, 50), sp.Rational(1, 50), sp.Rational(1, 100), 1 - 1/(Z_SYM + 1))
    >>> [(c.name[:4], c.decision.value) for c in passivity_conditions(sc)]       # a negative residue at z = -1
    [('(D) ', 'proved'), ('(P1)', 'proved'), ('(P2)', 'proved'), ('(P3)', 'proved'), ('(P4)', 'disproved'), ('(P5)', 'proved')]
    """
    names = scene.naming()
    if bound_parameters(scene):
        conds = _symbolic_conditions(scene)
        return [Condition(names.words(c.name), c.outcome) for c in conds]
    return named_conditions(_numeric_conditions(scene), names, numeric=True)


def passivity(scene: TeleoperatorScene) -> Outcome:
    """Is the teleoperator passive? The exact decision of the theorem (the masses need not be
    given), or the conditions on the parameters when some are symbols.

    >>> sc = TeleoperatorScene.pd(K=1, B=0, T=sp.Rational(15, 1000), b_m="0.01822", b_s="0.01822")
    >>> passivity(sc).decision.value, passivity(sc).witness          # h = b/2 >= KT/2
    ('proved', None)
    >>> unstable = TeleoperatorScene(1, 1, 1, 1, sp.Rational(1, 100), 2 / (Z_SYM - 3))
    >>> passivity(unstable).decision.value
    'disproved'
    """
    return combine(passivity_conditions(scene), subject="the teleoperator", holds="passive")


def exact_condition(scene: TeleoperatorScene) -> sp.Basic | None:
    """The exact passivity condition on the parameters (``True``/``False`` when decided), or
    ``None`` when a condition is undecided.

    >>> exact_condition(TeleoperatorScene.pd(alpha=1))
    b_m*b_s/(b_m + b_s) >= B + K*T/2
    """
    conds = passivity_conditions(scene)
    if any(c.decision == Decision.DISPROVED for c in conds):
        return sp.false
    if any(c.decision == Decision.UNDECIDED for c in conds):
        return None
    parts = [c.outcome.evidence.facts["condition"] for c in conds if c.decision == Decision.SYMBOLIC]
    if any(not isinstance(p, sp.Basic) for p in parts):
        return None
    return sp.And(*parts) if parts else sp.true


# ---------------------------------------------------------------------------------------------
# the paper's criterion (32), a sufficient condition
# ---------------------------------------------------------------------------------------------


def criterion_conditions(scene: TeleoperatorScene) -> list[Condition]:
    """The paper's criterion (32) (eq. 29 at ``alpha = 1``) decided exactly as printed: each
    robot's damping above its bound at every frequency. A sufficient condition for ``alpha > 0``
    under (P1)-(P4) only; ``disproved`` here is never a disproof of passivity.

    >>> sc = TeleoperatorScene.pd(K=2, B=0, T=sp.Rational(1, 3), b_m=10, b_s=sp.Rational(3, 7))
    >>> [(c.name, c.decision.value) for c in criterion_conditions(sc)]      # the slave needs b_s >= 2L = 2/3
    [('(32) master: b_m >= bound(c) for all w', 'proved'), ('(32) slave: b_s >= bound(c) for all w', 'disproved')]
    """
    from hapticproof.exact.kernel import decide_rational_sign, transfer_json
    from hapticproof.exact.unitcircle import circle_real_part

    names = scene.naming()
    if bound_parameters(scene):
        wc = worst_case(scene)
        conds = []
        for robot, sup, damping in (("master", wc.sup_master, scene.b_m), ("slave", wc.sup_slave, scene.b_s)):
            conds.append(Condition(names.words(f"(32) {robot}: b_{robot[0]} >= bound(c) for all w"),
                                   Outcome(Decision.SYMBOLIC, Evidence(Method.ENDPOINT_ANALYSIS, facts={"supremum": sup}),
                                           f"{names.text(damping)} >= {names.text(sup)}")))
        return conds
    conds = []
    for robot in ("master", "slave"):
        P, Q = margin_transfer(scene, robot)
        N, D = circle_real_part(P, Q)
        out = decide_rational_sign(N, D, -1, 1, "c", f"b_{robot[0]} - bound", transfer=transfer_json(P, Q), transfer_den=Q)
        conds.append(Condition(f"(32) {robot}: b_{robot[0]} >= bound(c) for all w", out))
    return named_conditions(conds, names, numeric=True)


def criterion(scene: TeleoperatorScene) -> Outcome:
    """The paper's (32) as printed, combined: ``proved`` means the printed bounds hold, not that
    the teleoperator is passive (that is :func:`passivity`).

    >>> criterion(TeleoperatorScene.pd(K=2, B=0, T=sp.Rational(1, 3), b_m=10, b_s=sp.Rational(3, 7))).decision.value
    'disproved'
    """
    return combine(criterion_conditions(scene), subject="the paper's criterion (32)", holds="satisfied")
