r"""``hapticproof derive network --matrix FILE``: passivity and absolute stability of an n-port.

The matrix file holds the impedance matrix ``Z(s)`` (``F = Z V``) of an n-port, entries rational
functions of ``s`` with rational coefficients, in one of two formats:

Text (``.txt`` or anything not ending in ``.json``)::

    # 2-port of eq. (5) of the 3-DOF bilateral paper; one row per line,
    # entries separated by commas; '#' starts a comment; ^ or ** for powers
    9/(s+3), -1/(s+1)
    -1/(s+1), 1/(s+3)

JSON (``.json``)::

    {"matrix": [["9/(s+3)", "-1/(s+1)"], ["-1/(s+1)", "1/(s+3)"]], "ports": [1, 1]}

(a plain list of rows is accepted too). Entries may use named parameters (letters, digits,
underscores), fixed with ``--param NAME=VALUE``; with free parameters only the symmetrization
conditions are derived (symbolically). ``--ports 3,3`` groups the ports (a 2-port with 3-DOF
ports terminated by full 3x3 impedances); the default is scalar ports.

The report: poles; positive realness (Definition 3, exact, with a frequency witness);
Llewellyn's criterion for scalar 2-ports (with the frequency where it is tightest); Youla's
symmetrization conditions (A, B) and the reciprocal ``Z'``; the absolute-stability verdict,
with verified destabilizing terminations when potentially unstable (``--no-search`` skips the
search). ``--format text|json|latex``.
"""

from __future__ import annotations

import argparse
import json
import re
from pathlib import Path
from typing import Any

import sympy as sp
from sympy.parsing.sympy_parser import (
    convert_xor,
    implicit_multiplication_application,
    parse_expr,
    standard_transformations,
)

from hapticproof import latex as tex
from hapticproof.cli._common import add_param_option, parse_params
from hapticproof.errors import InputFormatError
from hapticproof.evidence import Decision, to_jsonable
from hapticproof.networks import absolute_stability, llewellyn, port_blocks, positive_real, symmetrization_conditions
from hapticproof.rationalmatrix import RationalMatrix, pole_report
from hapticproof.symbols import s

__all__ = ["register", "run", "read_matrix", "parse_entry"]

_ENTRY = re.compile(r"^[0-9A-Za-z_+\-*/^(). ]+$")
_NAME = re.compile(r"[A-Za-z_][A-Za-z0-9_]*")
_TRANSFORMS = standard_transformations + (implicit_multiplication_application, convert_xor)


def parse_entry(text: str, where: str = "") -> sp.Expr:
    """One matrix entry: a rational expression in ``s`` and named parameters (nothing else).

    >>> parse_entry("9/(s+3)"), parse_entry("2s^2 + k")
    (9/(s + 3), k + 2*s**2)
    """
    text = text.strip()
    if not text or not _ENTRY.match(text):
        raise InputFormatError(f"{where}: {text!r} is not a rational expression in s")
    names = set(_NAME.findall(text))
    if any(n.startswith("_") for n in names):
        raise InputFormatError(f"{where}: names may not start with '_': {text!r}")
    local = {n: sp.Symbol(n, real=True) for n in names if n != "s"}
    local["s"] = s
    try:
        expr = parse_expr(text, local_dict=local, global_dict={"Integer": sp.Integer, "Rational": sp.Rational,
                                                                "Float": sp.Float, "Symbol": sp.Symbol},
                          transformations=_TRANSFORMS)
    except Exception as err:  # noqa: BLE001 - any parse failure is the user's input
        raise InputFormatError(f"{where}: cannot read {text!r} ({err.__class__.__name__})") from None
    expr = sp.nsimplify(expr, rational=True)
    if not isinstance(expr, sp.Expr) or not expr.is_rational_function(s):
        raise InputFormatError(f"{where}: {text!r} is not a rational function of s")
    return expr


