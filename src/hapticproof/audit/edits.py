r"""The edits of a printed display: the mutants of mutation testing and the trials of the repair search.

The operators work on the tokens of :func:`hapticproof.audit.reader.lexer.tokenize` (equation numbers,
``\text{...}`` prose, scripts of ``\sum``/``\lim`` and environment names are left alone):

``sign``      flip the sign of one term (``+`` <-> ``-``, or ``-`` before a leading term);
``scale``     multiply one term by 2;
``drop``      delete one term of a sum of several;
``swap``      swap two indices of a subscript (``K_{01} -> K_{10}``, ``z_{i,j} -> z_{j,i}``,
              ``k_{pmxy} -> k_{pmyx}``), kept only if the new name is in the paper's table;
``relation``  reverse an inequality (``>`` <-> ``<``, ``\geq`` <-> ``\leq``);
``symbol``    replace a name by another name of the display (or of the paper's table).

The repair search (:mod:`hapticproof.audit.claims`) adds index slips (``index``) and a lost half
(``half``). A :class:`Mutant` says its edit the way a reviewer writes it (:meth:`Mutant.edit`:
``KT -> KT/2``); :mod:`hapticproof.audit.mutate` runs the mutants through the checks.

>>> import sympy as sp
>>> from hapticproof.audit.reader.printed import SymbolTable
>>> K, T, b = sp.symbols('K T b', positive=True)
>>> demo = Paper("demo", title="Demo", source="none", symbols=SymbolTable({"K": K, "T": T, "b": b}))
>>> demo.equation("1", kind="condition", printed=r"b > KT")(lambda ctx: None)  # doctest: +ELLIPSIS
<function <lambda> at ...>
>>> [m.edit() for m in generate(demo.get("1"), demo, slips=True) if m.operator == "half"]
['b -> b/2', 'KT -> KT/2']
"""

from __future__ import annotations

import hashlib
import re
from dataclasses import dataclass, field
from typing import Any

import sympy as sp

from hapticproof.audit.runner import Equation, Paper
from hapticproof.core.errors import LatexParseError
from hapticproof.core.limits import check_mutants

__all__ = ["OPERATORS", "REPAIR_OPERATORS", "Mutant", "Token", "generate", "half_latex", "halved", "is_relation", "resolves",
           "table_names"]

OPERATORS = ("sign", "scale", "drop", "swap", "relation", "symbol")
#: The edits a repair search tries: the operators, index slips (``K_{02}`` for ``K_{01}``: one
#: index of a name replaced so that it names another parameter of the scene) and a lost half
#: (``KT`` for ``KT/2``, the commonest slip of these papers).
REPAIR_OPERATORS = OPERATORS + ("index", "half", "modulus")

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
    #: the printed term an edit of a term changes (``(start, end)`` in the target's text, its sign
    #: not included; ``None`` for edits of a relation or a name)
    term: tuple[int, int] | None = None

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
        return f"{self.operator} at {self.position}{on}: {old!r} -> {new!r} ({self.edit()})"

    @property
    def source(self) -> str:
        """The target's printed text before the edit."""
        return self.printed[:self.position] + self.original + self.printed[self.position + len(self.replacement):]

    def edit(self) -> str:
        r"""The edit as a reviewer writes it: the term or name before and after (``KT -> KT/2``,
        ``+ B -> - B``, ``K_{01} -> K_{10}``, ``> -> <``), or the term dropped.

        >>> import sympy as sp
        >>> from hapticproof.audit.reader.printed import SymbolTable
        >>> K, T, B, b = sp.symbols('K T B b', positive=True)
        >>> p = Paper("p", title="", source="", symbols=SymbolTable({"K": K, "T": T, "B": B, "b": b}))
        >>> p.equation("1", kind="condition", printed=r"b > KT + \frac{B}{T}")(lambda ctx: None)  # doctest: +ELLIPSIS
        <function <lambda> at ...>
        >>> for m in generate(p.get("1"), p, slips=True):
        ...     if m.operator in ("half", "sign", "drop", "relation") and m.position > 0:
        ...         print(m.operator, m.edit())
        relation > -> <
        sign KT -> -KT
        drop dropping KT
        half KT -> KT/2
        sign + \frac{B}{T} -> - \frac{B}{T}
        drop dropping + \frac{B}{T}
        half \frac{B}{T} -> \frac{B}{2T}
        sign B -> -B
        half B -> B/2
        sign T -> -T
        half T -> T/2
        """
        if self.operator == "drop":
            return "dropping " + " ".join(self.original.split()).rstrip("+- ")
        if self.term is None:
            return f"{self.original.strip()} -> {self.replacement.strip()}"
        term = self.source[self.term[0]:self.term[1]].strip()
        if self.operator == "half":
            return f"{term} -> {halved(term)}"
        if self.operator == "scale":
            factor = "2 \\cdot " if "cdot" in self.replacement else "2"
            return f"{term} -> {factor}{term}"
        if self.original:           # a sign flipped
            return f"{self.original} {term} -> {self.replacement} {term}"
        return f"{term} -> -{term}"


