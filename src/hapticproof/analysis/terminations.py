r"""Destabilizing passive terminations of an n-port: a search with a deadline, verified exactly.

An n-port ``Z`` is potentially unstable when passive terminations ``T = diag(T_1, ..., T_K)``
(one per port; a port may be a group of DOFs terminated by a full matrix) put a zero of
``det(Z + T)`` in ``Re s > 0``: a growing natural mode of the coupled system. This module finds
such terminations and proves them:

* **search (floating point, deterministic).** At trial points ``s0 = sigma + j w`` (and real
  ``s0 = sigma``) near the axis -- the frequencies where an exact decision failed first
  (``hints``), then a grid scaled to the poles and zeros of ``Z`` -- look for port velocities
  ``v`` such that *every* terminated port delivers power, ``Re(v_k^H (Z(s0) v)_k) < 0``
  (candidates: real eigenvectors of ``Re Z(s0)``, which suffice for reciprocal networks,
  eigenvectors of the Hermitian part, the dual optimum over the port weights, seeded random
  starts; each polished by BFGS on a smooth maximum). Ports outside the velocity's support are
  clamped by large resistors.
* **design (closed form).** For each port an RLC impedance ``T_k(s) = P + Q s + R/s`` (``P, Q,
  R`` symmetric PSD) with ``T_k(s0) v_k = -(Z(s0) v)_k``: the reactive part is fixed on
  ``span(Re v, Im v)`` so that ``P`` is positive definite there, the rest of ``P`` completes it
  with a margin, and half of the loss sits in a series resonator tuned to ``|s0|`` (real at
  ``s0``), so that ``det(Z + T)`` depends on ``s`` even for resistive networks.
* **verification (exact).** The design is rounded to rationals with several strategies
  (entrywise at several precisions, exactly-PSD factor rounding ``F F^T``, a Newton correction
  of the design point), and ``det(Z + T)`` is computed exactly; the kernel certifies a root
  in ``Re s > 0`` (:func:`hapticproof.exact.kernel.locate_roots`) and every ``T_k`` positive real.
  The certificate's JSON (``determinant``) lets the independent checker re-verify
  ``det(Z + T) = num/den`` by exact evaluation and the root by Routh-Hurwitz.

The search ends by its deadline and reports what it tried (:class:`TerminationSearch`); the
outcome does not hinge on the last bits of floating point: candidates must clear margins, the
coarsest roundings come first, and only an exact check decides.

>>> import sympy as sp
>>> from hapticproof.core.symbols import s
>>> Z = sp.diag(sp.Matrix([[0, 0, 0], [0, 1, 2], [0, 2, 1]]), sp.eye(3))   # not passive, reciprocal
>>> found = search_terminations(Z, ports=(3, 3), hints=[1.0])
>>> cert = found.certificate
>>> cert.terminations_positive_real and all(r.real > 0 for r in cert.roots)
True
"""

from __future__ import annotations

import importlib
import itertools
import math
import time
from collections.abc import Callable, Iterable, Iterator, Sequence
from dataclasses import dataclass
from fractions import Fraction
from typing import Any

import flint
import numpy as np
import sympy as sp

from hapticproof.exact.kernel import RootCertificate, locate_roots, poly_json
from hapticproof.exact.rationalmatrix import RationalMatrix
from hapticproof.core.symbols import s as S_SYM

__all__ = [
    "DeterminantCertificate",
    "InstabilityCertificate",
    "TerminationSearch",
    "exact_determinant",
    "verify_certificate",
    "certify_terminations",
    "search_terminations",
    "find_destabilizing_terminations",
]


# ---------------------------------------------------------------------------------------------
# certificates
# ---------------------------------------------------------------------------------------------


@dataclass(frozen=True, eq=False)
class DeterminantCertificate:
    """``det M(s) = numerator/denominator`` in lowest terms for ``M = Z + T``, with the kernel's
    root certificate of the numerator. Serializes to the checker's ``determinant`` kind."""

    matrix: RationalMatrix
    numerator: flint.fmpq_poly
    denominator: flint.fmpq_poly
    roots: RootCertificate | None

    @property
    def rhp_zero(self) -> bool:
        return self.roots is not None and self.roots.outside > 0

    def to_json(self) -> dict[str, Any]:
        return {"certificate": "determinant", "variable": "s", "claim": "det(Z + T) has a zero in Re s > 0",
                "matrix": self.matrix.transfer_json()["entries"], "numerator": poly_json(self.numerator),
                "denominator": poly_json(self.denominator), "rhp_zero": self.rhp_zero,
                "roots": None if self.roots is None else self.roots.to_json()}


@dataclass(frozen=True)
class InstabilityCertificate:
    """Passive terminations ``T_k(s) = P_k + Q_k s + R_k/s`` (``P, Q, R`` symmetric PSD, so each
    ``T_k`` is positive real: an RLC network) under which ``det(Z + T)`` has a zero in
    ``Re s > 0`` -- a growing natural mode of the coupled system. ``roots`` are the certified
    right-half-plane zeros (approximate values of exact roots); ``terminations`` are exact SymPy
    matrices; ``determinant`` and ``termination_checks`` (positive realness of each ``T_k``)
    carry the certificates the checker re-verifies."""

    terminations: tuple[sp.Matrix, ...]
    roots: tuple[complex, ...]
    numerator_degree: int
    frequency: float
    terminations_positive_real: bool
    determinant: DeterminantCertificate | None = None
    termination_checks: tuple[Any, ...] = ()
    design_point: complex | None = None
    strategy: str = ""

    def to_json(self) -> dict[str, Any]:
        from hapticproof.core.evidence import to_jsonable

        out = {"terminations": [to_jsonable(T) for T in self.terminations],
               "rhp_roots": [f"{r.real:.6g}{r.imag:+.6g}j" for r in self.roots],
               "numerator_degree": self.numerator_degree, "search_frequency": self.frequency,
               "terminations_positive_real": self.terminations_positive_real}
        if self.design_point is not None:
            out["design_point"] = f"{self.design_point.real:.6g}{self.design_point.imag:+.6g}j"
        if self.strategy:
            out["strategy"] = self.strategy
        if self.determinant is not None:
            out["determinant"] = self.determinant.to_json()
        if self.termination_checks:
            out["termination_checks"] = [t.to_json() for t in self.termination_checks]
        return out


