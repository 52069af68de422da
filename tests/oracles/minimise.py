"""Grid screening plus local refinement of a function of one real variable.

>>> import math
>>> x, fx = golden(lambda t: (t - 0.3)**2, 0.0, 1.0, 1e-12)
>>> round(x, 9), fx < 1e-20
(0.3, True)
>>> local_minima([3.0, 1.0, 2.0, 0.5, 4.0], keep=5)
[3, 1]
"""

from __future__ import annotations

import math
from typing import Any, Callable, Sequence

import numpy as np

__all__ = ["golden", "local_minima"]

_INVPHI = (math.sqrt(5) - 1) / 2


def golden(f: Callable[[Any], Any], a: Any, b: Any, tol: Any, maxiter: int = 400) -> tuple[Any, Any]:
    """Golden-section search for a minimum of ``f`` on ``[a, b]`` (bracket width down to ``tol``).

    Works with floats or mpmath numbers (``a``, ``b`` decide the arithmetic). Returns the best
    point evaluated and its value (the ends are evaluated too, so a monotone ``f`` gives its
    end point).
    """
    invphi = type(b - a)(_INVPHI) if not isinstance(a, float) else _INVPHI
    fa, fb = f(a), f(b)
    best = (a, fa) if fa <= fb else (b, fb)
    c = b - invphi * (b - a)
    d = a + invphi * (b - a)
    fc, fd = f(c), f(d)
    for _ in range(maxiter):
        if abs(b - a) <= tol:
            break
        if fc <= fd:
            b, d, fd = d, c, fc
            c = b - invphi * (b - a)
            fc = f(c)
        else:
            a, c, fc = c, d, fd
            d = a + invphi * (b - a)
            fd = f(d)
    for x, fx in ((c, fc), (d, fd)):
        if fx < best[1]:
            best = (x, fx)
    return best


def local_minima(values: Sequence[float], keep: int = 6) -> list[int]:
    """Indices of the discrete local minima (ends included), lowest first, at most ``keep``.
    Non-finite values (a pole hit by the grid) are ignored."""
    v = np.asarray(values, dtype=float)
    finite = np.isfinite(v)
    n = len(v)
    out = []
    for i in range(n):
        if not finite[i]:
            continue
        left = v[i - 1] if i > 0 and finite[i - 1] else math.inf
        right = v[i + 1] if i < n - 1 and finite[i + 1] else math.inf
        if v[i] <= left and v[i] <= right:
            out.append(i)
    out.sort(key=lambda i: v[i])
    # one index per plateau
    kept: list[int] = []
    for i in out:
        if all(abs(i - k) > 1 for k in kept):
            kept.append(i)
        if len(kept) >= keep:
            break
    return kept
