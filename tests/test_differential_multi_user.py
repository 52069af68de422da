"""Differential tests: m-user positive realness, toolkit against an independent oracle.

Random m-user haptic virtual environments (HVE paper, Section 3.2) -- 2 to 4 users, random
coupling graphs (possibly disconnected or empty) with random stiffness and damping weights,
ground couplings, unequal per-user delays 0-5, all three approximations of ``1/s``, active
operators -- are decided by :func:`hapticproof.analysis.multiuser.positive_real` and by the numeric oracle
of ``tests/oracles/discrete.py`` (written from the paper: ``G^-1 = diag(b - z_a) + D(z) H(z)
I(z)``; it imports nothing from the package). The dampings ``b_i - z_ai`` are shifted together so
that the smallest eigenvalue of the Hermitian part sits on the oracle's estimate of the boundary,
``1e-9`` (relative) above or below it.

Size knob: ``HAPTICPROOF_DIFF_EXAMPLES`` (default 10) Hypothesis examples per family (this
family uses half); ``HAPTICPROOF_DIFF_COLLECT=cases.jsonl`` records every case instead of
failing on the first disagreement. ``HYPOTHESIS_PROFILE=explore`` draws fresh examples.
"""

from __future__ import annotations

import itertools
import sys
from fractions import Fraction
from pathlib import Path

import pytest
import sympy as sp
from hypothesis import HealthCheck, Phase, given, settings
from hypothesis import strategies as st

sys.path.insert(0, str(Path(__file__).resolve().parent))

from oracles.discrete import multi_user_positive_real  # noqa: E402
from oracles.harness import Tally, examples, expected_decision, timed  # noqa: E402
from certified import assert_certified  # noqa: E402

from hapticproof.systems.multiuser import MultiUserScene
from hapticproof.analysis.multiuser import positive_real  # noqa: E402

R = sp.Rational
APPROXIMATIONS = ("forward", "backward", "tustin")
# No shrinking: every example costs oracle calls, and the failure message already gives the exact
# inputs; the minimal known-bad cases are the explicit regression tests below.
SETTINGS = dict(deadline=None, phases=(Phase.explicit, Phase.reuse, Phase.generate),
                suppress_health_check=[HealthCheck.too_slow, HealthCheck.data_too_large, HealthCheck.filter_too_much])


@st.composite
def magnitude(draw, lo: int, hi: int, zero: bool = True) -> sp.Rational:
    if zero and draw(st.integers(0, 4)) == 0:
        return R(0)
    return R(draw(st.integers(10, 99)), 10) * R(10) ** draw(st.integers(lo, hi))


@st.composite
def scenes(draw) -> dict:
    m = draw(st.integers(2, 4))
    T = R(draw(st.integers(10, 99)), 10) * R(10) ** draw(st.integers(-7, -1))
    pairs = list(itertools.combinations(range(m), 2))
    edges = [e for e in pairs if draw(st.integers(0, 3)) > 0]
    # stiffness scale ~ 1/T keeps K T of order one (the interesting regime) but varies widely
    kexp = draw(st.integers(-2, 3))
    # the definition needs no sign: a negative ground or coupling (one draw in eight) is decided too
    sign = lambda: draw(st.sampled_from([1, 1, 1, 1, 1, 1, 1, -1]))  # noqa: E731
    K0 = [sign() * draw(magnitude(kexp - 2, kexp + 1)) / T for _ in range(m)]
    B0 = [sign() * draw(magnitude(-4, 0)) for _ in range(m)]
    K = {e: sign() * draw(magnitude(kexp - 2, kexp + 1)) / T for e in edges}
    B = {e: sign() * draw(magnitude(-4, 0)) for e in edges}
    delays = [draw(st.integers(0, 5)) for _ in range(m)]
    approximation = draw(st.sampled_from(APPROXIMATIONS))
    spread = [draw(magnitude(-4, 0)) for _ in range(m)]  # b_i - z_ai before the common shift
    placement = draw(st.sampled_from(["above", "below", "far-above", "far-below", "random", "above", "below", "boundary"]))
    params = dict(T=T, K0=K0, B0=B0, K=K, B=B, delays=delays, approximation=approximation)
    if placement == "random":
        shift = draw(magnitude(-4, 2, zero=False)) * draw(st.sampled_from([1, -1]))
    else:
        try:
            probe = multi_user_positive_real(b=spread, z_a=[0] * m, **params)
            herm = probe.details.get("G + G^H >= 0")
        except Exception:  # noqa: BLE001 - a failing probe only costs the placement
            herm = None
        m0 = herm.margin if herm is not None and herm.margin is not None else 0.0
        m0 = m0 if abs(m0) > (herm.band or 0.0 if herm is not None else 0.0) else 0.0  # noise-level: 0
        offset = {"boundary": 0.0, "above": 1e-9, "below": -1e-9, "far-above": 1e-3, "far-below": -1e-3}[placement]
        value = -m0 / 2 + offset * abs(m0) / 2
        q = Fraction(f"{value:.15g}")
        shift = R(q.numerator, q.denominator)
    d = [v + shift for v in spread]
    active = [draw(st.integers(0, 2)) == 0 for _ in range(m)]
    z_a = [(-di if di < 0 else 0) + (draw(magnitude(-4, 0, zero=False)) if act else 0) for di, act in zip(d, active)]
    b = [di + za for di, za in zip(d, z_a)]
    return {"m": m, "placement": placement, "b": b, "z_a": z_a, "edges": edges, **params}


