r"""HVE paper, Section 3.2: which aggregate of the per-user values makes the worst case of (44)
uniform, and the m-user passivity conditions (45)-(54) -- sufficient uniform conditions, their worst cases (which aggregate of the per-user values makes them sufficient,
claims ``44-worst``, ``51-worst``) and the dual-user reductions.
"""

from __future__ import annotations

import itertools
import random
from functools import cache, lru_cache
from typing import Any

import sympy as sp

from hapticproof.audit.runner import AuditContext
from hapticproof.audit.compare import NotABound, as_bound, as_sign_condition, compare_bounds, compare_expressions, compare_sign_conditions, relation
from hapticproof.exact.canonical import is_identically_zero
from hapticproof.core.errors import LatexParseError
from hapticproof.core.evidence import Decision, Evidence, Finding, Method, Verdict
from hapticproof.systems.multiuser import MultiUserScene, complete_graph, inverse_transfer_matrix, stiffness_matrix, damping_matrix, user_symbols
from hapticproof.analysis.multiuser import hermitian, kernel_bounds, principal_minors, sufficient_condition, uniform_condition
from hapticproof.audit.reader.statements import IndexedExtremum, IndexedMin, expand_indexed
from hapticproof.audit.reader.printed import parse_printed
from hapticproof.exact.psd import PolyRing
from hapticproof.exact.charpoly import is_psd
from hapticproof.core.symbols import c as C
from hapticproof.derivations.hve.paper import ASSUME, B, K, PAPER, T, b, omega, t_d, z_a
from hapticproof.derivations.hve.users_model import B_0, B_SUM, K_0, K_SUM, M_COUNT, NotInC, SECTION, Z0, align, decide, decision_facts, det_chain, det_relation, display, hermitian_matrix, leading_minor_entry, lhs_means_inverse, matrix_mismatch, matrix_of, minor_in_c, not_ginv, not_in_c, not_pr, numeric_users, pr, printed_in_c, psd_by_strict_leading, residue_at_one, same_condition, scene_values, uniform_names, uniform_subs, users_scene, witness_json


def _quoted_choices(ctx: AuditContext) -> tuple[dict[sp.Symbol, Any], Any]:
    """The aggregates a claim chooses (``$b = \\min(b_1, b_2)$`` ...) and the worst frequency it
    names (``$\\cos(\\omega T) = -1$``, or None), parsed from its quoted mathematics."""
    from hapticproof.audit.runner import quoted_math

    choices: dict[sp.Symbol, Any] = {}
    worst_c = None
    for quote in quoted_math(ctx.equation.printed):
        for rel in parse_printed(quote, PAPER.symbols).relations():
            r = rel.as_sympy()
            if not isinstance(r, sp.Eq):
                continue
            if r.lhs == sp.cos(omega * T):
                worst_c = r.rhs
            elif isinstance(r.lhs, sp.Symbol) and r.lhs in (b, K_0, B_0, K, B):
                choices[r.lhs] = r.rhs
            elif r.atoms(sp.cos, sp.sin) or omega in r.free_symbols:
                worst_c = _frequency_named(r)
    return choices, worst_c


def _frequency_named(relation: sp.Eq) -> Any:
    """The ``c = cos(omega T)`` a printed frequency statement names (``2 cos(omega T) = -1`` ->
    -1/2); the relation itself when it names no single c (it then matches no derived c)."""
    if omega not in relation.free_symbols:
        return relation
    try:
        roots = sp.solve(printed_in_c(relation.lhs - relation.rhs), C)
    except (ValueError, NotImplementedError, sp.PolynomialError):
        return relation
    return roots[0] if len(roots) == 1 else relation


@lru_cache(maxsize=8)
def _worst_aggregates(m: int, delay: int, c_star: int) -> dict[sp.Symbol, str]:
    """Which aggregate of the per-user values gives the worst case at ``c = c_star``: ``min`` where
    M(c_star) grows with the parameter (Loewner order), ``max`` where it shrinks."""
    M = hermitian_matrix(MultiUserScene.uniform(m, delay=delay)).subs(C, c_star)
    out = {}
    for p in (b, K_0, B_0, K, B):
        slope = M.diff(p).subs(T, 1)
        eigen = [sp.nsimplify(v) for v in slope.eigenvals(multiple=True)]
        out[p] = "min" if all(v >= 0 for v in eigen) else "max" if all(v <= 0 for v in eigen) else "none"
    return out


def _worst_frequency(m: int) -> int:
    """The worst c of M(c) without delay: dM/dc = 2 Bmat is PSD, so M is smallest at c = -1."""
    slope = hermitian_matrix(MultiUserScene.uniform(m)).diff(C).subs(T, 1)
    eigen = slope.eigenvals(multiple=True)
    return -1 if all(sp.nsimplify(v).subs({B: 1, B_0: 1}) >= 0 for v in eigen) else 1


def _members(m: int) -> dict[sp.Symbol, set]:
    """The per-user symbols each uniform worst-case symbol aggregates."""
    sym = user_symbols(m)
    return {b: set(sym["b"]), K_0: set(sym["K0"]), B_0: set(sym["B0"]), K: set(sym["K"].values()), B: set(sym["B"].values())}


def _aggregate_kind(expr: Any) -> str:
    return "min" if isinstance(expr, sp.Min) else "max" if isinstance(expr, sp.Max) else f"the single value {sp.sstr(expr)}"


def worst_choice_claim(ctx: AuditContext, m: int, condition_id: str, scene: MultiUserScene, delay: int = 0,
                        c_star: int | None = None) -> Finding:
    """The claim's printed aggregates against the derived worst case; the referenced uniform
    condition evaluated with the printed aggregates at a witness scene."""
    choices, worst_c = _quoted_choices(ctx)
    c_star = _worst_frequency(m) if c_star is None else c_star
    derived = _worst_aggregates(m, delay, c_star)
    wrong = {p: (_aggregate_kind(v), derived[p]) for p, v in choices.items() if _aggregate_kind(v) != derived[p]}
    members = _members(m)
    stray = {p: v for p, v in choices.items() if set(getattr(v, "args", ())) != members[p]}
    users = scene_values(scene)
    values = {p: sp.sympify(v).xreplace(users) for p, v in choices.items()}
    for p in (b, K_0, B_0, K, B):      # aggregates the text does not choose: the derived one
        if p not in values:
            group = {b: scene.b, K_0: scene.K0, B_0: scene.B0, K: scene.K, B: scene.B}[p] or [0]
            values[p] = (min if derived[p] == "min" else max)(group)
    values[T] = scene.T
    values[t_d] = scene.delays[0] * scene.T
    condition = uniform_names(display(condition_id))
    at = condition.xreplace(values)
    holds = bool(at) if at in (sp.true, sp.false) else None
    printed_choices = {str(k): sp.sstr(v) for k, v in choices.items()}
    facts = {"printed_choices": printed_choices, "derived_aggregates": {str(k): v for k, v in derived.items()},
             "worst_c_printed": worst_c, "worst_c_derived": c_star, f"({condition_id})_at_witness": str(at),
             "printed_form": (tuple(sorted(printed_choices.items())), str(worst_c)), **decision_facts(scene)}
    corrected = ", ".join(f"{p} = {derived[p]}" for p in (b, K_0, B_0, K, B))
    c_wrong = worst_c is not None and worst_c != c_star
    if wrong or c_wrong or stray:
        listing = "; ".join([f"{p} = {sp.sstr(choices[p])} is the {got} where the worst case needs the {want}"
                             for p, (got, want) in wrong.items()]
                            + [f"{p} = {sp.sstr(v)} does not aggregate {sorted(map(str, members[p]))}" for p, v in stray.items()])
        if c_wrong:
            listing = (listing + "; " if listing else "") + f"the worst frequency is c = {c_star}, not {worst_c}"
        unchosen = [str(p) for p in (b, K_0, B_0, K, B) if p not in choices and len(members[p]) > 1]
        if unchosen:
            listing += f"; no choice printed for {', '.join(unchosen)} (the derived one is used)"
        if holds and not_pr(scene):
            return Finding(Verdict.WRONG,
                           f"with the printed choices ({listing}) ({condition_id}) holds at the witness while "
                           "the exact decision shows G^-1 is not PR (M(c) decreases in the Loewner order as the couplings "
                           "grow and increases with b)",
                           Evidence(Method.COUNTEREXAMPLE, witness=witness_json(scene), facts=facts), corrected=corrected)
        return Finding(Verdict.WRONG, f"the printed choices are not the worst case ({listing}); the witness scene does not "
                       f"separate them ({condition_id} "
                       f"{'holds' if holds else 'fails' if holds is not None else 'reads ' + sp.sstr(at)} at the witness)",
                       Evidence(Method.STRUCTURAL, facts=facts), corrected=corrected)
    return Finding(Verdict.CONFIRMED, f"the printed choices {printed_choices} are the worst case at c = {c_star} "
                   "(Loewner order of M(c))", Evidence(Method.STRUCTURAL, facts=facts))


