"""Export the derived conditions of registered papers as one LaTeX document.

For every equation the document shows the toolkit's derivation and, where the printed equation
is defective, the corrected LaTeX. A paper may also list ``conditions``: ``(label, condition LaTeX, source)``
rows collected into one table in a common notation.

>>> from hapticproof.audit import Paper
>>> doc = export_document([Paper("demo", title="Demo", source="none")])
>>> doc.startswith(r"\\documentclass") and doc.rstrip().endswith(r"\\end{document}")
True
"""

from __future__ import annotations

from collections.abc import Iterable

from hapticproof import latex as tex
from hapticproof.audit import Paper, audit_paper
from hapticproof.evidence import Verdict

__all__ = ["export_document", "conditions_table"]


def conditions_table(papers: Iterable[Paper]) -> str:
    """One table of the papers' ``conditions`` rows (label, condition, source)."""
    rows = []
    for paper in papers:
        for label, condition, source in paper.condition_rows():
            rows.append(
                tex.escape_text(label) + " & $\\displaystyle " + condition + "$ & " + tex.escape_text(source) + r" \\"
            )
    if not rows:
        return ""
    return "\n".join(
        [r"\begin{center}\begin{tabular}{lll}", r"condition & statement & source \\ \hline", *rows, r"\end{tabular}\end{center}"]
    )


def export_document(papers: Iterable[Paper]) -> str:
    """The derived (and corrected) conditions of ``papers`` as a complete amsmath document."""
    papers = list(papers)
    sections: list[tuple[str, str]] = []
    table = conditions_table(papers)
    if table:
        sections.append(("All conditions in one notation", table))
    for paper in papers:
        report = audit_paper(paper)
        body: list[str] = []
        for result in report.results:
            if not result.derived and not result.corrected:
                continue
            label = f"({result.id}) {result.verdict.value}"
            body.append(r"\paragraph{" + tex.escape_text(label) + "}" + " " + tex.escape_text(result.detail))
            if result.derived:
                body.append(tex.safe_math(result.derived))
            if result.corrected and result.verdict != Verdict.CONFIRMED:
                body.append(r"\textit{Corrected printed equation:}")
                body.append(tex.safe_math(result.corrected))
        sections.append((f"{paper.title} ({paper.id})", "\n".join(body) or "No derived conditions."))
    return tex.document("Derived stability and passivity conditions (hapticproof)", sections)
