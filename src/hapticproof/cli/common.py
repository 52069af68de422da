"""Helpers shared by the subcommands: scene options (one set for ``derive`` and ``boundary``,
the fields of a scene file), ``--param NAME=VALUE`` parsing and output files (``-`` is
standard output everywhere, and an output is checked before any work starts)."""

from __future__ import annotations

import argparse
import sys
from pathlib import Path
from typing import TYPE_CHECKING, Any

from hapticproof.core.errors import InputFormatError
from hapticproof.core.limits import LimitError

if TYPE_CHECKING:       # SymPy is loaded by the commands that compute, not by --help or --version
    import sympy as sp

__all__ = ["parse_params", "param_items", "add_param_option", "add_role_option", "role_items", "write_text", "add_output_option", "check_output",
           "write_output", "add_scene_options", "scene_from_args", "add_any_scene_options", "scene_from_any_args",
           "build_model", "refuse", "input_files"]


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


def add_role_option(parser: argparse.ArgumentParser, system: str | None = None) -> None:
    """``--role ROLE=NAME``: the ``roles`` of the scene (a scene file's ``[roles]`` table)."""
    from hapticproof.systems.roles import ROLES

    systems = [system] if system else [s for s in ROLES if ROLES[s]]
    fields = list(dict.fromkeys(f for s in systems for f in ROLES[s]))
    defaults = {f: ROLES[s][f].default for s in systems for f in ROLES[s]}
    parser.add_argument(
        "--role",
        action="append",
        default=[],
        metavar="ROLE=NAME",
        help="name the parameter that plays a role of the system (default name in parentheses): "
        + ", ".join(f"{f} ({defaults[f]})" for f in fields)
        + "; e.g. --role period=Ts makes Ts the sampling period everywhere (--range, --delay-margin, "
        "boundaries, maps)" + ("; m users: a group name or one name per user, NAME_1,...,NAME_m"
                               if system in (None, "multi-user") else "") + "; repeat for several",
    )


def role_items(items: list[str]) -> dict[str, str | list[str]]:
    """``["period=Ts", "device_damping=c_1,c_2"]`` -> ``{"period": "Ts", "device_damping": ["c_1", "c_2"]}``.

    >>> role_items(["period=Ts", "device_damping = c_1, c_2"])
    {'period': 'Ts', 'device_damping': ['c_1', 'c_2']}
    """
    out: dict[str, str | list[str]] = {}
    for item in items:
        field, sep, value = item.partition("=")
        field = field.strip()
        if not sep or not field or not value.strip():
            raise InputFormatError(f"--role expects ROLE=NAME, got {item!r}")
        out[field] = [v.strip() for v in value.split(",")] if "," in value else value.strip()
    return out


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
    from hapticproof.core.evidence import exact

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
    """Write ``text`` to ``path`` (``-``: standard output, returns ``None``) with the one output
    writer (:func:`hapticproof.core.files.write_output`): whole or not at all, no link followed,
    no folder created."""
    from hapticproof.core.files import write_output as write

    return write(path, text)


def write_output(path: str | None, text: str) -> None:
    """Standard output for ``None``/``-``, else the file (and ``wrote FILE`` on standard error)."""
    written = write_text("-" if path is None else path, text)
    if written is not None:
        print(f"wrote {written}", file=sys.stderr)


def refuse(args: argparse.Namespace, message: str, data: dict | None = None) -> None:
    """A question with no exact answer (a user's choice causes it): with ``--format json`` a JSON
    document ``{"error": message, ...data}`` on the output, then always the one error line and
    exit 2 (raises :class:`~hapticproof.core.errors.SceneError`)."""
    import json

    from hapticproof.core.errors import SceneError

    if getattr(args, "format", None) == "json":
        write_text(getattr(args, "output", None) or "-", json.dumps({"error": message, **(data or {})}, indent=2))
    raise SceneError(message)


# ---------------------------------------------------------------------------------------------
# scene options: the fields of a scene file
# ---------------------------------------------------------------------------------------------


def add_scene_options(parser: argparse.ArgumentParser, system: str, *, stability: bool = False) -> None:
    """The options of ``system`` that are fields of a scene file (same names, same meaning)."""
    from hapticproof.systems.choices import APPROXIMATIONS, METHODS

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
    else:
        add_role_option(parser, system)
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
    roles: dict[str, Any] = {}
    for option in ("output", "csv", "json", "plot"):     # an output may not replace an input
        if isinstance(getattr(args, option, None), str):
            check_output(getattr(args, option), f"--{option}", inputs=input_files(args))
    if getattr(args, "scene", None):
        base = read_scene(args.scene, system=system)
        if base.system != system:
            raise InputFormatError(f"{args.scene} describes a {base.system} scene, not {system}")
        fields = {name: getattr(base, name) for name in _FIELDS}
        params = dict(base.params)
        roles = dict(base.roles)
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
    roles.update(role_items(getattr(args, "role", []) or []))
    fields = {k: v for k, v in fields.items() if v is not None}
    return Scene(system, **fields, params=params, roles=roles)


