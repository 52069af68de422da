"""Exact ZOH discretisation, closed loops, spectral boundaries (hapticproof.analysis.sampled)."""

from __future__ import annotations

import math

import mpmath
import numpy as np
import pytest
import scipy.signal
from hypothesis import given, settings
from hypothesis import strategies as st

from hapticproof.core.errors import InputFormatError, SceneError
from hapticproof.analysis.maps import SceneFamily, find_boundary, refine_boundary_mp
from hapticproof.systems.impedance import CLAMPED, DiscreteTF, Impedance
from hapticproof.systems.loops import MultiUser, SingleUser, Teleoperator
from hapticproof.analysis.sampled import closed_loop_matrix, discretize, free_device_boundary, spectral_radius

HAND = Impedance.spring_damper(0.05, 1.0)
SCENES = [
    SingleUser(m=0.015, b=0.02, T=0.001, K=10),
    SingleUser(m=0.015, b=0.02, T=0.003, K=5, B=0.002, operator=Impedance.active_spring(0.01)),
    SingleUser(m=0.2, b=0.1, T=0.01, K=1, operator=Impedance((1, 2, 3, 4), (1, 1, 0))),
    MultiUser.uniform(3, m=0.015, b=0.018, T=0.002, K=8, B=0.001, delay=2,
                      operator=Impedance.active_spring(0.004)),
    Teleoperator.symmetric(m=0.015, b=0.018, T=0.004, K=2, master=HAND, slave=HAND),
    Teleoperator(m_m=0.02, m_s=0.01, b_m=0.03, b_s=0.01, T=0.002, K=3, alpha=0.5, slave=CLAMPED),
]


@pytest.mark.parametrize("scene", SCENES, ids=lambda s: type(s).__name__)
def test_zoh_matches_scipy_cont2discrete(scene):
    loop = scene.loop()
    phi, gamma = discretize(loop.a, loop.bu, loop.T)
    d = np.zeros((loop.c.shape[0], loop.bu.shape[1]))
    ad, bd, *_ = scipy.signal.cont2discrete((loop.a, loop.bu, loop.c, d), loop.T, method="zoh")
    np.testing.assert_allclose(phi, ad, rtol=1e-12, atol=1e-14)
    np.testing.assert_allclose(gamma, bd, rtol=1e-12, atol=1e-16)


@pytest.mark.parametrize("scene", SCENES[:4], ids=lambda s: type(s).__name__)
def test_mp_discretisation_agrees_with_float(scene):
    loop = scene.loop("mp")
    phi, gamma = discretize(loop.a, loop.bu, loop.T, precision="mp", dps=40)
    fphi, fgamma = discretize(scene.loop().a, scene.loop().bu, scene.loop().T)
    np.testing.assert_allclose(np.array(phi.tolist(), dtype=float), fphi, rtol=1e-12, atol=1e-15)
    np.testing.assert_allclose(np.array(gamma.tolist(), dtype=float).ravel(), fgamma.ravel(),
                               rtol=1e-12, atol=1e-17)


@settings(max_examples=25, deadline=None)
@given(
    m=st.floats(0.01, 2.0), b=st.floats(0.0, 1.0), k=st.floats(0.0, 5.0),
    t1=st.floats(1e-4, 0.05), t2=st.floats(1e-4, 0.05),
)
def test_zoh_semigroup(m, b, k, t1, t2):
    """Phi(t1 + t2) = Phi(t2) Phi(t1); Gamma(t1 + t2) = Phi(t2) Gamma(t1) + Gamma(t2)."""
    op = Impedance.spring_damper(0.01, k) if k else None
    loop = SingleUser(m=m, b=b, T=t1, operator=op).loop()
    p1, g1 = discretize(loop.a, loop.bu, t1)
    p2, g2 = discretize(loop.a, loop.bu, t2)
    p12, g12 = discretize(loop.a, loop.bu, t1 + t2)
    np.testing.assert_allclose(p12, p2 @ p1, rtol=1e-10, atol=1e-12)
    np.testing.assert_allclose(g12, p2 @ g1 + g2, rtol=1e-10, atol=1e-14)


