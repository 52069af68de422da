"""Sampled-data teleoperator passivity (hapticproof.analysis.teleoperator) and the audit of the
teleoperator paper (derivations/teleoperator/)."""

from __future__ import annotations

import cmath
import math
from dataclasses import replace

import pytest
import sympy as sp
from hypothesis import given, settings
from hypothesis import strategies as st

from hapticproof.analysis import classics
from hapticproof.analysis import teleoperator as tele
from hapticproof.systems import teleoperator as telemodel
from hapticproof.audit.runner import audit_paper, run_equation
from hapticproof.core.errors import InputFormatError, SceneError
from hapticproof.audit.registry import get_paper
from hapticproof.systems.impedance import CLAMPED, Impedance
from hapticproof.analysis.sampled import spectral_radius
from hapticproof.core.symbols import c, z

S = telemodel.TELE_SYMBOLS
K, B, T, b_m, b_s, alpha = (S[k] for k in ("K", "B", "T", "b_m", "b_s", "alpha"))
R = sp.Rational


def test_pd_bounds_are_34_and_35():
    scene = telemodel.TeleoperatorScene.pd()
    assert sp.expand(tele.bounds(scene).master - (K * T - 2 * B * c)) == 0
    wc = tele.worst_case(scene)
    assert wc.sup_master == K * T + 2 * B and wc.maximiser == -1


def test_scaled_bounds_and_reduction():
    scene = telemodel.TeleoperatorScene.pd(alpha=None)
    bd = tele.bounds(scene)
    leak = K * T / 2 - B * c
    assert sp.expand(bd.master - (alpha + 1) * alpha * leak) == 0
    assert sp.expand(bd.slave - (alpha + 1) * leak) == 0
    assert sp.expand(bd.master.subs(alpha, 1) - 2 * classics.colgate_bound(scene.C, T)) == 0


@settings(max_examples=20, deadline=None)
@given(theta=st.floats(0.05, 3.09), a=st.floats(0.0, 0.9), al=st.floats(0.2, 3.0))
def test_bounds_against_direct_complex_evaluation(theta, a, al):
    Kv, Bv, Tv = 2.0, 0.01, 0.002
    # exact rationals: plain nsimplify may return radicals (e.g. for a = 0.686844161539459),
    # which the exact c-forms rightly refuse as non-rational coefficients
    C = telemodel.filtered_pd_controller(R(2), R(1, 100), R(2, 1000), sp.nsimplify(a, rational=True))
    scene = telemodel.TeleoperatorScene(1, 1, 1, 1, R(2, 1000), C, sp.nsimplify(al, rational=True))
    got = float(tele.bounds(scene).master.subs(c, math.cos(theta)))
    zz = cmath.exp(1j * theta)
    Cz = Kv + Bv * (1 - a) * (zz - 1) / (Tv * (zz - a))
    al_exact = float(sp.nsimplify(al, rational=True))
    direct = Tv / 2 * (al_exact + 1) / (1 - math.cos(theta)) * ((1 - 1 / zz) * al_exact * Cz).real
    assert abs(got - direct) < 1e-8 * (1 + abs(direct))


def test_numeric_worst_case_and_decisions():
    C = telemodel.filtered_pd_controller(2, R(1, 100), R(1, 1000), R(1, 2))
    scene = telemodel.TeleoperatorScene(R(15, 1000), R(15, 1000), R(2, 100), R(2, 100), R(1, 1000), C)
    wc = tele.worst_case(scene)
    grid = [tele.bounds(scene).master.subs(c, R(k, 50)) for k in range(-50, 51)]
    assert all(v <= wc.sup_master for v in grid)
    assert tele.passivity(scene).decision.value == "proved"
    low = replace(scene, b_m=R(1, 1000))
    out = tele.passivity(low)
    assert out.decision.value == "disproved"
    cw = out.witness["c"]
    assert R(1, 1000) < tele.bounds(low).master.subs(c, cw)


