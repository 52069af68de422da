"""Exact c- and x-forms against direct complex evaluation at random frequencies."""

import cmath
import math

import mpmath

import pytest
import sympy as sp
from hypothesis import given, settings
from hypothesis import strategies as st

from hapticproof.core.symbols import c, n, s, x, z
from hapticproof.exact.unitcircle import delayed_hermitian_part, hermitian_part, hermitian_part_rational, imaginary_axis_rational, imaginary_part_rational, theta_form, theta_to_cos

ints = st.integers(-9, 9)
polys = st.lists(ints, min_size=1, max_size=4).filter(any)
thetas = st.floats(0.05, math.pi - 0.05)


def rational_in_z(num, den, shift):
    P = sum(a * z**k for k, a in enumerate(num))
    Q = sum(a * z**k for k, a in enumerate(den)) * z**shift
    return P / Q


def direct(F, point):
    return complex(sp.lambdify(z, F, "mpmath")(point))


@settings(max_examples=120, deadline=None)
@given(polys, polys, st.integers(0, 3), thetas)
def test_hermitian_and_imaginary_parts_match_complex_evaluation(num, den, shift, theta):
    F = rational_in_z(num, den, shift)
    point = cmath.exp(1j * theta)
    Q = sum(a * point**k for k, a in enumerate(den))
    if abs(Q) < 1e-3:
        return  # too close to a pole for a float comparison
    value = direct(F, point)
    re = hermitian_part_rational(F)
    im = imaginary_part_rational(F)
    cval = math.cos(theta)
    re_val = float(re.expr().subs(c, cval))
    im_val = float(im.expr().subs(c, cval)) * math.sin(theta)
    scale = 1 + abs(value)
    assert abs(re_val - value.real) < 1e-9 * scale
    assert abs(im_val - value.imag) < 1e-9 * scale


@settings(max_examples=60, deadline=None)
@given(polys, polys, st.integers(0, 20), thetas)
def test_delayed_parts_match(num, den, delay, theta):
    F = rational_in_z(num, den, 0)
    point = cmath.exp(1j * theta)
    if abs(sum(a * point**k for k, a in enumerate(den))) < 1e-3:
        return
    value = direct(F, point) * point ** (-delay)
    re = delayed_hermitian_part(F, delay)
    # the c-form is a high-degree monomial polynomial: evaluate it with 50 digits, not float64
    with mpmath.workdps(50):
        re_val = sp.lambdify(c, re.expr(), "mpmath")(mpmath.cos(theta))
    assert abs(float(re_val) - value.real) < 1e-9 * (1 + abs(value))


def test_symbolic_coefficients():
    K, T, B, b = sp.symbols("K T B b", positive=True)
    F = b + (K + B * (z - 1) / (T * z)) * T / (z - 1)
    assert sp.simplify(hermitian_part(F) - (b - K * T / 2 + B * c)) == 0
    tustin = b + (K + B * (z - 1) / (T * z)) * T / 2 * (z + 1) / (z - 1)
    assert sp.simplify(hermitian_part(tustin) - (b + B * (1 + c) / 2)) == 0


@settings(max_examples=40, deadline=None)
@given(st.integers(0, 12), thetas, st.fractions(-3, 3, max_denominator=7), st.fractions(0, 3, max_denominator=7))
def test_theta_form_agrees_with_concrete_delay(delay, theta, Bv, Kv):
    K, T, B, b = sp.symbols("K T B b", positive=True)
    F = K * T / (z - 1) + B / z
    tf = theta_form(b, F, n)
    vals = {K: sp.Rational(Kv), T: sp.Rational(1, 3), B: sp.Rational(Bv), b: 2}
    concrete = delayed_hermitian_part(F.subs(vals), delay).expr() + 2
    via_theta = tf.at(delay).subs(vals)
    assert sp.simplify(concrete - via_theta) == 0
    t = sp.Symbol("t")
    assert abs(float(tf.expr(t).subs(vals).subs({n: delay, t: theta})) - float(concrete.subs(c, math.cos(theta)))) < 1e-9


def test_theta_to_cos():
    t = sp.Symbol("t")
    assert sp.simplify(theta_to_cos(sp.cos(3 * t) - sp.sin(t) * sp.sin(2 * t), t) - (4 * c**3 - 3 * c - 2 * c * (1 - c**2))) == 0
    with pytest.raises(ValueError):
        theta_to_cos(sp.sin(t), t)


@settings(max_examples=80, deadline=None)
@given(polys, polys, st.floats(0.01, 20))
def test_imaginary_axis_forms(num, den, w):
    Z = sum(a * s**k for k, a in enumerate(num)) / sum(a * s**k for k, a in enumerate(den))
    Q = sum(a * (1j * w) ** k for k, a in enumerate(den))
    if abs(Q) < 1e-3:
        return
    value = complex(sp.lambdify(s, Z)(1j * w))
    re, im = imaginary_axis_rational(Z)
    assert abs(float(re.expr().subs(x, w * w)) - value.real) < 1e-9 * (1 + abs(value))
    assert abs(float(im.expr().subs(x, w * w)) * w - value.imag) < 1e-9 * (1 + abs(value))


def test_long_delay_is_exact_and_numeric():
    F = sp.Rational(1, 3) / (z - 1) + sp.Rational(1, 7) / z
    re = delayed_hermitian_part(F, 300)
    assert re.is_numeric and re.num.degree() <= 302
    theta = 0.3
    value = direct(F, cmath.exp(1j * theta)) * cmath.exp(-300j * theta)
    assert abs(float(re.expr().subs(c, sp.Rational(math.cos(theta)))) - value.real) < 1e-6
