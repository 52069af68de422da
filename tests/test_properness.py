"""Properness in the decision kernel (:mod:`hapticproof.exact.infinity`), from every entry point.

A discrete positive-real function is analytic in ``|z| > 1`` *including* ``z = oo``; a continuous
one may have at ``s = oo`` only a simple pole with a positive semidefinite residue. Issue 18: an
improper ``G^-1`` (a non-causal model) was "proved" positive real because only the finite poles
were checked. Each test below states the exact value it expects (derived in the comments) and
re-verifies the certificates with the independent checker.
"""

from __future__ import annotations

import contextlib
import io
import json
import sys
from fractions import Fraction as F
from pathlib import Path

import flint
import pytest
import sympy as sp

sys.path.insert(0, str(Path(__file__).resolve().parent))

from certified import assert_certified  # noqa: E402

from hapticproof.analysis.design import delay_margin  # noqa: E402
from hapticproof.analysis.passiverange import passive_range  # noqa: E402
from hapticproof.analysis.fastpath import NumericScene, decide  # noqa: E402
from hapticproof.analysis.nport import positive_real as nport_positive_real  # noqa: E402
from hapticproof.analysis.positivereal import conditions, positive_real  # noqa: E402
from hapticproof.audit.paperfile import loads  # noqa: E402
from hapticproof.audit.runner import audit_paper  # noqa: E402
from hapticproof.core.symbols import s  # noqa: E402
from hapticproof.exact.checker import check_certificate  # noqa: E402
from hapticproof.exact.infinity import decide_infinity  # noqa: E402
from hapticproof.systems.scene import Scene  # noqa: E402

Z = flint.fmpq_poly([0, 1])


def run(*args: str) -> tuple[int, str, str]:
    """``hapticproof args`` in process: (exit code, stdout, stderr)."""
    from hapticproof.cli import main

    out, err = io.StringIO(), io.StringIO()
    try:
        with contextlib.redirect_stdout(out), contextlib.redirect_stderr(err):
            code = main(list(args))
    except SystemExit as exc:
        code = exc.code
    return code, out.getvalue(), err.getvalue()


def cli(*args: str) -> dict:
    code, out, err = run(*args, "--format", "json")
    assert code == 0, err
    return json.loads(out)


# ---------------------------------------------------------------------------------------------
# the kernel
# ---------------------------------------------------------------------------------------------


def test_improper_witness_is_exact_and_checked():
    # G^-1 = 1 + z^2/(1000(z - 1)): at z = -10^4, 1 - 10^8/(1000 * 10001) = -89999/10001 (about -9)
    out = decide_infinity((1000 * (Z - 1) + Z * Z, 1000 * (Z - 1)), "disk", "G^-1")
    assert out.decision.value == "disproved" and out.witness["z"] == ["-10000", "0"]
    assert out.evidence.facts["value"] == sp.Rational(-89999, 10001)
    cert = out.evidence.facts["certificate"].to_json()
    assert check_certificate(cert).ok and check_certificate(cert).verified
    # a tampered certificate is rejected: a witness inside the disk, a wrong value, a wrong order
    assert not check_certificate({**cert, "witness": ["-1/2", "0"]}).ok
    assert not check_certificate({**cert, "re_value": "1"}).ok
    assert not check_certificate({**cert, "order": 0, "holds": True}).ok


@pytest.mark.parametrize("num, den, domain, decision", [
    (Z + 1, Z - 1, "disk", "proved"),                  # (z + 1)/(z - 1): proper, lossless
    (Z * Z * Z, Z + 2, "disk", "disproved"),           # z^3/(z + 2) ~ z^2
    (-Z * Z, Z + 1, "disk", "disproved"),              # ~ -z: negative on the positive real axis
    (3 * Z * Z + 1, Z + 2, "halfplane", "proved"),     # 3 s^2/(s + 2) ~ 3 s: a mass, allowed
    (-Z * Z, Z + 1, "halfplane", "disproved"),         # ~ -s: negative residue at s = oo
    (Z ** 3 + 1, flint.fmpq_poly([1]), "halfplane", "disproved"),   # s^3: order 3
])
def test_decisions_at_infinity(num, den, domain, decision):
    out = decide_infinity((num, den), domain)
    assert out.decision.value == decision
    assert check_certificate(out.evidence.facts["certificate"].to_json()).ok


