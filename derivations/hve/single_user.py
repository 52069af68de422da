r"""HVE paper, Sections 1-3.1 up to the delayed wall: the model (1)-(3), the approximations
(16a)-(16d), G^-1(z) for the three approximations (17)-(19), their passivity conditions (20)-(22)
and the delayed condition (23).
"""

from __future__ import annotations

from pathlib import Path

import sympy as sp

from hapticproof.audit.paperfile import read_paper, register_claims
from hapticproof.audit.runner import AuditContext, malformed
from hapticproof.audit.compare import NotABound, as_bound, as_lower_bound, as_sign_condition, compare_bounds, compare_expressions
from hapticproof.exact.canonical import is_identically_zero
from hapticproof.analysis.classics import colgate_bound
from hapticproof.core.evidence import Evidence, Finding, Method, Verdict
from hapticproof.systems.models import RECURRENCES, integrator, inverse_transfer, transfer_from_recurrence
from hapticproof.analysis.positivereal import hermitian, residues, poles
from hapticproof.exact.realroots import minimise_rational
from hapticproof.systems.singleuser import SingleUserScene, virtual_wall
from hapticproof.core.symbols import c as C
from hapticproof.core.symbols import helper_definitions
from hapticproof.exact.unitcircle import canonical_theta, omega_to_c
from hapticproof.derivations.hve.paper import ASSUME, B, F_h, G_INV, K, PAPER, S_EXPR, T, V_h, X_h, b, exact_worst, in_c, k_idx, n, omega, scene, t_d, verify_pointwise, verify_worst_case, x_h, xdot_h


@PAPER.equation("1", kind="condition", printed="", section="1", parse=False,
                derivation="Minsky et al.'s model (Fig. 1): the hold as a one-sample delay, second-order Taylor series, Routh-Hurwitz")
def eq1(ctx: AuditContext) -> Finding:
    # m s^2 + b s + K e^{-sT}, with e^{-sT} replaced by its second-order Taylor polynomial: a
    # quadratic, Hurwitz iff all its coefficients are positive
    m_, s_ = sp.Symbol("m", positive=True), sp.Symbol("s")
    taylor = sp.series(sp.exp(-s_ * T), s_, 0, 3).removeO()
    poly = sp.Poly(sp.expand(m_ * s_**2 + b * s_ + K * taylor), s_)
    conditions = [sp.Gt(coeff, 0, evaluate=False) for coeff in poly.all_coeffs()]
    binding = [c for c in conditions if not (c.lhs - c.rhs).is_positive]
    (derived,) = binding
    return malformed(
        ctx,
        "the display of (1) is missing from the text ('... is stable if' is followed by no condition); the model it "
        "describes gives b > KT (Routh-Hurwitz of m s^2 + b s + K(1 - sT + s^2 T^2/2)), consistent with the text's remark "
        "that the true condition is b > C KT with C about 1/2",
        corrected=r"b > KT",
        derived=derived,
    )


@PAPER.equation("3", kind="condition", printed=r"b > \frac{KT}{2} + B", section="1",
                assumptions="b, K, T > 0; B >= 0 (a physical virtual damper)",
                derivation="Colgate & Schenkel's passivity condition sup_c of its bound for the virtual wall")
def eq3(ctx: AuditContext) -> Finding:
    bound = colgate_bound(virtual_wall(K, B, T), T)          # KT/2 - B c
    # sup over c in [-1, 1] of an affine function: an endpoint (B >= 0 puts it at c = -1)
    sup = sp.Max(bound.subs(C, -1), bound.subs(C, 1))
    exact = sp.Ge(b, sp.simplify(sup))
    return compare_bounds(ctx.relation(), exact, b, what="Colgate's condition as quoted",
                          note="derived from Colgate & Schenkel's frequency form with H(z) = K + B(z-1)/(Tz); "
                               "for B < 0 the exact bound is KT/2 + |B|")


@PAPER.equation("def3", kind="claim", after="13", section="2",
                printed="Definition 3. Let A be a Hermitian symmetric matrix. A is positive semidefinite, "
                        "if all its leading principle minors are non-negative.",
                derivation="leading principal minors vs all principal minors")
