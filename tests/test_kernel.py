"""The decision kernel and the independent checker.

Sign decisions and root locations are compared with numpy on random exact inputs (with a
margin so that floating point is never asked to decide a boundary case), every certificate is
re-verified by the checker, and tampered certificates must be rejected: a checker that cannot
fail would prove nothing.
"""

from __future__ import annotations

import copy
from fractions import Fraction

import flint
import numpy as np
import pytest
from hypothesis import assume, given, settings
from hypothesis import strategies as st

from hapticproof.exact.checker import check_certificate, check_report
from hapticproof.core.evidence import to_jsonable
from hapticproof.exact.kernel import circle_point, axis_point, decide_psd, decide_rational_sign, decide_sign, locate_roots, residue_outcome, simplest_between

small = st.integers(-6, 6)
coefficient_lists = st.lists(small, min_size=2, max_size=7).filter(lambda c: c[-1] != 0)


def cert_of(outcome):
    return to_jsonable(outcome.evidence.facts)["certificate"]


def numpy_min(coeffs, lo, hi):
    """min of the polynomial on [lo, hi] by numpy (critical points and ends)."""
    p = np.polynomial.Polynomial([float(c) for c in coeffs])
    points = [lo, hi] + [r.real for r in p.deriv().roots() if abs(r.imag) < 1e-9 and lo <= r.real <= hi]
    return min(p(x) for x in points)


@settings(max_examples=80, deadline=None)
@given(coefficient_lists)
def test_sign_decisions_agree_with_numpy_and_the_checker(coeffs):
    out = decide_sign(flint.fmpq_poly(coeffs), -1, 1, variable="c")
    cert = cert_of(out)
    assert check_certificate(cert).ok
    low = numpy_min(coeffs, -1.0, 1.0)
    assume(abs(low) > 1e-9)                  # numpy decides only clear cases
    assert (out.decision.value == "proved") == (low > 0)


@settings(max_examples=60, deadline=None)
@given(coefficient_lists)
def test_half_line_decisions_agree_with_numpy(coeffs):
    out = decide_sign(flint.fmpq_poly(coeffs), 0, None, variable="x")
    assert check_certificate(cert_of(out)).ok
    lead_ok = coeffs[-1] > 0
    low = numpy_min(coeffs, 0.0, 1e6)
    assume(abs(low) > 1e-9)
    assert (out.decision.value == "proved") == (low > 0 and lead_ok)


def test_negative_stretch_next_to_zero_is_found():
    # issue 10: Z(s) = 1 - 2/(s+1) + 10/(s+10^4); the Hermitian polynomial is negative on
    # [0, first root) and the old route never tested that stretch
    out = decide_sign(flint.fmpq_poly([-99900000, 100099999, 1]), 0, None, variable="x")
    assert out.decision.value == "disproved" and out.witness["x"] == 0
    # a polynomial negative only between 0 and a tiny root
    p = flint.fmpq_poly([-1, 10**12])
    out = decide_sign(p * p * flint.fmpq_poly([-1, 10**12]), 0, None, variable="x")
    assert out.decision.value == "disproved"
    assert check_certificate(cert_of(out)).ok


def test_circle_witness_is_a_gaussian_rational_point_off_the_poles():
    c = flint.fmpq_poly([0, 1])
    out = decide_sign(c * c - flint.fmpq(1, 4), -1, 1)          # negative on (-1/2, 1/2)
    z_re, z_im = (Fraction(v) for v in out.witness["z"])
    assert z_re**2 + z_im**2 == 1 and abs(z_re) < Fraction(1, 2)
    # 1/(z - 1) - 1: the endpoint c = 1 is a pole of F; the witness must not be z = 1
    z = flint.fmpq_poly([0, 1])
    num, den = flint.fmpq_poly([-1, 0]) * 0 + flint.fmpq_poly([-1]), flint.fmpq_poly([1])
    out = decide_rational_sign(num, den, -1, 1, transfer={"variable": "z", "num": ["2", "-1"], "den": ["-1", "1"]},
                               transfer_den=z - 1)
    assert out.witness["z"] != ["1", "0"]
    assert check_certificate(cert_of(out)).ok


