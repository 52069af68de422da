"""Command-line interface: ``hapticproof audit | derive | export | boundary | bench``.

Each subcommand lives in its own module of this package and exposes ``register(subparsers)``,
which adds its parser and sets ``handler`` to a function ``handler(args) -> int``.
User mistakes (:class:`~hapticproof.errors.HapticproofError`) become one line on stderr and exit
code 2; nothing else is caught.
"""

from __future__ import annotations

import argparse
import importlib
import sys
from collections.abc import Sequence

from hapticproof.errors import HapticproofError

__all__ = ["main", "build_parser"]

#: Subcommand modules, in the order they appear in ``--help``.
COMMANDS = ("audit", "derive", "export", "boundary", "bench")


def build_parser() -> argparse.ArgumentParser:
    parser = argparse.ArgumentParser(
        prog="hapticproof",
        description="Regenerate, certify and audit stability and passivity conditions of "
        "sampled-data haptic and teleoperation systems.",
    )
    sub = parser.add_subparsers(dest="command", required=True, metavar="COMMAND")
    for name in COMMANDS:
        try:
            module = importlib.import_module(f"hapticproof.cli.{name}")
        except ModuleNotFoundError as err:
            if err.name != f"hapticproof.cli.{name}":
                raise
            continue  # command not built yet
        module.register(sub)
    return parser


def main(argv: Sequence[str] | None = None) -> int:
    parser = build_parser()
    args = parser.parse_args(argv)
    try:
        return int(args.handler(args) or 0)
    except HapticproofError as err:
        print(f"hapticproof: error: {err}", file=sys.stderr)
        return 2
    except BrokenPipeError:  # e.g. piped into `head`
        return 0
