r"""Audit printed equations: registry entries, the audit run, and its reports.

A paper module in ``derivations/`` creates one :class:`Paper` and registers each printed
equation **verbatim** with a check function::

    PAPER = Paper("hve", title=..., source=..., symbols=TABLE)

    @PAPER.equation("17", kind="condition", section="3.1.1",
                    printed=r"b > \frac{KT}{2} - B\cos(\omega T)",
                    assumptions="b, K, T > 0; B >= 0",
                    derivation="Re G_1^{-1}(e^{jwT}) >= 0, forward difference")
    def eq17(ctx: AuditContext) -> Finding:
        ...  # derive with the toolkit, compare with ctx.relation(), return a Finding

The check derives its counterpart with the toolkit and compares, returning a
:class:`~hapticproof.core.evidence.Finding` (one verdict with evidence). A printed string the parser
rejects becomes ``malformed`` automatically (with the position), unless the check handles the
parse error itself (for documented OCR readings). Reports render as a text table, Markdown,
the JSON of DESIGN.md, a compilable LaTeX file (:mod:`hapticproof.report.latex`) and a self-contained
HTML page (:mod:`hapticproof.report.html`; also the report's view in a notebook).

>>> paper = Paper("demo", title="Demo", source="none")
>>> @paper.equation("1", kind="claim", printed="1 + 1 = 2")
... def one(ctx):
...     return Finding(Verdict.CONFIRMED, "arithmetic", Evidence("canonical-form"))
>>> report = audit_paper(paper)
>>> [(r.id, r.verdict.value) for r in report.results]
[('1', 'confirmed')]
"""

from __future__ import annotations

import functools
import json
import re
import time
from collections.abc import Callable, Iterable, Mapping
from dataclasses import dataclass, field, replace
from typing import Any

import sympy as sp

from hapticproof.core.naming import witness_keys
from hapticproof.core.notation import symbol_names, to_latex
from hapticproof.core.errors import LatexParseError, UnknownEquationError
from hapticproof.core.evidence import Evidence, Finding, Method, Verdict, to_jsonable

__all__ = [
    "KINDS",
    "Paper",
    "Equation",
    "AuditContext",
    "EquationResult",
    "AuditReport",
    "audit_paper",
    "notation_of",
    "malformed",
    "quoted_math",
    "run_equation",
    "parse_failure",
    "printed_offset",
]

KINDS = ("expression", "condition", "claim")

Check = Callable[["AuditContext"], Finding]


@dataclass(frozen=True)
class Equation:
    """One printed equation or claim, registered verbatim with how to audit it."""

    id: str
    kind: str
    printed: str
    check: Check
    section: str = ""
    assumptions: str = ""
    derivation: str = ""
    parse: bool = True
    after: str = ""
    #: other displays whose content this check is about (``"20"`` or ``"paper:id"``): the
    #: mutation test audits this check against their mutants too (:mod:`hapticproof.audit.mutate`)
    quotes: tuple[str, ...] = ()

    def __post_init__(self) -> None:
        if self.kind not in KINDS:
            raise ValueError(f"kind must be one of {KINDS}, got {self.kind!r}")

    @property
    def position(self) -> tuple[int, str, int]:
        """Place in the paper: the equation number (or the number of the equation a claim
        follows, ``after``), then the letter of an unnumbered display; claims after displays."""
        key = self.after or self.id
        match = re.match(r"(\d+)([a-z]?)", key)
        if not match:
            return (10**6, key, 1)
        return (int(match.group(1)), match.group(2), 1 if (self.after or self.kind == "claim") else 0)


@functools.lru_cache(maxsize=None)
def _deferred_rows(build: Callable[[], Any]) -> tuple:
    return tuple(build())


