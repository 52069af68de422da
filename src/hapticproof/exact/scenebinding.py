r"""The scene a ``derive`` report names, rebuilt by the checker (part of the checker: imports only
``core`` and the checker's own arithmetic, never the code that derived the report).

A report certifies a decision about the ``G^{-1}(z)`` its definition object carries; it also
*shows* what that ``G^{-1}`` is of: a system, an approximation of ``1/s``, a delay, and the
values of its scene. Editing those fields while keeping the certificates would make a genuine
proof about one scene read as a proof about another. The checker rebuilds ``G^{-1}`` from what
the report shows, from the definitions (HVE paper, Section 3.1.1 and eqs. 21-22, 39, 47):

* the integrator ``X_h/V_h`` from its recurrence: forward ``x(k+1) = x(k) + T v(k)`` gives
  ``T/(z-1)``, backward ``x(k+1) = x(k) + T v(k+1)`` gives ``Tz/(z-1)``, Tustin (their mean)
  gives ``T(z+1)/(2(z-1))``;
* ``G^{-1}_ij(z) = (b_i - z_ai) delta_ij + z^{-n_i} H_ij(z) X_h/V_h`` with ``n_i`` user ``i``'s
  delay in samples (one user: the single-user wall, ``i = j = 1``);

and holds it against the definition's transfer function exactly (as rational functions).

>>> scene = {"period": "1/1000", "damping": ["1/50"], "shortage": ["0"], "environment": [[{"num": ["20"], "den": ["1"]}]]}
>>> report = {"system": "single-user", "approximation": "forward", "delay": "0", "scene": scene, "G_inverse": "",
...           "definition": {"transfer": {"variable": "z", "num": ["0", "1/50"], "den": ["-1", "1"]}}}
>>> scene_binding(report)
[]
>>> scene_binding({**report, "system": "multi-user"})
['the report is not a multi-user report (it shows no users or delays): its G^-1 is of another system']
>>> scene_binding({**report, "approximation": "tustin"})
['the G^-1 decided is not the one of the scene shown (system single-user, tustin approximation, delay 0): entry (1, 1) differs']
"""

from __future__ import annotations

from collections.abc import Mapping
from fractions import Fraction
from typing import Any

import flint

from hapticproof.core.limits import current
from hapticproof.exact.checkarith import as_fmpq, exact_q, json_poly

__all__ = ["integrator", "scene_binding"]


def integrator(approximation: str, T: Fraction) -> tuple[flint.fmpq_poly, flint.fmpq_poly]:
    """``X_h/V_h`` of an approximation of ``1/s`` as ``(num, den)`` in ``z``, from its recurrence.

    >>> integrator("tustin", Fraction(2))
    (x + 1, x + (-1))
    """
    t = as_fmpq(T)
    num = {"forward": [t], "backward": [0, t], "tustin": [t / 2, t / 2]}.get(approximation)
    if num is None:
        raise ValueError(f"the approximation {approximation!r} is none of forward, backward, tustin")
    return flint.fmpq_poly(num), flint.fmpq_poly([-1, 1])


def _delays(report: Mapping[str, Any], users: int) -> list[int]:
    """The delays in samples the report shows: ``delays`` (one per user, or one for all) or ``delay``."""
    shown = report.get("delay" if users == 1 and "users" not in report else "delays")   # the field the report shows
    values = shown if isinstance(shown, list) else [shown]
    if len(values) == 1:
        values = values * users
    if len(values) != users:
        raise ValueError(f"{len(values)} delays shown for {users} users")
    out = []
    for value in values:
        n = exact_q(value if not isinstance(value, bool) else "x")
        if n.denominator != 1 or n < 0 or n > current().delay:
            raise ValueError(f"the delay {value!r} is not a number of samples from 0 to {current().delay} (the delay limit)")
        out.append(int(n))
    return out


def _entries(transfer: Mapping[str, Any]) -> list[list[Mapping[str, Any]]]:
    if "entries" in transfer:
        rows = transfer["entries"]
        if not isinstance(rows, list) or not all(isinstance(r, list) and len(r) == len(rows) for r in rows):
            raise ValueError("the transfer matrix is not square")
        return rows
    return [[transfer]]


