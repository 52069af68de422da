"""Tokens of printed LaTeX: control words and symbols, braces, scripts and operators with their
positions, balanced groups and delimiters, and the command vocabulary of the dialect (Greek
letters, decorations, relations, fractions, environments)."""

from __future__ import annotations

import re
from dataclasses import dataclass, replace


from hapticproof.core.errors import LatexParseError
from hapticproof.core.limits import check_number_text



GREEK = frozenset(
    "\\" + g
    for g in (
        "alpha beta gamma delta epsilon varepsilon zeta eta theta vartheta iota kappa lambda mu "
        "nu xi pi varpi rho varrho sigma varsigma tau upsilon phi varphi chi psi omega ell "
        "Gamma Delta Theta Lambda Xi Pi Sigma Upsilon Phi Psi Omega"
    ).split()
)


DECORATIONS = frozenset(
    "\\" + d
    for d in (
        "mathbf mathcal mathscr mathfrak mathbb boldsymbol bm mathit mathsf bar tilde hat "
        "widehat widetilde dot ddot vec overline check breve"
    ).split()
)


#: Commands whose braced argument is kept verbatim (prose, operator names).
TEXT_COMMANDS = frozenset({"\\text", "\\textrm", "\\textit", "\\mbox", "\\operatorname", "\\mathrm"})


FRACTIONS = frozenset({"\\frac", "\\dfrac", "\\tfrac", "\\cfrac"})


OPERATOR_COMMANDS = frozenset(
    {"\\det", "\\min", "\\max", "\\sum", "\\lim", "\\int", "\\sqrt", "\\boxed", "\\infty"}
)


RELATIONS = {
    "=": "=",
    "<": "<",
    ">": ">",
    "\\geq": ">=",
    "\\ge": ">=",
    "\\geqslant": ">=",
    "\\leq": "<=",
    "\\le": "<=",
    "\\leqslant": "<=",
    "\\neq": "!=",
    "\\ne": "!=",
}


UNSUPPORTED_RELATIONS = frozenset(
    "\\" + r
    for r in (
        "in notin approx sim simeq equiv propto subset subseteq supset gg ll succ prec succeq "
        "preceq cong to rightarrow mapsto"
    ).split()
)


ARROWS = frozenset({"\\implies", "\\Longrightarrow", "\\Rightarrow", "\\xrightarrow", "\\iff"})


ELLIPSES = frozenset({"\\dots", "\\ldots", "\\cdots", "\\vdots", "\\ddots", "\\dotsc", "\\dotsb"})


MULTIPLY = frozenset({"*", "\\cdot", "\\times"})


#: Layout commands that are dropped (sizes, styles) -- they carry no mathematics.
IGNORED = frozenset(
    "\\" + c
    for c in (
        "displaystyle textstyle limits nolimits hline big Big bigg Bigg bigl bigr Bigl Bigr "
        "biggl biggr Biggl Biggr mathstrut nonumber notag"
    ).split()
)


SEPARATOR_COMMANDS = frozenset({"\\quad", "\\qquad"})


ALIGN_ENVS = frozenset(
    "aligned align align* split gathered gather gather* equation equation* multline multline* "
    "eqnarray eqnarray* alignedat".split()
)


MATRIX_ENVS = frozenset({"bmatrix", "pmatrix", "matrix", "Bmatrix", "smallmatrix", "vmatrix"})


#: ``\text{...}`` words that join clauses (``..., \text{ where } i = 1, 2``).
CONNECTORS = frozenset({"where", "and", "with", "for", "for all", "for any", "when"})


#: Operator names recognised when spelled with plain letters (``det(R_0)`` in the HVE paper).
PROSE_WORDS = ("diag", "det")


OPERATOR_CHARS = frozenset("+-*/=<>()[]|,'^_{}&.;:!")


OPENERS = {"{": "}", "(": ")", "[": "]", "\\{": "\\}"}


CLOSERS = {v: k for k, v in OPENERS.items()}


DELIMITER_PAIRS = {"(": ")", "[": "]", "\\{": "\\}", "|": "|", "\\|": "\\|", ".": None}