def def3(ctx: AuditContext) -> Finding:
    A = sp.Matrix([[0, 0], [0, -1]])
    leading = [A[:k, :k].det() for k in (1, 2)]
    eigen = min(A.eigenvals())
    if not (all(m >= 0 for m in leading) and eigen < 0):
        return Finding(Verdict.UNDECIDED, f"the witness {A.tolist()} did not separate the leading-minor test from PSD",
                       Evidence(Method.INSTANCES, facts={"leading_minors": leading, "min_eigenvalue": eigen}))
    return Finding(
        Verdict.WRONG,
        "non-negative leading principal minors do not imply positive semidefiniteness "
        "(they do imply definiteness when all are positive); PSD needs all principal minors >= 0",
        Evidence(Method.COUNTEREXAMPLE, witness={"A": A}, facts={"leading_minors": leading, "min_eigenvalue": eigen}),
        corrected=r"A \succeq 0 \iff \text{all principal minors of } A \text{ are non-negative}",
    )


#: The routine claims of Section 3.1.1, (17), (18), (21), (22) and (26): kept as a paper file
#: beside this module and decided by the generic claim checkers.
ROUTINE = read_paper(Path(__file__).with_name("routine.toml"))
register_claims(ROUTINE, PAPER)


def _approximation_check(ctx: AuditContext, approximation: str, restore_lhs: bool = False) -> Finding:
    """Re-derive a printed approximation: its recurrence (transformed by the shift rule) and its
    final ``X_h(z) = ... V_h(z)`` against the integrator derived from the paper's recurrence."""
    relations = []
    for rel in ctx.statement.relations():        # a chain a = b = c reads as its links
        r = rel.as_sympy()
        relations.extend(r.args if isinstance(r, sp.And) else [r])
    derived = integrator(approximation, T)
    finals = [rel for rel in relations if isinstance(rel, sp.Eq) and rel.lhs == X_h and rel.rhs.has(V_h)]
    if not finals:
        return malformed(ctx, "no final relation X_h(z) = ... V_h(z) in the display")
    final = compare_expressions(sp.cancel(finals[-1].rhs / V_h), derived, what="the printed result X_h/V_h")
    if final.verdict != Verdict.CONFIRMED:
        return final
    recurrence = relations[0]
    problems = []
    # the z-domain steps between the recurrence and the result: each must give the same X_h/V_h
    for step in relations[1:-1]:
        if not step.has(X_h) or step.has(x_h) or step.has(xdot_h):
            continue                    # a time-domain step (the recurrence is checked below)
        solved = sp.solve(step, X_h)
        ratio = sp.cancel(solved[0] / V_h) if len(solved) == 1 else None
        if ratio is None or not is_identically_zero(ratio - derived):
            problems.append(f"the z-domain step {sp.sstr(step)} gives X_h/V_h = {sp.sstr(ratio)} instead of {sp.sstr(derived)}")
    try:
        from_recurrence = transfer_from_recurrence(recurrence, x_h, xdot_h, k_idx, T)
    except ValueError as err:
        problems.append(f"the printed recurrence {sp.sstr(recurrence)} cannot be transformed: {err}")
        from_recurrence = None
        if restore_lhs:
            # documented reading: the transcription lost 'x_h' before '(kT+T)'
            repaired = sp.Eq(x_h(recurrence.lhs), recurrence.rhs)
            try:
                from_recurrence = transfer_from_recurrence(repaired, x_h, xdot_h, k_idx, T)
                problems.append("with x_h restored on the left")
            except ValueError as again:
                problems.append(f"not even with x_h restored on the left ({again})")
    if from_recurrence is not None and not is_identically_zero(from_recurrence - derived):
        problems.append(f"it gives X_h/V_h = {sp.sstr(from_recurrence)} instead of {sp.sstr(derived)}")
    from hapticproof.audit.reader.statements import Expression

    def bare(statement):        # expressions that are not part of any relation, at any depth
        for s in getattr(statement, "statements", ()):
            yield from ([s.expr] if isinstance(s, Expression) else bare(s))

    stray = list(bare(ctx.statement))
    if stray:
        problems.append(f"the display has a stray expression between its steps: {', '.join(map(sp.sstr, stray))}")
    if not problems:
        return Finding(Verdict.CONFIRMED, f"recurrence and result X_h/V_h = {sp.sstr(derived)} both re-derived",
                       Evidence(Method.CANONICAL_FORM, facts={"printed_form": ("equals", sp.srepr(derived))}),
                       derived=sp.Eq(X_h, derived * V_h))
    return Finding(
        Verdict.TYPO,
        f"the result X_h/V_h = {sp.sstr(derived)} is right, but " + "; ".join(problems),
        Evidence(Method.CANONICAL_FORM, facts={"recurrence": recurrence, "derived_from": RECURRENCES[approximation]}),
        derived=sp.Eq(X_h, derived * V_h),
        corrected=CORRECT_RECURRENCES[approximation],
    )


