r"""The grammar's rules for names: a base with its decorations, primes and scripts, resolved
through the symbol table to a symbol, an indexed family member or a function application.

Mixed into :class:`~hapticproof.audit.reader.grammar.Parser`: the methods use its token
cursor (``peek``, ``next``, ``error``...) and each other's rules through ``self``.
"""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

import sympy as sp
from hapticproof.core.limits import check_power, degree_bound
from hapticproof.audit.reader.lexer import DECORATIONS, GREEK, PROSE_WORDS, Token
from hapticproof.audit.reader.names import FamilySpec, Script, canonical_name, compose_name, index_symbol, read_name_base, split_commas, subscript_slots
from hapticproof.audit.reader.statements import IndexedCall, is_matrix


__all__ = ["NameRules"]


class NameRules:
    """Rules of the parser (a mixin of :class:`~hapticproof.audit.reader.grammar.Parser`)."""

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
        base, end = read_name_base(self.text, self.toks, self.i, self.match)
        if end > self.limit:
            raise self.error(f"unbalanced argument of {t.value}")
        return base, end - self.i

    def parse_name(self) -> Any:
        start = self.peek()
        if start.kind == "letter":
            word = self.letter_word()
            if word is not None:
                return self.parse_word(word)
        if start.kind == "cmd" and start.value in DECORATIONS:
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
        for word in PROSE_WORDS:  # longest first
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

    def read_script(self) -> Script:
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
            return Script(start, stop, tuple(self.toks[start:stop]), op)
        if t.kind == "eof":
            raise self.error(f"missing script after '{op.value}'", op)
        single = (
            t.kind == "letter"
            or (t.kind == "cmd" and (t.value in GREEK or t.value in ("\\infty", "\\prime", "\\ast", "\\star")))
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
        return Script(self.i - 1, self.i, (t,), op)

    def parse_script(self, script: Script, context: str) -> Any:
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
        self, start: Token, base: str, primes: int, sub: Script | None, sup: Script | None
    ) -> Any:
        """Give a parsed name its meaning (symbol, function application, family member...)."""
        table = self.table
        plain = compose_name(base, primes, sub.toks if sub else None, None)
        if sup is not None:
            full = compose_name(base, primes, sub.toks if sub else None, sup.toks)
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
        self, base: str, primes: int, sub: Script, start: Token
    ) -> tuple[Any, bool] | None:
        """Match ``base_{sub}`` against the table's families; ``(value, applied)`` or None."""
        full_base = base + "'" * primes
        candidates: list[tuple[int, FamilySpec, list[Any]]] = []
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

    def match_family(self, spec: FamilySpec, sub: Script) -> tuple[int, list[Any]] | None:
        """``(number of literal slots matched, index values)`` or None."""
        toks = list(sub.toks)
        indices: list[Any] = []
        literals = 0
        if spec.comma:
            parts = split_commas(toks)
            if len(parts) != len(spec.slots):
                return None
            offset = sub.start
            for part, slot in zip(parts, spec.slots):
                if not part:
                    return None
                if slot is not None:
                    if canonical_name(part) != slot:
                        return None
                    literals += 1
                else:
                    with self.bounded(offset, offset + len(part), "an index"), self.indexing():
                        indices.append(self.parse_sum())
                offset += len(part) + 1
            return literals, indices
        slots = subscript_slots(toks)
        if len(slots) != len(spec.slots):
            return None
        for (text, tok), slot in zip(slots, spec.slots):
            if slot is not None:
                if text != slot:
                    return None
                literals += 1
            elif text in self.table.indices:
                indices.append(self.bound(text) or index_symbol(text))
            elif text.isascii() and text.isdigit():
                indices.append(sp.Integer(text))
            else:
                return None
        return literals, indices

    def superscript(
        self, value: Any, sup: Script, start: Token, applied: bool, name: str | None = None
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
            if is_matrix(value):
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
        if getattr(exponent, "is_Integer", False):   # bounded before it is built (K^{99999999})
            check_power(value if getattr(value, "is_Rational", False) else None, int(exponent),
                        f"printed display, position {sup.op.pos}", degree=degree_bound(value))
        return self.combine(lambda: value**exponent, sup.op, "a power")

    def apply(self, func: Callable[..., Any], name: str, start: Token) -> Any:
        args = self.call_arguments(name, start)
        return self.combine(lambda: func(*args), start, f"{name}(...)")
