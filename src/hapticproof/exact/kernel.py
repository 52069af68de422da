r"""The decision kernel: every exact sign question of the toolkit, answered with a certificate.

Three kinds of question reach it (DESIGN.md, *One decision kernel, one checker*):

* **sign** -- ``p(v) >= 0`` for every ``v`` in ``[lo, hi]`` (``hi`` may be ``+oo``), ``p`` a
  rational polynomial; a rational function ``num/den`` is decided by the sign of ``num*den``
  (equal wherever the function is defined). On the unit circle ``v = c = cos(wT)`` on
  ``[-1, 1]``; on the imaginary axis ``v = x = w**2`` on ``[0, oo)``.
* **psd** -- a Hermitian matrix function ``M(v)`` is PSD on the interval iff each coefficient
  ``E_k`` of its characteristic polynomial (sum of the ``k x k`` principal minors) is ``>= 0``
  there; the caller passes ``scale**k * E_k`` with a ``scale >= 0`` (certified too).
* **roots** -- where the roots of a polynomial lie relative to the unit circle (``disk``) or
  the imaginary axis (``halfplane``), with multiplicities of the boundary roots.

A decision is an :class:`~hapticproof.core.evidence.Outcome` whose ``evidence.facts['certificate']``
is a certificate object (:class:`SignCertificate`, :class:`PsdCertificate`,
:class:`RootCertificate`). Certificates serialize to plain JSON that the independent checker
(:mod:`hapticproof.exact.checker`) re-verifies with other algorithms (Sturm sequences, exact
evaluation of the original transfer function, Routh-Hurwitz), so a saved report can be
re-checked without trusting this module.

Witnesses are chosen where the checker can evaluate the *original* function exactly: on the
circle a point ``z0 = (1 + j t)/(1 - j t)`` with rational ``t`` (``cos``, ``sin`` rational), on
the axis a rational ``w``.

>>> import flint
>>> out = decide_sign(flint.fmpq_poly([-1, 0, 2]), -1, 1, variable="c")     # 2c^2 - 1
>>> out.decision.value, out.witness
('disproved', {'c': 0, 'z': ['0', '1'], 'omega_T': 'pi/2'})
>>> decide_sign(flint.fmpq_poly([1, -2, 1]), -1, 1, variable="c").decision.value  # (c-1)^2
'proved'
"""

from __future__ import annotations

import itertools
import math
from collections.abc import Callable, Sequence
from dataclasses import dataclass
from fractions import Fraction
from typing import Any

import flint
import sympy as sp

from hapticproof.core.evidence import Decision, Evidence, Method, Outcome
from hapticproof.exact.realroots import as_fmpq, flint_precision, real_roots, to_rational
from hapticproof.exact.rootcount import approximate_outside, exact_split

__all__ = [
    "SignCertificate",
    "PsdCertificate",
    "RootCertificate",
    "BoundaryRoot",
    "decide_sign",
    "decide_rational_sign",
    "sign_outcome",
    "decide_psd",
    "locate_roots",
    "simplest_between",
    "transfer_json",
    "scene_json",
    "ResidueCertificate",
    "ConstantPsdCertificate",
    "decide_constant_psd",
    "residue_outcome",
    "circle_point",
    "axis_point",
    "q_str",
    "poly_json",
    "squarefree_part",
]


# ---------------------------------------------------------------------------------------------
# exact numbers as JSON strings
# ---------------------------------------------------------------------------------------------


def q_str(value: Any) -> str:
    """An exact rational as ``"p/q"`` (or ``"p"``).

    >>> q_str(flint.fmpq(-3, 6)), q_str(2)
    ('-1/2', '2')
    """
    v = as_fmpq(value)
    return str(v.p) if v.q == 1 else f"{v.p}/{v.q}"


def poly_json(p: flint.fmpq_poly | flint.fmpz_poly) -> list[str]:
    """Coefficients, lowest degree first, as exact strings (``[]`` for the zero polynomial)."""
    return [q_str(a) for a in flint.fmpq_poly(p).coeffs()]


def squarefree_part(p: flint.fmpq_poly) -> flint.fmpq_poly:
    """The product of the distinct irreducible factors of ``p`` (same real roots, simple)."""
    out = flint.fmpq_poly([1])
    for factor, _ in p.numer().factor_squarefree()[1]:
        out *= flint.fmpq_poly(factor)
    return out


# ---------------------------------------------------------------------------------------------
# simple witnesses: simplest rationals, rational points of the circle and the axis
# ---------------------------------------------------------------------------------------------


def simplest_between(a: Fraction, b: Fraction | None) -> Fraction:
    """The simplest rational (smallest denominator, then numerator) in the open ``(a, b)``
    (``b = None``: unbounded above).

    >>> simplest_between(Fraction(1, 3), Fraction(1, 2)), simplest_between(Fraction(-7, 2), None)
    (Fraction(2, 5), Fraction(-3, 1))
    """
    if b is not None and not a < b:
        raise ValueError("empty interval")
    if b is None:
        return Fraction(math.floor(a) + 1)
    if a < 0 < b:
        return Fraction(0)
    if b <= 0:
        return -simplest_between(-b, -a)
    floor = math.floor(a)
    if floor + 1 < b:
        return Fraction(floor + 1)
    lo, hi = a - floor, b - floor            # 0 <= lo < hi <= 1
    if lo == 0:
        return floor + Fraction(1, math.floor(1 / hi) + 1)
    return floor + 1 / simplest_between(1 / hi, 1 / lo)


def _fraction(value: flint.fmpq) -> Fraction:
    return Fraction(int(value.p), int(value.q))


def _sqrt_bounds(value: Fraction, bits: int) -> tuple[Fraction, Fraction]:
    """Rational ``l <= sqrt(value) <= u`` (``value >= 0``)."""
    with flint_precision(bits):
        ball = flint.arb(flint.fmpq(value.numerator, value.denominator)).sqrt()
        lower, upper = ball.lower(), ball.upper()
    return _arb_fraction(lower), _arb_fraction(upper)


