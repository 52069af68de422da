r"""Mutation testing of the audit: does every check notice a changed display?

A check that returns the same verdict whatever the printed display says is a stub. This module
changes the printed LaTeX of every registered display at the token level, audits each *mutant*
through the same check function (a copy of the :class:`~hapticproof.audit.runner.Equation` with the
mutated ``printed``) and classifies the outcome:

``killed``
    the verdict, the detail or the corrected LaTeX changed (for a ``confirmed`` original: the
    verdict is no longer ``confirmed`` -- a changed display must not stay confirmed);
``equivalent``
    the mutant is proved to say the same thing: its parse with the paper's table is identical
    to the original's (e.g. ``K_{12} -> K_{21}`` of a symmetric family), or the check reports
    the same canonical form of what it read (``evidence.facts["printed_form"]``, e.g. gains
    identified by the paper's symmetry condition B);
``survived``
    the result did not change and no such proof exists (the check cannot tell the displays
    apart: a defect of the check);
``crashed``
    the check raised (a traceback is always a defect; a mutant that no longer parses must give
    ``malformed``).

The operators work on the tokens of :func:`hapticproof.audit.reader.lexer.tokenize` (equation numbers,
``\text{...}`` prose, scripts of ``\sum``/``\lim`` and environment names are left alone):

``sign``      flip the sign of one term (``+`` <-> ``-``, or ``-`` before a leading term);
``scale``     multiply one term by 2;
``drop``      delete one term of a sum of several;
``swap``      swap two indices of a subscript (``K_{01} -> K_{10}``, ``z_{i,j} -> z_{j,i}``,
              ``k_{pmxy} -> k_{pmyx}``), kept only if the new name is in the paper's table;
``relation``  reverse an inequality (``>`` <-> ``<``, ``\geq`` <-> ``\leq``);
``symbol``    replace a name by another name of the display (or of the paper's table).

Claims (quoted prose) are mutated inside their ``$...$`` math only, and only when their check
reads its own printed text (found by running the check once with recording copies of every
registered equation, :func:`dependencies`). A claim or display whose verdict is *about* other
displays declares them in ``Equation.quotes`` (``20-colgate`` quotes (20) and (3); the
cross-paper checks quote displays of three papers): it is audited against the mutants of those
displays too (``dependent`` mutants), with the mutated display installed in its paper for the
duration of the check. A declared quote that the check never reads is a :class:`QuoteError`.

What counts as *proved* equivalent is decided by the check, not by this module: a check that
proves a display equal to what it derives (``compare_expressions``, ``compare_bounds``,
``compare_sign_conditions``) reports the canonical form of what it read in
``evidence.facts["printed_form"]`` -- the derived form when it proved them equal, the printed
one otherwise -- so a mutant that stays confirmed with the same canonical form was proved equal
by the same exact computation. Data displays (a matrix of numbers whose stated properties are
all the paper uses) report the tuple of the properties they verified; a mutant that keeps every
stated property is equivalent *as data*. A claim that states a property of quoted values (the
terminations it names are passive) reports the proposition and its exact decisions; a mutant
naming other values with the same property is equivalent *as a claim* (it is proved true the
same way). Each equivalent mutant records its basis (:data:`EQUIVALENCE_BASES`) and the report
counts them separately (see ``benchmarks/README.md``).

A run generates every mutant (``count=None``) or a deterministic sample: equations are shuffled
with ``seed`` and take one mutant each per round, operators in turn, until ``count`` mutants are
chosen. Each mutant runs under a time limit (:data:`TIME_LIMIT`; a check that hangs is a crash).
The test suite runs :func:`knob` mutants per paper (``HAPTICPROOF_MUTANTS=all`` runs every one).

The mutation score of a paper is ``killed / (total - equivalent)``.

>>> from hapticproof.audit.runner import Paper, AuditContext
>>> from hapticproof.audit.compare import compare_bounds
>>> from hapticproof.core.evidence import Finding
>>> import sympy as sp
>>> from hapticproof.audit.reader.printed import SymbolTable
>>> K, T, b = sp.symbols('K T b', positive=True)
>>> demo = Paper("demo", title="Demo", source="none", symbols=SymbolTable({"K": K, "T": T, "b": b}))
>>> @demo.equation("1", kind="condition", printed=r"b > \frac{KT}{2}")
... def one(ctx):
...     return compare_bounds(ctx.relation(), sp.Ge(b, K*T/2), b)
>>> [m.replacement for m in generate(demo.get("1"), demo) if m.operator == "relation"]
['<']
>>> report = mutate_paper(demo)
>>> report.counts()["killed"] == report.total, report.score
(True, 1.0)
"""

from __future__ import annotations

import dataclasses
import hashlib
import itertools
import os
import random
import re
import time
import traceback
from collections.abc import Callable, Iterable, Iterator
from contextlib import contextmanager
from dataclasses import dataclass, field
from typing import Any

import sympy as sp

from hapticproof.audit.runner import AuditContext, Equation, Paper
from hapticproof.core.errors import LatexParseError
from hapticproof.core.evidence import Finding, Verdict, to_jsonable
from hapticproof.core.limits import check_mutants

