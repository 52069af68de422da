"""``hapticproof derive multi-user``: exact conditions of an m-user haptic virtual environment.

Examples::

    hapticproof derive multi-user --users 3
    hapticproof derive multi-user --users 2 --delay 2 --uniform --param B_0=0 --param B=0 --latex
    hapticproof derive multi-user --users 4 --param b=0.02 --param K_0=10 --param K=5 \\
        --param B_0=0 --param B=0 --param T=0.001 --format json

Parameters are symbolic unless fixed with ``--param``; per-user names are ``b_1``, ``K_01``,
``B_01``, ``z_a1``, ``K_12``, ``B_12`` ...; the group names ``b``, ``K_0``, ``B_0``, ``K``, ``B``,
``z_a`` set every member of the group (with ``--uniform`` they are the only names). ``--uniform``
is about the symbols, not the delays: ``--uniform --delay 1,2,5`` is a scene with one symbol per
group and unequal delays (no closed form; numbers give the exact decision).
"""

from __future__ import annotations

import argparse
import json
from typing import Any

import sympy as sp

from hapticproof.report import latex as tex
from hapticproof.cli.common import add_output_option, build_model, add_scene_options, check_output, scene_from_args, write_output
from hapticproof.cli.derive_single_user import add_design_options, design_answers
from hapticproof.core.errors import InputFormatError
from hapticproof.core.evidence import to_jsonable
from hapticproof.systems.multiuser import MultiUserScene, inverse_transfer_matrix
from hapticproof.analysis.multiuser import conditions, hermitian, positive_real, principal_minors, residues, sufficient_condition, worst_case

__all__ = ["register", "build_scene", "derive"]

COS = r"\cos(\omega T)"
GROUPS = {"b": "b", "K_0": "K0", "B_0": "B0", "z_a": "z_a", "K": "K", "B": "B"}


def register(systems: argparse._SubParsersAction) -> None:
    parser = systems.add_parser(
        "multi-user",
        help="m users coupled through a shared virtual environment (HVE paper, Section 3.2)",
        description="G^-1(z) as an m x m matrix, the residue matrix at z = 1, the Hermitian part M(c), its "
        "principal minors and the exact worst case over w (all principal minors / characteristic "
        "coefficients, never leading minors alone). Parameters: per-user b_i, K_0i, B_0i, z_ai, K_ij, B_ij; "
        "the group names b, K_0, B_0, K, B, z_a set every member (with --uniform they are the only names); "
        "m / m_i (masses) enter only the stability boundary.",
    )
    add_scene_options(parser, "multi-user")
    add_design_options(parser)
    parser.add_argument("--latex", action="store_true", help="same as --format latex")
    parser.add_argument("--format", choices=("text", "latex", "json"), default="text",
                        help="text (default), latex (a complete document) or json")
    parser.add_argument("--fragment", action="store_true",
                        help="with --format latex: only the displays (amsmath), not a complete document")
    parser.add_argument("--minors", choices=("auto", "all", "none"), default="auto",
                        help="print the principal minors (auto: when m <= 3)")
    parser.add_argument("--verbose", action="store_true", help="print large expressions in full (text format)")
    add_output_option(parser)
    parser.set_defaults(handler=run)


def build_scene(users: int, delay: str = "0", uniform: bool = False, active: bool = False, graph: str = "complete",
                approximation: str = "forward", params: dict | None = None) -> MultiUserScene:
    """The scene the command line describes (parameters substituted).

    >>> build_scene(2, uniform=True, params={"b": 1, "K_0": 2, "B_0": 0, "K": 2, "B": 0, "T": "1/100"}).is_numeric
    True
    """
    from hapticproof.systems.scene import Scene

    return Scene("multi-user", users=users, delay=delay, uniform=uniform, active=active, graph=graph,
                 approximation=approximation, params=params or {}).build()


def derive(scene: MultiUserScene, minors: str = "auto") -> dict[str, Any]:
    """Everything the command prints, as SymPy objects."""
    G = inverse_transfer_matrix(scene)
    (res,) = [r for r in residues(scene) if r.pole == 1] or [None]
    H = hermitian(scene)
    show_minors = minors == "all" or (minors == "auto" and scene.users <= 3)
    wc = worst_case(scene)
    out: dict[str, Any] = {
        "users": scene.users,
        "delays": list(scene.delays),
        "approximation": scene.approximation,
        "edges": [(i + 1, j + 1) for i, j in scene.edges],
        "G_inverse": G,
        "residue_at_1": res.matrix if res is not None else None,
        "residue_condition": res.outcome.reason if res is not None else "no pole on |z| = 1",
        "hermitian_part": H.matrix(sp.Symbol("s_theta")),
        "hermitian_is_real": H.is_symmetric,
        "worst_case_method": wc.method,
        "worst_case_condition": wc.condition,
        "worst_c": wc.minimiser,
        "conditions": conditions(scene),
        "verdict": positive_real(scene).decision.value,
        "reason": positive_real(scene).reason,
        "witness": positive_real(scene).evidence.witness,
    }
    if show_minors:
        out["principal_minors"] = {tuple(i + 1 for i in k): mn.expr() for k, mn in principal_minors(scene).items()}
    if scene.equal_delays and not scene.is_numeric:
        out["sufficient_condition"] = sufficient_condition(scene)
    return out


