r"""The Z-width of a haptic device: the virtual walls it renders passively, and where its exact
sampled-data loop stays stable (Colgate & Brown, *Factors affecting the Z-width of a haptic
display*, ICRA 1994).

A device (damping ``b``, period ``T``, delay ``n``, mass ``m``) renders the virtual wall
``H(z) = K + B(z - 1)/(Tz)`` (or any environment of the scene, its stiffness and damping named
by the user). Its Z-width is drawn in the stiffness-damping plane from two exact computations
of the one map system (:mod:`hapticproof.analysis.designmap`) and the boundary code:

* **passive region** -- the scene's model ``G^{-1}`` positive real (HVE paper, Section 3.1): the
  exact verdict at every grid point (:func:`~hapticproof.analysis.designmap.compute`, quantity
  ``passivity``) and, for every damping value, the exact passive range of the stiffness
  (:func:`~hapticproof.analysis.passiverange.passive_range`, rational or algebraic ends);
* **stable region** -- the exact ZOH loop of the device with its mass on the wall (Gil et al.
  2004): the certified verdict at every grid point (quantity ``stability``) and, for every
  damping value, the certified critical stiffness
  (:func:`~hapticproof.analysis.boundary.critical_stiffness` for the wall, else the certified
  crossing of :func:`~hapticproof.analysis.maps.find_boundary`).

With the forward model of the integrator (the default) the passive region is Colgate and
Schenkel's ``b >= KT/2 + |B|`` (a virtual damping ``B < 0`` included); the backward and Tustin
models are passive for every stiffness while the exact loop is not, which is what the stable
region tells.

>>> from hapticproof.systems.scene import Scene
>>> device = Scene("single-user", params={"b": "0.02", "T": "0.001", "m": "0.015"})
>>> zw = zwidth(device, stiffness="K=0:60:7", damping="B=0:0.02:3")
>>> [(str(line.damping), line.passive_text) for line in zw.lines]      # K_max = 2(b - B)/T
[('0', '0 < K <= 40'), ('1/100', '0 < K <= 20'), ('1/50', 'never passive')]
>>> [round(line.stable_max, 3) for line in zw.lines]        # the exact loop: K* ~ 2(b + B)/T
[40.009, 59.973, 79.911]
"""

from __future__ import annotations

import csv
import io
import math
from dataclasses import dataclass
from fractions import Fraction
from pathlib import Path
from typing import Any

import sympy as sp

from hapticproof.core.errors import InputFormatError, SceneError

__all__ = ["ZWidthLine", "ZWidth", "zwidth", "loop_notes"]


@dataclass(frozen=True)
class ZWidthLine:
    """One damping value of the Z-width: the exact passive range of the stiffness and the exact
    loop's stable stiffnesses (``stable_min < K < stable_max``, certified to ``stable_tolerance``;
    ``None`` without a mass, ``stable_note`` says why)."""

    damping: Fraction
    passive: Any                              # ParameterRange of the stiffness
    stable_min: float | None = None
    stable_max: float | None = None
    stable_tolerance: float | None = None
    stable_note: str = ""

    @property
    def passive_max(self) -> Any:
        """The largest passive stiffness (an exact :class:`~hapticproof.analysis.passiverange.Endpoint`),
        ``None`` when the range is unbounded or empty."""
        return self.passive.maximum()

    @property
    def passive_text(self) -> str:
        """The exact passive set of the stiffness, as ``0 < K <= 38``."""
        return _passive_text(self.passive)

    @property
    def passive_unbounded(self) -> bool:
        return bool(self.passive.intervals) and self.passive.intervals[-1][2] is None

    def exceeds(self) -> bool:
        """The model is passive at stiffnesses where the exact loop is unstable."""
        if self.stable_max is None or not self.passive.intervals:
            return False
        tolerance = self.stable_tolerance or 0.0
        low = self.passive.minimum()
        if self.stable_min and (low is None or float(low.approx(17)) < self.stable_min - tolerance):
            return True              # passive soft walls a large virtual damping destabilises
        if self.passive_unbounded:
            return True
        return float(self.passive_max.approx(17)) > self.stable_max + tolerance


