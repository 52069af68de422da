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

import math
from typing import Any

import flint
import sympy as sp

from hapticproof.exact.unitcircle import CRational

__all__ = ["brief", "number", "full_text", "poly_text", "tidy", "plural", "witness_text", "LIMIT"]

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


def brief(expr: Any, limit: int = LIMIT, verbose: bool = False, names: Any = None) -> str:
    """``sstr(expr)`` when at most ``limit`` characters (or ``verbose``), else a summary.

    A numeric c-form (``num``/``den`` flint polynomials) is summarised from its coefficients,
    and an expression with far more terms than fit is summarised without printing it first.
    ``names`` (a :class:`~hapticproof.core.naming.Naming`) prints the toolkit's symbols under
    the scene's names (``gamma`` for ``c``)."""
    if hasattr(expr, "num") and isinstance(getattr(expr, "num", None), flint.fmpq_poly):
        if verbose or max(expr.num.degree(), expr.den.degree()) <= 12:
            text = full_text(expr, names)
            if verbose or len(text) <= limit:
                return text
        return _flint_brief(expr.num, expr.den, _var_name(expr, names))
    variables = _VARIABLES
    if names is not None and not isinstance(expr, str):
        expr = names.renamed(expr)
        variables = ("z", names.helper("cos"), "s", names.helper("x"), names.helper("theta"))
    if not verbose and isinstance(expr, sp.Expr):
        num, den = sp.fraction(expr)
        if len(sp.Add.make_args(num)) + len(sp.Add.make_args(den)) > limit // 4:
            return _summary(expr, None, variables)
    text = sp.sstr(expr)
    if verbose or len(text) <= limit:
        return text
    if isinstance(expr, (list, tuple)):
        return f"{len(expr)} entries, {len(text)} characters [full text: --verbose or --format json]"
    if isinstance(expr, sp.core.relational.Relational):         # a long condition: each side summarised
        return f"{brief(expr.lhs, limit // 2)} {expr.rel_op} {brief(expr.rhs, limit // 2)}"
    if isinstance(expr, sp.core.function.AppliedUndef) and len(expr.args) == 1:     # min_c(<long form>)
        return f"{expr.func}({brief(expr.args[0], limit)})"
    if not isinstance(expr, sp.Expr):
        return f"{len(text)} characters [full text: --verbose or --format json]"
    return _summary(expr, text, variables)


def _summary(expr: Any, text: str | None, variables: tuple[str, ...] = _VARIABLES) -> str:
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
    var = next((names[v] for v in variables if v in names), None)
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


def plural(count: int, word: str, many: str | None = None) -> str:
    """``1 equation``, ``2 equations``.

    >>> plural(1, "equation"), plural(3, "equation"), plural(2, "matrix", "matrices")
    ('1 equation', '3 equations', '2 matrices')
    """
    return f"{count} {word if count == 1 else (many or word + 's')}"


def tidy(expr: Any) -> Any:
    """An exact expression in a readable normal form: a polynomial expanded with its rationals
    reduced (no common power-of-two scale left over from the exact arithmetic), the imaginary
    part collected behind ``I``, a rational function as one fraction.

    >>> s_theta, B, c = sp.symbols("s_theta B c")
    >>> tidy(2*B*c + sp.I*s_theta*(8192*B*c - 4096*B)/4096)
    2*B*c + I*s_theta*(2*B*c - B)
    """
    expr = sp.sympify(expr)
    if not isinstance(expr, sp.Expr) or not expr.free_symbols:
        return expr
    expanded = sp.expand(expr)
    real, imag = expanded.as_independent(sp.I, as_Add=True)
    imag = sp.expand(imag / sp.I) if imag != 0 else sp.Integer(0)

    def one(part: sp.Expr) -> sp.Expr:
        num, den = sp.fraction(sp.cancel(sp.together(part)))
        if not den.free_symbols:
            return sp.expand(part)
        return sp.Mul(sp.expand(num), sp.Pow(sp.expand(den), -1), evaluate=False)

    real = one(real)
    if imag == 0:
        return real
    helpers = sorted((s for s in imag.free_symbols if s.name in ("s_theta", "S_n")), key=str)
    imag = sp.collect(one(imag), helpers) if helpers else one(imag)
    return real + sp.I * imag


