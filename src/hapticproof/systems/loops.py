"""Sampled-data loops as state-space models: a 1-DOF device, m users and a teleoperator, each
continuous robot with its termination, sampled by a discrete controller through a zero-order
hold (:mod:`hapticproof.analysis.sampled` discretises and decides them)."""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass
from fractions import Fraction
from typing import Any, Union

import mpmath
import numpy as np
import sympy as sp

from hapticproof.core.errors import SceneError
from hapticproof.systems.impedance import Clamped, DiscreteTF, Impedance, NumberField, Precision, Termination, check_delay, check_positive, split_impedance, to_fraction

__all__ = ["SingleUser", "MultiUser", "Teleoperator", "Scene", "Loop", "Port"]


# --------------------------------------------------------------------------------------------
# discrete state-space algebra (controllers, delays)
# --------------------------------------------------------------------------------------------
@dataclass(frozen=True, slots=True, eq=False)
class _SS:
    """Discrete state space ``x+ = a x + b y, u = c x + d y`` in one precision."""

    a: np.ndarray
    b: np.ndarray
    c: np.ndarray
    d: np.ndarray


def _static(d: np.ndarray, field: NumberField) -> _SS:
    rows, cols = d.shape
    return _SS(field.zeros(0, 0), field.zeros(0, cols), field.zeros(rows, 0), d)


def _series(first: _SS, second: _SS, field: NumberField) -> _SS:
    n1, n2 = first.a.shape[0], second.a.shape[0]
    a = field.zeros(n1 + n2, n1 + n2)
    a[:n1, :n1] = first.a
    a[n1:, :n1] = second.b @ first.c
    a[n1:, n1:] = second.a
    b = np.vstack([first.b, second.b @ first.d]) if n1 + n2 else field.zeros(0, first.b.shape[1])
    c = np.hstack([second.d @ first.c, second.c])
    return _SS(a, b, c, second.d @ first.d)


def _diag(systems: Sequence[_SS], field: NumberField) -> _SS:
    ns = [s.a.shape[0] for s in systems]
    ins = [s.b.shape[1] for s in systems]
    outs = [s.c.shape[0] for s in systems]
    n, ni, no = sum(ns), sum(ins), sum(outs)
    a, b, c, d = field.zeros(n, n), field.zeros(n, ni), field.zeros(no, n), field.zeros(no, ni)
    i = j = k = 0
    for s, dn, di, do in zip(systems, ns, ins, outs):
        a[i : i + dn, i : i + dn] = s.a
        b[i : i + dn, j : j + di] = s.b
        c[k : k + do, i : i + dn] = s.c
        d[k : k + do, j : j + di] = s.d
        i, j, k = i + dn, j + di, k + do
    return _SS(a, b, c, d)


def _delay(n: int, field: NumberField) -> _SS:
    """``z**-n`` on one channel as a shift register (no state when ``n = 0``)."""
    if n == 0:
        return _static(field.eye(1), field)
    a = field.zeros(n, n)
    for i in range(1, n):
        a[i, i - 1] = field.num(1)
    b, c = field.zeros(n, 1), field.zeros(1, n)
    b[0, 0] = field.num(1)
    c[0, n - 1] = field.num(1)
    return _SS(a, b, c, field.zeros(1, 1))


def _tf_ss(tf: DiscreteTF, field: NumberField) -> _SS:
    """Controllable canonical realisation of a proper SISO ``H(z)``."""
    num = [field.num(c) for c in tf.num]
    den = [field.num(c) for c in tf.den]
    lead = den[0]
    den = [c / lead for c in den]
    num = [field.num(0)] * (len(den) - len(num)) + [c / lead for c in num]
    n = len(den) - 1
    d = field.zeros(1, 1)
    d[0, 0] = num[0]
    if n == 0:
        return _static(d, field)
    a, b, c = field.zeros(n, n), field.zeros(n, 1), field.zeros(1, n)
    for i in range(n):
        a[0, i] = -den[i + 1]
        c[0, i] = num[i + 1] - num[0] * den[i + 1]
    for i in range(1, n):
        a[i, i - 1] = field.num(1)
    b[0, 0] = field.num(1)
    return _SS(a, b, c, d)


