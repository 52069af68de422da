"""n-port networks: run time of the exact symbolic case study and of numeric absolute-stability
verdicts, and their accuracy against a dense 50-digit frequency sweep.

1. Symbolic case study (3-DOF bilateral paper, Section 5.1): Youla's symmetrization conditions
   of the symbolic impedance (25) (the 12 printed ones are 6 B-conditions and 6 of the 18 reduced
   A-conditions, all derived) and the six leading real-part minors of Z' under (38).
   Target: < 10 s.
2. Random 6x6 rational impedance matrices of degree 2 (``Z = D S D^-1``, ``S = P0 + (P1 + P2 s) /
   (s^2 + a s + b)`` symmetric, ``D`` a positive diagonal: non-reciprocal but symmetrizable):
   exact absolute-stability verdict (Youla: positive realness of Z' by root isolation in
   ``x = w^2``). Target: < 1 s each. Accuracy: the smallest eigenvalue of the Hermitian part of
   Z'(jw) on a dense log grid (mpmath, 50 digits) must be >= 0 for every "absolutely stable"
   verdict, and negative at the exact witness frequency of every "potentially unstable" one.
3. The slowest decisions (issue 10): whole ``absolute_stability`` verdicts with the termination
   search on (deadline 10 s) for the cases that used to take long -- a positive-real
   non-symmetrizable 4x4 (it ran a 170 s search before positive realness was decided first),
   the reciprocal non-passive 3-DOF network of the test suite (Youla plus a certificate), the
   Table 1 teleoperators (k_vmyz = 60: Youla; 6: not symmetrizable, certificate by search) and
   a non-symmetrizable 4x4 whose search finds nothing (it must end by its deadline and say what
   it tried). Seconds per decision (median of ``--repeats``).

Writes benchmarks/results/bench_networks.{json,png}. Quote medians.

Run:  python benchmarks/bench_networks.py [--matrices 20] [--repeats 5] [--grid 400] [--only slowest]
"""

from __future__ import annotations

import os

os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")

import argparse
import json
import statistics
import time
from pathlib import Path

import mpmath
import numpy as np
import sympy as sp

import hapticproof.derivations.bilateral_3dof as paper
from hapticproof.core.evidence import Decision
from hapticproof.analysis.networks import absolute_stability, symmetrization_conditions, symmetrize
from hapticproof.core.symbols import s

RESULTS = Path(__file__).parent / "results"


def symbolic_case_study(repeats: int) -> dict:
    times_conditions, times_minors = [], []
    for _ in range(repeats):
        for cached in (paper.symbolic_impedance, paper.derived_conditions, paper.zprime_under_38,
                       paper.real_part_zprime, paper.real_part_leading_minors):
            cached.cache_clear()
        start = time.perf_counter()
        conditions = symmetrization_conditions(paper.symbolic_impedance(), ports=(3, 3))
        times_conditions.append(time.perf_counter() - start)
        start = time.perf_counter()
        minors = paper.real_part_leading_minors()
        times_minors.append(time.perf_counter() - start)
    kinds = {k: sum(c.kind == k for c in conditions) for k in ("A", "B")}
    return {
        "conditions": kinds,
        "leading_minors": [sp.sstr(m) for m in minors],
        "seconds_conditions_median": statistics.median(times_conditions),
        "seconds_minors_median": statistics.median(times_minors),
        "seconds_total_median": statistics.median(a + b for a, b in zip(times_conditions, times_minors)),
        "target_seconds": 10.0,
    }


def random_matrix(rng: np.random.Generator, n: int = 6) -> sp.Matrix:
    def psd(k: int) -> sp.Matrix:
        B = rng.integers(-k, k + 1, size=(n, n))
        return sp.Matrix(B @ B.T)

    E = rng.integers(-2, 3, size=(n, n))
    P0 = psd(1) + int(rng.integers(0, 4)) * sp.eye(n) + sp.Matrix(E + E.T) * int(rng.integers(0, 2))
    P1, P2 = psd(2), psd(2)
    a, b = int(rng.integers(1, 5)), int(rng.integers(1, 9))
    S = P0 + (P1 + P2 * s) / (s**2 + a * s + b)
    D = sp.diag(*[int(x) for x in rng.integers(1, 5, size=n)])
    return D * S * D.inv()


