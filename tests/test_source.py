r"""The reader of ``hapticproof new-paper --from``: LaTeX sources and transcriptions
(:mod:`hapticproof.audit.source.displays`, :mod:`hapticproof.audit.source.tex`) and the guesses
of claims and symbols (:mod:`hapticproof.audit.source.guess`)."""

from __future__ import annotations

import os
from pathlib import Path

import pytest

from hapticproof.audit.source import displays as texsource
from hapticproof.audit.source import guess
from hapticproof.audit.source.read import read_source, read_text
from hapticproof.audit.source.tex import SourceError
from hapticproof.core.errors import InputFormatError

MAIN = r"""\documentclass{article}
\usepackage{amsmath}
\newcommand{\half}[1]{\frac{#1}{2}}
\newcommand{\gain}[2][K]{#1_{#2}}
\renewcommand{\vec}[1]{\mathbf{#1}}
\providecommand{\half}{never used}
\def\damp{b}
\def\pair#1#2{(#1, #2)}
\def\upto#1.{[#1]}
\let\Damp\damp
\DeclareMathOperator{\Res}{Res}
\newcommand\R{\mathbb{R}} % the reals; $$ not a display $$
\numberwithin{equation}{section}
\begin{document}
\section{Model}
Prose with 50\% and $x$ inline. % \begin{equation} commented out \end{equation}
\begin{equation}
  \damp > \half{KT} + B \label{eq:wall}
\end{equation}
\begin{align}
  G^{-1}(z) &= \Damp + \frac{\gain{1} T}{z-1} \label{eq:g} \\
  \Res_{z=1} G^{-1} &= \gain[k]{2} T \nonumber \\
   &= KT \label{eq:res}
\end{align}
\subsection{Cases}
\begin{equation*} a = \pair{1}{2} \end{equation*}
\[ c > \upto x. \]
$$ d > 0 \tag{T1} $$
\begin{gather}
 x = 1 \\
 y = 2
\end{gather}
\begin{multline}
 a + b \\ + c = 0
\end{multline}
\begin{eqnarray}
 u &=& v \nonumber \\
 w &<& 1
\end{eqnarray}
\iffalse
\begin{equation} skipped \end{equation}
\fi
\begin{verbatim}
\begin{equation} not maths \end{equation}
\end{verbatim}
\input{sections/part}
\end{document}
\begin{equation} after the end \end{equation}
"""

PART = r"""\section{Part}
\begin{equation} \omega \in \R \tag{P} \end{equation}
"""


@pytest.fixture
def paper(tmp_path: Path) -> Path:
    (tmp_path / "sections").mkdir()
    (tmp_path / "main.tex").write_text(MAIN, encoding="utf-8")
    (tmp_path / "sections" / "part.tex").write_text(PART, encoding="utf-8")
    return tmp_path


def _by_line(source):
    return {d.line: d for d in source.displays}


# ---------------------------------------------------------------------------------------------
# LaTeX
# ---------------------------------------------------------------------------------------------


