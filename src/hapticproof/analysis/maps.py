"""Stability boundaries and parameter-plane maps of sampled-data scenes.

A :class:`SceneFamily` is a scene with some parameters fixed and the rest left free; a
**boundary** varies one free parameter (``K``) until the loop changes stability
(:func:`find_boundary`); a **curve** repeats that over a grid of another (``T``,
:func:`boundary_curve`); a **plane map** evaluates the spectral radius (or the passivity
observer) on a grid of two (:func:`stability_map`, :func:`passivity_map`).

Boundary search. The varied parameter is scanned on a geometric grid over a search interval
(found automatically by doubling from 1 until the loop is unstable, then ``[u 1e-6, 4 u]``),
with batched eigenvalues; every sign change of ``rho - 1`` is a crossing, refined by Brent's
method on the continuous function ``rho(p) - 1`` and then *certified*: the loop is evaluated
at ``p -/+ tol`` and ``tol`` is widened until the two sides differ as claimed. The reported
``tolerance`` is that certified half-width. The boundary is the first crossing (the smallest
value where stability changes -- for ``K`` with a free device, the first ``K > 0`` where the
loop loses stability, as ``K = 0`` carries the device's integrator at ``z = 1``); all crossings
found are listed, so a stable window beyond the first loss of stability is reported, not hidden.
Windows narrower than the scan spacing can be missed (the scan has ``scan`` points).

Large curves and maps are split over a process pool (``workers``); the output does not depend
on the number of workers.

>>> fam = SceneFamily("single-user", {"m": 0.015, "b": 0.02, "B": 0, "T": 0.001})
>>> bnd = find_boundary(fam, "K", rtol=1e-10)
>>> round(bnd.value, 6), bnd.direction, len(bnd.crossings), bnd.tolerance < 1e-8
(40.008891, 'destabilising', 1, True)
"""

from __future__ import annotations

import concurrent.futures
import csv
import io
import json
import math
import os
from collections.abc import Callable, Iterable, Mapping, Sequence
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any, Literal

import numpy as np
import scipy.optimize

from hapticproof.core.errors import SceneError
from hapticproof.systems.impedance import CLAMPED, Impedance, IDENTIFIER, to_fraction
from hapticproof.systems.loops import MultiUser, Scene, SingleUser, Teleoperator
from hapticproof.analysis.sampled import DECIDE_BITS, TRUSTED_MARGIN, certified_stability, loop_json, spectral_radii, spectral_radius, trusted_radii, trusted_radius

__all__ = [
    "SceneFamily",
    "Crossing",
    "Boundary",
    "BoundaryCurve",
    "PlaneMap",
    "find_boundary",
    "boundary_curve",
    "stability_map",
    "passivity_map",
    "plot_curves",
    "plot_map",
    "grid",
    "refine_boundary_mp",
]

SYSTEMS = ("single-user", "multi-user", "teleoperator")
_NAMES = {
    "single-user": ("m", "b", "T", "K", "B"),
    "multi-user": ("m", "b", "T", "K", "B"),
    "teleoperator": ("m", "b", "m_m", "m_s", "b_m", "b_s", "T", "K", "B", "alpha"),
}
Method = Literal["spectral", "doubling", "steps"]
Progress = Callable[[int, int], None]


def grid(text: str) -> tuple[str, np.ndarray]:
    """Parse ``NAME=start:stop:count`` (inclusive, evenly spaced) into a name and values.

    >>> grid("T=0.001:0.02:20")[1][[0, -1]].tolist()
    [0.001, 0.02]
    """
    from hapticproof.core.errors import InputFormatError

    name, sep, spec = text.partition("=")
    parts = spec.split(":")
    if not sep or not name.strip() or len(parts) != 3:
        raise InputFormatError(f"expected NAME=start:stop:count, got {text!r}")
    try:
        start, stop, count = float(parts[0]), float(parts[1]), int(parts[2])
    except ValueError as err:
        raise InputFormatError(f"expected NAME=start:stop:count with numbers, got {text!r}") from err
    if count < 1 or not (math.isfinite(start) and math.isfinite(stop)):
        raise InputFormatError(f"{text!r}: count must be >= 1 and bounds finite")
    return name.strip(), np.linspace(start, stop, count)


def with_paper_names(v: dict[str, float], *, delay: int, users: int, system: str) -> dict[str, float]:
    """Complete a scene's values with the names the papers' printed conditions use: ``t_d = n T``,
    ``n``, ``users``, ``b`` of a teleoperator (the smaller robot damping) and ``B`` (0 if absent)."""
    if "T" in v:
        v["t_d"] = delay * v["T"]
    v["n"] = float(delay)
    v["users"] = float(users)
    if system == "teleoperator":
        v.setdefault("b", min(v.get("b_m", math.inf), v.get("b_s", math.inf)))
    v.setdefault("B", 0.0)
    return v


