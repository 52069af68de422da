"""The grammar of the printed dialect: a recursive-descent parser over the tokens, from lines and
clauses down to sums, products, factors and atoms (names and constructs are read by the rules
of :mod:`~hapticproof.audit.reader.namerules` and :mod:`~hapticproof.audit.reader.constructs`)."""

from __future__ import annotations

from collections.abc import Callable, Iterator, Mapping
from contextlib import contextmanager
from dataclasses import dataclass
from typing import Any

import sympy as sp

from hapticproof.core.errors import LatexParseError
from hapticproof.audit.reader.constructs import ConstructRules
from hapticproof.audit.reader.lexer import ARROWS, CONNECTORS, DECORATIONS, ELLIPSES, FRACTIONS, GREEK, MULTIPLY, OPERATOR_COMMANDS, RELATIONS, Token, UNSUPPORTED_RELATIONS, describe_token, is_relation, matching_close
from hapticproof.audit.reader.namerules import NameRules
from hapticproof.audit.reader.names import SymbolTable, index_symbol, normalise_name
from hapticproof.audit.reader.statements import Elision, Expression, IndexRange, Lines, Qualified, Relation, Span, Statement
from hapticproof.audit.reader.names import ELEMENTARY, PARTS, is_known_command

















class Parser(NameRules, ConstructRules):
    """Recursive-descent parser over the tokens of one (possibly wrapped) line."""

    def __init__(self, text: str, toks: list[Token], table: SymbolTable) -> None:
        self.text = text
        self.toks = toks
        self.table = table
        self.match = matching_close(text, toks)
        self.i = 0
        self.limit = len(toks)
        self.last_end = toks[0].pos if toks else 0
        self.scopes: list[dict[str, sp.Symbol]] = []
        self.index_mode = 0
        self.depth = 0
        self.bars: list[tuple[str, int]] = []  # open | and \| with the depth they close at
        self.differentials: list[str] = []  # integration variables awaiting their d<var>

    # -- token access -----------------------------------------------------------------------------
    def peek(self, k: int = 0) -> Token:
        j = self.i + k
        if j < self.limit:
            return self.toks[j]
        end = self.toks[self.limit - 1].end if self.limit else len(self.text)
        return Token("eof", "end of input", end, end)

    def next(self) -> Token:
        t = self.peek()
        if t.kind != "eof":
            self.i += 1
            self.last_end = t.end
        return t

    def at(self, kind: str, value: str | None = None, k: int = 0) -> bool:
        t = self.peek(k)
        return t.kind == kind and (value is None or t.value == value)

    def error(self, message: str, tok: Token | None = None) -> LatexParseError:
        return LatexParseError(message, self.text, (tok or self.peek()).pos)

    def unexpected(self, context: str) -> LatexParseError:
        t = self.peek()
        if t.kind == "eof":
            return self.error(f"unexpected end of input in {context}")
        if is_relation(t):
            return self.error(f"relation symbol '{t.value}' inside {context}")
        if t.kind == "cmd" and t.value in UNSUPPORTED_RELATIONS:
            return self.error(f"unsupported relation {t.value}")
        if t.kind == "text":
            return self.error(f"prose {t.value}{{{t.arg}}} is not mathematics")
        if t.kind == "cmd" and not is_known_command(t.value):
            return self.error(f"unsupported command {t.value}")
        return self.error(f"unexpected '{describe_token(t)}' in {context}")

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

    def combine(self, build: Callable[[], Any], tok: Token, what: str) -> Any:
        """Run a SymPy construction; turn its failures (shape errors...) into parse errors."""
        try:
            return build()
        except LatexParseError:
            raise
        except (TypeError, ValueError, NotImplementedError, ArithmeticError) as err:
            detail = str(err).strip().splitlines()[0] if str(err).strip() else type(err).__name__
            raise self.error(f"cannot build {what}: {detail}", tok) from None

    def span_from(self, tok: Token) -> Span:
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

    def assemble(self, clauses: list[Any], first: Token) -> Statement:
        mains = [c for c in clauses if isinstance(c, Statement)]
        ranges = tuple(c for c in clauses if isinstance(c, IndexRange))
        conditions = tuple(c for c in clauses if isinstance(c, Condition))
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
        return t.kind == "cmd" and t.value in ARROWS

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
        return t.kind == "text" and t.value != "\\mathrm" and " ".join(t.arg.split()) in CONNECTORS

    def at_clause_end(self, k: int = 0) -> bool:
        t = self.peek(k)
        return (
            t.kind in ("eof", "sep")
            or (t.kind == "op" and t.value in ",.")
            or self.at_connector(k)
            or (t.kind == "cmd" and t.value in ARROWS)
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
        if self.index_name(0) is None or not is_relation(self.peek(1)):
            return False
        k = 1
        while is_relation(self.peek(k)):
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
        if t.kind == "cmd" and t.value in ELLIPSES and self.at_clause_end(1):
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

    def parse_condition(self) -> Condition:
        first = self.peek()
        terms = [index_symbol(self.next().value)]
        ops = []
        while is_relation(self.peek()):
            ops.append(self.relation_op())
            terms.append(index_symbol(self.next().value))
        return Condition(Relation(tuple(terms), tuple(ops), self.span_from(first)))

    def relation_op(self) -> str:
        t = self.next()
        if t.kind == "op" and t.value in "<>" and self.at("op", "=") and not self.peek().space:
            self.next()
            return t.value + "="
        return RELATIONS[t.value]

    def parse_chain(self) -> Statement:
        first = self.peek()
        if is_relation(first):
            raise self.error(f"missing left-hand side before '{first.value}'")
        terms, spans, ops = [], [], []
        while True:
            start = self.peek()
            terms.append(self.parse_sum())
            spans.append(self.span_from(start))
            if not is_relation(self.peek()):
                break
            op_tok = self.peek()
            ops.append(self.relation_op())
            if self.at_clause_end() or is_relation(self.peek()):
                raise self.error(f"missing right-hand side after '{op_tok.value}'")
        t = self.peek()
        if t.kind == "cmd" and t.value in UNSUPPORTED_RELATIONS:
            raise self.error(f"unsupported relation {t.value}")
        span = self.span_from(first)
        if not ops:
            return Expression(terms[0], span)
        return Relation(tuple(terms), tuple(ops), span, tuple(spans))

    # -- expressions ------------------------------------------------------------------------------
    def parse_sum(self) -> Any:
        value = self.parse_signed()
        terms: list[Any] = []       # scalar terms, added at once (one by one, a long sum is sorted n times)
        while True:
            t = self.peek()
            if t.kind == "op" and t.value in "+-":
                self.next()
                rhs = self.parse_signed()
                if isinstance(value, sp.Expr) and isinstance(rhs, sp.Expr):
                    terms.append(rhs if t.value == "+" else -rhs)
                    continue
                if terms:
                    value, terms = sp.Add(value, *terms), []
                if t.value == "+":
                    value = self.combine(lambda v=value, r=rhs: v + r, t, "a sum")
                else:
                    value = self.combine(lambda v=value, r=rhs: v - r, t, "a difference")
            elif t.kind == "cmd" and t.value in ("\\pm", "\\mp"):
                raise self.error(f"{t.value} stands for two statements; write them separately")
            else:
                return sp.Add(value, *terms) if terms else value

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
            if t.kind in ("op", "cmd") and t.value in MULTIPLY:
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
        if t.kind == "cmd" and t.value in ELLIPSES:
            return True
        return self.starts_implicit()

    def at_function_command(self) -> bool:
        t = self.peek()
        if t.kind == "cmd":
            return t.value in ELEMENTARY or t.value in PARTS or t.value in OPERATOR_COMMANDS - {
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
                t.value in GREEK
                or t.value in DECORATIONS
                or t.value in FRACTIONS
                or t.value in ELEMENTARY
                or t.value in PARTS
                or t.value in OPERATOR_COMMANDS
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
        if t.kind == "cmd" and t.value in ELLIPSES:
            if not first:
                raise self.error(f"{t.value} cannot be a factor of a product")
            self.next()
            return Elision(t.value)
        value = self.parse_atom()
        return self.postfix(value, t, applied=True)

    def postfix(self, value: Any, start: Token, applied: bool) -> Any:
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
            if v in GREEK or v in DECORATIONS:
                return self.parse_name()
            if v in FRACTIONS:
                return self.parse_fraction()
            if v in ELEMENTARY:
                return self.parse_elementary()
            if v in PARTS:
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
            if arg == "Res":
                return self.parse_residue()
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


@dataclass(frozen=True, slots=True)
class Condition:
    """An index condition clause (``j \\neq i``) before it is attached to its statement."""

    relation: Relation

    @property
    def span(self) -> Span:
        return self.relation.span

