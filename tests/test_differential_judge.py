"""Differential tests of the definition-level judge (:mod:`hapticproof.exact.judge`).

The judge must accept what is right and reject what is not, judged by oracles written from the
definitions (``tests/oracles/``, importing nothing from the package):

* **positive realness** -- random rational ``F(z)`` (proper and improper, poles inside, on and
  outside the unit circle) decided by the toolkit's fast path and by the numeric oracle
  :func:`oracles.discrete.discrete_positive_real`. The judge must accept the decision the oracle
  agrees with (and its witness); it must reject the opposite decision: a ``disproved`` of a
  positive real ``F`` always (no violation exists), a ``proved`` of a non-positive-real ``F``
  whenever the violation is structural (improper, a pole outside) or covers more than 1/16 of the
  circle (the oracle measures it on 4096 angles); and it must reject a witness moved to a point
  where ``Re F >= 0``.
* **printed Re G^-1 on the circle** -- trigonometric forms of ``Re G^{-1}(e^{j theta})`` for the
  three approximations and delays (Dirichlet kernels, shifted cosines, products of sines, half
  angles) with random parameters, correct and with a slip. The oracle evaluates the scene's
  ``G^{-1}`` (:func:`oracles.discrete.single_user_inverse`) and the display at the judge's points
  with mpmath; the judge must accept ``equal`` exactly for the correct forms and ``differ`` at a
  point exactly where the oracle sees a difference.

Size knob: ``HAPTICPROOF_DIFF_EXAMPLES`` (default 10) Hypothesis examples per family.
"""

from __future__ import annotations

import math
import sys
from fractions import Fraction
from pathlib import Path

import mpmath
import numpy as np
import pytest
import sympy as sp
from hypothesis import HealthCheck, Phase, given, settings
from hypothesis import strategies as st

sys.path.insert(0, str(Path(__file__).resolve().parent))

from oracles.discrete import Z, discrete_positive_real, single_user_inverse  # noqa: E402
from oracles.harness import examples  # noqa: E402
from oracles.polys import RationalFunction  # noqa: E402
from oracles.result import NO, YES  # noqa: E402

from hapticproof.analysis.fastpath import NumericScene, decide, transfer  # noqa: E402
from hapticproof.core.evidence import to_jsonable  # noqa: E402
from hapticproof.core.exprtree import to_tree  # noqa: E402
from hapticproof.exact.judge import consistent_witness, judge  # noqa: E402
from hapticproof.exact.kernel import transfer_json  # noqa: E402

SETTINGS = dict(deadline=None, phases=(Phase.explicit, Phase.reuse, Phase.generate),
                suppress_health_check=[HealthCheck.too_slow, HealthCheck.data_too_large, HealthCheck.filter_too_much])


# ---------------------------------------------------------------------------------------------
# positive realness: random F(z)
# ---------------------------------------------------------------------------------------------


@st.composite
def rationals(draw, lo: int = -6, hi: int = 6) -> Fraction:
    return Fraction(draw(st.integers(lo, hi)), draw(st.sampled_from((1, 2, 3, 4, 5, 10))))


@st.composite
def transfer_functions(draw) -> tuple[list[Fraction], list[Fraction]]:
    """``F = num/den`` (lowest degree first): a constant plus poles placed inside, on and
    outside the circle, and now and then a term ``z`` or ``z^2`` (improper)."""
    poles = draw(st.lists(st.sampled_from([Fraction(1, 2), Fraction(-1, 2), Fraction(1), Fraction(-1), Fraction(2),
                                           Fraction(0), Fraction(-3, 2), Fraction(9, 10)]), min_size=0, max_size=3, unique=True))
    den = [Fraction(1)]
    for p in poles:
        den = [a - p * b for a, b in zip([Fraction(0)] + den, den + [Fraction(0)])]
    num = [draw(rationals()) for _ in range(len(den))]
    extra = draw(st.sampled_from((0, 0, 0, 1, 2)))
    if extra:
        lift = [Fraction(0)] * extra + den                       # z^extra * den
        num = [a + draw(rationals(1, 3)) * b for a, b in zip(num + [Fraction(0)] * extra, lift)]
    if all(a == 0 for a in num):
        num[0] = Fraction(1)
    return num, den


def _as_scene(num: list[Fraction], den: list[Fraction]) -> NumericScene:
    """``G^{-1} = F`` as a single-user scene: ``b = 0``, ``T = 1``, forward, ``H = F (z - 1)``."""
    shifted = [Fraction(0)] + num
    h_num = [a - b for a, b in zip(shifted, num + [Fraction(0)])]
    return NumericScene(b=0, T=1, H=(tuple(h_num), tuple(den)), approximation="forward")


def _oracle(num: list[Fraction], den: list[Fraction]):
    F = sum(sp.Rational(a.numerator, a.denominator) * Z**k for k, a in enumerate(num)) / \
        sum(sp.Rational(a.numerator, a.denominator) * Z**k for k, a in enumerate(den))
    return discrete_positive_real(F), RationalFunction.from_expr(F, Z)


