r"""Exact rational functions of one variable over Q, and a reader of what users type.

The oracles need ``G(z)`` and ``C(s)`` as exact objects: polynomials are tuples of
:class:`fractions.Fraction` in *ascending* powers (``(a0, a1, a2)`` is ``a0 + a1 x + a2 x^2``),
rational functions are :class:`Rat` (numerator and denominator with their greatest common divisor
cancelled and a monic denominator, so one function has one representation). Nothing here
imports SymPy or the package under test: the reader at the end is written from the command-line grammar a
user sees in ``--help`` (numbers, names, ``+ - * / ** ^`` and parentheses; decimals exact),
so the oracle reads the very string the toolkit is given.

>>> z = Rat.variable()
>>> G = 1 + z**2 / (1000 * (z - 1))
>>> G.num, G.den
((Fraction(-1, 1), Fraction(1, 1), Fraction(1, 1000)), (Fraction(-1, 1), Fraction(1, 1)))
>>> read("K*z**2", "z", {"K": "1e300"}).num[-1] == 10**300
True
"""

from __future__ import annotations

import re
from dataclasses import dataclass
from fractions import Fraction
from typing import Any, Mapping, Sequence

__all__ = [
    "Poly", "ptrim", "pdeg", "padd", "psub", "pmul", "pscale", "pdivmod", "pgcd", "pderiv", "ppow",
    "prev", "pcompose_rat", "peval", "peval_complex", "squarefree", "Rat", "ReadError", "read", "read_number",
    "complex_div", "real_part_exact",
]

Poly = tuple  # tuple[Fraction, ...], ascending powers
ZERO: Poly = ()
ONE: Poly = (Fraction(1),)


# ---------------------------------------------------------------------------------------------
# polynomials over Q
# ---------------------------------------------------------------------------------------------
def ptrim(p: Sequence[Any]) -> Poly:
    """Drop vanishing leading coefficients; the zero polynomial is ``()``."""
    q = [Fraction(c) for c in p]
    while q and q[-1] == 0:
        q.pop()
    return tuple(q)


def pdeg(p: Poly) -> int:
    """Degree (``-1`` for the zero polynomial)."""
    return len(p) - 1


def padd(p: Poly, q: Poly) -> Poly:
    n = max(len(p), len(q))
    return ptrim([(p[i] if i < len(p) else 0) + (q[i] if i < len(q) else 0) for i in range(n)])


def psub(p: Poly, q: Poly) -> Poly:
    return padd(p, pscale(q, -1))


def pscale(p: Poly, c: Any) -> Poly:
    c = Fraction(c)
    return ptrim([a * c for a in p]) if c else ZERO


def pmul(p: Poly, q: Poly) -> Poly:
    if not p or not q:
        return ZERO
    out = [Fraction(0)] * (len(p) + len(q) - 1)
    for i, a in enumerate(p):
        if a:
            for j, b in enumerate(q):
                out[i + j] += a * b
    return ptrim(out)


def ppow(p: Poly, k: int) -> Poly:
    out, base = ONE, p
    while k:
        if k & 1:
            out = pmul(out, base)
        base, k = pmul(base, base), k >> 1
    return out


def pdivmod(p: Poly, q: Poly) -> tuple[Poly, Poly]:
    """Exact division with remainder (``q`` non-zero)."""
    if not q:
        raise ZeroDivisionError("polynomial division by zero")
    rem = list(p)
    quot = [Fraction(0)] * max(len(p) - len(q) + 1, 0)
    lead = q[-1]
    for k in range(len(p) - len(q), -1, -1):
        c = rem[k + len(q) - 1] / lead
        quot[k] = c
        if c:
            for j, b in enumerate(q):
                rem[k + j] -= c * b
    return ptrim(quot), ptrim(rem[: len(q) - 1])


def pmonic(p: Poly) -> Poly:
    return pscale(p, 1 / p[-1]) if p else ZERO


def pgcd(p: Poly, q: Poly) -> Poly:
    """Monic greatest common divisor (Euclid over Q, remainders made monic to keep sizes down)."""
    a, b = pmonic(p), pmonic(q)
    while b:
        a, b = b, pmonic(pdivmod(a, b)[1])
    return a if a else ONE


