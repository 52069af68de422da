"""The definition-level oracles (``tests/oracles/definitions.py``, ``models.py``, ``exactpoly.py``)
checked against hand-derived cases (every expected value is derived in a comment). Nothing here
imports the package under test."""

from __future__ import annotations

import sys
from fractions import Fraction as F
from pathlib import Path

import mpmath
import pytest

sys.path.insert(0, str(Path(__file__).resolve().parent))

from oracles.definitions import (NO, UNCERTAIN, YES, Rat, ReadError, continuous_pr, discrete_pr,  # noqa: E402
                                 discrete_pr_matrix, read, unit_point)
from oracles.exactpoly import real_part_exact, squarefree  # noqa: E402
from oracles.models import discretize, hve_inverse, integrator, shortage_of_passivity, teleoperator_criterion  # noqa: E402

z = Rat.variable()
s = Rat.variable()
T = F(1, 1000)


def mpq(x: F):
    return mpmath.mpf(x.numerator) / x.denominator


def recheck(G: Rat, witness: dict) -> None:
    """A 'no' witness must be valid on its own: |z| > 1 and Re G(z) < 0, exactly."""
    x, y = (F(v) for v in witness["z"])
    assert x * x + y * y > 1
    assert real_part_exact(G.num, G.den, x, y) < 0


# ---------------------------------------------------------------------------------------------
# the regression seed: an improper G^-1 is not positive real
# ---------------------------------------------------------------------------------------------
def test_improper_inverse_has_negative_real_part_at_minus_1e4():
    # G = 1 + z^2/(1000(z - 1)); at z = -10^4: 1 - 10^8/(1000 * 10001) = 1 - 9.9990... = -8.999...
    G = hve_inverse(read("K*z**2", "z", {"K": 1}), "forward", T=T, b=1)
    assert G == 1 + z**2 / (1000 * (z - 1))
    value = real_part_exact(G.num, G.den, F(-10**4), F(0))
    assert value == 1 - F(10**8, 1000 * 10001)
    assert -9 < value < -8.99
    ans = discrete_pr(G)
    assert ans.verdict == NO and ans.witness["kind"] == "infinity"
    recheck(G, ans.witness)


@pytest.mark.parametrize("approximation", ["backward", "tustin"])
def test_forward_differenced_pd_on_backward_or_tustin_device_is_improper(approximation):
    # H = K + B(z-1)/T (forward Euler of K + Bs); X/V = Tz/(z-1) or T(z+1)/(2(z-1)) gives a B z or
    # B(z+1)/2 term: G^-1 ~ B z at infinity, Re(B z) < 0 on the ray arg z = pi
    H = discretize(read("K + B*s", "s", {"K": 2, "B": "0.01"}), "forward", T)
    assert H == 2 + F(1, 100) * (z - 1) / T
    G = hve_inverse(H, approximation, T=T, b=1)
    assert G.excess == 1
    ans = discrete_pr(G)
    assert ans.verdict == NO
    recheck(G, ans.witness)
    # the same design with B = 0 is proper and positive real (Re = b + KT/2 or b)
    assert discrete_pr(hve_inverse(discretize(read("K + B*s", "s", {"K": 2, "B": 0}), "forward", T), approximation,
                                   T=T, b=1)).verdict == YES


def test_nearly_improper_leading_coefficient_1e_minus_12():
    # 1e-12 z^2 + K: still improper; the witness sits far out (|z| ~ 1e12 * 1000)
    G = hve_inverse(read("1e-12*z**2 + K", "z", {"K": 1}), "forward", T=T, b=1)
    ans = discrete_pr(G)
    assert ans.verdict == NO and ans.witness["kind"] == "infinity"
    recheck(G, ans.witness)


# ---------------------------------------------------------------------------------------------
# the virtual wall: Colgate's condition and the other two integrators (HVE (17)-(20))
# ---------------------------------------------------------------------------------------------
@pytest.mark.parametrize("K, B, Tp", [(2, F(1, 100), T), (F(10**9), F(3, 7), F(1, 10**6)), (F(1, 3), F(-1, 5), F(1, 2)),
                                      (F(10**300), F(10**-300), F(10**-300))])
