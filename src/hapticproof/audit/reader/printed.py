r"""Parse the printed LaTeX dialect of the audited papers into SymPy.

The three papers print their equations in a loose LaTeX dialect (and the transcriptions add OCR
damage).  SymPy's ``parse_latex`` cannot read it: names such as ``K_{01}`` or ``k_{pmxy}``,
implicit products such as ``KTS``, ``\min_i``, ``\Re\{\cdot\}`` and ``bmatrix`` all defeat it.
This module is the project's own reader.  It is **driven by a symbol table**
(:class:`SymbolTable`): a name the table does not know is an error, never a guess.

The dialect
-----------
Names
    A name is a base (a letter, a Greek command such as ``\omega``, or a decorated letter such as
    ``\mathbf{Z}``, ``\mathcal{Z}``, ``\mathscr{M}``, ``\bar{C}``, ``\dot{x}``) followed by primes
    and ``_``/``^`` scripts, exactly as LaTeX groups them: ``Kt_d`` is ``K`` times ``t_d``, and
    ``k_{pmxy}`` is one name.  Letter runs are split one letter per factor unless the table (or
    the built-in words ``det`` and ``diag``) knows a longer word, longest match first.  A name is
    looked up after :func:`normalise_name` (so ``t_d``, ``t_{d}`` and ``t_{ d }`` are one name).
    A one-character script must really be one character: ``K_01`` raises (write ``K_{01}``).
Implicit products
    Juxtaposition multiplies, left to right (order matters for matrices).  A number may only open
    a product (``2B`` is fine, ``B2`` raises).  ``a / b c`` raises: it reads ``(a/b)c`` in one
    convention and ``a/(bc)`` in another, so use ``\frac`` or parentheses.
Function application
    ``H(z)`` applies ``H`` only when ``H`` is one of the table's *functions*; otherwise ``B(z-1)``
    is a product.  Functions may also be applied with braces (``\mathscr{Z}\{v_h/s\}``) and to
    several arguments (``h(t, u)``).  ``G^{-1}(z)`` uses the table's ``G^{-1}`` if present, else
    ``G(z)^{-1}``; ``G^T(z)`` likewise transposes.
Elementary functions
    ``\cos``, ``\sin``, ``\tan``, ``\exp``, ``\ln``... take a parenthesised argument, or else the
    implicit product that follows (``\cos \omega T`` is ``cos(omega*T)``; the run stops at the
    next function and an explicit ``*`` or ``/`` right after it is an ambiguity error).
    ``e^{x}`` is ``exp(x)`` and ``j`` is the imaginary unit (both configurable per table).
Real parts, determinants, norms
    ``\Re``, ``\text{Re}``, ``\operatorname{Re}``, ``\mathrm{Re}`` with ``( )``, ``\{ \}``, or an
    implicit-product argument give ``re``; ``det``/``\det`` give an unevaluated
    :class:`sympy.Determinant`; ``|x|`` gives ``Abs`` (a ``|`` after an operand closes the
    innermost open bar: nest with ``\left|``); ``\|X\|_\infty`` gives an unevaluated
    :class:`Norm`.  Superscripts that are not powers (the teleoperation paper's ``^c``) get their
    meaning from the table's ``superscripts``.
Indexed operators
    ``\min(a, b)``/``\max(...)`` are ``Min``/``Max``.  ``\min_i``, ``\max_{i,j \neq i}\{...\}``
    give unevaluated :class:`IndexedMin`/:class:`IndexedMax` over the users ``1..m`` and
    ``\sum_{k=1, k \neq i}^{m}`` gives a ``Sum`` (the condition becomes a ``Piecewise``).  The
    body of ``\min_i``/``\max_i`` is the ``\{...\}`` group after it, else the implicit product
    that follows; a summand extends over the whole product (``\sum_j (a_j + b)X_j`` sums
    ``(a_j + b)X_j``), as the papers' multi-user sums need.  Inside
    them, subscripts such as ``b_i``, ``K_{0i}``, ``K_{ij}`` or ``z_{3i-2,3j}`` are members of the
    table's :class:`IndexedFamily` s; :func:`expand_indexed` turns everything into concrete
    symbols for a given number of users ``m``.  ``\lim_{x \to a}`` gives :class:`PrintedLimit`
    (the papers take limits in an *expression*: ``\lim_{\cos(\omega T)\to 1}``), and
    ``\int_a^b f\, d\tau`` gives an unevaluated ``Integral``.
Matrices
    ``bmatrix``/``pmatrix``/``matrix`` give an ``ImmutableMatrix`` (a ``BlockMatrix`` when the
    entries are matrices), ``vmatrix`` a ``Determinant``, ``cases`` a ``Piecewise`` and
    ``[a, b]`` a row vector.  ``\dots``, ``\cdots``, ``\vdots`` and ``\ddots`` are kept as
    :class:`Elision` atoms: a matrix printed with ellipses comes back as a matrix holding them
    (see :func:`has_elision`), never as a made-up concrete matrix.
Statements
    A display is one :class:`Statement`: an :class:`Expression` (no relation: the caller decides
    whether that is malformed), a :class:`Relation` chain (``0 < a < b``, ``F = bV + ... = GV``;
    ``>``, ``<``, ``=``, ``\geq``/``\ge``, ``\leq``/``\le``, ``\neq``/``\ne``), a
    :class:`Qualified` statement (``..., \quad i = 1, 2, \dots, 6`` or ``..., j \neq i``), or
    :class:`Lines`.  Lines come from ``\\`` (inside or outside ``aligned``/``split``/``gathered``,
    possibly ``\boxed``), comma-separated clauses and ``\implies``/``\xrightarrow{}`` steps.  A
    ``\\`` is a line *wrap*, not a new statement, when the line before it has no relation yet,
    ends with an operator, or the next line starts with an operator or a relation.  ``\tag{..}``,
    a final ``\quad (15a)`` and, after a relation, a final `` (48)`` are equation numbers (a
    lone ``(36)`` is an orphaned number and raises); ``\text{A)}`` at the
    start is a label; ``\quad``, ``\,``, ``\;``, ``\left``/``\right`` sizes and final ``.``/``,``
    are layout.

Strictness: unknown names, unbalanced delimiters, relations inside arguments, dangling operators
and prose in ``\text{...}`` raise :class:`~hapticproof.core.errors.LatexParseError` carrying the
0-based character offset in the original string.  OCR damage that is still well-formed LaTeX is
parsed exactly as printed (``\cos(\omega t_d - T)`` is ``cos(omega*t_d - T)``).

>>> import sympy as sp
>>> K, T, B, b, w = sp.symbols('K T B b omega', positive=True)
>>> table = SymbolTable({'K': K, 'T': T, 'B': B, 'b': b, r'\omega': w})
>>> stmt = parse_printed(r'b > \frac{KT}{2} - B\cos(\omega T) \tag{17}', table)
>>> stmt.ops, stmt.rhs, stmt.tag
(('>',), -B*cos(T*omega) + K*T/2, '17')
>>> parse_printed(r'\cos(\omega T = -1)', table)
Traceback (most recent call last):
...
hapticproof.core.errors.LatexParseError: relation symbol '=' inside the argument of \cos at position 14 (near '\\cos(\\omega T = -1)')
"""

