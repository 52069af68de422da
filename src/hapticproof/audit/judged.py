r"""What a finding hands the definition-level judge: the printed display as given, the scene's
original ``G^{-1}(z)`` at each point, and the points themselves with every linked quantity.

The judge (:mod:`hapticproof.exact.judge`, beside the independent checker) re-evaluates a
finding from this data alone: the display tree with its own ball arithmetic, ``Re G^{-1}`` from
the transfer function's coefficients at a point ``z = e^{j theta}`` of the circle. A point is a
rational ``t`` with ``u = (1 + j t)/(1 - j t) = e^{j theta/L}``: ``theta = 2 L atan(t)``,
``z = u^L`` (a Gaussian rational), ``c = Re z`` (rational), ``omega = theta/T``, ``t_d = n T``
-- one angle, every quantity derived from it, none set on its own.

>>> import sympy as sp
>>> point = circle_point(sp.Rational(1, 2), 1)
>>> point["c"], point["z"]
(3/5, [3/5, 4/5])
"""

from __future__ import annotations

from collections.abc import Mapping
from typing import Any

import sympy as sp

from hapticproof.core.exprtree import to_tree
from hapticproof.core.naming import angle_marker, marker

__all__ = ["circle_point", "witness_of", "transfer_at", "display_tree", "circle_judge", "condition_judge", "ANGLES"]

#: The rational ``t`` of the points tried (``theta = 2 L atan(t)``): spread over the circle.
ANGLES = tuple(sp.Rational(p, q) for p, q in ((1, 2), (1, 3), (2, 1), (1, 5), (3, 1), (2, 3), (1, 7), (3, 2), (5, 2),
                                                (1, 4), (4, 3), (7, 2)))


def circle_point(t: Any, L: int, n: int | None = None) -> dict[str, Any]:
    """The linked quantities of the point ``u = (1 + j t)/(1 - j t)``: ``theta = 2 L atan(t)``,
    ``z = u^L`` (real and imaginary parts, exact), ``c = Re z`` and, for a delay ``n``,
    ``z^n``."""
    t = sp.Rational(t)
    u = (1 + sp.I * t) / (1 - sp.I * t)
    z = sp.expand(u ** int(L))
    re, im = sp.re(z), sp.im(z)
    out: dict[str, Any] = {"t": t, "L": int(L), "theta": 2 * int(L) * sp.atan(t), "c": re, "z": [re, im]}
    if n is not None:
        zn = sp.expand(z ** int(n))
        out["n"] = int(n)
        out["z^n"] = [sp.re(zn), sp.im(zn)]
    return out


def witness_of(values: Mapping[Any, Any], point: Mapping[str, Any], T: Any) -> dict[str, Any]:
    """The displayed witness: the parameters, the delay ``n`` (if any), ``omega_T = theta``,
    ``omega = theta/T``, ``c`` and ``z`` -- all from the one point."""
    out = {str(getattr(k, "name", k)): v for k, v in values.items()}
    if "n" in point:
        out["n"] = point["n"]
    # the circle's keys marked: the paper's naming writes them (gamma when the paper has a c)
    out[angle_marker()] = point["theta"]
    T_value = sp.sympify(T).xreplace({k: v for k, v in values.items() if isinstance(k, sp.Symbol)})
    if T_value.is_Rational:
        out[marker("omega")] = point["theta"] / T_value
    out[marker("cos")] = point["c"]
    out["z"] = list(point["z"])
    return out


def transfer_at(model: Any) -> dict[str, Any] | None:
    """The original ``G^{-1}(z)`` of a numeric single-user model as transfer-function JSON
    (``None`` for any other model)."""
    from hapticproof.exact.kernel import transfer_json

    if not getattr(model, "is_numeric", False):
        return None
    from hapticproof.analysis.positivereal import transfer_polynomials

    P, Q = transfer_polynomials(model)
    return transfer_json(P, Q)


def display_tree(expr: Any) -> list | None:
    """The display as a tree (:func:`hapticproof.core.exprtree.to_tree`), ``None`` when some part
    of it has no tree (the judge then says it cannot re-evaluate the finding)."""
    try:
        return to_tree(expr)
    except (ValueError, TypeError):
        return None


def scene_inverse(state: Any) -> list | None:
    """The scene's ``G^{-1}(z)`` with its parameters symbolic, as a tree in the paper's names
    (``None`` for a scene that is not single-user or a model without a tree): the object a
    judge evaluates at points of its own choosing."""
    if getattr(state, "scene", None) is None or state.scene.system != "single-user":
        return None
    try:
        from hapticproof.systems.models import inverse_transfer

        chart = getattr(state, "chart", None)
        back = chart.back if chart is not None else (lambda expr: expr)
        return display_tree(back(inverse_transfer(state.model)))
    except Exception:  # noqa: BLE001 - a model the judge cannot read is not judged, never a failure
        return None