def test_colgate_boundary_forward_wall(K, B, Tp):
    # forward: Re G1 = b - KT/2 - B cos(wT); worst case b >= KT/2 + |B| (c = -1 for B > 0, c = 1 for B < 0)
    H = K + B * (z - 1) / (Tp * z)
    edge = K * Tp / 2 + abs(B)
    eps = edge * F(1, 10**6) + F(1, 10**320)
    above = discrete_pr(hve_inverse(H, "forward", T=Tp, b=edge + eps))
    at = discrete_pr(hve_inverse(H, "forward", T=Tp, b=edge))
    below = discrete_pr(hve_inverse(H, "forward", T=Tp, b=edge - eps))
    assert above.verdict == YES
    assert at.verdict in (YES, UNCERTAIN)            # touching zero
    assert below.verdict == NO
    recheck(hve_inverse(H, "forward", T=Tp, b=edge - eps), below.witness)


def test_backward_and_tustin_walls():
    # backward: G2 = b + KTz/(z-1) + B, Re = b + KT/2 + B, residue KT at z = 1 (HVE (18))
    H = lambda K, B: K + B * (z - 1) / (T * z)  # noqa: E731
    assert discrete_pr(hve_inverse(H(2, F(-1, 100)), "backward", T=T, b=F(9, 1000))).verdict == YES   # 9 + 1 - 10 = 0
    assert discrete_pr(hve_inverse(H(2, F(-1, 100)), "backward", T=T, b=F(8, 1000))).verdict == NO
    neg = hve_inverse(H(-1, 0), "backward", T=T, b=100)                      # residue -T < 0
    ans = discrete_pr(neg)
    assert ans.verdict == NO and ans.witness["kind"] == "pole"
    recheck(neg, ans.witness)
    # Tustin: Re G3 = b + B(1 + c)/2 (HVE (19)); K drops out of the real part
    assert discrete_pr(hve_inverse(H(10**6, F(-1, 10)), "tustin", T=T, b=F(1, 10))).verdict == YES
    assert discrete_pr(hve_inverse(H(10**6, F(-1, 10)), "tustin", T=T, b=F(99, 1000))).verdict == NO


def test_delay_wall_margin_at_low_frequency():
    # forward, delay n, B = 0: Re G -> b - KT/2 - K n T as w -> 0 (HVE (25)), K = 1, T = 1/1000, b = 0.0105:
    # passive for n with 1/2 + n <= 10.5, i.e. n <= 10, not for n = 11
    H = Rat.const(1)
    assert discrete_pr(hve_inverse(H, "forward", T=T, b=F(105, 10000), delay=10)).verdict in (YES, UNCERTAIN)
    assert discrete_pr(hve_inverse(H, "forward", T=T, b=F(106, 10000), delay=10)).verdict == YES
    ans = discrete_pr(hve_inverse(H, "forward", T=T, b=F(105, 10000), delay=11))
    assert ans.verdict == NO


def test_unit_circle_poles():
    assert discrete_pr((z + 1) / (z - 1)).verdict == YES                     # lossless, Res/z0 = 2
    assert discrete_pr(-(z + 1) / (z - 1)).verdict == NO                     # Res/z0 = -2
    double = 1 + 1 / (z - 1) ** 2
    ans = discrete_pr(double)
    assert ans.verdict == NO
    recheck(double, ans.witness)
    # complex pair on the circle: 1/2 - 1/(z^2 + 1) has Res/z0 = (j/2)/j = 1/2 at z0 = j and
    # Re = 1/2 - 1/2 = 0 on the circle (1/(1 + e^{2jt}) = e^{-jt}/(2 cos t)): lossless, PR
    assert discrete_pr(F(1, 2) - 1 / (z**2 + 1)).verdict == YES
    # z/(z^2 + 1): Res = 1/2 at z0 = j, Res/z0 = -j/2 is not real: not PR
    assert discrete_pr(z / (z**2 + 1)).verdict == NO
    # 1/(z^2 + 1): Res/z0 at j is 1/(2j * j) = -1/2 < 0
    assert discrete_pr(2 + 1 / (z**2 + 1)).verdict == NO


def test_poles_outside_and_just_outside():
    for r in (F(2), F(10000001, 10000000), F(-1001, 1000)):
        G = 10 + 1 / (z - r)
        ans = discrete_pr(G)
        assert ans.verdict == NO and ans.witness["kind"] == "pole"
        recheck(G, ans.witness)
    assert discrete_pr(10 + 1 / (z - F(9999999, 10000000))).verdict == YES   # inside, Re >= 10 - 1/(2 * 1e-7)? no:
    # (check the comment above) Re 1/(z - r) on the circle >= -1/(1 + r) = -0.5000...: 10 - 0.5 > 0


