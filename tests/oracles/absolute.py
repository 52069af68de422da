r"""Absolute stability of an n-port (3-DOF bilateral paper, Definition 6): decided when a
structural route applies, else searched for a counterexample.

* an entry with a pole in ``Re s > 0``: ``no`` (unstable with open ports);
* a reciprocal ``Z = Z^T``: absolutely stable iff positive real (Youla 1959, Lemma 7; a
  positive-real n-port with passive, even full-block, terminations cannot have a zero of
  ``det(Z + T)`` in ``Re s > 0``, and a non-positive-real reciprocal one is destabilised by
  scalar terminations, which are block terminations too) -- :func:`positive_real_matrix`;
* ``Z = D S D^-1`` with ``S`` symmetric and ``D`` diagonal with rational entries, constant up to
  sign on each port block: every block-compatible minor of ``Z`` and ``S`` agree, so
  ``det(Z + T) = det(S + D^-1 T D)`` and ``D^-1 T D`` is a passive block termination iff ``T`` is
  (Youla 1960, Lemma 8): decided as ``S``. ``D`` is found from the exact ratios
  ``z_ij/z_ji = d_i^2/d_j^2`` (positive constants, consistent around cycles, rational squares);
* a 2-port with scalar ports: Llewellyn's criterion (:func:`llewellyn`), necessary and sufficient;
* otherwise (or to confirm): :func:`find_destabilizing_termination` -- ``no`` with exact
  terminations, or ``uncertain``.

>>> import sympy as sp
>>> s = S
>>> absolute_stability(sp.Matrix([[2, -1, 0, 0], [-1, 2, 0, 0], [0, 0, 2, 0], [0, 0, 0, 2]]), ports=(2, 2)).verdict
'yes'
"""

from __future__ import annotations

import math
from fractions import Fraction
from typing import Any, Sequence

import sympy as sp

from .continuous import S, RationalMatrix, llewellyn, positive_real_matrix
from .result import NO, UNCERTAIN, OracleResult
from .search import find_destabilizing_termination, port_blocks

__all__ = ["absolute_stability", "diagonal_symmetrization"]


def _rational_sqrt(q: Fraction) -> Fraction | None:
    if q <= 0:
        return None
    a, b = math.isqrt(q.numerator), math.isqrt(q.denominator)
    if a * a == q.numerator and b * b == q.denominator:
        return Fraction(a, b)
    return None


def diagonal_symmetrization(Z: sp.Matrix, ports: Sequence[int] | None = None,
                            s: sp.Symbol = S) -> tuple[list[Fraction], sp.Matrix] | None:
    """``(d, S)`` with ``Z = D S D^-1``, ``S`` symmetric, ``d`` rational and equal in magnitude on
    each port block; None if there is none."""
    n = Z.rows
    blocks = port_blocks(n, ports)
    ratio: dict[tuple[int, int], Fraction] = {}
    for i in range(n):
        for j in range(i + 1, n):
            a, b = sp.cancel(Z[i, j]), sp.cancel(Z[j, i])
            if a == 0 and b == 0:
                continue
            if a == 0 or b == 0:
                return None
            r = sp.cancel(a / b)
            if r.free_symbols or not r.is_Rational or r <= 0:
                return None
            ratio[(i, j)] = Fraction(int(r.p), int(r.q))
    # d_i^2 / d_j^2 = ratio(i, j): propagate from node 0 of each connected component
    sq: dict[int, Fraction] = {}
    for start in range(n):
        if start in sq:
            continue
        sq[start] = Fraction(1)
        stack = [start]
        while stack:
            i = stack.pop()
            for (a, b), r in ratio.items():
                if i not in (a, b):
                    continue
                other, value = (b, sq[a] / r) if i == a else (a, sq[b] * r)
                if other in sq:
                    if sq[other] != value:
                        return None
                else:
                    sq[other] = value
                    stack.append(other)
    for blk in blocks:
        if len({sq[i] for i in blk}) > 1:
            return None
    d = []
    for i in range(n):
        root = _rational_sqrt(sq[i])
        if root is None:
            return None
        d.append(root)
    Sm = sp.Matrix(n, n, lambda i, j: sp.cancel(Z[i, j] * sp.Rational(d[j].numerator, d[j].denominator)
                                                / sp.Rational(d[i].numerator, d[i].denominator)))
    if any(sp.cancel(Sm[i, j] - Sm[j, i]) != 0 for i in range(n) for j in range(i + 1, n)):
        return None
    return d, Sm


def absolute_stability(Z: Any, ports: Sequence[int] | None = None, s: sp.Symbol = S, *,
                       search: bool = True, seed: int = 0) -> OracleResult:
    """See the module docstring. ``details['route']`` names the route taken."""
    Zs = sp.Matrix(Z)
    if s != S:
        Zs = Zs.subs(s, S)
    Zm = RationalMatrix(Zs, S)
    n = Zm.n
    poles = [(ij, r) for ij, r, _ in Zm.poles() if r.real > 1e-40 * max(1, abs(r))]
    if poles:
        ij, r = poles[0]
        return OracleResult(NO, f"entry {ij} has a pole at s ~ {complex(r):.6g} in Re s > 0: unstable with open ports",
                            where={"pole": complex(r)}, details={"route": "open-circuit"})

    def route(result: OracleResult, name: str) -> OracleResult:
        result.details = {**result.details, "route": name}
        if result.verdict == UNCERTAIN and search and name != "search":
            found = find_destabilizing_termination(Zs, ports, seed=seed)
            if found.verdict == NO:
                found.details = {**found.details, "route": f"{name} + search"}
                return found
        return result

    if all(sp.cancel(Zs[i, j] - Zs[j, i]) == 0 for i in range(n) for j in range(i + 1, n)):
        return route(positive_real_matrix(Zm), "reciprocal: positive realness (Youla)")
    sym = diagonal_symmetrization(Zs, ports)
    if sym is not None:
        d, Sm = sym
        out = route(positive_real_matrix(Sm), "Z = D S D^-1: positive realness of S (Youla)")
        out.details["d"] = [str(v) for v in d]
        return out
    if n == 2 and (ports is None or tuple(ports) == (1, 1)):
        return route(llewellyn(Zs), "Llewellyn")
    if not search:
        return OracleResult(UNCERTAIN, "no structural route applies and the search is off", details={"route": "none"})
    found = find_destabilizing_termination(Zs, ports, seed=seed)
    found.details = {**found.details, "route": "search"}
    return found
