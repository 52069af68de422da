"""Scenes: frozen descriptions of *what* to analyse.

A :class:`SingleUserScene` is the 1-DOF haptic device of the HVE paper (Fig. 4): device damping
``b`` (its mass is moved into the passive operator, as the paper does), a discrete environment
``H(z)`` (default the virtual wall ``K + B(z-1)/(Tz)``), an approximation of ``1/s``
(``forward``, ``backward``, ``tustin``), an integer delay ``n = t_d/T`` and the operator's
shortage of passivity ``z_a``. Parameters are SymPy symbols or exact numbers (floats are
converted exactly, decimal strings as exact decimals).

>>> scene = SingleUserScene.virtual_wall(approximation="tustin", delay=3)
>>> scene.H
B*(z - 1)/(T*z) + K
>>> scene.with_values(K=2, T="0.001").is_numeric
False
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass, field, replace
from typing import Any

import sympy as sp

from hapticproof.errors import SceneError
from hapticproof.evidence import exact
from hapticproof.symbols import n as N_SYM
from hapticproof.symbols import z as Z_SYM

__all__ = ["APPROXIMATIONS", "SYMBOLS", "SYSTEMS", "Scene", "SingleUserScene", "virtual_wall", "as_parameter", "as_delay"]

#: Approximations of ``X_h(z)`` from ``V_h(z)`` (HVE paper, Section 3.1.1).
APPROXIMATIONS = ("forward", "backward", "tustin")

#: Default symbols with the papers' physical assumptions: dampings, stiffnesses and the
#: sampling period are positive; virtual damping and shortage of passivity are non-negative.
SYMBOLS: dict[str, sp.Symbol] = {
    "b": sp.Symbol("b", positive=True),
    "T": sp.Symbol("T", positive=True),
    "K": sp.Symbol("K", positive=True),
    "B": sp.Symbol("B", nonnegative=True),
    "z_a": sp.Symbol("z_a", nonnegative=True),
    "t_d": sp.Symbol("t_d", nonnegative=True),
    "n": N_SYM,
}


def as_parameter(name: str, value: Any) -> sp.Expr:
    """An exact SymPy parameter: symbols stay, numbers become exact rationals."""
    if isinstance(value, str):
        try:
            return exact(value)
        except (ValueError, ZeroDivisionError):
            raise SceneError(f"{name}: {value!r} is not a number") from None
    try:
        return exact(value)
    except (TypeError, sp.SympifyError) as err:
        raise SceneError(f"{name}: cannot use {value!r} as a parameter") from err


def as_delay(delay: Any) -> sp.Expr:
    """Validate an integer delay ratio ``n = t_d/T`` (a non-negative integer or a symbol)."""
    value = as_parameter("delay", delay)
    if value.is_Symbol:
        return value
    if not value.is_number or not value.is_integer or value < 0:
        raise SceneError(f"the delay n = t_d/T must be a non-negative integer, got {value}")
    return sp.Integer(value)


def virtual_wall(K: Any, B: Any, T: Any, z: sp.Symbol = Z_SYM) -> sp.Expr:
    """The virtual wall ``H(z) = K + B(z-1)/(Tz)`` of Colgate & Schenkel and the HVE paper."""
    K, B, T = (sp.sympify(v) for v in (K, B, T))
    return K + B * (z - 1) / (T * z)


@dataclass(frozen=True, slots=True, weakref_slot=True)
class SingleUserScene:
    """A 1-DOF sampled-data haptic device on a discrete environment (HVE paper, Fig. 4).

    Parameters
    ----------
    b : expr
        Device damping (positive when numeric).
    T : expr
        Sampling period (positive when numeric).
    H : expr
        Real-rational environment ``H(z)``.
    approximation : {'forward', 'backward', 'tustin'}
        Approximation of ``X_h(z) = Z{v_h/s}`` (the three forms before eq. 17).
    delay : int or Symbol
        ``n = t_d/T``; a symbol keeps the delay symbolic (theta-forms).
    z_a : expr
        Operator's shortage of passivity (moved from ``b``, as in eq. 26).
    """

    b: sp.Expr
    T: sp.Expr
    H: sp.Expr
    approximation: str = "forward"
    delay: sp.Expr = field(default=sp.Integer(0))
    z_a: sp.Expr = field(default=sp.Integer(0))

    def __post_init__(self) -> None:
        for name in ("b", "T", "z_a"):
            object.__setattr__(self, name, as_parameter(name, getattr(self, name)))
        object.__setattr__(self, "delay", as_delay(self.delay))
        from hapticproof.expr import normalise_variables

        H = normalise_variables(self.H, "z", "H(z)")
        if not H.is_rational_function(Z_SYM):
            raise SceneError(f"H(z) must be a rational function of z, got {H}")
        object.__setattr__(self, "H", H)
        if self.approximation not in APPROXIMATIONS:
            raise SceneError(
                f"unknown approximation {self.approximation!r}; choose one of {', '.join(APPROXIMATIONS)}"
            )
        if self.T.is_number and not self.T > 0:
            raise SceneError(f"the sampling period T must be positive, got {self.T}")
        if self.b.is_number and self.b < 0:
            raise SceneError(f"the device damping b must be non-negative, got {self.b}")
        if self.z_a.is_number and self.z_a < 0:
            raise SceneError(f"the shortage of passivity z_a must be non-negative, got {self.z_a}")

    @classmethod
    def virtual_wall(
        cls,
        *,
        K: Any = None,
        B: Any = None,
        b: Any = None,
        T: Any = None,
        approximation: str = "forward",
        delay: Any = 0,
        z_a: Any = 0,
        t_d: Any = None,
    ) -> SingleUserScene:
        """The paper's scene: virtual wall ``K + B(z-1)/(Tz)``; unspecified parameters are
        the default symbols (:data:`SYMBOLS`). Give either ``delay`` (= n) or ``t_d`` (then
        ``t_d/T`` must be an integer).
        """
        K = SYMBOLS["K"] if K is None else as_parameter("K", K)
        B = SYMBOLS["B"] if B is None else as_parameter("B", B)
        b = SYMBOLS["b"] if b is None else b
        T = SYMBOLS["T"] if T is None else as_parameter("T", T)
        if T.is_number and not T > 0:
            raise SceneError(f"the sampling period T must be positive, got {T}")
        if t_d is not None:
            delay = delay_ratio(t_d, T)
        return cls(b=b, T=T, H=virtual_wall(K, B, T), approximation=approximation, delay=delay, z_a=z_a)

    @property
    def parameters(self) -> set[sp.Symbol]:
        """Free parameters (``z`` excluded)."""
        symbols = set()
        for value in (self.b, self.T, self.H, self.delay, self.z_a):
            symbols |= sp.sympify(value).free_symbols
        return {s for s in symbols if s != Z_SYM}

    @property
    def is_numeric(self) -> bool:
        """True when every parameter (including the delay) is a number."""
        return not self.parameters

    @property
    def has_delay(self) -> bool:
        return self.delay != 0

    def _repr_latex_(self) -> str:
        from hapticproof.latex import scene_latex

        return "$" + scene_latex(self) + "$"

    def with_values(self, values: Mapping[Any, Any] | None = None, **named: Any) -> SingleUserScene:
        """Substitute exact values for parameters (by symbol or by name).

        >>> SingleUserScene.virtual_wall().with_values(K=1, B=0, b="0.02", T="1/100").H
        1
        """
        mapping: dict[sp.Symbol, sp.Expr] = {}
        by_name = {s.name: s for s in self.parameters}
        items = list((values or {}).items()) + list(named.items())
        for key, value in items:
            symbol = by_name.get(key) if isinstance(key, str) else key
            if symbol is None:
                raise SceneError(f"unknown parameter {key!r}; the scene has {sorted(by_name)}")
            mapping[symbol] = as_parameter(str(key), value)
        if mapping.get(by_name.get("T")) is not None and mapping[by_name["T"]] <= 0:
            raise SceneError(f"the sampling period T must be positive, got {mapping[by_name['T']]}")
        return replace(
            self,
            b=self.b.subs(mapping),
            T=self.T.subs(mapping),
            H=sp.sympify(self.H).subs(mapping),
            delay=as_delay(sp.sympify(self.delay).subs(mapping)),
            z_a=self.z_a.subs(mapping),
        )


def delay_ratio(t_d: Any, T: Any) -> sp.Expr:
    """``n = t_d/T``, which the HVE paper assumes to be an integer.

    >>> delay_ratio("0.01", "0.001")
    10
    """
    t_d = as_parameter("t_d", t_d)
    T = as_parameter("T", T)
    ratio = sp.cancel(t_d / T)
    if ratio.is_number and not ratio.is_integer:
        raise SceneError(f"t_d/T must be an integer (the paper assumes n = t_d/T), got {ratio}")
    return ratio


# =============================================================================================
# One scene model: what every entry point takes (derive, boundary, scene files, the API)
# =============================================================================================

#: Systems a :class:`Scene` describes.
SYSTEMS = ("single-user", "multi-user", "teleoperator", "network")

#: Terminations that are words rather than impedances (boundary only).
TERMINATIONS = ("free", "clamped")

#: Controller presets of the teleoperator paper.
PRESETS = ("pd", "filtered-pd")

_GRAPHS = ("complete", "path", "star", "ring")

#: Names every system reserves, with their meaning (``m``... enter only stability boundaries).
RESERVED = {
    "single-user": {"b": "device damping", "T": "sampling period", "z_a": "operator's shortage of passivity",
                    "t_d": "delay time (n = t_d/T)", "m": "device mass (stability only)"},
    "multi-user": {"T": "sampling period", "m": "device masses (stability only)"},
    "teleoperator": {"b_m": "master damping", "b_s": "slave damping", "T": "sampling period",
                     "alpha": "position scaling", "m_m": "master mass (stability only)",
                     "m_s": "slave mass (stability only)", "m": "both masses (stability only)",
                     "b": "both dampings"},
    "network": {},
}


def _assumption_of(symbol: sp.Symbol) -> str | None:
    """The assumption word of a symbol built in Python (``None``: no assumption)."""
    for word, attr in (("positive", "is_positive"), ("negative", "is_negative"), ("nonnegative", "is_nonnegative"),
                       ("nonpositive", "is_nonpositive"), ("integer", "is_integer"), ("real", "is_real")):
        if getattr(symbol, attr):
            return word
    return None


def _param_value(name: str, value: Any, where: str) -> Any:
    """A parameter value, normalised: an exact rational, an assumption word or an expression."""
    from decimal import Decimal
    from fractions import Fraction

    from hapticproof.expr import ASSUMPTIONS, read_expression, read_number

    if isinstance(value, bool):
        raise SceneError(f"{where}{name}: {value!r} is not a number, an expression or an assumption")
    if isinstance(value, (int, Fraction)):
        return sp.Rational(value)
    if isinstance(value, float):
        # a Python float is read by its shortest decimal text: 0.001 is 1/1000, as typed
        return read_number(repr(value), f"{where}{name}")
    if isinstance(value, Decimal):
        return read_number(str(value), f"{where}{name}")
    if isinstance(value, sp.Basic):
        if value.is_Rational:
            return value
        if value.is_Float:
            return sp.Rational(value)
        return value
    if isinstance(value, str):
        text = value.strip()
        if text in ASSUMPTIONS:
            return text
        try:
            return read_number(text)
        except SceneError:
            pass
        except Exception:  # noqa: BLE001 - not a plain number: read it as an expression
            pass
        expr = read_expression(text, None, where=f"{where}{name}")
        if expr.is_Symbol:
            import difflib

            close = difflib.get_close_matches(text, list(ASSUMPTIONS), n=1, cutoff=0.75)
            if close:
                raise SceneError(f"{where}{name}: {text!r} is not an assumption; did you mean {close[0]!r}?")
        return expr if not expr.is_Rational else sp.Rational(expr)
    raise SceneError(f"{where}{name}: cannot use {value!r} (a number, an expression or one of "
                     f"{', '.join(ASSUMPTIONS)})")


@dataclass(frozen=True, slots=True)
class Scene:
    """A scene as a user describes it: the same fields in the Python API, a scene file (TOML), a
    paper file's ``[scenes.X]`` table and the command-line options of ``derive`` and
    ``boundary`` (``--environment`` is ``environment``, ``--param K=2`` an entry of ``params``).

    Parameters
    ----------
    system : {'single-user', 'multi-user', 'teleoperator', 'network'}
    approximation : {'forward', 'backward', 'tustin'}
        HVE model: the approximation of ``X_h = Z{v_h/s}`` (single- and multi-user).
    environment : str or expr, optional
        Single-user: the virtual environment ``H(z)`` (default: the wall ``K + B*(z-1)/(T*z)``),
        or ``H(s)`` with ``discretize``. Teleoperator: the slave's termination ``Z_e(s)``,
        ``'free'`` or ``'clamped'`` (stability only).
    controller : str or expr, optional
        Teleoperator: ``C(z)``, or ``C(s)`` with ``discretize``, or ``'pd'`` (eq. 33, default) /
        ``'filtered-pd'``. Single-user: a synonym of ``environment`` (the virtual environment is
        the haptic loop's controller).
    discretize : {'forward', 'backward', 'tustin', 'zoh', 'matched'}, optional
        How a continuous design in ``s`` becomes discrete (:mod:`hapticproof.discretize`).
    delay : int, 'n' or list of int
        ``n = t_d/T`` in samples; ``'n'`` keeps it symbolic; multi-user: one per user.
    users, graph, uniform : multi-user
        Number of users, the coupling graph (``complete``, ``path``, ``star``, ``ring`` or edges
        ``1-2,2-3``) and whether all users share one symbol per group (``b, K_0, B_0, K, B, z_a``).
    active : bool
        Include the operator's shortage of passivity ``z_a`` as a symbol.
    operator : str or expr, optional
        The operator's impedance ``Z_h(s)`` (stability; for passivity its shortage of
        passivity is ``z_a`` when ``z_a`` is not given), ``'free'`` or ``'clamped'``.
    params : mapping
        Name -> exact number (``0.9`` is 9/10), an expression of other parameters (``'K/2'``)
        or an assumption (``'positive'``, ``'nonnegative'``, ``'real'``, ``'integer'``...).
        Any names; unnamed parameters stay symbolic with the papers' signs (``b, K, T``
        positive, ``B, z_a`` non-negative) or ``real``.
    matrix, ports : network
        Impedance matrix ``Z(s)`` (rows of expressions in ``s``) and port sizes.

    Examples
    --------
    >>> scene = Scene("single-user", environment="K + B*(z-1)/(T*z) + M*(z-1)**2/(T**2*z**2)",
    ...               params={"K": 2, "B": "0.01", "M": "0.5", "T": "1/1000", "b": "0.9"})
    >>> scene.build().H
    2 + 10*(z - 1)/z + 500000*(z - 1)**2/z**2
    >>> Scene.from_toml(scene.to_toml()) == scene
    True
    """

    system: str
    approximation: str = "forward"
    environment: Any = None
    controller: Any = None
    discretize: str | None = None
    delay: Any = 0
    users: int | None = None
    graph: str = "complete"
    uniform: bool = False
    active: bool = False
    operator: Any = None
    params: Any = ()
    matrix: Any = None
    ports: Any = None

    def __post_init__(self) -> None:
        from hapticproof.discretize import METHODS

        where = ""
        set_ = lambda name, value: object.__setattr__(self, name, value)  # noqa: E731
        if self.system not in SYSTEMS:
            raise SceneError(f"unknown system {self.system!r}; choose one of {', '.join(SYSTEMS)}")
        if self.approximation not in APPROXIMATIONS:
            raise SceneError(f"unknown approximation {self.approximation!r}; choose one of {', '.join(APPROXIMATIONS)}")
        if self.discretize is not None and self.discretize not in METHODS:
            raise SceneError(f"unknown discretisation {self.discretize!r}; choose one of {', '.join(METHODS)}")
        for name in ("uniform", "active"):
            if not isinstance(getattr(self, name), bool):
                raise SceneError(f"{name} must be true or false, got {getattr(self, name)!r}")
        # parameters first: their assumptions decide the symbols of every expression
        items = self.params.items() if isinstance(self.params, Mapping) else tuple(self.params)
        params: dict[str, Any] = {}
        from hapticproof.expr import parameter_symbol

        for key, value in items:
            key = str(key).strip()
            parameter_symbol(key)                       # a valid name, not z or s
            if key in params:
                raise SceneError(f"parameter {key} given twice")
            params[key] = _param_value(key, value, where)
        system = self.system
        if system in ("single-user", "multi-user") and self.controller is not None:
            if self.environment is not None or system == "multi-user":
                raise SceneError(f"{system}: give the virtual environment once (environment; controller is its synonym)")
            set_("environment", self.controller)
            set_("controller", None)
        if system == "multi-user" and self.environment is not None:
            raise SceneError("multi-user scenes couple users by K_0i, B_0i, K_ij, B_ij (no custom environment)")
        if system != "teleoperator" and self.controller is not None:
            raise SceneError(f"{system}: no controller field (teleoperator only)")
        if system == "network":
            if self.matrix is None:
                raise SceneError("a network scene needs its impedance matrix (matrix)")
        elif self.matrix is not None or self.ports is not None:
            raise SceneError("matrix and ports describe a network scene")
        # expressions, read with the parameters' assumptions
        assumptions = {k: v for k, v in params.items() if isinstance(v, str)}
        continuous_env = system == "teleoperator" or self.discretize is not None
        if system == "teleoperator":
            set_("environment", self._expr(self.environment, "s", "environment", assumptions, words=TERMINATIONS))
            controller = self.controller
            if isinstance(controller, str) and controller.strip().lower() in PRESETS:
                if self.discretize is not None:
                    raise SceneError(f"the preset {controller!r} is already discrete; discretize applies to C(s)")
                set_("controller", controller.strip().lower())
            else:
                set_("controller", self._expr(controller, "s" if self.discretize else "z", "controller", assumptions))
        else:
            set_("environment", self._expr(self.environment, "s" if continuous_env else "z", "environment", assumptions))
        if self.discretize is not None and (self.environment if system != "teleoperator" else self.controller) in (None, "pd", "filtered-pd"):
            raise SceneError("discretize needs a continuous design in s (environment, or controller for a teleoperator)")
        set_("operator", self._expr(self.operator, "s", "operator", assumptions, words=TERMINATIONS))
        # the symbols of the expressions, normalised (a Python symbol with other assumptions
        # gets the scene's: equal scenes print, save and read back equal)
        for name in ("environment", "controller", "operator"):
            value = getattr(self, name)
            if isinstance(value, sp.Basic):
                set_(name, self._normalise(value, name, params))
        params = {k: (self._normalise(v, k, params) if isinstance(v, sp.Basic) and not v.is_Rational else v)
                  for k, v in params.items()}
        set_("params", tuple(sorted(params.items())))
        # delays, users, graph
        set_("delay", self._delay(self.delay))
        if system == "multi-user":
            users = 2 if self.users is None else self.users
            if isinstance(users, bool) or not isinstance(users, int) or users < 1:
                raise SceneError(f"users must be a positive integer, got {users!r}")
            set_("users", users)
            graph = str(self.graph).strip().lower().replace(" ", "")
            set_("graph", graph)
            _edges_of(graph, users)                     # validate
            if isinstance(self.delay, tuple) and len(self.delay) != users:
                raise SceneError(f"delay: {len(self.delay)} values for {users} users")
        else:
            if self.users is not None:
                raise SceneError("users applies to multi-user scenes")
            if self.graph != "complete" or self.uniform:
                raise SceneError("graph and uniform apply to multi-user scenes")
            if isinstance(self.delay, tuple):
                raise SceneError("one delay per user applies to multi-user scenes")
        if system == "network":
            rows = tuple(tuple(self._expr(e, "s", f"matrix[{i + 1}][{j + 1}]", assumptions) for j, e in enumerate(row))
                         for i, row in enumerate(self.matrix))
            if not rows or any(len(r) != len(rows) for r in rows):
                raise SceneError("the impedance matrix must be square and not empty")
            set_("matrix", tuple(tuple(self._normalise(e, "matrix", params) for e in row) for row in rows))
            if self.ports is not None:
                ports = tuple(int(p) for p in self.ports)
                if sum(ports) != len(rows) or any(p < 1 for p in ports):
                    raise SceneError(f"ports {list(ports)} must be positive sizes adding up to {len(rows)}")
                set_("ports", ports)

    # -- helpers of construction --------------------------------------------------------------
    @staticmethod
    def _expr(value: Any, variable: str, name: str, assumptions: Mapping[str, str],
              words: tuple[str, ...] = ()) -> Any:
        from hapticproof.expr import normalise_variables, read_expression

        if value is None:
            return None
        if isinstance(value, str):
            if value.strip().lower() in words:
                return value.strip().lower()
            return read_expression(value, variable, where=name, assumptions=assumptions)
        if isinstance(value, (int, float)) and not isinstance(value, bool):
            return _param_value(name, value, "")
        if isinstance(value, sp.Basic):
            return normalise_variables(value, variable, name)
        raise SceneError(f"{name}: expected an expression, got {value!r}")

    @staticmethod
    def _normalise(expr: sp.Expr, where: str, params: Mapping[str, Any]) -> sp.Expr:
        from hapticproof.expr import parameter_symbol

        mapping = {}
        for sym in expr.free_symbols:
            if sym.name in ("z", "s"):
                continue
            word = params.get(sym.name) if isinstance(params.get(sym.name), str) else None
            target = parameter_symbol(sym.name, word)
            if sym != target:
                # a parameter given a value is substituted whatever its symbol's assumption
                # (Scene.with_params on a scene whose B was declared "real", say)
                if word is None and sym.name not in params and _assumption_of(sym) not in (None, _assumption_of(target)):
                    raise SceneError(f"{where}: the symbol {sym.name} carries the assumption {_assumption_of(sym)!r}; "
                                     f"declare it in params ({sym.name} = {_assumption_of(sym)!r})")
                mapping[sym] = target
        return expr.xreplace(mapping) if mapping else expr

    @staticmethod
    def _delay(delay: Any) -> Any:
        if isinstance(delay, (list, tuple)):
            values = tuple(Scene._delay(d) for d in delay)
            if any(not isinstance(v, int) for v in values):
                raise SceneError("per-user delays must be integers")
            return values if len(set(values)) > 1 else values[0]
        if isinstance(delay, str) and delay.strip() == "n":
            return "n"
        if isinstance(delay, sp.Symbol) and delay.name == "n":
            return "n"
        if isinstance(delay, str):
            if "," in delay:
                return Scene._delay([d for d in delay.split(",")])
            try:
                delay = sp.Rational(delay.strip())
            except (TypeError, ValueError):
                raise SceneError(f"the delay n = t_d/T must be a non-negative integer or 'n', got {delay!r}") from None
        value = sp.sympify(delay)
        if not (value.is_Integer and value >= 0):
            raise SceneError(f"the delay n = t_d/T must be a non-negative integer or 'n', got {delay}")
        return int(value)

    # -- reading the fields -------------------------------------------------------------------
    @property
    def param_values(self) -> dict[str, Any]:
        """Parameters with a value (a number or an expression)."""
        return {k: v for k, v in self.params if not isinstance(v, str)}

    @property
    def assumptions(self) -> dict[str, str]:
        """Parameters with an assumption only (they stay symbolic)."""
        return {k: v for k, v in self.params if isinstance(v, str)}

    def symbol(self, name: str) -> sp.Symbol:
        """The symbol of ``name`` in this scene (its assumption, else the default)."""
        from hapticproof.expr import parameter_symbol

        return parameter_symbol(name, self.assumptions.get(name))

    def with_params(self, values: Mapping[str, Any] | None = None, **named: Any) -> Scene:
        """The scene with more (or changed) parameters; a value ``None`` removes one.

        >>> Scene("single-user").with_params(K=2, T="0.001").param_values
        {'K': 2, 'T': 1/1000}
        """
        params = dict(self.params)
        for key, value in list((values or {}).items()) + list(named.items()):
            if value is None:
                params.pop(key, None)
            else:
                params[key] = value
        return replace(self, params=params)

    def replace(self, **fields: Any) -> Scene:
        """The scene with other field values (validated again)."""
        return replace(self, **fields)

    # -- building the models ------------------------------------------------------------------
    def _substitution(self, extra: Mapping[str, Any] | None = None) -> dict[sp.Symbol, Any]:
        """Symbol -> value for every parameter with a value; expression values are substituted
        until only free symbols and numbers remain (a cycle is an error)."""
        values = dict(self.param_values)
        values.update(extra or {})
        mapping = {self.symbol(k): (v if isinstance(v, sp.Basic) else exact(v)) for k, v in values.items()}
        for _ in range(len(mapping) + 1):
            changed = False
            for sym, value in list(mapping.items()):
                if isinstance(value, sp.Basic) and value.free_symbols & set(mapping):
                    new = value.xreplace(mapping)
                    if new != value:
                        mapping[sym] = new
                        changed = True
            if not changed:
                return {k: (sp.cancel(v) if v.free_symbols else v) for k, v in mapping.items()}
        raise SceneError("the parameter expressions refer to each other in a cycle")

    def names(self) -> set[str]:
        """Every parameter name the scene's model uses (before values are substituted)."""
        model = self._model(substitute=False)
        if self.system == "network":
            free = set().union(*(e.free_symbols for e in model))
        else:
            free = set(model.parameters)
        for value in (self.environment, self.controller, self.operator):
            if isinstance(value, sp.Basic):
                free |= value.free_symbols
        names = {s.name for s in free} - {"z", "s", "n"}
        for value in self.param_values.values():
            if isinstance(value, sp.Basic):
                names |= {s.name for s in value.free_symbols}
        return names | (set(RESERVED[self.system]) & set(dict(self.params)))

    def check_names(self) -> None:
        """Every parameter given must be used by the scene (a misspelt name is an error).

        >>> Scene("single-user", params={"Q": 1}).check_names()
        Traceback (most recent call last):
        ...
        hapticproof.errors.SceneError: unknown parameter 'Q': this single-user scene has B, K, T, b
        """
        known = self.names() | set(RESERVED[self.system])
        if self.system == "multi-user":
            known |= {"b", "K_0", "B_0", "K", "B", "z_a"} | {f"m_{i + 1}" for i in range(self.users)}
        for name in dict(self.params):
            if name not in known:
                shown = sorted(self.names() - {name}) or ["no parameters"]
                raise SceneError(f"unknown parameter {name!r}: this {self.system} scene has {', '.join(shown)}")

    def build(self) -> Any:
        """The analysis model with the parameter values substituted: a :class:`SingleUserScene`,
        :class:`~hapticproof.multiuser.MultiUserScene`,
        :class:`~hapticproof.teleoperator.TeleoperatorScene` or, for a network, the impedance
        matrix (``sympy.Matrix``).

        >>> Scene("teleoperator", controller="K_p + K_i*T*z/(z - 1)").build().C
        K_i*T*z/(z - 1) + K_p
        """
        self.check_names()
        return self._model(substitute=True)

    def _model(self, substitute: bool) -> Any:
        mapping = self._substitution() if substitute else {}
        sub = (lambda e: sp.sympify(e).xreplace(mapping) if mapping else sp.sympify(e))  # noqa: E731
        if self.system == "single-user":
            return self._single_user(mapping, sub)
        if self.system == "multi-user":
            return self._multi_user(mapping)
        if self.system == "teleoperator":
            return self._teleoperator(mapping, sub)
        Z = sp.Matrix([[sub(e) for e in row] for row in self.matrix])
        return Z

    def environment_z(self) -> sp.Expr | None:
        """The discrete environment ``H(z)`` (single-user) or controller ``C(z)`` (teleoperator)
        before values are substituted: the continuous design discretised when asked."""
        from hapticproof.discretize import discretize

        design = self.environment if self.system == "single-user" else self.controller
        if self.system == "teleoperator" and design in (None, "pd", "filtered-pd"):
            from hapticproof.teleoperator import filtered_pd_controller, pd_controller

            K, B, T = self.symbol("K"), self.symbol("B"), self.symbol("T")
            return filtered_pd_controller(K, B, T, self.symbol("a")) if design == "filtered-pd" else pd_controller(K, B, T)
        if design is None:
            return virtual_wall(self.symbol("K"), self.symbol("B"), self.symbol("T"))
        if self.discretize is not None:
            return discretize(design, self.discretize, self.symbol("T"))
        return design

    def _z_a(self, mapping: Mapping[sp.Symbol, Any]) -> Any:
        z_a = self.symbol("z_a")
        if z_a in mapping:
            return mapping[z_a]
        if "z_a" in self.assumptions or self.active:
            return z_a
        if isinstance(self.operator, sp.Basic) and not (self.operator.xreplace(dict(mapping)).free_symbols - {Z_SYM} - {sp.Symbol("s")}):
            from hapticproof.sampled import Impedance
            from hapticproof.symbols import s as S_SYM

            num, den = sp.fraction(sp.cancel(sp.together(self.operator.xreplace(dict(mapping)))))
            imp = Impedance(tuple(sp.Poly(num, S_SYM).all_coeffs()), tuple(sp.Poly(den, S_SYM).all_coeffs()))
            return sp.nsimplify(imp.shortage_of_passivity())
        return sp.Integer(0)

    def _single_user(self, mapping, sub) -> SingleUserScene:
        T = sub(self.symbol("T"))
        b = sub(self.symbol("b"))
        H = sub(self.environment_z())
        delay: Any = N_SYM if self.delay == "n" else self.delay
        t_d = self.symbol("t_d")
        if t_d in mapping:
            if self.delay not in (0, "n"):
                raise SceneError("give the delay once: delay or t_d")
            delay = delay_ratio(mapping[t_d], T) if T.is_number else sp.cancel(mapping[t_d] / T)
        return SingleUserScene(b=b, T=T, H=H, approximation=self.approximation, delay=delay, z_a=self._z_a(mapping))

    def _multi_user(self, mapping) -> Any:
        from hapticproof.multiuser import UNIFORM_SYMBOLS, MultiUserScene

        edges = _edges_of(self.graph, self.users)
        active = self.active or "z_a" in dict(self.params)
        z_a = None if active else self._z_a(mapping)      # from the operator's impedance, or 0
        if self.delay == "n":
            raise SceneError("multi-user scenes need integer delays")
        if self.uniform:
            scene = MultiUserScene.uniform(self.users, delay=self.delay, edges=edges, approximation=self.approximation,
                                           z_a=UNIFORM_SYMBOLS["z_a"] if active else (z_a or 0))
        else:
            scene = MultiUserScene.symbolic(self.users, edges=edges, delays=self.delay, active=active,
                                            approximation=self.approximation)
            if z_a:
                scene = replace(scene, z_a=(z_a,) * self.users)
        if not mapping:
            return scene
        groups = {"b": "b", "K_0": "K0", "B_0": "B0", "z_a": "z_a", "K": "K", "B": "B"}
        values: dict[sp.Symbol, Any] = {}
        by_name = {s.name: s for s in scene.parameters}
        for sym, value in mapping.items():
            name = sym.name
            if name in by_name:
                values[by_name[name]] = value
            elif not self.uniform and name in groups:
                for member in getattr(scene, groups[name]):
                    if isinstance(member, sp.Symbol):
                        values.setdefault(member, value)
        # per-user names win over group names
        for sym, value in mapping.items():
            if sym.name in by_name:
                values[by_name[sym.name]] = value
        rename = {s: parameter_like(s, self) for s in scene.parameters}
        sub = lambda v: sp.sympify(v).xreplace(values).xreplace(rename)  # noqa: E731
        return replace(scene, b=tuple(map(sub, scene.b)), T=sub(scene.T), K0=tuple(map(sub, scene.K0)),
                       B0=tuple(map(sub, scene.B0)), K=tuple(map(sub, scene.K)), B=tuple(map(sub, scene.B)),
                       z_a=tuple(map(sub, scene.z_a)))

    def _teleoperator(self, mapping, sub) -> Any:
        from hapticproof.teleoperator import TeleoperatorScene

        if self.delay not in (0,):
            if self.delay == "n":
                raise SceneError("teleoperator scenes need an integer communication delay")
        values = {s.name: v for s, v in mapping.items()}
        mass = lambda name: values.get(name, values.get("m"))  # noqa: E731
        # "b" is both dampings: a value, or an assumption (one symbol b for both robots)
        both = self.symbol("b") if "b" in self.assumptions else None
        damping = lambda name: values.get(name, values.get("b", both if both is not None and name not in self.assumptions  # noqa: E731
                                                           else self.symbol(name)))
        alpha = values.get("alpha", self.symbol("alpha") if "alpha" in self.assumptions else 1)
        return TeleoperatorScene(mass("m_m"), mass("m_s"), damping("b_m"), damping("b_s"), sub(self.symbol("T")),
                                 sub(self.environment_z()), alpha)

    # -- files ------------------------------------------------------------------------------------
    @classmethod
    def from_table(cls, table: Mapping[str, Any], where: str = "", base: str | None = None,
                   assumptions: Mapping[str, str] | None = None) -> Scene:
        """A scene from a TOML table (a scene file, or a paper file's ``[scenes.X]``), see
        :mod:`hapticproof.scenefile`; ``assumptions`` (name -> word) come from outside, e.g. a
        paper's ``[symbols]``."""
        from hapticproof.scenefile import scene_from_table

        return scene_from_table(table, where=where, base=base, assumptions=assumptions)

    @classmethod
    def from_toml(cls, text: str, where: str = "scene") -> Scene:
        """A scene from the text of a scene file."""
        from hapticproof.scenefile import loads

        return loads(text, where)

    @classmethod
    def read(cls, path: Any) -> Scene:
        """A scene from a scene file (``.toml``)."""
        from hapticproof.scenefile import read_scene

        return read_scene(path)

    def to_toml(self) -> str:
        """The scene file text; :meth:`from_toml` reads it back equal."""
        from hapticproof.scenefile import dumps

        return dumps(self)

    def write(self, path: Any) -> Any:
        """Write the scene file (``-`` is standard output)."""
        from hapticproof.scenefile import write_scene

        return write_scene(self, path)