def witness_text(witness: Any, names: Any = None) -> str:
    """A witness as ``name = value`` pairs: a point ``z`` as ``x + j*y``, numbers by :func:`number`;
    the keys in the scene's naming ``names`` (``gamma`` for ``c``, ``omega*h`` for ``omega_T``).

    >>> witness_text({"c": "-3/5", "z": ["-3/5", "4/5"], "omega_T": "2*atan(2)"})
    'c = -3/5, z = -3/5 + j*4/5, omega_T = 2*atan(2)'
    """
    out = []
    # the circle's keys by the scene's names; other keys are the scene's own already (a key "h"
    # is the user's period, not a toolkit word to rename)
    shown_witness = names.witness(dict(witness)) if names is not None else dict(witness)
    for key, value in shown_witness.items():
        if isinstance(value, (list, tuple)) and len(value) == 2:
            re, im = (str(v) for v in value)
            shown = f"{re} - j*{im[1:]}" if im.startswith("-") else f"{re} + j*{im}"
        elif isinstance(value, (list, tuple)):
            shown = "(" + ", ".join(str(v) for v in value) + ")"
        else:
            try:
                shown = number(sp.Rational(str(value))) if "/" in str(value) or str(value).lstrip("-").isdigit() else str(value)
            except (TypeError, ValueError):
                shown = str(value)
        out.append(f"{key} = {shown}")
    return ", ".join(out)


def number(value: Any, digits: int = 15) -> str:
    """A number for text output: exact rationals exactly (a huge power-of-two denominator from a
    certified enclosure as a decimal, with the exact value after it), other exact numbers with a
    decimal, arb balls as decimals, infinity in words.

    >>> number(sp.Rational(805306367, 2**30))
    '0.749999999068677 (exactly 805306367/2**30)'
    """
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
        q = int(value.q)
        if q >= 2**20 and q & (q - 1) == 0:
            return f"{sp.N(value, digits)} (exactly {value.p}/2**{q.bit_length() - 1})"
        return str(value)
    if value.is_number:
        return f"{sp.sstr(value)} ~ {sp.N(value, digits)}"
    return sp.sstr(value)




def _var_name(form: Any, names: Any) -> str:
    """The printed name of a c-form's variable (the toolkit's ``c`` under the scene's name)."""
    var = getattr(form, "var", None)
    if names is not None and var is not None:
        return names.text(var)
    return str(var if var is not None else "c")


def full_text(value: Any, names: Any = None) -> str:
    """Full text of an expression; a numeric c-form is written from its flint coefficients, as
    one polynomial when its denominator is a constant (``c/1000 + 19/1000``) and otherwise as a
    ratio of integer polynomials with no common content (``(3*c + 1)/(2*c - 2)``).

    >>> from hapticproof.exact.unitcircle import CRational
    >>> full_text(CRational(flint.fmpq_poly([flint.fmpq(19, 500), flint.fmpq(1, 500)]), flint.fmpq_poly([2])))
    'c/1000 + 19/1000'
    """
    if isinstance(value, CRational) and value.is_numeric:
        var = _var_name(value, names)
        num, den = flint.fmpq_poly(value.num), flint.fmpq_poly(value.den)
        if den.degree() <= 0:
            return poly_text(num / den.coeffs()[0], var)
        scale = 1
        for a in num.coeffs() + den.coeffs():
            scale = scale * int(a.q) // math.gcd(scale, int(a.q))
        num, den = num * scale, den * scale
        content = 0
        for a in num.coeffs() + den.coeffs():
            content = math.gcd(content, int(a.p))
        sign = -1 if den.coeffs()[-1] < 0 else 1
        num, den = num * flint.fmpq(sign, content or 1), den * flint.fmpq(sign, content or 1)
        return f"({poly_text(num, var)})/({poly_text(den, var)})"
    return sp.sstr(value) if names is None or isinstance(value, str) else names.text(value)


def poly_text(p: Any, var: str) -> str:
    """A flint polynomial as text in ``var``, highest power first, in SymPy's style
    (``3*c**2 - c/2 + 1``).

    >>> poly_text(flint.fmpq_poly([1, flint.fmpq(-1, 2), 3]), "c")
    '3*c**2 - c/2 + 1'
    """
    terms = []
    for k, a in enumerate(p.coeffs()):
        if a == 0:
            continue
        num, den = abs(int(a.p)), int(a.q)
        power = "" if k == 0 else var if k == 1 else f"{var}**{k}"
        if not power:
            body = str(num) if den == 1 else f"{num}/{den}"
        else:
            body = (power if num == 1 else f"{num}*{power}") + ("" if den == 1 else f"/{den}")
        terms.append(("-" if a < 0 else "+", body))
    if not terms:
        return "0"
    terms.reverse()
    text = ("-" if terms[0][0] == "-" else "") + terms[0][1]
    return text + "".join(f" {sign} {body}" for sign, body in terms[1:])
