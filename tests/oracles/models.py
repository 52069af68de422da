r"""The papers' models, built here from the papers and the CLI's documentation (no code of the package under test).

* the HVE device model (Section 3.1): ``G^{-1}(z) = (b - z_a) + z^{-n} H(z) X_h/V_h`` with the
  forward ``T/(z-1)``, backward ``Tz/(z-1)`` and Tustin ``T(z+1)/(2(z-1))`` integrators;
* continuous designs made discrete as ``--discretize`` means it: ``forward s = (z-1)/T``,
  ``backward s = (z-1)/(Tz)``, ``tustin s = 2(z-1)/(T(z+1))``, ``zoh`` (step invariance) and
  ``matched`` (pole-zero) where the result is rational;
* the teleoperator paper's criterion (32) evaluated from its printed form (exact samples);
* an operator impedance's shortage of passivity ``z_a = max(0, -inf Re Z(jw))``.

>>> from fractions import Fraction
>>> z = Rat.variable()
>>> hve_inverse(Rat.const(2), "forward", T=Fraction(1, 10), b=1) == 1 + Fraction(2, 10) / (z - 1)
True
"""

from __future__ import annotations

import math
from fractions import Fraction
from typing import Any

import mpmath

from .definitions import (NO, ROOT_DPS, UNCERTAIN, YES, Answer, _dps_for, _ExactRe, _fnum, _golden, _mp, _poles, _roots,
                         unit_point)
from .exactpoly import Poly, Rat, pdeg, pderiv, peval_complex, pmul, ptrim, squarefree

__all__ = ["integrator", "hve_inverse", "discretize", "teleoperator_criterion", "shortage_of_passivity"]


# ---------------------------------------------------------------------------------------------
# the HVE device model and continuous designs made discrete
# ---------------------------------------------------------------------------------------------
def integrator(approximation: str, T: Any) -> Rat:
    """``X_h/V_h`` of the HVE paper's three approximations of ``1/s`` (Section 3.1.1):
    forward ``T/(z-1)``, backward ``Tz/(z-1)``, Tustin ``T(z+1)/(2(z-1))``.

    >>> integrator("tustin", 2).num, integrator("tustin", 2).den
    ((Fraction(1, 1), Fraction(1, 1)), (Fraction(-1, 1), Fraction(1, 1)))
    """
    z, T = Rat.variable(), Fraction(T)
    forms = {"forward": T / (z - 1), "backward": T * z / (z - 1), "tustin": T * (z + 1) / (2 * (z - 1))}
    if approximation not in forms:
        raise ValueError(f"unknown approximation {approximation!r}")
    return forms[approximation]


def hve_inverse(H: Rat, approximation: str, *, T: Any, b: Any, z_a: Any = 0, delay: int = 0) -> Rat:
    """``G^{-1}(z) = (b - z_a) + z^{-n} H(z) X_h/V_h`` (HVE eqs. before (17), (21)-(22), (26)-(27)).

    >>> z = Rat.variable()
    >>> hve_inverse(Rat.const(2), "forward", T=Fraction(1, 10), b=1) == 1 + Fraction(2, 10) / (z - 1)
    True
    """
    z = Rat.variable()
    return Fraction(b) - Fraction(z_a) + H * integrator(approximation, T) / z ** int(delay)


def discretize(C: Rat, method: str, T: Any) -> Rat | None:
    """``C(z)`` of a continuous ``C(s)`` as the toolkit's ``--discretize`` means it (read from its
    documentation, coded here independently); ``None`` when the result is not rational
    (``e^{pT}`` with ``p != 0``: ZOH/matched of a pole or zero off the origin).

    * ``forward`` ``s = (z-1)/T``, ``backward`` ``s = (z-1)/(Tz)``, ``tustin`` ``s = 2(z-1)/(T(z+1))``;
    * ``zoh`` ``C(z) = (1 - z^{-1}) Z{C(s)/s}`` (proper ``C``; rational when every pole is at 0);
    * ``matched``: poles and zeros ``q -> e^{qT}``, zeros at infinity to ``z = -1``, a pole excess
      to ``z = 0``, gain matched on the lowest-order term at ``s = 0`` (rational for ``L s^r``).

    >>> s = Rat.variable()
    >>> discretize(2 + s, "backward", Fraction(1, 10)) == 2 + 10 * (Rat.variable() - 1) / Rat.variable()
    True
    >>> z = Rat.variable()
    >>> discretize(3 / s, "zoh", 2) == 6 / (z - 1)
    True
    """
    z, T = Rat.variable(), Fraction(T)
    if method == "forward":
        return C.compose((z - 1) / T)
    if method == "backward":
        return C.compose((z - 1) / (T * z))
    if method == "tustin":
        return C.compose(2 * (z - 1) / (T * (z + 1)))
    if method == "zoh":
        return _zoh(C, T)
    if method == "matched":
        return _matched(C, T)
    raise ValueError(f"unknown method {method!r}")