def test_passive_scene_is_stable_with_passive_terminations():
    """Passivity (32) implies stability with any passive terminations (independent loop check)."""
    m, bb, Tv = R(15, 1000), R(1822, 100000), R(7, 1000)
    scene = telemodel.TeleoperatorScene.symmetric(m, bb, Tv, telemodel.pd_controller(1, R(1, 1000), Tv))
    assert tele.passivity(scene).decision.value == "proved"
    for master, slave in ((None, None), (None, CLAMPED), (Impedance.spring_damper(R(1, 20), 5), Impedance.spring_damper(0, 40))):
        assert spectral_radius(scene.to_sampled(master, slave), "mp", 30) < 1


def test_discretisations_and_controller_parsing():
    assert sp.simplify(telemodel.discretize_pd("backward") - telemodel.pd_controller()) == 0
    assert sp.simplify(telemodel.discretize_pd("bilinear") - telemodel.pd_controller()) != 0
    assert sp.simplify(telemodel.parse_controller("K + B*(z - 1)/(T*z)") - telemodel.pd_controller()) == 0
    for bad in ("foo(z)", "import os", "K + ", "sin(z)"):
        with pytest.raises(InputFormatError):
            telemodel.parse_controller(bad)
    with pytest.raises(SceneError):
        telemodel.TeleoperatorScene(1, 1, 1, 1, 1, z**2)                  # improper
    with pytest.raises(SceneError):
        telemodel.TeleoperatorScene(1, 1, 1, 1, -1, 1)                    # T <= 0
    with pytest.raises(SceneError):
        telemodel.discretize_pd("zoh")


def test_error_coordinate_damping_is_less_conservative():
    h = tele.error_coordinate_damping(telemodel.TeleoperatorScene.pd(alpha=None))
    # (32) implies h >= L: with b_m = alpha(alpha+1)L, b_s = (alpha+1)L the series damping is exactly L
    L = sp.Symbol("L", positive=True)
    assert sp.simplify(h.subs({b_m: alpha * (alpha + 1) * L, b_s: (alpha + 1) * L}) - L) == 0


# ---------------------------------------------------------------------------------------------
# the audit
# ---------------------------------------------------------------------------------------------

EXPECTED = {
    "5": "typo", "7": "typo", "13": "typo", "18": "typo", "28-less": "typo", "29": "needs-assumption",
    "32": "needs-assumption", "33": "confirmed", "33-bilinear": "wrong", "34": "confirmed", "35": "conservative",
    "35-colgate": "inconsistent",
    "intro-routh": "needs-assumption", "lemma1": "needs-assumption", "16": "confirmed", "38": "typo",
    "table1-stable": "confirmed",
}


@pytest.fixture(scope="module")
def paper():
    return get_paper("teleoperator")


def test_selected_verdicts(paper):
    report = audit_paper(paper, list(EXPECTED))
    assert {r.id: r.verdict.value for r in report.results} == EXPECTED
    five = next(r for r in report.results if r.id == "5")
    assert five.corrected and r"\frac{1 - e^{-sT}}{s}" in five.corrected
    # (29)/(32): sufficient only under (P1)-(P4) -- a negative spring passes them yet is not passive
    # (exact decision), and they are not necessary with unequal dampers; (35): sufficient, exact for
    # equal robots only
    for eq in ("29", "32"):
        facts = next(r for r in report.results if r.id == eq).evidence.facts
        assert facts["exact_decisions"] == {"negative spring C = -1: (29)/(32) holds": "proved",
                                            "negative spring C = -1: passive": "disproved",
                                            "unequal robots: (29)/(32) holds": "disproved", "unequal robots: passive": "proved"}
        assert facts["harmonic_mean_identity"] is True
    thirty_five = next(r for r in report.results if r.id == "35")
    assert thirty_five.evidence.witness == {"K": "2", "B": "0", "T": "1/3", "b_m": "10", "b_s": "3/7"}


def test_every_numbered_display_is_registered(paper):
    assert {str(k) for k in range(1, 41)} <= set(paper.equations)


