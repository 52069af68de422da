r"""HVE paper, Section 3.1: the delayed wall (24)-(27), the active operator, and the small-gain
route (28)-(36).
"""

from __future__ import annotations

import functools

import sympy as sp

from hapticproof.audit.runner import AuditContext, malformed
from hapticproof.audit.compare import NotABound, as_bound, as_lower_bound, as_sign_condition, compare_bounds, compare_expressions
from hapticproof.exact.canonical import is_identically_zero
from hapticproof.core.errors import LatexParseError
from hapticproof.core.evidence import Decision, Evidence, Finding, Method, Verdict
from hapticproof.audit.reader.names import SymbolTable
from hapticproof.analysis.positivereal import hermitian, worst_case
from hapticproof.exact.realroots import minimise_rational
from hapticproof.systems.singleuser import SingleUserScene, virtual_wall
from hapticproof.core.symbols import c as C
from hapticproof.core.symbols import z
from hapticproof.exact.unitcircle import canonical_theta
from hapticproof.derivations.hve.paper import ASSUME, B, G_T, H_FUN, K, M_FUN, N_FUN, PAPER, R_FUN, T, TABLE, b, exact_worst, n, omega, s, scene, t_d, verify_worst_case, z_a
from hapticproof.derivations.hve.single_user import reading_of_b


@functools.lru_cache(maxsize=None)
def delay_analysis() -> dict:
    """Exact facts about the worst case of the delayed wall, for the (23)-(27) verdicts."""
    from hapticproof.analysis.delayed import check_dirichlet_identity, small_damping_threshold

    thresholds = {}
    for k in range(1, 5):
        th = small_damping_threshold(k)
        thresholds[k] = th.lo if th.lo == th.hi else (th.lo, th.hi)
    return {"dirichlet_instances": check_dirichlet_identity(12), "kappa": thresholds}


def required_damping(approximation: str, delay: int, values: dict, active: bool):
    """Certified damping needed by a numeric instance: ``b >= z_a - min_c Re G^-1|_{b=0}``."""
    numeric = SingleUserScene.virtual_wall(K=values[K], B=values[B], b=0, T=values[T], approximation=approximation,
                                           delay=delay, z_a=values.get(z_a, 0) if active else 0)
    form = hermitian(numeric).numeric()
    minimum = minimise_rational(form.num, form.den, -1, 1)
    return -minimum.exact if minimum.exact is not None else -minimum.value


def instance_counterexample(printed: sp.Basic, delay: int, values: dict, active: bool) -> dict | None:
    """Parameters where the printed condition holds and the exact worst case fails, re-verified
    by the exact decision (None when the instance does not separate them)."""
    try:
        bound = as_bound(printed.subs(t_d, delay * T).subs(values), b)
    except NotABound:
        return None
    if not bound.lower or not bound.bound.is_Rational:
        return None
    need = required_damping("forward", delay, values, active)
    printed_bound = sp.Rational(bound.bound)
    need_low = need if isinstance(need, sp.Rational) else sp.Rational(need.lower().str(40, radius=False))
    if not need_low > max(printed_bound, 0):
        return None
    witness_b = (max(printed_bound, 0) + need_low) / 2
    point = {**{str(k): v for k, v in values.items()}, "b": witness_b, "n": delay}
    check = verify_worst_case("forward", delay=delay, active=active)({sp.Symbol(k): v for k, v in point.items()})
    if check.decision != Decision.DISPROVED:
        return None
    return {"point": point, "printed_bound": printed_bound, "exact_bound": need if isinstance(need, sp.Rational) else need.str(15),
            "recheck": check.to_json()}