__all__ = [
    "OPERATORS",
    "OUTCOMES",
    "Mutant",
    "MutantResult",
    "MutationReport",
    "generate",
    "dependencies",
    "mutants_of",
    "run_mutant",
    "mutate_paper",
    "choose",
    "knob",
    "EQUIVALENCE_BASES",
    "QuoteError",
    "MutantTimeout",
    "ENV_KNOB",
]

OPERATORS = ("sign", "scale", "drop", "swap", "relation", "symbol")
#: The edits a repair search tries: the operators, index slips (``K_{02}`` for ``K_{01}``: one
#: index of a name replaced so that it names another parameter of the scene) and a lost half
#: (``KT`` for ``KT/2``, the commonest slip of these papers).
REPAIR_OPERATORS = OPERATORS + ("index", "half")
OUTCOMES = ("killed", "equivalent", "survived", "crashed")
#: Environment variable: ``all`` runs every mutant in the test suite, a number N samples N per paper.
ENV_KNOB = "HAPTICPROOF_MUTANTS"

_REVERSED = {">": "<", "<": ">", r"\geq": r"\leq", r"\leq": r"\geq", r"\ge": r"\le", r"\le": r"\ge",
             r"\geqslant": r"\leqslant", r"\leqslant": r"\geqslant"}
OPENERS = {"{": "}", "(": ")", "[": "]"}
CLOSERS = {v: k for k, v in OPENERS.items()}
#: commands whose braced argument is not mathematics of the display (labels of arrows)
_LABEL_COMMANDS = {r"\xrightarrow", r"\xleftarrow", r"\overset", r"\underset", r"\stackrel"}
_SEGMENT_BREAKS = {",", "&", ";"}
#: letter runs that are words of the dialect, not products of names
PROSE_WORDS = {"det", "diag", "Re", "Im", "lim", "sup", "inf"}


# ---------------------------------------------------------------------------------------------
# mutants
# ---------------------------------------------------------------------------------------------


@dataclass(frozen=True, slots=True)
class Mutant:
    """One changed display.

    ``equation`` is the id of the audited equation, ``target`` the id of the equation whose
    printed text was changed (``paper:id`` when it belongs to another paper); they differ for
    dependent mutants. ``position`` is the character offset of the change in the target's text.
    """

    paper: str
    equation: str
    target: str
    operator: str
    position: int
    original: str
    replacement: str
    printed: str

    def __post_init__(self) -> None:
        if self.operator not in REPAIR_OPERATORS:
            raise ValueError(f"unknown mutation operator {self.operator!r}")

    @property
    def key(self) -> str:
        """A stable identifier (used for sampling and in reports)."""
        return f"{self.paper}:{self.equation}<-{self.target}@{self.position}:{self.operator}:{self.replacement}"

    def describe(self) -> str:
        old = self.original or "''"
        new = self.replacement or "''"
        on = "" if self.target == self.equation else f" (in {self.target})"
        return f"{self.operator} at {self.position}{on}: {old!r} -> {new!r}"


@dataclass(frozen=True, slots=True)
class Token:
    kind: str
    value: str
    pos: int
    end: int


def _tokens(text: str, lo: int, hi: int) -> list[Token]:
    from hapticproof.audit.reader.lexer import tokenize

    return [Token(t.kind, t.value, t.pos, t.end) for t in tokenize(text, lo, hi)]


def _tag_start(toks: list[Token]) -> int:
    """Index of the first token of a trailing equation number (``\\tag``, ``\\quad (15a)``, ``(48)``)."""
    end = len(toks)
    while end and toks[end - 1].kind in ("sep", "newline"):
        end -= 1
    for k, t in enumerate(toks):
        if t.kind == "tag":
            return k
    for width in (4, 3):
        if end >= width:
            o, *mid, c = toks[end - width:end]
            if o.value == "(" and c.value == ")" and mid[0].kind == "number" and (width == 3 or mid[1].kind == "letter"):
                before = toks[end - width - 1] if end > width else None
                if before is None or before.kind == "sep" or any(is_relation(t) for t in toks[:end - width]):
                    return end - width
    return end


def is_relation(t: Token) -> bool:
    from hapticproof.audit.reader.lexer import RELATIONS

    return (t.kind == "op" and t.value in "=<>") or (t.kind == "cmd" and t.value in RELATIONS)


@dataclass
class _Frame:
    kind: str            # 'top', 'group', 'script', 'label', 'bars'
    closer: str | None
    segments: list[list[int]] = field(default_factory=lambda: [[]])


