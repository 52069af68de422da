r"""Oracles for discrete-time positive realness (HVE paper, Definition 2, Section 3).

Scalar ``F(z)`` (:func:`discrete_positive_real`) is positive real when

1. it is proper and its poles lie in ``|z| <= 1``;
2. its poles on ``|z| = 1`` are simple and ``q = Res(F, z0)/z0`` is real and ``>= 0`` (at
   ``z0 = 1`` that is the residue itself);
3. ``Re F(e^{j theta}) >= 0`` wherever defined.

Near a simple unit-circle pole ``z0 = e^{j theta0}``, ``F = (q z0)/(z - z0) + F_reg`` and
``z - z0 = z0 (e^{j phi} - 1)``, so the polar part is ``q/(e^{j phi} - 1) = -q/2 - j (q/2)
cot(phi/2)``: its real part is the constant ``-Re q/2`` plus ``Im q cot(phi/2)/2``. With ``q``
real, ``Re F`` extends continuously through the pole (limit ``Re F_reg(z0) - q/2``), so the
oracle evaluates it there as the mean of the two sides at ``phi = +-1e-15`` (error
``O(1e-30)``; 60 digits absorb the ``1e15`` growth of ``F``). With ``Im q != 0`` it is
unbounded below, which condition 2 already rejects.

Method: exact cancellation and square-free factorisation (SymPy), poles by mpmath ``polyroots``
at 60+ digits (a root is on the circle when ``||z| - 1| <= 1e-40``), residues ``num/den'`` at 60
digits. ``F(z) + F(1/z) = 0`` identically (lossless: ``Re F = 0`` on the circle) is recognised
exactly. Otherwise ``Re F`` is screened on ``[0, pi]`` (``F`` real-rational: symmetric) with 4097
points plus points clustered at the angles of poles near the circle, in double precision except
within ``1e-3`` of a unit-circle pole (mpmath there), then the six lowest local minima (and the
pole angles) are refined by a golden-section search at 60 digits down to a bracket of ``1e-22``.
Within ``1e-2`` of a unit-circle pole the precision is raised by ``2 log10(1/distance)`` digits.

Uncertainty band: the minimum ``m`` of ``Re F`` is decisive when ``|m| > band`` with
``band = max(1e-25 * S, 1e-40 * A)``, ``S = max |Re F|`` and ``A = max |F|`` over the screened
points (away from unit-circle poles); residues need ``|Im q| <= 1e-40 |q|`` (real) or ``> 1e-30
|q|`` (not real).

The models (:func:`single_user_inverse`, :func:`multi_user_positive_real`) are written from the
HVE paper: ``G^{-1}(z) = (b - z_a) + z^{-n} H(z) X(z)/V(z)`` with ``X/V = T/(z-1)`` (forward),
``Tz/(z-1)`` (backward), ``T(z+1)/(2(z-1))`` (Tustin); for m users ``G^{-1} = diag(b - z_a) +
D(z) H(z) I(z)``, ``D = diag(z^{-n_i})``, ``H = Kmat + Bmat (z-1)/(Tz)``.

>>> import sympy as sp
>>> T = sp.Rational(1, 1000)
>>> wall = lambda b: single_user_positive_real(b=b, T=T, H=2 + (Z - 1)/(10*T*Z), approximation="forward")
>>> [wall(sp.Rational(b, 1000)).verdict for b in (102, 100, 101)]   # Colgate: b >= KT/2 + B = 0.101
['yes', 'no', 'uncertain']
"""

from __future__ import annotations

import itertools
import math
from fractions import Fraction
from typing import Any, Mapping, Sequence

import mpmath
import numpy as np
import sympy as sp

from .minimise import golden, local_minima
from .polys import RationalFunction, mpf_of, to_fraction
from .result import NO, UNCERTAIN, YES, OracleFailure, OracleResult, combine

