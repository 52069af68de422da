r"""The teleoperator paper, Sections III-A and III-B: the passivity criterion (29)-(32) and its PD
special case (33)-(35).
"""

from __future__ import annotations


import sympy as sp

from hapticproof.analysis import classics, teleoperator as tele
from hapticproof.systems import teleoperator as telemodel
from hapticproof.audit.runner import AuditContext
from hapticproof.audit.compare import NotABound, as_bound, compare_bounds, compare_expressions
from hapticproof.exact.canonical import is_identically_zero
from hapticproof.core.evidence import Evidence, Finding, Method, Verdict
from hapticproof.core.symbols import c as C_SYM
from hapticproof.core.symbols import z as Z_SYM
from hapticproof.exact.unitcircle import omega_to_c
from hapticproof.derivations.teleoperator.paper import ASSUME, B, CONTROLLERS, ERROR_TABLE, K, PAPER, PRINTED, T, TABLE, X_M, X_S, alpha, b, b_m, b_s, controller_kernel, line_pairs, m_m, m_s, omega, parse_with, relations_of
from hapticproof.derivations.teleoperator.model import error_defined, restoring_forces


def _generic_bound(name: str, weight: sp.Expr) -> sp.Expr:
    """``weight * (-Re kernel) * alias weight`` in omega, for an unspecified controller."""
    leak = -sp.re(controller_kernel(name)) * classics.alias_weight(T).subs(C_SYM, sp.cos(omega * T))
    return weight * leak


def _controller_instances() -> list[tuple[str, sp.Expr]]:
    a = sp.Rational(1, 2)
    return [("PD (33)", telemodel.pd_controller()), ("PD with filtered derivative (a = 1/2)", telemodel.filtered_pd_controller(a=a))]


def bound_check(ctx: AuditContext, alpha_value: sp.Expr | None, sufficient: bool = True) -> Finding:
    """(29) (alpha_value = 1) or (32) (symbolic alpha): generic controller, then instances; then,
    with ``sufficient``, the printed bounds as the passivity criterion the paper claims
    (:func:`sufficiency`). Without it the derivation alone (Lemma 5's (40) bounds (39), an
    integral inequality, not passivity)."""
    relations = ctx.statement.relations()
    lines = line_pairs(ctx.statement)
    al = alpha if alpha_value is None else alpha_value
    for rel, damping in zip(relations, (b_m, b_s)):
        if len(rel.terms) != 2 or rel.lhs != damping or rel.ops[0] not in (">", ">="):
            return Finding(Verdict.WRONG, f"each line must bound a robot's damping from below ({damping} > ...); the display "
                           f"reads {sp.sstr(rel.lhs)} {' '.join(rel.ops)} ...",
                           Evidence(Method.PARSE, facts={"printed_form": [sp.srepr(rel.lhs), list(rel.ops)]}))
    if len(relations) != 2:
        return Finding(Verdict.WRONG, f"expected the two lines b_m > ..., b_s > ...; found {len(relations)}",
                       Evidence(Method.PARSE))
    generic_ok = []
    u, v = sp.symbols("u v", real=True)         # C(e^{jwT}) = u + jv: a general controller value
    for (lhs, rhs), name in zip(lines, ("C_m", "C_s")):
        derived = _generic_bound(name, al + 1)
        value = CONTROLLERS[name](sp.exp(sp.I * omega * T))
        diff = sp.expand_complex(sp.expand((rhs - derived).subs(value, u + sp.I * v)))
        generic_ok.append(is_identically_zero(diff))
    if not all(generic_ok):
        which = [name for name, ok in zip(("b_m", "b_s"), generic_ok) if not ok]
        return Finding(Verdict.WRONG, f"the printed bound on {', '.join(which)} differs from the derived leak bound "
                       f"(alpha + 1) L_C for a general controller C(e^(jwT)) = u + jv",
                       Evidence(Method.CANONICAL_FORM, facts={"lines_match": generic_ok}))
    instances = {}
    for label, controller in _controller_instances():
        scene = telemodel.TeleoperatorScene(m_m, m_s, b_m, b_s, T, controller, al if alpha_value is None else alpha_value)
        derived = tele.bounds(scene)
        for (lhs, rhs), name, bound in zip(lines, ("C_m", "C_s"), (derived.master, derived.slave)):
            ctrl = scene.C_m if name == "C_m" else scene.C_s
            printed = rhs.replace(CONTROLLERS[name], sp.Lambda(sp.Symbol("zz"), ctrl.subs(Z_SYM, sp.Symbol("zz"))))
            # exact comparison at angles with rational cosines (the general-C identity is proved above)
            angles = (sp.pi / 3, sp.pi / 2, 2 * sp.pi / 3, 3 * sp.pi / 4)
            agree = all(is_identically_zero(sp.expand_complex(printed.subs(omega, th / T)) - bound.subs(C_SYM, sp.cos(th)))
                        for th in angles)
            if not agree:
                return Finding(Verdict.WRONG, f"{label}: printed and derived bounds differ", Evidence(Method.CANONICAL_FORM))
            instances[f"{label}, {name}"] = bound
    reduction = ""
    if alpha_value is None:
        reduction = "; at alpha = 1 it is (29)"
    derivation = ("derived for a general C(z): the sampled spring on e = alpha x_m - x_s leaks at most L(c)|alpha V_m - V_s|^2 "
                  "(kernel (14), alias weight T^2/(2(1 - c))), and |alpha a - b|^2 <= (alpha + 1)(alpha|a|^2 + |b|^2) gives "
                  f"b_m >= (alpha + 1) L_(C_m), b_s >= (alpha + 1) L_(C_s){reduction}; exact in c for PD and filtered PD")
    derived = sp.And(*[sp.Ge(d, v) for d, v in zip((b_m, b_s), list(instances.values())[:2])])
    if not sufficient:
        return Finding(Verdict.CONFIRMED, derivation, Evidence(Method.CANONICAL_FORM, instances=len(instances),
                                                                facts={"bounds_in_c": instances}), derived=derived)
    return sufficiency(derivation, instances, derived, sp.Integer(1) if alpha_value is not None else sp.Integer(2))


