"""``hapticproof boundary SYSTEM``: exact stability boundaries along a parameter sweep.

Example::

    hapticproof boundary single-user --param m=0.015 --param b=0.02 --param B=0 \\
        --operator '-z_a + 1/s' --param z_a=0.01 --vary K --over T=0.001:0.02:20 \\
        --plot out.png --csv out.csv

prints one line per grid point (``T  K_exact  K_printed  ratio``) and writes the CSV
(columns ``T, K_exact, K_printed``; the printed column is empty where no printed condition
applies), a JSON file with the full boundary records and a PNG plot.
"""

from __future__ import annotations

import argparse
import sys

from hapticproof.borderlines import printed_borderline
from hapticproof.cli._common import add_param_option, parse_params
from hapticproof.cli._terminal import ProgressBar, progress_bar
from hapticproof.errors import InputFormatError
from hapticproof.maps import SYSTEMS, SceneFamily, boundary_curve, grid, plot_curves

__all__ = ["register", "handler", "ProgressBar"]


def register(subparsers: argparse._SubParsersAction) -> None:
    parser = subparsers.add_parser(
        "boundary",
        help="exact sampled-data stability boundaries (spectral radius of the exact ZOH loop)",
        description="Stability boundary of one parameter (--vary) along a sweep of another "
        "(--over), next to the borderline of the paper's printed condition.",
    )
    parser.add_argument("system", choices=SYSTEMS)
    add_param_option(parser)
    parser.add_argument("--operator", help="operator impedance Z_h(s), e.g. '-z_a + 1/s' "
                        "(teleoperator: master termination; 'clamped' allowed)")
    parser.add_argument("--environment", help="teleoperator slave termination: an impedance "
                        "in s or 'clamped' (default: free)")
    parser.add_argument("--delay", type=int, default=0, help="delay in samples (t_d = n T)")
    parser.add_argument("--users", type=int, default=2, help="multi-user: number of users")
    parser.add_argument("--vary", required=True, help="parameter whose boundary is sought (K)")
    parser.add_argument("--over", required=True, metavar="NAME=start:stop:count",
                        help="sweep, e.g. T=0.001:0.02:20")
    parser.add_argument("--search", metavar="lo:hi", help="search interval of --vary")
    parser.add_argument("--rtol", type=float, default=1e-10, help="relative tolerance")
    parser.add_argument("--workers", type=int, default=None, help="processes (default: auto)")
    parser.add_argument("--plot", metavar="PNG")
    parser.add_argument("--csv", metavar="CSV")
    parser.add_argument("--json", metavar="JSON")
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
    if not hi > lo:
        raise InputFormatError(f"--search needs lo < hi, got {text!r}")
    return lo, hi


def handler(args: argparse.Namespace) -> int:
    params = parse_params(args.param)
    over_name, over_values = grid(args.over)
    if args.vary == over_name:
        raise InputFormatError("--vary and --over must name different parameters")
    if args.vary in params or over_name in params:
        raise InputFormatError("--vary/--over parameters must not also be fixed with --param")
    if not (0 < args.rtol < 1):
        raise InputFormatError("--rtol must be in (0, 1)")
    family = SceneFamily(
        args.system, params, operator=args.operator, environment=args.environment,
        delay=args.delay, users=args.users,
    )
    family.scene(**{args.vary: 1.0, over_name: float(over_values[0])})  # fail early, clearly
    border = printed_borderline(family, args.vary)
    bar = None if args.no_progress else progress_bar(sys.stderr, "boundary")  # a terminal only
    curve = boundary_curve(
        family, args.vary, (over_name, over_values), printed_borderline=border,
        search=_search(args.search), rtol=args.rtol, workers=args.workers,
        progress=bar,
    )
    vary = args.vary
    print(f"{over_name:>12} {vary + '_exact':>18} {vary + '_printed':>18} {'ratio':>9}  notes")
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
            notes.append("stable" if bnd.stable_at_start else "unstable" + " throughout search")
        print(f"{x:>12.6g} {exact:>18} {pr:>18} {ratio:>9}  {', '.join(notes)}")
    if args.csv:
        curve.to_csv(args.csv)
    if args.json:
        curve.to_json(args.json)
    if args.plot:
        title = f"{args.system}: {vary}*({over_name})"
        plot_curves([curve], args.plot, title=title, scale={"T": 1000} if over_name == "T" else None)
    return 0
