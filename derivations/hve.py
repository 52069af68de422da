r"""Miandashti & Tavakoli, "Stability of Sampled-Data, Delayed Haptic Interaction under Passive
or Active Operator" (the HVE paper, ``000_e6b68def623c8e74.txt``).

Every printed equation is registered **verbatim** (OCR damage included) with the toolkit's
derivation of its counterpart. This module holds the paper's symbol table and Sections 1-3.1
(single user); Section 3.2 (m users) and Section 4 live in ``_hve_multiuser.py`` and register
onto the same :data:`PAPER`.

Physical assumptions used throughout (the paper's model): device damping ``b``, stiffness
``K`` and sampling period ``T`` are positive; virtual damping ``B`` and shortage of passivity
``z_a`` are non-negative; ``n = t_d/T`` is a non-negative integer.
"""

from __future__ import annotations

import sympy as sp

from hapticproof.audit import AuditContext, Paper, malformed
from hapticproof.certify import compare_bounds, compare_expressions, is_identically_zero
from hapticproof.classics import colgate_bound
from hapticproof.evidence import Decision, Evidence, Finding, Method, Outcome, Verdict
from hapticproof.models import RECURRENCES, integrator, inverse_transfer
from hapticproof.parse import IndexedFamily, SymbolTable
from hapticproof.positivereal import hermitian, residues, poles, worst_case
from hapticproof.realroots import minimise_rational
from hapticproof.scene import SYMBOLS, SingleUserScene, virtual_wall
from hapticproof.symbols import c as C
from hapticproof.symbols import z
from hapticproof.unitcircle import canonical_theta, omega_to_c

K, B, b, T, z_a, t_d, n = (SYMBOLS[name] for name in ("K", "B", "b", "T", "z_a", "t_d", "n"))
omega = sp.Symbol("omega", real=True)
s = sp.Symbol("s")
#: The paper's S (defined after eq. 23).
S_EXPR = sp.sin(omega * t_d) * sp.sin(omega * T) / (2 * (1 - sp.cos(omega * T)))

# Signals that appear as functions of z in displays; the audit divides by V_h.
F_h, V_h, X_h = sp.symbols("F_h V_h X_h")
G_INV = {i: sp.Symbol(f"G{i}inv") for i in (1, 2, 3)}
H_FUN = sp.Function("H")
R_FUN = sp.Function("r")
G_T = sp.Function("G_T^*")
M_FUN, N_FUN = sp.Function("M"), sp.Function("N")


def _signal(symbol: sp.Symbol):
    return lambda *args: symbol


TABLE = SymbolTable(
    symbols={
        "K": K, "B": B, "b": b, "T": T, "t_d": t_d, "z_a": z_a, r"\omega": omega, "S": S_EXPR,
        "z": z, "s": s, "n": n,
        "b_h": sp.Symbol("b_h", positive=True), "k_h": sp.Symbol("k_h", positive=True),
        "m_h": sp.Symbol("m_h", positive=True), "C": sp.Symbol("C", positive=True),
        "m": sp.Symbol("m", integer=True, positive=True),
    },
    functions={
        "F_h": _signal(F_h), "V_h": _signal(V_h), "X_h": _signal(X_h),
        "G_1^{-1}": _signal(G_INV[1]), "G_2^{-1}": _signal(G_INV[2]), "G_3^{-1}": _signal(G_INV[3]),
        "H": H_FUN, "r": R_FUN, "G_T^*": G_T,
        r"\mathscr{M}": lambda *a: M_FUN(*a), r"\mathscr{N}": lambda *a: N_FUN(*a),
        r"\mathcal{M}": lambda *a: M_FUN(*a), r"\mathcal{N}": lambda *a: N_FUN(*a),
        r"\mathscr{Z}": sp.Function("Z"), r"\mathcal{Z}": sp.Function("Z"),
    },
    families=[
        IndexedFamily("b_{i}", assumptions={"positive": True}),
        IndexedFamily("z_{ai}", assumptions={"nonnegative": True}),
        IndexedFamily("K_{0i}", assumptions={"positive": True}),
        IndexedFamily("B_{0i}", assumptions={"nonnegative": True}),
        IndexedFamily("K_{ij}", symmetric=True, assumptions={"positive": True}),
        IndexedFamily("B_{ij}", symmetric=True, assumptions={"nonnegative": True}),
        IndexedFamily("t_{di}", assumptions={"nonnegative": True}),
        IndexedFamily("n_{i}", assumptions={"integer": True, "nonnegative": True}),
    ],
)