@dataclass
class Paper:
    """A registered paper: its printed-name table and its equations, in printed order."""

    id: str
    title: str
    source: str
    authors: str = ""
    symbols: Any = None  # hapticproof.audit.reader.names.SymbolTable
    aliases: tuple[str, ...] = ()
    equations: dict[str, Equation] = field(default_factory=dict)
    #: rows (label, condition LaTeX, source) for the export's one-notation table
    conditions: list[tuple[str, str, str]] = field(default_factory=list)
    #: functions returning more such rows: costly derived rows are built only when exported
    deferred_conditions: list[Callable[[], Any]] = field(default_factory=list)
    #: the names the reports of this paper print (:class:`~hapticproof.core.naming.Naming`; by
    #: default chosen from its symbols: a paper file sets the one of its symbols and scenes)
    notation: Any = None

    @property
    def naming(self) -> Any:
        """The paper's naming: its symbols' names, the toolkit's helpers under names that no
        symbol of the paper can be confused with (``c`` stays ``c`` unless the paper has ``c_*``)."""
        if self.notation is not None:
            return self.notation
        from hapticproof.core.naming import Naming

        table = getattr(self.symbols, "symbols", None) or {}
        return Naming.of_symbols(v for v in table.values() if isinstance(v, sp.Symbol))

    def condition_rows(self) -> list[tuple[str, str, str]]:
        """All export rows: ``conditions`` then the deferred rows (each built once per process)."""
        return [*self.conditions, *(row for build in self.deferred_conditions for row in _deferred_rows(build))]

    def equation(
        self,
        id: str,
        *,
        kind: str,
        printed: str,
        section: str = "",
        assumptions: str = "",
        derivation: str = "",
        parse: bool | None = None,
        after: str = "",
        quotes: tuple[str, ...] | list[str] = (),
    ) -> Callable[[Check], Check]:
        """Register a printed equation (decorator). ``parse`` defaults to True for expressions
        and conditions, False for claims (whose printed text is a quoted sentence). ``quotes``
        names the other displays whose content the check compares (``"20"``, ``"hve:3"``)."""

        def register(check: Check) -> Check:
            if id in self.equations:
                raise ValueError(f"equation {id!r} registered twice in {self.id}")
            self.equations[id] = Equation(
                id=id,
                kind=kind,
                printed=printed,
                check=functools.update_wrapper(functools.partial(_in_paper_names, check), check),
                section=section,
                assumptions=assumptions,
                derivation=derivation,
                parse=(kind != "claim") if parse is None else parse,
                after=after,
                quotes=tuple(quotes),
            )
            return check

        return register

    def ordered(self) -> list[Equation]:
        """Equations in paper order (stable for equal positions: registration order)."""
        return sorted(self.equations.values(), key=lambda eq: eq.position)

    def get(self, id: str) -> Equation:
        try:
            return self.equations[id]
        except KeyError:
            known = ", ".join(eq.id for eq in self.ordered())
            raise UnknownEquationError(f"paper {self.id!r} has no equation {id!r} (known: {known})") from None

    @property
    def names(self) -> dict[sp.Symbol, str]:
        """Printed names of the paper's symbols (for LaTeX in the paper's notation)."""
        table = getattr(self.symbols, "symbols", None) or {}
        return symbol_names(table)


class AuditContext:
    """What a check function receives: the equation, the paper and the parsed printed text."""

    def __init__(self, paper: Paper, equation: Equation):
        self.paper = paper
        self.equation = equation
        self._statement: Any = None
        self._error: LatexParseError | None = None
        self._parsed = False

    def parse(self, text: str | None = None) -> Any:
        """Parse ``text`` (default: the printed string) with the paper's symbol table."""
        from hapticproof.audit.reader.printed import parse_printed

        return parse_printed(self.equation.printed if text is None else text, self.paper.symbols)

    @property
    def statement(self) -> Any:
        """The parsed printed text (raises :class:`LatexParseError` if it does not parse)."""
        if not self._parsed:
            self._parsed = True
            try:
                self._statement = self.parse()
            except LatexParseError as err:
                self._error = err
        if self._error is not None:
            raise self._error
        return self._statement

    @property
    def parse_error(self) -> LatexParseError | None:
        try:
            self.statement
        except LatexParseError:
            pass
        return self._error

    def relation(self) -> Any:
        """The printed statement as one SymPy relational (the single relation of the display)."""
        statement = self.statement
        relations = statement.relations()
        if len(relations) != 1:
            what = "no relation (an expression, not a condition)" if not relations else f"{len(relations)} relations"
            raise LatexParseError(f"expected one relation, found {what}", self.equation.printed, statement.span.start)
        return relations[0].as_sympy()

    def names(self) -> dict[sp.Symbol, str]:
        return self.paper.names


def _in_paper_names(check: Check, ctx: AuditContext) -> Finding:
    """The finding of ``check`` in its paper's names: the toolkit's own names a check writes
    (:func:`~hapticproof.core.naming.marker`) as the paper's naming chose them."""
    return ctx.paper.naming.unmarked(check(ctx))


def quoted_math(text: str) -> list[str]:
    r"""The ``$...$`` mathematics quoted in a claim's text, in order.

    >>> quoted_math("the condition $b > KT/2 - B$ of [8] and $K + sB$")
    ['b > KT/2 - B', 'K + sB']
    """
    return [m.group(1) for m in re.finditer(r"\$([^$]+)\$", text)]