# --------------------------------------------------------------------------------------------
# families
# --------------------------------------------------------------------------------------------
@dataclass(frozen=True, slots=True)
class SceneFamily:
    """A scene with some parameters fixed: builds scenes for given values of the others.

    Parameters
    ----------
    system : {"single-user", "multi-user", "teleoperator"}
    params : mapping or tuple of pairs
        Fixed parameters. Single and multi user: ``m, b, T, K, B``; teleoperator: ``m, b``
        (both robots) or ``m_m, m_s, b_m, b_s``, and ``T, K, B, alpha``. Names used in the
        termination expressions (e.g. ``z_a``) are allowed too.
    operator : str, optional
        Operator impedance ``Z_h(s)`` as an expression in ``s`` (teleoperator: the master's
        termination; ``"clamped"`` allowed there). ``None``: free device.
    environment : str, optional
        Teleoperator only: the slave's termination (expression or ``"clamped"``).
    delay : int
        Delay in samples (teleoperator: communication delay).
    users : int
        Number of users (multi-user; uniform couplings ``K/2``, see
        :meth:`MultiUser.uniform`).

    Examples
    --------
    >>> fam = SceneFamily("single-user", {"m": 0.015, "b": 0.02, "B": 0, "z_a": 0.01},
    ...                   operator="-z_a + 1/s")
    >>> fam.scene(K=10, T=0.001).operator.num
    (Fraction(-5764607523034235, 576460752303423488), Fraction(1, 1))
    >>> fam.printed_values(T=0.001)["z_a"]
    0.01
    """

    system: str
    params: Any = ()
    operator: str | None = None
    environment: str | None = None
    delay: int = 0
    users: int = 2

    def __post_init__(self) -> None:
        if self.system not in SYSTEMS:
            raise SceneError(f"unknown system {self.system!r}; choose one of {', '.join(SYSTEMS)}")
        items = self.params.items() if isinstance(self.params, Mapping) else self.params
        params = tuple(sorted((str(k), v) for k, v in items))
        object.__setattr__(self, "params", params)
        for name, value in params:
            to_fraction(value, name)
        if self.environment is not None and self.system != "teleoperator":
            raise SceneError("an environment termination applies to the teleoperator only")
        if isinstance(self.delay, bool) or not isinstance(self.delay, int) or self.delay < 0:
            raise SceneError(f"delay must be an integer number of samples >= 0, got {self.delay!r}")
        if isinstance(self.users, bool) or not isinstance(self.users, int) or self.users < 1:
            raise SceneError(f"users must be a positive integer, got {self.users!r}")
        self._check_expressions()
        self._check_names([k for k, _ in params])

    def _check_expressions(self) -> None:
        from hapticproof.core.errors import InputFormatError
        from hapticproof.systems.impedance import ALLOWED_EXPRESSION

        for text in (self.operator, self.environment):
            if text is not None and not ALLOWED_EXPRESSION.match(text):
                raise InputFormatError(
                    f"impedance {text!r}: only numbers, s, parameter names, + - * / ^ and () allowed"
                )

    def _expression_names(self) -> set[str]:
        names: set[str] = set()
        for text in (self.operator, self.environment):
            if text is not None and text.strip().lower() not in ("clamped", "free"):
                names |= set(IDENTIFIER.findall(text)) - {"s"}
        return names

    def _check_names(self, names: Iterable[str]) -> None:
        allowed = set(_NAMES[self.system]) | self._expression_names()
        for name in names:
            if name not in allowed:
                raise SceneError(
                    f"unknown parameter {name!r} for {self.system} "
                    f"(known: {', '.join(sorted(allowed))})"
                )

    def values(self, **overrides: Any) -> dict[str, Any]:
        """Fixed parameters updated with ``overrides``."""
        self._check_names(overrides)
        out = dict(self.params)
        out.update(overrides)
        return out

    def with_params(self, **values: Any) -> SceneFamily:
        """A family with more parameters fixed."""
        return SceneFamily(
            self.system, self.values(**values), self.operator, self.environment, self.delay, self.users
        )

    def _termination(self, text: str | None, values: Mapping[str, Any]):
        if text is None or text.strip().lower() == "free":
            return None
        if text.strip().lower() == "clamped":
            if self.system != "teleoperator":
                raise SceneError("a clamped termination applies to the teleoperator only")
            return CLAMPED
        names = self._expression_names()
        missing = sorted(n for n in names if n not in values)
        if missing:
            raise SceneError(f"impedance {text!r} needs --param {', '.join(missing)}")
        return Impedance.from_expression(text, {n: values[n] for n in names})

    def scene(self, **overrides: Any) -> Scene:
        """The scene at the fixed parameters plus ``overrides``."""
        v = self.values(**overrides)

        def need(*names: str) -> list[Any]:
            missing = [n for n in names if n not in v]
            if missing:
                raise SceneError(f"{self.system} needs a value for {', '.join(missing)}")
            return [v[n] for n in names]

        operator = self._termination(self.operator, v)
        if self.system == "single-user":
            m, b, T, K = need("m", "b", "T", "K")
            return SingleUser(m=m, b=b, T=T, K=K, B=v.get("B", 0), delay=self.delay, operator=operator)
        if self.system == "multi-user":
            m, b, T, K = need("m", "b", "T", "K")
            return MultiUser.uniform(
                self.users, m=m, b=b, T=T, K=K, B=v.get("B", 0), delay=self.delay, operator=operator
            )
        T, K = need("T", "K")
        m_m = v.get("m_m", v.get("m"))
        m_s = v.get("m_s", v.get("m"))
        b_m = v.get("b_m", v.get("b"))
        b_s = v.get("b_s", v.get("b"))
        if None in (m_m, m_s, b_m, b_s):
            raise SceneError("teleoperator needs m and b (or m_m, m_s, b_m, b_s)")
        return Teleoperator(
            m_m=m_m, m_s=m_s, b_m=b_m, b_s=b_s, T=T, K=K, B=v.get("B", 0),
            alpha=v.get("alpha", 1), master=operator,
            slave=self._termination(self.environment, v), delay=self.delay,
        )

    def printed_values(self, **overrides: Any) -> dict[str, float]:
        """Values for a printed condition: parameters, ``z_a``, ``t_d = n T``, ``users``.

        ``z_a`` is the operator's shortage of passivity unless given as a parameter.
        """
        v = {k: float(to_fraction(x)) for k, x in self.values(**overrides).items()}
        if "z_a" not in v:
            term = self._termination(self.operator, v) if self.operator else None
            v["z_a"] = float(term.shortage_of_passivity()) if isinstance(term, Impedance) else 0.0
        return with_paper_names(v, delay=self.delay, users=self.users, system=self.system)


