r"""Input energy of a terminated port network under sinusoidal forces, exact between samples.

The 3-DOF bilateral paper checks absolute stability in time: drive one port with sine forces,
terminate the other with a passive impedance, and watch the input energy
``E_s(t) = int_0^t F_h(tau)^T V_h(tau) dtau`` of its eq. (6) (Fig. 2, Fig. 3).

Here the network ``F = Z V`` (``Z`` exact rational) with terminations ``F_k = -T_k V_k + f_k`` at
the terminated ports and pure force sources at the driven port gives the exact transfer matrix
``G = ((Z + T)^-1)[driven, driven]`` from the applied forces to the driven port's velocities. It
is realized in state space (controllable canonical form per column, balanced), the forces by
an undamped oscillator in the state, and the energy is propagated sample to sample with the
exact transition matrix ``expm(A h)`` and the exact quadratic integral of Van Loan
(:func:`hapticproof.analysis.simulate.van_loan_gram`): no integration step, only rounding.

>>> import sympy as sp
>>> from hapticproof.core.symbols import s
>>> G = port_admittance(sp.Matrix([[1]]), {}, driven=(0,))          # a unit resistor
>>> trace = input_energy(G, [Sinusoid(1.0, 1.0)], t_end=2 * 3.141592653589793, steps=64)
>>> round(trace.final, 8)                                            # int sin^2 over a period
3.14159265
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from typing import Any

import numpy as np
import scipy.linalg
import sympy as sp

from hapticproof.core.errors import InputFormatError
from hapticproof.analysis.networks import as_rational_matrix
from hapticproof.exact.rationalmatrix import RationalMatrix
from hapticproof.analysis.simulate import van_loan_gram

__all__ = ["StateSpace", "realize", "port_admittance", "Sinusoid", "EnergyTrace", "input_energy"]


@dataclass(frozen=True, slots=True, eq=False)
class StateSpace:
    """``x' = a x + b u``, ``y = c x + d u`` (float64 arrays)."""

    a: np.ndarray
    b: np.ndarray
    c: np.ndarray
    d: np.ndarray

    def __post_init__(self) -> None:
        n = self.a.shape[0]
        if self.a.shape != (n, n) or self.b.shape[0] != n or self.c.shape[1] != n:
            raise ValueError("inconsistent state-space dimensions")
        if self.d.shape != (self.c.shape[0], self.b.shape[1]):
            raise ValueError("inconsistent feedthrough dimensions")

    def transfer_at(self, point: complex) -> np.ndarray:
        """``c (sI - a)^-1 b + d`` at a complex point."""
        n = self.a.shape[0]
        if n == 0:
            return self.d.astype(complex)
        return self.c @ np.linalg.solve(point * np.eye(n) - self.a, self.b) + self.d


def _floats(p) -> list[float]:
    return [float(a) for a in p.coeffs()]


