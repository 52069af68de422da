"""m-user HVE: symbolic principal minors (flint polynomial rings vs SymPy) and exact numeric
decisions, with peak memory.

Cases (each run in a fresh child process, so its peak RSS is its own):

* ``minors-flint`` -- the Hermitian part of a complete-graph scene with fully general
  parameters (every b_i, K_0i, B_0i, K_ij, B_ij, z_ai its own symbol) built from the kernels,
  and ALL its principal minors as ``fmpq_mpoly`` (hapticproof.analysis.multiuser/psd), m = 2..5 (m = 6 takes
  ~3 s but ~10 GB: its determinant has 4.2 million terms);
* ``minors-sympy-c`` -- the same minors as SymPy determinants of the entrywise c-matrix
  (``Matrix.det`` + ``expand``), m = 2..4: the "SymPy expressions" route;
* ``minors-naive`` -- the naive route: Hermitian part G(z) + G(1/z)^T of the rational matrix,
  its principal minors by ``det`` followed by ``simplify``; time-boxed (``--timebox`` s);
* ``decide-m16`` -- exact decision of M(c) >= 0 on [-1, 1] for m = 16 with random exact
  parameters (no delay, equal delays n = 3, mixed delays 0..3), seeds 0..repeats-1; plus the
  m-scaling of the undelayed decision (m = 4, 8, 16, 24).

Medians over repeats; ratios are computed between routes measured in the same run.
Writes benchmarks/results/bench_multiuser.{json,png}.

Run:  python benchmarks/bench_multiuser.py [--repeats 5] [--timebox 120] [--quick]
"""

from __future__ import annotations

import os

os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")

import argparse
import json
import multiprocessing as mp
import random
import resource
import statistics
import time
from pathlib import Path

RESULTS = Path(__file__).parent / "results"


# ------------------------------------------------------------------------------------------
# cases (run in children)
# ------------------------------------------------------------------------------------------


def _minors_flint(m: int) -> dict:
    from hapticproof.systems.multiuser import MultiUserScene
    from hapticproof.analysis.multiuser import hermitian
    from hapticproof.exact.psd import principal_minors

    hermitian(MultiUserScene.symbolic(2))          # warm the kernel cache (shared by every m)
    scene = MultiUserScene.symbolic(m, active=True)
    start = time.perf_counter()
    minors = principal_minors(hermitian(scene))
    seconds = time.perf_counter() - start
    top = minors[tuple(range(m))].num
    return {"seconds": seconds, "minors": len(minors), "det_terms": len(top.to_dict()),
            "parameters": len(scene.parameters)}


def _minors_sympy_c(m: int) -> dict:
    import itertools

    import sympy as sp

    from hapticproof.systems.multiuser import MultiUserScene
    from hapticproof.analysis.multiuser import hermitian

    scene = MultiUserScene.symbolic(m, active=True)
    M = hermitian(scene).matrix()
    start = time.perf_counter()
    out = {}
    for k in range(1, m + 1):
        for subset in itertools.combinations(range(m), k):
            out[subset] = sp.expand(M.extract(list(subset), list(subset)).det(method="berkowitz"))
    seconds = time.perf_counter() - start
    return {"seconds": seconds, "minors": len(out), "det_terms": len(sp.Add.make_args(out[tuple(range(m))]))}


def _minors_naive(m: int) -> dict:
    import itertools

    import sympy as sp

    from hapticproof.systems.multiuser import MultiUserScene, inverse_transfer_matrix
    from hapticproof.core.symbols import z

    scene = MultiUserScene.symbolic(m, active=True)
    G = sp.Matrix(inverse_transfer_matrix(scene))
    start = time.perf_counter()
    M = G + G.subs(z, 1 / z).T
    out = {}
    for k in range(1, m + 1):
        for subset in itertools.combinations(range(m), k):
            out[subset] = sp.simplify(M.extract(list(subset), list(subset)).det())
    seconds = time.perf_counter() - start
    return {"seconds": seconds, "minors": len(out)}


