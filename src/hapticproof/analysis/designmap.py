r"""Exact design-space maps: passivity and stability over a grid of two parameters.

Every point of a map is an exact verdict (``1`` passive/stable, ``0`` not, ``-1`` undecided),
yet a whole line of the grid costs one or a few exact computations, because of structure the
models have (HVE paper, eqs. 21-27; Gil et al. 2004):

* **passivity along b or z_a** -- ``Re G^{-1} = (b - z_a) + Re(z^{-n} H X_h/V_h)``: the
  Hermitian condition holds iff ``b - z_a >= beta`` with ``beta = -min_w Re(z^{-n} H X/V)``, one
  certified minimum per line (:func:`hapticproof.analysis.fastpath.critical_damping`); the pole and
  residue conditions do not depend on ``b``. Points inside ``beta``'s enclosure (none, in
  practice) are decided one by one.
* **passivity along K, B or T** (virtual wall) -- ``G^{-1}`` is affine in each of them, so the
  set where ``Re G^{-1} >= 0`` for all ``w`` is an interval of the line (an intersection of
  half-lines), and the poles (``0`` and ``1``, ``Res = KT > 0``) do not move: exact decisions
  at both ends and a binary search of the line's sorted values classify every point with
  ``O(log m)`` decisions.
* **m users** (``users``, with ground ``K0``, ``B0`` and couplings ``K``, ``B`` between every
  pair, HVE Section 3.2) -- the uniform complete-graph HVE decouples into the walls
  ``K0 + lambda K``, ``B0 + lambda B`` with ``lambda`` in ``{0, m}``
  (:func:`hapticproof.analysis.multiuser.uniform_modes`): passive iff both are, and the line tricks apply
  to each (an intersection of intervals is an interval).
* **stability along K** -- the loop's characteristic polynomial is affine in ``beta = KT^2/m``;
  the stiffnesses where a root crosses the unit circle are isolated with certified balls and
  stability in each gap between them is certified once (:mod:`hapticproof.analysis.boundary`), which
  classifies the whole line; a point inside a crossing's ball gets its own certified spectral
  radius.

Any other line (a delay, a mass) is decided point by point. Lines are grouped into chunks; one
chunk function (:func:`map_chunk`) runs serially, in local processes or on Dask
(:mod:`hapticproof.analysis.scaleout`), and the map streams to CSV or Parquet in grid order, identical in
every mode.

>>> spec = MapSpec.build("passivity", "b=0.001:0.003:3", "K=1:3:3", {"T": "0.001", "B": 0})
>>> compute(spec).values.tolist()          # b >= KT/2 (n = 0, B = 0); K in rows
[[1, 1, 1], [1, 1, 1], [0, 1, 1]]
"""

from __future__ import annotations

import csv
import io
import time
from collections.abc import Callable, Iterator, Mapping
from dataclasses import dataclass, field
from fractions import Fraction
from pathlib import Path
from typing import Any

import numpy as np

from hapticproof.core.errors import InputFormatError
from hapticproof.core.limits import check

__all__ = ["QUANTITIES", "PARAMETERS", "Axis", "MapSpec", "MapResult", "map_chunk", "compute", "stream",
           "line_values", "write_map", "plot_map"]

QUANTITIES = ("passivity", "stability")
#: Parameter names per quantity (passivity: HVE discrete model; stability: the sampled loop of
#: the device with mass m on the delayed virtual wall).
PARAMETERS = {"passivity": ("K", "B", "b", "T", "z_a", "delay", "users", "K0", "B0"),
              "stability": ("m", "b", "T", "K", "B", "delay")}
DEFAULTS = {"passivity": {"B": 0, "z_a": 0, "delay": 0}, "stability": {"B": 0, "delay": 0}}
#: Parameters that only the m-user model has (with ``users``: K, B couple every pair of users).
MULTI_USER = ("users", "K0", "B0")
#: Line axes in order of preference (the cheapest structure first).
LINE_AXES = {"passivity": ("b", "z_a", "K", "B", "T", "K0", "B0"), "stability": ("K",)}


