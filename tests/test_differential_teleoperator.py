"""Differential tests of the teleoperator: the exact passivity decision against the energy of the
sampled-data two-port, and the paper's criterion (32) against its numeric oracle.

**Exact decision vs energy** (``test_exact_decision_matches_the_energy_oracle``). Cases are what a
user types (:func:`draw_case`): controllers as text -- PD, filtered PD, PID (integral action of
either sign), resonant and unstable controllers, poles on the circle at ``z = +-1`` and in pairs,
``1 - 1/(z + 1)``, continuous designs ``C(s)`` through ``--discretize`` (forward, backward,
tustin) -- with negative and zero gains, unequal dampers (zero and negative too), scalings
``alpha`` of any sign and random masses, the dampings placed around the exact boundary
``h = sup L``. Each is built through :class:`hapticproof.systems.scene.Scene` exactly as the CLI
builds it and decided by :func:`hapticproof.analysis.teleoperator.passivity`; its certificates
are re-verified by the checker, and a disproof's failing condition is re-checked from the
definition with the test's own arithmetic (``C(1)``, the poles of ``C``, the residues, or
``h - L(c) = h + T Re{C(z)/(z - 1)}`` at the witness, in mpmath). The oracle
(``tests/oracles/energy.py``, no code of the package) simulates the hybrid loop exactly and searches
for an input of negative supplied energy: a ``proved`` case with a certified negative energy is a
failure; a ``disproved`` case the oracle cannot reach is counted ``uncertain`` only when the
finite-horizon energy form (computed here from the impulse response of ``C(z)/(z - 1)``) shows
the violation is beyond its horizon or resolution.

Size knob: ``HAPTICPROOF_TELEOP_EXAMPLES`` (default 12 cases, about 10 s), ``HAPTICPROOF_TELEOP_SEED``;
``HAPTICPROOF_DIFF_COLLECT=cases.jsonl`` records every case instead of failing at the first
disagreement.

**Criterion (32) vs its oracle** (``test_criterion_32_matches_oracle``): random PD, filtered-PD and
stable rational controllers decided by :func:`~hapticproof.analysis.teleoperator.criterion` and by
``tests/oracles/discrete.py`` (``L = Re{T C(z)/(1 - z)}`` minimised numerically), dampings on the
oracle's boundary and ``1e-9`` (relative) above or below it. ``HAPTICPROOF_DIFF_EXAMPLES`` sizes it.
"""

from __future__ import annotations

import json
import math
import os
import random
import re
import subprocess
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

from oracles.discrete import Z, teleoperator_passivity  # noqa: E402
from oracles.energy import teleoperator_energy_oracle  # noqa: E402
from oracles.harness import Tally, examples, expected_decision, timed  # noqa: E402
from certified import assert_certified  # noqa: E402

from hapticproof.analysis.teleoperator import criterion, passivity  # noqa: E402
from hapticproof.core.errors import HapticproofError  # noqa: E402
from hapticproof.systems.scene import Scene  # noqa: E402
from hapticproof.systems.teleoperator import TeleoperatorScene  # noqa: E402

z = Z
R = sp.Rational
SETTINGS = dict(deadline=None, phases=(Phase.explicit, Phase.reuse, Phase.generate),
                suppress_health_check=[HealthCheck.too_slow, HealthCheck.data_too_large, HealthCheck.filter_too_much])
S_VAR = sp.Symbol("s")

N_CASES = int(os.environ.get("HAPTICPROOF_TELEOP_EXAMPLES", "12") or 12)
SEED = int(os.environ.get("HAPTICPROOF_TELEOP_SEED", "20240607") or 20240607)
HORIZON, KICK, LONG = 96, 0.01, 2048
BAND = 2 * KICK                 # the oracle's stated depth resolution (relative)


# ---------------------------------------------------------------------------------------------
# cases as a user types them
# ---------------------------------------------------------------------------------------------


def _num(rng: random.Random, lo: int, hi: int, signed: float = 0.0, zero: float = 0.0) -> str:
    if rng.random() < zero:
        return "0"
    text = f"{rng.randint(11, 99) / 10}e{rng.randint(lo, hi)}"
    return ("-" + text) if rng.random() < signed else text