def _negative_fraction(f: RationalFunction) -> float:
    """Share of 4096 angles where ``Re F < 0`` (double precision, poles skipped): the oracle's
    measure of how wide a violation on the circle is."""
    theta = np.linspace(0, 2 * np.pi, 4096, endpoint=False) + 1e-3
    zz = np.exp(1j * theta)
    num, den = (np.polyval(np.array([float(c) for c in part]), zz) for part in (f.num, f.den))
    with np.errstate(all="ignore"):
        values = (num / den).real
    finite = np.isfinite(values)
    return float(np.mean(values[finite] < -1e-9)) if finite.any() else 0.0


def _object(decision: str, num, den) -> dict:
    return {"judge": "positive-real", "domain": "disk", "decision": decision,
            "transfer": {"variable": "z", "num": [str(a) for a in num], "den": [str(a) for a in den]}}


@settings(max_examples=examples(3.0), **SETTINGS)
@given(transfer_functions())
def test_judge_accepts_right_and_rejects_wrong_positive_realness(data):
    num, den = data
    oracle, f = _oracle(num, den)
    if oracle.verdict not in (YES, NO):
        return
    scene = _as_scene(num, den)
    P, Q = transfer(scene)
    out = decide(scene)
    tj = transfer_json(P, Q)
    right = "proved" if oracle.verdict == YES else "disproved"
    witness = out.witness if out.decision.value == "disproved" else None
    if out.decision.value == right:
        obj = {"judge": "positive-real", "domain": "disk", "decision": right, "transfer": tj}
        if witness:
            obj["witness"] = to_jsonable(witness)
        assert judge(obj).ok, (num, den, judge(obj).reason)
    # the opposite decision: always rejected when F is positive real, and whenever the violation
    # is structural or wide when it is not
    wrong = {"judge": "positive-real", "domain": "disk", "decision": "disproved" if right == "proved" else "proved",
             "transfer": tj}
    structural = f.relative_degree < 0 or any(abs(complex(p)) > 1 + 1e-9 for p, _ in f.poles())
    if right == "proved" or structural or _negative_fraction(f) > 1 / 16:
        assert not judge(wrong).ok, (num, den, right)
    # a witness moved to a point where Re F >= 0 (the oracle's check) is refused
    if right == "disproved" and witness and "z" in witness:
        for t in (Fraction(1, 3), Fraction(2), Fraction(-1, 2), Fraction(7, 3)):
            zz = complex((1 - t * t) / (1 + t * t), 2 * t / (1 + t * t))
            with np.errstate(all="ignore"):
                value = complex(np.polyval([float(c) for c in f.num], zz) / np.polyval([float(c) for c in f.den], zz))
            if np.isfinite(value) and value.real > 1e-6:
                moved = {"judge": "positive-real", "domain": "disk", "decision": "disproved", "transfer": tj,
                         "witness": {"c": str((1 - t * t) / (1 + t * t)),
                                     "z": [str((1 - t * t) / (1 + t * t)), str(2 * t / (1 + t * t))]}}
                assert not judge(moved).ok, (num, den, t)
                break


def test_judge_regressions_of_the_issue():
    """Issue 18, item 1: an improper G^-1 'proved' positive real (a pole at infinity)."""
    # G^-1 = 1 + z^2/(1000 (z - 1)) (environment K z^2, K = 1, b = 1, T = 0.001): -9 at z = -10^4
    obj = _object("proved", [Fraction(-1000), Fraction(1000), Fraction(1)], [Fraction(-1000), Fraction(1000)])
    assert not judge(obj).ok and "improper" in judge(obj).reason
    # a pole outside the circle
    assert "outside" in judge(_object("proved", [Fraction(1)], [Fraction(-2), Fraction(1)])).reason
    # a proper, positive real F: accepted; its disproof refused
    ok = _object("proved", [Fraction(1), Fraction(3)], [Fraction(-1), Fraction(1)])    # (3z + 1)/(z - 1)
    assert judge(ok).ok and not judge(dict(ok, decision="disproved")).ok


# ---------------------------------------------------------------------------------------------
# printed Re G^-1: trigonometric forms against the scene, at the judge's points
# ---------------------------------------------------------------------------------------------

