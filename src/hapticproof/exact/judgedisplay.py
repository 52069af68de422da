"""What a report displays, re-derived from what it carries: ``hapticproof check`` refuses a
verdict or witness that the report's own evidence does not give (part of the checker: imports
only :mod:`hapticproof.exact.judge` and :mod:`hapticproof.exact.checkarith`)."""

from __future__ import annotations

import math
from collections.abc import Iterator, Mapping
from typing import Any

from hapticproof.exact.judge import consistent_witness, displayed_number

__all__ = ["derive_display", "finding_display", "boundary_display"]


#: The verdicts a judged claim supports (a finding showing another verdict is refused).
_VERDICTS = {
    ("circle-identity", "equal"): ("confirmed",),
    ("circle-identity", "differ"): ("wrong", "typo"),
    ("condition", "holds-not-passive"): ("wrong", "typo", "needs-assumption"),
    ("condition", "fails-passive"): ("wrong", "typo", "needs-assumption"),
    ("condition", "holds-passive"): ("confirmed", "conservative"),
}

#: The names of a positive-realness decision's pole conditions (the JSON of ``derive``).
_POLES, _SIMPLE, _RESIDUES = ("poles in |z| <= 1", "unit-circle poles simple", "Res/z0 >= 0 at unit-circle poles")


def _certificates_in(node: Any) -> Iterator[dict]:
    if isinstance(node, dict):
        if isinstance(node.get("certificate"), str):
            yield node
            return
        for value in node.values():
            yield from _certificates_in(value)
    elif isinstance(node, list):
        for value in node:
            yield from _certificates_in(value)


def _same(a: Any, b: Any) -> bool:
    """Equal as exact numbers where both are numbers, else as JSON."""
    if isinstance(a, dict) and isinstance(b, dict):
        return a.keys() == b.keys() and all(_same(a[k], b[k]) for k in a)
    if isinstance(a, (list, tuple)) and isinstance(b, (list, tuple)):
        return len(a) == len(b) and all(_same(x, y) for x, y in zip(a, b))
    na, nb = displayed_number(a), displayed_number(b)
    return na == nb


def _condition_display(cond: Mapping[str, Any]) -> list[str]:
    """A derive condition's decision and witness against its own certificates."""
    name, decision = cond.get("name"), cond.get("decision")
    evidence = cond.get("evidence", {})
    certs = list(_certificates_in(evidence))
    problems = []
    if name not in (_POLES, _SIMPLE, _RESIDUES):
        # a sign condition (Re G^-1 >= 0, a Hermitian part PSD): its certificates decide it
        signs = [c for c in certs if c["certificate"] in ("sign", "chebyshev-sign", "psd", "constant-psd")]
        if signs and decision in ("proved", "disproved") and all(c["holds"] for c in signs) != (decision == "proved"):
            problems.append(f"{name}: the decision says {decision}, its certificates say "
                            f"{'it holds' if decision == 'disproved' else 'it fails'}")
        witness = evidence.get("witness")
        for cert in signs:
            if cert["holds"] or not witness:
                continue
            own = cert["witness"] if isinstance(cert.get("witness"), dict) else \
                {"c": cert.get("witness"), "z": cert.get("witness_point")}
            for key in ("c", "z"):
                if key in witness and own.get(key) is not None and not _same(witness[key], own[key]):
                    problems.append(f"{name}: the displayed {key} = {witness[key]} is not the certificate's {own[key]}")
            break
    elif name == _POLES:
        for cert in certs:
            if cert["certificate"] == "roots" and decision in ("proved", "disproved") and \
                    (cert["outside"] == 0) != (decision == "proved"):
                problems.append(f"{name}: the decision says {decision}, the roots certificate counts {cert['outside']} outside")
    elif name == _SIMPLE:
        for cert in certs:
            if cert["certificate"] == "roots" and decision in ("proved", "disproved"):
                simple = all(r.get("multiplicity") == 1 for r in cert.get("boundary", []))
                if simple != (decision == "proved"):
                    problems.append(f"{name}: the decision says {decision}, the roots certificate says simple = {simple}")
    elif name == _RESIDUES:
        residues = [c for c in certs if c["certificate"] == "residue"]
        if residues and decision in ("proved", "disproved") and all(c["holds"] for c in residues) != (decision == "proved"):
            problems.append(f"{name}: the decision says {decision}, the residue certificates disagree")
    return problems