def half_latex(term: str) -> str:
    r"""Half of a printed term in LaTeX, as an author writes it: ``\frac{KT}{2}``, ``\frac{B}{2T}``.

    >>> half_latex("KT"), half_latex(r"\frac{K}{T}"), half_latex(r"\frac{K}{T + a}")
    ('\\frac{KT}{2}', '\\frac{K}{2T}', '\\frac{K}{2(T + a)}')
    """
    match = re.fullmatch(r"\\frac\{([^{}]*)\}\{([^{}]*)\}", term)
    if match:
        below = match.group(2)
        below = f"({below})" if re.search(r"[+\-]", below) else below
        return rf"\frac{{{match.group(1)}}}{{2{below}}}"
    return rf"\frac{{{term}}}{{2}}"


def halved(term: str) -> str:
    r"""Half of a printed term, written as a reader would: ``KT/2``, ``\frac{B}{2T}``.

    >>> halved("KT"), halved(r"\frac{K}{T}"), halved(r"\frac{K}{T + a}"), halved("K + B")
    ('KT/2', '\\frac{K}{2T}', '\\frac{K}{2(T + a)}', '(K + B)/2')
    """
    if re.fullmatch(r"\\frac\{([^{}]*)\}\{([^{}]*)\}", term):
        return half_latex(term)
    return f"({term})/2" if re.search(r"[+\-]", term) else f"{term}/2"


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


def resolves(name: str, table: Any) -> Any:
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

    def add(operator: str, lo: int, hi: int, replacement: str, term: tuple[int, int] | None = None) -> None:
        if re.search(r"\\[A-Za-z]+$", replacement) and text[hi:hi + 1].isalnum():
            replacement += " "      # '\omega' before 'T' must not become '\omegaT'
        if not replacement and text[hi:hi + 1] == " " and (lo == 0 or text[lo - 1] in " {($&"):
            hi += 1                 # a dropped term leaves one space, not two
        check_mutants(len(found) + 1, len(text), f"{paper.id}:{equation.id}")   # each mutant is the whole display
        printed = text[:lo] + replacement + text[hi:]
        if printed == text or printed in found:
            return
        found[printed] = Mutant(paper.id, equation.id, equation.id, operator, lo, text[lo:hi], replacement, printed, term)

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
                span = (a.pos, z.end)
                if sign is not None:
                    st = body[segment[sign]]
                    add("sign", st.pos, st.end, "+" if st.value == "-" else "-", span)
                else:
                    add("sign", a.pos, a.pos, "-", span)
                factor = r"2\cdot " if a.kind == "number" else "2 "
                add("scale", a.pos, a.pos, factor, span)
                if slips:
                    # the term without the sentence's punctuation that ends a display ("... T).")
                    term = text[a.pos:z.end]
                    end = z.end - (len(term) - len(term.rstrip(" .,;")))
                    if end > a.pos:
                        add("half", a.pos, end, half_latex(text[a.pos:end]), span)
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
            meaning = resolves(name, table)
            if meaning is None:
                continue
            meanings.setdefault(name, meaning)
            spans.append((name_lo, name_hi, name, base, sub))
            if sub is not None:
                swapped = _swapped(sub)
                if swapped is not None:
                    new = f"{base}_{{{swapped}}}"
                    if resolves(new, table) is not None:
                        add("swap", name_lo, name_hi, new)
        distinct = {}
        for name, meaning in meanings.items():
            distinct.setdefault(str(meaning), name)
        for name_lo, name_hi, name, base, sub in spans:
            others = [n for m, n in sorted(distinct.items()) if m != str(meanings[name])]
            if not others:
                others = [n for n in table_names(table) if str(resolves(n, table)) != str(meanings[name])]
            if others:
                add("symbol", name_lo, name_hi, _choose(others, f"{paper.id}:{equation.id}:{name_lo}"))
            if slips and sub is not None:
                for new in _index_slips(base, sub, table):
                    add("index", name_lo, name_hi, new)
    if slips:
        # a modulus the derivation does not have: |g_1| -> g_1
        for m in re.finditer(r"\\left\s*\|([^|]{1,80})\\right\s*\||\\lvert([^|]{1,80})\\rvert|(?<!\\)\|([^|]{1,80})\|", text):
            inner = next(g for g in m.groups() if g is not None)
            add("modulus", m.start(), m.end(), inner.strip())
    return sorted(found.values(), key=lambda m: (m.position, REPAIR_OPERATORS.index(m.operator), m.replacement))


def _index_slips(base: str, sub: str, table: Any) -> list[str]:
    """Names of the table with the same base, a subscript differing in one index (``K_{02}``: ``K_{01}``);
    for a two-index entry any other entry of the same matrix (``z_{11}`` for ``z_{22}``)."""
    inner, out = sub.replace(" ", ""), []
    for key in table_names(table):
        match = re.fullmatch(re.escape(base) + r"_\{?([A-Za-z0-9]+)\}?", key)
        if not match or len(match.group(1)) != len(inner) or match.group(1) == inner:
            continue
        differ = sum(x != y for x, y in zip(match.group(1), inner))
        if differ == 1 or (len(inner) == 2 and inner.isdigit() and match.group(1).isdigit()):
            out.append(f"{base}_{{{match.group(1)}}}")
    return out


def table_names(table: Any) -> list[str]:
    names = []
    for key, value in getattr(table, "symbols", {}).items():
        if isinstance(value, sp.Symbol) and not isinstance(value, sp.MatrixSymbol):
            names.append(key)
    return sorted(names)