from __future__ import annotations

import re

from collections.abc import Iterator
from dataclasses import replace
from typing import Any


from hapticproof.core.errors import LatexParseError
from hapticproof.core.limits import LimitError, check_depth, current
from hapticproof.audit.reader.grammar import Parser
from hapticproof.audit.reader.lexer import ALIGN_ENVS, LABEL, Token, closer_key, demote_separators, is_binary, is_relation, matching_close, opener_key, tokenize
from hapticproof.audit.reader.names import SymbolTable
from hapticproof.audit.reader.statements import Expression, Lines, Span, Statement

__all__ = ["parse_printed", "parse_expression", "slash_readings"]


def _is_tag_number(t: Token) -> bool:
    return t.kind == "number" and "." not in t.value


def _extract_tag(text: str, toks: list[Token]) -> tuple[list[Token], str | None]:
    """Remove the equation number (``\\tag{..}``, ``\\quad (15a)``, `` (48)``) at the end."""
    tags = [k for k, t in enumerate(toks) if t.kind == "tag"]
    if tags:
        k = tags[0]
        if len(tags) > 1 or any(t.kind not in ("sep", "newline") for t in toks[k + 1 :]):
            raise LatexParseError(f"\\tag{{{toks[k].arg}}} must end the display", text, toks[k].pos)
        return _strip_trailing(toks[:k]), toks[k].arg.strip()
    body = _strip_trailing(toks)
    n = len(body)
    for width in (4, 3):  # '(' number [letter] ')'
        if n < width:
            continue
        o, *mid, c = body[n - width :]
        if not (o.kind == "op" and o.value == "(" and c.kind == "op" and c.value == ")"):
            continue
        if not _is_tag_number(mid[0]) or (width == 4 and mid[1].kind != "letter"):
            continue
        before = body[n - width - 1] if n > width else None
        rest = body[: n - width]
        # Why: 'a > 0 (48)' is numbered (HVE eq. (48)), but in a bare expression '1 + 1 (2)'
        # the spaced '(2)' may be a factor; only '\quad (2)' or a relation makes it a number.
        spaced = o.space and any(is_relation(x) for _, x in _top_level(text, rest))
        if before is None or before.kind == "sep" or spaced:
            return _strip_trailing(rest), "".join(t.value for t in mid)
    return body, None