@PAPER.equation("44-worst", kind="claim", after="44", section=SECTION,
                printed="The worst-case for (43)-(44) occurs when $\\cos(\\omega T) = -1$. With $b = \\min(b_1, b_2)$, "
                        "$B_0 = \\max(B_{01}, B_{02})$ and $K_0 = \\min(K_{01}, K_{02})$, the above two conditions will hold if",
                derivation="Loewner order: M(c) = 2diag(b) - T Kmat + 2c Bmat; smaller b, larger K, B decrease M")
def worst44(ctx: AuditContext) -> Finding:
    scene = numeric_users(b=[2, 2], T=1, K0=[1, 3], K=1, B0=[0, 0], B=0)
    return worst_choice_claim(ctx, 2, "46", scene)


P45 = r"(2b - K_0T - 2B_0)^2 + 2(2b - K_0T - 2B_0)(-K_{12}T - 2B_{12}) > 0"


@PAPER.equation("45", kind="condition", printed=P45, section=SECTION, assumptions=ASSUME,
                derivation="det M(-1) for uniform b, K_0, B_0: a(a - 2w), a = 2b - K_0T - 2B_0, w = K_12 T + 2B_12")
def eq45(ctx: AuditContext) -> Finding:
    rel = uniform_names(ctx.relation())
    Mu = hermitian_matrix(MultiUserScene.uniform(2)).subs(C, -1)
    det = sp.expand(Mu.det())
    sign = compare_sign_conditions(rel, sp.Gt(det, 0, evaluate=False), what="(45) as det M(-1) > 0")
    if sign.verdict != Verdict.CONFIRMED:
        return sign
    printed = as_sign_condition(rel).expr
    a = 2 * b - K_0 * T - 2 * B_0
    factored = sp.factor(printed)
    # where (45) alone is not enough: a < 0 (the first minor (43) at c = -1 fails) with (45) holding
    values = {b: sp.Rational(1, 10), K_0: 1, B_0: 0, K: 1, B: 0, T: 1}
    scene = MultiUserScene.uniform(2, b=values[b], K0=1, B0=0, K=1, B=0, T=1)
    holds = bool(rel.subs(values))
    facts = {"factored": factored, "det_M(-1)": det, "region": sp.Gt(a, 0), "printed_form": sign.evidence.facts["printed_form"],
             "a_at_witness": a.subs(values), **decision_facts(scene)}
    if not (holds and a.subs(values) < 0 and not_pr(scene)):
        return Finding(Verdict.UNDECIDED, f"(45) reads {factored} > 0 = det M(-1) > 0 ({sign.detail}), but the a < 0 "
                       "witness did not separate it from the PR condition", Evidence(Method.INSTANCES, facts=facts))
    return Finding(
        Verdict.NEEDS_ASSUMPTION,
        f"(45) reads {sp.sstr(factored)} > 0, exactly det M(-1) > 0 for uniform parameters (a(a - 2w) with a = 2b - K_0T - 2B_0, "
        f"w = K_12T + 2B_12); alone it also holds for a < 0 (at the witness a = {a.subs(values)}), where (43) fails and G^-1 "
        "is not PR: it needs a > 0 (the first minor at c = -1), and on a > 0 it is equivalent to a > 2w, i.e. (46)",
        Evidence(Method.COUNTEREXAMPLE, witness={str(k): v for k, v in values.items()}, facts=facts),
        derived=relation(sp.Gt, det, 0),
        corrected=r"(2b - K_0T - 2B_0)^2 + 2(2b - K_0T - 2B_0)(-K_{12}T - 2B_{12}) > 0, \quad 2b - K_0T - 2B_0 > 0",
    )


def _random_scene(rng: random.Random, m: int, delays: int = 0, damped: bool = True) -> MultiUserScene:
    R = lambda lo, hi: sp.Rational(rng.randint(lo, hi), 20)  # noqa: E731
    return MultiUserScene.from_values(
        b=[R(10, 80) for _ in range(m)], T=sp.Rational(1, 10), K0=[R(1, 60) for _ in range(m)],
        K={e: R(1, 30) for e in complete_graph(m)}, B0=[R(0, 4) if damped else 0 for _ in range(m)],
        B={e: R(0, 2) if damped else 0 for e in complete_graph(m)}, delays=delays)


def _sufficiency_instances(bound_of, m_range=range(2, 9), per_m: int = 4, delays: int = 0, damped: bool = True,
                           seed: int = 3) -> dict[str, Any]:
    """Random non-uniform exact instances put just above a printed bound on ``min_i b_i``
    (``bound_of(scene)``); the exact decision must prove PR for each. ``failure`` holds the first
    instance where the printed condition holds and PR fails (None when all are PR)."""
    rng = random.Random(seed)
    checked = 0
    for m in m_range:
        for _ in range(per_m):
            scene = _random_scene(rng, m, delays, damped)
            bound = bound_of(scene)
            if not (bound.is_number and bound.is_real):
                return {"instances": checked, "failure": None, "unevaluated_bound": str(bound)}
            low = max(bound, 0) + sp.Rational(rng.randint(1, 20), 1000)
            extra = [0] + [sp.Rational(rng.randint(0, 40), 100) for _ in range(m - 1)]
            rng.shuffle(extra)
            scene = MultiUserScene.from_values(b=[low + e for e in extra], T=scene.T, K0=list(scene.K0),
                                               K=dict(zip(scene.edges, scene.K)), B0=list(scene.B0),
                                               B=dict(zip(scene.edges, scene.B)), delays=delays)
            if decide(scene) != Decision.PROVED:
                return {"instances": checked, "failure": scene, "m": m}
            checked += 1
    return {"instances": checked, "m": f"{m_range.start}..{m_range.stop - 1}", "all_positive_real": True, "failure": None}


