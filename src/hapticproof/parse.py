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
and prose in ``\text{...}`` raise :class:`~hapticproof.errors.LatexParseError` carrying the
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
hapticproof.errors.LatexParseError: relation symbol '=' inside the argument of \cos at position 14 (near '\\cos(\\omega T = -1)')
"""

from __future__ import annotations

import re
from collections.abc import Callable, Iterable, Iterator, Mapping
from contextlib import contextmanager
from dataclasses import dataclass, field, replace
from itertools import product as cartesian_product
from typing import Any

import sympy as sp
from sympy.core.symbol import Str

from hapticproof.errors import LatexParseError

__all__ = [
    "DEFAULT_CONSTANTS",
    "SymbolTable",
    "IndexedFamily",
    "Span",
    "Statement",
    "Expression",
    "Relation",
    "IndexRange",
    "Qualified",
    "Lines",
    "Elision",
    "IndexedExtremum",
    "IndexedMin",
    "IndexedMax",
    "IndexedCall",
    "PrintedLimit",
    "Norm",
    "parse_printed",
    "parse_expression",
    "slash_readings",
    "normalise_name",
    "symbol_for",
    "index_symbol",
    "expand_indexed",
    "has_elision",
]

# ----------------------------------------------------------------------------------------------
# Vocabulary of the dialect
# ----------------------------------------------------------------------------------------------

_GREEK = frozenset(
    "\\" + g
    for g in (
        "alpha beta gamma delta epsilon varepsilon zeta eta theta vartheta iota kappa lambda mu "
        "nu xi pi varpi rho varrho sigma varsigma tau upsilon phi varphi chi psi omega ell "
        "Gamma Delta Theta Lambda Xi Pi Sigma Upsilon Phi Psi Omega"
    ).split()
)
_DECORATIONS = frozenset(
    "\\" + d
    for d in (
        "mathbf mathcal mathscr mathfrak mathbb boldsymbol bm mathit mathsf bar tilde hat "
        "widehat widetilde dot ddot vec overline check breve"
    ).split()
)
#: Commands whose braced argument is kept verbatim (prose, operator names).
_TEXT_COMMANDS = frozenset({"\\text", "\\textrm", "\\textit", "\\mbox", "\\operatorname", "\\mathrm"})
_ELEMENTARY: dict[str, Callable[[Any], Any]] = {
    "\\cos": sp.cos,
    "\\sin": sp.sin,
    "\\tan": sp.tan,
    "\\cot": sp.cot,
    "\\sec": sp.sec,
    "\\csc": sp.csc,
    "\\cosh": sp.cosh,
    "\\sinh": sp.sinh,
    "\\tanh": sp.tanh,
    "\\arccos": sp.acos,
    "\\arcsin": sp.asin,
    "\\arctan": sp.atan,
    "\\exp": sp.exp,
    "\\ln": sp.log,
    "\\log": sp.log,
}
_PARTS: dict[str, Callable[[Any], Any]] = {"\\Re": sp.re, "\\Im": sp.im, "Re": sp.re, "Im": sp.im}
_FRACTIONS = frozenset({"\\frac", "\\dfrac", "\\tfrac", "\\cfrac"})
_OPERATOR_COMMANDS = frozenset(
    {"\\det", "\\min", "\\max", "\\sum", "\\lim", "\\int", "\\sqrt", "\\boxed", "\\infty"}
)
_RELATIONS = {
    "=": "=",
    "<": "<",
    ">": ">",
    "\\geq": ">=",
    "\\ge": ">=",
    "\\geqslant": ">=",
    "\\leq": "<=",
    "\\le": "<=",
    "\\leqslant": "<=",
    "\\neq": "!=",
    "\\ne": "!=",
}
_UNSUPPORTED_RELATIONS = frozenset(
    "\\" + r
    for r in (
        "in notin approx sim simeq equiv propto subset subseteq supset gg ll succ prec succeq "
        "preceq cong to rightarrow mapsto"
    ).split()
)
_ARROWS = frozenset({"\\implies", "\\Longrightarrow", "\\Rightarrow", "\\xrightarrow", "\\iff"})
_ELLIPSES = frozenset({"\\dots", "\\ldots", "\\cdots", "\\vdots", "\\ddots", "\\dotsc", "\\dotsb"})
_MULTIPLY = frozenset({"*", "\\cdot", "\\times"})
#: Layout commands that are dropped (sizes, styles) -- they carry no mathematics.
_IGNORED = frozenset(
    "\\" + c
    for c in (
        "displaystyle textstyle limits nolimits hline big Big bigg Bigg bigl bigr Bigl Bigr "
        "biggl biggr Biggl Biggr mathstrut nonumber notag"
    ).split()
)
_SEPARATOR_COMMANDS = frozenset({"\\quad", "\\qquad"})
_ALIGN_ENVS = frozenset(
    "aligned align align* split gathered gather gather* equation equation* multline multline* "
    "eqnarray eqnarray* alignedat".split()
)
_MATRIX_ENVS = frozenset({"bmatrix", "pmatrix", "matrix", "Bmatrix", "smallmatrix", "vmatrix"})
#: ``\text{...}`` words that join clauses (``..., \text{ where } i = 1, 2``).
_CONNECTORS = frozenset({"where", "and", "with", "for", "for all", "for any", "when"})
#: Operator names recognised when spelled with plain letters (``det(R_0)`` in the HVE paper).
_WORDS = ("diag", "det")
_OPS = frozenset("+-*/=<>()[]|,'^_{}&.;:!")
_OPENERS = {"{": "}", "(": ")", "[": "]", "\\{": "\\}"}
_CLOSERS = {v: k for k, v in _OPENERS.items()}
_DELIMITER_PAIRS = {"(": ")", "[": "]", "\\{": "\\}", "|": "|", "\\|": "\\|", ".": None}
_LABEL = re.compile(r"^\s*\(?[A-Za-z0-9]{1,4}\)\s*$")


# ----------------------------------------------------------------------------------------------
# SymPy objects for printed constructs that SymPy has no unevaluated form of
# ----------------------------------------------------------------------------------------------


class Elision(sp.Symbol):
    r"""A printed ellipsis (``\dots``, ``\cdots``, ``\vdots``, ``\ddots``) kept as an atom.

    A matrix or list printed with ellipses cannot be made concrete without guessing its missing
    entries, so the parser returns it with these atoms in place; :func:`has_elision` tells.

    >>> Elision('vdots'), Elision('vdots').kind
    (\vdots, 'vdots')
    """

    def __new__(cls, kind: str = "dots") -> Elision:
        kind = kind.lstrip("\\")
        if "\\" + kind not in _ELLIPSES:
            raise ValueError(f"not an ellipsis command: {kind!r}")
        return super().__new__(cls, "\\" + kind)

    def __getnewargs__(self) -> tuple[str]:
        return (self.name,)

    @property
    def kind(self) -> str:
        """The ellipsis command without its backslash (``'dots'``, ``'vdots'``...)."""
        return self.name[1:]


class IndexedExtremum(sp.Expr):
    r"""Unevaluated ``\min``/``\max`` of ``body`` over indices ranging over the users ``1..m``.

    ``condition`` restricts the index tuples (``j \neq i``).  The indices are bound: they are not
    among the free symbols.  Expand with :func:`expand_indexed`.
    """

    is_commutative = True
    _combine: Callable[..., Any] = sp.Min

    def __new__(cls, body: Any, indices: Iterable[sp.Symbol], condition: Any = sp.true) -> Any:
        return sp.Expr.__new__(cls, sp.sympify(body), sp.Tuple(*indices), sp.sympify(condition))

    @property
    def body(self) -> sp.Expr:
        """The expression whose extremum is taken."""
        return self.args[0]

    @property
    def indices(self) -> tuple[sp.Symbol, ...]:
        """The bound indices, in printed order."""
        return tuple(self.args[1])

    @property
    def condition(self) -> Any:
        """A SymPy boolean the index tuple must satisfy (``true`` if none was printed)."""
        return self.args[2]

    @property
    def free_symbols(self) -> set[sp.Basic]:
        return _unbound(self.body.free_symbols | self.condition.free_symbols, set(self.indices))

    def _eval_is_real(self) -> bool | None:
        return self.body.is_real


class IndexedMin(IndexedExtremum):
    r"""``\min_{i} \{...\}`` over the users ``1..m`` (see :class:`IndexedExtremum`).

    >>> i = index_symbol('i')
    >>> low = IndexedMin(sp.IndexedBase('b_{i}')[i], (i,))
    >>> low.indices, i in low.free_symbols
    ((i,), False)
    """

    _combine = sp.Min


class IndexedMax(IndexedExtremum):
    r"""``\max_{i,j \neq i} \{...\}`` over the users ``1..m`` (see :class:`IndexedExtremum`)."""

    _combine = sp.Max


class IndexedCall(sp.Expr):
    r"""A member of a *function* family applied to arguments, e.g. ``X_{hj}(z)`` with ``j`` free.

    ``args`` are ``(Str(pattern), Tuple(indices), Tuple(arguments))``; :func:`expand_indexed`
    replaces it by the concrete function of the table applied to the arguments.
    """

    is_commutative = True

    def __new__(cls, pattern: str, indices: Iterable[Any], arguments: Iterable[Any]) -> Any:
        label = pattern if isinstance(pattern, Str) else Str(pattern)  # SymPy rebuilds with a Str
        return sp.Expr.__new__(cls, label, sp.Tuple(*indices), sp.Tuple(*arguments))

    @property
    def pattern(self) -> str:
        """The family's printed pattern, e.g. ``'X_{hi}'``."""
        return self.args[0].name

    @property
    def indices(self) -> tuple[Any, ...]:
        """Index values (symbols or integers)."""
        return tuple(self.args[1])

    @property
    def arguments(self) -> tuple[Any, ...]:
        """The arguments the member is applied to."""
        return tuple(self.args[2])


class PrintedLimit(sp.Expr):
    r"""Unevaluated ``\lim_{variable \to target} expr``; the variable may be an expression.

    The papers write ``\lim_{\cos(\omega T)\to 1}``, which :class:`sympy.Limit` cannot hold.

    >>> x = sp.Symbol('x')
    >>> PrintedLimit(sp.sin(x)/x, x, 0).as_sympy().doit()
    1
    """

    def __new__(cls, expr: Any, variable: Any, target: Any) -> Any:
        return sp.Expr.__new__(cls, sp.sympify(expr), sp.sympify(variable), sp.sympify(target))

    @property
    def expr(self) -> sp.Expr:
        """The expression whose limit is taken."""
        return self.args[0]

    @property
    def variable(self) -> sp.Expr:
        """What tends to the target (a symbol or an expression such as ``cos(omega*T)``)."""
        return self.args[1]

    @property
    def target(self) -> sp.Expr:
        """The value approached."""
        return self.args[2]

    def as_sympy(self) -> sp.Limit:
        """The equivalent :class:`sympy.Limit`; the variable must be a symbol."""
        if not isinstance(self.variable, sp.Symbol):
            raise ValueError(f"the limit variable {self.variable} is not a symbol")
        return sp.Limit(self.expr, self.variable, self.target)


class Norm(sp.Expr):
    r"""Unevaluated norm ``\|x\|`` (``args == (x,)``) or ``\|x\|_p`` (``args == (x, p)``).

    >>> Norm(sp.Symbol('M'), sp.oo).order
    oo
    """

    is_commutative = True
    is_extended_real = True
    is_extended_nonnegative = True

    def __new__(cls, arg: Any, *order: Any) -> Any:
        if len(order) > 1:
            raise ValueError("a norm has at most one order")
        return sp.Expr.__new__(cls, sp.sympify(arg), *map(sp.sympify, order))

    @property
    def arg(self) -> sp.Basic:
        """The normed object."""
        return self.args[0]

    @property
    def order(self) -> sp.Basic | None:
        """The printed subscript (``oo`` for ``\\infty``), or ``None``."""
        return self.args[1] if len(self.args) > 1 else None


def _unbound(symbols: set[sp.Basic], bound: set[sp.Basic]) -> set[sp.Basic]:
    """Drop bound indices and indexed objects that mention them from ``symbols``."""
    return {
        s
        for s in symbols
        if s not in bound and not (isinstance(s, sp.Indexed) and _mentions(s.indices, bound))
    }


def _mentions(exprs: Iterable[Any], bound: set[sp.Basic]) -> bool:
    return any(sp.sympify(e).free_symbols & bound for e in exprs)


def has_elision(obj: Any) -> bool:
    r"""Whether an expression, matrix or :class:`Statement` holds an :class:`Elision`.

    >>> has_elision(sp.ImmutableMatrix([[1, Elision('cdots')]]))
    True
    """
    if isinstance(obj, Statement):
        return any(has_elision(e) for e in obj.expressions())
    return bool(sp.sympify(obj).atoms(Elision))


# ----------------------------------------------------------------------------------------------
# Statements
# ----------------------------------------------------------------------------------------------


@dataclass(frozen=True, slots=True)
class Span:
    """Half-open character range ``[start, end)`` in the parsed string.

    >>> Span(4, 7).slice('a > b + c')
    'b +'
    """

    start: int
    end: int

    def __post_init__(self) -> None:
        if not 0 <= self.start <= self.end:
            raise ValueError(f"invalid span {self.start}..{self.end}")

    def slice(self, text: str) -> str:
        """The spanned part of ``text``."""
        return text[self.start : self.end]


