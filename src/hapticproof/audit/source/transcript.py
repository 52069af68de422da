r"""The text mode of the source reader: transcriptions and Markdown (``.txt``, ``.md``) whose
displays are ``$$...$$``, ``\[...\]`` or the LaTeX environments, with the OCR repairs, the
numbers printed beside or under a display, the headings of a plain-text paper and the inline
``where`` definition lists (see :mod:`hapticproof.audit.source.displays` for what is read).
"""

from __future__ import annotations

import re
from dataclasses import dataclass, field

from hapticproof.audit.source.displays import DISPLAY_ENVS, PARAGRAPH, Display, Reader, Section, replace_display
from hapticproof.audit.source.tex import Expander, Files, tokenize

__all__ = ["TextReader", "where_list"]

_ENV_NAMES = "|".join(sorted(DISPLAY_ENVS, key=len, reverse=True))
_TEXT_OPEN = re.compile(r"\$\$|\$|\\\[|\\begin\{(" + _ENV_NAMES + r")(\*?)\}|^[ \t]*(?:```|~~~)", re.M)
_FENCE = re.compile(r"^[ \t]*(?:```|~~~)[^\n]*$", re.M)
_SUPERSCRIPT = str.maketrans("⁰¹²³⁴⁵⁶⁷⁸⁹", "0123456789")
_NUMBER_LINE = re.compile(r"[ \t]*\n(?:[ \t]*\n)?[ \t]*(?:\$\$[ \t]*)?(?:\\tag\{([^{}\n]{1,12})\}|\(\s*(\d{1,3}[a-z]?)\s*\)|"
                          r"⁽([⁰¹²³⁴⁵⁶⁷⁸⁹]{1,3})⁾)[ \t]*(?:\$\$)?[ \t]*(?=\n|$)")
_DEFINITION = re.compile(r"\\(?:newcommand|renewcommand|providecommand|DeclareRobustCommand|def|gdef|edef|let|"
                         r"DeclareMathOperator)(?![A-Za-z])")
_ENDS_WITH_OPERATOR = re.compile(r"(?:=|\+|-|<|>|\\(?:le|leq|ge|geq|neq|ne|cdot|times|pm|mp)|\\\\)\s*$")
_STARTS_WITH_RELATION = re.compile(r"^\s*(?:&\s*)?(?:=|<|>|\\(?:implies|Longrightarrow|Rightarrow|iff|Leftrightarrow|"
                                   r"le|leq|ge|geq|approx|equiv)(?![A-Za-z]))")
_NAMED_HEADINGS = {"abstract": "Abstract", "abstract:": "Abstract", "appendix": "Appendix", "appendices": "Appendix",
                   "references": "References", "acknowledgment": "Acknowledgment",
                   "acknowledgments": "Acknowledgments", "acknowledgement": "Acknowledgement",
                   "acknowledgements": "Acknowledgements", "bibliography": "References"}
_ROMAN = {"I": 1, "II": 2, "III": 3, "IV": 4, "V": 5, "VI": 6, "VII": 7, "VIII": 8, "IX": 9, "X": 10, "XI": 11, "XII": 12}


def _escaped(text: str, pos: int) -> bool:
    count = 0
    while pos - count - 1 >= 0 and text[pos - count - 1] == "\\":
        count += 1
    return count % 2 == 1


@dataclass
class _Region:
    env: str
    start: int            # the opener
    inner: int            # after the opener
    inner_end: int
    end: int              # after the closer (or where an unclosed display stops)
    number: str | None = None
    notes: list = field(default_factory=list)


