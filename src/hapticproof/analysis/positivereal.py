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

>>> from hapticproof.systems.singleuser import SingleUserScene
>>> scene = SingleUserScene.virtual_wall(K=2, B=0, b="0.0012", T="0.001")
>>> worst_case(scene).decision.value, worst_case(scene).minimiser
('proved', -1)
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

import flint
import sympy as sp

from hapticproof.exact.canonical import cancel as exact_cancel
from hapticproof.core.evidence import Decision, Evidence, Method, Outcome, to_jsonable
from hapticproof.exact.kernel import decide_rational_sign, locate_roots, transfer_json
from hapticproof.core.lazy import stage
from hapticproof.systems.models import environment_path, inverse_transfer
from hapticproof.exact.realroots import flint_precision, minimise_rational, real_roots
from hapticproof.exact.rootcount import approximate_outside
from hapticproof.systems.singleuser import SingleUserScene
from hapticproof.core.symbols import c as C_SYM
from hapticproof.core.symbols import z as Z_SYM
from hapticproof.exact.unitcircle import CRational, ThetaForm, circle_real_part, hermitian_part_rational, numerator_denominator, theta_form
from hapticproof.exact.conditions import HERMITIAN, RESIDUES, Condition, POLES_IN_DISK, POLES_SIMPLE, combine, pole_conditions, properness_condition

__all__ = ["conditions", "transfer_polynomials", "numeric_scene", "Pole", "Residue", "WorstCase", "poles_of", "unit_circle_residues", "hermitian_of", "decide_hermitian", "symbolic_minimum", "bernstein_sign", "symbolic_c_degree", "SYMBOLIC_CFORM_LIMIT", "poles", "residues", "hermitian", "worst_case", "positive_real", "definition_object", "pole_location_outcome", "named_conditions"]


@dataclass(frozen=True, slots=True)
class Pole:
    """A pole of a transfer function: exact location (when known), multiplicity and where it
    lies: ``'inside'``, ``'on'`` (the unit circle) , ``'outside'`` or ``'unknown'``."""

    value: sp.Expr
    multiplicity: int
    location: str
    #: the multiplicity as a formula when it is not a number (``n + 1`` with a symbolic delay
    #: ``n``; ``multiplicity`` is then -1)
    formula: str | None = None


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
    if exact_cancel(sp.expand(modulus - 1)) == 0:      # (no simplify: it loads sympy.physics on first use)
        return "on"
    if (modulus - 1).is_positive:
        return "outside"
    return "unknown"


def poles_of(F: Any, z: sp.Symbol = Z_SYM) -> list[Pole]:
    """Poles of ``F`` (after cancellation) with their location relative to the unit circle.

    >>> from hapticproof.core.symbols import z
    >>> [(p.value, p.multiplicity, p.location) for p in poles_of(3 + 2/(z - 1) + 1/z**2)]
    [(0, 2, 'inside'), (1, 1, 'on')]
    """
    P, Q = numerator_denominator(exact_cancel(sp.sympify(F)), z)
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

    >>> from hapticproof.core.symbols import z
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
        residue = _simple_residue(F, pole.value, z)
        scaled = _tidy_value(residue / pole.value)
        out.append(Residue(pole.value, residue, scaled, _sign_outcome(scaled, f"Res/z0 at z0 = {pole.value}")))
    return out


def _simple_residue(F: Any, z0: Any, z: sp.Symbol) -> sp.Expr:
    """The residue of ``F`` at a simple pole ``z0``: ``P(z0)/Q'(z0)`` for ``F = P/Q`` rational in
    ``z`` with a rational pole (no limit taken), else the limit of ``(z - z0) F``."""
    F = exact_cancel(sp.sympify(F))
    if sp.sympify(z0).is_Rational:
        num, den = sp.fraction(sp.together(F))
        try:
            P, Q = sp.Poly(num, z), sp.Poly(den, z)
        except sp.PolynomialError:
            P = Q = None
        if P is not None and Q.eval(z0) == 0 and Q.diff(z).eval(z0) != 0:
            return exact_cancel(P.eval(z0) / Q.diff(z).eval(z0))
    return exact_cancel(sp.limit((z - z0) * F, z, z0))


