r"""Transfer functions built from scenes: the integrator approximations and ``G^{-1}(z)``.

Each approximation of ``X_h(z) = Z{v_h/s}`` is *derived* from its recurrence (HVE paper,
Section 3.1.1) by z-transforming it with the shift rule ``x(k+1) -> z X`` and solving for
``X/V``; ``G^{-1}(z) = (b - z_a) + z^{-n} H(z) X_h(z)/V_h(z)`` (the three forms before eq. 17,
and eqs. 21-22). The tests compare the integrators with ``sympy.physics.control``'s
``forward_diff``, ``backward_diff`` and ``bilinear`` (an independent implementation).

>>> import sympy as sp
>>> from hapticproof.core.symbols import z
>>> T = sp.Symbol('T', positive=True)
>>> integrator("forward", T), integrator("backward", T), sp.factor(integrator("tustin", T))
(T/(z - 1), T*z/(z - 1), T*(z + 1)/(2*(z - 1)))
"""

from __future__ import annotations

from functools import lru_cache

import sympy as sp

from hapticproof.core.errors import SceneError
from hapticproof.core.lazy import stage
from hapticproof.systems.singleuser import APPROXIMATIONS, SingleUserScene
from hapticproof.core.symbols import z as Z_SYM

__all__ = ["RECURRENCES", "integrator", "inverse_transfer", "environment_path", "transfer_from_recurrence"]

# Recurrences relating samples of x_h and v_h = dx_h/dt, written with x(k), x(k+1), v(k), v(k+1)
# (the HVE paper's forward, backward and Tustin forms, normalised to advance by one step).
_xk, _xk1, _vk, _vk1, _T = sp.symbols("x_k x_k1 v_k v_k1 T")
RECURRENCES: dict[str, sp.Eq] = {
    "forward": sp.Eq(_xk1, _xk + _T * _vk),
    "backward": sp.Eq(_xk1, _xk + _T * _vk1),
    "tustin": sp.Eq(_xk1, _xk + _T * _vk + (_vk1 - _vk) * _T / 2),
}


@lru_cache(maxsize=None)
def _integrator_template(approximation: str) -> sp.Expr:
    """``X/V`` solved from the z-transformed recurrence (shift rule ``x(k+1) -> zX``)."""
    X, V = sp.symbols("X V")
    transformed = RECURRENCES[approximation].subs(
        {_xk1: Z_SYM * X, _xk: X, _vk1: Z_SYM * V, _vk: V}, simultaneous=True
    )
    # the transformed recurrence is linear in X: a X + r = 0 (no sp.solve, which simplifies)
    residual = sp.expand(transformed.lhs - transformed.rhs)
    a, r = residual.coeff(X), residual.subs(X, 0)
    if a == 0 or sp.expand(a * X + r - residual) != 0:
        raise SceneError(f"the {approximation} recurrence is not linear in X")
    return sp.factor(-r / (a * V))


def integrator(approximation: str, T: sp.Expr, z: sp.Symbol = Z_SYM) -> sp.Expr:
    """Discrete approximation of ``1/s`` (the map ``V_h -> X_h``).

    >>> integrator("trapezoid", 1)
    Traceback (most recent call last):
    ...
    hapticproof.core.errors.SceneError: unknown approximation 'trapezoid'; choose one of forward, backward, tustin
    """
    if approximation not in APPROXIMATIONS:
        raise SceneError(
            f"unknown approximation {approximation!r}; choose one of {', '.join(APPROXIMATIONS)}"
        )
    expr = _integrator_template(approximation).subs(_T, T)
    if z != Z_SYM:
        expr = expr.subs(Z_SYM, z)
    return expr


@stage("environment_path")
def environment_path(scene: SingleUserScene) -> sp.Expr:
    """``H(z) X_h/V_h``: the velocity-to-force path through the environment, before delay."""
    from hapticproof.exact.canonical import canonical_rational

    return canonical_rational(scene.H * integrator(scene.approximation, scene.T))


@stage("inverse_transfer")
def inverse_transfer(scene: SingleUserScene) -> sp.Expr:
    """``G^{-1}(z)`` of the scene (force over velocity), eqs. (21)-(22) and the forms before (17).

    >>> scene = SingleUserScene.virtual_wall(delay=2)
    >>> sp.simplify(inverse_transfer(scene) - (scene.b + (scene.H * scene.T/(Z_SYM - 1)) / Z_SYM**2))
    0
    """
    return (scene.b - scene.z_a) + Z_SYM ** (-scene.delay) * environment_path(scene)


def transfer_from_recurrence(
    relation: sp.Basic, x: sp.Function, v: sp.Function, k: sp.Symbol, T: sp.Symbol, z: sp.Symbol = Z_SYM
) -> sp.Expr:
    """``X/V`` of a printed recurrence in the samples ``x(kT + jT)`` and ``v(kT + jT)``.

    Each ``x(kT + jT)`` becomes ``z**j X`` and each ``v(kT + jT)`` becomes ``z**j V`` (the shift
    rule); the transformed equation is solved for ``X/V``. A sample argument that is not
    ``kT`` plus an integer multiple of ``T``, or a side that is not built from samples, raises
    :class:`ValueError` naming it.

    >>> x, v = sp.Function('x'), sp.Function('v')
    >>> k, T = sp.symbols('k T', positive=True)
    >>> transfer_from_recurrence(sp.Eq(x(k*T + T), x(k*T) + T*v(k*T)), x, v, k, T)
    T/(z - 1)
    >>> transfer_from_recurrence(sp.Eq(x(k*T + 3), x(k*T) + T*v(k*T)), x, v, k, T)
    Traceback (most recent call last):
    ...
    ValueError: x(T*k + 3) is not a sample x(kT + jT) with an integer j
    """
    X, V = sp.symbols("X V")
    replacements = {}
    for func, target in ((x, X), (v, V)):
        for call in relation.atoms(func):
            (arg,) = call.args
            shift = sp.simplify((arg - k * T) / T)
            if not shift.is_integer:
                raise ValueError(f"{call} is not a sample {func}(kT + jT) with an integer j")
            replacements[call] = z**shift * target
    transformed = relation.xreplace(replacements)
    if any(s == k for s in transformed.free_symbols):
        raise ValueError("the recurrence has terms that are not samples of x or v")
    if not transformed.lhs.has(X) and not transformed.rhs.has(X):
        raise ValueError("the recurrence has no sample of x")
    solutions = sp.solve(transformed, X)
    if len(solutions) != 1:
        raise ValueError("the recurrence does not determine X")
    return sp.factor(sp.cancel(solutions[0] / V))
