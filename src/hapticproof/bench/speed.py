"""Speed studies of whole decisions: the peer library, long delays, design-space maps.

Each study measures side by side in one run and reports medians; every verdict is judged
against the exact answer (DESIGN.md, *Performance and accuracy*). ``hapticproof bench`` runs
them as the tasks ``peers``, ``delays`` and ``maps``; ``benchmarks/bench_peers.py``,
``bench_delays.py`` and ``bench_maps.py`` run one each with more options.

* :func:`peer_study` -- end-to-end numeric decisions (scene from numbers -> verdict with
  certificate) against python-control's ``ispassive`` (KYP LMI solved by cvxopt) on the HVE
  forward-difference virtual wall with ``b`` just above and below the exact boundary;
* :func:`delay_study` -- exact decisions for delays up to 10 000 samples (time, peak memory);
* :func:`map_study` -- exact passivity and stability maps (points per second, serial and parallel).

>>> rows = peer_study(delays=(0,), rels=(1e-2,), repeat=1, peer=False)["rows"]
>>> [(r["side"], r["truth"], r["hapticproof"]["verdict"]) for r in rows]
[('above', True, True), ('below', False, False)]
"""

from __future__ import annotations

import statistics
import time
import tracemalloc
from collections.abc import Callable, Sequence
from fractions import Fraction
from pathlib import Path
from typing import Any

from hapticproof.bench.timing import median_time

__all__ = ["peer_cases", "peer_study", "interleaved", "delay_study", "margin_search_study", "map_study", "plot_peers", "plot_delays",
           "peer_available"]

#: The scene of the comparison (HVE forward-difference virtual wall, Phantom-like numbers).
PEER_SCENE = {"K": Fraction(2), "B": Fraction(1, 1000), "T": Fraction(1, 1000)}


def peer_available() -> str | None:
    """``None`` when python-control and cvxopt import, else the reason (for the skip note)."""
    import importlib

    try:
        for name in ("control", "cvxopt"):
            importlib.import_module(name)
    except ImportError as err:
        return f"python-control/cvxopt not installed ({err.name}); pip install 'hapticproof[bench]'"
    return None


def peer_cases(delays: Sequence[int] = (0, 3, 10), rels: Sequence[float] = (1e-2, 1e-6, 1e-9),
               K: Any = None, B: Any = None, T: Any = None) -> list[dict[str, Any]]:
    """Scenes ``b = b*(1 +- rel)`` around the exact boundary ``b*`` of each delay.

    ``b*`` is the certified critical damping (:func:`hapticproof.analysis.fastpath.critical_damping`);
    its enclosure is required to be much narrower than ``rel`` so that ``truth`` (passive iff
    ``b >= b*``) is exact.
    """
    from hapticproof.analysis.fastpath import NumericScene, critical_damping

    K = PEER_SCENE["K"] if K is None else Fraction(K)
    B = PEER_SCENE["B"] if B is None else Fraction(B)
    T = PEER_SCENE["T"] if T is None else Fraction(T)
    out = []
    for n in delays:
        lo, hi = critical_damping(NumericScene.virtual_wall(K=K, B=B, b=1, T=T, delay=n))
        for rel in rels:
            r = Fraction(rel).limit_denominator(10**12)
            if (hi - lo) * 1000 > r * lo:
                raise ArithmeticError(f"boundary enclosure too wide for rel = {rel}")
            for side, b, truth in (("above", hi * (1 + r), True), ("below", lo * (1 - r), False)):
                out.append({"delay": n, "rel": float(rel), "side": side, "b": b, "truth": truth,
                            "b_star": [str(lo), str(hi)], "K": K, "B": B, "T": T})
    return out


def _ours(case: dict[str, Any]):
    from hapticproof.analysis.fastpath import NumericScene, decide

    def run():
        scene = NumericScene.virtual_wall(K=case["K"], B=case["B"], b=case["b"], T=case["T"], delay=case["delay"])
        return decide(scene)

    return run


def _api(case: dict[str, Any]):
    """The public API as a user calls it: a :class:`~hapticproof.systems.singleuser.SingleUserScene`
    from numbers, :func:`~hapticproof.analysis.positivereal.positive_real` (its stage cache cleared
    after each call: every run is a first decision)."""
    from hapticproof.analysis.positivereal import positive_real
    from hapticproof.core.lazy import clear
    from hapticproof.systems.singleuser import SingleUserScene

    def run():
        scene = SingleUserScene.virtual_wall(K=case["K"], B=case["B"], b=case["b"], T=case["T"], delay=case["delay"])
        out = positive_real(scene)
        clear(scene)
        return out

    return run