def _exact(text: Any, name: str) -> Fraction:
    from hapticproof.core.limits import check_number_text

    try:
        if isinstance(text, (int, Fraction)):
            return Fraction(text)
        value = str(text).strip()
        if not value.isascii():    # digits 0-9 only
            raise ValueError(value)
        for part in value.split("/"):
            check_number_text(part, name)
        return Fraction(value)
    except (ValueError, ZeroDivisionError):
        raise InputFormatError(f"{name}: {text!r} is not a number") from None


@dataclass(frozen=True, slots=True)
class Axis:
    """A grid axis: a parameter name and exact values (decimals read exactly).

    >>> Axis.parse("T=0.001:0.002:3").values
    (Fraction(1, 1000), Fraction(3, 2000), Fraction(1, 500))
    """

    name: str
    values: tuple[Fraction, ...]

    @classmethod
    def parse(cls, text: str) -> Axis:
        """``NAME=start:stop:count`` (inclusive, evenly spaced) or ``NAME=v1,v2,...``."""
        name, sep, spec = text.partition("=")
        name = name.strip()
        if not sep or not name or not spec.strip():
            raise InputFormatError(f"expected NAME=start:stop:count or NAME=v1,v2,..., got {text!r}")
        if ":" in spec:
            parts = spec.split(":")
            if len(parts) != 3:
                raise InputFormatError(f"expected NAME=start:stop:count, got {text!r}")
            start, stop = _exact(parts[0], name), _exact(parts[1], name)
            count_text = parts[2].strip()
            if not (count_text.isascii() and count_text.isdigit()):
                raise InputFormatError(f"{text!r}: the count must be an integer")
            if len(count_text) > 30:
                count_text = "9" * 31
            count = int(count_text)
            if count < 1:
                raise InputFormatError(f"{text!r}: the count must be at least 1")
            check("grid", count, name)          # before the values are built
            values = (start,) if count == 1 else tuple(start + (stop - start) * k / (count - 1) for k in range(count))
        else:
            values = tuple(_exact(v, name) for v in spec.split(","))
        return cls(name, values)


@dataclass(frozen=True)
class MapSpec:
    """What to map: ``quantity`` over ``x`` (columns) and ``y`` (rows) with ``fixed`` parameters.

    Build with :meth:`build`, which validates names and values (a user mistake is a
    :class:`~hapticproof.core.errors.InputFormatError` with one clear line).
    """

    quantity: str
    x: Axis
    y: Axis
    fixed: tuple[tuple[str, Fraction], ...]
    approximation: str = "forward"

    @classmethod
    def build(cls, quantity: str, x: str | Axis, y: str | Axis, fixed: Mapping[str, Any] | None = None,
              approximation: str = "forward") -> MapSpec:
        """Validated spec: axes ``NAME=start:stop:count``, fixed parameters by name.

        >>> spec = MapSpec.build("passivity", "b=0.001:0.01:10", "K=1:2:3", {"T": "0.001"})
        >>> spec.points, spec.line_axis, dict(spec.fixed)["B"]
        (30, 'x', Fraction(0, 1))
        """
        if quantity not in QUANTITIES:
            raise InputFormatError(f"unknown map {quantity!r}; choose one of {', '.join(QUANTITIES)}")
        x = Axis.parse(x) if isinstance(x, str) else x
        y = Axis.parse(y) if isinstance(y, str) else y
        check("grid", len(x.values) * len(y.values), f"the {quantity} map ({x.name} x {y.name})")
        names = PARAMETERS[quantity]
        if x.name == y.name:
            raise InputFormatError(f"both axes vary {x.name}")
        values = {k: Fraction(v) for k, v in DEFAULTS[quantity].items()}
        for name, value in (fixed or {}).items():
            values[name] = _exact(value, name)
        for axis in (x, y):
            values.pop(axis.name, None)
        for name in list(values) + [x.name, y.name]:
            if name not in names:
                raise InputFormatError(f"unknown parameter {name!r} for a {quantity} map (known: {', '.join(names)})")
        given = set(values) | {x.name, y.name}
        if quantity == "passivity":
            if given & {"K0", "B0"} and "users" not in given:
                raise InputFormatError("K0 and B0 (ground coupling) need users (the m-user HVE)")
            if "users" in given:
                values.setdefault("K0", Fraction(0))
                values.setdefault("B0", Fraction(0))
            else:
                names = tuple(n for n in names if n not in MULTI_USER)
        missing = [n for n in names if n not in values and n not in (x.name, y.name)]
        if missing:
            raise InputFormatError(f"a {quantity} map needs --param {', '.join(f'{m}=...' for m in missing)}")
        spec = cls(quantity, x, y, tuple(sorted(values.items())), approximation)
        spec._validate()
        return spec

    def _validate(self) -> None:
        for axis in (self.x, self.y):
            for v in axis.values:
                self._check(axis.name, v)
        for name, v in self.fixed:
            self._check(name, v)
        if self.approximation not in ("forward", "backward", "tustin"):
            raise InputFormatError(f"unknown approximation {self.approximation!r}")
        if self.quantity == "stability" and self.approximation != "forward":
            raise InputFormatError("stability maps model the forward-difference virtual wall only")

    @staticmethod
    def _check(name: str, v: Fraction) -> None:
        if name == "delay" and (v.denominator != 1 or v < 0):
            raise InputFormatError(f"delay must be a non-negative integer, got {v}")
        if name == "users" and (v.denominator != 1 or v < 1):
            raise InputFormatError(f"users must be a positive integer, got {v}")
        if name in ("delay", "users"):
            check(name, int(v), name)
        if name in ("T", "m", "K") and v <= 0:
            raise InputFormatError(f"{name} must be positive, got {v}")
        if name in ("b", "B", "z_a") and v < 0:
            raise InputFormatError(f"{name} must be non-negative, got {v}")

    @property
    def line_axis(self) -> str:
        """``'x'`` or ``'y'``: the axis a line varies (the one with the cheapest structure)."""
        for name in LINE_AXES[self.quantity]:
            if self.x.name == name:
                return "x"
            if self.y.name == name:
                return "y"
        return "x"

    @property
    def lines(self) -> int:
        return len(self.y.values) if self.line_axis == "x" else len(self.x.values)

    def line(self, index: int) -> tuple[str, tuple[Fraction, ...], dict[str, Fraction]]:
        """``(varied name, its values, the other parameters)`` of line ``index``."""
        along, across = (self.x, self.y) if self.line_axis == "x" else (self.y, self.x)
        params = dict(self.fixed)
        params[across.name] = across.values[index]
        return along.name, along.values, params

    @property
    def points(self) -> int:
        return len(self.x.values) * len(self.y.values)


