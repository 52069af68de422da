r"""A paper read as its definitions: each display binds names, states an identity, or a condition.

:class:`PaperReading` reads a paper's displays in order (and the inline ``$...$`` definitions of
the prose before each), keeping the paper's namespace: a display ``H(z) = K + B\frac{z-1}{Tz}``
*binds* ``H`` exactly (:mod:`~hapticproof.audit.definitions.values`); a display whose sides are both
computable from bound names is an *identity*; an inequality is a *condition*, whose claim -- the
property, its strength and the object it is about -- comes from the sentence that leads into it
(:mod:`~hapticproof.audit.definitions.prose`). Trailing qualifiers (``, \quad K \ge 0``,
``t_d = T``, ``0 < \omega \le \pi/T``, ``\star \in \{f, b, t\}``) are assumptions, substitutions,
frequency ranges and index sets, never a side of the equation.

>>> r = PaperReading()
>>> r.read("1", r"H(z) = K + B\,\frac{z-1}{Tz}, \quad K \ge 0,\; B \ge 0 .").kind
'definition'
>>> r.read("2", r"G^{-1}(z) = b + H(z)\frac{T}{z-1}").binds
('G^-1',)
>>> r.read("3", r"\operatorname{Re} G^{-1}(e^{j\omega T}) = b - \frac{KT}{2} + B\cos\omega T").kind
'identity'
"""

from __future__ import annotations

import re
from collections.abc import Iterable, Mapping
from dataclasses import dataclass, field
from typing import Any

import sympy as sp
from sympy.core.function import AppliedUndef

from hapticproof.audit.definitions.ports import TWO_PORT_LETTERS, SignalSystem, two_port_entry
from hapticproof.audit.definitions.signals import letter_of
from hapticproof.audit.definitions.prose import ProseClaim, claim_of, inline_math, last_sentence
from hapticproof.audit.definitions.values import (TRANSFER, Binding, Environment, Unbound, Unsupported,
                                                  evaluate)
from hapticproof.core.errors import HapticproofError, LatexParseError
from hapticproof.core.symbols import omega as OMEGA
from hapticproof.core.symbols import s as S_SYM
from hapticproof.core.symbols import z as Z_SYM

__all__ = ["PaperReading", "Reading", "definition_target", "DEFINITION", "IDENTITY", "CONDITION", "OTHER", "MALFORMED"]

DEFINITION, IDENTITY, CONDITION, OTHER, MALFORMED = "definition", "identity", "condition", "other", "malformed"
#: an inline formula about the real or imaginary part of an object (``$\operatorname{Re} Z_c(e^{j\omega T}) = ...$``)
_INLINE_PART = re.compile(r"\s*(?:\\operatorname\{(?:Re|Im)\}|\\(?:Re|Im|Real|Imag)\b|\\mathrm\{(?:Re|Im)\}|\\mathfrak\{[RI]\})")
#: a display that introduces a new name as the result of a derivation ("eliminating ... gives")
DERIVED = "derived"
#: an equation among signals (a model: ``Z_m v_m = f_h - k_f f_e``)
MODEL = "model"
#: a bound name defined again, differently, with no word tying it to the first definition
REDEFINED = "redefined"
#: words that tie a display to an earlier one: then it is an identity with it, not a new definition
_REFERENCE = re.compile(r"\\eqref|\\ref|rewritten|restated|\bi\.e\.|\bthat\s+is\b|\brecall|\bagain\b|as\s+before|"
                        r"equivalently|in\s+other\s+words|\bsame\b", re.I)

_DERIVATION = re.compile(r"\b(?:gives?|giving|yields?|we\s+obtain|one\s+obtains|we\s+get|one\s+(?:gets|finds)|it\s+follows|"
                         r"follows\s+from|hence|thus|therefore|so\s+that|eliminating|solving|substituting|reduces?\s+to|"
                         r"we\s+find|leads?\s+to|results?\s+in|is\s+found|we\s+have)\b", re.I)

#: a real part, imaginary part, modulus or conjugate in a display's text
_COMPLEX_CONTEXT = re.compile(r"\\(?:Re|Im|Real|Imag|lvert|overline)\b|(?:operatorname|mathrm|text|mathfrak)\{(?:Re|Im)\}|\|")
_INDEX_SET = re.compile(r",?(?:\s|\\q?quad|\\[,;: ]|~)*\\?(\\[A-Za-z]+|[A-Za-z])\s*\\in\s*\\\{([^{}]{1,80})\\\}\s*[.,;]?\s*$")
_ANGLES = ("theta", "vartheta")
#: words before an inline inequality that make it a result, not an assumption
_CLAIMED = re.compile(r"reduces?\s+to|becomes?|gives?|yields?|if\s+and\s+only\s+if|\biff\b|condition|requires?|necessary|"
                      r"sufficient|\bbound\b|holds?|positive\s+real|passive|stable|implies|so\s+that|hence|thus|therefore", re.I)
_RELATION_OPS = (">", "<", ">=", "<=")