def test_simple_points():
    assert simplest_between(Fraction(1, 3), Fraction(1, 2)) == Fraction(2, 5)
    assert simplest_between(Fraction(-1, 2), Fraction(1, 3)) == 0
    point = circle_point(Fraction(9, 10), Fraction(91, 100))
    assert Fraction(9, 10) < point["c"] < Fraction(91, 100)
    assert point["z"][0] ** 2 + point["z"][1] ** 2 == 1
    w = axis_point(Fraction(10**-12), Fraction(2 * 10**-12))
    assert Fraction(10**-12) < w["x"] < Fraction(2 * 10**-12)


@settings(max_examples=60, deadline=None)
@given(st.lists(st.tuples(st.integers(-9, 9), st.integers(1, 5)), min_size=1, max_size=4))
def test_root_locations_agree_with_numpy(factors):
    # products of (a z + b)-type factors with rational roots a/b and random quadratics
    p = flint.fmpq_poly([1])
    for a, b in factors:
        p *= flint.fmpq_poly([-a, b])
    cert = locate_roots(p, "disk")
    assert check_certificate(cert.to_json()).ok
    # the roots a/b are known exactly: count them (repeated roots defeat numpy)
    assert cert.outside == sum(abs(Fraction(a, b)) > 1 for a, b in factors)
    assert sum(r.multiplicity for r in cert.boundary) == sum(abs(Fraction(a, b)) == 1 for a, b in factors)


@settings(max_examples=50, deadline=None)
@given(coefficient_lists)
def test_root_locations_of_random_polynomials(coeffs):
    p = flint.fmpq_poly(coeffs)
    roots = np.roots([float(c) for c in reversed(coeffs)])
    assume(all(abs(abs(r) - 1) > 1e-6 for r in roots))
    cert = locate_roots(p, "disk")
    assert check_certificate(cert.to_json()).ok
    assert cert.outside == sum(abs(r) > 1 for r in roots)
    assume(all(abs(r.real) > 1e-6 for r in roots))
    half = locate_roots(p, "halfplane")
    assert check_certificate(half.to_json()).ok
    assert half.outside == sum(r.real > 0 for r in roots)


def test_boundary_roots_and_multiplicities():
    z = flint.fmpq_poly([0, 1])
    cert = locate_roots((z - 1) ** 2 * (z * z + 1) * (2 * z - 1) * (z - 3))
    assert cert.outside == 1 and cert.inside == 1
    assert sorted((r.label(), r.multiplicity) for r in cert.boundary)[0] == ("1", 2)
    assert check_certificate(cert.to_json()).ok
    # a Salem-type factor: roots on and off the circle in one irreducible polynomial
    salem = flint.fmpq_poly([1, -1, 0, -1, 1])        # z^4 - z^3 - z + 1 = (z-1)^2 (z^2+z+1): reducible
    lehmer = flint.fmpq_poly([1, 1, 0, -1, -1, -1, -1, -1, 0, 1, 1])
    cert = locate_roots(lehmer)
    assert cert.outside == 1 and cert.inside == 1 and sum(2 for r in cert.boundary) == 8
    assert check_certificate(cert.to_json()).ok
    assert check_certificate(locate_roots(salem).to_json()).ok


def test_residues_at_unit_circle_poles():
    z = flint.fmpq_poly([0, 1])
    pair = locate_roots(z * z + 1).boundary[0]
    assert residue_outcome(z * z - 1, z * z + 1, pair).decision.value == "proved"
    assert residue_outcome(1 - z * z, z * z + 1, pair).decision.value == "disproved"
    assert residue_outcome(z, z * z + 1, pair).decision.value == "disproved"       # Res/z0 not real
    minus_one = locate_roots(z + 1).boundary[0]
    out = residue_outcome(z - 1, z + 1, minus_one)                                    # (z-1)/(z+1): +2
    assert out.decision.value == "proved" and check_certificate(cert_of(out)).ok


