r"""Read the displayed equations of a paper's source: LaTeX or a text/Markdown transcription.

This is the reading half of ``hapticproof new-paper --from SOURCE``. ``SOURCE`` is

* a LaTeX file (``.tex``), or a folder holding the main file and the files it ``\input`` s;
* a text or Markdown transcription (``.txt``, ``.md``) whose displays are ``$$...$$`` (or
  ``\[...\]`` and the LaTeX environments), as the bundled papers' transcriptions are.

:func:`read_source` returns a :class:`Source` whose ``displays`` are :class:`Display` objects:
the display's LaTeX after macro expansion (``text``), the source exactly as written
(``original``), its ``\label``, ``\tag``, printed ``number``, :class:`Section`, line, file and
environment.

LaTeX
    Definitions are expanded where they are used: ``\newcommand``, ``\renewcommand``,
    ``\providecommand``, ``\DeclareRobustCommand`` (parameters ``#1..#9``, an optional first
    argument with its default), ``\def``/``\gdef``/``\edef`` (undelimited or delimited
    parameter text), ``\let``, ``\DeclareMathOperator`` (``\operatorname{...}``) and
    ``\newenvironment``. Expansion is bounded (:data:`MAX_EXPANSION_DEPTH` levels, a token
    budget linear in the source size), so a recursive definition is one error line, not a hang.
    Comments (``%``, not ``\%``), ``\iffalse...\fi``, ``verbatim`` and ``comment`` blocks are
    skipped; reading stops at ``\end{document}``.
Files
    ``\input{x}`` and ``\include{x}`` are read relative to the main file's folder only: an
    absolute name, ``..``, a link leading outside the folder, anything but a regular file, and a
    file over the byte budget are refused with one line that names the request, never the
    content of what was refused. ``.tex`` is appended when the name has no ``.tex``.
    A file that is not UTF-8 (or is UTF-16/32) is one error line; a UTF-8 byte-order mark is
    dropped. Braces (and environments) nested deeper than :data:`MAX_NESTING` are refused.
Displays
    ``equation``, ``align``, ``alignat``, ``flalign``, ``eqnarray``, ``gather``, ``multline``,
    ``displaymath``, ``dmath`` (starred or not), ``\[...\]`` and ``$$...$$``.
    Multi-line environments: in ``align``/``alignat``/``flalign``/``eqnarray``/``gather`` each
    *numbered* row (with its own number, ``\tag`` or ``\label``) is one display, and the
    unnumbered rows (``\nonumber``, ``\notag``, starred environments) join the display of the
    next numbered row (or of the last one), since they continue it: ``a &= b \nonumber \\ &=
    c`` is one display. A one-row display drops the alignment ``&``; several rows are kept as
    ``\begin{aligned}...\end{aligned}`` (``gathered`` for ``gather``). ``multline`` and an
    ``equation`` holding ``split``/``aligned`` are one display.
Numbers
    ``\tag{..}`` (or ``\eqno``) gives the number; otherwise the automatic counter, which numbered
    environments advance and starred ones, ``\nonumber`` and ``\notag`` do not, with
    ``\numberwithin{equation}{section}`` and ``subequations`` (``3a``, ``3b``).
Sections
    ``\section``/``\subsection``/``\subsubsection`` (and ``\chapter``) with their counters,
    ``\appendix`` (A, B, ...); starred ones are unnumbered.
Transcriptions (text mode)
    ``%`` is text, not a comment, and there is no ``\input``. A display's number is a trailing
    ``\tag{17}``, ``\quad (17)`` or `` (17)``, or a line right after it holding only ``(17)``,
    ``$$(17)$$`` or ``⁽¹⁷⁾`` (OCR puts them there). OCR repairs, each noted on the display: a
    ``$$`` never closed ends at the paragraph break (TeX would stop there too); a display ending
    in ``=`` or another operator continues into the next display (joined by a line break); a
    display starting with a relation (``=``, ``\implies``...) right under an unnumbered one is
    its next row (joined by ``\\``). Headings: Markdown ``#`` lines, numbered lines such as
    ``3.1 Title`` or ``1. INTRODUCTION`` (accepted only as the next section number), ``III.
    TITLE`` with ``A. Title`` below it (section ``III-A``), and ``ABSTRACT``/``APPENDIX``/
    ``REFERENCES``; a heading stands alone between blank lines.

Every mistake is a :class:`SourceError`: one line, ``file:line: reason``. Files, tokens and
macro expansion live in :mod:`hapticproof.audit.source.tex`; the claim and symbol guesses in :mod:`hapticproof.audit.source.guess`.

The entry points are :func:`hapticproof.audit.source.read.read_source` and
:func:`~hapticproof.audit.source.read.read_text`; the text mode is :mod:`hapticproof.audit.source.transcript`.
"""

