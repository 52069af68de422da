"""Matrix files of network scenes: rows of comma-separated entries (``#`` comments) or JSON,
each entry a rational expression in ``s`` (read, never evaluated)."""

from __future__ import annotations

from pathlib import Path
from typing import Any

from hapticproof.core.errors import SceneFileError

__all__ = ["read_matrix"]


def read_matrix(path: str | Path, *, named_in: str | None = None) -> tuple[list[list[str]], tuple[int, ...] | None]:
    """Entries (text) and port sizes of a matrix file: rows of comma-separated entries ('#'
    comments) or JSON (``{"matrix": [[...]], "ports": [..]}`` or a list of rows).

    ``named_in`` says the file was named inside another file (a scene's ``matrix``): it is then
    read only if it is a regular file. Every entry must read as a rational expression in ``s``;
    a mistake names the line and the entry but never shows the file's content.
    """
    from hapticproof.core.expr import ExpressionError, read_expression
    from hapticproof.core.files import read_json, read_text

    path = Path(path)
    shown = str(path)
    content = read_text(path, shown, regular_only=named_in is not None)
    ports: Any = None
    lines: list[int | None] = []
    if path.suffix.lower() == ".json":
        data = read_json(content, shown, parse_float=str)
        rows, ports = (data.get("matrix"), data.get("ports")) if isinstance(data, dict) else (data, None)
        if not isinstance(rows, list) or not rows or not all(isinstance(r, list) for r in rows):
            raise SceneFileError(f"{shown}: expected a list of rows (or {{'matrix': [...]}})")
        for i, row in enumerate(rows):
            for j, entry in enumerate(row):
                if isinstance(entry, bool) or not isinstance(entry, (str, int)):
                    raise SceneFileError(f"{shown}: row {i + 1}, entry {j + 1}: expected an expression as text or "
                                         f"a number, got {type(entry).__name__}")
        table = [[str(e) for e in r] for r in rows]
        lines = [None] * len(table)
    else:
        table = []
        for number, line in enumerate(content.splitlines(), 1):
            line = line.split("#", 1)[0].strip()
            if line:
                table.append([e.strip() for e in line.split(",")])
                lines.append(number)
    if not table:
        raise SceneFileError(f"{shown}: no matrix rows")
    for i, (row, number) in enumerate(zip(table, lines)):
        place = f"{shown}:{number}" if number else f"{shown}: row {i + 1}"
        for j, entry in enumerate(row):
            try:
                read_expression(entry, "s")
            except ExpressionError as err:   # the reason and the place, not the file's text
                raise SceneFileError(f"{place}, entry {j + 1}: {err.reason}"
                                     + (f" at position {err.position}" if err.position is not None else "")) from None
    if ports is not None:
        if not isinstance(ports, list) or not all(isinstance(p, int) and not isinstance(p, bool) for p in ports):
            raise SceneFileError(f"{shown}: 'ports' must be a list of integers (port sizes)")
    return table, (tuple(ports) if ports else None)