def _strip_trailing(toks: list[Token]) -> list[Token]:
    end = len(toks)
    while end and toks[end - 1].kind in ("sep", "newline"):
        end -= 1
    return toks[:end]


def _strip_leading(toks: list[Token]) -> list[Token]:
    start = 0
    while start < len(toks) and toks[start].kind == "sep":
        start += 1
    return toks[start:]


def _extract_label(toks: list[Token]) -> tuple[list[Token], str | None]:
    r"""Remove a leading ``\text{A)}`` label (and the separator after it)."""
    if toks and toks[0].kind == "text" and LABEL.match(toks[0].arg or ""):
        rest = toks[1:]
        while rest and rest[0].kind == "sep":
            rest = rest[1:]
        return rest, toks[0].arg.strip()
    return toks, None


def _unwrap(text: str, toks: list[Token]) -> tuple[list[Token], bool]:
    r"""Strip ``\boxed{...}`` and alignment environments enclosing the whole display."""
    aligned = False
    while toks:
        match = matching_close(text, toks)
        first = toks[0]
        if first.kind == "cmd" and first.value == "\\boxed" and len(toks) > 2:
            if toks[1].kind == "op" and toks[1].value == "{" and match[1] == len(toks) - 1:
                toks = toks[2:-1]
                continue
        if first.kind == "begin" and first.value in ALIGN_ENVS and match[0] == len(toks) - 1:
            toks, aligned = toks[1:-1], True
            continue
        break
    return toks, aligned


def _top_level(text: str, toks: list[Token]) -> Iterator[tuple[int, Token]]:
    """Tokens outside every delimiter pair, with their indices."""
    match = matching_close(text, toks)
    k = 0
    while k < len(toks):
        yield k, toks[k]
        k = match[k] + 1 if (k in match and match[k] > k) else k + 1


def _split_lines(text: str, toks: list[Token], aligned: bool) -> list[list[Token]]:
    r"""Split at top-level ``\\`` and re-join lines that merely wrap one statement.

    A ``\\`` (and an alignment ``&``) inside an open group other than a matrix or ``cases`` is a
    wrap of that group (teleoperator eq. (32) breaks a parenthesis across lines): it is dropped.
    """
    lines: list[list[Token]] = [[]]
    stack: list[bool] = []  # per open group: is it an environment with its own rows?
    for t in toks:
        if opener_key(t) is not None:
            stack.append(t.kind == "begin")
        elif closer_key(t) is not None:
            stack.pop()
        in_rows = any(stack)
        if t.kind == "newline" and not in_rows:
            if not stack:
                lines.append([])
            continue
        if t.kind == "op" and t.value == "&" and not in_rows:
            if not aligned:
                raise LatexParseError("'&' outside an alignment environment", text, t.pos)
            continue
        lines[-1].append(t)
    # Why: '\\ & \quad \times ...' indents a continuation; separators at a line's edge are layout.
    lines = [_strip_trailing(_strip_leading(line)) for line in lines]
    lines = [line for line in lines if line]
    merged: list[list[Token]] = []
    for line in lines:
        if merged and _wraps(text, merged[-1], line):
            merged[-1] = merged[-1] + line
        else:
            merged.append(line)
    return merged


def _wraps(text: str, previous: list[Token], line: list[Token]) -> bool:
    """Whether ``line`` continues ``previous`` (a wrapped statement) rather than starting one."""
    if is_binary(previous[-1]) or is_relation(previous[-1]):
        return True
    if is_binary(line[0]) or is_relation(line[0]):
        return True
    # Why: a display line holding no relation yet is a wrapped expression (e.g. HVE eq. (44)).
    return not any(is_relation(t) for _, t in _top_level(text, previous))


