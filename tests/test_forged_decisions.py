"""Issue 30, fourth attack (a hostile author who had read the checker): each class of forgery it
found accepted is refused, and the genuine report it was made from is accepted.

A  a derive verdict with its definition object removed (or its G^-1 made unreadable);
B  an m-user report's matrix displays (G^-1, residue matrix, Hermitian part, minors, worst case);
C  a network report's summaries, matrix and poles;
D  a teleoperator's nested decisions against their own certificates, its summary decision and condition;
E  an audit verdict backed by a judge that judged nothing, or by a judge of another kind;
F  a residue decision against its certificate, a roots certificate's counts, an unreadable minimum;
G  a boundary with its judge object removed;
H  a boundary whose loops are too large to judge in bounded work.
"""

from __future__ import annotations

import copy
import sys
from pathlib import Path

import pytest

from hapticproof.exact.checker import check_report

sys.path.insert(0, str(Path(__file__).parent))
from clirun import json_of  # noqa: E402

PASSIVE_WALL = ["single-user", "--param", "K=2", "--param", "B=1/1000", "--param", "b=201/10000", "--param", "T=1/1000"]
USERS = ["--uniform", "--param", "K_0=1", "--param", "B_0=1/1000", "--param", "K=1", "--param", "B=1/1000",
         "--param", "T=1/1000"]


@pytest.fixture(scope="module")
def reports(tmp_path_factory) -> dict:
    folder = tmp_path_factory.mktemp("nets")
    (folder / "two.txt").write_text("9/(s+3), -1/(s+1)\n-1/(s+1), 1/(s+3)\n", encoding="utf-8")
    (folder / "unstable.txt").write_text("1/(s-1)\n", encoding="utf-8")
    return {
        "wall": json_of("derive", *PASSIVE_WALL, "--format", "json"),
        "leaky wall": json_of("derive", "single-user", "--param", "K=2", "--param", "B=1/1000", "--param",
                              "b=1/2000", "--param", "T=1/1000", "--format", "json"),
        "users": json_of("derive", "multi-user", *USERS, "--param", "b=1/50", "--format", "json"),
        "leaky users": json_of("derive", "multi-user", *USERS, "--param", "b=1/10000", "--format", "json"),
        "unequal delays": json_of("derive", "multi-user", "--users", "3", "--graph", "path", "--delay", "0,1,2",
                                  *USERS[1:], "--param", "b=1/50", "--format", "json"),
        "two-port": json_of("derive", "network", "--matrix", folder / "two.txt", "--format", "json"),
        "unstable port": json_of("derive", "network", "--matrix", folder / "unstable.txt", "--format", "json"),
        "teleoperator": json_of("derive", "teleoperator", "--param", "K=10", "--param", "B=1/500", "--param", "T=1/1000",
                                "--param", "b_m=1/20", "--param", "b_s=1/25", "--format", "json"),
        "boundary": json_of("boundary", *PASSIVE_WALL[:1], "--param", "m=3/200", "--param", "b=1/50", "--param",
                            "T=1/1000", "--param", "B=1/1000", "--vary", "K", "--json", "-", "--no-progress"),
    }


def _accepted(report) -> bool:
    return check_report(report).accepted


def _forged(report, change):
    forged = copy.deepcopy(report)
    change(forged)
    return forged


def test_the_genuine_reports_are_accepted(reports):
    for name, report in reports.items():
        assert _accepted(report), (name, check_report(report).summary())


def test_a_verdict_without_its_definition_is_refused(reports):
    leaky, wall = reports["leaky wall"], reports["wall"]
    # the non-passive wall shown proved with a passive wall's conditions, G^-1 and definition gone
    forged = _forged(leaky, lambda r: (r.pop("definition"), r.pop("G_inverse"),
                                       r.update(conditions=wall["conditions"], verdict="proved", witness=None)))
    assert not _accepted(forged)
    # a G^-1 made unreadable (padded past the reader's length), its definition removed
    forged = _forged(wall, lambda r: (r.pop("definition"), r.update(G_inverse=r["G_inverse"] + " " * 20_001)))
    assert not _accepted(forged)


def test_an_m_user_report_shows_its_own_matrices(reports):
    users, leaky = reports["users"], reports["leaky users"]
    for key in ("G_inverse", "hermitian_part", "principal_minors"):
        assert not _accepted(_forged(users, lambda r, k=key: r.update({k: leaky[k]}))), key
    assert not _accepted(_forged(users, lambda r: r["residue_at_1"][0].__setitem__(0, "7")))
    assert not _accepted(_forged(users, lambda r: r.update(worst_case_condition="False")))
    complex_part = reports["unequal delays"]
    assert complex_part["hermitian_is_real"] is False
    assert not _accepted(_forged(complex_part, lambda r: r["hermitian_part"][0].__setitem__(1, "-c/100 - 1/100")))


