r"""Generic claim checkers: the verdict of a printed display from what a paper file says it claims.

Each checker reads the printed display (verbatim, with the file's symbols and the scene's
``H``/``C``), derives its counterpart from the scene with the toolkit and returns a
:class:`~hapticproof.core.evidence.Finding` -- the same objects the hand-written derivation modules
return, so every report format shows both. The conventions are those of the bundled audit
(:mod:`hapticproof.audit.compare`): a proof for ``confirmed`` and ``conservative``, an exact
counterexample re-checked by an exact decision for ``wrong``, ``undecided`` with the instances
when only sampling agrees.

``inverse-transfer``
    Every member of the display that is an expression of ``z`` (or such an expression times one
    signal, ``bV_h(z) + ...``) is compared with ``G^{-1}(z)`` of the scene: ``confirmed`` when
    the difference cancels, else ``wrong`` with an exact point where they differ.
``hermitian-part``
    An expression is compared with ``Re G^{-1}(e^{j\omega T})`` as a rational function of
    ``c = cos(omega T)`` (or, with a symbolic delay, in the canonical theta-form, for every
    integer ``n``); a condition (``b > KT/2 - B\cos(\omega T)``) with ``Re G^{-1} >= 0`` at each
    frequency, as a bound on the device damping. m users: the matrix ``G + G^H`` (or its half)
    or one of its principal minors (a condition: that minor ``>= 0``). Teleoperator: the
    condition that each robot's damping exceeds its bound at every frequency (eq. 32 of the
    teleoperator paper).
``residue``
    The residue (matrix) of ``G^{-1}`` at ``z = 1``.
``passivity-condition``, ``sufficient-condition``, ``necessary-condition``
    The exact condition for ``G^{-1}`` positive real: the worst case over frequency when it has
    a closed form; for a virtual-wall-like path ``R/(z-1) + F_0`` and any delay ``n`` (also
    symbolic) the Dirichlet-kernel bounds ``a >= R(n + 1/2) - F_0(1)`` (necessary) and ``a >=
    R(n + 1/2) + max|F_0|`` (sufficient), exact when ``F_0 = 0``; otherwise exact decisions on
    numeric instances (exact passive ranges, :func:`hapticproof.analysis.passiverange.passive_range`).
    Compared as bounds on one parameter (:func:`hapticproof.audit.compare.compare_bounds`: equal is
    ``confirmed``, a provably larger bound ``conservative``, a smaller one ``wrong`` with a
    witness re-checked by the exact decision). ``assumption = "B = 0"``: a condition that fails
    in general but holds under the assumption is ``needs-assumption``.
``stability-condition``
    ``order = "leading"``: the leading order of the exact ZOH boundary of the wall,
    ``b (+ b_h) + B > K(T/2 + t_d)`` (:func:`hapticproof.analysis.classics.leading_order_boundary`).
    ``order = "exact"``: certified spectral radii of the exact sampled-data loop (the scene
    names the device mass ``m``) near the printed boundary: an unstable loop where the display
    holds is ``wrong``; agreement on instances is ``undecided`` (never a proof).
``same-as``
    The display and the equation ``other`` (this file's or a bundled paper's ``paper:id``),
    with ``under`` substituted in both: the same expression or condition is ``confirmed``,
    otherwise ``inconsistent`` (both ids) with a point where they differ.

A display that is not confirmed gets a search for a nearby correct reading: the edits of
:mod:`hapticproof.audit.edits` (a sign, a factor 2, a dropped term, swapped indices, a reversed
relation, another symbol); when one edit makes it exactly right the verdict is ``typo`` and the
corrected LaTeX is that edited display.

>>> from hapticproof.audit.paperfile import loads, TEMPLATE
>>> from hapticproof.audit.runner import audit_paper
>>> report = audit_paper(loads(TEMPLATE).paper)
>>> [(r.id, r.verdict.value) for r in report.results]
[('1', 'confirmed'), ('2', 'confirmed'), ('3', 'confirmed')]
"""

