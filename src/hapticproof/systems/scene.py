r"""Scenes: frozen descriptions of *what* to analyse, as a user writes them -- in Python, on the
command line, in a scene file (TOML) or in a paper file's ``[scenes.X]`` table.

:class:`Scene` names the system and its fields; :meth:`Scene.build` gives the analysis model
(:class:`~hapticproof.systems.singleuser.SingleUserScene`, :class:`~hapticproof.systems.multiuser.MultiUserScene`,
:class:`~hapticproof.systems.teleoperator.TeleoperatorScene` or an impedance matrix).

Scene files
-----------
``tomllib`` and written by a small writer of our own.

A scene file holds the fields of :class:`~hapticproof.systems.scene.Scene` at the top level -- the
same names as the command-line options of ``hapticproof derive`` and ``boundary`` -- and the
parameters in a ``[params]`` table (``--param NAME=VALUE``). A paper file's ``[scenes.X]``
tables have exactly the same fields (:func:`scene_from_table`).

.. code-block:: toml

    # a virtual wall with a virtual mass, on a 1 kHz haptic device
    system = "single-user"          # single-user | multi-user | teleoperator | network
    approximation = "forward"       # forward | backward | tustin (the HVE model of X_h)
    environment = "K + B*(z - 1)/(T*z) + M*(z - 1)**2/(T**2*z**2)"
    delay = 0                       # n = t_d/T; "n" keeps it symbolic

    [params]
    K = 2                           # numbers are exact: 0.001 is 1/1000
    B = 0.01
    M = "positive"                  # an assumption: M stays a symbol
    T = 0.001
    b = "9/10"

Numbers are exact (TOML floats are read by their decimal text, never as binary floats);
expressions are read by :func:`hapticproof.core.expr.read_expression`. A mistake is one line naming
the file, the line and the field (:class:`SceneFileError`).

>>> scene = loads('system = "single-user"\nenvironment = "K + B*(z-1)/(T*z)"\n[params]\nT = 0.001\n')
>>> scene.param_values
{'T': 1/1000}
>>> loads('system = "single-user"\nenviroment = "K"\n', "wall.toml")
Traceback (most recent call last):
...
hapticproof.core.errors.SceneFileError: wall.toml:2: unknown field 'enviroment' (fields: system, approximation, environment, controller, discretize, delay, users, graph, uniform, active, operator, matrix, ports, roles, params)
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass, replace
from typing import Any

import sympy as sp

from hapticproof.core.errors import SceneError
from hapticproof.core.evidence import exact
from hapticproof.core.symbols import n as N_SYM
from hapticproof.core.symbols import z as Z_SYM
from hapticproof.systems.singleuser import APPROXIMATIONS, SingleUserScene, delay_ratio, virtual_wall
from hapticproof.systems.matrixfile import read_matrix
from hapticproof.systems.values import check_declared, check_positive_roles, param_value, refuse_cycles, refuse_toolkit_names
import json
import re
import sys
from decimal import Decimal
from pathlib import Path
from hapticproof.core.errors import HapticproofError, SceneFileError
from hapticproof.core.expr import write_expression
from hapticproof.core.tomltext import line_of, read_toml as _read_toml

__all__ = ["SYSTEMS", "Scene", "FIELDS", "SceneFileError", "loads", "dumps", "read_scene", "write_scene", "scene_from_table",            "read_matrix", "toml_value", "line_of",
           "read_toml"]


#: Systems a :class:`Scene` describes.
SYSTEMS = ("single-user", "multi-user", "teleoperator", "network")

#: Terminations that are words rather than impedances (boundary only).
TERMINATIONS = ("free", "clamped")

#: Controller presets of the teleoperator paper.
PRESETS = ("pd", "filtered-pd")

_GRAPHS = ("complete", "path", "star", "ring")


def reserved_names(system: str, roles: tuple = (), users: int | None = None) -> dict[str, str]:
    """The names a scene of ``system`` gives a meaning: its roles' names
    (:mod:`hapticproof.systems.roles`) and the fixed names (``z_a``, ``t_d``, ``alpha``), with
    what they mean.

    >>> reserved_names("single-user", (("period", "Ts"),))["Ts"]
    'the sampling period'
    """
    from hapticproof.systems.roles import FIXED_NAMES, ROLES, role_names

    out = {name: ROLES[system][field].meaning for name, field in role_names(system, roles, users).items()}
    out.update(FIXED_NAMES[system])
    return out


def _assumption_of(symbol: sp.Symbol) -> str | None:
    """The assumption word of a symbol built in Python (``None``: no assumption)."""
    for word, attr in (("positive", "is_positive"), ("negative", "is_negative"), ("nonnegative", "is_nonnegative"),
                       ("nonpositive", "is_nonpositive"), ("integer", "is_integer"), ("real", "is_real")):
        if getattr(symbol, attr):
            return word
    return None


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
        ``'free'`` or ``'clamped'`` (stability only). A python-control or SymPy system is read
        exactly (:mod:`hapticproof.systems.lti`; floats by their decimal text) and its ``dt`` is
        ``T``; so for ``controller`` and ``operator``.
    controller : str or expr, optional
        Teleoperator: ``C(z)``, or ``C(s)`` with ``discretize``, or ``'pd'`` (eq. 33, default) /
        ``'filtered-pd'``. Single-user: a synonym of ``environment`` (the virtual environment is
        the haptic loop's controller).
    discretize : {'forward', 'backward', 'tustin', 'zoh', 'matched'}, optional
        How a continuous design in ``s`` becomes discrete (:mod:`hapticproof.systems.discretize`).
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
    roles : mapping
        The names of the parameters the system gives a meaning (:mod:`hapticproof.systems.roles`):
        ``device_damping`` (default ``b``), ``period`` (``T``), ``mass`` (``m``); teleoperator
        ``master_damping``/``slave_damping`` (``b_m``/``b_s``) and ``master_mass``/``slave_mass``
        (``m_m``/``m_s``). ``{"period": "Ts"}`` makes ``Ts`` the sampling period everywhere.

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
    roles: Any = ()

    def __post_init__(self) -> None:
        from hapticproof.systems.discretize import METHODS

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
        from hapticproof.systems.roles import check_members, read_roles

        set_("roles", read_roles(self.system, self.roles))
        if self.system == "multi-user":
            users = 2 if self.users is None else self.users
            if isinstance(users, bool) or not isinstance(users, int) or users < 1:
                raise SceneError(f"users must be a positive integer, got {users!r}")
            from hapticproof.core.limits import check

            check("users", users, "users")
            set_("users", users)
            check_members(self.roles, users, self.uniform)
        # parameters first: their assumptions decide the symbols of every expression
        items = self.params.items() if isinstance(self.params, Mapping) else tuple(self.params)
        params: dict[str, Any] = {}
        from hapticproof.core.expr import parameter_symbol

        for key, value in items:
            key = str(key).strip()
            parameter_symbol(key)                       # a valid name, not z or s
            if key in params:
                raise SceneError(f"parameter {key} given twice")
            params[key] = param_value(key, value, where)
        self._read_systems(params)
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
        # expressions, read with the parameters' assumptions (a role's parameter is positive)
        assumptions = {**self._role_words(), **{k: v for k, v in params.items() if isinstance(v, str)}}
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
                set_(name, self._normalise(value, name, params, assumptions))
        params = {k: (self._normalise(v, k, params, assumptions) if isinstance(v, sp.Basic) and not v.is_Rational else v)
                  for k, v in params.items()}
        refuse_cycles(params)                        # and chained definitions bounded before any substitution
        set_("params", tuple(sorted(params.items())))
        # delays, users, graph
        set_("delay", self._delay(self.delay))
        if system == "multi-user":
            users = self.users
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
            set_("matrix", tuple(tuple(self._normalise(e, "matrix", params, assumptions) for e in row) for row in rows))
            if self.ports is not None:
                items = self.ports if isinstance(self.ports, (list, tuple)) else [self.ports]
                if not all((isinstance(p, int) and not isinstance(p, bool))
                           or (isinstance(p, str) and p.strip().isascii() and p.strip().isdigit()) for p in items):
                    raise SceneError(f"ports must be port sizes (positive integers such as 3,3), got {self.ports!r}")
                ports = tuple(int(p) for p in items)
                if sum(ports) != len(rows) or any(p < 1 for p in ports):
                    raise SceneError(f"ports {list(ports)} must be positive sizes adding up to {len(rows)}")
                set_("ports", ports)
        refuse_toolkit_names(self)                   # n, c, ...: the toolkit's own quantities

    # -- helpers of construction --------------------------------------------------------------
    def _read_systems(self, params: dict[str, Any]) -> None:
        """A python-control or SymPy system as environment, controller or operator becomes its
        exact expression (:func:`hapticproof.systems.lti.expression_of`); a sampling period it
        carries is the scene's ``T`` (given as well, they must agree)."""
        from hapticproof.systems.lti import expression_of, is_lti_object

        for name in ("environment", "controller", "operator"):
            value = getattr(self, name)
            if not is_lti_object(value):
                continue
            expr, dt = expression_of(value)
            object.__setattr__(self, name, expr)
            if dt is None:
                continue
            period = sp.Rational(dt.numerator, dt.denominator)
            if "T" in params and params["T"] != period:
                raise SceneError(f"{name}: the system's sampling period dt = {period} differs from T = {params['T']}")
            params["T"] = period

    @staticmethod
    def _expr(value: Any, variable: str, name: str, assumptions: Mapping[str, str],
              words: tuple[str, ...] = ()) -> Any:
        from hapticproof.core.expr import normalise_variables, read_expression

        if value is None:
            return None
        if isinstance(value, str):
            if value.strip().lower() in words:
                return value.strip().lower()
            return read_expression(value, variable, where=name, assumptions=assumptions)
        if isinstance(value, (int, float)) and not isinstance(value, bool):
            return param_value(name, value, "")
        if isinstance(value, sp.Basic):
            return normalise_variables(value, variable, name)
        raise SceneError(f"{name}: expected an expression, got {value!r}")

    @staticmethod
    def _normalise(expr: sp.Expr, where: str, params: Mapping[str, Any], words: Mapping[str, str]) -> sp.Expr:
        from hapticproof.core.expr import parameter_symbol

        mapping = {}
        for sym in expr.free_symbols:
            if sym.name in ("z", "s"):
                continue
            word = words.get(sym.name)
            target = parameter_symbol(sym.name, word)
            if sym != target:
                # a parameter given a value is substituted whatever its symbol's assumption
                # (Scene.with_params on a scene whose B was declared "real", say)
                if sym.name not in params and _assumption_of(sym) not in (None, _assumption_of(target)):
                    raise SceneError(f"{where}: the symbol {sym.name} carries the assumption {_assumption_of(sym)!r}; "
                                     f"declare it in params ({sym.name} = {_assumption_of(sym)!r})")
                mapping[sym] = target
        return expr.xreplace(mapping) if mapping else expr

    @staticmethod
    def _delay(delay: Any) -> Any:
        from hapticproof.core.limits import check

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
            text = delay.strip()
            # digits 0-9 only (int() reads Arabic-Indic digits too); "1/0", "2.5", "1e9" are refused
            if not (text.isascii() and text.isdigit()):
                raise SceneError(f"the delay n = t_d/T must be a non-negative integer or 'n', got {delay!r}")
            if len(text) > 30:
                check("delay", 10**30, "delay")
            delay = int(text)
        if isinstance(delay, bool) or not isinstance(delay, (int, sp.Basic)):
            raise SceneError(f"the delay n = t_d/T must be a non-negative integer or 'n', got {delay!r}")
        value = sp.sympify(delay)
        if not (value.is_Integer and value >= 0):
            raise SceneError(f"the delay n = t_d/T must be a non-negative integer or 'n', got {delay}")
        check("delay", int(value), "delay")
        return int(value)

    # -- roles ---------------------------------------------------------------------------------
    def role(self, field: str) -> str | None:
        """The parameter name of a role (:mod:`hapticproof.systems.roles`): ``'T'`` for
        ``'period'`` unless the scene names it (``None``: a multi-user role named per user only).

        >>> Scene("single-user", roles={"period": "Ts"}).role("period")
        'Ts'
        """
        from hapticproof.systems.roles import ROLES, role_name

        if field not in ROLES[self.system]:
            raise SceneError(f"a {self.system} scene has no role {field!r}")
        return role_name(self.system, self.roles, field)

    def members(self, field: str) -> tuple[str, ...]:
        """The per-user names of a multi-user role (``b_1``, ..., ``b_m`` by default)."""
        from hapticproof.systems.roles import member_names

        return member_names(self.system, self.roles, field, self.users or 1)

    def reserved(self) -> dict[str, str]:
        """The names this scene gives a meaning (its roles' names, ``z_a``...) -> the meaning."""
        return reserved_names(self.system, self.roles, self.users)

    def _role_words(self) -> Mapping[str, str]:
        """Name -> the assumption of a role's parameter (positive), for every name a role gives."""
        from hapticproof.systems.roles import role_words

        return role_words(self.system, self.roles, self.users)

    def role_symbol(self, field: str) -> sp.Symbol:
        """The symbol of a role's parameter (``T`` or the scene's own name for it)."""
        return self.symbol(self.role(field))

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
        from hapticproof.core.expr import parameter_symbol

        return parameter_symbol(name, self.assumptions.get(name) or self._role_words().get(name))

    def resolved_values(self) -> dict[str, Any]:
        """Name -> value of every parameter with a value, expressions of others resolved.

        >>> Scene("single-user", params={"Kw": 4, "K": "Kw/2"}).resolved_values()["K"]
        2
        """
        return {sym.name: value for sym, value in self._substitution().items()}

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
                out = {k: (sp.cancel(v) if v.free_symbols else v) for k, v in mapping.items()}
                for sym, value in out.items():
                    if value.has(sp.zoo, sp.nan, sp.oo, -sp.oo):
                        given = dict(values).get(sym.name)
                        raise SceneError(f"parameter {sym.name!r}: {sp.sstr(given)} divides by zero at the scene's values")
                check_positive_roles(self, out)
                return out
        raise SceneError("the parameter expressions refer to each other in a cycle")

    def model_names(self) -> set[str]:
        """The parameter names of the scene's model and expressions (before values are substituted)."""
        model = self._model(substitute=False)
        if self.system == "network":
            free = set().union(*(e.free_symbols for e in model))
        else:
            free = set(model.parameters)
        for value in (self.environment, self.controller, self.operator):
            if isinstance(value, sp.Basic):
                free |= value.free_symbols
        return {s.name for s in free} - {"z", "s", "n"}

    def names(self) -> set[str]:
        """Every parameter name the scene uses: its model's, and those of its parameters' values."""
        names = self.model_names()
        for value in self.param_values.values():
            if isinstance(value, sp.Basic):
                names |= {s.name for s in value.free_symbols}
        return names | (set(self.reserved()) & set(dict(self.params)))

    def check_names(self) -> None:
        """Every parameter given must be used by the scene (a misspelt name is an error).

        >>> Scene("single-user", params={"Q": 1}).check_names()
        Traceback (most recent call last):
        ...
        hapticproof.core.errors.SceneError: unknown parameter 'Q': this single-user scene has B, K, T, b (and m, t_d, z_a)
        """
        from hapticproof.systems.roles import ROLES, role_names

        if self.system in ("single-user", "teleoperator"):
            # a role's name is not also a parameter of the design (the device damping named K in
            # the wall K + B(z-1)/(Tz)): one name, one meaning; the period belongs in both
            design = self.environment_z()
            used = {s.name for s in sp.sympify(design).free_symbols} if design is not None else set()
            builtin = self.environment if self.system == "single-user" else self.controller
            if builtin in (None, "pd", "filtered-pd"):
                # the built-in wall or PD controller: its stiffness and damping (and filter) are
                # its own, so not even the period may take their names
                own = {self.symbol(key).name for key in ("K", "B", "a") if key != "a" or builtin == "filtered-pd"}
                for name, field in role_names(self.system, self.roles, self.users).items():
                    if field == "period" and name in own:
                        raise SceneError(f"roles: period = {name!r}, but {name} is already a parameter of the built-in "
                                         f"{'wall K + B(z-1)/(Tz)' if self.system == 'single-user' else 'controller'}: "
                                         "one name, one meaning (give the role another name)")
            for name, field in role_names(self.system, self.roles, self.users).items():
                if name in used and field != "period":
                    what = "environment H(z)" if self.system == "single-user" else "controller C(z)"
                    raise SceneError(f"roles: {field} = {name!r}, but {name} is already a parameter of the {what}: "
                                     "one name, one meaning (give the role another name)")
        model_names = self.model_names()
        names = self.names()
        known = names | set(self.reserved())
        if self.system == "multi-user":
            known |= {"K_0", "B_0", "K", "B", "z_a"}
        # a value is a number or an expression of declared names: the model's, the parameters'
        # (with a value or an assumption) and the roles'; anything else is a typo, not a new symbol
        declared = (model_names | set(dict(self.params)) | set(self.reserved())
                    | ({"K_0", "B_0", "K", "B", "z_a"} if self.system == "multi-user" else set()))
        check_declared(self.param_values, declared, model_names | set(dict(self.params)))
        for name in dict(self.params):
            if name not in known:
                shown = sorted(names - {name}) or ["no parameters"]
                renamed = [(field, role) for field, role in ROLES[self.system].items()
                           if role.default == name and self.role(field) != name]
                hint = ""
                if renamed:
                    field, role = renamed[0]
                    now = self.role(field) or ", ".join(self.members(field))
                    hint = f" ({role.meaning} is {now} in this scene: roles {field} = {now!r})"
                others = sorted(set(self.reserved()) - names - {name})
                also = f" (and {', '.join(others)})" if others else ""
                raise SceneError(f"unknown parameter {name!r}: this {self.system} scene has {', '.join(shown)}{also}{hint}")

    def build(self) -> Any:
        """The analysis model with the parameter values substituted: a :class:`SingleUserScene`,
        :class:`~hapticproof.systems.multiuser.MultiUserScene`,
        :class:`~hapticproof.systems.teleoperator.TeleoperatorScene` or, for a network, the impedance
        matrix (``sympy.Matrix``).

        >>> Scene("teleoperator", controller="K_p + K_i*T*z/(z - 1)").build().C
        K_i*T*z/(z - 1) + K_p
        """
        from hapticproof.systems.naming import with_naming

        self.check_names()
        return with_naming(self, self._model(substitute=True))

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
        from hapticproof.systems.discretize import discretize

        design = self.environment if self.system == "single-user" else self.controller
        if self.system == "teleoperator" and design in (None, "pd", "filtered-pd"):
            from hapticproof.systems.teleoperator import filtered_pd_controller, pd_controller

            K, B, T = self.symbol("K"), self.symbol("B"), self.role_symbol("period")
            return filtered_pd_controller(K, B, T, self.symbol("a")) if design == "filtered-pd" else pd_controller(K, B, T)
        if design is None:
            return virtual_wall(self.symbol("K"), self.symbol("B"), self.role_symbol("period"))
        if self.discretize is not None:
            return discretize(design, self.discretize, self.role_symbol("period"))
        return design

    def _z_a(self, mapping: Mapping[sp.Symbol, Any]) -> Any:
        z_a = self.symbol("z_a")
        if z_a in mapping:
            return mapping[z_a]
        if "z_a" in self.assumptions or self.active:
            return z_a
        if isinstance(self.operator, sp.Basic) and not (self.operator.xreplace(dict(mapping)).free_symbols - {Z_SYM} - {sp.Symbol("s")}):
            from hapticproof.systems.impedance import Impedance
            from hapticproof.core.symbols import s as S_SYM

            num, den = sp.fraction(sp.cancel(sp.together(self.operator.xreplace(dict(mapping)))))
            imp = Impedance(tuple(sp.Poly(num, S_SYM).all_coeffs()), tuple(sp.Poly(den, S_SYM).all_coeffs()))
            return sp.nsimplify(imp.shortage_of_passivity())
        return sp.Integer(0)

    def _single_user(self, mapping, sub) -> SingleUserScene:
        T = sub(self.role_symbol("period"))
        b = sub(self.role_symbol("device_damping"))
        H = sub(self.environment_z())
        delay: Any = N_SYM if self.delay == "n" else self.delay
        t_d = self.symbol("t_d")
        if t_d in mapping:
            if self.delay not in (0, "n"):
                raise SceneError("give the delay once: delay or t_d")
            delay = delay_ratio(mapping[t_d], T) if T.is_number else sp.cancel(mapping[t_d] / T)
        return SingleUserScene(b=b, T=T, H=H, approximation=self.approximation, delay=delay, z_a=self._z_a(mapping))

    def _multi_user(self, mapping) -> Any:
        from hapticproof.systems.multiuser import UNIFORM_SYMBOLS, MultiUserScene, map_values

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
        # the roles' names: the period and the dampings (a group name, or one per user)
        group = self.role("device_damping")
        dampings = ((self.symbol(group),) * self.users if self.uniform else
                    tuple(self.symbol(name) for name in self.members("device_damping")))
        scene = replace(scene, T=self.role_symbol("period"), b=dampings)
        if not mapping:
            return scene
        groups = {"K_0": "K0", "B_0": "B0", "z_a": "z_a", "K": "K", "B": "B"}
        if group is not None:
            groups[group] = "b"
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
        each = lambda vals: map_values(sub, vals)  # noqa: E731 - a uniform scene repeats one value per edge
        return replace(scene, b=each(scene.b), T=sub(scene.T), K0=each(scene.K0), B0=each(scene.B0), K=each(scene.K),
                       B=each(scene.B), z_a=each(scene.z_a))

    def _teleoperator(self, mapping, sub) -> Any:
        from hapticproof.systems.teleoperator import TeleoperatorScene

        if self.delay not in (0,):
            if self.delay == "n":
                raise SceneError("teleoperator scenes need an integer communication delay")
        values = {s.name: v for s, v in mapping.items()}
        role = self.role
        mass = lambda field: values.get(role(field), values.get(role("mass")))  # noqa: E731
        # the device damping is both dampings: a value, or an assumption (one symbol for both robots)
        both_name = role("device_damping")
        both = self.symbol(both_name) if both_name in self.assumptions else None
        damping = lambda field: values.get(role(field), values.get(both_name, both if both is not None and role(field) not in self.assumptions  # noqa: E731
                                                                   else self.symbol(role(field))))
        alpha = values.get("alpha", self.symbol("alpha") if "alpha" in self.assumptions else 1)
        return TeleoperatorScene(mass("master_mass"), mass("slave_mass"), damping("master_damping"),
                                 damping("slave_damping"), sub(self.role_symbol("period")), sub(self.environment_z()), alpha)

    # -- files ------------------------------------------------------------------------------------
    @classmethod
    def from_table(cls, table: Mapping[str, Any], where: str = "", base: str | None = None,
                   assumptions: Mapping[str, str] | None = None) -> Scene:
        """A scene from a TOML table (a scene file, or a paper file's ``[scenes.X]``), see
        :mod:`hapticproof.systems.scene`; ``assumptions`` (name -> word) come from outside, e.g. a
        paper's ``[symbols]``."""

        return scene_from_table(table, where=where, base=base, assumptions=assumptions)

    @classmethod
    def from_toml(cls, text: str, where: str = "scene") -> Scene:
        """A scene from the text of a scene file."""

        return loads(text, where)

    @classmethod
    def read(cls, path: Any) -> Scene:
        """A scene from a scene file (``.toml``)."""

        return read_scene(path)

    def to_toml(self) -> str:
        """The scene file text; :meth:`from_toml` reads it back equal."""

        return dumps(self)

    def write(self, path: Any) -> Any:
        """Write the scene file (``-`` is standard output)."""

        return write_scene(self, path)