@dataclass
class Reading:
    """What one display is: ``kind`` (definition, identity, condition, other, malformed), the
    names it ``binds``, its main relations, qualifiers and the claim of its sentence."""

    id: str
    text: str
    kind: str
    statement: Any = None
    main: tuple[Any, ...] = ()
    binds: tuple[str, ...] = ()
    assumptions: tuple[Any, ...] = ()
    substitutions: Mapping[str, Any] = field(default_factory=dict)
    frequency_range: Any = None
    claim: ProseClaim | None = None
    #: the namespace the display is read in (names bound before it)
    environment: Environment | None = None
    #: name -> id of the display that bound it, at this display
    defined_at: Mapping[str, str] = field(default_factory=dict)
    note: str = ""
    error: str = ""
    #: the sentence presents the display as derived (``gives``, ``eliminating``): a definition
    #: it makes is a claim the toolkit could not verify
    derived: bool = False
    #: the display as the file or the source prints it (before a continued chain is completed)
    printed: str = ""
    #: an assumption stated for this claim (a paper file's ``assumption``)
    stated: str = ""
    #: printed names the display uses beyond its statement's (a family's ``G_\\star^{-1}`` and ``\\star``)
    extra_names: tuple[str, ...] = ()
    #: what the paper's model or port relations say the display's left-hand name is (an identity
    #: then compares the printed right-hand side with it), and how it was found
    expected: Any = None
    expected_how: str = ""


