"""``hapticproof zwidth``: the Z-width of a haptic device (Colgate & Brown 1994) -- the stiffness and
damping of the virtual wall it renders passively, with the exact sampled-data stability boundary
for its mass overlaid.

Examples::

    hapticproof zwidth --param b=0.02 --param T=0.001 --param m=0.015 -o zwidth.csv --plot zwidth.png
    hapticproof zwidth --approximation tustin --delay 1 --param b=0.02 --param T=0.001 --param m=0.015
    hapticproof zwidth --scene device.toml --stiffness K=0:80:161 --damping B=0:0.02:41

The device is a single-user scene (``--scene FILE`` or the options of ``derive single-user``, your
names and roles); the plane is its wall's stiffness and damping (``K`` and ``B``, or the names
``--stiffness``/``--damping`` give). Every grid point is an exact verdict of the one map system;
each damping value gets the exact passive range of the stiffness and the certified critical
stiffness of the exact ZOH loop (:mod:`hapticproof.analysis.zwidth`).
"""

from __future__ import annotations

import argparse
import sys

from hapticproof.cli.common import add_scene_options, check_output, scene_from_args, write_text
from hapticproof.core.errors import InputFormatError

__all__ = ["register"]


def register(sub: argparse._SubParsersAction) -> None:
    parser = sub.add_parser(
        "zwidth",
        help="the Z-width of a device: passive stiffness-damping region and the exact loop's stability boundary",
        description="The Z-width of a haptic device (Colgate & Brown 1994): the stiffness-damping pairs of the "
        "virtual wall its model renders passively (exact, at every grid point and as the passive range of the "
        "stiffness at every damping) with the exact ZOH sampled-data stability boundary for its mass overlaid "
        "(certified). The device is the scene of 'derive single-user' (--scene FILE or the same options); its "
        "damping, period and delay must be numbers, its mass gives the stability overlay.",
    )
    add_scene_options(parser, "single-user")
    parser.add_argument("--stiffness", metavar="NAME=start:stop:count",
                        help="the stiffness axis (default K from 0 to past both boundaries at zero damping, 81 values; "
                        "start:stop:count names K)")
    parser.add_argument("--damping", metavar="NAME=start:stop:count",
                        help="the damping axis (default B from 0 to the device damping, 41 values; start:stop:count "
                        "names B)")
    parser.add_argument("--workers", type=int, default=1, metavar="N", help="local worker processes for the maps")
    parser.add_argument("--scheduler", metavar="dask|ADDRESS", help="run the maps on Dask (as 'map')")
    parser.add_argument("--output", "-o", metavar="FILE.csv",
                        help="the Z-width as CSV: one row per damping value ('-': standard output)")
    parser.add_argument("--plot", metavar="FILE.png", help="draw the Z-width (.png, .pdf or .svg)")
    parser.set_defaults(handler=run)


def run(args: argparse.Namespace) -> int:
    from hapticproof.analysis.zwidth import zwidth

    check_output(args.output, "--output", (".csv",) if args.output not in (None, "-") else ())
    check_output(args.plot, "--plot", (".png", ".pdf", ".svg"))
    if args.workers < 1:
        raise InputFormatError("--workers must be at least 1")
    scene = scene_from_args(args, "single-user")
    result = zwidth(scene, stiffness=args.stiffness, damping=args.damping, workers=args.workers,
                    scheduler=args.scheduler)
    to_stdout = args.output == "-"
    print(result.to_text(), file=sys.stderr if to_stdout else sys.stdout)
    if args.output:
        path = write_text(args.output, result.to_csv())
        if path is not None:
            print(f"wrote {path}", file=sys.stderr)
    if args.plot:
        print(f"wrote {result.plot(args.plot)}", file=sys.stderr)
    return 0
