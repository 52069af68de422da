r"""The 3-DOF paper, Sections 2-3: the two-port and its subsystems (1)-(5), the energy
definitions (6)-(7) and Property 4.
"""

from __future__ import annotations

import itertools
from fractions import Fraction
from typing import Any

import sympy as sp

from hapticproof.audit.runner import AuditContext, malformed
from hapticproof.exact.canonical import is_identically_zero
from hapticproof.core.evidence import Decision, Evidence, Finding, Method, Verdict
from hapticproof.analysis.networks import absolute_stability, llewellyn, symmetrize
from hapticproof.analysis.nport import input_impedance, positive_real
from hapticproof.audit.reader.printed import parse_printed
from hapticproof.exact.rationalmatrix import RationalMatrix
from hapticproof.core.symbols import s
from hapticproof.derivations.bilateral_3dof.paper import AXES, PAPER, PRINTED, TABLE, certificate_facts, certified, definition, not_in_s, one_line, pr_facts, pr_text, printed_matrix, rhs_matrix, searched_terminations, section2_network, text_diagonal


@PAPER.equation("1", kind="expression", printed=PRINTED["1"], section="2", quotes=("1-diagonal",),
                derivation="diagonal of the printed T_1 vs the terminations the text names after it")
def eq1(ctx: AuditContext) -> Finding:
    T = rhs_matrix(ctx)
    bad = not_in_s(T, "T_1")
    if bad is not None:
        return bad
    text = text_diagonal()
    stray = not_in_s(sp.Matrix([list(text)]), "the terminations the text names (1-diagonal)")
    if stray is not None:
        return Finding(Verdict.UNDECIDED, f"cannot compare the diagonal: {stray.detail}", Evidence(Method.PARSE))
    if T.shape != (3, 3) or len(text) != 3:
        return Finding(Verdict.MALFORMED, f"T_1 is {T.shape[0]}x{T.shape[1]} and the text names {len(text)} terminations",
                       Evidence(Method.PARSE, facts={"printed_form": sp.srepr(T)}))
    printed_diag = [sp.cancel(T[i, i]) for i in range(3)]
    differ = [i for i in range(3) if not is_identically_zero(printed_diag[i] - text[i])]
    variant = T.copy()
    for i in range(3):
        variant[i, i] = text[i]
    results = {"as printed": positive_real(T), "with the text's diagonal": positive_real(variant)}
    facts = {name: pr_facts(r) for name, r in results.items()}
    facts.update({"printed_diagonal": printed_diag, "text_diagonal": list(text), "printed_form": sp.srepr(T)})
    passivity = f"as printed T_1 is {pr_text(results['as printed'])}; with the text's diagonal it is " \
                f"{pr_text(results['with the text' + chr(39) + 's diagonal'])}"
    if not differ:
        return Finding(Verdict.CONFIRMED, f"the printed diagonal agrees with the text; {passivity}",
                       Evidence(Method.CANONICAL_FORM, facts=facts))
    return Finding(
        Verdict.INCONSISTENT,
        f"the display prints {', '.join(sp.sstr(d) for d in printed_diag)} on the diagonal while the text after it (claim "
        f"1-diagonal) names the DOF terminations {', '.join(sp.sstr(t) for t in text)} (entries "
        f"{[i + 1 for i in differ]} differ; off the diagonal it reads {_off_diagonal(T)}); {passivity}",
        Evidence(Method.CANONICAL_FORM, witness={"entries": [[i + 1, i + 1] for i in differ]}, facts=facts),
        derived=variant,
    )


def _off_diagonal(T: sp.Matrix) -> str:
    """The off-diagonal entries as read (the couplings the passivity verdicts depend on)."""
    upper = [sp.sstr(sp.cancel(T[i, j])) for i in range(T.rows) for j in range(i + 1, T.cols)]
    symmetric = all(is_identically_zero(T[i, j] - T[j, i]) for i in range(T.rows) for j in range(i + 1, T.cols))
    if symmetric:
        return f"{', '.join(upper)} (symmetric)"
    lower = [sp.sstr(sp.cancel(T[j, i])) for i in range(T.rows) for j in range(i + 1, T.cols)]
    return f"{', '.join(upper)} above and {', '.join(lower)} below (not symmetric)"


@PAPER.equation("1-diagonal", kind="claim", after="1", section="2",
                printed="the terminations $\\frac{9}{s+3}$, $\\frac{1}{s+3}$ and $\\frac{2}{s+3}$ along each of the first "
                        "three DOFs are passive",
                derivation="positive realness of each scalar termination")
