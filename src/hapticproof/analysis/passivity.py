r"""``ispassive``: the exact positive-realness decision of a python-control or SymPy system.

python-control's ``control.ispassive`` answers by the feasibility of a KYP linear matrix
inequality solved in floating point (cvxopt): near the boundary, and for poles on the unit circle
or the imaginary axis (an integrator, a virtual wall's ``G^{-1}``) where the LMI is feasible only
on its boundary, its answer is the solver's tolerance. :func:`ispassive` takes the same objects
(:mod:`hapticproof.systems.lti`: ``TransferFunction`` / ``StateSpace``, SymPy ``TransferFunction``
/ ``TransferFunctionMatrix``) at the **exact rational values of their coefficients** and decides
the definition of positive realness (passivity of an LTI system) with certificates:

* discrete (HVE paper, Definition 2): proper (no pole at ``z = infinity``), poles in ``|z| <= 1``,
  unit-circle poles simple with ``Res/z0`` Hermitian PSD, ``G(e^{jw}) + G(e^{jw})^H >= 0`` for
  every ``w`` (scalar: an exact sign decision in ``c = cos w``; matrices: every characteristic
  coefficient of the Hermitian part);
* continuous (:func:`hapticproof.analysis.nport.positive_real`): poles in ``Re s <= 0``,
  imaginary-axis poles (and one at infinity) simple with Hermitian PSD residues,
  ``G(jw) + G(jw)^H >= 0`` for every ``w``.

>>> import sympy as sp
>>> z = sp.Symbol("z")
>>> r = ispassive(sp.Rational(1, 10) + 1 / (z - 1), domain="discrete")          # Re = 1/10 - 1/2 < 0
>>> r.decision.value, r.witness["c"], bool(r)
('disproved', -1, False)
>>> ispassive(sp.Rational(1, 2) + 1 / (z - 1)).decision.value                   # Re = 1/2 - 1/2 = 0
'proved'
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass
from typing import Any

import flint
import sympy as sp

from hapticproof.core.errors import SceneError
from hapticproof.core.evidence import Decision, Evidence, Method, Outcome, to_jsonable
from hapticproof.exact.conditions import Condition, combine, pole_conditions
from hapticproof.exact.kernel import decide_rational_sign, locate_roots, transfer_json
from hapticproof.systems.lti import ExactSystem, from_object, hermitian_system

__all__ = ["PassivityResult", "ispassive", "PROPER", "HERMITIAN"]

#: Names of the conditions that are not those of :func:`hapticproof.exact.conditions.pole_conditions`.
PROPER = "proper (no pole at z = infinity)"
HERMITIAN = "G + G^H >= 0 on the unit circle"


@dataclass(frozen=True)
class PassivityResult:
    """The exact decision of :func:`ispassive` with its certificates.

    ``decision`` is ``proved`` (positive real: passive), ``disproved`` (with an exact ``witness``:
    a frequency, a pole or a residue) or ``undecided``; ``conditions`` are the conditions of the
    definition, each decided; ``system`` the exact system decided (:class:`~hapticproof.systems.lti.ExactSystem`)
    and ``note`` how its coefficients were read. ``bool(result)`` is true only for ``proved``.
    """

    decision: Decision
    reason: str
    conditions: tuple[Condition, ...]
    outcome: Outcome
    system: ExactSystem
    note: str

    def __bool__(self) -> bool:
        return self.decision == Decision.PROVED

    @property
    def witness(self) -> Mapping[str, Any] | None:
        return self.outcome.witness

    @property
    def frequency(self) -> Any:
        """The failing frequency ``w`` (rad/s; ``w T`` when the sampling period is unknown), or None."""
        w = self.witness or {}
        if self.system.domain == "continuous":
            return w.get("omega")
        if "c" not in w:
            return None
        import math

        theta = math.acos(max(-1.0, min(1.0, float(sp.Rational(str(w["c"]))))))
        return theta / float(self.system.dt) if self.system.dt else theta

    def hermitian_part(self) -> ExactSystem:
        """``(G(z) + G(1/z)^T)/2`` or ``(G(s) + G(-s)^T)/2`` as an exact system (``.to_control()``,
        ``.to_sympy()``)."""
        return hermitian_system(self.system)

    def to_json(self) -> dict[str, Any]:
        return to_jsonable({"decision": self.decision.value, "reason": self.reason, "note": self.note,
                            "system": self.system.to_json(), "conditions": [c.to_json() for c in self.conditions]})

    def __repr__(self) -> str:
        return f"PassivityResult({self.decision.value}: {self.reason})"


def ispassive(sys: Any, *, floats: str = "binary", domain: str | None = None, dt: Any = None) -> PassivityResult:
    """Is ``sys`` passive (positive real)? The exact decision, with certificates.

    ``sys``: a python-control ``TransferFunction`` or ``StateSpace`` (discrete with ``dt``, or
    continuous; SISO or square MIMO), a SymPy ``TransferFunction`` or ``TransferFunctionMatrix``, a
    SymPy expression or matrix in ``z`` or ``s``, or an :class:`~hapticproof.systems.lti.ExactSystem`.
    ``floats``: ``'binary'`` (default) decides the exact values of the floats, ``'decimal'`` their
    shortest decimal text; the result's ``note`` says which. ``domain`` (``'discrete'`` or
    ``'continuous'``) when the object does not say; ``dt`` the sampling period (only reported).

    >>> import sympy as sp
    >>> s = sp.Symbol("s")
    >>> ispassive((s + 2) / (s + 1)).decision.value, ispassive((s - 1) / (s + 1)).decision.value
    ('proved', 'disproved')
    """
    system = from_object(sys, floats=floats, domain=domain, dt=dt)
    n, m = system.shape
    if n != m:
        raise SceneError(f"passivity needs a square system, got {n} outputs and {m} inputs")
    if system.domain == "continuous":
        conditions = _continuous(system)
        subject = "G(s)"
    elif system.is_siso:
        conditions = _discrete_siso(system)
        subject = "G(z)"
    else:
        conditions = _discrete_matrix(system)
        subject = "G(z)"
    whole = combine(list(conditions), subject=subject, holds="positive real (passive)")
    return PassivityResult(whole.decision, whole.reason, tuple(conditions), whole, system, system.floats_note())


def _proper(system: ExactSystem) -> Condition:
    improper = [(i, j) for i, row in enumerate(system.entries) for j, (num, den) in enumerate(row)
                if num.degree() > den.degree()]
    if improper:
        i, j = improper[0]
        return Condition(PROPER, Outcome(Decision.DISPROVED, Evidence(Method.CANONICAL_FORM, witness={"pole": "infinity",
                                                                                                     "entry": [i + 1, j + 1]}),
                                         f"entry ({i + 1}, {j + 1}) is improper (numerator degree above the denominator's): "
                                         "a pole at z = infinity, outside the unit circle"))
    return Condition(PROPER, Outcome(Decision.PROVED, Evidence(Method.CANONICAL_FORM), "every entry is proper"))


def _discrete_siso(system: ExactSystem) -> list[Condition]:
    from hapticproof.exact.unitcircle import circle_real_part

    P, Q = system.entries[0][0]
    conditions = [_proper(system)] + pole_conditions(P, Q)
    N, D = circle_real_part(P, Q)
    herm = decide_rational_sign(N, D, -1, 1, "c", "Re G", transfer=transfer_json(P, Q), transfer_den=Q)
    return conditions + [Condition(HERMITIAN, herm)]


def _lcm(polys: list[flint.fmpq_poly]) -> flint.fmpq_poly:
    out = flint.fmpq_poly([1])
    for p in polys:
        if p.degree() > 0:
            out = out * p / out.gcd(p)
    return out


def _discrete_matrix(system: ExactSystem) -> list[Condition]:
    from hapticproof.exact.psd import decide_psd_on_circle, hermitian_part_matrix, residue_matrices

    conditions = [_proper(system)]
    den = _lcm([d for row in system.entries for _, d in row])
    roots = locate_roots(den, "disk")
    facts = {"certificate": roots}
    if roots.outside:
        poles = Outcome(Decision.DISPROVED, Evidence(Method.ROOT_ISOLATION, witness={"pole": [str(complex(p)) for p in roots.outside_points[:3]]},
                                                     facts=facts), f"{roots.outside} pole(s) outside the unit circle")
    else:
        poles = Outcome(Decision.PROVED, Evidence(Method.ROOT_ISOLATION, facts=facts), "no pole outside the unit circle")
    simple = Outcome(Decision.PROVED if roots.boundary_simple else Decision.DISPROVED, Evidence(Method.ROOT_ISOLATION, facts=facts),
                     "every unit-circle pole is simple" if roots.boundary_simple else "a unit-circle pole is not simple")
    G = system.matrix()
    if roots.boundary and roots.boundary_simple:
        residues = residue_matrices(G)
        bad = [r.outcome for r in residues if r.outcome.decision != Decision.PROVED]
        residue = bad[0] if bad else Outcome(Decision.PROVED, Evidence(Method.CANONICAL_FORM, facts={"residues": [r.outcome for r in residues]}),
                                             "; ".join(r.outcome.reason for r in residues))
    elif roots.boundary:
        residue = Outcome(Decision.UNDECIDED, Evidence(Method.CANONICAL_FORM), "not examined: a unit-circle pole is not simple")
    else:
        residue = Outcome(Decision.PROVED, Evidence(Method.CANONICAL_FORM), "no poles on the unit circle")
    conditions += [Condition("poles in |z| <= 1", poles), Condition("unit-circle poles simple", simple),
                   Condition("residue matrices Res/z0 Hermitian PSD", residue)]
    transfer = {"variable": "z", "entries": system.to_json()["entries"]}
    herm = decide_psd_on_circle(hermitian_part_matrix(G), transfer=transfer)
    return conditions + [Condition(HERMITIAN, herm.outcome)]


def _continuous(system: ExactSystem) -> list[Condition]:
    from hapticproof.analysis.nport import positive_real
    from hapticproof.exact.rationalmatrix import RationalFunction, RationalMatrix

    Z = RationalMatrix(tuple(tuple(RationalFunction(num, den) for num, den in row) for row in system.entries))
    return list(positive_real(Z).conditions)