# --------------------------------------------------------------------------------------------
# boundaries
# --------------------------------------------------------------------------------------------
@dataclass(frozen=True, slots=True)
class Crossing:
    """Where stability changes as the parameter increases (within ``+/- tolerance``).

    ``certified``: the loop at ``value -/+ tolerance`` was decided by the certified spectral
    radius (ball arithmetic, :func:`hapticproof.analysis.sampled.certified_radius`) to be stable
    on one side and unstable on the other, as ``direction`` says."""

    value: float
    direction: str  # "destabilising" or "stabilising"
    tolerance: float
    certified: bool = True
    #: the exact loops at ``value -/+ tolerance`` (for the judge of ``hapticproof check``)
    sides: tuple = ()


@dataclass(frozen=True, slots=True)
class Boundary:
    """The stability boundary of one parameter, with its certified tolerance.

    ``value`` is the first crossing (``None`` if stability never changes at the points
    scanned), ``tolerance`` its certified absolute half-width, ``rtol`` the requested relative
    tolerance; ``crossings`` lists every change found; ``stable_at_start`` tells the
    stability at the low end of ``search``. ``note`` says what was not established: with no
    crossing found, that the scan's points (not the whole interval) were decided; a crossing
    whose two sides could not be certified.
    """

    parameter: str
    value: float | None
    direction: str | None
    tolerance: float | None
    rtol: float
    crossings: tuple[Crossing, ...]
    search: tuple[float, float]
    scan_points: int
    stable_at_start: bool
    method: str
    evaluations: int
    note: str = ""
    #: the family's loops keep a free translation (an exact eigenvalue ``z = 1`` no gain moves: a
    #: free teleoperator, m users without ground): the boundary is that of the motion relative to
    #: it, and no point is asymptotically stable (``map stability`` says 0, ``rho = 1``)
    translation: bool = False

    @property
    def multiple(self) -> bool:
        """More than one crossing found (stability regained or lost again)."""
        return len(self.crossings) > 1

    @property
    def certified(self) -> bool:
        """A crossing was found and certified on both sides (``False`` with no crossing)."""
        return bool(self.crossings) and self.crossings[0].certified

    @property
    def outcome(self) -> str:
        """``"crossing"`` (certified on both sides), ``"uncertified"`` (a crossing whose sides
        were not certified), ``"none-found"`` (every point scanned had the same stability: a
        statement about those points only) or ``"undecided"`` (a point could not be decided)."""
        if self.crossings:
            return "crossing" if self.certified else "uncertified"
        return "undecided" if self.note.startswith("not decided") else "none-found"

    def to_json(self) -> dict[str, Any]:
        return {
            "parameter": self.parameter,
            "value": self.value,
            "direction": self.direction,
            "tolerance": self.tolerance,
            "rtol": self.rtol,
            "certified": self.certified,
            "outcome": self.outcome,
            "crossings": [
                {"value": c.value, "direction": c.direction, "tolerance": c.tolerance, "certified": c.certified}
                for c in self.crossings
            ],
            "search": list(self.search),
            **({"judge": {"judge": "stability", "parameter": self.parameter, "sides": list(self.crossings[0].sides)}}
               if self.crossings and self.crossings[0].sides else {}),
            "scan_points": self.scan_points,
            "stable_at_start": None if self.outcome == "undecided" and not self.crossings else self.stable_at_start,
            "method": self.method,
            "evaluations": self.evaluations,
            "note": self.note,
            **({"translation": "the free translation (z = 1) is set aside: the boundary of the relative motion"}
               if self.translation else {}),
        }


