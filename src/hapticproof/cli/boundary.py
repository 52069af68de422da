"""``hapticproof boundary SYSTEM``: exact stability boundaries along a parameter sweep.

Example::

    hapticproof boundary single-user --param m=0.015 --param b=0.02 --param B=0 \\
        --operator '-z_a + 1/s' --param z_a=0.01 --vary K --over T=0.001:0.02:20 \\
        --plot out.png --csv out.csv

prints one line per grid point (``T  K_exact  K_printed  ratio``) and writes the CSV
(columns ``T, K_exact, K_printed``; the printed column is empty where no printed condition
applies), a JSON file with the full boundary records and a PNG plot. The scene is the one of
``derive`` (``--scene FILE`` or the same options: any environment, per-user couplings and delays,
any controller), with the masses as parameters; without ``--over`` one boundary is computed at
the scene's values. ``-`` as a CSV or JSON file is standard output (the table then goes to
standard error); every output file is checked before the work starts.
"""

from __future__ import annotations

import argparse
import math
import sys

import json

from hapticproof.cli.common import add_any_scene_options
from hapticproof.cli.terminal import ProgressBar, progress_bar  # noqa: F401 - ProgressBar re-exported
from hapticproof.core.errors import InputFormatError

__all__ = ["register", "handler", "ProgressBar"]


SYSTEMS = ("single-user", "multi-user", "teleoperator")


def register(subparsers: argparse._SubParsersAction) -> None:
    parser = subparsers.add_parser(
        "boundary",
        help="exact sampled-data stability boundaries (spectral radius of the exact ZOH loop)",
        description="Stability boundary of one parameter (--vary) of a scene -- the same scene as 'derive' "
        "(options or --scene FILE), plus the device masses m (m_1.. or m_m, m_s) -- at the scene's values or "
        "along a sweep of another parameter (--over), next to the borderline of the paper's printed "
        "condition when the scene is the paper's own. The virtual damping B (B_0) is 0 unless given.",
    )
    parser.add_argument("system", nargs="?", choices=SYSTEMS, help="the system (default: the scene file's)")
    add_any_scene_options(parser)
    parser.add_argument("--vary", required=True, help="parameter whose boundary is sought (e.g. K, B_0, K_i)")
    parser.add_argument("--over", metavar="NAME=start:stop:count",
                        help="sweep, e.g. T=0.001:0.02:20 (default: one boundary at the scene's values)")
    parser.add_argument("--search", metavar="lo:hi", help="search interval of --vary")
    parser.add_argument("--rtol", type=float, default=1e-10, help="relative tolerance")
    parser.add_argument("--workers", type=int, default=None, help="processes (default: auto)")
    parser.add_argument("--plot", metavar="FILE", help="plot (.png, .pdf or .svg)")
    parser.add_argument("--csv", metavar="FILE", help="CSV of the curve ('-': standard output)")
    parser.add_argument("--json", metavar="FILE", help="JSON of the boundaries ('-': standard output)")
    parser.add_argument("--no-progress", action="store_true", help="no progress bar")
    parser.set_defaults(handler=handler)


def _search(text: str | None) -> tuple[float, float] | None:
    if text is None:
        return None
    parts = text.split(":")
    try:
        lo, hi = (float(p) for p in parts)
    except ValueError as err:
        raise InputFormatError(f"--search expects lo:hi, got {text!r}") from err
    if not (math.isfinite(lo) and math.isfinite(hi)):
        raise InputFormatError(f"--search needs finite numbers, got {text!r}")
    if not hi > lo:
        raise InputFormatError(f"--search needs lo < hi, got {text!r}")
    return lo, hi


def _scene(args: argparse.Namespace):
    from hapticproof.cli.common import scene_from_any_args

    return scene_from_any_args(args, SYSTEMS)