def test_matrix_at_infinity():
    one, zero = flint.fmpq_poly([1]), flint.fmpq_poly([])
    # a gyrator s [[0, 1], [-1, 0]]: the residue at s = oo is not Hermitian; v = (1, j) gives
    # v^H Z v = 2 j s, whose real part is negative for Im s > 0
    out = decide_infinity([[(zero, one), (Z, one)], [(-Z, one), (zero, one)]], "halfplane")
    assert out.decision.value == "disproved" and out.witness["vector"] == [["1", "0"], ["0", "1"]]
    assert check_certificate(out.evidence.facts["certificate"].to_json()).ok
    # diag(s, s): a Hermitian PSD residue, allowed; [[s, 2s], [2s, s]] has residue eigenvalues 3, -1
    assert decide_infinity([[(Z, one), (zero, one)], [(zero, one), (Z, one)]], "halfplane").decision.value == "proved"
    assert decide_infinity([[(Z, one), (2 * Z, one)], [(2 * Z, one), (Z, one)]], "halfplane").decision.value == "disproved"


# ---------------------------------------------------------------------------------------------
# the reproductions, every entry point
# ---------------------------------------------------------------------------------------------


def test_cli_improper_environment_is_disproved():
    data = cli("derive", "single-user", "--environment", "K*z**2", "--param", "K=1", "--param", "b=1", "--param", "T=0.001")
    assert data["verdict"] == "disproved" and "improper: pole at infinity" in data["reason"]
    assert data["witness"] == {"pole": "infinity", "order": 1, "z": ["-10000", "0"]}


@pytest.mark.parametrize("approximation", ["backward", "tustin"])
def test_forward_differenced_pd_behind_backward_or_tustin(approximation):
    # H = K + B(z - 1)/T; the integrator Tz/(z - 1) or T(z + 1)/(2(z - 1)) leaves B z or B(z + 1)/2
    data = cli("derive", "single-user", "--controller", "K + B*s", "--discretize", "forward", "--approximation",
               approximation, "--param", "K=2", "--param", "B=0.001", "--param", "T=0.001", "--param", "b=0.02")
    assert data["verdict"] == "disproved" and data["witness"]["pole"] == "infinity"
    # the same design through the forward integrator is proper: b + KT/(z - 1) + B
    ok = cli("derive", "single-user", "--controller", "K + B*s", "--discretize", "forward", "--approximation", "forward",
             "--param", "K=2", "--param", "B=0.001", "--param", "T=0.001", "--param", "b=0.02")
    assert ok["verdict"] == "proved"


def test_every_discretisation_on_every_approximation_symbolically():
    # the symbolic route carries the condition at z = oo: B = 0 exactly where the forward
    # difference meets a backward or Tustin integrator, nothing elsewhere
    for method in ("forward", "backward", "tustin"):
        for approximation in ("forward", "backward", "tustin"):
            model = Scene("single-user", controller="K + B*s", discretize=method, approximation=approximation,
                          params={"B": "real"}).build()
            first = conditions(model)[0]
            if method == "forward" and approximation != "forward":
                assert first.decision.value == "symbolic"
                B = next(p for p in model.parameters if p.name == "B")
                assert first.outcome.evidence.facts["condition"] == sp.Eq(B, 0)
            else:
                assert first.decision.value == "proved"


def test_symbolic_delay_makes_it_proper():
    # z^-n K z^2 T/(z - 1): proper iff n >= 1
    model = Scene("single-user", environment="K*z**2", delay="n").build()
    cond = conditions(model)[0].outcome.evidence.facts["condition"]
    assert cond == sp.Ge(model.delay, 1)
    numeric = Scene("single-user", environment="K*z**2", params={"K": 1, "b": 1, "T": "0.001"})
    assert positive_real(numeric.replace(delay=0).build()).decision.value == "disproved"
    assert positive_real(numeric.replace(delay=1).build()).evidence.facts["conditions"][0].decision.value == "proved"