@dataclass(frozen=True)
class ZWidth:
    """The Z-width of a device: the grid maps (``passivity``; ``stability`` when the mass is
    known) and one :class:`ZWidthLine` per damping value."""

    scene: Any
    stiffness: str
    damping: str
    passivity: Any                            # designmap.MapResult
    stability: Any                            # designmap.MapResult or None
    lines: tuple[ZWidthLine, ...]

    def to_csv(self, path: str | Path | None = None) -> str:
        """One row per damping value: the passive stiffnesses (exact and as a number) and the
        exact loop's stable ones.

        Columns: ``<damping>``, ``<stiffness>_passive`` (the exact set, e.g. ``0 < K <= 38``),
        ``<stiffness>_passive_max`` (``inf`` unbounded, empty when never passive),
        ``<stiffness>_stable_min``, ``<stiffness>_stable_max``, ``stable_tolerance`` (the certified
        half-width), ``passive_but_unstable`` (1 where the model is passive beyond the loop's
        stability)."""
        k = self.stiffness
        buf = io.StringIO()
        writer = csv.writer(buf, lineterminator="\n")
        writer.writerow([self.damping, f"{k}_passive", f"{k}_passive_max", f"{k}_stable_min", f"{k}_stable_max",
                         "stable_tolerance", "passive_but_unstable"])
        for line in self.lines:
            passive = _passive_text(line.passive)
            if not line.passive.intervals:
                top = ""
            elif line.passive_unbounded:
                top = "inf"
            else:
                top = str(line.passive_max.value) if line.passive_max.value is not None else line.passive_max.approx(17)
            writer.writerow([_number(line.damping), passive, top, _float(line.stable_min), _float(line.stable_max),
                             _float(line.stable_tolerance), int(line.exceeds())])
        text = buf.getvalue()
        if path is not None:
            from hapticproof.core.files import write_atomic

            write_atomic(path, text)
        return text

    def to_text(self) -> str:
        """A summary: the region's corners and where the model's passivity exceeds the exact loop."""
        mass = self.scene.role("mass")
        lines = [self.title() + ":"]
        width = max(len(_number(line.damping)) for line in self.lines)
        for line in self.lines:
            stable = (f"stable {line.stable_min:.6g} < {self.stiffness} < {line.stable_max:.6g}"
                      if line.stable_max is not None else line.stable_note)
            flag = "   <- passive model beyond the stable loop" if line.exceeds() else ""
            lines.append(f"  {self.damping} = {_number(line.damping).ljust(width)}  "
                         f"{_passive_text(line.passive):<28} {stable}{flag}")
        counts = self.passivity.counts
        lines.append(f"grid {len(self.passivity.spec.x.values)} x {len(self.passivity.spec.y.values)}: "
                     + ", ".join(f"{k} {v}" for k, v in counts.items())
                     + ("" if self.stability is None else "; " + ", ".join(f"{k} {v}" for k, v in
                                                                         self.stability.counts.items())))
        if self.stability is None:
            lines.append(f"(no stability overlay: give the device mass, --param {mass}=VALUE)")
        return "\n".join(lines)

    def plot(self, path: str | Path, title: str = "") -> Path:
        """The Z-width figure: the two exact maps as one image (light green: passive and stable;
        orange: a passive model whose exact loop is unstable), the exact passive boundary (black)
        and the exact loop's stability boundary (blue, dashed) on top."""
        from hapticproof.analysis.designmap import plot_map

        curves = []
        finite = [(float(line.passive_max.approx(17)), float(line.damping)) for line in self.lines
                  if line.passive.intervals and not line.passive_unbounded]
        if finite:
            curves.append(("passive boundary (exact)", [p[0] for p in finite], [p[1] for p in finite], "k-"))
        stable = [(line.stable_max, float(line.damping)) for line in self.lines if line.stable_max is not None]
        if stable:
            curves.append(("stability boundary (exact ZOH loop)", [p[0] for p in stable], [p[1] for p in stable],
                           "b--"))
        return plot_map(self.passivity, path, title or self.title(), overlay=self.stability, curves=curves)

    def title(self) -> str:
        """``Z-width: b = 0.02, T = 0.001, m = 0.015; forward model, no delay``."""
        scene = self.scene
        fixed = ", ".join(f"{name} = {_decimal(value)}" for name, value in _fixed(scene, (self.stiffness, self.damping)))
        delay = f"delay {scene.delay}" if scene.delay else "no delay"
        return f"Z-width: {fixed}; {scene.approximation or 'forward'} model, {delay}"