LABEL = re.compile(r"^\s*\(?[A-Za-z0-9]{1,4}\)\s*$")


@dataclass(frozen=True, slots=True)
class Token:
    """One lexical token: ``kind`` is letter, number, cmd, op, sym, text, tag, begin, end,
    left, right, sep, newline or eof; ``space`` tells whether whitespace preceded it."""

    kind: str
    value: str
    pos: int
    end: int
    space: bool = False
    arg: str | None = None


def read_braced(text: str, i: int, stop: int, what: str) -> tuple[str, int]:
    """The raw content of the ``{...}`` group starting at or after ``i`` and the index after it."""
    while i < stop and text[i].isspace():
        i += 1
    if i >= stop or text[i] != "{":
        raise LatexParseError(f"{what} needs a braced argument", text, min(i, len(text)))
    depth, j = 0, i
    while j < stop:
        ch = text[j]
        if ch == "\\":
            j += 2
            continue
        if ch == "{":
            depth += 1
        elif ch == "}":
            depth -= 1
            if depth == 0:
                return text[i + 1 : j], j + 1
        j += 1
    raise LatexParseError(f"unbalanced '{{' in the argument of {what}", text, i)


def read_delimiter(text: str, i: int, stop: int, what: str) -> tuple[str, int]:
    """The delimiter after ``\\left``/``\\right`` and the index after it."""
    while i < stop and text[i].isspace():
        i += 1
    if i < stop and text[i] in "()[]|.":
        return text[i], i + 1
    if i + 1 < stop and text[i] == "\\" and text[i + 1] in "{}|":
        return text[i : i + 2], i + 2
    raise LatexParseError(f"{what} must be followed by a delimiter", text, min(i, len(text)))


def tokenize(text: str, start: int = 0, stop: int | None = None) -> list[Token]:
    """Split ``text[start:stop]`` into tokens; positions are offsets in ``text``."""
    stop = len(text) if stop is None else stop
    toks: list[Token] = []
    i, space = start, False

    def emit(kind: str, value: str, end: int, arg: str | None = None) -> None:
        nonlocal space
        toks.append(Token(kind, value, i, end, space, arg))
        space = False

    while i < stop:
        ch = text[i]
        if ch.isspace() or ch == "~":
            space, i = True, i + 1
            continue
        if ch == "\\":
            j = i + 1
            if j < stop and text[j].isascii() and text[j].isalpha():
                while j < stop and text[j].isascii() and text[j].isalpha():
                    j += 1
                name = text[i:j]
                if name in ("\\begin", "\\end"):
                    env, k = read_braced(text, j, stop, name)
                    emit(name[1:], env.strip(), k)
                elif name in TEXT_COMMANDS or name == "\\tag":
                    content, k = read_braced(text, j, stop, name)
                    emit("tag" if name == "\\tag" else "text", name, k, content)
                elif name in ("\\left", "\\right"):
                    delim, k = read_delimiter(text, j, stop, name)
                    emit(name[1:], delim, k)
                elif name == "\\forall":          # the quantifier reads as the words "for all"
                    emit("text", "\\text", j, "for all")
                    k = j
                elif name in IGNORED:
                    space, k = True, j
                elif name in SEPARATOR_COMMANDS:
                    emit("sep", name, j)
                    k = j
                else:
                    emit("cmd", name, j)
                    k = j
                i = k
                continue
            if j >= stop:
                raise LatexParseError("lone backslash", text, i)
            c = text[j]
            if c == "\\":
                emit("newline", "\\\\", j + 1)
            elif c in ",;:!>":
                space = True  # thin spaces are layout
            elif c == " ":
                emit("sep", "\\ ", j + 1)
            elif c in "{}|":
                emit("sym", "\\" + c, j + 1)
            else:
                raise LatexParseError(f"unsupported control symbol '\\{c}'", text, i)
            i = j + 1
            continue
        if ch.isascii() and ch.isalpha():
            emit("letter", ch, i + 1)
            i += 1
        elif "0" <= ch <= "9":      # digits 0-9 only (str.isdigit takes ² and Arabic-Indic digits)
            j = i
            while j < stop and "0" <= text[j] <= "9":
                j += 1
            if j + 1 < stop and text[j] == "." and "0" <= text[j + 1] <= "9":
                j += 1
                while j < stop and "0" <= text[j] <= "9":
                    j += 1
            check_number_text(text[i:j], f"printed display, position {i}")
            emit("number", text[i:j], j)
            i = j
        elif text.startswith("...", i):
            emit("cmd", "\\dots", i + 3)
            i += 3
        elif ch in OPERATOR_CHARS:
            emit("op", ch, i + 1)
            i += 1
        else:
            raise LatexParseError(f"unexpected character {ch!r}", text, i)
    return toks


