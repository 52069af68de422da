r"""The 3-DOF paper, Section 5.1: the position-position case study (21)-(40) and the gains of
Table 1.
"""

from __future__ import annotations

import itertools
from functools import lru_cache
from typing import Any

import sympy as sp
from sympy.matrices.expressions.matexpr import MatrixElement

from hapticproof.exact.canonical import cancel as exact_cancel
from hapticproof.audit.runner import AuditContext
from hapticproof.audit.compare import compare_expressions
from hapticproof.exact.canonical import is_identically_zero
from hapticproof.exact.evaluator import relation_at
from hapticproof.core.evidence import Evidence, Finding, Method, Verdict
from hapticproof.analysis.networks import symmetrization_conditions
from hapticproof.audit.reader.printed import parse_printed
from hapticproof.exact.rationalmatrix import RationalMatrix, matrix_psd
from hapticproof.core.symbols import s
from hapticproof.derivations.bilateral_3dof.paper import ASSUME_CASE, AXES, NAMES, PAPER, PRINTED, TABLE, canonical, case_study_impedance, definition, derived_conditions, explicit, gain, gain_matrix, omega, one_line, real_part_zprime, residue_zprime, rho, rhs_matrix, sym3, table1_gains, table1_impedance, tex


def _model_definitions() -> dict[str, tuple[str, Any, Any]]:
    """The case study's model (the convention of :func:`case_study_impedance`): device forces
    balance the port force and the controller force; position-position controllers."""
    L = TABLE.lookup
    Zm, Zs, Cm, Cs = (L(k) for k in (r"\mathbf{Z}_m", r"\mathbf{Z}_s", r"\mathbf{C}_m", r"\mathbf{C}_s"))
    Vh, Ve, Fh, Fe, Fcm, Fcs = (L(k) for k in ("V_h", "V_e", "F_h", "F_e", "F_{cm}", "F_{cs}"))
    return {
        "21a": ("master dynamics Z_m V_h = F_h + F_cm with Z_m = M_m s", Zm * Vh, Fh + Fcm),
        "21b": ("slave dynamics Z_s V_e = F_e + F_cs with Z_s = M_s s", Zs * Ve, Fe + Fcs),
        "23a": ("master position-position law", Fcm, -Cm * Vh + Cm * Ve),
        "23b": ("slave position-position law", Fcs, -Cs * Ve + Cs * Vh),
    }


for _id in ("21a", "21b", "23a", "23b"):
    def _check(ctx: AuditContext) -> Finding:
        what, lhs, rhs = _model_definitions()[ctx.equation.id]
        return definition(ctx, "defines the " + what + " (used in (25))", lhs, rhs)
    PAPER.equation(_id, kind="expression", printed=PRINTED[_id], section="5.1", derivation="model definition")(_check)


@PAPER.equation("22", kind="expression", printed=PRINTED["22"], section="5.1",
                derivation="general inertia matrix; which of its entries the symmetrization conditions see")
def eq22(ctx: AuditContext) -> Finding:
    rel = ctx.statement.relations()[0]
    M = rhs_matrix(ctx)
    expected = sp.Matrix(3, 3, lambda a, c: TABLE.lookup(f"m_{{i{AXES[a]}{AXES[c]}}}"))
    if rel.lhs != TABLE.lookup(r"\mathbf{M}_i") or M.shape != (3, 3):
        return Finding(Verdict.TYPO, f"the display must define the 3x3 inertia matrix M_i; it reads {one_line(rel.lhs)} = "
                       f"{M.shape[0]}x{M.shape[1]} matrix", Evidence(Method.PARSE, facts={"printed_form": sp.srepr(rel.lhs)}))
    misplaced = [(a, c) for a in range(3) for c in range(3) if M[a, c] != expected[a, c]]
    if misplaced:
        listing = "; ".join(f"({AXES[a]},{AXES[c]}): {sp.sstr(M[a, c])}" for a, c in misplaced)
        return Finding(Verdict.TYPO, f"entry (a, b) of M_i must be m_iab; the display has {listing}",
                       Evidence(Method.CANONICAL_FORM, facts={"printed_form": sp.srepr(M)}), corrected=tex(sp.Eq(
                           TABLE.lookup(r"\mathbf{M}_i"), expected, evaluate=False)))
    general = case_study_impedance(gain_matrix("pm"), gain_matrix("vm"), gain_matrix("ps"), gain_matrix("vs"),
                                   gain_matrix("mm"), gain_matrix("ms"))
    extra = [c for c in symmetrization_conditions(general, ports=(3, 3)) if c.kind == "B"]
    mass_terms = any(c.expr.has(gain("mm", "x", "y")) for c in extra)
    return Finding(Verdict.CONFIRMED,
                   "a general 3x3 inertia matrix (9 entries); with m_ixy != m_iyx condition B would carry the extra terms "
                   "j w (m_iyx - m_ixy) absent from (26)-(31) -- the audit takes M_i symmetric, as inertia matrices are",
                   Evidence(Method.PARSE, facts={"entries": len(M.free_symbols), "mass_terms_in_B_if_asymmetric": mass_terms,
                                                 "printed_form": sp.srepr(M)}))


