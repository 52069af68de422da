"""Canonical forms and zero tests of exact expressions: is a difference identically zero,
the canonical rational function, deterministic sample points for probing."""

from __future__ import annotations

import functools
import itertools
import math
import random
from collections.abc import Iterable, Iterator, Mapping, Sequence
from typing import Any

import flint
import sympy as sp
from sympy.core.evalf import PrecisionExhausted
from sympy.polys.fields import sfield

from hapticproof.core.symbols import c as C_SYM
from hapticproof.exact import evaluator

__all__ = ["Sampler", "is_identically_zero", "canonical_rational", "canonical_fraction", "flint_fraction", "generator_order", "sympy_fraction", "cancel"]


_NICE = [sp.Integer(1), sp.Integer(2), sp.Rational(1, 2), sp.Integer(3), sp.Rational(1, 3), sp.Integer(5),
         sp.Rational(2, 3), sp.Integer(10), sp.Rational(1, 10), sp.Rational(7, 4), sp.Rational(3, 7)]
_C_NICE = [sp.Rational(1, 2), sp.Integer(-1), sp.Integer(1), sp.Integer(0)]
_ONE, _ZERO = sp.Integer(1), sp.Integer(0)


class Sampler:
    """Exact rational values for symbols, respecting their SymPy assumptions.

    ``positive`` symbols get values in (0, oo), ``nonnegative`` in [0, oo), ``integer`` ones
    integers, and the symbol ``c`` (``cos wT``) values in [-1, 1]. Explicit ``ranges`` override.
    Deterministic for a given seed: a few "nice" values first, then random rationals.

    >>> K = sp.Symbol('K', positive=True)
    >>> n = sp.Symbol('n', integer=True, nonnegative=True)
    >>> values = Sampler([K, n, C_SYM], seed=1).draw(3)
    >>> all(v[K] > 0 and v[n].is_integer and -1 <= v[C_SYM] <= 1 for v in values)
    True
    """

    def __init__(
        self,
        symbols: Iterable[sp.Symbol],
        seed: int = 0,
        ranges: Mapping[sp.Symbol, tuple[Any, Any]] | None = None,
    ):
        self.symbols = sorted(set(symbols), key=str)
        self.ranges = dict(ranges or {})
        self._rng = random.Random(seed)
        # each symbol's kind, read once (assumption queries and range conversions cost more
        # than the draws): ("range", lo, hi, integer), ("c",), ("integer", low) or
        # ("real", positive, nonnegative)
        self._kinds = [self._kind(s) for s in self.symbols]

    def _kind(self, symbol: sp.Symbol) -> tuple:
        if symbol in self.ranges:
            lo, hi = (sp.Rational(v) for v in self.ranges[symbol])
            return ("range", lo, hi, bool(symbol.is_integer))
        if symbol == C_SYM:
            return ("c",)
        if symbol.is_integer:
            return ("integer", 0 if symbol.is_nonnegative else (1 if symbol.is_positive else -6))
        return ("real", bool(symbol.is_positive), bool(symbol.is_nonnegative))

    def _value(self, kind: tuple, position: int, index: int) -> sp.Rational:
        rng = self._rng
        tag = kind[0]
        if tag == "range":
            lo, hi, integer = kind[1], kind[2], kind[3]
            if integer:
                return sp.Integer(rng.randint(int(lo), int(hi)))
            if index == 0:
                return (lo + hi) / 2
            return lo + (hi - lo) * sp.Rational(rng.randint(0, 1000), 1000)
        if tag == "c":
            if index < len(_NICE):
                return _C_NICE[index % 4]
            return sp.Rational(rng.randint(-60, 60), 60)
        if tag == "integer":
            return sp.Integer(1 + index % 3 if index < len(_NICE) else rng.randint(kind[1], 12))
        if index == 0:
            value = _ONE
        elif index < 4 * len(_NICE):
            value = _NICE[(index + 3 * position) % len(_NICE)]
        else:
            value = sp.Rational(rng.randint(1, 400), rng.randint(1, 60))
        if kind[1]:
            return value
        if kind[2]:
            return _ZERO if index % 7 == 3 else value
        return value if (index + position) % 2 == 0 else -value

    def __iter__(self) -> Iterator[dict[sp.Symbol, sp.Rational]]:
        pairs = list(enumerate(zip(self.symbols, self._kinds)))
        for index in itertools.count():
            yield {s: self._value(kind, k, index) for k, (s, kind) in pairs}

    def draw(self, count: int) -> Sequence[dict[sp.Symbol, sp.Rational]]:
        """The first ``count`` points, drawn as they are read: a search that stops at its
        first witness draws (and builds) no more rationals than it looked at.

        >>> x = sp.Symbol('x', positive=True)
        >>> points = Sampler([x], seed=2).draw(300)
        >>> len(points), points[1], points[1:3] == [{x: 2}, {x: sp.Rational(1, 2)}]
        (300, {x: 2}, True)
        """
        return _Draws(iter(self), count)


