"""Issue 30: a derive report's scene is bound to the G^-1 its certificates decide. A genuine proof
about one scene, relabelled as a proof about another (its approximation, delay, system, users or
values edited, or its scene removed), is refused by ``check``; every genuine report is accepted.

The checker rebuilds G^-1 from the definitions (:mod:`hapticproof.exact.scenebinding`); the
genuine reports below are a differential test of that rebuild against ``derive`` (single-user and
multi-user, every approximation, delays, an active operator, an environment of the user's own,
negative and zero values).
"""

from __future__ import annotations

import copy
import random
import sys
from pathlib import Path

import pytest

from hapticproof.exact.checker import check_report

sys.path.insert(0, str(Path(__file__).parent))
from clirun import json_of  # noqa: E402

WALL = ["--param", "K=30", "--param", "B=1/1000", "--param", "b=1/50", "--param", "T=1/1000"]
USERS = ["--param", "b=1/50", "--param", "K_0=10", "--param", "B_0=1/100", "--param", "K=5", "--param", "B=1/100",
         "--param", "T=1/1000"]

GENUINE = {
    "forward": ["single-user", *WALL],
    "backward-delay-2": ["single-user", "--approximation", "backward", "--delay", "2", *WALL],
    "tustin-active": ["single-user", "--approximation", "tustin", "--active", "--param", "z_a=1/200", *WALL],
    "own-environment": ["single-user", "--environment", "k*z/(z - 1/2)", "--param", "k=-3", "--param", "b=0",
                        "--param", "T=1/10"],
    "two-users": ["multi-user", "--uniform", *USERS],
    "three-users-unequal-delays": ["multi-user", "--users", "3", "--graph", "path", "--delay", "0,1,2",
                                   "--approximation", "backward", *USERS],
}


@pytest.fixture(scope="module")
def reports() -> dict:
    return {name: json_of("derive", *argv, "--format", "json") for name, argv in GENUINE.items()}


def _accepted(report) -> bool:
    return check_report(report).accepted


def _refusals(report) -> str:
    return " | ".join(r.reason for _, r in check_report(report).failed)


@pytest.mark.parametrize("name", sorted(GENUINE))
def test_genuine_reports_carry_their_scene_and_are_accepted(reports, name):
    report = reports[name]
    assert "scene" in report and "definition" in report
    assert _accepted(report), _refusals(report)


def _edits(report):
    """(what was edited, the forged report): each keeps every certificate and changes only what
    the report says G^-1 is of."""
    def edited(change):
        forged = copy.deepcopy(report)
        change(forged)
        return forged

    other = {"forward": "tustin", "backward": "forward", "tustin": "backward"}[report["approximation"]]
    yield "approximation", edited(lambda r: r.update(approximation=other))
    if "delay" in report:
        yield "delay", edited(lambda r: r.update(delay=str(int(r["delay"]) + 1)))
        yield "system", edited(lambda r: r.update(system="multi-user"))
    else:
        yield "delays", edited(lambda r: r.update(delays=[d + 1 for d in r["delays"]]))
        yield "users", edited(lambda r: r.update(users=r["users"] + 1))
    yield "period", edited(lambda r: r["scene"].update(period="1/999"))
    yield "damping", edited(lambda r: r["scene"]["damping"].__setitem__(0, "1/49"))
    yield "z_a", edited(lambda r: r["scene"]["shortage"].__setitem__(0, "1/7"))
    yield "environment", edited(lambda r: r["scene"]["environment"][0][0]["num"].append("1"))
    yield "scene removed", edited(lambda r: r.pop("scene"))


@pytest.mark.parametrize("name", sorted(GENUINE))
def test_a_report_relabelled_to_another_scene_is_refused(reports, name):
    for what, forged in _edits(reports[name]):
        assert not _accepted(forged), f"{name}: the {what} edit was accepted"


def test_the_refusal_names_what_differs(reports):
    forged = copy.deepcopy(reports["forward"])
    forged["approximation"] = "tustin"
    assert "not the one of the scene shown" in _refusals(forged)
    forged = copy.deepcopy(reports["forward"])
    del forged["scene"]
    assert "shows no scene values" in _refusals(forged)


def test_type_edited_scenes_are_refused_in_one_line(reports):
    """A scene block of the wrong shape or type is a refusal, never a traceback."""
    base = reports["two-users"]
    for change in (lambda s: s.update(period=None), lambda s: s.update(damping="1"), lambda s: s.update(environment=[[1]]),
                   lambda s: s.update(environment=[]), lambda s: s["environment"][0].pop(),
                   lambda s: s.update(period="-1/1000")):
        forged = copy.deepcopy(base)
        change(forged["scene"])
        assert not _accepted(forged)
    for delays in (["-1", "0"], [True, 0], [10**9, 0], ["1/2", "0"], "x"):
        forged = copy.deepcopy(base)
        forged["delays"] = delays
        assert not _accepted(forged)


def test_random_walls_rebuilt_by_the_checker(capsys):
    """Random numeric walls and environments (signs, zeros, every approximation and small delays):
    every genuine report is accepted, and the same report with another delay is refused."""
    rng = random.Random(30)
    for _ in range(6):
        k, c = rng.choice([-2, 0, 1, 7]), rng.choice([0, 1, -1])
        argv = ["single-user", "--environment", f"{k} + {c}*(z - 1)/(T*z)", "--param", f"b={rng.choice([0, 1, 3])}/10",
                "--param", f"T=1/{rng.choice([10, 1000])}", "--approximation", rng.choice(["forward", "backward", "tustin"]),
                "--delay", str(rng.choice([0, 1, 3]))]
        report = json_of("derive", *argv, "--format", "json")
        assert _accepted(report), (argv, _refusals(report))
        forged = copy.deepcopy(report)
        forged["delay"] = str(int(report["delay"]) + 2)
        assert not _accepted(forged), argv
