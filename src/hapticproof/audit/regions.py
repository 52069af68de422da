r"""Assumptions as people state them: inequalities, intervals and relations between parameters.

A paper file restricts its parameters in two places: ``[symbols]`` (``a = "0 <= a < 1"`` for
a filter pole, ``b_m = "b_m >= b_s"``, ``B = 'B \geq 0'``), which holds for every claim, and
an equation's ``assumption`` (``"B = 0"``, ``'B \leq \frac{KT}{2}'``), the paper's vague
assumption made precise. Both are read here into a :class:`Region`: one
:class:`Restriction` per parameter, in LaTeX or in the expression syntax.

How a region restricts the exact decisions
    A region is turned into a change of variables onto sign-assumed symbols
    (:meth:`Region.parametrize`): ``x >= L`` is ``x = L + u`` with ``u >= 0``, ``x < U`` is
    ``x = U - u`` with ``u > 0``, and ``L <= x < U`` is ``x = L + (U - L) u/(1 + u)`` with
    ``u >= 0`` (a bijection of ``[0, oo)`` onto ``[L, U)``). The scene's parameter becomes that
    expression of a new parameter ``u`` that carries the sign, so every exact decision of the
    toolkit -- pole locations, residues, worst cases over frequency, bound comparisons, the
    instances drawn -- ranges over the region and nothing else, with the same proofs.
    Witnesses are mapped back to the paper's names (:meth:`Parametrization.witness`) and so are
    derived conditions (:meth:`Parametrization.back`). A closed end that the change of variables
    does not reach (``U`` in ``L <= x <= U``) is a boundary of the region, and conditions are
    compared up to their boundaries, as ``>`` and ``>=`` are.

>>> import sympy as sp
>>> a = sp.Symbol("a", real=True)
>>> region = read_region("0 <= a < 1", {"a": a})
>>> region.latex(), region.restrictions[0].sign_word()
('0 \\leq a < 1', 'nonnegative')
>>> chart = region.parametrize(taken={"a"})
>>> chart.params
{'a': u_a/(u_a + 1), 'u_a': 'nonnegative'}
>>> chart.witness({"u_a": 3, "b": 2})
{'b': 2, 'a': 3/4}
"""

from __future__ import annotations

import re
from collections.abc import Iterable, Mapping
from dataclasses import dataclass, field, replace
from typing import Any

import sympy as sp

from hapticproof.core.errors import InputFormatError, LatexParseError

__all__ = ["RegionError", "Restriction", "Region", "Parametrization", "read_region", "parse_relations", "with_symbols"]


class RegionError(InputFormatError):
    """An assumption that cannot be read as a region of the parameters (one line: why)."""


_SIGN_WORDS = ("positive", "nonnegative", "negative", "nonpositive")


