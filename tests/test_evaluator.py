"""The compiled exact evaluator and the flint canonical forms, against SymPy's own evaluation.

Every fast path must give exactly what SymPy gives: values at rational points (parameters,
zeros and poles included), truth of relations, zero tests, SymPy's canonical numerator and
denominator (``sfield``) and polynomial conversions into flint rings.
"""

from __future__ import annotations

import random

import flint
import pytest
import sympy as sp
from hypothesis import given, settings
from hypothesis import strategies as st
from sympy.polys.fields import sfield

from hapticproof.exact.canonical import (
    Sampler,
    canonical_fraction,
    canonical_rational,
    evaluate_at,
    is_identically_zero,
)
from hapticproof.exact.evaluator import (
    NotAtRationalPoint,
    RationalProgram,
    is_zero_rational,
    rational_quotient,
    relation_at,
)
from hapticproof.exact.psd import PolyRing

K = sp.Symbol("K", positive=True)
T = sp.Symbol("T", positive=True)
B = sp.Symbol("B", nonnegative=True)
b = sp.Symbol("b")
c = sp.Symbol("c", real=True)
n = sp.Symbol("n", integer=True, nonnegative=True)
SYMBOLS = (K, T, B, b, c, n)


def random_expression(rng: random.Random, depth: int) -> sp.Expr:
    """A random rational expression of the symbols (sums, products, integer powers, quotients)."""
    if depth == 0 or rng.random() < 0.25:
        if rng.random() < 0.4:
            return sp.Rational(rng.randint(-6, 6), rng.randint(1, 5))
        return rng.choice(SYMBOLS)
    op = rng.choice(("add", "sub", "mul", "pow", "div"))
    left, right = random_expression(rng, depth - 1), random_expression(rng, depth - 1)
    if op == "add":
        return left + right
    if op == "sub":
        return left - right
    if op == "mul":
        return left * right
    if op == "pow":
        return left ** rng.randint(-3, 4)
    return left / right if right != 0 else left


def random_point(rng: random.Random, symbols=SYMBOLS) -> dict:
    """Exact rational values, zero often (so that poles are hit)."""
    return {s: sp.Rational(rng.choice((0, 0, 1, -1, 2, rng.randint(-30, 30))), rng.randint(1, 7)) for s in symbols}


def reference_value(expr: sp.Expr, point: dict):
    """SymPy's own evaluation (what ``evaluate_at`` did before it compiled expressions)."""
    try:
        value = expr.xreplace(point)
        if value.has(sp.zoo, sp.nan, sp.oo, -sp.oo):
            return None
        if not value.is_Rational and not value.free_symbols:
            value = sp.cancel(value)
        return None if value.has(sp.zoo, sp.nan) else value
    except (ZeroDivisionError, TypeError):
        return None


EXPRESSIONS = [e for e in (random_expression(random.Random(seed), 5) for seed in range(400))
               if isinstance(e, sp.Expr) and not e.has(sp.zoo, sp.nan)]


@pytest.mark.parametrize("seed", range(0, 400, 7))
def test_program_equals_sympy_at_rational_points(seed):
    rng = random.Random(seed)
    expr = EXPRESSIONS[seed % len(EXPRESSIONS)]
    program = RationalProgram.compile(expr)
    assert program is not None
    poles = 0
    for _ in range(40):
        point = random_point(rng)
        expected = reference_value(expr, point)
        try:
            got = program.at(point)
        except ZeroDivisionError:
            poles += 1
            # at a pole of a sub-expression the caller falls back to SymPy's rules
            assert evaluate_at(expr, point) == expected
            continue
        assert got == expected, (expr, point)
        assert evaluate_at(expr, point) == expected
    assert poles < 40


def test_evaluate_at_keeps_sympys_rules_at_poles_and_other_values():
    x, y = sp.symbols("x y")
    assert evaluate_at(1 / (1 + 1 / x), {x: sp.Integer(0)}) == 0         # zoo rules: 1/(1 + zoo) = 0
    assert evaluate_at(x / y, {x: sp.Integer(0), y: sp.Integer(0)}) is None
    assert evaluate_at(x**-2 * 0 + y, {y: sp.Integer(3)}) == 3
    assert evaluate_at(x + y, {x: sp.Integer(1)}) == 1 + y                # a free symbol stays
    assert evaluate_at(x + y, {x: 1, y: sp.Rational(1, 2)}) == sp.Rational(3, 2)   # plain ints: SymPy's path
    assert evaluate_at(x * y, {x * y: sp.Integer(5)}) == 5                # a key that is not a symbol
    assert evaluate_at(sp.sqrt(x) + 1, {x: sp.Integer(4)}) == 3
    assert evaluate_at(sp.Float(0.5) * x, {x: sp.Integer(2)}) == sp.Float(1.0)


