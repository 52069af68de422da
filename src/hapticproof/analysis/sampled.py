"""Exact sampled-data loops: zero-order hold by the matrix exponential, spectral stability (the
loops themselves are :mod:`hapticproof.systems.loops`).

A *scene* is a frozen value object describing one sampled-data loop: continuous devices
(mass ``m``, damping ``b``), their port terminations (an operator or environment impedance
``Z(s)``, free, or clamped), a sampler, a discrete controller ``H(z)`` / ``C(z)``, integer delays
``z**-n`` and a zero-order hold. Three scenes are provided:

* :class:`SingleUser` -- HVE paper (000), Fig. 4a: a device on a virtual wall
  ``H(z) = K + B(z-1)/(Tz)`` with an optional operator ``Z_h(s)`` (Fig. 8 uses ``-z_a + 1/s``);
* :class:`MultiUser` -- HVE paper, Fig. 6/7 and eqs. (37)-(39), (56): ``m`` devices coupled to
  ground and to each other, per-user delays ``n_i`` and operators;
* :class:`Teleoperator` -- teleoperator paper (002), Fig. 2 and eqs. (1)-(7): master and slave
  coupled by position-error controllers, with free, clamped or impedance terminations.

Each scene assembles a :class:`Loop` (continuous plant matrices, discrete controller, ports),
which is discretised **exactly**: ``expm([[A, B], [0, 0]] T) = [[Phi, Gamma], [0, I]]`` gives
the sample-to-sample map of the plant under a zero-order hold, so the discrete closed-loop
matrix is exact up to rounding; no small-step integration is involved. Two precisions are
offered: ``"float"`` (float64, :func:`scipy.linalg.expm`) for speed and ``"mp"`` (mpmath at
``dps`` digits, default 50) as the high-precision reference.

Sign conventions (derived from the mechanics, not copied from the printed equations):

* every device obeys ``m dv/dt = f - b v - u`` where ``f`` is the force its port termination
  applies and ``u`` the held controller force, so a controller with positive DC gain is
  restoring: ``u = H(z) x`` for the virtual wall (HVE (14)-(16));
* a termination of impedance ``Z(s)`` applies ``f = f_ext - Z(s) v`` (HVE Fig. 4b, teleoperator
  (2)); ``Z_h(s) = -z_a + 1/s`` gives ``m dv/dt = f_ext - (b - z_a) v - x - u``;
* teleoperator: with ``e = alpha x_m - x_s`` (002 (6), (31)) the master force is
  ``u_m = C_m(z) e = alpha C(z) e`` and the slave force ``u_s = -C_s(z) e = -C(z) e``. These are
  the forces of the discrete "spring" ``C(z) e**2 / 2`` on both robots, hence restoring. The
  printed (7) has both signs flipped and (13) flips only the master's; neither is restoring
  with (1)'s ``f_h - f_m`` convention.

A free device (no termination stiffness, no ground coupling) has a rigid-body translation mode:
an eigenvalue exactly 1 that no controller gain moves (the free teleoperator, or an m-user HVE
without ground couplings). It is removed exactly by a change of coordinates before eigenvalues
are taken (:func:`closed_loop_matrix`), so "stable" means every other mode is strictly inside
the unit circle.

>>> from hapticproof.systems.loops import SingleUser
>>> scene = SingleUser(m=0.015, b=0.02, T=0.001, K=30)
>>> round(spectral_radius(scene), 6), is_stable(scene)
(0.999833, True)
>>> is_stable(SingleUser(m=0.015, b=0.02, T=0.001, K=50))
False
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from dataclasses import dataclass, field
from typing import Any

import math
from fractions import Fraction

import flint
import mpmath
import numpy as np
import scipy.linalg

from hapticproof.core.evidence import Decision, Evidence, Method, Outcome
from hapticproof.exact.realroots import ball_spectral_radius, flint_precision
from hapticproof.systems.impedance import Precision, as_float, as_mp
from hapticproof.systems.loops import Loop, Scene

__all__ = ["TRUSTED_MARGIN", "discretize", "closed_loop_matrix", "closed_loop_matrices", "spectral_radius", "spectral_radii", "is_stable",
           "free_device_boundary", "certified_radius", "certified_stability", "decide_stability", "LoopStability", "trusted_radius", "trusted_radii", "loop_json", "MAX_BITS", "DECIDE_BITS"]

#: The certified route doubles its working precision up to this many bits (an ``expm`` of a
#: generator of norm 1e300 squares some 1000 times and needs about as many bits).
MAX_BITS = 16384
#: A decision by the certified route stops doubling here (a radius within about 2^-4000 of 1
#: is reported as undecided rather than computed for minutes).
DECIDE_BITS = 4096


# --------------------------------------------------------------------------------------------
# exact discretisation and the closed loop
# --------------------------------------------------------------------------------------------
def discretize(a: Any, b: Any, T: Any, precision: Precision = "float", dps: int = 50):
    """Exact zero-order-hold discretisation ``(Phi, Gamma)`` of ``dx/dt = a x + b u``.

    ``expm([[a, b], [0, 0]] T) = [[Phi, Gamma], [0, I]]`` with ``Phi = e^{aT}`` and
    ``Gamma = int_0^T e^{a s} ds b`` (Van Loan). ``precision="mp"`` uses mpmath at ``dps``
    digits and returns mpmath matrices.

    >>> Phi, Gamma = discretize([[0, 1], [0, -2]], [[0], [1]], 0.1)
    >>> np.round(Phi, 6).tolist(), np.round(Gamma.ravel(), 8).tolist()
    ([[1.0, 0.090635], [0.0, 0.818731]], [0.00468269, 0.09063462])
    """
    if precision == "float":
        a_arr = np.asarray(a, dtype=float)
        b_arr = np.asarray(b, dtype=float).reshape(a_arr.shape[0], -1)
        n, m = b_arr.shape
        aug = np.zeros((n + m, n + m))
        aug[:n, :n], aug[:n, n:] = a_arr, b_arr
        e = scipy.linalg.expm(aug * as_float(T))
        return e[:n, :n], e[:n, n:]
    with mpmath.workdps(dps):
        a_m = mpmath.matrix([[as_mp(v) for v in row] for row in np.asarray(a, dtype=object)])
        b_obj = np.asarray(b, dtype=object).reshape(a_m.rows, -1)
        n, m = b_obj.shape
        aug = mpmath.zeros(n + m, n + m)
        for i in range(n):
            for j in range(n):
                aug[i, j] = a_m[i, j]
            for j in range(m):
                aug[i, n + j] = as_mp(b_obj[i, j])
        e = mpmath.expm(aug * as_mp(T))
        return e[:n, :n], e[:n, n : n + m]


def closed_loop_from(loop: Loop, phi: np.ndarray, gamma: np.ndarray) -> np.ndarray:
    """``[[Phi + Gamma D C, Gamma Cc], [Bc C, Ac]]`` over ``[xi; eta]``."""
    ctrl = loop.ctrl
    n, nc = loop.a.shape[0], ctrl.a.shape[0]
    dtype = float if loop.precision == "float" else object
    out = np.zeros((n + nc, n + nc), dtype=dtype)
    out[:n, :n] = phi + gamma @ ctrl.d @ loop.c
    out[:n, n:] = gamma @ ctrl.c
    out[n:, :n] = ctrl.b @ loop.c
    out[n:, n:] = ctrl.a
    return out


def _deflate(matrix: np.ndarray, rigid: np.ndarray) -> np.ndarray:
    """Remove the rigid-body eigenvalue 1 exactly: similarity ``P^-1 A P``, drop a row/column.

    ``P = I + (w - e_a) e_a^T`` maps ``e_a`` to the eigenvector ``w`` (``w_a = 1``), so column
    ``a`` of ``P^-1 A P`` is ``e_a`` and the other eigenvalues are those of the rest.
    """
    idx = int(np.argmax([abs(v) for v in rigid]))
    w = rigid / rigid[idx]
    d = w.copy()
    d[idx] = d[idx] - 1
    ap = matrix.copy()
    ap[:, idx] = ap[:, idx] + matrix @ d
    out = ap - np.outer(d, ap[idx, :])
    keep = [i for i in range(matrix.shape[0]) if i != idx]
    return out[np.ix_(keep, keep)]


def closed_loop_matrix(
    scene: Scene, precision: Precision = "float", dps: int = 50, deflate: bool = True
) -> Any:
    """The exact discrete closed-loop matrix of ``scene`` (sample to sample).

    State ``[plant states; controller and delay states]``. With ``deflate`` the rigid-body
    translation mode (eigenvalue exactly 1 of a free, ungrounded system) is removed.
    ``precision="mp"`` returns an :class:`mpmath.matrix` computed at ``dps`` digits.

    >>> from hapticproof.systems.loops import SingleUser
    >>> closed_loop_matrix(SingleUser(m=1, b=1, T=0.1, K=1, delay=2)).shape
    (4, 4)
    """
    if precision == "float":
        loop = scene.loop("float")
        phi, gamma = discretize(loop.a, loop.bu, loop.T)
        out = closed_loop_from(loop, phi, gamma)
        if deflate and loop.rigid is not None:
            out = _deflate(out, loop.rigid)
        return out
    with mpmath.workdps(dps):
        loop = scene.loop("mp")
        phi, gamma = discretize(loop.a, loop.bu, loop.T, precision="mp", dps=dps)
        phi_o = np.array(phi.tolist(), dtype=object).reshape(loop.a.shape)
        gamma_o = np.array(gamma.tolist(), dtype=object).reshape(loop.bu.shape)
        out = closed_loop_from(loop, phi_o, gamma_o)
        if deflate and loop.rigid is not None:
            out = _deflate(out, loop.rigid)
        return mpmath.matrix(out.tolist())


def closed_loop_matrices(scenes: Sequence[Scene]) -> list[np.ndarray]:
    """Float closed-loop matrices of many scenes, with one batched ``expm`` per plant size."""
    loops = [s.loop("float") for s in scenes]
    out: list[np.ndarray | None] = [None] * len(loops)
    groups: dict[tuple[int, int], list[int]] = {}
    for i, lp in enumerate(loops):
        groups.setdefault(lp.bu.shape, []).append(i)
    for (n, m), idx in groups.items():
        aug = np.zeros((len(idx), n + m, n + m))
        for k, i in enumerate(idx):
            aug[k, :n, :n] = loops[i].a
            aug[k, :n, n:] = loops[i].bu
            aug[k] *= as_float(loops[i].T)
        expd = scipy.linalg.expm(aug)
        for k, i in enumerate(idx):
            mat = closed_loop_from(loops[i], expd[k, :n, :n], expd[k, :n, n:])
            if loops[i].rigid is not None:
                mat = _deflate(mat, loops[i].rigid)
            out[i] = mat
    return out  # type: ignore[return-value]


def spectral_radius(scene: Scene, precision: Precision = "float", dps: int = 50) -> Any:
    """Largest eigenvalue modulus of the (deflated) closed loop; ``< 1`` means stable.

    >>> from hapticproof.systems.loops import SingleUser
    >>> float(spectral_radius(SingleUser(m=1, b=1, T=0.1, K=1), precision="mp", dps=30)) < 1
    True
    """
    if precision == "float":
        return float(np.max(np.abs(np.linalg.eigvals(closed_loop_matrix(scene)))))
    with mpmath.workdps(dps):
        mat = closed_loop_matrix(scene, "mp", dps)
        if mat.rows == 0:
            return mpmath.mpf(0)
        radius = _ball_spectral_radius(mat, dps)
        if radius is not None:
            return radius
        eig = mpmath.eig(mat, left=False, right=False)
        return max(abs(v) for v in eig)


def _ball_spectral_radius(mat: mpmath.matrix, dps: int) -> mpmath.mpf | None:
    """Spectral radius of an mpmath matrix from python-flint's isolating eigenvalue balls.

    Some 40x faster than ``mpmath.eig`` at 30 digits and certified for the matrix as given
    (its entries are already rounded to ``dps`` digits); ``None`` when the balls do not isolate
    the eigenvalues (clusters), and the caller falls back to ``mpmath.eig``."""
    with flint_precision(int(dps * 3.33) + 32):
        radius = ball_spectral_radius(
            flint.acb_mat([[flint.acb(mat[i, j]) for j in range(mat.cols)] for i in range(mat.rows)]))
        return None if radius is None else mpmath.mpf(radius.mid().str(dps + 5, radius=False))


def spectral_radii(scenes: Sequence[Scene]) -> np.ndarray:
    """Spectral radii of many scenes: batched ``expm`` and batched eigenvalues (float64).

    >>> from hapticproof.systems.loops import SingleUser
    >>> rho = spectral_radii([SingleUser(m=0.015, b=0.02, T=0.001, K=k) for k in (10, 60)])
    >>> (rho < 1).tolist()
    [True, False]
    """
    mats = closed_loop_matrices(scenes)
    out = np.empty(len(mats))
    groups: dict[int, list[int]] = {}
    for i, mat in enumerate(mats):
        groups.setdefault(mat.shape[0], []).append(i)
    for size, idx in groups.items():
        if size == 0:
            out[idx] = 0.0
            continue
        stack = np.stack([mats[i] for i in idx])
        out[idx] = np.max(np.abs(np.linalg.eigvals(stack)), axis=-1)
    return out


def is_stable(scene: Scene) -> bool:
    """Whether every (non-rigid) closed-loop eigenvalue is strictly inside the unit circle, in
    float64: a simulation's guard, the motion relative to a free translation (a free
    teleoperator's). Not a verdict: the decision is :func:`decide_stability` (``rho = 1``, a free
    translation included, is not stable there)."""
    return spectral_radius(scene) < 1


def free_device_boundary(m: Any, b: Any, T: Any, precision: Precision = "float", dps: int = 50) -> Any:
    """Closed-form stability boundary ``K*`` of the free device on ``H = K`` (B = 0, n = 0).

    With ``a = b/m``, ``alpha = a T`` and ``p = e^{-alpha}`` the ZOH equivalent of
    ``1/(s (m s + b))`` is ``G(z) = (m/b^2) ((alpha + p - 1) z + (1 - p - alpha p)) /
    ((z - 1)(z - p))``, so the loop ``1 + K G(z) = 0`` has the quadratic characteristic
    polynomial ``z^2 + a1 z + a0`` with (``kappa = K m / b^2``)
    ``a1 = -(1 + p) + kappa (alpha + p - 1)`` and ``a0 = p + kappa (1 - p - alpha p)``.
    Jury: ``P(1) = kappa alpha (1 - p) > 0`` for every ``K > 0``; ``a0 < 1`` and ``P(-1) > 0``
    give

    ``K* = (b^2/m) min( (1 - p)/(1 - p - alpha p),
    2 (1 + p)/(alpha (1 + p) - 2 (1 - p)) )``

    i.e. ``K* = (b/T) alpha (1 - e^-alpha)/(1 - (1 + alpha) e^-alpha)`` while the complex pair
    leaves first (small ``alpha``; ``K* -> 2b/T (1 + alpha/6 + ...)``, Gil's ``b > KT/2``),
    and the flip (``z = -1``) bound for large ``alpha``. The stable set in ``K > 0`` is the
    single interval ``(0, K*)``: both bounds are linear upper bounds in ``kappa``.

    >>> round(free_device_boundary(0.015, 0.02, 0.001), 6)
    40.008891
    """
    if precision == "float":
        # 1 - p - alpha p ~ alpha^2/2 cancels catastrophically in float64: evaluate at 30 digits
        return float(free_device_boundary(m, b, T, precision="mp", dps=30))
    with mpmath.workdps(dps):
        m_, b_, t_ = as_mp(m), as_mp(b), as_mp(T)
        alpha = b_ * t_ / m_
        p = mpmath.exp(-alpha)
        bound1 = (1 - p) / (1 - p - alpha * p)
        c2 = alpha * (1 + p) - 2 * (1 - p)
        bound2 = 2 * (1 + p) / c2 if c2 > 0 else mpmath.inf
        return b_ * b_ / m_ * min(bound1, bound2)


# --------------------------------------------------------------------------------------------
# certified spectral radius at any scale (ball arithmetic from the exact loop)
# --------------------------------------------------------------------------------------------
def _arb_q(value: Any) -> flint.arb:
    q = Fraction(value)
    return flint.arb(flint.fmpq(q.numerator, q.denominator))


def _arb_matrix(rows: np.ndarray) -> flint.arb_mat:
    r, c = rows.shape
    return flint.arb_mat(r, c, [_arb_q(rows[i, j]) for i in range(r) for j in range(c)])


def _closed_loop_arb(loop: Loop, deflate: bool = True) -> flint.arb_mat:
    """The ZOH closed loop of an exact loop as an arb matrix at the current precision (with
    ``deflate``, the rigid translation mode deflated by the exact similarity of :func:`_deflate`)."""
    n, m = loop.bu.shape
    T = Fraction(loop.T)
    gen = np.zeros((n + m, n + m), dtype=object)
    gen[...] = Fraction(0)
    gen[:n, :n], gen[:n, n:] = loop.a * T, loop.bu * T
    E = _arb_matrix(gen).exp() if n + m else flint.arb_mat(0, 0)
    phi = flint.arb_mat(n, n, [E[i, j] for i in range(n) for j in range(n)])
    gamma = flint.arb_mat(n, m, [E[i, n + j] for i in range(n) for j in range(m)])
    ctrl, nc = loop.ctrl, loop.ctrl.a.shape[0]
    top_left = phi + gamma * _arb_matrix(ctrl.d @ loop.c)
    top_right = gamma * _arb_matrix(ctrl.c) if nc else None
    bottom_left = _arb_matrix(ctrl.b @ loop.c) if nc else None
    size = n + nc
    rows = [[flint.arb(0)] * size for _ in range(size)]
    for i in range(n):
        for j in range(n):
            rows[i][j] = top_left[i, j]
        for j in range(nc):
            rows[i][n + j] = top_right[i, j]
    for i in range(nc):
        for j in range(n):
            rows[n + i][j] = bottom_left[i, j]
        for j in range(nc):
            rows[n + i][n + j] = _arb_q(ctrl.a[i, j])
    if deflate and loop.rigid is not None:
        rigid = [Fraction(v) for v in loop.rigid]
        idx = max(range(size), key=lambda i: abs(rigid[i]))
        w = [v / rigid[idx] for v in rigid]
        d = [_arb_q(v - (1 if i == idx else 0)) for i, v in enumerate(w)]
        ap = [row[:] for row in rows]
        for i in range(size):
            ap[i][idx] = ap[i][idx] + sum((rows[i][k] * d[k] for k in range(size)), flint.arb(0))
        out = [[ap[i][j] - d[i] * ap[idx][j] for j in range(size)] for i in range(size)]
        keep = [i for i in range(size) if i != idx]
        rows = [[out[i][j] for j in keep] for i in keep]
        size -= 1
    return flint.arb_mat(size, size, [v for row in rows for v in row]) if size else flint.arb_mat(0, 0)


def _scale_bits(loop: Any) -> int:
    """About log2 of the largest entry of ``A T`` and ``B T``: scaling and squaring an exponential
    of norm 2^k loses about k bits, so the certified exponentials start that much above."""
    T = Fraction(loop.T)
    entries = [abs(Fraction(v) * T) for v in (*loop.a.ravel(), *loop.bu.ravel())]
    norm = max(entries, default=Fraction(0))
    return max(0, norm.numerator.bit_length() - norm.denominator.bit_length()) if norm else 0


def certified_radius(scene: Scene, bits: int = 128, decide: bool = False, max_bits: int = MAX_BITS) -> flint.arb:
    """A certified enclosure of the spectral radius of the (deflated) closed loop, at any scale.

    The loop is assembled from exact fractions (``scene.loop("exact")``), the ZOH transition
    matrix enclosed by ``arb_mat.exp`` of the exact generator and the eigenvalues by isolating
    balls (``acb_mat.eig``); the working precision doubles from ``bits`` until the balls
    isolate the eigenvalues -- with ``decide``, until the ball also excludes 1 (a radius
    ``1 - 1e-260`` needs some 900 bits) -- up to ``max_bits`` (then the last ball, which may
    hold 1, is returned). Ball arithmetic has no overflow, so
    parameters from 1e-300 to 1e300 are decided as they are given, where ``float64`` loses
    every digit (an ``expm`` entry ``e^{-1e300}``, a gain ``1e300`` next to an entry ``1``).
    Raises :class:`ArithmeticError` when the eigenvalues stay clustered.

    >>> from hapticproof.systems.loops import SingleUser
    >>> rho = certified_radius(SingleUser(m="0.015", b="0.02", T="0.001", K=30))
    >>> rho < 1, round(float(rho.mid()), 6)
    (True, 0.999833)
    >>> certified_radius(SingleUser(m="0.015", b="1e297", T="0.001", K="1e300")) < 1     # far beyond float64
    True
    """
    scale_bits = _scale_bits(loop := scene.loop("exact"))
    precision = max(bits, 64 + 2 * scale_bits)
    last = None
    while precision <= max(max_bits, bits):
        with flint_precision(precision):
            matrix = _closed_loop_arb(loop)
            if matrix.nrows() == 0:
                return flint.arb(0)
            finite = all(matrix[i, j].is_finite() for i in range(matrix.nrows()) for j in range(matrix.ncols()))
            radius = ball_spectral_radius(flint.acb_mat(matrix)) if finite else None
            if radius is not None and radius.is_finite() and radius.rad() < flint.arb(2) ** -40 * (1 + radius.mid()):
                last = radius
                if not decide or radius < 1 or radius > 1:
                    return radius
        precision *= 2
    if last is not None:
        return last
    raise ArithmeticError("the closed-loop eigenvalues were not isolated at the highest working precision")


def _disk_routh(charpoly: flint.arb_poly) -> bool | None:
    """Every root of a real polynomial strictly inside the unit circle (``True``), one strictly
    outside (``False``), or undecided (``None``), in ball arithmetic: the bilinear map
    ``z = (1 + s)/(1 - s)`` and a Routh array whose first column must be certainly positive.

    Clusters of roots do not matter (a crowd of eigenvalues near 0 -- the delay states of a
    loop with a tiny period -- maps near ``s = -1``, far from the axis); only roots near the
    circle need precision. With a regular array the sign changes of the first column count the
    roots in ``Re s > 0`` (Routh), i.e. outside the circle.
    """
    coeffs = [charpoly[k] for k in range(charpoly.degree() + 1)]
    n = len(coeffs) - 1
    if n <= 0:
        return True
    one_plus, one_minus = flint.arb_poly([1, 1]), flint.arb_poly([1, -1])
    R = flint.arb_poly([0])
    for k, a in enumerate(coeffs):
        R += a * one_plus**k * one_minus ** (n - k)
    c = [R[k] for k in range(n + 1)][::-1]          # highest degree first
    if not (c[0] > 0 or c[0] < 0):
        return None                                  # a root near z = -1 (s = infinity)
    if c[0] < 0:
        c = [-v for v in c]
    top, below = c[0::2], c[1::2]
    width = len(top)
    below = below + [flint.arb(0)] * (width - len(below))
    column = [top[0]]
    rows = [top, below]
    for _ in range(n):
        a, b = rows[-2], rows[-1]
        if not (b[0] > 0 or b[0] < 0):
            return None
        column.append(b[0])
        rows.append([(b[0] * a[k + 1] - a[0] * b[k + 1]) / b[0] for k in range(width - 1)] + [flint.arb(0)])
    column = column[: n + 1]
    changes = sum(1 for x, y in zip(column, column[1:]) if (x > 0) != (y > 0))
    return changes == 0


def certified_stability(scene: Scene, max_bits: int = 0, relative: bool = False) -> bool | None:
    """``True`` (every closed-loop eigenvalue strictly inside the unit circle), ``False`` (not:
    one outside, or one exactly on the circle) or ``None`` (undecided at ``max_bits``, default
    :data:`DECIDE_BITS`): :attr:`LoopStability.stable` of :func:`decide_stability`.

    ``relative=True`` asks about the motion apart from a free translation (the exact eigenvalue
    ``z = 1`` of a free device or teleoperator that no gain moves, :attr:`LoopStability.relative`):
    what a stability *boundary* of such a family separates.

    >>> from hapticproof.systems.loops import SingleUser
    >>> certified_stability(SingleUser(m="0.015", b="0.02", T="0.001", K=30)), certified_stability(
    ...     SingleUser(m="0.015", b="0.02", T="0.001", K=50))
    (True, False)
    >>> certified_stability(SingleUser(m="0.015", b="0.02", T="1e-300", K=30, delay=5))    # every eigenvalue near 0 or 1
    True
    >>> certified_stability(SingleUser(m="0.02", b="0.01", T="0.001", K=0, B="0.001"))     # rho = 1 exactly
    False
    """
    decision = decide_stability(scene, max_bits=max_bits)
    return decision.relative if relative else decision.stable


# --------------------------------------------------------------------------------------------
# the one stability decision: strictly inside, exactly on the circle, outside
# --------------------------------------------------------------------------------------------
#: The verdicts of :class:`LoopStability`.
STABLE, MARGINAL, UNSTABLE, ON_CIRCLE, UNDECIDED = "stable", "marginal", "unstable", "on-circle", "undecided"


@dataclass(frozen=True, slots=True)
class LoopStability:
    """The stability of an exact sampled-data loop, decided once (:func:`decide_stability`).

    ``verdict``:

    * ``"stable"`` -- every eigenvalue of the closed loop strictly inside the unit circle
      (``rho < 1``: asymptotically stable);
    * ``"marginal"`` -- none outside, some exactly on the circle and semisimple (``rho = 1``:
      bounded, not asymptotically stable; ``z = 1`` is the usual one -- a mode whose position
      nothing feeds back, ``K = 0`` or a singular stiffness matrix without ground);
    * ``"unstable"`` -- an eigenvalue outside, or one on the circle in a Jordan block;
    * ``"on-circle"`` -- ``z = 1`` is an exact eigenvalue (so not stable), the others undecided;
    * ``"undecided"`` -- an eigenvalue within ``2^-bits`` of the circle, not decided.

    ``fixed_points`` is an exact basis of the eigenvectors of ``z = 1`` (loop states, plant
    first), ``translation`` whether the loop has a free translation (a rigid motion the
    controller cannot see) and ``relative`` the stability of the motion apart from it (``True``
    only when every other eigenvalue is strictly inside; equal to :attr:`stable` without one).
    ``method`` is ``"exact-charpoly"`` (a plant without dissipation or springs: the ZOH matrix
    and the characteristic polynomial are exact over Q, roots located exactly) or ``"ball-routh"``
    (the characteristic polynomial in ball arithmetic after the exact eigenvalues ``z = 1`` are
    deflated, a Routh array after the bilinear map).
    """

    verdict: str
    relative: bool | None
    fixed_points: tuple[tuple[Fraction, ...], ...]
    translation: bool
    method: str
    bits: int
    reason: str
    facts: Mapping[str, Any] = field(default_factory=dict)

    @property
    def stable(self) -> bool | None:
        """``True`` only for ``rho < 1``; ``None`` when undecided."""
        return True if self.verdict == STABLE else None if self.verdict == UNDECIDED else False

    @property
    def value(self) -> int:
        """The map's number: ``1`` stable, ``0`` not (marginal included), ``-1`` undecided."""
        return {True: 1, False: 0, None: -1}[self.stable]

    def outcome(self, witness: Mapping[str, Any] | None = None) -> Outcome:
        """As a decision of "the loop is asymptotically stable" (``witness``: the parameters)."""
        facts = {"verdict": self.verdict, "method": self.method, **dict(self.facts)}
        if self.fixed_points:
            facts["fixed_points"] = [[str(v) for v in vec] for vec in self.fixed_points]
        if self.stable is True:
            return Outcome(Decision.PROVED, Evidence(Method.INTERVAL_ARITHMETIC, facts=facts | {"parameters": dict(witness or {})}),
                           self.reason)
        if self.stable is False:
            return Outcome(Decision.DISPROVED, Evidence(Method.INTERVAL_ARITHMETIC, witness=dict(witness or {}), facts=facts),
                           self.reason)
        return Outcome(Decision.UNDECIDED, Evidence(Method.INTERVAL_ARITHMETIC, facts=facts), self.reason)


def _fmpq(value: Any) -> flint.fmpq:
    q = Fraction(value)
    return flint.fmpq(q.numerator, q.denominator)


def _fmpq_mat(rows: np.ndarray) -> flint.fmpq_mat:
    r, c = rows.shape
    return flint.fmpq_mat(r, c, [_fmpq(rows[i, j]) for i in range(r) for j in range(c)])


def _fixed_point_system(loop: Loop) -> flint.fmpq_mat:
    """The exact linear conditions on a loop state ``[x; eta]`` fixed by the sample map.

    ``M [x; eta] = [x; eta]`` says ``e^{F T} [x; u] = [x; u]`` for the held force
    ``u = Cc eta + Dc C x`` (``F = [[A, Bu], [0, 0]]``) and ``(I - Ac) eta = Bc C x``. Now
    ``e^{FT} - I = FT phi(FT)`` with ``phi(w) = (e^w - 1)/w``, invertible unless an eigenvalue of
    ``FT`` is a non-zero multiple of ``2 pi j``; the eigenvalues of a rational ``F`` are
    algebraic and ``T`` is rational, so none is (pi is transcendental). Hence the first condition
    is ``A x + Bu u = 0``: an equilibrium, a rational linear system.
    """
    n, m = loop.bu.shape
    ctrl = loop.ctrl
    nc = ctrl.a.shape[0]
    zero = Fraction(0)
    # u = Dc C x + Cc eta over [x; eta]
    u_x = ctrl.d @ loop.c if m else np.zeros((0, n), dtype=object)
    top = np.zeros((n, n + nc), dtype=object)
    top[...] = zero
    top[:, :n] = loop.a + (loop.bu @ u_x if m else zero)
    if nc:
        top[:, n:] = loop.bu @ ctrl.c
        bottom = np.zeros((nc, n + nc), dtype=object)
        bottom[...] = zero
        bottom[:, :n] = -(ctrl.b @ loop.c)
        bottom[:, n:] = np.eye(nc, dtype=object) * Fraction(1) - ctrl.a
        rows = np.vstack([top, bottom])
    else:
        rows = top
    return _fmpq_mat(rows)


def _kernel(system: flint.fmpq_mat) -> tuple[list[list[flint.fmpq]], list[int]]:
    """An exact basis of the null space (each vector 1 at its free column, 0 at the others) and
    the pivot columns."""
    size = system.ncols()
    if system.nrows() == 0:
        return [[flint.fmpq(1 if i == j else 0) for i in range(size)] for j in range(size)], []
    reduced, rank = system.rref()
    pivots = []
    for r in range(rank):
        pivots.append(next(c for c in range(size) if reduced[r, c] != 0))
    free = [c for c in range(size) if c not in pivots]
    basis = []
    for f in free:
        vec = [flint.fmpq(0)] * size
        vec[f] = flint.fmpq(1)
        for r, p in enumerate(pivots):
            vec[p] = -reduced[r, f]
        basis.append(vec)
    return basis, pivots


def _nilpotent(a: np.ndarray) -> bool:
    """``A`` nilpotent (exactly): the ZOH exponential is then a finite sum, rational."""
    n = a.shape[0]
    return n == 0 or _fmpq_mat(a).charpoly() == flint.fmpq_poly([0] * n + [1])


def _exact_closed_loop(loop: Loop) -> flint.fmpq_mat:
    """The closed-loop matrix over Q when ``A`` is nilpotent: ``exp(F T)`` summed exactly."""
    n, m = loop.bu.shape
    size = n + m
    T = _fmpq(loop.T)
    gen = flint.fmpq_mat(size, size)
    for i in range(n):
        for j in range(n):
            gen[i, j] = _fmpq(loop.a[i, j]) * T
        for j in range(m):
            gen[i, n + j] = _fmpq(loop.bu[i, j]) * T
    E = flint.fmpq_mat(size, size, [1 if i == j else 0 for i in range(size) for j in range(size)])
    term = E
    for k in range(1, size + 1):
        term = term * gen * flint.fmpq(1, k)
        if all(term[i, j] == 0 for i in range(size) for j in range(size)):
            break
        E = E + term
    ctrl = loop.ctrl
    nc = ctrl.a.shape[0]
    phi = flint.fmpq_mat(n, n, [E[i, j] for i in range(n) for j in range(n)])
    gamma = flint.fmpq_mat(n, m, [E[i, n + j] for i in range(n) for j in range(m)])
    top_left = phi + (gamma * _fmpq_mat(ctrl.d @ loop.c) if m else 0)
    out = flint.fmpq_mat(n + nc, n + nc)
    for i in range(n):
        for j in range(n):
            out[i, j] = top_left[i, j]
    if nc:
        top_right, bottom_left, ac = gamma * _fmpq_mat(ctrl.c), _fmpq_mat(ctrl.b @ loop.c), _fmpq_mat(ctrl.a)
        for i in range(n):
            for j in range(nc):
                out[i, n + j] = top_right[i, j]
        for i in range(nc):
            for j in range(n):
                out[n + i, j] = bottom_left[i, j]
            for j in range(nc):
                out[n + i, n + j] = ac[i, j]
    return out


def _fraction_vectors(basis: list[list[flint.fmpq]]) -> tuple[tuple[Fraction, ...], ...]:
    return tuple(tuple(Fraction(int(v.p), int(v.q)) for v in vec) for vec in basis)


def _on_circle_text(count: int) -> str:
    return (f"z = 1 is an exact eigenvalue of the closed loop ({count} independent fixed state"
            f"{'s' if count > 1 else ''}: a mode whose position nothing feeds back), so rho >= 1")


def _decide_exact(loop: Loop, basis: list, translation: bool) -> LoopStability:
    """A loop whose plant matrix ``A`` is nilpotent: exact characteristic and minimal polynomials,
    roots located exactly relative to the circle (:func:`hapticproof.exact.kernel.locate_roots`)."""
    from hapticproof.exact.kernel import locate_roots, poly_json

    matrix = _exact_closed_loop(loop)
    fixed = _fraction_vectors(basis)
    if matrix.nrows() == 0:
        return LoopStability(STABLE, True, fixed, translation, "exact-charpoly", 0, "the loop has no state")
    chi = matrix.charpoly()
    cert = locate_roots(chi, "disk")
    on = sum(r.multiplicity * (1 if r.value is not None else 2) for r in cert.boundary)
    facts = {"characteristic_polynomial": poly_json(chi), "outside": cert.outside, "on_circle": on,
             "on_circle_roots": [r.label() for r in cert.boundary]}
    if cert.outside:
        verdict, reason = UNSTABLE, f"{cert.outside} root(s) of the exact characteristic polynomial outside the unit circle"
    elif not cert.boundary:
        verdict, reason = STABLE, "every root of the exact characteristic polynomial strictly inside the unit circle"
    else:
        mu = matrix.minpoly()
        repeated = mu.gcd(mu.derivative())
        jordan = repeated.degree() > 0 and bool(locate_roots(repeated, "disk").boundary)
        roots = ", ".join(r.label() for r in cert.boundary)
        if jordan:
            verdict, reason = UNSTABLE, (f"rho = 1 exactly with a Jordan block on the circle (roots {roots} repeated in the "
                                         "minimal polynomial): the response grows polynomially")
        else:
            verdict, reason = MARGINAL, (f"rho = 1 exactly: roots {roots} on the unit circle, semisimple, none outside "
                                         "(bounded, not asymptotically stable)")
    relative: bool | None = verdict == STABLE
    if translation:
        rest = chi // flint.fmpq_poly([-1, 1])
        rest_cert = locate_roots(rest, "disk") if rest.degree() > 0 else None
        relative = rest_cert is None or (rest_cert.outside == 0 and not rest_cert.boundary)
    return LoopStability(verdict, relative, fixed, translation, "exact-charpoly", 0, reason, facts)


def _deflated_arb(matrix: flint.arb_mat, basis: list, pivots: list[int]) -> flint.arb_mat:
    """``M22`` of ``P^-1 M P = [[I, X], [0, M22]]``: ``P`` holds the exact fixed vectors of ``M``
    and the unit vectors of the pivot columns (invertible), so the eigenvalues of ``M`` are
    ``1`` (once per fixed vector) and those of ``M22``."""
    size, d = matrix.nrows(), len(basis)
    P = flint.fmpq_mat(size, size)
    for k, vec in enumerate(basis):
        for i in range(size):
            P[i, k] = vec[i]
    for k, p in enumerate(pivots):
        P[p, d + k] = 1
    Pinv = P.inv()
    moved = flint.arb_mat(Pinv) * matrix * flint.arb_mat(P)
    rest = size - d
    return flint.arb_mat(rest, rest, [moved[d + i, d + j] for i in range(rest) for j in range(rest)])


def decide_stability(scene: Scene, max_bits: int = 0) -> LoopStability:
    """The one stability decision of a sampled-data loop (single user, m users, teleoperator).

    1. The eigenvalue ``z = 1`` is decided exactly: the loop's fixed states are the rational
       solutions of the equilibrium equations (see :func:`_fixed_point_system`). Any of them
       makes ``rho >= 1``: never ``stable``.
    2. A plant without dissipation or springs (``A`` nilpotent, e.g. a mass with ``b = 0``)
       has an exact rational ZOH matrix: its characteristic polynomial is located exactly
       (marginal cases included; a Jordan block on the circle is unstable).
    3. Otherwise the exact eigenvalues ``z = 1`` are deflated by an exact similarity and the
       rest decided in ball arithmetic (characteristic polynomial, Routh array after the
       bilinear map), the precision doubling up to ``max_bits`` (default :data:`DECIDE_BITS`).

    >>> from hapticproof.systems.loops import SingleUser, MultiUser
    >>> decide_stability(SingleUser(m="0.015", b="0.02", T="0.001", K=30)).verdict
    'stable'
    >>> d = decide_stability(SingleUser(m="0.02", b="0.01", T="0.001", K=0, B="0.001"))
    >>> d.verdict, d.value, d.fixed_points
    ('marginal', 0, ((Fraction(1, 1), Fraction(0, 1), Fraction(1, 1)),))
    >>> decide_stability(SingleUser(m=1, b=0, T="0.1", K=0)).verdict         # a free mass: a Jordan block at z = 1
    'unstable'
    >>> decide_stability(MultiUser.uniform(3, m="0.02", b="0.01", T="0.001", K=0, B="0.002")).verdict
    'marginal'
    """
    loop = scene.loop("exact")
    translation = loop.rigid is not None
    basis, pivots = _kernel(_fixed_point_system(loop))
    fixed = _fraction_vectors(basis)
    if _nilpotent(loop.a):
        return _decide_exact(loop, basis, translation)
    d = len(basis)
    scale_bits = _scale_bits(loop)
    precision, top = max(128, 64 + 2 * scale_bits), max(max_bits or DECIDE_BITS, 128 + 2 * scale_bits)
    rest: bool | None = None
    bits = precision
    while precision <= top:
        bits = precision
        with flint_precision(precision):
            matrix = _closed_loop_arb(loop, deflate=False)
            if all(matrix[i, j].is_finite() for i in range(matrix.nrows()) for j in range(matrix.ncols())):
                if matrix.nrows() == d:
                    rest = True
                    break
                reduced = _deflated_arb(matrix, basis, pivots) if d else matrix
                rest = _disk_routh(reduced.charpoly())
                if rest is not None:
                    break
        precision *= 2
    facts = {"bits": bits, "fixed_states": d}
    if d == 0:
        verdict = {True: STABLE, False: UNSTABLE, None: UNDECIDED}[rest]
        reason = {True: "every eigenvalue of the exact ZOH loop strictly inside the unit circle (certified)",
                  False: "an eigenvalue of the exact ZOH loop outside the unit circle (certified)",
                  None: f"an eigenvalue of the exact ZOH loop within 2^-{bits} of the unit circle: not decided"}[rest]
        return LoopStability(verdict, rest if verdict != UNDECIDED else None, fixed, translation, "ball-routh", bits, reason, facts)
    verdict = {True: MARGINAL, False: UNSTABLE, None: ON_CIRCLE}[rest]
    reason = _on_circle_text(d) + {
        True: "; every other eigenvalue strictly inside (certified): marginal, rho = 1 exactly",
        False: "; another eigenvalue outside the unit circle (certified): unstable",
        None: f"; the others not separated from the circle at {bits} bits"}[rest]
    relative = (rest if d == 1 else False) if translation else False
    return LoopStability(verdict, relative, fixed, translation, "ball-routh", bits, reason, facts)


#: A float64 spectral radius is trusted only this far from 1, and only for a closed-loop
#: matrix whose entries stay below :data:`_TRUSTED_ENTRY` (eigenvalue errors grow with the norm).
TRUSTED_MARGIN = _TRUSTED_MARGIN = 1e-7
_TRUSTED_ENTRY = 1e8


def _float_scaled(scene: Scene) -> bool:
    """The loop's generator ``[A, Bu] T`` and controller entries are within float64's comfortable
    range (no entry above 1e8: a larger ``expm`` argument squares away every digit)."""
    try:
        with np.errstate(all="ignore"):
            loop = scene.loop("float")
            parts = [loop.a * loop.T, loop.bu * loop.T, loop.ctrl.a, loop.ctrl.b, loop.ctrl.c, loop.ctrl.d]
            return all(p.size == 0 or (np.all(np.isfinite(p)) and np.max(np.abs(p)) <= _TRUSTED_ENTRY) for p in parts)
    except (OverflowError, ValueError, ZeroDivisionError):
        return False


def trusted_radius(scene: Scene, margin: float = _TRUSTED_MARGIN) -> float | None:
    """The float64 spectral radius when it can be trusted, else ``None``: the matrix exponential
    overflowed or produced NaN, the closed loop is badly scaled (an entry above 1e8), or the
    radius lies within 1e-7 of 1 (rounding decides such a sign). Callers then take the
    certified route (:func:`certified_radius`)."""
    if not _float_scaled(scene):
        return None
    try:
        with np.errstate(all="ignore"):
            matrix = closed_loop_matrix(scene)
            if not np.all(np.isfinite(matrix)) or (matrix.size and np.max(np.abs(matrix)) > _TRUSTED_ENTRY):
                return None
            rho = float(np.max(np.abs(np.linalg.eigvals(matrix)))) if matrix.size else 0.0
    except (np.linalg.LinAlgError, OverflowError, ValueError, ZeroDivisionError):
        return None
    if not math.isfinite(rho) or abs(rho - 1) < margin:
        return None
    return rho


def trusted_radii(scenes: Sequence[Scene]) -> np.ndarray:
    """Batched float64 spectral radii (as :func:`spectral_radii`), ``NaN`` wherever
    :func:`trusted_radius` would not trust the value (overflow, a badly scaled loop, a radius
    within 1e-7 of 1)."""
    out = np.full(len(scenes), np.nan)
    keep = [i for i, scene in enumerate(scenes) if _float_scaled(scene)]
    try:
        with np.errstate(all="ignore"):
            mats = closed_loop_matrices([scenes[i] for i in keep])
    except (np.linalg.LinAlgError, OverflowError, ValueError, ZeroDivisionError):
        return out
    for i, mat in zip(keep, mats):
        if mat.size == 0:
            out[i] = 0.0
            continue
        if not np.all(np.isfinite(mat)) or np.max(np.abs(mat)) > _TRUSTED_ENTRY:
            continue
        try:
            rho = float(np.max(np.abs(np.linalg.eigvals(mat))))
        except np.linalg.LinAlgError:
            continue
        if math.isfinite(rho) and abs(rho - 1) >= _TRUSTED_MARGIN:
            out[i] = rho
    return out


def loop_json(scene: Scene) -> dict[str, Any]:
    """The exact loop of a scene as JSON (exact fractions as strings), for the judge of
    :mod:`hapticproof.exact.judge`: ``dx/dt = a x + bu u`` held over the ``period``, sampled ``y = c x``
    (``state``, ``input``, ``output``), the discrete controller ``(A, B, C, D)`` from ``y`` to ``u``
    (``state``, ``input``, ``output``, ``feedthrough``), and whether a rigid
    translation mode (an exact eigenvalue 1 no gain moves) is to be set aside."""
    loop = scene.loop("exact")

    def rows(m: np.ndarray) -> list[list[str]]:
        return [[str(Fraction(v)) for v in row] for row in m.tolist()] if m.size else [[] for _ in range(m.shape[0])]

    ctrl = loop.ctrl
    # (the sampling period under a neutral key: a report of a scene whose period is h names no T)
    # (the matrices under descriptive keys too: no single letter that reads as a scene's b or c)
    return {"period": str(Fraction(loop.T)), "state": rows(loop.a), "input": rows(loop.bu), "output": rows(loop.c),
            "controller": {"state": rows(ctrl.a), "input": rows(ctrl.b), "output": rows(ctrl.c),
                           "feedthrough": rows(ctrl.d)},
            "shape": {"plant": list(loop.a.shape), "inputs": loop.bu.shape[1], "outputs": loop.c.shape[0],
                      "controller": ctrl.a.shape[0]},
            "rigid": loop.rigid is not None}