def _rational(entry: Any) -> tuple[flint.fmpq_poly, flint.fmpq_poly]:
    if not isinstance(entry, Mapping):
        raise TypeError("an entry is not a transfer function")
    num, den = json_poly(entry["num"]), json_poly(entry["den"])
    if den.is_zero():
        raise ValueError("a transfer function has a zero denominator")
    if max(num.degree(), den.degree()) > current().delay + current().degree:
        # (a delay of n samples makes G^-1 of degree n + deg H + 1: products of such polynomials are cheap)
        raise ValueError("a transfer function's degree is above the delay and degree limits")
    return num, den


def _graph(edges: list[list[int]], m: int) -> str:
    """The coupling graph's kind by its edges (1-based pairs): as ``derive`` names it."""
    shown = {tuple(e) for e in edges}
    path = {(i, i + 1) for i in range(1, m)}
    if shown == {(i, j) for i in range(1, m + 1) for j in range(i + 1, m + 1)}:
        return "complete"
    if shown == path:
        return "path"
    if m >= 3 and shown == path | {(1, m)}:
        return "ring"
    if shown == {(1, i) for i in range(2, m + 1)}:
        return "star"
    return "other"


def scene_binding(report: Mapping[str, Any]) -> list[str]:
    """Refusals: the ``G^{-1}`` a derive report decides is not rebuilt from the scene it shows
    (its system, approximation, delays and values), or the report shows no values to rebuild it
    from. A report with no numeric definition object (a symbolic scene) is left to the other
    bindings: its decisions are never accepted as re-verified."""
    definition = report.get("definition")
    if "G_inverse" not in report or not isinstance(definition, Mapping) or \
            not isinstance(definition.get("transfer"), Mapping):
        return []
    system = report.get("system", "multi-user" if "users" in report else None)
    users = report.get("users", 1) if system == "multi-user" else 1
    if system not in ("single-user", "multi-user") or isinstance(users, bool) or not isinstance(users, int):
        return [f"the system shown ({str(system)[:40]!r}) is not one whose G^-1 the checker rebuilds "
                "(single-user, multi-user)"]
    shape = ("delay",) if system == "single-user" else ("users", "delays")
    if any(key not in report for key in shape):
        return [f"the report is not a {system} report (it shows no {' or '.join(shape)}): its G^-1 is of another system"]
    scene = report.get("scene")
    if not isinstance(scene, Mapping):
        return ["the report shows no scene values (period, damping, shortage, environment): nothing ties its G^-1 to "
                "the scene it names "
                "(a report of an older version, or one whose scene was removed: re-derive it)"]
    approximation = report.get("approximation")
    delays = _delays(report, users)
    T = exact_q(scene["period"])
    if T <= 0:
        return [f"the sampling period shown is {T}, not positive"]
    b, z_a, H = scene["damping"], scene["shortage"], _entries({"entries": scene["environment"]})
    decided = _entries(definition["transfer"])
    if not (len(b) == len(z_a) == len(H) == len(decided) == users):
        return [f"the scene shown has {len(H)} users' values, its G^-1 {len(decided)} rows, the report {users} users"]
    coupled = sorted([i + 1, j + 1] for i in range(users) for j in range(i + 1, users)
                     if not (json_poly(H[i][j]["num"]).is_zero() and json_poly(H[j][i]["num"]).is_zero()))
    if system == "multi-user" and "graph" in report and report["graph"] != _graph(coupled, users):
        return [f"the graph shown ({str(report['graph'])[:20]}) is not that of the scene's couplings ({_graph(coupled, users)})"]
    if system == "multi-user" and "edges" in report:
        edges = report["edges"]
        if not isinstance(edges, list) or sorted(list(e) for e in edges if isinstance(e, (list, tuple))) != coupled \
                or len(edges) != len(coupled):
            return [f"the edges shown are not the couplings of the scene's H(z) ({coupled})"]
    i_num, i_den = integrator(str(approximation), T)
    for i in range(users):
        shift = flint.fmpq_poly([0] * delays[i] + [1])
        for j in range(users):
            h_num, h_den = _rational(H[i][j])
            num, den = h_num * i_num, h_den * i_den * shift
            if i == j:
                num += as_fmpq(exact_q(b[i]) - exact_q(z_a[i])) * den
            g_num, g_den = _rational(decided[i][j])
            if num * g_den != g_num * den:
                where = f"delay {delays[0]}" if users == 1 else f"delays {delays}"
                return [f"the G^-1 decided is not the one of the scene shown (system {system}, {approximation} "
                        f"approximation, {where}): entry ({i + 1}, {j + 1}) differs"]
    return []