def test_values_and_refusals():
    x = sp.Symbol("x")
    program = RationalProgram.compile(x**3 - x / 2)
    assert program.value({x: sp.Rational(1, 3)}) == flint.fmpq(1, 27) - flint.fmpq(1, 6)
    with pytest.raises(NotAtRationalPoint):
        program.value({x: sp.Float(0.5)})
    with pytest.raises(NotAtRationalPoint):
        program.value({})
    assert RationalProgram.compile(sp.cos(x)) is None
    assert RationalProgram.compile(sp.I * x) is None
    assert RationalProgram.compile(sp.Matrix([x])) is None
    assert RationalProgram.compile(sp.Integer(0)).at({}) == 0


def test_shared_subexpressions_are_evaluated_once():
    x = sp.Symbol("x")
    inner = (x + 1) ** 2
    program = RationalProgram.compile(inner * (inner + 3) + 1 / inner)
    assert program.at({x: sp.Integer(1)}) == 4 * 7 + sp.Rational(1, 4)
    with pytest.raises(ZeroDivisionError):
        program.at({x: sp.Integer(-1)})


@pytest.mark.parametrize("seed", range(0, 400, 9))
def test_relation_at_equals_sympy(seed):
    rng = random.Random(seed)
    lhs, rhs = EXPRESSIONS[seed % len(EXPRESSIONS)], EXPRESSIONS[(seed * 7 + 3) % len(EXPRESSIONS)]
    for relation in (sp.Gt, sp.Ge, sp.Lt, sp.Le, sp.Eq, sp.Ne):
        rel = relation(lhs, rhs, evaluate=False)
        for _ in range(10):
            point = random_point(rng)
            fast = relation_at(rel, point)
            if fast is None:
                continue
            assert fast == bool(rel.xreplace(point)), (rel, point)


def test_is_zero_rational_equals_the_field():
    checked = 0
    for expr in EXPRESSIONS[:160]:
        fast = is_zero_rational(expr)
        if fast is None:
            continue
        try:
            _, element = sfield(expr)
        except ZeroDivisionError:
            continue
        assert fast == (element == 0), expr
        checked += 1
    x, y = sp.symbols("x y")
    identity = (x**2 - y**2) / (x - y) - x - y + 1 / (x * y) - 1 / (y * x)
    assert is_zero_rational(identity) is True and is_identically_zero(identity)
    assert is_zero_rational(x / (x * (y + 1) - x * y - x)) is None       # an identically zero denominator
    assert checked > 120


def test_canonical_forms_are_sympys_field_elements():
    checked = 0
    for expr in EXPRESSIONS[160:320]:
        if not expr.free_symbols:
            continue
        try:
            _, element = sfield(expr)
        except ZeroDivisionError:
            continue
        assert canonical_fraction(expr) == (element.numer.as_expr(), element.denom.as_expr()), expr
        assert canonical_rational(expr) == element.as_expr(), expr
        checked += 1
    assert checked > 120


def test_rational_quotient_values():
    rng = random.Random(3)
    checked = 0
    for expr in EXPRESSIONS[:150]:
        found = rational_quotient(expr, SYMBOLS)
        if found is None:
            continue
        num, den = found
        assert num.is_zero() or num.gcd(den).is_one()
        for _ in range(5):
            point = random_point(rng)
            values = [flint.fmpq(int(point[s].p), int(point[s].q)) for s in SYMBOLS]
            expected = reference_value(expr, point)
            d = den(*values)
            if expected is None or d == 0:
                continue
            assert num(*values) / d == flint.fmpq(int(expected.p), int(expected.q))
            checked += 1
    assert checked > 100


@settings(max_examples=60, deadline=None)
@given(st.integers(0, 10**6))
def test_polyring_conversion_equals_expand(seed):
    rng = random.Random(seed)
    params = (K, T, b)
    terms = [rng.choice((*params, c, sp.Rational(rng.randint(-5, 5), rng.randint(1, 3)))) for _ in range(6)]
    expr = (terms[0] * c + terms[1]) ** rng.randint(0, 3) * (terms[2] - terms[3] * c**2) + terms[4] * terms[5]
    ring = PolyRing.over(params)
    poly = sp.Poly(sp.expand(expr), *ring.symbols)
    expected = ring.ctx.from_dict({m: flint.fmpq(int(a.p), int(a.q)) for m, a in poly.terms()})
    assert ring.from_expr(expr) == expected
    numeric = PolyRing.over(())
    at = expr.xreplace({K: 2, T: sp.Rational(1, 3), b: -1})
    assert numeric.from_expr(at) == flint.fmpq_poly([flint.fmpq(int(a.p), int(a.q))
                                                     for a in sp.Poly(sp.expand(at), c).all_coeffs()[::-1]])