def _as_matrix(Z: Any) -> RationalMatrix:
    if isinstance(Z, RationalMatrix):
        return Z
    return RationalMatrix.from_sympy(Z)


def _blocks(n: int, ports: Sequence[int] | None) -> tuple[tuple[int, ...], ...]:
    from hapticproof.analysis.youla import port_blocks

    return port_blocks(n, ports)


def _coupled(Z: RationalMatrix, terminations: Sequence[Any], blocks) -> RationalMatrix:
    n = Z.shape[0]
    full = sp.zeros(n, n)
    for blk, T in zip(blocks, terminations):
        T = sp.Matrix(T)
        for a, i in enumerate(blk):
            for b, j in enumerate(blk):
                full[i, j] = T[a, b]
    return Z + RationalMatrix.from_sympy(full)


def exact_determinant(Z: Any, terminations: Sequence[Any], blocks) -> DeterminantCertificate:
    """``det(Z + diag(T_k))`` exactly, with the kernel's root certificate of its numerator.

    >>> cert = exact_determinant(sp.Matrix([[1, 3], [3, 1]]), [sp.Matrix([[4/(S_SYM + 1)]])] * 2, ((0,), (1,)))
    >>> cert.rhp_zero, cert.roots.outside_points                # (1 + 4/(s+1))^2 = 9 at s = 1
    (True, ((1+0j),))
    """
    M = _coupled(_as_matrix(Z), terminations, blocks)
    det = M.determinant()
    roots = locate_roots(det.num, "halfplane") if not det.num.is_zero() and det.num.degree() > 0 else None
    return DeterminantCertificate(M, det.num, det.den, roots)


def verify_certificate(Z: Any, terminations: Sequence[sp.Matrix], blocks) -> tuple[list[complex], int]:
    """Exact: the open-RHP zeros of ``det(Z + diag(T_k))`` (certified) and the numerator degree.

    >>> Z = sp.diag(sp.Matrix([[0, 0, 0], [0, 1, 2], [0, 2, 1]]), sp.eye(3))
    >>> roots, degree = verify_certificate(Z, [sp.diag(1, 2/(S_SYM + 1), 2/(S_SYM + 1)), sp.eye(3)], ((0, 1, 2), (3, 4, 5)))
    >>> roots, degree                                   # det = 8((1 + 2/(s+1))^2 - 4): a zero at s = 1
    ([(1+0j)], 2)
    """
    cert = exact_determinant(Z, terminations, blocks)
    roots = list(cert.roots.outside_points) if cert.roots is not None else []
    return roots, cert.numerator.degree() if not cert.numerator.is_zero() else -1


def certify_terminations(Z: Any, terminations: Sequence[sp.Matrix], blocks, frequency: float = math.nan,
                         design_point: complex | None = None, strategy: str = "") -> InstabilityCertificate | None:
    """An :class:`InstabilityCertificate` when ``det(Z + T)`` has a certified zero in
    ``Re s > 0`` and every termination is positive real (exact), else None.

    >>> cert = certify_terminations(sp.Matrix([[1, 3], [3, 1]]), [sp.Matrix([[4/(S_SYM + 1)]])] * 2, ((0,), (1,)))
    >>> cert.roots, cert.terminations_positive_real
    (((1+0j),), True)
    """
    from hapticproof.core.evidence import Decision
    from hapticproof.analysis.nport import positive_real

    det = exact_determinant(Z, terminations, blocks)
    if not det.rhp_zero:
        return None
    checks = tuple(positive_real(T) for T in terminations)
    passive = all(c.decision == Decision.PROVED for c in checks)
    if not passive:
        return None
    return InstabilityCertificate(tuple(sp.Matrix(T) for T in terminations), tuple(det.roots.outside_points),
                                  det.numerator.degree(), float(frequency), passive, det, checks, design_point, strategy)


# ---------------------------------------------------------------------------------------------
# the search report
# ---------------------------------------------------------------------------------------------


