"""Differential tests: the teleoperator passivity condition, toolkit against an independent oracle.

Random sampled-data position-error-based teleoperators (teleoperator paper) -- PD, filtered-PD
and random stable rational controllers ``C(z)``, negative gains, scalings ``alpha`` -- are decided
by :func:`hapticproof.analysis.teleoperator.passivity` (the per-robot bounds ``b_s >= (alpha + 1) L``,
``b_m >= (alpha + 1) alpha L`` with ``L = T/(2(1 - cos wT)) Re{(1 - e^{-jwT}) C}``, the printed
``b > T/(1 - cos wT) Re{...}`` at ``alpha = 1``) and by the oracle of
``tests/oracles/discrete.py`` (``L = Re{T C(z)/(1 - z)}`` on the circle, minimised numerically).
The dampings are placed on the oracle's boundary and ``1e-9`` (relative) above or below it.

Size knob: ``HAPTICPROOF_DIFF_EXAMPLES`` (default 10) Hypothesis examples per family (this
family uses half); ``HAPTICPROOF_DIFF_COLLECT=cases.jsonl`` records every case instead of
failing on the first disagreement. ``HYPOTHESIS_PROFILE=explore`` draws fresh examples.
"""

from __future__ import annotations

import json
import os
import subprocess
import sys
from fractions import Fraction
from pathlib import Path

import sympy as sp
from hypothesis import HealthCheck, Phase, given, settings
from hypothesis import strategies as st

sys.path.insert(0, str(Path(__file__).resolve().parent))

from oracles.discrete import Z, teleoperator_passivity  # noqa: E402
from oracles.harness import Tally, examples, expected_decision, timed  # noqa: E402
from certified import assert_certified  # noqa: E402

from hapticproof.systems.teleoperator import TeleoperatorScene
from hapticproof.analysis.teleoperator import passivity  # noqa: E402

z = Z
R = sp.Rational
SETTINGS = dict(deadline=None, phases=(Phase.explicit, Phase.reuse, Phase.generate),
                suppress_health_check=[HealthCheck.too_slow, HealthCheck.data_too_large, HealthCheck.filter_too_much])


@st.composite
def magnitude(draw, lo: int, hi: int, signed: bool = False) -> sp.Rational:
    value = R(draw(st.integers(10, 99)), 10) * R(10) ** draw(st.integers(lo, hi))
    return -value if signed and draw(st.integers(0, 4)) == 0 else value


@st.composite
def controllers(draw, T: sp.Rational) -> tuple[str, sp.Expr]:
    kind = draw(st.sampled_from(["pd", "filtered-pd", "rational"]))
    K = draw(magnitude(-1, 4, signed=True))
    B = draw(st.one_of(st.just(R(0)), magnitude(-4, 1, signed=True)))
    if kind == "pd":
        return kind, K + B * (z - 1) / (T * z)
    if kind == "filtered-pd":
        a = R(draw(st.integers(0, 19)), 20)
        return kind, K + B * (1 - a) * (z - 1) / (T * (z - a))
    poles = draw(st.lists(st.integers(-9, 9).map(lambda k: R(k, 10)), min_size=1, max_size=2))
    zeros = draw(st.lists(st.integers(-15, 15).map(lambda k: R(k, 10)), min_size=0, max_size=len(poles)))
    num = sp.Mul(*[(z - q) for q in zeros]) if zeros else sp.Integer(1)
    return kind, K * num / sp.Mul(*[(z - p) for p in poles])


@st.composite
def scenes(draw) -> dict:
    T = R(draw(st.integers(10, 99)), 10) * R(10) ** draw(st.integers(-5, -1))
    kind, C = draw(controllers(T))
    alpha = draw(st.sampled_from([R(1), R(1), R(1, 2), R(2), R(3, 2), R(1, 10)]))
    placement = draw(st.sampled_from(["above", "below", "far-above", "far-below", "random", "boundary"]))
    try:
        probe = teleoperator_passivity(b_m=0, b_s=0, T=T, C=C, alpha=alpha).details
    except Exception:  # noqa: BLE001 - a failing probe only costs the placement
        probe = {}
    dampings = []
    for key in ("b_m >= bound", "b_s >= bound"):
        part = probe.get(key)
        if placement == "random" or part is None or part.margin is None:
            dampings.append(draw(magnitude(-4, 1)))
            continue
        base = -part.margin if abs(part.margin) > (part.band or 0.0) else 0.0
        offset = {"boundary": 0.0, "above": 1e-9, "below": -1e-9, "far-above": 1e-3, "far-below": -1e-3}[placement]
        value = base + offset * abs(base)
        q = Fraction(f"{value:.15g}")
        dampings.append(R(q.numerator, q.denominator) if value > 0 else draw(magnitude(-4, 1)))
    return {"kind": kind, "placement": placement, "T": T, "C": C, "alpha": alpha, "b_m": dampings[0],
            "b_s": dampings[1]}


def test_teleoperator_passivity_matches_oracle():
    tally = Tally("teleoperator passivity")

    @settings(max_examples=examples(0.5), **SETTINGS)
    @given(case=scenes())
    def run(case):
        oracle, t_oracle, oracle_error = timed(lambda: teleoperator_passivity(b_m=case["b_m"], b_s=case["b_s"], T=case["T"],
                                                                   C=case["C"], alpha=case["alpha"]))
        scene = lambda: TeleoperatorScene(1, 1, case["b_m"], case["b_s"], case["T"], case["C"], case["alpha"])  # noqa: E731
        outcome, t_toolkit, error = timed(lambda: passivity(scene()))
        assert_certified(outcome)
        decision = outcome.decision.value if outcome is not None else None
        call = (f"passivity(TeleoperatorScene(m_m=1, m_s=1, b_m={case['b_m']}, b_s={case['b_s']}, T={case['T']}, "
                f"C={sp.sstr(case['C'])}, alpha={case['alpha']}))")
        tally.check(case, decision, oracle, call=call, error=error, seconds={"toolkit": t_toolkit, "oracle": t_oracle},
                    oracle_error=oracle_error)

    run()
    print(tally)
    tally.assert_few_uncertain()


def test_cli_teleoperator_verdict_includes_controller_poles():
    """Issue 10: ``derive teleoperator --controller 'K/(z-3)'`` must not say proved: the
    controller itself is unstable (its bound (32) alone happens to hold)."""
    T, b = R(1, 10), R(1)
    args = [sys.executable, "-m", "hapticproof", "derive", "teleoperator", "--controller", "K/(z-3)",
            "--param", "K=1", "--param", "T=1/10", "--param", "b_m=1", "--param", "b_s=1", "--param", "m_m=1",
            "--param", "m_s=1", "--format", "json"]
    out = subprocess.run(args, capture_output=True, text=True, timeout=600, env={**os.environ})
    assert out.returncode == 0, out.stderr
    decision = json.loads(out.stdout)["decision"]["decision"]
    bound_only = teleoperator_passivity(b_m=b, b_s=b, T=T, C=1 / (z - 3))
    full = teleoperator_passivity(b_m=b, b_s=b, T=T, C=1 / (z - 3), controller_poles=True)
    assert expected_decision(bound_only) == "proved" and expected_decision(full) == "disproved"
    assert decision == "disproved", f"the CLI says {decision!r}; the oracle: {full.summary()}"