def _rat_deriv(R: Rat) -> Rat:
    from .exactpoly import psub
    return Rat(psub(pmul(pderiv(R.num), R.den), pmul(R.num, pderiv(R.den))), pmul(R.den, R.den))


def _zoh(C: Rat, T: Fraction) -> Rat | None:
    if C.excess > 0:
        raise ValueError("ZOH needs a proper C(s)")
    if any(c != 0 for c in C.den[:-1]):
        return None                        # a pole off the origin: e^{pT} is transcendental
    z = Rat.variable()
    k = pdeg(C.den)                        # C = num/s^k: C/s = sum_i num_i s^(i-k-1)
    total = Rat.const(0)
    geometric = z / (z - 1)                # Z{1} = z/(z-1); Z{j^m} = (-z d/dz)^m z/(z-1)
    power_series = [geometric]
    for m in range(1, k + 1):
        power_series.append(-z * _rat_deriv(power_series[-1]))
    for i, c in enumerate(C.num):
        order = k + 1 - i                  # term c s^-(order): step response c t^(order-1)/(order-1)!
        if c == 0 or order < 1:
            continue
        m = order - 1
        total = total + c * T**m / math.factorial(m) * power_series[m]
    return (z - 1) / z * total


def _matched(C: Rat, T: Fraction) -> Rat | None:
    num, den = C.num, C.den
    # rational only when C = L s^r (every finite pole and zero at the origin)
    nz = [i for i, c in enumerate(num) if c]
    dz = [i for i, c in enumerate(den) if c]
    if len(nz) != 1 or len(dz) != 1:
        return None
    r = nz[0] - dz[0]
    L = num[nz[0]] / den[dz[0]]
    z = Rat.variable()
    excess = pdeg(den) - pdeg(num)         # zeros at infinity (> 0) or a pole excess (< 0)
    zrest = (z + 1) ** excess if excess > 0 else Rat.const(1)
    prest = z ** (-excess) if excess < 0 else Rat.const(1)
    shape = zrest.at(Fraction(1)) / prest.at(Fraction(1))
    gain = L / (T**r * shape)
    return gain * (z - 1) ** r * zrest / prest


