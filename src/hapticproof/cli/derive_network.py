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

(a plain list of rows is accepted too). Entries are rational expressions in ``s`` (``*`` for
products, exact decimals, no functions: ``sin(s)`` or a ``z`` is an error) and named parameters,
fixed with ``--param NAME=VALUE``; a scene file (``--scene``, ``system = "network"``) may hold
the matrix itself or name the file; with free parameters only the symmetrization
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
from pathlib import Path
from typing import Any

import sympy as sp

from hapticproof.report import latex as tex
from hapticproof.cli.common import add_output_option, build_model, add_scene_options, check_output, scene_from_args, write_output
from hapticproof.core.errors import InputFormatError
from hapticproof.core.evidence import Decision, to_jsonable
from hapticproof.core.symbols import s  # noqa: F401 - the variable of the matrix entries

__all__ = ["register", "run", "read_matrix", "parse_entry"]

def parse_entry(text: str, where: str = "") -> sp.Expr:
    """One matrix entry: a rational expression in ``s`` and named parameters (the one reader,
    :func:`hapticproof.core.expr.read_expression`: exact decimals, ``*`` for products, no functions).

    >>> parse_entry("9/(s+3)"), parse_entry("2*s^2 + k")
    (9/(s + 3), k + 2*s**2)
    >>> parse_entry("sin(s)", "z.txt:1, entry 1")
    Traceback (most recent call last):
    ...
    hapticproof.core.expr.ExpressionError: z.txt:1, entry 1: unknown function 'sin' at position 0 in 'sin(s)' (a rational expression has numbers, names, + - * / ^ and parentheses)
    """
    from hapticproof.core.expr import read_expression

    return read_expression(str(text), "s", where=where)


def read_matrix(path: str | Path) -> tuple[sp.Matrix, tuple[int, ...] | None]:
    """Read the documented text or JSON matrix format; returns ``(Z, ports or None)``."""
    from hapticproof.systems.scene import read_matrix as read_entries

    rows, ports = read_entries(path)
    table = [[parse_entry(e, f"{path}: row {i + 1}, entry {j + 1}") for j, e in enumerate(r)] for i, r in enumerate(rows)]
    if any(len(r) != len(table) for r in table):
        raise InputFormatError(f"{path}: the matrix must be square (found rows of lengths {[len(r) for r in table]})")
    return sp.Matrix(table), ports


def register(systems: argparse._SubParsersAction, line: str = "") -> None:
    parser = systems.add_parser(
        "network",
        help=line,
        description=__doc__.split("\n\n", 1)[1],
        formatter_class=argparse.RawDescriptionHelpFormatter,
    )
    add_scene_options(parser, "network")
    parser.add_argument("--format", choices=("text", "json", "latex"), default="text",
                        help="text (default), json or latex (a complete document)")
    parser.add_argument("--fragment", action="store_true",
                        help="with --format latex: only the displays (amsmath), not a complete document")
    parser.add_argument("--no-search", action="store_true", help="do not search destabilizing terminations")
    parser.add_argument("--deadline", default="10", metavar="SECONDS",
                        help="time limit of the termination search (default 10 s); it then reports what it tried")
    add_output_option(parser)
    parser.set_defaults(handler=run)


def _deadline(text: str) -> float:
    try:
        value = float(text)
    except ValueError:
        raise InputFormatError(f"--deadline expects a number of seconds, got {text!r}") from None
    if not value > 0 or value == float("inf"):
        raise InputFormatError(f"--deadline must be a positive number of seconds, got {text!r}")
    return value