@dataclass(frozen=True)
class TerminationSearch:
    """What a termination search did: the certificate (or None), the time it took against its
    deadline, whether it tried everything before the deadline (``complete``), the trial points
    ``s0``, the port subsets, how many float candidates it designed and how many it verified
    exactly, the restarts per point, the rounding strategies, and how many (point, subset) pairs
    the port-power screen left (``promising``: the subnetwork's Hermitian part not PSD there)."""

    certificate: InstabilityCertificate | None
    seconds: float
    deadline: float
    complete: bool
    points: tuple[complex, ...] = ()
    subsets: tuple[tuple[int, ...], ...] = ()
    candidates: int = 0
    verifications: int = 0
    restarts: int = 0
    strategies: tuple[str, ...] = ()
    promising: int = 0

    def summary(self) -> str:
        tried = (f"tried {len(self.points)} trial points s0 (w from {self._range()}) x {len(self.subsets)} port subsets "
                 f"({self.promising} not excluded by the port-power screen), "
                 f"{self.candidates} candidate terminations, {self.verifications} exact verifications "
                 f"({self.restarts} random restarts per point; roundings {', '.join(self.strategies) or 'none'})")
        if self.certificate is not None:
            return f"found after {self.seconds:.1f} s: {tried}"
        if self.complete:
            return f"no destabilizing termination found ({self.seconds:.1f} s, which proves nothing): {tried}"
        return f"undecided after {self.seconds:.1f} s (deadline {self.deadline:g} s): {tried}"

    def _range(self) -> str:
        ws = sorted({abs(p.imag) if p.imag else abs(p.real) for p in self.points})
        return f"{ws[0]:.3g} to {ws[-1]:.3g}" if ws else "none"

    def to_json(self) -> dict[str, Any]:
        return {"found": self.certificate is not None, "summary": self.summary(), "seconds": round(self.seconds, 3),
                "deadline": self.deadline, "complete": self.complete,
                "points": [f"{p.real:.4g}{p.imag:+.4g}j" for p in self.points],
                "subsets": [[k + 1 for k in sub] for sub in self.subsets], "promising": self.promising,
                "candidates": self.candidates,
                "verifications": self.verifications, "restarts": self.restarts, "strategies": list(self.strategies)}


# ---------------------------------------------------------------------------------------------
# floating point: candidate velocities
# ---------------------------------------------------------------------------------------------


def _block_forms(M: np.ndarray, blocks) -> list[np.ndarray]:
    """Hermitian ``H_k`` with ``v^H H_k v = Re(v_k^H (M v)_k)`` (power delivered into port ``k``)."""
    return _port_forms(M, blocks)[0]


def _port_forms(M: np.ndarray, blocks) -> tuple[list[np.ndarray], list[np.ndarray]]:
    """Hermitian ``H_k``, ``G_k`` with ``v_k^H (M v)_k = v^H H_k v + j v^H G_k v`` (active and
    reactive power at port ``k``)."""
    n = M.shape[0]
    real, reactive = [], []
    for blk in blocks:
        E = np.zeros((n, n))
        for i in blk:
            E[i, i] = 1.0
        A = E @ M
        real.append((A + A.conj().T) / 2)
        reactive.append((A - A.conj().T) / 2j)
    return real, reactive


def _powers(forms: list[np.ndarray], v: np.ndarray) -> np.ndarray:
    return np.array([np.vdot(v, F @ v).real for F in forms])


def _sector_powers(forms: tuple[list[np.ndarray], list[np.ndarray]], v: np.ndarray, kappa: float) -> np.ndarray:
    """``Re p_k + kappa |Im p_k|`` per port (``p_k = v_k^H (M v)_k``): a passive termination at
    ``s0 = sigma + j w`` can absorb ``-p_k`` only when this is negative (``kappa = sigma/w``)."""
    real, reactive = forms
    return np.array([np.vdot(v, H @ v).real + kappa * abs(np.vdot(v, G @ v).real) for H, G in zip(real, reactive)])


def _dual(forms: list[np.ndarray]) -> tuple[float, np.ndarray]:
    """``max over port weights lambda (simplex) of lambda_min(sum lambda_k H_k)`` (concave; a
    lower estimate) and the eigenvector there. A value >= 0 proves that no velocity makes every
    port deliver power (``sum lambda_k p_k >= 0``); for two ports a negative maximum gives such a
    velocity. Equal weights (the Hermitian part of the subnetwork) first, then mirror ascent
    along the supergradient ``(v^H H_k v)_k`` of the smallest eigenvector ``v``."""
    K = len(forms)
    stack = np.array(forms)
    scale = max(1e-300, float(np.abs(stack).max()))

    def evaluate(lam):
        values, vectors = np.linalg.eigh(np.tensordot(lam, stack, axes=1))
        return float(values[0]), vectors[:, 0]

    lam = np.full(K, 1.0 / K)
    best, vector = evaluate(lam)
    best_lam = lam
    if K > 1 and best < 0:
        for step in range(1, 41):
            grad = np.array([np.vdot(vector, F @ vector).real for F in forms])
            lam = lam * np.exp(np.clip(2.0 * grad / (scale * math.sqrt(step)), -30, 30))   # ascent on g
            lam = lam / lam.sum()
            value, vector = evaluate(lam)
            if value > best:
                best, best_lam = value, lam
            if best >= 0:
                break
        best, vector = evaluate(best_lam)
    return best, vector


