"""Shapes of the JSON reports the toolkit reads back (``check REPORT.json``, ``export
--from-audit AUDIT.json``): checked before anything uses them, so that a number, ``null``, a
string or a table of the wrong form is one line naming the file and the place
(``audit.json: papers[0].equations[3]: missing field 'id'``), never a ``KeyError``.

The shapes are those of ``DESIGN.md`` (audit JSON) and of ``derive ... --format json``:

* an audit of one paper: ``{"paper": str, "title": str, "equations": [equation, ...]}``;
* audits of several: ``{"papers": [audit, ...]}``;
* a derivation: ``{"conditions": [{"name": str, "decision": str, ...}, ...], ...}``;

where an equation is ``{"id": str, "kind": str, "printed": str, "derived": str | null,
"verdict": str, "detail": str, "corrected": str | null, "evidence": {"method": str, ...},
"seconds": number}``.

>>> report_kind({"papers": []}, "a.json")
'audits'
>>> report_kind(42, "a.json")
Traceback (most recent call last):
...
hapticproof.core.errors.InputFormatError: a.json: not a hapticproof report (a JSON object with 'paper' and 'equations', 'papers', 'parameter' or 'conditions' is expected, got a number)
"""

from __future__ import annotations

from collections.abc import Mapping
from typing import Any

from hapticproof.core.errors import InputFormatError

__all__ = ["report_kind", "check_audit", "check_report"]


def _kind_of(value: Any) -> str:
    if value is None:
        return "null"
    if isinstance(value, bool):
        return "true/false"
    if isinstance(value, (int, float)):
        return "a number"
    if isinstance(value, str):
        return "text"
    if isinstance(value, list):
        return "a list"
    if isinstance(value, Mapping):
        return "an object"
    return type(value).__name__


def report_kind(data: Any, name: str) -> str:
    """``'audit'`` (one paper), ``'audits'`` (``{"papers": [...]}``), ``'derive'`` (``conditions``)
    or ``'boundary'`` (a stability boundary: ``parameter`` and its ``judge``); anything else is
    refused in one line."""
    if isinstance(data, Mapping):
        if "parameter" in data and isinstance(data.get("judge"), Mapping):
            return "boundary"
        if "papers" in data:
            return "audits"
        if "equations" in data:
            return "audit"
        if "conditions" in data:
            return "derive"
    raise InputFormatError(f"{name}: not a hapticproof report (a JSON object with 'paper' and 'equations', 'papers', 'parameter' "
                           f"or 'conditions' is expected, got {_kind_of(data) if not isinstance(data, Mapping) else 'an object without them'})")


def _field(entry: Mapping[str, Any], key: str, kinds: tuple[type, ...], where: str, required: bool = True) -> None:
    if key not in entry:
        if required:
            raise InputFormatError(f"{where}: missing field {key!r}")
        return
    value = entry[key]
    ok = isinstance(value, kinds) and not (isinstance(value, bool) and bool not in kinds)
    if not ok:
        wanted = " or ".join({str: "text", type(None): "null", Mapping: "an object", list: "a list",
                              int: "a number", float: "a number", bool: "true/false"}.get(k, k.__name__) for k in kinds)
        raise InputFormatError(f"{where}: field {key!r} must be {wanted}, got {_kind_of(value)}")


def _list(data: Mapping[str, Any], key: str, where: str) -> list:
    _field(data, key, (list,), where)
    return data[key]


def _object(value: Any, where: str) -> Mapping[str, Any]:
    if not isinstance(value, Mapping):
        raise InputFormatError(f"{where}: expected an object, got {_kind_of(value)}")
    return value


def _paper(data: Any, name: str, path: str) -> None:
    from hapticproof.core.evidence import Verdict

    here = f"{name}: {path}" if path else name
    paper = _object(data, here)
    _field(paper, "paper", (str,), here)
    _field(paper, "title", (str,), here, required=False)
    verdicts = {v.value for v in Verdict}
    for k, entry in enumerate(_list(paper, "equations", here)):
        where = f"{name}: {path + '.' if path else ''}equations[{k}]"
        entry = _object(entry, where)
        for key in ("id", "kind", "printed", "verdict", "detail"):
            _field(entry, key, (str,), where)
        for key in ("derived", "corrected"):
            _field(entry, key, (str, type(None)), where, required=False)
        _field(entry, "seconds", (int, float), where, required=False)
        if entry["verdict"] not in verdicts:
            raise InputFormatError(f"{where}: unknown verdict {entry['verdict'][:40]!r} (verdicts: {', '.join(sorted(verdicts))})")
        _field(entry, "evidence", (Mapping,), where)
        if "evidence" in entry:
            evidence = _object(entry["evidence"], f"{where}.evidence")
            _field(evidence, "method", (str,), f"{where}.evidence")
            _field(evidence, "witness", (Mapping, type(None)), f"{where}.evidence", required=False)
            _field(evidence, "facts", (Mapping,), f"{where}.evidence", required=False)
            _field(evidence, "instances", (int, Mapping, list, type(None)), f"{where}.evidence", required=False)


def check_audit(data: Any, name: str) -> str:
    """Check a saved audit (``audit --format json``): one paper or ``{"papers": [...]}``;
    returns its :func:`report_kind`.

    >>> check_audit({"paper": "p", "equations": [{"id": "1", "kind": "condition", "printed": "x", "verdict": "typo",
    ...     "detail": "a slip", "evidence": {"method": "canonical-form"}}]}, "a.json")
    'audit'
    >>> check_audit({"paper": "p", "equations": [None]}, "a.json")
    Traceback (most recent call last):
    ...
    hapticproof.core.errors.InputFormatError: a.json: equations[0]: expected an object, got null
    """
    kind = report_kind(data, name)
    if kind == "derive":
        raise InputFormatError(f"{name}: a derivation (conditions), not a saved audit (audit --format json)")
    if kind == "audit":
        _paper(data, name, "")
    else:
        for k, paper in enumerate(_list(data, "papers", name)):
            _paper(paper, name, f"papers[{k}]")
    return kind


def check_report(data: Any, name: str) -> str:
    """Check a report for ``hapticproof check``: a saved audit or derivation; returns its kind.

    >>> check_report({"conditions": [{"name": "x", "decision": "proved"}]}, "d.json")
    'derive'
    """
    kind = report_kind(data, name)
    if kind == "boundary":
        _field(data, "parameter", (str,), name)
        _field(data, "outcome", (str,), name, required=False)
        return kind
    if kind != "derive":
        return check_audit(data, name)
    for k, entry in enumerate(_list(data, "conditions", name)):
        where = f"{name}: conditions[{k}]"
        entry = _object(entry, where)
        _field(entry, "name", (str,), where, required=False)
        _field(entry, "decision", (str,), where, required=False)
    return kind
