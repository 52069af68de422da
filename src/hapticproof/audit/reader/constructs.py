r"""The grammar's rules for constructs: groups and brackets, bars and ``\left``/``\right``,
fractions and roots, elementary functions and real parts, determinants, ``diag``, indexed extrema,
sums, limits, integrals, environments (matrices, cases).

Mixed into :class:`~hapticproof.audit.reader.grammar.Parser`: the methods use its token
cursor (``peek``, ``next``, ``error``...) and each other's rules through ``self``.
"""

from __future__ import annotations

from dataclasses import replace
from typing import Any

import sympy as sp
from hapticproof.core.limits import check_power, degree_bound
from hapticproof.audit.reader.lexer import ALIGN_ENVS, DELIMITER_PAIRS, GREEK, MATRIX_ENVS, MULTIPLY, OPENERS, Token, is_relation
from hapticproof.audit.reader.names import Script, index_symbol, sympy_name
from hapticproof.audit.reader.statements import Elision, IndexedMax, IndexedMin, Norm, PrintedLimit, RELATION_CLASSES, Relation, is_matrix
from hapticproof.audit.reader.names import ELEMENTARY, PARTS


__all__ = ["ConstructRules"]


class ConstructRules:
    """Rules of the parser (a mixin of :class:`~hapticproof.audit.reader.grammar.Parser`)."""

    def call_arguments(self, name: str, start: Token) -> list[Any]:
        open_ = self.next()
        context = f"the argument of {name}"
        with self.nested():
            args = [self.parse_sum()]
            while self.at("op", ","):
                self.next()
                args.append(self.parse_sum())
            self.expect_close(open_, context)
        return args

    def closer_for(self, open_: Token) -> tuple[str, str]:
        if open_.kind == "left":
            return "right", "\\right"
        if open_.kind == "sym":
            return "sym", "\\}"
        return "op", OPENERS[open_.value]

    def expect_close(self, open_: Token, context: str) -> Token:
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

    def bracket_items(self, open_: Token, context: str) -> list[Any]:
        with self.nested():
            items = [self.parse_sum()]
            while self.at("op", ",") or self.at("sep"):
                self.next()
                items.append(self.parse_sum())
            self.expect_close(open_, context)
        return items

    def row_vector(self, items: list[Any], tok: Token) -> Any:
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

    def wrap_bars(self, delimiter: str, inner: Any, tok: Token) -> Any:
        if delimiter == "|":
            if is_matrix(inner):
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
        expected = DELIMITER_PAIRS[delimiter]
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

        def evaluated() -> Any:
            v = sp.sympify(value)
            if variable in v.free_symbols or not v.free_symbols:
                return v.subs(variable, target)
            # Z_t|_{Z_e = 0}: a name whose value depends on Z_e only through its definition
            return sp.Subs(v, variable, target)

        return self.combine(evaluated, script.op, "an evaluation")

    # -- operators --------------------------------------------------------------------------------
    def parse_fraction(self) -> Any:
        cmd = self.next()
        num = self.fraction_argument(f"the numerator of {cmd.value}")
        den = self.fraction_argument(f"the denominator of {cmd.value}")
        if is_matrix(den):
            raise self.error(f"{cmd.value} with a matrix denominator", cmd)
        return self.combine(lambda: num * sp.Pow(den, -1), cmd, cmd.value)

    def fraction_argument(self, context: str) -> Any:
        t = self.peek()
        if t.kind == "op" and t.value == "{":
            return self.parse_group(context)
        if t.kind == "number" and t.value.isascii() and t.value.isdigit():
            if len(t.value) == 1:
                self.next()
            else:  # TeX reads one digit per argument: \frac12 is 1/2
                self.toks[self.i] = replace(t, value=t.value[1:], pos=t.pos + 1, space=False)
            return sp.Integer(t.value[0])
        if t.kind == "letter" or (t.kind == "cmd" and t.value in GREEK):
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
        if is_matrix(radicand):
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
        if (t.kind in ("op", "cmd") and t.value in MULTIPLY) or (t.kind == "op" and t.value == "/"):
            raise self.error(
                f"ambiguous: the unparenthesised argument of {what} (from position {start.pos}) "
                f"is followed by '{t.value}'; use parentheses"
            )
        return value

    def parse_elementary(self) -> Any:
        cmd = self.next()
        func = ELEMENTARY[cmd.value]
        power = None
        if self.at("op", "^"):
            script = self.read_script()
            if script.canon == "-1":
                raise self.error(f"{cmd.value}^{{-1}} is ambiguous (inverse or reciprocal?)", script.op)
            power = self.parse_script(script, f"the power of {cmd.value}")
        argument = self.delimited_argument(cmd.value, "(")
        if argument is None:
            argument = self.parse_run(cmd.value, "function")
        if is_matrix(argument):
            raise self.error(f"{cmd.value} of a matrix", cmd)
        value = self.combine(lambda: func(argument), cmd, cmd.value)
        if power is not None and getattr(power, "is_Integer", False):
            check_power(None, int(power), f"printed display, position {cmd.pos}", degree=degree_bound(value))
        return value if power is None else value**power

    def parse_part(self) -> Any:
        t = self.next()
        name = t.value if t.kind == "cmd" else t.arg.strip()
        func = PARTS[name]
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
        if not is_matrix(argument):
            raise self.error("det of a scalar expression (the table should give a matrix)", first)
        return self.combine(lambda: sp.Determinant(argument), first, "a determinant")

    def parse_residue(self) -> Any:
        r"""``\mathrm{Res}_{z = z_0} F`` (``\operatorname{Res}``, ``\text{Res}``): the residue of ``F``
        at ``z_0``, computed when ``F`` is an expression of the variable; the residue of a named
        function (``\mathrm{Res}_{z=1} G^{-1}(z)``) is what the display names, kept as
        ``Res(F, z_0)``."""
        cmd = self.next()
        variable, point = None, None
        if self.at("op", "_"):
            script = self.read_script()
            with self.bounded(script.start, script.stop, "the subscript of Res"):
                t = self.next()
                if t.kind != "letter":
                    raise self.error("Res needs its variable and point as a subscript (_{z=1})", t)
                variable = sp.Symbol(t.value)
                if not self.at("op", "="):
                    raise self.unexpected("the subscript of Res (expected '=')")
                self.next()
                point = self.parse_sum()
        body = self.delimited_argument("Res", "([{")
        if body is None:
            body = self.parse_run("Res", "operator")
        if is_matrix(body):
            raise self.error("Res of a matrix (give the residue matrix itself)", cmd)
        body = sp.sympify(body)
        if variable is not None and point is not None and not body.atoms(sp.core.function.AppliedUndef) \
                and variable in body.free_symbols:
            return sp.residue(body, variable, point)
        return sp.Function("Res")(body, point if point is not None else sp.Symbol("z_0"))

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
        if all(is_matrix(x) for x in items):
            return self.combine(lambda: sp.BlockDiagMatrix(*items), first, "a block diagonal")
        if any(is_matrix(x) for x in items):
            raise self.error("diag mixes matrices and scalars", first)
        return sp.ImmutableMatrix(sp.diag(*items))

    def parse_binding(self, script: Script, what: str) -> tuple[dict[str, sp.Symbol], list[Any]]:
        """``i``, ``i,j \\neq i``: the bound indices (printed name -> symbol) and conditions."""
        indices: dict[str, sp.Symbol] = {}
        conditions: list[Any] = []
        with self.bounded(script.start, script.stop, f"the subscript of {what}"), self.indexing():
            while True:
                t = self.peek()
                if t.kind not in ("letter", "cmd") or (t.kind == "cmd" and t.value not in GREEK):
                    raise self.unexpected(f"the subscript of {what}")
                self.next()
                symbol = index_symbol(t.value)
                indices[t.value] = symbol
                with self.scope(indices):
                    conditions.extend(self.condition_chain(symbol))
                if not self.at("op", ","):
                    break
                self.next()
        return indices, conditions

    def condition_chain(self, left: Any) -> list[Any]:
        """The relations of a chain ``left < a <= b ...`` that follows ``left`` (each link one condition)."""
        conditions = []
        while is_relation(self.peek()):
            op_tok = self.peek()
            op = self.relation_op()
            right = self.parse_sum()
            conditions.append(self.combine(lambda l=left, o=op, r=right: RELATION_CLASSES[o](l, r), op_tok, "a condition"))
            left = right
        return conditions

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
            if any(is_matrix(a) for a in args):
                raise self.error(f"{cmd.value} of matrices", cmd)
            return (sp.Min if kind is IndexedMin else sp.Max)(*args)
        raise self.error(f"{cmd.value} needs a subscript or an argument list", cmd)

    def summation_limits(self, cmd: Token) -> tuple[Script, Script]:
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
            if t.kind not in ("letter", "cmd") or (t.kind == "cmd" and t.value not in GREEK):
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
                    conditions.extend(self.condition_chain(self.parse_sum()))
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
        var = existing if isinstance(existing, sp.Symbol) else sp.Symbol(sympy_name(name), real=True)
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
            if is_relation(t) or t.kind in ("sep", "newline", "right", "end") or (
                t.kind == "op" and t.value in "+-,&)]}"
            ):
                return None
            if t.kind == "letter" and t.value == "d" and "d" not in self.table.symbols and k + 1 < self.limit:
                nxt = self.toks[k + 1]
                if nxt.kind == "letter" or (nxt.kind == "cmd" and nxt.value in GREEK):
                    return nxt.value
            k += 1
        return None

    # -- environments -----------------------------------------------------------------------------
    def parse_environment(self) -> Any:
        begin = self.peek()
        if begin.value in MATRIX_ENVS:
            matrix = self.parse_matrix()
            if begin.value == "vmatrix":
                return self.combine(lambda: sp.Determinant(matrix), begin, "a determinant")
            return matrix
        if begin.value == "cases":
            return self.parse_cases()
        if begin.value in ALIGN_ENVS:
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

    def make_matrix(self, rows: list[list[Any]], tok: Token) -> Any:
        blocks = [[is_matrix(x) for x in row] for row in rows]
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
