"""The exact passivity decision of the sampled-data PEB teleoperator
(:mod:`hapticproof.analysis.teleoperator`): the theorem's conditions (D), (P1)-(P5) on the cases
that separate them, the issue's reproductions (issue 18), the paper's PD example, and the energy
oracle (``tests/oracles/energy.py``, no package code) on every case where a verdict could be in
doubt. Exact values are derived in the comments."""

from __future__ import annotations

import json
import subprocess
import sys
from fractions import Fraction as F
from pathlib import Path

import mpmath
import pytest
import sympy as sp

sys.path.insert(0, str(Path(__file__).resolve().parent))

from oracles.energy import teleoperator_energy_oracle  # noqa: E402
from certified import assert_certified  # noqa: E402

from hapticproof.analysis import teleoperator as tele  # noqa: E402
from hapticproof.analysis.passiverange import passive_range  # noqa: E402
from hapticproof.core.errors import SceneError  # noqa: E402
from hapticproof.core.symbols import z  # noqa: E402
from hapticproof.systems.scene import Scene  # noqa: E402
from hapticproof.systems.teleoperator import TELE_SYMBOLS, TeleoperatorScene  # noqa: E402

R = sp.Rational
EXAMPLES = Path(__file__).resolve().parents[1] / "examples"


def scene(C, T, b_m, b_s, alpha=1) -> TeleoperatorScene:
    q = lambda v: sp.Rational(F(str(v)).numerator, F(str(v)).denominator)  # noqa: E731
    return TeleoperatorScene(None, None, q(b_m), q(b_s), q(T), sp.sympify(C), q(alpha))


def decide(C, T, b_m, b_s, alpha=1):
    out = tele.passivity(scene(C, T, b_m, b_s, alpha))
    assert_certified(out)
    return out


def failed(out) -> list[str]:
    return [c.name.split(")")[0][1:] for c in out.evidence.facts["conditions"] if c.decision.value == "disproved"]


def witness(out, key: str) -> dict:
    return next(c.outcome for c in out.evidence.facts["conditions"] if c.name.startswith(f"({key})")).witness


def coeffs(C) -> tuple[list[F], list[F]]:
    num, den = sp.fraction(sp.cancel(sp.sympify(C)))
    conv = lambda p: [F(int(R(c).p), int(R(c).q)) for c in sp.Poly(p, z).all_coeffs()]  # noqa: E731
    return conv(num), conv(den)


def energy(C, T, b_m, b_s, alpha=1, m_m="0.01", m_s="0.02", **kw):
    num, den = coeffs(C)
    kw.setdefault("horizon", 64)
    kw.setdefault("long_horizon", 1024)
    return teleoperator_energy_oracle(num, den, F(str(T)), F(str(b_m)), F(str(b_s)), F(str(alpha)), F(m_m), F(m_s), **kw)


def pd(K, B, T):
    K, B, T = (R(F(str(v)).numerator, F(str(v)).denominator) for v in (K, B, T))
    return K + B * (z - 1) / (T * z)


# ---------------------------------------------------------------------------------------------
# the reproductions
# ---------------------------------------------------------------------------------------------


def test_negative_stiffness_is_disproved_by_the_dc_condition():
    # C = K = -5: (32) holds for any damping (L = KT/2 < 0) but C(1) = -5 < 0; a slow displacement
    # of the error needs 1 + 2h/(|K| T) = 8.5 periods (h = 3/160) to show the negative energy
    out = decide(-5, "0.001", "0.03", "0.05")
    assert out.decision.value == "disproved" and failed(out) == ["P3"]
    assert witness(out, "P3") == {"C(1)": -5}
    assert tele.criterion(scene(-5, "0.001", "0.03", "0.05")).decision.value == "proved"
    o = energy(-5, "0.001", "0.03", "0.05")
    assert o.verdict == "not passive" and o.energy < 0


def test_unequal_dampers_passive_although_32_fails():
    # h = 10 (3/7)/(10 + 3/7) = 30/73 > KT/2 = 1/3: passive; (32) needs b_s >= 2 L = 2/3
    out = decide(2, "1/3", 10, "3/7")
    assert out.decision.value == "proved"
    assert tele.error_coordinate_damping(scene(2, "1/3", 10, "3/7")) == R(30, 73)
    assert tele.criterion(scene(2, "1/3", 10, "3/7")).decision.value == "disproved"
    assert energy(2, "1/3", 10, "3/7", m_m="1", m_s="1").verdict == "no negative energy found"
    # the boundary h = 1/3 is b_s = 10/29 (passive); just below it is not
    assert decide(2, "1/3", 10, "10/29").decision.value == "proved"
    below = decide(2, "1/3", 10, F(10, 29) - F(1, 1000))
    assert failed(below) == ["P5"] and below.decision.value == "disproved"


