"""Exact n-port analysis: rational matrices, positive realness, Llewellyn, Youla, absolute stability,
destabilizing terminations, and the exact port-energy simulation -- each cross-checked numerically."""

import itertools
import math

import flint
import mpmath
import numpy as np
import pytest
import sympy as sp
from hypothesis import given, settings
from hypothesis import strategies as st

from hapticproof.energy import Sinusoid, input_energy, port_admittance, realize
from hapticproof.evidence import Decision
from hapticproof.networks import (
    absolute_stability,
    input_impedance,
    llewellyn,
    positive_real,
    residue_matrix,
    symmetrization_conditions,
    symmetrize,
    verify_certificate,
)
from hapticproof.rationalmatrix import (
    RationalFunction,
    RationalMatrix,
    decide_psd,
    hermitian_minors,
    minimise_halfline,
    pole_report,
)
from hapticproof.kernel import locate_roots
from hapticproof.symbols import s

small = st.integers(min_value=-5, max_value=5)
positive = st.integers(min_value=1, max_value=6)


def hermitian_min_eig(Z, w):
    R = Z if isinstance(Z, RationalMatrix) else RationalMatrix.from_sympy(Z)
    M = R.numpy_at(1j * w)
    return np.linalg.eigvalsh((M + M.conj().T) / 2).min()


# ---------------------------------------------------------------------------------------------
# rational functions and matrices
# ---------------------------------------------------------------------------------------------


@settings(max_examples=20, deadline=None)
@given(small, small, positive, small, positive)
def test_rational_function_arithmetic_matches_sympy(a, b, c, d, e):
    f = a / (s + c) + b
    g = d * s / (s**2 + e)
    F, G = RationalFunction.from_sympy(f), RationalFunction.from_sympy(g)
    for ours, theirs in ((F + G, f + g), (F * G, f * g), (F - G, f - g)):
        assert sp.cancel(ours.expr() - theirs) == 0
    if g != 0:
        assert sp.cancel((F / G).expr() - f / g) == 0


def test_inverse_and_determinant_are_exact():
    Z = sp.Matrix([[1 / (s + 1), 2], [s, 3 / (s + 2)]])
    R = RationalMatrix.from_sympy(Z)
    assert sp.cancel(R.determinant().expr() - Z.det()) == 0
    assert (R.inverse().to_sympy() - Z.inv()).applyfunc(sp.cancel) == sp.zeros(2, 2)


@settings(max_examples=25, deadline=None)
@given(st.lists(small, min_size=9, max_size=9), st.lists(positive, min_size=3, max_size=3),
       st.floats(min_value=0.05, max_value=20))
def test_hermitian_minors_match_numeric_eigen_data(nums, poles, w):
    """Every principal minor of the Hermitian part, exact in x, equals the float value at jw."""
    entries = [[sp.Integer(nums[3 * i + j]) / (s + poles[j]) + (2 if i == j else 0) for j in range(3)] for i in range(3)]
    Z = sp.Matrix(entries)
    minors = hermitian_minors(RationalMatrix.from_sympy(Z))
    M = RationalMatrix.from_sympy(Z).numpy_at(1j * w)
    H = (M + M.conj().T) / 2
    x = sp.Rational(w).limit_denominator(10**6) ** 2
    wq = math.sqrt(float(x))
    M = RationalMatrix.from_sympy(Z).numpy_at(1j * wq)
    H = (M + M.conj().T) / 2
    for subset in itertools.combinations(range(3), 2):
        exact = float(minors.true_minor(subset, x))
        numeric = np.linalg.det(H[np.ix_(subset, subset)]).real
        assert exact == pytest.approx(numeric, rel=1e-8, abs=1e-10)


def test_leading_minors_are_not_enough():
    # constant Hermitian part with leading minors 0, 0 -- not PSD; the decision must see it
    out = decide_psd(hermitian_minors(RationalMatrix.from_sympy(sp.Matrix([[0, 0], [0, -1]]))))
    assert out.decision == Decision.DISPROVED


def test_minimise_halfline_limit_at_infinity():
    m = minimise_halfline(flint.fmpq_poly([2, 0, 1]), flint.fmpq_poly([1, 0, 1]))   # (x^2+2)/(x^2+1) -> 1
    assert m.argmin == sp.oo and float(m.value.mid()) == pytest.approx(1.0)


def test_rhp_roots_are_certified_and_axis_roots_excluded():
    p = flint.fmpq_poly([4, 0, 1]) * flint.fmpq_poly([-1, 1]) * flint.fmpq_poly([2, 1])   # (s^2+4)(s-1)(s+2)
    cert = locate_roots(p, "halfplane")
    assert cert.outside == 1 and cert.outside_points[0].real == pytest.approx(1.0)


