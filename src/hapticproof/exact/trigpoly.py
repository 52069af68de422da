r"""Certified sign and minimum of ``Re G^{-1}(e^{j theta})`` for long delays, in closed form.

For a delayed loop ``G^{-1}(z) = a + z^{-n} F(z)`` with a small rational ``F = pe/qe`` (HVE paper,
eqs. 21-27), the Hermitian part on the circle is

.. math:: f(\theta) = a + \Re\left(e^{-jn\theta} F(e^{j\theta})\right) = \frac{g(\theta)}{w(\theta)},
          \qquad g(\theta) = \sum_{k=0}^{N} b_k \cos k\theta ,

a trigonometric polynomial of degree ``N ~ n`` over a small positive one (``Re`` of a rational
function of ``c = cos theta`` in the Chebyshev basis: ``cos k theta = T_k(c)``). In the monomial
basis of ``c`` its coefficients grow like ``2^n``; here nothing is expanded:

* ``b_k`` are the coefficients of one palindromic Laurent polynomial
  ``a qe(z) qe(1/z) + (z^{-n} pe(z) qe(1/z) + z^n pe(1/z) qe(z))/2`` divided exactly by its
  common factor with ``qe(z) qe(1/z)`` (e.g. ``(z - 1)^2`` for the integrator): flint products
  and one exact division, ``O(n)`` memory;
* ``f`` and its derivatives are evaluated in **closed form** with ball arithmetic:
  ``d^k/dtheta^k [z^{-n} F] = j^k z^{-n} F_k`` with ``F_k = (z d/dz - n)^k F`` a small rational
  function, and ``e^{-jn theta}`` one cosine and sine -- the cost of a point does not depend on
  ``n`` (the Dirichlet kernel of :mod:`hapticproof.analysis.delayed` is the case ``F = KT/(z - 1)``);
* the **envelope** ``f >= a - |F(e^{j theta})|`` (``|z^{-n}| = 1``) proves whole stretches of
  frequencies at once where the delay's oscillation cannot reach zero.

A decision covers ``[0, pi]`` by pieces, each proved positive by one of: the envelope; a Taylor
bound ``f(mu) - |f'(mu)| h - max|f''| h^2/2`` (or, on convex pieces, ``f(mu) - f'(mu)^2/(2 min f'')``)
with every quantity a rigorous ``arb`` enclosure; or, next to ``theta = 0`` and ``pi``, an
**exact** Taylor expansion from the power sums ``S_m = sum b_k (+-1)^k k^m`` with the remainder
bounded by ``sum |b_k| k^m`` (exact rationals), which also proves a minimum that touches zero
exactly at an end (``b`` exactly at the boundary). A negative value is turned into an exact
witness: a rational point ``z0 = ((1 - t^2) + 2jt)/(1 + t^2)`` of the circle, re-evaluated with
exact inputs.

>>> import flint
>>> z = flint.fmpq_poly([0, 1])
>>> form = CircleForm(flint.fmpq(21, 1000), 10, flint.fmpq(2, 1000) + 0 * z, z - 1)   # b + z^-10 KT/(z-1)
>>> d = decide(form)
>>> d.holds, d.touching                      # b = KT/2 + KTn exactly: touches 0 at c = 1
(True, (1,))
>>> decide(CircleForm(flint.fmpq(20, 1000), 10, flint.fmpq(2, 1000) + 0 * z, z - 1)).witness['c'] < 1
True
"""

from __future__ import annotations

import math
from collections import deque
from dataclasses import dataclass
from fractions import Fraction
from typing import Any

import flint

from hapticproof.exact.realroots import flint_precision, real_roots

__all__ = ["CircleForm", "TrigDecision", "decide", "minimum", "chebyshev_to_monomial", "PI_HI"]

def _pi_upper() -> flint.fmpq:
    """A dyadic rational just above pi (pieces may reach past pi: f is symmetric about pi)."""
    with flint_precision(128):
        up = flint.arb.pi().upper()
        man, exp = up.mid().man_exp()
    value = flint.fmpq(int(man)) * flint.fmpq(2) ** int(exp) if int(exp) >= 0 else flint.fmpq(int(man), 2 ** -int(exp))
    return value + flint.fmpq(1, 2**100)


