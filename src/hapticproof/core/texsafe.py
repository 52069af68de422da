r"""Read text the way TeX reads it, before any of it is allowed into a LaTeX report.

A report places printed, derived and corrected displays (from paper files and saved audits,
i.e. from untrusted text) inside its LaTeX. Looking for ``\name`` with a regular expression
is not what TeX does: TeX's input stage turns ``^^5c`` into a backslash, ``\^^69nput`` into
``\input`` and ``^^5e^5c`` into a backslash too (the first code makes a ``^`` that starts the
second). :func:`tokenize` follows TeX's own procedure (*The TeXbook*, ch. 7-8; tex.web
§§343-356: the line buffer, the states N/M/S, the in-place reduction of ``^^`` codes inside
control-sequence names) with the category codes a LaTeX document body has, so the control
sequences it returns (:func:`tex_commands`) are the ones TeX will see. :func:`check_tex` then
refuses a display that uses any ``^^`` code, a command outside an allow-list, one of the
primitives that read or write files, define macros or change how TeX reads
(:data:`ALWAYS_REFUSED`, refused even when an allow-list names them), an environment outside
its list, a comment, a macro-parameter character, unbalanced braces or a control character.
:func:`escape_tex_text` escapes plain text (outside mathematics) so that TeX reads it as
exactly those characters, and checks its own output with the tokenizer.

>>> tex_commands(r"b > \frac{KT}{2} ^^5cinput{/etc/hostname}")
['\\frac', '\\input']
>>> check_tex(r"b > \frac{KT}{2}", {"frac"}) is None
True
>>> print(check_tex(r"b > \frac{KT}{2} ^^5cinput{/etc/hostname}", {"frac"}))
^^5c at offset 17 is TeX's code for '\' (no ^^ code is accepted)
>>> escape_tex_text("50% of ^^5c")
'50\\% of \\textasciicircum{}\\textasciicircum{}5c'

What is not modelled: category-code changes (``\catcode``, ``\makeatletter``, ``\verb``,
``\ExplSyntaxOn`` are refused before they could take effect), and macro expansion beyond
``\csname ... \endcsname`` names (every macro that is not on the allow-list is refused, so
nothing unlisted gets expanded).
"""

from __future__ import annotations

import re
import unicodedata
from collections.abc import Collection, Iterable, Mapping
from dataclasses import dataclass, field

__all__ = [
    "LATEX_CATCODES",
    "ALWAYS_REFUSED",
    "SAFE_CONTROL_SYMBOLS",
    "Token",
    "Reading",
    "tokenize",
    "tex_commands",
    "check_tex",
    "escape_tex_text",
]

# --------------------------------------------------------------------------------------------
# category codes
# --------------------------------------------------------------------------------------------
ESCAPE, BEGIN_GROUP, END_GROUP, MATH_SHIFT, ALIGN, END_LINE, PARAMETER, SUPERSCRIPT, SUBSCRIPT = range(9)
IGNORED, SPACE, LETTER, OTHER, ACTIVE, COMMENT, INVALID = range(9, 16)

#: ``\catcode`` of codes 0-255 in the body of the report documents, as pdflatex 1.40.24
#: (TeX Live 2022, LaTeX 2022-11) reports them after ``\begin{document}`` with the reports'
#: preamble (T1, lmodern, amsmath, hyperref): the control characters and every byte >= 128
#: are active (inputenc's UTF-8 reader), NUL and DEL invalid, ``@`` other.
#: ``tests/test_texsafe.py`` measures the table again with pdflatex when it is installed.
LATEX_CATCODES: tuple[int, ...] = tuple(
    [INVALID] + [ACTIVE] * 8 + [SPACE, OTHER, ACTIVE, ACTIVE, END_LINE] + [ACTIVE] * 18  # 0-31
    + [SPACE, OTHER, OTHER, PARAMETER, MATH_SHIFT, COMMENT, ALIGN] + [OTHER] * 25  # 32-63
    + [OTHER] + [LETTER] * 26 + [OTHER, ESCAPE, OTHER, SUPERSCRIPT, SUBSCRIPT]  # 64-95
    + [OTHER] + [LETTER] * 26 + [BEGIN_GROUP, OTHER, END_GROUP, ACTIVE, INVALID]  # 96-127
    + [ACTIVE] * 128
)
assert len(LATEX_CATCODES) == 256

