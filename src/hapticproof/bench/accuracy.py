"""Run time against error: the studies behind ``hapticproof bench``.

Every study measures its methods side by side in one run, reports medians over repeats, and
measures errors against an independent reference (exact arithmetic, certified balls or
50-digit mpmath). Results are JSON-able dicts; :func:`plot_time_error` draws the log-log plot.

* :func:`margin_study` -- the passivity margin ``min_w lambda_min(Hermitian part)``: float64
  grids (10..10^6 points), mpmath grids at 15/30/50 digits, and the exact c-polynomial method
  (certified root isolation), for a single-user scene with delays 0, 10, 100 and a 4-user scene;
* :func:`boundary_study` -- the stability boundary ``K*(T)``: time-domain simulation plus
  bisection (Simulink-style), spectral radius plus root-finding, and the exact
  characteristic-polynomial conditions (:mod:`hapticproof.analysis.boundary`);
* :func:`audit_study` -- cold-process wall time of the whole audit and the slowest equations;
* :func:`stress_study` -- float paths against exact results at extreme parameters;
* :func:`lazy_study` -- each bundled scene's lazy pipeline (what a request needs) against the
  full pipeline (every stage forced);
* the tasks ``peers``, ``delays`` and ``maps`` run :mod:`hapticproof.bench.speed` (python-control
  side by side, delays up to 10 000 samples, exact design-space maps).

>>> rows = margin_study(cases=["single-user n=0"], float_points=[100], mp_points=[], repeat=1)
>>> sorted({r["method"] for r in rows})
['exact', 'float64']
"""

from __future__ import annotations

import json
import os
import statistics
import subprocess
import sys
import time
from collections.abc import Callable, Iterable
from pathlib import Path
from typing import Any

import sympy as sp
from hapticproof.core.files import write_atomic
from hapticproof.bench.timing import jsonable, machine_info, median_time

__all__ = ["margin_cases", "margin_study", "boundary_study", "audit_study", "lazy_study", "stress_study", "stress_cases", "plot_time_error", "run"]


def margin_cases() -> dict[str, Any]:
    """The scenes of the margin study: G^-1(z) of the HVE single-user wall (delays 0, 10, 100;
    Phantom-like parameters) and of a 4-user complete-graph HVE."""
    from hapticproof.systems.models import inverse_transfer
    from hapticproof.systems.multiuser import MultiUserScene, inverse_transfer_matrix
    from hapticproof.systems.singleuser import SingleUserScene

    out: dict[str, Any] = {}
    for n, b in ((0, "0.02"), (10, "0.05"), (100, "0.3")):
        scene = SingleUserScene.virtual_wall(K=2, B="0.001", b=b, T="0.001", delay=n)
        out[f"single-user n={n}"] = inverse_transfer(scene)
    multi = MultiUserScene.from_values(b=["0.05", "0.06", "0.07", "0.08"], T="0.001", K0=[2, 3, 1, 2], K=1,
                                       B0="0.001", B="0.002")
    out["4-user"] = inverse_transfer_matrix(multi)
    return out


def margin_study(
    cases: Iterable[str] | None = None,
    float_points: Iterable[int] = (10, 100, 1_000, 10_000, 100_000, 1_000_000),
    mp_points: Iterable[int] = (10, 100, 1_000),
    mp_digits: Iterable[int] = (15, 30, 50),
    repeat: int = 3,
) -> list[dict[str, Any]]:
    """Time and relative error of every margin method on every case (see module docstring)."""
    import mpmath

    from hapticproof.analysis.numerics import exact_margin, exact_margin_prepared, float_margin, mp_margin, stable_evaluator

    all_cases = margin_cases()
    rows: list[dict[str, Any]] = []
    for name in cases or all_cases:
        G = all_cases[name]
        reference = exact_margin(G, bits=110)
        ref = reference.mid

        def error(value: Any) -> float:
            with mpmath.workdps(60):
                return float(abs(mpmath.mpf(value) - ref) / abs(ref))

        # one-time preparations (exact c-forms / compiled float and mpmath evaluators) are
        # measured separately and excluded from every method's per-margin time
        compute, prep_exact = median_time(lambda: exact_margin_prepared(G), 1)
        exact, seconds = median_time(lambda: compute(53), repeat)
        rows.append({"case": name, "method": "exact", "points": None, "digits": None, "seconds": seconds,
                     "setup_seconds": prep_exact,
                     "relative_error": max(error(exact.lo), error(exact.hi)), "certified": True})
        evaluator, prep_float = median_time(lambda: stable_evaluator(G), 1)
        for points in float_points:
            reps = 1 if points >= 100_000 else repeat
            (value, _), seconds = median_time(lambda: float_margin(G, points, evaluator), reps)
            rows.append({"case": name, "method": "float64", "points": points, "digits": 16, "seconds": seconds,
                         "setup_seconds": prep_float, "relative_error": error(repr(value)), "certified": False})
        for digits in mp_digits:
            for points in mp_points:
                value, seconds = median_time(lambda: mp_margin(G, points, digits), 1)
                rows.append({"case": name, "method": f"mpmath-{digits}", "points": points, "digits": digits,
                             "seconds": seconds, "relative_error": error(value), "certified": False})
    return rows


