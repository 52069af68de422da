"""Issue 30, views: every view escapes for its own format (from :mod:`hapticproof.core.escape`).

A hostile paper file puts HTML in its title, ids and displays, terminal escape sequences in its
names, and ``\\text{a & b}`` in a display. The Markdown report carries no raw HTML (no ``<``
outside code spans, which is where CommonMark's raw HTML and autolinks start); terminal text
(the audit table, ``check``'s summary, error lines) carries no control character; the LaTeX
report compiles.
"""

from __future__ import annotations

import json
import re
import shutil
import subprocess
import unicodedata
from pathlib import Path

import pytest

from hapticproof.cli import main
from hapticproof.core.escape import for_markdown, for_markdown_code, for_terminal

PAYLOAD = "<img src=x onerror=alert(1)>"
ESCAPES = "\x1b[2J\x1b]0;pwned\x07\x9b31m\u202eevil"

PAPER = """[paper]
id = "evil"
title = "{title}"
[symbols]
b = "positive"
K = "positive"
B = "nonnegative"
T = "positive"
[scenes.wall]
system = "single-user"
environment = "K + B*(z - 1)/(T*z)"
[[equations]]
id = "{eq_id}"
printed = '{printed}'
claim = "passivity-condition"
scene = "wall"
[[equations]]
id = "2"
printed = 'b > \\frac{{KT}}{{2}} + B \\text{{a & b}}'
claim = "passivity-condition"
scene = "wall"
"""


def _toml_text(text: str) -> str:
    return "".join(f"\\u{ord(ch):04x}" if ord(ch) < 32 or 127 <= ord(ch) < 160 or ch in '"\\' else ch for ch in text)


def _paper(folder: Path, title: str = PAYLOAD + ESCAPES, eq_id: str = "1" + PAYLOAD,
           printed: str = r"b > \frac{KT}{2} + B \text{" + PAYLOAD + "}") -> Path:
    path = folder / "evil.toml"
    path.write_text(PAPER.format(title=_toml_text(title), eq_id=_toml_text(eq_id), printed=printed), encoding="utf-8")
    return path


def _outside_code_spans(markdown: str) -> str:
    """The text of a Markdown document with its inline code spans removed (CommonMark: a run of
    n backticks opens a span that the next run of exactly n backticks closes)."""
    out, k = [], 0
    while k < len(markdown):
        if markdown[k] == "`":
            run = re.match(r"`+", markdown[k:]).group()
            closing = re.compile(r"(?<!`)" + run + r"(?!`)")
            end = closing.search(markdown, k + len(run))
            if end is not None:
                k = end.end()
                continue
            out.append(run)
            k += len(run)
            continue
        out.append(markdown[k])
        k += 1
    return "".join(out)


def _controls(text: str) -> list[str]:
    return [ch for ch in text if ch not in "\n" and (unicodedata.category(ch) == "Cc" or ch in "\u202e\u2066\u2069")]


def test_the_markdown_report_carries_no_raw_html(tmp_path, capsys):
    assert main(["audit", "--paper", str(_paper(tmp_path)), "--format", "markdown", "-o", str(tmp_path / "r.md")]) == 0
    capsys.readouterr()
    text = (tmp_path / "r.md").read_text(encoding="utf-8")
    assert "onerror" in text                                      # the payload is shown ...
    assert "<" not in _outside_code_spans(text)                   # ... as text: no tag, no autolink
    assert _controls(text) == []


def test_the_markdown_check_can_fail():
    assert "<" in _outside_code_spans("| a | <img src=x> |")
    assert "<" not in _outside_code_spans("| a | `` <img src=x> ` `` |")


@pytest.mark.parametrize("text", [PAYLOAD, "a|b", "``x`` ` y", "*b* _c_ [l](javascript:x)", ESCAPES, "a\nb", "<", "`"])
def test_markdown_escapes_are_literal(text):
    assert "<" not in _outside_code_spans(for_markdown(text))
    code = for_markdown_code(text)
    assert _outside_code_spans(code) == "" and "\n" not in code and _controls(code) == []


def test_terminal_text_carries_no_control_character(tmp_path, capsys):
    paper = _paper(tmp_path)                                    # (ids with control characters are refused)
    assert main(["audit", "--paper", str(paper)]) == 0
    captured = capsys.readouterr()
    assert "pwned" in captured.out and _controls(captured.out + captured.err) == []
    assert main(["audit", "--paper", str(paper), "--format", "json", "-o", str(tmp_path / "a.json")]) == 0
    capsys.readouterr()
    data = json.loads((tmp_path / "a.json").read_text(encoding="utf-8"))
    data["paper"] = "x" + ESCAPES                               # a saved report edited by hand
    data["equations"][0]["id"] = "1" + ESCAPES
    (tmp_path / "b.json").write_text(json.dumps(data), encoding="utf-8")
    main(["check", str(tmp_path / "b.json")])                   # the report's names in check's summary
    captured = capsys.readouterr()
    assert "pwned" in captured.out and _controls(captured.out + captured.err) == []


