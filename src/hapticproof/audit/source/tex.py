r"""The lexical half of :mod:`hapticproof.audit.source.displays`: files, tokens and TeX macro expansion (stdlib only).

Tokens are tuples ``(kind, text, file, offset, depth)``: ``kind`` one of :data:`CS` (a control
sequence), :data:`SP` (a whitespace run, kept verbatim), :data:`BG`/:data:`EG` (braces),
:data:`CH` (one other character), :data:`TX` (a run of ASCII letters and digits), :data:`OB` (an
opaque verbatim block); ``file``/``offset`` locate it (a token a macro produced carries the
position of the macro's use) and ``depth`` counts the expansions that produced it.

:class:`Expander` runs TeX-like expansion over a stack of token frames: definitions
(``\newcommand`` and kin, ``\def`` with delimited parameters, ``\let``,
``\DeclareMathOperator``, ``\newenvironment``) are recorded and consumed, uses are replaced,
``\input`` pushes the named file's tokens (through :class:`Files`, which keeps reads inside the
main file's folder and within the byte and file budgets). Expansion depth is capped at
:data:`MAX_EXPANSION_DEPTH` and the tokens produced by a budget linear in the source size.

>>> files = Files(None, MAX_BYTES, MAX_FILES)
>>> main = files.add("t.tex", r"\def\x#1{[#1]}\x{a}b")
>>> serialize(Expander(files, inputs=False, warnings=[], budget=100).run(tokenize(files.texts[main], main, files, latex=True)))
'[a]b'
"""

from __future__ import annotations

import bisect
import os
import re
import stat
from dataclasses import dataclass, field
from pathlib import Path

from hapticproof.core.errors import InputFormatError

__all__ = ["MAX_BYTES", "MAX_FILES", "MAX_NESTING", "MAX_EXPANSION_DEPTH", "SourceError", "Files", "Macro",
           "Expander", "tokenize", "serialize", "is_par", "shown", "CS", "SP", "BG", "EG", "CH", "TX", "OB"]

#: Bytes read in all (the main file and every \input file together).
MAX_BYTES = 8_000_000
#: Files read in all (the main file counts).
MAX_FILES = 64
#: Deepest brace or environment nesting accepted.
MAX_NESTING = 200
#: Deepest macro expansion accepted (a macro whose expansion uses a macro... this many levels).
MAX_EXPANSION_DEPTH = 64

_DEFINERS = ("\\newcommand", "\\renewcommand", "\\providecommand", "\\DeclareRobustCommand")
_DEFS = ("\\def", "\\gdef", "\\edef", "\\xdef")

# token kinds; a token is (kind, text, file index, offset, expansion depth)
CS, SP, BG, EG, CH, TX, OB = "cs", "sp", "bg", "eg", "ch", "tx", "ob"
_LATEX_TOKEN = re.compile(r"\\(?:[A-Za-z@]+|.|\n|$)|%[^\n]*(?:\n[ \t]*)?|[ \t\n]+|[A-Za-z0-9]+|.", re.S)
_TEXT_TOKEN = re.compile(r"\\(?:[A-Za-z@]+|.|\n|$)|[ \t\n]+|[A-Za-z0-9]+|.", re.S)
_VERBATIM_ENV = re.compile(r"\{(verbatim\*?|Verbatim|lstlisting|minted|comment)\}")


class SourceError(InputFormatError):
    """A source that cannot be read: one line, ``file:line: reason``."""


# ---------------------------------------------------------------------------------------------
# files
# ---------------------------------------------------------------------------------------------


def shown(name: str) -> str:
    """A requested name as it may appear in an error: printable, at most 60 characters."""
    clean = "".join(c if c.isprintable() else "?" for c in name)
    return clean if len(clean) <= 60 else clean[:57] + "..."


