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

from hapticproof.exact.acceptance import differing_entry
from hapticproof.exact.checkarith import certificates, exact_q

__all__ = ["network_displays"]

#: summary key -> the name its condition starts with
_SUMMARIES = {"positive_real": "Z positive real", "llewellyn": "Llewellyn's criterion",
              "absolute_stability": "absolute stability", "zprime_positive_real": "Z' positive real"}

#: the method an absolute-stability decision names -> the summary that must back it (and its decision)
_METHODS = {"positive real": ("positive_real", "proved"), "Llewellyn": ("llewellyn", None),
            "Youla symmetrization": ("zprime_positive_real", None)}


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
    cells = transfer["entries"]
    m = len(cells)
    try:
        differs = differing_entry(report["matrix"], cells, "s")
    except ValueError:
        return out + [f"the matrix shown is not the {m} x {m} matrix its conditions decide"]
    if report.get("size") != m or not (isinstance(report.get("ports"), list) and sum(report["ports"]) == m
                                        and all(isinstance(p, int) and p > 0 for p in report["ports"])):
        out.append(f"the size and ports shown do not fit the {m} x {m} matrix decided")
    if differs:
        return out + [f"the matrix shown is not the Z(s) its conditions decide: entry {differs} differs"]
    out += _symmetrization(report) + _absolute_stability(report, cells)
    poles = report.get("poles")
    roots = [c for cond in (pr.get("conditions") or []) if isinstance(cond, Mapping)
             and str(cond.get("name", "")).startswith("poles in Re s") for c in certificates(cond)
             if c.get("certificate") == "roots"]
    if isinstance(poles, Mapping) and roots:
        if not isinstance(poles.get("rhp"), list) or (len(poles["rhp"]) == 0) != (roots[0].get("outside") == 0):
            out.append("the poles in Re s > 0 shown are not what the roots certificate counts")
    return out


def _symmetrization(report: Mapping[str, Any]) -> list[str]:
    """Youla's symmetrization: proved only with no condition left unsatisfied; the ``Z_prime`` shown
    is the ``Z'`` the certificates of its positive-realness condition decide."""
    sym = report.get("symmetrization")
    if sym is None:
        return []
    if not isinstance(sym, Mapping):
        return ["the symmetrization shown is not an object"]
    out = []
    if (sym.get("decision") == "proved") != (not report.get("symmetrization_conditions")):
        out.append(f"the symmetrization is shown {str(sym.get('decision'))[:20]!r}, but its conditions "
                   f"{'do not all' if report.get('symmetrization_conditions') else 'all'} hold identically")
    cond = _condition(report, _SUMMARIES["zprime_positive_real"])
    shown = sym.get("Z_prime")
    if shown is not None:
        decided = [c["transfer"] for c in certificates(cond or {}) if isinstance(c.get("transfer"), Mapping)
                   and "entries" in c["transfer"]]
        if not decided:
            return out + ["the Z' shown is not tied to a certificate of its positive realness"]
        try:
            differs = differing_entry(shown, decided[0]["entries"], "s")
        except ValueError:
            return out + ["the Z' shown is not the matrix its certificates decide"]
        if differs:
            return out + [f"the Z' shown is not the one its certificates decide: entry {differs} differs"]
    return out


def _absolute_stability(report: Mapping[str, Any], cells: list) -> list[str]:
    """The method an absolute-stability decision names is the summary that decides it; a
    destabilising termination shown makes ``det(Z + R)`` vanish in ``Re s > 0`` (exact)."""
    shown = report.get("absolute_stability")
    if not isinstance(shown, Mapping):
        return []
    out = []
    backing = _METHODS.get(shown.get("method"))
    if backing is not None:
        summary = report.get(backing[0])
        if not isinstance(summary, Mapping) or (backing[1] or shown.get("decision")) != summary.get("decision"):
            out.append(f"the absolute stability shown rests on {shown.get('method')!r}, which does not decide it so")
    elif shown.get("method") == "open-circuit instability":
        if shown.get("decision") != "disproved" or not (report.get("poles") or {}).get("rhp"):
            out.append("the absolute stability shown rests on an open-circuit instability the poles shown do not have")
    elif shown.get("method") is not None:
        out.append(f"the absolute stability shown names an unknown method {str(shown.get('method'))[:30]!r}")
    certificate = shown.get("certificate")
    if certificate is not None:
        out += _termination(certificate, cells, report.get("ports"))
    return out


def _termination(certificate: Any, cells: list, ports: Any) -> list[str]:
    """``det(Z(s) + R)`` with the block-diagonal resistive termination ``R`` shown has a zero in
    ``Re s > 0`` (its numerator in lowest terms, by Routh-Hurwitz): the network is destabilised."""
    import sympy as sp

    from hapticproof.exact.checkarith import has_root_outside

    blocks = certificate.get("terminations") if isinstance(certificate, Mapping) else None
    m = len(cells)
    if not isinstance(blocks, list) or not isinstance(ports, list) or len(blocks) != len(ports) or sum(ports) != m:
        return ["the destabilising termination shown does not fit the ports"]
    s = sp.Symbol("s")
    R = sp.zeros(m, m)
    at = 0
    for block, size in zip(blocks, ports):
        if not (isinstance(block, list) and len(block) == size and all(isinstance(r, list) and len(r) == size for r in block)):
            return ["the destabilising termination shown does not fit the ports"]
        for i in range(size):
            for j in range(size):
                value = exact_q(block[i][j])
                R[at + i, at + j] = sp.Rational(value.numerator, value.denominator)
        at += size

    def entry(cell: Mapping[str, Any]) -> Any:
        num = sum(sp.Rational(str(c)) * s**k for k, c in enumerate(cell["num"]))
        den = sum(sp.Rational(str(c)) * s**k for k, c in enumerate(cell["den"]))
        return num / den

    Z = sp.Matrix(m, m, lambda i, j: entry(cells[i][j]))
    num, _ = sp.fraction(sp.cancel(sp.together((Z + R).det())))
    coeffs = [sp.Rational(c) for c in reversed(sp.Poly(num, s).all_coeffs())]
    import flint

    p = flint.fmpq_poly([flint.fmpq(int(c.p), int(c.q)) for c in coeffs])
    if not has_root_outside(p, "halfplane"):
        return ["the destabilising termination shown does not destabilise Z: det(Z + R) has no zero in Re s > 0"]
    roots = [complex(float(r.real.mid()), float(r.imag.mid())) for r, _ in p.complex_roots()] if p.degree() > 0 else []
    for text in certificate.get("rhp_roots") or []:
        try:
            root = complex(str(text).replace(" ", ""))
        except ValueError:
            return [f"a right-half-plane root shown ({str(text)[:30]}) cannot be read"]
        if root.real <= 0 or not any(abs(root - r) <= 1e-3 * (1 + abs(r)) for r in roots):
            return [f"the right-half-plane root shown {str(text)[:30]} is no zero of det(Z + R) in Re s > 0"]
    return []