from __future__ import annotations

import re
from dataclasses import dataclass, field

from hapticproof.audit.source.tex import (BG, CH, CS, EG, MAX_BYTES, MAX_EXPANSION_DEPTH, MAX_FILES, MAX_NESTING, SP,
                                          Expander, Files, SourceError, is_par, serialize, shown, tokenize)

__all__ = ["MAX_BYTES", "MAX_FILES", "MAX_NESTING", "MAX_EXPANSION_DEPTH", "SourceError", "Section", "Display",
           "Source", "Reader", "LatexReader", "replace_display", "DISPLAY_ENVS", "PARAGRAPH", "LATEX_SUFFIXES",
           "TEXT_SUFFIXES"]

_ROW_ENVS = frozenset({"align", "alignat", "flalign", "xalignat", "eqnarray", "gather"})
DISPLAY_ENVS = _ROW_ENVS | {"equation", "multline", "displaymath", "dmath"}
LATEX_SUFFIXES = (".tex", ".ltx", ".latex")
TEXT_SUFFIXES = (".txt", ".md", ".markdown", ".text", ".mmd")
_SECTION_LEVELS = {"\\chapter": 0, "\\section": 1, "\\subsection": 2, "\\subsubsection": 3}
PARAGRAPH = re.compile(r"\n[ \t]*\n")



@dataclass(frozen=True)
class Section:
    """A heading: ``number`` as printed (``"3.1.1"``, ``"III-A"``, ``""`` when unnumbered).

    ``id`` is the number, or the title of an unnumbered heading (``"Appendix"``).
    """

    number: str
    title: str
    level: int
    line: int
    file: str

    @property
    def id(self) -> str:
        return self.number or self.title


@dataclass(frozen=True)
class Display:
    r"""One displayed equation.

    ``text`` is the display's LaTeX after macro expansion, without its ``\label``, ``\tag``
    and printed number; ``original`` is the source between the delimiters exactly as written
    (for one row of a multi-row environment: that row's source). ``number`` is the equation
    number as printed (the tag, else the automatic counter; in a transcription the number it
    shows), ``None`` for an unnumbered display. ``row`` is the display's index among the
    displays of its environment (``None`` when the environment is one display); ``context`` is
    the prose just before it; ``notes`` record repairs and doubts (an unclosed ``$$``, a join).
    """

    text: str
    original: str
    label: str | None
    tag: str | None
    number: str | None
    section: Section | None
    line: int
    end_line: int
    environment: str
    file: str
    row: int | None = None
    context: str = ""
    notes: tuple[str, ...] = ()
    #: the prose since the display before, inline maths kept between ``$`` (for the claims a
    #: sentence makes and the definitions inline maths states)
    prose: str = ""

    @property
    def id(self) -> str:
        """A paper-file id: the tag, else the number, else the label (``:`` becomes ``-``,
        since ``paper:id`` is a same-as reference), else ``line-N``."""
        if self.tag:
            return self.tag
        if self.number:
            return self.number
        if self.label:
            return self.label.replace(":", "-")
        return f"line-{self.line}"


@dataclass
class Source:
    """What :func:`read_source` read: ``mode`` is ``"latex"`` or ``"text"``; ``macros`` maps
    each defined name to its parameter count; ``warnings`` are ``file:line: ...`` lines."""

    path: str
    mode: str
    displays: list[Display]
    sections: list[Section]
    files: list[str]
    macros: dict[str, int] = field(default_factory=dict)
    warnings: list[str] = field(default_factory=list)