def _structure(toks: list[Token]) -> list[list[int]]:
    """Segments of token indices (maximal runs of one sum, at every nesting depth, outside
    scripts and labels): split at relations, commas, ``&``, ``\\\\`` and separators."""
    out: list[list[int]] = []
    stack = [_Frame("top", None)]
    pending_script = False
    pending_label = False
    for k, t in enumerate(toks):
        frame = stack[-1]
        opener = t.value if (t.kind == "op" and t.value in OPENERS) else ("\\{" if (t.kind == "sym" and t.value == "\\{") else None)
        if t.kind == "left":
            opener = "left"
        if t.kind == "begin":
            opener = "begin"
        closer = (t.kind == "op" and t.value in CLOSERS) or (t.kind == "sym" and t.value == "\\}") or t.kind in ("right", "end")
        if t.kind == "op" and t.value == "|":
            if frame.kind == "bars":
                out.extend(s for s in frame.segments if s)
                stack.pop()
                stack[-1].segments[-1].append(k)
                continue
            stack[-1].segments[-1].append(k)
            stack.append(_Frame("bars", "|"))
            continue
        if opener is not None:
            kind = "script" if pending_script else "label" if pending_label else "group"
            if frame.kind not in ("script", "label"):
                frame.segments[-1].append(k)
            stack.append(_Frame(kind if frame.kind not in ("script", "label") else frame.kind, opener))
            pending_script = pending_label = False
            continue
        if closer and len(stack) > 1:
            done = stack.pop()
            if done.kind not in ("script", "label"):
                out.extend(s for s in done.segments if s)
            if stack[-1].kind not in ("script", "label"):
                stack[-1].segments[-1].append(k)
            continue
        pending_script = t.kind == "op" and t.value in "_^"
        pending_label = t.kind == "cmd" and t.value in _LABEL_COMMANDS
        if frame.kind in ("script", "label"):
            continue
        if pending_script:
            frame.segments[-1].append(k)
            continue
        if is_relation(t) or t.kind in ("sep", "newline", "text", "tag") or (t.kind == "op" and t.value in _SEGMENT_BREAKS) \
                or (t.kind == "cmd" and t.value in (r"\implies", r"\Longrightarrow", r"\Rightarrow", r"\iff", r"\to")):
            frame.segments.append([])
            continue
        frame.segments[-1].append(k)
    for frame in stack:
        if frame.kind not in ("script", "label"):
            out.extend(s for s in frame.segments if s)
    return out


def _script_after(toks: list[Token], k: int) -> int:
    """Index after the script group starting at ``toks[k]`` (``{...}`` or one token)."""
    if k >= len(toks):
        return k
    if toks[k].kind == "op" and toks[k].value == "{":
        depth = 0
        for j in range(k, len(toks)):
            if toks[j].kind == "op" and toks[j].value == "{":
                depth += 1
            elif toks[j].kind == "op" and toks[j].value == "}":
                depth -= 1
                if depth == 0:
                    return j + 1
        return len(toks)
    return k + 1


def _terms(toks: list[Token], segment: list[int]) -> list[tuple[int | None, int, int]]:
    """Terms of a segment: ``(sign token index or None, first index, last index)`` (positions in
    ``segment``), split at top-level ``+``/``-`` of the segment (the segment holds only its own
    level: inner groups are separate segments, but their delimiters belong to this one)."""
    terms: list[tuple[int | None, int, int]] = []
    depth = 0
    sign: int | None = None
    start: int | None = None
    # inner group tokens are not in the segment; delimiter tokens are, so count depth by them
    for pos, k in enumerate(segment):
        t = toks[k]
        is_open = (t.kind == "op" and t.value in OPENERS) or (t.kind == "sym" and t.value == "\\{") or t.kind in ("left", "begin")
        is_close = (t.kind == "op" and t.value in CLOSERS) or (t.kind == "sym" and t.value == "\\}") or t.kind in ("right", "end")
        if depth == 0 and t.kind == "op" and t.value in "+-":
            if start is not None:
                terms.append((sign, start, pos - 1))
            elif sign is not None:
                pass  # two signs in a row ('+ -'): keep the latter
            sign, start = pos, None
            continue
        if start is None:
            start = pos
        if is_open:
            depth += 1
        elif is_close:
            depth = max(0, depth - 1)
    if start is not None:
        terms.append((sign, start, len(segment) - 1))
    return terms


def _is_zero_term(toks: list[Token], segment: list[int], first: int, last: int) -> bool:
    return first == last and toks[segment[first]].kind == "number" and set(toks[segment[first]].value) <= {"0", "."}


def _math_ranges(text: str, claim: bool) -> list[tuple[int, int]]:
    """Where the mathematics is: the whole display, or the ``$...$`` parts of a claim."""
    if not claim:
        from hapticproof.audit.reader.printed import strip_math_delimiters

        lo, hi = strip_math_delimiters(text)
        return [(lo, hi)] if hi > lo else []
    return [(m.start(1), m.end(1)) for m in re.finditer(r"\$([^$]+)\$", text)]


def _choose(options: list[str], key: str) -> str:
    digest = int(hashlib.sha256(key.encode()).hexdigest()[:12], 16)
    return options[digest % len(options)]


def _resolves(name: str, table: Any) -> Any:
    """What a printed name means in ``table`` (None if it is not a known scalar name)."""
    from hapticproof.audit.reader.printed import parse_expression

    if table is None:
        return None
    try:
        value = parse_expression(name, table)
    except (LatexParseError, ValueError, TypeError):
        return None
    if isinstance(value, (sp.Symbol, sp.Indexed)) and not isinstance(value, sp.MatrixSymbol):
        return value
    return None