PI_HI = _pi_upper()


def _valuation(p: flint.fmpq_poly) -> int:
    for k, a in enumerate(p.coeffs()):
        if a != 0:
            return k
    return 0


def _shift(p: flint.fmpq_poly, k: int) -> flint.fmpq_poly:
    """``z^k p`` (``k >= 0``)."""
    return p * flint.fmpq_poly([0] * k + [1]) if k else p


def _reverse(p: flint.fmpq_poly) -> flint.fmpq_poly:
    return flint.fmpq_poly(p.coeffs()[::-1])


def chebyshev_to_monomial(coeffs: list) -> flint.fmpq_poly:
    """``sum_k coeffs[k] T_k(c)`` as a polynomial in ``c`` (Clenshaw; quadratic cost -- for
    certificates of moderate degree only).

    >>> chebyshev_to_monomial([1, 0, 2])          # 1 + 2 T_2 = 4c^2 - 1
    4*x^2 + (-1)
    """
    c2 = flint.fmpq_poly([0, 2])
    b1 = b2 = flint.fmpq_poly([])
    for a in reversed(list(coeffs)[1:]):
        b1, b2 = c2 * b1 - b2 + a, b1
    head = list(coeffs)[0] if coeffs else 0
    return flint.fmpq_poly([0, 1]) * b1 - b2 + head


def _sum_powers(poly: flint.fmpq_poly, m: int, at: int) -> flint.fmpq:
    """``sum_k poly_k k^m at^k`` via ``(x d/dx)^m`` (flint, linear cost)."""
    x = flint.fmpq_poly([0, 1])
    for _ in range(m):
        poly = poly.derivative() * x
    return poly(flint.fmpq(at))


