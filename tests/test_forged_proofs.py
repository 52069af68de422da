"""Issue 30, second attack: a ``proved`` derive report needs every condition of Definition 2,
re-derived from its own ``G^-1`` (proper, no pole outside, simple unit-circle poles with PSD
residues) and a sign certificate of ``Re G^-1`` over the whole circle bound to it. A report
whose conditions were emptied, cut or relabelled is refused even where the definition judge's
sample points miss a narrow negative band of ``Re G^-1``.
"""

from __future__ import annotations

import copy
import json
import sys
from pathlib import Path

import pytest

from hapticproof.exact.checker import check_report

sys.path.insert(0, str(Path(__file__).parent))
from clirun import check_file, json_of  # noqa: E402

SIGN = "Re G^-1 >= 0 for all w"

#: Re G^-1 = 2c^2 - 6c/5 + 17999999/100000000: negative only for c in a band of width ~1e-4 around
#: 3/10, which the definition judge's own sample points miss.
BAND = ["derive", "single-user", "--environment", "K + B*(z-1)/(T*z) + M*(z-1)**2/(T**2*z**2)", "--param", "T=1",
        "--param", "M=-1", "--param", "B=-0.2", "--param", "K=2", "--param", "b=2.17999999", "--format", "json"]
#: A negative stiffness: Re G^-1 >= 0 everywhere, the residue K T at z = 1 is negative.
NEGATIVE_RESIDUE = ["derive", "single-user", "--param", "K=-2", "--param", "B=0", "--param", "b=1", "--param", "T=1/10",
                    "--format", "json"]
#: A wall with a second-order pole at z = 1 (not simple).
DOUBLE_POLE = ["derive", "single-user", "--environment", "1/(z-1)**2", "--param", "b=1", "--param", "T=1/1000",
               "--format", "json"]
PASSIVE = ["derive", "single-user", "--param", "K=2", "--param", "T=0.001", "--param", "b=0.02", "--param", "B=0.001",
           "--format", "json"]
MULTI = ["derive", "multi-user", "--users", "2", "--param", "b=1", "--param", "K_0=2", "--param", "B_0=0", "--param", "K=3",
         "--param", "B=0", "--param", "T=1/1000", "--format", "json"]
MULTI_BAD = ["derive", "multi-user", "--users", "3", "--param", "b=1/1000", "--param", "K_0=2", "--param", "B_0=0",
             "--param", "K=3", "--param", "B=0", "--param", "T=1/1000", "--format", "json"]


@pytest.fixture(scope="module")
def reports():
    return {name: json_of(*argv) for name, argv in (("band", BAND), ("residue", NEGATIVE_RESIDUE),
                                                   ("double", DOUBLE_POLE), ("passive", PASSIVE),
                                                   ("multi", MULTI), ("multi_bad", MULTI_BAD))}


def _refused(capsys, tmp_path, report, expected: str) -> None:
    status, out, err = check_file(capsys, tmp_path, report)
    assert status == 1, out[-800:]
    assert "report accepted" not in out and expected in out + err, (expected, out[-800:], err)
    assert len(err.strip().splitlines()) == 1 and err.startswith("report "), err
    assert not check_report(report).accepted


def _proved(report: dict) -> dict:
    """Every decision, the verdict and the definition object say ``proved``; no witness."""
    report = copy.deepcopy(report)
    for cond in report["conditions"]:
        cond["decision"] = "proved"
        cond.get("evidence", {}).pop("witness", None)
    report["verdict"], report["witness"] = "proved", None
    report["definition"]["decision"] = "proved"
    report["definition"].pop("witness", None)
    report["definition"].pop("judged", None)
    return report


def test_genuine_reports_of_each_kind_are_accepted(capsys, tmp_path, reports):
    for name in ("band", "residue", "double", "passive", "multi", "multi_bad"):
        status, out, err = check_file(capsys, tmp_path, reports[name])
        assert status == 0 and out.rstrip().endswith("report accepted"), (name, out[-800:], err)
    assert reports["band"]["verdict"] == "disproved" and reports["multi"]["verdict"] == "proved"


