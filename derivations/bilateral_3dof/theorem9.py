r"""The 3-DOF paper, Section 4: Youla symmetrization (12)-(14), the conditions A-E of Theorem 9,
(15a)-(20).
"""

from __future__ import annotations

import itertools
from functools import lru_cache
from typing import Any

import sympy as sp

from hapticproof.exact.canonical import cancel as exact_cancel
from hapticproof.audit.runner import AuditContext
from hapticproof.exact.canonical import is_identically_zero
from hapticproof.core.evidence import Decision, Evidence, Finding, Method, Verdict
from hapticproof.analysis.networks import symmetrization_conditions, symmetrize
from hapticproof.analysis.nport import positive_real
from hapticproof.audit.reader.printed import parse_printed
from hapticproof.exact.rationalmatrix import RationalMatrix, matrix_psd
from hapticproof.core.symbols import s
from hapticproof.derivations.bilateral_3dof.paper import PAPER, PRINTED, TABLE, certified, cycle_network, definition, leading_minor_network, real_part_leading_minors, rhs_matrix, stacked, table1_impedance, table1_verdict
from hapticproof.derivations.bilateral_3dof.two_port import partition_blocks


def _section4_definitions() -> dict[str, tuple[str, Any, Any, Any]]:
    L = TABLE.lookup
    Z, Zb = partition_blocks()
    return {
        "8": ("impedance model of the 2-port with 3-DOF ports (6x1 = 6x6 * 6x1)", L(r"\mathcal{F}"),
              L(r"\mathcal{Z}") * L(r"\mathcal{V}"), None),
        "9": ("stacks the port forces F_1, F_2 (3x1 each; [F_1 F_2]^T read as the stack)", L(r"\mathcal{F}"),
              sp.BlockMatrix([[L("F_1")], [L("F_2")]]), stacked),
        "10": ("stacks the port velocities V_1, V_2 (3x1 each; [V_1 V_2]^T read as the stack)", L(r"\mathcal{V}"),
               sp.BlockMatrix([[L("V_1")], [L("V_2")]]), stacked),
        "11": ("block partition of Z (as (3))", Z, Zb, None),
        "13": ("block-diagonal termination of two 3-DOF (full 3x3) impedances", L(r"\mathcal{T}"),
               sp.BlockDiagMatrix(L(r"\mathbf{T}_1"), L(r"\mathbf{T}_2")), None),
    }


for _id in ("8", "9", "10", "11", "13"):
    def _check(ctx: AuditContext) -> Finding:
        what, lhs, rhs, reading = _section4_definitions()[ctx.equation.id]
        return definition(ctx, "defines " + what, lhs, rhs, reading=reading)
    PAPER.equation(_id, kind="expression", printed=PRINTED[_id], section="4", derivation="definition")(_check)


@PAPER.equation("12", kind="expression", printed=PRINTED["12"], section="4",
                derivation="the printed index map z_{3i-2,3j-2}, ... for i, j = 1, 2 vs the 3x3 partition of a 6x6 matrix")
def eq12(ctx: AuditContext) -> Finding:
    from hapticproof.audit.reader.statements import expand_indexed
    from hapticproof.audit.reader.names import index_symbol

    rel = ctx.statement.relations()[0]
    if rel.lhs != TABLE.lookup(r"\mathbf{Z}_{ij}"):
        return Finding(Verdict.TYPO, f"the display must define the block Z_ij; it defines {sp.sstr(rel.lhs)}",
                       Evidence(Method.PARSE, facts={"printed_form": sp.srepr(rel.lhs)}))
    M = rhs_matrix(ctx)
    i, j = index_symbol("i"), index_symbol("j")
    for bi in (1, 2):
        for bj in (1, 2):
            block = expand_indexed(M.subs({i: bi, j: bj}), 6, TABLE)
            expected = sp.Matrix(3, 3, lambda a, b: TABLE.concrete("z_{i,j}", (3 * (bi - 1) + a + 1, 3 * (bj - 1) + b + 1)))
            if block != expected:
                return Finding(Verdict.TYPO, f"block ({bi},{bj}) maps to the wrong entries",
                               Evidence(Method.CANONICAL_FORM, facts={"printed": block, "expected": expected}))
    return Finding(Verdict.CONFIRMED, "for i, j = 1, 2 the printed indices give exactly the four 3x3 blocks of the 6x6 matrix",
                   Evidence(Method.CANONICAL_FORM, instances=4))


@lru_cache(maxsize=1)
def _table1_symmetrization():
    return symmetrize(table1_impedance(60), (3, 3))


def _zprime_entry(i: int, j: int) -> sp.Expr:
    """Youla's z'_ij (1-based): z_ii on the diagonal, gamma_k sqrt(z_ij z_ji) off it, with k the
    position of the pair among the 15 upper pairs in row order (as (14) numbers them)."""
    z = lambda a, c: TABLE.concrete("z_{i,j}", (a, c))  # noqa: E731
    if i == j:
        return z(i, i)
    a, c = min(i, j), max(i, j)
    k = [(p, q) for p in range(1, 7) for q in range(p + 1, 7)].index((a, c)) + 1
    return TABLE.concrete(r"\gamma_{i}", (k,)) * sp.sqrt(z(a, c) * z(c, a))


