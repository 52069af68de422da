"""Scenes, integrators and G^-1(z), cross-checked with sympy.physics.control and by direct
complex evaluation of G^-1(e^{jwT}) at random frequencies and parameters."""

import dataclasses
import math
from fractions import Fraction

import mpmath
import pytest
import sympy as sp
from hypothesis import given, settings
from hypothesis import strategies as st
from sympy.physics.control import TransferFunction, backward_diff, bilinear, forward_diff

from hapticproof.core.errors import SceneError
from hapticproof.core.lazy import computed_stages, profile
from hapticproof.systems.models import integrator, inverse_transfer
from hapticproof.analysis.positivereal import hermitian, residues, worst_case
from hapticproof.systems.singleuser import SYMBOLS, SingleUserScene, delay_ratio, virtual_wall
from hapticproof.core.symbols import c, s, z

K, B, T = sp.symbols("K B T", positive=True)


def from_coefficients(num, den):
    """Falling coefficients (sympy.physics.control convention) -> expression in z."""
    return sum(a * z ** (len(num) - 1 - i) for i, a in enumerate(num)) / sum(
        a * z ** (len(den) - 1 - i) for i, a in enumerate(den)
    )


def test_integrators_match_sympy_physics_control():
    one_over_s = TransferFunction(1, s, s)
    assert sp.simplify(integrator("forward", T) - from_coefficients(*forward_diff(one_over_s, T))) == 0
    assert sp.simplify(integrator("backward", T) - from_coefficients(*backward_diff(one_over_s, T))) == 0
    assert sp.simplify(integrator("tustin", T) - from_coefficients(*bilinear(one_over_s, T))) == 0


def test_virtual_wall_is_backward_difference_of_spring_damper():
    spring_damper = TransferFunction(K + B * s, 1, s)
    assert sp.simplify(virtual_wall(K, B, T) - from_coefficients(*backward_diff(spring_damper, T))) == 0
    # and it is NOT the bilinear (Tustin) discretisation of K + Bs
    assert sp.simplify(virtual_wall(K, B, T) - from_coefficients(*bilinear(spring_damper, T))) != 0


def test_g_inverse_forms_before_eq17():
    b = sp.Symbol("b", positive=True)
    forms = {
        "forward": b + K * T / (z - 1) + B / z,
        "backward": b + K * T * z / (z - 1) + B,
        "tustin": b + K * T / 2 * (z + 1) / (z - 1) + B * (z + 1) / (2 * z),
    }
    for approximation, expected in forms.items():
        scene = SingleUserScene.virtual_wall(K=K, B=B, b=b, T=T, approximation=approximation)
        assert sp.simplify(inverse_transfer(scene) - expected) == 0


params = st.fractions(Fraction(1, 100), 10, max_denominator=100)


@settings(max_examples=150, deadline=None)
@given(
    st.sampled_from(["forward", "backward", "tustin"]),
    st.integers(0, 20),
    params, params, params, params, st.fractions(0, 1, max_denominator=13),
    st.floats(0.01, math.pi - 0.01),
)
def test_c_form_matches_direct_evaluation(approximation, delay, Kv, Bv, bv, Tv, zav, theta):
    scene = SingleUserScene.virtual_wall(K=Kv, B=Bv, b=bv, T=Tv, approximation=approximation, delay=delay, z_a=zav)
    form = hermitian(scene)
    G = inverse_transfer(scene)
    with mpmath.workdps(40):
        direct = sp.lambdify(z, G, "mpmath")(mpmath.expj(theta))
        exact_form = sp.lambdify(c, form.expr(), "mpmath")(mpmath.cos(theta))
        assert abs(exact_form - direct.real) <= 1e-12 * (1 + abs(direct))


def test_theta_form_symbolic_delay_matches_corrected_eq23():
    n = SYMBOLS["n"]
    Ks, Bs, bs, Ts = (SYMBOLS[name] for name in ("K", "B", "b", "T"))
    tf = hermitian(SingleUserScene.virtual_wall(delay=n))
    theta = sp.Symbol("theta")
    # Re G^-1 = b + B cos((n+1) theta) - KT/2 cos(n theta) - KT S, S as in the paper
    S = sp.sin(n * theta) * sp.sin(theta) / (2 * (1 - sp.cos(theta)))
    expected = bs + Bs * sp.cos((n + 1) * theta) - Ks * Ts / 2 * sp.cos(n * theta) - Ks * Ts * S
    values = {Bs: 0.7, Ks: 1.3, Ts: 0.4, bs: 2.0}
    for n_value in range(6):
        for t in (0.3, 1.1, 2.9):
            point = {n: n_value, theta: t}
            assert abs(float(tf.expr(theta).subs(values).subs(point)) - float(expected.subs(values).subs(point))) < 1e-12


def test_residue_is_KT_for_all_approximations_and_delays():
    for approximation in ("forward", "backward", "tustin"):
        for delay in (0, 3):
            scene = SingleUserScene.virtual_wall(approximation=approximation, delay=delay)
            (res,) = residues(scene)
            assert res.pole == 1
            assert sp.simplify(res.residue - scene.H.subs(z, 1) * scene.T) == 0


def test_scene_validation():
    with pytest.raises(SceneError, match="T must be positive"):
        SingleUserScene.virtual_wall(T=0)
    with pytest.raises(SceneError, match="non-negative integer"):
        SingleUserScene.virtual_wall(delay="2.5")
    with pytest.raises(SceneError, match="must be an integer"):
        SingleUserScene.virtual_wall(T="0.003", t_d="0.01")
    # a negative damping is decided, not refused: G^-1 = -1 + ... is not positive real
    from hapticproof.analysis.positivereal import positive_real
    assert positive_real(SingleUserScene.virtual_wall(b=-1, K=2, B="0.001", T="0.001")).decision.value == "disproved"
    with pytest.raises(SceneError, match="unknown approximation"):
        SingleUserScene.virtual_wall(approximation="euler")
    assert delay_ratio("0.01", "0.001") == 10
    assert SingleUserScene.virtual_wall(T=0.5).T == sp.Rational(1, 2)  # floats converted exactly


def test_scenes_are_hashable_values_and_lazy():
    a = SingleUserScene.virtual_wall(K=2, B=0, b=1, T=sp.Rational(1, 10))
    b = SingleUserScene.virtual_wall(K=2, B=0, b=1, T=sp.Rational(1, 10))
    assert a == b and hash(a) == hash(b)
    hermitian(a)
    assert "hermitian" in computed_stages(b)  # equal scenes share their cache
    assert "residues" not in computed_stages(a)  # nothing computed that was not asked for
    assert set(profile(a)) >= {"hermitian", "transfer_polynomials"}   # numeric: flint route, no G^-1 expression
    assert "inverse_transfer" not in computed_stages(a)


def test_worst_case_numeric_decisions():
    # forward difference, no delay: exact boundary b = KT/2 + B (Colgate), minimum at c = -1
    at_boundary = SingleUserScene.virtual_wall(K=2, B=sp.Rational(1, 10), b=sp.Rational(11, 10), T=1)
    wc = worst_case(at_boundary)
    assert wc.decision.value == "proved" and wc.minimum == 0 and wc.minimiser == -1
    below = dataclasses.replace(at_boundary, b=sp.Rational(109, 100))
    wc = worst_case(below)
    assert wc.decision.value == "disproved"
    assert hermitian(below)(wc.outcome.witness["c"]) < 0
