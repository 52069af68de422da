"""What a printed display reads as: an expression, a relation chain, qualified or several lines,
with the unevaluated objects of the dialect (elisions, indexed extrema and calls, printed
limits, norms) and the expansion of indexed families for m users."""

from __future__ import annotations

from collections.abc import Callable, Iterable
from dataclasses import dataclass, replace
from itertools import product as cartesian_product
from typing import Any

import sympy as sp
from sympy.core.symbol import Str
from hapticproof.audit.reader.lexer import ELLIPSES
from hapticproof.audit.reader.names import SymbolTable


__all__ = ["Span", "Statement", "Expression", "Relation", "IndexRange", "Qualified", "Lines", "Elision", "IndexedExtremum", "IndexedMin", "IndexedMax", "IndexedCall", "PrintedLimit", "Norm", "expand_indexed", "has_elision"]


class Elision(sp.Symbol):
    r"""A printed ellipsis (``\dots``, ``\cdots``, ``\vdots``, ``\ddots``) kept as an atom.

    A matrix or list printed with ellipses cannot be made concrete without guessing its missing
    entries, so the parser returns it with these atoms in place; :func:`has_elision` tells.

    >>> Elision('vdots'), Elision('vdots').kind
    (\vdots, 'vdots')
    """

    def __new__(cls, kind: str = "dots") -> Elision:
        kind = kind.lstrip("\\")
        if "\\" + kind not in ELLIPSES:
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
        return unbound_indices(self.body.free_symbols | self.condition.free_symbols, set(self.indices))

    def _eval_is_real(self) -> bool | None:
        return self.body.is_real


class IndexedMin(IndexedExtremum):
    r"""``\min_{i} \{...\}`` over the users ``1..m`` (see :class:`IndexedExtremum`).

    >>> from hapticproof.audit.reader.names import index_symbol
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


def unbound_indices(symbols: set[sp.Basic], bound: set[sp.Basic]) -> set[sp.Basic]:
    """Drop bound indices and indexed objects that mention them from ``symbols``."""
    return {
        s
        for s in symbols
        if s not in bound and not (isinstance(s, sp.Indexed) and mentions(s.indices, bound))
    }


def mentions(exprs: Iterable[Any], bound: set[sp.Basic]) -> bool:
    return any(sp.sympify(e).free_symbols & bound for e in exprs)


def has_elision(obj: Any) -> bool:
    r"""Whether an expression, matrix or :class:`Statement` holds an :class:`Elision`.

    >>> has_elision(sp.ImmutableMatrix([[1, Elision('cdots')]]))
    True
    """
    if isinstance(obj, Statement):
        return any(has_elision(e) for e in obj.expressions())
    return bool(sp.sympify(obj).atoms(Elision))


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


RELATION_CLASSES: dict[str, Any] = {
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
        if bad := [op for op in self.ops if op not in RELATION_CLASSES]:
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
        links = [RELATION_CLASSES[op](lhs, rhs, evaluate=False) for lhs, op, rhs in self.pairs()]
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

    >>> from hapticproof.audit.reader.printed import parse_printed
    >>> from hapticproof.audit.reader.names import IndexedFamily
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

    >>> from hapticproof.audit.reader.printed import parse_printed
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
    >>> from hapticproof.audit.reader.names import IndexedFamily
    >>> from hapticproof.audit.reader.names import index_symbol
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


def is_matrix(value: Any) -> bool:
    return isinstance(value, (sp.MatrixBase, sp.MatrixExpr))
