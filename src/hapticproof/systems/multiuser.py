"""m-user haptic virtual environments (HVE paper, Section 3.2): the scene, its coupling
matrices and ``G^{-1}(z)`` as an m x m matrix (the decisions are in
:mod:`hapticproof.analysis.multiuser`)."""

from __future__ import annotations

import functools
import itertools
import operator
from collections.abc import Iterable, Mapping, Sequence
from dataclasses import dataclass, field, fields, replace
from typing import Any

import sympy as sp

from hapticproof.core.errors import SceneError
from hapticproof.core.lazy import stage
from hapticproof.systems.models import integrator
from hapticproof.systems.singleuser import APPROXIMATIONS, SYMBOLS, as_parameter
from hapticproof.core.symbols import z as Z_SYM

__all__ = ["UNIFORM_SYMBOLS", "MultiUserScene", "complete_graph", "map_values", "user_symbols", "inverse_transfer_matrix", "stiffness_matrix", "damping_matrix", "to_sampled"]


#: Symbols of the uniform (worst-case) parameters, named as the paper prints them.
UNIFORM_SYMBOLS: dict[str, sp.Symbol] = {
    "b": SYMBOLS["b"],
    "T": SYMBOLS["T"],
    "K_0": sp.Symbol("K_0", positive=True),
    "B_0": sp.Symbol("B_0", nonnegative=True),
    "K": SYMBOLS["K"],
    "B": SYMBOLS["B"],
    "z_a": SYMBOLS["z_a"],
}


def _index(i: int, j: int | None = None) -> str:
    """Subscript text for 1-based indices (a separator once an index has two digits)."""
    if j is None:
        return str(i)
    return f"{i}{j}" if i < 10 and j < 10 else f"{i}_{j}"


def user_symbols(m: int) -> dict[str, Any]:
    """The paper's per-user symbols for ``m`` users (complete graph): ``b_i``, ``K_0i``,
    ``B_0i``, ``z_ai``, ``K_ij``, ``B_ij`` with its assumptions (damping, stiffness positive;
    virtual damping and shortage of passivity non-negative).

    >>> s = user_symbols(2)
    >>> s["b"], s["K0"], s["K"][(0, 1)], s["z_a"][1]
    ((b_1, b_2), (K_01, K_02), K_12, z_a2)
    """
    users = range(1, m + 1)
    return {
        "b": tuple(sp.Symbol(f"b_{i}", positive=True) for i in users),
        "K0": tuple(sp.Symbol(f"K_0{_index(i)}", positive=True) for i in users),
        "B0": tuple(sp.Symbol(f"B_0{_index(i)}", nonnegative=True) for i in users),
        "z_a": tuple(sp.Symbol(f"z_a{_index(i)}", nonnegative=True) for i in users),
        "K": {(i - 1, j - 1): sp.Symbol(f"K_{_index(i, j)}", positive=True) for i, j in itertools.combinations(users, 2)},
        "B": {(i - 1, j - 1): sp.Symbol(f"B_{_index(i, j)}", nonnegative=True) for i, j in itertools.combinations(users, 2)},
    }


@functools.lru_cache(maxsize=16)
def complete_graph(m: int) -> tuple[tuple[int, int], ...]:
    """Edges ``(i, j)``, ``0 <= i < j < m``, of the complete graph (one tuple per ``m``, shared: a
    scene holding it needs no edge validation, which matters for ``m(m-1)/2`` edges)."""
    return tuple(itertools.combinations(range(m), 2))


def _repeats(values: tuple) -> bool:
    """All entries one object (a uniform scene's edge weights): an identity test at C speed."""
    return bool(values) and all(map(operator.is_, values, itertools.repeat(values[0])))


def map_values(func: Any, values: Any) -> tuple:
    """``tuple(map(func, values))`` with ``func`` called once per distinct object: a uniform scene
    repeats one value ``m`` or ``m(m-1)/2`` times.

    >>> map_values(lambda v: 2 * v, (1, 1, 3))
    (2, 2, 6)
    """
    values = tuple(values)
    if _repeats(values):
        return (func(values[0]),) * len(values)
    objects = dict(zip(map(id, values), values))
    images = {key: func(v) for key, v in objects.items()}
    return tuple(map(images.__getitem__, map(id, values)))


def _exact_values(values: Any, name: str) -> tuple[sp.Expr, ...]:
    """``as_parameter`` of each value, each distinct object converted once."""
    return map_values(lambda v: as_parameter(name, v), values)


