"""Reports people read: every LaTeX output typesets cleanly with pdflatex, and the HTML report
renders as MathML in a real browser (headless Chromium).

The PDFs, logs, HTML pages and screenshots are left in the artefacts directory (``test-artefacts/``
or ``$HAPTICPROOF_ARTEFACTS``; git-ignored) for a person to look at. Without pdflatex/pdftotext or
chromium the corresponding tests are skipped with the reason; ``.ci/run`` installs both.
"""

from __future__ import annotations

import importlib.util
import io
import json
import os
import re
import shutil
import subprocess
from pathlib import Path

import pytest

from hapticproof.report import latex as tex
from hapticproof.cli import main
from hapticproof.core.evidence import Plot, Verdict
from hapticproof.report.export import export_document
from hapticproof.report.html import _plots, report_html
from hapticproof.audit.registry import papers
from hapticproof.report.sanitize import html_violations

HERE = Path(__file__).resolve().parent
_spec = importlib.util.spec_from_file_location("hp_chromium", HERE / "chromium.py")
chromium = importlib.util.module_from_spec(_spec)
_spec.loader.exec_module(chromium)

CHROMIUM = chromium.find_chromium()
needs_tex = pytest.mark.skipif(
    shutil.which("pdflatex") is None or shutil.which("pdftotext") is None,
    reason="pdflatex and pdftotext are not installed (Debian: texlive-latex-base texlive-latex-recommended "
           "poppler-utils; .ci/run installs them)")
needs_chromium = pytest.mark.skipif(CHROMIUM is None, reason="chromium is not installed (Debian: chromium; "
                                                             ".ci/run installs it)")
MAX_OVERFULL_PT = 20.0


# ---------------------------------------------------------------------------------------------
# LaTeX: compile, then read the log and the text of the PDF
# ---------------------------------------------------------------------------------------------
def typeset(source: str, name: str, directory: Path) -> tuple[str, str]:
    """Compile ``source`` with pdflatex in ``directory``; return (log, text of the PDF)."""
    path = directory / f"{name}.tex"
    path.write_text(source, encoding="utf-8")
    run = subprocess.run(["pdflatex", "-no-shell-escape", "-interaction=nonstopmode", "-halt-on-error", path.name],
                         cwd=directory, capture_output=True, text=True, timeout=300,
                         env=dict(os.environ, openout_any="p", openin_any="p"))  # the README's command
    log = (directory / f"{name}.log").read_text(encoding="latin-1")
    assert run.returncode == 0, f"{name}.tex does not compile:\n" + run.stdout[-3000:]
    text = subprocess.run(["pdftotext", "-enc", "UTF-8", f"{name}.pdf", "-"], cwd=directory,
                          capture_output=True, text=True, timeout=120).stdout
    return log, text


def assert_typesets_cleanly(source: str, name: str, directory: Path) -> str:
    log, text = typeset(source, name, directory)
    wide = [float(w) for w in re.findall(r"Overfull \\[hv]box \(([\d.]+)pt too", log) if float(w) > MAX_OVERFULL_PT]
    assert not wide, f"{name}: overfull boxes wider than {MAX_OVERFULL_PT} pt: {wide} (see {directory / name}.log)"
    bad = [line for line in text.splitlines() if "\u00a1" in line or "\u00bf" in line]
    assert not bad, f"{name}: '<' or '>' typeset as inverted punctuation: {bad[:5]}"
    return text


@needs_tex
def test_audit_pdf_of_every_paper_typesets(audit_reports, artefacts):
    """``hapticproof audit --all --format tex`` (the same document, from the shared audit)."""
    text = assert_typesets_cleanly(tex.audit_document(audit_reports), "audit-all", artefacts)
    assert "Printed" in text and "Derived" in text and "Corrected" in text
    assert "x_h(kT" in text  # an underscore of prose is an underscore, not a subscript


@needs_tex
def test_export_pdf_typesets(audit_reports, artefacts):
    document = export_document(list(papers().values()), reports=audit_reports)
    text = assert_typesets_cleanly(document, "export-all", artefacts)
    assert "All conditions in one notation" in text


