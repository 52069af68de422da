r"""Tests of :mod:`hapticproof.core.texsafe`: the attacks of the issue and a larger hostile corpus are refused,
the bundled papers' displays are not, the tokenizer agrees with TeX itself (pdflatex reads
the same strings and lists its tokens, when pdflatex is installed), and a report compiled
with the README's command neither reads nor writes files outside what it should.
"""

from __future__ import annotations

import json
import os
import pathlib
import re
import shutil
import subprocess

import pytest

from hapticproof.report import latex as tex

from hapticproof.core.texsafe import (
    ALWAYS_REFUSED, LATEX_CATCODES, check_tex, escape_tex_text, tex_commands, tokenize,
)

HERE = pathlib.Path(__file__).parent
CORPUS = json.loads((HERE / "data" / "benign_displays.json").read_text(encoding="utf-8"))
ALLOWED = set(tex._KNOWN)  # the report's allow-list
ENVIRONMENTS = set(tex._ENVIRONMENTS)
LAYOUT = set(tex._LAYOUT)
PDFLATEX = shutil.which("pdflatex")
needs_pdflatex = pytest.mark.skipif(PDFLATEX is None, reason="pdflatex is not installed")


# --------------------------------------------------------------------------------------------
# the issue's attacks
# --------------------------------------------------------------------------------------------
def test_issue_input_through_caret_code_is_seen_and_refused():
    printed = r"b > \frac{KT}{2} + B ^^5cinput{/etc/hostname}"
    assert "\\input" in tex_commands(printed)
    assert re.findall(r"\\([A-Za-z]+)", printed) == ["frac"]  # what the old (before issue 22) allow-list looked at
    reason = check_tex(printed, ALLOWED, ENVIRONMENTS)
    assert reason is not None and "^^5c" in reason


def test_issue_immediate_openout_is_seen_and_refused():
    printed = r"b > B ^^5cimmediate^^5copenout5 pwned.tex ^^5cimmediate^^5cwrite5{owned}"
    commands = tex_commands(printed)
    assert commands.count("\\immediate") == 2 and "\\openout" in commands and "\\write" in commands
    assert check_tex(printed, ALLOWED, ENVIRONMENTS) is not None


def test_alignment_mark_between_carets_is_refused():
    # the old (before issue 22) layout drops top-level & and joins the tokens: ^&^5c became ^^5c in the PDF
    printed = r"b > a^&^5cinput{/etc/hostname}"
    assert "\\input" not in tex_commands(printed)  # TeX does not see it in the display as given ...
    assert "\\input" in tex_commands(printed.replace("&", ""))  # ... but in the laid-out display
    assert check_tex(printed, ALLOWED, ENVIRONMENTS) == "^ at offset 5 has no argument"


# --------------------------------------------------------------------------------------------
# what TeX sees
# --------------------------------------------------------------------------------------------
@pytest.mark.parametrize("text, seen", [
    (r"\^^69nput{x}", "\\input"),                       # a code inside a control-sequence name
    (r"\inp^^75t{x}", "\\input"),
    ("^^5e^5cinput{x}", "\\input"),                     # ^^5e makes the ^ of the next code
    ("^^5c^^69nput", "\\input"),
    (r"\csname input\endcsname", "\\input"),            # names built from characters
    (r"\lowercase{\csname INPUT\endcsname}", "\\input"),
    (r"\uppercase{\csname input\endcsname}", "\\INPUT"),
    ("\r\\input{x}", "\\input"),                        # CR ends a line in TeX Live: the rest is read
])
def test_tokenizer_sees_the_hidden_command(text, seen):
    assert seen in tex_commands(text)


@pytest.mark.parametrize("text, hidden", [
    (r"a % \input{x}", "\\input"),                      # a comment: TeX never reads it
    (r"a ^^M \input{x}", "\\input"),                    # ^^M ends the line: the rest is dropped
    ("^^\\input", "\\input"),                           # ^^\ is character 28, then letters
    ("^^5Cinput", "\\input"),                           # only lowercase hex: ^^5 is 'u'
    (r"\lowercase{\INPUT}", "\\input"),                 # \lowercase leaves control sequences alone
])
def test_tokenizer_does_not_invent_commands(text, hidden):
    assert hidden not in tex_commands(text)


def test_benign_commands_in_order():
    assert tex_commands(r"\frac{a}{b} + \left( x_{1}^{2} \right) \, \Re\{z\} \quad \text{if } a~b") == [
        "\\frac", "\\left", "\\right", "\\,", "\\Re", "\\{", "\\}", "\\quad", "\\text", "~"]