_END_LINE_CHAR = 13  # \endlinechar: TeX appends it to every line it reads
_HEX = "0123456789abcdef"  # only lowercase digits make a two-digit ^^ code


def _catcode(code: int, table: tuple[int, ...], engine: str) -> int:
    if code < len(table):
        return table[code]
    if engine == "pdftex":
        return ACTIVE  # every byte of a multi-byte UTF-8 character is active in pdflatex
    return LETTER if chr(code).isalpha() else OTHER  # XeTeX/LuaTeX: Unicode letters


# --------------------------------------------------------------------------------------------
# what must never reach TeX, whatever an allow-list says
# --------------------------------------------------------------------------------------------
#: Control words refused in every context: files and the shell, definitions and expansion
#: tricks, category and case codes, hooks that run code later, links and PDF actions, the
#: job's state. Names without the backslash.
ALWAYS_REFUSED: frozenset[str] = frozenset(
    # files, terminal, shell, PDF objects
    """input endinput include includeonly InputIfFileExists IfFileExists openin openout closein closeout
    read readline write immediate message errmessage special shipout newwrite newread jobname
    write18 ShellEscape directlua latelua luaexec luadirect pdfliteral pdfobj pdfrefobj pdfximage
    pdfrefximage pdfstartlink pdfendlink pdfannot pdfdest pdfoutline pdffiledump pdffilesize
    pdffilemoddate pdfmdfivesum pdfinclusioncopyfonts pdfsavepos pdfcatalog pdfnames pdftrailer pdfinfo
    filesize filemoddate filedump mdfivesum pdfshellescape usepackage RequirePackage documentclass
    LoadClass includegraphics includepdf verbatiminput lstinputlisting inputminted openoutfile
    href url nolinkurl hyperlink hypertarget hyperref hyperdef hyperimage hyperbaseurl Acrobatmenu
    TextField CheckBox ChoiceMenu PushButton Submit Reset Form pdfstringdef
    """
    # definitions, expansion control, name construction
    """
    def edef gdef xdef let futurelet global long outer protected newcommand renewcommand
    providecommand DeclareRobustCommand DeclareTextCommand DeclareTextSymbol NewDocumentCommand
    RenewDocumentCommand ProvideDocumentCommand DeclareDocumentCommand NewExpandableDocumentCommand
    NewCommandCopy newenvironment renewenvironment NewDocumentEnvironment RenewDocumentEnvironment
    newif newcount newdimen newskip newtoks newbox newlength chardef mathchardef countdef dimendef
    skipdef muskipdef toksdef csname endcsname ifcsname begincsname lastnamedcs expandafter noexpand
    unexpanded detokenize scantokens scantextokens string meaning the showtokens afterassignment
    aftergroup primitive pdfprimitive csuse csdef cslet csgdef
    """
    # how TeX reads and prints text, hooks, modes, the end of the job
    """
    catcode lccode uccode sfcode mathcode delcode uppercase lowercase endlinechar newlinechar
    escapechar makeatletter makeatother ExplSyntaxOn ExplSyntaxOff verb everypar everymath
    everydisplay everyhbox everyvbox everyjob everycr everyeof AtBeginDocument AtEndDocument
    AtBeginShipout AtEndOfClass AtEndOfPackage AddToHook AddToHookNext pretocmd apptocmd patchcmd
    dump batchmode nonstopmode scrollmode errorstopmode show showbox showthe showlists
    tracingall tracingonline loop repeat
    """.split()
)

#: Control symbols (``\`` and one non-letter) that a display may use: spacing, escaped
#: specials, the line break. Names without the backslash.
SAFE_CONTROL_SYMBOLS: frozenset[str] = frozenset(list(",;:!> {}|&%#$_\\") + ["\t"])


