"""A whole decision as named conditions, and the pole conditions of discrete positive realness
(poles in the closed disk *and none at z = oo*, unit-circle poles simple, residues non-negative)
for ``P/Q`` given by exact polynomials: shared by the symbolic route and the numeric fast path,
so that every entry point (derive, ranges, margins, maps, paper files) gets properness from here.

A pole at infinity lies outside the closed disk: an improper ``G^{-1}`` (a non-causal model)
fails the first condition with the evidence ``improper: pole at infinity`` and an exact point
``|z0| > 1`` where ``Re G^{-1}(z0) < 0`` (:func:`hapticproof.exact.infinity.decide_infinity`).
:func:`properness_condition` is the same condition for symbolic coefficients."""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

import flint

import sympy as sp

from hapticproof.core.evidence import Decision, Evidence, Method, Outcome
from hapticproof.exact.infinity import decide_infinity
from hapticproof.exact.kernel import locate_roots, residue_outcome

__all__ = ["Condition", "combine", "pole_conditions", "properness_condition"]


@dataclass(frozen=True, slots=True)
class Condition:
    """One condition of a whole decision (a pole, residue or Hermitian-part condition) with its
    outcome; :func:`combine` makes the verdict from a list of them."""

    name: str
    outcome: Outcome

    @property
    def decision(self) -> Decision:
        return self.outcome.decision

    def to_json(self) -> dict[str, Any]:
        return {"name": self.name, **self.outcome.to_json()}


def combine(conditions: list[Condition], subject: str = "G^-1", holds: str = "positive real") -> Outcome:
    """The whole decision: disproved if any condition is, else undecided, else symbolic, else
    proved; the evidence lists every condition (the first failing one's witness leads).

    >>> ok = Outcome(Decision.PROVED, Evidence(Method.ROOT_ISOLATION), "fine")
    >>> bad = Outcome(Decision.DISPROVED, Evidence(Method.ROOT_ISOLATION, witness={"pole": 2}), "pole at 2")
    >>> out = combine([Condition("poles", bad), Condition("Hermitian part", ok)])
    >>> out.decision.value, out.reason, out.witness
    ('disproved', 'G^-1 is not positive real: poles: pole at 2', {'pole': 2})
    """
    facts = {"conditions": list(conditions)}
    for decision, verb in ((Decision.DISPROVED, "is not"), (Decision.UNDECIDED, "undecided:"), (Decision.SYMBOLIC, "")):
        failing = [c for c in conditions if c.decision == decision]
        if not failing:
            continue
        first = failing[0]
        if decision == Decision.DISPROVED:
            reason = f"{subject} is not {holds}: {first.name}: {first.outcome.reason}"
        elif decision == Decision.UNDECIDED:
            reason = f"{subject}: {first.name} undecided: {first.outcome.reason}"
        else:
            # the conditions themselves are listed with the verdict: name them, do not repeat them
            reason = f"{subject} is {holds} iff these conditions on the parameters hold: " + "; ".join(c.name for c in failing)
        return Outcome(decision, Evidence(first.outcome.evidence.method, witness=first.outcome.witness, facts=facts), reason,
                       minimiser=first.outcome.minimiser, minimum=first.outcome.minimum)
    herm = conditions[-1].outcome if conditions else None
    return Outcome(Decision.PROVED, Evidence(Method.ROOT_ISOLATION, facts=facts),
                   f"{subject} is {holds}: " + "; ".join(c.name for c in conditions) + " (each decided exactly)",
                   minimiser=herm.minimiser if herm else None, minimum=herm.minimum if herm else None)


POLES_IN_DISK = "poles in |z| <= 1"   # z = oo included: an improper G fails it


POLES_SIMPLE = "unit-circle poles simple"


RESIDUES = "Res/z0 >= 0 at unit-circle poles"


HERMITIAN = "Re G^-1 >= 0 for all w"