__all__ = [
    "Z",
    "integrator",
    "single_user_inverse",
    "discrete_positive_real",
    "single_user_positive_real",
    "multi_user_inverse",
    "multi_user_positive_real",
    "laplacian",
    "teleoperator_passivity",
]

#: The oracle's own ``z`` (a plain SymPy symbol).
Z = sp.Symbol("z")

DPS = 60
ON_CIRCLE = 1e-40
PHI = 1e-15


def integrator(approximation: str, T: Any, z: sp.Symbol = Z) -> sp.Expr:
    """``X_h/V_h`` of the HVE paper, Section 3.1.1 (forward, backward, Tustin)."""
    T = sp.nsimplify(T) if not isinstance(T, sp.Basic) else T
    if approximation == "forward":
        return T / (z - 1)
    if approximation == "backward":
        return T * z / (z - 1)
    if approximation == "tustin":
        return T * (z + 1) / (2 * (z - 1))
    raise ValueError(f"unknown approximation {approximation!r}")


def single_user_inverse(*, b: Any, T: Any, H: Any, approximation: str = "forward", delay: int = 0,
                        z_a: Any = 0, z: sp.Symbol = Z) -> sp.Expr:
    """``G^{-1}(z) = (b - z_a) + z^{-n} H(z) X/V`` (HVE paper, forms before (17), eqs. (21)-(22))."""
    b, T, z_a = (sp.Rational(to_fraction(v).numerator, to_fraction(v).denominator) for v in (b, T, z_a))
    return (b - z_a) + z ** (-int(delay)) * sp.sympify(H) * integrator(approximation, T, z)


def single_user_positive_real(*, b: Any, T: Any, H: Any, approximation: str = "forward", delay: int = 0,
                              z_a: Any = 0, z: sp.Symbol = Z, **options: Any) -> OracleResult:
    """Positive realness of the single-user scene's ``G^{-1}(z)``."""
    G = single_user_inverse(b=b, T=T, H=H, approximation=approximation, delay=delay, z_a=z_a, z=z)
    return discrete_positive_real(G, z, **options)


# ---------------------------------------------------------------------------------------------
# scalar F(z)
# ---------------------------------------------------------------------------------------------


def _angle(z0: Any) -> Any:
    return abs(mpmath.arg(z0))


def discrete_positive_real(F: Any, z: sp.Symbol = Z, *, n_grid: int = 4096, always_hermitian: bool = False) -> OracleResult:
    """Definition 2 (HVE paper) for a scalar real-rational ``F(z)``; see the module docstring.

    With ``always_hermitian`` the minimum of ``Re F`` is measured even when a pole condition
    fails, as long as ``Re F`` is bounded on the circle (unit-circle poles simple with real
    ``Res/z0``); it is then in ``details['Re F >= 0']``.
    """
    f = F if isinstance(F, RationalFunction) else RationalFunction.from_expr(F, z)
    with mpmath.workdps(DPS):
        poles = _pole_condition(f)
        if poles.verdict == NO and not always_hermitian:
            return combine([("poles", poles)])
        residues, angles = _residue_condition(f)
        parts = [("poles", poles), ("residues", residues)]
        if NO in (poles.verdict, residues.verdict) and not always_hermitian:
            return combine(parts)
        if _bounded_on_circle(f) and f.relative_degree >= 0:
            if sp.cancel(f.expr(Z) + f.expr(Z).subs(Z, 1 / Z)) == 0:
                herm = OracleResult(YES, "F(z) + F(1/z) = 0 identically (lossless): Re F = 0 on the circle",
                                    margin=0.0, band=0.0)
            else:
                herm = _hermitian_condition(f, angles, n_grid)
            parts.append(("Re F >= 0", herm))
    return combine(parts)


def _bounded_on_circle(f: RationalFunction) -> bool:
    """Re F bounded near every unit-circle pole: simple, with real Res/z0."""
    for r, mult in f.poles(DPS):
        if abs(1 - abs(r)) <= ON_CIRCLE:
            if mult > 1:
                return False
            q = f.residue(r) / r
            if abs(q.imag) > 1e-40 * abs(q):
                return False
    return True


