"""The differential suite's oracles themselves: independence from the package, and known answers.

The oracles in ``tests/oracles/`` must import nothing from the package under test (only numpy,
mpmath, scipy, SymPy and the standard library); this is checked on their sources. Their answers
are checked on closed-form cases (Colgate's wall, the Dirichlet-kernel bound of the delayed
wall, lossless and improper impedances, Llewellyn's examples) and against each other (the m-user
oracle with one user against the scalar one, Routh counts against numpy roots).
"""

from __future__ import annotations

import ast
import sys
from fractions import Fraction
from pathlib import Path

import pytest
import sympy as sp
from hypothesis import given, settings
from hypothesis import strategies as st

sys.path.insert(0, str(Path(__file__).resolve().parent))

from oracles.absolute import absolute_stability  # noqa: E402
from oracles.continuous import S, llewellyn, positive_real_matrix  # noqa: E402
from oracles.discrete import Z, discrete_positive_real, multi_user_positive_real, single_user_positive_real  # noqa: E402
from oracles.harness import examples  # noqa: E402
from oracles.search import check_termination, find_destabilizing_termination, routh_rhp_count  # noqa: E402

ORACLES = Path(__file__).resolve().parent / "oracles"
ALLOWED = {"numpy", "mpmath", "scipy", "sympy", "__future__", "dataclasses", "fractions", "functools", "itertools",
           "json", "math", "os", "random", "re", "tempfile", "time", "typing"}
R = sp.Rational
z, s = Z, S


def test_oracles_import_nothing_from_the_package():
    sources = sorted(ORACLES.glob("*.py"))
    assert sources
    for path in sources:
        text = path.read_text(encoding="utf-8")
        assert "hapticproof" not in text, f"{path.name} mentions the package under test"
        for node in ast.walk(ast.parse(text)):
            if isinstance(node, ast.Import):
                names = [alias.name for alias in node.names]
            elif isinstance(node, ast.ImportFrom):
                if node.level > 0:
                    continue  # within the oracle package
                names = [node.module or ""]
            else:
                continue
            for name in names:
                assert name.split(".")[0] in ALLOWED, f"{path.name} imports {name}"


# ---------------------------------------------------------------------------------------------
# discrete time
# ---------------------------------------------------------------------------------------------


@pytest.mark.parametrize("F, want", [
    (1 + 1 / (z - 1), "yes"),             # Res 1 at z = 1, Re F = 1/2
    (1 + 1 / (z + 1), "no"),              # Res/z0 = -1 at z = -1
    ((z - 1) / (z + 1), "yes"),           # lossless: Re F = 0 on the circle (Res/z0 = 2), exact
    (1 / (z - 1) ** 2 + 5, "no"),         # double pole on the circle
    (1 + 1 / (z - 2), "no"),              # pole outside
    (z**2 / (z - R(1, 2)), "no"),         # improper
    (3 + 1 / (z**2 - z + 1), "no"),       # poles e^{+-j pi/3}: Res/z0 = -j/sqrt(3), not real
])
def test_discrete_known_answers(F, want):
    assert discrete_positive_real(F).verdict == want


@pytest.mark.parametrize("n", [0, 1, 3, 5])
@pytest.mark.parametrize("approximation", ["forward"])
def test_delayed_wall_dirichlet_bound(n, approximation):
    """G^-1 = b + z^-n K T/(z - 1): Re = b - K T sin((n + 1/2) theta)/(2 sin(theta/2)), whose
    minimum -K T (n + 1/2) is the limit theta -> 0, at the pole z = 1."""
    K, T = R(3), R(1, 100)
    bound = K * T * (n + R(1, 2))
    # at the bound itself the minimum 0 is a limit (uncertain), but for n = 0 G^-1 = KT(z+1)/(2(z-1))
    # is lossless, Re G^-1 = 0 identically, which the oracle recognises exactly
    for factor, want in ((1 + R(1, 10**9), "yes"), (1 - R(1, 10**9), "no"), (1, "yes" if n == 0 else "uncertain")):
        result = single_user_positive_real(b=bound * factor, T=T, H=K + 0 * z, approximation=approximation, delay=n)
        assert result.verdict == want, result.summary()


@settings(max_examples=examples(0.5), deadline=None)
@given(K=st.integers(0, 50), B=st.integers(0, 5), n=st.integers(0, 3), b=st.integers(1, 400),
       approximation=st.sampled_from(["forward", "backward", "tustin"]))
