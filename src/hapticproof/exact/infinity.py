r"""The decision kernel at infinity: properness of real-rational functions and matrices.

Positive realness is analyticity plus a sign on a whole region, and infinity belongs to it:

* **discrete** (HVE paper, Definition 2; Hitz & Anderson): ``G(z)`` is positive real when it is
  analytic in ``|z| > 1`` *including* ``z = oo`` and ``Re G >= 0`` there. An improper ``G``
  (``deg num > deg den``: a non-causal model, e.g. a forward difference ``(z - 1)/T`` behind a
  backward or Tustin integrator) has a pole at infinity, ``G ~ a z^k`` (``k >= 1``), which takes
  every argument on a large circle: ``Re G < 0`` somewhere outside the disk. No pole at infinity
  is allowed, whatever the unit circle says.
* **continuous** (Khalil, Definition 6.4): ``Z(s)`` analytic in ``Re s > 0`` with
  ``Re Z >= 0`` there; at ``s = oo`` a *simple* pole whose residue (the coefficient of ``s``)
  is Hermitian positive semidefinite is allowed (a mass ``M s``), nothing else: ``Z ~ A s^k``
  with ``k >= 2``, or ``k = 1`` with a residue that is not PSD, gives ``Re(v^H Z(s) v) < 0`` at
  large ``s`` in the open right half-plane.

The decision is the degree count (exact); a disproof carries an exact witness: a
Gaussian-rational point ``w`` (``|w| > 1``, or ``Re w > 0``) and a vector ``v`` with
``Re(v^H F(w) v) < 0``, evaluated in exact arithmetic. The point lies on a ray where
``Re(q u^k) < 0`` (``q = v^H A v``, ``A`` the leading coefficients) at the first power of ten
that makes the leading term dominate. The certificate (:class:`InfinityCertificate`) keeps the
original transfer function so that the checker (:mod:`hapticproof.exact.checker`) recounts the
degrees and re-evaluates ``F`` at the witness itself.

>>> import flint
>>> z = flint.fmpq_poly([0, 1])
>>> out = decide_infinity((1000 * (z - 1) + z * z, 1000 * (z - 1)))     # 1 + z^2/(1000(z - 1))
>>> out.decision.value, out.witness["z"], out.evidence.facts["value"]
('disproved', ['-10000', '0'], -89999/10001)
>>> decide_infinity((z + 1, z - 1)).decision.value                        # proper
'proved'
>>> s = z
>>> decide_infinity((3 * s * s + 1, s + 2), "halfplane").reason          # 3 s^2/(s + 2) ~ 3 s
'pole at s = oo of order 1 with residue 3 >= 0: allowed (simple, positive)'
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from fractions import Fraction
from typing import Any

import flint
import sympy as sp

from hapticproof.core.evidence import Decision, Evidence, Method, Outcome
from hapticproof.exact.kernel import decide_constant_psd, poly_json, q_str

__all__ = ["InfinityCertificate", "decide_infinity", "excess", "leading_matrix"]

Entry = tuple[flint.fmpq_poly, flint.fmpq_poly]
Gaussian = tuple[Fraction, Fraction]


def _fraction(value: Any) -> Fraction:
    if isinstance(value, Fraction):
        return value
    if isinstance(value, flint.fmpq):
        return Fraction(int(value.p), int(value.q))
    return Fraction(value)


def excess(num: flint.fmpq_poly, den: flint.fmpq_poly) -> int | None:
    """``deg num - deg den`` (the order of the pole at infinity when positive); ``None`` for
    ``num = 0``. Common factors cancel from both degrees, so the excess needs no gcd.

    >>> excess(flint.fmpq_poly([0, 0, 1]), flint.fmpq_poly([-1, 1]))
    1
    """
    if num.is_zero():
        return None
    if den.is_zero():
        raise ZeroDivisionError("zero denominator")
    return num.degree() - den.degree()


def leading_matrix(entries: list[list[Entry]], order: int) -> list[list[Fraction]]:
    """The coefficient of ``w^order`` in the expansion at infinity: ``lc(num)/lc(den)`` for the
    entries of that excess, ``0`` for the others (the residue matrix at ``s = oo`` when
    ``order = 1``).

    >>> z = flint.fmpq_poly([0, 1])
    >>> leading_matrix([[(2 * z, z + 1), (z, z * z)]], 0)
    [[Fraction(2, 1), Fraction(0, 1)]]
    """
    out = []
    for row in entries:
        line = []
        for num, den in row:
            k = excess(num, den)
            line.append(_fraction(num.coeffs()[-1] / den.coeffs()[-1]) if k == order else Fraction(0))
        out.append(line)
    return out


@dataclass(frozen=True, eq=False)
class InfinityCertificate:
    """Evidence about ``F`` at infinity: its ``order`` (largest degree excess over the entries;
    ``<= 0``: analytic there) and, for a disproof, the witness point ``witness`` (Gaussian
    rational, in the domain), the vector ``vector`` (Gaussian rationals) and the exact value
    ``value = Re(v^H F(w) v) < 0``. ``entries`` is the original transfer function (square, a
    ``1 x 1`` matrix for a scalar)."""

    domain: str
    entries: tuple[tuple[Entry, ...], ...]
    order: int
    holds: bool
    leading: tuple[tuple[Fraction, ...], ...] = ()
    witness: Gaussian | None = None
    vector: tuple[Gaussian, ...] | None = None
    value: Fraction | None = None

    @property
    def variable(self) -> str:
        return "z" if self.domain == "disk" else "s"

    def to_json(self) -> dict[str, Any]:
        cells = [[{"num": poly_json(n), "den": poly_json(d)} for n, d in row] for row in self.entries]
        if len(cells) == 1 and len(cells[0]) == 1:
            transfer: dict[str, Any] = {"variable": self.variable, **cells[0][0]}
        else:
            transfer = {"variable": self.variable, "entries": cells}
        out: dict[str, Any] = {
            "certificate": "infinity",
            "claim": ("no pole at z = oo (proper)" if self.domain == "disk"
                      else "at s = oo at most a simple pole with a Hermitian PSD residue"),
            "domain": self.domain,
            "variable": self.variable,
            "transfer": transfer,
            "order": self.order,
            "holds": self.holds,
        }
        if self.leading:
            out["leading"] = [[q_str(flint.fmpq(v.numerator, v.denominator)) for v in row] for row in self.leading]
        if self.witness is not None:
            out["witness"] = [_q(v) for v in self.witness]
            out["vector"] = [[_q(a), _q(b)] for a, b in self.vector]
            out["re_value"] = _q(self.value)
        return out


def _q(value: Fraction) -> str:
    return str(value.numerator) if value.denominator == 1 else f"{value.numerator}/{value.denominator}"


# ---------------------------------------------------------------------------------------------
# exact evaluation over the Gaussian rationals
# ---------------------------------------------------------------------------------------------


def _mul(a: Gaussian, b: Gaussian) -> Gaussian:
    return (a[0] * b[0] - a[1] * b[1], a[0] * b[1] + a[1] * b[0])


def _horner(p: flint.fmpq_poly, w: Gaussian) -> Gaussian:
    acc = (Fraction(0), Fraction(0))
    for c in reversed(p.coeffs()):
        acc = _mul(acc, w)
        acc = (acc[0] + _fraction(c), acc[1])
    return acc


def _div(a: Gaussian, b: Gaussian) -> Gaussian | None:
    norm = b[0] * b[0] + b[1] * b[1]
    if norm == 0:
        return None
    return ((a[0] * b[0] + a[1] * b[1]) / norm, (a[1] * b[0] - a[0] * b[1]) / norm)


def _quadratic_form(entries: list[list[Entry]], w: Gaussian, v: tuple[Gaussian, ...]) -> Fraction | None:
    """``Re(v^H F(w) v)`` exactly (``None`` at a pole of an entry)."""
    total = (Fraction(0), Fraction(0))
    for i, row in enumerate(entries):
        for j, (num, den) in enumerate(row):
            if num.is_zero() or (v[i] == (0, 0)) or (v[j] == (0, 0)):
                continue
            value = _div(_horner(num, w), _horner(den, w))
            if value is None:
                return None
            conj_vi = (v[i][0], -v[i][1])
            term = _mul(_mul(conj_vi, value), v[j])
            total = (total[0] + term[0], total[1] + term[1])
    return total[0]


# ---------------------------------------------------------------------------------------------
# the witness: a ray where the leading term is negative, then a large enough radius
# ---------------------------------------------------------------------------------------------


def _candidate_vectors(A: list[list[Fraction]]) -> list[tuple[Gaussian, ...]]:
    """Vectors ``v`` with ``v^H A v != 0`` when ``A != 0``: unit vectors, ``e_i +- e_j``,
    ``e_i +- j e_j`` (an antisymmetric part) and a rationalised eigenvector of the symmetric
    part's least eigenvalue (a negative direction that is no coordinate combination)."""
    m = len(A)
    zero, one = (Fraction(0), Fraction(0)), (Fraction(1), Fraction(0))

    def unit(pairs: dict[int, Gaussian]) -> tuple[Gaussian, ...]:
        return tuple(pairs.get(k, zero) for k in range(m))

    out = [unit({i: one}) for i in range(m)]
    for i in range(m):
        for j in range(i + 1, m):
            for second in (one, (Fraction(-1), Fraction(0)), (Fraction(0), Fraction(1)), (Fraction(0), Fraction(-1))):
                out.append(unit({i: one, j: second}))
    if m > 1:
        import numpy as np

        sym = np.array([[float(A[i][j] + A[j][i]) / 2 for j in range(m)] for i in range(m)])
        if np.all(np.isfinite(sym)):
            _, vectors = np.linalg.eigh(sym)
            vec = vectors[:, 0] / max(abs(vectors[:, 0]).max(), 1e-300)
            out.append(tuple((Fraction(float(x)).limit_denominator(1000), Fraction(0)) for x in vec))
    return out


