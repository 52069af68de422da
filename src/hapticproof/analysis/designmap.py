r"""Exact design-space maps: passivity and stability over a grid of two parameters of a scene.

A map is a :class:`~hapticproof.systems.scene.Scene` -- the one scene model of ``derive`` and
``boundary``: any environment ``H(z)``, m users, teleoperators, the user's names and roles --
with two of its parameters (or the fields ``delay`` and ``users``) on a grid. Every point is an
exact verdict (``1`` passive/stable, ``0`` not, ``-1`` undecided), yet a whole line of the grid
costs one or a few exact computations where the models have structure (HVE paper, eqs. 21-27;
Gil et al. 2004):

* **passivity along the device damping or z_a** (single user, ``H`` free of it) --
  ``Re G^{-1} = a + Re(z^{-n} H X_h/V_h)`` with ``a = b - z_a`` affine in the parameter: the
  Hermitian condition holds iff ``a >= beta`` with ``beta = -min_w Re(z^{-n} H X/V)``, one
  certified minimum per line (:func:`hapticproof.analysis.fastpath.critical_damping`); the pole
  and residue conditions do not depend on ``a``. Points inside ``beta``'s enclosure (none, in
  practice) are decided one by one.
* **passivity along a parameter that enters G^{-1} affinely with fixed poles** (``K``, ``B``,
  ``T`` of the virtual wall; the couplings and dampings of m users; a teleoperator's robot
  dampings) -- the set where the conditions hold is an intersection of half-lines and of a
  convex cone's preimages, an interval of the line: exact decisions at both ends and a binary
  search of the line's sorted values classify every point with ``O(log m)`` decisions. The
  affinity is checked symbolically once per map.
* **stability along K** (the virtual wall, no operator) -- the loop's characteristic polynomial
  is affine in ``beta = KT^2/m``; the stiffnesses where a root crosses the unit circle are
  isolated with certified balls and stability in each gap between them is certified once
  (:mod:`hapticproof.analysis.boundary`), which classifies the whole line; a point inside a
  crossing's ball gets its own certified spectral radius.

Any other line is decided point by point: single-user passivity by the numeric fast path
(:func:`hapticproof.analysis.fastpath.decide`), m users and teleoperators by their exact
decisions, stability by the one decision of the exact ZOH loop
(:class:`hapticproof.analysis.stability.SceneLoops`, :func:`hapticproof.analysis.sampled.decide_stability`:
an exact eigenvalue ``z = 1`` -- no position feedback on a mode -- is ``rho = 1``, not stable). The virtual damping ``B`` (``B_0``) is 0 unless given, as in
``boundary``. Lines are grouped into chunks; one chunk function (:func:`map_chunk`) runs
serially, in local processes or on Dask (:mod:`hapticproof.analysis.scaleout`), and the map
streams to CSV or Parquet in grid order, identical in every mode.

>>> from hapticproof.systems.scene import Scene
>>> spec = MapSpec.build("passivity", "b=0.001:0.003:3", "K=1:3:3", Scene("single-user", params={"T": "0.001"}))
>>> compute(spec).values.tolist()          # b >= KT/2 (n = 0, B = 0); K in rows
[[1, 1, 1], [1, 1, 1], [0, 1, 1]]
"""

from __future__ import annotations

import csv
import functools
import io
import time
from collections.abc import Callable, Iterator, Mapping
from dataclasses import dataclass, field
from fractions import Fraction
from pathlib import Path
from typing import Any

import numpy as np
import sympy as sp

from hapticproof.core.errors import InputFormatError, SceneError
from hapticproof.core.limits import check
from hapticproof.systems.choices import QUANTITIES

__all__ = ["QUANTITIES", "FIELD_AXES", "Axis", "MapSpec", "MapResult", "map_chunk", "compute", "stream",
           "line_values", "write_map", "plot_map"]

#: Scene fields a map may vary besides the parameters.
FIELD_AXES = ("delay", "users")