def test_latex_paper_displays(paper: Path) -> None:
    source = read_source(paper / "main.tex")
    assert source.mode == "latex"
    texts = [d.text for d in source.displays]
    assert texts == [
        r"b > \frac{KT}{2} + B",
        r"G^{-1}(z) = b + \frac{K_{1} T}{z-1}",
        r"\begin{aligned} \operatorname{Res}_{z=1} G^{-1} &= k_{2} T \\ &= KT \end{aligned}",
        "a = (1, 2)",
        "c > [x]",
        "d > 0",
        "x = 1",
        "y = 2",
        r"a + b \\ + c = 0",
        r"\begin{aligned} u &= v \\ w &< 1 \end{aligned}",
        r"\omega \in \mathbb{R}",
    ]
    d = _by_line(source)
    assert d[17].original == r"\damp > \half{KT} + B \label{eq:wall}"
    assert (d[17].label, d[17].number, d[17].environment, d[17].section.id, d[17].end_line) == \
        ("eq:wall", "1.1", "equation", "1", 19)
    # align: one display per numbered row; the \nonumber row joins the next numbered one
    assert [(d[21].row, d[21].label, d[21].number), (d[22].row, d[22].label, d[22].number)] == \
        [(0, "eq:g", "1.2"), (1, "eq:res", "1.3")]
    assert d[22].original.startswith(r"\Res_{z=1}") and d[22].original.endswith(r"\label{eq:res}")
    assert d[22].end_line == 23 and d[21].end_line == 21
    # unnumbered displays, the tag, gather rows, multline, eqnarray
    assert [d[n].number for n in (26, 27, 28)] == [None, None, "T1"]
    assert d[28].tag == "T1" and d[28].id == "T1" and d[28].section.id == "1.1"
    assert [(d[n].number, d[n].environment, d[n].row) for n in (30, 31)] == [("1.4", "gather", 0), ("1.5", "gather", 1)]
    assert (d[33].number, d[36].number, d[36].environment, d[36].row) == ("1.6", "1.7", "eqnarray", None)
    # the \input file: its own name and lines, the next section's numbering, the tag
    last = source.displays[-1]
    assert (last.file, last.line, last.number, last.section.number, last.section.title) == \
        ("sections/part.tex", 2, "P", "2", "Part")
    assert [s.id for s in source.sections] == ["1", "1.1", "2"]
    assert source.files == [str(paper / "main.tex"), "sections/part.tex"]
    assert source.macros[r"\gain"] == 2 and source.macros[r"\Res"] == 0
    assert source.warnings == []


def test_folder_finds_the_main_file(paper: Path) -> None:
    (paper / "notes.tex").write_text(r"\begin{equation} x \end{equation}", encoding="utf-8")
    assert read_source(paper).displays[0].text == r"b > \frac{KT}{2} + B"


def test_automatic_numbers_and_appendix() -> None:
    source = read_text(r"""\begin{document}
\section{A}
\begin{equation} a \end{equation}
\begin{subequations}
\begin{align} b \\ c \end{align}
\end{subequations}
\begin{equation} d \nonumber \end{equation}
\begin{equation} e \tag{7'} \end{equation}
\begin{align*} f \\ g \tag{G} \end{align*}
\setcounter{equation}{9}
\appendix
\section{Proofs}
\begin{equation} h \end{equation}
\end{document}""", "n.tex")
    assert [(d.text, d.number) for d in source.displays] == [
        ("a", "1"), ("b", "2a"), ("c", "2b"), ("d", None), ("e", "7'"),
        (r"\begin{aligned} f \\ g \end{aligned}", "G"), ("h", "10")]
    assert [s.id for s in source.sections] == ["1", "A"]


def test_macros_with_delimiters_defaults_and_environments() -> None:
    source = read_text(r"""\newcommand{\norm}[2][\infty]{\|#2\|_{#1}}
\def\abs|#1|{\left|#1\right|}
\newenvironment{eq}{\begin{equation}}{\end{equation}}
\newcommand{\be}{\begin{equation}}
\newcommand{\ee}{\end{equation}}
\begin{eq} \norm{x} + \norm[2]{y} < \abs|z| \end{eq}
\be q = 1 \ee""", "m.tex")
    assert [d.text for d in source.displays] == [r"\|x\|_{\infty} + \|y\|_{2} < \left|z\right|", "q = 1"]
    assert source.displays[1].original == "q = 1"


def test_recursive_and_exploding_macros_are_one_error_line() -> None:
    with pytest.raises(SourceError, match=r"r\.tex:1: \\a expands more than 64 levels deep"):
        read_text(r"\def\a{x\a}\a", "r.tex")
    chain = "".join(rf"\def\{a}{{\{b}\{b}}}" for a, b in zip("abcdefghijklmnopq", "bcdefghijklmnopqr")) + r"\def\r{x}\a"
    with pytest.raises(SourceError, match="beyond the budget"):      # the budget stops it, not a timeout
        read_text(chain, "r.tex")


def test_unclosed_display_is_kept_with_a_warning() -> None:
    source = read_text("\\begin{document}\n\\begin{equation}\n a = b\n\nprose\n\\end{document}", "u.tex")
    (display,) = source.displays
    assert display.text == "a = b" and "not closed" in display.notes[0]
    assert source.warnings == ["u.tex:2: equation: not closed before the blank line; the display ends there"]