def _decode(data: bytes, name: str) -> str:
    for bom, what in ((b"\xff\xfe\x00\x00", "UTF-32"), (b"\x00\x00\xfe\xff", "UTF-32"),
                      (b"\xff\xfe", "UTF-16"), (b"\xfe\xff", "UTF-16")):
        if data.startswith(bom):
            raise SourceError(f"{name}: the file is {what} (byte-order mark); save it as UTF-8")
    if data.startswith(b"\xef\xbb\xbf"):
        data = data[3:]
    nul = data.find(b"\x00")
    if nul >= 0:
        line = data.count(b"\n", 0, nul) + 1
        raise SourceError(f"{name}:{line}: not a text file (a NUL byte); save it as UTF-8 text")
    try:
        text = data.decode("utf-8")
    except UnicodeDecodeError as err:
        line = data.count(b"\n", 0, err.start) + 1
        column = err.start - (data.rfind(b"\n", 0, err.start) + 1) + 1
        raise SourceError(f"{name}:{line}: not UTF-8 (invalid byte at column {column}); save the file as UTF-8") from None
    return text.replace("\r\n", "\n").replace("\r", "\n")


class Files:
    """The files read: names as given, texts, line starts; enforces the folder and budgets."""

    def __init__(self, root: Path | None, max_bytes: int, max_files: int):
        self.root = root                      # None: a string source, no folder to read from
        self.real_root = os.path.realpath(root) if root is not None else ""
        self.max_bytes, self.max_files = max_bytes, max_files
        self.used = 0
        self.names: list[str] = []
        self.reals: list[str] = []            # real paths, to find input cycles
        self.texts: list[str] = []
        self.starts: list[list[int]] = []

    def add(self, name: str, text: str, real: str = "") -> int:
        self.names.append(name)
        self.reals.append(real)
        self.texts.append(text)
        self.starts.append([0] + [m.end() for m in re.finditer("\n", text)])
        return len(self.names) - 1

    def line(self, file: int, offset: int) -> int:
        return bisect.bisect_right(self.starts[file], offset)

    def where(self, file: int, offset: int) -> str:
        return f"{self.names[file]}:{self.line(file, offset)}"

    def read(self, path: Path, name: str) -> int:
        """Read ``path`` (already checked) within the budgets; the file's index."""
        if len(self.names) >= self.max_files:
            raise SourceError(f"{name}: more than {self.max_files} files to read")
        try:
            size = os.stat(path).st_size
            if size > self.max_bytes - self.used:
                raise SourceError(f"{name}: too large ({size} bytes; the limit is {self.max_bytes} in all)")
            with open(path, "rb") as handle:
                data = handle.read(self.max_bytes - self.used + 1)
        except OSError as err:
            raise SourceError(f"{name}: cannot read it ({err.strerror})") from None
        if len(data) > self.max_bytes - self.used:
            raise SourceError(f"{name}: too large (the limit is {self.max_bytes} bytes in all)")
        self.used += len(data)
        return self.add(name, _decode(data, name), os.path.realpath(path))

    def resolve(self, request: str, where: str, command: str) -> tuple[Path, str]:
        """The file an ``\\input{request}`` names, refused unless it is a regular file inside the
        main file's folder."""
        asked = shown(request)
        refuse = f"{where}: {command}{{{asked}}}: refused"
        name = request.strip()
        if not name or "\x00" in name:
            raise SourceError(f"{refuse}: not a file name")
        if name.startswith(("/", "\\", "~")) or re.match(r"[A-Za-z]:", name):
            raise SourceError(f"{refuse}: an absolute path (names are read relative to the main file's folder)")
        if any(part == ".." for part in re.split(r"[/\\]", name)):
            raise SourceError(f"{refuse}: '..' leaves the main file's folder")
        if self.root is None:
            raise SourceError(f"{refuse}: a source given as text has no folder to read files from")
        candidates = [name] if name.endswith(".tex") else [name + ".tex", name]
        for candidate in candidates:
            path = self.root / candidate
            real = os.path.realpath(path)
            if not os.path.lexists(path):
                continue
            if os.path.commonpath([real, self.real_root]) != self.real_root:
                raise SourceError(f"{refuse}: it leads outside the main file's folder")
            try:
                mode = os.stat(real).st_mode
            except OSError:
                continue
            if not stat.S_ISREG(mode):
                raise SourceError(f"{refuse}: not a regular file")
            return Path(real), candidate
        raise SourceError(f"{where}: {command}{{{asked}}}: no such file in {self.root}")


# ---------------------------------------------------------------------------------------------
# tokens
# ---------------------------------------------------------------------------------------------