def _pole_condition(f: RationalFunction) -> OracleResult:
    if f.relative_degree < 0:
        return OracleResult(NO, "F is improper: a pole at z = oo, outside the unit disk", margin=-math.inf,
                            where={"pole": "oo"})
    worst = None
    for r, mult in f.poles(DPS):
        gap = 1 - abs(r)
        if gap < -ON_CIRCLE:
            return OracleResult(NO, f"pole z ~ {complex(r):.12g} outside the unit circle (|z| - 1 = {float(-gap):.3g})",
                                margin=float(gap), band=ON_CIRCLE, where={"pole": complex(r)})
        if abs(gap) <= ON_CIRCLE and mult > 1:
            return OracleResult(NO, f"pole z ~ {complex(r):.12g} on the unit circle has multiplicity {mult}",
                                margin=-float(mult - 1), where={"pole": complex(r), "multiplicity": mult})
        if worst is None or gap < worst[0]:
            worst = (gap, r)
    if worst is None:
        return OracleResult(YES, "no finite poles")
    return OracleResult(YES, "poles in |z| <= 1, those on the circle simple", margin=float(worst[0]), band=ON_CIRCLE,
                        where={"pole": complex(worst[1])})


def _residue_condition(f: RationalFunction) -> tuple[OracleResult, list]:
    """Res/z0 real and >= 0 at every simple unit-circle pole; also returns the angles of all of
    them (where Re F is evaluated as the mean of both sides)."""
    angles, checked, failures = [], [], []
    for r, mult in f.poles(DPS):
        if abs(1 - abs(r)) > ON_CIRCLE or mult > 1:
            continue
        angles.append(_angle(r))
        q = f.residue(r) / r
        size = abs(q)
        where = {"pole": complex(r), "Res/z0": complex(q)}
        if abs(q.imag) > 1e-30 * size:
            failures.append(OracleResult(NO, f"Res/z0 = {complex(q):.6g} at z0 ~ {complex(r):.6g} is not real",
                                         margin=-float(abs(q.imag)), band=float(1e-30 * size), where=where))
        elif abs(q.imag) > 1e-40 * size:
            failures.append(OracleResult(UNCERTAIN, f"Res/z0 at z0 ~ {complex(r):.6g} is nearly real", where=where))
        elif q.real < 0:
            failures.append(OracleResult(NO, f"Res/z0 = {float(q.real):.6g} < 0 at z0 ~ {complex(r):.6g}",
                                         margin=float(q.real), band=float(1e-40 * size), where=where))
        else:
            checked.append(float(q.real))
    failures.sort(key=lambda o: o.verdict != NO)
    if failures:
        return failures[0], angles
    if not checked:
        return OracleResult(YES, "no poles on the unit circle"), angles
    return OracleResult(YES, "unit-circle poles simple with Res/z0 > 0", margin=min(checked), where={}), angles


def _safe_value(f: RationalFunction, theta: Any, angles: Sequence[Any]) -> Any:
    """``Re F(e^{j theta})``; at (or within 1e-15 of) a unit-circle pole, the mean of both sides.
    Within ``1e-2`` of a unit-circle pole the precision is raised by ``2 log10(1/distance)``
    (the distance ``z - z0`` and the polar part each cost that many digits)."""
    for a in angles:
        if abs(theta - a) < PHI:
            with mpmath.workdps(mpmath.mp.dps + 35):
                left = f.mp(mpmath.expj(a - PHI)).real
                right = f.mp(mpmath.expj(a + PHI)).real
                return (left + right) / 2 * 1
    gap = min([abs(theta - a) for a in angles] + [mpmath.mpf(1)])
    extra = 2 * int(max(0, -math.log10(float(gap)))) + 5 if gap < 1e-2 else 0
    with mpmath.workdps(mpmath.mp.dps + extra):
        value = f.mp(mpmath.expj(theta)).real
    return value * 1