def _names(text: str, toks: list[Token], stop: int) -> list[tuple[int, int, str, str | None]]:
    """Candidate names ``(first token, index after, base text, subscript text or None)``: a letter,
    a Greek command or a decorated letter, with its subscript (superscripts are left alone)."""
    from hapticproof.audit.reader.lexer import DECORATIONS, GREEK

    out = []
    k = 0
    while k < stop:
        t = toks[k]
        start = k
        if t.kind == "op" and t.value in "_^":
            k = _script_after(toks, k + 1)     # scripts (indices, exponents, transposes) are left alone
            continue
        if t.kind == "letter":
            run = k
            while run + 1 < stop and toks[run + 1].kind == "letter" and toks[run + 1].pos == toks[run].end:
                run += 1
            word = "".join(x.value for x in toks[k:run + 1])
            if word in PROSE_WORDS:
                k = run + 1
                continue
            k += 1
        elif t.kind == "cmd" and t.value in GREEK:
            k += 1
        elif t.kind == "cmd" and t.value in DECORATIONS and k + 1 < stop:
            k = _script_after(toks, k + 1)
        else:
            k += 1
            continue
        while k < stop and toks[k].kind == "op" and toks[k].value == "'":
            k += 1
        sub = None
        if k + 1 < stop and toks[k].kind == "op" and toks[k].value == "_":
            after = _script_after(toks, k + 1)
            inner_lo = toks[k + 1].end if toks[k + 1].value == "{" else toks[k + 1].pos
            inner_hi = toks[after - 1].pos if toks[k + 1].value == "{" else toks[k + 1].end
            sub = text[inner_lo:inner_hi]
            k = after
        base_hi = toks[start].end if toks[start].kind != "cmd" or toks[start].value in GREEK else toks[_script_after(toks, start + 1) - 1].end
        out.append((start, k, text[toks[start].pos:base_hi], sub))
    return out


def _swapped(sub: str) -> str | None:
    """The subscript with two indices swapped, or None (``01 -> 10``, ``i,j -> j,i``, ``pmxy -> pmyx``)."""
    inner = sub.strip()
    if inner.count(",") == 1:
        a, b = (part.strip() for part in inner.split(","))
        return f"{b},{a}" if a != b and a and b else None
    compact = inner.replace(" ", "")
    if not compact.isalnum() or len(compact) < 2:
        return None
    a, b = compact[-2], compact[-1]
    if a == b:
        return None
    return compact[:-2] + b + a


def generate(equation: Equation, paper: Paper, *, text: str | None = None, table: Any = None,
             slips: bool = False) -> list[Mutant]:
    """All mutants of ``equation``'s printed text (or of ``text``), in printed order.

    Displays are mutated as a whole; claims only inside their ``$...$`` mathematics. ``table``
    reads the names (default: the paper's symbols); ``slips`` adds the index slips of
    :data:`REPAIR_OPERATORS` (for repair searches; mutation testing uses :data:`OPERATORS`).

    >>> import sympy as sp
    >>> from hapticproof.audit.reader.printed import SymbolTable
    >>> x, y = sp.symbols('x y')
    >>> p = Paper("p", title="", source="", symbols=SymbolTable({"x": x, "y": y}))
    >>> p.equation("1", kind="condition", printed="x + y > 0")(lambda ctx: None)  # doctest: +ELLIPSIS
    <function <lambda> at ...>
    >>> sorted({(m.operator, m.printed) for m in generate(p.get("1"), p)})  # doctest: +NORMALIZE_WHITESPACE
    [('drop', 'x > 0'), ('drop', 'y > 0'), ('relation', 'x + y < 0'), ('scale', '2 x + y > 0'),
     ('scale', 'x + 2 y > 0'), ('sign', '-x + y > 0'), ('sign', 'x - y > 0'), ('symbol', 'x + x > 0'),
     ('symbol', 'y + y > 0')]
    """
    text = equation.printed if text is None else text
    table = paper.symbols if table is None else table
    found: dict[str, Mutant] = {}

    def add(operator: str, lo: int, hi: int, replacement: str) -> None:
        if re.search(r"\\[A-Za-z]+$", replacement) and text[hi:hi + 1].isalnum():
            replacement += " "      # '\omega' before 'T' must not become '\omegaT'
        if not replacement and text[hi:hi + 1] == " " and (lo == 0 or text[lo - 1] in " {($&"):
            hi += 1                 # a dropped term leaves one space, not two
        check_mutants(len(found) + 1, len(text), f"{paper.id}:{equation.id}")   # each mutant is the whole display
        printed = text[:lo] + replacement + text[hi:]
        if printed == text or printed in found:
            return
        found[printed] = Mutant(paper.id, equation.id, equation.id, operator, lo, text[lo:hi], replacement, printed)

    for lo, hi in _math_ranges(text, equation.kind == "claim"):
        try:
            toks = _tokens(text, lo, hi)
        except LatexParseError:
            continue
        stop = _tag_start(toks)
        body = toks[:stop]
        # relations
        for t in body:
            if t.kind in ("op", "cmd") and t.value in _REVERSED:
                add("relation", t.pos, t.end, _REVERSED[t.value])
        # terms
        for segment in _structure(body):
            terms = _terms(body, segment)
            for sign, first, last in terms:
                if _is_zero_term(body, segment, first, last):
                    continue
                a, z = body[segment[first]], body[segment[last]]
                if sign is not None:
                    st = body[segment[sign]]
                    add("sign", st.pos, st.end, "+" if st.value == "-" else "-")
                else:
                    add("sign", a.pos, a.pos, "-")
                factor = r"2\cdot " if a.kind == "number" else "2 "
                add("scale", a.pos, a.pos, factor)
                if slips:
                    add("half", a.pos, a.pos, r"\frac{1}{2}")
                if len(terms) >= 2:
                    if sign is not None:
                        add("drop", body[segment[sign]].pos, z.end, "")
                    else:
                        nxt = terms[1] if terms[0][1] == first else None
                        if nxt is not None and nxt[0] is not None and body[segment[nxt[0]]].value == "+":
                            add("drop", a.pos, body[segment[nxt[0]]].end, "")
                        else:
                            add("drop", a.pos, z.end, "")
        # names: index swaps and replacements
        names = _names(text, body, len(body))
        meanings: dict[str, Any] = {}
        spans = []
        for first, after, base, sub in names:
            name_lo, name_hi = body[first].pos, body[after - 1].end
            name = text[name_lo:name_hi]
            meaning = _resolves(name, table)
            if meaning is None:
                continue
            meanings.setdefault(name, meaning)
            spans.append((name_lo, name_hi, name, base, sub))
            if sub is not None:
                swapped = _swapped(sub)
                if swapped is not None:
                    new = f"{base}_{{{swapped}}}"
                    if _resolves(new, table) is not None:
                        add("swap", name_lo, name_hi, new)
        distinct = {}
        for name, meaning in meanings.items():
            distinct.setdefault(str(meaning), name)
        for name_lo, name_hi, name, base, sub in spans:
            others = [n for m, n in sorted(distinct.items()) if m != str(meanings[name])]
            if not others:
                others = [n for n in _table_names(table) if str(_resolves(n, table)) != str(meanings[name])]
            if others:
                add("symbol", name_lo, name_hi, _choose(others, f"{paper.id}:{equation.id}:{name_lo}"))
            if slips and sub is not None:
                for new in _index_slips(base, sub, table):
                    add("index", name_lo, name_hi, new)
    return sorted(found.values(), key=lambda m: (m.position, REPAIR_OPERATORS.index(m.operator), m.replacement))


