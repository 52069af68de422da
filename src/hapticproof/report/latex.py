r"""LaTeX documents and displays in the papers' notation (all printing of the toolkit lives here and
in :mod:`hapticproof.core.notation`).

The printer maps SymPy symbols back to the names a paper prints (``K_{01}``, ``t_d``, ``z_a``,
``\omega``), writes ``c`` as ``\cos(\omega T)`` when asked, and renders conditions, matrices
and whole documents (amsmath, T1 fonts) that compile with pdflatex from texlive-latex-base and
-recommended alone.

The expression printer itself is :func:`hapticproof.core.notation.to_latex` (the audit records
derived results with it).

Long displays are cut at their top-level relations and binary operators into pieces that the
document lays out like words of a paragraph (:func:`display_lines`, :func:`display_pieces`), so
no display runs off the page; the HTML view (:mod:`hapticproof.report.html`) uses the same pieces.

>>> display_pieces(r"b > \frac{KT}{2} + B - \left(x + y\right)")
['b', '{}> \\frac{KT}{2}', '{}+ B', '{}- \\left(x + y\\right)']
"""

from __future__ import annotations

import re
from collections.abc import Iterable, Mapping, Sequence
from typing import Any

import sympy as sp

from hapticproof.core.notation import default_name, to_latex
from hapticproof.core.texsafe import check_tex, escape_tex_text

__all__ = ["escape_text", "verbatim_block", "document", "display", "fit_display", "safe_math", "is_typesettable", "display_lines", "display_pieces", "prose_with_math", "labelled", "verdict_badge", "witness_math", "equation_block", "audit_document", "longtable", "scene_latex", "derivation_document", "derivation_fragment", "VERDICT_COLOURS"]


#: One colour per audit verdict (hex RGB), shared by the LaTeX and HTML views.
VERDICT_COLOURS = {
    "confirmed": "1E7B34",
    "conservative": "2B6CB0",
    "typo": "B7791F",
    "wrong": "C53030",
    "needs-assumption": "C05621",
    "inconsistent": "97266D",
    "malformed": "5A5A5A",
    "undecided": "718096",
}


# --------------------------------------------------------------------------------------------
# prose
# --------------------------------------------------------------------------------------------
# the escaping tables live in core.texsafe.escape_tex_text, which checks its own output


def escape_text(text: str, breakable: bool = True) -> str:
    r"""Escape plain text for LaTeX (T1 fonts): relations become mathematics, so no ``<`` is
    ever printed as an inverted exclamation mark; long words (expressions written as text)
    may break after punctuation. No ``^^`` code, comment, line end or control character gets
    through (:func:`hapticproof.core.texsafe.escape_tex_text` checks what it writes).

    >>> escape_text("b_1 > 50% & {x}")
    'b\\_1 $>$ 50\\% \\& \\{x\\}'
    >>> escape_text("b >= B + K*T/2, |B|")
    'b $\\geq$ B + K*T/2, $|$B$|$'
    """
    return escape_tex_text(text, breakable)


def verbatim_block(text: str) -> str:
    """Printed text shown verbatim (it may be OCR-damaged and not compile as LaTeX)."""
    return (r"\begin{hpverbatim}" + escape_text(text).replace("\n", " ") + r"\end{hpverbatim}")


def prose_with_math(text: str) -> str:
    r"""Quoted text with inline ``$...$`` mathematics: the mathematics is typeset when it is
    sound (:func:`is_typesettable`), the rest is escaped.

    >>> prose_with_math(r"with $K_{vmyz} = 60$, E < 0")
    'with $K_{vmyz} = 60$, E $<$ 0'
    >>> prose_with_math(r"broken $\frac{a}{$ math")
    'broken \\$\\textbackslash{}frac\\{a\\}\\{\\$ math'
    """
    parts = re.split(r"(?<!\\)\$", text)
    if len(parts) % 2 == 0:  # an odd number of dollars: no mathematics at all
        return escape_text(text)
    out = []
    for k, part in enumerate(parts):
        if k % 2 == 0:
            out.append(escape_text(part))
        elif is_typesettable(part) and "\\\\" not in part and _laid_out_safely("$" + part + "$"):
            out.append("$" + part + "$")
        else:
            out.append(escape_text("$" + part + "$"))
    return "".join(out)


# --------------------------------------------------------------------------------------------
# the structure of a display: lines and unbreakable pieces
# --------------------------------------------------------------------------------------------
_TOKEN = re.compile(r"\\(?:begin|end)\s*\{[A-Za-z*]+\}|\\[A-Za-z]+\*?|\\.|\s+|.", re.S)


_RELATIONS = {
    "=", "<", ">", r"\leq", r"\geq", r"\le", r"\ge", r"\neq", r"\ne", r"\succeq", r"\preceq", r"\succ", r"\prec",
    r"\implies", r"\impliedby", r"\iff", r"\Rightarrow", r"\Longrightarrow", r"\Leftrightarrow",
    r"\Longleftrightarrow", r"\rightarrow", r"\longrightarrow", r"\to", r"\xrightarrow", r"\approx", r"\sim",
    r"\equiv", r"\ll", r"\gg", r"\geqslant", r"\leqslant", r"\mapsto",
}