def parameter_like(symbol: sp.Symbol, scene: Scene) -> sp.Symbol:
    """A model symbol (``b_1``, ``K_12``...) with the assumption the scene gives its name."""
    word = scene.assumptions.get(symbol.name)
    if word is None:
        return symbol
    from hapticproof.core.expr import parameter_symbol

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


# =============================================================================================
# Scene files: TOML in, TOML out
# =============================================================================================


#: The fields of a scene table, in the order they are written.
FIELDS = ("system", "approximation", "environment", "controller", "discretize", "delay", "users", "graph",
          "uniform", "active", "operator", "matrix", "ports", "roles", "params")

_TYPES: dict[str, tuple[type, ...]] = {
    "system": (str,), "approximation": (str,), "environment": (str, int, Decimal), "controller": (str, int, Decimal),
    "discretize": (str,), "delay": (int, str, list), "users": (int,), "graph": (str,), "uniform": (bool,),
    "active": (bool,), "operator": (str, int, Decimal), "matrix": (list, str), "ports": (list, str), "roles": (dict,),
    "params": (dict,),
}


def _where(source: str, text: str | None, key: str, table: str = "") -> str:
    line = line_of(text, key, table)
    return f"{source}:{line}" if line is not None else source


def _plain(value: Any) -> Any:
    """TOML values as the scene expects them (decimals as exact text)."""
    if isinstance(value, Decimal):
        if not value.is_finite():
            raise ValueError(f"{value} is not a number")
        return str(value)
    if isinstance(value, list):
        return [_plain(v) for v in value]
    if isinstance(value, dict):
        return {k: _plain(v) for k, v in value.items()}
    return value