class _Criterion:
    """``p -> signed distance to instability`` (negative: stable) for one method.

    The spectral method uses the float64 radius where it can be trusted
    (:func:`hapticproof.analysis.sampled.trusted_radius`) and the certified sign everywhere else
    (overflow, extreme scales, a radius within 1e-7 of 1: ball arithmetic on the exact loop),
    so the sign it returns is never a rounding artefact."""

    def __init__(self, family: SceneFamily, vary: str, at: Mapping[str, Any], method: Method,
                 steps: int | None):
        self.family, self.vary, self.at, self.method, self.steps = family, vary, dict(at), method, steps
        self.evaluations = 0
        self.undecided: list[float] = []

    def scene(self, value: float) -> Scene:
        return self.family.scene(**self.at, **{self.vary: float(value)})

    def certified(self, value: float) -> float:
        """The certified sign of ``rho - 1`` (:func:`hapticproof.analysis.sampled.certified_stability`)
        as ``-/+ 5e-324``; ``0.0`` when undecided (the value is recorded in ``undecided``). A loop
        with a free translation (its exact eigenvalue ``z = 1`` no gain moves: a free teleoperator,
        m users without ground) is judged by the motion apart from it, as the float radius
        (:func:`hapticproof.analysis.sampled.trusted_radius`) is: the boundary of the relative motion."""
        stable = certified_stability(self.scene(value), max_bits=DECIDE_BITS, relative=True)
        if stable is None:
            self.undecided.append(float(value))
            return 0.0
        return -5e-324 if stable else 5e-324

    def __call__(self, value: float) -> float:
        self.evaluations += 1
        if self.method == "spectral":
            rho = trusted_radius(self.scene(value), margin=0.0)
            if rho is None:
                return self.certified(value)
            if abs(rho - 1) >= TRUSTED_MARGIN:
                return rho - 1.0
            # near 1 the sign is the certified one; the float keeps its magnitude when it agrees
            sign = self.certified(value)
            return rho - 1.0 if sign != 0 and (rho - 1.0) * sign > 0 else sign
        from hapticproof.analysis.simulate import growth_rate

        steps = self.steps or (2**52 if self.method == "doubling" else 10_000)
        return growth_rate(self.scene(value), steps=steps, method=self.method)

    def many(self, values: np.ndarray) -> np.ndarray:
        if self.method == "spectral":
            self.evaluations += len(values)
            out = trusted_radii([self.scene(v) for v in values]) - 1.0
            for i in np.flatnonzero(~np.isfinite(out)):
                out[i] = self.certified(values[i])
            return out
        return np.array([self(v) for v in values])


#: The automatic search: doublings from 1 (to 2**30 and 2**-30), then factors of 100 out to
#: 1e300 and 1e-300 -- every positive float64 scale a parameter can have.
_LADDER_DOUBLINGS = 30
_LADDER_STEP = 100.0


def _auto_search(crit: _Criterion) -> tuple[tuple[float, float] | None, int, bool]:
    """A search interval around a change of stability found by a ladder of values from 1.

    Up from 1 by doublings (to 2**30), then by factors of 100 (to 1e300); else down the same
    way (to 1e-300). With the adjacent pair (s on the side of 1, u beyond) the interval spans six
    decades beyond the side of 1 and a factor 4 beyond the other, so the scan also sees
    crossings past the first. A rung the certified radius cannot decide ends that direction
    (``crit.undecided`` records it). Returns the interval (``None`` when stability is the same
    at every decided rung), the number of rungs and the stability at 1.
    """
    first = crit(1.0)
    start, rungs = first < 0, 1
    if first == 0.0:
        return None, rungs, start
    for factor in (2.0, 0.5):
        ladder = [factor ** k for k in range(1, _LADDER_DOUBLINGS + 1)]
        step = _LADDER_STEP if factor > 1 else 1 / _LADDER_STEP
        while 1e-300 <= ladder[-1] * step <= 1e300:
            ladder.append(ladder[-1] * step)
        previous, blocked = 1.0, False
        for chunk in range(0, len(ladder), 16):
            values = np.array(ladder[chunk:chunk + 16])
            signs = crit.many(values)
            rungs += len(values)
            for v, sign in zip(values, signs):
                if sign == 0.0:          # undecided: this direction ends here
                    blocked = True
                    break
                if (sign < 0) != start:
                    lo, hi = sorted((previous, float(v)))
                    if (factor > 1) == start:  # unstable above: K-like parameter
                        return (max(lo * 1e-6, 5e-324), min(hi * 4, 1.7e308)), rungs, start
                    return (lo / 4, min(hi * 1e6, 1.7e308)), rungs, start  # unstable below: b-like parameter
                previous = float(v)
            if blocked:
                break
    return None, rungs, start