# --------------------------------------------------------------------------------------------
# the tokenizer
# --------------------------------------------------------------------------------------------
@dataclass(frozen=True)
class Token:
    """One token as TeX's mouth delivers it.

    ``kind`` is ``"cs"`` (a control word or symbol; ``text`` is its name without the
    backslash), ``"active"`` (an active character; ``text`` is the character) or ``"char"``
    (``text`` is the character and ``catcode`` its category). ``offset`` is where in the
    original text the token starts, ``source`` the original text it was read from.
    """

    kind: str
    text: str
    catcode: int
    offset: int
    source: str

    def __str__(self) -> str:
        return "\\" + self.text if self.kind == "cs" else self.text


@dataclass(frozen=True)
class CaretCode:
    """A ``^^`` code TeX replaced by one character (``source`` at ``offset`` became ``char``)."""

    offset: int
    source: str
    char: str


@dataclass
class Reading:
    """What :func:`tokenize` saw: the tokens, every ``^^`` reduction, the comments (their
    offsets), invalid and ignored characters (offsets)."""

    tokens: list[Token] = field(default_factory=list)
    carets: list[CaretCode] = field(default_factory=list)
    comments: list[int] = field(default_factory=list)
    invalid: list[int] = field(default_factory=list)
    ignored: list[int] = field(default_factory=list)


def _lines(text: str) -> Iterable[tuple[str, int]]:
    """TeX Live's lines: CR LF, CR and LF end a line (but not U+2028 and friends, unlike
    :meth:`str.splitlines`); the text after the last line end is a last line."""
    start = 0
    for match in re.finditer(r"\r\n|\r|\n", text):
        yield text[start:match.start()], start
        start = match.end()
    if start < len(text) or not text:
        yield text[start:], start