CORRECT_RECURRENCES = {
    "forward": r"x_h(kT+T) = x_h(kT) + T\dot{x}_h(kT) \implies X_h(z) = \frac{T}{z-1}V_h(z)",
    "backward": r"x_h(kT) = x_h(kT - T) + T\dot{x}_h(kT) \implies X_h(z) = \frac{Tz}{z-1}V_h(z)",
    "tustin": r"x_h(kT+T) = x_h(kT) + \frac{T}{2}\left(\dot{x}_h(kT+T) + \dot{x}_h(kT)\right) \implies X_h(z) = \frac{T}{2}\frac{z+1}{z-1}V_h(z)",
}


@PAPER.equation(
    "16a", kind="expression", section="3.1.1",
    printed=r"x_h(kT+K) = x_h(kT) + T\dot{x}_h(kT) \xrightarrow{\mathcal{Z}} zX_h(z) = X_h(z) + TV_h(z) \\ \implies X_h(z) = \frac{T}{z-1}V_h(z)",
    derivation="shift-rule z-transform of the printed recurrence; result vs x(k+1) = x(k) + T v(k)",
)
def eq16a(ctx: AuditContext) -> Finding:
    return _approximation_check(ctx, "forward")


@PAPER.equation(
    "16b", kind="expression", section="3.1.1",
    printed=r"\begin{aligned} x_h(kT) &= x_h(KT - T) + T\dot{x}_h(kT) \xrightarrow{\mathscr{D}} X_h(z) = z^{-1}X_h(z) + TV_h(z) \\ &\Longrightarrow X_h(z) = \frac{Tz}{z - 1}V_h(z) \end{aligned}",
    derivation="shift-rule z-transform of the printed recurrence; result vs x(k) = x(k-1) + T v(k)",
)
def eq16b(ctx: AuditContext) -> Finding:
    return _approximation_check(ctx, "backward")


@PAPER.equation(
    "16c", kind="expression", section="3.1.1",
    printed=r"\begin{aligned} (kT+T) &= x_h(kT) + T\dot{x}_h(kT) + (\dot{x}_h(kT+T) - \dot{x}_h(kT))\frac{1}{2} \\ \xrightarrow{\mathscr{Z}} zX_h(z) &= X_h(z) + TV_h(z) + (zV_h(z) - V_h(z))\frac{T}{2} \\ &\implies X_h(z) = \frac{T}{2}\frac{z+1}{z-1}V_h(z) \end{aligned}",
    derivation="shift-rule z-transform of the printed recurrence (its left side x_h was lost in the transcription); result vs the trapezoidal rule",
)
def eq16c(ctx: AuditContext) -> Finding:
    return _approximation_check(ctx, "tustin", restore_lhs=True)