def opener_key(t: Token) -> str | None:
    if t.kind == "op" and t.value in ("{", "(", "["):
        return t.value
    if t.kind == "sym" and t.value == "\\{":
        return "\\{"
    if t.kind == "left":
        return "left"
    if t.kind == "begin":
        return "begin:" + t.value
    return None


def closer_key(t: Token) -> str | None:
    if t.kind == "op" and t.value in ("}", ")", "]"):
        return CLOSERS[t.value]
    if t.kind == "sym" and t.value == "\\}":
        return "\\{"
    if t.kind == "right":
        return "left"
    if t.kind == "end":
        return "begin:" + t.value
    return None


def describe_token(t: Token) -> str:
    if t.kind in ("begin", "end"):
        return f"\\{t.kind}{{{t.value}}}"
    if t.kind in ("left", "right"):
        return f"\\{t.kind}{t.value}"
    return t.value


def matching_close(text: str, toks: list[Token]) -> dict[int, int]:
    """Pair every opening delimiter with its closer (both directions) or raise."""
    stack: list[int] = []
    match: dict[int, int] = {}
    for k, t in enumerate(toks):
        if opener_key(t) is not None:
            stack.append(k)
        elif (key := closer_key(t)) is not None:
            if not stack:
                raise LatexParseError(f"unmatched '{describe_token(t)}'", text, t.pos)
            opener = toks[stack[-1]]
            if opener_key(opener) != key:
                raise LatexParseError(
                    f"'{describe_token(t)}' closes '{describe_token(opener)}' opened at position {opener.pos}",
                    text,
                    t.pos,
                )
            o = stack.pop()
            match[o], match[k] = k, o
    if stack:
        t = toks[stack[-1]]
        raise LatexParseError(f"unclosed '{describe_token(t)}'", text, t.pos)
    return match


def demote_separators(toks: list[Token]) -> list[Token]:
    r"""Turn ``\quad``/``\ `` into plain space except at top level and directly inside ``[ ]``.

    Why: separators split clauses (``a = b, \quad c = d``) and vector entries (``[F_1 \ F_2]``);
    anywhere else (inside parentheses, fractions, matrices) they are only layout.
    """
    out: list[Token] = []
    stack: list[str] = []  # 'keep' / 'space' / 'transparent'
    space_pending = False
    for k, t in enumerate(toks):
        if space_pending:
            t = replace(t, space=True)
            space_pending = False
        if t.kind == "sep":
            kinds = [s for s in stack if s != "transparent"]
            if kinds and kinds[-1] == "space":
                space_pending = True
                continue
        if opener_key(t) is not None:
            after_boxed = k > 0 and toks[k - 1].kind == "cmd" and toks[k - 1].value == "\\boxed"
            if (t.kind == "begin" and t.value in ALIGN_ENVS) or (t.value == "{" and after_boxed):
                stack.append("transparent")
            elif (t.kind == "op" and t.value == "[") or (t.kind == "left" and t.value == "["):
                stack.append("keep")
            else:
                stack.append("space")
        elif closer_key(t) is not None and stack:
            stack.pop()
        out.append(t)
    return out








def is_relation(t: Token) -> bool:
    return (t.kind == "op" and t.value in "=<>") or (t.kind == "cmd" and t.value in RELATIONS)


def is_binary(t: Token) -> bool:
    return (t.kind == "op" and t.value in "+-*/") or (t.kind == "cmd" and t.value in MULTIPLY)
