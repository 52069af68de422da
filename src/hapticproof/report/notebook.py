r"""Notebook views: how scenes, findings and audit reports display in Jupyter.

The value objects of the lower layers know nothing of their views (outputs are views); when
``hapticproof`` is imported inside a running IPython, :func:`register` adds these functions to
IPython's display formatters, by class name, so a scene shows as mathematics and a finding or an
audit report as the HTML report's card.

>>> from hapticproof.systems.singleuser import SingleUserScene
>>> latex_view(SingleUserScene.virtual_wall()).startswith("$\\text{single-user scene")
True
"""

from __future__ import annotations

from typing import Any

from hapticproof.report.html import finding_html, report_fragment, result_html
from hapticproof.report.latex import scene_latex

__all__ = ["VIEWS", "latex_view", "finding_view", "result_view", "report_view", "register"]


def latex_view(scene: Any) -> str:
    """A scene model as inline mathematics."""
    return "$" + scene_latex(scene) + "$"


def finding_view(finding: Any) -> str:
    """A :class:`~hapticproof.core.evidence.Finding` as an HTML card."""
    return finding_html(finding)


def result_view(result: Any) -> str:
    """One audited equation as an HTML card, without timings (notebooks compare outputs)."""
    return result_html(result, timings=False)


def report_view(report: Any) -> str:
    """An audit report as the HTML report's body, without timings."""
    return report_fragment([report], timings=False, prefixed=True)


#: (module, class name) -> (MIME type, view)
VIEWS = {
    ("hapticproof.systems.singleuser", "SingleUserScene"): ("text/latex", latex_view),
    ("hapticproof.systems.multiuser", "MultiUserScene"): ("text/latex", latex_view),
    ("hapticproof.systems.teleoperator", "TeleoperatorScene"): ("text/latex", latex_view),
    ("hapticproof.core.evidence", "Finding"): ("text/html", finding_view),
    ("hapticproof.audit.runner", "EquationResult"): ("text/html", result_view),
    ("hapticproof.audit.runner", "AuditReport"): ("text/html", report_view),
}


def register(shell: Any) -> None:
    """Register every view with an IPython shell's display formatters (by class name, so the
    classes are not imported here)."""
    formatters = shell.display_formatter.formatters
    for (module, name), (mime, view) in VIEWS.items():
        formatters[mime].for_type_by_name(module, name, view)
