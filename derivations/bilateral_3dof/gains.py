r"""The 3-DOF paper, Sections 5.1-5.2: the gain conditions (44)-(46), the masses of Section 5.2,
the termination (47) and the energy runs of Fig. 3.
"""

from __future__ import annotations

import itertools
from dataclasses import dataclass
from typing import Any

import sympy as sp

from hapticproof.audit.runner import AuditContext
from hapticproof.core.evidence import Decision, Evidence, Finding, Method, Plot, Series, Verdict
from hapticproof.analysis.networks import absolute_stability, symmetrization_conditions
from hapticproof.analysis.nport import positive_real
from hapticproof.audit.reader.names import SymbolTable
from hapticproof.audit.reader.printed import parse_printed
from hapticproof.core.symbols import s
from hapticproof.derivations.bilateral_3dof.paper import ASSUME_CASE, AXES, PAPER, PRINTED, TABLE, canonical, case_study_impedance, certificate_facts, compact_impedance, compact_set_counterexample, fig3_energy, gain, gain_matrix, master_input_impedance, not_in_s, one_line, pr_facts, pr_text, real_part_leading_minors, real_part_zprime, rho, rhs_matrix, searched_terminations, table1_gains, table1_verdict
from hapticproof.derivations.bilateral_3dof.case_study import CORRECTED_38C, as_master


@PAPER.equation("44", kind="condition", printed=PRINTED["44"], section="5.1", assumptions=ASSUME_CASE,
                derivation="the 4th leading principal minor of Re Z'(j omega) under (38)")
def eq44(ctx: AuditContext) -> Finding:
    from hapticproof.audit.compare import as_sign_condition

    rel = ctx.relation()
    capital = TABLE.lookup("K_{vmxx}")
    condition = as_sign_condition(rel)
    printed = as_master(condition.expr.subs(capital, gain("vm", "x", "x")))
    fourth = real_part_leading_minors()[3]
    R = real_part_zprime()
    Kvm = gain_matrix("vm", True)
    u = sp.Matrix([1, -1 / sp.sqrt(rho)])
    structure = (R - sp.kronecker_product(u * u.T, Kvm)).applyfunc(sp.simplify) == sp.zeros(6, 6)
    values = {gain("vm", AXES[i], AXES[j]): table1_gains(60)["vm"][i, j] for i in range(3) for j in range(i, 3)}
    values[rho] = sp.Rational(1, 2)
    at_table = sp.nsimplify(sp.simplify(printed.subs(values)))
    holds = {">": at_table > 0, ">=": at_table >= 0, "=": at_table == 0, "!=": at_table != 0}[condition.op] \
        if at_table.is_real else None
    form = (condition.op, sp.srepr(sp.expand(printed)))
    if fourth == 0 and structure and holds is not None:
        fails = ("although that teleoperator is absolutely stable, the printed condition fails there" if not holds else
                 "so it separates nothing there")
        return Finding(Verdict.WRONG,
                       "under (38) Re Z'(j omega) = u u^T (x) K_vm with u = (1, -1/sqrt(rho)) has rank <= 3, so its 4th (and 5th, "
                       "6th) leading minor is identically 0: the condition is void. The printed expression "
                       f"({condition.op} 0) is not a minor of Re Z' (it also writes K_vmxx for k_vmxx); at the Table 1 gains with "
                       f"k_vmyz = 60 it is {at_table}: {fails}",
                       Evidence(Method.CANONICAL_FORM, witness={"gains": "Table 1, k_vmyz = 60"},
                                facts={"fourth_leading_minor": fourth, "printed_at_table1": at_table, "printed_form": form}),
                       derived=sp.Ge(fourth, 0), corrected=r"\det\left(\text{Re}\,\mathcal{Z}'\right)_{4\times 4} = 0 \geq 0")
    return Finding(Verdict.UNDECIDED, "4th minor not established", Evidence(Method.CANONICAL_FORM, facts={"fourth": fourth}))


