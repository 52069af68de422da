"""``hapticproof new-paper FILE.toml [--from SOURCE]``: write a commented paper-file template to
fill in, or a draft read from the paper's LaTeX source or transcription."""

from __future__ import annotations

import argparse
import os
import sys

from hapticproof.cli.common import check_output, write_text
from hapticproof.core.errors import InputFormatError

__all__ = ["register"]


def register(sub: argparse._SubParsersAction) -> None:
    parser = sub.add_parser(
        "new-paper",
        help="write a paper-file template, or a draft from the paper's source (audit it with audit --paper FILE)",
        description="Write a commented paper file: the paper, its symbols, a scene and three printed displays "
        "with their claims. With --from SOURCE (a .tex file, a folder holding the main file and its \\input "
        "files, or a .txt/.md transcription with $$...$$ displays) every display of the source is written "
        "verbatim with its label or number as id, its section, the names it uses and, where its shape says "
        "it, a guessed claim and scene marked '# guessed:' for you to confirm; displays that cannot be "
        "classified are kept commented out with the reason. The file loads and audits as written. Edit the "
        "guesses, then run hapticproof audit --paper FILE.",
    )
    parser.add_argument("file", metavar="FILE", help="the paper file to write (.toml; - for standard output)")
    parser.add_argument("--from", dest="source", metavar="SOURCE",
                        help="the paper's LaTeX source (.tex file or folder) or a text/Markdown transcription")
    parser.add_argument("--id", dest="paper_id", metavar="ID", help="the paper id (default: from the source's name)")
    parser.add_argument("--force", action="store_true", help="overwrite an existing file")
    parser.set_defaults(handler=run)


def run(args: argparse.Namespace) -> int:
    from hapticproof.audit.paperfile import TEMPLATE

    path = args.file
    if path != "-":
        check_output(path, "new-paper", (".toml",), inputs=[args.source])     # never its own source
        if os.path.lexists(path) and not args.force:
            raise InputFormatError(f"new-paper {path}: the file exists (use --force to overwrite it)")
    note = ""
    if args.source is None:
        text = TEMPLATE
    else:
        from hapticproof.audit.source import draft, read_source
        from hapticproof.audit.source.draft import paper_id_of

        source = read_source(args.source)
        if not source.displays:
            raise InputFormatError(f"new-paper --from {args.source}: no displayed equation found "
                                   "(equation, align, \\[...\\], $$...$$)")
        paper_id = args.paper_id or (paper_id_of(path) if path != "-" else None)
        result = draft(source, paper_id=paper_id)
        text = result.text
        note = (f" ({len(source.displays)} displays: {result.active} with a guessed claim, "
                f"{result.commented} commented out)")
    written = write_text(path, text)
    if written is not None:
        print(f"wrote {written}{note}; audit it with: hapticproof audit --paper {written}", file=sys.stderr)
    return 0