class _Draws(Sequence):
    """The first ``count`` items of an iterator, read only as far as they are used; equal to
    the list of them."""

    def __init__(self, source: Iterator, count: int, start: int = 0, shared: list | None = None):
        self._source, self._count, self._start = source, max(0, count), start
        self._items = [] if shared is None else shared

    def _fill(self, upto: int) -> None:
        while len(self._items) < min(upto, self._start + self._count):
            self._items.append(next(self._source))

    def __len__(self) -> int:
        return self._count

    def __getitem__(self, index: Any) -> Any:
        if isinstance(index, slice):
            start, stop, step = index.indices(self._count)
            if step == 1:
                return _Draws(self._source, max(0, stop - start), self._start + start, self._items)
            return [self[i] for i in range(start, stop, step)]
        if index < 0:
            index += self._count
        if not 0 <= index < self._count:
            raise IndexError("sample index out of range")
        self._fill(self._start + index + 1)
        return self._items[self._start + index]

    def __iter__(self) -> Iterator:
        for i in range(self._count):
            self._fill(self._start + i + 1)
            yield self._items[self._start + i]

    def __eq__(self, other: object) -> bool:
        return isinstance(other, Sequence) and list(self) == list(other)

    def __repr__(self) -> str:
        return repr(list(self))


def is_identically_zero(expr: sp.Expr) -> bool:
    """Exact zero test of a rational (or trigonometric-polynomial) expression.

    Canonical forms are tried from cheapest to dearest: rational functions over Q (``cancel``),
    over Q with algebraic numbers such as sqrt(2) (``cancel`` with ``extension``), polynomials
    in ``sin``/``cos`` of one angle (reduced modulo ``sin^2 + cos^2 - 1``), and only then
    ``simplify``, which a numeric probe at a rational point spares non-zero expressions (the
    probe comes last: on the audit's mostly-zero differences it costs more than it saves).

    >>> x = sp.Symbol('x')
    >>> is_identically_zero((x**2 - 1)/(x - 1) - x - 1), is_identically_zero(sp.sin(x)**2 + sp.cos(x)**2 - 1)
    (True, True)
    >>> is_identically_zero(sp.sqrt(2)*x/(sp.sqrt(2) + 1) - x*(2 - sp.sqrt(2)))
    True
    """
    expr = sp.sympify(expr)
    if expr == 0:
        return True
    fast = evaluator.is_zero_rational(expr)     # a rational function over Q: its numerator in flint
    if fast is not None:
        return fast
    if expr.is_rational_function():
        return canonical_rational(expr) == 0  # a canonical form for rational functions over Q
    # zero as a rational function of its atoms (cos(x), H(z), exp(sT) independent): zero (the
    # test cancel(together(expr)) makes below, in flint)
    if evaluator.is_zero_rational(expr, opaque=True) or sp.cancel(sp.together(expr)) == 0:
        return True
    if not expr.has(sp.Function, sp.exp):
        return sp.cancel(sp.together(expr), extension=True) == 0
    reduced = _single_angle_form(expr)
    if reduced is not None:
        return reduced == 0
    if _probe_nonzero(expr):
        return False
    if expr.has(sp.sin, sp.cos, sp.exp):
        return sp.simplify(sp.expand_trig(expr)) == 0
    return sp.simplify(expr) == 0


