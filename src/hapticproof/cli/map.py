"""``hapticproof map QUANTITY``: exact passivity or stability maps over a grid of two parameters.

Example (a 100 000-point passivity map of the delayed HVE virtual wall)::

    hapticproof map passivity --x b=0.0005:0.05:317 --y K=0.1:20:316 \\
        --param T=0.001 --param B=0.001 --param delay=3 -o map.csv --plot map.png

Every point is an exact verdict (1 passive/stable, 0 not, -1 undecided); a whole line of the grid
costs one or a few exact computations (see :mod:`hapticproof.analysis.designmap`). ``--workers N`` uses
local processes, ``--scheduler dask`` a Dask ``LocalCluster`` (``--scheduler tcp://host:8786``: a
running cluster); results stream to CSV or Parquet (by the file's suffix) in the same order and
with the same values in every mode. A progress bar is drawn on stderr when it is a terminal.
"""

from __future__ import annotations

import argparse
import sys

from hapticproof.cli.common import add_param_option, check_output, parse_params
from hapticproof.core.errors import InputFormatError

__all__ = ["register"]


def register(sub: argparse._SubParsersAction) -> None:
    from hapticproof.analysis.designmap import PARAMETERS, QUANTITIES

    parser = sub.add_parser(
        "map",
        help="exact passivity / stability maps over a grid of two parameters",
        description="Exact verdict at every point of a two-parameter grid, vectorised per line. "
        f"Passivity parameters: {', '.join(PARAMETERS['passivity'])} (HVE discrete model, virtual wall); "
        f"stability parameters: {', '.join(PARAMETERS['stability'])} (device of mass m on the delayed wall).",
    )
    parser.add_argument("quantity", choices=QUANTITIES)
    parser.add_argument("--x", required=True, metavar="NAME=start:stop:count",
                        help="column axis (inclusive, evenly spaced; or NAME=v1,v2,...)")
    parser.add_argument("--y", required=True, metavar="NAME=start:stop:count", help="row axis")
    add_param_option(parser)
    parser.add_argument("--approximation", default="forward", choices=("forward", "backward", "tustin"),
                        help="integrator approximation (passivity maps)")
    parser.add_argument("--workers", type=int, default=1, metavar="N",
                        help="local worker processes (with --scheduler dask: the LocalCluster's workers)")
    parser.add_argument("--scheduler", metavar="dask|ADDRESS",
                        help="run on Dask: 'dask' starts a LocalCluster, tcp://host:port uses a running one")
    parser.add_argument("--chunk-lines", type=int, metavar="L", help="grid lines per chunk (default: automatic)")
    parser.add_argument("--output", "-o", metavar="FILE", help="write the map (.csv, or .parquet with pyarrow)")
    parser.add_argument("--plot", metavar="FILE.png", help="draw the map")
    parser.set_defaults(handler=run)


def run(args: argparse.Namespace) -> int:
    from hapticproof.analysis import designmap
    from hapticproof.analysis.scaleout import ProgressBar

    check_output(args.output, "--output")                                  # before any work
    check_output(args.plot, "--plot", (".png", ".pdf", ".svg"))
    if args.workers < 1:
        raise InputFormatError("--workers must be at least 1")
    if args.chunk_lines is not None and args.chunk_lines < 1:
        raise InputFormatError("--chunk-lines must be at least 1")
    spec = designmap.MapSpec.build(args.quantity, args.x, args.y, parse_params(args.param), args.approximation)
    to_file = bool(args.output) and args.output != "-"           # "-" is standard output, as everywhere
    sink = designmap.MapWriter(args.output, spec) if to_file else None
    bar = ProgressBar(1, f"{args.quantity} map")
    complete = False
    try:
        result = designmap.compute(spec, workers=args.workers, scheduler=args.scheduler,
                                   lines_per_chunk=args.chunk_lines, progress=bar, sink=sink)
        complete = True
    finally:
        bar.close()
        if sink is not None:
            sink.close(ok=complete)     # an incomplete map never replaces the target
    counts = ", ".join(f"{k}: {v}" for k, v in result.counts.items())
    print(f"{spec.points} points ({spec.lines} lines along {spec.x.name if spec.line_axis == 'x' else spec.y.name}) "
          f"in {result.seconds:.2f} s [{result.settings['mode']}]; {counts}", file=sys.stderr)
    if to_file:
        print(f"wrote {args.output}", file=sys.stderr)
    else:
        sys.stdout.write(designmap.write_map(result))
    if args.plot:
        print(f"wrote {designmap.plot_map(result, args.plot)}", file=sys.stderr)
    return 0