def test_pole_report():
    rep = pole_report(RationalMatrix.from_sympy(sp.Matrix([[1 / (s - 2), 1 / s**2]])))
    assert rep.rhp and not rep.axis_simple


# ---------------------------------------------------------------------------------------------
# positive realness
# ---------------------------------------------------------------------------------------------


def test_positive_real_rlc_and_residues():
    # a reciprocal RLC 2-port: P + Q s + R/s with PSD P, Q, R
    P, Q, R = sp.Matrix([[2, 1], [1, 1]]), sp.Matrix([[1, 0], [0, 0]]), sp.Matrix([[1, 1], [1, 1]])
    T = P + Q * s + R / s
    result = positive_real(T)
    assert result.decision == Decision.PROVED
    assert residue_matrix(RationalMatrix.from_sympy(T), "zero") == R
    assert residue_matrix(RationalMatrix.from_sympy(T), "infinity") == Q
    # an indefinite residue at s = 0 breaks it
    bad = positive_real(P + sp.Matrix([[1, 2], [2, 1]]) / s)
    assert bad.decision == Decision.DISPROVED and bad.residues.decision == Decision.DISPROVED


def test_positive_real_pair_pole():
    # s/(s^2 + 4) is PR (LC tank): residue 1/2 at +-2j; -s/(s^2+4) is not
    assert positive_real(sp.Matrix([[s / (s**2 + 4)]])).decision == Decision.PROVED
    assert positive_real(sp.Matrix([[-s / (s**2 + 4)]])).decision == Decision.DISPROVED
    B, A = residue_matrix(RationalMatrix.from_sympy(sp.Matrix([[s / (s**2 + 4)]])), ("pair", 4))
    assert B == sp.Matrix([[1]]) and A == sp.Matrix([[0]])


@settings(max_examples=15, deadline=None)
@given(st.lists(small, min_size=4, max_size=4), st.lists(positive, min_size=2, max_size=2))
def test_positive_real_agrees_with_dense_sweep(nums, poles):
    Z = sp.Matrix([[3 + nums[0] / (s + poles[0]), nums[1] / (s + poles[1])],
                   [nums[2] / (s + poles[1]), 2 + nums[3] / (s + poles[0])]])
    result = positive_real(Z)
    R = RationalMatrix.from_sympy(Z)
    sweep = min(hermitian_min_eig(R, w) for w in np.concatenate([[0.0], np.logspace(-3, 3, 400)]))
    if result.decision == Decision.PROVED:
        assert sweep >= -1e-9
    else:
        w = result.hermitian.witness
        x = float(w["x"])
        assert hermitian_min_eig(Z, math.sqrt(x)) < 0


# ---------------------------------------------------------------------------------------------
# Llewellyn
# ---------------------------------------------------------------------------------------------


def test_llewellyn_paper_subsystem_is_tight_at_zero():
    result = llewellyn(sp.Matrix([[9 / (s + 3), -1 / (s + 1)], [-1 / (s + 1), 1 / (s + 3)]]))
    assert result.decision == Decision.PROVED
    assert result.tightest.argmin == 0 and result.eta_min == 1


def test_llewellyn_gyrator_and_failure():
    assert llewellyn(sp.Matrix([[1, 2], [-2, 1]])).decision == Decision.PROVED     # eta = (2 + 4)/4 >= 1
    assert llewellyn(sp.Matrix([[1, 3], [3, 1]])).decision == Decision.DISPROVED   # eta = (2 - 9)/9 < 1


@settings(max_examples=15, deadline=None)
@given(st.lists(small, min_size=4, max_size=4), st.lists(positive, min_size=2, max_size=2))
def test_llewellyn_agrees_with_dense_mpmath_sweep(nums, poles):
    Z = sp.Matrix([[2 + 3 * abs(nums[0]) / (s + poles[0]), nums[1] / (s + poles[1])],
                   [nums[2] / (s + poles[0]), 1 + abs(nums[3]) / (s + poles[1])]])
    result = llewellyn(Z)
    f = [sp.lambdify(s, Z[i, j], "mpmath") for i in range(2) for j in range(2)]
    worst = mpmath.inf
    for w in [0] + list(np.logspace(-3, 3, 300)):
        z11, z12, z21, z22 = (g(mpmath.mpc(0, w)) for g in f)
        p = z12 * z21
        worst = min(worst, 2 * z11.real * z22.real - p.real - abs(p))
    if result.decision == Decision.PROVED:
        assert worst >= -1e-12
    else:
        assert worst < 1e-12


# ---------------------------------------------------------------------------------------------
# Youla symmetrization
# ---------------------------------------------------------------------------------------------