def _tidy_value(value: Any) -> sp.Expr:
    """A value in canonical form: cancelled when its numbers are rational (no ``simplify``,
    which loads sympy.physics on first use), simplified otherwise (algebraic numbers)."""
    value = sp.sympify(value)
    if all(a.is_Rational for a in value.atoms(sp.Number)) and not value.atoms(sp.Pow, sp.exp) - {
            p for p in value.atoms(sp.Pow) if p.exp.is_Integer}:
        return exact_cancel(value)
    return sp.simplify(value)


def _sign_outcome(value: sp.Expr, what: str) -> Outcome:
    value = _tidy_value(value)
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


def decide_hermitian(form: CRational, transfer: tuple | None = None) -> WorstCase:
    """Exact decision of ``Re F >= 0 on [-1, 1]`` for a numeric c-form, with the minimiser.

    The sign of ``num/den`` equals that of ``num*den`` wherever the function is finite, so the
    decision is one certified sign decision of the kernel (:func:`hapticproof.exact.kernel.decide_rational_sign`);
    a disproof's witness is a rational point ``z0`` of the circle, never a pole. ``transfer``
    (the original ``F = P/Q`` as flint polynomials) lets the checker re-evaluate ``F`` itself.

    >>> from hapticproof.core.symbols import z
    >>> wc = decide_hermitian(hermitian_of(sp.Rational(1, 10) + 1/(z - 1) + sp.Rational(3, 10)/z))
    >>> wc.decision.value, wc.outcome.witness['c']
    ('disproved', -1)
    """
    form = form.numeric()
    outcome = decide_rational_sign(form.num, form.den, -1, 1, "c", "Re G^-1",
                                   transfer=None if transfer is None else transfer_json(*transfer),
                                   transfer_den=None if transfer is None else transfer[1])
    minimum = minimiser = None
    if not real_roots_in(form.den):
        m = minimise_rational(form.num, form.den, -1, 1)
        minimiser, minimum = m.argmin, (m.exact if m.exact is not None else m.value)
    outcome = Outcome(outcome.decision, outcome.evidence, outcome.reason, minimiser=minimiser, minimum=minimum)
    return WorstCase(outcome, sp.true if outcome.decision == Decision.PROVED else sp.false, minimiser, minimum)


def real_roots_in(den: flint.fmpq_poly, lo: int = -1, hi: int = 1) -> bool:
    return den.degree() > 0 and bool(real_roots(den, lo, hi))


def symbolic_minimum(expr: sp.Expr, var: sp.Symbol = C_SYM, names: Any = None) -> WorstCase:
    """Worst case of a symbolic ``Re F(c)`` over ``c`` in ``[-1, 1]`` by endpoint analysis.

    Exact when ``Re F`` is affine or concave-quadratic in ``c`` with a denominator that is a
    positive constant; the sign of the slope is taken from the symbols' assumptions
    (``positive=True`` ...), and when it is unknown the exact condition keeps ``|slope|``.
    The reasons speak the scene's naming ``names`` (:class:`~hapticproof.core.naming.Naming`:
    ``c`` under its printed name).

    >>> K, T, b = sp.symbols('K T b', positive=True)
    >>> B = sp.Symbol('B', nonnegative=True)
    >>> wc = symbolic_minimum(b - K*T/2 + B*C_SYM)
    >>> wc.condition, wc.minimiser
    (b >= B + K*T/2, -1)
    """
    wc = _symbolic_minimum(expr, var)
    if names is None or names.is_default:
        return wc
    out = wc.outcome
    facts = dict(out.evidence.facts)
    if isinstance(facts.get("reason"), str):
        facts["reason"] = names.words(facts["reason"])
    low = sp.sympify(out.minimum) if out.minimum is not None else None
    if out.decision == Decision.SYMBOLIC:
        reason = names.words(out.reason)
    else:   # 'the minimum <expression> over c is ... (<why>)': the toolkit's words renamed, not the expression's
        told = f"the minimum {names.text(low)} over {names.helper('cos')}" if low is not None else "Re G^-1"
        reason = f"{told} is {'>= 0' if out.decision == Decision.PROVED else '< 0'} for every value the parameters' " \
                 f"signs allow ({facts['reason']})"
    outcome = Outcome(out.decision, Evidence(out.evidence.method, witness=out.evidence.witness, facts=facts), reason,
                      minimiser=out.minimiser, minimum=out.minimum)
    return WorstCase(outcome, wc.condition, wc.minimiser, wc.minimum)


