"""The example paper files: every faithful display gets the verdict the mathematics says, and
every deliberately altered one (ids ``ALTERED-...``) the pinned verdict; and the single-user part
of the HVE paper written as a paper file agrees with the hand-written modules of derivations/hve/.

Claims of hve.py's Sections 1-3.1 that the paper file cannot express, and why:

* (1), (2), (4), (5) -- Section 1's quotes of other papers (a missing display; operator dynamics
  with the hand spring ``k_h`` to leading order; Gil's conditions judged against the small-damping
  region of the exact boundary and the quote's own numbers); a stability claim compares a display
  with the exact loop or its leading order, not with a region where it is "valid".
* (16a)-(16c) -- the printed recurrences (x(kT + T) = ...) and their z-transforms: no claim kind
  for difference equations.
* (24) -- the c -> 1 limit of (23) printed with an ambiguous slash; the limit of a Hermitian part
  is no claim kind, and the hand-written verdict (typo: the factor KT) rests on a reading outside
  the edit family of the repair search.
* (23a) -- a limit of an expression; (28)-(35) -- the small-gain maps r, M and N (operators on
  G_T^*); def3 -- a definition in words; and the prose claims (16f-residue, 19-worst, 20-colgate,
  20-forward, 22-conditions, 23-worst, 25-identical-7, 36-agree, 36-reduces, 36-identical-7).
"""

from __future__ import annotations

from pathlib import Path

import pytest

from hapticproof.audit.runner import audit_paper
from hapticproof.audit.paperfile import read_paper

ROOT = Path(__file__).resolve().parents[1]

EXPECTED = {
    "colgate-schenkel-1997": {
        "frequency-form": "confirmed", "wall": "confirmed", "spring": "confirmed",
        "ALTERED-sign": "typo", "ALTERED-half": "typo",
    },
    "abbott-okamura-2005": {
        "stiffness": "confirmed", "sampling-period": "confirmed", "necessary": "confirmed",
        "ALTERED-relation": "typo", "ALTERED-damping": "typo", "ALTERED-factor": "wrong",
    },
    "gil-2009": {
        "linear": "confirmed", "no-delay": "confirmed",
        "ALTERED-period": "typo", "ALTERED-damping": "typo", "ALTERED-exact": "wrong",
    },
}

CORRECTED = {
    ("colgate-schenkel-1997", "ALTERED-sign"): r"b > \frac{KT}{2} + |B|",
    ("abbott-okamura-2005", "ALTERED-relation"): r"K < \frac{2b}{T}",
    ("abbott-okamura-2005", "ALTERED-damping"): r"K < \frac{2(b - B)}{T}",
    ("gil-2009", "ALTERED-damping"): r"K < \frac{b + B}{\frac{T}{2} + t_d}",
    # the lost half: T/2 printed as T (a sufficient condition, but not the one claimed)
    ("colgate-schenkel-1997", "ALTERED-half"): r"b > \frac{KT}{2} + |B|",
    ("gil-2009", "ALTERED-period"): r"K < \frac{b + B}{\frac{T}{2} + t_d}",
}


@pytest.fixture(scope="module")
def example_reports():
    out = {}
    for name in EXPECTED:
        paper = read_paper(ROOT / "examples" / f"{name}.toml")
        out[name] = {r.id: r for r in audit_paper(paper.paper).results}
    return out


@pytest.mark.parametrize("name", sorted(EXPECTED))
def test_example_verdicts(name, example_reports):
    results = example_reports[name]
    assert {k: r.verdict.value for k, r in results.items()} == EXPECTED[name]
    for eq_id, result in results.items():
        if not eq_id.startswith("ALTERED"):
            assert result.verdict.value == "confirmed", (eq_id, result.detail)
        if (name, eq_id) in CORRECTED:
            assert result.corrected == CORRECTED[(name, eq_id)]
            assert result.evidence.facts["repair"]["repairs_found"] >= 1


def test_altered_displays_are_marked(example_reports):
    for name in EXPECTED:
        text = (ROOT / "examples" / f"{name}.toml").read_text()
        for eq_id in EXPECTED[name]:
            if eq_id.startswith("ALTERED"):
                line = next(line for line in text.splitlines() if f'id = "{eq_id}"' in line)
                assert "DELIBERATELY ALTERED" in line


def test_wrong_witnesses_are_rechecked(example_reports):
    factor = example_reports["abbott-okamura-2005"]["ALTERED-factor"]
    assert factor.evidence.method == "counterexample" and factor.evidence.facts["recheck"]["decision"] == "disproved"
    exact = example_reports["gil-2009"]["ALTERED-exact"]
    assert exact.evidence.facts["certified"]["decision"] == "disproved"


HVE_IDS = ["3", "16d", "16e", "16f", "17", "18", "19", "20", "21", "22", "23", "25", "26", "26-extends", "27", "36"]


def test_hve_single_user_file_agrees_with_the_hand_written_module():
    from hapticproof.audit.registry import get_paper

    file_paper = read_paper(ROOT / "examples" / "hve-single-user.toml")
    assert [c.id for c in file_paper.claims] == HVE_IDS
    mine = {r.id: r for r in audit_paper(file_paper.paper).results}
    theirs = {r.id: r for r in audit_paper(get_paper("hve"), HVE_IDS).results}
    assert {k: r.verdict.value for k, r in mine.items()} == {k: r.verdict.value for k, r in theirs.items()}
    # the displays are the bundled ones, verbatim
    for eq_id in HVE_IDS:
        source = "27" if eq_id == "26-extends" else eq_id
        assert file_paper.claim(eq_id).printed == get_paper("hve").get(source).printed
    assert mine["19"].corrected == r"b + B \frac{1 + \cos(\omega T)}{2} > 0"
    assert mine["26-extends"].evidence.facts["ids"] == ["26-extends", "3"]