#: the assumptions (P1)-(P4) of the exact theorem (hapticproof.analysis.teleoperator) that the
#: paper does not state for a general controller
UNSTATED = ("C has no pole in |z| > 1 (P1) nor at z = 1 (P2), C(1) >= 0 (P3), and its other unit-circle poles are simple "
            "with Res(C,z0)/(z0(z0-1)) > 0 (P4)")


def sufficiency(derivation: str, instances: dict, derived: sp.Basic, al: sp.Expr) -> Finding:
    """(29)/(32) as the sufficient condition the paper claims, against the exact decision: not
    sufficient without (P1)-(P4) (a negative spring passes it), sufficient with them (``h`` is a
    weighted harmonic mean of the per-robot shares, hence above their minimum), not necessary
    when ``b_m != alpha b_s``. Every instance is decided exactly; none is assumed."""
    from hapticproof.exact.canonical import is_identically_zero as zero

    third, tenth = sp.Rational(1, 3), sp.Rational(1, 100)
    spring = telemodel.TeleoperatorScene(1, 1, tenth, tenth, tenth, sp.Integer(-1), al)
    # h = 30/73 (alpha = 1) or 5/12 (alpha = 2) >= L = KT/2 = 1/3 while b_s < (alpha + 1) L
    split = telemodel.TeleoperatorScene.pd(K=2, B=0, T=third, alpha=al, b_m=10, b_s=sp.Rational(3, 7) if al == 1 else sp.Rational(1, 2))
    h = b_m * b_s / (b_m + alpha**2 * b_s)
    p, q = b_m / (alpha * (alpha + 1)), b_s / (alpha + 1)
    identity = zero(sp.cancel(1 / h - (1 / (alpha + 1)) / q - (alpha / (alpha + 1)) / p))
    checks = {"negative spring C = -1: (29)/(32) holds": tele.criterion(spring).decision.value,
              "negative spring C = -1: passive": tele.passivity(spring).decision.value,
              "unequal robots: (29)/(32) holds": tele.criterion(split).decision.value,
              "unequal robots: passive": tele.passivity(split).decision.value}
    expected = ["proved", "disproved", "disproved", "proved"]
    facts = {"bounds_in_c": instances, "exact_decisions": checks, "unstated_assumption": UNSTATED,
             "harmonic_mean_identity": identity, "counterexample": tele.passivity(spring).to_json(),
             "not_necessary": tele.passivity(split).to_json()}
    if list(checks.values()) != expected or not identity:
        return Finding(Verdict.UNDECIDED, f"{derivation}; the sufficiency audit did not go as the theorem says: {checks}",
                       Evidence(Method.INSTANCES, facts=facts), derived=derived)
    witness = {"C": "-1", "T": sp.sstr(tenth), "b_m": sp.sstr(tenth), "b_s": sp.sstr(tenth), "alpha": sp.sstr(al)}
    return Finding(
        Verdict.NEEDS_ASSUMPTION,
        f"sufficient only under (P1)-(P4), which the paper does not state for a general C: C = -1 (T = b_m = b_s = 1/100, "
        f"alpha = {al}) satisfies it at every frequency but is not passive ((P3) C(1) < 0, exact decision); under them it "
        "implies the exact h = b_m b_s/(b_m + alpha^2 b_s) >= L(c) (h is a weighted harmonic mean of the robots' shares, "
        f"alpha > 0), with equality iff b_m = alpha b_s (C = 2, T = 1/3, b_m = 10, b_s = {sp.sstr(split.b_s)}: passive, yet it "
        "fails); the bound itself is derived for a general C(z)",
        Evidence(Method.COUNTEREXAMPLE, witness=witness, instances=len(instances) + 2,
                 facts={**facts, "derivation": derivation}),
        derived=derived,
    )