def margin_goal(rows: list[dict[str, Any]], threshold: float = 1e-6) -> dict[str, Any]:
    """Per case: is the exact method faster than every grid whose error is below ``threshold``?"""
    out = {}
    for case in dict.fromkeys(r["case"] for r in rows):
        exact = next(r for r in rows if r["case"] == case and r["method"] == "exact")
        good = [r for r in rows if r["case"] == case and r["method"] != "exact" and r["relative_error"] < threshold]
        fastest = min(good, key=lambda r: r["seconds"]) if good else None
        out[case] = {
            "exact_seconds": exact["seconds"],
            "exact_relative_error": exact["relative_error"],
            "fastest_grid_below_threshold": fastest,
            "exact_faster": fastest is None or exact["seconds"] < fastest["seconds"],
            "ratio_grid_over_exact": (fastest["seconds"] / exact["seconds"]) if fastest else None,
        }
    return out


def boundary_study(quick: bool = False, repeat: int = 3) -> list[dict[str, Any]]:
    """``K*`` of the free device (m = 0.015, b = 0.01822, T = 1 ms; and with B = 0.002, n = 2)
    by simulation + bisection, spectral radius + root-finding, and the exact characteristic
    polynomial; errors against the certified exact value at 200 bits."""
    from hapticproof.analysis.boundary import critical_stiffness
    from hapticproof.analysis.maps import SceneFamily, find_boundary

    cases = {
        "free device n=0": ({"m": 0.015, "b": 0.01822, "B": 0}, 0, {"m": "0.015", "b": "0.01822", "T": "0.001"}),
        "B=0.002, n=2": ({"m": 0.015, "b": 0.01822, "B": 0.002}, 2,
                          {"m": "0.015", "b": "0.01822", "T": "0.001", "B": "0.002", "n": 2}),
    }
    tolerances = (1e-2, 1e-4) if quick else (1e-2, 1e-3, 1e-4, 1e-5, 1e-6)
    rows: list[dict[str, Any]] = []
    for name, (params, delay, exact_args) in cases.items():
        ref = critical_stiffness(**exact_args, bits=200).value
        family = SceneFamily("single-user", params, delay=delay)
        at = {"T": 0.001}
        bracket = (0.5 * ref, 2.0 * ref)
        for tol in tolerances:
            steps = min(20_000 if quick else 200_000, int(1 / tol))
            for method, func in (
                ("simulation", lambda: find_boundary(family, "K", at=at, search=bracket, scan=2, rtol=tol,
                                                     method="steps", steps=steps)),
                ("spectral", lambda: find_boundary(family, "K", at=at, search=bracket, scan=2, rtol=tol)),
            ):
                reps = 1 if method == "simulation" and steps > 10_000 else repeat
                bnd, seconds = median_time(func, reps)
                err = abs(bnd.value - ref) / ref if bnd.value else float("nan")
                rows.append({"case": name, "method": method, "tolerance": tol, "seconds": seconds,
                             "relative_error": err})
        for bits in (53, 100) if quick else (53, 80, 120):
            cs, seconds = median_time(lambda: critical_stiffness(**exact_args, bits=bits), repeat)
            # the certified tolerance is the ball's relative radius (cancellation in the closed form
            # costs digits, so it is wider than 2^-bits at low working precision)
            certified = float(cs.K.rad()) / abs(float(cs.K.mid()))
            rows.append({"case": name, "method": "exact-characteristic", "tolerance": max(certified, 2.0**-bits),
                         "working_bits": bits, "seconds": seconds, "relative_error": abs(cs.value - ref) / ref})
    return rows


