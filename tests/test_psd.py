"""Matrix PSD tests, principal minors and unit-circle decisions against independent numerics."""

import cmath
import itertools
import math

import flint
import numpy as np
import pytest
import sympy as sp
from hypothesis import assume, given, settings
from hypothesis import strategies as st

from hapticproof.core.evidence import Decision
from hapticproof.exact.psd import HermitianPart, PolyRing, affine_worst_case, characteristic_coefficients, decide_psd_on_circle, hermitian_part_matrix, leading_minor_counterexample, leading_minor_shortcut, leading_minors, min_eigenvalue, nonnegative_certificate, principal_minors, residue_matrices, shortcut_failure
from hapticproof.exact.charpoly import is_psd
from hapticproof.core.symbols import c, z

small = st.integers(-6, 6)


def _minor(M, subset):
    return M.extract(list(subset), list(subset)).det()


def exact_psd(M):
    """Hermitian M is PSD iff every principal minor is >= 0 (exact, independent of psd.py)."""
    n = M.shape[0]
    return all(sp.simplify(_minor(M, sub)) >= 0 for k in range(1, n + 1) for sub in itertools.combinations(range(n), k))


def sym_matrix(size, entries):
    it = iter(entries)
    M = sp.zeros(size, size)
    for i in range(size):
        for j in range(i, size):
            M[i, j] = M[j, i] = sp.Rational(next(it), 2)
    return M


