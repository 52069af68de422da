r"""TOML text as the readers of scene and paper files need it: parsed with its nesting bounded
first (:func:`read_toml`, numbers as exact decimals, a syntax error in one line), and where
each key, header and entry is (:class:`TomlLines`, indexed once so that naming the line of a
mistake stays linear in the file's size however many keys it has).
"""

from __future__ import annotations

import functools
import re
import tomllib
from decimal import Decimal
from typing import Any

from hapticproof.core.errors import InputFormatError

__all__ = ["TomlLines", "toml_lines", "line_of", "read_toml"]


class TomlLines:
    r"""Where things are in a TOML text, indexed once (loading stays linear in the file's size):
    the first line of each ``key = ...`` per table, every line of each key, the headers
    ``[table]`` and the entries ``[[name]]``.

    >>> index = TomlLines('a = 1\n[params]\nK = 2\n[[equations]]\nid = "1"\n[[equations]]\nid = "2"\n')
    >>> index.line("K", "params"), index.header("params"), index.entries("equations")
    (3, 2, [(4, 5), (6, 7)])
    >>> index.line_between("id", 6, 7)
    7
    """

    _KEY = re.compile(r"""\s*(?:"([^"\\]*)"|'([^']*)'|([A-Za-z0-9_-]+))\s*=""")
    _HEADER = re.compile(r"\s*(\[+)\s*([^\]]+?)\s*\]+")

    def __init__(self, text: str):
        self.count = 0
        self.first: dict[tuple[str, str], int] = {}
        self.lines: dict[str, list[int]] = {}
        self.headers: dict[str, int] = {}
        self.arrays: dict[str, list[int]] = {}
        self.header_lines: list[int] = []
        current = ""
        for number, line in enumerate(text.splitlines(), 1):
            self.count = number
            header = self._HEADER.match(line)
            if header:
                current = header.group(2).strip()
                self.header_lines.append(number)
                if len(header.group(1)) == 1:
                    self.headers.setdefault(current, number)
                else:
                    self.arrays.setdefault(current, []).append(number)
                continue
            key = self._KEY.match(line)
            if key:
                name = next(g for g in key.groups() if g is not None)
                self.first.setdefault((current, name), number)
                self.lines.setdefault(name, []).append(number)

    def line(self, key: str, table: str = "") -> int | None:
        """The first line of ``key = ...`` in ``[table]`` (``None``: not found)."""
        return self.first.get((table, key))

    def header(self, table: str) -> int | None:
        """The line of the header ``[table]``."""
        return self.headers.get(table)

    def entries(self, name: str) -> list[tuple[int, int]]:
        """First and last line of each ``[[name]]`` entry."""
        import bisect

        out = []
        for start in self.arrays.get(name, []):
            k = bisect.bisect_right(self.header_lines, start)
            out.append((start, self.header_lines[k] - 1 if k < len(self.header_lines) else self.count))
        return out

    def line_between(self, key: str, first: int, last: int) -> int | None:
        """The first line of ``key = ...`` from line ``first`` to ``last``."""
        import bisect

        lines = self.lines.get(key, [])
        k = bisect.bisect_left(lines, first)
        return lines[k] if k < len(lines) and lines[k] <= last else None


@functools.lru_cache(maxsize=8)
def toml_lines(text: str) -> TomlLines:
    """The :class:`TomlLines` of ``text`` (built once per text)."""
    return TomlLines(text)


def line_of(text: str | None, key: str, table: str = "") -> int | None:
    """The line (1-based) of ``key = ...`` in ``[table]`` of a TOML text (``None`` if not found).

    >>> line_of('a = 1\\n[params]\\nK = 2\\n', "K", "params")
    3
    """
    if not text:
        return None
    return toml_lines(text).line(key, table)


def read_toml(text: str, where: str, error: type[Exception] | None = None) -> dict[str, Any]:
    r"""TOML text as tables (numbers as exact decimals), its nesting within
    :attr:`~hapticproof.core.limits.Limits.depth` before the (recursive) parser sees it; a
    syntax error is one ``error`` line (default :class:`~hapticproof.core.errors.InputFormatError`) naming the line.

    >>> read_toml("a = 0.1", "s.toml")
    {'a': Decimal('0.1')}
    >>> read_toml("a = [1,\nb = 2\n", "s.toml")
    Traceback (most recent call last):
    ...
    hapticproof.core.errors.InputFormatError: s.toml:2: TOML syntax: Invalid value
    """
    from hapticproof.core.files import toml_depth
    from hapticproof.core.limits import check

    error = error or InputFormatError
    if text.startswith("\N{BYTE ORDER MARK}"):
        text = text[1:]
    check("depth", toml_depth(text), where)
    try:
        return tomllib.loads(text, parse_float=Decimal)
    except tomllib.TOMLDecodeError as err:
        message = str(err)
        match = re.search(r"\(at line (\d+), column \d+\)", message)
        line = match.group(1) if match else str(max(1, text.count("\n") + (not text.endswith("\n"))))
        reason = re.sub(r"\s*\(at (?:line \d+, column \d+|end of document)\)", "", message)
        raise error(f"{where}:{line}: TOML syntax: {reason}") from None
    except RecursionError:
        raise error(f"{where}: nested too deeply") from None