def tokenize(text: str, file: int, files: Files, *, latex: bool, base: int = 0,
              end: int | None = None) -> list[tuple]:
    """The tokens of ``text[base:end]`` (offsets into ``text``); raises on nesting over
    :data:`MAX_NESTING`."""
    out: list[tuple] = []
    append = out.append
    match = (_LATEX_TOKEN if latex else _TEXT_TOKEN).match
    pos, stop, depth = base, len(text) if end is None else end, 0
    while pos < stop:
        m = match(text, pos, stop)
        s = m.group()
        c = s[0]
        nxt = m.end()
        if c == "\\":
            if latex and s in ("\\verb", "\\verb*") and nxt < stop:
                close = text.find(text[nxt], nxt + 1, stop)
                newline = text.find("\n", nxt, stop)
                if close > 0 and (newline < 0 or close < newline):
                    append((OB, text[pos:close + 1], file, pos, 0))
                    pos = close + 1
                    continue
            if latex and s == "\\begin":
                env = _VERBATIM_ENV.match(text, nxt, stop)
                if env:
                    closing = text.find("\\end{" + env.group(1) + "}", env.end(), stop)
                    close = stop if closing < 0 else closing + len(env.group(1)) + 6
                    if env.group(1) != "comment":
                        append((OB, text[pos:close], file, pos, 0))
                    pos = close
                    continue
            append((CS, s, file, pos, 0))
        elif c == "%" and latex:
            pass
        elif c in " \t\n":
            append((SP, s, file, pos, 0))
        elif c == "{":
            depth += 1
            if depth > MAX_NESTING:
                raise SourceError(f"{files.where(file, pos)}: braces nested deeper than {MAX_NESTING}")
            append((BG, s, file, pos, 0))
        elif c == "}":
            depth = max(depth - 1, 0)
            append((EG, s, file, pos, 0))
        elif s.isascii() and s.isalnum():
            append((TX, s, file, pos, 0))
        else:
            append((CH, s, file, pos, 0))
        pos = nxt
    return out


def serialize(tokens) -> str:
    """The text of tokens; a space where a control word would otherwise swallow a letter."""
    parts: list[str] = []
    prev_word = False
    for tok in tokens:
        text = tok[1]
        if prev_word and text[:1].isalpha():
            parts.append(" ")
        parts.append(text)
        prev_word = tok[0] == CS and len(text) > 1 and text[1:].replace("@", "a").isalpha()
    return "".join(parts)


def is_par(tok) -> bool:
    return tok[0] == SP and tok[1].count("\n") >= 2


# ---------------------------------------------------------------------------------------------
# macro expansion
# ---------------------------------------------------------------------------------------------


@dataclass
class Macro:
    params: int
    body: list            # tokens and parameter numbers (int)
    optional: list | None = None           # default of an optional first argument
    prefix: list = field(default_factory=list)   # \def: literal tokens before #1
    delimiters: list | None = None         # \def: per parameter, the tokens that end it


def _key(tok) -> tuple:
    return (SP, " ") if tok[0] == SP else (tok[0], tok[1])


