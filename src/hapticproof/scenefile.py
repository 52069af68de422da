r"""Scene files: a :class:`~hapticproof.scene.Scene` as TOML, read with the standard library's
``tomllib`` and written by a small writer of our own.

A scene file holds the fields of :class:`~hapticproof.scene.Scene` at the top level -- the
same names as the command-line options of ``hapticproof derive`` and ``boundary`` -- and the
parameters in a ``[params]`` table (``--param NAME=VALUE``). A paper file's ``[scenes.X]``
tables have exactly the same fields (:func:`scene_from_table`).

.. code-block:: toml

    # a virtual wall with a virtual mass, on a 1 kHz haptic device
    system = "single-user"          # single-user | multi-user | teleoperator | network
    approximation = "forward"       # forward | backward | tustin (the HVE model of X_h)
    environment = "K + B*(z - 1)/(T*z) + M*(z - 1)**2/(T**2*z**2)"
    delay = 0                       # n = t_d/T; "n" keeps it symbolic

    [params]
    K = 2                           # numbers are exact: 0.001 is 1/1000
    B = 0.01
    M = "positive"                  # an assumption: M stays a symbol
    T = 0.001
    b = "9/10"

Numbers are exact (TOML floats are read by their decimal text, never as binary floats);
expressions are read by :func:`hapticproof.expr.read_expression`. A mistake is one line naming
the file, the line and the field (:class:`SceneFileError`).

>>> scene = loads('system = "single-user"\nenvironment = "K + B*(z-1)/(T*z)"\n[params]\nT = 0.001\n')
>>> scene.param_values
{'T': 1/1000}
>>> loads('system = "single-user"\nenviroment = "K"\n', "wall.toml")
Traceback (most recent call last):
...
hapticproof.scenefile.SceneFileError: wall.toml:2: unknown field 'enviroment' (fields: system, approximation, environment, controller, discretize, delay, users, graph, uniform, active, operator, matrix, ports, params)
"""

from __future__ import annotations

import json
import re
import sys
import tomllib
from collections.abc import Mapping
from decimal import Decimal
from pathlib import Path
from typing import Any

import sympy as sp

from hapticproof.errors import HapticproofError, InputFormatError
from hapticproof.expr import write_expression

__all__ = ["FIELDS", "SceneFileError", "loads", "dumps", "read_scene", "write_scene", "scene_from_table",
           "read_matrix", "toml_value", "line_of"]

#: The fields of a scene table, in the order they are written.
FIELDS = ("system", "approximation", "environment", "controller", "discretize", "delay", "users", "graph",
          "uniform", "active", "operator", "matrix", "ports", "params")

_TYPES: dict[str, tuple[type, ...]] = {
    "system": (str,), "approximation": (str,), "environment": (str, int, Decimal), "controller": (str, int, Decimal),
    "discretize": (str,), "delay": (int, str, list), "users": (int,), "graph": (str,), "uniform": (bool,),
    "active": (bool,), "operator": (str, int, Decimal), "matrix": (list, str), "ports": (list, str), "params": (dict,),
}


class SceneFileError(InputFormatError):
    """A scene file (or scene table) that cannot be read: names the file, line and field."""


def line_of(text: str | None, key: str, table: str = "") -> int | None:
    """The line (1-based) of ``key = ...`` in ``[table]`` of a TOML text (``None`` if not found).

    >>> line_of('a = 1\\n[params]\\nK = 2\\n', "K", "params")
    3
    """
    if not text:
        return None
    current = ""
    pattern = re.compile(r"\s*(?:\"" + re.escape(key) + r"\"|'" + re.escape(key) + r"'|" + re.escape(key) + r")\s*=")
    for number, line in enumerate(text.splitlines(), 1):
        header = re.match(r"\s*\[+\s*([^\]]+?)\s*\]+", line)
        if header:
            current = header.group(1).strip()
            continue
        if current == table and pattern.match(line):
            return number
    return None


def _where(source: str, text: str | None, key: str, table: str = "") -> str:
    line = line_of(text, key, table)
    return f"{source}:{line}" if line is not None else source


