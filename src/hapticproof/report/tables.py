"""Plain-text and Markdown views of audit reports: what ``hapticproof audit`` prints on a terminal
(``--format table``) and ``--format markdown``, each escaped for its format
(:mod:`hapticproof.core.escape`).
"""

from __future__ import annotations

import textwrap
from collections.abc import Callable

from hapticproof.audit.runner import AuditReport
from hapticproof.core.escape import for_markdown, for_markdown_code, for_terminal
from hapticproof.core.evidence import Verdict
from hapticproof.report.readable import plural

__all__ = ["audit_table", "audit_markdown"]


def audit_table(report: AuditReport, width: int = 120, wide: bool = False,
                style: Callable[[str], str] | None = None) -> str:
    """Plain-text table: equation, verdict, detail (shortened to one line unless ``wide``);
    ``style(verdict_text)`` may decorate the verdict column (the CLI colours it)."""
    lines = [f"{for_terminal(report.paper)}: {for_terminal(report.title)}", ""]
    if getattr(report, "notation", None):
        lines[-1:] = ["notation: " + for_terminal(", ".join(f"{k} = {v}" for k, v in report.notation.items())), ""]
    ids = [for_terminal(r.id) for r in report.results]
    id_w = max([len("eq")] + [len(i) for i in ids])
    v_w = max(len(v.value) for v in Verdict)
    header = f"{'eq'.ljust(id_w)}  {'verdict'.ljust(v_w)}  detail"
    lines += [header, "-" * min(width, len(header) + 60)]
    detail_w = max(30, width - id_w - v_w - 4)
    for shown_id, r in zip(ids, report.results):
        detail = for_terminal(r.detail if wide else textwrap.shorten(r.detail, detail_w, placeholder=" ..."))
        verdict = r.verdict.value.ljust(v_w)
        lines.append(f"{shown_id.ljust(id_w)}  {style(verdict) if style else verdict}  {detail}")
    summary = ", ".join(f"{k}: {v}" for k, v in sorted(report.counts().items()))
    lines += ["", f"{plural(len(report.results), 'equation')} ({summary})"]
    return "\n".join(lines)


def audit_markdown(report: AuditReport) -> str:
    """A Markdown section: one table row per equation (verdict, detail, corrected LaTeX); every
    text from the paper file is escaped (:func:`hapticproof.core.escape.for_markdown`: no raw
    HTML reaches a Markdown viewer) and the LaTeX is an inline code span."""
    lines = [f"## {for_markdown(report.paper)}: {for_markdown(report.title)}", ""]
    if getattr(report, "notation", None):
        lines += ["Notation: " + ", ".join(for_markdown_code(f"{k} = {v}") for k, v in report.notation.items()), ""]
    lines += ["| eq | kind | verdict | detail | corrected |", "|---|---|---|---|---|"]
    for r in report.results:
        corrected = for_markdown_code(r.corrected) if r.corrected else ""
        lines.append(f"| {for_markdown(r.id)} | {for_markdown(r.kind)} | **{for_markdown(r.verdict.value)}** | "
                     f"{for_markdown(r.detail)} | {corrected} |")
    return "\n".join(lines) + "\n"