PAPER = Paper(
    "hve",
    title="Stability of Sampled-Data, Delayed Haptic Interaction under Passive or Active Operator",
    source="000_e6b68def623c8e74.txt",
    authors="N. Miandashti and M. Tavakoli",
    symbols=TABLE,
    aliases=("000", "miandashti-tavakoli", "haptic-virtual-environment"),
)

ASSUME = "b, K, T > 0; B >= 0; z_a >= 0; n = t_d/T a non-negative integer"


# ---------------------------------------------------------------------------------------------
# helpers shared by the entries
# ---------------------------------------------------------------------------------------------


def scene(approximation: str = "forward", delay=0, active: bool = False) -> SingleUserScene:
    """The paper's symbolic single-user scene."""
    return SingleUserScene.virtual_wall(
        K=K, B=B, b=b, T=T, approximation=approximation, delay=delay, z_a=z_a if active else 0
    )


def pointwise_exact(sc: SingleUserScene) -> sp.Basic:
    """``Re G^{-1}(e^{jwT}) >= 0`` at one frequency, as a condition in the parameters and c."""
    return sp.Ge(sp.expand(hermitian(sc).expr()), 0, evaluate=False)


def verify_pointwise(approximation: str, delay=0, active: bool = False):
    """Re-check a witness (parameters and c) by exact evaluation of the numeric scene."""

    def verify(point: dict) -> Outcome:
        values = {str(k): v for k, v in point.items()}
        numeric = SingleUserScene.virtual_wall(
            K=values["K"], B=values.get("B", 0), b=values["b"], T=values["T"],
            approximation=approximation, delay=delay, z_a=values.get("z_a", 0) if active else 0,
        )
        value = hermitian(numeric)(values["c"])
        decision = Decision.DISPROVED if value < 0 else Decision.PROVED
        return Outcome(decision, Evidence(Method.ROOT_ISOLATION, witness={"c": values["c"]}, facts={"Re G^-1": value}),
                       f"Re G^-1 = {value} at c = {values['c']}")

    return verify


def verify_worst_case(approximation: str = "forward", delay=0, active: bool = False):
    """Re-check a parameter witness by the exact worst-case decision (root isolation)."""

    def verify(point: dict) -> Outcome:
        values = {str(k): v for k, v in point.items()}
        numeric = SingleUserScene.virtual_wall(
            K=values["K"], B=values.get("B", 0), b=values["b"], T=values["T"],
            approximation=approximation, delay=values.get("n", delay), z_a=values.get("z_a", 0) if active else 0,
        )
        return worst_case(numeric).outcome

    return verify


def in_c(relation: sp.Basic) -> sp.Basic:
    """A printed frequency-wise condition with ``cos(wT)`` rewritten in ``c``."""
    return relation.func(omega_to_c(relation.lhs, omega, T), omega_to_c(relation.rhs, omega, T), evaluate=False)


def exact_worst(sc: SingleUserScene) -> sp.Basic:
    return worst_case(sc).condition


# ---------------------------------------------------------------------------------------------
# Section 1: conditions quoted in the introduction
# ---------------------------------------------------------------------------------------------


@PAPER.equation("1", kind="condition", printed="", section="1", parse=False,
                derivation="Minsky et al.'s condition announced in the text")