def _exact(text: Any, name: str) -> Fraction:
    from hapticproof.core.expr import not_a_name
    from hapticproof.core.limits import check_number_text

    if isinstance(text, (int, Fraction)) and not isinstance(text, bool):
        return Fraction(text)
    if not_a_name(str(text).strip().lstrip("+-")):
        raise InputFormatError(f"{name}: {str(text).strip()!r} {not_a_name(str(text).strip().lstrip('+-'))}")
    try:
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


def _corners(x: Axis, y: Axis) -> list[dict[str, Fraction]]:
    xs = sorted({min(x.values), max(x.values)})
    ys = sorted({min(y.values), max(y.values)})
    return [{x.name: a, y.name: b} for a in xs for b in ys]


@dataclass(frozen=True)
class MapSpec:
    """What to map: ``quantity`` over ``x`` (columns) and ``y`` (rows) of ``scene`` (a
    :class:`~hapticproof.systems.scene.Scene` whose other parameters are numbers).

    Build with :meth:`build`, which validates names and values (a user mistake is a
    :class:`~hapticproof.core.errors.HapticproofError` with one clear line).
    """

    quantity: str
    x: Axis
    y: Axis
    scene: Any

    @classmethod
    def build(cls, quantity: str, x: str | Axis, y: str | Axis, scene: Any = None) -> MapSpec:
        """Validated spec: axes ``NAME=start:stop:count`` (a parameter of the scene, ``delay``,
        or ``users`` of m users), the scene (a mapping is the parameters of a single-user one).

        >>> from hapticproof.systems.scene import Scene
        >>> spec = MapSpec.build("passivity", "b=0.001:0.01:10", "K=1:2:3", Scene("single-user", params={"T": "0.001"}))
        >>> spec.points, spec.line_axis, spec.scene.param_values["B"]
        (30, 'x', 0)
        """
        from hapticproof.systems.scene import Scene

        if quantity not in QUANTITIES:
            raise InputFormatError(f"unknown map {quantity!r}; choose one of {', '.join(QUANTITIES)}")
        x = Axis.parse(x) if isinstance(x, str) else x
        y = Axis.parse(y) if isinstance(y, str) else y
        check("grid", len(x.values) * len(y.values), f"the {quantity} map ({x.name} x {y.name})")
        if x.name == y.name:
            raise InputFormatError(f"both axes vary {x.name}")
        if scene is None or isinstance(scene, Mapping):
            scene = Scene("single-user", params=dict(scene or {}))
        if not isinstance(scene, Scene):
            raise InputFormatError("a map takes a Scene (or the parameters of a single-user scene)")
        if scene.system == "network":
            raise InputFormatError("maps apply to single-user, multi-user and teleoperator scenes")
        axes = [a.name for a in (x, y)]
        scene.check_names()                     # a misspelt --param first
        scene = scene.with_params({name: None for name in axes if name not in FIELD_AXES})
        if "z_a" in axes and scene.system in ("single-user", "multi-user"):
            scene = scene.replace(active=True)  # the operator's shortage of passivity as a parameter
        names = scene.names()
        # the virtual damping is 0 unless given (as the papers' stability studies and boundary)
        unset = ({"B", "B_0"} & names) - set(dict(scene.params)) - set(axes)
        if unset:
            scene = scene.with_params({name: 0 for name in unset})
        groups = ({"K_0", "B_0", "K", "B", "z_a", scene.role("device_damping")} - {None}
                  if scene.system == "multi-user" else set())
        known = names | set(scene.reserved()) | groups
        for axis in (x, y):
            if axis.name in FIELD_AXES:
                if axis.name == "users" and scene.system != "multi-user":
                    raise InputFormatError("the users axis applies to multi-user scenes")
                least = 0 if axis.name == "delay" else 1
                bad = [v for v in axis.values if v.denominator != 1 or v < least]
                if bad:
                    kind = "non-negative" if axis.name == "delay" else "positive"
                    raise InputFormatError(f"{axis.name} must be a {kind} integer, got {bad[0]}")
                check(axis.name, int(max(axis.values)), axis.name)
                continue
            if axis.name not in known:
                import difflib

                close = difflib.get_close_matches(axis.name, sorted(names | set(FIELD_AXES)), n=1, cutoff=0.6)
                hint = f"; did you mean {close[0]!r}?" if close else ""
                raise InputFormatError(f"unknown parameter {axis.name!r} for a {quantity} map of this {scene.system} "
                                       f"scene (it has {', '.join(sorted(names))}; or delay"
                                       f"{', users' if scene.system == 'multi-user' else ''}){hint}")
            if quantity == "passivity" and axis.name not in names | groups:
                raise InputFormatError(f"{axis.name} ({scene.reserved().get(axis.name, 'this name')}) does not enter "
                                       "the passivity decision")
        spec = cls(quantity, x, y, scene)
        for corner in _corners(x, y):       # every value is checked where it is extreme: signs are per parameter
            spec._check_point(corner)
        return spec

    def at(self, values: Mapping[str, Fraction]) -> Any:
        """The scene with axis values set (parameters, ``delay``, ``users``)."""
        scene = self.scene
        fields = {k: int(v) for k, v in values.items() if k in FIELD_AXES}
        if fields:
            scene = scene.replace(**fields)
        params = {k: sp.Rational(v.numerator, v.denominator) for k, v in values.items() if k not in FIELD_AXES}
        return scene.with_params(params) if params else scene

    @property
    def free_translation(self) -> bool:
        """Whether the loops keep a free translation (an exact eigenvalue ``z = 1`` that no gain
        moves: a free teleoperator), judged at the grid's corners (at every one of them): then no
        point of a stability map is asymptotically stable (``rho = 1``).

        >>> from hapticproof.systems.scene import Scene
        >>> MapSpec.build("stability", "K=1:2:2", "T=0.001:0.002:2", {"m": "0.02", "b": "0.01"}).free_translation
        False
        """
        from hapticproof.analysis.stability import SceneLoops

        if self.quantity != "stability":
            return False
        return all(SceneLoops(self.at(corner)).scene().loop("exact").rigid is not None
                   for corner in _corners(self.x, self.y))

    def _check_point(self, values: Mapping[str, Fraction]) -> None:
        scene = self.at(values)
        model = scene.build()
        free = sorted(s.name for s in getattr(model, "parameters", set()) if s.name != "n")
        if free:
            raise InputFormatError(f"a {self.quantity} map needs numbers for {', '.join(free)} "
                                   f"(--param {free[0]}=VALUE)")
        if sp.sympify(getattr(model, "delay", 0)).is_Symbol:
            raise InputFormatError("a map needs an integer delay (--delay N, or an axis delay=start:stop:count)")
        if self.quantity == "stability":
            from hapticproof.analysis.stability import SceneLoops

            SceneLoops(scene).scene()

    @property
    def fixed(self) -> tuple[tuple[str, Any], ...]:
        """The scene's parameters with a number (for titles)."""
        return tuple((k, Fraction(int(v.p), int(v.q))) for k, v in sorted(self.scene.param_values.items())
                     if isinstance(v, sp.Basic) and v.is_Rational)

    @functools.cached_property
    def line_axis(self) -> str:
        """``'x'`` or ``'y'``: the axis a line varies (the one with the cheapest structure)."""
        scene = self.scene
        if self.quantity == "stability":
            order = ["K"]
        else:
            damping = scene.role("device_damping") if scene.system == "single-user" else None
            order = [damping, "z_a", "K", "B", scene.role("period"), "K_0", "B_0"]

        def rank(name: str) -> int:
            return 100 if name in FIELD_AXES else order.index(name) if name in order else 50

        return "x" if rank(self.x.name) <= rank(self.y.name) else "y"

    @property
    def lines(self) -> int:
        return len(self.y.values) if self.line_axis == "x" else len(self.x.values)

    def line(self, index: int) -> tuple[str, tuple[Fraction, ...], str, Fraction]:
        """``(varied name, its values, the other axis' name, its value)`` of line ``index``."""
        along, across = (self.x, self.y) if self.line_axis == "x" else (self.y, self.x)
        return along.name, along.values, across.name, across.values[index]

    @property
    def points(self) -> int:
        return len(self.x.values) * len(self.y.values)