class CircleForm:
    """``f(theta) = a + Re(e^{-jn theta} pe(e^{j theta})/qe(e^{j theta}))``: ``Re G^{-1}`` of a
    loop with a delay of ``n`` samples in front of a small path ``F = pe/qe``.

    Parameters
    ----------
    a : fmpq
        The undelayed constant (``b - z_a`` for the HVE device).
    n : int
        Delay in samples (any integer; powers of ``z`` in ``pe`` and ``qe`` are moved into it).
    pe, qe : fmpq_poly
        Numerator and denominator of ``F`` (``qe`` non-zero).
    """

    def __init__(self, a: Any, n: int, pe: flint.fmpq_poly, qe: flint.fmpq_poly):
        if qe.is_zero():
            raise ZeroDivisionError("qe = 0")
        self.a = flint.fmpq(a) if not isinstance(a, flint.fmpq) else a
        if not pe.is_zero():
            g = pe.gcd(qe)
            if g.degree() > 0:
                pe, qe = pe / g, qe / g
        vq = _valuation(qe)
        vp = _valuation(pe) if not pe.is_zero() else 0
        self.pe = flint.fmpq_poly(pe.coeffs()[vp:]) if not pe.is_zero() else pe
        self.qe = flint.fmpq_poly(qe.coeffs()[vq:])
        self.n = int(n) + vq - vp
        self._build()

    # -- exact Chebyshev form -----------------------------------------------------------------
    def _build(self) -> None:
        pe, qe, n, a = self.pe, self.qe, self.n, self.a
        dq = qe.degree()
        qq = qe * _reverse(qe)                       # z^dq |qe|^2, palindromic, degree 2 dq
        if pe.is_zero():
            num, m_shift = a * qq, dq
        else:
            dp = pe.degree()
            A = pe * _reverse(qe)                    # z^dq pe(z) qe(1/z)
            rA = _reverse(A)
            M = max(n + dq, dp - n, dq, 0)
            num = a * _shift(qq, M - dq) + (_shift(A, M - n - dq) + _shift(rA, M + n - dp)) / 2
            m_shift = M
        self.zero = num.is_zero()
        if self.zero:
            self.b = [flint.fmpq(0)]
            self.w = [flint.fmpq(1)]
            self.regular = True
            return
        common = num.gcd(qq)
        gnum, wden = num / common, qq / common
        r = common.degree() // 2
        gc, wc = m_shift - r, dq - r
        gco, wco = gnum.coeffs(), wden.coeffs()
        self.b = [gco[gc]] + [2 * gco[gc + k] for k in range(1, gc + 1)]
        self.w = [wco[wc]] + [2 * wco[wc + k] for k in range(1, wc + 1)]
        wmono = chebyshev_to_monomial(self.w)
        self.regular = wmono.degree() <= 0 or not real_roots(wmono, -1, 1)
        if self.regular and wmono(flint.fmpq(0)) < 0:
            self.b = [-x for x in self.b]
            self.w = [-x for x in self.w]
        self._bpoly = flint.fmpq_poly(self.b)
        self._babs = flint.fmpq_poly([abs(x) for x in self.b])
        self._wpoly = flint.fmpq_poly(self.w)
        self._wabs = flint.fmpq_poly([abs(x) for x in self.w])
        self._moments: dict[tuple, flint.fmpq] = {}

    @property
    def degree(self) -> int:
        """Degree ``N`` of the numerator's cosine series (= degree in ``c``)."""
        return len(self.b) - 1

    def pole_at(self, end: int) -> bool:
        """Whether ``qe`` vanishes at ``z = end`` (``+1``: ``c = 1``; ``-1``: ``c = -1``)."""
        return self.qe(flint.fmpq(end)) == 0

    def end_value(self, end: int) -> flint.fmpq:
        """Exact ``f`` at ``c = end`` (the limit where ``z = end`` is a pole of ``F``)."""
        if self.zero:
            return flint.fmpq(0)
        return self._bpoly(flint.fmpq(end)) / self._wpoly(flint.fmpq(end))

    def _moment(self, which: str, m: int, end: int) -> flint.fmpq:
        key = (which, m, end)
        if key not in self._moments:
            poly = {"b": self._bpoly, "w": self._wpoly, "|b|": self._babs, "|w|": self._wabs}[which]
            self._moments[key] = _sum_powers(poly, m, end)
        return self._moments[key]

    # -- exact expansion at an end --------------------------------------------------------------
    def end_cover(self, end: int, m: Any, sign: int = 1) -> tuple[str, Fraction | None]:
        """Exact Taylor analysis of ``h = sign (g - m w)`` at ``theta = 0`` (``end = 1``) or
        ``pi`` (``end = -1``): ``('ok', t)`` with ``h >= 0`` for ``|theta - theta_end| <= t``
        (rational ``t > 0``), ``('negative', None)`` when ``h < 0`` just off the end, or
        ``('unknown', None)``."""
        m = flint.fmpq(m) if not isinstance(m, flint.fmpq) else m
        s = []
        for j in range(4):
            S = self._moment("b", 2 * j, end) - m * self._moment("w", 2 * j, end)
            s.append(sign * (-1) ** j * S / math.factorial(2 * j))
        j0 = next((j for j, v in enumerate(s) if v != 0), None)
        if j0 is None or j0 > 2:
            return "unknown", None
        if s[j0] < 0:
            return "negative", None

        def remainder(J: int) -> flint.fmpq:
            return (self._moment("|b|", 2 * J + 2, 1) + abs(m) * self._moment("|w|", 2 * J + 2, 1)) / math.factorial(2 * J + 2)

        best = None
        R0 = remainder(j0)
        if R0 > 0:
            best = Fraction(int((s[j0] / R0).p), int((s[j0] / R0).q)) * Fraction(1023, 1024)   # strictly inside
        else:
            return "ok", Fraction(4)
        R1 = remainder(j0 + 1)
        if R1 > 0:
            b1 = float(s[j0 + 1])
            cand = (b1 + math.sqrt(b1 * b1 + 4 * float(R1) * float(s[j0]))) / (2 * float(R1))
            if cand > 0 and math.isfinite(cand):
                u = Fraction(cand * (1 - 1e-9)).limit_denominator(2**62) if cand > 1e-300 else Fraction(0)
                for _ in range(60):
                    uq = flint.fmpq(u.numerator, u.denominator)
                    if u > 0 and s[j0] + s[j0 + 1] * uq - R1 * uq * uq > 0:
                        break
                    u /= 2
                if u > best:
                    best = u
        t = _sqrt_lower(best)
        return ("ok", t) if t > 0 else ("unknown", None)

    # -- closed-form ball evaluation ------------------------------------------------------------
    def _prepare(self, prec: int) -> None:
        if getattr(self, "_prec", None) == prec:
            return
        self._prec = prec
        qe = self.qe
        R = [self.pe]
        dqe = qe.derivative()
        z = flint.fmpq_poly([0, 1])
        for k in range(3):
            Rk = R[-1]
            R.append(z * (Rk.derivative() * qe - (k + 1) * Rk * dqe) - self.n * Rk * qe)
        self._acb_R = [flint.acb_poly(r) for r in R]
        self._acb_q = flint.acb_poly(qe)
        self._arb_a = flint.arb(self.a)

    def _point(self, theta: flint.arb):
        c, s = theta.cos(), theta.sin()
        z = flint.acb(c, s)
        nt = theta * self.n
        e = flint.acb(nt.cos(), -nt.sin())
        return z, e

    def values(self, theta: flint.arb, orders: tuple[int, ...]) -> list[flint.arb]:
        """Enclosures of ``f^{(k)}`` over the ball ``theta`` for ``k`` in ``orders``."""
        z, e = self._point(theta)
        qz = self._acb_q(z)
        out = []
        unit = (flint.acb(1), flint.acb(0, 1), flint.acb(-1), flint.acb(0, -1))
        for k in orders:
            value = (unit[k % 4] * e * self._acb_R[k](z) / qz ** (k + 1)).real
            out.append(value + self._arb_a if k == 0 else value)
        return out

    def at_point(self, zr: Fraction, zi: Fraction) -> flint.arb:
        """Enclosure of ``f`` at the exact circle point ``z0 = zr + j zi``."""
        z = flint.acb(flint.arb(flint.fmpq(zr.numerator, zr.denominator)), flint.arb(flint.fmpq(zi.numerator, zi.denominator)))
        e = z.conjugate() ** self.n if self.n >= 0 else z ** (-self.n)
        return (e * self._acb_R[0](z) / self._acb_q(z)).real + self._arb_a

    def envelope(self, theta: flint.arb) -> flint.arb:
        """Lower bound ``a - |F(e^{j theta})|`` over the ball (no dependence on ``n``)."""
        z = flint.acb(theta.cos(), theta.sin())
        return self._arb_a - abs(self._acb_R[0](z) / self._acb_q(z))