class Statement:
    """Base class of the parse results.

    Every statement has a ``span`` (its place in the source), and the top-level one carries the
    display's ``tag`` (equation number) and ``label`` (``\\text{A)}``) when printed.
    """

    __slots__ = ()
    span: Span
    tag: str | None
    label: str | None

    def expressions(self) -> tuple[Any, ...]:
        """Every SymPy object in the statement, in printed order."""
        raise NotImplementedError

    def relations(self) -> tuple[Relation, ...]:
        """The relation chains in the statement (conditions of qualifiers excluded)."""
        raise NotImplementedError

    def map(self, func: Callable[[Any], Any]) -> Statement:
        """A copy with ``func`` applied to every expression (e.g. :func:`expand_indexed`)."""
        raise NotImplementedError


@dataclass(frozen=True, slots=True)
class Expression(Statement):
    r"""A display that is an expression without a relation (e.g. HVE eq. (19))."""

    expr: Any
    span: Span
    tag: str | None = None
    label: str | None = None

    def expressions(self) -> tuple[Any, ...]:
        return (self.expr,)

    def relations(self) -> tuple[Relation, ...]:
        return ()

    def map(self, func: Callable[[Any], Any]) -> Expression:
        return replace(self, expr=func(self.expr))


_REL_CLASSES: dict[str, Any] = {
    "<": sp.StrictLessThan,
    "<=": sp.LessThan,
    ">": sp.StrictGreaterThan,
    ">=": sp.GreaterThan,
    "=": sp.Eq,
    "!=": sp.Ne,
}


@dataclass(frozen=True, slots=True)
class Relation(Statement):
    r"""A relation chain ``terms[0] ops[0] terms[1] ops[1] ...`` (``0 < a < b``).

    ``ops`` are ``'<'``, ``'<='``, ``'>'``, ``'>='``, ``'='`` and ``'!='``; ``term_spans`` locate
    each term in the source.
    """

    terms: tuple[Any, ...]
    ops: tuple[str, ...]
    span: Span
    term_spans: tuple[Span, ...] = ()
    tag: str | None = None
    label: str | None = None

    def __post_init__(self) -> None:
        if len(self.terms) < 2 or len(self.ops) != len(self.terms) - 1:
            raise ValueError("a relation needs n >= 2 terms and n - 1 operators")
        if bad := [op for op in self.ops if op not in _REL_CLASSES]:
            raise ValueError(f"unknown relation operators {bad}")

    @property
    def lhs(self) -> Any:
        """The first term."""
        return self.terms[0]

    @property
    def rhs(self) -> Any:
        """The last term."""
        return self.terms[-1]

    def pairs(self) -> tuple[tuple[Any, str, Any], ...]:
        """The chain as ``(left, op, right)`` links: ``0 < a < b`` gives two links."""
        return tuple(zip(self.terms, self.ops, self.terms[1:]))

    def as_sympy(self) -> Any:
        """The chain as one SymPy boolean (an ``And`` of unevaluated relationals).

        >>> a, b = sp.symbols('a b')
        >>> Relation((0, a, b), ('<', '<'), Span(0, 9)).as_sympy()
        (0 < a) & (a < b)
        """
        links = [_REL_CLASSES[op](lhs, rhs, evaluate=False) for lhs, op, rhs in self.pairs()]
        return links[0] if len(links) == 1 else sp.And(*links, evaluate=False)

    def expressions(self) -> tuple[Any, ...]:
        return self.terms

    def relations(self) -> tuple[Relation, ...]:
        return (self,)

    def map(self, func: Callable[[Any], Any]) -> Relation:
        return replace(self, terms=tuple(func(t) for t in self.terms))


@dataclass(frozen=True, slots=True)
class IndexRange:
    r"""A printed index range such as ``i = 1, 2, \dots, 6`` or ``i, j = 1, 2``.

    ``values`` are Rationals, symbols of the table, bare letters (labels such as ``i = x, y, z``)
    and :class:`Elision` atoms, in printed order.
    """

    indices: tuple[sp.Symbol, ...]
    values: tuple[Any, ...]
    span: Span

    def __post_init__(self) -> None:
        if not self.indices or not self.values:
            raise ValueError("an index range needs indices and values")


@dataclass(frozen=True, slots=True)
class Qualified(Statement):
    r"""A statement with index ranges and index conditions, e.g. ``..., \quad i = 1, \dots, 6``.

    >>> z = sp.Symbol('z_1')
    >>> q = parse_printed(r'z_{i} \geq 0, \quad i = 1, 2, \dots, 6',
    ...                   SymbolTable(families=[IndexedFamily('z_{i}')]))
    >>> q.body.lhs, q.ranges[0].values
    (z_{i}[i], (1, 2, \dots, 6))
    """

    body: Statement
    ranges: tuple[IndexRange, ...]
    conditions: tuple[Relation, ...]
    span: Span
    tag: str | None = None
    label: str | None = None

    def expressions(self) -> tuple[Any, ...]:
        return self.body.expressions()

    def relations(self) -> tuple[Relation, ...]:
        return self.body.relations()

    def map(self, func: Callable[[Any], Any]) -> Qualified:
        return replace(self, body=self.body.map(func))


@dataclass(frozen=True, slots=True)
class Lines(Statement):
    r"""Several statements of one display.

    ``kind`` is ``'lines'`` (``\\`` breaks), ``'list'`` (comma-separated clauses) or ``'steps'``
    (``\implies`` / ``\xrightarrow{}`` derivation steps).

    >>> a, b = sp.symbols('a b')
    >>> both = parse_printed(r'a \geq 0, \quad b \geq 0 \quad (39a)', SymbolTable({'a': a, 'b': b}))
    >>> both.kind, [r.lhs for r in both.relations()], both.tag
    ('list', [a, b], '39a')
    """

    statements: tuple[Statement, ...]
    kind: str
    span: Span
    tag: str | None = None
    label: str | None = None

    def __post_init__(self) -> None:
        if self.kind not in ("lines", "list", "steps"):
            raise ValueError(f"unknown Lines kind {self.kind!r}")

    def expressions(self) -> tuple[Any, ...]:
        return tuple(e for s in self.statements for e in s.expressions())

    def relations(self) -> tuple[Relation, ...]:
        return tuple(r for s in self.statements for r in s.relations())

    def map(self, func: Callable[[Any], Any]) -> Lines:
        return replace(self, statements=tuple(s.map(func) for s in self.statements))


# ----------------------------------------------------------------------------------------------
# Tokens
# ----------------------------------------------------------------------------------------------


@dataclass(frozen=True, slots=True)
class _Tok:
    """One lexical token: ``kind`` is letter, number, cmd, op, sym, text, tag, begin, end,
    left, right, sep, newline or eof; ``space`` tells whether whitespace preceded it."""

    kind: str
    value: str
    pos: int
    end: int
    space: bool = False
    arg: str | None = None


def _read_braced(text: str, i: int, stop: int, what: str) -> tuple[str, int]:
    """The raw content of the ``{...}`` group starting at or after ``i`` and the index after it."""
    while i < stop and text[i].isspace():
        i += 1
    if i >= stop or text[i] != "{":
        raise LatexParseError(f"{what} needs a braced argument", text, min(i, len(text)))
    depth, j = 0, i
    while j < stop:
        ch = text[j]
        if ch == "\\":
            j += 2
            continue
        if ch == "{":
            depth += 1
        elif ch == "}":
            depth -= 1
            if depth == 0:
                return text[i + 1 : j], j + 1
        j += 1
    raise LatexParseError(f"unbalanced '{{' in the argument of {what}", text, i)


def _read_delimiter(text: str, i: int, stop: int, what: str) -> tuple[str, int]:
    """The delimiter after ``\\left``/``\\right`` and the index after it."""
    while i < stop and text[i].isspace():
        i += 1
    if i < stop and text[i] in "()[]|.":
        return text[i], i + 1
    if i + 1 < stop and text[i] == "\\" and text[i + 1] in "{}|":
        return text[i : i + 2], i + 2
    raise LatexParseError(f"{what} must be followed by a delimiter", text, min(i, len(text)))


def _tokenize(text: str, start: int = 0, stop: int | None = None) -> list[_Tok]:
    """Split ``text[start:stop]`` into tokens; positions are offsets in ``text``."""
    stop = len(text) if stop is None else stop
    toks: list[_Tok] = []
    i, space = start, False

    def emit(kind: str, value: str, end: int, arg: str | None = None) -> None:
        nonlocal space
        toks.append(_Tok(kind, value, i, end, space, arg))
        space = False

    while i < stop:
        ch = text[i]
        if ch.isspace() or ch == "~":
            space, i = True, i + 1
            continue
        if ch == "\\":
            j = i + 1
            if j < stop and text[j].isascii() and text[j].isalpha():
                while j < stop and text[j].isascii() and text[j].isalpha():
                    j += 1
                name = text[i:j]
                if name in ("\\begin", "\\end"):
                    env, k = _read_braced(text, j, stop, name)
                    emit(name[1:], env.strip(), k)
                elif name in _TEXT_COMMANDS or name == "\\tag":
                    content, k = _read_braced(text, j, stop, name)
                    emit("tag" if name == "\\tag" else "text", name, k, content)
                elif name in ("\\left", "\\right"):
                    delim, k = _read_delimiter(text, j, stop, name)
                    emit(name[1:], delim, k)
                elif name in _IGNORED:
                    space, k = True, j
                elif name in _SEPARATOR_COMMANDS:
                    emit("sep", name, j)
                    k = j
                else:
                    emit("cmd", name, j)
                    k = j
                i = k
                continue
            if j >= stop:
                raise LatexParseError("lone backslash", text, i)
            c = text[j]
            if c == "\\":
                emit("newline", "\\\\", j + 1)
            elif c in ",;:!>":
                space = True  # thin spaces are layout
            elif c == " ":
                emit("sep", "\\ ", j + 1)
            elif c in "{}|":
                emit("sym", "\\" + c, j + 1)
            else:
                raise LatexParseError(f"unsupported control symbol '\\{c}'", text, i)
            i = j + 1
            continue
        if ch.isascii() and ch.isalpha():
            emit("letter", ch, i + 1)
            i += 1
        elif ch.isdigit():
            j = i
            while j < stop and text[j].isdigit():
                j += 1
            if j + 1 < stop and text[j] == "." and text[j + 1].isdigit():
                j += 1
                while j < stop and text[j].isdigit():
                    j += 1
            emit("number", text[i:j], j)
            i = j
        elif text.startswith("...", i):
            emit("cmd", "\\dots", i + 3)
            i += 3
        elif ch in _OPS:
            emit("op", ch, i + 1)
            i += 1
        else:
            raise LatexParseError(f"unexpected character {ch!r}", text, i)
    return toks


def _opener_key(t: _Tok) -> str | None:
    if t.kind == "op" and t.value in ("{", "(", "["):
        return t.value
    if t.kind == "sym" and t.value == "\\{":
        return "\\{"
    if t.kind == "left":
        return "left"
    if t.kind == "begin":
        return "begin:" + t.value
    return None


def _closer_key(t: _Tok) -> str | None:
    if t.kind == "op" and t.value in ("}", ")", "]"):
        return _CLOSERS[t.value]
    if t.kind == "sym" and t.value == "\\}":
        return "\\{"
    if t.kind == "right":
        return "left"
    if t.kind == "end":
        return "begin:" + t.value
    return None


def _describe(t: _Tok) -> str:
    if t.kind in ("begin", "end"):
        return f"\\{t.kind}{{{t.value}}}"
    if t.kind in ("left", "right"):
        return f"\\{t.kind}{t.value}"
    return t.value


def _match(text: str, toks: list[_Tok]) -> dict[int, int]:
    """Pair every opening delimiter with its closer (both directions) or raise."""
    stack: list[int] = []
    match: dict[int, int] = {}
    for k, t in enumerate(toks):
        if _opener_key(t) is not None:
            stack.append(k)
        elif (key := _closer_key(t)) is not None:
            if not stack:
                raise LatexParseError(f"unmatched '{_describe(t)}'", text, t.pos)
            opener = toks[stack[-1]]
            if _opener_key(opener) != key:
                raise LatexParseError(
                    f"'{_describe(t)}' closes '{_describe(opener)}' opened at position {opener.pos}",
                    text,
                    t.pos,
                )
            o = stack.pop()
            match[o], match[k] = k, o
    if stack:
        t = toks[stack[-1]]
        raise LatexParseError(f"unclosed '{_describe(t)}'", text, t.pos)
    return match