@dataclass(frozen=True, slots=True)
class Restriction:
    """What one parameter may be: ``lower (<|<=) symbol (<|<=) upper``, or ``symbol = value``.

    Bounds are expressions of the other parameters (or numbers); ``text`` is the assumption as
    written (LaTeX or the expression syntax).
    """

    symbol: sp.Symbol
    lower: Any = None
    lower_strict: bool = False
    upper: Any = None
    upper_strict: bool = False
    value: Any = None
    text: str = ""

    @property
    def name(self) -> str:
        return self.symbol.name

    def is_equality(self) -> bool:
        return self.value is not None

    def latex(self) -> str:
        """The restriction in LaTeX (``0 \\leq a < 1``, ``B = 0``)."""
        x = sp.latex(self.symbol)
        if self.value is not None:
            return f"{x} = {sp.latex(self.value)}"
        leq, geq = "\\leq", "\\geq"
        if self.lower is not None and self.upper is None:
            return f"{x} {'>' if self.lower_strict else geq} {sp.latex(self.lower)}"
        parts = []
        if self.lower is not None:
            parts.append(f"{sp.latex(self.lower)} {'<' if self.lower_strict else leq} ")
        parts.append(x)
        if self.upper is not None:
            parts.append(f" {'<' if self.upper_strict else leq} {sp.latex(self.upper)}")
        return "".join(parts)

    def text_form(self) -> str:
        """The restriction in plain text (``0 <= a < 1``)."""
        if self.value is not None:
            return f"{self.name} = {sp.sstr(self.value)}"
        if self.lower is not None and self.upper is None:
            return f"{self.name} {'>' if self.lower_strict else '>='} {sp.sstr(self.lower)}"
        out = ""
        if self.lower is not None:
            out += f"{sp.sstr(self.lower)} {'<' if self.lower_strict else '<='} "
        out += self.name
        if self.upper is not None:
            out += f" {'<' if self.upper_strict else '<='} {sp.sstr(self.upper)}"
        return out

    def sign_word(self) -> str | None:
        """The sign the restriction implies on its own (``0 <= a < 1``: ``nonnegative``; a lower
        bound that is a positive expression of positive parameters: ``positive``), or None."""
        if self.value is not None:
            value = sp.sympify(self.value)
            for word, attr in (("positive", "is_positive"), ("negative", "is_negative"),
                               ("nonnegative", "is_nonnegative"), ("nonpositive", "is_nonpositive")):
                if getattr(value, attr):
                    return word
            return None
        if self.lower is not None:
            low = sp.sympify(self.lower)
            if low.is_positive or (self.lower_strict and low.is_nonnegative):
                return "positive"
            if low.is_nonnegative:
                return "nonnegative"
        if self.upper is not None:
            high = sp.sympify(self.upper)
            if high.is_negative or (self.upper_strict and high.is_nonpositive):
                return "negative"
            if high.is_nonpositive:
                return "nonpositive"
        return None

    def only_sign(self) -> bool:
        """Whether the restriction says no more than its symbol's sign assumption (``B >= 0`` of a
        non-negative ``B``); the same words about a real ``B`` restrict it."""
        if self.value is not None:
            return False
        ends = [e for e in (self.lower, self.upper) if e is not None]
        if len(ends) != 1 or sp.sympify(ends[0]) != 0:
            return False
        if self.lower is not None:
            implied = self.symbol.is_positive if self.lower_strict else self.symbol.is_nonnegative
        else:
            implied = self.symbol.is_negative if self.upper_strict else self.symbol.is_nonpositive
        return implied is True

    def contains(self, value: Any) -> bool | None:
        """Whether a number satisfies the restriction (None: its bounds are not numbers)."""
        value = sp.sympify(value)
        checks = []
        if self.value is not None:
            checks.append(sp.Eq(value, self.value))
        if self.lower is not None:
            checks.append((sp.Gt if self.lower_strict else sp.Ge)(value, self.lower))
        if self.upper is not None:
            checks.append((sp.Lt if self.upper_strict else sp.Le)(value, self.upper))
        out = True
        for check in checks:
            if check not in (sp.true, sp.false):
                return None
            out = out and bool(check)
        return out

    def intersect(self, other: Restriction) -> Restriction:
        """Both restrictions on the same parameter at once (numbers compared exactly)."""
        if other.symbol.name != self.symbol.name:
            raise ValueError("restrictions of different parameters")
        if self.value is not None or other.value is not None:
            if self.value is not None and other.value is not None:
                if sp.simplify(sp.sympify(self.value) - other.value) != 0:
                    raise RegionError(f"{self.text_form()} and {other.text_form()} contradict each other")
                return self
            eq, ineq = (self, other) if self.value is not None else (other, self)
            if ineq.contains(eq.value) is False:
                raise RegionError(f"{eq.text_form()} lies outside {ineq.text_form()}")
            return eq
        lower, lower_strict = _tighter(self.lower, self.lower_strict, other.lower, other.lower_strict, 1,
                                       self.text_form(), other.text_form())
        upper, upper_strict = _tighter(self.upper, self.upper_strict, other.upper, other.upper_strict, -1,
                                       self.text_form(), other.text_form())
        text = " and ".join(t for t in (self.text, other.text) if t)
        return Restriction(self.symbol, lower, lower_strict, upper, upper_strict, None, text).checked()

    def checked(self) -> Restriction:
        """The restriction, or :class:`RegionError` when no value satisfies it."""
        if self.lower is not None and self.upper is not None:
            gap = sp.sympify(self.upper) - sp.sympify(self.lower)
            if gap.is_negative or (gap.is_zero and (self.lower_strict or self.upper_strict)):
                raise RegionError(f"{self.text_form()}: no value of {self.name} satisfies it")
        return self


def _tighter(a: Any, a_strict: bool, b: Any, b_strict: bool, direction: int, ta: str, tb: str) -> tuple[Any, bool]:
    """The tighter of two lower (``direction = 1``) or upper (``-1``) bounds."""
    if a is None:
        return b, b_strict
    if b is None:
        return a, a_strict
    gap = (sp.sympify(a) - sp.sympify(b)) * direction
    if gap.is_zero:
        return a, a_strict or b_strict
    if gap.is_positive:
        return a, a_strict
    if gap.is_negative:
        return b, b_strict
    raise RegionError(f"{ta} and {tb}: the two bounds cannot be compared; state one")