def _delayed_condition_check(ctx: AuditContext, active: bool) -> Finding:
    printed = ctx.relation()
    za = z_a if active else 0
    facts = dict(delay_analysis())
    reading = reading_of_b(printed)
    derived = sp.Ge(b - za, K * T / 2 + K * t_d)
    # B = 0: exact for all n (structural, Dirichlet kernel): b - z_a >= KT/2 + KTn
    at_b0 = compare_bounds(printed.subs(B, 0), derived, b, what="the printed condition at B = 0")
    facts["printed_form"] = at_b0.evidence.facts.get("printed_form")
    if at_b0.verdict != Verdict.CONFIRMED:
        return Finding(at_b0.verdict, f"it reads {reading}; {at_b0.detail}", at_b0.evidence, derived=derived,
                       corrected=at_b0.corrected)
    # small B: the exact worst case is the limit c -> 1, b - z_a + B >= KT/2 + K t_d (n = 1..4)
    small = {}
    for k in range(1, 5):
        limit = hermitian(scene(delay=k, active=active)).expr().subs(C, 1)
        small[k] = compare_bounds(printed.subs(t_d, k * T), sp.Ge(limit, 0), b, what=f"the printed condition at t_d = {k}T")
    off = {k: f for k, f in small.items() if f.verdict != Verdict.CONFIRMED}
    facts["c_to_1_n_1_to_4"] = {k: f.verdict.value for k, f in small.items()}
    facts["printed_form"] = (facts["printed_form"], tuple(repr(f.evidence.facts.get("printed_form")) for f in small.values()))
    if off:
        k0 = min(off)
        return Finding(off[k0].verdict if off[k0].verdict != Verdict.CONFIRMED else Verdict.UNDECIDED,
                       f"it reads {reading}: exact when B = 0, but for small B > 0 it is not the exact worst case (the limit "
                       f"c -> 1, at t_d = {sorted(off)} T): {off[k0].detail}",
                       Evidence(off[k0].evidence.method, witness=off[k0].evidence.witness, facts=facts), derived=derived)
    # B > kappa_1 KT at n = 1: exact worst case by root isolation
    values = {K: sp.Integer(1), T: sp.Integer(1), B: sp.Integer(1)}
    if active:
        values[z_a] = sp.Rational(1, 10)
    counter = instance_counterexample(printed, 1, values, active)
    # t_d = 0: the printed condition becomes b - z_a + B > KT/2, the exact one b - z_a >= KT/2 + B
    at_n0 = compare_bounds(printed.subs(t_d, 0), exact_worst(scene(active=active)), b,
                           verify=verify_worst_case(active=active), what="the printed condition at t_d = 0")
    facts.update({"t_d=0": at_n0.evidence.to_json(), "B=0": at_b0.detail})
    if counter is None:
        return Finding(Verdict.UNDECIDED, f"it reads {reading}, exact for B = 0 and for small B (c -> 1), but the instance "
                       "beyond the small-damping threshold did not refute it", Evidence(Method.INSTANCES, instances=1, facts=facts),
                       derived=derived)
    kappas = ", ".join(str(v) if not isinstance(v, tuple) else f"[{v[0]}, {v[1]}]" for v in facts["kappa"].values())
    facts.update({"printed_bound": counter["printed_bound"], "exact_bound": counter["exact_bound"], "recheck": counter["recheck"]})
    return Finding(
        Verdict.NEEDS_ASSUMPTION,
        f"it reads {reading}: exact when B = 0 for every n (Re G^-1 = b - z_a - KT/2 - KT sum_{{k<=n}} cos k wT + "
        "B cos((n+1) wT) is smallest as c -> 1; identity checked for n = 0..12, the bound on the sum is termwise); for B > 0 "
        "it is the c -> 1 condition (n = 1..4), exact only while B <= kappa_n KT with kappa_n = n(2n+1)/(6(n+1)) (certified "
        f"for n = 1..4: {kappas}) - the paper's 'B small' - and not sufficient beyond that (witness at n = 1: printed "
        f"bound {counter['printed_bound']}, exact {counter['exact_bound']}); at t_d = 0 it is {at_n0.verdict.value} against "
        "the exact condition",
        Evidence(Method.COUNTEREXAMPLE, witness=counter["point"], facts=facts),
        derived=derived,
        corrected=(r"b - z_a > \frac{KT}{2} + Kt_d + B" if active else r"b > \frac{KT}{2} + Kt_d + B")
        + r"\quad (\text{sufficient for all } B \ge 0;\ \text{the printed form is exact iff } B \le \tfrac{n(2n+1)}{6(n+1)} KT)",
    )


@PAPER.equation("24", kind="condition", section="3.1.1",
                printed=r"b + B - \frac{KT}{2} - t_d / T \cos(\omega T/2) > 0",
                assumptions=ASSUME, derivation="(23) in the limit c -> 1 (S -> n)")