def _zprime_reading(ctx: AuditContext) -> Finding | None:
    """The printed Z' (rows and columns 1, 2, ..., 6 with ellipses) against Youla's construction."""
    from hapticproof.audit.reader.statements import Elision

    rel = ctx.statement.relations()[0]
    M = sp.Matrix(rel.rhs)
    index = [1, 2, None, 6]
    problems = []
    if rel.lhs != TABLE.lookup(r"\mathcal{Z}'"):
        problems.append(f"the left side is {sp.sstr(rel.lhs)}, not Z'")
    if M.shape != (4, 4):
        problems.append(f"the printed matrix is {M.shape[0]}x{M.shape[1]}")
    else:
        for r in range(4):
            for c in range(4):
                entry, i, j = M[r, c], index[r], index[c]
                if i is None or j is None:
                    if not isinstance(entry, Elision):
                        problems.append(f"printed entry ({r + 1},{c + 1}) should be an ellipsis, it is {sp.sstr(entry)}")
                    continue
                if isinstance(entry, Elision) or not is_identically_zero(entry - _zprime_entry(i, j)):
                    problems.append(f"entry ({i},{j}) reads {sp.sstr(entry)} instead of {sp.sstr(_zprime_entry(i, j))}")
    if not problems:
        return None
    return Finding(Verdict.TYPO, "the printed Z' is not Youla's z'_ii = z_ii, z'_ij = gamma sqrt(z_ij z_ji): " + "; ".join(problems),
                   Evidence(Method.CANONICAL_FORM, facts={"problems": problems, "printed_form": sp.srepr(M)}))


@PAPER.equation("14", kind="expression", printed=PRINTED["14"], section="4",
                derivation="Youla's Z' for Table 1 (k_vmyz = 60): are the 15 signs gamma free?")
def eq14(ctx: AuditContext) -> Finding:
    reading = _zprime_reading(ctx)
    if reading is not None:
        return reading
    Y = _table1_symmetrization()
    Zp = Y.zprime()
    Z = table1_impedance(60)
    flipped = Zp.copy()
    flipped[0, 3] = flipped[3, 0] = -Zp[0, 3]
    rows = [0, 1, 3]
    at = {s: 1}
    mz = sp.nsimplify(sp.simplify(Z.extract(rows, rows).det().subs(at)))
    mp = sp.nsimplify(sp.simplify(Zp.extract(rows, rows).det().subs(at)))
    mf = sp.nsimplify(sp.simplify(flipped.extract(rows, rows).det().subs(at)))
    if mz == mp and mz != mf:
        return Finding(
            Verdict.NEEDS_ASSUMPTION,
            "Z' has the principal minors of Z only for consistent signs: gamma_ij gamma_jk gamma_ki sqrt(z_ij z_ji) "
            "sqrt(z_jk z_kj) sqrt(z_ki z_ik) = z_ij z_jk z_ki on every triangle (cycle), which fixes the gammas up to a "
            "diagonal +-1 similarity; the roots must be analytic branches. For Table 1, flipping gamma of entry (1,4) alone "
            f"changes the principal minor on rows (1,2,4) at s = 1 from {mz} to {mf}",
            Evidence(Method.COUNTEREXAMPLE, witness={"entry": [1, 4], "rows": [1, 2, 4], "s": 1},
                     facts={"minor_Z": mz, "minor_Zprime": mp, "minor_flipped": mf, "gamma": dict(Y.evidence.facts)["gamma"],
                            "printed_form": "Youla's Z' with free signs gamma"}),
            corrected=(r"z'_{ij} = \gamma_{ij}\sqrt{z_{ij}z_{ji}},\ \gamma_{ij}\gamma_{jk}\gamma_{ki}\sqrt{z_{ij}z_{ji}}"
                       r"\sqrt{z_{jk}z_{kj}}\sqrt{z_{ki}z_{ik}} = z_{ij}z_{jk}z_{ki}"),
        )
    return Finding(Verdict.UNDECIDED, "sign test inconclusive", Evidence(Method.INSTANCES))


PROSE_TABLE = TABLE.with_symbols({r"\mathbf{Z}_{\ell\ell}": sp.MatrixSymbol("Z_ll", 3, 3), r"\ell": sp.Symbol("ell")})


def _prose_math(text: str) -> list[Any]:
    """The mathematics of a prose condition (``\\text{...}`` removed): its expressions and the
    values of its index ranges, in printed order."""
    import re

    fragments = [f.replace(r"\quad", " ").strip(" ,.;") for f in re.split(r"\\text\{[^}]*\}", text)]
    joined = r", \quad ".join(f for f in fragments if f)
    if not joined:
        return []
    statement = parse_printed(joined, PROSE_TABLE)
    out = list(statement.expressions())
    for r in getattr(statement, "ranges", ()):
        out.append(tuple(r.values))
    return out


def _prose_reading(ctx: AuditContext, expected: list[Any], what: str) -> Finding | None:
    found = _prose_math(ctx.equation.printed)
    if found == expected:
        return None
    return Finding(Verdict.TYPO, f"{what} must refer to {', '.join(map(sp.sstr, expected))}; the text's mathematics is "
                   f"{', '.join(map(sp.sstr, found)) or 'missing'}", Evidence(Method.PARSE, facts={"printed_form": [sp.srepr(x) for x in found]}))


