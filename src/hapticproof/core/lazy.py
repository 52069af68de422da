"""Lazy, cached, timed computation stages for frozen scenes.

A scene is a frozen, hashable value object; the work done for it is a set of *stages*
(G^-1, poles, residues, Hermitian part, worst case, ...). A stage runs only when something asks
for it, runs at most once per scene (equal scenes share one cache), and records its wall time,
so ``profile(scene)`` shows what a request cost and what it skipped (DESIGN.md: *Scenes are
frozen, hashable and lazy*).

>>> from dataclasses import dataclass
>>> @dataclass(frozen=True, slots=True, weakref_slot=True)
... class Square:
...     side: int
>>> @stage("area")
... def area(sq):
...     return sq.side ** 2
>>> sq = Square(3)
>>> area(sq), area(Square(3)), list(profile(sq))
(9, 9, ['area'])
"""

from __future__ import annotations

import functools
import time
from collections import OrderedDict
from collections.abc import Callable
from dataclasses import dataclass
from typing import Any, TypeVar

__all__ = ["stage", "profile", "computed_stages", "clear", "force"]

F = TypeVar("F", bound=Callable[..., Any])


@dataclass(frozen=True, slots=True)
class _Record:
    value: Any
    seconds: float


class _SceneCache:
    """Per-scene stage records, least recently used scenes evicted beyond ``capacity``.

    Strong references on purpose: equal scenes built independently (e.g. by different audit
    checks) then share their stages even when the first instance is gone.
    """

    def __init__(self, capacity: int = 512):
        self.capacity = capacity
        self._data: OrderedDict[Any, dict[tuple, _Record]] = OrderedDict()

    def get(self, scene: Any, default: Any = None) -> Any:
        store = self._data.get(scene)
        if store is None:
            return default
        self._data.move_to_end(scene)
        return store

    def __setitem__(self, scene: Any, store: dict[tuple, _Record]) -> None:
        self._data[scene] = store
        self._data.move_to_end(scene)
        while len(self._data) > self.capacity:
            self._data.popitem(last=False)

    def pop(self, scene: Any, default: Any = None) -> Any:
        return self._data.pop(scene, default)


_CACHE = _SceneCache()


def stage(name: str) -> Callable[[F], F]:
    """Decorate ``func(scene, *args)`` as the cached, timed stage ``name``.

    Extra positional arguments must be hashable; they are part of the cache key.
    """

    def decorate(func: F) -> F:
        @functools.wraps(func)
        def wrapper(scene: Any, *args: Any) -> Any:
            store = _CACHE.get(scene)
            if store is None:
                store = {}
                _CACHE[scene] = store
            key = (name, args)
            record = store.get(key)
            if record is None:
                start = time.perf_counter()
                value = func(scene, *args)
                record = _Record(value, time.perf_counter() - start)
                store[key] = record
            return record.value

        wrapper.stage_name = name  # type: ignore[attr-defined]
        return wrapper  # type: ignore[return-value]

    return decorate


def profile(scene: Any) -> dict[str, float]:
    """Wall time in seconds of each stage computed so far for ``scene`` (inclusive of the
    stages it called), in the order they finished."""
    store = _CACHE.get(scene, {})
    out: dict[str, float] = {}
    for (name, args), record in store.items():
        label = name if not args else f"{name}{args}"
        out[label] = record.seconds
    return out


def computed_stages(scene: Any) -> set[str]:
    """Names of the stages already computed for ``scene``."""
    return {name for name, _ in _CACHE.get(scene, {})}


def clear(scene: Any) -> None:
    """Forget everything computed for ``scene`` (for benchmarks: cold runs)."""
    _CACHE.pop(scene, None)


def force(scene: Any, stages: list[Callable[[Any], Any]]) -> None:
    """Compute the given argument-free stage functions (the 'full pipeline' of a benchmark).

    Stage *functions* rather than names: different scene types may use the same stage name.
    """
    for func in stages:
        func(scene)