# ---------------------------------------------------------------------------------------------
# files from strangers
# ---------------------------------------------------------------------------------------------

SECRET = "SECRET-CONTENT-42"


@pytest.mark.parametrize("request_name, reason", [
    ("/etc/passwd", "an absolute path"),
    ("../outside", "'..' leaves the main file's folder"),
    ("sub/../../outside", "'..' leaves"),
    ("~/outside", "an absolute path"),
    ("link", "leads outside the main file's folder"),
    ("sub", "not a regular file"),
    ("missing", "no such file"),
])
def test_refused_inputs_never_echo_content(tmp_path: Path, request_name: str, reason: str) -> None:
    folder = tmp_path / "paper"
    (folder / "sub").mkdir(parents=True)
    (tmp_path / "outside.tex").write_text(SECRET, encoding="utf-8")
    os.symlink(tmp_path / "outside.tex", folder / "link.tex")
    (folder / "main.tex").write_text(f"\\begin{{document}}\nfirst line\n\\input{{{request_name}}}\n\\end{{document}}\n",
                                     encoding="utf-8")
    with pytest.raises(SourceError) as info:
        read_source(folder / "main.tex")
    message = str(info.value)
    assert reason in message and message.startswith(f"{folder / 'main.tex'}:3: \\input")
    assert "\n" not in message and SECRET not in message and "root:" not in message


def test_input_cycle_and_file_budgets(tmp_path: Path) -> None:
    (tmp_path / "a.tex").write_text(r"\input{b}", encoding="utf-8")
    (tmp_path / "b.tex").write_text(r"\input{a}", encoding="utf-8")
    with pytest.raises(SourceError, match="a cycle"):
        read_source(tmp_path / "a.tex")
    (tmp_path / "c.tex").write_text(r"\input{d}\input{d}\input{d}", encoding="utf-8")
    (tmp_path / "d.tex").write_text("$$x$$", encoding="utf-8")
    assert len(read_source(tmp_path / "c.tex").displays) == 3
    with pytest.raises(SourceError, match="more than 3 files"):
        read_source(tmp_path / "c.tex", max_files=3)
    with pytest.raises(SourceError, match="too large"):
        read_source(tmp_path / "c.tex", max_bytes=40)


def test_not_utf8_and_byte_order_marks(tmp_path: Path) -> None:
    bad = tmp_path / "latin1.tex"
    bad.write_bytes("\\section{A}\n\\begin{equation} \xe9t\xe9 \\end{equation}\n".encode("latin-1"))
    with pytest.raises(SourceError) as info:
        read_source(bad)
    assert str(info.value) == f"{bad}:2: not UTF-8 (invalid byte at column 18); save the file as UTF-8"
    (tmp_path / "main.tex").write_text("\\input{latin1}", encoding="utf-8")
    with pytest.raises(SourceError, match=r"^latin1\.tex:2: not UTF-8"):
        read_source(tmp_path / "main.tex")
    bom = tmp_path / "bom.tex"
    bom.write_bytes(b"\xef\xbb\xbf\\begin{equation} a = 1 \\end{equation}")
    (display,) = read_source(bom).displays
    assert (display.text, display.line, display.original) == ("a = 1", 1, "a = 1")
    utf16 = tmp_path / "utf16.tex"
    utf16.write_bytes("$$a$$".encode("utf-16"))
    with pytest.raises(SourceError, match="is UTF-16 .byte-order mark.; save it as UTF-8"):
        read_source(utf16)
    binary = tmp_path / "binary.tex"
    binary.write_bytes(b"$$a$$\n\x00\x01")
    with pytest.raises(SourceError, match=r"binary\.tex:2: not a text file"):
        read_source(binary)


def test_deep_nesting_is_refused_quickly() -> None:
    with pytest.raises(SourceError, match=r"deep\.tex:1: braces nested deeper than 200"):
        read_text("{" * 100_000 + "}" * 100_000, "deep.tex")
    with pytest.raises(SourceError, match=r"deep\.md:1: braces nested deeper than 200"):
        read_text("$$" + "{" * 100_000 + "}" * 100_000 + "$$", "deep.md")
    with pytest.raises(SourceError, match="environments nested deeper than 200"):
        read_text(r"\begin{equation}" + r"\begin{aligned}" * 1000, "env.tex")


