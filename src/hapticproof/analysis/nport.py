"""Positive realness of n-port impedance matrices ``Z(s)``: poles, residue matrices on the
imaginary axis and the Hermitian part for every ``w``, decided exactly through the kernel."""

from __future__ import annotations

import math
from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from typing import Any

import flint
import sympy as sp

from hapticproof.exact import kernel
from hapticproof.core.errors import InputFormatError
from hapticproof.core.evidence import Decision, Evidence, Method, Outcome
from hapticproof.exact.conditions import Condition, combine
from hapticproof.exact.rationalmatrix import AxisPole, PoleReport, RationalFunction, RationalMatrix, constant_psd, decide_psd, hermitian_minors, pole_report
from hapticproof.exact.realroots import as_fmpq, to_rational
from hapticproof.analysis.youla import as_rational_matrix, port_blocks

__all__ = ["PositiveRealResult", "positive_real", "residue_matrix", "input_impedance"]


ZERO_FUNCTION = RationalFunction(flint.fmpq_poly([]), flint.fmpq_poly([1]))


#: names of the conditions of Definition 3 (positive realness), in order
POLES = "poles in Re s <= 0"


AXIS_SIMPLE = "imaginary-axis poles (and a pole at infinity) simple"


RESIDUES = "residue matrices Hermitian PSD"


HERMITIAN = "Hermitian part PSD for every w"