def _short(x: float) -> str:
    """A 3-digit decimal near ``x`` (as a user would round it)."""
    if x == 0:
        return "0"
    return f"{x:.3g}"


def draw_case(rng: random.Random) -> dict:
    T = rng.choice(["0.001", "0.01", "0.0005", "1/3", "0.05", _num(rng, -4, -1)])
    kind = rng.choice(["pd", "pd", "filtered-pd", "pid", "first", "second", "circle", "circle", "unstable", "design",
                       "design", "zero"])
    params: dict[str, str] = {"T": T}
    discretize = None
    if kind == "pd":
        text = "K + B*(z - 1)/(T*z)"
        params.update(K=_num(rng, -1, 2, signed=0.2, zero=0.05), B=_num(rng, -4, -1, signed=0.2, zero=0.3))
    elif kind == "filtered-pd":
        text = "K + B*(1 - a)*(z - 1)/(T*(z - a))"
        params.update(K=_num(rng, -1, 2, signed=0.15), B=_num(rng, -4, -1, signed=0.15), a=rng.choice(["0", "0.5", "0.9", "-0.5"]))
    elif kind == "pid":
        text = "K_p + K_i*T*z/(z - 1) + K_d*(z - 1)/(T*z)"
        params.update(K_p=_num(rng, -1, 1, signed=0.1), K_i=_num(rng, -2, 0, signed=0.5), K_d=_num(rng, -4, -2))
    elif kind == "first":
        text = "K*(z - q)/(z - p)"
        params.update(K=_num(rng, -1, 1, signed=0.2), q=str(rng.randint(-15, 15) / 10), p=str(rng.randint(-9, 9) / 10))
    elif kind == "second":
        text = "K*(z - q)/(z**2 + a1*z + a0)"
        r, th = rng.uniform(0, 0.95), rng.uniform(0, math.pi)
        params.update(K=_num(rng, -1, 1, signed=0.2), q=str(rng.randint(-9, 9) / 10), a1=_short(-2 * r * math.cos(th)),
                      a0=_short(r * r))
    elif kind == "circle":
        text = rng.choice(["K/(z + 1)", "K*z/(z + 1)", "1 - 1/(z + 1)", "K*(z - 1)/(z**2 + 1)", "K*(1 - z)/(z**2 + 1)",
                           "K*(z**2 - 1)/(z**2 - 2*c0*z + 1)", "K*(z - 1)/(z**2 - 2*c0*z + 1)", "K/(z - 1)", "K*z/(z + 1)**2"])
        params.update(K=_num(rng, -1, 1, signed=0.3), c0=rng.choice(["0", "0.5", "-0.5", "0.8"]))
    elif kind == "unstable":
        text = rng.choice(["K/(z - p)", "K*(z - 0.5)/(z - p)", "K + B*(z - 1)/(T*(z - p))"])
        params.update(K=_num(rng, -1, 1), B=_num(rng, -3, -1), p=rng.choice(["1.5", "-1.2", "2", "1.05"]))
    elif kind == "design":
        discretize = rng.choice(["backward", "tustin", "forward"])
        text = rng.choice(["K_p + K_d*s/(tau*s + 1)", "K_p + K_i/s", "K/(tau*s + 1)", "K*s/(s**2 + w**2)", "K_p + K_d*s",
                           "K_p + K_d*s/(tau*s + 1) + K_i/s"])
        params.update(K_p=_num(rng, -1, 1, signed=0.15), K_d=_num(rng, -4, -2), tau=rng.choice(["0.005", "0.02", "0.1"]),
                      K_i=_num(rng, -2, 0, signed=0.4), K=_num(rng, -1, 1, signed=0.2), w=rng.choice(["1", "10", "100"]))
    else:
        text = "0"
    names = set(re.findall(r"[A-Za-z_][A-Za-z0-9_]*", text)) | {"T"}
    params = {k: v for k, v in params.items() if k in names}
    alpha = rng.choice(["1", "1", "2", "1/3", "-1", "0", _short(rng.uniform(-3, 3))])
    masses = {"m_m": _short(10 ** rng.uniform(-3, 0)), "m_s": _short(10 ** rng.uniform(-3, 0))}
    return {"kind": kind, "controller": text, "discretize": discretize, "params": params, "alpha": alpha, "masses": masses}