def _form(A: list[list[Fraction]], v: tuple[Gaussian, ...]) -> Gaussian:
    total = (Fraction(0), Fraction(0))
    for i, row in enumerate(A):
        for j, a in enumerate(row):
            if a == 0:
                continue
            term = _mul(_mul((v[i][0], -v[i][1]), (a, Fraction(0))), v[j])
            total = (total[0] + term[0], total[1] + term[1])
    return total


def _power(u: Gaussian, k: int) -> Gaussian:
    out = (Fraction(1), Fraction(0))
    for _ in range(k):
        out = _mul(out, u)
    return out


def _directions(q: Gaussian, k: int, domain: str) -> list[Gaussian]:
    """Short rational directions ``u`` with ``Re(q u^k) < 0`` (and ``Re u > 0`` on the
    half-plane), exact-checked: the simple ones first, then rationalised optimal angles."""
    simple = [(Fraction(-1), Fraction(0)), (Fraction(1), Fraction(0)), (Fraction(0), Fraction(1)),
              (Fraction(0), Fraction(-1)), (Fraction(1), Fraction(1)), (Fraction(1), Fraction(-1)),
              (Fraction(1), Fraction(2)), (Fraction(1), Fraction(-2))]
    arg_q = math.atan2(float(q[1]), float(q[0]))
    angles = []
    for m in range(-k - 1, k + 2):
        phi = (math.pi - arg_q + 2 * math.pi * m) / k
        angles.append(phi)
        # on the half-plane also the middle of the allowed part of the negative sector
        lo, hi = max(phi - math.pi / (2 * k), -math.pi / 2), min(phi + math.pi / (2 * k), math.pi / 2)
        if lo < hi:
            angles.append((lo + hi) / 2)
    rational = [(Fraction(math.cos(phi)).limit_denominator(den), Fraction(math.sin(phi)).limit_denominator(den))
                for den in (4, 16, 256, 10**6) for phi in angles]
    out = []
    for u in simple + rational:
        if u == (0, 0) or u in out:
            continue
        if domain == "halfplane" and not u[0] > 0:
            continue
        if _mul(q, _power(u, k))[0] < 0:
            out.append(u)
    return out