@PAPER.equation("29", kind="condition", printed=PRINTED["29"], section="III", assumptions=ASSUME,
                derivation="Lemmas 1-5 chain: b_i >= 2 L_(C)(c), twice Colgate's bound (classics.leak_bound)")
def eq29(ctx: AuditContext) -> Finding:
    return bound_check(ctx, sp.Integer(1))


@PAPER.equation("30", kind="expression", printed=PRINTED["30"], section="III-A", assumptions=ASSUME,
                derivation="scaled controllers; consistent with the text's C_m < C_s and x_m > x_s (both mean alpha < 1)", quotes=('31',))
def eq30(ctx: AuditContext) -> Finding:
    (rel,) = relations_of(ctx.statement)
    (rel31,) = parse_with(ctx, ERROR_TABLE, PAPER.get("31").printed).relations()
    if len(rel.terms) != 3 or rel.terms[2] != CONTROLLERS["C"](sp.I * omega) or not is_identically_zero(
            rel.terms[1] - CONTROLLERS["C_s"](sp.I * omega)):
        return Finding(Verdict.WRONG, f"(30) must read C_m/alpha = C_s = C; it reads {' = '.join(map(sp.sstr, rel.terms))}",
                       Evidence(Method.PARSE, facts={"printed_form": [sp.srepr(x) for x in rel.terms]}))
    solved = sp.solve(sp.Eq(rel.terms[0], rel.terms[1]), CONTROLLERS["C_m"](sp.I * omega))
    if len(solved) != 1:
        return Finding(Verdict.WRONG, f"(30) does not determine C_m: {sp.sstr(rel.terms[0])} = {sp.sstr(rel.terms[1])}",
                       Evidence(Method.PARSE))
    cm = solved[0]
    ratio = sp.cancel(cm / CONTROLLERS["C_s"](sp.I * omega))
    error = error_defined(rel31)
    zero_error = sp.solve(sp.Eq(error, 0), X_S) if error is not None else []
    if len(zero_error) != 1:
        return Finding(Verdict.INCONSISTENT, f"(31) ({sp.sstr(rel31.as_sympy())}) does not fix x_s when the error vanishes, "
                       "so it cannot be the error of the scaled controllers (30)",
                       Evidence(Method.CANONICAL_FORM, facts={"ids": ["30", "31"], "printed_form": sp.srepr(rel31.as_sympy())}))
    tracking = sp.cancel(zero_error[0] / X_M)            # x_s/x_m when the error vanishes
    if not (is_identically_zero(ratio - alpha) and is_identically_zero(tracking - alpha)):
        return Finding(Verdict.INCONSISTENT, "(30) and (31) scale differently",
                       Evidence(Method.CANONICAL_FORM, facts={"ids": ["30", "31"], "C_m/C_s": ratio, "x_s/x_m": tracking}))
    return Finding(Verdict.CONFIRMED, "C_m = alpha C_s; with (31) the robots track x_s = alpha x_m, so the text's 'C_m < C_s and "
                   "x_m > x_s' both mean alpha < 1; alpha = 1 is (17)",
                   Evidence(Method.CANONICAL_FORM, facts={"C_m/C_s": ratio, "x_s/x_m": tracking,
                                                          "printed_form": (sp.srepr(ratio), sp.srepr(tracking))}))


