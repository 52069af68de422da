"""Classic conditions derived from their models (hapticproof.analysis.classics) and compared with the
published statements recorded with their sources."""

from __future__ import annotations

import cmath
import math

import pytest
import sympy as sp
from hypothesis import given, settings
from hypothesis import strategies as st

from hapticproof.analysis import boundary as bnd
from hapticproof.analysis import classics
from hapticproof.audit.runner import audit_paper
from hapticproof.audit.compare import compare_bounds
from hapticproof.audit.reader.names import SymbolTable
from hapticproof.audit.reader.printed import parse_printed
from hapticproof.analysis.positivereal import hermitian
from hapticproof.audit.registry import get_paper
from hapticproof.systems.singleuser import SYMBOLS, SingleUserScene, virtual_wall
from hapticproof.core.symbols import c, z
from hapticproof.systems.teleoperator import filtered_pd_controller

K, B, b, T, t_d = (SYMBOLS[k] for k in ("K", "B", "b", "T", "t_d"))
R = sp.Rational
CONTROLLERS = [
    virtual_wall(K, B, T),
    filtered_pd_controller(K, B, T, R(1, 3)),
    (z + R(1, 2)) / (z**2 - R(1, 4)) * 3,
    virtual_wall(2, R(1, 10), R(1, 100)) / z**2,                   # a delayed wall
]


def test_zoh_is_the_pulse_transform():
    s = sp.Symbol("s")
    assert sp.simplify(classics.zoh_transfer(s, T) - (1 - sp.exp(-s * T)) / s) == 0


@pytest.mark.parametrize("H", CONTROLLERS)
def test_leak_route_equals_colgate_and_the_circle_criterion(H):
    period = T if H.has(T) else sp.Rational(1, 10)
    leak = classics.leak_bound(H, period)
    assert sp.cancel(leak - classics.colgate_bound(H, period)) == 0
    # the HVE circle-criterion route: Re G_1^{-1} = b - bound (forward difference)
    circle = hermitian(SingleUserScene(b=b, T=period, H=H)).expr()
    assert sp.cancel(b - circle - leak) == 0


@settings(max_examples=25, deadline=None)
@given(theta=st.floats(0.05, 3.09), k=st.floats(0.1, 10), bb=st.floats(-2, 2), period=st.floats(1e-3, 0.5))
def test_colgate_bound_against_direct_complex_evaluation(theta, k, bb, period):
    bound = classics.colgate_bound(virtual_wall(K, B, T), T).subs({K: k, B: bb, T: period, c: math.cos(theta)})
    zz = cmath.exp(1j * theta)
    H = k + bb * (zz - 1) / (period * zz)
    direct = period / (2 * (1 - math.cos(theta))) * ((1 - 1 / zz) * H).real
    assert abs(float(bound) - direct) < 1e-9 * (1 + abs(direct))


def test_alias_weight_against_the_series():
    assert classics.check_alias_weight([(1, "0.1"), ("0.3", 2), ("-2.5", "0.7")]) < 1e-25


def test_colgate_wall_published_form():
    derived = classics.colgate_wall()
    Br = sp.Symbol("B", real=True)
    assert derived.rhs == K * T / 2 + sp.Abs(Br)
    table = SymbolTable({"K": K, "T": T, "b": b, "B": Br})
    published = parse_printed(r"b > \frac{KT}{2} + |B|", table).relations()[0].as_sympy()
    assert compare_bounds(published, derived, b).verdict.value == "confirmed"
    assert classics.colgate_wall(B=B).rhs == K * T / 2 + B              # HVE (3), B >= 0


def test_leading_order_for_every_delay_and_operator():
    n = SYMBOLS["n"]
    plain, with_operator = classics.leading_order_boundary(n), classics.leading_order_boundary(n, operator=True)
    a, d = sp.symbols("a d", positive=True)
    assert sp.simplify(plain.critical - 2 * (a + d) / (2 * n + 1)) == 0
    assert sp.simplify(with_operator.critical - plain.critical) == 0     # k_h drops out at leading order
    cond = classics.gil_linear_condition(n)
    assert sp.expand(cond.lhs - cond.rhs - (b + B - K * (T / 2 + t_d))) == 0


def test_minsky_condition_is_conservative_at_leading_order():
    bh, kh = classics.OPERATOR["b_h"], classics.OPERATOR["k_h"]
    minsky = sp.Gt(B + b + bh, (K + kh) * T / 2)
    leading = classics.leading_order_boundary(0, operator=True).condition
    assert compare_bounds(minsky, sp.Ge(leading.lhs, sp.expand(leading.rhs)), b).verdict.value == "conservative"


def test_sufficiency_expansion_against_the_exact_boundary():
    _, expansion = classics.gil_sufficiency_region()
    for alpha, delta in ((R(1, 1000), 0), (R(1, 1000), R(1, 1000)), (R(1, 2000), R(1, 4000))):
        exact = bnd.critical_stiffness(1, alpha, 1, delta).value        # m = T = 1: K = beta
        ratio = exact / float(2 * (alpha + delta))
        predicted = float(expansion.subs({bnd.ALPHA: alpha, bnd.DELTA: delta}))
        assert abs(ratio - predicted) < 10 * float(alpha + delta) ** 2


def test_sources_are_complete():
    for src in classics.SOURCES.values():
        assert src.authors and src.title and src.venue and 1950 < src.year < 2015 and src.statement
        assert str(src.year) in src.citation()


def test_published_statements_are_confirmed_by_the_derivations():
    report = audit_paper(get_paper("classics"))
    assert {r.id: r.verdict.value for r in report.results} == {
        "gil-2004-region": "confirmed", "colgate-frequency": "confirmed", "colgate-wall": "confirmed",
        "gil-2004": "confirmed", "gil-2009": "confirmed", "llewellyn": "confirmed"}


def test_a_misquoted_classic_is_not_confirmed():
    from dataclasses import replace

    from hapticproof.audit.runner import run_equation

    paper = get_paper("classics")
    wrong_2009 = replace(paper.get("gil-2009"), printed=r"K < \frac{b + B}{T + t_d}")
    assert run_equation(paper, wrong_2009).verdict.value != "confirmed"
    wrong_wall = replace(paper.get("colgate-wall"), printed=r"b > \frac{KT}{2} + B")
    assert run_equation(paper, wrong_wall).verdict.value != "confirmed"