# ---------------------------------------------------------------------------------------------
# one display body -> displays
# ---------------------------------------------------------------------------------------------

_NUMBER_INSIDE = re.compile(r"\s*(\d{1,3}[a-z]?)\s*")
_SEPARATORS = ("\\qquad", "\\quad", "\\,", "\\;", "\\:", "\\!", "\\ ", "~")


def trailing_number(text: str, commands: bool = True) -> tuple[int, str] | None:
    r"""A display's own number written at its end, ``... \quad (12).``: where the number and the
    space before it start, and the number; ``None`` when the text does not end so. Linear in
    the text (string operations, no back-tracking regular expression: a display may hold a
    40 KB run of spaces). ``commands=False`` accepts only spaces and ``\quad`` before it.

    >>> trailing_number(r"b > 0 \quad (12).")
    (5, '12')
    >>> trailing_number("b > 0 " + " " * 40000 + "x") is None
    True
    """
    end = len(text)
    while end and (text[end - 1].isspace() or text[end - 1] in ".,"):
        end -= 1
    if not end or text[end - 1] != ")":
        return None
    opening = text.rfind("(", 0, end - 1)
    if opening < 0:
        return None
    inside = _NUMBER_INSIDE.fullmatch(text, opening + 1, end - 1)
    if inside is None:
        return None
    start = opening
    separators = _SEPARATORS if commands else ("\\qquad", "\\quad")
    while start:
        if text[start - 1].isspace():
            start -= 1
            continue
        for separator in separators:
            if text.endswith(separator, 0, start):
                start -= len(separator)
                break
        else:
            break
    if start == opening and start != 0:
        return None                          # no space before the number: part of the display
    return start, inside.group(1)


@dataclass
class _Row:
    tokens: list
    label: str | None = None
    tag: str | None = None
    unnumbered: bool = False
    notes: list = field(default_factory=list)


def _nesting(tok: tuple, depth: int, env: int) -> tuple[int, int]:
    """Brace depth and environment depth after ``tok`` (a top-level ``\\\\`` or ``&`` is one at 0, 0)."""
    if tok[0] == BG:
        return depth + 1, env
    if tok[0] == EG:
        return depth - 1, env
    if tok[0] == CS and tok[1] in ("\\begin", "\\end"):
        return depth, env + (1 if tok[1] == "\\begin" else -1)
    return depth, env


def _split_rows(tokens: list, rows: bool) -> list[list]:
    r"""Rows at top-level ``\\`` (outside braces and inner environments), for row environments."""
    if not rows:
        return [tokens]
    out: list[list] = [[]]
    depth = env = 0
    k = 0
    while k < len(tokens):
        tok = tokens[k]
        depth, env = _nesting(tok, depth, env)
        if tok[0] == CS and tok[1] == "\\\\" and depth == 0 and env == 0:
            out.append([])
            k += 1
            if k < len(tokens) and tokens[k][0] == CH and tokens[k][1] == "*":
                k += 1
            if k < len(tokens) and tokens[k][0] == CH and tokens[k][1] == "[":
                while k < len(tokens) and not (tokens[k][0] == CH and tokens[k][1] == "]"):
                    k += 1
                k += 1
            continue
        out[-1].append(tok)
        k += 1
    return out


def _braced(tokens: list, k: int) -> tuple[list, int] | None:
    """The group starting at ``tokens[k]`` (spaces skipped): its content and the index after it."""
    while k < len(tokens) and tokens[k][0] == SP:
        k += 1
    if k >= len(tokens) or tokens[k][0] != BG:
        return None
    depth = 0
    for j in range(k, len(tokens)):
        depth += (tokens[j][0] == BG) - (tokens[j][0] == EG)
        if depth == 0:
            return tokens[k + 1:j], j + 1
    return None