def _arb_fraction(value: flint.arb) -> Fraction:
    man, exp = value.mid().man_exp()
    man, exp = int(man), int(exp)
    return Fraction(man * 2**exp) if exp >= 0 else Fraction(man, 2**-exp)


def circle_point(a: Fraction, b: Fraction) -> dict[str, Any] | None:
    """A rational point ``c = (1 - t^2)/(1 + t^2)`` strictly inside ``(a, b)`` (a subinterval of
    ``[-1, 1]``), where ``sin(wT) = 2t/(1 + t^2)`` is rational too: the witness
    ``z0 = e^{jwT} = c + j sin(wT)`` is a Gaussian rational. ``None`` if none was found (an
    interval narrower than 2^-4000).

    >>> circle_point(Fraction(0), Fraction(1, 2))['c']
    Fraction(5, 13)
    """
    a, b = max(a, Fraction(-1)), min(b, Fraction(1))
    if not a < b:
        return None
    bits = 96
    while bits <= 4096:
        # t = sqrt((1 - c)/(1 + c)) decreases in c: c in (a, b) <=> t in (t(b), t(a))
        _, t_low = _sqrt_bounds((1 - b) / (1 + b), bits)
        t_high = None if a == -1 else _sqrt_bounds((1 - a) / (1 + a), bits)[0]
        if t_high is None or t_low < t_high:
            t = simplest_between(t_low, t_high)
            c = (1 - t * t) / (1 + t * t)
            if a < c < b:
                return _circle_witness(c, t)
        bits *= 2
    return None


def _circle_witness(c: Fraction, t: Fraction | None) -> dict[str, Any]:
    """``{'c', 'z': [Re, Im], 'omega_T'}`` for ``c = (1-t^2)/(1+t^2)``; ``t=None`` means c = -1."""
    if t is None:
        return {"c": Fraction(-1), "z": [Fraction(-1), Fraction(0)], "omega_T": "pi"}
    sine = 2 * t / (1 + t * t)
    if t == 0:
        angle = "0"
    elif t == 1:
        angle = "pi/2"
    else:
        angle = f"2*atan({t})"
    return {"c": c, "z": [c, sine], "omega_T": angle}


def axis_point(a: Fraction, b: Fraction | None) -> dict[str, Any]:
    """A rational frequency ``w`` with ``x = w^2`` strictly inside ``(a, b)`` (``0 <= a``;
    ``b = None`` unbounded): the witness ``s0 = j w`` is exact.

    >>> axis_point(Fraction(2), Fraction(3))
    {'x': Fraction(9, 4), 'omega': Fraction(3, 2)}
    """
    bits = 96
    while True:
        _, low = _sqrt_bounds(a, bits)
        high = None if b is None else _sqrt_bounds(b, bits)[0]
        if high is None or low < high:
            w = simplest_between(low, high)
            if w > 0 and a < w * w and (b is None or w * w < b):
                return {"x": w * w, "omega": w}
        bits *= 2
        if bits > 8192:  # pragma: no cover - an interval narrower than 2^-8000
            raise ArithmeticError("no rational frequency found in the interval")


# ---------------------------------------------------------------------------------------------
# sign decisions
# ---------------------------------------------------------------------------------------------


@dataclass(frozen=True, eq=False)
class SignCertificate:
    """Evidence that ``polynomial >= 0`` on ``[lo, hi]`` (``holds``) or that it is not.

    ``points`` are exact sample points (the finite ends and one point in every gap between the
    isolating intervals ``roots`` of the distinct real roots); between consecutive points lies
    at most one distinct root, and ``polynomial`` is ``>= 0`` at every point -- the checker
    re-counts the roots with Sturm sequences. When it fails, ``witness`` is a point where the
    polynomial is negative. ``numerator``/``denominator`` are kept when the polynomial is their
    product (the sign of a rational function).
    """

    polynomial: flint.fmpq_poly
    lo: flint.fmpq
    hi: flint.fmpq | None
    variable: str
    holds: bool
    points: tuple[flint.fmpq, ...] = ()
    roots: tuple[tuple[flint.fmpq, flint.fmpq], ...] = ()
    witness: flint.fmpq | None = None
    label: str = ""
    numerator: flint.fmpq_poly | None = None
    denominator: flint.fmpq_poly | None = None
    witness_point: Any = None
    transfer: dict[str, Any] | None = None

    def to_json(self) -> dict[str, Any]:
        out: dict[str, Any] = {
            "certificate": "sign",
            "claim": f"{self.label or 'p'}({self.variable}) >= 0",
            "variable": self.variable,
            "interval": [q_str(self.lo), None if self.hi is None else q_str(self.hi)],
            "polynomial": poly_json(self.polynomial),
            "holds": self.holds,
        }
        if self.numerator is not None:
            out["numerator"] = poly_json(self.numerator)
            out["denominator"] = poly_json(self.denominator)
        if self.holds:
            out["points"] = [q_str(p) for p in self.points]
            out["roots"] = [[q_str(a), q_str(b)] for a, b in self.roots]
        else:
            out["witness"] = q_str(self.witness)
            if self.witness_point is not None:
                out["witness_point"] = ([q_str(v) for v in self.witness_point] if isinstance(self.witness_point, list)
                                        else q_str(self.witness_point))
        if self.transfer is not None:
            out["transfer"] = self.transfer
        return out


def transfer_json(num: Any, den: Any, variable: str = "z") -> dict[str, Any]:
    """The original transfer function ``num/den`` (polynomials in ``z`` or ``s``) for the checker."""
    return {"variable": variable, "num": poly_json(flint.fmpq_poly(num)), "den": poly_json(flint.fmpq_poly(den))}


