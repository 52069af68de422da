r"""Oracles written from the definitions, at high precision, importing nothing from the package under test.

Positive realness is decided from what the word means, not from a derivation's shape:

* **discrete** (Hitz & Anderson; HVE paper, Definition 2): a real-rational ``G(z)`` is positive
  real when it is analytic in ``|z| > 1`` *including* ``z = infinity`` and ``Re G(z) >= 0`` there.
  Everything else is a consequence: an improper ``G`` has a pole at infinity (``G ~ a z^k`` takes
  every argument on a large circle), a pole outside the disc makes ``Re G`` take every value
  near it, a unit-circle pole must be simple with ``Res/z0 > 0`` (near ``z0`` the function is
  ``(Res/z0)/delta`` with ``Re delta > 0``), and ``Re G >= 0`` on the circle is the limit of the
  exterior values;
* **matrix**: ``G(z) + G(z)^H`` positive semidefinite for every ``|z| > 1`` (smallest eigenvalue);
* **continuous**: ``Z(s)`` analytic in ``Re s > 0`` with ``Re Z(s) >= 0`` there, ``s -> infinity``
  included (``Z ~ a s^k``: only ``k = 1, a > 0``, ``k = 0`` or ``k = -1, a > 0`` survive).

Each oracle returns an :class:`Answer`: ``yes``, ``no`` or ``uncertain``. A ``no`` always comes
with an **exact** witness -- a complex rational ``z`` (or ``s``) with ``|z| > 1`` (``Re s > 0``)
at which the real part (smallest Hermitian eigenvalue, through an exact rational vector) is
negative, re-computed in :class:`fractions.Fraction` arithmetic; so a ``no`` carries no floating
point doubt. A ``yes`` is numeric: ``Re G`` is sampled on circles ``|z| = r`` from ``r = 1`` (the
limit) through ``1 + 1e-12`` to ``1e100`` and at infinity, densely near poles and zeros close
to the circle, at the sign changes of ``Re G`` on the circle (roots of an exact polynomial) and
at the refined local minima, in mpmath at ``60 + (coefficient spread in decades)`` digits. The
stated uncertainty is the Horner forward-error bound of each evaluation; a minimum inside that
band is ``uncertain`` unless it sits at ``z = +-1`` where it is re-evaluated exactly.

The HVE device model (Section 3.1) ``G^{-1}(z) = (b - z_a) + z^{-n} H(z) X(z)/V(z)`` with the
three integrators, the continuous designs' discretisations (``forward s = (z-1)/T``, ``backward
s = (z-1)/(Tz)``, ``tustin s = 2(z-1)/(T(z+1))``, and ``zoh``/``matched`` where the result is
rational), the teleoperator's criterion (32) and the operator's shortage of passivity are built
here from the papers (:mod:`.models`).

>>> from oracles.models import hve_inverse
>>> z = Rat.variable()
>>> T = Fraction(1, 1000)
>>> G = hve_inverse(read("K*z**2", "z", {"K": 1}), "forward", T=T, b=1)
>>> ans = discrete_pr(G)
>>> ans.verdict, ans.witness["kind"]
('no', 'infinity')
>>> discrete_pr(hve_inverse(2 + (z - 1) / (10 * T * z), "forward", T=T, b=Fraction(102, 1000))).verdict
'yes'
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from fractions import Fraction
from typing import Any, Sequence

import mpmath

from .exactpoly import (Poly, Rat, ReadError, pdeg, pderiv, peval_complex, pgcd, pmul, prev, ptrim,
                       read, real_part_exact, squarefree)

__all__ = [
    "YES", "NO", "UNCERTAIN", "Answer", "discrete_pr", "discrete_pr_matrix", "continuous_pr",
    "unit_point", "read", "Rat", "ReadError",
]

YES, NO, UNCERTAIN = "yes", "no", "uncertain"
BASE_DPS = 60
MAX_DPS = 1500


@dataclass
class Answer:
    """An oracle's answer: ``verdict``, a sentence, an exact witness for ``no``, a relative margin
    (the smallest sampled value over the function's scale; negative: violated) and what the
    answer's uncertainty is."""

    verdict: str
    reason: str
    witness: dict | None = None
    margin: float | None = None
    uncertainty: str = ""
    extra: dict = field(default_factory=dict)

    def to_json(self) -> dict:
        return {"verdict": self.verdict, "reason": self.reason, "witness": self.witness,
                "margin": self.margin, "uncertainty": self.uncertainty, **self.extra}


# ---------------------------------------------------------------------------------------------
# numbers: mpmath <-> exact, precision from the data
# ---------------------------------------------------------------------------------------------
def _frac(x: Any, digits: int = 40) -> Fraction:
    """A readable exact rational close to an mpmath real (``digits`` significant digits)."""
    return Fraction(mpmath.nstr(mpmath.mpf(x), digits, min_fixed=-mpmath.inf, max_fixed=mpmath.inf)) \
        if x != 0 else Fraction(0)


def _fnum(q: Fraction) -> Any:
    """A float for the report, or a short decimal string beyond the float range."""
    if q == 0 or Fraction(10) ** -300 < abs(q) < Fraction(10) ** 300:
        return float(q)
    return mpmath.nstr(mpmath.mpf(q.numerator) / q.denominator, 12)


def _decades(polys: Sequence[Poly]) -> int:
    """Spread of the coefficients' magnitudes in decades (how much cancellation may occur)."""
    logs = [math.log10(abs(c.numerator)) - math.log10(c.denominator) for p in polys for c in p if c]
    return int(max(logs) - min(logs)) + 1 if logs else 0


def _height(polys: Sequence[Poly]) -> int:
    """Digits of the longest numerator or denominator: ``1 + 1.8e-99`` needs 100 digits to
    keep the pole it puts at ``1/(1 + 1.8e-99)`` apart from ``z = 1``."""
    bits = [max(abs(c.numerator).bit_length(), c.denominator.bit_length()) for p in polys for c in p]
    return int(max(bits, default=0) * 0.30103) + 1


def _dps_for(polys: Sequence[Poly]) -> int:
    return min(MAX_DPS, BASE_DPS + max(_decades(polys), _height(polys)) + 2 * max((pdeg(p) for p in polys), default=0))


def _mp(p: Poly) -> list:
    """Descending mpmath coefficients for :func:`mpmath.polyval`."""
    return [mpmath.mpf(c.numerator) / c.denominator for c in reversed(p)] if p else [mpmath.mpf(0)]


def _abs_poly(p: Poly, r: Any) -> Any:
    """``sum |p_k| r^k``: the scale of a Horner evaluation at ``|z| = r`` (its error bound)."""
    return mpmath.polyval([abs(c) for c in _mp(p)], r)


def unit_point(theta: Any, digits: int = 40) -> tuple[Fraction, Fraction]:
    """An exact rational point of the unit circle near angle ``theta`` (``|u| = 1`` exactly).

    ``u = ((1 - t^2) + 2jt)/(1 + t^2)`` with rational ``t ~ tan(theta/2)``; near ``theta = pi``
    the point is ``-u(theta - pi)``.

    >>> x, y = unit_point(2.0)
    >>> x * x + y * y == 1
    True
    """
    with mpmath.workdps(max(mpmath.mp.dps, digits + 10)):
        return _unit_point(mpmath.mpf(theta), digits)


def _unit_point(theta: Any, digits: int) -> tuple[Fraction, Fraction]:
    theta = theta - 2 * mpmath.pi * mpmath.floor((theta + mpmath.pi) / (2 * mpmath.pi))  # (-pi, pi]
    flip = abs(theta) > mpmath.pi / 2
    if flip:
        theta = theta - mpmath.pi if theta > 0 else theta + mpmath.pi
    t = _frac(mpmath.tan(theta / 2), digits)
    x, y = (1 - t * t) / (1 + t * t), 2 * t / (1 + t * t)
    return (-x, -y) if flip else (x, y)


def _as_rat(G: Any) -> Rat:
    if isinstance(G, Rat):
        return G
    num, den = G
    return Rat(ptrim(num), ptrim(den))


# ---------------------------------------------------------------------------------------------
# roots and poles
# ---------------------------------------------------------------------------------------------
ROOT_DPS = 100


class RootsFailed(RuntimeError):
    """The root finder did not converge within its budget."""


def _roots(p: Poly, dps: int, quick: bool = False, cap: int = ROOT_DPS) -> list:
    """Numeric roots of a square-free polynomial (mpmath at ``min(dps, ROOT_DPS)`` digits: a
    root's position relative to the unit circle needs digits of the root, not of the
    coefficients' spread); exact for degree 1. ``quick``: one bounded attempt, else
    :class:`RootsFailed`."""
    work = min(dps, cap)
    with mpmath.workdps(work):
        if quick and pdeg(p) > 1:
            try:
                roots, err = mpmath.polyroots(_mp(p), maxsteps=40 + 4 * pdeg(p), extraprec=work, error=True)
            except mpmath.libmp.NoConvergence as exc:
                raise RootsFailed(str(exc)) from None
            if err > mpmath.mpf(10) ** (-(work // 2)):
                raise RootsFailed(f"error estimate {err}")
            return [mpmath.mpc(r) for r in roots]
        return _roots_at(p, work)


def _roots_at(p: Poly, dps: int) -> list:
    d = pdeg(p)
    if d < 1:
        return []
    if d == 1:
        return [mpmath.mpc(mpmath.mpf(-p[0].numerator) / p[0].denominator / (mpmath.mpf(p[1].numerator) / p[1].denominator))]
    coeffs = _mp(p)
    for extra in (1, 3):
        try:
            roots, err = mpmath.polyroots(coeffs, maxsteps=60 + 12 * d * extra, extraprec=dps * extra, error=True)
            if err < mpmath.mpf(10) ** (-(dps // 2)):
                return [mpmath.mpc(r) for r in roots]
        except mpmath.libmp.NoConvergence:
            pass
    try:
        return [mpmath.mpc(r) for r in mpmath.polyroots(coeffs, maxsteps=400 + 40 * d, extraprec=4 * dps)]
    except mpmath.libmp.NoConvergence:
        # eigenvalues of the companion matrix (slower, robust to clustered roots)
        lead = coeffs[0]
        comp = mpmath.matrix(d, d)
        for j in range(d):
            comp[0, j] = -coeffs[j + 1] / lead
        for i in range(1, d):
            comp[i, i - 1] = 1
        return [mpmath.mpc(r) for r in mpmath.eig(comp, left=False, right=False)]


@dataclass
class _Pole:
    z: Any          # mpmath complex
    mult: int
    where: str      # "inside" | "on" | "outside"
    factor: Poly    # the square-free factor it is a root of


def _poles(den: Poly, dps: int) -> list[_Pole]:
    """Poles with multiplicities (exact square-free split, numeric roots); a pole is ``on`` the
    circle only if it is also a root of ``gcd(den, reversed den)`` (exact), else its modulus
    decides inside/outside."""
    out = []
    # poles at full precision: two poles 1e-99 apart (a pole near z = 1 and the integrator's)
    # must stay apart; denominators are short
    tol = mpmath.mpf(10) ** (-(dps // 2))
    for factor, mult in squarefree(den):
        circle = pgcd(factor, prev(factor))
        for r in _roots(factor, dps, cap=MAX_DPS):
            dist = abs(r) - 1
            on_candidate = pdeg(circle) > 0 and abs(mpmath.polyval(_mp(circle), r)) <= tol * _abs_poly(circle, abs(r))
            if on_candidate and abs(dist) <= tol:
                where = "on"
            elif dist > 0:
                where = "outside"
            else:
                where = "inside"
            out.append(_Pole(r, mult, where, factor))
    return out


def _laurent_lead(G: Rat, pole: _Pole) -> Any:
    """``c`` in ``G ~ c/(z - p)^mu`` at a pole ``p`` of multiplicity ``mu`` (numeric)."""
    mu = pole.mult
    # den = (z - p)^mu q(z): c = num(p)/q(p) = num(p) mu!/den^(mu)(p)
    d = G.den
    for _ in range(mu):
        d = pderiv(d)
    return mpmath.polyval(_mp(G.num), pole.z) * math.factorial(mu) / mpmath.polyval(_mp(d), pole.z)


# ---------------------------------------------------------------------------------------------
# exact witnesses
# ---------------------------------------------------------------------------------------------
def _check_point(G: Rat, x: Fraction, y: Fraction, domain: str) -> Fraction | None:
    """``Re G`` exactly at ``x + jy`` if the point is in the domain and not a pole."""
    if domain == "disc" and not x * x + y * y > 1:
        return None
    if domain == "half" and not x > 0:
        return None
    return real_part_exact(G.num, G.den, x, y)


def _witness(G: Rat, x: Fraction, y: Fraction, kind: str, domain: str = "disc", **info: Any) -> dict | None:
    value = _check_point(G, x, y, domain)
    if value is None or not value < 0:
        return None
    var = "z" if domain == "disc" else "s"
    return {"kind": kind, var: [str(x), str(y)], "re_value": str(value),
            "re_value_float": _fnum(value),
            **info}


def _point_candidates(z: Any, domain: str) -> list[tuple[Fraction, Fraction]]:
    """Rational points at and just beyond ``z`` (pushed outwards for the disc, rightwards for
    the half plane), at 40 and 25 significant digits."""
    out = []
    for digits in (40, 25, 60):
        x, y = _frac(mpmath.re(z), digits), _frac(mpmath.im(z), digits)
        out.append((x, y))
        if domain == "disc":
            for eps in (Fraction(1, 10**30), Fraction(1, 10**12), Fraction(1, 10**6)):
                out.append((x * (1 + eps), y * (1 + eps)))
        else:
            for eps in (Fraction(1, 10**30), Fraction(1, 10**12)):
                out.append((x + eps * (1 + abs(x)), y))
    return out


def _witness_near(G: Rat, z: Any, kind: str, domain: str = "disc", **info: Any) -> dict | None:
    for x, y in _point_candidates(z, domain):
        w = _witness(G, x, y, kind, domain, **info)
        if w is not None:
            return w
    return None


def _witness_at_circle_angle(G: Rat, theta: Any, kind: str = "circle") -> dict | None:
    """A point ``(1 + eps) u(theta)`` with ``u`` an exact rational unit point."""
    for digits in (40, 60, 25):
        ux, uy = unit_point(theta, digits)
        for k in (30, 20, 12, 8, 6, 4):
            eps = Fraction(1, 10**k)
            w = _witness(G, ux * (1 + eps), uy * (1 + eps), kind, "disc", theta=mpmath.nstr(theta, 20))
            if w is not None:
                return w
    return None


def _improper_witness(G: Rat, domain: str = "disc") -> dict | None:
    """``G ~ a x^k`` at infinity: on the ray where ``a x^k`` is negative real, far enough out."""
    k = G.excess
    a = G.num[-1] / G.den[-1]
    if domain == "disc":
        theta = mpmath.pi / k if a > 0 else mpmath.mpf(0)
        ux, uy = unit_point(theta, 4)                  # a short rational direction: a readable witness
    else:
        # arg s in (-pi/2, pi/2) with cos(k arg + arg a) < 0
        if k == 1:
            ux, uy = Fraction(1), Fraction(0)          # a < 0 here
        else:
            phi = (mpmath.pi if a > 0 else 0) / k + (0 if a > 0 else 0)
            phi = mpmath.pi * 3 / (4 * abs(k)) if a > 0 else mpmath.mpf(0)
            phi = min(phi, mpmath.pi * 0.45)
            ux, uy = _frac(mpmath.cos(phi), 30), _frac(mpmath.sin(phi), 30)
    found = None
    for e in (1, 2, 4, 8, 16, 32, 64, 128, 256, 512, 1024, 2048, 4096, 8192):
        R = Fraction(2) ** e
        if _witness(G, ux * R, uy * R, "infinity", domain) is not None:
            found = e
            break
    if found is None:
        return None
    lo, hi = found // 2, found            # a moderate radius: bisect on the exponent
    while hi - lo > 1:
        mid = (lo + hi) // 2
        if _witness(G, ux * Fraction(2) ** mid, uy * Fraction(2) ** mid, "infinity", domain) is not None:
            hi = mid
        else:
            lo = mid
    R = Fraction(2) ** hi
    return _witness(G, ux * R, uy * R, "infinity", domain, excess=k, leading=str(a))


def _pole_witness(G: Rat, pole: _Pole, domain: str = "disc") -> dict | None:
    """Near a pole ``p`` (``G ~ c/(z - p)^mu``) step ``delta`` in the direction that makes the
    polar part negative real; on the circle the direction is restricted to ``|z| > 1``."""
    c = _laurent_lead(G, pole)
    mu = pole.mult
    p = pole.z
    candidates = []
    if pole.where == "outside" or domain == "half" and mpmath.re(p) > 0:
        # c e^{-j mu phi} negative real: phi = (arg c - pi)/mu (+ 2 pi k/mu)
        for k in range(mu):
            candidates.append((mpmath.arg(c) - mpmath.pi + 2 * mpmath.pi * k) / mu)
    else:
        # boundary pole: z = p + delta e^{j phi} must lie in the domain: the outward normal is
        # arg p (disc) or 0 (half plane); allowed phi within +-pi/2 of it (strictly)
        normal = mpmath.arg(p) if domain == "disc" else mpmath.mpf(0)
        for k in range(-mu - 1, mu + 2):
            phi = (mpmath.arg(c) - mpmath.pi + 2 * mpmath.pi * k) / mu
            rel = phi - normal
            rel = rel - 2 * mpmath.pi * mpmath.floor((rel + mpmath.pi) / (2 * mpmath.pi))
            if abs(rel) < mpmath.pi / 2:
                candidates.append(phi)
            # the nearest allowed direction, if the ideal one is outside the domain
            edge = normal + mpmath.sign(rel) * (mpmath.pi / 2 - mpmath.mpf(10) ** -6)
            candidates.append(edge)
    for phi in candidates:
        for k in (3, 6, 10, 16, 24, 40):
            delta = mpmath.mpf(10) ** (-k) * max(1, abs(p))
            w = _witness_near(G, p + delta * mpmath.expj(phi), "pole", domain,
                              pole=[mpmath.nstr(mpmath.re(p), 20), mpmath.nstr(mpmath.im(p), 20)],
                              multiplicity=mu, location=pole.where)
            if w is not None:
                return w
    return None


# ---------------------------------------------------------------------------------------------
# the discrete scalar oracle
# ---------------------------------------------------------------------------------------------
def _circle_realpart_poly(G: Rat) -> Poly:
    """``P(z)`` with ``P(e^{jt}) = e^{jmt} 2 Re(N D^*)``: its unit-circle roots are the zeros of
    ``Re G`` on the circle (and the circle poles)."""
    N, D = G.num, G.den
    dN, dD = pdeg(N), pdeg(D)
    m = max(dN, dD)
    E = pmul(N, prev(D))             # z^dD N(z) D(1/z)
    F = pmul(prev(N), D)             # z^dN N(1/z) D(z)
    shift = lambda p, k: ptrim([Fraction(0)] * k + list(p))  # noqa: E731
    from .exactpoly import padd
    return padd(shift(E, m - dD), shift(F, m - dN))


def _circle_sign_changes(G: Rat, dps: int) -> tuple[list, bool, bool]:
    """Angles in ``[0, pi]`` of the unit-circle roots of :func:`_circle_realpart_poly`, whether
    every one of them has even multiplicity (exact, Yun), and whether the analysis was done
    (skipped for degrees above 48, where the dense grid alone is used)."""
    P = _circle_realpart_poly(G)
    if not P:
        return [], True, True
    if pdeg(P) > 48:
        return [], False, False
    angles, all_even = [], True
    tol = mpmath.mpf(10) ** (-(min(dps, ROOT_DPS) // 3))
    for factor, mult in squarefree(P):
        if pdeg(pgcd(factor, prev(factor))) == 0:
            continue                         # no unit-circle root in this factor (exact)
        try:
            found = _roots(factor, dps, quick=True)
        except RootsFailed:
            return [], False, False
        for r in found:
            if abs(abs(r) - 1) <= tol:
                th = abs(mpmath.arg(r))
                angles.append(th)
                if mult % 2 == 1 and abs(mpmath.polyval(_mp(G.den), r)) > tol:
                    all_even = False
    return sorted(angles), all_even, True


def discrete_pr(G: Any, *, dps: int | None = None, grid: int = 256) -> Answer:
    """Is the real-rational ``G(z)`` positive real (analytic and ``Re G >= 0`` in ``|z| > 1``,
    ``z = infinity`` included)?

    ``G`` is a :class:`Rat` or ``(num, den)`` coefficient lists (ascending powers, exact
    rationals).

    >>> z = Rat.variable()
    >>> discrete_pr(1 + z**2 / (1000 * (z - 1))).witness["kind"]
    'infinity'
    >>> discrete_pr((z + 1) / (z - 1)).verdict          # lossless: Re G = 0 on the circle
    'yes'
    >>> discrete_pr(1 / (z - 2)).witness["kind"]
    'pole'
    """
    G = _as_rat(G)
    if not G.num:
        return Answer(YES, "G = 0", margin=0.0, uncertainty="exact")
    if G.excess > 0:
        w = _improper_witness(G)
        return Answer(NO if w else UNCERTAIN, f"improper (degree excess {G.excess}): a pole at z = infinity", w,
                      uncertainty="exact witness" if w else "no witness found")
    dps = dps or _dps_for([G.num, G.den])
    with mpmath.workdps(dps):
        return _discrete_pr_proper(G, dps, grid)


def _discrete_pr_proper(G: Rat, dps: int, grid: int) -> Answer:
    poles = _poles(G.den, dps)
    for pole in poles:
        if pole.where == "outside":
            w = _pole_witness(G, pole)
            return Answer(NO if w else UNCERTAIN, f"pole outside the unit circle at z ~ {mpmath.nstr(pole.z, 12)}", w,
                          uncertainty="exact witness" if w else f"pole |z| - 1 = {mpmath.nstr(abs(pole.z) - 1, 5)}")
    on = [p for p in poles if p.where == "on"]
    for pole in on:
        try:
            c = _laurent_lead(G, pole)
        except ZeroDivisionError:
            return Answer(UNCERTAIN, f"poles near z0 ~ {mpmath.nstr(pole.z, 12)} not separated at {dps} digits")
        q = c / pole.z
        bad = pole.mult > 1 or mpmath.re(q) <= 0 or abs(mpmath.im(q)) > mpmath.mpf(10) ** (-(dps // 3)) * abs(q)
        if bad:
            w = _pole_witness(G, pole)
            what = "multiple" if pole.mult > 1 else f"Res/z0 = {mpmath.nstr(q, 12)} is not positive real"
            if w is not None:
                return Answer(NO, f"unit-circle pole z0 ~ {mpmath.nstr(pole.z, 12)}: {what}", w, uncertainty="exact witness")
            return Answer(UNCERTAIN, f"unit-circle pole z0 ~ {mpmath.nstr(pole.z, 12)}: {what}, but no witness found")
    exact = _ExactRe(G)
    heavy = pdeg(G.den) > 30                          # long delays: a sparser exterior
    if heavy:
        grid = min(grid, 160)
    # --- the angles: a grid, the circle poles, poles close to the circle, zeros of Re G on it
    angles = [mpmath.pi * k / grid for k in range(grid + 1)]
    pole_angles = [abs(mpmath.arg(p.z)) for p in on]
    for p in poles:
        th, gap = abs(mpmath.arg(p.z)), 1 - abs(p.z)
        if p.where == "on":
            angles += [th + s * mpmath.mpf(10) ** -k for k in (2, 4, 7, 12, 20) for s in (-1, 1)]
        elif gap < mpmath.mpf(1) / 4:
            angles += [th + s * gap * f for f in (0, 0.25, 0.5, 1, 2, 4) for s in (-1, 1)]
    roots, all_even, analysed = _circle_sign_changes(G, dps)
    marks = sorted(set([mpmath.mpf(0), mpmath.pi] + roots + pole_angles))
    angles += roots + [(a + b) / 2 for a, b in zip(marks, marks[1:])]
    angles = [a for a in angles if 0 <= a <= mpmath.pi]
    angles = [a for a in angles if all(abs(a - pa) > mpmath.mpf(10) ** -30 for pa in pole_angles)]
    radii = [Fraction(1), 1 + Fraction(1, 10**12), 1 + Fraction(1, 10**6), Fraction(1001, 1000), Fraction(11, 10),
             Fraction(2), Fraction(10), Fraction(10**3), Fraction(10**8), Fraction(10**30), Fraction(10**100)]
    if heavy:
        radii = radii[:2] + radii[4:6] + radii[-2:]
    coarse = [mpmath.pi * k / (12 if heavy else 32) for k in range(13 if heavy else 33)] + pole_angles + roots
    units = {}
    samples = []          # (value, sign, |G|, r, theta, x, y): Re G computed exactly at x + jy

    def sample(r, th):
        key = mpmath.nstr(th, 30)
        if key not in units:
            units[key] = unit_point(th)
        ux, uy = units[key]
        x, y = r * ux, r * uy
        got = exact.at(x, y)
        if got is not None:
            samples.append((got[0], got[1], got[2], r, th, x, y))
    for r in radii:
        for th in (angles if r == 1 else coarse):
            sample(r, th)
    g_inf = G.num[-1] / G.den[-1] if G.excess == 0 else Fraction(0)
    # the function's scale away from its circle poles (the margin is relative to it)
    far = [s[2] for s in samples if s[3] <= 2 and all(abs(s[4] - pa) > mpmath.mpf("0.01") for pa in pole_angles)]
    scale = max(far + [abs(mpmath.mpf(g_inf.numerator) / g_inf.denominator), mpmath.mpf(10) ** -300])
    # refine the lowest local minima on the circle (golden section, exact values)
    circle = sorted([s for s in samples if s[3] == 1], key=lambda s: s[4])
    mins = [i for i in range(len(circle)) if (i == 0 or circle[i][0] <= circle[i - 1][0])
            and (i == len(circle) - 1 or circle[i][0] <= circle[i + 1][0])]
    mins = sorted(mins, key=lambda i: circle[i][0])[:6]

    def on_circle(t):
        got = exact.at(*unit_point(t))
        return None if got is None else got[0]
    for i in mins:
        lo = circle[i - 1][4] if i > 0 else circle[i][4]
        hi = circle[i + 1][4] if i + 1 < len(circle) else circle[i][4]
        th = _golden(on_circle, lo, hi, pole_angles, iters=30)
        if th is not None:
            sample(Fraction(1), th)
    lowest = min(samples, key=lambda s: s[0])
    margin = float(lowest[0] / scale)
    if g_inf < 0:
        w = _witness_near(G, mpmath.mpf(10) ** 40, "infinity")
        return Answer(NO if w else UNCERTAIN, f"G(infinity) = {g_inf} < 0", w, margin, "exact witness" if w else "")
    negative = sorted([s for s in samples if s[1] < 0], key=lambda s: s[0])
    for v, sgn, mag, r, th, x, y in negative[:12]:
        w = _witness(G, x, y, "point", theta=mpmath.nstr(th, 20)) if r > 1 else _witness_at_circle_angle(G, th)
        if w is not None:
            w.setdefault("r", str(r))
            return Answer(NO, f"Re G = {mpmath.nstr(v, 10)} < 0 at |z| = {mpmath.nstr(mpmath.mpf(r.numerator) / r.denominator, 6)}, "
                          f"arg z = {mpmath.nstr(th, 12)}", w, margin, "exact witness")
    if negative:
        return Answer(UNCERTAIN, "Re G < 0 on the unit circle only (no exterior witness found)", None, margin, "exact samples")
    detail = ("sign structure on the circle from the unit-circle roots of an exact polynomial" if analysed
              else "dense grid only (degree too high for the root analysis)")
    how = f"{len(samples)} exact samples (Fractions) on |z| = 1 ... 1e100; {detail}"
    if lowest[1] > 0 and (analysed or margin > 1e-9):
        return Answer(YES, f"Re G >= {mpmath.nstr(lowest[0], 8)} > 0 at every sample; poles ok", None, margin, how)
    if lowest[1] == 0 and (all_even or not analysed):
        return Answer(YES, f"min Re G = 0 exactly at z ~ {mpmath.nstr(mpmath.expj(lowest[4]), 8)}; poles ok", None, 0.0,
                      how + ("; zeros on the circle of even multiplicity" if analysed else "; touching zero (grid)"))
    return Answer(UNCERTAIN, f"min sampled Re G = {mpmath.nstr(lowest[0], 6)} (relative {margin:.3g}) close to 0", None,
                  margin, how)


class _ExactRe:
    """``Re G`` at complex rational points by integer Horner: ``G = n/d`` with integer
    coefficients, ``z = (a + jb)/c``, ``Re G = Re(N conj D)/|D|^2`` with ``N = c^m n(z)``;
    the sign is exact, the value is reported in mpmath (30 digits)."""

    def __init__(self, G: Rat):
        L = 1
        for c in G.num + G.den:
            L = L * c.denominator // math.gcd(L, c.denominator)
        self.n = [int(c * L) for c in G.num]
        self.d = [int(c * L) for c in G.den]
        self.m = max(len(self.n), len(self.d)) - 1

    def _horner(self, p: list, a: int, b: int, cpow: list) -> tuple[int, int]:
        re_, im_ = 0, 0
        for k in range(self.m, -1, -1):
            coef = p[k] if k < len(p) else 0
            re_, im_ = re_ * a - im_ * b + coef * cpow[self.m - k], re_ * b + im_ * a
        return re_, im_

    def at(self, x: Fraction, y: Fraction) -> tuple[Any, int, Any] | None:
        c = x.denominator * y.denominator // math.gcd(x.denominator, y.denominator)
        a, b = x.numerator * (c // x.denominator), y.numerator * (c // y.denominator)
        cpow = [1]
        for _ in range(self.m):
            cpow.append(cpow[-1] * c)
        nr, ni = self._horner(self.n, a, b, cpow)
        dr, di = self._horner(self.d, a, b, cpow)
        dd = dr * dr + di * di
        if dd == 0:
            return None
        num = nr * dr + ni * di
        with mpmath.workdps(30):
            value = mpmath.mpf(num) / mpmath.mpf(dd)
            mag = mpmath.sqrt(mpmath.mpf(nr * nr + ni * ni) / mpmath.mpf(dd))
        return value, (num > 0) - (num < 0), mag


def _golden(f, lo: Any, hi: Any, avoid: list, iters: int = 45) -> Any:
    """Golden-section minimiser of ``f`` on ``[lo, hi]`` (``None`` if the bracket is empty)."""
    if hi <= lo:
        return None
    g = (mpmath.sqrt(5) - 1) / 2
    a, b = mpmath.mpf(lo), mpmath.mpf(hi)
    c, d = b - g * (b - a), a + g * (b - a)

    def val(t):
        if any(abs(t - pa) < mpmath.mpf(10) ** -30 for pa in avoid):
            return mpmath.inf
        v = f(t)
        return mpmath.inf if v is None else v
    fc, fd = val(c), val(d)
    for _ in range(iters):
        if fc < fd:
            b, d, fd = d, c, fc
            c = b - g * (b - a)
            fc = val(c)
        else:
            a, c, fc = c, d, fd
            d = a + g * (b - a)
            fd = val(d)
    return c if fc < fd else d


# ---------------------------------------------------------------------------------------------
# matrix discrete positive realness
# ---------------------------------------------------------------------------------------------
def _herm_min(mat: list[list[Any]]) -> tuple[Any, Any]:
    """Smallest eigenvalue and its eigenvector of ``M + M^H`` (mpmath)."""
    n = len(mat)
    H = mpmath.matrix(n, n)
    for i in range(n):
        for j in range(n):
            H[i, j] = mat[i][j] + mpmath.conj(mat[j][i])
    vals, vecs = mpmath.eighe(H)
    k = min(range(n), key=lambda i: vals[i])
    return vals[k], [vecs[i, k] for i in range(n)]


def _matrix_witness(G: list[list[Rat]], z: Any, vec: list, kind: str) -> dict | None:
    """Exact check of ``v^H (G + G^H) v < 0`` at a rational point near ``z`` (``|z| > 1``)."""
    n = len(G)
    for digits in (30, 45, 20):
        v = [(_frac(mpmath.re(c), digits), _frac(mpmath.im(c), digits)) for c in vec]
        for x, y in _point_candidates(z, "disc")[:4]:
            if not x * x + y * y > 1:
                continue
            vals = {}
            ok = True
            for i in range(n):
                for j in range(n):
                    nn = peval_complex(G[i][j].num, x, y)
                    dd = peval_complex(G[i][j].den, x, y)
                    if dd == (0, 0):
                        ok = False
                        break
                    from .exactpoly import complex_div
                    vals[i, j] = complex_div(nn, dd)
                if not ok:
                    break
            if not ok:
                continue
            # q = sum_ij conj(v_i) (G_ij + conj(G_ji)) v_j = 2 Re sum_ij conj(v_i) G_ij v_j
            total = Fraction(0)
            for i in range(n):
                for j in range(n):
                    gr, gi = vals[i, j]
                    # conj(v_i) * g * v_j
                    ar, ai = v[i][0], -v[i][1]
                    pr, pi_ = ar * gr - ai * gi, ar * gi + ai * gr
                    total += pr * v[j][0] - pi_ * v[j][1]
            if total < 0:
                return {"kind": kind, "z": [str(x), str(y)], "vector": [[str(a), str(b)] for a, b in v],
                        "quadratic_form": str(2 * total), "quadratic_form_float": _fnum(2 * total)}
    return None


def discrete_pr_matrix(G: Sequence[Sequence[Any]], *, dps: int | None = None, grid: int = 192) -> Answer:
    """Is the square real-rational matrix ``G(z)`` positive real (analytic in ``|z| > 1`` with
    infinity, ``G + G^H >= 0`` there)?

    >>> z = Rat.variable()
    >>> discrete_pr_matrix([[(z + 1) / (z - 1) + 1, 1 / z], [1 / z, 2 + 0 * z]]).verdict
    'yes'
    >>> discrete_pr_matrix([[1 + 0 * z, (z + 1) / (z - 1)], [-(z + 1) / (z - 1), 1 + 0 * z]]).verdict  # skew residue
    'no'
    >>> discrete_pr_matrix([[1 + 0 * z, 3 + 0 * z], [0 * z, 1 + 0 * z]]).verdict   # 2x2 [[2,3],[3,2]] indefinite
    'no'
    """
    G = [[_as_rat(e) for e in row] for row in G]
    entries = [e for row in G for e in row]
    dps = dps or min(_dps_for([p for e in entries for p in (e.num, e.den)]), 200)
    with mpmath.workdps(dps):
        mp_entries = [[(_mp(e.num), _mp(e.den)) for e in row] for row in G]

        def at(z):
            out = []
            for row in mp_entries:
                r = []
                for nu, de in row:
                    d = mpmath.polyval(de, z)
                    if d == 0:
                        return None
                    r.append(mpmath.polyval(nu, z) / d)
                out.append(r)
            return out
        # improper entries: a pole at infinity of some entry
        if any(e.excess > 0 for e in entries):
            for R in [mpmath.mpf(2) ** k for k in (4, 10, 20, 40, 80, 160, 320, 640)]:
                for th in [mpmath.pi * k / 16 for k in range(17)]:
                    z = R * mpmath.expj(th)
                    mat = at(z)
                    if mat is None:
                        continue
                    val, vec = _herm_min(mat)
                    if val < 0:
                        w = _matrix_witness(G, z, vec, "infinity")
                        if w:
                            return Answer(NO, "an improper entry: a pole at z = infinity", w, uncertainty="exact witness")
            return Answer(UNCERTAIN, "an improper entry but no witness found")
        poles = []
        seen = set()
        for e in entries:
            if pdeg(e.den) >= 1 and e.den not in seen:
                seen.add(e.den)
                poles += _poles(e.den, dps)
        for p in poles:
            if p.where == "outside" or p.where == "on":
                # probe around the pole in |z| > 1
                normal = mpmath.arg(p.z)
                for k in (3, 6, 10, 16):
                    for phi in [normal + mpmath.pi * (j / 12 - 0.5) * (0.999 if p.where == "on" else 2) for j in range(13)]:
                        z = p.z + mpmath.mpf(10) ** -k * mpmath.expj(phi)
                        if abs(z) <= 1:
                            continue
                        mat = at(z)
                        if mat is None:
                            continue
                        val, vec = _herm_min(mat)
                        if val < 0:
                            w = _matrix_witness(G, z, vec, "pole")
                            if w:
                                w["pole"] = [mpmath.nstr(mpmath.re(p.z), 20), mpmath.nstr(mpmath.im(p.z), 20)]
                                return Answer(NO, f"pole {p.where} the unit circle at z ~ {mpmath.nstr(p.z, 12)}", w,
                                              uncertainty="exact witness")
                if p.where == "outside":
                    return Answer(UNCERTAIN, f"pole outside at {mpmath.nstr(p.z, 12)} but no witness found")
        pole_angles = [abs(mpmath.arg(p.z)) for p in poles if p.where == "on"]
        angles = [mpmath.pi * k / grid for k in range(grid + 1)]
        for p in poles:
            th, gap = abs(mpmath.arg(p.z)), 1 - abs(p.z)
            if p.where == "on":
                angles += [th + s * mpmath.mpf(10) ** -k for k in (3, 6, 10) for s in (-1, 1)]
            elif gap < 0.25:
                angles += [th + s * gap * f for f in (0, 0.5, 1, 2) for s in (-1, 1)]
        angles = [a for a in angles if 0 <= a <= mpmath.pi and all(abs(a - pa) > mpmath.mpf(10) ** -40 for pa in pole_angles)]
        samples = []
        for r in (mpmath.mpf(1), 1 + mpmath.mpf(10) ** -8, mpmath.mpf("1.01"), mpmath.mpf(2), mpmath.mpf(100), mpmath.mpf(10) ** 20):
            for th in (angles if r == 1 else angles[:: max(1, len(angles) // 24)]):
                for sgn in ((1, -1) if r == 1 else (1,)):     # the matrix need not be symmetric: both halves
                    z = r * mpmath.expj(sgn * th)
                    mat = at(z)
                    if mat is None:
                        continue
                    val, vec = _herm_min(mat)
                    scale = max(abs(x) for row in mat for x in row)
                    samples.append((val, scale, z, vec))
        scale = max(s[1] for s in samples) if samples else mpmath.mpf(1)
        band = scale * mpmath.mpf(10) ** (-(dps - 15))
        lowest = min(samples, key=lambda s: s[0])
        margin = float(lowest[0] / scale)
        for val, _, z, vec in sorted(samples, key=lambda s: s[0])[:8]:
            if val < -band:
                zz = z * (1 + mpmath.mpf(10) ** -20) if abs(abs(z) - 1) < mpmath.mpf(10) ** -30 else z
                w = _matrix_witness(G, zz, vec, "point")
                if w:
                    return Answer(NO, f"min eig (G + G^H) = {mpmath.nstr(val, 8)} < 0 at z ~ {mpmath.nstr(z, 10)}", w,
                                  margin, "exact witness")
        if lowest[0] < -band:
            return Answer(UNCERTAIN, "negative samples without an exact witness", None, margin)
        if lowest[0] > band:
            return Answer(YES, f"min eig (G + G^H) >= {mpmath.nstr(lowest[0], 8)} on the sampled circles", None, margin,
                          f"sampled grid ({grid + 1} angles on |z| = 1, both halves); band {mpmath.nstr(band, 3)}")
        return Answer(UNCERTAIN, f"min eig {mpmath.nstr(lowest[0], 6)} within the band", None, margin, "borderline")


# ---------------------------------------------------------------------------------------------
# continuous positive realness
# ---------------------------------------------------------------------------------------------
def continuous_pr(Z: Any, *, dps: int | None = None) -> Answer:
    """Is the real-rational ``Z(s)`` positive real (analytic and ``Re Z >= 0`` in ``Re s > 0``,
    ``s -> infinity`` included)?

    At infinity ``Z ~ a s^k``: on the ray ``arg s = phi`` with ``|phi| < pi/2`` the real part is
    ``|a| R^k cos(k phi + arg a)``, which is negative somewhere unless ``k in {-1, 0, 1}``, and
    for ``k = +-1`` unless ``a > 0``: derived, then checked by the same exact witness search.

    >>> s = Rat.variable()
    >>> continuous_pr(s + 1 / s).verdict, continuous_pr(s**2 + 1).verdict, continuous_pr(-s).verdict
    ('yes', 'no', 'no')
    >>> continuous_pr(1 / (s + 1)).verdict, continuous_pr(1 / (s - 1)).verdict
    ('yes', 'no')
    """
    Z = _as_rat(Z)
    if not Z.num:
        return Answer(YES, "Z = 0", margin=0.0, uncertainty="exact")
    dps = dps or _dps_for([Z.num, Z.den])
    with mpmath.workdps(dps):
        k = Z.excess
        a = Z.num[-1] / Z.den[-1]
        if k >= 2 or (k == 1 and a < 0):
            w = _improper_witness(Z, "half")
            return Answer(NO if w else UNCERTAIN, f"Z ~ {a} s^{k} at infinity", w, uncertainty="exact witness" if w else "")
        if k <= -2 or (k == -1 and a < 0):
            # Z ~ a s^k: choose the ray where cos(k phi + arg a) < 0
            for phi in [mpmath.pi * j / 40 for j in range(-19, 20)]:
                for R in [mpmath.mpf(10) ** e for e in (3, 6, 12, 24, 48, 96, 200, 400)]:
                    w = _witness_near(Z, R * mpmath.expj(phi), "infinity", "half")
                    if w:
                        return Answer(NO, f"Z ~ {a} s^{k} at infinity", w, uncertainty="exact witness")
            return Answer(UNCERTAIN, f"Z ~ {a} s^{k} at infinity, no witness found")
        poles = []
        for factor, mult in squarefree(Z.den):
            for r in _roots(factor, dps):
                poles.append(_Pole(r, mult, "", factor))
        tol = mpmath.mpf(10) ** (-(min(dps, ROOT_DPS) // 2))
        axis = []
        for p in poles:
            exactly_axis = _on_imaginary_axis(p.factor, p.z, tol)
            if mpmath.re(p.z) > tol * max(1, abs(p.z)) and not exactly_axis:
                p.where = "outside"
                w = _pole_witness(Z, p, "half")
                return Answer(NO if w else UNCERTAIN, f"pole in Re s > 0 at s ~ {mpmath.nstr(p.z, 12)}", w,
                              uncertainty="exact witness" if w else "")
            if exactly_axis:
                p.where = "on"
                axis.append(p)
        for p in axis:
            c = _laurent_lead(Z, p)
            if p.mult > 1 or mpmath.re(c) <= 0 or abs(mpmath.im(c)) > tol * abs(c):
                w = _pole_witness(Z, p, "half")
                return Answer(NO if w else UNCERTAIN, f"imaginary-axis pole s ~ {mpmath.nstr(p.z, 12)}: residue "
                              f"{mpmath.nstr(c, 10)} (multiplicity {p.mult}) is not positive real", w)
        num_mp, den_mp = _mp(Z.num), _mp(Z.den)
        mags = [abs(p.z) for p in poles if p.z != 0] + [mpmath.mpf(1)]
        lo, hi = min(mags) * mpmath.mpf(10) ** -8, max(mags) * mpmath.mpf(10) ** 8
        omegas = [mpmath.mpf(0)] + [lo * (hi / lo) ** (mpmath.mpf(i) / 400) for i in range(401)]
        omegas += [abs(mpmath.im(p.z)) * (1 + f) for p in poles for f in (-1e-3, -1e-6, 1e-6, 1e-3, 0)]
        axis_w = [abs(mpmath.im(p.z)) for p in axis]
        samples = []
        for sigma in [mpmath.mpf(0), lo, mpmath.mpf(10) ** -3 * min(mags), min(mags), max(mags), hi]:
            for w_ in (omegas if sigma == 0 else omegas[::10]):
                if sigma == 0 and any(abs(w_ - aw) < tol for aw in axis_w):
                    continue
                for sgn in (1, -1):
                    s_ = mpmath.mpc(sigma, sgn * w_)
                    n_, d_ = mpmath.polyval(num_mp, s_), mpmath.polyval(den_mp, s_)
                    if d_ == 0:
                        continue
                    g = n_ / d_
                    err = mpmath.mpf(10) ** (-(dps - 8)) * (_abs_poly(Z.num, abs(s_)) + abs(g) * _abs_poly(Z.den, abs(s_))) / abs(d_)
                    samples.append((mpmath.re(g), err, abs(g), s_))
        scale = max(s[2] for s in samples)
        lowest = min(samples, key=lambda s: s[0])
        margin = float(lowest[0] / scale)
        for v, err, _, s_ in sorted(samples, key=lambda s: s[0])[:10]:
            if v < -err:
                target = s_ if mpmath.re(s_) > 0 else s_ + mpmath.mpf(10) ** -30 * (1 + abs(s_))
                w = _witness_near(Z, target, "point", "half")
                if w:
                    return Answer(NO, f"Re Z = {mpmath.nstr(v, 8)} < 0 at s ~ {mpmath.nstr(s_, 10)}", w, margin, "exact witness")
        band = max(s[1] for s in samples)
        if lowest[0] > band:
            return Answer(YES, f"Re Z >= {mpmath.nstr(lowest[0], 8)} on the sampled lines", None, margin,
                          f"sampled Re s in {{0, ...}}, log grid of |Im s| over [{mpmath.nstr(lo, 3)}, {mpmath.nstr(hi, 3)}]")
        if lowest[0] >= -band:
            return Answer(YES if lowest[0] >= 0 else UNCERTAIN, f"min Re Z = {mpmath.nstr(lowest[0], 6)} ~ 0", None, margin,
                          "touching zero within the evaluation band")
        return Answer(UNCERTAIN, "negative samples without an exact witness", None, margin)


def _on_imaginary_axis(factor: Poly, r: Any, tol: Any) -> bool:
    """Exact test that a root of ``factor`` may lie on ``Re s = 0``: it is a common root of
    ``factor(s)`` and ``factor(-s)`` (real coefficients: ``-conj r = -r`` conjugate-mirrored)."""
    mirrored = tuple(c if k % 2 == 0 else -c for k, c in enumerate(factor))
    g = pgcd(factor, mirrored)
    if pdeg(g) == 0:
        return False
    return abs(mpmath.re(r)) <= tol * max(1, abs(r)) and abs(mpmath.polyval(_mp(g), r)) <= tol * _abs_poly(g, abs(r))


# the HVE device model, the discretisations, the teleoperator's criterion and the operator's
# shortage of passivity live in .models; they are re-exported here (lazily: that module
# imports this one)
_MODELS = ("integrator", "hve_inverse", "discretize", "teleoperator_criterion", "shortage_of_passivity")


def __getattr__(name: str) -> Any:
    if name in _MODELS:
        from . import models
        return getattr(models, name)
    raise AttributeError(f"module 'definitions' has no attribute {name!r}")