def pderiv(p: Poly) -> Poly:
    return ptrim([k * p[k] for k in range(1, len(p))])


def prev(p: Poly, degree: int | None = None) -> Poly:
    """``x^d p(1/x)`` with ``d = degree`` (default ``deg p``)."""
    d = pdeg(p) if degree is None else degree
    padded = list(p) + [Fraction(0)] * (d + 1 - len(p))
    return ptrim(padded[::-1])


def peval(p: Poly, x: Any) -> Any:
    """Horner evaluation in whatever arithmetic ``x`` brings (Fraction, mpmath, complex)."""
    acc = 0 * x
    for c in reversed(p):
        acc = acc * x + c
    return acc


def peval_complex(p: Poly, x: Fraction, y: Fraction) -> tuple[Fraction, Fraction]:
    """Exact ``p(x + jy)`` for rational ``x, y`` as ``(real, imaginary)``."""
    re_, im_ = Fraction(0), Fraction(0)
    for c in reversed(p):
        re_, im_ = re_ * x - im_ * y + c, re_ * y + im_ * x
    return re_, im_


def squarefree(p: Poly) -> list[tuple[Poly, int]]:
    """Yun's square-free factorisation ``p = lc * prod f_k^k`` (monic ``f_k``), exact."""
    out: list[tuple[Poly, int]] = []
    if pdeg(p) < 1:
        return out
    a = pmonic(p)
    b = pderiv(a)
    c = pgcd(a, b)
    w = pdivmod(a, c)[0]
    y = pdivmod(b, c)[0]
    k = 1
    while pdeg(w) > 0:
        zz = psub(y, pderiv(w))
        g = pgcd(w, zz) if zz else w
        if pdeg(g) > 0:
            out.append((g, k))
        w = pdivmod(w, g)[0]
        y = pdivmod(zz, g)[0] if zz else ZERO
        k += 1
    return out


def complex_div(a: tuple[Fraction, Fraction], b: tuple[Fraction, Fraction]) -> tuple[Fraction, Fraction]:
    """Exact ``a / b`` for complex rationals given as pairs."""
    den = b[0] * b[0] + b[1] * b[1]
    return ((a[0] * b[0] + a[1] * b[1]) / den, (a[1] * b[0] - a[0] * b[1]) / den)


def real_part_exact(num: Poly, den: Poly, x: Fraction, y: Fraction) -> Fraction | None:
    """Exact ``Re(num/den)`` at ``x + jy``; ``None`` at a zero of ``den``."""
    n = peval_complex(num, x, y)
    d = peval_complex(den, x, y)
    mod2 = d[0] * d[0] + d[1] * d[1]
    if mod2 == 0:
        return None
    return (n[0] * d[0] + n[1] * d[1]) / mod2