def _radius_decades(entries: list[list[Entry]]) -> int:
    """How far out the leading term is sure to dominate, in decades (generous: the sizes of
    all coefficients and degrees)."""
    digits = 0
    degree = 0
    for row in entries:
        for num, den in row:
            for p in (num, den):
                degree = max(degree, p.degree())
                for c in p.coeffs():
                    if c != 0:
                        digits = max(digits, len(str(abs(c.p))) + len(str(c.q)))
    return 2 * digits + 4 * degree + 24


def _witness(entries: list[list[Entry]], order: int, A: list[list[Fraction]], domain: str,
             vectors: list[tuple[Gaussian, ...]] | None = None) -> tuple[Gaussian, tuple[Gaussian, ...], Fraction] | None:
    top = _radius_decades(entries)
    for v in vectors or _candidate_vectors(A):
        q = _form(A, v)
        if q == (0, 0):
            continue
        for u in _directions(q, order, domain)[:3]:
            for m in range(1, top + 1):
                R = Fraction(10) ** m
                w = (u[0] * R, u[1] * R)
                value = _quadratic_form(entries, w, v)
                if value is not None and value < 0:
                    return w, v, value
    return None


# ---------------------------------------------------------------------------------------------
# the decision
# ---------------------------------------------------------------------------------------------