def _expected_prose(eq_id: str) -> list[Any]:
    L = PROSE_TABLE.lookup
    return {"14b": [L(r"\mathbf{Z}_{\ell\ell}"), (sp.Integer(1), sp.Integer(2))], "14c": [L(r"\mathcal{Z}")],
            "14d": [L(r"\mathcal{Z}"), L(r"\mathcal{Z}")], "14e": [L(r"\omega"), L(r"\mathcal{Z}'")]}[eq_id]


@PAPER.equation("14a", kind="condition", printed=PRINTED["14a"], section="4",
                derivation="A and B vs Youla's equivalence (identical principal and block-compatible minors)")
def condition_a(ctx: AuditContext) -> Finding:
    from hapticproof.audit.reader.statements import expand_indexed
    from hapticproof.audit.reader.names import index_symbol

    statement = ctx.statement
    i, j, k = (index_symbol(x) for x in "ijk")
    (rel,) = [r.as_sympy() for r in statement.relations()]
    problems = []
    ranges = [(tuple(map(str, r.indices)), tuple(map(str, r.values))) for r in getattr(statement, "ranges", ())]
    if ranges != [(("i", "j", "k"), ("1", "2", r"\dots", "6"))]:
        problems.append(f"the indices must run over 1..6, the display has {ranges}")
    for triple in ((1, 2, 3), (1, 4, 2), (2, 5, 6), (3, 6, 4)):
        got = expand_indexed((rel.lhs - rel.rhs).subs(dict(zip((i, j, k), triple))), 6, TABLE)
        z = lambda a, c: TABLE.concrete("z_{i,j}", (a, c))  # noqa: E731
        a, c, e = triple
        cycle = z(a, c) * z(c, e) * z(e, a) - z(c, a) * z(e, c) * z(a, e)
        if not (is_identically_zero(got - cycle) or is_identically_zero(got + cycle)):
            problems.append(f"for (i, j, k) = {triple} it reads {sp.sstr(got)} = 0, not the triangle condition {sp.sstr(cycle)} = 0")
            break
    if problems:
        return Finding(Verdict.TYPO, "condition A as printed is not Youla's triangle condition: " + "; ".join(problems),
                       Evidence(Method.CANONICAL_FORM, facts={"problems": problems, "printed_form": sp.srepr(rel)}))
    Z = cycle_network()
    conditions = symmetrization_conditions(Z, ports=(3, 3))
    sym = symmetrize(Z, (3, 3))
    roots, degree, passive = certified("cycle")
    if not conditions and sym.symmetrizable == Decision.DISPROVED and roots and passive:
        return Finding(
            Verdict.NEEDS_ASSUMPTION,
            "A (with B) makes the principal minors of Z' and Z agree only when the entries it cancels are nonzero; "
            "with vanishing entries longer cycles matter: the network cycle_network() (couplings on the cycle 1-4-2-5 only, "
            "z_14 = 2, z_41 = 1/2, others 1) satisfies A and B, but its 4x4 minor on (1,2,4,5) cannot be matched by any Z' "
            f"({sym.reason}) and passive terminations 1/(10(s+1)) make it unstable (det(Z + T) = 0 at s ~ {roots[0].real:.4g})",
            Evidence(Method.COUNTEREXAMPLE, witness={"Z": Z}, facts={"rhp_roots": [str(r) for r in roots], "symmetrization": sym.reason,
                                                                     "printed_form": "Youla's triangle condition"}),
            corrected=(r"z_{i_1 i_2} z_{i_2 i_3} \cdots z_{i_k i_1} = z_{i_2 i_1} z_{i_3 i_2} \cdots z_{i_1 i_k}"
                       r"\ \text{for every cycle } (i_1, \dots, i_k),\ k \geq 3"),
        )
    return Finding(Verdict.UNDECIDED, "the cycle counterexample did not verify", Evidence(Method.INSTANCES))


@PAPER.equation("14b", kind="condition", printed=PRINTED["14b"], section="4", parse=False,
                derivation="det(Z + T) = det(Z' + T) for full block terminations T, one 2-DOF port, symbolic")
def condition_b(ctx: AuditContext) -> Finding:
    reading = _prose_reading(ctx, _expected_prose("14b"), "condition B")
    if reading is not None:
        return reading
    a, b, c, d = sp.symbols("a b c d", positive=True)
    t = sp.Matrix(2, 2, sp.symbols("t11 t12 t21 t22"))
    Z = sp.Matrix([[a, b], [c, d]])
    Zp = sp.Matrix([[a, sp.sqrt(b * c)], [sp.sqrt(b * c), d]])
    diff = sp.expand((Z + t).det() - (Zp + t).det())
    coeffs = [diff.coeff(t[0, 1]), diff.coeff(t[1, 0])]
    solutions = sp.solve(coeffs, [b], dict=True)
    if solutions and all(is_identically_zero(sol[b] - c) for sol in solutions):
        return Finding(Verdict.CONFIRMED,
                       "needed for block (multi-DOF) terminations: det(Z + T) - det(Z' + T) has the coefficients "
                       f"{[sp.sstr(x) for x in coeffs]} of t_12 and t_21, which vanish only for z_12 = z_21 (B); for diagonal "
                       "terminations (single-DOF ports) B is not needed",
                       Evidence(Method.CANONICAL_FORM, facts={"difference": diff}))
    return Finding(Verdict.WRONG, "B is not implied by the determinant identity", Evidence(Method.CANONICAL_FORM, facts={"difference": diff}))