def _symbolic_minimum(expr: sp.Expr, var: sp.Symbol) -> WorstCase:
    num, den = sp.fraction(exact_cancel(sp.together(expr)))
    den_poly = sp.Poly(den, var)
    if den_poly.degree() > 0:
        return _rational_minimum(expr, num, den, var)
    if not (den.is_positive or den.is_negative):
        return _undecided_symbolic(expr, "the denominator has an unknown sign")
    if den.is_negative:
        num, den = -num, -den
    poly = sp.Poly(sp.expand(num / den), var)
    degree = poly.degree()            # -oo for the zero polynomial
    if degree <= 0:
        cond = sp.Ge(poly.as_expr(), 0)
        return _symbolic(cond, None, poly.as_expr(), "constant in c")
    coeffs = {k: poly.coeff_monomial(var**k) for k in range(degree + 1)}
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


def bernstein_sign(poly: sp.Expr, var: sp.Symbol = C_SYM, lo: Any = -1, hi: Any = 1) -> int | None:
    """A provable sign of a polynomial in ``var`` on ``[lo, hi]`` with symbolic coefficients:
    ``+1`` when every coefficient in the Bernstein basis of the interval is provably
    non-negative (then so is the polynomial on the whole interval), ``-1`` when every one is
    provably non-positive, ``2`` / ``-2`` when moreover the polynomial is provably non-zero
    there (every coefficient strictly signed), else ``None`` (which proves nothing).

    >>> a = sp.Symbol('a', positive=True)
    >>> bernstein_sign(1 + a**2 - 2*a*C_SYM), bernstein_sign(C_SYM**2 - C_SYM/2)
    (1, None)
    """
    t = sp.Dummy("t")
    shifted = sp.Poly(sp.expand(sp.sympify(poly).subs(var, lo + (hi - lo) * t)), t)
    degree = max(shifted.degree(), 0)
    power = [shifted.coeff_monomial(t**k) for k in range(degree + 1)]
    signs = set()
    for i in range(degree + 1):
        coeff = sum(sp.binomial(i, k) / sp.binomial(degree, k) * power[k] for k in range(i + 1))
        sign = _coefficient_sign(coeff)
        if sign is None:
            return None
        signs.add(sign)
    if signs <= {2, 1, 0}:
        return 2 if signs == {2} else 1
    if signs <= {-2, -1, 0}:
        return -2 if signs == {-2} else -1
    return None


def _coefficient_sign(value: sp.Expr) -> int | None:
    """+2 / -2 (provably positive / negative), +1 / -1 (non-negative / non-positive), 0, or None."""
    value = sp.sympify(value)
    if value == 0:
        return 0
    for form in (value, sp.factor(exact_cancel(value))):
        if form.is_positive:
            return 2
        if form.is_negative:
            return -2
    for form in (value, sp.factor(exact_cancel(value))):
        if form.is_nonnegative:
            return 1
        if form.is_nonpositive:
            return -1
    return None


def _rational_minimum(expr: sp.Expr, num: sp.Expr, den: sp.Expr, var: sp.Symbol) -> WorstCase:
    """``num/den`` with ``den`` depending on ``c``: when ``den`` keeps a strict sign on ``[-1, 1]``
    and the derivative's numerator ``num' den - num den'`` a sign (both proved through their
    Bernstein coefficients under the symbols' assumptions), the function is monotone on the
    interval and its minimum is at an end; otherwise the reason why not."""
    den_sign = bernstein_sign(den, var)
    if den_sign not in (2, -2):
        return _undecided_symbolic(expr, "the denominator depends on c and its sign on [-1, 1] is not proved")
    if den_sign < 0:
        num, den = -num, -den
    slope = sp.expand(sp.diff(num, var) * den - num * sp.diff(den, var))
    slope_sign = bernstein_sign(slope, var)
    if slope_sign is None:
        return _undecided_symbolic(expr, "a rational function of c whose derivative's sign on [-1, 1] is not proved "
                                   "(a stationary point may lie inside)")
    end = sp.Integer(-1) if slope_sign > 0 else sp.Integer(1)
    value = sp.factor(exact_cancel(num.subs(var, end) / den.subs(var, end)))
    value = sp.collect(sp.expand(value), sorted(value.free_symbols, key=str), func=sp.factor)   # one term per parameter
    side = "increasing" if slope_sign > 0 else "decreasing"
    return _symbolic(_ge(value), end, value, f"rational in c with a denominator of fixed sign, {side} on [-1, 1] "
                     f"(Bernstein coefficients of the derivative): minimum at c = {end}")