# ---------------------------------------------------------------------------------------------
# rational functions
# ---------------------------------------------------------------------------------------------
@dataclass(frozen=True)
class Rat:
    """An exact real-rational function ``num(x)/den(x)``, reduced, with a monic denominator.

    >>> z = Rat.variable()
    >>> (z**2 - 1) / (z - 1) == z + 1
    True
    >>> (1 / z**3).den
    (Fraction(0, 1), Fraction(0, 1), Fraction(0, 1), Fraction(1, 1))
    """

    num: Poly
    den: Poly

    def __post_init__(self) -> None:
        num, den = ptrim(self.num), ptrim(self.den)
        if not den:
            raise ZeroDivisionError("rational function with a zero denominator")
        if not num:
            num, den = ZERO, ONE
        else:
            g = pgcd(num, den)
            if pdeg(g) > 0:
                num, den = pdivmod(num, g)[0], pdivmod(den, g)[0]
            lead = den[-1]
            num, den = pscale(num, 1 / lead), pscale(den, 1 / lead)
        object.__setattr__(self, "num", num)
        object.__setattr__(self, "den", den)

    @classmethod
    def const(cls, c: Any) -> "Rat":
        return cls(ptrim([Fraction(c)]), ONE)

    @classmethod
    def variable(cls) -> "Rat":
        return cls((Fraction(0), Fraction(1)), ONE)

    @staticmethod
    def _lift(other: Any) -> "Rat":
        return other if isinstance(other, Rat) else Rat.const(other)

    def __add__(self, other: Any) -> "Rat":
        o = self._lift(other)
        if self.den == o.den:
            return Rat(padd(self.num, o.num), self.den)
        return Rat(padd(pmul(self.num, o.den), pmul(o.num, self.den)), pmul(self.den, o.den))

    __radd__ = __add__

    def __neg__(self) -> "Rat":
        return Rat(pscale(self.num, -1), self.den)

    def __sub__(self, other: Any) -> "Rat":
        return self + (-self._lift(other))

    def __rsub__(self, other: Any) -> "Rat":
        return self._lift(other) - self

    def __mul__(self, other: Any) -> "Rat":
        o = self._lift(other)
        return Rat(pmul(self.num, o.num), pmul(self.den, o.den))

    __rmul__ = __mul__

    def __truediv__(self, other: Any) -> "Rat":
        o = self._lift(other)
        if not o.num:
            raise ZeroDivisionError("division by the zero function")
        return Rat(pmul(self.num, o.den), pmul(self.den, o.num))

    def __rtruediv__(self, other: Any) -> "Rat":
        return self._lift(other) / self

    def __pow__(self, k: int) -> "Rat":
        if not isinstance(k, int):
            raise TypeError("integer exponents only")
        if k < 0:
            return Rat.const(1) / (self ** (-k))
        return Rat(ppow(self.num, k), ppow(self.den, k))

    def __eq__(self, other: object) -> bool:
        if not isinstance(other, (Rat, int, Fraction)):
            return NotImplemented
        o = self._lift(other)
        return self.num == o.num and self.den == o.den

    def __hash__(self) -> int:
        return hash((self.num, self.den))

    @property
    def is_const(self) -> bool:
        return pdeg(self.num) <= 0 and pdeg(self.den) == 0

    @property
    def excess(self) -> int:
        """``deg num - deg den`` (``> 0``: improper; the zero function has excess ``-inf``)."""
        return pdeg(self.num) - pdeg(self.den) if self.num else -10**9

    def value(self) -> Fraction:
        """The constant of a constant function."""
        if not self.is_const:
            raise ValueError("not a constant")
        return self.num[0] if self.num else Fraction(0)

    def at(self, x: Any) -> Any:
        return peval(self.num, x) / peval(self.den, x)

    def compose(self, image: "Rat") -> "Rat":
        """``self(image(y))``: substitute a rational function for the variable (exact)."""
        return pcompose_rat(self.num, image) / pcompose_rat(self.den, image)

    def __repr__(self) -> str:
        return f"Rat({[str(c) for c in self.num]}, {[str(c) for c in self.den]})"


def pcompose_rat(p: Poly, image: Rat) -> Rat:
    """``p(image)`` by Horner in rational-function arithmetic."""
    acc = Rat.const(0)
    for c in reversed(p):
        acc = acc * image + c
    return acc


# ---------------------------------------------------------------------------------------------
# the reader: what a user types after --environment / --controller / --operator / --param
# ---------------------------------------------------------------------------------------------
class ReadError(ValueError):
    """The text is not a rational expression the oracle can read (or names an unknown)."""


_TOKEN = re.compile(r"\s*(?:(\d+\.?\d*(?:[eE][+-]?\d+)?|\.\d+(?:[eE][+-]?\d+)?)|([A-Za-z_][A-Za-z0-9_]*)|(\*\*|[-+*/^()]))")


def read_number(text: str) -> Fraction:
    """A decimal as the exact rational it denotes (``1e-300`` is ``1/10**300``).

    >>> read_number("0.015"), read_number("1/3")
    (Fraction(3, 200), Fraction(1, 3))
    """
    try:
        return Fraction(text.strip())
    except (ValueError, ZeroDivisionError) as err:
        raise ReadError(f"not a number: {text!r}") from err