def min_eig_hermitian(f, w: float, dps: int = 50) -> mpmath.mpf:
    with mpmath.workdps(dps):
        M = mpmath.matrix(f(mpmath.mpc(0, w)))
        H = (M + M.transpose_conj()) / 2
        return min(mpmath.eighe(H, eigvals_only=True))


def random_networks(count: int, grid: int, seed: int = 2024) -> dict:
    rng = np.random.default_rng(seed)
    rows = []
    for k in range(count):
        Z = random_matrix(rng)
        start = time.perf_counter()
        verdict = absolute_stability(Z, search=False)
        exact_seconds = time.perf_counter() - start
        Zp = symmetrize(Z).zprime()             # Z itself when positive realness decided first
        f = sp.lambdify(s, Zp, "mpmath")
        start = time.perf_counter()
        freqs = [0.0] + list(np.logspace(-3, 3, grid))
        sweep = min(min_eig_hermitian(f, w) for w in freqs)
        sweep_seconds = time.perf_counter() - start
        row = {"decision": verdict.decision.value, "seconds_exact": exact_seconds, "seconds_sweep": sweep_seconds,
               "sweep_min_eig": float(sweep)}
        if verdict.decision == Decision.PROVED:
            row["agrees"] = bool(sweep >= -mpmath.mpf(10) ** -40)
        else:
            decided = verdict.zprime or verdict.positive_real
            witness = decided.hermitian.witness if decided is not None else None
            if witness:
                w = float(mpmath.sqrt(mpmath.mpf(sp.Rational(witness["x"]).p) / sp.Rational(witness["x"]).q))
                at_witness = min_eig_hermitian(f, w)
                row["witness_x"] = str(witness["x"])
                row["min_eig_at_witness"] = float(at_witness)
                row["agrees"] = bool(at_witness < 0)
                row["sweep_also_negative"] = bool(sweep < 0)
            else:
                row["agrees"] = True  # pole/residue failure: not a frequency question
        rows.append(row)
        print(f"  matrix {k}: {row['decision']:9s} exact {exact_seconds:.3f} s, 50-digit sweep {sweep_seconds:.1f} s, "
              f"agrees={row['agrees']}")
    exact = [r["seconds_exact"] for r in rows]
    return {
        "matrices": rows,
        "seconds_exact_median": statistics.median(exact),
        "seconds_exact_max": max(exact),
        "seconds_sweep_median": statistics.median(r["seconds_sweep"] for r in rows),
        "speedup_median": statistics.median(r["seconds_sweep"] / r["seconds_exact"] for r in rows),
        "all_agree": all(r["agrees"] for r in rows),
        "verdicts": {d: sum(r["decision"] == d for r in rows) for d in ("proved", "disproved", "undecided")},
        "grid_points": grid + 1,
        "target_seconds": 1.0,
    }


def slowest_cases() -> dict[str, tuple[sp.Matrix, tuple[int, ...] | None]]:
    """The decisions that used to be slow (issue 10), as exact matrices."""
    pr_nonsym = sp.Matrix([[6 + 1 / (s + 1), 1, 0, 1 / (s + 2)], [2 / (s + 1), 5, 1, 0],
                           [0, -1, 7, 1], [1, 0, 2 / (s + 3), 6]])
    undecided = sp.Matrix([[(8 * s + 77) / (s + 10), 1, (s**2 + 2 * s + 5) / (s + 2), (3 * s + 1) / (s + 2)],
                           [(s + 9) / (s + 5), (4 * s + 15) / (s + 3), (3 * s + 15) / (s + 3), 2],
                           [0, 3 / (s + 1), (5 * s + 9) / (s + 2), -1],
                           [(-14 * s - 83) / (2 * s**2 + 21 * s + 10), (3 * s + 7) / (s + 3), -2 * s / (2 * s**2 + 3 * s + 1),
                            (5 * s**2 + 14 * s + 6) / (s**2 + 3 * s)]])
    return {
        "positive-real non-symmetrizable 4x4": (pr_nonsym, None),
        "reciprocal non-passive 3-DOF 2-port": (sp.diag(sp.Matrix([[0, 0, 0], [0, 1, 2], [0, 2, 1]]), sp.eye(3)), (3, 3)),
        "Table 1, k_vmyz = 60": (paper.table1_impedance(60), (3, 3)),
        "Table 1, k_vmyz = 6": (paper.table1_impedance(6), (3, 3)),
        "non-symmetrizable 4x4, nothing found": (undecided, None),
    }