def _demote_separators(toks: list[_Tok]) -> list[_Tok]:
    r"""Turn ``\quad``/``\ `` into plain space except at top level and directly inside ``[ ]``.

    Why: separators split clauses (``a = b, \quad c = d``) and vector entries (``[F_1 \ F_2]``);
    anywhere else (inside parentheses, fractions, matrices) they are only layout.
    """
    out: list[_Tok] = []
    stack: list[str] = []  # 'keep' / 'space' / 'transparent'
    space_pending = False
    for k, t in enumerate(toks):
        if space_pending:
            t = replace(t, space=True)
            space_pending = False
        if t.kind == "sep":
            kinds = [s for s in stack if s != "transparent"]
            if kinds and kinds[-1] == "space":
                space_pending = True
                continue
        if _opener_key(t) is not None:
            after_boxed = k > 0 and toks[k - 1].kind == "cmd" and toks[k - 1].value == "\\boxed"
            if (t.kind == "begin" and t.value in _ALIGN_ENVS) or (t.value == "{" and after_boxed):
                stack.append("transparent")
            elif (t.kind == "op" and t.value == "[") or (t.kind == "left" and t.value == "["):
                stack.append("keep")
            else:
                stack.append("space")
        elif _closer_key(t) is not None and stack:
            stack.pop()
        out.append(t)
    return out


def _canon(toks: Iterable[_Tok]) -> str:
    """Canonical source text of a token run (whitespace dropped where it is not needed)."""
    out = ""
    for t in toks:
        if t.kind == "text":
            piece = f"{t.value}{{{t.arg.strip()}}}"
        elif t.kind in ("begin", "end", "left", "right"):
            piece = _describe(t)
        else:
            piece = t.value
        if re.search(r"\\[A-Za-z]+$", out) and piece[:1].isalpha():
            out += " "  # keep '\ell j' from becoming '\ellj'
        out += piece
    return out


# ----------------------------------------------------------------------------------------------
# Names
# ----------------------------------------------------------------------------------------------


@dataclass(frozen=True, slots=True)
class _NameParts:
    """A printed name split into canonical base, primes and script token runs."""

    base: str
    primes: int
    sub: tuple[_Tok, ...] | None
    sup: tuple[_Tok, ...] | None

    @property
    def canonical(self) -> str:
        return _compose(self.base, self.primes, self.sub, self.sup)


def _compose(base: str, primes: int, sub: Iterable[_Tok] | None, sup: Iterable[_Tok] | None) -> str:
    name = base + "'" * primes
    if sub is not None:
        name += "_{" + _canon(sub) + "}"
    if sup is not None:
        name += "^{" + _canon(sup) + "}"
    return name


def _name_parts(printed: str) -> _NameParts:
    """Parse a table key such as ``K_01``, ``\\mathbf Z_{11}`` or ``G^{-1}`` into parts.

    Keys are read leniently: an unbraced script extends to the next script (``K_01`` is
    ``K_{01}``), which is what a person typing a table means.
    """
    toks = _tokenize(printed)
    if not toks:
        raise LatexParseError("empty name", printed, 0)
    match = _match(printed, toks)
    base, k = _read_base(printed, toks, 0, match)
    primes, sub, sup = 0, None, None
    while k < len(toks):
        t = toks[k]
        if t.kind == "op" and t.value == "'":
            primes, k = primes + 1, k + 1
            continue
        if t.kind == "op" and t.value in "_^":
            k += 1
            if k >= len(toks):
                raise LatexParseError(f"missing script after '{t.value}'", printed, t.pos)
            if toks[k].kind == "op" and toks[k].value == "{":
                close = match[k]
                run, k = tuple(toks[k + 1 : close]), close + 1
            else:
                j = k
                while j < len(toks) and not (toks[j].kind == "op" and toks[j].value in "_^'"):
                    j += 1
                run, k = tuple(toks[k:j]), j
            if (t.value == "_" and sub is not None) or (t.value == "^" and sup is not None):
                raise LatexParseError(f"double '{t.value}' script", printed, t.pos)
            if not run:
                raise LatexParseError(f"empty script after '{t.value}'", printed, t.pos)
            if t.value == "_":
                sub = run
            elif _canon(run) == "\\prime":
                primes += 1
            else:
                sup = run
            continue
        raise LatexParseError(f"unexpected '{t.value}' in a name", printed, t.pos)
    return _NameParts(base, primes, sub, sup)


def _read_base(text: str, toks: list[_Tok], k: int, match: Mapping[int, int]) -> tuple[str, int]:
    """Canonical base of the name at ``toks[k]`` and the index after it (``match`` pairs braces)."""
    t = toks[k]
    if t.kind == "letter":
        j = k + 1
        while j < len(toks) and toks[j].kind == "letter" and not toks[j].space:
            j += 1
        return "".join(x.value for x in toks[k:j]), j
    if t.kind == "number" and k > 0 and toks[k - 1].kind == "op" and toks[k - 1].value == "{":
        return t.value, k + 1  # \mathbf{0}
    if t.kind == "cmd" and t.value in _GREEK:
        return t.value, k + 1
    if t.kind == "text" and t.value in ("\\mathrm", "\\operatorname") and t.arg.strip().isalpha():
        return f"{t.value}{{{t.arg.strip()}}}", k + 1
    if t.kind == "cmd" and t.value in _DECORATIONS:
        if k + 1 >= len(toks):
            raise LatexParseError(f"{t.value} needs an argument", text, t.pos)
        nxt = toks[k + 1]
        if nxt.kind == "op" and nxt.value == "{":
            first, stop = k + 2, match[k + 1]
            after = stop + 1
        else:
            first, stop = k + 1, k + 2
            after = stop
        if first >= stop:
            raise LatexParseError(f"empty {t.value}{{}}", text, t.pos)
        base, end = _read_base(text, toks, first, match)
        if end != stop:
            raise LatexParseError(f"{t.value}{{...}} must hold one name", text, t.pos)
        return f"{t.value}{{{base}}}", after
    raise LatexParseError(f"a name cannot start with '{t.value}'", text, t.pos)


def normalise_name(printed: str) -> str:
    r"""The canonical spelling of a printed name, used for every table lookup.

    Scripts are always braced and ordered ``base'_{sub}^{sup}``; decorations are braced;
    spaces inside scripts are dropped.  Keys are read leniently (``K_01`` means ``K_{01}``), but
    inside a display LaTeX's own grouping rules apply.

    >>> normalise_name('K_01') == normalise_name('K_{01}') == 'K_{01}'
    True
    >>> normalise_name('t_d'), normalise_name(r'\mathbf Z_{11}'), normalise_name('G^{-1}_1')
    ('t_{d}', '\\mathbf{Z}_{11}', 'G_{1}^{-1}')
    """
    return _name_parts(printed).canonical


def _sympy_name(canonical: str) -> str:
    """Conventional SymPy name for a canonical printed name (``K_{01}`` -> ``K_01``)."""
    if any(d in canonical for d in _DECORATIONS) or "\\mathrm" in canonical:
        return canonical  # decorations are part of the identity: keep the LaTeX spelling
    return re.sub(r"[{}\\]", "", canonical).replace(" ", "")


def symbol_for(printed: str, **assumptions: bool) -> sp.Symbol:
    r"""A SymPy symbol for a printed name, named by the project's convention.

    >>> symbol_for('K_{01}', positive=True), symbol_for(r'\omega_s'), symbol_for(r'\mathbf{Z}_x')
    (K_01, omega_s, \mathbf{Z}_{x})
    """
    return sp.Symbol(_sympy_name(normalise_name(printed)), **assumptions)


def index_symbol(name: str) -> sp.Symbol:
    r"""The integer symbol that stands for a printed index letter (``i``, ``j``, ``\ell``).

    >>> index_symbol('i'), index_symbol('i').is_integer
    (i, True)
    """
    return sp.Symbol(name.lstrip("\\"), integer=True)


# ----------------------------------------------------------------------------------------------
# Symbol table
# ----------------------------------------------------------------------------------------------


class _FrozenMap(Mapping):
    """A read-only, hashable mapping (keeps the frozen table hashable)."""

    __slots__ = ("_data", "_hash")

    def __init__(self, data: Mapping[str, Any] | Iterable[tuple[str, Any]] = ()) -> None:
        self._data = dict(data)
        self._hash: int | None = None

    def __getitem__(self, key: str) -> Any:
        return self._data[key]

    def __iter__(self) -> Iterator[str]:
        return iter(self._data)

    def __len__(self) -> int:
        return len(self._data)

    def __hash__(self) -> int:
        if self._hash is None:
            self._hash = hash(frozenset(self._data.items()))
        return self._hash

    def __repr__(self) -> str:
        return repr(self._data)


@dataclass(frozen=True, slots=True)
class IndexedFamily:
    r"""A family of printed names indexed by users, such as ``K_{0i}``, ``K_{ij}`` or ``z_{i,j}``.

    Parameters
    ----------
    pattern : str
        The printed member with index letters (the table's ``indices``) as placeholders:
        ``'b_{i}'``, ``'K_{0i}'``, ``'z_{ai}'``.  With commas (``'z_{i,j}'``) each slot may be
        printed as an index expression (``z_{3i-2,3j}``).
    symmetric : bool
        Whether the member does not depend on the order of its indices (``K_{ij} = K_{ji}``).
    function : bool
        Whether members are functions, applied as ``X_{hj}(z)``.
    assumptions : Mapping[str, bool]
        Assumptions of concrete members the table does not list (they are created on demand).

    >>> IndexedFamily('K_{ij}', symmetric=True).pattern
    'K_{ij}'
    """

    pattern: str
    symmetric: bool = False
    function: bool = False
    assumptions: Mapping[str, bool] = field(default_factory=dict)

    def __post_init__(self) -> None:
        parts = _name_parts(self.pattern)
        if parts.sub is None or parts.sup is not None:
            raise ValueError(f"a family pattern needs a subscript and no superscript: {self.pattern!r}")
        object.__setattr__(self, "pattern", parts.canonical)
        object.__setattr__(self, "assumptions", _FrozenMap(self.assumptions))


@dataclass(frozen=True, slots=True)
class _FamilySpec:
    """A family compiled against the table's index letters."""

    family: IndexedFamily
    base: str
    comma: bool
    slots: tuple[str | None, ...]  # literal canonical text, or None for an index placeholder


def _sub_slots(toks: Iterable[_Tok]) -> list[tuple[str, _Tok]]:
    """Split a subscript into one-character slots (``01`` gives two slots)."""
    slots = []
    for t in toks:
        if t.kind == "number":
            slots.extend((ch, t) for ch in t.value)
        else:
            slots.append((_canon([t]), t))
    return slots


def _split_commas(toks: list[_Tok]) -> list[list[_Tok]]:
    parts: list[list[_Tok]] = [[]]
    depth = 0
    for t in toks:
        if _opener_key(t) is not None:
            depth += 1
        elif _closer_key(t) is not None:
            depth -= 1
        if depth == 0 and t.kind == "op" and t.value == ",":
            parts.append([])
        else:
            parts[-1].append(t)
    return parts


DEFAULT_CONSTANTS: Mapping[str, Any] = _FrozenMap({"j": sp.I, "e": sp.E, "\\pi": sp.pi})