def eq24(ctx: AuditContext) -> Finding:
    from hapticproof.audit.reader.printed import slash_readings

    derived_limit = b + B - K * T / 2 - K * t_d
    texts = slash_readings(ctx.equation.printed, PAPER.symbols) or {"as printed": ctx.equation.printed}
    readings = {}
    for name, text in texts.items():
        relations = ctx.parse(text).relations()          # the printed text itself, or a spelled-out reading of it
        if len(relations) != 1:
            raise LatexParseError(f"expected one relation, found {len(relations)}", text, 0)
        readings[name] = as_sign_condition(relations[0].as_sympy())
    # the limit c -> 1 means omega -> 0: cos(omega T/2) -> 1
    values = {name: sp.simplify(c.expr.subs(omega, 0)) for name, c in readings.items()}
    ops = {c.op for c in readings.values()}
    facts = {"printed_limits": values, "derived_limit": derived_limit, "readings": list(texts),
             "printed_form": tuple(sorted((n, c.op, sp.srepr(v)) for (n, c), v in zip(readings.items(), values.values())))}
    if ops <= {">", ">="} and any(is_identically_zero(v - derived_limit) for v in values.values()):
        return Finding(Verdict.CONFIRMED, "equals the c -> 1 limit of (23)", Evidence(Method.CANONICAL_FORM, facts=facts))
    diff = find_point(values, derived_limit)
    how = "; ".join(f"{name}: {sp.sstr(value)} {readings[name].op} 0" for name, value in values.items())
    ambiguous = " (ambiguous slash; both readings tried)" if len(texts) > 1 else ""
    return Finding(
        Verdict.TYPO,
        f"the c -> 1 limit of (23) is b + B - KT/2 - Kt_d > 0; the printed condition{ambiguous} tends to {how}, e.g. "
        f"{sp.sstr(diff['values'][0])} against {sp.sstr(diff['values'][1])} at the witness",
        Evidence(Method.COUNTEREXAMPLE, witness=diff["point"], facts={**facts, "values_at_witness": diff["values"]}),
        derived=sp.Gt(derived_limit, 0),
        corrected=r"b + B - \frac{KT}{2} - Kt_d > 0",
    )


def find_point(readings: dict, derived: sp.Expr) -> dict:
    from hapticproof.audit.compare import find_difference

    first = next(iter(readings.values()))
    found = find_difference(first, derived)
    return {"point": {str(k): v for k, v in found["point"].items()}, "values": found["values"]}


@PAPER.equation("23-worst", kind="claim", after="23", section="3.1.1",
                printed="With the assumption that t_d/T = n and B is small, the worst-case condition will happen if cos(omega T) = 1.",
                derivation="exact minimiser of Re G^-1 over c for B = 0 (all n) and B > 0 (instances)")
def worst_at_one(ctx: AuditContext) -> Finding:
    import re

    facts = dict(delay_analysis())
    quoted = re.search(r"cos\(omega T\) = (-?\d+)", ctx.equation.printed)
    if quoted is None:
        return Finding(Verdict.UNDECIDED, "the claim names no worst-case value of cos(omega T)", Evidence(Method.PARSE))
    claimed = sp.Integer(quoted.group(1))
    # B = 0: the minimiser of Re G^-1 over c for n = 1..4 (exact root isolation)
    at_b0 = {}
    for k in range(1, 5):
        wc0 = worst_case(SingleUserScene.virtual_wall(K=1, B=0, b=10, T=1, delay=k))
        at_b0[k] = wc0.minimiser
    # B small (at kappa_n KT) and B large (n = 1, K = T = B = 1)
    kappa1 = facts["kappa"][1] if not isinstance(facts["kappa"][1], tuple) else facts["kappa"][1][0]
    small = worst_case(SingleUserScene.virtual_wall(K=1, B=kappa1, b=10, T=1, delay=1)).minimiser
    large = worst_case(SingleUserScene.virtual_wall(K=1, B=1, b=2, T=1, delay=1)).minimiser
    undelayed = worst_case(SingleUserScene.virtual_wall(K=1, B=1, b=2, T=1, delay=0)).minimiser
    facts.update({"claimed_c": claimed, "minimiser_B0_n1_4": at_b0, "minimiser_n1_B_kappa1": small,
                  "minimiser_n1_B1": large, "minimiser_n0_B1": undelayed, "printed_form": str(claimed)})
    holds_small = all(v == claimed for v in at_b0.values()) and small == claimed
    if not holds_small:
        return Finding(Verdict.WRONG, f"the worst case is not at cos(omega T) = {claimed} even for small B: the exact "
                       f"minimiser over c is {at_b0} for B = 0 (n = 1..4) and {small} at B = kappa_1 KT (n = 1)",
                       Evidence(Method.ROOT_ISOLATION, witness={"n": 1, "K": 1, "T": 1, "B": 0}, facts=facts))
    if large == claimed and undelayed == claimed:
        return Finding(Verdict.CONFIRMED, f"the exact minimiser is c = {claimed} for B = 0, small and large B",
                       Evidence(Method.ROOT_ISOLATION, facts=facts))
    return Finding(
        Verdict.NEEDS_ASSUMPTION,
        f"true for B = 0 (minimiser c = {claimed} for n = 1..4, and structurally for every n) and for 0 < B <= kappa_n KT "
        f"(kappa_1 = {kappa1}: minimiser {small}); for larger B the minimum moves inside (n = 1, K = T = B = 1: "
        f"minimiser c = {large}) and at n = 0 it is at c = {undelayed} for B > 0",
        Evidence(Method.ROOT_ISOLATION, witness={"n": 1, "K": 1, "T": 1, "B": 1, "c_min": large}, facts=facts),
    )


