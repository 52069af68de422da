"""The single-user model: a 1-DOF sampled-data haptic device on a discrete environment.

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

from hapticproof.core.errors import SceneError
from hapticproof.core.evidence import exact
from hapticproof.core.symbols import n as N_SYM
from hapticproof.core.symbols import z as Z_SYM
from hapticproof.systems.choices import APPROXIMATIONS  # of X_h(z) from V_h(z) (HVE, Section 3.1.1)

__all__ = ["APPROXIMATIONS", "SYMBOLS", "SingleUserScene", "virtual_wall", "as_parameter", "as_delay"]




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
    #: the scene's naming (:mod:`hapticproof.systems.naming`) when its symbols do not give it
    names: Any = field(default=None, repr=False)
    #: every parameter a number (set once on construction: the numeric route asks often)
    _numeric: bool = field(default=False, init=False, repr=False, compare=False)

    def __post_init__(self) -> None:
        for name in ("b", "T", "z_a"):
            object.__setattr__(self, name, as_parameter(name, getattr(self, name)))
        object.__setattr__(self, "delay", as_delay(self.delay))
        from hapticproof.core.expr import normalise_variables
        from hapticproof.exact.canonical import flint_fraction

        H = sp.sympify(self.H)
        # a rational function of the toolkit's z with rational coefficients (the numeric case, read
        # without SymPy algebra) needs no normalisation; anything else is checked by SymPy
        if flint_fraction(H, Z_SYM) is None:
            H = normalise_variables(H, "z", "H(z)")
            if not H.is_rational_function(Z_SYM):
                raise SceneError(f"H(z) must be a rational function of z, got {H}")
        object.__setattr__(self, "H", H)
        if self.approximation not in APPROXIMATIONS:
            raise SceneError(
                f"unknown approximation {self.approximation!r}; choose one of {', '.join(APPROXIMATIONS)}"
            )
        if _negative(self.T, strict=False):
            raise SceneError(f"the sampling period T must be positive, got {self.T}")
        # a negative damping or shortage of passivity is a scene like any other: the definition
        # decides it (a refusal here would leak into an audit's finding as an internal error)
        object.__setattr__(self, "_numeric", all(v.is_Rational or not v.free_symbols for v in (self.b, self.T, self.delay, self.z_a))
                           and not (self.H.free_symbols - {Z_SYM}))

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
        if _negative(T, strict=False):
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

    def naming(self) -> Any:
        """The names every view of this scene prints (:class:`~hapticproof.core.naming.Naming`)."""
        if self.names is not None:
            return self.names
        from hapticproof.systems.naming import model_naming

        return model_naming("single-user", {"period": self.T, "device_damping": self.b}, self.parameters)

    @property
    def is_numeric(self) -> bool:
        """True when every parameter (including the delay) is a number."""
        return self._numeric

    @property
    def has_delay(self) -> bool:
        return self.delay != 0

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


def _negative(value: sp.Expr, strict: bool = True) -> bool:
    """``value < 0`` (``strict``) or ``value <= 0`` for a number; a rational is compared without
    SymPy relationals (the numeric route's construction costs microseconds)."""
    if value.is_Rational:
        return value.p < 0 or (not strict and value.p == 0)
    if not value.is_number:
        return False
    return bool(value < 0) if strict else not bool(value > 0)


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