def _ispassive(case: dict[str, Any]):
    """:func:`hapticproof.ispassive` on the very ``control.tf`` the peer gets (its floats' exact values)."""
    from hapticproof.analysis.passivity import ispassive

    def run():
        return ispassive(_peer_system(case))

    return run


def _peer_system(case: dict[str, Any], damping: float = 0.0):
    """``G^{-1}(z)`` as a python-control transfer function in ``z`` (floats, ``dt = T``):
    ``(b z^{n+1}(z - r) + (KT + B) z - B) / (z^{n+1}(z - r))`` with ``r = 1 - damping``."""
    import numpy as np

    import control

    n, b, K, B, T = case["delay"], float(case["b"]), float(case["K"]), float(case["B"]), float(case["T"])
    r = 1.0 - damping
    den = np.zeros(n + 3)
    den[0], den[1] = 1.0, -r                         # z^{n+2} - r z^{n+1}
    num = b * den
    num[-2] += K * T + B
    num[-1] += -B
    return control.tf(num, den, T)


def _peer(case: dict[str, Any], damping: float = 0.0):
    import cvxopt

    import control

    cvxopt.solvers.options["show_progress"] = False

    def run():
        try:
            return bool(control.ispassive(_peer_system(case, damping)))
        except Exception as err:  # noqa: BLE001 - a solver failure is the peer's verdict, recorded
            return f"error: {type(err).__name__}"

    return run


def interleaved(funcs: dict[str, Callable[[], Any]], repeat: int) -> dict[str, tuple[Any, float]]:
    """``name -> (last result, median seconds)``, the functions called in turn ``repeat`` times
    (side by side: a drift of the machine's speed hits every column alike)."""
    times: dict[str, list[float]] = {name: [] for name in funcs}
    results: dict[str, Any] = {}
    for _ in range(max(1, repeat)):
        for name, func in funcs.items():
            start = time.perf_counter()
            results[name] = func()
            times[name].append(time.perf_counter() - start)
    return {name: (results[name], statistics.median(times[name])) for name in funcs}