@PAPER.equation("46", kind="condition", printed=r"b > \frac{K_0 T}{2} + K_{12} T + B_0 + 2B_{12} \tag{46}",
                section=SECTION, assumptions=ASSUME + "; b = min b_i, K_0 = max K_0i, B_0 = max B_0i (see 44-worst)",
                derivation="uniform m = 2: eigenvalues of M(-1) are a and a - 2w; Loewner bound for the general case")
def eq46(ctx: AuditContext) -> Finding:
    return _uniform_conservative(uniform_names(ctx.relation()), 2, "(46)")


def _uniform_conservative(printed: sp.Basic, m: int, label: str) -> Finding:
    """A printed uniform condition (b, K_0, B_0, K, B) vs the exact uniform condition, plus the
    Loewner argument that the max-aggregated version is sufficient for any parameters."""
    exact = uniform_condition(m).xreplace({z_a: 0})
    cmp = compare_bounds(printed, sp.Ge(exact.lhs, exact.rhs), b, what=label)
    if cmp.verdict != Verdict.CONFIRMED:
        return Finding(cmp.verdict, f"{label} is not the exact uniform PR condition {sp.sstr(exact)}: {cmp.detail}",
                       cmp.evidence, derived=exact, corrected=cmp.corrected)
    bound = as_bound(printed, b).bound

    # general (non-uniform) parameters: sufficient by Loewner monotonicity; not necessary (witness)
    def values(scene: MultiUserScene) -> dict:
        return {b: min(scene.b), K_0: max(scene.K0), B_0: max(scene.B0), K: max(scene.K), B: max(scene.B), T: scene.T}

    checks = _sufficiency_instances(lambda sc: bound.subs(values(sc)), m_range=range(m, m + 1), per_m=10)
    witness = numeric_users(b=[sp.Rational(5, 2)] + [sp.Rational(1, 2)] * (m - 1), T=1, K0=[2] + [sp.Rational(1, 10)] * (m - 1),
                       K=sp.Rational(1, 100), B0=0, B=0)
    fails_at_witness = not bool(values(witness)[b] > bound.subs(values(witness)))
    facts = {"exact_uniform": exact, "non_uniform_checks": {k: v for k, v in checks.items() if k != "failure"},
             "printed_form": cmp.evidence.facts.get("printed_form"), **decision_facts(witness)}
    if checks["failure"] is not None:
        return Finding(Verdict.WRONG, f"{label} reads b > {sp.sstr(bound)} (exact for uniform parameters), but with b = min "
                       "b_i and the maxima of the couplings it holds at the witness while G^-1 is not PR",
                       Evidence(Method.COUNTEREXAMPLE, witness=witness_json(checks["failure"]), facts=facts), derived=exact)
    if not (fails_at_witness and pr(witness)):
        return Finding(Verdict.UNDECIDED, f"{label} reads b > {sp.sstr(bound)}, exact for uniform parameters; the "
                       "non-uniform witness did not show it is not necessary", Evidence(Method.INSTANCES, facts=facts),
                       derived=exact)
    return Finding(
        Verdict.CONSERVATIVE,
        f"for uniform parameters {label} (b > {sp.sstr(bound)}) is exactly the PR condition (eigenvalues of M(-1): "
        f"2b - K_0T - 2B_0 and, with multiplicity m - 1, 2b - K_0T - 2B_0 - m(KT + 2B)); for general parameters, with "
        f"b = min b_i and maxima of the couplings it is sufficient (Loewner order; {checks['instances']} exact non-uniform "
        "instances PR) but not necessary: at the witness it fails while G^-1 is PR",
        Evidence(Method.STRUCTURAL, witness=witness_json(witness), facts=facts),
        derived=exact,
    )


P46A = (r"\begin{split} G^{-1}(z) &= \\ \begin{bmatrix} b_1 + \frac{K_1T}{z-1} + \frac{B_1}{z} & -(\frac{K_{12}T}{z-1} + \frac{B_{12}}{z}) & "
        r"-(\frac{K_{13}T}{z-1} + \frac{B_{13}}{z}) \\ -(\frac{K_{12}T}{z-1} + \frac{B_{12}}{z}) & b_2 + \frac{K_2T}{z-1} + \frac{B_2}{z} & "
        r"-(\frac{K_{23}T}{z-1} + \frac{B_{23}}{z}) \\ -(\frac{K_{13}T}{z-1} + \frac{B_{13}}{z}) & -(\frac{K_{23}T}{z-1} + \frac{B_{23}}{z}) & "
        r"b_3 + \frac{K_3T}{z-1} + \frac{B_3}{z} \end{bmatrix} \end{split}")


def coupling_sums(m: int) -> dict:
    scene = users_scene(m)
    Km, Bm = stiffness_matrix(scene), damping_matrix(scene)
    out = {K_SUM[i + 1]: Km[i, i] for i in range(m)}
    out.update({B_SUM[i + 1]: Bm[i, i] for i in range(m)})
    return out


@PAPER.equation("46a", kind="expression", printed=P46A, section=SECTION, assumptions=ASSUME,
                derivation="G^-1(z) = diag(b) + Kmat T/(z-1) + Bmat/z for m = 3, with K_i, B_i the diagonal sums")
def eq46a(ctx: AuditContext) -> Finding:
    wrong_lhs = not_ginv(ctx.statement)
    if wrong_lhs is not None:
        return wrong_lhs
    printed = matrix_of(ctx.statement).xreplace(coupling_sums(3))
    derived = inverse_transfer_matrix(users_scene(3))
    finding = matrix_mismatch(printed, derived, "the printed 3x3 G^-1")
    if finding.verdict == Verdict.CONFIRMED:
        return Finding(Verdict.CONFIRMED, "the printed 3x3 G^-1 (with K_i = K_0i + sum_k K_ik, B_i likewise) equals the "
                       "derived matrix entry by entry", finding.evidence, derived=derived)
    return finding


P46B = (r"K_1 = K_{01} + K_{12} + K_{13}, K_2 = K_{02} + k_{12} + K_{23}, K_3 = K_{03} + k_{13} + K_{23}, "
        r"B_1 = B_{01} + B_{12} + B_{13}, B_2 = B_{02} + B_{12} + B_{23}, B_3 = B_{03} + B_{13} + B_{23}")


@PAPER.equation("46b", kind="expression", printed=P46B, section=SECTION, assumptions=ASSUME,
                derivation="K_i = Kmat_ii = K_0i + sum_k K_ik and B_i = Bmat_ii (inline definitions after the 3x3 G^-1)")