# ---------------------------------------------------------------------------------------------
# exact rational functions of the axes, evaluated with fractions (no SymPy per point)
# ---------------------------------------------------------------------------------------------


class _Rational:
    """A rational function of a few symbols with rational coefficients, evaluated exactly."""

    def __init__(self, expr: Any, gens: tuple[sp.Symbol, ...]):
        num, den = sp.fraction(sp.cancel(sp.together(sp.sympify(expr))))
        self.gens = gens
        self.names = tuple(g.name for g in gens)
        self.num, self.den = self._terms(num), self._terms(den)

    def _terms(self, poly: Any) -> tuple[tuple[tuple[int, ...], Fraction], ...]:
        if not self.gens:
            value = sp.Rational(poly)
            return (((), Fraction(int(value.p), int(value.q))),)
        terms = sp.Poly(poly, *self.gens).terms()
        return tuple((tuple(int(e) for e in monom), Fraction(int(sp.Rational(c).p), int(sp.Rational(c).q)))
                     for monom, c in terms)

    def degree(self, name: str, part: str = "num") -> int:
        if name not in self.names:
            return 0
        k = self.names.index(name)
        return max((m[k] for m, _ in getattr(self, part)), default=0)

    @staticmethod
    def _eval(terms: tuple, values: tuple[Fraction, ...]) -> Fraction:
        total = Fraction(0)
        for monom, c in terms:
            term = c
            for v, e in zip(values, monom):
                if e:
                    term *= v**e
            total += term
        return total

    def __call__(self, values: Mapping[str, Fraction]) -> Fraction:
        args = tuple(values[name] for name in self.names)
        den = self._eval(self.den, args)
        if den == 0:
            shown = ", ".join(f"{n} = {v}" for n, v in zip(self.names, args))
            raise SceneError(f"the scene divides by zero at {shown}")
        return self._eval(self.num, args) / den


