"""The parallel audit gives the serial audit's output; export reuses an audit instead of deriving again."""

from __future__ import annotations

import json

from hapticproof.audit.runner import audit_paper
from hapticproof.audit.pool import audit_reports
from hapticproof.cli import main
from hapticproof.report.export import export_document, reports_from_json
from hapticproof.audit.registry import get_paper
from hapticproof.report.latex import audit_document
from hapticproof.report.tables import audit_table


def without_seconds(report_json):
    for eq in report_json["equations"]:
        eq.pop("seconds")
    return report_json


def test_workers_give_the_serial_reports():
    paper = get_paper("classics")
    serial = audit_paper(paper)
    (parallel,) = audit_reports([paper], jobs=2)
    assert without_seconds(parallel.to_json()) == without_seconds(serial.to_json())
    assert audit_table(parallel) == audit_table(serial) and audit_document([parallel]) == audit_document([serial])
    # a saved audit read back renders the same export as the audit in memory (no re-derivation)
    assert export_document([paper], reports=reports_from_json(serial.to_json(), [paper])) == export_document([paper], reports=[serial])


def test_export_from_a_saved_audit(tmp_path, capsys):
    paper = get_paper("classics")
    saved = tmp_path / "audit.json"
    assert main(["audit", "classics", "--format", "json", "--jobs", "2", "-o", str(saved)]) == 0
    reports = reports_from_json(json.loads(saved.read_text()), [paper])
    assert [r.id for r in reports[0].results] == [eq.id for eq in paper.ordered()]
    out = tmp_path / "conditions.tex"
    assert main(["export", "classics", "--from-audit", str(saved), "-o", str(out)]) == 0
    assert out.read_text() == export_document([paper], reports=reports)
    assert main(["export", "hve", "--from-audit", str(saved)]) == 2
    assert "no audit of hve" in capsys.readouterr().err
    assert main(["audit", "classics", "--jobs", "0"]) == 2


def test_a_check_that_raises_raises_in_the_parent():
    import pytest

    from hapticproof.audit.runner import Evidence, Finding, Paper, Verdict

    paper = Paper("demo-errors", title="Demo", source="none")

    @paper.equation("1", kind="claim", printed="fine")
    def fine(ctx):
        return Finding(Verdict.CONFIRMED, "fine", Evidence("canonical-form"))

    @paper.equation("2", kind="claim", printed="a bug")
    def bug(ctx):
        raise ZeroDivisionError("a bug in a check")

    with pytest.raises(ZeroDivisionError, match="a bug in a check"):
        audit_reports([paper], jobs=2)