@PAPER.equation("14c", kind="condition", printed=PRINTED["14c"], section="4", parse=False,
                derivation="open-port stability: an unstable z_ij invisible to Z'")
def condition_c(ctx: AuditContext) -> Finding:
    reading = _prose_reading(ctx, _expected_prose("14c"), "condition C")
    if reading is not None:
        return reading
    from hapticproof.exact.rationalmatrix import pole_report

    Z = sp.Matrix([[1, 1 / (s - 1)], [0, 1]])
    sym = symmetrize(sp.Matrix([[1, 0], [0, 1]]))
    zprime_pr = positive_real(sp.eye(2))
    coupled = (RationalMatrix.from_sympy(Z) + RationalMatrix.from_sympy(sp.eye(2))).inverse()
    unstable = pole_report(coupled).rhp
    if unstable and zprime_pr.decision == Decision.PROVED and sym.symmetrizable == Decision.PROVED:
        return Finding(Verdict.CONFIRMED,
                       "necessary, and not implied by positive realness of Z': for Z = [[1, 1/(s-1)], [0, 1]] Youla's Z' = I is "
                       "positive real, yet with unit resistive terminations the map from source to port velocities, (Z + I)^-1, "
                       "has a pole at s = 1",
                       Evidence(Method.COUNTEREXAMPLE, witness={"Z": Z}, facts={"pole": str(unstable[0][1])}))
    return Finding(Verdict.UNDECIDED, "example did not verify", Evidence(Method.INSTANCES))


@PAPER.equation("14d", kind="condition", printed=PRINTED["14d"], section="4", parse=False,
                derivation="residue matrix of Z' at s = 0 for Table 1 (k_vmyz = 60), exact")
def condition_d(ctx: AuditContext) -> Finding:
    reading = _prose_reading(ctx, _expected_prose("14d"), "condition D")
    if reading is not None:
        return reading
    Zp = _table1_symmetrization().zprime()
    R = Zp.applyfunc(lambda e: exact_cancel(e * s).subs(s, 0))
    leading = [sp.nsimplify(sp.simplify(R[:k, :k].det())) for k in range(1, 7)]
    verdict = table1_verdict(60)
    psd, _ = matrix_psd(R)
    if verdict.decision == Decision.PROVED and leading[3] == 0 and psd:
        return Finding(
            Verdict.WRONG,
            "not necessary: for the paper's own Table 1 gains (k_vmyz = 60), absolutely stable (Z' positive real, verified), "
            f"the residue matrix of Z' at s = 0 has rank 3 and leading principal minors {[sp.sstr(v) for v in leading]}, so "
            "'greater than zero' fails; the residues must be Hermitian PSD (all principal minors >= 0), and they are those of "
            "Z' (the residue matrix of Z, [[K_pm, -K_pm], [-K_ps, K_ps]], is not even symmetric)",
            Evidence(Method.COUNTEREXAMPLE, witness={"gains": "Table 1, k_vmyz = 60"},
                     facts={"leading_minors": leading, "residue_psd": psd, "absolute_stability": verdict.reason}),
            corrected=(r"\text{D) Any poles of the elements of } \mathcal{Z}' \text{ on the imaginary axis (and at infinity) are simple,"
                       r" with Hermitian positive semidefinite residue matrices (all principal minors} \geq 0)"),
        )
    return Finding(Verdict.UNDECIDED, "the residue test did not behave as expected", Evidence(Method.INSTANCES, facts={"leading": leading}))


@PAPER.equation("14e", kind="condition", printed=PRINTED["14e"], section="4", parse=False,
                derivation="leading minors >= 0 vs PSD; exact destabilizing terminations")
def condition_e(ctx: AuditContext) -> Finding:
    reading = _prose_reading(ctx, _expected_prose("14e"), "condition E")
    if reading is not None:
        return reading
    Z = leading_minor_network()
    leading = [Z[:k, :k].det() for k in range(1, 7)]
    roots, degree, passive = certified("leading")
    if all(v >= 0 for v in leading) and roots and passive:
        return Finding(
            Verdict.WRONG,
            "leading principal minors >= 0 do not give PSD: the reciprocal network Z = diag([[0,0,0],[0,1,2],[0,2,1]], I_3) "
            "(Z' = Z) has all leading minors 0 and satisfies A-D, but passive terminations diag(1, 2/(s+1), 2/(s+1)), I_3 make "
            f"det(Z + T) vanish at s = {roots[0].real:.4g} > 0; all principal minors of Re Z'(jw) must be >= 0",
            Evidence(Method.COUNTEREXAMPLE, witness={"Z": Z}, facts={"leading_minors": leading, "rhp_roots": [str(r) for r in roots]}),
            corrected=(r"\text{E) For all real } \omega, \text{ all principal minors of } \text{Re}(\mathcal{Z}'(j\omega))"
                       r"\text{ are } \geq 0"),
        )
    return Finding(Verdict.UNDECIDED, "the counterexample did not verify", Evidence(Method.INSTANCES))


@PAPER.equation("15a", kind="condition", printed=PRINTED["15a"], section="4",
                derivation="1x1 principal minors of Re Z': z'_ii = z_ii by (14)")