def audit_study(repeat: int = 3, single_core: bool = True, jobs: int = 1) -> dict[str, Any]:
    """Cold-process wall time of ``hapticproof audit --all --jobs N`` (medians) and the ten
    slowest equations (median per-equation seconds); ``jobs = 1`` pinned to one core."""
    env = dict(os.environ, OPENBLAS_NUM_THREADS="1", OMP_NUM_THREADS="1", MKL_NUM_THREADS="1")
    # cold = a fresh process, as a user runs it: Python's bytecode cache is allowed (some
    # sandboxes set PYTHONDONTWRITEBYTECODE, which recompiles every module on every run)
    env.pop("PYTHONDONTWRITEBYTECODE", None)
    cmd = [sys.executable, "-m", "hapticproof", "audit", "--all", "--format", "json", "--jobs", str(jobs)]
    if single_core and jobs == 1 and sys.platform.startswith("linux") and _has("taskset"):
        cmd = ["taskset", "-c", "0"] + cmd
    walls: list[float] = []
    per_equation: dict[str, list[float]] = {}
    for _ in range(repeat):
        start = time.perf_counter()
        out = subprocess.run(cmd, capture_output=True, text=True, env=env, check=True).stdout
        walls.append(time.perf_counter() - start)
        for paper in json.loads(out)["papers"]:
            for eq in paper["equations"]:
                per_equation.setdefault(f"{paper['paper']}:{eq['id']}", []).append(eq["seconds"])
    medians = {k: statistics.median(v) for k, v in per_equation.items()}
    return {
        "cold_wall_seconds_median": statistics.median(walls),
        "cold_wall_seconds": walls,
        "equations": len(medians),
        "single_core": single_core and jobs == 1,
        "jobs": jobs,
        "slowest": sorted(medians.items(), key=lambda kv: -kv[1])[:10],
        "total_equation_seconds": sum(medians.values()),
    }


def _has(program: str) -> bool:
    from shutil import which

    return which(program) is not None


def single_user_stages() -> list[Callable[[Any], Any]]:
    """Every stage of a single-user scene (the 'full pipeline')."""
    from hapticproof.systems import models
    from hapticproof.analysis import positivereal

    return [models.environment_path, models.inverse_transfer, positivereal.poles, positivereal.residues,
            positivereal.hermitian, positivereal.worst_case, positivereal.positive_real]


def bundled_scenes() -> dict[str, Any]:
    """The single-user scenes the HVE paper analyses (symbolic and numeric instances)."""
    from hapticproof.systems.singleuser import SYMBOLS, SingleUserScene

    return {
        "forward, symbolic": SingleUserScene.virtual_wall(),
        "tustin, symbolic": SingleUserScene.virtual_wall(approximation="tustin"),
        "delay n symbolic": SingleUserScene.virtual_wall(delay=SYMBOLS["n"]),
        "active, delay 3": SingleUserScene.virtual_wall(delay=3, z_a=SYMBOLS["z_a"]),
        "Fig. 8a point (numeric)": SingleUserScene.virtual_wall(K=30, B=0, b="0.02", T="0.001", z_a="0.01"),
        "Fig. 8b point, delay 10": SingleUserScene.virtual_wall(K=10, B=0, b="0.2", T="0.002", delay=10, z_a="0.04"),
    }