G_FORMS = {
    "16d": ("forward", r"F_{h}(z) = bV_{h}(z) + \left(K + \frac{B(z-1)}{Tz}\right)\frac{T}{z-1}V_{h}(z) = G_{1}^{-1}(z)V_{h}(z)"),
    "16e": ("backward", r"F_{h}(z) = bV_{h}(z) + \left(K + \frac{B(z-1)}{Tz}\right)\frac{Tz}{z-1}V_{h}(z) = G_{2}^{-1}(z)V_{h}(z)"),
    "16f": ("tustin", r"F_{h}(z) = bV_{h}(z) + \left(K + \frac{B(z-1)}{Tz}\right)\frac{T}{2}\frac{z+1}{z-1}V_{h}(z) = G_{3}^{-1}(z)V_{h}(z)"),
}


def _g_form_check(approximation: str, index: int):
    def check(ctx: AuditContext) -> Finding:
        statement = ctx.statement
        relations = statement.relations()
        if len(relations) != 1 or len(relations[0].terms) != 3 or relations[0].ops != ("=", "="):
            return malformed(ctx, "expected the chain F_h(z) = ... = G_i^{-1}(z)V_h(z)")
        first, middle, last = relations[0].terms
        derived = inverse_transfer(scene(approximation))
        if first != F_h or not is_identically_zero(last - G_INV[index] * V_h):
            return Finding(Verdict.TYPO, f"the chain must run from F_h(z) to G_{index}^-1(z)V_h(z) for the {approximation} "
                           f"difference; it reads {sp.sstr(first)} = ... = {sp.sstr(last)}",
                           Evidence(Method.PARSE, facts={"printed_form": (sp.srepr(first), sp.srepr(last))}),
                           derived=sp.Eq(F_h, derived * V_h))
        return compare_expressions(sp.cancel(middle / V_h), derived,
                                   what=f"the printed G^-1(z) ({approximation} difference)")
    return check


for _index, (_id, (_approx, _printed)) in enumerate(G_FORMS.items(), start=1):
    PAPER.equation(_id, kind="expression", printed=_printed, section="3.1.1",
                   derivation=f"G^-1 = b + H(z) X_h/V_h with the {_approx} approximation")(_g_form_check(_approx, _index))


@PAPER.equation("16f-residue", kind="claim", after="16f", section="3.1.1",
                printed="the poles of G_i^{-1}(z), i = 1, 2, 3, lie inside or on the unit circle. Since z = 1 is a "
                        "simple pole and its residue for each G_i^{-1}(z) is positive semidefinite, KT",
                derivation="poles and residues of the three G_i^{-1}")
def residue_claim(ctx: AuditContext) -> Finding:
    facts = {}
    for approx in ("forward", "backward", "tustin"):
        sc = scene(approx)
        pole_list = poles(sc)
        if any(p.location not in ("inside", "on") for p in pole_list):
            return Finding(Verdict.WRONG, f"{approx}: a pole outside the unit circle", Evidence(Method.CANONICAL_FORM))
        (res,) = residues(sc)
        if res.pole != 1 or not is_identically_zero(res.residue - K * T):
            return Finding(Verdict.WRONG, f"{approx}: residue at z = 1 is {res.residue}", Evidence(Method.CANONICAL_FORM))
        facts[approx] = {"poles": [(p.value, p.multiplicity) for p in pole_list], "residue_at_1": res.residue}
    return Finding(Verdict.CONFIRMED,
                   "all poles of the three G_i^-1 are at z = 0 or z = 1; z = 1 is simple with residue KT >= 0 in each case",
                   Evidence(Method.CANONICAL_FORM, facts=facts), derived=K * T)


@PAPER.equation("19", kind="condition", printed=r"b + B \frac{1 + \cos(\omega T)}{2}", section="3.1.1",
                assumptions=ASSUME, derivation="Re G_3^{-1}(e^{jwT}) >= 0 (Tustin)")
def eq19(ctx: AuditContext) -> Finding:
    statement = ctx.statement
    derived = hermitian(scene("tustin")).expr()
    if statement.relations():
        return compare_bounds(in_c(ctx.relation()), sp.Ge(derived, 0), b, what="the printed condition")
    same = is_identically_zero(omega_to_c(statement.expr, omega, T) - derived)
    what = "equals Re G_3^-1 exactly" if same else "is not even Re G_3^-1"
    return malformed(ctx, f"the display is an expression, not a condition: '> 0' is missing (the expression {what})",
                     corrected=r"b + B\frac{1 + \cos(\omega T)}{2} > 0", derived=sp.Gt(derived, 0))