@dataclass(frozen=True)
class Region:
    """A conjunction of restrictions, at most one per parameter (merged on construction)."""

    restrictions: tuple[Restriction, ...] = ()

    def __post_init__(self) -> None:
        merged: dict[str, Restriction] = {}
        for r in self.restrictions:
            merged[r.name] = merged[r.name].intersect(r) if r.name in merged else r.checked()
        object.__setattr__(self, "restrictions", tuple(merged.values()))

    def __bool__(self) -> bool:
        return bool(self.restrictions)

    def __and__(self, other: Region) -> Region:
        return Region(self.restrictions + other.restrictions)

    def get(self, name: str) -> Restriction | None:
        return next((r for r in self.restrictions if r.name == name), None)

    def names(self) -> set[str]:
        return {r.name for r in self.restrictions}

    def equalities(self) -> dict[str, Any]:
        return {r.name: r.value for r in self.restrictions if r.value is not None}

    def inequalities(self) -> Region:
        return Region(tuple(r for r in self.restrictions if r.value is None and not r.only_sign()))

    def latex(self) -> str:
        return ", ".join(r.latex() for r in self.restrictions)

    def text(self) -> str:
        return ", ".join(r.text_form() for r in self.restrictions)

    def restricted_to(self, names: Iterable[str]) -> Region:
        keep = set(names)
        return Region(tuple(r for r in self.restrictions if r.name in keep))

    def parametrize(self, taken: Iterable[str] = ()) -> Parametrization:
        """The change of variables onto sign-assumed parameters (see the module docstring).

        ``taken`` holds the names in use (a new parameter never takes one). Equalities are
        substitutions; a restriction that says no more than a sign is left to the symbol's
        assumption.

        >>> b_m, b_s = sp.symbols("b_m b_s", positive=True)
        >>> chart = read_region("b_m >= b_s", {"b_m": b_m, "b_s": b_s}).parametrize({"b_m", "b_s"})
        >>> chart.params, chart.back(sp.Symbol("u_b_m", nonnegative=True))
        ({'b_m': b_s + u_b_m, 'u_b_m': 'nonnegative'}, b_m - b_s)
        """
        used = set(taken) | self.names()
        params: dict[str, Any] = {}
        forward: dict[str, sp.Expr] = {}
        inverse: dict[sp.Symbol, sp.Expr] = {}
        notes: list[str] = []
        for r in self.restrictions:
            if r.value is not None:
                params[r.name] = sp.sympify(r.value)
                forward[r.name] = sp.sympify(r.value)
                continue
            if r.only_sign():
                continue
            fresh = _fresh_name(r.name, used)
            used.add(fresh)
            strict = r.lower_strict if r.lower is not None else r.upper_strict
            word = "positive" if strict else "nonnegative"
            u = sp.Symbol(fresh, **{word: True})
            x = r.symbol
            if r.lower is not None and r.upper is not None:
                low, high = sp.sympify(r.lower), sp.sympify(r.upper)
                if not (sp.factor(high - low).is_positive):
                    raise RegionError(f"{r.text_form()}: the interval's ends are not ordered by the other assumptions "
                                      f"({sp.sstr(high)} > {sp.sstr(low)} is not proved)")
                value = low + (high - low) * u / (1 + u)
                back = (x - low) / (high - x)
            elif r.lower is not None:
                value = sp.sympify(r.lower) + u
                back = x - sp.sympify(r.lower)
            else:
                value = sp.sympify(r.upper) - u
                back = sp.sympify(r.upper) - x
            value = sp.factor(value) if r.lower is not None and r.upper is not None else value
            params[r.name] = value
            params[fresh] = word
            forward[r.name] = value
            inverse[u] = back
            notes.append(f"{fresh} = {sp.sstr(_fewer_minus(sp.factor(back)))} {'>' if strict else '>='} 0 parametrises {r.text_form()}")
        return Parametrization(self, params, forward, inverse, tuple(notes))


def _fresh_name(name: str, used: set[str]) -> str:
    base = "u_" + name
    candidate, k = base, 2
    while candidate in used:
        candidate, k = f"{base}{k}", k + 1
    return candidate