def pole_conditions(P: flint.fmpq_poly, Q: flint.fmpq_poly) -> list[Condition]:
    """The pole and residue conditions of Definition 2 for ``G^{-1} = P/Q`` (coprime, numeric):
    poles in the closed disk, unit-circle poles simple, ``Res/z0 >= 0`` (shared with the numeric
    fast path, :mod:`hapticproof.analysis.fastpath`).

    >>> z = flint.fmpq_poly([0, 1])
    >>> [c.decision.value for c in pole_conditions(z + 1, z - 1)]          # 1 + 2/(z - 1)
    ['proved', 'proved', 'proved']
    >>> pole_conditions(z * z + z - 1, z - 1)[0].outcome.reason           # 1 + z^2/(z - 1): improper
    'improper: pole at infinity (order 1): G^-1 ~ z; Re G^-1(-10) = -89/11 < 0'
    """
    roots = locate_roots(Q, "disk")
    infinity = decide_infinity((P, Q), "disk", "G^-1")
    facts = {"certificate": roots, "infinity": infinity.evidence.facts["certificate"]}
    outside = ""
    if roots.outside:
        where = ", ".join(f"z ~ {complex(p):.6g}".replace("+0j", "").replace("(", "").replace(")", "") for p in roots.outside_points[:3])
        outside = f"{roots.outside} pole(s) outside the unit circle ({where})"
    if infinity.decision == Decision.DISPROVED:
        value = infinity.evidence.facts.get("value")
        pole_out = Outcome(Decision.DISPROVED, Evidence(infinity.evidence.method, witness=infinity.witness,
                                                        facts={**facts, **({"value": value} if value is not None else {})}),
                           infinity.reason + (f"; also {outside}" if outside else ""))
    elif roots.outside:
        pole_out = Outcome(Decision.DISPROVED, Evidence(Method.ROOT_ISOLATION, witness={"pole": where}, facts=facts), outside)
    else:
        on = sum(r.multiplicity * (1 if r.value is not None else 2) for r in roots.boundary)
        pole_out = Outcome(Decision.PROVED, Evidence(Method.ROOT_ISOLATION, facts=facts),
                           f"no pole outside the unit circle ({on} on it, {roots.inside} inside), none at z = oo (proper)")
    facts = {"certificate": roots}
    multiple = [r for r in roots.boundary if r.multiplicity > 1]
    if multiple:
        r = multiple[0]
        simple = Outcome(Decision.DISPROVED, Evidence(Method.ROOT_ISOLATION, witness={"pole": r.label(), "multiplicity": r.multiplicity},
                                                      facts=facts),
                         f"the unit-circle pole {r.label()} has multiplicity {r.multiplicity}")
    else:
        simple = Outcome(Decision.PROVED, Evidence(Method.ROOT_ISOLATION, facts=facts),
                         "every unit-circle pole is simple" if roots.boundary else "no poles on the unit circle")
    outcomes = [residue_outcome(P, Q, r) for r in roots.boundary if r.multiplicity == 1]
    bad = [o for o in outcomes if o.decision != Decision.PROVED]
    if bad:
        residue = bad[0]
    elif outcomes:
        residue = Outcome(Decision.PROVED, Evidence(Method.CANONICAL_FORM, facts={"residues": outcomes}),
                          "; ".join(o.reason for o in outcomes))
    elif multiple:
        residue = Outcome(Decision.UNDECIDED, Evidence(Method.CANONICAL_FORM),
                          "not examined: the unit-circle poles are not simple (no residue condition applies)")
    else:
        residue = Outcome(Decision.PROVED, Evidence(Method.CANONICAL_FORM), "no poles on the unit circle")
    return [Condition(POLES_IN_DISK, pole_out), Condition(POLES_SIMPLE, simple), Condition(RESIDUES, residue)]


