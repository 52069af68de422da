"""Whole verdicts (issue 10): every derive verdict is the full decision -- poles, residues,
Hermitian part, controller poles -- with each condition listed, and every saved report can be
re-verified by ``hapticproof check``.

Each case the issue names is a regression test here, through the command line as a user runs it.
"""

from __future__ import annotations

import json

import pytest
import sympy as sp

from hapticproof.exact.checker import check_report
from hapticproof.cli import main
from hapticproof.core.evidence import to_jsonable
from hapticproof.systems.multiuser import MultiUserScene
from hapticproof.analysis.multiuser import conditions as multi_conditions
from hapticproof.analysis.multiuser import positive_real as multi_positive_real
from hapticproof.analysis.positivereal import positive_real
from hapticproof.systems.singleuser import SingleUserScene
from hapticproof.systems.teleoperator import TeleoperatorScene
from hapticproof.analysis.teleoperator import criterion, passivity


def derive_json(capsys, *args):
    code = main(["derive", *args, "--format", "json"])
    out = capsys.readouterr().out
    assert code == 0
    return json.loads(out)


NUMBERS = ["--param", "K=2", "--param", "B=1/10", "--param", "b=1", "--param", "T=1/1000"]


@pytest.mark.parametrize("environment,failing", [
    ("K + B*(z-1)/(T*(z-2))", "poles in |z| <= 1"),          # a pole outside the unit circle
    ("1/(z-1)**2", "unit-circle poles simple"),               # a double pole on the circle
])
def test_derive_single_user_verdict_follows_poles(capsys, environment, failing):
    numbers = NUMBERS if "K" in environment else ["--param", "b=1", "--param", "T=1/1000"]
    for params in ([], numbers):
        data = derive_json(capsys, "single-user", "--environment", environment, *params)
        assert data["verdict"] == "disproved"
        failed = [c["name"] for c in data["conditions"] if c["decision"] == "disproved"]
        assert failing in failed
        assert failing in data["reason"]
        assert check_report(data).ok


def test_derive_single_user_negative_residue(capsys):
    # K = -2: the residue K T at z = 1 is negative although Re G^-1 >= 0 everywhere
    data = derive_json(capsys, "single-user", "--param", "K=-2", "--param", "B=0", "--param", "b=1", "--param", "T=1/10")
    decisions = {c["name"]: c["decision"] for c in data["conditions"]}
    assert decisions["Res/z0 >= 0 at unit-circle poles"] == "disproved"
    assert decisions["Re G^-1 >= 0 for all w"] == "proved"
    assert data["verdict"] == "disproved" and check_report(data).ok


def test_single_user_api_and_cli_agree_on_a_proved_scene(capsys):
    data = derive_json(capsys, "single-user", *NUMBERS)
    assert data["verdict"] == "proved"
    assert [c["decision"] for c in data["conditions"]] == ["proved"] * 4
    scene = SingleUserScene.virtual_wall(K=2, B=sp.Rational(1, 10), b=1, T=sp.Rational(1, 1000))
    assert positive_real(scene).decision.value == "proved"
    result = check_report(data)
    # four conditions and the verdict (judged against the definition from G^-1 itself)
    assert result.ok and "5 fully re-verified" in result.summary()


def test_derive_teleoperator_reports_an_unstable_controller(capsys):
    data = derive_json(capsys, "teleoperator", "--controller", "K/(z-3)", "--param", "K=1", "--param", "T=0.001",
                       "--param", "b_m=0.02", "--param", "b_s=0.02")
    assert data["verdict"] == "disproved"
    poles = next(c for c in data["conditions"] if c["name"].startswith("(P1)"))
    assert poles["decision"] == "disproved" and "outside" in poles["reason"]
    assert check_report(data).ok


def test_teleoperator_decides_without_masses():
    # the masses do not enter the bound of (32): a decision needs only b_m, b_s, T and C
    scene = TeleoperatorScene.pd(K=2, B=sp.Rational(1, 100), T=sp.Rational(1, 1000), b_m=sp.Rational(1, 10),
                                 b_s=sp.Rational(1, 10))
    assert scene.parameters                       # m_m, m_s symbolic
    assert passivity(scene).decision.value == "proved"
    below = TeleoperatorScene.pd(K=2, B=sp.Rational(1, 100), T=sp.Rational(1, 1000), b_m=sp.Rational(2, 100),
                                 b_s=sp.Rational(1, 10))
    # b_m < KT + 2B = 0.022 fails the paper's (32), yet h = b_m b_s/(b_m + b_s) = 1/60 > KT/2 + B
    assert passivity(below).decision.value == "proved"
    assert criterion(below).decision.value == "disproved" and "master" in criterion(below).reason
    leaky = TeleoperatorScene.pd(K=2, B=sp.Rational(1, 100), T=sp.Rational(1, 1000), b_m=sp.Rational(1, 100),
                                 b_s=sp.Rational(1, 100))
    out = passivity(leaky)                        # h = 1/200 < KT/2 + B = 0.011
    assert out.decision.value == "disproved" and "(P5)" in out.reason