def _axis_symbols(spec: MapSpec) -> tuple[sp.Symbol, ...]:
    return tuple(spec.scene.symbol(a.name) for a in (spec.x, spec.y) if a.name not in FIELD_AXES)


@dataclass(frozen=True)
class _SingleUserForm:
    """A single-user scene with the map's parameters symbolic: ``b``, ``T``, ``z_a`` and the
    coefficients of ``H(z)`` as exact rational functions of them, and which lines have the
    damping (additive) or the affine (convex) structure."""

    b: _Rational
    T: _Rational
    z_a: _Rational
    H_num: tuple[_Rational, ...]
    H_den: tuple[_Rational, ...]
    approximation: str
    delay: int
    additive: frozenset         # a = b - z_a affine in it, H and T free of it
    convex: frozenset           # G^-1 affine in it with fixed poles

    @classmethod
    def of(cls, spec: MapSpec) -> _SingleUserForm:
        from hapticproof.core.symbols import z as Z_SYM
        from hapticproof.systems.models import environment_path

        gens = _axis_symbols(spec)
        model = spec.scene.build()
        H = sp.cancel(sp.together(sp.sympify(model.H)))
        num, den = sp.fraction(H)
        H_num = tuple(_Rational(c, gens) for c in sp.Poly(num, Z_SYM).all_coeffs()[::-1])
        H_den = tuple(_Rational(c, gens) for c in sp.Poly(den, Z_SYM).all_coeffs()[::-1])
        a = _Rational(model.b - model.z_a, gens)
        b, z_a = _Rational(model.b, gens), _Rational(model.z_a, gens)
        additive, convex = set(), set()
        path = sp.fraction(sp.cancel(sp.together(environment_path(model))))
        for g in gens:
            linear_a = a.degree(g.name) <= 1 and a.degree(g.name, "den") == 0
            parts_linear = all(f.degree(g.name) <= 1 and f.degree(g.name, "den") == 0 for f in (b, z_a))
            if linear_a and parts_linear and a.degree(g.name) == 1 and not H.has(g) and not sp.sympify(model.T).has(g):
                additive.add(g.name)
            if linear_a and not path[1].has(g) and sp.Poly(path[0], g).degree() <= 1:
                convex.add(g.name)
        delay = sp.sympify(model.delay)
        return cls(b, _Rational(model.T, gens), z_a, H_num, H_den,
                   model.approximation, int(delay) if delay.is_Integer else 0, frozenset(additive), frozenset(convex))

    def line(self, along: str, fixed: Mapping[str, Fraction]) -> Callable[[Fraction], Any]:
        """``v -> NumericScene`` along ``along`` with ``fixed`` (the other axis): what does not
        depend on ``along`` is evaluated once."""
        from hapticproof.analysis.fastpath import NumericScene

        parts = [self.b, self.T, self.z_a, *self.H_num, *self.H_den]
        known = [None if along in f.names else f(fixed) for f in parts]
        n_num = len(self.H_num)

        def point(v: Fraction) -> Any:
            values = {**fixed, along: v}
            b, T, z_a, *H = (k if k is not None else f(values) for f, k in zip(parts, known))
            delay = int(values.get("delay", self.delay))
            return NumericScene(b=b, T=T, H=(tuple(H[:n_num]), tuple(H[n_num:])), approximation=self.approximation,
                                delay=delay, z_a=z_a)

        return point