def find_boundary(
    family: SceneFamily,
    vary: str,
    *,
    at: Mapping[str, Any] | None = None,
    search: tuple[float, float] | None = None,
    rtol: float = 1e-10,
    scan: int = 48,
    method: Method = "spectral",
    steps: int | None = None,
) -> Boundary:
    """Stability boundary of ``vary`` for the family at the values ``at``.

    Parameters
    ----------
    family : SceneFamily
    vary : str
        The parameter to vary (``"K"``, ``"b"``, ``"B"``, ``"T"`` ...).
    at : mapping, optional
        Values of the family's other free parameters (``{"T": 0.001}``).
    search : (float, float), optional
        Interval to search; automatic when omitted (positive parameters only: a ladder of
        values from 1 out to 1e300 and 1e-300).
    rtol : float
        Requested relative tolerance.
    scan : int
        Number of scan points (the geometric grid on which crossings are detected).
    method : {"spectral", "doubling", "steps"}
        ``"spectral"``: spectral radius of the exact closed loop (scan + Brent), float64 where
        it can be trusted, certified ball arithmetic elsewhere and on both sides of every
        crossing; ``"doubling"`` / ``"steps"``: time-domain growth
        (:func:`hapticproof.analysis.simulate.growth_rate`) with bisection on its sign (the
        Simulink-style method; ``steps`` sets the horizon).

    Without a change of stability at the points scanned, ``value`` is ``None`` and ``note``
    says so: the scan decides its points, not the stretches between them.

    Examples
    --------
    >>> fam = SceneFamily("single-user", {"m": 0.15, "b": 0.2, "B": 0}, delay=10)
    >>> bnd = find_boundary(fam, "K", at={"T": 0.002})
    >>> round(bnd.value, 4), bnd.multiple, bnd.certified
    (9.5681, False, True)
    """
    at = dict(at or {})
    crit = _Criterion(family, vary, at, method, steps)
    if search is None:
        found, rungs, stable = _auto_search(crit)
        translation = crit.scene(1.0).loop("float").rigid is not None
        if found is None:
            state = "stable" if stable else "unstable"
            note = (f"no change of stability at the {rungs} values of {vary} from 1e-300 to 1e300 scanned "
                    f"({state} at every one); a window between them is not excluded")
            if crit.undecided:
                note = (f"not decided: the spectral radius at {vary} = {crit.undecided[0]:.6g} could not be separated "
                        f"from 1 at {DECIDE_BITS} bits")
            return Boundary(vary, None, None, None, rtol, (), (1e-300, 1e300), rungs, stable, method,
                            crit.evaluations, note, translation)
        search = found
    lo, hi = float(search[0]), float(search[1])
    if not hi > lo:
        raise SceneError(f"search interval must have lo < hi, got {search}")
    if lo > 0:
        points = np.geomspace(lo, hi, scan)
    else:
        points = np.linspace(lo, hi, scan)
    signs = crit.many(points)
    translation = crit.scene(points[-1]).loop("float").rigid is not None
    unstable = signs >= 0
    crossings = []
    for i in range(len(points) - 1):
        if unstable[i] != unstable[i + 1]:
            crossings.append(_refine(crit, points[i], points[i + 1], signs[i], rtol, method))
    first = crossings[0] if crossings else None
    note = ""
    if first is None:
        note = (f"no change of stability at the {scan} scan points in [{lo:.6g}, {hi:.6g}] "
                f"({'stable' if not unstable[0] else 'unstable'} at every one); a window between them is not excluded")
    elif not first.certified:
        note = "the two sides of the crossing could not be certified (the spectral radius balls hold 1)"
    if crit.undecided and first is None:
        note = (f"not decided: the spectral radius at {vary} = {crit.undecided[0]:.6g} could not be separated "
                f"from 1 at {DECIDE_BITS} bits")
    return Boundary(
        vary,
        first.value if first else None,
        first.direction if first else None,
        first.tolerance if first else None,
        rtol,
        tuple(crossings),
        (lo, hi),
        scan,
        bool(not unstable[0]),
        method,
        crit.evaluations,
        note,
        translation,
    )


def _refine(crit: _Criterion, a: float, b: float, fa: float, rtol: float, method: Method) -> Crossing:
    direction = "destabilising" if fa < 0 else "stabilising"
    eps = 4 * np.finfo(float).eps
    if method == "spectral":
        x = scipy.optimize.brentq(crit, a, b, xtol=rtol * abs(b) / 4, rtol=max(rtol / 4, eps))
    else:  # bisection on the sign only: what a simulation tells
        left_stable = fa < 0
        while b - a > 2 * rtol * abs(b):
            mid = 0.5 * (a + b)
            if (crit(mid) < 0) == left_stable:
                a = mid
            else:
                b = mid
        return Crossing(0.5 * (a + b), direction, 0.5 * (b - a), certified=False)
    tol = max(rtol * abs(x), eps * abs(x), 5e-324)
    for _ in range(30):  # certify: the two sides must differ as claimed, by the certified radius
        if x - tol < a or x + tol > b:   # the scan's own points bracket the crossing
            tol = min(x - a, b - x)
        left, right = crit.certified(x - tol), crit.certified(x + tol)
        crit.evaluations += 2
        if left != 0 and right != 0 and (left < 0) == (fa < 0) and (right < 0) != (fa < 0):
            sides = tuple({"value": v, "stable": st, "loop": loop_json(crit.scene(v))}
                          for v, st in ((x - tol, left < 0), (x + tol, right < 0)))
            return Crossing(float(x), direction, float(tol), sides=sides)
        if tol >= min(x - a, b - x):
            break
        tol *= 4
    return Crossing(float(x), direction, float(tol), certified=False)