@PAPER.equation("45", kind="condition", printed=PRINTED["45"], section="5.1", assumptions=ASSUME_CASE,
                derivation="Table 1 (k_vmyz = 60) against (45) and against the exact absolute-stability verdict")
def eq45(ctx: AuditContext) -> Finding:
    rel = ctx.relation()
    values = {gain("vm", AXES[i], AXES[j]): table1_gains(60)["vm"][i, j] for i in range(3) for j in range(3)}
    at = rel.subs(values)
    holds = bool(at) if at in (sp.true, sp.false) else None
    verdict = table1_verdict(60)
    sides = (sp.nsimplify(rel.lhs.subs(values)), sp.nsimplify(rel.rhs.subs(values)))
    if holds is False and verdict.decision == Decision.PROVED:
        return Finding(Verdict.WRONG,
                       f"not a necessary condition (it only follows from the wrong (44)): Table 1 with k_vmyz = 60 violates it "
                       f"({sp.sstr(rel)} reads {sides[0]} vs {sides[1]}) yet is absolutely stable (Z' positive real, minors "
                       "verified); under (38) the exact real-part condition is K_vm PSD, which requires the opposite-looking "
                       "k_vmyy k_vmzz >= k_vmyz^2",
                       Evidence(Method.COUNTEREXAMPLE, witness={"gains": "Table 1", "k_vmyz": 60},
                                facts={"absolute_stability": verdict.reason, "printed_form": sp.srepr(canonical(rel))}),
                       corrected=r"\mathbf{K}_{vm} \succeq 0:\ \text{all principal minors of } \mathbf{K}_{vm} \geq 0")
    return Finding(Verdict.UNDECIDED, f"Table 1 does not separate (45): {sp.sstr(rel)} reads {sides[0]} vs {sides[1]} there",
                   Evidence(Method.INSTANCES, facts={"printed_form": sp.srepr(canonical(rel))}))


@PAPER.equation("45-minors56", kind="claim", after="45", section="5.1",
                printed="the fifth leading principal minor condition and the sixth leading principal minor condition, i.e., (15c) "
                        "always greater than zero",
                derivation="5th and 6th leading minors of Re Z' under (38)")
def minors56(ctx: AuditContext) -> Finding:
    minors = real_part_leading_minors()
    if minors[4] == 0 and minors[5] == 0:
        return Finding(Verdict.WRONG,
                       "both vanish identically (Re Z' has rank <= 3 under (38)): they are >= 0 but never > 0, so Property 4 "
                       "(positive leading minors) can never certify Re Z' here; PSD must be decided by all principal minors, "
                       "which reduces to K_vm PSD",
                       Evidence(Method.CANONICAL_FORM, facts={"leading_minors": list(minors)}),
                       corrected=r"\det\left(\text{Re}\,\mathcal{Z}'\right)_{5\times 5} = \det\left(\text{Re}\,\mathcal{Z}'\right) = 0")
    return Finding(Verdict.CONFIRMED, "positive", Evidence(Method.CANONICAL_FORM, facts={"leading_minors": list(minors)}))


CORRECTED_46 = (
    r"\mathbf{K}_{pm} = \mathbf{K}_{pm}^T,\ \mathbf{K}_{vm} = \mathbf{K}_{vm}^T,\ \mathbf{K}_{ps} = \mathbf{K}_{ps}^T,\ "
    r"\mathbf{K}_{vs} = \mathbf{K}_{vs}^T,\ " + CORRECTED_38C +
    r",\ \mathbf{K}_{pm} \succeq 0,\ \mathbf{K}_{vm} \succeq 0\ (\text{all principal minors} \geq 0),\ \mathbf{M}_m, \mathbf{M}_s \succeq 0"
)