def _as_entries(F: Any) -> list[list[Entry]]:
    if isinstance(F, tuple) and len(F) == 2 and all(isinstance(p, flint.fmpq_poly) for p in F):
        return [[F]]
    rows = [list(row) for row in F]
    if not rows or any(len(row) != len(rows) for row in rows):
        raise ValueError("decide_infinity needs (num, den) or a square matrix of (num, den) pairs")
    return [[(flint.fmpq_poly(n), flint.fmpq_poly(d)) for n, d in row] for row in rows]


def _text(value: Fraction) -> str:
    text = _q(value)
    if len(text) <= 24:
        return text
    exponent = len(str(abs(value.numerator))) - len(str(value.denominator))
    if abs(exponent) <= 4:
        return f"{float(value):.6g}"
    mantissa = float(value / Fraction(10) ** exponent)
    while abs(mantissa) >= 10:
        mantissa, exponent = mantissa / 10, exponent + 1
    while 0 < abs(mantissa) < 1:
        mantissa, exponent = mantissa * 10, exponent - 1
    return f"{mantissa:.6g}e{exponent:+d}"


def _point_text(w: Gaussian) -> str:
    re, im = w
    if im == 0:
        return _text(re)
    if re == 0:
        return f"{_text(im)} j"
    return f"{_text(re)} {'+' if im > 0 else '-'} {_text(abs(im))} j"