def test_dirichlet_kernel_environment():
    # H = K(1 + z^-1 + ... + z^-N)/(N+1), forward: G^-1 = b + K T sum z^-k/((N+1)(z-1)); at w -> 0
    # Re -> b - KT/2 - KT N/2 (the mean delay N/2); with K = 1, T = 1/1000, N = 4: b* >= 0.0025 needed there
    H = sum((z ** -k for k in range(5)), Rat.const(0)) / 5
    assert discrete_pr(hve_inverse(H, "forward", T=T, b=F(24, 10000))).verdict == NO
    ans = discrete_pr(hve_inverse(H, "forward", T=T, b=F(3, 1000)))
    assert ans.verdict == YES


# ---------------------------------------------------------------------------------------------
# continuous positive realness, and its Cayley image
# ---------------------------------------------------------------------------------------------
@pytest.mark.parametrize("Z, want", [
    (s + 1 / s, YES),                     # lossless LC
    ((s + 1) / (s + 2), YES),
    (1 / (s + 1), YES),
    (s / (s**2 + 1), YES),                # axis poles +-j, residues 1/2
    (2 * s + 3, YES),                     # improper by one, positive leading coefficient
    (s**2 + 1, NO),                       # excess 2
    (-s, NO),                             # excess 1, negative coefficient
    (1 / (s - 1), NO),                    # pole in Re s > 0
    (1 / s**2, NO),                       # double pole at 0
    ((s - 1) / (s + 1), NO),              # Re = (w^2 - 1)/(w^2 + 1) < 0 at w = 0
    (1 / (s**2 + s + 1) ** 0 * 0 + 1 / ((s + 1) ** 3), NO),   # Re 1/(jw + 1)^3 < 0 at w = 1
])
def test_continuous_pr(Z, want):
    ans = continuous_pr(Z)
    assert ans.verdict == want
    if want == NO:
        x, y = (F(v) for v in ans.witness["s"])
        assert x > 0 and real_part_exact(Z.num, Z.den, x, y) < 0
    # Cayley: Re s > 0 <-> |z| > 1 with s = (z - 1)/(z + 1): the same answer from the discrete oracle
    assert discrete_pr(Z.compose((z - 1) / (z + 1))).verdict == want


# ---------------------------------------------------------------------------------------------
# matrices
# ---------------------------------------------------------------------------------------------
def test_matrix_uniform_two_users_forward():
    # K_01 = K_02 = K_12 = K/2, B = 0, forward: G^-1 = b I + T/(z-1) [[K, -K/2], [-K/2, K]]; modes
    # lambda = K/2, 3K/2: each b + lambda T/(z-1) PR iff b >= lambda T/2, so b >= 3KT/4
    K = F(20)
    Hm = [[K, -K / 2], [-K / 2, K]]
    I = integrator("forward", T)

    def G(b):
        return [[Hm[i][j] * I + (b if i == j else 0) for j in range(2)] for i in range(2)]
    assert discrete_pr_matrix(G(3 * K * T / 4 + F(1, 10**6))).verdict == YES
    ans = discrete_pr_matrix(G(3 * K * T / 4 - F(1, 10**4)))
    assert ans.verdict == NO and ans.witness["quadratic_form_float"] < 0


def test_matrix_indefinite_constant_and_diagonal():
    assert discrete_pr_matrix([[1 + 0 * z, 3 + 0 * z], [0 * z, 1 + 0 * z]]).verdict == NO   # [[2, 3], [3, 2]]
    # Re((z+1)/(z-1)) + 1 = 1 and Re(2 + 1/z) >= 1 on the circle: G + G^H >= 2 I
    assert discrete_pr_matrix([[(z + 1) / (z - 1) + 1, 0 * z], [0 * z, 2 + 1 / z]]).verdict == YES
    # a lossless entry makes the minimum eigenvalue touch 0: sampling cannot certify that
    assert discrete_pr_matrix([[(z + 1) / (z - 1), 0 * z], [0 * z, 2 + 1 / z]]).verdict == UNCERTAIN


