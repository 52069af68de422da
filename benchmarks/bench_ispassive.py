"""hapticproof.ispassive against control.ispassive: time and wrong verdicts, side by side.

Two families, every system decided by both libraries in this process, the calls interleaved
(``--repeat`` times, medians):

* **near the boundary**: the HVE virtual wall's ``G^{-1}`` as a ``control.tf`` (delays 0, 3, 10; ``b``
  1e-2, 1e-6, 1e-9 relative above and below the exact boundary ``b*``, which is known in closed form
  there: ``KT/2 + B`` at n = 0, ``KT/2 + KTn - B`` at n = 3, 10) -- the rows of ``bench_peers.py``;
* **random systems**: ``control.ss`` models, discrete (``dt = 0.01``, poles inside the circle) and
  continuous (poles left of the axis), 1 to 4 states, SISO and 2 x 2, with the feedthrough ``D = d I``
  placed 1e-2 (and, SISO, 1e-6) relative above and below the passivity boundary ``d*`` of the
  strictly proper part (located numerically: placement only).

**Truth** for the random systems is the definition-level oracle of ``tests/oracles/lti.py`` (it reads
the objects itself, decides positive realness numerically at 60 digits, imports nothing from the
package); a system the oracle calls uncertain is left out of the wrong-verdict counts (and counted).
For the walls it is the closed-form boundary. Writes ``benchmarks/results/ispassive.json``.

    pip install 'hapticproof[bench]'          # python-control + cvxopt
    python benchmarks/bench_ispassive.py [--systems 24] [--repeat 5] [--seed 0]
"""

from __future__ import annotations

import argparse
import json
import math
import os
import statistics
import sys
from fractions import Fraction
from pathlib import Path

import numpy as np

HERE = Path(__file__).resolve().parent
RESULTS = HERE / "results"
sys.path.insert(0, str(HERE.parent / "tests"))


def _random_system(rng: np.random.Generator, discrete: bool, n: int, p: int):
    """A stable strictly proper model with coefficients that are short binary fractions."""
    A = np.round(rng.uniform(-1, 1, (n, n)) * 64) / 64
    if discrete:
        A = A / max(1.0, float(np.max(np.abs(np.linalg.eigvals(A))))) * 0.9
        A = np.round(A * 256) / 256
        if np.max(np.abs(np.linalg.eigvals(A))) >= 0.99:
            A = A * 0.5
    else:
        A = A - (np.max(np.linalg.eigvals(A).real) + rng.uniform(0.1, 1.0)) * np.eye(n)
        A = np.round(A * 256) / 256
    B = np.round(rng.uniform(-1, 1, (n, p)) * 16) / 16
    C = np.round((B.T + rng.uniform(-0.5, 0.5, (p, n)) * rng.integers(0, 2)) * 16) / 16
    return A, B, C


def _hermitian_min(A, B, C, discrete: bool, dt: float) -> float:
    """min over frequency of lambda_min(G0 + G0^H)/2 (dense grid and golden refinement; placement only)."""
    from scipy.optimize import minimize_scalar

    n = A.shape[0]

    def value(x: float) -> float:
        point = np.exp(1j * x) if discrete else 1j * 10**x
        G = C @ np.linalg.solve(point * np.eye(n) - A, B)
        return float(np.linalg.eigvalsh((G + G.conj().T) / 2)[0])

    grid = np.linspace(0, math.pi, 4001) if discrete else np.linspace(-4, 4, 4001)
    vals = np.array([value(x) for x in grid])
    i = int(np.argmin(vals))
    lo, hi = grid[max(i - 1, 0)], grid[min(i + 1, len(grid) - 1)]
    best = minimize_scalar(value, bounds=(lo, hi), method="bounded", options={"xatol": 1e-13})
    candidates = [vals[i], best.fun] + ([value(0.0), value(math.pi)] if discrete else [value(-8.0), value(8.0)])
    return float(min(candidates))


def random_cases(count: int, seed: int) -> list[dict]:
    rng = np.random.default_rng(seed)
    cases = []
    systems = 0
    while systems < count:
        discrete = bool(rng.integers(0, 2))
        n, p = int(rng.integers(1, 5)), int(rng.choice([1, 1, 2]))
        A, B, C = _random_system(rng, discrete, n, p)
        d_star = -_hermitian_min(A, B, C, discrete, 0.01)
        if not d_star > 1e-3:
            continue
        systems += 1
        for rel in ((1e-2, 1e-6) if p == 1 else (1e-2,)):
            for side, sign in (("above", 1), ("below", -1)):
                d = float(Fraction(d_star * (1 + sign * rel)).limit_denominator(2**40))
                cases.append({"A": A, "B": B, "C": C, "D": d * np.eye(p), "dt": 0.01 if discrete else 0,
                              "rel": rel, "side": side, "states": n, "ports": p})
    return cases