def _hermitian_condition(f: RationalFunction, angles: list, n_grid: int) -> OracleResult:
    pi = float(mpmath.pi)
    points = set(np.linspace(0.0, pi, n_grid + 1).tolist())
    for a in angles:
        a = float(a)
        points.update(min(pi, max(0.0, a + d)) for d in (0.0, -1e-3, 1e-3, -1e-6, 1e-6))
    for r, _ in f.poles(DPS):
        rho = float(abs(r))
        if 0.5 < rho and abs(1 - rho) < 1e-2:
            a, w = float(_angle(r)), abs(1 - rho)
            points.update(min(pi, max(0.0, a + k * w)) for k in (-8, -4, -2, -1, -0.5, -0.25, 0, 0.25, 0.5, 1, 2, 4, 8))
    theta = np.array(sorted(points))
    with np.errstate(all="ignore"):
        zz = np.exp(1j * theta)
        full = f.np(zz)
        values = full.real
    near = np.zeros(len(theta), dtype=bool)
    for a in angles:
        near |= np.abs(theta - float(a)) < 1e-3
    with mpmath.workdps(30):
        for i in np.nonzero(near | ~np.isfinite(values))[0]:
            v = f.mp(mpmath.expj(theta[i])) if all(abs(theta[i] - float(a)) >= PHI for a in angles) else None
            values[i] = float(_safe_value(f, mpmath.mpf(theta[i]), angles))
            full[i] = complex(v) if v is not None else values[i]
    finite = np.isfinite(values)
    S = float(np.max(np.abs(values[finite]))) if finite.any() else 0.0
    far = finite & ~near
    A = float(np.max(np.abs(full[far]))) if far.any() else S
    band = max(1e-25 * S, 1e-40 * A)
    candidates = set(local_minima(values, keep=6))
    candidates.update(int(np.argmin(np.abs(theta - float(a)))) for a in angles)
    best = None
    for i in sorted(candidates):
        lo = mpmath.mpf(theta[max(i - 1, 0)])
        hi = mpmath.mpf(theta[min(i + 1, len(theta) - 1)])
        x, fx = golden(lambda t: _safe_value(f, t, angles), lo, hi, mpmath.mpf(10) ** -22)
        if best is None or fx < best[1]:
            best = (x, fx)
    x, m = best
    where = {"theta": float(x), "c": float(mpmath.cos(x))}
    if m < -band:
        return OracleResult(NO, f"Re F = {float(m):.6g} < 0 at theta = {float(x):.12g}", margin=float(m), band=band, where=where)
    if m > band:
        return OracleResult(YES, f"min Re F = {float(m):.6g} at theta = {float(x):.12g}", margin=float(m), band=band, where=where)
    return OracleResult(UNCERTAIN, f"min Re F = {float(m):.3g} is inside the band {band:.3g}", margin=float(m), band=band, where=where)


# ---------------------------------------------------------------------------------------------
# m users
# ---------------------------------------------------------------------------------------------


def laplacian(m: int, ground: Sequence[Any], weights: Mapping[tuple[int, int], Any]) -> list[list[Fraction]]:
    """``diag(ground) + L_w`` with ``L_ii = sum_k w_ik`` and ``L_ij = -w_ij`` (0-based edges)."""
    out = [[Fraction(0)] * m for _ in range(m)]
    for i in range(m):
        out[i][i] = to_fraction(ground[i])
    for (i, j), w in weights.items():
        w = to_fraction(w)
        out[i][j] -= w
        out[j][i] -= w
        out[i][i] += w
        out[j][j] += w
    return out