def test_the_band_judge_alone_misses_it(reports):
    """The forgery's premise: the definition judge alone passes a ``proved`` for the band wall."""
    from hapticproof.exact.judge import judge

    definition = dict(reports["band"]["definition"], decision="proved")
    definition.pop("witness")
    assert judge(definition).ok


def test_a_proof_with_its_conditions_removed_is_refused(capsys, tmp_path, reports):
    forged = _proved(reports["band"])
    forged["conditions"] = []
    _refused(capsys, tmp_path, forged, "no condition to back it")
    forged.pop("minimum"), forged.pop("minimiser")
    _refused(capsys, tmp_path, forged, "no condition to back it")


@pytest.mark.parametrize("keep", [
    ("poles in |z| <= 1", "unit-circle poles simple", "Res/z0 >= 0 at unit-circle poles"),   # no sign condition
    ("poles in |z| <= 1",),
])
def test_a_proof_without_its_sign_certificate_is_refused(capsys, tmp_path, reports, keep):
    forged = _proved(reports["band"])
    forged["conditions"] = [c for c in forged["conditions"] if c["name"] in keep]
    forged["minimum"], forged["minimiser"] = "0", "1"
    _refused(capsys, tmp_path, forged, "no sign certificate of Re G^-1 over the whole circle backs the proof")


def test_a_sign_condition_proved_without_a_certificate_is_refused(capsys, tmp_path, reports):
    forged = _proved(reports["band"])
    sign = next(c for c in forged["conditions"] if c["name"] == SIGN)
    sign["evidence"] = {"method": "canonical-form", "facts": {}}
    for where in (forged, sign):
        where["minimum"], where["minimiser"] = "1/1000", "1"
    _refused(capsys, tmp_path, forged, "no sign certificate")


def test_a_negative_minimum_with_a_proof_is_refused(capsys, tmp_path, reports):
    forged = copy.deepcopy(reports["passive"])
    assert forged["verdict"] == "proved"
    forged["minimum"] = "-1/100"
    _refused(capsys, tmp_path, forged, "is negative")


def test_a_negative_residue_relabelled_proved_is_refused(capsys, tmp_path, reports):
    genuine = reports["residue"]
    assert genuine["verdict"] == "disproved"
    forged = _proved(genuine)
    forged["conditions"] = [c for c in forged["conditions"] if not c["name"].startswith("Res")]
    _refused(capsys, tmp_path, forged, "the residue at z0 = 1 is not PSD")


def test_a_double_pole_relabelled_proved_is_refused(capsys, tmp_path, reports):
    forged = _proved(reports["double"])
    for cond in forged["conditions"]:
        for key in ("certificate",):
            cond.get("evidence", {}).get("facts", {}).pop(key, None)
    _refused(capsys, tmp_path, forged, "multiple pole on the unit circle")


def test_a_matrix_proof_without_its_psd_certificate_is_refused(capsys, tmp_path, reports):
    forged = _proved(reports["multi_bad"])
    forged["conditions"] = forged["conditions"][:3]
    _refused(capsys, tmp_path, forged, "no psd certificate of G^-1 + G^-H")


# ---------------------------------------------------------------------------------------------
# audit entries: the judge chooses its own points
# ---------------------------------------------------------------------------------------------

ROOT = __import__("pathlib").Path(__file__).resolve().parents[1]


@pytest.fixture(scope="module")
def walls(tmp_path_factory):
    """The tutorial's walls paper with display 3 printed right (``b >= KT/2 + B``, confirmed)."""
    text = (ROOT / "examples" / "walls.toml").read_text(encoding="utf-8")
    assert "printed = 'b > KT + B'" in text
    path = tmp_path_factory.mktemp("walls") / "walls.toml"
    path.write_text(text.replace("printed = 'b > KT + B'", "printed = 'b \\geq \\frac{KT}{2} + B'"), encoding="utf-8")
    report = json_of("audit", "--paper", str(path), "--format", "json")
    return {e["id"]: e for e in report["equations"]}, {k: v for k, v in report.items() if k != "equations"}


def _one(walls, entry) -> dict:
    return dict(walls[1], equations=[entry])


def _judge(entry) -> dict:
    return entry["evidence"]["facts"]["judge"]