def test_caret_reductions_are_reported_with_their_source():
    reading = tokenize("x ^^5e^5c y ^^41")
    assert [(c.source, c.char) for c in reading.carets] == [("^^5e", "^"), ("^^5e^5c", "\\"), ("^^41", "A")]
    assert [str(t) for t in reading.tokens] == ["x", " ", "\\ ", "y", " ", "A", " "]  # ^^5c + space: \ 


def test_xetex_four_caret_codes():
    assert "\\input" in tex_commands("^^^^005cinput", engine="xetex")
    assert check_tex("^^^^005cinput", ALLOWED, engine="xetex") is not None


# --------------------------------------------------------------------------------------------
# the hostile corpus: refused, each for the reason that applies
# --------------------------------------------------------------------------------------------
HOSTILE = {
    "caret-5c": (r"b > ^^5cinput{/etc/hostname}", "^^5c"),
    "caret-5C": (r"b > ^^5Cinput{/etc/hostname}", "^^5"),
    "caret-backslash": (r"b > ^^\input{/etc/hostname}", "^^\\"),
    "caret-M": (r"b > ^^M \input{x}", "^^M"),
    "caret-in-name": (r"b > \^^69nput{/etc/hostname}", "^^69"),
    "caret-chain": (r"b > ^^5e^5cinput{/etc/hostname}", "^^5e"),
    "caret-before-8bit": ("b > ^^\u00e9", "^^"),
    "caret-at-end": ("b > x^^", "^^"),
    "caret-in-text": (r"b > \text{^^5cinput{/etc/hostname}}", "^^5c"),
    "caret-in-tag": (r"b > 0 \tag{^^5cinput /etc/hostname }", "^^5c"),
    "caret-openout": (r"^^5cimmediate^^5copenout5 x.tex", "^^5c"),
    "csname": (r"\csname input\endcsname{/etc/hostname}", "\\csname"),
    "catcode": (r"\catcode`\^=7 x", "\\catcode"),
    "lowercase": (r"\lowercase{\INPUT}", "\\lowercase"),
    "uppercase": (r"\uppercase{\csname input\endcsname}", "\\uppercase"),
    "expandafter": (r"\expandafter\input x", "\\expandafter"),
    "input": (r"\input{/etc/hostname}", "\\input"),
    "input-in-text": (r"a \text{\input{/etc/hostname}}", "\\input"),
    "input-in-inline-math-of-text": (r"\text{ $\input{/etc/hostname}$ }", "\\input"),
    "include": (r"\include{x}", "\\include"),
    "openin": (r"\openin5=/etc/hostname", "\\openin"),
    "read": (r"\read5 to\x", "\\read"),
    "write18": (r"\immediate\write18{id}", "\\immediate"),
    "special": (r"\special{ps: x}", "\\special"),
    "def": (r"\def\frac#1#2{#1}", "\\def"),
    "gdef": (r"\gdef\x{}", "\\gdef"),
    "let": (r"\let\frac\input", "\\let"),
    "newcommand": (r"\newcommand{\x}{y}", "\\newcommand"),
    "verb": (r"\verb|\input|", "\\verb"),
    "scantokens": (r"\scantokens{x}", "\\scantokens"),
    "href": (r"\href{run:/bin/sh}{B}", "\\href"),
    "url": (r"\url{javascript:alert(1)}", "\\url"),
    "hyperref-link": (r"\hyperlink{x}{B}", "\\hyperlink"),
    "usepackage": (r"\usepackage{shellesc}", "\\usepackage"),
    "everymath": (r"\everymath{\input x}", "\\everymath"),
    "end-document": (r"\end{document}", "environment document"),
    "filecontents": (r"\begin{filecontents}{x.tex}", "environment filecontents"),
    "verbatim-env": (r"\begin {verbatim}", "environment verbatim"),
    "env-without-braces": (r"\begin x", "not followed by an environment name"),
    "env-name-from-command": (r"\begin{\x}", "not followed by an environment name"),
    "begin-after-comment": ("\\begin%\n{filecontents}{x.tex}", "comment"),
    "comment": (r"b > 0 % \frac", "comment"),
    "parameter": (r"#1", "macro-parameter"),
    "unbalanced-open": (r"\frac{a}{b", "not closed"),
    "unbalanced-close": (r"a}}\input{x}{{", "closes a group"),
    "escaped-brace-trick": (r"x \\{ y", "not closed"),  # \\ then {: the old (before issue 22) is_balanced saw \{
    "trailing-backslash": ("b > a \\", "ends the text"),
    "blank-line": ("a\n\nb", "blank line"),
    "null": ("a\x00b", "control character"),
    "delete": ("a\x7fb", "control character"),
    "escape-char": ("a\x1bb", "control character"),
    "nel": ("a\x85b", "control character"),
    "line-separator": ("a\u2028b", "invisible"),
    "zero-width": ("\\fr\u200bac{a}{b}", "invisible"),
    "fullwidth-i": ("\\\uff49nput", "not allowed"),
    "unknown": (r"\foo x", "not an allowed command"),
    "unknown-symbol": (r"\@ x", "not allowed"),
    "relax": (r"\relax", "not an allowed command"),
    "script-without-argument": (r"a^&^5c", "has no argument"),
    "subscript-without-argument": (r"a_\\ b", "has no argument"),
}


