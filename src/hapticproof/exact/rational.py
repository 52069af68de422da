r"""Exact rational functions over Q in named variables: the field element of every transfer matrix.

A :class:`RationalFunction` is ``num/den`` with ``num``, ``den`` python-flint ``fmpq_mpoly`` in one
context whose generators are the *names* the function uses (``"K"``, ``"T"``, ``"z"``, ``"K_{01}"``),
kept coprime with a monic denominator, so equal functions have equal fields. Operations between
functions in different names lift both into the union of their names. Nothing here knows what a
name means: the transfer variable (``z`` or ``s``), a parameter and ``c = cos(theta)`` are all just
names (:mod:`hapticproof.exact.transfer` gives ``z`` and ``s`` their meaning).

python-flint's multivariate GCD makes arithmetic on ``Q(K, B, T, z)`` a few microseconds per
operation, where SymPy's ``cancel`` of the same expression takes milliseconds.

>>> import sympy as sp
>>> K, B, T, z = sp.symbols("K B T z")
>>> H = RationalFunction.from_sympy(K + B*(z - 1)/(T*z))
>>> G = RationalFunction.from_sympy(sp.Rational(1, 100)) + H * RationalFunction.from_sympy(T/(z - 1))
>>> G.to_sympy()
(B*z - B + K*T*z + z**2/100 - z/100)/(z**2 - z)
>>> G.subs({"K": 2, "B": 0, "T": sp.Rational(1, 1000)}).to_sympy()
(z/100 - 1/125)/(z - 1)
>>> G.degree("z"), sorted(G.names)
(2, ['B', 'K', 'T', 'z'])
"""

from __future__ import annotations

import functools
from collections.abc import Iterable, Mapping
from fractions import Fraction
from typing import Any

import flint
import sympy as sp

__all__ = ["RationalFunction", "NotRationalError", "context", "to_fmpq", "as_fraction"]


class NotRationalError(ValueError):
    """An expression that is not a rational function with rational coefficients."""


@functools.lru_cache(maxsize=4096)
def context(names: tuple[str, ...]) -> flint.fmpq_mpoly_ctx:
    """The polynomial ring ``Q[names]`` (lex order in the given order; cached).

    >>> context(("B", "K")).gens()
    (B, K)
    """
    return flint.fmpq_mpoly_ctx.get(names if names else ("_",), "lex")


def _names_of(ctx: flint.fmpq_mpoly_ctx) -> tuple[str, ...]:
    names = ctx.names()
    return () if names == ("_",) else tuple(names)


def to_fmpq(value: Any) -> flint.fmpq:
    """An exact rational (Python, Fraction, SymPy or flint) as ``flint.fmpq``; floats are refused.

    >>> to_fmpq(Fraction(1, 3)), to_fmpq(sp.Rational(-2, 4)), to_fmpq(5)
    (1/3, -1/2, 5)
    """
    if isinstance(value, flint.fmpq):
        return value
    if isinstance(value, bool):
        raise NotRationalError("a boolean is not a number")
    if isinstance(value, (int, flint.fmpz)):
        return flint.fmpq(value)
    if isinstance(value, Fraction):
        return flint.fmpq(value.numerator, value.denominator)
    if isinstance(value, sp.Rational):
        return flint.fmpq(int(value.p), int(value.q))
    if isinstance(value, sp.Basic) and value.is_Rational:
        return flint.fmpq(int(value.p), int(value.q))
    raise NotRationalError(f"not an exact rational number: {value!r}")


def as_fraction(value: flint.fmpq) -> Fraction:
    """``flint.fmpq`` as a Python ``Fraction``."""
    return Fraction(int(value.p), int(value.q))


def _lift(p: flint.fmpq_mpoly, ctx: flint.fmpq_mpoly_ctx) -> flint.fmpq_mpoly:
    if p.context() is ctx:
        return p
    if p.is_constant():
        return ctx.constant(p.leading_coefficient() if not p.is_zero() else 0)
    return p.project_to_context(ctx)