def _wall_ss(K: Any, B: Any, T: Any, field: NumberField) -> _SS:
    """``K + B(z-1)/(Tz)``; static when ``B = 0`` (no spurious state)."""
    k, b, t = field.num(K), field.num(B), field.num(T)
    if to_fraction(B) == 0:
        d = field.zeros(1, 1)
        d[0, 0] = k
        return _static(d, field)
    a, bb, c, d = field.zeros(1, 1), field.zeros(1, 1), field.zeros(1, 1), field.zeros(1, 1)
    bb[0, 0] = field.num(1)
    c[0, 0] = -b / t
    d[0, 0] = k + b / t
    return _SS(a, bb, c, d)


# --------------------------------------------------------------------------------------------
# continuous devices and the assembled loop
# --------------------------------------------------------------------------------------------
@dataclass(frozen=True, slots=True, eq=False)
class Port:
    """A port: its force (over ``[state; u; w]``) and velocity (over ``state``) rows.

    ``force . velocity`` is the power flowing from the termination into the system, so
    ``E(t) = int f v dt`` is the energy the system has absorbed (teleoperator (8)).
    """

    name: str
    force: np.ndarray
    velocity: np.ndarray


@dataclass(frozen=True, slots=True, eq=False)
class Loop:
    """An assembled sampled-data loop in one precision.

    Continuous plant ``dxi/dt = a xi + bu u + bw w`` with held controller forces ``u``
    (one per device) and exogenous port forces ``w``; sampled outputs ``y = c xi``
    (device positions); discrete controller ``ctrl`` from ``y`` to ``u`` (delays included).
    """

    T: Any
    a: np.ndarray
    bu: np.ndarray
    bw: np.ndarray
    c: np.ndarray
    ctrl: _SS
    ports: tuple[Port, ...]
    positions: np.ndarray
    velocities: np.ndarray
    rigid: np.ndarray | None
    precision: str

    @property
    def plant_order(self) -> int:
        return self.a.shape[0]

    @property
    def order(self) -> int:
        return self.a.shape[0] + self.ctrl.a.shape[0]


@dataclass(frozen=True, slots=True, eq=False)
class _Device:
    a: np.ndarray
    bu: np.ndarray  # (n, 1)
    bw: np.ndarray  # (n, 1)
    position: np.ndarray  # (1, n)
    velocity: np.ndarray  # (1, n)
    force: np.ndarray  # (1, n + 2): over [state, u, w]


def _device(m: Any, b: Any, term: Termination, field: NumberField) -> _Device:
    """One device ``m dv/dt = f - b v - u`` with port force ``f = w - Z(s) v``."""
    one = field.num(1)
    if isinstance(term, Clamped):
        force = field.zeros(1, 2)
        force[0, 0] = one  # the clamp's reaction balances the controller force
        z = field.zeros(0, 1)
        return _Device(field.zeros(0, 0), z, z, field.zeros(1, 0), field.zeros(1, 0), force)
    if term is None:
        q1 = q0 = k = Fraction(0)
        sp_num, sp_den = (Fraction(0),), (Fraction(1),)
    else:
        q1, q0, k, sp_num, sp_den = split_impedance(term._exact_num(), term._exact_den())
    nz = len(sp_den) - 1 if any(c != 0 for c in sp_num) else 0
    n = 2 + nz
    m_eff = field.num(to_fraction(m) + q1)
    if to_fraction(m) + q1 <= 0:
        raise SceneError("device mass plus the termination's mass term must be positive")
    b_eff = field.num(b) + field.num(q0)
    kk = field.num(k)
    # termination force (without w) as a row over the state: k x + q0 v + Csp xi
    a = field.zeros(n, n)
    term_row = field.zeros(1, n)
    term_row[0, 0] = kk
    term_row[0, 1] = field.num(q0)
    a[0, 1] = one
    if nz:
        den = [field.num(c) for c in sp_den]
        num = [field.num(0)] * (len(sp_den) - len(sp_num)) + [field.num(c) for c in sp_num]
        for i in range(nz):
            a[2, 2 + i] = -den[i + 1]
            term_row[0, 2 + i] = num[i + 1]
        for i in range(1, nz):
            a[2 + i, 2 + i - 1] = one
        a[2, 1] = one  # the strictly proper part is driven by the velocity
    a[1, 0] = -kk / m_eff
    a[1, 1] = -b_eff / m_eff
    for i in range(nz):
        a[1, 2 + i] = -term_row[0, 2 + i] / m_eff
    bu, bw = field.zeros(n, 1), field.zeros(n, 1)
    bu[1, 0] = -one / m_eff
    bw[1, 0] = one / m_eff
    position, velocity = field.zeros(1, n), field.zeros(1, n)
    position[0, 0] = one
    velocity[0, 1] = one
    # f = w - q1 dv/dt - (k x + q0 v + Csp xi)
    q1f = field.num(q1)
    force = field.zeros(1, n + 2)
    force[0, :n] = -q1f * a[1, :] - term_row[0, :]
    force[0, n] = -q1f * bu[1, 0]
    force[0, n + 1] = one - q1f * bw[1, 0]
    return _Device(a, bu, bw, position, velocity, force)


