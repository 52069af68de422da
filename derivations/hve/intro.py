r"""HVE paper, introduction: the quoted classic conditions (2), (4), (5) and the claims that (25)
and (36) are "identical to" Gil et al. 2009 ([7]).

Each quote is compared with the classic result *derived* by the toolkit
(:mod:`hapticproof.analysis.classics`, :mod:`hapticproof.analysis.boundary`): the exact ZOH stability boundary of
the device on the wall (with a continuous operator for (2)) and its small-damping expansion.
"""

from __future__ import annotations

import functools

import sympy as sp

from hapticproof.analysis import boundary as bnd
from hapticproof.analysis import classics
from hapticproof.audit.runner import AuditContext
from hapticproof.audit.compare import NotABound, as_bound, compare_bounds
from hapticproof.core.evidence import Evidence, Finding, Method, Verdict
from hapticproof.derivations.hve.paper import PAPER, TABLE


K, B, b, T, t_d, z_a = (TABLE.lookup(name) for name in ("K", "B", "b", "T", "t_d", "z_a"))


b_h, k_h = TABLE.lookup("b_h"), TABLE.lookup("k_h")


def _relation(ctx: AuditContext, eq_id: str) -> sp.Basic:
    return ctx.parse(PAPER.get(eq_id).printed).relations()[0].as_sympy()


def _linear_delayed() -> sp.Basic:
    """Gil et al. 2009 derived: b + B > K(T/2 + t_d) (leading order of the exact boundary)."""
    cond = classics.gil_linear_condition(classics.SYMBOLS["n"])
    return sp.Gt(cond.lhs, cond.rhs, evaluate=False)


def reading_of_b(condition: sp.Basic) -> str:
    """What a printed condition says about b (for details built from the display)."""
    try:
        return str(as_bound(condition, b))
    except NotABound as err:
        return f"{sp.sstr(condition)} ({err.reason})"


def _holds(condition: sp.Basic, values: dict) -> bool | None:
    value = condition.subs(values)
    return bool(value) if value in (sp.true, sp.false) else None


@functools.lru_cache(maxsize=1)
def _operator_instances() -> dict:
    """Certified decisions of the ZOH loop with the operator at two damping levels (m = 1, b = 1,
    T = 0.01, m_h = b_h = k_h = 0.001): independent of any printed text."""
    op = bnd.Operator(sp.Rational(1, 1000), sp.Rational(1, 1000), sp.Rational(1, 1000))
    out = {}
    for name, (Bv, Kv) in {"moderate_B": (1, 398), "large_B": (300, 1)}.items():
        point = {"m": 1, "b": 1, "T": sp.Rational(1, 100), "B": Bv, "K": Kv}
        outcome = bnd.certified_stable(point["m"], point["b"], point["T"], Kv, Bv, 0, op)
        out[name] = {"point": {**point, "m_h": op.mass, "b_h": op.damping, "k_h": op.stiffness},
                     "values": {B: Bv, b: 1, b_h: op.damping, K: Kv, k_h: op.stiffness, T: point["T"]},
                     "decision": outcome.decision.value, "spectral_radius": outcome.evidence.facts["spectral_radius"]}
    return out


@PAPER.equation("2", kind="condition", printed=r"B+b+b_h > \frac{(K+k_h)T}{2}", section="1",
                assumptions="operator m_h s + b_h + k_h/s attached to the device; b, K, T > 0; B >= 0",
                derivation="exact ZOH loop with the operator (certified spectral radius) and its small-damping expansion")