_BINARY = {"+", "-", r"\pm", r"\mp"}


_SPACES = {r"\quad", r"\qquad"}


#: tokens after which a + or - is a sign, not a binary operator
_NOT_OPERAND = _RELATIONS | _BINARY | _SPACES | {"(", "[", ",", "^", "_", "&", r"\left", r"\cdot", r"\times",
                                                 r"\,", r"\;", r"\:", r"\ ", r"\\"}


_DELIMITED = {r"\left", r"\right", r"\middle", r"\big", r"\Big", r"\bigg", r"\Bigg", r"\bigl", r"\bigr", r"\Bigl",
              r"\Bigr", r"\biggl", r"\biggr", r"\Biggl", r"\Biggr"}


#: environments that may make up a whole display; their rows become the display's lines
_LINE_ENVIRONMENTS = {"aligned", "gathered", "split", "align", "align*", "gather", "gather*", "multline",
                      "multline*", "equation", "equation*", "alignedat"}


#: environments allowed inside a piece of inline mathematics
_INLINE_ENVIRONMENTS = {"aligned", "gathered", "bmatrix", "pmatrix", "matrix", "vmatrix", "Vmatrix", "Bmatrix",
                        "smallmatrix", "cases", "array", "split"}


def _tokens(latex: str) -> list[str]:
    return _TOKEN.findall(latex)


def _env(token: str) -> tuple[str, str] | None:
    match = re.fullmatch(r"\\(begin|end)\s*\{([A-Za-z*]+)\}", token)
    return (match.group(1), match.group(2)) if match else None


def _depths(tokens: Sequence[str]) -> list[int]:
    """Nesting depth before each token (braces, environments, ``\\left ... \\right``)."""
    depths, depth = [], 0
    for tok in tokens:
        env = _env(tok)
        if tok == "}" or tok == r"\right" or (env and env[0] == "end"):
            depth -= 1
        depths.append(depth)
        if tok == "{" or tok == r"\left" or (env and env[0] == "begin"):
            depth += 1
    return depths


def strip_tag(latex: str) -> tuple[str, str | None]:
    """``(latex without \\tag{...}, the tag or None)``."""
    match = re.search(r"\\tag\*?\{([^{}]*)\}", latex)
    if not match:
        return latex, None
    return (latex[: match.start()] + latex[match.end():]).strip(), match.group(1)


def _whole_environment(tokens: list[str]) -> tuple[str, list[str]] | None:
    """``(name, body tokens)`` when the tokens are exactly one line environment."""
    core = list(tokens)
    while core and core[0].isspace():
        core.pop(0)
    while core and core[-1].isspace():
        core.pop()
    if len(core) < 2:
        return None
    first, last = _env(core[0]), _env(core[-1])
    if not (first and last and first[0] == "begin" and last[0] == "end" and first[1] == last[1]
            and first[1] in _LINE_ENVIRONMENTS):
        return None
    depths = _depths(core)
    if any(d == 0 for d in depths[1:-1]):  # the environment closes before the end
        return None
    body = core[1:-1]
    if first[1] == "alignedat" and body and body[0] == "{":  # \begin{alignedat}{2}
        close = body.index("}") if "}" in body else 0
        body = body[close + 1:]
    return first[1], body


def display_lines(latex: str) -> tuple[list[str], str | None]:
    r"""The lines of a display and its tag: a display that is one ``aligned`` (``gathered``,
    ``split`` ...) environment or has top-level ``\\`` becomes its rows, alignment marks
    dropped; ``\tag{...}`` is taken out.

    >>> display_lines(r"\begin{aligned} a &= b \\ &\le c \end{aligned}")
    (['a = b', '\\le c'], None)
    >>> display_lines(r"b > B \tag{20}")
    (['b > B'], '20')
    """
    latex, tag = strip_tag(latex.strip())
    lines: list[str] = []

    def walk(tokens: list[str]) -> None:
        whole = _whole_environment(tokens)
        if whole is not None:
            tokens = whole[1]
        depths = _depths(tokens)
        current: list[str] = []
        skip_option = False
        rows: list[list[str]] = []
        for tok, depth in zip(tokens, depths):
            if skip_option:  # the optional [2pt] after \\
                if tok == "]":
                    skip_option = False
                continue
            if depth == 0 and tok == "\\\\":
                rows.append(current)
                current = []
                continue
            if depth == 0 and tok == "[" and not "".join(current).strip() and rows:
                skip_option = True
                continue
            if depth == 0 and tok == "&":
                continue
            current.append(tok)
        rows.append(current)
        rows = [r for r in rows if "".join(r).strip()]
        if whole is None and len(rows) == 1:
            lines.append(re.sub(r"\s+", " ", "".join(rows[0])).strip())
            return
        for row in rows:
            walk(row)

    walk(_tokens(latex))
    return (lines or ([latex] if latex else [])), tag