def diagonal_passive(ctx: AuditContext) -> Finding:
    from hapticproof.audit.runner import quoted_math

    terms = [ctx.parse(q).expressions()[0] for q in quoted_math(ctx.equation.printed)]
    for t in terms:
        bad = not_in_s(sp.Matrix([[t]]), f"the termination {sp.sstr(t)}")
        if bad is not None:
            return bad
    results = [(sp.sstr(t), positive_real(sp.Matrix([[t]]))) for t in terms]
    facts: dict[str, Any] = {"decisions": {k: v.reason for k, v in results}}
    # the claim is the proposition "each of the n named terminations is positive real": what the
    # check proves about it (a mutant naming other PR terminations makes a claim proved the same way)
    facts["printed_form"] = ("claim: each named termination is positive real", tuple(r.decision.value for _, r in results))
    if all(r.decision == Decision.PROVED for _, r in results):
        return Finding(Verdict.CONFIRMED, f"each named scalar termination ({', '.join(k for k, _ in results)}) is positive real",
                       Evidence(Method.ROOT_ISOLATION, facts=facts))
    bad, result = next((k, r) for k, r in results if r.decision != Decision.PROVED)
    return Finding(Verdict.WRONG if result.decision == Decision.DISPROVED else Verdict.UNDECIDED,
                   f"{bad} is {'not' if result.decision == Decision.DISPROVED else 'not proved'} positive real ({result.reason})",
                   Evidence(result.evidence.method, witness=result.evidence.witness, facts=facts))


@PAPER.equation("1-nonpassive", kind="claim", after="1", section="2",
                printed="the coupled 3-DOF termination \\mathbf{T}_1 is non-passive",
                derivation="Definition 3 for the printed T_1 (and for the text's diagonal)")
def t1_nonpassive(ctx: AuditContext) -> Finding:
    T = printed_matrix("1")
    bad = not_in_s(T, "T_1 of (1)")
    if bad is not None:
        return Finding(Verdict.UNDECIDED, bad.detail, bad.evidence)
    variant = T.copy()
    text = text_diagonal()
    stray = not_in_s(sp.Matrix([list(text)]), "the terminations the text names (1-diagonal)")
    if stray is not None:
        return Finding(Verdict.UNDECIDED, f"cannot build the text's variant: {stray.detail}", Evidence(Method.PARSE))
    for i in range(min(3, len(text), T.rows)):
        variant[i, i] = text[i]
    printed, altered = positive_real(T), positive_real(variant)
    diagonal = [positive_real(sp.Matrix([[T[i, i]]])).decision == Decision.PROVED for i in range(min(T.rows, T.cols))]
    facts = {"as printed": pr_facts(printed), "text diagonal": pr_facts(altered), "diagonal_entries_pr": diagonal}
    if printed.decision == Decision.DISPROVED and altered.decision == Decision.DISPROVED:
        w = printed.hermitian.witness
        return Finding(Verdict.CONFIRMED,
                       f"T_1 (1) is not positive real: T_1(jw) + T_1(jw)^H has a negative principal minor at w = {w.get('omega', w)}; "
                       "with the text's diagonal it is not passive either (already at w = "
                       f"{altered.hermitian.witness.get('omega', altered.hermitian.witness)}), "
                       + ("although every diagonal entry is" if all(diagonal) else
                          f"and its diagonal entries {[i + 1 for i, ok in enumerate(diagonal) if not ok]} are not PR either"),
                       Evidence(Method.ROOT_ISOLATION, witness=dict(w), facts=facts))
    return Finding(Verdict.WRONG, f"T_1 as printed is {pr_text(printed)}; with the text's diagonal it is {pr_text(altered)}",
                   Evidence(printed.evidence.method, facts=facts))


@PAPER.equation("2", kind="expression", printed=PRINTED["2"], section="2", derivation="impedance form of the 2-port")
def eq2(ctx: AuditContext) -> Finding:
    L = TABLE.lookup
    return definition(ctx, "defines the 3-DOF teleoperator in impedance form: forces [F_h; F_e] (6x1) = Z (6x6) velocities",
                       sp.BlockMatrix([[L("F_h")], [L("F_e")]]), L(r"\mathcal{Z}") * sp.BlockMatrix([[L("V_h")], [L("V_e")]]))