def scene_json(T: Any, b: Any, z_a: Any, H: list[list[tuple[Any, Any]]]) -> dict[str, Any]:
    """The values a ``derive`` report's ``G^{-1}(z) = diag(b - z_a) + D(z) H(z) I(z)`` is built
    from -- the ``period`` T, the devices' ``damping`` b and operators' ``shortage`` of passivity
    z_a, the ``environment`` H(z) entry by entry as ``(num, den)`` in ``z`` -- so that ``check``
    rebuilds ``G^{-1}`` from the scene the report names, with the approximation and the delays it
    shows.

    >>> scene_json(1, [2], [0], [[([1, 3], [0, 1])]])["environment"]
    [[{'num': ['1', '3'], 'den': ['0', '1']}]]
    """
    def poly(coeffs: Any) -> list[str]:
        return poly_json(coeffs) if isinstance(coeffs, flint.fmpq_poly) else [q_str(c) for c in coeffs]

    # neutral keys: a scene whose period is h and damping c_d shows no T and no b
    return {"period": q_str(T), "damping": [q_str(v) for v in b], "shortage": [q_str(v) for v in z_a],
            "environment": [[{"num": poly(num), "den": poly(den)} for num, den in row]
                  for row in H]}


def _gaps(roots: list, lo: flint.fmpq, hi: flint.fmpq | None) -> tuple[list[flint.fmpq], list[tuple]]:
    """Sample points and the open gaps ``(a, b, point)`` between the isolating intervals.

    The points are the finite ends and one point inside every non-empty gap (``lo`` to the
    first interval, between consecutive intervals, the last interval to ``hi`` or beyond it when
    unbounded), so between consecutive points lies at most one distinct root.
    """
    edges: list[tuple[flint.fmpq, flint.fmpq | None]] = []
    start = lo
    for r in roots:
        if start < r.lo:
            edges.append((start, r.lo))
        start = r.hi
    if hi is None:
        edges.append((start, None))
    elif start < hi:
        edges.append((start, hi))
    gaps = [(a, b, a + 1 if b is None else (a + b) / 2) for a, b in edges]
    points = {lo} | ({hi} if hi is not None else set()) | {g[2] for g in gaps}
    return sorted(points), gaps


def _witness_data(variable: str, w: flint.fmpq, gap: tuple | None, lo: flint.fmpq, hi: flint.fmpq | None,
                  is_pole: Callable[[dict[str, Any]], bool] | None = None) -> dict[str, Any] | None:
    """The witness mapping of a disproof: ``c`` with ``z`` on the circle, ``x`` with ``omega``
    on the axis, the plain point otherwise; ``None`` when the only candidate is a pole of the
    original transfer function (``is_pole``)."""
    fw = _fraction(w)
    candidates: list[dict[str, Any]] = []
    if variable == "c" and lo >= -1 and hi is not None and hi <= 1:
        if fw in (-1, 1):
            candidates.append(_circle_witness(fw, None if fw == -1 else Fraction(0)))
        elif gap is not None:
            a, b = _fraction(gap[0]), _fraction(gap[1])
            mid = (a + b) / 2
            candidates += [pt for pt in (circle_point(a, b), circle_point(a, mid), circle_point(mid, b)) if pt is not None]
    elif variable == "x" and lo >= 0:
        if fw == 0:
            candidates.append({"x": Fraction(0), "omega": Fraction(0)})
        elif gap is not None:
            a, b = max(_fraction(gap[0]), Fraction(0)), None if gap[1] is None else _fraction(gap[1])
            candidates.append(axis_point(a, b))
            candidates.append(axis_point(a, (a + b) / 2 if b is not None else a + 1))
    for cand in candidates:
        if is_pole is None or not is_pole(cand):
            return cand
    if candidates:
        return None
    return {variable: fw}


def _gaussian_at(coeffs: list[flint.fmpq], re: Fraction, im: Fraction) -> tuple[Fraction, Fraction]:
    acc_re, acc_im = Fraction(0), Fraction(0)
    for a in reversed(coeffs):
        acc_re, acc_im = acc_re * re - acc_im * im + _fraction(a), acc_re * im + acc_im * re
    return acc_re, acc_im


def _pole_test(transfer: dict[str, Any] | None, den: flint.fmpq_poly | None) -> Callable[[dict[str, Any]], bool] | None:
    """``is_pole(witness)`` for the original transfer function's denominator."""
    if den is None:
        return None
    coeffs = den.coeffs()
    variable = transfer.get("variable", "z") if transfer else "z"

    def is_pole(witness: dict[str, Any]) -> bool:
        if "z" in witness and variable == "z":
            re, im = witness["z"]
        elif "omega" in witness and variable == "s":
            re, im = Fraction(0), witness["omega"]
        else:
            return False
        return _gaussian_at(coeffs, re, im) == (0, 0)

    return is_pole


def _witness_outcome_value(witness: dict[str, Any], variable: str) -> flint.fmpq:
    value = witness[variable]
    return flint.fmpq(value.numerator, value.denominator)


def _sympy_witness(witness: dict[str, Any]) -> dict[str, Any]:
    out = {}
    for key, value in witness.items():
        if isinstance(value, Fraction):
            out[key] = sp.Rational(value.numerator, value.denominator)
        elif isinstance(value, list):
            out[key] = [str(v) for v in value]
        else:
            out[key] = value
    return out


def _refine_off_ends(roots: list, lo: flint.fmpq, hi: flint.fmpq | None) -> list:
    """Shrink isolating intervals that touch an end (root strictly inside), so that the open
    stretch between the end and the root has a sample point of its own."""
    out = []
    for r in roots:
        while not r.is_exact and (r.lo == lo or (hi is not None and r.hi == hi)):
            r = r.refine((r.hi - r.lo) / 2)
        out.append(r)
    return out


