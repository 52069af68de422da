r"""Cross-paper consistency: every "is identical to" / "coincides with" statement across the
registered papers and the classics, and every claimed reduction (``m = 1``, ``z_a = 0``,
``alpha = 1``), checked by computation. Each entry parses the printed strings from the
registries (nothing is re-typed) and reports ``confirmed`` or ``inconsistent`` with both ids.
"""

from __future__ import annotations

from typing import Any

import sympy as sp

from hapticproof.audit.runner import AuditContext, Paper
from hapticproof.audit.compare import NotABound, as_bound, as_lower_bound, compare_bounds
from hapticproof.exact.canonical import is_identically_zero
from hapticproof.core.evidence import Evidence, Finding, Method, Verdict
from hapticproof.audit.reader.printed import parse_printed
from hapticproof.audit.registry import get_paper
from hapticproof.systems.singleuser import SYMBOLS

K, B, b, T, t_d, z_a = (SYMBOLS[name] for name in ("K", "B", "b", "T", "t_d", "z_a"))

PAPER = Paper(
    "cross-paper",
    title="Cross-paper consistency of the sampled-data haptic conditions",
    source="hve, teleoperator, classics (registered printed strings)",
    authors="hapticproof",
    aliases=("cross", "consistency"),
)


def _printed(paper: str, eq: str) -> tuple[Any, Any]:
    """The parsed printed statement of ``paper``'s equation ``eq`` and the paper."""
    registered = get_paper(paper)
    return parse_printed(registered.get(eq).printed, registered.symbols), registered


def _relation(paper: str, eq: str) -> sp.Basic:
    statement, _ = _printed(paper, eq)
    (rel,) = statement.relations()
    return rel.as_sympy()


def _teleoperator_intro(which: str) -> sp.Basic:
    """The condition quoted by the teleoperator paper's introduction (parsed from its claim)."""
    from hapticproof.derivations.teleoperator.claims import intro_condition

    return intro_condition(which)


def _reading(rel: sp.Basic, var: sp.Symbol = b) -> str:
    try:
        return str(as_bound(rel, var))
    except NotABound as err:
        return f"{sp.sstr(rel)} ({err.reason})"


def _as_ge(rel: sp.Basic, var: sp.Symbol = b) -> sp.Basic:
    """A printed condition as the non-strict reference of :func:`compare_bounds` (a lower bound
    on ``var``); :class:`NotABound` when it is not one."""
    return sp.Ge(var, as_lower_bound(rel, var).bound, evaluate=False)


def _compare(a: sp.Basic, b_rel: sp.Basic, ids: list[str], what: str, var: sp.Symbol = b, note: str = "") -> Finding:
    """``confirmed`` when the two conditions are equivalent, else ``inconsistent`` with a witness."""
    facts = {"ids": ids, "first": a, "second": b_rel, "readings": [_reading(a, var), _reading(b_rel, var)]}
    try:
        reference = _as_ge(b_rel, var)
    except NotABound as err:
        return Finding(Verdict.INCONSISTENT, f"{ids[0]} reads {_reading(a, var)} but {ids[1]} is not a lower bound on {var} "
                       f"({err.reason}){note}", Evidence(Method.CANONICAL_FORM, facts=facts))
    cmp = compare_bounds(a, reference, var, what=what)
    facts["comparison"] = cmp.verdict.value
    if cmp.verdict == Verdict.CONFIRMED:
        return Finding(Verdict.CONFIRMED, f"{ids[0]} and {ids[1]} are the same condition, {_reading(b_rel, var)}{note}",
                       Evidence(Method.CANONICAL_FORM, facts=facts))
    try:
        first, second = as_bound(a, var).bound, as_bound(reference, var).bound
        how = (f"as bounds on {var}: {_reading(a, var)} vs {_reading(reference, var)} (difference {sp.sstr(sp.simplify(first - second))}; "
               "witness where one holds and the other fails)")
    except NotABound as err:
        how = f"{ids[0]} is not a lower bound on {var} ({err.reason}); {cmp.detail}"
    return Finding(Verdict.INCONSISTENT, f"{ids[0]} and {ids[1]} differ, {how}{note}",
                   Evidence(cmp.evidence.method, witness=cmp.evidence.witness, facts=facts))


# ---------------------------------------------------------------------------------------------
# teleoperator paper vs HVE paper and the classics
# ---------------------------------------------------------------------------------------------


@PAPER.equation("tele35-colgate", kind="claim", after="1",
                printed="teleoperator (35) 'has coincided with the passivity condition ... Colgate and Schenkel' "
                        "(HVE (3), classics colgate-wall)",
                derivation="(35) and HVE (3) as printed, compared as bounds on b", quotes=('teleoperator:35', 'hve:3'))