def _ge(expr: sp.Expr) -> sp.Basic:
    """``expr >= 0`` written as ``positive part >= negative part`` (readable bounds)."""
    expr = sp.expand(expr)
    pos = sp.Add(*[t for t in sp.Add.make_args(expr) if not t.could_extract_minus_sign()])
    neg = sp.Add(*[-t for t in sp.Add.make_args(expr) if t.could_extract_minus_sign()])
    return sp.Ge(pos, neg, evaluate=False)


def _symbolic(condition: Any, minimiser: Any, minimum: Any, reason: str) -> WorstCase:
    condition = sp.simplify(condition) if condition in (sp.true, sp.false) else condition
    # a condition the parameters' signs already settle is a decision, not a condition to state
    low = sp.sympify(minimum) if minimum is not None else None
    holds = True if condition is sp.true else False if condition is sp.false else None
    if holds is None and low is not None:
        holds = True if low.is_nonnegative else False if low.is_negative else None
    if holds is not None:
        facts = {"condition": condition, "reason": reason, "minimum": low}
        told = f"the minimum {sp.sstr(low)} over c" if low is not None else "Re G^-1"
        outcome = Outcome(Decision.PROVED if holds else Decision.DISPROVED, Evidence(Method.ENDPOINT_ANALYSIS, facts=facts),
                          f"{told} is {'>= 0' if holds else '< 0'} for every value the parameters' signs allow ({reason})",
                          minimiser=minimiser, minimum=minimum)
        return WorstCase(outcome, sp.true if holds else sp.false, minimiser, minimum)
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


@stage("transfer_polynomials")
def transfer_polynomials(scene: SingleUserScene) -> tuple[flint.fmpq_poly, flint.fmpq_poly]:
    """``G^{-1}(z) = P(z)/Q(z)`` of a numeric scene as coprime flint polynomials (``Q`` monic).

    >>> P, Q = transfer_polynomials(SingleUserScene.virtual_wall(K=2, B=0, b=1, T=1))
    >>> P, Q                                                  # 1 + 2/(z - 1)
    (x + 1, x + (-1))
    """
    from hapticproof.analysis.fastpath import transfer

    return transfer(numeric_scene(scene))


@stage("numeric_scene")
def numeric_scene(scene: SingleUserScene) -> Any:
    """The scene as a :class:`hapticproof.analysis.fastpath.NumericScene` (exact fractions, no SymPy
    after this one reading of ``H``): numeric scenes are decided on the fast path."""
    from hapticproof.analysis.fastpath import NumericScene

    return NumericScene.from_scene(scene)


@stage("poles")
def poles(scene: SingleUserScene) -> list[Pole]:
    """Poles of ``G^{-1}(z)``. With a symbolic delay the delay adds only a pole at ``z = 0``."""
    if scene.delay.is_Symbol:
        listed = poles_of(environment_path(scene))
        others = [p for p in listed if p.value != 0]
        # multiplicity n + (the path's order of pole at 0, negative for a zero): not a number,
        # so -1 with its formula
        num, den = sp.fraction(sp.cancel(environment_path(scene)))
        order = _order_at_zero(den) - _order_at_zero(num)
        formula = str(scene.delay) + (f" + {order}" if order > 0 else f" - {-order} (for n > {-order})" if order < 0 else "")
        return [Pole(sp.Integer(0), -1, "inside", formula)] + others
    if scene.is_numeric:
        return _numeric_poles(transfer_polynomials(scene)[1])
    return poles_of(inverse_transfer(scene))


