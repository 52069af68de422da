"""Exact decisions with long delays (n up to 10 000 samples), and the delay margin through them.

The HVE virtual wall (K = 2, B = 0.001, T = 1 ms) with ``b`` 1e-2 and 1e-9 relative above and
below, and exactly at, the exact boundary of each delay: median time of the whole decision with
certificates (``hapticproof.analysis.fastpath.decide``), peak memory (traced Python allocations, and the
resident set of a fresh process deciding n = 10 000), the critical damping ``b*`` alone (one map
line), and a delay-margin search (doubling + bisection over exact decisions). Writes
``benchmarks/results/delays.json`` and ``delays.png``.

    python benchmarks/bench_delays.py [--delays 100 1000 10000] [--repeat 3]
"""

from __future__ import annotations

import argparse
import json
import os
import subprocess
import sys
from pathlib import Path

RESULTS = Path(__file__).resolve().parent / "results"

CHILD = """
import resource, time
from fractions import Fraction
from hapticproof.analysis.fastpath import NumericScene, critical_damping, decide
n = {n}
scene = NumericScene.virtual_wall(K=2, B=Fraction(1, 1000), b=1, T=Fraction(1, 1000), delay=n)
lo, hi = critical_damping(scene)
start = time.perf_counter()
out = decide(scene.with_b(lo))
print(time.perf_counter() - start, out.decision.value, resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024)
"""


def resident(n: int) -> dict:
    """Peak resident set (MB) of a fresh process that imports hapticproof and decides delay n."""
    base = subprocess.run([sys.executable, "-c", "import resource, hapticproof.analysis.fastpath; "
                           "print(resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024)"],
                          capture_output=True, text=True, check=True).stdout.split()
    seconds, decision, peak = subprocess.run([sys.executable, "-c", CHILD.format(n=n)], capture_output=True, text=True,
                                             check=True).stdout.split()
    return {"delay": n, "peak_rss_mb": float(peak), "import_rss_mb": float(base[0]), "decision": decision,
            "seconds_cold": float(seconds)}


def main() -> None:
    from hapticproof.bench.timing import jsonable, machine_info
    from hapticproof.bench.speed import delay_study, margin_search_study, plot_delays

    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--delays", type=int, nargs="+", default=[10, 100, 1000, 3000, 10_000])
    parser.add_argument("--repeat", type=int, default=3)
    parser.add_argument("--output", default=str(RESULTS))
    args = parser.parse_args()
    out = Path(args.output)
    out.mkdir(parents=True, exist_ok=True)
    data = delay_study(delays=args.delays, repeat=args.repeat, log=print)
    data["margin_search"] = margin_search_study(delays=[n for n in args.delays if n <= 3000], repeat=args.repeat,
                                                log=print)
    data["resident"] = resident(max(args.delays))
    print(f"fresh process deciding n = {max(args.delays)}: peak RSS {data['resident']['peak_rss_mb']:.0f} MB "
          f"(import alone {data['resident']['import_rss_mb']:.0f} MB), {data['resident']['seconds_cold']:.2f} s")
    data["machine"] = machine_info() | {"load_average": os.getloadavg()}
    print(f"wrong verdicts: {data['wrong_verdicts']} of {len(data['rows'])}")
    (out / "delays.json").write_text(json.dumps(jsonable(data), indent=1))
    plot_delays(data, out / "delays.png")
    print(f"wrote {out / 'delays.json'}, {out / 'delays.png'}", file=sys.stderr)


if __name__ == "__main__":
    main()
