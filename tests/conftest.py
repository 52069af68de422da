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


#: Set to 1 where the papers' transcriptions are intentionally absent (e.g. an sdist build):
#: the verbatim tests then skip; anywhere else a missing ``../shared/papers`` fails them.
NO_PAPERS = "HAPTICPROOF_NO_PAPERS"


@pytest.fixture(scope="session")
def paper_transcriptions() -> Path:
    """``$HAPTICPROOF_PAPERS`` or ``../shared/papers`` beside the checkout (CI has it). Missing
    papers fail the test unless ``HAPTICPROOF_NO_PAPERS=1`` says they are absent on purpose, so
    the verbatim tests cannot vanish silently."""
    path = Path(os.environ.get("HAPTICPROOF_PAPERS", ROOT.parent / "shared" / "papers"))
    if not path.is_dir():
        if os.environ.get(NO_PAPERS, "") not in ("", "0"):
            pytest.skip(f"paper transcriptions intentionally absent ({NO_PAPERS} is set)")
        pytest.fail(f"paper transcriptions not found at {path} (set HAPTICPROOF_PAPERS, or {NO_PAPERS}=1 to skip)")
    return path
