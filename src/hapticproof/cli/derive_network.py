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

The report: poles; positive realness (Definition 3: every condition with its decision and a
certificate; a disproof gives an exact frequency); Llewellyn's criterion for scalar 2-ports
(with the frequency where it is tightest); Youla's symmetrization conditions (A, B), the
reciprocal ``Z'`` and its positive realness; the absolute-stability verdict (a positive-real
``Z`` is absolutely stable, decided first), with verified destabilizing terminations when
potentially unstable. The termination search ends after ``--deadline`` seconds (default 10)
and then says what it tried; ``--no-search`` skips it. ``--format text|json|latex``; the JSON
report lists every decided condition under ``conditions`` with its certificates, so that
``hapticproof check REPORT.json`` re-verifies it.
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
from hapticproof.networks import absolute_stability, llewellyn, port_blocks, symmetrization_conditions
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
    parser.add_argument("--format", choices=("text", "json", "latex"), default="text")
    parser.add_argument("--no-search", action="store_true", help="do not search destabilizing terminations")
    parser.add_argument("--deadline", default="10", metavar="SECONDS",
                        help="time limit of the termination search (default 10 s); it then reports what it tried")
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


def _deadline(text: str) -> float:
    try:
        value = float(text)
    except ValueError:
        raise InputFormatError(f"--deadline expects a number of seconds, got {text!r}") from None
    if not value > 0 or value == float("inf"):
        raise InputFormatError(f"--deadline must be a positive number of seconds, got {text!r}")
    return value


def analyse(Z: sp.Matrix, ports: tuple[int, ...] | None, search: bool = True, deadline: float = 10.0) -> dict[str, Any]:
    """The report as data (used by all formats). ``conditions`` holds every decided condition
    with its certificates (what ``hapticproof check`` re-verifies)."""
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
    verdict = absolute_stability(R, ports, search=search, deadline=deadline)
    pr = verdict.positive_real
    rep = pole_report(R)
    out["poles"] = {"rhp": [f"{r:.6g}" for _, r in rep.rhp], "imaginary_axis": [(p.label(), m) for p, m in rep.axis],
                    "pole_at_infinity_order": rep.improper}
    decided = [{"name": "Z positive real (Definition 3)", **pr.to_json()}]
    out["positive_real"] = {"decision": pr.decision.value, "reason": pr.reason}
    blocks = port_blocks(n, ports)
    if n == 2 and len(blocks) == 2:
        result = verdict.llewellyn if verdict.llewellyn is not None else llewellyn(R)
        decided.append({"name": "Llewellyn's criterion", **result.to_json()})
        out["llewellyn"] = {"decision": result.decision.value, "reason": result.reason,
                            "conditions": {c.name: c.decision.value for c in result.conditions},
                            "tightest_x": str(result.tightest.argmin) if result.tightest else None,
                            "eta_min": result.eta_min}
    if verdict.symmetrization is not None:
        sym = verdict.symmetrization
        out["symmetrization"] = {"decision": sym.symmetrizable.value, "reason": sym.reason}
        if sym.symmetrizable == Decision.PROVED:
            out["symmetrization"]["Z_prime"] = sym.zprime()
    if verdict.zprime is not None:
        decided.append({"name": "Z' positive real (Youla)", **verdict.zprime.to_json()})
        out["zprime_positive_real"] = {"decision": verdict.zprime.decision.value, "reason": verdict.zprime.reason}
    summary = {"decision": verdict.decision.value, "method": verdict.method, "reason": verdict.reason}
    entry = {"name": "absolute stability", **summary, "evidence": {"method": verdict.evidence.method}}
    if verdict.certificate is not None:
        entry["certificate"] = verdict.certificate.to_json()
        summary["certificate"] = {k: v for k, v in entry["certificate"].items() if k in ("terminations", "rhp_roots", "strategy")}
    if verdict.search is not None:
        entry["search"] = verdict.search.to_json()
        summary["search"] = verdict.search.summary()
    decided.append(entry)
    out["absolute_stability"] = summary
    out["conditions"] = decided
    return out


