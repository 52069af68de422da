"""The exact transfer-matrix type against SymPy and against direct complex evaluation.

Every property compares exact values: the type's arithmetic against SymPy's ``cancel`` at random
rational points, its values on the unit circle and the imaginary axis against Gaussian-rational
evaluation of the original function at exact points of the boundary.
"""

from __future__ import annotations

from fractions import Fraction

import pytest
import sympy as sp
from hypothesis import given, settings
from hypothesis import strategies as st

from hapticproof.exact.boundaryvalue import C_NAME, X_NAME
from hapticproof.exact.rational import NotRationalError, RationalFunction
from hapticproof.exact.transfer import TransferMatrix

K, B, z, s = sp.symbols("K B z s")
small = st.integers(-4, 4)


@st.composite
def polynomials(draw, var, params=(K,), degree=3):
    terms = []
    for k in range(draw(st.integers(0, degree)) + 1):
        coeff = draw(small)
        for p in params:
            coeff += draw(small) * p
        terms.append(coeff * var**k)
    return sp.Add(*terms)


@st.composite
def rationals(draw, var=z, params=(K,)):
    num = draw(polynomials(var, params))
    den = draw(polynomials(var, params))
    if sp.expand(den) == 0:
        den = var + 2
    return num / den


points = st.fractions(min_value=-5, max_value=5, max_denominator=7)


def _value(expr, values):
    """Exact value of a SymPy expression at rational values (``None`` at a pole)."""
    v = expr.xreplace({sym: sp.Rational(q.numerator, q.denominator) for sym, q in values.items()})
    return None if v.has(sp.zoo, sp.nan, sp.oo) else v


@settings(max_examples=40, deadline=None)
@given(rationals(), rationals(), points, points)
def test_arithmetic_agrees_with_sympy(a, b, kv, zv):
    A, Bm = RationalFunction.from_sympy(a), RationalFunction.from_sympy(b)
    values = {K: kv, z: zv}
    va, vb = _value(a, values), _value(b, values)
    if va is None or vb is None:
        return
    for ours, expected in ((A + Bm, va + vb), (A - Bm, va - vb), (A * Bm, va * vb)):
        got = ours.evaluate({"K": kv, "z": zv})         # a cancelled form: defined wherever both are
        assert sp.Rational(got.numerator, got.denominator) == expected
    if vb != 0:
        got = (A / Bm).evaluate({"K": kv, "z": zv})
        assert sp.Rational(got.numerator, got.denominator) == va / vb


@settings(max_examples=40, deadline=None)
@given(rationals())
def test_round_trip_through_sympy_and_json(a):
    f = RationalFunction.from_sympy(a)
    assert sp.expand(sp.together(f.to_sympy() - a).as_numer_denom()[0]) == 0
    assert RationalFunction.from_json(f.to_json()) == f
    G = TransferMatrix.from_sympy(a, z)
    assert TransferMatrix.from_json(G.to_json()) == G
    assert sp.expand(sp.together(G.to_sympy() - a).as_numer_denom()[0]) == 0


def _circle_point(u: Fraction) -> tuple[Fraction, Fraction]:
    """``z = (1 + j u)/(1 - j u)``: an exact rational point of the unit circle."""
    d = 1 + u * u
    return (1 - u * u) / d, 2 * u / d


@settings(max_examples=40, deadline=None)
@given(rationals(params=()), st.fractions(min_value=0, max_value=20, max_denominator=9))
def test_values_on_the_circle_are_the_functions_values(a, u):
    G = TransferMatrix.from_sympy(a, z)
    c, r = _circle_point(u)
    try:
        re, im = G[0, 0].gaussian("$z", c, r)
    except ZeroDivisionError:
        return
    v = G.on_boundary().entries[0][0]
    assert v.re1.is_zero and v.im0.is_zero                     # real-rational: A(c) + j r B(c)
    try:
        A = v.re0.evaluate({C_NAME: c})
        Bv = v.im1.evaluate({C_NAME: c})
    except ZeroDivisionError:
        return
    assert A == re and Bv * r == im


@settings(max_examples=40, deadline=None)
@given(rationals(var=s, params=()), st.fractions(min_value=0, max_value=20, max_denominator=9))
def test_values_on_the_axis_are_the_functions_values(a, w):
    G = TransferMatrix.from_sympy(a, s)
    try:
        re, im = G[0, 0].gaussian("$s", Fraction(0), w)
    except ZeroDivisionError:
        return
    v = G.on_boundary().entries[0][0]
    try:
        A = v.re0.evaluate({X_NAME: w * w})
        Bv = v.im1.evaluate({X_NAME: w * w})
    except ZeroDivisionError:
        return
    assert A == re and Bv * w == im


def test_hermitian_part_of_a_matrix_is_hermitian_and_exact():
    M = TransferMatrix.from_sympy(sp.Matrix([[K + 1/(z - 1), 1/z], [2*z/(z - sp.Rational(1, 2)), 3]]), z)
    H = M.hermitian_part()
    assert H.shape == (2, 2)
    c, r = _circle_point(Fraction(1, 3))
    m = M.subs({"K": 2})
    vals = m.at_gaussian(c, r)
    h = H.entries[1][0]
    # (G_21 + conj(G_12))/2 at the point
    want_re = (vals[1][0][0] + vals[0][1][0]) / 2
    want_im = (vals[1][0][1] - vals[0][1][1]) / 2
    assert h.re0.evaluate({C_NAME: c}) == want_re
    assert h.im1.evaluate({C_NAME: c}) * r == want_im
    assert H.entries[0][1] == H.entries[1][0].conjugate()


def test_inverse_and_determinant():
    M = TransferMatrix.from_sympy(sp.Matrix([[K + 1/(z - 1), 1/z], [2*z, 3]]), z)
    assert M @ M.inverse() == TransferMatrix.identity(2)
    assert sp.cancel(M.determinant().to_sympy({"$z": z}) - sp.Matrix(M.to_sympy()).det()) == 0
    with pytest.raises(ZeroDivisionError):
        TransferMatrix.from_sympy(sp.Matrix([[z, 1], [z, 1]]), z).inverse()


def test_refusals():
    with pytest.raises(NotRationalError):
        TransferMatrix.from_sympy(sp.exp(-s), s)
    with pytest.raises(NotRationalError):
        TransferMatrix.from_sympy(sp.Float(0.1) * z, z)
    with pytest.raises(ValueError):
        TransferMatrix.from_sympy(z, "w")


def test_a_parameter_named_like_the_boundary_variables_means_nothing_more():
    c, x, r = sp.symbols("c x r")
    G = TransferMatrix.from_sympy(c + x / z + r, z)
    assert G.parameters == {"c", "x", "r"}
    v = G.on_boundary().entries[0][0]
    assert v.re0.subs({C_NAME: 0}).to_sympy() == c + r