def _sign(p: flint.fmpq_poly, lo: Any, hi: Any, variable: str, label: str,
          numerator: flint.fmpq_poly | None = None, denominator: flint.fmpq_poly | None = None,
          transfer: dict[str, Any] | None = None, transfer_den: flint.fmpq_poly | None = None,
          pole_variable: str | None = None) -> tuple[SignCertificate, dict[str, Any] | None]:
    lo_q = as_fmpq(lo)
    hi_q = None if hi is None else as_fmpq(hi)
    if hi_q is not None and lo_q > hi_q:
        raise ValueError("empty interval")
    kwargs = dict(label=label, numerator=numerator, denominator=denominator, transfer=transfer)
    if p.is_zero():
        return SignCertificate(p, lo_q, hi_q, variable, True, (lo_q,), (), **kwargs), None
    roots = _refine_off_ends(real_roots(squarefree_part(p), lo_q, hi_q), lo_q, hi_q) if p.degree() > 0 else []
    points, gaps = _gaps(roots, lo_q, hi_q)
    if p.degree() == 0:
        points = [lo_q] if hi_q is None else [lo_q, hi_q]
    # the ends first (exact points the user knows: c = +-1, w = 0), then the gaps
    negative = [(pt, None) for pt in (lo_q, hi_q) if pt is not None and p(pt) < 0]
    negative += [(pt, gap) for gap in gaps for pt in (gap[2],) if p(pt) < 0]
    is_pole = _pole_test(transfer or ({"variable": pole_variable} if pole_variable else None), transfer_den)
    witness = None
    for point, gap in negative:
        witness = _witness_data(variable, point, gap, lo_q, hi_q, is_pole)
        if witness is not None:
            break
    if negative and witness is None:  # every simple candidate is a pole: keep a gap's sample point
        point, gap = next(((pt, g) for pt, g in negative if g is not None), negative[0])
        witness = {variable: _fraction(point)}
    if negative:
        value = _witness_outcome_value(witness, variable)
        if not p(value) < 0:  # the chosen simple point left the gap: keep the sample point
            witness = {variable: _fraction(point)}
            value = point
        exact_point = witness.get("z", witness.get("omega"))
        return SignCertificate(p, lo_q, hi_q, variable, False, witness=value, witness_point=exact_point, **kwargs), witness
    if any(p(pt) < 0 for pt in points):  # pragma: no cover - every point is an end or in a gap
        raise ArithmeticError("sign certificate inconsistent")
    return SignCertificate(p, lo_q, hi_q, variable, True, tuple(points),
                           tuple((r.lo, r.hi) for r in roots), **kwargs), None


def decide_sign(p: Any, lo: Any, hi: Any, variable: str = "c", label: str = "p") -> Outcome:
    """Exact decision of ``p >= 0`` on ``[lo, hi]`` (``hi=None``: ``[lo, oo)``) with a certificate.

    A disproof carries a witness where ``p < 0`` (on the circle with ``z``, on the axis with
    ``omega``, see :func:`circle_point`).

    >>> out = decide_sign(flint.fmpq_poly([-99900000, 100099999, 1]), 0, None, variable="x")
    >>> out.decision.value, out.witness['x']         # negative just right of x = 0
    ('disproved', 0)
    """
    p = flint.fmpq_poly(p) if not isinstance(p, flint.fmpq_poly) else p
    cert, witness = _sign(p, lo, hi, variable, label)
    return sign_outcome(cert, witness, f"{label}({variable})")


def _interval_text(cert: SignCertificate) -> str:
    return f"[{q_str(cert.lo)}, {'oo' if cert.hi is None else q_str(cert.hi)}]"


def _short(value: Any) -> str:
    """An exact number for a sentence: in full when short, else ~6 digits (the exact value is in
    the certificate)."""
    text = q_str(value)
    if len(text) <= 40:
        return text
    q = Fraction(int(value.p), int(value.q)) if hasattr(value, "p") else Fraction(value)
    sign, q = ("-" if q < 0 else ""), abs(q)
    # scientific notation from the exact integer parts (floats overflow past 1e308; the bit
    # lengths, not decimal strings, which Python refuses past 4300 digits)
    exponent = int((q.numerator.bit_length() - q.denominator.bit_length()) * 0.30102999566398120)
    while q >= Fraction(10) ** (exponent + 1):
        exponent += 1
    while q < Fraction(10) ** exponent:
        exponent -= 1
    mantissa = float(q / Fraction(10) ** exponent)
    return f"{sign}{mantissa:.6g}e{exponent:+d} (exact value in the certificate)"


def sign_outcome(cert: SignCertificate, witness: dict[str, Any] | None, what: str) -> Outcome:
    if cert.holds:
        touching = len(cert.roots)
        if cert.numerator is not None and cert.denominator is not None:
            # zeros of the function, not of num*den: a pole (a root of the denominator) touches nothing
            g = cert.numerator.gcd(cert.denominator)
            zeros = cert.numerator / g if g.degree() > 0 else cert.numerator
            touching = len(real_roots(zeros, cert.lo, cert.hi)) if zeros.degree() > 0 else 0
        reason = f"{what} >= 0 for all {cert.variable} in {_interval_text(cert)}"
        if touching:
            reason += f" (touches 0 at {touching} point{'s' if touching > 1 else ''})"
        return Outcome(Decision.PROVED, Evidence(Method.ROOT_ISOLATION, facts={"certificate": cert}), reason)
    value = cert.polynomial(cert.witness)
    if cert.numerator is not None:
        value = cert.numerator(cert.witness) / cert.denominator(cert.witness)
    shown = _sympy_witness(witness)
    return Outcome(Decision.DISPROVED,
                   Evidence(Method.ROOT_ISOLATION, witness=shown, facts={"certificate": cert, "value": to_rational(value)}),
                   f"{what} = {_short(value)} < 0 at {cert.variable} = {_short(cert.witness)}",
                   minimiser=None)


def decide_rational_sign(num: flint.fmpq_poly, den: flint.fmpq_poly, lo: Any, hi: Any, variable: str = "c",
                         label: str = "F", transfer: dict[str, Any] | None = None,
                         transfer_den: flint.fmpq_poly | None = None) -> Outcome:
    """Exact decision of ``num/den >= 0`` wherever it is defined on ``[lo, hi]``: the sign of
    ``num*den`` (equal off the poles; a limit argument covers the poles themselves).

    >>> c = flint.fmpq_poly([0, 1])
    >>> decide_rational_sign(1 + c, 1 - c, -1, 1).decision.value          # (1+c)/(1-c)
    'proved'
    """
    if den.is_zero():
        raise ZeroDivisionError("zero denominator")
    cert, witness = _sign(num * den, lo, hi, variable, label, numerator=num, denominator=den, transfer=transfer,
                          transfer_den=transfer_den)
    return sign_outcome(cert, witness, f"{label}({variable})")