@PAPER.equation("3", kind="expression", printed=PRINTED["3"], section="2", derivation="block partition")
def eq3(ctx: AuditContext) -> Finding:
    return definition(ctx, "partitions Z into 3x3 blocks Z_ij (port 1 = operator, port 2 = environment)", *partition_blocks())


def partition_blocks() -> tuple[Any, Any]:
    L = TABLE.lookup
    return L(r"\mathcal{Z}"), sp.BlockMatrix([[L(r"\mathbf{Z}_{11}"), L(r"\mathbf{Z}_{12}")],
                                              [L(r"\mathbf{Z}_{21}"), L(r"\mathbf{Z}_{22}")]])


@PAPER.equation("3a", kind="expression", printed=PRINTED["3a"], section="2", parse=False,
                derivation="the printed 6x6 impedance: open-circuit stability, symmetrization conditions", quotes=('5',))
def eq3a(ctx: AuditContext) -> Finding:
    from hapticproof.exact.rationalmatrix import pole_report

    Z = printed_matrix("3a", prefix=r"\mathcal{Z} ")
    bad = not_in_s(Z, "the impedance (3)")
    if bad is not None:
        return bad
    if Z.shape != (6, 6):
        return Finding(Verdict.MALFORMED, f"the impedance of (3) is {Z.shape[0]}x{Z.shape[1]}, not 6x6",
                       Evidence(Method.PARSE, facts={"printed_form": sp.srepr(Z)}))
    rep = RationalMatrix.from_sympy(Z)
    poles = pole_report(rep)
    # what the paper states about this network: its DOF subsystems are (5), it is potentially unstable
    p5 = printed_matrix("5")
    subsystems = [name for i, name in enumerate(AXES)
                  if p5.shape == (2, 2) and all(is_identically_zero(a - c) for a, c in zip(Z.extract([i, i + 3], [i, i + 3]), p5))]
    roots, degree, passive = certified("unit")
    sym = symmetrize(rep, (3, 3))
    properties = ("entries stable" if not poles.rhp else "an entry has an RHP pole",
                  f"DOF subsystems equal to (5): {subsystems}", f"unit terminations destabilise it: {bool(roots and passive)}")
    facts = {"symmetrization": sym.reason, "axis_poles": [p.label() for p, _ in poles.axis], "rhp_roots_unit": [str(r) for r in roots],
             "printed_form": ("data display; the properties the paper states about it", properties)}
    if poles.rhp:
        (i, j), root = poles.rhp[0]
        where = root.label() if hasattr(root, "label") else str(root)
        return Finding(Verdict.WRONG, f"entry ({i + 1}, {j + 1}) has a pole in Re s > 0 ({where}): the open-circuit network is "
                       "unstable", Evidence(Method.ROOT_ISOLATION, witness={"entry": [i + 1, j + 1], "pole": where}, facts=facts))
    if len(subsystems) != 3:
        return Finding(Verdict.INCONSISTENT, f"the DOF subsystems of (3) extracted at (i, i), (i, i+3), (i+3, i), (i+3, i+3) "
                       f"agree with (5) only for {subsystems or 'no DOF'}", Evidence(Method.CANONICAL_FORM,
                                                                                     facts={**facts, "ids": ["3a", "5"]}))
    if not (roots and passive):
        return Finding(Verdict.INCONSISTENT, "with unit resistive terminations det(Z + I) has no zero in Re s > 0, so the network "
                       "does not show the potential instability the text states (see 5-unstable)",
                       Evidence(Method.ROOT_ISOLATION, facts={**facts, "ids": ["3a", "5-unstable"]}))
    return Finding(Verdict.CONFIRMED,
                   "a well-formed 6x6 rational impedance (read as the continuation '\\mathcal{Z} = ...' of (3)) whose entries are "
                   f"all stable, whose DOF subsystems are (5) and which unit terminations destabilise (det(Z + I) = 0 at "
                   f"s ~ {roots[0].real:.6g}); it is not symmetrizable ({sym.reason}), so Theorem 9 does not apply to it",
                   Evidence(Method.PARSE, facts=facts))