theta, T, K, B, b, n = sp.symbols("theta T K B b n")
w = sp.Symbol("omega")
HALF = sp.Rational(1, 2)
#: ``(approximation, correct form in theta, slipped form)``: Re G^-1 of the wall K + B(z-1)/(Tz).
FORMS = [
    ("forward", b - K*T/2*sp.sin((n + HALF)*theta)/sp.sin(theta/2) + B*sp.cos((n + 1)*theta),
     b - K*T/2*sp.sin((n - HALF)*theta)/sp.sin(theta/2) + B*sp.cos((n + 1)*theta)),
    ("forward", b + B - 2*B*sp.sin((n + 1)*theta/2)**2 - K*T/2*sp.sin((n + HALF)*theta)/sp.sin(theta/2),
     b + B - 2*B*sp.sin((n + 1)*theta/2)**2 - K*T*sp.sin((n + HALF)*theta)/sp.sin(theta/2)),
    ("backward", b + B*sp.cos(n*theta) - K*T/2*sp.sin((n - HALF)*theta)/sp.sin(theta/2),
     b + B*sp.cos(n*theta) - K*T/2*sp.sin((n + HALF)*theta)/sp.sin(theta/2)),
    ("tustin", b + B*sp.cos(theta/2)*sp.cos((n + HALF)*theta) - K*T/2*sp.cot(theta/2)*sp.sin(n*theta),
     b + B*sp.cos(theta/2)*sp.cos((n + HALF)*theta) - K*T/2*sp.tan(theta/2)*sp.sin(n*theta)),
]


def _oracle_re(approximation: str, values: dict, delay: int, zz: complex) -> float:
    F = single_user_inverse(b=values["b"], T=values["T"], H=values["K"] + values["B"] * (Z - 1) / (values["T"] * Z),
                            approximation=approximation, delay=delay)
    with mpmath.workdps(40):
        return float(mpmath.re(sp.lambdify(Z, F, "mpmath")(mpmath.mpc(zz.real, zz.imag))))


@settings(max_examples=examples(2.0), **SETTINGS)
@given(st.integers(0, len(FORMS) - 1), st.booleans(), st.integers(0, 4),
       st.fixed_dictionaries({"b": rationals(1, 9), "K": rationals(1, 9), "B": rationals(-5, 5), "T": rationals(1, 5)}),
       st.sampled_from([Fraction(1, 3), Fraction(1, 2), Fraction(2), Fraction(3, 7), Fraction(5, 2)]))
def test_judge_of_printed_hermitian_parts(k, slipped, delay, values, t):
    approximation, good, bad = FORMS[k]
    form = bad if slipped else good
    values = {name: sp.Rational(v.numerator, v.denominator) for name, v in values.items()}
    display = form.xreplace({n: delay}).xreplace({theta: w * T})
    L = 2
    u = complex((1 - t * t) / (1 + t * t), 2 * t / (1 + t * t))
    zz = u**L
    th = 2 * L * math.atan(float(t))
    symbols = {sp.Symbol(name): v for name, v in values.items()}
    shown = complex(sp.N(display.xreplace(symbols).xreplace({w: sp.Float(th, 30) / values["T"]}), 30))
    differ = abs(shown.real - _oracle_re(approximation, values, delay, zz)) > 1e-9
    F = single_user_inverse(b=values["b"], T=values["T"], H=values["K"] + values["B"] * (Z - 1) / (values["T"] * Z),
                            approximation=approximation, delay=delay)
    f = RationalFunction.from_expr(F, Z)
    lowest = lambda c: [str(v) for v in reversed(c)]  # noqa: E731
    point = {"values": {name: str(v) for name, v in values.items()}, "t": str(t), "L": L,
             "transfer": {"variable": "z", "num": lowest(f.num), "den": lowest(f.den)}}
    obj = {"judge": "circle-identity", "object": "Re G^-1", "display": to_tree(display), "frequency": "omega",
           "period": ["s", "T"], "points": [point]}
    assert judge(dict(obj, claim="equal")).ok == (not differ), (approximation, slipped, delay, values, t)
    assert judge(dict(obj, claim="differ")).ok == differ, (approximation, slipped, delay, values, t)
    if not slipped:
        assert not differ                      # the oracle agrees that the form is exact


def test_displayed_witness_is_held_against_the_judged_point():
    good = FORMS[0][1].xreplace({n: 1}).xreplace({theta: w * T})
    point = {"values": {"b": "1", "K": "1", "B": "1", "T": "1"}, "t": "1/2", "L": 1,
             "transfer": {"variable": "z", "num": ["1"], "den": ["1"]}}
    obj = {"judge": "circle-identity", "claim": "differ", "display": to_tree(good), "frequency": "omega",
           "period": ["s", "T"], "points": [point]}
    # the point's own quantities: c = 3/5, z = 3/5 + 4/5 j, omega T = 2 atan(1/2)
    shown = {"b": "1", "K": "1", "B": "1", "T": "1", "c": "3/5", "z": ["3/5", "4/5"],
             "omega_T": {"exact": "2*atan(1/2)", "approx": str(2 * math.atan(0.5))}}
    assert consistent_witness(shown, obj) == []
    # theta and c set independently (the defect of issue 18 item 4) are refused
    assert consistent_witness(dict(shown, c="1/2"), obj)
    assert consistent_witness(dict(shown, omega_T={"exact": "1", "approx": "1.0"}), obj)
    assert consistent_witness(dict(shown, b="2"), obj)
    assert consistent_witness(dict(shown, z=["1", "0"]), obj)


if __name__ == "__main__":  # pragma: no cover
    sys.exit(pytest.main([__file__, "-q"]))