class PaperReading:
    """The namespace of a paper read display by display (see the module doc)."""

    def __init__(self, symbols: Mapping[str, sp.Symbol] | None = None, functions: Iterable[str] = ()) -> None:
        from hapticproof.audit.reader.names import SymbolTable

        self.symbols: dict[str, sp.Symbol] = dict(symbols or {})
        self.functions: set[str] = set(functions)
        self.bindings: dict[str, Binding] = {}
        self.defined_at: dict[str, str] = {}
        #: definitions over names no display binds (``\eta = ... z_{12} ...``): SymPy forms
        self.formulas: dict[str, tuple[Any, str | None]] = {}
        self.order: list[str] = []
        self.assumptions: list[Any] = []
        self.readings: list[Reading] = []
        #: the periods: names multiplying the frequency (e^{j omega T}, cos(omega h)): positive
        self.periods: set[str] = set()
        #: names bound by derived displays the toolkit did not verify
        self.tentative: set[str] = set()
        #: the index letters of families (``\\star`` in ``G_\\star``)
        self.indices: set[str] = set()
        #: signals, the model's relations, port descriptions and terminations
        self.system = SignalSystem()
        self._last_lhs = ""
        self._mode = "auto"
        self._table_type = SymbolTable

    @classmethod
    def of_claims(cls, claims: Iterable[Any], table: Any = None, region: Any = None) -> PaperReading:
        """The reading of a paper file: its ``definition``, ``identity`` and ``condition`` claims in
        order (each claim's kind decides whether it binds), with the file's names and assumptions."""
        from hapticproof.audit.reader.names import normalise_name

        symbols: dict[str, sp.Symbol] = {}
        functions: set[str] = set()
        if table is not None:
            for printed, value in dict(table.symbols).items():
                if isinstance(value, sp.Symbol) and printed not in ("z", "s", "\\omega"):
                    symbols[normalise_name(printed)] = value
            for printed in dict(table.functions):
                functions.add(normalise_name(printed))
                symbols.setdefault(normalise_name(printed), sp.Symbol(_sympy_name(printed), real=True))
        reading = cls(symbols, functions)
        for sym in symbols.values():
            if sym.is_positive:
                reading.assumptions.append(sp.StrictGreaterThan(sp.Symbol(sym.name, real=True), 0))
            elif sym.is_nonnegative:
                reading.assumptions.append(sp.GreaterThan(sp.Symbol(sym.name, real=True), 0))
        if region:
            for r in region.restrictions:
                sym = sp.Symbol(r.name, real=True)
                if r.lower is not None:
                    reading.assumptions.append((sp.StrictGreaterThan if r.lower_strict else sp.GreaterThan)(sym, r.lower))
                if r.upper is not None:
                    reading.assumptions.append((sp.StrictLessThan if r.upper_strict else sp.LessThan)(sym, r.upper))
        for spec in claims:
            if spec.claim not in ("definition", "identity", "condition"):
                continue
            reading.read(spec.id, spec.printed, mode=spec.claim, derived=spec.derived, stated=spec.stated)
            if spec.claim == "definition" and reading.readings and reading.readings[-1].kind == IDENTITY:
                # a definition claim of a bound name: the file says it is a new definition
                last = reading.readings.pop()
                reading.read(spec.id, spec.printed, mode="redefine", derived=spec.derived, stated=spec.stated)
                del last
        return reading

    def verified(self, id: str) -> None:
        """The names display ``id`` derived are verified (a scene's model gives them): no longer tentative."""
        for r in self.readings:
            if r.id == id:
                self.tentative.difference_update(r.binds)

    def reading_for(self, id: str, text: str) -> Reading:
        """The reading of display ``id`` as printed, or of another text (a repair's trial edit) in
        the namespace the display sees, without binding anything."""
        index = next((k for k, r in enumerate(self.readings) if r.id == id), None)
        if index is None:
            raise KeyError(id)
        original = self.readings[index]
        if text == original.printed:
            return original
        trial = PaperReading(self.symbols, self.functions)
        trial.bindings = dict(original.environment.bindings) if original.environment else {}
        trial.defined_at = dict(original.defined_at)
        trial.formulas = dict(self.formulas)
        trial.assumptions = list(self.assumptions)
        trial.periods = set(self.periods)
        trial.tentative = set(self.tentative)
        trial.readings = list(self.readings[:index])
        trial.order = list(self.order)
        trial.system = self.system
        mode = {DEFINITION: "definition", DERIVED: "definition", IDENTITY: "identity", CONDITION: "condition"}.get(original.kind, "auto")
        out = trial.read(id, text, mode=mode if mode != "definition" else "identity", derived=original.derived,
                         stated=original.stated)
        out.claim = original.claim
        return out

    # -- the symbol table ------------------------------------------------------------------------

    def _table(self, text: str) -> Any:
        """A symbol table knowing every name of ``text``: parse, and add each unknown name the
        reader reports (a name followed by ``(z)``, ``(s)``, ``(e^{...})`` or ``(\\omega)`` is a
        function)."""
        from hapticproof.audit.reader.names import normalise_name, sympy_name
        from hapticproof.audit.reader.printed import parse_printed

        # a transfer function's name known as a plain symbol ("F = G^{-1} V" inline) is a function
        # where this text applies it ("G^{-1}(z) = ..."): else it would read as a product with (z)
        for name in [n for n in self.symbols if n not in self.functions and ("^{-1}" in n or n[:1] in "GHZY")]:
            for m in re.finditer(re.escape(name), text):
                if _applied(text[m.end():].lstrip()):
                    self.functions.add(name)
                    break
        complex_entries = True
        for _ in range(60):
            table = self._make_table(text, complex_entries)
            try:
                return table, parse_printed(text, table)
            except TypeError:
                if not complex_entries:
                    raise
                complex_entries = False         # "|z_11| > z_22" compares the entries: read them real
                continue
            except LatexParseError as err:
                match = re.search(r"unknown name (.+?) at position (\d+)", str(err))
                if not match:
                    raise
                position = int(match.group(2))
                rest = text[position:]
                name_end = _name_end(rest)
                try:
                    canonical = normalise_name(rest[:name_end])
                except (LatexParseError, ValueError):
                    canonical = normalise_name(match.group(1))
                following = rest[name_end:].lstrip()
                if canonical in self.symbols and (canonical in self.functions or not _applied(following)):
                    canonical = normalise_name(match.group(1))
                    if canonical in self.symbols:
                        raise
                if _applied(following):
                    self.functions.add(canonical)
                # every name is also a plain symbol: a bound function written without its argument
                # (Z_c for Z_c(z)) is its value
                self.symbols.setdefault(canonical, sp.Symbol(sympy_name(canonical), real=True))
        raise LatexParseError("too many unknown names", text, 0)

    def _make_table(self, text: str = "", complex_entries: bool = True) -> Any:
        from hapticproof.audit.reader.names import sympy_name

        symbols = {"z": Z_SYM, "s": S_SYM, "\\omega": OMEGA}
        symbols.update(self.symbols)
        if re.search(r"(?<![A-Za-z\\])e(?![A-Za-z^])", text) and not re.search(r"(?<![A-Za-z\\])e\s*\^", text):
            symbols["e"] = sp.Symbol("e", real=True)      # "e = x_m - x_s": a name, not Euler's number
        if complex_entries and _COMPLEX_CONTEXT.search(text):
            # \Re z_{11}, |z_{12} z_{21}|: a general two-port's entries are complex numbers here
            letters = TWO_PORT_LETTERS | {letter_of(m) for m in self.system.ports}
            for key, value in symbols.items():
                if isinstance(value, sp.Symbol) and two_port_entry(value.name, letters):
                    symbols[key] = sp.Symbol(value.name)
        functions = {name: sp.Function(sympy_name(name)) for name in self.functions}
        return self._table_type(symbols=symbols, functions=functions)

    # -- reading ---------------------------------------------------------------------------------

    def environment(self) -> Environment:
        return Environment(dict(self.bindings), angles=frozenset(_ANGLES))

    def read_inline(self, id: str, prose: str) -> list[Reading]:
        """The inline ``$...$`` definitions of a prose passage (``$Z_m(s) = m_m s + b_m$``), and
        its identities on a real or imaginary part of a defined object
        (``$\\operatorname{Re} Z_c(e^{j\\omega T}) = B_c - K_c T/2$``)."""
        out = []
        for k, math in enumerate(inline_math(prose)):
            if "=" not in math or re.search(r"\\[lg]eq?\b|[<>]", math):
                continue
            if _INLINE_PART.match(math):
                before = last_sentence(prose[:prose.find(f"${math}$")])
                reading = self._inline_identity(f"{id}.inline{len(out) + 1}", math, before)
                if reading is not None:
                    out.append(reading)
                continue
            if not re.match(r"\s*\\?[A-Za-z][^=]*\([zs]\)\s*=|\s*(?:\\mathbf\{?[A-Za-z]\}?|[A-Za-z])(?:_\{?[A-Za-z0-9]+\}?)?(?:\^\{-1\})?\s*=", math):
                continue
            known, functions = dict(self.symbols), set(self.functions)
            try:
                reading = self.read(f"{id}.inline{len(out) + 1}", math, definitions_only=True)
            except HapticproofError:
                continue
            if reading.kind in (DEFINITION, MODEL):
                out.append(reading)           # a definition, or a port variable / termination among signals
                continue
            if reading in self.readings:
                self.readings.remove(reading)
            self.symbols, self.functions = known, functions      # nothing of it is kept ("writing $Z_c = R + jX$")
        return out

    def _inline_identity(self, id: str, math: str, sentence: str) -> Reading | None:
        """An inline identity: one relation ``=`` between names the paper has already introduced,
        under the settings of its sentence ("with ($B_p = 0$), $\\operatorname{Re} z_{11} = b_m$").
        A formula with new names ("writing $Z_c = R + jX$ one finds $\\operatorname{Re}(Z_c^2) =
        R^2 - X^2$") or a chain is prose, not a claim: nothing of it is kept."""
        known, functions = dict(self.symbols), set(self.functions)
        try:
            reading = self.read(id, math, prose=sentence, definitions_only=True, mode="identity")
        except HapticproofError:
            reading = None
        if reading is None or reading.kind != IDENTITY or len(reading.main) != 1 or reading.main[0].ops != ("=",) \
                or set(self.symbols) - set(known):
            if reading is not None and reading in self.readings:
                self.readings.remove(reading)
            self.symbols, self.functions = known, functions
            return None
        return reading

    def read(self, id: str, text: str, *, prose: str = "", after: str = "", definitions_only: bool = False,
             mode: str = "auto", derived: bool = False, stated: str = "") -> Reading:
        """Read one display (its LaTeX as printed), binding what it defines.

        ``mode`` is ``auto`` (classify from the display and its sentence), or the kind a paper file
        gives: ``definition`` (binds), ``identity`` or ``condition`` (binds nothing)."""
        printed = text
        self._mode = mode
        claim = claim_of(prose, after) if prose or after else None
        if stated:
            claim = _with_stated(claim, stated)
        self._periods(text)
        if prose and not definitions_only:
            self._prose_assumptions(prose)
        if re.match(r"\s*(?:&\s*)?=", text) and self._last_lhs and not definitions_only:
            # the next row of an aligned chain: "= z_{11} - ..." continues the row above
            text = self._last_lhs + " " + re.sub(r"^\s*&\s*", "", text)
        text, index = _index_set(text)
        if index is not None:
            return self._family(id, text, index, claim)
        try:
            table, statement = self._table(text)
        except (LatexParseError, HapticproofError, ValueError) as err:
            reading = Reading(id, text, MALFORMED, claim=claim, error=str(err), environment=self.environment())
            self.readings.append(reading)
            return reading
        relations = list(statement.relations())
        reading = Reading(id, text, OTHER, statement, claim=claim, environment=self.environment(),
                          defined_at=dict(self.defined_at), printed=printed, stated=stated,
                          derived=derived or bool(mode == "auto" and claim is not None
                                                  and _DERIVATION.search(_plain_sentence(claim.sentence))))
        if not relations:
            reading.kind = MALFORMED if (claim is not None and claim.property) or mode == "condition" else OTHER
            reading.note = "an expression with no relation"
            self.readings.append(reading)
            return reading
        main, qualifiers = _split(relations)
        self._qualify(reading, qualifiers)
        reading.main = tuple(main)
        lhs = _lhs_text(text)
        if lhs and not definitions_only:
            self._last_lhs = lhs
        equations = all(op == "=" for r in main for op in r.ops)
        if equations and mode != "condition" and self._signal_equations(reading, main, prose or "", definitions_only):
            pass                              # ports, a model or a termination: relations among signals
        elif mode in ("identity", "condition"):
            reading.kind = IDENTITY if mode == "identity" else CONDITION
            reading.environment = self._env(reading)
            if mode == "identity":
                self._derivable(reading, main)
        elif equations:
            self._equations(reading, main, definitions_only)
        elif definitions_only or mode == "definition":
            reading.kind = OTHER
        else:
            reading.kind = CONDITION
        self.readings.append(reading)
        return reading

    def _qualify(self, reading: Reading, qualifiers: list[Any]) -> None:
        subs = {}
        assumptions = []
        for q in qualifiers:
            expr = q.as_sympy()
            free = expr.free_symbols
            if OMEGA in free or any(s.name in _ANGLES for s in free):
                reading.frequency_range = expr
                continue
            if q.ops == ("=",) and isinstance(q.terms[0], sp.Symbol):
                subs[q.terms[0].name] = q.terms[1]
                continue
            assumptions.append(expr)
        reading.substitutions = subs
        reading.assumptions = tuple(assumptions)
        if reading.claim is not None:
            for text in reading.claim.assumptions:
                for piece in _comma_list(text):
                    try:
                        _, st = self._table(piece)
                    except (LatexParseError, HapticproofError, ValueError):
                        continue
                    for r in st.relations():
                        if r.ops == ("=",) and isinstance(r.terms[0], sp.Symbol) and sp.sympify(r.terms[1]).is_number:
                            reading.substitutions = {**reading.substitutions, r.terms[0].name: r.terms[1]}
                        elif r.ops and all(op in _RELATION_OPS for op in r.ops):
                            reading.assumptions += (r.as_sympy(),)

    def _equations(self, reading: Reading, main: list[Any], definitions_only: bool) -> None:
        """Equations: definitions of the names they introduce (several per display, bound in the
        order their dependencies allow), otherwise an identity."""
        pending = []
        for relation in main:
            terms = list(relation.terms)
            target = definition_target(terms[0])
            if target is not None and target[0] in self.bindings and relation is main[0] and len(main) == 1 \
                    and not definitions_only and self._redefines(reading, target, terms[-1]):
                return
            if target is None or target[0] in self.bindings or target[0] in self.formulas:
                if definitions_only or pending or relation is not main[0]:
                    continue
                reading.kind = IDENTITY
                reading.environment = self._env(reading)
                self._derivable(reading, main)
                return
            if target[0] in self._parameters_used():
                reading.kind = OTHER if definitions_only else IDENTITY
                reading.note = f"{target[0]} is a parameter of an earlier definition: a value for it, not a definition"
                reading.environment = self._env(reading)
                return
            if not definitions_only and len(main) == 1 and len(terms) == 2 and self._determined(reading, target, terms):
                return
            pending.append((target, terms[-1]))
            for middle in terms[1:-1]:            # C_s(z) = C_m(z) = K + ...: each name of the chain
                other = definition_target(middle)
                if other is not None and other[0] not in self.bindings and other[0] != target[0]:
                    pending.append((other, terms[-1]))
        if not pending:
            reading.kind = OTHER
            return
        pending_all = list(pending)
        bound: list[str] = []
        notes: list[str] = []
        for _ in range(len(pending)):
            progress = False
            for item in list(pending):
                (name, variable), expr = item
                done, note = self._bind(reading, name, variable, expr, final=False)
                if done:
                    pending.remove(item)
                    bound.append(name)
                    progress = True
                    if note:
                        notes.append(note)
            if not progress:
                break
        for (name, variable), expr in pending:          # formulas over names no display binds
            done, note = self._bind(reading, name, variable, expr, final=True)
            if done:
                bound.append(name)
                if note:
                    notes.append(note)
        reading.environment = self._env(reading)
        if not bound:
            reading.kind = OTHER
            reading.note = "; ".join(notes)
            return
        # a derived name written through the paper's own bound names (G = c + W(z) h/(z-1)) is its
        # definition; one written out in the parameters alone is a result to verify
        composed = reading.derived and not _REFERENCE.search(reading.claim.sentence if reading.claim else "") and all(
            self._uses_bound(expr, bound) and not self._instance_of_bound(n) for (n, _v), expr in pending_all)
        reading.kind = DERIVED if reading.derived and not composed else DEFINITION
        reading.binds = tuple(bound)
        reading.note = "; ".join(notes)
        if reading.kind == DERIVED:
            self.tentative.update(bound)
        self.assumptions.extend(reading.assumptions)

    # -- signals, ports and what the model determines ------------------------------------------------

    def _signal_equations(self, reading: Reading, main: list[Any], prose: str, definitions_only: bool) -> bool:
        """Relations among signals: port descriptions (``[f_1; f_2] = \\mathbf{Z}(s)[v_1; v_2]``),
        a model (``Z_m v_m = f_h - k_f f_e``), port variables (``f_1 = f_h``) and terminations
        (``f_2 = -Z_e v_2``, kept apart): registered in :attr:`system`, the reading ``MODEL``."""
        from hapticproof.audit.definitions.signals import port_relation, signal_rows

        env = self._env(reading)
        ports = [port_relation(r) for r in main]
        if all(p is not None for p in ports) and ports:
            for p in ports:
                self.system.add_port(*p, source=reading.id)
                self.functions.add(_printed_of(p[0], self))
            reading.kind, reading.environment = MODEL, env
            reading.note = "defines " + ", ".join(f"{_public(p[0])} by {list(p[1])} = {_public(p[0])} {list(p[2])}" for p in ports)
            return True
        rows = []
        for relation in main:
            row = signal_rows(relation, env, self)
            if row is None:
                return False
            rows.append(row)
        terminal = bool(re.search(r"terminat", last_sentence(prose), re.I))
        for row, termination in rows:
            self.system.add_relation(row, termination=termination or terminal)
        reading.kind, reading.environment = MODEL, env
        reading.note = "a termination of a port" if all(t or terminal for _, t in rows) else "a model equation among signals"
        return True

    def _derivable(self, reading: Reading, main: list[Any]) -> None:
        """What the paper's own model or port relations say the left-hand name is (a port matrix,
        a generic entry of one): ``reading.expected``, compared by the identity's verdict."""
        from hapticproof.audit.definitions.signals import expected_value

        if len(main) != 1 or len(main[0].terms) != 2:
            return
        found = expected_value(main[0].terms[0], main[0].terms[1], self, self._env(reading))
        if found is not None:
            reading.expected, reading.expected_how = found
            target = definition_target(main[0].terms[0])
            if target is not None and target[0] not in self.bindings and self._mode == "identity":
                # a paper file's identity of a name the model determines binds the determined value
                name, variable = target
                value = found[0]
                if variable is None and value.kind == TRANSFER:
                    variable = "z" if value.domain == "discrete" else "s"
                self.bindings[name] = Binding(value, variable, reading.id)
                self.defined_at[name] = reading.id
                self.order.append(name)
                reading.binds = (name,)

    def _determined(self, reading: Reading, target: tuple[str, str | None], terms: list[Any]) -> bool:
        """A new name the paper's model or port relations determine (a port matrix "eliminating
        variables gives", a generic entry of a conversion, the transmitted impedance): an identity
        with the determined value, which is bound (verified) whatever the display prints."""
        from hapticproof.audit.definitions.signals import expected_value

        found = expected_value(terms[0], terms[1], self, self._env(reading))
        if found is None:
            return False
        value, how = found
        name, variable = target
        if variable is None and value.kind == TRANSFER:
            variable = "z" if value.domain == "discrete" else "s"
        reading.kind = IDENTITY
        reading.expected, reading.expected_how = value, how
        reading.environment = self._env(reading)
        self.bindings[name] = Binding(value, variable, reading.id)
        self.defined_at[name] = reading.id
        self.order.append(name)
        reading.binds = (name,)
        return True

    def _redefines(self, reading: Reading, target: tuple[str, str | None], expr: Any) -> bool:
        """A bound name defined again without a word that ties it to the first definition
        ("rewritten", "\\eqref", "i.e.", "recall"): a new definition from here on (a scaled case,
        another section's system) when it differs from the first; bound again, and ``REDEFINED``."""
        claim = reading.claim
        if self._mode != "redefine" and (claim is None or _REFERENCE.search(claim.sentence)):
            return False
        name, variable = target
        env = self._env(reading)
        try:
            value = evaluate(expr, env)
            old = self.bindings[name].value
            if (value - old).is_zero:
                return False                  # the same: an identity, confirmed as a restatement
        except (Unbound, Unsupported, ValueError, ZeroDivisionError):
            return False
        if variable is None and value.kind == TRANSFER:
            variable = "z" if value.domain == "discrete" else "s"
        previous = self.defined_at.get(name, "?")
        self.bindings[name] = Binding(value, variable, reading.id)
        self.defined_at[name] = reading.id
        reading.kind = REDEFINED
        reading.binds = (name,)
        reading.note = f"defined again, differently from ({previous}): read as a new definition from here on"
        reading.environment = env
        return True

    def _instance_of_bound(self, name: str) -> bool:
        """``eta_vc`` when ``eta`` is bound: a defined quantity for one object, a derived claim."""
        base = re.split(r"_", name, maxsplit=1)[0]
        return base != name and (base in self.bindings or base in self.formulas or "\\" + base in self.formulas)

    def _uses_bound(self, expr: Any, bound_here: list[str]) -> bool:
        """Whether an expression names a function or value an earlier display bound."""
        expr = sp.sympify(expr)
        names = {f.func.__name__ for f in expr.atoms(AppliedUndef)} if hasattr(expr, "atoms") else set()
        names |= {s.name for s in getattr(expr, "free_symbols", ())}
        return any(n in self.bindings and n not in bound_here for n in names)

    def _env(self, reading: Reading) -> Environment:
        return Environment(dict(self.bindings), angles=frozenset(_ANGLES), substitutions=reading.substitutions)

    def _bind(self, reading: Reading, name: str, variable: str | None, expr: Any, *, final: bool) -> tuple[bool, str]:
        env = self._env(reading)
        try:
            value = evaluate(expr, env)
        except (Unbound, Unsupported) as err:
            if not final:
                return False, ""
            if isinstance(err, Unbound):
                generic = ", ".join(sorted(err.names))
                note = f"{_public(name)} is a formula in {generic} (names no display binds)"
            else:
                note = f"{_public(name)} is a formula outside the exact algebra ({err})"
            self.formulas[name] = (expr, variable)
            self.defined_at[name] = reading.id
            return True, note
        except (ValueError, ZeroDivisionError) as err:
            return (False, "") if not final else (False, f"the definition of {_public(name)} does not evaluate: {err}")
        if variable is None and value.kind == TRANSFER:
            variable = "z" if value.domain == "discrete" else "s"
        self.bindings[name] = Binding(value, variable, reading.id)
        self.defined_at[name] = reading.id
        self.order.append(name)
        return True, ""

    def _prose_assumptions(self, prose: str) -> None:
        """Signs and ranges the prose states of single names (``$K \\ge 0$``, ``$b_1, b_2 > 0$``,
        ``$0 \\le a < 1$``): assumptions of the whole paper from there on; "sampling period $h$"
        names the period."""
        self._periods(prose=prose)
        for m in re.finditer(r"\$([^$]{1,400})\$", prose):
            math = m.group(1).strip()
            if not re.search(r"\\[lg]eq?\b|\\[lg]eqslant|[<>]", math) or re.search(r"\\omega|\\vartheta|\\theta|=\s*$", math):
                continue
            if _CLAIMED.search(prose[max(0, m.start() - 60):m.start()]):
                continue                      # "it reduces to $c_d \\ge 0$": a result, not an assumption
            for piece in _comma_list(math):
                try:
                    _, st = self._table(piece)
                except (LatexParseError, HapticproofError, ValueError):
                    continue
                for r in st.relations():
                    if _is_assumption(r):
                        expr = r.as_sympy()
                        if expr not in self.assumptions:
                            self.assumptions.append(expr)

    def _periods(self, text: str = "", prose: str = "") -> None:
        from hapticproof.audit.reader.names import normalise_name, sympy_name
        from hapticproof.audit.source.guess import period_names

        for printed in period_names(prose, text):
            try:
                self.periods.add(sympy_name(normalise_name(printed)))
            except (HapticproofError, ValueError):
                continue

    def _parameters_used(self) -> set[str]:
        out: set[str] = set()
        for b in self.bindings.values():
            out |= set(b.value.names)
        return out

    def _family(self, id: str, text: str, index: tuple[str, list[str]], claim: ProseClaim | None) -> Reading:
        r"""``G_\star^{-1}(z) = b + H(z) A_\star(z), \star \in \{f, b, t\}``: one display per member."""
        letter, members = index
        self.indices.add(letter)
        readings = []
        for member in members:
            instance = re.sub(r"(_\{?)" + re.escape(letter) + r"(\}?)", lambda m: m.group(1) + member + m.group(2), text)
            readings.append(self.read(f"{id}[{member}]", instance))
        self.readings = [r for r in self.readings if r not in readings]
        # the family's own names (G_\\star^{-1}) are functions of the paper too
        extra: set[str] = set()
        for member in members:
            for name in [n for n in list(self.functions) if f"_{{{member}}}" in n]:
                template = name.replace(f"_{{{member}}}", "_{" + letter + "}")
                self.functions.add(template)
                self.symbols.setdefault(template, sp.Symbol(_sympy_name(template), real=True))
                extra.add(template)
        for r in readings:
            if r.statement is not None:
                for relation in r.statement.relations():
                    for term in relation.terms:
                        extra |= {p for p in self.symbols if _sympy_name(p) in {getattr(a, "name", "") for a in getattr(term, "free_symbols", ())}}
                        extra |= {p for p in self.functions if _sympy_name(p) in {f.func.__name__ for f in getattr(term, "atoms", lambda *a: ())(AppliedUndef)}}
        kinds = {r.kind for r in readings}
        binds = tuple(n for r in readings for n in r.binds)
        reading = Reading(id, text, kinds.pop() if len(kinds) == 1 else OTHER, claim=claim, binds=binds,
                          environment=self.environment(), note=f"a family over {letter} in {{{', '.join(members)}}}")
        reading.main = tuple(m for r in readings for m in r.main)
        reading.extra_names = tuple(sorted(extra))
        self.readings.append(reading)
        return reading