def eq15a(ctx: AuditContext) -> Finding:
    from hapticproof.audit.compare import as_sign_condition
    from hapticproof.audit.reader.statements import expand_indexed
    from hapticproof.audit.reader.names import index_symbol

    statement = ctx.statement
    ranges = [tuple(map(str, r.values)) for r in getattr(statement, "ranges", ())]
    (rel,) = [r.as_sympy() for r in statement.relations()]
    condition = as_sign_condition(rel)
    i = index_symbol("i")
    read = [expand_indexed(condition.expr.subs(i, k), 6, TABLE) for k in range(1, 7)]
    want = [sp.re(TABLE.concrete("z_{i,j}", (k, k))) for k in range(1, 7)]
    problems = []
    if ranges != [("1", "2", r"\dots", "6")]:
        problems.append(f"the index must run over all six diagonal entries, the display has {ranges}")
    if condition.op not in (">=",):
        problems.append(f"a principal minor of a PSD matrix is >= 0, the display says {condition.op} 0")
    if read != want:
        problems.append(f"it reads {[sp.sstr(x) for x in read[:2]]}... >= 0 instead of Re z_ii >= 0")
    if problems:
        if condition.op != ">=":
            return Finding(Verdict.WRONG,
                           "(15a) is not the 1x1 principal-minor condition Re z_ii >= 0, i = 1..6: " + "; ".join(problems),
                           Evidence(Method.PARSE, facts={"problems": problems, "printed_form": sp.srepr(rel)}))
        return Finding(Verdict.TYPO,
                       "(15a) has the relation of a 1x1 principal-minor condition but not its entries or range: "
                       + "; ".join(problems),
                       Evidence(Method.PARSE, facts={"problems": problems, "printed_form": sp.srepr(rel)}),
                       corrected=r"\text{Re}(z_{i,i}) \geq 0, \quad i = 1, 2, \dots, 6")
    Y = _table1_symmetrization()
    Z = table1_impedance(60)
    same = all(is_identically_zero(Y.zprime()[i, i] - Z[i, i]) for i in range(6))
    if not same:
        return Finding(Verdict.WRONG, "diagonal of Z' differs from Z", Evidence(Method.CANONICAL_FORM))
    return Finding(Verdict.CONFIRMED, "Re z'_ii = Re z_ii >= 0 are the 1x1 principal minors of Re Z' (necessary; all six, "
                   "not only the leading one)", Evidence(Method.CANONICAL_FORM, facts={"checked_on": "Table 1",
                                                                                      "printed_form": "Re z_ii >= 0, i = 1..6"}))


@PAPER.equation("15b", kind="condition", printed=PRINTED["15b"], section="4",
                derivation="2nd leading minor of Re Z' with (20): Re z11 Re z22 - (|z12 z21| + Re z12 z21)/2")
def eq15b(ctx: AuditContext) -> Finding:
    from hapticproof.audit.compare import as_sign_condition

    condition = as_sign_condition(ctx.relation())
    printed_lhs = condition.expr
    z = {(i, j): TABLE.concrete("z_{i,j}", (i, j)) for i in (1, 2) for j in (1, 2)}
    p = z[(1, 2)] * z[(2, 1)]
    derived = sp.re(z[(1, 1)]) * sp.re(z[(2, 2)]) - (sp.Abs(p) + sp.re(p)) / 2
    slip = sp.re(z[(1, 1)]) * sp.re(z[(2, 2)]) - sp.Abs(sp.re(p))           # |Re(z12 z21)| printed twice
    point = {z[(1, 1)]: 2, z[(2, 2)]: 3, z[(1, 2)]: 1 + 2 * sp.I, z[(2, 1)]: 3 - sp.I}
    value_p, value_d = sp.nsimplify(sp.simplify(printed_lhs.subs(point))), sp.nsimplify(sp.simplify(derived.subs(point)))
    facts = {"printed": value_p, "derived": value_d, "printed_form": (condition.op, sp.srepr(sp.expand(printed_lhs)))}
    corrected = r"\text{Re}(z_{1,1})\text{Re}(z_{2,2}) - \frac{|z_{1,2}z_{2,1}| + \text{Re}(z_{1,2}z_{2,1})}{2} \geq 0"
    witness = {"z11": 2, "z22": 3, "z12": "1+2j", "z21": "3-j"}
    if condition.op != ">=":
        return Finding(Verdict.WRONG, f"a principal minor of a PSD matrix is >= 0; the display says {condition.op} 0 "
                       f"(at the witness the printed expression is {value_p}, the minor {value_d})",
                       Evidence(Method.COUNTEREXAMPLE, witness=witness, facts=facts), derived=sp.Ge(derived, 0), corrected=corrected)
    if is_identically_zero(sp.expand(printed_lhs - derived)):
        return Finding(Verdict.CONFIRMED, "the printed minor is Re z11 Re z22 - (|z12 z21| + Re z12 z21)/2, by (20)",
                       Evidence(Method.CANONICAL_FORM, facts=facts), derived=sp.Ge(derived, 0))
    cause = ("the printed numerator |Re(z12 z21)| + |Re(z12 z21)| repeats one term: (20) gives |z12 z21| + Re(z12 z21)"
             if is_identically_zero(sp.expand(printed_lhs - slip)) else "it is not the 2nd minor given by (20)")
    return Finding(Verdict.TYPO,
                   f"{cause}; at z11 = 2, z22 = 3, z12 = 1 + 2j, z21 = 3 - j the printed minor is {value_p}, the true one "
                   f"{value_d}", Evidence(Method.COUNTEREXAMPLE, witness=witness, facts=facts),
                   derived=sp.Ge(derived, 0), corrected=corrected)