# ---------------------------------------------------------------------------------------------
# the teleoperator's criterion (32) and an operator's shortage of passivity
# ---------------------------------------------------------------------------------------------
def teleoperator_criterion(C: Rat, *, T: Any, alpha: Any, b_m: Any, b_s: Any, grid: int = 1024) -> Answer:
    """The teleoperator paper's (32), evaluated from its printed form:
    ``b_m >= alpha (alpha + 1) L(w)`` and ``b_s >= (alpha + 1) L(w)`` for every ``0 < w <= pi/T``,
    ``L = T/(2(1 - cos wT)) Re{(1 - e^{-jwT}) C(e^{jwT})}``, for a controller ``C`` without poles
    outside the unit circle (the criterion presumes it stable). ``no`` gives an exact witness:
    a rational unit point ``u`` and ``L(u)`` computed exactly.

    >>> z = Rat.variable()
    >>> T = Fraction(1, 1000)
    >>> pd = 2 + Fraction(1, 100) * (z - 1) / (T * z)          # sup L = KT/2 + B = 0.011
    >>> teleoperator_criterion(pd, T=T, alpha=1, b_m=Fraction(23, 1000), b_s=Fraction(23, 1000)).verdict
    'yes'
    >>> teleoperator_criterion(pd, T=T, alpha=1, b_m=Fraction(23, 1000), b_s=Fraction(21, 1000)).verdict
    'no'
    """
    T, alpha, b_m, b_s = (Fraction(v) for v in (T, alpha, b_m, b_s))
    dps = _dps_for([C.num, C.den, (T, alpha, b_m, b_s)])
    with mpmath.workdps(dps):
        poles = _poles(C.den, dps) if pdeg(C.den) > 0 else []
        for p in poles:
            if p.where == "outside":
                return Answer(NO, f"C(z) has a pole outside the unit circle at {mpmath.nstr(p.z, 10)}",
                              {"kind": "controller-pole", "pole": [mpmath.nstr(mpmath.re(p.z), 20), mpmath.nstr(mpmath.im(p.z), 20)]},
                              uncertainty="pole location at high precision")
        weights = {"master": alpha * (alpha + 1), "slave": alpha + 1}
        damping = {"master": b_m, "slave": b_s}
        Tm = mpmath.mpf(T.numerator) / T.denominator
        z = Rat.variable()
        # on the circle (1 - e^{-jwT}) C = (1 - 1/u) C(u) = F(u) with F = (z - 1) C/z: exact samples
        exact = _ExactRe((z - 1) * C / z)

        def L(theta):
            x, y = unit_point(theta)
            got = exact.at(x, y)
            if got is None or x == 1:
                return None
            return Tm * got[0] / (2 * (1 - mpmath.mpf(x.numerator) / x.denominator))
        thetas = [mpmath.pi * k / grid for k in range(1, grid + 1)] + [mpmath.mpf(10) ** -k for k in (3, 5, 8, 12, 20)]
        circle = [abs(mpmath.arg(p.z)) for p in poles if p.where == "on"]
        for th in circle:
            thetas += [th + s * mpmath.mpf(10) ** -k for k in (2, 4, 7, 12) for s in (-1, 1)]
        for p in poles:
            if p.where == "inside" and 1 - abs(p.z) < 0.25:
                gap = 1 - abs(p.z)
                thetas += [abs(mpmath.arg(p.z)) + s * gap * f for f in (0, 0.5, 1, 2) for s in (-1, 1)]
        thetas = [t for t in thetas if 0 < t <= mpmath.pi and all(abs(t - c) > mpmath.mpf(10) ** -30 for c in circle)]
        values = [(L(t), t) for t in thetas]
        values = [(v, t) for v, t in values if v is not None]
        top = max(values, key=lambda vt: vt[0])
        refined = _golden(lambda t: -L(t), max(top[1] - mpmath.pi / grid, mpmath.mpf(10) ** -30), min(top[1] + mpmath.pi / grid, mpmath.pi), circle)
        if refined is not None and L(refined) is not None and L(refined) > top[0]:
            top = (L(refined), refined)
        sup_L, arg = top
        scale = max(abs(v) for v, _ in values) + max(abs(mpmath.mpf(b_m.numerator) / b_m.denominator), mpmath.mpf(10) ** -300)
        band = scale * mpmath.mpf(10) ** (-(dps - 20))
        out_margin = []
        for robot in ("master", "slave"):
            wgt = mpmath.mpf(weights[robot].numerator) / weights[robot].denominator
            bnd = wgt * sup_L
            bb = mpmath.mpf(damping[robot].numerator) / damping[robot].denominator
            out_margin.append((robot, bb - bnd, bnd))
        worst = min(out_margin, key=lambda t: t[1])
        margin = float(worst[1] / scale)
        if worst[1] < -band:
            robot = worst[0]
            for digits in (40, 25, 60):
                ux, uy = unit_point(arg, digits)
                if ux == 1:
                    continue
                nn, dd = peval_complex(C.num, ux, uy), peval_complex(C.den, ux, uy)
                if dd == (0, 0):
                    continue
                from .exactpoly import complex_div
                cval = complex_div(nn, dd)
                one_minus_conj = (1 - ux, uy)            # 1 - conj(u) = 1 - 1/u on the circle
                re_prod = one_minus_conj[0] * cval[0] - one_minus_conj[1] * cval[1]
                Lx = T / (2 * (1 - ux)) * re_prod
                if damping[robot] < weights[robot] * Lx:
                    return Answer(NO, f"{robot}: b = {damping[robot]} < bound {mpmath.nstr(worst[2], 12)} at wT ~ {mpmath.nstr(arg, 12)}",
                                  {"kind": "frequency", "robot": robot, "u": [str(ux), str(uy)], "bound": str(weights[robot] * Lx),
                                   "bound_float": _fnum(weights[robot] * Lx)}, margin, "exact witness")
            return Answer(UNCERTAIN, "violation without exact witness", None, margin)
        if worst[1] > band:
            return Answer(YES, f"sup L = {mpmath.nstr(sup_L, 12)} (wT ~ {mpmath.nstr(arg, 8)}); both dampings exceed their bounds",
                          None, margin, f"sampled {len(values)} frequencies, refined; band {mpmath.nstr(band, 3)}")
        return Answer(UNCERTAIN, "damping equals its bound within the band", None, margin, "borderline")