def _distinct(*groups: Any) -> list:
    """The distinct values of some tuples (by identity first, then by equality)."""
    out: dict[int, Any] = {}
    for values in groups:
        values = tuple(values)
        if _repeats(values):
            out.setdefault(id(values[0]), values[0])
        else:
            out.update(zip(map(id, values), values))
    return list(dict.fromkeys(out.values()))


def _tuple(values: Any, m: int, name: str) -> tuple[sp.Expr, ...]:
    if isinstance(values, (list, tuple)):
        if len(values) != m:
            raise SceneError(f"{name} needs one value per user ({m}), got {len(values)}")
        return _exact_values(values, name)
    return (as_parameter(name, values),) * m


def _edge_values(values: Any, edges: Sequence[tuple[int, int]], m: int, name: str) -> tuple[sp.Expr, ...]:
    """Edge weights from a scalar, a mapping ``{(i, j): w}`` (0-based) or an ``m x m`` matrix."""
    if isinstance(values, Mapping):
        out = []
        for i, j in edges:
            if (i, j) in values:
                out.append(as_parameter(name, values[(i, j)]))
            elif (j, i) in values:
                out.append(as_parameter(name, values[(j, i)]))
            else:
                raise SceneError(f"{name}: no value for the edge ({i + 1}, {j + 1})")
        return tuple(out)
    if isinstance(values, (list, tuple, sp.MatrixBase)) and not isinstance(values, str):
        rows = sp.Matrix(values)
        if rows.shape == (m, m):
            for i in range(m):
                for j in range(m):
                    if sp.simplify(rows[i, j] - rows[j, i]) != 0:
                        raise SceneError(f"{name} must be symmetric")
            return tuple(as_parameter(name, rows[i, j]) for i, j in edges)
        if rows.shape in ((len(edges), 1), (1, len(edges))):
            return tuple(as_parameter(name, v) for v in rows)
        raise SceneError(f"{name} must be a scalar, an edge mapping or an {m}x{m} matrix")
    return (as_parameter(name, values),) * len(edges)