@PAPER.equation("15c", kind="condition", printed=PRINTED["15c"], section="4",
                derivation="the 6th principal minor of Re Z' (exact for Table 1)")
def eq15c(ctx: AuditContext) -> Finding:
    from hapticproof.audit.compare import as_sign_condition

    condition = as_sign_condition(ctx.relation())
    Zp = TABLE.lookup(r"\mathcal{Z}'")
    # the printed left side evaluated at test matrices A (in place of Z') against det Re A
    rng = __import__("random").Random(15)
    tests = []
    for _ in range(3):
        A = sp.Matrix(6, 6, lambda i, j: sp.Rational(rng.randint(-5, 5), rng.randint(1, 3))
                      + sp.I * sp.Rational(rng.randint(-5, 5), rng.randint(1, 3)))
        read = sp.nsimplify(sp.expand(condition.expr.subs(Zp, sp.ImmutableMatrix(A)).doit()))
        tests.append((read, ((A + A.conjugate()) / 2).det()))
    ratios = {sp.nsimplify(r / d) if d != 0 else None for r, d in tests}
    facts = {"printed_over_det_re": [str(r) for r in ratios], "printed_form": (condition.op, sorted(map(str, ratios)))}
    if len(ratios) != 1 or None in ratios or not list(ratios)[0].is_positive or condition.op not in (">=",):
        return Finding(Verdict.WRONG, f"(15c) reads {sp.sstr(condition.expr)} {condition.op} 0, not det Re Z' >= 0 (the full "
                       f"principal minor): at three test matrices the printed left side over det Re A is {sorted(map(str, ratios))}",
                       Evidence(Method.COUNTEREXAMPLE, facts=facts), derived=sp.Ge(sp.Symbol("det_Re_Zp"), 0),
                       corrected=r"\det(\text{Re}(\mathcal{Z}')) \geq 0")
    det = real_part_leading_minors()[5]
    return Finding(Verdict.CONFIRMED,
                   "det Re Z' >= 0 is a necessary condition (the full principal minor); under (38) it is identically "
                   f"{det} (Re Z' has rank 3), so it holds but says nothing -- the order-1..3 principal minors decide",
                   Evidence(Method.CANONICAL_FORM, facts={**facts, "det_under_38": det, "printed_form": "det Re Z' >= 0"}))


@PAPER.equation("thm9", kind="claim", after="15c", section="4",
                printed="Theorem 9. An 3-DOF bilateral haptic system with impedance matrix \\mathcal{Z} in (11) satisfying the "
                        "symmetrization conditions A) B) is absolutely stable if and only if C) D) E)",
                derivation="a network satisfying A-E (even E with all principal minors) with verified destabilizing terminations")
def theorem9(ctx: AuditContext) -> Finding:
    Z = cycle_network()
    roots, degree, passive = certified("cycle")
    conditions = symmetrization_conditions(Z, ports=(3, 3))
    gammas = []
    for g in itertools.product((1, -1), repeat=4):
        Zp = sp.Matrix(Z)
        for (a, b), sign in zip(((0, 3), (3, 1), (1, 4), (4, 0)), g):
            Zp[a, b] = Zp[b, a] = sign
        gammas.append(matrix_psd(Zp)[0])
    if not conditions and roots and passive and all(gammas):
        return Finding(
            Verdict.WRONG,
            "the 'if' fails: cycle_network() satisfies A and B, has no poles (C, D), and Re Z' = Z' is PSD for every sign "
            f"choice of (14) (E, even with all principal minors), yet passive terminations make det(Z + T) vanish at "
            f"s ~ {roots[0].real:.4g} > 0; besides, D and E as printed use leading minors (see 14d, 14e)",
            Evidence(Method.COUNTEREXAMPLE, witness={"Z": Z},
                     facts={"rhp_roots": [str(r) for r in roots], "zprime_psd_for_all_signs": True}),
            corrected=(r"\text{If } \mathcal{Z}' \text{ with the same principal and block-compatible minors as } \mathcal{Z}"
                       r"\text{ exists, } \mathcal{Z} \text{ is absolutely stable iff C holds and } \mathcal{Z}' \text{ is positive real}"),
        )
    return Finding(Verdict.UNDECIDED, "the counterexample did not verify", Evidence(Method.INSTANCES))