def _union(a: tuple[str, ...], b: tuple[str, ...]) -> tuple[str, ...]:
    if a == b:
        return a
    return tuple(sorted(set(a) | set(b)))


class RationalFunction:
    """``num/den`` over Q in named variables, coprime with a monic denominator (see module doc).

    Build with :meth:`from_sympy`, :meth:`constant`, :meth:`variable` or :meth:`from_polynomials`;
    values are immutable and hashable.
    """

    __slots__ = ("num", "den", "_hash")

    def __init__(self, num: flint.fmpq_mpoly, den: flint.fmpq_mpoly | None = None, *, normal: bool = False) -> None:
        if den is None:
            den = num.context().constant(1)
        if den.is_zero():
            raise ZeroDivisionError("a rational function with a zero denominator")
        if num.context() is not den.context():
            ctx = context(_union(_names_of(num.context()), _names_of(den.context())))
            num, den = _lift(num, ctx), _lift(den, ctx)
        if not normal:
            num, den = _normalise(num, den)
        self.num, self.den = num, den
        self._hash = None

    # -- construction -------------------------------------------------------------------------

    @classmethod
    def constant(cls, value: Any, names: tuple[str, ...] = ()) -> RationalFunction:
        """A constant (exact rational) in the ring of ``names``.

        >>> RationalFunction.constant(Fraction(3, 4)).to_sympy()
        3/4
        """
        ctx = context(tuple(names))
        return cls(ctx.constant(to_fmpq(value)), ctx.constant(1), normal=True)

    @classmethod
    def variable(cls, name: str) -> RationalFunction:
        """The variable ``name`` itself.

        >>> (RationalFunction.variable("z") ** 2).to_sympy()
        z**2
        """
        ctx = context((name,))
        return cls(ctx.gens()[0], ctx.constant(1), normal=True)

    @classmethod
    def from_polynomials(cls, num: flint.fmpq_poly | Iterable[Any], den: flint.fmpq_poly | Iterable[Any] | None, name: str
                         ) -> RationalFunction:
        """``num/den`` from univariate coefficients (low degree first, or ``flint.fmpq_poly``) in ``name``.

        >>> RationalFunction.from_polynomials([1, 1], [-1, 1], "z").to_sympy()
        (z + 1)/(z - 1)
        """
        ctx = context((name,))

        def lift(p: Any) -> flint.fmpq_mpoly:
            coeffs = p.coeffs() if isinstance(p, flint.fmpq_poly) else [to_fmpq(a) for a in p]
            return ctx.from_dict({(k,): a for k, a in enumerate(coeffs) if a != 0}) if any(a != 0 for a in coeffs) else ctx.constant(0)

        return cls(lift(num), lift(den) if den is not None else ctx.constant(1))

    @classmethod
    def from_sympy(cls, expr: Any) -> RationalFunction:
        """A SymPy expression built from symbols, rationals, ``+``, ``*`` and integer powers.

        Anything else (``exp``, ``sqrt``, ``sin``, floats, ``I``) is refused with
        :class:`NotRationalError`: a transfer function's coefficients are exact rationals.

        >>> K, z = sp.symbols("K z")
        >>> RationalFunction.from_sympy((K*z - K)/(z**2 - 1)).to_sympy()
        K/(z + 1)
        >>> RationalFunction.from_sympy(sp.sqrt(2)*z)
        Traceback (most recent call last):
        ...
        hapticproof.exact.rational.NotRationalError: not a rational function: sqrt(2)
        """
        expr = sp.sympify(expr)
        return _from_sympy(expr)

    # -- structure ------------------------------------------------------------------------------

    @property
    def names(self) -> frozenset[str]:
        """The names the function actually depends on."""
        ctx = self.num.context()
        used = set()
        for p in (self.num, self.den):
            if not p.is_constant():
                for name, d in zip(_names_of(ctx), p.degrees()):
                    if d:
                        used.add(name)
        return frozenset(used)

    @property
    def is_zero(self) -> bool:
        return self.num.is_zero()

    @property
    def is_constant(self) -> bool:
        return self.num.is_constant() and self.den.is_constant()

    @property
    def is_polynomial(self) -> bool:
        return self.den.is_constant()

    def constant_value(self) -> Fraction:
        """The value of a constant function (``ValueError`` otherwise)."""
        if not self.is_constant:
            raise ValueError(f"{self} is not a constant")
        n = self.num.leading_coefficient() if not self.num.is_zero() else flint.fmpq(0)
        return as_fraction(n / self.den.leading_coefficient())

    def degree(self, name: str) -> int:
        """Degree in ``name`` of the numerator minus nothing: ``max(deg num, deg den)`` is
        :meth:`degrees`; this is the numerator's degree (``-1`` for zero)."""
        return _degree(self.num, name)

    def degrees(self, name: str) -> tuple[int, int]:
        """``(deg num, deg den)`` in ``name`` (``-1`` for a zero numerator)."""
        return _degree(self.num, name), _degree(self.den, name)

    def coefficients(self, name: str) -> tuple[list[RationalFunction], list[RationalFunction]]:
        """Numerator and denominator as coefficient lists in ``name`` (low degree first), each
        coefficient a polynomial in the other names (the denominator is *not* made monic in ``name``)."""
        return _coefficients(self.num, name), _coefficients(self.den, name)

    def univariate(self, name: str) -> tuple[flint.fmpq_poly, flint.fmpq_poly]:
        """``(num, den)`` as ``flint.fmpq_poly`` in ``name``, for a function of ``name`` alone.

        >>> RationalFunction.from_polynomials([1, 1], [-1, 1], "z").univariate("z")
        (x + 1, x + (-1))
        """
        stray = self.names - {name}
        if stray:
            raise ValueError(f"the function depends on {', '.join(sorted(stray))} besides {name}")
        return _univariate(self.num, name), _univariate(self.den, name)

    # -- arithmetic ---------------------------------------------------------------------------

    def _pair(self, other: Any) -> tuple[RationalFunction, RationalFunction]:
        if not isinstance(other, RationalFunction):
            other = RationalFunction.constant(other, _names_of(self.num.context()))
        ca, cb = self.num.context(), other.num.context()
        if ca is cb:
            return self, other
        ctx = context(_union(_names_of(ca), _names_of(cb)))
        return self._in(ctx), other._in(ctx)

    def _in(self, ctx: flint.fmpq_mpoly_ctx) -> RationalFunction:
        if self.num.context() is ctx:
            return self
        return RationalFunction(_lift(self.num, ctx), _lift(self.den, ctx), normal=True)

    def __add__(self, other: Any) -> RationalFunction:
        a, b = self._pair(other)
        if a.den == b.den:
            return RationalFunction(a.num + b.num, a.den)
        return RationalFunction(a.num * b.den + b.num * a.den, a.den * b.den)

    __radd__ = __add__

    def __neg__(self) -> RationalFunction:
        return RationalFunction(-self.num, self.den, normal=True)

    def __sub__(self, other: Any) -> RationalFunction:
        a, b = self._pair(other)
        return a + (-b)

    def __rsub__(self, other: Any) -> RationalFunction:
        a, b = self._pair(other)
        return b + (-a)

    def __mul__(self, other: Any) -> RationalFunction:
        a, b = self._pair(other)
        return RationalFunction(a.num * b.num, a.den * b.den)

    __rmul__ = __mul__

    def inverse(self) -> RationalFunction:
        if self.is_zero:
            raise ZeroDivisionError("the inverse of the zero function")
        return RationalFunction(self.den, self.num)

    def __truediv__(self, other: Any) -> RationalFunction:
        a, b = self._pair(other)
        return a * b.inverse()

    def __rtruediv__(self, other: Any) -> RationalFunction:
        a, b = self._pair(other)
        return b * a.inverse()

    def __pow__(self, k: int) -> RationalFunction:
        if not isinstance(k, int):
            raise NotRationalError(f"a rational function has integer powers only, not {k!r}")
        if k < 0:
            return self.inverse() ** (-k)
        return RationalFunction(self.num ** k, self.den ** k, normal=True)

    def __eq__(self, other: object) -> bool:
        if not isinstance(other, RationalFunction):
            try:
                other = RationalFunction.constant(other)
            except NotRationalError:
                return NotImplemented
        a, b = self._pair(other)
        return a.num == b.num and a.den == b.den

    def __hash__(self) -> int:
        if self._hash is None:
            self._hash = hash((str(self.num), str(self.den)))
        return self._hash

    def __repr__(self) -> str:
        return f"RationalFunction({self})"

    def __str__(self) -> str:
        if self.is_polynomial and self.den.is_one():
            return str(self.num)
        return f"({self.num})/({self.den})"

    # -- substitution and evaluation -------------------------------------------------------------

    def subs(self, values: Mapping[str, Any]) -> RationalFunction:
        """Substitute numbers or rational functions for names (all at once).

        >>> z = RationalFunction.variable("z")
        >>> f = (z + 1) / (z - 1)
        >>> f.subs({"z": 1 / z}).to_sympy(), f.subs({"z": 3}).to_sympy()
        ((-z - 1)/(z - 1), 2)
        """
        names = _names_of(self.num.context())
        values = {k: v for k, v in values.items() if k in names}
        if not values:
            return self
        if all(not isinstance(v, RationalFunction) for v in values.values()):
            mapping = {k: to_fmpq(v) for k, v in values.items()}
            num, den = self.num.subs(mapping), self.den.subs(mapping)
            if den.is_zero():
                raise ZeroDivisionError(f"the denominator vanishes at {_shown(values)}")
            return RationalFunction(num, den)
        images = {}
        for name in names:
            v = values.get(name, None)
            images[name] = v if isinstance(v, RationalFunction) else (
                RationalFunction.variable(name) if v is None else RationalFunction.constant(v))
        # a common denominator for the images: compose the numerator and denominator polynomials
        out_names = tuple(sorted(set().union(*(set(_names_of(f.num.context())) for f in images.values()))))
        ctx = context(out_names)
        lifted = [images[n]._in(ctx) for n in names]
        num = _compose_rational(self.num, lifted, ctx)
        den = _compose_rational(self.den, lifted, ctx)
        return num / den

    def evaluate(self, values: Mapping[str, Any]) -> Fraction:
        """The exact value when every name gets a number (``ZeroDivisionError`` at a pole).

        >>> RationalFunction.from_sympy(sp.Symbol("a") / 3).evaluate({"a": Fraction(1, 2)})
        Fraction(1, 6)
        """
        out = self.subs(values)
        if out.names:
            raise ValueError(f"no value for {', '.join(sorted(out.names))}")
        return out.constant_value()

    def gaussian(self, name: str, re: Fraction, im: Fraction) -> tuple[Fraction, Fraction]:
        """The exact value at ``name = re + j im`` of a function of ``name`` alone, as ``(Re, Im)``.

        >>> z = RationalFunction.variable("z")
        >>> (1 / (z - 1)).gaussian("z", Fraction(0), Fraction(1))       # 1/(j - 1) = (-1 - j)/2
        (Fraction(-1, 2), Fraction(-1, 2))
        """
        P, Q = self.univariate(name)
        pr, pi = _horner_gaussian(P, re, im)
        qr, qi = _horner_gaussian(Q, re, im)
        d = qr * qr + qi * qi
        if d == 0:
            raise ZeroDivisionError(f"{name} = {re} + j {im} is a pole")
        return (pr * qr + pi * qi) / d, (pi * qr - pr * qi) / d

    # -- conversion ---------------------------------------------------------------------------

    def to_sympy(self, symbols: Mapping[str, sp.Symbol] | None = None) -> sp.Expr:
        """A SymPy expression (``symbols`` maps names to the symbols to use, e.g. with assumptions)."""
        symbols = symbols or {}
        names = _names_of(self.num.context())
        syms = [symbols.get(n) or sp.Symbol(n) for n in names]
        num, den = _poly_to_sympy(self.num, syms), _poly_to_sympy(self.den, syms)
        if den == 1:
            return num
        return num / den

    def to_json(self) -> dict[str, Any]:
        """Plain JSON: names and the terms of numerator and denominator (exponent lists, rationals as text)."""
        names = list(_names_of(self.num.context()))
        width = len(names)
        return {"names": names,
                "num": [[list(map(int, m))[:width], str(c)] for m, c in self.num.to_dict().items()],
                "den": [[list(map(int, m))[:width], str(c)] for m, c in self.den.to_dict().items()]}

    @classmethod
    def from_json(cls, data: Mapping[str, Any]) -> RationalFunction:
        """Inverse of :meth:`to_json` (shapes checked; ``ValueError`` on anything else).

        >>> f = RationalFunction.from_sympy(sp.Symbol("K") / (sp.Symbol("z") - 1))
        >>> RationalFunction.from_json(f.to_json()) == f
        True
        """
        names = data.get("names")
        if not isinstance(names, list) or not all(isinstance(n, str) and n for n in names) or len(set(names)) != len(names):
            raise ValueError("a rational function's 'names' must be a list of distinct names")
        ctx = context(tuple(names))

        def poly(terms: Any) -> flint.fmpq_mpoly:
            if not isinstance(terms, list):
                raise ValueError("terms must be a list")
            out = {}
            for term in terms:
                if (not isinstance(term, list) or len(term) != 2 or not isinstance(term[0], list) or len(term[0]) != len(names)
                        or not all(isinstance(e, int) and not isinstance(e, bool) and 0 <= e <= 10_000 for e in term[0])
                        or not isinstance(term[1], str)):
                    raise ValueError("a term must be [exponents, 'p/q']")
                out[tuple(term[0]) if names else (0,)] = to_fmpq(Fraction(term[1]))
            return ctx.from_dict(out) if out else ctx.constant(0)

        return cls(poly(data.get("num")), poly(data.get("den")))

    def reflect(self, name: str) -> RationalFunction:
        """``f(1/name)``: the para-conjugate on the unit circle."""
        return self.subs({name: 1 / RationalFunction.variable(name)})

    def mirror(self, name: str) -> RationalFunction:
        """``f(-name)``: the para-conjugate on the imaginary axis."""
        return self.subs({name: -RationalFunction.variable(name)})

    def polynomial_lcm(self, other: RationalFunction) -> RationalFunction:
        """The least common multiple of two polynomials (monic in the ring's order).

        >>> z = RationalFunction.variable("z")
        >>> (z * z - 1).polynomial_lcm((z - 1) * (z + 2)).to_sympy()
        z**3 + 2*z**2 - z - 2
        """
        a, b = self._pair(other)
        if not (a.is_polynomial and b.is_polynomial):
            raise ValueError("the lcm of two polynomials")
        g = a.num.gcd(b.num)
        return RationalFunction(a.num * (b.num / g))

    def derivative(self, name: str) -> RationalFunction:
        """``d f / d name``."""
        ctx = self.num.context()
        names = _names_of(ctx)
        if name not in names:
            return RationalFunction.constant(0, names)
        k = names.index(name)
        n, d = self.num, self.den
        return RationalFunction(n.derivative(k) * d - n * d.derivative(k), d * d)