# ---------------------------------------------------------------------------------------------
# passivity lines
# ---------------------------------------------------------------------------------------------


def _wall(params: Mapping[str, Fraction], approximation: str, **override: Any):
    from hapticproof.analysis.fastpath import NumericScene

    p = dict(params, **override)
    return NumericScene.virtual_wall(K=p["K"], B=p["B"], b=p.get("b", 1), T=p["T"], approximation=approximation,
                                     delay=int(p["delay"]), z_a=p.get("z_a", 0))


def _modes(params: Mapping[str, Fraction], approximation: str, **override: Any) -> list:
    """The single-user walls whose passivity is the scene's: the wall itself, or for ``users = m``
    the uniform complete-graph m-user HVE's decoupled modes ``K0 + lambda K``, ``B0 + lambda B``
    with ``lambda`` in ``{0, m}`` (:func:`hapticproof.analysis.multiuser.uniform_modes`)."""
    p = dict(params, **override)
    if "users" not in p:
        return [_wall(p, approximation)]
    m = int(p["users"])
    return [_wall(dict(p, K=p["K0"] + lam * p["K"], B=p["B0"] + lam * p["B"]), approximation)
            for lam in ((0, m) if m > 1 else (0,))]


def _passive(scenes) -> int:
    from hapticproof.core.evidence import Decision
    from hapticproof.analysis.fastpath import decide

    verdicts = []
    for scene in scenes if isinstance(scenes, list) else [scenes]:
        d = decide(scene, minimum=False).decision
        verdicts.append(1 if d == Decision.PROVED else 0 if d == Decision.DISPROVED else -1)
    return 0 if 0 in verdicts else -1 if -1 in verdicts else 1


