r"""n-port networks: positive realness, Llewellyn, Youla symmetrization, absolute stability.

An n-port is given by its impedance matrix ``Z(s)`` (``F = Z V``), real-rational in ``s``. Ports
may be grouped (``ports=(3, 3)``: a 2-port whose ports are 3-DOF, terminated by full 3x3
passive impedances as in the 3-DOF bilateral paper, eq. (13)); the default is scalar ports.

* :func:`positive_real` -- Definition 3 of the 3-DOF bilateral paper (Khalil) for a rational
  matrix: poles in ``Re s <= 0``; imaginary-axis poles (and a pole at infinity) simple with
  Hermitian PSD residue matrices; ``Z(jw) + Z(jw)^H`` PSD for every ``w``, decided exactly
  with all principal minors as polynomials in ``x = w**2``.
* :func:`llewellyn` -- Llewellyn's absolute-stability criterion of a 2-port, exact, with the
  frequency where the stability factor ``eta = (2 Re z11 Re z22 - Re z12 z21)/|z12 z21|`` is
  smallest.
* :func:`symmetrization_conditions` -- Youla's conditions as exact equations in the parameters
  and ``s`` (any n, symbolic entries): A (``z_ij z_jk z_ki = z_ji z_kj z_ik``) and B (diagonal
  port blocks symmetric).
* :func:`symmetrize` -- the reciprocal ``Z'`` of eq. (14) with ``Z'_ij = gamma_ij
  sqrt(z_ij z_ji)``: the signs ``gamma`` are *not* free (they are fixed, up to a diagonal
  ``+-1`` similarity, by the cycle products), the square roots are analytic branches
  (``sqrt(c) q(s)`` with ``q`` rational), and the identity of all principal minors of ``Z`` and
  ``Z'`` (Youla 1960) -- and, for grouped ports, of every block-compatible minor, which is what
  ``det(Z + T) = det(Z' + T)`` for block terminations needs -- is verified exactly.
* :func:`absolute_stability` -- the verdict: Llewellyn for scalar 2-ports; positive realness
  of ``Z'`` (Youla 1959 + 1960) for symmetrizable networks; otherwise a search for passive
  terminations that put a zero of ``det(Z + T)`` in ``Re s > 0``, verified exactly
  (:func:`find_destabilizing_terminations`), or an honest ``undecided``.

All PSD decisions use every principal minor (or the characteristic-polynomial coefficients),
never the leading minors alone.

>>> import sympy as sp
>>> from hapticproof.symbols import s
>>> Zx = sp.Matrix([[9/(s + 3), -1/(s + 1)], [-1/(s + 1), 1/(s + 3)]])    # eq. (5)
>>> result = llewellyn(Zx)
>>> result.decision.value, result.tightest.argmin, result.eta_min
('proved', 0, 1)
"""

from __future__ import annotations

import itertools
import math
from collections.abc import Iterable, Mapping, Sequence
from dataclasses import dataclass, field
from fractions import Fraction
from typing import Any

import flint
import numpy as np
import sympy as sp

from hapticproof.errors import InputFormatError
from hapticproof.evidence import Decision, Evidence, Method, Outcome
from hapticproof.rationalmatrix import (
    AxisPole,
    HalflineMinimum,
    HermitianMinors,
    RationalFunction,
    RationalMatrix,
    decide_nonnegative,
    decide_psd,
    hermitian_minors,
    minimise_halfline,
    minors_from_polynomial_matrix,
    pole_report,
    rhp_roots,
)
from hapticproof.realroots import as_fmpq, to_rational
from hapticproof.symbols import s as S_SYM
from hapticproof.unitcircle import imaginary_axis_rational
from hapticproof.certify import canonical_fraction

__all__ = [
    "as_rational_matrix",
    "port_blocks",
    "PositiveRealResult",
    "positive_real",
    "residue_matrix",
    "LlewellynResult",
    "llewellyn",
    "SymmetrizationCondition",
    "symmetrization_conditions",
    "Symmetrization",
    "symmetrize",
    "StabilityVerdict",
    "Theorem9",
    "theorem9_conditions",
    "absolute_stability",
    "InstabilityCertificate",
    "find_destabilizing_terminations",
    "verify_certificate",
    "input_impedance",
]

_ZERO_RF = RationalFunction(flint.fmpq_poly([]), flint.fmpq_poly([1]))


def as_rational_matrix(Z: Any, s: sp.Symbol = S_SYM) -> RationalMatrix:
    """Accept a :class:`RationalMatrix` or anything ``sympy.Matrix`` accepts (numbers only)."""
    if isinstance(Z, RationalMatrix):
        return Z
    return RationalMatrix.from_sympy(Z, s)


def port_blocks(n: int, ports: Sequence[int] | None) -> tuple[tuple[int, ...], ...]:
    """Index blocks of the ports: ``port_blocks(6, (3, 3)) == ((0, 1, 2), (3, 4, 5))``.

    >>> port_blocks(3, None)
    ((0,), (1,), (2,))
    """
    if ports is None:
        return tuple((i,) for i in range(n))
    if any(int(p) <= 0 for p in ports) or sum(ports) != n:
        raise InputFormatError(f"port sizes {tuple(ports)} do not add up to the matrix size {n}")
    out, start = [], 0
    for p in ports:
        out.append(tuple(range(start, start + int(p))))
        start += int(p)
    return tuple(out)


# ---------------------------------------------------------------------------------------------
# residues
# ---------------------------------------------------------------------------------------------


def _psd_constant(M: sp.Matrix) -> tuple[bool, dict[str, Any]]:
    """Exact PSD test of a constant rational symmetric matrix (characteristic coefficients,
    :func:`hapticproof.psd.is_psd`); the failing principal minor as evidence."""
    from hapticproof.psd import is_psd

    test = is_psd(M)
    if test.holds:
        return True, {}
    rows, value = test.minor if test.minor else ((), None)
    return False, {str(list(rows)): value, "failing_coefficient": f"E_{test.failing}"}


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

    >>> Z = RationalMatrix.from_sympy(sp.Matrix([[2/S_SYM + 1, 1/S_SYM], [1/S_SYM, S_SYM]]))
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