def scene_from_table(table: Mapping[str, Any], where: str = "scene", base: str | Path | None = None,
                     assumptions: Mapping[str, str] | None = None, text: str | None = None, prefix: str = ""):
    """A :class:`~hapticproof.systems.scene.Scene` from a table of fields (a parsed scene file, or a
    paper file's ``[scenes.X]``). ``base`` is the folder of the file (default: the current
    folder): a ``matrix`` file is read there only (relative, no ``..``, a regular file); ``assumptions``
    adds parameter assumptions from outside (a paper's ``[symbols]``), the table's own
    ``[params]`` winning; ``text`` and ``prefix`` (the table's TOML path, ``'scenes.wall'``)
    let errors name the line.

    >>> scene_from_table({"system": "teleoperator", "controller": "K_p + K_d*(z - 1)/(T*z)"}).controller
    K_d*(z - 1)/(T*z) + K_p
    """

    if not isinstance(table, Mapping):
        raise SceneFileError(f"{where}: a scene is a table of fields")
    fields: dict[str, Any] = {}
    for key, value in table.items():
        if key not in FIELDS:
            raise SceneFileError(f"{_where(where, text, key, prefix)}: unknown field {key!r} (fields: {', '.join(FIELDS)})")
        if not isinstance(value, _TYPES[key]) or (isinstance(value, bool) and bool not in _TYPES[key]):
            kinds = " or ".join(t.__name__.replace("Decimal", "number").replace("dict", "table").replace("str", "text")
                                .replace("int", "integer").replace("list", "list") for t in _TYPES[key])
            raise SceneFileError(f"{_where(where, text, key, prefix)}: field {key!r} must be {kinds}, got {_shown(value)}")
        if key in ("delay", "ports") and isinstance(value, list):
            allowed = (int,) if key == "ports" else (int, str)
            bad = [v for v in value if isinstance(v, bool) or not isinstance(v, allowed)]
            if bad:
                what = "integers (port sizes)" if key == "ports" else "integers (one delay per user)"
                raise SceneFileError(f"{_where(where, text, key, prefix)}: field {key!r} must be a list of {what}, "
                                     f"got {_shown(bad[0])} in it")
        if key == "params":       # each value is checked below, with its own line
            fields[key] = dict(value)
            continue
        try:
            fields[key] = _plain(value)
        except ValueError as err:
            raise SceneFileError(f"{_where(where, text, key, prefix)}: field {key!r}: {err}") from None
    if "system" not in fields:
        raise SceneFileError(f"{where}: missing field 'system' (single-user, multi-user, teleoperator or network)")
    params = dict(fields.pop("params", {}))
    for name, value in (assumptions or {}).items():
        params.setdefault(name, value)
    for name, value in params.items():
        here = _where(where, text, name, (prefix + '.params').lstrip('.'))
        if isinstance(value, (list, dict)):
            raise SceneFileError(f"{here}: parameter {name!r} must be a number, an expression or an assumption")
        # a non-finite TOML float (nan, inf) goes on as its text: systems.values refuses it
        params[name] = str(value) if isinstance(value, Decimal) and not value.is_finite() else _plain(value)
    if isinstance(fields.get("matrix"), str):
        from hapticproof.core.files import file_in_folder

        path = file_in_folder(base, fields["matrix"], f"{_where(where, text, 'matrix', prefix)}: field 'matrix'",
                              owner=where if base is not None else None)
        rows, ports = read_matrix(path, named_in=where)
        fields["matrix"] = rows
        if ports and "ports" not in fields:
            fields["ports"] = list(ports)
    if isinstance(fields.get("ports"), str):
        fields["ports"] = [p for p in fields["ports"].split(",")]
    try:
        return Scene(**fields, params=params)
    except HapticproofError as err:
        message = str(err)
        if message.startswith("roles:") and isinstance(fields.get("roles"), Mapping):
            table_name = (prefix + ".roles").lstrip(".")
            named = [k for k, v in fields["roles"].items()
                     if message.startswith(f"roles: {k}:") or f"'{k}'" in message or f"'{v}'" in message] or [None]
            line = line_of(text, named[0], table_name) if named[0] else None
            line = line or line_of(text, "roles", prefix) or _table_header(text, table_name)
            raise SceneFileError(f"{where}:{line}: {message}" if line else f"{where}: {message}") from None
        else:
            key = _field_in(message, list(fields) + list(params))
            table_name = (prefix + ".params").lstrip(".") if key in params else prefix
        raise SceneFileError(f"{_where(where, text, key, table_name) if key else where}: {message}") from None