def _markers(tokens: list) -> _Row:
    r"""A row without its ``\label``, ``\tag``, ``\nonumber``/``\notag`` and ``\eqno``."""
    row = _Row([])
    k = 0
    while k < len(tokens):
        tok = tokens[k]
        if tok[0] == CS and tok[1] in ("\\label", "\\tag"):
            j = k + 1
            if tok[1] == "\\tag" and j < len(tokens) and tokens[j][0] == CH and tokens[j][1] == "*":
                j += 1
            got = _braced(tokens, j)
            if got is not None:
                value = serialize(got[0]).strip()
                if tok[1] == "\\label":
                    row.label = row.label or value
                elif row.tag is None:
                    row.tag = value
                else:
                    row.notes.append(f"a second \\tag{{{shown(value)}}} is ignored")
                k = got[1]
                continue
        if tok[0] == CS and tok[1] in ("\\nonumber", "\\notag"):
            row.unnumbered = True
            k += 1
            continue
        if tok[0] == CS and tok[1] in ("\\eqno", "\\leqno"):
            row.tag = serialize(tokens[k + 1:]).strip().strip("()") or row.tag
            break
        row.tokens.append(tok)
        k += 1
    return row


def _without_ampersands(tokens: list, keep_first: bool = False) -> list:
    out, depth, env, seen = [], 0, 0, False
    for tok in tokens:
        depth, env = _nesting(tok, depth, env)
        if tok[0] == CH and tok[1] == "&" and depth == 0 and env == 0:
            if keep_first and not seen:
                seen = True
                out.append(tok)
            continue
        out.append(tok)
    return out


def _strip_spaces(tokens: list) -> list:
    lo, hi = 0, len(tokens)
    while lo < hi and tokens[lo][0] == SP:
        lo += 1
    while hi > lo and tokens[hi - 1][0] == SP:
        hi -= 1
    return tokens[lo:hi]


# ---------------------------------------------------------------------------------------------
# the reader
# ---------------------------------------------------------------------------------------------