def _fixed(scene: Any, skip: tuple[str, ...]) -> list[tuple[str, Any]]:
    return [(k, v) for k, v in sorted(scene.param_values.items(), key=lambda kv: str(kv[0]))
            if k not in skip and isinstance(v, sp.Basic) and v.is_Rational]


def _decimal(value: Any) -> str:
    """An exact value as people write it: ``0.015`` (a short decimal), else ``1/3``.

    >>> _decimal(sp.Rational(3, 200)), _decimal(sp.Rational(1, 3)), _decimal(sp.Integer(20))
    ('0.015', '1/3', '20')
    """
    q = Fraction(int(value.p), int(value.q))
    for digits in range(13):
        if (q * 10**digits).denominator == 1:
            return f"{float(q):.{digits}f}" if digits else str(q.numerator)
    return str(q)


def _passive_text(rng: Any) -> str:
    return rng.to_text().split(": ", 1)[1].split("   [")[0]


def _number(value: Fraction) -> str:
    return str(value.numerator) if value.denominator == 1 else repr(float(value))


def _float(value: float | None) -> str:
    return "" if value is None else repr(float(value))


def _axis(text: str | None, default_name: str) -> Any:
    """``NAME=start:stop:count`` or ``start:stop:count`` (the default name) as a map axis."""
    from hapticproof.analysis.designmap import Axis

    if text is None:
        return None
    return Axis.parse(text if "=" in text else f"{default_name}={text}")


def _is_wall(scene: Any, stiffness: str, damping: str) -> bool:
    """The device on the virtual wall ``K + B(z-1)/(Tz)`` itself (the boundary code's closed form)."""
    return (scene.environment is None and scene.discretize is None and scene.operator is None and not scene.active
            and (stiffness, damping) == ("K", "B"))


def _stable_interval(scene: Any, stiffness: str, damping: str, value: Fraction, row: Any = None) -> tuple:
    """``(K_min, K_max, tolerance, note)`` of the exact loop at one damping: the certified
    critical stiffness of the wall, or the first certified crossing of another environment (searched
    between the grid stiffnesses where the stability map's ``row`` of ``(K, verdict)`` turns)."""
    from hapticproof.analysis.boundary import arb_interval, critical_stiffness

    at = scene.with_params({damping: sp.Rational(value.numerator, value.denominator)})
    mass = at.role("mass")
    values = at.resolved_values()
    if values.get(mass) is None or not values[mass].is_Rational:
        return None, None, None, f"no stability boundary: the mass {mass} is not given"
    if _is_wall(at, stiffness, damping) and value >= 0:
        try:
            cs = critical_stiffness(m=values[mass], b=values[at.role("device_damping")],
                                    T=values[at.role("period")], B=values[damping], n=int(at.delay))
        except (ArithmeticError, SceneError):
            cs = None
        if cs is not None:
            if cs.mode == "unstable":
                return 0.0, 0.0, 0.0, "unstable for every stiffness"
            lo, hi = arb_interval(cs.K)
            lower = float(arb_interval(cs.lower * cs.K / cs.beta)[0]) if cs.lower > 0 else 0.0
            return lower, float((lo + hi) / 2), float((hi - lo) / 2), ""
    from hapticproof.analysis.maps import find_boundary
    from hapticproof.analysis.stability import SceneLoops

    search = None
    if row is not None:
        verdicts = [v for _, v in row]
        if all(v == 1 for v in verdicts):
            return None, None, None, "stable at every stiffness of the grid"
        if all(v == 0 for v in verdicts):
            return None, None, None, "unstable at every stiffness of the grid"
        for (k0, v0), (k1, v1) in zip(row, row[1:]):
            if v0 == 1 and v1 == 0:
                search = (float(k0) if k0 > 0 else float(k1) * 1e-6, float(k1))
                break
    bnd = find_boundary(SceneLoops(at.with_params({stiffness: None})), stiffness, search=search)
    if bnd.value is None or bnd.direction != "destabilising" or not bnd.certified:
        return None, None, None, f"stability boundary not certified: {bnd.note or bnd.direction}"
    return 0.0, float(bnd.value), float(bnd.tolerance), ""


