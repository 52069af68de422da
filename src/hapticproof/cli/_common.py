"""Helpers shared by the subcommands: ``--param NAME=VALUE`` parsing and output files."""

from __future__ import annotations

import argparse
from pathlib import Path

import sympy as sp

from hapticproof.errors import InputFormatError
from hapticproof.evidence import exact

__all__ = ["parse_params", "add_param_option", "write_text"]


def add_param_option(parser: argparse.ArgumentParser) -> None:
    parser.add_argument(
        "--param",
        action="append",
        default=[],
        metavar="NAME=VALUE",
        help="fix a parameter to an exact value (decimals are read as exact decimals: "
        "0.015 means 15/1000); repeat for several parameters",
    )


def parse_params(items: list[str]) -> dict[str, sp.Rational]:
    """Parse ``["K=2", "T=1e-3"]`` into exact rationals.

    >>> parse_params(["K=2", "T=1e-3", "b=0.01822"])
    {'K': 2, 'T': 1/1000, 'b': 911/50000}
    """
    out: dict[str, sp.Rational] = {}
    for item in items:
        name, sep, value = item.partition("=")
        name = name.strip()
        if not sep or not name or not value.strip():
            raise InputFormatError(f"--param expects NAME=VALUE, got {item!r}")
        try:
            out[name] = exact(value.strip())
        except (ValueError, ZeroDivisionError) as err:
            raise InputFormatError(f"--param {name}: {value!r} is not a number") from err
    return out


def write_text(path: str | Path, text: str) -> Path:
    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    path.write_text(text, encoding="utf-8")
    return path
