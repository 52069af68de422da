r"""Is a value with square roots zero? Exact reduction, or a point where it is not.

Llewellyn's stability parameter divides by ``|z_{12} z_{21}|`` and a continuous two-port's
criterion carries ``\sqrt{b_s^2 + (m_s\omega - K_p/\omega)^2}``: the square root of a rational
function of the frequency that no rational algebra holds. :func:`values.evaluate` names each such
root (``$rad<k>``, its radicand a non-negative rational function); this module decides whether a
difference written with them is zero identically.

On the boundary the frequency is made rational first: ``omega > 0`` on the axis (``x = omega^2``,
``r = omega``), ``t = tan(theta/2) > 0`` on the circle (``c = (1 - t^2)/(1 + t^2)``,
``r = 2t/(1 + t^2)``); the other half of the boundary carries the conjugate values. Every radicand
is then factored over Q into irreducible polynomials ``p``: its root is a rational function times
``|q|`` for the squared factors (the sign known from the stated signs, else a case) times the
roots ``sqrt(p)`` of the factors of odd multiplicity. Roots of distinct irreducible polynomials
(and of distinct primes) are independent: a polynomial in them, each to the power 0 or 1, is zero
only when each coefficient is (Kummer). So the difference is zero exactly when every coefficient
cancels, and otherwise it is non-zero on an open set, where a rational point shows it.

>>> import sympy as sp
>>> b, w = sp.symbols("b omega", positive=True)
>>> zero_of(b/w * sp.sqrt(w**2 + b**2 * w**2) - b * sp.sqrt(1 + b**2), {}).zero
True
"""

from __future__ import annotations

import functools
from dataclasses import dataclass, field
from fractions import Fraction
from itertools import product
from typing import Any

import sympy as sp

from hapticproof.audit.definitions.values import RADICAL_PREFIX, Unsupported, Value, radicand
from hapticproof.exact.boundaryvalue import AXIS, C_NAME, X_NAME

__all__ = ["RootResult", "zero_of", "value_zero", "has_roots", "positive_multiple"]

#: the work bound: at most this many independent roots and sign cases
_MAX_ROOTS, _MAX_CASES = 8, 8
_OMEGA = sp.Symbol("omega", positive=True)
_T = sp.Symbol("t", positive=True)


@dataclass
class RootResult:
    """``zero``: ``True`` (identically), ``False`` (``witness`` a point where it is not),
    ``None`` (undecided, ``reason``). ``assumed``: the signs a zero needs that nothing states."""

    zero: bool | None
    witness: dict[str, str] | None = None
    assumed: list[str] = field(default_factory=list)
    reason: str = ""


def has_roots(value: Value) -> bool:
    """Whether ``value`` is written with a named square root."""
    return any(n.startswith(RADICAL_PREFIX) for n in value.names)


def value_zero(value: Value, signs: dict[str, dict[str, bool]]) -> RootResult:
    """Whether every entry of ``value`` (real and imaginary parts) is zero identically."""
    domain = None
    parts = []
    for row in value.rows:
        for e in row:
            if hasattr(e, "re0"):
                domain = e.domain
                parts += [(e.re0, e.re1), (e.im0, e.im1)]
            else:
                parts.append((e, None))
    symbols: dict[str, sp.Symbol] = {}
    exprs = [_to_sympy(even, odd, domain, signs, symbols) for even, odd in parts if not (even.is_zero and (odd is None or odd.is_zero))]
    found = RootResult(True)
    for expr in exprs:
        found = zero_of(expr, signs)
        if found.zero is not True:
            return found
    return found


def _to_sympy(even: Any, odd: Any, domain: str | None, signs: dict[str, dict[str, bool]], symbols: dict[str, sp.Symbol]) -> sp.Expr:
    """``even + r odd`` with the frequency rational and each named root as ``sqrt(radicand)``."""
    if domain == AXIS:
        t_image, r = _OMEGA**2, _OMEGA
    else:
        t_image, r = (1 - _T**2) / (1 + _T**2), 2 * _T / (1 + _T**2)

    def convert(f: Any) -> sp.Expr:
        table = {}
        for n in f.names:
            if n == C_NAME or n == X_NAME:
                table[n] = sp.Dummy(n)
            elif n.startswith(RADICAL_PREFIX):
                table[n] = sp.Dummy(n)
            else:
                sign = signs.get(n, {}) if "'" not in n else {}   # a complex entry's parts have no sign
                table[n] = symbols.setdefault(n, sp.Symbol(n, real=True, **sign))
        expr = f.to_sympy(table)
        images = {}
        for n, d in table.items():
            if n in (C_NAME, X_NAME):
                images[d] = t_image
            elif n.startswith(RADICAL_PREFIX):
                images[d] = sp.sqrt(convert(radicand(n)), evaluate=False)
        return expr.xreplace(images) if images else expr

    out = convert(even)
    if odd is not None and not odd.is_zero:
        out = out + r * convert(odd)
    return out


