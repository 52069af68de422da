"""Issue 30, ``check``: a forged report is refused (exit 1, one line on standard error), and a
genuine report is accepted only when every verdict is backed by evidence that was re-verified
and bound to what the verdict is about. An unverifiable ``proved`` is never success.
"""

from __future__ import annotations

import copy
import json
import sys
from pathlib import Path

import pytest

sys.path.insert(0, str(Path(__file__).resolve().parent))

from clirun import check_file, json_of  # noqa: E402
from forgeries import NOT_PASSIVE, PASSIVE, forged_audits, forged_walls

from hapticproof.cli import main
from hapticproof.exact.checker import check_report

ROOT = Path(__file__).resolve().parents[1]


@pytest.fixture(scope="module")
def walls():
    out = [json_of(*argv) for argv in (NOT_PASSIVE, PASSIVE)]
    assert out[0]["verdict"] == "disproved" and out[1]["verdict"] == "proved"
    return out


@pytest.fixture(scope="module")
def audit():
    return json_of("audit", "--paper", ROOT / "examples" / "hve-single-user.toml", "--format", "json")


def test_genuine_wall_reports_are_accepted(capsys, tmp_path, walls):
    for report in walls:
        status, out, err = check_file(capsys, tmp_path, report)
        assert status == 0 and out.rstrip().endswith("report accepted") and err == "", out[-600:]


def test_each_forged_wall_report_is_refused(capsys, tmp_path, walls):
    forgeries = forged_walls(*walls)
    assert len(forgeries) == 14
    for what, report, expected in forgeries:
        status, out, err = check_file(capsys, tmp_path, report)
        assert status == 1, (what, out[-800:])
        assert "report accepted" not in out and expected in out + err, (what, expected, out[-800:], err)
        assert len(err.strip().splitlines()) == 1 and err.startswith("report "), (what, err)
        assert not check_report(report).accepted


def test_each_forged_audit_is_refused(capsys, tmp_path, audit):
    forgeries = forged_audits(audit)
    assert len(forgeries) >= 4
    for what, report, expected in forgeries:
        status, out, err = check_file(capsys, tmp_path, report)
        assert status == 1 and expected in out + err, (what, expected, out[-800:], err)
        assert len(err.strip().splitlines()) == 1, (what, err)


def test_an_unbacked_verdict_is_not_success(capsys, tmp_path, audit):
    """The template's audit: two confirmed entries carry no certificate or judge object, so the
    report is listed in full but not accepted; the judged entry alone is."""
    status, out, err = check_file(capsys, tmp_path, audit)
    unbacked = [e for e in audit["equations"] if not e["evidence"].get("facts", {}).get("judge")
                and "certificate" not in json.dumps(e["evidence"])]
    if unbacked:
        assert status == 1 and "NOT BACKED" in out and err.startswith("report not accepted:")
    backed = dict(audit, equations=[e for e in audit["equations"] if e not in unbacked])
    status, out, err = check_file(capsys, tmp_path, backed)
    assert status == 0 and out.rstrip().endswith("report accepted"), out[-800:]
    undecided = dict(audit, equations=[dict(e, verdict="undecided", evidence={"method": "instances"}) for e in unbacked])
    assert check_file(capsys, tmp_path, undecided)[0] == 0          # a verdict that claims nothing needs nothing


def test_a_certificate_above_the_work_limit_is_bounded_and_not_success(capsys, tmp_path, walls, monkeypatch):
    """A 3.5 KB degree-599 sign certificate (random two-digit coefficients) cost 24 s: its Sturm
    sequence grows to 15 000-bit coefficients. Now it stops at the work limit: not re-verified,
    never success."""
    import random

    from hapticproof.exact import checkarith

    monkeypatch.setenv("HAPTICPROOF_CHECK_MAX_WORK", str(10**7))     # (a tenth of the default: the same stop, sooner)
    rng = random.Random(1)
    report = copy.deepcopy(walls[0])
    cond = next(c for c in report["conditions"] if c["name"] == "Re G^-1 >= 0 for all w")
    cond["decision"] = "proved"
    cond["evidence"]["facts"]["certificate"] = {
        "certificate": "sign", "variable": "c", "interval": ["-1", "1"], "holds": True, "points": ["-1", "1"],
        "roots": [], "polynomial": [str(rng.randint(1, 99)) for _ in range(600)]}
    work = []
    real_spend = checkarith.spend
    monkeypatch.setattr(checkarith, "spend", lambda units: (work.append(units), real_spend(units)))
    status, out, _ = check_file(capsys, tmp_path, report)
    assert status == 1 and "work limit" in out
    assert checkarith.max_work() <= sum(work) < checkarith.max_work() + max(work)   # stopped at the budget