DERIVE = {
    "single-user": ["derive", "single-user"],
    "single-user-delay-n": ["derive", "single-user", "--delay", "n"],
    "single-user-numeric": ["derive", "single-user", "--param", "K=2", "--param", "T=0.001", "--param", "b=0.0009",
                            "--param", "B=0", "--delay", "2"],
    "multi-user": ["derive", "multi-user", "--users", "3"],
    "multi-user-uniform": ["derive", "multi-user", "--users", "3", "--uniform", "--delay", "2"],
    "teleoperator": ["derive", "teleoperator", "--controller", "filtered-pd", "--param", "a=1/2"],
    "network": ["derive", "network", "--matrix", "{matrix}"],
    # the designer's answers as displays (issue 21): margins, ranges with rational and algebraic ends
    "single-user-answers": ["derive", "single-user", "--environment", "K + B*(1-a)*(z-1)/(T*(z-a))", "--param",
                            "B=0.005", "--param", "a=0.5", "--param", "T=0.001", "--param", "b=0.02", "--param",
                            "K=2", "--delay", "2", "--range", "K", "--range", "b", "--delay-margin"],
    "multi-user-answers": ["derive", "multi-user", "--users", "2", "--uniform", "--param", "b=0.02", "--param",
                           "K_0=10", "--param", "K=5", "--param", "B_0=0", "--param", "B=0", "--param", "T=0.001",
                           "--delay-margin", "--range", "K"],
    "teleoperator-answers": ["derive", "teleoperator", "--param", "K=20", "--param", "B=0.01", "--param", "T=0.001",
                             "--param", "b_s=0.05", "--range", "b_m"],
}


def _derive(argv: list[str], tmp_path: Path, capsys, *extra: str) -> str:
    matrix = tmp_path / "z5.txt"
    matrix.write_text("# eq. (5) of the 3-DOF bilateral paper\n9/(s+3), -1/(s+1)\n-1/(s+1), 1/(s+3)\n")
    capsys.readouterr()
    assert main([a.format(matrix=matrix) for a in argv] + ["--format", "latex", *extra]) == 0
    return capsys.readouterr().out


@needs_tex
@pytest.mark.parametrize("name", list(DERIVE))
def test_derive_latex_is_a_document_that_typesets(name, tmp_path, capsys, artefacts):
    document = _derive(DERIVE[name], tmp_path, capsys)
    assert document.startswith("\\documentclass") and "\\end{document}" in document
    assert_typesets_cleanly(document, f"derive-{name}", artefacts)


@needs_tex
def test_derive_fragments_compile_in_an_amsmath_paper(tmp_path, capsys):
    body = "\n".join(_derive(DERIVE[name], tmp_path, capsys, "--fragment")
                     for name in ("single-user", "teleoperator", "network", "multi-user", "single-user-answers",
                                  "multi-user-answers", "teleoperator-answers"))
    assert "\\documentclass" not in body
    paper = "\\documentclass{article}\n\\usepackage{amsmath,amssymb}\n\\begin{document}\n" + body + "\n\\end{document}\n"
    typeset(paper, "fragments", tmp_path)


# ---------------------------------------------------------------------------------------------
# HTML: the page itself
# ---------------------------------------------------------------------------------------------
@pytest.fixture(scope="module")
def hve_page(audit_reports, artefacts) -> Path:
    (hve,) = [r for r in audit_reports if r.paper == "hve"]
    path = artefacts / "report-hve.html"
    path.write_text(report_html([hve]), encoding="utf-8")
    return path


@pytest.fixture(scope="module")
def all_page(audit_reports, artefacts) -> Path:
    path = artefacts / "report-all.html"
    path.write_text(report_html(audit_reports), encoding="utf-8")
    return path


def _expected_fallbacks(reports) -> int:
    """Displays that cannot be mathematics: an empty printed display (noted as such) and
    OCR-damaged printed text with unbalanced braces or environments (e.g. a missing
    \\end{bmatrix}), shown as marked source."""
    def damaged(text: str) -> bool:
        return not text.strip() or not tex.is_balanced(tex.strip_tag(text)[0])

    return sum(damaged(text) for report in reports for r in report.results
               for text in ([r.printed] if r.kind != "claim" else []) + [t for t in (r.derived, r.corrected) if t])


