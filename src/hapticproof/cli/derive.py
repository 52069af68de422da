"""``hapticproof derive SYSTEM ...``: derive the exact conditions of a scene.

Each system lives in its own module ``hapticproof.cli.derive_<system>`` exposing
``register(subparsers)`` (adds its parser, sets ``handler``).
"""

from __future__ import annotations

import argparse
import importlib

__all__ = ["register", "SYSTEMS"]

#: System modules, in ``--help`` order.
SYSTEMS = ("single_user", "multi_user", "network", "teleoperator")


def register(sub: argparse._SubParsersAction) -> None:
    parser = sub.add_parser(
        "derive",
        help="derive the exact conditions of a scene (G^-1, residues, Hermitian part, worst case)",
        description="Derive the exact stability/passivity conditions of a scene given on the "
        "command line. Parameters are symbolic unless fixed with --param NAME=VALUE.",
    )
    systems = parser.add_subparsers(dest="system", required=True, metavar="SYSTEM")
    for name in SYSTEMS:
        try:
            module = importlib.import_module(f"hapticproof.cli.derive_{name}")
        except ModuleNotFoundError as err:
            if err.name != f"hapticproof.cli.derive_{name}":
                raise
            continue
        module.register(systems)
