"""A stranger's paper drafted with no edits and audited, against its answer key.

``examples/blended-wall`` holds a short paper in unusual notation and its key, written without
the toolkit (``check_key.py`` re-verifies the key with SymPy and NumPy alone). The unedited draft
must not confirm a flaw, must not flag a correct statement, and must agree with the key on most
of the statements it judges.
"""

from __future__ import annotations

import functools
import json
import re
from pathlib import Path

from hapticproof.audit.paperfile import loads
from hapticproof.audit.runner import audit_paper
from hapticproof.audit.source import draft, read_source

EXAMPLE = Path(__file__).resolve().parents[1] / "examples" / "blended-wall"
DEFECTS = {"wrong", "typo", "inconsistent", "needs-assumption", "malformed"}


@functools.lru_cache(maxsize=1)
def _audited() -> dict[str, tuple[str, str]]:
    """id -> (verdict, printed) of the unedited draft's audit."""
    result = draft(read_source(str(EXAMPLE / "paper.tex")), paper_id="blended")
    paper = loads(result.text, "blended.toml")
    return {r.id: (r.verdict.value, paper.paper.get(r.id).printed) for r in audit_paper(paper.paper).results}


def _plain(latex: str) -> str:
    return re.sub(r"\\operatorname\{Re\}|\\Real|[\s$.,;]|\\[,;!]|\\q?quad", "", latex)


def _matched() -> list[tuple[dict, str]]:
    """(key entry, the audit's verdict) for every statement of the key the audit judges: by the
    printed number, else an inline statement by its text."""
    found = _audited()
    by_text = {_plain(printed): verdict for verdict, printed in found.values()}
    out = []
    for entry in json.loads((EXAMPLE / "key.json").read_text(encoding="utf-8")):
        number = str(entry["number"])
        if number in found:
            out.append((entry, found[number][0]))
        elif _plain(entry["latex"]) in by_text:
            out.append((entry, by_text[_plain(entry["latex"])]))
    return out


def test_no_flaw_of_the_key_is_confirmed():
    confirmed = [(e["number"], e["verdict"]) for e, v in _matched() if e["verdict"] != "confirmed" and v == "confirmed"]
    assert not confirmed, confirmed


def test_no_correct_statement_is_flagged():
    """A statement the key confirms is never a defect; ``conservative`` only where the paper itself
    says the condition is sufficient (the key's ``claimed``)."""
    flagged = [(e["number"], v) for e, v in _matched() if e["verdict"] == "confirmed"
               and (v in DEFECTS or (v == "conservative" and e.get("claimed") != "sufficient"))]
    assert not flagged, flagged


def test_the_unedited_draft_agrees_with_most_of_the_key():
    matched = _matched()
    same = [e["number"] for e, v in matched
            if v == e["verdict"] or (v == "conservative" and e["verdict"] == "confirmed" and e.get("claimed") == "sufficient")]
    flaws = [e["number"] for e, v in matched if e["verdict"] != "confirmed" and v == e["verdict"]]
    assert len(matched) >= 14, [e["number"] for e, _ in matched]
    assert len(same) >= 14, (same, matched)
    assert len(flaws) >= 4, flaws                  # the typos and the wrong bound found as such
