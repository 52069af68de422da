"""Exact virtual-wall stability boundary (hapticproof.analysis.boundary) against independent methods:
the sampled loop's spectral radius (hapticproof.analysis.sampled, matrix exponential, 50 digits), the
free-device formula of hapticproof.analysis.sampled, and the certified eigenvalue enclosure."""

from __future__ import annotations

import mpmath
import pytest
import sympy as sp
from hypothesis import given, settings
from hypothesis import strategies as st

from hapticproof.analysis import boundary as bnd
from hapticproof.core.errors import SceneError
from hapticproof.systems.loops import SingleUser
from hapticproof.analysis.sampled import closed_loop_matrix, free_device_boundary, spectral_radius

R = sp.Rational
CASES = [
    # (m, b, T, B, n): closed form (n = 0), crossings (n >= 1), flip mode, large damping
    (R(15, 1000), R(2, 100), R(1, 1000), 0, 0),
    (R(15, 1000), R(2, 100), R(1, 1000), R(2, 1000), 0),
    (R(15, 1000), R(2, 100), R(2, 1000), R(2, 100), 0),
    (1, 2, R(1, 2), R(3, 2), 0),
    (1, 10, 1, 2, 0),
    (1, 1, R(1, 100), 190, 0),
    (R(15, 1000), R(2, 100), R(1, 1000), R(2, 1000), 2),
    (R(15, 100), R(2, 10), R(1, 1000), 0, 10),
    (1, 1, R(1, 100), 1, 3),
    (1, 10, 1, 0, 1),
    (1, 1, R(1, 100), 60, 1),
]


def _radius(m, b, T, K, B, n) -> float:
    return float(spectral_radius(SingleUser(m=m, b=b, T=T, K=K, B=B, delay=n), "mp", 50))


@pytest.mark.parametrize("m,b,T,B,n", CASES)
def test_critical_stiffness_matches_spectral_radius_to_1e9(m, b, T, B, n):
    cs = bnd.critical_stiffness(m, b, T, B, n)
    assert cs.mode in ("complex", "flip")
    lo, hi = bnd.arb_interval(cs.K)
    assert (hi - lo) < lo * R(1, 10**20)                                    # certified to 20 digits
    K = bnd.arb_midpoint(cs.K)
    eps = R(1, 10**9)
    assert _radius(m, b, T, K * (1 - eps), B, n) < 1 < _radius(m, b, T, K * (1 + eps), B, n)


def test_modes_and_methods():
    assert bnd.critical_stiffness(1, 10, 1).mode == "flip"
    assert bnd.critical_stiffness(1, 1, R(1, 100), 1).mode == "complex"
    assert bnd.critical_stiffness(1, 1, R(1, 100), 1, 2).method == "crossing"
    assert bnd.critical_stiffness(1, 1, R(1, 100), 1, 0).method == "closed-form"


def test_too_much_virtual_damping_destabilises_every_stiffness():
    cs = bnd.critical_stiffness(1, 1, R(1, 100), 300)              # delta = 3 > alpha^2/l_0 ~ 2
    assert cs.mode == "unstable"
    for K in (R(1, 100), 1, 100, 10**4):
        assert _radius(1, 1, R(1, 100), K, 300, 0) > 1
    assert bnd.critical_stiffness(1, 1, R(1, 100), 120, 1).mode == "unstable"


def test_free_device_closed_form_agrees_with_sampled_formula():
    for m, b, T in ((R(15, 1000), R(2, 100), R(1, 1000)), (1, 3, R(1, 2)), (1, 10, 1)):
        cs = bnd.critical_stiffness(m, b, T)
        ref = free_device_boundary(m, b, T, precision="mp", dps=40)
        with mpmath.workdps(50):
            q = bnd.arb_midpoint(cs.K)
            assert abs(mpmath.mpf(q.p) / q.q - ref) < mpmath.mpf(10) ** -30 * ref


def test_closed_form_agrees_with_crossing_analysis():
    for alpha, delta in ((R(1, 100), 0), (R(1, 100), R(1, 100)), (R(1, 2), R(3, 4)), (10, 2)):
        norm = bnd.Normalised(alpha, delta)
        closed, _, mode_a = bnd.closed_form_stiffness(norm, 160)
        with bnd.flint_precision(160):
            crossing, _, mode_b, _ = bnd._crossing_stiffness(norm, 0, 160)
        assert closed.overlaps(crossing) and mode_a == mode_b


