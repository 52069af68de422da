"""Readable text for large exact objects: a one-line summary instead of a 300 KB polynomial.

Text output shows an expression in full when it is short, and otherwise says what it is
(variable, degrees, number of terms); JSON output and ``--verbose`` keep everything. Numbers
print as numbers: exact rationals as ``p/q``, certified balls as decimals, ``oo`` as
"unbounded" -- never as the raw dictionaries of the JSON form.

>>> from hapticproof.core.symbols import z
>>> brief(sum(z**k for k in range(400)) / (z - 1), limit=80)
'rational function of z: numerator degree 399 (400 terms), denominator degree 1 (2 terms) [full text: --verbose or --format json]'
>>> number(sp.oo), number(sp.Rational(3, 7)), number(sp.sqrt(2))
('unbounded (oo)', '3/7', 'sqrt(2) ~ 1.41421356237310')
"""

from __future__ import annotations

from typing import Any

import flint
import sympy as sp

from hapticproof.exact.unitcircle import CRational

__all__ = ["brief", "number", "full_text", "poly_text", "LIMIT"]

#: Characters up to which an expression is printed in full in text output.
LIMIT = 400

_VARIABLES = ("z", "c", "s", "x", "theta")


def _degree_terms(expr: sp.Expr, var: sp.Symbol | None) -> tuple[int | None, int]:
    terms = sp.Add.make_args(sp.expand(expr) if len(sp.Add.make_args(expr)) == 1 and expr.is_Mul else expr)
    if var is None:
        return None, len(terms)
    degree = 0
    for term in terms:
        if not isinstance(term, sp.Expr):
            continue
        powers = term.as_powers_dict()
        exp = sp.sympify(powers.get(var, 0))
        if exp.is_Integer:
            degree = max(degree, int(exp))
    return degree, len(terms)


def _flint_brief(num: Any, den: Any, var: str) -> str:
    terms = lambda p: sum(1 for a in p.coeffs() if a != 0)  # noqa: E731
    if den.degree() == 0:
        return f"polynomial of {var}: degree {num.degree()}, {terms(num)} terms [full text: --verbose or --format json]"
    return (f"rational function of {var}: numerator degree {num.degree()} ({terms(num)} terms), denominator degree "
            f"{den.degree()} ({terms(den)} terms) [full text: --verbose or --format json]")


def brief(expr: Any, limit: int = LIMIT, verbose: bool = False) -> str:
    """``sstr(expr)`` when at most ``limit`` characters (or ``verbose``), else a summary.

    A numeric c-form (``num``/``den`` flint polynomials) is summarised from its coefficients,
    and an expression with far more terms than fit is summarised without printing it first."""
    if hasattr(expr, "num") and isinstance(getattr(expr, "num", None), flint.fmpq_poly):
        if verbose or max(expr.num.degree(), expr.den.degree()) <= 12:
            text = full_text(expr)
            if verbose or len(text) <= limit:
                return text
        return _flint_brief(expr.num, expr.den, str(getattr(expr, "var", "c")))
    if not verbose and isinstance(expr, sp.Expr):
        num, den = sp.fraction(expr)
        if len(sp.Add.make_args(num)) + len(sp.Add.make_args(den)) > limit // 4:
            return _summary(expr, None)
    text = sp.sstr(expr)
    if verbose or len(text) <= limit:
        return text
    if isinstance(expr, (list, tuple)):
        return f"{len(expr)} entries, {len(text)} characters [full text: --verbose or --format json]"
    return _summary(expr, text)


def _summary(expr: Any, text: str | None) -> str:
    expr = sp.sympify(expr)
    if isinstance(expr, sp.Rel):        # a long condition: each side summarised (``--delay 16``)
        sides = [brief(side, LIMIT // 2).replace(" [full text: --verbose or --format json]", "")
                 for side in (expr.lhs, expr.rhs)]
        return f"{sides[0]} {expr.rel_op} {sides[1]} [full text: --verbose or --format json]"
    if isinstance(expr, sp.core.function.AppliedUndef) and len(expr.args) == 1:   # min_c(...)
        inner = brief(expr.args[0], LIMIT // 2).replace(" [full text: --verbose or --format json]", "")
        return f"{expr.func}({inner}) [full text: --verbose or --format json]"
    if isinstance(expr, sp.logic.boolalg.BooleanFunction):
        return (f"{type(expr).__name__} of {len(expr.args)} conditions ({len(sp.sstr(expr))} characters) "
                "[full text: --verbose or --format json]")
    names = {s.name: s for s in getattr(expr, "free_symbols", set())}
    var = next((names[v] for v in _VARIABLES if v in names), None)
    if isinstance(expr, sp.MatrixBase):
        size = f" ({len(text)} characters)" if text is not None else ""
        return f"{expr.rows}x{expr.cols} matrix{size} [full text: --verbose or --format json]"
    num, den = sp.fraction(expr) if isinstance(expr, sp.Expr) else (expr, sp.Integer(1))
    of = f" of {var}" if var is not None else ""
    dn, tn = _degree_terms(num, var)
    if den == 1:
        degree = f" degree {dn}," if dn is not None else ""
        return f"polynomial{of}:{degree} {tn} terms [full text: --verbose or --format json]"
    dd, td = _degree_terms(den, var)
    shown = (lambda d, t: f"degree {d} ({t} terms)" if d is not None else f"{t} terms")  # noqa: E731
    return (f"rational function{of}: numerator {shown(dn, tn)}, denominator {shown(dd, td)} "
            "[full text: --verbose or --format json]")


def number(value: Any, digits: int = 15) -> str:
    """A number for text output: exact rationals exactly, other exact numbers with a decimal,
    arb balls as decimals, infinity in words."""
    if value is None:
        return "none"
    if isinstance(value, flint.arb):
        return value.str(digits, radius=False)
    if isinstance(value, (int, float)):
        return str(value)
    value = sp.sympify(value)
    if value in (sp.oo, sp.zoo):
        return "unbounded (oo)"
    if value == -sp.oo:
        return "-oo"
    if value.is_Rational:
        return str(value)
    if value.is_number:
        return f"{sp.sstr(value)} ~ {sp.N(value, digits)}"
    return sp.sstr(value)




def full_text(value: Any) -> str:
    """Full text of an expression; a numeric c-form is written from its flint coefficients."""
    if isinstance(value, CRational) and value.is_numeric:
        num = poly_text(value.num, str(value.var))
        return num if value.den.degree() == 0 and value.den.coeffs()[0] == 1 else f"({num})/({poly_text(value.den, str(value.var))})"
    return sp.sstr(value)


def poly_text(p: Any, var: str) -> str:
    """A flint polynomial as text in ``var``, highest power first (``3*c**2 - 1/2*c + 1``)."""
    terms = []
    for k, a in enumerate(p.coeffs()):
        if a == 0:
            continue
        coeff = str(a.p) if a.q == 1 else f"{a.p}/{a.q}"
        terms.append(coeff if k == 0 else f"{coeff}*{var}" + (f"**{k}" if k > 1 else ""))
    return " + ".join(reversed(terms)).replace("+ -", "- ") or "0"