# ---------------------------------------------------------------------------------------------


def _normalise(num: flint.fmpq_mpoly, den: flint.fmpq_mpoly) -> tuple[flint.fmpq_mpoly, flint.fmpq_mpoly]:
    if num.is_zero():
        ctx = num.context()
        return ctx.constant(0), ctx.constant(1)
    if not den.is_constant():
        g = num.gcd(den)
        if not g.is_constant():
            num, den = num / g, den / g     # exact division (flint raises if not exact)
    lc = den.leading_coefficient()
    if lc != 1:
        num, den = num / lc, den / lc
    return num, den


def _degree(p: flint.fmpq_mpoly, name: str) -> int:
    if p.is_zero():
        return -1
    names = _names_of(p.context())
    if name not in names:
        return 0
    return int(p.degrees()[names.index(name)])


def _coefficients(p: flint.fmpq_mpoly, name: str) -> list[RationalFunction]:
    ctx = p.context()
    names = _names_of(ctx)
    if name not in names:
        return [RationalFunction(p, normal=False)]
    k = names.index(name)
    groups: dict[int, dict[tuple[int, ...], flint.fmpq]] = {}
    for monom, coeff in p.to_dict().items():
        rest = monom[:k] + (0,) + monom[k + 1:]
        groups.setdefault(monom[k], {})[rest] = coeff
    top = max(groups, default=-1)
    return [RationalFunction(ctx.from_dict(groups[d]) if d in groups else ctx.constant(0)) for d in range(top + 1)]