def display_pieces(line: str) -> list[str]:
    r"""Cut one line of a display before its top-level relations and binary ``+``/``-``
    (and after top-level commas) into pieces that are typeset unbroken; a piece after the
    first starts with ``{}`` so its operator keeps binary spacing.

    >>> display_pieces(r"\frac{a + b}{2} \leq -c, \quad d")
    ['\\frac{a + b}{2}', '{}\\leq -c,\\,', '\\quad d']
    """
    return [piece for piece, _ in display_breaks(line)]


def display_breaks(line: str) -> list[tuple[str, int]]:
    r"""The pieces of :func:`display_pieces`, each with the number of plain parentheses
    (``(``, ``[``, ``\{``) open where it starts: breaking there is possible but worse.

    >>> display_breaks(r"a = (b + c) + d")
    [('a', 0), ('{}= (b', 0), ('{}+ c)', 1), ('{}+ d', 0)]
    """
    tokens = _tokens(line)
    depths = _depths(tokens)
    pieces: list[list[str]] = [[]]
    levels = [0]
    previous = ""  # last significant top-level token
    parens = 0  # plain ( [ \{ open at the top level
    delimiter = ""  # the command whose delimiter comes next (\left, \bigl, ...)
    for tok, depth in zip(tokens, depths):
        if tok.isspace():
            pieces[-1].append(tok)
            continue
        if delimiter:
            pieces[-1].append(tok)
            if depth == 0:
                previous = "(" if delimiter.endswith("l") or delimiter == r"\left" else ")"
            delimiter = ""
            continue
        if depth == 0 and "".join(pieces[-1]).strip():
            binary = tok in _BINARY and previous and previous not in _NOT_OPERAND
            if tok in _RELATIONS or binary or tok in _SPACES:
                pieces.append([])
                levels.append(parens)
        pieces[-1].append(tok)
        if tok in _DELIMITED:
            delimiter = tok
        if depth == 0:
            previous = tok
            parens += tok in ("(", "[", r"\{", r"\lbrace")
            parens -= tok in (")", "]", r"\}", r"\rbrace") and parens > 0
            if tok == ",":
                pieces.append([])
                levels.append(parens)
    out = []
    for k, (piece, level) in enumerate((p, lv) for p, lv in zip(pieces, levels) if "".join(p).strip()):
        text = "".join(piece).strip()
        first = _tokens(text)[0]
        text = ("{}" + text) if k and (first in _RELATIONS or first in _BINARY) else text
        out.append((text + r"\," if text.endswith(",") else text, level))  # the space a comma is followed by
    return out


def _joined_pieces(line: str) -> str:
    """The pieces of a line as LaTeX, with TeX's order of preference for breaks: after a
    comma or before a quad, then before a relation, then before a binary operator; breaks
    inside parentheses are discouraged."""
    out = []
    for k, (piece, level) in enumerate(display_breaks(line)):
        if k:
            first = _tokens(piece[2:] if piece.startswith("{}") else piece)[0]
            penalty = 100 if first in _RELATIONS else 200 if first in _BINARY else 0
            penalty = min(900, penalty + 300 * level)
            out.append(r"\allowbreak" if penalty == 0 else r"\penalty" + str(penalty) + " ")
        out.append(r"\hpfit{" + _inline_safe(piece) + "}")
    return "".join(out)


# --------------------------------------------------------------------------------------------
# displays in documents
# --------------------------------------------------------------------------------------------
def display(latex: str) -> str:
    """A plain amsmath display (``equation*``) to paste into a paper: content with its own
    environments (aligned, bmatrix) is kept as it is; bare multi-line content goes into
    ``gathered`` (alignment marks dropped).

    >>> display("b > 0")
    '\\\\begin{equation*}b > 0\\\\end{equation*}'
    """
    if "\\begin{" in latex:
        return "\\begin{equation*}" + latex + "\\end{equation*}"
    if "\\\\" in latex or "&" in latex:
        body = latex.replace("&", "")
        return "\\begin{equation*}\\begin{gathered}" + body + "\\end{gathered}\\end{equation*}"
    return "\\begin{equation*}" + latex + "\\end{equation*}"


def _inline_safe(piece: str) -> str:
    """A piece as inline mathematics: ``split`` is only allowed in displays (use aligned)."""
    return piece.replace(r"\begin{split}", r"\begin{aligned}").replace(r"\end{split}", r"\end{aligned}")


def fit_display(latex: str) -> str:
    r"""A display for the documents of :func:`document`: each line is set like a paragraph of
    unbreakable pieces (:func:`display_pieces`), so a long line breaks at its relations and
    operators, and only a piece wider than the line (a wide matrix) is scaled down.

    >>> print(fit_display(r"b > \frac{KT}{2} + B"))
    \begin{hpdisplay}
    \hpline{\hpfit{b}\penalty100 \hpfit{{}> \frac{KT}{2}}\penalty200 \hpfit{{}+ B}}
    \end{hpdisplay}
    """
    lines, tag = display_lines(latex)
    rows = []
    for k, line in enumerate(lines):
        pieces = _joined_pieces(line)
        if tag is not None and k == len(lines) - 1:
            pieces += r"\hptag{" + escape_text(tag) + "}"
        rows.append(r"\hpline{" + pieces + "}")
    return "\\begin{hpdisplay}\n" + "\n".join(rows) + "\n\\end{hpdisplay}"