def lazy_study(repeat: int = 3) -> list[dict[str, Any]]:
    """Per bundled scene: time of the worst-case request alone (lazy) vs every stage forced."""
    from hapticproof.core.lazy import clear, computed_stages, force
    from hapticproof.analysis.positivereal import worst_case

    rows = []
    for name, scene in bundled_scenes().items():
        def lazy() -> set[str]:
            clear(scene)
            worst_case(scene)
            return computed_stages(scene)

        def full() -> set[str]:
            clear(scene)
            force(scene, single_user_stages())
            return computed_stages(scene)

        stages, lazy_s = median_time(lazy, repeat)
        _, full_s = median_time(full, repeat)
        rows.append({"scene": name, "lazy_seconds": lazy_s, "full_seconds": full_s,
                     "ratio": full_s / lazy_s if lazy_s else None, "lazy_stages": sorted(stages),
                     "skipped": sorted({f.stage_name for f in single_user_stages()} - stages)})
    return rows


def stress_cases(size: str = "small") -> list[dict[str, Any]]:
    """Extreme single-user scenes: T 1e-7..1, K 1e-3..1e9, b and B over 12 decades, delays up to
    1000 (``size='large'``), each with b just above, exactly at and just below the exact
    boundary ``b* = KT/2 + B`` (no delay) or ``KT/2 + KTn`` (delay, B = 0).

    With ``B = 0`` a delayed scene depends on ``(T, K)`` only through the scale ``KT`` (``b`` is
    proportional to it), so ``n = 1000`` (about 10 s per exact decision) is run on three
    ``(T, K)`` pairs spanning that scale, ``KT`` = 1e-10, 1e-3 and 1e9."""
    from fractions import Fraction

    Ts = ["1e-7", "1e-3", "1"]
    Ks = ["1e-3", "1", "1e9"]
    Bs = ["0", "1e-6", "1e6"]
    delays = [0, 10, 200] if size == "small" else [0, 10, 200, 1000]
    out = []
    for T in Ts:
        for K in Ks:
            for n in delays:
                if n == 1000 and Ts.index(T) != Ks.index(K):
                    continue
                for B in (Bs if n == 0 else ["0"]):
                    Tq, Kq, Bq = Fraction(T), Fraction(K), Fraction(B)
                    boundary = Kq * Tq / 2 + (Bq if n == 0 else Kq * Tq * n)
                    for label, factor in (("above", Fraction(1) + Fraction(1, 10**9)), ("at", Fraction(1)),
                                          ("below", Fraction(1) - Fraction(1, 10**9))):
                        out.append({"T": T, "K": K, "B": B, "n": n, "where": label, "b": boundary * factor})
    return out


def stress_study(size: str = "small") -> dict[str, Any]:
    """Every float path against the exact result on :func:`stress_cases`: the worst relative
    error of each path's margin, and wrong verdicts (must be zero for the toolkit's paths)."""
    import mpmath

    from hapticproof.systems.models import inverse_transfer
    import numpy as np

    from hapticproof.analysis.numerics import exact_margin, float_decision, float_margin, naive_evaluator, stable_evaluator
    from hapticproof.analysis.positivereal import decide_hermitian, hermitian
    from hapticproof.systems.singleuser import SingleUserScene

    worst: dict[str, float] = {"float64-stable": 0.0, "float64-naive": 0.0,
                               "float64-stable@minimiser": 0.0, "float64-naive@minimiser": 0.0}
    wrong: dict[str, int] = {"float_decision": 0, "float64-stable-sign": 0, "float64-naive-sign": 0}
    escalated = 0
    cases = stress_cases(size)
    for case in cases:
        scene = SingleUserScene.virtual_wall(K=case["K"], B=case["B"], b=case["b"], T=case["T"], delay=case["n"])
        G = inverse_transfer(scene)
        fast = float_decision(G, points=2048)
        switched = "switched to exact" in fast.reason
        escalated += switched
        # an escalated float_decision *is* the exact decision: recompute only the others
        exact = fast if switched else decide_hermitian(hermitian(scene))
        if fast.decision != exact.decision:
            wrong["float_decision"] += 1
        margin = exact_margin(G, bits=60) if case["n"] <= 200 else None
        # the margin is relative to the size of the terms (b + KT(n + 1/2) + B)
        scale = float(sp.Rational(case["b"]) + sp.Rational(case["K"]) * sp.Rational(case["T"]) * (case["n"] + 1)
                      + sp.Rational(case["B"]))
        for path, evaluator in (("float64-stable", None), ("float64-naive", naive_evaluator(G))):
            value, _ = float_margin(G, 2048, evaluator)
            if margin is not None:
                with mpmath.workdps(40):
                    err = float(abs(mpmath.mpf(value) - margin.mid) / scale)
                worst[path] = max(worst[path], err)
            says_ok = value >= 0
            if says_ok and exact.decision.value == "disproved":
                wrong[f"{path}-sign"] += 1
        # pure rounding error: each float evaluator at the exact minimiser (theta -> 0 when the
        # minimiser is c = 1, where the naive form loses Re T/(z - 1))
        if margin is not None and exact.minimiser is not None:
            c_star = exact.minimiser if not hasattr(exact.minimiser, "midpoint") else exact.minimiser.midpoint(60)
            theta = float(mpmath.acos(mpmath.mpf(str(sp.Rational(c_star))))) or 1e-9
            with mpmath.workdps(40):
                at = hermitian(scene)(sp.Rational(c_star)) if not hasattr(exact.minimiser, "midpoint") else margin.mid
                for path, evaluator in (("float64-stable@minimiser", stable_evaluator(G)),
                                        ("float64-naive@minimiser", naive_evaluator(G))):
                    value = float(evaluator(np.array([theta]))[0].real)
                    worst[path] = max(worst[path], float(abs(mpmath.mpf(value) - mpmath.mpf(str(at))) / scale))
    return {"cases": len(cases), "worst_relative_error": worst, "wrong_verdicts": wrong,
            "escalated_to_exact": escalated,
            "note": "float64 grid signs are not verdicts of the toolkit; float_decision is (it escalates)"}


