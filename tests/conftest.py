"""Shared fixtures: the full audit (computed once per test session, for the report tests), the
directory where report tests keep their artefacts (PDFs, screenshots; not committed) and the
papers' transcriptions the "printed verbatim" tests compare with."""

from __future__ import annotations

import os
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]


@pytest.fixture(scope="session")
def audit_reports():
    """The audit of every registered paper, in registry order (about 30 s, once)."""
    from hapticproof.audit.runner import audit_paper
    from hapticproof.audit.registry import papers

    return [audit_paper(paper) for paper in papers().values()]


@pytest.fixture(scope="session")
def artefacts() -> Path:
    """``$HAPTICPROOF_ARTEFACTS`` or ``test-artefacts/`` (git-ignored): PDFs, logs and
    screenshots the report tests leave for a person (or a CI job) to look at."""
    path = Path(os.environ.get("HAPTICPROOF_ARTEFACTS", ROOT / "test-artefacts"))
    path.mkdir(parents=True, exist_ok=True)
    return path


#: Where the papers' transcriptions are. Set (CI sets it when ``../shared/papers`` is there), a
#: missing folder fails the verbatim tests; unset, they read ``../shared/papers`` beside the
#: checkout and skip with the reason when it is absent (a fresh clone on its own).
PAPERS = "HAPTICPROOF_PAPERS"


@pytest.fixture(scope="session")
def paper_transcriptions() -> Path:
    """``$HAPTICPROOF_PAPERS`` or ``../shared/papers`` beside the checkout."""
    given = os.environ.get(PAPERS, "")
    path = Path(given) if given else ROOT.parent / "shared" / "papers"
    if not path.is_dir():
        if given:
            pytest.fail(f"paper transcriptions not found at {path} ({PAPERS} is set)")
        pytest.skip(f"paper transcriptions not found at {path} (a clone on its own; set {PAPERS} to run the verbatim tests)")
    return path
