"""LaTeX export: the derived conditions as a document (compiled with pdflatex in test_reports.py)."""

import sympy as sp

from hapticproof.report.export import export_document
from hapticproof.report.latex import display_breaks, display_lines, escape_text, is_typesettable, safe_math, to_latex
from hapticproof.audit.registry import get_paper


def test_document_structure(audit_reports):
    (hve,) = [r for r in audit_reports if r.paper == "hve"]
    document = export_document([get_paper("hve")], reports=[hve])
    assert document.startswith("\\documentclass")
    assert "\\usepackage[T1]{fontenc}" in document and "\\usepackage{amsmath" in document
    assert document.rstrip().endswith("\\end{document}")
    # every defective printed equation appears, labelled, with its correction
    corrected = [r for r in hve.results if r.corrected]
    assert document.count(r"\hplabel{Corrected}") == len(corrected) > 0
    for result in corrected:
        assert "{hve-eq-" + result.id + "}" in document


def test_unbalanced_printed_text_is_shown_verbatim():
    shown = safe_math(r"\frac{a}{b}}")
    assert "hpverbatim" in shown and "hpfit" not in shown
    assert escape_text("50% & $x$") == r"50\% \& \$x\$"
    # parentheses may be unbalanced (an interval; OCR damage the audit reports): still mathematics
    assert is_typesettable(r"\omega \in [0, \infty)") and not is_typesettable(r"\left( x")


def test_prose_relations_are_mathematics():
    # pdflatex with OT1 fonts printed '<' as an inverted exclamation mark
    text = escape_text("K (T/2 + t_d) < b + B, b >= B + K*T/2, |B|, x_h(kT)")
    assert "<" not in text.replace("$<$", "") and ">" not in text.replace("$>$", "")
    assert r"$\geq$" in text and r"$|$B$|$" in text and r"x\_h" in text


def test_display_lines_and_breaks():
    lines, tag = display_lines(r"\begin{aligned} G^{-1}(z) &= b + \frac{K T}{z - 1} \\ &\le c \end{aligned} \tag{20}")
    assert lines == [r"G^{-1}(z) = b + \frac{K T}{z - 1}", r"\le c"] and tag == "20"
    # nothing inside braces, \left...\right or environments is cut
    pieces = display_breaks(r"x = \left(a + b\right) - \frac{c + d}{2} + \begin{bmatrix} 1 & -2 \end{bmatrix}")
    assert [p for p, _ in pieces] == ["x", r"{}= \left(a + b\right)", r"{}- \frac{c + d}{2}",
                                      r"{}+ \begin{bmatrix} 1 & -2 \end{bmatrix}"]
    # a sign is not a break: after a relation, an opening parenthesis or at the start
    assert [p for p, _ in display_breaks(r"-a \geq (-b + c)")] == ["-a", r"{}\geq (-b", "{}+ c)"]


def test_to_latex_uses_paper_names():
    K01 = sp.Symbol("K_01")
    assert to_latex(K01 * 2, {K01: "K_{01}"}) == "2 K_{01}"