def read_matrix(path: str | Path) -> tuple[list[list[str]], tuple[int, ...] | None]:
    """Entries (text) and port sizes of a matrix file: rows of comma-separated entries ('#'
    comments) or JSON (``{"matrix": [[...]], "ports": [..]}`` or a list of rows)."""
    path = Path(path)
    try:
        content = path.read_text(encoding="utf-8")
    except OSError as err:
        raise SceneFileError(f"cannot read {path}: {err.strerror}") from None
    ports = None
    if path.suffix.lower() == ".json":
        try:
            data = json.loads(content)
        except json.JSONDecodeError as err:
            raise SceneFileError(f"{path}:{err.lineno}: invalid JSON ({err.msg})") from None
        rows, ports = (data.get("matrix"), data.get("ports")) if isinstance(data, dict) else (data, None)
        if not isinstance(rows, list) or not all(isinstance(r, list) for r in rows):
            raise SceneFileError(f"{path}: expected a list of rows (or {{'matrix': [...]}})")
        table = [[str(e) for e in r] for r in rows]
    else:
        table = []
        for line in content.splitlines():
            line = line.split("#", 1)[0].strip()
            if line:
                table.append([e.strip() for e in line.split(",")])
    if not table:
        raise SceneFileError(f"{path}: no matrix rows")
    return table, (tuple(int(p) for p in ports) if ports else None)


def _plain(value: Any) -> Any:
    """TOML values as the scene expects them (decimals as exact text)."""
    if isinstance(value, Decimal):
        return str(value)
    if isinstance(value, list):
        return [_plain(v) for v in value]
    if isinstance(value, dict):
        return {k: _plain(v) for k, v in value.items()}
    return value


def scene_from_table(table: Mapping[str, Any], where: str = "scene", base: str | Path | None = None,
                     assumptions: Mapping[str, str] | None = None, text: str | None = None, prefix: str = ""):
    """A :class:`~hapticproof.scene.Scene` from a table of fields (a parsed scene file, or a
    paper file's ``[scenes.X]``). ``base`` resolves a relative matrix file; ``assumptions``
    adds parameter assumptions from outside (a paper's ``[symbols]``), the table's own
    ``[params]`` winning; ``text`` and ``prefix`` (the table's TOML path, ``'scenes.wall'``)
    let errors name the line.

    >>> scene_from_table({"system": "teleoperator", "controller": "K_p + K_d*(z - 1)/(T*z)"}).controller
    K_d*(z - 1)/(T*z) + K_p
    """
    from hapticproof.scene import Scene

    if not isinstance(table, Mapping):
        raise SceneFileError(f"{where}: a scene is a table of fields")
    fields: dict[str, Any] = {}
    for key, value in table.items():
        if key not in FIELDS:
            raise SceneFileError(f"{_where(where, text, key, prefix)}: unknown field {key!r} (fields: {', '.join(FIELDS)})")
        if not isinstance(value, _TYPES[key]) or (isinstance(value, bool) and bool not in _TYPES[key]):
            kinds = " or ".join(t.__name__.replace("Decimal", "number").replace("dict", "table").replace("str", "text")
                                .replace("int", "integer").replace("list", "list") for t in _TYPES[key])
            raise SceneFileError(f"{_where(where, text, key, prefix)}: field {key!r} must be {kinds}, got {value!r}")
        fields[key] = _plain(value)
    if "system" not in fields:
        raise SceneFileError(f"{where}: missing field 'system' (single-user, multi-user, teleoperator or network)")
    params = dict(fields.pop("params", {}))
    for name, value in (assumptions or {}).items():
        params.setdefault(name, value)
    for name, value in params.items():
        if isinstance(value, (list, dict)):
            raise SceneFileError(f"{_where(where, text, name, (prefix + '.params').lstrip('.'))}: parameter {name!r} "
                                 "must be a number, an expression or an assumption")
    if isinstance(fields.get("matrix"), str):
        path = Path(fields["matrix"])
        if base is not None and not path.is_absolute():
            path = Path(base) / path
        rows, ports = read_matrix(path)
        fields["matrix"] = rows
        if ports and "ports" not in fields:
            fields["ports"] = list(ports)
    if isinstance(fields.get("ports"), str):
        fields["ports"] = [p for p in fields["ports"].split(",")]
    try:
        return Scene(**fields, params=params)
    except HapticproofError as err:
        message = str(err)
        key = _field_in(message, list(fields) + list(params))
        table_name = (prefix + ".params").lstrip(".") if key in params else prefix
        raise SceneFileError(f"{_where(where, text, key, table_name) if key else where}: {message}") from None