@pytest.mark.parametrize("C, T, b_m, b_s, alpha, expected, fails", [
    (2, "1/3", 10, "3/7", 1, "proved", []),
    (1, "0.01", "0.1", "0.0135", 2, "proved", []),                 # h = 27/3080 >= KT/2 = 1/200
    ("1 - 1/(z + 1)", "0.01", "0.02", "0.02", 1, "disproved", ["P4"]),    # Res(C, -1)/2 = -1/2
    ("(z - 1)/(z**2 + 1)", "0.01", "0.02", "0.02", 1, "disproved", ["P4"]),   # rho = -1/2 at z = +-j
    ("1/(z + 1)", "0.01", "0.02", "0.02", 1, "proved", []),          # rho = 1/2, L = T/2 = 1/200 <= h = 1/100
    ("1/(z + 1)", "0.01", "0.009", "0.009", 1, "disproved", ["P5"]), # h = 0.0045 < T/2
    ("(1 - z)/(z**2 + 1)", "0.01", "0.02", "0.02", 1, "proved", []), # rho = 1/2, L = T/2
    ("1/(z - 2)", "0.01", 1, 1, 1, "disproved", ["P1", "P3"]),    # pole at 2, and C(1) = -1
    (0, "0.01", "0.1", "0.2", 1, "proved", []),                      # no controller
    (0, "0.01", 0, 0, 1, "proved", []),                              # free masses
    (1, "0.01", "0.1", 0, 1, "disproved", ["P5"]),                   # h = 0 with C != 0
    (0, "0.01", "-0.1", "0.2", 1, "disproved", ["D"]),               # a negative damping
])
def test_theorem_cases(C, T, b_m, b_s, alpha, expected, fails):
    out = decide(C, T, b_m, b_s, alpha)
    assert out.decision.value == expected and failed(out) == fails
    if fails in ([], ["P4"], ["P5"], ["D"]):
        o = energy(C, T, b_m, b_s, alpha)
        assert (o.verdict == "not passive") is (expected == "disproved"), (C, o)


@pytest.mark.parametrize("Ki", [F(1), F(-1)])
def test_integral_action_is_never_passive(Ki):
    # backward PID: a pole at z = 1, whatever the sign of K_i (K_i < 0: a ramp of the error gives
    # K_i t^3/6 against the dampers' O(t))
    T = R(1, 100)
    C = 1 + R(Ki.numerator, Ki.denominator) * T * z / (z - 1) + R(1, 1000) * (z - 1) / (T * z)
    out = decide(C, T, "0.5", "0.5")
    assert out.decision.value == "disproved" and "P2" in failed(out)
    assert witness(out, "P2") == {"pole": 1, "order": 1}
    assert energy(C, T, "0.5", "0.5", long_horizon=2048).verdict == "not passive"


def test_alpha_of_any_sign_and_zero():
    C = pd(1, "0.001", "0.01")
    assert decide(C, "0.01", "0.05", "0.05", "-3/2").decision.value == "proved"
    # alpha = -1: (32) reduces to b_m, b_s >= 0 and "holds" for a damping-starved system
    assert tele.criterion(scene(C, "0.01", "0.001", "0.5", -1)).decision.value == "proved"
    out = decide(C, "0.01", "0.001", "0.5", -1)
    assert out.decision.value == "disproved" and failed(out) == ["P5"]
    assert energy(C, "0.01", "0.001", "0.5", -1).verdict == "not passive"
    # alpha = 0: Colgate's wall on the slave, b_s >= KT/2 + B = 0.006 (and b_m = 0 is allowed)
    for b_s, passive in (("0.006", True), ("0.0059", False)):
        assert tele.error_coordinate_damping(scene(C, "0.01", 0, b_s, 0)) == R(b_s)
        assert (decide(C, "0.01", 0, b_s, 0).decision.value == "proved") is passive


