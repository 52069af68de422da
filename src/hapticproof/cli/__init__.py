"""Command-line interface: ``hapticproof audit | derive | export | boundary | map | bench``.

Each subcommand lives in its own module of this package and exposes ``register(subparsers)``,
which adds its parser and sets ``handler`` to a function ``handler(args) -> int``.
User mistakes (:class:`~hapticproof.core.errors.HapticproofError`) become one line on stderr and exit
code 2; nothing else is caught.
"""

from __future__ import annotations

import argparse
import importlib
import sys
from collections.abc import Sequence

from hapticproof.core.errors import HapticproofError

__all__ = ["main", "build_parser"]

#: Subcommand modules, in the order they appear in ``--help``.
COMMANDS = ("audit", "new-paper", "derive", "check", "export", "boundary", "map", "bench")


def build_parser(command: str | None = None) -> argparse.ArgumentParser:
    """The parser with every subcommand, or only ``command`` (its module alone is imported:
    ``hapticproof audit`` need not load the simulation and plotting stack of ``boundary``)."""
    parser = argparse.ArgumentParser(
        prog="hapticproof",
        description="Regenerate, certify and audit stability and passivity conditions of "
        "sampled-data haptic and teleoperation systems.",
    )
    from hapticproof.core.version import VERSION

    parser.add_argument("--version", action="version", version=f"hapticproof {VERSION}")
    sub = parser.add_subparsers(dest="command", required=True, metavar="COMMAND")
    for name in (command,) if command in COMMANDS else COMMANDS:
        importlib.import_module(f"hapticproof.cli.{name.replace('-', '_')}").register(sub)
    return parser


def main(argv: Sequence[str] | None = None) -> int:
    argv = list(sys.argv[1:] if argv is None else argv)
    try:
        if argv and argv[0] in ("derive", "boundary") and "--scene" in " ".join(argv):
            from hapticproof.cli.derive import complete_argv

            argv = complete_argv(argv)
    except HapticproofError as err:
        print(f"hapticproof: error: {err}", file=sys.stderr)
        return 2
    parser = build_parser(argv[0] if argv else None)
    args = parser.parse_args(argv)
    try:
        return int(args.handler(args) or 0)
    except HapticproofError as err:
        print(f"hapticproof: error: {err}", file=sys.stderr)
        return 2
    except BrokenPipeError:  # e.g. piped into `head`
        return 0