def _index_slips(base: str, sub: str, table: Any) -> list[str]:
    """Names of the table with the same base, a subscript differing in one index (``K_{02}``: ``K_{01}``)."""
    inner, out = sub.replace(" ", ""), []
    for key in _table_names(table):
        match = re.fullmatch(re.escape(base) + r"_\{?([A-Za-z0-9]+)\}?", key)
        if match and len(match.group(1)) == len(inner) and sum(x != y for x, y in zip(match.group(1), inner)) == 1:
            out.append(f"{base}_{{{match.group(1)}}}")
    return out


def _table_names(table: Any) -> list[str]:
    names = []
    for key, value in getattr(table, "symbols", {}).items():
        if isinstance(value, sp.Symbol) and not isinstance(value, sp.MatrixSymbol):
            names.append(key)
    return sorted(names)


# ---------------------------------------------------------------------------------------------
# which displays a check reads
# ---------------------------------------------------------------------------------------------


class _Reading(Equation):
    """An :class:`Equation` that records when its printed text is read."""

    def __getattribute__(self, name: str) -> Any:
        if name == "printed":
            _READ.add(object.__getattribute__(self, "_key"))
        return object.__getattribute__(self, name)


_READ: set[str] = set()


def _reading(paper: Paper, equation: Equation) -> _Reading:
    copy = _Reading(**{f.name: getattr(equation, f.name) for f in dataclasses.fields(Equation)})
    object.__setattr__(copy, "_key", f"{paper.id}:{equation.id}")
    return copy


def dependencies(paper: Paper, equation: Equation, registry: dict[str, Paper] | None = None) -> list[str]:
    """Displays (``paper:id``) whose printed text the check of ``equation`` reads, found by
    running it once with recording copies of every registered equation installed."""
    from hapticproof.audit.registry import papers as registered

    everything = dict(registry or registered())
    everything.setdefault(paper.id, paper)
    saved = {pid: dict(p.equations) for pid, p in everything.items()}
    _READ.clear()
    try:
        for p in everything.values():
            for eid, eq in list(p.equations.items()):
                p.equations[eid] = _reading(p, eq)
        own = paper.equations[equation.id]
        try:
            own.check(AuditContext(paper, own))
        except Exception:  # noqa: BLE001 - the reads before a failure still count
            pass
    finally:
        for pid, p in everything.items():
            p.equations.clear()
            p.equations.update(saved[pid])
    return sorted(_READ)


# ---------------------------------------------------------------------------------------------
# running mutants
# ---------------------------------------------------------------------------------------------


@dataclass(frozen=True, slots=True)
class MutantResult:
    """The audit of one mutant and its classification (one of :data:`OUTCOMES`)."""

    mutant: Mutant
    outcome: str
    verdict: str | None
    detail: str
    reason: str
    seconds: float
    basis: str = ""

    def to_json(self) -> dict[str, Any]:
        m = self.mutant
        return {"paper": m.paper, "equation": m.equation, "target": m.target, "operator": m.operator,
                "position": m.position, "original": m.original, "replacement": m.replacement,
                "outcome": self.outcome, "basis": self.basis, "verdict": self.verdict, "detail": self.detail,
                "reason": self.reason, "seconds": round(self.seconds, 4)}


#: How an equivalent mutant was proved equivalent (:attr:`MutantResult.basis`):
#: ``parse``  the mutant parses to the identical object with the paper's table (a declared
#:            symmetry such as K_{12} = K_{21}, or another spelling of the same mathematics);
#: ``form``   the check proved the mutated display equal to the same canonical form (e.g. the
#:            derived condition it confirms, a positive multiple, a renamed bound variable);
#: ``data``   a data display (a table of values) keeps every property the paper states and uses;
#: ``claim``  a claim (a proposition about quoted values or displays) is proved by the same
#:            exact decisions: it states the property of other values, and the property holds
#:            for them exactly as it does for the printed ones.
EQUIVALENCE_BASES = ("parse", "form", "data", "claim")