def _polish(forms: tuple[list[np.ndarray], list[np.ndarray]], v: np.ndarray, real: bool, scale: float,
            kappa: float) -> np.ndarray:
    """Gradient descent on the unit sphere (Armijo backtracking) of a smooth maximum
    (log-sum-exp) of ``Re p_k + kappa |Im p_k|`` over the ports, sharpened in steps: the
    smoothing error ``log(K)/beta`` must fall below the margins being sought. Plain numpy, no
    optimizer overhead; deterministic."""
    Hs, Gs = np.array(forms[0]), np.array(forms[1])
    delta = 1e-9 * scale

    def value_grad(x: np.ndarray, beta: float) -> tuple[float, np.ndarray]:
        Hx, Gx = Hs @ x, Gs @ x                         # (K, n); |x| = 1
        re = (Hx @ x.conj()).real
        im = (Gx @ x.conj()).real
        soft = np.sqrt(im * im + delta * delta)
        q = re + kappa * soft
        top = q.max()
        e = np.exp(beta * (q - top))
        weights = e / e.sum()
        parts = (Hx - re[:, None] * x) + (kappa * im / soft)[:, None] * (Gx - im[:, None] * x)
        grad = 2 * (weights @ parts)
        if real:
            grad = grad.real.astype(complex)
        return top + math.log(e.sum()) / beta, grad

    x = (v.real.astype(complex) if real else v) / np.linalg.norm(v)
    best, best_value = x, _sector_powers(forms, x, kappa).max()
    step = 1.0 / scale
    for beta in (100.0 / scale, 3e3 / scale, 1e5 / scale):
        f, g = value_grad(x, beta)
        for _ in range(40):
            norm_g = np.linalg.norm(g)
            if norm_g < 1e-12 * scale:
                break
            while step > 1e-12 / scale:
                y = x - step * g
                y = y / np.linalg.norm(y)
                fy, gy = value_grad(y, beta)
                if fy <= f - 0.25 * step * norm_g**2:
                    x, f, g = y, fy, gy
                    step *= 2.0
                    break
                step *= 0.5
            else:
                break
        value = _sector_powers(forms, x, kappa).max()
        if value < best_value:
            best, best_value = x, value
        if best_value < -1e-3 * scale:
            break
    return best / np.linalg.norm(best)


def _candidates(M: np.ndarray, blocks, rng: np.random.Generator, restarts: int, real: bool,
                dual_vector: np.ndarray | None, similarity: np.ndarray | None) -> Iterator[tuple[str, np.ndarray]]:
    """Candidate velocities, most structured first: real eigenvectors of the symmetric part of
    ``Re M`` with negative eigenvalues (every port of a reciprocal network then delivers power
    ``lambda |v_k|^2 < 0``), the same for Youla's ``D M D^-1`` (``similarity`` = the diagonal of
    ``D(s0)``), eigenvectors of the Hermitian part, the dual optimum, seeded random starts."""
    n = M.shape[0]
    X = M.real
    values, vectors = np.linalg.eigh((X + X.T) / 2)
    for k in range(n):
        if values[k] < 0:
            yield "real eigenvector", vectors[:, k].astype(complex)
    if similarity is not None and not real:
        Y = (similarity[:, None] * M / similarity[None, :]).real
        values, vectors = np.linalg.eigh((Y + Y.T) / 2)
        for k in range(n):
            if values[k] < 0:
                yield "Youla eigenvector", vectors[:, k] / similarity
    if not real:
        values, vectors = np.linalg.eigh((M + M.conj().T) / 2)
        for k in range(n):
            if values[k] < 0:
                yield "Hermitian eigenvector", vectors[:, k]
    if dual_vector is not None:
        yield "dual optimum", dual_vector
    for _ in range(restarts):
        v = rng.normal(size=n) + (0 if real else 1j * rng.normal(size=n))
        yield "random start", v.astype(complex)


def _support(v: np.ndarray, blocks, tol: float = 1e-4) -> list[int]:
    weight = np.vdot(v, v).real
    return [k for k, blk in enumerate(blocks) if np.vdot(v[list(blk)], v[list(blk)]).real > tol * weight]


# ---------------------------------------------------------------------------------------------
# floating point: the RLC design of one port
# ---------------------------------------------------------------------------------------------