def test_pd_closed_form_and_the_paper_table():
    # passive iff K >= 0 and h >= KT/2 + |B|; the paper's Table I (b = 0.01822, B = 0)
    for T, K, passive in (("0.007", "2.4", True), ("0.015", "1", True), ("0.015", "2", False)):
        out = decide(pd(K, 0, T), T, "0.01822", "0.01822")
        assert (out.decision.value == "proved") is passive
        if not passive:
            w = witness(out, "P5")
            assert failed(out) == ["P5"] and w["c"] == -1                   # the worst case at Nyquist
    # (35) as printed for B < 0 is wrong: K = 1, B = -0.001, T = 0.01, b = 0.011 > KT + 2B = 0.008,
    # but h = 0.0055 < KT/2 + |B| = 0.006: h - L(c) = 0.0005 - 0.001 c < 0 for c > 1/2 (worst at c = 1,
    # where T H has its pole: the witness is inside (1/2, 1))
    out = decide(pd(1, "-0.001", "0.01"), "0.01", "0.011", "0.011")
    assert out.decision.value == "disproved" and F(1, 2) < F(str(witness(out, "P5")["c"])) < 1
    assert energy(pd(1, "-0.001", "0.01"), "0.01", "0.011", "0.011").verdict == "not passive"
    S = TELE_SYMBOLS                     # K > 0 and B >= 0 by the paper's assumptions: (P3) holds
    exact = tele.exact_condition(TeleoperatorScene.pd(alpha=1))
    assert exact == sp.Ge(S["b_m"] * S["b_s"] / (S["b_m"] + S["b_s"]), S["B"] + S["K"] * S["T"] / 2)
    K = sp.Symbol("K", real=True)      # a gain of either sign: K >= 0 is a condition of its own
    general = tele.exact_condition(TeleoperatorScene(None, None, S["b_m"], S["b_s"], S["T"], K + S["B"] * (z - 1) / (S["T"] * z)))
    assert set(general.args) == {sp.Ge(K, 0), sp.Ge(S["b_m"] * S["b_s"] / (S["b_m"] + S["b_s"]), S["B"] + K * S["T"] / 2)}


def test_p5_witness_is_a_true_violation():
    # h - L(c) at the witness, L evaluated from its definition -T Re{C(z)/(z - 1)} in mpmath
    for C, T, b in ((2, "0.015", "0.01822"), ("(5*z - 3)/(z - 1/2)", "0.05", "0.1"), ("z/(z**2 - 6*z/5 + 81/100)", "0.1", "0.5")):
        out = decide(C, T, b, b)
        w = witness(out, "P5")
        c = F(str(w["c"]))
        num, den = coeffs(C)
        with mpmath.workdps(50):
            zz = mpmath.mpc(mpmath.mpf(c.numerator) / c.denominator, mpmath.sqrt(1 - (mpmath.mpf(c.numerator) / c.denominator) ** 2))
            Cz = mpmath.polyval([mpmath.mpf(x.numerator) / x.denominator for x in num], zz) / \
                mpmath.polyval([mpmath.mpf(x.numerator) / x.denominator for x in den], zz)
            h = mpmath.mpf(F(str(b)).numerator) / F(str(b)).denominator / 2
            T_ = mpmath.mpf(F(str(T)).numerator) / F(str(T)).denominator
            assert h + T_ * mpmath.re(Cz / (zz - 1)) < 0


def test_improper_controller_is_refused_in_one_line():
    with pytest.raises(SceneError, match="improper"):
        TeleoperatorScene(None, None, 1, 1, R(1, 100), z)
    with pytest.raises(SceneError, match="improper"):
        Scene("teleoperator", controller="K + B*s", discretize="forward", params={"K": 1, "B": "0.01", "T": "0.01"}).build()
    out = subprocess.run([sys.executable, "-m", "hapticproof", "derive", "teleoperator", "--controller", "K + B*s",
                          "--discretize", "forward", "--param", "K=1", "--param", "B=0.01", "--param", "T=0.01"],
                         capture_output=True, text=True, timeout=300)
    assert out.returncode == 2 and "improper" in out.stderr and "Traceback" not in out.stderr


def test_exact_ranges():
    rng = passive_range(Scene.read(EXAMPLES / "pid_teleoperator.toml"), "K_p")
    assert rng.to_text().startswith("passive range of K_p (others fixed): 0 <= K_p <= 98/5")
    pd_scene = Scene("teleoperator", params={"K": "real", "B": "0.001", "T": "0.01", "b_m": "0.05", "b_s": "0.02"})
    # h = 1/70 >= KT/2 + B  <=>  K <= 2 (1/70 - 1/1000)/(1/100) = 93/35; K >= 0 by (P3)
    assert passive_range(pd_scene, "K").to_text().startswith("passive range of K (others fixed): 0 <= K <= 93/35")


def test_cli_prints_the_exact_conditions_and_32_apart():
    args = [sys.executable, "-m", "hapticproof", "derive", "teleoperator", "--param", "K=2", "--param", "T=1/3",
            "--param", "B=0", "--param", "b_m=10", "--param", "b_s=3/7", "--format", "json"]
    data = json.loads(subprocess.run(args, capture_output=True, text=True, timeout=300, check=True).stdout)
    assert data["verdict"] == "proved"
    assert [c["name"][:4] for c in data["conditions"]] == ["(D) ", "(P1)", "(P2)", "(P3)", "(P4)", "(P5)"]
    assert data["criterion_32"]["decision"] == "disproved"


def test_a_zero_controller_is_passive_with_nonnegative_dampers():
    """Found by the fuzz test (controller = "0": the zero polynomial's degree is -oo)."""
    from hapticproof.analysis.teleoperator import passivity
    from hapticproof.systems.scene import Scene

    scene = Scene("teleoperator", controller="0").build()
    assert passivity(scene).decision.value == "proved"