def decide_infinity(F: Any, domain: str = "disk", what: str | None = None) -> Outcome:
    """Decide the condition at infinity of positive realness for ``F``: ``(num, den)`` (flint
    polynomials in ``z`` or ``s``) or a square matrix of such pairs.

    ``domain='disk'`` (discrete): no pole at ``z = oo``, i.e. every entry proper.
    ``domain='halfplane'`` (continuous): no pole at ``s = oo``, or a simple one (largest excess
    1) whose residue matrix (the coefficients of ``s``) is Hermitian PSD. A disproof's witness
    ``{'pole': 'infinity', 'order': k, 'z' (or 's'): [re, im], 'vector': ...}`` is an exact point
    of the domain where ``Re(v^H F v) < 0`` (``facts['value']``).

    >>> s = flint.fmpq_poly([0, 1])
    >>> out = decide_infinity((-s * s, s + 1), "halfplane")                   # -s^2/(s + 1) ~ -s
    >>> out.decision.value, out.witness["s"]
    ('disproved', ['10', '0'])
    """
    if domain not in ("disk", "halfplane"):
        raise ValueError("domain must be 'disk' or 'halfplane'")
    entries = _as_entries(F)
    var = "z" if domain == "disk" else "s"
    what = what or ("G" if domain == "disk" else "Z")
    orders = [k for row in entries for n, d in row if (k := excess(n, d)) is not None]
    order = max(orders, default=-1)
    frozen = tuple(tuple(row) for row in entries)
    if order <= 0:
        cert = InfinityCertificate(domain, frozen, order, True)
        return Outcome(Decision.PROVED, Evidence(Method.CANONICAL_FORM, facts={"certificate": cert, "order": order}),
                       f"proper: no pole at {var} = oo (deg num <= deg den)")
    A = leading_matrix(entries, order)
    scalar = len(entries) == 1
    leading = tuple(tuple(row) for row in A)
    psd_outcome = None
    if domain == "halfplane" and order == 1:
        symmetric = all(A[i][j] == A[j][i] for i in range(len(A)) for j in range(len(A)))
        if symmetric:
            psd_outcome = decide_constant_psd(sp.Matrix([[sp.Rational(v.numerator, v.denominator) for v in row] for row in A]),
                                              f"the residue at {var} = oo")
            if psd_outcome.decision == Decision.PROVED:
                cert = InfinityCertificate(domain, frozen, order, True, leading)
                residue = _text(A[0][0]) if scalar else "matrix"
                text = (f"pole at s = oo of order 1 with residue {residue} >= 0: allowed (simple, positive)" if scalar
                        else "pole at s = oo of order 1 with a Hermitian PSD residue matrix: allowed")
                return Outcome(Decision.PROVED, Evidence(Method.CANONICAL_FORM,
                                                         facts={"certificate": cert, "order": order,
                                                                "residue": psd_outcome.evidence.facts.get("certificate")}),
                               text)
    found = _witness(entries, order, A, domain)
    cert = InfinityCertificate(domain, frozen, order, False, leading, *(found if found else (None, None, None)))
    facts: dict[str, Any] = {"certificate": cert, "order": order}
    if psd_outcome is not None:
        facts["residue"] = psd_outcome.evidence.facts.get("certificate")
    if domain == "disk":
        power = var if order == 1 else f"{var}^{order}"
        a = A[0][0]
        coefficient = "" if a == 1 else "-" if a == -1 else f"({_text(a)}) "
        lead = f"{what} ~ {coefficient}{power}" if scalar else f"entries grow like {power}"
        head = f"improper: pole at infinity (order {order}): {lead}"
    elif order > 1:
        head = f"pole at s = oo of order {order} > 1 (only a simple one is allowed)"
    else:
        head = (f"pole at s = oo with residue {_text(A[0][0])} < 0" if scalar
                else "pole at s = oo whose residue matrix is not Hermitian PSD")
    if found is None:
        return Outcome(Decision.DISPROVED, Evidence(Method.CANONICAL_FORM, witness={"pole": "infinity", "order": order},
                                                    facts=facts),
                       f"{head} (the degree count is exact; no witness point was found below 10^{_radius_decades(entries)})")
    w, v, value = found
    facts["value"] = sp.Rational(value.numerator, value.denominator)
    witness: dict[str, Any] = {"pole": "infinity", "order": order, var: [_q(w[0]), _q(w[1])]}
    if not scalar:
        witness["vector"] = [[_q(a), _q(b)] for a, b in v]
    where = f"Re {what}({_point_text(w)}) = {_text(value)} < 0" if scalar else \
        f"Re(v^H {what}(w) v) = {_text(value)} < 0 at w = {_point_text(w)}"
    return Outcome(Decision.DISPROVED, Evidence(Method.COUNTEREXAMPLE, witness=witness, facts=facts), f"{head}; {where}")