@PAPER.equation("16", kind="expression", printed=PRINTED["16"], section="4", derivation="Laplace transform, checked on h = e^{-2t}")
def eq16(ctx: AuditContext) -> Finding:
    rel = ctx.statement.relations()[0]
    t = TABLE.lookup("t")
    h = sp.Function("h")
    if rel.lhs != sp.Function("H")(s) or rel.ops != ("=",):
        return Finding(Verdict.TYPO, f"the display must define H(s); it reads {sp.sstr(rel.lhs)} {rel.ops[0]} ...",
                       Evidence(Method.PARSE, facts={"printed_form": sp.srepr(rel.lhs)}))
    value = rel.rhs.subs(h(t), sp.exp(-2 * t)).subs(s, 3).doit()
    if value == sp.Rational(1, 5):
        return Finding(Verdict.CONFIRMED, "the one-sided Laplace transform (for h = e^{-2t} at s = 3 it gives 1/(s+2) = 1/5)",
                       Evidence(Method.INSTANCES, instances=1))
    return Finding(Verdict.TYPO, f"gives {value} for h = e^(-2t) at s = 3, where the Laplace transform is 1/5",
                   Evidence(Method.INSTANCES, facts={"printed_form": sp.srepr(rel.rhs)}))


def _det_with_diagonal(M: sp.Matrix, t: list) -> sp.Expr:
    return (M + sp.diag(*t)).det(method="berkowitz")


def _det_identity(ctx: AuditContext, first: Any, second: Any, termination: Any, blocks: bool, label: str) -> Finding | None:
    """The printed ``det(X + T) = det(Y + T)`` evaluated with X := Z, Y := Z' of Table 1 at exact
    instances (diagonal or full block terminations T); a finding when it is not that identity."""
    import random

    (rel,) = ctx.statement.relations()
    symbols = rel.lhs.free_symbols | rel.rhs.free_symbols
    if rel.ops != ("=",) or first not in rel.lhs.free_symbols | rel.rhs.free_symbols or second not in symbols \
            or (first in rel.lhs.free_symbols) == (first in rel.rhs.free_symbols):
        return Finding(Verdict.WRONG, f"{label} must equate det(Z + T) and det(Z' + T); it reads {sp.sstr(rel.as_sympy())}",
                       Evidence(Method.PARSE, facts={"printed_form": sp.srepr(rel.as_sympy())}))
    Z = table1_impedance(60)
    Zp = _table1_symmetrization().zprime()
    rng = random.Random(17)
    for _ in range(3):
        point = sp.Rational(rng.randint(1, 9), rng.randint(1, 4))
        if blocks:
            T = sp.diag(*[sp.Matrix(3, 3, lambda i, j: sp.Rational(rng.randint(0, 9), rng.randint(1, 5))) for _ in range(2)])
        else:
            T = sp.diag(*[sp.Rational(rng.randint(0, 9), rng.randint(1, 5)) for _ in range(6)])
        values = {first: sp.ImmutableMatrix(Z.subs(s, point)), second: sp.ImmutableMatrix(Zp.subs(s, point)),
                  termination: sp.ImmutableMatrix(T)}
        a, c = (sp.nsimplify(sp.simplify(side.xreplace(values).doit())) for side in (rel.lhs, rel.rhs))
        if sp.simplify(a - c) != 0:
            return Finding(Verdict.WRONG, f"{label} fails for Table 1 at s = {point}: {sp.sstr(a)} vs {sp.sstr(c)}",
                           Evidence(Method.COUNTEREXAMPLE, witness={"s": point, "T": T}, facts={"printed_form": sp.srepr(rel.as_sympy())}))
    return None


@PAPER.equation("17", kind="condition", printed=PRINTED["17"], section="4",
                derivation="det(Z + diag t) = sum over S of det Z[S] prod_{i not in S} t_i; exact instances for Table 1 and its Z'")
def eq17(ctx: AuditContext) -> Finding:
    L = TABLE.lookup
    failure = _det_identity(ctx, L("Z_1"), L("Z_2"), L("T_0"), False, "(17)")
    if failure is not None:
        return failure
    return Finding(Verdict.CONFIRMED,
                   "det(Z + T_0) expands into principal minors of Z times products of the t_i, so identical principal minors "
                   "give equal determinants for every diagonal T_0 (checked exactly on 3 instances for Table 1 and its Z')",
                   Evidence(Method.INSTANCES, instances=3, facts={"printed_form": "det(Z + T) = det(Z' + T), T diagonal"}))


@PAPER.equation("18", kind="condition", printed=PRINTED["18"], section="4",
                derivation="all block-compatible minors of Z and Z' (Table 1, k_vmyz = 60), exact")
def eq18(ctx: AuditContext) -> Finding:
    L = TABLE.lookup
    failure = _det_identity(ctx, L(r"\mathcal{Z}'"), L(r"\mathcal{Z}"), L(r"\mathcal{T}"), True, "(18)")
    if failure is not None:
        return failure
    Y = _table1_symmetrization()
    if Y.symmetrizable == Decision.PROVED:
        count = Y.evidence.facts.get("block_compatible_minors_checked")
        return Finding(Verdict.CONFIRMED,
                       "for 3-DOF block terminations det(Z + T) = det(Z' + T) holds iff every minor of Z with the same number of "
                       f"rows and columns in each port equals that of Z'; verified exactly for Table 1 ({count} minors) and on 3 "
                       "exact block terminations. A and B alone do not guarantee it (see 14a)",
                       Evidence(Y.evidence.method, facts={**dict(Y.evidence.facts), "printed_form": "det(Z' + T) = det(Z + T)"}))
    return Finding(Verdict.WRONG, Y.reason, Y.evidence)


@PAPER.equation("19", kind="condition", printed=PRINTED["19"], section="4", parse=False,
                derivation="Z'(-jw) = conj Z'(jw) for a real-rational symmetric Z' (Table 1)")
