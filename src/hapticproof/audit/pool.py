"""The audit in parallel: the papers' equations in worker processes, the same reports.

:func:`audit_reports` audits several papers with ``jobs`` worker processes and returns the
:class:`~hapticproof.audit.runner.AuditReport` objects the serial run gives, in paper order; every output
format renders them identically. The parent imports and registers every paper first, so the
workers (forked) start warm. Equations travel in small chunks of neighbours of one section; each
worker keeps to one paper while it has work (a paper's equations share cached derivations, which
one worker then computes once) and takes its costliest chunks first (:data:`COST_HINTS`, a
previous run's slowest derivations), so that the long ones do not end up last on one core. A
worker returns each result with its evidence as plain data (the evidence's own JSON, which every
view renders the same way), because certificates hold flint objects that do
not pickle. A check's exception propagates, as in the serial run.

``jobs=1`` is the serial run itself (:func:`hapticproof.audit.runner.audit_paper`).

>>> from hapticproof.audit.runner import Paper, Finding, Verdict, Evidence
>>> paper = Paper("demo", title="Demo", source="none")
>>> @paper.equation("1", kind="claim", printed="1 + 1 = 2")
... def one(ctx):
...     return Finding(Verdict.CONFIRMED, "arithmetic", Evidence("canonical-form"))
>>> [r.verdict.value for r in audit_reports([paper], jobs=1)[0].results]
['confirmed']
"""

from __future__ import annotations

import multiprocessing
import multiprocessing.connection
import os
from collections.abc import Callable, Mapping, Sequence
from dataclasses import replace
from typing import Any
from hapticproof.audit.runner import AuditReport, EquationResult, Paper, audit_paper, notation_of, run_equation
from hapticproof.core.evidence import Evidence
from hapticproof.core.processes import die_with_parent

__all__ = ["audit_reports", "default_jobs", "COST_HINTS", "CHUNK"]

#: At most this many consecutive equations of one section per task.
CHUNK = 4
#: Assumed seconds of an equation without a hint (only the order depends on it).
DEFAULT_COST = 0.08

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


def _worker(conn: Any, inherited: Sequence[Any] = (), parent: int | None = None) -> None:
    """A forked worker: run the chunks it is sent until ``None`` (or the end of the pipe: the
    parent is gone); an exception goes back to the parent (which raises it, as the serial run
    would). ``inherited`` are the parent's ends of the other workers' pipes, which the fork
    copied: closed here, so that each pipe ends when the parent does."""
    for other in inherited:
        other.close()
    if parent is not None:
        die_with_parent(parent)
    while True:
        try:
            task = conn.recv()
        except (EOFError, OSError):     # the parent closed its end or died
            os._exit(0)
        if task is None:
            conn.close()
            return
        try:
            conn.send(("ok", _run(task)))
        except BaseException as err:  # noqa: BLE001 - re-raised in the parent
            import traceback

            try:
                conn.send(("error", err, traceback.format_exc()))
            except Exception:  # noqa: BLE001 - an unpicklable exception: its text
                conn.send(("error", RuntimeError(repr(err)), traceback.format_exc()))


def _cost(task: tuple[str, tuple[str, ...]]) -> float:
    return sum(COST_HINTS.get((task[0], i), DEFAULT_COST) for i in task[1])


class _Queues:
    """Chunks per paper, with paper affinity: a worker keeps to one paper (its cached
    derivations stay warm) and, when that runs dry, takes the costliest chunk of the paper with
    the most work left that no worker holds, else of the one with the most work left."""

    def __init__(self, tasks: list[tuple[str, tuple[str, ...]]]):
        self.papers: dict[str, list] = {}
        for task in tasks:
            self.papers.setdefault(task[0], []).append(task)
        for chunks in self.papers.values():
            chunks.sort(key=_cost)          # the costliest last: pop() takes it first

    def left(self, paper: str) -> float:
        return sum(_cost(t) for t in self.papers.get(paper, []))

    def next(self, home: str | None, held: set[str]) -> tuple[str, tuple[str, ...]] | None:
        if home is None or not self.papers.get(home):
            free = [p for p, chunks in self.papers.items() if chunks and p not in held]
            pool = free or [p for p, chunks in self.papers.items() if chunks]
            if not pool:
                return None
            home = max(pool, key=self.left)
        return self.papers[home].pop()


def audit_reports(papers: Sequence[Paper], only: Mapping[str, Sequence[str] | None] | None = None,
                  jobs: int | None = None, progress: Callable[[int, int], None] | None = None) -> list[AuditReport]:
    """Audit ``papers`` (``only[paper.id]``: just those equation ids) with ``jobs`` processes;
    ``progress(done, total)`` after each equation (serial) or each finished chunk (parallel)."""
    jobs = default_jobs() if jobs is None else max(1, int(jobs))
    only = only or {}
    selected = {p.id: ([p.get(i) for i in only[p.id]] if only.get(p.id) else p.ordered()) for p in papers}
    tasks = _chunks(papers, selected, CHUNK)
    total = sum(len(eqs) for eqs in selected.values())
    if jobs <= 1 or len(tasks) <= 1 or "fork" not in multiprocessing.get_all_start_methods():
        reports: list[AuditReport] = []
        for p in papers:
            base = sum(len(r.results) for r in reports)
            tick = (lambda k, _n, base=base: progress(base + k, total)) if progress else None
            reports.append(audit_paper(p, only.get(p.id) or None, progress=tick))
        return reports
    _PAPERS.clear()
    _PAPERS.update({p.id: p for p in papers})
    context = multiprocessing.get_context("fork")
    queues = _Queues(tasks)
    results: dict[tuple[str, str], EquationResult] = {}
    workers = []
    finished = False
    for _ in range(min(jobs, len(tasks))):
        parent, child = context.Pipe()
        process = context.Process(target=_worker, args=(child, [w[1] for w in workers] + [parent], os.getpid()),
                                  daemon=True)
        process.start()
        child.close()
        workers.append([process, parent, None])          # process, pipe, paper in hand
    try:
        busy = 0
        for worker in workers:
            task = queues.next(None, {w[2] for w in workers if w[2]})
            if task is None:
                break
            worker[2] = task[0]
            worker[1].send(task)
            busy += 1
        by_pipe = {w[1]: w for w in workers}
        while busy:
            for pipe in multiprocessing.connection.wait([w[1] for w in workers if w[2] is not None]):
                worker = by_pipe[pipe]
                try:
                    message = pipe.recv()
                except EOFError:
                    raise RuntimeError("an audit worker process died") from None
                if message[0] == "error":
                    raise message[1] from RuntimeError("in the audit worker:\n" + message[2])
                paper = worker[2]
                for result in message[1]:
                    results[(paper, result.id)] = result
                if progress:
                    progress(len(results), total)
                worker[2] = None
                task = queues.next(paper, {w[2] for w in workers if w[2]})
                if task is None:
                    busy -= 1
                    continue
                worker[2] = task[0]
                pipe.send(task)
        finished = True
    finally:
        for process, pipe, _ in workers:
            try:
                if finished:
                    pipe.send(None)
                else:           # an error or Ctrl-C: the workers' work is of no use any more
                    process.terminate()
            except (BrokenPipeError, OSError):
                pass
        for process, pipe, _ in workers:
            process.join(timeout=5)
            if process.is_alive():
                process.kill()
                process.join(timeout=5)
            pipe.close()
    return [AuditReport(p.id, p.title, rows, notation_of(p, rows), p.naming.changed())
            for p in papers for rows in [tuple(results[(p.id, eq.id)] for eq in selected[p.id])]]
