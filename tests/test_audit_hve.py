"""Pin every verdict of the HVE paper's audit (Sections 1-3.1) and the evidence it carries."""

import functools

import pytest
import sympy as sp

from hapticproof.audit.runner import audit_paper
from hapticproof.core.evidence import Verdict
from hapticproof.audit.registry import get_paper

# Every registered equation of Sections 1-3.1 and its verdict. A change here is a change of a
# mathematical finding: re-derive by hand before editing.
EXPECTED = {
    "1": "malformed",
    "3": "confirmed",
    "def3": "wrong",
    "16a": "typo",
    "16b": "typo",
    "16c": "typo",
    "16d": "confirmed",
    "16e": "confirmed",
    "16f": "confirmed",
    "16f-residue": "confirmed",
    "17": "confirmed",
    "18": "confirmed",
    "19": "malformed",
    "19-worst": "confirmed",
    "20": "confirmed",
    "20-colgate": "confirmed",
    "20-forward": "confirmed",
    "21": "confirmed",
    "22": "confirmed",
    "22-conditions": "typo",
    "23": "wrong",
    "23-worst": "needs-assumption",
    "23a": "confirmed",
    "24": "typo",
    "25": "needs-assumption",
    "26": "confirmed",
    "26-extends": "inconsistent",
    "27": "needs-assumption",
    "28": "confirmed",
    "29": "confirmed",
    "30": "confirmed",
    "31": "typo",
    "32": "confirmed",
    "33": "confirmed",
    "34": "typo",
    "35": "typo",
    "36": "confirmed",
    "36-agree": "confirmed",
    "36-reduces": "needs-assumption",
}


@functools.lru_cache(maxsize=1)
def report():
    paper = get_paper("hve")
    return {r.id: r for r in audit_paper(paper, list(EXPECTED)).results}


@pytest.mark.parametrize("eq_id", list(EXPECTED))
def test_verdict(eq_id):
    result = report()[eq_id]
    assert result.verdict.value == EXPECTED[eq_id], result.detail


@pytest.mark.parametrize("eq_id", list(EXPECTED))
def test_evidence_is_data(eq_id):
    result = report()[eq_id]
    evidence = result.evidence.to_json()
    assert evidence["method"]
    if result.verdict in (Verdict.WRONG, Verdict.NEEDS_ASSUMPTION) and result.kind != "claim":
        assert evidence.get("witness"), "a refutation needs an exact witness"
    if result.verdict not in (Verdict.CONFIRMED, Verdict.CONSERVATIVE, Verdict.UNDECIDED) and result.kind != "claim":
        assert result.corrected, "a defective printed equation needs its corrected LaTeX"


def test_single_user_section_is_complete():
    """Every numbered display of Sections 1-3.1 that the issue names is registered."""
    registered = set(get_paper("hve").equations)
    needed = {"1", "3", *map(str, range(17, 37)), "16a", "16b", "16c", "16d", "16e", "16f", "23a"}
    assert needed <= registered


def test_witnesses_are_exact_and_recheck():
    from hapticproof.analysis.positivereal import worst_case
    from hapticproof.systems.singleuser import SingleUserScene

    w = report()["25"].evidence.witness
    scene = SingleUserScene.virtual_wall(K=w["K"], B=w["B"], b=w["b"], T=w["T"], delay=w["n"])
    printed = sp.Rational(w["b"]) + sp.Rational(w["B"]) - sp.Rational(w["K"]) * sp.Rational(w["T"]) * sp.Rational(3, 2)
    assert printed > 0  # (25) holds at the witness ...
    assert worst_case(scene).decision.value == "disproved"  # ... and G^-1 is not positive real


def test_json_shape():
    paper = get_paper("hve")
    data = audit_paper(paper, ["17", "23"]).to_json()
    assert data["paper"] == "hve" and data["title"]
    for eq in data["equations"]:
        assert set(eq) == {"id", "kind", "printed", "derived", "verdict", "detail", "corrected", "evidence", "seconds"}
