r"""The naming context of a scene: the :class:`~hapticproof.core.naming.Naming` its views print
with, built from the scene's roles and every name it uses (:mod:`hapticproof.systems.roles`).

A :class:`~hapticproof.systems.scene.Scene` produces it (:func:`scene_naming`) and gives it to
the model it builds (its ``names`` field, only when the model's own symbols would not give the
same names: a numeric scene has lost the names of its period and dampings); a model built
directly in Python names itself from its symbols (:func:`model_naming`). Every view asks the
model (``model.naming()``); none invents a name.

>>> from hapticproof.systems.scene import Scene
>>> names = Scene("single-user", roles={"period": "h", "device_damping": "c_d"}, params={"h": "0.001"}).build().naming()
>>> names.period, names.helper("cos"), names.cos_latex
('h', 'gamma', '\\cos(\\omega h)')
>>> Scene("single-user").build().naming().is_default
True
"""

from __future__ import annotations

import functools
from collections.abc import Iterable, Mapping
from dataclasses import replace
from typing import Any

import sympy as sp

from hapticproof.core.naming import Naming
from hapticproof.systems.roles import FIXED_NAMES, ROLES, role_names

__all__ = ["choose_naming", "model_naming", "scene_names", "scene_roles", "scene_naming", "with_naming"]


@functools.lru_cache(maxsize=1024)
def choose_naming(taken: frozenset, roles: tuple) -> Naming:
    """:meth:`Naming.choose`, cached (scenes ask for their naming for every view)."""
    return Naming.choose(taken, roles)


def _name(value: Any, default: str) -> str:
    return value.name if isinstance(value, sp.Symbol) else default


def model_naming(system: str, values: Mapping[str, Any], free: Iterable[Any]) -> Naming:
    """The naming a model gives itself: each role named by its symbol (``values``: field ->
    the model's value; a number keeps the role's default name), the helpers chosen to avoid
    the names of its free symbols ``free``.

    >>> T, c = sp.Symbol("Ts", positive=True), sp.Symbol("c", positive=True)
    >>> model_naming("single-user", {"period": T, "device_damping": c}, {T, c}).helper("cos")
    'gamma'
    """
    roles = tuple((field, role.default, _name(values.get(field), role.default)) for field, role in ROLES[system].items())
    taken = frozenset(s.name for s in free if isinstance(s, sp.Symbol)) - {"z", "s"}
    return choose_naming(taken, roles)


def scene_names(scene: Any) -> set[str]:
    """Every name a scene uses: its parameters (valued or not), its roles' and its fixed names."""
    table = ROLES[scene.system]
    taken = set(scene.names()) | set(dict(scene.params)) | set(FIXED_NAMES[scene.system])
    if table:
        taken |= set(role_names(scene.system, scene.roles, scene.users))
    return taken


def scene_roles(scene: Any) -> tuple[tuple[str, str, str], ...]:
    """``(field, default, name)`` of every role of the scene's system (a multi-user role listed per
    user keeps its default as the group's name)."""
    return tuple((field, role.default, scene.role(field) or role.default) for field, role in ROLES[scene.system].items())


def scene_naming(scene: Any, extra: Iterable[str] = ()) -> Naming:
    """The naming of a :class:`~hapticproof.systems.scene.Scene`: its roles' names and helpers
    that avoid every name the scene uses (:func:`scene_names`) and the names ``extra`` (those of
    the paper a scene belongs to: one paper, one choice of helper names)."""
    taken = scene_names(scene) | set(extra)
    return choose_naming(frozenset(taken - {"z", "s"}), scene_roles(scene))


def with_naming(scene: Any, model: Any, extra: Iterable[str] = ()) -> Any:
    """``model`` carrying the scene's naming when its own symbols would name it otherwise (the
    same model otherwise, so that equal scenes in the papers' names stay equal models); ``extra``
    are more names to avoid (:func:`scene_naming`)."""
    if not hasattr(model, "naming"):
        return model
    naming = scene_naming(scene, extra)
    own = model.naming()
    if (naming.roles, naming.helpers) == (own.roles, own.helpers):
        return model
    return replace(model, names=naming)
