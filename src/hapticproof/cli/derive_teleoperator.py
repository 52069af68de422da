"""``hapticproof derive teleoperator``: passivity of the sampled-data PEB teleoperator.

Prints the exact passivity decision condition by condition -- (D) non-negative dampings, (P1)-(P4)
the poles of ``C`` and its DC stiffness, (P5) ``h >= L(c)`` with the error-coordinate damping
``h = b_m b_s/(b_m + alpha^2 b_s)`` (:mod:`hapticproof.analysis.teleoperator`) -- and, apart, the
per-robot bounds of the paper's (32) (``(29)`` at ``alpha = 1``) as exact functions of
``c = cos(wT)`` with their worst case: a sufficient condition only, never a disproof.

Examples::

    hapticproof derive teleoperator                                    # symbolic PD: (34), (35)
    hapticproof derive teleoperator --controller filtered-pd --param a=1/2
    hapticproof derive teleoperator --controller "K/(1 - 0.5/z)" --param K=1 --param T=0.001 \\
        --param b_m=0.02 --param b_s=0.02
    hapticproof derive teleoperator --controller 'K_p + K_i/s' --discretize tustin --param K_i=2 \\
        --param T=0.001 --param b_m=0.02 --param b_s=0.02 --range K_p
"""

from __future__ import annotations

import argparse
import json
from typing import Any

import sympy as sp

from hapticproof.report import latex as tex
from hapticproof.cli.common import add_output_option, build_model, add_scene_options, check_output, refuse, scene_from_args, write_output
from hapticproof.cli.derive_single_user import add_design_options, design_answers
from hapticproof.core.errors import InputFormatError
from hapticproof.core.evidence import to_jsonable
from hapticproof.analysis.teleoperator import (bounds, criterion, criterion_conditions, error_coordinate_damping, passivity,
                                               passivity_conditions, worst_case)

__all__ = ["register", "run"]

def register(systems: argparse._SubParsersAction, line: str = "") -> None:
    parser = systems.add_parser(
        "teleoperator",
        help=line,
        description="The exact passivity decision, condition by condition: (D) b_m, b_s >= 0; (P1) no pole of C "
        "in |z| > 1; (P2) none at z = 1; (P3) C(1) >= 0; (P4) other unit-circle poles simple with positive "
        "Res(C,z0)/(z0(z0-1)); (P5) h >= L(c) for all c = cos(wT), h = b_m b_s/(b_m + alpha^2 b_s) (exact when "
        "the controller, T, alpha, b_m and b_s are numbers, conditions on the parameters otherwise; the masses "
        "m_m, m_s do not enter it: they are needed only for the stability boundary). The per-robot bounds of the "
        "paper's (32) (eq. (29) at alpha = 1) are printed apart: a sufficient condition only. Controllers: 'pd' "
        "(eq. 33, default), 'filtered-pd' (derivative low-pass with pole a), any rational C(z), or C(s) with "
        "--discretize; any parameter names.",
    )
    add_scene_options(parser, "teleoperator")
    add_design_options(parser, margin=False)
    parser.add_argument("--format", choices=("text", "latex", "json"), default="text",
                        help="text (default), latex (a complete document) or json")
    parser.add_argument("--fragment", action="store_true",
                        help="with --format latex: only the displays (amsmath), not a complete document")
    parser.add_argument("--verbose", action="store_true", help="print large expressions in full (text format)")
    add_output_option(parser)
    parser.set_defaults(handler=run)


def _value_latex(value: Any, names: Any) -> str:
    """An exact number as LaTeX; a certified ball (an irrational supremum) by its digits."""
    from hapticproof.report.readable import number

    value = sp.sympify(value) if not hasattr(value, "mid") else value
    if isinstance(value, sp.Basic) and value.is_number:
        return names.latex(value)
    return r"\text{" + number(value) + "}"