@dataclass(frozen=True)
class Parametrization:
    """A region as a change of variables: scene parameters (``params``, for
    :meth:`~hapticproof.systems.scene.Scene.with_params`), each restricted name's expression
    in the new parameters (``forward``) and each new parameter's expression in the paper's names
    (``inverse``); ``notes`` say what each new parameter is."""

    region: Region
    params: dict[str, Any]
    forward: dict[str, sp.Expr]
    inverse: dict[sp.Symbol, sp.Expr]
    notes: tuple[str, ...] = ()
    _resolved: dict = field(default_factory=dict, repr=False, compare=False)

    @property
    def fresh(self) -> set[str]:
        """The names of the new parameters."""
        return {u.name for u in self.inverse}

    def resolved(self) -> dict[str, sp.Expr]:
        """Each restricted name in the new parameters only (bounds that name restricted
        parameters substituted through)."""
        if self._resolved:
            return self._resolved
        out = dict(self.forward)
        by_name = {name: value for name, value in out.items()}
        for _ in range(len(out) + 1):
            changed = False
            for name, value in list(out.items()):
                subs = {s: by_name[s.name] for s in sp.sympify(value).free_symbols if s.name in by_name and s.name != name}
                if subs:
                    new = sp.sympify(value).xreplace(subs)
                    if new != value:
                        out[name] = new
                        by_name[name] = new
                        changed = True
            if not changed:
                break
        else:
            raise RegionError("the assumptions bound parameters by each other in a cycle")
        self._resolved.update(out)
        return out

    def witness(self, point: Mapping[Any, Any]) -> dict[str, Any]:
        """A point of the new parameters as a point of the paper's names (new ones dropped)."""
        values = {(k if isinstance(k, str) else k.name): v for k, v in point.items()}
        fresh = self.fresh
        out = {k: v for k, v in values.items() if k not in fresh}
        if not fresh & set(values):
            return out
        for name, expr in self.resolved().items():
            if name in self.region.equalities():
                continue
            expr = sp.sympify(expr)
            subs = {s: values[s.name] for s in expr.free_symbols if s.name in values}
            value = expr.xreplace(subs)
            if not value.free_symbols:
                out[name] = sp.nsimplify(value) if value.is_Float else sp.cancel(value)
        return out

    def back(self, expr: Any) -> Any:
        """An expression (or condition, matrix) of the new parameters in the paper's names."""
        if expr is None or not self.inverse:
            return expr
        value = sp.sympify(expr)
        by_name = {u.name: inv for u, inv in self.inverse.items()}
        subs = {s: by_name[s.name] for s in getattr(value, "free_symbols", ()) if s.name in by_name}
        if not subs:
            return expr
        value = value.xreplace(subs)
        return _tidy(value)


def _tidy(value: Any) -> Any:
    if isinstance(value, sp.MatrixBase):
        return value.applyfunc(_tidy)
    if isinstance(value, sp.core.relational.Relational):
        return value.func(_tidy(value.lhs), _tidy(value.rhs), evaluate=False)
    if isinstance(value, (sp.And, sp.Or)):
        return value.func(*[_tidy(a) for a in value.args])
    if isinstance(value, sp.Expr) and value.free_symbols:
        try:
            factored = sp.factor(sp.cancel(value))
            collected = sp.collect(sp.expand(factored), sorted(factored.free_symbols, key=str), func=sp.factor)
        except (sp.PolynomialError, TypeError, ValueError):
            return value
        return sp.Add(*[_fewer_minus(t) for t in sp.Add.make_args(collected)])
    return value


def _fewer_minus(term: sp.Expr) -> sp.Expr:
    """``-B(a - 1)/(a + 1)`` as ``B(1 - a)/(a + 1)``: a leading minus absorbed by a factor
    that gets no more minus signs by it."""
    if not term.is_Mul:
        return term
    coeff, factors = term.as_coeff_mul()
    if coeff >= 0:
        return term

    def minus(expr: sp.Expr) -> int:
        return sum(1 for t in sp.Add.make_args(expr) if t.could_extract_minus_sign())

    best = None
    for k, f in enumerate(factors):
        base, power = f.as_base_exp()
        if base.is_Add and power.is_Integer and power % 2 == 1:
            cost = minus(-base) - minus(base)
            if cost <= 0 and (best is None or cost < best[0]):
                best = (cost, k, base, power)
    if best is None:
        return term
    _cost, k, base, power = best
    flipped = -base if power == 1 else sp.Pow(-base, power, evaluate=False)
    rest = [-coeff] if coeff != -1 else []
    return sp.Mul(*rest, *factors[:k], flipped, *factors[k + 1:], evaluate=False)