def test_sampler_values_are_the_documented_sequence():
    """The sample points are part of the audit's evidence (witnesses): the sequence is fixed."""
    assert Sampler([K, b, c, n], seed=1).draw(3) == [
        {K: 1, b: -1, c: sp.Rational(1, 2), n: 1},
        {K: 2, b: sp.Rational(1, 3), c: -1, n: 2},
        {K: sp.Rational(1, 2), b: -5, c: 1, n: 3}]
    assert Sampler([K], seed=2, ranges={K: (1, 3)}).draw(2) == [{K: 2}, {K: sp.Rational(739, 250)}]


def _canonical_theta_by_sympy(expr, omega, T, t_d, n, var):
    """The SymPy route of canonical_theta, written out (the reference of its flint route)."""
    from hapticproof.core.symbols import cos_n, sin_n, sin_theta

    theta = sp.Dummy("theta", real=True)
    e = sp.sympify(expr).subs(t_d, n * T).subs(omega, theta / T)
    e = sp.expand(sp.expand_trig(sp.expand(e)))
    e = e.subs({sp.cos(n * theta): cos_n, sp.sin(n * theta): sin_n}).subs({sp.cos(theta): var, sp.sin(theta): sin_theta})
    num, den = sp.fraction(sp.together(sp.expand(e)))

    def reduce_sin(p):
        out = sp.Integer(0)
        for (power,), coeff in sp.Poly(sp.expand(p), sin_theta).terms():
            out += coeff * (1 - var**2) ** (power // 2) * sin_theta ** (power % 2)
        return sp.expand(out)

    return sp.expand(sp.cancel(reduce_sin(num) / reduce_sin(den)))


@pytest.mark.parametrize("seed", range(40))
def test_canonical_theta_equals_the_sympy_route(seed):
    from hapticproof.core.symbols import c as C_SYM
    from hapticproof.exact.unitcircle import canonical_theta

    w, t_d = sp.symbols("omega t_d", positive=True)
    rng = random.Random(seed)
    angles = [w * T, w * t_d, w * (t_d + T), w * (t_d - T), 2 * w * t_d, 3 * w * T, w * (2 * t_d - 3 * T), w * (3 * t_d + T)]

    def trig():
        return rng.choice((sp.cos, sp.sin))(rng.choice(angles))

    def term():
        factors = [rng.choice((K, B, b, sp.Rational(rng.randint(-4, 4), rng.randint(1, 3))))]
        factors += [trig() ** rng.randint(1, 3) for _ in range(rng.randint(0, 2))]
        return sp.Mul(*factors)

    expr = sp.Add(*[term() for _ in range(rng.randint(1, 4))])
    if seed % 3 == 0:
        expr = expr / (K + sp.cos(rng.choice(angles[:3] + angles[4:5])) * rng.choice((1, b)))
    n = sp.Symbol("n", integer=True)
    assert canonical_theta(expr, w, T, t_d, n) == _canonical_theta_by_sympy(expr, w, T, t_d, n, C_SYM)


def test_cancel_is_sympys_cancel():
    from hapticproof.exact.canonical import cancel

    x, y, z = sp.symbols("x y z")
    rho = sp.Symbol("rho", positive=True)
    rng = random.Random(0)
    checked = 0
    for _ in range(150):
        e = sum(rng.randint(-3, 3) * rng.choice([x, y, rho, x * y, rho**2, 1]) ** rng.randint(0, 2) for _ in range(3))
        f = sum(rng.randint(-3, 3) * rng.choice([x, y, rho, x * z, 1]) ** rng.randint(0, 2) for _ in range(3))
        if f == 0:
            continue
        for q in (e / f, e * f / (f**2 + x), (e + 1) / (2 * f), e / 6 + f / 4):
            assert cancel(q) == sp.cancel(q), q
            checked += 1
    for expr in EXPRESSIONS[320:]:
        assert cancel(expr) == sp.cancel(expr), expr
    assert cancel(sp.sqrt(x) / x) == sp.cancel(sp.sqrt(x) / x)          # SymPy's route
    assert cancel(sp.Rational(3, 4)) == sp.Rational(3, 4)
    assert checked > 400