_KNOWN = set(
    r"""frac dfrac tfrac cfrac binom left right middle cos sin tan cot sec csc exp log ln sqrt sinh cosh tanh arg
    omega alpha beta gamma delta epsilon varepsilon zeta eta theta vartheta iota kappa lambda mu nu xi pi rho sigma
    tau phi varphi chi psi Delta Gamma Theta Lambda Sigma Phi Psi Omega Pi Xi
    Re Im min max sup inf sum prod lim to infty cdot times div pm mp leq geq le ge neq ne quad qquad text mathrm
    textrm mathit mathsf mathtt mathbf boldsymbol mathcal mathscr mathbb operatorname det dots cdots ldots vdots ddots
    begin end hline boxed ell partial nabla forall exists in notin subset subseteq cup cap emptyset
    implies impliedby iff Rightarrow rightarrow Leftarrow leftarrow longrightarrow xrightarrow Longrightarrow
    Leftrightarrow Longleftrightarrow mapsto approx sim equiv ll gg succ prec succeq preceq geqslant leqslant
    vert Vert lvert rvert lVert rVert langle rangle lbrace rbrace mid prime displaystyle textstyle
    dot ddot bar hat tilde vec check overline underline widehat widetilde overbrace underbrace
    Res big Big bigg Bigg bigl bigr Bigl Bigr biggl biggr int iint oint limits nolimits
    wedge vee neg lnot land lor circ ast star bullet perp parallel overset underset stackrel substack
    phantom hphantom vphantom mathop mathrel mathbin mathord tag""".split()
)


_ENVIRONMENTS = _INLINE_ENVIRONMENTS | _LINE_ENVIRONMENTS


def _known_commands(latex: str) -> bool:
    if not all(cmd in _KNOWN for cmd in re.findall(r"\\([A-Za-z]+)", latex)):
        return False
    envs = re.findall(r"\\(?:begin|end)\s*\{([A-Za-z*]+)\}", latex)
    return all(env in _INLINE_ENVIRONMENTS or env in _LINE_ENVIRONMENTS for env in envs)


def is_balanced(text: str) -> bool:
    """Braces, environments and ``\\left``/``\\right`` pairs nest properly (escaped braces
    ignored): what TeX needs. Unbalanced parentheses are printed as they are (an interval
    ``[0, \\infty)``, or OCR damage the audit reports)."""
    stripped = re.sub(r"\\[{}]", "", text)
    depth = 0
    for ch in stripped:
        depth += ch == "{"
        depth -= ch == "}"
        if depth < 0:
            return False
    if depth:
        return False
    stack: list[str] = []
    for kind, name in re.findall(r"\\(begin|end)\{([A-Za-z*]+)\}", text):
        if kind == "begin":
            stack.append(name)
        elif not stack or stack.pop() != name:
            return False
    return not stack and len(re.findall(r"\\left\b", text)) == len(re.findall(r"\\right\b", text))


def is_typesettable(latex: str | None) -> bool:
    r"""True when ``latex`` is structurally sound and uses only known commands (OCR-damaged
    printed text often is not; it is then shown verbatim).

    >>> is_typesettable(r"\frac{a}{b}"), is_typesettable(r"\frac{a}{b}}"), is_typesettable(r"\foo x")
    (True, False, False)
    """
    if not latex or not latex.strip():
        return False
    body, _ = strip_tag(latex)
    if r"\tag" in body:
        return False
    # what TeX reads (^^ codes, \csname ...), the whole text with its tag, before the layout
    return is_balanced(body) and _known_commands(body) and check_tex(latex, _KNOWN, _ENVIRONMENTS) is None


def safe_math(latex: str | None, fit: bool = True) -> str:
    """Display ``latex`` as mathematics when it is structurally sound, verbatim otherwise.

    OCR-damaged printed equations may contain commands that do not compile; only balanced
    strings that use known commands are typeset. ``fit`` (default) gives the breakable
    display of :func:`fit_display` (which needs :func:`document`'s preamble), else a plain
    amsmath display.
    """
    if is_typesettable(latex):
        out = fit_display(latex) if fit else display(latex)
        if _laid_out_safely(out):  # the layout drops & and \\: check what it made
            return out
    return verbatim_block(latex or "(empty)")


#: the commands and environment of the layout (:func:`fit_display`, :func:`math_cell`) and
#: those :func:`escape_text` writes
_LAYOUT = frozenset({"hpfit", "hpline", "hptag", "hpcell", "penalty", "allowbreak", "textbackslash",
                     "textasciicircum", "sim", "dots", "leq", "geq", "neq", "Rightarrow", "rightarrow",
                     "Leftrightarrow", "times", "approx", "omega", "theta", "alpha", "beta", "delta", "lambda",
                     "tau", "infty", "pm"})


