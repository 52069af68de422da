"""Helpers shared by the subcommands: scene options (one set for ``derive`` and ``boundary``,
the fields of a scene file), ``--param NAME=VALUE`` parsing and output files (``-`` is
standard output everywhere, and an output is checked before any work starts)."""

from __future__ import annotations

import argparse
import sys
from pathlib import Path
from typing import Any

import sympy as sp

from hapticproof.core.errors import InputFormatError
from hapticproof.core.evidence import exact
from hapticproof.core.limits import LimitError

__all__ = ["parse_params", "param_items", "add_param_option", "write_text", "add_output_option", "check_output",
           "write_output", "add_scene_options", "scene_from_args", "input_files"]


def add_param_option(parser: argparse.ArgumentParser) -> None:
    parser.add_argument(
        "--param",
        action="append",
        default=[],
        metavar="NAME=VALUE",
        help="set a parameter of the scene (any name the scene uses): an exact number (0.015 means "
        "15/1000, 1/3 a third), an expression of other parameters (K_0=K/2) or an assumption "
        "(M=positive, nonnegative, real...) that keeps it symbolic; repeat for several. Unset "
        "parameters stay symbolic.",
    )


def param_items(items: list[str]) -> dict[str, str]:
    """``["K=2", "M=positive"]`` -> ``{"K": "2", "M": "positive"}`` (values read by the scene).

    >>> param_items(["K=2", " M = positive"])
    {'K': '2', 'M': 'positive'}
    """
    out: dict[str, str] = {}
    for item in items:
        name, sep, value = item.partition("=")
        name = name.strip()
        if not sep or not name or not value.strip():
            raise InputFormatError(f"--param expects NAME=VALUE, got {item!r}")
        out[name] = value.strip()
    return out


def parse_params(items: list[str]) -> dict[str, sp.Rational]:
    """Parse ``["K=2", "T=1e-3"]`` into exact rationals (numbers only).

    >>> parse_params(["K=2", "T=1e-3", "b=0.01822"])
    {'K': 2, 'T': 1/1000, 'b': 911/50000}
    """
    out: dict[str, sp.Rational] = {}
    for name, value in param_items(items).items():
        try:
            out[name] = exact(value)
        except LimitError as err:     # "number: a number of ... digits ..." named by its option
            raise LimitError(f"--param {name}: {str(err).split(': ', 1)[-1]}") from None
        except (ValueError, ZeroDivisionError) as err:
            raise InputFormatError(f"--param {name}: {value!r} is not a number") from err
    return out


# ---------------------------------------------------------------------------------------------
# output files
# ---------------------------------------------------------------------------------------------


def add_output_option(parser: argparse.ArgumentParser, default: str | None = "-") -> None:
    parser.add_argument("--output", "-o", metavar="FILE", default=default,
                        help="write the report to FILE ('-', the default, is standard output)")


def check_output(path: str | None, option: str, suffixes: tuple[str, ...] = (), inputs: Any = ()) -> None:
    """Fail before any work if ``path`` cannot be an output: a wrong suffix, a directory, a
    missing folder (none is created), a parent that is a file, a read-only file or folder, or
    one of the command's ``inputs``. ``-`` (standard output) is always fine.

    >>> check_output("-", "--csv"); check_output("out.csv", "--csv", (".csv",))
    >>> check_output("out.txt", "--plot", (".png", ".pdf", ".svg"))
    Traceback (most recent call last):
    ...
    hapticproof.core.files.OutputError: --plot out.txt: the file name must end in .png, .pdf or .svg
    """
    from hapticproof.core.files import check_output as check

    check(path, option, suffixes, [inputs] if isinstance(inputs, str) else list(inputs or ()))


def input_files(args: argparse.Namespace) -> list[str]:
    """The files a command reads (an output may not be one of them)."""
    out: list[str] = []
    for name in ("scene", "matrix", "from_audit", "report"):
        value = getattr(args, name, None)
        if isinstance(value, str):
            out.append(value)
    out += [p for p in getattr(args, "paper", None) or [] if isinstance(p, str)]
    return out


def write_text(path: str | Path, text: str) -> Path | None:
    """Write ``text`` to ``path`` (``-``: standard output, returns ``None``): whole or not at
    all (a temporary file beside it, renamed when complete); no folder is created."""
    from hapticproof.core.files import write_atomic

    if str(path) == "-":
        sys.stdout.write(text if text.endswith("\n") else text + "\n")
        return None
    return write_atomic(path, text)


def write_output(path: str | None, text: str) -> None:
    """Standard output for ``None``/``-``, else the file (and ``wrote FILE`` on standard error)."""
    written = write_text("-" if path is None else path, text)
    if written is not None:
        print(f"wrote {written}", file=sys.stderr)


# ---------------------------------------------------------------------------------------------
# scene options: the fields of a scene file
# ---------------------------------------------------------------------------------------------