def test_psd_decisions_and_matrix_witness():
    c = flint.fmpq_poly([0, 1])
    # diag(1 + c, c): E_1 = 1 + 2c, E_2 = c + c^2 -> not PSD for c < 0
    import sympy as sp

    def at(witness):
        cv = sp.Rational(witness["c"].numerator, witness["c"].denominator)
        return sp.Matrix([[1 + cv, 0], [0, cv]])

    out = decide_psd([1 + 2 * c, c + c * c], -1, 1, evaluate=at)
    assert out.decision.value == "disproved"
    cert = cert_of(out)
    assert check_certificate(cert).ok and cert["negative_minor"]["value"].startswith("-")
    assert decide_psd([2 + 0 * c, 1 - c * c], -1, 1).decision.value == "proved"


# --- the checker must be able to fail ---------------------------------------------------------


def tampered_sign_certificates():
    p = flint.fmpq_poly([1, -2, 1])                       # (c - 1)^2 >= 0
    good = cert_of(decide_sign(p, -1, 1))
    two = cert_of(decide_sign(flint.fmpq_poly([-1, 0, 4]) ** 2, -1, 1))     # double roots at +-1/2
    middle = len(two["points"]) // 2
    yield "drop the point between two roots", dict(two, points=two["points"][:middle] + two["points"][middle + 1:])
    yield "claim for a negative polynomial", dict(good, polynomial=["-1", "0", "2"])
    yield "shift the interval", dict(good, interval=["-2", "1"])
    bad = cert_of(decide_sign(flint.fmpq_poly([-1, 0, 2]), -1, 1))
    yield "witness where it is positive", dict(bad, witness="1")
    yield "witness outside the interval", dict(bad, witness="3")
    yield "product mismatch", dict(cert_of(decide_rational_sign(p, p + 1, -1, 1)), denominator=["1"])
    tail = cert_of(decide_sign(flint.fmpq_poly([1, 0, 1]), 0, None, variable="x"))
    yield "negative at infinity", dict(tail, polynomial=["1", "0", "-1"])


@pytest.mark.parametrize("name,cert", list(tampered_sign_certificates()), ids=lambda v: v if isinstance(v, str) else "")
def test_checker_rejects_tampered_sign_certificates(name, cert):
    assert not check_certificate(cert).ok


def test_checker_rejects_tampered_root_and_residue_certificates():
    z = flint.fmpq_poly([0, 1])
    good = locate_roots((z - 2) * (z - 1)).to_json()
    assert check_certificate(good).ok
    assert not check_certificate(dict(good, outside=0)).ok
    assert not check_certificate(dict(good, boundary_count=2)).ok
    stable = locate_roots((2 * z - 1) * (z - 1)).to_json()
    assert not check_certificate(dict(stable, outside=1)).ok
    double = locate_roots((z - 1) ** 2).to_json()
    claim_simple = copy.deepcopy(double)
    claim_simple["boundary"][0]["multiplicity"] = 1
    assert check_certificate(double).ok and not check_certificate(claim_simple).ok
    res = cert_of(residue_outcome(z - 1, z + 1, locate_roots(z + 1).boundary[0]))
    assert check_certificate(res).ok
    assert not check_certificate(dict(res, scaled="-2", holds=False)).ok


def test_check_report_walks_saved_reports():
    out = decide_sign(flint.fmpq_poly([-1, 0, 2]), -1, 1)
    report = {"conditions": [{"name": "a", **to_jsonable(out.to_json())}, {"name": "b", "decision": "proved"}]}
    result = check_report(report)
    assert result.ok and "b: no certificate" in result.summary()
    report["conditions"][0]["evidence"]["facts"]["certificate"]["witness"] = "1"
    assert not check_report(report).ok