def test_one_user_matrix_oracle_agrees_with_scalar_oracle(K, B, n, b, approximation):
    T = R(1, 100)
    b = R(b, 1000)
    scalar = single_user_positive_real(b=b, T=T, H=K + B * (z - 1) / (T * z), approximation=approximation, delay=n)
    matrix = multi_user_positive_real(b=[b], T=T, K0=[K], B0=[B], delays=[n], approximation=approximation)
    if scalar.decided and matrix.decided:
        assert scalar.verdict == matrix.verdict, (scalar.summary(), matrix.summary())


# ---------------------------------------------------------------------------------------------
# continuous time
# ---------------------------------------------------------------------------------------------

ISSUE_Z = 1 - 2 / (s + 1) + R(10) / (s + 10**4)


@pytest.mark.parametrize("Zm, want", [
    ([[s + 1]], "yes"),
    ([[1 / (s**2 + 1)]], "no"),                       # residue -j/2 at s = j: not Hermitian PSD
    ([[s / (s**2 + 1) + 1]], "yes"),
    ([[1 / s**2 + 1]], "no"),                         # double pole at 0
    ([[s**2 + 1]], "no"),                             # double pole at infinity
    ([[ISSUE_Z]], "no"),                              # Re Z(j0) = -0.999 (issue 10)
    ([[(s - 1) / (s + 1)]], "no"),                    # Re = (w^2 - 1)/(w^2 + 1)
    ([[2, 1], [1, 2]], "yes"),
    ([[1, 2], [2, 1]], "no"),
    ([[1 + 1 / s, 1 / s], [1 / s, 1 + 1 / s]], "yes"),  # residue [[1, 1], [1, 1]] PSD, rank 1
    ([[1 + 1 / s, 2 / s], [2 / s, 1 + 1 / s]], "no"),   # residue [[1, 2], [2, 1]] indefinite
    ([[1, 1 / s], [-1 / s, 1]], "no"),                # residue [[0, 1], [-1, 0]] not Hermitian
])
def test_continuous_known_answers(Zm, want):
    assert positive_real_matrix(sp.Matrix(Zm)).verdict == want


@pytest.mark.parametrize("Zm, want", [
    ([[9 / (s + 3), -1 / (s + 1)], [-1 / (s + 1), 1 / (s + 3)]], "yes"),  # 3-DOF paper eq. (5): eta_min = 1
    ([[1, 3], [-5, 1]], "yes"),
    ([[1, 3], [5, 1]], "no"),
    ([[ISSUE_Z, 0], [0, 1]], "no"),
    ([[1, 1 / (s - 1)], [0, 1]], "no"),                                    # open-circuit unstable
])
def test_llewellyn_known_answers(Zm, want):
    assert llewellyn(sp.Matrix(Zm)).verdict == want


@settings(max_examples=examples(2.0), deadline=None)
@given(roots=st.lists(st.tuples(st.integers(-9, 9), st.integers(0, 9)), min_size=1, max_size=4),
       lead=st.integers(1, 5))
def test_routh_count_matches_roots(roots, lead):
    poly = sp.Integer(lead)
    for re, im in roots:
        poly *= (s - re) if im == 0 else (s**2 - 2 * re * s + re**2 + im**2)
    coeffs = [Fraction(int(c)) for c in sp.Poly(sp.expand(poly), s).all_coeffs()]
    count = routh_rhp_count(coeffs)
    expected = sum((1 if im == 0 else 2) for re, im in roots if re > 0)
    if count is not None:
        assert count == expected
    else:  # a singular array: only when some root lies on the axis or roots are symmetric about 0
        assert any(re == 0 for re, _ in roots) or any(r1 == -r2 for r1, _ in roots for r2, _ in roots)


def test_issue_counterexample_is_found_and_checked():
    Zm = sp.Matrix([[ISSUE_Z, 0], [0, 1]])
    found = find_destabilizing_termination(Zm)
    assert found.verdict == "no"
    assert check_termination(Zm, found.details["terminations"]).verdict == "yes"
    assert check_termination(Zm, [sp.Matrix([[2]]), sp.Matrix([[1]])]).verdict == "no"  # 2 ohm: stable


def test_absolute_stability_routes():
    assert absolute_stability(sp.Matrix([[2, -1, 0, 0], [-1, 2, 0, 0], [0, 0, 2, 0], [0, 0, 0, 2]]), (2, 2)).verdict == "yes"
    # D S D^-1 with S = [[2, 1], [1, 2]] (positive real) and D = diag(1, 3): non-reciprocal, stable
    result = absolute_stability(sp.Matrix([[2, R(1, 3)], [3, 2]]), search=False)
    assert result.verdict == "yes" and result.details["route"].startswith("Z = D S D^-1")