# ---------------------------------------------------------------------------------------------


def _printed_of(name: str, paper: PaperReading) -> str:
    """The printed (canonical) name of a SymPy name the paper knows."""
    for printed in list(paper.symbols) + list(paper.functions):
        if _sympy_name(printed) == name:
            return printed
    return name


def _sympy_name(printed: str) -> str:
    from hapticproof.audit.reader.names import normalise_name, sympy_name

    return sympy_name(normalise_name(printed))


def _with_stated(claim: ProseClaim | None, stated: str) -> ProseClaim:
    """A claim with a paper file's stated assumption (``K_c > 0, b > 0``) among its assumptions."""
    from dataclasses import replace

    pieces = tuple(p.strip() for p in re.split(r";|\band\b", stated) if p.strip())
    base = claim or ProseClaim()
    return replace(base, assumptions=tuple(base.assumptions) + pieces)


def _plain_sentence(sentence: str) -> str:
    return re.sub(r"\$[^$]*\$", " ", sentence)


def _public(name: str) -> str:
    return name.replace("^-1", "^{-1}")


def _comma_list(text: str) -> list[str]:
    r"""``b_1, b_2 > 0`` as ``b_1 > 0`` and ``b_2 > 0``; anything else unchanged."""
    m = re.match(r"^\s*((?:[^,<>=]+,\s*)+[^,<>=]+?)\s*((?:\\[lg]eq?|[<>]=?|\\g?l?eqslant)\s*.+)$", text)
    if not m:
        return [text]
    names = [n.strip() for n in m.group(1).split(",")]
    if not all(re.fullmatch(r"\\?[A-Za-z]+(?:_\{?[A-Za-z0-9]+\}?)?", n) for n in names):
        return [text]
    return [f"{n} {m.group(2)}" for n in names]