# ---------------------------------------------------------------------------------------------
# transcriptions (text mode)
# ---------------------------------------------------------------------------------------------

TRANSCRIPT = r"""TITLE

ABSTRACT

Costs fall by 50% (a percent sign is text here) and $x$ is inline.

1 INTRODUCTION

$$b > \frac{KT}{2} + B \tag{3}$$

2 MODEL

2.1 The Wall

$$F_h(z) = bV_h(z) + \frac{KT}{z-1}V_h(z)$$
(21)

$$b > \frac{KT}{2} - B\cos(\omega T)$$
⁽²³⁾

$$R_0 = \begin{bmatrix} KT \end{bmatrix} \quad (24)$$

$$b - z_a > \frac{T}{2} \Re\{H(e^{j\omega T})\}$$

$$(36)$$

$$det(G) =$$
(44)

$$(2b - KT)^2 > 0$$

$$x_h(kT+T) = x_h(kT) + TV_h(kT)$$
$$\implies X_h(z) = \frac{T}{z-1}V_h(z)$$

$$b + B > KT (25)$$

$$K < \frac{2b}{T} (26)

after the paragraph break: that display was never closed

```
$$ not a display in code $$
```

III. NOT A SECTION: ROMAN AFTER ARABIC IS ACCEPTED

A. First Part

$$k_{pmxx} \geq 0, \quad k_{pmyy} \geq 0 \quad (39a)$$

# Appendix heading in Markdown

\[ \begin{aligned} a &= 1 \\ b &= 2 \end{aligned} \]
"""


def test_transcription_displays_numbers_and_repairs() -> None:
    source = read_text(TRANSCRIPT, "paper.txt")
    assert source.mode == "text"
    got = [(d.number, d.text) for d in source.displays]
    assert got == [
        ("3", r"b > \frac{KT}{2} + B"),
        ("21", r"F_h(z) = bV_h(z) + \frac{KT}{z-1}V_h(z)"),
        ("23", r"b > \frac{KT}{2} - B\cos(\omega T)"),
        ("24", r"R_0 = \begin{bmatrix} KT \end{bmatrix}"),
        ("36", r"b - z_a > \frac{T}{2} \Re\{H(e^{j\omega T})\}"),
        ("44", "det(G) =\n(2b - KT)^2 > 0"),
        (None, r"x_h(kT+T) = x_h(kT) + TV_h(kT) \\ \implies X_h(z) = \frac{T}{z-1}V_h(z)"),
        ("25", "b + B > KT"),
        ("26", r"K < \frac{2b}{T}"),
        ("39a", r"k_{pmxx} \geq 0, \quad k_{pmyy} \geq 0"),
        (None, r"\begin{aligned} a &= 1 \\ b &= 2 \end{aligned}"),
    ]
    d = {x.number: x for x in source.displays}
    assert d["24"].original == r"R_0 = \begin{bmatrix} KT \end{bmatrix} \quad (24)"
    assert d["26"].original == r"K < \frac{2b}{T} (26)"
    assert any("not closed before the paragraph break" in n for n in d["26"].notes)
    assert any("ends with an operator" in n for n in d["44"].notes)
    assert [s.id for s in source.sections] == ["Abstract", "1", "2", "2.1", "III", "III-A", "Appendix heading in Markdown"]
    assert [x.section.id for x in source.displays][:3] == ["1", "2.1", "2.1"]
    assert source.displays[-1].section.title == "Appendix heading in Markdown"
    assert d["3"].line == 9 and d["21"].line == 15
    assert "50%" in d["3"].context and "percent sign" in d["3"].context


def test_headings_need_their_numbering_order_and_blank_lines() -> None:
    text = "1 INTRODUCTION\n\n$$a$$\n\n7 Not a heading out of order\n\n2 Next Section\n\nnot alone\n3 Heading\n\n$$b$$\n"
    source = read_text(text, "h.md")
    assert [s.id for s in source.sections] == ["1", "2"]
    assert [d.section.id for d in source.displays] == ["1", "2"]