# ---------------------------------------------------------------------------------------------
# PSD of a Hermitian matrix function over an interval
# ---------------------------------------------------------------------------------------------


@dataclass(frozen=True, eq=False)
class PsdCertificate:
    """Evidence that a Hermitian ``M(v)`` is PSD on the interval, or a point where it is not.

    ``coefficients[k-1]`` certifies ``scale**k E_k >= 0`` (``E_k`` the sum of the ``k x k``
    principal minors); ``scale`` certifies the scale itself ``>= 0``. A disproof gives the
    witness, the exact matrix there (``matrix``, Gaussian rationals as ``[re, im]``) and its
    negative principal minor. ``transfer`` (optional) is the original transfer matrix (entries
    ``[num, den]`` in ``z`` or ``s``) so that the checker can evaluate it itself.
    """

    variable: str
    lo: flint.fmpq
    hi: flint.fmpq | None
    size: int
    holds: bool
    coefficients: tuple[SignCertificate, ...]
    scale: SignCertificate | None
    witness: dict[str, Any] | None = None
    failing: int | None = None
    matrix: Any = None
    negative_minor: tuple[tuple[int, ...], Any] | None = None
    transfer: Any = None

    def to_json(self) -> dict[str, Any]:
        out: dict[str, Any] = {
            "certificate": "psd",
            "variable": self.variable,
            "interval": [q_str(self.lo), None if self.hi is None else q_str(self.hi)],
            "size": self.size,
            "holds": self.holds,
            "coefficients": [c.to_json() for c in self.coefficients],
        }
        if self.scale is not None:
            out["scale"] = self.scale.to_json()
        if self.transfer is not None:
            out["transfer"] = self.transfer
        if not self.holds:
            out["witness"] = {k: (q_str(v) if isinstance(v, Fraction) else [q_str(x) for x in v] if isinstance(v, list) else v)
                              for k, v in self.witness.items()}
            out["failing_k"] = self.failing
            if self.matrix is not None:
                out["matrix_at_witness"] = [[[q_str(sp.re(v)), q_str(sp.im(v))] for v in row] for row in self.matrix.tolist()]
            if self.negative_minor is not None:
                rows, value = self.negative_minor
                out["negative_minor"] = {"rows": list(rows), "value": q_str(value)}
        return out


def _negative_principal_minor(M: sp.Matrix) -> tuple[tuple[int, ...], Any] | None:
    """A principal minor of the exact Hermitian ``M`` that is negative (smallest first)."""
    m = M.rows
    for size in range(1, m + 1):
        if math.comb(m, size) > 5000:
            break
        for subset in itertools.combinations(range(m), size):
            value = sp.expand(M.extract(list(subset), list(subset)).det(method="bareiss"))
            if sp.re(value) < 0:
                return subset, sp.re(value)
    return None


def _transfer_poles(transfer: dict[str, Any]) -> flint.fmpq_poly:
    """The lcm of the denominators of a transfer matrix given as JSON (its poles)."""
    out = flint.fmpq_poly([1])
    for row in transfer["entries"]:
        for entry in row:
            den = flint.fmpq_poly([flint.fmpq(Fraction(v).numerator, Fraction(v).denominator) for v in entry["den"]])
            if den.degree() > 0:
                out = out * den / out.gcd(den)
    return out


def decide_psd(coefficients: Sequence[flint.fmpq_poly], lo: Any, hi: Any, variable: str = "c", *,
               scale: flint.fmpq_poly | None = None,
               evaluate: Callable[[dict[str, Any]], sp.Matrix] | None = None,
               transfer: Any = None, what: str = "M") -> Outcome:
    """Exact decision of ``M(v) >= 0`` (PSD) for every ``v`` in ``[lo, hi]``.

    ``coefficients[k-1]`` is ``scale(v)**k E_k(v)`` with ``E_k`` the characteristic
    coefficients of the Hermitian ``M`` and ``scale >= 0`` (``None`` means 1). PSD iff every
    ``E_k >= 0`` (the eigenvalues are real: Descartes' rule) -- never leading minors alone.
    ``evaluate(witness)`` returns the exact matrix at a disproof's witness, whose negative
    principal minor is recorded.

    >>> c = flint.fmpq_poly([0, 1])
    >>> out = decide_psd([2 + 0 * c, 1 - c * c], -1, 1)          # diag(1 + c, 1 - c)
    >>> out.decision.value
    'proved'
    """
    lo_q = as_fmpq(lo)
    hi_q = None if hi is None else as_fmpq(hi)
    scale_cert = None
    if scale is not None and scale.degree() > 0:
        scale_cert, bad = _sign(scale, lo_q, hi_q, variable, "scale")
        if not scale_cert.holds:
            raise ArithmeticError("the scale of the characteristic coefficients is negative somewhere")
    certs = []
    poles = _transfer_poles(transfer) if transfer is not None else None
    for k, p in enumerate(coefficients, start=1):
        cert, witness = _sign(flint.fmpq_poly(p), lo_q, hi_q, variable, f"E_{k}", transfer=None,
                              transfer_den=poles, pole_variable=(transfer or {}).get("variable", "z"))
        certs.append(cert)
        if not cert.holds:
            matrix = evaluate(witness) if evaluate is not None else None
            minor = _negative_principal_minor(matrix) if matrix is not None else None
            full = PsdCertificate(variable, lo_q, hi_q, len(coefficients), False, tuple(certs), scale_cert,
                                  witness, k, matrix, minor, transfer)
            facts: dict[str, Any] = {"certificate": full, "failing_k": k}
            if minor is not None:
                facts["negative_principal_minor"] = {"rows": [i + 1 for i in minor[0]], "value": minor[1]}
            return Outcome(Decision.DISPROVED, Evidence(Method.ROOT_ISOLATION, witness=_sympy_witness(witness), facts=facts),
                           f"{what} is not PSD at {variable} = {q_str(cert.witness)}: the sum of its {k}x{k} principal "
                           "minors is negative", minimiser=to_rational(cert.witness))
    full = PsdCertificate(variable, lo_q, hi_q, len(coefficients), True, tuple(certs), scale_cert, transfer=transfer)
    interval = f"[{q_str(lo_q)}, {'oo' if hi_q is None else q_str(hi_q)}]"
    return Outcome(Decision.PROVED, Evidence(Method.ROOT_ISOLATION, facts={"certificate": full, "size": len(coefficients)}),
                   f"{what} >= 0 for all {variable} in {interval}: every characteristic coefficient E_k >= 0")