def test_symmetrization_conditions_reduce_only_by_nonzero_entries():
    a, b, c = sp.symbols("a b c")
    Z = sp.Matrix([[1, a, 1], [a, 1, b], [c, 1, 1]])
    conds = symmetrization_conditions(Z, ports=(2, 1))
    assert [(x.kind, x.reduced) for x in conds] == [("A", True)]
    assert sp.expand(conds[0].expr - (b * c - 1)) == 0 or sp.expand(conds[0].expr + (b * c - 1)) == 0
    # with the cancelled entry zero, A is not reduced (and holds vacuously here)
    Z0 = Z.subs(a, 0)
    assert symmetrization_conditions(Z0, ports=(2, 1)) == []


@settings(max_examples=10, deadline=None)
@given(st.lists(st.integers(min_value=1, max_value=5), min_size=3, max_size=3),
       st.lists(small, min_size=6, max_size=6))
def test_symmetrize_diagonal_similarity_recovers_minors(scales, couplings):
    """Z = D S D^-1 with S symmetric: Youla's Z' exists and has all principal minors of Z."""
    S = sp.Matrix([[2 + 1 / (s + 1), couplings[0] / (s + 2), couplings[1]],
                   [couplings[0] / (s + 2), 3, couplings[2] / (s + 1)],
                   [couplings[1], couplings[2] / (s + 1), 1 + s]])
    D = sp.diag(*scales)
    Z = D * S * D.inv()
    Y = symmetrize(Z)
    assert Y.symmetrizable == Decision.PROVED
    Zp = Y.zprime()
    assert (Zp - Zp.T).applyfunc(sp.simplify) == sp.zeros(3, 3)
    point = sp.Rational(3, 2)
    for k in (1, 2, 3):
        for rows in itertools.combinations(range(3), k):
            rows = list(rows)
            a = sp.nsimplify(sp.simplify(Z.extract(rows, rows).subs(s, point).det()))
            b = sp.nsimplify(sp.simplify(Zp.extract(rows, rows).subs(s, point).det()))
            assert a == b


def test_symmetrize_imaginary_couplings_and_cycles():
    # gyrator-like couplings: z12 z21 = -4 (negative constant times a square): Z' is complex
    Z = sp.Matrix([[1, 2, 0], [-2, 1, 0], [0, 0, 1]])
    Y = symmetrize(Z)
    assert Y.symmetrizable == Decision.PROVED and any(u < 0 for u in Y.scales)
    assert sp.simplify(Y.zprime()[0, 1] ** 2 + 4) == 0
    assert absolute_stability(Z, search=False).decision == Decision.PROVED
    # a 4-cycle with unequal forward/backward products: A holds vacuously, no Z' exists
    C = sp.eye(4) * 2
    C[0, 1], C[1, 0] = 2, sp.Rational(1, 2)
    for a, b in ((1, 2), (2, 3), (3, 0)):
        C[a, b] = C[b, a] = 1
    assert symmetrization_conditions(C) == []
    assert symmetrize(C).symmetrizable == Decision.DISPROVED


def test_irrational_zprime_is_undecided_not_guessed():
    Z = sp.Matrix([[2, 1 / (s + 1), 1], [1 / (s + 2), 2, 1], [1, 1, 2]])
    assert symmetrize(Z).symmetrizable == Decision.DISPROVED  # A fails here
    Z2 = sp.Matrix([[2, 1 / (s + 1), 0], [1 / (s + 2), 2, 0], [0, 0, 2]])
    assert symmetrize(Z2).symmetrizable == Decision.UNDECIDED   # (s+1)(s+2) is not a square


# ---------------------------------------------------------------------------------------------
# absolute stability and terminations
# ---------------------------------------------------------------------------------------------


def test_hand_certificate_is_verified_exactly():
    Z = sp.diag(sp.Matrix([[0, 0, 0], [0, 1, 2], [0, 2, 1]]), sp.eye(3))
    terms = (sp.diag(1, 2 / (s + 1), 2 / (s + 1)), sp.eye(3))
    roots, degree = verify_certificate(RationalMatrix.from_sympy(Z), terms, ((0, 1, 2), (3, 4, 5)))
    assert len(roots) == 1 and roots[0].real == pytest.approx(1.0)
    # and no RHP zero with passive terminations that keep the network passive
    roots, _ = verify_certificate(RationalMatrix.from_sympy(sp.eye(6)), terms, ((0, 1, 2), (3, 4, 5)))
    assert roots == []


def test_absolute_stability_detects_reciprocal_non_passive_network():
    Z = sp.diag(sp.Matrix([[0, 0, 0], [0, 1, 2], [0, 2, 1]]), sp.eye(3))
    verdict = absolute_stability(Z, ports=(3, 3))
    assert verdict.decision == Decision.DISPROVED
    assert verdict.certificate is not None and verdict.certificate.terminations_positive_real
    assert all(r.real > 0 for r in verdict.certificate.roots)


