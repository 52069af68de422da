"""The sampled-data position-error-based teleoperator (teleoperator paper, Fig. 2): its
controllers and scene (the passivity decision is in :mod:`hapticproof.analysis.teleoperator`)."""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass, field, replace
from functools import lru_cache
from typing import Any

import sympy as sp

from hapticproof.core.errors import InputFormatError, SceneError
from hapticproof.core.evidence import exact
from hapticproof.systems.singleuser import SYMBOLS
from hapticproof.core.symbols import z as Z_SYM

__all__ = ["TELE_SYMBOLS", "pd_controller", "filtered_pd_controller", "discretize_pd", "parse_controller", "TeleoperatorScene"]


#: Symbols of the teleoperator paper (dampings and masses positive, B >= 0 derivative gain).
TELE_SYMBOLS: dict[str, sp.Symbol] = {
    "K": SYMBOLS["K"],
    "B": SYMBOLS["B"],
    "T": SYMBOLS["T"],
    "b": SYMBOLS["b"],
    "b_m": sp.Symbol("b_m", positive=True),
    "b_s": sp.Symbol("b_s", positive=True),
    "m_m": sp.Symbol("m_m", positive=True),
    "m_s": sp.Symbol("m_s", positive=True),
    "alpha": sp.Symbol("alpha", positive=True),
    "a": sp.Symbol("a", nonnegative=True),
}


def pd_controller(K: Any = TELE_SYMBOLS["K"], B: Any = TELE_SYMBOLS["B"], T: Any = TELE_SYMBOLS["T"],
                  z: sp.Symbol = Z_SYM) -> sp.Expr:
    """The PD controller of eq. (33), ``K + B(z-1)/(Tz)``: the backward difference of ``K + Bs``.

    >>> pd_controller(2, 1, sp.Rational(1, 10))
    2 + 10*(z - 1)/z
    """
    K, B, T = (sp.sympify(v) for v in (K, B, T))
    return K + B * (z - 1) / (T * z)


def filtered_pd_controller(K: Any = TELE_SYMBOLS["K"], B: Any = TELE_SYMBOLS["B"], T: Any = TELE_SYMBOLS["T"],
                           a: Any = TELE_SYMBOLS["a"], z: sp.Symbol = Z_SYM) -> sp.Expr:
    """PD with a first-order low-pass on the derivative, ``K + B(1 - a)(z - 1)/(T(z - a))``
    (``0 <= a < 1``; ``a = 0`` is eq. 33).

    >>> sp.simplify(filtered_pd_controller(a=0) - pd_controller())
    0
    """
    K, B, T, a = (sp.sympify(v) for v in (K, B, T, a))
    return K + B * (1 - a) * (z - 1) / (T * (z - a))


def _generalized_bilinear(num: sp.Expr, den: sp.Expr, s: sp.Symbol, T: Any, alpha: sp.Rational) -> tuple[list, list]:
    """Coefficient lists (highest power first, denominator monic) of ``num(s)/den(s)`` under
    ``s = (z - 1)/(T (alpha z + 1 - alpha))``, computed exactly as ``sympy.physics.control.gbt``
    (``alpha = 0`` forward, ``1`` backward, ``1/2`` bilinear) -- importing that package costs
    about a second (it loads matplotlib), longer than the whole audit of a display."""
    num_coeffs, den_coeffs = sp.Poly(num, s).all_coeffs(), sp.Poly(den, s).all_coeffs()
    z = s
    order = max(len(num_coeffs), len(den_coeffs)) - 1

    def substituted(coeffs: list) -> sp.Expr:
        return sp.Add(*[T ** (order - i) * c * (z - 1) ** i * (alpha * z + 1 - alpha) ** (order - i)
                        for c, i in zip(coeffs[::-1], range(len(coeffs)))])

    top = substituted(num_coeffs).as_poly(z).all_coeffs()
    bottom = substituted(den_coeffs).as_poly(z).all_coeffs()
    lead = bottom[0]
    return [c / lead for c in top], [c / lead for c in bottom]


