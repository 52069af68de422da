"""Numerical stress (small size): extreme parameters, long delays, w near 0, margins at zero.

No path may give a wrong verdict; the toolkit's fast path must escalate to exact arithmetic
when float64 cannot decide. The scaled-up sweep is ``hapticproof bench --tasks stress``.
"""

from fractions import Fraction

import numpy as np
import pytest
import sympy as sp

from hapticproof.bench.accuracy import stress_cases
from hapticproof.systems.models import inverse_transfer
from hapticproof.analysis.numerics import exact_margin, float_decision, float_margin, naive_evaluator, stable_evaluator
from hapticproof.analysis.positivereal import decide_hermitian, hermitian
from hapticproof.systems.singleuser import SingleUserScene
from hapticproof.core.symbols import z

EXTREMES = [c for c in stress_cases("small") if c["T"] in ("1e-7", "1") and c["K"] in ("1e-3", "1e9")
            and c["B"] in ("0", "1e6") and c["n"] in (0, 200)]


@pytest.mark.parametrize("case", EXTREMES, ids=lambda c: f"T{c['T']}-K{c['K']}-B{c['B']}-n{c['n']}-{c['where']}")
def test_fast_path_never_gives_a_wrong_verdict(case):
    scene = SingleUserScene.virtual_wall(K=case["K"], B=case["B"], b=case["b"], T=case["T"], delay=case["n"])
    exact = decide_hermitian(hermitian(scene))
    expected = "disproved" if case["where"] == "below" else "proved"
    assert exact.decision.value == expected  # b* = KT/2 + B (n = 0) or KT/2 + KTn (B = 0), exactly
    fast = float_decision(inverse_transfer(scene), points=512)
    assert fast.decision == exact.decision
    if fast.decision.value == "proved":
        assert "switched to exact" in fast.reason


def test_omega_near_zero_cancellation_is_avoided():
    G = 1 / (z - 1)
    theta = np.array([1e-12, 1e-9, 1e-6])
    assert np.allclose(stable_evaluator(G)(theta).real, -0.5, rtol=0, atol=1e-15)
    assert abs(naive_evaluator(G)(theta)[0].real + 0.5) > 0.4  # the trap: cos(1e-12) - 1 == 0


@pytest.mark.parametrize("delay", [10, 200])
def test_long_delay_margin_is_exact_and_float_close(delay):
    # B = 0: min Re G^-1 = b - KT/2 - KTn, attained as c -> 1 (Dirichlet kernel)
    K, T, b = Fraction(3), Fraction(1, 1000), Fraction(7, 10)
    scene = SingleUserScene.virtual_wall(K=K, B=0, b=b, T=T, delay=delay)
    margin = exact_margin(inverse_transfer(scene))
    expected = b - K * T / 2 - K * T * delay
    assert margin.lo <= sp.Rational(expected) <= margin.hi
    # the minimum is sharp (curvature ~ KT n^3): the grid needs ~ 40 n points to resolve it
    value, _ = float_margin(inverse_transfer(scene), 40 * delay)
    assert value >= float(expected) - 1e-12
    assert value - float(expected) < 1e-3 * float(b)


def test_nearly_singular_hermitian_part():
    # at the exact boundary the minimum is 0: positive real (touches zero); 1e-30 below, not
    boundary = Fraction(2) * Fraction(1, 10**7) / 2 + Fraction(10**6)
    at = SingleUserScene.virtual_wall(K=2, B=10**6, b=boundary, T=Fraction(1, 10**7))
    below = SingleUserScene.virtual_wall(K=2, B=10**6, b=boundary - Fraction(1, 10**30), T=Fraction(1, 10**7))
    assert decide_hermitian(hermitian(at)).decision.value == "proved"
    result = decide_hermitian(hermitian(below))
    assert result.decision.value == "disproved" and hermitian(below)(result.outcome.witness["c"]) < 0


def test_many_users_exact_decision_matches_closed_form():
    from hapticproof.systems.multiuser import MultiUserScene
    from hapticproof.analysis.multiuser import positive_real

    m = 12
    # uniform complete graph: PR iff b >= K0 T/2 + B0 + m (K T/2 + B)
    threshold = Fraction(2, 1000) / 2 + Fraction(1, 1000) + m * (Fraction(1, 1000) / 2 + Fraction(2, 1000))
    for b, expected in ((threshold, "proved"), (threshold - Fraction(1, 10**9), "disproved")):
        scene = MultiUserScene.from_values(b=[b] * m, T="0.001", K0=[2] * m, K=1, B0="0.001", B="0.002")
        assert positive_real(scene).decision.value == expected
