r"""Floating-point paths that are safe, and the exact margins they are measured against.

The *passivity margin* of a real-rational (matrix) ``G(z)`` is
``min over w of lambda_min((G(e^{jwT}) + G(e^{jwT})^H)/2)`` (for a scalar: ``min Re G``).

Float pitfalls handled here:

* near ``w = 0``, ``e^{jwT} - 1`` computed as ``cos - 1 + j sin`` loses every digit of its real
  part (``cos(1e-9) - 1 == 0`` in float64), so ``Re T/(z - 1)`` comes out ``0`` instead of
  ``-T/2``. :func:`stable_evaluator` writes ``z = 1 + u`` with ``u = expm1(jwT)`` so every
  factor ``z - 1`` is the accurate ``u``;
* monomial forms of high-degree polynomials in ``c`` (Chebyshev coefficients ~ ``2^n``) are
  never evaluated in float; evaluation goes through ``G(e^{jw})`` directly;
* a float path never *proves* positivity: :func:`float_decision` reports ``disproved`` only
  with a witness re-checked exactly, and otherwise hands the question to the exact engine,
  saying so.

>>> import sympy as sp
>>> from hapticproof.core.symbols import z
>>> f = stable_evaluator(1/(z - 1))
>>> round(float(f(np.array([1e-9]))[0].real), 12)
-0.5
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

import flint
import mpmath
import numpy as np
import sympy as sp

from hapticproof.core.evidence import Decision, Evidence, Method, Outcome
from hapticproof.exact.realroots import arb_to_fmpq, as_fmpq, minimise_rational, nonnegative_on, real_roots
from hapticproof.core.symbols import z as Z_SYM
from hapticproof.exact.unitcircle import hermitian_part_rational

__all__ = [
    "stable_evaluator",
    "naive_evaluator",
    "float_margin",
    "mp_margin",
    "exact_margin",
    "ExactMargin",
    "float_decision",
]


def _as_matrix(G: Any) -> sp.Matrix:
    return G if isinstance(G, sp.MatrixBase) else sp.Matrix([[sp.sympify(G)]])


def stable_evaluator(G: Any, z: sp.Symbol = Z_SYM):
    """Vectorised float64 ``G(e^{j theta})`` (shape ``(N,)`` for a scalar, ``(N, m, m)``
    for a matrix) with ``z - 1`` evaluated as ``expm1(j theta)``."""
    u = sp.Dummy("u")
    matrix = _as_matrix(G)
    entries = [sp.lambdify(u, sp.sympify(e).subs(z, 1 + u), "numpy") for e in matrix]
    shape = matrix.shape

    def evaluate(theta: np.ndarray) -> np.ndarray:
        uu = np.expm1(1j * np.asarray(theta, dtype=float))
        values = np.stack([np.broadcast_to(np.asarray(f(uu), dtype=complex), uu.shape) for f in entries], axis=-1)
        if shape == (1, 1):
            return values[..., 0]
        return values.reshape(uu.shape + shape)

    return evaluate


def naive_evaluator(G: Any, z: sp.Symbol = Z_SYM):
    """Float64 ``G(e^{j theta})`` with ``z = exp(j theta)``: the textbook path, kept only to
    measure the cancellation it suffers near ``theta = 0``."""
    matrix = _as_matrix(G)
    entries = [sp.lambdify(z, e, "numpy") for e in matrix]
    shape = matrix.shape

    def evaluate(theta: np.ndarray) -> np.ndarray:
        zz = np.exp(1j * np.asarray(theta, dtype=float))
        values = np.stack([np.broadcast_to(np.asarray(f(zz), dtype=complex), zz.shape) for f in entries], axis=-1)
        return values[..., 0] if shape == (1, 1) else values.reshape(zz.shape + shape)

    return evaluate


def _grid(points: int) -> np.ndarray:
    """Midpoints of a uniform grid on (0, pi) (``theta = 0`` is a pole of the integrators)."""
    return np.pi * (np.arange(points) + 0.5) / points


def float_margin(G: Any, points: int, evaluator=None) -> tuple[float, float]:
    """Grid estimate of the passivity margin in float64: ``(margin, theta at the minimum)``."""
    evaluate = evaluator or stable_evaluator(G)
    theta = _grid(points)
    values = evaluate(theta)
    if values.ndim == 1:
        herm = values.real
    else:
        herm = np.linalg.eigvalsh((values + np.conj(np.swapaxes(values, -1, -2))) / 2)[..., 0]
    k = int(np.argmin(herm))
    return float(herm[k]), float(theta[k])


def mp_margin(G: Any, points: int, digits: int, z: sp.Symbol = Z_SYM) -> mpmath.mpf:
    """Grid estimate of the margin with mpmath at ``digits`` significant digits."""
    matrix = _as_matrix(G)
    entries = [sp.lambdify(z, e, "mpmath") for e in matrix]
    m = matrix.shape[0]
    best = None
    with mpmath.workdps(digits):
        for k in range(points):
            theta = mpmath.pi * (k + mpmath.mpf(1) / 2) / points
            zz = mpmath.expj(theta)
            vals = [f(zz) for f in entries]
            if m == 1:
                value = mpmath.re(vals[0])
            else:
                M = mpmath.matrix(m, m)
                for i in range(m):
                    for j in range(m):
                        M[i, j] = (vals[i * m + j] + mpmath.conj(vals[j * m + i])) / 2
                value = min(mpmath.eighe(M, eigvals_only=True))
            best = value if best is None or value < best else best
    return best


@dataclass(frozen=True, slots=True)
class ExactMargin:
    """The margin certified in ``[lo, hi]`` (rationals or ``arb`` endpoints) and how."""

    lo: Any
    hi: Any
    method: str

    @property
    def mid(self) -> mpmath.mpf:
        with mpmath.workdps(60):
            return (mpmath.mpf(str(sp.Rational(self.lo))) + mpmath.mpf(str(sp.Rational(self.hi)))) / 2


def exact_margin(G: Any, bits: int = 64, z: sp.Symbol = Z_SYM) -> ExactMargin:
    """Certified margin: a scalar by the exact minimum of ``Re G`` over ``c`` (root isolation);
    a matrix by the smallest eigenvalue at ``c = +-1`` when one exact test proves it global,
    otherwise by bisection on a shift ``lam`` with exact decisions of
    ``(G + G^H)/2 - lam I >= 0 on the whole circle`` (characteristic coefficients, root
    isolation), to ``2**-bits`` relative."""
    return exact_margin_prepared(G, z, estimate_points=2048)(bits)


def _shifted_coefficients(nums: list, den: flint.fmpq_poly, mu: flint.fmpq) -> list:
    """Numerators of ``E_k(M - mu I)`` from those of ``E_j(M)`` (``M = A/den``):
    ``E_k(M + tI) = sum_j C(m-j, k-j) t^(k-j) E_j(M)`` with ``t = -mu``."""
    from math import comb

    m = len(nums) - 1
    shift = -mu * den
    powers = [flint.fmpq_poly([1])]
    for _ in range(m):
        powers.append(powers[-1] * shift)
    return [sum((comb(m - j, k - j) * powers[k - j] * nums[j] for j in range(k + 1)), flint.fmpq_poly([0]))
            for k in range(m + 1)]


def _matrix_margin(nums: list, den: flint.fmpq_poly, estimate: float, bits: int) -> ExactMargin:
    """Exact margin of ``M/2`` over ``c in [-1, 1]`` from the characteristic coefficients.

    First the endpoint shortcut (:func:`_endpoint_margin`); otherwise bisection on ``lam``
    with exact decisions of ``M/2 - lam I >= 0 on [-1, 1]``: every characteristic coefficient
    of the shifted matrix non-negative (root isolation). The coefficients of ``M`` are
    computed once; each step is ``m`` univariate tests."""
    nums = [flint.fmpq_poly(p) if not isinstance(p, flint.fmpq_poly) else p for p in nums]

    def holds(lam: flint.fmpq) -> bool:
        return all(p.is_zero() or nonnegative_on(p, -1, 1, touching=False).holds for p in _shifted_coefficients(nums, den, 2 * lam)[1:])

    found = _endpoint_margin(nums, den, bits, holds)
    if found is not None:
        return found
    step = as_fmpq(sp.Rational(max(abs(estimate), 1.0) * 1e-3))
    lo = as_fmpq(sp.Rational(estimate)) - step
    hi = as_fmpq(sp.Rational(estimate)) + step
    while not holds(lo):
        lo -= 2 * step
        step *= 2
    while holds(hi):
        hi += 2 * step
        step *= 2
    scale = max(abs(lo), abs(hi), flint.fmpq(1, 2**20))
    while hi - lo > scale / 2**bits:
        mid = (lo + hi) / 2
        if holds(mid):
            lo = mid
        else:
            hi = mid
    return ExactMargin(sp.Rational(int(lo.p), int(lo.q)), sp.Rational(int(hi.p), int(hi.q)), "bisection-root-isolation")


def _endpoint_margin(nums: list, den: flint.fmpq_poly, bits: int, holds) -> ExactMargin | None:
    """The margin when the worst case sits at ``c = -1`` or ``c = 1`` (often the Nyquist
    frequency): the smallest eigenvalue of ``M/2`` there is isolated exactly as a root of its
    characteristic polynomial, and one exact test ``M/2 - lo I >= 0 on [-1, 1]`` with ``lo`` just
    below it proves it global. ``None`` when that test fails (an interior minimum)."""
    m = len(nums) - 1
    smallest = None
    for end in (flint.fmpq(-1), flint.fmpq(1)):
        d = den(end)
        if d == 0:
            continue
        # det(t I - M/2) = sum_k (-1)^k E_k(M/2) t^(m-k),  E_k(M/2) = nums_k(end) / (2 d)^k
        coeffs = [(-1) ** k * nums[k](end) / (2 * d) ** k for k in range(m + 1)]
        roots = real_roots(flint.fmpq_poly(coeffs[::-1]), None, None)
        if roots and (smallest is None or roots[0].hi < smallest.lo):
            smallest = roots[0]
    if smallest is None:
        return None
    scale = max(abs(smallest.lo), abs(smallest.hi), flint.fmpq(1, 2**20))
    root = smallest.refine(scale / 2**bits)
    if not holds(root.lo):
        return None
    return ExactMargin(sp.Rational(int(root.lo.p), int(root.lo.q)), sp.Rational(int(root.hi.p), int(root.hi.q)),
                       "endpoint-eigenvalue-root-isolation")


def exact_margin_prepared(G: Any, z: sp.Symbol = Z_SYM, estimate_points: int = 256):
    """Split :func:`exact_margin` into a one-time preparation (the exact c-forms, like a grid
    method's compiled evaluator) and the margin computation; returns ``compute(bits)``.
    ``estimate_points``: the float grid that seeds a matrix bisection."""
    matrix = _as_matrix(G)
    if matrix.shape == (1, 1):
        form = hermitian_part_rational(matrix[0, 0], z).numeric()

        def compute_scalar(bits: int = 64) -> ExactMargin:
            m = minimise_rational(form.num, form.den, -1, 1, bits=2 * bits)
            if m.exact is not None:
                return ExactMargin(m.exact, m.exact, "root-isolation")
            lo, hi = arb_to_fmpq(m.value.lower()), arb_to_fmpq(m.value.upper())
            return ExactMargin(sp.Rational(int(lo.p), int(lo.q)), sp.Rational(int(hi.p), int(hi.q)), "root-isolation")

        return compute_scalar
    from hapticproof.exact.psd import characteristic_coefficients, hermitian_part_matrix

    H = hermitian_part_matrix(matrix, z)
    nums = characteristic_coefficients(H)
    estimate = float_margin(matrix, estimate_points)[0]
    return lambda bits=64: _matrix_margin(nums, H.den, estimate, bits)


def float_decision(G: Any, points: int = 4096) -> Outcome:
    """A fast verdict on ``Re G >= 0`` (scalar ``G``): float64 grid first; a negative grid
    value is turned into a rational ``c`` and re-checked exactly (then ``disproved``); a
    non-negative grid proves nothing, so the exact engine decides and the reason says so."""
    from hapticproof.analysis.positivereal import decide_hermitian

    value, theta = float_margin(G, points)
    form = hermitian_part_rational(sp.sympify(G)).numeric()
    if value < 0:
        c = sp.nsimplify(np.cos(theta), rational=True, tolerance=1e-12)
        exact_value = form(c)
        if exact_value < 0:
            return Outcome(Decision.DISPROVED, Evidence(Method.COUNTEREXAMPLE, witness={"c": c}, facts={"Re": exact_value}),
                           f"float64 grid found Re G < 0; re-checked exactly: Re G = {exact_value} at c = {c}")
    outcome = decide_hermitian(form).outcome
    reason = "float64 cannot prove positivity; switched to exact root isolation: " + outcome.reason
    return Outcome(outcome.decision, outcome.evidence, reason, outcome.minimiser, outcome.minimum)
