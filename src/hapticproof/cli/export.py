"""``hapticproof export [PAPER ...] -o FILE``: the derived conditions as a LaTeX document."""

from __future__ import annotations

import argparse
import sys

from hapticproof.cli._common import write_text
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
    path = write_text(args.output, export_document(selected))
    if path is not None:  # "-" is standard output
        print(f"wrote {path}", file=sys.stderr)
    return 0
