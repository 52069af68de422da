"""``export`` of one's own paper (issue 29): ``export --paper FILE`` and ``export --from-audit`` of a paper
file's saved audit write the derived and corrected conditions as LaTeX that compiles with pdflatex
(the documents are left in the artefacts directory)."""

from __future__ import annotations

import json
import os
import shutil
import subprocess
import sys
from pathlib import Path

import pytest

sys.path.insert(0, str(Path(__file__).resolve().parent))

from clirun import one_line_error, run  # noqa: E402

ROOT = Path(__file__).resolve().parents[1]
REVIEW = ROOT / "examples" / "reviewer-walls.toml"

needs_tex = pytest.mark.skipif(
    shutil.which("pdflatex") is None or shutil.which("pdftotext") is None,
    reason="pdflatex and pdftotext are not installed (Debian: texlive-latex-base texlive-latex-recommended "
           "texlive-fonts-recommended lmodern poppler-utils; .ci/run installs them)")


def compiled_text(tex: Path) -> str:
    """Compile ``tex`` as the documentation says (no shell escape, no file outside the folder) and
    return the text of the PDF."""
    done = subprocess.run(["pdflatex", "-no-shell-escape", "-interaction=nonstopmode", "-halt-on-error", tex.name],
                          cwd=tex.parent, capture_output=True, text=True, timeout=300,
                          env=dict(os.environ, openout_any="p", openin_any="p"))
    assert done.returncode == 0, f"{tex.name} does not compile:\n" + done.stdout[-3000:]
    return subprocess.run(["pdftotext", "-enc", "UTF-8", tex.with_suffix(".pdf").name, "-"], cwd=tex.parent,
                          capture_output=True, text=True, timeout=120, check=True).stdout


@pytest.fixture(scope="module")
def exported(tmp_path_factory, artefacts):
    """The paper file exported directly and through its saved audit (with and without the file)."""
    import contextlib
    import io

    from hapticproof.cli import main

    folder = tmp_path_factory.mktemp("own")
    out: dict[str, Path] = {}
    with contextlib.redirect_stderr(io.StringIO()):
        assert main(["export", "--paper", str(REVIEW), "-o", str(folder / "direct.tex")]) == 0
        assert main(["audit", "--paper", str(REVIEW), "--format", "json", "-o", str(folder / "audit.json")]) == 0
        assert main(["export", "--from-audit", str(folder / "audit.json"), "-o", str(folder / "saved.tex")]) == 0
        assert main(["export", "--paper", str(REVIEW), "--from-audit", str(folder / "audit.json"),
                     "-o", str(folder / "saved-with-file.tex")]) == 0
    for name in ("direct", "saved", "saved-with-file"):
        out[name] = folder / f"{name}.tex"
        shutil.copy(out[name], artefacts / f"export-own-{name}.tex")
    out["audit"] = folder / "audit.json"
    return out


@needs_tex
@pytest.mark.parametrize("name", ["direct", "saved"])
def test_the_export_of_a_paper_file_compiles_with_its_corrections(exported, name):
    audit = json.loads(exported["audit"].read_text())
    text = compiled_text(exported[name])
    assert audit["title"].split(",")[0] in text
    corrected = [e for e in audit["equations"] if e["corrected"]]
    labels = [line.strip() for line in text.splitlines()]
    assert corrected and labels.count("Corrected") == len(corrected)          # every defect with its correction
    assert labels.count("Derived") == sum(1 for e in audit["equations"] if e["derived"])
    typo = next(e for e in audit["equations"] if e["verdict"] == "typo" and "a lost half" in e["detail"])
    assert "(a lost half)" in text and f"({typo['id']})" in text


def test_the_saved_audit_gives_the_same_document_as_the_file(exported):
    assert exported["saved-with-file"].read_text() == exported["direct"].read_text()
    # without the paper file the document misses only what the JSON does not carry (sections, assumptions)
    assert "reviewer-walls" in exported["saved"].read_text()


def test_a_paper_file_named_as_a_paper_is_pointed_to_paper(capsys):
    err = one_line_error(capsys, "export", str(REVIEW))
    assert f"a paper file is exported with --paper {REVIEW}" in err
    err = one_line_error(capsys, "export", "reviewer-walls")
    assert "unknown paper 'reviewer-walls'" in err and "--paper FILE" in err


def test_a_saved_audit_without_the_named_paper_says_what_it_holds(capsys, exported):
    err = one_line_error(capsys, "export", "hve", "--from-audit", str(exported["audit"]))
    assert "has no audit of hve (it holds: reviewer-walls)" in err


def test_a_mistake_in_the_paper_file_is_one_line(capsys, tmp_path):
    bad = tmp_path / "bad.toml"
    bad.write_text('[paper]\nid = "x"\ntitle = "x"\n[[equations]]\nid = "1"\nprinted = "b > 0"\nclaim = "passivity"\n')
    err = one_line_error(capsys, "export", "--paper", str(bad), "-o", str(tmp_path / "x.tex"))
    assert "bad.toml" in err and not (tmp_path / "x.tex").exists()
    code, _, _ = run(capsys, "export", "--paper", str(bad), "-o", str(tmp_path / "x.tex"))
    assert code == 2