@PAPER.equation("25", kind="condition", printed=r"b+B > \frac{KT}{2} + Kt_d", section="3.1.1",
                assumptions=ASSUME + "; B small (paper)", derivation="exact worst case of (22) over c")
def eq25(ctx: AuditContext) -> Finding:
    return _delayed_condition_check(ctx, active=False)


@PAPER.equation("27", kind="condition", printed=r"b - z_a + B > Kt_d + \frac{KT}{2}", section="3.1.1",
                assumptions=ASSUME + "; B small (paper)", derivation="exact worst case of (22) with b - z_a")
def eq27(ctx: AuditContext) -> Finding:
    return _delayed_condition_check(ctx, active=True)


@PAPER.equation("26-extends", kind="claim", after="26", section="3.1.1",
                printed="Evidently, the proposed condition (27) extends the condition in [3] by both allowing the operator "
                        "to be active and for the delay to exist, and extends the condition in [7] by allowing the operator to be active.",
                derivation="(27) at z_a = 0, t_d = 0 vs (3); (27) at z_a = 0 vs (5)", quotes=('3',))
def extends(ctx: AuditContext) -> Finding:
    p27 = ctx.parse(PAPER.get("27").printed).relations()[0].as_sympy()
    p3 = ctx.parse(PAPER.get("3").printed).relations()[0].as_sympy()
    reduced = p27.subs({z_a: 0, t_d: 0})
    try:
        reference = as_lower_bound(p3, b)
    except NotABound as err:
        return Finding(Verdict.INCONSISTENT, f"(3) reads {reading_of_b(p3)}: not a lower bound on b ({err.reason}), so (27) at "
                       f"z_a = t_d = 0, {reading_of_b(reduced)}, cannot contain it", Evidence(Method.CANONICAL_FORM,
                       facts={"ids": ["27", "3"], "reduced": reduced}))
    vs3 = compare_bounds(reduced, sp.Ge(b, reference.bound), b, what="(27) at z_a = 0, t_d = 0")
    facts = {"ids": ["27", "3"], "reduced": reduced, "against_(3)": vs3.verdict.value}
    if vs3.verdict == Verdict.CONFIRMED:
        return Finding(Verdict.CONFIRMED, f"(27) at z_a = t_d = 0 reads {reading_of_b(reduced)}, which is (3)",
                       Evidence(vs3.evidence.method, facts=facts))
    return Finding(
        Verdict.INCONSISTENT,
        f"(27) with z_a = 0 and t_d = 0 reads {reading_of_b(reduced)}, not Colgate's (3) {reading_of_b(p3)}: it does not contain (3) as "
        f"a special case ({vs3.verdict.value} against it; see the witness)",
        Evidence(Method.COUNTEREXAMPLE, witness=vs3.evidence.witness, facts=facts),
        corrected=r"b - z_a > \frac{KT}{2} + Kt_d + B \ \text{reduces to (3) at } z_a = t_d = 0",
    )


BETA = b - z_a


G_sym, N_sym, M_sym = sp.Symbol("G_T"), sp.Symbol("N"), sp.Symbol("M")


# (29) and (32) use the maps M and N as operands; they are read as plain symbols there.
OPERAND_TABLE = SymbolTable(
    symbols={**dict(TABLE.symbols), r"\mathscr{M}": M_sym, r"\mathscr{N}": N_sym, r"\mathcal{MN}": M_sym * N_sym},
    functions={name: f for name, f in TABLE.functions.items() if "M" not in name and "N" not in name},
    families=list(TABLE.families.values()),
)


def _derived_r() -> sp.Expr:
    from hapticproof.analysis.smallgain import region_factor

    return region_factor(omega, T, t_d)


@functools.lru_cache(maxsize=None)
def _derived_M(argument: sp.Expr) -> sp.Expr:
    from hapticproof.analysis.smallgain import disk_map

    return disk_map(G_T(argument), R_FUN(argument), BETA)