@dataclass(frozen=True, slots=True, weakref_slot=True)
class MultiUserScene:
    """An m-user sampled-data HVE (HVE paper Fig. 6/7, eqs. 37-39, 47, 56).

    Parameters
    ----------
    b, K0, B0, z_a : tuple
        Per-user device damping ``b_i``, ground stiffness ``K_0i``, ground damping ``B_0i`` and
        the operators' shortage of passivity ``z_ai``.
    T : expr
        Sampling period.
    edges : tuple of (int, int)
        The coupling graph (0-based ``i < j``); complete by default in the constructors.
    K, B : tuple
        Coupling stiffness ``K_ij`` and damping ``B_ij``, one per edge.
    delays : tuple of int
        Per-user delays ``n_i = t_di/T`` (integers; the row of user ``i`` is delayed).
    approximation : {'forward', 'backward', 'tustin'}
        Approximation of ``X_h = Z{v_h/s}``.
    """

    b: tuple
    T: sp.Expr
    K0: tuple
    B0: tuple
    edges: tuple
    K: tuple
    B: tuple
    delays: tuple
    z_a: tuple
    approximation: str = "forward"
    #: the scene's naming (:mod:`hapticproof.systems.naming`) when its symbols do not give it
    names: Any = field(default=None, repr=False)
    #: derived facts computed once per scene (its hash, uniformity): m(m-1)/2 edge values make
    #: them costly to recompute at every cache lookup
    _memo: dict = field(default=None, init=False, repr=False, compare=False, hash=False)

    def __hash__(self) -> int:
        memo = self._facts()
        if "hash" not in memo:
            distinct = lambda values: frozenset(_distinct(values))  # noqa: E731 - equal scenes: equal sets
            m = self.users            # distinct valid pairs: all m(m-1)/2 of them is the complete graph
            edges = ("complete", m) if len(self.edges) == m * (m - 1) // 2 else self.edges
            memo["hash"] = hash((len(self.b), distinct(self.b), self.T, distinct(self.K0), distinct(self.B0), edges,
                                 distinct(self.K), distinct(self.B), self.delays, distinct(self.z_a), self.approximation))
        return memo["hash"]

    def _facts(self) -> dict:
        if self._memo is None:
            object.__setattr__(self, "_memo", {})
        return self._memo

    def __getstate__(self) -> list:            # the memo stays home: a hash is valid in one process only
        return [None if f.name == "_memo" else getattr(self, f.name) for f in fields(self)]

    def __setstate__(self, state: list) -> None:
        for f, value in zip(fields(self), state):
            object.__setattr__(self, f.name, value)
        if self.edges == complete_graph(len(self.b)):          # the shared tuple again (no edge validation)
            object.__setattr__(self, "edges", complete_graph(len(self.b)))

    def __post_init__(self) -> None:
        m = len(self.b)
        if m < 1:
            raise SceneError("an m-user scene needs at least one user")
        for name in ("b", "K0", "B0", "z_a"):
            object.__setattr__(self, name, _tuple(tuple(getattr(self, name)), m, name))
        object.__setattr__(self, "T", as_parameter("T", self.T))
        if self.edges is not complete_graph(m):      # the shared complete graph is valid as it is
            edges = tuple(tuple(sorted((int(i), int(j)))) for i, j in self.edges)
            if any(i == j or i < 0 or j >= m for i, j in edges) or len(set(edges)) != len(edges):
                raise SceneError(f"edges must be distinct pairs of distinct users in 0..{m - 1}")
            object.__setattr__(self, "edges", complete_graph(m) if edges == complete_graph(m) else edges)
        edges = self.edges
        for name in ("K", "B"):
            values = _exact_values(getattr(self, name), name)
            if len(values) != len(edges):
                raise SceneError(f"{name} needs one value per edge ({len(edges)})")
            object.__setattr__(self, name, values)
        delays = tuple(self.delays)
        if len(delays) != m:
            raise SceneError(f"delays needs one value per user ({m})")
        checked = []
        for n in delays:
            value = as_parameter("delay", n)
            if not (value.is_Integer and value >= 0):
                raise SceneError(f"the delays n_i = t_di/T must be non-negative integers, got {n}")
            checked.append(int(value))
        object.__setattr__(self, "delays", tuple(checked))
        if self.approximation not in APPROXIMATIONS:
            raise SceneError(f"unknown approximation {self.approximation!r}; choose one of {', '.join(APPROXIMATIONS)}")
        if self.T.is_number and not self.T > 0:
            raise SceneError(f"the sampling period T must be positive, got {self.T}")

    # -- constructors ---------------------------------------------------------------------------
    @classmethod
    def symbolic(
        cls,
        m: int,
        *,
        edges: Iterable[tuple[int, int]] | None = None,
        delays: Any = 0,
        active: bool = False,
        approximation: str = "forward",
        T: Any = None,
    ) -> MultiUserScene:
        """Every parameter its own symbol (``b_i``, ``K_0i``, ``B_0i``, ``K_ij``, ``B_ij`` and,
        when ``active``, ``z_ai``).

        >>> MultiUserScene.symbolic(2).K
        (K_12,)
        """
        _check_users(m)
        sym = user_symbols(m)
        graph = complete_graph(m) if edges is None else tuple(tuple(sorted(e)) for e in edges)
        K = tuple(sym["K"].get(e) or sp.Symbol(f"K_{_index(e[0] + 1, e[1] + 1)}", positive=True) for e in graph)
        B = tuple(sym["B"].get(e) or sp.Symbol(f"B_{_index(e[0] + 1, e[1] + 1)}", nonnegative=True) for e in graph)
        return cls(
            b=sym["b"], T=SYMBOLS["T"] if T is None else T, K0=sym["K0"], B0=sym["B0"], edges=graph, K=K, B=B,
            delays=_delays(delays, m), z_a=sym["z_a"] if active else (0,) * m, approximation=approximation,
        )

    @classmethod
    def uniform(
        cls,
        m: int,
        *,
        b: Any = None,
        K0: Any = None,
        B0: Any = None,
        K: Any = None,
        B: Any = None,
        T: Any = None,
        delay: Any = 0,
        z_a: Any = 0,
        edges: Iterable[tuple[int, int]] | None = None,
        approximation: str = "forward",
    ) -> MultiUserScene:
        """All users alike: one ``b``, ``K_0``, ``B_0``, ``z_a``, one ``K`` and ``B`` on every
        edge (complete graph by default); unspecified values are the symbols
        :data:`UNIFORM_SYMBOLS`. ``delay`` is one delay or one per user: uniform parameters
        with unequal delays are still one scene, but no longer decouple into modes (their
        decision then needs numbers).

        >>> MultiUserScene.uniform(2, b=1, K0=2, B0=0, K=2, B=0, T="0.001").is_numeric
        True
        """
        _check_users(m)
        u = UNIFORM_SYMBOLS
        graph = complete_graph(m) if edges is None else tuple(tuple(sorted(e)) for e in edges)
        pick = lambda value, key: u[key] if value is None else value  # noqa: E731
        return cls(
            b=(pick(b, "b"),) * m, T=pick(T, "T"), K0=(pick(K0, "K_0"),) * m, B0=(pick(B0, "B_0"),) * m,
            edges=graph, K=(pick(K, "K"),) * len(graph), B=(pick(B, "B"),) * len(graph),
            delays=_delays(delay, m), z_a=(z_a,) * m, approximation=approximation,
        )

    @classmethod
    def from_values(
        cls,
        *,
        b: Any,
        T: Any,
        K0: Any,
        K: Any = 0,
        B0: Any = 0,
        B: Any = 0,
        delays: Any = 0,
        z_a: Any = 0,
        users: int | None = None,
        edges: Iterable[tuple[int, int]] | None = None,
        approximation: str = "forward",
    ) -> MultiUserScene:
        """Numeric (or mixed) parameters; per-user values as lists, couplings as a scalar, an
        edge mapping ``{(i, j): w}`` (0-based) or an ``m x m`` matrix.

        >>> s = MultiUserScene.from_values(b=[1, 2, 3], T="0.01", K0=5, K={(0, 1): 1, (0, 2): 2, (1, 2): 3})
        >>> s.users, s.K
        (3, (1, 2, 3))
        """
        m = users
        for value in (b, K0, B0, z_a, delays):
            if isinstance(value, (list, tuple)):
                m = len(value)
                break
        if m is None:
            raise SceneError("give per-user values as lists or the number of users")
        graph = complete_graph(m) if edges is None else tuple(tuple(sorted(e)) for e in edges)
        return cls(
            b=_tuple(b, m, "b"), T=T, K0=_tuple(K0, m, "K_0"), B0=_tuple(B0, m, "B_0"), edges=graph,
            K=_edge_values(K, graph, m, "K"), B=_edge_values(B, graph, m, "B"), delays=_delays(delays, m),
            z_a=_tuple(z_a, m, "z_a"), approximation=approximation,
        )

    # -- properties -----------------------------------------------------------------------------
    @property
    def users(self) -> int:
        return len(self.b)

    @property
    def parameters(self) -> set[sp.Symbol]:
        out: set[sp.Symbol] = set()
        for v in _distinct(self.b, self.K0, self.B0, self.z_a, self.K, self.B, (self.T,)):
            out |= sp.sympify(v).free_symbols
        return out

    @property
    def is_numeric(self) -> bool:
        return not self.parameters

    def naming(self) -> Any:
        """The names every view of this scene prints (:class:`~hapticproof.core.naming.Naming`)."""
        if self.names is not None:
            return self.names
        from hapticproof.systems.naming import model_naming

        b = set(self.b)
        group = next(iter(b)) if len(b) == 1 else None
        if group is None and all(isinstance(v, sp.Symbol) for v in self.b):
            heads = {v.name.rpartition("_")[0] for v in self.b}
            if len(heads) == 1 and [v.name for v in self.b] == [f"{next(iter(heads))}_{i + 1}" for i in range(self.users)]:
                group = sp.Symbol(next(iter(heads)))
        return model_naming("multi-user", {"period": self.T, "device_damping": group}, self.parameters)

    @property
    def has_delay(self) -> bool:
        return any(self.delays)

    @property
    def equal_delays(self) -> bool:
        return len(set(self.delays)) == 1

    @property
    def is_uniform(self) -> bool:
        """Equal per-user values and equal edge weights (the paper's worst-case reading)."""
        memo = self._facts()
        if "uniform" not in memo:
            same = lambda values: len(_distinct(values)) <= 1  # noqa: E731 - the values are exact SymPy numbers
            memo["uniform"] = all(same(v) for v in (self.b, self.K0, self.B0, self.z_a, self.K, self.B, self.delays))
        return memo["uniform"]

    @property
    def is_complete(self) -> bool:
        return self.edges is complete_graph(self.users) or set(self.edges) == set(complete_graph(self.users))

    @property
    def damped(self) -> bool:
        """Some virtual damping is (possibly) non-zero."""
        return any(sp.sympify(v) != 0 for v in (*self.B0, *self.B))

    def with_values(self, values: Mapping[Any, Any] | None = None, **named: Any) -> MultiUserScene:
        """Substitute exact values for parameters (by symbol or by name).

        >>> MultiUserScene.uniform(2).with_values(b=1, K_0=1, B_0=0, K=1, B=0, T="0.01").is_numeric
        True
        """
        by_name = {s.name: s for s in self.parameters}
        mapping: dict[sp.Symbol, sp.Expr] = {}
        for key, value in list((values or {}).items()) + list(named.items()):
            symbol = by_name.get(key) if isinstance(key, str) else key
            if symbol is None:
                raise SceneError(f"unknown parameter {key!r}; the scene has {sorted(by_name)}")
            mapping[symbol] = as_parameter(str(key), value)
        sub = lambda vals: map_values(lambda v: sp.sympify(v).xreplace(mapping), vals)  # noqa: E731
        return replace(self, b=sub(self.b), T=sp.sympify(self.T).xreplace(mapping), K0=sub(self.K0), B0=sub(self.B0),
                       K=sub(self.K), B=sub(self.B), z_a=sub(self.z_a))

    def weights(self, values: Sequence[Any]) -> sp.Matrix:
        """The symmetric ``m x m`` matrix of edge weights (zero diagonal, zero off the graph)."""
        W = sp.zeros(self.users, self.users)
        for (i, j), w in zip(self.edges, values):
            W[i, j] = W[j, i] = w
        return W