from __future__ import annotations

import dataclasses
import functools
from collections.abc import Callable, Mapping
from typing import Any

import sympy as sp

from hapticproof.core.errors import HapticproofError, LatexParseError
from hapticproof.core.evidence import Evidence, Finding, Method, Verdict
from hapticproof.core.naming import marked
from hapticproof.audit.claimbase import ClaimError, PROVED_VERDICTS, State

__all__ = ["check", "describe", "checkers"]


Checker = Callable[[State], Finding]


@functools.lru_cache(maxsize=1)
def checkers() -> dict[str, Checker]:
    """The checker of each claim kind (:mod:`hapticproof.audit.claimcheckers`, :mod:`hapticproof.audit.claimconditions`)."""
    from hapticproof.audit import claimcheckers as ce
    from hapticproof.audit import claimconditions as cc
    from hapticproof.audit.definitions.checks import check as by_definitions

    return {
        "inverse-transfer": ce.inverse_transfer,
        "hermitian-part": ce.hermitian_part,
        "residue": ce.residue,
        "passivity-condition": functools.partial(cc.condition, claim="passivity"),
        "sufficient-condition": functools.partial(cc.condition, claim="sufficient"),
        "necessary-condition": functools.partial(cc.condition, claim="necessary"),
        "stability-condition": cc.stability,
        "definition": by_definitions,
        "identity": by_definitions,
        "condition": by_definitions,
        "same-as": cc.same_as,
    }


def check(ctx: Any, *, spec: Any, source: Any) -> Finding:
    """The audit check of one paper-file claim (registered by :mod:`hapticproof.audit.paperfile`)."""
    state = State(spec, source, ctx.equation.printed, equation=ctx.equation)
    try:
        state = _in_region(state, _file_region(state), "region")
        finding = _with_assumption(state)
    except ClaimError as err:
        return Finding(Verdict.UNDECIDED, f"the claim cannot be checked: {err}", Evidence(Method.STRUCTURAL))
    except LatexParseError:
        raise                                   # the audit reports the printed display as malformed
    except (HapticproofError, ArithmeticError, TypeError, ValueError, NotImplementedError, sp.PolynomialError) as err:
        # a display the generic checker cannot handle is undecided with the reason, never a traceback
        return Finding(Verdict.UNDECIDED, f"the check could not decide this display: {type(err).__name__}: {err}",
                       Evidence(Method.STRUCTURAL, facts={"error": f"{type(err).__name__}: {err}"}))
    if _should_repair(state, finding):
        finding = _repair(state, finding)
    return _judged(state, finding)


def _judged(state: State, finding: Finding) -> Finding:
    """The finding with the judge's data of a condition claim (:func:`hapticproof.audit.judged.condition_judge`)."""
    if state.spec.claim not in ("passivity-condition", "sufficient-condition", "necessary-condition"):
        return finding
    if "judge" in finding.evidence.facts:
        return finding
    from hapticproof.audit.judged import condition_judge

    obj = condition_judge(state, finding)
    if obj is None:
        return finding
    return dataclasses.replace(finding, evidence=dataclasses.replace(finding.evidence,
                                                                     facts={**finding.evidence.facts, "judge": obj}))


def _run(state: State) -> Finding:
    finding = checkers()[state.spec.claim](state)
    if state.repairing:            # a trial's finding is told in the paper's names only if it is chosen
        return finding
    return _in_paper_names(finding, state.chart)


def _file_region(state: State) -> Any:
    from hapticproof.audit.regions import Region

    return getattr(state.source, "region", None) or Region()


def _stated(state: State) -> Any:
    from hapticproof.audit.regions import Region

    spec = state.origin[0] if state.origin else state.spec
    return spec.assumption or Region()


