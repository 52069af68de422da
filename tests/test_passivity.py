"""``hapticproof.ispassive`` and the python-control / SymPy adapters (:mod:`hapticproof.systems.lti`).

Differential: random discrete and continuous systems (python-control ``StateSpace`` and
``TransferFunction``, SISO and 2 x 2; SymPy ``TransferFunction``), some far from the passivity
boundary and some placed near it, are decided by :func:`hapticproof.ispassive` and by the oracle of
``tests/oracles/lti.py`` (reads the objects itself, decides the definition numerically at 60 digits,
imports nothing from the package). They must agree whenever the oracle is certain; every
certificate is re-verified. Size knob: ``HAPTICPROOF_DIFF_EXAMPLES`` (this family uses 0.6 of it).
The python-control tests skip when it is not installed (``pip install 'hapticproof[control]'``).
"""

from __future__ import annotations

import sys
from fractions import Fraction
from pathlib import Path

import pytest
import sympy as sp
from hypothesis import HealthCheck, Phase, given, settings
from hypothesis import strategies as st

sys.path.insert(0, str(Path(__file__).resolve().parent))

from certified import assert_certified  # noqa: E402
from oracles.discrete import discrete_positive_real  # noqa: E402
from oracles.harness import examples, expected_decision  # noqa: E402
from oracles.lti import bilinear_positive_real, exact_matrix, lti_positive_real  # noqa: E402

import hapticproof  # noqa: E402
from hapticproof import ispassive  # noqa: E402
from hapticproof.core.errors import SceneError  # noqa: E402
from hapticproof.core.evidence import Decision  # noqa: E402
from hapticproof.exact.checker import check_certificates  # noqa: E402
from hapticproof.systems.lti import from_object, hermitian_system, inverse_transfer_system  # noqa: E402

R = sp.Rational
z, s = sp.Symbol("z"), sp.Symbol("s")
SETTINGS = dict(deadline=None, phases=(Phase.explicit, Phase.reuse, Phase.generate),
                suppress_health_check=[HealthCheck.too_slow, HealthCheck.filter_too_much])


def _all_verified(result) -> None:
    checks = check_certificates(result.to_json())
    assert checks and all(c.ok for c in checks), [c for c in checks if not c.ok]
    assert_certified(result.outcome)


# ---------------------------------------------------------------------------------------------
# SymPy in, exact answers out (no python-control needed)
# ---------------------------------------------------------------------------------------------


def test_public_name_and_known_answers():
    assert hapticproof.ispassive is ispassive
    # 1/2 + 1/(z - 1): Re = 1/2 - 1/2 = 0 on the circle (touching), residue 1 at z = 1
    assert ispassive(R(1, 2) + 1 / (z - 1)).decision == Decision.PROVED
    below = ispassive(R(1, 2) - R(1, 10**12) + 1 / (z - 1))
    assert below.decision == Decision.DISPROVED and not below
    # (z - 1)/(z + 1) is the bilinear image of s: positive real with Res/z0 = 2 at z0 = -1
    assert ispassive((z - 1) / (z + 1)).decision == Decision.PROVED
    # improper: a pole at z = infinity
    assert ispassive(z**2 / (z + R(1, 2))).decision == Decision.DISPROVED
    # a pole outside, a double pole on the circle, a negative residue
    assert ispassive(1 / (z - 2)).decision == Decision.DISPROVED
    assert ispassive(z**2 / (z - 1) ** 2).decision == Decision.DISPROVED
    assert ispassive(1 - 1 / (z - 1)).decision == Decision.DISPROVED
    # continuous: a mass-spring-damper impedance and its negative
    assert ispassive(s + 2 + 3 / s).decision == Decision.PROVED
    assert ispassive((s - 1) / (s + 1)).decision == Decision.DISPROVED


def test_sympy_transfer_function_matrix_and_witness():
    from sympy.physics.control.lti import TransferFunction, TransferFunctionMatrix

    ok = TransferFunctionMatrix([[TransferFunction(1, s + 1, s), TransferFunction(0, 1, s)],
                                 [TransferFunction(0, 1, s), TransferFunction(s, 1, s)]])
    assert ispassive(ok).decision == Decision.PROVED
    # coupling 3 on a diagonal of 1: Hermitian part [[2, 3], [3, 2]] is not PSD
    bad = TransferFunctionMatrix([[TransferFunction(1, 1, s), TransferFunction(3, 1, s)],
                                  [TransferFunction(0, 1, s), TransferFunction(1, 1, s)]])
    result = ispassive(bad)
    assert result.decision == Decision.DISPROVED
    # discrete: the variable z says so
    disc = TransferFunctionMatrix([[TransferFunction(2 * z, z - R(1, 2), z), TransferFunction(R(1, 10), 1, z)],
                                   [TransferFunction(R(1, 10), 1, z), TransferFunction(1, 1, z)]])
    r = ispassive(disc)
    assert r.system.domain == "discrete"
    oracle = bilinear_positive_real(exact_matrix(disc)[0])
    assert expected_decision(oracle) in (None, r.decision.value)
    _all_verified(r)