def _lhs_text(text: str) -> str:
    """The left-hand side of a display's first equation (for a continued chain ``= ...``)."""
    depth = 0
    for k, ch in enumerate(text):
        depth += (ch == "{") - (ch == "}")
        if ch == "=" and depth == 0:
            return text[:k].strip().lstrip("&").strip()
    return ""


def _name_end(text: str) -> int:
    """The length of the printed name at the start of ``text`` (base and scripts)."""
    m = re.match(r"\\(?:mathbf|mathrm|boldsymbol|bm|mathcal|hat|bar|tilde)\s*\{[^{}]*\}|\\[A-Za-z]+|[A-Za-z]", text)
    k = m.end() if m else 1
    while k < len(text) and text[k] in "_^":
        k += 1
        if k < len(text) and text[k] == "{":
            depth = 0
            while k < len(text):
                depth += (text[k] == "{") - (text[k] == "}")
                k += 1
                if depth == 0:
                    break
        else:
            m = re.match(r"\\[A-Za-z]+|.", text[k:])
            k += m.end() if m else 1
    return k


def _applied(following: str) -> bool:
    r"""Whether a name is applied: followed by ``(z)``, ``(s)``, ``(e^{...})``, ``(j\omega)``,
    ``(\omega)`` or ``(z^{-1})``."""
    following = re.sub(r"^\\(?:left|bigl|Bigl|big|Big)\s*", "", following)
    return bool(re.match(r"\(\s*(?:(?:z|s|j\s*\\omega|\\omega|\\vartheta|\\theta|z\^\{?-1\}?|1/z|t|k)\s*\)|e\^)", following))


