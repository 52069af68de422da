"""Exact root isolation and sign decisions, checked against SymPy's independent root counting."""

from fractions import Fraction

import flint
import mpmath
import numpy as np
import pytest
import sympy as sp
from hypothesis import given, settings
from hypothesis import strategies as st

from hapticproof.exact.realroots import RealRoot, as_fmpq_poly, minimise_rational, nonnegative_on, real_roots, sign_at

c = sp.Symbol("c")

small_rationals = st.fractions(min_value=-2, max_value=2, max_denominator=12)
coefficients = st.lists(st.integers(-20, 20), min_size=2, max_size=9).filter(lambda a: any(a[1:]))


def to_poly(coeffs):
    return flint.fmpq_poly(coeffs)


def sympy_poly(coeffs):
    return sp.Poly(list(reversed(coeffs)), c)


@settings(max_examples=150, deadline=None)
@given(coefficients)
def test_root_count_matches_sympy(coeffs):
    p = to_poly(coeffs)
    roots = real_roots(p, -1, 1)
    distinct = sp.Poly(sympy_poly(coeffs).as_expr(), c).sqf_part()
    assert len(roots) == distinct.count_roots(-1, 1)
    for root in roots:
        assert root.lo <= root.hi
        if not root.is_exact:
            # the factor changes sign across an isolating interval: exactly one simple root
            assert sign_at(root.poly, root.lo) * sign_at(root.poly, root.hi) < 0


@settings(max_examples=100, deadline=None)
@given(st.lists(small_rationals, min_size=1, max_size=5), st.integers(1, 3))
def test_rational_roots_are_found_with_multiplicity(roots, power):
    p = flint.fmpq_poly([1])
    for r in roots:
        p *= flint.fmpq_poly([flint.fmpq(-r.numerator, r.denominator), 1]) ** power
    found = real_roots(p, -2, 2)
    assert len(found) == len(set(roots))
    for root, expected in zip(found, sorted(set(roots))):
        assert root.multiplicity >= power
        refined = root.refine(Fraction(1, 10**12))
        assert refined.lo <= flint.fmpq(expected.numerator, expected.denominator) <= refined.hi


@settings(max_examples=150, deadline=None)
@given(coefficients, small_rationals, small_rationals)
def test_nonnegative_decision_and_witness(coeffs, a, b):
    lo, hi = min(a, b), max(a, b)
    p = to_poly(coeffs)
    result = nonnegative_on(p, lo, hi)
    if result.holds:
        # independent check: no sign change of the squarefree part inside, and a sample >= 0
        samples = [lo + (hi - lo) * Fraction(k, 64) for k in range(65)]
        assert all(p(flint.fmpq(s.numerator, s.denominator)) >= 0 for s in samples)
    else:
        w = result.witness
        assert lo <= Fraction(int(w.p), int(w.q)) <= hi
        assert sign_at(p, Fraction(int(w.p), int(w.q))) < 0


def test_touching_zero_is_nonnegative():
    p = as_fmpq_poly((2 * c**2 - 1) ** 2 * (c + 3), c)
    result = nonnegative_on(p, -1, 1)
    assert result.holds
    assert len(result.touches_zero) == 2


def test_unbounded_interval():
    assert nonnegative_on(as_fmpq_poly(c**4 - c + 1, c), 0, None).holds
    bad = nonnegative_on(as_fmpq_poly(c**4 - 3 * c + 1, c), 0, None)
    assert not bad.holds and bad.witness >= 0


def test_high_degree_chebyshev_roots():
    p = flint.fmpq_poly(flint.fmpz_poly.chebyshev_t(60)) - flint.fmpq(1, 3)
    roots = real_roots(p, -1, 1)
    assert len(roots) == 60
    mpmath.mp.dps = 30
    for k, root in enumerate(reversed(roots)):
        # T_60(cos t) = 1/3  <=>  t = (+-acos(1/3) + 2 pi j) / 60
        value = root.midpoint(80)
        assert abs(mpmath.chebyt(60, mpmath.mpf(value.p) / value.q) - mpmath.mpf(1) / 3) < 1e-15


@settings(max_examples=60, deadline=None)
@given(coefficients, st.lists(st.integers(1, 9), min_size=1, max_size=3))
def test_minimum_matches_dense_sampling(num_coeffs, den_roots):
    num = to_poly(num_coeffs)
    den = flint.fmpq_poly([1])
    for r in den_roots:  # positive on [-1, 1]: roots outside
        den *= flint.fmpq_poly([r + 1, 1])
    m = minimise_rational(num, den, -1, 1)
    grid = np.linspace(-1, 1, 4001)
    values = np.polyval([float(a) for a in reversed(num.coeffs())], grid) / np.polyval(
        [float(a) for a in reversed(den.coeffs())], grid
    )
    sampled = values.min()
    low = float(m.value.lower().str(20, radius=False))
    assert low <= sampled + 1e-12 * (1 + abs(sampled))
    # the minimum is attained: the sampled minimum is close to it
    assert sampled - low < 1e-3 * (1 + abs(sampled))
    if isinstance(m.argmin, RealRoot):
        assert m.exact is None
    else:
        assert m.exact is not None


def test_minimum_rejects_pole_inside():
    with pytest.raises(ValueError):
        minimise_rational(flint.fmpq_poly([1]), flint.fmpq_poly([0, 1]), -1, 1)


@settings(max_examples=60, deadline=None)
@given(coefficients, st.integers(0, 3), st.sampled_from([-1, 1]))
def test_endpoint_shortcut_agrees_with_full_isolation(coeffs, power, end):
    """p(c) = (1 + end*c) q(c)^2 (1 + ...) + small: minima at the endpoint c = -end half of the time;
    the shortcut's minimum equals the exhaustive one (shortcut disabled) exactly when both are rational."""
    import hapticproof.exact.realroots as rr

    q = to_poly(coeffs)
    num = flint.fmpq_poly([1, end]) * q * q * flint.fmpq_poly([2, 0, 1]) ** power + flint.fmpq_poly([coeffs[0], 1])
    den = flint.fmpq_poly([3, 1])
    fast = minimise_rational(num, den, -1, 1)
    original, rr._endpoint_minimum = rr._endpoint_minimum, lambda *args: None
    try:
        slow = minimise_rational(num, den, -1, 1)
    finally:
        rr._endpoint_minimum = original
    assert fast.value.overlaps(slow.value)
    if fast.exact is not None and slow.exact is not None:
        assert fast.exact == slow.exact
