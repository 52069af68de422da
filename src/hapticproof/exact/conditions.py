"""A whole decision as named conditions, and the pole conditions of discrete positive realness
(poles in the closed disk, unit-circle poles simple, residues non-negative) for ``P/Q`` given by
exact polynomials: shared by the symbolic route and the numeric fast path."""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

import flint

from hapticproof.core.evidence import Decision, Evidence, Method, Outcome
from hapticproof.exact.kernel import locate_roots, residue_outcome

__all__ = ["Condition", "combine", "pole_conditions"]


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


POLES_IN_DISK = "poles in |z| <= 1"


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
    """
    roots = locate_roots(Q, "disk")
    facts = {"certificate": roots}
    if roots.outside:
        where = ", ".join(f"z ~ {complex(p):.6g}".replace("+0j", "").replace("(", "").replace(")", "") for p in roots.outside_points[:3])
        pole_out = Outcome(Decision.DISPROVED, Evidence(Method.ROOT_ISOLATION, witness={"pole": where}, facts=facts),
                           f"{roots.outside} pole(s) outside the unit circle ({where})")
    else:
        on = sum(r.multiplicity * (1 if r.value is not None else 2) for r in roots.boundary)
        pole_out = Outcome(Decision.PROVED, Evidence(Method.ROOT_ISOLATION, facts=facts),
                           f"no pole outside the unit circle ({on} on it, {roots.inside} inside)")
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