def refine_boundary_mp(
    family: SceneFamily,
    vary: str,
    bracket: tuple[Any, Any],
    *,
    at: Mapping[str, Any] | None = None,
    dps: int = 50,
    tol: Any = None,
    max_iter: int = 200,
):
    """The boundary inside ``bracket`` at ``dps`` digits (the high-precision reference).

    The spectral radius of the closed loop is computed with mpmath (exact discretisation at
    ``dps`` digits, :func:`mpmath.eig`); ``rho - 1`` must change sign over ``bracket`` (checked
    at that precision). The Illinois variant of regula falsi keeps a certified bracket and
    stops when it is narrower than ``tol`` (default ``10**-(dps - 10)`` relative). Returns
    ``(value, half_width)`` as mpmath numbers.

    >>> import mpmath
    >>> from hapticproof.analysis.sampled import free_device_boundary
    >>> fam = SceneFamily("single-user", {"m": 0.015, "b": 0.02, "B": 0, "T": 0.001})
    >>> k, w = refine_boundary_mp(fam, "K", (40.0, 40.02), dps=30)
    >>> bool(abs(k - free_device_boundary(0.015, 0.02, 0.001, "mp", 30)) < 1e-15)
    True
    """
    import mpmath

    at = dict(at or {})
    with mpmath.workdps(dps):
        def f(value):
            scene = family.scene(**at, **{vary: value})
            return spectral_radius(scene, precision="mp", dps=dps) - 1

        a, b = mpmath.mpf(to_fraction(bracket[0]).numerator) / to_fraction(bracket[0]).denominator, \
            mpmath.mpf(to_fraction(bracket[1]).numerator) / to_fraction(bracket[1]).denominator
        fa, fb = f(a), f(b)
        if (fa < 0) == (fb < 0):
            raise SceneError(f"no change of stability of {vary} inside {bracket}")
        tol = mpmath.mpf(10) ** (-(dps - 10)) * abs(b) if tol is None else mpmath.mpf(tol)
        side = 0
        for _ in range(max_iter):
            if b - a <= 2 * tol:
                break
            c = (a * fb - b * fa) / (fb - fa)
            if not (a < c < b):
                c = (a + b) / 2
            fc = f(c)
            if (fc < 0) == (fa < 0):
                a, fa = c, fc
                if side == -1:
                    fb /= 2  # Illinois: halve the stale end's weight
                side = -1
            else:
                b, fb = c, fc
                if side == 1:
                    fa /= 2
                side = 1
        return (a + b) / 2, (b - a) / 2


# --------------------------------------------------------------------------------------------
# curves
# --------------------------------------------------------------------------------------------
@dataclass(frozen=True, slots=True, eq=False)
class BoundaryCurve:
    """Boundaries of ``vary`` along a grid of ``over``, with the printed borderline."""

    family: SceneFamily
    vary: str
    over: str
    grid: tuple[float, ...]
    boundaries: tuple[Boundary, ...]
    printed: tuple[float | None, ...]
    printed_label: str | None = None
    label: str | None = None

    @property
    def exact(self) -> np.ndarray:
        return np.array([b.value if b.value is not None else np.nan for b in self.boundaries])

    @property
    def printed_values(self) -> np.ndarray:
        return np.array([p if p is not None else np.nan for p in self.printed])

    @property
    def ratio(self) -> np.ndarray:
        """``exact / printed``: > 1 where the printed condition is conservative (safe)."""
        with np.errstate(divide="ignore", invalid="ignore"):
            return self.exact / self.printed_values

    def rows(self) -> list[dict[str, Any]]:
        """One row per grid point: ``{over, <vary>_exact, <vary>_printed}``."""
        return [
            {self.over: x, f"{self.vary}_exact": b.value, f"{self.vary}_printed": p}
            for x, b, p in zip(self.grid, self.boundaries, self.printed)
        ]

    def to_csv(self, path: str | Path | None = None) -> str:
        """CSV with columns ``<over>, <vary>_exact, <vary>_printed`` (empty where none)."""
        header = [self.over, f"{self.vary}_exact", f"{self.vary}_printed"]
        rows = (["" if row[h] is None else repr(float(row[h])) for h in header] for row in self.rows())
        return _csv(header, rows, path)

    def to_json(self, path: str | Path | None = None) -> dict[str, Any]:
        data = {
            "system": self.family.system,
            "params": {k: str(v) for k, v in self.family.params},
            "operator": self.family.operator,
            "environment": self.family.environment,
            "delay": self.family.delay,
            "vary": self.vary,
            "over": self.over,
            "printed_condition": self.printed_label,
            "points": [
                {self.over: x, "printed": p, "boundary": b.to_json()}
                for x, b, p in zip(self.grid, self.boundaries, self.printed)
            ],
        }
        if path is not None:
            _write(path, json.dumps(data, indent=1))
        return data


def _csv(header: list[str], rows: Iterable[list[Any]], path: str | Path | None) -> str:
    """CSV text (header, then rows), also written to ``path`` when given."""
    buf = io.StringIO()
    writer = csv.writer(buf, lineterminator="\n")
    writer.writerow(header)
    writer.writerows(rows)
    text = buf.getvalue()
    if path is not None:
        _write(path, text)
    return text


def _write(path: str | Path, text: str) -> None:
    from hapticproof.core.files import write_atomic

    write_atomic(path, text)        # whole or not at all; no folder created


def _boundary_task(args: tuple) -> Boundary:
    family, vary, at, search, rtol, scan, method, steps = args
    return find_boundary(family, vary, at=at, search=search, rtol=rtol, scan=scan, method=method,
                         steps=steps)


def _workers(workers: int | None, tasks: int, threshold: int) -> int:
    if workers is None:
        workers = (os.cpu_count() or 1) if tasks >= threshold else 1
    return max(1, min(int(workers), tasks))