@functools.lru_cache(maxsize=None)
def _derived_N(argument: sp.Expr) -> sp.Expr:
    from hapticproof.analysis.smallgain import lft_partner

    return lft_partner(_derived_M(argument), G_T(argument), H_FUN(sp.exp(argument * T))).subs(G_sym, G_T(argument))


@PAPER.equation("28", kind="expression", section="3.1.2",
                printed=r"r(j\omega) = e^{-j\omega t_d} \frac{T}{2} \frac{e^{-j\omega T} - 1}{1 - \cos(\omega T)}",
                assumptions="t_d an integer multiple of T",
                derivation="convex hull of R_1 weighted by sum_k 1/(w + k w_s)^2 = T^2/(2(1 - cos wT)) (checked with mpmath)")
def eq28(ctx: AuditContext) -> Finding:
    from hapticproof.analysis.smallgain import check_weights_sum

    relation = ctx.relation()
    if not isinstance(relation, sp.Eq) or relation.lhs != R_FUN(sp.I * omega):
        return Finding(Verdict.TYPO, f"the display reads {sp.sstr(relation)}: not r(jw) = ...",
                       Evidence(Method.PARSE, facts={"printed_form": sp.srepr(relation)}))
    finding = compare_expressions(relation.rhs, _derived_r(), what="the printed r(jw)")
    error = check_weights_sum(4)
    return Finding(finding.verdict, finding.detail + f"; the weight-sum identity agrees with a direct 30-digit sum to {error:.1e}",
                   Evidence(finding.evidence.method, witness=finding.evidence.witness,
                            facts={**dict(finding.evidence.facts), "weights_sum_relative_error": error}),
                   derived=finding.derived, corrected=finding.corrected)


@PAPER.equation("29", kind="condition", printed=r"\|\mathscr{M}\mathscr{N}\|_{\infty} < 1", section="3.1.2",
                derivation="small-gain theorem for 1 + MN = 0 with M mapping the region of G_T^* into the unit disk")
def eq29(ctx: AuditContext) -> Finding:
    from hapticproof.audit.reader.statements import Norm
    from hapticproof.audit.reader.printed import parse_printed
    from hapticproof.analysis.smallgain import disk_identity

    relations = parse_printed(ctx.equation.printed, OPERAND_TABLE).relations()
    if len(relations) != 1:
        return malformed(ctx, f"expected one relation, found {len(relations)}")
    relation = relations[0].as_sympy()
    norm = relation.lhs
    form = sp.srepr(relation)
    if not (isinstance(relation, sp.StrictLessThan) and isinstance(norm, Norm) and is_identically_zero(norm.arg - M_sym * N_sym)
            and norm.order == sp.oo and relation.rhs == 1):
        return Finding(Verdict.WRONG, f"not the small-gain condition ||MN||_inf < 1: the display reads {sp.sstr(relation)}",
                       Evidence(Method.PARSE, facts={"printed_form": form}))
    # |M| <= 1 on the region: M = 2 beta (G/r - rho) and G/r in the disk |y - rho| <= rho, with
    # R_1 the Moebius image of Re p >= 0 (identity |beta+p|^2 - |beta-p|^2 = 4 beta Re p)
    if disk_identity() != 0 or not is_identically_zero(_derived_M(s) - (2 * BETA * G_T(s) / R_FUN(s) - 1)):
        return Finding(Verdict.WRONG, "M does not map the region of G_T^* into the unit disk", Evidence(Method.STRUCTURAL))
    return Finding(Verdict.CONFIRMED,
                   "the infinity-norm small-gain condition on the loop MN; M maps the region r R_1 of G_T^* onto the closed "
                   "unit disk (so |N| < 1 suffices, eq. 35)",
                   Evidence(Method.STRUCTURAL, facts={"disk_identity": disk_identity(), "printed_form": form}))


def _m_check(ctx: AuditContext) -> Finding:
    relation = ctx.relation()
    if not isinstance(relation, sp.Eq) or relation.lhs != M_FUN(s, G_T(s)):
        return Finding(Verdict.TYPO, f"the display reads {sp.sstr(relation)}: not M{{s, G_T^*(s)}} = ...",
                       Evidence(Method.PARSE, facts={"printed_form": sp.srepr(relation)}))
    return compare_expressions(relation.rhs, _derived_M(s), what="the printed M{s, G_T^*}")