@settings(max_examples=60, deadline=None)
@given(st.integers(1, 5).flatmap(lambda m: st.tuples(st.just(m), st.lists(small, min_size=m * (m + 1) // 2,
                                                                         max_size=m * (m + 1) // 2))))
def test_is_psd_agrees_with_eigenvalues(data):
    m, entries = data
    M = sym_matrix(m, entries)
    eig = np.linalg.eigvalsh(np.array(M.tolist(), dtype=float))
    test = is_psd(M)
    exact = exact_psd(M)                  # every example is decided, singular ones included
    assert test.holds == exact
    assert eig.min() > -1e-9 if exact else eig.min() < 1e-9
    assert test.minor is None if exact else (test.minor[1] < 0 and _minor(M, test.minor[0]) == test.minor[1])
    # E_k are the sums of the k x k principal minors
    for k in range(1, m + 1):
        total = sum(M.extract(list(s), list(s)).det() for s in itertools.combinations(range(m), k))
        assert test.coefficients[k] == total


@settings(max_examples=40, deadline=None)
@given(st.lists(small, min_size=6, max_size=6), st.lists(small, min_size=3, max_size=3))
def test_is_psd_complex_hermitian(re_entries, im_entries):
    M = sym_matrix(3, re_entries)
    for (i, j), v in zip(((0, 1), (0, 2), (1, 2)), im_entries):
        M[i, j] += sp.I * v
        M[j, i] -= sp.I * v
    eig = np.linalg.eigvalsh(np.array(M.evalf().tolist(), dtype=complex))
    test = is_psd(M, search_minor=False)
    exact = exact_psd(M)
    assert test.holds == exact
    assert eig.min() > -1e-9 if exact else eig.min() < 1e-9
    assert float(test.coefficients[3]) == pytest.approx(float(np.prod(eig)), rel=1e-9, abs=1e-9)


def test_leading_minor_shortcut_fails_on_concrete_matrices():
    for M in ([[0, 0], [0, -1]], [[1, 1, 0], [1, 1, 0], [0, 0, -1]]):
        assert leading_minor_shortcut(M)
        failure = shortcut_failure(M)
        assert failure is not None and failure.negative_minor[1] < 0 and failure.min_eigenvalue < 0
        assert not is_psd(M).holds
    # Sylvester: strictly positive leading minors do certify definiteness
    assert shortcut_failure([[2, 1], [1, 2]]) is None
    assert leading_minors([[2, 1], [1, 2]]) == [2, 3]


@settings(max_examples=50, deadline=None)
@given(st.lists(small, min_size=3, max_size=3), st.lists(st.integers(1, 6), min_size=3, max_size=3))
def test_strict_leading_minors_imply_psd(lower, pivots):
    """Sylvester: M = L D L^T with unit lower-triangular L and positive D has the leading minors
    d_1, d_1 d_2, d_1 d_2 d_3 > 0 -- every example has them (constructed, not filtered)."""
    L = sp.Matrix([[1, 0, 0], [sp.Rational(lower[0], 2), 1, 0], [sp.Rational(lower[1], 2), sp.Rational(lower[2], 2), 1]])
    D = sp.diag(*[sp.Rational(d, 2) for d in pivots])
    M = L * D * L.T
    minors = leading_minors(M)
    assert minors == [D[0, 0], D[0, 0] * D[1, 1], D[0, 0] * D[1, 1] * D[2, 2]] and all(v > 0 for v in minors)
    assert is_psd(M).holds


@settings(max_examples=50, deadline=None)
@given(st.lists(small, min_size=6, max_size=6))
def test_a_negative_leading_minor_refutes_psd(entries):
    M = sym_matrix(3, entries)
    minors = leading_minors(M)
    assume(any(v < 0 for v in minors))
    assert not is_psd(M).holds


def direct_M(G, theta):
    f = sp.lambdify(z, G, "numpy")
    Gv = np.array(f(cmath.exp(1j * theta)), dtype=complex)
    return Gv + Gv.conj().T


@settings(max_examples=25, deadline=None)
@given(st.lists(st.integers(-4, 4), min_size=8, max_size=8), st.integers(0, 2), st.floats(0.1, 3.0))
def test_hermitian_part_matches_direct_evaluation(coeffs, shift, theta):
    a = [sp.Rational(v, 2) for v in coeffs]
    G = sp.Matrix([[a[0] + a[1] / (z - 1), a[2] / z ** (shift + 1)],
                   [a[3] + a[4] / (z - 1), a[5] + a[6] / z + a[7] * z / (z - 1)]])
    H = hermitian_part_matrix(G)
    assert np.allclose(H.evaluate(theta), direct_M(G, theta), atol=1e-9)
    # minors: exact in c, compared with numpy determinants of principal submatrices
    Mv = direct_M(G, theta)
    for subset, minor in principal_minors(H).items():
        value = float(minor.expr().subs(c, math.cos(theta)))
        assert value == pytest.approx(np.linalg.det(Mv[np.ix_(subset, subset)]).real, rel=1e-7, abs=1e-7)


def test_minors_of_unequal_delays_are_real_polynomials():
    G = sp.Matrix([[3 + 1 / (z - 1), -1 / (z - 1)], [-1 / (z**3 * (z - 1)), 3 + 1 / (z**3 * (z - 1))]])
    H = hermitian_part_matrix(G)
    assert not H.is_symmetric
    det = principal_minors(H)[(0, 1)]
    assert det.expr().free_symbols <= {c}
    assert characteristic_coefficients(H, "minors") == characteristic_coefficients(H, "interpolation")


def test_symbolic_minors_match_sympy_determinants():
    a, b_, w = sp.symbols("a b w", nonnegative=True)
    G = sp.Matrix([[a + w / z, -w / z, 0], [-w / z, b_ + 2 * w / z, -w / z], [0, -w / z, a + w / z]])
    H = hermitian_part_matrix(G)
    M = H.matrix()
    for subset, minor in principal_minors(H).items():
        assert sp.expand(minor.expr() - M.extract(list(subset), list(subset)).det()) == 0


def test_decision_against_numpy_grid():
    thetas = np.linspace(1e-3, math.pi, 1500)
    for b in (sp.Rational(1, 4), sp.Rational(3, 5), 1, 2):
        G = sp.Matrix([[b + 1 / (z - 1) + sp.Rational(1, 3) / z, -sp.Rational(1, 2) / (z - 1)],
                       [-sp.Rational(1, 2) / (z**2 * (z - 1)), b + 1 / (z**2 * (z - 1))]])
        H = hermitian_part_matrix(G)
        decision = decide_psd_on_circle(H)
        grid_min = min(min_eigenvalue(H, t) for t in thetas)
        if decision.decision == Decision.PROVED:
            assert grid_min > -1e-9
        else:
            theta = math.acos(float(decision.witness))
            assert min_eigenvalue(H, theta) < 0


def test_residue_matrices():
    K1, K2, T = sp.symbols("K_1 K_2 T", positive=True)
    G = sp.Matrix([[(K1 + K2) * T / (z - 1), -K2 * T / (z - 1)], [-K2 * T / (z - 1), K2 * T / (z - 1)]])
    (r,) = residue_matrices(G)
    assert r.pole == 1 and r.outcome.decision == Decision.PROVED
    (double,) = residue_matrices(sp.Matrix([[1 / (z - 1) ** 2]]))
    assert double.outcome.decision == Decision.DISPROVED
    (neg,) = residue_matrices(sp.Matrix([[-1 / (z - 1), 0], [0, 1 / (z - 1)]]))
    assert neg.outcome.decision == Decision.DISPROVED
    (non_herm,) = residue_matrices(sp.Matrix([[1 / (z - 1), 1 / (z - 1)], [0, 1 / (z - 1)]]))
    assert non_herm.outcome.decision == Decision.DISPROVED


def test_affine_worst_case_endpoints():
    B, b = sp.symbols("B b", nonnegative=True)
    up = affine_worst_case(hermitian_part_matrix(sp.Matrix([[b + B / z]])))
    assert up.endpoint == -1 and sp.expand(up.conditions()[0].lhs - (2 * b - 2 * B)) == 0
    down = affine_worst_case(hermitian_part_matrix(sp.Matrix([[b - B / z]])))
    assert down.endpoint == 1
    assert affine_worst_case(hermitian_part_matrix(sp.Matrix([[b + B / z**2]]))) is None   # quadratic in c


def test_leading_minor_counterexample_on_a_matrix_function():
    G = sp.Matrix([[sp.Rational(1, 2) + 2 / (z - 1) + 1 / z, -(1 / (z - 1) + 1 / z)],
                   [-(1 / (z - 1) + 1 / z), sp.Rational(1, 4) + 2 / (z - 1) + 1 / z]])
    c0, failure = leading_minor_counterexample(hermitian_part_matrix(G))
    assert c0 == sp.Rational(1, 2) and all(v == 0 for v in failure.leading)
    assert failure.negative_minor[1] < 0


def test_poly_ring_and_certificates():
    a, b_ = sp.symbols("a b", nonnegative=True)
    R = PolyRing.over((a, b_))
    p = R.from_expr(a**2 * c - 3 * b_ + sp.Rational(1, 7))
    assert sp.expand(R.to_expr(p) - (a**2 * c - 3 * b_ + sp.Rational(1, 7))) == 0
    assert R.substitute(p, {a: 1, b_: 0, c: 1}).coeffs()[0] == flint.fmpq(8, 7)
    assert nonnegative_certificate(R, R.from_expr(a * b_ + 1))
    assert not nonnegative_certificate(R, R.from_expr(a * c))          # depends on c
    free = sp.Symbol("f")
    assert not nonnegative_certificate(PolyRing.over((free,)), PolyRing.over((free,)).from_expr(free))
    H = HermitianPart(PolyRing.over(()), ((flint.fmpq_poly([1, 1]),),), None, flint.fmpq_poly([1]))
    assert H.subs({}).is_numeric and H.at(0)[0, 0] == 1
    with pytest.raises(ValueError):
        is_psd([[1, 2], [0, 1]])