#: the environments whose cells ``&`` separates: anywhere else (``\text{a & b}``, a group, a
#: line of a display once the layout has dropped its own marks) TeX stops the report
#: with the most cells a row may have (amsmath: 10 matrix columns, 2 in cases and split); array
#: and alignedat count their columns from an argument, so their ``&`` is shown verbatim
_ALIGNMENTS = {"aligned": None, "align": None, "align*": None, "split": 2, "cases": 2,
               **dict.fromkeys(("bmatrix", "pmatrix", "matrix", "vmatrix", "Vmatrix", "Bmatrix", "smallmatrix"), 10)}
#: the environments whose rows ``\\`` ends
_ROWS = set(_ALIGNMENTS) | {"gathered", "gather", "gather*", "multline", "multline*", "array", "alignedat"}


def _laid_out_safely(out: str) -> bool:
    return check_tex(out, _KNOWN | _LAYOUT, _ENVIRONMENTS | {"hpdisplay"}, alignments=_ALIGNMENTS, rows=_ROWS) is None


def labelled(label: str, body: str) -> str:
    r"""A labelled block: the label (``Printed``, ``Derived``, ``Corrected``) on its own line,
    kept with what follows.

    >>> labelled("Derived", "x")
    '\\hplabel{Derived}\nx'
    """
    return r"\hplabel{" + escape_text(label) + "}\n" + body


def verdict_badge(verdict: str) -> str:
    r"""The verdict as a coloured badge (colours of :data:`VERDICT_COLOURS`).

    >>> verdict_badge("needs-assumption")
    '\\hpverdict{hpneedsassumption}{needs-assumption}'
    """
    return r"\hpverdict{hp" + re.sub(r"[^a-z]", "", verdict) + "}{" + escape_text(verdict) + "}"


def witness_math(witness: Mapping[str, Any] | None) -> str:
    r"""A witness as inline mathematics, ``$K = 1$, $b = \tfrac{17}{16}$``.

    >>> witness_math({"K": "1", "b": "17/16", "z_a": "-1/10"})
    '$K = 1$, $b = \\tfrac{17}{16}$, $z_{a} = -\\tfrac{1}{10}$'
    """
    from hapticproof.core.evidence import to_jsonable

    items = []
    for name, value in to_jsonable(dict(witness or {})).items():
        items.append("$" + name_math(name) + " = " + value_math(value) + "$" if value_math(value) is not None
                     else "$" + name_math(name) + "$ = " + escape_text(str(value)))
    return ", ".join(items)


def name_math(name: str) -> str:
    """A witness name as LaTeX (``z_a`` -> ``z_{a}``, ``omega`` -> ``\\omega``)."""
    return default_name(name) if re.fullmatch(r"[A-Za-z]+(_[A-Za-z0-9]+)?|[A-Za-z]\d+", name) else (
        r"\text{" + escape_text(name) + "}")


def value_math(value: Any) -> str | None:
    r"""A witness value (JSON form) as LaTeX, or None when it is not a number, a vector or a
    matrix of numbers.

    >>> value_math("-3/4"), value_math([["1", "0"], ["0", "-1/2"]])
    ('-\\tfrac{3}{4}', '\\begin{bmatrix}1 & 0\\\\0 & -\\tfrac{1}{2}\\end{bmatrix}')
    """
    if isinstance(value, list) and value:
        if all(isinstance(row, list) and row for row in value):
            rows = [[value_math(v) for v in row] for row in value]
            if all(v is not None for row in rows for v in row):
                return r"\begin{bmatrix}" + r"\\".join(" & ".join(row) for row in rows) + r"\end{bmatrix}"
            return None
        items = [value_math(v) for v in value]
        return r"\left(" + ", ".join(items) + r"\right)" if all(v is not None for v in items) else None
    if isinstance(value, dict) and "approx" in value:
        return value_math(value["approx"])
    text = str(value)
    match = re.fullmatch(r"(-?)(\d+)/(\d+)", text)
    if match:
        return match.group(1) + r"\tfrac{" + match.group(2) + "}{" + match.group(3) + "}"
    if re.fullmatch(r"-?\d+(\.\d+)?(e-?\d+)?", text):
        return text
    return None


