"""A reviewer's 20-display paper audited from a cold process: wall time, CPU time, per-equation times.

Runs ``hapticproof audit --paper FILE --format json --jobs N`` in fresh processes and reports
medians of the wall time and of the CPU time of the process and its workers
(``resource.getrusage(RUSAGE_CHILDREN)``), with the load average before each run (the machine is
shared: a wall time is only comparable with the CPU time and load beside it). Writes
``benchmarks/results/review.json``.

    python benchmarks/bench_review.py [--files examples/reviewer-walls.toml ...] [--jobs 1 2] [--repeat 3]

Goal (issue 20): the 20-display paper ``examples/reviewer-walls.toml`` in under 5 s on two cores
(``--jobs 2``).
"""

from __future__ import annotations

import argparse
import json
import os
import resource
import statistics
import subprocess
import sys
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
RESULTS = ROOT / "benchmarks" / "results"
FILES = ["examples/reviewer-walls.toml", "tests/fixtures/review-walls.toml"]


def cold_run(path: str, jobs: int) -> dict:
    env = dict(os.environ, OPENBLAS_NUM_THREADS="1", OMP_NUM_THREADS="1", MKL_NUM_THREADS="1")
    env.pop("PYTHONDONTWRITEBYTECODE", None)
    cmd = [sys.executable, "-m", "hapticproof", "audit", "--paper", str(ROOT / path), "--format", "json",
           "--jobs", str(jobs)]
    load = os.getloadavg()[0]
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    start = time.perf_counter()
    out = subprocess.run(cmd, capture_output=True, text=True, env=env)
    wall = time.perf_counter() - start
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    if out.returncode not in (0, 1):
        raise SystemExit(f"{' '.join(cmd)} failed: {out.stderr.strip()[-400:]}")
    data = json.loads(out.stdout)
    cpu = (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)
    return {"wall": wall, "cpu": cpu, "load": load, "equations": {e["id"]: (e["verdict"], e["seconds"]) for e in data["equations"]}}


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--files", nargs="+", default=FILES)
    parser.add_argument("--jobs", nargs="+", type=int, default=[2, 1])
    parser.add_argument("--repeat", type=int, default=3)
    args = parser.parse_args(argv)
    results = []
    for path in args.files:
        for jobs in args.jobs:
            runs = [cold_run(path, jobs) for _ in range(args.repeat)]
            per_equation = {k: statistics.median(r["equations"][k][1] for r in runs) for k in runs[0]["equations"]}
            verdicts = {k: v for k, (v, _s) in runs[0]["equations"].items()}
            row = {"file": path, "jobs": jobs, "displays": len(verdicts), "wall_median": round(statistics.median(r["wall"] for r in runs), 2),
                   "walls": [round(r["wall"], 2) for r in runs], "cpu_median": round(statistics.median(r["cpu"] for r in runs), 2),
                   "load_averages": [round(r["load"], 1) for r in runs], "verdicts": verdicts,
                   "slowest": sorted(((round(s, 2), k) for k, s in per_equation.items()), reverse=True)[:5]}
            results.append(row)
            print(f"{path} --jobs {jobs}: wall {row['wall_median']} s (runs {row['walls']}), cpu {row['cpu_median']} s, "
                  f"load {row['load_averages']}; slowest {row['slowest']}")
    RESULTS.mkdir(parents=True, exist_ok=True)
    (RESULTS / "review.json").write_text(json.dumps({"runs": results}, indent=1) + "\n", encoding="utf-8")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