@pytest.mark.parametrize("name", sorted(HOSTILE))
def test_hostile_text_is_refused(name):
    text, why = HOSTILE[name]
    reason = check_tex(text, ALLOWED, ENVIRONMENTS)
    assert reason is not None, text
    assert why in reason, (text, reason)


@pytest.mark.parametrize("name", sorted(ALWAYS_REFUSED & {"input", "openout", "write", "csname", "def", "catcode",
                                                          "immediate", "href", "lowercase", "expandafter"}))
def test_always_refused_even_when_allowed(name):
    reason = check_tex("\\" + name + " x", ALLOWED | {name})
    assert reason is not None and "never accepted" in reason


def test_benign_displays_of_the_papers_are_accepted():
    refused = {x: check_tex(x, ALLOWED, ENVIRONMENTS) for x in CORPUS["typesettable"]}
    refused = {x: r for x, r in refused.items() if r is not None}
    assert len(CORPUS["typesettable"]) > 200 and refused == {}


def test_emitted_report_fragments_of_the_papers_are_accepted():
    # the layout of latex.fit_display / math_cell, checked after it was applied
    emitted = [tex.fit_display(x) for x in CORPUS["typesettable"]] + [tex.math_cell(x) for x in CORPUS["typesettable"]]
    refused = {x: check_tex(x, ALLOWED | LAYOUT, ENVIRONMENTS | {"hpdisplay"}) for x in emitted}
    refused = {x: r for x, r in refused.items() if r is not None}
    assert len(emitted) > 400 and refused == {}


@pytest.mark.parametrize("text", [
    r"\frac{a}{b}", r"x_{1}^{2} + y_i", r"\Re\left\{ (1 - e^{-j\omega T}) H \right\}", r"\cos(\omega T)",
    r"\begin{bmatrix} 1 & 0 \\ 0 & -\tfrac{1}{2} \end{bmatrix}", r"\left( x \right)", r"\text{if } b > 0",
    r"b \geq \frac{KT}{2} + |B| \tag{20}", "a\nb", r"\|x\| \, \; \! \quad", r"\alpha' \ne \beta^{\prime}",
])
def test_benign_math_is_accepted(text):
    assert check_tex(text, ALLOWED, ENVIRONMENTS) is None


# --------------------------------------------------------------------------------------------
# plain text
# --------------------------------------------------------------------------------------------
ESCAPED_HOSTILE = [
    r"^^5cinput{/etc/hostname}", r"\input{/etc/hostname}", "50% off", "a\r\\input{x}", "a\n\nb", "#1 & $x$",
    "~^_{}", "x^^", "^^5e^5cinput", "\x00\x1b\x7f\x85\u2028", "<=> <= >= != => -> | < >", "\\", "^",
    "verylongwordwith,commas;and/slashes_and=equals" * 2, "ω ≤ 1 …",
]


@pytest.mark.parametrize("text", ESCAPED_HOSTILE)
def test_escaped_text_reads_as_text(text):
    escaped = escape_tex_text(text)
    reading = tokenize(escaped)
    assert reading.carets == [] and reading.comments == [] and reading.invalid == []
    words = {t.text for t in reading.tokens if t.kind == "cs" and len(t.text) > 1}
    assert words <= {"textbackslash", "textasciicircum", "allowbreak", "sim", "leq", "geq", "neq", "Rightarrow",
                     "rightarrow", "Leftrightarrow", "omega", "dots"}
    assert not any(t.kind == "char" and t.catcode == 6 for t in reading.tokens)
    assert "\n" not in escaped and "\r" not in escaped