@settings(max_examples=20, deadline=None)
@given(
    q1=st.floats(0, 0.1), q0=st.floats(-0.05, 0.5), k=st.floats(0, 3), r=st.floats(0.1, 3),
    p=st.floats(0.5, 20), w=st.floats(0.1, 100),
)
def test_device_realisation_matches_impedance(q1, q0, k, r, p, w):
    """X(s)/U(s) of the assembled device equals -1/(s (m s + b + Z(s))) for
    Z = q1 s + q0 + k/s + r/(s + p)."""
    num = np.polyadd(np.polymul([q1, q0], [1, p, 0]), np.polyadd(np.polymul([k], [1, p]), [r, 0]))
    z = Impedance(tuple(float(c) for c in num), (1.0, p, 0.0))
    m, b = 0.02, 0.01
    loop = SingleUser(m=m, b=b, T=0.001, operator=z).loop()
    s = 1j * w
    tf = (loop.c @ np.linalg.solve(s * np.eye(loop.a.shape[0]) - loop.a, loop.bu))[0, 0]
    expected = -1 / (s * (m * s + b + z(s)))
    assert abs(tf - expected) <= 1e-9 * abs(expected)


@pytest.mark.parametrize(
    "m, b, T", [(0.015, 0.02, 0.001), (0.015, 0.01822, 0.02), (1.0, 2.0, 0.5), (0.1, 3.0, 0.2)]
)
def test_spectral_boundary_matches_closed_form(m, b, T):
    fam = SceneFamily("single-user", {"m": m, "b": b, "B": 0, "T": T})
    bnd = find_boundary(fam, "K", rtol=1e-12)
    exact = free_device_boundary(m, b, T)
    assert bnd.crossings and len(bnd.crossings) == 1
    assert abs(bnd.value - exact) <= 1e-9 * exact
    assert abs(bnd.value - exact) <= bnd.tolerance + 1e-12 * exact


def test_closed_form_has_both_jury_branches():
    """Small alpha: the complex pair leaves (a0 = 1); large alpha: z = -1 (flip)."""
    for m, b, T in [(0.015, 0.02, 0.001), (0.1, 3.0, 0.2)]:
        k = free_device_boundary(m, b, T) * (1 + 1e-7)
        eig = np.linalg.eigvals(closed_loop_matrix(SingleUser(m=m, b=b, T=T, K=k)))
        top = eig[np.argmax(abs(eig))]
        if b * T / m < 1:
            assert abs(top.imag) > 1e-3
        else:
            assert abs(top + 1) < 1e-5


def test_closed_form_mp_matches_float_reference():
    exact = free_device_boundary(0.015, 0.02, 0.001, precision="mp", dps=50)
    assert abs(free_device_boundary(0.015, 0.02, 0.001) - exact) <= 1e-14 * exact
    # the small-alpha series: K* = (2b/T)(1 + alpha/6 + O(alpha^2))
    alpha = 0.02 * 0.001 / 0.015
    assert abs(exact / (2 * 0.02 / 0.001) - (1 + alpha / 6)) < alpha**2


@pytest.mark.parametrize(
    "params, delay",
    [({"m": 0.015, "b": 0.02, "B": 0, "T": 0.001}, 0), ({"m": 0.15, "b": 0.2, "B": 0.01, "T": 0.004}, 2)],
)
def test_float_boundary_matches_50_digit_boundary(params, delay):
    fam = SceneFamily("single-user", params, delay=delay)
    bnd = find_boundary(fam, "K", rtol=1e-12)
    ref, width = refine_boundary_mp(fam, "K", (bnd.value * (1 - 1e-7), bnd.value * (1 + 1e-7)),
                                    dps=50, tol=mpmath.mpf(10) ** -35)
    assert width < 1e-34
    assert abs(bnd.value - float(ref)) <= 1e-11 * float(ref)


def test_free_device_has_the_integrator_at_z_equal_1():
    at_zero = closed_loop_matrix(SingleUser(m=0.015, b=0.02, T=0.001, K=0), deflate=False)
    assert np.max(abs(np.linalg.eigvals(at_zero))) == pytest.approx(1, abs=1e-13)
    # K > 0 pulls it inside: lambda ~ 1 - K T / b
    mat = closed_loop_matrix(SingleUser(m=0.015, b=0.02, T=0.001, K=1e-3), deflate=False)
    assert 1 - np.max(abs(np.linalg.eigvals(mat))) == pytest.approx(1e-3 * 0.001 / 0.02, rel=0.1)


