r"""Mutation testing of the audit: does every check notice a changed display?

A check that returns the same verdict whatever the printed display says is a stub. This module
changes the printed LaTeX of every registered display at the token level, audits each *mutant*
through the same check function (a copy of the :class:`~hapticproof.audit.runner.Equation` with the
mutated ``printed``) and classifies the outcome:

``killed``
    the verdict, the detail or the corrected LaTeX changed (for a ``confirmed`` original: the
    verdict is no longer ``confirmed`` -- a changed display must not stay confirmed);
``equivalent``
    the mutant is proved to say the same thing: its parse with the paper's table is identical
    to the original's (e.g. ``K_{12} -> K_{21}`` of a symmetric family), or the check reports
    the same canonical form of what it read (``evidence.facts["printed_form"]``, e.g. gains
    identified by the paper's symmetry condition B); or the display is judged a defect and the
    mutant keeps that defect with its own evidence (a changed ``wrong`` display still ``wrong``
    at an exact witness, :func:`kept_defect`);
``survived``
    the result did not change and no such proof exists (the check cannot tell the displays
    apart: a defect of the check);
``crashed``
    the check raised (a traceback is always a defect; a mutant that no longer parses must give
    ``malformed``).

The edits are those of :mod:`hapticproof.audit.edits` (a sign, a factor 2, a dropped term, swapped
indices, a reversed relation, another symbol).

Claims (quoted prose) are mutated inside their ``$...$`` math only, and only when their check
reads its own printed text (found by running the check once with recording copies of every
registered equation, :func:`dependencies`). A claim or display whose verdict is *about* other
displays declares them in ``Equation.quotes`` (``20-colgate`` quotes (20) and (3); the
cross-paper checks quote displays of three papers): it is audited against the mutants of those
displays too (``dependent`` mutants), with the mutated display installed in its paper for the
duration of the check. A declared quote that the check never reads is a :class:`QuoteError`.

What counts as *proved* equivalent is decided by the check, not by this module: a check that
proves a display equal to what it derives (``compare_expressions``, ``compare_bounds``,
``compare_sign_conditions``) reports the canonical form of what it read in
``evidence.facts["printed_form"]`` -- the derived form when it proved them equal, the printed
one otherwise -- so a mutant that stays confirmed with the same canonical form was proved equal
by the same exact computation. Data displays (a matrix of numbers whose stated properties are
all the paper uses) report the tuple of the properties they verified; a mutant that keeps every
stated property is equivalent *as data*. A claim that states a property of quoted values (the
terminations it names are passive) reports the proposition and its exact decisions; a mutant
naming other values with the same property is equivalent *as a claim* (it is proved true the
same way). Each equivalent mutant records its basis (:data:`EQUIVALENCE_BASES`) and the report
counts them separately (see ``benchmarks/README.md``).

A run generates every mutant (``count=None``) or a deterministic sample: equations are shuffled
with ``seed`` and take one mutant each per round, operators in turn, until ``count`` mutants are
chosen. Each mutant runs under a time limit (:data:`TIME_LIMIT`; a check that hangs is a crash).
The test suite runs :func:`knob` mutants per paper (``HAPTICPROOF_MUTANTS=all`` runs every one).

The mutation score of a paper is ``killed / (total - equivalent)``.

>>> from hapticproof.audit.runner import Paper, AuditContext
>>> from hapticproof.audit.compare import compare_bounds
>>> from hapticproof.core.evidence import Finding
>>> import sympy as sp
>>> from hapticproof.audit.reader.printed import SymbolTable
>>> K, T, b = sp.symbols('K T b', positive=True)
>>> demo = Paper("demo", title="Demo", source="none", symbols=SymbolTable({"K": K, "T": T, "b": b}))
>>> @demo.equation("1", kind="condition", printed=r"b > \frac{KT}{2}")
... def one(ctx):
...     return compare_bounds(ctx.relation(), sp.Ge(b, K*T/2), b)
>>> [m.replacement for m in generate(demo.get("1"), demo) if m.operator == "relation"]
['<']
>>> report = mutate_paper(demo)
>>> report.counts()["killed"] == report.total, report.score
(True, 1.0)
"""

from __future__ import annotations

import dataclasses
import itertools
import os
import random
import re
import time
import traceback
from collections.abc import Callable, Iterable, Iterator
from contextlib import contextmanager
from dataclasses import dataclass
from typing import Any

import sympy as sp