def eq19(ctx: AuditContext) -> Finding:
    import mpmath

    Y = _table1_symmetrization()
    Zp_sym = Y.zprime()
    table = TABLE.with_functions({r"\mathcal{Z}'": lambda a: sp.ImmutableMatrix(Zp_sym.subs(s, a))})
    (rel,) = parse_printed(ctx.equation.printed, table).relations()
    w_sym = TABLE.lookup(r"\omega")
    variables = sorted(sp.Matrix(rel.lhs - rel.rhs).free_symbols, key=str)
    if len(variables) != 1 or not variables[0].is_real:
        return Finding(Verdict.WRONG, f"the printed identity is not one in a real frequency: its sides hold "
                       f"{[str(v) for v in variables]}", Evidence(Method.PARSE, facts={"variables": [str(v) for v in variables]}))
    (var,) = variables                      # the printed frequency (a renamed one is the same identity)
    form = sp.srepr(rel.as_sympy().xreplace({var: w_sym}))
    residual = 0.0
    for w in (1, 3):
        gap = sp.Matrix(rel.lhs - rel.rhs).subs(var, w).evalf(30)
        residual = max(residual, float(gap.norm()))
    if rel.ops != ("=",) or residual > 1e-12:
        return Finding(Verdict.WRONG, f"the printed identity does not hold for Table 1's Z': |lhs - rhs| = {residual:.3g} at "
                       f"{var} = 1 or 3", Evidence(Method.COUNTEREXAMPLE, witness={str(var): [1, 3]},
                                                    facts={"residual": residual, "printed_form": form}))
    positive = all(c > 0 for c in Y.c.values())
    Zp = Y.zprime()
    worst = mpmath.mpf(0)
    with mpmath.workdps(40):
        for w in (1, 3):
            for i in range(6):
                for j in range(6):
                    a = complex(sp.N(Zp[i, j].subs(s, sp.I * w), 40))
                    b = complex(sp.N(Zp[j, i].subs(s, -sp.I * w), 40))
                    worst = max(worst, abs(a + b - 2 * a.real))
    if positive and worst < 1e-12:
        return Finding(Verdict.CONFIRMED,
                       "every off-diagonal z'_ij = gamma sqrt(c_ij) q_ij(s) has c_ij > 0 and q_ij real-rational (Table 1), so Z' "
                       "is symmetric with real coefficients, Z'^T(-jw) = conj Z'(jw) and the Hermitian part is 2 Re Z'(jw) "
                       "(numerically re-checked at w = 1, 3); when some z_ij z_ji is a negative constant times a square, Z' has "
                       "imaginary entries and Z'^H(jw) must replace Z'^T(-jw)",
                       Evidence(Method.STRUCTURAL, facts={"c": {f"{i},{j}": v for (i, j), v in Y.c.items()}, "max_residual": float(worst),
                                                          "printed_form": form}))
    return Finding(Verdict.UNDECIDED,
                   f"the printed identity holds at w = 1, 3, but Table 1's Z' is not symmetric with real coefficients "
                   f"(all c_ij > 0: {positive}; largest |z'_ij(jw) + z'_ji(-jw) - 2 Re z'_ij(jw)| = {float(worst):.3g})",
                   Evidence(Method.COUNTEREXAMPLE, facts={"max_residual": float(worst), "printed_form": form}))


@PAPER.equation("20", kind="condition", printed=PRINTED["20"], section="4",
                derivation="principal square root: exact Gaussian-rational instances")
def eq20(ctx: AuditContext) -> Finding:
    rel = ctx.statement.relations()[0]
    zij, zji = TABLE.concrete("z_{i,j}", (1, 2)), TABLE.concrete("z_{i,j}", (2, 1))
    from hapticproof.audit.reader.statements import expand_indexed
    from hapticproof.audit.reader.names import index_symbol

    i, j = index_symbol("i"), index_symbol("j")
    lhs = expand_indexed(rel.lhs.subs({i: 1, j: 2}), 6, TABLE)
    rhs = expand_indexed(rel.rhs.subs({i: 1, j: 2}), 6, TABLE)
    count = 0
    for a, b in ((1, 2), (3, -1), (-2, 5), (1, 0), (-3, -4), (0, 2)):
        w = sp.expand((a + sp.I * b) ** 2)
        point = {zij: w, zji: 1}
        left, right = sp.nsimplify(sp.simplify(lhs.subs(point))), sp.nsimplify(sp.simplify(rhs.subs(point)))
        if not is_identically_zero(left - right) or not is_identically_zero(left - abs(a)):
            return Finding(Verdict.WRONG, f"fails at w = {w}", Evidence(Method.COUNTEREXAMPLE, witness={"w": w}))
        count += 1
    return Finding(Verdict.CONFIRMED,
                   "for the principal branch Re sqrt(w) = sqrt((|w| + Re w)/2) >= 0 (w = r e^{j phi}: Re = sqrt(r) cos(phi/2)); "
                   f"checked exactly on {count} instances w = (a + jb)^2; it fixes (Re z'_ij)^2 whatever gamma, but the sign of "
                   "Re z'_ij (needed in minors of order >= 3) follows the analytic branch, not the principal one",
                   Evidence(Method.INSTANCES, instances=count))
