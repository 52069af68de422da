r"""Energy oracle for the sampled-data PEB teleoperator, written from the definition of passivity.

It imports nothing from the package under test (numpy, scipy and mpmath only) and knows nothing
of its theorem: it simulates the hybrid loop exactly and searches for an input of negative
supplied energy.

System (teleoperator paper, Fig. 2, restoring sign convention)::

    m_m dv_m/dt = f_m - b_m v_m - alpha y_k,   m_s dv_s/dt = f_s - b_s v_s + y_k   (kT <= t < (k+1)T)
    e_k = alpha x_m(kT) - x_s(kT),   y = C(z) e   (controllable canonical realisation, from rest)

Passivity means ``E(t) = int_0^t f_m v_m + f_s v_s dt >= 0`` for every input from rest.

What the oracle does
--------------------
Inputs are forces held constant on two substeps of every period: a short "kick" of length
``kick*T`` right after the sample and a "hold" for the rest (that is what lets an input change
the velocities quickly at the sample instants, which the worst inputs do). On each substep the
continuous robots are integrated exactly (matrix exponential of the augmented system, Van Loan),
and since the force is constant there the supplied energy is exactly ``f . (x(t1) - x(t0))``.
Over ``N`` periods the supplied energy is therefore an exact quadratic form ``w^T S w`` in the
``4N`` force values ``w``. Two searches:

1. dense: the least eigenvalue of ``S`` (after a diagonal congruence, which keeps the inertia)
   over every input of ``horizon`` periods;
2. slow: long horizons (``long_horizon`` periods) restricted to slowly varying envelopes
   (Legendre polynomials) modulated at ``0``, ``pi`` and the angles of the controller's poles
   near the unit circle, plus free forces in the first and last periods. This is where a
   negative DC stiffness or a negative residue at a unit-circle pole shows: the energy deficit
   grows like ``n^2`` while the dampers take ``~n``.

A candidate input with negative energy is re-simulated in mpmath at ``dps`` digits (matrix
exponentials and the period recursion in multiprecision, the float input taken as exact); the
verdict is ``'not passive'`` only if that energy is below ``-10^-(dps-10)`` times the sum of the
absolute substep energies. That certificate is sound up to mpmath's own rounding.

Uncertainty (what ``'no negative energy found'`` does not exclude)
------------------------------------------------------------------
It is a finite search, never a proof of passivity. It can miss: violations of the frequency
condition confined to an interval narrower than about ``4 pi / horizon`` rad/sample; violations
shallower than about ``2 kick`` relative to the dampers' dissipation (the kicks are not
instantaneous); atoms (DC, unit-circle poles) whose deficit needs more than ``long_horizon``
periods; instabilities slower than the horizons. Each result carries these numbers.

>>> r = teleoperator_energy_oracle([-5], [1], 0.001, 0.03, 0.05, 1.0, m_m=0.01, m_s=0.02)
>>> r.verdict, r.energy < 0
('not passive', True)
>>> teleoperator_energy_oracle([1], [1], 0.015, 0.01822, 0.01822, 1.0, m_m=0.015, m_s=0.015).verdict
'no negative energy found'
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from fractions import Fraction
from typing import Any, Sequence

import mpmath
import numpy as np
import scipy.linalg

__all__ = ["OracleResult", "teleoperator_energy_oracle", "lifted_system", "supplied_energy"]


def _fraction(x: Any) -> Fraction:
    if isinstance(x, Fraction):
        return x
    if isinstance(x, str):
        return Fraction(x.strip())
    if isinstance(x, float):
        return Fraction(x)                      # the float's exact value
    try:
        return Fraction(int(x.p), int(x.q))     # sympy Rational
    except AttributeError:
        return Fraction(x)


@dataclass(frozen=True)
class OracleResult:
    """``verdict`` is ``'not passive'`` (with the certified ``energy`` of ``forces``, an array
    ``(periods, 4)`` of ``[f_m kick, f_s kick, f_m hold, f_s hold]``) or
    ``'no negative energy found'``; ``eigen`` holds the least normalised eigenvalue of each
    search, ``uncertainty`` what the search could have missed."""

    verdict: str
    energy: float | None
    forces: np.ndarray | None
    stage: str | None
    eigen: dict[str, float]
    uncertainty: dict[str, Any] = field(default_factory=dict)


# ------------------------------------------------------------------------------------------
# the hybrid system, exactly between samples
# ------------------------------------------------------------------------------------------
def _controller(num: Sequence[Fraction], den: Sequence[Fraction]):
    """Controllable canonical realisation ``(A, B, C, D)`` of ``num/den`` (highest power first)."""
    num = list(num)
    den = list(den)
    while den and den[0] == 0:
        den.pop(0)
    while num and num[0] == 0:
        num.pop(0)
    if not den:
        raise ValueError("C(z): zero denominator")
    if len(num) > len(den):
        raise ValueError("C(z) is improper (non-causal)")
    n = len(den) - 1
    lead = den[0]
    a = [d / lead for d in den]
    b = [Fraction(0)] * (n + 1 - len(num)) + [c / lead for c in num]
    d0 = b[0]
    r = [b[i] - d0 * a[i] for i in range(1, n + 1)]          # strictly proper remainder
    A = [[Fraction(0)] * n for _ in range(n)]
    for j in range(n):
        A[0][j] = -a[j + 1]
    for i in range(1, n):
        A[i][i - 1] = Fraction(1)
    B = [[Fraction(1)]] + [[Fraction(0)] for _ in range(n - 1)]
    return A, B, [r], d0, n


class _Float:
    def num(self, q: Fraction):
        return float(q)

    def array(self, rows):
        return np.array(rows, dtype=float).reshape(len(rows), -1) if rows else np.zeros((0, 0))

    def expm(self, M):
        return scipy.linalg.expm(M)


class _MP:
    def __init__(self, dps: int):
        self.dps = dps

    def num(self, q: Fraction):
        return mpmath.mpf(q.numerator) / q.denominator

    def array(self, rows):
        out = np.empty((len(rows), len(rows[0]) if rows else 0), dtype=object)
        for i, row in enumerate(rows):
            for j, v in enumerate(row):
                out[i, j] = v
        return out

    def expm(self, M):
        E = mpmath.expm(mpmath.matrix(M.tolist()))
        return np.array(E.tolist(), dtype=object)


def lifted_system(C_num, C_den, T, b_m, b_s, alpha, m_m, m_s, kick=0.01, field_=None):
    r"""The period map of the hybrid loop: ``s_{k+1} = A s_k + B w_k`` and the substep position
    increments ``Delta_k = C s_k + D w_k`` (``[dx_m, dx_s]`` on the kick, then on the hold), so
    that the energy supplied in period ``k`` is exactly ``w_k . Delta_k``. State
    ``s = [x_m, v_m, x_s, v_s, controller state]``; float (numpy) or mpmath (object arrays).

    >>> A, B, C, D = lifted_system([1], [1], 0.1, 1, 1, 1, 1, 1)
    >>> A.shape, D.shape
    ((4, 4), (4, 4))
    """
    F = field_ or _Float()
    q = lambda v: _fraction(v)                      # noqa: E731
    num, den = [q(c) for c in C_num], [q(c) for c in C_den]
    Ac, Bc, Cc, d0, n = _controller(num, den)
    T, b_m, b_s, al, m_m, m_s = (q(v) for v in (T, b_m, b_s, alpha, m_m, m_s))
    if T <= 0 or m_m <= 0 or m_s <= 0:
        raise ValueError("T and the masses must be positive")
    zero, one = Fraction(0), Fraction(1)
    # continuous robots: p = [x_m, v_m, x_s, v_s], inputs [f_m, f_s, y]
    Ap = [[zero, one, zero, zero], [zero, -b_m / m_m, zero, zero],
          [zero, zero, zero, one], [zero, zero, zero, -b_s / m_s]]
    Bp = [[zero, zero, zero], [one / m_m, zero, -al / m_m], [zero, zero, zero], [zero, one / m_s, one / m_s]]
    kick = q(kick)

    def substep(tau: Fraction):
        aug = [[zero] * 7 for _ in range(7)]
        for i in range(4):
            for j in range(4):
                aug[i][j] = Ap[i][j] * tau
            for j in range(3):
                aug[i][4 + j] = Bp[i][j] * tau
        E = F.expm(F.array([[F.num(v) for v in row] for row in aug]))
        return E[:4, :4], E[:4, 4:6], E[:4, 6:7]

    Phi1, Gf1, Gy1 = substep(kick * T)
    Phi2, Gf2, Gy2 = substep((1 - kick) * T)
    nS = 4 + n
    N = lambda v: F.num(v)                          # noqa: E731
    Cy = F.array([[N(al * d0), N(zero), N(-d0), N(zero)] + [N(c) for c in Cc[0]]])
    Ce = F.array([[N(al), N(zero), N(-one), N(zero)] + [N(zero)] * n])
    P0 = F.array([[N(one if i == j else zero) for j in range(nS)] for i in range(4)])
    Px = F.array([[N(one if j == 2 * i else zero) for j in range(4)] for i in range(2)])
    M1 = Phi1 @ P0 + Gy1 @ Cy
    N1 = Gf1
    M2 = Phi2 @ M1 + Gy2 @ Cy
    N2a, N2b = Phi2 @ N1, Gf2
    A = F.array([[N(zero)] * nS for _ in range(nS)])
    A[:4, :] = M2
    if n:
        Acm = F.array([[N(v) for v in row] for row in Ac])
        Bcm = F.array([[N(v) for v in row] for row in Bc])
        Pxi = F.array([[N(one if j == 4 + i else zero) for j in range(nS)] for i in range(n)])
        A[4:, :] = Acm @ Pxi + Bcm @ Ce
    B = F.array([[N(zero)] * 4 for _ in range(nS)])
    B[:4, 0:2] = N2a
    B[:4, 2:4] = N2b
    C = F.array([[N(zero)] * nS for _ in range(4)])
    C[0:2, :] = Px @ (M1 - P0)
    C[2:4, :] = Px @ (M2 - M1)
    D = F.array([[N(zero)] * 4 for _ in range(4)])
    D[0:2, 0:2] = Px @ N1
    D[2:4, 0:2] = Px @ (N2a - N1)
    D[2:4, 2:4] = Px @ N2b
    return A, B, C, D


def supplied_energy(system, forces) -> tuple[Any, Any, np.ndarray]:
    """Energy supplied by ``forces`` (``(periods, 4)``) from rest, by the period recursion:
    ``(total, sum of |substep energies|, cumulative energy after each period)``.

    >>> sys_ = lifted_system([0], [1], 0.1, 1, 1, 1, 1, 1)          # no controller: dampers only
    >>> float(supplied_energy(sys_, np.ones((5, 4)))[0]) > 0
    True
    """
    A, B, C, D = system
    s = np.zeros(A.shape[0], dtype=A.dtype)
    if A.dtype == object:
        s = np.array([mpmath.mpf(0)] * A.shape[0], dtype=object)
    total = s[0] * 0 if A.dtype == object else 0.0
    absolute = total
    cumulative = []
    for w in forces:
        w = np.array([mpmath.mpf(float(v)) for v in w], dtype=object) if A.dtype == object else np.asarray(w, float)
        delta = C @ s + D @ w
        parts = w * delta
        total = total + sum(parts)
        absolute = absolute + sum(abs(p) for p in parts)
        cumulative.append(total)
        s = A @ s + B @ w
    return total, absolute, np.array(cumulative, dtype=object if A.dtype == object else float)


# ------------------------------------------------------------------------------------------
# the energy form and its searches
# ------------------------------------------------------------------------------------------
def _impulse_blocks(system, N: int) -> np.ndarray:
    A, B, C, D = system
    G = np.empty((N, 4, 4))
    G[0] = D
    X = B.copy()
    for k in range(1, N):
        G[k] = C @ X
        X = A @ X
    return G


def _spectral_radius(A: np.ndarray) -> float:
    return float(max(abs(np.linalg.eigvals(A)))) if A.size else 0.0


def _cap(N: int, rho: float, budget: float) -> int:
    if rho <= 1 + 1e-12:
        return N
    return max(4, min(N, int(math.log(budget) / math.log(rho))))


def _least_directions(S: np.ndarray, count: int = 3) -> tuple[float, list[np.ndarray]]:
    """Least eigenvalue of ``S`` after the congruence ``D^-1/2 S D^-1/2`` (``D = |diag S|``,
    floored at ``1e-12 max D`` so that near-null directions do not amplify rounding), and the
    directions of the ``count`` least eigenvalues that are negative, mapped back."""
    S = (S + S.T) / 2
    d = np.abs(np.diag(S)).copy()
    d = np.maximum(d, 1e-12 * d.max()) if d.max() > 0 else np.ones_like(d)
    scale = 1 / np.sqrt(d)
    Sn = S * scale[:, None] * scale[None, :]
    vals, vecs = np.linalg.eigh(Sn)
    return float(vals[0]), [vecs[:, i] * scale for i in range(min(count, len(vals))) if vals[i] < 0]


def _toeplitz_apply(FG: np.ndarray, W: np.ndarray, N: int, nfft: int) -> np.ndarray:
    """``(L W)`` for the block lower-triangular Toeplitz ``L`` with blocks ``G`` (FFT)."""
    FW = np.fft.rfft(W, n=nfft, axis=0)                  # (f, 4, nv)
    Y = np.einsum("fab,fbv->fav", FG, FW)
    return np.fft.irfft(Y, n=nfft, axis=0)[:N]


def _slow_basis(N: int, angles: Sequence[float], degree: int, local: int) -> np.ndarray:
    t = np.linspace(-1.0, 1.0, N)
    env = np.polynomial.legendre.legvander(t, degree - 1)     # (N, degree)
    k = np.arange(N)
    cols = []
    for phi in angles:
        carriers = [np.cos(phi * k)]
        if 1e-9 < phi < math.pi - 1e-9:
            carriers.append(np.sin(phi * k))
        for car in carriers:
            for j in range(degree):
                for ch in range(4):
                    v = np.zeros((N, 4))
                    v[:, ch] = env[:, j] * car
                    cols.append(v)
    for idx in list(range(min(local, N))) + list(range(max(N - local, 0), N)):
        for ch in range(4):
            v = np.zeros((N, 4))
            v[idx, ch] = 1.0
            cols.append(v)
    return np.stack(cols, axis=-1)                            # (N, 4, nv)


def teleoperator_energy_oracle(C_num, C_den, T, b_m, b_s, alpha, m_m=1.0, m_s=1.0, *, horizon: int = 64,
                               kick: float = 0.01, long_horizon: int = 4096, degree: int = 6,
                               dps: int = 30) -> OracleResult:
    r"""Search for an input of negative supplied energy (see the module docstring).

    Parameters
    ----------
    C_num, C_den : sequences
        ``C(z)`` coefficients, highest power first (ints, Fractions, strings or floats).
    T, b_m, b_s, alpha, m_m, m_s : numbers
        Period, dampings, scaling, masses (any positive masses).
    horizon, long_horizon : int
        Periods of the dense and of the slow search (``long_horizon = 0`` skips the latter).
    kick : float
        Length of the first substep as a fraction of ``T``.
    dps : int
        mpmath digits of the certificate.

    Returns
    -------
    OracleResult

    Examples
    --------
    >>> r = teleoperator_energy_oracle([2], [1], 0.015, 0.01822, 0.01822, 1, m_m=0.015, m_s=0.015)
    >>> r.verdict, r.stage
    ('not passive', 'dense')
    """
    fsys = lifted_system(C_num, C_den, T, b_m, b_s, alpha, m_m, m_s, kick)
    rho = _spectral_radius(fsys[0])
    eigen: dict[str, float] = {}
    unc: dict[str, Any] = {"kick": kick, "spectral_radius": rho, "dps": dps,
                           "missed_if": "violations narrower than ~4*pi/horizon rad, shallower than "
                                        "~2*kick relative, or atoms needing more than long_horizon periods"}
    msys = []                                                  # the mpmath system, built once if needed

    def certify(stage: str, directions: list[np.ndarray]) -> OracleResult | None:
        if not directions:
            return None
        with mpmath.workdps(dps):
            if not msys:
                msys.append(lifted_system(C_num, C_den, T, b_m, b_s, alpha, m_m, m_s, kick, field_=_MP(dps)))
            for forces in directions:
                # truncate at the most negative prefix (the input is zero afterwards: same energy)
                _, _, cum = supplied_energy(fsys, forces)
                stop = int(np.argmin(cum)) + 1
                forces = forces[:stop] / np.abs(forces[:stop]).max()
                total, absolute, _ = supplied_energy(msys[0], forces)
                if total < -mpmath.mpf(10) ** (-(dps - 10)) * absolute:
                    return OracleResult("not passive", float(total), forces, stage, eigen, unc)
        return None

    # 1. dense search
    Nd = _cap(horizon, rho, 1e10)
    G = _impulse_blocks(fsys, Nd)
    idx = np.subtract.outer(np.arange(Nd), np.arange(Nd))
    L = np.where((idx >= 0)[:, :, None, None], G[np.clip(idx, 0, Nd - 1)], 0.0)   # (k, j, a, b)
    L = L.transpose(0, 2, 1, 3).reshape(4 * Nd, 4 * Nd)
    lam, vecs = _least_directions(L)
    eigen["dense"] = lam
    unc["horizon"] = Nd
    found = certify("dense", [v.reshape(Nd, 4) for v in vecs])
    if found:
        return found
    # 2. slow search over long horizons
    if long_horizon:
        Nl = _cap(long_horizon, rho, 1e6)
        unc["long_horizon"] = Nl
        den = [float(_fraction(c)) for c in C_den]
        while den and den[0] == 0:
            den.pop(0)
        angles = {0.0, math.pi}
        if len(den) > 1:
            for p in np.roots(den):
                if abs(abs(p) - 1) < 1e-6:
                    angles.add(abs(float(np.angle(p))))
        angles = sorted(angles)
        unc["modulations"] = angles
        Gl = _impulse_blocks(fsys, Nl)
        nfft = 1 << (2 * Nl - 1).bit_length()
        FG = np.fft.rfft(Gl, n=nfft, axis=0)                   # (f, 4, 4)
        V = _slow_basis(Nl, angles, degree, local=3)
        Vflat = V.reshape(4 * Nl, -1)
        Qm, Rm = np.linalg.qr(Vflat)
        keep = np.abs(np.diag(Rm)) > 1e-10 * np.abs(np.diag(Rm)).max()
        Qm = Qm[:, keep]
        LQ = _toeplitz_apply(FG, Qm.reshape(Nl, 4, -1), Nl, nfft).reshape(4 * Nl, -1)
        Ssub = Qm.T @ LQ
        lam_s, dirs = _least_directions(Ssub)
        eigen["slow"] = lam_s
        found = certify("slow", [(Qm @ a).reshape(Nl, 4) for a in dirs])
        if found:
            return found
    return OracleResult("no negative energy found", None, None, None, eigen, unc)