def test_input_impedance():
    Zin = input_impedance(sp.Matrix([[1, 3], [3, 1]]), sp.Matrix([[10]]), (1, 1))
    assert Zin.to_sympy() == sp.Matrix([[sp.Rational(2, 11)]])


# ---------------------------------------------------------------------------------------------
# energy
# ---------------------------------------------------------------------------------------------


def test_realization_matches_transfer_matrix():
    G = RationalMatrix.from_sympy(sp.Matrix([[1 / (s + 1), 2 / (s**2 + s + 3)], [s / (s + 2), 1]]))
    ss = realize(G)
    for point in (0.3j, 1 + 2j, 5j):
        assert np.allclose(ss.transfer_at(point), G.numpy_at(point), rtol=1e-9, atol=1e-12)


def test_energy_matches_independent_quadrature():
    """Exact-between-samples energy vs a tight ODE integration with mpmath-free quadrature."""
    from scipy.integrate import solve_ivp

    Z = sp.Matrix([[1 + 1 / s, 1], [1, 2 + s]])      # a passive 2-port
    G = port_admittance(Z, {1: sp.Matrix([[1 / (s + 1)]])}, driven=(0,))
    ss = realize(G)
    sine = Sinusoid(1.5, 2.0, 0.3)
    trace = input_energy(ss, [sine], t_end=5.0, steps=500)

    def rhs(t, z):
        x = z[:-1]
        u = sine.amplitude * math.sin(sine.omega * t + sine.phase)
        y = (ss.c @ x + ss.d[:, 0] * u)[0]
        return np.concatenate([ss.a @ x + ss.b[:, 0] * u, [u * y]])

    sol = solve_ivp(rhs, (0, 5.0), np.zeros(ss.a.shape[0] + 1), rtol=1e-11, atol=1e-13, t_eval=trace.times)
    assert np.allclose(sol.y[-1], trace.energy, atol=1e-8)
    assert trace.minimum >= -1e-12   # passive network, passive load: E_s >= 0


# ---------------------------------------------------------------------------------------------
# CLI: hapticproof derive network
# ---------------------------------------------------------------------------------------------


def test_cli_text_and_json(tmp_path, capsys):
    import json

    from hapticproof.cli import main

    text = tmp_path / "z5.txt"
    text.write_text("# eq. (5)\n9/(s+3), -1/(s+1)\n-1/(s+1), 1/(s+3)\n")
    assert main(["derive", "network", "--matrix", str(text)]) == 0
    out = capsys.readouterr().out
    assert "absolutely stable (Llewellyn)" in out
    js = tmp_path / "z.json"
    js.write_text(json.dumps({"matrix": [["1", "3"], ["3", "1"]]}))
    assert main(["derive", "network", "--matrix", str(js), "--format", "json", "--no-search"]) == 0
    data = json.loads(capsys.readouterr().out)
    assert data["absolute_stability"]["decision"] == "disproved"
    assert data["positive_real"]["decision"] == "disproved"


def test_cli_parameters_and_errors(tmp_path, capsys):
    from hapticproof.cli import main

    f = tmp_path / "zk.txt"
    f.write_text("2, k\n1/(s+1), 2\n")
    assert main(["derive", "network", "--matrix", str(f)]) == 0
    assert "free parameters" in capsys.readouterr().out
    assert main(["derive", "network", "--matrix", str(f), "--param", "k=1", "--format", "latex"]) == 0
    assert r"\begin{document}" in capsys.readouterr().out
    bad = tmp_path / "bad.txt"
    bad.write_text("1, __import__('os')\n")
    assert main(["derive", "network", "--matrix", str(bad)]) == 2
    ragged = tmp_path / "ragged.txt"
    ragged.write_text("1, 2\n3\n")
    assert main(["derive", "network", "--matrix", str(ragged)]) == 2
    assert main(["derive", "network", "--matrix", str(f), "--param", "k=1", "--ports", "3,3"]) == 2


def test_theorem9_conditions_corrected_vs_printed():
    from hapticproof.networks import theorem9_conditions

    leading = sp.diag(sp.Matrix([[0, 0, 0], [0, 1, 2], [0, 2, 1]]), sp.eye(3))
    th = theorem9_conditions(leading, (3, 3))
    assert [getattr(th, k).decision for k in ("A", "B", "C", "D")] == [Decision.PROVED] * 4
    assert th.E_printed.decision == Decision.PROVED and th.E.decision == Decision.DISPROVED
    cycle = sp.eye(6) * 2
    cycle[0, 3], cycle[3, 0] = 2, sp.Rational(1, 2)
    for a, b in ((3, 1), (1, 4), (4, 0)):
        cycle[a, b] = cycle[b, a] = 1
    th = theorem9_conditions(cycle, (3, 3))
    assert th.B.decision == Decision.PROVED and th.A.decision == Decision.DISPROVED
