"""``hapticproof derive SYSTEM ...``: derive the exact conditions of a scene.

Each system lives in its own module ``hapticproof.cli.derive_<system>`` exposing
``register(subparsers)`` (adds its parser, sets ``handler``).
"""

from __future__ import annotations

import argparse
import importlib

__all__ = ["register", "SYSTEMS", "complete_argv"]

#: System modules, in ``--help`` order.
SYSTEMS = ("single_user", "multi_user", "network", "teleoperator")


def register(sub: argparse._SubParsersAction) -> None:
    parser = sub.add_parser(
        "derive",
        help="derive the exact conditions of a scene (G^-1, residues, Hermitian part, worst case)",
        description="Derive the exact stability/passivity conditions of a scene given on the "
        "command line or in a scene file (hapticproof derive --scene FILE.toml: the system is the file's). "
        "Parameters are symbolic unless fixed with --param NAME=VALUE.",
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


def complete_argv(argv: list[str]) -> list[str]:
    """``derive --scene FILE ...`` (or ``boundary --scene FILE ...``) without a system: insert
    the scene file's system after the command, so the system's options parse as usual."""
    if len(argv) < 2 or argv[0] not in ("derive", "boundary"):
        return argv
    systems = ("single-user", "multi-user", "teleoperator", "network")
    if any(a in systems for a in argv[1:2]):
        return argv
    path = None
    for i, arg in enumerate(argv):
        if arg == "--scene" and i + 1 < len(argv):
            path = argv[i + 1]
        elif arg.startswith("--scene="):
            path = arg.split("=", 1)[1]
    if path is None:
        return argv
    from hapticproof.systems.scene import read_scene

    system = read_scene(path).system
    return [argv[0], system] + argv[1:]