def _univariate(p: flint.fmpq_mpoly, name: str) -> flint.fmpq_poly:
    if p.is_zero():
        return flint.fmpq_poly([])
    names = _names_of(p.context())
    if p.is_constant():
        return flint.fmpq_poly([p.leading_coefficient()])
    k = names.index(name)
    coeffs: dict[int, flint.fmpq] = {}
    for monom, coeff in p.to_dict().items():
        coeffs[int(monom[k])] = coeff
    return flint.fmpq_poly([coeffs.get(d, flint.fmpq(0)) for d in range(max(coeffs) + 1)])


def _compose_rational(p: flint.fmpq_mpoly, images: list[RationalFunction], ctx: flint.fmpq_mpoly_ctx) -> RationalFunction:
    """``p(images)`` for a polynomial ``p`` and rational images: Horner-free, term by term over a
    common denominator per generator (powers cached)."""
    out = RationalFunction(ctx.constant(0), ctx.constant(1), normal=True)
    powers: list[dict[int, RationalFunction]] = [{} for _ in images]
    for monom, coeff in p.to_dict().items():
        term = RationalFunction(ctx.constant(coeff), ctx.constant(1), normal=True)
        for k, e in enumerate(monom):
            if e:
                cache = powers[k]
                if e not in cache:
                    cache[e] = images[k] ** int(e)
                term = term * cache[e]
        out = out + term
    return out