def _repair_ratio(term: sp.Expr) -> tuple[sp.Expr, str | None]:
    """A ratio k_{vm ab}/k_{vs ??} (or k_{pm ab}/k_{ps ??}) of (46): a denominator whose indices are
    not those of its numerator (the OCR damage k_vsx, k_vsy, k_vsz and the slave's k_psyx at the
    yy, yz places) takes the numerator's indices; returns the term and the repair made."""
    num, den = sp.fraction(sp.together(term))
    if den == 1 or not (isinstance(num, sp.Symbol) and isinstance(den, sp.Symbol)):
        return term, None
    n, d = str(num), str(den)
    kinds = {"k_vm": "k_vs", "k_pm": "k_ps"}
    if len(n) != 6 or n[:4] not in kinds or not d.startswith(kinds[n[:4]]):
        return term, None
    if sorted(d[4:]) == sorted(n[4:]):
        return term, None
    want = gain(kinds[n[:4]][2:], n[4], n[5])
    return num / want, f"{d} -> {want}"


@dataclass(frozen=True)
class _RatioChain:
    """``a_1/b_1 = a_2/b_2 = ...`` read as proportionality: the ratios with b_i != 0 are equal and
    a_i = 0 where b_i = 0 (the gain matrices are proportional, zero entries included)."""

    terms: tuple

    def holds(self, values: dict) -> bool:
        ratios, ok = set(), True
        for t in self.terms:
            num, den = (sp.sympify(x).xreplace(values) for x in sp.fraction(sp.together(t)))
            if den == 0:
                ok = ok and num == 0
            else:
                ratios.add(sp.nsimplify(num / den))
        return ok and len(ratios) <= 1

    def __str__(self) -> str:
        return " = ".join(sp.sstr(t) for t in self.terms)


def _read_46(text: str) -> tuple[list[Any], list[str]]:
    """The printed (46) as a list of conditions (ratio chains as proportionality, damaged ratio
    denominators repaired by the index rule) and the repairs made."""
    conditions, repairs = [], []
    for rel in parse_printed(text, TABLE).relations():
        terms = []
        for t in rel.terms:
            fixed, repair = _repair_ratio(t)
            terms.append(fixed)
            if repair:
                repairs.append(repair)
        if len(terms) > 2 and set(rel.ops) == {"="} and all(sp.fraction(sp.together(t))[1] != 1 for t in terms):
            conditions.append(_RatioChain(tuple(terms)))
            continue
        for a, op, c in zip(terms, rel.ops, terms[1:]):
            conditions.append({"=": sp.Eq, ">=": sp.Ge, ">": sp.Gt, "<=": sp.Le, "<": sp.Lt, "!=": sp.Ne}[op](a, c, evaluate=False))
    return conditions, repairs


def _gain_values(g: dict[str, sp.Matrix]) -> dict[sp.Symbol, sp.Expr]:
    return {gain(kind, AXES[i], AXES[j]): M[i, j] for kind, M in g.items() for i in range(3) for j in range(3)}


def _failing(conditions: list[Any], g: dict[str, sp.Matrix]) -> list[str]:
    values = _gain_values(g)
    out = []
    for c in conditions:
        if isinstance(c, _RatioChain):
            if not c.holds(values):
                out.append(str(c))
            continue
        try:
            at = c.xreplace(values)
        except (TypeError, ZeroDivisionError):
            at = None
        if at is not sp.true:
            out.append(sp.sstr(c))
    return out


@PAPER.equation("46", kind="condition", printed=PRINTED["46"], section="5.1", assumptions=ASSUME_CASE,
                derivation="gains meeting every line of (46) whose Z' is not positive real; Table 1 against (46)")