@PAPER.equation("4", kind="expression", printed=PRINTED["4"], section="2", derivation="the 1-DOF subsystems")
def eq4(ctx: AuditContext) -> Finding:
    L = TABLE.lookup
    statement = ctx.statement
    ranges = [tuple(map(str, r.values)) for r in getattr(statement, "ranges", ())]
    if ranges != [("x", "y", "z")]:
        return Finding(Verdict.TYPO, f"the per-DOF 2-ports must range over the three DOFs i = x, y, z; the display has {ranges}",
                       Evidence(Method.PARSE, facts={"printed_form": ranges}))
    return definition(ctx, "defines the per-DOF 2-ports Z_i, i = x, y, z (entries (i, i), (i, i+3), (i+3, i), (i+3, i+3) of (3))",
                       sp.Matrix([[L("f_{hi}")], [L("f_{ei}")]]), L(r"\mathbf{Z}_i") * sp.Matrix([[L("v_{hi}")], [L("v_{ei}")]]))


@PAPER.equation("5", kind="expression", printed=PRINTED["5"], section="2",
                derivation="extract [[z_ii, z_i,i+3], [z_i+3,i, z_i+3,i+3]] from (3) for i = x, y, z", quotes=('3a',))
def eq5(ctx: AuditContext) -> Finding:
    rel = ctx.statement.relations()[0]
    names = tuple(rel.terms[:-1])
    expected = tuple(TABLE.lookup(rf"\mathbf{{Z}}_{a}") for a in AXES)
    printed = rhs_matrix(ctx)
    if names != expected:
        return Finding(Verdict.TYPO, f"the chain must name the three DOF subsystems Z_x = Z_y = Z_z; it reads "
                       f"{' = '.join(map(sp.sstr, names))}", Evidence(Method.PARSE, facts={"printed_form": [sp.srepr(x) for x in names]}))
    Z = section2_network()
    mismatched = []
    for i, name in enumerate(AXES):
        sub = Z.extract([i, i + 3], [i, i + 3])
        if printed.shape != (2, 2) or not all(is_identically_zero(a - b) for a, b in zip(sub, printed)):
            mismatched.append((name, sub))
    if mismatched:
        listing = "; ".join(f"Z_{n} = {one_line(sub)}" for n, sub in mismatched)
        return Finding(Verdict.TYPO, f"the printed {one_line(printed)} is not the subsystem extracted from (3): {listing}",
                       Evidence(Method.CANONICAL_FORM, facts={"printed_form": sp.srepr(printed)}))
    return Finding(Verdict.CONFIRMED, "Z_x, Z_y and Z_z extracted from (3) all equal the printed 2x2 matrix",
                   Evidence(Method.CANONICAL_FORM, facts={"subsystems": list(AXES), "printed_form": ("equals (3)",)}),
                   derived=printed)


@PAPER.equation("5-llewellyn", kind="claim", after="5", section="2",
                printed="the subsystems involving \\mathbf{Z}_x , \\mathbf{Z}_y , and \\mathbf{Z}_z always satisfy Llewellyn's criterion",
                derivation="Llewellyn's criterion decided exactly for (5)")
def subsystems_llewellyn(ctx: AuditContext) -> Finding:
    Z = printed_matrix("5")
    bad = not_in_s(Z, "the subsystem (5)")
    if bad is not None or Z.shape != (2, 2):
        return Finding(Verdict.UNDECIDED, "(5) is not a 2x2 transfer matrix in s", Evidence(Method.PARSE))
    result = llewellyn(Z)
    if result.decision != Decision.PROVED:
        return Finding(Verdict.WRONG, f"Llewellyn's criterion fails for (5): {result.reason}", result.evidence)
    where = result.tightest.argmin if result.tightest is not None else None
    w = sp.Symbol("w", positive=True)
    at = Z.subs(s, sp.I * w).applyfunc(lambda e: sp.expand_complex(sp.cancel(e)))
    P = sp.expand_complex(at[0, 1] * at[1, 0])
    modulus = sp.sqrt(sp.factor(sp.cancel(sp.expand(P * sp.conjugate(P)))))
    product = sp.factor(sp.cancel(2 * sp.re(at[0, 0]) * sp.re(at[1, 1]) - sp.re(P) - modulus))
    return Finding(Verdict.CONFIRMED,
                   f"Llewellyn's conditions hold exactly: 2 Re z11 Re z22 - Re z12z21 - |z12z21| = {sp.sstr(sp.factor(product))} >= 0; "
                   f"the stability factor is smallest at x = w^2 = {where} with eta = {result.eta_min}",
                   Evidence(result.evidence.method, witness=result.evidence.witness,
                            facts={**dict(result.evidence.facts), "printed_form": ("llewellyn holds", str(result.eta_min))}))


