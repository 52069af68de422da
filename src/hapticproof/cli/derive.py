"""``hapticproof derive SYSTEM ...``: derive the exact conditions of a scene.

Each system lives in its own module ``hapticproof.cli.derive_<system>`` exposing
``register(subparsers)`` (adds its parser, sets ``handler``).
"""

from __future__ import annotations

import argparse
import importlib

__all__ = ["register", "SYSTEMS", "complete_argv"]

#: The systems, in ``--help`` order, with the one line ``derive --help`` shows for each. A system's
#: module ``hapticproof.cli.derive_<system>`` is imported only when its system is asked for.
SYSTEMS = {
    "single-user": "1-DOF device on a discrete environment (HVE paper, Fig. 4)",
    "multi-user": "m users coupled through a shared virtual environment (HVE paper, Section 3.2)",
    "network": "n-port networks: positive realness, Llewellyn, Youla symmetrization, absolute stability",
    "teleoperator": "sampled-data position-error-based teleoperator (teleoperator paper, Fig. 2)",
}


def register(sub: argparse._SubParsersAction, system: str | None = None) -> None:
    """Add ``derive`` and its systems; only ``system`` (the one on the command line) gets its full
    parser, the others a line in ``derive --help`` (so ``--help`` loads no system's module)."""
    parser = sub.add_parser(
        "derive",
        help="derive the exact conditions of a scene (G^-1, residues, Hermitian part, worst case)",
        description="Derive the exact stability/passivity conditions of a scene given on the "
        "command line or in a scene file (hapticproof derive --scene FILE.toml: the system is the file's). "
        "Parameters are symbolic unless fixed with --param NAME=VALUE.",
    )
    systems = parser.add_subparsers(dest="system", required=True, metavar="SYSTEM")
    for name, line in SYSTEMS.items():
        if name == system:
            importlib.import_module(f"hapticproof.cli.derive_{name.replace('-', '_')}").register(systems, line)
        else:
            systems.add_parser(name, help=line, add_help=False)


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