def eq46b(ctx: AuditContext) -> Finding:
    sums = coupling_sums(3)
    wrong = []
    seen = []
    for rel in ctx.statement.relations():
        lhs, rhs = rel.lhs, align(rel.rhs)
        if lhs not in sums or len(rel.terms) != 2 or rel.ops != ("=",):
            wrong.append((sp.sstr(lhs), sp.sstr(rhs), "not one of the sums K_i, B_i"))
            continue
        seen.append(lhs)
        if not is_identically_zero(rhs - sums[lhs]):
            wrong.append((str(lhs), sp.sstr(rhs), sp.sstr(sums[lhs])))
    missing = sorted(map(str, set(sums) - set(seen)))
    if not wrong and not missing:
        return Finding(Verdict.CONFIRMED, "all six sums are the diagonal entries of Kmat and Bmat",
                       Evidence(Method.CANONICAL_FORM, instances=6))
    undefined = sorted({str(s_) for rel in ctx.statement.relations() for s_ in align(rel.rhs).free_symbols
                        if s_.name in ("k_12", "k_13")})
    listing = "; ".join(f"{a} = {b_} (derived {c_})" for a, b_, c_ in wrong)
    return Finding(
        Verdict.TYPO,
        (f"lower-case {', '.join(undefined)} name symbols the paper never defines (the matrix above and R_0 in (47) use the "
         "coupling stiffnesses K_ij); " if undefined else "") + f"the printed sums differ from the diagonal entries of "
        f"Kmat, Bmat: {listing}" + (f"; missing: {missing}" if missing else ""),
        Evidence(Method.COUNTEREXAMPLE, facts={"mismatches": wrong, "missing": missing}),
        corrected=(r"K_1 = K_{01} + K_{12} + K_{13}, K_2 = K_{02} + K_{12} + K_{23}, K_3 = K_{03} + K_{13} + K_{23}, "
                   r"B_1 = B_{01} + B_{12} + B_{13}, B_2 = B_{02} + B_{12} + B_{23}, B_3 = B_{03} + B_{13} + B_{23}"),
    )


P47 = (r"R_{0} =" + "\n" + r"\begin{bmatrix} (K_{01} + K_{12} + K_{13})T & -K_{12}T & -K_{13} \\ -K_{12}T & (K_{02} + K_{12} + K_{23})T \\ "
       r"-K_{13}T & -K_{23}T & (K_{03} + K_{13} + K_{23}) \end{bmatrix}")


@PAPER.equation("47", kind="expression", printed=P47, section=SECTION, assumptions=ASSUME,
                derivation="residue matrix at z = 1 for m = 3: T Kmat")
def eq47(ctx: AuditContext) -> Finding:
    derived = residue_at_one(3)
    rows_text = ctx.equation.printed.split(r"\begin{bmatrix}")[1].split(r"\end{bmatrix}")[0].split(r"\\")
    head = ctx.equation.printed.split(r"\begin{bmatrix}")[0]
    lhs_text, _, factor_text = head.partition("=")
    problems = []
    lhs = "".join(ch for ch in lhs_text if ch not in " \n{}")       # R_0 is a name of the text, not of the table
    if lhs != "R_0":
        problems.append(f"the left side reads {lhs or 'nothing'}, not R_0")
    # a factor printed in front of the matrix multiplies every entry
    factor = parse_printed(factor_text, PAPER.symbols).expressions()[0] if factor_text.strip() else sp.Integer(1)
    rows = [[factor * align(parse_printed(cell, PAPER.symbols).expressions()[0]) for cell in row.split("&")] for row in rows_text]
    for i, row in enumerate(rows):
        if len(row) != 3:
            problems.append(f"row {i + 1} has {len(row)} entries (the entry -K_{{{i + 1}3}}T is missing)")
        for j, entry in enumerate(row[:3]):
            if not is_identically_zero(entry - derived[i, j]):
                problems.append(f"entry ({i + 1},{j + 1}) is {sp.sstr(entry)}, derived {sp.sstr(derived[i, j])}")
    try:
        ctx.statement
        parse_error = None
    except LatexParseError as err:
        parse_error = err.reason
    if not problems:
        return Finding(Verdict.CONFIRMED, "R_0 = T Kmat entry by entry", Evidence(Method.CANONICAL_FORM), derived=derived)
    return Finding(
        Verdict.TYPO,
        "R_0 = T Kmat, but the printed matrix drops the factor T in two entries and the (2,3) entry: " + "; ".join(problems),
        Evidence(Method.CANONICAL_FORM, facts={"parse_error": parse_error, "problems": problems}),
        derived=derived,
        corrected=(r"R_0 = T\,K_{mat}:\ (R_0)_{13} = -K_{13}T,\ (R_0)_{23} = (R_0)_{32} = -K_{23}T,\ "
                   r"(R_0)_{33} = (K_{03} + K_{13} + K_{23})T"),
    )


@PAPER.equation("48", kind="condition", printed=r"(K_{01} + K_{12} + K_{13})T > 0 (48)", section=SECTION, assumptions=ASSUME,
                derivation="first leading principal minor of R_0 (m = 3)")
def eq48(ctx: AuditContext) -> Finding:
    return leading_minor_entry(ctx.relation(), residue_at_one(3)[0, 0], "the printed minor")


@PAPER.equation("49", kind="condition",
                printed=r"((K_{01}+K_{13})(K_{02}+K_{23})+K_{12}(K_{01}+K_{02}+K_{13}+K_{23}))T^2 > 0",
                section=SECTION, assumptions=ASSUME, derivation="second leading principal minor of R_0 (m = 3)")
def eq49(ctx: AuditContext) -> Finding:
    return leading_minor_entry(ctx.relation(), sp.expand(residue_at_one(3)[:2, :2].det()), "the printed 2x2 minor")


P49A = (r"det(R_0) = K_{01}K_{02}K_{03} + (K_{01} + K_{02} + K_{03})(K_{12}K_{13} + K_{12}K_{23} + K_{13}K_{23}) + "
        r"K_{01}K_{02}(K_{13} + K_{23}) + K_{01}K_{03}(K_{12} + K_{23}) + K_{02}K_{03}(K_{12} + K_{13}) > 0")


@PAPER.equation("49a", kind="condition", printed=P49A, section=SECTION, assumptions=ASSUME,
                derivation="det T Kmat = T^3 det Kmat (matrix-forest expansion of det(diag(K_0) + L_K))")
def eq49a(ctx: AuditContext) -> Finding:
    def mismatch(printed: sp.Expr, det: sp.Expr) -> Finding:
        ratio = sp.factor(sp.cancel(det / printed))
        if ratio.free_symbols <= {T} and _provable_positive(ratio) and ratio != 1:
            return Finding(
                Verdict.TYPO,
                f"the printed polynomial is det(R_0)/({sp.sstr(ratio)}): det(R_0) = det(T Kmat) = T^3 det(Kmat), so the "
                f"display misses the factor {sp.sstr(ratio)} (the sign, hence the condition, is unaffected for T > 0)",
                Evidence(Method.CANONICAL_FORM, facts={"derived_over_printed": ratio, "printed_form": sp.srepr(printed)}),
                derived=det,
                corrected=(r"\det(R_0) = (K_{01}K_{02}K_{03} + (K_{01} + K_{02} + K_{03})(K_{12}K_{13} + K_{12}K_{23} + K_{13}K_{23}) + "
                           r"K_{01}K_{02}(K_{13} + K_{23}) + K_{01}K_{03}(K_{12} + K_{23}) + K_{02}K_{03}(K_{12} + K_{13}))T^3 > 0"),
            )
        return compare_expressions(printed, det, on_mismatch=Verdict.WRONG, what="the printed det(R_0)")

    return det_chain(det_relation(ctx, residue_at_one(3)), residue_at_one(3), "det(R_0)", mismatch)