def _printed_gain_matrix(ctx: AuditContext, kind: str) -> Finding:
    rel = ctx.statement.relations()[0]
    name = TABLE.lookup(r"\mathbf{C}_" + kind)
    if rel.lhs != name:
        return Finding(Verdict.TYPO, f"the display must define {sp.sstr(name)}; it defines {sp.sstr(rel.lhs)}",
                       Evidence(Method.PARSE, facts={"printed_form": sp.srepr(rel.lhs)}))
    printed = rhs_matrix(ctx)
    derived = (gain_matrix("p" + kind) + gain_matrix("v" + kind) * s) / s
    bad = [(i, j) for i in range(3) for j in range(3) if not is_identically_zero(printed[i, j] - derived[i, j])]
    if not bad:
        return Finding(Verdict.CONFIRMED, "matches (K_p + K_v s)/s entrywise", Evidence(Method.CANONICAL_FORM))
    listing = "; ".join(f"({AXES[i]},{AXES[j]}): printed {sp.sstr(sp.together(printed[i, j]))}" for i, j in bad)
    return Finding(Verdict.TYPO,
                   f"{len(bad)} entries carry wrong gain names (PD gains k_p{kind}ab + k_v{kind}ab s expected at (a, b)): {listing}",
                   Evidence(Method.CANONICAL_FORM, witness={"entries": [[AXES[i], AXES[j]] for i, j in bad]}),
                   derived=derived, corrected=r"\mathbf{C}_%s = \frac{1}{s}\left(\mathbf{K}_{p%s} + \mathbf{K}_{v%s}s\right) = "
                   % (kind, kind, kind) + tex(derived))


@PAPER.equation("23c", kind="expression", printed=PRINTED["23c"], section="5.1", derivation="C_m = (K_pm + K_vm s)/s entrywise")
def eq23c(ctx: AuditContext) -> Finding:
    return _printed_gain_matrix(ctx, "m")


@PAPER.equation("24", kind="expression", printed=PRINTED["24"], section="5.1", derivation="C_s = (K_ps + K_vs s)/s entrywise")
def eq24(ctx: AuditContext) -> Finding:
    return _printed_gain_matrix(ctx, "s")


@PAPER.equation("25", kind="expression", printed=PRINTED["25"], section="5.1", derivation="substitute (23) into (21)", quotes=('21a', '21b', '23a', '23b'))
def eq25(ctx: AuditContext) -> Finding:
    L = TABLE.lookup
    Fh, Fe, Fcm, Fcs = (L(k) for k in ("F_h", "F_e", "F_{cm}", "F_{cs}"))
    unknowns = [e for M in (Fh, Fe, Fcm, Fcs) for e in M.as_explicit()]
    equations = []
    for eq_id in ("21a", "21b", "23a", "23b"):
        (rel,) = parse_printed(PAPER.get(eq_id).printed, TABLE).relations()
        equations += list(explicit(rel.lhs) - explicit(rel.rhs))
    confirmed = Finding(Verdict.CONFIRMED, "F_h = (C_m + Z_m) V_h - C_m V_e and F_e = -C_s V_h + (C_s + Z_s) V_e follow from "
                        "the printed (21) and (23)", Evidence(Method.CANONICAL_FORM,
                                                             facts={"printed_form": ("follows from (21), (23)",)}))
    unique = _unique_linear_solution(equations, unknowns)
    if unique is not None:
        rel = ctx.statement.relations()[0].as_sympy()
        if all(sp.expand(e.xreplace(unique)) == 0 for e in explicit(rel.lhs) - explicit(rel.rhs)):
            return confirmed
    solution = sp.solve(equations, unknowns, dict=True)
    if len(solution) != 1 or any(u not in solution[0] for u in unknowns[:6]):
        return Finding(Verdict.UNDECIDED, "(21) and (23) as printed do not determine the port forces",
                       Evidence(Method.CANONICAL_FORM, facts={"ids": ["21a", "21b", "23a", "23b"]}))
    rel = ctx.statement.relations()[0].as_sympy()
    difference = (explicit(rel.lhs) - explicit(rel.rhs)).applyfunc(lambda e: sp.expand(e.xreplace(solution[0])))
    bad = [k for k, e in enumerate(difference) if e != 0]
    if not bad:
        return confirmed
    row = bad[0]
    return Finding(Verdict.TYPO, f"does not follow from (21) and (23): row {row + 1} of the printed system differs from them by "
                   f"{sp.sstr(difference[row])}", Evidence(Method.COUNTEREXAMPLE, facts={"rows": [k + 1 for k in bad],
                                                                                          "printed_form": sp.srepr(difference)}))


def _unique_linear_solution(equations: list, unknowns: list) -> dict | None:
    """The unique solution of linear equations whose unknowns have constant rational
    coefficients (a port-force system), by the exact inverse of that constant matrix; ``None``
    for anything else (then ``sp.solve`` decides). Matrix entries are read as plain symbols."""
    atoms = set().union(*(e.atoms(MatrixElement) for e in equations))
    names = {a: sp.Dummy(str(a)) for a in atoms}
    try:
        A, rhs = sp.linear_eq_to_matrix([e.xreplace(names) for e in equations], [names.get(u, u) for u in unknowns])
    except (sp.PolynomialError, ValueError):
        return None
    if A.rows != A.cols or A.free_symbols or A.det() == 0:
        return None
    back = {v: k for k, v in names.items()}
    return dict(zip(unknowns, (A.inv() * rhs).xreplace(back)))


B_PAIRS = {"26": (0, 1), "27": (0, 2), "28": (1, 2), "29": (3, 4), "30": (3, 5), "31": (4, 5)}


def _at_omega(expr: sp.Expr) -> sp.Expr:
    poly = sp.Poly(expr, s)
    low = min(m[0] for m in poly.monoms())
    return sp.expand(sp.expand(expr / s**low).subs(s, sp.I * omega))


