"""``hapticproof bench``: run time against error, numerical stress and lazy-pipeline studies."""

from __future__ import annotations

import argparse
import sys

from hapticproof.core.errors import InputFormatError

__all__ = ["register"]

TASKS = ("margin", "boundary", "stress", "audit", "lazy", "peers", "delays", "maps")
#: The figures each study writes into the output folder.
_FIGURES = (("margin", "margin.png"), ("boundary", "boundary.png"), ("peers", "peers.png"), ("delays", "delays.png"),
            ("maps", "map_passivity.png"))


def register(sub: argparse._SubParsersAction) -> None:
    parser = sub.add_parser(
        "bench",
        help="benchmark run time against error (JSON + PNG)",
        description="Side-by-side studies: passivity margin (float grids, mpmath grids, exact), "
        "stability boundary (simulation, spectral, exact), cold audit time (one core and --jobs), lazy vs "
        "full pipeline, whole decisions against python-control (peers), long delays, exact maps. "
        "Writes <task>.json and PNG plots into the output directory.",
    )
    parser.add_argument("--tasks", nargs="+", default=list(TASKS), metavar="TASK",
                        help=f"studies to run (default: all of {', '.join(TASKS)})")
    parser.add_argument("--quick", action="store_true", help="small sizes (minutes -> seconds)")
    parser.add_argument("--repeat", type=int, default=3, help="repeats per measurement (median)")
    parser.add_argument("--output", "-o", default="benchmarks/results", metavar="DIR")
    parser.set_defaults(handler=run)


def run(args: argparse.Namespace) -> int:
    unknown = [t for t in args.tasks if t not in TASKS]
    if unknown:
        raise InputFormatError(f"unknown task(s) {unknown}; choose from {', '.join(TASKS)}")
    if args.repeat < 1:
        raise InputFormatError("--repeat must be at least 1")
    from hapticproof.core.files import check_output_folder

    outputs = [f"{task}.json" for task in args.tasks] + ["summary.json"] + [
        name for task, name in _FIGURES if task in args.tasks]
    check_output_folder(args.output, "--output", outputs)      # before any work
    from hapticproof.bench.accuracy import run as run_studies
    from hapticproof.cli.terminal import progress_bar

    bar = progress_bar(sys.stderr, "bench")  # a terminal only

    def log(line: str) -> None:
        if bar is not None:
            bar.clear()
        print(line, file=sys.stderr)

    run_studies(args.tasks, args.output, quick=args.quick, repeat=args.repeat, log=log, progress=bar)
    print(f"wrote {args.output}/<task>.json and PNG plots", file=sys.stderr)
    return 0