def _random_scene(m: int, seed: int, delays):
    import sympy as sp

    from hapticproof.systems.multiuser import MultiUserScene, complete_graph

    rng = random.Random(seed)
    R = lambda lo, hi: sp.Rational(rng.randint(lo, hi), 1000)  # noqa: E731
    if delays == "mixed":
        delays = [rng.randint(0, 3) for _ in range(m)]
    n = max(delays) if isinstance(delays, list) else delays
    T = sp.Rational(1, 1000)
    K0 = [R(1000, 20000) for _ in range(m)]
    K = {e: R(500, 8000) for e in complete_graph(m)}
    B0 = [R(0, 20) for _ in range(m)]
    B = {e: R(0, 10) for e in complete_graph(m)}
    # dampings around lambda_max((n + 1/2) T Kmat + Bmat), the Loewner worst case, so both outcomes occur
    import numpy as np

    W = np.zeros((m, m))
    for (i, j), k in K.items():
        W[i, j] = W[j, i] = float((n + sp.Rational(1, 2)) * T * k + B[(i, j)])
    A = np.diag([float((n + sp.Rational(1, 2)) * T * k0 + b0) for k0, b0 in zip(K0, B0)]) + np.diag(W.sum(1)) - W
    base = sp.Rational(float(np.linalg.eigvalsh(A).max())).limit_denominator(10**6)
    factor = sp.Rational(rng.randint(96, 104) if n == 0 else rng.randint(40, 100), 100)
    return MultiUserScene.from_values(
        b=[base * factor * sp.Rational(rng.randint(100, 103), 100) for _ in range(m)], T=T, K0=K0, K=K, B0=B0, B=B, delays=delays)


def _decide(m: int, seed: int, delays) -> dict:
    from hapticproof.analysis.multiuser import hermitian, worst_case

    worst_case(_random_scene(2, 99, 0))          # warm imports and kernel caches
    scene = _random_scene(m, seed, delays)
    start = time.perf_counter()
    H = hermitian(scene)
    decision = worst_case(scene)
    seconds = time.perf_counter() - start
    return {"seconds": seconds, "decision": decision.decision.value, "complex": not H.is_symmetric,
            "degree_in_c": H.c_degree()}


CASES = {"minors-flint": _minors_flint, "minors-sympy-c": _minors_sympy_c, "minors-naive": _minors_naive,
         "decide": _decide}


def _child(name: str, args: tuple, queue: mp.Queue) -> None:
    result = CASES[name](*args)
    result["peak_rss_mb"] = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024
    queue.put(result)


def run_case(name: str, args: tuple, timebox: float) -> dict:
    ctx = mp.get_context("spawn")
    queue = ctx.Queue()
    proc = ctx.Process(target=_child, args=(name, args, queue))
    start = time.perf_counter()
    proc.start()
    proc.join(timebox)
    if proc.is_alive():
        proc.kill()
        proc.join()
        return {"timed_out": True, "timebox_seconds": timebox, "wall": time.perf_counter() - start}
    return queue.get() if not queue.empty() else {"failed": True, "exitcode": proc.exitcode}


def median_case(name: str, args_list: list[tuple], timebox: float) -> dict:
    runs = [run_case(name, args, timebox) for args in args_list]
    done = [r for r in runs if "seconds" in r]
    out = {"runs": runs}
    if done:
        out["median_seconds"] = statistics.median(r["seconds"] for r in done)
        out["max_peak_rss_mb"] = max(r["peak_rss_mb"] for r in done)
    if any(r.get("timed_out") for r in runs):
        out["timed_out"] = True
    return out