def _scene(case: dict) -> MultiUserScene:
    return MultiUserScene.from_values(b=case["b"], T=case["T"], K0=case["K0"], B0=case["B0"], K=case["K"] or 0,
                                      B=case["B"] or 0, delays=case["delays"], z_a=case["z_a"], edges=case["edges"],
                                      approximation=case["approximation"])


def _oracle(case: dict):
    return multi_user_positive_real(b=case["b"], T=case["T"], K0=case["K0"], B0=case["B0"], K=case["K"], B=case["B"],
                                    delays=case["delays"], z_a=case["z_a"], approximation=case["approximation"])


def _call(case: dict) -> str:
    keys = ("b", "T", "K0", "B0", "K", "B", "delays", "z_a", "edges", "approximation")
    return "multiuser.positive_real(MultiUserScene.from_values(" + ", ".join(f"{k}={case[k]!r}" for k in keys) + "))"


def test_multi_user_positive_real_matches_oracle():
    tally = Tally("multi-user positive_real")

    @settings(max_examples=examples(0.5), **SETTINGS)
    @given(case=scenes())
    def run(case):
        oracle, t_oracle, oracle_error = timed(_oracle, case)
        outcome, t_toolkit, error = timed(lambda: positive_real(_scene(case)))
        assert_certified(outcome)
        decision = outcome.decision.value if outcome is not None else None
        tally.check(dict(case), decision, oracle, call=_call(case), error=error,
                    seconds={"toolkit": t_toolkit, "oracle": t_oracle}, oracle_error=oracle_error)

    run()
    print(tally)
    tally.assert_few_uncertain()


# ---------------------------------------------------------------------------------------------
# known answers and regressions
# ---------------------------------------------------------------------------------------------


@pytest.mark.parametrize("approximation", APPROXIMATIONS)
def test_uncoupled_users_reduce_to_walls(approximation):
    """Without couplings G^-1 is diagonal: PR iff every user's wall is. Re G_ii = (b_i - z_ai) +
    K_0i T Re(I/T) with Re(I/T) = -1/2 (forward), 1/2 (backward), 0 (Tustin): the boundary is
    exact; at it (PR), 1e-9 above (PR) and 1e-9 below (not PR)."""
    T = R(1, 1000)
    K0 = [R(2000), R(500)]
    kernel = {"forward": R(-1, 2), "backward": R(1, 2), "tustin": R(0)}[approximation]
    for offset, want in ((0, "proved"), (R(1, 10**9), "proved"), (-R(1, 10**9), "disproved")):
        d = [-kernel * K0[0] * T + offset, -kernel * K0[1] * T + R(1, 10)]
        z_a = [-di + 1 if di < 0 else 0 for di in d]
        b = [di + za for di, za in zip(d, z_a)]
        scene = MultiUserScene.from_values(b=b, T=T, K0=K0, z_a=z_a, edges=(), approximation=approximation)
        oracle = multi_user_positive_real(b=b, T=T, K0=K0, z_a=z_a, approximation=approximation)
        assert expected_decision(oracle) in (None, want), oracle.summary()
        assert positive_real(scene).decision.value == want, (offset, b, z_a)