@dataclass(frozen=True, slots=True)
class SymbolTable:
    r"""What the printed names of one paper mean.

    Parameters
    ----------
    symbols : Mapping[str, sympy.Basic]
        Printed name -> SymPy object (a symbol, an expression such as the paper's ``S``, a
        matrix or a ``MatrixSymbol``).  Keys are normalised (:func:`normalise_name`); plain
        multi-letter keys (``'KT'``) are matched in letter runs, longest first.
    functions : Mapping[str, Callable]
        Names applied with parentheses or braces: ``{'H': lambda z: ..., 'G^{-1}': ...}``.
    families : Mapping[str, IndexedFamily] or Iterable[IndexedFamily]
        Indexed families for ``\min_i``, ``\max_{i,j}`` and ``\sum`` bodies, keyed by pattern.
    constants : Mapping[str, sympy.Basic]
        Names used when neither ``symbols`` nor a bound index claims them: by default ``j`` is
        the imaginary unit, ``e`` Euler's number (``e^{x}`` is ``exp(x)``) and ``\pi`` is pi.
    indices : tuple of str
        Letters that are indices in subscripts, ranges, conditions and operator subscripts.
    superscripts : Mapping[str, Callable]
        Meanings of superscripts that are not powers, for the whole paper, e.g.
        ``{'c': sympy.conjugate}`` (teleoperator paper: "the superscript c denotes the complex
        conjugate").  A name registered with its superscript (``V_m^c``) still wins.

    >>> K, T = sp.symbols('K T', positive=True)
    >>> table = SymbolTable({'K': K, 'T': T}).with_symbols({'K_01': sp.Symbol('K_01')})
    >>> table.lookup('K_{01}'), 'K_{ 01 }' in table
    (K_01, True)
    """

    symbols: Mapping[str, Any] = field(default_factory=dict)
    functions: Mapping[str, Callable[..., Any]] = field(default_factory=dict)
    families: Mapping[str, IndexedFamily] | Iterable[IndexedFamily] = ()
    constants: Mapping[str, Any] = DEFAULT_CONSTANTS
    indices: tuple[str, ...] = ("i", "j", "k", "\\ell")
    superscripts: Mapping[str, Callable[[Any], Any]] = _FrozenMap()
    _specs: Mapping[str, _FamilySpec] = field(init=False, repr=False, compare=False)
    _words: frozenset[str] = field(init=False, repr=False, compare=False)

    def __post_init__(self) -> None:
        set_ = object.__setattr__
        set_(self, "symbols", _normalised(self.symbols, "symbol", _as_sympy))
        set_(self, "functions", _normalised(self.functions, "function", _as_callable))
        set_(self, "constants", _normalised(self.constants, "constant", _as_sympy))
        set_(self, "indices", tuple(normalise_name(i) for i in self.indices))
        set_(self, "superscripts", _FrozenMap({_canon(_tokenize(k)): _as_callable(v) for k, v in dict(self.superscripts).items()}))
        families = self.families.values() if isinstance(self.families, Mapping) else self.families
        families = [f if isinstance(f, IndexedFamily) else IndexedFamily(f) for f in families]
        set_(self, "families", _FrozenMap({f.pattern: f for f in families}))
        set_(self, "_specs", _FrozenMap({f.pattern: self._compile(f) for f in families}))
        words = set()
        for key in (*self.symbols, *self.functions):
            parts = _name_parts(key)
            if len(parts.base) > 1 and parts.base.isalpha():
                if parts.sub is not None or parts.sup is not None or parts.primes:
                    raise ValueError(
                        f"{key!r}: a multi-letter name cannot carry scripts (LaTeX attaches them "
                        "to the last letter)"
                    )
                words.add(parts.base)
        set_(self, "_words", frozenset(words))

    def _compile(self, family: IndexedFamily) -> _FamilySpec:
        parts = _name_parts(family.pattern)
        sub = list(parts.sub or ())
        pieces = _split_commas(sub)
        if len(pieces) > 1:
            slots = tuple(None if _canon(p) in self.indices else _canon(p) for p in pieces)
            comma = True
        else:
            slots = tuple(None if c in self.indices else c for c, _ in _sub_slots(sub))
            comma = False
        if None not in slots:
            raise ValueError(f"family {family.pattern!r} has no index letter from {self.indices}")
        base = parts.base + "'" * parts.primes
        return _FamilySpec(family, base, comma, slots)

    # -- lookups --------------------------------------------------------------------------------
    def __contains__(self, name: object) -> bool:
        return isinstance(name, str) and normalise_name(name) in self.symbols

    def lookup(self, name: str) -> Any:
        """The symbol of a printed name (any spelling), or ``None``."""
        return self.symbols.get(normalise_name(name))

    def concrete(self, pattern: str, values: Iterable[int]) -> Any:
        """The concrete member of a family for integer index values (creates missing ones).

        >>> t = SymbolTable(families=[IndexedFamily('K_{ij}', symmetric=True)])
        >>> t.concrete('K_{ij}', (2, 1))
        K_12
        """
        spec = self._specs[normalise_name(pattern)]
        values = [int(v) for v in values]
        if spec.family.symmetric:
            values = sorted(values)
        it = iter(values)
        filled = [str(next(it)) if s is None else s for s in spec.slots]
        if not spec.comma and any(len(v) > 1 for v, s in zip(filled, spec.slots) if s is None):
            raise ValueError(f"index values above 9 cannot be written in {spec.family.pattern!r}")
        name = normalise_name(f"{spec.base}_{{{(',' if spec.comma else '').join(filled)}}}")
        if spec.family.function:
            found = self.functions.get(name)
            return found if found is not None else sp.Function(_sympy_name(name))
        found = self.symbols.get(name)
        return found if found is not None else sp.Symbol(_sympy_name(name), **spec.family.assumptions)

    # -- derived tables -------------------------------------------------------------------------
    def with_symbols(self, mapping: Mapping[str, Any] | None = None, /, **more: Any) -> SymbolTable:
        """A copy with more (or overriding) symbols; keyword names must be plain identifiers."""
        return replace(self, symbols={**self.symbols, **_renormalised(mapping, more)})

    def with_functions(
        self, mapping: Mapping[str, Callable[..., Any]] | None = None, /, **more: Callable[..., Any]
    ) -> SymbolTable:
        """A copy with more (or overriding) functions."""
        return replace(self, functions={**self.functions, **_renormalised(mapping, more)})

    def with_families(self, *families: IndexedFamily) -> SymbolTable:
        """A copy with more families."""
        return replace(self, families=[*self.families.values(), *families])

    def with_constants(self, mapping: Mapping[str, Any] | None = None, /, **more: Any) -> SymbolTable:
        """A copy with constants changed; a value of ``None`` removes the constant.

        >>> SymbolTable().with_constants(j=None).constants.get('j') is None
        True
        """
        merged = {**self.constants, **_renormalised(mapping, more)}
        return replace(self, constants={k: v for k, v in merged.items() if v is not None})

    @classmethod
    def from_names(cls, names: Iterable[str], **assumptions: bool) -> SymbolTable:
        """A table of fresh symbols (see :func:`symbol_for`) for the given printed names.

        >>> SymbolTable.from_names(['K_{01}', r'\\omega'], positive=True).lookup('K_01')
        K_01
        """
        return cls({name: symbol_for(name, **assumptions) for name in names})


def _as_sympy(value: Any) -> Any:
    if isinstance(value, sp.MatrixBase):
        return sp.ImmutableMatrix(value)
    return sp.sympify(value, strict=True)


def _as_callable(value: Any) -> Any:
    if not callable(value):
        raise TypeError(f"{value!r} is not callable")
    return value


def _normalised(mapping: Mapping[str, Any], what: str, convert: Callable[[Any], Any]) -> _FrozenMap:
    out: dict[str, Any] = {}
    for key, value in dict(mapping).items():
        try:
            canonical = normalise_name(key)
        except LatexParseError as err:
            raise ValueError(f"invalid {what} name {key!r}: {err}") from None
        if canonical in out:
            raise ValueError(f"{what} names {key!r} and another key both normalise to {canonical!r}")
        out[canonical] = convert(value)
    return _FrozenMap(out)


def _renormalised(mapping: Mapping[str, Any] | None, more: Mapping[str, Any]) -> dict[str, Any]:
    return {normalise_name(k): v for k, v in {**(mapping or {}), **more}.items()}


# ----------------------------------------------------------------------------------------------
# Display-level processing: tags, labels, environments, line breaks
# ----------------------------------------------------------------------------------------------


def _is_known_command(name: str) -> bool:
    return any(
        name in group
        for group in (
            _GREEK, _DECORATIONS, _ELEMENTARY, _PARTS, _FRACTIONS, _OPERATOR_COMMANDS, _RELATIONS,
            _UNSUPPORTED_RELATIONS, _ARROWS, _ELLIPSES, _MULTIPLY, ("\\pm", "\\mp"),
        )
    )


def _is_relation(t: _Tok) -> bool:
    return (t.kind == "op" and t.value in "=<>") or (t.kind == "cmd" and t.value in _RELATIONS)


def _is_binary(t: _Tok) -> bool:
    return (t.kind == "op" and t.value in "+-*/") or (t.kind == "cmd" and t.value in _MULTIPLY)


def _is_tag_number(t: _Tok) -> bool:
    return t.kind == "number" and "." not in t.value


def _extract_tag(text: str, toks: list[_Tok]) -> tuple[list[_Tok], str | None]:
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
        spaced = o.space and any(_is_relation(x) for _, x in _top_level(text, rest))
        if before is None or before.kind == "sep" or spaced:
            return _strip_trailing(rest), "".join(t.value for t in mid)
    return body, None


def _strip_trailing(toks: list[_Tok]) -> list[_Tok]:
    end = len(toks)
    while end and toks[end - 1].kind in ("sep", "newline"):
        end -= 1
    return toks[:end]


def _strip_leading(toks: list[_Tok]) -> list[_Tok]:
    start = 0
    while start < len(toks) and toks[start].kind == "sep":
        start += 1
    return toks[start:]


def _extract_label(toks: list[_Tok]) -> tuple[list[_Tok], str | None]:
    r"""Remove a leading ``\text{A)}`` label (and the separator after it)."""
    if toks and toks[0].kind == "text" and _LABEL.match(toks[0].arg or ""):
        rest = toks[1:]
        while rest and rest[0].kind == "sep":
            rest = rest[1:]
        return rest, toks[0].arg.strip()
    return toks, None


def _unwrap(text: str, toks: list[_Tok]) -> tuple[list[_Tok], bool]:
    r"""Strip ``\boxed{...}`` and alignment environments enclosing the whole display."""
    aligned = False
    while toks:
        match = _match(text, toks)
        first = toks[0]
        if first.kind == "cmd" and first.value == "\\boxed" and len(toks) > 2:
            if toks[1].kind == "op" and toks[1].value == "{" and match[1] == len(toks) - 1:
                toks = toks[2:-1]
                continue
        if first.kind == "begin" and first.value in _ALIGN_ENVS and match[0] == len(toks) - 1:
            toks, aligned = toks[1:-1], True
            continue
        break
    return toks, aligned


def _top_level(text: str, toks: list[_Tok]) -> Iterator[tuple[int, _Tok]]:
    """Tokens outside every delimiter pair, with their indices."""
    match = _match(text, toks)
    k = 0
    while k < len(toks):
        yield k, toks[k]
        k = match[k] + 1 if (k in match and match[k] > k) else k + 1


def _split_lines(text: str, toks: list[_Tok], aligned: bool) -> list[list[_Tok]]:
    r"""Split at top-level ``\\`` and re-join lines that merely wrap one statement.

    A ``\\`` (and an alignment ``&``) inside an open group other than a matrix or ``cases`` is a
    wrap of that group (teleoperator eq. (32) breaks a parenthesis across lines): it is dropped.
    """
    lines: list[list[_Tok]] = [[]]
    stack: list[bool] = []  # per open group: is it an environment with its own rows?
    for t in toks:
        if _opener_key(t) is not None:
            stack.append(t.kind == "begin")
        elif _closer_key(t) is not None:
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
    merged: list[list[_Tok]] = []
    for line in lines:
        if merged and _wraps(text, merged[-1], line):
            merged[-1] = merged[-1] + line
        else:
            merged.append(line)
    return merged


def _wraps(text: str, previous: list[_Tok], line: list[_Tok]) -> bool:
    """Whether ``line`` continues ``previous`` (a wrapped statement) rather than starting one."""
    if _is_binary(previous[-1]) or _is_relation(previous[-1]):
        return True
    if _is_binary(line[0]) or _is_relation(line[0]):
        return True
    # Why: a display line holding no relation yet is a wrapped expression (e.g. HVE eq. (44)).
    return not any(_is_relation(t) for _, t in _top_level(text, previous))


def _strip_math_delimiters(text: str) -> tuple[int, int]:
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
    lo, hi = _strip_math_delimiters(text)
    toks = _demote_separators(_tokenize(text, lo, hi))
    _match(text, toks)
    toks, tag = _extract_tag(text, toks)
    toks, label = _extract_label(toks)
    toks, aligned = _unwrap(text, toks)
    if not toks:
        what = f"only the equation number ({tag})" if tag else "nothing"
        raise LatexParseError(f"the display holds {what}", text, lo)
    lines = _split_lines(text, toks, aligned)
    statements = [_Parser(text, line, table).parse_line() for line in lines]
    if len(statements) == 1:
        result = statements[0]
    else:
        result = Lines(tuple(statements), "lines", Span(statements[0].span.start, statements[-1].span.end))
    return replace(result, tag=tag, label=label)


def slash_readings(text: str, table: SymbolTable) -> dict[str, str]:
    r"""The two readings of an ambiguous ``a / b c`` in a display that the parser rejects for it:
    ``\frac{a}{b} c`` and ``\frac{a}{b c}`` (spelled out in the printed text, so that both
    parse), keyed by a description; empty when the display parses or fails for another reason.

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
    lo, hi = _strip_math_delimiters(text)
    toks = _tokenize(text, lo, hi)
    depth, stack = {}, 0
    for k, t in enumerate(toks):
        if _opener_key(t) is not None:
            depth[k] = stack
            stack += 1
        elif _closer_key(t) is not None:
            stack -= 1
            depth[k] = stack
        else:
            depth[k] = stack
    slash = max((k for k, t in enumerate(toks) if t.kind == "op" and t.value == "/" and t.pos < where), default=None)
    if slash is None:
        return {}
    level = depth[slash]

    def boundary(t: _Tok, k: int) -> bool:
        return depth[k] == level and (_is_relation(t) or (t.kind == "op" and t.value in "+-,&") or t.kind in ("sep", "newline", "tag"))

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

    >>> x = sp.Symbol('x')
    >>> parse_expression(r'\frac{x^2}{2} + 3x', SymbolTable({'x': x}))
    x**2/2 + 3*x
    """
    stmt = parse_printed(text, table)
    if not isinstance(stmt, Expression):
        raise LatexParseError(f"expected an expression, got a {type(stmt).__name__}", text, stmt.span.start)
    return stmt.expr


# ----------------------------------------------------------------------------------------------
# The parser proper
# ----------------------------------------------------------------------------------------------


@dataclass(frozen=True, slots=True)
class _Script:
    """A ``_``/``^`` script: the token range of its content and its canonical text."""

    start: int
    stop: int
    toks: tuple[_Tok, ...]
    op: _Tok

    @property
    def canon(self) -> str:
        return _canon(self.toks)


def _is_matrix(value: Any) -> bool:
    return isinstance(value, (sp.MatrixBase, sp.MatrixExpr))