def read_matrix(path: str | Path) -> tuple[sp.Matrix, tuple[int, ...] | None]:
    """Read the documented text or JSON matrix format; returns ``(Z, ports or None)``."""
    path = Path(path)
    try:
        content = path.read_text(encoding="utf-8")
    except OSError as err:
        raise InputFormatError(f"cannot read {path}: {err.strerror}") from None
    ports = None
    if path.suffix.lower() == ".json":
        try:
            data = json.loads(content)
        except json.JSONDecodeError as err:
            raise InputFormatError(f"{path}: invalid JSON ({err.msg} at line {err.lineno})") from None
        if isinstance(data, dict):
            rows, ports = data.get("matrix"), data.get("ports")
        else:
            rows = data
        if not isinstance(rows, list) or not all(isinstance(r, list) for r in rows):
            raise InputFormatError(f"{path}: expected a list of rows (or {{'matrix': [...]}})")
        table = [[parse_entry(str(e), f"{path}: row {i + 1}, column {j + 1}") for j, e in enumerate(r)] for i, r in enumerate(rows)]
    else:
        table = []
        for number, line in enumerate(content.splitlines(), 1):
            line = line.split("#", 1)[0].strip()
            if line:
                table.append([parse_entry(e, f"{path}:{number}, entry {k + 1}") for k, e in enumerate(line.split(","))])
    if not table:
        raise InputFormatError(f"{path}: no matrix rows")
    n = len(table)
    if any(len(r) != n for r in table):
        raise InputFormatError(f"{path}: the matrix must be square (found rows of lengths {[len(r) for r in table]})")
    return sp.Matrix(table), (tuple(int(p) for p in ports) if ports else None)


def register(systems: argparse._SubParsersAction) -> None:
    parser = systems.add_parser(
        "network",
        help="n-port networks: positive realness, Llewellyn, Youla symmetrization, absolute stability",
        description=__doc__.split("\n\n", 1)[1],
        formatter_class=argparse.RawDescriptionHelpFormatter,
    )
    parser.add_argument("--matrix", required=True, metavar="FILE", help="impedance matrix file (text or .json)")
    parser.add_argument("--ports", metavar="SIZES", help="port sizes, e.g. 3,3 (default: scalar ports)")
    parser.add_argument("--format", choices=("text", "json", "latex"), default="text",
                        help="text (default), json or latex (a complete document)")
    parser.add_argument("--fragment", action="store_true",
                        help="with --format latex: only the displays (amsmath), not a complete document")
    parser.add_argument("--no-search", action="store_true", help="do not search destabilizing terminations")
    add_param_option(parser)
    parser.set_defaults(handler=run)


def _ports(text: str | None, from_file, n: int) -> tuple[int, ...] | None:
    if text:
        try:
            ports = tuple(int(p) for p in text.split(","))
        except ValueError:
            raise InputFormatError(f"--ports expects sizes like 3,3, got {text!r}") from None
    else:
        ports = from_file
    port_blocks(n, ports)
    return ports


def analyse(Z: sp.Matrix, ports: tuple[int, ...] | None, search: bool = True) -> dict[str, Any]:
    """The report as data (used by all formats)."""
    n = Z.rows
    out: dict[str, Any] = {"size": n, "ports": list(ports) if ports else [1] * n, "matrix": Z}
    free = sorted(Z.free_symbols - {s}, key=str)
    conditions = symmetrization_conditions(Z, ports)
    out["symmetrization_conditions"] = [
        {"kind": c.kind, "indices": [i + 1 for i in c.indices], "equation_in_s": sp.Eq(sp.factor(c.expr), 0),
         "coefficients": c.coefficients()} for c in conditions]
    if free:
        out["free_parameters"] = [str(x) for x in free]
        out["note"] = "free parameters: only the symmetrization conditions are derived (fix them with --param)"
        return out
    R = RationalMatrix.from_sympy(Z)
    rep = pole_report(R)
    out["poles"] = {"rhp": [str(r) for _, r in rep.rhp], "imaginary_axis": [(p.label(), m) for p, m in rep.axis],
                    "pole_at_infinity_order": rep.improper}
    out["positive_real"] = positive_real(R).to_json()
    blocks = port_blocks(n, ports)
    if n == 2 and len(blocks) == 2:
        result = llewellyn(R)
        out["llewellyn"] = {"decision": result.decision.value, "reason": result.reason,
                            "conditions": {k: v.to_json() for k, v in result.conditions.items()},
                            "tightest_x": str(result.tightest.argmin) if result.tightest else None,
                            "eta_min": result.eta_min}
    verdict = absolute_stability(R, ports, search=search)
    out["absolute_stability"] = verdict.to_json()
    if verdict.symmetrization is not None:
        sym = verdict.symmetrization
        out["symmetrization"] = {"decision": sym.symmetrizable.value, "reason": sym.reason}
        if sym.symmetrizable == Decision.PROVED:
            out["symmetrization"]["Z_prime"] = sym.zprime()
    return out