from hapticproof.audit.edits import OPERATORS, Mutant, generate, resolves
from hapticproof.audit.runner import AuditContext, Equation, Paper
from hapticproof.core.errors import LatexParseError
from hapticproof.core.evidence import Finding, Verdict, to_jsonable

__all__ = [
    "OPERATORS",
    "OUTCOMES",
    "Mutant",
    "MutantResult",
    "MutationReport",
    "generate",
    "dependencies",
    "mutants_of",
    "run_mutant",
    "mutate_paper",
    "choose",
    "knob",
    "EQUIVALENCE_BASES",
    "DEFECTS",
    "kept_defect",
    "QuoteError",
    "MutantTimeout",
    "ENV_KNOB",
]

OUTCOMES = ("killed", "equivalent", "survived", "crashed")
#: Environment variable: ``all`` runs every mutant in the test suite, a number N samples N per paper.
ENV_KNOB = "HAPTICPROOF_MUTANTS"

# ---------------------------------------------------------------------------------------------
# which displays a check reads
# ---------------------------------------------------------------------------------------------


class _Reading(Equation):
    """An :class:`Equation` that records when its printed text is read."""

    def __getattribute__(self, name: str) -> Any:
        if name == "printed":
            _READ.add(object.__getattribute__(self, "_key"))
        return object.__getattribute__(self, name)


_READ: set[str] = set()


def _reading(paper: Paper, equation: Equation) -> _Reading:
    copy = _Reading(**{f.name: getattr(equation, f.name) for f in dataclasses.fields(Equation)})
    object.__setattr__(copy, "_key", f"{paper.id}:{equation.id}")
    return copy


def dependencies(paper: Paper, equation: Equation, registry: dict[str, Paper] | None = None) -> list[str]:
    """Displays (``paper:id``) whose printed text the check of ``equation`` reads, found by
    running it once with recording copies of every registered equation installed."""
    from hapticproof.audit.registry import papers as registered

    everything = dict(registry or registered())
    everything.setdefault(paper.id, paper)
    saved = {pid: dict(p.equations) for pid, p in everything.items()}
    _READ.clear()
    try:
        for p in everything.values():
            for eid, eq in list(p.equations.items()):
                p.equations[eid] = _reading(p, eq)
        own = paper.equations[equation.id]
        try:
            own.check(AuditContext(paper, own))
        except Exception:  # noqa: BLE001 - the reads before a failure still count
            pass
    finally:
        for pid, p in everything.items():
            p.equations.clear()
            p.equations.update(saved[pid])
    return sorted(_READ)


# ---------------------------------------------------------------------------------------------
# running mutants
# ---------------------------------------------------------------------------------------------


@dataclass(frozen=True, slots=True)
class MutantResult:
    """The audit of one mutant and its classification (one of :data:`OUTCOMES`)."""

    mutant: Mutant
    outcome: str
    verdict: str | None
    detail: str
    reason: str
    seconds: float
    basis: str = ""

    def to_json(self) -> dict[str, Any]:
        m = self.mutant
        return {"paper": m.paper, "equation": m.equation, "target": m.target, "operator": m.operator,
                "position": m.position, "original": m.original, "replacement": m.replacement, "edit": m.edit(),
                "outcome": self.outcome, "basis": self.basis, "verdict": self.verdict, "detail": self.detail,
                "reason": self.reason, "seconds": round(self.seconds, 4)}


#: How an equivalent mutant was proved equivalent (:attr:`MutantResult.basis`):
#: ``parse``  the mutant parses to the identical object with the paper's table (a declared
#:            symmetry such as K_{12} = K_{21}, or another spelling of the same mathematics);
#: ``form``   the check proved the mutated display equal to the same canonical form (e.g. the
#:            derived condition it confirms, a positive multiple, a renamed bound variable);
#: ``data``   a data display (a table of values) keeps every property the paper states and uses;
#: ``claim``  a claim (a proposition about quoted values or displays) is proved by the same
#:            exact decisions: it states the property of other values, and the property holds
#:            for them exactly as it does for the printed ones;
#: ``defect`` the display is judged a defect (``wrong``, ``typo``, ...) and the mutant keeps it,
#:            with its own evidence (:func:`kept_defect`): a changed wrong display that is still
#:            wrong is no survivor.
EQUIVALENCE_BASES = ("parse", "form", "data", "claim", "defect")


def _basis(form: str) -> str:
    if form.startswith("('data display"):
        return "data"
    if form.startswith("('claim:"):
        return "claim"
    return "form"


