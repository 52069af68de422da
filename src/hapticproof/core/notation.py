r"""SymPy expressions as LaTeX in the papers' notation: symbols back to the names a paper
prints (``K_{01}``, ``t_d``, ``z_a``, ``\omega``), ``c`` written as ``\cos(\omega T)`` when asked,
relations, boolean combinations and matrices; and huge exact numbers shortened in the sentences of
reasons (:func:`shorten_numbers`). Documents and displays are built on it in
:mod:`hapticproof.report.latex`.

>>> import sympy as sp
>>> K, T, b = sp.symbols('K T b', positive=True)
>>> to_latex(sp.Gt(b, K*T/2))
'b > \\frac{K T}{2}'
>>> from hapticproof.core.symbols import c
>>> to_latex(b - K*T/2 + 3*c, cos_name=r'\cos(\omega T)')
'- \\frac{K T}{2} + b + 3 \\cos(\\omega T)'
"""

from __future__ import annotations

import re
from collections.abc import Mapping
from typing import Any

import sympy as sp

from hapticproof.core.symbols import c as C_SYM

__all__ = ["to_latex", "symbol_names", "default_name", "shorten_numbers"]


def symbol_names(table: Mapping[str, Any] | None) -> dict[sp.Symbol, str]:
    """Invert a paper's printed-name table (printed name -> SymPy symbol)."""
    out: dict[sp.Symbol, str] = {}
    for printed, value in (table or {}).items():
        if isinstance(value, sp.Symbol) and value not in out:
            out[value] = printed
    return out


_GREEK = {"omega": r"\omega", "theta": r"\theta", "alpha": r"\alpha", "beta": r"\beta", "delta": r"\delta",
          "gamma": r"\gamma"}


def default_name(symbol: sp.Symbol | str) -> str:
    r"""The LaTeX of a symbol's name: Greek letters by name, ``K_12`` as ``K_{12}``, ``K01`` as ``K_{01}``.

    >>> default_name("omega"), default_name("b_m"), default_name("K12")
    ('\\omega', 'b_{m}', 'K_{12}')
    """
    name = symbol if isinstance(symbol, str) else symbol.name
    if name in _GREEK:
        return _GREEK[name]
    if "_" in name:
        head, _, tail = name.partition("_")
        head = _GREEK.get(head, head)
        return f"{head}_{{{tail}}}"
    match = re.fullmatch(r"([A-Za-z]+?)(\d+)", name)
    if match and len(match.group(1)) == 1:
        return f"{match.group(1)}_{{{match.group(2)}}}"
    return name


def to_latex(
    obj: Any,
    names: Mapping[sp.Symbol, str] | None = None,
    cos_name: str | None = None,
) -> str:
    """LaTeX of a SymPy expression, relation, boolean combination or matrix.

    ``names`` overrides symbol names (printed notation); ``cos_name`` prints ``c`` as the
    given text (e.g. ``\\cos(\\omega T)``).
    """
    if isinstance(obj, str):
        return obj
    obj = sp.sympify(obj)
    if obj is sp.true or obj is sp.false:       # a condition that holds identically (or never): words, not True
        return r"\text{holds for every value}" if obj is sp.true else r"\text{holds for no value}"
    symbol_map: dict[sp.Symbol, str] = {}
    for symbol in obj.free_symbols if hasattr(obj, "free_symbols") else ():
        if isinstance(symbol, sp.Symbol):
            symbol_map[symbol] = default_name(symbol)
    symbol_map.update(names or {})
    if cos_name is not None:
        symbol_map[C_SYM] = cos_name
    if isinstance(obj, (sp.And, sp.Or)):
        joiner = r", \quad " if isinstance(obj, sp.And) else r" \ \text{or}\ "
        return joiner.join(to_latex(arg, names, cos_name) for arg in obj.args)
    text = sp.latex(obj, symbol_names=symbol_map, mat_str="bmatrix", mat_delim="")
    if r"\operatorname{min}_{c}" in text or r"\operatorname{sup}_{c}" in text:
        # the worst case over the circle: over the angle when c is printed as cos(omega T), else
        # over c under its printed name (gamma when c is taken)
        over = cos_name[len("\\cos("):-1] if cos_name and cos_name.startswith("\\cos(") and cos_name.endswith(")") \
            else symbol_map.get(C_SYM, "c")
        for extremum in ("min", "sup"):
            text = text.replace(rf"\operatorname{{{extremum}}}_{{c}}", rf"\{extremum}_{{{over}}}")
    return text


def shorten_numbers(text: str, digits: int = 40, verbose: bool = False) -> str:
    """Integers of more than ``digits`` digits in a sentence abbreviated (exact data stays in JSON).

    >>> shorten_numbers("Re G^-1(c) = -" + "7" * 60 + "/3 < 0")
    'Re G^-1(c) = -<60-digit integer>/3 < 0'
    """
    import re

    if verbose:
        return text
    return re.sub(r"\d{%d,}" % digits, lambda m: f"<{len(m.group(0))}-digit integer>", text)