def _with_assumption(state: State) -> Finding:
    """Check the claim; with a stated ``assumption`` also under it (``needs-assumption`` when
    it holds only there)."""
    stated = _stated(state)
    text = stated.text()
    if stated and state.repairing:
        # a repair of a claim made under an assumption is right under that assumption
        assumed = _assumed(state)
        inner = _in_paper_names(_run(assumed), assumed.chart)
        return Finding(inner.verdict, f"under the stated assumption {text}: {inner.detail}", inner.evidence,
                       derived=inner.derived)
    inner = None
    finding = _run(state)
    if not stated or finding.verdict in PROVED_VERDICTS:
        if stated and finding.verdict in PROVED_VERDICTS:
            return Finding(finding.verdict, finding.detail + " (it holds without the stated assumption)",
                           finding.evidence, derived=finding.derived, corrected=finding.corrected)
        return finding
    if inner is None:
        inner = _run(_assumed(state))
    if inner.verdict in PROVED_VERDICTS and finding.verdict == Verdict.WRONG:
        return Finding(
            Verdict.NEEDS_ASSUMPTION,
            f"holds under the stated assumption {text} ({inner.verdict.value}: {inner.detail}); without it: {finding.detail}",
            Evidence(finding.evidence.method, witness=finding.evidence.witness,
                     facts={**dict(finding.evidence.facts), "under_assumption": inner.verdict.value,
                            "assumption": text, "under_assumption_evidence": inner.evidence.to_json()}),
            derived=inner.derived,
            corrected=_with_text(state.printed, r"\quad (" + stated.latex() + ")"),
        )
    if inner.verdict == Verdict.WRONG:
        return Finding(inner.verdict, f"{inner.detail} (even under the stated assumption {text})", inner.evidence,
                       derived=inner.derived, corrected=inner.corrected)
    return finding


def _assumed(state: State) -> State:
    """The state with the stated assumption (and the file's region) in the scene and the display."""
    return _in_region(state, _file_region(state) & _stated(state), "assumed")


def _in_region(state: State, region: Any, tag: str) -> State:
    """The state of the claim with its scene restricted to ``region``: equalities substituted,
    inequalities as a change of variables onto sign-assumed parameters
    (:meth:`hapticproof.audit.regions.Region.parametrize`), in the scene and so in the display."""
    spec, source = state.origin or (state.spec, state.source)
    if not region or spec.scene is None:
        return state if state.origin is None else State(spec, source, state.printed, equation=state.equation,
                                                        repairing=state.repairing, cache=state.cache)
    scene = source.scenes[spec.scene]
    used = scene.names() | set(dict(scene.params))
    region = region.restricted_to(used)
    if not region.inequalities() and not region.equalities():
        return State(spec, source, state.printed, equation=state.equation, repairing=state.repairing,
                     cache=state.cache, origin=(spec, source))
    taken = used | {getattr(sym, "name", "") for sym in _table_names(source)}
    chart = region.parametrize(taken)
    name = f"{spec.scene}#{tag}"
    scenes = dict(source.scenes)
    scenes[name] = scene.with_params(chart.params)
    view = _SourceView(source, scenes)
    new_spec = dataclasses.replace(spec, scene=name, assumption=None)
    return State(new_spec, view, state.printed, equation=state.equation, repairing=state.repairing, cache=state.cache,
                 chart=chart, origin=(spec, source))


def _table_names(source: Any) -> list[Any]:
    symbols = getattr(getattr(source, "symbols", None), "symbols", {}) or {}
    return [sym for value in symbols.values() for sym in getattr(value, "free_symbols", ())]


def _in_paper_names(finding: Finding, chart: Any) -> Finding:
    """A finding of a restricted scene told in the paper's names: the witness mapped back
    through the change of variables, the derived condition and the exact facts too."""
    if chart is None or not chart.inverse:
        return finding
    evidence = finding.evidence
    witness = chart.witness(evidence.witness) if evidence.witness else evidence.witness
    facts = {k: (chart.back(v) if isinstance(v, sp.Basic) else v) for k, v in dict(evidence.facts).items()}
    facts["region"] = "; ".join(chart.notes)
    derived = chart.back(finding.derived)
    detail = finding.detail
    if any(name in detail for name in chart.fresh):
        told = f"in the paper's names {marked(derived)}; " if isinstance(derived, sp.Basic) else ""
        detail += f" ({told}{'; '.join(chart.notes)})"
    return Finding(finding.verdict, detail, dataclasses.replace(evidence, witness=witness, facts=facts),
                   derived=derived, corrected=finding.corrected)