def handler(args: argparse.Namespace) -> int:
    from hapticproof.cli.common import check_output, write_text
    from hapticproof.analysis.borderlines import printed_borderline
    from hapticproof.analysis.maps import boundary_curve, find_boundary, grid, plot_curves
    from hapticproof.analysis.stability import SceneLoops

    # every output is checked before the work starts
    check_output(args.plot, "--plot", (".png", ".pdf", ".svg"))
    check_output(args.csv, "--csv")
    check_output(args.json, "--json")
    if not (0 < args.rtol < 1):
        raise InputFormatError("--rtol must be in (0, 1)")
    search = _search(args.search)
    spec = _scene(args)
    given = {item.partition("=")[0].strip() for item in args.param}
    over_name, over_values = grid(args.over) if args.over is not None else (None, None)
    if args.vary == over_name:
        raise InputFormatError("--vary and --over must name different parameters")
    if args.vary in given or over_name in given:
        raise InputFormatError("--vary/--over parameters must not also be fixed with --param")
    # a value in the scene file is the design point: the boundary varies it
    spec = spec.with_params({args.vary: None, **({over_name: None} if over_name else {})})
    # the virtual damping is 0 unless given (as the papers' stability studies)
    unset = {"B", "B_0"} & spec.names() - set(dict(spec.params)) - {args.vary, over_name}
    if unset:
        spec = spec.with_params({name: 0 for name in unset})
    loops = SceneLoops(spec)
    if args.over is None:
        if args.csv or args.plot:
            raise InputFormatError("--csv and --plot draw a curve: give --over NAME=start:stop:count")
        loops.scene(**{args.vary: 1.0})        # fail early, clearly
        bnd = find_boundary(loops, args.vary, search=search, rtol=args.rtol)
        out = sys.stderr if args.json == "-" else sys.stdout     # standard output is the JSON's
        if bnd.value is None:
            print(f"{args.vary}: {bnd.note}", file=out)
        else:
            more = f"; {len(bnd.crossings)} crossings: " + ", ".join(f"{c.value:.10g} ({c.direction})" for c in bnd.crossings) \
                if bnd.multiple else ""
            certified = "" if bnd.certified else f"; NOT certified: {bnd.note}"
            relative = ("; the free translation (z = 1, which no gain moves) is set aside: the boundary of the relative "
                        "motion, no point is asymptotically stable") if bnd.translation else ""
            print(f"{args.vary}* = {bnd.value:.10g} +- {bnd.tolerance:.2g} ({bnd.direction}: spectral radius of the exact "
                  f"ZOH loop crosses 1){more}{certified}{relative}", file=out)
        if args.json:
            write_text(args.json, json.dumps(bnd.to_json(), indent=1))
        return 0
    loops.scene(**{args.vary: 1.0, over_name: float(over_values[0])})  # fail early, clearly
    border = printed_borderline(loops, args.vary) if loops.is_paper_scene() else None
    bar = None if args.no_progress else progress_bar(sys.stderr, "boundary")  # a terminal only
    curve = boundary_curve(
        loops, args.vary, (over_name, over_values), printed_borderline=border,
        search=search, rtol=args.rtol, workers=args.workers,
        progress=bar,
    )
    vary = args.vary
    to_stdout = "-" in (args.csv, args.json)
    lines = [f"{over_name:>12} {vary + '_exact':>18} {vary + '_printed':>18} {'ratio':>9}  notes"]
    for x, bnd, printed in zip(curve.grid, curve.boundaries, curve.printed):
        exact = "none" if bnd.value is None else f"{bnd.value:.10g}"
        pr = "" if printed is None else f"{printed:.10g}"
        ratio = (
            f"{bnd.value / printed:.5f}" if bnd.value is not None and printed not in (None, 0) else ""
        )
        notes = []
        if bnd.multiple:
            notes.append(f"{len(bnd.crossings)} crossings")
        if bnd.value is not None and bnd.direction == "stabilising":
            notes.append("stabilising")
        if bnd.value is None:
            notes.append(("stable" if bnd.stable_at_start else "unstable") + f" at all {bnd.scan_points} scan points")
        elif not bnd.certified:
            notes.append("not certified")
        lines.append(f"{x:>12.6g} {exact:>18} {pr:>18} {ratio:>9}  {', '.join(notes)}")
    print("\n".join(lines), file=sys.stderr if to_stdout else sys.stdout)
    if args.csv:
        write_text(args.csv, curve.to_csv())
    if args.json:
        write_text(args.json, json.dumps(curve.to_json(), indent=1))
    if args.plot:
        title = f"{spec.system}: {vary}*({over_name})"
        period = spec.role("period")
        plot_curves([curve], args.plot, title=title, scale={period: 1000} if over_name == period else None)
    return 0