@PAPER.equation("19-worst", kind="claim", after="19", section="3.1.1",
                printed="From (17)-(19), the worst-case condition is (17).",
                derivation="compare the three exact worst cases over c")
def worst_of_three(ctx: AuditContext) -> Finding:
    # worst case over c of the three lower bounds on b (each Hermitian part is b + f_i(c))
    sups = {}
    for approx in ("forward", "backward", "tustin"):
        f = sp.expand(hermitian(scene(approx)).expr() - b)         # Re = b + f(c), need b >= -f
        sups[approx] = sp.Max(-f.subs(C, -1), -f.subs(C, 1))
    gaps = {a: sp.simplify(sups["forward"] - sups[a]) for a in ("backward", "tustin")}
    facts = {"worst_bounds": sups, "differences": gaps}
    if not all(sp.simplify(g).is_nonnegative for g in gaps.values()):
        return Finding(Verdict.WRONG, f"the forward-difference worst case is not the largest bound: differences {gaps}",
                       Evidence(Method.ENDPOINT_ANALYSIS, facts=facts))
    return Finding(Verdict.CONFIRMED,
                   f"the forward-difference bound sup_c = {sp.sstr(sp.simplify(sups['forward']))} exceeds the backward "
                   f"({sp.sstr(sp.simplify(sups['backward']))}) and Tustin ({sp.sstr(sp.simplify(sups['tustin']))}) bounds for "
                   f"all K, T > 0, B >= 0 (differences {sp.sstr(gaps['backward'])} and {sp.sstr(gaps['tustin'])})",
                   Evidence(Method.ENDPOINT_ANALYSIS, facts=facts))


@PAPER.equation("20", kind="condition", printed=r"b > \frac{KT}{2} + B", section="3.1.1",
                assumptions=ASSUME, derivation="exact minimum over c of Re G_1^{-1}: attained at c = -1 for B >= 0")
def eq20(ctx: AuditContext) -> Finding:
    return compare_bounds(ctx.relation(), exact_worst(scene("forward")), b, verify=verify_worst_case("forward"),
                          what="the printed worst-case condition",
                          note="the text's worst case cos(omega T = -1) is garbled but means c = -1, the exact minimiser for B >= 0")


@PAPER.equation("20-colgate", kind="claim", after="20", section="3.1.1",
                printed="This is identical to Colgate's condition.",
                derivation="(20) vs (3) as printed, and vs Colgate's frequency form", quotes=('20', '3'))
def identical_to_colgate(ctx: AuditContext) -> Finding:
    mine = ctx.parse(PAPER.get("20").printed).relations()[0].as_sympy()
    theirs = ctx.parse(PAPER.get("3").printed).relations()[0].as_sympy()
    try:
        reference = as_lower_bound(theirs, b)
    except NotABound as err:
        return Finding(Verdict.INCONSISTENT, f"(3) reads {reading_of_b(theirs)} ({err.reason}), (20) reads {reading_of_b(mine)}: they differ",
                       Evidence(Method.CANONICAL_FORM, facts={"ids": ["20", "3"]}))
    finding = compare_bounds(mine, sp.Ge(b, reference.bound), b, what="(20)")
    identity = is_identically_zero(colgate_bound(virtual_wall(K, B, T), T) + sp.expand(hermitian(scene()).expr()) - b)
    if finding.verdict != Verdict.CONFIRMED or not identity:
        return Finding(Verdict.INCONSISTENT, f"(20) reads {reading_of_b(mine)} and (3) reads {reading_of_b(theirs)}: they differ "
                       f"({finding.verdict.value})", Evidence(finding.evidence.method, witness=finding.evidence.witness,
                                                               facts={"ids": ["20", "3"]}))
    return Finding(Verdict.CONFIRMED,
                   "(20) and (3) are the same condition; moreover Colgate's frequency bound equals b - Re G_1^-1 identically, "
                   "so the two derivations agree at every frequency, not only in the worst case",
                   Evidence(Method.CANONICAL_FORM, facts={"frequency_identity": "colgate_bound(H) = b - Re G_1^-1(c)"}))