def test_hermitian_part_is_the_definition():
    G = from_object((2 * z + 1) / (z - R(1, 3)) + R(1, 5) / z)
    H = hermitian_system(G).expr()
    for c0, s0 in ((R(3, 5), R(4, 5)), (R(-5, 13), R(12, 13))):
        z0 = c0 + sp.I * s0
        want = sp.re(sp.nsimplify(G.expr().subs(sp.Symbol("z"), z0)))
        assert sp.simplify(H.subs(sp.Symbol("z"), z0) - want) == 0
    Gs = from_object((s + 3) / (s**2 + s + 2))
    Hs = hermitian_system(Gs).expr()
    w = R(7, 3)
    assert sp.simplify(Hs.subs(sp.Symbol("s"), sp.I * w) - sp.re(Gs.expr().subs(sp.Symbol("s"), sp.I * w))) == 0


def test_floats_are_exact_and_the_result_says_how():
    r = ispassive(sp.Float(0.1) + 1 / (z - 1))
    assert r.system.entries[0][0][0].coeffs()[0] != 0
    assert "binary" in r.note
    dec = ispassive(sp.Float(0.5) + 1 / (z - 1), floats="decimal")
    assert dec.decision == Decision.PROVED and "decimal" in dec.note


def test_user_mistakes_are_scene_errors():
    with pytest.raises(SceneError, match="symbols"):
        ispassive(sp.Symbol("K") / (z - 1))
    with pytest.raises(SceneError, match="square"):
        ispassive(sp.Matrix([[1 / (z - R(1, 2)), 1]]))
    with pytest.raises(SceneError, match="constant"):
        ispassive(sp.Integer(1))
    with pytest.raises(SceneError):
        ispassive("1/(z - 1)")


def test_scene_inverse_transfer_as_a_system():
    from hapticproof.systems.singleuser import SingleUserScene

    wall = SingleUserScene.virtual_wall(K=2, B="0.001", b="0.0201", T="0.001", delay=3)
    G = inverse_transfer_system(wall)
    assert G.dt == Fraction(1, 1000)
    from hapticproof.analysis.positivereal import positive_real

    assert ispassive(G).decision == positive_real(wall).decision
    tf = G.to_sympy()
    assert sp.simplify(tf.num / tf.den - G.expr()) == 0


# ---------------------------------------------------------------------------------------------
# python-control
# ---------------------------------------------------------------------------------------------


def test_control_objects_in_and_out():
    control = pytest.importorskip("control")
    G = control.tf([1, 0.5], [1, -0.25], 0.001)
    r = ispassive(G)
    assert r.system.domain == "discrete" and r.system.dt == Fraction(0.001)
    assert sp.simplify(r.system.expr() - (z + R(1, 2)) / (z - R(1, 4))) == 0
    back = r.system.to_control()
    assert back.dt == 0.001 and list(back.num[0][0]) == [1.0, 0.5]
    H = r.hermitian_part().to_control()
    assert H.dt == 0.001
    # a state-space model: exactly C (zI - A)^-1 B + D
    S = control.ss([[0.5, 0.25], [0, -0.5]], [[1], [0.5]], [[1, 0]], [[0.75]], 0.01)
    mine = from_object(S).expr()
    theirs = exact_matrix(S)[0][0, 0]
    assert sp.simplify(mine - theirs) == 0
    # continuous, MIMO transfer function (python-control's ispassive needs slycot for this one)
    M = control.tf([[[1], [0.125]], [[0.125], [1]]], [[[1, 1], [1, 1]], [[1, 1], [1, 2]]])
    assert ispassive(M).decision == expected_decision(lti_positive_real(M))
    # dt=True: discrete with an unspecified period
    assert ispassive(control.tf([1, 0], [1, -0.5], True)).system.dt is None