def _audit(paper: Paper, equation: Equation) -> Finding:
    """The finding of ``equation``'s check, as :func:`~hapticproof.audit.runner.run_equation` gets it
    (a parse error of the display becomes ``malformed``), without rendering the derived form."""
    from hapticproof.audit.runner import parse_failure

    try:
        return equation.check(AuditContext(paper, equation))
    except LatexParseError as err:
        return parse_failure(equation, err)


def _signature(obj: Any) -> Any:
    """A position-free normal form of a parse result (spans ignored)."""
    from hapticproof.audit.reader import statements as P

    if isinstance(obj, P.Expression):
        return ("expr", _signature(obj.expr), obj.label)
    if isinstance(obj, P.Relation):
        return ("rel", tuple(_signature(t) for t in obj.terms), obj.ops, obj.label)
    if isinstance(obj, P.Qualified):
        return ("qual", _signature(obj.body), tuple((r.indices, tuple(map(sp.srepr, r.values))) for r in obj.ranges),
                tuple(_signature(c) for c in obj.conditions), obj.label)
    if isinstance(obj, P.Lines):
        return ("lines", obj.kind, tuple(_signature(s) for s in obj.statements), obj.label)
    if isinstance(obj, sp.Basic):
        return sp.srepr(obj)
    return repr(obj)


def _parse_signature(text: str, paper: Paper) -> Any:
    from hapticproof.audit.reader.printed import parse_printed

    if paper.symbols is None:
        return None
    try:
        return _signature(parse_printed(text, paper.symbols))
    except Exception:  # noqa: BLE001 - a display that does not parse has no signature
        return None


def _printed_form(result: Any) -> Any:
    facts = result.evidence.facts or {}
    if "printed_form" not in facts:
        return None
    return repr(to_jsonable(facts["printed_form"]))


@contextmanager
def _installed(paper: Paper, equation: Equation) -> Iterator[None]:
    saved = paper.equations[equation.id]
    paper.equations[equation.id] = equation
    try:
        yield
    finally:
        paper.equations[equation.id] = saved


class MutantTimeout(Exception):
    """A check ran longer than the time limit on a mutant (counted as a crash)."""


@contextmanager
def _time_limit(seconds: float | None) -> Iterator[None]:
    import signal
    import threading

    if not seconds or threading.current_thread() is not threading.main_thread() or not hasattr(signal, "SIGPROF"):
        yield
        return

    def expire(signum: int, frame: Any) -> None:
        raise MutantTimeout(f"the check used more than {seconds:g} s of CPU time")

    # CPU time of this process (not wall time): a loaded machine must not turn slow checks into crashes
    previous = signal.signal(signal.SIGPROF, expire)
    signal.setitimer(signal.ITIMER_PROF, seconds)
    try:
        yield
    finally:
        signal.setitimer(signal.ITIMER_PROF, 0)
        signal.signal(signal.SIGPROF, previous)


#: CPU seconds a check may take on one mutant before it counts as a crash (a hanging check is a defect).
TIME_LIMIT = 120.0