@PAPER.equation("20-forward", kind="claim", after="20", section="3.1.1",
                printed="the forward difference approximation method resulted in the worst-case condition for stability "
                        "of the single-user HVE system",
                derivation="(19-worst) for general B and for the delayed scene")
def forward_is_worst(ctx: AuditContext) -> Finding:
    # no delay: as in 19-worst; with delay n the integrators differ by the factor z or (z+1)/2,
    # check the exact worst cases on instances
    counter = None
    instances = 0
    for delay in range(0, 4):
        for Kv, Bv in ((1, 0), (2, sp.Rational(1, 10)), (1, 1)):
            bounds = {}
            for approx in ("forward", "backward", "tustin"):
                sc = SingleUserScene.virtual_wall(K=Kv, B=Bv, b=0, T=1, approximation=approx, delay=delay)
                form = hermitian(sc).numeric()
                m = minimise_rational(form.num, form.den, -1, 1)
                bounds[approx] = -m.value.mid()          # b needed: -min(Re G^-1 at b = 0)
            instances += 1
            if bounds["forward"] < max(bounds["backward"], bounds["tustin"]) - 1e-12:
                counter = {"n": delay, "K": Kv, "B": Bv, "T": 1, "bounds": {k: float(v) for k, v in bounds.items()}}
                break
        if counter:
            break
    if counter:
        return Finding(Verdict.NEEDS_ASSUMPTION,
                       "true without delay; with a delay another approximation can need more damping",
                       Evidence(Method.COUNTEREXAMPLE, witness={k: v for k, v in counter.items() if k != "bounds"},
                                facts={"required_b": counter["bounds"]}))
    return Finding(Verdict.CONFIRMED,
                   f"without delay proved for all parameters (19-worst); with delays n = 0..3 checked on {instances} exact instances",
                   Evidence(Method.INSTANCES, instances=instances))


@PAPER.equation("22-conditions", kind="claim", after="22", section="3.1.1",
                printed="The first and third conditions in Definition 2 are readily satisfied leaving us with the third "
                        "condition which requires Re{G^{-1}(z)} >= 0.",
                derivation="poles and residue of (22) for symbolic n; which condition of Definition 2 is Re >= 0")
def remaining_condition(ctx: AuditContext) -> Finding:
    sc = scene(delay=n)
    pole_list = poles(sc)
    (res,) = residues(sc)
    ok = all(p.location in ("inside", "on") for p in pole_list) and is_identically_zero(res.residue - K * T)
    if not ok:
        return Finding(Verdict.WRONG, "conditions 1 and 3 of Definition 2 are not satisfied", Evidence(Method.CANONICAL_FORM))
    return Finding(
        Verdict.TYPO,
        "conditions 1 (poles at z = 0 and the simple pole z = 1) and 3 (residue KT >= 0) hold for every n, "
        "but the remaining condition Re G^-1 >= 0 is the second condition of Definition 2, not the third",
        Evidence(Method.CANONICAL_FORM, facts={"poles": [(p.value, p.location) for p in pole_list], "residue_at_1": res.residue}),
        corrected=r"\text{leaving us with the second condition, } \Re\{G^{-1}(e^{j\omega T})\} \ge 0",
    )


def _theta_mismatch(printed: sp.Expr, derived_canonical: sp.Expr) -> sp.Expr:
    return sp.simplify(canonical_theta(printed, omega, T, t_d, n) - derived_canonical)


_RELATIONS = {">": sp.Gt, ">=": sp.Ge, "=": sp.Eq, "!=": sp.Ne}