def test_multi_user_verdict_lists_conditions_and_checks():
    scene = MultiUserScene.from_values(b=["0.002", "0.02", "0.015"], T="0.001", K0=[10, 5, 3], B0=[0, 0, "0.001"],
                                       K={(0, 1): 4, (1, 2): 6}, edges=[(0, 1), (1, 2)], delays=[0, 2, 1])
    out = multi_positive_real(scene)
    assert out.decision.value == "disproved"
    report = to_jsonable({"conditions": [c.to_json() for c in multi_conditions(scene)]})
    result = check_report(report)
    assert result.ok and "4 fully re-verified" in result.summary()
    # the witness is a rational point of the unit circle, not a pole of G^-1 (z = 1)
    assert out.witness["z"] != ["1", "0"]


def test_check_command(capsys, tmp_path):
    data = derive_json(capsys, "single-user", "--delay", "3", "--approximation", "tustin", "--param", "K=2",
                       "--param", "T=0.001", "--param", "b=0.0019", "--param", "B=0.0001")
    path = tmp_path / "report.json"
    path.write_text(json.dumps(data))
    assert main(["check", str(path)]) == 0
    assert "0 certificate(s) failed" in capsys.readouterr().out
    # a tampered witness is caught: exit code 1
    herm = data["conditions"][3]["evidence"]["facts"]["certificate"]
    herm["witness"] = "-1/2" if herm["witness"] != "-1/2" else "0"
    herm["witness_point"] = ["1", "0"]
    path.write_text(json.dumps(data))
    assert main(["check", str(path)]) == 1
    assert "FAILED" in capsys.readouterr().out
    (tmp_path / "bad.json").write_text("{")
    assert main(["check", str(tmp_path / "bad.json")]) == 2


def test_check_reads_an_audit_report(capsys, tmp_path):
    assert main(["audit", "hve", "--equation", "25", "--format", "json"]) == 0
    path = tmp_path / "audit.json"
    path.write_text(capsys.readouterr().out)
    assert main(["check", str(path)]) == 0
    out = capsys.readouterr().out
    assert "hve (25)" in out


def test_the_audit_runs_the_checker_on_every_certificate():
    """A finding's certificates are re-verified by the independent checker; a certificate the
    checker rejects makes the verdict undecided (issue 10: 'the audit runs it')."""
    import flint

    from hapticproof.audit.runner import rechecked
    from hapticproof.core.evidence import Evidence, Finding, Method, Verdict
    from hapticproof.exact.kernel import decide_sign

    out = decide_sign(flint.fmpq_poly([1, -2, 1]), -1, 1)          # (c - 1)^2 >= 0: proved
    good = Finding(Verdict.CONFIRMED, "a square", Evidence(Method.ROOT_ISOLATION, facts={"certificate": out.evidence.facts["certificate"]}))
    checked = rechecked(good)
    assert checked.verdict == Verdict.CONFIRMED
    assert checked.evidence.facts["checker"] == {"certificates": 1, "re-verified": 1}
    forged = to_jsonable(out.evidence.facts["certificate"].to_json())
    forged["polynomial"] = ["-1", "0", "1"]                          # c^2 - 1 < 0 inside: 'holds' is false
    bad = rechecked(Finding(Verdict.CONFIRMED, "a forged square", Evidence(Method.ROOT_ISOLATION, facts={"certificate": forged})))
    assert bad.verdict == Verdict.UNDECIDED
    assert "rejected" in bad.evidence.facts["checker"] and "checker rejected" in bad.detail
    plain = Finding(Verdict.CONFIRMED, "no certificate", Evidence(Method.CANONICAL_FORM))
    assert rechecked(plain) is plain


def test_network_absolute_stability_carries_the_certificates_it_rests_on(capsys, tmp_path):
    """``derive network``: the absolute-stability entry carries the decision that settles it
    (here Z positive real), so ``hapticproof check`` re-verifies every entry."""
    matrix = tmp_path / "z.txt"
    matrix.write_text("9/(s+3), 1/(s+1)\n1/(s+1), 2/(s+2)\n")
    report = tmp_path / "net.json"
    assert main(["derive", "network", "--matrix", str(matrix), "--format", "json", "-o", str(report)]) == 0
    data = json.loads(report.read_text())
    entry = next(c for c in data["conditions"] if c["name"] == "absolute stability")
    assert entry["decision"] == "proved" and entry["rests_on"]["decision"] == "proved"
    capsys.readouterr()
    assert main(["check", str(report)]) == 0
    out = capsys.readouterr().out
    assert "0 without a certificate" in out and "0 certificate(s) failed" in out