def run_mutant(mutant: Mutant, original: Any, registry: dict[str, Paper] | None = None,
               limit: float | None = TIME_LIMIT) -> MutantResult:
    """Audit one mutant through the check of its equation and classify it against ``original``
    (the finding of the unmutated display)."""
    from hapticproof.audit.registry import get_paper

    lookup = dict(registry or {})

    def find(pid: str) -> Paper:
        return lookup[pid] if pid in lookup else get_paper(pid)

    paper = find(mutant.paper)
    equation = paper.get(mutant.equation)
    tpaper_id, _, tid = mutant.target.rpartition(":")
    target_paper = find(tpaper_id) if tpaper_id else paper
    target = target_paper.get(tid)
    mutated = dataclasses.replace(target, printed=mutant.printed)
    start = time.perf_counter()
    try:
        with _time_limit(limit), _installed(target_paper, mutated):
            result = _audit(paper, mutated if target is equation else equation)
    except Exception as err:  # noqa: BLE001 - a traceback is the finding
        seconds = time.perf_counter() - start
        tb = traceback.format_exception(type(err), err, err.__traceback__)
        return MutantResult(mutant, "crashed", None, f"{type(err).__name__}: {err}", "".join(tb[-4:]), seconds)
    seconds = time.perf_counter() - start
    verdict = result.verdict.value
    same = (result.verdict == original.verdict and result.detail == original.detail
            and result.corrected == original.corrected)
    if original.verdict == Verdict.CONFIRMED:
        unchanged = result.verdict == Verdict.CONFIRMED
    else:
        unchanged = same
    if not unchanged:
        return MutantResult(mutant, "killed", verdict, result.detail, "", seconds)
    if _parse_signature(mutant.printed, target_paper) is not None and \
            _parse_signature(mutant.printed, target_paper) == _parse_signature(target.printed, target_paper):
        return MutantResult(mutant, "equivalent", verdict, result.detail,
                            "identical parse with the paper's table (a declared symmetry or a canonical spelling)", seconds,
                            "parse")
    if mutant.operator in ("swap", "symbol") and _same_name(mutant, target_paper):
        return MutantResult(mutant, "equivalent", verdict, result.detail,
                            f"{mutant.replacement} and {mutant.original} name the same symbol in the paper's table "
                            "(a declared symmetry)", seconds, "parse")
    form, base = _printed_form(result), _printed_form(original)
    if form is not None and form == base:
        return MutantResult(mutant, "equivalent", verdict, result.detail,
                            f"the check reads the same canonical form: {form[:200]}", seconds, _basis(form))
    kept = kept_defect(original, result)
    if kept:
        return MutantResult(mutant, "equivalent", verdict, result.detail, kept, seconds, "defect")
    return MutantResult(mutant, "survived", verdict, result.detail, "same verdict, detail and correction", seconds)


#: Verdicts that judge a display a defect (a mutant of one may keep the defect).
DEFECTS = (Verdict.WRONG, Verdict.TYPO, Verdict.INCONSISTENT, Verdict.NEEDS_ASSUMPTION, Verdict.MALFORMED)


def kept_defect(original: Finding, result: Finding) -> str:
    """Why a mutant of a display judged a defect keeps that defect ('' when it does not): the same
    defect verdict, backed by the mutant's own evidence -- an exact witness (``wrong``,
    ``inconsistent``, ``needs-assumption``), the corrected display (``typo``) or what does not
    parse (``malformed``). Such a mutant is another wrong display, not one the check failed to
    tell apart from a right one: it counts as equivalent (basis ``defect``), not as a survivor.

    >>> from hapticproof.core.evidence import Evidence, Method
    >>> wrong = Finding(Verdict.WRONG, "fails at the witness", Evidence(Method.COUNTEREXAMPLE, witness={"K": 1}))
    >>> kept_defect(wrong, wrong)
    "keeps the display's defect: wrong with its own exact witness"
    >>> bare = Finding(Verdict.WRONG, "fails", Evidence(Method.COUNTEREXAMPLE))
    >>> kept_defect(wrong, bare)        # a verdict without evidence keeps nothing
    ''
    """
    if original.verdict not in DEFECTS or result.verdict != original.verdict:
        return ""
    if result.verdict in (Verdict.WRONG, Verdict.INCONSISTENT, Verdict.NEEDS_ASSUMPTION) and result.evidence.witness:
        return f"keeps the display's defect: {result.verdict.value} with its own exact witness"
    if result.verdict == Verdict.TYPO and result.corrected:
        return "keeps the display's defect: a typo with its corrected display"
    if result.verdict == Verdict.MALFORMED and result.evidence.method == "parse":
        return "keeps the display's defect: malformed, as the reader says"
    return ""


def _same_name(mutant: Mutant, paper: Paper) -> bool:
    """The replaced name resolves to the very symbol it replaced (``K_{30}`` is ``K_{03}`` when the
    table declares the family symmetric): equivalent even where the whole display does not parse."""
    before, after = resolves(mutant.original, paper.symbols), resolves(mutant.replacement, paper.symbols)
    if before is not None and before == after:
        return True
    # letter indices (K_{0i} -> K_{i0}): the same symbol for every concrete index, 1..3 each
    split = re.fullmatch(r"(.+?_\{?)([^{}]*)(\}?)", mutant.original), re.fullmatch(r"(.+?_\{?)([^{}]*)(\}?)", mutant.replacement)
    if not all(split) or split[0].group(1) != split[1].group(1) or before is None or after is None:
        return False
    letters = sorted({ch for ch in split[0].group(2) if ch.isalpha()})
    if not letters or len(letters) > 3 or {ch for ch in split[1].group(2) if ch.isalpha()} != set(letters):
        return False
    for values in itertools.product("123", repeat=len(letters)):
        table = str.maketrans(dict(zip(letters, values)))
        a = resolves(split[0].group(1) + split[0].group(2).translate(table) + split[0].group(3), paper.symbols)
        b = resolves(split[1].group(1) + split[1].group(2).translate(table) + split[1].group(3), paper.symbols)
        if a is None or a != b:
            return False
    return True