def slowest_decisions(repeats: int, deadline: float = 10.0) -> dict:
    out = {}
    for name, (Z, ports) in slowest_cases().items():
        times, verdict = [], None
        for _ in range(repeats):
            start = time.perf_counter()
            verdict = absolute_stability(Z, ports=ports, deadline=deadline)
            times.append(time.perf_counter() - start)
        out[name] = {"seconds_median": statistics.median(times), "seconds_max": max(times),
                     "decision": verdict.decision.value, "method": verdict.method,
                     "certificate": verdict.certificate is not None,
                     "search": verdict.search.summary() if verdict.search is not None else None}
        print(f"  {name}: {out[name]['seconds_median']:.2f} s, {verdict.decision.value} ({verdict.method})"
              + (f"; search: {out[name]['search'][:90]}" if out[name]["search"] else ""))
    return {"cases": out, "deadline": deadline}


def plot(result: dict, path: Path) -> None:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    rows = result["random"]["matrices"]
    fig, axes = plt.subplots(1, 2, figsize=(10, 4))
    exact = [r["seconds_exact"] for r in rows]
    sweep = [r["seconds_sweep"] for r in rows]
    colors = ["tab:green" if r["decision"] == "proved" else "tab:red" for r in rows]
    axes[0].scatter(exact, sweep, c=colors)
    axes[0].set_xlabel("exact verdict [s]")
    axes[0].set_ylabel(f"50-digit sweep, {result['random']['grid_points']} points [s]")
    axes[0].set_title("random 6x6 degree-2 impedances (green: abs. stable)")
    sym = result["symbolic"]
    axes[1].bar(["12 conditions (+18)", "6 real-part minors"],
                [sym["seconds_conditions_median"], sym["seconds_minors_median"]])
    axes[1].axhline(sym["target_seconds"], color="k", ls="--", label="target 10 s")
    axes[1].set_ylabel("median seconds")
    axes[1].set_title("symbolic case study")
    axes[1].legend()
    fig.tight_layout()
    fig.savefig(path, dpi=120)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--matrices", type=int, default=20)
    parser.add_argument("--repeats", type=int, default=5)
    parser.add_argument("--grid", type=int, default=400)
    parser.add_argument("--only", choices=("slowest",), help="run only the slowest-decisions section")
    args = parser.parse_args()
    print("slowest decisions (absolute stability, search deadline 10 s) ...")
    slowest = slowest_decisions(1 if args.only else min(args.repeats, 3))
    if args.only:
        RESULTS.mkdir(exist_ok=True)
        (RESULTS / "bench_networks_slowest.json").write_text(json.dumps(slowest, indent=2, default=str))
        return
    print("symbolic case study ...")
    symbolic = symbolic_case_study(args.repeats)
    print(f"  median {symbolic['seconds_total_median']:.2f} s (conditions {symbolic['seconds_conditions_median']:.2f} s, "
          f"minors {symbolic['seconds_minors_median']:.2f} s); conditions {symbolic['conditions']}")
    print("random 6x6 networks ...")
    random_result = random_networks(args.matrices, args.grid)
    print(f"  exact verdict median {random_result['seconds_exact_median']:.3f} s (max {random_result['seconds_exact_max']:.3f} s); "
          f"sweep median {random_result['seconds_sweep_median']:.1f} s; all agree: {random_result['all_agree']}; "
          f"verdicts {random_result['verdicts']}")
    result = {"symbolic": symbolic, "random": random_result, "slowest": slowest}
    RESULTS.mkdir(exist_ok=True)
    (RESULTS / "bench_networks.json").write_text(json.dumps(result, indent=2, default=str))
    plot(result, RESULTS / "bench_networks.png")
    print(f"wrote {RESULTS / 'bench_networks.json'} and .png")


if __name__ == "__main__":
    main()
