"""Export the derived conditions of registered papers as one LaTeX document.

For every equation the document shows the toolkit's derivation and, where the printed equation
is defective, the printed display and its correction, each labelled. A paper may also list
``conditions``: ``(label, condition LaTeX, source)`` rows collected into one table in a common
notation (a table whose cells wrap, across pages).

>>> from hapticproof.audit.runner import Paper
>>> doc = export_document([Paper("demo", title="Demo", source="none")])
>>> doc.startswith(r"\\documentclass") and doc.rstrip().endswith(r"\\end{document}")
True
"""

from __future__ import annotations

from collections.abc import Callable, Iterable
from typing import Any

from hapticproof.report import latex as tex
from hapticproof.audit.runner import AuditReport, EquationResult, Paper, audit_paper
from hapticproof.core.evidence import Evidence, Verdict

__all__ = ["export_document", "conditions_table", "reports_from_json"]


def reports_from_json(data: Any, papers: Iterable[Paper] = ()) -> list[AuditReport]:
    """Audit reports read back from ``hapticproof audit --format json`` output (one paper or
    ``{"papers": [...]}``): everything the export shows, without deriving it again. The
    registered ``papers`` supply what the JSON does not carry (each equation's section and
    assumptions).

    >>> r = reports_from_json({"paper": "demo", "title": "Demo", "equations": [{"id": "1", "kind": "claim",
    ...     "printed": "1 + 1 = 2", "derived": None, "verdict": "confirmed", "detail": "arithmetic",
    ...     "corrected": None, "evidence": {"method": "canonical-form"}, "seconds": 0.0}]})
    >>> r[0].results[0].verdict.value
    'confirmed'
    """
    registered = {p.id: p for p in papers}
    out = []
    for p in data["papers"] if "papers" in data else [data]:
        known = registered[p["paper"]].equations if p["paper"] in registered else {}
        results = tuple(
            EquationResult(id=e["id"], kind=e["kind"], printed=e["printed"], derived=e.get("derived"),
                           verdict=Verdict(e["verdict"]), detail=e["detail"], corrected=e.get("corrected"),
                           evidence=Evidence(e["evidence"]["method"], witness=e["evidence"].get("witness"),
                                             instances=e["evidence"].get("instances"),
                                             facts=e["evidence"].get("facts", {})),
                           seconds=e.get("seconds", 0.0),
                           section=known[e["id"]].section if e["id"] in known else "",
                           assumptions=known[e["id"]].assumptions if e["id"] in known else "")
            for e in p["equations"])
        out.append(AuditReport(p["paper"], p.get("title", ""), results, p.get("notation") or {}, p.get("names") or {}))
    return out


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
