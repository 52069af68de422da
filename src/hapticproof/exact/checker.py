r"""The independent checker: re-verify saved certificates with different algorithms.

The decision kernel (:mod:`hapticproof.exact.kernel`) isolates roots by Descartes' rule of signs
and places poles by complex root isolation. This module re-checks what a certificate claims
from its JSON alone, importing nothing of the kernel, with other methods:

* **sign** certificates -- distinct real roots between consecutive sample points are counted
  with **Sturm sequences** over exact rationals; the polynomial is evaluated exactly at every
  point; a disproof's witness is evaluated exactly;
* the link to the **original transfer function**: a disproof on the unit circle is re-checked
  by evaluating ``F(z0)`` at the Gaussian-rational witness ``z0`` (``Re F(z0) < 0``), on the axis
  at ``s0 = j w``; a proof's c-form is compared with ``Re F`` at rational points of the circle;
* **psd** certificates -- every coefficient's sign certificate; at a witness the exact matrix
  ``G(z0) + G(z0)^H`` from the transfer matrix and **all its principal minors**;
* **chebyshev-sign** certificates (long delays) -- converted to the monomial basis by the
  three-term recurrence and checked as sign certificates, up to the degree limit;
* **roots** certificates -- the bilinear map ``z = (1 + s)/(1 - s)`` and a **Routh-Hurwitz**
  array (after removing the imaginary-axis roots found as real roots of
  ``gcd(Re R(jw), Im R(jw))``), instead of complex root isolation;
* **infinity** certificates (properness) -- the pole order at ``z = oo`` / ``s = oo`` recounted
  from the raw degrees of the original transfer function (and, at ``s = oo``, the residue's
  characteristic coefficients); a disproof's point re-evaluated exactly, ``Re(v^H F(w) v) < 0``
  with ``|w| > 1`` or ``Re w > 0``;
* **determinant** certificates (destabilizing terminations of an n-port) -- ``det(Z + T)``
  against its claimed numerator/denominator by exact evaluation at more points than the degree
  of the identity, then the numerator's roots certificate (a zero in ``Re s > 0``).

``check_report`` walks a saved JSON report (audit or derive) and re-verifies every certificate
it contains, saying which entries carry none (not re-verifiable).

>>> cert = {"certificate": "sign", "variable": "c", "interval": ["-1", "1"], "polynomial": ["1", "-2", "1"],
...         "holds": True, "points": ["-1", "0", "1"], "roots": [["1", "1"]]}
>>> check_certificate(cert).ok
True
>>> check_certificate(dict(cert, polynomial=["-1", "0", "2"])).ok      # 2c^2 - 1 is negative at 0
False
"""

from __future__ import annotations

import itertools
import json
import math
from collections.abc import Iterator, Mapping
from dataclasses import dataclass, field
from fractions import Fraction
from typing import Any

import flint

from hapticproof.core.naming import witness_keys
from hapticproof.exact.checkarith import MAX_DEGREE, certificates, is_kind
from hapticproof.exact.checkarith import CheckFailed as _Fail
from hapticproof.exact.checkarith import CheckSkipped as _Skip
from hapticproof.exact.checkarith import Gaussian as _G
from hapticproof.exact.checkarith import Sturm as _Sturm
from hapticproof.exact.checkarith import as_fmpq as _fq
from hapticproof.exact.checkarith import axis_gcd as _axis_gcd
from hapticproof.exact.checkarith import bilinear as _bilinear
from hapticproof.exact.checkarith import budget as _budget
from hapticproof.exact.checkarith import charpoly_coefficients as _charpoly_coefficients
from hapticproof.exact.checkarith import (
    count_with_multiplicity as _count_with_multiplicity,
)
from hapticproof.exact.checkarith import determinant as _det
from hapticproof.exact.checkarith import eval_transfer as _eval_transfer
from hapticproof.exact.checkarith import exact_q as _q
from hapticproof.exact.checkarith import json_poly as _poly
from hapticproof.exact.checkarith import max_degree as _max_degree
from hapticproof.exact.checkarith import max_matrix as _max_matrix
from hapticproof.exact.checkarith import routh_hurwitz as _routh_hurwitz
from hapticproof.exact.checkarith import value_at as _val

__all__ = ["CheckResult", "certificates", "check_certificate", "check_certificates", "check_report", "ReportCheck",
           "judge_results", "MAX_DEGREE", "is_kind", "WHOLE"]



@dataclass
class CheckResult:
    """Outcome of re-verifying one certificate: ``ok`` (verified), ``verified`` False with
    ``ok`` True means it could not be re-verified (``reason`` says why, e.g. degree limit)."""

    ok: bool
    reason: str
    verified: bool = True
    notes: list[str] = field(default_factory=list)
    #: ``"certificate"``, ``"judge"`` (the definition, :mod:`hapticproof.exact.judge`) or
    #: ``"display"`` (what the report shows against what it carries)
    source: str = "certificate"


# ---------------------------------------------------------------------------------------------
# sign certificates
# ---------------------------------------------------------------------------------------------