class _Mouth:
    """TeX's get_next over one line buffer at a time (tex.web §§343-356)."""

    def __init__(self, text: str, table: tuple[int, ...], engine: str) -> None:
        self.text, self.table, self.engine = text, table, engine
        self.reading = Reading()

    def cat(self, code: int) -> int:
        return _catcode(code, self.table, self.engine)

    # one line -----------------------------------------------------------------------------
    def read_line(self, line: str, base: int, mid_line: bool) -> None:
        stripped = line.rstrip(" \t")  # web2c removes trailing blanks
        # the buffer: char codes and, for each, the span of original text it stands for
        self.buf = [ord(ch) for ch in stripped] + [_END_LINE_CHAR]
        self.span = [(base + k, base + k + 1) for k in range(len(stripped))]
        self.span.append((base + len(line), base + len(line)))
        self.limit = len(self.buf) - 1  # index of the end-of-line character
        self.loc = 0
        self.state = "M" if mid_line else "N"
        while self.loc <= self.limit:
            self.next_token()

    def emit(self, kind: str, text: str, catcode: int, start: int, end: int) -> None:
        self.reading.tokens.append(Token(kind, text, catcode, start, self.text[start:end]))

    def caret_code(self, k: int) -> tuple[int, int] | None:
        """``(char code, length)`` when ``buf[k]`` (a superscript character) starts an
        expanded code ``^^xy`` or ``^^c``, else None."""
        first = self.buf[k]
        if k + 1 > self.limit - 1 or self.buf[k + 1] != first:  # second ^ must come before the end
            return None
        if self.engine != "pdftex":  # XeTeX/LuaTeX: ^^^^abcd and ^^^^^^abcdef
            for count, digits in ((6, 6), (4, 4)):
                if all(k + j <= self.limit and self.buf[k + j] == first for j in range(count)):
                    hexa = "".join(chr(c) for c in self.buf[k + count:k + count + digits])
                    if len(hexa) == digits and all(ch in _HEX for ch in hexa) and k + count + digits - 1 <= self.limit:
                        return int(hexa, 16), count + digits
        c = self.buf[k + 2]
        if c >= 128:
            return None
        if chr(c) in _HEX and k + 3 <= self.limit and chr(self.buf[k + 3]) in _HEX:
            return int(chr(c) + chr(self.buf[k + 3]), 16), 4
        return (c + 64 if c < 64 else c - 64), 3

    def reduce(self, k: int, code: int, length: int) -> None:
        """Replace ``buf[k:k+length]`` by one character (TeX rewrites its buffer)."""
        start, end = self.span[k][0], self.span[k + length - 1][1]
        self.reading.carets.append(CaretCode(start, self.text[start:end], chr(code)))
        self.buf[k:k + length] = [code]
        self.span[k:k + length] = [(start, end)]
        self.limit -= length - 1

    def next_token(self) -> None:
        k = self.loc
        self.loc += 1
        code = self.buf[k]
        start = self.span[k][0]
        while True:  # reswitch
            cat = self.cat(code)
            if cat == SUPERSCRIPT:
                expanded = self.caret_code(k)
                if expanded is not None:  # the code replaces the characters; read it again
                    self.reduce(k, *expanded)
                    code = self.buf[k]
                    self.loc = k + 1
                    continue
            break
        end = self.span[k][1]
        if cat == ESCAPE:
            self.control_sequence(start)
        elif cat == END_LINE:
            self.loc = self.limit + 1
            if self.state == "N":
                self.emit("cs", "par", ESCAPE, start, end)
            elif self.state == "M":
                self.emit("char", " ", SPACE, start, end)
        elif cat == COMMENT:
            self.reading.comments.append(start)
            self.loc = self.limit + 1
        elif cat == SPACE:
            if self.state == "M":
                self.emit("char", " ", SPACE, start, end)
            self.state = "S"
        elif cat == IGNORED:
            self.reading.ignored.append(start)
        elif cat == INVALID:
            self.reading.invalid.append(start)
        elif cat == ACTIVE:
            self.emit("active", chr(code), ACTIVE, start, end)
            self.state = "M"
        else:
            self.emit("char", chr(code), cat, start, end)
            self.state = "M"

    def control_sequence(self, start: int) -> None:
        """The name after an escape character (tex.web §§354-356): letters make a control
        word; ``^^`` codes inside the name are reduced in the buffer and the name is read
        again from its start."""
        while True:  # start_cs
            loc = self.loc
            if loc > self.limit:  # cannot happen with \endlinechar = 13, kept as in TeX
                self.emit("cs", "", ESCAPE, start, self.span[self.limit][1])
                return
            k = loc
            code = self.buf[k]
            cat = self.cat(code)
            k += 1
            self.state = "S" if cat in (LETTER, SPACE) else "M"
            if cat == LETTER and k <= self.limit:
                while True:
                    code = self.buf[k]
                    cat = self.cat(code)
                    k += 1
                    if not (cat == LETTER and k <= self.limit):
                        break
                if self.reduce_in_name(k, code, cat):
                    continue
                if cat != LETTER:
                    k -= 1
                if k > loc + 1:  # a control word
                    name = "".join(chr(c) for c in self.buf[loc:k])
                    self.loc = k
                    self.emit("cs", name, ESCAPE, start, self.span[k - 1][1])
                    return
            elif self.reduce_in_name(k, code, cat):
                continue
            self.loc = loc + 1  # a control symbol (or a one-letter control word)
            self.emit("cs", chr(self.buf[loc]), ESCAPE, start, self.span[loc][1])
            return

    def reduce_in_name(self, k: int, code: int, cat: int) -> bool:
        """tex.web §355: ``buf[k-1]`` is a superscript character followed by the same one."""
        if cat != SUPERSCRIPT or k > self.limit or self.buf[k] != code:
            return False
        expanded = self.caret_code(k - 1)
        if expanded is None:
            return False
        self.reduce(k - 1, *expanded)
        return True