def _order_at_zero(poly: sp.Expr) -> int:
    """The power of ``z`` that divides the polynomial ``poly`` (its lowest degree)."""
    return min(m[0] for m in sp.Poly(poly, Z_SYM).monoms()) if poly != 0 else 0


def _numeric_poles(Q: flint.fmpq_poly) -> list[Pole]:
    """Poles from the exact factorization: rational ones exact, others as certified
    approximations located by :func:`hapticproof.exact.kernel.locate_roots`."""
    out: list[Pole] = []
    if Q.degree() <= 0:
        return out
    for f, mult in Q.numer().factor()[1]:
        cert = locate_roots(flint.fmpq_poly(f))
        if f.degree() == 1:
            a0, a1 = f.coeffs()
            value = sp.Rational(int(-a0), int(a1))
            location = "on" if cert.boundary else "outside" if cert.outside else "inside"
            out.append(Pole(value, mult, location))
            continue
        if cert.boundary or max(abs(int(c)).bit_length() for c in f.coeffs()) <= 256:
            with flint_precision(64):
                for r, _ in f.complex_roots():
                    gap = r.real * r.real + r.imag * r.imag - 1
                    location = "inside" if gap < 0 else "outside" if gap > 0 else "on"
                    value = sp.Float(float(r.real.mid()), 12) + sp.I * sp.Float(float(r.imag.mid()), 12)
                    out.append(Pole(value, mult, location))
            continue
        # huge coefficients (1e-300 scales): the locations are the certificate's exact counts,
        # the values only approximate (ball isolation of such clusters costs minutes)
        points = approximate_outside(f, f.degree(), "disk")
        for k, w in enumerate(points or [complex("nan")] * f.degree()):
            location = "outside" if k < cert.outside else "inside"
            out.append(Pole(sp.Float(w.real, 12) + sp.I * sp.Float(w.imag, 12), mult, location))
    return sorted(out, key=lambda p: (sp.default_sort_key(p.value)))


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
    if scene.is_numeric:
        return _numeric_residues(scene)
    return unit_circle_residues(inverse_transfer(scene), poles(scene))


#: Up to this degree of ``G^{-1}``'s denominator an algebraic unit-circle pole gets its residue in
#: closed form (SymPy); above it the residue is the kernel's certified value (the decision is the
#: kernel's in both cases).
EXACT_RESIDUE_DEGREE = 200


def _numeric_residues(scene: SingleUserScene) -> list[Residue]:
    """Residues at the unit-circle poles of a numeric scene from flint polynomials: exact at
    ``z = +-1`` (``P(z0)/Q'(z0)``), in closed form for other poles when ``Q`` is small, else the
    kernel's certified approximation -- no SymPy limit of a degree-n expression."""
    from hapticproof.exact.kernel import residue_outcome

    P, Q = transfer_polynomials(scene)
    boundary = locate_roots(Q, "disk").boundary if Q.degree() > 0 else ()
    if any(r.value is None for r in boundary) and Q.degree() <= EXACT_RESIDUE_DEGREE:
        return unit_circle_residues(inverse_transfer(scene), poles(scene))
    out: list[Residue] = []
    for root in boundary:
        pole = sp.Rational(root.value) if root.value is not None else None
        if root.multiplicity > 1:
            outcome = Outcome(Decision.DISPROVED, Evidence(Method.ROOT_ISOLATION, facts={"pole": root.label(), "multiplicity": root.multiplicity}),
                              f"the unit-circle pole z = {root.label()} is not simple")
            out.append(Residue(pole if pole is not None else sp.nan, sp.nan, sp.nan, outcome))
            continue
        outcome = residue_outcome(P, Q, root)
        if pole is not None:
            z0 = flint.fmpq(int(pole.p), int(pole.q))
            value = P(z0) / Q.derivative()(z0)
            residue = sp.Rational(int(value.p), int(value.q))
            out.append(Residue(pole, residue, residue / pole, outcome))
            continue
        cert = outcome.evidence.facts["certificate"]
        c0 = float(root.cosine.approx(17)) if hasattr(root.cosine, "approx") else float(root.cosine)
        z0 = complex(c0, (1 - c0 * c0) ** 0.5)
        scaled = cert.approx
        value = sp.Float(scaled.real, 12) + sp.I * sp.Float(scaled.imag, 12) if scaled is not None else sp.nan
        out.append(Residue(sp.Float(z0.real, 12) + sp.I * sp.Float(z0.imag, 12), value * (sp.Float(z0.real, 12) + sp.I * sp.Float(z0.imag, 12)),
                           value, outcome))
    return out


