r"""Roles: the parameters a system gives a meaning, and the names a scene assigns them.

The device damping, the sampling period and the device mass (a teleoperator's master and slave
dampings and masses; m users' dampings and masses) are **roles**, not reserved names. A scene
names them as it likes -- ``roles = {"period": "Ts", "device_damping": "b_dev"}`` in Python, a
``[roles]`` table in a scene file or a paper file's ``[scenes.X.roles]``, ``--role period=Ts``
on the command line -- and every answer follows: the model's ``T`` is the symbol ``Ts``,
``--range b_dev`` varies the device damping, the delay margin's ``t_d = N Ts``, a stability
boundary reads the mass from its role. A role not named keeps its default name (``b``, ``T``,
``m``...), so a scene without ``roles`` is the papers' scene. A role's parameter is positive
unless the scene declares another assumption for it.

Multi-user roles name a group (``device_damping = "c"``: ``c`` sets every user's damping,
``c_1``, ..., ``c_m`` set one each, as ``b`` and ``b_i`` do) or list one name per user
(``device_damping = ["c_left", "c_right"]``; a uniform scene takes one name).

>>> ROLES["single-user"]["period"].default
'T'
>>> read_roles("single-user", {"period": "Ts", "device_damping": "b"})     # defaults are dropped
(('period', 'Ts'),)
>>> read_roles("single-user", {"period": "b"})
Traceback (most recent call last):
...
hapticproof.core.errors.SceneError: roles: 'b' names both the device damping and the sampling period
>>> member_names("multi-user", (("device_damping", "c"),), "device_damping", 3)
('c_1', 'c_2', 'c_3')
"""

from __future__ import annotations

import difflib
import functools
import types
from collections.abc import Mapping
from dataclasses import dataclass
from typing import Any

from hapticproof.core.errors import HapticproofError, SceneError

__all__ = [
    "FIXED_NAMES",
    "ROLES",
    "ROLE_ASSUMPTION",
    "Role",
    "check_members",
    "member_names",
    "read_roles",
    "role_name",
    "role_names",
    "role_of_name",
    "role_words",
]


@dataclass(frozen=True, slots=True)
class Role:
    """A role of a system: its field name (``period``), default parameter name (``T``), what it
    means, and whether m users each have one (``per_user``: a group name and per-user names)."""

    field: str
    default: str
    meaning: str
    per_user: bool = False


def _table(*roles: Role) -> dict[str, Role]:
    return {role.field: role for role in roles}


#: The roles of each system, by field name.
ROLES: dict[str, dict[str, Role]] = {
    "single-user": _table(Role("device_damping", "b", "the device damping"),
                          Role("period", "T", "the sampling period"),
                          Role("mass", "m", "the device mass (stability only)")),
    "multi-user": _table(Role("device_damping", "b", "the device dampings", per_user=True),
                         Role("period", "T", "the sampling period"),
                         Role("mass", "m", "the device masses (stability only)", per_user=True)),
    "teleoperator": _table(Role("master_damping", "b_m", "the master damping"),
                           Role("slave_damping", "b_s", "the slave damping"),
                           Role("device_damping", "b", "both dampings"),
                           Role("master_mass", "m_m", "the master mass (stability only)"),
                           Role("slave_mass", "m_s", "the slave mass (stability only)"),
                           Role("mass", "m", "both masses (stability only)"),
                           Role("period", "T", "the sampling period")),
    "network": {},
}

#: Names with a fixed meaning in each system (no role renames them).
FIXED_NAMES: dict[str, dict[str, str]] = {
    "single-user": {"z_a": "the operator's shortage of passivity", "t_d": "the delay time (n = t_d/T)"},
    "multi-user": {},
    "teleoperator": {"alpha": "the position scaling"},
    "network": {},
}

#: The assumption of a role's parameter unless the scene declares another.
ROLE_ASSUMPTION = "positive"

#: The other group names of the m-user model (a role may not take them).
_MULTI_USER_GROUPS = ("K_0", "B_0", "K", "B", "z_a")


def _valid_name(name: Any, where: str) -> str:
    from hapticproof.core.expr import parameter_symbol

    if not isinstance(name, str):
        raise SceneError(f"{where}: a role names a parameter (text), got {name!r}")
    name = name.strip()
    try:
        parameter_symbol(name)
    except HapticproofError as err:
        raise SceneError(f"{where}: {err}") from None
    return name