def multi_user_inverse(*, b, T, K0, B0, K, B, delays, z_a, approximation="forward", z: sp.Symbol = Z) -> sp.Matrix:
    """``G^{-1}(z) = diag(b - z_a) + D(z) H(z) I(z)`` (HVE paper, Section 3.2) as a SymPy matrix."""
    m = len(b)
    Km, Bm = laplacian(m, K0, K), laplacian(m, B0, B)
    Tq = sp.Rational(to_fraction(T).numerator, to_fraction(T).denominator)
    I = integrator(approximation, Tq, z)
    R = lambda q: sp.Rational(q.numerator, q.denominator)  # noqa: E731
    out = sp.zeros(m, m)
    for i in range(m):
        for j in range(m):
            out[i, j] = z ** (-int(delays[i])) * (R(Km[i][j]) + R(Bm[i][j]) * (z - 1) / (Tq * z)) * I
            if i == j:
                out[i, j] += R(to_fraction(b[i]) - to_fraction(z_a[i]))
    return out


class _MultiUser:
    """Numeric evaluation of the m-user ``G^{-1}(e^{j theta})`` and its Hermitian part."""

    def __init__(self, b, T, K0, B0, K, B, delays, z_a, approximation):
        self.m = m = len(b)
        self.d = [to_fraction(b[i]) - to_fraction(z_a[i]) for i in range(m)]
        self.T = to_fraction(T)
        self.K = laplacian(m, K0, K)
        self.B = laplacian(m, B0, B)
        self.n = [int(n) for n in delays]
        self.approximation = approximation

    def _integrator(self, zz, T):
        if self.approximation == "forward":
            return T / (zz - 1)
        if self.approximation == "backward":
            return T * zz / (zz - 1)
        return T * (zz + 1) / (2 * (zz - 1))

    def np_hermitian(self, theta: np.ndarray) -> np.ndarray:
        zz = np.exp(1j * theta)
        T = float(self.T)
        I = self._integrator(zz, T)
        k = (zz - 1) / (T * zz)
        m = self.m
        G = np.zeros((len(theta), m, m), dtype=complex)
        for i in range(m):
            delay = zz ** (-self.n[i])
            for j in range(m):
                G[:, i, j] = delay * (float(self.K[i][j]) + float(self.B[i][j]) * k) * I
            G[:, i, i] += float(self.d[i])
        return G + np.conj(np.transpose(G, (0, 2, 1)))

    def _mp_params(self):
        dps = mpmath.mp.dps
        cache = self.__dict__.setdefault("_cache", {})
        if dps not in cache:
            cache[dps] = (mpf_of(self.T), [[mpf_of(v) for v in row] for row in self.K],
                          [[mpf_of(v) for v in row] for row in self.B], [mpf_of(v) for v in self.d])
        return cache[dps]

    def mp_G(self, zz: Any) -> mpmath.matrix:
        T, Km, Bm, d = self._mp_params()
        I = self._integrator(zz, T)
        k = (zz - 1) / (T * zz)
        G = mpmath.matrix(self.m, self.m)
        for i in range(self.m):
            delay = zz ** (-self.n[i])
            for j in range(self.m):
                G[i, j] = delay * (Km[i][j] + Bm[i][j] * k) * I
            G[i, i] += d[i]
        return G

    def mp_hermitian(self, theta: Any) -> mpmath.matrix:
        """``M = G + G^H``; at theta ~ 0 (the pole z = 1) the mean of both sides at +-1e-15.

        ``z - 1`` loses ``log10(1/theta)`` digits and the polar part ``~ 1/theta`` as many again:
        the working precision is raised by ``2 log10(1/theta)`` so that ``M`` keeps the digits
        asked for."""
        if abs(theta) < PHI:
            return (self.mp_hermitian(mpmath.mpf(PHI)) + self.mp_hermitian(-mpmath.mpf(PHI))) / 2
        extra = 2 * int(max(0, -math.log10(abs(float(theta))))) + 5 if abs(theta) < 1e-2 else 0
        with mpmath.workdps(mpmath.mp.dps + extra):
            G = self.mp_G(mpmath.expj(theta))
            M = G + G.H
        return M * 1

    def mid_min_eig(self, theta: Any) -> float:
        """M formed at 30 digits below theta = 1e-2 (the cancellation near z = 1 happens there),
        in double above; eigenvalues in double."""
        if theta >= 1e-2:
            return float(np.linalg.eigvalsh(self.np_hermitian(np.array([float(theta)])))[0, 0])
        with mpmath.workdps(30):
            M = self.mp_hermitian(mpmath.mpf(theta))
            A = np.array([[complex(M[i, j]) for j in range(self.m)] for i in range(self.m)])
        return float(np.linalg.eigvalsh((A + A.conj().T) / 2)[0])

    def mp_min_eig(self, theta: Any) -> tuple[Any, Any]:
        with mpmath.workdps(50):
            M = self.mp_hermitian(mpmath.mpf(theta))
            M = (M + M.H) / 2
            ev = mpmath.eighe(M, eigvals_only=True)
            return min(ev, key=lambda e: e.real).real, mpmath.mnorm(M, 1)