def _mod_quadratic(p: flint.fmpq_poly, a: flint.fmpq) -> tuple[flint.fmpq, flint.fmpq]:
    """``p(s) mod (s**2 + a)`` as ``(c0, c1)`` meaning ``c0 + c1 s``."""
    c0, c1 = flint.fmpq(0), flint.fmpq(0)
    for k, c in enumerate(p.coeffs()):
        # s^k = (-a)^(k//2) s^(k%2)
        factor = (-a) ** (k // 2)
        if k % 2:
            c1 += c * factor
        else:
            c0 += c * factor
    return c0, c1


def residue_matrix(Z: RationalMatrix, pole: str | tuple[str, Any]) -> Any:
    """Residue matrix of ``Z`` at ``s = 0`` (``'zero'``), at infinity (``'infinity'``: the
    coefficient of ``s``), or at ``s = j sqrt(a)`` (``('pair', a)``, returned as the pair
    ``(B, A)`` of rational matrices with residue ``B/2 - j A/(2 sqrt(a))``).

    >>> from hapticproof.core.symbols import s
    >>> Z = RationalMatrix.from_sympy(sp.Matrix([[2/s + 1, 1/s], [1/s, s]]))
    >>> residue_matrix(Z, 'zero'), residue_matrix(Z, 'infinity')
    (Matrix([
    [2, 1],
    [1, 0]]), Matrix([
    [0, 0],
    [0, 1]]))
    """
    n, m = Z.shape
    if pole == "zero":
        out = sp.zeros(n, m)
        for i in range(n):
            for j in range(m):
                e = Z[i, j]
                if e.den.degree() > 0 and e.den(flint.fmpq(0)) == 0:
                    rest = e.den // flint.fmpq_poly([0, 1])
                    out[i, j] = to_rational(e.num(flint.fmpq(0)) / rest(flint.fmpq(0)))
        return out
    if pole == "infinity":
        out = sp.zeros(n, m)
        for i in range(n):
            for j in range(m):
                e = Z[i, j]
                if not e.is_zero() and e.num.degree() - e.den.degree() == 1:
                    out[i, j] = to_rational(e.num.coeffs()[-1] / e.den.coeffs()[-1])
        return out
    kind, a = pole
    if kind != "pair":
        raise ValueError(f"unknown pole {pole!r}")
    aq = as_fmpq(a)
    quad = flint.fmpq_poly([aq, 0, 1])
    A, B = sp.zeros(n, m), sp.zeros(n, m)
    for i in range(n):
        for j in range(m):
            e = Z[i, j]
            quotient, remainder = divmod(e.den, quad)
            if e.den.degree() < 2 or not remainder.is_zero():
                continue
            n0, n1 = _mod_quadratic(e.num, aq)
            d0, d1 = _mod_quadratic(quotient, aq)
            norm = d0 * d0 + aq * d1 * d1
            alpha = (n0 * d0 + aq * n1 * d1) / norm
            beta = (n1 * d0 - n0 * d1) / norm
            A[i, j], B[i, j] = to_rational(alpha), to_rational(beta)
    return B, A


def _pair_residue_form(B: sp.Matrix, A: sp.Matrix, a: Any) -> sp.Matrix:
    """A rational symmetric matrix that is PSD iff the residue ``B/2 - j A/(2 sqrt a)`` is.

    ``H = B - j t A`` (``t = 1/sqrt a``; Hermitian: ``B`` symmetric, ``A`` antisymmetric) is PSD
    iff its real form ``[[B, t A], [-t A, B]]`` is, and the congruence ``diag(I, sqrt(a) I)``
    turns that into ``[[B, A], [-A, a B]]``.
    """
    return sp.Matrix(sp.BlockMatrix([[B, A], [-A, sp.Rational(a) * B]]))


def matrix_pole_conditions(report: PoleReport, subject: str = "Z") -> list[Condition]:
    facts = {"certificate": report.certificate} if report.certificate is not None else {}
    if report.rhp:
        (entry, root) = report.rhp[0]
        poles = Outcome(Decision.DISPROVED, Evidence(Method.ROOT_ISOLATION, witness={"entry": [entry[0] + 1, entry[1] + 1],
                                                                                     "pole": f"{root:.6g}"}, facts=facts),
                        f"entry ({entry[0] + 1}, {entry[1] + 1}) of {subject} has a pole at s ~ {root:.6g} in Re s > 0 "
                        f"({report.certificate.outside} pole(s) of the common denominator there, certified)")
    elif report.certificate is None:
        poles = Outcome(Decision.PROVED, Evidence(Method.CANONICAL_FORM), "no finite poles (polynomial entries)")
    else:
        poles = Outcome(Decision.PROVED, Evidence(Method.ROOT_ISOLATION, facts=facts),
                        f"no pole in Re s > 0 ({report.certificate.inside} in Re s < 0, "
                        f"{len(report.axis)} distinct on the imaginary axis, certified)")
    multiple = [(p.label(), m) for p, m in report.axis if m > 1]
    if report.improper > 1:
        multiple.append(("s = oo", report.improper))
    axis = [p.label() for p, _ in report.axis] + (["s = oo"] if report.improper == 1 else [])
    if multiple:
        label, order = multiple[0]
        where = next((_pole_frequency(p) for p, m in report.axis if m > 1), math.inf)
        infinity = report.infinity
        if label == "s = oo" and infinity is not None and infinity.decision == Decision.DISPROVED:
            # the kernel's decision at s = oo: an exact point Re s > 0 where Re(v^H Z v) < 0
            simple = Outcome(Decision.DISPROVED, Evidence(infinity.evidence.method,
                                                          witness={**(infinity.witness or {}), "pole_frequency": math.inf},
                                                          facts={**facts, "infinity": infinity.evidence.facts["certificate"]}),
                             f"improper: {infinity.reason}")
        else:
            simple = Outcome(Decision.DISPROVED, Evidence(Method.ROOT_ISOLATION, witness={"pole": label, "order": order,
                                                                                          "pole_frequency": where}, facts=facts),
                             f"the imaginary-axis pole {label} has order {order} > 1")
    else:
        simple = Outcome(Decision.PROVED, Evidence(Method.ROOT_ISOLATION, facts={**facts, "axis_poles": axis}),
                         f"simple poles at {', '.join(axis)}" if axis else "no imaginary-axis poles, proper")
    return [Condition(POLES, poles), Condition(AXIS_SIMPLE, simple)]


def _pole_frequency(pole: AxisPole) -> float:
    """Where an imaginary-axis pole sits (``w``; ``inf`` for the pole at infinity)."""
    return {"zero": 0.0, "infinity": math.inf}.get(pole.kind, math.sqrt(float(pole.a)) if pole.kind == "pair" else math.nan)


def failure_frequencies(conditions: Sequence[Condition]) -> list[float]:
    """Frequencies ``w`` where a condition fails (hints for a termination search): the witness
    frequency of a Hermitian-part or real-part condition, the frequency of an imaginary-axis pole
    whose residue fails (``inf`` at infinity)."""
    out = []
    for cond in conditions:
        witness = cond.outcome.witness or {}
        if cond.decision != Decision.DISPROVED:
            continue
        if "omega" in witness:
            out.append(float(witness["omega"]))
            out += _inside_stretch(cond.outcome, witness)
        elif "pole_frequency" in witness and not math.isnan(witness["pole_frequency"]):
            out.append(float(witness["pole_frequency"]))
    return out


def _inside_stretch(outcome: Outcome, witness: Mapping[str, Any]) -> list[float]:
    """Frequencies inside the stretch of ``x = w**2`` around the witness where the failing
    polynomial is negative (its ends are the neighbouring real roots): a witness at ``w = 0``
    says little about how far the stretch reaches (issue 10: up to ``w = 0.01`` only)."""
    from hapticproof.exact.realroots import real_roots

    certificate = outcome.evidence.facts.get("certificate")
    if certificate is None:
        certs = [c for c in outcome.evidence.facts.values() if hasattr(c, "polynomial") and not getattr(c, "holds", True)]
        certificate = certs[0] if certs else None
    if certificate is None:
        return []
    if hasattr(certificate, "coefficients"):          # a PSD certificate: its failing coefficient
        failing = [c for c in certificate.coefficients if not c.holds]
        if not failing:
            return []
        certificate = failing[0]
    p = certificate.polynomial
    if p.is_zero() or p.degree() < 1:
        return []
    x0 = float(as_fmpq(witness["x"]))
    ends = [float(r.lo + r.hi) / 2 for r in real_roots(kernel.squarefree_part(p), 0, None)]
    above = min((e for e in ends if e > x0), default=None)
    below = max((e for e in ends if e < x0), default=0.0)
    if above is None:
        return [math.sqrt(max(x0, below) + 1.0) * 2]
    low, high = math.sqrt(below), math.sqrt(above)
    return [high / 2, high / 10] if low == 0 else [math.sqrt(low * high)]


def residue_matrix_outcome(Z: RationalMatrix, report: PoleReport, signs: Sequence[int] | None = None,
                     subject: str = "Z") -> Outcome:
    """Residue matrices at the simple imaginary-axis poles (and infinity) Hermitian PSD?

    ``signs`` (for Youla's congruence-scaled ``J Rhat J`` with imaginary entries) marks the
    nodes of negative scale: entries between nodes of different sign are ``j`` times the stored
    real ones. Each PSD question is a constant one for the decision kernel
    (:func:`hapticproof.exact.rationalmatrix.constant_psd`).
    """
    outcomes: list[tuple[str, Outcome]] = []
    skipped = [p.label() for p, m in report.axis if m > 1]
    items = [p for p, m in report.axis if m == 1] + ([AxisPole("infinity")] if report.improper == 1 else [])
    for pole in items:
        where = f"the residue matrix of {subject} at {pole.label()}"
        if pole.kind == "infinity" and signs is None and report.infinity is not None:
            out = report.infinity                   # the kernel: residue Hermitian PSD, else a witness point
        elif pole.kind in ("zero", "infinity"):
            R = residue_matrix(Z, pole.kind)
            if signs is not None:
                cross = [(i, j) for i in range(R.rows) for j in range(R.cols) if signs[i] != signs[j] and R[i, j] != 0]
                if cross:
                    return Outcome(Decision.DISPROVED, Evidence(Method.CANONICAL_FORM, witness={"pole": pole.label(),
                                                                                               "entry": list(cross[0])}),
                                   f"{where} is not Hermitian (imaginary off-diagonal entry)")
                R = sp.Matrix(R.rows, R.cols, lambda i, j: -R[i, j] if signs[i] < 0 and signs[j] < 0 else R[i, j])
            out = constant_psd(R, where)
        elif pole.kind == "pair":
            if signs is not None and any(v < 0 for v in signs):
                return Outcome(Decision.UNDECIDED, Evidence(Method.CANONICAL_FORM, facts={"pole": pole.label()}),
                               f"residues at {pole.label()} of a Youla matrix with imaginary entries are not implemented")
            B, A = residue_matrix(Z, ("pair", pole.a))
            if B != B.T or A != -A.T:
                return Outcome(Decision.DISPROVED, Evidence(Method.CANONICAL_FORM, witness={"pole": pole.label()},
                                                            facts={"B": B, "A": A}),
                               f"{where} is not Hermitian")
            out = constant_psd(_pair_residue_form(B, A, pole.a), where + " (real form [[B, A], [-A, a B]])")
        else:
            return Outcome(Decision.UNDECIDED, Evidence(Method.CANONICAL_FORM, facts={"pole": pole.label()}),
                           f"residues at the irrational imaginary-axis poles ({pole.label()}) are not implemented")
        if out.decision != Decision.PROVED:
            witness = {"pole": pole.label(), "pole_frequency": _pole_frequency(pole), **(out.witness or {})}
            return Outcome(out.decision, Evidence(out.evidence.method, witness=witness, facts=out.evidence.facts), out.reason)
        outcomes.append((pole.label(), out))
    if skipped:
        return Outcome(Decision.UNDECIDED, Evidence(Method.CANONICAL_FORM, facts={"not_simple": skipped}),
                       f"not examined at {', '.join(skipped)} (not a simple pole: no residue condition applies)")
    if not outcomes:
        return Outcome(Decision.PROVED, Evidence(Method.CANONICAL_FORM), "no imaginary-axis poles")
    return Outcome(Decision.PROVED, Evidence(Method.CANONICAL_FORM, facts={"residues": dict(outcomes)}),
                   f"residue matrices Hermitian PSD at {', '.join(label for label, _ in outcomes)}")


@dataclass(frozen=True)
class PositiveRealResult:
    """Exact positive-realness decision: every condition of Definition 3 with its outcome
    (``conditions``, in the order poles, simple axis poles, residues, Hermitian part) and the
    whole decision (``outcome``, :func:`hapticproof.exact.conditions.combine`)."""

    decision: Decision
    reason: str
    conditions: tuple[Condition, ...]
    outcome: Outcome

    @classmethod
    def from_conditions(cls, conditions: Sequence[Condition], subject: str = "Z") -> PositiveRealResult:
        whole = combine(list(conditions), subject=subject, holds="positive real")
        return cls(whole.decision, whole.reason, tuple(conditions), whole)

    def condition(self, name: str) -> Outcome:
        """The outcome of one condition by name (:data:`POLES`, :data:`RESIDUES`, ...)."""
        return next(c.outcome for c in self.conditions if c.name == name)

    @property
    def poles(self) -> Outcome:
        return self.condition(POLES)

    @property
    def residues(self) -> Outcome:
        return self.condition(RESIDUES)

    @property
    def hermitian(self) -> Outcome:
        return self.condition(HERMITIAN)

    @property
    def evidence(self) -> Evidence:
        return self.outcome.evidence

    @property
    def witness(self) -> Mapping[str, Any] | None:
        return self.outcome.witness

    def frequencies(self) -> list[float]:
        """Frequencies ``w`` where a condition fails (hints for a termination search)."""
        return failure_frequencies(self.conditions)

    def to_json(self) -> dict[str, Any]:
        return {"decision": self.decision.value, "reason": self.reason,
                "conditions": [c.to_json() for c in self.conditions]}


def positive_real(Z: Any) -> PositiveRealResult:
    """Exact positive realness of a square real-rational matrix (Definition 3, Khalil).

    A pole at infinity (an improper entry such as a mass ``M s``) is allowed when simple with a
    symmetric PSD coefficient, as for impedances of LC networks. Each condition is decided by
    the kernel with a certificate; the decision is their combination.

    >>> import sympy as sp
    >>> from hapticproof.core.symbols import s
    >>> positive_real(sp.Matrix([[1/(s + 1), 0], [0, s]])).decision.value
    'proved'
    >>> r = positive_real(sp.Matrix([[1, 2], [0, 1]]))       # Hermitian part [[1, 1], [1, 1]] - ok
    >>> r.decision.value, positive_real(sp.Matrix([[1, 3], [0, 1]])).hermitian.witness
    ('proved', {'x': 0, 'omega': 0})
    >>> bad = positive_real(sp.Matrix([[1 - 2/(s + 1) + 10/(s + 10**4)]]))   # issue 10: Re Z(j0) < 0
    >>> bad.decision.value, [c.decision.value for c in bad.conditions]
    ('disproved', ['proved', 'proved', 'proved', 'disproved'])
    """
    Zr = as_rational_matrix(Z)
    n, m = Zr.shape
    if n != m:
        raise InputFormatError("positive realness needs a square matrix")
    report = pole_report(Zr)
    conditions = matrix_pole_conditions(report)
    conditions.append(Condition(RESIDUES, residue_matrix_outcome(Zr, report)))
    conditions.append(Condition(HERMITIAN, decide_psd(hermitian_minors(Zr), "Z(jw) + Z(jw)^H")))
    return PositiveRealResult.from_conditions(conditions, "Z")


def input_impedance(Z: Any, termination: Any, ports: Sequence[int]) -> RationalMatrix:
    """Impedance seen at the first port group when the second is terminated by ``termination``:
    ``Z11 - Z12 (Z22 + T)^-1 Z21`` (``ports=(p1, p2)``).

    >>> from hapticproof.core.symbols import s
    >>> input_impedance(sp.Matrix([[2, 1], [1, 2]]), sp.Matrix([[1]]), (1, 1)).to_sympy()
    Matrix([[5/3]])
    """
    Zr = as_rational_matrix(Z)
    T = as_rational_matrix(termination)
    a, b = port_blocks(Zr.shape[0], ports)
    Z11, Z12 = Zr.submatrix(a, a), Zr.submatrix(a, b)
    Z21, Z22 = Zr.submatrix(b, a), Zr.submatrix(b, b)
    return Z11 - Z12 @ (Z22 + T).inverse() @ Z21