def canonical_rational(expr: sp.Expr) -> sp.Expr:
    """Canonical (cancelled) form of a rational function over Q, as an expression.

    An element of the rational function field over its own symbols: cheaper than ``cancel``,
    whose term-factoring preprocessing dominates on large sums.

    >>> x, y = sp.symbols('x y')
    >>> canonical_rational((x**2 - y**2)/(x - y) - y)
    x
    >>> canonical_rational(sp.Float(0.75)), canonical_rational(sp.Float(0.686844161539459)).is_Rational
    (3/4, True)
    """
    expr = sp.sympify(expr)
    if not expr.free_symbols:
        # a float is read exactly, by its binary value (nsimplify could return radicals)
        return sp.Rational(expr) if expr.is_Float else sp.cancel(expr)
    fast = _field_element(expr)
    if fast is not None:
        return fast[0] / fast[1]
    _, element = sfield(expr)
    return element.as_expr()


def cancel(expr: Any) -> Any:
    """``sp.cancel(expr)``, computed in flint for a rational expression over Q in its symbols.

    SymPy's ``cancel`` of such an expression is ``p/q`` with SymPy's canonical pair (the
    coprime integer polynomials of :func:`sympy_fraction`), the same pair ``sfield`` holds;
    other expressions (functions, radicals, floats, numbers) go to ``sp.cancel``.

    >>> x, y = sp.symbols('x y')
    >>> cancel((x**2 - y**2)/(2*x - 2*y) + y/3), sp.cancel((x**2 - y**2)/(2*x - 2*y) + y/3)
    (x/2 + 5*y/6, x/2 + 5*y/6)
    """
    expr = sp.sympify(expr)
    if isinstance(expr, sp.Expr) and not expr.is_Number and expr.free_symbols:
        fast = _field_element(expr)
        if fast is not None:
            return fast[0] / fast[1]
    return sp.cancel(expr)


def canonical_fraction(expr: sp.Expr) -> tuple[sp.Expr, sp.Expr]:
    """Cancelled numerator and denominator of a rational function over Q (see
    :func:`canonical_rational`); falls back to ``cancel`` for other expressions.

    >>> x = sp.Symbol('x')
    >>> canonical_fraction(1/(x - 1) + 1)
    (x, x - 1)
    """
    expr = sp.sympify(expr)
    fast = _field_element(expr) if expr.free_symbols else None
    if fast is not None:
        return fast
    if expr.free_symbols and expr.is_rational_function():
        _, element = sfield(expr)
        return element.numer.as_expr(), element.denom.as_expr()
    return sp.fraction(sp.cancel(sp.together(expr)))


@functools.lru_cache(maxsize=1024)
def generator_order(symbols: frozenset) -> tuple[sp.Symbol, ...]:
    """SymPy's default order of polynomial generators for these symbols (with distinct names
    there are no ties, so the order depends on the set alone).

    >>> x, K, a = sp.symbols('x K a')
    >>> generator_order(frozenset({x, K, a}))
    (x, a, K)
    """
    return sp.Poly(sp.Add(*sorted(symbols, key=str))).gens


def _field_element(expr: sp.Expr) -> tuple[sp.Expr, sp.Expr] | None:
    """SymPy's canonical numerator and denominator of a rational expression over Q (what
    ``sfield(expr)[1]`` holds), computed in flint (:func:`sympy_fraction`); ``None`` (SymPy
    decides) for other expressions, or two symbols with one name (SymPy's order between them
    is not fixed).

    >>> x, y = sp.symbols('x y')
    >>> _field_element((x**2 - y**2)/(2*y - 2*x) + sp.Rational(1, 3))
    (-3*x - 3*y + 2, 6)
    """
    program = evaluator.rational_program(expr)
    if program is None or not program.symbols:
        return None
    names = [s.name for s in program.symbols]
    if len(set(names)) != len(names):
        return None
    gens = generator_order(frozenset(program.symbols))
    found = evaluator.rational_quotient(expr, gens)
    if found is None:
        return None
    return sympy_fraction(*found, gens)