@stage("hermitian")
def hermitian(scene: SingleUserScene) -> CRational | ThetaForm:
    """``Re G^{-1}(e^{jwT})``: a rational function of ``c`` (integer delay) or a theta-form
    (symbolic delay ``n``). Numeric scenes take the flint route (no SymPy expressions)."""
    if scene.delay.is_Symbol:
        return theta_form(scene.b - scene.z_a, environment_path(scene), scene.delay)
    if scene.is_numeric:
        N, D = circle_real_part(*transfer_polynomials(scene))
        return CRational(N, D, C_SYM)
    return hermitian_of(inverse_transfer(scene))


@stage("worst_case")
def worst_case(scene: SingleUserScene) -> WorstCase:
    """Worst case over frequency of ``Re G^{-1}``: exact decision when numeric, endpoint
    analysis when symbolic (integer delay), instances of the theta-form otherwise. Numeric
    scenes are decided on the fast path (:mod:`hapticproof.analysis.fastpath`: no c-form expression)."""
    if scene.is_numeric:
        from hapticproof.analysis.fastpath import hermitian_outcome

        out = hermitian_outcome(numeric_scene(scene), polynomials=transfer_polynomials(scene))
        return WorstCase(out, sp.true if out.decision == Decision.PROVED else sp.false, out.minimiser, out.minimum)
    if not scene.delay.is_Symbol and symbolic_c_degree(scene) > SYMBOLIC_CFORM_LIMIT:
        d = symbolic_c_degree(scene)
        reason = scene.naming().words(f"Re G^-1 is a polynomial of degree up to {d} in c with parameters: no closed-form "
                                      "worst case (not built; give the parameters numbers for the exact decision, or keep "
                                      "the delay symbolic, n)")
        return WorstCase(Outcome(Decision.SYMBOLIC, Evidence(Method.STRUCTURAL, facts={"degree": d, "reason": reason}), reason), None)
    form = hermitian(scene)
    if isinstance(form, ThetaForm):
        outcome = Outcome(
            Decision.SYMBOLIC,
            Evidence(Method.STRUCTURAL, facts={"reason": "symbolic delay n: fix n, or ask for the delay margin (hapticproof.analysis.design)"}),
            "symbolic delay n: the worst case depends on n (fix the delay, or ask for the delay margin)",
        )
        return WorstCase(outcome, None)
    return symbolic_minimum(form.expr(), names=scene.naming())


#: A symbolic scene's ``Re G^{-1}`` is built as a polynomial in ``c`` up to this degree (a
#: second or two); above it, it is a large exact object the symbolic answer cannot use (its worst
#: case has no closed form above degree 2) and is built only when asked (``derive --full``).
SYMBOLIC_CFORM_LIMIT = 100


def symbolic_c_degree(scene: SingleUserScene) -> int:
    """A bound on the degree in ``c`` of ``Re G^{-1}`` for an integer delay, read off ``G^{-1}``'s degrees in ``z``."""
    num, den = sp.fraction(exact_cancel(environment_path(scene)))
    dn, dd = (sp.Poly(p, Z_SYM).degree() if p.has(Z_SYM) else 0 for p in (num, den))
    return max(dn, dd + int(scene.delay))


