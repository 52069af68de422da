"""Wall time of the audit from a cold process, and time per derivation.

Runs ``hapticproof audit PAPER --format json`` in fresh processes (cold: imports and caches
included), repeats, and reports medians; the per-equation times come from the JSON's
``seconds``. Writes ``benchmarks/results/audit.json`` and a bar plot of the slowest equations.

    python benchmarks/bench_audit.py [--papers all hve-single-user hve ...] [--jobs 1 2] [--repeat 3]

``all`` is the whole audit (``hapticproof audit --all``; goal: 12 s cold on this 2-core machine
with ``--jobs 2``); ``hve-single-user`` is the HVE paper's Sections 1-3.1 (``hapticproof audit
hve -s 1 -s 2 -s 3.1``; goal: under 5 s cold on one core); any other name is a paper id (the whole
paper). ``--jobs 1`` runs pinned to one core (``taskset -c 0``), ``--jobs N`` (N > 1) on all cores
with N worker processes (``hapticproof audit --jobs N``).
"""

from __future__ import annotations

import argparse
import json
import os
import statistics
import subprocess
import sys
import time
from pathlib import Path

RESULTS = Path(__file__).resolve().parent / "results"
#: named audit targets: (paper, sections); an empty section list audits the whole paper
TARGETS = {"hve-single-user": ("hve", ["1", "2", "3.1"])}


def cold_run(target: str | None, single_core: bool = True, jobs: int = 1) -> tuple[float, dict]:
    env = dict(os.environ)
    env.pop("PYTHONDONTWRITEBYTECODE", None)   # a fresh process with Python's bytecode cache, as users run it
    env.update(OPENBLAS_NUM_THREADS="1", OMP_NUM_THREADS="1", MKL_NUM_THREADS="1")
    paper, sections = TARGETS.get(target, (None if target == "all" else target, []))
    cmd = [sys.executable, "-m", "hapticproof", "audit", "--format", "json", "--jobs", str(jobs)]
    cmd += [paper] if paper else ["--all"]
    cmd += [arg for section in sections for arg in ("--section", section)]
    if single_core and jobs == 1 and sys.platform.startswith("linux"):
        cmd = ["taskset", "-c", "0"] + cmd
    start = time.perf_counter()
    out = subprocess.run(cmd, capture_output=True, text=True, env=env, check=True).stdout
    data = json.loads(out)
    if "papers" in data:       # several papers: one flat list of equations
        data = {"equations": [dict(eq, id=f"{p['paper']}:{eq['id']}") for p in data["papers"] for eq in p["equations"]]}
    return time.perf_counter() - start, data


def derivation_times(repeat: int) -> dict[str, float]:
    """Median time of each single-user derivation (cold scene cache, warm process)."""
    from hapticproof.core.lazy import clear
    from hapticproof.systems.singleuser import SingleUserScene
    from hapticproof.report.summary import summarize_single_user

    cases = {
        "symbolic forward": dict(),
        "symbolic tustin delay 3": dict(approximation="tustin", delay=3),
        "symbolic delay n": dict(delay="n"),
        "numeric forward": dict(K=2, B=0, b="0.0011", T="0.001"),
        "numeric delay 10": dict(K=2, B="0.0001", b="0.03", T="0.001", delay=10),
        "numeric delay 100": dict(K=2, B="0.0001", b="0.3", T="0.001", delay=100),
    }
    out = {}
    for name, kw in cases.items():
        if kw.get("delay") == "n":
            from hapticproof.systems.singleuser import SYMBOLS

            kw = dict(kw, delay=SYMBOLS["n"])
        times = []
        for _ in range(repeat):
            scene = SingleUserScene.virtual_wall(**kw)
            clear(scene)
            start = time.perf_counter()
            summarize_single_user(scene)
            times.append(time.perf_counter() - start)
        out[name] = statistics.median(times)
    return out


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__)
    parser.add_argument("--papers", nargs="*", default=["all", "hve-single-user", "hve"])
    parser.add_argument("--jobs", type=int, nargs="+", default=[1, len(os.sched_getaffinity(0))],
                        help="worker processes to measure (1: pinned to one core)")
    parser.add_argument("--repeat", type=int, default=3)
    args = parser.parse_args()
    RESULTS.mkdir(parents=True, exist_ok=True)
    report: dict = {"machine": {"cpus": os.cpu_count(), "python": sys.version.split()[0],
                                "load_average": os.getloadavg()}, "papers": {}}
    for paper in args.papers:
        for jobs in sorted(set(args.jobs)):
            walls, per_equation = [], {}
            for _ in range(args.repeat):
                wall, data = cold_run(paper, jobs=jobs)
                walls.append(wall)
                for eq in data["equations"]:
                    per_equation.setdefault(eq["id"], []).append(eq["seconds"])
            medians = {k: statistics.median(v) for k, v in per_equation.items()}
            key = paper if jobs == 1 else f"{paper} --jobs {jobs}"
            report["papers"][key] = {
                "jobs": jobs,
                "cold_wall_seconds_median": statistics.median(walls),
                "cold_wall_seconds": walls,
                "equations": len(medians),
                "sum_of_equation_seconds": sum(medians.values()),
                "slowest": sorted(medians.items(), key=lambda kv: -kv[1])[:10],
            }
            print(f"{key}: cold wall median {statistics.median(walls):.2f} s over {args.repeat} runs; "
                  f"{len(medians)} equations ({sum(medians.values()):.1f} s of derivations); slowest: "
                  + ", ".join(f"{k} {v:.2f}s" for k, v in report["papers"][key]["slowest"][:5]))
    report["derivations_seconds_median"] = derivation_times(args.repeat)
    for name, t in report["derivations_seconds_median"].items():
        print(f"derivation {name}: {t * 1000:.1f} ms")
    (RESULTS / "audit.json").write_text(json.dumps(report, indent=2))
    try:
        import matplotlib

        matplotlib.use("Agg")
        import matplotlib.pyplot as plt

        fig, ax = plt.subplots(figsize=(7, 4))
        for paper, data in report["papers"].items():
            names = [k for k, _ in data["slowest"]][::-1]
            ax.barh([f"{paper}:{n}" for n in names], [v for _, v in data["slowest"]][::-1])
        ax.set_xlabel("seconds (median)")
        ax.set_title("slowest audited equations")
        fig.tight_layout()
        fig.savefig(RESULTS / "audit.png", dpi=120)
    except ImportError:  # pragma: no cover
        pass


if __name__ == "__main__":
    main()