def eq46(ctx: AuditContext) -> Finding:
    conditions, repairs = _read_46(ctx.equation.printed)
    g = compact_set_counterexample()
    at_counter = _failing(conditions, g)
    at_table = _failing(conditions, table1_gains(60))
    nonnegative = all(v >= 0 for M in g.values() for v in M)
    verdict = absolute_stability(compact_impedance(), ports=(3, 3), search=False)
    reading = "; ".join(str(c) if isinstance(c, _RatioChain) else sp.sstr(c) for c in conditions)
    facts = {"reading": reading, "repairs": repairs, "failing_at_counterexample": at_counter,
             "failing_at_table1": at_table, "youla": verdict.reason, "printed_form": reading}
    if not at_counter and nonnegative and verdict.decision == Decision.DISPROVED:
        return Finding(
            Verdict.WRONG,
            f"not sufficient: read as {reading} (OCR repaired: {', '.join(repairs) or 'none'}), every line holds at K_pm = "
            f"{one_line(g['pm'])}, K_vm = {one_line(g['vm'])}, K_ps = 2K_pm, K_vs = 2K_vm (nonnegative gains), but {verdict.reason}: "
            "(46) dropped det K_pm >= 0 (39d) and both sets of non-leading minors; Table 1's stable gains violate "
            f"{at_table or 'no line'}. Exact condition: K_pm and K_vm PSD",
            Evidence(Method.COUNTEREXAMPLE, witness={k: v for k, v in g.items()}, facts=facts),
            corrected=CORRECTED_46,
        )
    return Finding(Verdict.UNDECIDED, f"read as {reading}, (46) fails at the prepared counterexample ({at_counter}); its "
                   f"sufficiency was not refuted (Table 1 violates {at_table or 'no line'})",
                   Evidence(Method.INSTANCES, facts=facts))


MASSES_PRINTED = ("$M_{mxx} = 1.7$, $M_{mxy} = 0.2$, $M_{myy} = 1.9$, $M_{mxz} = 0.1$, $M_{myz} = 0.3$, $M_{mzz} = 1.3$, "
                  "$M_{sxx} = 1.3$, $M_{sxy} = 0.5$, $M_{syx} = 1.6$, $M_{sxz} = 0.1$, $M_{syz} = 0.3$, and $M_{szx} = 1.5$")


@PAPER.equation("52-masses", kind="claim", after="46", section="5.2", printed=MASSES_PRINTED,
                derivation="as printed M_s lacks its yy and zz entries and is not symmetric; the repaired reading")
def masses(ctx: AuditContext) -> Finding:
    import re

    from hapticproof.audit.runner import quoted_math
    from hapticproof.audit.reader.printed import parse_expression

    printed: dict[str, sp.Expr] = {}
    for quote in quoted_math(ctx.equation.printed):
        name, _, value = quote.partition("=")
        match = re.fullmatch(r"\s*M_\{(\w+)\}\s*", name)
        if match is None or not value.strip():
            return Finding(Verdict.MALFORMED, f"'{quote}' is not a mass entry M_{{..}} = value", Evidence(Method.PARSE))
        printed[match.group(1)] = parse_expression(value, SymbolTable())
    missing = sorted({"syy", "szz"} - set(printed))
    symbol = {"syy": sp.Symbol("m_syy"), "szz": sp.Symbol("m_szz")}

    def entry(which: str, a: str, b: str) -> sp.Expr:
        return printed.get(f"{which}{a}{b}", printed.get(f"{which}{b}{a}", symbol.get(f"{which}{a}{b}", sp.Symbol(f"m_{which}{a}{b}"))))

    # literal reading: each printed entry at its printed place; what is not printed stays symbolic
    literal_s = sp.Matrix(3, 3, lambda i, j: entry("s", AXES[i], AXES[j]))
    Mm = sp.Matrix(3, 3, lambda i, j: entry("m", AXES[min(i, j)], AXES[max(i, j)]))
    gains = [table1_gains(60)[k] for k in ("pm", "vm", "ps", "vs")]
    b_fails = any(c.kind == "B" for c in symmetrization_conditions(case_study_impedance(*gains, Mm, literal_s), ports=(3, 3)))
    # repaired reading: the printed yx and zx entries of M_s are its missing yy and zz entries
    repaired = dict(printed)
    if missing == ["syy", "szz"] and "syx" in printed and "szx" in printed:
        repaired["syy"], repaired["szz"] = repaired.pop("syx"), repaired.pop("szx")
    Ms = sp.Matrix(3, 3, lambda i, j: repaired.get(f"s{AXES[min(i, j)]}{AXES[max(i, j)]}", sp.Symbol("missing")))
    pd = {name: all(M[:k, :k].det() > 0 for k in (1, 2, 3)) if not M.free_symbols else False for name, M in (("M_m", Mm), ("M_s", Ms))}
    facts = {"printed": {k: str(v) for k, v in printed.items()}, "B_fails_literally": b_fails, "pd": pd,
             "printed_form": sorted((k, str(v)) for k, v in printed.items())}
    if missing and b_fails and all(pd.values()):
        return Finding(Verdict.TYPO,
                       f"{', '.join('M_' + m for m in missing)} are never given while M_syx = {printed.get('syx')} and M_szx = "
                       f"{printed.get('szx')} are: read literally M_s = {one_line(literal_s)} is not symmetric, which violates "
                       f"condition B, and lacks those entries; read as M_syy = {repaired.get('syy')}, M_szz = {repaired.get('szz')} "
                       f"it is {one_line(Ms)}, symmetric positive definite (and M_m = {one_line(Mm)} is positive definite)",
                       Evidence(Method.STRUCTURAL, witness={"missing": missing}, facts=facts),
                       corrected=rf"M_{{syy}} = {float(repaired['syy']):g},\quad M_{{szz}} = {float(repaired['szz']):g}")
    if not all(pd.values()):
        return Finding(Verdict.WRONG, f"the printed masses do not give positive definite inertia matrices: M_m = {one_line(Mm)}, "
                       f"M_s (repaired) = {one_line(Ms)}", Evidence(Method.COUNTEREXAMPLE, facts=facts))
    return Finding(Verdict.CONFIRMED, f"masses consistent: M_m = {one_line(Mm)}, M_s = {one_line(Ms)}", Evidence(Method.STRUCTURAL, facts=facts))