class _SourceView:
    """A paper file seen with other scenes (an assumption substituted into one)."""

    def __init__(self, source: Any, scenes: Mapping[str, Any]):
        self._source = source
        self.scenes = scenes

    def __getattr__(self, name: str) -> Any:
        return getattr(self._source, name)

    def table_for(self, scene: str | None) -> Any:
        return self._source.bound_table(self.scenes.get(scene) if scene else None, ("view", scene))


def _with_text(printed: str, suffix: str) -> str:
    return printed.rstrip() + suffix


def _should_repair(state: State, finding: Finding) -> bool:
    if state.repairing or not state.repairable or state.spec.claim == "same-as":
        return False
    if finding.verdict == Verdict.WRONG:
        return True
    if (finding.verdict == Verdict.UNDECIDED and finding.evidence.witness and state.repairable
            and state.spec.claim in ("passivity-condition", "stability-condition")):
        return True          # not necessary at the witness: a nearby display may be exactly right
    return finding.verdict == Verdict.CONSERVATIVE and state.spec.claim in ("passivity-condition", "stability-condition",
                                                                            "hermitian-part")


def _repaired(state: State, finding: Finding) -> bool:
    """A trial edit repairs the display when it is right: confirmed, a correct sufficient
    condition, or right under the claim's stated assumption."""
    if finding.verdict == Verdict.CONFIRMED:
        return True
    if finding.verdict == Verdict.NEEDS_ASSUMPTION:
        return bool(_stated(state))
    return finding.verdict == Verdict.CONSERVATIVE and state.spec.claim == "sufficient-condition"


#: At most this many edits are tried (in printed order).
MAX_EDITS = 80


#: The edits tried first when a display has more than :data:`MAX_EDITS`: the commonest slips.
_LIKELY = ("sign", "half", "index", "relation", "scale", "swap", "modulus", "drop", "symbol")


def _most_likely(mutants: list[Any]) -> list[Any]:
    """At most :data:`MAX_EDITS` edits, the commonest slips first over the whole display (a
    long display's last terms get their sign flips too), tried in printed order."""
    if len(mutants) <= MAX_EDITS:
        return mutants
    order = sorted(range(len(mutants)), key=lambda k: (_LIKELY.index(mutants[k].operator)
                                                       if mutants[k].operator in _LIKELY else len(_LIKELY), k))
    return [mutants[k] for k in sorted(order[:MAX_EDITS])]


def _repair(state: State, finding: Finding) -> Finding:
    """Search the edits of :mod:`hapticproof.audit.edits` for one that makes the display right."""
    try:
        from hapticproof.audit.edits import generate
        from hapticproof.core.limits import LimitError
    except ImportError:  # pragma: no cover - the mutation operators are not available
        return finding
    try:
        mutants = _most_likely(generate(state.equation, state.source.paper, text=state.printed, table=state.table,
                                        slips=True))
    except LimitError:             # a display too long to search its edits: no repair is offered
        return finding
    found = []
    for mutant in mutants:
        trial = State(state.spec, state.source, mutant.printed, equation=state.equation, repairing=True,
                      cache=state.cache, chart=state.chart, origin=state.origin)
        try:
            result = _with_assumption(trial)
        except (LatexParseError, HapticproofError, TypeError, ValueError, ZeroDivisionError, NotImplementedError):
            continue
        if _repaired(state, result):
            found.append((mutant, result))
    facts = dict(finding.evidence.facts)
    facts["edits_tried"] = len(mutants)
    if not found:
        return Finding(finding.verdict, finding.detail + f"; no single edit of the display repairs it ({len(mutants)} tried)",
                       Evidence(finding.evidence.method, witness=finding.evidence.witness,
                                instances=finding.evidence.instances, facts=facts),
                       derived=finding.derived, corrected=finding.corrected)
    mutant, result = found[0]
    if not _stated(state):               # (a trial under an assumption is told in its region's names already)
        result = _in_paper_names(result, state.chart)
    facts["repair"] = {"operator": mutant.operator, "position": mutant.position, "original": mutant.original,
                       "replacement": mutant.replacement, "repairs_found": len(found)}
    others = f" ({len(found) - 1} other edit{'s' if len(found) > 2 else ''} also repair it)" if len(found) > 1 else ""
    return Finding(
        Verdict.TYPO,
        f"one edit repairs it: {_describe_edit(mutant)} gives a display that is {result.verdict.value} ({result.detail}){others}; "
        f"as printed: {finding.detail}",
        Evidence(finding.evidence.method, witness=finding.evidence.witness, instances=finding.evidence.instances, facts=facts),
        derived=result.derived if result.derived is not None else finding.derived,
        corrected=mutant.printed,
    )