def test_bundled_transcriptions_are_read(paper_transcriptions: Path) -> None:
    counts = {}
    for name in ("000_e6b68def623c8e74.txt", "001_48f53b5d92944b5d.txt", "002_de715dde36093cfe.txt"):
        source = read_source(paper_transcriptions / name)
        counts[name[:3]] = (len(source.displays), sum(d.environment == "where" for d in source.displays))
        numbers = [d.number for d in source.displays if d.number]
        assert len(numbers) == len(set(numbers)), "an equation number read twice"
    # displays, of which inline 'where' definition lists (HVE (46b) and its 2-user twin)
    assert counts == {"000": (83, 2), "001": (67, 2), "002": (40, 0)}


def test_where_lists_in_prose() -> None:
    source = read_text("$$G^{-1}(z) = b + K_1$$\n\nwhere $K_1 = K_{01} + K_{12}$ and $B_1 = B_{01}$. Then $x$ is "
                       "small, where $y$ is not a definition.\n\n$$b > K_1$$\n", "w.md")
    assert [(d.environment, d.text) for d in source.displays] == [
        ("$$", "G^{-1}(z) = b + K_1"), ("where", "K_1 = K_{01} + K_{12}, B_1 = B_{01}"), ("$$", "b > K_1")]
    assert source.displays[1].line == 3


def test_source_errors_are_input_format_errors() -> None:
    with pytest.raises(InputFormatError):
        read_text(r"\def\a{x\a}\a", "r.tex")


# ---------------------------------------------------------------------------------------------
# guesses
# ---------------------------------------------------------------------------------------------


@pytest.mark.parametrize("display, context, claim", [
    (r"G^{-1}(z) = b + z^{-n} \left(K + \frac{B(z-1)}{Tz}\right) \frac{T}{z-1}", "", "inverse-transfer"),
    (r"F_{h}(z) = bV_{h}(z) + \frac{KT}{z-1}V_{h}(z) = G_{1}^{-1}(z)V_{h}(z)", "", "inverse-transfer"),
    (r"G^{-1}(z) = \begin{bmatrix} b_1 & 0 \\ 0 & b_2 \end{bmatrix} \tag{56}", "", "inverse-transfer"),
    (r"\mathrm{Res}_{z=1} G^{-1}(z) = KT", "", "residue"),
    (r"R_0 = \begin{bmatrix} KT \end{bmatrix}", "", "residue"),
    (r"b > \frac{KT}{2} - B\cos(\omega T)", "", "hermitian-part"),
    (r"b - z_a > \frac{T}{2} \frac{1}{1 - \cos(\omega T)} \Re\{(1 - e^{-j\omega T}) H(e^{j\omega T})\}", "", "hermitian-part"),
    (r"\boxed{\begin{aligned} b_m &> T \operatorname{Re} \{ C_m(e^{j\omega T}) \} \\ b_s &> T \operatorname{Re} \{ C_s(e^{j\omega T}) \} \end{aligned}} \quad (29)", "", "hermitian-part"),
    (r"b + B \frac{1 + \cos(\omega T)}{2}", "", "hermitian-part"),
    (r"det(G(e^{j\omega T}) + G^{T}(e^{-j\omega T})) = (2b - KT)^2 > 0", "", "hermitian-part"),
    (r"b > \frac{KT}{2} + B \tag{3}", "the necessary and sufficient condition was derived as", "passivity-condition"),
    (r"b > KT + 2B \quad (35)", "Thus, a sufficient condition for passivity will be", "sufficient-condition"),
    (r"b > KT", "A necessary condition is", "necessary-condition"),
    (r"\min_{i} b_{i} > \max_{i} \{ \frac{K_{0i}T}{2} + B_{0i} \}", "", "passivity-condition"),
])
def test_guess_claim_from_shape(display: str, context: str, claim: str) -> None:
    got, reason = guess.guess_claim(display, context=context)
    assert got == claim, reason
    assert reason


