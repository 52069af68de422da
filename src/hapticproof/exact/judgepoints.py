"""Points the definition judge chooses itself (part of the checker: imports nothing but the
standard library): a judge object is tested at points derived from a hash of the object, never
only at the points it carries, so a false identity or an insufficient condition that its author
made true at the author's points is still refused."""

from __future__ import annotations

import hashlib
import json
from collections.abc import Iterable, Iterator, Mapping
from fractions import Fraction
from typing import Any

__all__ = ["MAX_OWN_POINTS", "names_of", "own_points", "tree_size"]


def names_of(tree: Any) -> set[str]:
    """The symbol names of an expression tree.

    >>> sorted(names_of(["+", ["s", "b"], ["*", ["q", "2"], ["s", "K"]]]))
    ['K', 'b']
    """
    if not isinstance(tree, list) or not tree:
        return set()
    if tree[0] == "s" and len(tree) == 2 and isinstance(tree[1], str):
        return {tree[1]}
    return set().union(*(names_of(a) for a in tree[1:])) if len(tree) > 1 else set()


def tree_size(tree: Any) -> int:
    """The number of nodes of an expression tree (names and numbers included).

    >>> tree_size(["+", ["s", "b"], ["q", "2"]])
    5
    """
    return 1 + sum(tree_size(a) for a in tree[1:]) if isinstance(tree, list) and tree else 1


#: The most points of its own choosing the judge tests an identity at.
MAX_OWN_POINTS = 48


def own_points(obj: Mapping[str, Any], names: Iterable[str], count: int) -> Iterator[dict[str, Any]]:
    """Points the judge chooses itself, deterministic from a hash of the judge object (never
    from the points it carries): positive rational values ``p/q`` (``p < 1000``, ``q < 100``)
    for ``names``, distinct rational ``t`` of the circle and, where the object's points carry a
    delay, an integer ``n`` from 1 to 6. A false identity that the author made true at the
    object's own points is not true at these (the author does not choose them).

    >>> pts = list(own_points({"display": ["s", "b"]}, ["b"], 3))
    >>> len(pts), pts == list(own_points({"display": ["s", "b"]}, ["b"], 3)), len({p["t"] for p in pts})
    (3, True, 3)
    """
    seed = json.dumps({k: obj.get(k) for k in ("judge", "display", "inverse", "period", "frequency")},
                      sort_keys=True, default=str).encode()
    points = obj.get("points") if isinstance(obj.get("points"), list) else []
    delay = any(isinstance(p, Mapping) and "n" in p for p in points)
    L = points[0].get("L", 1) if points and isinstance(points[0], Mapping) else 1
    names = sorted(set(names) - {"n", "z", obj.get("frequency", "omega")})
    used: set[Fraction] = set()
    k = 0
    while count > 0:
        digest = hashlib.sha256(seed + str(k).encode()).digest()
        k += 1
        numbers = [int.from_bytes(digest[2 * i:2 * i + 2], "big") for i in range(16)]
        values = {name: str(Fraction(1 + numbers[(2 * i) % 16] % 999, 1 + numbers[(2 * i + 1) % 16] % 99))
                  for i, name in enumerate(names)}
        if len(names) > 8:                    # more names than one digest holds: a second stream
            extra = hashlib.sha256(digest).digest() * (len(names) // 8 + 1)
            values = {name: str(Fraction(1 + extra[2 * i] * 7 % 999, 1 + extra[2 * i + 1] % 99))
                      for i, name in enumerate(names)}
        t = Fraction(1 + numbers[14] % 997, 1 + numbers[15] % 331)
        if t in used:
            continue
        used.add(t)
        point: dict[str, Any] = {"values": values, "t": str(t), "L": L}
        if delay:
            point["n"] = 1 + numbers[13] % 6
        count -= 1
        yield point