def _tokens(text: str) -> list[tuple[str, str]]:
    out, pos = [], 0
    text = text.rstrip()
    while pos < len(text):
        m = _TOKEN.match(text, pos)
        if not m or m.end() == pos:
            raise ReadError(f"cannot read {text[pos:]!r} in {text!r}")
        num, name, op = m.groups()
        out.append(("num", num) if num else ("name", name) if name else ("op", op))
        pos = m.end()
    return out


class _Parser:
    def __init__(self, text: str, variable: str, resolve):
        self.toks, self.i, self.var, self.resolve, self.text = _tokens(text), 0, variable, resolve, text

    def peek(self) -> tuple[str, str] | None:
        return self.toks[self.i] if self.i < len(self.toks) else None

    def take(self) -> tuple[str, str]:
        tok = self.peek()
        if tok is None:
            raise ReadError(f"unexpected end of {self.text!r}")
        self.i += 1
        return tok

    def parse(self) -> Rat:
        out = self.expr()
        if self.peek() is not None:
            raise ReadError(f"unexpected {self.peek()[1]!r} in {self.text!r}")
        return out

    def expr(self) -> Rat:
        acc = self.term()
        while self.peek() in (("op", "+"), ("op", "-")):
            op = self.take()[1]
            rhs = self.term()
            acc = acc + rhs if op == "+" else acc - rhs
        return acc

    def term(self) -> Rat:
        acc = self.unary()
        while self.peek() in (("op", "*"), ("op", "/")):
            op = self.take()[1]
            rhs = self.unary()
            acc = acc * rhs if op == "*" else acc / rhs
        return acc

    def unary(self) -> Rat:
        if self.peek() in (("op", "+"), ("op", "-")):
            op = self.take()[1]
            val = self.unary()
            return val if op == "+" else -val
        return self.power()

    def power(self) -> Rat:
        base = self.atom()
        if self.peek() in (("op", "**"), ("op", "^")):
            self.take()
            exponent = self.unary()
            if not exponent.is_const or exponent.value().denominator != 1:
                raise ReadError(f"exponent must be an integer constant in {self.text!r}")
            return base ** int(exponent.value())
        return base

    def atom(self) -> Rat:
        kind, val = self.take()
        if kind == "num":
            return Rat.const(read_number(val))
        if kind == "name":
            if self.peek() == ("op", "("):
                raise ReadError(f"function call {val}( in {self.text!r}")
            if val == self.var:
                return Rat.variable()
            return Rat.const(self.resolve(val))
        if val == "(":
            inner = self.expr()
            if self.take() != ("op", ")"):
                raise ReadError(f"missing ')' in {self.text!r}")
            return inner
        raise ReadError(f"unexpected {val!r} in {self.text!r}")


def read(text: str, variable: str, params: Mapping[str, Any] | None = None) -> Rat:
    """Read ``text`` as an exact rational function of ``variable`` with the parameters' values.

    A parameter value may be a number, a decimal string or an expression of other parameters
    (``K_0 = "K/2"``); an unknown name raises :class:`ReadError` (the oracle decides numbers
    only).

    >>> read("K + B*(z - 1)/(T*z)", "z", {"K": 2, "B": "0.01", "T": "1e-3"})
    Rat(['-10', '12'], ['0', '1'])
    >>> read("2^-1 + s", "s").num
    (Fraction(1, 2), Fraction(1, 1))
    """
    params = dict(params or {})
    cache: dict[str, Fraction] = {}

    def resolve(name: str, stack: tuple = ()) -> Fraction:
        if name in cache:
            return cache[name]
        if name not in params:
            raise ReadError(f"unknown name {name!r}")
        if name in stack:
            raise ReadError(f"parameter {name!r} is defined by itself")
        value = params[name]
        if isinstance(value, (int, Fraction)):
            out = Fraction(value)
        else:
            text_value = str(value)
            try:
                out = Fraction(text_value.strip())
            except (ValueError, ZeroDivisionError):
                inner = _Parser(text_value, "\0", lambda n: resolve(n, stack + (name,))).parse()
                if not inner.is_const:
                    raise ReadError(f"parameter {name!r} = {text_value!r} is not a number") from None
                out = inner.value()
        cache[name] = out
        return out

    return _Parser(text, variable, resolve).parse()
