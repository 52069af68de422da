"""Float, mpmath and exact margins agree; the exact margin is certified."""

import math

import numpy as np
import sympy as sp
from hypothesis import given, settings
from hypothesis import strategies as st

from hapticproof.bench.accuracy import margin_cases
from hapticproof.analysis.numerics import exact_margin, exact_margin_prepared, float_margin, mp_margin
from hapticproof.core.symbols import z


def test_exact_margin_brackets_dense_mpmath_sweep():
    for name, G in margin_cases().items():
        if name == "single-user n=100":
            continue  # covered by test_stress at lower cost
        margin = exact_margin(G, bits=50)
        sweep = mp_margin(G, 400, 30)
        assert margin.lo <= margin.hi
        assert float(margin.hi) <= float(sweep) + 1e-12  # a sweep can only overestimate the minimum
        assert float(sweep) - float(margin.lo) < 1e-3 * max(1, abs(float(sweep)))


@settings(max_examples=25, deadline=None)
@given(st.fractions(0, 2, max_denominator=20), st.fractions(-1, 1, max_denominator=20), st.integers(0, 4))
def test_scalar_exact_margin_matches_float_grid(a, bcoef, delay):
    G = sp.Rational(a) + sp.Rational(bcoef) / z**(delay + 1) + sp.Rational(1, 3) / (z - 1)
    margin = exact_margin(G)
    value, _ = float_margin(G, 20000)
    assert float(margin.lo) <= value + 1e-12
    assert value - float(margin.hi) < 1e-4


def test_prepared_matrix_margin_equals_direct():
    G = margin_cases()["4-user"]
    direct = exact_margin(G, bits=40)
    prepared = exact_margin_prepared(G)(40)
    assert abs(float(direct.mid) - float(prepared.mid)) < 1e-10
    evaluate = sp.lambdify(z, G, "numpy")
    eig = min(np.linalg.eigvalsh((lambda M: (M + M.conj().T) / 2)(np.array(evaluate(np.exp(1j * t)), dtype=complex))).min()
              for t in np.linspace(1e-3, math.pi, 3000))
    assert float(prepared.lo) <= eig + 1e-12


@settings(max_examples=20, deadline=None)
@given(st.lists(st.fractions(-1, 1, max_denominator=12), min_size=6, max_size=6), st.integers(0, 2))
def test_endpoint_shortcut_agrees_with_bisection_and_sweep(values, delay):
    """The endpoint shortcut (worst case at c = +-1) and the bisection give overlapping
    certified intervals, and both bracket a dense numpy eigenvalue sweep."""
    import hapticproof.analysis.numerics as numerics

    a, b, c, d, e, f = (sp.Rational(v) for v in values)
    G = sp.Matrix([[2 + a + b / z ** (delay + 1) + sp.Rational(1, 3) / (z - 1), c / z ** delay],
                   [d / z, 2 + e + f / z ** (delay + 2)]])
    shortcut = exact_margin(G, bits=40)
    original = numerics._endpoint_margin
    numerics._endpoint_margin = lambda *args: None
    try:
        bisection = exact_margin(G, bits=40)
    finally:
        numerics._endpoint_margin = original
    assert shortcut.lo <= bisection.hi and bisection.lo <= shortcut.hi
    evaluate = sp.lambdify(z, G, "numpy")
    thetas = np.concatenate([np.linspace(1e-4, math.pi, 4000), [math.pi]])
    sweep = min(np.linalg.eigvalsh((lambda M: (M + M.conj().T) / 2)(np.array(evaluate(np.exp(1j * t)), dtype=complex))).min()
                for t in thetas)
    assert float(shortcut.lo) <= sweep + 1e-9
    assert sweep - float(shortcut.hi) < 1e-3 * max(1.0, abs(sweep))