def _run(func: Callable[[Any], Any], tasks: list, workers: int, progress: Progress | None) -> list:
    """Run tasks in order (serially or in a process pool) reporting progress."""
    results: list[Any] = [None] * len(tasks)
    if workers <= 1:
        for i, task in enumerate(tasks):
            results[i] = func(task)
            if progress:
                progress(i + 1, len(tasks))
        return results
    from hapticproof.core.processes import die_with_parent

    with concurrent.futures.ProcessPoolExecutor(max_workers=workers, initializer=die_with_parent,
                                                initargs=(os.getpid(),)) as pool:
        futures = {pool.submit(func, task): i for i, task in enumerate(tasks)}
        for done, fut in enumerate(concurrent.futures.as_completed(futures), 1):
            results[futures[fut]] = fut.result()
            if progress:
                progress(done, len(tasks))
    return results


def boundary_curve(
    family: SceneFamily,
    vary: str,
    over: tuple[str, Sequence[float]],
    *,
    printed_borderline: Callable[[Mapping[str, Any]], float] | None = None,
    search: tuple[float, float] | None = None,
    rtol: float = 1e-10,
    scan: int = 48,
    method: Method = "spectral",
    workers: int | None = None,
    progress: Progress | None = None,
    label: str | None = None,
) -> BoundaryCurve:
    """Boundary of ``vary`` at every value of ``over`` (e.g. ``K*(T)``), in parallel if large.

    ``printed_borderline`` (e.g. from :func:`hapticproof.analysis.borderlines.printed_borderline`) maps
    :meth:`SceneFamily.printed_values` to the printed borderline of ``vary``.

    >>> from hapticproof.analysis.borderlines import printed_borderline
    >>> fam = SceneFamily("single-user", {"m": 0.015, "b": 0.02, "B": 0})
    >>> curve = boundary_curve(fam, "K", ("T", [0.001, 0.01]),
    ...                        printed_borderline=printed_borderline(fam, "K"))
    >>> np.round(curve.ratio, 5).tolist()
    [1.00022, 1.00223]
    """
    name, values = over
    values = [float(v) for v in values]
    tasks = [(family, vary, {name: v}, search, rtol, scan, method, None) for v in values]
    results = _run(_boundary_task, tasks, _workers(workers, len(tasks), 64), progress)
    printed: list[float | None] = []
    for v in values:
        if printed_borderline is None:
            printed.append(None)
        else:
            printed.append(float(printed_borderline(family.printed_values(**{name: v}))))
    cond = getattr(printed_borderline, "condition", None)
    return BoundaryCurve(
        family, vary, name, tuple(values), tuple(results), tuple(printed),
        cond.label if cond is not None else None, label,
    )


# --------------------------------------------------------------------------------------------
# plane maps
# --------------------------------------------------------------------------------------------
@dataclass(frozen=True, slots=True, eq=False)
class PlaneMap:
    """Values on a grid of two parameters: ``values[i, j]`` at ``(x_values[j], y_values[i])``.

    ``quantity`` is ``"spectral radius"`` (stable where < 1) or ``"minimum energy"`` (the
    passivity observer's least port energy; passive where >= 0).
    """

    family: SceneFamily
    x: str
    x_values: np.ndarray
    y: str
    y_values: np.ndarray
    values: np.ndarray
    quantity: str
    settings: dict = field(default_factory=dict)

    @property
    def good(self) -> np.ndarray:
        """Stable (spectral radius < 1) or passive (observer energy >= -tolerance)."""
        if self.quantity == "spectral radius":
            return self.values < 1
        return self.values >= -self.settings.get("tolerance", 0.0)

    def to_csv(self, path: str | Path | None = None) -> str:
        header = [self.x, self.y, self.quantity.replace(" ", "_"), "good"]
        rows = ([repr(float(xv)), repr(float(yv)), repr(float(self.values[i, j])), int(self.good[i, j])]
                for i, yv in enumerate(self.y_values) for j, xv in enumerate(self.x_values))
        return _csv(header, rows, path)

    def to_json(self, path: str | Path | None = None) -> dict[str, Any]:
        data = {
            "system": self.family.system,
            "params": {k: str(v) for k, v in self.family.params},
            "x": self.x, "x_values": self.x_values.tolist(),
            "y": self.y, "y_values": self.y_values.tolist(),
            "quantity": self.quantity, "values": self.values.tolist(),
            "good": self.good.astype(int).tolist(), "settings": self.settings,
        }
        if path is not None:
            _write(path, json.dumps(data))
        return data


def _spectral_chunk(args: tuple) -> np.ndarray:
    family, x, y, points = args
    return spectral_radii([family.scene(**{x: px, y: py}) for px, py in points])


def _observer_chunk(args: tuple) -> np.ndarray:
    from hapticproof.analysis.simulate import observer_minimum_energies

    family, x, y, points, steps, excitation = args
    scenes = [family.scene(**{x: px, y: py}) for px, py in points]
    return observer_minimum_energies(scenes, steps, excitation)[:, 0]


def _plane(family, x, y, chunk_func, extra, workers, progress, chunk=256):
    (xn, xv), (yn, yv) = x, y
    xv, yv = np.asarray(xv, float), np.asarray(yv, float)
    points = [(float(a), float(b)) for b in yv for a in xv]
    tasks = [
        (family, xn, yn, points[i : i + chunk], *extra) for i in range(0, len(points), chunk)
    ]
    results = _run(chunk_func, tasks, _workers(workers, len(tasks), 8), progress)
    values = np.concatenate(results).reshape(len(yv), len(xv))
    return xn, xv, yn, yv, values


