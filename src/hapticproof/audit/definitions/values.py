r"""The exact value of a printed expression, computed from the names a paper has bound.

A printed display, read by :mod:`hapticproof.audit.reader`, is a SymPy tree whose names are
parameters (``K``, ``b_m``), the transfer variables ``z`` and ``s``, the frequency ``\omega``, and
applications of the paper's functions (``G_f^{-1}(z)``, ``Z_c(e^{j\omega T})``). :func:`evaluate`
turns it into a :class:`Value`, exactly:

* ``param`` -- a rational function of the parameters alone (``KT/2 + B``);
* ``transfer`` -- a :class:`~hapticproof.exact.transfer.TransferMatrix` in ``z`` (discrete) or
  ``s`` (continuous), a scalar being 1 x 1;
* ``boundary`` -- its value on the unit circle ``z = e^{j\omega T}`` or the axis ``s = j\omega``
  (:class:`~hapticproof.exact.boundaryvalue.BoundaryValue` entries: ``\cos\omega T``,
  ``\operatorname{Re}``, ``|\cdot|^2`` and the conjugate stay exact there).

Names the paper has not bound raise :class:`Unbound` (listing them): a display that uses them is
never given a verdict from a guess.

>>> import sympy as sp
>>> from hapticproof.core.symbols import z, omega
>>> K, B, T, b = sp.symbols("K B T b", real=True)
>>> H = sp.Function("H")
>>> env = Environment({"H": Binding.of(evaluate(K + B*(z - 1)/(T*z), Environment()), "z")})
>>> v = evaluate(b + H(z)*T/(z - 1), env)
>>> v.kind, v.to_sympy()
('transfer', (B*z - B + K*T*z + b*z**2 - b*z)/(z**2 - z))
>>> evaluate(sp.re(H(sp.exp(sp.I*omega*T))) - K - B/T*(1 - sp.cos(omega*T)), env).is_zero
True
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass, field
from fractions import Fraction
from typing import Any

import sympy as sp
from sympy.core.function import AppliedUndef

from hapticproof.core.errors import HapticproofError
from hapticproof.core.symbols import omega as OMEGA
from hapticproof.core.symbols import s as S_SYM
from hapticproof.core.symbols import z as Z_SYM
from hapticproof.exact.boundaryvalue import AXIS, C_NAME, CIRCLE, X_NAME, BoundaryValue, determinant
from hapticproof.exact.rational import NotRationalError, RationalFunction
from hapticproof.exact.transfer import CONTINUOUS, DISCRETE, VARIABLES, TransferMatrix

__all__ = ["Value", "Binding", "Environment", "Unbound", "Unsupported", "evaluate", "radicand", "RADICAL_PREFIX", "PARAM", "TRANSFER",
           "BOUNDARY"]

PARAM, TRANSFER, BOUNDARY = "param", "transfer", "boundary"
_BOUNDARY_OF = {DISCRETE: CIRCLE, CONTINUOUS: AXIS}


class Unbound(HapticproofError, ValueError):
    """A display uses names no definition binds (``names``: their printed SymPy names)."""

    def __init__(self, names: set[str], what: str = "") -> None:
        self.names = frozenset(names)
        shown = ", ".join(sorted(self.names))
        super().__init__(f"{what or 'the display'} uses {shown}, which no definition of the paper gives")


class Unsupported(HapticproofError, ValueError):
    """A construct the exact evaluation does not cover (a half-angle, ``|x|`` of a parameter, ...)."""


def _rf(value: Any) -> RationalFunction:
    return value if isinstance(value, RationalFunction) else RationalFunction.constant(value)


@dataclass(frozen=True, slots=True)
class Value:
    """An exact value: ``kind`` is ``param``, ``transfer`` or ``boundary``; ``domain`` is
    ``discrete``/``continuous`` (``None`` for a parameter expression); ``rows`` hold
    :class:`RationalFunction` entries (``param``, ``transfer``) or :class:`BoundaryValue` entries."""

    kind: str
    rows: tuple[tuple[Any, ...], ...]
    domain: str | None = None

    # -- construction -------------------------------------------------------------------------

    @classmethod
    def param(cls, f: RationalFunction | int | Fraction) -> Value:
        return cls(PARAM, ((_rf(f),),))

    @classmethod
    def transfer(cls, G: TransferMatrix) -> Value:
        return cls(TRANSFER, G.entries, G.domain)

    @classmethod
    def boundary(cls, v: BoundaryValue, domain: str) -> Value:
        return cls(BOUNDARY, ((v,),), domain)

    @property
    def shape(self) -> tuple[int, int]:
        return len(self.rows), len(self.rows[0])

    @property
    def is_scalar(self) -> bool:
        return self.shape == (1, 1)

    def matrix(self) -> TransferMatrix:
        """The transfer matrix of a ``transfer`` (or constant ``param``) value."""
        if self.kind == BOUNDARY:
            raise Unsupported("a value on the boundary is not a transfer function")
        return TransferMatrix(self.rows, self.domain or DISCRETE)

    # -- promotion ------------------------------------------------------------------------------

    def _as(self, kind: str, domain: str | None) -> Value:
        """This value promoted to ``kind`` in ``domain`` (param -> transfer -> boundary)."""
        if self.kind == kind and (self.domain == domain or kind == PARAM):
            return self
        if self.kind == PARAM and kind == TRANSFER:
            return Value(TRANSFER, self.rows, domain)
        if self.kind == PARAM and kind == BOUNDARY:
            b = _BOUNDARY_OF[domain]
            return Value(BOUNDARY, tuple(tuple(BoundaryValue.constant(e, b) for e in row) for row in self.rows), domain)
        if self.kind == TRANSFER and kind == BOUNDARY:
            if self.domain != domain:
                raise Unsupported("a discrete and a continuous quantity in one expression")
            return Value(BOUNDARY, self.matrix().on_boundary().entries, domain)
        if self.kind == kind and self.domain != domain:
            raise Unsupported("a discrete and a continuous quantity in one expression")
        raise Unsupported(f"cannot use a {self.kind} value as a {kind} value")

    @staticmethod
    def _common(a: Value, b: Value) -> tuple[Value, Value]:
        order = {PARAM: 0, TRANSFER: 1, BOUNDARY: 2}
        kind = a.kind if order[a.kind] >= order[b.kind] else b.kind
        domain = a.domain or b.domain
        if a.domain and b.domain and a.domain != b.domain:
            raise Unsupported("a discrete and a continuous quantity in one expression")
        return a._as(kind, domain), b._as(kind, domain)

    def _zero(self) -> Any:
        return BoundaryValue.constant(0, _BOUNDARY_OF[self.domain]) if self.kind == BOUNDARY else RationalFunction.constant(0)

    def _identity(self, n: int) -> Value:
        one = BoundaryValue.constant(1, _BOUNDARY_OF[self.domain]) if self.kind == BOUNDARY else RationalFunction.constant(1)
        return Value(self.kind, tuple(tuple(one if i == j else self._zero() for j in range(n)) for i in range(n)), self.domain)

    # -- arithmetic -------------------------------------------------------------------------------

    def __add__(self, other: Value) -> Value:
        a, b = self._common(self, other)
        if a.shape != b.shape:
            if b.is_scalar and a.shape[0] == a.shape[1]:
                b = a._identity(a.shape[0]) * b
            elif a.is_scalar and b.shape[0] == b.shape[1]:
                a = b._identity(b.shape[0]) * a
            else:
                raise Unsupported(f"adding a {a.shape[0]} x {a.shape[1]} and a {b.shape[0]} x {b.shape[1]} matrix")
        return Value(a.kind, tuple(tuple(x + y for x, y in zip(ra, rb)) for ra, rb in zip(a.rows, b.rows)), a.domain)

    def __neg__(self) -> Value:
        return Value(self.kind, tuple(tuple(-x for x in row) for row in self.rows), self.domain)

    def __sub__(self, other: Value) -> Value:
        return self + (-other)

    def __mul__(self, other: Value) -> Value:
        a, b = self._common(self, other)
        if a.is_scalar and not b.is_scalar:
            v = a.rows[0][0]
            return Value(a.kind, tuple(tuple(v * x for x in row) for row in b.rows), a.domain)
        if b.is_scalar and not a.is_scalar:
            v = b.rows[0][0]
            return Value(a.kind, tuple(tuple(x * v for x in row) for row in a.rows), a.domain)
        n, k = a.shape
        k2, m = b.shape
        if k != k2:
            raise Unsupported(f"multiplying a {n} x {k} by a {k2} x {m} matrix")
        rows = []
        for i in range(n):
            row = []
            for j in range(m):
                acc = a._zero()
                for t in range(k):
                    acc = acc + a.rows[i][t] * b.rows[t][j]
                row.append(acc)
            rows.append(tuple(row))
        return Value(a.kind, tuple(rows), a.domain)

    def inverse(self) -> Value:
        if self.kind == BOUNDARY:
            if not self.is_scalar:
                raise Unsupported("the inverse of a matrix on the boundary")
            return Value(BOUNDARY, ((self.rows[0][0].inverse(),),), self.domain)
        if self.is_scalar:
            return Value(self.kind, ((self.rows[0][0].inverse(),),), self.domain)
        return Value(self.kind, self.matrix().inverse().entries, self.domain)

    def __pow__(self, k: int) -> Value:
        if k < 0:
            return self.inverse() ** (-k)
        if self.is_scalar:
            return Value(self.kind, ((self.rows[0][0] ** k,),), self.domain)
        out = self._identity(self.shape[0])
        for _ in range(k):
            out = out * self
        return out

    def transpose(self) -> Value:
        return Value(self.kind, tuple(zip(*self.rows)), self.domain)

    def determinant(self) -> Value:
        if self.shape[0] != self.shape[1]:
            raise Unsupported("the determinant of a non-square matrix")
        if self.kind != BOUNDARY:
            return Value(self.kind, ((self.matrix().determinant(),),), self.domain)
        return Value(BOUNDARY, ((determinant([list(r) for r in self.rows]),),), self.domain)

    # -- parts on the boundary ----------------------------------------------------------------------

    def on_boundary(self, domain: str | None = None) -> Value:
        domain = domain or self.domain
        if domain is None:
            raise Unsupported("a real or imaginary part of a parameter expression")
        return self._as(BOUNDARY, domain)

    def map_boundary(self, func: Any, domain: str | None = None) -> Value:
        if self.kind == PARAM and domain is None:
            return Value(PARAM, tuple(tuple(func(BoundaryValue.constant(e)).re0 for e in row) for row in self.rows))
        v = self.on_boundary(domain)
        return Value(BOUNDARY, tuple(tuple(func(e) for e in row) for row in v.rows), v.domain)

    def conjugate_transpose(self) -> Value:
        v = self.on_boundary()
        return Value(BOUNDARY, tuple(tuple(e.conjugate() for e in row) for row in zip(*v.rows)), v.domain)

    # -- comparison -----------------------------------------------------------------------------------

    @property
    def is_zero(self) -> bool:
        if self.kind == BOUNDARY:
            return all(e.re0.is_zero and e.re1.is_zero and e.im0.is_zero and e.im1.is_zero for row in self.rows for e in row)
        return all(e.is_zero for row in self.rows for e in row)

    @property
    def names(self) -> frozenset[str]:
        """The parameter names the value depends on (transfer and boundary variables excluded;
        named square roots included)."""
        out: set[str] = set()
        for row in self.rows:
            for e in row:
                if isinstance(e, BoundaryValue):
                    for part in (e.re0, e.re1, e.im0, e.im1):
                        out |= part.names
                else:
                    out |= e.names
        return frozenset(n for n in out if not n.startswith("$") or n.startswith(RADICAL_PREFIX))

    def to_sympy(self, symbols: Mapping[str, sp.Symbol] | None = None) -> Any:
        """A SymPy expression (scalar) or matrix (``c``, ``x``, ``r`` for the boundary variables)."""
        if self.kind == BOUNDARY:
            from hapticproof.exact.transfer import BoundaryMatrix

            m = BoundaryMatrix(self.rows).to_sympy(symbols)
            return m[0, 0] if self.is_scalar else m
        if self.kind == TRANSFER:
            return self.matrix().to_sympy(symbols)
        table = dict(symbols or {})
        out = sp.Matrix([[e.to_sympy(table) for e in row] for row in self.rows])
        return out[0, 0] if self.is_scalar else out


@dataclass(frozen=True, slots=True)
class Binding:
    """What a name means: its value, and for a function its formal variable (``z`` or ``s``)."""

    value: Value
    variable: str | None = None
    source: str = ""

    @classmethod
    def of(cls, value: Value, variable: str | None = None, source: str = "") -> Binding:
        return cls(value, variable, source)


@dataclass
class Environment:
    """The bound names (by SymPy name) and the frequency conventions of one display."""

    bindings: Mapping[str, Binding] = field(default_factory=dict)
    #: names of angle symbols that stand for ``\omega T`` itself (``\vartheta``, ``\theta``)
    angles: frozenset[str] = frozenset({"theta", "vartheta"})
    #: parameters given a value by the display itself (``t_d = T``)
    substitutions: Mapping[str, Any] = field(default_factory=dict)
    #: the bound names an evaluation used (filled by :func:`evaluate`)
    used: set = field(default_factory=set)
    #: names that stand for complex values of a general two-port (``z_{11}`` under ``\Re``): each
    #: is ``a + j b`` with real unknowns ``a``, ``b``
    complex_names: frozenset = frozenset()
    #: where those complex values live (``discrete``: read on the unit circle)
    complex_domain: str = DISCRETE

    def lookup(self, name: str) -> Binding | None:
        found = self.bindings.get(name)
        if found is not None:
            self.used.add(name)
        return found


# ---------------------------------------------------------------------------------------------
# evaluation
# ---------------------------------------------------------------------------------------------


def evaluate(expr: Any, env: Environment, *, roots: bool = False) -> Value:
    """The exact :class:`Value` of a printed SymPy expression under ``env`` (see the module doc).

    Square roots (``|z_{12} z_{21}|``, ``\\sqrt{...}``) become named radicals (:func:`radicand`)
    only when ``roots`` is true: a caller that does not reduce them would read one as a free
    parameter.

    Raises :class:`Unbound` for names no definition gives, :class:`Unsupported` for constructs
    outside the exact algebra.
    """
    unbound = _unbound(expr, env)
    if unbound:
        raise Unbound(unbound)
    value = _Evaluator(env).value(sp.sympify(expr))
    if not roots and any(n.startswith(RADICAL_PREFIX) for n in value.names):
        raise Unsupported("a square root or the modulus of a complex value (exact only in an identity)")
    return value


#: the internal names of square roots: ``$rad<k>`` stands for ``sqrt(radicand(k))``, the same name
#: for the same radicand in every evaluation
RADICAL_PREFIX = "$rad"
_RADICANDS: dict[RationalFunction, str] = {}
_NAMES: dict[str, RationalFunction] = {}


def radicand(name: str) -> RationalFunction:
    """The non-negative rational function whose square root the radical ``name`` is."""
    return _NAMES[name]


def _radical_name(radicand: RationalFunction) -> str:
    name = _RADICANDS.get(radicand)
    if name is None:
        name = f"{RADICAL_PREFIX}{len(_RADICANDS) + 1}"
        _RADICANDS[radicand], _NAMES[name] = name, radicand
    return name


def _unbound(expr: Any, env: Environment) -> set[str]:
    out = set()
    if isinstance(expr, sp.MatrixBase):
        for e in expr:
            out |= _unbound(e, env)
        return out
    expr = sp.sympify(expr)
    for f in expr.atoms(AppliedUndef):
        if env.lookup(f.func.__name__) is None and not _is_residue(f):
            out.add(f.func.__name__)
    return out


def _is_residue(e: Any) -> bool:
    """``Res_{z = z0} F`` as the reader writes it: ``Res(F, z0)``."""
    return isinstance(e, AppliedUndef) and e.func.__name__ == "Res" and len(e.args) == 2


class _Evaluator:
    def __init__(self, env: Environment) -> None:
        self.env = env
        #: the names being substituted (a setting ``t_d = T`` read where ``T`` names ``t_d``: once)
        self.substituting: set[str] = set()

    # -- dispatch --------------------------------------------------------------------------------

    def value(self, e: Any) -> Value:
        if isinstance(e, sp.MatrixBase):
            return self._matrix(e)
        if e.is_Rational:
            return Value.param(RationalFunction.constant(e))
        if e == sp.I:
            raise Unsupported("j outside an exponential of the frequency")
        if e.is_Symbol:
            return self._symbol(e)
        if e.is_Add:
            out = self.value(e.args[0])
            for a in e.args[1:]:
                out = out + self.value(a)
            return out
        if e.is_Mul:
            return self._product(e)
        if e.is_Pow:
            return self._power(e)
        if _is_residue(e):
            return self._residue(e.args[0], e.args[1])
        if isinstance(e, AppliedUndef):
            return self._apply(e)
        if isinstance(e, (sp.cos, sp.sin)):
            return self._trig(e)
        if isinstance(e, sp.exp):
            return self._exponential(e.args[0])
        if isinstance(e, sp.re):
            return self.value(e.args[0]).map_boundary(lambda v: v.real_part(), self._domain_of(e.args[0]))
        if isinstance(e, sp.im):
            return self.value(e.args[0]).map_boundary(lambda v: v.imaginary_part(), self._domain_of(e.args[0]))
        if isinstance(e, sp.conjugate):
            return self.value(e.args[0]).map_boundary(lambda v: v.conjugate(), self._domain_of(e.args[0]))
        if isinstance(e, sp.Abs):
            return self._modulus(e.args[0], 1)
        if isinstance(e, sp.Determinant) or getattr(e.func, "__name__", "") == "det":
            return self.value(e.args[0]).determinant()
        if isinstance(e, sp.Transpose):
            return self.value(e.args[0]).transpose()
        if isinstance(e, sp.Subs):
            return self._at(self.value(e.args[0]), e.args[1], e.args[2], limit=False)
        if type(e).__name__ == "PrintedLimit":
            return self._at(self.value(e.args[0]), (e.args[1],), (e.args[2],), limit=True)
        raise Unsupported(f"{type(e).__name__} is not in the exact algebra")

    def _domain_of(self, e: Any) -> str | None:
        """The domain a part of ``e`` is taken in: that of its transfer content (``None``: a
        parameter expression, whose real part is itself)."""
        return self.value(e).domain

    # -- leaves ----------------------------------------------------------------------------------

    def _symbol(self, e: sp.Symbol) -> Value:
        if e == Z_SYM:
            return Value.transfer(TransferMatrix.transfer_variable(DISCRETE))
        if e == S_SYM:
            return Value.transfer(TransferMatrix.transfer_variable(CONTINUOUS))
        if e == OMEGA:
            # omega alone: the axis (s = j omega); on the circle it only appears in omega T
            return Value.boundary(BoundaryValue.r(AXIS), CONTINUOUS)
        if e.name in self.env.substitutions and e.name not in self.substituting:
            self.substituting.add(e.name)
            try:
                return self.value(sp.sympify(self.env.substitutions[e.name]))
            finally:
                self.substituting.discard(e.name)
        if e.name in self.env.complex_names:
            re_part, im_part = (RationalFunction.variable(f"{e.name}'{p}") for p in ("re", "im"))
            domain = self.env.complex_domain
            return Value.boundary(BoundaryValue(re_part, _zero(), im_part, _zero(), _BOUNDARY_OF[domain]), domain)
        binding = self.env.lookup(e.name)
        if binding is not None:
            if binding.value.names & self.env.complex_names:
                # a value written in a general two-port's entries, read with them complex
                return self.value(binding.value.to_sympy({n: sp.Symbol(n, real=True) for n in binding.value.names}))
            return binding.value
        if e.name in self.env.angles:
            raise Unsupported(f"the angle {e.name} outside cos, sin or an exponential")
        return Value.param(RationalFunction.variable(e.name))

    def _matrix(self, m: sp.MatrixBase) -> Value:
        cells = [[self.value(m[i, j]) for j in range(m.cols)] for i in range(m.rows)]
        if any(not c.is_scalar for row in cells for c in row):
            raise Unsupported("a matrix of matrices")
        order = {PARAM: 0, TRANSFER: 1, BOUNDARY: 2}
        top = max((c for row in cells for c in row), key=lambda c: order[c.kind])
        domains = {c.domain for row in cells for c in row} - {None}
        if len(domains) > 1:
            raise Unsupported("a discrete and a continuous quantity in one matrix")
        domain = next(iter(domains), None)
        rows = tuple(tuple(c._as(top.kind, domain).rows[0][0] for c in row) for row in cells)
        return Value(top.kind, rows, domain)

    def _product(self, e: sp.Mul) -> Value:
        # j omega T inside a product is the argument of an exponential only; j omega alone is s
        args = list(e.args)
        if sp.I in args:
            rest = sp.Mul(*[a for a in args if a != sp.I])
            if rest == OMEGA:
                return Value.boundary(BoundaryValue.point(AXIS), CONTINUOUS)
            inner = self.value(rest)
            return Value.boundary(BoundaryValue.j(_BOUNDARY_OF[inner.domain or CONTINUOUS]), inner.domain or CONTINUOUS) * inner
        out = self.value(args[0])
        for a in args[1:]:
            out = out * self.value(a)
        return out

    def _power(self, e: sp.Pow) -> Value:
        base, exp = e.args
        if exp.is_Rational and exp.q == 2:
            inner = self.value(base)
            root = self._radical(_real_rational(inner))
            return root ** int(exp.p)
        if not exp.is_Integer:
            raise Unsupported(f"a non-integer power {exp}")
        if isinstance(base, sp.Abs) and int(exp) % 2 == 0:
            inner = self.value(base.args[0])
            if not inner.is_scalar:
                raise Unsupported("|.| of a matrix")
            v = inner.on_boundary(inner.domain) if inner.kind != PARAM else None
            if v is None:
                f = inner.rows[0][0]
                return Value.param(f * f) ** (int(exp) // 2)
            return Value.boundary(v.rows[0][0].abs2(), v.domain) ** (int(exp) // 2)
        if isinstance(base, sp.Abs) or (base == sp.E):
            return self.value(sp.exp(exp)) if base == sp.E else self._power_abs(base, int(exp))
        return self.value(base) ** int(exp)

    def _power_abs(self, base: Any, k: int) -> Value:
        return self._modulus(base.args[0], k)

    def _modulus(self, arg: Any, k: int) -> Value:
        """``|arg|^k`` for an odd ``k``: ``|arg|^2`` is exact, its square root a radical."""
        inner = self.value(arg)
        if not inner.is_scalar:
            raise Unsupported("|.| of a matrix")
        if inner.kind == PARAM:
            square = inner.rows[0][0] * inner.rows[0][0]
        else:
            v = inner.on_boundary(inner.domain).rows[0][0].abs2()
            if not v.re1.is_zero:
                raise Unsupported("a modulus that is not a rational function of the frequency")
            square = v.re0
        out = self._radical(square) * Value.param(square) ** ((abs(k) - 1) // 2)
        return out if k > 0 else out.inverse()

    def _radical(self, radicand: RationalFunction) -> Value:
        """``sqrt(radicand)`` (a non-negative rational function): exact when it is a constant square,
        else one named radical per distinct radicand (``$rad1``), ``$rad1^2 = radicand``."""
        if radicand.is_constant:
            q = radicand.constant_value()
            if q < 0:
                raise Unsupported("the square root of a negative number")
            num, den = sp.sqrt(sp.Integer(q.numerator)), sp.sqrt(sp.Integer(q.denominator))
            if num.is_Integer and den.is_Integer:
                return Value.param(RationalFunction.constant(Fraction(int(num), int(den))))
        return Value.param(RationalFunction.variable(_radical_name(radicand)))

    def _at(self, value: Value, variables: Any, targets: Any, limit: bool) -> Value:
        """``value|_{x = a}`` and ``lim_{x -> a} value`` for a parameter ``x`` (a rational function of
        it: the limit at infinity from the leading coefficients)."""
        for variable, target in zip(variables, targets):
            if not isinstance(variable, sp.Symbol) or variable.name in (OMEGA.name,) or variable in (Z_SYM, S_SYM):
                raise Unsupported(f"a limit or evaluation in {variable}")
            name = variable.name
            if target in (sp.oo, -sp.oo):
                if not limit:
                    raise Unsupported("an evaluation at infinity")
                value = Value(value.kind, tuple(tuple(_at_infinity(e, name, target == sp.oo) for e in row) for row in value.rows),
                              value.domain)
                continue
            point = self.value(sp.sympify(target))
            if point.kind != PARAM:
                raise Unsupported("a limit at a frequency-dependent point")
            image = point.rows[0][0]
            try:
                value = Value(value.kind, tuple(tuple(_substituted(e, name, image) for e in row) for row in value.rows), value.domain)
            except ZeroDivisionError:
                raise Unsupported(f"{name} = {target} is a pole (a limit there is not a substitution)") from None
        return value

    # -- frequency ---------------------------------------------------------------------------------

    def _angle_multiple(self, arg: Any) -> int:
        """``arg = k omega P`` (``P`` the period, any product of parameters) or ``k theta``: ``k``."""
        arg = sp.sympify(arg)
        free = arg.free_symbols
        angle = [s for s in free if s.name in self.env.angles]
        if OMEGA in free:
            coeff = arg / OMEGA
            if coeff.has(OMEGA):
                raise Unsupported(f"{arg} is not a multiple of omega times the period")
            k, period = coeff.as_coeff_Mul()
            if period == 1 or not all(s.is_Symbol for s in sp.Mul.make_args(period)):
                raise Unsupported(f"{arg}: the frequency times a period is expected")
        elif len(angle) == 1:
            k, rest = arg.as_coeff_Mul()
            if rest != angle[0]:
                raise Unsupported(f"{arg} is not a multiple of the angle {angle[0]}")
        else:
            raise Unsupported(f"{arg} is not a frequency")
        if not k.is_Integer:
            raise Unsupported(f"the angle {arg} is not an integer multiple of the sampling angle (a half angle)")
        return int(k)

    def _trig(self, e: Any) -> Value:
        k = self._angle_multiple(e.args[0])
        c = BoundaryValue.t(CIRCLE)
        r = BoundaryValue.r(CIRCLE)
        cos_k, sin_k = _chebyshev(abs(k), c, r)
        if isinstance(e, sp.cos):
            return Value.boundary(cos_k, DISCRETE)
        return Value.boundary(sin_k if k >= 0 else -sin_k, DISCRETE)

    def _exponential(self, arg: Any) -> Value:
        arg = sp.sympify(arg)
        coeff = arg / sp.I
        if coeff.has(sp.I):
            raise Unsupported(f"exp({arg}) is not on the unit circle")
        k = self._angle_multiple(coeff)
        c = BoundaryValue.t(CIRCLE)
        r = BoundaryValue.r(CIRCLE)
        cos_k, sin_k = _chebyshev(abs(k), c, r)
        j = BoundaryValue.j(CIRCLE)
        return Value.boundary(cos_k + j * (sin_k if k >= 0 else -sin_k), DISCRETE)

    # -- applications ------------------------------------------------------------------------------

    def _residue(self, body: Any, point: Any) -> Value:
        """``Res_{z=z0} F``: ``((z - z0) F)(z0)`` at a simple pole (a multiple pole is no value here)."""
        value, at = self.value(body), self.value(point)
        if value.kind != TRANSFER or not value.is_scalar or at.kind != PARAM:
            raise Unsupported("a residue of a scalar transfer function at a point given by the parameters")
        internal = VARIABLES[value.domain][1]
        f, z0 = value.rows[0][0], at.rows[0][0]
        simple = f * (RationalFunction.variable(internal) - z0)
        try:
            residue = simple.subs({internal: z0})
        except ZeroDivisionError:
            raise Unsupported("a residue at a multiple pole") from None
        return Value(PARAM, ((residue,),))

    def _apply(self, e: AppliedUndef) -> Value:
        binding = self.env.lookup(e.func.__name__)
        if binding is None:
            raise Unbound({e.func.__name__})
        if len(e.args) != 1:
            raise Unsupported(f"{e.func.__name__} applied to {len(e.args)} arguments")
        value = binding.value
        if binding.variable is None or value.kind == PARAM:
            return value                         # a constant function: its value
        arg = sp.sympify(e.args[0])
        if not (arg.free_symbols & {Z_SYM, S_SYM, OMEGA} or any(s.name in self.env.angles for s in arg.free_symbols)):
            return value * self.value(arg)           # Z_p (v_m - v_s): a product, not an argument
        domain = value.domain
        internal = VARIABLES[domain][1]
        printed = Z_SYM if domain == DISCRETE else S_SYM
        if arg == printed:
            return value
        a = self.value(arg)
        if a.kind == BOUNDARY:
            if a.domain != domain:
                raise Unsupported(f"{e.func.__name__} is a function of {printed}, not of this argument")
            point = a.rows[0][0]
            rows = []
            for row in value.rows:
                rows.append(tuple(_compose_boundary(f, internal, point) for f in row))
            return Value(BOUNDARY, tuple(rows), domain)
        if a.kind == TRANSFER and a.domain == domain:
            image = a.rows[0][0]
            return Value(TRANSFER, tuple(tuple(f.subs({internal: image}) for f in row) for row in value.rows), domain)
        if a.kind == PARAM:
            image = a.rows[0][0]
            return Value(PARAM, tuple(tuple(f.subs({internal: image}) for f in row) for row in value.rows))
        raise Unsupported(f"{e.func.__name__} applied to {arg}")


def _zero() -> RationalFunction:
    return RationalFunction.constant(0)


def _real_rational(value: Value) -> RationalFunction:
    """A real value that is a rational function (of the parameters and the boundary variable)."""
    if not value.is_scalar:
        raise Unsupported("the square root of a matrix")
    e = value.rows[0][0]
    if isinstance(e, RationalFunction):
        return e
    if e.re1.is_zero and e.im0.is_zero and e.im1.is_zero:
        return e.re0
    raise Unsupported("the square root of a complex or odd-in-sin value")


def _substituted(e: Any, name: str, image: RationalFunction) -> Any:
    if isinstance(e, BoundaryValue):
        return BoundaryValue(*(p.subs({name: image}) for p in (e.re0, e.re1, e.im0, e.im1)), e.domain)
    return e.subs({name: image})


def _at_infinity(e: Any, name: str, positive: bool) -> Any:
    """The limit of a rational function as the parameter ``name`` grows without bound (a finite
    limit only: the numerator's degree in ``name`` at most the denominator's)."""
    if isinstance(e, BoundaryValue):
        return BoundaryValue(*(_at_infinity(p, name, positive) for p in (e.re0, e.re1, e.im0, e.im1)), e.domain)
    num, den = e.coefficients(name)
    if len(num) > len(den):
        raise Unsupported(f"the limit as {name} grows is infinite")
    if len(num) < len(den):
        return RationalFunction.constant(0)
    return num[-1] / den[-1]


def _compose_boundary(f: RationalFunction, name: str, point: BoundaryValue) -> BoundaryValue:
    """``f(point)`` for ``f`` rational in ``name`` and a point on the boundary."""
    num, den = f.coefficients(name)

    def horner(coeffs: list[RationalFunction]) -> BoundaryValue:
        out = BoundaryValue.constant(0, point.domain)
        for a in reversed(coeffs):
            out = out * point + BoundaryValue.constant(a, point.domain)
        return out

    return horner(num) / horner(den)


def _chebyshev(k: int, c: BoundaryValue, r: BoundaryValue) -> tuple[BoundaryValue, BoundaryValue]:
    """``(cos k theta, sin k theta)`` from ``cos theta = c``, ``sin theta = r`` (angle addition)."""
    cos_k, sin_k = BoundaryValue.constant(1), BoundaryValue.constant(0)
    for _ in range(k):
        cos_k, sin_k = cos_k * c - sin_k * r, sin_k * c + cos_k * r
    return cos_k, sin_k


def t_names() -> tuple[str, str]:
    """The internal names of the boundary variables (``c`` on the circle, ``x`` on the axis)."""
    return C_NAME, X_NAME


def refuses(expr: Any) -> NotRationalError | None:
    """Whether a SymPy expression is outside the exact algebra (for messages)."""
    try:
        RationalFunction.from_sympy(expr)
    except NotRationalError as err:
        return err
    return None