def _pair_residue_psd(B: sp.Matrix, A: sp.Matrix, a: sp.Rational) -> tuple[bool, dict[str, Any]]:
    """Hermitian PSD test of ``B/2 - j A/(2 sqrt a)``: Hermitian iff B symmetric and A
    antisymmetric; its principal minors are even polynomials in ``t = 1/sqrt(a)``."""
    t = sp.Symbol("t")
    n = B.rows
    M = B - sp.I * t * A
    bad = {}
    for k in range(1, n + 1):
        for subset in itertools.combinations(range(n), k):
            poly = sp.Poly(sp.expand(M.extract(list(subset), list(subset)).det(method="berkowitz")), t)
            value = sum(c * sp.Rational(1, a) ** (mon[0] // 2) for mon, c in poly.terms())
            if sp.simplify(value).is_negative:
                bad[str(list(subset))] = value
    return not bad, bad


# ---------------------------------------------------------------------------------------------
# positive realness (Definition 3)
# ---------------------------------------------------------------------------------------------


@dataclass(frozen=True)
class PositiveRealResult:
    """Exact positive-realness decision with the outcome of each condition of Definition 3."""

    decision: Decision
    reason: str
    poles: Outcome
    residues: Outcome
    hermitian: Outcome

    @property
    def evidence(self) -> Evidence:
        for part in (self.poles, self.residues, self.hermitian):
            if part.decision == Decision.DISPROVED:
                return part.evidence
        return Evidence(Method.ROOT_ISOLATION, facts={"poles": self.poles.reason, "residues": self.residues.reason,
                                                      "hermitian": self.hermitian.reason})

    def to_json(self) -> dict[str, Any]:
        return {"decision": self.decision.value, "reason": self.reason, "poles": self.poles.to_json(),
                "residues": self.residues.to_json(), "hermitian": self.hermitian.to_json()}


def _combine(parts: Sequence[tuple[str, Outcome]]) -> tuple[Decision, str]:
    for name, out in parts:
        if out.decision == Decision.DISPROVED:
            return Decision.DISPROVED, f"{name}: {out.reason}"
    for name, out in parts:
        if out.decision == Decision.UNDECIDED:
            return Decision.UNDECIDED, f"{name}: {out.reason}"
    return Decision.PROVED, "; ".join(out.reason for _, out in parts)


def _pole_outcome(Z: RationalMatrix) -> tuple[Outcome, Any]:
    report = pole_report(Z)
    if report.rhp:
        (entry, root) = report.rhp[0]
        return Outcome(Decision.DISPROVED, Evidence(Method.ROOT_ISOLATION, witness={"entry": list(entry), "pole": str(root)}),
                       f"entry {entry} has a pole at s ~ {root:.6g} in Re s > 0"), report
    multiple = [(p.label(), m) for p, m in report.axis if m > 1]
    if multiple or report.improper > 1:
        what = multiple or [("s = oo", report.improper)]
        return Outcome(Decision.DISPROVED, Evidence(Method.CANONICAL_FORM, witness={"pole": what[0][0], "order": what[0][1]}),
                       f"the imaginary-axis pole {what[0][0]} has order {what[0][1]} > 1"), report
    axis = [p.label() for p, _ in report.axis] + (["s = oo"] if report.improper == 1 else [])
    return Outcome(Decision.PROVED, Evidence(Method.ROOT_ISOLATION, facts={"axis_poles": axis}),
                   "no poles in Re s > 0" + (f"; simple poles at {', '.join(axis)}" if axis else "")), report


def _residue_outcome(Z: RationalMatrix, report: Any, signs: Sequence[int] | None = None) -> Outcome:
    """Residue matrices at the imaginary-axis poles (and infinity) Hermitian PSD?

    ``signs`` (for a congruence-scaled Youla matrix with imaginary entries) marks the nodes of
    negative scale: entries between nodes of different sign are ``j`` times the stored real ones.
    """
    facts: dict[str, Any] = {}
    checked = []
    items = [p for p, _ in report.axis] + ([AxisPole("infinity")] if report.improper == 1 else [])
    for pole in items:
        if pole.kind in ("zero", "infinity"):
            R = residue_matrix(Z, pole.kind)
            if signs is not None:
                cross = [(i, j) for i in range(R.rows) for j in range(R.cols) if signs[i] != signs[j] and R[i, j] != 0]
                if cross:
                    return Outcome(Decision.DISPROVED, Evidence(Method.CANONICAL_FORM, witness={"pole": pole.label(), "entry": list(cross[0])}),
                                   f"the residue matrix at {pole.label()} is not Hermitian (imaginary off-diagonal entry)")
                R = sp.Matrix(R.rows, R.cols, lambda i, j: -R[i, j] if signs[i] < 0 and signs[j] < 0 else R[i, j])
            if R != R.T:
                return Outcome(Decision.DISPROVED, Evidence(Method.CANONICAL_FORM, witness={"pole": pole.label()}, facts={"residue": R}),
                               f"the residue matrix at {pole.label()} is not Hermitian")
            ok, bad = _psd_constant(R)
            facts[pole.label()] = R
            if not ok:
                return Outcome(Decision.DISPROVED, Evidence(Method.CANONICAL_FORM, witness={"pole": pole.label()},
                                                            facts={"residue": R, "negative_principal_minors": bad}),
                               f"the residue matrix at {pole.label()} is not PSD")
            checked.append(pole.label())
        elif pole.kind == "pair":
            if signs is not None and any(v < 0 for v in signs):
                return Outcome(Decision.UNDECIDED, Evidence(Method.CANONICAL_FORM, facts={"pole": pole.label()}),
                               f"residues at {pole.label()} of a Youla matrix with imaginary entries are not implemented")
            B, A = residue_matrix(Z, ("pair", pole.a))
            if B != B.T or A != -A.T:
                return Outcome(Decision.DISPROVED, Evidence(Method.CANONICAL_FORM, witness={"pole": pole.label()}),
                               f"the residue matrix at {pole.label()} is not Hermitian")
            ok, bad = _pair_residue_psd(B, A, pole.a)
            facts[pole.label()] = {"B": B, "A": A}
            if not ok:
                return Outcome(Decision.DISPROVED, Evidence(Method.CANONICAL_FORM, witness={"pole": pole.label()},
                                                            facts={"negative_principal_minors": bad}),
                               f"the residue matrix at {pole.label()} is not PSD")
            checked.append(pole.label())
        else:
            return Outcome(Decision.UNDECIDED, Evidence(Method.CANONICAL_FORM, facts={"pole": pole.label()}),
                           f"residues at the irrational axis poles {pole.label()} are not implemented")
    if not checked:
        return Outcome(Decision.PROVED, Evidence(Method.CANONICAL_FORM), "no imaginary-axis poles")
    return Outcome(Decision.PROVED, Evidence(Method.CANONICAL_FORM, facts={"residues": facts}),
                   f"residue matrices Hermitian PSD at {', '.join(checked)}")


def positive_real(Z: Any, method: str = "charpoly") -> PositiveRealResult:
    """Exact positive realness of a square real-rational matrix (Definition 3, Khalil).

    A pole at infinity (an improper entry such as a mass ``M s``) is allowed when simple with a
    symmetric PSD coefficient, as for impedances of LC networks.

    >>> import sympy as sp
    >>> from hapticproof.symbols import s
    >>> positive_real(sp.Matrix([[1/(s + 1), 0], [0, s]])).decision.value
    'proved'
    >>> r = positive_real(sp.Matrix([[1, 2], [0, 1]]))       # Hermitian part [[1, 1], [1, 1]] - ok
    >>> r.decision.value, positive_real(sp.Matrix([[1, 3], [0, 1]])).hermitian.witness
    ('proved', {'x': 1, 'omega': 1})
    """
    Zr = as_rational_matrix(Z)
    n, m = Zr.shape
    if n != m:
        raise InputFormatError("positive realness needs a square matrix")
    poles, report = _pole_outcome(Zr)
    if poles.decision == Decision.DISPROVED:
        skipped = Outcome(Decision.UNDECIDED, Evidence(Method.CANONICAL_FORM), "not examined (pole condition fails)")
        return PositiveRealResult(Decision.DISPROVED, f"poles: {poles.reason}", poles, skipped, skipped)
    residues = _residue_outcome(Zr, report)
    herm = decide_psd(hermitian_minors(Zr), method)
    decision, reason = _combine([("poles", poles), ("residues", residues), ("Hermitian part", herm)])
    return PositiveRealResult(decision, reason, poles, residues, herm)


def input_impedance(Z: Any, termination: Any, ports: Sequence[int]) -> RationalMatrix:
    """Impedance seen at the first port group when the second is terminated by ``termination``:
    ``Z11 - Z12 (Z22 + T)^-1 Z21`` (``ports=(p1, p2)``).

    >>> from hapticproof.symbols import s
    >>> input_impedance(sp.Matrix([[2, 1], [1, 2]]), sp.Matrix([[1]]), (1, 1)).to_sympy()
    Matrix([[5/3]])
    """
    Zr = as_rational_matrix(Z)
    T = as_rational_matrix(termination)
    a, b = port_blocks(Zr.shape[0], ports)
    Z11, Z12 = Zr.submatrix(a, a), Zr.submatrix(a, b)
    Z21, Z22 = Zr.submatrix(b, a), Zr.submatrix(b, b)
    return Z11 - Z12 @ (Z22 + T).inverse() @ Z21


# ---------------------------------------------------------------------------------------------
# Llewellyn
# ---------------------------------------------------------------------------------------------


@dataclass(frozen=True)
class LlewellynResult:
    """Llewellyn's criterion for a 2-port: each condition's outcome, the overall decision, and
    where the stability factor ``eta`` is smallest (``tightest``; ``eta_min`` its exact value
    when the minimiser is rational)."""

    decision: Decision
    reason: str
    conditions: Mapping[str, Outcome]
    tightest: HalflineMinimum | None
    eta_min: Any

    @property
    def evidence(self) -> Evidence:
        for out in self.conditions.values():
            if out.decision == Decision.DISPROVED:
                return out.evidence
        facts = {k: v.reason for k, v in self.conditions.items()}
        if self.tightest is not None:
            facts["tightest_x"] = str(self.tightest.argmin)
            facts["eta_min"] = self.eta_min if self.eta_min is not None else str(self.tightest.value)
        return Evidence(Method.ROOT_ISOLATION, facts=facts)


def _xform(F: RationalFunction) -> tuple[flint.fmpq_poly, flint.fmpq_poly, flint.fmpq_poly]:
    """``Re F(jw) = a/d`` and ``Im F(jw) = w b/d`` with polynomials in ``x`` and ``d >= 0``."""
    re, im = imaginary_axis_rational(F.expr(S_SYM))
    re, im = re.numeric(), im.numeric()
    # bring both to the common denominator |Q(jw)|^2 (re.den and im.den divide it)
    d = re.den * im.den // re.den.gcd(im.den)
    return re.num * (d // re.den), im.num * (d // im.den), d


def llewellyn(Z: Any) -> LlewellynResult:
    """Llewellyn's absolute-stability criterion (impedance form) for a 2-port, decided exactly.

    Conditions (Llewellyn 1952; Haykin 1970): the network is open-circuit stable (no entry has
    a pole in ``Re s > 0``); ``z11`` and ``z22`` have only simple imaginary-axis poles with real
    non-negative residues; and for all ``w``: ``Re z11 >= 0``, ``Re z22 >= 0`` and
    ``2 Re z11 Re z22 - Re(z12 z21) - |z12 z21| >= 0``. The last one is kept polynomial by
    requiring ``N = 2 Re z11 Re z22 - Re(z12 z21) >= 0`` and ``N**2 - |z12 z21|**2 >= 0``.
    """
    Zr = as_rational_matrix(Z)
    if Zr.shape != (2, 2):
        raise InputFormatError("Llewellyn's criterion is for 2-ports (2x2 matrices)")
    z11, z12, z21, z22 = Zr[0, 0], Zr[0, 1], Zr[1, 0], Zr[1, 1]
    conditions: dict[str, Outcome] = {}
    poles, _ = _pole_outcome(Zr)
    rhp = pole_report(Zr).rhp
    conditions["open-circuit stability"] = (
        Outcome(Decision.DISPROVED, poles.evidence, poles.reason) if rhp else
        Outcome(Decision.PROVED, Evidence(Method.ROOT_ISOLATION), "no entry has a pole in Re s > 0"))
    diag = RationalMatrix(((z11, _ZERO_RF), (_ZERO_RF, z22)))
    dpoles, dreport = _pole_outcome(diag)
    if dpoles.decision == Decision.PROVED:
        conditions["z11, z22 axis poles"] = _residue_outcome(diag, dreport)
    else:
        conditions["z11, z22 axis poles"] = dpoles
    r11n, _, r11d = _xform(z11)
    r22n, _, r22d = _xform(z22)
    conditions["Re z11 >= 0"] = decide_nonnegative(r11n * r11d, "Re z11")
    conditions["Re z22 >= 0"] = decide_nonnegative(r22n * r22d, "Re z22")
    P = z12 * z21
    tightest, eta_min = None, None
    if P.is_zero():
        conditions["2 Re z11 Re z22 - Re z12z21 - |z12z21| >= 0"] = Outcome(
            Decision.PROVED, Evidence(Method.CANONICAL_FORM), "z12 z21 = 0 (unilateral): the product condition reduces to Re z11, Re z22 >= 0")
    else:
        an, bn, pd = _xform(P)
        x = flint.fmpq_poly([0, 1])
        # N = 2 r11 r22 - a  over the denominator r11d r22d pd (all >= 0)
        Nn = 2 * r11n * r22n * pd - an * r11d * r22d
        Nd = r11d * r22d * pd
        mod2n = an * an + x * bn * bn            # |P|^2 = mod2n / pd^2
        first = decide_nonnegative(Nn * Nd, "2 Re z11 Re z22 - Re z12z21")
        margin = Nn * Nn * pd * pd - mod2n * Nd * Nd
        second = decide_nonnegative(margin, "(2 Re z11 Re z22 - Re z12z21)^2 - |z12z21|^2")
        if first.decision == Decision.DISPROVED:
            conditions["2 Re z11 Re z22 - Re z12z21 - |z12z21| >= 0"] = first
        elif second.decision == Decision.DISPROVED:
            conditions["2 Re z11 Re z22 - Re z12z21 - |z12z21| >= 0"] = second
        else:
            conditions["2 Re z11 Re z22 - Re z12z21 - |z12z21| >= 0"] = Outcome(
                Decision.PROVED, Evidence(Method.ROOT_ISOLATION, facts={"first": first.reason, "second": second.reason}),
                "2 Re z11 Re z22 - Re(z12 z21) >= |z12 z21| for every w")
        # eta^2 = N^2/|P|^2 = (Nn^2 pd^2) / (Nd^2 mod2n)
        try:
            g = (Nn * pd).gcd(Nd)
            num, den = ((Nn * pd) // g) ** 2, (Nd // g) ** 2 * mod2n
            h = num.gcd(den)
            tightest = minimise_halfline(num // h, den // h)
            if tightest.exact is not None:
                eta_min = sp.sqrt(tightest.exact)
        except ValueError:
            tightest = None
    decision, reason = _combine(list(conditions.items()))
    if decision == Decision.PROVED:
        reason = "Llewellyn's conditions hold: the 2-port is absolutely stable"
        if tightest is not None:
            where = "w = 0" if tightest.argmin == 0 else ("w -> oo" if tightest.argmin == sp.oo else f"x = w^2 ~ {tightest.argmin_float():.6g}")
            reason += f" (stability factor smallest at {where})"
    return LlewellynResult(decision, reason, conditions, tightest, eta_min)


# ---------------------------------------------------------------------------------------------
# symmetrization conditions (symbolic, any n)
# ---------------------------------------------------------------------------------------------


@dataclass(frozen=True)
class SymmetrizationCondition:
    """One of Youla's symmetrization conditions as ``expr = 0`` for all ``s``.

    ``kind`` is ``'B'`` (``z_ij = z_ji`` inside a port block) or ``'A'`` (the triple products;
    ``reduced`` when a factor ``z_ij = z_ji`` known from B was cancelled, leaving
    ``z_jk z_ki - z_kj z_ik``). ``expr`` is the numerator polynomial in ``s`` and the parameters.
    """

    kind: str
    indices: tuple[int, ...]
    expr: sp.Expr
    reduced: bool = False

    def at_frequency(self, omega: sp.Symbol) -> sp.Expr:
        """The condition on the imaginary axis: ``expr`` with ``s = j omega``, expanded."""
        return sp.expand(self.expr.subs(S_SYM, sp.I * omega))

    def coefficients(self) -> list[sp.Expr]:
        """The equations in the parameters alone (coefficients of the powers of ``s``)."""
        return [c for c in sp.Poly(self.expr, S_SYM).all_coeffs() if c != 0]


def _num_den(expr: sp.Expr) -> tuple[sp.Expr, sp.Expr]:
    num, den = canonical_fraction(expr)
    return sp.expand(num), sp.expand(den)


def symmetrization_conditions(
    Z: Any, ports: Sequence[int] | None = None, reduce: bool = True, s: sp.Symbol = S_SYM
) -> list[SymmetrizationCondition]:
    """Youla's symmetrization conditions of an n-port as exact equations (symbolic entries allowed).

    A: ``z_ij z_jk z_ki = z_ji z_kj z_ik`` for all triples; B: every diagonal port block is
    symmetric. With ``reduce``, a triple containing a pair that B makes symmetric
    (``z_ij = z_ji``, assumed nonzero) is divided by it. Conditions that hold identically are
    omitted. The case study of the 3-DOF bilateral paper gives 6 B-conditions (26)-(31) and
    18 reduced A-conditions, of which (32)-(37) are a spanning subset.

    >>> from hapticproof.symbols import s
    >>> a, b = sp.symbols('a b')
    >>> [(c.kind, c.indices, c.expr) for c in symmetrization_conditions(sp.Matrix([[1, a], [b, 1]]), ports=(2,))]
    [('B', (0, 1), -a + b)]
    """
    M = sp.Matrix(Z)
    n = M.rows
    blocks = port_blocks(n, ports)
    nd = {(i, j): _num_den(M[i, j]) for i in range(n) for j in range(n)}
    out: list[SymmetrizationCondition] = []
    symmetric_pairs = set()
    for blk in blocks:
        for i, j in itertools.combinations(blk, 2):
            (ni, di), (nj, dj) = nd[(i, j)], nd[(j, i)]
            expr = sp.expand(nj * di - ni * dj)
            symmetric_pairs.add((i, j))
            if expr != 0:
                out.append(SymmetrizationCondition("B", (i, j), expr))
    for i, j, k in itertools.combinations(range(n), 3):
        pairs = [(i, j), (j, k), (i, k)]
        # A: z_ij z_jk z_ki - z_ji z_kj z_ik ; reduce by a B-symmetric pair
        cancel = next((p for p in pairs if p in symmetric_pairs and M[p[0], p[1]] != 0), None) if reduce else None
        if cancel is None:
            fwd = [(i, j), (j, k), (k, i)]
            bwd = [(j, i), (k, j), (i, k)]
        else:
            a, b = cancel
            c = ({i, j, k} - {a, b}).pop()
            # z_ab z_bc z_ca = z_ba z_cb z_ac  with z_ab = z_ba  ->  z_bc z_ca = z_cb z_ac
            fwd = [(b, c), (c, a)]
            bwd = [(c, b), (a, c)]
        lhs_n, lhs_d = sp.Integer(1), sp.Integer(1)
        rhs_n, rhs_d = sp.Integer(1), sp.Integer(1)
        for p in fwd:
            lhs_n, lhs_d = lhs_n * nd[p][0], lhs_d * nd[p][1]
        for p in bwd:
            rhs_n, rhs_d = rhs_n * nd[p][0], rhs_d * nd[p][1]
        expr = sp.expand(lhs_n * rhs_d - rhs_n * lhs_d)
        if expr != 0:
            out.append(SymmetrizationCondition("A", (i, j, k), expr, reduced=cancel is not None))
    return out


# ---------------------------------------------------------------------------------------------
# Youla symmetrization (numeric, exact)
# ---------------------------------------------------------------------------------------------


def _square_decomposition(p: RationalFunction) -> tuple[flint.fmpq, RationalFunction] | None:
    """``p = c q**2`` with ``c`` rational and ``q`` rational (numerator and denominator with
    positive leading coefficients), or None when the square-free part is not constant."""
    def split(poly: flint.fmpq_poly) -> tuple[flint.fmpq, flint.fmpq_poly] | None:
        content, factors = poly.numer().factor_squarefree()
        root = flint.fmpq_poly([1])
        for f, mult in factors:
            if mult % 2:
                return None
            root *= flint.fmpq_poly(f) ** (mult // 2)
        rest = poly / (root * root)
        if rest.degree() != 0:  # pragma: no cover - guaranteed by the factorization
            return None
        c = rest.coeffs()[0]
        if root.coeffs()[-1] < 0:
            root = -root
        return c, root

    top = split(p.num)
    bottom = split(p.den)
    if top is None or bottom is None:
        return None
    (cn, qn), (cd, qd) = top, bottom
    return cn / cd, RationalFunction.make(qn, qd)


def _rational_sqrt(q: flint.fmpq) -> flint.fmpq | None:
    if q < 0:
        return None
    num, den = int(q.p), int(q.q)
    rn, rd = math.isqrt(num), math.isqrt(den)
    if rn * rn == num and rd * rd == den:
        return flint.fmpq(rn, rd)
    return None


@dataclass(frozen=True)
class Symmetrization:
    """Youla's reciprocal equivalent ``Z'`` of an n-port, or why there is none.

    When ``symmetrizable`` is PROVED: ``Z'_ij = gamma[i, j] sqrt(c[i, j]) q[i, j](s)`` (off the
    diagonal; ``Z'_ii = z_ii``), with ``q`` rational. ``scales`` are rationals ``u_i`` such that
    the congruent matrix ``K = D Z' D``, ``D = diag(sqrt|u_i|)``, is ``J Rhat J`` with a *rational*
    symmetric ``Rhat`` (``J_ii = j`` where ``u_i < 0``): PR of ``Z'`` is decided on ``Rhat``.
    ``evidence`` records the exact check that every principal minor of ``Z'`` equals the one of
    ``Z`` (and, for grouped ports, every block-compatible minor).
    """

    symmetrizable: Decision
    reason: str
    evidence: Evidence
    gamma: Mapping[tuple[int, int], int] = field(default_factory=dict)
    c: Mapping[tuple[int, int], Any] = field(default_factory=dict)
    q: Mapping[tuple[int, int], RationalFunction] = field(default_factory=dict)
    scales: tuple[Any, ...] = ()
    rhat: RationalMatrix | None = None
    diagonal: tuple[RationalFunction, ...] = ()

    @property
    def signs(self) -> tuple[int, ...]:
        return tuple(1 if u > 0 else -1 for u in self.scales)

    def zprime(self, s: sp.Symbol = S_SYM) -> sp.Matrix:
        """``Z'`` as an exact SymPy matrix (square roots of rational constants kept exact)."""
        if self.symmetrizable != Decision.PROVED:
            raise ValueError("no symmetrization")
        n = len(self.diagonal)
        out = sp.zeros(n, n)
        for i in range(n):
            out[i, i] = self.diagonal[i].expr(s)
        for (i, j), g in self.gamma.items():
            value = g * sp.sqrt(to_rational(self.c[(i, j)])) * self.q[(i, j)].expr(s)
            out[i, j] = out[j, i] = value
        return out


def _cycle_path(parent: Mapping[int, int | None], depth: Mapping[int, int], a: int, b: int) -> list[int]:
    """Tree path from ``a`` to ``b`` (list of vertices)."""
    left, right = [a], [b]
    while left[-1] != right[-1]:
        if depth[left[-1]] >= depth[right[-1]]:
            left.append(parent[left[-1]])
        else:
            right.append(parent[right[-1]])
    return left + right[-2::-1]


def symmetrize(Z: Any, ports: Sequence[int] | None = None) -> Symmetrization:
    """Construct Youla's reciprocal ``Z'`` (eq. (14) of the 3-DOF bilateral paper) exactly.

    Steps: B (diagonal port blocks symmetric); for each pair ``p_ij = z_ij z_ji = c_ij q_ij**2``
    (else ``Z'`` is irrational: undecided); a spanning forest of the nonzero pairs, on which the
    signs are free (a diagonal ``+-1`` similarity); every other pair closes a cycle whose
    forward and backward products of ``z`` must agree (Youla's cycle conditions: for triangles
    this is condition A, longer cycles matter when entries vanish) and whose product fixes its
    sign ``gamma``. Finally all principal minors (and block-compatible minors) are compared.

    >>> from hapticproof.symbols import s
    >>> Y = symmetrize(sp.Matrix([[2, 4], [1, 3]]))           # z12 z21 = 4
    >>> Y.symmetrizable.value, Y.zprime()
    ('proved', Matrix([
    [2, 2],
    [2, 3]]))
    """
    Zr = as_rational_matrix(Z)
    n = Zr.shape[0]
    blocks = port_blocks(n, ports)
    for blk in blocks:
        for i, j in itertools.combinations(blk, 2):
            if Zr[i, j] != Zr[j, i]:
                return Symmetrization(Decision.DISPROVED, f"condition B fails: z[{i},{j}] != z[{j},{i}] in a port block",
                                      Evidence(Method.CANONICAL_FORM, witness={"pair": [i, j]}))
    # triangle conditions A (exact)
    for i, j, k in itertools.combinations(range(n), 3):
        fwd = Zr[i, j] * Zr[j, k] * Zr[k, i]
        bwd = Zr[j, i] * Zr[k, j] * Zr[i, k]
        if fwd != bwd:
            return Symmetrization(Decision.DISPROVED, f"condition A fails for (i, j, k) = ({i}, {j}, {k})",
                                  Evidence(Method.CANONICAL_FORM, witness={"triple": [i, j, k]},
                                           facts={"difference": (fwd - bwd).expr()}))
    c: dict[tuple[int, int], flint.fmpq] = {}
    q: dict[tuple[int, int], RationalFunction] = {}
    for i, j in itertools.combinations(range(n), 2):
        p = Zr[i, j] * Zr[j, i]
        if p.is_zero():
            # a unilateral (or absent) coupling: Z'_ij = 0; cycles through it are checked by the minors
            continue
        dec = _square_decomposition(p)
        if dec is None:
            return Symmetrization(Decision.UNDECIDED, f"z[{i},{j}] z[{j},{i}] is not a constant times a square: Z' is irrational",
                                  Evidence(Method.CANONICAL_FORM, witness={"pair": [i, j]}, facts={"product": p.expr()}))
        c[(i, j)], q[(i, j)] = dec
    # spanning forest
    adjacency = {i: [] for i in range(n)}
    for i, j in c:
        adjacency[i].append(j)
        adjacency[j].append(i)
    parent: dict[int, int | None] = {}
    depth: dict[int, int] = {}
    u: dict[int, flint.fmpq] = {}
    tree = set()
    for root in range(n):
        if root in parent:
            continue
        parent[root], depth[root], u[root] = None, 0, flint.fmpq(1)
        queue = [root]
        while queue:
            a = queue.pop(0)
            for b in sorted(adjacency[a]):
                if b not in parent:
                    parent[b], depth[b] = a, depth[a] + 1
                    key = (min(a, b), max(a, b))
                    u[b] = u[a] * c[key]
                    tree.add(key)
                    queue.append(b)
    # magnitudes r_ij = sqrt(u_i u_j c_ij) must be rational for every pair
    r: dict[tuple[int, int], flint.fmpq] = {}
    for (i, j), cij in c.items():
        root_value = _rational_sqrt(u[i] * u[j] * cij)
        if root_value is None:
            return Symmetrization(Decision.UNDECIDED,
                                  f"no rational diagonal scaling makes Z' rational (pair {i},{j}); Z' has irrational coefficients",
                                  Evidence(Method.CANONICAL_FORM, witness={"pair": [i, j]}))
        r[(i, j)] = root_value
    gamma: dict[tuple[int, int], int] = {key: 1 for key in tree}

    def rhat_entry(i: int, j: int, g: int) -> RationalFunction:
        key = (min(i, j), max(i, j))
        value = q[key].scale(r[key] * g)
        if u[i] < 0 and u[j] < 0:
            value = -value
        return value

    for key in sorted(set(c) - tree):
        i, j = key
        path = _cycle_path(parent, depth, j, i)  # j -> ... -> i along the tree, then i -> j closes it
        cycle = path + [j]
        fwd = RationalFunction.constant(1)
        bwd = RationalFunction.constant(1)
        for a, b in zip(cycle, cycle[1:]):
            fwd = fwd * Zr[a, b]
            bwd = bwd * Zr[b, a]
        if fwd != bwd:
            return Symmetrization(Decision.DISPROVED,
                                  f"Youla's cycle condition fails on the cycle {cycle}: forward and backward products of z differ",
                                  Evidence(Method.CANONICAL_FORM, witness={"cycle": cycle},
                                           facts={"forward": fwd.expr(), "backward": bwd.expr()}))
        # prod over the cycle of K_e = prod |u_v| * fwd, K_e = J-adjusted Rhat entries
        prod_u = flint.fmpq(1)
        for v in path:
            prod_u *= abs(u[v])
        target = fwd.scale(prod_u)
        current = RationalFunction.constant(1)
        j_count = 0
        for a, b in zip(path, path[1:]):
            kk = (min(a, b), max(a, b))
            current = current * q[kk].scale(r[kk] * gamma[kk])
            j_count += c[kk] < 0
        base = q[key].scale(r[key])
        j_count += c[key] < 0
        sign_j = -1 if (j_count // 2) % 2 else 1
        ratio = target / (current * base).scale(sign_j)
        if ratio == RationalFunction.constant(1):
            gamma[key] = 1
        elif ratio == RationalFunction.constant(-1):
            gamma[key] = -1
        else:  # pragma: no cover - fwd == bwd makes the ratio +-1
            return Symmetrization(Decision.DISPROVED, f"no sign makes the cycle {cycle} consistent",
                                  Evidence(Method.CANONICAL_FORM, witness={"cycle": cycle}))
    rows = []
    for i in range(n):
        row = []
        for j in range(n):
            if i == j:
                row.append(Zr[i, i])
            else:
                key = (min(i, j), max(i, j))
                row.append(rhat_entry(i, j, gamma[key]) if key in c else _ZERO_RF)
        rows.append(tuple(row))
    # Rhat_ii must carry the scale too: K_ii = |u_i| z_ii, Rhat_ii = K_ii / J_ii^2 = u_i z_ii
    rows = [tuple(e.scale(u[i]) if jj == i else e for jj, e in enumerate(row)) for i, row in enumerate(rows)]
    rhat = RationalMatrix(tuple(rows))
    scales = tuple(to_rational(u[i]) for i in range(n))
    check = _verify_minors(Zr, rhat, [u[i] for i in range(n)], blocks)
    result_kwargs = dict(gamma=gamma, c={k: to_rational(v) for k, v in c.items()}, q=q, scales=scales, rhat=rhat,
                         diagonal=tuple(Zr[i, i] for i in range(n)))
    if check is not None:
        return Symmetrization(Decision.DISPROVED, check[0], check[1], **result_kwargs)
    facts = {"principal_minors_checked": 2**n - 1, "scales": list(scales),
             "gamma": {f"{i},{j}": g for (i, j), g in sorted(gamma.items())}}
    if any(len(b) > 1 for b in blocks):
        facts["block_compatible_minors_checked"] = _count_block_pairs(blocks)
    return Symmetrization(Decision.PROVED,
                          "Z' is reciprocal and has the same principal minors as Z"
                          + (" (and the same block-compatible minors: det(Z + T) = det(Z' + T) for block terminations)"
                             if any(len(b) > 1 for b in blocks) else ""),
                          Evidence(Method.CANONICAL_FORM, facts=facts), **result_kwargs)


def _count_block_pairs(blocks: Sequence[Sequence[int]]) -> int:
    total = 1
    for blk in blocks:
        total *= sum(math.comb(len(blk), k) ** 2 for k in range(len(blk) + 1))
    return total - 1


def _block_pairs(blocks: Sequence[Sequence[int]]):
    """Row/column index sets with the same number of indices in every block (nonempty)."""
    per_block = []
    for blk in blocks:
        options = []
        for k in range(len(blk) + 1):
            subsets = list(itertools.combinations(blk, k))
            options.append([(a, b) for a in subsets for b in subsets])
        per_block.append([pair for opt in options for pair in opt])
    for combo in itertools.product(*per_block):
        rows = tuple(i for a, _ in combo for i in a)
        cols = tuple(j for _, b in combo for j in b)
        if rows:
            yield rows, cols


def _verify_minors(Zr: RationalMatrix, rhat: RationalMatrix, u: Sequence[flint.fmpq], blocks) -> tuple[str, Evidence] | None:
    """Check det Rhat[I, J] * j^(#neg I + #neg J) == det Z[I, J] * sqrt(prod_I |u| prod_J |u|)."""
    scalar = all(len(b) == 1 for b in blocks)
    pairs = ((S, S) for k in range(1, len(u) + 1) for S in itertools.combinations(range(len(u)), k)) if scalar else _block_pairs(blocks)
    for rows, cols in pairs:
        left = rhat.minor(rows, cols)
        right = Zr.minor(rows, cols)
        negs = sum(u[i] < 0 for i in rows) + sum(u[j] < 0 for j in cols)
        weight = flint.fmpq(1)
        for i in rows:
            weight *= abs(u[i])
        for j in cols:
            weight *= abs(u[j])
        root = _rational_sqrt(weight)
        if negs % 2 or root is None:
            ok = left.is_zero() and right.is_zero()
        else:
            sign = -1 if (negs // 2) % 2 else 1
            ok = left.scale(sign) == right.scale(root)
        if not ok:
            what = "principal minor" if rows == cols else "block-compatible minor"
            return (f"the {what} on rows {list(rows)}, columns {list(cols)} of Z' differs from that of Z",
                    Evidence(Method.CANONICAL_FORM, witness={"rows": list(rows), "cols": list(cols)},
                             facts={"Z": right.expr()}))
    return None


def _signed_hermitian_minors(rhat: RationalMatrix, signs: Sequence[int]) -> HermitianMinors:
    """Minors of ``Re K(jw)`` with ``K = J Rhat J``: same-sign entries ``+-Re Rhat``, cross
    entries ``-Im Rhat`` -- a real symmetric function of ``w`` whose minors are even in ``w``."""
    n = rhat.shape[0]
    P, L = rhat.polynomial()
    # entries over L(s): Rhat_ij(jw) = P_ij(jw)/L(jw); multiply by |L(jw)|^2: P_ij(jw) conj(L(jw))
    from hapticproof.rationalmatrix import _axis_parts

    Lr, Li = _axis_parts(L)
    out = [[flint.fmpq_poly([])] * n for _ in range(n)]
    for i in range(n):
        for j in range(n):
            pr, pi = _axis_parts(P[i][j])
            re = pr * Lr + pi * Li     # Re(P conj L)
            im = pi * Lr - pr * Li     # Im(P conj L)
            if signs[i] == signs[j]:
                out[i][j] = re if signs[i] > 0 else -re
            else:
                out[i][j] = -im
    scale = Lr * Lr + Li * Li
    return minors_from_polynomial_matrix(out, scale, "omega")


def _youla_positive_real(sym: Symmetrization) -> PositiveRealResult:
    rhat = sym.rhat
    signs = sym.signs
    poles, report = _pole_outcome(rhat)
    if poles.decision == Decision.DISPROVED:
        skipped = Outcome(Decision.UNDECIDED, Evidence(Method.CANONICAL_FORM), "not examined (pole condition fails)")
        return PositiveRealResult(Decision.DISPROVED, f"poles of Z': {poles.reason}", poles, skipped, skipped)
    residues = _residue_outcome(rhat, report, signs if any(v < 0 for v in signs) else None)
    herm = decide_psd(_signed_hermitian_minors(rhat, signs) if any(v < 0 for v in signs) else hermitian_minors(rhat))
    decision, reason = _combine([("poles", poles), ("residues", residues), ("Hermitian part", herm)])
    return PositiveRealResult(decision, reason, poles, residues, herm)


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

    >>> from hapticproof.symbols import s
    >>> th = theorem9_conditions(sp.diag(sp.Matrix([[0, 0, 0], [0, 1, 2], [0, 2, 1]]), sp.eye(3)), (3, 3))
    >>> th.E_printed.decision.value, th.E.decision.value       # leading minors 0 >= 0, yet not PSD
    ('proved', 'disproved')
    """
    Zr = as_rational_matrix(Z)
    blocks = port_blocks(Zr.shape[0], ports)
    b_fail = [(i, j) for blk in blocks for i, j in itertools.combinations(blk, 2) if Zr[i, j] != Zr[j, i]]
    B = (Outcome(Decision.DISPROVED, Evidence(Method.CANONICAL_FORM, witness={"pair": list(b_fail[0])}),
                 f"z[{b_fail[0][0]},{b_fail[0][1]}] != z[{b_fail[0][1]},{b_fail[0][0]}]") if b_fail else
         Outcome(Decision.PROVED, Evidence(Method.CANONICAL_FORM), "the diagonal port blocks are symmetric"))
    sym = symmetrize(Zr, ports)
    A = Outcome(sym.symmetrizable, sym.evidence, sym.reason)
    poles, _ = _pole_outcome(Zr)
    C = poles if pole_report(Zr).rhp else Outcome(Decision.PROVED, poles.evidence, "no entry of Z has a pole in Re s > 0")
    undecided = Outcome(Decision.UNDECIDED, Evidence(Method.CANONICAL_FORM), "no rational Z' (symmetrization failed)")
    if sym.symmetrizable != Decision.PROVED:
        return Theorem9(A, B, C, undecided, undecided, undecided)
    pr = _youla_positive_real(sym)
    signs = sym.signs
    minors = _signed_hermitian_minors(sym.rhat, signs) if any(v < 0 for v in signs) else hermitian_minors(sym.rhat)
    leading = [decide_nonnegative(minors.leading(k), f"leading minor {k}") for k in range(1, minors.n + 1)]
    leading += [decide_nonnegative(minors.minors[(i,)], f"Re z'_{i + 1}{i + 1}") for i in range(minors.n)]
    failed = next((o for o in leading if o.decision == Decision.DISPROVED), None)
    E_printed = failed or Outcome(Decision.PROVED, Evidence(Method.ROOT_ISOLATION),
                                  "all leading principal minors (and diagonal entries) of Re Z' are >= 0 for every w")
    return Theorem9(A, B, C, pr.residues, pr.hermitian, E_printed)


# ---------------------------------------------------------------------------------------------
# destabilizing terminations
# ---------------------------------------------------------------------------------------------


@dataclass(frozen=True)
class InstabilityCertificate:
    """Passive terminations ``T_k(s) = P_k + Q_k s + R_k/s`` (``P, Q, R`` symmetric PSD, so each
    ``T_k`` is positive real: an RLC network) under which ``det(Z + T)`` has a zero in
    ``Re s > 0`` -- a growing natural mode of the coupled system. ``roots`` are certified
    (ball arithmetic on the exact numerator); ``terminations`` are exact SymPy matrices."""

    terminations: tuple[sp.Matrix, ...]
    roots: tuple[complex, ...]
    numerator_degree: int
    frequency: float
    terminations_positive_real: bool

    def to_json(self) -> dict[str, Any]:
        from hapticproof.evidence import to_jsonable

        return {"terminations": [to_jsonable(T) for T in self.terminations],
                "rhp_roots": [f"{r.real:.6g}{r.imag:+.6g}j" for r in self.roots],
                "numerator_degree": self.numerator_degree, "search_frequency": self.frequency,
                "terminations_positive_real": self.terminations_positive_real}


def _rational(value: float, limit: int) -> sp.Rational:
    f = Fraction(value).limit_denominator(limit)
    return sp.Rational(f.numerator, f.denominator)


def _psd_factor(M: np.ndarray, limit: int) -> sp.Matrix:
    """A rational PSD matrix close to the PSD part of the symmetric ``M``: ``F F^T`` with
    ``F`` the rounded ``V sqrt(max(Lambda, 0))`` (exactly PSD by construction)."""
    w, V = np.linalg.eigh((M + M.T) / 2)
    cols = [V[:, k] * math.sqrt(w[k]) for k in range(len(w)) if w[k] > 1e-12 * max(1.0, abs(w).max())]
    m = M.shape[0]
    if not cols:
        return sp.zeros(m, m)
    F = sp.Matrix([[_rational(float(c[i]), limit) for c in cols] for i in range(m)])
    return F * F.T


def _block_termination(v: np.ndarray, w: np.ndarray, s0: complex, rng) -> tuple[np.ndarray, np.ndarray, np.ndarray] | None:
    """Float PSD ``(P, Q, R)`` of an RLC impedance ``P + Q s + R/s`` with ``T(s0) v = w``, or None."""
    m = len(v)
    sigma, omega = s0.real, s0.imag
    # unknowns: symmetric Ptot and S, with (Ptot + j S) v = w
    idx = [(i, j) for i in range(m) for j in range(i, m)]
    nvar = 2 * len(idx)
    rows, rhs = [], []
    for comp in range(2):  # real, imaginary part of row equations
        for i in range(m):
            row = np.zeros(nvar)
            for k, (a, b) in enumerate(idx):
                for (x, y) in ((a, b), (b, a)) if a != b else ((a, b),):
                    if x != i:
                        continue
                    vy = v[y]
                    # (Ptot v)_i = sum_y P_iy v_y ; (S v)_i likewise ; (Ptot + jS) v
                    if comp == 0:
                        row[k] += vy.real
                        row[len(idx) + k] += -vy.imag
                    else:
                        row[k] += vy.imag
                        row[len(idx) + k] += vy.real
            rows.append(row)
            rhs.append(w[i].real if comp == 0 else w[i].imag)
    A, b = np.array(rows), np.array(rhs)
    x0, *_ = np.linalg.lstsq(A, b, rcond=None)
    if np.linalg.norm(A @ x0 - b) > 1e-9 * (1 + np.linalg.norm(b)):
        return None
    null = np.linalg.svd(A)[2][np.linalg.matrix_rank(A):].T if A.shape[1] > np.linalg.matrix_rank(A) else np.zeros((nvar, 0))

    def unpack(x):
        P = np.zeros((m, m))
        S = np.zeros((m, m))
        for k, (a, b_) in enumerate(idx):
            P[a, b_] = P[b_, a] = x[k]
            S[a, b_] = S[b_, a] = x[len(idx) + k]
        return P, S

    def margin(y):
        P, S = unpack(x0 + null @ y)
        ws, Vs = np.linalg.eigh(S)
        absS = (Vs * np.abs(ws)) @ Vs.T
        return np.linalg.eigvalsh(P - (sigma / omega) * absS).min()

    best_y = np.zeros(null.shape[1])
    best = margin(best_y)
    if null.shape[1] and best <= 0:
        import scipy.optimize as so

        size = np.linalg.norm(x0) + 1
        for attempt in range(3):
            start = best_y if attempt == 0 else rng.normal(size=null.shape[1]) * size * 0.3
            res = so.minimize(lambda y: -margin(y), start, method="Nelder-Mead",
                              options={"maxiter": 150 * null.shape[1], "xatol": 1e-9, "fatol": 1e-12})
            if -res.fun > best:
                best, best_y = -res.fun, res.x
            if best > 0:
                break
    if margin(best_y) <= 0:
        return None
    P, S = unpack(x0 + null @ best_y)
    ws, Vs = np.linalg.eigh(S)
    Splus = (Vs * np.maximum(ws, 0)) @ Vs.T
    Sminus = (Vs * np.maximum(-ws, 0)) @ Vs.T
    mod2 = sigma**2 + omega**2
    Q = Splus / omega
    R = mod2 * Sminus / omega
    return P - sigma * (Q + R / mod2), Q, R


def _round_psd(M: np.ndarray, limit: int) -> sp.Matrix:
    """Entrywise rational rounding when it stays PSD (exact check), else a rational factorization."""
    m = M.shape[0]
    rounded = sp.Matrix(m, m, lambda i, j: _rational(float(M[i, j]), limit) if i <= j else 0)
    rounded = sp.Matrix(m, m, lambda i, j: rounded[min(i, j), max(i, j)])
    if _psd_constant(rounded)[0]:
        return rounded
    return _psd_factor(M, limit)


def _block_forms(M: np.ndarray, blocks) -> list[np.ndarray]:
    """Hermitian ``H_k`` with ``v^H H_k v = Re(v_k^H (M v)_k)`` (power into port ``k``)."""
    n = M.shape[0]
    forms = []
    for blk in blocks:
        E = np.zeros((n, n))
        for i in blk:
            E[i, i] = 1.0
        A = E @ M
        forms.append((A + A.conj().T) / 2)
    return forms


def _dual_bound(forms: list[np.ndarray]) -> tuple[float, np.ndarray]:
    """``max over the simplex of lambda_min(sum lambda_k H_k)`` (concave) and the eigenvector there.

    For two ports the joint numerical range is convex, so a negative maximum is equivalent to a
    ``v`` that pushes power out of both ports; a non-negative one proves there is none.
    """
    import scipy.optimize as so

    K = len(forms)

    def weights(theta):
        e = np.exp(np.concatenate([[0.0], theta]) - np.max(np.concatenate([[0.0], theta])))
        return e / e.sum()

    def g(theta):
        H = sum(w * F for w, F in zip(weights(theta), forms))
        return np.linalg.eigvalsh(H)[0]

    best_theta, best = np.zeros(K - 1), g(np.zeros(K - 1))
    if K > 1:
        if K == 2:
            res = so.minimize_scalar(lambda t: -g(np.array([t])), bounds=(-30, 30), method="bounded",
                                     options={"xatol": 1e-10})
            if -res.fun > best:
                best, best_theta = -res.fun, np.array([res.x])
        else:
            res = so.minimize(lambda th: -g(th), np.zeros(K - 1), method="Nelder-Mead", options={"maxiter": 200 * K})
            if -res.fun > best:
                best, best_theta = -res.fun, res.x
    H = sum(w * F for w, F in zip(weights(best_theta), forms))
    return float(best), np.linalg.eigh(H)[1][:, 0]


def _search_vectors(M: np.ndarray, blocks, eps: float, rng, restarts: int) -> tuple[float, np.ndarray | None]:
    """Minimise ``max_k [Re(v_k^H (M v)_k) + eps |Im(v_k^H (M v)_k)|] / |v|^2`` over complex ``v``."""
    import scipy.optimize as so

    n = M.shape[0]
    forms = _block_forms(M, blocks)
    bound, v0 = _dual_bound(forms)
    scale = max(1e-300, float(np.abs(M).max()))
    if len(blocks) == 2 and bound >= 0:
        return bound / scale, None

    def objective(p):
        v = p[:n] + 1j * p[n:]
        norm = np.vdot(v, v).real
        if norm == 0:
            return 1e9
        w = M @ v
        worst = -math.inf
        for blk in blocks:
            pw = np.vdot(v[list(blk)], w[list(blk)]) / norm
            worst = max(worst, pw.real + eps * abs(pw.imag))
        return worst / scale

    starts = [np.concatenate([v0.real, v0.imag])]
    starts += [rng.normal(size=2 * n) for _ in range(restarts if len(blocks) > 2 else 1)]
    best_val, best_p = math.inf, starts[0]
    for start in starts:
        res = so.minimize(objective, start, method="Nelder-Mead",
                          options={"maxiter": 300 * n, "xatol": 1e-10, "fatol": 1e-14, "adaptive": True})
        if res.fun < best_val:
            best_val, best_p = res.fun, res.x
        if best_val < -1e-4:
            break
    v = best_p[:n] + 1j * best_p[n:]
    return best_val, v / np.linalg.norm(v)


def verify_certificate(Z: RationalMatrix, terminations: Sequence[sp.Matrix], blocks) -> tuple[list[complex], int]:
    """Exact: the open-RHP zeros of ``det(Z + diag(T_k))`` (certified) and the numerator degree."""
    n = Z.shape[0]
    full = sp.zeros(n, n)
    for blk, T in zip(blocks, terminations):
        for a, i in enumerate(blk):
            for b, j in enumerate(blk):
                full[i, j] = T[a, b]
    total = Z + RationalMatrix.from_sympy(full)
    det = total.determinant()
    roots = rhp_roots(det.num)
    return [complex(float(r.real.mid()), float(r.imag.mid())) for r, _ in roots], det.num.degree()


def find_destabilizing_terminations(
    Z: Any,
    ports: Sequence[int] | None = None,
    frequencies: Iterable[float] | None = None,
    seed: int = 0,
    restarts: int = 4,
    limit: int = 1000,
    max_subsets: int = 8,
) -> InstabilityCertificate | None:
    """Search passive terminations making the coupled network unstable; verify exactly.

    For trial points ``s0 = sigma + j w`` near the axis, look for port velocities ``v`` such that
    every port can absorb the power ``-Re(v_k^H (Z(s0) v)_k) > 0`` through an RLC termination
    ``T_k`` with ``T_k(s0) v_k = -(Z(s0) v)_k`` (then ``det(Z + T)(s0) = 0``); build ``T_k`` with
    rational PSD ``P, Q, R`` and certify a zero of ``det(Z + T)`` in ``Re s > 0`` exactly.
    Ports outside a searched subset are clamped by large resistors. Returns None when nothing is
    found (which proves nothing).
    """
    Zr = as_rational_matrix(Z)
    n = Zr.shape[0]
    blocks = port_blocks(n, ports)
    rng = np.random.default_rng(seed)
    if frequencies is None:
        frequencies = np.logspace(-2, 2, 17)
    # Ports outside a subset are clamped by large resistors (their velocities ~ 0), so a
    # destabilizing mode living on some of the ports only is found too.
    subsets = [tuple(range(len(blocks)))]
    for size in range(len(blocks) - 1, 0, -1):
        subsets += list(itertools.combinations(range(len(blocks)), size))
    subsets = subsets[:max_subsets]
    # most promising first: the most negative dual bound of the port powers near the axis
    scored = []
    for omega in frequencies:
        M = Zr.numpy_at(complex(0.05 * omega, omega))
        if not np.all(np.isfinite(M)):
            continue
        for rank, subset in enumerate(subsets):
            idx = [i for k in subset for i in blocks[k]]
            sub_blocks = _renumber([blocks[k] for k in subset])
            bound, _ = _dual_bound(_block_forms(M[np.ix_(idx, idx)], sub_blocks))
            scored.append((bound / max(1e-300, float(np.abs(M).max())), rank, float(omega), subset))
    for bound, _, omega, subset in sorted(scored):
        if len(subset) == 2 and bound >= 0:
            continue
        idx = [i for k in subset for i in blocks[k]]
        sub_blocks = _renumber([blocks[k] for k in subset])
        for frac in (0.2, 0.05, 0.01):
            s0 = complex(frac * omega, omega)
            M = Zr.numpy_at(s0)
            if not np.all(np.isfinite(M)):
                continue
            Msub = M[np.ix_(idx, idx)]
            value, v = _search_vectors(Msub, sub_blocks, frac, rng, restarts)
            if v is None or value >= -1e-9:
                continue
            w = -(Msub @ v)
            parts = []
            for blk in sub_blocks:
                part = _block_termination(v[list(blk)], w[list(blk)], s0, rng)
                if part is None:
                    break
                parts.append(part)
            if len(parts) != len(sub_blocks):
                continue
            clamp = sp.Integer(10) ** (int(math.log10(max(1.0, float(np.abs(M).max())))) + 4)
            for lim in (10, 100, limit, 100 * limit):
                s = S_SYM
                made = iter(_round_psd(P, lim) + _round_psd(Q, lim) * s + _round_psd(R, lim) / s for P, Q, R in parts)
                terms = [next(made) if k in subset else clamp * sp.eye(len(blocks[k])) for k in range(len(blocks))]
                roots, degree = verify_certificate(Zr, terms, blocks)
                if roots:
                    pr_ok = all(positive_real(T).decision == Decision.PROVED for T in terms)
                    return InstabilityCertificate(tuple(terms), tuple(roots), degree, float(omega), pr_ok)
    return None


def _renumber(blocks: Sequence[Sequence[int]]) -> tuple[tuple[int, ...], ...]:
    out, start = [], 0
    for blk in blocks:
        out.append(tuple(range(start, start + len(blk))))
        start += len(blk)
    return tuple(out)


# ---------------------------------------------------------------------------------------------
# absolute stability
# ---------------------------------------------------------------------------------------------


@dataclass(frozen=True)
class StabilityVerdict:
    """Absolute stability of an n-port: ``decision`` proved (absolutely stable), disproved
    (potentially unstable) or undecided; ``method`` says how."""

    decision: Decision
    method: str
    reason: str
    evidence: Evidence
    symmetrization: Symmetrization | None = None
    positive_real: PositiveRealResult | None = None
    llewellyn: LlewellynResult | None = None
    certificate: InstabilityCertificate | None = None

    def to_json(self) -> dict[str, Any]:
        out = {"decision": self.decision.value, "method": self.method, "reason": self.reason,
               "evidence": self.evidence.to_json()}
        if self.certificate is not None:
            out["certificate"] = self.certificate.to_json()
        return out


def absolute_stability(Z: Any, ports: Sequence[int] | None = None, search: bool = True, seed: int = 0) -> StabilityVerdict:
    """Absolute stability of an n-port with impedance matrix ``Z`` (exact where possible).

    * scalar 2-ports: Llewellyn's criterion (:func:`llewellyn`);
    * symmetrizable networks (Youla): absolutely stable iff ``Z'`` is positive real
      (Youla 1959, Lemma 7; identical minors, Lemma 8);
    * otherwise: a verified destabilizing termination (:func:`find_destabilizing_terminations`)
      or ``undecided``.

    >>> from hapticproof.symbols import s
    >>> absolute_stability(sp.Matrix([[1/(s + 1), 0], [0, 1]])).decision.value
    'proved'
    """
    Zr = as_rational_matrix(Z)
    n = Zr.shape[0]
    blocks = port_blocks(n, ports)
    report = pole_report(Zr)
    if report.rhp:
        cert = find_destabilizing_terminations(Zr, ports, seed=seed) if search else None
        return StabilityVerdict(Decision.DISPROVED, "open-circuit instability",
                                "an entry of Z has a pole in Re s > 0: the network is unstable with open ports",
                                Evidence(Method.ROOT_ISOLATION, witness={"entry": list(report.rhp[0][0]), "pole": str(report.rhp[0][1])}),
                                certificate=cert)
    if n == 2 and len(blocks) == 2:
        result = llewellyn(Zr)
        cert = None
        if result.decision == Decision.DISPROVED and search:
            cert = find_destabilizing_terminations(Zr, ports, seed=seed)
        return StabilityVerdict(result.decision, "Llewellyn", result.reason, result.evidence, llewellyn=result, certificate=cert)
    sym = symmetrize(Zr, ports)
    if sym.symmetrizable == Decision.PROVED:
        pr = _youla_positive_real(sym)
        cert = None
        if pr.decision == Decision.DISPROVED and search:
            cert = find_destabilizing_terminations(Zr, ports, seed=seed)
        reason = ("Z' is positive real: absolutely stable (Youla)" if pr.decision == Decision.PROVED
                  else f"Z' is not positive real ({pr.reason}): potentially unstable (Youla)" if pr.decision == Decision.DISPROVED
                  else f"positive realness of Z' undecided: {pr.reason}")
        return StabilityVerdict(pr.decision, "Youla symmetrization", reason, pr.evidence, symmetrization=sym,
                                positive_real=pr, certificate=cert)
    cert = find_destabilizing_terminations(Zr, ports, seed=seed) if search else None
    if cert is not None:
        return StabilityVerdict(Decision.DISPROVED, "destabilizing terminations",
                                f"not symmetrizable ({sym.reason}); passive terminations put a zero of det(Z + T) at "
                                f"s ~ {cert.roots[0]:.6g} in Re s > 0",
                                Evidence(Method.COUNTEREXAMPLE, facts=cert.to_json()), symmetrization=sym, certificate=cert)
    return StabilityVerdict(Decision.UNDECIDED, "none",
                            f"not symmetrizable ({sym.reason}) and no destabilizing termination found",
                            Evidence(Method.INSTANCES, facts={"symmetrization": sym.reason}), symmetrization=sym)
