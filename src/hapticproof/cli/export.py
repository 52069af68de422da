"""``hapticproof export [PAPER ...] [--paper FILE ...] -o FILE``: the derived conditions as a LaTeX document.

Registered papers by id, your own papers by their paper files (``--paper review.toml``, as for
``audit``), or the papers of a saved audit (``--from-audit audit.json``: every paper it holds, a
paper file's included, unless papers are named).
"""

from __future__ import annotations

import argparse
import sys
import time

from hapticproof.cli.common import check_output, input_files, write_text
from hapticproof.cli.terminal import progress_bar, summary_line, use_colour
from hapticproof.core.errors import InputFormatError

__all__ = ["register"]


def register(sub: argparse._SubParsersAction) -> None:
    parser = sub.add_parser(
        "export",
        help="write the derived and corrected conditions of the bundled papers or of your paper files as LaTeX",
        description="Write the toolkit's derived conditions (and the corrected form of every "
        "defective printed equation) as a LaTeX document that compiles with pdflatex.",
    )
    parser.add_argument("papers", nargs="*", metavar="PAPER",
                        help="registered paper ids; default: all (with --from-audit: the papers of the saved audit)")
    parser.add_argument("--paper", "-p", action="append", default=[], metavar="FILE",
                        help="export your own paper from its paper file (TOML; repeatable), as 'audit --paper'")
    parser.add_argument("--output", "-o", metavar="FILE", default="hapticproof-conditions.tex")
    parser.add_argument("--from-audit", metavar="AUDIT.json",
                        help="reuse a saved 'hapticproof audit --format json' (of bundled papers or of paper files) "
                        "instead of deriving again")
    parser.add_argument("--jobs", "-j", type=int, metavar="N",
                        help="worker processes for the derivations (default: the machine's cores)")
    parser.set_defaults(handler=run)


def run(args: argparse.Namespace) -> int:
    from hapticproof.audit.registry import get_paper, papers
    from hapticproof.report.export import export_document

    check_output(args.output, "--output", inputs=input_files(args))     # before any work
    if args.jobs is not None and args.jobs < 1:
        raise InputFormatError("--jobs must be at least 1")
    files = _paper_files(args.paper)
    named = [_registered(name, get_paper) for name in args.papers] + files
    start = time.perf_counter()
    if args.from_audit:
        selected, reports = _saved(args.from_audit, named)
    else:
        from hapticproof.audit.pool import audit_reports

        selected = named or list(papers().values())
        total = sum(len(p.equations) for p in selected)
        bar = progress_bar(sys.stderr, "export")
        reports = audit_reports(selected, jobs=args.jobs, progress=(lambda k, _n: bar(k, total)) if bar else None)
    path = write_text(args.output, export_document(selected, reports=reports))
    counts: dict[str, int] = {}
    for report in reports:
        for verdict, n in report.counts().items():
            counts[verdict] = counts.get(verdict, 0) + n
    if path is not None:  # "-" is standard output
        print(f"wrote {path}", file=sys.stderr)
    print(summary_line(counts, use_colour(sys.stderr), len(reports), time.perf_counter() - start), file=sys.stderr)
    return 0


def _paper_files(paths: list[str]) -> list:
    """The papers of ``--paper`` files (their mistakes are one-line errors)."""
    if not paths:
        return []
    from hapticproof.audit.paperfile import read_paper

    return [read_paper(path).paper for path in paths]


def _registered(name: str, get_paper):
    """A registered paper by id; a paper file's name given as a PAPER is pointed to ``--paper``."""
    import os

    from hapticproof.core.errors import UnknownPaperError

    try:
        return get_paper(name)
    except UnknownPaperError as err:
        if os.path.isfile(name) or name.endswith(".toml"):
            raise InputFormatError(f"{err}; a paper file is exported with --paper {name}") from None
        raise UnknownPaperError(f"{err}; your own paper: --paper FILE (its paper file), or --from-audit "
                                "AUDIT.json (its saved audit)") from None


def _saved(path: str, named: list) -> tuple[list, list]:
    """The papers and reports of a saved audit: those ``named`` (registered or paper files), else
    every paper it holds (a paper it does not know is shown by the id and title it saved)."""
    from hapticproof.audit.registry import papers
    from hapticproof.audit.runner import Paper
    from hapticproof.core.files import read_json, read_text
    from hapticproof.core.shapes import check_audit
    from hapticproof.report.export import reports_from_json

    data = read_json(read_text(path), path)
    check_audit(data, path)          # the shape first: a number or null is one line, not a KeyError
    known = {**papers(), **{p.id: p for p in named}}
    try:
        reports = {r.paper: r for r in reports_from_json(data, known.values())}
    except (ValueError, KeyError, TypeError) as err:
        raise InputFormatError(f"--from-audit {path}: not a saved audit ({type(err).__name__}: {err})") from None
    if named:
        missing = [p.id for p in named if p.id not in reports]
        if missing:
            held = ", ".join(reports) or "none"
            raise InputFormatError(f"--from-audit {path} has no audit of {', '.join(missing)} (it holds: {held})")
        return named, [reports[p.id] for p in named]
    selected = [known.get(pid) or Paper(pid, title=report.title or pid, source=f"saved audit {path}")
                for pid, report in reports.items()]
    return selected, list(reports.values())