def plot_time_error(rows: list[dict[str, Any]], path: str | Path, title: str) -> None:
    """Log-log plot: wall time (x) against relative error (y), one panel per case."""
    from matplotlib.backends.backend_agg import FigureCanvasAgg
    from matplotlib.figure import Figure

    cases = list(dict.fromkeys(r["case"] for r in rows))
    fig = Figure(figsize=(4.2 * len(cases), 3.8))
    FigureCanvasAgg(fig)
    for k, case in enumerate(cases):
        ax = fig.add_subplot(1, len(cases), k + 1)
        methods = list(dict.fromkeys(r["method"] for r in rows if r["case"] == case))
        for i, method in enumerate(methods):
            sel = [r for r in rows if r["case"] == case and r["method"] == method]
            ax.loglog([max(r["seconds"], 1e-6) for r in sel], [max(r["relative_error"], 1e-18) for r in sel],
                      marker="o*s^vD"[i % 6], ls="-", label=method)
        ax.set_title(case, fontsize=9)
        ax.set_xlabel("wall time (s, median)")
        if k == 0:
            ax.set_ylabel("relative error")
        ax.grid(True, which="both", alpha=0.3)
        ax.legend(fontsize=7)
    fig.suptitle(title, fontsize=10)
    from hapticproof.core.files import write_figure

    write_figure(fig, path, "bench")


