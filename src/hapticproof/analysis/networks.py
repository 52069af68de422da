r"""n-port networks: positive realness, Llewellyn, Youla symmetrization, absolute stability.

An n-port is given by its impedance matrix ``Z(s)`` (``F = Z V``), real-rational in ``s``. Ports
may be grouped (``ports=(3, 3)``: a 2-port whose ports are 3-DOF, terminated by full 3x3
passive impedances as in the 3-DOF bilateral paper, eq. (13)); the default is scalar ports.

Every sign question goes to the decision kernel (:mod:`hapticproof.exact.kernel`) and every result
lists its conditions, each with its decision and evidence (a certificate the independent
checker :mod:`hapticproof.exact.checker` re-verifies), like :func:`hapticproof.exact.conditions.combine`.

* :func:`positive_real` -- Definition 3 of the 3-DOF bilateral paper (Khalil) for a rational
  matrix: poles in ``Re s <= 0``; imaginary-axis poles (and a pole at infinity) simple with
  Hermitian PSD residue matrices; ``Z(jw) + Z(jw)^H`` PSD for every ``w`` (``w = 0`` and
  ``w -> oo`` included), decided by the characteristic coefficients as polynomials in ``x = w**2``.
* :func:`llewellyn` -- Llewellyn's absolute-stability criterion of a 2-port, exact, with the
  frequency where the stability factor ``eta = (2 Re z11 Re z22 - Re z12 z21)/|z12 z21|`` is
  smallest.
* :func:`symmetrization_conditions`, :func:`symmetrize` (:mod:`hapticproof.analysis.youla`) -- Youla's
  conditions A and B, and the reciprocal ``Z'`` of eq. (14): ``Z' = D Z D^-1`` with ``D``
  constant on every port block, so that ``det(Z' + T) = det(Z + T)`` for every block
  termination ``T`` (one free sign per port, not per DOF; a reciprocal ``Z`` is its own
  symmetrization); :func:`zprime_positive_real` decides Definition 3 for ``Z'``.
* :func:`absolute_stability` -- the verdict: a positive-real ``Z`` is absolutely stable (decided
  first, for any port grouping); Llewellyn for scalar 2-ports; positive realness of ``Z'``
  (Youla 1959 + 1960) for symmetrizable networks; a potentially unstable port or pair of ports;
  otherwise a search, with a deadline, for passive terminations that put a zero of
  ``det(Z + T)`` in ``Re s > 0``, verified exactly (:mod:`hapticproof.analysis.terminations`), or an
  honest ``undecided`` that says what was tried.

All PSD decisions use the characteristic coefficients (every principal minor), never the
leading minors alone.

>>> import sympy as sp
>>> from hapticproof.core.symbols import s
>>> Zx = sp.Matrix([[9/(s + 3), -1/(s + 1)], [-1/(s + 1), 1/(s + 3)]])    # eq. (5)
>>> result = llewellyn(Zx)
>>> result.decision.value, result.tightest.argmin, result.eta_min
('proved', 0, 1)
"""

from __future__ import annotations

import itertools
from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from typing import Any

import flint
import sympy as sp

from hapticproof.exact import kernel
from hapticproof.core.errors import InputFormatError
from hapticproof.core.evidence import Decision, Evidence, Method, Outcome
from hapticproof.exact.conditions import Condition, combine
from hapticproof.exact.rationalmatrix import HalflineMinimum, HermitianMinors, RationalFunction, RationalMatrix, axis_parts, decide_psd, hermitian_minors, minimise_halfline, minors_from_polynomial_matrix, pole_report
from hapticproof.analysis.youla import Symmetrization, SymmetrizationCondition, as_rational_matrix, port_blocks, symmetrization_conditions, symmetrize
from hapticproof.analysis.terminations import InstabilityCertificate, TerminationSearch, find_destabilizing_terminations, search_terminations, verify_certificate
from hapticproof.analysis.nport import AXIS_SIMPLE, HERMITIAN, RESIDUES, PositiveRealResult, ZERO_FUNCTION, failure_frequencies, matrix_pole_conditions, positive_real, residue_matrix_outcome