def tele35(ctx: AuditContext) -> Finding:
    finding = _compare(_relation("teleoperator", "35"), _relation("hve", "3"), ["teleoperator:35", "hve:3"],
                       "teleoperator (35) against HVE (3)")
    if finding.verdict == Verdict.INCONSISTENT:
        from hapticproof.analysis import classics

        doubled = classics.colgate_wall(K=2 * K, B=2 * B)
        try:
            same = is_identically_zero(as_bound(_relation("teleoperator", "35"), b).bound - as_bound(doubled, b).bound.subs(
                sp.Abs(2 * B), 2 * B))
        except NotABound:
            same = False
        if same:
            return Finding(finding.verdict, finding.detail + f"; (35) is Colgate's condition for doubled gains ({sp.sstr(doubled)})",
                           finding.evidence)
    return finding


@PAPER.equation("tele-routh-hve4", kind="claim", after="2",
                printed="teleoperator introduction 'b > KT/2 - B' (Routh-Hurwitz, Gil et al.) vs HVE (4) 'b+B > KT/2'",
                derivation="both quotes as bounds on b", quotes=('teleoperator:intro-routh', 'hve:4'))
def tele_routh(ctx: AuditContext) -> Finding:
    return _compare(_teleoperator_intro("routh"), _relation("hve", "4"), ["teleoperator:intro-routh", "hve:4"],
                    "the two quotes of Gil et al. 2004")


@PAPER.equation("tele-colgate-hve3", kind="claim", after="3",
                printed="teleoperator introduction 'b > KT/2 + B' (Colgate and Schenkel) vs HVE (3) 'b > KT/2 + B'",
                derivation="both quotes as bounds on b", quotes=('teleoperator:intro-colgate', 'hve:3'))
def tele_colgate(ctx: AuditContext) -> Finding:
    from hapticproof.audit.runner import quoted_math
    from hapticproof.audit.reader.printed import parse_printed
    from hapticproof.derivations.teleoperator import paper as tele

    # both quote Colgate and Schenkel's condition for the wall K + sB: the quoted wall must be it
    quotes = quoted_math(tele.PAPER.get("intro-colgate").printed)
    walls = parse_printed(quotes[0], tele.TABLE).expressions() if len(quotes) > 1 else ()
    wall = walls[0] if len(walls) == 1 else None
    wall = getattr(wall, "as_sympy", lambda: wall)()
    names = {x.name: x for x in getattr(wall, "free_symbols", ())}
    if wall is None or {"K", "B", "s"} - set(names) or not is_identically_zero(wall - (names["K"] + names["s"] * names["B"])):
        return Finding(Verdict.INCONSISTENT, f"the teleoperator's introduction quotes the condition for the wall "
                       f"{sp.sstr(wall) if wall is not None else quotes[:1]}, while HVE (3) is Colgate and Schenkel's "
                       "condition for the wall K + sB", Evidence(Method.CANONICAL_FORM, facts={"ids": ["teleoperator:intro-colgate", "hve:3"],
                                                                                           "printed_form": sp.srepr(wall)}))
    return _compare(_teleoperator_intro("colgate"), _relation("hve", "3"), ["teleoperator:intro-colgate", "hve:3"],
                    "the two quotes of Colgate and Schenkel")


@PAPER.equation("tele32-alpha1-29", kind="claim", after="4",
                printed="teleoperator (32) at alpha = 1 reduces to (29)",
                derivation="both displays, line by line, at alpha = 1", quotes=('teleoperator:32', 'teleoperator:29'))
def tele32(ctx: AuditContext) -> Finding:
    s32, tele = _printed("teleoperator", "32")
    s29, _ = _printed("teleoperator", "29")
    alpha = tele.symbols.lookup(r"\alpha")
    same = [is_identically_zero(sp.expand(r32.rhs.subs(alpha, 1) - r29.rhs)) and r32.lhs == r29.lhs
            and type(r32.as_sympy()) is type(r29.as_sympy())                 # the same relation (> vs <)
            for r32, r29 in zip(s32.relations(), s29.relations())]
    ids = ["teleoperator:32", "teleoperator:29"]
    if all(same) and len(same) == 2:
        return Finding(Verdict.CONFIRMED, "(32) at alpha = 1 is (29), line by line ((T/2)(alpha + 1) = T)",
                       Evidence(Method.CANONICAL_FORM, facts={"ids": ids}))
    return Finding(Verdict.INCONSISTENT, "(32) at alpha = 1 is not (29)", Evidence(Method.CANONICAL_FORM, facts={"ids": ids, "lines": same}))


# ---------------------------------------------------------------------------------------------
# HVE quotes vs the classics (published statements)
# ---------------------------------------------------------------------------------------------


@PAPER.equation("hve3-classics", kind="claim", after="5",
                printed="HVE (3) quotes Colgate and Schenkel's virtual-wall condition b > KT/2 + |B|",
                derivation="HVE (3) vs classics colgate-wall (B >= 0)", quotes=('hve:3', 'classics:colgate-wall'))
def hve3_classics(ctx: AuditContext) -> Finding:
    published = _relation("classics", "colgate-wall").subs(sp.Symbol("B", real=True), B)
    return _compare(_relation("hve", "3"), published, ["hve:3", "classics:colgate-wall"], "HVE (3)",
                    note=" for the paper's B >= 0 (|B| = B)")