def read_roles(system: str, roles: Any) -> tuple[tuple[str, Any], ...]:
    """The roles a scene assigns, validated and normalised: sorted ``(field, name)`` pairs (a
    multi-user list as a tuple of names), the roles that keep their default name dropped.

    >>> read_roles("teleoperator", {"master_damping": "c_m", "slave_damping": "c_s"})
    (('master_damping', 'c_m'), ('slave_damping', 'c_s'))
    """
    if roles is None:
        return ()
    table = ROLES[system]
    items = roles.items() if isinstance(roles, Mapping) else tuple(roles)
    out: dict[str, Any] = {}
    for item in items:
        try:
            field, value = item
        except (TypeError, ValueError):
            raise SceneError(f"roles: expected ROLE = NAME pairs, got {item!r}") from None
        field = str(field).strip()
        if field not in table:
            if not table:
                raise SceneError(f"roles: a {system} scene has no roles (its matrix names every parameter)")
            close = difflib.get_close_matches(field, list(table), n=1, cutoff=0.6)
            hint = f"; did you mean {close[0]!r}?" if close else ""
            raise SceneError(f"roles: unknown role {field!r} of a {system} scene (roles: {', '.join(table)}){hint}")
        if field in out:
            raise SceneError(f"roles: {field} given twice")
        where = f"roles: {field}"
        if isinstance(value, (list, tuple)):
            if not table[field].per_user:
                raise SceneError(f"{where}: one name (a list gives one name per user, for multi-user scenes)")
            names = tuple(_valid_name(v, where) for v in value)
            if not names:
                raise SceneError(f"{where}: the list of per-user names is empty")
            out[field] = names
        else:
            out[field] = _valid_name(value, where)
    # every name a role gives (the defaults of the roles not named included) serves one role
    owner: dict[str, str] = {}
    fixed = FIXED_NAMES[system]
    for field, role in table.items():
        value = out.get(field, role.default)
        for name in (value if isinstance(value, tuple) else (value,)):
            if name in fixed:
                raise SceneError(f"roles: {field}: {name!r} is {fixed[name]} of a {system} scene")
            if system == "multi-user" and name in _MULTI_USER_GROUPS:
                raise SceneError(f"roles: {field}: {name!r} is a group name of the m-user couplings")
            if name in owner:
                raise SceneError(f"roles: {name!r} names both {table[owner[name]].meaning} and {role.meaning}")
            owner[name] = field
    return tuple(sorted((k, v) for k, v in out.items() if v != table[k].default))


def role_name(system: str, roles: tuple, field: str) -> str | None:
    """The parameter name of role ``field`` (``None``: a multi-user role given per user only).

    >>> role_name("single-user", (("period", "Ts"),), "period"), role_name("single-user", (), "period")
    ('Ts', 'T')
    """
    value = dict(roles).get(field, ROLES[system][field].default)
    return None if isinstance(value, tuple) else value


def member_names(system: str, roles: tuple, field: str, users: int) -> tuple[str, ...]:
    """The per-user names of a multi-user role: the listed names, or ``NAME_1``, ..., ``NAME_m``
    of its group name (``b_1``, ... by default)."""
    value = dict(roles).get(field, ROLES[system][field].default)
    if isinstance(value, tuple):
        return value
    return tuple(f"{value}_{i + 1}" for i in range(users))


def check_members(roles: tuple, users: int, uniform: bool) -> None:
    """A multi-user list of names has one name per user, a uniform scene one name per role, and
    no name (group, member or period) serves two roles."""
    for field, value in roles:
        if not isinstance(value, tuple):
            continue
        if uniform:
            raise SceneError(f"roles: {field}: a uniform scene has one {field.replace('_', ' ')} for all users: "
                             "give one name")
        if len(value) != users:
            raise SceneError(f"roles: {field}: {len(value)} names for {users} users")
    owner: dict[str, str] = {}
    table = ROLES["multi-user"]
    for field, role in table.items():
        names = [role_name("multi-user", roles, field)]
        if role.per_user:
            names += list(member_names("multi-user", roles, field, users))
        for name in names:
            if name is None:
                continue
            if name in owner and owner[name] != field:
                raise SceneError(f"roles: {name!r} names both {table[owner[name]].meaning} and {role.meaning}")
            if name in owner:
                raise SceneError(f"roles: {field}: the per-user names must differ ({name!r} twice)")
            owner[name] = field


def role_of_name(system: str, roles: tuple, name: str, users: int | None = None) -> str | None:
    """The role (field) whose parameter is ``name`` (a multi-user member name included), if any.

    >>> role_of_name("multi-user", (), "b_2", 3), role_of_name("single-user", (("period", "Ts"),), "T")
    ('device_damping', None)
    """
    for field, role in ROLES[system].items():
        if role_name(system, roles, field) == name:
            return field
        if role.per_user and users and name in member_names(system, roles, field, users):
            return field
    return None


@functools.lru_cache(maxsize=512)
def role_names(system: str, roles: tuple, users: int | None = None) -> Mapping[str, str]:
    """Every parameter name the roles give (multi-user members included) -> its role's field
    (read-only; cached, since scenes ask for it for every symbol they build).

    >>> dict(role_names("single-user", (("period", "Ts"),)))
    {'b': 'device_damping', 'Ts': 'period', 'm': 'mass'}
    """
    out: dict[str, str] = {}
    for field, role in ROLES[system].items():
        name = role_name(system, roles, field)
        if name is not None:
            out[name] = field
        if role.per_user and users:
            for member in member_names(system, roles, field, users):
                out[member] = field
    return types.MappingProxyType(out)


@functools.lru_cache(maxsize=512)
def role_words(system: str, roles: tuple, users: int | None = None) -> Mapping[str, str]:
    """Every name a role gives -> :data:`ROLE_ASSUMPTION` (read-only, cached)."""
    return types.MappingProxyType({name: ROLE_ASSUMPTION for name in role_names(system, roles, users)})