def _text(report: dict[str, Any]) -> str:
    lines = [f"n-port: {report['size']} x {report['size']}, ports {report['ports']}", ""]
    conds = report["symmetrization_conditions"]
    lines.append(f"Youla symmetrization conditions (A: triple products, B: port blocks symmetric): "
                 f"{len(conds)} not identically satisfied")
    for c in conds:
        lines.append(f"  {c['kind']} {tuple(c['indices'])}: {sp.sstr(c['equation_in_s'].lhs)} = 0")
    if "note" in report:
        lines += ["", report["note"]]
        return "\n".join(lines)
    p = report["poles"]
    lines += ["", f"poles: RHP {p['rhp'] or 'none'}; imaginary axis {p['imaginary_axis'] or 'none'}; "
                  f"order at infinity {p['pole_at_infinity_order']}"]
    pr = report["positive_real"]
    lines.append(f"positive real (Definition 3): {pr['decision']} -- {pr['reason']}")
    if pr["hermitian"].get("evidence", {}).get("witness"):
        lines.append(f"  witness: {pr['hermitian']['evidence']['witness']}")
    if "llewellyn" in report:
        ll = report["llewellyn"]
        lines.append(f"Llewellyn: {ll['decision']} -- {ll['reason']}")
        for name, outcome in ll["conditions"].items():
            lines.append(f"  {name}: {outcome['decision']} ({outcome['reason']})")
    if "symmetrization" in report:
        sym = report["symmetrization"]
        lines.append(f"symmetrization: {sym['decision']} -- {sym['reason']}")
        if "Z_prime" in sym:
            lines.append(f"  Z' = {sp.sstr(sym['Z_prime'])}")
    ab = report["absolute_stability"]
    word = {"proved": "absolutely stable", "disproved": "potentially unstable", "undecided": "undecided"}[ab["decision"]]
    lines += ["", f"absolute stability: {word} ({ab['method']}) -- {ab['reason']}"]
    if "certificate" in ab:
        cert = ab["certificate"]
        lines.append(f"  destabilizing passive terminations (RHP zeros of det(Z + T) at {cert['rhp_roots']}):")
        for k, T in enumerate(cert["terminations"], 1):
            lines.append(f"    T_{k} = {T}")
    return "\n".join(lines)


def _latex(report: dict[str, Any], fragment: bool = False) -> str:
    """A complete document (or, with ``fragment``, the amsmath displays alone)."""
    items = [("impedance matrix", "Z(s) = " + tex.to_latex(report["matrix"]))]
    items += [(f"symmetrization condition {c['kind']} {tuple(c['indices'])}", tex.to_latex(c["equation_in_s"]))
              for c in report["symmetrization_conditions"]]
    sym = report.get("symmetrization", {})
    if "Z_prime" in sym:
        items.append(("reciprocal equivalent", "Z'(s) = " + tex.to_latex(sym["Z_prime"])))
    if fragment:
        return tex.derivation_fragment(items)
    notes = []
    if not report["symmetrization_conditions"]:
        notes.append(("symmetrization conditions (A, B)", "all hold identically"))
    if "note" in report:
        notes.append(("note", report["note"]))
    else:
        pr = report["positive_real"]
        notes.append(("positive realness", f"{pr['decision']}: {pr['reason']}"))
        if "llewellyn" in report:
            notes.append(("Llewellyn", report["llewellyn"]["reason"]))
        ab = report["absolute_stability"]
        notes.append(("absolute stability", f"{ab['decision']} ({ab['method']}): {ab['reason']}"))
    intro = tex.escape_text(f"{report['size']} x {report['size']} impedance matrix, ports {report['ports']}.")
    return tex.derivation_document("n-port network analysis", items, notes, intro=intro)


def run(args: argparse.Namespace) -> int:
    if args.fragment and args.format != "latex":
        raise InputFormatError("--fragment needs --format latex")
    Z, file_ports = read_matrix(args.matrix)
    params = parse_params(args.param)
    if params:
        names = {str(x): x for x in Z.free_symbols}
        unknown = sorted(set(params) - set(names))
        if unknown:
            raise InputFormatError(f"unknown parameter(s) {unknown}; the matrix has {sorted(set(names) - {'s'})}")
        Z = Z.subs({names[k]: v for k, v in params.items()})
    ports = _ports(args.ports, file_ports, Z.rows)
    report = analyse(Z, ports, search=not args.no_search)
    if args.format == "json":
        print(json.dumps(to_jsonable(report), indent=2))
    elif args.format == "latex":
        print(_latex(report, args.fragment))
    else:
        print(_text(report))
    return 0