@stage("conditions")
def conditions(scene: SingleUserScene) -> list[Condition]:
    """The three conditions of Definition 2 (HVE paper) for ``G^{-1}``, each decided: poles in the
    closed disk, unit-circle poles simple with ``Res/z0 >= 0``, and ``Re G^{-1} >= 0``.

    The names and reasons speak the scene's naming (``scene.naming()``).

    >>> sc = SingleUserScene.virtual_wall(K=2, B=0, b="0.0012", T="0.001")
    >>> [(c.name, c.decision.value) for c in conditions(sc)]     # doctest: +NORMALIZE_WHITESPACE
    [('poles in |z| <= 1', 'proved'), ('unit-circle poles simple', 'proved'),
     ('Res/z0 >= 0 at unit-circle poles', 'proved'), ('Re G^-1 >= 0 for all w', 'proved')]
    """
    if scene.is_numeric:
        return named_conditions(_numeric_conditions(scene), scene.naming(), numeric=True)
    return named_conditions(_symbolic_conditions(scene), scene.naming(), numeric=False)


def named_conditions(conds: list[Condition], names: Any, numeric: bool) -> list[Condition]:
    """Conditions in a scene's naming: their names (the toolkit's words) renamed; the reasons of a
    numeric scene too (numbers and the toolkit's words only); a symbolic scene's reasons are
    written in its naming where they are made (they hold the user's expressions)."""
    if names.is_default:
        return conds
    if numeric:          # the reasons of the outcomes in the evidence too (a mode's decision...)
        return [names.worded(cond) for cond in conds]
    return [Condition(names.words(cond.name), cond.outcome) for cond in conds]


def _numeric_conditions(scene: SingleUserScene) -> list[Condition]:
    P, Q = transfer_polynomials(scene)
    return pole_conditions(P, Q) + [Condition(HERMITIAN, worst_case(scene).outcome)]


def pole_location_outcome(pole_list: list[Pole], of: str = "") -> Outcome:
    """Whether every pole of :func:`poles_of`'s list lies in ``|z| <= 1``: disproved by a pole
    outside, undecided when a location depends on the parameters (``of``: whose poles, e.g.
    ``" of C"``, for the message)."""
    outside = [p for p in pole_list if p.location == "outside"]
    unknown = [p for p in pole_list if p.location == "unknown"]
    if outside:
        return Outcome(Decision.DISPROVED, Evidence(Method.CANONICAL_FORM, witness={"pole": outside[0].value}),
                       f"pole z = {sp.sstr(outside[0].value)}{of} outside the unit circle")
    if unknown:
        return Outcome(Decision.UNDECIDED, Evidence(Method.CANONICAL_FORM, facts={"poles": [str(p.value) for p in unknown]}),
                       f"the location of some pole{of} depends on the parameters")
    return Outcome(Decision.PROVED, Evidence(Method.CANONICAL_FORM, facts={"poles": [str(p.value) for p in pole_list]}),
                   f"every pole{of} lies in |z| <= 1 for all parameter values")


def _symbolic_conditions(scene: SingleUserScene) -> list[Condition]:
    pole_list = poles(scene)
    pole_out = _with_properness(pole_location_outcome(pole_list), _properness(scene))
    multiple = [p for p in pole_list if p.location == "on" and p.multiplicity > 1]
    if multiple:
        simple = Outcome(Decision.DISPROVED, Evidence(Method.CANONICAL_FORM, witness={"pole": multiple[0].value}),
                         f"the unit-circle pole z = {multiple[0].value} has multiplicity {multiple[0].multiplicity}")
    else:
        simple = Outcome(Decision.PROVED, Evidence(Method.CANONICAL_FORM), "every unit-circle pole is simple")
    res = [r for r in residues(scene) if r.residue is not sp.nan]     # simple unit-circle poles
    order = {Decision.DISPROVED: 0, Decision.UNDECIDED: 1, Decision.SYMBOLIC: 2, Decision.PROVED: 3}
    worst = min(res, key=lambda r: order[r.outcome.decision], default=None)
    if worst is None and multiple:
        residue = Outcome(Decision.UNDECIDED, Evidence(Method.CANONICAL_FORM),
                          "not examined: the unit-circle poles are not simple (no residue condition applies)")
    elif worst is None:
        residue = Outcome(Decision.PROVED, Evidence(Method.CANONICAL_FORM), "no poles on the unit circle")
    elif worst.outcome.decision == Decision.PROVED:
        residue = Outcome(Decision.PROVED, Evidence(Method.CANONICAL_FORM, facts={"residues": [r.outcome for r in res]}),
                          "; ".join(r.outcome.reason for r in res))
    else:
        residue = worst.outcome
    wc = worst_case(scene)
    herm = wc.outcome
    if herm.decision == Decision.SYMBOLIC and wc.condition is not None:
        herm = Outcome(Decision.SYMBOLIC, herm.evidence, f"{scene.naming().text(wc.condition)} ({herm.reason})",
                       minimiser=herm.minimiser, minimum=herm.minimum)
    return [Condition(POLES_IN_DISK, pole_out), Condition(POLES_SIMPLE, simple), Condition(RESIDUES, residue),
            Condition(HERMITIAN, herm)]


