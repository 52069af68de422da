"""``hapticproof map QUANTITY [SYSTEM]``: exact passivity or stability maps over a grid of two
parameters of a scene -- the scene of ``derive`` and ``boundary`` (``--scene FILE`` or the same
options: any environment, m users, teleoperators, your names and roles, expressions as values).

Examples (a 100 000-point passivity map of the delayed HVE virtual wall; a filtered wall from a
scene file; three users)::

    hapticproof map passivity --x b=0.0005:0.05:317 --y K=0.1:20:316 \\
        --param T=0.001 --param B=0.001 --delay 3 -o map.csv --plot map.png
    hapticproof map passivity --scene examples/filtered_wall.toml --x K=1:60:60 --y a=0:0.9:10
    hapticproof map passivity multi-user --uniform --x K=0.5:20:40 --y users=1:8:8 \\
        --param b=0.05 --param T=0.001 --param B=0.001 --param K_0=1

Every point is an exact verdict (1 passive/stable, 0 not, -1 undecided); a whole line of the grid
costs one or a few exact computations where the model has the structure for it (see
:mod:`hapticproof.analysis.designmap`). ``--workers N`` uses local processes, ``--scheduler dask``
a Dask ``LocalCluster`` (``--scheduler tcp://host:8786``: a running cluster); results stream to
CSV or Parquet (by the file's suffix) in the same order and with the same values in every mode.
A progress bar is drawn on stderr when it is a terminal.
"""

from __future__ import annotations

import argparse
import sys

from hapticproof.cli.common import (
    LOOP_SYSTEMS,
    add_any_scene_options,
    check_output,
    scene_from_any_args,
)
from hapticproof.core.errors import InputFormatError

__all__ = ["register"]


def register(sub: argparse._SubParsersAction) -> None:
    from hapticproof.systems.choices import QUANTITIES

    parser = sub.add_parser(
        "map",
        help="exact passivity / stability maps over a grid of two parameters of a scene",
        description="Exact verdict at every point of a two-parameter grid of a scene (the scene of 'derive' and "
        "'boundary': --scene FILE or the same options, any environment, m users, teleoperators, your own names "
        "and roles), vectorised per line where the model allows. An axis is a parameter of the scene, delay, or "
        "users (multi-user); every other parameter needs a number (the virtual damping B, B_0 is 0 unless "
        "given). Stability maps need the masses (the mass role, m by default).",
    )
    parser.add_argument("quantity", choices=QUANTITIES)
    parser.add_argument("system", nargs="?", choices=LOOP_SYSTEMS,
                        help="the system (default: the scene file's, else single-user)")
    parser.add_argument("--x", required=True, metavar="NAME=start:stop:count",
                        help="column axis (inclusive, evenly spaced; or NAME=v1,v2,...)")
    parser.add_argument("--y", required=True, metavar="NAME=start:stop:count", help="row axis")
    add_any_scene_options(parser)
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

    check_output(args.output, "--output", (".csv", ".parquet", ".pq"))     # before any work
    check_output(args.plot, "--plot", (".png", ".pdf", ".svg"))
    if args.workers < 1:
        raise InputFormatError("--workers must be at least 1")
    if args.chunk_lines is not None and args.chunk_lines < 1:
        raise InputFormatError("--chunk-lines must be at least 1")
    if args.scheduler is not None and args.scheduler != "dask":
        from hapticproof.analysis.scaleout import scheduler_address

        scheduler_address(args.scheduler)          # a malformed address is one line before any work
    scene = scene_from_any_args(args, LOOP_SYSTEMS, default="single-user")
    spec = designmap.MapSpec.build(args.quantity, args.x, args.y, scene)
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
    if spec.free_translation:
        print("note: the loops keep a free translation (an exact eigenvalue z = 1 that no gain moves), so no point is "
              "asymptotically stable (rho = 1); 'hapticproof boundary' gives the boundary of the relative motion",
              file=sys.stderr)
    if to_file:
        print(f"wrote {args.output}", file=sys.stderr)
    else:
        sys.stdout.write(designmap.write_map(result))
    if args.plot:
        print(f"wrote {designmap.plot_map(result, args.plot)}", file=sys.stderr)
    return 0