def test_escaped_text_matches_the_old_escaper_on_plain_text():
    # the old (before issue 22) doctests of latex.escape_text
    assert escape_tex_text("b_1 > 50% & {x}") == "b\\_1 $>$ 50\\% \\& \\{x\\}"
    assert escape_tex_text("b >= B + K*T/2, |B|") == "b $\\geq$ B + K*T/2, $|$B$|$"


# --------------------------------------------------------------------------------------------
# against TeX itself
# --------------------------------------------------------------------------------------------
_PROBE = r"""\documentclass{article}
\usepackage[T1]{fontenc}
\usepackage{amsmath,amssymb,graphicx,array,longtable,xcolor}
\usepackage[hidelinks]{hyperref}
\ExplSyntaxOn
\ior_new:N \g_probe_ior
\tl_new:N \l_probe_tl
\tl_new:N \l_probe_line_tl
\tl_new:N \l_probe_cs_tl
\cs_new_protected:Npn \probe:n #1
  {
    \tl_clear:N \l_probe_tl
    \ior_open:Nn \g_probe_ior {#1}
    \bool_until_do:nn { \ior_if_eof_p:N \g_probe_ior }
      {
        \ior_get:NN \g_probe_ior \l_probe_line_tl
        \tl_put_right:NV \l_probe_tl \l_probe_line_tl
      }
    \ior_close:N \g_probe_ior
    \iow_term:n {PROBE-BEGIN}
    \tl_analysis_map_inline:Nn \l_probe_tl
      {
        \int_compare:nNnTF {##2} = {-1}
          { \tl_set:Nx \l_probe_cs_tl {##1} \iow_term:x { CS \tl_to_str:N \l_probe_cs_tl } }
          { \iow_term:x { CH ~ ##2 ~ ##3 } }
      }
    \iow_term:n {PROBE-END}
  }
\NewDocumentCommand \Probe { m } { \probe:n {#1} }
\ExplSyntaxOff
\begin{document}
%s
\typeout{CATCODES}\newcount\probecount
\loop\typeout{CAT \the\probecount\space\the\catcode\probecount}\advance\probecount 1
\ifnum\probecount<256 \repeat
\end{document}
"""

#: strings whose reading is subtle; brace-balanced and ASCII (pdflatex reads bytes)
DIFFERENTIAL = [
    r"\^^69nput{x}", "^^5e^5cfoo", "^^5e^5e5c", r"\inp^^75t", "^^5cinput{a}", "^^5Cinput", "x^^", "^^\\input",
    "a ^^M b", r"\csname input\endcsname", r"\lowercase{\INPUT}", "^^5c^^69nput", r"\^^5c", "^^7b x ^^7d",
    "a%comment \\input\nb", "a\rb", "  leading spaces", "a   b", r"\ x\  y", "~", "#", "$x^2_3&y$", "^^I x",
    "\\a\\b1", "^^^^005c", "^^7f", "^^e9", "a\n\nb", "\\relax\n  \\relax", r"\frac{a}{b}+\left(x\right)",
    "^^5c^^5c", "^^Ab ^^aB ^^A5", "\\^^M", "x ^^20 y", "^^3a^^3b", "\\fo^^6f^^6fbar", "\\^^41BC", "^^5c^", "^", "^^^5c",
]


def _tex_reading(raw: list[str]) -> list[tuple]:
    out = []
    for line in raw:
        if line.startswith("CS\\"):  # expl3 syntax ignores the space: CS\input
            name = line[3:]
            if name != " " and name.endswith(" ") and name[:-1].isalpha():
                name = name[:-1]
            if re.fullmatch(r"\^\^[@-_?]", name):  # TeX prints control characters as ^^M, ^^?
                name = chr(ord(name[2]) ^ 64)
            out.append(("cs", name))
        elif line.startswith("CH "):
            code, cat = line[3:].split()
            out.append(("char", int(code), int(cat, 16)))
    # \ior_get meets the end of the file only when it reads once more: an empty line, \par
    return out[:-1] if out and out[-1] == ("cs", "par") else out


def _our_reading(text: str) -> list[tuple]:
    out = []
    for token in tokenize(text, start_mid_line=False).tokens:
        out.append(("cs", token.text) if token.kind == "cs" else ("char", ord(token.text), token.catcode))
    return out


