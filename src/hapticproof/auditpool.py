"""The audit in parallel: the papers' equations in worker processes, the same reports.

:func:`audit_reports` audits several papers with ``jobs`` worker processes and returns the
:class:`~hapticproof.audit.AuditReport` objects the serial run gives, in paper order; every output
format renders them identically. The parent imports and registers every paper first, so the
workers (forked) start warm; equations are handed out in small chunks, costliest first when a
previous run's timings are known (:data:`COST_HINTS`), so that the long derivations do not end
up last on one core, and neighbouring equations of a section travel together (they often share
cached derivations, which one worker then computes once). A worker returns each result with its evidence as plain data (the evidence's
own JSON, which every view renders the same way), because certificates hold flint objects that do
not pickle. A check's exception propagates, as in the serial run.

``jobs=1`` is the serial run itself (:func:`hapticproof.audit.audit_paper`).

>>> from hapticproof.audit import Paper, Finding, Verdict, Evidence
>>> paper = Paper("demo", title="Demo", source="none")
>>> @paper.equation("1", kind="claim", printed="1 + 1 = 2")
... def one(ctx):
...     return Finding(Verdict.CONFIRMED, "arithmetic", Evidence("canonical-form"))
>>> [r.verdict.value for r in audit_reports([paper], jobs=1)[0].results]
['confirmed']
"""

from __future__ import annotations

import concurrent.futures
import multiprocessing
import os
from collections.abc import Mapping, Sequence
from dataclasses import replace
from hapticproof.audit import AuditReport, EquationResult, Paper, audit_paper, run_equation
from hapticproof.evidence import Evidence

__all__ = ["audit_reports", "default_jobs", "COST_HINTS", "CHUNK"]

#: At most this many consecutive equations of one section per task.
CHUNK = 4

#: Seconds of the slowest derivations in a previous full run (one core): handed out first.
#: Only the order depends on it; unknown equations count as cheap.
COST_HINTS: dict[tuple[str, str], float] = {
    ("teleoperator", "33"): 0.52, ("hve", "sec4-dual"): 0.47, ("bilateral-3dof", "fig3-6"): 0.67,
    ("hve", "51"): 0.63, ("hve", "59b"): 0.43, ("bilateral-3dof", "15c"): 0.3, ("hve", "23"): 0.53,
    ("teleoperator", "32"): 0.3, ("hve", "54"): 0.39, ("hve", "56-residue"): 0.3, ("hve", "59"): 0.45,
    ("teleoperator", "29"): 0.25, ("hve", "4"): 0.43, ("hve", "2"): 0.42,
}


def default_jobs() -> int:
    """The machine's cores available to this process (``hapticproof audit --jobs`` default).

    >>> default_jobs() >= 1
    True
    """
    try:
        return len(os.sched_getaffinity(0))
    except AttributeError:  # pragma: no cover - not Linux
        return os.cpu_count() or 1


_PAPERS: dict[str, Paper] = {}


def _plain(result: EquationResult) -> EquationResult:
    """The result with its evidence rebuilt from its JSON (picklable; renders identically)."""
    data = result.evidence.to_json()
    evidence = Evidence(data["method"], witness=data.get("witness"), instances=data.get("instances"),
                        facts=data.get("facts", {}))
    return replace(result, evidence=evidence)


def _run(task: tuple[str, tuple[str, ...]]) -> list[EquationResult]:
    paper = _PAPERS[task[0]]
    return [_plain(run_equation(paper, paper.get(i))) for i in task[1]]


def _chunks(papers: Sequence[Paper], selected: Mapping[str, list], size: int) -> list[tuple[str, tuple[str, ...]]]:
    """Consecutive equations of one section, at most ``size`` per task (neighbours often share
    cached derivations, which a worker then computes once); the costliest alone."""
    out: list[tuple[str, tuple[str, ...]]] = []
    for p in papers:
        run: list[str] = []
        section = None
        for eq in selected[p.id]:
            if run and (eq.section != section or len(run) >= size or (p.id, eq.id) in COST_HINTS):
                out.append((p.id, tuple(run)))
                run = []
            run.append(eq.id)
            section = eq.section
            if (p.id, eq.id) in COST_HINTS:
                out.append((p.id, tuple(run)))
                run = []
        if run:
            out.append((p.id, tuple(run)))
    return out


def audit_reports(papers: Sequence[Paper], only: Mapping[str, Sequence[str]] | None = None,
                  jobs: int | None = None) -> list[AuditReport]:
    """Audit ``papers`` (``only[paper.id]``: just those equation ids) with ``jobs`` processes."""
    jobs = default_jobs() if jobs is None else max(1, int(jobs))
    only = only or {}
    selected = {p.id: ([p.get(i) for i in only[p.id]] if only.get(p.id) else p.ordered()) for p in papers}
    tasks = _chunks(papers, selected, CHUNK)
    if jobs <= 1 or len(tasks) <= 1 or "fork" not in multiprocessing.get_all_start_methods():
        return [audit_paper(p, only.get(p.id) or None) for p in papers]
    _PAPERS.clear()
    _PAPERS.update({p.id: p for p in papers})

    def cost(task: tuple[str, tuple[str, ...]]) -> float:
        return sum(COST_HINTS.get((task[0], i), 0.05) for i in task[1])

    results: dict[tuple[str, str], EquationResult] = {}
    context = multiprocessing.get_context("fork")
    with concurrent.futures.ProcessPoolExecutor(max_workers=min(jobs, len(tasks)), mp_context=context) as pool:
        futures = {pool.submit(_run, task): task for task in sorted(tasks, key=cost, reverse=True)}
        for future in concurrent.futures.as_completed(futures):
            for result in future.result():
                results[(futures[future][0], result.id)] = result
    return [AuditReport(p.id, p.title, tuple(results[(p.id, eq.id)] for eq in selected[p.id])) for p in papers]