def _table_header(text: str | None, table: str) -> int | None:
    """The line of the header ``[table]`` in a TOML text."""
    for number, line in enumerate((text or "").splitlines(), 1):
        if re.match(r"\s*\[\s*" + re.escape(table) + r"\s*\]", line):
            return number
    return None


def _shown(value: Any, limit: int = 60) -> str:
    """A value for an error message, shortened (a file's table may be large)."""
    text = repr(_plain_safe(value))
    return text if len(text) <= limit else text[:limit - 3] + "..."


def _plain_safe(value: Any) -> Any:
    try:
        return _plain(value)
    except ValueError:
        return value


def _field_in(message: str, keys: list[str]) -> str | None:
    for key in sorted(keys, key=len, reverse=True):
        if message.startswith(key) or f" {key}" in message or f"{key}:" in message or f"{key!r}" in message:
            return key
    return None


def read_toml(text: str, where: str, error: type[Exception] | None = None) -> dict[str, Any]:
    """:func:`hapticproof.core.tomltext.read_toml`, its errors :class:`SceneFileError` by default."""
    return _read_toml(text, where, error or SceneFileError)


def loads(text: str, where: str = "scene", base: str | Path | None = None, system: str | None = None):
    """A scene from the text of a scene file (``base``: the folder its ``matrix`` file is in;
    default the current folder; ``system``: the kind the command line names, for a file that
    does not say)."""
    table = read_toml(text, where)
    if system is not None and isinstance(table, dict) and "system" not in table:
        table = {"system": system, **table}
    return scene_from_table(table, where=where, base=base, text=text)