def _basis(form: str) -> str:
    if form.startswith("('data display"):
        return "data"
    if form.startswith("('claim:"):
        return "claim"
    return "form"


def _audit(paper: Paper, equation: Equation) -> Finding:
    """The finding of ``equation``'s check, as :func:`~hapticproof.audit.runner.run_equation` gets it
    (a parse error of the display becomes ``malformed``), without rendering the derived form."""
    from hapticproof.audit.runner import parse_failure

    try:
        return equation.check(AuditContext(paper, equation))
    except LatexParseError as err:
        return parse_failure(equation, err)


def _signature(obj: Any) -> Any:
    """A position-free normal form of a parse result (spans ignored)."""
    from hapticproof.audit.reader import statements as P

    if isinstance(obj, P.Expression):
        return ("expr", _signature(obj.expr), obj.label)
    if isinstance(obj, P.Relation):
        return ("rel", tuple(_signature(t) for t in obj.terms), obj.ops, obj.label)
    if isinstance(obj, P.Qualified):
        return ("qual", _signature(obj.body), tuple((r.indices, tuple(map(sp.srepr, r.values))) for r in obj.ranges),
                tuple(_signature(c) for c in obj.conditions), obj.label)
    if isinstance(obj, P.Lines):
        return ("lines", obj.kind, tuple(_signature(s) for s in obj.statements), obj.label)
    if isinstance(obj, sp.Basic):
        return sp.srepr(obj)
    return repr(obj)


def _parse_signature(text: str, paper: Paper) -> Any:
    from hapticproof.audit.reader.printed import parse_printed

    if paper.symbols is None:
        return None
    try:
        return _signature(parse_printed(text, paper.symbols))
    except Exception:  # noqa: BLE001 - a display that does not parse has no signature
        return None


def _printed_form(result: Any) -> Any:
    facts = result.evidence.facts or {}
    if "printed_form" not in facts:
        return None
    return repr(to_jsonable(facts["printed_form"]))


@contextmanager
def _installed(paper: Paper, equation: Equation) -> Iterator[None]:
    saved = paper.equations[equation.id]
    paper.equations[equation.id] = equation
    try:
        yield
    finally:
        paper.equations[equation.id] = saved


class MutantTimeout(Exception):
    """A check ran longer than the time limit on a mutant (counted as a crash)."""


@contextmanager
def _time_limit(seconds: float | None) -> Iterator[None]:
    import signal
    import threading

    if not seconds or threading.current_thread() is not threading.main_thread() or not hasattr(signal, "SIGPROF"):
        yield
        return

    def expire(signum: int, frame: Any) -> None:
        raise MutantTimeout(f"the check used more than {seconds:g} s of CPU time")

    # CPU time of this process (not wall time): a loaded machine must not turn slow checks into crashes
    previous = signal.signal(signal.SIGPROF, expire)
    signal.setitimer(signal.ITIMER_PROF, seconds)
    try:
        yield
    finally:
        signal.setitimer(signal.ITIMER_PROF, 0)
        signal.signal(signal.SIGPROF, previous)


#: CPU seconds a check may take on one mutant before it counts as a crash (a hanging check is a defect).
TIME_LIMIT = 120.0


def run_mutant(mutant: Mutant, original: Any, registry: dict[str, Paper] | None = None,
               limit: float | None = TIME_LIMIT) -> MutantResult:
    """Audit one mutant through the check of its equation and classify it against ``original``
    (the finding of the unmutated display)."""
    from hapticproof.audit.registry import get_paper

    lookup = dict(registry or {})

    def find(pid: str) -> Paper:
        return lookup[pid] if pid in lookup else get_paper(pid)

    paper = find(mutant.paper)
    equation = paper.get(mutant.equation)
    tpaper_id, _, tid = mutant.target.rpartition(":")
    target_paper = find(tpaper_id) if tpaper_id else paper
    target = target_paper.get(tid)
    mutated = dataclasses.replace(target, printed=mutant.printed)
    start = time.perf_counter()
    try:
        with _time_limit(limit), _installed(target_paper, mutated):
            result = _audit(paper, mutated if target is equation else equation)
    except Exception as err:  # noqa: BLE001 - a traceback is the finding
        seconds = time.perf_counter() - start
        tb = traceback.format_exception(type(err), err, err.__traceback__)
        return MutantResult(mutant, "crashed", None, f"{type(err).__name__}: {err}", "".join(tb[-4:]), seconds)
    seconds = time.perf_counter() - start
    verdict = result.verdict.value
    same = (result.verdict == original.verdict and result.detail == original.detail
            and result.corrected == original.corrected)
    if original.verdict == Verdict.CONFIRMED:
        unchanged = result.verdict == Verdict.CONFIRMED
    else:
        unchanged = same
    if not unchanged:
        return MutantResult(mutant, "killed", verdict, result.detail, "", seconds)
    if _parse_signature(mutant.printed, target_paper) is not None and \
            _parse_signature(mutant.printed, target_paper) == _parse_signature(target.printed, target_paper):
        return MutantResult(mutant, "equivalent", verdict, result.detail,
                            "identical parse with the paper's table (a declared symmetry or a canonical spelling)", seconds,
                            "parse")
    if mutant.operator in ("swap", "symbol") and _same_name(mutant, target_paper):
        return MutantResult(mutant, "equivalent", verdict, result.detail,
                            f"{mutant.replacement} and {mutant.original} name the same symbol in the paper's table "
                            "(a declared symmetry)", seconds, "parse")
    form, base = _printed_form(result), _printed_form(original)
    if form is not None and form == base:
        return MutantResult(mutant, "equivalent", verdict, result.detail,
                            f"the check reads the same canonical form: {form[:200]}", seconds, _basis(form))
    return MutantResult(mutant, "survived", verdict, result.detail, "same verdict, detail and correction", seconds)