def strip_math_delimiters(text: str) -> tuple[int, int]:
    lo, hi = 0, len(text)
    while lo < hi and text[lo].isspace():
        lo += 1
    while hi > lo and text[hi - 1].isspace():
        hi -= 1
    for delim in ("$$", "$"):
        if text.startswith(delim, lo) and text.endswith(delim, 0, hi) and hi - lo >= 2 * len(delim):
            return lo + len(delim), hi - len(delim)
    return lo, hi


def parse_printed(text: str, table: SymbolTable) -> Statement:
    r"""Parse one printed display (with or without ``$$``) into a :class:`Statement`.

    Parameters
    ----------
    text : str
        The display exactly as printed (OCR damage included).
    table : SymbolTable
        What the names mean.

    Returns
    -------
    Statement
        An :class:`Expression`, :class:`Relation`, :class:`Qualified` or :class:`Lines`, carrying
        the display's ``tag`` and ``label``.

    Raises
    ------
    LatexParseError
        With the 0-based offset of the offending token in ``text``.

    Examples
    --------
    HVE eq. (54) (indexed extrema over the users):

    >>> import sympy as sp
    >>> from hapticproof.audit.reader.names import IndexedFamily
    >>> from hapticproof.audit.reader.statements import expand_indexed
    >>> b, B, K, T, m = sp.symbols('b B K T m', positive=True)
    >>> table = SymbolTable({'T': T, 'm': m}, families=[
    ...     IndexedFamily('b_{i}'), IndexedFamily('K_{0i}'), IndexedFamily('B_{0i}'),
    ...     IndexedFamily('K_{ij}', symmetric=True), IndexedFamily('B_{ij}', symmetric=True)])
    >>> s = parse_printed(r'\min_{i} b_{i} > \max_{i} \{ \frac{K_{0i}T}{2} + B_{0i} \}'
    ...                   r' + m \max_{i,j \neq i} \{ \frac{K_{ij}T}{2} + B_{ij} \}', table)
    >>> expand_indexed(s.lhs, 2, table)
    Min(b_1, b_2)
    >>> expand_indexed(s.rhs, 2, table, count=m)
    2*B_12 + K_12*T + Max(B_01 + K_01*T/2, B_02 + K_02*T/2)

    Teleoperator eq. (34), unparenthesised cosine:

    >>> w = sp.Symbol('omega', real=True)
    >>> t2 = SymbolTable({'b': b, 'K': K, 'T': T, 'B': B, r'\omega': w})
    >>> parse_printed(r'b > KT - 2B \cos \omega T \quad (34)', t2).rhs
    -2*B*cos(T*omega) + K*T
    """
    key = (text, current())
    held = _PARSED.get(id(table))
    if held is not None and held[0] is table and key in held[1]:
        return held[1][key]
    try:
        statement = _parse_printed(text, table)
    except RecursionError:    # a construct nested in a way the depth check does not count
        raise LimitError("printed display: nested too deeply") from None
    if held is None or held[0] is not table:
        if len(_PARSED) >= _PARSED_TABLES:
            _PARSED.pop(next(iter(_PARSED)))
        held = _PARSED[id(table)] = (table, {})
    if len(held[1]) >= _PARSED_TEXTS:
        held[1].pop(next(iter(held[1])))
    held[1][key] = statement
    return statement


#: Parsed displays by symbol table (held, so that its id is not reused) and by (text, limits in
#: force): a statement is an immutable value, and the audit parses many displays several times
#: (a display, the claims quoting it, the cross-paper checks). Failures are not kept.
_PARSED: dict[int, tuple[SymbolTable, dict[tuple[str, Any], Statement]]] = {}
_PARSED_TABLES = 32
_PARSED_TEXTS = 4096


_ROW_SPACING = re.compile(r"(?<=\\\\)\s*\[\s*-?[\d.]+\s*(?:pt|em|ex|mm|cm|in|bp|mu|pc|sp|dd)\s*\]")


def _without_row_spacing(text: str) -> str:
    r"""``\\[2pt]`` is a row break with extra space: the ``[2pt]`` is blanked (same length, so
    positions in the text stay right)."""
    return _ROW_SPACING.sub(lambda m: " " * len(m.group(0)), text)