def stability_map(
    family: SceneFamily,
    x: tuple[str, Sequence[float]],
    y: tuple[str, Sequence[float]],
    *,
    workers: int | None = None,
    progress: Progress | None = None,
) -> PlaneMap:
    """Spectral radius on a parameter plane (batched eigenvalues, parallel chunks).

    >>> fam = SceneFamily("single-user", {"m": 0.015, "b": 0.02, "B": 0})
    >>> mp_ = stability_map(fam, ("T", [0.001, 0.002]), ("K", [10, 30, 50]))
    >>> mp_.good.astype(int).tolist()
    [[1, 1], [1, 0], [0, 0]]
    """
    xn, xv, yn, yv, values = _plane(family, x, y, _spectral_chunk, (), workers, progress)
    return PlaneMap(family, xn, xv, yn, yv, values, "spectral radius")


def passivity_map(
    family: SceneFamily,
    x: tuple[str, Sequence[float]],
    y: tuple[str, Sequence[float]],
    *,
    steps: int,
    excitation: Any,
    rtol: float = 1e-9,
    workers: int | None = None,
    progress: Progress | None = None,
) -> PlaneMap:
    """The passivity observer's minimum port energy on a plane (teleoperator Fig. 3).

    Each point starts at rest and is driven by ``excitation`` for ``steps`` samples; the
    map holds ``min_k E(t_k)`` (negative: non-passive).
    """
    xn, xv, yn, yv, values = _plane(
        family, x, y, _observer_chunk, (steps, excitation), workers, progress, chunk=128
    )
    settings = {"steps": steps, "excitation": {"amplitudes": list(excitation.amplitudes),
                                               "frequency": float(excitation.frequency)},
                "tolerance": 0.0}
    return PlaneMap(family, xn, xv, yn, yv, values, "minimum energy", settings)


# --------------------------------------------------------------------------------------------
# plots (Agg canvas, no pyplot state)
# --------------------------------------------------------------------------------------------
def _figure(size=(6.4, 4.4)):
    from matplotlib.backends.backend_agg import FigureCanvasAgg
    from matplotlib.figure import Figure

    fig = Figure(figsize=size)
    FigureCanvasAgg(fig)
    return fig


def plot_curves(
    curves: Sequence[BoundaryCurve], path: str | Path, title: str = "", scale: Mapping[str, float] | None = None
) -> Path:
    """Exact boundaries (markers and lines) and printed borderlines (dashed) on one plot.

    ``scale`` multiplies axis values for display (``{"T": 1000}`` plots T in ms).
    """
    scale = dict(scale or {})
    fig = _figure()
    ax = fig.add_subplot(111)
    colors = ["C0", "C1", "C2", "C3", "C4", "C5"]
    for i, curve in enumerate(curves):
        color = colors[i % len(colors)]
        xs = np.array(curve.grid) * scale.get(curve.over, 1.0)
        label = curve.label or curve.family.system
        ax.plot(xs, curve.exact, "*-", color=color, label=f"{label}: exact")
        if np.any(np.isfinite(curve.printed_values)):
            ax.plot(xs, curve.printed_values, "--", color=color,
                    label=f"{label}: printed {curve.printed_label or ''}".rstrip())
    if curves:
        unit = " (ms)" if scale.get(curves[0].over) == 1000 else ""
        ax.set_xlabel(curves[0].over + unit)
        ax.set_ylabel(curves[0].vary)
    ax.set_title(title)
    ax.grid(True, alpha=0.3)
    ax.legend(fontsize=7)
    return _save(fig, path)


def _save(fig: Any, path: str | Path) -> Path:
    """Save a figure through the one output writer (whole or not at all, no link followed)."""
    from hapticproof.core.files import write_figure

    return write_figure(fig, path, "--plot")


def plot_map(
    plane: PlaneMap,
    path: str | Path,
    curves: Sequence[tuple[str, np.ndarray, np.ndarray]] = (),
    title: str = "",
    scale: Mapping[str, float] | None = None,
) -> Path:
    """The map as a two-colour image (dark: unstable / non-passive) with curves on top.

    ``curves`` are ``(label, x, y)`` triples in the map's parameter units.
    """
    from matplotlib.colors import ListedColormap

    scale = dict(scale or {})
    sx, sy = scale.get(plane.x, 1.0), scale.get(plane.y, 1.0)
    fig = _figure()
    ax = fig.add_subplot(111)
    ax.pcolormesh(plane.x_values * sx, plane.y_values * sy, (~plane.good).astype(float),
                  cmap=ListedColormap(["#f4f4f4", "#444444"]), vmin=0, vmax=1, shading="nearest")
    styles = ["r-", "b--", "g-.", "m:"]
    for i, (label, xs, ys) in enumerate(curves):
        ax.plot(np.asarray(xs) * sx, np.asarray(ys) * sy, styles[i % len(styles)], lw=2, label=label)
    ax.set_xlim(plane.x_values[0] * sx, plane.x_values[-1] * sx)
    ax.set_ylim(plane.y_values[0] * sy, plane.y_values[-1] * sy)
    ax.set_xlabel(plane.x + (" (ms)" if sx == 1000 else ""))
    ax.set_ylabel(plane.y + (" (ms)" if sy == 1000 else ""))
    ax.set_title(title)
    if curves:
        ax.legend(fontsize=7, loc="upper right")
    return _save(fig, path)