def realize(G: RationalMatrix) -> StateSpace:
    """A state-space realization of a proper rational matrix: one controllable canonical block
    per input column (on the column's lcm denominator), balanced by a diagonal similarity.

    >>> from hapticproof.core.symbols import s
    >>> ss = realize(RationalMatrix.from_sympy(sp.Matrix([[1/(s + 1)], [s/(s + 2)]])))
    >>> np.allclose(ss.transfer_at(1j), [[1/(1 + 1j)], [1j/(2 + 1j)]])
    True
    """
    p, m = G.shape
    blocks_a, blocks_b, blocks_c = [], [], []
    d = np.zeros((p, m))
    for j in range(m):
        column = [G[i, j] for i in range(p)]
        if any(e.num.degree() > e.den.degree() for e in column if not e.is_zero()):
            raise InputFormatError("the transfer matrix is improper: it has no state-space realization")
        den = RationalMatrix(tuple((e,) for e in column)).denominator_lcm()
        order = den.degree()
        rows = []
        for i, e in enumerate(column):
            num = e.num * (den // e.den)
            quotient, remainder = divmod(num, den)
            d[i, j] = float(quotient.coeffs()[0]) if not quotient.is_zero() else 0.0
            coeffs = _floats(remainder) + [0.0] * (order - len(remainder.coeffs()))
            rows.append(coeffs[:order])
        a = np.zeros((order, order))
        if order:
            a[:-1, 1:] = np.eye(order - 1)
            a[-1, :] = -np.array(_floats(den)[:order])
        b = np.zeros((order, 1))
        if order:
            b[-1, 0] = 1.0
        blocks_a.append(a)
        blocks_b.append(b)
        blocks_c.append(np.array(rows).reshape(p, order))
    a = scipy.linalg.block_diag(*blocks_a) if blocks_a else np.zeros((0, 0))
    n = a.shape[0]
    b = np.zeros((n, m))
    c = np.zeros((p, n))
    start = 0
    for j, (bj, cj) in enumerate(zip(blocks_b, blocks_c)):
        k = bj.shape[0]
        b[start:start + k, j] = bj[:, 0]
        c[:, start:start + k] = cj
        start += k
    if n:
        # companion forms are badly scaled: balance with an exact power-of-two similarity
        _, (scale, perm) = scipy.linalg.matrix_balance(a, permute=False, separate=True)
        a = (a * scale[None, :]) / scale[:, None]
        b = b / scale[:, None]
        c = c * scale[None, :]
    return StateSpace(a, b, c, d)


def port_admittance(Z: Any, terminations: Mapping[int, Any], driven: Sequence[int],
                    ports: Sequence[int] | None = None) -> RationalMatrix:
    """Exact ``((Z + T)^-1)[driven, driven]``: velocities at the driven port(s) per applied force.

    ``terminations`` maps a port number (its block in ``ports``, scalar ports by default) to its
    impedance matrix; unlisted ports are driven by pure force sources (zero impedance) when in
    ``driven`` and must otherwise be terminated.
    """
    from hapticproof.analysis.networks import port_blocks

    Zr = as_rational_matrix(Z)
    n = Zr.shape[0]
    blocks = port_blocks(n, ports)
    full = sp.zeros(n, n)
    for k, T in terminations.items():
        blk = blocks[k]
        Tm = sp.Matrix(T)
        if Tm.shape != (len(blk), len(blk)):
            raise InputFormatError(f"termination of port {k} must be {len(blk)}x{len(blk)}")
        for a, i in enumerate(blk):
            for b, j in enumerate(blk):
                full[i, j] = Tm[a, b]
    missing = [k for k in range(len(blocks)) if k not in terminations and k not in driven]
    if missing:
        raise InputFormatError(f"ports {missing} are neither terminated nor driven")
    Y = (Zr + RationalMatrix.from_sympy(full)).inverse()
    idx = [i for k in driven for i in blocks[k]]
    return Y.submatrix(idx, idx)


@dataclass(frozen=True, slots=True)
class Sinusoid:
    """``amplitude * sin(omega t + phase)``."""

    amplitude: float
    omega: float
    phase: float = 0.0


@dataclass(frozen=True, slots=True, eq=False)
class EnergyTrace:
    """``E_s`` at the sample times (exact up to rounding); ``minimum`` over the samples."""

    times: np.ndarray
    energy: np.ndarray

    @property
    def final(self) -> float:
        return float(self.energy[-1])

    @property
    def minimum(self) -> float:
        return float(self.energy.min())

    @property
    def argmin(self) -> float:
        return float(self.times[int(self.energy.argmin())])

    def first_negative(self, tol: float = 0.0) -> float | None:
        """First sample time where ``E_s < -tol``, or None."""
        below = np.nonzero(self.energy < -tol)[0]
        return float(self.times[below[0]]) if len(below) else None


def input_energy(system: RationalMatrix | StateSpace, inputs: Sequence[Sinusoid], t_end: float,
                 steps: int) -> EnergyTrace:
    """``E_s(t) = int_0^t f(tau)^T v(tau) dtau`` from rest for ``f_i = inputs[i]`` and
    ``v = G f`` (``G`` square: forces in, velocities out of the same port), on ``steps``
    equal intervals of ``[0, t_end]``.
    """
    ss = realize(system) if isinstance(system, RationalMatrix) else system
    p, m = ss.d.shape
    if p != m or len(inputs) != m:
        raise InputFormatError(f"need one sinusoid per driven channel ({m}), got {len(inputs)}")
    if t_end <= 0 or steps < 1:
        raise InputFormatError("t_end must be positive and steps >= 1")
    n = ss.a.shape[0]
    k = 2 * m  # oscillator states (cos, sin) per channel
    big = np.zeros((n + k, n + k))
    cu = np.zeros((m, n + k))
    for i, sine in enumerate(inputs):
        w = float(sine.omega)
        r = n + 2 * i
        big[r:r + 2, r:r + 2] = [[0.0, -w], [w, 0.0]]
        cu[i, r:r + 2] = [sine.amplitude * np.sin(sine.phase), sine.amplitude * np.cos(sine.phase)]
    big[:n, :n] = ss.a
    big[:n, :] += ss.b @ cu
    cy = np.zeros((p, n + k))
    cy[:, :n] = ss.c
    cy += ss.d @ cu
    q = (cu.T @ cy + cy.T @ cu) / 2
    h = t_end / steps
    phi = scipy.linalg.expm(big * h)
    w = van_loan_gram(big, q, h)
    z = np.zeros(n + k)
    for i in range(m):
        z[n + 2 * i] = 1.0  # cos(0) = 1, sin(0) = 0
    energy = np.zeros(steps + 1)
    for step in range(steps):
        energy[step + 1] = energy[step] + z @ w @ z
        z = phi @ z
    return EnergyTrace(np.linspace(0.0, t_end, steps + 1), energy)