def _check_users(m: Any) -> None:
    if isinstance(m, bool) or not isinstance(m, int) or m < 1:
        raise SceneError(f"the number of users must be a positive integer, got {m!r}")


def _delays(delays: Any, m: int) -> tuple:
    if isinstance(delays, (list, tuple)):
        if len(delays) != m:
            raise SceneError(f"delays needs one value per user ({m})")
        return tuple(delays)
    return (delays,) * m


def laplacian(ground: Sequence[Any], W: sp.Matrix) -> sp.Matrix:
    m = W.rows
    L = -W
    for i in range(m):
        L[i, i] = ground[i] + sum(W[i, k] for k in range(m))
    return L


@stage("stiffness_matrix")
def stiffness_matrix(scene: MultiUserScene) -> sp.ImmutableMatrix:
    """``Kmat = diag(K_0) + L_K`` (``Kmat_ii = K_0i + sum_k K_ik``, ``Kmat_ij = -K_ij``)."""
    return sp.ImmutableMatrix(laplacian(scene.K0, scene.weights(scene.K)))


@stage("damping_matrix")
def damping_matrix(scene: MultiUserScene) -> sp.ImmutableMatrix:
    """``Bmat = diag(B_0) + L_B``."""
    return sp.ImmutableMatrix(laplacian(scene.B0, scene.weights(scene.B)))