def zero_of(expr: Any, signs: dict[str, dict[str, bool]]) -> RootResult:
    """Whether the real expression ``expr`` (rational in its symbols and in square roots of
    rational functions) is zero identically; see the module doc."""
    quick = _witness(expr, signs, tries=3)
    if quick is not None:
        return RootResult(False, quick)         # non-zero at a point where every name is positive
    roots = sorted({p for p in sp.sympify(expr).atoms(sp.Pow) if p.exp.is_Rational and p.exp.q == 2}, key=sp.default_sort_key)
    basis: dict[sp.Expr, sp.Symbol] = {}
    images = {p: _root(p.base, basis) ** p.exp.p for p in roots}
    if len(basis) > _MAX_ROOTS:
        return RootResult(None, reason=f"more than {_MAX_ROOTS} independent square roots")
    reduced = sp.sympify(expr).xreplace(images)
    moduli = sorted(reduced.atoms(sp.Abs), key=sp.default_sort_key)
    if 2 ** len(moduli) > _MAX_CASES:
        return RootResult(None, reason="too many moduli of unknown sign")
    failing = []
    for case in product((1, -1), repeat=len(moduli)):
        chosen = {m: s * m.args[0] for m, s in zip(moduli, case)}
        if not _reduces_to_zero(reduced.xreplace(chosen), basis):
            failing.append(case)
    if not failing:
        return RootResult(True)
    witness = _witness(expr, signs)
    if len(failing) < 2 ** len(moduli):
        # zero when the moduli have some signs: say which, and show a point of a failing case
        holding = [c for c in product((1, -1), repeat=len(moduli)) if c not in failing]
        assumed = [f"{sp.sstr(m.args[0])} {'>=' if s > 0 else '<='} 0" for m, s in zip(moduli, holding[0])]
        return RootResult(None if witness is None else False, witness, assumed,
                          "zero only where " + " and ".join(assumed))
    if witness is None:
        return RootResult(None, reason="the reduced coefficients do not cancel, but no point where the sides differ was found")
    return RootResult(False, witness)


def positive_multiple(g: Any, h: Any) -> bool:
    """Whether ``g = m h`` with ``m > 0`` wherever both are defined (proved: the square roots
    reduced to a shared basis, the ratio cancelled, its sign known from the symbols' signs).

    >>> a, b = sp.symbols("a b", real=True)
    >>> positive_multiple((a - sp.sqrt(a**2 + b**2)) / sp.sqrt(4*a**2 + 4*b**2), a - sp.sqrt(a**2 + b**2))
    True
    """
    basis: dict[sp.Expr, sp.Symbol] = {}
    reduced = []
    for e in (sp.sympify(g), sp.sympify(h)):
        roots = {p for p in e.atoms(sp.Pow) if p.exp.is_Rational and p.exp.q == 2}
        try:
            e = e.xreplace({p: _root(p.base, basis) ** p.exp.p for p in roots})
        except Unsupported:
            return False
        if e.has(sp.Abs) or e == 0:
            return False
        reduced.append(e)
    if len(basis) > _MAX_ROOTS:
        return False
    ratio = sp.cancel(sp.together(reduced[0] / reduced[1]))
    return bool(ratio.is_positive)


