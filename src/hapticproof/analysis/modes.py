r"""Uniform m-user scenes decided by modes: two single-user walls instead of ``2^m`` minors.

A uniform scene (HVE paper, Section 3.2: one ``b``, ``K_0``, ``B_0``, ``z_a`` for every user, one
``K`` and ``B`` on every edge of the coupling graph, one delay ``n``) has ``Kmat = K_0 I + K L`` and
``Bmat = B_0 I + B L`` with ``L`` the unweighted Laplacian of the graph. With ``L = U diag(lambda) U^T``
(``U`` real orthogonal, constant)

.. math:: G^{-1}(z) = U \operatorname{diag}\big(g_\lambda(z)\big) U^T, \qquad
          g_\lambda = (b - z_a) + z^{-n} \big((K_0 + \lambda K)\, T k_K(z) + (B_0 + \lambda B)\, k_B(z)\big),

so ``G^{-1}`` is positive real iff every mode ``g_lambda`` is (poles, residue matrices and the
Hermitian part are all congruent to diagonal ones). Every mode has its poles among the kernels'
(``z = 0`` and a simple ``z = 1``), its residue at ``z = 1`` is ``T (K_0 + lambda K)`` and, for each
``c``, ``Re g_lambda(c)`` is **affine in lambda**: the set of ``lambda`` whose mode is positive real
is an interval. The Laplacian's eigenvalues lie in ``[0, lambda_max]`` and ``0`` is one of them, so

    ``G^{-1}`` is positive real  iff  the modes ``lambda = 0`` and ``lambda = lambda_max`` are,

two single-user decisions on the fast path (:mod:`hapticproof.analysis.fastpath`), whatever ``m``.
A failing mode's witness ``c`` is a witness for the matrix (``M(c)`` has the eigenvalue
``2 Re g_lambda(c) < 0``). The spectra are exact: complete graph ``{0, m}``, star ``{0, 1, m}``, path
``2 - 2 cos(pi k/m)``, ring (circulant) ``2 - 2 cos(2 pi k/m)``; other graphs by SymPy up to
:data:`GENERAL_GRAPH_USERS` users. An irrational ``lambda_max`` (a path, an odd ring) is bracketed
by rationals ``lo < lambda_max < hi``: the mode at ``hi`` positive real proves it (with ``lambda = 0``),
the mode at ``lo`` not positive real disproves it (affinity: the failure only grows with ``lambda``).

>>> from hapticproof.systems.multiuser import MultiUserScene
>>> scene = MultiUserScene.uniform(1000, b="0.02", K0=1, B0=0, K="0.05", B=0, T="0.001")    # b < (K_0 + m K) T/2
>>> largest_eigenvalue(scene)
1000
>>> [c.decision.value for c in mode_conditions(scene)]
['proved', 'proved', 'proved', 'disproved']
"""

from __future__ import annotations

from dataclasses import dataclass
from fractions import Fraction
from typing import Any

import flint
import sympy as sp

from hapticproof.core.errors import SceneError
from hapticproof.core.evidence import Decision, Evidence, Method, Outcome
from hapticproof.exact.conditions import Condition
from hapticproof.exact.kernel import locate_roots
from hapticproof.systems.multiuser import MultiUserScene, laplacian

__all__ = ["GENERAL_GRAPH_USERS", "graph_kind", "spectrum", "largest_eigenvalue", "decides_by_modes", "mode_wall",
           "ModeDecision", "decide_mode", "mode_conditions"]

#: Arbitrary coupling graphs get their Laplacian spectrum from SymPy up to this many users.
GENERAL_GRAPH_USERS = 12

#: Names of the matrix conditions (those of :func:`hapticproof.analysis.multiuser.conditions`).
POLES = "poles in |z| <= 1"
SIMPLE = "unit-circle poles simple"
RESIDUE = "residue matrix at z = 1 PSD"
HERMITIAN = "M(c) = G^-1 + G^-H PSD for all c"


def graph_kind(scene: MultiUserScene) -> str:
    """``complete``, ``star``, ``path``, ``ring`` or ``other`` (by the edges; 0-based users).

    >>> graph_kind(MultiUserScene.uniform(4, edges=[(0, 1), (1, 2), (2, 3), (0, 3)]))
    'ring'
    """
    if scene.is_complete:
        return "complete"
    m, edges = scene.users, set(scene.edges)
    path = {(i, i + 1) for i in range(m - 1)}
    if edges == path:
        return "path"
    if m >= 3 and edges == path | {(0, m - 1)}:
        return "ring"
    if edges == {(0, i) for i in range(1, m)}:
        return "star"
    return "other"