@pytest.mark.parametrize("display, why", [
    (r"e = x_m - x_s \quad (6)", "an equation"),
    (r"F_h(z) = G^{-1}(z)V_h(z)", "names G^{-1} without saying"),
    (r"\int_0^t f_h(\tau)\dot{x}_m(\tau)d\tau > 0", "an integral"),
    (r"\|\mathscr{M}\mathscr{N}\|_{\infty} < 1", "small-gain"),
    (r"\left|\frac{r H}{2b + r H}\right| < 1", "small-gain"),
    (r"(K_{01} + K_{12})T > 0", "a step of a proof"),
    (r"k_{pmxx} \geq 0, \quad k_{pmyy} \geq 0", "sign conditions"),
    (r"K^{-1} + C(zI - A)^{-1}B", "without a relation"),
    ("", "empty"),
])
def test_guess_claim_abstains_with_a_reason(display: str, why: str) -> None:
    got, reason = guess.guess_claim(display)
    assert got is None and why in reason


def test_stability_is_never_guessed_from_shape_alone() -> None:
    claim, reason = guess.guess_claim(r"b+B > \frac{KT}{2}", context="the stability condition was derived as")
    assert claim == "passivity-condition" and "stability-condition" in reason


def test_symbols_of() -> None:
    assert guess.symbols_of(r"b - z_a + B > Kt_d + \frac{KT}{2}") == {
        "b": "positive", "z_a": "nonnegative", "B": "nonnegative", "K": "positive", "t_d": "nonnegative",
        "T": "positive"}
    assert guess.symbols_of(r"F_{h}(z) = bV_{h}(z) + \left(K + \frac{B(z-1)}{Tz}\right)\frac{T}{z-1}V_{h}(z) "
                            r"= G_{1}^{-1}(z)V_{h}(z)") == {
        "F_h": "signal", "b": "positive", "V_h": "signal", "K": "positive", "B": "nonnegative", "T": "positive",
        "G_1^{-1}": "function"}
    assert guess.symbols_of(r"\min_{i} b_{i} > m \max_{i,j \neq i} \{ \frac{K_{ij}T}{2} + B_{ij} \}") == {
        "b_i": "positive", "m": "positive", "K_{ij}": "positive, symmetric", "T": "positive",
        "B_{ij}": "nonnegative, symmetric"}
    # H(...) is the scene's environment, z/s/j/e are built in, d\tau is a differential
    assert guess.symbols_of(r"\int_0^t y(\tau) d\tau + H(e^{j\omega T}) + \sum_{k=1}^{m} x_k(s)") == {
        "t": "real", "y": "signal", "tau": "real", "omega": "real", "T": "positive", "x_k": "signal"}
    assert guess.symbols_of(r"\mathcal{Z}'(j\omega) + \bar{C}^-(\omega) V^c") == {
        "\\mathcal{Z}'": "function", "omega": "real", "\\bar{C}": "function", "V": "real"}


def test_guessed_symbols_load_in_a_paper_file() -> None:
    """Every name of a guessed display is declared by symbols_of (checked by the paper-file reader)."""
    import json

    from hapticproof.audit import paperfile

    displays = [r"b - z_a > \frac{T}{2} \frac{1}{1 - \cos(\omega T)} \Re\{e^{-j\omega t_d} (1 - e^{-j\omega T}) "
                r"H(e^{j\omega T})\}", r"F_h(z) = bV_h(z) + z^{-n}\left(K + \frac{B(z-1)}{Tz}\right)\frac{T}{z-1}V_h(z)"]
    symbols: dict[str, str] = {}
    for text in displays:
        symbols.update(guess.symbols_of(text))
    lines = ["[paper]", 'id = "t"', 'title = "t"', "[symbols]"] + [f"{json.dumps(k)} = {json.dumps(v)}" for k, v in symbols.items()]
    lines += ["[scenes.wall]", 'system = "single-user"', 'approximation = "forward"']
    for k, text in enumerate(displays):
        claim = guess.guess_claim(text)[0]
        lines += ["[[equations]]", f'id = "{k}"', f"printed = {json.dumps(text)}", f'claim = "{claim}"', 'scene = "wall"']
    paper = paperfile.loads("\n".join(lines) + "\n", "t.toml")
    assert [c.claim for c in paper.claims] == ["hermitian-part", "inverse-transfer"]


def test_module_constants_are_exposed() -> None:
    assert texsource.MAX_NESTING == 200 and texsource.MAX_FILES >= 1
