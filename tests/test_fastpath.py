"""The numeric fast path and the closed-form long-delay prover.

Differential tests: the fast path gives the same four decisions as the SymPy path
(:func:`hapticproof.analysis.positivereal.positive_real`), every certificate re-verifies with the
independent checker (Sturm sequences on the monomial form, the transfer function evaluated at the
witness), and the Hermitian verdicts agree with a 50-digit mpmath evaluation of ``G^{-1}`` on the
circle -- near and exactly at the boundary, for tiny and huge scales and long delays. Sizes are
small here (``n <= 250``); the benchmarks run ``n = 10 000``.
"""

from __future__ import annotations

from fractions import Fraction

import flint
import mpmath
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from hapticproof.analysis import fastpath as fp
from hapticproof.exact import trigpoly
from hapticproof.exact.checker import check_certificate, check_certificates
from hapticproof.core.errors import SceneError
from hapticproof.core.evidence import Decision, to_jsonable
from hapticproof.core.lazy import clear
from hapticproof.analysis.positivereal import positive_real, transfer_polynomials
from hapticproof.exact.checker import certificates as _certificates
from hapticproof.exact.unitcircle import circle_real_part

F = Fraction


def wall(n=0, b=1, K=2, B="0.001", T="0.001", approximation="forward", z_a=0):
    return fp.NumericScene.virtual_wall(K=K, B=B, b=b, T=T, delay=n, approximation=approximation, z_a=z_a)


def decisions(outcome):
    return [c.decision for c in outcome.evidence.facts["conditions"]]


def reference(scene):
    sym = scene.to_scene()
    clear(sym)
    return positive_real(sym)


def certificates_ok(outcome) -> tuple[int, int]:
    results = check_certificates(to_jsonable(outcome.to_json()))
    assert all(r.ok for r in results), [r.reason for r in results if not r.ok]
    return len(results), sum(r.verified for r in results)


def re_g(scene, theta, digits=50):
    """Re G^-1(e^{j theta}) from the transfer polynomials, 50-digit mpmath (independent)."""
    P, Q = fp.transfer(scene)
    with mpmath.workdps(digits):
        z = mpmath.expj(theta)
        val = lambda p: sum(mpmath.mpf(int(c.p)) / int(c.q) * z**k for k, c in enumerate(p.coeffs()))
        return mpmath.re(val(P) / val(Q))


def test_polynomials_match_the_sympy_path():
    for approximation in ("forward", "backward", "tustin"):
        for n in (0, 1, 4):
            scene = wall(n=n, b="0.013", approximation=approximation, z_a="0.002")
            assert fp.transfer(scene) == transfer_polynomials(scene.to_scene())
    generic = fp.NumericScene(b=F(1, 50), T=F(1, 100), H=((F(3), F(-1), F(1, 2)), (F(1, 4), F(0), F(1))), delay=2)
    assert fp.transfer(generic) == transfer_polynomials(generic.to_scene())
    # read back from the SymPy scene: the same H(z), in lowest terms with a monic denominator
    assert fp.NumericScene.from_scene(generic.to_scene()).H == ((F(3), F(-1), F(1, 2)), (F(1, 4), F(0), F(1)))


@pytest.mark.parametrize("n", [0, 3, 10])
def test_decisions_around_the_boundary_match_positive_real(n):
    lo, hi = fp.critical_damping(wall(n=n))
    assert lo == hi                       # the worst case sits at c = +-1: exact
    for b in (lo * (1 + F(1, 100)), lo * (1 - F(1, 100)), lo * (1 + F(1, 10**9)), lo * (1 - F(1, 10**9)), lo):
        scene = wall(n=n, b=b)
        out = fp.decide(scene)
        assert decisions(out) == decisions(reference(scene))
        assert (out.decision == Decision.PROVED) == (b >= lo)
        certificates_ok(out)


@pytest.fixture
def chebyshev(monkeypatch):
    """Chebyshev certificates from degree 10 on (the default switch is at 200; the checker's
    Sturm sequences at that degree take a minute, so tests use smaller ones)."""
    monkeypatch.setattr(fp, "MONOMIAL_LIMIT", 10)


def test_long_delay_certificates_and_closed_form(chebyshev):
    n = 40
    lo, hi = fp.critical_damping(wall(n=n))
    kt, B = F(2, 1000), F(1, 1000)
    assert lo == hi == kt / 2 + kt * n - B            # delayed.py: the limit at c = 1 (B small)
    for b, holds in ((lo, True), (lo * (1 - F(1, 10**12)), False), (lo * (1 + F(1, 10**6)), True)):
        scene = wall(n=n, b=b)
        out = fp.decide(scene)
        assert (out.decision == Decision.PROVED) == holds
        assert decisions(out) == decisions(reference(scene))
        herm = out.evidence.facts["conditions"][-1].outcome
        assert type(herm.evidence.facts["certificate"]).__name__ == "ChebyshevCertificate"
        count, verified = certificates_ok(out)
        assert verified == count
        if not holds:   # the witness is a rational point of the circle where Re G^-1 < 0
            c, s = (F(v) for v in herm.witness["z"])
            assert c * c + s * s == 1 and re_g(scene, mpmath.atan2(s, c)) < 0


def test_ten_thousand_samples_decide_in_closed_form():
    n = 10_000
    lo, hi = fp.critical_damping(wall(n=n))
    assert lo == hi == F(2, 1000) * (n + F(1, 2)) - F(1, 1000)
    assert fp.decide(wall(n=n, b=lo), minimum=False).decision == Decision.PROVED
    assert fp.decide(wall(n=n, b=lo * (1 - F(1, 10**9))), minimum=False).decision == Decision.DISPROVED


