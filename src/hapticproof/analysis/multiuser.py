r"""Exact positive realness of m-user haptic virtual environments (HVE paper, Section 3.2) with its
structured worst cases (the scene and ``G^{-1}(z)`` are :mod:`hapticproof.systems.multiuser`).

The model (Fig. 7b, eqs. 37-39, 47, 56), derived rather than copied
---------------------------------------------------------------------
Device ``i`` obeys ``b_i V_i = F_i - U_i`` (37) with the environment force
``U_i = z^{-n_i} sum_j H_ij(z) X_j`` (per-user delay ``n_i = t_di/T``) and
``H(z) = Kmat + Bmat (z-1)/(Tz)``, where ``Kmat = diag(K_0) + L_K`` and
``Bmat = diag(B_0) + L_B`` are a ground coupling plus the weighted Laplacian of the coupling
graph (``L_ii = sum_k w_ik``, ``L_ij = -w_ij``). With ``X_j = I(z) V_j`` (forward difference
``I = T/(z-1)`` by default, backward or Tustin allowed) and an active operator's shortage of
passivity ``z_ai`` moved from ``b_i`` (as eq. 26 does),

.. math:: G^{-1}(z) = \operatorname{diag}(b - z_a) + D(z)\, H(z)\, I(z),
          \qquad D(z) = \operatorname{diag}(z^{-n_i}).

Hermitian part by kernels
-------------------------
``G_ij = (b_i - z_ai) delta_ij + z^{-n_i} (T Kmat_ij k_K(z) + Bmat_ij k_B(z))`` with the scalar
kernels ``k_K = I(z)/T`` and ``k_B = I(z)(z-1)/(Tz)``, so every entry of
``M = G + G^H`` is a parameter-linear combination of the kernels' exact ``c``-forms
(:mod:`hapticproof.exact.unitcircle`), computed once per delay. This is the fast path behind
:func:`hermitian`; the tests check it against the generic
:func:`hapticproof.exact.psd.hermitian_part_matrix` of :func:`inverse_transfer_matrix`.

Structure (proved in :func:`worst_case` and the tests)
-------------------------------------------------------
* **Undelayed, forward difference**: ``M(c) = 2 diag(b - z_a) - T Kmat + 2 c Bmat`` is affine in
  ``c`` with slope ``2 Bmat >= 0`` (``B >= 0``), so the worst case is ``c = -1`` for any ``m``
  and any graph (Loewner order): ``M(-1) = 2 diag(b - z_a) - diag(K_0 T + 2 B_0) - L_w`` with
  ``w_ij = K_ij T + 2 B_ij``.
* **Equal delays**: ``M(c) = 2 diag(b - z_a) + 2 Re k_K(c) T Kmat + 2 Re k_B(c) Bmat``; with
  ``Re k_K >= -kappa_K`` and ``Re k_B >= -kappa_B`` (exact minima over ``[-1, 1]``; forward
  difference: ``kappa_K = n + 1/2`` from the Dirichlet kernel, ``kappa_B = 1``)

  .. math:: M/2 \succeq \operatorname{diag}(b - z_a) - \kappa_K T\,Kmat - \kappa_B Bmat ,

  which is exact when ``B = 0`` (the minimum of ``Re k_K`` is attained).
* **Loewner monotonicity**: smaller ``b_i`` and larger ``K_0i, B_0i, K_ij, B_ij`` decrease the
  bound; ``L_w <= max(w) L_{K_m}`` and ``lambda_max(L_{K_m}) = m``, so
  ``min_i (b_i - z_ai) >= max_i(kappa_K T K_0i + kappa_B B_0i) + m max_ij(kappa_K T K_ij + kappa_B B_ij)``
  is sufficient for every graph (:func:`sufficient_condition`) -- the corrected form of the
  paper's (54), (55), (62), (63).
* **Uniform parameters** (equal ``b``, ``K_0``, ``B_0``, ``K``, ``B``, delays, ``z_a``): ``Kmat``
  and ``Bmat`` are polynomials in the unweighted Laplacian, so ``G^{-1}`` decouples into one
  single-user virtual wall per Laplacian eigenvalue ``lambda`` with ``K' = K_0 + lambda K`` and
  ``B' = B_0 + lambda B`` (:func:`uniform_modes`; complete graph: ``lambda`` in ``{0, m}``).

>>> scene = MultiUserScene.uniform(3)
>>> sp.factor(inverse_transfer_matrix(scene)[0, 1])
-(B*z - B + K*T*z)/(z*(z - 1))
>>> worst_case(scene).condition
b >= 3*B + B_0 + 3*K*T/2 + K_0*T/2
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from dataclasses import dataclass, field
from functools import lru_cache
from typing import Any

import flint
import sympy as sp

from hapticproof.exact.canonical import cancel as exact_cancel
from hapticproof.core.errors import DerivationError, SceneError
from hapticproof.core.evidence import Decision, Evidence, Method, Outcome
from hapticproof.exact.kernel import decide_constant_psd, locate_roots, poly_json
from hapticproof.exact.infinity import decide_infinity
from hapticproof.core.lazy import stage
from hapticproof.systems.models import integrator
from hapticproof.exact.conditions import Condition, combine
from hapticproof.analysis.modes import decides_by_modes, largest_eigenvalue, mode_conditions, spectrum
from hapticproof.analysis.positivereal import named_conditions
from hapticproof.analysis.positivereal import worst_case as single_worst_case
from hapticproof.exact.psd import HermitianPart, Minor, PolyRing, affine_worst_case, decide_psd_on_circle, nonnegative_certificate, residue_matrices as matrix_residues
from hapticproof.exact.psd import principal_minors as psd_minors
from hapticproof.exact.realroots import minimise_rational
from hapticproof.systems.singleuser import SingleUserScene
from hapticproof.core.symbols import z as Z_SYM
from hapticproof.exact.unitcircle import hermitian_part_rational, imaginary_part_rational
from hapticproof.systems.multiuser import MultiUserScene, UNIFORM_SYMBOLS, damping_matrix, inverse_transfer_matrix, laplacian, stiffness_matrix

__all__ = ["MODE_USERS", "check_work", "by_modes", "extreme_modes", "Mode", "MatrixWorstCase", "PSD", "residues", "hermitian", "principal_minors", "worst_case", "positive_real", "conditions", "transfer_entries", "kernel_bounds", "worst_case_matrix", "uniform_modes", "uniform_condition", "sufficient_condition", "hve_leading_minor_counterexample"]


@stage("residues")
def residues(scene: MultiUserScene):
    """Residue matrices of ``G^{-1}`` at its unit-circle poles (``z = 1``: ``T Kmat``)."""
    return matrix_residues(inverse_transfer_matrix(scene))


@lru_cache(maxsize=None)
def _kernels(approximation: str, n: int) -> tuple[tuple[flint.fmpq_poly, flint.fmpq_poly], ...]:
    """``(Re, Im/sin)`` of ``k_K = z^-n I/T`` and ``k_B = z^-n I (z-1)/(Tz)`` as (num, den)."""
    iota = integrator(approximation, 1)
    out = []
    for kernel in (Z_SYM ** (-n) * iota, Z_SYM ** (-n) * exact_cancel(iota * (Z_SYM - 1) / Z_SYM)):
        re = hermitian_part_rational(kernel).numeric()
        im = imaginary_part_rational(kernel).numeric()
        out.append(((re.num, re.den), (im.num, im.den)))
    return tuple(out)  # ((reK, imK), (reB, imB))


@lru_cache(maxsize=None)
def _kernel_polynomials(approximation: str, n: int) -> tuple[tuple[flint.fmpq_poly, flint.fmpq_poly], ...]:
    """``k_K = z^-n I/T`` and ``k_B = z^-n I (z-1)/(Tz)`` as coprime (num, den) in ``z`` (flint)."""
    iota = exact_cancel(integrator(approximation, 1))
    out = []
    for kernel in (iota, exact_cancel(iota * (Z_SYM - 1) / Z_SYM)):
        num, den = sp.fraction(exact_cancel(kernel))
        pn = flint.fmpq_poly([flint.fmpq(int(sp.Rational(a).p), int(sp.Rational(a).q)) for a in sp.Poly(num, Z_SYM).all_coeffs()[::-1]])
        pd = flint.fmpq_poly([flint.fmpq(int(sp.Rational(a).p), int(sp.Rational(a).q)) for a in sp.Poly(den, Z_SYM).all_coeffs()[::-1]])
        pd = pd * flint.fmpq_poly([0] * n + [1])
        g = pn.gcd(pd)
        out.append((pn / g, pd / g))
    return tuple(out)


def transfer_entries(scene: MultiUserScene) -> dict[str, Any]:
    """``G^{-1}(z)`` of a numeric scene as polynomials per entry (JSON for the checker),
    built from the kernels: ``G_ij = (b_i - z_ai) delta_ij + T Kmat_ij k_K + Bmat_ij k_B``.

    >>> s = MultiUserScene.from_values(b=[1, 1], T=1, K0=[1, 1], K={(0, 1): 1}, edges=[(0, 1)])
    >>> transfer_entries(s)["entries"][0][1]
    {'num': ['-1'], 'den': ['-1', '1']}
    """
    if not scene.is_numeric:
        raise SceneError("transfer_entries needs numeric parameters")
    m = scene.users
    Kmat, Bmat = stiffness_matrix(scene), damping_matrix(scene)
    T = _fmpq(scene.T)
    rows = []
    for i in range(m):
        (kn, kd), (bn, bd) = _kernel_polynomials(scene.approximation, scene.delays[i])
        row = []
        for j in range(m):
            num, den = flint.fmpq_poly([0]), flint.fmpq_poly([1])
            terms = [(T * _fmpq(Kmat[i, j]), kn, kd), (_fmpq(Bmat[i, j]), bn, bd)]
            if i == j:
                terms.append((_fmpq(scene.b[i] - scene.z_a[i]), flint.fmpq_poly([1]), flint.fmpq_poly([1])))
            for weight, pn, pd in terms:
                if weight != 0:
                    num, den = num * pd + weight * pn * den, den * pd
            g = num.gcd(den) if not num.is_zero() else den
            num, den = num / g, den / g
            lead = den.coeffs()[-1]
            row.append({"num": poly_json(num / lead), "den": poly_json(den / lead)})
        rows.append(row)
    return {"variable": "z", "entries": rows}


def _poly(coeffs: list[str]) -> flint.fmpq_poly:
    return flint.fmpq_poly([_fmpq(v) for v in coeffs])


def _fmpq(value: Any) -> flint.fmpq:
    value = sp.Rational(value)
    return flint.fmpq(int(value.p), int(value.q))


def _combine(p: tuple, q: tuple, sign: int) -> tuple[flint.fmpq_poly, flint.fmpq_poly]:
    """``p + sign*q`` for (num, den) pairs, reduced, with a denominator positive at c = 0."""
    num = p[0] * q[1] + sign * q[0] * p[1]
    den = p[1] * q[1]
    if num.is_zero():
        return flint.fmpq_poly([0]), flint.fmpq_poly([1])
    g = num.gcd(den)
    num, den = num / g, den / g
    if den(flint.fmpq(0)) < 0:
        num, den = -num, -den
    return num, den


@stage("hermitian")
def hermitian(scene: MultiUserScene) -> HermitianPart:
    """``M = G^{-1} + G^{-H}`` on the unit circle, built from the kernels (fast path).

    Entrywise real when the delays are equal; with unequal delays ``S != 0`` (complex
    Hermitian, rows delayed differently).
    """
    m = scene.users
    Kmat, Bmat = stiffness_matrix(scene), damping_matrix(scene)
    ring = PolyRing.over(scene.parameters)
    kern = {n: _kernels(scene.approximation, n) for n in set(scene.delays)}
    combos: dict[tuple[int, int, int], tuple] = {}   # (n_i, n_j, which) -> (reK, reB) sums and (imK, imB) diffs
    for ni in kern:
        for nj in kern:
            (reKi, imKi), (reBi, imBi) = kern[ni]
            (reKj, imKj), (reBj, imBj) = kern[nj]
            combos[(ni, nj, 0)] = (_combine(reKi, reKj, 1), _combine(reBi, reBj, 1))
            combos[(ni, nj, 1)] = (_combine(imKi, imKj, -1), _combine(imBi, imBj, -1))
    den = flint.fmpq_poly([1])
    for pair in combos.values():
        for _, d in pair:
            den = den * d / den.gcd(d)
    if den(flint.fmpq(0)) < 0:
        den = -den

    lifted: dict[int, Any] = {}

    def lift(poly_pair: tuple) -> Any:
        key = id(poly_pair)
        if key not in lifted:
            num, d = poly_pair
            lifted[key] = ring.from_c_poly(num * (den / d))
        return lifted[key]

    to_ring: dict[sp.Expr, Any] = {}

    def param(expr: Any) -> Any:
        key = sp.sympify(expr)
        if key not in to_ring:
            to_ring[key] = ring.constant(key) if key.is_Rational else ring.from_expr(key)
        return to_ring[key]

    T = param(scene.T)
    zero = ring.zero
    A, S = [], []
    for i in range(m):
        row_a, row_s = [], []
        for j in range(m):
            ni, nj = scene.delays[i], scene.delays[j]
            (kre, bre), (kim, bim) = combos[(ni, nj, 0)], combos[(ni, nj, 1)]
            a = zero
            s = zero
            if Kmat[i, j] != 0:
                kij = param(Kmat[i, j]) * T
                a = a + kij * lift(kre)
                s = s + kij * lift(kim)
            if Bmat[i, j] != 0:
                bij = param(Bmat[i, j])
                a = a + bij * lift(bre)
                s = s + bij * lift(bim)
            if i == j:
                a = a + param(2 * (scene.b[i] - scene.z_a[i])) * ring.from_c_poly(den)
            row_a.append(a)
            row_s.append(s)
        A.append(tuple(row_a))
        S.append(tuple(row_s))
    return HermitianPart(ring, tuple(A), tuple(S), ring.from_c_poly(den))


@stage("principal_minors")
def principal_minors(scene: MultiUserScene) -> dict[tuple[int, ...], Minor]:
    """All principal minors of the Hermitian part, exact in ``c`` (and the parameters)."""
    return psd_minors(hermitian(scene))


@dataclass(frozen=True, slots=True)
class KernelBounds:
    """``kappa_K = -min Re k_K`` and ``kappa_B = -min Re k_B`` over ``c`` in ``[-1, 1]`` (exact
    minima, with their minimisers): ``Re k_K >= -kappa_K``, ``Re k_B >= -kappa_B``."""

    approximation: str
    delay: int
    kappa_K: Any
    kappa_B: Any
    argmin_K: Any
    argmin_B: Any


@lru_cache(maxsize=None)
def kernel_bounds(approximation: str = "forward", delay: int = 0) -> KernelBounds:
    """Exact worst values of the two kernels (forward difference: ``n + 1/2`` at ``c = 1``
    (Dirichlet kernel) and ``1`` at the minimiser of ``T_{n+1}``).

    >>> kb = kernel_bounds("forward", 2)
    >>> kb.kappa_K, kb.argmin_K, kb.kappa_B
    (5/2, 1, 1)
    """
    (reK, _), (reB, _) = _kernels(approximation, delay)
    out = []
    for num, den in (reK, reB):
        mn = minimise_rational(num, den, -1, 1)
        value = mn.exact if mn.exact is not None else _recognise_minimum(num, den, mn.value)
        argmin = mn.argmin if not hasattr(mn.argmin, "as_sympy") else mn.argmin.as_sympy()
        out.append((-value, argmin))
    return KernelBounds(approximation, delay, out[0][0], out[1][0], out[0][1], out[1][1])


def _recognise_minimum(num: flint.fmpq_poly, den: flint.fmpq_poly, ball: Any) -> Any:
    """An exact rational minimum when the certified ball holds one: ``q`` is the minimum of
    ``num/den`` (``den > 0``) on ``[-1, 1]`` iff ``num - q den >= 0`` there with a zero."""
    from fractions import Fraction

    from hapticproof.exact.realroots import nonnegative_on, real_roots

    guess = Fraction(float(ball.mid())).limit_denominator(10**6)
    q = flint.fmpq(guess.numerator, guess.denominator)
    diff = num - q * den
    if nonnegative_on(diff, -1, 1).holds and (diff.is_zero() or real_roots(diff, -1, 1)):
        return sp.Rational(guess.numerator, guess.denominator)
    return ball


@dataclass(frozen=True, slots=True)
class Mode:
    """One decoupled mode of a uniform scene: a single-user virtual wall with stiffness
    ``K_0 + lambda K`` and damping ``B_0 + lambda B`` (``lambda`` a Laplacian eigenvalue of the
    unweighted coupling graph, with its multiplicity)."""

    eigenvalue: sp.Expr
    multiplicity: int
    scene: SingleUserScene


@stage("uniform_modes")
def uniform_modes(scene: MultiUserScene) -> tuple[Mode, ...]:
    """The single-user walls a uniform scene decouples into (complete graph: ``lambda = 0``
    once and ``lambda = m`` with multiplicity ``m - 1``).

    >>> [(md.eigenvalue, md.multiplicity, md.scene.H) for md in uniform_modes(MultiUserScene.uniform(3))]
    [(0, 1, B_0*(z - 1)/(T*z) + K_0), (3, 2, 3*K + K_0 + (3*B + B_0)*(z - 1)/(T*z))]
    """
    if not scene.is_uniform:
        raise SceneError("uniform_modes needs a uniform scene (equal per-user values and edge weights)")
    m = scene.users
    values = spectrum(scene)
    if values is None:
        values = laplacian([0] * m, scene.weights([1] * len(scene.edges))).eigenvals()
    return tuple(_mode(scene, lam, mult) for lam, mult in sorted(values.items(), key=lambda kv: float(kv[0])))


def _mode(scene: MultiUserScene, lam: Any, multiplicity: int) -> Mode:
    K0, B0 = scene.K0[0], scene.B0[0]
    K = scene.K[0] if scene.K else sp.Integer(0)
    B = scene.B[0] if scene.B else sp.Integer(0)
    wall = SingleUserScene.virtual_wall(K=K0 + lam * K, B=B0 + lam * B, b=scene.b[0], T=scene.T,
                                        approximation=scene.approximation, delay=scene.delays[0], z_a=scene.z_a[0])
    return Mode(sp.nsimplify(lam) if lam.is_Rational else lam, int(multiplicity), wall)


#: Uniform scenes with at least this many users are decided by their two extreme modes
#: (:mod:`hapticproof.analysis.modes`) rather than by the ``2^m`` minors / characteristic
#: coefficients of the m x m Hermitian part; smaller ones keep the matrix certificates.
MODE_USERS = 5


def by_modes(scene: MultiUserScene) -> bool:
    """Is the scene decided by modes (uniform, one delay, a known spectrum, ``m >=`` :data:`MODE_USERS`)?"""
    return scene.users >= MODE_USERS and decides_by_modes(scene)


def extreme_modes(scene: MultiUserScene) -> tuple[Mode, ...]:
    """The modes ``lambda = 0`` and ``lambda = lambda_max`` of a uniform scene: the Hermitian part and
    the residues are affine in ``lambda``, so these two decide (:mod:`hapticproof.analysis.modes`).

    >>> [md.eigenvalue for md in extreme_modes(MultiUserScene.uniform(6, edges=[(i, i + 1) for i in range(5)]))]
    [0, sqrt(3) + 2]
    """
    if not decides_by_modes(scene):
        raise SceneError("extreme_modes needs a uniform scene with one delay on a graph of known spectrum")
    top = largest_eigenvalue(scene)
    values = spectrum(scene) if scene.users <= 64 else None
    mult = (lambda lam: values.get(lam, 1)) if values else (lambda lam: 1 if lam == 0 else (scene.users - 1 if scene.is_complete else 1))  # noqa: E731
    return tuple(_mode(scene, lam, mult(lam)) for lam in ((sp.Integer(0), top) if top != 0 else (sp.Integer(0),)))


def worst_case_matrix(scene: MultiUserScene) -> sp.ImmutableMatrix:
    """``2 diag(b - z_a) - 2 kappa_K T Kmat - 2 kappa_B Bmat`` (equal delays): ``M(c)`` is
    above it in the Loewner order for every ``c``; undelayed forward difference:
    ``M(-1) = 2 diag(b - z_a) - diag(K_0 T + 2 B_0) - L_w``, ``w = K T + 2 B``.

    >>> worst_case_matrix(MultiUserScene.symbolic(2))[0, 1]
    2*B_12 + K_12*T
    """
    if not scene.equal_delays:
        raise SceneError("the Loewner bound needs equal delays")
    kb = kernel_bounds(scene.approximation, scene.delays[0])
    kK, kB = max(kb.kappa_K, 0), max(kb.kappa_B, 0)
    bz = sp.diag(*[bi - zi for bi, zi in zip(scene.b, scene.z_a)])
    return sp.ImmutableMatrix((2 * bz - 2 * kK * scene.T * stiffness_matrix(scene) - 2 * kB * damping_matrix(scene)).applyfunc(sp.expand))


def sufficient_condition(scene: MultiUserScene) -> sp.Basic:
    """The corrected general condition (any graph, equal delays, ``B >= 0``):

    ``min_i (b_i - z_ai) >= max_i(kappa_K T K_0i + kappa_B B_0i) + m max_ij(kappa_K T K_ij + kappa_B B_ij)``.

    Sufficient by Loewner monotonicity and ``lambda_max(L_w) <= m max w``; exact for uniform
    scenes on the complete graph when the two kernel minima coincide (no delay, or ``B = 0``).
    For the forward difference ``kappa_K T = t_d + T/2`` and ``kappa_B = 1``.

    >>> sufficient_condition(MultiUserScene.uniform(3))
    b >= 3*B + B_0 + 3*K*T/2 + K_0*T/2
    """
    if not scene.equal_delays:
        raise SceneError("the closed form needs equal delays")
    kb = kernel_bounds(scene.approximation, scene.delays[0])
    kK, kB = max(kb.kappa_K, 0), max(kb.kappa_B, 0)
    lhs = _extremum(sp.Min, [bi - zi for bi, zi in zip(scene.b, scene.z_a)])
    ground = _extremum(sp.Max, [kK * scene.T * k0 + kB * b0 for k0, b0 in zip(scene.K0, scene.B0)])
    pair = _extremum(sp.Max, [kK * scene.T * k + kB * bb for k, bb in zip(scene.K, scene.B)]) if scene.edges else 0
    rhs = ground + scene.users * pair
    return sp.Ge(lhs, rhs if rhs.has(sp.Max) else sp.expand(rhs), evaluate=False)


def _extremum(func, values: Sequence[Any]) -> Any:
    unique = []
    for v in values:
        v = sp.expand(v)
        if not any(sp.expand(v - u) == 0 for u in unique):
            unique.append(v)
    return unique[0] if len(unique) == 1 else func(*unique)


def uniform_condition(m: int, delay: int = 0, approximation: str = "forward", damped: bool = True) -> sp.Basic:
    """The exact PR condition of the uniform complete-graph scene with the symbols of
    :data:`UNIFORM_SYMBOLS`, when it has a closed form: no delay (any ``B >= 0``), or a delay
    with ``B_0 = B = 0`` (``damped=False``).

    >>> uniform_condition(2)
    b - z_a >= 2*B + B_0 + K*T + K_0*T/2
    >>> uniform_condition(3, delay=2, damped=False)
    b - z_a >= 15*K*T/2 + 5*K_0*T/2
    """
    u = UNIFORM_SYMBOLS
    scene = MultiUserScene.uniform(m, z_a=u["z_a"], delay=delay, approximation=approximation,
                                   B0=None if damped else 0, B=None if damped else 0)
    if delay and damped:
        raise SceneError("with a delay and virtual damping the uniform worst case has no closed form (see worst_case)")
    kb = kernel_bounds(approximation, delay)
    top = max(md.eigenvalue for md in uniform_modes(scene))
    bound = kb.kappa_K * u["T"] * (u["K_0"] + top * u["K"])
    if damped:
        bound += kb.kappa_B * (u["B_0"] + top * u["B"])
    return sp.Ge(u["b"] - u["z_a"], sp.expand(bound))


@dataclass(frozen=True, slots=True)
class MatrixWorstCase:
    """Worst case over frequency of ``M(c) >= 0`` for an m-user scene.

    ``outcome`` decides (numeric) or states (symbolic) the condition; ``condition`` is the
    equivalent condition on the parameters (SymPy; ``True``/``False`` when numeric);
    ``minimiser`` the worst ``c`` when known; ``method`` names the route
    (``root-isolation``, ``loewner-affine``, ``loewner-dirichlet``, ``uniform-modes``).
    """

    outcome: Outcome
    condition: Any
    method: str
    minimiser: Any = None
    details: Mapping[str, Any] = field(default_factory=dict)

    @property
    def decision(self) -> Decision:
        return self.outcome.decision


def _and(conditions: Sequence[sp.Basic]) -> sp.Basic:
    kept = [cnd for cnd in conditions if cnd is not sp.true]
    if not kept:
        return sp.true
    return kept[0] if len(kept) == 1 else sp.And(*kept, evaluate=False)


def _dominates(a: sp.Basic, b: sp.Basic) -> bool:
    """``a`` implies ``b`` for ``lhs >= rhs`` conditions with the same lhs and a rhs larger
    by a non-negative-coefficient polynomial in non-negative symbols."""
    if not (isinstance(a, sp.Rel) and isinstance(b, sp.Rel)) or a.lhs != b.lhs:
        return False
    diff = sp.expand(a.rhs - b.rhs)
    if diff == 0:
        return True
    if not all(s.is_nonnegative for s in diff.free_symbols):
        return False
    try:
        poly = sp.Poly(diff, *sorted(diff.free_symbols, key=str)) if diff.free_symbols else None
    except sp.PolynomialError:             # rational in the parameters: no coefficient argument
        return False
    return (poly is None and diff >= 0) or (poly is not None and all(cf >= 0 for cf in poly.coeffs()))


@stage("worst_case")
def worst_case(scene: MultiUserScene) -> MatrixWorstCase:
    """Exact worst case of the Hermitian part over ``c`` in ``[-1, 1]``.

    Numeric parameters: exact decision by root isolation of the characteristic coefficients
    (any delays). Symbolic: the structured routes of the module docstring -- uniform modes,
    the affine Loewner argument (no delay), the Dirichlet bound (equal delays, ``B = 0``);
    otherwise ``undecided`` (give numbers).
    """
    if scene.is_numeric and by_modes(scene):
        herm = mode_conditions(scene)[-1].outcome
        holds = herm.decision == Decision.PROVED
        witness = herm.witness.get("c") if herm.witness else None
        return MatrixWorstCase(herm, sp.true if holds else sp.false, "uniform-modes", witness)
    if scene.is_numeric:
        decision = decide_psd_on_circle(hermitian(scene), transfer=transfer_entries(scene))
        holds = decision.decision == Decision.PROVED
        return MatrixWorstCase(decision.outcome, sp.true if holds else sp.false, "root-isolation",
                               decision.witness, {"failing_k": decision.failing})
    w = scene.naming().words           # the toolkit's words of the reasons below, in the scene's names
    if scene.is_uniform and (not scene.has_delay or not scene.damped) and decides_by_modes(scene):
        conditions = []
        modes = extreme_modes(scene)
        for md in modes:
            wc = _mode_condition(md.scene)
            conditions.append(wc)
        kept = [cnd for cnd in conditions if not any(o is not cnd and _dominates(o, cnd) and not _dominates(cnd, o) for o in conditions)]
        kept = list(dict.fromkeys(kept))
        condition = sp.false if sp.false in kept else _and(kept)      # (_and drops sp.true)
        settled = {sp.true: Decision.PROVED, sp.false: Decision.DISPROVED}.get(condition)
        outcome = Outcome(settled or Decision.SYMBOLIC,
                          Evidence(Method.STRUCTURAL, facts={"modes": [(md.eigenvalue, md.multiplicity) for md in modes],
                                                            "mode_conditions": conditions}),
                          w("uniform couplings: G^-1 decouples into single-user walls K_0 + lambda K, B_0 + lambda B "
                            "(lambda: Laplacian eigenvalues); exact per mode"))
        minimiser = sp.Integer(-1) if not scene.has_delay else kernel_bounds(scene.approximation, scene.delays[0]).argmin_K
        return MatrixWorstCase(outcome, condition, "uniform-modes", minimiser)
    if by_modes(scene):
        outcome = Outcome(Decision.UNDECIDED, Evidence(Method.STRUCTURAL, facts={"reason": "symbolic, delayed and damped"}),
                          "symbolic parameters with delays and damping: the modes have no closed-form worst case; "
                          "substitute numbers for an exact decision")
        return MatrixWorstCase(outcome, None, "none")
    H = hermitian(scene)
    if not scene.has_delay:
        aff = affine_worst_case(H)
        if aff is not None:
            conditions = _minor_conditions(aff.minors, H.ring, aff.matrix.matrix())
            outcome = Outcome(Decision.SYMBOLIC,
                              Evidence(Method.STRUCTURAL, facts={"endpoint": aff.endpoint, "certificate": aff.slope_certificate}),
                              w(f"M(c) = M0 + c M1 with M1 certified semidefinite: the worst case is c = {aff.endpoint} "
                                "(Loewner order); PR iff every principal minor of M(endpoint) is >= 0"))
            return MatrixWorstCase(outcome, _and(conditions), "loewner-affine", sp.Integer(aff.endpoint),
                                   {"minors": aff.minors})
    if scene.equal_delays and not scene.damped:
        W = worst_case_matrix(scene)
        ring = PolyRing.over(W.free_symbols)
        HW = HermitianPart(ring, tuple(tuple(ring.from_expr(v) for v in W.row(i)) for i in range(W.rows)), None, ring.one)
        minors = psd_minors(HW)
        conditions = _minor_conditions(minors, ring, W)
        kb = kernel_bounds(scene.approximation, scene.delays[0])
        outcome = Outcome(Decision.SYMBOLIC,
                          Evidence(Method.STRUCTURAL, facts={"kappa_K": kb.kappa_K, "argmin": kb.argmin_K}),
                          w(f"B = 0: M(c) = 2 diag(b - z_a) + 2 Re k_K(c) T Kmat with Kmat >= 0 and min Re k_K = "
                            f"-{kb.kappa_K} attained at c = {kb.argmin_K}: exact"))
        return MatrixWorstCase(outcome, _and(conditions), "loewner-dirichlet", kb.argmin_K, {"minors": minors})
    outcome = Outcome(Decision.UNDECIDED, Evidence(Method.STRUCTURAL, facts={"reason": "no structure applies"}),
                      "symbolic parameters with delays and damping (or unequal delays): substitute numbers for an exact decision")
    return MatrixWorstCase(outcome, None, "none")


#: ``PSD(M)``: the condition "the constant matrix M is positive semidefinite" (printed for m > 3,
#: where listing every principal minor would be unreadable).
PSD = sp.Function("PSD")


def _minor_conditions(minors: Mapping, ring: PolyRing, matrix: Any) -> list[sp.Basic]:
    """``minor >= 0`` for every principal minor not certified non-negative (m <= 3), else
    the single condition ``PSD(matrix)``."""
    open_minors = [mn for mn in minors.values() if not nonnegative_certificate(ring, mn.num)]
    if not open_minors:
        return []
    if max(len(k) for k in minors) > 3:
        return [PSD(sp.ImmutableMatrix(matrix))]
    return [sp.Ge(mn.expr(), 0, evaluate=False) for mn in open_minors]


def _mode_condition(wall: SingleUserScene) -> sp.Basic:
    """Exact worst-case condition of one mode, as ``b - z_a >= bound``."""
    K = wall.H
    if wall.has_delay:
        # B = 0: Dirichlet kernel, exact (see hapticproof.analysis.delayed)
        stiffness = exact_cancel(K).subs(Z_SYM, 1)
        kb = kernel_bounds(wall.approximation, int(wall.delay))
        return sp.Ge(wall.b - wall.z_a, sp.expand(kb.kappa_K * wall.T * stiffness))
    cond = single_worst_case(wall).condition
    if not isinstance(cond, sp.Rel) or not sp.sympify(wall.b).is_Symbol:
        return cond                 # settled by the signs (sp.true / sp.false), or b a number: nothing to solve for
    bound = sp.solve(sp.Eq(cond.lhs - cond.rhs, 0), wall.b)
    if len(bound) != 1:
        return cond
    return sp.Ge(wall.b - wall.z_a, sp.expand(bound[0] - wall.z_a))


@stage("conditions")
def conditions(scene: MultiUserScene) -> list[Condition]:
    """Definition 2 for the matrix ``G^{-1}``, each condition decided: poles in the closed disk
    and simple on the circle (those of the kernels ``k_K``, ``k_B``, parameter-free), the residue
    matrix at ``z = 1`` (``T Kmat``) PSD, the Hermitian part PSD for every ``c``.

    >>> s = MultiUserScene.uniform(2, b="0.02", K0=10, B0=0, K=5, B=0, T="0.001")
    >>> [c.decision.value for c in conditions(s)]
    ['proved', 'proved', 'proved', 'proved']

    Uniform scenes with :data:`MODE_USERS` users or more are decided by their extreme modes
    (:func:`hapticproof.analysis.modes.mode_conditions`: two single-user decisions, any ``m``).
    """
    names = scene.naming()
    if scene.is_numeric and by_modes(scene):
        return named_conditions(mode_conditions(scene), names, numeric=True)
    dens = flint.fmpq_poly([1])
    for n in sorted(set(scene.delays)):
        for _, den in _kernel_polynomials(scene.approximation, n):
            dens = dens * den / dens.gcd(den)
    roots = locate_roots(dens, "disk")
    facts = {"certificate": roots, "kernel_denominator": str(dens)}
    # z = oo: G^-1 = diag(b - z_a) + T Kmat k_K + Bmat k_B is proper when its kernels are (they
    # are, for every approximation: k_B = z^-n I (z - 1)/(Tz)); a numeric scene is checked entry by
    # entry in case a kernel ever is not
    kernel_ends = [decide_infinity(k, "disk", "the kernel") for n in sorted(set(scene.delays))
                   for k in _kernel_polynomials(scene.approximation, n)]
    infinity = next((o for o in kernel_ends if o.decision != Decision.PROVED), kernel_ends[0])
    if infinity.decision != Decision.PROVED and scene.is_numeric:
        entries = [[(_poly(e["num"]), _poly(e["den"])) for e in row] for row in transfer_entries(scene)["entries"]]
        infinity = decide_infinity(entries, "disk", "G^-1")
    facts["infinity"] = infinity.evidence.facts["certificate"]
    if infinity.decision == Decision.DISPROVED:
        poles_ok = Outcome(Decision.DISPROVED, Evidence(infinity.evidence.method, witness=infinity.witness, facts=facts),
                           infinity.reason)
    else:
        poles_ok = Outcome(Decision.PROVED if roots.outside == 0 else Decision.DISPROVED,
                           Evidence(Method.ROOT_ISOLATION, facts=facts),
                           "the poles of G^-1 are among those of its kernels: "
                           + (f"none outside the unit circle ({sum(r.multiplicity for r in roots.boundary)} on it)"
                              if roots.outside == 0 else f"{roots.outside} outside the unit circle")
                           + ", none at z = oo (proper kernels)")
    simple_ok = Outcome(Decision.PROVED if roots.boundary_simple else Decision.DISPROVED,
                        Evidence(Method.ROOT_ISOLATION, facts=facts),
                        "every unit-circle pole of the kernels is simple" if roots.boundary_simple
                        else "a unit-circle pole of the kernels is not simple")
    if by_modes(scene):
        residue = _mode_residue(scene)
    else:
        residue = _matrix_residue(scene)
    wc = worst_case(scene)
    herm = wc.outcome
    if wc.decision == Decision.SYMBOLIC and wc.condition is not None:
        herm = Outcome(Decision.SYMBOLIC, herm.evidence, f"{names.text(wc.condition)} ({herm.reason})", minimiser=wc.minimiser)
    conds = [Condition("poles in |z| <= 1", poles_ok), Condition("unit-circle poles simple", simple_ok),
             Condition("residue matrix at z = 1 PSD", residue), Condition("M(c) = G^-1 + G^-H PSD for all c", herm)]
    return named_conditions(conds, names, numeric=scene.is_numeric)


def _mode_residue(scene: MultiUserScene) -> Outcome:
    """``T Kmat = T (K_0 I + K L)`` PSD iff ``T (K_0 + lambda K) >= 0`` at ``lambda = 0`` and ``lambda_max``."""
    top = largest_eigenvalue(scene)
    K = scene.K[0] if scene.K else sp.Integer(0)
    ends = [sp.expand(scene.T * scene.K0[0]), sp.expand(scene.T * (scene.K0[0] + top * K))]
    names = scene.naming()
    what = names.words("the residue matrix T Kmat at z = 1 (eigenvalues T(K_0 + lambda K), lambda in [0, lambda_max])")
    if all(v.is_nonnegative for v in ends):
        return Outcome(Decision.PROVED, Evidence(Method.STRUCTURAL, facts={"eigenvalues": ends}),
                       f"{what} is PSD: " + names.words("T K_0 >= 0 and T(K_0 + lambda_max K) >= 0") + " under the "
                       "parameters' signs")
    if any(v.is_negative for v in ends):
        return Outcome(Decision.DISPROVED, Evidence(Method.STRUCTURAL, witness={"eigenvalue": min(ends)}), f"{what} is not PSD")
    cond = sp.And(*[sp.Ge(v, 0) for v in ends if not v.is_nonnegative])
    return Outcome(Decision.SYMBOLIC, Evidence(Method.STRUCTURAL, facts={"condition": cond}), f"{what} is PSD iff {names.text(cond)}")


def _matrix_residue(scene: MultiUserScene) -> Outcome:
    R = sp.Matrix(scene.T * stiffness_matrix(scene))
    # a numeric scene's reasons are worded once, with its conditions; a symbolic one's here
    what = "the residue matrix T Kmat at z = 1" if scene.is_numeric else scene.naming().words("the residue matrix T Kmat at z = 1")
    if R.free_symbols:
        from hapticproof.exact.psd import psd_outcome

        return psd_outcome(R, what)
    return decide_constant_psd(R, what)


def check_work(scene: MultiUserScene) -> None:
    """Refuse, before any algebra, what the decision would refuse after it: a scene not decided
    by modes whose residue matrix ``T Kmat`` has parameters is decided by its ``2^m - 1``
    principal minors (:func:`hapticproof.core.limits.check_minors`).

    >>> from hapticproof.systems.multiuser import MultiUserScene
    >>> check_work(MultiUserScene.symbolic(3))
    >>> check_work(MultiUserScene.symbolic(20))
    Traceback (most recent call last):
    ...
    hapticproof.core.limits.LimitError: the residue matrix T Kmat at z = 1: 2^20 - 1 principal minors (of a 20 x 20 matrix) is above the limit of 4096 (raise it with --limit minors=N)
    """
    from hapticproof.core.limits import check_minors

    if by_modes(scene):
        return
    if any(sp.sympify(v).free_symbols for v in (scene.T, *scene.K0, *scene.K)):
        check_minors(scene.users, "the residue matrix T Kmat at z = 1")


@stage("positive_real")
def positive_real(scene: MultiUserScene) -> Outcome:
    """All three conditions of Definition 2 for ``G^{-1}``, combined (:func:`conditions`)."""
    check_work(scene)
    return combine(conditions(scene))


def hve_leading_minor_counterexample() -> tuple[MultiUserScene, Any]:
    """A dual-user HVE the leading-minor shortcut (HVE Definition 3) declares positive real at
    *every* frequency although it is not: two uncoupled users, user 1 exactly at Colgate's
    bound (``b_1 = K_01 T/2``, ``B_01 = 0``) so that ``M_11 = 0`` identically, user 2 below it.
    Returns the scene and the :class:`~hapticproof.exact.psd.CircleDecision` of the exact test.

    >>> scene, decision = hve_leading_minor_counterexample()
    >>> decision.decision.value, decision.witness, decision.failing
    ('disproved', -1, 1)
    """
    scene = MultiUserScene.from_values(b=[sp.Rational(1, 2), sp.Rational(1, 4)], T=1, K0=[1, 1], B0=[0, 0], edges=())
    H = hermitian(scene)
    lead = psd_minors(H, subsets=[(0,), (0, 1)])
    if not all(mn.num.is_zero() for mn in lead.values()):
        raise DerivationError("the leading minors of the counterexample scene should vanish identically")
    return scene, decide_psd_on_circle(H)