def _check_sign(cert: dict) -> list[str]:
    notes: list[str] = []
    p = _poly(cert["polynomial"])
    lo = _q(cert["interval"][0])
    hi = None if cert["interval"][1] is None else _q(cert["interval"][1])
    if "numerator" in cert:
        num, den = _poly(cert["numerator"]), _poly(cert["denominator"])
        if num * den != p:
            raise _Fail("the polynomial is not numerator * denominator")
    if not cert["holds"]:
        w = _q(cert["witness"])
        if w < lo or (hi is not None and w > hi):
            raise _Fail(f"witness {w} outside the interval")
        if not _val(p, w) < 0:
            raise _Fail(f"the polynomial is not negative at the witness {w}")
        if "numerator" in cert and _val(_poly(cert["denominator"]), w) == 0:
            raise _Fail("the witness is a pole")
        notes.append(f"negative at {cert['variable']} = {w}")
        return notes
    if p.is_zero():
        notes.append("identically zero")
        return notes
    points = [_q(v) for v in cert["points"]]
    if points != sorted(set(points)) or not points:
        raise _Fail("sample points not strictly increasing")
    if points[0] != lo or (hi is not None and points[-1] != hi) or any(pt < lo or (hi is not None and pt > hi) for pt in points):
        raise _Fail("sample points do not span the interval")
    values = [_val(p, pt) for pt in points]
    if any(v < 0 for v in values):
        raise _Fail("negative at a sample point")
    sturm = _Sturm(p)
    for (a, va), (b, vb) in zip(zip(points, values), zip(points[1:], values[1:])):
        inside = sturm.count_open(a, b)
        if inside > 1:
            raise _Fail(f"{inside} roots between consecutive sample points {a} and {b}")
        if inside == 1 and not (va > 0 and vb > 0):
            raise _Fail(f"a root between {a} and {b} without positive values on both sides")
        if inside == 0 and not (va > 0 or vb > 0):
            raise _Fail(f"no positive sample around ({a}, {b})")
    if hi is None:
        if sturm.count_open(points[-1], None) != 0:
            raise _Fail("roots beyond the last sample point")
        if not (values[-1] > 0 or p.coeffs()[-1] > 0):
            raise _Fail("negative towards infinity")
    notes.append(f"{len(points)} sample points, Sturm counts checked")
    return notes


def _circle_points(count: int) -> Iterator[tuple[Fraction, _G]]:
    """Rational points ``z = (1 + jt)/(1 - jt)`` of the unit circle (distinct ``c``)."""
    for k in range(1, count + 1):
        t = Fraction(k, count + 1) * 3
        c = (1 - t * t) / (1 + t * t)
        yield c, _G(c, 2 * t / (1 + t * t))


def _check_transfer_sign(cert: dict, transfer: dict) -> list[str]:
    """The c-form (or x-form) ``num/den`` against ``Re F`` of the original transfer function."""
    notes = []
    variable = transfer.get("variable", "z")
    if not cert["holds"] and cert.get("witness_point") is not None:
        w = cert["witness_point"]
        if variable == "z":
            point = _G(_q(w[0]), _q(w[1]))
            if point.re * point.re + point.im * point.im != 1:
                raise _Fail("the witness z0 is not on the unit circle")
            if cert.get("variable") == "c" and "witness" in cert and _q(cert["witness"]) != point.re:
                raise _Fail(f"the witness c = {cert['witness']} is not Re z0 = {point.re}")
        else:
            point = _G(Fraction(0), _q(w))
            if cert.get("variable") == "x" and "witness" in cert and _q(cert["witness"]) != point.im * point.im:
                raise _Fail(f"the witness x = {cert['witness']} is not omega^2 = {point.im * point.im}")
        value = _eval_transfer(transfer, point)
        if not value.re < 0:
            raise _Fail(f"Re F = {value.re} is not negative at the witness")
        notes.append(f"Re F(witness) = {float(value.re):.6g} < 0 evaluated exactly from the transfer function")
        return notes
    if "numerator" not in cert:
        return notes
    num, den = _poly(cert["numerator"]), _poly(cert["denominator"])
    # both sides are rational in t (z = (1 + jt)/(1 - jt)) or in w; their cross-multiplied
    # difference has degree <= 2 deg(form) + 2 deg(F): that many + 1 points prove the identity
    needed = 2 * max(num.degree(), den.degree(), 0) + 2 * (max(len(transfer["num"]), len(transfer["den"])) - 1) + 1
    if needed > 4 * _max_degree() + 1:
        raise _Skip(f"the form's identity with Re F needs {needed} exact points, above the checker's limit")
    limit = 2 * needed + 8               # (poles of F among the points are skipped)
    checked = 0
    points = _circle_points(limit) if variable == "z" else _axis_points(limit)
    for c, z in points:
        if checked >= needed:
            break
        d = _val(den, c)
        try:
            value = _eval_transfer(transfer, z)
        except _Fail:
            continue
        if d == 0:
            continue
        if _val(num, c) / d != value.re:
            raise _Fail(f"the form in {cert['variable']} differs from Re F at {cert['variable']} = {c}")
        checked += 1
    if checked < needed:
        raise _Skip(f"the form in {cert['variable']} equals Re F at {checked} exact points only, fewer than its degree needs")
    notes.append(f"form = Re F at {checked} exact points (identity proved by degree)")
    return notes


def _axis_points(count: int) -> Iterator[tuple[Fraction, _G]]:
    for k in range(1, count + 1):
        w = Fraction(k, 3)
        yield w * w, _G(Fraction(0), w)


# ---------------------------------------------------------------------------------------------
# matrices
# ---------------------------------------------------------------------------------------------


def _hermitian_at(transfer: dict, point: _G) -> list[list[_G]]:
    entries = transfer["entries"]
    m = len(entries)
    G = [[_eval_transfer(entries[i][j], point) for j in range(m)] for i in range(m)]
    return [[G[i][j] + G[j][i].conj() for j in range(m)] for i in range(m)]