def _index_set(text: str) -> tuple[str, tuple[str, list[str]] | None]:
    if "\\in" not in text:
        return text, None                     # (the search is quadratic in a run of spaces: only where it can match)
    m = _INDEX_SET.search(re.sub(r"\s+", " ", text))
    text = re.sub(r"\s+", " ", text) if m else text
    if not m:
        return text, None
    members = [x.strip() for x in m.group(2).split(",") if x.strip()]
    if not members or not all(re.fullmatch(r"[A-Za-z0-9]+", x) for x in members):
        return text, None
    return text[:m.start()].rstrip(" ,"), (m.group(1), members)


def definition_target(term: Any) -> tuple[str, str | None] | None:
    """The name a left-hand side defines: ``F(z)``, ``F(s)`` (a function of that variable) or a
    bare name (a value)."""
    if isinstance(term, AppliedUndef) and len(term.args) == 1:
        arg = term.args[0]
        if arg == Z_SYM:
            return term.func.__name__, "z"
        if arg == S_SYM:
            return term.func.__name__, "s"
        if arg == OMEGA or getattr(arg, "name", None) in _ANGLES:
            return term.func.__name__, None
        return None
    if isinstance(term, sp.Symbol) and term not in (Z_SYM, S_SYM, OMEGA):
        return term.name, None
    return None