def malformed(ctx: AuditContext, what: str, corrected: str | None = None, derived: Any = None) -> Finding:
    """A ``malformed`` finding: the printed text is not a well-formed equation (say what is
    missing); the parse result or error is the evidence."""
    facts: dict[str, Any] = {}
    error = ctx.parse_error if ctx.equation.parse else None
    if error is not None:
        facts = {"parse_error": error.reason, "position": error.position}
    return Finding(Verdict.MALFORMED, what, Evidence(Method.PARSE, facts=facts), derived=derived, corrected=corrected)


@dataclass(frozen=True)
class EquationResult:
    """One row of an audit report (the JSON object of DESIGN.md)."""

    id: str
    kind: str
    printed: str
    derived: str | None
    verdict: Verdict
    detail: str
    corrected: str | None
    evidence: Evidence
    seconds: float
    section: str = ""
    assumptions: str = ""

    def to_json(self) -> dict[str, Any]:
        return {
            "id": self.id,
            "kind": self.kind,
            "printed": self.printed,
            "derived": self.derived,
            "verdict": self.verdict.value,
            "detail": self.detail,
            "corrected": self.corrected,
            "evidence": self.evidence.to_json(),
            "seconds": round(self.seconds, 6),
        }

    def __repr__(self) -> str:  # short and free of timings (notebooks compare it)
        return f"EquationResult({self.id!r}, {self.verdict.value})"


@dataclass(frozen=True)
class AuditReport:
    """The audit of one paper."""

    paper: str
    title: str
    results: tuple[EquationResult, ...]
    #: the toolkit's names this report prints differently from the papers' (``{"gamma": "cos wh"}``:
    #: :func:`notation_of`), defined in every format
    notation: Mapping[str, str] = field(default_factory=dict)
    #: what the paper's naming prints differently (:meth:`~hapticproof.core.naming.Naming.changed`:
    #: the period ``h``, ``cos`` -> ``gamma``): the keys of its witnesses, for ``check``
    names: Mapping[str, str] = field(default_factory=dict)

    def to_json(self) -> dict[str, Any]:
        out = {"paper": self.paper, "title": self.title, "equations": [r.to_json() for r in self.results]}
        if self.notation:
            out["notation"] = dict(self.notation)
        if self.names:
            out["names"] = dict(self.names)
        return out

    def __repr__(self) -> str:  # short and free of timings (notebooks compare it)
        counts = ", ".join(f"{k} {v}" for k, v in sorted(self.counts().items()))
        return f"AuditReport({self.paper!r}, {len(self.results)} equations: {counts})"

    def counts(self) -> dict[str, int]:
        out: dict[str, int] = {}
        for r in self.results:
            out[r.verdict.value] = out.get(r.verdict.value, 0) + 1
        return out


def _derived_latex(value: Any, names: Mapping[sp.Symbol, str], naming: Any = None) -> str | None:
    if value is None:
        return None
    if isinstance(value, str):
        return value
    try:
        return naming.latex(value, names) if naming is not None else to_latex(value, names)
    except Exception:  # noqa: BLE001 - a display problem must not hide the verdict
        return sp.sstr(value)


def printed_offset(err: LatexParseError, printed: str) -> int | None:
    """Where in ``printed`` the parse error is, when the text that failed to parse is the printed
    display itself or a verbatim part of it; ``None`` for any other text (a repair, another
    equation, a string of the check's own).

    >>> from hapticproof.core.errors import LatexParseError
    >>> printed_offset(LatexParseError("unknown name I", "2b - KI", 6), "a = 2b - KI > 0")
    10
    >>> printed_offset(LatexParseError("unknown name I", "2b - KT", 6), "a = 2b - KI > 0") is None
    True
    """
    text = err.text or ""
    if not text.strip():
        return None
    at = printed.find(text)
    return None if at < 0 else at + err.position


def parse_failure(equation: Equation, err: LatexParseError) -> Finding:
    """The finding for a :class:`LatexParseError` that escaped a check: ``malformed`` when the
    printed display (or a verbatim part of it) does not parse; ``undecided`` when the check
    failed to parse some other text (a repaired reading, another equation, its own string) --
    an error of the check, not of the paper."""
    offset = printed_offset(err, equation.printed)
    if offset is not None:
        return Finding(
            Verdict.MALFORMED,
            f"the printed text does not parse: {err.reason} at position {offset}",
            Evidence(Method.PARSE, facts={"parse_error": err.reason, "position": offset}),
        )
    return Finding(
        Verdict.UNDECIDED,
        f"the check could not parse a text of its own (not the printed display): {err.reason} at position "
        f"{err.position} of {err.text[:80]!r}",
        Evidence(Method.PARSE, facts={"internal_parse_error": err.reason, "text": err.text, "position": err.position}),
    )