@PAPER.equation("5-unstable", kind="claim", after="5", section="2",
                printed="the coupled 3-DOF teleoperator (2) is not absolutely stable",
                derivation="search for passive 3-DOF terminations with a zero of det(Z + T) in Re s > 0, verified exactly")
def coupled_unstable(ctx: AuditContext) -> Finding:
    roots, degree, passive = certified("unit")
    sym = symmetrize(RationalMatrix.from_sympy(section2_network()), (3, 3))
    if roots and passive:
        return Finding(Verdict.CONFIRMED,
                       "unit resistors on all six DOFs (T_1 = T_2 = I_3, passive) already destabilize the network (3): "
                       f"det(Z + I) has a zero at s ~ {roots[0].real:.4g} > 0 (certified on the exact degree-{degree} numerator); "
                       f"(3) is not symmetrizable ({sym.reason}), so Theorem 9 does not apply to it",
                       Evidence(Method.COUNTEREXAMPLE, witness={"T_1": "I_3", "T_2": "I_3"},
                                facts={"rhp_roots": [str(r) for r in roots], "numerator_degree": degree}))
    cert = searched_terminations("3a")
    if cert is None:
        return Finding(Verdict.UNDECIDED, "no destabilizing termination found (not symmetrizable, so Youla does not decide)",
                       Evidence(Method.INSTANCES))
    return Finding(Verdict.CONFIRMED,
                   f"passive RLC terminations T_1, T_2 (3x3, positive real) put zeros of det(Z + T) at s ~ {cert.roots[0]:.4g} "
                   "(certified, Re s > 0): the network (3) is potentially unstable",
                   Evidence(Method.COUNTEREXAMPLE, facts=certificate_facts(cert)))


def _scalar_counterexample() -> tuple[sp.Matrix, sp.Matrix]:
    """A potentially unstable reciprocal 2-port and a passive load making its input passive."""
    return sp.Matrix([[1, 3], [3, 1]]), sp.Matrix([[10]])


ENERGY_TABLE = TABLE.with_functions({name: sp.Function(name.replace("{", "").replace("}", ""))
                                     for name in ("F_h", "V_h", "F_e", "V_e", "f_{hx}", "v_{hx}", "f_{ex}", "v_{ex}", "E_s")})


def _energy_reading(ctx: AuditContext, three_dof: bool) -> Finding | None:
    """The display must be the input energy at port 1 from rest, E_s(t) = int_0^t force . velocity >= 0."""
    tau, t = TABLE.lookup(r"\tau"), TABLE.lookup("t")
    force, velocity = ("F_h", "V_h") if three_dof else ("f_hx", "v_hx")
    statement = parse_printed(ctx.equation.printed, ENERGY_TABLE)
    relations = statement.relations()
    expected = sp.Integral(sp.Function(force)(tau) * sp.Function(velocity)(tau), (tau, 0, t))
    if len(relations) != 1:
        return malformed(ctx, f"expected one relation chain, found {len(relations)}")
    rel = relations[0]
    ok = (rel.ops == ("=", ">=") and rel.terms[0] == sp.Function("E_s")(t) and rel.terms[1] == expected and rel.terms[2] == 0)
    if ok:
        return None
    return Finding(Verdict.WRONG, f"the display must be the input energy at port 1, E_s(t) = int_0^t {force} {velocity} dtau >= 0; "
                   f"it reads {' '.join(f'{sp.sstr(x)} {op}' for x, op in zip(rel.terms, rel.ops))} {sp.sstr(rel.terms[-1])}",
                   Evidence(Method.PARSE, facts={"printed_form": sp.srepr(rel.as_sympy())}))