def tokenize(text: str, catcodes: tuple[int, ...] = LATEX_CATCODES, engine: str = "pdftex",
             start_mid_line: bool = True) -> Reading:
    r"""The tokens TeX reads from ``text`` placed in the middle of a line of a LaTeX document
    body (category codes ``catcodes``), with every ``^^`` reduction, comment, invalid and
    ignored character. ``engine`` is ``"pdftex"`` (characters >= 128 active) or ``"xetex"``
    (also ``^^^^abcd`` codes; Unicode letters are letters). The first line is read from the
    middle of a line (where a report puts a display) unless ``start_mid_line`` is False (a
    line read from a file: leading spaces skipped).

    >>> [str(t) for t in tokenize(r"\^^69nput{x}").tokens]  # the line end is a space
    ['\\input', '{', 'x', '}', ' ']
    >>> [(c.source, c.char) for c in tokenize("^^5e^5c").carets]  # ^^5e makes the ^ of a second code
    [('^^5e', '^'), ('^^5e^5c', '\\')]
    """
    if engine not in ("pdftex", "xetex"):
        raise ValueError(f"engine must be 'pdftex' or 'xetex', not {engine!r}")
    mouth = _Mouth(text, catcodes, engine)
    for k, (line, base) in enumerate(_lines(text)):
        mouth.read_line(line, base, mid_line=start_mid_line and k == 0)
    return mouth.reading


def _case_map(token: Token, case: str) -> str:
    r"""What ``\lowercase``/``\uppercase`` make of a character token (standard lc/uc codes:
    only the letters A-Z and a-z change)."""
    if token.kind == "cs" or not ("A" <= token.text <= "Z" or "a" <= token.text <= "z"):
        return token.text
    return token.text.lower() if case == "lower" else token.text.upper() if case == "upper" else token.text


def tex_commands(text: str, engine: str = "pdftex") -> list[str]:
    r"""Every control sequence TeX would see in ``text``: control words and symbols
    (``\input``, ``\,``), active characters (``~``) and the names ``\csname ... \endcsname``
    builds (after ``\endcsname``; letters case-mapped inside ``\lowercase{...}`` or
    ``\uppercase{...}``).

    >>> tex_commands(r"\lowercase{\csname INPUT\endcsname} a~b")
    ['\\lowercase', '\\csname', '\\endcsname', '\\input', '~']
    """
    out: list[str] = []
    case_stack: list[tuple[str, int]] = []  # (case, brace depth where its argument opened)
    depth = 0
    pending_case = ""
    name: list[str] | None = None
    for token in tokenize(text, engine=engine).tokens:
        if token.kind == "char" and token.catcode == BEGIN_GROUP:
            depth += 1
            if pending_case:
                case_stack.append((pending_case, depth))
                pending_case = ""
        elif token.kind == "char" and token.catcode == END_GROUP:
            if case_stack and case_stack[-1][1] == depth:
                case_stack.pop()
            depth -= 1
        case = case_stack[-1][0] if case_stack else ""
        if token.kind != "char":
            out.append(str(token))
        if token.kind == "cs" and token.text in ("lowercase", "uppercase"):
            pending_case = token.text[:-4]
        elif token.kind == "cs" and token.text == "csname":
            name = []
        elif token.kind == "cs" and token.text == "endcsname" and name is not None:
            out.append("\\" + "".join(name))
            name = None
        elif name is not None:
            name.append(_case_map(token, case) if token.kind != "cs" else "\\" + token.text)
    return out


# --------------------------------------------------------------------------------------------
# the check
# --------------------------------------------------------------------------------------------
def _bad_character(ch: str) -> str | None:
    code = ord(ch)
    if ch in "\t\n\r":
        return None
    category = unicodedata.category(ch)
    if code < 32 or code == 127 or 0x80 <= code < 0xA0:
        return "a control character"
    if category == "Cs":
        return "a lone surrogate"
    if category in ("Cf", "Co", "Cn") or ch in "\u2028\u2029":
        return "an invisible, private-use or unassigned character"
    return None


def _plain(names: Iterable[str]) -> set[str]:
    return {n[1:] if n.startswith("\\") and len(n) > 1 else n for n in names}