class Reader:
    """Display and section recognition shared by the LaTeX and text modes."""

    def __init__(self, files: Files, mode: str):
        self.files, self.mode = files, mode
        self.warnings: list[str] = []
        self.displays: list[Display] = []
        self.sections: list[Section] = []
        self.section: Section | None = None
        self.counters = [0, 0, 0, 0]          # chapter, section, subsection, subsubsection
        self.chapters = False
        self.appendix = False
        self.equation = 0
        self.within: int | None = None        # \numberwithin{equation}{...}: the level
        self.sub: tuple[str, int] | None = None   # subequations: (parent number, count)
        self.last_prose = ""                  # the prose before the display being emitted

    # -- numbering ----------------------------------------------------------------------------
    def section_number(self, level: int) -> str:
        top = 0 if self.chapters else 1
        parts = []
        for lvl in range(top, level + 1):
            value = self.counters[lvl]
            parts.append(chr(64 + value) if (self.appendix and lvl == top and 0 < value <= 26) else str(value))
        return ".".join(parts)

    def open_section(self, level: int, title: str, starred: bool, file: int, offset: int) -> None:
        if level == 0:
            self.chapters = True
        if starred:
            number = ""
        else:
            self.counters[level] += 1
            for deeper in range(level + 1, 4):
                self.counters[deeper] = 0
            number = self.section_number(level)
            if self.within is not None and level <= self.within:
                self.equation = 0
        self.section = Section(number, " ".join(title.split()), level, self.files.line(file, offset),
                               self.files.names[file])
        self.sections.append(self.section)

    def next_number(self) -> str:
        if self.sub is not None:
            parent, count = self.sub
            self.sub = (parent, count + 1)
            return parent + chr(97 + count % 26)
        self.equation += 1
        if self.within is not None:
            return f"{self.section_number(self.within)}.{self.equation}"
        return str(self.equation)

    # -- displays -----------------------------------------------------------------------------
    def emit(self, body: list, env: str, start: tuple[int, int], end: tuple[int, int], context: str,
             notes: list[str]) -> None:
        """Turn one display's expanded tokens into :class:`Display` objects."""
        base = env.rstrip("*")
        starred = env.endswith("*") or env in ("$$", "\\[", "displaymath")
        if base == "alignat":                 # \begin{alignat}{2}: the column count is no content
            got = _braced(body, 0)
            if got is not None:
                body = body[got[1]:]
        file = start[0]
        text = self.files.texts[file]
        rows = [_markers(r) for r in _split_rows(body, base in _ROW_ENVS)]
        while len(rows) > 1 and not _strip_spaces(rows[-1].tokens) and not rows[-1].label and not rows[-1].tag:
            rows.pop()                        # a final \\ makes an empty last row
        numbered_env = not starred and self.mode == "latex"
        groups: list[list[_Row]] = []
        pending: list[_Row] = []
        for row in rows:
            pending.append(row)
            carries = row.tag is not None or row.label is not None or (numbered_env and not row.unnumbered)
            if carries or base not in _ROW_ENVS:
                groups.append(pending)
                pending = []
        if pending:
            if groups and base in _ROW_ENVS:
                groups[-1].extend(pending)
            else:
                groups.append(pending)
        raw_spans = self.raw_spans(groups, start, end) if len(groups) > 1 else None
        for index, group in enumerate(groups):
            tag = next((r.tag for r in group if r.tag is not None), None)
            label = next((r.label for r in group if r.label is not None), None)
            unnumbered = all(r.unnumbered for r in group) if numbered_env else True
            group_notes = list(notes) + [n for r in group for n in r.notes]
            if base in _ROW_ENVS and len(group) > 1:
                inner = "gathered" if base == "gather" else "aligned"
                parts = [serialize(_strip_spaces(_without_ampersands(r.tokens, keep_first=True)
                                                  if base == "eqnarray" else r.tokens)) for r in group]
                content = "\\begin{" + inner + "} " + " \\\\ ".join(p for p in parts) + " \\end{" + inner + "}"
            elif base in _ROW_ENVS:
                content = serialize(_strip_spaces(_without_ampersands(group[0].tokens)))
            else:
                content = serialize(_strip_spaces(group[0].tokens))
            number = tag
            if number is None and self.mode == "text":
                found = trailing_number(content)
                if found:
                    number = found[1]
                    content = content[:found[0]].rstrip()
            if number is None and numbered_env and not unnumbered:
                number = self.next_number()
            if not content.strip():
                if number is not None and self.mode == "text" and self.displays and self.displays[-1].number is None:
                    last = self.displays[-1]           # a display holding only "(36)": the number of the one before
                    self.displays[-1] = replace_display(last, number=number, notes=last.notes + (f"number ({number}) from the "
                                                                                          f"display at line {self.files.line(*start)}",))
                elif number is not None or label is not None:
                    self.warnings.append(f"{self.files.where(*start)}: a display holding only its number or label; skipped")
                continue
            if len(groups) == 1:
                original = text[start[1]:end[1]].strip()
                line, last_line = self.files.line(*start), self.files.line(*end)
            else:
                lo, hi = raw_spans[index] if raw_spans else self.approximate_span(group, start, end)
                original = text[lo:hi].strip()
                line, last_line = self.files.line(file, lo), self.files.line(file, hi)
            self.displays.append(Display(content.strip(), original, label, tag, number, self.section, line, last_line,
                                         env, self.files.names[file], index if len(groups) > 1 else None, context,
                                         tuple(group_notes), self.last_prose))


    def raw_spans(self, groups: list[list[_Row]], start: tuple[int, int], end: tuple[int, int]) -> list | None:
        """Source spans of the groups of a multi-row environment, from its unexpanded rows (None
        when macros changed the row count)."""
        if start[0] != end[0]:
            return None
        raw = tokenize(self.files.texts[start[0]], start[0], self.files, latex=self.mode == "latex", base=start[1],
                       end=end[1])
        rows = _split_rows(raw, True)
        while len(rows) > 1 and not _strip_spaces(rows[-1]):
            rows.pop()
        if len(rows) != sum(len(g) for g in groups):
            return None
        spans, k = [], 0
        for group in groups:
            mine = [t for row in rows[k:k + len(group)] for t in row if t[0] != SP]
            k += len(group)
            spans.append((mine[0][3], mine[-1][3] + len(mine[-1][1])) if mine else (start[1], start[1]))
        return spans

    def approximate_span(self, group: list[_Row], start: tuple[int, int], end: tuple[int, int]) -> tuple[int, int]:
        mine = [t for r in group for t in r.tokens if t[2] == start[0] and t[4] == 0 and t[0] != SP]
        if not mine:
            return start[1], end[1]
        return min(t[3] for t in mine), max(t[3] + len(t[1]) for t in mine)