def eq2(ctx: AuditContext) -> Finding:
    printed = ctx.relation()
    leading = classics.leading_order_boundary(0, operator=True).condition      # B + b + b_h > K T/2
    leading = sp.Gt(leading.lhs, sp.expand(leading.rhs), evaluate=False)
    against_leading = compare_bounds(printed, sp.Ge(leading.lhs, leading.rhs), b, what="(2)")
    reading = reading_of_b(printed)
    facts: dict = {"leading_order": leading, "against_leading_order": against_leading.verdict.value,
                   "printed_form": against_leading.evidence.facts.get("printed_form")}
    if against_leading.verdict not in (Verdict.CONFIRMED, Verdict.CONSERVATIVE):
        return Finding(against_leading.verdict,
                       f"(2) reads {reading}, which is not even sufficient at the leading order b + b_h + B > KT/2 of the "
                       f"exact ZOH loop with the operator: {against_leading.detail}",
                       Evidence(against_leading.evidence.method, witness=against_leading.evidence.witness,
                                facts={**facts, **dict(against_leading.evidence.facts)}),
                       derived=leading, corrected=r"B + b + b_h > \frac{KT}{2} \ \text{(leading order; small } B\text{)}")
    instances = _operator_instances()
    holding = {name: _holds(printed, inst["values"]) for name, inst in instances.items()}
    unstable = [name for name, inst in instances.items() if holding[name] and inst["decision"] == "disproved"]
    facts["certified"] = {name: {"point": inst["point"], "printed_holds": holding[name], "decision": inst["decision"],
                                 "spectral_radius": inst["spectral_radius"]} for name, inst in instances.items()}
    margin = sp.simplify(as_bound(printed, b).bound - as_bound(sp.Ge(leading.lhs, leading.rhs), b).bound)
    if not unstable:
        return Finding(Verdict.UNDECIDED,
                       f"(2) reads {reading} ({against_leading.verdict.value} against the leading order, margin "
                       f"{sp.sstr(margin)}); it fails at the certified unstable loops tried, and its sufficiency beyond the "
                       "leading order was not settled",
                       Evidence(Method.INSTANCES, instances=len(instances), facts=facts), derived=leading)
    where = ", ".join(f"(B, K) = ({instances[n]['point']['B']}, {instances[n]['point']['K']}) "
                      f"[rho = {instances[n]['spectral_radius'][:8]}]" for n in unstable)
    return Finding(
        Verdict.NEEDS_ASSUMPTION,
        f"(2) reads {reading}; the exact ZOH loop with the operator has the leading-order boundary b + b_h + B > KT/2 "
        f"(the continuous hand spring k_h drops out at this order), so (2) is that condition with the extra margin "
        f"{sp.sstr(margin)} ({against_leading.verdict.value} against it) and holds only for small virtual damping: it is "
        f"satisfied by certified unstable loops at m = 1, b = 1, T = 0.01, m_h = b_h = k_h = 0.001 with {where}",
        Evidence(Method.COUNTEREXAMPLE, witness=instances[unstable[0]]["point"], facts=facts),
        derived=leading,
        corrected=r"B + b + b_h > \frac{KT}{2} \ \text{(leading order; small } B\text{)}",
    )


@PAPER.equation("4", kind="condition", printed=r"b+B > \frac{KT}{2}", section="1",
                assumptions="b, K, T > 0; B >= 0 ('valid only for low values of B', as the text says)",
                derivation="exact ZOH stability boundary (Jury, closed form) and its small-damping expansion")
def eq4(ctx: AuditContext) -> Finding:
    from hapticproof.derivations.teleoperator.claims import routh_finding

    return routh_finding(ctx.relation(), "Gil et al.'s condition (4)")


#: The paper's Fig. 8b loop (Section 4): m = 0.15, b = 0.2, T = 1 ms, t_d = 10T, B = 0.
FIG8B = {"m": sp.Rational(15, 100), "b": sp.Rational(2, 10), "T": sp.Rational(1, 1000), "n": 10, "B": 0}


@functools.lru_cache(maxsize=1)
def _fig8b_critical():
    return bnd.critical_stiffness(FIG8B["m"], FIG8B["b"], FIG8B["T"], FIG8B["B"], FIG8B["n"])


def _stiffness_limit(condition: sp.Basic, values: dict) -> sp.Expr | None:
    """The largest K a condition allows at numeric values of the other parameters (None if it
    is not an upper bound on K there)."""
    try:
        bound = as_bound(condition.subs(values), K)
    except NotABound:
        return None
    return None if bound.lower else bound.bound


@PAPER.equation("5", kind="condition", printed=r"K < \frac{B+b}{T+t_d}", section="1",
                assumptions="b, K, T > 0; B >= 0 small; t_d = nT",
                derivation="small-damping expansion of the exact delayed ZOH boundary: K (T/2 + t_d) < b + B")
def eq5(ctx: AuditContext) -> Finding:
    printed = ctx.relation()
    derived = _linear_delayed()
    cmp = compare_bounds(printed, sp.Ge(derived.lhs, derived.rhs), b, what="(5)")
    if cmp.verdict == Verdict.CONFIRMED:
        return cmp
    reading = reading_of_b(printed)
    # the slip the quote suggests: T where Gil et al. have T/2 (derived condition with T/2 -> T)
    half_slip = sp.Gt(derived.lhs, derived.rhs.subs(T, 2 * T), evaluate=False)
    is_half_slip = compare_bounds(printed, sp.Ge(half_slip.lhs, half_slip.rhs), b).verdict == Verdict.CONFIRMED
    try:
        at_zero = printed.subs(t_d, 0)
        vs4_verdict = compare_bounds(at_zero, sp.Ge(b + B, K * T / 2), b).verdict.value
    except TypeError:           # the printed bound divides by t_d: no condition at t_d = 0
        at_zero, vs4_verdict = sp.S.false, "undefined at t_d = 0"
    values = {b: FIG8B["b"], B: FIG8B["B"], T: FIG8B["T"], t_d: FIG8B["n"] * FIG8B["T"]}
    printed_K = _stiffness_limit(printed, values)
    derived_K = _stiffness_limit(derived, values)
    crit = _fig8b_critical()
    numbers = {"exact_K*": crit.K.str(12), "derived_linear": derived_K, "printed_(5)": printed_K}
    loop = ("for the paper's Fig. 8b loop (m = 0.15, b = 0.2, T = 1 ms, t_d = 10T) it gives "
            + (f"K < {float(printed_K):.2f}" if printed_K is not None else "no upper limit on K")
            + f" against the derived {float(derived_K):.2f} and the exact {float(crit.value):.2f}")
    evidence = Evidence(Method.COUNTEREXAMPLE, witness=cmp.evidence.witness,
                        facts={"comparison_with_derived": cmp.verdict.value, "at_t_d_0_vs_(4)": vs4_verdict,
                               "printed_form": cmp.evidence.facts.get("printed_form"), **numbers})
    corrected = r"K < \frac{B+b}{\frac{T}{2}+t_d}"
    if is_half_slip:
        return Finding(
            Verdict.TYPO,
            f"(5) reads {reading}; the delayed linear condition derived from the exact ZOH loop (leading order for every n) "
            f"is K (T/2 + t_d) < b + B, as Gil et al. 2009 publish it, and (5) is exactly that with T for T/2: at t_d = 0 it "
            f"reads {reading_of_b(at_zero)} ({vs4_verdict} against (4), b + B > KT/2); {loop}",
            evidence, derived=derived, corrected=corrected)
    return Finding(cmp.verdict,
                   f"(5) reads {reading}, not the delayed linear condition K (T/2 + t_d) < b + B derived from the exact ZOH "
                   f"loop (Gil et al. 2009): {cmp.detail}; {loop}",
                   evidence, derived=derived, corrected=corrected)