def _n_check(ctx: AuditContext) -> Finding:
    derived = _derived_N(s)
    error = ctx.parse_error
    printed_text = ctx.equation.printed
    note = ""
    corrected = r"\mathcal{N}\{s, G_T^*(s)\} = \frac{r(s)H(e^{sT})}{2(b-z_a) + r(s)H(e^{sT})}"
    if error is not None:
        repaired = printed_text.replace("r(s)H(s))}", "r(s)H(s)}")
        note = f"the display has an unbalanced ')' ({error.reason} at position {error.position}; removed to read it)"
        relations = ctx.parse(repaired).relations()
    else:
        relations = ctx.statement.relations()
    if len(relations) != 1:
        return malformed(ctx, f"expected one relation, found {len(relations)}")
    relation = relations[0].as_sympy()
    form = sp.srepr(relation)
    if not isinstance(relation, sp.Eq) or relation.lhs != N_FUN(s, G_T(s)):
        return Finding(Verdict.TYPO, f"the display reads {sp.sstr(relation)}: not N{{s, G_T^*(s)}} = ...",
                       Evidence(Method.PARSE, facts={"printed_form": form}), derived=derived, corrected=corrected)
    printed = relation.rhs
    if is_identically_zero(printed - derived):
        return Finding(Verdict.CONFIRMED if not note else Verdict.TYPO, "N equals the derived partner" + (f"; {note}" if note else ""),
                       Evidence(Method.CANONICAL_FORM, facts={"printed_form": form}), derived=derived,
                       corrected=corrected if note else None)
    # witness: any environment with H(s) != H(e^{sT}); take H(z) = z, r = 1, beta = 1, s = 1
    values = {H_FUN: sp.Lambda(z, z), R_FUN: sp.Lambda(s, 1)}
    point = {s: 1, T: 1, b: 1, z_a: 0}
    pv = sp.simplify(printed.subs(values).subs(point))
    dv = sp.simplify(derived.subs(values).subs(point))
    slip = is_identically_zero(printed.subs(H_FUN(s), H_FUN(sp.exp(s * T))) - derived)
    cause = ("the printed denominator has H(s) instead of H(e^{sT})" if slip else
             f"the printed N differs from it ({compare_expressions(printed, derived).detail})")
    return Finding(
        Verdict.TYPO,
        f"N = rH(e^{{sT}})/(2(b - z_a) + rH(e^{{sT}})) solves 1 + MN = 0 <=> 1 + H G_T^* = 0; {cause}: with H(z) = z, r = 1, "
        f"s = T = b = 1, z_a = 0 the printed N is {sp.sstr(pv)}, the derived {sp.sstr(dv)}" + (f" ({note})" if note else ""),
        Evidence(Method.COUNTEREXAMPLE, witness={"H(z)": "z", "r": 1, "s": 1, "T": 1, "b": 1, "z_a": 0},
                 facts={"printed_value": pv, "derived_value": dv, "printed_form": form}),
        derived=derived,
        corrected=corrected,
    )


for _id, _printed in (("30", r"\mathscr{M}\{s, G_T^*(s)\} = -1 + \frac{2(b - z_a)}{r(s)} G_T^*(s)"),
                      ("33", r"\mathscr{M}\{s, G_T^*(s)\} = -1 + \frac{2(b-z_a)}{r(s)}G_T^*(s)")):
    PAPER.equation(_id, kind="expression", printed=_printed, section="3.1.2",
                   derivation="affine map of the disk r R_1 (centre r/(2(b - z_a)), radius |r|/(2(b - z_a))) onto the unit disk")(_m_check)


for _id, _printed in (("31", r"\mathcal{N}\{s, G_T^*(s)\} = \frac{r(s)H(e^{sT})}{2(b-z_a) + r(s)H(s))}"),
                      ("34", r"\mathscr{N}\{s, G_T^*(s)\} = \frac{r(s)H(e^{sT})}{2(b-z_a) + r(s)H(s))}")):
    PAPER.equation(_id, kind="expression", printed=_printed, section="3.1.2",
                   derivation="N from 1 + MN = 0 <=> 1 + H(e^{sT}) G_T^*(s) = 0")(_n_check)


@PAPER.equation("32", kind="condition", printed=r"1 + \mathcal{MN} = 0", section="3.1.2",
                derivation="1 + MN with the derived M and N equals 2(b - z_a)(1 + H G_T^*)/(2(b - z_a) + rH)")