def test_scenes_take_control_and_sympy_systems():
    control = pytest.importorskip("control")
    from sympy.physics.control.lti import TransferFunction

    from hapticproof.analysis.positivereal import positive_real
    from hapticproof.systems.scene import Scene

    # the wall K + B(z - 1)/(T z) = ((K T + B) z - B)/(T z), K = 2, B = 0.001, T = 0.001
    wall = control.tf([0.003, -0.001], [0.001, 0], 0.001)
    scene = Scene("single-user", environment=wall, params={"b": "0.0201"})
    assert dict(scene.params)["T"] == R(1, 1000)
    same = Scene("single-user", params={"K": 2, "B": "0.001", "T": "0.001", "b": "0.0201"})
    assert sp.simplify(scene.build().H - same.build().H) == 0
    assert positive_real(scene.build()).decision == positive_real(same.build()).decision
    with pytest.raises(SceneError, match="sampling period"):
        Scene("single-user", environment=wall, params={"T": "0.002"})
    pid = Scene("single-user", controller=TransferFunction(2 + s / 1000, 1, s), discretize="tustin",
                params={"T": "0.001", "b": "0.02"})
    assert sp.simplify(pid.build().H - (2 + 2 * (z - 1) / (z + 1))) == 0


# ---------------------------------------------------------------------------------------------
# differential: random systems against the oracle
# ---------------------------------------------------------------------------------------------


@st.composite
def state_space(draw) -> dict:
    n = draw(st.integers(1, 3))
    p = draw(st.sampled_from([1, 1, 2]))
    discrete = draw(st.booleans())
    num = lambda lo, hi: Fraction(draw(st.integers(lo, hi)), 8)  # noqa: E731 - exact binary floats
    A = [[num(-6, 6) for _ in range(n)] for _ in range(n)]
    # keep the poles inside (discrete: |eigenvalues| < 1 by a scaled A; continuous: shift left)
    scale = max(1, sum(abs(v) for row in A for v in row))
    A = [[v / scale * Fraction(7, 8) if discrete else v - (2 if i == j else 0) for j, v in enumerate(row)]
         for i, row in enumerate(A)]
    B = [[num(-8, 8) for _ in range(p)] for _ in range(n)]
    C = [[B[i][k] + num(-2, 2) * draw(st.integers(0, 1)) for i in range(n)] for k in range(p)]
    D = [[num(0, 40) if i == j else num(-3, 3) for j in range(p)] for i in range(p)]
    return {"A": A, "B": B, "C": C, "D": D, "dt": Fraction(1, 100) if discrete else 0}


def test_random_systems_match_the_oracle():
    control = pytest.importorskip("control")
    import numpy as np

    @settings(max_examples=examples(0.6), **SETTINGS)
    @given(case=state_space(), as_tf=st.booleans())
    def run(case, as_tf):
        arr = lambda M: np.array([[float(v) for v in row] for row in M], dtype=float)  # noqa: E731
        sysm = control.ss(arr(case["A"]), arr(case["B"]), arr(case["C"]), arr(case["D"]), float(case["dt"]))
        if as_tf and sysm.ninputs == 1:
            sysm = control.ss2tf(sysm)
        result = ispassive(sysm)
        _all_verified(result)
        want = expected_decision(lti_positive_real(sysm))
        assert want in (None, result.decision.value), (case, as_tf, result.reason)

    run()


def test_bilinear_oracle_agrees_with_the_scalar_one():
    """The two discrete oracles (scalar Definition 2, and the bilinear map to the continuous one)."""
    for F in (R(1, 2) + 1 / (z - 1), (z - 1) / (z + 1) + R(1, 10), 1 / (z - R(1, 2)), R(1, 5) + 1 / (z - 1)):
        a = discrete_positive_real(F).verdict
        b = bilinear_positive_real(sp.Matrix([[F]])).verdict
        assert "uncertain" in (a, b) or a == b, (F, a, b)
        assert expected_decision(discrete_positive_real(F)) in (None, ispassive(F).decision.value)


def test_flint_hermitian_part_is_the_sympy_one():
    """The flint Hermitian part of a discrete matrix against the generic SymPy route, exactly."""
    from hapticproof.analysis.passivity import circle_hermitian
    from hapticproof.exact.psd import hermitian_part_matrix

    G = sp.Matrix([[2 + 1 / (z - 1), R(1, 3) / z], [(z + R(1, 2)) / (z**2 - R(1, 4)), 1 + z**-3 / (z - R(1, 5))]])
    system = from_object(G)
    mine, generic = circle_hermitian(system), hermitian_part_matrix(system.matrix())
    assert not mine.is_symmetric
    for c0, s0 in ((R(3, 5), R(4, 5)), (R(-5, 13), R(12, 13)), (R(8, 17), -R(15, 17))):
        assert sp.simplify(mine.at(c0, s0) - generic.at(c0, s0)) == sp.zeros(2, 2)