def _is_assumption(relation: Any) -> bool:
    """A sign or range assumption: a single parameter against numbers (``K \\ge 0``, ``0 \\le a < 1``)."""
    if not relation.ops or not all(op in _RELATION_OPS for op in relation.ops):
        return False
    symbols = [t for t in relation.terms if not sp.sympify(t).is_number]
    if not symbols:
        return False
    return all(isinstance(t, sp.Symbol) for t in symbols) and len(symbols) <= len(relation.terms) - 1


def _linear_assumption(relation: Any) -> bool:
    """A relation among parameters alone, such as ``g_0 + g_1 \\ge 0`` (no function, no frequency)."""
    if not relation.ops or not all(op in _RELATION_OPS for op in relation.ops):
        return False
    for t in relation.terms:
        t = sp.sympify(t)
        if isinstance(t, sp.MatrixBase) or t.atoms(AppliedUndef) or t.has(sp.cos, sp.sin, sp.exp, sp.re, sp.im, sp.Abs):
            return False
        if t.free_symbols & {OMEGA, Z_SYM, S_SYM}:
            return False
    return True


def _split(relations: list[Any]) -> tuple[list[Any], list[Any]]:
    """The main relations of a display and its trailing qualifiers."""
    main = [relations[0]]
    qualifiers = []
    first_equation = all(op == "=" for op in relations[0].ops)
    for r in relations[1:]:
        if first_equation and _linear_assumption(r):
            qualifiers.append(r)             # "H(z) = ..., \\quad g_0 + g_1 \\ge 0": an assumption
            continue
        expr = r.as_sympy() if hasattr(r, "as_sympy") else None
        free = getattr(expr, "free_symbols", set())
        if OMEGA in free and not any(isinstance(t, AppliedUndef) for t in r.terms) and all(
                not sp.sympify(t).has(sp.cos, sp.sin, sp.exp) for t in r.terms) and r.ops and all(op in _RELATION_OPS for op in r.ops):
            qualifiers.append(r)
        elif _is_assumption(r):
            qualifiers.append(r)
        elif r.ops == ("=",) and isinstance(r.terms[0], sp.Symbol) and not first_equation:
            qualifiers.append(r)
        elif r.ops == ("=",) and isinstance(r.terms[0], sp.Symbol) and first_equation and main and _uses(main[0], r.terms[0]):
            qualifiers.append(r)
        else:
            main.append(r)
    return main, qualifiers


def _uses(relation: Any, symbol: sp.Symbol) -> bool:
    return any(symbol in sp.sympify(t).free_symbols for t in relation.terms if not isinstance(t, sp.MatrixBase))