def eq32(ctx: AuditContext) -> Finding:
    from hapticproof.audit.reader.printed import parse_printed

    relation = parse_printed(ctx.equation.printed, OPERAND_TABLE).relations()[0].as_sympy()
    printed = relation.lhs - relation.rhs
    HsT = H_FUN(sp.exp(s * T))
    substituted = printed.subs({M_sym: _derived_M(s), N_sym: _derived_N(s)})
    target = 2 * BETA * (1 + HsT * G_T(s)) / (2 * BETA + R_FUN(s) * HsT)
    return compare_expressions(substituted, target, what="1 + MN with the derived M, N",
                               note="it vanishes exactly where 1 + H G_T^* does (the factor 2(b - z_a) + rH is finite there)")


@PAPER.equation("35", kind="condition", section="3.1.2",
                printed=r"\left|\frac{r(j\omega)H(e^{\ell}j\omega T)}{2(b-z_a)+r(j\omega)H(e^{j\omega T})}\right| < 1",
                derivation="|N(jw)| < 1 with N = rH/(2(b - z_a) + rH)")
def eq35(ctx: AuditContext) -> Finding:
    derived = sp.Abs(_derived_N(sp.I * omega))
    note = ""
    if ctx.parse_error is not None:
        note = (f"the printed H(e^{{\\ell}} j w T) does not parse ({ctx.parse_error.reason} at position "
                f"{ctx.parse_error.position}); read as H(e^{{j w T}})")
        relations = ctx.parse(ctx.equation.printed.replace(r"e^{\ell}j\omega T", r"e^{j\omega T}")).relations()
    else:
        relations = ctx.statement.relations()
    if len(relations) != 1:
        return malformed(ctx, f"expected one relation, found {len(relations)}")
    relation = relations[0].as_sympy()
    if not (isinstance(relation, sp.StrictLessThan) and relation.rhs == 1):
        return Finding(Verdict.WRONG, f"not the small-gain condition |N(jw)| < 1: the display reads {sp.sstr(relation)}",
                       Evidence(Method.PARSE, facts={"printed_form": sp.srepr(relation)}), derived=sp.Lt(derived, 1))
    finding = compare_expressions(relation.lhs, derived, what="the printed |N(jw)|")
    if finding.verdict == Verdict.CONFIRMED and note:
        return Finding(Verdict.TYPO, f"|N(jw)| < 1 as derived; {note} (OCR damage)",
                       Evidence(Method.PARSE, facts={"reading": "H(e^{jwT})", "printed_form": sp.srepr(relation)}),
                       derived=sp.Lt(derived, 1),
                       corrected=r"\left|\frac{r(j\omega)H(e^{j\omega T})}{2(b-z_a)+r(j\omega)H(e^{j\omega T})}\right| < 1")
    return finding


def _rhs36_canonical(expr: sp.Expr) -> sp.Expr:
    """Canonical theta-form of an expression with H the virtual wall."""
    wall = sp.Lambda(z, virtual_wall(K, B, T))
    expanded = sp.expand_complex(expr.subs(H_FUN, wall).rewrite(sp.cos))
    return canonical_theta(expanded, omega, T, t_d, n)


@PAPER.equation("36", kind="condition", section="3.1.2",
                printed=r"b - z_a > \frac{T}{2} \frac{1}{1 - \cos(\omega T)} \Re\{e^{-j\omega t_d} (1 - e^{-j\omega T}) H(e^{j\omega T})\}",
                derivation="|w| < |2 beta + w| <=> beta + Re w > 0 with w = rH (and -r written out)")
def eq36(ctx: AuditContext) -> Finding:
    from hapticproof.analysis.smallgain import small_gain_margin

    relation = ctx.relation()
    derived_bound = z_a - sp.re(_derived_r() * H_FUN(sp.exp(sp.I * omega * T)))
    try:
        bound = as_bound(relation, b)
    except NotABound as err:
        return Finding(Verdict.WRONG, f"the display is not a lower bound on b ({err.reason}): {sp.sstr(relation)}",
                       Evidence(Method.PARSE, facts={"printed_form": sp.srepr(relation)}), derived=sp.Gt(b, derived_bound))
    if not bound.lower:
        return Finding(Verdict.WRONG, f"the display is an upper bound, {bound}, where |N(jw)| < 1 needs b - z_a > -Re(rH)",
                       Evidence(Method.PARSE, facts={"printed_form": str(bound)}), derived=sp.Gt(b, derived_bound))
    # |N| < 1 <=> beta + Re(rH) > 0: the margin identity
    x_, y_ = sp.symbols("x y", real=True)
    identity = sp.simplify(small_gain_margin(BETA, x_ + sp.I * y_) - 4 * BETA * (BETA + x_))
    difference = sp.simplify(_rhs36_canonical(bound.bound) - _rhs36_canonical(derived_bound))
    if identity != 0 or difference != 0:
        return Finding(Verdict.WRONG, f"the bound b > {sp.sstr(bound.bound)} differs from z_a - Re(rH) by {sp.sstr(difference)} "
                       "(canonical theta-form, virtual wall)",
                       Evidence(Method.CANONICAL_FORM, facts={"difference": difference, "printed_form": sp.srepr(bound.bound)}))
    return Finding(Verdict.CONFIRMED,
                   "equivalent to |N(jw)| < 1 (|2 beta + w|^2 - |w|^2 = 4 beta (beta + Re w)); the right side equals -Re(r H) "
                   "identically for every integer n (virtual wall, canonical theta-form)",
                   Evidence(Method.CANONICAL_FORM, facts={"margin_identity": identity, "difference": difference}),
                   derived=sp.Gt(b, derived_bound))