def _assemble(
    T: Any,
    devices: Sequence[_Device],
    names: Sequence[str],
    ctrl: _SS,
    field: NumberField,
    rigid_pattern: Sequence[Any] | None,
) -> Loop:
    sizes = [d.a.shape[0] for d in devices]
    n, nd = sum(sizes), len(devices)
    a, bu, bw = field.zeros(n, n), field.zeros(n, nd), field.zeros(n, nd)
    pos, vel = field.zeros(nd, n), field.zeros(nd, n)
    ports = []
    offset = 0
    for i, (dev, size) in enumerate(zip(devices, sizes)):
        sl = slice(offset, offset + size)
        a[sl, sl] = dev.a
        bu[sl, i : i + 1] = dev.bu
        bw[sl, i : i + 1] = dev.bw
        pos[i, sl] = dev.position[0]
        vel[i, sl] = dev.velocity[0]
        force = field.zeros(1, n + 2 * nd)
        force[0, sl] = dev.force[0, :size]
        force[0, n + i] = dev.force[0, size]
        force[0, n + nd + i] = dev.force[0, size + 1]
        ports.append(Port(names[i], force[0], vel[i].copy()))
        offset += size
    rigid = None
    if rigid_pattern is not None:
        rigid = _rigid_vector(pos, [field.num(p) for p in rigid_pattern], ctrl, field)
    return Loop(field.num(T), a, bu, bw, pos.copy(), ctrl, tuple(ports), pos, vel, rigid, field.name)


def _rigid_vector(pos: np.ndarray, pattern: list, ctrl: _SS, field: NumberField) -> np.ndarray:
    """Closed-loop eigenvector (eigenvalue 1) of a rigid translation the controller ignores.

    The caller has checked exactly that the controller's output is zero for this constant
    position pattern; the controller states then settle at ``(I - Ac) eta = Bc y``.
    """
    xi = pos.T @ np.array(pattern, dtype=field.dtype)
    y = pos @ xi
    nc = ctrl.a.shape[0]
    if not nc:
        return xi
    lhs = field.eye(nc) - ctrl.a
    rhs = ctrl.b @ y
    if field.name == "float":
        eta = np.linalg.lstsq(lhs.astype(float), rhs.astype(float), rcond=None)[0]
    elif field.name == "exact":
        eta = np.array(_solve_exact(lhs, rhs), dtype=object)
    else:
        sol = mpmath.qr_solve(mpmath.matrix(lhs.tolist()), mpmath.matrix(rhs.tolist()))[0]
        eta = np.array([sol[i] for i in range(nc)], dtype=object)
    return np.concatenate([xi, eta])