__all__ = ["as_rational_matrix", "port_blocks", "LlewellynResult", "llewellyn", "SymmetrizationCondition", "symmetrization_conditions", "Symmetrization", "symmetrize", "zprime_positive_real", "StabilityVerdict", "Theorem9", "theorem9_conditions", "absolute_stability", "InstabilityCertificate", "TerminationSearch", "search_terminations", "find_destabilizing_terminations", "verify_certificate"]


#: names of Llewellyn's conditions, in order
OPEN_CIRCUIT = "open-circuit stability (no entry has a pole in Re s > 0)"


DIAGONAL_POLES = "z11, z22: imaginary-axis poles simple with positive residues"


RE_Z11 = "Re z11 >= 0 for every w"


RE_Z22 = "Re z22 >= 0 for every w"


PRODUCT = "2 Re z11 Re z22 - Re z12z21 - |z12z21| >= 0 for every w"


@dataclass(frozen=True)
class LlewellynResult:
    """Llewellyn's criterion for a 2-port: each condition with its outcome (``conditions``), the
    whole decision, and where the stability factor ``eta`` is smallest (``tightest``;
    ``eta_min`` its exact value when the minimiser is rational)."""

    decision: Decision
    reason: str
    conditions: tuple[Condition, ...]
    tightest: HalflineMinimum | None
    eta_min: Any
    outcome: Outcome | None = None

    def condition(self, name: str) -> Outcome:
        return next(c.outcome for c in self.conditions if c.name == name)

    @property
    def evidence(self) -> Evidence:
        if self.outcome is not None and self.decision != Decision.PROVED:
            return self.outcome.evidence
        facts: dict[str, Any] = {"conditions": list(self.conditions)}
        if self.tightest is not None:
            facts["tightest_x"] = str(self.tightest.argmin)
            facts["eta_min"] = self.eta_min if self.eta_min is not None else str(self.tightest.value)
        return Evidence(Method.ROOT_ISOLATION, facts=facts)

    def frequencies(self) -> list[float]:
        """Frequencies ``w`` where a condition fails (hints for a termination search)."""
        return failure_frequencies(self.conditions)

    def to_json(self) -> dict[str, Any]:
        return {"decision": self.decision.value, "reason": self.reason,
                "conditions": [c.to_json() for c in self.conditions],
                "tightest_x": str(self.tightest.argmin) if self.tightest is not None else None,
                "eta_min": self.eta_min}


def _diagonal_poles(z11: RationalFunction, z22: RationalFunction) -> Outcome:
    diag = RationalMatrix(((z11, ZERO_FUNCTION), (ZERO_FUNCTION, z22)))
    report = pole_report(diag)
    simple = matrix_pole_conditions(report, "diag(z11, z22)")[1].outcome
    if simple.decision != Decision.PROVED:
        return simple
    return residue_matrix_outcome(diag, report, subject="diag(z11, z22)")


def _real_part_condition(F: RationalFunction, label: str) -> Outcome:
    a, _, d = F.axis_form()
    return kernel.decide_rational_sign(a, d, 0, None, "x", label, transfer=kernel.transfer_json(F.num, F.den, "s"),
                                       transfer_den=F.den)