def _b_check(ctx: AuditContext) -> Finding:
    pair = B_PAIRS[ctx.equation.id]
    cond = next(c for c in derived_conditions() if c.kind == "B" and c.indices == pair)
    rel = ctx.relation()
    printed = sp.expand(rel.lhs - rel.rhs)
    derived = cond.at_frequency(omega)
    if not isinstance(rel, sp.Eq) or printed == 0:
        return Finding(Verdict.WRONG, f"condition B is an equation z_ji - z_ij = 0; the display reads {sp.sstr(rel)}",
                       Evidence(Method.PARSE, facts={"printed_form": sp.srepr(rel)}), derived=sp.Eq(derived, 0))
    ratio = exact_cancel(derived / printed)
    if ratio != 0 and ratio.free_symbols <= {omega} and not ratio.has(sp.zoo, sp.nan):
        a, b = (AXES[i % 3] for i in pair)
        return Finding(Verdict.CONFIRMED,
                       f"equivalent to z_{{{pair[1] + 1},{pair[0] + 1}}} = z_{{{pair[0] + 1},{pair[1] + 1}}} at s = j omega "
                       f"(the derived numerator is {sp.sstr(sp.factor(ratio))} times the printed expression); with a non-symmetric "
                       f"inertia matrix the term j omega (m_{b}{a} - m_{a}{b}) would be missing",
                       Evidence(Method.CANONICAL_FORM, facts={"ratio": ratio, "printed_form": ("B", pair)}),
                       derived=sp.Eq(derived, 0))
    return compare_expressions(printed, derived, what="the printed B-condition")


for _id in B_PAIRS:
    PAPER.equation(_id, kind="condition", printed=PRINTED[_id], section="5.1", assumptions=ASSUME_CASE,
                   derivation=f"condition B for the pair {B_PAIRS[_id]}: z_ji - z_ij at s = j omega")(_b_check)