def build_model(scene: Any, args: argparse.Namespace) -> Any:
    """``scene.build()``; a mistake about a parameter of the ``--scene`` file names its line."""
    import re

    from hapticproof.core.errors import SceneError

    try:
        return scene.build()
    except SceneError as err:
        path = getattr(args, "scene", None)
        named = re.match(r"(?:unknown )?parameter '([^']+)'", str(err))
        if not path or path == "-" or named is None or named.group(1) in param_items(getattr(args, "param", []) or []):
            raise
        from hapticproof.systems.scene import SceneFileError, line_of

        try:
            text = Path(path).read_text(encoding="utf-8")
        except OSError:
            raise err from None
        line = line_of(text, named.group(1), "params")
        raise SceneFileError(f"{path}:{line}: {err}" if line else f"{path}: {err}") from None


# ---------------------------------------------------------------------------------------------
# the scene options of every system at once (boundary, map: the system is an argument)
# ---------------------------------------------------------------------------------------------

#: The systems ``boundary`` and ``map`` take.
LOOP_SYSTEMS = ("single-user", "multi-user", "teleoperator")


def add_any_scene_options(parser: argparse.ArgumentParser) -> None:
    """The scene options of ``derive`` for every system but networks (``boundary``, ``map``):
    the same names and meanings; a field that does not apply to the system is an error."""
    from hapticproof.systems.choices import APPROXIMATIONS, METHODS

    parser.add_argument("--scene", metavar="FILE", help="read the scene from a scene file (TOML; - for standard "
                        "input); options given here override its fields and --param adds to its [params]")
    parser.add_argument("--approximation", choices=APPROXIMATIONS, default=None,
                        help="HVE model: approximation of X_h = Z{v_h/s} (default forward; passivity)")
    parser.add_argument("--environment", "--H", dest="environment",
                        help="single-user: the virtual environment H(z) (or H(s) with --discretize; default "
                        "K + B*(z-1)/(T*z)); teleoperator: the slave's termination Z_e(s), 'free' or 'clamped'")
    parser.add_argument("--controller", help="teleoperator: 'pd', 'filtered-pd', C(z) or C(s) with --discretize; "
                        "single-user: a synonym of --environment")
    parser.add_argument("--discretize", choices=METHODS, default=None, help="make a continuous design discrete")
    parser.add_argument("--operator", help="operator impedance Z_h(s), e.g. '-z_a + 1/s' "
                        "(teleoperator: master termination; 'clamped' allowed)")
    parser.add_argument("--delay", default=None, help="delay in samples (multi-user: one per user, n_1,...,n_m)")
    parser.add_argument("--users", type=int, default=None, help="multi-user: number of users (default 2)")
    parser.add_argument("--graph", default=None, help="multi-user: coupling graph (complete, path, star, ring, 1-2,2-3)")
    parser.add_argument("--uniform", action="store_true", default=None,
                        help="multi-user: one symbol per group (b, K_0, B_0, K, B); else per-user names")
    parser.add_argument("--active", action="store_true", default=None,
                        help="include the operator's shortage of passivity z_a (single- and multi-user)")
    add_role_option(parser)
    add_param_option(parser)


def scene_from_any_args(args: argparse.Namespace, systems: tuple[str, ...] = LOOP_SYSTEMS,
                        default: str | None = None) -> Any:
    """The scene of :func:`add_any_scene_options` and the positional ``args.system`` (else the
    scene file's, else ``default``)."""
    from hapticproof.systems.scene import Scene, read_scene

    fields: dict[str, Any] = {}
    params: dict[str, Any] = {}
    roles: dict[str, Any] = {}
    system = getattr(args, "system", None)
    if getattr(args, "scene", None):
        base = read_scene(args.scene, system=system)
        if system is not None and base.system != system:
            raise InputFormatError(f"{args.scene} describes a {base.system} scene, not {system}")
        system = base.system
        fields = {name: getattr(base, name) for name in _FIELDS if name not in ("matrix", "ports")}
        params = dict(base.params)
        roles = dict(base.roles)
    system = system or default
    if system is None:
        raise InputFormatError(f"name the system ({', '.join(systems)}) or give --scene FILE")
    if system not in systems:
        raise InputFormatError(f"this command applies to {', '.join(systems)} scenes, not {system}")
    for name in _FIELDS:
        value = getattr(args, name, None)
        if value is not None:
            fields[name] = value
    params.update(param_items(getattr(args, "param", []) or []))
    roles.update(role_items(getattr(args, "role", []) or []))
    return Scene(system, **{k: v for k, v in fields.items() if v is not None}, params=params, roles=roles)