@PAPER.equation("36-agree", kind="claim", after="36", section="3.1",
                printed="It is shown that both methods result in the same stability conditions for single-user HVE systems.",
                derivation="b - z_a - RHS(36) vs Re G^-1 (forward difference, delay n, active operator), identity", quotes=('36',))
def methods_agree(ctx: AuditContext) -> Finding:
    printed36 = ctx.parse(PAPER.get("36").printed).relations()[0].as_sympy()
    try:
        bound36 = as_bound(printed36, b)
    except NotABound as err:
        return Finding(Verdict.INCONSISTENT, f"(36) is not a lower bound on b ({err.reason}); the circle criterion gives "
                       "Re G^-1 >= 0", Evidence(Method.CANONICAL_FORM, facts={"ids": ["36"]}))
    if not bound36.lower:
        return Finding(Verdict.INCONSISTENT, f"(36) is an upper bound, {bound36}; the circle criterion gives a lower bound",
                       Evidence(Method.CANONICAL_FORM, facts={"ids": ["36"]}))
    rhs = bound36.bound - z_a
    small_gain = sp.expand(_rhs36_canonical(b - z_a - rhs))
    circle = hermitian(scene(delay=n, active=True)).canonical()
    if not is_identically_zero(small_gain - circle):
        gap = sp.expand(small_gain - circle)
        return Finding(Verdict.INCONSISTENT, f"the small-gain condition (36) and Re G^-1 >= 0 differ by {sp.sstr(gap)} in the "
                       "canonical theta-form", Evidence(Method.CANONICAL_FORM, facts={"difference": gap, "ids": ["36"]}))
    # general H: 1/(z - 1) = -(1 - 1/z)/(2(1 - cos wT)) on |z| = 1, checked in canonical variables
    general = canonical_theta(sp.expand_complex((1 / (sp.exp(sp.I * omega * T) - 1)
                                                 + (1 - sp.exp(-sp.I * omega * T)) / (2 * (1 - sp.cos(omega * T)))).rewrite(sp.cos)),
                              omega, T, t_d, n)
    if not is_identically_zero(general):
        return Finding(Verdict.INCONSISTENT, "the unit-circle identity behind the general case fails",
                       Evidence(Method.CANONICAL_FORM, facts={"identity": general}))
    return Finding(Verdict.CONFIRMED,
                   "the small-gain condition (36) and the circle-criterion condition Re G^-1 >= 0 (forward difference, delay n, "
                   "b - z_a) are the same function of w for every integer n; for any H(z) this follows from "
                   "1/(z - 1) = -(1 - z^-1)/(2(1 - cos wT)) on |z| = 1",
                   Evidence(Method.CANONICAL_FORM, facts={"unit_circle_identity": sp.simplify(general)}))


@PAPER.equation("36-reduces", kind="claim", after="36", section="3.1.2",
                printed="For the virtual wall H(z) = K + B(z-1)/(Tz) and assuming that B is small enough, this stability "
                        "condition will again reduce to (27)",
                derivation="(36) is Re G^-1 >= 0 (36-agree); its exact worst case vs (27)", quotes=('27',))
def reduces_to_27(ctx: AuditContext) -> Finding:
    inner = AuditContext(PAPER, PAPER.get("27"))
    finding = _delayed_condition_check(inner, active=True)
    return Finding(finding.verdict, "(36) is Re G^-1 >= 0 at every frequency (see 36-agree), so its worst case is that of (27): "
                   + finding.detail, finding.evidence, derived=finding.derived, corrected=finding.corrected)