def check_tex(
    text: str,
    allowed: Collection[str],
    environments: Collection[str] = (),
    *,
    symbols: Collection[str] = SAFE_CONTROL_SYMBOLS,
    allow_comments: bool = False,
    allow_non_ascii: bool = True,
    engine: str = "pdftex",
    alignments: Mapping[str, int | None] | Collection[str] | None = None,
    rows: Collection[str] | None = None,
) -> str | None:
    r"""The reason to refuse ``text`` as mathematics in a LaTeX report, or None when TeX
    reads nothing but allowed commands in it.

    ``allowed`` are the control words (names with or without the backslash) and ``symbols``
    the control symbols that may occur; ``environments`` the names ``\begin{...}`` may open.
    Refused in any case: a ``^^`` code, a name of :data:`ALWAYS_REFUSED`, an environment
    given otherwise than as ``{name}``, ``#``, unbalanced braces, a lone ``\`` at the end (it
    would join the report's next character), ``^`` or ``_`` without an argument (``^&^5c``
    becomes ``^^5c`` once the report drops the alignment mark), invalid and control characters, and a comment
    unless ``allow_comments`` (the report joins a display's lines, so a comment would swallow
    the report's own closing braces). Characters >= 128 (active in pdflatex, defined by the
    UTF-8 input encoding) pass unless ``allow_non_ascii`` is False. ``alignments`` (the
    environments whose cells ``&`` separates, optionally with the most cells a row may have):
    when given, an ``&`` is accepted only directly inside one of them and within its cells, not
    in a group such as ``\text{a & b}`` (TeX stops there with "Misplaced alignment tab
    character"), and a ``\\`` only directly inside one of ``rows`` (default: the alignments).

    >>> check_tex(r"\begin{bmatrix} 1 & 0 \\ 0 & 1 \end{bmatrix}", {"begin", "end"}, {"bmatrix"}) is None
    True
    >>> print(check_tex(r"\csname input\endcsname", {"csname", "endcsname"}))
    \csname at offset 0 is never accepted (it builds or runs commands that no allow-list can check)
    >>> print(check_tex(r"b > \text{a & b}", {"text"}, alignments={"bmatrix"}))
    & at offset 12 is outside an alignment (inside a group or at the top)
    >>> print(check_tex(r"\begin{cases} a & b & c \end{cases}", {"begin", "end"}, {"cases"}, alignments={"cases": 2}))
    & at offset 20 makes more than 2 cells in a row of cases
    """
    for k, ch in enumerate(text):
        bad = _bad_character(ch)
        if bad:
            return f"U+{ord(ch):04X} at offset {k} is {bad}"
        if not allow_non_ascii and ord(ch) >= 128:
            return f"U+{ord(ch):04X} at offset {k} is not ASCII"
    reading = tokenize(text, engine=engine)
    if reading.carets:
        caret = reading.carets[0]
        return (f"{caret.source} at offset {caret.offset} is TeX's code for {caret.char!r}"
                .replace("'\\\\'", "'\\'") + " (no ^^ code is accepted)")
    if "^^" in text:  # not a code TeX reduces (before a character >= 128), still no use in a display
        return f"^^ at offset {text.index('^^')} (no ^^ code is accepted)"
    if reading.invalid:
        return f"character at offset {reading.invalid[0]} is invalid in TeX"
    if reading.comments and not allow_comments:
        return f"% at offset {reading.comments[0]} starts a comment (the rest of the line would vanish)"
    allowed_words, allowed_symbols = _plain(allowed), set(symbols)
    envs = set(environments)
    tokens = reading.tokens
    depth = 0
    cells = alignments if isinstance(alignments, Mapping) else dict.fromkeys(alignments or (), None)
    row_envs = set(cells) if rows is None else set(rows)
    opened: list[list] = []                  # environments open: [name, brace depth of their cells, cells in this row]
    for k, token in enumerate(tokens):
        where = f"at offset {token.offset}"
        if token.kind == "char":
            if token.catcode == PARAMETER:
                return f"# {where} is TeX's macro-parameter character"
            if token.catcode == ALIGN and alignments is not None:
                if not (opened and opened[-1][0] in cells and opened[-1][1] == depth):
                    return f"& {where} is outside an alignment (inside a group or at the top)"
                opened[-1][2] += 1
                most = cells[opened[-1][0]]
                if most is not None and opened[-1][2] > most:
                    return f"& {where} makes more than {most} cells in a row of {opened[-1][0]}"
            if token.catcode in (SUPERSCRIPT, SUBSCRIPT) and not _has_argument(tokens, k + 1):
                # a script without its argument is an error in TeX; the report drops & and \\
                # when it lays a display out, so ^&^5c would become ^^5c there
                return f"{token.text} {where} has no argument"
            depth += token.catcode == BEGIN_GROUP
            depth -= token.catcode == END_GROUP
            if depth < 0:
                return f"}} {where} closes a group that was not opened"
            continue
        if token.kind == "active":
            if token.text != "~" and ord(token.text) < 128:
                return f"active character U+{ord(token.text):04X} {where}"
            continue
        name = token.text
        if name == "par" and not token.source:
            return f"blank line {where} (a paragraph break inside mathematics)"
        is_word = len(name) > 1 or ("A" <= name <= "Z" or "a" <= name <= "z")
        if name in ALWAYS_REFUSED:
            return f"\\{name} {where} is never accepted (it builds or runs commands that no allow-list can check)" \
                if name in ("csname", "endcsname", "expandafter", "ifcsname", "begincsname", "lastnamedcs",
                            "scantokens", "scantextokens") else \
                f"\\{name} {where} is never accepted (files, definitions, category codes or PDF actions)"
        if is_word and name not in allowed_words:
            return f"\\{name} {where} is not an allowed command"
        if name == "\\" and alignments is not None:
            if not (opened and opened[-1][0] in row_envs and opened[-1][1] == depth):
                return f"\\\\ {where} ends a row outside an alignment (inside a group or at the top)"
            opened[-1][2] = 1
        if not is_word and name not in allowed_symbols:
            shown = {"\r": "^^M", " ": "\\ ", "": "(empty)"}.get(name, name)
            if name == "\r" and k == len(tokens) - 1:
                return f"\\ {where} ends the text (it would join the report's next character)"
            return f"control symbol \\{shown} {where} is not allowed"
        if name in ("begin", "end"):
            env = _environment_name(tokens, k + 1)
            if env is None:
                return f"\\{name} {where} is not followed by an environment name in braces"
            if env not in envs:
                return f"environment {env} {where} is not allowed"
            if name == "begin":
                opened.append([env, depth, 1])
            elif opened and opened[-1][0] == env:
                opened.pop()
    if depth:
        return f"{depth} group(s) opened and not closed"
    return None


