"""``hapticproof derive teleoperator``: passivity bounds of the sampled-data PEB teleoperator.

Prints the per-robot damping bounds of the teleoperator paper's (32) (``(29)`` at ``alpha = 1``)
as exact functions of ``c = cos(wT)`` for the chosen controller, their worst case over
frequency, and, when every parameter is a number, the exact passivity decision.

Examples::

    hapticproof derive teleoperator                                    # symbolic PD: (34), (35)
    hapticproof derive teleoperator --controller filtered-pd --param a=1/2
    hapticproof derive teleoperator --controller "K/(1 - 0.5/z)" --param K=1 --param T=0.001 \\
        --param b_m=0.02 --param b_s=0.02
"""

from __future__ import annotations

import argparse
import json

import sympy as sp

from hapticproof import latex as tex
from hapticproof.cli._common import add_param_option, parse_params
from hapticproof.errors import InputFormatError
from hapticproof.evidence import to_jsonable
from hapticproof.teleoperator import (
    TELE_SYMBOLS,
    TeleoperatorScene,
    bounds,
    error_coordinate_damping,
    filtered_pd_controller,
    parse_controller,
    passivity,
    passivity_conditions,
    pd_controller,
    worst_case,
)

__all__ = ["register", "run"]

PARAMETERS = ("K", "B", "T", "a", "alpha", "b_m", "b_s", "m_m", "m_s")


def register(systems: argparse._SubParsersAction) -> None:
    parser = systems.add_parser(
        "teleoperator",
        help="sampled-data position-error-based teleoperator (teleoperator paper, Fig. 2)",
        description="Per-robot damping bounds of eq. (32) (eq. (29) at alpha = 1) as exact functions of "
        "c = cos(wT), their worst case over w, and the exact passivity decision when every parameter is fixed. "
        "Controllers: 'pd' (eq. 33, default), 'filtered-pd' (derivative low-pass with pole a), or any "
        "rational C(z) in z and the names " + ", ".join(PARAMETERS) + ".",
    )
    parser.add_argument("--controller", default="pd", metavar="C(z)",
                        help="'pd', 'filtered-pd' or an expression in z (default: pd)")
    parser.add_argument("--format", choices=("text", "latex", "json"), default="text",
                        help="text (default), latex (a complete document) or json")
    parser.add_argument("--fragment", action="store_true",
                        help="with --format latex: only the displays (amsmath), not a complete document")
    add_param_option(parser)
    parser.set_defaults(handler=run)


def _controller(text: str, params: dict) -> sp.Expr:
    T = params.get("T", TELE_SYMBOLS["T"])
    if text == "pd":
        return pd_controller(params.get("K", TELE_SYMBOLS["K"]), params.get("B", TELE_SYMBOLS["B"]), T)
    if text == "filtered-pd":
        return filtered_pd_controller(params.get("K", TELE_SYMBOLS["K"]), params.get("B", TELE_SYMBOLS["B"]), T,
                                      params.get("a", TELE_SYMBOLS["a"]))
    return parse_controller(text, {k: v for k, v in params.items() if k in ("K", "B", "T", "a")})


def run(args: argparse.Namespace) -> int:
    if args.fragment and args.format != "latex":
        raise InputFormatError("--fragment needs --format latex")
    params = parse_params(args.param)
    unknown = set(params) - set(PARAMETERS)
    if unknown:
        raise InputFormatError(f"unknown parameter(s) {sorted(unknown)}; the teleoperator has {', '.join(PARAMETERS)}")
    sym = TELE_SYMBOLS
    scene = TeleoperatorScene(
        params.get("m_m", sym["m_m"]), params.get("m_s", sym["m_s"]), params.get("b_m", sym["b_m"]),
        params.get("b_s", sym["b_s"]), params.get("T", sym["T"]), _controller(args.controller, params),
        params.get("alpha", 1),
    )
    bd, wc = bounds(scene), worst_case(scene)
    decision = passivity(scene)
    conds = passivity_conditions(scene)
    if args.format == "json":
        out = {"controller": sp.sstr(scene.C), "alpha": sp.sstr(scene.alpha), "bound_master": sp.sstr(bd.master),
               "bound_slave": sp.sstr(bd.slave), "sup_master": to_jsonable(wc.sup_master),
               "sup_slave": to_jsonable(wc.sup_slave), "maximiser": to_jsonable(wc.maximiser),
               "condition": sp.sstr(wc.condition) if wc.condition is not None else None,
               "error_coordinate_damping": sp.sstr(error_coordinate_damping(scene)),
               "conditions": [c.to_json() for c in conds],
               "verdict": decision.decision.value, "reason": decision.reason,
               "decision": decision.to_json()}
        out = to_jsonable(out)
        print(json.dumps(out, indent=2))
        return 0
    cos = r"\cos(\omega T)"
    if args.format == "latex":
        items = [("controller", r"C(z) = " + tex.to_latex(scene.C)),
                 ("master damping bound (c = cos wT)", r"b_m > " + tex.to_latex(bd.master, cos_name=cos)),
                 ("slave damping bound", r"b_s > " + tex.to_latex(bd.slave, cos_name=cos))]
        if wc.condition is not None:
            items.append(("worst case over frequency", tex.to_latex(wc.condition)))
        items.append(("error-coordinate damping (less conservative)", r"b_e = " + tex.to_latex(error_coordinate_damping(scene))))
        if args.fragment:
            print(tex.derivation_fragment(items))
            return 0
        notes = []
        if sp.sympify(wc.sup_master).is_number:
            notes.append(("worst case", f"sup over c = {to_jsonable(wc.sup_master)} (master), "
                          f"{to_jsonable(wc.sup_slave)} (slave)"
                          + (f" at c = {to_jsonable(wc.maximiser)}" if wc.maximiser is not None else "")))
        if decision is not None:
            notes.append(("decision", f"{decision.decision.value} ({decision.reason})"))
        print(tex.derivation_document("hapticproof derive teleoperator", items, notes,
                                      intro=tex.escape_text(f"PEB teleoperator, alpha = {scene.alpha}.")))
        return 0
    print(f"controller C(z) = {sp.sstr(scene.C)}, alpha = {scene.alpha}")
    print(f"b_m > {sp.sstr(sp.factor(bd.master))}    (c = cos wT)")
    print(f"b_s > {sp.sstr(sp.factor(bd.slave))}")
    where = f" at c = {_number(wc.maximiser)}" if wc.maximiser is not None else ""
    print(f"worst case: sup over c of the bounds = {_number(wc.sup_master)} (master), {_number(wc.sup_slave)} (slave){where}")
    if wc.condition is not None and decision.decision.value == "symbolic":
        print(f"passive if {sp.sstr(wc.condition)}")
    print(f"error-coordinate damping (less conservative): {sp.sstr(error_coordinate_damping(scene))}")
    print("conditions:")
    width = max(len(c.name) for c in conds)
    for cond in conds:
        print(f"  {cond.name.ljust(width)}  {cond.decision.value:<9}  {cond.outcome.reason}")
    print(f"verdict: {decision.decision.value} ({decision.reason})")
    return 0


def _number(value) -> str:
    """An exact number, a certified ball (as a decimal) or infinity, for the text output."""
    if value is None:
        return "?"
    if value == sp.oo:
        return "oo (unbounded: no finite damping suffices)"
    if hasattr(value, "mid"):
        return f"{float(value.mid()):.12g}"
    if hasattr(value, "approx"):
        return value.approx(12)
    return sp.sstr(value)
