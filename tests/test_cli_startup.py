"""``--version`` and ``--help`` load nothing that computes (issue 29): the command modules import SymPy,
NumPy, SciPy, matplotlib and flint in their handlers, so answering costs the interpreter's start-up.
The time is measured by ``benchmarks/bench_cli.py``; here, which modules a fresh process loaded."""

from __future__ import annotations

import json
import subprocess
import sys

import pytest

#: What a parser must not load (each costs tenths of a second).
HEAVY = ("sympy", "numpy", "scipy", "matplotlib", "flint", "mpmath", "hapticproof.audit.runner",
         "hapticproof.analysis.maps")

PROBE = """
import contextlib, io, json, sys
from hapticproof.cli import main
out = io.StringIO()
with contextlib.redirect_stdout(out):
    try:
        code = main(sys.argv[1:])
    except SystemExit as stop:
        code = stop.code
print(json.dumps({"code": code, "out": out.getvalue(), "loaded": sorted(m for m in sys.modules)}))
"""


def probe(*argv: str) -> dict:
    done = subprocess.run([sys.executable, "-c", PROBE, *argv], capture_output=True, text=True, check=True)
    return json.loads(done.stdout)


@pytest.mark.parametrize("argv", [
    ["--version"], ["--help"], ["audit", "--help"], ["export", "--help"], ["derive", "--help"],
    ["derive", "single-user", "--help"], ["boundary", "--help"], ["map", "--help"], ["check", "--help"],
    ["new-paper", "--help"], ["bench", "--help"], ["zwidth", "--help"],
])
def test_help_and_version_load_nothing_that_computes(argv):
    result = probe(*argv)
    assert result["code"] == 0
    loaded = [m for m in result["loaded"] if any(m == h or m.startswith(h + ".") for h in HEAVY)]
    assert loaded == []
    assert result["out"].strip()


def test_the_version_and_the_commands_are_told():
    from hapticproof.cli import COMMANDS
    from hapticproof.core.version import VERSION

    assert probe("--version")["out"] == f"hapticproof {VERSION}\n"
    listing = probe("--help")["out"]
    assert all(command in listing for command in COMMANDS)
    systems = probe("derive", "--help")["out"]
    assert all(system in systems for system in ("single-user", "multi-user", "network", "teleoperator"))


def test_a_system_parsed_in_full_still_gets_its_options():
    # derive's systems other than the one asked for are a line of --help; the asked one parses as before
    from hapticproof.cli import build_parser

    args = build_parser("derive", "multi-user").parse_args(["derive", "multi-user", "--users", "3"])
    assert args.users == 3 and args.system == "multi-user"
    with pytest.raises(SystemExit):
        build_parser("derive", "single-user").parse_args(["derive", "single-user", "--users", "3"])

