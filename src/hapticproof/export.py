"""Export the derived conditions of registered papers as one LaTeX document.

For every equation the document shows the toolkit's derivation and, where the printed equation
is defective, the printed display and its correction, each labelled. A paper may also list
``conditions``: ``(label, condition LaTeX, source)`` rows collected into one table in a common
notation (a table whose cells wrap, across pages).

>>> from hapticproof.audit import Paper
>>> doc = export_document([Paper("demo", title="Demo", source="none")])
>>> doc.startswith(r"\\documentclass") and doc.rstrip().endswith(r"\\end{document}")
True
"""

from __future__ import annotations

from collections.abc import Callable, Iterable

from hapticproof import latex as tex
from hapticproof.audit import AuditReport, Paper, audit_paper

__all__ = ["export_document", "conditions_table"]


def conditions_table(papers: Iterable[Paper]) -> str:
    """One table of the papers' ``conditions`` rows (label, condition, source)."""
    rows = []
    for paper in papers:
        for label, condition, source in paper.condition_rows():
            rows.append([tex.escape_text(label), tex.math_cell(condition), r"{\small " + tex.escape_text(source) + "}"])
    if not rows:
        return ""
    return tex.longtable(["condition", "statement", "source"], rows, [0.25, 0.45, 0.24])


def export_document(papers: Iterable[Paper], progress: Callable[[int, int], None] | None = None,
                    reports: Iterable[AuditReport] | None = None) -> str:
    """The derived (and corrected) conditions of ``papers`` as a complete document.

    ``progress(done, total)`` is called after each audited equation (over all papers);
    ``reports`` (the papers' audit reports, in the same order) are used instead of auditing.
    """
    papers = list(papers)
    if reports is None:
        total = sum(len(p.equations) for p in papers)
        done = 0
        audited = []
        for paper in papers:
            def tick(k: int, _n: int, base: int = done) -> None:
                if progress is not None:
                    progress(base + k, total)
            audited.append(audit_paper(paper, progress=tick))
            done += len(paper.equations)
        reports = audited
    sections: list[tuple[str, str]] = []
    table = conditions_table(papers)
    if table:
        sections.append(("All conditions in one notation", table))
    for paper, report in zip(papers, reports):
        body: list[str] = []
        for result in report.results:
            if not result.derived and not result.corrected:
                continue
            body.append(tex.equation_block(result, tex.anchor(paper.id, result.id, single=False),
                                           show_printed=bool(result.corrected), evidence=False))
        sections.append((f"{paper.title} ({paper.id})", "\n\n".join(body) or "No derived conditions."))
    return tex.document("Derived stability and passivity conditions (hapticproof)", sections)
