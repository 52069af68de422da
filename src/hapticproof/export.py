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
from typing import Any

from hapticproof import latex as tex
from hapticproof.audit import AuditReport, EquationResult, Paper, audit_paper
from hapticproof.evidence import Evidence, Verdict

__all__ = ["export_document", "conditions_table", "reports_from_json"]


def reports_from_json(data: Any) -> list[AuditReport]:
    """Audit reports read back from ``hapticproof audit --format json`` output (one paper or
    ``{"papers": [...]}``): everything the export shows, without deriving it again.

    >>> r = reports_from_json({"paper": "demo", "title": "Demo", "equations": [{"id": "1", "kind": "claim",
    ...     "printed": "1 + 1 = 2", "derived": None, "verdict": "confirmed", "detail": "arithmetic",
    ...     "corrected": None, "evidence": {"method": "canonical-form"}, "seconds": 0.0}]})
    >>> r[0].results[0].verdict.value
    'confirmed'
    """
    papers = data["papers"] if "papers" in data else [data]
    out = []
    for p in papers:
        results = tuple(
            EquationResult(id=e["id"], kind=e["kind"], printed=e["printed"], derived=e.get("derived"),
                           verdict=Verdict(e["verdict"]), detail=e["detail"], corrected=e.get("corrected"),
                           evidence=Evidence(e["evidence"]["method"], witness=e["evidence"].get("witness"),
                                             instances=e["evidence"].get("instances"),
                                             facts=e["evidence"].get("facts", {})),
                           seconds=e.get("seconds", 0.0))
            for e in p["equations"])
        out.append(AuditReport(p["paper"], p.get("title", ""), results))
    return out


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


def export_document(papers: Iterable[Paper], reports: Iterable[Any] | None = None) -> str:
    """The derived (and corrected) conditions of ``papers`` as a complete amsmath document.

    ``reports``: the papers' audit reports when already computed (one per paper, in order:
    :func:`hapticproof.auditpool.audit_reports`, or a saved audit read back with
    :func:`reports_from_json`), so that exporting does not derive everything a second time."""
    papers = list(papers)
    given = {r.paper: r for r in reports} if reports is not None else {}
    sections: list[tuple[str, str]] = []
    table = conditions_table(papers)
    if table:
        sections.append(("All conditions in one notation", table))
    for paper in papers:
        report = given.get(paper.id) or audit_paper(paper)
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