@needs_pdflatex
def test_tokenizer_agrees_with_pdflatex(tmp_path):
    calls = []
    for k, text in enumerate(DIFFERENTIAL):
        (tmp_path / f"p{k}.txt").write_bytes(text.encode("ascii"))
        calls.append(f"\\Probe{{p{k}.txt}}")
    (tmp_path / "probe.tex").write_text(_PROBE % "\n".join(calls), encoding="ascii")
    env = dict(os.environ, max_print_line="100000", openout_any="p", openin_any="p")
    subprocess.run([PDFLATEX, "-no-shell-escape", "-interaction=nonstopmode", "probe.tex"], cwd=tmp_path, env=env,
                   capture_output=True, timeout=120)
    log = (tmp_path / "probe.log").read_text(encoding="latin-1")
    blocks = re.findall(r"^PROBE-BEGIN\n(.*?)^PROBE-END$", log, flags=re.S | re.M)
    assert len(blocks) == len(DIFFERENTIAL)
    mismatches = {}
    for text, block in zip(DIFFERENTIAL, blocks):
        ours = _our_reading(text)
        theirs = _tex_reading(block.splitlines())
        if ours != theirs:
            mismatches[text] = (ours, theirs)
    assert mismatches == {}
    catcodes = dict(re.findall(r"^CAT (\d+) (\d+)$", log, flags=re.M))
    assert tuple(int(catcodes[str(k)]) for k in range(256)) == LATEX_CATCODES


# --------------------------------------------------------------------------------------------
# compiling: the README's command, and what the check keeps out
# --------------------------------------------------------------------------------------------
COMPILE = ["-no-shell-escape", "-interaction=nonstopmode", "-halt-on-error"]
RESTRICTED = {"openout_any": "p", "openin_any": "p"}


def _compile(directory: pathlib.Path, body: str, restricted: bool = True) -> str:
    (directory / "doc.tex").write_text("\\documentclass{article}\n\\usepackage{amsmath}\n\\begin{document}\n"
                                       + body + "\n\\end{document}\n", encoding="utf-8")
    env = dict(os.environ, **(RESTRICTED if restricted else {}))
    subprocess.run([PDFLATEX, *COMPILE, "doc.tex"], cwd=directory, env=env, capture_output=True, timeout=60)
    return (directory / "doc.log").read_text(encoding="latin-1")


@needs_pdflatex
def test_the_attack_works_unchecked_and_is_kept_out_by_the_check(tmp_path):
    (tmp_path / "secret.tex").write_text("\\typeout{SECRETMARKER}", encoding="ascii")
    display = r"b > \frac{KT}{2} + B ^^5cinput{secret} ^^5cimmediate^^5cwrite16{LEAK ^^5cjobname}"
    unchecked = _compile(tmp_path, "$" + display + "$")
    assert "SECRETMARKER" in unchecked and "LEAK doc" in unchecked  # the control: the attack is real
    shown = ("$" + display + "$") if check_tex(display, ALLOWED, ENVIRONMENTS) is None \
        else escape_tex_text(display)
    checked = _compile(tmp_path, shown)
    assert "SECRETMARKER" not in checked and "LEAK doc" not in checked
    assert "Output written on doc.pdf" in checked


@needs_pdflatex
@pytest.mark.skipif(not os.path.exists("/etc/hostname"), reason="no /etc/hostname to read")
def test_restricted_openin_refuses_absolute_paths(tmp_path):
    body = (r"\newread\probe\openin\probe=/etc/hostname \ifeof\probe\typeout{OPENIN-REFUSED}"
            r"\else\typeout{OPENIN-READ}\fi x")
    assert "OPENIN-READ" in _compile(tmp_path, body, restricted=False)  # the control: TeX Live's default reads
    assert "OPENIN-REFUSED" in _compile(tmp_path, body, restricted=True)


@needs_pdflatex
def test_no_shell_escape(tmp_path):
    log = _compile(tmp_path, r"\immediate\write18{touch shell-ran} x")
    assert not (tmp_path / "shell-ran").exists()
    assert "runsystem(touch shell-ran)...disabled" in log


@needs_pdflatex
@pytest.mark.parametrize("target", ["absolute", "parent"])
def test_restricted_openout_refuses_paths_outside_the_directory(tmp_path, target):
    work = tmp_path / "work"
    work.mkdir()
    path = str(tmp_path / "written.txt") if target == "absolute" else "../written.txt"
    body = r"\newwrite\probe\immediate\openout\probe=" + path + r" \immediate\write\probe{x}\immediate\closeout\probe x"
    unrestricted = _compile(work, body, restricted=False)  # the control: TeX Live's default (p) for openout ...
    log = _compile(work, body)
    assert not (tmp_path / "written.txt").exists()
    assert "I can't write on file" in log and "I can't write on file" in unrestricted  # ... is already paranoid