def _regions(text: str, name: str, files: Files, file: int,
             warnings: list[str]) -> tuple[list[_Region], list[tuple[int, int]]]:
    """Display regions of a transcription, and the spans of code blocks (unclosed ones warned)."""
    regions: list[_Region] = []
    code: list[tuple[int, int]] = []
    pos = limit = 0
    while True:
        m = _TEXT_OPEN.search(text, pos)
        if m is None:
            break
        s, opener = m.start(), m.group()
        if opener.lstrip().startswith(("```", "~~~")):
            close = _FENCE.search(text, m.end())
            stop = close.end() if close else len(text)
            code.append((s, stop))
            pos = stop
            continue
        if _escaped(text, s):
            pos = s + 1
            continue
        if limit <= m.end():                   # the paragraph break after the opener (searched once per paragraph)
            paragraph = PARAGRAPH.search(text, m.end())
            limit = paragraph.start() if paragraph else len(text)
        if opener == "$":                      # inline maths: skipped, within its paragraph
            close = text.find("$", m.end(), limit)
            while close > 0 and _escaped(text, close):
                close = text.find("$", close + 1, limit)
            pos = close + 1 if close > 0 else m.end()
            continue
        if opener == "$$":
            env, closer = "$$", re.compile(r"(?<!\\)\$\$")
        elif opener == "\\[":
            env, closer = "\\[", re.compile(r"\\\]")
        else:
            env = m.group(1) + m.group(2)
            closer = re.compile(r"\\end\{" + re.escape(env) + r"\}")
        close = closer.search(text, m.end(), limit)     # a closer past the paragraph break does not count
        region = _Region(env, s, m.end(), 0, 0)
        if close is None:
            region.inner_end = region.end = limit
            region.notes.append(f"{env} not closed before the paragraph break; the display ends there")
            warnings.append(f"{name}:{files.line(file, s)}: {region.notes[-1]}")
        else:
            region.inner_end, region.end = close.start(), close.end()
        number = _NUMBER_LINE.match(text, region.end)
        if number:
            region.number = (number.group(1) or number.group(2) or number.group(3).translate(_SUPERSCRIPT)).strip()
            region.notes.append(f"number ({region.number}) from the line after the display")
            region.end = number.end()
        regions.append(region)
        pos = region.end
    return regions, code


class _Headings:
    """Heading lines of a transcription, accepted only in a plausible numbering order."""

    def __init__(self):
        self.arabic: tuple[int, ...] = ()
        self.roman = 0
        self.letter = ""

    def arabic_ok(self, number: tuple[int, ...]) -> bool:
        c = self.arabic
        if not c:
            return all(part == 1 for part in number[1:])
        successors = {c + (1,)} | {c[:k] + (c[k] + 1,) for k in range(len(c))}
        return number in successors

    def match(self, line: str) -> tuple[str, str, int] | None:
        stripped = line.strip()
        if not stripped or len(stripped) > 100:
            return None
        md = re.match(r"(#{1,6})\s+(.+?)\s*#*$", stripped)
        if md:
            inner = self.match(md.group(2)) if not md.group(2).startswith("#") else None
            return inner or ("", md.group(2), len(md.group(1)))
        named = _NAMED_HEADINGS.get(stripped.lower().rstrip("."))
        if named:
            return "", named, 1
        m = re.match(r"(\d{1,2}(?:\.\d{1,2}){0,3})\.?\s+([A-Z].*)$", stripped)
        if m and not m.group(2).endswith((".", ",", ";")) and "$" not in m.group(2):
            number = tuple(int(p) for p in m.group(1).split("."))
            if self.arabic_ok(number):
                self.arabic = number
                return m.group(1), m.group(2), len(number)
            return None
        m = re.match(r"([IVX]{1,4})\.\s+([A-Z][^a-z]*)$", stripped)
        if m and m.group(1) in _ROMAN and (self.roman == 0 or _ROMAN[m.group(1)] == self.roman + 1):
            self.roman, self.letter = _ROMAN[m.group(1)], ""
            return m.group(1), m.group(2), 1
        m = re.match(r"([A-H])\.\s+([A-Z].*)$", stripped)
        if m and self.roman and ord(m.group(1)) == (ord(self.letter) + 1 if self.letter else 65):
            self.letter = m.group(1)
            roman = next(k for k, v in _ROMAN.items() if v == self.roman)
            return f"{roman}-{m.group(1)}", m.group(2), 2
        return None


def _headings(text: str, regions: list[_Region], code: list[tuple[int, int]],
              file_name: str) -> list[tuple[int, Section]]:
    """The headings outside displays and code, with their offsets."""
    blocked = sorted([(r.start, r.end) for r in regions] + code)
    lines = text.split("\n")
    offsets = [0]
    for line in lines:
        offsets.append(offsets[-1] + len(line) + 1)
    state = _Headings()
    out = []
    k_block = 0
    for k, line in enumerate(lines):
        start = offsets[k]
        while k_block < len(blocked) and blocked[k_block][1] <= start:
            k_block += 1
        if k_block < len(blocked) and blocked[k_block][0] < offsets[k + 1] and blocked[k_block][1] > start:
            continue
        markdown = line.lstrip().startswith("#")
        alone = (k == 0 or not lines[k - 1].strip()) and (k + 1 >= len(lines) or not lines[k + 1].strip())
        if not (markdown or alone):
            continue
        got = state.match(line)
        if got:
            number, title, level = got
            out.append((start, Section(number, " ".join(title.split()), level, k + 1, file_name)))
    return out


