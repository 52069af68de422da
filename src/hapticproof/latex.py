r"""LaTeX printing in the papers' notation (all printing of the toolkit lives here).

The printer maps SymPy symbols back to the names a paper prints (``K_{01}``, ``t_d``, ``z_a``,
``\omega``), writes ``c`` as ``\cos(\omega T)`` when asked, and renders conditions, matrices
and whole documents (amsmath) that compile with pdflatex.

>>> import sympy as sp
>>> K, T, b = sp.symbols('K T b', positive=True)
>>> to_latex(sp.Gt(b, K*T/2))
'b > \\frac{K T}{2}'
>>> from hapticproof.symbols import c
>>> to_latex(b - K*T/2 + 3*c, cos_name=r'\cos(\omega T)')
'- \\frac{K T}{2} + b + 3 \\cos(\\omega T)'
"""

from __future__ import annotations

import re
from collections.abc import Iterable, Mapping
from typing import Any

import sympy as sp

from hapticproof.symbols import c as C_SYM

__all__ = ["to_latex", "escape_text", "verbatim_block", "document", "symbol_names"]


def symbol_names(table: Mapping[str, Any] | None) -> dict[sp.Symbol, str]:
    """Invert a paper's printed-name table (printed name -> SymPy symbol)."""
    out: dict[sp.Symbol, str] = {}
    for printed, value in (table or {}).items():
        if isinstance(value, sp.Symbol) and value not in out:
            out[value] = printed
    return out


def _default_name(symbol: sp.Symbol) -> str:
    name = symbol.name
    greek = {"omega": r"\omega", "theta": r"\theta", "alpha": r"\alpha", "beta": r"\beta", "delta": r"\delta", "gamma": r"\gamma"}
    if name in greek:
        return greek[name]
    if "_" in name:
        head, _, tail = name.partition("_")
        head = greek.get(head, head)
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
    symbol_map: dict[sp.Symbol, str] = {}
    for symbol in obj.free_symbols if hasattr(obj, "free_symbols") else ():
        if isinstance(symbol, sp.Symbol):
            symbol_map[symbol] = _default_name(symbol)
    symbol_map.update(names or {})
    if cos_name is not None:
        symbol_map[C_SYM] = cos_name
    if isinstance(obj, (sp.And, sp.Or)):
        joiner = r", \quad " if isinstance(obj, sp.And) else r" \ \text{or}\ "
        return joiner.join(to_latex(arg, names, cos_name) for arg in obj.args)
    return sp.latex(obj, symbol_names=symbol_map, mat_str="bmatrix", mat_delim="")


_TEXT_SPECIALS = {
    "\\": r"\textbackslash{}",
    "{": r"\{",
    "}": r"\}",
    "$": r"\$",
    "&": r"\&",
    "#": r"\#",
    "%": r"\%",
    "_": r"\_",
    "^": r"\^{}",
    "~": r"\~{}",
}


def escape_text(text: str) -> str:
    r"""Escape plain text for LaTeX.

    >>> escape_text("b_1 > 50% & {x}")
    'b\\_1 > 50\\% \\& \\{x\\}'
    """
    return "".join(_TEXT_SPECIALS.get(ch, ch) for ch in text)


def verbatim_block(text: str) -> str:
    """Printed text shown verbatim (it may be OCR-damaged and not compile as LaTeX)."""
    return r"\begin{flushleft}\small\ttfamily " + escape_text(text) + r"\end{flushleft}"


def _balanced(text: str) -> bool:
    """Braces, parentheses and environments nest properly (escaped braces and
    ``\\left``/``\\right`` delimiters ignored)."""
    stripped = re.sub(r"\\(left|right|big|Big)[()\[\]|.]|\\[{}]", "", text)
    for opening, closing in ("{}", "()"):
        depth = 0
        for ch in stripped:
            depth += ch == opening
            depth -= ch == closing
            if depth < 0:
                return False
        if depth:
            return False
    stack: list[str] = []
    for kind, name in re.findall(r"\\(begin|end)\{([A-Za-z*]+)\}", text):
        if kind == "begin":
            stack.append(name)
        elif not stack or stack.pop() != name:
            return False
    return not stack


def display(latex: str) -> str:
    """A display-math block. Content with its own environments (aligned, bmatrix) is kept as it
    is; bare multi-line content goes into ``gathered`` (alignment marks dropped)."""
    if "\\begin{" in latex:
        return "\\begin{equation*}" + latex + "\\end{equation*}"
    if "\\\\" in latex or "&" in latex:
        body = latex.replace("&", "")
        return "\\begin{equation*}\\begin{gathered}" + body + "\\end{gathered}\\end{equation*}"
    return "\\begin{equation*}" + latex + "\\end{equation*}"


def document(title: str, sections: Iterable[tuple[str, str]]) -> str:
    """A complete amsmath document with the given (heading, body) sections."""
    parts = [
        r"\documentclass[10pt]{article}",
        r"\usepackage[a4paper,margin=2cm]{geometry}",
        r"\usepackage{amsmath,amssymb}",
        r"\allowdisplaybreaks",
        r"\setlength{\parindent}{0pt}",
        r"\begin{document}",
        r"\section*{" + escape_text(title) + "}",
    ]
    for heading, body in sections:
        parts.append(r"\subsection*{" + escape_text(heading) + "}")
        parts.append(body)
    parts.append(r"\end{document}")
    return "\n".join(parts) + "\n"


def safe_math(latex: str) -> str:
    """Display ``latex`` as math when it is structurally sound, verbatim otherwise.

    OCR-damaged printed equations may contain commands that do not compile; only balanced
    strings that use known commands are typeset.
    """
    if latex and _balanced(latex) and _known_commands(latex):
        return display(latex)
    return verbatim_block(latex or "(empty)")


_KNOWN = set(
    r"""frac dfrac tfrac left right cos sin tan exp sqrt omega alpha beta gamma delta theta pi
    Re Im min max sum lim to infty cdot times leq geq le ge neq ne quad qquad text mathrm
    operatorname mathbf mathcal det dots cdots ldots vdots ddots begin end bmatrix pmatrix
    matrix aligned gathered boxed ell hline mathbb partial mu sigma tau lambda
    implies Rightarrow rightarrow xrightarrow infty vert Vert lvert rvert prime succeq preceq iff
    operatorname Res displaystyle tfrac dot lbrace rbrace ddot bar hat tilde mathcal Longrightarrow Leftrightarrow
    Big big Bigg bigg int iint sqrt overline underline mid""".split()
)


def _known_commands(latex: str) -> bool:
    return all(cmd in _KNOWN for cmd in re.findall(r"\\([A-Za-z]+)", latex))
