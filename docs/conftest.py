"""The documentation's ``>>>`` examples run as a reader runs them: in a folder of their own that holds
the source folder's ``examples/`` and the tutorial's ``walls.toml`` ("save this as walls.toml")."""

from __future__ import annotations

import shutil
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]


@pytest.fixture(autouse=True)
def _a_readers_folder(request, tmp_path, monkeypatch):
    if not str(getattr(request.node, "path", "")).endswith(".rst"):
        yield
        return
    shutil.copytree(ROOT / "examples", tmp_path / "examples")
    shutil.copy(ROOT / "examples" / "walls.toml", tmp_path / "walls.toml")
    monkeypatch.chdir(tmp_path)
    yield