# --------------------------------------------------------------------------------------------
# documents
# --------------------------------------------------------------------------------------------
_PREAMBLE = r"""\documentclass[10pt]{article}
\usepackage[T1]{fontenc}
\IfFileExists{lmodern.sty}{\usepackage{lmodern}}{}
\usepackage[a4paper,margin=2cm]{geometry}
\usepackage{amsmath,amssymb}
\IfFileExists{mathrsfs.sty}{\usepackage{mathrsfs}}{\providecommand{\mathscr}{\mathcal}}
\usepackage{graphicx,array,longtable,xcolor}
\usepackage[hidelinks]{hyperref}
\allowdisplaybreaks
\setlength{\parindent}{0pt}
\setlength{\parskip}{2pt plus 1pt}
\setlength{\emergencystretch}{3em}
\newcommand{\Res}{\operatorname{Res}}
% hapticproof displays: a line of unbreakable pieces, broken like a paragraph; a piece wider
% than the line (a wide matrix) is scaled down to it
\newsavebox{\hppiece}
\newlength{\hpmaxwidth}
\newlength{\hpindent}\setlength{\hpindent}{1.5em}
\newcommand{\hpfit}[1]{\sbox{\hppiece}{$\displaystyle #1$}%
  \ifdim\wd\hppiece>\hpmaxwidth\sbox{\hppiece}{\resizebox{\hpmaxwidth}{!}{\usebox{\hppiece}}}\fi
  \ifdim\dimexpr\ht\hppiece+\dp\hppiece\relax>.7\textheight
    \sbox{\hppiece}{\resizebox*{!}{.7\textheight}{\usebox{\hppiece}}}\fi
  \usebox{\hppiece}}
\newenvironment{hpdisplay}{\par\addvspace{3pt}\begingroup\raggedright
  \setlength{\lineskiplimit}{2pt}\setlength{\lineskip}{4pt}\setlength{\leftskip}{\hpindent}\setlength{\hpmaxwidth}{\dimexpr\linewidth-3\hpindent\relax}}%
  {\par\endgroup\addvspace{6pt}}
\newcommand{\hpline}[1]{{\hangindent=2\hpindent\hangafter=1\noindent#1\par}}
\newcommand{\hptag}[1]{\hfill\mbox{(#1)}}
\newcommand{\hplabel}[1]{\par\addvspace{4pt}\noindent{\small\sffamily\bfseries #1}\par\nopagebreak}
\newenvironment{hpverbatim}{\par\addvspace{3pt}\begingroup\raggedright\setlength{\leftskip}{\hpindent}%
  \small\ttfamily\noindent}{\par\endgroup\addvspace{6pt}}
\newcommand{\hpverdict}[2]{\colorbox{#1}{\strut\textcolor{white}{\sffamily\bfseries\small #2}}}
\newcommand{\hpequation}[3]{\par\addvspace{12pt}\needspace\noindent\hypertarget{#1}{}%
  {\large\bfseries #2}\hfill #3\par\nopagebreak\addvspace{2pt}}
\newcommand{\needspace}{\penalty-100\relax}
\newcommand{\hpcell}[1]{\setlength{\hpmaxwidth}{\linewidth}\setlength{\lineskiplimit}{2pt}%
  \setlength{\lineskip}{4pt}\vspace{0pt}#1\par\vspace{3pt}}
"""


def _colour_definitions() -> str:
    return "\n".join(r"\definecolor{hp" + re.sub(r"[^a-z]", "", v) + "}{HTML}{" + hexa + "}"
                     for v, hexa in VERDICT_COLOURS.items())


def document(title: str, sections: Iterable[tuple[str, str]], intro: str = "") -> str:
    """A complete document (T1 fonts, amsmath) with the given (heading, body) sections.

    Only packages of texlive-latex-base and -recommended are used (Latin Modern when
    installed); the display macros of :func:`fit_display` are defined in the preamble.
    """
    parts = [
        _PREAMBLE + _colour_definitions(),
        r"\begin{document}",
        r"\section*{" + escape_text(title) + "}",
    ]
    if intro:
        parts.append(intro)
    for heading, body in sections:
        if heading:
            parts.append(r"\subsection*{" + escape_text(heading) + "}")
        if body:
            parts.append(body)
    parts.append(r"\end{document}")
    return "\n".join(parts) + "\n"


def longtable(header: Sequence[str], rows: Iterable[Sequence[str]], widths: Sequence[float]) -> str:
    r"""A table that wraps its cells (ragged right) and breaks across pages. Cells are LaTeX;
    ``widths`` are fractions of the line width.

    >>> print(longtable(["a", "b"], [["1", "2"]], [0.3, 0.6]))
    \begin{longtable}{@{}>{\raggedright\arraybackslash}p{0.3\linewidth}>{\raggedright\arraybackslash}p{0.6\linewidth}@{}}
    \textbf{a} & \textbf{b}\\ \hline\endhead
    1 & 2\\[3pt]
    \end{longtable}
    """
    spec = "".join(r">{\raggedright\arraybackslash}p{" + f"{w:g}" + r"\linewidth}" for w in widths)
    lines = [r"\begin{longtable}{@{}" + spec + "@{}}",
             " & ".join(r"\textbf{" + escape_text(h) + "}" for h in header) + r"\\ \hline\endhead"]
    lines += [" & ".join(row) + r"\\[3pt]" for row in rows]
    lines.append(r"\end{longtable}")
    return "\n".join(lines)


def math_cell(latex: str) -> str:
    r"""Mathematics in a table cell: pieces that wrap at the column's width.

    >>> math_cell("a + b")
    '\\hpcell{\\hpfit{a}\\penalty200 \\hpfit{{}+ b}}'
    """
    if is_typesettable(latex):
        lines, _ = display_lines(latex)
        out = r"\hpcell{" + r"\allowbreak".join(_joined_pieces(line) for line in lines) + "}"
        if _laid_out_safely(out):
            return out
    return r"{\small\ttfamily " + escape_text(latex) + "}"