@dataclass(frozen=True, eq=False)
class ConstantPsdCertificate:
    """A constant Hermitian matrix (Gaussian rationals) is PSD: its characteristic coefficients
    ``E_k`` (exact) are all ``>= 0``; or it is not: a negative principal minor."""

    matrix: Any
    holds: bool
    coefficients: tuple[Any, ...]
    negative_minor: tuple[tuple[int, ...], Any] | None = None

    def to_json(self) -> dict[str, Any]:
        out: dict[str, Any] = {
            "certificate": "constant-psd",
            "matrix": [[[q_str(sp.re(v)), q_str(sp.im(v))] for v in row] for row in self.matrix.tolist()],
            "holds": self.holds,
            "coefficients": [q_str(e) for e in self.coefficients],
        }
        if self.negative_minor is not None:
            out["negative_minor"] = {"rows": list(self.negative_minor[0]), "value": q_str(self.negative_minor[1])}
        return out


def decide_constant_psd(matrix: Any, what: str = "the matrix") -> Outcome:
    """Exact PSD decision of a constant Hermitian matrix with rational (or Gaussian rational)
    entries by its characteristic coefficients; a disproof names a negative principal minor.

    >>> decide_constant_psd(sp.Matrix([[0, 0], [0, -1]])).reason
    'the matrix is not PSD: principal minor [2] = -1 < 0'
    """
    from hapticproof.exact.charpoly import is_psd

    M = sp.Matrix(matrix)
    test = is_psd(M)
    minor = None
    if not test.holds:
        minor = test.minor or _negative_principal_minor(M)
    cert = ConstantPsdCertificate(sp.ImmutableMatrix(M), test.holds, test.coefficients[1:], minor)
    if test.holds:
        return Outcome(Decision.PROVED, Evidence(Method.CANONICAL_FORM, facts={"certificate": cert}),
                       f"{what} is PSD (every characteristic coefficient E_k >= 0)")
    rows = [i + 1 for i in minor[0]] if minor else []
    value = minor[1] if minor else None
    return Outcome(Decision.DISPROVED,
                   Evidence(Method.CANONICAL_FORM, witness={"principal_minor": rows, "value": value}, facts={"certificate": cert}),
                   f"{what} is not PSD: principal minor {rows} = {value} < 0")


# ---------------------------------------------------------------------------------------------
# where the roots lie: unit disk or left half plane
# ---------------------------------------------------------------------------------------------


@dataclass(frozen=True, slots=True)
class BoundaryRoot:
    """A root on the unit circle (``disk``) or the imaginary axis (``halfplane``).

    ``value`` is exact when rational (``z = +-1``, ``s = 0``); otherwise ``factor`` (an
    irreducible integer polynomial) and ``cosine`` (the isolated real root ``c0`` of the factor's
    image in ``c``, or ``w0**2`` on the axis) locate it. A conjugate pair counts once.
    """

    multiplicity: int
    value: sp.Expr | None = None
    factor: flint.fmpz_poly | None = None
    cosine: Any = None

    def label(self) -> str:
        if self.value is not None:
            return str(self.value)
        return f"pair with c = {self.cosine.approx(12)}" if self.cosine is not None else f"roots of {self.factor}"


@dataclass(frozen=True, eq=False)
class RootCertificate:
    """Where the roots of ``polynomial`` lie: ``boundary`` roots (exact, with multiplicities),
    the number ``outside`` (``|z| > 1`` or ``Re s > 0``, certified balls in ``outside_points``)
    and ``inside``."""

    polynomial: flint.fmpq_poly
    domain: str
    boundary: tuple[BoundaryRoot, ...]
    outside: int
    inside: int
    outside_points: tuple[complex, ...] = ()

    @property
    def boundary_simple(self) -> bool:
        return all(r.multiplicity == 1 for r in self.boundary)

    def to_json(self) -> dict[str, Any]:
        return {
            "certificate": "roots",
            "domain": self.domain,
            "variable": "z" if self.domain == "disk" else "s",
            "polynomial": poly_json(self.polynomial),
            "outside": self.outside,
            "inside": self.inside,
            "boundary": [{"multiplicity": r.multiplicity, "root": r.label()} for r in self.boundary],
            "boundary_count": sum(r.multiplicity * (1 if r.value is not None else 2) for r in self.boundary),
            "outside_points": [[p.real, p.imag] for p in self.outside_points],
        }


def _approximate(root: flint.fmpq) -> complex:
    """A rational root as a complex float for display, clamped to the float range (a pole at
    1e400 is shown as 1.8e308, the certificate's counts are exact)."""
    try:
        return complex(float(root))
    except OverflowError:
        return complex(1.7976931348623157e308 if root > 0 else -1.7976931348623157e308)


def _reciprocal(f: flint.fmpz_poly) -> flint.fmpz_poly:
    return flint.fmpz_poly(f.coeffs()[::-1])


