r"""The summaries a network report shows, held against its conditions (part of the checker:
imports only ``core`` and the checker's own modules).

``derive network`` shows its matrix ``Z(s)``, its poles, and the decisions of positive realness,
Llewellyn's criterion and absolute stability twice: as conditions that carry their certificates
and definition objects, and as summaries (``positive_real``, ``llewellyn``, ``absolute_stability``)
a reader looks at first. A summary is only what its condition says:

* each summary's decision is its condition's; Llewellyn's table of conditions and ``eta_min``
  are those of the condition's own nested conditions;
* the ``matrix`` shown is the definition object's ``Z(s)``, entry by entry, as rational functions
  of ``s``, with ``size`` and ``ports`` that fit it;
* ``poles.rhp`` is empty exactly when the roots certificate counts no pole in ``Re s > 0``.

>>> report = {"matrix": [["1/(s + 1)"]], "size": 1, "ports": [1],
...           "positive_real": {"decision": "disproved"},
...           "conditions": [{"name": "Z positive real (Definition 3)", "decision": "proved",
...                           "definition": {"transfer": {"variable": "s", "entries": [[{"num": ["1"], "den": ["1", "1"]}]]}}}]}
>>> network_displays(report)
["the summary positive_real says 'disproved', its condition 'Z positive real (Definition 3)' says 'proved'"]
"""

from __future__ import annotations

from collections.abc import Mapping
from typing import Any

from hapticproof.exact.acceptance import rational_of
from hapticproof.exact.checkarith import certificates, exact_q, json_poly

__all__ = ["network_displays"]

#: summary key -> the name its condition starts with
_SUMMARIES = {"positive_real": "Z positive real", "llewellyn": "Llewellyn's criterion",
              "absolute_stability": "absolute stability"}


def _condition(report: Mapping[str, Any], prefix: str) -> Mapping[str, Any] | None:
    for cond in report.get("conditions") or []:
        if isinstance(cond, Mapping) and str(cond.get("name", "")).startswith(prefix):
            return cond
    return None


def _summaries(report: Mapping[str, Any]) -> list[str]:
    out = []
    for key, prefix in _SUMMARIES.items():
        shown = report.get(key)
        if shown is None:
            continue
        cond = _condition(report, prefix)
        if not isinstance(shown, Mapping):
            out.append(f"the summary {key} is not an object")
            continue
        if cond is None:
            out.append(f"the summary {key} is shown with no condition {prefix!r} to back it")
            continue
        if shown.get("decision") != cond.get("decision"):
            out.append(f"the summary {key} says {str(shown.get('decision'))[:20]!r}, its condition "
                       f"{str(cond.get('name'))[:60]!r} says {str(cond.get('decision'))[:20]!r}")
        if key == "llewellyn":
            nested = {str(c.get("name")): c.get("decision") for c in cond.get("conditions") or [] if isinstance(c, Mapping)}
            if shown.get("conditions") is not None and shown.get("conditions") != nested:
                out.append("Llewellyn's conditions shown are not those of its condition (a name or a decision differs)")
            if "eta_min" in shown and not _same_number(shown.get("eta_min"), cond.get("eta_min")):
                out.append(f"the eta_min shown ({str(shown.get('eta_min'))[:30]}) is not its condition's "
                           f"({str(cond.get('eta_min'))[:30]})")
    return out


def _same_number(a: Any, b: Any) -> bool:
    if a is None or b is None:
        return a is b
    try:
        return exact_q(str(a)) == exact_q(str(b))
    except (TypeError, ValueError, ZeroDivisionError):
        return a == b


def network_displays(report: Mapping[str, Any]) -> list[str]:
    """Refusals: a network report's summaries, matrix or poles that are not what its conditions
    and their definition object say."""
    if "matrix" not in report or "conditions" not in report:
        return []
    out = _summaries(report)
    pr = _condition(report, _SUMMARIES["positive_real"])
    definition = pr.get("definition") if isinstance(pr, Mapping) else None
    transfer = definition.get("transfer") if isinstance(definition, Mapping) else None
    if not isinstance(transfer, Mapping) or "entries" not in transfer:
        return out + ["the matrix shown is not tied to a definition object (no condition 'Z positive real' carries one)"]
    cells, shown = transfer["entries"], report["matrix"]
    m = len(cells)
    if not (isinstance(shown, list) and len(shown) == m and all(isinstance(r, list) and len(r) == m for r in shown)):
        return out + [f"the matrix shown is not the {m} x {m} matrix its conditions decide"]
    if report.get("size") != m or not (isinstance(report.get("ports"), list) and sum(report["ports"]) == m
                                        and all(isinstance(p, int) and p > 0 for p in report["ports"])):
        out.append(f"the size and ports shown do not fit the {m} x {m} matrix decided")
    for i in range(m):
        for j in range(m):
            cell = cells[i][j]
            num, den = rational_of(shown[i][j], max(len(cell["num"]), len(cell["den"])), "s")
            if num * json_poly(cell["den"]) != json_poly(cell["num"]) * den:
                return out + [f"the matrix shown is not the Z(s) its conditions decide: entry ({i + 1}, {j + 1}) differs"]
    poles = report.get("poles")
    roots = [c for cond in (pr.get("conditions") or []) if isinstance(cond, Mapping)
             and str(cond.get("name", "")).startswith("poles in Re s") for c in certificates(cond)
             if c.get("certificate") == "roots"]
    if isinstance(poles, Mapping) and roots:
        if not isinstance(poles.get("rhp"), list) or (len(poles["rhp"]) == 0) != (roots[0].get("outside") == 0):
            out.append("the poles in Re s > 0 shown are not what the roots certificate counts")
    return out
