"""Exact design-space maps: 100 000-point passivity maps serially, on local processes and on Dask.

``hapticproof map passivity --x b=0.0005:0.05:317 --y K=0.1:20:316 --param T=0.001 --param B=0.001
--param delay=N`` for N = 0, 3, 10: one process, ``--workers 2`` and ``--scheduler dask`` (a fresh
``LocalCluster``, start-up included), checking that all three give identical values; and an exact
stability map (K lines over T). Writes ``benchmarks/results/maps.json``, ``map_passivity.png``
and ``map_stability.png``.

    pip install 'hapticproof[dask]'
    python benchmarks/bench_maps.py [--size 316] [--workers 2] [--no-dask]
"""

from __future__ import annotations

import argparse
import json
import os
import sys
from pathlib import Path

RESULTS = Path(__file__).resolve().parent / "results"


def main() -> None:
    from hapticproof.bench.timing import jsonable, machine_info
    from hapticproof.bench.speed import map_study

    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--size", type=int, default=316, help="K values; b has size + 1 (316: 100 172 points)")
    parser.add_argument("--delays", type=int, nargs="+", default=[0, 3, 10])
    parser.add_argument("--workers", type=int, default=2)
    parser.add_argument("--stability-size", type=int, default=100)
    parser.add_argument("--no-dask", action="store_true")
    parser.add_argument("--output", default=str(RESULTS))
    args = parser.parse_args()
    out = Path(args.output)
    out.mkdir(parents=True, exist_ok=True)
    data = map_study(size=args.size, delays=args.delays, workers=args.workers, dask=not args.no_dask,
                     stability_size=args.stability_size, plot=out / "map_passivity.png", log=print)
    data["machine"] = machine_info() | {"load_average": os.getloadavg()}
    (out / "maps.json").write_text(json.dumps(jsonable(data), indent=1))
    print(f"wrote {out / 'maps.json'}, {out / 'map_passivity.png'}, {out / 'map_stability.png'}", file=sys.stderr)


if __name__ == "__main__":
    main()