def spectrum(scene: MultiUserScene) -> dict[sp.Expr, int] | None:
    """The Laplacian eigenvalues of the unweighted coupling graph with their multiplicities, exact
    (``None``: an arbitrary graph with more than :data:`GENERAL_GRAPH_USERS` users).

    >>> spectrum(MultiUserScene.uniform(3, edges=[(0, 1), (1, 2)]))
    {0: 1, 1: 1, 3: 1}
    """
    m, kind = scene.users, graph_kind(scene)
    if m == 1:
        return {sp.Integer(0): 1}
    if kind == "complete":
        return {sp.Integer(0): 1, sp.Integer(m): m - 1}
    if kind == "star":
        return {sp.Integer(0): 1, sp.Integer(1): m - 2, sp.Integer(m): 1} if m > 2 else {sp.Integer(0): 1, sp.Integer(2): 1}
    out: dict[sp.Expr, int] = {}
    if kind == "path":
        for k in range(m):
            lam = sp.nsimplify(2 - 2 * sp.cos(sp.pi * k / m))
            out[lam] = out.get(lam, 0) + 1
        return out
    if kind == "ring":
        for k in range(m // 2 + 1):
            lam = sp.nsimplify(2 - 2 * sp.cos(2 * sp.pi * sp.Rational(k, m)))
            out[lam] = out.get(lam, 0) + (1 if k == 0 or 2 * k == m else 2)
        return out
    if m > GENERAL_GRAPH_USERS:
        return None
    return dict(laplacian([0] * m, scene.weights([1] * len(scene.edges))).eigenvals())


def largest_eigenvalue(scene: MultiUserScene) -> sp.Expr | None:
    """``lambda_max`` of the unweighted Laplacian, exact (``None`` when :func:`spectrum` is).

    >>> largest_eigenvalue(MultiUserScene.uniform(5, edges=[(0, 1), (1, 2), (2, 3), (3, 4), (0, 4)]))
    sqrt(5)/2 + 5/2
    """
    m, kind = scene.users, graph_kind(scene)
    if m == 1 or not scene.edges:
        return sp.Integer(0)
    if kind in ("complete", "star"):
        return sp.Integer(m) if m > 2 or kind == "complete" else sp.Integer(2)
    if kind == "path" or (kind == "ring" and m % 2):
        return sp.nsimplify(2 + 2 * sp.cos(sp.pi / m))
    if kind == "ring":
        return sp.Integer(4)
    values = spectrum(scene)
    return None if values is None else max(values, key=lambda v: float(v))


def decides_by_modes(scene: MultiUserScene) -> bool:
    """A uniform scene with one delay whose ``lambda_max`` is known in closed form."""
    return scene.is_uniform and scene.equal_delays and (graph_kind(scene) != "other" or scene.users <= GENERAL_GRAPH_USERS)


def mode_wall(scene: MultiUserScene, lam: Any) -> Any:
    """The mode ``g_lambda`` of a numeric uniform scene at a rational ``lambda``, as a
    :class:`~hapticproof.analysis.fastpath.NumericScene` (the wall ``K_0 + lambda K``, ``B_0 + lambda B``).

    >>> mode_wall(MultiUserScene.uniform(2, b=1, K0=2, B0=0, K=3, B=0, T="0.001"), 2).H[0]
    (Fraction(0, 1), Fraction(1, 125))
    """
    from hapticproof.analysis.fastpath import NumericScene

    lam = Fraction(lam)
    value = lambda v: Fraction(int(sp.Rational(v).p), int(sp.Rational(v).q))  # noqa: E731
    K = scene.K[0] if scene.K else 0
    B = scene.B[0] if scene.B else 0
    return NumericScene.virtual_wall(K=value(scene.K0[0]) + lam * value(K), B=value(scene.B0[0]) + lam * value(B),
                                     b=value(scene.b[0]), T=value(scene.T), approximation=scene.approximation,
                                     delay=int(scene.delays[0]), z_a=value(scene.z_a[0]))


@dataclass(frozen=True)
class ModeDecision:
    """The decision of one mode: the eigenvalue ``lambda`` it stands for (exact; ``bracket`` the
    rational ``lambda`` actually decided when ``lambda`` is irrational, with ``side`` ``'above'`` or
    ``'below'``) and its whole single-user decision."""

    eigenvalue: sp.Expr
    decided_at: Fraction
    side: str
    outcome: Outcome

    def to_json(self) -> dict[str, Any]:
        return {"eigenvalue": sp.sstr(self.eigenvalue), "decided_at": str(self.decided_at), "side": self.side,
                "decision": self.outcome.decision.value, "reason": self.outcome.reason}


def _bracket(lam: sp.Expr, bits: int) -> tuple[Fraction, Fraction]:
    """Rationals ``lo < lam < hi`` within ``2^-bits`` (``lam`` an irrational real number)."""
    value = sp.N(lam, bits // 3 + 20)
    mid = Fraction(int(sp.Rational(value).p), int(sp.Rational(value).q))
    step = Fraction(1, 2**bits)
    lo, hi = mid - step, mid + step
    if not (sp.Rational(lo.numerator, lo.denominator) < lam < sp.Rational(hi.numerator, hi.denominator)):
        raise ArithmeticError(f"could not bracket {lam}")                       # pragma: no cover
    return lo, hi


def decide_mode(scene: MultiUserScene, lam: sp.Expr, *, minimum: bool = False, bits: tuple[int, ...] = (32, 96, 256)) -> ModeDecision:
    """Decide the mode at the eigenvalue ``lam`` (exact; bracketed when irrational, see the module
    docstring: correct only for ``lam = lambda_max`` with the mode ``lambda = 0`` positive real)."""
    from hapticproof.analysis.fastpath import decide

    if lam.is_Rational:
        value = Fraction(int(lam.p), int(lam.q))
        return ModeDecision(lam, value, "exact", decide(mode_wall(scene, value), minimum=minimum))
    last = None
    for b in bits:
        lo, hi = _bracket(lam, b)
        above = decide(mode_wall(scene, hi), minimum=minimum)
        if above.decision == Decision.PROVED:
            return ModeDecision(lam, hi, "above", above)
        below = decide(mode_wall(scene, lo), minimum=minimum)
        if below.decision == Decision.DISPROVED:
            return ModeDecision(lam, lo, "below", below)
        last = (lo, hi, above, below)
    lo, hi, above, below = last
    out = Outcome(Decision.UNDECIDED, Evidence(Method.STRUCTURAL, facts={"below": below, "above": above}),
                  f"the mode lambda = {sp.sstr(lam)} lies on the passivity boundary within 2^-{bits[-1]}: positive real at "
                  f"lambda = {lo}, not at {hi}")
    return ModeDecision(lam, hi, "undecided", out)


def _kernel_denominator(scene: MultiUserScene) -> flint.fmpq_poly:
    """``z^n`` times the least common denominator of the kernels ``k_K = I/T`` and ``k_B = I (z-1)/(T z)``."""
    from hapticproof.analysis.fastpath import integrator_polynomials

    inum, iden = integrator_polynomials(scene.approximation, 1)
    z = flint.fmpq_poly([0, 1])
    kb_den = z // inum.gcd(z) if not inum.is_zero() else z
    den = iden * kb_den // iden.gcd(kb_den)
    return den * flint.fmpq_poly([0] * int(scene.delays[0]) + [1])


def mode_conditions(scene: MultiUserScene) -> list[Condition]:
    """Definition 2 for the matrix ``G^{-1}`` of a numeric uniform scene, by its modes at ``lambda = 0``
    and ``lambda_max`` (the conditions of :func:`hapticproof.analysis.multiuser.conditions`, same names).

    >>> from hapticproof.systems.multiuser import MultiUserScene
    >>> s = MultiUserScene.uniform(7, b="0.05", K0=10, B0=0, K=1, B=0, T="0.001", edges=[(i, i + 1) for i in range(6)])
    >>> [c.decision.value for c in mode_conditions(s)]
    ['proved', 'proved', 'proved', 'proved']
    """
    if not scene.is_numeric:
        raise SceneError("mode_conditions needs numeric parameters")
    if not decides_by_modes(scene):
        raise SceneError("mode_conditions needs a uniform scene with one delay on a graph of known spectrum")
    top = largest_eigenvalue(scene)
    modes = [decide_mode(scene, sp.Integer(0))]
    if top != 0 and modes[0].outcome.decision == Decision.PROVED:
        modes.append(decide_mode(scene, top))
    elif top != 0 and top.is_Rational:
        modes.append(decide_mode(scene, top))
    den = _kernel_denominator(scene)
    roots = locate_roots(den, "disk")
    facts = {"certificate": roots, "kernel_denominator": str(den)}
    poles_ok = Outcome(Decision.PROVED if roots.outside == 0 else Decision.DISPROVED, Evidence(Method.ROOT_ISOLATION, facts=facts),
                       "the poles of G^-1 are among those of its kernels: "
                       + (f"none outside the unit circle ({sum(r.multiplicity for r in roots.boundary)} on it)"
                          if roots.outside == 0 else f"{roots.outside} outside the unit circle"))
    simple_ok = Outcome(Decision.PROVED if roots.boundary_simple else Decision.DISPROVED, Evidence(Method.ROOT_ISOLATION, facts=facts),
                        "every unit-circle pole of the kernels is simple" if roots.boundary_simple
                        else "a unit-circle pole of the kernels is not simple")
    T = Fraction(str(scene.T)) if scene.T.is_Rational else None
    K0 = Fraction(str(scene.K0[0]))
    K = Fraction(str(scene.K[0])) if scene.K else Fraction(0)
    # eigenvalues of T Kmat = T (K_0 + lambda K) over lambda in [0, lambda_max]: affine, checked at both ends
    ends = [T * K0] + ([T * (K0 + md.decided_at * K) for md in modes[1:]] if K >= 0 else [])
    residue = Outcome(Decision.PROVED if all(v >= 0 for v in ends) and K >= 0 else Decision.DISPROVED,
                      Evidence(Method.STRUCTURAL, facts={"eigenvalues": [str(v) for v in ends]}),
                      "the residue matrix T Kmat at z = 1 has the eigenvalues T(K_0 + lambda K) >= "
                      f"{min(ends)} (lambda in [0, {sp.sstr(top)}])")
    herm = _hermitian_from_modes(scene, modes, top)
    return [Condition(POLES, poles_ok), Condition(SIMPLE, simple_ok), Condition(RESIDUE, residue), Condition(HERMITIAN, herm)]


def _hermitian_from_modes(scene: MultiUserScene, modes: list[ModeDecision], top: sp.Expr) -> Outcome:
    facts = {"modes": [md.to_json() for md in modes], "mode_outcomes": [md.outcome for md in modes],
             "lambda_max": sp.sstr(top), "users": scene.users, "graph": graph_kind(scene)}
    how = (f"uniform couplings: G^-1 = U diag(g_lambda) U^-1 (U orthogonal) over the Laplacian eigenvalues lambda in [0, {sp.sstr(top)}]; "
           "Re g_lambda is affine in lambda, so the modes lambda = 0 and lambda_max decide")
    for md in modes:
        d = md.outcome.decision
        if d == Decision.DISPROVED:
            herm = _condition_of(md.outcome, "Re G^-1 >= 0 for all w")
            if herm is None or herm.decision != Decision.DISPROVED:          # a pole/residue condition failed
                return Outcome(Decision.DISPROVED, Evidence(Method.STRUCTURAL, witness=md.outcome.witness, facts=facts),
                               f"the mode lambda = {sp.sstr(md.eigenvalue)} is not positive real: {md.outcome.reason}")
            where = "" if md.side == "exact" else f" (decided at lambda = {md.decided_at} < lambda_max: the failure grows with lambda)"
            return Outcome(Decision.DISPROVED, Evidence(Method.STRUCTURAL, witness=herm.witness, facts=facts),
                           f"M(c) has the eigenvalue 2 Re g_lambda(c) < 0 for lambda = {sp.sstr(md.eigenvalue)}{where}: "
                           f"{herm.reason}")
        if d != Decision.PROVED:
            return Outcome(Decision.UNDECIDED, Evidence(Method.STRUCTURAL, facts=facts),
                           f"the mode lambda = {sp.sstr(md.eigenvalue)}: {md.outcome.reason}")
    return Outcome(Decision.PROVED, Evidence(Method.STRUCTURAL, facts=facts), how + ": both are positive real")


def _condition_of(outcome: Outcome, name: str) -> Outcome | None:
    for cond in outcome.evidence.facts.get("conditions", []):
        if cond.name == name:
            return cond.outcome
    return None