def run(args: argparse.Namespace) -> int:
    from hapticproof.systems.discretize import is_rational
    from hapticproof.core.notation import default_name, shorten_numbers
    from hapticproof.report.readable import brief, number

    if args.fragment and args.format != "latex":
        raise InputFormatError("--fragment needs --format latex")
    check_output(args.output, "--output")
    spec = scene_from_args(args, "teleoperator")
    scene = build_model(spec, args)
    if not is_rational(scene.C):
        refuse(args, f"{spec.discretize}: C(z) = {sp.sstr(scene.C)} has transcendental coefficients (e^(pT) of the "
               "exact map): an exact decision needs rational coefficients; use forward, backward or tustin, or give "
               "the discrete C(z) with rounded poles",
               {"continuous_design": {"C_s": sp.sstr(spec.controller), "discretize": spec.discretize,
                                      "C_z": sp.sstr(scene.C)}, "verdict": None})
    bd, wc = bounds(scene), worst_case(scene)
    decision = passivity(scene)
    conds = passivity_conditions(scene)
    paper = criterion(scene)
    paper_conds = criterion_conditions(scene)
    extra, lines, answers = design_answers(spec, args, False)
    names = scene.naming()                 # every name below is the scene's (roles, c, h, L)
    t, w = names.text, names.words
    if args.format == "json":
        out = {"controller": t(scene.C), "alpha": t(scene.alpha), "bound_master": t(bd.master),
               "bound_slave": t(bd.slave), "sup_master": to_jsonable(wc.sup_master),
               "sup_slave": to_jsonable(wc.sup_slave), "maximiser": to_jsonable(wc.maximiser),
               "condition": t(wc.condition) if wc.condition is not None else None,
               "error_coordinate_damping": t(error_coordinate_damping(scene)),
               "conditions": [c.to_json() for c in conds],
               "verdict": decision.decision.value, "reason": decision.reason,
               "decision": decision.to_json(),
               "criterion_32": {"note": "the paper's (32): a sufficient condition for alpha > 0 under (P1)-(P4), "
                                        "never a disproof", "decision": paper.decision.value, "reason": paper.reason,
                                "conditions": [c.to_json() for c in paper_conds]}}
        if names.changed():
            out["notation"] = names.changed()
        if spec.discretize is not None:
            out["continuous_design"] = {"C_s": sp.sstr(spec.controller), "discretize": spec.discretize}
        out = names.claims({**to_jsonable(out), **extra})
        write_output(args.output, json.dumps(out, indent=2))
        return 0
    cos = names.helper("cos")
    master, slave = names.role("master_damping", "b_m"), names.role("slave_damping", "b_s")
    if args.format == "latex":
        items = [("controller", r"C(z) = " + names.latex(scene.C)),
                 ("error-coordinate damping", f"{names.helper_latex('coupling')} = "
                  + names.latex(error_coordinate_damping(scene)))]
        exact = conds[-1].outcome.evidence.facts.get("condition")      # (P5): passive iff, with (D), (P1)-(P4)
        if isinstance(exact, sp.Basic) and exact not in (sp.true, sp.false):
            items.append(("exact condition (P5), with (D) and (P1)-(P4): passive iff", names.latex(exact)))
        items += [(f"the paper's (32), sufficient only: master damping bound ({cos} = {names.cos_text})",
                   f"{default_name(master)} > " + names.latex(bd.master, cos=True)),
                  ("the paper's (32), sufficient only: slave damping bound", f"{default_name(slave)} > "
                   + names.latex(bd.slave, cos=True))]
        if wc.condition in (sp.true, sp.false):
            # numbers: what (32) needs of each damping, and whether these values meet it
            needed = (rf"{default_name(master)} \ge {_value_latex(wc.sup_master, names)},\quad "
                      rf"{default_name(slave)} \ge {_value_latex(wc.sup_slave, names)}")
            items.append((f"the paper's (32) over frequency (sufficient only): "
                          f"{'met' if wc.condition is sp.true else 'not met'} by these values", needed))
        elif wc.condition is not None:
            items.append(("the paper's (32) over frequency (sufficient only)", names.latex(wc.condition)))
        items += answers
        if args.fragment:
            write_output(args.output, tex.derivation_fragment(items))
            return 0
        notes = []
        if sp.sympify(wc.sup_master).is_number:
            notes.append(("worst case", f"sup over {cos} = {number(wc.sup_master)} (master), "
                          f"{number(wc.sup_slave)} (slave)"
                          + (f" at {cos} = {number(wc.maximiser)}" if wc.maximiser is not None else "")))
        notes.append(("decision", f"{decision.decision.value} ({decision.reason})"))
        notes.append(("the paper's (32)", f"{paper.decision.value} (a sufficient condition only)"))
        write_output(args.output, tex.derivation_document("hapticproof derive teleoperator", items, notes,
                                                          intro=tex.escape_text(f"PEB teleoperator, alpha = {scene.alpha}.")))
        return 0
    v = args.verbose
    out_lines = []
    if spec.discretize is not None:
        out_lines.append(f"C(s) = {sp.sstr(spec.controller)}  ->  {spec.discretize}")
    out_lines += [f"controller C(z) = {brief(scene.C, verbose=v, names=names)}, alpha = {scene.alpha}",
                  w("leak L(c)") + f" = {brief(sp.factor(bd.leak), verbose=v, names=names)}    ({cos} = {names.cos_text})",
                  w("error-coordinate damping h = b_m b_s/(b_m + alpha^2 b_s)") + f" = {_damping_text(scene, names)}",
                  "conditions (exact: passive iff all hold):"]
    width = max(len(c.name) for c in conds + paper_conds)
    for cond in conds:
        out_lines.append(f"  {cond.name.ljust(width)}  {cond.decision.value:<9}  {shorten_numbers(cond.outcome.reason, verbose=v)}")
    out_lines.append(f"verdict: {decision.decision.value} ({shorten_numbers(decision.reason, verbose=v)})")
    out_lines.append("the paper's (32), a sufficient condition only (alpha > 0, under (P1)-(P4)):")
    out_lines += [f"  {master} > {brief(sp.factor(bd.master), verbose=v, names=names)}",
                  f"  {slave} > {brief(sp.factor(bd.slave), verbose=v, names=names)}"]
    where = f" at {cos} = {number(wc.maximiser) if not hasattr(wc.maximiser, 'approx') else wc.maximiser.approx(12)}" \
        if wc.maximiser is not None else ""
    if wc.sup_master is sp.oo or wc.sup_master == sp.oo:
        out_lines.append("  worst case: the bounds are unbounded (C(z) has a pole on the unit circle)")
    else:
        out_lines.append(f"  worst case: sup over {cos} of the bounds = {number(wc.sup_master)} (master), "
                         f"{number(wc.sup_slave)} (slave){where}")
    for cond in paper_conds:
        out_lines.append(f"  {cond.name.ljust(width)}  {cond.decision.value:<9}  {shorten_numbers(cond.outcome.reason, verbose=v)}")
    write_output(args.output, "\n".join(out_lines + lines))
    return 0


def _damping_text(scene, names) -> str:
    """``h``, or why it is not defined (a negative damping: condition (D) decides)."""
    negative = [names.words(name) for name in ("b_m", "b_s")
                if getattr(scene, name).is_number and getattr(scene, name) < 0]
    if negative:
        return f"not defined ({', '.join(negative)} < 0: condition (D) fails)"
    return names.text(error_coordinate_damping(scene))


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