_FORMS: dict[Any, _SingleUserForm] = {}


def _form(spec: MapSpec) -> _SingleUserForm:
    """The spec's symbolic analysis, once per process (every line of a chunk, every chunk)."""
    key = (spec.quantity, spec.x.name, spec.y.name, spec.scene)
    if key not in _FORMS:
        if len(_FORMS) > 16:
            _FORMS.clear()
        _FORMS[key] = _SingleUserForm.of(spec)
    return _FORMS[key]


# ---------------------------------------------------------------------------------------------
# passivity lines
# ---------------------------------------------------------------------------------------------


def _verdict(decision: Any) -> int:
    from hapticproof.core.evidence import Decision

    return 1 if decision == Decision.PROVED else 0 if decision == Decision.DISPROVED else -1


def _passive(scene: Any) -> int:
    from hapticproof.analysis.fastpath import decide

    return _verdict(decide(scene, minimum=False).decision)


def _damping_line(name: str, values: tuple[Fraction, ...], point: Callable[[Fraction], Any],
                  form: _SingleUserForm, fixed: Mapping[str, Fraction]) -> np.ndarray:
    """The device damping or ``z_a`` varies (``a = b - z_a`` affine in it): one certified
    ``beta`` for the whole line (``a`` itself is all a point needs outside beta's enclosure)."""
    from hapticproof.analysis.fastpath import (
        critical_damping,
        hermitian_outcome,
        transfer,
    )
    from hapticproof.core.evidence import Decision
    from hapticproof.exact.conditions import pole_conditions

    base = point(values[0])
    out = np.zeros(len(values), dtype=np.int8)
    if not all(c.decision == Decision.PROVED for c in pole_conditions(*transfer(base))):
        return out                              # the poles and residues do not depend on a
    lo, hi = critical_damping(base)             # passive iff a >= beta, beta in [lo, hi]
    b0, b1 = form.b({**fixed, name: values[0]}), form.b({**fixed, name: values[-1]})
    z0, z1 = form.z_a({**fixed, name: values[0]}), form.z_a({**fixed, name: values[-1]})
    for bound, what in ((min(b0, b1), "the device damping"), (min(z0, z1), "the shortage of passivity z_a")):
        if bound < 0:                           # a and its parts are affine: the ends are the extremes
            raise SceneError(f"{what} must be non-negative, got {bound} on the line {name}")
    a0 = b0 - z0
    slope = ((b1 - z1) - a0) / (values[-1] - values[0]) if len(values) > 1 and values[-1] != values[0] else 0
    for i, v in enumerate(values):
        a = a0 + slope * (v - values[0])
        if a >= hi:
            out[i] = 1
        elif a >= lo:                           # inside the certified enclosure: decide this point
            out[i] = _verdict(hermitian_outcome(point(v), minimum=False).decision)
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


