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

And the fifth attack's classes (a delay read under another key, displays the reader cannot read,
worst cases and minima, m-user graphs, crossings after the first, Youla's symmetrization and a
destabilising termination): ``test_fifth_attack_*``.
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
    (folder / "three.txt").write_text("1/(s+1), 0, 0\n0, 2/(s+2), 1/(s+5)\n0, 1/(s+5), 1 - 2/(s+1) + 10/(s+10000)\n",
                                      encoding="utf-8")
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
        "three-port": json_of("derive", "network", "--matrix", folder / "three.txt", "--format", "json"),
        "path users": json_of("derive", "multi-user", "--users", "3", "--graph", "path", *USERS[1:], "--param",
                              "b=1/10000", "--format", "json"),
        "symbolic wall": json_of("derive", "single-user", "--format", "json"),
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
        if name == "symbolic wall":         # symbolic conditions: never accepted as re-verified (re-derive them)
            assert not _accepted(report) and not check_report(report).failed
            continue
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
    assert not _accepted(_forged(tel, lambda r: r.update(error_coordinate_damping="1")))
    assert not _accepted(_forged(tel, lambda r: r.update(sup_master="1/1000")))      # below the true 7/500
    assert not _accepted(_forged(tel, lambda r: r.update(sup_slave="1")))            # above it
    assert not _accepted(_forged(tel, lambda r: r.update(maximiser="1/2")))


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
            side["loop"] = {"period": "1/1000", "state": [["1"] * n] * n, "input": [["1"] * n] * n,
                            "output": [["1"] * n] * n,
                            "controller": {"state": [["1"] * n] * n, "input": [["1"] * n] * n,
                                           "output": [["1"] * n] * n, "feedthrough": [["1"] * n] * n},
                            "shape": {"plant": [n, n], "inputs": n, "outputs": n, "controller": n}, "rigid": False}
    assert not _accepted(_forged(reports["boundary"], huge))


def test_fifth_attack_delays_and_displays(reports):
    wall, leaky = reports["wall"], reports["leaky wall"]
    # the delay shown is the delay: no alias under another key
    assert not _accepted(_forged(wall, lambda r: r.update(delay="30", delays="0")))
    for shown in (5, ["c"], "Re G^-1 = c/1000 - 1/100", "c/1000 \u2212 1/100", "c/1000 + sqrt(2)/100"):
        assert not _accepted(_forged(wall, lambda r, v=shown: r.update(hermitian_part=v))), shown
    assert not _accepted(_forged(leaky, lambda r: r.update(worst_case="true")))
    assert not _accepted(_forged(wall, lambda r: r.update(worst_case="b >= B + K*T/8")))
    assert not _accepted(_forged(leaky, lambda r: r.update(minimum="[5 +/- 1]")))
    assert not _accepted(_forged(wall, lambda r: (r.pop("minimum"), r.update(minimiser="0"))))
    # a symbolic report made to claim nothing still shows its (wrong) worst case: not success
    symbolic = reports["symbolic wall"]

    def undecided(r):
        for cond in r["conditions"]:
            cond["decision"] = "undecided"
        r.update(verdict="undecided", worst_case="b >= B + K*T/8")
    assert not _accepted(_forged(symbolic, undecided))


def test_fifth_attack_m_users(reports):
    path, leaky = reports["path users"], reports["leaky users"]
    assert _accepted(path), check_report(path).summary()
    assert not _accepted(_forged(path, lambda r: r.update(edges=[])))
    assert not _accepted(_forged(leaky, lambda r: r.update(graph="path", edges=[[1, 2]])))  # two users: complete
    assert not _accepted(_forged(leaky, lambda r: r.update(worst_c="1/2")))

    def minimiser(r):
        for cond in r["conditions"]:
            if "minimiser" in cond:
                cond["minimiser"] = "1/3"
    assert not _accepted(_forged(leaky, minimiser))
    assert not _accepted(_forged(reports["unequal delays"], lambda r: r.update(hermitian_is_real=True)))


def test_fifth_attack_boundary_crossings(reports):
    boundary = reports["boundary"]
    second = {**boundary["crossings"][0], "value": 100.0, "direction": "restabilising"}
    assert not _accepted(_forged(boundary, lambda r: r["crossings"].append(second)))
    assert not _accepted(_forged(boundary, lambda r: r["crossings"][0].update(tolerance=5.0)))
    assert not _accepted(_forged(boundary, lambda r: r["crossings"][0].update(certified=False)))


def test_fifth_attack_youla_and_terminations(reports):
    three = reports["three-port"]
    assert three["absolute_stability"]["decision"] == "disproved" and "certificate" in three["absolute_stability"]
    assert not _accepted(_forged(three, lambda r: r["zprime_positive_real"].update(decision="proved")))
    assert not _accepted(_forged(three, lambda r: r["symmetrization"].update(decision="disproved")))
    assert not _accepted(_forged(three, lambda r: r["symmetrization"].update(Z_prime=[["1"] * 3] * 3)))
    assert not _accepted(_forged(three, lambda r: r["absolute_stability"].update(method="positive real")))
    assert not _accepted(_forged(three, lambda r: r["absolute_stability"]["certificate"].update(rhp_roots=["5+0j"])))
    # a passive termination of a positive-real port destabilises nothing
    three_pr = _forged(three, lambda r: r["absolute_stability"]["certificate"].update(
        terminations=[[["0"]], [["0"]], [["0"]]]))
    assert not _accepted(three_pr)


def test_type_edited_reports_are_refused_without_a_traceback(reports):
    """A condition that is text, conditions that are a number, a definition's witness that is
    text: refused (not accepted), never an exception out of the checker."""
    for name in ("wall", "users", "two-port"):
        report = reports[name]
        for change in (lambda r: r["conditions"].__setitem__(0, "x"), lambda r: r.update(conditions=7),
                       lambda r: r["conditions"][0].update(definition={"judge": "positive-real", "witness": "x"})):
            assert not _accepted(_forged(report, change)), name