def test_teleoperator_free_free_is_half_the_single_device_boundary():
    """FF with equal robots: the differential mode is a device (m/2, b/2) on C(z)."""
    fam = SceneFamily("teleoperator", {"m": 0.015, "b": 0.01822, "B": 0, "T": 0.007})
    bnd = find_boundary(fam, "K", rtol=1e-12)
    assert bnd.value == pytest.approx(free_device_boundary(0.015, 0.01822, 0.007) / 2, rel=1e-9)
    full = np.linalg.eigvals(closed_loop_matrix(fam.scene(K=1.0), deflate=False))
    assert np.min(abs(full - 1)) < 1e-12  # the rigid translation, removed before the verdict
    assert spectral_radius(fam.scene(K=1.0)) < 1


def test_dual_user_free_devices_decouple_into_common_and_differential_modes():
    """x1 + x2 sees K/2, x1 - x2 sees K/2 + 2 K/2: the boundary is 2/3 of a device's."""
    fam = SceneFamily("multi-user", {"m": 0.015, "b": 0.01822, "B": 0, "T": 0.004}, users=2)
    bnd = find_boundary(fam, "K", rtol=1e-12)
    assert bnd.value == pytest.approx(2 / 3 * free_device_boundary(0.015, 0.01822, 0.004), rel=1e-9)


def test_multi_user_with_one_user_is_the_single_user_scene():
    one = MultiUser.uniform(1, m=0.015, b=0.02, T=0.002, K=20, B=0.004, delay=3)
    single = SingleUser(m=0.015, b=0.02, T=0.002, K=10, B=0.002, delay=3)
    assert spectral_radius(one) == pytest.approx(spectral_radius(single), abs=1e-14)


def test_teleoperator_coupling_is_restoring():
    """Released with the master ahead, the slave follows: e = x_m - x_s decays."""
    from hapticproof.analysis.simulate import simulate

    traj = simulate(Teleoperator.symmetric(m=0.015, b=0.02, T=0.001, K=5), 3000,
                    initial={"position:0": 0.01})
    e = traj.positions[:, 0] - traj.positions[:, 1]
    assert abs(e[-1]) < 0.2 * abs(e[0])  # differential mode decays like exp(-b t / 2m)
    assert traj.positions[-1, 1] > 0.004  # the slave moved towards the master


def test_general_environment_equals_the_wall():
    wall = DiscreteTF.virtual_wall(K=20, B=0.003, T=0.001)
    a = SingleUser(m=0.015, b=0.02, T=0.001, environment=wall, delay=1)
    b = SingleUser(m=0.015, b=0.02, T=0.001, K=20, B=0.003, delay=1)
    assert spectral_radius(a) == pytest.approx(spectral_radius(b), abs=1e-13)


@pytest.mark.parametrize(
    "build",
    [
        lambda: SingleUser(m=0.015, b=0.02, T=0),
        lambda: SingleUser(m=-1, b=0.02, T=0.001),
        lambda: SingleUser(m=1, b=0.02, T=0.001, delay=2.5),
        lambda: SingleUser(m=1, b=0.02, T=0.001, delay=-1),
        lambda: SingleUser(m=1, b=float("nan"), T=0.001),
        lambda: MultiUser.uniform(0, m=1, b=1, T=0.1, K=1),
        lambda: Teleoperator.symmetric(m=1, b=1, T=0.1, alpha=0),
        lambda: Impedance((1,), (1, 0, 0)),
        lambda: Impedance((1, 0, 0), (1,)),
        lambda: DiscreteTF((1, 0, 0), (1, 0)),
    ],
)
def test_invalid_scenes_raise_scene_error(build):
    with pytest.raises(SceneError):
        build()


@pytest.mark.parametrize(
    "text", ["__import__('os')", "exp(s)", "z_a + q", "s**s", "", "1/(s*s)", "lambda: 1"]
)
def test_impedance_parser_rejects(text):
    with pytest.raises(InputFormatError):
        Impedance.from_expression(text, {"z_a": 1})


def test_impedance_parser_and_shortage_of_passivity():
    z = Impedance.from_expression("-z_a + 1/s", {"z_a": "0.01"})
    assert z == Impedance.active_spring("0.01")
    assert z.shortage_of_passivity() == pytest.approx(0.01)
    assert Impedance.from_expression("(2*s + 3)/(s + 1)").shortage_of_passivity() == 0
    # Re (s - 1)/(s + 1) = (w^2 - 1)/(w^2 + 1) >= -1
    assert Impedance.from_expression("(s - 1)/(s + 1)").shortage_of_passivity() == 1
    assert math.isclose(abs(z(2j) - (-0.01 + 1 / 2j)), 0, abs_tol=1e-15)