def test_an_error_line_carries_no_control_character(tmp_path, capsys):
    assert main(["audit", "--paper", str(tmp_path / ("missing" + ESCAPES + ".toml"))]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and _controls(err) == []


def test_terminal_escapes_are_visible():
    assert for_terminal(ESCAPES) == "\\x1b[2J\\x1b]0;pwned\\x07\\x9b31m\\u202eevil"
    assert for_terminal("two\nlines", multiline=True) == "two\nlines" and for_terminal("two\nlines") == "two\\x0alines"


def test_text_with_an_ampersand_does_not_break_the_latex_report(tmp_path, capsys):
    from hapticproof.core.texsafe import check_tex

    assert check_tex(r"b > \text{a & b}", {"text"}, alignments={"bmatrix"}) is not None
    assert check_tex(r"\begin{bmatrix} 1 & 0 \end{bmatrix}", {"begin", "end"}, {"bmatrix"}, alignments={"bmatrix"}) is None
    assert check_tex(r"\begin{bmatrix} \text{1 & 0} \end{bmatrix}", {"begin", "end", "text"}, {"bmatrix"},
                     alignments={"bmatrix"}) is not None
    assert main(["audit", "--paper", str(_paper(tmp_path)), "--format", "tex", "-o", str(tmp_path / "r.tex")]) == 0
    capsys.readouterr()
    pdflatex = shutil.which("pdflatex")
    if pdflatex is None:
        pytest.skip("pdflatex is not installed")
    run = subprocess.run([pdflatex, "-interaction=nonstopmode", "-no-shell-escape", "-halt-on-error", "r.tex"],
                         cwd=tmp_path, capture_output=True, text=True, timeout=180, check=False)
    assert run.returncode == 0, run.stdout[-2000:]
    assert (tmp_path / "r.pdf").exists()


#: Displays whose alignment marks or row ends TeX cannot place (inside a group, more cells than
#: the environment has columns): each is shown verbatim, and the report compiles.
MISPLACED = [r"b > \text{a & b}", r"b > \text{a \\ b}", r"b > {a & b}", r"b > \mbox{a & b}", r"b > \frac{a & b}{2}",
             r"\begin{aligned} a &= \text{x & y} \end{aligned}", r"\begin{bmatrix} 1 & \text{2 & 3} \end{bmatrix}",
             r"b > \begin{array}{c} a & b \end{array}", r"\begin{cases} a & b & c \end{cases}",
             r"\begin{bmatrix} 1&2&3&4&5&6&7&8&9&10&11 \end{bmatrix}", r"b > \sqrt{a \\ b}", r"x^{a \\ b}",
             r"b > \begin{matrix} {a & b} \end{matrix}"]
PLACED = [r"\begin{cases} a & b \\ c \end{cases}", r"\begin{bmatrix} 1 & 0 \\ 0 & 1 \end{bmatrix} \succeq 0",
          r"\begin{aligned} a &= b \\ &\le c \end{aligned}", r"a = b \\ c = d"]


def test_misplaced_alignment_marks_are_shown_verbatim_and_the_report_compiles(tmp_path):
    from hapticproof.audit.runner import AuditReport, EquationResult
    from hapticproof.core.evidence import Evidence, Verdict
    from hapticproof.report import latex as tex

    for display in MISPLACED:
        assert tex.safe_math(display).startswith(r"\begin{hpverbatim}"), display
    for display in PLACED:
        assert tex.safe_math(display).startswith(r"\begin{hpdisplay}"), display
    results = tuple(EquationResult(str(k), "condition", d, d, Verdict.TYPO, d, d, Evidence("counterexample", witness={"c": d}),
                                   0.0) for k, d in enumerate(MISPLACED + PLACED))
    (tmp_path / "r.tex").write_text(tex.audit_document([AuditReport("t", "t", results)]), encoding="utf-8")
    pdflatex = shutil.which("pdflatex")
    if pdflatex is None:
        pytest.skip("pdflatex is not installed")
    run = subprocess.run([pdflatex, "-interaction=nonstopmode", "-no-shell-escape", "-halt-on-error", "r.tex"],
                         cwd=tmp_path, capture_output=True, text=True, timeout=180, check=False)
    assert run.returncode == 0, run.stdout[-2000:]