def _provable_positive(expr: sp.Expr) -> bool:
    return bool(sp.factor(expr).is_positive)


@PAPER.equation("49-psd", kind="claim", after="49a", section=SECTION,
                printed="R_0 is a Hermitian matrix and based on Definition 3 it is positive semidefinite since",
                derivation="strictly positive leading minors (Sylvester) and all principal minors of T Kmat (m = 3)")
def psd49(ctx: AuditContext) -> Finding:
    return psd_by_strict_leading(3)


P49B = r"b_{1} - \frac{(K_{01} + K_{12} + K_{13})T}{2} + (B_{01} + B_{12} + B_{13})\cos(\omega T) > 0"


@PAPER.equation("49b", kind="condition", printed=P49B, section=SECTION, assumptions=ASSUME,
                derivation="first leading principal minor of M/2 (m = 3)")
def eq49b(ctx: AuditContext) -> Finding:
    return minor_in_c(ctx.relation(), sp.expand(hermitian_matrix(users_scene(3))[0, 0] / 2), "the printed first minor (in c)")


P50 = r"det(G(e^{j\omega T}) + G^{T}(e^{-j\omega T})) = 0"


@PAPER.equation("50", kind="condition", printed=P50, section=SECTION, assumptions=ASSUME,
                derivation="det M(c) for m = 3 is not identically zero; the display is the left half of (51)")
def eq50(ctx: AuditContext) -> Finding:
    values = {s: v for s, v in zip(sorted(users_scene(3).parameters, key=str), itertools.cycle([2, 1, 3, 1, 5, 2]))}
    facts = lhs_means_inverse(ctx.equation.printed, 3, values, full=True)
    relations = facts.pop("relations")
    if len(relations) != 1 or len(relations[0][2]) != 2:
        raise LatexParseError(f"expected one relation det(...) = value, found {relations}", ctx.equation.printed, 0)
    kind, ops, (_, rhs) = relations[0]
    det = principal_minors(users_scene(3))[(0, 1, 2)].expr()
    meant, derived = facts["det_with_G_read_as_inverse"], facts["det_M"]
    facts["printed_form"] = (str(meant), str(facts["det_with_G_literal"]), str(rhs), ops)
    head = ("its left side is det M with G read as G^-1" if meant == derived else
            f"its left side is not even det M with G read as G^-1 ({sp.sstr(meant)} vs det M = {sp.sstr(derived)})")
    if ops == ("=",) and rhs.is_number and meant != rhs:
        what = (f"the display reads det(...) = {sp.sstr(rhs)}, an identity that is false (at the witness z = (3 + 4j)/5 "
                f"the printed determinant is {sp.sstr(meant)} with G read as G^-1 and {sp.sstr(facts['det_with_G_literal'])} "
                f"with G itself); {head}: the layout split the inequality of (51) into its left-hand side, with "
                f"'= {sp.sstr(rhs)}' in place of '='")
        return Finding(Verdict.MALFORMED, what,
                       Evidence(Method.PARSE, witness={"z": Z0, **{str(k): v for k, v in values.items()}}, facts=facts),
                       derived=relation(sp.Gt, det, 0),
                       corrected=r"\det(G^{-1}(e^{j\omega T}) + G^{-T}(e^{-j\omega T})) = (\text{the expression of (51)}) > 0")
    return Finding(Verdict.UNDECIDED, f"the display relates det(...) {ops[0]} {sp.sstr(rhs)}; {head}; it is not an identity the audit can "
                   "refute at the witness", Evidence(Method.INSTANCES, facts=facts), derived=relation(sp.Gt, det, 0))


P51 = (r"(2b_{1} - (K_{01} + K_{12} + K_{13})T + 2(B_{01} + B_{12} + B_{13})\cos(\omega T))(2b_{2} - (K_{02} + K_{12} + K_{23})T + "
       r"2(B_{02} + B_{12} + B_{23})\cos(\omega T)) (2b_{3} - (K_{03} + K_{13} + K_{23})T + 2(B_{03} + B_{13} + B_{23})\cos(\omega T)) - "
       r"2(K_{12}T + 2B_{12})(K_{13}T + 2B_{13})(K_{23}T + 2B_{23}) - (2b_{1} - (K_{01} + K_{12} + K_{13})T + 2(B_{01} + B_{12} + B_{13})"
       r"\cos(\omega T))(K_{23}T + 2B_{23})^{2} - (2b_{2} - (K_{02} + K_{12} + K_{23})T + 2(B_{02} + B_{12} + B_{23})\cos(\omega T))"
       r"(K_{13}T + 2B_{13})^{2} - (2b_{3} - (K_{03} + K_{13} + K_{23})T - 2(B_{03} + B_{13} + B_{23})\cos(\omega T))(K_{12}T + 2B_{12})^{2} > 0")


C51 = (r"d_1 d_2 d_3 + 2w_{12}w_{13}w_{23} - d_1 w_{23}^2 - d_2 w_{13}^2 - d_3 w_{12}^2 > 0,\quad "
       r"d_i = 2b_i - K_iT + 2B_i\cos(\omega T),\ w_{ij} = K_{ij}T - 2B_{ij}\cos(\omega T)")


@PAPER.equation("51", kind="condition", printed=P51, section=SECTION, assumptions=ASSUME,
                derivation="det of M = diag(d) + [w_ij] (m = 3): d1 d2 d3 + 2 w12 w13 w23 - sum d_i w_jk^2, w_ij = K_ij T - 2B_ij c")
def eq51(ctx: AuditContext) -> Finding:
    rel = ctx.relation()
    condition = as_sign_condition(rel)
    try:
        printed = align(printed_in_c(condition.expr))
    except NotInC as err:
        return not_in_c("the printed determinant condition", err)
    det = sp.expand(principal_minors(users_scene(3))[(0, 1, 2)].expr())
    diff = sp.expand(printed - det)
    form = (condition.op, sp.srepr(printed))
    if diff == 0 and condition.op in (">", ">="):
        return Finding(Verdict.CONFIRMED, "the printed expression is det M(c), required positive",
                       Evidence(Method.CANONICAL_FORM, facts={"printed_form": ("equals the derived", sp.srepr(det))}),
                       derived=relation(sp.Gt, det, 0))
    at_minus_one = sp.factor(diff.subs(C, -1))
    # a sign disagreement: the printed condition holds while det M < 0, at exact rational parameters and c
    rng = random.Random(5)
    ring = PolyRing.over(users_scene(3).parameters)
    printed_el, det_el = ring.from_expr(printed), ring.from_expr(det)
    params = ring.params
    witness = None
    holds = {">": lambda v: v > 0, ">=": lambda v: v >= 0, "=": lambda v: v == 0, "!=": lambda v: v != 0}[condition.op]
    for _ in range(400):
        point = {p: sp.Rational(rng.randint(1, 30), 10) for p in params}
        point[C] = sp.Rational(rng.randint(-10, 10), 10)
        pv = ring.substitute(printed_el, point).coeffs()
        dv = ring.substitute(det_el, point).coeffs()
        pv, dv = (pv[0] if pv else 0), (dv[0] if dv else 0)
        if holds(pv) and dv < 0:
            witness = point
            break
    short = sp.sstr(at_minus_one)
    gap = f"printed - det M at c = -1: {short if len(short) < 150 else 'a polynomial of ' + str(len(sp.Add.make_args(sp.expand(at_minus_one)))) + ' terms'}"
    facts = {"printed_minus_det_at_c=-1": at_minus_one, "printed_form": form}
    if witness is None:
        return Finding(Verdict.UNDECIDED, f"the printed condition ({condition.op} 0) is not det M(c) > 0 ({gap}), but no "
                       "point where it holds while det M(c) < 0 was found in 400 exact samples",
                       Evidence(Method.INSTANCES, instances=400, facts=facts), derived=relation(sp.Gt, det, 0), corrected=C51)
    pv, dv = printed.xreplace(witness), det.xreplace(witness)
    facts.update({"printed_value": pv, "det_M_value": dv})
    return Finding(
        Verdict.WRONG,
        f"the printed expression is not det M(c) ({gap}); at the witness (c = {witness[C]}) the printed condition holds "
        f"({sp.sstr(pv)} {condition.op} 0) while det M(c) = {sp.sstr(dv)} < 0",
        Evidence(Method.COUNTEREXAMPLE, witness={str(k): v for k, v in witness.items()}, facts=facts),
        derived=relation(sp.Gt, det, 0), corrected=C51,
    )


