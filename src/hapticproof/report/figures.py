"""Reproductions of the papers' simulation figures: data, comparison tables and plots.

* HVE paper (000), Fig. 8 a-e: exact stability boundaries ``K*(T)`` of the Simulink setups
  next to the printed borderlines (26), (27), (55), (63); Fig. 9: the printed lines (20) and
  (25) against the exact boundary of the free device.
* Teleoperator paper (002), Fig. 3 a-c: passive / non-passive regions found by the passivity
  observer with the printed borderline (35) and the exact free/free stability boundary drawn
  on top; Table I: master-slave tracking error.

Every function returns data (and writes a PNG when given a path); the notebook only calls them.
Grids default to the papers' ranges; pass coarser ones for quick looks.

Choices the papers leave open (documented here, used below):

* Fig. 8: T from 1 ms in 1 ms steps up to 20 ms. Fig. 8c overlays the ``z_a = 0.5 b`` curves
  of panels (a) (no delay, m = 0.015, b = 0.02) and (b) (t_d = 10T, m = 0.15, b = 0.2).
* Teleoperator Fig. 3: both terminations ``Z(s) = 0.05 + 1/s`` (a 0.05 N s/m damper and a
  1 N/m spring: first-order, positive real); the ports are driven antisymmetrically,
  ``f_h = -f_e = sin(2 pi 2 t)`` N (the differential mode, which carries the controller's
  energy leak), from rest, for ``steps`` samples; a point is non-passive when the total port
  energy ``int f_h v_m + int f_e v_s`` (teleoperator (8)) is ever negative.
* Table I: free/free robots (m = 0.015, b = 0.01822, B = 0); the operator is an ideal force
  source ``f_h = sin(2 pi t)`` N on the master, 10 s; MSE = ``100 int (x_m - x_s)^2 /
  int x_m^2`` (exact integrals); stability from the spectral radius.

>>> fig = hve_fig9("a", T_values=[0.001, 0.01])
>>> [round(r["ratio"], 5) for r in fig.table()]
[1.0002, 1.00203]
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np

from hapticproof.analysis.borderlines import printed_borderline
from hapticproof.core.errors import SceneError
from hapticproof.analysis.maps import BoundaryCurve, PlaneMap, SceneFamily, boundary_curve, passivity_map, plot_curves, plot_map
from hapticproof.systems.loops import Teleoperator
from hapticproof.analysis.sampled import is_stable
from hapticproof.analysis.simulate import Excitation, tracking_mse

__all__ = [
    "CurveFigure",
    "MapFigure",
    "hve_fig8",
    "hve_fig9",
    "teleop_fig3",
    "teleop_table1",
    "FIG8_T",
    "text_table",
]

#: The sampling periods of HVE Fig. 8/9: 1 ms to 20 ms in 1 ms steps.
FIG8_T = tuple(k / 1000 for k in range(1, 21))


@dataclass(frozen=True, slots=True, eq=False)
class CurveFigure:
    """Exact boundaries and printed borderlines of one figure panel."""

    name: str
    curves: tuple[BoundaryCurve, ...]
    path: Path | None = None

    def table(self) -> list[dict[str, Any]]:
        """One row per curve and T: exact, printed, their ratio and whether printed is safe.

        ``ratio = K_exact / K_printed``; ``safe`` is False where the printed borderline admits
        gains that are actually unstable (``K_printed > K_exact``).
        """
        rows = []
        for curve in self.curves:
            for x, exact, printed in zip(curve.grid, curve.exact, curve.printed_values):
                ratio = exact / printed if np.isfinite(printed) and printed != 0 else float("nan")
                rows.append({
                    "curve": curve.label, "T_ms": round(x * 1000, 6), "K_exact": float(exact),
                    "K_printed": float(printed), "ratio": float(ratio),
                    "safe": bool(printed <= exact) if np.isfinite(printed) else None,
                })
        return rows

    def summary(self) -> list[dict[str, Any]]:
        """Per curve: printed condition, min/max ratio, and the T values where it is unsafe."""
        out = []
        for curve in self.curves:
            ratio = curve.ratio
            finite = ratio[np.isfinite(ratio)]
            out.append({
                "curve": curve.label,
                "printed": curve.printed_label,
                "min_ratio": float(finite.min()) if finite.size else float("nan"),
                "max_ratio": float(finite.max()) if finite.size else float("nan"),
                "unsafe_T_ms": [round(t * 1000, 6) for t, r in zip(curve.grid, ratio) if r < 1],
                "multiple_crossings": [round(t * 1000, 6) for t, b in zip(curve.grid, curve.boundaries)
                                       if b.multiple],
            })
        return out


def _curve(family: SceneFamily, T_values, label, workers, rtol) -> BoundaryCurve:
    return boundary_curve(
        family, "K", ("T", T_values), printed_borderline=printed_borderline(family, "K"),
        rtol=rtol, workers=workers, label=label,
    )


def _operator_family(system, m, b, delay, z_a, **extra) -> SceneFamily:
    return SceneFamily(system, {"m": m, "b": b, "B": 0, "z_a": z_a}, operator="-z_a + 1/s",
                       delay=delay, **extra)


_FIG8 = {
    # panel: (system, m, b, delay, z_a fractions of b)
    "a": ("single-user", 0.015, 0.02, 0, (0.0, 0.5, 0.8)),
    "b": ("single-user", 0.15, 0.2, 10, (0.0, 0.2, 0.5)),
    "d": ("multi-user", 0.015, 0.01822, 0, (0.0, 0.2, 0.5)),
    "e": ("multi-user", 0.15, 0.1822, 5, (0.0, 0.2, 0.5)),
}


def hve_fig8(
    panel: str,
    T_values: Sequence[float] = FIG8_T,
    *,
    path: str | Path | None = None,
    workers: int | None = None,
    rtol: float = 1e-10,
) -> CurveFigure:
    """HVE paper Fig. 8 panel ``a``-``e``: exact ``K*(T)`` vs the printed borderline.

    Operators ``Z_h = -z_a + 1/s`` (Section 4); dual-user panels use
    ``K_01 = K_02 = K_12 = K/2`` and ``B = 0``.

    >>> fig = hve_fig8("a", T_values=[0.002])
    >>> [round(r["ratio"], 4) for r in fig.table()]
    [1.0005, 1.0002, 1.0001]
    """
    if panel == "c":
        curves = tuple(
            _curve(_operator_family(*_FIG8[p][:4], 0.5 * _FIG8[p][2]), T_values, label, workers, rtol)
            for p, label in (("a", "no delay, z_a=0.5b"), ("b", "t_d=10T, z_a=0.5b"))
        )
    elif panel in _FIG8:
        system, m, b, delay, fractions = _FIG8[panel]
        curves = tuple(
            _curve(_operator_family(system, m, b, delay, frac * b), T_values,
                   f"z_a={frac:g}b", workers, rtol)
            for frac in fractions
        )
        if panel == "e":  # the dual-user delayed condition (61), which (62)/(63) generalise
            curves += tuple(_with_condition(c, "hve-61") for c in curves)
    else:
        raise SceneError(f"HVE Fig. 8 has panels a-e, got {panel!r}")
    out = CurveFigure(f"HVE Fig. 8{panel}", curves)
    if path is not None:
        plot_curves(curves, path, title=out.name, scale={"T": 1000})
        out = CurveFigure(out.name, curves, Path(path))
    return out


def _with_condition(curve: BoundaryCurve, key: str) -> BoundaryCurve:
    """The same exact boundaries against another printed condition."""
    border = printed_borderline(curve.family, curve.vary, key)
    printed = tuple(border(curve.family.printed_values(**{curve.over: x})) for x in curve.grid)
    return BoundaryCurve(curve.family, curve.vary, curve.over, curve.grid, curve.boundaries,
                         printed, border.condition.label, f"{curve.label} vs {border.condition.label}")


def hve_fig9(
    panel: str,
    T_values: Sequence[float] = FIG8_T,
    *,
    path: str | Path | None = None,
    workers: int | None = None,
    rtol: float = 1e-10,
) -> CurveFigure:
    """HVE paper Fig. 9: printed (20) (``a``) and (25) with ``t_d = 10T`` (``b``) against the
    exact boundary of the free device (m = 0.015, b = 0.01822, B = 0)."""
    if panel not in ("a", "b"):
        raise SceneError(f"HVE Fig. 9 has panels a and b, got {panel!r}")
    delay = 0 if panel == "a" else 10
    family = SceneFamily("single-user", {"m": 0.015, "b": 0.01822, "B": 0}, delay=delay)
    curves = (_curve(family, T_values, "free device" + (", t_d=10T" if delay else ""), workers, rtol),)
    out = CurveFigure(f"HVE Fig. 9{panel}", curves)
    if path is not None:
        plot_curves(curves, path, title=out.name, scale={"T": 1000})
        out = CurveFigure(out.name, curves, Path(path))
    return out


def text_table(rows: Sequence[dict[str, Any]], digits: int = 4) -> str:
    """Rows of dicts as an aligned text table, floats rounded to ``digits`` significant digits
    (so printed tables do not depend on the last bits of a machine's arithmetic).

    >>> print(text_table([{"T_ms": 1.0, "ratio": 1.000227}, {"T_ms": 2.0, "ratio": 0.6674}]))
     T_ms   ratio
    1.000   1.000
    2.000  0.6674
    """
    def cell(value: Any) -> str:
        if isinstance(value, float):
            if not np.isfinite(value):
                return str(value)
            return f"{value:#.{digits}g}" if abs(value) >= 1e-3 or value == 0 else f"{value:.{digits - 1}e}"
        if isinstance(value, list):
            return ",".join(cell(v) for v in value) or "-"
        return str(value)

    if not rows:
        return ""
    keys = list(rows[0])
    cells = [[cell(r[k]) for k in keys] for r in rows]
    widths = [max(len(k), *(len(c[i]) for c in cells)) for i, k in enumerate(keys)]
    lines = ["  ".join(k.rjust(w) for k, w in zip(keys, widths))]
    lines += ["  ".join(c.rjust(w) for c, w in zip(row, widths)) for row in cells]
    return "\n".join(line.rstrip() for line in lines)


# --------------------------------------------------------------------------------------------
# teleoperator
# --------------------------------------------------------------------------------------------
#: The passive first-order termination used at both ports for the observer maps.
TERMINATION = "0.05 + 1/s"
#: Antisymmetric 2 Hz excitation of the two ports (N).
EXCITATION = Excitation((1.0, -1.0), 2.0)


@dataclass(frozen=True, slots=True, eq=False)
class MapFigure:
    """A passivity map with the printed borderline and the exact FF stability boundary."""

    name: str
    plane: PlaneMap
    printed: tuple[np.ndarray, np.ndarray]
    exact: BoundaryCurve
    path: Path | None = None

    def agreement(self) -> dict[str, float]:
        """Fraction of grid points where the observer and the printed condition (35) agree,
        and where the observer finds non-passivity inside the printed passive region."""
        plane = self.plane
        xs, ys = np.meshgrid(plane.x_values, plane.y_values)
        inside = _printed_passive(self.name, xs, ys)
        observer = plane.good
        return {
            "agree": float(np.mean(inside == observer)),
            "observer_nonpassive_inside_printed": float(np.mean(inside & ~observer)),
            "observer_passive_outside_printed": float(np.mean(~inside & observer)),
        }


_B, _M = 0.01822, 0.015
_FIG3 = {
    # panel: fixed params, x axis, y axis, borderline y(x) from (35) with B = 0
    "a": ({"m": _M, "b": _B, "B": 0}, ("T", (0.001, 0.02)), ("K", (0.25, 25.0))),
    "b": ({"m": _M, "K": 1.0, "B": 0}, ("T", (0.001, 0.02)), ("b", (0.0005, 0.03))),
    "c": ({"m": _M, "T": 0.001, "B": 0}, ("K", (0.5, 40.0)), ("b", (0.0005, 0.04))),
}


def _printed_passive(name: str, xs: np.ndarray, ys: np.ndarray) -> np.ndarray:
    """Condition (35) ``b > K T + 2B`` (B = 0) on the panel's axes."""
    panel = name[-1]
    if panel == "a":
        return _B > ys * xs
    if panel == "b":
        return ys > 1.0 * xs
    return ys > xs * 0.001


def teleop_fig3(
    panel: str,
    nx: int = 40,
    ny: int = 40,
    *,
    steps: int = 2000,
    path: str | Path | None = None,
    workers: int | None = None,
) -> MapFigure:
    """Teleoperator paper Fig. 3 panel ``a`` (K-T), ``b`` (b-T) or ``c`` (K-b).

    >>> fig = teleop_fig3("a", nx=3, ny=4, steps=400)
    >>> fig.plane.good.astype(int).tolist()
    [[1, 1, 1], [1, 0, 0], [1, 0, 0], [1, 0, 0]]
    """
    if panel not in _FIG3:
        raise SceneError(f"teleoperator Fig. 3 has panels a-c, got {panel!r}")
    params, (xn, (x0, x1)), (yn, (y0, y1)) = _FIG3[panel]
    xs, ys = np.linspace(x0, x1, nx), np.linspace(y0, y1, ny)
    family = SceneFamily("teleoperator", params, operator=TERMINATION, environment=TERMINATION)
    plane = passivity_map(family, (xn, xs), (yn, ys), steps=steps, excitation=EXCITATION,
                          workers=workers)
    fine = np.linspace(x0, x1, 200)
    if panel == "a":
        printed = (fine, _B / fine)
    elif panel == "b":
        printed = (fine, 1.0 * fine)
    else:
        printed = (fine, fine * 0.001)
    free = SceneFamily("teleoperator", params)
    exact = boundary_curve(free, yn, (xn, np.linspace(x0, x1, max(nx // 2, 2))), workers=workers,
                           label="exact FF stability")
    name = f"teleoperator Fig. 3{panel}"
    out = MapFigure(name, plane, printed, exact)
    if path is not None:
        scale = {"T": 1000}
        plot_map(plane, path, [("printed (35)", *printed),
                               ("exact FF stability", np.array(exact.grid), exact.exact)],
                 title=name + f" (observer, Z = {TERMINATION})", scale=scale)
        out = MapFigure(name, plane, printed, exact, Path(path))
    return out


def teleop_table1(
    T_values: Sequence[float] = (0.007, 0.015),
    K_values: Sequence[float] = (0.4, 1.0, 2.0, 2.4),
    *,
    seconds: float = 10.0,
) -> list[dict[str, Any]]:
    """Teleoperator paper Table I: tracking MSE (%) and stability per ``(T, K)``.

    >>> rows = teleop_table1(T_values=[0.015], K_values=[1.0, 2.0], seconds=2)
    >>> [(r["K"], r["stable"]) for r in rows]
    [(1.0, True), (2.0, False)]
    """
    rows = []
    excitation = Excitation((1.0, 0.0), 1.0)
    for T in T_values:
        for K in K_values:
            scene = Teleoperator.symmetric(m=_M, b=_B, T=T, K=K)
            stable = is_stable(scene)
            steps = int(round(seconds / T))
            mse = tracking_mse(scene, steps, excitation) if stable else float("inf")
            rows.append({"T_ms": round(T * 1000, 6), "K": float(K), "stable": stable,
                         "mse_percent": mse})
    return rows