def _condition_lines(entry: dict[str, Any], indent: str = "  ") -> list[str]:
    lines = []
    for cond in entry.get("conditions", []):
        text = f"{indent}{cond['name']}: {cond['decision']}"
        if cond["decision"] != "proved" or len(cond["reason"]) < 100:
            text += f" ({cond['reason']})"
        lines.append(text)
    return lines


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
    entries = {e["name"]: e for e in report["conditions"]}
    pr = entries["Z positive real (Definition 3)"]
    lines.append(f"positive real (Definition 3): {pr['decision']} -- {pr['reason']}")
    lines += _condition_lines(pr)
    if "Llewellyn's criterion" in entries:
        ll = entries["Llewellyn's criterion"]
        lines.append(f"Llewellyn: {ll['decision']} -- {ll['reason']}")
        lines += _condition_lines(ll)
    if "symmetrization" in report:
        sym = report["symmetrization"]
        lines.append(f"symmetrization: {sym['decision']} -- {sym['reason']}")
        if "Z_prime" in sym:
            lines.append(f"  Z' = {sp.sstr(sym['Z_prime'])}")
    if "Z' positive real (Youla)" in entries:
        zp = entries["Z' positive real (Youla)"]
        lines.append(f"Z' positive real: {zp['decision']}")
        lines += _condition_lines(zp)
    ab = entries["absolute stability"]
    word = {"proved": "absolutely stable", "disproved": "potentially unstable", "undecided": "undecided"}[ab["decision"]]
    lines += ["", f"absolute stability: {word} ({ab['method']}) -- {ab['reason']}"]
    if "certificate" in ab:
        cert = ab["certificate"]
        lines.append(f"  destabilizing passive terminations (RHP zeros of det(Z + T) at {cert['rhp_roots']}, verified exactly):")
        for k, T in enumerate(cert["terminations"], 1):
            lines.append(f"    T_{k} = {T}")
    if "search" in ab:
        lines.append(f"  termination search: {ab['search']['summary']}")
    return "\n".join(lines)


def _latex(report: dict[str, Any]) -> str:
    sections = [("Impedance matrix", tex.display(tex.to_latex(report["matrix"])))]
    conds = report["symmetrization_conditions"]
    body = "\n".join(tex.display(tex.to_latex(c["equation_in_s"])) for c in conds) or "All hold identically."
    sections.append(("Symmetrization conditions (A, B)", body))
    if "note" not in report:
        pr = report["positive_real"]
        sections.append(("Positive realness", tex.escape_text(f"{pr['decision']}: {pr['reason']}")))
        if "llewellyn" in report:
            sections.append(("Llewellyn", tex.escape_text(report["llewellyn"]["reason"])))
        sym = report.get("symmetrization", {})
        if "Z_prime" in sym:
            sections.append(("Reciprocal equivalent Z'", tex.display(tex.to_latex(sym["Z_prime"]))))
        ab = report["absolute_stability"]
        sections.append(("Absolute stability", tex.escape_text(f"{ab['decision']} ({ab['method']}): {ab['reason']}")))
    return tex.document("n-port network analysis", sections)


def run(args: argparse.Namespace) -> int:
    Z, file_ports = read_matrix(args.matrix)
    params = parse_params(args.param)
    if params:
        names = {str(x): x for x in Z.free_symbols}
        unknown = sorted(set(params) - set(names))
        if unknown:
            raise InputFormatError(f"unknown parameter(s) {unknown}; the matrix has {sorted(set(names) - {'s'})}")
        Z = Z.subs({names[k]: v for k, v in params.items()})
    ports = _ports(args.ports, file_ports, Z.rows)
    report = analyse(Z, ports, search=not args.no_search, deadline=_deadline(args.deadline))
    if args.format == "json":
        print(json.dumps(to_jsonable(report), indent=2))
    elif args.format == "latex":
        print(_latex(report))
    else:
        print(_text(report))
    return 0