def test_ranges_margins_and_the_fast_path():
    # Tustin device, forward damper: G^-1 = b + KT(z + 1)/(2(z - 1)) + B(z + 1)/2 is improper unless B = 0
    scene = Scene("single-user", approximation="tustin", environment="K + B*(z-1)/T", params={"K": 2, "T": "0.05", "b": "0.1"})
    assert passive_range(scene, "B").to_text().startswith("passive range of B (others fixed): B = 0 ")
    # no delay makes K z + B proper: never passive, whatever the bound on Re G^-1 says
    margin = delay_margin(Scene("single-user", approximation="backward", environment="K*z + B",
                                params={"K": 3, "B": 100, "T": "0.0005", "b": "0.00035"}))
    assert margin.margin == -1
    # the numeric fast path: H = z^2 (improper) through the forward integrator
    out = decide(NumericScene(b=1, T=F(1, 1000), H=((0, 0, 1), (1,))))
    assert out.decision.value == "disproved" and out.witness["pole"] == "infinity"
    assert_certified(out)


def test_paper_file_passivity_and_sufficient_conditions_are_not_confirmed():
    text = r'''
[paper]
id = "improper-wall"
title = "A wall with a forward-difference damper"
[symbols]
b = "positive"
K = "positive"
B = "real"
T = "positive"
[scenes.wall]
system = "single-user"
approximation = "backward"
environment = "K + B*(z - 1)/T"
[[equations]]
id = "1"
printed = 'b > -\frac{KT}{2} + |B|'
claim = "passivity-condition"
scene = "wall"
[[equations]]
id = "2"
printed = 'b > K T + |B|'
claim = "sufficient-condition"
scene = "wall"
'''
    results = {r.id: r for r in audit_paper(loads(text, "improper.toml").paper).results}
    # G^-1 = b + KTz/(z - 1) + B z: the exact condition is B = 0 (then Re G^-1 = b + KT/2 > 0);
    # both printed conditions hold at a witness with B != 0, where G^-1 is improper
    assert results["1"].verdict.value == "wrong" and results["2"].verdict.value == "wrong"
    for r in results.values():
        assert r.evidence.facts["recheck"]["decision"] == "disproved"
        assert sp.Rational(r.evidence.witness["B"]) != 0


def test_continuous_nport_pole_at_infinity():
    # a negative mass -s: residue -1 at s = oo, Re Z(10) = -10; s^3 + 1: order 3
    bad = nport_positive_real(sp.Matrix([[-s]]))
    assert bad.decision.value == "disproved" and bad.witness["s"] == ["10", "0"]
    order3 = nport_positive_real(sp.Matrix([[s**3 + 1]]))
    assert order3.decision.value == "disproved" and order3.witness["order"] == 3
    assert nport_positive_real(sp.Matrix([[1 / (s + 1), 0], [0, s]])).decision.value == "proved"
    assert_certified(bad.outcome)
    assert_certified(order3.outcome)


@pytest.mark.parametrize("method", ["forward", "backward", "tustin", "zoh", "matched"])
@pytest.mark.parametrize("approximation", ["forward", "backward", "tustin"])
def test_every_discretisation_on_every_approximation_numerically(method, approximation):
    """A PD designed in s on every --discretize and --approximation, judged by the definition
    (tests/oracles/definitions.py): a verdict agrees with the oracle, a ZOH of the pure derivative is
    refused in one line, a matched map's transcendental coefficients refused with the reason in the
    JSON document (exit 2)."""
    from oracles.definitions import NO, YES, discrete_pr, read
    from oracles.models import discretize as oracle_discretize, hve_inverse

    args = ["derive", "single-user", "--controller", "K + B*s", "--discretize", method, "--approximation", approximation,
            "--param", "K=2", "--param", "B=0.001", "--param", "T=0.001", "--param", "b=0.02", "--format", "json"]
    code, out, err = run(*args)
    if method == "zoh":                              # (1 - z^-1) Z{C(s)/s} needs a proper C(s)
        assert code == 2 and len(err.strip().splitlines()) == 1 and "proper" in err
        return
    if method == "matched":                          # e^{-KT/B}: no exact rational decision
        assert code == 2 and len(err.strip().splitlines()) == 1 and "transcendental" in err
        assert "transcendental" in json.loads(out)["error"]
        return
    assert code == 0, err
    data = json.loads(out)
    params = {"K": "2", "B": "0.001", "T": "0.001", "b": "0.02"}
    H = oracle_discretize(read("K + B*s", "s", params), method, F(1, 1000))
    oracle = discrete_pr(hve_inverse(H, approximation, T=F(1, 1000), b=F(2, 100))).verdict
    assert oracle in (YES, NO) and data["verdict"] == {YES: "proved", NO: "disproved"}[oracle]