def _root(radicand_expr: sp.Expr, basis: dict[sp.Expr, sp.Symbol]) -> sp.Expr:
    """``sqrt(radicand)`` as rational * ``|squared factors|`` * basis roots of odd factors."""
    out = sp.Integer(1)
    flip = False
    for (coeff, factors), power in zip(_factored(radicand_expr), (1, -1)):
        if coeff < 0:
            flip = not flip
            coeff = -coeff
        out *= _rational_root(coeff, basis) ** power
        for f, e in factors:
            if e // 2:
                out *= sp.Abs(f) ** (power * (e // 2)) if (e // 2) % 2 else f ** (power * (e // 2))
            if e % 2:
                if flip:
                    f, flip = -f, False
                out *= _basis(sp.expand(f), basis) ** power
    if flip:
        raise Unsupported("the square root of a negative quantity")
    return out


@functools.lru_cache(maxsize=512)
def _factored(radicand_expr: sp.Expr) -> tuple[tuple[sp.Rational, list[tuple[sp.Expr, int]]], ...]:
    """The numerator's and the denominator's content and irreducible factors over Q."""
    num, den = sp.fraction(sp.factor(sp.cancel(radicand_expr)))
    out = []
    for part in (num, den):
        coeff, factors = sp.factor_list(part)
        out.append((sp.Rational(coeff), factors))
    return tuple(out)


def _rational_root(q: sp.Rational, basis: dict[sp.Expr, sp.Symbol]) -> sp.Expr:
    if q == 0:
        return sp.Integer(0)
    if max(abs(q.p), q.q).bit_length() > 200:
        raise Unsupported("a square root of a number with more than 60 digits")
    out = sp.Integer(1)
    for n, power in ((q.p, 1), (q.q, -1)):
        for prime, e in sp.factorint(n).items():
            out *= sp.Integer(prime) ** (power * (e // 2))
            if e % 2:
                out *= _basis(sp.Integer(prime), basis) ** power
    return out


def _basis(p: sp.Expr, basis: dict[sp.Expr, sp.Symbol]) -> sp.Symbol:
    if p not in basis:
        basis[p] = sp.Symbol(f"sqrt{len(basis)}", positive=True)
    return basis[p]


def _reduces_to_zero(expr: sp.Expr, basis: dict[sp.Expr, sp.Symbol]) -> bool:
    """Zero once each basis root squared is its polynomial: every coefficient of the square-free
    monomials in the roots cancels."""
    numerator = sp.numer(sp.together(expr))
    roots = list(basis.values())
    if not roots:
        return sp.expand(numerator) == 0
    squares = {s: p for p, s in basis.items()}
    poly = sp.Poly(sp.expand(numerator), *roots)
    collected: dict[tuple[int, ...], sp.Expr] = {}
    for monomial, coeff in poly.terms():
        factor = sp.Mul(*(squares[s] ** (e // 2) for s, e in zip(roots, monomial)))
        key = tuple(e % 2 for e in monomial)
        collected[key] = collected.get(key, 0) + coeff * factor
    return all(sp.expand(c) == 0 for c in collected.values())


def _witness(expr: sp.Expr, signs: dict[str, dict[str, bool]], tries: int = 60) -> dict[str, str] | None:
    """A rational point (the stated signs kept, the frequency inside its range) where ``expr`` is
    clearly non-zero: 40 significant digits, the value far from the rounding. The first 30 tries
    take every name positive."""
    import random

    rng = random.Random(11)
    symbols = sorted(sp.sympify(expr).free_symbols, key=lambda s: s.name)
    choices = [Fraction(1, 2), Fraction(1), Fraction(2), Fraction(3), Fraction(5, 3), Fraction(7, 10), Fraction(4)]
    for attempt in range(tries):
        point = {}
        for s in symbols:
            v = rng.choice(choices)
            if attempt >= 30 and not (s.is_nonnegative or s.is_positive) and rng.random() < 0.5:
                v = -v
            point[s] = sp.Rational(v.numerator, v.denominator)
        try:
            value = sp.sympify(expr).xreplace(point)
            if value.has(sp.zoo, sp.nan) or any(p.base.is_negative for p in value.atoms(sp.Pow) if p.exp.is_Rational and p.exp.q == 2):
                continue
            number = sp.N(value, 40)
        except (ZeroDivisionError, TypeError, ValueError):
            continue
        if not number.is_real or not number.is_finite:
            continue
        if abs(number) > sp.Float("1e-25"):
            return _shown(point, number)
    return None


def _shown(point: dict[sp.Symbol, sp.Rational], difference: sp.Expr) -> dict[str, str]:
    out: dict[str, str] = {}
    complex_parts: dict[str, dict[str, sp.Rational]] = {}
    for s, v in point.items():
        if s == _T:
            out["c"] = str((1 - v**2) / (1 + v**2))
            out["sin(theta)"] = str(2 * v / (1 + v**2))
        elif "'" in s.name:
            name, part = s.name.split("'")
            complex_parts.setdefault(name, {})[part] = v
        else:
            out[s.name] = str(v)
    for name, parts in complex_parts.items():
        out[name] = sp.sstr(parts.get("re", 0) + sp.I * parts.get("im", 0))
    out["difference"] = sp.sstr(sp.Float(difference, 12))
    return out