@lru_cache(maxsize=1)
def _a_candidates():
    out = []
    for c in derived_conditions():
        if c.kind != "A" or len({i // 3 for i in c.indices}) == 1:
            continue
        out.append((c, canonical(_at_omega(c.expr))))
    return tuple(out)


def _omega_form(expr: sp.Expr) -> str:
    parts = sp.collect(sp.expand(expr), omega, evaluate=False)
    pieces = []
    for power, coefficient in sorted(parts.items(), key=lambda kv: -sp.degree(kv[0], omega)):
        k = sp.degree(power, omega)
        coefficient = sp.expand(coefficient)
        if k == 1:
            coefficient = sp.expand(coefficient / sp.I)
            pieces.append(r"j\omega(" + tex(coefficient) + ")")
        elif k == 2:
            pieces.append(r"\omega^2(" + tex(coefficient) + ")")
        else:
            pieces.append(tex(coefficient))
    return " + ".join(pieces).replace("+ - ", "- ").replace("+ -", "- ") + " = 0"


def _a_check(ctx: AuditContext) -> Finding:
    rel = ctx.relation()
    printed = canonical(sp.expand(rel.lhs - rel.rhs))
    if not isinstance(rel, sp.Eq) or printed == 0:
        return Finding(Verdict.WRONG, f"condition A is an equation (... = 0); the display reads {sp.sstr(rel)}",
                       Evidence(Method.PARSE, facts={"printed_form": sp.srepr(rel)}))
    form = ("A with gains identified by B", sp.srepr(sp.expand(printed)))
    best = None
    for cond, derived in _a_candidates():
        for sign in (1, -1):
            diff = sp.expand(printed - sign * derived)
            score = len(sp.Add.make_args(diff)) if diff != 0 else 0
            if best is None or score < best[0]:
                best = (score, cond, sign, diff, sign * derived)
    score, cond, sign, diff, target = best
    triple = [i + 1 for i in cond.indices]
    if score == 0:
        return Finding(Verdict.CONFIRMED,
                       f"equals {'minus ' if sign < 0 else ''}condition A for (i, j, k) = {tuple(triple)} reduced by B "
                       "(z_jk z_ki = z_kj z_ik) at s = j omega, with gains identified by B (k_yx = k_xy)",
                       Evidence(Method.CANONICAL_FORM, facts={"triple": triple, "printed_form": ("A", tuple(triple), sign)}),
                       derived=sp.Eq(target, 0))
    printed_only = [t for t in sp.Add.make_args(sp.expand(printed)) if t not in sp.Add.make_args(target)]
    derived_only = [t for t in sp.Add.make_args(target) if t not in sp.Add.make_args(sp.expand(printed))]
    point = {sym: sp.Integer(k + 2) for k, sym in enumerate(sorted(printed.free_symbols | target.free_symbols, key=str)) if sym != omega}
    point[omega] = sp.Integer(1)
    return Finding(Verdict.TYPO,
                   f"closest to condition A for (i, j, k) = {tuple(triple)} (reduced by B), which it matches except for "
                   f"{len(printed_only)} printed terms {[sp.sstr(t) for t in printed_only]} where the derivation has "
                   f"{[sp.sstr(t) for t in derived_only]} (an index slip, e.g. k_psyx for k_psyy)",
                   Evidence(Method.COUNTEREXAMPLE, witness={str(k): v for k, v in point.items()},
                            facts={"printed_value": sp.expand(printed.subs(point)), "derived_value": sp.expand(target.subs(point)),
                                   "triple": triple, "printed_form": form}),
                   derived=sp.Eq(target, 0), corrected=_omega_form(target))


for _id in ("32", "33", "34", "35", "36", "37"):
    PAPER.equation(_id, kind="condition", printed=PRINTED[_id], section="5.1", assumptions=ASSUME_CASE,
                   derivation="condition A (cross-port triples, reduced by B) at s = j omega, gains identified by B")(_a_check)


@PAPER.equation("37-count", kind="claim", after="37", section="5.1",
                printed="the symmetrization conditions of A and B boils down to the following 12 conditions",
                derivation="all conditions A and B of the symbolic case study vs the 12 printed ones")
def twelve_conditions(ctx: AuditContext) -> Finding:
    conds = derived_conditions()
    b = [c for c in conds if c.kind == "B"]
    cross = [c for c in conds if c.kind == "A" and len({i // 3 for i in c.indices}) == 2]
    within = [c for c in conds if c.kind == "A" and len({i // 3 for i in c.indices}) == 1]
    within_vanish = all(canonical(c.expr) == 0 for c in within)
    # under B each cross condition equates the ratios C_m,ab / C_s,ab of two gain pairs; the edges
    # of the six printed ones come from the conditions (32)-(37) match (best match, see _a_check)
    edges = []
    for eq_id in ("32", "33", "34", "35", "36", "37"):
        rel = parse_printed(PAPER.get(eq_id).printed, TABLE).relations()[0].as_sympy()
        printed = canonical(sp.expand(rel.lhs - rel.rhs))
        best = min(((len(sp.Add.make_args(sp.expand(printed - sg * d))), d) for _, d in _a_candidates() for sg in (1, -1)),
                   key=lambda item: item[0])[1]
        pairs = sorted({str(x)[-2:] for x in best.free_symbols if str(x).startswith("k_")})
        edges.append(tuple(pairs))
    nodes = {"xx", "yy", "zz", "xy", "xz", "yz"}
    reached, frontier = {"xx"}, ["xx"]
    while frontier:
        a = frontier.pop()
        for edge in edges:
            if len(edge) == 2 and a in edge:
                other = edge[1] if edge[0] == a else edge[0]
                if other not in reached:
                    reached.add(other)
                    frontier.append(other)
    if len(b) == 6 and len(cross) == 18 and within_vanish and reached == nodes:
        return Finding(Verdict.CONFIRMED,
                       "A and B give 6 B-conditions and 18 cross-port A-conditions (the 2 within-port triples vanish under B); "
                       "under B the 18 say that C_m,ab / C_s,ab is one function for all six gain pairs, and the six printed "
                       "(32)-(37) already chain the six pairs together: the 12 conditions are equivalent to A and B "
                       "(for nonzero couplings)",
                       Evidence(Method.STRUCTURAL, facts={"B": len(b), "A_cross": len(cross), "A_within_vanish_under_B": within_vanish,
                                                          "ratio_links_32_37": edges}))
    return Finding(Verdict.WRONG, "the printed 12 conditions do not span A and B", Evidence(Method.STRUCTURAL))


def _symmetry_equalities() -> set[frozenset]:
    out = set()
    for c in derived_conditions():
        if c.kind == "B":
            for coefficient in c.coefficients():
                syms = sorted(coefficient.free_symbols, key=str)
                out.add(frozenset(syms))
    return out


def _equality_pair(rel: sp.Basic) -> frozenset | None:
    """``k_a = k_b`` as the pair {k_a, k_b}; None when the relation is not such an equality
    (another relation, coefficients, more or fewer gains)."""
    if not isinstance(rel, sp.Eq):
        return None
    difference = sp.expand(rel.lhs - rel.rhs)
    terms = sp.Add.make_args(difference)
    if len(terms) != 2 or not all(t.free_symbols and len(t.free_symbols) == 1 for t in terms):
        return None
    coefficients = sorted(t.as_coeff_Mul()[0] for t in terms)
    if coefficients != [-1, 1] or not all(isinstance(t.as_coeff_Mul()[1], sp.Symbol) for t in terms):
        return None
    return frozenset(t.as_coeff_Mul()[1] for t in terms)


def _38ab_check(ctx: AuditContext) -> Finding:
    relations = [r.as_sympy() for r in ctx.statement.relations()]
    pairs = [_equality_pair(r) for r in relations]
    which = "m" if ctx.equation.id == "38a" else "s"
    derived = {e for e in _symmetry_equalities() if any(str(x).startswith(f"k_p{which}") or str(x).startswith(f"k_v{which}") for x in e)}
    not_equalities = [sp.sstr(r) for r, p in zip(relations, pairs) if p is None]
    if not_equalities:
        return Finding(Verdict.WRONG, f"{not_equalities} are not equalities of two gains (B requires k_ab = k_ba)",
                       Evidence(Method.PARSE, facts={"printed_form": [sp.srepr(r) for r in relations]}))
    printed = pairs
    wrong = [p for p in printed if p not in derived]
    missing = sorted((d for d in derived if d not in printed), key=lambda e: sorted(map(str, e)))   # a set: fixed order
    if wrong:
        return Finding(Verdict.WRONG, f"printed equalities not implied by B: {[' = '.join(sorted(map(str, w))) for w in wrong]}",
                       Evidence(Method.CANONICAL_FORM, facts={"printed_form": sorted(sorted(map(str, p)) for p in printed)}))
    if not missing:
        return Finding(Verdict.CONFIRMED, "all symmetry equalities listed", Evidence(Method.CANONICAL_FORM))
    first = sorted(missing, key=lambda e: sorted(map(str, e)))[0]
    a, b = sorted(first, key=str)
    # witness: the printed equalities hold, the missing one fails
    witness = {x: sp.Integer(1) for x in a.free_symbols | b.free_symbols}
    witness[b] = sp.Integer(2)
    corrected = ", \\quad ".join(f"{NAMES[x]} = {NAMES[y]}" for x, y in sorted((tuple(sorted(e, key=str)) for e in derived), key=str))
    return Finding(Verdict.TYPO,
                   f"lists {len(printed)} of the {len(derived)} symmetry equalities that B requires for all w "
                   f"(each of (26)-(31) needs both k_p and k_v symmetric); missing: "
                   f"{[' = '.join(sorted(map(str, e))) for e in missing]}; with only the printed ones, {a} = 1, {b} = 2 violates B",
                   Evidence(Method.COUNTEREXAMPLE, witness={str(k): v for k, v in witness.items()},
                            facts={"missing": [sorted(map(str, e)) for e in missing],
                                   "printed_form": sorted(sorted(map(str, p)) for p in printed)}),
                   corrected=corrected)


for _id in ("38a", "38b"):
    PAPER.equation(_id, kind="condition", printed=PRINTED[_id], section="5.1",
                   derivation="coefficients of (26)-(31) in w")(_38ab_check)


def _ratio_chain_substitution() -> dict:
    """(38) repaired: symmetric gains and K_pm = rho K_ps, K_vm = rho K_vs."""
    subs = {}
    for kind in ("p", "v"):
        for i in range(3):
            for j in range(3):
                a, b = AXES[min(i, j)], AXES[max(i, j)]
                subs[gain(kind + "s", AXES[i], AXES[j])] = gain(kind + "s", a, b)
                subs[gain(kind + "m", AXES[i], AXES[j])] = rho * gain(kind + "s", a, b)
    return subs


CORRECTED_38C = (r"\frac{k_{vmxx}}{k_{vsxx}} = \frac{k_{vmxy}}{k_{vsxy}} = \frac{k_{vmxz}}{k_{vsxz}} = \frac{k_{vmyy}}{k_{vsyy}}"
                 r" = \frac{k_{vmyz}}{k_{vsyz}} = \frac{k_{vmzz}}{k_{vszz}} = \frac{k_{pmxx}}{k_{psxx}} = \frac{k_{pmxy}}{k_{psxy}}"
                 r" = \frac{k_{pmxz}}{k_{psxz}} = \frac{k_{pmyy}}{k_{psyy}} = \frac{k_{pmyz}}{k_{psyz}} = \frac{k_{pmzz}}{k_{pszz}}")


@PAPER.equation("38c", kind="condition", printed=PRINTED["38c"], section="5.1",
                derivation="literal reading vs Table 1; repaired ratio chain substituted into all 24 conditions")
def eq38c(ctx: AuditContext) -> Finding:
    terms = ctx.statement.relations()[0].terms
    values = {}
    for kind, M in table1_gains(60).items():
        for i in range(3):
            for j in range(3):
                values[gain(kind, AXES[i], AXES[j])] = M[i, j]
    literal = [sp.nsimplify(t.subs(values)) for t in terms]
    subs = _ratio_chain_substitution()
    vanish = all(sp.expand(c.expr.xreplace(subs)) == 0 for c in derived_conditions())
    mismatched = []
    for t in terms:
        num, den = sp.fraction(sp.together(t))
        if den != 1 and not (str(num)[-2:] == str(den)[-2:] and str(num).startswith("k_pm") and str(den).startswith("k_ps")):
            mismatched.append(f"{sp.sstr(num)}/{sp.sstr(den)}")
    reading = " = ".join(sp.sstr(t) for t in terms)
    facts = {"literal_at_table1": literal, "repaired_chain_solves_all": vanish, "printed_form": sp.srepr(tuple(terms)),
             "mismatched_ratios": mismatched}
    if len(set(literal)) > 1 and vanish:
        return Finding(Verdict.TYPO,
                       f"garbled: read literally it is the chain {reading}, which equates the velocity gains to each other and "
                       f"to the position-gain ratios (Table 1 gives {literal}); ratios whose indices do not match: {mismatched}; "
                       "the intended chain, as in (46), is equal ratios k_vm/k_vs = k_pm/k_ps for all six gain pairs, which "
                       "makes all 24 conditions A and B vanish identically",
                       Evidence(Method.CANONICAL_FORM, facts=facts), corrected=CORRECTED_38C)
    return Finding(Verdict.UNDECIDED, "literal and repaired readings not separated", Evidence(Method.INSTANCES))


@PAPER.equation("38-sufficient", kind="claim", after="38c", section="5.1",
                printed="Conditions (26)-(37) will be fulfilled for all frequencies \\omega if the gains of the PD controllers (24) satisfy (38)",
                derivation="repaired (38) substituted into all conditions; a solution outside (38)")
def sufficient_38(ctx: AuditContext) -> Finding:
    subs = _ratio_chain_substitution()
    vanish = all(sp.expand(c.expr.xreplace(subs)) == 0 for c in derived_conditions())
    L = sym3(2, 3, 4, 1, 1, 1)
    other = {}
    for kind, factor in (("pm", 1), ("vm", 2), ("ps", 3), ("vs", 4)):
        for i in range(3):
            for j in range(3):
                other[gain(kind, AXES[i], AXES[j])] = factor * L[i, j]
    other_vanish = all(sp.expand(c.expr.xreplace(other)) == 0 for c in derived_conditions())
    if vanish and other_vanish:
        return Finding(Verdict.CONSERVATIVE,
                       "with (38) repaired (symmetric gains, one ratio rho = k_vm/k_vs = k_pm/k_ps) every condition vanishes "
                       "identically in s; not necessary: K_pm = L, K_vm = 2L, K_ps = 3L, K_vs = 4L (L symmetric) also solves "
                       "all of them while k_vm/k_vs = 1/2 != k_pm/k_ps = 1/3 (then z_ij z_ji is not a square and Z' is irrational)",
                       Evidence(Method.COUNTEREXAMPLE, witness={"L": L, "K_pm": "L", "K_vm": "2L", "K_ps": "3L", "K_vs": "4L"},
                                facts={"repaired_38_solves": vanish}))
    return Finding(Verdict.WRONG, "the repaired (38) does not solve the conditions", Evidence(Method.CANONICAL_FORM))


@PAPER.equation("38-poles", kind="claim", after="38c", section="5.1",
                printed="under (38), all the elements of the impedance matrix (25) have only a simple pole on the imaginary axis, "
                        "thus satisfying Condition C",
                derivation="poles of the entries (k_p + k_v s + m s^2)/s; Table 1 instance")
def poles_38(ctx: AuditContext) -> Finding:
    from hapticproof.exact.rationalmatrix import pole_report

    report = pole_report(RationalMatrix.from_sympy(table1_impedance(60)))
    labels = [p.label() for p, m in report.axis if m == 1]
    if not report.rhp and labels == ["s = 0"]:
        return Finding(Verdict.CONFIRMED,
                       "each entry is (k_p + k_v s + m s^2)/s: a simple pole at s = 0 and no RHP pole (C holds); the masses add a "
                       "simple pole at infinity, outside Definition 3's proper matrices, whose residue diag(M_m, M_s) must be PSD",
                       Evidence(Method.ROOT_ISOLATION, facts={"axis_poles": labels, "pole_at_infinity_order": report.improper}))
    return Finding(Verdict.WRONG, "unexpected poles", Evidence(Method.ROOT_ISOLATION))


def _residue_relations(ctx: AuditContext) -> list:
    return [r.as_sympy() for r in ctx.statement.relations()]


def as_master(expr: sp.Expr) -> sp.Expr:
    """Express slave gains through master gains under (38): k_s = k_m / rho."""
    subs = {}
    for kind in ("p", "v"):
        for i in range(3):
            for j in range(3):
                a, b = AXES[min(i, j)], AXES[max(i, j)]
                subs[gain(kind + "s", AXES[i], AXES[j])] = gain(kind + "m", a, b) / rho
    return canonical(sp.sympify(expr).xreplace(subs))


@lru_cache(maxsize=2)
def _low_order_minors(which: str) -> dict:
    """Principal minors of order <= 3 of the residue (``'residue'``) or real part (``'real'``) of Z'."""
    R = residue_zprime() if which == "residue" else real_part_zprime()
    D = sp.diag(1, 1, 1, sp.sqrt(rho), sp.sqrt(rho), sp.sqrt(rho))
    P = (D * R * D).applyfunc(sp.expand)       # polynomial entries; minors scale by rho^(#slave rows)
    out = {}
    # only their values matter (a printed minor is matched by the cancelled ratio, _minor_of)
    for k in range(1, 4):
        for S in itertools.combinations(range(6), k):
            slave = sum(i >= 3 for i in S)
            out[S] = exact_cancel(P.extract(list(S), list(S)).det(method="bareiss") / rho**slave)
    return out


#: The principal minors (0-based rows of the 6x6 residue or real part of Z') each display lists.
EXPECTED_MINORS = {"39a": [(0,), (1,), (2,)], "39b": [(3,), (4,), (5,)], "39c": [(0, 1)], "39d": [(0, 1, 2)],
                   "41a": [(0,), (1,), (2,)], "41b": [(3,), (4,), (5,)], "42": [(0, 1)], "43": [(0, 1, 2)]}


def _minor_of(expr: sp.Expr, minors: dict) -> tuple[tuple[int, ...] | None, sp.Expr | None]:
    """The principal minor a printed expression is, up to a positive factor (exact match first)."""
    best = None
    for S, m in minors.items():
        if m == 0:
            continue
        ratio = exact_cancel(expr / m)
        if ratio == 1:
            return S, ratio
        if best is None and ratio.free_symbols <= {rho} and ratio.is_positive:
            best = (S, ratio)
    return best if best is not None else (None, None)


def _minor_check(ctx: AuditContext, which: str, what: str) -> Finding:
    """Each printed relation must say 'a principal minor >= 0' (up to a positive factor), and
    together they must be the minors the display stands for (:data:`EXPECTED_MINORS`)."""
    from hapticproof.audit.compare import as_sign_condition

    minors = _low_order_minors(which)
    unmatched, matched, reversed_ = [], [], []
    for rel in _residue_relations(ctx):
        condition = as_sign_condition(rel)
        S, _ = _minor_of(as_master(condition.expr), minors)
        if S is None:
            S_neg, _ = _minor_of(-as_master(condition.expr), minors)
            if S_neg is not None:
                reversed_.append(sp.sstr(rel))
                continue
        if condition.op not in (">=", ">"):
            reversed_.append(sp.sstr(rel))
            continue
        (matched if S is not None else unmatched).append((sp.sstr(rel), S))
    expected = EXPECTED_MINORS.get(ctx.equation.id)
    listed = sorted(S for _, S in matched)
    form = ("minors", tuple(listed), tuple(u for u, _ in unmatched), tuple(reversed_))
    if reversed_:
        return Finding(Verdict.WRONG, f"{reversed_} bound a principal minor of the {what} from above: a principal minor of a PSD "
                       "matrix is >= 0", Evidence(Method.COUNTEREXAMPLE, facts={"printed_form": form}))
    missing = [[i + 1 for i in S] for S in (expected or []) if S not in listed]
    if unmatched:
        why = ("the printed k_psyx is the xy gain; the yy gain k_psyy belongs here" if ctx.equation.id == "39b"
               else "it is not of the form (principal minor) >= 0")
        return Finding(Verdict.TYPO,
                       f"{[u for u, _ in unmatched]} is not a principal minor of the {what} ({why}); the others are the "
                       f"minors {[[i + 1 for i in S] for S in listed]} (of {[[i + 1 for i in S] for S in expected or []]}; "
                       f"missing {missing})",
                       Evidence(Method.CANONICAL_FORM, facts={"matched": matched, "printed_form": form}),
                       corrected=_corrected_39b() if ctx.equation.id == "39b" else None)
    if expected is not None and listed != sorted(expected):
        return Finding(Verdict.TYPO, f"the display lists the principal minors {[[i + 1 for i in S] for S in listed]} of the {what}; "
                       f"it stands for {[[i + 1 for i in S] for S in expected]} (missing {missing})",
                       Evidence(Method.CANONICAL_FORM, facts={"printed_form": form}))
    return Finding(Verdict.CONFIRMED,
                   f"each is a principal minor of the {what} under (38) ({[[i + 1 for i in S] for _, S in matched]}); "
                   "necessary conditions -- sufficiency needs all principal minors (see the claims after them)",
                   Evidence(Method.CANONICAL_FORM, facts={"minors": [[i + 1 for i in S] for _, S in matched], "printed_form": form}))


def _corrected_39b() -> str:
    return r"k_{psxx} \geq 0, \quad k_{psyy} \geq 0, \quad k_{pszz} \geq 0"


for _id in ("39a", "39b", "39c", "39d"):
    def _check(ctx: AuditContext) -> Finding:
        return _minor_check(ctx, "residue", "residue matrix of Z' at s = 0")
    PAPER.equation(_id, kind="condition", printed=PRINTED[_id], section="5.1", assumptions=ASSUME_CASE,
                   derivation="principal minors of the residue of Z' at s = 0 under (38)")(_check)


@PAPER.equation("39-D", kind="claim", after="39d", section="5.1",
                printed="Analysis of the residues according to Condition D leads to the following constraints: (39)",
                derivation="the residue of Z' at 0 is u u^T (x) K_pm: PSD iff K_pm is; a K_pm meeting (39) that is not PSD")
def residues_39(ctx: AuditContext) -> Finding:
    R = residue_zprime()
    Kpm = gain_matrix("pm", True)
    u = sp.Matrix([1, -1 / sp.sqrt(rho)])
    structure = (R - sp.kronecker_product(u * u.T, Kpm)).applyfunc(sp.simplify) == sp.zeros(6, 6)
    bad = {gain("pm", a, b): v for (a, b), v in zip(("xx", "yy", "zz", "xy", "xz", "yz"), (0, 1, 1, 0, 0, 2))}
    point = {**bad, rho: sp.Integer(1)}
    statements = [PAPER.get(k).printed for k in ("39a", "39b", "39c", "39d")]
    holds = []
    for text in statements:
        for rel in parse_printed(text, TABLE).relations():
            value = rel.as_sympy()
            value = value.func(as_master(value.lhs), as_master(value.rhs)).subs(point)
            holds.append(bool(value) if value in (sp.true, sp.false) else False)
    psd, negative = matrix_psd(R.subs(point))
    Kbad = sp.Matrix(3, 3, lambda i, j: gain("pm", AXES[min(i, j)], AXES[max(i, j)])).subs(bad)
    failing = {f"{AXES[i]}{AXES[j]}": Kbad.extract([i, j], [i, j]).det() for i in range(3) for j in range(i + 1, 3)
               if Kbad.extract([i, j], [i, j]).det() < 0}
    if structure and all(holds) and not psd:
        return Finding(
            Verdict.WRONG,
            "under (38) the residue of Z' at s = 0 is u u^T (x) K_pm with u = (1, -1/sqrt(rho)), PSD iff K_pm is PSD, i.e. all "
            f"seven principal minors of K_pm >= 0; the printed (39a)-(39d) all hold at K_pm = {one_line(Kbad)}, whose 2x2 "
            f"principal minor(s) {failing} are negative (D as printed, leading minors of the 6x6 residue > 0, can never "
            "hold: the residue has rank <= 3)",
            Evidence(Method.COUNTEREXAMPLE, witness={"K_pm": Kbad, "rho": 1},
                     facts={"negative_minors": negative}),
            corrected=r"\mathbf{K}_{pm} \succeq 0:\ \text{all principal minors of } \mathbf{K}_{pm} \geq 0",
        )
    return Finding(Verdict.UNDECIDED, f"the printed (39) {'fails' if not all(holds) else 'holds'} at the witness K_pm = "
                   f"{one_line(Kbad)} (non-PSD); residue structure {'established' if structure else 'not established'}",
                   Evidence(Method.CANONICAL_FORM, facts={"holds": holds}))


@PAPER.equation("40", kind="condition", printed=PRINTED["40"], section="5.1", derivation="restates (39c)", quotes=('39c',))
def eq40(ctx: AuditContext) -> Finding:
    from hapticproof.audit.compare import compare_sign_conditions

    rel = ctx.relation()
    (other,) = [r.as_sympy() for r in parse_printed(PAPER.get("39c").printed, TABLE).relations()]
    cmp = compare_sign_conditions(rel.func(as_master(rel.lhs), as_master(rel.rhs), evaluate=False),
                                  other.func(as_master(other.lhs), as_master(other.rhs), evaluate=False), what="(40)")
    if cmp.verdict == Verdict.CONFIRMED:
        return Finding(Verdict.CONFIRMED, "the same inequality as (39c) (2x2 leading minor of K_pm)",
                       Evidence(Method.CANONICAL_FORM, facts={"printed_form": "same as (39c)"}))
    return Finding(Verdict.TYPO, f"differs from (39c): {cmp.detail}", Evidence(cmp.evidence.method, witness=cmp.evidence.witness,
                                                                              facts={"ids": ["40", "39c"]}))


@PAPER.equation("40-claim", kind="claim", after="40", section="5.1",
                printed="the condition set (39) holds if (40) and condition (39d) hold",
                derivation="(39a), (39b) follow from nonnegative gains (stated with (46)); without them they do not")
def claim_40(ctx: AuditContext) -> Finding:
    import random

    printed = {k: [r.as_sympy() for r in parse_printed(PAPER.get(k).printed, TABLE).relations()]
               for k in ("39a", "39b", "39c", "39d", "40")}

    def all_hold(conditions: list, values: dict) -> bool:
        return all(c.subs(values) is sp.true if (fast := relation_at(c, values)) is None else fast for c in conditions)

    # with the paper's nonnegative gains: (40) and (39d) must imply all of (39)
    rng = random.Random(40)
    names = sorted({x for conds in printed.values() for c in conds for x in c.free_symbols}, key=str)
    counter = None
    for _ in range(300):
        values = {x: sp.Rational(rng.randint(0, 12), rng.randint(1, 3)) for x in names}
        if all_hold(printed["40"] + printed["39d"], values) and not all_hold(
                [c for k in ("39a", "39b", "39c", "39d") for c in printed[k]], values):
            counter = values
            break
    facts = {"ids": ["40", "39a", "39b", "39c", "39d"]}
    if counter is not None:
        failing = [k for k in ("39a", "39b", "39c", "39d") if not all_hold(printed[k], counter)]
        return Finding(Verdict.WRONG, f"with nonnegative gains (40) and (39d) hold at the witness while {failing} fail",
                       Evidence(Method.COUNTEREXAMPLE, witness={str(k): v for k, v in counter.items()}, facts=facts))
    point = {gain("pm", "x", "x"): -1, gain("pm", "y", "y"): -1, gain("pm", "z", "z"): 1,
             gain("pm", "x", "y"): 0, gain("pm", "x", "z"): 0, gain("pm", "y", "z"): 0}
    without = all_hold(printed["40"] + printed["39d"], point) and not all_hold(printed["39a"], point)
    return Finding(Verdict.CONFIRMED,
                   "true because the paper takes all gains nonnegative (stated with (46)): then (39a), (39b) hold and (39) "
                   "reduces to (40) and (39d) (no counterexample among 300 exact nonnegative gain sets)"
                   + ("; without that assumption K_pm = diag(-1, -1, 1) meets (40), (39d) but not (39a)" if without else ""),
                   Evidence(Method.INSTANCES, instances=300, facts=facts))


TABLE1_PRINTED = (
    "Master k_{pmxx} 40 k_{pmyy} 40 k_{pmzz} 25 | k_{vmxx} 80 k_{vmyy} 80 k_{vmzz} 50 | k_{pmxy} 4 k_{pmxz} 3 k_{pmyz} 30 | "
    "k_{vmyx} 8 k_{vmxz} 6 k_{vmyz} 60 (6) || Slave k_{psxx} 80 k_{psyx} 80 k_{pszz} 50 | k_{vsxx} 160 k_{vsyy} 160 "
    "k_{vszz} 100 | k_{psxy} 8 k_{psxz} 6 k_{psyx} 60 | k_{vsxy} 16 k_{vsxz} 12 k_{vsyz} 120"
)


#: Table 1's layout: the twelve gains of each robot in printed order (the slave's are named alike).
TABLE1_LAYOUT = ("pxx", "pyy", "pzz", "vxx", "vyy", "vzz", "pxy", "pxz", "pyz", "vxy", "vxz", "vyz")


@PAPER.equation("table1", kind="claim", after="40", section="5.1", printed=TABLE1_PRINTED,
                derivation="literal names vs the ratio structure (38) of the values")
def table1(ctx: AuditContext) -> Finding:
    import re

    text = ctx.equation.printed
    master, _, slave = text.partition("||")
    read = {}
    clashes: dict[str, list[str]] = {}
    misplaced: list[tuple[str, str]] = []
    for robot, part in (("m", master), ("s", slave)):
        entries = re.findall(r"k_\{(\w+)\} (\d+)", part)
        if len(entries) != len(TABLE1_LAYOUT):
            return Finding(Verdict.MALFORMED, f"the {'master' if robot == 'm' else 'slave'} column lists {len(entries)} gains, "
                           f"not {len(TABLE1_LAYOUT)}", Evidence(Method.PARSE, facts={"entries": entries}))
        for (name, value), place in zip(entries, TABLE1_LAYOUT):
            expected = place[0] + robot + place[1:]
            symmetric = place[0] + robot + place[2] + place[1]
            read[expected] = sp.Integer(value)
            if name not in (expected, symmetric):
                clashes.setdefault(name, []).append(f"{value} at the {expected} place")
                misplaced.append((expected, value))
    ratios = {read[place[0] + "m" + place[1:]] / read[place[0] + "s" + place[1:]] for place in TABLE1_LAYOUT}
    facts = {"gains": {k: str(v) for k, v in read.items()}, "ratios": sorted(ratios), "misnamed": clashes}
    corrected = r",\quad ".join(f"k_{{{name}}} = {value}" for name, value in misplaced)
    one_ratio = len(ratios) == 1
    rho = next(iter(ratios)) if one_ratio else None
    if not one_ratio:
        return Finding(Verdict.INCONSISTENT,
                       f"master/slave gain ratios {sorted(map(str, ratios))} are not one ratio rho, as (38) requires"
                       + (f"; misnamed entries {sorted(clashes)}" if clashes else ""),
                       Evidence(Method.STRUCTURAL, witness={"ratios": sorted(map(str, ratios))}, facts=facts))
    if clashes:
        return Finding(Verdict.TYPO,
                       f"the table names entries at other places' names: {clashes}; read by their places, every master gain is "
                       f"{sp.sstr(rho)} times the slave gain (one ratio rho = {sp.sstr(rho)}, as (38) requires)",
                       Evidence(Method.STRUCTURAL, witness={"clashes": clashes}, facts=facts),
                       corrected=corrected.replace(", ", r",\quad "))
    return Finding(Verdict.CONFIRMED, f"names in their places and one master/slave ratio rho = {sp.sstr(rho)}, as (38) requires",
                   Evidence(Method.STRUCTURAL, facts=facts))


for _id in ("41a", "41b", "42", "43"):
    def _check(ctx: AuditContext) -> Finding:
        return _minor_check(ctx, "real", "real part of Z'(j omega)")
    PAPER.equation(_id, kind="condition", printed=PRINTED[_id], section="5.1", assumptions=ASSUME_CASE,
                   derivation="principal minors of Re Z'(j omega) under (38)")(_check)