def _single_user_passivity(spec: MapSpec, along: str, values: tuple[Fraction, ...], fixed: dict) -> np.ndarray:
    form = _form(spec)
    point = form.line(along, fixed)
    if along in form.additive:
        return _damping_line(along, values, point, form, fixed)
    if along in form.convex:
        return _convex_line(values, lambda i: _passive(point(values[i])))
    return np.array([_passive(point(v)) for v in values], dtype=np.int8)


def _affine_entries(entries: Any, p: sp.Symbol) -> bool:
    """Every entry a rational function whose denominator is free of ``p`` and numerator affine in it."""
    for entry in entries:
        num, den = sp.fraction(sp.cancel(sp.together(entry)))
        if den.has(p) or (num.has(p) and sp.Poly(num, p).degree() > 1):
            return False
    return True


def _model_line(scene: Any, along: str, values: tuple[Fraction, ...], decide: Callable[[Any], Any],
                affine: Callable[[Any, sp.Symbol], bool]) -> np.ndarray:
    """An m-user or teleoperator line: the model once with the parameter symbolic, each point its
    exact decision; convex lines (``affine``) by the binary search."""
    if along in FIELD_AXES:
        return np.array([_verdict(decide(scene.replace(**{along: int(v)}).build()).decision) for v in values],
                        dtype=np.int8)
    model = scene.build()
    p = scene.symbol(along)
    groups = {"K_0", "B_0", "K", "B", "z_a", scene.role("device_damping")} if scene.system == "multi-user" else set()
    direct = p in model.parameters and (along not in groups or scene.uniform)
    if direct:
        at = lambda v: model.with_values(**{p.name: sp.Rational(v.numerator, v.denominator)})  # noqa: E731
    else:                                       # a group name of per-user parameters: the scene sets them
        at = lambda v: scene.with_params({along: sp.Rational(v.numerator, v.denominator)}).build()  # noqa: E731
    verdict = lambda i: _verdict(decide(at(values[i])).decision)  # noqa: E731
    if direct and affine(model, p):
        return _convex_line(values, verdict)
    return np.array([verdict(i) for i in range(len(values))], dtype=np.int8)


def _multi_user_affine(model: Any, p: sp.Symbol) -> bool:
    from hapticproof.systems.multiuser import inverse_transfer_matrix

    return _affine_entries(list(inverse_transfer_matrix(model)), p)


def _teleoperator_affine(model: Any, p: sp.Symbol) -> bool:
    """A robot damping: the conditions are ``b_m >= bound_m(c)``, ``b_s >= bound_s(c)`` with
    bounds free of it."""
    from hapticproof.analysis.teleoperator import bounds

    if p not in (model.b_m, model.b_s):
        return False
    bd = bounds(model)
    return not (sp.sympify(bd.master).has(p) or sp.sympify(bd.slave).has(p) or sp.sympify(model.C).has(p))


def _passivity_line(spec: MapSpec, along: str, values: tuple[Fraction, ...], across: str,
                    across_value: Fraction) -> np.ndarray:
    fixed = {across: across_value}
    if spec.scene.system == "single-user":
        return _single_user_passivity(spec, along, values, fixed)
    scene = spec.at(fixed)
    if spec.scene.system == "multi-user":
        from hapticproof.analysis.multiuser import positive_real

        return _model_line(scene, along, values, positive_real, _multi_user_affine)
    from hapticproof.analysis.teleoperator import passivity

    return _model_line(scene, along, values, passivity, _teleoperator_affine)


# ---------------------------------------------------------------------------------------------
# stability lines
# ---------------------------------------------------------------------------------------------