def _properness(scene: SingleUserScene) -> Outcome:
    """The condition at ``z = oo`` for symbolic coefficients (:func:`hapticproof.exact.conditions.properness_condition`):
    ``G^{-1}`` itself for an integer delay, ``z^{-n}`` times the environment path for a symbolic
    one (the constant ``b - z_a`` is proper)."""
    if scene.delay.is_Symbol:
        P, Q = numerator_denominator(environment_path(scene))
        return properness_condition(P, Q, scene.delay)
    P, Q = numerator_denominator(inverse_transfer(scene))
    return properness_condition(P, Q)


def _with_properness(poles_out: Outcome, proper: Outcome) -> Outcome:
    """One condition "poles in |z| <= 1" for the finite poles and the one at ``z = oo``: the
    worse of the two decides (disproved, undecided, symbolic, proved), the other is kept in the
    facts."""
    order = {Decision.DISPROVED: 0, Decision.UNDECIDED: 1, Decision.SYMBOLIC: 2, Decision.PROVED: 3}
    if proper.decision == Decision.PROVED:
        if poles_out.decision == Decision.PROVED:
            return Outcome(Decision.PROVED, poles_out.evidence, poles_out.reason + "; " + proper.reason)
        return poles_out
    first, second = (proper, poles_out) if order[proper.decision] <= order[poles_out.decision] else (poles_out, proper)
    facts = dict(first.evidence.facts or {})
    if second.decision == Decision.SYMBOLIC and first.decision == Decision.SYMBOLIC:
        facts["condition"] = sp.And(facts["condition"], second.evidence.facts["condition"])
    facts["other"] = second.reason
    reason = first.reason if second.decision == Decision.PROVED else f"{first.reason}; {second.reason}"
    return Outcome(first.decision, Evidence(first.evidence.method, witness=first.evidence.witness, facts=facts), reason)


@stage("positive_real")
def positive_real(scene: SingleUserScene) -> Outcome:
    """All three conditions of Definition 2 for ``G^{-1}``, combined (:func:`conditions`).

    >>> from hapticproof.core.symbols import z
    >>> sc = SingleUserScene(b=1, T=1, H=1/(z - 2))             # a pole outside the circle
    >>> out = positive_real(sc)
    >>> out.decision.value, out.reason
    ('disproved', 'G^-1 is not positive real: poles in |z| <= 1: 1 pole(s) outside the unit circle (z ~ 2)')
    """
    return combine(conditions(scene))


def definition_object(out: Outcome, transfer: dict[str, Any], names: Any = None) -> dict[str, Any] | None:
    """The judged definition object of a decision (:func:`hapticproof.exact.judge.judged_definition`)
    for a report that shows it (``derive``): ``hapticproof check`` tests the decision against the
    definition from ``G^{-1}`` itself. Not part of the decision: the judge's exact sample points
    cost far more than the decision (a map or an audit decides thousands of scenes)."""
    from hapticproof.core.naming import witness_keys
    from hapticproof.exact.judge import judged_definition

    witness = None
    if out.decision == Decision.DISPROVED and out.witness:
        # the judge's object speaks the checker's keys (c, omega_T), whatever the scene's names
        printed = {shown: key for key, shown in witness_keys(names.changed() if names is not None else None).items()}
        witness = to_jsonable({printed.get(k, k): v for k, v in out.witness.items()})
    return judged_definition("disk", out.decision.value, transfer, witness)
