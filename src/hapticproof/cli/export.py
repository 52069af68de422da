"""``hapticproof export [PAPER ...] -o FILE``: the derived conditions as a LaTeX document."""

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
        help="write the derived conditions of the papers as a LaTeX file (amsmath)",
        description="Write the toolkit's derived conditions (and the corrected form of every "
        "defective printed equation) as a LaTeX document that compiles with pdflatex.",
    )
    parser.add_argument("papers", nargs="*", metavar="PAPER", help="paper ids; default: all")
    parser.add_argument("--output", "-o", metavar="FILE", default="hapticproof-conditions.tex")
    parser.add_argument("--from-audit", metavar="AUDIT.json",
                        help="reuse a saved 'hapticproof audit --format json' instead of deriving again")
    parser.add_argument("--jobs", "-j", type=int, metavar="N",
                        help="worker processes for the derivations (default: the machine's cores)")
    parser.set_defaults(handler=run)


def run(args: argparse.Namespace) -> int:
    from hapticproof.audit.registry import get_paper, papers
    from hapticproof.report.export import export_document

    check_output(args.output, "--output", inputs=input_files(args))     # before any work
    selected = [get_paper(p) for p in args.papers] if args.papers else list(papers().values())
    if args.jobs is not None and args.jobs < 1:
        raise InputFormatError("--jobs must be at least 1")
    start = time.perf_counter()
    if args.from_audit:
        reports = _saved(args.from_audit, selected)
    else:
        from hapticproof.audit.pool import audit_reports

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


def _saved(path: str, selected: list) -> list:
    from hapticproof.core.files import read_json, read_text
    from hapticproof.core.shapes import check_audit
    from hapticproof.report.export import reports_from_json

    data = read_json(read_text(path), path)
    check_audit(data, path)          # the shape first: a number or null is one line, not a KeyError
    try:
        reports = {r.paper: r for r in reports_from_json(data, selected)}
    except (ValueError, KeyError, TypeError) as err:
        raise InputFormatError(f"--from-audit {path}: not a saved audit ({type(err).__name__}: {err})") from None
    missing = [p.id for p in selected if p.id not in reports]
    if missing:
        raise InputFormatError(f"--from-audit {path} has no audit of {', '.join(missing)}")
    return [reports[p.id] for p in selected]