@PAPER.equation("30-requisite", kind="claim", after="30", section="III-A",
                printed="The assumption (30), which serves as a requisite for the passivity of the teleoperator",
                derivation="curl of the controller force field (f_m, f_s) = (K_m e, -K_s e), e = alpha x_m - x_s")
def requisite(ctx: AuditContext) -> Finding:
    Km, Ks = sp.symbols("K_m K_s", positive=True)
    e = alpha * X_M - X_S
    fm, fs = Km * e, -Ks * e
    curl = sp.expand(sp.diff(fs, X_M) - sp.diff(fm, X_S))
    if not is_identically_zero(curl - (Km - alpha * Ks)):
        return Finding(Verdict.UNDECIDED, "unexpected curl", Evidence(Method.STRUCTURAL, facts={"curl": curl}))
    return Finding(Verdict.CONFIRMED, "the controller forces are the gradient of a spring potential iff their curl "
                   f"{sp.sstr(curl)} vanishes, i.e. K_m = alpha K_s (30); otherwise a slow closed path in (x_m, x_s) extracts "
                   "net work proportional to the enclosed area while the damping losses vanish with the speed, so the "
                   "teleoperator is not passive for any damping (static gains; the low-frequency limit of C(z))",
                   Evidence(Method.STRUCTURAL, facts={"curl": curl}))


@PAPER.equation("31", kind="expression", printed=PRINTED["31"], section="III-A", assumptions=ASSUME,
                derivation="the coordinate on which (30)'s controllers are one spring: forces = gradient of C e^2/2")
def eq31(ctx: AuditContext) -> Finding:
    (rel,) = parse_with(ctx, ERROR_TABLE).relations()
    gain = sp.Symbol("C_gain", positive=True)
    error = error_defined(rel)
    if error is None or not error.free_symbols & {X_M, X_S}:
        return Finding(Verdict.WRONG, f"(31) must define the error e from the positions; it reads {sp.sstr(rel.as_sympy())}",
                       Evidence(Method.PARSE, facts={"printed_form": sp.srepr(rel.as_sympy())}), corrected=PRINTED["31"])
    fm, fs = restoring_forces(gain, error)
    if fs == 0:
        return Finding(Verdict.INCONSISTENT, f"with e = {sp.sstr(error)} the spring C e^2/2 exerts no force on the slave, "
                       "unlike the controllers (30)", Evidence(Method.CANONICAL_FORM, facts={"forces": (fm, fs)}))
    ratio = sp.cancel(-fm / fs)
    # the spring's potential is what the controllers (30) implement: e and -e give the same one
    potential = sp.expand(gain * error**2 / 2)
    expected = sp.expand(gain * (alpha * X_M - X_S) ** 2 / 2)
    if is_identically_zero(ratio - alpha) and not is_identically_zero(potential - expected):
        return Finding(Verdict.INCONSISTENT, f"with e = {sp.sstr(error)} the spring C e^2/2 has stiffness "
                       f"{sp.sstr(sp.cancel(potential / expected))} C on alpha x_m - x_s, not the C of (30)",
                       Evidence(Method.CANONICAL_FORM, facts={"forces": (fm, fs), "printed_form": sp.srepr(potential)}))
    if is_identically_zero(ratio - alpha):
        return Finding(Verdict.CONFIRMED, "with e = alpha x_m - x_s the spring C e^2/2 pulls the master with alpha C e = C_m e and "
                       "the slave with -C e = -C_s e: exactly the controllers (30)", Evidence(Method.CANONICAL_FORM,
                                                                                         facts={"forces": (fm, fs), "printed_form": sp.srepr(potential)}))
    return Finding(Verdict.INCONSISTENT, f"with the printed error the master/slave gain ratio is {ratio}, not alpha as in (30)",
                   Evidence(Method.CANONICAL_FORM, facts={"ids": ["31", "30"], "ratio": ratio}))