@PAPER.equation("51-minors", kind="claim", after="51", section=SECTION,
                printed="Substituting $z = e^{j\\omega T} = \\cos(\\omega T) + j\\sin(\\omega T)$, the second condition in "
                        "Definition 2 for positive realness of $G^{-1}(z)$ will lead to the following conditions:",
                derivation="positive definiteness of a 3x3 matrix needs all three leading minors (or all principal minors)")
def minors51(ctx: AuditContext) -> Finding:
    scene = numeric_users(b=[10, sp.Rational(1, 10), sp.Rational(1, 10)], T=1, K0=[1, 1, 1], K=sp.Rational(1, 100), B0=0, B=0)
    H = hermitian(scene)
    M = H.at(-1)
    lead = [M[:k, :k].det() for k in (1, 2, 3)]
    if not (lead[0] > 0 and lead[2] > 0 and lead[1] < 0 and not_pr(scene)):
        return Finding(Verdict.UNDECIDED, f"the witness did not separate the two printed conditions from PSD (leading minors "
                       f"at c = -1: {lead})", Evidence(Method.INSTANCES, facts={"leading_minors_at_c=-1": lead}))
    return Finding(
        Verdict.WRONG,
        "for m = 3 the first leading minor and the determinant do not imply M(c) >= 0: the 2x2 leading minor is missing; at "
        "the witness (c = -1) both printed conditions hold while M has two negative eigenvalues",
        Evidence(Method.COUNTEREXAMPLE, witness={**witness_json(scene), "c": -1},
                 facts={"leading_minors_at_c=-1": lead, "psd_test": is_psd(M).coefficients, **decision_facts(scene)}),
        corrected=r"\text{all principal minors (or } E_1, E_2, E_3\text{) of } M(c) \ge 0 \text{ for } -1 \le c \le 1",
    )


@PAPER.equation("51-worst", kind="claim", after="51", section=SECTION,
                printed="The worst-case for the above conditions occurs when $\\cos(\\omega T) = -1$. With $B = \\min(B_{12}, "
                        "B_{13}, B_{23})$, $B_0 = \\max(B_{01}, B_{02}, B_{03})$, $K_0 = \\min(K_{01}, K_{02}, K_{03})$, "
                        "$K = \\min(K_{12}, K_{13}, K_{23})$ and $b = \\min(b_1, b_2, b_3)$, the above two conditions will hold if",
                derivation="Loewner order: the worst case needs the maxima of K_0i, K_ij, B_0i, B_ij")
def worst51(ctx: AuditContext) -> Finding:
    scene = numeric_users(b=[3, 3, 3], T=1, K0=[1, 1, 1], K={(0, 1): 1, (0, 2): 1, (1, 2): 3}, B0=0, B=0)
    return worst_choice_claim(ctx, 3, "53", scene)


P52 = r"(2b - K_0T - 2B_0 - 4B)^3 - 2(KT + 2B)^3 - 3(KT + 2B)^2(2b - K_0T - 2B_0 - 4B) > 0"


@cache
def _factor_list(expr: sp.Expr) -> tuple:
    """``sp.factor_list(expr)``, once per polynomial: (52) and the claim that simplifies it
    factor the same display."""
    return sp.factor_list(expr)


@cache
def _factor(expr: sp.Expr) -> sp.Expr:
    """``sp.factor(expr)``, once per polynomial (see :func:`_factor_list`)."""
    return sp.factor(expr)


def _solved(expr: sp.Expr) -> list[str]:
    """What ``expr > 0`` says about b, factor by factor (odd-multiplicity factors in b)."""
    out = []
    for factor, power in _factor_list(sp.expand(expr))[1]:
        if factor.has(b) and power % 2 == 1:
            try:
                out.append(str(as_bound(sp.Gt(factor, 0, evaluate=False), b)))
            except NotABound as err:
                out.append(f"{sp.sstr(factor)} > 0 ({err.reason})")
    return out


@PAPER.equation("52", kind="condition", printed=P52, section=SECTION, assumptions=ASSUME,
                derivation="det M(-1) for uniform m = 3: (d - w)^2 (d + 2w), d = 2b - K_0T - 2B_0 - 2w, w = KT + 2B")
def eq52(ctx: AuditContext) -> Finding:
    rel = ctx.relation()
    condition = as_sign_condition(rel)
    printed = sp.expand(condition.expr)
    det = sp.expand(hermitian_matrix(MultiUserScene.uniform(3)).subs(C, -1).det())
    sign = compare_sign_conditions(rel, sp.Gt(det, 0, evaluate=False), what="(52) as det M(-1) > 0")
    if sign.verdict == Verdict.CONFIRMED:
        return sign
    scene = MultiUserScene.uniform(3, b=sp.Rational(8, 5), K0=1, B0=0, K=1, B=0, T=1)
    values = {b: sp.Rational(8, 5), K_0: 1, B_0: 0, K: 1, B: 0, T: 1}
    holds = condition.holds(values)
    reading = _solved(printed)
    printed_factored, det_factored = _factor(printed), _factor(det)     # each factored once
    facts = {"printed_factored": printed_factored, "det_M(-1)_factored": det_factored, "printed_form": (condition.op, sp.srepr(printed)),
             "printed_at_witness": holds, **decision_facts(scene)}
    if not (holds and not_pr(scene)):
        return Finding(sign.verdict, f"(52) reads {sp.sstr(printed_factored)} {condition.op} 0 (i.e. {reading}), not det M(-1) "
                       f"= {sp.sstr(det_factored)} > 0 of the uniform triple-user scene: {sign.detail}",
                       Evidence(sign.evidence.method, witness=sign.evidence.witness, facts=facts),
                       derived=sp.Gt(det_factored, 0),
                       corrected=r"(2b - K_0T - 2B_0 - 3(KT + 2B))^2\,(2b - K_0T - 2B_0) > 0,\quad 2b - K_0T - 2B_0 > 0")
    return Finding(
        Verdict.WRONG,
        f"(52) reads {sp.sstr(printed_factored)} {condition.op} 0, i.e. {'; '.join(reading)}; it is not det M(-1) = "
        f"{sp.sstr(det_factored)} of the uniform triple-user scene (each user has two couplings), and at the witness "
        "(B = 0) it holds while G^-1 is not PR",
        Evidence(Method.COUNTEREXAMPLE, witness={str(k): v for k, v in values.items()}, facts=facts),
        derived=sp.Gt(det_factored, 0),
        corrected=r"(2b - K_0T - 2B_0 - 3(KT + 2B))^2\,(2b - K_0T - 2B_0) > 0,\quad 2b - K_0T - 2B_0 > 0",
    )