def _field_in(message: str, keys: list[str]) -> str | None:
    for key in sorted(keys, key=len, reverse=True):
        if message.startswith(key) or f" {key}" in message or f"{key}:" in message or f"{key!r}" in message:
            return key
    return None


def loads(text: str, where: str = "scene", base: str | Path | None = None):
    """A scene from the text of a scene file."""
    try:
        table = tomllib.loads(text, parse_float=Decimal)
    except tomllib.TOMLDecodeError as err:
        raise SceneFileError(f"{where}: {err}") from None
    return scene_from_table(table, where=where, base=base, text=text)


def read_scene(path: str | Path):
    """A scene from a scene file (``-``: standard input)."""
    if str(path) == "-":
        return loads(sys.stdin.read(), "<stdin>")
    path = Path(path)
    try:
        text = path.read_text(encoding="utf-8")
    except OSError as err:
        raise SceneFileError(f"cannot read {path}: {err.strerror}") from None
    return loads(text, str(path), base=path.parent)


# ---------------------------------------------------------------------------------------------
# writing
# ---------------------------------------------------------------------------------------------

_BARE = re.compile(r"^[A-Za-z0-9_-]+$")


def toml_value(value: Any) -> str:
    """One TOML value: strings quoted (JSON escapes are TOML escapes), exact numbers as integers
    or quoted exact text (``"1/3"``, ``"0.001"``), lists inline.

    >>> toml_value(sp.Rational(1, 1000)), toml_value(sp.Rational(1, 3)), toml_value([1, "n"]), toml_value(True)
    ('"0.001"', '"1/3"', '[1, "n"]', 'true')
    """
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, int):
        return str(value)
    if isinstance(value, sp.Basic) and value.is_Integer:
        return str(int(value))
    if isinstance(value, sp.Basic) and value.is_Rational:
        return json.dumps(_decimal_text(value))
    if isinstance(value, sp.Basic):
        return json.dumps(write_expression(value))
    if isinstance(value, str):
        return json.dumps(value, ensure_ascii=False)
    if isinstance(value, (list, tuple)):
        return "[" + ", ".join(toml_value(v) for v in value) + "]"
    raise TypeError(f"cannot write {value!r} as TOML")


def _decimal_text(q: sp.Rational) -> str:
    """``p/q`` as a terminating decimal when it is one, else the fraction."""
    p, d = int(q.p), int(q.q)
    twos = fives = 0
    while d % 2 == 0:
        d //= 2
        twos += 1
    while d % 5 == 0:
        d //= 5
        fives += 1
    if d != 1:
        return f"{q.p}/{q.q}"
    digits = max(twos, fives)
    scaled = abs(p) * (10**digits // int(q.q))
    text = str(scaled).rjust(digits + 1, "0")
    text = text[:-digits] + "." + text[-digits:]
    return ("-" if p < 0 else "") + text


def dumps(scene) -> str:
    """The scene file text (fields that differ from their defaults, then ``[params]``).

    >>> from hapticproof.scene import Scene
    >>> print(dumps(Scene("single-user", delay=3, params={"K": 2, "T": "0.001", "M": "positive"})).strip())
    # hapticproof scene
    system = "single-user"
    delay = 3
    <BLANKLINE>
    [params]
    K = 2
    M = "positive"
    T = "0.001"
    """
    from hapticproof.scene import Scene

    default = Scene(scene.system) if scene.system != "network" else None
    lines = ["# hapticproof scene"]
    for name in FIELDS[:-1]:
        value = getattr(scene, name)
        if value is None:
            continue
        if default is not None and name != "system" and value == getattr(default, name):
            continue
        if name == "matrix":
            rows = ",\n".join("  [" + ", ".join(toml_value(e) for e in row) + "]" for row in value)
            lines.append(f"matrix = [\n{rows},\n]")
            continue
        if name == "users" and scene.system == "multi-user" and value == 2:
            continue
        lines.append(f"{name} = {toml_value(value)}")
    if scene.params:
        lines += ["", "[params]"]
        for key, value in scene.params:
            shown = key if _BARE.match(key) else json.dumps(key)
            lines.append(f"{shown} = {toml_value(value)}")
    return "\n".join(lines) + "\n"


def write_scene(scene, path: str | Path) -> Path | None:
    """Write the scene file; ``-`` writes to standard output (returns ``None``)."""
    text = dumps(scene)
    if str(path) == "-":
        sys.stdout.write(text)
        return None
    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    path.write_text(text, encoding="utf-8")
    return path