def shortage_of_passivity(Z: Rat, *, grid: int = 600) -> tuple[Any, str]:
    """``z_a = max(0, -inf_w Re Z(jw))`` of an operator impedance (HVE Definition 4), numeric
    (mpmath): a logarithmic grid of ``w`` over the scales of the poles and zeros, ``w = 0`` and
    ``w -> infinity`` limits, the critical points (roots of the derivative of ``Re Z(jw)`` as a
    rational function of ``u = w^2``, exact polynomials) refined. Returns ``(z_a, note)``.

    >>> s = Rat.variable()
    >>> shortage_of_passivity(-Fraction(1, 100) + 1 / s)[0]
    mpf('0.01')
    """
    # Re Z(jw) = E(u)/F(u) with u = w^2: Re(N(jw) conj D(jw)) and |D(jw)|^2 are polynomials in u
    def split(p: Poly) -> tuple[Poly, Poly]:
        """p(jw) = A(u) + j w B(u)."""
        A, B = [], []
        for k, c in enumerate(p):
            sign = -1 if (k // 2) % 2 else 1
            (A if k % 2 == 0 else B).append((k // 2, sign * c))
        mk = lambda terms: ptrim([sum(c for kk, c in terms if kk == i) for i in range(max([kk for kk, _ in terms], default=-1) + 1)])  # noqa: E731
        return mk(A), mk(B)
    from .exactpoly import padd, psub
    nA, nB = split(Z.num)
    dA, dB = split(Z.den)
    u_poly = (Fraction(0), Fraction(1))
    E = padd(pmul(nA, dA), pmul(u_poly, pmul(nB, dB)))
    F = padd(pmul(dA, dA), pmul(u_poly, pmul(dB, dB)))
    dps = _dps_for([Z.num, Z.den])
    with mpmath.workdps(dps):
        E_mp, F_mp = _mp(E), _mp(F)
        crit = psub(pmul(pderiv(E), F), pmul(E, pderiv(F)))
        cands = []
        for factor, _ in squarefree(crit) if pdeg(crit) > 0 else []:
            for r in _roots(factor, dps):
                if abs(mpmath.im(r)) < mpmath.mpf(10) ** (-(min(dps, ROOT_DPS) // 3)) * (1 + abs(r)) and mpmath.re(r) > 0:
                    cands.append(mpmath.re(r))
        mags = [abs(r) for f, _ in squarefree(F) for r in _roots(f, dps) if r != 0] + [mpmath.mpf(1)]
        lo, hi = min(mags) * mpmath.mpf(10) ** -10, max(mags) * mpmath.mpf(10) ** 10
        cands += [lo * (hi / lo) ** (mpmath.mpf(i) / grid) for i in range(grid + 1)]
        vals = []
        for u in cands:
            f = mpmath.polyval(F_mp, u)
            if f != 0:
                vals.append(mpmath.polyval(E_mp, u) / f)
        # limits u -> 0+ and u -> infinity
        for limit in (_limit_at_zero(E, F), _limit_at_inf(E, F)):
            if limit is not None:
                vals.append(mpmath.mpf(limit.numerator) / limit.denominator)
        low = min(vals)
        return (max(mpmath.mpf(0), -low), f"{len(vals)} points incl. {len(cands) - grid - 1} critical points, limits")


def _limit_at_zero(E: Poly, F: Poly) -> Fraction | None:
    ke = next((i for i, c in enumerate(E) if c), None)
    kf = next((i for i, c in enumerate(F) if c), None)
    if ke is None:
        return Fraction(0)
    if kf is None or ke < kf:
        return None
    return E[kf] / F[kf] if ke == kf else Fraction(0)


def _limit_at_inf(E: Poly, F: Poly) -> Fraction | None:
    if not E:
        return Fraction(0)
    if pdeg(E) > pdeg(F):
        return None
    return E[-1] / F[-1] if pdeg(E) == pdeg(F) else Fraction(0)