def _has_argument(tokens: list[Token], k: int) -> bool:
    """Whether a superscript or subscript before ``tokens[k]`` gets an argument."""
    while k < len(tokens) and tokens[k].kind == "char" and tokens[k].catcode == SPACE:
        k += 1
    if k >= len(tokens):
        return False
    token = tokens[k]
    if token.kind == "cs":
        return token.text not in ("\\", "par")
    return token.kind == "active" or token.catcode not in (ALIGN, END_GROUP, MATH_SHIFT, PARAMETER, SUPERSCRIPT,
                                                           SUBSCRIPT)


def _environment_name(tokens: list[Token], k: int) -> str | None:
    """The name in ``{...}`` after ``\\begin``/``\\end`` (spaces skipped, as LaTeX's argument
    reader does), when it is letters and ``*`` only."""
    while k < len(tokens) and tokens[k].kind == "char" and tokens[k].catcode == SPACE:
        k += 1
    if k >= len(tokens) or not (tokens[k].kind == "char" and tokens[k].catcode == BEGIN_GROUP):
        return None
    name = []
    for token in tokens[k + 1:]:
        if token.kind == "char" and token.catcode == END_GROUP:
            return "".join(name) if name else None
        if token.kind != "char" or not (token.catcode == LETTER or token.text == "*"):
            return None
        name.append(token.text)
    return None