def _poly_to_sympy(p: flint.fmpq_mpoly, syms: list[sp.Symbol]) -> sp.Expr:
    terms = []
    for monom, coeff in p.to_dict().items():
        term = sp.Rational(int(coeff.p), int(coeff.q))
        for s, e in zip(syms, monom):
            if e:
                term *= s ** int(e)
        terms.append(term)
    return sp.Add(*terms)


def _horner_gaussian(p: flint.fmpq_poly, re: Fraction, im: Fraction) -> tuple[Fraction, Fraction]:
    ar, ai = Fraction(0), Fraction(0)
    for c in reversed(p.coeffs()):
        ar, ai = ar * re - ai * im + as_fraction(c), ar * im + ai * re
    return ar, ai


def _shown(values: Mapping[str, Any]) -> str:
    return ", ".join(f"{k} = {v}" for k, v in values.items())


def _from_sympy(expr: sp.Basic) -> RationalFunction:
    if expr.is_Rational:
        return RationalFunction.constant(expr)
    if expr.is_Symbol:
        return RationalFunction.variable(expr.name)
    if expr.is_Add:
        out = _from_sympy(expr.args[0])
        for arg in expr.args[1:]:
            out = out + _from_sympy(arg)
        return out
    if expr.is_Mul:
        out = _from_sympy(expr.args[0])
        for arg in expr.args[1:]:
            out = out * _from_sympy(arg)
        return out
    if expr.is_Pow and expr.exp.is_Integer:
        return _from_sympy(expr.base) ** int(expr.exp)
    raise NotRationalError(f"not a rational function: {expr}")