def sympy_fraction(num: Any, den: Any, gens: tuple[sp.Symbol, ...]) -> tuple[sp.Expr, sp.Expr]:
    """The fraction ``num/den`` of flint polynomials in ``gens`` (SymPy's generator order, lex)
    as SymPy's canonical pair: the coprime integer polynomials ``p``, ``q`` (no common factor,
    contents included) with ``q``'s leading coefficient positive -- the unique pair SymPy's
    cancellation (``cancel``, ``sfield``) leaves.

    >>> import flint
    >>> ctx = flint.fmpq_mpoly_ctx.get(('x0', 'x1'), 'lex')
    >>> x0, x1 = ctx.gens()
    >>> sympy_fraction(x0 / 2 - x1, -x1 / 3, sp.symbols('a b'))
    (-3*a + 6*b, 2*b)
    """
    if num.is_zero():
        return sp.Integer(0), sp.Integer(1)
    coeffs = num.coeffs() + den.coeffs()
    scale = math.lcm(*(int(a.q) for a in coeffs))
    content = math.gcd(*(int(a.p) * (scale // int(a.q)) for a in coeffs))
    factor = flint.fmpq(scale, content)
    if den.leading_coefficient() < 0:
        factor = -factor

    def as_expr(poly: Any) -> sp.Expr:
        terms = []
        for monom, a in poly.terms():
            a = a * factor
            term = [sp.Integer(int(a.p))]
            term += [sp.Pow(g, e) for g, e in zip(gens, monom) if e]
            terms.append(sp.Mul(*term))
        return sp.Add(*terms)

    return as_expr(num), as_expr(den)


def _probe_nonzero(expr: sp.Expr) -> bool:
    """True when the expression is certainly non-zero at a rational point: evaluated with
    ``strict=True``, so every digit is correct or evalf raises (an exact zero always raises, as
    zero has no relative accuracy) and the probe then proves nothing."""
    symbols = sorted(expr.free_symbols, key=str)
    point = {s: sp.Rational(7 + 3 * k, 11 + 2 * k) for k, s in enumerate(symbols)}
    try:
        value = sp.N(expr.xreplace(point), 30, strict=True)
    except (TypeError, ValueError, ZeroDivisionError, PrecisionExhausted):
        return False
    if not value.is_number or value.has(sp.zoo, sp.nan, sp.oo, -sp.oo):
        return False
    return abs(value) > sp.Float("1e-20")


def _single_angle_form(expr: sp.Expr) -> sp.Expr | None:
    """Rewrite a polynomial in sin/cos of integer multiples of one angle in the canonical ring
    Q(params, c)[s]/(s^2 + c^2 - 1); ``None`` when the expression has other functions."""
    trig = [f for f in expr.atoms(sp.Function) if isinstance(f, (sp.sin, sp.cos))]
    if not trig or expr.atoms(sp.Function) - set(trig) or expr.has(sp.exp):
        return None
    args = {f.args[0] for f in trig}
    base = None
    for a in args:
        coeff, rest = a.as_coeff_Mul()
        if not coeff.is_Integer:
            return None
        if base is None:
            base = rest
        elif rest != base:
            return None
    cs, sn = sp.Dummy("c"), sp.Dummy("s")
    expanded = sp.expand_trig(expr).subs({sp.cos(base): cs, sp.sin(base): sn})
    if expanded.has(sp.sin, sp.cos):
        return None
    num, den = sp.fraction(sp.together(expanded))

    def reduce(p: sp.Expr) -> sp.Expr:
        poly = sp.Poly(sp.expand(p), sn)
        out = sp.Integer(0)
        for (power,), coeff in poly.terms():
            out += coeff * (1 - cs**2) ** (power // 2) * sn ** (power % 2)
        return sp.expand(out)

    reduced_den = reduce(den)
    if reduced_den == 0:
        return None
    return sp.cancel(reduce(num) / reduced_den)


def evaluate_at(expr: sp.Expr, values: Mapping[sp.Symbol, Any]) -> sp.Expr | None:
    """Exact value at a point (rational when the expression is rational; exact transcendental
    numbers such as ``cos(1)`` otherwise, which compare correctly through evalf).

    A rational expression at a rational point is evaluated by its compiled program
    (:mod:`hapticproof.exact.evaluator`, no SymPy tree rebuilt); at a pole of a sub-expression,
    and for every other expression, SymPy's ``xreplace`` decides (its ``zoo``/``nan`` rules).

    >>> x, y = sp.symbols('x y')
    >>> evaluate_at((x**2 + 1)/(y - 1), {x: sp.Integer(2), y: sp.Rational(3, 2)})
    10
    >>> evaluate_at(1/(1 + 1/x), {x: sp.Integer(0)}), evaluate_at(x/y, {x: 1, y: 0}) is None
    (0, True)
    >>> evaluate_at(sp.cos(x), {x: sp.Integer(1)})
    cos(1)
    """
    program = evaluator.rational_program(expr) if isinstance(expr, sp.Expr) else None
    if program is not None:
        try:
            return program.at(values)
        except (ZeroDivisionError, evaluator.NotAtRationalPoint):
            pass
    try:
        value = sp.sympify(expr).xreplace(dict(values))
        if value.has(sp.zoo, sp.nan, sp.oo, -sp.oo):
            return None
        if not value.is_Rational and not value.free_symbols:
            value = sp.cancel(value)
        return None if value.has(sp.zoo, sp.nan) else value
    except (ZeroDivisionError, TypeError):
        return None


def certified_nonzero(value: sp.Expr) -> bool:
    """Certified ``value != 0`` for an exact number (evalf with increasing precision).

    ``False`` means "not certified": a value that evaluates to below ``10^-50`` at 100 digits
    is not called non-zero (``simplify`` failing to reach 0 proves nothing: ``2 - 2 sin(2
    atan(1/2))^2 - sqrt(5) sin(3 atan(1/2))/2 + 19/50`` is 0).

    >>> t = 2*sp.atan(sp.Rational(1, 2))
    >>> certified_nonzero(2 - 2*sp.sin(t)**2 - sp.sqrt(5)*sp.sin(3*t/2)/2 + sp.Rational(19, 50))
    False
    >>> certified_nonzero(sp.sin(t) - sp.Rational(4, 5) + sp.Rational(1, 10**40))
    True
    """
    if value.is_Rational:
        return value != 0
    for digits in (30, 100):
        approx = sp.N(value, digits)
        if approx.is_number and abs(approx) > sp.Float(10) ** (-digits // 2):
            return True
    return False


class _NotRational(Exception):
    pass


def flint_fraction(expr: Any, var: sp.Symbol) -> tuple[flint.fmpq_poly, flint.fmpq_poly] | None:
    """``(num, den)`` of a rational function of ``var`` with rational coefficients as coprime flint
    polynomials (``den`` monic), read from the expression tree -- no ``together``/``cancel`` (the
    numeric route of a scene needs no SymPy algebra); ``None`` when ``expr`` has other symbols,
    floats or functions (then SymPy decides).

    >>> z = sp.Symbol("z")
    >>> flint_fraction(2 + sp.Rational(1, 1000) * (z - 1) / (sp.Rational(1, 1000) * z), z)
    (3*x + (-1), x)
    >>> flint_fraction(z**-3 / (z - 1), z), flint_fraction(sp.Symbol("K") * z, z)
    ((1, x^4 + (-1)*x^3), None)
    """
    one = flint.fmpq_poly([1])

    def walk(e: Any) -> tuple[flint.fmpq_poly, flint.fmpq_poly]:
        if e is var or (e.is_Symbol and e == var):
            return flint.fmpq_poly([0, 1]), one
        if e.is_Rational:
            return flint.fmpq_poly([flint.fmpq(int(e.p), int(e.q))]), one
        if e.is_Add or e.is_Mul:
            num, den = walk(e.args[0])
            for arg in e.args[1:]:
                n2, d2 = walk(arg)
                if e.is_Add:
                    num, den = (num * d2 + n2 * den, den * d2) if den != d2 else (num + n2, den)
                else:
                    num, den = num * n2, den * d2
            return num, den
        if e.is_Pow and e.exp.is_Integer:
            num, den = walk(e.base)
            k = int(e.exp)
            if k < 0:
                if num.is_zero():
                    raise _NotRational
                num, den, k = den, num, -k
            return num**k, den**k
        raise _NotRational

    try:
        num, den = walk(sp.sympify(expr))
    except (_NotRational, AttributeError):
        return None
    if den.is_zero():
        return None
    if num.is_zero():
        return num, one
    g = num.gcd(den)
    if g.degree() > 0:
        num, den = num / g, den / g
    lead = den.coeffs()[-1]
    return num / lead, den / lead