class _Parser:
    """Recursive-descent parser over the tokens of one (possibly wrapped) line."""

    def __init__(self, text: str, toks: list[_Tok], table: SymbolTable) -> None:
        self.text = text
        self.toks = toks
        self.table = table
        self.match = _match(text, toks)
        self.i = 0
        self.limit = len(toks)
        self.last_end = toks[0].pos if toks else 0
        self.scopes: list[dict[str, sp.Symbol]] = []
        self.index_mode = 0
        self.depth = 0
        self.bars: list[tuple[str, int]] = []  # open | and \| with the depth they close at
        self.differentials: list[str] = []  # integration variables awaiting their d<var>

    # -- token access -----------------------------------------------------------------------------
    def peek(self, k: int = 0) -> _Tok:
        j = self.i + k
        if j < self.limit:
            return self.toks[j]
        end = self.toks[self.limit - 1].end if self.limit else len(self.text)
        return _Tok("eof", "end of input", end, end)

    def next(self) -> _Tok:
        t = self.peek()
        if t.kind != "eof":
            self.i += 1
            self.last_end = t.end
        return t

    def at(self, kind: str, value: str | None = None, k: int = 0) -> bool:
        t = self.peek(k)
        return t.kind == kind and (value is None or t.value == value)

    def error(self, message: str, tok: _Tok | None = None) -> LatexParseError:
        return LatexParseError(message, self.text, (tok or self.peek()).pos)

    def unexpected(self, context: str) -> LatexParseError:
        t = self.peek()
        if t.kind == "eof":
            return self.error(f"unexpected end of input in {context}")
        if _is_relation(t):
            return self.error(f"relation symbol '{t.value}' inside {context}")
        if t.kind == "cmd" and t.value in _UNSUPPORTED_RELATIONS:
            return self.error(f"unsupported relation {t.value}")
        if t.kind == "text":
            return self.error(f"prose {t.value}{{{t.arg}}} is not mathematics")
        if t.kind == "cmd" and not _is_known_command(t.value):
            return self.error(f"unsupported command {t.value}")
        return self.error(f"unexpected '{_describe(t)}' in {context}")

    @contextmanager
    def bounded(self, start: int, stop: int, context: str) -> Iterator[None]:
        """Parse ``toks[start:stop]`` (a script or group) and require it all to be consumed."""
        saved = (self.i, self.limit, self.last_end)
        self.i, self.limit = start, stop
        try:
            yield
            if self.i < self.limit:
                raise self.unexpected(context)
        finally:
            self.i, self.limit, self.last_end = saved

    @contextmanager
    def scope(self, names: Mapping[str, sp.Symbol]) -> Iterator[None]:
        self.scopes.append(dict(names))
        try:
            yield
        finally:
            self.scopes.pop()

    @contextmanager
    def nested(self) -> Iterator[None]:
        self.depth += 1
        try:
            yield
        finally:
            self.depth -= 1

    @contextmanager
    def indexing(self) -> Iterator[None]:
        self.index_mode += 1
        try:
            yield
        finally:
            self.index_mode -= 1

    def combine(self, build: Callable[[], Any], tok: _Tok, what: str) -> Any:
        """Run a SymPy construction; turn its failures (shape errors...) into parse errors."""
        try:
            return build()
        except LatexParseError:
            raise
        except (TypeError, ValueError, NotImplementedError, ArithmeticError) as err:
            detail = str(err).strip().splitlines()[0] if str(err).strip() else type(err).__name__
            raise self.error(f"cannot build {what}: {detail}", tok) from None

    def span_from(self, tok: _Tok) -> Span:
        return Span(tok.pos, max(tok.pos, self.last_end))

    # -- lines and clauses ------------------------------------------------------------------------
    def parse_line(self) -> Statement:
        first = self.peek()
        steps: list[list[Any]] = [[]]
        self.skip_arrows()
        while self.peek().kind != "eof":
            steps[-1].append(self.parse_clause())
            if self.skip_separators():
                continue
            if self.at_arrow():
                arrow = self.peek()
                self.skip_arrows()
                if self.peek().kind == "eof":
                    raise self.error(f"nothing follows {arrow.value}", arrow)
                steps.append([])
                continue
            if self.peek().kind != "eof":
                raise self.unexpected("the statement")
        if not steps[0]:
            raise self.error("an arrow without a statement", first)
        statements = [self.assemble(step, first) for step in steps]
        if len(statements) == 1:
            return statements[0]
        return Lines(tuple(statements), "steps", self.span_from(first))

    def assemble(self, clauses: list[Any], first: _Tok) -> Statement:
        mains = [c for c in clauses if isinstance(c, Statement)]
        ranges = tuple(c for c in clauses if isinstance(c, IndexRange))
        conditions = tuple(c for c in clauses if isinstance(c, _Condition))
        if not mains:
            raise self.error("a qualifier without a statement", first)
        if len(mains) == 1:
            body: Statement = mains[0]
        else:
            body = Lines(tuple(mains), "list", Span(mains[0].span.start, mains[-1].span.end))
        if not ranges and not conditions:
            return body
        span = Span(body.span.start, max(x.span.end for x in (body, *ranges, *conditions)))
        return Qualified(body, ranges, tuple(c.relation for c in conditions), span)

    def at_arrow(self) -> bool:
        t = self.peek()
        return t.kind == "cmd" and t.value in _ARROWS

    def skip_arrows(self) -> None:
        while self.at_arrow():
            t = self.next()
            if t.value == "\\xrightarrow":
                if self.at("op", "["):
                    self.i = self.match[self.i] + 1
                if not self.at("op", "{"):
                    raise self.error("\\xrightarrow needs a braced label")
                self.i = self.match[self.i] + 1

    def at_connector(self, k: int = 0) -> bool:
        t = self.peek(k)
        return t.kind == "text" and t.value != "\\mathrm" and " ".join(t.arg.split()) in _CONNECTORS

    def at_clause_end(self, k: int = 0) -> bool:
        t = self.peek(k)
        return (
            t.kind in ("eof", "sep")
            or (t.kind == "op" and t.value in ",.")
            or self.at_connector(k)
            or (t.kind == "cmd" and t.value in _ARROWS)
        )

    def skip_separators(self) -> bool:
        """Consume clause separators (``,``, ``\\quad``, ``\\text{ where }``, a final ``.``)."""
        consumed = False
        while True:
            t = self.peek()
            if t.kind == "sep" or (t.kind == "op" and t.value == ",") or self.at_connector():
                self.next()
            elif t.kind == "op" and t.value == ".":
                nxt = self.peek(1)
                if not (nxt.kind in ("eof", "sep") or self.at_connector(1)):
                    raise self.error("'.' is only allowed as final punctuation")
                self.next()
            else:
                return consumed
            consumed = True

    def index_name(self, k: int = 0) -> str | None:
        """The index letter at ``peek(k)`` if it stands alone (no scripts or application)."""
        t = self.peek(k)
        if t.kind not in ("letter", "cmd") or t.value not in self.table.indices:
            return None
        nxt = self.peek(k + 1)
        if nxt.kind == "op" and nxt.value in "_^'(" and not nxt.space:
            return None
        if nxt.kind == "letter" and not nxt.space:
            return None
        return t.value

    def parse_clause(self) -> Any:
        if self.looks_like_range():
            return self.parse_range()
        if self.looks_like_condition():
            return self.parse_condition()
        return self.parse_chain()

    def looks_like_range(self) -> bool:
        k = 0
        if self.index_name(k) is None:
            return False
        while self.at("op", ",", k + 1) and self.index_name(k + 2) is not None:
            k += 2
        return self.at("op", "=", k + 1)

    def looks_like_condition(self) -> bool:
        if self.index_name(0) is None or not _is_relation(self.peek(1)):
            return False
        k = 1
        while _is_relation(self.peek(k)):
            if self.index_name(k + 1) is None:
                return False
            k += 2
        return self.at_clause_end(k)

    def parse_range(self) -> IndexRange:
        first = self.peek()
        names = [self.next().value]
        while self.at("op", ","):
            self.next()
            names.append(self.next().value)
        self.next()  # '='
        value = self.range_value()
        if value is None:
            raise self.unexpected("an index range")
        values = [value]
        while self.at("op", ","):
            saved = (self.i, self.last_end)
            self.next()
            value = self.range_value()
            if value is None:  # the comma ends the range: 'i = 1, 2, j \neq i'
                self.i, self.last_end = saved
                break
            values.append(value)
        return IndexRange(tuple(index_symbol(n) for n in names), tuple(values), self.span_from(first))

    def range_value(self) -> Any | None:
        r"""One value of an index range (a number, ``\dots``, ``m``, ``n_1``...) or None."""
        t = self.peek()
        if t.kind == "cmd" and t.value in _ELLIPSES and self.at_clause_end(1):
            self.next()
            return Elision(t.value)
        if t.kind == "letter" and self.at_clause_end(1) and normalise_name(t.value) not in self.table.symbols:
            self.next()
            # Why: 'i = x, y, z' enumerates axis labels, which are not quantities of the table.
            return sp.Symbol(t.value)
        saved = (self.i, self.last_end)
        try:
            with self.indexing():
                value = self.parse_unary_factor()
        except LatexParseError:
            value = None
        if value is None or not self.at_clause_end() or self.index_name(0) is not None:
            self.i, self.last_end = saved
            return None
        return value

    def parse_condition(self) -> _Condition:
        first = self.peek()
        terms = [index_symbol(self.next().value)]
        ops = []
        while _is_relation(self.peek()):
            ops.append(self.relation_op())
            terms.append(index_symbol(self.next().value))
        return _Condition(Relation(tuple(terms), tuple(ops), self.span_from(first)))

    def relation_op(self) -> str:
        t = self.next()
        if t.kind == "op" and t.value in "<>" and self.at("op", "=") and not self.peek().space:
            self.next()
            return t.value + "="
        return _RELATIONS[t.value]

    def parse_chain(self) -> Statement:
        first = self.peek()
        if _is_relation(first):
            raise self.error(f"missing left-hand side before '{first.value}'")
        terms, spans, ops = [], [], []
        while True:
            start = self.peek()
            terms.append(self.parse_sum())
            spans.append(self.span_from(start))
            if not _is_relation(self.peek()):
                break
            op_tok = self.peek()
            ops.append(self.relation_op())
            if self.at_clause_end() or _is_relation(self.peek()):
                raise self.error(f"missing right-hand side after '{op_tok.value}'")
        t = self.peek()
        if t.kind == "cmd" and t.value in _UNSUPPORTED_RELATIONS:
            raise self.error(f"unsupported relation {t.value}")
        span = self.span_from(first)
        if not ops:
            return Expression(terms[0], span)
        return Relation(tuple(terms), tuple(ops), span, tuple(spans))

    # -- expressions ------------------------------------------------------------------------------
    def parse_sum(self) -> Any:
        value = self.parse_signed()
        while True:
            t = self.peek()
            if t.kind == "op" and t.value in "+-":
                self.next()
                rhs = self.parse_signed()
                if t.value == "+":
                    value = self.combine(lambda v=value, r=rhs: v + r, t, "a sum")
                else:
                    value = self.combine(lambda v=value, r=rhs: v - r, t, "a difference")
            elif t.kind == "cmd" and t.value in ("\\pm", "\\mp"):
                raise self.error(f"{t.value} stands for two statements; write them separately")
            else:
                return value

    def parse_signed(self) -> Any:
        t = self.peek()
        if t.kind == "op" and t.value in "+-":
            self.next()
            operand = self.parse_signed()
            return self.combine(lambda: -operand, t, "a negation") if t.value == "-" else operand
        if not self.starts_operand():
            if t.kind == "eof":
                raise self.error("expected an expression at the end of input")
            raise self.unexpected("an expression")
        return self.parse_product()

    def parse_product(self) -> Any:
        value = self.parse_factor(first=True)
        while True:
            t = self.peek()
            if t.kind in ("op", "cmd") and t.value in _MULTIPLY:
                self.next()
                rhs = self.parse_unary_factor()
                value = self.combine(lambda v=value, r=rhs: v * r, t, "a product")
            elif t.kind == "op" and t.value == "/":
                self.next()
                rhs = self.parse_unary_factor()
                value = self.combine(lambda v=value, r=rhs: v / r, t, "a quotient")
                if self.starts_implicit():
                    raise self.error(
                        "ambiguous implicit product after '/' (a / b c); use \\frac or parentheses"
                    )
            elif self.starts_implicit():
                rhs = self.parse_factor(first=False)
                value = self.combine(lambda v=value, r=rhs: v * r, t, "a product")
            else:
                return value

    def parse_unary_factor(self) -> Any:
        t = self.peek()
        if t.kind == "op" and t.value in "+-":
            self.next()
            operand = self.parse_unary_factor()
            return -operand if t.value == "-" else operand
        if not self.starts_operand():
            raise self.unexpected(f"the operand after '{self.toks[self.i - 1].value}'")
        return self.parse_factor(first=True)

    def starts_operand(self) -> bool:
        t = self.peek()
        if t.kind == "number":
            return True
        if t.kind == "cmd" and t.value in _ELLIPSES:
            return True
        return self.starts_implicit()

    def at_function_command(self) -> bool:
        t = self.peek()
        if t.kind == "cmd":
            return t.value in _ELEMENTARY or t.value in _PARTS or t.value in _OPERATOR_COMMANDS - {
                "\\sqrt",
                "\\boxed",
                "\\infty",
            }
        return t.kind == "text" and t.arg.strip() in ("Re", "Im", "det", "diag")

    def at_differential(self) -> bool:
        """Whether ``d<var>`` of the innermost open integral starts here."""
        if not self.differentials or not self.at("letter", "d"):
            return False
        nxt = self.peek(1)
        return nxt.kind in ("letter", "cmd") and nxt.value == self.differentials[-1]

    def bar_closes(self, bar: str) -> bool:
        return bool(self.bars) and self.bars[-1] == (bar, self.depth)

    def starts_implicit(self) -> bool:
        """Whether the next token can start a juxtaposed factor."""
        t = self.peek()
        if t.kind == "letter":
            return not self.at_differential()
        if t.kind == "number":
            return True
        if t.kind == "cmd":
            return (
                t.value in _GREEK
                or t.value in _DECORATIONS
                or t.value in _FRACTIONS
                or t.value in _ELEMENTARY
                or t.value in _PARTS
                or t.value in _OPERATOR_COMMANDS
            )
        if t.kind == "text":
            arg = t.arg.strip()
            return arg in ("Re", "Im", "det", "diag") or (
                t.value in ("\\mathrm", "\\operatorname") and arg.isalpha()
            )
        if t.kind in ("left", "begin"):
            return True
        if t.kind == "op":
            return t.value in "([{" or (t.value == "|" and not self.bar_closes("|"))
        if t.kind == "sym":
            return t.value == "\\{" or (t.value == "\\|" and not self.bar_closes("\\|"))
        return False

    def parse_factor(self, first: bool) -> Any:
        t = self.peek()
        if t.kind == "number":
            if not first:
                raise self.error(
                    f"number {t.value} after a factor is ambiguous; write it first or use \\cdot"
                )
            self.next()
            return self.postfix(sp.Rational(t.value), t, applied=False)
        if t.kind == "cmd" and t.value in _ELLIPSES:
            if not first:
                raise self.error(f"{t.value} cannot be a factor of a product")
            self.next()
            return Elision(t.value)
        value = self.parse_atom()
        return self.postfix(value, t, applied=True)

    def postfix(self, value: Any, start: _Tok, applied: bool) -> Any:
        """Superscripts on a non-name atom and the evaluation bar ``|_{z=...}``."""
        while True:
            t = self.peek()
            if t.kind == "op" and t.value == "^":
                script = self.read_script()
                value = self.superscript(value, script, start, applied=False)
            elif t.kind == "op" and t.value == "_":
                raise self.error("a subscript needs a name before it")
            elif t.kind == "op" and t.value == "|" and self.at("op", "_", 1):
                value = self.evaluation_bar(value)
            else:
                return value

    def parse_atom(self) -> Any:
        t = self.peek()
        if t.kind == "letter":
            return self.parse_name()
        if t.kind == "cmd":
            v = t.value
            if v in _GREEK or v in _DECORATIONS:
                return self.parse_name()
            if v in _FRACTIONS:
                return self.parse_fraction()
            if v in _ELEMENTARY:
                return self.parse_elementary()
            if v in _PARTS:
                return self.parse_part()
            if v == "\\det":
                return self.parse_det()
            if v in ("\\min", "\\max"):
                return self.parse_extremum()
            if v == "\\sum":
                return self.parse_summation()
            if v == "\\lim":
                return self.parse_limit()
            if v == "\\int":
                return self.parse_integral()
            if v == "\\sqrt":
                return self.parse_sqrt()
            if v == "\\infty":
                self.next()
                return sp.oo
            if v == "\\boxed":
                self.next()
                return self.parse_braced("\\boxed{...}")
            raise self.error(f"unsupported command {v}")
        if t.kind == "text":
            arg = t.arg.strip()
            if arg in ("Re", "Im"):
                return self.parse_part()
            if arg == "det":
                return self.parse_det()
            if arg == "diag":
                return self.parse_diag()
            if t.value in ("\\mathrm", "\\operatorname") and arg.isalpha():
                return self.parse_name()
            raise self.error(f"prose {t.value}{{{t.arg}}} is not mathematics")
        if t.kind == "op":
            if t.value == "(":
                return self.parse_group("parentheses")
            if t.value == "[":
                return self.parse_bracket()
            if t.value == "{":
                return self.parse_braced("braces")
            if t.value == "|":
                return self.parse_bars("|", "|", "an absolute value")
        if t.kind == "sym":
            if t.value == "\\{":
                return self.parse_group("\\{...\\}")
            if t.value == "\\|":
                return self.parse_bars("\\|", "\\|", "a norm")
        if t.kind == "left":
            return self.parse_left()
        if t.kind == "begin":
            return self.parse_environment()
        raise self.unexpected("an expression")

    # -- names ------------------------------------------------------------------------------------
    def read_base(self) -> tuple[str, int]:
        """Canonical base of the name at the cursor and its token count (no consumption)."""
        t = self.peek()
        if t.kind == "letter":
            run = [t]
            while self.peek(len(run)).kind == "letter" and not self.peek(len(run)).space:
                run.append(self.peek(len(run)))
            word = "".join(x.value for x in run)
            for n in range(len(run), 1, -1):
                after = self.peek(n)
                scripted = after.kind == "op" and after.value in "_^'" and not after.space
                if word[:n] in self.table._words and not scripted:
                    return word[:n], n
            return t.value, 1
        base, end = _read_base(self.text, self.toks, self.i, self.match)
        if end > self.limit:
            raise self.error(f"unbalanced argument of {t.value}")
        return base, end - self.i

    def parse_name(self) -> Any:
        start = self.peek()
        if start.kind == "letter":
            word = self.letter_word()
            if word is not None:
                return self.parse_word(word)
        if start.kind == "cmd" and start.value in _DECORATIONS:
            split = self.split_decoration()
            if split is not None:
                return split
        base, width = self.read_base()
        for _ in range(width):
            self.next()
        primes, sub, sup = 0, None, None
        while True:
            t = self.peek()
            if t.kind == "op" and t.value == "'":
                self.next()
                primes += 1
            elif t.kind == "op" and t.value in "_^":
                if (t.value == "_" and sub is not None) or (t.value == "^" and sup is not None):
                    raise self.error(f"double {'sub' if t.value == '_' else 'super'}script")
                script = self.read_script()
                if t.value == "_":
                    sub = script
                elif script.canon == "\\prime":
                    primes += 1
                else:
                    sup = script
            else:
                break
        return self.resolve(start, base, primes, sub, sup)

    def letter_word(self) -> str | None:
        """A built-in word (``det``, ``diag``) spelled by adjacent letters at the cursor."""
        for word in _WORDS:  # longest first
            toks = [self.peek(k) for k in range(len(word))]
            if all(t.kind == "letter" for t in toks) and "".join(t.value for t in toks) == word:
                if all(not t.space for t in toks[1:]) and word not in self.table._words:
                    return word
        return None

    def parse_word(self, word: str) -> Any:
        if word == "det":
            return self.parse_det(width=3)
        return self.parse_diag(width=4)

    def split_decoration(self) -> Any:
        r"""``\mathcal{MN}`` is ``\mathcal{M}\mathcal{N}`` unless the table knows the whole name."""
        cmd = self.peek()
        if not self.at("op", "{", 1):
            return None
        close = self.match[self.i + 1]
        inner = self.toks[self.i + 2 : close]
        if len(inner) < 2 or not all(t.kind == "letter" for t in inner):
            return None
        whole = f"{cmd.value}{{{''.join(t.value for t in inner)}}}"
        if whole in self.table.symbols or whole in self.table.functions:
            return None
        nxt = self.toks[close + 1] if close + 1 < self.limit else None
        if nxt is not None and nxt.kind == "op" and nxt.value in "_^'":
            raise self.error(f"a script after {whole} is ambiguous (which letter carries it?)", nxt)
        self.i = close + 1
        self.last_end = self.toks[close].end
        value: Any = sp.S.One
        for t in inner:
            value = value * self.resolve(t, f"{cmd.value}{{{t.value}}}", 0, None, None)
        return value

    def read_script(self) -> _Script:
        """Consume ``_x``, ``^x``, ``_{...}`` or ``^{...}`` and return its content."""
        op = self.next()
        t = self.peek()
        if t.kind == "op" and t.value == "{":
            close = self.match[self.i]
            start, stop = self.i + 1, close
            if start == stop:
                raise self.error(f"empty script after '{op.value}'", op)
            self.i = close + 1
            self.last_end = self.toks[close].end
            return _Script(start, stop, tuple(self.toks[start:stop]), op)
        if t.kind == "eof":
            raise self.error(f"missing script after '{op.value}'", op)
        single = (
            t.kind == "letter"
            or (t.kind == "cmd" and (t.value in _GREEK or t.value in ("\\infty", "\\prime", "\\ast", "\\star")))
            or (t.kind == "op" and t.value in "*+-'")
            or t.kind == "number"
        )
        if not single:
            raise self.error(f"the script after '{op.value}' needs braces")
        if t.kind == "number" and len(t.value) > 1:
            raise self.error(
                f"'{op.value}{t.value}' sets only '{t.value[0]}' as the script in LaTeX; "
                f"write {op.value}{{{t.value}}}"
            )
        self.next()
        return _Script(self.i - 1, self.i, (t,), op)

    def parse_script(self, script: _Script, context: str) -> Any:
        with self.bounded(script.start, script.stop, context), self.nested():
            return self.parse_sum()

    def at_application(self) -> bool:
        t = self.peek()
        return (t.kind == "op" and t.value == "(") or (t.kind == "sym" and t.value == "\\{") or (
            t.kind == "left" and t.value in ("(", "\\{")
        )

    def bound(self, name: str) -> sp.Symbol | None:
        for names in reversed(self.scopes):
            if name in names:
                return names[name]
        return None

    def resolve(
        self, start: _Tok, base: str, primes: int, sub: _Script | None, sup: _Script | None
    ) -> Any:
        """Give a parsed name its meaning (symbol, function application, family member...)."""
        table = self.table
        plain = _compose(base, primes, sub.toks if sub else None, None)
        if sup is not None:
            full = _compose(base, primes, sub.toks if sub else None, sup.toks)
            if full in table.functions and self.at_application():
                return self.apply(table.functions[full], full, start)
            if full in table.symbols:
                return table.symbols[full]
        applied = False
        value: Any = None
        if sub is None and not primes and (found := self.bound(base)) is not None:
            value = found
        elif plain in table.functions and self.at_application():
            value, applied = self.apply(table.functions[plain], plain, start), True
        elif plain in table.symbols:
            value = table.symbols[plain]
        elif sub is None and not primes and self.index_mode and base in table.indices:
            value = index_symbol(base)
        elif sub is None and not primes and base in table.constants:
            value = table.constants[base]
        elif sub is not None and (member := self.family_member(base, primes, sub, start)) is not None:
            value, applied = member
        elif plain in table.functions:
            raise self.error(f"function {plain} used without an argument", start)
        else:
            raise self.error(f"unknown name {plain}", start)
        if sup is not None:
            value = self.superscript(value, sup, start, applied=applied, name=plain)
        return value

    def family_member(
        self, base: str, primes: int, sub: _Script, start: _Tok
    ) -> tuple[Any, bool] | None:
        """Match ``base_{sub}`` against the table's families; ``(value, applied)`` or None."""
        full_base = base + "'" * primes
        candidates: list[tuple[int, _FamilySpec, list[Any]]] = []
        for spec in self.table._specs.values():
            if spec.base != full_base:
                continue
            found = self.match_family(spec, sub)
            if found is not None:
                candidates.append((found[0], spec, found[1]))
        if not candidates:
            return None
        best = max(c[0] for c in candidates)
        winners = [c for c in candidates if c[0] == best]
        if len(winners) > 1:
            names = ", ".join(c[1].family.pattern for c in winners)
            raise self.error(f"{full_base}_{{{sub.canon}}} matches several families: {names}", start)
        _, spec, indices = winners[0]
        concrete = all(isinstance(v, sp.Integer) for v in indices)
        if spec.family.function:
            if not self.at_application():
                raise self.error(f"function {spec.family.pattern} used without an argument", start)
            args = self.call_arguments(spec.family.pattern, start)
            if concrete:
                func = self.table.concrete(spec.family.pattern, indices)
                return self.combine(lambda: func(*args), start, f"{spec.family.pattern}(...)"), True
            return IndexedCall(spec.family.pattern, indices, args), True
        if concrete:
            return self.table.concrete(spec.family.pattern, indices), False
        return sp.IndexedBase(spec.family.pattern)[tuple(indices)], False

    def match_family(self, spec: _FamilySpec, sub: _Script) -> tuple[int, list[Any]] | None:
        """``(number of literal slots matched, index values)`` or None."""
        toks = list(sub.toks)
        indices: list[Any] = []
        literals = 0
        if spec.comma:
            parts = _split_commas(toks)
            if len(parts) != len(spec.slots):
                return None
            offset = sub.start
            for part, slot in zip(parts, spec.slots):
                if not part:
                    return None
                if slot is not None:
                    if _canon(part) != slot:
                        return None
                    literals += 1
                else:
                    with self.bounded(offset, offset + len(part), "an index"), self.indexing():
                        indices.append(self.parse_sum())
                offset += len(part) + 1
            return literals, indices
        slots = _sub_slots(toks)
        if len(slots) != len(spec.slots):
            return None
        for (text, tok), slot in zip(slots, spec.slots):
            if slot is not None:
                if text != slot:
                    return None
                literals += 1
            elif text in self.table.indices:
                indices.append(self.bound(text) or index_symbol(text))
            elif text.isdigit():
                indices.append(sp.Integer(text))
            else:
                return None
        return literals, indices

    def superscript(
        self, value: Any, sup: _Script, start: _Tok, applied: bool, name: str | None = None
    ) -> Any:
        """Apply ``^T`` (transpose) or a power; other superscripts must be table names."""
        canon = sup.canon
        shown = name or "the expression"
        if canon in self.table.superscripts:
            meaning = self.table.superscripts[canon]
            if isinstance(value, sp.MatrixBase):
                return value.applyfunc(meaning)
            return self.combine(lambda: meaning(value), sup.op, f"^{canon}")
        if canon == "T" and value is not sp.E:
            if _is_matrix(value):
                return self.combine(lambda: value.T, sup.op, "a transpose")
            if not applied and "T" in self.table.symbols:
                raise self.error(
                    f"'^T' on the scalar {shown} is ambiguous (transpose, or power of T?)", sup.op
                )
            return value  # the transpose of a scalar
        if canon in ("*", "+", "-", "\\ast", "\\star", "\\dagger", "H", "c"):
            hint = f"; add '{name}^{{{canon}}}' to the table" if name else ""
            raise self.error(f"superscript '{canon}' on {shown} is not a power{hint}", sup.op)
        exponent = self.parse_script(sup, "a superscript")
        if applied and name is not None and not exponent.is_Integer:
            raise self.error(
                f"superscript '{canon}' on the function {name} is ambiguous; "
                f"add '{name}^{{{canon}}}' to the table",
                sup.op,
            )
        return self.combine(lambda: value**exponent, sup.op, "a power")

    def apply(self, func: Callable[..., Any], name: str, start: _Tok) -> Any:
        args = self.call_arguments(name, start)
        return self.combine(lambda: func(*args), start, f"{name}(...)")

    def call_arguments(self, name: str, start: _Tok) -> list[Any]:
        open_ = self.next()
        context = f"the argument of {name}"
        with self.nested():
            args = [self.parse_sum()]
            while self.at("op", ","):
                self.next()
                args.append(self.parse_sum())
            self.expect_close(open_, context)
        return args

    def closer_for(self, open_: _Tok) -> tuple[str, str]:
        if open_.kind == "left":
            return "right", "\\right"
        if open_.kind == "sym":
            return "sym", "\\}"
        return "op", _OPENERS[open_.value]

    def expect_close(self, open_: _Tok, context: str) -> _Tok:
        kind, value = self.closer_for(open_)
        t = self.peek()
        if t.kind == kind and (kind == "right" or t.value == value):
            return self.next()
        raise self.unexpected(context)

    # -- groups -----------------------------------------------------------------------------------
    def parse_group(self, context: str) -> Any:
        open_ = self.next()
        with self.nested():
            value = self.parse_sum()
            if self.at("op", ","):
                raise self.error(f"unexpected ',' inside {context}")
            self.expect_close(open_, context if context.startswith("the ") else f"the {context}")
        return value

    def parse_braced(self, context: str) -> Any:
        if not self.at("op", "{"):
            raise self.error(f"{context} needs braces")
        return self.parse_group(context)

    def parse_bracket(self) -> Any:
        open_ = self.next()
        items = self.bracket_items(open_, "brackets")
        return self.row_vector(items, open_)

    def bracket_items(self, open_: _Tok, context: str) -> list[Any]:
        with self.nested():
            items = [self.parse_sum()]
            while self.at("op", ",") or self.at("sep"):
                self.next()
                items.append(self.parse_sum())
            self.expect_close(open_, context)
        return items

    def row_vector(self, items: list[Any], tok: _Tok) -> Any:
        if len(items) == 1:
            return items[0]
        return self.make_matrix([items], tok)

    def parse_bars(self, opener: str, closer: str, what: str) -> Any:
        open_ = self.next()
        with self.nested():
            self.bars.append((opener, self.depth))
            try:
                inner = self.parse_sum()
            finally:
                self.bars.pop()
            t = self.peek()
            if not (t.kind in ("op", "sym") and t.value == closer):
                raise self.unexpected(what)
            self.next()
        return self.wrap_bars(opener, inner, open_)

    def wrap_bars(self, delimiter: str, inner: Any, tok: _Tok) -> Any:
        if delimiter == "|":
            if _is_matrix(inner):
                raise self.error("|...| of a matrix is ambiguous (determinant or norm?)", tok)
            return sp.Abs(inner)
        order = None
        if self.at("op", "_"):
            order = self.parse_script(self.read_script(), "the norm's subscript")
        return Norm(inner) if order is None else Norm(inner, order)

    def parse_left(self) -> Any:
        open_ = self.next()
        delimiter = open_.value
        with self.nested():
            if delimiter == "[":
                items = [self.parse_sum()]
                while self.at("op", ",") or self.at("sep"):
                    self.next()
                    items.append(self.parse_sum())
            else:
                items = [self.parse_sum()]
                if self.at("op", ","):
                    raise self.error(f"unexpected ',' inside \\left{delimiter}")
            if not self.at("right"):
                raise self.unexpected(f"\\left{delimiter}...\\right")
            close = self.next()
        expected = _DELIMITER_PAIRS[delimiter]
        if delimiter == ".":
            if close.value == "|" and self.at("op", "_"):
                return self.evaluation_bar(items[0], bar_consumed=True)
            raise self.error("\\left. is only supported before \\right|_{...}", open_)
        if close.value != expected:
            raise self.error(f"\\left{delimiter} closed by \\right{close.value}", close)
        if delimiter in ("|", "\\|"):
            return self.wrap_bars(delimiter, items[0], open_)
        if delimiter == "[":
            return self.row_vector(items, open_)
        return items[0]

    def evaluation_bar(self, value: Any, bar_consumed: bool = False) -> Any:
        r"""``f|_{z=e^{sT}}``: substitute the printed value."""
        if not bar_consumed:
            self.next()  # '|'
        script = self.read_script()
        with self.bounded(script.start, script.stop, "an evaluation bar"), self.nested():
            variable = self.parse_sum()
            if not self.at("op", "="):
                raise self.unexpected("an evaluation bar (expected '=')")
            self.next()
            target = self.parse_sum()
        if not isinstance(variable, sp.Symbol):
            raise self.error("the evaluation bar needs a symbol before '='", script.op)
        return self.combine(lambda: sp.sympify(value).subs(variable, target), script.op, "an evaluation")

    # -- operators --------------------------------------------------------------------------------
    def parse_fraction(self) -> Any:
        cmd = self.next()
        num = self.fraction_argument(f"the numerator of {cmd.value}")
        den = self.fraction_argument(f"the denominator of {cmd.value}")
        if _is_matrix(den):
            raise self.error(f"{cmd.value} with a matrix denominator", cmd)
        return self.combine(lambda: num * sp.Pow(den, -1), cmd, cmd.value)

    def fraction_argument(self, context: str) -> Any:
        t = self.peek()
        if t.kind == "op" and t.value == "{":
            return self.parse_group(context)
        if t.kind == "number" and t.value.isdigit():
            if len(t.value) == 1:
                self.next()
            else:  # TeX reads one digit per argument: \frac12 is 1/2
                self.toks[self.i] = replace(t, value=t.value[1:], pos=t.pos + 1, space=False)
            return sp.Integer(t.value[0])
        if t.kind == "letter" or (t.kind == "cmd" and t.value in _GREEK):
            self.next()  # TeX takes one token: \frac ab is a/b
            return self.resolve(t, t.value, 0, None, None)
        raise self.error(f"{context} needs braces")

    def parse_sqrt(self) -> Any:
        cmd = self.next()
        degree = None
        if self.at("op", "["):
            open_ = self.next()
            with self.nested():
                degree = self.parse_sum()
                self.expect_close(open_, "the degree of \\sqrt")
        radicand = self.fraction_argument("\\sqrt")
        if _is_matrix(radicand):
            raise self.error("\\sqrt of a matrix", cmd)
        return sp.sqrt(radicand) if degree is None else self.combine(
            lambda: sp.root(radicand, degree), cmd, "a root"
        )

    def delimited_argument(self, what: str, delimiters: str) -> Any | None:
        """A parenthesised (``(``), braced (``{``) or bracketed (``[``) argument, if present."""
        t = self.peek()
        if t.kind == "op" and t.value == "(" and "(" in delimiters:
            return self.parse_group(f"the argument of {what}")
        if t.kind == "sym" and t.value == "\\{" and "{" in delimiters:
            return self.parse_group(f"the argument of {what}")
        if t.kind == "op" and t.value == "[" and "[" in delimiters:
            open_ = self.next()
            return self.row_vector(self.bracket_items(open_, f"the argument of {what}"), open_)
        if t.kind == "left" and t.value in ("(", "\\{", "[") and (t.value[-1] in delimiters):
            return self.parse_left()
        return None

    def parse_run(self, what: str, mode: str) -> Any:
        r"""The unparenthesised argument of ``\cos``, ``\min_i``, ``\lim``... (an implicit product).

        ``mode`` is ``'function'`` (stops at the next function: ``\sin x \cos x``), ``'operator'``
        (nested functions belong to it) or ``'summand'`` (a whole product, explicit ``\times``
        included, as the body of ``\sum`` and ``\int``).
        """
        if not self.starts_implicit():
            raise self.unexpected(f"the argument of {what}")
        if mode == "summand":
            return self.parse_product()
        start = self.peek()
        value = self.parse_factor(first=True)
        while self.starts_implicit() and not (mode == "function" and self.at_function_command()):
            t = self.peek()
            rhs = self.parse_factor(first=False)
            value = self.combine(lambda v=value, r=rhs: v * r, t, "a product")
        t = self.peek()
        if (t.kind in ("op", "cmd") and t.value in _MULTIPLY) or (t.kind == "op" and t.value == "/"):
            raise self.error(
                f"ambiguous: the unparenthesised argument of {what} (from position {start.pos}) "
                f"is followed by '{t.value}'; use parentheses"
            )
        return value

    def parse_elementary(self) -> Any:
        cmd = self.next()
        func = _ELEMENTARY[cmd.value]
        power = None
        if self.at("op", "^"):
            script = self.read_script()
            if script.canon == "-1":
                raise self.error(f"{cmd.value}^{{-1}} is ambiguous (inverse or reciprocal?)", script.op)
            power = self.parse_script(script, f"the power of {cmd.value}")
        argument = self.delimited_argument(cmd.value, "(")
        if argument is None:
            argument = self.parse_run(cmd.value, "function")
        if _is_matrix(argument):
            raise self.error(f"{cmd.value} of a matrix", cmd)
        value = self.combine(lambda: func(argument), cmd, cmd.value)
        return value if power is None else value**power

    def parse_part(self) -> Any:
        t = self.next()
        name = t.value if t.kind == "cmd" else t.arg.strip()
        func = _PARTS[name]
        argument = self.delimited_argument(name, "({[")
        if argument is None:
            argument = self.parse_run(name, "operator")
        if isinstance(argument, sp.MatrixBase):
            return argument.applyfunc(func)
        return self.combine(lambda: func(argument), t, name)

    def parse_det(self, width: int = 1) -> Any:
        first = self.peek()
        for _ in range(width):
            self.next()
        argument = self.delimited_argument("det", "(")
        if argument is None:
            argument = self.parse_run("det", "operator")
        if not _is_matrix(argument):
            raise self.error("det of a scalar expression (the table should give a matrix)", first)
        return self.combine(lambda: sp.Determinant(argument), first, "a determinant")

    def parse_diag(self, width: int = 1) -> Any:
        first = self.peek()
        for _ in range(width):
            self.next()
        t = self.peek()
        if not ((t.kind == "op" and t.value in "([") or (t.kind == "left" and t.value in "([")):
            raise self.error("diag needs a parenthesised or bracketed list", t)
        if t.kind == "left":
            with self.nested():
                self.next()
                items = [self.parse_sum()]
                while self.at("op", ","):
                    self.next()
                    items.append(self.parse_sum())
                if not self.at("right"):
                    raise self.unexpected("diag")
                self.next()
        else:
            items = self.bracket_items(self.next(), "diag")
        if any(isinstance(x, Elision) for x in items):
            raise self.error("diag with an ellipsis cannot be built", first)
        if all(_is_matrix(x) for x in items):
            return self.combine(lambda: sp.BlockDiagMatrix(*items), first, "a block diagonal")
        if any(_is_matrix(x) for x in items):
            raise self.error("diag mixes matrices and scalars", first)
        return sp.ImmutableMatrix(sp.diag(*items))

    def parse_binding(self, script: _Script, what: str) -> tuple[dict[str, sp.Symbol], list[Any]]:
        """``i``, ``i,j \\neq i``: the bound indices (printed name -> symbol) and conditions."""
        indices: dict[str, sp.Symbol] = {}
        conditions: list[Any] = []
        with self.bounded(script.start, script.stop, f"the subscript of {what}"), self.indexing():
            while True:
                t = self.peek()
                if t.kind not in ("letter", "cmd") or (t.kind == "cmd" and t.value not in _GREEK):
                    raise self.unexpected(f"the subscript of {what}")
                self.next()
                symbol = index_symbol(t.value)
                indices[t.value] = symbol
                left: Any = symbol
                with self.scope(indices):
                    while _is_relation(self.peek()):
                        op_tok = self.peek()
                        op = self.relation_op()
                        right = self.parse_sum()
                        conditions.append(
                            self.combine(lambda l=left, o=op, r=right: _REL_CLASSES[o](l, r), op_tok, "a condition")
                        )
                        left = right
                if not self.at("op", ","):
                    break
                self.next()
        return indices, conditions

    def parse_extremum(self) -> Any:
        cmd = self.next()
        kind = IndexedMin if cmd.value == "\\min" else IndexedMax
        if self.at("op", "_"):
            script = self.read_script()
            indices, conditions = self.parse_binding(script, cmd.value)
            with self.scope(indices):
                body = self.delimited_argument(cmd.value, "{")
                if body is None:
                    body = self.parse_run(f"{cmd.value}_{{{script.canon}}}", "operator")
            return kind(body, indices.values(), sp.And(*conditions))
        if self.at_application():
            args = self.call_arguments(cmd.value, cmd)
            if any(_is_matrix(a) for a in args):
                raise self.error(f"{cmd.value} of matrices", cmd)
            return (sp.Min if kind is IndexedMin else sp.Max)(*args)
        raise self.error(f"{cmd.value} needs a subscript or an argument list", cmd)

    def summation_limits(self, cmd: _Tok) -> tuple[_Script, _Script]:
        lower = upper = None
        while self.at("op", "_") or self.at("op", "^"):
            which = self.peek().value
            script = self.read_script()
            if (which == "_" and lower) or (which == "^" and upper):
                raise self.error(f"double '{which}' on {cmd.value}", script.op)
            lower, upper = (script, upper) if which == "_" else (lower, script)
        if lower is None or upper is None:
            raise self.error(f"{cmd.value} needs both limits (_{{k=1}}^{{m}})", cmd)
        return lower, upper

    def parse_summation(self) -> Any:
        cmd = self.next()
        lower, upper = self.summation_limits(cmd)
        with self.bounded(lower.start, lower.stop, "the lower limit of \\sum"), self.indexing():
            t = self.next()
            if t.kind not in ("letter", "cmd") or (t.kind == "cmd" and t.value not in _GREEK):
                raise self.error("\\sum needs a summation variable", t)
            var = index_symbol(t.value)
            if not self.at("op", "="):
                raise self.unexpected("the lower limit of \\sum (expected '=')")
            self.next()
            start = self.parse_sum()
            conditions = []
            with self.scope({t.value: var}):
                while self.at("op", ","):
                    self.next()
                    left = self.parse_sum()
                    while _is_relation(self.peek()):
                        op_tok = self.peek()
                        op = self.relation_op()
                        right = self.parse_sum()
                        conditions.append(
                            self.combine(lambda l=left, o=op, r=right: _REL_CLASSES[o](l, r), op_tok, "a condition")
                        )
                        left = right
        with self.indexing():
            stop = self.parse_script(upper, "the upper limit of \\sum")
        with self.scope({t.value: var}):
            body = self.parse_run("\\sum", "summand")
        if conditions:
            body = sp.Piecewise((body, sp.And(*conditions)), (0, True))
        return self.combine(lambda: sp.Sum(body, (var, start, stop)), cmd, "a sum")

    def parse_limit(self) -> Any:
        cmd = self.next()
        if not self.at("op", "_"):
            raise self.error("\\lim needs a subscript", cmd)
        script = self.read_script()
        with self.bounded(script.start, script.stop, "the subscript of \\lim"), self.nested():
            variable = self.parse_sum()
            t = self.peek()
            if not (t.kind == "cmd" and t.value in ("\\to", "\\rightarrow", "\\longrightarrow")):
                raise self.unexpected("the subscript of \\lim (expected \\to)")
            self.next()
            target = self.parse_sum()
        body = self.parse_run("\\lim", "operator")
        return PrintedLimit(body, variable, target)

    def parse_integral(self) -> Any:
        cmd = self.next()
        lower = upper = None
        while self.at("op", "_") or self.at("op", "^"):
            which = self.peek().value
            script = self.read_script()
            value = self.parse_script(script, "a limit of \\int")
            lower, upper = (value, upper) if which == "_" else (lower, value)
        name = self.find_differential()
        if name is None:
            raise self.error("the integrand has no d<variable>", cmd)
        existing = self.table.symbols.get(name)
        var = existing if isinstance(existing, sp.Symbol) else sp.Symbol(_sympy_name(name), real=True)
        self.differentials.append(name)
        try:
            with self.scope({name: var}):
                body = self.parse_run("\\int", "summand")
            if not self.at_differential():
                raise self.unexpected(f"the integrand (expected d{name})")
        finally:
            self.differentials.pop()
        self.next()
        self.next()
        if (lower is None) != (upper is None):
            raise self.error("\\int needs both limits or none", cmd)
        limits = (var,) if lower is None else (var, lower, upper)
        return self.combine(lambda: sp.Integral(body, limits), cmd, "an integral")

    def find_differential(self) -> str | None:
        """Look ahead (without consuming) for the ``d<var>`` closing the integrand."""
        k = self.i
        while k < self.limit:
            t = self.toks[k]
            if k in self.match and self.match[k] > k:
                k = self.match[k] + 1
                continue
            if t.kind == "op" and t.value in "_^" and k + 1 < self.limit:
                k += 2 if k + 1 not in self.match else self.match[k + 1] - k + 1
                continue
            if _is_relation(t) or t.kind in ("sep", "newline", "right", "end") or (
                t.kind == "op" and t.value in "+-,&)]}"
            ):
                return None
            if t.kind == "letter" and t.value == "d" and "d" not in self.table.symbols and k + 1 < self.limit:
                nxt = self.toks[k + 1]
                if nxt.kind == "letter" or (nxt.kind == "cmd" and nxt.value in _GREEK):
                    return nxt.value
            k += 1
        return None

    # -- environments -----------------------------------------------------------------------------
    def parse_environment(self) -> Any:
        begin = self.peek()
        if begin.value in _MATRIX_ENVS:
            matrix = self.parse_matrix()
            if begin.value == "vmatrix":
                return self.combine(lambda: sp.Determinant(matrix), begin, "a determinant")
            return matrix
        if begin.value == "cases":
            return self.parse_cases()
        if begin.value in _ALIGN_ENVS:
            raise self.error(f"\\begin{{{begin.value}}} must enclose the whole display")
        raise self.error(f"unsupported environment {begin.value}")

    def parse_matrix(self) -> Any:
        begin = self.next()
        rows: list[list[Any]] = [[]]
        row_starts = [self.peek()]
        with self.nested():
            while not self.at("end"):
                if self.at("op", "&") or self.at("newline"):
                    raise self.error("empty matrix entry")
                rows[-1].append(self.parse_sum())
                if self.at("op", "&"):
                    self.next()
                    if self.at("end"):
                        raise self.error("empty matrix entry")
                elif self.at("newline"):
                    self.next()
                    rows.append([])
                    row_starts.append(self.peek())
                elif not self.at("end"):
                    raise self.unexpected("a matrix entry")
            self.next()
        if not rows[-1]:
            rows.pop()
        if not rows:
            raise self.error("empty matrix", begin)
        width = len(rows[0])
        for row, start in zip(rows, row_starts):
            if len(row) != width:
                raise self.error(f"matrix row has {len(row)} entries, the first row has {width}", start)
        return self.make_matrix(rows, begin)

    def make_matrix(self, rows: list[list[Any]], tok: _Tok) -> Any:
        blocks = [[_is_matrix(x) for x in row] for row in rows]
        if any(any(r) for r in blocks):
            if not all(all(r) for r in blocks):
                raise self.error("a matrix mixes matrix and scalar entries", tok)
            return self.combine(lambda: sp.BlockMatrix(rows), tok, "a block matrix")
        return sp.ImmutableMatrix(rows)

    def parse_cases(self) -> Any:
        begin = self.next()
        pieces: list[tuple[Any, Any]] = []
        with self.nested():
            while not self.at("end"):
                value = self.parse_sum()
                if not self.at("op", "&"):
                    raise self.unexpected("a cases row (expected '&')")
                self.next()
                if self.at("op", ","):
                    self.next()
                t = self.peek()
                word = " ".join(t.arg.split()) if t.kind == "text" else ""
                if word == "otherwise":
                    self.next()
                    condition: Any = sp.true
                elif word in ("if", "for", "when"):
                    self.next()
                    chain = self.parse_chain()
                    if not isinstance(chain, Relation):
                        raise self.error("a cases condition must be a relation", t)
                    condition = chain.as_sympy()
                else:
                    raise self.unexpected("a cases row (expected \\text{if} or \\text{otherwise})")
                pieces.append((value, condition))
                if self.at("newline"):
                    self.next()
                elif not self.at("end"):
                    raise self.unexpected("a cases row")
            self.next()
        if not pieces:
            raise self.error("empty cases", begin)
        return self.combine(lambda: sp.Piecewise(*pieces), begin, "a Piecewise")


