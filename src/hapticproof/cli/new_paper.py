"""``hapticproof new-paper FILE.toml``: write a commented paper-file template to fill in."""

from __future__ import annotations

import argparse
import sys
from pathlib import Path

from hapticproof.cli.common import check_output, write_text
from hapticproof.core.errors import InputFormatError

__all__ = ["register"]


def register(sub: argparse._SubParsersAction) -> None:
    parser = sub.add_parser(
        "new-paper",
        help="write a paper-file template (audit your own paper with audit --paper FILE)",
        description="Write a commented paper file: the paper, its symbols, a scene and three printed displays "
        "with their claims. Edit it, then run hapticproof audit --paper FILE.",
    )
    parser.add_argument("file", metavar="FILE", help="the paper file to write (.toml; - for standard output)")
    parser.add_argument("--force", action="store_true", help="overwrite an existing file")
    parser.set_defaults(handler=run)


def run(args: argparse.Namespace) -> int:
    from hapticproof.audit.paperfile import TEMPLATE

    path = args.file
    if path != "-":
        check_output(path, "new-paper", (".toml",))
        if Path(path).exists() and not args.force:
            raise InputFormatError(f"new-paper {path}: the file exists (use --force to overwrite it)")
    written = write_text(path, TEMPLATE)
    if written is not None:
        print(f"wrote {written}; audit it with: hapticproof audit --paper {written}", file=sys.stderr)
    return 0
