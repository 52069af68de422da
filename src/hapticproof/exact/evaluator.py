"""Exact values of rational SymPy expressions at rational points, without rebuilding SymPy trees.

A rational expression (sums, products and integer powers of symbols and rational numbers) is
compiled once into a short straight-line program over python-flint's ``fmpq``: one slot per
distinct sub-expression (shared sub-trees are evaluated once), in the order of the tree. Running
the program at a point costs a few microseconds per operation, where ``expr.xreplace(point)``
rebuilds (and re-canonicalises) every node of the tree as a new SymPy object.

The program evaluates the tree *as written* -- nothing is cancelled or expanded first -- so its
value is the value SymPy's own evaluation gives whenever no denominator vanishes. At a pole of
any sub-expression (a division by zero) it raises :class:`ZeroDivisionError`, and callers fall
back to SymPy's rules for ``zoo`` and ``nan`` (``1/(1 + 1/x)`` is ``0`` at ``x = 0`` there).

>>> import sympy as sp
>>> x, y = sp.symbols('x y')
>>> program = RationalProgram.compile((x**2 - y) / (x + sp.Rational(1, 3)) + y**-2)
>>> program.at({x: sp.Integer(2), y: sp.Rational(1, 2)})
11/2
>>> RationalProgram.compile(sp.sqrt(x)) is None      # not a rational expression
True
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from functools import lru_cache
from typing import Any

import flint
import sympy as sp

__all__ = ["NotAtRationalPoint", "RationalProgram", "is_zero_rational", "rational_program", "rational_quotient", "relation_at"]

_LOAD, _CONST, _ADD, _MUL, _POW = range(5)


class NotAtRationalPoint(ValueError):
    """The point does not give every symbol of the program a rational value (a missing symbol,
    a float, a symbolic value, or a key that is not a symbol and could match a sub-expression)."""


class _NotCompilable(Exception):
    pass


class RationalProgram:
    """A rational expression compiled to a straight-line program over ``fmpq``.

    Build with :meth:`compile` (``None`` for an expression that is not rational over Q in its
    symbols: floats, functions, radicals, ``I``, matrices); run with :meth:`value` (an ``fmpq``)
    or :meth:`at` (a SymPy ``Rational``). Both raise :class:`ZeroDivisionError` when a
    denominator of the tree vanishes at the point and :class:`NotAtRationalPoint` when the
    point does not give every symbol a SymPy rational value.

    >>> import sympy as sp
    >>> K, T = sp.symbols('K T', positive=True)
    >>> p = RationalProgram.compile(K*T/2 - 1/(K - T))
    >>> sorted(map(str, p.symbols)), p.at({K: sp.Integer(3), T: sp.Rational(1, 2)})
    (['K', 'T'], 7/20)
    >>> p.at({K: sp.Integer(1), T: sp.Integer(1)})
    Traceback (most recent call last):
    ...
    ZeroDivisionError: ...
    """

    __slots__ = ("_loads", "_ops", "symbols")

    def __init__(self, symbols: tuple[sp.Symbol, ...], ops: tuple[tuple[int, Any], ...],
                 loads: tuple[tuple[int, sp.Symbol], ...]):
        self.symbols = symbols
        self._ops = ops
        self._loads = loads

    @classmethod
    def compile(cls, expr: Any, opaque: bool = False) -> RationalProgram | None:
        """The program of ``expr``, or ``None`` when it is not a rational expression over Q.

        With ``opaque``, every other sub-expression (``cos(x)``, ``H(s)``, ``sqrt(2)``, a float)
        is one more independent symbol of the program, which then computes ``expr`` as a
        rational function of those atoms.

        >>> import sympy as sp
        >>> x = sp.Symbol('x')
        >>> RationalProgram.compile(x**3 - 2*x).at({x: sp.Integer(2)}), RationalProgram.compile(sp.Float(0.5) * x)
        (4, None)
        >>> RationalProgram.compile(sp.cos(x)**2 + x, opaque=True).symbols
        (x, cos(x))
        """
        if not isinstance(expr, sp.Expr):
            return None
        slots: dict[sp.Basic, int] = {}
        ops: list[tuple[int, Any]] = []
        symbols: list[sp.Symbol] = []

        def slot(e: sp.Basic) -> int:
            found = slots.get(e)
            if found is not None:
                return found
            if e.is_Symbol:
                symbols.append(e)
                op: tuple[int, Any] = (_LOAD, len(symbols) - 1)
            elif e.is_Rational:
                op = (_CONST, flint.fmpq(int(e.p), int(e.q)))
            elif e.is_Add or e.is_Mul:
                op = (_ADD if e.is_Add else _MUL, tuple(slot(a) for a in e.args))
            elif e.is_Pow and e.exp.is_Integer:
                op = (_POW, (slot(e.base), int(e.exp)))
            elif opaque and isinstance(e, sp.Expr):
                symbols.append(e)
                op = (_LOAD, len(symbols) - 1)
            else:
                raise _NotCompilable
            ops.append(op)
            slots[e] = len(ops) - 1
            return len(ops) - 1

        try:
            slot(expr)
        except (_NotCompilable, RecursionError):
            return None
        loads = tuple((k, symbols[op[1]]) for k, op in enumerate(ops) if op[0] == _LOAD)
        return cls(tuple(symbols), tuple(ops), loads)

    @property
    def polynomial(self) -> bool:
        """No negative power: the expression is a polynomial in its symbols, and the program
        runs in any ring (:meth:`run` with polynomial values)."""
        return all(kind != _POW or arg[1] >= 0 for kind, arg in self._ops)

    def run(self, values: Mapping[sp.Symbol, Any]) -> Any:
        """The program with ``values[symbol]`` for each symbol: elements of any ring that mixes
        with ``fmpq`` constants (``fmpq``, ``fmpq_poly``, ``fmpq_mpoly`` ...). A negative power
        divides by its base (``1 / base``), so with polynomial values only a
        :attr:`polynomial` program is meaningful.

        >>> import flint, sympy as sp
        >>> a, c = sp.symbols('a c')
        >>> ctx = flint.fmpq_mpoly_ctx.get(('a', 'c'), 'lex')
        >>> A, C = ctx.gens()
        >>> RationalProgram.compile((a*c - 1)**2 / 2).run({a: A, c: C})
        1/2*a^2*c^2 - a*c + 1/2
        """
        registers: list[Any] = [None] * len(self._ops)
        for k, symbol in self._loads:
            registers[k] = values[symbol]
        for k, (kind, arg) in enumerate(self._ops):
            if kind == _ADD:
                acc = registers[arg[0]]
                for i in arg[1:]:
                    acc = acc + registers[i]
                registers[k] = acc
            elif kind == _MUL:
                acc = registers[arg[0]]
                for i in arg[1:]:
                    acc = acc * registers[i]
                registers[k] = acc
            elif kind == _POW:
                base, exp = registers[arg[0]], arg[1]
                if exp < 0:
                    if base == 0:
                        raise ZeroDivisionError("a denominator vanishes at the point")
                    registers[k] = (1 / base) ** -exp
                else:
                    registers[k] = base**exp
            elif kind == _CONST:
                registers[k] = arg
        return registers[-1]

    def value(self, point: Mapping[Any, Any]) -> flint.fmpq:
        """The exact value at ``point`` (SymPy rationals by symbol) as an ``fmpq``.

        >>> import sympy as sp
        >>> x = sp.Symbol('x')
        >>> RationalProgram.compile(1/x + 1).value({x: sp.Integer(4)})
        5/4
        """
        for key in point:
            if not isinstance(key, sp.Symbol):
                raise NotAtRationalPoint(f"the key {key} is not a symbol")
        values = {}
        for symbol in self.symbols:
            v = point.get(symbol)
            if v is None or not isinstance(v, sp.Rational):
                raise NotAtRationalPoint(f"{symbol} has no rational value")
            values[symbol] = flint.fmpq(int(v.p), int(v.q))
        return self.run(values)

    def at(self, point: Mapping[Any, Any]) -> sp.Rational:
        """The exact value at ``point`` as a SymPy ``Rational`` (see :meth:`value`)."""
        v = self.value(point)
        p, q = int(v.p), int(v.q)
        return sp.Integer(p) if q == 1 else sp.Rational(p, q)


@lru_cache(maxsize=4096)
def rational_program(expr: sp.Basic, opaque: bool = False) -> RationalProgram | None:
    """:meth:`RationalProgram.compile`, cached by expression (an expression evaluated at many
    sample points is compiled once).

    >>> import sympy as sp
    >>> x = sp.Symbol('x')
    >>> rational_program(x + 1) is rational_program(x + 1)
    True
    """
    return RationalProgram.compile(expr, opaque)


_RELATIONS = {sp.StrictGreaterThan: lambda d: d > 0, sp.GreaterThan: lambda d: d >= 0,
              sp.StrictLessThan: lambda d: d < 0, sp.LessThan: lambda d: d <= 0,
              sp.Equality: lambda d: d == 0, sp.Unequality: lambda d: d != 0}


def relation_at(relation: Any, point: Mapping[Any, Any]) -> bool | None:
    """Truth of a relation between rational expressions at a rational point, by their compiled
    programs; ``None`` when this cannot say it exactly (not such a relation, a symbol without
    a rational value, a pole of either side) -- then ``relation.xreplace(point)`` decides.

    >>> import sympy as sp
    >>> x, y = sp.symbols('x y')
    >>> relation_at(sp.Gt(x**2, y + 1), {x: sp.Integer(2), y: sp.Integer(3)}), relation_at(sp.Le(1/x, y), {x: sp.Integer(0), y: sp.Integer(1)})
    (False, None)
    """
    test = _RELATIONS.get(type(relation))
    if test is None:
        return None
    lhs, rhs = rational_program(relation.lhs), rational_program(relation.rhs)
    if lhs is None or rhs is None:
        return None
    try:
        return bool(test(lhs.value(point) - rhs.value(point)))
    except (ZeroDivisionError, NotAtRationalPoint):
        return None


class _Quotient:
    """``num / den`` over a flint polynomial ring (the arithmetic :meth:`RationalProgram.run`
    needs to run a rational expression in Q(symbols)); denominators kept small by gcds."""

    __slots__ = ("den", "num")

    def __init__(self, num: Any, den: Any):
        self.num, self.den = num, den

    @staticmethod
    def _lift(other: Any, like: Any) -> _Quotient:
        if isinstance(other, _Quotient):
            return other
        one = like.den.context().constant(1)
        return _Quotient(one * other, one)

    def __add__(self, other: Any) -> _Quotient:
        other = self._lift(other, self)
        if self.den == other.den:
            num, den = self.num + other.num, self.den
        else:
            g = self.den.gcd(other.den)
            a, b = self.den / g, other.den / g
            num, den = self.num * b + other.num * a, a * other.den
        g = num.gcd(den)
        if not g.is_one() and not g.is_zero():
            num, den = num / g, den / g
        return _Quotient(num, den)

    __radd__ = __add__

    def __mul__(self, other: Any) -> _Quotient:
        other = self._lift(other, self)
        return _Quotient(self.num * other.num, self.den * other.den)

    __rmul__ = __mul__

    def __pow__(self, k: int) -> _Quotient:
        return _Quotient(self.num**k, self.den**k)

    def __rtruediv__(self, one: Any) -> _Quotient:
        if self.num.is_zero():
            raise ZeroDivisionError("a denominator is identically zero")
        return _Quotient(self.den * one, self.num)

    def __eq__(self, other: object) -> bool:
        return other == 0 and self.num.is_zero()

    __hash__ = None  # type: ignore[assignment]


def is_zero_rational(expr: Any, opaque: bool = False) -> bool | None:
    """Whether a rational expression over Q is identically zero, decided in flint's polynomial
    rings (the numerator of its value in Q(symbols) is the zero polynomial); ``None`` when
    ``expr`` is not such an expression or a sub-expression divides by an identically zero
    denominator (then SymPy decides, and raises).

    With ``opaque`` every other atom (``cos(x)``, ``H(e^{sT})``) is an independent
    indeterminate: ``True`` then proves ``expr`` zero, while ``False`` only says it is not zero
    as a rational function of its atoms (``sin(x)**2 + cos(x)**2 - 1`` is zero all the same).

    >>> import sympy as sp
    >>> x, y = sp.symbols('x y')
    >>> is_zero_rational((x**2 - y**2)/(x - y) - x - y), is_zero_rational(1/(x + y) - 1/x), is_zero_rational(sp.sqrt(x))
    (True, False, None)
    >>> is_zero_rational(sp.cos(x)/(1 + sp.cos(x)) - 1 + 1/(1 + sp.cos(x)), opaque=True)
    True
    """
    program = rational_program(expr, opaque)
    if program is None:
        return None
    if not program.symbols:
        try:
            return program.run({}) == 0
        except ZeroDivisionError:
            return None
    names = tuple(f"x{k}" for k in range(len(program.symbols)))
    ctx = flint.fmpq_mpoly_ctx.get(names, "lex")
    one = ctx.constant(1)
    try:
        value = program.run({s: _Quotient(g, one) for s, g in zip(program.symbols, ctx.gens())})
    except ZeroDivisionError:
        return None
    if isinstance(value, _Quotient):
        return bool(value.num.is_zero())
    return value == 0


def rational_quotient(expr: Any, symbols: Sequence[sp.Symbol]) -> tuple[Any, Any] | None:
    """A rational expression over Q as ``(num, den)``, coprime ``fmpq_mpoly`` in ``symbols``
    (in that order, lex; ``den`` monic), or ``None`` when ``expr`` is not a rational expression
    in (a subset of) ``symbols`` or divides by an identically zero denominator.

    >>> import sympy as sp
    >>> x, y = sp.symbols('x y')
    >>> rational_quotient((x**2 - y**2)/(2*x - 2*y) + 1/y, (x, y))
    (1/2*x0*x1 + 1/2*x1^2 + 1, x1)
    """
    program = rational_program(expr)
    if program is None or not set(program.symbols) <= set(symbols):
        return None
    ctx = flint.fmpq_mpoly_ctx.get(tuple(f"x{k}" for k in range(max(len(symbols), 1))), "lex")
    gens = dict(zip(symbols, ctx.gens()))
    return run_quotient(program, {s: gens[s] for s in program.symbols}, ctx)


def run_quotient(program: RationalProgram, values: Mapping[Any, Any], ctx: Any) -> tuple[Any, Any] | None:
    """Run ``program`` in the field of fractions of the flint ring ``ctx`` (``values``: an
    ``fmpq_mpoly`` or ``fmpq`` per program symbol); ``(num, den)`` coprime, ``den`` monic, or
    ``None`` when a denominator is identically zero.

    >>> import flint, sympy as sp
    >>> a, t = sp.symbols('a t')
    >>> ctx = flint.fmpq_mpoly_ctx.get(('c',), 'lex')
    >>> (c,) = ctx.gens()
    >>> run_quotient(RationalProgram.compile(a / (1 - t), opaque=False), {a: c, t: c**2}, ctx)
    (-c, c^2 - 1)
    """
    one = ctx.constant(1)
    try:
        value = program.run({s: _Quotient(one * v, one) for s, v in values.items()})
    except ZeroDivisionError:
        return None
    if not isinstance(value, _Quotient):
        value = _Quotient(one * value, one)
    num, den = value.num, value.den
    if num.is_zero():
        return num, one
    g = num.gcd(den)
    if not g.is_one():
        num, den = num / g, den / g
    lead = den.leading_coefficient()
    return num / lead, den / lead
