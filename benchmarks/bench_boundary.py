"""Boundary K*(T): Simulink-style simulation + bisection vs the spectral method, side by side.

For each case and tolerance, three methods find the stability boundary in K:

* ``simulation`` -- the Simulink-style method: simulate the exact sampled-data loop sample by
  sample from an initial state exciting every mode over a horizon of ``~1/tol`` samples
  (capped), call it unstable when the state norm grows over the second half, and bisect on K
  from the bracket [0.5, 2] x the printed borderline (as the papers start from the theory);
* ``doubling`` -- the same exact propagation over 2**52 samples by repeated squaring, with
  the same bisection;
* ``spectral`` -- spectral radius of the exact closed loop, Brent's method in the same
  bracket, certified tolerance (hapticproof.analysis.maps.find_boundary with ``search``);
* ``spectral-auto`` -- the full default pipeline: automatic bracket by doubling, a 48-point
  batched scan for multiple crossings, Brent, certification.

The speed-up is reported at matched accuracy: for each simulation run, the cheapest spectral
run whose error is at least as small.

Errors are against a 50-digit reference (mpmath spectral boundary, and for the free device
also the closed form). Wall times are medians over repeats, all methods in one run.
Writes benchmarks/results/bench_boundary.{json,png}.

Run:  python benchmarks/bench_boundary.py [--repeats 3] [--quick]
"""

from __future__ import annotations

import os

os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")  # tiny matrices: BLAS threads only add overhead

import argparse
import json
import math
import statistics
import time
from pathlib import Path

import mpmath

from hapticproof.analysis.borderlines import printed_borderline
from hapticproof.analysis.maps import SceneFamily, find_boundary, refine_boundary_mp
from hapticproof.analysis.sampled import free_device_boundary

RESULTS = Path(__file__).parent / "results"

CASES = {
    "free device, T=1ms (HVE Fig. 9a)": (
        SceneFamily("single-user", {"m": 0.015, "b": 0.01822, "B": 0}), {"T": 0.001}),
    "z_a=0.5b, t_d=10T, T=2ms (HVE Fig. 8b)": (
        SceneFamily("single-user", {"m": 0.15, "b": 0.2, "B": 0, "z_a": 0.1},
                    operator="-z_a + 1/s", delay=10), {"T": 0.002}),
}


def timed(func, repeats):
    times, result = [], None
    for _ in range(repeats):
        start = time.perf_counter()
        result = func()
        times.append(time.perf_counter() - start)
    return result, statistics.median(times)


def reference(family, at):
    bnd = find_boundary(family, "K", at=at, rtol=1e-13)
    value, width = refine_boundary_mp(family, "K", (bnd.value * (1 - 1e-8), bnd.value * (1 + 1e-8)),
                                      at=at, dps=50, tol=mpmath.mpf(10) ** -40)
    return value, width


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeats", type=int, default=3)
    parser.add_argument("--quick", action="store_true", help="fewer tolerances, shorter horizons")
    args = parser.parse_args()
    tolerances = [1e-2, 1e-3, 1e-4] if args.quick else [1e-2, 1e-3, 1e-4, 1e-5, 1e-6]
    cap = 20_000 if args.quick else 200_000
    rows = []
    for name, (family, at) in CASES.items():
        ref, width = reference(family, at)
        check = None
        if family.operator is None and family.delay == 0:
            check = float(abs(ref - free_device_boundary(0.015, 0.01822, at["T"], "mp", 50)) / ref)
        print(f"\n{name}: K* = {mpmath.nstr(ref, 20)} (50-digit, +/- {mpmath.nstr(width, 2)})"
              + (f"; closed form agrees to {check:.1e}" if check is not None else ""))
        guess = printed_borderline(family, "K")(family.printed_values(**at))
        bracket = (0.5 * guess, 2.0 * guess)
        for tol in tolerances:
            steps = min(cap, int(math.ceil(1 / tol)))
            runs = {
                "simulation": lambda: find_boundary(family, "K", at=at, search=bracket, scan=2,
                                                    rtol=tol, method="steps", steps=steps),
                "doubling": lambda: find_boundary(family, "K", at=at, search=bracket, scan=2,
                                                  rtol=tol, method="doubling"),
                "spectral": lambda: find_boundary(family, "K", at=at, search=bracket, scan=2,
                                                  rtol=tol),
                "spectral-auto": lambda: find_boundary(family, "K", at=at, rtol=tol),
            }
            for method, func in runs.items():
                reps = 1 if method == "simulation" and steps > 50_000 else args.repeats
                bnd, seconds = timed(func, reps)
                error = abs(bnd.value - float(ref)) / float(ref) if bnd.value else math.nan
                rows.append({"case": name, "method": method, "rtol": tol, "horizon": steps
                             if method == "simulation" else (2**52 if method == "doubling" else None),
                             "relative_error": error, "seconds": seconds,
                             "evaluations": bnd.evaluations, "reference": str(ref)})
                print(f"  tol={tol:.0e} {method:>10}: error {error:9.2e}  time {seconds * 1e3:9.2f} ms"
                      f"  ({bnd.evaluations} evaluations)")
        for sim in [r for r in rows if r["case"] == name and r["method"] == "simulation"]:
            if not math.isfinite(sim["relative_error"]):
                print(f"  simulation tol={sim['rtol']:.0e}: horizon {sim['horizon']} too short, "
                      "no boundary found in the bracket")
                continue
            better = [r for r in rows if r["case"] == name and r["method"] == "spectral"
                      and r["relative_error"] <= sim["relative_error"]]
            best = min(better, key=lambda r: r["seconds"])
            sim["speedup_at_matched_accuracy"] = sim["seconds"] / best["seconds"]
            print(f"  simulation tol={sim['rtol']:.0e} (error {sim['relative_error']:.1e}, "
                  f"{sim['seconds'] * 1e3:.0f} ms): spectral reaches error "
                  f"{best['relative_error']:.1e} in {best['seconds'] * 1e3:.2f} ms -> "
                  f"{sim['speedup_at_matched_accuracy']:.0f}x faster")
    RESULTS.mkdir(parents=True, exist_ok=True)
    (RESULTS / "bench_boundary.json").write_text(json.dumps({"rows": rows}, indent=1))
    plot(rows, RESULTS / "bench_boundary.png")
    print(f"\nwrote {RESULTS / 'bench_boundary.json'} and .png")


def plot(rows, path):
    from matplotlib.backends.backend_agg import FigureCanvasAgg
    from matplotlib.figure import Figure

    fig = Figure(figsize=(7, 4.5))
    FigureCanvasAgg(fig)
    ax = fig.add_subplot(111)
    markers = {"simulation": "o", "doubling": "s", "spectral": "*", "spectral-auto": "^"}
    for i, case in enumerate(dict.fromkeys(r["case"] for r in rows)):
        for method, marker in markers.items():
            sel = [r for r in rows if r["case"] == case and r["method"] == method]
            ax.loglog([r["seconds"] for r in sel], [max(r["relative_error"], 1e-17) for r in sel],
                      marker=marker, color=f"C{i}", ls="-" if i == 0 else "--",
                      label=f"{method} / {case.split(',')[0]}")
    ax.set_xlabel("wall time (s, median)")
    ax.set_ylabel("relative error vs 50-digit reference")
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=7)
    fig.savefig(path, dpi=110, bbox_inches="tight")


if __name__ == "__main__":
    main()