def peer_study(delays: Sequence[int] = (0, 3, 10), rels: Sequence[float] = (1e-2, 1e-6, 1e-9), repeat: int = 15,
               peer: bool = True, reference: bool = True, check: bool = True,
               log: Callable[[str], None] = lambda line: None) -> dict[str, Any]:
    """hapticproof's end-to-end numeric decision against python-control's ``ispassive``.

    For every case, the methods are called in turn ``repeat`` times in this warm process
    (:func:`interleaved`) and their median wall times compared: (a) the fast path, the scene from
    numbers to the whole decision with certificates (:func:`hapticproof.analysis.fastpath.decide`);
    (b) the public API, ``positive_real(SingleUserScene.virtual_wall(...))`` (:func:`_api`); (c)
    :func:`hapticproof.ispassive` on the ``control.tf`` of ``G^{-1}``; (d) python-control's
    ``control.ispassive`` on the same transfer function (its state-space realization and KYP LMI),
    and on a variant with the integrator pole damped to ``z = 1 - 1e-6`` (strictly stable, the usual
    workaround; it changes the exact answer by ``O(1e-6)``). Every verdict is judged against the
    exact answer of the original scene (passive iff ``b >= b*``; the floats of the transfer function
    move the boundary by ~1e-16 relative, far inside the 1e-9 placement). ``reference``: also check
    that :func:`hapticproof.analysis.positivereal.positive_real` on the SymPy scene gives the same
    decision; ``check``: re-verify every certificate with :mod:`hapticproof.exact.checker` (untimed).
    """
    from hapticproof.exact.checker import check_certificates
    from hapticproof.core.evidence import to_jsonable

    cases = peer_cases(delays, rels)
    missing = peer_available() if peer else "not requested"
    variants = {"ispassive": 0.0, "ispassive (pole damped to 1 - 1e-6)": 1e-6} if missing is None else {}
    rows = []
    for case in cases:
        funcs = {"hapticproof": _ours(case), "hapticproof API": _api(case)}
        if missing is None:
            funcs["hapticproof.ispassive"] = _ispassive(case)
        funcs.update({name: _peer(case, damping) for name, damping in variants.items()})
        timed = interleaved(funcs, repeat)
        out, seconds = timed["hapticproof"]
        verdict = out.decision.value == "proved"
        row = {k: (str(v) if isinstance(v, Fraction) else v) for k, v in case.items()}
        row["hapticproof"] = {"seconds": seconds, "verdict": verdict, "decision": out.decision.value,
                              "wrong": verdict != case["truth"]}
        for name in ("hapticproof API", "hapticproof.ispassive"):
            if name in timed:
                value, t = timed[name]
                v = value.decision.value == "proved"
                row[name] = {"seconds": t, "verdict": v, "decision": value.decision.value, "wrong": v != case["truth"]}
        if check:
            results = check_certificates(to_jsonable(out.to_json()))
            row["hapticproof"]["certificates"] = len(results)
            row["hapticproof"]["certificates_verified"] = sum(r.ok and r.verified for r in results)
            row["hapticproof"]["certificates_failed"] = sum(not r.ok for r in results)
        if reference:
            from hapticproof.analysis.fastpath import NumericScene
            from hapticproof.analysis.positivereal import positive_real

            scene = NumericScene.virtual_wall(K=case["K"], B=case["B"], b=case["b"], T=case["T"], delay=case["delay"])
            row["hapticproof"]["reference_agrees"] = positive_real(scene.to_scene()).decision == out.decision
        for name in variants:
            value, t = timed[name]
            row[name] = {"seconds": t, "verdict": value, "wrong": value != case["truth"]}
        rows.append(row)
        shown = [name for name in funcs if name != "hapticproof"]
        log(f"  n={case['delay']:<3d} {case['side']:5s} rel {case['rel']:.0e}: hapticproof {row['hapticproof']['seconds'] * 1e3:7.2f} ms "
            f"{'ok' if not row['hapticproof']['wrong'] else 'WRONG'}"
            + "".join(f" | {name} {row[name]['seconds'] * 1e3:7.2f} ms {'ok' if not row[name]['wrong'] else 'WRONG'}"
                      for name in shown))
    summary = {"cases": len(rows), "hapticproof": _summary(rows, "hapticproof")}
    for name in ("hapticproof API", "hapticproof.ispassive", *variants):
        if name in rows[0]:
            summary[name] = _summary(rows, name)
            summary[name]["median_ratio_to_hapticproof"] = summary[name]["median_seconds"] / summary["hapticproof"]["median_seconds"]
    if "ispassive" in summary:
        peer_median = summary["ispassive"]["median_seconds"]
        for name in ("hapticproof", "hapticproof API", "hapticproof.ispassive"):
            if name in summary:
                summary[name]["median_ratio_to_ispassive"] = summary[name]["median_seconds"] / peer_median
    if missing is not None:
        summary["peer_note"] = f"peer column skipped: {missing}"
    return {"rows": rows, "summary": summary, "scene": {k: str(v) for k, v in PEER_SCENE.items()}, "repeat": repeat}


def _summary(rows: list[dict[str, Any]], name: str) -> dict[str, Any]:
    times = [r[name]["seconds"] for r in rows]
    return {"median_seconds": statistics.median(times), "max_seconds": max(times),
            "wrong_verdicts": sum(bool(r[name]["wrong"]) for r in rows), "of": len(rows)}


def plot_peers(data: dict[str, Any], path: str | Path) -> None:
    """Median time per case, hapticproof against the peer pipelines (wrong verdicts crossed)."""
    from matplotlib.backends.backend_agg import FigureCanvasAgg
    from matplotlib.figure import Figure

    rows = data["rows"]
    names = [k for k in rows[0] if k.startswith(("hapticproof", "ispassive")) and isinstance(rows[0][k], dict)]
    fig = Figure(figsize=(9, 3.8))
    FigureCanvasAgg(fig)
    ax = fig.add_subplot(111)
    xs = range(len(rows))
    labelled = False
    for i, name in enumerate(names):
        ys = [r[name]["seconds"] * 1e3 for r in rows]
        ax.semilogy(xs, ys, "o*sdv"[i % 5] + "-", label=name, alpha=0.8)
        bad = [(x, y) for x, y, r in zip(xs, ys, rows) if r[name]["wrong"]]
        if bad:
            ax.plot([x for x, _ in bad], [y for _, y in bad], "rx", ms=10, mew=2,
                    label=None if labelled else "wrong verdict")
            labelled = True
    ax.set_xticks(list(xs))
    ax.set_xticklabels([f"n={r['delay']} {'+' if r['side'] == 'above' else '-'}{r['rel']:.0e}" for r in rows],
                       rotation=60, fontsize=7)
    ax.set_ylabel("median time per decision (ms)")
    ax.set_title("end-to-end numeric passivity decisions (HVE virtual wall, b near the exact boundary)", fontsize=9)
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=7)
    from hapticproof.core.files import write_figure

    write_figure(fig, path, "bench")


# ---------------------------------------------------------------------------------------------
# long delays
# ---------------------------------------------------------------------------------------------


