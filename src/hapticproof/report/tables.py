"""Plain-text and Markdown views of audit reports: what ``hapticproof audit`` prints on a terminal
(``--format table``) and ``--format markdown``.
"""

from __future__ import annotations

import textwrap
from collections.abc import Callable

from hapticproof.audit.runner import AuditReport
from hapticproof.core.evidence import Verdict
from hapticproof.report.readable import plural

__all__ = ["audit_table", "audit_markdown"]


def audit_table(report: AuditReport, width: int = 120, wide: bool = False,
                style: Callable[[str], str] | None = None) -> str:
    """Plain-text table: equation, verdict, detail (shortened to one line unless ``wide``);
    ``style(verdict_text)`` may decorate the verdict column (the CLI colours it)."""
    lines = [f"{report.paper}: {report.title}", ""]
    if getattr(report, "notation", None):
        lines[-1:] = ["notation: " + ", ".join(f"{k} = {v}" for k, v in report.notation.items()), ""]
    id_w = max([len("eq")] + [len(r.id) for r in report.results])
    v_w = max(len(v.value) for v in Verdict)
    header = f"{'eq'.ljust(id_w)}  {'verdict'.ljust(v_w)}  detail"
    lines += [header, "-" * min(width, len(header) + 60)]
    detail_w = max(30, width - id_w - v_w - 4)
    for r in report.results:
        detail = r.detail if wide else textwrap.shorten(r.detail, detail_w, placeholder=" ...")
        verdict = r.verdict.value.ljust(v_w)
        lines.append(f"{r.id.ljust(id_w)}  {style(verdict) if style else verdict}  {detail}")
    summary = ", ".join(f"{k}: {v}" for k, v in sorted(report.counts().items()))
    lines += ["", f"{plural(len(report.results), 'equation')} ({summary})"]
    return "\n".join(lines)


def audit_markdown(report: AuditReport) -> str:
    """A Markdown section: one table row per equation (verdict, detail, corrected LaTeX)."""
    def cell(text: str | None) -> str:
        return (text or "").replace("|", r"\|").replace("\n", " ")

    lines = [f"## {report.paper}: {report.title}", ""]
    if getattr(report, "notation", None):
        lines += ["Notation: " + ", ".join(f"`{cell(k)} = {cell(v)}`" for k, v in report.notation.items()), ""]
    lines += ["| eq | kind | verdict | detail | corrected |", "|---|---|---|---|---|"]
    for r in report.results:
        corrected = f"`{cell(r.corrected)}`" if r.corrected else ""
        lines.append(f"| {r.id} | {r.kind} | **{r.verdict.value}** | {cell(r.detail)} | {corrected} |")
    return "\n".join(lines) + "\n"