def test_interior_zeros_touching_fall_back_to_the_kernel(chebyshev):
    # G^-1 = 1/2 + z^-31/2: Re = (1 + cos 31 theta)/2 >= 0 touches 0 at 16 irrational points,
    # which no finite cover of balls can prove: the kernel decides the monomial form
    scene = fp.NumericScene(b=F(1, 2), T=1, H=((F(-1, 2), F(1, 2)), (F(1),)), delay=31)
    out = fp.decide(scene)
    assert out.decision == Decision.PROVED
    assert "touches 0 at 16 points" in out.evidence.facts["conditions"][-1].outcome.reason
    assert decisions(out) == decisions(reference(scene))
    certificates_ok(out)


def test_above_the_checker_limit_it_says_so(monkeypatch, chebyshev):
    monkeypatch.setenv("HAPTICPROOF_CHECK_MAX_DEGREE", "20")
    out = fp.decide(wall(n=40, b=1))
    results = check_certificates(to_jsonable(out.to_json()))
    assert all(r.ok for r in results)
    assert any(not r.verified and "limit" in r.reason for r in results)


def test_tampered_chebyshev_certificate_is_rejected(chebyshev):
    out = fp.decide(wall(n=40, b=1))
    cert = next(c for c in _certificates(to_jsonable(out.to_json())) if c["certificate"] == "chebyshev-sign")
    assert check_certificate(cert).ok
    bad = dict(cert, numerator=["-1"] + cert["numerator"][1:])     # now negative at c = 0
    assert not check_certificate(bad).ok


@st.composite
def scenes(draw):
    approximation = draw(st.sampled_from(["forward", "backward", "tustin"]))
    n = draw(st.sampled_from([0, 1, 2, 5, 12, 30]))
    K = F(draw(st.integers(1, 500)), 100)
    B = F(draw(st.integers(0, 50)), 10**draw(st.integers(3, 5)))
    T = F(1, 10 ** draw(st.integers(2, 7)))
    z_a = F(draw(st.integers(0, 20)), 10**4)
    base = wall(n=n, K=K, B=B, T=T, approximation=approximation, z_a=z_a)
    lo, hi = fp.critical_damping(base)
    rel = draw(st.sampled_from([F(1, 10), F(-1, 10), F(1, 10**9), F(-1, 10**9), F(0)]))
    b = (hi if rel >= 0 else lo) * (1 + rel) + z_a
    return base.with_b(max(b, F(0)))


@settings(max_examples=15, deadline=None)
@given(scenes())
def test_random_scenes_match_positive_real_and_mpmath(scene):
    out = fp.decide(scene)
    assert decisions(out) == decisions(reference(scene))
    certificates_ok(out)
    herm = out.evidence.facts["conditions"][-1].outcome
    if herm.decision == Decision.DISPROVED:
        c, s = (F(v) for v in herm.witness["z"])
        assert re_g(scene, mpmath.atan2(s, c)) < 0
    else:   # a 50-digit sweep of Re G^-1 never goes below zero (beyond rounding)
        scale = abs(scene.b) + 1
        low = min(re_g(scene, mpmath.pi * (k + F(1, 2)) / 200, 40) for k in range(200))
        assert low > -scale * mpmath.mpf(10) ** -30


def test_generic_environments_with_poles_on_the_circle():
    # H with a pole at z = -1 (Res/z0 of G^-1 there decides), and a stable complex pair
    for H in (((F(1),), (F(1), F(1))), ((F(1), F(2)), (F(1, 2), F(-1), F(1)))):
        for n in (0, 3, 25):
            scene = fp.NumericScene(b=F(3, 10), T=F(1, 10), H=H, delay=n)
            assert decisions(fp.decide(scene)) == decisions(reference(scene))


def test_chebyshev_form_is_the_monomial_form():
    for scene in (wall(n=7, b="0.02"), wall(n=3, approximation="tustin", b="0.01"),
                  fp.NumericScene(b=1, T=1, H=((F(1), F(2)), (F(1, 2), F(-1), F(1))), delay=4)):
        form = fp.circle_form(scene)
        N, D = circle_real_part(*fp.transfer(scene))
        g, w = trigpoly.chebyshev_to_monomial(form.b), trigpoly.chebyshev_to_monomial(form.w)
        assert g * D == N * w


def test_minimum_enclosures():
    for n in (0, 3, 40):
        form = fp.circle_form(wall(n=n), a=0)
        m = trigpoly.minimum(form, tol=flint.fmpq(1, 10**12))
        exact = -fp.critical_damping(wall(n=n))[0]
        assert m.lower <= flint.fmpq(exact.numerator, exact.denominator) <= m.upper
        assert m.upper - m.lower <= flint.fmpq(1, 10**12)


def test_tiny_and_huge_scales():
    for K, T, B in ((F(10**9), F(1, 10**7), F(0)), (F(1, 1000), F(1), F(10**6)), (F(2), F(1, 10**9), F(1, 10**12))):
        for n in (0, 4):
            lo, hi = fp.critical_damping(wall(n=n, K=K, B=B, T=T))
            for b in (hi * (1 + F(1, 10**9)), lo * (1 - F(1, 10**9))):
                if b >= 0:
                    scene = wall(n=n, K=K, B=B, T=T, b=b)
                    assert decisions(fp.decide(scene)) == decisions(reference(scene))


def test_user_mistakes_are_scene_errors():
    with pytest.raises(SceneError, match="sampling period"):
        wall(T=0)
    with pytest.raises(SceneError, match="non-negative integer"):
        wall(n=-1)
    with pytest.raises(SceneError, match="not a number"):
        wall(b="ten")
    with pytest.raises(SceneError, match="approximation"):
        wall(approximation="euler")