def add_scene_options(parser: argparse.ArgumentParser, system: str, *, stability: bool = False) -> None:
    """The options of ``system`` that are fields of a scene file (same names, same meaning)."""
    from hapticproof.systems.discretize import METHODS
    from hapticproof.systems.singleuser import APPROXIMATIONS

    parser.add_argument("--scene", metavar="FILE",
                        help="read the scene from a scene file (TOML; - for standard input); options given "
                        "here override its fields and --param adds to its [params]")
    if system in ("single-user", "multi-user"):
        parser.add_argument("--approximation", choices=APPROXIMATIONS, default=None,
                            help="HVE model: approximation of X_h = Z{v_h/s} (default forward)")
    if system == "single-user":
        parser.add_argument("--environment", "--controller", dest="environment", metavar="H",
                            help="the virtual environment H(z), e.g. 'K + B*(z-1)/(T*z) + M*(z-1)**2/(T**2*z**2)' "
                            "(default: the wall K + B*(z-1)/(T*z)), or H(s) with --discretize; any parameter "
                            "names; decimals are exact")
    if system == "teleoperator":
        parser.add_argument("--controller", metavar="C",
                            help="'pd' (eq. 33, default), 'filtered-pd' (derivative low-pass with pole a), C(z) "
                            "in z, or C(s) in s with --discretize (e.g. 'K_p + K_i/s + K_d*s/(tau*s + 1)')")
    if system in ("single-user", "teleoperator"):
        parser.add_argument("--discretize", choices=METHODS, default=None,
                            help="make a continuous design in s discrete: forward/backward Euler, tustin "
                            "(bilinear), zoh (step invariant) or matched (pole-zero)")
    if system == "multi-user":
        parser.add_argument("--users", type=int, default=None, help="number of users m (default 2)")
        parser.add_argument("--graph", default=None, metavar="GRAPH",
                            help="coupling graph: complete (default), path, star, ring, or edges like 1-2,2-3")
        parser.add_argument("--uniform", action="store_true", default=None,
                            help="one symbol per group for all users: b, K_0, B_0, K, B, z_a (else per-user "
                            "b_i, K_0i, B_0i, K_ij, B_ij, z_ai, which the group names set all at once). Delays "
                            "may still differ per user; the closed form by modes needs equal delays, and "
                            "unequal ones need numbers for a decision")
    if system != "network":
        delay_help = {"single-user": "n = t_d/T in samples, or 'n' for a symbolic delay (default 0)",
                      "multi-user": "n = t_d/T for every user, or one per user: n_1,...,n_m (default 0)",
                      "teleoperator": "communication delay in samples (stability boundary only; default 0)"}[system]
        parser.add_argument("--delay", default=None, help=delay_help)
    if system in ("single-user", "multi-user"):
        parser.add_argument("--active", action="store_true", default=None,
                            help="include the operator's shortage of passivity z_a (as a symbol, or set it with "
                            "--param z_a=VALUE)")
    if system != "network":
        parser.add_argument("--operator", metavar="Z_h(s)",
                            help="the operator's impedance, e.g. '-z_a + 1/s' (stability boundary; for passivity "
                            "its shortage of passivity is z_a unless z_a is given)" +
                            ("; teleoperator: the master's termination, 'free' or 'clamped'" if system == "teleoperator" else ""))
    if system == "teleoperator":
        parser.add_argument("--environment", metavar="Z_e(s)",
                            help="the slave's termination: an impedance in s, 'free' (default) or 'clamped' "
                            "(stability boundary only)")
    if system == "network":
        parser.add_argument("--matrix", metavar="FILE", help="impedance matrix file (text or .json)")
        parser.add_argument("--ports", metavar="SIZES", help="port sizes, e.g. 3,3 (default: scalar ports)")
    add_param_option(parser)


_FIELDS = ("approximation", "environment", "controller", "discretize", "delay", "users", "graph", "uniform",
           "active", "operator", "matrix", "ports")


def scene_from_args(args: argparse.Namespace, system: str) -> Any:
    """The scene the options describe: the scene file (if any), its fields overridden by the
    options given, ``--param`` added to its parameters."""
    from hapticproof.systems.scene import Scene
    from hapticproof.systems.scene import read_matrix, read_scene

    fields: dict[str, Any] = {}
    params: dict[str, Any] = {}
    for option in ("output", "csv", "json", "plot"):     # an output may not replace an input
        if isinstance(getattr(args, option, None), str):
            check_output(getattr(args, option), f"--{option}", inputs=input_files(args))
    if getattr(args, "scene", None):
        base = read_scene(args.scene)
        if base.system != system:
            raise InputFormatError(f"{args.scene} describes a {base.system} scene, not {system}")
        fields = {name: getattr(base, name) for name in _FIELDS}
        params = dict(base.params)
    for name in _FIELDS:
        value = getattr(args, name, None)
        if value is not None:
            fields[name] = value
    if system == "network" and isinstance(getattr(args, "matrix", None), str):
        rows, ports = read_matrix(args.matrix)
        fields["matrix"] = rows
        if ports and getattr(args, "ports", None) is None:
            fields["ports"] = ports
    if isinstance(fields.get("ports"), str):
        try:
            fields["ports"] = [int(p) for p in fields["ports"].split(",")]
        except ValueError:
            raise InputFormatError(f"--ports expects sizes like 3,3, got {fields['ports']!r}") from None
    if system == "network" and fields.get("matrix") is None:
        raise InputFormatError("derive network needs --matrix FILE (or a scene file with a matrix)")
    params.update(param_items(getattr(args, "param", []) or []))
    fields = {k: v for k, v in fields.items() if v is not None}
    return Scene(system, **fields, params=params)
