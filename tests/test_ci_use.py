"""The audit in a paper's CI (issue 29): ``audit --fail-on VERDICTS`` exits with status 1 exactly when
one of those verdicts is present (2 stays a user's mistake), and writes its report as usual."""

from __future__ import annotations

import json
import sys
from pathlib import Path

import pytest

sys.path.insert(0, str(Path(__file__).resolve().parent))

from clirun import one_line_error, run  # noqa: E402

from hapticproof.cli.audit import FAIL_STATUS  # noqa: E402
from hapticproof.core.evidence import Verdict  # noqa: E402

#: Colgate's condition right, with a lost half (a typo) and with the sign of B lost (wrong).
PAPER = r"""
[paper]
id = "walls"
title = "Three walls"

[symbols]
b = "positive"
K = "positive"
B = "positive"
T = "positive"

[scenes.wall]
system = "single-user"
environment = "K + B*(z - 1)/(T*z)"

[[equations]]
id = "1"
printed = 'b > \frac{KT}{2} + B'
claim = "passivity-condition"
scene = "wall"

[[equations]]
id = "2"
printed = 'b > KT + B'
claim = "passivity-condition"
scene = "wall"

[[equations]]
id = "3"
printed = 'b > \frac{KT}{8} - B'
claim = "passivity-condition"
scene = "wall"
"""


@pytest.fixture(scope="module")
def paper(tmp_path_factory):
    path = tmp_path_factory.mktemp("ci") / "walls.toml"
    path.write_text(PAPER)
    return path


@pytest.fixture(scope="module")
def verdicts(paper):
    from hapticproof.cli import main

    import contextlib
    import io

    out = io.StringIO()
    with contextlib.redirect_stdout(out), contextlib.redirect_stderr(io.StringIO()):
        assert main(["audit", "--paper", str(paper), "--format", "json"]) == 0      # no --fail-on: 0 whatever it finds
    return {e["id"]: e["verdict"] for e in json.loads(out.getvalue())["equations"]}


def test_the_paper_has_one_of_each(verdicts):
    assert verdicts == {"1": "confirmed", "2": "typo", "3": "wrong"}


@pytest.mark.parametrize("verdict", [v.value for v in Verdict])
def test_fail_on_each_verdict_exits_1_exactly_when_it_is_present(capsys, paper, verdicts, verdict):
    code, _, err = run(capsys, "audit", "--paper", str(paper), "--fail-on", verdict)
    present = verdict in verdicts.values()
    assert code == (FAIL_STATUS if present else 0) and FAIL_STATUS == 1
    assert (f"--fail-on {verdict}: {verdict} 1" in err) == present


def test_fail_on_a_list_writes_the_report_and_names_what_it_found(capsys, paper, tmp_path):
    report = tmp_path / "audit.json"
    code, _, err = run(capsys, "audit", "--paper", str(paper), "--fail-on", "wrong,typo,inconsistent",
                       "--format", "json", "-o", str(report))
    assert code == 1
    assert err.strip().splitlines()[-1] == "hapticproof: --fail-on wrong,typo,inconsistent: wrong 1, typo 1"
    assert [e["verdict"] for e in json.loads(report.read_text())["equations"]] == ["confirmed", "typo", "wrong"]
    # repeated options add up; a verdict that is absent does not fail
    assert run(capsys, "audit", "--paper", str(paper), "--fail-on", "inconsistent", "--fail-on", "malformed")[0] == 0
    assert run(capsys, "audit", "--paper", str(paper), "-e", "1", "--fail-on", "wrong,typo")[0] == 0


def test_fail_on_the_bundled_audit(capsys):
    # the classic conditions: all right, so failing on every defect passes
    code, _, _ = run(capsys, "audit", "classics", "--fail-on", "wrong,typo,inconsistent,malformed")
    assert code == 0


@pytest.mark.parametrize("argv, message", [
    (["--fail-on", "wrng"], "unknown verdict 'wrng' (did you mean 'wrong'?)"),
    (["--fail-on", "wrong,,typo"], "--fail-on expects verdicts separated by commas"),
    (["--fail-on", "wrong", "--mutate"], "--fail-on reads the audit's verdicts"),
])
def test_fail_on_mistakes_are_exit_2(capsys, paper, argv, message):
    err = one_line_error(capsys, "audit", "--paper", str(paper), *argv)
    assert message in err