@lru_cache(maxsize=32)   # pure; the audit and the tests ask for the same few
def discretize_pd(method: str, K: Any = TELE_SYMBOLS["K"], B: Any = TELE_SYMBOLS["B"],
                  T: Any = TELE_SYMBOLS["T"], z: sp.Symbol = Z_SYM) -> sp.Expr:
    """Discretise ``K + Bs`` as :mod:`sympy.physics.control` does (``backward_diff``,
    ``forward_diff`` or ``bilinear``: its generalized bilinear transform, written out in
    :func:`_generalized_bilinear`) and return ``C(z)``.

    >>> sp.simplify(discretize_pd("backward") - pd_controller())
    0
    >>> sp.factor(discretize_pd("bilinear", 1, 1, 2))
    2*z/(z + 1)
    """
    methods = {"backward": sp.Integer(1), "forward": sp.Integer(0), "bilinear": sp.Rational(1, 2)}
    if method not in methods:
        raise SceneError(f"unknown discretisation {method!r}; choose one of {', '.join(methods)}")
    s = sp.Symbol("s")
    K, B, T = (sp.sympify(v) for v in (K, B, T))
    num, den = _generalized_bilinear(K + B * s, sp.Integer(1), s, T, methods[method])
    top = max(len(num), len(den)) - 1
    as_poly = lambda coeffs: sum(c * z ** (len(coeffs) - 1 - i) for i, c in enumerate(coeffs))  # noqa: E731
    return sp.cancel(as_poly(num) * z ** (top - len(num) + 1) / (as_poly(den) * z ** (top - len(den) + 1)))


def parse_controller(text: str, params: Mapping[str, Any] | None = None) -> sp.Expr:
    """A user's controller ``C(z)`` from text such as ``"K + B*(z-1)/(T*z)"`` (read by
    :func:`hapticproof.core.expr.read_expression`: exact decimals, any parameter names).

    Names given in ``params`` get those exact values; the others stay symbolic (the teleoperator
    symbols ``K``, ``B``, ``T``, ``a``, ``alpha``... with their signs).

    >>> parse_controller("K + B*(z - 1)/(T*z)", {"K": 2, "B": "0.01", "T": "0.001"})
    2 + 10*(z - 1)/z
    """
    from hapticproof.core.expr import read_expression

    if not isinstance(text, str) or not text.strip():
        raise InputFormatError(f"controller {text!r}: give C(z) as an expression in z")
    expr = read_expression(text, "z", where="controller", symbols=TELE_SYMBOLS)
    values = {sym: exact(params[sym.name]) for sym in expr.free_symbols if params and sym.name in params}
    expr = expr.subs(values)
    if not isinstance(expr, sp.Expr) or not expr.is_rational_function(Z_SYM):
        raise InputFormatError(f"controller {text!r} must be a rational function of z")
    return expr