@PAPER.equation("23", kind="condition", section="3.1.1",
                printed=r"b + B\cos(\omega t_d - T) - \frac{KT}{2}\cos(\omega t_d) - KTS > 0",
                assumptions=ASSUME, derivation="exact theta-form of Re G^-1 for symbolic n (eq. 22)")
def eq23(ctx: AuditContext) -> Finding:
    relation = ctx.relation()
    condition = as_sign_condition(relation)
    printed = condition.expr
    derived = hermitian(scene(delay=n))
    as_printed = _theta_mismatch(printed, derived.canonical())
    facts: dict = {"difference_as_printed": as_printed, "printed_form": (condition.op, sp.srepr(sp.expand(printed)))}
    if as_printed == 0 and condition.op in (">", ">="):
        return Finding(Verdict.CONFIRMED, "equals Re G^-1 for every integer n, required positive",
                       Evidence(Method.CANONICAL_FORM, facts=facts))
    # the evident intent, printed explicitly in (58)-(59): cos(omega (t_d - T))
    intended = printed.subs(sp.cos(omega * t_d - T), sp.cos(omega * (t_d - T)))
    as_intended = _theta_mismatch(intended, derived.canonical())
    corrected_expr = printed.subs(sp.cos(omega * t_d - T), sp.cos(omega * (t_d + T)))
    corrected_ok = _theta_mismatch(corrected_expr, derived.canonical()) == 0 and condition.op in (">", ">=")
    # exact witness on the intended reading at n = 1 (t_d = T): compare as bounds on b, c in [-1, 1]
    try:
        printed_1 = omega_to_c(intended.subs({t_d: T}), omega, T)
    except ValueError as err:
        # Re G^-1 at n = 1 is a polynomial in cos(omega T); a display that is not one cannot be it
        return Finding(
            Verdict.WRONG,
            f"not the real part of (22): at n = 1 the printed expression is not a function of cos(omega T) alone "
            f"({err}), which Re G^-1 is; it differs by {sp.sstr(as_intended)} in the canonical variables"
            f"{helper_definitions(as_intended)}",
            Evidence(Method.CANONICAL_FORM, facts=facts),
            derived=sp.Gt(derived.expr(omega * T).subs(n, t_d / T), 0),
            corrected=r"b + B\cos(\omega (t_d + T)) - \frac{KT}{2}\cos(\omega t_d) - KTS > 0",
        )
    exact_1 = hermitian(scene(delay=1)).expr()
    witness = compare_bounds(_RELATIONS[condition.op](printed_1, 0, evaluate=False), sp.Ge(exact_1, 0), b,
                             verify=verify_pointwise("forward", delay=1), what="(23) read as cos(omega(t_d - T)), at n = 1")
    facts.update({"difference_intended": as_intended, "corrected_equals_derived_for_all_n": corrected_ok,
                  "at_n_1": witness.verdict.value, **{k: v for k, v in witness.evidence.facts.items() if k != "printed_form"}})
    slip = ("the B-term must be B cos(omega(t_d + T)) (z^{-n} B/z = B z^{-(n+1)}); as printed cos(omega t_d - T) mixes a "
            "time with an angle, and the evident reading cos(omega(t_d - T)), repeated in (58)-(59), "
            if corrected_ok else "")
    at_n1 = ("at n = 1 it holds where Re G^-1 < 0" if witness.verdict == Verdict.WRONG
             else f"at n = 1 it is {witness.verdict.value} against Re G^-1 >= 0")
    verdict = Verdict.WRONG if witness.verdict == Verdict.WRONG else (Verdict.TYPO if corrected_ok else witness.verdict)
    return Finding(
        verdict,
        f"not the real part of (22) ({condition.op} 0): {slip}differs by {sp.sstr(as_intended)} in the canonical variables"
        f"{helper_definitions(as_intended)}; {at_n1}",
        Evidence(Method.COUNTEREXAMPLE, witness=witness.evidence.witness, facts=facts),
        derived=sp.Gt(derived.expr(omega * T).subs(n, t_d / T), 0),
        corrected=r"b + B\cos(\omega (t_d + T)) - \frac{KT}{2}\cos(\omega t_d) - KTS > 0",
    )