def zwidth(scene: Any, *, stiffness: str | None = None, damping: str | None = None, workers: int = 1,
           scheduler: str | None = None, progress: Any = None) -> ZWidth:
    """The Z-width of the single-user ``scene`` (a :class:`~hapticproof.systems.scene.Scene` whose
    device damping, period and delay are numbers; its mass gives the stability overlay).

    ``stiffness`` and ``damping`` are the axes, ``NAME=start:stop:count`` (``start:stop:count``
    names the wall's ``K`` and ``B``); without them the stiffness runs from its first positive grid
    value to past both boundaries at zero damping (80 values; 40 for another environment, whose
    stability is decided point by point; at ``K = 0`` the device drifts, never stable) and the
    damping from 0 to the device damping (41; 21).
    """
    from hapticproof.analysis.designmap import MapSpec, compute
    from hapticproof.analysis.passiverange import passive_range

    if scene.system != "single-user":
        raise InputFormatError(f"the Z-width is of a single-user device, not a {scene.system} scene")
    k_axis, b_axis = _axis(stiffness, "K"), _axis(damping, "B")
    k_name = k_axis.name if k_axis is not None else "K"
    b_name = b_axis.name if b_axis is not None else "B"
    if k_name == b_name:
        raise InputFormatError(f"the stiffness and the damping are both {k_name}")
    names = scene.names()
    for name, what in ((k_name, "stiffness"), (b_name, "damping")):
        if name not in names:
            raise InputFormatError(f"the scene has no {what} {name!r} (its parameters: {', '.join(sorted(names))}); "
                                   f"name it: --{what} NAME=start:stop:count")
    scene = scene.with_params({k_name: None, b_name: None})
    values = scene.resolved_values()
    for role in ("device_damping", "period"):
        name = scene.role(role)
        if values.get(name) is None or not values[name].is_Rational:
            raise InputFormatError(f"the Z-width needs the {role.replace('_', ' ')} {name} (--param {name}=VALUE)")
    wall = _is_wall(scene, k_name, b_name)            # elsewhere each point costs a certified radius
    if b_axis is None:
        top = values[scene.role("device_damping")]
        b_axis = _axis(f"{b_name}=0:{top}:{41 if wall else 21}", b_name)
    if k_axis is None:
        # from the first positive stiffness: at K = 0 the device drifts (an eigenvalue at z = 1, not
        # stable), a line of the map but no width of the Z-width
        top, count = _stiffness_top(scene, k_name, b_name), 80 if wall else 40
        k_axis = _axis(f"{k_name}={top / count}:{top}:{count}", k_name)
    spec = MapSpec.build("passivity", k_axis, b_axis, scene)
    passivity = compute(spec, workers=workers, scheduler=scheduler, progress=progress)
    mass = scene.role("mass")
    stability = None
    if values.get(mass) is not None and values[mass].is_Rational:
        stability = compute(MapSpec.build("stability", k_axis, b_axis, scene), workers=workers, scheduler=scheduler)
    lines = []
    for i, value in enumerate(b_axis.values):
        at = scene.with_params({b_name: sp.Rational(value.numerator, value.denominator)})
        rng = passive_range(at, k_name)
        row = None if stability is None else list(zip(k_axis.values, stability.values[i].tolist()))
        lo, hi, tol, note = _stable_interval(scene, k_name, b_name, value, row)
        lines.append(ZWidthLine(value, rng, lo, hi, tol, note))
    return ZWidth(spec.scene, k_name, b_name, passivity, stability, tuple(lines))