@PAPER.equation("hve4-classics", kind="claim", after="6",
                printed="HVE (4) quotes Gil et al. 2004's condition b > KT/2 - B",
                derivation="HVE (4) vs classics gil-2004", quotes=('hve:4', 'classics:gil-2004'))
def hve4_classics(ctx: AuditContext) -> Finding:
    return _compare(_relation("hve", "4"), _relation("classics", "gil-2004"), ["hve:4", "classics:gil-2004"], "HVE (4)")


@PAPER.equation("hve5-classics", kind="claim", after="7",
                printed="HVE (5) quotes Gil et al. 2009's condition K < (b + B)/(T/2 + t_d)",
                derivation="HVE (5) vs classics gil-2009 (derived leading order of the exact delayed boundary)", quotes=('hve:5', 'classics:gil-2009'))
def hve5_classics(ctx: AuditContext) -> Finding:
    quote, published = _relation("hve", "5"), _relation("classics", "gil-2009")
    finding = _compare(quote, published, ["hve:5", "classics:gil-2009"], "HVE (5)")
    if finding.verdict == Verdict.INCONSISTENT:
        try:
            slip = as_bound(published, b).bound.subs(T, 2 * T)       # T where Gil et al. have T/2
            if is_identically_zero(as_bound(quote, b).bound - slip):
                return Finding(finding.verdict, finding.detail + "; (5) prints T for T/2", finding.evidence)
        except NotABound:
            pass
    return finding


def _vs_quote5(eq: str, reduce: dict, label: str) -> Finding:
    mine = _relation("hve", eq).subs(reduce)
    finding = _compare(mine, _relation("hve", "5"), [f"hve:{eq}", "hve:5"], label)
    derived = _compare(mine, _relation("classics", "gil-2009"), [f"hve:{eq}", "classics:gil-2009"], label)
    if finding.verdict == Verdict.INCONSISTENT:
        blame = ("it equals the published/derived condition (confirmed against classics:gil-2009), so the quote (5) is what is off"
                 if derived.verdict == Verdict.CONFIRMED else
                 f"it is not the published/derived condition either ({derived.verdict.value} against classics:gil-2009)")
        return Finding(Verdict.INCONSISTENT, finding.detail + "; " + blame,
                       Evidence(finding.evidence.method, witness=finding.evidence.witness,
                                facts={**finding.evidence.facts, "versus_gil_2009": derived.verdict.value}))
    return finding


@PAPER.equation("hve25-5", kind="claim", after="8",
                printed="HVE (25) 'is identical to the condition reported in [7]', quoted as (5)",
                derivation="HVE (25) vs HVE (5), and vs classics gil-2009", quotes=('hve:25', 'hve:5', 'classics:gil-2009'))
def hve25(ctx: AuditContext) -> Finding:
    return _vs_quote5("25", {}, "HVE (25)")


@PAPER.equation("hve27-5", kind="claim", after="9",
                printed="HVE (27) 'extends the condition in [7] by allowing the operator to be active': (27) at z_a = 0 vs (5)",
                derivation="HVE (27) at z_a = 0 vs HVE (5), and vs classics gil-2009", quotes=('hve:5', 'classics:gil-2009'))
def hve27(ctx: AuditContext) -> Finding:
    return _vs_quote5("27", {z_a: 0}, "HVE (27) at z_a = 0")


@PAPER.equation("hve36-5", kind="claim", after="10",
                printed="HVE (36) for the virtual wall and small B 'reduces to (27), where if z_a = 0 the condition will be "
                        "identical to that reported in [7]'",
                derivation="the reduction (36) -> (27) is audited in hve 36-reduces; here (27) at z_a = 0 vs (5)", quotes=('hve:5', 'classics:gil-2009'))
def hve36(ctx: AuditContext) -> Finding:
    finding = _vs_quote5("27", {z_a: 0}, "HVE (36) via (27) at z_a = 0")
    return Finding(finding.verdict, finding.detail.replace("hve:27", "hve:36 (via 27)"), finding.evidence)


@PAPER.equation("hve26-za0-20", kind="claim", after="11",
                printed="HVE (26) is (20) 'after replacing b by b - z_a': (26) at z_a = 0 vs (20)",
                derivation="HVE (26) at z_a = 0 vs HVE (20)", quotes=('hve:20',))
def hve26(ctx: AuditContext) -> Finding:
    return _compare(_relation("hve", "26").subs(z_a, 0), _relation("hve", "20"), ["hve:26", "hve:20"], "HVE (26) at z_a = 0")


@PAPER.equation("hve27-za0-25", kind="claim", after="12",
                printed="HVE (27) is (25) 'after replacing b by b - z_a': (27) at z_a = 0 vs (25)",
                derivation="HVE (27) at z_a = 0 vs HVE (25)", quotes=('hve:25',))
def hve27_25(ctx: AuditContext) -> Finding:
    return _compare(_relation("hve", "27").subs(z_a, 0), _relation("hve", "25"), ["hve:27", "hve:25"], "HVE (27) at z_a = 0")