def _c_image(f: flint.fmpz_poly) -> flint.fmpq_poly:
    """``h(c)`` with ``f(z) = z^(d/2) h(c)`` on the circle for a self-reciprocal ``f`` of even
    degree ``d``: ``z^k + z^-k = 2 T_k(c)``."""
    coeffs = f.coeffs()
    d = len(coeffs) - 1
    half = d // 2
    out = flint.fmpq_poly([coeffs[half]])
    for k in range(1, half + 1):
        out += flint.fmpq_poly(flint.fmpz_poly.chebyshev_t(k)) * (2 * coeffs[half + k])
    return out


def _located(f: flint.fmpz_poly, known_on: int, domain: str) -> tuple[int, int, list[complex]]:
    """Numbers of roots of ``f`` strictly inside / outside the unit circle (``disk``) or left /
    right of the imaginary axis (``halfplane``), given that exactly ``known_on`` of its roots
    are on the boundary: certified balls at moderate precision, else exact counts
    (:func:`hapticproof.exact.rootcount.exact_split`: a pole at ``1 + 1e-300`` needs no 2000-bit
    arithmetic), else balls at higher precision."""
    huge = max(abs(int(c)).bit_length() for c in f.coeffs()) > 256
    if huge or f.degree() <= 2:
        # exact first: big coefficients (1e-300 scales) make ball isolation slow at any precision
        exact = exact_split(f, known_on, domain)
        if exact is not None:
            return exact[0], exact[1], approximate_outside(f, exact[1], domain)
    precision = 64
    while precision <= 1 << 16:
        with flint_precision(precision):
            inside = outside = undecided = 0
            points = []
            for r, mult in f.complex_roots():
                gap = r.real * r.real + r.imag * r.imag - 1 if domain == "disk" else r.real
                if gap < 0:
                    inside += mult
                elif gap > 0:
                    outside += mult
                    points.append(complex(float(r.real.mid()), float(r.imag.mid())))
                else:
                    undecided += mult
            if undecided == known_on:
                return inside, outside, points
        if precision == 1024:
            exact = exact_split(f, known_on, domain)
            if exact is not None:
                return exact[0], exact[1], approximate_outside(f, exact[1], domain)
        precision *= 4
    where = "the unit circle" if domain == "disk" else "the imaginary axis"
    raise ArithmeticError(f"could not separate the roots from {where}")  # pragma: no cover


def _moduli(f: flint.fmpz_poly, known_on: int) -> tuple[int, int, list[complex]]:
    """Roots of ``f`` strictly inside / outside the unit circle (see :func:`_located`)."""
    return _located(f, known_on, "disk")


def _halfplane(f: flint.fmpz_poly, known_on: int) -> tuple[int, int, list[complex]]:
    """Roots of ``f`` left / right of the imaginary axis (see :func:`_located`)."""
    return _located(f, known_on, "halfplane")


def _even_odd(f: flint.fmpz_poly) -> tuple[flint.fmpz_poly, flint.fmpz_poly]:
    """``f(jw) = E(w^2)... `` split: even and odd coefficient polynomials in ``y = s^2``."""
    coeffs = f.coeffs()
    return flint.fmpz_poly(coeffs[0::2]), flint.fmpz_poly(coeffs[1::2])


def locate_roots(p: Any, domain: str = "disk") -> RootCertificate:
    """Exact location of the roots of ``p`` relative to the unit circle (``domain='disk'``) or
    the imaginary axis (``'halfplane'``).

    Each irreducible factor is examined: on the circle only self-reciprocal factors can have
    roots, and their number is the number of real roots in ``(-1, 1)`` of the factor's image in
    ``c`` (exact); the other roots are placed by certified complex isolation. On the axis only
    even factors (``f(-s) = +-f(s)``) can have roots, counted from the image in ``s^2 = -y``.

    >>> import flint
    >>> cert = locate_roots(flint.fmpq_poly([-2, 1]) * flint.fmpq_poly([-1, 1])**2)    # (z-2)(z-1)^2
    >>> cert.outside, [(r.label(), r.multiplicity) for r in cert.boundary]
    (1, [('1', 2)])
    """
    if domain not in ("disk", "halfplane"):
        raise ValueError("domain must be 'disk' or 'halfplane'")
    p = flint.fmpq_poly(p) if not isinstance(p, flint.fmpq_poly) else p
    if p.is_zero():
        raise ValueError("the zero polynomial")
    boundary: list[BoundaryRoot] = []
    inside = outside = 0
    points: list[complex] = []
    if p.degree() <= 0:
        return RootCertificate(p, domain, (), 0, 0)
    _, factors = p.numer().factor()
    for f, mult in factors:
        if f.degree() == 1:
            a0, a1 = f.coeffs()
            root = flint.fmpq(-a0, a1)
            if domain == "disk":
                if abs(root) == 1:
                    boundary.append(BoundaryRoot(mult, to_rational(root), f))
                elif abs(root) < 1:
                    inside += mult
                else:
                    outside += mult
                    points.append(_approximate(root))
            else:
                if root == 0:
                    boundary.append(BoundaryRoot(mult, sp.Integer(0), f))
                elif root < 0:
                    inside += mult
                else:
                    outside += mult
                    points.append(_approximate(root))
            continue
        on_roots: list[BoundaryRoot] = []
        if domain == "disk":
            rev = _reciprocal(f)
            if rev == f or rev == -f:
                if rev == -f:  # only z = +-1 factors are anti-reciprocal among irreducibles
                    pass
                else:
                    h = _c_image(f)
                    for r in real_roots(h, -1, 1):
                        on_roots.append(BoundaryRoot(mult, None, f, r))
        else:
            even, odd = _even_odd(f)
            if odd.is_zero() or even.is_zero():
                # f(s) = E(s^2) (or s O(s^2), handled by degree 1): roots on the axis are
                # s = +-j w with w^2 = -y for roots y < 0 of E
                image = even if odd.is_zero() else odd
                for r in real_roots(flint.fmpq_poly(image), None, 0):
                    if not (r.is_exact and r.lo == 0):
                        on_roots.append(BoundaryRoot(mult, None, f, r))
        boundary += on_roots
        known = 2 * len(on_roots)
        if domain == "disk":
            i, o, pts = _moduli(f, known)
        else:
            i, o, pts = _halfplane(f, known)
        inside += i * mult
        outside += o * mult
        points += pts
    return RootCertificate(p, domain, tuple(boundary), outside, inside, tuple(points))