@PAPER.equation("47", kind="expression", printed=PRINTED["47"], section="5.2",
                derivation="Definition 3 for the printed termination (the text calls it passive)")
def eq47(ctx: AuditContext) -> Finding:
    T = rhs_matrix(ctx)
    bad = not_in_s(T, "T_1 of (47)")
    if bad is not None:
        return bad
    result = positive_real(T)
    high = T.applyfunc(lambda e: sp.limit(e * s, s, sp.oo))          # the 1/s coefficient at high frequency
    symmetric = high == high.T
    facts = {**pr_facts(result), "one_over_s_coefficient": high, "printed_form": sp.srepr(T)}
    if result.decision == Decision.DISPROVED:
        w = result.hermitian.witness or {}
        why = (f"the 1/s coefficient of T_1, {one_line(high)}, is not symmetric, so at high frequency the Hermitian part is "
               "dominated by an indefinite skew term j(.)/w; exactly, " if not symmetric else "")
        at = {s: sp.I * sp.Rational(w["omega"])} if "omega" in w else None
        value = ""
        if at is not None:
            Tw = T.subs(at)
            H = (Tw + Tw.H).applyfunc(sp.nsimplify)
            smallest = min((sp.nsimplify(sp.re(H.extract(list(S), list(S)).det())), [i + 1 for i in S])
                           for k in range(1, H.rows + 1) for S in itertools.combinations(range(H.rows), k))
            value = f" (the minor on rows {smallest[1]} is {sp.sstr(smallest[0])})"
        return Finding(Verdict.WRONG,
                       f"'which are passive' is false: {why}T_1(jw) + T_1(jw)^H has a negative principal minor at "
                       f"w = {w.get('omega', w)}{value} (exact)",
                       Evidence(Method.ROOT_ISOLATION, witness=dict(w), facts=facts))
    return Finding(Verdict.CONFIRMED if result.decision == Decision.PROVED else Verdict.UNDECIDED,
                   f"T_1 of (47) is {pr_text(result)} (1/s coefficient {one_line(high)})", Evidence(Method.ROOT_ISOLATION, facts=facts))


def fig3_plot(traces: dict[int, Any]) -> Plot:
    """The Fig. 3 runs ``E_s(t)`` (every 10th sample) as evidence data for the reports."""
    series = tuple(Series(f"k_vmyz = {k}", tr.times[::10], tr.energy[::10], "line" if k == 60 else "dashed")
                   for k, tr in traces.items())
    return Plot("Fig. 3 regenerated: input energy at the master port, slave terminated by (47)", "t (s)", "E_s(t) (J)",
                series, hline=0.0)