def _energy_quantifier(ctx: AuditContext, three_dof: bool) -> Finding:
    reading = _energy_reading(ctx, three_dof)
    if reading is not None:
        return reading
    Z2, load = _scalar_counterexample()
    Z = sp.kronecker_product(Z2, sp.eye(3)) if three_dof else Z2
    ports = (3, 3) if three_dof else (1, 1)
    termination = sp.kronecker_product(load, sp.eye(3)) if three_dof else load
    verdict = absolute_stability(Z, ports=ports, search=False)
    zin = positive_real(input_impedance(Z, termination, ports))
    if verdict.decision == Decision.DISPROVED and zin.decision == Decision.PROVED:
        return Finding(
            Verdict.NEEDS_ASSUMPTION,
            "true only when E_s(t) >= 0 is required for every passive termination of port 2 and every input from rest "
            "(i.e. the input impedance is positive real for all passive loads); for one termination it is necessary only: "
            f"the 2-port {'kron([[1, 3], [3, 1]], I_3)' if three_dof else '[[1, 3], [3, 1]]'} is potentially unstable, yet with "
            "the passive load 10 its input impedance 2/11 is positive real, so E_s >= 0 for every input",
            Evidence(Method.COUNTEREXAMPLE, witness={"Z": Z2, "load": load},
                     facts={"absolute_stability": verdict.reason, "input_impedance_PR": zin.reason,
                            "printed_form": "input energy at port 1 >= 0"}),
            corrected=(r"\text{absolutely stable} \iff E_s(t) \geq 0 \ \forall t > 0,\ \forall \text{inputs from rest},\ "
                       r"\forall \text{passive terminations of port 2}"),
        )
    return Finding(Verdict.UNDECIDED, "the counterexample did not behave as expected", verdict.evidence)


@PAPER.equation("6", kind="condition", printed=PRINTED["6"], section="2", parse=False,
                derivation="input energy vs absolute stability: quantifiers over terminations and inputs")
def eq6(ctx: AuditContext) -> Finding:
    return _energy_quantifier(ctx, three_dof=True)


@PAPER.equation("7", kind="condition", printed=PRINTED["7"], section="2", parse=False,
                derivation="as (6) for a 1-DOF subsystem")
def eq7(ctx: AuditContext) -> Finding:
    return _energy_quantifier(ctx, three_dof=False)


@PAPER.equation("prop4", kind="claim", after="7", section="3",
                printed="Property 4. A Hermitian matrix, i.e., a square matrix equal to its conjugate transpose, is positive "
                        "definite if its leading principal minors are all positive.",
                derivation="Sylvester's criterion, checked on exact instances; the paper later uses it with '>= 0'")
def property4(ctx: AuditContext) -> Finding:
    import random

    import flint

    def minors_positive(M: list[list[Fraction]], subsets) -> bool:
        for S in subsets:
            sub = flint.fmpq_mat([[flint.fmpq(M[i][j].numerator, M[i][j].denominator) for j in S] for i in S])
            if not sub.det() > 0:
                return False
        return True

    rng = random.Random(4)
    checked = 0
    for _ in range(150):
        n = rng.randint(2, 4)
        A = [[Fraction(0)] * n for _ in range(n)]
        B = [[Fraction(0)] * n for _ in range(n)]
        for i in range(n):
            A[i][i] = Fraction(rng.randint(-4, 8), rng.randint(1, 3))
            for j in range(i + 1, n):
                A[i][j] = A[j][i] = Fraction(rng.randint(-4, 4), rng.randint(1, 3))
                B[i][j] = Fraction(rng.randint(-2, 2), rng.randint(1, 3))
                B[j][i] = -B[i][j]
        # H = A + jB is positive definite iff the real embedding [[A, -B], [B, A]] is
        M = [A[i] + [-b for b in B[i]] for i in range(n)] + [B[i] + A[i] for i in range(n)]
        H_leading = [list(range(k)) for k in range(1, n + 1)]
        leading_positive = all(
            sp.expand(sp.Matrix(k, k, lambda a, b: sp.Rational(A[a][b]) + sp.I * sp.Rational(B[a][b])).det()) > 0
            for k in range(1, n + 1)) if minors_positive(A, H_leading[:1]) else False
        if leading_positive:
            checked += 1
            everything = [list(S) for k in range(1, 2 * n + 1) for S in itertools.combinations(range(2 * n), k)]
            if not minors_positive(M, everything):
                return Finding(Verdict.WRONG, "a Hermitian matrix with positive leading minors that is not PD",
                               Evidence(Method.COUNTEREXAMPLE, witness={"A": str(A), "B": str(B)}))
    A = sp.Matrix([[0, 0], [0, -1]])
    return Finding(Verdict.CONFIRMED,
                   "Sylvester's criterion: positive leading minors imply positive definiteness (confirmed on "
                   f"{checked} exact Hermitian instances); note that with '>= 0' it fails ([[0, 0], [0, -1]]), which is "
                   "how conditions D, E and (39)-(45) use it",
                   Evidence(Method.INSTANCES, instances=checked, facts={"semidefinite_counterexample": A}))