def _identical_to_7(ctx: AuditContext, eq_id: str, reduce: dict) -> Finding:
    mine = _relation(ctx, eq_id).subs(reduce)
    quoted = _relation(ctx, "5")
    derived = _linear_delayed()
    vs_derived = compare_bounds(mine, sp.Ge(derived.lhs, derived.rhs), b, what=f"({eq_id})")
    try:
        reference = _as_lower(quoted)
    except NotABound as err:
        return Finding(Verdict.INCONSISTENT,
                       f"the quote (5) reads {reading_of_b(quoted)}: not a lower bound on b ({err.reason}), so it cannot be the "
                       f"condition ({eq_id}), which reads {reading_of_b(mine)}",
                       Evidence(Method.CANONICAL_FORM, facts={"ids": [eq_id, "5"], "reading": reading_of_b(mine)}),
                       derived=derived)
    vs_quote = compare_bounds(mine, reference, b, what=f"({eq_id}) against (5)")
    facts = {"ids": [eq_id, "5"], "versus_derived": vs_derived.verdict.value, "versus_quote_(5)": vs_quote.verdict.value,
             "reading": reading_of_b(mine), "quote_reading": reading_of_b(quoted)}
    if vs_quote.verdict == Verdict.CONFIRMED:
        return Finding(Verdict.CONFIRMED, f"({eq_id}){' at z_a = 0' if reduce else ''} reads {reading_of_b(mine)}, the same "
                       f"condition as the quote (5), {reading_of_b(quoted)}", Evidence(vs_quote.evidence.method, facts=facts))
    gap = ""
    try:
        gap = f" (bounds differ by {sp.sstr(sp.simplify(as_bound(_as_lower(quoted), b).bound - as_bound(mine, b).bound))})"
    except NotABound:
        pass
    return Finding(
        Verdict.INCONSISTENT,
        f"({eq_id}){' at z_a = 0' if reduce else ''} reads {reading_of_b(mine)}, {vs_derived.verdict.value} against the linear "
        f"condition of Gil et al. 2009 as derived and published (K(T/2 + t_d) < b + B), but not the paper's own quote (5), "
        f"{reading_of_b(quoted)}{gap}: {vs_quote.verdict.value} against it (witness)",
        Evidence(Method.COUNTEREXAMPLE, witness=vs_quote.evidence.witness, facts=facts),
        derived=derived,
        corrected=r"\text{identical to [7] as published: } K < \frac{B+b}{\frac{T}{2}+t_d} \text{ (correct (5))}",
    )


def _as_lower(rel: sp.Basic) -> sp.Basic:
    """A printed condition as the non-strict reference of :func:`compare_bounds` (a lower bound on b)."""
    bound = as_bound(rel, b)
    if not bound.lower:
        raise NotABound(f"it is an upper bound, {bound}")
    return sp.Ge(b, bound.bound, evaluate=False)


@PAPER.equation("25-identical-7", kind="claim", after="25", section="3.1.1",
                printed="Interestingly, the above condition is identical to the condition reported in [7].",
                derivation="(25) vs the quote (5) and vs the derived Gil et al. 2009 condition", quotes=('25', '5'))
def identical_25(ctx: AuditContext) -> Finding:
    return _identical_to_7(ctx, "25", {})


@PAPER.equation("36-identical-7", kind="claim", after="36", section="3.1.2",
                printed="For the virtual wall H(z) = K + B(z-1)/(Tz) and assuming that B is small enough, this stability "
                        "condition will again reduce to (27), where if z_a = 0 the condition will be identical to that "
                        "reported in [7].",
                derivation="(27) at z_a = 0 vs the quote (5) and vs the derived Gil et al. 2009 condition", quotes=('5',))
def identical_36(ctx: AuditContext) -> Finding:
    return _identical_to_7(ctx, "27", {z_a: 0})