@PAPER.equation("52-53", kind="claim", after="52", section=SECTION,
                printed="After simplifying (52), the stability condition for this sampled-data, triple-user HVE system will be",
                derivation="factor (52) exactly and compare its solution set with (53)", quotes=('52', '53'))
def simplify52(ctx: AuditContext) -> Finding:
    condition = as_sign_condition(display("52"))
    expr = sp.expand(condition.expr)
    factored = _factor(expr)
    reading = _solved(expr)
    p53 = display("53")
    facts = {"factored": factored, "simplified": reading, "printed_53": p53}
    bounds = []
    for factor, power in _factor_list(expr)[1]:
        if factor.has(b) and power % 2 == 1:
            try:
                bounds.append(as_bound(sp.Gt(factor, 0, evaluate=False), b))
            except NotABound:
                pass
    if len(bounds) == 1 and bounds[0].lower and condition.op in (">", ">="):
        simplified = sp.Gt(b, bounds[0].bound)
        cmp = compare_bounds(p53, sp.Ge(b, bounds[0].bound), b, what="(53) against simplified (52)")
        if cmp.verdict == Verdict.CONFIRMED:
            return Finding(Verdict.CONFIRMED, f"(52) factors as {sp.sstr(factored)} and simplifies to (53), {sp.sstr(simplified)}",
                           Evidence(Method.CANONICAL_FORM, facts=facts), derived=simplified)
        gap = sp.simplify(as_bound(p53, b).bound - bounds[0].bound) if cmp.evidence.facts.get("printed_bound") is not None else None
        return Finding(
            Verdict.WRONG,
            f"(52) factors exactly as {sp.sstr(factored)}, so it simplifies to {sp.sstr(simplified)} (away from the double "
            f"root), not to (53) {sp.sstr(p53)}" + (f": the two bounds differ by {sp.sstr(gap)}" if gap is not None else "")
            + f" ({cmp.verdict.value})",
            Evidence(Method.CANONICAL_FORM, witness=cmp.evidence.witness, facts=facts), derived=simplified)
    return Finding(Verdict.WRONG, f"(52) factors as {sp.sstr(factored)} {condition.op} 0, which is not a single lower bound on b "
                   f"({reading}), so it does not simplify to (53) {sp.sstr(p53)}", Evidence(Method.CANONICAL_FORM, facts=facts))


@PAPER.equation("53", kind="condition", printed=r"b > \frac{K_0 T}{2} + \frac{3KT}{2} + B_0 + 3B \tag{53}",
                section=SECTION, assumptions=ASSUME + "; b = min b_i, K_0, K, B_0, B = maxima (see 51-worst)",
                derivation="uniform m = 3: eigenvalues of M(-1) are a (once) and a - 3w (twice)")
def eq53(ctx: AuditContext) -> Finding:
    return _uniform_conservative(ctx.relation(), 3, "(53)")


P54 = r"\min_{i} b_{i} > \max_{i} \{ \frac{K_{0i}T}{2} + B_{0i} \} + m \max_{i,j \neq i} \{ \frac{K_{ij}T}{2} + B_{ij} \}"


P55 = r"\min_{i} \{b_{i} - z_{ai}\} > \max_{i} \{\frac{K_{0i}T}{2} + B_{0i}\} + m \max_{i,j} \{\frac{K_{ij}T}{2} + B_{ij}\}"


@lru_cache(maxsize=None)
def _skeleton(expr: Any, m: int) -> tuple[Any, tuple[tuple[sp.Symbol, bool, tuple[Any, ...]], ...]]:
    """``expr`` for ``m`` users with each indexed extremum replaced by a placeholder, and per
    placeholder its kind and its expanded bodies over the index tuples (computed once; an
    instance then only substitutes values)."""
    table = PAPER.symbols
    expr = sp.sympify(expr).xreplace({M_COUNT: sp.Integer(m)})
    extrema: list[tuple[sp.Symbol, bool, tuple[Any, ...]]] = []

    def placeholder(e: Any) -> Any:
        bodies: list[Any] = []
        for combo in itertools.product(range(1, m + 1), repeat=len(e.indices)):
            mapping = dict(zip(e.indices, map(sp.Integer, combo)))
            if e.condition.xreplace(mapping) is sp.false:
                continue
            body = sp.expand(align(expand_indexed(e.body.xreplace(mapping), m, table)))
            if body not in bodies:
                bodies.append(body)
        symbol = sp.Dummy(f"extremum{len(extrema)}")
        extrema.append((symbol, isinstance(e, IndexedMin), tuple(bodies)))
        return symbol

    expr = expr.replace(lambda e: isinstance(e, IndexedExtremum), placeholder)
    return align(expand_indexed(expr, m, table, empty=sp.Integer(0))), tuple(extrema)


def _evaluate(expr: Any, m: int, values: dict) -> Any:
    """Evaluate a printed indexed expression for ``m`` users at ``values`` (concrete symbols ->
    numbers or symbols), one extremum body at a time: SymPy's Max/Min of many symbolic
    arguments is slow, of a few equal or numeric ones it is instant."""
    skeleton, extrema = _skeleton(sp.sympify(expr), m)
    filled = {}
    for symbol, is_min, bodies in extrema:
        results: list[Any] = []
        for body in bodies:
            value = sp.expand(body.xreplace(values))
            if value not in results:
                results.append(value)
        # an extremum over no pair (one user) is no coupling term
        filled[symbol] = (sp.Min if is_min else sp.Max)(*results) if results else sp.Integer(0)
    return skeleton.xreplace(filled).xreplace(values)


class IndexedDisplay:
    """A printed indexed condition ``lhs > rhs`` for ``m`` users."""

    def __init__(self, rel: sp.Basic, m: int):
        self.rel, self.m = rel, m

    def at(self, values: dict) -> sp.Basic:
        lhs, rhs = (_evaluate(side, self.m, values) for side in (self.rel.lhs, self.rel.rhs))
        return self.rel.func(lhs, rhs, evaluate=False)         # the printed relation, whichever it is

    def holds(self, scene: MultiUserScene) -> bool:
        rel = self.at(scene_values(scene))
        value = rel.func(rel.lhs, rel.rhs)
        if value not in (sp.true, sp.false):
            # e.g. K_{ij} under max_i: an index the display never binds
            raise LatexParseError(f"the printed condition does not evaluate at numeric parameters (left free: "
                                  f"{', '.join(sorted(map(str, value.free_symbols)))})", "", 0)
        return bool(value)

    def bound(self, scene: MultiUserScene) -> sp.Expr:
        """The right-hand side: the bound on ``min_i b_i`` (z_a = 0, B on the right)."""
        return self.at(scene_values(scene)).rhs

    def symbolic(self) -> sp.Basic:
        return self.at({})

    def uniform(self, **extra: Any) -> sp.Basic:
        values = uniform_subs(self.m)
        rel = self.at(values)
        return rel.xreplace(extra) if extra else rel