def properness_condition(num: sp.Poly, den: sp.Poly, delay: Any = 0) -> Outcome:
    """The condition at ``z = oo`` for ``G = num/den`` with symbolic coefficients (``sp.Poly`` in
    ``z``), times ``z^(-delay)`` for a symbolic integer delay: every coefficient of ``num`` above
    ``deg den + delay`` must vanish. The degree excess does not change when common factors
    cancel, so the condition is exact wherever ``den``'s leading coefficient is nonzero (when
    that coefficient may vanish the degree is not fixed: undecided). Decided by the symbols'
    assumptions when it can be (``PROVED``/``DISPROVED``), else ``SYMBOLIC`` with
    ``facts['condition']``.

    >>> z, B, T = sp.symbols("z"), sp.Symbol("B", real=True), sp.Symbol("T", positive=True)
    >>> properness_condition(sp.Poly(B*z**2 + T*z, z), sp.Poly(z - 1, z)).evidence.facts["condition"]
    Eq(B, 0)
    >>> n = sp.Symbol("n", integer=True, nonnegative=True)
    >>> properness_condition(sp.Poly(z**2, z), sp.Poly(z - 1, z), n).evidence.facts["condition"]
    n >= 1
    """
    if num.is_zero:
        return Outcome(Decision.PROVED, Evidence(Method.CANONICAL_FORM), "G = 0: no pole at z = oo")
    lead = den.LC()
    if sp.sympify(lead).is_zero is not False:
        return Outcome(Decision.UNDECIDED, Evidence(Method.CANONICAL_FORM, facts={"leading": lead}),
                       f"the degree of the denominator in z depends on the parameters (leading coefficient {sp.sstr(lead)})")
    d = den.degree()
    if not isinstance(delay, int) and not getattr(delay, "is_Integer", False):
        # z^-n num/den with a symbolic n >= 0: proper iff n >= deg num - deg den (num's own degree
        # for the generic coefficients; the excess never depends on a cancellation)
        top = num.degree()
        while top > d and sp.sympify(num.coeff_monomial(num.gens[0] ** top)).is_zero:
            top -= 1
        needed = top - d
        if needed <= 0:
            return Outcome(Decision.PROVED, Evidence(Method.CANONICAL_FORM), "proper for every delay (deg num <= deg den)")
        coefficient = num.coeff_monomial(num.gens[0] ** top)
        condition = sp.Ge(delay, needed) if sp.sympify(coefficient).is_zero is False else sp.Or(sp.Ge(delay, needed),
                                                                                                 sp.Eq(coefficient, 0))
        return Outcome(Decision.SYMBOLIC, Evidence(Method.CANONICAL_FORM, facts={"condition": condition}),
                       f"improper unless the delay makes it proper: {sp.sstr(condition)} (z^-n G has a pole of "
                       f"order {needed} - n at z = oo otherwise)")
    d += int(delay)
    high = [(k, num.coeff_monomial(num.gens[0] ** k)) for k in range(d + 1, num.degree() + 1)]
    high = [(k, cf) for k, cf in high if not sp.sympify(cf).is_zero]
    if not high:
        return Outcome(Decision.PROVED, Evidence(Method.CANONICAL_FORM), "proper: no pole at z = oo for all parameter values")
    nonzero = [(k, cf) for k, cf in high if sp.sympify(cf).is_zero is False]
    if nonzero:
        k, cf = nonzero[-1]
        return Outcome(Decision.DISPROVED, Evidence(Method.CANONICAL_FORM, witness={"pole": "infinity", "order": k - d},
                                                    facts={"coefficient": cf}),
                       f"improper: pole at infinity (order {k - d}) for every parameter value: the coefficient "
                       f"{sp.sstr(cf)} of z^{k} in the numerator is nonzero (the denominator has degree {d})")
    condition = sp.And(*[sp.Eq(cf, 0) for _, cf in high])
    text = " and ".join(f"{sp.sstr(cf)} = 0" for _, cf in high)
    return Outcome(Decision.SYMBOLIC, Evidence(Method.CANONICAL_FORM, facts={"condition": condition}),
                   f"proper (no pole at z = oo) iff {text}")