FIG3_PRINTED_46 = ("if the control gains are selected according to (46), e.g., as listed in Table 1, with $K_{vmyz} = 60$")


def _quoted_kvmyz(text: str) -> tuple[sp.Expr | None, str]:
    """The value of k_vmyz a Fig. 3 claim quotes in its mathematics (``$K_{vmyz} = 60$``), read
    as a relation and solved; ``(None, reason)`` when it quotes no such value."""
    from hapticproof.audit.runner import quoted_math

    k = TABLE.lookup("k_{vmyz}")
    table = TABLE.with_symbols({"K_{vmyz}": k})           # the paper writes K_{vmyz} for the gain k_{vmyz}
    for q in quoted_math(text):
        for rel in parse_printed(q, table).relations():
            relation = rel.as_sympy()
            if k not in getattr(relation, "free_symbols", set()):
                continue
            solved = sp.solve(sp.Eq(rel.lhs, rel.rhs), k) if rel.ops == ("=",) else []
            if len(solved) != 1 or not solved[0].is_number:
                return None, f"the quoted {q!r} does not fix k_vmyz"
            return solved[0], ""
    return None, "the claim quotes no value of k_vmyz"


def _table1_kvmyz() -> tuple[sp.Expr, ...]:
    """The values of k_vmyz Table 1 lists (the registered table text: ``60 (6)``)."""
    import re

    match = re.search(r"k_\{vmyz\} (\d+)(?: \((\d+)\))?", PAPER.get("table1").printed)
    return tuple(sp.Integer(v) for v in match.groups() if v) if match else ()


def _fig3_value(ctx: AuditContext, which: int) -> tuple[sp.Expr | None, Finding | None]:
    """The quoted k_vmyz of a Fig. 3 claim, checked against Table 1's listing (its ``which``-th value)."""
    kvmyz, reason = _quoted_kvmyz(ctx.equation.printed)
    if kvmyz is None:
        return None, Finding(Verdict.UNDECIDED, reason, Evidence(Method.PARSE))
    listed = _table1_kvmyz()
    if len(listed) <= which or listed[which] != kvmyz:
        return None, Finding(Verdict.INCONSISTENT,
                             f"the claim quotes k_vmyz = {sp.sstr(kvmyz)}, but the gains of Fig. 3 are Table 1's, which lists "
                             f"k_vmyz = {', '.join(map(str, listed)) or 'nothing'} (caption of Fig. 3: the stable case first)",
                             Evidence(Method.PARSE, witness={"quoted": str(kvmyz), "table1": [str(v) for v in listed]},
                                      facts={"ids": ["fig3", "table1"]}))
    return (int(kvmyz) if kvmyz.is_integer else kvmyz), None


@PAPER.equation("fig3-46", kind="claim", after="47", section="5.2", printed=FIG3_PRINTED_46,
                derivation="every line of (46) at the Table 1 gains", quotes=('46',))
def fig3_46(ctx: AuditContext) -> Finding:
    kvmyz, problem = _fig3_value(ctx, 0)
    if problem is not None:
        return problem
    conditions, repairs = _read_46(PAPER.get("46").printed)
    failing = _failing(conditions, table1_gains(kvmyz))
    lines = [str(c) if isinstance(c, _RatioChain) else sp.sstr(c) for c in conditions]
    holding = [line for line in lines if line not in failing]
    # the lines as read (after the index rule) are what the claim is about
    facts = {"failing": failing, "holding": holding, "k_vmyz": kvmyz, "printed_form": ("lines of (46) as read", tuple(lines))}
    if failing:
        return Finding(Verdict.INCONSISTENT,
                       f"Table 1 with k_vmyz = {kvmyz} violates line(s) {failing} of (46), so it is not 'selected according to "
                       "(46)'; it is nevertheless absolutely stable (see fig3-60): (45)/(46) are wrong, not the gains "
                       f"(the other {len(holding)} line(s) hold: {'; '.join(holding)})",
                       Evidence(Method.COUNTEREXAMPLE, witness={"k_vmyz": kvmyz}, facts=facts))
    return Finding(Verdict.CONFIRMED, f"Table 1 with k_vmyz = {kvmyz} satisfies every line of (46)",
                   Evidence(Method.INSTANCES, facts=facts))