def llewellyn(Z: Any) -> LlewellynResult:
    """Llewellyn's absolute-stability criterion (impedance form) for a 2-port, decided exactly.

    Conditions (Llewellyn 1952; Haykin 1970): the network is open-circuit stable (no entry has
    a pole in ``Re s > 0``); ``z11`` and ``z22`` have only simple imaginary-axis poles with real
    non-negative residues; and for all ``w``: ``Re z11 >= 0``, ``Re z22 >= 0`` and
    ``2 Re z11 Re z22 - Re(z12 z21) - |z12 z21| >= 0``. The last one is kept polynomial by
    requiring ``N = 2 Re z11 Re z22 - Re(z12 z21) >= 0`` and ``N**2 - |z12 z21|**2 >= 0``. Every
    sign question is a kernel decision on the whole half line ``x = w**2 >= 0``.

    >>> from hapticproof.core.symbols import s
    >>> r = llewellyn(sp.Matrix([[1, 3], [3, 1]]))          # eta = (2 - 9)/9 < 1
    >>> r.decision.value, [c.decision.value for c in r.conditions]
    ('disproved', ['proved', 'proved', 'proved', 'proved', 'disproved'])
    """
    Zr = as_rational_matrix(Z)
    if Zr.shape != (2, 2):
        raise InputFormatError("Llewellyn's criterion is for 2-ports (2x2 matrices)")
    z11, z12, z21, z22 = Zr[0, 0], Zr[0, 1], Zr[1, 0], Zr[1, 1]
    conditions = [Condition(OPEN_CIRCUIT, matrix_pole_conditions(pole_report(Zr))[0].outcome),
                  Condition(DIAGONAL_POLES, _diagonal_poles(z11, z22)),
                  Condition(RE_Z11, _real_part_condition(z11, "Re z11")),
                  Condition(RE_Z22, _real_part_condition(z22, "Re z22"))]
    P = z12 * z21
    tightest, eta_min = None, None
    if P.is_zero():
        conditions.append(Condition(PRODUCT, Outcome(
            Decision.PROVED, Evidence(Method.CANONICAL_FORM),
            "z12 z21 = 0 (unilateral): the product condition reduces to Re z11, Re z22 >= 0")))
    else:
        an, bn, pd = P.axis_form()
        r11n, _, r11d = z11.axis_form()
        r22n, _, r22d = z22.axis_form()
        x = flint.fmpq_poly([0, 1])
        # N = 2 Re z11 Re z22 - Re z12z21 = Nn/Nd with Nd >= 0; |z12 z21|^2 = (an^2 + x bn^2)/pd^2
        Nn = 2 * r11n * r22n * pd - an * r11d * r22d
        Nd = r11d * r22d * pd
        first = kernel.decide_rational_sign(Nn, Nd, 0, None, "x", "2 Re z11 Re z22 - Re z12z21")
        margin = Nn * Nn * pd * pd - (an * an + x * bn * bn) * Nd * Nd
        second = kernel.decide_sign(margin, 0, None, "x", "(2 Re z11 Re z22 - Re z12z21)^2 - |z12z21|^2")
        certificates = {"N >= 0": first.evidence.facts["certificate"],
                        "N^2 - |z12 z21|^2 >= 0": second.evidence.facts["certificate"]}
        failing = first if first.decision == Decision.DISPROVED else second if second.decision == Decision.DISPROVED else None
        if failing is not None:
            outcome = Outcome(Decision.DISPROVED, Evidence(Method.ROOT_ISOLATION, witness=failing.witness, facts=certificates),
                              failing.reason)
        else:
            outcome = Outcome(Decision.PROVED, Evidence(Method.ROOT_ISOLATION, facts=certificates),
                              "2 Re z11 Re z22 - Re(z12 z21) >= |z12 z21| for every w (both polynomial forms certified)")
        conditions.append(Condition(PRODUCT, outcome))
        # eta^2 = N^2/|P|^2 = (Nn^2 pd^2) / (Nd^2 mod2n)
        try:
            g = (Nn * pd).gcd(Nd)
            num, den = ((Nn * pd) // g) ** 2, (Nd // g) ** 2 * (an * an + x * bn * bn)
            h = num.gcd(den)
            tightest = minimise_halfline(num // h, den // h)
            if tightest.exact is not None:
                eta_min = sp.sqrt(tightest.exact)
        except (ValueError, ZeroDivisionError):
            tightest = None
    whole = combine(conditions, subject="the 2-port", holds="absolutely stable (Llewellyn)")
    reason = whole.reason
    if whole.decision == Decision.PROVED:
        reason = "Llewellyn's conditions hold: the 2-port is absolutely stable"
        if tightest is not None:
            where = "w = 0" if tightest.argmin == 0 else ("w -> oo" if tightest.argmin == sp.oo else f"x = w^2 ~ {tightest.argmin_float():.6g}")
            reason += f" (stability factor smallest at {where})"
    return LlewellynResult(whole.decision, reason, tuple(conditions), tightest, eta_min, whole)


def _signed_hermitian_minors(rhat: RationalMatrix, signs: Sequence[int]) -> HermitianMinors:
    """Minors of ``Re K(jw)`` with ``K = J Rhat J``: same-sign entries ``+-Re Rhat``, cross
    entries ``-Im Rhat`` -- a real symmetric function of ``w`` whose minors are even in ``w``.
    The checker gets ``K`` itself (cross entries with the factor ``j``)."""
    n = rhat.shape[0]
    P, L = rhat.polynomial()
    # entries over L(s): Rhat_ij(jw) = P_ij(jw)/L(jw); multiply by |L(jw)|^2: P_ij(jw) conj(L(jw))
    Lr, Li = axis_parts(L)
    out = [[flint.fmpq_poly([])] * n for _ in range(n)]
    for i in range(n):
        for j in range(n):
            pr, pi = axis_parts(P[i][j])
            re = pr * Lr + pi * Li     # Re(P conj L)
            im = pi * Lr - pr * Li     # Im(P conj L)
            if signs[i] == signs[j]:
                out[i][j] = re if signs[i] > 0 else -re
            else:
                out[i][j] = -im
    scale = Lr * Lr + Li * Li

    def factor(i: int, j: int) -> sp.Expr:
        return sp.Integer(1) if signs[i] == signs[j] > 0 else sp.Integer(-1) if signs[i] == signs[j] else sp.I

    def evaluate(witness: Mapping[str, Any]) -> sp.Matrix | None:
        if "omega" not in witness:
            return None
        R = rhat.axis_value(witness["omega"])
        Kw = sp.Matrix(n, n, lambda i, j: factor(i, j) * R[i, j])
        return (Kw + Kw.H).applyfunc(sp.expand)

    entries = []
    for i in range(n):
        row = []
        for j in range(n):
            e = rhat[i, j]
            entry = {"num": kernel.poly_json(-e.num if factor(i, j) == -1 else e.num), "den": kernel.poly_json(e.den)}
            if factor(i, j) == sp.I:
                entry["factor"] = ["0", "1"]
            row.append(entry)
        entries.append(row)
    return minors_from_polynomial_matrix(out, scale, "omega", evaluate=evaluate, transfer={"variable": "s", "entries": entries})


def zprime_positive_real(sym: Symmetrization) -> PositiveRealResult:
    """Positive realness of Youla's ``Z'`` (Definition 3), decided on ``K = J Rhat J``: the same
    four conditions as :func:`positive_real`, each with a kernel certificate.

    >>> Y = symmetrize(sp.Matrix([[1, 2], [-2, 1]]))          # z12 z21 = -4: Z' = [[1, 2j], [2j, 1]]
    >>> zprime_positive_real(Y).decision.value
    'proved'
    """
    if sym.symmetrizable != Decision.PROVED:
        raise ValueError("no symmetrization")
    rhat = sym.rhat
    signs = sym.signs
    signed = any(v < 0 for v in signs)
    report = pole_report(rhat)
    conditions = matrix_pole_conditions(report, "Z'")
    conditions.append(Condition(RESIDUES, residue_matrix_outcome(rhat, report, signs if signed else None, "Z'")))
    minors = _signed_hermitian_minors(rhat, signs) if signed else hermitian_minors(rhat)
    conditions.append(Condition(HERMITIAN, decide_psd(minors, "Z'(jw) + Z'(jw)^H")))
    return PositiveRealResult.from_conditions(conditions, "Z'")


@dataclass(frozen=True)
class Theorem9:
    """Conditions A-E of Theorem 9 (3-DOF bilateral paper), decided exactly, in the corrected
    reading (D: residue matrices of Z' Hermitian PSD; E: all principal minors of Re Z' >= 0) and,
    for E, also as printed (leading principal minors only): ``E_printed`` may hold where E fails.
    A and B are decided through the symmetrization (A covers Youla's longer cycle conditions)."""

    A: Outcome
    B: Outcome
    C: Outcome
    D: Outcome
    E: Outcome
    E_printed: Outcome

    def to_json(self) -> dict[str, Any]:
        return {k: getattr(self, k).to_json() for k in ("A", "B", "C", "D", "E", "E_printed")}


def theorem9_conditions(Z: Any, ports: Sequence[int] | None = None) -> Theorem9:
    """Decide Theorem 9's conditions for a numeric impedance matrix.

    >>> from hapticproof.core.symbols import s
    >>> th = theorem9_conditions(sp.diag(sp.Matrix([[0, 0, 0], [0, 1, 2], [0, 2, 1]]), sp.eye(3)), (3, 3))
    >>> th.E_printed.decision.value, th.E.decision.value       # leading minors 0 >= 0, yet not PSD
    ('proved', 'disproved')
    """
    Zr = as_rational_matrix(Z)
    blocks = port_blocks(Zr.shape[0], ports)
    b_fail = [(i, j) for blk in blocks for i, j in itertools.combinations(blk, 2) if Zr[i, j] != Zr[j, i]]
    B = (Outcome(Decision.DISPROVED, Evidence(Method.CANONICAL_FORM, witness={"pair": [b_fail[0][0] + 1, b_fail[0][1] + 1]}),
                 f"z[{b_fail[0][0] + 1},{b_fail[0][1] + 1}] != z[{b_fail[0][1] + 1},{b_fail[0][0] + 1}]") if b_fail else
         Outcome(Decision.PROVED, Evidence(Method.CANONICAL_FORM), "the diagonal port blocks are symmetric"))
    sym = symmetrize(Zr, ports)
    A = Outcome(sym.symmetrizable, sym.evidence, sym.reason)
    C = matrix_pole_conditions(pole_report(Zr))[0].outcome
    undecided = Outcome(Decision.UNDECIDED, Evidence(Method.CANONICAL_FORM), "no rational Z' (symmetrization failed)")
    if sym.symmetrizable != Decision.PROVED:
        return Theorem9(A, B, C, undecided, undecided, undecided)
    pr = zprime_positive_real(sym)
    signs = sym.signs
    minors = _signed_hermitian_minors(sym.rhat, signs) if any(v < 0 for v in signs) else hermitian_minors(sym.rhat)
    leading = [kernel.decide_sign(minors.leading(k), 0, None, "x", f"leading minor {k}") for k in range(1, minors.n + 1)]
    leading += [kernel.decide_sign(minors.minors[(i,)], 0, None, "x", f"Re z'_{i + 1}{i + 1}") for i in range(minors.n)]
    failed = next((o for o in leading if o.decision == Decision.DISPROVED), None)
    E_printed = failed or Outcome(Decision.PROVED,
                                  Evidence(Method.ROOT_ISOLATION, facts={"certificates": [o.evidence.facts["certificate"] for o in leading]}),
                                  "all leading principal minors (and diagonal entries) of Re Z' are >= 0 for every w")
    residues = pr.residues
    if pr.condition(AXIS_SIMPLE).decision == Decision.DISPROVED:
        residues = pr.condition(AXIS_SIMPLE)
    return Theorem9(A, B, C, residues, pr.hermitian, E_printed)


@dataclass(frozen=True)
class StabilityVerdict:
    """Absolute stability of an n-port: ``decision`` proved (absolutely stable), disproved
    (potentially unstable) or undecided; ``method`` says how. The sub-results that decided it
    (positive realness of ``Z``, Llewellyn, the symmetrization and ``Z'``) carry their
    conditions and certificates; ``certificate`` holds verified destabilizing terminations and
    ``search`` what a termination search tried (also when it found nothing)."""

    decision: Decision
    method: str
    reason: str
    evidence: Evidence
    symmetrization: Symmetrization | None = None
    positive_real: PositiveRealResult | None = None
    llewellyn: LlewellynResult | None = None
    certificate: InstabilityCertificate | None = None
    zprime: PositiveRealResult | None = None
    search: TerminationSearch | None = None
    subnetwork: tuple[tuple[int, ...], Any] | None = None

    def to_json(self) -> dict[str, Any]:
        out: dict[str, Any] = {"decision": self.decision.value, "method": self.method, "reason": self.reason,
                               "evidence": self.evidence.to_json()}
        if self.positive_real is not None:
            out["positive_real"] = self.positive_real.to_json()
        if self.llewellyn is not None:
            out["llewellyn"] = self.llewellyn.to_json()
        if self.symmetrization is not None:
            out["symmetrization"] = {"decision": self.symmetrization.symmetrizable.value, "reason": self.symmetrization.reason}
        if self.zprime is not None:
            out["zprime_positive_real"] = self.zprime.to_json()
        if self.subnetwork is not None:
            ports, result = self.subnetwork
            out["subnetwork"] = {"ports": [k + 1 for k in ports], **result.to_json()}
        if self.certificate is not None:
            out["certificate"] = self.certificate.to_json()
        if self.search is not None:
            out["search"] = self.search.to_json()
        return out


def _hints(*results: Any) -> list[float]:
    out: list[float] = []
    for result in results:
        if result is not None and result.decision == Decision.DISPROVED:
            out += [w for w in result.frequencies() if w not in out]
    return out


def _unstable_subnetwork(Z: RationalMatrix, blocks) -> tuple[tuple[int, ...], Any] | None:
    """A port, or (scalar ports) a pair of ports, whose subnetwork alone -- the other ports held
    at zero velocity, the limit of large resistive terminations -- is potentially unstable: a
    port block that is not positive real, or a 2-port that fails Llewellyn's criterion. Such a
    subnetwork makes the whole network potentially unstable (its RHP zero of ``det(Z_SS + T_S)``
    persists for large enough resistors on the other ports, by Hurwitz's theorem)."""
    if len(blocks) < 2:
        return None
    for k, blk in enumerate(blocks):
        result = positive_real(Z.submatrix(blk))
        if result.decision == Decision.DISPROVED:
            return (k,), result
    if all(len(blk) == 1 for blk in blocks) and len(blocks) > 2:
        for i, j in itertools.combinations(range(len(blocks)), 2):
            result = llewellyn(Z.submatrix((blocks[i][0], blocks[j][0])))
            if result.decision == Decision.DISPROVED:
                return (i, j), result
    return None


def absolute_stability(Z: Any, ports: Sequence[int] | None = None, search: bool = True, seed: int = 0,
                       deadline: float = 10.0, progress: Any = None) -> StabilityVerdict:
    """Absolute stability of an n-port with impedance matrix ``Z`` (exact where possible).

    In this order:

    * an entry with a pole in ``Re s > 0``: potentially unstable (large resistive terminations
      already destabilize it);
    * ``Z`` positive real: absolutely stable, for any grouping of the ports (``Z + T`` is positive
      real for every passive ``T``); decided before anything else;
    * scalar 2-ports: Llewellyn's criterion (:func:`llewellyn`), necessary and sufficient;
    * symmetrizable networks (Youla): absolutely stable iff ``Z'`` is positive real
      (Youla 1959, Lemma 7; identical minors, Lemma 8);
    * otherwise: a port (or, with scalar ports, a pair of ports) whose subnetwork alone is
      potentially unstable -- not positive real, or failing Llewellyn's criterion -- makes the
      network potentially unstable (the other ports held by large resistors);
    * otherwise: a search for destabilizing terminations that ends by ``deadline`` seconds
      (:func:`hapticproof.analysis.terminations.search_terminations`): potentially unstable with a
      verified certificate, or ``undecided after N s`` with what was tried.

    A disproof by theory (Llewellyn, Youla) is followed by the same search for an explicit
    certificate when ``search`` is true; the decision does not depend on it.

    >>> from hapticproof.core.symbols import s
    >>> absolute_stability(sp.Matrix([[1/(s + 1), 0], [0, 1]])).method
    'positive real'
    >>> Zg = sp.diag(sp.Matrix([[2, -1], [-1, 2]]), 2 * sp.eye(2))   # issue 10: was undecided
    >>> absolute_stability(Zg, ports=(2, 2)).decision.value
    'proved'
    """
    Zr = as_rational_matrix(Z)
    n = Zr.shape[0]
    blocks = port_blocks(n, ports)

    def find(*results: Any, open_circuit: bool = False, sym: Symmetrization | None = None,
             prefer: Sequence[Sequence[int]] = ()) -> TerminationSearch | None:
        if not search:
            return None
        return search_terminations(Zr, ports, hints=_hints(*results), seed=seed, deadline=deadline, clamp_all=open_circuit,
                                   similarity=sym.similarity_at if sym is not None else None, prefer=prefer,
                                   progress=progress)

    pr = positive_real(Zr)
    poles = pr.poles
    if poles.decision == Decision.DISPROVED:
        found = find(open_circuit=True)
        return StabilityVerdict(Decision.DISPROVED, "open-circuit instability",
                                f"{poles.reason}: large passive (resistive) terminations destabilize the network",
                                poles.evidence, positive_real=pr, certificate=found.certificate if found else None, search=found)
    if pr.decision == Decision.PROVED:
        return StabilityVerdict(Decision.PROVED, "positive real",
                                "Z is positive real: with any passive termination at its ports it stays positive real, so "
                                "the network is absolutely stable (for any grouping of the ports)", pr.evidence, positive_real=pr)
    if n == 2 and len(blocks) == 2:
        result = llewellyn(Zr)
        found = find(result, pr) if result.decision == Decision.DISPROVED else None
        return StabilityVerdict(result.decision, "Llewellyn", result.reason, result.evidence, positive_real=pr, llewellyn=result,
                                certificate=found.certificate if found else None, search=found)
    sym = symmetrize(Zr, ports)
    zpr = None
    if sym.symmetrizable == Decision.PROVED:
        zpr = zprime_positive_real(sym)
        if zpr.decision != Decision.UNDECIDED:
            found = find(zpr, pr, sym=sym) if zpr.decision == Decision.DISPROVED else None
            reason = ("Z' is positive real: absolutely stable (Youla)" if zpr.decision == Decision.PROVED
                      else f"potentially unstable (Youla): {zpr.reason}")
            return StabilityVerdict(zpr.decision, "Youla symmetrization", reason, zpr.evidence, symmetrization=sym,
                                    positive_real=pr, zprime=zpr, certificate=found.certificate if found else None, search=found)
    why = (f"positive realness of Z' undecided ({zpr.reason})" if zpr is not None
           else f"not symmetrizable ({sym.reason})")
    sub = _unstable_subnetwork(Zr, blocks)
    if sub is not None:
        subset, result = sub
        found = find(result, pr, prefer=[subset])
        names = ", ".join(str(k + 1) for k in subset)
        what = "is not positive real" if len(subset) == 1 else "fails Llewellyn's criterion"
        return StabilityVerdict(
            Decision.DISPROVED, "subnetwork",
            f"{why}; the subnetwork of port{'s' if len(subset) > 1 else ''} {names} alone {what} ({result.reason}): with the "
            "other ports held by large resistors the network is potentially unstable",
            result.evidence, symmetrization=sym, positive_real=pr, zprime=zpr, subnetwork=sub,
            certificate=found.certificate if found else None, search=found)
    found = find(pr)
    if found is not None and found.certificate is not None:
        cert = found.certificate
        return StabilityVerdict(Decision.DISPROVED, "destabilizing terminations",
                                f"{why}; passive terminations put a zero of det(Z + T) at s ~ {cert.roots[0]:.6g} in Re s > 0 "
                                "(verified exactly)",
                                Evidence(Method.COUNTEREXAMPLE, facts={"certificate": cert}), symmetrization=sym,
                                positive_real=pr, zprime=zpr, certificate=cert, search=found)
    tried = found.summary() if found is not None else "no search (search=False)"
    return StabilityVerdict(Decision.UNDECIDED, "none", f"{why}; Z is not positive real; {tried}",
                            Evidence(Method.INSTANCES, facts={"symmetrization": sym.reason,
                                                              **({"search": found} if found is not None else {})}),
                            symmetrization=sym, positive_real=pr, zprime=zpr, search=found)