def circle_judge(claim: str, display: Any, frequency: str, period: Any, points: list[dict[str, Any]],
                 inverse: list | None = None) -> dict[str, Any] | None:
    """The judge's data of a claim about ``Re G^{-1}(e^{j omega T})``: ``claim`` is ``"equal"``
    (the display is ``Re G^{-1}`` at every point) or ``"differ"`` (at the first point);
    ``period`` is the sampling period ``T`` (a symbol of the values, or the scene's number);
    ``points`` hold ``values`` (parameters), the circle point (:func:`circle_point`) and the
    ``transfer`` at those values. The judge also holds the finding's displayed witness against
    the first point (a ``differ`` claim). ``inverse``, the scene's ``G^{-1}(z)`` as a tree
    (:func:`scene_inverse`), lets the checker test an ``equal`` claim at points of its own
    choosing (without it, the claim is not judged)."""
    tree, period_tree = display_tree(display), display_tree(period)
    if tree is None or period_tree is None or not points or any(p.get("transfer") is None for p in points):
        return None
    rows = []
    for p in points:
        rows.append({"values": {str(getattr(k, "name", k)): str(v) for k, v in p["values"].items()},
                     "t": str(p["t"]), "L": p["L"], **({"n": p["n"]} if "n" in p else {}), "transfer": p["transfer"]})
    shown_period = period.name if isinstance(period, sp.Symbol) else "T"      # the paper's period in the object's name
    out = {"judge": "circle-identity", "claim": claim, "object": f"Re G^-1(e^{{j {frequency} {shown_period}}})", "display": tree,
           "frequency": frequency, "period": period_tree, "points": rows}
    if inverse is not None:
        out.update(inverse=inverse, variable="z")
    return out


#: The judged claim of a condition finding, by the exact decision at its witness.
_CONDITION_CLAIMS = {"disproved": "holds-not-passive", "proved": "fails-passive"}


def condition_judge(state: Any, finding: Any) -> dict[str, Any] | None:
    """The judge's data of a condition claim on a single-user scene: the printed condition as
    given, the scene's ``G^{-1}(z)`` with its parameters symbolic (a tree), and the witness --
    where the printed condition holds and the scene is not positive real (with the point
    ``|z0| >= 1`` where ``Re G^{-1}(z0) < 0``), or where it fails and the scene is positive
    real; for a confirmed condition, points where it holds (the scene must be positive real
    there). ``None`` when the finding has none of these."""
    from hapticproof.core.evidence import Verdict

    if state.scene is None or state.scene.system != "single-user":
        return None
    try:
        from hapticproof.systems.models import inverse_transfer

        # a restricted scene (audit.regions) is judged in the paper's names, as its witness is told
        chart = getattr(state, "chart", None)
        back = chart.back if chart is not None else (lambda expr: expr)
        inverse = display_tree(back(inverse_transfer(state.model)))
        relations = [r.as_sympy() for r in state.statement.relations()]
        display = display_tree(back(sp.And(*[state.prepare(r) for r in relations]))) if relations else None
    except Exception:  # noqa: BLE001 - a display the judge cannot read is not judged, never a failure
        return None
    if inverse is None or display is None:
        return None
    base = {"judge": "condition", "display": display, "inverse": inverse, "variable": "z"}
    evidence = finding.evidence
    witness = evidence.witness
    recheck = evidence.facts.get("recheck")
    if finding.verdict in (Verdict.WRONG, Verdict.TYPO, Verdict.NEEDS_ASSUMPTION) and witness and isinstance(recheck, dict):
        claim = _CONDITION_CLAIMS.get(recheck.get("decision"))
        if claim is None or any(k in witness for k in ("c", "omega", "z")):
            return None
        values = {str(k): str(v) for k, v in witness.items()}
        stated = getattr(state.spec, "assumption", None)    # a Region (hapticproof.audit.regions) or None
        for name, value in (stated.equalities() if stated else {}).items():   # a witness found under it
            values.setdefault(name, str(value))
        out = {**base, "claim": claim, "values": values}
        point = (recheck.get("evidence") or {}).get("witness") or {}
        if claim == "holds-not-passive" and isinstance(point.get("z"), (list, tuple)):
            out["point"] = [str(v) for v in point["z"]]
        return out
    if finding.verdict in (Verdict.CONFIRMED, Verdict.CONSERVATIVE) and state.spec.claim != "necessary-condition" \
            and not state.spec.assumption:
        samples = _holding_points(state, relations)
        if samples and chart is not None and chart.inverse:       # points of the region, in the paper's names
            samples = [{k: str(v) for k, v in chart.witness({n: sp.Rational(x) for n, x in point.items()}).items()}
                       for point in samples]
        if samples:
            out = {**base, "claim": "holds-passive", "values": samples[0], "samples": samples}
            if chart is not None:
                out["region"] = True        # a restricted scene: the checker chooses no points of its own
            return out
    return None


def _holding_points(state: Any, relations: list, count: int = 3) -> list[dict[str, str]]:
    """A few exact parameter points where the printed condition holds (the scene must be
    positive real there, if the condition is sufficient)."""
    from hapticproof.audit.claimbase import holds_at
    from hapticproof.exact.canonical import Sampler
    from hapticproof.systems.models import inverse_transfer

    condition = sp.And(*[state.prepare(r) for r in relations])
    symbols = sorted((condition.free_symbols | inverse_transfer(state.model).free_symbols) - {sp.Symbol("z")}, key=str)
    symbols = [s for s in symbols if s.name != "z"]
    out = []
    for point in Sampler(symbols, seed=23).draw(60):
        if holds_at(condition, point) is True:
            out.append({s.name: str(v) for s, v in point.items()})
            if len(out) == count:
                break
    return out