# ---------------------------------------------------------------------------------------------
# the test's own reading of the controller (sympy as a computer-algebra system, no package code)
# ---------------------------------------------------------------------------------------------


def _values(params: dict) -> dict[sp.Symbol, sp.Rational]:
    out = {}
    for name, text in params.items():
        q = Fraction(text)
        out[sp.Symbol(name)] = sp.Rational(q.numerator, q.denominator)
    return out


def controller_z(case: dict) -> sp.Expr:
    """``C(z)`` from the typed text: ``s`` replaced by the discretisation's map when designed in
    continuous time (forward ``(z-1)/T``, backward ``(z-1)/(Tz)``, Tustin ``2(z-1)/(T(z+1))``)."""
    values = _values(case["params"])
    names = {str(k): k for k in values} | {"z": z, "s": S_VAR}
    expr = sp.sympify(case["controller"], locals=names, rational=True)
    T = values[sp.Symbol("T")]
    if case["discretize"]:
        image = {"forward": (z - 1) / T, "backward": (z - 1) / (T * z), "tustin": 2 * (z - 1) / (T * (z + 1))}[case["discretize"]]
        expr = expr.subs(S_VAR, image)
    return sp.cancel(sp.together(expr.subs(values)))


def coefficients(C: sp.Expr) -> tuple[list[Fraction], list[Fraction]]:
    num, den = sp.fraction(sp.cancel(C))
    as_list = lambda p: [Fraction(int(sp.Rational(c).p), int(sp.Rational(c).q)) for c in sp.Poly(p, z).all_coeffs()]  # noqa: E731
    return as_list(num), as_list(den)


def leak_sup(num: list[Fraction], den: list[Fraction], T: Fraction) -> float:
    """``max L(c)``, ``L = -T Re{C(z)/(z - 1)}`` on a grid (floats: only to place the dampings)."""
    th = np.linspace(1e-3, math.pi, 3000)
    zz = np.exp(1j * th)
    C = np.polyval([float(c) for c in num], zz) / np.polyval([float(c) for c in den], zz)
    vals = -float(T) * np.real(C / (zz - 1))
    vals = vals[np.isfinite(vals)]
    return float(vals.max()) if vals.size else 0.0


def place_dampings(rng: random.Random, case: dict, num, den) -> None:
    """``b_m, b_s`` around the boundary ``h = sup L`` with a random split (sometimes a zero or a
    negative damping)."""
    T = Fraction(case["params"]["T"])
    lmax = leak_sup(num, den, T)
    scale = abs(lmax) if lmax != 0 else 0.01
    h = scale * 10 ** rng.uniform(-0.4, 0.4)
    ratio = 10 ** rng.uniform(-1.5, 1.5)               # b_m / b_s
    a2 = float(Fraction(case["alpha"])) ** 2
    b_s = h * (ratio + a2) / ratio if a2 else h
    b_m = ratio * b_s
    case["params"]["b_m"], case["params"]["b_s"] = _short(b_m), _short(b_s)
    # masses do not enter the verdict; keep the oracle's period map well conditioned (b T/m ~ 0.03..10)
    mass = float(T) * max(h, 1e-9) * 10 ** rng.uniform(-1, 1.5)
    case["masses"] = {"m_m": _short(mass), "m_s": _short(mass * 10 ** rng.uniform(-1, 1))}
    roll = rng.random()
    if roll < 0.04:
        case["params"]["b_m"] = "0"
    elif roll < 0.07:
        case["params"]["b_s"] = "-" + case["params"]["b_s"]


# ---------------------------------------------------------------------------------------------
# disproofs re-checked from the definition
# ---------------------------------------------------------------------------------------------


def _mp(q: Fraction) -> mpmath.mpf:
    return mpmath.mpf(q.numerator) / q.denominator