def replace_display(display: Display, **changes) -> Display:
    values = {name: getattr(display, name) for name in display.__dataclass_fields__}
    values.update(changes)
    return Display(**values)


# ---------------------------------------------------------------------------------------------
# LaTeX mode
# ---------------------------------------------------------------------------------------------


class _Peek:
    def __init__(self, tokens):
        self.tokens, self.buffer = tokens, []

    def next(self):
        return self.buffer.pop() if self.buffer else next(self.tokens, None)

    def push(self, tok) -> None:
        self.buffer.append(tok)


def _env_name(stream: _Peek) -> tuple[str | None, list]:
    r"""After ``\begin``/``\end``: the environment name and the tokens read for it."""
    first = stream.next()
    if first is None or first[0] != BG:
        if first is not None:
            stream.push(first)
        return None, []
    read = [first]
    while True:
        tok = stream.next()
        if tok is None:
            return None, read
        read.append(tok)
        if tok[0] == EG:
            return serialize(read[1:-1]).strip(), read
        if len(read) > 64:
            return None, read


class LatexReader(Reader):
    def __init__(self, files: Files, expander: Expander):
        super().__init__(files, "latex")
        self.expander = expander
        self.prose: list[str] = []

    def after(self, tok) -> int:
        """The offset after ``tok`` in its file; for a token a macro produced, after the macro's name."""
        if tok[4] == 0:
            return tok[3] + len(tok[1])
        m = re.compile(r"\\(?:[A-Za-z@]+|.)").match(self.files.texts[tok[2]], tok[3])
        return m.end() if m else tok[3]

    def context(self) -> str:
        joined = " ".join("".join(self.prose[-3000:]).split())
        self.last_prose = joined[-4000:]
        self.prose = []
        return joined.replace("$", "")[-300:]

    def group_text(self, stream: _Peek) -> str | None:
        tok = stream.next()
        while tok is not None and tok[0] == SP:
            tok = stream.next()
        if tok is None or tok[0] != BG:
            if tok is not None:
                stream.push(tok)
            return None
        out, depth = [], 1
        while True:
            t = stream.next()
            if t is None:
                return serialize(out)
            depth += (t[0] == BG) - (t[0] == EG)
            if depth == 0:
                return serialize(out)
            out.append(t)

    def heading(self, tok, stream: _Peek) -> None:
        starred = False
        nxt = stream.next()
        if nxt is not None and nxt[0] == CH and nxt[1] == "*":
            starred = True
        elif nxt is not None:
            stream.push(nxt)
        nxt = stream.next()
        while nxt is not None and nxt[0] == SP:
            nxt = stream.next()
        if nxt is not None and nxt[0] == CH and nxt[1] == "[":      # [short title]
            depth = 0
            while nxt is not None and not (nxt[0] == CH and nxt[1] == "]" and depth == 0):
                depth += (nxt[0] == BG) - (nxt[0] == EG)
                nxt = stream.next()
        elif nxt is not None:
            stream.push(nxt)
        title = self.group_text(stream)
        if title is not None:
            self.open_section(_SECTION_LEVELS[tok[1]], title, starred, tok[2], tok[3])

    def collect(self, opener, env: str, stream: _Peek, inner_start: int) -> None:
        """Read a display's tokens up to its closer and emit it (``inner_start``: the offset
        after the opener)."""
        body: list = []
        depth = 0
        notes: list[str] = []
        end = inner_end = None
        while True:
            tok = stream.next()
            if tok is None:
                notes.append("never closed; the display ends at the end of the file")
                break
            if is_par(tok):
                notes.append("not closed before the blank line; the display ends there")
                break
            if env == "$$" and tok[0] == CH and tok[1] == "$":
                nxt = stream.next()
                if nxt is not None and nxt[0] == CH and nxt[1] == "$":
                    end, inner_end = (nxt[2], nxt[3] + 1), tok[3]
                    break
                if nxt is not None:
                    stream.push(nxt)
            elif env == "\\[" and tok[0] == CS and tok[1] == "\\]":
                end, inner_end = (tok[2], tok[3] + 2), tok[3]
                break
            elif tok[0] == CS and tok[1] in ("\\begin", "\\end") and env not in ("$$", "\\["):
                name, read = _env_name(stream)
                if tok[1] == "\\end" and name == env and depth == 0:
                    end, inner_end = (tok[2], read[-1][3] + 1), tok[3]
                    break
                if name is not None:
                    depth += 1 if tok[1] == "\\begin" else -1
                    if depth > MAX_NESTING:
                        raise SourceError(f"{self.files.where(tok[2], tok[3])}: environments nested deeper than {MAX_NESTING}")
                body.append(tok)
                body.extend(read)
                continue
            body.append(tok)
        if end is None:
            self.warnings.append(f"{self.files.where(opener[2], opener[3])}: {env}: {notes[0]}")
            last = next((t for t in reversed(body) if t[2] == opener[2] and t[4] == 0), opener)
            end = (last[2], last[3] + len(last[1]))
            inner_end = end[1]
        self.emit(body, env, (opener[2], inner_start), (end[0], inner_end), self.context(), notes)

    def counter_command(self, command: str, stream: _Peek) -> None:
        r"""``\numberwithin{equation}{section}`` and ``\setcounter{equation|section...}{n}``."""
        first, second = self.group_text(stream), self.group_text(stream)
        if not first or second is None:
            return
        first, second = first.strip(), second.strip()
        if command == "\\numberwithin":
            if first == "equation" and "\\" + second in _SECTION_LEVELS:
                self.within = _SECTION_LEVELS["\\" + second]
        elif re.fullmatch(r"-?[0-9]{1,9}", second):       # ASCII digits only ('²' is isdigit(), not int())
            if first == "equation":
                self.equation = int(second)
            elif "\\" + first in _SECTION_LEVELS:
                self.counters[_SECTION_LEVELS["\\" + first]] = int(second)

    def read(self, main: int) -> None:
        tokens = tokenize(self.files.texts[main], main, self.files, latex=True)
        self.expander.budget += 50 * len(tokens)
        has_document = "\\begin{document}" in self.files.texts[main]
        in_body = not has_document
        stream = _Peek(self.expander.run(tokens, main))
        while (tok := stream.next()) is not None:
            kind, text = tok[0], tok[1]
            if kind == CS and text in ("\\begin", "\\end"):
                name, read = _env_name(stream)
                if name == "document":
                    if text == "\\end":
                        return
                    in_body = True
                elif in_body and text == "\\begin" and name is not None and name.rstrip("*") in DISPLAY_ENVS:
                    self.collect(tok, name, stream, self.after(read[-1]))
                elif name == "subequations":
                    if text == "\\begin":
                        self.sub = (self.next_number(), 0)
                    else:
                        self.sub = None
                continue
            if kind == CS and text in ("\\numberwithin", "\\setcounter"):
                self.counter_command(text, stream)
                continue
            if not in_body:
                continue
            if kind == CH and text == "$":
                nxt = stream.next()
                if nxt is not None and nxt[0] == CH and nxt[1] == "$":
                    self.collect((CH, "$$", tok[2], tok[3], tok[4]), "$$", stream, tok[3] + 2)
                    continue
                self.prose.append("$")                 # inline maths is prose context, kept delimited
                while nxt is not None and not (nxt[0] == CH and nxt[1] == "$") and not is_par(nxt):
                    self.prose.append(nxt[1])
                    nxt = stream.next()
                self.prose.append("$")
                continue
            if kind == CS:
                if text == "\\[":
                    self.collect(tok, "\\[", stream, tok[3] + 2)
                elif text in _SECTION_LEVELS:
                    self.heading(tok, stream)
                elif text == "\\appendix":
                    self.appendix = True
                    self.counters[0 if self.chapters else 1] = 0
                else:
                    self.prose.append(text)
                continue
            self.prose.append(text if kind != SP else " ")
            if len(self.prose) > 4000:
                del self.prose[:2000]