def _passivity_damping_line(name: str, values: tuple[Fraction, ...], params: dict, approximation: str) -> np.ndarray:
    """``b`` or ``z_a`` varies: one certified ``beta`` for the whole line."""
    from hapticproof.core.evidence import Decision
    from hapticproof.analysis.fastpath import critical_damping, hermitian_outcome, transfer
    from hapticproof.exact.conditions import pole_conditions

    bases = _modes(params, approximation, **{name: values[0]})
    poles_ok = all(c.decision == Decision.PROVED for base in bases for c in pole_conditions(*transfer(base)))
    out = np.zeros(len(values), dtype=np.int8)
    if not poles_ok:
        return out
    bounds = [critical_damping(base) for base in bases]      # passive iff b - z_a >= every beta
    lo, hi = max(b[0] for b in bounds), max(b[1] for b in bounds)
    # a = b - z_a is monotone along the line: passive iff a >= beta, beta in [lo, hi]
    if name == "b":
        passive_from, failing_below = hi + params.get("z_a", 0), lo + params.get("z_a", 0)
    else:
        passive_from, failing_below = None, None
    for i, v in enumerate(values):
        if name == "b":
            if v >= passive_from:
                out[i] = 1
                continue
            if v < failing_below:
                continue
        else:
            a = params["b"] - v
            if a >= hi:
                out[i] = 1
                continue
            if a < lo:
                continue
        # inside the certified enclosure of beta: decide this point exactly
        ds = [hermitian_outcome(w, minimum=False).decision for w in _modes(params, approximation, **{name: v})]
        out[i] = 0 if Decision.DISPROVED in ds else 1 if all(d == Decision.PROVED for d in ds) else -1
    return out


def _convex_line(values: tuple[Fraction, ...], verdict: Callable[[int], int]) -> np.ndarray:
    """Classify a line whose passive points form one contiguous block (an interval of an
    affine parameter, values sorted): exact verdicts at the ends and a binary search for the
    block's edge; every point between two proved ones is passive, every point beyond a
    disproved one (away from the block) is not. Falls back to every point when neither end is
    passive or a verdict is undecided."""
    m = len(values)
    out = np.full(m, -2, dtype=np.int8)
    order = sorted(range(m), key=lambda i: values[i])

    def at(k: int) -> int:
        i = order[k]
        if out[i] == -2:
            out[i] = verdict(i)
        return int(out[i])

    first, last = at(0), at(m - 1)
    if -1 in (first, last) or (first == 0 and last == 0):
        for k in range(m):
            at(k)
        return out
    if first == 1 and last == 1:
        out[out == -2] = 1
        return out
    # one end passive: the block is a prefix (or suffix); binary search its edge
    good, bad = (0, m - 1) if first == 1 else (m - 1, 0)
    while abs(bad - good) > 1:
        mid = (good + bad) // 2
        v = at(mid)
        if v == -1:
            for k in range(m):
                at(k)
            return out
        if v == 1:
            good = mid
        else:
            bad = mid
    for k in range(m):                  # good and bad are adjacent in sorted order
        i = order[k]
        if out[i] == -2:
            out[i] = 1 if (k <= good if good < bad else k >= good) else 0
    return out


def _passivity_line(name: str, values: tuple[Fraction, ...], params: dict, approximation: str) -> np.ndarray:
    if name in ("b", "z_a"):
        return _passivity_damping_line(name, values, params, approximation)
    if name in ("K", "B", "T", "K0", "B0"):
        return _convex_line(values, lambda i: _passive(_modes(params, approximation, **{name: values[i]})))
    return np.array([_passive(_modes(params, approximation, **{name: v})) for v in values], dtype=np.int8)


# ---------------------------------------------------------------------------------------------
# stability lines
# ---------------------------------------------------------------------------------------------


def _stability_point(params: Mapping[str, Fraction]) -> int:
    from hapticproof.analysis.boundary import certified_stable
    from hapticproof.core.evidence import Decision

    try:
        d = certified_stable(m=params["m"], b=params["b"], T=params["T"], K=params["K"], B=params["B"],
                             n=int(params["delay"])).decision
    except ArithmeticError:
        return -1
    return 1 if d == Decision.PROVED else 0 if d == Decision.DISPROVED else -1