def recheck_disproof(outcome, num, den, T: Fraction, b_m: Fraction, b_s: Fraction, alpha: Fraction) -> str:
    """The first failing condition, recomputed from its definition with the test's arithmetic."""
    cond = next(c for c in outcome.evidence.facts["conditions"] if c.decision.value == "disproved")
    key = cond.name.split(")")[0][1:]
    witness = cond.outcome.witness or {}
    with mpmath.workdps(60):
        P = [_mp(c) for c in num]
        Q = [_mp(c) for c in den]
        roots = mpmath.polyroots(Q, maxsteps=200, extraprec=200) if len(Q) > 1 else []
        if key == "D":
            assert b_m < 0 or b_s < 0
        elif key == "P1":
            assert any(abs(r) > 1 + mpmath.mpf(10) ** -30 for r in roots), roots
        elif key == "P2":
            assert mpmath.polyval(Q, 1) == 0
        elif key == "P3":
            assert mpmath.polyval(Q, 1) != 0 and mpmath.polyval(P, 1) / mpmath.polyval(Q, 1) < 0
        elif key == "P4":
            on = [r for r in roots if abs(abs(r) - 1) < mpmath.mpf(10) ** -25 and abs(r - 1) > mpmath.mpf(10) ** -25]
            assert on, roots
            dQ = [c * (len(Q) - 1 - i) for i, c in enumerate(Q[:-1])]
            bad = False
            for r in on:
                mult = sum(1 for t in on if abs(t - r) < mpmath.mpf(10) ** -20)
                d = mpmath.polyval(dQ, r)
                rho = mpmath.polyval(P, r) / d / (r * (r - 1)) if abs(d) > mpmath.mpf(10) ** -25 else None
                bad |= mult > 1 or rho is None or mpmath.re(rho) <= 0 or abs(mpmath.im(rho)) > mpmath.mpf(10) ** -20 * abs(rho)
            assert bad
        elif key == "P5":
            c = Fraction(str(witness["c"]))
            zz = mpmath.mpc(_mp(c), mpmath.sqrt(1 - _mp(c) ** 2))
            den_h = _mp(b_m) + _mp(alpha) ** 2 * _mp(b_s)
            h = _mp(b_s) if den_h == 0 else _mp(b_m) * _mp(b_s) / den_h
            value = h + _mp(T) * mpmath.re(mpmath.polyval(P, zz) / mpmath.polyval(Q, zz) / (zz - 1)) if c != 1 else None
            if value is not None:
                assert value < 0, value
        else:                                                    # pragma: no cover
            raise AssertionError(f"unknown condition {cond.name}")
    return key


def energy_form_depth(num, den, T: Fraction, b_m: Fraction, b_s: Fraction, alpha: Fraction, N: int) -> float:
    """Least eigenvalue (relative) of the ``N``-period energy form ``(h/T) I + sym(Toeplitz(g))``,
    ``g`` the impulse response of ``C(z)/(z - 1)`` (numpy): how deep a violation is that
    ``N`` periods can show (used only to tell an unreachable violation from a missed one)."""
    if b_m < 0 or b_s < 0:
        return -1.0
    den_h = b_m + alpha * alpha * b_s
    h = float(b_s if den_h == 0 else b_m * b_s / den_h)
    d = np.convolve([float(c) for c in den], [1.0, -1.0])
    pc = [float(c) for c in num]
    numc = [0.0] * (len(d) - len(pc)) + pc
    g = np.zeros(N)
    for k in range(N):
        acc = numc[k] if k < len(numc) else 0.0
        for j in range(1, min(k, len(d) - 1) + 1):
            acc -= d[j] * g[k - j]
        g[k] = acc / d[0]
    idx = np.subtract.outer(np.arange(N), np.arange(N))
    L = np.where(idx >= 0, g[np.clip(idx, 0, N - 1)], 0.0)
    S = h / float(T) * np.eye(N) + (L + L.T) / 2
    scale = float(np.abs(S).max()) or 1.0
    return float(np.linalg.eigvalsh(S).min()) / scale


# ---------------------------------------------------------------------------------------------
# the families
# ---------------------------------------------------------------------------------------------


