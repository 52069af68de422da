"""Time-domain simulation, exact energies and the time-domain boundary (hapticproof.analysis.simulate)."""

from __future__ import annotations

import math

import numpy as np
import pytest
import scipy.integrate
import scipy.linalg

from hapticproof.analysis.maps import SceneFamily, find_boundary
from hapticproof.systems.impedance import Impedance
from hapticproof.systems.loops import SingleUser, Teleoperator
from hapticproof.analysis.sampled import closed_loop_matrix
from hapticproof.analysis.simulate import Excitation, _augment, _discrete, growth_rate, passivity_observer, simulate, tracking_mse

HAND = Impedance.spring_damper(0.05, 1.0)


def _energy_by_quadrature(scene, excitation, steps, substeps=600):
    """Port energy by dense sampling of the exact intersample solution + Simpson's rule."""
    disc = _discrete(_augment(scene.loop(), excitation))
    aug = disc.aug
    nx, nu = aug.a.shape[0], aug.bu.shape[1]
    abar = np.zeros((nx + nu, nx + nu))
    abar[:nx, :nx], abar[:nx, nx:] = aug.a, aug.bu
    ts = np.linspace(0, disc.T, substeps + 1)
    step = scipy.linalg.expm(abar * ts[1])
    props = [np.eye(nx + nu)]
    for _ in range(substeps):
        props.append(step @ props[-1])
    state = np.zeros(disc.matrix.shape[0])
    state[aug.n_plant + 1] = 1.0
    total = 0.0
    for _ in range(steps):
        zeta0 = disc.lift @ state
        power = []
        for prop in props:
            zeta = prop @ zeta0
            power.append(sum((zeta @ aug.rows[f"force:{p.name}"]) * (zeta @ aug.rows[f"velocity:{p.name}"])
                             for p in aug.loop.ports))
        total += scipy.integrate.simpson(power, x=ts)
        state = disc.matrix @ state
    return total


@pytest.mark.parametrize(
    "scene",
    [
        Teleoperator.symmetric(m=0.015, b=0.01822, T=0.01, K=3, master=HAND, slave=HAND),
        SingleUser(m=0.015, b=0.02, T=0.005, K=4, B=0.001, delay=1,
                   operator=Impedance.from_expression("0.01 + 2/s + 1/(s + 3)")),
    ],
)
def test_van_loan_energy_matches_quadrature(scene):
    ports = len(scene.loop().ports)
    excitation = Excitation((1.0, -0.5)[:ports], 7.0)
    traj = simulate(scene, 4, excitation=excitation)
    reference = _energy_by_quadrature(scene, excitation, 4)
    assert traj.total_energy[-1] == pytest.approx(reference, rel=1e-9)


def test_simulation_samples_are_powers_of_the_closed_loop():
    scene = SingleUser(m=0.015, b=0.02, T=0.002, K=10, delay=3)
    traj = simulate(scene, 50, initial={"position:0": 0.01, "velocity:0": -0.1})
    mat = closed_loop_matrix(scene, deflate=False)
    x0 = np.zeros(mat.shape[0])
    x0[0], x0[1] = 0.01, -0.1
    x50 = np.linalg.matrix_power(mat, 50) @ x0
    assert traj.positions[-1, 0] == pytest.approx(x50[0], rel=1e-12)


def test_passive_termination_absorbs_energy_of_a_stable_passive_loop():
    """A damper termination on a free device released from rest with a push: E(t) >= 0."""
    scene = Teleoperator.symmetric(m=0.015, b=0.01822, T=0.001, K=5, master=HAND, slave=HAND)
    result = passivity_observer(scene, 3000, Excitation((1.0, -1.0), 2.0))
    assert result.passive and result.maximum > 0


@pytest.mark.parametrize("T", [0.002, 0.01])
def test_observer_matches_printed_condition_35_away_from_the_border(T):
    """(35) b > KT is the exact passivity border of the equal-robot teleoperator (its
    differential mode is Colgate's wall with m/2, b/2): the observer agrees 20 % away."""
    k_printed = 0.01822 / T
    ex = Excitation((1.0, -1.0), 2.0)
    make = lambda K: Teleoperator.symmetric(m=0.015, b=0.01822, T=T, K=K, master=HAND, slave=HAND)  # noqa: E731
    assert passivity_observer(make(0.8 * k_printed), 3000, ex).passive
    assert not passivity_observer(make(1.2 * k_printed), 3000, ex).passive


def test_growth_rate_estimates_log_spectral_radius():
    scene = SingleUser(m=0.015, b=0.02, T=0.001, K=39.9)
    rho = np.max(abs(np.linalg.eigvals(closed_loop_matrix(scene))))
    assert growth_rate(scene, method="doubling") == pytest.approx(math.log(rho), abs=1e-13)
    assert growth_rate(scene, steps=200_000, method="steps") == pytest.approx(math.log(rho), abs=2e-5)


@pytest.mark.parametrize(
    "family, at",
    [
        (SceneFamily("single-user", {"m": 0.015, "b": 0.02, "B": 0}), {"T": 0.001}),
        (SceneFamily("single-user", {"m": 0.15, "b": 0.2, "B": 0, "z_a": 0.04}, operator="-z_a + 1/s",
                     delay=10), {"T": 0.004}),
        (SceneFamily("teleoperator", {"m": 0.015, "b": 0.01822, "B": 0}), {"T": 0.015}),
    ],
)
def test_time_domain_boundary_matches_spectral(family, at):
    """Bisection on the sign of the growth over 2**52 samples (exact propagation by
    doubling) reproduces the spectral boundary to 1e-9: the growth resolves log(rho) to
    ~1e-15 and |d rho/d K| K is ~1e-4 to 1e-2 here."""
    spectral = find_boundary(family, "K", at=at, rtol=1e-12)
    timed = find_boundary(family, "K", at=at, rtol=1e-11, method="doubling",
                          search=(spectral.value * 0.9, spectral.value * 1.1), scan=3)
    assert timed.value == pytest.approx(spectral.value, rel=1e-9)


def test_tracking_mse_table1_shape():
    ex = Excitation((1.0, 0.0), 1.0)
    make = lambda K, T: Teleoperator.symmetric(m=0.015, b=0.01822, T=T, K=K)  # noqa: E731
    low, high = (tracking_mse(make(K, 0.007), 1000, ex) for K in (0.4, 2.4))
    assert 0 < high < low < 100
    assert tracking_mse(make(2.4, 0.015), 2000, ex) == math.inf
