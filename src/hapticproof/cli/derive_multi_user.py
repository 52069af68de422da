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
from hapticproof.report.readable import tidy, witness_text
from hapticproof.cli.common import add_output_option, build_model, add_scene_options, check_output, scene_from_args, write_output
from hapticproof.cli.derive_single_user import add_design_options, design_answers
from hapticproof.core.errors import InputFormatError
from hapticproof.core.evidence import to_jsonable

__all__ = ["register", "build_scene", "derive"]

#: ``sin(omega T)`` in the imaginary parts of M(c) (unequal delays), defined where it is printed.
SIN_THETA = sp.Symbol("s_theta", real=True)
GROUPS = {"b": "b", "K_0": "K0", "B_0": "B0", "z_a": "z_a", "K": "K", "B": "B"}


def _decision_lines(data: dict) -> list[str]:
    """The conditions, the verdict and (when disproved) the witness, as the report prints them."""
    width = max(len(c.name) for c in data["conditions"])
    lines = ["conditions:", *(f"  {c.name.ljust(width)}  {c.decision.value:<9}  {c.outcome.reason}" for c in data["conditions"]),
             f"verdict:           {data['verdict']}  ({data['reason']})"]
    if data["witness"] and data["verdict"] == "disproved":
        lines.append("witness:           " + witness_text(data["witness"], data["names"]))
    return lines