def delay_study(delays: Sequence[int] = (10, 100, 1000, 3000, 10_000), rels: Sequence[float] = (1e-2, 1e-9, 0.0),
                repeat: int = 3, log: Callable[[str], None] = lambda line: None) -> dict[str, Any]:
    """Exact whole decisions for long delays (HVE virtual wall, ``b = b*(1 +- rel)``; ``rel = 0``:
    exactly at the boundary). Median time per decision and peak traced memory (``tracemalloc``,
    Python allocations; flint's own buffers are not traced), and the time of the boundary
    ``b*`` itself (:func:`hapticproof.analysis.fastpath.critical_damping`, what a delay-margin search or a
    map row calls)."""
    from hapticproof.analysis.fastpath import NumericScene, critical_damping, decide

    K, B, T = PEER_SCENE["K"], PEER_SCENE["B"], PEER_SCENE["T"]
    rows = []
    for n in delays:
        base = NumericScene.virtual_wall(K=K, B=B, b=1, T=T, delay=n)
        (lo, hi), boundary_seconds = median_time(lambda: critical_damping(base), repeat)
        for rel in rels:
            r = Fraction(rel).limit_denominator(10**12)
            sides = (("above", hi * (1 + r), True), ("below", lo * (1 - r), False)) if r else (("at", lo, True),)
            if not r and lo != hi:
                continue
            for side, b, truth in sides:
                scene = base.with_b(b)
                out, seconds = median_time(lambda: decide(scene), repeat)
                tracemalloc.start()
                decide(scene)
                peak = tracemalloc.get_traced_memory()[1]
                tracemalloc.stop()
                cert = out.evidence.facts["conditions"][-1].outcome.evidence.facts.get("certificate")
                row = {"delay": n, "rel": float(rel), "side": side, "seconds": seconds, "decision": out.decision.value,
                       "wrong": (out.decision.value == "proved") != truth, "peak_traced_mb": peak / 2**20,
                       "boundary_seconds": boundary_seconds, "b_star": [str(lo), str(hi)],
                       "certificate": type(cert).__name__}
                rows.append(row)
                log(f"  n={n:<6d} {side:5s} rel {rel:.0e}: {seconds * 1e3:8.1f} ms, {row['decision']}, "
                    f"peak {row['peak_traced_mb']:.1f} MB, b* in {boundary_seconds * 1e3:.1f} ms ({row['certificate']})")
    return {"rows": rows, "wrong_verdicts": sum(r["wrong"] for r in rows)}


def plot_delays(data: dict[str, Any], path: str | Path) -> None:
    from matplotlib.backends.backend_agg import FigureCanvasAgg
    from matplotlib.figure import Figure

    fig = Figure(figsize=(5.5, 3.8))
    FigureCanvasAgg(fig)
    ax = fig.add_subplot(111)
    rows = data["rows"]
    for side, marker in (("above", "o"), ("below", "s"), ("at", "*")):
        sel = [r for r in rows if r["side"] == side]
        if sel:
            ax.loglog([r["delay"] for r in sel], [r["seconds"] for r in sel], marker, label=f"decision, b {side} b*")
    delays = sorted({r["delay"] for r in rows})
    ax.loglog(delays, [next(r["boundary_seconds"] for r in rows if r["delay"] == n) for n in delays], "k--",
              label="boundary b* (one map row)")
    ax.axhline(0.5, color="C3", lw=0.8, ls=":")
    ax.axhline(5, color="C3", lw=0.8, ls=":")
    ax.set_xlabel("delay n (samples)")
    ax.set_ylabel("wall time (s, median)")
    ax.set_title("exact decisions with long delays", fontsize=9)
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=7)
    from hapticproof.core.files import write_figure

    write_figure(fig, path, "bench")