def derivation_document(title: str, items: Sequence[tuple[str, str]], notes: Sequence[tuple[str, str]] = (),
                        intro: str = "", sections: Sequence[tuple[str, str]] = ()) -> str:
    r"""A complete document of derived displays: ``items`` are ``(label, LaTeX)``, each shown
    labelled and breakable; ``notes`` are ``(label, plain text)`` (the decision); ``sections``
    are further ``(heading, LaTeX body)``.

    >>> doc = derivation_document("demo", [("condition", "b > 0")], [("verdict", "proved (b = 1 > 0)")])
    >>> doc.startswith(r"\documentclass") and r"\hplabel{condition}" in doc and "$>$" in doc
    True
    """
    body = [labelled(label, safe_math(latex)) for label, latex in items]
    out: list[tuple[str, str]] = [("Derived conditions", "\n".join(body))] if body else []
    out += list(sections)
    if notes:
        out.append(("Decision", "\n".join(r"\textbf{" + escape_text(label) + r":} " + escape_text(text) + r"\par"
                                          for label, text in notes)))
    return document(title, out, intro=intro)


def derivation_fragment(items: Sequence[tuple[str, str]]) -> str:
    r"""The displays of :func:`derivation_document` as plain amsmath displays, each after a
    ``%`` comment with its label: to paste into a paper (needs only amsmath).

    >>> print(derivation_fragment([("condition", "b > 0")]))
    % condition
    \begin{equation*}b > 0\end{equation*}
    """
    for label, latex in items:
        if not (is_typesettable(latex) and _laid_out_safely(display(latex))):
            from hapticproof.core.errors import DerivationError

            raise DerivationError(f"derived display {' '.join(label.split())[:60]!r} is not safe to typeset "
                                  "as a fragment (a bug, or symbol names TeX would read as commands)")
    return "\n".join("% " + " ".join(label.split()) + "\n" + display(latex) for label, latex in items)


# --------------------------------------------------------------------------------------------
# audit reports
# --------------------------------------------------------------------------------------------
def anchor(paper: str, equation: str, single: bool = True) -> str:
    """The anchor of an equation in a report: ``eq-17`` (one paper) or ``hve-eq-17``.

    >>> anchor("hve", "17"), anchor("hve", "sec4 dual", single=False)
    ('eq-17', 'hve-eq-sec4-dual')
    """
    eq = re.sub(r"[^A-Za-z0-9_.-]+", "-", equation)
    return f"eq-{eq}" if single else f"{re.sub(r'[^A-Za-z0-9_.-]+', '-', paper)}-eq-{eq}"


def detail_text(text: str) -> str:
    r"""A finding's detail: prose whose quoted LaTeX (a repair ``'+ \frac{KT}{2}' -> '- \frac{KT}{2}'``)
    is typeset as mathematics when it is sound (:func:`prose_with_math`), the rest escaped.

    >>> print(detail_text("one edit: '+ \\frac{K T}{2}' -> '- \\frac{K T}{2}' at position 7"))
    one edit: $+ \frac{K T}{2}$ $\rightarrow$ $- \frac{K T}{2}$ at position 7
    """
    if "$" in text:
        return escape_text(text)
    # a quotation, not a prime (Z'): opened after a space or a bracket, holding a LaTeX command
    quoted = re.sub(r"(?<![^\s(\[])'([^'\n]*\\[A-Za-z][^'\n]*)'(?=[\s,;:.)\]]|$)", lambda m: "$" + m.group(1) + "$", text)
    return prose_with_math(quoted)


def equation_block(result: Any, anchor_id: str = "", show_printed: bool = True, evidence: bool = True) -> str:
    """One audited equation: heading with the verdict badge, the detail, then the labelled
    printed, derived and corrected displays and the evidence (method, witness)."""
    where = ", ".join(x for x in (result.kind, f"Section {result.section}" if result.section else "") if x)
    head = (r"\hpequation{" + anchor_id + "}{(" + escape_text(result.id) + r")\quad\normalsize\mdseries "
            + escape_text(where) + "}{" + verdict_badge(result.verdict.value) + "}")
    body = [head, detail_text(result.detail)]
    if result.assumptions:
        body.append(r"\par{\small\textit{Assumptions:} " + escape_text(result.assumptions) + "}")
    if show_printed:
        if result.kind == "claim":
            body.append(labelled("Printed (quoted)", r"\begin{quote}\itshape " + prose_with_math(result.printed)
                                 + r"\end{quote}"))
        else:
            body.append(labelled("Printed", safe_math(result.printed)))
    if result.derived:
        body.append(labelled("Derived", safe_math(result.derived)))
    if result.corrected:
        body.append(labelled("Corrected", safe_math(result.corrected)))
    if evidence:
        ev = result.evidence
        line = r"{\small\textit{Evidence:} " + escape_text(ev.method)
        if ev.instances is not None:
            line += f", {ev.instances} instances"
        if ev.witness:
            line += "; witness " + witness_math(dict(ev.witness))
        body.append(r"\par" + line + "}")
    return "\n".join(body)