def _structural_facts(delay: int = 0, damped: bool = True) -> dict[str, Any]:
    kb = kernel_bounds("forward", delay)
    spectra = {}
    for m in range(2, 9):
        L = sp.Matrix(m, m, lambda i, j: m - 1 if i == j else -1)
        lam = sp.Symbol("lambda")
        spectra[m] = sp.factor(L.charpoly(lam).as_expr())
    return {
        "proof": [
            f"equal delays n = {delay}: M(c)/2 = diag(b - z_a) + Re k_K(c) T Kmat + Re k_B(c) Bmat, Kmat, Bmat >= 0 "
            "(ground coupling plus a Laplacian with non-negative weights)",
            f"Re k_K >= -{kb.kappa_K} (attained at c = {kb.argmin_K}), Re k_B >= -{kb.kappa_B}: "
            f"M/2 >= diag(b - z_a) - {kb.kappa_K} T Kmat - {kb.kappa_B} Bmat for every c",
            "diag(d) <= max(d) I and L_w <= max(w) L_{K_m} (the difference is a Laplacian with non-negative weights); "
            "lambda_max(L_{K_m}) = m",
        ],
        "laplacian_charpolys_m_2_to_8": spectra,
    }


@PAPER.equation("54", kind="condition", printed=P54, section=SECTION, assumptions=ASSUME,
                derivation="Loewner bound of M(-1) for any m and any coupling graph; exact for uniform complete graphs")
def eq54(ctx: AuditContext) -> Finding:
    rel = ctx.relation()
    if not isinstance(rel, (sp.StrictGreaterThan, sp.GreaterThan)):
        return Finding(Verdict.WRONG, f"(54) reads {sp.sstr(rel)}: not a lower bound min_i b_i > ... on the device dampings",
                       Evidence(Method.PARSE, facts={"printed_form": sp.srepr(rel)}),
                       derived=sufficient_condition(MultiUserScene.symbolic(3)))
    checks = {m: IndexedDisplay(rel, m) for m in range(1, 9)}
    # uniform: printed == exact for m = 1..8
    uniform = {}
    for m in range(1, 9):
        exact = uniform_condition(m).xreplace({z_a: 0})
        uniform[m] = compare_bounds(checks[m].uniform(), sp.Ge(exact.lhs, exact.rhs), b, what=f"(54) at m = {m}, uniform")
    not_exact = {m: f.verdict.value for m, f in uniform.items() if f.verdict != Verdict.CONFIRMED}
    form = ("uniform", tuple(repr(uniform[m].evidence.facts.get("printed_form")) for m in range(1, 9)))
    if not_exact:
        m0 = min(not_exact)
        return Finding(uniform[m0].verdict if uniform[m0].verdict != Verdict.CONSERVATIVE else Verdict.TYPO,
                       f"(54) differs from the exact PR condition for uniform parameters (m = {sorted(not_exact)}): "
                       f"{uniform[m0].detail}",
                       Evidence(uniform[m0].evidence.method, witness=uniform[m0].evidence.witness,
                                facts={"uniform": not_exact, "printed_form": form}),
                       derived=sufficient_condition(MultiUserScene.symbolic(3)))
    counts = {}
    for m in range(2, 9):
        result = _sufficiency_instances(checks[m].bound, m_range=range(m, m + 1), per_m=3, seed=m)
        if result["failure"] is not None:
            return Finding(Verdict.WRONG, f"(54) is exact for uniform parameters but not sufficient in general: at the "
                           f"witness (m = {m}) it holds while the exact decision shows G^-1 is not PR",
                           Evidence(Method.COUNTEREXAMPLE, witness=witness_json(result["failure"]),
                                    facts={"printed_form": form, **decision_facts(result["failure"])}))
        counts[m] = result["instances"]
    witness = numeric_users(b=[3, sp.Rational(1, 2), sp.Rational(1, 2)], T=1, K0=[4, sp.Rational(1, 10), sp.Rational(1, 10)],
                       K=sp.Rational(1, 100), B0=0, B=0)
    facts = {**_structural_facts(), "exact_instances": counts, "uniform_equal_m_1_to_8": True,
             "printed_form": form, **decision_facts(witness)}
    if not pr(witness):
        return Finding(Verdict.UNDECIDED,
                       "(54) is exact for uniform parameters and sufficient on every instance tried, but the non-uniform "
                       "witness is not PR (exact decision), so it cannot show that (54) is not necessary",
                       Evidence(Method.STRUCTURAL, witness=witness_json(witness), facts=facts))
    if checks[3].holds(witness):
        return Finding(Verdict.UNDECIDED,
                       "(54) is exact for uniform parameters and sufficient on every instance tried; it also holds at the "
                       "non-uniform witness (PR), so it is not shown conservative, and equivalence in general is not proved",
                       Evidence(Method.STRUCTURAL, witness=witness_json(witness), facts=facts))
    return Finding(
        Verdict.CONSERVATIVE,
        "proved for every m and every coupling graph from the structure (worst case c = -1 in the Loewner order, "
        "lambda_max of the weighted Laplacian <= m max w); equal to the exact PR condition for uniform parameters "
        "(checked symbolically for m = 1..8, reading the empty max for m = 1 as 0); sufficient but not necessary "
        f"otherwise (checked on {sum(counts.values())} exact random instances for m = 2..8; witness: PR although (54) fails)",
        Evidence(Method.STRUCTURAL, witness=witness_json(witness), facts=facts),
        derived=sufficient_condition(MultiUserScene.symbolic(3)),
    )


@PAPER.equation("54-general", kind="claim", after="54", section=SECTION,
                printed="In a similar way, it is possible to show that the stability condition for any *m* will be",
                derivation="(54) at m = 2, 3 with uniform values vs (46), (53)", quotes=('54', '46', '53'))
def general54(ctx: AuditContext) -> Finding:
    rel = display("54")
    printed46 = uniform_names(display("46"))
    printed53 = display("53")
    facts = {}
    for m, other in ((2, printed46), (3, printed53)):
        u = IndexedDisplay(rel, m).uniform()
        facts[f"m={m}"] = {"(54) uniform": str(u), "printed": str(other), "same": same_condition(u, other)}
    if all(f["same"] for f in facts.values()):
        return Finding(Verdict.CONFIRMED,
                       "with uniform values (54) reduces to (46) for m = 2 and to (53) for m = 3 (both read with the maxima), "
                       "and the general-m statement is proved (see (54))",
                       Evidence(Method.CANONICAL_FORM, facts=facts))
    bad = [f"m = {k[2:]}: {v['(54) uniform']} vs {v['printed']}" for k, v in facts.items() if not v["same"]]
    return Finding(Verdict.INCONSISTENT, f"(54) with uniform values does not reduce to (46)/(53): {'; '.join(bad)}",
                   Evidence(Method.CANONICAL_FORM, facts={**facts, "ids": ["54", "46", "53"]}))