class QuoteError(ValueError):
    """An equation declares that it quotes a display its check never reads."""


def _quote_key(paper: Paper, quote: str) -> str:
    return quote if ":" in quote else f"{paper.id}:{quote}"


def mutants_of(paper: Paper, equation: Equation, registry: dict[str, Paper] | None = None) -> list[Mutant]:
    """Own mutants of a display (or of a claim's quoted mathematics, when its check reads it)
    and dependent mutants of the displays it declares it quotes (``Equation.quotes``)."""
    from hapticproof.audit.registry import get_paper

    own_key = f"{paper.id}:{equation.id}"
    quoted = [_quote_key(paper, q) for q in equation.quotes]
    reads = dependencies(paper, equation, registry) if (equation.kind == "claim" or quoted) else [own_key]
    missing = [q for q in quoted if q not in reads]
    if missing:
        raise QuoteError(f"{own_key} declares it quotes {missing} but its check does not read them")
    out: list[Mutant] = []
    if equation.kind != "claim" or own_key in reads:
        out.extend(generate(equation, paper))
    for key in quoted:
        pid, _, eid = key.partition(":")
        other_paper = (registry or {}).get(pid) or (paper if pid == paper.id else get_paper(pid))
        other = other_paper.get(eid)
        target = eid if pid == paper.id else key
        for m in generate(other, other_paper):
            out.append(dataclasses.replace(m, paper=paper.id, equation=equation.id, target=target))
    return out


@dataclass(frozen=True)
class MutationReport:
    """The mutation run of one paper."""

    paper: str
    results: tuple[MutantResult, ...]
    seconds: float
    generated: int = 0

    @property
    def total(self) -> int:
        return len(self.results)

    def counts(self) -> dict[str, int]:
        out = {k: 0 for k in OUTCOMES}
        for r in self.results:
            out[r.outcome] += 1
        return out

    @property
    def score(self) -> float:
        """``killed / (total - equivalent)`` (1.0 when every mutant is equivalent)."""
        c = self.counts()
        denominator = self.total - c["equivalent"]
        return 1.0 if denominator == 0 else c["killed"] / denominator

    def equivalence(self) -> dict[str, int]:
        """Equivalent mutants by the basis of their proof (:data:`EQUIVALENCE_BASES`)."""
        out = {k: 0 for k in EQUIVALENCE_BASES}
        for r in self.results:
            if r.outcome == "equivalent":
                out[r.basis] = out.get(r.basis, 0) + 1
        return out

    def survivors(self) -> list[MutantResult]:
        return [r for r in self.results if r.outcome == "survived"]

    def crashes(self) -> list[MutantResult]:
        return [r for r in self.results if r.outcome == "crashed"]

    def summary(self) -> str:
        c = self.counts()
        basis = ", ".join(f"{k} {n}" for k, n in self.equivalence().items() if n)
        # a sample generates only the mutants of the equations it visits (see choose)
        pool = "every mutant" if self.total == self.generated else f"a sample of the {self.generated} generated for the equations it visits"
        return (f"{self.paper}: {self.total} mutants ({pool}), {c['equivalent']} proved equivalent"
                f"{f' ({basis})' if basis else ''}, "
                f"{c['killed']} killed, {c['survived']} survived, {c['crashed']} crashed; "
                f"score {100 * self.score:.1f}% ({self.seconds:.0f} s)")

    def to_text(self) -> str:
        lines = [self.summary()]
        for r in self.crashes():
            lines.append(f"  CRASH {r.mutant.equation}: {r.mutant.describe()}: {r.detail}")
        for r in self.survivors():
            lines.append(f"  SURVIVED {r.mutant.equation}: {r.mutant.describe()} -> {r.verdict}: {r.detail[:120]}")
        return "\n".join(lines)

    def to_json(self) -> dict[str, Any]:
        return {"paper": self.paper, "generated": self.generated, "total": self.total, "counts": self.counts(),
                "equivalence": self.equivalence(),
                "score": self.score, "seconds": round(self.seconds, 2), "results": [r.to_json() for r in self.results]}