def _summary_table(reports: Sequence[Any], single: bool) -> str:
    """Counts per verdict with links to each equation of that verdict."""
    from hapticproof.core.evidence import Verdict

    rows = []
    for verdict in Verdict:
        links = [r"\hyperlink{" + anchor(rep.paper, r.id, single) + "}{" + escape_text(
            ("" if single else rep.paper + " ") + "(" + r.id + ")") + "}"
                 for rep in reports for r in rep.results if r.verdict == verdict]
        if links:
            rows.append([verdict_badge(verdict.value), str(len(links)), ", ".join(links)])
    total = sum(len(rep.results) for rep in reports)
    rows.append([r"\textbf{total}", str(total), ""])
    return longtable(["verdict", "count", "equations"], rows, [0.19, 0.07, 0.68])


def audit_document(reports: Sequence[Any], title: str | None = None) -> str:
    """The LaTeX errata sheet of one or more :class:`~hapticproof.audit.runner.AuditReport`: counts
    per verdict with links, then every equation with printed / derived / corrected."""
    reports = list(reports)
    single = len(reports) == 1
    if title is None:
        title = f"Audit of {reports[0].title} ({reports[0].paper})" if single else "hapticproof audit"
    sections: list[tuple[str, str]] = [("Summary", _summary_table(reports, single))]
    for rep in reports:
        blocks = [equation_block(r, anchor(rep.paper, r.id, single)) for r in rep.results]
        heading = "" if single else f"{rep.paper}: {rep.title}"
        notation = getattr(rep, "notation", None)
        if notation:        # the toolkit's names this report prints in the paper's stead (gamma = cos wh)
            blocks.insert(0, r"\textbf{notation:} " + escape_text(", ".join(f"{k} = {v}" for k, v in notation.items())) + r"\par")
        sections.append((heading, "\n\n".join(blocks)))
    return document(title, sections)


# --------------------------------------------------------------------------------------------
# scenes
# --------------------------------------------------------------------------------------------
def scene_latex(scene: Any) -> str:
    r"""A scene as mathematics (what it is, not what is derived from it), for notebooks.
    Parameters that are their own symbol are listed as free.

    >>> from hapticproof.systems.singleuser import SingleUserScene
    >>> scene_latex(SingleUserScene.virtual_wall(delay=2, b="0.02"))
    '\\text{single-user scene, forward difference: }\\ H(z) = \\frac{B \\left(z - 1\\right)}{T z} + K,\\quad t_d = 2 T,\\quad b = \\frac{1}{50},\\quad z_{a} = 0;\\quad \\text{free: } B, K, T'
    """
    kind = type(scene).__name__
    free = sorted((s for s in getattr(scene, "parameters", set()) if isinstance(s, sp.Symbol)), key=str)
    names = scene.naming() if hasattr(scene, "naming") else None     # the scene's own names for its roles
    shown: list[str] = []

    def role(field_: str, default: str) -> tuple[str, str]:
        name = names.role(field_, default) if names is not None else default
        return name, to_latex(sp.Symbol(name))

    def value(name: str, latex_name: str, v: Any) -> None:
        v = sp.sympify(v)
        if not (isinstance(v, sp.Symbol) and v.name == name):
            shown.append(latex_name + " = " + to_latex(v))

    def vector(values: Sequence[Any]) -> str:
        return r"\left(" + ", ".join(to_latex(v) for v in values) + r"\right)"

    if kind == "SingleUserScene":
        n = scene.delay
        T = role("period", "T")[1]
        head = r"\text{single-user scene, " + scene.approximation + (" difference" if scene.approximation != "tustin" else "") + r": }\ "
        shown.append("H(z) = " + to_latex(scene.H))
        shown.append("t_d = 0" if n == 0 else f"t_d = {T}" if n == 1 else "t_d = " + to_latex(n) + f" {T}")
        value(*role("device_damping", "b"), scene.b)
        value("z_a", "z_{a}", scene.z_a)
    elif kind == "MultiUserScene":
        head = r"\text{" + f"{len(scene.b)}-user scene, {scene.approximation} difference" + r": }\ "
        shown += [role("device_damping", "b")[1] + " = " + vector(scene.b), "K_0 = " + vector(scene.K0), "B_0 = " + vector(scene.B0)]
        edges = ", ".join(f"{i + 1}{j + 1}" for i, j in scene.edges)
        shown += [r"(K, B)_{" + edges + "} = " + vector(scene.K) + ", " + vector(scene.B),
                  "n = " + vector(scene.delays), "z_{a} = " + vector(scene.z_a)]
        value(*role("period", "T"), scene.T)
    elif kind == "TeleoperatorScene":
        head = r"\text{teleoperator scene: }\ "
        shown.append("C(z) = " + to_latex(scene.C))
        value("alpha", r"\alpha", scene.alpha)
        for field_, default in (("master_mass", "m_m"), ("slave_mass", "m_s"), ("master_damping", "b_m"),
                                ("slave_damping", "b_s"), ("period", "T")):
            name, latex_name = role(field_, default)
            value(name, latex_name if name != default else default, getattr(scene, default))
    else:
        return r"\text{" + escape_text(repr(scene)) + "}"
    tail = (r";\quad \text{free: } " + ", ".join(to_latex(f) for f in free)) if free else ""
    return head + r",\quad ".join(shown) + tail