def _psd_exact(M: list[list[Fraction]]) -> tuple[bool, Any]:
    """Exact PSD test of a rational symmetric matrix: every principal minor ``>= 0``."""
    m = len(M)
    S = sp.Matrix(m, m, lambda i, j: sp.Rational(M[i][j].numerator, M[i][j].denominator))
    for k in range(1, m + 1):
        for rows in itertools.combinations(range(m), k):
            minor = S.extract(list(rows), list(rows)).det(method="bareiss")
            if minor < 0:
                return False, (rows, minor)
    return True, None


def multi_user_positive_real(*, b, T, K0, B0=None, K=None, B=None, delays=None, z_a=None,
                             approximation: str = "forward", n_grid: int = 2048) -> OracleResult:
    """Positive realness of the m-user ``G^{-1}(z)`` (HVE paper, Section 3.2).

    Poles: every entry is ``z^{-n_i}`` times a rational function with poles at ``z = 0`` and a
    simple pole at ``z = 1`` only (from ``I(z)``; ``H`` has its pole at ``0``), so condition 1 holds
    and condition 3 is the residue matrix at ``z = 1``: ``D(1) H(1) Res I = T Kmat``, real
    symmetric, decided exactly (all principal minors) and cross-checked against
    ``(z - 1) G(z)`` at ``z = 1 + 1e-30``. Hermitian part: ``lambda_min(G + G^H)`` on
    ``[0, pi]`` (``M(-theta)`` is the conjugate of ``M(theta)``), screened on ``n_grid + 1``
    points in double precision for ``theta >= 1e-2`` and with ``M`` formed at 30 digits below,
    the six lowest local minima refined by golden section (``M`` at 30 digits, eigenvalues in
    double) to ``1e-10``, then the minimum eigenvalue recomputed at 50 digits there.

    Band: ``yes`` needs ``min > 1e-13 * S`` (``S = max |M_ij|`` over the grid: the refinement
    locates the minimiser to ~1e-8, an error ``O(1e-16 S)`` in the value); a minimum below that
    is located again (two at most) by golden section on 50-digit eigenvalues (to ``1e-12`` of its
    bracket) and then needs ``> 1e-20 * S``; ``no`` needs a 50-digit eigenvalue ``< -1e-30 * S``.
    """
    m = len(b)
    B0 = B0 if B0 is not None else [0] * m
    K = K or {}
    B = B or {}
    delays = delays if delays is not None else [0] * m
    z_a = z_a if z_a is not None else [0] * m
    model = _MultiUser(b, T, K0, B0, K, B, delays, z_a, approximation)
    # residue at z = 1
    R = [[model.T * model.K[i][j] for j in range(m)] for i in range(m)]
    ok, bad = _psd_exact(R)
    with mpmath.workdps(DPS):
        zz = 1 + mpmath.mpf(10) ** -30
        G = model.mp_G(zz) * (zz - 1)
        err = max(abs(G[i, j] - mpf_of(R[i][j])) for i in range(m) for j in range(m))
        scale = max([abs(mpf_of(R[i][j])) for i in range(m) for j in range(m)] + [mpmath.mpf(1)])
    if err > 1e-20 * scale:
        raise OracleFailure(f"the residue at z = 1 is not T Kmat (difference {float(err):.3g})")
    residue = (OracleResult(YES, "residue matrix T Kmat at z = 1 is PSD (exact minors)") if ok else
               OracleResult(NO, f"residue matrix T Kmat at z = 1 is not PSD: minor {bad[0]} = {bad[1]}",
                            margin=float(bad[1]), where={"minor": bad[0]}))
    poles = OracleResult(YES, "poles at z = 0 and a simple pole at z = 1 only")
    if residue.verdict == NO:
        return combine([("poles", poles), ("residues", residue)])
    hermitian = _matrix_circle_minimum(model, n_grid + (n_grid // 4) * max(model.n))
    if hermitian.verdict == UNCERTAIN:
        # lossless (e.g. no damping, no coupling, b = z_a): G(z) + G(1/z)^T = 0 identically
        G = multi_user_inverse(b=b, T=T, K0=K0, B0=B0, K=K, B=B, delays=delays, z_a=z_a, approximation=approximation)
        if all(sp.cancel(G[i, j] + G[j, i].subs(Z, 1 / Z)) == 0 for i in range(m) for j in range(i, m)):
            hermitian = OracleResult(YES, "G(z) + G(1/z)^T = 0 identically (lossless): G + G^H = 0 on the circle",
                                     margin=0.0, band=0.0)
    return combine([("poles", poles), ("residues", residue), ("G + G^H >= 0", hermitian)])


def _matrix_circle_minimum(model: _MultiUser, n_grid: int) -> OracleResult:
    pi = float(mpmath.pi)
    coarse = np.linspace(0.0, pi, n_grid + 1)
    small = np.concatenate([[0.0], np.logspace(-12, -2, 21)])
    theta = np.unique(np.concatenate([small, coarse[coarse > 1e-2]]))
    values = np.empty(len(theta))
    norms = np.empty(len(theta))
    big = theta >= 1e-2
    M = model.np_hermitian(theta[big])
    values[big] = np.linalg.eigvalsh(M)[:, 0]
    norms[big] = np.abs(M).max(axis=(1, 2))
    for i in np.nonzero(~big)[0]:
        with mpmath.workdps(30):
            Mi = model.mp_hermitian(mpmath.mpf(theta[i]))
            A = np.array([[complex(Mi[r, c]) for c in range(model.m)] for r in range(model.m)])
        values[i] = np.linalg.eigvalsh((A + A.conj().T) / 2)[0]
        norms[i] = np.abs(A).max()
    S = float(norms.max())
    beta, nu = 1e-13 * S, 1e-30 * S
    results = []
    refined = 0
    for i in local_minima(values, keep=6):
        lo, hi = theta[max(i - 1, 0)], theta[min(i + 1, len(theta) - 1)]
        x, _ = golden(model.mid_min_eig, float(lo), float(hi), 1e-10 * max(hi - lo, 1e-300) + 1e-16)
        value, _ = model.mp_min_eig(x)
        band = beta
        plateau = False
        if abs(value) <= beta:
            # flat to 50 digits on both sides: a plateau (a constant eigen-direction of M)
            h = 1e-4 * (hi - lo)
            sides = [model.mp_min_eig(x + d)[0] for d in (-h, h) if 0 <= x + d <= pi]
            plateau = all(abs(v - value) <= 1e-25 * S for v in sides)
            if plateau:
                band = 1e-25 * S
        if abs(value) <= beta and not plateau and refined < 2:
            refined += 1
            # a small minimum: locate it at full precision before judging
            with mpmath.workdps(50):
                x, value = golden(lambda t: model.mp_min_eig(t)[0], mpmath.mpf(lo), mpmath.mpf(hi),
                                  mpmath.mpf(10) ** -12 * (hi - lo) + mpmath.mpf(10) ** -40)
            band = 1e-20 * S
        results.append((value, x, band))
    value, x, band = min(results, key=lambda r: r[0])
    where = {"theta": float(x), "c": math.cos(float(x))}
    if value < -nu:
        return OracleResult(NO, f"lambda_min(G + G^H) = {float(value):.6g} < 0 at theta = {float(x):.12g}",
                            margin=float(value), band=nu, where=where)
    if all(v > b for v, _, b in results):
        return OracleResult(YES, f"min lambda_min(G + G^H) = {float(value):.6g}", margin=float(value), band=band,
                            where=where)
    value, x, band = min((r for r in results if r[0] <= r[2]), key=lambda r: r[0])
    where = {"theta": float(x), "c": math.cos(float(x))}
    return OracleResult(UNCERTAIN, f"min lambda_min = {float(value):.3g} inside the band", margin=float(value),
                        band=band, where=where)


# ---------------------------------------------------------------------------------------------
# the sampled-data teleoperator (teleoperator paper)
# ---------------------------------------------------------------------------------------------


def teleoperator_passivity(*, b_m: Any, b_s: Any, T: Any, C: Any, alpha: Any = 1, z: sp.Symbol = Z,
                           controller_poles: bool = False) -> OracleResult:
    r"""The passivity condition of the teleoperator paper: ``b > T/(1 - cos wT) Re{(1 - e^{-jwT})
    C(e^{jwT})}`` for equal controllers, and for ``C_m = alpha C`` the per-robot form
    ``b_s >= (alpha + 1) L``, ``b_m >= (alpha + 1) alpha L`` with ``L = T/(2(1 - c)) Re{(1 -
    z^{-1}) C}`` (``alpha = 1`` gives the printed bound).

    On the circle ``|1 - z|^2 = 2(1 - c)``, so ``T (1 - z^{-1})/(2(1 - c)) = T/(1 - z)`` and ``L =
    Re{T C(z)/(1 - z)}``: each condition is ``Re G(e^{jwT}) >= 0`` for ``G = b + k T C(z)/(z - 1)``
    (``k = alpha + 1`` or ``(alpha + 1) alpha``), decided with the Hermitian-part minimiser of
    :func:`discrete_positive_real` (only its third condition: the bound says nothing about
    poles). With ``controller_poles`` a pole of ``C`` outside the unit circle (an unstable
    controller) is a ``no`` as well.
    """
    a = sp.Rational(to_fraction(alpha).numerator, to_fraction(alpha).denominator)
    Tq = sp.Rational(to_fraction(T).numerator, to_fraction(T).denominator)
    parts = []
    if controller_poles:
        with mpmath.workdps(DPS):
            for r, _ in RationalFunction.from_expr(C, z).poles(DPS):
                if abs(r) - 1 > ON_CIRCLE:
                    return combine([("controller poles", OracleResult(
                        NO, f"the controller has a pole z ~ {complex(r):.6g} outside the unit circle",
                        margin=float(1 - abs(r)), where={"pole": complex(r)}))])
        parts.append(("controller poles", OracleResult(YES, "controller poles in |z| <= 1")))
    for robot, b, k in (("master", b_m, (a + 1) * a), ("slave", b_s, a + 1)):
        bq = sp.Rational(to_fraction(b).numerator, to_fraction(b).denominator)
        G = bq + k * Tq * sp.sympify(C) / (z - 1)
        herm = discrete_positive_real(G, z, always_hermitian=True).details.get("Re F >= 0")
        if herm is None:
            herm = OracleResult(UNCERTAIN, "Re G is unbounded near a unit-circle pole of C")
        parts.append((f"b_{robot[0]} >= bound", herm))
    return combine(parts)