def run(tasks: Iterable[str], outdir: str | Path, quick: bool = False, repeat: int = 3,
        log: Callable[[str], None] = print, progress: Callable[..., None] | None = None) -> dict[str, Any]:
    """Run the named studies, write ``<task>.json`` (+ PNG) into ``outdir``, return a summary;
    ``progress(done, total, label)`` is called before each study and at the end."""
    from hapticproof.core.files import check_output_folder

    check_output_folder(outdir, "bench")              # no link, file or device where the folder goes
    outdir = Path(outdir)
    outdir.mkdir(parents=True, exist_ok=True)
    summary: dict[str, Any] = {"machine": machine_info(), "quick": quick, "repeat": repeat}
    tasks = list(tasks)
    for number, task in enumerate(tasks):
        if progress is not None:
            progress(number, len(tasks), f"bench {task}")
        start = time.perf_counter()
        log(f"[bench] {task} ...")
        if task == "margin":
            rows = margin_study(
                float_points=(10, 100, 1_000, 10_000) if quick else (10, 100, 1_000, 10_000, 100_000, 1_000_000),
                mp_points=(10, 100) if quick else (10, 100, 1_000),
                repeat=repeat,
            )
            goal = margin_goal(rows)
            data = {"rows": rows, "goal": goal}
            plot_time_error(rows, outdir / "margin.png", "passivity margin: time vs error")
            for case, g in goal.items():
                log(f"  {case}: exact {g['exact_seconds'] * 1e3:.1f} ms (error {g['exact_relative_error']:.1e}); "
                    + (f"fastest grid with error < 1e-6: {g['fastest_grid_below_threshold']['method']} "
                       f"{g['fastest_grid_below_threshold']['points']} pts, {g['fastest_grid_below_threshold']['seconds'] * 1e3:.1f} ms"
                       if g["fastest_grid_below_threshold"] else "no grid reached error < 1e-6"))
        elif task == "boundary":
            rows = boundary_study(quick=quick, repeat=repeat)
            data = {"rows": rows}
            plot_time_error(rows, outdir / "boundary.png", "stability boundary K*: time vs error")
            for r in rows:
                log(f"  {r['case']:16s} {r['method']:22s} tol {r['tolerance']:.0e}: error {r['relative_error']:.1e} "
                    f"in {r['seconds'] * 1e3:.2f} ms")
        elif task == "audit":
            data = audit_study(repeat=1 if quick else repeat)
            log(f"  cold wall (median, one core) {data['cold_wall_seconds_median']:.1f} s for {data['equations']} "
                "equations; slowest: " + ", ".join(f"{k} {v:.2f}s" for k, v in data["slowest"][:5]))
            from hapticproof.audit.pool import default_jobs

            if default_jobs() > 1:
                data["parallel"] = audit_study(repeat=1 if quick else repeat, jobs=default_jobs())
                log(f"  cold wall (median, --jobs {default_jobs()}) {data['parallel']['cold_wall_seconds_median']:.1f} s")
        elif task == "peers":
            from hapticproof.bench.speed import peer_study, plot_peers

            data = peer_study(delays=(0, 3, 10), rels=(1e-2, 1e-9) if quick else (1e-2, 1e-6, 1e-9),
                              repeat=3 if quick else max(repeat, 15), log=log)
            if data["rows"]:
                plot_peers(data, outdir / "peers.png")
            for name, s in data["summary"].items():
                if isinstance(s, dict):
                    log(f"  {name}: median {s['median_seconds'] * 1e3:.2f} ms, wrong verdicts {s['wrong_verdicts']} of {s['of']}")
            if "peer_note" in data["summary"]:
                log("  " + data["summary"]["peer_note"])
        elif task == "delays":
            from hapticproof.bench.speed import delay_study, margin_search_study, plot_delays

            data = delay_study(delays=(10, 100, 1000) if quick else (10, 100, 1000, 3000, 10_000),
                               repeat=1 if quick else repeat, log=log)
            data["margin_search"] = margin_search_study(delays=(10, 100) if quick else (10, 100, 1000),
                                                        repeat=1 if quick else repeat, log=log)
            plot_delays(data, outdir / "delays.png")
        elif task == "maps":
            from hapticproof.bench.speed import map_study

            data = map_study(size=40 if quick else 316, delays=(3,) if quick else (0, 3, 10), dask=not quick,
                             stability_size=20 if quick else 100, plot=outdir / "map_passivity.png", log=log)
        elif task == "stress":
            data = stress_study("small" if quick else "large")
            log(f"  {data['cases']} cases; worst relative error {data['worst_relative_error']}; "
                f"wrong verdicts {data['wrong_verdicts']}; escalated to exact {data['escalated_to_exact']}")
        elif task == "lazy":
            data = {"rows": lazy_study(repeat=repeat)}
            for r in data["rows"]:
                log(f"  {r['scene']:26s} lazy {r['lazy_seconds'] * 1e3:8.1f} ms  full {r['full_seconds'] * 1e3:8.1f} ms  "
                    f"skipped {', '.join(r['skipped']) or '-'}")
        else:
            raise ValueError(f"unknown task {task!r}")
        data["seconds"] = time.perf_counter() - start
        write_atomic(outdir / f"{task}.json", json.dumps(jsonable(data), indent=1), "bench")
        summary[task] = {"seconds": data["seconds"]}
    if progress is not None:
        progress(len(tasks), len(tasks), "bench")
    write_atomic(outdir / "summary.json", json.dumps(summary, indent=1), "bench")
    return summary