# ---------------------------------------------------------------------------------------------
# residues at unit-circle poles
# ---------------------------------------------------------------------------------------------


@dataclass(frozen=True, eq=False)
class ResidueCertificate:
    """``Res(F, z0)/z0`` at a simple unit-circle pole ``z0`` of ``F = num/den``.

    For ``z0 = +-1`` the value is an exact rational (``scaled``) that the checker recomputes.
    For a conjugate pair ``z0 = c0 +- j sqrt(1 - c0^2)`` (``factor`` its minimal polynomial) the
    value lies in the number field ``Q(z0)``: its realness is decided exactly there (``real``)
    and its sign by certified ball arithmetic (``sign``); the checker does not re-verify these.
    """

    num: flint.fmpq_poly
    den: flint.fmpq_poly
    pole: Any
    holds: bool
    scaled: Any = None
    factor: flint.fmpz_poly | None = None
    real: bool = True
    approx: complex | None = None

    def to_json(self) -> dict[str, Any]:
        if self.factor is None:
            return {"certificate": "residue", "transfer": transfer_json(self.num, self.den), "pole": q_str(self.pole),
                    "scaled": q_str(self.scaled), "holds": self.holds}
        return {"certificate": "residue-algebraic", "transfer": transfer_json(self.num, self.den),
                "minimal_polynomial": poly_json(flint.fmpq_poly(self.factor)), "real": self.real,
                "approx": None if self.approx is None else [self.approx.real, self.approx.imag], "holds": self.holds}


def _mod(p: flint.fmpq_poly, f: flint.fmpq_poly) -> flint.fmpq_poly:
    return p % f


def _inverse_mod(a: flint.fmpq_poly, f: flint.fmpq_poly) -> flint.fmpq_poly:
    g, s, _ = a.xgcd(f)
    if g.degree() != 0:
        raise ZeroDivisionError("not invertible modulo the minimal polynomial")
    return s / g.coeffs()[0]


def _compose_mod(p: flint.fmpq_poly, w: flint.fmpq_poly, f: flint.fmpq_poly) -> flint.fmpq_poly:
    acc = flint.fmpq_poly([])
    for a in reversed(p.coeffs()):
        acc = _mod(acc * w + a, f)
    return acc


def residue_outcome(num: flint.fmpq_poly, den: flint.fmpq_poly, root: BoundaryRoot) -> Outcome:
    """Decide ``Res(num/den, z0)/z0 >= 0`` (real and non-negative) at a simple unit-circle pole.

    >>> z = flint.fmpq_poly([0, 1])
    >>> residue_outcome(z - 1, z + 1, locate_roots(z + 1).boundary[0]).decision.value     # (z-1)/(z+1)
    'proved'
    """
    deriv = den.derivative()
    if root.value is not None:
        z0 = as_fmpq(root.value)
        scaled = num(z0) / deriv(z0) / z0
        holds = scaled >= 0
        cert = ResidueCertificate(num, den, z0, holds, scaled)
        text = f"Res/z0 = {q_str(scaled)} at z0 = {q_str(z0)}"
        return Outcome(Decision.PROVED if holds else Decision.DISPROVED,
                       Evidence(Method.CANONICAL_FORM, witness=None if holds else {"pole": to_rational(z0)},
                                facts={"certificate": cert, "scaled_residue": to_rational(scaled)}),
                       text + (" >= 0" if holds else " < 0"))
    f = flint.fmpq_poly(root.factor)
    z = flint.fmpq_poly([0, 1])
    # g(z) = num(z) / (z den'(z)); real at z0 iff g(z0) = g(1/z0) in Q(z0) = Q[z]/(f)
    g = _mod(num, f) * _inverse_mod(_mod(z * deriv, f), f)
    w = _inverse_mod(z, f)
    g_conj = _compose_mod(num, w, f) * _inverse_mod(_compose_mod(z * deriv, w, f), f)
    real = _mod(g - g_conj, f).is_zero()
    c0 = root.cosine
    where = f"the unit-circle pole pair with cos(wT) ~ {c0.approx(10)}"
    if not real:
        cert = ResidueCertificate(num, den, None, False, None, root.factor, False)
        return Outcome(Decision.DISPROVED, Evidence(Method.CANONICAL_FORM, witness={"pole_cos": c0.approx(15)},
                                                    facts={"certificate": cert}),
                       f"Res/z0 is not real at {where} (exact, in Q(z0))")
    bits = 64
    value = None
    while bits <= 1 << 14:
        with flint_precision(bits + 32):
            cb = c0.ball(bits) if hasattr(c0, "ball") else flint.arb(c0)
            sb = (1 - cb * cb).sqrt()
            zb = flint.acb(cb, sb)
            gv = flint.acb_poly([flint.acb(a) for a in num.coeffs()])(zb) / (
                zb * flint.acb_poly([flint.acb(a) for a in deriv.coeffs()])(zb))
            if gv.real > 0 or gv.real < 0:
                value = complex(float(gv.real.mid()), float(gv.imag.mid()))
                positive = bool(gv.real > 0)
                break
        bits *= 4
    if value is None:  # pragma: no cover - the residue of a pole is nonzero
        return Outcome(Decision.UNDECIDED, Evidence(Method.INTERVAL_ARITHMETIC), "residue sign not separated from 0")
    holds = positive
    cert = ResidueCertificate(num, den, None, holds, None, root.factor, True, value)
    text = f"Res/z0 ~ {value.real:.6g} {'>= 0' if positive else '< 0'} at {where}"
    return Outcome(Decision.PROVED if holds else Decision.DISPROVED,
                   Evidence(Method.INTERVAL_ARITHMETIC, witness=None if holds else {"pole_cos": c0.approx(15)},
                            facts={"certificate": cert}), text)