def test_exact_decision_matches_the_energy_oracle():
    rng = random.Random(SEED)
    stats = {"cases": 0, "agree": 0, "uncertain": 0, "refused": 0, "rechecked": {}}
    collect = os.environ.get("HAPTICPROOF_DIFF_COLLECT", "").strip()
    failures = []
    while stats["cases"] < N_CASES:
        case = draw_case(rng)
        try:
            C = controller_z(case)
        except (ZeroDivisionError, ValueError, TypeError):
            continue
        num, den = coefficients(C)
        if len(num) > len(den):                  # improper: the scene must refuse it in one line
            with pytest.raises(HapticproofError, match="improper"):
                Scene("teleoperator", controller=case["controller"], discretize=case["discretize"],
                      params={**case["params"], "b_m": "1", "b_s": "1", "alpha": case["alpha"]}).build()
            stats["refused"] += 1
            continue
        place_dampings(rng, case, num, den)
        p = case["params"]
        T, b_m, b_s, alpha = (Fraction(v) for v in (p["T"], p["b_m"], p["b_s"], case["alpha"]))
        scene = Scene("teleoperator", controller=case["controller"], discretize=case["discretize"],
                      params={**p, "alpha": case["alpha"]}).build()
        outcome = passivity(scene)
        decision = outcome.decision.value
        stats["cases"] += 1
        row = {"case": case, "toolkit": decision, "reason": outcome.reason}
        problem = None
        if decision not in ("proved", "disproved"):
            problem = f"a numeric scene must be decided, got {decision}"
        else:
            assert_certified(outcome, json.dumps(case))
        if problem is None and decision == "disproved":
            key = recheck_disproof(outcome, num, den, T, b_m, b_s, alpha)
            stats["rechecked"][key] = stats["rechecked"].get(key, 0) + 1
        oracle = teleoperator_energy_oracle(num, den, T, b_m, b_s, alpha, Fraction(case["masses"]["m_m"]),
                                            Fraction(case["masses"]["m_s"]), horizon=HORIZON, kick=KICK, long_horizon=LONG)
        row.update(oracle=oracle.verdict, stage=oracle.stage, eigen=oracle.eigen)
        if problem is None:
            if decision == "proved" and oracle.verdict == "not passive":
                problem = f"proved, but the oracle certifies a negative energy {oracle.energy}"
            elif decision == "disproved" and oracle.verdict != "not passive":
                depth = energy_form_depth(num, den, T, b_m, b_s, alpha, HORIZON)
                row["form_depth"] = depth
                if depth < -BAND:
                    problem = f"disproved with a violation of relative depth {depth:.3g} within {HORIZON} periods, " \
                              "yet the oracle found no negative energy"
                else:
                    stats["uncertain"] += 1
            else:
                stats["agree"] += 1
        if collect:
            with open(collect, "a", encoding="utf-8") as fh:
                fh.write(json.dumps({"family": "teleoperator-energy", "problem": problem, **row}, default=str) + "\n")
        elif problem:
            failures.append(f"{problem}: {json.dumps(case)}; toolkit: {outcome.reason}")
    print(f"\nteleoperator energy family: {stats}")
    assert not failures, failures
    assert stats["agree"] >= 0.5 * stats["cases"], stats


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


def test_criterion_32_matches_oracle():
    tally = Tally("teleoperator criterion (32)")

    @settings(max_examples=examples(0.5), **SETTINGS)
    @given(case=scenes())
    def run(case):
        oracle, t_oracle, oracle_error = timed(lambda: teleoperator_passivity(b_m=case["b_m"], b_s=case["b_s"], T=case["T"],
                                                                   C=case["C"], alpha=case["alpha"]))
        scene = lambda: TeleoperatorScene(1, 1, case["b_m"], case["b_s"], case["T"], case["C"], case["alpha"])  # noqa: E731
        outcome, t_toolkit, error = timed(lambda: criterion(scene()))
        assert_certified(outcome)
        decision = outcome.decision.value if outcome is not None else None
        call = (f"criterion(TeleoperatorScene(m_m=1, m_s=1, b_m={case['b_m']}, b_s={case['b_s']}, T={case['T']}, "
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
    data = json.loads(out.stdout)
    bound_only = teleoperator_passivity(b_m=b, b_s=b, T=T, C=1 / (z - 3))
    assert expected_decision(bound_only) == "proved" and data["criterion_32"]["decision"] == "proved"
    assert data["decision"]["decision"] == "disproved"
    assert data["conditions"][1]["name"].startswith("(P1)") and data["conditions"][1]["decision"] == "disproved"
