"""``hapticproof derive multi-user``: exact conditions of an m-user haptic virtual environment.

Examples::

    hapticproof derive multi-user --users 3
    hapticproof derive multi-user --users 2 --delay 2 --uniform --param B_0=0 --param B=0 --latex
    hapticproof derive multi-user --users 4 --param b=0.02 --param K_0=10 --param K=5 \\
        --param B_0=0 --param B=0 --param T=0.001 --format json

Parameters are symbolic unless fixed with ``--param``; per-user names are ``b_1``, ``K_01``,
``B_01``, ``z_a1``, ``K_12``, ``B_12`` ...; the group names ``b``, ``K_0``, ``B_0``, ``K``, ``B``,
``z_a`` set every member of the group (with ``--uniform`` they are the only names).
"""

from __future__ import annotations

import argparse
import json
from typing import Any

import sympy as sp

from hapticproof import latex as tex
from hapticproof.cli._common import add_param_option, parse_params
from hapticproof.errors import InputFormatError
from hapticproof.evidence import to_jsonable
from hapticproof.multiuser import (
    MultiUserScene,
    conditions,
    hermitian,
    inverse_transfer_matrix,
    positive_real,
    principal_minors,
    residues,
    sufficient_condition,
    worst_case,
)
from hapticproof.scene import APPROXIMATIONS

__all__ = ["register", "build_scene", "derive"]

COS = r"\cos(\omega T)"
GROUPS = {"b": "b", "K_0": "K0", "B_0": "B0", "z_a": "z_a", "K": "K", "B": "B"}


def register(systems: argparse._SubParsersAction) -> None:
    parser = systems.add_parser(
        "multi-user",
        help="m users coupled through a shared virtual environment (HVE paper, Section 3.2)",
        description="G^-1(z) as an m x m matrix, the residue matrix at z = 1, the Hermitian part M(c), its "
        "principal minors and the exact worst case over w (all principal minors / characteristic "
        "coefficients, never leading minors alone).",
    )
    parser.add_argument("--users", type=int, default=2, help="number of users m (default 2)")
    parser.add_argument("--delay", default="0", help="n = t_d/T for every user, or a comma list n_1,...,n_m")
    parser.add_argument("--uniform", action="store_true", help="all users alike: symbols b, K_0, B_0, K, B, z_a")
    parser.add_argument("--active", action="store_true", help="include the operators' shortage of passivity z_a")
    parser.add_argument("--graph", default="complete", metavar="GRAPH",
                        help="coupling graph: complete (default), path, star, ring, or edges like 1-2,2-3")
    parser.add_argument("--approximation", choices=APPROXIMATIONS, default="forward")
    parser.add_argument("--latex", action="store_true", help="same as --format latex")
    parser.add_argument("--format", choices=("text", "latex", "json"), default="text",
                        help="text (default), latex (a complete document) or json")
    parser.add_argument("--fragment", action="store_true",
                        help="with --format latex: only the displays (amsmath), not a complete document")
    parser.add_argument("--minors", choices=("auto", "all", "none"), default="auto",
                        help="print the principal minors (auto: when m <= 3)")
    add_param_option(parser)
    parser.set_defaults(handler=run)


def _edges(text: str, m: int) -> tuple[tuple[int, int], ...] | None:
    text = text.strip().lower()
    if text == "complete":
        return None
    if text == "path":
        return tuple((i, i + 1) for i in range(m - 1))
    if text == "star":
        return tuple((0, i) for i in range(1, m))
    if text == "ring":
        return tuple(sorted({tuple(sorted((i, (i + 1) % m))) for i in range(m)} - {(0, 0)})) if m > 1 else ()
    edges = []
    for item in text.split(","):
        try:
            i, j = (int(v) for v in item.split("-"))
        except ValueError:
            raise InputFormatError(f"--graph: expected complete, path, star, ring or edges like 1-2,2-3; got {item!r}") from None
        if not (1 <= i <= m and 1 <= j <= m) or i == j:
            raise InputFormatError(f"--graph: edge {item!r} needs two different users in 1..{m}")
        edges.append((i - 1, j - 1))
    return tuple(edges)