_EDITS = {"sign": "a sign", "scale": "a factor 2", "drop": "a term", "swap": "swapped indices",
          "relation": "the relation", "symbol": "another symbol", "index": "another index",
          "half": "a lost half", "modulus": "a modulus"}


def _describe_edit(mutant: Any) -> str:
    """``KT -> KT/2 (a lost half)``: the edit as a reviewer writes it, and what kind of slip it is."""
    return f"{mutant.edit()} ({_EDITS.get(mutant.operator, mutant.operator)})"


def describe(spec: Any, paper: Any) -> str:
    """One line: what the claim is compared with (the report's ``derivation``).

    >>> from hapticproof.audit.paperfile import loads, TEMPLATE
    >>> paper = loads(TEMPLATE)
    >>> describe(paper.claim("3"), paper)
    "exact condition for G^-1 positive real of scene 'wall' (single-user, forward) (necessary and sufficient)"
    """
    scene = paper.scenes.get(spec.scene) if spec.scene else None
    names = paper.naming()
    w, T = names.helper("omega"), (scene.role("period") if scene is not None and scene.system != "network" else names.period)
    where = ""
    if scene is not None:
        where = f" of scene '{spec.scene}' ({scene.system}, {scene.approximation}"
        where += f", delay {scene.delay})" if scene.delay not in (0, None) else ")"
    texts = {
        "inverse-transfer": f"G^-1(z){where}, exact (canonical form)",
        "hermitian-part": f"Re G^-1(e^(j {w} {T})){where}, exact in {names.helper('cos')} = cos({w} {T})",
        "residue": f"residue of G^-1 at z = 1{where}",
        "passivity-condition": f"exact condition for G^-1 positive real{where} (necessary and sufficient)",
        "sufficient-condition": f"exact condition for G^-1 positive real{where}: the display must imply it",
        "necessary-condition": f"exact condition for G^-1 positive real{where}: it must imply the display",
        "stability-condition": (f"exact ZOH sampled-data stability{where}" if spec.order == "exact"
                                else f"leading order of the exact ZOH stability boundary{where}"),
        "same-as": f"equation {spec.other}" + (" with " + ", ".join(f"{k} = {v}" for k, v in spec.under) if spec.under else ""),
        "definition": "a definition of the paper: it binds its names" + (" (derived by the paper)" if spec.derived else ""),
        "identity": "both sides from the paper's definitions, exactly",
        "condition": (f"exact condition for {spec.about or 'the object'} {(spec.property or 'its property').replace('-', ' ')}"
                      f" ({spec.strength or 'strength not stated'})"),
    }
    text = texts[spec.claim]
    region = getattr(paper, "region", None)
    if region and scene is not None and region.restricted_to(scene.names() | set(dict(scene.params))):
        text += "; in the region " + region.restricted_to(scene.names() | set(dict(scene.params))).text()
    if spec.assumption:
        text += "; stated assumption " + spec.assumption.text()
    if spec.stated:
        text += "; stated assumption " + spec.stated
    return text