def test_a_network_summary_is_its_condition(reports):
    port, unstable = reports["two-port"], reports["unstable port"]
    assert not _accepted(_forged(port, lambda r: r["llewellyn"].update(decision="disproved")))
    assert not _accepted(_forged(port, lambda r: r["llewellyn"]["conditions"].update({"Re z11 >= 0 for every w": "disproved"})))
    assert not _accepted(_forged(port, lambda r: r["llewellyn"].update(eta_min="7")))
    assert not _accepted(_forged(port, lambda r: r["matrix"][0].__setitem__(0, "(s + 2)/(s + 1)")))
    assert not _accepted(_forged(port, lambda r: r.update(size=1)))
    assert not _accepted(_forged(unstable, lambda r: (r["positive_real"].update(decision="proved"),
                                                      r["absolute_stability"].update(decision="proved"))))
    assert not _accepted(_forged(unstable, lambda r: r["poles"].update(rhp=[])))


def test_a_teleoperator_decision_is_held_against_its_own_evidence(reports):
    tel = reports["teleoperator"]

    def flip_p5(r):
        for cond in r["conditions"]:
            if cond["name"].startswith("(P5)"):
                cert = cond["evidence"]["facts"]["certificate"]
                cert["holds"] = not cert["holds"]
    assert not _accepted(_forged(tel, flip_p5))
    assert not _accepted(_forged(tel, lambda r: r["decision"].update(decision="disproved")))
    assert not _accepted(_forged(tel, lambda r: r.update(condition="False")))


def test_nested_residues_roots_and_minimum(reports):
    wall = reports["wall"]

    def residue(r, decision=None, shown=None):
        for cond in r["conditions"]:
            for item in cond["evidence"].get("facts", {}).get("residues", []):
                if decision:
                    item["decision"] = decision
                if shown:
                    item["evidence"]["facts"]["scaled_residue"] = shown
    assert not _accepted(_forged(wall, lambda r: residue(r, decision="disproved")))
    assert not _accepted(_forged(wall, lambda r: residue(r, shown="-1/500")))

    def roots(r, **edit):
        for cond in r["conditions"]:
            cert = cond["evidence"].get("facts", {}).get("certificate", {})
            if cert.get("certificate") == "roots":
                cert.update(edit)
    assert not _accepted(_forged(wall, lambda r: roots(r, inside=-7)))
    assert not _accepted(_forged(wall, lambda r: roots(r, boundary=[{"multiplicity": 1, "root": "2"}])))
    assert not _accepted(_forged(wall, lambda r: r.update(minimum="oo")))


def test_an_audit_verdict_needs_a_judge_of_its_display():
    """A condition judge that found no counterexample judged nothing; a positive-real judge
    judges no printed display: neither backs a verdict on one."""
    from hapticproof.exact.acceptance import audit_binding
    from hapticproof.exact.judge import judge

    inverse = ["+", ["s", "b"], ["*", ["q", "1"], ["^", ["+", ["s", "z"], ["q", "-1"]], ["q", "-1"]]]]
    holds = {"judge": "condition", "display": [">", ["s", "b"], ["q", "0"]], "inverse": inverse, "variable": "z",
             "claim": "holds-not-passive", "values": {"b": "1"}}
    assert judge(holds).judged is False                # b = 1: passive, no point with Re G^-1 < 0
    entry = {"verdict": "wrong", "evidence": {"witness": {"b": "1"}, "facts": {"judge": {"judge": "positive-real"}}}}
    assert audit_binding(entry)
    entry = {"verdict": "confirmed", "evidence": {"facts": {"judge": {**holds, "claim": "holds-not-passive"}},
                                                  "witness": {"b": "1"}}}
    assert audit_binding(entry)


def test_a_boundary_without_its_judge_is_refused(reports):
    boundary = reports["boundary"]
    assert not _accepted(_forged(boundary, lambda r: (r["judge"].pop("judge"), r.update(value=1000.0))))
    assert not _accepted(_forged(boundary, lambda r: (r.pop("judge"), r.update(value=1000.0, conditions=[]))))
    assert not _accepted({})


def test_a_boundary_too_large_to_judge_is_not_accepted(reports):
    """Loops of 64 states, inputs and outputs: refused within the work limit (not minutes)."""
    def huge(r):
        for side in r["judge"]["sides"]:
            n = 64
            side["loop"] = {"T": "1/1000", "a": [["1"] * n] * n, "bu": [["1"] * n] * n, "c": [["1"] * n] * n,
                            "controller": {"a": [["1"] * n] * n, "b": [["1"] * n] * n, "c": [["1"] * n] * n,
                                           "d": [["1"] * n] * n},
                            "shape": {"plant": [n, n], "inputs": n, "outputs": n, "controller": n}, "rigid": False}
    assert not _accepted(_forged(reports["boundary"], huge))
