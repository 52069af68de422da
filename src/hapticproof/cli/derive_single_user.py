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
import sys

from hapticproof.cli.common import add_output_option, build_model, add_scene_options, check_output, refuse, scene_from_args, write_output
from hapticproof.core.errors import InputFormatError

__all__ = ["register", "run", "add_design_options", "design_answers"]


def register(systems: argparse._SubParsersAction, line: str = "") -> None:
    parser = systems.add_parser(
        "single-user",
        help=line,
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
    parser.add_argument("--full", action="store_true",
                        help="also compute the large exact objects the decision does not need (Re G^-1 as a "
                        "polynomial in c when its degree is above 500: long delays)")
    add_output_option(parser)
    parser.set_defaults(handler=run)


def add_design_options(parser: argparse.ArgumentParser, margin: bool = True) -> None:
    if margin:
        parser.add_argument("--delay-margin", action="store_true",
                            help="the largest N such that the scene is passive for every delay n = 0..N (exact; "
                            "numeric parameters; with --delay n it is computed unasked)")
        parser.add_argument("--max-delay", type=int, default=2000, metavar="N",
                            help="search the delay margin up to N when no bound ends the search (default 2000)")
        parser.add_argument("--deadline", type=float, default=60.0, metavar="SECONDS",
                            help="stop the delay-margin search after SECONDS (default 60): it then reports the "
                            "delays it decided, undecided beyond them; a progress bar shows on a terminal")
    parser.add_argument("--range", action="append", default=[], metavar="NAME",
                        help="the exact passive range of parameter NAME with the others fixed (e.g. K: K_max; "
                        "b: b_min); repeatable")


def design_answers(scene, args: argparse.Namespace, margin_wanted: bool,
                   keep: list | None = None) -> tuple[dict, list[str], list[tuple[str, str]]]:
    """The designer's answers asked for on the command line: JSON data, text lines and LaTeX
    displays (``(label, display)``, :func:`hapticproof.report.answers.answer_items`); the passive
    ranges are also appended to ``keep`` when given."""
    from hapticproof.analysis.design import delay_margin
    from hapticproof.analysis.passiverange import passive_range
    from hapticproof.report.answers import answer_items

    data: dict = {}
    lines: list[str] = []
    margin = None
    ranges = []
    if margin_wanted:
        import sys

        from hapticproof.cli.terminal import progress_bar

        bar = progress_bar(sys.stderr, "delay margin")        # a terminal only
        margin = delay_margin(scene, max_delay=getattr(args, "max_delay", 2000), deadline=getattr(args, "deadline", 60.0),
                              progress=bar)
        if bar is not None:
            bar.clear()
        data["delay_margin"] = margin.to_json()
        lines.append(margin.to_text())
    for name in args.range:
        rng = passive_range(scene, name)
        ranges.append(rng)
        if keep is not None:
            keep.append(rng)
        data.setdefault("passive_ranges", {})[name] = rng.to_json()
        lines.append(rng.to_text())
    names = scene.build().naming()
    return data, lines, answer_items(margin, ranges, scene.role("period"), names)


def run(args: argparse.Namespace) -> int:
    import sympy as sp

    from hapticproof.systems.discretize import is_rational
    from hapticproof.report.summary import summarize_single_user

    if args.fragment and args.format != "latex":
        raise InputFormatError("--fragment needs --format latex")
    check_output(args.output, "--output")
    if getattr(args, "max_delay", 1) < 0:
        raise InputFormatError("--max-delay must be >= 0")
    if not getattr(args, "deadline", 1.0) > 0:
        raise InputFormatError("--deadline must be a positive number of seconds")
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
    summary = summarize_single_user(model, with_profile=args.profile, full=args.full)
    ranges: list = []
    extra, lines, answers = design_answers(scene, args, args.delay_margin or numeric_but_delay, keep=ranges)
    notes = _loop_notes(scene, model, summary.verdict, ranges)
    if args.format == "json":
        out = summary.to_json()
        if scene.discretize is not None:
            out["continuous_design"] = {"H_s": sp.sstr(scene.environment), "discretize": scene.discretize,
                                        "H_z": sp.sstr(model.H)}
        out.update(summary.names.claims(extra))
        if notes:
            out["exact_loop_notes"] = notes
        text = json.dumps(out, indent=2)
    elif args.format == "latex":
        text = summary.dumps("latex", fragment=args.fragment, answers=answers, remarks=notes)
    else:
        text = "\n".join(head + [summary.to_text(verbose=args.verbose)] + lines + notes)
    write_output(args.output, text)
    if notes and args.format == "latex" and args.fragment:
        print("\n".join(notes), file=sys.stderr)     # a fragment is the derivation only; the note is for the reader
    return 0


def _loop_notes(scene, model, verdict: str, ranges: list) -> list[str]:
    """Where the model's passivity exceeds the exact loop's stability for the scene's mass
    (:func:`hapticproof.analysis.zwidth.loop_notes`): a numeric scene with its mass only."""
    free = {s for s in getattr(model, "parameters", set()) if s != getattr(model, "delay", None)}
    if free or not getattr(model.delay, "is_Integer", False):
        return []
    mass = scene.role("mass")
    if mass is None or scene.resolved_values().get(mass) is None:
        return []
    from hapticproof.analysis.zwidth import loop_notes

    return loop_notes(scene, verdict, ranges)