def _run_group(job: tuple[str, str, list[Mutant]]) -> list[MutantResult]:
    """Run the mutants of one audited equation (in a worker process or in this one)."""
    from hapticproof.audit.registry import get_paper

    paper_id, eq_id, group = job
    paper = get_paper(paper_id)
    original = _audit(paper, paper.get(eq_id))
    return [run_mutant(m, original) for m in group]


def choose(
    paper: Paper,
    only: Iterable[str] | None = None,
    *,
    count: int | None = None,
    seed: int = 0,
    registry: dict[str, Paper] | None = None,
) -> tuple[list[Mutant], int]:
    """The mutants a run audits and how many were generated: every mutant of ``paper`` (or of
    the equations ``only``) when ``count`` is None, else a deterministic sample of ``count``:
    the equations that read a display are shuffled with ``seed`` and give one mutant each per
    round, operators in turn, so that a small sample spreads over the paper without generating
    every mutant."""
    equations = [paper.get(i) for i in only] if only else paper.ordered()
    everything: list[Mutant] = []
    if count is None:
        for eq in equations:
            everything.extend(mutants_of(paper, eq, registry))
        return everything, len(everything)
    rng = random.Random(seed)
    candidates = [eq for eq in equations if eq.kind != "claim" or "$" in eq.printed or eq.quotes]
    rng.shuffle(candidates)
    pools: dict[str, list[Mutant]] = {}
    chosen: list[Mutant] = []
    for rounds in range(len(OPERATORS)):
        for k, eq in enumerate(candidates):
            if len(chosen) >= count:
                break
            if eq.id not in pools:
                pools[eq.id] = mutants_of(paper, eq, registry)
                everything.extend(pools[eq.id])
            pool = [m for m in pools[eq.id] if m not in chosen]
            if not pool:
                continue
            wanted = OPERATORS[(k + rounds) % len(OPERATORS)]
            preferred = [m for m in pool if m.operator == wanted] or pool
            chosen.append(preferred[rng.randrange(len(preferred))])
        if len(chosen) >= count:
            break
    return chosen, len(everything)


def mutate_paper(
    paper: Paper,
    only: Iterable[str] | None = None,
    *,
    count: int | None = None,
    seed: int = 0,
    registry: dict[str, Paper] | None = None,
    progress: Callable[[MutantResult], None] | None = None,
    jobs: int = 1,
) -> MutationReport:
    """Generate, sample (:func:`choose`) and run the mutants of ``paper`` (or of the equations
    ``only``); ``jobs > 1`` runs the equations' groups of mutants in that many worker processes
    (registered papers only).
    """
    from hapticproof.audit.registry import papers as registered

    start = time.perf_counter()
    if registry is None and registered().get(paper.id) is not paper:
        registry = {paper.id: paper}          # a paper of one's own, not in the registry
    chosen, generated = choose(paper, only, count=count, seed=seed, registry=registry)
    groups: dict[str, list[Mutant]] = {}
    for m in sorted(chosen, key=lambda m: (m.equation, m.target, m.position, m.operator, m.replacement)):
        groups.setdefault(m.equation, []).append(m)
    results: list[MutantResult] = []
    if jobs > 1 and len(groups) > 1 and registry is None:
        import multiprocessing
        from concurrent.futures import ProcessPoolExecutor

        order = sorted(groups, key=lambda e: -len(groups[e]))
        import os

        from hapticproof.core.processes import die_with_parent

        with ProcessPoolExecutor(jobs, mp_context=multiprocessing.get_context("fork"), initializer=die_with_parent,
                                 initargs=(os.getpid(),)) as pool:
            for batch in pool.map(_run_group, [(paper.id, e, groups[e]) for e in order]):
                for r in batch:
                    results.append(r)
                    if progress is not None:
                        progress(r)
    else:
        for eq_id, group in groups.items():
            original = _audit(paper, paper.get(eq_id))
            for m in group:
                r = run_mutant(m, original, registry)
                results.append(r)
                if progress is not None:
                    progress(r)
    results.sort(key=lambda r: (r.mutant.equation, r.mutant.target, r.mutant.position, r.mutant.operator))
    return MutationReport(paper.id, tuple(results), time.perf_counter() - start, generated)


def knob() -> int | None:
    """The sample size per paper the test suite uses: ``HAPTICPROOF_MUTANTS=all`` (every mutant)
    or a number; default 12."""
    value = os.environ.get(ENV_KNOB, "").strip().lower()
    if value == "all":
        return None
    return int(value) if value.isdigit() else 12