class TextReader(Reader):
    def __init__(self, files: Files, expander: Expander):
        super().__init__(files, "text")
        self.expander = expander

    def where_lists(self, text: str, file: int, start: int, end: int) -> None:
        """Inline definition lists in the prose between two displays, as displays of their own
        (environment ``where``): a transcription keeps some definitions inline."""
        for offset, body in where_list(text[start:end]):
            line = self.files.line(file, start + offset)
            context = " ".join(text[max(start, start + offset - 300):start + offset].split())
            self.displays.append(Display(body, body, None, None, None, self.section, line, line, "where",
                                         self.files.names[file], None, context,
                                         ("definitions written inline after 'where', joined into one display",)))

    def read(self, file: int) -> None:
        text, name = self.files.texts[file], self.files.names[file]
        regions, code = _regions(text, name, self.files, file, self.warnings)
        headings = _headings(text, regions, code, name)
        self.expander.budget += 50 * (len(text) // 4 + 1)
        h = 0
        previous_end = 0
        for region in regions:
            while h < len(headings) and headings[h][0] < region.start:
                self.section = headings[h][1]
                self.sections.append(self.section)
                h += 1
            prose = text[previous_end:region.start]
            self.where_lists(text, file, previous_end, region.start)
            if _DEFINITION.search(prose):
                for _ in self.expander.run(tokenize(text, file, self.files, latex=False, base=previous_end,
                                                     end=region.start), file):
                    pass
            body = list(self.expander.run(tokenize(text, file, self.files, latex=False, base=region.inner,
                                                    end=region.inner_end), file))
            before = len(self.displays)
            self.last_prose = " ".join(prose.split())[-4000:]     # the prose with its inline $...$ maths
            self.emit(body, region.env, (file, region.inner), (file, region.inner_end),
                      " ".join(prose.split())[-300:], region.notes)
            if region.number and len(self.displays) > before and self.displays[-1].number is None:
                self.displays[-1] = replace_display(self.displays[-1], number=region.number)
            previous_end = region.end
        self.where_lists(text, file, previous_end, len(text))
        self.sections.extend(section for _, section in headings[h:])
        self.displays = _join_continued(self.displays)


_WHERE = re.compile(r"\bwhere\s+((?:\$[^$\n]+\$(?:\s*(?:,\s*)?(?:and\s+)?)){2,})")
_DEFINES = re.compile(r"^\s*\\?[A-Za-z]+(?:_\{?[A-Za-z0-9]+\}?)?(?:\([^()]*\))?\s*=[^=<>]+$")


def where_list(prose: str) -> list[tuple[int, str]]:
    r"""The definitions of a ``where $K_1 = ...$, $K_2 = ...$ and $B_1 = ...$`` sentence: the
    start of each run of at least two inline definitions and the run joined by ``", "`` (one
    display of definitions, as a reviewer reads it).

    >>> where_list(r"with $x$ and where $K_1 = K_{01} + K_{12}$, $B_1 = B_{01}$ and $n = 2$. Then")
    [(19, 'K_1 = K_{01} + K_{12}, B_1 = B_{01}, n = 2')]
    """
    out = []
    for match in _WHERE.finditer(prose):
        pieces = re.findall(r"\$([^$\n]+)\$", match.group(1))
        if len(pieces) >= 2 and all(_DEFINES.match(p) for p in pieces):
            out.append((match.start(1), ", ".join(p.strip() for p in pieces)))
    return out


def _join_continued(displays: list[Display]) -> list[Display]:
    """Join the displays a transcription split: one ending in an operator continues into the
    next; one starting with a relation right under an unnumbered display is its next row."""
    out: list[Display] = []
    for display in displays:
        if out:
            last = out[-1]
            close = display.line - last.end_line <= 3
            dangling = _ENDS_WITH_OPERATOR.search(last.text) is not None
            if close and dangling and not (last.number and display.number):
                out[-1] = replace_display(last, text=last.text + "\n" + display.text, original=last.original + "\n" + display.original,
                                   number=last.number or display.number, tag=last.tag or display.tag, end_line=display.end_line,
                                   notes=last.notes + display.notes + (f"joined with the display at line {display.line}: "
                                                                       f"this one ends with an operator",))
                continue
            adjacent = display.line - last.end_line == 1      # no blank line between them
            if adjacent and last.number is None and _STARTS_WITH_RELATION.match(display.text):
                out[-1] = replace_display(last, text=last.text + " \\\\ " + display.text,
                                   original=last.original + " \\\\ " + display.original, number=display.number,
                                   tag=display.tag, end_line=display.end_line,
                                   notes=last.notes + display.notes + (f"joined with the display at line {display.line}: "
                                                                       f"it starts with a relation",))
                continue
        out.append(display)
    return out