def _combined(decisions: list[str]) -> str:
    for word in ("disproved", "undecided", "symbolic"):
        if word in decisions:
            return word
    return "proved"


def derive_display(report: Mapping[str, Any]) -> list[str]:
    """A ``derive --format json`` report's verdict and witness re-derived from its conditions
    and their certificates, and its ``definition`` (when present) held against both."""
    conditions = report.get("conditions") or []
    problems = [p for cond in conditions for p in _condition_display(cond)]
    if not conditions or "verdict" not in report:
        return problems
    expected = _combined([c.get("decision") for c in conditions])
    definition = report.get("definition")
    refused = isinstance(definition, dict) and definition.get("judged", {}).get("ok") is False
    if refused:
        # the report itself says the judge disagreed: then (and only then) it shows 'undecided'
        if report["verdict"] != "undecided":
            problems.append(f"the verdict shown is {report['verdict']!r} although its definition check failed")
        if report.get("witness"):
            problems.append("a witness is shown for a verdict the definition check refused")
        return problems
    if report["verdict"] != expected:
        problems.append(f"the verdict shown is {report['verdict']!r}, its conditions give {expected!r}")
    first = next((c for c in conditions if c.get("decision") == "disproved"), None)
    shown = report.get("witness")
    if first is not None and shown is not None:       # (a report that shows no witness shows none wrongly)
        own = first.get("evidence", {}).get("witness")
        if not _same(shown, own):
            problems.append(f"the witness shown {shown} is not the failing condition's ({first.get('name')}: {own})")
    elif shown:
        problems.append(f"a witness {shown} is shown, but no condition is disproved")
    if isinstance(definition, dict):
        if definition.get("decision") != report["verdict"] and report["verdict"] in ("proved", "disproved"):
            problems.append(f"the verdict shown is {report['verdict']!r}, the definition object says {definition.get('decision')!r}")
        problems += consistent_witness(shown, definition)
    return problems


def finding_display(entry: Mapping[str, Any]) -> list[str]:
    """An audit entry's verdict and displayed witness against its judge object."""
    evidence = entry.get("evidence") or {}
    obj = (evidence.get("facts") or {}).get("judge")
    if not isinstance(obj, dict) or "verdict" not in entry:
        return []
    problems = []
    allowed = _VERDICTS.get((obj.get("judge"), obj.get("claim")))
    if allowed is not None and entry["verdict"] not in allowed:
        problems.append(f"the verdict shown is {entry['verdict']!r}, but the judged claim {obj.get('claim')!r} supports "
                        f"{' or '.join(allowed)}")
    problems += consistent_witness(evidence.get("witness"), obj)
    return problems


def boundary_display(report: Mapping[str, Any]) -> list[str]:
    """A boundary's displayed value, tolerance and direction against the two loops it carries."""
    obj = report.get("judge")
    if not isinstance(obj, dict) or obj.get("judge") != "stability" or report.get("value") is None:
        return []
    problems = []
    (left, right) = obj["sides"]
    value, tol = float(report["value"]), float(report["tolerance"])
    for side, target in ((left, value - tol), (right, value + tol)):
        if not math.isclose(float(side["value"]), target, rel_tol=1e-12, abs_tol=1e-300):
            problems.append(f"the loop judged at {side['value']:.12g} is not the displayed {report['parameter']}* "
                            f"{'-' if side is left else '+'} tolerance = {target:.12g}")
    expected = (True, False) if report.get("direction") == "destabilising" else (False, True)
    if (left["stable"], right["stable"]) != expected:
        problems.append(f"the direction shown ({report.get('direction')}) is not what the two judged loops say")
    return problems