# --------------------------------------------------------------------------------------------
# plain text
# --------------------------------------------------------------------------------------------
_TEXT_SPECIALS = {
    "\\": r"\textbackslash{}", "{": r"\{", "}": r"\}", "$": r"\$", "&": r"\&", "#": r"\#", "%": r"\%",
    "_": r"\_", "^": r"\textasciicircum{}", "~": r"$\sim$", "<": r"$<$", ">": r"$>$", "|": r"$|$",
}
_TEXT_RELATIONS = (("<=>", r"$\Leftrightarrow$"), ("<=", r"$\leq$"), (">=", r"$\geq$"), ("!=", r"$\neq$"),
                   ("=>", r"$\Rightarrow$"), ("->", r"$\rightarrow$"),
                   # G^-1 as an inverse, not a circumflex; an option's -- as two hyphens, not a dash
                   ("^-1", r"$^{-1}$"), ("^-H", r"$^{-H}$"), ("--", "-{}-"))
_UNICODE = {
    "\u2264": r"$\leq$", "\u2265": r"$\geq$", "\u2260": r"$\neq$", "\u2212": "-", "\u00d7": r"$\times$",
    "\u2192": r"$\rightarrow$", "\u21d2": r"$\Rightarrow$", "\u21d4": r"$\Leftrightarrow$", "\u2248": r"$\approx$",
    "\u03c9": r"$\omega$", "\u03b8": r"$\theta$", "\u03b1": r"$\alpha$", "\u03b2": r"$\beta$", "\u03b4": r"$\delta$",
    "\u03bb": r"$\lambda$", "\u03c4": r"$\tau$", "\u221e": r"$\infty$", "\u00b1": r"$\pm$", "\u2026": r"\dots{}",
}
_TEXT_TOKEN = re.compile("|".join(re.escape(k) for k, _ in _TEXT_RELATIONS) + r"|.", re.S)
_WORD_BREAKS = set(",;:/=+*)_")
#: every command :func:`escape_tex_text` writes
_TEXT_COMMANDS = frozenset({"textbackslash", "textasciicircum", "sim", "allowbreak", "dots", "leq", "geq", "neq",
                            "Rightarrow", "rightarrow", "Leftrightarrow", "times", "approx", "omega", "theta",
                            "alpha", "beta", "delta", "lambda", "tau", "infty", "pm"})


def escape_tex_text(text: str, breakable: bool = True) -> str:
    r"""Plain text for a LaTeX document (outside mathematics, T1 fonts) that TeX reads as
    those very characters: the specials (``\ { } $ & # % _ ^ ~``) become commands, so no
    ``^^`` code, comment or command survives; relations become mathematics (no ``<`` printed
    as an inverted exclamation mark); line ends and other white space become one space (a
    blank line would be a paragraph break, a CR a line end); control, invisible and
    unassigned characters are dropped; long words may break after punctuation. The output
    is checked with :func:`tokenize` (only the commands written here, no ``^^`` code, no
    comment), so a mistake in the table raises instead of reaching TeX.

    For text without control characters or line ends, the same output as the escaper the
    reports had before.

    >>> escape_text_ = escape_tex_text
    >>> escape_text_("b_1 > 50% & {x}")
    'b\\_1 $>$ 50\\% \\& \\{x\\}'
    >>> escape_text_("a\r\\input{x}\n\nb")
    'a \\textbackslash{}input\\{x\\} b'
    """
    text = "".join(ch for ch in text if ch in "\t\n\r" or _bad_character(ch) is None)
    text = re.sub(r"[\t\n\r]+", " ", text)
    out: list[str] = []
    for word in re.split(r"(\s+)", text):
        long_word = breakable and len(word) > 20
        for match in _TEXT_TOKEN.finditer(word):
            tok = match.group(0)
            rel = dict(_TEXT_RELATIONS).get(tok)
            out.append(rel or _TEXT_SPECIALS.get(tok) or _UNICODE.get(tok) or tok)
            if long_word and tok in _WORD_BREAKS and match.end() < len(word):
                out.append(r"\allowbreak{}")
    escaped = "".join(out)
    problem = check_tex(escaped, _TEXT_COMMANDS, symbols=set("{}$&#%_"))
    if problem is not None:  # cannot happen: every special is replaced above
        raise AssertionError(f"escape_tex_text produced unsafe LaTeX ({problem}): {escaped!r}")
    return escaped