def _stability_point(params: Mapping[str, Fraction]) -> int:
    """The stability of the exact ZOH loop at one point (:func:`hapticproof.analysis.sampled.decide_stability`:
    ``rho = 1`` exactly -- ``K = 0``, say -- is not stable)."""
    from hapticproof.analysis.sampled import decide_stability
    from hapticproof.systems.loops import SingleUser

    return decide_stability(SingleUser(m=params["m"], b=params["b"], T=params["T"], K=params["K"], B=params["B"],
                                       delay=int(params["delay"]))).value


def _stability_gaps(params: Mapping[str, Fraction], bits: int) -> tuple[list, list[bool]]:
    """The certified crossing stiffnesses (``beta`` balls, sorted) and the stability of each gap
    between them (from ``beta = 0+`` up): every crossing, not only the first."""

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
        edges = [beta for beta, _ in bd.crossings(norm, n, bits)]
        stable = bd.stable_between(norm, n, edges, bits)
        return edges, stable


def _stability_line(name: str, values: tuple[Fraction, ...], params: dict) -> np.ndarray:
    if name != "K" or params["B"] < 0 or params["b"] <= 0:
        # the crossing analysis takes a device damping b > 0 and a virtual damping B >= 0: the
        # other lines are decided point by point, as every point is (b = 0 exactly)
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
        if edges is None or K <= 0:        # the gaps start at beta = 0+: K = 0 (rho = 1) and K < 0 by points
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


def _radius_verdict(loop: Any) -> int:
    """The stability of the exact ZOH loop (:func:`hapticproof.analysis.sampled.decide_stability`):
    ``1`` stable, ``0`` not (``rho = 1`` exactly included), ``-1`` undecided."""
    from hapticproof.analysis.sampled import decide_stability

    return decide_stability(loop).value


def _wall_parameters(scene: Any, skip: str) -> dict[str, Fraction] | None:
    """``m, b, T, K, B, delay`` (the papers' names; ``skip`` the varied one) of a free device on
    the virtual wall, or ``None`` when the scene is another one or a value is not a number (an
    expression of the varied parameter, say)."""
    if scene.system != "single-user" or scene.environment is not None or scene.discretize is not None \
            or scene.operator is not None or scene.active or "z_a" in dict(scene.params):
        return None
    values = scene.resolved_values()
    role = scene.role
    out = {"delay": Fraction(int(scene.delay))}
    for std, name in (("m", role("mass")), ("b", role("device_damping")), ("T", role("period")), ("K", "K"), ("B", "B")):
        if std == skip:
            continue
        v = values.get(name)
        if v is None or not v.is_Rational:
            return None
        out[std] = Fraction(int(v.p), int(v.q))
    return out


def _stability_of(spec: MapSpec, along: str, values: tuple[Fraction, ...], across: str,
                  across_value: Fraction) -> np.ndarray:
    from hapticproof.analysis.stability import SceneLoops

    scene = spec.at({across: across_value})
    if scene.system == "single-user":
        role = scene.role
        std = {role("mass"): "m", role("device_damping"): "b", role("period"): "T", "K": "K", "B": "B",
               "delay": "delay"}.get(along)
        wall = _wall_parameters(scene, std) if std is not None else None
        if wall is not None:
            return _stability_line(std, values, wall)
    if along in FIELD_AXES:
        return np.array([_radius_verdict(SceneLoops(scene.replace(**{along: int(v)})).scene()) for v in values],
                        dtype=np.int8)
    loops = SceneLoops(scene)
    return np.array([_radius_verdict(loops.scene(**{along: v})) for v in values], dtype=np.int8)


# ---------------------------------------------------------------------------------------------
# the chunk function and the runs
# ---------------------------------------------------------------------------------------------


def line_values(spec: MapSpec, index: int) -> np.ndarray:
    """Verdicts along line ``index`` (``1``, ``0``, ``-1`` undecided)."""
    along, values, across, across_value = spec.line(index)
    if spec.quantity == "passivity":
        return _passivity_line(spec, along, values, across, across_value)
    return _stability_of(spec, along, values, across, across_value)