def test_genuine_judged_entries_are_accepted(capsys, tmp_path, walls):
    entries, _ = walls
    assert entries["2"]["verdict"] == "confirmed" and _judge(entries["2"])["judge"] == "circle-identity"
    assert entries["3"]["verdict"] == "confirmed" and _judge(entries["3"])["claim"] == "holds-passive"
    for key in ("2", "3", "4"):
        status, out, err = check_file(capsys, tmp_path, _one(walls, entries[key]))
        assert status == 0 and out.rstrip().endswith("report accepted"), (key, out[-800:], err)
    assert "points of the checker's choosing" in json.dumps(entries["2"]["evidence"]["facts"]["checker"])


#: Re G^-1 of the wall is b - KT/2 + B cos(omega T); the forgery prints 2b + KT + B cos(omega T).
FALSE_IDENTITY = ["+", ["*", ["q", "2"], ["s", "b"]], ["*", ["s", "B"], ["cos", ["*", ["s", "omega"], ["s", "T"]]]],
                  ["*", ["s", "K"], ["s", "T"]]]


def test_an_identity_judged_at_no_point_or_the_authors_points_is_refused(capsys, tmp_path, walls):
    entries, _ = walls
    forged = copy.deepcopy(entries["2"])
    printed = "\\Re\\{G^{-1}(e^{j\\omega T})\\} = 2b + KT + B\\cos(\\omega T)"
    forged["printed"] = _judge(forged)["printed"] = printed
    _judge(forged)["display"] = FALSE_IDENTITY
    _judge(forged)["points"] = []
    _refused(capsys, tmp_path, _one(walls, forged), "no point is no evidence")
    # one point the author chose where the false display happens to equal Re G^-1 (b = K = 0, B = 1)
    _judge(forged)["points"] = [{"values": {"B": "1", "K": "0", "T": "1", "b": "0"}, "t": "1/2", "L": 1,
                                 "transfer": {"variable": "z", "num": ["-1", "1", "0"], "den": ["0", "-1", "1"]}}]
    _refused(capsys, tmp_path, _one(walls, forged), "at a point the checker chose")
    # without the scene's G^-1 the checker cannot choose points: never success
    del _judge(forged)["inverse"]
    status, out, err = check_file(capsys, tmp_path, _one(walls, forged))
    assert status == 1 and "cannot test it at points of its own choosing" in out + err, out[-600:]


def test_a_condition_relabelled_with_its_display_tree_is_refused(capsys, tmp_path, walls):
    """``b > KT/8 + B`` printed, judged and displayed consistently, at sample points the author
    chose far from the boundary: the checker's own points at the printed boundary refute it."""
    entries, _ = walls
    forged = copy.deepcopy(entries["3"])
    forged["printed"] = _judge(forged)["printed"] = "b > \\frac{KT}{8} + B"
    _judge(forged)["display"] = [">", ["s", "b"], ["+", ["s", "B"], ["*", ["q", "1/8"], ["s", "K"], ["s", "T"]]]]
    _refused(capsys, tmp_path, _one(walls, forged), "it is not sufficient")
    _judge(forged)["samples"] = [{"B": "1", "K": "1", "T": "1", "b": "10"}, {"B": "0", "K": "1", "T": "1", "b": "5"}]
    _judge(forged)["values"] = _judge(forged)["samples"][0]
    _refused(capsys, tmp_path, _one(walls, forged), "it is not sufficient")
    _judge(forged)["samples"] = []
    _refused(capsys, tmp_path, _one(walls, forged), "no sample point")


@pytest.mark.parametrize("edit,expected", [
    (lambda r: r["poles"][-1].update(location="outside"), "is on the unit circle, not outside"),
    (lambda r: r["poles"][-1].update(multiplicity=2), "has multiplicity 1, not 2"),
    (lambda r: r["poles"].pop(), "of G^-1 is not shown"),
    (lambda r: r["residues"][0].update(residue="-1"), "the residue shown at z0 = 1 is -1"),
    (lambda r: r.update(minimiser="7"), "is not a point of the circle"),
])
def test_displayed_poles_residues_and_minimiser_are_bound(capsys, tmp_path, reports, edit, expected):
    forged = copy.deepcopy(reports["passive"])
    edit(forged)
    _refused(capsys, tmp_path, forged, expected)