def _stability_gaps(params: Mapping[str, Fraction], bits: int) -> tuple[list, list[bool]]:
    """The certified crossing stiffnesses (``beta`` balls, sorted) and the stability of each gap
    between them (from ``beta = 0+`` up): every crossing, not only the first."""
    import flint

    from hapticproof.analysis import boundary as bd

    norm = bd.Normalised.from_physical(params["m"], params["b"], params["T"], None, params["B"])
    n = int(params["delay"])
    with bd.flint_precision(bits):
        if n == 0:
            upper, lower, mode = bd.closed_form_stiffness(norm, bits)
            if mode == "unstable":
                return [], [False]
            if lower > 0:
                return [lower, upper], [False, True, False]
            return [upper], [True, False]
        A, C, _ = bd.wall_parts(norm, n)
        cross = bd.laurent_product(A, C)
        V = bd.chebyshev_sum(cross, "U")
        R = bd.chebyshev_sum(cross, "T")
        Q = bd.chebyshev_sum(bd.laurent_product(C, C), "T")
        edges = []
        for c in bd.real_roots_inside(V, bits):
            beta = -R(c) / Q(c)
            if beta > 0:
                edges.append(beta)
            elif not beta < 0:
                raise ArithmeticError("sign of a crossing stiffness not decided")
        a_m1 = sum((coef * (-1) ** k for k, coef in enumerate(A)), flint.arb(0))
        c_m1 = sum((coef * (-1) ** k for k, coef in enumerate(C)), flint.arb(0))
        flip = -a_m1 / c_m1
        if flip > 0:
            edges.append(flip)
        edges.sort(key=lambda e: float(e.mid()))
        for x, y in zip(edges, edges[1:]):
            if not x < y:
                raise ArithmeticError("crossing stiffnesses not separated")
        stable = []
        bounds = [flint.arb(0)] + edges
        for i, lo in enumerate(bounds):
            lo_q = bd.arb_interval(lo)[1]
            test = (lo_q + bd.arb_interval(bounds[i + 1])[0]) / 2 if i + 1 < len(bounds) else 2 * lo_q + 1
            verdict = bd.stable_at(norm, n, test, bits)
            if verdict is None:
                raise ArithmeticError("stability between crossings not certified")
            stable.append(verdict)
        return edges, stable


def _stability_line(name: str, values: tuple[Fraction, ...], params: dict) -> np.ndarray:
    if name != "K":
        return np.array([_stability_point(dict(params, **{name: v})) for v in values], dtype=np.int8)
    import flint

    edges = stable = None
    for bits in (160, 320, 640):
        try:
            edges, stable = _stability_gaps(params, bits)
            break
        except ArithmeticError:
            continue
    out = np.zeros(len(values), dtype=np.int8)
    scale = params["T"] ** 2 / params["m"]
    for i, K in enumerate(values):
        if edges is None:
            out[i] = _stability_point(dict(params, K=K))
            continue
        beta = flint.arb(flint.fmpq((K * scale).numerator, (K * scale).denominator))
        gap = 0
        ambiguous = False
        for e in edges:
            if beta > e:
                gap += 1
            elif not beta < e:
                ambiguous = True
                break
        out[i] = _stability_point(dict(params, K=K)) if ambiguous else int(stable[gap])
    return out


# ---------------------------------------------------------------------------------------------
# the chunk function and the runs
# ---------------------------------------------------------------------------------------------


def line_values(spec: MapSpec, index: int) -> np.ndarray:
    """Verdicts along line ``index`` (``1``, ``0``, ``-1`` undecided)."""
    name, values, params = spec.line(index)
    if spec.quantity == "passivity":
        return _passivity_line(name, values, params, spec.approximation)
    return _stability_line(name, values, params)


def map_chunk(task: tuple[MapSpec, tuple[int, ...]]) -> list[tuple[int, np.ndarray]]:
    """The one chunk function of serial, process and Dask runs: the lines of a chunk.

    >>> spec = MapSpec.build("passivity", "b=0.001:0.003:3", "K=1:3:3", {"T": "0.001"})
    >>> [(i, v.tolist()) for i, v in map_chunk((spec, (2,)))]          # K = 3: b >= 0.0015
    [(2, [0, 1, 1])]
    """
    spec, indices = task
    return [(i, line_values(spec, i)) for i in indices]


