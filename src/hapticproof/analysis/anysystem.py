"""Positive realness of any system, from one entry point: the decision ``hapticproof.positive_real``.

Each system kind has its decision (Definition 2 of the HVE paper for ``G^{-1}(z)`` of a single or
an m-user scene, the theorem of the bilateral paper for a teleoperator, Definition 3 for an n-port
impedance ``Z(s)``, the same definitions for any matrix or python-control system); this module
chooses it from what it is given and returns its :class:`~hapticproof.core.evidence.Outcome` --
the decision, its reason, its evidence (certificates, witness) -- exactly as the command line
(``derive``) computes it. A scene is built first; a built model, a SymPy expression or matrix in
``z`` or ``s``, a SymPy ``TransferFunction`` or a python-control system is decided as it is.

>>> from hapticproof.systems.scene import Scene
>>> [positive_real(Scene(kind, **extra)).decision.value for kind, extra in (
...     ("single-user", {"params": {"K": 2, "B": 0, "b": "0.02", "T": "0.001"}}),
...     ("multi-user", {"users": 2, "uniform": True, "params": {"b": 1, "K_0": 1, "B_0": 0, "K": 1, "B": 0, "T": "0.01"}}),
...     ("teleoperator", {"params": {"K": 1, "B": 0, "T": "0.015", "b_m": "0.01822", "b_s": "0.01822"}}),
...     ("network", {"matrix": [["1/(s + 1)", "0"], ["0", "s"]]}))]
['proved', 'proved', 'proved', 'proved']
>>> import sympy as sp
>>> positive_real((sp.Symbol("z") - sp.Rational(1, 2)) / sp.Symbol("z")).decision.value
'proved'
"""

from __future__ import annotations

from typing import Any

import sympy as sp

from hapticproof.core.errors import InputFormatError
from hapticproof.core.evidence import Outcome
from hapticproof.core.symbols import s as S_SYM

__all__ = ["positive_real"]


def positive_real(system: Any) -> Outcome:
    """Is ``system`` positive real (passive)? The exact decision of its kind, with its evidence.

    ``system``: a :class:`~hapticproof.systems.scene.Scene` of any kind or its build (a
    single-user, m-user or teleoperator scene, a network's impedance matrix), a SymPy expression
    or matrix in ``z`` (discrete) or ``s`` (continuous), a SymPy ``TransferFunction`` or
    ``TransferFunctionMatrix``, a python-control system or an
    :class:`~hapticproof.systems.lti.ExactSystem`.
    """
    from hapticproof.systems.multiuser import MultiUserScene
    from hapticproof.systems.scene import Scene
    from hapticproof.systems.singleuser import SingleUserScene
    from hapticproof.systems.teleoperator import TeleoperatorScene

    if isinstance(system, Scene):
        return positive_real(system.build())
    if isinstance(system, SingleUserScene):
        from hapticproof.analysis.positivereal import positive_real as single_user

        return single_user(system)
    if isinstance(system, MultiUserScene):
        from hapticproof.analysis.multiuser import positive_real as multi_user

        return multi_user(system)
    if isinstance(system, TeleoperatorScene):
        from hapticproof.analysis.teleoperator import passivity

        return passivity(system)
    if _is_impedance_matrix(system):
        from hapticproof.analysis.nport import positive_real as n_port     # a network's Z(s), as `derive network`

        return n_port(system).outcome
    from hapticproof.analysis.passivity import ispassive

    try:
        return ispassive(system).outcome
    except (TypeError, AttributeError) as err:
        raise InputFormatError(f"positive_real: cannot read a {type(system).__name__} as a system (a scene, its "
                               "build, a SymPy expression or matrix in z or s, or a python-control system)") from err


def _is_impedance_matrix(system: Any) -> bool:
    """A SymPy matrix of numbers and ``s`` only: an n-port impedance (a network scene's build; a
    constant matrix is positive real in either domain exactly when its symmetric part is PSD)."""
    if not isinstance(system, sp.MatrixBase):
        return False
    return set().union(*(sp.sympify(e).free_symbols for e in system)) <= {S_SYM}