def _solve_exact(lhs: np.ndarray, rhs: np.ndarray) -> list[Fraction]:
    """A solution of the consistent system ``lhs eta = rhs`` over the rationals (Gaussian
    elimination; free unknowns set to 0, as a least-squares solution need not be)."""
    rows, cols = lhs.shape
    aug = [[Fraction(lhs[i, j]) for j in range(cols)] + [Fraction(rhs[i])] for i in range(rows)]
    pivots, r = [], 0
    for col in range(cols):
        pivot = next((i for i in range(r, rows) if aug[i][col] != 0), None)
        if pivot is None:
            continue
        aug[r], aug[pivot] = aug[pivot], aug[r]
        lead = aug[r][col]
        aug[r] = [v / lead for v in aug[r]]
        for i in range(rows):
            if i != r and aug[i][col] != 0:
                factor = aug[i][col]
                aug[i] = [a - factor * b for a, b in zip(aug[i], aug[r])]
        pivots.append(col)
        r += 1
    if any(all(v == 0 for v in row[:-1]) and row[-1] != 0 for row in aug):
        raise SceneError("the controller's rigid-mode states have no steady state")
    eta = [Fraction(0)] * cols
    for i, col in enumerate(pivots):
        eta[col] = aug[i][-1]
    return eta


def _free(term: Termination) -> bool:
    """The termination exerts no static force on a displaced device (no spring, no clamp)."""
    return term is None or (isinstance(term, Impedance) and term.stiffness == 0)


# --------------------------------------------------------------------------------------------
# scenes
# --------------------------------------------------------------------------------------------
def _check_termination(name: str, term: Any) -> None:
    if term is not None and not isinstance(term, (Impedance, Clamped)):
        raise SceneError(f"{name} must be an Impedance, CLAMPED or None, got {term!r}")


@dataclass(frozen=True, slots=True)
class SingleUser:
    """A single-user haptic device on a discrete virtual environment (HVE paper Fig. 4a).

    ``m dv/dt = f_h - b v - u``, ``u = z**-n H(z) x*`` through a zero-order hold, with
    ``H(z) = K + B(z-1)/(Tz)`` unless ``environment`` is given, and ``f_h = f_ext - Z_h(s) v``.

    Parameters
    ----------
    m, b : number
        Device mass (> 0) and damping.
    T : number
        Sampling period (> 0).
    K, B : number
        Virtual wall stiffness and damping (ignored when ``environment`` is given).
    delay : int
        Delay ``n = t_d / T`` in samples (>= 0).
    operator : Impedance, optional
        Operator impedance ``Z_h(s)``; ``None`` is the free device (Colgate, Gil).
    environment : DiscreteTF, optional
        A general virtual environment ``H(z)``.

    Examples
    --------
    HVE Fig. 8a at T = 1 ms, z_a = 0.5 b:

    >>> from hapticproof.analysis.sampled import is_stable
    >>> scene = SingleUser(m=0.015, b=0.02, T=0.001, K=15, operator=Impedance.active_spring(0.01))
    >>> is_stable(scene), is_stable(SingleUser(m=0.015, b=0.02, T=0.001, K=25,
    ...                                        operator=Impedance.active_spring(0.01)))
    (True, False)
    """

    m: Any
    b: Any
    T: Any
    K: Any = 0
    B: Any = 0
    delay: int = 0
    operator: Impedance | None = None
    environment: DiscreteTF | None = None

    def __post_init__(self) -> None:
        check_positive("m", self.m)
        check_positive("T", self.T)
        for name in ("b", "K", "B"):
            to_fraction(getattr(self, name), name)
        check_delay("delay", self.delay)
        if self.operator is not None and not isinstance(self.operator, Impedance):
            raise SceneError(f"operator must be an Impedance or None, got {self.operator!r}")
        if self.environment is not None and not isinstance(self.environment, DiscreteTF):
            raise SceneError("environment must be a DiscreteTF or None")

    def loop(self, precision: Precision = "float") -> Loop:
        """Assemble the loop matrices in the given precision."""
        field = NumberField(precision)
        if self.environment is None:
            h = _wall_ss(self.K, self.B, self.T, field)
        else:
            h = _tf_ss(self.environment, field)
        ctrl = _series(h, _delay(int(self.delay), field), field)
        device = _device(self.m, self.b, self.operator, field)
        return _assemble(self.T, [device], ["operator"], ctrl, field, self._rigid_pattern())

    def _rigid_pattern(self) -> tuple | None:
        """Exact test: a free device whose environment has zero DC gain keeps a rigid mode."""
        if not _free(self.operator):
            return None
        if self.environment is None:
            dc_zero = to_fraction(self.K) == 0
        else:
            num = sum(to_fraction(c) for c in self.environment.num)
            dc_zero = num == 0 and sum(to_fraction(c) for c in self.environment.den) != 0
        return (1,) if dc_zero else None