@PAPER.equation("32", kind="condition", printed=PRINTED["32"], section="III-A", assumptions=ASSUME,
                derivation="the (29) chain on e = alpha x_m - x_s with (alpha + 1)(alpha |V_m|^2 + |V_s|^2)")
def eq32(ctx: AuditContext) -> Finding:
    return bound_check(ctx, None)


@PAPER.equation("33", kind="expression", printed=PRINTED["33"], section="III-B", assumptions=ASSUME,
                derivation="sympy.physics.control.backward_diff of K + Bs")
def eq33(ctx: AuditContext) -> Finding:
    (rel,) = relations_of(ctx.statement)
    if tuple(rel.terms[:-1]) != (CONTROLLERS["C_s"](Z_SYM), CONTROLLERS["C_m"](Z_SYM)):
        return Finding(Verdict.TYPO, f"(33) must give both controllers, C_s(z) = C_m(z) = ...; it reads "
                       f"{' = '.join(map(sp.sstr, rel.terms[:-1]))} = ...",
                       Evidence(Method.PARSE, facts={"printed_form": [sp.srepr(x) for x in rel.terms[:-1]]}))
    return compare_expressions(rel.terms[-1], telemodel.discretize_pd("backward"),
                               what="the PD controller (33)", note="it is the backward-difference discretisation of K + Bs")


@PAPER.equation("33-bilinear", kind="claim", after="33", section="III-B",
                printed="a PD controller K + Bs, which can be discretized using bilinear transformation method as (33)",
                derivation="sympy.physics.control.bilinear of K + Bs vs (33)", quotes=('33',))
def bilinear_claim(ctx: AuditContext) -> Finding:
    (rel,) = relations_of(parse_with(ctx, TABLE, PAPER.get("33").printed))
    finding = compare_expressions(rel.terms[-1], telemodel.discretize_pd("bilinear"), what="(33)", on_mismatch=Verdict.WRONG)
    if finding.verdict == Verdict.CONFIRMED:
        return finding
    backward = compare_expressions(rel.terms[-1], telemodel.discretize_pd("backward"), what="(33)")
    return Finding(
        Verdict.WRONG,
        "the bilinear (Tustin) transform of K + Bs is K + 2B(z - 1)/(T(z + 1)), not (33); (33) is the backward difference "
        f"s -> (z - 1)/(Tz) ({backward.verdict.value} against sympy's backward_diff), the controller all results (34)-(35) use",
        finding.evidence,
        derived=telemodel.discretize_pd("bilinear"),
        corrected=r"C_s(z) = C_m(z) = K + B\frac{z-1}{Tz} \ \text{(backward difference } s \to \frac{z-1}{Tz}\text{)}",
    )


def _in_c(relation: sp.Basic) -> sp.Basic:
    return relation.func(omega_to_c(relation.lhs, omega, T), omega_to_c(relation.rhs, omega, T), evaluate=False)


@PAPER.equation("34", kind="condition", printed=PRINTED["34"], section="III-B", assumptions=ASSUME,
                derivation="(29) for the PD controller (33): teleoperator.bounds, exact in c")
def eq34(ctx: AuditContext) -> Finding:
    bound = tele.bounds(telemodel.TeleoperatorScene.pd()).master
    return compare_bounds(_in_c(ctx.relation()), sp.Ge(b, bound), b, what="the PD bound at one frequency")


@PAPER.equation("34-min", kind="claim", after="34", section="III-B",
                printed="where b is the minimum of b_s and b_m",
                derivation="b_m > X and b_s > X iff min(b_m, b_s) > X; the error coordinate's series damping")