@dataclass(frozen=True, slots=True, weakref_slot=True)
class TeleoperatorScene:
    """A sampled-data PEB teleoperator: robots, sampling period, controller and scaling.

    Parameters
    ----------
    m_m, m_s, b_m, b_s : expr
        Masses (positive) and dampings (any sign: a negative damping is decided, not refused).
        The masses do not enter the passivity decision (they store energy losslessly) and may
        be ``None``; the stability checks (:meth:`to_sampled`) need them.
    T : expr
        Sampling period.
    C : expr
        ``C(z) = C_s(z)``, any real-rational function of ``z``; ``C_m = alpha C`` (eq. 30).
    alpha : expr
        Position scaling (eq. 31), any real number; ``1`` gives equal controllers (eq. 17).
    """

    m_m: Any
    m_s: Any
    b_m: Any
    b_s: Any
    T: Any
    C: Any
    alpha: Any = 1
    #: the scene's naming (:mod:`hapticproof.systems.naming`) when its symbols do not give it
    names: Any = field(default=None, repr=False)

    def __post_init__(self) -> None:
        from hapticproof.core.expr import normalise_variables

        for name in ("m_m", "m_s", "b_m", "b_s", "T", "alpha"):
            value = getattr(self, name)
            if value is None and name in ("m_m", "m_s"):
                continue                      # masses are optional: they do not enter the bounds
            value = value if isinstance(value, sp.Basic) and not value.is_number else exact(value)
            object.__setattr__(self, name, value)
            if value.is_number and not value.is_real:
                raise SceneError(f"{name} must be a real number, got {value}")
            # dampings of any sign and any scaling alpha are decided (condition (D); only alpha^2
            # enters the error-coordinate damping); masses and the period are physical
            if name in ("m_m", "m_s", "T") and value.is_number and not value > 0:
                raise SceneError(f"{name} must be positive, got {value}")
        C = normalise_variables(self.C, "z", "C(z)")
        if not C.is_rational_function(Z_SYM):
            raise SceneError(f"C(z) must be a rational function of z, got {C}")
        num, den = sp.fraction(sp.cancel(sp.together(C)))
        if sp.Poly(num, Z_SYM).degree() > sp.Poly(den, Z_SYM).degree():
            raise SceneError(f"C(z) = {sp.sstr(sp.cancel(C))} is improper (non-causal: y_k would need later samples of the "
                             "error), so the sampled-data teleoperator is not defined; give a proper C(z) (a backward "
                             "difference or a filtered derivative)")
        object.__setattr__(self, "C", C)

    @classmethod
    def pd(cls, K: Any = None, B: Any = None, T: Any = None, alpha: Any = 1, *, m_m: Any = None,
           m_s: Any = None, b_m: Any = None, b_s: Any = None) -> TeleoperatorScene:
        """The paper's scene with the PD controller (33); unspecified values stay symbolic."""
        sym = TELE_SYMBOLS
        T = sym["T"] if T is None else exact(T)
        C = pd_controller(sym["K"] if K is None else exact(K), sym["B"] if B is None else exact(B), T)
        return cls(sym["m_m"] if m_m is None else m_m, sym["m_s"] if m_s is None else m_s,
                   sym["b_m"] if b_m is None else b_m, sym["b_s"] if b_s is None else b_s, T, C,
                   sym["alpha"] if alpha is None else alpha)

    @classmethod
    def symmetric(cls, m: Any, b: Any, T: Any, C: Any, alpha: Any = 1) -> TeleoperatorScene:
        """Identical robots (the paper's simulations and experiments)."""
        return cls(m, m, b, b, T, C, alpha)

    @property
    def C_m(self) -> sp.Expr:
        return self.alpha * self.C

    @property
    def C_s(self) -> sp.Expr:
        return self.C

    @property
    def parameters(self) -> set[sp.Symbol]:
        out: set[sp.Symbol] = set()
        for value in (self.m_m, self.m_s, self.b_m, self.b_s, self.T, self.C, self.alpha):
            if value is not None:
                out |= sp.sympify(value).free_symbols
        return out - {Z_SYM}

    def naming(self) -> Any:
        """The names every view of this scene prints (:class:`~hapticproof.core.naming.Naming`)."""
        if self.names is not None:
            return self.names
        from hapticproof.systems.naming import model_naming

        both = self.b_m if self.b_m == self.b_s else None
        values = {"period": self.T, "master_damping": self.b_m, "slave_damping": self.b_s, "device_damping": both,
                  "master_mass": self.m_m, "slave_mass": self.m_s, "mass": self.m_m if self.m_m == self.m_s else None}
        return model_naming("teleoperator", values, self.parameters)

    @property
    def controller_is_numeric(self) -> bool:
        return not ((sp.sympify(self.C).free_symbols - {Z_SYM}) | self.T.free_symbols | self.alpha.free_symbols)

    def with_values(self, **values: Any) -> TeleoperatorScene:
        """Substitute exact values for symbols by name.

        >>> TeleoperatorScene.pd().with_values(K=1, B=0, T="0.001").C
        1
        """
        by_name = {s.name: s for s in self.parameters}
        mapping = {}
        for key, value in values.items():
            if key not in by_name:
                raise SceneError(f"unknown parameter {key!r}; the scene has {sorted(by_name)}")
            mapping[by_name[key]] = exact(value)
        sub = lambda v: None if v is None else sp.sympify(v).subs(mapping)  # noqa: E731
        return replace(self, m_m=sub(self.m_m), m_s=sub(self.m_s), b_m=sub(self.b_m), b_s=sub(self.b_s),
                       T=sub(self.T), C=sub(self.C), alpha=sub(self.alpha))

    def to_sampled(self, master: Any = None, slave: Any = None) -> Any:
        """The numeric scene as a :class:`hapticproof.systems.loops.Teleoperator` (exact ZOH loop)."""
        from hapticproof.systems.impedance import DiscreteTF
        from hapticproof.systems.loops import Teleoperator

        if self.parameters:
            raise SceneError(f"the scene has free parameters {sorted(map(str, self.parameters))}")
        if self.m_m is None or self.m_s is None:
            raise SceneError("the sampled-data loop needs the masses m_m and m_s")
        num, den = sp.fraction(sp.cancel(sp.together(self.C)))
        pn, pd = sp.Poly(num, Z_SYM), sp.Poly(den, Z_SYM)
        tf = DiscreteTF(tuple(pn.all_coeffs()), tuple(pd.all_coeffs()))
        return Teleoperator(m_m=self.m_m, m_s=self.m_s, b_m=self.b_m, b_s=self.b_s, T=self.T,
                            alpha=self.alpha, master=master, slave=slave, controller=tf)
