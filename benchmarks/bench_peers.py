"""End-to-end numeric passivity decisions: hapticproof against python-control, side by side.

For the HVE forward-difference virtual wall (K = 2, B = 0.001, T = 1 ms) with delays 0, 3, 10 and
``b`` at 1e-2, 1e-6 and 1e-9 relative above and below the exact boundary, both libraries decide
the same 18 scenes in this process: hapticproof builds the scene from numbers and returns the
whole positive-real decision with certificates (``hapticproof.analysis.fastpath.decide``), through
its public API (``positive_real(SingleUserScene.virtual_wall(...))``) and through
``hapticproof.ispassive`` on the peer's transfer function; python-control builds ``G^-1`` as a
transfer function and calls ``control.ispassive`` (its KYP LMI, solved by cvxopt), once as it is and
once with the integrator pole damped to ``z = 1 - 1e-6``. The methods are called in turn,
``--repeat`` times, and their medians compared; every verdict is judged against the exact answer.
Writes
``benchmarks/results/peers.json`` and ``peers.png``.

    pip install 'hapticproof[bench]'          # python-control + cvxopt (else the peer column is skipped)
    python benchmarks/bench_peers.py [--repeat 15]
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
    from hapticproof.bench.speed import peer_study, plot_peers

    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeat", type=int, default=15)
    parser.add_argument("--delays", type=int, nargs="+", default=[0, 3, 10])
    parser.add_argument("--output", default=str(RESULTS))
    args = parser.parse_args()
    out = Path(args.output)
    out.mkdir(parents=True, exist_ok=True)
    data = peer_study(delays=args.delays, repeat=args.repeat, log=print)
    data["machine"] = machine_info() | {"load_average": os.getloadavg()}
    summary = data["summary"]
    print()
    for name, s in summary.items():
        if isinstance(s, dict):
            ratio = f", {s['median_ratio_to_hapticproof']:.1f}x hapticproof's median" if "median_ratio_to_hapticproof" in s else ""
            if "median_ratio_to_ispassive" in s:
                ratio += f", {s['median_ratio_to_ispassive']:.3f} of control.ispassive's"
            print(f"{name:40s} median {s['median_seconds'] * 1e3:7.2f} ms, max {s['max_seconds'] * 1e3:7.1f} ms, "
                  f"wrong verdicts {s['wrong_verdicts']} of {s['of']}{ratio}")
    if "peer_note" in summary:
        print(summary["peer_note"])
    (out / "peers.json").write_text(json.dumps(jsonable(data), indent=1))
    plot_peers(data, out / "peers.png")
    print(f"wrote {out / 'peers.json'}, {out / 'peers.png'}", file=sys.stderr)


if __name__ == "__main__":
    main()