def min_claim(ctx: AuditContext) -> Finding:
    grid = [sp.Rational(v, 4) for v in range(0, 9)]
    agree = all(
        (bool(x > X) and bool(y > X)) == bool(min(x, y) > X) for x in grid for y in grid for X in grid
    )
    series = tele.error_coordinate_damping(telemodel.TeleoperatorScene.pd())
    if not agree:  # pragma: no cover - elementary logic
        return Finding(Verdict.WRONG, "min does not capture both conditions", Evidence(Method.INSTANCES))
    return Finding(Verdict.CONFIRMED, "both per-robot conditions hold iff the smaller damping exceeds the bound (the least "
                   "damping the robots give the error coordinate is the series value b_m b_s/(b_m + b_s); twice it, the "
                   "harmonic mean, is >= min(b_m, b_s), so using it instead of the minimum is sufficient and less conservative)",
                   Evidence(Method.INSTANCES, instances=len(grid) ** 3, facts={"series_damping": series}))


@PAPER.equation("35", kind="condition", printed=PRINTED["35"], section="III-B", assumptions=ASSUME,
                derivation="exact worst case over c of (34): endpoint c = -1 for B >= 0")
def eq35(ctx: AuditContext) -> Finding:
    """(35) against the exact PD condition ``K >= 0`` and ``h = b_m b_s/(b_m + b_s) >= KT/2 + |B|``
    (:func:`hapticproof.analysis.teleoperator.exact_condition`): for equal robots ``b_m = b_s = b``
    that is ``b >= KT + 2B`` (``K > 0``, ``B >= 0``); with ``b = min(b_m, b_s)`` (the text after
    (34)) the printed condition is sufficient (``h >= min/2``) but not necessary."""
    wc = tele.worst_case(telemodel.TeleoperatorScene.pd())
    equal = tele.exact_condition(telemodel.TeleoperatorScene.pd(b_m=b, b_s=b))
    first = compare_bounds(ctx.relation(), equal, b, what="the PD worst case for equal robots (b_m = b_s = b)",
                           note=f"maximiser c = {wc.maximiser}; for B < 0 it would be KT + 2|B|")
    if first.verdict != Verdict.CONFIRMED:
        return first
    third = sp.Rational(1, 3)
    split = telemodel.TeleoperatorScene.pd(K=2, B=0, T=third, b_m=10, b_s=sp.Rational(3, 7))
    smaller = min(split.b_m, split.b_s)
    printed_holds = bool(ctx.relation().subs({b: smaller, K: 2, B: 0, T: third}))
    passive = tele.passivity(split)
    if printed_holds or passive.decision.value != "proved":        # pragma: no cover - the theorem says otherwise
        return first
    return Finding(
        Verdict.CONSERVATIVE,
        f"{first.detail}; with b = min(b_m, b_s) as the text says it is sufficient (the exact condition is h = b_m b_s/"
        "(b_m + b_s) >= KT/2 + B with K >= 0, and h >= min(b_m, b_s)/2) but not necessary: K = 2, B = 0, T = 1/3, "
        "b_m = 10, b_s = 3/7 is passive (h = 30/73 >= 1/3, exact decision) while min(b_m, b_s) = 3/7 < KT + 2B = 2/3",
        Evidence(Method.COUNTEREXAMPLE, witness={"K": "2", "B": "0", "T": "1/3", "b_m": "10", "b_s": "3/7"},
                 facts={**first.evidence.facts, "passive": passive.to_json()}),
        derived=first.derived)


@PAPER.equation("35-colgate", kind="claim", after="35", section="III-B",
                printed="the passivity condition (35) for the teleoperation system with equal PD controllers (33) for the master "
                        "and the slave has coincided with the passivity condition for a system involving haptic interaction with "
                        "a discretely-simulated virtual wall as investigated by Colgate and Schenkel [7]",
                derivation="(35) vs Colgate's virtual-wall condition derived by classics.colgate_wall", quotes=('35',))