@pytest.mark.parametrize("inputs", [-1, 100000000, 1e8, "2", True])
def test_a_crafted_boundary_report_never_reaches_the_native_library(capsys, tmp_path, inputs):
    """``"inputs": -1`` made FLINT abort the process (signal 6), ``1e8`` took 9 GB."""
    assert main(["boundary", "single-user", "--param", "m=0.015", "--param", "b=0.02", "--param", "T=0.001",
                 "--vary", "K", "--json", str(tmp_path / "b.json")]) == 0
    capsys.readouterr()
    report = json.loads((tmp_path / "b.json").read_text(encoding="utf-8"))
    assert check_file(capsys, tmp_path, report)[0] == 0
    report["judge"]["sides"][0]["loop"]["shape"]["inputs"] = inputs
    status, out, err = check_file(capsys, tmp_path, report)
    assert status == 1 and "size" in out and "Traceback" not in err


@pytest.mark.parametrize("text, expected", [
    ('{"conditions": [], "verdict": "proved", "verdict": "disproved"}', "given twice"),
    ('{"conditions": [{"name": "x", "decision": "proved", "evidence": {"n": ' + "9" * 1500 + "}}]}", "digits"),
    ('{"conditions": [{"name": "x", "decision": "proved"}], "witness": {"c": 1e999999}}', "digits"),
    ('{"conditions": [{"name": "x", "decision": "proved"}], "witness": {"c": 1e400}}', "range of a double"),
])
def test_json_numbers_and_keys_are_bounded(capsys, tmp_path, text, expected):
    path = tmp_path / "r.json"
    path.write_text(text, encoding="utf-8")
    assert main(["check", str(path)]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and expected in err and "Traceback" not in err


#: What a hand edit puts where a report has a value (about 90 such saved reports were tracebacks).
TYPE_EDITS = [None, 0, -1, 1.5, "x", "", [], {}, True, [[]], {"a": 1}, "-1/0", ["1", "x"]]


def _paths(node, path=()):
    yield path
    if isinstance(node, dict):
        for key, value in node.items():
            yield from _paths(value, (*path, key))
    elif isinstance(node, list):
        for k, value in enumerate(node):
            yield from _paths(value, (*path, k))


def test_type_edited_reports_are_refused_never_a_traceback(capsys, tmp_path, walls, audit):
    """Every value of a genuine report replaced by another type, one at a time (a sample of the
    places of each report): ``check`` refuses or accepts in one line, never a traceback."""
    from hapticproof.core.errors import HapticproofError
    from hapticproof.core.shapes import check_report as shape

    assert main(["boundary", "single-user", "--param", "m=0.015", "--param", "b=0.02", "--param", "T=0.001",
                 "--vary", "K", "--json", str(tmp_path / "b.json")]) == 0
    capsys.readouterr()
    boundary = json.loads((tmp_path / "b.json").read_text(encoding="utf-8"))
    edited = accepted = 0
    for report in (walls[0], boundary, dict(audit, equations=audit["equations"][:3])):
        places = [p for p in _paths(report) if p]
        for place in places[::max(1, len(places) // 12)]:
            for value in TYPE_EDITS:
                forged = copy.deepcopy(report)
                node = forged
                for key in place[:-1]:
                    node = node[key]
                node[place[-1]] = value
                edited += 1
                try:
                    shape(forged, "r.json")
                    accepted += check_report(forged).accepted
                except HapticproofError:
                    pass
    assert edited > 300 and accepted < edited
    # and through the command line, for a few: one line, no traceback
    for value in (None, "x", [], -1):
        forged = copy.deepcopy(walls[0])
        forged["conditions"][3]["evidence"]["facts"] = value
        status, _, err = check_file(capsys, tmp_path, forged)
        assert status in (1, 2) and "Traceback" not in err and len(err.strip().splitlines()) == 1, err