def read_scene(path: str | Path, system: str | None = None):
    """A scene from a scene file (``-``: standard input); ``system`` is the kind a file that does
    not say is read as (``derive single-user --scene FILE``)."""
    from hapticproof.core.files import FileAccessError, read_text

    try:
        text = read_text(path, "<stdin>" if str(path) == "-" else str(path))
    except FileAccessError as err:
        raise SceneFileError(str(err)) from None
    if str(path) == "-":
        return loads(text, "<stdin>", system=system)
    return loads(text, str(path), base=Path(path).parent, system=system)


# ---------------------------------------------------------------------------------------------
# writing
# ---------------------------------------------------------------------------------------------

_BARE = re.compile(r"^[A-Za-z0-9_-]+$")


def toml_value(value: Any) -> str:
    """One TOML value: strings quoted (JSON escapes are TOML escapes), exact numbers as integers
    or quoted exact text (``"1/3"``, ``"0.001"``), lists inline.

    >>> toml_value(sp.Rational(1, 1000)), toml_value(sp.Rational(1, 3)), toml_value([1, "n"]), toml_value(True)
    ('"0.001"', '"1/3"', '[1, "n"]', 'true')
    """
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, int):
        return str(value)
    if isinstance(value, sp.Basic) and value.is_Integer:
        return str(int(value))
    if isinstance(value, sp.Basic) and value.is_Rational:
        return json.dumps(_decimal_text(value))
    if isinstance(value, sp.Basic):
        return json.dumps(write_expression(value))
    if isinstance(value, str):
        return json.dumps(value, ensure_ascii=False)
    if isinstance(value, (list, tuple)):
        return "[" + ", ".join(toml_value(v) for v in value) + "]"
    raise TypeError(f"cannot write {value!r} as TOML")