@PAPER.equation("23a", kind="expression", section="3.1.1",
                printed=r"\lim_{\cos(\omega T)\to 1} KTS = \lim_{\cos(\omega T)\to 1} KT \frac{\sin(\omega t_d)\sin(\omega T)}{2(1-\cos(\omega T))} = Kt_d",
                derivation="limit theta -> 0 of KT sin(n theta) sin(theta) / (2(1 - cos theta)), t_d = nT")
def eq23a(ctx: AuditContext) -> Finding:
    from hapticproof.audit.reader.statements import PrintedLimit

    theta = sp.Symbol("theta", positive=True)
    limit = sp.limit(K * T * sp.sin(n * theta) * sp.sin(theta) / (2 * (1 - sp.cos(theta))), theta, 0)
    derived = sp.simplify(limit.subs(n, t_d / T))
    terms = list(ctx.statement.terms)
    values = []
    for i, term in enumerate(terms):
        # every printed limit inside the member (a member may be 2 lim ..., or lim ... + x)
        limits = [term] if isinstance(term, PrintedLimit) else sorted(sp.sympify(term).atoms(PrintedLimit), key=sp.srepr)
        evaluated = {}
        for lim in limits:
            # where the printed variable reaches its target: the smallest omega >= 0 (omega T -> 0 for cos -> 1)
            roots = sorted(r for r in sp.solve(sp.Eq(lim.variable.subs(omega, theta / T), lim.target), theta)
                           if r.is_real and r.is_nonnegative) if omega in lim.variable.free_symbols else []
            if not roots:
                return Finding(Verdict.UNDECIDED, f"member {i + 1}: cannot locate where {sp.sstr(lim.variable)} -> "
                               f"{sp.sstr(lim.target)} as a function of omega", Evidence(Method.CANONICAL_FORM))
            value = sp.limit(lim.expr.subs({omega: theta / T, t_d: n * T}), theta, roots[0], "+")
            evaluated[lim] = sp.simplify(value.subs(n, t_d / T))
        values.append(evaluated[term] if isinstance(term, PrintedLimit) else sp.simplify(sp.sympify(term).xreplace(evaluated)))
    facts = {"limit": limit, "printed_form": tuple(sp.srepr(sp.simplify(v)) for v in values),
             "member_limits": [sp.sstr(v) for v in values]}
    for i, value in enumerate(values):
        member = compare_expressions(value, derived, what=f"member {i + 1} of the printed chain")
        if member.verdict != Verdict.CONFIRMED:
            return Finding(Verdict.WRONG if member.verdict in (Verdict.WRONG, Verdict.TYPO) else member.verdict,
                           f"member {i + 1} of the chain tends to {sp.sstr(value)}, not Kt_d = {sp.sstr(derived)} "
                           f"(the SymPy limit of KT sin(n theta) sin(theta)/(2(1 - cos theta)), theta -> 0, t_d = nT)",
                           Evidence(Method.COUNTEREXAMPLE, witness=member.evidence.witness, facts=facts),
                           derived=sp.Eq(sp.Symbol("lim"), derived))
    middle_is_S = len(terms) > 1 and isinstance(terms[1], PrintedLimit) and is_identically_zero(terms[1].expr - K * T * S_EXPR)
    facts["middle_is_KTS"] = middle_is_S
    return Finding(Verdict.CONFIRMED,
                   f"all {len(values)} members tend to {sp.sstr(derived)} (SymPy limits at the point where the printed "
                   "variable reaches its target), the limit of KTn = Kt_d"
                   + ("; the middle member is KTS written out" if middle_is_S else
                      "; the middle member is not KTS written out, but has the same limit"),
                   Evidence(Method.CANONICAL_FORM, facts=facts), derived=sp.Eq(sp.Symbol("lim"), derived))


def reading_of_b(condition: sp.Basic) -> str:
    """What a printed condition says about b."""
    try:
        return str(as_bound(condition, b))
    except NotABound as err:
        return f"{sp.sstr(condition)} ({err.reason})"