@PAPER.equation("fig3-60", kind="claim", after="47", section="5.2",
                printed="with $K_{vmyz} = 60$, then the input energy at port 1 is non-negative at all times, indicating the "
                        "absolute stability of the bilateral teleoperator",
                derivation="Youla verdict for Table 1; positive realness of the master-port impedance with (47); simulation")
def fig3_60(ctx: AuditContext) -> Finding:
    kvmyz, problem = _fig3_value(ctx, 0)
    if problem is not None:
        return problem
    verdict = table1_verdict(kvmyz)
    zin = positive_real(master_input_impedance(kvmyz))
    trace = fig3_energy(kvmyz)
    if verdict.decision == Decision.PROVED and zin.decision == Decision.PROVED and trace.minimum >= -1e-9:
        return Finding(Verdict.CONFIRMED,
                       "absolutely stable (Z' positive real, principal and block-compatible minors verified); with the slave "
                       "terminated by (47) -- which is not passive -- the master-port impedance is still positive real, so "
                       "E_s(t) >= 0 for every input from rest; simulated (exact between samples) E_s stays >= 0 "
                       f"(min {trace.minimum:.3g} J over {trace.times[-1]:.0f} s)",
                       Evidence(Method.SIMULATION, facts={"absolute_stability": verdict.reason, "input_impedance": zin.reason,
                                                          "E_min": trace.minimum, "E_final": trace.final,
                                                          "plot": fig3_plot({60: trace})}))
    return Finding(Verdict.WRONG, f"the k_vmyz = {sp.sstr(kvmyz)} case is not shown stable: absolute stability "
                   f"{verdict.decision.value}, master-port impedance {zin.decision.value} positive real, simulated E_s min "
                   f"{trace.minimum:.3g} J", verdict.evidence)


@PAPER.equation("fig3-6", kind="claim", after="47", section="5.2",
                printed="when we change K_{vmyz} to 6, which violate (46), the input energy $E_s(t)$ will become negative at least "
                        "for a period of time, indicating potential instability of the bilateral teleoperator",
                derivation="destabilizing terminations; non-positive-real master-port impedance; simulation")
def fig3_6(ctx: AuditContext) -> Finding:
    cert = searched_terminations("k6")
    zin = positive_real(master_input_impedance(6))
    trace = fig3_energy(6)
    negative = trace.first_negative(1e-9)
    same_forces_60 = fig3_energy(60).minimum
    if cert is not None and zin.decision == Decision.DISPROVED and negative is not None and same_forces_60 >= -1e-9:
        w = zin.hermitian.witness
        return Finding(Verdict.CONFIRMED,
                       "potentially unstable: passive 3-DOF RLC terminations put zeros of det(Z + T) at "
                       f"s ~ {cert.roots[0]:.4g} (certified); with (47) at the slave the master-port impedance is not positive real "
                       f"(w = {w.get('omega', w)}), and three sine forces at w = 4 rad/s along its power-delivering direction make "
                       f"E_s negative from t ~ {negative:.3g} s (min {trace.minimum:.3g} J); the same forces give E_s >= 0 for "
                       f"k_vmyz = 60 (min {same_forces_60:.3g} J). The paper does not state its sine inputs; the sign depends on them",
                       Evidence(Method.SIMULATION, facts={"certificate": certificate_facts(cert), "input_impedance": zin.reason,
                                                          "first_negative_time": negative, "E_min": trace.minimum,
                                                          "plot": fig3_plot({6: trace, 60: fig3_energy(60)})}))
    return Finding(Verdict.UNDECIDED, "potential instability not established", Evidence(Method.INSTANCES))
