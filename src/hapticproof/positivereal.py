r"""Discrete positive-realness of scalar transfer functions (Definition 2 of the HVE paper).

``F(z)`` is positive real when (i) its poles lie in ``|z| <= 1``; (ii) ``Re F(e^{jwT}) >= 0``
wherever defined; (iii) its poles on ``|z| = 1`` are simple with positive semidefinite
residues. For a pole ``z0 = e^{j theta0}`` other than ``z0 = 1`` the quantity that must be
non-negative is ``Res(F, z0)/z0`` (e.g. ``(z - 1)/(z + 1)``, the image of ``s`` under the
bilinear map, is positive real with residue ``-2`` at ``z = -1``); at ``z0 = 1`` it is the
residue itself, as the paper states.

The Hermitian part is an exact rational function of ``c = cos(wT)`` (:mod:`unitcircle`); the
worst case over ``w`` is its exact minimum over ``c`` in ``[-1, 1]``: a certified decision by
root isolation when every parameter is a number, an endpoint/stationary-point analysis under
the parameters' sign assumptions otherwise.

>>> from hapticproof.scene import SingleUserScene
>>> scene = SingleUserScene.virtual_wall(K=2, B=0, b="0.0012", T="0.001")
>>> worst_case(scene).decision.value, worst_case(scene).minimiser
('proved', -1)
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

import flint
import sympy as sp

from hapticproof.evidence import Decision, Evidence, Method, Outcome
from hapticproof.lazy import stage
from hapticproof.models import environment_path, inverse_transfer
from hapticproof.realroots import minimise_rational, nonnegative_on, real_roots
from hapticproof.scene import SingleUserScene
from hapticproof.symbols import c as C_SYM
from hapticproof.symbols import z as Z_SYM
from hapticproof.unitcircle import (
    CRational,
    ThetaForm,
    hermitian_part_rational,
    numerator_denominator,
    theta_form,
)

__all__ = [
    "Pole",
    "Residue",
    "WorstCase",
    "poles_of",
    "unit_circle_residues",
    "hermitian_of",
    "decide_hermitian",
    "symbolic_minimum",
    "poles",
    "residues",
    "hermitian",
    "worst_case",
    "positive_real",
]


@dataclass(frozen=True, slots=True)
class Pole:
    """A pole of a transfer function: exact location (when known), multiplicity and where it
    lies: ``'inside'``, ``'on'`` (the unit circle) , ``'outside'`` or ``'unknown'``."""

    value: sp.Expr
    multiplicity: int
    location: str


@dataclass(frozen=True, slots=True)
class Residue:
    """Residue at a unit-circle pole ``z0``; ``scaled = residue/z0`` must be real and >= 0."""

    pole: sp.Expr
    residue: sp.Expr
    scaled: sp.Expr
    outcome: Outcome


@dataclass(frozen=True, slots=True)
class WorstCase:
    """Worst case of ``Re F`` over frequency.

    ``outcome`` decides ``Re F >= 0 for all w``; ``condition`` is the equivalent condition on the
    parameters (a SymPy relational, ``True``/``False`` when numeric); ``minimiser`` is the ``c``
    where the minimum is attained (exact or an isolated root) and ``minimum`` its value.
    """

    outcome: Outcome
    condition: Any
    minimiser: Any = None
    minimum: Any = None

    @property
    def decision(self) -> Decision:
        return self.outcome.decision


# ---------------------------------------------------------------------------------------------
# generic functions of a transfer function expression
# ---------------------------------------------------------------------------------------------


def _location(value: sp.Expr) -> str:
    modulus = sp.Abs(value)
    if not value.free_symbols:
        if value == 0:
            return "inside"
        # exact test first: |z0|^2 - 1 simplifies to zero for unit-circle algebraic numbers
        gap = sp.nsimplify(sp.expand(value * sp.conjugate(value)) - 1)
        if gap == 0:
            return "on"
        numeric = sp.N(gap, 50)
        if numeric.is_number and abs(numeric) > sp.Float(10) ** -40:
            return "inside" if numeric < 0 else "outside"
        return "unknown"
    lt = (modulus - 1).is_negative
    if lt:
        return "inside"
    if sp.simplify(modulus - 1) == 0:
        return "on"
    if (modulus - 1).is_positive:
        return "outside"
    return "unknown"


def poles_of(F: Any, z: sp.Symbol = Z_SYM) -> list[Pole]:
    """Poles of ``F`` (after cancellation) with their location relative to the unit circle.

    >>> from hapticproof.symbols import z
    >>> [(p.value, p.multiplicity, p.location) for p in poles_of(3 + 2/(z - 1) + 1/z**2)]
    [(0, 2, 'inside'), (1, 1, 'on')]
    """
    P, Q = numerator_denominator(sp.cancel(sp.sympify(F)), z)
    roots = sp.roots(Q, z)
    out: list[Pole] = []
    if sum(roots.values()) != Q.degree():
        # not all roots in closed form: numeric coefficients are still decided exactly
        if Q.free_symbols - {z}:
            return [Pole(sp.nan, Q.degree(), "unknown")]
        roots = _all_roots(Q)
    for value, multiplicity in sorted(roots.items(), key=lambda kv: (sp.default_sort_key(kv[0]))):
        out.append(Pole(sp.nsimplify(value) if value.is_number else value, int(multiplicity), _location(value)))
    return out


def _all_roots(Q: sp.Poly) -> dict[sp.Expr, int]:
    out: dict[sp.Expr, int] = {}
    for factor, multiplicity in sp.factor_list(Q.as_expr())[1]:
        for root in sp.Poly(factor, Q.gens[0]).all_roots():
            out[root] = out.get(root, 0) + multiplicity
    return out


def unit_circle_residues(F: Any, poles: list[Pole], z: sp.Symbol = Z_SYM) -> list[Residue]:
    """Residues at the poles on ``|z| = 1`` and their positivity (simple poles only).

    >>> from hapticproof.symbols import z
    >>> [(r.pole, r.residue, r.outcome.decision.value) for r in unit_circle_residues((z - 1)/(z + 1), poles_of((z - 1)/(z + 1)))]
    [(-1, -2, 'proved')]
    """
    out: list[Residue] = []
    for pole in poles:
        if pole.location != "on":
            continue
        if pole.multiplicity > 1:
            outcome = Outcome(
                Decision.DISPROVED,
                Evidence(Method.CANONICAL_FORM, facts={"pole": pole.value, "multiplicity": pole.multiplicity}),
                f"the unit-circle pole z = {pole.value} is not simple",
            )
            out.append(Residue(pole.value, sp.nan, sp.nan, outcome))
            continue
        residue = sp.cancel(sp.limit((z - pole.value) * sp.cancel(F), z, pole.value))
        scaled = sp.simplify(residue / pole.value)
        out.append(Residue(pole.value, residue, scaled, _sign_outcome(scaled, f"Res/z0 at z0 = {pole.value}")))
    return out


def _sign_outcome(value: sp.Expr, what: str) -> Outcome:
    value = sp.simplify(value)
    if value.is_real is False or (value.is_number and sp.im(value) != 0):
        return Outcome(Decision.DISPROVED, Evidence(Method.CANONICAL_FORM, facts={"value": value}), f"{what} = {value} is not real")
    if value.is_nonnegative:
        return Outcome(Decision.PROVED, Evidence(Method.CANONICAL_FORM, facts={"value": value}), f"{what} = {value} >= 0")
    if value.is_negative:
        return Outcome(Decision.DISPROVED, Evidence(Method.CANONICAL_FORM, witness={"value": value}), f"{what} = {value} < 0")
    return Outcome(
        Decision.SYMBOLIC,
        Evidence(Method.CANONICAL_FORM, facts={"condition": sp.Ge(value, 0)}),
        f"{what} >= 0 requires {sp.sstr(value)} >= 0",
    )


def hermitian_of(F: Any, z: sp.Symbol = Z_SYM) -> CRational:
    """``Re F(e^{jwT})`` as an exact rational function of ``c`` (see :mod:`unitcircle`)."""
    return hermitian_part_rational(F, z)


def decide_hermitian(form: CRational) -> WorstCase:
    """Exact decision of ``Re F >= 0 on [-1, 1]`` for a numeric c-form, with the minimiser.

    The sign of ``num/den`` equals that of ``num*den`` wherever the function is finite, so the
    decision is one exact non-negativity test of ``num*den`` by root isolation; the witness is a
    rational ``c`` re-checked by exact evaluation.

    >>> from hapticproof.symbols import z
    >>> wc = decide_hermitian(hermitian_of(sp.Rational(1, 10) + 1/(z - 1) + sp.Rational(3, 10)/z))
    >>> wc.decision.value, wc.outcome.witness
    ('disproved', {'c': -1})
    """
    form = form.numeric()
    product = form.num * form.den
    result = nonnegative_on(product, -1, 1)
    minimum = minimiser = None
    if not real_roots_in(form.den):
        m = minimise_rational(form.num, form.den, -1, 1)
        minimiser, minimum = m.argmin, (m.exact if m.exact is not None else m.value)
    if result.holds:
        outcome = Outcome(
            Decision.PROVED,
            Evidence(Method.ROOT_ISOLATION, facts={"touches_zero": [str(r) for r in result.touches_zero], "degree": product.degree()}),
            "Re G^-1 >= 0 for all c in [-1, 1] (exact root isolation)",
            minimiser=minimiser,
            minimum=minimum,
        )
        return WorstCase(outcome, sp.true, minimiser, minimum)
    witness = result.witness
    value = form(witness)
    assert value < 0, "witness re-check failed"
    outcome = Outcome(
        Decision.DISPROVED,
        Evidence(Method.ROOT_ISOLATION, witness={"c": witness}, facts={"value_at_witness": value}),
        f"Re G^-1 = {value} < 0 at c = {witness}",
        minimiser=minimiser,
        minimum=minimum,
    )
    return WorstCase(outcome, sp.false, minimiser, minimum)


def real_roots_in(den: flint.fmpq_poly, lo: int = -1, hi: int = 1) -> bool:
    return den.degree() > 0 and bool(real_roots(den, lo, hi))


def symbolic_minimum(expr: sp.Expr, var: sp.Symbol = C_SYM) -> WorstCase:
    """Worst case of a symbolic ``Re F(c)`` over ``c`` in ``[-1, 1]`` by endpoint analysis.

    Exact when ``Re F`` is affine or concave-quadratic in ``c`` with a denominator that is a
    positive constant; the sign of the slope is taken from the symbols' assumptions
    (``positive=True`` ...), and when it is unknown the exact condition keeps ``|slope|``.

    >>> K, T, b = sp.symbols('K T b', positive=True)
    >>> B = sp.Symbol('B', nonnegative=True)
    >>> wc = symbolic_minimum(b - K*T/2 + B*C_SYM)
    >>> wc.condition, wc.minimiser
    (b >= B + K*T/2, -1)
    """
    num, den = sp.fraction(sp.cancel(sp.together(expr)))
    den_poly = sp.Poly(den, var)
    if den_poly.degree() > 0 or not (den.is_positive or den.is_negative):
        return _undecided_symbolic(expr, "the denominator depends on c or has an unknown sign")
    if den.is_negative:
        num, den = -num, -den
    poly = sp.Poly(sp.expand(num / den), var)
    degree = poly.degree()
    coeffs = {k: poly.coeff_monomial(var**k) for k in range(degree + 1)}
    if degree <= 0:
        cond = sp.Ge(poly.as_expr(), 0)
        return _symbolic(cond, None, poly.as_expr(), "constant in c")
    if degree == 1:
        alpha, beta = coeffs[0], coeffs[1]
        if beta.is_nonnegative:
            return _symbolic(_ge(alpha - beta), sp.Integer(-1), alpha - beta, "slope >= 0: minimum at c = -1")
        if beta.is_nonpositive:
            return _symbolic(_ge(alpha + beta), sp.Integer(1), alpha + beta, "slope <= 0: minimum at c = 1")
        return _symbolic(_ge(alpha - sp.Abs(beta)), None, alpha - sp.Abs(beta), "minimum at c = -sign(slope)")
    if degree == 2 and coeffs[2].is_nonpositive:
        low, high = poly.as_expr().subs(var, -1), poly.as_expr().subs(var, 1)
        cond = sp.And(_ge(low), _ge(high))
        return _symbolic(cond, None, sp.Min(low, high), "concave in c: minimum at an endpoint")
    return _undecided_symbolic(expr, f"degree {degree} in c with parameters: no closed-form minimum")


def _ge(expr: sp.Expr) -> sp.Basic:
    """``expr >= 0`` written as ``positive part >= negative part`` (readable bounds)."""
    expr = sp.expand(expr)
    pos = sp.Add(*[t for t in sp.Add.make_args(expr) if not t.could_extract_minus_sign()])
    neg = sp.Add(*[-t for t in sp.Add.make_args(expr) if t.could_extract_minus_sign()])
    return sp.Ge(pos, neg, evaluate=False)


def _symbolic(condition: Any, minimiser: Any, minimum: Any, reason: str) -> WorstCase:
    condition = sp.simplify(condition) if condition in (sp.true, sp.false) else condition
    outcome = Outcome(
        Decision.SYMBOLIC,
        Evidence(Method.ENDPOINT_ANALYSIS, facts={"condition": condition, "reason": reason}),
        reason,
        minimiser=minimiser,
        minimum=minimum,
    )
    return WorstCase(outcome, condition, minimiser, minimum)


def _undecided_symbolic(expr: sp.Expr, reason: str) -> WorstCase:
    outcome = Outcome(Decision.SYMBOLIC, Evidence(Method.ENDPOINT_ANALYSIS, facts={"reason": reason}), reason)
    return WorstCase(outcome, sp.Ge(sp.Function("min_c")(expr), 0))


# ---------------------------------------------------------------------------------------------
# stages of a single-user scene
# ---------------------------------------------------------------------------------------------


@stage("poles")
def poles(scene: SingleUserScene) -> list[Pole]:
    """Poles of ``G^{-1}(z)``. With a symbolic delay the delay adds only a pole at ``z = 0``."""
    if scene.delay.is_Symbol:
        listed = poles_of(environment_path(scene))
        others = [p for p in listed if p.value != 0]
        # multiplicity n + (that of the path at 0): unknown as a number, recorded as -1
        return [Pole(sp.Integer(0), -1, "inside")] + others
    return poles_of(inverse_transfer(scene))


@stage("residues")
def residues(scene: SingleUserScene) -> list[Residue]:
    """Residues of ``G^{-1}`` at its unit-circle poles (``z^{-n}`` is 1 at ``z = 1``)."""
    if scene.delay.is_Symbol:
        # z^-n is analytic and unimodular away from 0: residue of z^-n F at z0 is z0^-n Res(F)
        path = environment_path(scene)
        out = []
        for r in unit_circle_residues(path, poles_of(path)):
            if r.pole == 1:
                out.append(r)
            else:
                out.append(Residue(r.pole, r.residue * r.pole ** (-scene.delay), sp.nan,
                                   Outcome(Decision.UNDECIDED, Evidence(Method.CANONICAL_FORM),
                                           "residue at a unit-circle pole other than 1 with a symbolic delay")))
        return out
    return unit_circle_residues(inverse_transfer(scene), poles(scene))


@stage("hermitian")
def hermitian(scene: SingleUserScene) -> CRational | ThetaForm:
    """``Re G^{-1}(e^{jwT})``: a rational function of ``c`` (integer delay) or a theta-form
    (symbolic delay ``n``)."""
    if scene.delay.is_Symbol:
        return theta_form(scene.b - scene.z_a, environment_path(scene), scene.delay)
    return hermitian_of(inverse_transfer(scene))


@stage("worst_case")
def worst_case(scene: SingleUserScene) -> WorstCase:
    """Worst case over frequency of ``Re G^{-1}``: exact decision when numeric, endpoint
    analysis when symbolic (integer delay), instances of the theta-form otherwise."""
    form = hermitian(scene)
    if isinstance(form, ThetaForm):
        outcome = Outcome(
            Decision.SYMBOLIC,
            Evidence(Method.INSTANCES, facts={"reason": "symbolic delay: use worst_case_instances"}),
            "symbolic delay n: the worst case depends on n; see worst_case_instances",
        )
        return WorstCase(outcome, None)
    if scene.is_numeric:
        return decide_hermitian(form)
    return symbolic_minimum(form.expr())


@stage("positive_real")
def positive_real(scene: SingleUserScene) -> Outcome:
    """All three conditions of Definition 2 for ``G^{-1}``, combined."""
    pole_list = poles(scene)
    outside = [p for p in pole_list if p.location == "outside"]
    unknown = [p for p in pole_list if p.location == "unknown"]
    if outside:
        return Outcome(Decision.DISPROVED, Evidence(Method.CANONICAL_FORM, witness={"pole": outside[0].value}),
                       f"pole z = {outside[0].value} outside the unit circle")
    res = residues(scene)
    for r in res:
        if r.outcome.decision == Decision.DISPROVED:
            return r.outcome
    wc = worst_case(scene)
    decisions = [r.outcome.decision for r in res] + [wc.decision]
    if unknown or Decision.UNDECIDED in decisions:
        return Outcome(Decision.UNDECIDED, Evidence(Method.CANONICAL_FORM), "some condition could not be decided")
    if Decision.SYMBOLIC in decisions:
        conds = [r.outcome.evidence.facts.get("condition") for r in res if r.outcome.decision == Decision.SYMBOLIC]
        conds.append(wc.condition)
        return Outcome(Decision.SYMBOLIC, Evidence(Method.ENDPOINT_ANALYSIS, facts={"conditions": [c for c in conds if c is not None]}),
                       "positive real iff the residue and worst-case conditions hold")
    if wc.decision == Decision.DISPROVED:
        return wc.outcome
    return Outcome(Decision.PROVED, wc.outcome.evidence, "G^-1 is positive real: poles, residues and Hermitian part checked exactly",
                   minimiser=wc.minimiser, minimum=wc.minimum)
