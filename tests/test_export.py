"""LaTeX export: the derived conditions as a document that compiles with pdflatex."""

import shutil
import subprocess

import pytest

from hapticproof.audit import audit_paper
from hapticproof.export import export_document
from hapticproof.latex import escape_text, safe_math, to_latex
from hapticproof.registry import get_paper


@pytest.fixture(scope="module")
def hve_document():
    return export_document([get_paper("hve")])


def test_document_structure(hve_document):
    assert hve_document.startswith("\\documentclass")
    assert "\\usepackage{amsmath" in hve_document
    assert hve_document.rstrip().endswith("\\end{document}")
    # every defective printed equation appears, labelled, with its correction
    report = audit_paper(get_paper("hve"))
    corrected = [r for r in report.results if r.corrected]
    assert hve_document.count(r"\hplabel{Corrected}") == len(corrected) > 0
    for result in corrected:
        assert "{hve-eq-" + result.id + "}" in hve_document


def test_unbalanced_printed_text_is_shown_verbatim():
    shown = safe_math(r"\frac{a}{b))}")
    assert "hpverbatim" in shown and "hpfit" not in shown
    assert escape_text("50% & $x$") == r"50\% \& \$x\$"


@pytest.mark.skipif(shutil.which("pdflatex") is None, reason="pdflatex is not installed")
def test_export_compiles_with_pdflatex(tmp_path, hve_document):
    source = tmp_path / "conditions.tex"
    source.write_text(hve_document)
    result = subprocess.run(
        ["pdflatex", "-interaction=nonstopmode", "-halt-on-error", source.name],
        cwd=tmp_path, capture_output=True, text=True, timeout=120,
    )
    assert result.returncode == 0, result.stdout[-3000:]
    assert (tmp_path / "conditions.pdf").stat().st_size > 1000


@pytest.mark.skipif(shutil.which("pdflatex") is None, reason="pdflatex is not installed")
def test_audit_report_compiles_with_pdflatex(tmp_path):
    source = tmp_path / "audit.tex"
    source.write_text(audit_paper(get_paper("hve")).to_latex())
    result = subprocess.run(["pdflatex", "-interaction=nonstopmode", "-halt-on-error", source.name],
                            cwd=tmp_path, capture_output=True, text=True, timeout=120)
    assert result.returncode == 0, result.stdout[-3000:]


def test_to_latex_uses_paper_names():
    import sympy as sp

    K01 = sp.Symbol("K_01")
    assert to_latex(K01 * 2, {K01: "K_{01}"}) == "2 K_{01}"