def _same_name(mutant: Mutant, paper: Paper) -> bool:
    """The replaced name resolves to the very symbol it replaced (``K_{30}`` is ``K_{03}`` when the
    table declares the family symmetric): equivalent even where the whole display does not parse."""
    before, after = _resolves(mutant.original, paper.symbols), _resolves(mutant.replacement, paper.symbols)
    if before is not None and before == after:
        return True
    # letter indices (K_{0i} -> K_{i0}): the same symbol for every concrete index, 1..3 each
    split = re.fullmatch(r"(.+?_\{?)([^{}]*)(\}?)", mutant.original), re.fullmatch(r"(.+?_\{?)([^{}]*)(\}?)", mutant.replacement)
    if not all(split) or split[0].group(1) != split[1].group(1) or before is None or after is None:
        return False
    letters = sorted({ch for ch in split[0].group(2) if ch.isalpha()})
    if not letters or len(letters) > 3 or {ch for ch in split[1].group(2) if ch.isalpha()} != set(letters):
        return False
    for values in itertools.product("123", repeat=len(letters)):
        table = str.maketrans(dict(zip(letters, values)))
        a = _resolves(split[0].group(1) + split[0].group(2).translate(table) + split[0].group(3), paper.symbols)
        b = _resolves(split[1].group(1) + split[1].group(2).translate(table) + split[1].group(3), paper.symbols)
        if a is None or a != b:
            return False
    return True


class QuoteError(ValueError):
    """An equation declares that it quotes a display its check never reads."""


def _quote_key(paper: Paper, quote: str) -> str:
    return quote if ":" in quote else f"{paper.id}:{quote}"


def mutants_of(paper: Paper, equation: Equation, registry: dict[str, Paper] | None = None) -> list[Mutant]:
    """Own mutants of a display (or of a claim's quoted mathematics, when its check reads it)
    and dependent mutants of the displays it declares it quotes (``Equation.quotes``)."""
    from hapticproof.audit.registry import get_paper

    own_key = f"{paper.id}:{equation.id}"
    quoted = [_quote_key(paper, q) for q in equation.quotes]
    reads = dependencies(paper, equation, registry) if (equation.kind == "claim" or quoted) else [own_key]
    missing = [q for q in quoted if q not in reads]
    if missing:
        raise QuoteError(f"{own_key} declares it quotes {missing} but its check does not read them")
    out: list[Mutant] = []
    if equation.kind != "claim" or own_key in reads:
        out.extend(generate(equation, paper))
    for key in quoted:
        pid, _, eid = key.partition(":")
        other_paper = (registry or {}).get(pid) or (paper if pid == paper.id else get_paper(pid))
        other = other_paper.get(eid)
        target = eid if pid == paper.id else key
        for m in generate(other, other_paper):
            out.append(dataclasses.replace(m, paper=paper.id, equation=equation.id, target=target))
    return out


@dataclass(frozen=True)
class MutationReport:
    """The mutation run of one paper."""

    paper: str
    results: tuple[MutantResult, ...]
    seconds: float
    generated: int = 0

    @property
    def total(self) -> int:
        return len(self.results)

    def counts(self) -> dict[str, int]:
        out = {k: 0 for k in OUTCOMES}
        for r in self.results:
            out[r.outcome] += 1
        return out

    @property
    def score(self) -> float:
        """``killed / (total - equivalent)`` (1.0 when every mutant is equivalent)."""
        c = self.counts()
        denominator = self.total - c["equivalent"]
        return 1.0 if denominator == 0 else c["killed"] / denominator

    def equivalence(self) -> dict[str, int]:
        """Equivalent mutants by the basis of their proof (:data:`EQUIVALENCE_BASES`)."""
        out = {k: 0 for k in EQUIVALENCE_BASES}
        for r in self.results:
            if r.outcome == "equivalent":
                out[r.basis] = out.get(r.basis, 0) + 1
        return out

    def survivors(self) -> list[MutantResult]:
        return [r for r in self.results if r.outcome == "survived"]

    def crashes(self) -> list[MutantResult]:
        return [r for r in self.results if r.outcome == "crashed"]

    def summary(self) -> str:
        c = self.counts()
        basis = ", ".join(f"{k} {n}" for k, n in self.equivalence().items() if n)
        # a sample generates only the mutants of the equations it visits (see choose)
        pool = "every mutant" if self.total == self.generated else f"a sample of the {self.generated} generated for the equations it visits"
        return (f"{self.paper}: {self.total} mutants ({pool}), {c['equivalent']} proved equivalent"
                f"{f' ({basis})' if basis else ''}, "
                f"{c['killed']} killed, {c['survived']} survived, {c['crashed']} crashed; "
                f"score {100 * self.score:.1f}% ({self.seconds:.0f} s)")

    def to_text(self) -> str:
        lines = [self.summary()]
        for r in self.crashes():
            lines.append(f"  CRASH {r.mutant.equation}: {r.mutant.describe()}: {r.detail}")
        for r in self.survivors():
            lines.append(f"  SURVIVED {r.mutant.equation}: {r.mutant.describe()} -> {r.verdict}: {r.detail[:120]}")
        return "\n".join(lines)

    def to_json(self) -> dict[str, Any]:
        return {"paper": self.paper, "generated": self.generated, "total": self.total, "counts": self.counts(),
                "equivalence": self.equivalence(),
                "score": self.score, "seconds": round(self.seconds, 2), "results": [r.to_json() for r in self.results]}


