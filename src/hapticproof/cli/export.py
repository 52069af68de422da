"""``hapticproof export [PAPER ...] -o FILE``: the derived conditions as a LaTeX document."""

from __future__ import annotations

import argparse
import sys
import time

from hapticproof.audit import audit_paper
from hapticproof.cli._common import write_text
from hapticproof.cli._terminal import progress_bar, summary_line, use_colour
from hapticproof.export import export_document
from hapticproof.registry import get_paper, papers

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
    parser.set_defaults(handler=run)


def run(args: argparse.Namespace) -> int:
    selected = [get_paper(p) for p in args.papers] if args.papers else list(papers().values())
    total = sum(len(p.equations) for p in selected)
    bar, start, reports = progress_bar(sys.stderr, "export"), time.perf_counter(), []
    for paper in selected:
        base = sum(len(r.results) for r in reports)
        reports.append(audit_paper(paper, progress=(lambda k, _n, base=base: bar(base + k, total)) if bar else None))
    path = write_text(args.output, export_document(selected, reports=reports))
    counts: dict[str, int] = {}
    for report in reports:
        for verdict, n in report.counts().items():
            counts[verdict] = counts.get(verdict, 0) + n
    if path is not None:  # "-" is standard output
        print(f"wrote {path}", file=sys.stderr)
    print(summary_line(counts, use_colour(sys.stderr), len(reports), time.perf_counter() - start), file=sys.stderr)
    return 0