# ------------------------------------------------------------------------------------------
# main
# ------------------------------------------------------------------------------------------


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--repeats", type=int, default=5)
    parser.add_argument("--timebox", type=float, default=120.0, help="seconds allowed to the naive SymPy route")
    parser.add_argument("--quick", action="store_true", help="fewer sizes and repeats (smoke test)")
    args = parser.parse_args()
    repeats = 2 if args.quick else args.repeats
    results: dict = {"repeats": repeats, "minors": {}, "decide": {}}

    sizes = (2, 3, 4) if args.quick else (2, 3, 4, 5)   # m = 6 needs ~10 GB (4.2M-term determinant)
    for m in sizes:
        row = {"flint": median_case("minors-flint", [(m,)] * repeats, 600)}
        if m <= 4:
            row["sympy_c"] = median_case("minors-sympy-c", [(m,)] * (1 if m == 4 else repeats), 600)
        if m <= 3:
            row["naive"] = median_case("minors-naive", [(m,)], args.timebox)
        for key in ("sympy_c", "naive"):
            if key in row and "median_seconds" in row[key]:
                row[f"{key}_over_flint"] = row[key]["median_seconds"] / row["flint"]["median_seconds"]
            elif key in row:
                row[f"{key}_over_flint_at_least"] = args.timebox / row["flint"]["median_seconds"]
        results["minors"][m] = row
        print(f"minors m={m}: " + ", ".join(f"{k} {v['median_seconds']:.4g}s" for k, v in row.items()
                                             if isinstance(v, dict) and "median_seconds" in v)
              + "".join(f", {k} {v:.0f}x" for k, v in row.items() if k.endswith("_over_flint") or k.endswith("_at_least")), flush=True)

    seeds = list(range(repeats))
    for label, m, delays in (("m16-undelayed", 16, 0), ("m16-equal-delay-3", 16, 3), ("m16-mixed-delays", 16, "mixed")):
        results["decide"][label] = median_case("decide", [(m, s, delays) for s in seeds], 600)
        r = results["decide"][label]
        print(f"decide {label}: median {r['median_seconds']:.3f}s, decisions "
              f"{[x['decision'] for x in r['runs']]}, peak {r['max_peak_rss_mb']:.0f} MB", flush=True)
    scaling = (4, 8, 16) if args.quick else (4, 8, 16, 24)
    results["decide_scaling"] = {m: median_case("decide", [(m, s, 0) for s in seeds], 600) for m in scaling}

    RESULTS.mkdir(parents=True, exist_ok=True)
    (RESULTS / "bench_multiuser.json").write_text(json.dumps(results, indent=2, default=str))
    plot(results, RESULTS / "bench_multiuser.png")
    print(f"wrote {RESULTS / 'bench_multiuser.json'} and .png")


def plot(results: dict, path: Path) -> None:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, (ax1, ax2) = plt.subplots(1, 2, figsize=(10, 4))
    for key, label in (("flint", "flint fmpq_mpoly (kernels + memoised Laplace)"), ("sympy_c", "SymPy det of the c-matrix"),
                       ("naive", "naive: det of rational matrix + simplify")):
        xs = [m for m, row in results["minors"].items() if key in row and "median_seconds" in row[key]]
        ys = [results["minors"][m][key]["median_seconds"] for m in xs]
        if xs:
            ax1.semilogy(xs, ys, "o-", label=label)
        out = [m for m, row in results["minors"].items() if key in row and row[key].get("timed_out")]
        for m in out:
            ax1.semilogy([m], [results["minors"][m][key]["runs"][0]["timebox_seconds"]], "x", color="red")
    ax1.set_xlabel("users m (complete graph, every parameter a symbol)")
    ax1.set_ylabel("all principal minors [s] (median)")
    ax1.legend(fontsize=7)
    xs = list(results["decide_scaling"])
    ax2.plot(xs, [results["decide_scaling"][m]["median_seconds"] for m in xs], "o-", label="no delay")
    for label, r in results["decide"].items():
        ax2.plot([16], [r["median_seconds"]], "s", label=label)
    ax2.set_xlabel("users m (random exact parameters)")
    ax2.set_ylabel("exact decision of M(c) >= 0 [s] (median)")
    ax2.legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(path, dpi=120)


if __name__ == "__main__":
    main()