def eq1(ctx: AuditContext) -> Finding:
    return malformed(
        ctx,
        "the display of (1) is missing from the text: 'It was shown that the system in Figure 1 is "
        "stable if' is followed by no condition",
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


# ---------------------------------------------------------------------------------------------
# Section 2: definitions
# ---------------------------------------------------------------------------------------------


@PAPER.equation("def3", kind="claim", after="13", section="2",
                printed="Definition 3. Let A be a Hermitian symmetric matrix. A is positive semidefinite, "
                        "if all its leading principle minors are non-negative.",
                derivation="leading principal minors vs all principal minors")
def def3(ctx: AuditContext) -> Finding:
    A = sp.Matrix([[0, 0], [0, -1]])
    leading = [A[:k, :k].det() for k in (1, 2)]
    eigen = min(A.eigenvals())
    assert all(m >= 0 for m in leading) and eigen < 0
    return Finding(
        Verdict.WRONG,
        "non-negative leading principal minors do not imply positive semidefiniteness "
        "(they do imply definiteness when all are positive); PSD needs all principal minors >= 0",
        Evidence(Method.COUNTEREXAMPLE, witness={"A": A}, facts={"leading_minors": leading, "min_eigenvalue": eigen}),
        corrected=r"A \succeq 0 \iff \text{all principal minors of } A \text{ are non-negative}",
    )


# ---------------------------------------------------------------------------------------------
# Section 3.1.1: the three approximations and G_i^{-1}(z)
# ---------------------------------------------------------------------------------------------


def _integrator_check(ctx: AuditContext, approximation: str, recurrence_note: str | None) -> Finding:
    """The z-domain result of a printed approximation vs the derivation from its recurrence."""
    statement = ctx.statement
    derived = integrator(approximation, T)
    finals = [rel for rel in statement.relations() if rel.lhs == X_h and V_h in rel.rhs.free_symbols]
    if not finals:
        return malformed(ctx, "no final relation X_h(z) = ... V_h(z) found in the display")
    printed = sp.cancel(finals[-1].rhs / V_h)
    finding = compare_expressions(printed, derived, what="the printed X_h/V_h")
    if finding.verdict != Verdict.CONFIRMED or recurrence_note is None:
        return finding
    return Finding(
        Verdict.TYPO,
        f"the z-domain result X_h/V_h = {sp.sstr(derived)} is right, but {recurrence_note}",
        Evidence(Method.CANONICAL_FORM, facts={"derived_from": sp.sstr(RECURRENCES[approximation])}),
        derived=sp.Eq(X_h, derived * V_h),
        corrected=None,
    )


FORWARD_PRINTED = (
    r"x_h(kT+K) = x_h(kT) + T\dot{x}_h(kT) \xrightarrow{\mathcal{Z}} zX_h(z) = X_h(z) + TV_h(z)"
    r" \\ \implies X_h(z) = \frac{T}{z-1}V_h(z)"
)


@PAPER.equation("16a", kind="expression", printed=FORWARD_PRINTED, section="3.1.1", parse=False,
                derivation="z-transform of x(k+1) = x(k) + T v(k)")
def eq16a(ctx: AuditContext) -> Finding:
    # The time argument x_h(kT+K) uses the stiffness K where the step T belongs; the parser
    # would read it faithfully as a product with K, so only the z-domain lines are compared.
    zline = r"zX_h(z) = X_h(z) + TV_h(z) \\ \implies X_h(z) = \frac{T}{z-1}V_h(z)"
    ctx._statement, ctx._parsed = ctx.parse(zline), True
    return _integrator_check(ctx, "forward", "the recurrence prints x_h(kT+K): the step is T, x_h(kT+T)")


BACKWARD_PRINTED = (
    r"\begin{aligned} x_h(kT) &= x_h(KT - T) + T\dot{x}_h(kT) \xrightarrow{\mathscr{D}} X_h(z) = z^{-1}X_h(z) + TV_h(z) \end{aligned}"
    r" \\ \implies X_h(z) = \frac{Tz}{z - 1}V_h(z)"
)


@PAPER.equation("16b", kind="expression", printed=BACKWARD_PRINTED, section="3.1.1", parse=False,
                derivation="z-transform of x(k) = x(k-1) + T v(k)")
def eq16b(ctx: AuditContext) -> Finding:
    zline = r"X_h(z) = z^{-1}X_h(z) + TV_h(z) \\ \implies X_h(z) = \frac{Tz}{z - 1}V_h(z)"
    ctx._statement, ctx._parsed = ctx.parse(zline), True
    return _integrator_check(ctx, "backward", "the recurrence prints x_h(KT - T) with a capital K (the stiffness) for k, "
                                              "and the transform arrow is labelled D instead of Z")


TUSTIN_PRINTED = (
    r"\begin{aligned} (kT+T) &= x_h(kT) + T\dot{x}_h(kT) + (\dot{x}_h(kT+T) - \dot{x}_h(kT))\frac{1}{2} \\"
    r" \xrightarrow{\mathscr{Z}} zX_h(z) &= X_h(z) + TV_h(z) + (zV_h(z) - V_h(z))\frac{T}{2} \\"
    r" &\implies X_h(z) = \frac{T}{2}\frac{z+1}{z-1}V_h(z) \end{aligned}"
)


@PAPER.equation("16c", kind="expression", printed=TUSTIN_PRINTED, section="3.1.1", parse=False,
                derivation="z-transform of the trapezoidal rule x(k+1) = x(k) + T(v(k) + v(k+1))/2")
def eq16c(ctx: AuditContext) -> Finding:
    zline = (r"zX_h(z) = X_h(z) + TV_h(z) + (zV_h(z) - V_h(z))\frac{T}{2} \\"
             r" \implies X_h(z) = \frac{T}{2}\frac{z+1}{z-1}V_h(z)")
    ctx._statement, ctx._parsed = ctx.parse(zline), True
    return _integrator_check(ctx, "tustin", "the printed recurrence multiplies (x'(kT+T) - x'(kT)) by 1/2 "
                                            "instead of T/2 (the transformed line has T/2), and its left-hand side "
                                            "lost x_h in the transcription")


G_FORMS = {
    "16d": ("forward", r"F_{h}(z) = bV_{h}(z) + \left(K + \frac{B(z-1)}{Tz}\right)\frac{T}{z-1}V_{h}(z) = G_{1}^{-1}(z)V_{h}(z)"),
    "16e": ("backward", r"F_{h}(z) = bV_{h}(z) + \left(K + \frac{B(z-1)}{Tz}\right)\frac{Tz}{z-1}V_{h}(z) = G_{2}^{-1}(z)V_{h}(z)"),
    "16f": ("tustin", r"F_{h}(z) = bV_{h}(z) + \left(K + \frac{B(z-1)}{Tz}\right)\frac{T}{2}\frac{z+1}{z-1}V_{h}(z) = G_{3}^{-1}(z)V_{h}(z)"),
}


def _g_form_check(approximation: str):
    def check(ctx: AuditContext) -> Finding:
        terms = ctx.statement.terms
        printed = sp.cancel(terms[1] / V_h)
        return compare_expressions(printed, inverse_transfer(scene(approximation)),
                                   what=f"the printed G^-1(z) ({approximation} difference)")
    return check


for _id, (_approx, _printed) in G_FORMS.items():
    PAPER.equation(_id, kind="expression", printed=_printed, section="3.1.1",
                   derivation=f"G^-1 = b + H(z) X_h/V_h with the {_approx} approximation")(_g_form_check(_approx))


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


# ---------------------------------------------------------------------------------------------
# (17)-(20): Hermitian parts and the worst case
# ---------------------------------------------------------------------------------------------


@PAPER.equation("17", kind="condition", printed=r"b > \frac{KT}{2} - B\cos(\omega T)", section="3.1.1",
                assumptions=ASSUME, derivation="Re G_1^{-1}(e^{jwT}) >= 0 (forward difference) as a bound on b")
def eq17(ctx: AuditContext) -> Finding:
    return compare_bounds(in_c(ctx.relation()), pointwise_exact(scene("forward")), b,
                          verify=verify_pointwise("forward"), what="the printed frequency-wise condition")


@PAPER.equation("18", kind="condition", printed=r"b + \frac{KT}{2} + B > 0", section="3.1.1",
                assumptions=ASSUME, derivation="Re G_2^{-1}(e^{jwT}) >= 0 (backward difference)")
def eq18(ctx: AuditContext) -> Finding:
    return compare_bounds(in_c(ctx.relation()), pointwise_exact(scene("backward")), b,
                          verify=verify_pointwise("backward"), what="the printed frequency-wise condition")


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
    assert all(sp.simplify(g).is_nonnegative for g in gaps.values())
    return Finding(Verdict.CONFIRMED,
                   "the forward-difference bound sup_c(KT/2 - Bc) = KT/2 + B exceeds the backward (-KT/2 - B) and Tustin (0) "
                   "bounds for all K, T > 0, B >= 0 (differences KT + 2B and KT/2 + B)",
                   Evidence(Method.ENDPOINT_ANALYSIS, facts={"worst_bounds": sups, "differences": gaps}))


@PAPER.equation("20", kind="condition", printed=r"b > \frac{KT}{2} + B", section="3.1.1",
                assumptions=ASSUME, derivation="exact minimum over c of Re G_1^{-1}: attained at c = -1 for B >= 0")
def eq20(ctx: AuditContext) -> Finding:
    return compare_bounds(ctx.relation(), exact_worst(scene("forward")), b, verify=verify_worst_case("forward"),
                          what="the printed worst-case condition",
                          note="the text's worst case cos(omega T = -1) is garbled but means c = -1, the exact minimiser for B >= 0")


@PAPER.equation("20-colgate", kind="claim", after="20", section="3.1.1",
                printed="This is identical to Colgate's condition.",
                derivation="(20) vs (3) as printed, and vs Colgate's frequency form")
def identical_to_colgate(ctx: AuditContext) -> Finding:
    mine = ctx.parse(PAPER.get("20").printed).relations()[0].as_sympy()
    theirs = ctx.parse(PAPER.get("3").printed).relations()[0].as_sympy()
    finding = compare_bounds(mine, sp.Ge(theirs.lhs, theirs.rhs), b, what="(20)")
    identity = is_identically_zero(colgate_bound(virtual_wall(K, B, T), T) + sp.expand(hermitian(scene()).expr()) - b)
    if finding.verdict != Verdict.CONFIRMED or not identity:
        return Finding(Verdict.INCONSISTENT, "(20) and (3) differ", finding.evidence)
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