# ---------------------------------------------------------------------------------------------
# reading
# ---------------------------------------------------------------------------------------------

_INTERVAL = re.compile(r"^\s*(?P<x>.+?)\s*\\in\s*(?P<open>[\[(]|\\left\s*[\[(])\s*(?P<lo>[^,]+?)\s*,\s*(?P<hi>[^,]+?)\s*"
                       r"(?P<close>[\])]|\\right\s*[\])])\s*$")


def _intervals(text: str) -> str:
    r"""``x \in [L, U)`` as ``L <= x < U`` (the LaTeX reader has no interval notation)."""
    match = _INTERVAL.match(text)
    if match is None:
        return text
    low_op = "<" if match.group("open").rstrip().endswith("(") else "<="
    high_op = "<" if match.group("close").rstrip().endswith(")") else "<="
    parts = []
    if match.group("lo").strip() not in ("-\\infty", "-infty", "-oo"):
        parts.append(f"{match.group('lo')} {low_op} ")
    parts.append(match.group("x"))
    if match.group("hi").strip() not in ("\\infty", "infty", "oo", "+\\infty"):
        parts.append(f" {high_op} {match.group('hi')}")
    return "".join(parts)


def parse_relations(text: str, parse: Any) -> list[tuple[tuple[str, ...], tuple[Any, ...]]]:
    """The relation chains of an assumption (``parse`` reads LaTeX into a statement), each as
    ``(ops, terms)``; comma-separated parts are read one by one."""
    out = []
    pieces = [p for p in re.split(r",(?![^{(\[]*[})\]])|\\quad|\\text\{\s*and\s*\}|\band\b", text) if p.strip()]
    for piece in pieces:
        try:
            statement = parse(_intervals(piece.strip()))
        except LatexParseError as err:
            raise RegionError(f"{piece.strip()!r} does not read ({err.reason})") from None
        relations = statement.relations()
        if not relations:
            raise RegionError(f"{piece.strip()!r} is not a relation (expected e.g. 'B = 0', 'B \\geq 0', '0 <= a < 1')")
        for relation in relations:
            out.append((tuple(relation.ops), tuple(sp.sympify(t) for t in relation.terms)))
    if not out:
        raise RegionError("no relation given (expected e.g. 'B = 0', 'B \\geq 0', '0 <= a < 1')")
    return out


_FLIP = {"<": ">", "<=": ">=", ">": "<", ">=": "<=", "=": "="}


def _solved(ops: tuple[str, ...], terms: tuple[Any, ...], key: str | None) -> tuple[tuple[str, ...], tuple[Any, ...]]:
    """A linear relation between parameters (``g_0 + g_1 \\ge 0``) solved for ``key`` (else for
    its first symbol with a numeric coefficient): ``g_0 >= -g_1``; other relations unchanged."""
    if len(terms) != 2 or ops[0] == "=" and key is None:
        return ops, terms
    left, right = (sp.sympify(t) for t in terms)
    if isinstance(left, sp.Symbol) or isinstance(right, sp.Symbol):
        if key is None or any(isinstance(t, sp.Symbol) and t.name == key for t in (left, right)):
            return ops, terms
    diff = sp.expand(left - right)
    candidates = sorted(diff.free_symbols, key=lambda s: (s.name != key, s.name))
    for target in candidates:
        if key is not None and target.name != key:
            continue
        coeff = diff.coeff(target)
        rest = sp.expand(diff - coeff * target)
        if not coeff.is_number or coeff == 0 or target in rest.free_symbols:
            continue
        op = ops[0] if coeff > 0 else _FLIP[ops[0]]
        return (op,), (target, sp.expand(-rest / coeff))
    return ops, terms