@stage("inverse_transfer_matrix")
def inverse_transfer_matrix(scene: MultiUserScene) -> sp.ImmutableMatrix:
    """``G^{-1}(z) = diag(b - z_a) + D(z) H(z) I(z)`` (eqs. 39, 47, 56 for m = 2, 3)."""
    m = scene.users
    Kmat, Bmat = stiffness_matrix(scene), damping_matrix(scene)
    I = integrator(scene.approximation, scene.T)
    H = Kmat + Bmat * (Z_SYM - 1) / (scene.T * Z_SYM)
    out = sp.zeros(m, m)
    for i in range(m):
        for j in range(m):
            entry = Z_SYM ** (-scene.delays[i]) * H[i, j] * I
            if i == j:
                entry += scene.b[i] - scene.z_a[i]
            out[i, j] = entry
    return sp.ImmutableMatrix(out)


def to_sampled(scene: MultiUserScene, masses: Sequence[Any] | Any, operators: Sequence[Any] | Any = None):
    """The exact sampled-data loop (:class:`hapticproof.systems.loops.MultiUser`) of a numeric scene
    with device masses and operator impedances (``z_a`` stays in the operators there).

    >>> s = MultiUserScene.uniform(2, b="0.01822", K0=10, B0=0, K=10, B=0, T="0.001")
    >>> from hapticproof.analysis.sampled import is_stable
    >>> is_stable(to_sampled(s, "0.015"))
    True
    """
    from hapticproof.systems.loops import MultiUser

    if not scene.is_numeric:
        raise SceneError("to_sampled needs numeric parameters")
    if scene.approximation != "forward":
        raise SceneError("the sampled-data loop implements the virtual coupling itself; use approximation='forward'")
    m = scene.users
    masses = tuple(masses) if isinstance(masses, (list, tuple)) else (masses,) * m
    ops = tuple(operators) if isinstance(operators, (list, tuple)) else (operators,) * m
    W = lambda values: scene.weights(values).tolist()  # noqa: E731
    return MultiUser(masses=masses, dampings=tuple(scene.b), T=scene.T, ground_stiffness=tuple(scene.K0),
                     ground_damping=tuple(scene.B0), coupling_stiffness=W(scene.K), coupling_damping=W(scene.B),
                     delays=tuple(scene.delays), operators=ops)