def _text(data: dict[str, Any], verbose: bool = False) -> str:
    from hapticproof.report.readable import brief

    lines = [
        f"system:            {data['users']}-user HVE ({data['approximation']} difference, delays {data['delays']}, "
        f"edges {data['edges']})",
        "G^-1(z):",
        *(f"  row {i + 1}: {brief(list(row), verbose=verbose)}" for i, row in enumerate(data["G_inverse"].tolist())),
        f"residue at z = 1:  {sp.sstr(data['residue_at_1'])}  [{data['residue_condition']}]",
        f"M(c) = G^-1 + G^-H on |z| = 1 (c = cos wT{'' if data['hermitian_is_real'] else ', s_theta = sin wT'}):",
        *(f"  row {i + 1}: {brief(list(row), verbose=verbose)}" for i, row in enumerate(data["hermitian_part"].tolist())),
    ]
    if "principal_minors" in data:
        lines.append("principal minors (all of them):")
        lines += [f"  {k}: {brief(v, verbose=verbose)}" for k, v in data["principal_minors"].items()]
    lines.append(f"worst case ({data['worst_case_method']}): {sp.sstr(data['worst_case_condition'])}"
                 + (f"   at c = {data['worst_c']}" if data["worst_c"] is not None else ""))
    if "sufficient_condition" in data:
        lines.append(f"sufficient (any graph, Loewner): {sp.sstr(data['sufficient_condition'])}")
    lines.append("conditions:")
    width = max(len(c.name) for c in data["conditions"])
    lines += [f"  {c.name.ljust(width)}  {c.decision.value:<9}  {c.outcome.reason}" for c in data["conditions"]]
    lines.append(f"verdict:           {data['verdict']}  ({data['reason']})")
    if data["witness"] and data["verdict"] == "disproved":
        lines.append("witness:           " + ", ".join(f"{k} = {v}" for k, v in data["witness"].items()))
    return "\n".join(lines)


def _matrix_items(label: str, name: str, matrix: sp.Matrix, cos_name: str | None = None) -> list[tuple[str, str]]:
    """A matrix as one display, or entry by entry (upper triangle when symmetric) when it
    is too long to read as one."""
    whole = tex.to_latex(matrix, cos_name=cos_name)
    if len(whole) <= 600:
        return [(label, f"{name} = " + whole)]
    symmetric = matrix.is_symmetric()
    return [(f"{label}, entry ({i + 1}, {j + 1})", f"{name}_{{{i + 1}{j + 1}}} = " + tex.to_latex(matrix[i, j], cos_name=cos_name))
            for i in range(matrix.rows) for j in range(matrix.cols) if not symmetric or j >= i]


def _latex_items(data: dict[str, Any]) -> list[tuple[str, str]]:
    """``(label, display)`` of everything the command derives."""
    items = _matrix_items("inverse transfer matrix", r"G^{-1}(z)", data["G_inverse"])
    if data["residue_at_1"] is not None:
        items += _matrix_items("residue matrix at z = 1", "R_0", data["residue_at_1"])
    items += _matrix_items("Hermitian part on the unit circle", "M", data["hermitian_part"], COS)
    for k, v in data.get("principal_minors", {}).items():
        items.append((f"principal minor {k}", r"\Delta_{" + "".join(map(str, k)) + "} = " + tex.to_latex(v, cos_name=COS)))
    if data["worst_case_condition"] not in (None, sp.true, sp.false):
        items.append((f"worst case over frequency ({data['worst_case_method']})", tex.to_latex(data["worst_case_condition"])))
    if "sufficient_condition" in data:
        items.append(("sufficient condition (any graph, Loewner order)", tex.to_latex(data["sufficient_condition"])))
    return items


def _latex(data: dict[str, Any], fragment: bool = False) -> str:
    """A complete document (or, with ``fragment``, the amsmath displays alone)."""
    items = _latex_items(data)
    if fragment:
        return tex.derivation_fragment(items)
    intro = tex.escape_text(f"{data['users']}-user HVE, {data['approximation']} difference, delays {data['delays']}, "
                            f"edges {data['edges']}.")
    notes = [("verdict", f"{data['verdict']} ({data['reason']})"), ("residue condition", str(data["residue_condition"]))]
    if data["witness"]:
        notes.append(("witness", ", ".join(f"{k} = {v}" for k, v in to_jsonable(data["witness"]).items())))
    return tex.derivation_document(f"hapticproof derive multi-user ({data['users']} users)", items, notes, intro=intro)


def run(args: argparse.Namespace) -> int:
    fmt = "latex" if args.latex else args.format
    if args.fragment and fmt != "latex":
        raise InputFormatError("--fragment needs --format latex")
    check_output(args.output, "--output")
    spec = scene_from_args(args, "multi-user")
    scene = build_model(spec, args)
    data = derive(scene, args.minors)
    extra, lines = design_answers(spec, args, args.delay_margin)
    if fmt == "json":
        out = to_jsonable({k: ([c.to_json() for c in v] if k == "conditions" else v) for k, v in data.items()})
        out.update(extra)
        text = json.dumps(out, indent=2)
    elif fmt == "latex":
        text = _latex(data, args.fragment)
    else:
        text = "\n".join([_text(data, args.verbose)] + lines)
    write_output(args.output, text)
    return 0