@dataclass
class MapResult:
    """A computed map: ``values[i, j]`` at ``(x.values[j], y.values[i])``."""

    spec: MapSpec
    values: np.ndarray
    seconds: float = 0.0
    chunks: int = 0
    settings: dict = field(default_factory=dict)

    @property
    def counts(self) -> dict[str, int]:
        label = "passive" if self.spec.quantity == "passivity" else "stable"
        return {label: int((self.values == 1).sum()), f"not {label}": int((self.values == 0).sum()),
                "undecided": int((self.values == -1).sum())}


def _chunks(spec: MapSpec, lines_per_chunk: int | None, workers: int) -> list[tuple[MapSpec, tuple[int, ...]]]:
    lines = spec.lines
    if lines_per_chunk is None:
        lines_per_chunk = max(1, min(64, lines // max(1, 4 * workers)))
    return [(spec, tuple(range(s, min(s + lines_per_chunk, lines)))) for s in range(0, lines, lines_per_chunk)]


def stream(spec: MapSpec, *, workers: int = 1, scheduler: str | None = None, lines_per_chunk: int | None = None,
           progress: Callable[[int, int], None] | None = None, client: Any = None) -> Iterator[tuple[int, np.ndarray]]:
    """``(line index, verdicts)`` in line order, computed by chunks in the chosen mode."""
    from hapticproof.analysis.scaleout import ordered_map

    tasks = _chunks(spec, lines_per_chunk, workers if (workers > 1 or scheduler) else 1)
    for chunk in ordered_map(map_chunk, tasks, workers=workers, scheduler=scheduler, progress=progress, client=client):
        yield from chunk


def _grid_position(spec: MapSpec, line: int, k: int) -> tuple[int, int]:
    """``(row i, column j)`` of point ``k`` of line ``line``."""
    return (line, k) if spec.line_axis == "x" else (k, line)


def compute(spec: MapSpec, *, workers: int = 1, scheduler: str | None = None, lines_per_chunk: int | None = None,
            progress: Callable[[int, int], None] | None = None, sink: Any = None, client: Any = None) -> MapResult:
    """The whole map; ``sink`` (a :class:`MapWriter`) receives each line as soon as it is in order.

    >>> spec = MapSpec.build("stability", "T=0.001:0.002:2", "K=10:50:3", {"m": "0.015", "b": "0.02"})
    >>> compute(spec).values.tolist()        # K* = 40.0 at T = 1 ms, 20.0 at T = 2 ms
    [[1, 1], [1, 0], [0, 0]]
    """
    start = time.perf_counter()
    values = np.zeros((len(spec.y.values), len(spec.x.values)), dtype=np.int8)
    count = 0
    for line, verdicts in stream(spec, workers=workers, scheduler=scheduler, lines_per_chunk=lines_per_chunk,
                                 progress=progress, client=client):
        for k, v in enumerate(verdicts):
            values[_grid_position(spec, line, k)] = v
        if sink is not None:
            sink.write(spec, line, verdicts)
        count += 1
    mode = "dask" if (scheduler or client) else "processes" if workers > 1 else "serial"
    return MapResult(spec, values, time.perf_counter() - start, len(_chunks(spec, lines_per_chunk, max(workers, 1))),
                     {"mode": mode, "workers": workers, "scheduler": scheduler})


# ---------------------------------------------------------------------------------------------
# output
# ---------------------------------------------------------------------------------------------


def _label(spec: MapSpec) -> str:
    return "passive" if spec.quantity == "passivity" else "stable"


def _line_rows(spec: MapSpec, line: int, verdicts: np.ndarray) -> Iterator[tuple[str, str, int]]:
    name, values, params = spec.line(line)
    across = spec.y if spec.line_axis == "x" else spec.x
    for v, verdict in zip(values, verdicts):
        x, y = (v, params[across.name]) if spec.line_axis == "x" else (params[across.name], v)
        yield _number(x), _number(y), int(verdict)


def _number(value: Fraction) -> str:
    """A grid value as written: integers and decimals as such; a value that is no short decimal
    (``8/3`` from ``K=0.5:20:10``) as the nearest double (the verdict is the exact value's)."""
    if value.denominator == 1:
        return str(value.numerator)
    return repr(float(value))


class MapWriter:
    """Streams lines to CSV (``.csv``) or Parquet (``.parquet``, needs pyarrow) in line order,
    into a temporary file beside the target: :meth:`close` renames it over the target when the
    map is complete (``ok``), and removes it otherwise (an error, Ctrl-C), so that the target is
    never a partial or torn map, and two maps writing the same file each leave a whole one."""

    def __init__(self, path: str | Path, spec: MapSpec):
        from hapticproof.core.files import AtomicOutput

        self.path = Path(path)
        self.header = [spec.x.name, spec.y.name, _label(spec)]
        self.parquet = self.path.suffix.lower() in (".parquet", ".pq")
        if self.parquet:
            try:
                import pyarrow as pa
                import pyarrow.parquet as pq
            except ImportError:
                raise InputFormatError("Parquet output needs pyarrow: pip install 'hapticproof[parquet]'") from None
            self._pa = pa
            self.schema = pa.schema([(spec.x.name, pa.string()), (spec.y.name, pa.string()), (self.header[2], pa.int8())])
        self._out = AtomicOutput(self.path, "--output", binary=self.parquet).__enter__()
        if self.parquet:
            self._writer = pq.ParquetWriter(self._out.stream, self.schema)
        else:
            self._csv = csv.writer(self._out.stream, lineterminator="\n")
            self._csv.writerow(self.header)

    def write(self, spec: MapSpec, line: int, verdicts: np.ndarray) -> None:
        rows = list(_line_rows(spec, line, verdicts))
        if self.parquet:
            cols = list(zip(*rows))
            table = self._pa.table([self._pa.array(cols[0]), self._pa.array(cols[1]),
                                    self._pa.array(cols[2], type=self._pa.int8())], schema=self.schema)
            self._writer.write_table(table)
        else:
            self._csv.writerows(rows)

    def close(self, ok: bool = True) -> None:
        """Finish the file: renamed over the target when ``ok``, else removed (the target is left as it was)."""
        if self._out.done:
            return
        try:
            if self.parquet and ok:
                self._writer.close()
        finally:
            if ok:
                self._out.commit()
            else:
                self._out.__exit__(None, None, None)


def write_map(result: MapResult, path: str | Path | None = None) -> str:
    """The map as CSV text in line order (also written to ``path``).

    >>> spec = MapSpec.build("passivity", "b=0.001,0.002", "K=3", {"T": "0.001"})
    >>> print(write_map(compute(spec)), end="")
    b,K,passive
    0.001,3,0
    0.002,3,1
    """
    buf = io.StringIO()
    writer = csv.writer(buf, lineterminator="\n")
    spec = result.spec
    writer.writerow([spec.x.name, spec.y.name, _label(spec)])
    for line in range(spec.lines):
        along = [result.values[_grid_position(spec, line, k)] for k in range(len(spec.line(line)[1]))]
        writer.writerows(_line_rows(spec, line, np.array(along)))
    text = buf.getvalue()
    if path is not None:
        from hapticproof.core.files import write_atomic

        write_atomic(path, text)
    return text


def plot_map(result: MapResult, path: str | Path, title: str = "") -> Path:
    """Two-colour image of the map (dark: not passive / unstable; red: undecided)."""
    from matplotlib.backends.backend_agg import FigureCanvasAgg
    from matplotlib.colors import ListedColormap
    from matplotlib.figure import Figure

    spec = result.spec
    fig = Figure(figsize=(6.4, 4.4))
    FigureCanvasAgg(fig)
    ax = fig.add_subplot(111)
    xs = np.array([float(v) for v in spec.x.values])
    ys = np.array([float(v) for v in spec.y.values])
    image = np.where(result.values == 1, 0, np.where(result.values == 0, 1, 2)).astype(float)
    ax.pcolormesh(xs, ys, image, cmap=ListedColormap(["#f4f4f4", "#444444", "#d62728"]), vmin=0, vmax=2,
                  shading="nearest")
    ax.set_xlabel(spec.x.name)
    ax.set_ylabel(spec.y.name)
    fixed = ", ".join(f"{k} = {_number(v)}" for k, v in spec.fixed)
    ax.set_title(title or f"exact {spec.quantity} map ({fixed}); light: {_label(spec)}", fontsize=9)
    from hapticproof.core.files import atomic_path

    path = Path(path)
    with atomic_path(path, "--plot") as temp:     # whole or not at all, no folder created
        fig.savefig(temp, dpi=110, bbox_inches="tight", format=path.suffix.lstrip(".").lower() or "png")
    return path