def map_chunk(task: tuple[MapSpec, tuple[int, ...]]) -> list[tuple[int, np.ndarray]]:
    """The one chunk function of serial, process and Dask runs: the lines of a chunk.

    >>> from hapticproof.systems.scene import Scene
    >>> spec = MapSpec.build("passivity", "b=0.001:0.003:3", "K=1:3:3", Scene("single-user", params={"T": "0.001"}))
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
    _, values, _, across_value = spec.line(line)
    for v, verdict in zip(values, verdicts):
        x, y = (v, across_value) if spec.line_axis == "x" else (across_value, v)
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


def plot_map(result: MapResult, path: str | Path, title: str = "", *, overlay: MapResult | None = None,
             curves: Any = ()) -> Path:
    """Two-colour image of the map (dark: not passive / unstable; red: undecided).

    ``overlay`` (a map of the other quantity on the same grid) makes it four classes: both good
    (light green), only the overlay's good (grey), only this map's good (orange: a passive model
    whose exact loop is unstable), neither (dark). ``curves`` are ``(label, xs, ys)`` or ``(label,
    xs, ys, style)`` drawn on top (boundaries).
    """
    from matplotlib.backends.backend_agg import FigureCanvasAgg
    from matplotlib.colors import ListedColormap
    from matplotlib.figure import Figure
    from matplotlib.patches import Patch

    spec = result.spec
    fig = Figure(figsize=(6.4, 4.4))
    FigureCanvasAgg(fig)
    ax = fig.add_subplot(111)
    xs = np.array([float(v) for v in spec.x.values])
    ys = np.array([float(v) for v in spec.y.values])
    legend = []
    if overlay is None:
        image = np.where(result.values == 1, 0, np.where(result.values == 0, 1, 2)).astype(float)
        colours = ["#f4f4f4", "#444444", "#d62728"]
    else:
        if overlay.values.shape != result.values.shape:
            raise ValueError("the overlay is a map of another grid")
        mine, other = _label(spec), _label(overlay.spec)
        undecided = (result.values == -1) | (overlay.values == -1)
        image = np.where(undecided, 4, np.where(result.values == 1, np.where(overlay.values == 1, 0, 2),
                                                np.where(overlay.values == 1, 1, 3))).astype(float)
        colours = ["#d8efd0", "#d4d4d4", "#f5a35c", "#555555", "#d62728"]
        words = [f"{mine} and {other}", f"{other}, not {mine}", f"{mine}, not {other}", "neither", "undecided"]
        legend = [Patch(facecolor=c, edgecolor="#888888", label=w) for c, w, k in zip(colours, words, range(5))
                  if (image == k).any()]
    ax.pcolormesh(xs, ys, image, cmap=ListedColormap(colours), vmin=0, vmax=len(colours) - 1, shading="nearest")
    styles = ["k-", "b--", "g-.", "m:"]
    for k, (label, cx, cy, *style) in enumerate(curves):
        ax.plot(np.asarray(cx, float), np.asarray(cy, float), style[0] if style else styles[k % len(styles)], lw=1.8,
                label=label)
    ax.set_xlim(xs[0], xs[-1])
    ax.set_ylim(ys[0], ys[-1])
    ax.set_xlabel(spec.x.name)
    ax.set_ylabel(spec.y.name)
    fixed = ", ".join(f"{k} = {_number(v)}" for k, v in spec.fixed)
    ax.set_title(title or f"exact {spec.quantity} map ({fixed}); light: {_label(spec)}", fontsize=9)
    if legend or curves:
        handles, _ = ax.get_legend_handles_labels()
        ax.legend(handles=handles + legend, fontsize=7, loc="upper left", bbox_to_anchor=(1.01, 1.0),
                  borderaxespad=0.0)        # beside the map, never over it
    from hapticproof.core.files import write_figure

    return write_figure(fig, path, "--plot")      # the one writer: whole or not at all, no link followed
