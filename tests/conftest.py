"""Shared fixtures: the full audit (computed once per test session, for the report tests) and
the directory where report tests keep their artefacts (PDFs, screenshots; not committed)."""

from __future__ import annotations

import os
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]


@pytest.fixture(scope="session")
def audit_reports():
    """The audit of every registered paper, in registry order (about 30 s, once)."""
    from hapticproof.audit import audit_paper
    from hapticproof.registry import papers

    return [audit_paper(paper) for paper in papers().values()]


@pytest.fixture(scope="session")
def artefacts() -> Path:
    """``$HAPTICPROOF_ARTEFACTS`` or ``test-artefacts/`` (git-ignored): PDFs, logs and
    screenshots the report tests leave for a person (or a CI job) to look at."""
    path = Path(os.environ.get("HAPTICPROOF_ARTEFACTS", ROOT / "test-artefacts"))
    path.mkdir(parents=True, exist_ok=True)
    return path