def parameter_like(symbol: sp.Symbol, scene: Scene) -> sp.Symbol:
    """A model symbol (``b_1``, ``K_12``...) with the assumption the scene gives its name."""
    word = scene.assumptions.get(symbol.name)
    if word is None:
        return symbol
    from hapticproof.expr import parameter_symbol

    return parameter_symbol(symbol.name, word)


def _edges_of(graph: str, m: int) -> tuple[tuple[int, int], ...] | None:
    """The coupling graph's edges (0-based) from ``complete``, ``path``, ``star``, ``ring`` or
    ``1-2,2-3`` (``None``: complete)."""
    if graph == "complete":
        return None
    if graph == "path":
        return tuple((i, i + 1) for i in range(m - 1))
    if graph == "star":
        return tuple((0, i) for i in range(1, m))
    if graph == "ring":
        return tuple(sorted({tuple(sorted((i, (i + 1) % m))) for i in range(m)} - {(0, 0)})) if m > 1 else ()
    edges = []
    for item in graph.split(","):
        try:
            i, j = (int(v) for v in item.split("-"))
        except ValueError:
            raise SceneError(f"graph: expected complete, path, star, ring or edges like 1-2,2-3; got {item!r}") from None
        if not (1 <= i <= m and 1 <= j <= m) or i == j:
            raise SceneError(f"graph: edge {item!r} needs two different users in 1..{m}")
        edges.append((i - 1, j - 1))
    return tuple(edges)