def _delays(text: str, m: int) -> Any:
    try:
        values = [int(v) for v in text.split(",")]
    except ValueError:
        raise InputFormatError(f"--delay: expected an integer or a comma list of integers, got {text!r}") from None
    if len(values) == 1:
        return values[0]
    if len(values) != m:
        raise InputFormatError(f"--delay: {len(values)} values for {m} users")
    return values


def build_scene(users: int, delay: str = "0", uniform: bool = False, active: bool = False, graph: str = "complete",
                approximation: str = "forward", params: dict | None = None) -> MultiUserScene:
    """The scene the command line describes (parameters substituted).

    >>> build_scene(2, uniform=True, params={"b": 1, "K_0": 2, "B_0": 0, "K": 2, "B": 0, "T": "1/100"}).is_numeric
    True
    """
    if users < 1:
        raise InputFormatError("--users must be a positive integer")
    edges = _edges(graph, users)
    delays = _delays(delay, users)
    params = dict(params or {})
    if uniform:
        if not isinstance(delays, int):
            raise InputFormatError("--uniform needs one delay for every user")
        from hapticproof.multiuser import UNIFORM_SYMBOLS

        scene = MultiUserScene.uniform(users, delay=delays, edges=edges, approximation=approximation,
                                       z_a=UNIFORM_SYMBOLS["z_a"] if active else 0)
        names = {s.name for s in scene.parameters}
        unknown = set(params) - names
        if unknown:
            raise InputFormatError(f"unknown parameter(s) {sorted(unknown)}; this scene has {sorted(names)}")
        return scene.with_values(params)
    scene = MultiUserScene.symbolic(users, edges=edges, delays=delays, active=active, approximation=approximation)
    values: dict[sp.Symbol, Any] = {}
    members = {"b": scene.b, "K0": scene.K0, "B0": scene.B0, "z_a": scene.z_a, "K": scene.K, "B": scene.B}
    by_name = {s.name: s for s in scene.parameters}
    for name, value in params.items():
        if name in GROUPS:
            for s in members[GROUPS[name]]:
                if isinstance(s, sp.Symbol):
                    values[s] = value
        elif name in by_name:
            values[by_name[name]] = value
        else:
            raise InputFormatError(f"unknown parameter {name!r}; use {', '.join(sorted(GROUPS))}, T or per-user names "
                                   f"such as {', '.join(sorted(by_name)[:4])}")
    return scene.with_values(values)


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


def _text(data: dict[str, Any]) -> str:
    lines = [
        f"system:            {data['users']}-user HVE ({data['approximation']} difference, delays {data['delays']}, "
        f"edges {data['edges']})",
        "G^-1(z):",
        *(f"  row {i + 1}: {sp.sstr(list(row))}" for i, row in enumerate(data["G_inverse"].tolist())),
        f"residue at z = 1:  {sp.sstr(data['residue_at_1'])}  [{data['residue_condition']}]",
        f"M(c) = G^-1 + G^-H on |z| = 1 (c = cos wT{'' if data['hermitian_is_real'] else ', s_theta = sin wT'}):",
        *(f"  row {i + 1}: {sp.sstr(list(row))}" for i, row in enumerate(data["hermitian_part"].tolist())),
    ]
    if "principal_minors" in data:
        lines.append("principal minors (all of them):")
        lines += [f"  {k}: {sp.sstr(v)}" for k, v in data["principal_minors"].items()]
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
    scene = build_scene(args.users, args.delay, args.uniform, args.active, args.graph, args.approximation,
                        parse_params(args.param))
    data = derive(scene, args.minors)
    if fmt == "json":
        print(json.dumps(to_jsonable({k: ([c.to_json() for c in v] if k == "conditions" else v) for k, v in data.items()}),
                         indent=2))
    elif fmt == "latex":
        print(_latex(data, args.fragment))
    else:
        print(_text(data))
    return 0
