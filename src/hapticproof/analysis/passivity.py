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

__all__ = ["PassivityResult", "ispassive", "circle_hermitian", "PROPER", "HERMITIAN"]

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
    from hapticproof.exact.psd import decide_psd_on_circle

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
    if roots.boundary and roots.boundary_simple:
        outcomes = [_residue_matrix(system, r) for r in roots.boundary]
        bad = [o for o in outcomes if o.decision != Decision.PROVED]
        residue = bad[0] if bad else Outcome(Decision.PROVED, Evidence(Method.CANONICAL_FORM, facts={"residues": outcomes}),
                                             "; ".join(o.reason for o in outcomes))
    elif roots.boundary:
        residue = Outcome(Decision.UNDECIDED, Evidence(Method.CANONICAL_FORM), "not examined: a unit-circle pole is not simple")
    else:
        residue = Outcome(Decision.PROVED, Evidence(Method.CANONICAL_FORM), "no poles on the unit circle")
    conditions += [Condition("poles in |z| <= 1", poles), Condition("unit-circle poles simple", simple),
                   Condition("residue matrices Res/z0 Hermitian PSD", residue)]
    transfer = {"variable": "z", "entries": system.to_json()["entries"]}
    herm = decide_psd_on_circle(circle_hermitian(system), transfer=transfer)
    return conditions + [Condition(HERMITIAN, herm.outcome)]


def _residue_matrix(system: ExactSystem, root: Any) -> Outcome:
    """``R/z0`` Hermitian PSD at a simple unit-circle pole: exact from flint at ``z0 = +-1``
    (``R_ij = P_ij(z0)/Q_ij'(z0)``), by SymPy's residues at other poles."""
    from hapticproof.exact.kernel import decide_constant_psd
    from hapticproof.exact.psd import residue_matrices

    if root.value is None:
        found = residue_matrices(system.matrix())
        bad = [r.outcome for r in found if r.outcome.decision != Decision.PROVED]
        return bad[0] if bad else Outcome(Decision.PROVED, Evidence(Method.CANONICAL_FORM), "; ".join(r.outcome.reason for r in found))
    z0 = flint.fmpq(int(sp.Rational(root.value).p), int(sp.Rational(root.value).q))
    n = system.shape[0]
    R = sp.zeros(n, n)
    for i, row in enumerate(system.entries):
        for j, (num, den) in enumerate(row):
            if den.degree() > 0 and den(z0) == 0:
                v = num(z0) / den.derivative()(z0) / z0
                R[i, j] = sp.Rational(int(v.p), int(v.q))
    what = f"the residue matrix at z = {sp.sstr(root.value)} (divided by z0)"
    if R != R.T:
        return Outcome(Decision.DISPROVED, Evidence(Method.CANONICAL_FORM, witness={"pole": str(root.value)}, facts={"matrix": R}),
                       f"{what} is not symmetric")
    return decide_constant_psd(R, what)


def circle_hermitian(system: ExactSystem) -> Any:
    """``M = G + G^H`` on the unit circle as a numeric :class:`~hapticproof.exact.psd.HermitianPart`
    built from flint polynomials (no SymPy): ``Re G_ij`` and ``Im G_ij / sin(theta)`` of ``P/Q`` are
    ``P(z)Q(1/z)`` in the Chebyshev bases ``T_k`` and ``U_{k-1}`` over ``|Q|^2``."""
    from hapticproof.exact.psd import HermitianPart, PolyRing
    from hapticproof.exact.unitcircle import fast_cross, symmetric_to_c

    zero, cvar, one = flint.fmpq(0), flint.fmpq_poly([0, 1]), flint.fmpq_poly([1])
    n = system.shape[0]
    parts = {}
    for i, row in enumerate(system.entries):
        for j, (num, den) in enumerate(row):
            p, q = num.coeffs(), den.coeffs()
            cross = fast_cross(p, q) if p else {}
            parts[i, j] = (symmetric_to_c(cross, zero, cvar, one, +1), symmetric_to_c(cross, zero, cvar, one, -1),
                           symmetric_to_c(fast_cross(q, q), zero, cvar, one, +1))
    common = _lcm([d for _, _, d in parts.values()])
    if common(flint.fmpq(0)) < 0:
        common = -common
    lift = lambda key, k: parts[key][k] * (common / parts[key][2])  # noqa: E731
    A = tuple(tuple(lift((i, j), 0) + lift((j, i), 0) for j in range(n)) for i in range(n))
    S = tuple(tuple(lift((i, j), 1) - lift((j, i), 1) for j in range(n)) for i in range(n))
    return HermitianPart(PolyRing.over(()), A, S, common)


def _continuous(system: ExactSystem) -> list[Condition]:
    from hapticproof.analysis.nport import positive_real
    from hapticproof.exact.rationalmatrix import RationalFunction, RationalMatrix

    Z = RationalMatrix(tuple(tuple(RationalFunction(num, den) for num, den in row) for row in system.entries))
    return list(positive_real(Z).conditions)