def _psd_parts(B: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    w, V = np.linalg.eigh((B + B.T) / 2)
    return (V * np.maximum(w, 0)) @ V.T, (V * np.maximum(-w, 0)) @ V.T


def _port_design(v: np.ndarray, w: np.ndarray, s0: complex, resonator: float = 0.5
                 ) -> tuple[np.ndarray, np.ndarray, np.ndarray] | None:
    """Float PSD ``(P, Q, R)`` of ``T(s) = P + Q s + R/s`` with ``T(s0) v = w``, or None.

    Needs ``c = Re(v^H w) > 0`` (the port absorbs power). After a common phase that makes
    ``x = Re v`` and ``y = Im v`` orthogonal, the reactive part ``B`` (``Im T(s0)``) is fixed on
    ``span(x, y)`` so that the real part ``A`` is ``diag(c/2|x|^2, c/2|y|^2)`` there -- positive
    definite whatever ``w`` is -- and ``A`` is completed outside by a Schur complement plus a
    margin. ``A - (sigma/w)|B|`` is split between ``P`` and (the fraction ``resonator``) a series
    resonator tuned to ``|s0|`` (``G (s + |s0|^2/s)``, real at ``s0``), which makes ``det(Z + T)``
    depend on ``s`` even for a resistive ``Z``; ``Q``, ``R`` take the positive and negative parts
    of ``B``.
    """
    sigma, omega = s0.real, s0.imag
    m = v.shape[0]
    scale = np.linalg.norm(v) * np.linalg.norm(w)
    c = np.vdot(v, w).real
    if not c > 1e-9 * scale or sigma <= 0:
        return None
    t = v @ v
    phase = np.exp(-0.5j * np.angle(t)) if abs(t) > 1e-14 * np.vdot(v, v).real else 1.0
    v, w = v * phase, w * phase
    x, y, a, b = v.real, v.imag, w.real, w.imag
    if omega == 0:
        if np.linalg.norm(y) > 1e-9 * np.linalg.norm(x) or np.linalg.norm(b) > 1e-9 * np.linalg.norm(w):
            return None
        y, b = np.zeros(m), np.zeros(m)
    if np.linalg.norm(y) <= 1e-9 * np.linalg.norm(x):
        V = x[:, None]
        nx = x @ x
        B = (np.outer(b, x) + np.outer(x, b)) / nx - (x @ b) * np.outer(x, x) / nx**2
        Pm = a[:, None]
    else:
        V = np.column_stack([x, y])
        Bv = np.array([[x @ b, (y @ b - x @ a) / 2], [(y @ b - x @ a) / 2, -(y @ a)]])
        Vp = np.diag([1 / (x @ x), 1 / (y @ y)]) @ V.T
        B = Vp.T @ Bv @ Vp
        Pm = np.column_stack([a + B @ y, b - B @ x])
    Vp = np.linalg.pinv(V)
    A0 = Pm @ Vp + Vp.T @ Pm.T - Vp.T @ (V.T @ Pm) @ Vp
    A0 = (A0 + A0.T) / 2
    U = V / np.linalg.norm(V, axis=0)
    kappa = sigma / omega if omega > 0 else 0.0
    Bplus, Bminus = _psd_parts(B)
    absB = Bplus + Bminus
    core = U.T @ (A0 - kappa * absB) @ U
    core = (core + core.T) / 2
    margin = np.linalg.eigvalsh(core)[0]
    if not margin > 1e-7 * np.abs(core).max():
        return None
    r = U.shape[1]
    A = A0
    if r < m:
        full, _ = np.linalg.qr(np.column_stack([U, np.eye(m)]))
        Uperp = full[:, r:m]
        N = Uperp.T @ A0 @ U
        W = N @ np.linalg.solve(core, N.T) + margin * np.eye(m - r)
        A = A0 + Uperp @ W @ Uperp.T
    real_part = A - kappa * absB
    real_part = (real_part + real_part.T) / 2
    rho2 = sigma**2 + omega**2
    G = resonator * real_part / (2 * sigma)      # resonator G (s + rho^2/s): 2 sigma G at s0
    P = (1 - resonator) * real_part
    Q = (Bplus / omega if omega > 0 else 0 * B) + G
    R = (rho2 * Bminus / omega if omega > 0 else 0 * B) + rho2 * G
    T0 = P + Q * s0 + R / s0
    if np.linalg.norm(T0 @ v - w) > 1e-6 * np.linalg.norm(w) + 1e-300:  # pragma: no cover - a design error
        return None
    return P, Q, R


# ---------------------------------------------------------------------------------------------
# exact: rounding to rationals
# ---------------------------------------------------------------------------------------------


def _exactly_psd(M: sp.Matrix) -> bool:
    n = M.rows
    if n == 0:
        return True
    mat = flint.fmpq_mat(n, n, [flint.fmpq(int(v.p), int(v.q)) for v in M])
    char = mat.charpoly().coeffs()
    return all(char[n - k] * (-1) ** k >= 0 for k in range(1, n + 1))


def _quantum(M: np.ndarray, digits: int) -> Fraction | None:
    top = float(np.abs(M).max()) if M.size else 0.0
    if not top > 0 or not math.isfinite(top):
        return None
    return Fraction(10) ** (math.floor(math.log10(top)) - digits)


def _round_entrywise(M: np.ndarray, digits: int) -> sp.Matrix | None:
    m = M.shape[0]
    q = _quantum(M, digits)
    if q is None:
        return sp.zeros(m, m)
    S = (M + M.T) / 2
    out = sp.Matrix(m, m, lambda i, j: sp.Rational(round(Fraction(float(S[min(i, j), max(i, j)])) / q) * q))
    return out if _exactly_psd(out) else None


def _round_factor(M: np.ndarray, digits: int) -> sp.Matrix:
    """``F F^T`` with ``F`` the rounded ``V sqrt(max(Lambda, 0))``: exactly PSD by construction."""
    m = M.shape[0]
    w, V = np.linalg.eigh((M + M.T) / 2)
    keep = [k for k in range(m) if w[k] > 1e-12 * max(1e-300, abs(w).max())]
    if not keep:
        return sp.zeros(m, m)
    F = np.column_stack([V[:, k] * math.sqrt(w[k]) for k in keep])
    q = _quantum(F, digits)
    Fr = sp.Matrix(m, len(keep), lambda i, j: sp.Rational(round(Fraction(float(F[i, j])) / q) * q))
    return Fr * Fr.T


def _rational_psd(M: np.ndarray, digits: int, mode: str) -> sp.Matrix:
    if mode == "entrywise":
        out = _round_entrywise(M, digits)
        if out is not None:
            return out
    return _round_factor(M, digits)


#: roundings tried in order: coarse first (simple certificates, insensitive to the last bits)
_ROUNDINGS = (("entrywise", 2), ("entrywise", 3), ("factor", 3), ("entrywise", 5), ("factor", 6), ("entrywise", 9))


def _termination(P: np.ndarray, Q: np.ndarray, R: np.ndarray, digits: int, mode: str) -> sp.Matrix:
    s = S_SYM
    return _rational_psd(P, digits, mode) + _rational_psd(Q, digits, mode) * s + _rational_psd(R, digits, mode) / s


# ---------------------------------------------------------------------------------------------
# the search
# ---------------------------------------------------------------------------------------------


def _round_sig(value: float, digits: int = 2) -> float:
    if value <= 0 or not math.isfinite(value):
        return value
    return float(f"{value:.{digits - 1}e}")


def _characteristic_frequencies(Z: RationalMatrix) -> list[float]:
    """Magnitudes of the nonzero poles and zeros of the entries: the frequency scales of the
    network (from flint's ball-arithmetic roots, the same on every machine)."""
    out = set()
    for row in Z.rows:
        for e in row:
            for p in (e.num, e.den):
                if p.degree() < 1:
                    continue
                for factor, _ in p.numer().factor_squarefree()[1]:
                    for root, _ in factor.complex_roots():
                        value = abs(complex(float(root.real.mid()), float(root.imag.mid())))
                        if value > 0 and math.isfinite(value):
                            out.add(_round_sig(value))
    return sorted(out)


def _grid(Z: RationalMatrix, frequencies: Iterable[float] | None) -> list[float]:
    if frequencies is not None:
        return [float(w) for w in frequencies]
    scales = _characteristic_frequencies(Z)
    lo, hi = (min(scales), max(scales)) if scales else (1.0, 1.0)
    lo, hi = math.log10(lo) - 1.5, math.log10(hi) + 1.5
    count = int(min(24, max(9, round(3 * (hi - lo)) + 1)))
    return sorted({_round_sig(10 ** (lo + (hi - lo) * k / (count - 1))) for k in range(count)})


def _axis_frequencies(Z: RationalMatrix) -> list[float]:
    """Frequencies of the imaginary-axis poles of ``Z`` (from the exact pole report)."""
    from hapticproof.exact.rationalmatrix import pole_report

    out = []
    report = pole_report(Z)
    for pole, _ in report.axis:
        if pole.kind == "zero":
            out.append(0.0)
        elif pole.kind == "pair":
            out.append(math.sqrt(float(pole.a)))
    if report.certificate is not None:
        for root in report.certificate.boundary:
            if root.value is None and root.cosine is not None and hasattr(root.cosine, "approx"):
                out.append(math.sqrt(abs(float(root.cosine.approx(17)))))
    return sorted(set(out))


def _trial_points(hints: Sequence[float], grid: Sequence[float], axis: Sequence[float] = ()) -> tuple[list[complex], int]:
    """Design points ``s0``: near the hint frequencies first (``0``: small real points; ``inf``:
    large ones, for a failing residue at infinity), then the grid (complex, then real). The
    distance to the axis is a fraction of ``w`` and of the distance to the nearest imaginary-axis
    pole of ``Z`` (next to a pole a point off the axis sees a very different phase). Returns the
    points and how many of the first ones come from the hints."""
    points: list[complex] = []

    def add(p: complex) -> None:
        if p not in points:
            points.append(p)

    def near(w: float, frac: float) -> complex:
        room = min([w] + [abs(w - f) for f in axis if f > 0])
        return complex(_round_sig(frac * room, 3), w)

    fracs = (0.05, 0.2, 0.01)
    for w in hints:
        if math.isinf(w):
            for g in (10 * grid[-1], 100 * grid[-1], 1000 * grid[-1]):
                add(complex(_round_sig(g), 0.0))
                add(complex(_round_sig(0.2 * g, 3), _round_sig(g)))
            continue
        w = _round_sig(float(w), 3)
        if w > 0:
            for frac in fracs:
                add(near(w, frac))
            for f in (0.8, 1.25):
                add(near(_round_sig(w * f, 3), 0.05))
            add(complex(_round_sig(0.5 * w, 3), 0.0))
        else:
            for g in grid[: max(3, len(grid) // 2)]:
                add(complex(g, 0.0))
                add(near(g, 0.2))
    hinted = len(points)
    for w in grid:
        for frac in fracs:
            add(near(w, frac))
    for g in grid:
        add(complex(g, 0.0))
    keep = [p.real > 0 for p in points]
    return [p for p, k in zip(points, keep) if k], sum(keep[:hinted])


def _subsets(K: int, limit: int) -> list[tuple[int, ...]]:
    out = [tuple(range(K))]
    for size in range(K - 1, 0, -1):
        out += list(itertools.combinations(range(K), size))
    return out[:max(1, limit)]


def _renumber(blocks: Sequence[Sequence[int]]) -> tuple[tuple[int, ...], ...]:
    out, start = [], 0
    for blk in blocks:
        out.append(tuple(range(start, start + len(blk))))
        start += len(blk)
    return tuple(out)


def _clamp(M: np.ndarray) -> sp.Integer:
    top = float(np.abs(M).max()) if np.all(np.isfinite(M)) else 1.0
    return sp.Integer(10) ** (int(math.floor(math.log10(max(top, 1e-3)))) + 4)


def _newton_point(Z: RationalMatrix, terms: list[sp.Matrix], blocks, s0: complex) -> complex | None:
    """When the exact ``det(Z + T)`` of a rounded design has its root near ``s0`` just left of the
    axis, the design point moved by the same error the other way (``s0 + (s0 - r)``), else None."""
    try:
        det = _coupled(Z, terms, blocks).determinant()
    except ZeroDivisionError:  # pragma: no cover - defensive
        return None
    if det.num.is_zero() or det.num.degree() < 1:
        return None
    roots = [complex(float(r.real.mid()), float(r.imag.mid())) for r, _ in det.num.numer().complex_roots()]
    near = min(roots, key=lambda r: abs(r - s0))
    if abs(near - s0) > 0.5 * abs(s0) or near.real > 0:
        return None
    target = s0 + (s0 - near)
    return complex(target.real, s0.imag) if s0.imag == 0 else target


def _redesign(Z: RationalMatrix, s0: complex, idx, subset, sub_blocks, support, keep, u, resonator) -> dict | None:
    if s0.real <= 0 or (s0.imag != 0 and s0.imag < 0):
        return None
    M = Z.numpy_at(s0)
    if not np.all(np.isfinite(M)):
        return None
    Msub = M[np.ix_(idx, idx)]
    vfull = np.zeros(len(idx), dtype=complex)
    vfull[keep] = u
    wfull = -(Msub @ vfull)
    parts = {}
    for k in support:
        blk = list(sub_blocks[k])
        design = _port_design(vfull[blk], wfull[blk], s0, resonator)
        if design is None:
            return None
        parts[subset[k]] = design
    return parts


def search_terminations(
    Z: Any,
    ports: Sequence[int] | None = None,
    *,
    hints: Iterable[float] = (),
    frequencies: Iterable[float] | None = None,
    seed: int = 0,
    restarts: int = 3,
    deadline: float = 10.0,
    max_subsets: int = 8,
    clamp_all: bool = False,
    similarity: Callable[[complex], np.ndarray] | None = None,
    prefer: Sequence[Sequence[int]] = (),
    progress: Callable[[int, int], None] | None = None,
) -> TerminationSearch:
    """Search passive terminations making the coupled network unstable, verify them exactly, and
    stop by ``deadline`` seconds. Returns the report; its ``certificate`` is None when nothing
    was found (which proves nothing).

    ``hints`` are frequencies where an exact decision failed (the witnesses of positive realness,
    Llewellyn or Youla): the search starts there. ``clamp_all`` first tries large resistors on
    every port (for entries with right-half-plane poles). ``similarity(s0)`` (optional) is the
    diagonal of Youla's ``D(s0)`` with ``Z' = D Z D^-1`` reciprocal: real eigenvectors of
    ``Re Z'(s0)`` then give velocities for ``Z``. A port subset is skipped at ``s0`` when some
    positive combination of its port-power forms is PSD (then no velocity makes all of them
    deliver power). ``prefer`` lists port subsets (0-based port numbers) to try first, e.g. a
    subnetwork known to be potentially unstable. Time spent importing SciPy does not count
    against the deadline. ``progress(done, total)`` is called as the (point, subset) tasks are
    worked through (a progress bar; the report says what was covered when the deadline ends it).

    >>> import sympy as sp
    >>> out = search_terminations(sp.Matrix([[1, 3], [3, 1]]))
    >>> out.certificate is not None, out.certificate.terminations_positive_real
    (True, True)
    """
    importlib.import_module("scipy.optimize")       # imported before the clock starts

    start = time.monotonic()
    Zr = _as_matrix(Z)
    n = Zr.shape[0]
    blocks = _blocks(n, ports)
    K = len(blocks)
    points_tried: list[complex] = []
    subsets_tried: list[tuple[int, ...]] = []
    strategies_used: list[str] = []
    counts = {"candidates": 0, "verifications": 0, "promising": 0}

    def report(cert: InstabilityCertificate | None, complete: bool) -> TerminationSearch:
        if progress is not None:
            progress(1, 1)
        return TerminationSearch(cert, time.monotonic() - start, deadline, complete, tuple(points_tried),
                                 tuple(subsets_tried), counts["candidates"], counts["verifications"], restarts,
                                 tuple(strategies_used), counts["promising"])

    def out_of_time() -> bool:
        return time.monotonic() - start > deadline

    def verify(terms: list[sp.Matrix], s0: complex, strategy: str) -> InstabilityCertificate | None:
        counts["verifications"] += 1
        if strategy not in strategies_used:
            strategies_used.append(strategy)
        return certify_terminations(Zr, terms, blocks, abs(s0.imag) if s0.imag else s0.real, s0, strategy)

    if clamp_all:
        M = Zr.numpy_at(complex(1.0, 1.0))
        base = _clamp(M) if np.all(np.isfinite(M)) else sp.Integer(10**4)
        for k in (0, 1, 2, 3):
            if out_of_time():
                return report(None, False)
            terms = [base * 10**k * sp.eye(len(blk)) for blk in blocks]
            counts["candidates"] += 1
            cert = verify(terms, complex(0, 0), "resistors on every port")
            if cert is not None:
                return report(cert, False)
    grid = _grid(Zr, frequencies)
    subsets = [tuple(sorted(p)) for p in prefer]
    subsets += [sub for sub in _subsets(K, max_subsets) if sub not in subsets]
    constant = all(e.num.degree() <= 0 and e.den.degree() <= 0 for row in Zr.rows for e in row)
    resonators = (0.5,) if constant else (0.0, 0.5)
    points, hint_count = _trial_points(list(hints), grid, _axis_frequencies(Zr))
    values: dict[complex, np.ndarray] = {}
    for s0 in points:
        M = Zr.numpy_at(s0)
        if np.all(np.isfinite(M)):
            values[s0] = M
    # tasks (point, port subset): those near the hints first, then the others; within each group
    # the most negative Hermitian part of the subnetwork first (the dual bound at equal port
    # weights, one eigenvalue; rounded to two digits: no last-bit reordering); a subset whose
    # Hermitian part is PSD cannot have every port deliver power and is dropped
    scored = []
    for k, p in enumerate(p for p in points if p in values):
        if out_of_time():
            return report(None, False)
        points_tried.append(p)
        for number, subset in enumerate(subsets):
            if subset not in subsets_tried:
                subsets_tried.append(subset)
            idx = [i for b in subset for i in blocks[b]]
            Msub = values[p][np.ix_(idx, idx)]
            low = np.linalg.eigvalsh((Msub + Msub.conj().T) / 2)[0]
            relative = low / max(1e-300, float(np.abs(Msub).max()))
            if relative < -1e-9:
                scored.append((points.index(p) >= hint_count, float(f"{relative:.2g}"), k, number, p))
    tasks = [(p, number) for *_, number, p in sorted(scored, key=lambda t: t[:4])]
    counts["promising"] = len(tasks)
    for task, (s0, number) in enumerate(tasks):
        if progress is not None:
            progress(task, len(tasks))
        subset = subsets[number]
        point = points.index(s0)
        M = values[s0]
        clamp = _clamp(M)
        real = s0.imag == 0
        kappa = s0.real / s0.imag if not real else 0.0
        if out_of_time():
            return report(None, False)
        rng = np.random.default_rng([seed, point, number])     # independent of what was skipped before
        idx = [i for k in subset for i in blocks[k]]
        sub_blocks = _renumber([blocks[k] for k in subset])
        Msub = M[np.ix_(idx, idx)]
        scale = max(1e-300, float(np.abs(Msub).max()))
        bound, dual_vector = _dual(_block_forms(Msub, sub_blocks))
        if bound >= -1e-9 * scale:
            continue                       # no velocity makes every port of the subset deliver power
        similar = None
        if similarity is not None:
            D = similarity(s0)
            similar = D[idx] if D is not None and np.all(np.isfinite(D)) and np.all(D != 0) else None
        designs = polished = 0
        seen: list[np.ndarray] = []
        queue = []
        for order, (origin, v) in enumerate(_candidates(Msub, sub_blocks, rng, restarts, real,
                                                        dual_vector if K > 1 else None, similar)):
            support = _support(v, sub_blocks)
            if not support:
                continue
            keep = [i for k in support for i in sub_blocks[k]]
            forms = _port_forms(Msub[np.ix_(keep, keep)], _renumber([sub_blocks[k] for k in support]))
            u = v[keep] / np.linalg.norm(v[keep])
            start_value = _sector_powers(forms, u, kappa).max() / scale
            queue.append((float(f"{start_value:.2g}"), order, origin, support, keep, forms, u))
        queue.sort(key=lambda item: item[:2])      # most promising first (rounded: no last-bit ties)
        for _, _, origin, support, keep, forms, u in queue:
            if out_of_time():
                return report(None, False)
            if not _sector_powers(forms, u, kappa).max() < -1e-6 * scale:
                if polished >= 2:
                    continue
                polished += 1
                u = _polish(forms, u, real, scale, kappa)
                if not _sector_powers(forms, u, kappa).max() < -1e-6 * scale:
                    continue
            vfull = np.zeros(len(idx), dtype=complex)
            vfull[keep] = u
            if any(abs(np.vdot(vfull, old)) > 0.999 for old in seen):
                continue
            seen.append(vfull)
            counts["candidates"] += 1
            wfull = -(Msub @ vfull)
            found = False
            for resonator in resonators:
                parts = {}
                for k in support:
                    blk = list(sub_blocks[k])
                    design = _port_design(vfull[blk], wfull[blk], s0, resonator)
                    if design is None:
                        break
                    parts[subset[k]] = design
                if len(parts) != len(support):
                    break
                found = True
                label = f"{origin}{', series resonator' if resonator else ''}"
                for mode, digits in _ROUNDINGS:
                    if out_of_time():
                        return report(None, False)
                    terms = [_termination(*parts[k], digits, mode) if k in parts else clamp * sp.eye(len(blocks[k]))
                             for k in range(K)]
                    cert = verify(terms, s0, f"{mode} rounding to {digits + 1} digits ({label})")
                    if cert is not None:
                        return report(cert, False)
                    # Newton step on the design point: aim the rounded root back at s0
                    shifted = _newton_point(Zr, terms, blocks, s0)
                    if shifted is not None and mode == "entrywise" and digits == _ROUNDINGS[0][1]:
                        polished = _redesign(Zr, shifted, idx, subset, sub_blocks, support, keep, u, resonator)
                        if polished is not None:
                            terms = [_termination(*polished[k], digits, mode) if k in polished
                                     else clamp * sp.eye(len(blocks[k])) for k in range(K)]
                            cert = verify(terms, s0, f"Newton-corrected design point, {mode} rounding to {digits + 1} digits ({label})")
                            if cert is not None:
                                return report(cert, False)
            designs += found
            if designs >= 2:
                break
    return report(None, True)


def find_destabilizing_terminations(
    Z: Any,
    ports: Sequence[int] | None = None,
    frequencies: Iterable[float] | None = None,
    seed: int = 0,
    restarts: int = 3,
    max_subsets: int = 8,
    deadline: float = 10.0,
    hints: Iterable[float] = (),
) -> InstabilityCertificate | None:
    """The certificate of :func:`search_terminations`, or None when it found nothing by its
    deadline (which proves nothing).

    >>> import sympy as sp
    >>> from hapticproof.core.symbols import s
    >>> Z = sp.Matrix([[1 - 2/(s + 1) + 10/(s + 10**4), 0], [0, 1]])   # issue 10: Re z11(j0) < 0
    >>> cert = find_destabilizing_terminations(Z, hints=[0.0])
    >>> cert is not None and cert.roots[0].real > 0
    True
    """
    return search_terminations(Z, ports, hints=hints, frequencies=frequencies, seed=seed, restarts=restarts,
                               deadline=deadline, max_subsets=max_subsets).certificate
