"""``hapticproof derive single-user``: the exact conditions of a 1-DOF haptic scene.

Examples::

    hapticproof derive single-user --environment 'K + B*(z-1)/(T*z) + M*(z-1)**2/(T**2*z**2)' \\
        --param K=2 --param B=0.01 --param M=0.5 --param T=0.001 --param b=0.9 --delay-margin --range K
    hapticproof derive single-user --controller 'K + B*s' --discretize tustin --param T=0.001
    hapticproof derive --scene examples/filtered_wall.toml --range K
"""

from __future__ import annotations

import argparse
import json

import sympy as sp

from hapticproof.cli.common import add_output_option, build_model, add_scene_options, check_output, refuse, scene_from_args, write_output
from hapticproof.core.errors import InputFormatError

__all__ = ["register", "run", "add_design_options", "design_answers"]


def register(systems: argparse._SubParsersAction) -> None:
    parser = systems.add_parser(
        "single-user",
        help="1-DOF device on a discrete environment (HVE paper, Fig. 4)",
        description="G^-1(z), poles, residues, the exact Hermitian part as a function of c = cos(wT), the "
        "worst case over w and the whole positive-realness decision (exact when every parameter is a number). "
        "Any parameter names; decimals are exact. --delay-margin and --range NAME answer the designer's "
        "questions exactly.",
    )
    add_scene_options(parser, "single-user")
    add_design_options(parser)
    parser.add_argument("--format", choices=("text", "latex", "json"), default="text",
                        help="text (default), latex (a complete document) or json")
    parser.add_argument("--fragment", action="store_true",
                        help="with --format latex: only the displays (amsmath), not a complete document")
    parser.add_argument("--verbose", action="store_true", help="print large expressions in full (text format)")
    parser.add_argument("--profile", action="store_true", help="print the time of each computed stage")
    add_output_option(parser)
    parser.set_defaults(handler=run)


def add_design_options(parser: argparse.ArgumentParser, margin: bool = True) -> None:
    if margin:
        parser.add_argument("--delay-margin", action="store_true",
                            help="the largest N such that the scene is passive for every delay n = 0..N (exact; "
                            "numeric parameters; with --delay n it is computed unasked)")
        parser.add_argument("--max-delay", type=int, default=2000, metavar="N",
                            help="search the delay margin up to N when no bound ends the search (default 2000)")
    parser.add_argument("--range", action="append", default=[], metavar="NAME",
                        help="the exact passive range of parameter NAME with the others fixed (e.g. K: K_max; "
                        "b: b_min); repeatable")


def design_answers(scene, args: argparse.Namespace, margin_wanted: bool) -> tuple[dict, list[str]]:
    """The designer's answers asked for on the command line, as JSON data and text lines."""
    from hapticproof.analysis.design import delay_margin, passive_range

    data: dict = {}
    lines: list[str] = []
    if margin_wanted:
        margin = delay_margin(scene, max_delay=getattr(args, "max_delay", 2000))
        data["delay_margin"] = margin.to_json()
        lines.append(margin.to_text())
    for name in args.range:
        rng = passive_range(scene, name)
        data.setdefault("passive_ranges", {})[name] = rng.to_json()
        lines.append(rng.to_text())
    return data, lines


def run(args: argparse.Namespace) -> int:
    from hapticproof.systems.discretize import is_rational
    from hapticproof.report.summary import summarize_single_user

    if args.fragment and args.format != "latex":
        raise InputFormatError("--fragment needs --format latex")
    check_output(args.output, "--output")
    if getattr(args, "max_delay", 1) < 0:
        raise InputFormatError("--max-delay must be >= 0")
    scene = scene_from_args(args, "single-user")
    model = build_model(scene, args)
    head: list[str] = []
    if scene.discretize is not None:
        head.append(f"H(s) = {sp.sstr(scene.environment)}  ->  {scene.discretize}: H(z) = {sp.sstr(model.H)}")
    if not is_rational(model.H):
        refuse(args, f"{scene.discretize}: H(z) = {sp.sstr(model.H)} has transcendental coefficients (e^(pT) of the "
               "exact map): an exact decision needs rational coefficients; use forward, backward or tustin, or give "
               "the discrete H(z) with rounded poles",
               {"continuous_design": {"H_s": sp.sstr(scene.environment), "discretize": scene.discretize,
                                      "H_z": sp.sstr(model.H)}, "verdict": None})
    numeric_but_delay = model.delay.is_Symbol and not (model.parameters - {model.delay})
    summary = summarize_single_user(model, with_profile=args.profile)
    extra, lines = design_answers(scene, args, args.delay_margin or numeric_but_delay)
    if args.format == "json":
        out = summary.to_json()
        if scene.discretize is not None:
            out["continuous_design"] = {"H_s": sp.sstr(scene.environment), "discretize": scene.discretize,
                                        "H_z": sp.sstr(model.H)}
        out.update(extra)
        text = json.dumps(out, indent=2)
    elif args.format == "latex":
        text = summary.dumps("latex", fragment=args.fragment)
        if lines:
            text += "\n" + "\n".join("% " + line for block in lines for line in block.splitlines())
    else:
        text = "\n".join(head + [summary.to_text(verbose=args.verbose)] + lines)
    write_output(args.output, text)
    return 0