def _stiffness_top(scene: Any, k_name: str, b_name: str) -> Fraction:
    """A round stiffness past the passive and the stability boundary at zero damping."""
    from hapticproof.analysis.passiverange import passive_range

    ends = []
    rng = passive_range(scene.with_params({b_name: 0}), k_name)
    if rng.intervals and rng.intervals[-1][2] is not None:
        ends.append(float(rng.maximum().approx(17)))
    _, stable, _, _ = _stable_interval(scene, k_name, b_name, Fraction(0))
    if stable:
        ends.append(stable)
    if not ends or max(ends) <= 0:
        raise InputFormatError(f"no passive or stability boundary of {k_name} at {b_name} = 0 to size the plane: "
                               f"give --stiffness {k_name}=start:stop:count")
    top = 1.25 * max(ends)
    step = 10 ** math.floor(math.log10(top))
    return Fraction(math.ceil(top / step)) * Fraction(step).limit_denominator(10**12)


def loop_notes(scene: Any, decision: Any = None, ranges: Any = ()) -> list[str]:
    """Where the model's passivity exceeds the exact loop's stability for the scene's mass (a
    single-user scene whose parameters are numbers): the scene itself proved passive while its exact
    ZOH loop is certainly unstable, and each passive range reaching past the loop's stability
    boundary of that parameter. Empty without a mass.

    >>> from hapticproof.systems.scene import Scene
    >>> from hapticproof.analysis.passiverange import passive_range
    >>> wall = Scene("single-user", approximation="tustin",
    ...              params={"b": "0.02", "B": "0.001", "T": "0.001", "m": "0.015", "K": 50})
    >>> print("\\n".join(loop_notes(wall, "proved", [passive_range(wall, "K")])))   # doctest: +NORMALIZE_WHITESPACE
    note: the tustin model is passive here, but the exact sampled-data loop (ZOH, m = 0.015) is unstable (certified)
    note: the tustin model is passive for every K > 0, but the exact sampled-data loop (ZOH, m = 0.015) is unstable
      above K* = 42.0065 (certified to 4.2e-09)
    """
    from hapticproof.analysis.sampled import decide_stability
    from hapticproof.analysis.stability import SceneLoops

    if scene.system != "single-user":
        return []
    mass = scene.role("mass")
    values = scene.resolved_values()
    if values.get(mass) is None or not values[mass].is_Rational:
        return []
    model = f"{scene.approximation or 'forward'} model"
    loop = f"the exact sampled-data loop (ZOH, {mass} = {_decimal(values[mass])})"
    notes = []
    verdict = getattr(decision, "value", decision)
    if verdict == "proved":
        try:
            decided = decide_stability(SceneLoops(scene).scene())
        except (SceneError, ValueError, ArithmeticError):
            decided = None
        if decided is not None and decided.stable is False:
            how = "unstable" if decided.verdict == "unstable" else "not asymptotically stable (rho = 1 exactly)"
            notes.append(f"note: the {model} is passive here, but {loop} is {how} (certified)")
    for rng in ranges:
        name = rng.parameter
        if not rng.intervals:
            continue
        try:
            from hapticproof.analysis.maps import find_boundary

            bnd = find_boundary(SceneLoops(scene.with_params({name: None})), name)
        except (SceneError, ValueError, ArithmeticError):
            continue
        if bnd.value is None or not bnd.certified or bnd.direction != "destabilising":
            continue
        top = rng.intervals[-1][2]
        if top is not None and float(top.approx(17)) <= bnd.value + bnd.tolerance:
            continue
        low, low_closed = rng.intervals[-1][0], rng.intervals[-1][1]
        if top is not None:
            reach = f"up to {name} = {top.text()}"
        elif low is not None:
            reach = f"for every {name} {'>=' if low_closed else '>'} {low.text()}"
        else:
            reach = f"for every {name}"
        notes.append(f"note: the {model} is passive {reach}, but {loop} is unstable above {name}* = "
                     f"{bnd.value:.6g} (certified to {bnd.tolerance:.2g})")
    return notes