@dataclass(frozen=True, slots=True)
class _Condition:
    """An index condition clause (``j \\neq i``) before it is attached to its statement."""

    relation: Relation

    @property
    def span(self) -> Span:
        return self.relation.span


# ----------------------------------------------------------------------------------------------
# Expansion of indexed operators for a given number of users
# ----------------------------------------------------------------------------------------------


def expand_indexed(
    expr: Any, m: int, table: SymbolTable, *, count: sp.Symbol | None = None, empty: Any = None
) -> Any:
    r"""Expand indexed extrema, sums and family members for ``m`` users.

    Parameters
    ----------
    expr : sympy.Basic
        A parsed expression holding :class:`IndexedMin`/:class:`IndexedMax`, ``Sum`` s and
        indexed family members (``b[i]``).
    m : int
        Number of users; extrema range over ``1..m`` in every index.
    table : SymbolTable
        Supplies the concrete members (``K_{12}``...) of the families.
    count : sympy.Symbol, optional
        The symbol printed for the number of users (the papers' ``m``); replaced by ``m``.
    empty : sympy.Basic, optional
        Value of an extremum over no index tuple (``\max_{i,j \neq i}`` for one user); by
        default such an extremum raises ``ValueError``.

    Returns
    -------
    sympy.Basic
        The expression over concrete symbols (indices left free stay symbolic).

    Examples
    --------
    >>> t = SymbolTable(families=[IndexedFamily('K_{ij}', symmetric=True)])
    >>> i, j = index_symbol('i'), index_symbol('j')
    >>> K = sp.IndexedBase('K_{ij}')
    >>> expand_indexed(IndexedMax(K[i, j], (i, j), sp.Ne(j, i)), 3, t)
    Max(K_12, K_13, K_23)
    """
    if m < 1:
        raise ValueError(f"the number of users must be positive, got {m}")
    expr = sp.sympify(expr)
    if count is not None:
        expr = expr.xreplace({count: sp.Integer(m)})

    def concrete(e: Any) -> Any:
        """Replace family members with integer indices by the table's symbols."""
        members = {
            x: table.concrete(str(x.base.label), x.indices)
            for x in e.atoms(sp.Indexed)
            if str(x.base.label) in table.families and all(v.is_Integer for v in x.indices)
        }
        e = e.xreplace(members) if members else e
        return e.replace(
            lambda x: isinstance(x, IndexedCall) and all(v.is_Integer for v in x.indices),
            lambda x: table.concrete(x.pattern, x.indices)(*x.arguments),
        )

    def extremum(e: IndexedExtremum) -> Any:
        bodies = []
        for combo in cartesian_product(range(1, m + 1), repeat=len(e.indices)):
            mapping = dict(zip(e.indices, map(sp.Integer, combo)))
            verdict = e.condition.xreplace(mapping)
            if verdict not in (sp.true, sp.false):
                raise ValueError(f"cannot decide the index condition {e.condition} at {combo}")
            if verdict is sp.true:
                bodies.append(concrete(finite_sums(e.body.xreplace(mapping))))
        if not bodies:
            if empty is None:
                raise ValueError(f"{type(e).__name__} over no index tuple for m = {m}")
            return empty
        # Why: members are made concrete first so Min/Max (costly to build) is built only once.
        return e._combine(*bodies)

    def finite_sums(e: Any) -> Any:
        return e.replace(
            lambda x: isinstance(x, sp.Sum) and all(lim[1].is_Integer and lim[2].is_Integer for lim in x.limits),
            lambda x: x.doit(deep=False),
        )

    expr = expr.replace(lambda e: isinstance(e, IndexedExtremum), extremum)
    return concrete(finite_sums(expr))