def margin_search_study(delays: Sequence[int] = (10, 100, 1000), repeat: int = 3,
                        log: Callable[[str], None] = lambda line: None) -> dict[str, Any]:
    """The delay margin through the fast decision: for a scene whose exact margin is ``n``
    (``b`` chosen at the boundary of delay ``n``), the largest passive delay found by doubling
    and bisection with :func:`hapticproof.analysis.fastpath.critical_damping` at each probe -- the call a
    delay-margin search (issue 11) makes. Timed end to end, with the number of probes."""
    from hapticproof.analysis.fastpath import NumericScene, critical_damping

    K, B, T = PEER_SCENE["K"], PEER_SCENE["B"], PEER_SCENE["T"]
    rows = []
    for n in delays:
        b = critical_damping(NumericScene.virtual_wall(K=K, B=B, b=1, T=T, delay=n))[1]

        def passive(d: int) -> bool:
            lo, hi = critical_damping(NumericScene.virtual_wall(K=K, B=B, b=1, T=T, delay=d))
            if b >= hi:
                return True
            if b < lo:
                return False
            raise ArithmeticError("b inside the enclosure")

        def search() -> tuple[int, int]:
            probes, good, step = 0, 0, 1
            while True:
                probes += 1
                if not passive(good + step):
                    bad = good + step
                    break
                good, step = good + step, 2 * step
            while bad - good > 1:
                mid = (good + bad) // 2
                probes += 1
                if passive(mid):
                    good = mid
                else:
                    bad = mid
            return good, probes

        (found, probes), seconds = median_time(search, repeat)
        rows.append({"delay": n, "found": found, "probes": probes, "seconds": seconds, "correct": found == n})
        log(f"  margin n = {n:<6d}: found {found} with {probes} exact probes in {seconds * 1e3:.1f} ms")
    return {"rows": rows}


# ---------------------------------------------------------------------------------------------
# design-space maps
# ---------------------------------------------------------------------------------------------


def map_study(size: int = 316, delays: Sequence[int] = (0, 3, 10), workers: int = 2, dask: bool = True,
              stability_size: int = 100, plot: str | Path | None = None,
              log: Callable[[str], None] = lambda line: None) -> dict[str, Any]:
    """Exact passivity maps of ``size x (size + 1)`` points (``K`` rows, ``b`` lines; HVE virtual
    wall, ``T = 1 ms``, ``B = 0.001``) serially on one process, with ``workers`` local processes
    and on a Dask ``LocalCluster`` (its start-up included), checking that the three give identical
    values; and an exact stability map (``K`` lines over ``T``) of ``stability_size^2`` points."""
    from hapticproof.analysis import designmap as dm
    from hapticproof.systems.scene import Scene

    rows = []
    first = None
    for n in delays:
        spec = dm.MapSpec.build("passivity", f"b=0.0005:0.05:{size + 1}", f"K=0.1:20:{size}",
                                Scene("single-user", delay=n, params={"T": "0.001", "B": "0.001"}))
        modes = [("serial", {}), (f"{workers} processes", {"workers": workers})]
        if dask:
            modes.append((f"dask LocalCluster ({workers} workers)", {"scheduler": "dask", "workers": workers}))
        reference = None
        for mode, kwargs in modes:
            if mode.startswith("dask") and _missing("distributed"):
                continue
            startup = 0.0
            client = None
            if "scheduler" in kwargs:        # the cluster's start-up reported apart from the map
                from hapticproof.analysis.scaleout import dask_client

                start = time.perf_counter()
                client = dask_client("dask", workers)
                client.run(lambda: __import__("hapticproof.analysis.designmap"))
                startup = time.perf_counter() - start
                kwargs = {"client": client}
            try:
                result = dm.compute(spec, **kwargs)
            finally:
                if client is not None:
                    cluster = client.cluster
                    client.close()
                    cluster.close()
            same = reference is None or bool((result.values == reference).all())
            reference = result.values if reference is None else reference
            rows.append({"quantity": "passivity", "delay": n, "points": spec.points, "mode": mode,
                         "seconds": result.seconds, "points_per_second": spec.points / result.seconds,
                         "startup_seconds": startup, "identical_to_serial": same, **result.counts})
            log(f"  passivity n={n:<3d} {spec.points} points, {mode:28s}: {result.seconds:6.2f} s "
                f"({spec.points / result.seconds:9.0f} points/s)"
                + (f" + cluster start-up {startup:.1f} s" if startup else "") + ("" if same else " DIFFERENT VALUES"))
            if first is None:
                first = result
    spec = dm.MapSpec.build("stability", f"T=0.0005:0.004:{stability_size}", f"K=1:80:{stability_size}",
                            Scene("single-user", delay=2, params={"m": "0.015", "b": "0.02", "B": "0.002"}))
    result = dm.compute(spec)
    rows.append({"quantity": "stability", "delay": 2, "points": spec.points, "mode": "serial",
                 "seconds": result.seconds, "points_per_second": spec.points / result.seconds,
                 "identical_to_serial": True, **result.counts})
    log(f"  stability n=2 {spec.points} points, serial: {result.seconds:.2f} s; {result.counts}")
    if plot is not None and first is not None:
        dm.plot_map(first, plot)
        dm.plot_map(result, Path(plot).with_name("map_stability.png"))
    return {"rows": rows}


def _missing(module: str) -> bool:
    import importlib.util

    return importlib.util.find_spec(module) is None