@pytest.mark.parametrize("n", [0, 1, 3])
def test_characteristic_polynomial_is_derived_and_has_the_loop_eigenvalues(n):
    assert sp.expand(bnd.derive_characteristic_polynomial(n).as_expr() - bnd.characteristic_polynomial(n).as_expr()) == 0
    m, b, T, K, B = R(15, 1000), R(2, 100), R(1, 1000), 30, R(1, 1000)
    a_, d_, b_ = b * T / m, B * T / m, K * T**2 / m
    poly = bnd.characteristic_polynomial(n, a_, d_, b_, sp.exp(-a_))
    roots = sorted(abs(complex(r)) for r in poly.nroots(n=30))
    with mpmath.workdps(40):
        eig = sorted(float(abs(v)) for v in mpmath.eig(closed_loop_matrix(SingleUser(m=m, b=b, T=T, K=K, B=B, delay=n), "mp", 40),
                                                      left=False, right=False))
    assert len(roots) == len(eig)
    assert all(abs(x - y) < 1e-12 for x, y in zip(roots, eig))


def test_jury_closed_form_reduces_to_free_device_and_is_affine():
    cf = bnd.closed_form_boundary()
    a, p = bnd.ALPHA, bnd.P
    assert sp.simplify(cf.complex_pair.subs(bnd.DELTA, 0) - a**2 * (1 - p) / (1 - p - a * p)) == 0
    # P(1) = alpha beta (1 - p) > 0: only the other Jury conditions bound beta
    assert sp.expand(bnd.characteristic_polynomial(0).eval(1) - a * bnd.BETA * (1 - p)) == 0


def test_certified_spectral_radius_agrees_with_sampled():
    op = bnd.Operator(R(1, 100), R(1, 50), 3)
    for kwargs, operator in (({"K": 30}, None), ({"K": 20, "B": R(1, 1000), "n": 2}, None), ({"K": 25}, op)):
        m, b, T = R(15, 1000), R(2, 100), R(1, 1000)
        rho = bnd.certified_spectral_radius(m, b, T, kwargs["K"], kwargs.get("B", 0), kwargs.get("n", 0), operator)
        ref = spectral_radius(SingleUser(m=m, b=b, T=T, K=kwargs["K"], B=kwargs.get("B", 0), delay=kwargs.get("n", 0),
                                         operator=None if operator is None else operator.impedance()), "mp", 50)
        with mpmath.workdps(50):
            q = bnd.arb_midpoint(rho)
            assert abs(mpmath.mpf(q.p) / q.q - ref) < mpmath.mpf(10) ** -25
        lo, hi = bnd.arb_interval(rho)
        assert hi - lo < R(1, 10**25)


def test_certified_stable_decisions():
    assert bnd.certified_stable(R(15, 1000), R(2, 100), R(1, 1000), 30).decision.value == "proved"
    out = bnd.certified_stable(1, 1, R(1, 100), 398, 1)             # b + B > KT/2 holds, loop unstable
    assert out.decision.value == "disproved" and out.witness["K"] == 398


@settings(max_examples=12, deadline=None)
@given(alpha=st.fractions(R(1, 1000), R(1, 2)), ratio=st.fractions(0, 2), n=st.integers(0, 3))
def test_boundary_property_against_float_spectral_radius(alpha, ratio, n):
    m, T = 1, R(1, 100)
    b = R(alpha.numerator, alpha.denominator) * m / T
    B = b * R(ratio.numerator, ratio.denominator)
    cs = bnd.critical_stiffness(m, b, T, B, n)
    if cs.mode == "unstable":
        assert spectral_radius(SingleUser(m=m, b=b, T=T, K=1, B=B, delay=n)) > 1
        return
    K = bnd.arb_midpoint(cs.K)
    assert spectral_radius(SingleUser(m=m, b=b, T=T, K=K * R(999, 1000), B=B, delay=n)) < 1
    assert spectral_radius(SingleUser(m=m, b=b, T=T, K=K * R(1001, 1000), B=B, delay=n)) > 1


def test_linear_condition_is_the_small_damping_limit():
    for n in (0, 2):
        for ratio in (0, 1):
            b, T = R(1, 1000), R(1, 1000)           # alpha = 1e-6
            cs = bnd.critical_stiffness(1, b, T, b * ratio, n)
            linear = bnd.linear_critical_beta(b * T, b * ratio * T, n) / T**2
            assert abs(cs.value / float(linear) - 1) < 1e-4


def test_errors():
    with pytest.raises(SceneError):
        bnd.critical_stiffness(1, 1, 1, B=-1)
    with pytest.raises(SceneError):
        bnd.critical_stiffness(1, 1, 0)
    with pytest.raises(SceneError):
        bnd.critical_stiffness(1, 1, 1, n=R(1, 2))
    with pytest.raises(SceneError):
        bnd.Operator(-1)