def test_html_report_is_one_self_contained_page(audit_reports, all_page):
    page = all_page.read_text(encoding="utf-8")
    assert page.startswith("<!DOCTYPE html>") and "<script" not in page.lower()
    assert html_violations(page) == []  # nothing runs or loads; the policy is the first thing in <head>
    assert not re.search(r"""(src|href)=["']?(https?:)?//""", page), "the page must not load anything"
    assert "merror" not in page
    # one anchor per equation, a summary chip per verdict present, linked to its index row
    ids = re.findall(r'<article class="hp-eq hp-v-[a-z-]+" id="([^"]+)"', page)
    assert len(ids) == len(set(ids)) == sum(len(r.results) for r in audit_reports)
    for verdict in Verdict:
        n = sum(r.verdict == verdict for rep in audit_reports for r in rep.results)
        assert (f'href="#verdict-{verdict.value}">{verdict.value} <b>{n}</b></a>' in page) == (n > 0)
    # every display is MathML except the OCR-damaged printed text, shown as marked source
    displays = page.count('<div class="hp-display')
    fallbacks = page.count('<div class="hp-display hp-fallback"')
    assert displays > 300 and fallbacks == _expected_fallbacks(audit_reports) <= 3
    # the plots carried in the evidence are inline SVG
    plots = sum(len(_plots(r.evidence.facts)) for rep in audit_reports for r in rep.results)
    assert plots >= 5 and page.count("<svg") == plots


# ---------------------------------------------------------------------------------------------
# HTML in a real browser
# ---------------------------------------------------------------------------------------------
DOM_CHECK = """(() => {
  const displays = [...document.querySelectorAll('.hp-display')];
  const maths = [...document.querySelectorAll('math')];
  return {
    displays: displays.length,
    mathml: displays.filter(d => d.querySelector('math') && !d.classList.contains('hp-fallback')).length,
    fallbacks: displays.filter(d => d.classList.contains('hp-fallback')).length,
    merror: document.querySelectorAll('merror').length,
    notMathML: maths.filter(m => !(m instanceof MathMLElement)).length,
    notLaidOut: maths.filter(m => !getComputedStyle(m).display.includes('math')
                                  || m.getBoundingClientRect().width <= 0).length,
    scrollWidth: document.documentElement.scrollWidth,
    innerWidth: innerWidth,
  };
})()"""


@pytest.fixture(scope="module")
def browser():
    if CHROMIUM is None:
        pytest.skip("chromium is not installed")
    with chromium.Browser(CHROMIUM, width=1000, height=800) as b:
        yield b


@needs_chromium
def test_html_report_in_chromium(browser, hve_page, audit_reports, artefacts):
    (hve,) = [r for r in audit_reports if r.paper == "hve"]
    browser.resize(1000, 800)
    browser.open(hve_page.as_uri())
    browser.screenshot(artefacts / "report-hve-first-screen.png")
    dom = browser.evaluate(DOM_CHECK)
    assert dom["merror"] == 0 and dom["notMathML"] == 0 and dom["notLaidOut"] == 0, dom
    assert dom["mathml"] + dom["fallbacks"] == dom["displays"] and dom["fallbacks"] == _expected_fallbacks([hve]), dom
    assert dom["scrollWidth"] <= dom["innerWidth"], dom
    # an equation anchor scrolls its card to the top
    browser.open(hve_page.as_uri() + "#eq-17")
    top = browser.evaluate("document.getElementById('eq-17').getBoundingClientRect().top")
    assert 0 <= top < 40 and browser.evaluate("document.querySelector(':target').id") == "eq-17"
    browser.screenshot(artefacts / "report-hve-eq-17.png")
    # a narrow window: long displays wrap or scroll inside their box, the page does not widen
    browser.resize(420, 800)
    browser.open(hve_page.as_uri())
    dom = browser.evaluate(DOM_CHECK)
    assert dom["scrollWidth"] <= dom["innerWidth"], dom
    browser.screenshot(artefacts / "report-hve-narrow.png")


@needs_chromium
def test_html_report_of_every_paper_in_chromium(browser, all_page, audit_reports):
    browser.resize(1000, 800)
    browser.open(all_page.as_uri())
    dom = browser.evaluate(DOM_CHECK)
    assert dom["merror"] == 0 and dom["notMathML"] == 0 and dom["notLaidOut"] == 0, dom
    assert dom["mathml"] + dom["fallbacks"] == dom["displays"] == all_page.read_text().count('<div class="hp-display')
    assert dom["scrollWidth"] <= dom["innerWidth"], dom
    plots = browser.evaluate("[...document.querySelectorAll('svg.hp-svg')].filter("
                             "s => s.getBoundingClientRect().width > 200).length")
    assert plots == all_page.read_text().count("<svg")