# ---------------------------------------------------------------------------------------------
# discretisations
# ---------------------------------------------------------------------------------------------
def test_discretisations_by_hand():
    Tp = F(1, 10)
    assert discretize(read("K + B*s", "s", {"K": 2, "B": 3}), "backward", Tp) == 2 + 30 * (z - 1) / z
    assert discretize(read("B*s", "s", {"B": 3}), "forward", Tp) == 30 * (z - 1)
    assert discretize(read("K_i/s", "s", {"K_i": 4}), "tustin", Tp) == F(4, 10) * (z + 1) / (2 * (z - 1))
    # ZOH: C = K/s -> (1 - z^-1) Z{K t} = (1 - z^-1) K T z/(z-1)^2 = K T/(z - 1)
    assert discretize(read("K/s", "s", {"K": 4}), "zoh", Tp) == F(4, 10) / (z - 1)
    # ZOH of 1/s^2: (1 - z^-1) T^2 z(z + 1)/(2(z-1)^3) = T^2 (z + 1)/(2 (z-1)^2)
    assert discretize(read("1/s^2", "s"), "zoh", Tp) == Tp**2 * (z + 1) / (2 * (z - 1) ** 2)
    assert discretize(read("1/(s + 1)", "s"), "zoh", Tp) is None            # e^{-T}: transcendental
    # matched: K_i/s -> g (z+1)/(z-1) with g = K_i T/2 (the gain of the 1/s term at z = 1)
    assert discretize(read("K_i/s", "s", {"K_i": 4}), "matched", Tp) == F(2, 10) * (z + 1) / (z - 1)
    assert discretize(read("B*s", "s", {"B": 3}), "matched", Tp) == 30 * (z - 1) / z
    assert discretize(read("K + B*s", "s", {"K": 1, "B": 3}), "matched", Tp) is None





# ---------------------------------------------------------------------------------------------
# teleoperator criterion (32) and the operator's shortage of passivity
# ---------------------------------------------------------------------------------------------
def test_teleoperator_pd_scaled():
    # PD: L(c) = KT/2 - B c, sup = KT/2 + B at c = -1 (B >= 0); alpha = 2: b_m >= 6 sup, b_s >= 3 sup
    K, B = F(2), F(1, 100)
    C = K + B * (z - 1) / (T * z)
    sup = K * T / 2 + B                        # 0.011
    ok = teleoperator_criterion(C, T=T, alpha=2, b_m=6 * sup * F(1001, 1000), b_s=3 * sup * F(1001, 1000))
    assert ok.verdict == YES
    bad = teleoperator_criterion(C, T=T, alpha=2, b_m=6 * sup * F(999, 1000), b_s=1)
    assert bad.verdict == NO and bad.witness["robot"] == "master"
    bad_s = teleoperator_criterion(C, T=T, alpha=2, b_m=1, b_s=3 * sup * F(999, 1000))
    assert bad_s.verdict == NO and bad_s.witness["robot"] == "slave"


def test_teleoperator_integrator_never_passive_and_unstable_controller():
    # C = K_i T/(z - 1): (1 - 1/z) C = K_i T/z, L = T K_i T cos(wT)/(2(1 - cos wT)) -> +oo as w -> 0
    assert teleoperator_criterion(F(5) * T / (z - 1), T=T, alpha=1, b_m=10**6, b_s=10**6).verdict == NO
    assert teleoperator_criterion(1 / (z - 2), T=T, alpha=1, b_m=1, b_s=1).verdict == NO


def test_shortage_of_passivity():
    with mpmath.workdps(60):
        assert abs(shortage_of_passivity(read("-z_a + 1/s", "s", {"z_a": "0.01"}))[0] - mpmath.mpf(1) / 100) < 1e-40
    assert shortage_of_passivity(read("d/(tau*s + 1)", "s", {"d": -2, "tau": 3}))[0] == 2          # Re = d/(1 + tau^2 w^2)
    assert shortage_of_passivity(read("d/(tau*s + 1)", "s", {"d": 2, "tau": 3}))[0] == 0
    # d (s - c)/(s + c): |.| = d on the axis, Re = d (w^2 - c^2)/(w^2 + c^2) -> -d at w = 0
    assert abs(shortage_of_passivity(read("d*(s - c)/(s + c)", "s", {"d": 3, "c": 5}))[0] - 3) < 1e-30


# ---------------------------------------------------------------------------------------------
# the reader and the exact helpers
# ---------------------------------------------------------------------------------------------
def test_reader():
    assert read("2^-1 + s", "s") == F(1, 2) + s
    assert read("K_0*z", "z", {"K_0": "K/2", "K": "1e300"}) == F(10**300, 2) * z
    assert read("-z**2", "z") == -(z**2)                     # unary minus binds looser than **
    with pytest.raises(ReadError):
        read("K*z", "z", {})
    with pytest.raises(ReadError):
        read("sin(z)", "z", {})


def test_unit_points_and_squarefree():
    for th in (0.1, 1.5, 2.0, 3.1, -2.5):
        x, y = unit_point(th)
        with mpmath.workdps(50):
            assert x * x + y * y == 1 and abs(mpq(x) - mpmath.cos(th)) < 1e-30
    factors = squarefree(((z - 1) ** 2 * (z + 2) * (z**2 + 1) ** 3).num)
    assert sorted(k for _, k in factors) == [1, 2, 3]