def _parse_printed(text: str, table: SymbolTable) -> Statement:
    # bounded before the recursive parser starts: nesting, and (in the lexer and the grammar)
    # the size of numbers and exponents
    text = _without_row_spacing(text)
    check_depth(text, "printed display")
    lo, hi = strip_math_delimiters(text)
    toks = demote_separators(tokenize(text, lo, hi))
    matching_close(text, toks)
    toks, tag = _extract_tag(text, toks)
    toks, label = _extract_label(toks)
    toks, aligned = _unwrap(text, toks)
    if not toks:
        what = f"only the equation number ({tag})" if tag else "nothing"
        raise LatexParseError(f"the display holds {what}", text, lo)
    lines = _split_lines(text, toks, aligned)
    statements = [Parser(text, line, table).parse_line() for line in lines]
    if len(statements) == 1:
        result = statements[0]
    else:
        result = Lines(tuple(statements), "lines", Span(statements[0].span.start, statements[-1].span.end))
    return replace(result, tag=tag, label=label)


def slash_readings(text: str, table: SymbolTable) -> dict[str, str]:
    r"""The two readings of an ambiguous ``a / b c`` in a display that the parser rejects for it:
    ``\frac{a}{b} c`` and ``\frac{a}{b c}`` (spelled out in the printed text, so that both
    parse), keyed by a description; empty when the display parses or fails for another reason.

    >>> import sympy as sp
    >>> t, T, w = sp.symbols('t_d T omega', positive=True)
    >>> table = SymbolTable({'t_d': t, 'T': T, r'\omega': w})
    >>> sorted(slash_readings(r'1 - t_d / T \cos(\omega T) > 0', table).values())
    ['1 - \\frac{t_d }{T \\cos(\\omega T)} > 0', '1 - \\frac{t_d }{T} \\cos(\\omega T) > 0']
    """
    try:
        parse_printed(text, table)
        return {}
    except LatexParseError as err:
        if "ambiguous implicit product after '/'" not in err.reason or err.text != text:
            return {}
        where = err.position
    lo, hi = strip_math_delimiters(text)
    toks = tokenize(text, lo, hi)
    depth, stack = {}, 0
    for k, t in enumerate(toks):
        if opener_key(t) is not None:
            depth[k] = stack
            stack += 1
        elif closer_key(t) is not None:
            stack -= 1
            depth[k] = stack
        else:
            depth[k] = stack
    slash = max((k for k, t in enumerate(toks) if t.kind == "op" and t.value == "/" and t.pos < where), default=None)
    if slash is None:
        return {}
    level = depth[slash]

    def boundary(t: Token, k: int) -> bool:
        return depth[k] == level and (is_relation(t) or (t.kind == "op" and t.value in "+-,&") or t.kind in ("sep", "newline", "tag"))

    start = slash
    while start > 0 and not boundary(toks[start - 1], start - 1) and depth[start - 1] >= level:
        start -= 1
    after = next((k for k, t in enumerate(toks) if t.pos >= where), len(toks))
    end = after
    while end < len(toks) and not boundary(toks[end], end) and depth[end] >= level:
        end += 1
    a0, s0, w0 = toks[start].pos, toks[slash].pos, toks[after].pos if after < len(toks) else hi
    e0 = toks[end - 1].end
    numerator, divisor, rest = text[a0:s0], text[s0 + 1:w0].strip(), text[w0:e0].strip()
    return {
        f"({numerator.strip()})/({divisor}) {rest}": text[:a0] + rf"\frac{{{numerator}}}{{{divisor}}} {rest}" + text[e0:],
        f"({numerator.strip()})/({divisor} {rest})": text[:a0] + rf"\frac{{{numerator}}}{{{divisor} {rest}}}" + text[e0:],
    }


def parse_expression(text: str, table: SymbolTable) -> Any:
    r"""Parse a display that must be a single expression and return the SymPy object.

    >>> import sympy as sp
    >>> x = sp.Symbol('x')
    >>> parse_expression(r'\frac{x^2}{2} + 3x', SymbolTable({'x': x}))
    x**2/2 + 3*x
    """
    stmt = parse_printed(text, table)
    if not isinstance(stmt, Expression):
        raise LatexParseError(f"expected an expression, got a {type(stmt).__name__}", text, stmt.span.start)
    return stmt.expr
