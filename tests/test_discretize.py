"""Continuous designs made discrete: exact results cross-checked against independent
implementations -- sympy.physics.control (forward_diff, backward_diff, bilinear, exact) and
SciPy's cont2discrete (ZOH, floating point, compared with relative tolerances far above
rounding); matched keeps ZOH's poles and the continuous gain at s = 0."""

import numpy as np
import pytest
import scipy.signal
import sympy as sp
from sympy.physics.control import TransferFunction, backward_diff, bilinear, forward_diff

from hapticproof.systems.discretize import discretize, is_rational
from hapticproof.core.errors import SceneError
from hapticproof.core.expr import read_expression
from hapticproof.core.symbols import s, z

R = sp.Rational
DESIGNS = {
    "pd": "K + B*s",
    "pid-filtered": "K + K_i/s + K_d*s/(tau*s + 1)",
    "lead-lag": "K*(s + a)/(s + p)",
}
VALUES = {"K": 3, "B": R(1, 50), "K_i": 7, "K_d": R(1, 20), "tau": R(1, 100), "a": 2, "p": 30}
T = R(1, 100)


def _numeric(text):
    expr = read_expression(text, "s")
    return expr.xreplace({sym: VALUES[sym.name] for sym in expr.free_symbols if sym != s})


def _sympy_control(expr, method):
    num, den = sp.fraction(sp.cancel(sp.together(expr)))
    tf = TransferFunction(num, den, s)
    b, a = {"forward": forward_diff, "backward": backward_diff, "tustin": bilinear}[method](tf, T)
    poly = lambda c: sum(ci * z ** (len(c) - 1 - i) for i, ci in enumerate(c))  # noqa: E731
    return poly(b) / poly(a)              # coefficients of polynomials in z, highest power first


@pytest.mark.parametrize("name", DESIGNS)
@pytest.mark.parametrize("method", ["forward", "backward", "tustin"])
def test_substitutions_equal_sympy_physics_control(name, method):
    expr = _numeric(DESIGNS[name])
    assert sp.cancel(discretize(expr, method, T) - _sympy_control(expr, method)) == 0


def test_symbolic_pd_backward_is_the_papers_controller():
    K, B, Tsym = (sp.Symbol(n, positive=True) for n in "KBT")
    B = sp.Symbol("B", nonnegative=True)
    assert sp.cancel(discretize(K + B * s, "backward", Tsym) - (K + B * (z - 1) / (Tsym * z))) == 0


def _coefficients(expr):
    num, den = sp.fraction(sp.together(expr))          # no cancel: the coefficients hold e^(pT)
    pn, pd = sp.Poly(sp.expand(num), z), sp.Poly(sp.expand(den), z)
    lead = pd.LC()
    return (np.array([complex(sp.N(c / lead, 30)).real for c in pn.all_coeffs()]),
            np.array([complex(sp.N(c / lead, 30)).real for c in pd.all_coeffs()]))


@pytest.mark.parametrize("name", ["pid-filtered", "lead-lag"])
def test_zoh_equals_scipy_cont2discrete(name):
    expr = _numeric(DESIGNS[name])
    num, den = sp.fraction(sp.cancel(sp.together(expr)))
    cn = [float(c) for c in sp.Poly(num, s).all_coeffs()]
    cd = [float(c) for c in sp.Poly(den, s).all_coeffs()]
    bz, az, _ = scipy.signal.cont2discrete((cn, cd), float(T), method="zoh")
    bz, az = np.atleast_1d(np.squeeze(bz)) / az[0], np.asarray(az) / az[0]
    mine_b, mine_a = _coefficients(discretize(expr, "zoh", T))
    mine_b = np.concatenate([np.zeros(len(bz) - len(mine_b)), mine_b])
    assert np.allclose(mine_a, az, rtol=1e-9, atol=1e-12) and np.allclose(mine_b, bz, rtol=1e-9, atol=1e-9)


@pytest.mark.parametrize("name", ["pid-filtered", "lead-lag"])
def test_matched_keeps_the_zoh_poles_and_the_gain_at_s_0(name):
    expr = _numeric(DESIGNS[name])
    matched, zoh = discretize(expr, "matched", T), discretize(expr, "zoh", T)
    _, a_matched = _coefficients(matched)
    _, a_zoh = _coefficients(zoh)
    assert np.allclose(np.sort_complex(np.roots(a_matched)), np.sort_complex(np.roots(a_zoh)), rtol=1e-12)
    # the lowest-order term at s = 0 (z - 1 ~ sT): DC gain, or the integral gain of the PID
    order = -1 if name == "pid-filtered" else 0
    cont = sp.cancel(expr * s ** (-order)).subs(s, 0)
    eps = sp.Rational(1, 10**30)          # z = 1 + eps, evaluated at 60 digits
    disc = sp.N((matched * ((z - 1) / T) ** (-order)).subs(z, 1 + eps), 60)
    assert abs(complex(disc - cont)) < 1e-20 * max(1, abs(float(cont)))


def test_zoh_needs_a_proper_design_and_is_transcendental():
    with pytest.raises(SceneError, match="proper"):
        discretize(_numeric("K + B*s"), "zoh", T)
    assert not is_rational(discretize(_numeric("K*(s + a)/(s + p)"), "zoh", T))
    assert is_rational(discretize(_numeric("K*(s + a)/(s + p)"), "tustin", T))


def test_continuous_design_on_the_command_line(capsys):
    from hapticproof.cli import main

    assert main(["derive", "single-user", "--controller", "K + B*s", "--discretize", "backward", "--param", "K=2",
                 "--param", "B=0.001", "--param", "T=0.001", "--param", "b=0.02"]) == 0
    out = capsys.readouterr().out
    assert "backward: H(z) =" in out and "verdict:         proved" in out
    assert main(["derive", "teleoperator", "--controller", "K_p + K_d*s/(tau*s + 1)", "--discretize", "zoh",
                 "--param", "K_p=1", "--param", "K_d=0.01", "--param", "tau=0.01", "--param", "T=0.001",
                 "--param", "b_m=0.02", "--param", "b_s=0.02"]) == 2     # refused: no exact decision (issue 21)
    assert "transcendental" in capsys.readouterr().err