def _matrix(values: Any, size: int, name: str) -> tuple[tuple, ...]:
    rows = tuple(tuple(row) for row in values)
    if len(rows) != size or any(len(r) != size for r in rows):
        raise SceneError(f"{name} must be a {size}x{size} matrix")
    for i in range(size):
        if to_fraction(rows[i][i], name) != 0:
            raise SceneError(f"{name} must have a zero diagonal")
        for j in range(size):
            if to_fraction(rows[i][j], name) != to_fraction(rows[j][i], name):
                raise SceneError(f"{name} must be symmetric")
    return rows


@dataclass(frozen=True, slots=True)
class MultiUser:
    """An m-user haptic virtual environment (HVE paper Fig. 6/7, eqs. (37)-(39), (56)).

    Device ``i``: ``m_i dv_i/dt = f_hi - b_i v_i - u_i`` with
    ``u_i = z**-n_i sum_j H_ij(z) x_j*``, ``H_ii = K_0i + sum_k K_ik + (B_0i + sum_k B_ik)
    (z-1)/(Tz)`` and ``H_ij = -(K_ij + B_ij (z-1)/(Tz))``.

    Parameters
    ----------
    masses, dampings : tuple of numbers
        ``m_i > 0`` and ``b_i``.
    T : number
        Sampling period.
    ground_stiffness, ground_damping : tuple of numbers
        ``K_0i`` and ``B_0i``.
    coupling_stiffness, coupling_damping : tuple of tuples
        Symmetric ``K_ij`` and ``B_ij`` with zero diagonal (any graph).
    delays : tuple of int
        ``n_i`` in samples.
    operators : tuple of Impedance or None
        Per-user operator impedances.

    Examples
    --------
    HVE Fig. 8d (dual user, ``K_01 = K_02 = K_12 = K/2``) at T = 1 ms:

    >>> from hapticproof.analysis.sampled import is_stable
    >>> scene = MultiUser.uniform(2, m=0.015, b=0.01822, T=0.001, K=20)
    >>> scene.coupling_stiffness
    ((0, 10), (10, 0))
    >>> is_stable(scene)
    True
    """

    masses: tuple
    dampings: tuple
    T: Any
    ground_stiffness: tuple
    ground_damping: tuple
    coupling_stiffness: tuple
    coupling_damping: tuple
    delays: tuple
    operators: tuple

    def __post_init__(self) -> None:
        users = len(self.masses)
        if users < 1:
            raise SceneError("a multi-user scene needs at least one user")
        for name in ("masses", "dampings", "ground_stiffness", "ground_damping", "delays", "operators"):
            value = tuple(getattr(self, name))
            object.__setattr__(self, name, value)
            if len(value) != users:
                raise SceneError(f"{name} must have one entry per user ({users})")
        for i in range(users):
            check_positive(f"m_{i + 1}", self.masses[i])
            to_fraction(self.dampings[i], f"b_{i + 1}")
            to_fraction(self.ground_stiffness[i], f"K_0{i + 1}")
            to_fraction(self.ground_damping[i], f"B_0{i + 1}")
            check_delay(f"n_{i + 1}", self.delays[i])
            _check_termination(f"operator {i + 1}", self.operators[i])
        check_positive("T", self.T)
        object.__setattr__(
            self, "coupling_stiffness", _matrix(self.coupling_stiffness, users, "K_ij")
        )
        object.__setattr__(self, "coupling_damping", _matrix(self.coupling_damping, users, "B_ij"))

    @classmethod
    def uniform(
        cls,
        users: int,
        m: Any,
        b: Any,
        T: Any,
        K: Any,
        B: Any = 0,
        delay: int = 0,
        operator: Termination = None,
    ) -> MultiUser:
        """Identical users, every ground and pairwise coupling ``K/2`` and ``B/2``.

        This is the HVE paper's Fig. 8d/e setting (``K_01 = K_02 = K_12 = K/2``).
        """
        if isinstance(users, bool) or not isinstance(users, int) or users < 1:
            raise SceneError(f"users must be a positive integer, got {users!r}")
        half_k, half_b = _half(K, "K"), _half(B, "B")
        off = lambda v: tuple(tuple(0 if i == j else v for j in range(users)) for i in range(users))  # noqa: E731
        return cls(
            masses=(m,) * users,
            dampings=(b,) * users,
            T=T,
            ground_stiffness=(half_k,) * users,
            ground_damping=(half_b,) * users,
            coupling_stiffness=off(half_k),
            coupling_damping=off(half_b),
            delays=(delay,) * users,
            operators=(operator,) * users,
        )

    @property
    def users(self) -> int:
        return len(self.masses)

    def stiffness_matrix(self) -> list[list[Fraction]]:
        """``K_ii = K_0i + sum_k K_ik``, ``K_ij = -K_ij`` (exact)."""
        return _laplacian(self.ground_stiffness, self.coupling_stiffness)

    def damping_matrix(self) -> list[list[Fraction]]:
        """``B_ii = B_0i + sum_k B_ik``, ``B_ij = -B_ij`` (exact)."""
        return _laplacian(self.ground_damping, self.coupling_damping)

    def loop(self, precision: Precision = "float") -> Loop:
        field = NumberField(precision)
        users = self.users
        kmat, bmat = self.stiffness_matrix(), self.damping_matrix()
        t = field.num(self.T)
        k_arr = np.array([[field.num(v) for v in row] for row in kmat], dtype=field.dtype)
        b_arr = np.array([[field.num(v) for v in row] for row in bmat], dtype=field.dtype)
        if any(v != 0 for row in bmat for v in row):
            # u = (K + B/T) x_k - (B/T) x_{k-1}: the state holds the previous positions
            h = _SS(field.zeros(users, users), field.eye(users), -b_arr / t, k_arr + b_arr / t)
        else:
            h = _static(k_arr, field)
        delays = _diag([_delay(int(n), field) for n in self.delays], field)
        ctrl = _series(h, delays, field)
        devices = [
            _device(self.masses[i], self.dampings[i], self.operators[i], field) for i in range(users)
        ]
        names = [f"operator {i + 1}" for i in range(users)]
        grounded = any(sum(row) != 0 for row in kmat) or not all(map(_free, self.operators))
        return _assemble(self.T, devices, names, ctrl, field, None if grounded else (1,) * users)