def _sqrt_lower(u: Fraction) -> Fraction:
    """A rational ``t > 0`` with ``t^2 <= u`` (``0`` if ``u <= 0``)."""
    if u <= 0:
        return Fraction(0)
    t = Fraction(math.sqrt(float(u)) * (1 - 1e-12)).limit_denominator(2**62) if float(u) > 0 else Fraction(0)
    while t > 0 and t * t > u:
        t *= Fraction(1023, 1024)
    if t == 0:   # u below float range
        t = Fraction(1, 2 ** (u.denominator.bit_length() // 2 + 2))
        while t * t > u:
            t /= 2
    return t


# ---------------------------------------------------------------------------------------------
# decisions
# ---------------------------------------------------------------------------------------------


@dataclass(frozen=True, eq=False)
class TrigDecision:
    """The outcome of :func:`decide` or :func:`minimum`.

    ``holds``: ``f >= 0`` on ``[0, pi]`` (``None``: not decided within the budget -- the caller
    uses the exact monomial path); ``touching``: ends (``+1`` = ``c = 1``, ``-1`` = ``c = -1``)
    where ``f = 0`` exactly; ``witness``: ``{'c', 'z', 'omega_T'}`` with ``f < 0``; ``cover``:
    the pieces ``(theta_lo, theta_hi, method)`` of the proof (``theta_hi`` may be a rational just
    above ``pi``); ``lower``/``upper``: a certified enclosure of ``min f`` (``minimum`` mode, or
    what the proof saw); ``argmin``: ``theta`` of the best sample.
    """

    holds: bool | None
    touching: tuple[int, ...] = ()
    witness: dict[str, Any] | None = None
    witness_value: Any = None
    cover: tuple[tuple[Any, Any, str], ...] = ()
    lower: Any = None
    upper: Any = None
    argmin: Any = None
    reason: str = ""


def _precision(form: CircleForm) -> int:
    return 96 + 2 * max(1, abs(form.n)).bit_length()


def _piece_ball(lo: flint.fmpq, hi: flint.fmpq) -> flint.arb:
    return flint.arb(lo).union(flint.arb(hi))


def _taylor_lower(form: CircleForm, lo: flint.fmpq, hi: flint.fmpq) -> tuple[flint.arb, flint.arb]:
    """Rigorous lower bound of ``f`` on ``[lo, hi]`` and the enclosure of ``f`` at the midpoint."""
    mu = (lo + hi) / 2
    half = flint.arb((hi - lo) / 2)
    f0, f1 = form.values(flint.arb(mu), (0, 1))
    (f2,) = form.values(_piece_ball(lo, hi), (2,))
    if not (f0.is_finite() and f1.is_finite() and f2.is_finite()):
        return flint.arb(-(10**300)), f0
    bound = f0 - abs(f1) * half - flint.arb(abs(f2).upper()) * half * half / 2
    if f2 > 0:
        inf2 = flint.arb(f2.lower())
        convex = f0 - f1 * f1 / (2 * inf2)
        if convex.lower() > bound.lower():
            bound = convex
    return bound, f0


def circle_rational(t: Fraction) -> dict[str, Any]:
    """A rational point of the unit circle from the half-angle tangent ``t``: ``((1 - t^2)/(1 + t^2), 2t/(1 + t^2))``."""
    t2 = t * t
    c = (1 - t2) / (1 + t2)
    s = 2 * t / (1 + t2)
    angle = "0" if t == 0 else "pi/2" if t == 1 else f"2*atan({t})"
    return {"c": c, "z": [c, s], "omega_T": angle}


def is_root_at_witness(qe: flint.fmpq_poly, witness: dict[str, Any]) -> bool:
    """Is the Gaussian-rational ``z0`` a root of ``qe``? (exact: ``qe`` mod its minimal polynomial)"""
    re, im = witness["z"]
    x = flint.fmpq(re.numerator, re.denominator)
    if im == 0:
        return qe(x) == 0
    y2 = flint.fmpq((im * im).numerator, (im * im).denominator)
    minimal = flint.fmpq_poly([x * x + y2, -2 * x, 1])
    return (qe % minimal).is_zero()


def circle_witness(form: CircleForm, theta: flint.fmpq | None = None, *, end: int | None = None,
                   radius: Fraction | None = None) -> tuple[dict[str, Any], flint.arb] | None:
    """A rational point ``z0`` of the circle where ``f < 0``, re-evaluated with exact inputs: near
    ``theta`` (a point where a ball evaluation was negative) or within ``radius`` of an end."""
    candidates: list[Fraction] = []
    if end is not None:
        # theta = 2 atan(t) is within `radius` of 0 for t <= radius/2, of pi for t >= 2/radius:
        # the simplest such t (every point within the radius is negative)
        k = math.ceil(2 / radius)
        candidates = [Fraction(1, k), Fraction(1, 2 * k)] if end == 1 else [Fraction(k), Fraction(2 * k)]
    else:
        with flint_precision(128):
            tan = (flint.arb(theta) / 2).tan()
        t0 = float(tan.mid())
        for bits in (6, 10, 16, 24, 32, 48, 62):
            candidates.append(Fraction(t0).limit_denominator(2**bits))
        man, exp = tan.mid().man_exp()
        candidates.append(Fraction(int(man)) * Fraction(2) ** int(exp))
    seen = set()
    for t in candidates:
        if t < 0 or t in seen:
            continue
        seen.add(t)
        witness = circle_rational(t)
        if is_root_at_witness(form.qe, witness):
            continue
        with flint_precision(_precision(form) + 64):
            value = form.at_point(*witness["z"])
        if value < 0:
            return witness, value
    return None


def _end_witness(form: CircleForm, end: int, value: flint.fmpq) -> tuple[dict[str, Any], Any] | None:
    """The end itself when ``f(end) < 0`` and it is not a pole, else a rational point near it."""
    if not form.pole_at(end):
        c = Fraction(end)
        return {"c": c, "z": [c, Fraction(0)], "omega_T": "0" if end == 1 else "pi"}, value
    status, radius = form.end_cover(end, value / 2, sign=-1)     # g - (v/2) w <= 0 near the end
    if status != "ok":
        return None
    return circle_witness(form, end=end, radius=radius)


def _initial_pieces(lo: flint.fmpq, hi: flint.fmpq, n: int) -> list[tuple[flint.fmpq, flint.fmpq]]:
    """Geometric pieces away from ``theta = 0`` (the scale of a pole at ``z = 1``), then steps of
    at most ``pi/16`` (and ``2 pi/(n+1)``, the delay's period, capped at 4096 pieces)."""
    points = [lo]
    x = lo
    step_cap = flint.fmpq(1, 5)
    while x < hi:
        nxt = min(hi, x * 2 if x > 0 and x * 2 - x < step_cap else x + step_cap)
        points.append(nxt)
        x = nxt
    return list(zip(points, points[1:]))


def _run(form: CircleForm, mode: str, tol: flint.fmpq | None, budget: int) -> TrigDecision:
    """The branch-and-bound of :func:`decide` (``mode='sign'``) and :func:`minimum`."""
    if form.zero:
        return TrigDecision(True, (1, -1), lower=flint.fmpq(0), upper=flint.fmpq(0), reason="identically zero")
    if not form.regular:
        return TrigDecision(None, reason="unit-circle poles that do not cancel (or are not simple)")
    prec = _precision(form)
    cover: list[tuple[Any, Any, str]] = []
    touching: list[int] = []
    ends = {e: form.end_value(e) for e in (1, -1)}
    upper = min(ends.values())
    argmin = flint.fmpq(0) if ends[1] <= ends[-1] else PI_HI
    lower = None
    radius = {}
    with flint_precision(prec):
        form._prepare(prec)
        for end in (1, -1):
            v = ends[end]
            bound = v
            if mode == "sign":
                if v < 0:
                    found = _end_witness(form, end, v)
                    if found is None:
                        return TrigDecision(None, reason=f"negative at c = {end}, no exact witness found")
                    return TrigDecision(False, witness=found[0], witness_value=found[1], upper=v,
                                        reason=f"f = {v} < 0 at c = {end}")
                if v == 0:
                    status, r = form.end_cover(end, 0)
                    if status == "negative":     # f = 0 at the end and negative just inside
                        status, r = form.end_cover(end, 0, sign=-1)
                        found = circle_witness(form, end=end, radius=r) if status == "ok" else None
                        if found is None:
                            return TrigDecision(None, reason=f"negative next to c = {end}, no exact witness found")
                        return TrigDecision(False, witness=found[0], witness_value=found[1], upper=v,
                                            reason=f"f < 0 next to c = {end}")
                    touching.append(end)
                else:        # f = g/w > 0 on the whole exact piece (the bound is strict)
                    bound = flint.fmpq(0)
                    status, r = form.end_cover(end, bound)
            else:
                status, r = form.end_cover(end, v)
                if status != "ok":   # not a local minimum: cover down to the best value so far
                    bound = upper - tol
                    status, r = form.end_cover(end, bound)
            if status != "ok":
                return TrigDecision(None, reason=f"no exact expansion at c = {end}")
            r = min(r, Fraction(3, 2))
            radius[end] = r
            lower = bound if lower is None or bound < lower else lower
            cover.append((Fraction(0), r, "end-taylor") if end == 1 else ("pi - " + str(r), "pi", "end-taylor"))
        lo = flint.fmpq(radius[1].numerator, radius[1].denominator)
        hi = PI_HI - flint.fmpq(radius[-1].numerator, radius[-1].denominator)
        queue = deque((a, b, 0) for a, b in _initial_pieces(lo, hi, form.n)) if lo < hi else deque()
        count = 0
        while queue:
            a, b, depth = queue.popleft()
            count += 1
            if count > budget or depth > 48:
                return TrigDecision(None, reason=f"not decided ({count} pieces, depth {depth}): a zero touching 0 inside?",
                                    lower=lower, upper=upper)
            target = flint.fmpq(0) if mode == "sign" else upper - tol
            env = form.envelope(_piece_ball(a, b))
            if env.is_finite() and env > target:
                bound = env
                method = "envelope"
            else:
                bound, sample = _taylor_lower(form, a, b)
                method = "taylor"
                mid = (a + b) / 2
                if sample.is_finite():
                    up = sample.upper()
                    upq = arb_fmpq(up)
                    if upq < upper:
                        upper, argmin = upq, mid
                    if mode == "sign" and sample < 0:
                        found = circle_witness(form, mid)
                        if found is not None:
                            return TrigDecision(False, witness=found[0], witness_value=found[1], upper=upper,
                                                argmin=mid, reason="negative inside")
                if mode == "min":
                    target = upper - tol
            if bound.is_finite() and bound > target:
                lb = arb_fmpq(bound.lower())
                lower = lb if lower is None or lb < lower else lower
                cover.append((a, b, method))
                continue
            mid = (a + b) / 2
            queue.append((a, mid, depth + 1))
            queue.append((mid, b, depth + 1))
    if mode == "sign":
        return TrigDecision(True, tuple(touching), cover=tuple(cover), lower=lower, upper=upper, argmin=argmin,
                            reason=f"{len(cover)} pieces")
    return TrigDecision(True, cover=tuple(cover), lower=min(lower, upper) if lower is not None else upper,
                        upper=upper, argmin=argmin, reason=f"{len(cover)} pieces")


def arb_fmpq(value: flint.arb) -> flint.fmpq:
    """The midpoint of an arb ball as an exact rational."""
    man, exp = value.mid().man_exp()
    man, exp = int(man), int(exp)
    return flint.fmpq(man * 2**exp) if exp >= 0 else flint.fmpq(man, 2**-exp)


def decide(form: CircleForm, budget: int = 200_000) -> TrigDecision:
    """Decide ``f(theta) >= 0`` for every ``theta`` (equivalently every ``c`` in ``[-1, 1]``).

    >>> import flint
    >>> z = flint.fmpq_poly([0, 1])
    >>> decide(CircleForm(flint.fmpq(3, 10), 0, 0 * z + 1, z - 1)).holds        # 3/10 + 1/(z-1)
    False
    """
    return _run(form, "sign", None, budget)


def minimum(form: CircleForm, tol: Any = flint.fmpq(1, 2**40), budget: int = 200_000) -> TrigDecision:
    """A certified enclosure ``[lower, upper]`` of ``min f`` with ``upper - lower <= tol``
    (absolute), or ``holds=None`` when the budget runs out.

    >>> import flint
    >>> z = flint.fmpq_poly([0, 1])
    >>> m = minimum(CircleForm(0, 10, flint.fmpq(2, 1000) + 0 * z, z - 1))    # -KT/2 - KT n at c = 1
    >>> m.lower == m.upper == flint.fmpq(-21, 1000)
    True
    """
    tol = flint.fmpq(tol) if not isinstance(tol, flint.fmpq) else tol
    return _run(form, "min", tol, budget)