@pytest.mark.parametrize("eq_id,mutated", [
    ("35", r"b > \frac{KT}{2} + B"),                                # Colgate's form: not the PD worst case
    ("34", r"b > KT + 2B \cos \omega T"),
    ("32", r"\boxed{\begin{aligned} b_m &> \frac{T}{1 - \cos \omega T} \operatorname{Re} \{ (1 - e^{-j\omega T}) C_m(e^{j\omega T}) \} \\ "
           r"b_s &> \frac{T}{1 - \cos \omega T} \operatorname{Re} \{ (1 - e^{-j\omega T}) C_s(e^{j\omega T}) \} \end{aligned}}"),
    ("14", r"\begin{aligned}\bar{C}_m(j\omega) &= -(1 - e^{-j\omega T}) C_m(e^{j\omega T}) \\ \bar{C}_s(j\omega) &= -\frac{1 - e^{-j\omega T}}{T} C_s(e^{j\omega T})\end{aligned}"),
    ("19", r"V(j\omega) = V_m(j\omega) + V_s(j\omega)"),
])
def test_checks_can_fail(paper, eq_id, mutated):
    assert run_equation(paper, replace(paper.get(eq_id), printed=mutated)).verdict.value != "confirmed"


def test_cross_paper_and_hve_intro():
    cross = audit_paper(get_paper("cross-paper"), ["tele35-colgate", "tele-routh-hve4", "tele32-alpha1-29", "hve25-5",
                                                   "hve5-classics"])
    assert [r.verdict.value for r in cross.results] == ["inconsistent", "confirmed", "confirmed", "inconsistent", "inconsistent"]
    hve = audit_paper(get_paper("hve"), ["2", "4", "5", "25-identical-7", "36-identical-7"])
    assert [r.verdict.value for r in hve.results] == ["needs-assumption", "needs-assumption", "typo", "inconsistent", "inconsistent"]


@pytest.mark.parametrize("method", ["backward", "forward", "bilinear"])
@pytest.mark.parametrize("gains", [None, (1, 1, 2), (sp.Rational(3, 2), 0, sp.Rational(1, 1000)), (0, 5, sp.Rational(1, 3))])
def test_discretize_pd_is_sympy_physics_control(method, gains):
    """The written-out generalized bilinear transform gives sympy.physics.control's result exactly."""
    from sympy.physics import control

    K, B, T = gains or (telemodel.TELE_SYMBOLS["K"], telemodel.TELE_SYMBOLS["B"], telemodel.TELE_SYMBOLS["T"])
    K, B, T = (sp.sympify(v) for v in (K, B, T))
    s = sp.Symbol("s")
    reference = {"backward": control.backward_diff, "forward": control.forward_diff, "bilinear": control.bilinear}[method]
    num, den = reference(control.TransferFunction(K + B * s, 1, s), T)
    top = max(len(num), len(den)) - 1

    def as_poly(coeffs):
        return sum(c_ * z ** (len(coeffs) - 1 - i) for i, c_ in enumerate(coeffs))

    expected = sp.cancel(as_poly(num) * z ** (top - len(num) + 1) / (as_poly(den) * z ** (top - len(den) + 1)))
    assert telemodel.discretize_pd(method, K, B, T) == expected


def test_numeric_latex_says_what_32_needs_not_holds_for_no_value(capsys):
    from hapticproof.cli import main

    base = ["derive", "teleoperator", "--role", "master_damping=c_m", "--role", "slave_damping=c_s", "--role", "period=h",
            "--param", "K=20", "--param", "B=0.01", "--param", "h=0.001", "--param", "c_s=0.05", "--format", "latex",
            "--fragment"]
    for c_m, verdict in (("0.001", "not met"), ("0.05", "met")):
        assert main([*base, "--param", f"c_m={c_m}"]) == 0
        out = capsys.readouterr().out
        assert f"(sufficient only): {verdict} by these values" in out and "holds for no value" not in out
        assert r"c_{m} \ge \frac{1}{25},\quad c_{s} \ge \frac{1}{25}" in out
