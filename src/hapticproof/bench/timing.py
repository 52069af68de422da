"""Timing and machine facts shared by the benchmark studies: medians of repeated runs, the
machine a run was made on, JSON-safe values."""

from __future__ import annotations

import os
import statistics
import time
from collections.abc import Callable
from typing import Any

import sympy as sp



def median_time(func: Callable[[], Any], repeat: int) -> tuple[Any, float]:
    """``(result, median seconds)`` of ``repeat`` calls of ``func`` (the studies time with it too)."""
    times, result = [], None
    for _ in range(max(1, repeat)):
        start = time.perf_counter()
        result = func()
        times.append(time.perf_counter() - start)
    return result, statistics.median(times)


def machine_info() -> dict[str, Any]:
    import platform

    return {"cpus": os.cpu_count(), "python": platform.python_version(), "platform": platform.platform(),
            "processor": platform.processor() or platform.machine()}


def jsonable(value: Any) -> Any:
    from hapticproof.core.evidence import to_jsonable

    if isinstance(value, float):
        return value
    if isinstance(value, dict):
        return {k: jsonable(v) for k, v in value.items()}
    if isinstance(value, (list, tuple)):
        return [jsonable(v) for v in value]
    if isinstance(value, sp.Basic):
        return to_jsonable(value)
    return value