def _half(value: Any, name: str) -> Any:
    """``value / 2`` keeping the caller's number type (floats stay floats, exact stays exact)."""
    if isinstance(value, (float, np.floating)):
        return float(value) / 2
    frac = to_fraction(value, name) / 2
    if isinstance(value, sp.Basic):
        return sp.Rational(frac.numerator, frac.denominator)
    return frac.numerator if frac.denominator == 1 else frac


def _laplacian(ground: tuple, coupling: tuple) -> list[list[Fraction]]:
    n = len(ground)
    out = [[Fraction(0)] * n for _ in range(n)]
    for i in range(n):
        out[i][i] = to_fraction(ground[i]) + sum(to_fraction(coupling[i][k]) for k in range(n))
        for j in range(n):
            if j != i:
                out[i][j] = -to_fraction(coupling[i][j])
    return out


@dataclass(frozen=True, slots=True)
class Teleoperator:
    """A position-error-based sampled-data teleoperator (teleoperator paper Fig. 2, (1)-(7)).

    Master and slave: ``m_m dv_m/dt = f_h - b_m v_m - u_m`` and
    ``m_s dv_s/dt = f_e - b_s v_s - u_s`` with ``u_m = alpha C(z) e*``, ``u_s = -C(z) e*``
    through zero-order holds, ``e = alpha x_m - x_s`` ((30)-(31); ``alpha = 1`` is (6), (17)),
    and ``C(z) = K + B(z-1)/(Tz)`` (33) unless ``controller`` is given. ``delay`` is a
    communication delay in samples on the remote position (0 in the paper).

    Parameters
    ----------
    m_m, m_s, b_m, b_s : number
        Masses (> 0) and dampings.
    T, K, B, alpha : number
        Sampling period, PD gains, position scaling.
    master, slave : Impedance, CLAMPED or None
        Terminations; ``None`` is free motion (zero impedance).
    controller : DiscreteTF, optional
        A general ``C(z)``.
    delay : int
        Communication delay in samples.

    Examples
    --------
    Free/free (FF) teleoperator of the paper's Fig. 3 at T = 15 ms (Table I):

    >>> from hapticproof.analysis.sampled import is_stable
    >>> tele = Teleoperator.symmetric(m=0.015, b=0.01822, T=0.015, K=1.0)
    >>> is_stable(tele), is_stable(Teleoperator.symmetric(m=0.015, b=0.01822, T=0.015, K=2.0))
    (True, False)
    """

    m_m: Any
    m_s: Any
    b_m: Any
    b_s: Any
    T: Any
    K: Any = 0
    B: Any = 0
    alpha: Any = 1
    master: Termination = None
    slave: Termination = None
    controller: DiscreteTF | None = None
    delay: int = 0

    def __post_init__(self) -> None:
        for name in ("m_m", "m_s", "T"):
            check_positive(name, getattr(self, name))
        for name in ("b_m", "b_s", "K", "B", "alpha"):
            to_fraction(getattr(self, name), name)
        if to_fraction(self.alpha) == 0:
            raise SceneError("alpha must be non-zero")
        _check_termination("master", self.master)
        _check_termination("slave", self.slave)
        check_delay("delay", self.delay)
        if self.controller is not None and not isinstance(self.controller, DiscreteTF):
            raise SceneError("controller must be a DiscreteTF or None")

    @classmethod
    def symmetric(cls, m: Any, b: Any, T: Any, K: Any = 0, B: Any = 0, **kwargs: Any) -> Teleoperator:
        """Identical master and slave robots (the paper's simulations and experiments)."""
        return cls(m_m=m, m_s=m, b_m=b, b_s=b, T=T, K=K, B=B, **kwargs)

    def loop(self, precision: Precision = "float") -> Loop:
        field = NumberField(precision)
        one = field.num(1)
        al = field.num(self.alpha)
        n = int(self.delay)
        # y = [x_m, x_s] -> [x_m, x_s, z^-n x_m, z^-n x_s]
        split = _SS(
            field.zeros(0, 0), field.zeros(0, 2), field.zeros(4, 0),
            np.array([[one, 0], [0, one], [one, 0], [0, one]], dtype=field.dtype),
        )
        delayed = _diag(
            [_static(field.eye(2), field), _delay(n, field), _delay(n, field)], field
        )
        # e_m = alpha x_m - z^-n x_s (seen by the master), e_s = alpha z^-n x_m - x_s
        errors = _static(np.array([[al, 0, 0, -one], [0, -one, al, 0]], dtype=field.dtype), field)
        if self.controller is None:
            c_one = _wall_ss(self.K, self.B, self.T, field)
        else:
            c_one = _tf_ss(self.controller, field)
        gains = _static(np.array([[al, 0], [0, -one]], dtype=field.dtype), field)
        ctrl = split
        for stage in (delayed, errors, _diag([c_one, c_one], field), gains):
            ctrl = _series(ctrl, stage, field)
        devices = [
            _device(self.m_m, self.b_m, self.master, field),
            _device(self.m_s, self.b_s, self.slave, field),
        ]
        # e = alpha x_m - x_s vanishes on the translation (1, alpha): a rigid mode unless a
        # termination holds its robot in place
        free = _free(self.master) and _free(self.slave)
        return _assemble(
            self.T, devices, ["master", "slave"], ctrl, field, (1, self.alpha) if free else None
        )


Scene = Union[SingleUser, MultiUser, Teleoperator]