class Expander:
    """Expands macros over a stack of token frames; definitions and ``\\input`` are consumed."""

    def __init__(self, files: Files, *, inputs: bool, warnings: list[str], budget: int):
        self.files, self.inputs, self.warnings, self.budget = files, inputs, warnings, budget
        self.macros: dict[str, Macro] = {}
        self.envs: dict[str, tuple[Macro, list]] = {}
        self.frames: list[list] = []          # [tokens, index, file index or None]

    # -- the stream ---------------------------------------------------------------------------
    def next(self):
        frames = self.frames
        while frames:
            frame = frames[-1]
            if frame[1] < len(frame[0]):
                frame[1] += 1
                return frame[0][frame[1] - 1]
            frames.pop()
        return None

    def push(self, tokens: list, file: int | None = None) -> None:
        if tokens or file is not None:
            self.frames.append([tokens, 0, file])

    def where(self, tok) -> str:
        return self.files.where(tok[2], tok[3])

    def next_nonspace(self):
        tok = self.next()
        while tok is not None and tok[0] == SP:
            tok = self.next()
        return tok

    def group(self, opener) -> list:
        """The tokens up to the ``}`` matching ``opener`` (already read)."""
        out, depth = [], 1
        while True:
            tok = self.next()
            if tok is None:
                raise SourceError(f"{self.where(opener)}: this {{ is never closed")
            if tok[0] == BG:
                depth += 1
                if depth > MAX_NESTING:
                    raise SourceError(f"{self.where(tok)}: braces nested deeper than {MAX_NESTING}")
            elif tok[0] == EG:
                depth -= 1
                if depth == 0:
                    return out
            out.append(tok)

    def argument(self, owner) -> list:
        """An undelimited argument: a brace group's content or one token."""
        tok = self.next_nonspace()
        if tok is None or tok[0] == EG:
            raise SourceError(f"{self.where(owner)}: {owner[1]} is missing an argument")
        if tok[0] == BG:
            return self.group(tok)
        if tok[0] == TX and len(tok[1]) > 1:       # \x ab: the argument is 'a'
            self.push([(TX, tok[1][1:], tok[2], tok[3] + 1, tok[4])])
            return [(TX, tok[1][0], tok[2], tok[3], tok[4])]
        return [tok]

    def optional(self) -> list | None:
        """A ``[...]`` argument if one comes next (spaces skipped), else None."""
        tok = self.next_nonspace()
        if tok is None:
            return None
        if tok[0] != CH or tok[1] != "[":
            self.push([tok])
            return None
        out, depth = [], 0
        while True:
            t = self.next()
            if t is None:
                raise SourceError(f"{self.where(tok)}: this [ is never closed")
            if t[0] == BG:
                depth += 1
            elif t[0] == EG:
                depth -= 1
            elif t[0] == CH and t[1] == "]" and depth == 0:
                return out
            out.append(t)

    def star(self) -> bool:
        tok = self.next()
        if tok is not None and tok[0] == CH and tok[1] == "*":
            return True
        if tok is not None:
            self.push([tok])
        return False

    def name(self, owner) -> str:
        """A command name: ``\\x`` or ``{\\x}``."""
        tok = self.next_nonspace()
        if tok is not None and tok[0] == CS:
            return tok[1]
        if tok is not None and tok[0] == BG:
            inner = [t for t in self.group(tok) if t[0] != SP]
            if len(inner) == 1 and inner[0][0] == CS:
                return inner[0][1]
        raise SourceError(f"{self.where(owner)}: {owner[1]} expects a command name such as \\name")

    # -- definitions --------------------------------------------------------------------------
    def body(self, tokens: list, params: int, owner) -> list:
        """Replacement text with ``#n`` as parameter numbers."""
        out: list = []
        k = 0
        while k < len(tokens):
            tok = tokens[k]
            if tok[0] == CH and tok[1] == "#" and k + 1 < len(tokens):
                nxt = tokens[k + 1]
                if nxt[0] == CH and nxt[1] == "#":
                    out.append(tok)
                    k += 2
                    continue
                if nxt[0] == TX and nxt[1][0] in "0123456789":
                    number = int(nxt[1][0])
                    if not 1 <= number <= max(params, 0):
                        raise SourceError(f"{self.where(owner)}: #{number} but the definition takes {params} parameters")
                    out.append(number)
                    if len(nxt[1]) > 1:
                        out.append((TX, nxt[1][1:], nxt[2], nxt[3] + 1, nxt[4]))
                    k += 2
                    continue
            out.append(tok)
            k += 1
        return out

    def newcommand(self, owner) -> None:
        self.star()
        name = self.name(owner)
        count = self.optional()
        params = 0
        if count is not None:
            digits = serialize(count).strip()
            if digits not in tuple("0123456789"):         # (str.isdigit takes '²', which int() does not)
                raise SourceError(f"{self.where(owner)}: {owner[1]}{{{name}}}: [{shown(digits)}] is not a parameter count 0-9")
            params = int(digits)
        default = self.optional() if params else None
        body = self.argument(owner)
        if owner[1] == "\\providecommand" and name in self.macros:
            return
        self.macros[name] = Macro(params, self.body(body, params, owner), default)

    def define(self, owner) -> None:
        """``\\def\\x#1#2{...}``: parameter text up to the body's brace."""
        name = self.name(owner)
        prefix: list = []
        delimiters: list[list] = []
        while True:
            tok = self.next()
            if tok is None:
                raise SourceError(f"{self.where(owner)}: {owner[1]}{name} has no body")
            if tok[0] == BG:
                break
            if tok[0] == CH and tok[1] == "#":
                digit = self.next()
                if digit is None or digit[0] != TX or digit[1][0] != str(len(delimiters) + 1):
                    raise SourceError(f"{self.where(owner)}: {owner[1]}{name}: parameters must be #1, #2, ... in order")
                delimiters.append([])
                if len(digit[1]) > 1:
                    delimiters[-1].append((TX, digit[1][1:], digit[2], digit[3] + 1, digit[4]))
                continue
            (delimiters[-1] if delimiters else prefix).append(tok)
        body = self.group(tok)
        simple = not prefix and not any(delimiters)
        self.macros[name] = Macro(len(delimiters), self.body(body, len(delimiters), owner), None,
                                   [] if simple else prefix, None if simple else delimiters)

    def declare_operator(self, owner) -> None:
        starred = self.star()
        name = self.name(owner)
        text = self.argument(owner)
        op = "\\operatorname*" if starred else "\\operatorname"
        self.macros[name] = Macro(0, [(CS, op, owner[2], owner[3], owner[4]), (BG, "{", owner[2], owner[3], owner[4]),
                                       *text, (EG, "}", owner[2], owner[3], owner[4])])

    def let(self, owner) -> None:
        name = self.name(owner)
        tok = self.next_nonspace()
        if tok is not None and tok[0] == CH and tok[1] == "=":
            tok = self.next_nonspace()
        if tok is None:
            raise SourceError(f"{self.where(owner)}: \\let{name} has nothing to copy")
        if tok[0] == CS and tok[1] in self.macros:
            self.macros[name] = self.macros[tok[1]]
        else:
            self.macros[name] = Macro(0, [tok])

    def newenvironment(self, owner) -> None:
        self.star()
        first = self.next_nonspace()
        if first is None or first[0] != BG:
            raise SourceError(f"{self.where(owner)}: {owner[1]} expects {{name}}")
        env = serialize(self.group(first)).strip()
        count = self.optional()
        params = int(serialize(count).strip()) if count and serialize(count).strip() in tuple("0123456789") else 0
        default = self.optional() if params else None
        begin, end = self.argument(owner), self.argument(owner)
        self.envs[env] = (Macro(params, self.body(begin, params, owner), default), self.body(end, 0, owner))

    # -- expansion ----------------------------------------------------------------------------
    def arguments(self, tok, macro: Macro) -> list[list] | None:
        if macro.delimiters is None:
            args = []
            if macro.optional is not None:
                given = self.optional()
                args.append([(t[0], t[1], tok[2], tok[3], tok[4] + 1) for t in macro.optional] if given is None else given)
            while len(args) < macro.params:
                args.append(self.argument(tok))
            return args
        nxt = self.next()                      # TeX drops the space after a control word
        if nxt is not None and not (nxt[0] == SP and not is_par(nxt) and tok[1][1:2].isalpha()):
            self.push([nxt])
        for expected in macro.prefix:
            got = self.next()
            if got is None or _key(got) != _key(expected):
                self.warnings.append(f"{self.where(tok)}: {tok[1]} does not match its definition; left as written")
                if got is not None:
                    self.push([got])
                return None
        args = []
        for delimiter in macro.delimiters:
            if not delimiter:
                args.append(self.argument(tok))
                continue
            want = [_key(t) for t in delimiter]
            got: list = []
            keys: list = []
            while keys[-len(want):] != want:
                t = self.next()
                if t is None:
                    raise SourceError(f"{self.where(tok)}: runaway argument of {tok[1]} (its delimiter never comes)")
                if t[0] == BG:
                    inner = self.group(t)
                    got.extend([t, *inner, (EG, "}", t[2], t[3], t[4])])
                    keys.append(None)
                    continue
                got.append(t)
                keys.append(_key(t))
            arg = got[:len(got) - len(want)]
            if arg and arg[0][0] == BG and arg[-1][0] == EG and self._one_group(arg):
                arg = arg[1:-1]
            args.append(arg)
        return args

    @staticmethod
    def _one_group(tokens: list) -> bool:
        depth = 0
        for k, t in enumerate(tokens):
            depth += (t[0] == BG) - (t[0] == EG)
            if depth == 0 and k < len(tokens) - 1:
                return False
        return True

    def substitute(self, tok, macro: Macro, args: list[list]) -> None:
        depth = tok[4] + 1
        if depth > MAX_EXPANSION_DEPTH:
            raise SourceError(f"{self.where(tok)}: {tok[1]} expands more than {MAX_EXPANSION_DEPTH} levels deep "
                              f"(a recursive definition?)")
        out: list = []
        for item in macro.body:
            if isinstance(item, int):
                out.extend(args[item - 1])
            else:
                out.append((item[0], item[1], tok[2], tok[3], depth))
        self.budget -= len(out) + 1
        if self.budget < 0:
            raise SourceError(f"{self.where(tok)}: macro expansion grows beyond the budget (a recursive definition?)")
        self.push(out)

    def skip_false(self, tok) -> None:
        """``\\iffalse ... \\else`` or ``\\fi``: skipped (nested ``\\if...`` counted)."""
        depth = 1
        while depth:
            t = self.next()
            if t is None:
                raise SourceError(f"{self.where(tok)}: \\iffalse is never closed by \\fi")
            if t[0] == CS:
                if t[1].startswith("\\if"):
                    depth += 1
                elif t[1] == "\\fi":
                    depth -= 1
                elif t[1] == "\\else" and depth == 1:
                    return

    def input(self, tok) -> None:
        first = self.next_nonspace()
        if first is None:
            raise SourceError(f"{self.where(tok)}: {tok[1]} names no file")
        if first[0] == BG:
            parts = self.group(first)
        else:                                  # TeX's \input name: up to a space
            parts = [first]
            while True:
                t = self.next()
                if t is None or t[0] in (SP, BG, EG, CS):
                    if t is not None:
                        self.push([t])
                    break
                parts.append(t)
        if any(t[0] == CS for t in parts):
            raise SourceError(f"{self.where(tok)}: {tok[1]}: a file name built by commands is not read")
        request = serialize(parts)
        path, name = self.files.resolve(request, self.where(tok), tok[1])
        active = {frame[2] for frame in self.frames if frame[2] is not None}    # files still being read
        if any(self.files.reals[f] == os.path.realpath(path) for f in active):
            raise SourceError(f"{self.where(tok)}: {tok[1]}{{{shown(request)}}}: the file inputs itself (a cycle)")
        index = self.files.read(path, name)
        tokens = tokenize(self.files.texts[index], index, self.files, latex=True)
        self.budget += 10 * len(tokens)
        self.push(tokens, index)

    def run(self, tokens: list, file: int | None = None):
        """The expanded tokens of ``tokens`` (a generator)."""
        self.push(tokens, file)
        floor = len(self.frames) - 1
        while len(self.frames) > floor:
            tok = self.next()
            if tok is None:
                return
            if tok[0] != CS:
                yield tok
                continue
            text = tok[1]
            macro = self.macros.get(text)
            if macro is not None:
                args = self.arguments(tok, macro)
                if args is None:
                    yield tok
                    continue
                self.substitute(tok, macro, args)
                if macro.params == 0 and macro.delimiters is None:   # TeX drops the space after \name
                    nxt = self.next()
                    if nxt is not None and not (nxt[0] == SP and not is_par(nxt)):
                        self.push([nxt])
                continue
            if text in _DEFINERS:
                self.newcommand(tok)
            elif text in _DEFS:
                self.define(tok)
            elif text == "\\let":
                self.let(tok)
            elif text == "\\DeclareMathOperator":
                self.declare_operator(tok)
            elif text in ("\\newenvironment", "\\renewenvironment"):
                self.newenvironment(tok)
            elif text == "\\iffalse":
                self.skip_false(tok)
            elif text in ("\\input", "\\include") and self.inputs:
                self.input(tok)
            elif text == "\\endinput" and self.inputs:
                for frame in reversed(self.frames):
                    if frame[2] is not None:
                        frame[1] = len(frame[0])
                        break
            elif text in ("\\begin", "\\end") and self.envs:
                yield from self.user_environment(tok)
            else:
                yield tok

    def user_environment(self, tok):
        """``\\begin{name}`` of a ``\\newenvironment``: its begin code, else the tokens as read."""
        first = self.next_nonspace()
        if first is None or first[0] != BG:
            if first is not None:
                self.push([first])
            yield tok
            return
        inner = self.group(first)
        name = serialize(inner).strip()
        if name not in self.envs:
            self.push([first, *inner, (EG, "}", first[2], first[3], first[4])])
            yield tok
            return
        begin, end = self.envs[name]
        if tok[1] == "\\begin":
            args = self.arguments(tok, begin)
            self.substitute(tok, begin, args or [])
        else:
            self.substitute(tok, Macro(0, end), [])