def analyse(Z: sp.Matrix, ports: tuple[int, ...] | None, search: bool = True, deadline: float = 10.0,
            progress: Any = None) -> dict[str, Any]:
    """The report as data (used by all formats). ``conditions`` holds every decided condition
    with its certificates (what ``hapticproof check`` re-verifies)."""
    from hapticproof.analysis.networks import absolute_stability, llewellyn, port_blocks, symmetrization_conditions
    from hapticproof.exact.rationalmatrix import RationalMatrix, pole_report

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
    verdict = absolute_stability(R, ports, search=search, deadline=deadline, progress=progress)
    pr = verdict.positive_real
    rep = pole_report(R)
    out["poles"] = {"rhp": [f"{r:.6g}" for _, r in rep.rhp], "imaginary_axis": [(p.label(), m) for p, m in rep.axis],
                    "pole_at_infinity_order": rep.improper}
    decided = [{"name": "Z positive real (Definition 3)", **pr.to_json()}]
    from hapticproof.core.evidence import to_jsonable
    from hapticproof.exact.judge import judged_definition

    # the original Z(s) for the definition-level judge (and 'check'): proper up to a simple
    # pole at infinity, no pole in Re s > 0, Z + Z^H >= 0 at points of the closed right half plane
    definition = judged_definition("halfplane", pr.decision.value, R.transfer_json(),
                                   to_jsonable(pr.evidence.witness) if pr.evidence.witness else None)
    if definition is not None:
        decided[0]["definition"] = definition
        if not definition["judged"]["ok"]:     # the decision and the definition disagree
            decided[0]["decision"] = "undecided"
            decided[0]["reason"] = (f"the definition-level judge disagrees with '{pr.decision.value}' "
                                    f"({definition['judged']['reason']}); the decision said: {pr.reason}")
    out["positive_real"] = {"decision": decided[0]["decision"], "reason": decided[0]["reason"]}
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
    # the decision that settles it, with its certificates (what `hapticproof check` re-verifies)
    basis = {"positive real": pr, "open-circuit instability": pr, "Llewellyn": verdict.llewellyn,
             "Youla symmetrization": verdict.zprime}.get(verdict.method)
    if basis is not None:
        entry["rests_on"] = basis.to_json()
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


def _in_names(value: Any, names: Any) -> Any:
    """The reasons, condition names and shown witnesses of a numeric network's report in the
    scene's naming (the certificates, read back by ``check``, keep the toolkit's own variable names)."""
    if isinstance(value, dict):
        out = {}
        for key, item in value.items():
            if key == "evidence" and isinstance(item, dict) and isinstance(item.get("witness"), dict):
                out[key] = {**item, "witness": names.witness(item["witness"])}     # shown: the scene's names
            elif key in ("certificate", "definition", "evidence") and isinstance(item, dict):
                out[key] = item
            elif key == "witness" and isinstance(item, dict):
                out[key] = names.witness(item)
            elif key in ("reason", "name", "summary") and isinstance(item, str):
                out[key] = names.words(item)
            elif key == "conditions" and isinstance(item, dict):
                out[key] = {names.words(k): v for k, v in item.items()}
            else:
                out[key] = _in_names(item, names)
        return out
    if isinstance(value, list):
        return [_in_names(item, names) for item in value]
    return value


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
    lines.append("Youla symmetrization conditions (A: triple products, B: port blocks symmetric): "
                 + (f"{len(conds)} not identically satisfied" if conds else "all hold identically"))
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
    check_output(args.output, "--output")
    spec = scene_from_args(args, "network")
    Z = build_model(spec, args)
    ports = spec.ports
    import sys

    from hapticproof.analysis.networks import port_blocks
    from hapticproof.cli.terminal import progress_bar

    if ports is not None:
        port_blocks(Z.rows, ports)

    bar = progress_bar(sys.stderr, "termination search")     # a terminal only
    report = analyse(Z, ports, search=not args.no_search, deadline=_deadline(args.deadline), progress=bar)
    if bar is not None:
        bar.clear()
    from hapticproof.systems.naming import scene_naming

    names = scene_naming(spec)
    if not names.is_default and "note" not in report:
        # a numeric network's reasons hold numbers and the toolkit's words only (x = w^2, w): they
        # speak the scene's names when its parameters take those (a parameter x = 9, say)
        report = {**_in_names(report, names), "notation": names.changed()}
    if args.format == "json":
        text = json.dumps(names.claims(to_jsonable(report)), indent=2)
    elif args.format == "latex":
        text = _latex(report, args.fragment)
    else:
        text = _text(report)
    write_output(args.output, text)
    return 0