def main() -> None:
    import control
    import cvxopt

    from hapticproof.analysis.passivity import ispassive
    from hapticproof.bench.speed import interleaved, peer_study
    from hapticproof.bench.timing import jsonable, machine_info
    from oracles.harness import expected_decision
    from oracles.lti import lti_positive_real

    cvxopt.solvers.options["show_progress"] = False
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--systems", type=int, default=24, help="random systems (each at 2-4 placements)")
    parser.add_argument("--repeat", type=int, default=5)
    parser.add_argument("--seed", type=int, default=0)
    parser.add_argument("--output", default=str(RESULTS))
    args = parser.parse_args()
    out = Path(args.output)
    out.mkdir(parents=True, exist_ok=True)

    walls = peer_study(delays=(0, 3, 10), repeat=args.repeat, reference=False, check=False)
    rows = []
    for case in random_cases(args.systems, args.seed):
        sysm = control.ss(case["A"], case["B"], case["C"], case["D"], case["dt"])

        def peer(sysm=sysm):
            try:
                return bool(control.ispassive(sysm))
            except Exception as err:  # noqa: BLE001 - a solver failure is the peer's answer, recorded
                return f"error: {type(err).__name__}"

        timed = interleaved({"hapticproof.ispassive": lambda sysm=sysm: ispassive(sysm), "control.ispassive": peer},
                            args.repeat)
        truth = expected_decision(lti_positive_real(sysm))
        ours, t_ours = timed["hapticproof.ispassive"]
        theirs, t_theirs = timed["control.ispassive"]
        row = {"domain": "discrete" if case["dt"] else "continuous", "states": case["states"], "ports": case["ports"],
               "rel": case["rel"], "side": case["side"], "truth": truth,
               "hapticproof.ispassive": {"seconds": t_ours, "verdict": ours.decision.value,
                                         "wrong": truth is not None and ours.decision.value != truth},
               "control.ispassive": {"seconds": t_theirs, "verdict": theirs,
                                     "wrong": truth is not None and theirs != (truth == "proved")}}
        rows.append(row)
        print(f"  {row['domain']:10s} n={case['states']} {case['ports']}x{case['ports']} {case['side']:5s} rel {case['rel']:.0e}: "
              f"truth {truth or 'uncertain':9s} | hapticproof {t_ours * 1e3:7.2f} ms {ours.decision.value:9s} | "
              f"control {t_theirs * 1e3:7.2f} ms {theirs}")

    def summary(rows: list[dict], name: str) -> dict:
        judged = [r for r in rows if r.get("truth", "x") is not None]
        times = [r[name]["seconds"] for r in rows]
        return {"median_seconds": statistics.median(times), "max_seconds": max(times),
                "wrong_verdicts": sum(bool(r[name]["wrong"]) for r in judged), "judged": len(judged), "of": len(rows)}

    result = {
        "walls": {"summary": {k: walls["summary"][k] for k in ("hapticproof.ispassive", "ispassive") if k in walls["summary"]},
                  "rows": walls["rows"]},
        "random": {"summary": {name: summary(rows, name) for name in ("hapticproof.ispassive", "control.ispassive")},
                   "uncertain_truth": sum(r["truth"] is None for r in rows), "rows": rows},
        "repeat": args.repeat, "seed": args.seed,
        "machine": machine_info() | {"load_average": os.getloadavg(), "control": control.__version__},
    }
    print()
    for family in ("walls", "random"):
        for name, s in result[family]["summary"].items():
            print(f"{family:7s} {name:24s} median {s['median_seconds'] * 1e3:8.2f} ms, max {s['max_seconds'] * 1e3:8.1f} ms, "
                  f"wrong verdicts {s['wrong_verdicts']} of {s.get('judged', s['of'])}")
    (out / "ispassive.json").write_text(json.dumps(jsonable(result), indent=1, default=str))
    print(f"wrote {out / 'ispassive.json'}", file=sys.stderr)


if __name__ == "__main__":
    main()