def _check_psd(cert: dict) -> list[str]:
    notes = []
    for sub in cert["coefficients"]:
        _check_sign(sub)
    if "scale" in cert:
        if not cert["scale"]["holds"]:
            raise _Fail("the scale is not certified non-negative")
        _check_sign(cert["scale"])
    if cert["holds"]:
        if not all(sub["holds"] for sub in cert["coefficients"]):
            raise _Fail("a coefficient certificate does not hold")
        if len(cert["coefficients"]) != cert["size"]:
            raise _Fail("not every characteristic coefficient is certified")
        notes.append(f"{cert['size']} characteristic coefficients certified >= 0")
        return notes
    transfer = cert.get("transfer")
    witness = cert.get("witness", {})
    if transfer is not None and ("z" in witness or "omega" in witness):
        point = _G(_q(witness["z"][0]), _q(witness["z"][1])) if "z" in witness else _G(Fraction(0), _q(witness["omega"]))
        M = _hermitian_at(transfer, point)
        source = "the transfer matrix"
    elif "matrix_at_witness" in cert:
        M = [[_G(_q(a), _q(b)) for a, b in row] for row in cert["matrix_at_witness"]]
        source = "the recorded matrix"
    else:
        notes.append("no matrix at the witness to re-check")
        return notes
    m = len(M)
    if any(M[i][j].re != M[j][i].re or M[i][j].im != -M[j][i].im for i in range(m) for j in range(m)):
        raise _Fail("the matrix at the witness is not Hermitian")
    smallest = None
    checked = 0
    for size in range(1, m + 1):
        if math.comb(m, size) > 4000:
            break
        for subset in itertools.combinations(range(m), size):
            value = _det([[M[i][j] for j in subset] for i in subset]).re
            checked += 1
            if value < 0 and smallest is None:
                smallest = (subset, value)
    if smallest is None:
        raise _Fail(f"no negative principal minor at the witness ({checked} checked)")
    notes.append(f"principal minor {[i + 1 for i in smallest[0]]} = {smallest[1]} < 0 at the witness, from {source}")
    return notes


# ---------------------------------------------------------------------------------------------
# roots: bilinear map, imaginary-axis part, Routh-Hurwitz
# ---------------------------------------------------------------------------------------------