def register(systems: argparse._SubParsersAction, line: str = "") -> None:
    parser = systems.add_parser(
        "multi-user",
        help=line,
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
    parser.add_argument("--full", action="store_true",
                        help="uniform scenes with 5 or more users are decided by their two extreme modes and shown "
                        "by them; --full also builds the m x m matrices (G^-1, the residue matrix, M(c): slow for large m)")
    add_output_option(parser)
    parser.set_defaults(handler=run)


def build_scene(users: int, delay: str = "0", uniform: bool = False, active: bool = False, graph: str = "complete",
                approximation: str = "forward", params: dict | None = None) -> Any:
    """The scene the command line describes (parameters substituted).

    >>> build_scene(2, uniform=True, params={"b": 1, "K_0": 2, "B_0": 0, "K": 2, "B": 0, "T": "1/100"}).is_numeric
    True
    """
    from hapticproof.systems.scene import Scene

    return Scene("multi-user", users=users, delay=delay, uniform=uniform, active=active, graph=graph,
                 approximation=approximation, params=params or {}).build()


def derive(scene: Any, minors: str = "auto", full: bool = False) -> dict[str, Any]:
    """Everything the command prints, as SymPy objects (by modes for uniform scenes of five users
    or more unless ``full``: :func:`derive_by_modes`)."""
    from hapticproof.analysis.multiuser import (by_modes, check_work, conditions, hermitian, positive_real,
                                                principal_minors, residues, sufficient_condition, worst_case)
    from hapticproof.systems.multiuser import inverse_transfer_matrix

    check_work(scene)                    # the limits, before any algebra
    if by_modes(scene) and not full:
        return derive_by_modes(scene, minors)
    names = scene.naming()
    G = inverse_transfer_matrix(scene).applyfunc(tidy)
    (res,) = [r for r in residues(scene) if r.pole == 1] or [None]
    H = hermitian(scene)
    show_minors = minors == "all" or (minors == "auto" and scene.users <= 3)
    wc = worst_case(scene)
    out: dict[str, Any] = {
        "names": names,
        "users": scene.users,
        "delays": list(scene.delays),
        "approximation": scene.approximation,
        "edges": [(i + 1, j + 1) for i, j in scene.edges],
        "G_inverse": G,
        "residue_at_1": res.matrix if res is not None else None,
        "residue_condition": res.outcome.reason if res is not None else "no pole on |z| = 1",
        "hermitian_part": H.matrix(SIN_THETA).applyfunc(tidy),
        "hermitian_is_real": H.is_symmetric,
        "worst_case_method": wc.method,
        "worst_case_condition": wc.condition,
        # a numeric scene's decision is in the toolkit's words; a symbolic one's in the scene's names
        "worst_case_reason": names.worded(wc.outcome).reason if scene.is_numeric else wc.outcome.reason,
        "worst_c": wc.minimiser,
        "conditions": conditions(scene),
        "verdict": positive_real(scene).decision.value,
        "reason": positive_real(scene).reason,
        "witness": positive_real(scene).evidence.witness,
    }
    if scene.is_numeric:
        # the original G^-1(z) matrix, judged against the definition (and re-judged by 'check');
        # above MAX_JUDGED_SIZE users the judge's exact points cost minutes: not judged
        from hapticproof.analysis.multiuser import transfer_entries
        from hapticproof.analysis.positivereal import definition_object
        from hapticproof.exact.judge import MAX_JUDGED_SIZE

        definition = (definition_object(positive_real(scene), transfer_entries(scene), scene.naming())
                      if scene.users <= MAX_JUDGED_SIZE else None)
        if definition is not None:
            out["definition"] = definition
            out["scene"] = _scene_values(scene)
            if not definition["judged"]["ok"]:   # the decision and the definition disagree
                out["reason"] = (f"the definition-level judge disagrees with '{out['verdict']}' "
                                 f"({definition['judged']['reason']}); the decision said: {out['reason']}")
                out["verdict"], out["witness"] = "undecided", None
    if show_minors:
        out["principal_minors"] = {tuple(i + 1 for i in k): mn.expr() for k, mn in principal_minors(scene).items()}
    if scene.equal_delays and not scene.is_numeric:
        out["sufficient_condition"] = sufficient_condition(scene)
    return out


def _scene_values(scene: Any) -> dict[str, Any]:
    """``T``, ``b``, ``z_a`` and ``H(z) = Kmat + Bmat (z-1)/(Tz)`` of a numeric scene, as ``check``
    rebuilds ``G^{-1}`` from them."""
    from hapticproof.exact.kernel import scene_json
    from hapticproof.systems.multiuser import damping_matrix, stiffness_matrix

    T, m = scene.T, scene.users
    Kmat, Bmat = stiffness_matrix(scene), damping_matrix(scene)
    H = [[([-Bmat[i, j], T * Kmat[i, j] + Bmat[i, j]], [0, T]) for j in range(m)] for i in range(m)]
    return scene_json(T, scene.b, scene.z_a, H)


def derive_by_modes(scene: Any, minors: str = "auto") -> dict[str, Any]:
    """A uniform scene by its modes: ``G^{-1} = U diag(g_lambda) U^T`` over the Laplacian eigenvalues,
    decided by the modes ``lambda = 0`` and ``lambda_max`` (:mod:`hapticproof.analysis.modes`); the
    m x m matrices are not built (``skipped`` says so)."""
    from hapticproof.analysis.modes import graph_kind, spectrum
    from hapticproof.analysis.multiuser import conditions, extreme_modes, positive_real, worst_case
    from hapticproof.systems.models import inverse_transfer

    m = scene.users
    names = scene.naming()
    w = names.words
    wc = worst_case(scene)
    verdict = positive_real(scene)
    values = spectrum(scene) if m <= 64 else None
    modes = [{"eigenvalue": md.eigenvalue, "multiplicity": md.multiplicity if values else None,
              "g": inverse_transfer(md.scene)} for md in extreme_modes(scene)]
    out: dict[str, Any] = {
        "names": names,
        "users": m,
        "delays": [scene.delays[0]] if len(set(scene.delays)) == 1 else list(scene.delays),
        "approximation": scene.approximation,
        "graph": graph_kind(scene),
        "edges_count": len(scene.edges),
        "by_modes": True,
        "spectrum": None if values is None else {sp.sstr(k): v for k, v in sorted(values.items(), key=lambda kv: float(kv[0]))},
        "modes": modes,
        "worst_case_method": wc.method,
        "worst_case_condition": wc.condition,
        "worst_c": wc.minimiser,
        "conditions": conditions(scene),
        "verdict": verdict.decision.value,
        "reason": verdict.reason,
        "witness": verdict.evidence.witness,
        "skipped": {
            "G_inverse": (f"the {m} x {m} matrix G^-1(z) = " + w("U diag(g_lambda) U^-1 (U orthogonal) is shown by its modes"), "--full"),
            "hermitian_part": (f"the {m} x {m} matrix " + w("M(c) = U diag(2 Re g_lambda(c)) U^-1 is shown by its modes"),
                               "--full"),
            "residue_at_1": (w("the residue matrix T Kmat = T (K_0 I + K L) has the eigenvalues T(K_0 + lambda K)"), "--full"),
        },
    }
    if minors == "all":
        out["skipped"]["principal_minors"] = (f"2^{m} - 1 principal minors: the modes decide without them", "--full")
    return out


def _modes_text(data: dict[str, Any], verbose: bool = False) -> str:
    from hapticproof.report.readable import brief

    names = data["names"]
    w = names.words
    graph = {"complete": "complete graph", "path": "path", "ring": "ring (circulant)", "star": "star"}.get(data["graph"], "graph")
    lines = [f"system:            {data['users']}-user HVE ({data['approximation']} difference, delay {data['delays'][0]}, "
             f"{graph}, {data['edges_count']} edges), uniform: decided by modes",
             w("G^-1(z) = U diag(g_lambda(z)) U^-1 (U orthogonal) over the Laplacian eigenvalues lambda of the coupling graph, "
               "g_lambda = single-user wall with K_0 + lambda K, B_0 + lambda B")]
    if data["spectrum"] is not None:
        lines.append("eigenvalues:       " + ", ".join(f"{k} (x{v})" for k, v in data["spectrum"].items()))
    for md in data["modes"]:
        lines.append(w("mode lambda") + f" = {sp.sstr(md['eigenvalue'])}: g(z) = {brief(md['g'], verbose=verbose, names=names)}")
    lines.append(w("Re g_lambda and the residues T(K_0 + lambda K) are affine in lambda: the modes lambda = 0 and "
                   "lambda_max decide"))
    lines.append(_worst_case_text(data, verbose))
    lines += _decision_lines(data)
    lines += [f"not computed:      {why} [{how} computes it]" for why, how in data["skipped"].values()]
    return "\n".join(lines)


def _modes_latex_items(data: dict[str, Any]) -> list[tuple[str, str]]:
    names = data["names"]
    lam = names.helper("eigenvalue")
    items = [(f"mode {lam} = {sp.sstr(md['eigenvalue'])}", r"g_{" + names.latex(md["eigenvalue"]) + r"}(z) = "
              + names.latex(md["g"])) for md in data["modes"]]
    if data["worst_case_condition"] not in (None, sp.true, sp.false):
        items.append((f"worst case over frequency ({data['worst_case_method']})", names.latex(data["worst_case_condition"])))
    return items


def _worst_case_text(data: dict[str, Any], verbose: bool) -> str:
    """The worst case over frequency in words: a condition on the parameters, or (numbers) whether
    M(c) is PSD for every c -- never a bare True/False/None."""
    from hapticproof.report.readable import brief

    names = data["names"]
    c, Mc = names.helper("cos"), names.words("M(c)")
    condition = data["worst_case_condition"]
    where = f" (worst at {c} = {data['worst_c']})" if data["worst_c"] is not None else ""
    if condition is sp.true or condition is True:
        text = f"{Mc} is PSD for every {c} in [-1, 1]" + where
    elif condition is sp.false or condition is False:
        text = f"{Mc} is not PSD for every {c}" + (f": fails at {c} = {data['worst_c']}" if data["worst_c"] is not None else "")
    elif condition is None:
        text = f"no closed form ({data.get('worst_case_reason', 'see the conditions')}); the conditions below decide"
    else:
        text = f"{Mc} is PSD for every {c} iff {brief(condition, verbose=verbose, names=names)}" + where
    method = "" if data["worst_case_method"] in (None, "none") else f" ({data['worst_case_method']})"
    return f"worst case{method}: {text}"


def _rows(label: str, matrix: Any, verbose: bool, names: Any) -> list[str]:
    from hapticproof.report.readable import brief

    if matrix is None:
        return [f"{label} none"]
    return [label] + [f"  row {i + 1}: {brief(list(row), verbose=verbose, names=names)}" for i, row in enumerate(matrix.tolist())]


def _text(data: dict[str, Any], verbose: bool = False) -> str:
    from hapticproof.report.readable import brief

    if data.get("by_modes"):
        return _modes_text(data, verbose)
    names = data["names"]
    helpers = f"{names.helper('cos')} = {names.cos_text}" + ("" if data["hermitian_is_real"] else
                                                           f"; {names.helper('sin')} = {names.sin_text}")
    lines = [
        f"system:            {data['users']}-user HVE ({data['approximation']} difference, delays {data['delays']}, "
        f"edges {data['edges']})",
        *_rows("G^-1(z):", data["G_inverse"], verbose, names),
        *_rows(f"residue matrix at z = 1 [{data['residue_condition']}]:", data["residue_at_1"], verbose, names),
        names.words("M(c)") + f" = G^-1 + G^-H on |z| = 1 ({helpers}):",
        *(f"  row {i + 1}: {brief(list(row), verbose=verbose, names=names)}" for i, row in enumerate(data["hermitian_part"].tolist())),
    ]
    if "principal_minors" in data:
        lines.append("principal minors (all of them):")
        lines += [f"  {k}: {brief(v, verbose=verbose, names=names)}" for k, v in data["principal_minors"].items()]
    lines.append(_worst_case_text(data, verbose))
    if "sufficient_condition" in data:
        lines.append(f"sufficient (any graph, Loewner): {names.text(data['sufficient_condition'])}")
    lines += _decision_lines(data)
    return "\n".join(lines)


def _matrix_items(label: str, name: str, matrix: sp.Matrix, names: Any, cos: bool = False) -> list[tuple[str, str]]:
    """A matrix as one display, or entry by entry (upper triangle when symmetric) when it
    is too long to read as one (in the scene's ``names``; ``cos``: ``c`` as ``\\cos(\\omega T)``)."""
    shown = {SIN_THETA: names.sin_latex}
    whole = names.latex(matrix, shown, cos=cos)
    if len(whole) <= 600:
        return [(label, f"{name} = " + whole)]
    symmetric = matrix.is_symmetric()
    return [(f"{label}, entry ({i + 1}, {j + 1})", f"{name}_{{{i + 1}{j + 1}}} = " + names.latex(matrix[i, j], shown, cos=cos))
            for i in range(matrix.rows) for j in range(matrix.cols) if not symmetric or j >= i]


def _latex_items(data: dict[str, Any]) -> list[tuple[str, str]]:
    """``(label, display)`` of everything the command derives."""
    if data.get("by_modes"):
        return _modes_latex_items(data)
    names = data["names"]
    c, M = names.helper_latex("cos"), names.helper_latex("matrix")
    items = _matrix_items("inverse transfer matrix", r"G^{-1}(z)", data["G_inverse"], names)
    if data["residue_at_1"] is not None:
        items += _matrix_items("residue matrix at z = 1", "R_0", data["residue_at_1"], names)
    items += _matrix_items("Hermitian part on the unit circle" + ("" if data["hermitian_is_real"] else
                                                                  f" ({names.helper('sin')} = {names.sin_text})"),
                           M, data["hermitian_part"], names, cos=True)
    for k, v in data.get("principal_minors", {}).items():
        items.append((f"principal minor {k}", r"\Delta_{" + "".join(map(str, k)) + "} = " + names.latex(v, cos=True)))
    condition = data["worst_case_condition"]
    if condition not in (None, sp.true, sp.false, True, False):
        items.append((f"worst case over frequency ({data['worst_case_method']})", names.latex(condition)))
    elif condition in (sp.true, True, sp.false, False):
        at = (rf" \ \text{{at }} {c} = " + names.latex(sp.sympify(data["worst_c"]))) if data["worst_c"] is not None else ""
        # (no \not: the reports typeset only the commands they know)
        shown = (rf"{M}({c}) \succeq 0 \text{{ for every }} {c} \in [-1, 1]" + at if condition in (sp.true, True)
                 else rf"{M}({c}) \succeq 0 \text{{ fails}}" + at)
        items.append((f"worst case over frequency ({data['worst_case_method']}; {names.helper('cos')} = {names.cos_text})",
                      shown))
    if "sufficient_condition" in data:
        items.append(("sufficient condition (any graph, Loewner order)", names.latex(data["sufficient_condition"])))
    return items


def _latex(data: dict[str, Any], fragment: bool = False, answers: list[tuple[str, str]] = ()) -> str:
    """A complete document (or, with ``fragment``, the amsmath displays alone); ``answers`` are
    the displays of the delay margin and passive ranges asked for."""
    items = _latex_items(data) + list(answers)
    if fragment:
        return tex.derivation_fragment(items)
    if data.get("by_modes"):
        intro = tex.escape_text(f"{data['users']}-user HVE, {data['approximation']} difference, delay {data['delays'][0]}, "
                                f"uniform couplings on a {data['graph']} graph, decided by its modes.")
        notes = [("verdict", f"{data['verdict']} ({data['reason']})")]
        notes += [(f"not computed: {name.replace('_', ' ')}", f"{why} ({how} computes it)") for name, (why, how) in data["skipped"].items()]
    else:
        intro = tex.escape_text(f"{data['users']}-user HVE, {data['approximation']} difference, delays {data['delays']}, "
                                f"edges {data['edges']}.")
        notes = [("verdict", f"{data['verdict']} ({data['reason']})"), ("residue condition", str(data["residue_condition"]))]
    if data["witness"]:
        from hapticproof.report.readable import witness_text

        notes.append(("witness", witness_text(data["witness"], data["names"])))
    return tex.derivation_document(f"hapticproof derive multi-user ({data['users']} users)", items, notes, intro=intro)


def run(args: argparse.Namespace) -> int:
    fmt = "latex" if args.latex else args.format
    if args.fragment and fmt != "latex":
        raise InputFormatError("--fragment needs --format latex")
    check_output(args.output, "--output")
    if args.max_delay < 0 or not args.deadline > 0:
        raise InputFormatError("--max-delay must be >= 0 and --deadline a positive number of seconds")
    spec = scene_from_args(args, "multi-user")
    scene = build_model(spec, args)
    data = derive(scene, args.minors, full=args.full)
    extra, lines, answers = design_answers(spec, args, args.delay_margin)
    names = data["names"]
    if fmt == "json":
        shown = {k: ([c.to_json() for c in v] if k == "conditions" else v) for k, v in data.items() if k != "names"}
        for key in ("G_inverse", "residue_at_1", "hermitian_part", "worst_case_condition", "sufficient_condition"):
            if shown.get(key) is not None:
                shown[key] = names.renamed(shown[key])      # the toolkit's c, s_theta under the scene's names
        if "principal_minors" in shown:
            shown["principal_minors"] = {k: names.renamed(v) for k, v in shown["principal_minors"].items()}
        notation = names.changed(omit=("leak", "coupling"))    # (no teleoperator quantity in an m-user report)
        if notation:
            shown["notation"] = notation
        if "skipped" in shown:
            shown["skipped"] = {k: {"reason": why, "option": how} for k, (why, how) in shown["skipped"].items()}
        out = names.claims({**to_jsonable(shown), **extra})
        text = json.dumps(out, indent=2)
    elif fmt == "latex":
        text = _latex(data, args.fragment, answers)
    else:
        text = "\n".join([_text(data, args.verbose)] + lines)
    write_output(args.output, text)
    return 0