def run_equation(paper: Paper, equation: Equation) -> EquationResult:
    """Audit one equation; the check's own errors propagate (they are bugs, not findings),
    except parse errors (see :func:`parse_failure`)."""
    ctx = AuditContext(paper, equation)
    start = time.perf_counter()
    try:
        finding = equation.check(ctx)
    except LatexParseError as err:
        finding = parse_failure(equation, err)
    finding = rechecked(_with_printed(finding, equation.printed), witness_keys(paper.naming.changed()))
    seconds = time.perf_counter() - start
    return EquationResult(
        id=equation.id,
        kind=equation.kind,
        printed=equation.printed,
        derived=_derived_latex(finding.derived, paper.names, paper.naming),
        verdict=finding.verdict,
        detail=finding.detail,
        corrected=finding.corrected,
        evidence=finding.evidence,
        seconds=seconds,
        section=equation.section,
        assumptions=equation.assumptions,
    )


def _with_printed(finding: Finding, printed: str) -> Finding:
    """A judge object remembers the display as printed: ``check`` refuses an entry whose shown
    ``printed`` is not the one judged."""
    judge = finding.evidence.facts.get("judge")
    if not isinstance(judge, dict):
        return finding
    facts = {**finding.evidence.facts, "judge": {**judge, "printed": printed}}
    return replace(finding, evidence=replace(finding.evidence, facts=facts))


def rechecked(finding: Finding, keys: Mapping[str, str] | None = None) -> Finding:
    """``finding`` with every certificate in its evidence re-verified by the independent checker
    (:mod:`hapticproof.exact.checker`) and every judge object (the printed display and the
    scene's original ``G^{-1}`` at its points) judged against the definition
    (:mod:`hapticproof.exact.judge`), the verdict and the displayed witness held against them;
    the tally goes to ``evidence.facts["checker"]``. A certificate the checker rejects, or a
    disagreement of the judge, makes the verdict ``undecided`` -- the decision and its proof
    (or the definition) disagree, so neither is reported as established."""
    from hapticproof.exact.checker import check_certificates, judge_results

    data = finding.evidence.to_json()
    results = check_certificates(data)
    judged = judge_results({"verdict": finding.verdict.value, "evidence": data}, keys)
    if not results and not judged:
        return finding
    tally: dict[str, Any] = {}
    if results:
        tally.update({"certificates": len(results), "re-verified": sum(r.ok and r.verified for r in results)})
    definition = [r for r in judged if r.source == "judge"]
    if definition:
        tally["definition"] = [r.reason for r in definition]
    skipped = [r.reason for r in results if r.ok and not r.verified]
    failed = [r.reason for r in results + judged if not r.ok]
    if skipped:
        tally["not re-verified"] = skipped
    if failed:
        tally["rejected"] = failed
    evidence = replace(finding.evidence, facts={**finding.evidence.facts, "checker": tally})
    if not failed:
        return replace(finding, evidence=evidence)
    what = "a certificate of this check" if any(not r.ok for r in results) else "this verdict against the definition"
    return replace(finding, verdict=Verdict.UNDECIDED, evidence=evidence, corrected=None,
                   detail=f"the independent checker rejected {what} ({failed[0]}); "
                          f"the check had said {finding.verdict.value}: {finding.detail}")


def audit_paper(paper: Paper, only: Iterable[str] | None = None,
                progress: Callable[[int, int], None] | None = None) -> AuditReport:
    """Audit every registered equation of ``paper`` (or only the given ids), in order;
    ``progress(done, total)`` is called after each equation."""
    equations = [paper.get(i) for i in only] if only else paper.ordered()
    results = []
    for eq in equations:
        results.append(run_equation(paper, eq))
        if progress is not None:
            progress(len(results), len(equations))
    return AuditReport(paper.id, paper.title, tuple(results), notation_of(paper, results), paper.naming.changed())


def notation_of(paper: Paper, results: Iterable[EquationResult]) -> dict[str, str]:
    """The paper's renamed helpers (:meth:`~hapticproof.core.naming.Naming.legend`) that its
    results use, name -> meaning (``{"gamma": "cos wh"}``): what a report defines.

    >>> notation_of(Paper("p", "P", ""), ())
    {}
    """
    legend = paper.naming.legend()
    if not legend:
        return {}
    words: set[str] = set()
    for r in results:
        for text in (r.detail, r.derived, r.corrected, json.dumps(to_jsonable(r.evidence.to_json()))):
            words |= set(re.findall(r"[A-Za-z_]+", text or ""))
    return {name: meaning for name, meaning in legend.items() if name in words or name.replace("\\", "") in words}


def reports_to_json(reports: Iterable[AuditReport]) -> str:
    """``{"papers": [...]}`` for an audit of several papers."""
    return json.dumps({"papers": [r.to_json() for r in reports]}, indent=2, default=to_jsonable)