def _run_group(job: tuple[str, str, list[Mutant]]) -> list[MutantResult]:
    """Run the mutants of one audited equation (in a worker process or in this one)."""
    from hapticproof.audit.registry import get_paper

    paper_id, eq_id, group = job
    paper = get_paper(paper_id)
    original = _audit(paper, paper.get(eq_id))
    return [run_mutant(m, original) for m in group]


def choose(
    paper: Paper,
    only: Iterable[str] | None = None,
    *,
    count: int | None = None,
    seed: int = 0,
    registry: dict[str, Paper] | None = None,
) -> tuple[list[Mutant], int]:
    """The mutants a run audits and how many were generated: every mutant of ``paper`` (or of
    the equations ``only``) when ``count`` is None, else a deterministic sample of ``count``:
    the equations that read a display are shuffled with ``seed`` and give one mutant each per
    round, operators in turn, so that a small sample spreads over the paper without generating
    every mutant."""
    equations = [paper.get(i) for i in only] if only else paper.ordered()
    everything: list[Mutant] = []
    if count is None:
        for eq in equations:
            everything.extend(mutants_of(paper, eq, registry))
        return everything, len(everything)
    rng = random.Random(seed)
    candidates = [eq for eq in equations if eq.kind != "claim" or "$" in eq.printed or eq.quotes]
    rng.shuffle(candidates)
    pools: dict[str, list[Mutant]] = {}
    chosen: list[Mutant] = []
    for rounds in range(len(OPERATORS)):
        for k, eq in enumerate(candidates):
            if len(chosen) >= count:
                break
            if eq.id not in pools:
                pools[eq.id] = mutants_of(paper, eq, registry)
                everything.extend(pools[eq.id])
            pool = [m for m in pools[eq.id] if m not in chosen]
            if not pool:
                continue
            wanted = OPERATORS[(k + rounds) % len(OPERATORS)]
            preferred = [m for m in pool if m.operator == wanted] or pool
            chosen.append(preferred[rng.randrange(len(preferred))])
        if len(chosen) >= count:
            break
    return chosen, len(everything)


def mutate_paper(
    paper: Paper,
    only: Iterable[str] | None = None,
    *,
    count: int | None = None,
    seed: int = 0,
    registry: dict[str, Paper] | None = None,
    progress: Callable[[MutantResult], None] | None = None,
    jobs: int = 1,
) -> MutationReport:
    """Generate, sample (:func:`choose`) and run the mutants of ``paper`` (or of the equations
    ``only``); ``jobs > 1`` runs the equations' groups of mutants in that many worker processes
    (registered papers only).
    """
    from hapticproof.audit.registry import papers as registered

    start = time.perf_counter()
    if registry is None and registered().get(paper.id) is not paper:
        registry = {paper.id: paper}          # a paper of one's own, not in the registry
    chosen, generated = choose(paper, only, count=count, seed=seed, registry=registry)
    groups: dict[str, list[Mutant]] = {}
    for m in sorted(chosen, key=lambda m: (m.equation, m.target, m.position, m.operator, m.replacement)):
        groups.setdefault(m.equation, []).append(m)
    results: list[MutantResult] = []
    if jobs > 1 and len(groups) > 1 and registry is None:
        import multiprocessing
        from concurrent.futures import ProcessPoolExecutor

        order = sorted(groups, key=lambda e: -len(groups[e]))
        import os

        from hapticproof.core.processes import die_with_parent

        with ProcessPoolExecutor(jobs, mp_context=multiprocessing.get_context("fork"), initializer=die_with_parent,
                                 initargs=(os.getpid(),)) as pool:
            for batch in pool.map(_run_group, [(paper.id, e, groups[e]) for e in order]):
                for r in batch:
                    results.append(r)
                    if progress is not None:
                        progress(r)
    else:
        for eq_id, group in groups.items():
            original = _audit(paper, paper.get(eq_id))
            for m in group:
                r = run_mutant(m, original, registry)
                results.append(r)
                if progress is not None:
                    progress(r)
    results.sort(key=lambda r: (r.mutant.equation, r.mutant.target, r.mutant.position, r.mutant.operator))
    return MutationReport(paper.id, tuple(results), time.perf_counter() - start, generated)


def knob() -> int | None:
    """The sample size per paper the test suite uses: ``HAPTICPROOF_MUTANTS=all`` (every mutant)
    or a number; default 12."""
    value = os.environ.get(ENV_KNOB, "").strip().lower()
    if value == "all":
        return None
    return int(value) if value.isdigit() else 12