# ---------------------------------------------------------------------------------------------
# command line and notebooks
# ---------------------------------------------------------------------------------------------
def test_audit_html_and_wide_table(tmp_path, capsys):
    target = tmp_path / "report.html"
    assert main(["audit", "hve", "-e", "17", "-e", "19", "--format", "html", "-o", str(target)]) == 0
    page = target.read_text()
    assert 'id="eq-17"' in page and 'id="eq-19"' in page and "<math" in page
    err = capsys.readouterr().err
    assert "wrote" in err and "2 equations in 1 paper" in err and "\r" not in err  # no bar in a pipe
    assert main(["audit", "hve", "-e", "5", "--wide"]) == 0
    out = capsys.readouterr().out
    (detail,) = [line for line in out.splitlines() if line.startswith("5 ")]
    assert " ..." not in detail and "\033[" not in out   # untruncated; no colour in a pipe


def test_fragment_needs_latex(capsys):
    assert main(["derive", "single-user", "--fragment"]) == 2
    assert capsys.readouterr().err.count("\n") == 1


def test_terminal_progress_and_colour(monkeypatch):
    from hapticproof.cli.terminal import colour_verdict, progress_bar, summary_line, use_colour

    class Terminal(io.StringIO):
        def isatty(self):
            return True

    assert progress_bar(io.StringIO()) is None
    stream = Terminal()
    bar = progress_bar(stream, "audit")
    bar(1, 2)
    bar(2, 2)
    assert "audit [###############---------------] 1/2" in stream.getvalue() and stream.getvalue().endswith("2/2\n")
    monkeypatch.delenv("NO_COLOR", raising=False)
    assert use_colour(Terminal()) and not use_colour(io.StringIO())
    monkeypatch.setenv("NO_COLOR", "1")
    assert not use_colour(Terminal())
    assert summary_line({"confirmed": 2, "wrong": 1}, colour=True).endswith(colour_verdict("confirmed") + " 2")


def test_notebook_views(audit_reports):
    from IPython.core.interactiveshell import InteractiveShell

    from hapticproof.core.evidence import Evidence, Finding
    from hapticproof.report.notebook import register
    from hapticproof.report.summary import summarize_single_user
    from hapticproof.systems.singleuser import SingleUserScene

    shell = InteractiveShell.instance()
    register(shell)
    show = lambda obj: shell.display_formatter.format(obj)[0]  # noqa: E731  (the MIME bundle a notebook gets)
    (hve,) = [r for r in audit_reports if r.paper == "hve"]
    result = next(r for r in hve.results if r.id == "17")
    html = show(result)["text/html"]
    assert "<math" in html and "hp-time" not in html   # no timings: nbval compares
    page = show(hve)["text/html"]
    assert page.startswith('<div class="hp-report">') and "<!DOCTYPE" not in page
    finding = Finding(Verdict.WRONG, "b < KT/2 fails", Evidence("counterexample", witness={"c": "-1"}),
                      corrected=r"b > \frac{KT}{2}")
    assert "hp-wrong" in show(finding)["text/html"] and "<math" in show(finding)["text/html"]
    scene = SingleUserScene.virtual_wall()
    assert show(scene)["text/latex"].startswith("$\\text{single-user scene")
    assert show(summarize_single_user(scene))["text/latex"].startswith("$$\\begin{aligned}")


def test_plot_evidence_is_json(audit_reports):
    (bilateral,) = [r for r in audit_reports if r.paper == "bilateral-3dof"]
    fig3 = next(r for r in bilateral.results if r.id == "fig3-6")
    (plot,) = [p for _, p in _plots(fig3.evidence.facts)]
    assert isinstance(plot, Plot) and {s.label for s in plot.series} == {"k_vmyz = 6", "k_vmyz = 60"}
    assert min(plot.series[0].y) < 0 <= min(plot.series[1].y)   # the k = 6 run goes negative
    data = json.loads(json.dumps(fig3.to_json()))
    assert data["evidence"]["facts"]["plot"]["series"][0]["label"] == "k_vmyz = 6"