def _decimal_text(q: sp.Rational) -> str:
    """``p/q`` as a terminating decimal when it is one, else the fraction."""
    p, d = int(q.p), int(q.q)
    twos = fives = 0
    while d % 2 == 0:
        d //= 2
        twos += 1
    while d % 5 == 0:
        d //= 5
        fives += 1
    if d != 1:
        return f"{q.p}/{q.q}"
    digits = max(twos, fives)
    scaled = abs(p) * (10**digits // int(q.q))
    text = str(scaled).rjust(digits + 1, "0")
    text = text[:-digits] + "." + text[-digits:]
    return ("-" if p < 0 else "") + text


def dumps(scene) -> str:
    """The scene file text (fields that differ from their defaults, then ``[params]``).

    >>> print(dumps(Scene("single-user", delay=3, params={"K": 2, "T": "0.001", "M": "positive"})).strip())
    # hapticproof scene
    system = "single-user"
    delay = 3
    <BLANKLINE>
    [params]
    K = 2
    M = "positive"
    T = "0.001"
    """

    default = Scene(scene.system) if scene.system != "network" else None
    lines = ["# hapticproof scene"]
    for name in FIELDS[:-2]:
        value = getattr(scene, name)
        if value is None:
            continue
        if default is not None and name != "system" and value == getattr(default, name):
            continue
        if name == "matrix":
            rows = ",\n".join("  [" + ", ".join(toml_value(e) for e in row) + "]" for row in value)
            lines.append(f"matrix = [\n{rows},\n]")
            continue
        if name == "users" and scene.system == "multi-user" and value == 2:
            continue
        lines.append(f"{name} = {toml_value(value)}")
    if scene.roles:
        lines += ["", "[roles]"]
        lines += [f"{field} = {toml_value(list(name) if isinstance(name, tuple) else name)}" for field, name in scene.roles]
    if scene.params:
        lines += ["", "[params]"]
        for key, value in scene.params:
            shown = key if _BARE.match(key) else json.dumps(key)
            lines.append(f"{shown} = {toml_value(value)}")
    return "\n".join(lines) + "\n"


def write_scene(scene, path: str | Path) -> Path | None:
    """Write the scene file; ``-`` writes to standard output (returns ``None``)."""
    text = dumps(scene)
    if str(path) == "-":
        sys.stdout.write(text)
        return None
    from hapticproof.core.files import write_atomic

    return write_atomic(path, text)          # whole or not at all; no folder created