def _check_roots(cert: dict) -> list[str]:
    p = _poly(cert["polynomial"])
    notes = []
    if p.degree() <= 0:
        if cert["outside"] != 0 or cert["boundary_count"] != 0:
            raise _Fail("a constant has no roots")
        return ["constant"]
    coeffs = p.coeffs()
    zeros = next(k for k, a in enumerate(coeffs) if a != 0)   # roots at z = 0 / s = 0
    if cert["domain"] == "disk":
        core = flint.fmpq_poly(coeffs[zeros:])
        boundary_infinity = 0
        R = _bilinear(core)
        boundary_infinity = core.degree() - R.degree()       # roots at z = -1
        axis_zero = 0
    else:
        R = flint.fmpq_poly(coeffs[zeros:])
        boundary_infinity = 0
        axis_zero = zeros
    if R.degree() > _max_degree():
        raise _Skip(f"degree {R.degree()} above the checker's limit")
    g = _axis_gcd(R) if R.degree() > 0 else flint.fmpq_poly([1])
    axis_count, axis_simple = _count_with_multiplicity(g) if g.degree() > 0 else (0, True)
    boundary = axis_count + boundary_infinity + axis_zero
    simple = axis_simple and boundary_infinity <= 1 and axis_zero <= 1
    if boundary != cert["boundary_count"]:
        raise _Fail(f"{boundary} boundary roots, the certificate claims {cert['boundary_count']}")
    claims_simple = all(r["multiplicity"] == 1 for r in cert["boundary"])
    if claims_simple != simple:
        raise _Fail("the boundary roots' simplicity differs from the certificate")
    # g's roots are the w0 with both s0 = j w0 and -s0 roots of R: the axis roots (real w0) and
    # mirror pairs off the axis (half of them in the right half plane). A(s) = g(-j s) collects
    # them all (real up to the unit -j when g is odd); the rest, R/A, has neither.
    mirrored = 0
    if g.degree() > 0:
        coeffs = g.coeffs()
        parity = next(k for k, a in enumerate(coeffs) if a != 0) % 2
        if any(a != 0 and k % 2 != parity for k, a in enumerate(coeffs)):
            raise _Fail("the axis factor is neither even nor odd")
        A = flint.fmpq_poly([a * (-1) ** ((k - parity) // 2) if k % 2 == parity else 0 for k, a in enumerate(coeffs)])
        core, remainder = divmod(R, A)
        if not remainder.is_zero():
            raise _Fail("the axis factor does not divide the polynomial")
        mirrored = g.degree() - axis_count
        if mirrored % 2:
            raise _Fail("mirror pairs of roots do not pair up")
    else:
        core = R
    if core.degree() > 0 and _axis_gcd(core).degree() > 0:
        raise _Fail("mirrored or axis roots remain after removing them")
    stable = (_routh_hurwitz(core) if core.degree() > 0 else True) and mirrored == 0
    if stable != (cert["outside"] == 0):
        raise _Fail("Routh-Hurwitz disagrees with the certificate on roots outside")
    _check_root_counts(cert, p)
    notes.append(f"{boundary} boundary roots ({'simple' if simple else 'not simple'}); "
                 + ("no root outside (Routh-Hurwitz)" if stable else "a root outside (Routh-Hurwitz fails, no axis roots left)"))
    return notes


def _check_root_counts(cert: dict, p: flint.fmpq_poly) -> None:
    """The counts add up to the degree, and each boundary root listed by its value is a root of
    that multiplicity on the boundary (``|z| = 1``; ``s = 0`` on the axis)."""
    counts = [cert.get(key) for key in ("inside", "outside", "boundary_count")]
    if not all(isinstance(n, int) and not isinstance(n, bool) and n >= 0 for n in counts):
        raise _Fail("the root counts (inside, outside, boundary_count) are not non-negative integers")
    if sum(counts) != p.degree():
        raise _Fail(f"inside + outside + boundary = {sum(counts)}, but the polynomial has degree {p.degree()}")
    listed = 0
    for root in cert["boundary"]:
        multiplicity = root["multiplicity"]
        if not isinstance(multiplicity, int) or isinstance(multiplicity, bool) or multiplicity < 1:
            raise _Fail(f"a boundary root's multiplicity {str(multiplicity)[:20]!r} is not a positive integer")
        try:
            value = _q(root["root"])
        except (TypeError, ValueError, ZeroDivisionError):
            listed += 2 * multiplicity                  # a conjugate pair, shown by its cosine or its factor
            continue
        listed += multiplicity
        on = abs(value) == 1 if cert["domain"] == "disk" else value == 0
        if not on:
            raise _Fail(f"the boundary root {value} is not on the boundary")
        order, q = 0, p
        x = flint.fmpq_poly([-flint.fmpq(value.numerator, value.denominator), 1])
        while not q.is_zero() and (q % x).is_zero():
            q, order = q // x, order + 1
        if order != multiplicity:
            raise _Fail(f"{value} is a root of multiplicity {order}, the certificate shows {multiplicity}")
    if listed != cert["boundary_count"]:
        raise _Fail(f"the boundary roots listed count {listed}, the certificate claims {cert['boundary_count']}")


def _check_residue(cert: dict) -> list[str]:
    transfer = cert["transfer"]
    pole = _q(cert["pole"])
    num, den = _poly(transfer["num"]), _poly(transfer["den"])
    factor = flint.fmpq_poly([-_fq(pole), 1])
    quotient, remainder = divmod(den, factor)
    if not remainder.is_zero():
        raise _Fail(f"z = {pole} is not a pole")
    if quotient(_fq(pole)) == 0:
        raise _Fail(f"z = {pole} is not a simple pole")
    value = _val(num, pole) / _val(quotient, pole) / pole
    if value != _q(cert["scaled"]):
        raise _Fail(f"Res/z0 = {value}, the certificate says {cert['scaled']}")
    if (value >= 0) != cert["holds"]:
        raise _Fail("the residue's sign differs from the certificate")
    return [f"Res/z0 = {value} at z0 = {pole}"]


def _check_constant_psd(cert: dict) -> list[str]:
    if len(cert["matrix"]) > _max_matrix():      # bounded before any work
        raise _Skip(f"a {len(cert['matrix'])} x {len(cert['matrix'])} matrix is above the checker's limit of "
                    f"{_max_matrix()} rows (HAPTICPROOF_CHECK_MAX_MATRIX)")
    M = [[_G(_q(a), _q(b)) for a, b in row] for row in cert["matrix"]]
    m = len(M)
    if any(M[i][j].re != M[j][i].re or M[i][j].im != -M[j][i].im for i in range(m) for j in range(m)):
        raise _Fail("the matrix is not Hermitian")
    E = _charpoly_coefficients(M)
    holds = all(e >= 0 for e in E)
    if holds != cert["holds"]:
        raise _Fail("the characteristic coefficients contradict the certificate")
    if not holds and "negative_minor" in cert:
        rows = cert["negative_minor"]["rows"]
        value = _det([[M[i][j] for j in rows] for i in rows]).re
        if not value < 0 or value != _q(cert["negative_minor"]["value"]):
            raise _Fail("the recorded principal minor is not negative")
    return [f"{m}x{m} matrix: E_k = {', '.join(str(e) for e in E[:4])}{'...' if m > 4 else ''} (Faddeev-LeVerrier)"]



def _degree(coeffs: list) -> int | None:
    """Degree of a JSON polynomial (lowest first), trailing zeros ignored; ``None`` for zero."""
    values = [_q(v) for v in coeffs]
    while values and values[-1] == 0:
        values.pop()
    return len(values) - 1 if values else None


def _check_infinity(cert: dict) -> list[str]:
    """Properness: the pole order at infinity recounted from the raw degrees of the original
    transfer function; a disproof's witness re-evaluated there (``Re(v^H F(w) v) < 0`` with
    ``|w| > 1`` or ``Re w > 0``), independently of the order's claim."""
    transfer = cert["transfer"]
    cells = transfer["entries"] if "entries" in transfer else [[{"num": transfer["num"], "den": transfer["den"]}]]
    m = len(cells)
    if any(len(row) != m for row in cells):
        raise _Fail("the transfer matrix is not square")
    orders, lead = [], [[Fraction(0)] * m for _ in range(m)]
    for row in cells:
        for cell in row:
            dn, dd = _degree(cell["num"]), _degree(cell["den"])
            if dd is None:
                raise _Fail("an entry has a zero denominator")
            if dn is not None:
                orders.append(dn - dd)
    order = max(orders, default=-1)
    if order != cert["order"]:
        raise _Fail(f"the pole order at infinity is {order}, the certificate says {cert['order']}")
    for i, row in enumerate(cells):
        for j, cell in enumerate(row):
            dn, dd = _degree(cell["num"]), _degree(cell["den"])
            if dn is not None and dn - dd == order:
                lead[i][j] = _q(cell["num"][dn]) / _q(cell["den"][dd])
    disk = cert["domain"] == "disk"
    if disk:
        holds = order <= 0
        how = "no pole at z = oo" if holds else f"a pole of order {order} at z = oo"
    elif order <= 0:
        holds, how = True, "no pole at s = oo"
    elif order > 1:
        holds, how = False, f"a pole of order {order} > 1 at s = oo"
    else:
        M = [[_G(lead[i][j]) for j in range(m)] for i in range(m)]
        hermitian = all(lead[i][j] == lead[j][i] for i in range(m) for j in range(m))
        holds = hermitian and all(e >= 0 for e in _charpoly_coefficients(M))
        how = "a simple pole at s = oo, residue " + ("PSD" if holds else "not Hermitian PSD")
    if holds != cert["holds"]:
        raise _Fail(f"{how}, the certificate says it {'holds' if cert['holds'] else 'fails'}")
    notes = [f"{how} (degrees recounted)"]
    if "witness" in cert:
        w = _G(_q(cert["witness"][0]), _q(cert["witness"][1]))
        if disk and not w.re * w.re + w.im * w.im > 1:
            raise _Fail("the witness is not outside the unit circle")
        if not disk and not w.re > 0:
            raise _Fail("the witness is not in the open right half-plane")
        v = [_G(_q(a), _q(b)) for a, b in cert["vector"]]
        total = _G(Fraction(0))
        for i in range(m):
            for j in range(m):
                if v[i].is_zero() or v[j].is_zero():
                    continue
                total = total + v[i].conj() * _eval_transfer(cells[i][j], w) * v[j]
        if total.re != _q(cert["re_value"]):
            raise _Fail(f"Re(v^H F(w) v) = {total.re}, the certificate says {cert['re_value']}")
        if not total.re < 0:
            raise _Fail("the witness value is not negative")
        notes.append("Re(v^H F(w) v) < 0 at the witness (exact)")
    elif not holds:
        notes.append("no witness point recorded (the degree count alone decides)")
    return notes


def _chebyshev_monomial(coeffs: list) -> flint.fmpq_poly:
    """``sum_k a_k T_k(c)`` in the monomial basis (the recurrence ``T_{k+1} = 2c T_k - T_{k-1}``)."""
    c = flint.fmpq_poly([0, 1])
    t0, t1 = flint.fmpq_poly([1]), c
    out = flint.fmpq_poly([])
    for k, a in enumerate(_q(v) for v in coeffs):
        if k >= 2:
            t0, t1 = t1, 2 * c * t1 - t0
        out += _fq(a) * (t0 if k == 0 else t1)
    return out


def _as_sign_certificate(cert: dict) -> dict:
    """A Chebyshev-basis sign certificate (long delays) as a monomial sign certificate: the
    same claim about ``num(c) den(c)``, converted here (up to the degree limit)."""
    degree = len(cert["numerator"]) + len(cert["denominator"]) - 2
    if degree > _max_degree():
        raise _Skip(f"degree {degree} above the checker's limit {_max_degree()} (HAPTICPROOF_CHECK_MAX_DEGREE)")
    num, den = _chebyshev_monomial(cert["numerator"]), _chebyshev_monomial(cert["denominator"])
    out = {k: v for k, v in cert.items() if k not in ("numerator", "denominator", "basis", "cover")}
    out.update(certificate="sign", polynomial=[str(a) for a in (num * den).coeffs()],
               numerator=[str(a) for a in num.coeffs()], denominator=[str(a) for a in den.coeffs()])
    return out


def _check_chebyshev(cert: dict) -> list[str]:
    return _check_sign(_as_sign_certificate(cert)) + ["converted from the Chebyshev basis"]


def _check_determinant(cert: dict) -> list[str]:
    """``det M(s) = numerator/denominator`` (lowest terms) for the rational matrix ``M`` (entries
    ``{num, den}`` in ``s``), proved by exact evaluation at more points than the degree of the
    polynomial identity allows; then the roots certificate of the numerator (Routh-Hurwitz) and,
    when ``rhp_zero`` is claimed, a zero of ``det M`` in ``Re s > 0``."""
    num, den = _poly(cert["numerator"]), _poly(cert["denominator"])
    if num.is_zero() or den.is_zero():
        raise _Fail("the determinant is identically zero (or has a zero denominator)")
    if num.gcd(den).degree() > 0:
        raise _Fail("numerator and denominator are not coprime")
    rows = [[(_poly(e["num"]), _poly(e["den"])) for e in row] for row in cert["matrix"]]
    m = len(rows)
    if any(len(row) != m for row in rows):
        raise _Fail("the matrix is not square")
    lcms, degree = [], 0
    for row in rows:
        lcm = flint.fmpq_poly([1])
        for _, d in row:
            lcm = lcm * d / lcm.gcd(d)
        lcms.append(lcm)
        present = [n.degree() + lcm.degree() - d.degree() for n, d in row if not n.is_zero()]
        if not present:
            raise _Fail("a zero row: the determinant vanishes identically")
        degree += max(present)
    product = flint.fmpq_poly([1])
    for lcm in lcms:
        product *= lcm
    if max(degree + den.degree(), num.degree() + product.degree()) > 4 * _max_degree():
        raise _Skip("determinant identity above the checker's degree limit")
    # det(M) * product is a polynomial of degree <= `degree`; the identity
    # det(M) * product * den - num * product = 0 has degree <= bound
    bound = max(degree + den.degree(), num.degree() + product.degree())
    checked, point = 0, Fraction(0)
    while checked <= bound:
        point += 1
        if _val(product, point) == 0 or _val(den, point) == 0:
            continue
        M = [[_G(_val(n, point) / _val(d, point)) for n, d in row] for row in rows]
        if _det(M).re * _val(den, point) != _val(num, point):
            raise _Fail(f"det M differs from numerator/denominator at s = {point}")
        checked += 1
    notes = [f"det M = numerator/denominator at {checked} points (identity proved by degree)"]
    roots = cert.get("roots")
    if roots is not None:
        if _poly(roots["polynomial"]) != num:
            raise _Fail("the roots certificate is not about the numerator")
        notes += _check_roots(roots)
        if cert.get("rhp_zero") and not roots["outside"] > 0:
            raise _Fail("no zero in Re s > 0 is certified")
        if cert.get("rhp_zero"):
            notes.append("a zero of det M in Re s > 0")
    return notes


def _check_residue_algebraic(cert: dict) -> list[str]:
    """A residue at an algebraic unit-circle pole (a conjugate pair): its value lies in a number
    field the checker has no arithmetic for -- a known kind, never re-verified (never success)."""
    raise _Skip("a residue at an algebraic pole (the checker has no number-field arithmetic)")


_CHECKS = {"sign": _check_sign, "psd": _check_psd, "roots": _check_roots, "residue": _check_residue,
           "residue-algebraic": _check_residue_algebraic,
           "constant-psd": _check_constant_psd, "chebyshev-sign": _check_chebyshev, "determinant": _check_determinant,
           "infinity": _check_infinity}


#: The whole interval a sign question over frequency covers: all ``c = cos(omega T)`` in
#: [-1, 1], all ``x = omega^2`` in [0, oo). A certificate over less decides less than it claims.
WHOLE = {"c": (Fraction(-1), Fraction(1)), "x": (Fraction(0), None)}


def _whole_interval(cert: dict) -> None:
    whole = WHOLE.get(cert.get("variable"))
    if whole is None or cert.get("certificate") not in ("sign", "chebyshev-sign", "psd"):
        return
    interval = cert.get("interval")
    if not isinstance(interval, list) or len(interval) != 2:
        raise _Fail("the certificate has no interval [lo, hi]")
    lo, hi = _q(interval[0]), None if interval[1] is None else _q(interval[1])
    if (lo, hi) != whole:
        shown = f"[{whole[0]}, {'oo)' if whole[1] is None else str(whole[1]) + ']'}"
        raise _Fail(f"the interval [{interval[0]}, {interval[1]}] does not cover the whole range {shown} of "
                    f"{cert['variable']}")


def check_certificate(cert: dict) -> CheckResult:
    """Re-verify one certificate (a JSON object with a ``"certificate"`` kind); an unknown
    kind, an interval that does not cover the whole range of ``c`` or ``x``, or a certificate
    whose exact arithmetic grows past the checker's work limit is never success."""
    kind = cert.get("certificate")
    check = _CHECKS.get(kind)
    if check is None:
        return CheckResult(False, f"FAILED: unknown certificate kind {str(kind)[:40]!r} "
                                  f"(known: {', '.join(sorted(_CHECKS))})")
    try:
        with _budget():
            _whole_interval(cert)
            for sub in cert.get("coefficients") or () if kind == "psd" else ():
                _whole_interval(sub)
            notes = check(cert)
            if kind == "sign" and "transfer" in cert:
                notes += _check_transfer_sign(cert, cert["transfer"])
            if kind == "chebyshev-sign" and "transfer" in cert:
                notes += _check_transfer_sign(_as_sign_certificate(cert), cert["transfer"])
    except _Skip as skip:
        return CheckResult(True, f"not re-verified: {skip}", verified=False)
    except _Fail as fail:
        return CheckResult(False, f"FAILED: {fail}")
    except (KeyError, TypeError, ValueError, ZeroDivisionError, IndexError, AttributeError, OverflowError) as err:
        return CheckResult(False, f"FAILED: malformed certificate ({type(err).__name__}: {str(err)[:200]})")
    return CheckResult(True, "; ".join(notes))


# ---------------------------------------------------------------------------------------------
# whole reports
# ---------------------------------------------------------------------------------------------


@dataclass
class ReportCheck:
    """Per-entry results of :func:`check_report`."""

    entries: list[tuple[str, list[CheckResult]]]
    #: every entry shows a verdict that claims nothing (``undecided``): no evidence is needed
    claims_nothing: bool = False

    @property
    def failed(self) -> list[tuple[str, CheckResult]]:
        return [(name, r) for name, results in self.entries for r in results if not r.ok]

    @property
    def ok(self) -> bool:
        return not self.failed

    @property
    def not_verified(self) -> list[tuple[str, CheckResult]]:
        """Results that could not be re-verified (a limit, a judge that could not evaluate)."""
        return [(name, r) for name, results in self.entries for r in results if r.ok and not r.verified]

    @property
    def accepted(self) -> bool:
        """Every verdict backed by evidence the checker re-verified and bound to it: nothing
        failed, refused or unbacked, and nothing left unverified (an unverifiable ``proved`` is
        never success)."""
        return self.ok and not self.not_verified and (self.evidenced or self.claims_nothing)

    @property
    def evidenced(self) -> bool:
        """Some certificate or judge object was re-verified (a report of nothing proves nothing)."""
        return any(r.ok and r.verified and r.source in ("certificate", "judge") for _, results in self.entries for r in results)

    def summary(self) -> str:
        lines = []
        verified = unverifiable = 0
        for name, results in self.entries:
            certs = [r for r in results if r.source == "certificate"]
            judged = [r for r in results if r.source != "certificate"]
            if all(r.source == "unbacked" for r in results):
                lines.append(f"{name}: no certificate (not re-verifiable)"
                             + ("; NOT BACKED: " + results[0].reason if results else ""))
                unverifiable += 1
                continue
            unbound = [r for r in results if r.source in ("unbacked", "symbolic")]
            results = [r for r in results if r.source != "unbacked"]
            good = sum(r.ok and r.verified for r in certs)
            skipped = [r for r in certs if r.ok and not r.verified]
            bad = [r for r in results if not r.ok]
            parts = [f"{good}/{len(certs)} certificates re-verified"] if certs else []
            definition = [r for r in judged if r.source == "judge"]
            if definition:
                parts.append(f"definition judged {sum(r.ok and r.verified for r in definition)}/{len(definition)}")
            shown = [r for r in judged if r.source == "display" and r.ok]
            if shown:
                parts.append(shown[0].reason)
            text = f"{name}: " + ("; ".join(parts) if parts else "no certificate")
            if skipped:
                text += "; " + "; ".join(r.reason for r in skipped[:2])
            if bad:
                text += "; " + "; ".join(_LABELS.get(r.source, "") + r.reason for r in bad[:3])
            if unbound:
                text += "; NOT RE-VERIFIED: " + unbound[0].reason
            lines.append(text)
            verified += good == len(certs) and not bad and bool(certs or definition) and \
                all(r.verified for r in results) and not unbound
        failed = self.failed
        unbacked = sum(r.source == "unbacked" for _, r in self.not_verified)
        skipped = len(self.not_verified) - unbacked
        lines.append(f"{len(self.entries)} entries: {verified} fully re-verified, "
                     f"{sum(r.source == 'certificate' for _, r in failed)} certificate(s) failed, "
                     f"{sum(r.source == 'judge' for _, r in failed)} definition check(s) failed, "
                     f"{sum(r.source in ('display', 'binding') for _, r in failed)} display(s) refused, "
                     f"{unverifiable} without a certificate; "
                     + ("report accepted" if self.accepted else
                        "report NOT accepted (" + ", ".join(part for part in (
                            f"{len(failed)} failed or refused" if failed else "",
                            f"{unbacked} verdict(s) without evidence" if unbacked else "",
                            f"{skipped} not re-verified" if skipped else "",
                            "no certificate or judge object re-verified" if not (self.evidenced or self.claims_nothing)
                            else "") if part) + ")"))
        return "\n".join(lines)


#: how a failure of each source is shown in the summary
_LABELS = {"display": "REFUSED (display): ", "binding": "REFUSED (not bound to its object): ",
           "unbacked": "NOT BACKED: "}


def check_certificates(node: Any) -> list[CheckResult]:
    """:func:`check_certificate` on every certificate inside a JSON value (in document order)."""
    return [check_certificate(c) for c in certificates(node)]


def _entries(report: Any) -> list[tuple[str, Any, dict[str, str]]]:
    """Top-level entries: audit equations, derive conditions (and the verdict they give), or
    the report itself; each with the keys its witnesses name the circle's quantities by (the
    paper's or the scene's ``names``/``notation``: :func:`~hapticproof.core.naming.witness_keys`)."""
    def keys(node: Any) -> dict[str, str]:
        return witness_keys(node.get("names") or node.get("notation") if isinstance(node, dict) else None)
    if isinstance(report, dict) and "papers" in report:
        return [(f"{p['paper']} ({e['id']})", e, keys(p)) for p in report["papers"] for e in p.get("equations", [])]
    if isinstance(report, dict) and "equations" in report:
        return [(f"{report.get('paper', '?')} ({e['id']})", e, keys(report)) for e in report["equations"]]
    if isinstance(report, dict) and isinstance(report.get("conditions"), list):
        return [(str(c.get("name", f"condition {i + 1}")) if isinstance(c, dict) else f"condition {i + 1}", c, keys(report))
                for i, c in enumerate(report["conditions"])]
    return [("report", report, keys(report))]


def judge_results(node: Any, keys: Mapping[str, str] | None = None) -> list[CheckResult]:
    """The definition-level judge (:mod:`hapticproof.exact.judge`) on every judge object inside
    a JSON value, and an audit finding's verdict and witness held against its judge object (the
    witness's circle keys named by ``keys``, :func:`~hapticproof.core.naming.witness_keys`)."""
    from hapticproof.exact.judge import judge, judges
    from hapticproof.exact.judgedisplay import boundary_display, finding_display

    out = []
    for obj in judges(node):
        result = judge(obj)
        out.append(CheckResult(result.ok, result.reason, verified=result.judged, source="judge"))
    if isinstance(node, dict):
        try:
            problems = finding_display(node, keys) + boundary_display(node)
        except (KeyError, TypeError, ValueError, IndexError, AttributeError, ArithmeticError) as err:
            reason = f"{type(err).__name__}: {str(err)[:120]}"
            problems = [f"what the entry displays cannot be held against its evidence ({reason})"]
        out += [CheckResult(False, problem, source="display") for problem in problems]
        crossings = node.get("crossings")
        if isinstance(node.get("judge"), dict) and isinstance(crossings, list) and len(crossings) > 1:
            # the judge holds the loops around the first crossing only
            out.append(CheckResult(True, f"{len(crossings) - 1} crossing(s) after the first are shown but not judged "
                                         "(no loops on their sides)", verified=False, source="symbolic"))
    return out


def check_report(report: Any) -> ReportCheck:
    """Re-verify every certificate in a saved JSON report (a dict, or a JSON string), judge every
    verdict that carries its original object against the definition, and re-derive what the
    report displays (verdicts, witnesses) from what it carries: a displayed verdict or witness
    its certificates and judge objects do not give is refused.

    >>> check_report({"conditions": [{"name": "x", "decision": "proved"}]}).summary().splitlines()[0]
    "x: no certificate (not re-verifiable); NOT BACKED: the verdict 'proved' carries no certificate or judge object to re-verify"
    >>> check_report({"conditions": [{"name": "x", "decision": "proved"}]}).accepted
    False
    >>> shown = {"conditions": [{"name": "x", "decision": "proved"}], "verdict": "disproved"}
    >>> check_report(shown).failed[0][1].reason
    "the verdict shown is 'disproved', its conditions give 'proved'"
    """
    from hapticproof.exact.acceptance import (
        CLAIMLESS,
        audit_binding,
        claim_of,
        decision_problems,
        derive_binding,
        factored_transfers,
        teleoperator_bounds,
        unbound_verdict,
        witness_problems,
    )
    from hapticproof.exact.judge import judge, judges
    from hapticproof.exact.judgedisplay import boundary_display, condition_display, derive_display
    from hapticproof.exact.scenebinding import scene_binding
    from hapticproof.exact.shownmatrix import matrix_displays
    from hapticproof.exact.shownnetwork import network_displays

    if isinstance(report, str):
        report = json.loads(report)
    out = []
    audit = isinstance(report, dict) and ("papers" in report or "equations" in report)
    factored = _guarded(lambda: factored_transfers(report), "binding")
    factored += _guarded(lambda: decision_problems(report), "binding")
    if factored:
        out.append(("report", factored))
    for name, entry, keys in _entries(report):
        results = check_certificates(entry) + judge_results(entry, keys)
        results += _guarded(lambda e=entry: audit_binding(e) if isinstance(e, dict) and "verdict" in e else [], "binding")
        results += _guarded(lambda e=entry, k=keys: witness_problems(e, k), "display")
        if not audit and isinstance(report, dict) and "verdict" not in report and isinstance(entry, dict):
            # a report without a verdict of its own (a network's): each condition against its certificates
            results += _guarded(lambda e=entry, k=keys: condition_display(e, k), "display")
        claim = claim_of(entry)
        if isinstance(entry, dict) and entry.get("decision") == "symbolic":
            # a condition on the parameters claims an 'iff' the checker cannot test at numbers: it
            # is re-derived (derive), never accepted as re-verified
            results.append(CheckResult(True, "a symbolic condition on the parameters (not re-verifiable by the "
                                             "checker: re-derive it)", verified=False, source="symbolic"))
        if audit and claim is not None and any(r.source == "certificate" for r in results) and \
                not any(r.source == "judge" and r.verified for r in results) and not _rechecked(entry):
            # certificates re-verify the exact decision; only a judge object binds it to the verdict
            # on the printed display (wrong, typo, confirmed...): without one, a relabelled verdict
            # would pass with the same certificates
            results.append(CheckResult(True, f"the verdict {claim!r} compares the printed display with the exact "
                                             "decision; no judge object re-judges that comparison (its certificates "
                                             "alone do not say which verdict they back)", verified=False,
                                       source="unbacked"))
        elif claim is not None and not any(r.source in ("certificate", "judge") for r in results):
            if _vacuous_residues(report, name, claim, out):
                results.append(CheckResult(True, "no pole on the boundary (the verified roots certificate of this report): "
                                                 "no residue to check", source="binding"))
            else:
                results.append(CheckResult(True, f"the verdict {claim!r} carries no certificate or judge object to "
                                                 "re-verify", verified=False, source="unbacked"))
        out.append((name, results))
    if not out:
        out.append(("report", [CheckResult(False, "nothing to check: the report carries no condition, certificate or "
                                                  "judge object", source="binding")]))
    if isinstance(report, dict) and "conditions" in report and "parameter" in report:
        # a boundary shown beside conditions: its judge object is looked for at the top level too
        out.append(("boundary", _guarded(lambda: boundary_display(report), "display")))
    if isinstance(report, dict) and "matrix" in report and "conditions" in report:
        out.append(("network", _guarded(lambda: network_displays(report), "display")))
    out = [(name, results) for name, results in out if results or name not in ("boundary", "network")]
    if isinstance(report, dict) and "conditions" in report and "verdict" in report:
        top = []
        definition = report.get("definition")
        for obj in judges(definition) if isinstance(definition, dict) else ():
            result = judge(obj)
            top.append(CheckResult(result.ok, result.reason, verified=result.judged, source="judge"))
        problems = [r for r in _guarded(lambda: derive_display(report), "display")]
        problems += _guarded(lambda: derive_binding(report), "binding")
        unbound = unbound_verdict(report)
        if unbound:
            top.append(CheckResult(True, unbound, verified=False, source="symbolic"))
        problems += _guarded(lambda: scene_binding(report), "binding")
        problems += _guarded(lambda: matrix_displays(report), "display")
        problems += _guarded(lambda: teleoperator_bounds(report), "display")
        problems += _guarded(lambda: witness_problems({"witness": report.get("witness")},
                                                       witness_keys(report.get("notation"))), "display")
        problems += _guarded(lambda: witness_problems({"definition": report.get("definition")}), "display")
        top += problems
        if not problems:
            top.append(CheckResult(True, "verdict and witness re-derived from the conditions", source="display"))
        out.append(("verdict", top))
    shown = [entry for _, entry, _ in _entries(report)]
    # (an audit only: a derive report of undecided conditions still shows its G^-1 and worst case)
    claimless = audit and bool(shown) and all(isinstance(e, dict) and (e.get("verdict", e.get("decision")) in CLAIMLESS)
                                              for e in shown)
    return ReportCheck(out, claims_nothing=claimless)


def _rechecked(entry: Any) -> bool:
    """An audit entry whose exact recheck at its witness binds its verdict (held against it by
    :func:`~hapticproof.exact.acceptance.audit_binding`: a disproof is never shown confirmed)."""
    evidence = entry.get("evidence") if isinstance(entry, dict) else None
    facts = evidence.get("facts") if isinstance(evidence, dict) else None
    return isinstance(facts, dict) and isinstance(facts.get("recheck"), dict) and \
        facts["recheck"].get("decision") in ("proved", "disproved")


def _vacuous_residues(report: Any, name: str, claim: str, done: list) -> bool:
    """A residue condition proved without a certificate because there is no pole on the
    boundary: backed by a roots certificate of the same report, re-verified above, that counts
    no boundary root."""
    if claim != "proved" or not ("esidue" in name or name.startswith("Res")) or not isinstance(report, dict) or "conditions" not in report:
        return False
    for _, results in done:
        for result in results:
            if result.source == "certificate" and result.ok and result.verified and \
                    (result.reason.startswith("0 boundary roots") or result.reason == "constant"):   # (a constant: no roots)
                return True
    return False


def _guarded(problems: Any, source: str) -> list[CheckResult]:
    """The refusals ``problems()`` finds; a part of the report it cannot read is a refusal too."""
    try:
        found = problems()
    except (KeyError, TypeError, ValueError, IndexError, AttributeError, ArithmeticError, RecursionError) as err:
        found = [f"a part of the report cannot be read ({type(err).__name__}: {str(err)[:120]})"]
    return [CheckResult(False, problem, source=source) for problem in found]