def colgate_claim(ctx: AuditContext) -> Finding:
    p35 = ctx.parse(PAPER.get("35").printed).relations()[0].as_sympy()
    colgate = classics.colgate_wall(B=B)
    from hapticproof.audit.compare import NotABound, as_lower_bound

    try:
        bound35 = as_lower_bound(p35, b)
    except NotABound as err:
        return Finding(Verdict.INCONSISTENT, f"(35) reads {bound_reading(p35)}: not a lower bound on b ({err.reason}), so it "
                       f"cannot coincide with Colgate and Schenkel's condition {sp.sstr(colgate)}",
                       Evidence(Method.CANONICAL_FORM, facts={"printed_form": sp.srepr(p35)}))
    cmp = compare_bounds(colgate, sp.Ge(b, bound35.bound), b, what="Colgate's condition as a condition for (35)")
    doubled = classics.colgate_wall(K=2 * K, B=2 * B)
    facts = {"ids": ["teleoperator:35", "hve:3", "classics:colgate-wall"], "colgate": colgate,
             "colgate_doubled_gains": doubled, "printed_35": sp.sstr(p35)}
    if cmp.verdict == Verdict.CONFIRMED:
        return Finding(Verdict.CONFIRMED, f"(35), {sp.sstr(p35)}, is Colgate's condition {sp.sstr(colgate)}", cmp.evidence)
    twice = compare_bounds(p35, sp.Ge(doubled.lhs, doubled.rhs), b, what="(35) as Colgate's condition for 2K, 2B")
    if twice.verdict == Verdict.CONFIRMED:
        return Finding(
            Verdict.INCONSISTENT,
            f"(35) {sp.sstr(p35)} is Colgate & Schenkel's condition {sp.sstr(colgate)} (HVE (3)) for the doubled wall "
            f"2K + 2B(z-1)/(Tz) ({sp.sstr(doubled)}), which is what the error coordinate of two equal robots sees, not "
            f"Colgate's condition itself: {cmp.detail}",
            Evidence(Method.COUNTEREXAMPLE, witness=cmp.evidence.witness, facts=facts), derived=colgate)
    return Finding(
        Verdict.INCONSISTENT,
        f"(35) {sp.sstr(p35)} is neither Colgate & Schenkel's condition {sp.sstr(colgate)} (HVE (3)) nor Colgate's "
        f"condition for the doubled wall ({sp.sstr(doubled)}): {cmp.detail}",
        Evidence(Method.COUNTEREXAMPLE, witness=cmp.evidence.witness, facts=facts), derived=colgate)


@PAPER.equation("35-monotone", kind="claim", after="35", section="III-B",
                printed="Condition (35) implies that increasing the sampling time and controller gains drive the teleoperator "
                        "closer to non-passivity",
                derivation="derivatives of the worst-case bound KT + 2B")
def monotone(ctx: AuditContext) -> Finding:
    (rel,) = ctx.parse(PAPER.get("35").printed).relations()
    try:
        condition = as_bound(rel.as_sympy(), b)
    except NotABound as exc:
        return Finding(Verdict.UNDECIDED, f"(35) is not a bound on b: {exc}", Evidence(Method.PARSE))
    if not condition.lower:
        return Finding(Verdict.WRONG, f"(35) reads {condition}, an upper bound on b: larger K, B, T do not require more "
                       "damping by it", Evidence(Method.STRUCTURAL, facts={"condition": str(condition)}))
    bound = condition.bound
    slopes = {str(v): sp.diff(bound, v) for v in (K, B, T)}
    if all(sp.sympify(d).is_positive for d in slopes.values()):
        return Finding(Verdict.CONFIRMED, f"the damping (35) requires, {sp.sstr(bound)}, increases with K, B and T (all "
                       "partial derivatives positive)", Evidence(Method.STRUCTURAL, facts={"derivatives": slopes}))
    flat = [v for v, d in slopes.items() if not sp.sympify(d).is_positive]
    return Finding(Verdict.WRONG, f"the damping (35) requires, {sp.sstr(bound)}, does not increase with {', '.join(flat)} "
                   f"(partial derivatives {', '.join(f'{v}: {sp.sstr(slopes[v])}' for v in flat)})",
                   Evidence(Method.STRUCTURAL, facts={"derivatives": slopes}))


def bound_reading(condition: sp.Basic, var: sp.Symbol = b) -> str:
    from hapticproof.audit.compare import NotABound, as_bound

    try:
        return str(as_bound(condition, var))
    except NotABound as err:
        return f"{sp.sstr(condition)} ({err.reason})"