def _restriction(ops: tuple[str, ...], terms: tuple[Any, ...], key: str | None, text: str) -> Restriction:
    """One relation chain as a restriction of one parameter (``key``, else the lone symbol); a
    linear relation among parameters is solved for it (``g_0 + g_1 >= 0`` bounds ``g_0`` by ``-g_1``)."""
    ops, terms = _solved(ops, terms, key)
    if any(op not in ("<", "<=", ">", ">=", "=") for op in ops):
        raise RegionError(f"{text!r}: only =, <, <=, > and >= restrict a parameter")
    if len(terms) > 3:
        raise RegionError(f"{text!r}: at most two bounds per parameter")
    if key is not None:
        target = next((t for t in terms if isinstance(t, sp.Symbol) and t.name == key), None)
        if target is None:
            raise RegionError(f"{text!r} does not bound {key} alone on one side (write e.g. '0 <= {key} < 1')")
    else:
        if len(terms) == 3:
            target = terms[1] if isinstance(terms[1], sp.Symbol) else None
        else:
            target = next((t for t in terms if isinstance(t, sp.Symbol)), None)
        if target is None:
            raise RegionError(f"{text!r} does not bound a parameter alone on one side (write e.g. 'B \\leq 1', "
                              "'0 <= a < 1', 'b_m >= b_s')")
    index = list(terms).index(target)
    if len(terms) == 3 and index != 1:
        raise RegionError(f"{text!r}: in a chain the bounded parameter stands in the middle")
    if len(ops) == 2 and ((ops[0] in ("<", "<=")) != (ops[1] in ("<", "<="))):
        raise RegionError(f"{text!r}: a chain reads one way (0 <= a < 1)")
    lower = upper = value = None
    lower_strict = upper_strict = False
    for k, op in enumerate(ops):
        left, right = terms[k], terms[k + 1]
        if left is target:
            other, rel = right, op
        elif right is target:
            other, rel = left, _FLIP[op]
        else:
            continue
        if target in sp.sympify(other).free_symbols:
            raise RegionError(f"{text!r}: {target} appears on both sides")
        if rel == "=":
            value = other
        elif rel in (">", ">="):
            lower, lower_strict = other, rel == ">"
        else:
            upper, upper_strict = other, rel == "<"
    if value is not None and (lower is not None or upper is not None):
        raise RegionError(f"{text!r}: an equality and a bound at once")
    return Restriction(target, lower, lower_strict, upper, upper_strict, value, text).checked()


def read_region(text: str, symbols: Mapping[str, Any] | Any, key: str | None = None) -> Region:
    r"""A region from an assumption as written: ``"B = 0"``, ``'B \geq 0'``, ``"0 <= a < 1"``,
    ``'a \in [0, 1)'``, ``"b_m >= b_s, B <= K*T"`` (LaTeX or the expression syntax).

    ``symbols`` is the paper's symbol table (or a mapping of names to symbols, for tests);
    ``key`` names the parameter the restriction is about (a ``[symbols]`` entry), else each
    relation bounds its lone symbol (the middle of a chain, the left one of ``b_m >= b_s``).

    >>> import sympy as sp
    >>> K, T = sp.symbols("K T", positive=True)
    >>> B = sp.Symbol("B", real=True)
    >>> read_region(r"B \leq \frac{KT}{2}", {"B": B, "K": K, "T": T}).text()
    'B <= K*T/2'
    >>> read_region(r"B \in [0, 1)", {"B": B}).text()
    '0 <= B < 1'
    >>> read_region("1 < B < 0", {"B": B})
    Traceback (most recent call last):
    ...
    hapticproof.audit.regions.RegionError: 1 < B < 0: no value of B satisfies it
    """
    parse = _parser(symbols)
    restrictions = [_restriction(ops, terms, key, text.strip()) for ops, terms in parse_relations(text, parse)]
    return Region(tuple(restrictions))


def _parser(symbols: Any) -> Any:
    from hapticproof.audit.reader.names import SymbolTable
    from hapticproof.audit.reader.printed import parse_printed

    table = symbols if isinstance(symbols, SymbolTable) else SymbolTable(symbols=dict(symbols))
    return lambda text: parse_printed(text, table)


def with_symbols(region: Region, symbols: Mapping[str, sp.Symbol]) -> Region:
    """The region with each restricted parameter and bound written in ``symbols`` (by name)."""
    def sub(expr: Any) -> Any:
        if expr is None:
            return None
        expr = sp.sympify(expr)
        mapping = {s: symbols[s.name] for s in expr.free_symbols if s.name in symbols and symbols[s.name] != s}
        return expr.xreplace(mapping) if mapping else expr

    out = []
    for r in region.restrictions:
        symbol = symbols.get(r.name, r.symbol)
        out.append(replace(r, symbol=symbol, lower=sub(r.lower), upper=sub(r.upper), value=sub(r.value)))
    return Region(tuple(out))
