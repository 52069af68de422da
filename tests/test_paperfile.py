"""Paper files: the format, its errors (file, line, field; exit 2, no traceback), the template
and ``hapticproof audit --paper`` in every output format."""

from __future__ import annotations

import json
import shutil
import subprocess

import pytest
import sympy as sp

from hapticproof.audit.runner import audit_paper
from hapticproof.cli import main
from hapticproof.audit.paperfile import TEMPLATE, PaperFileError, loads, read_paper


@pytest.fixture(scope="module")
def template_file(tmp_path_factory):
    path = tmp_path_factory.mktemp("paper") / "mine.toml"
    path.write_text(TEMPLATE)
    return path


def test_template_reads_and_audits_cleanly():
    paper = loads(TEMPLATE, "new.toml")
    report = audit_paper(paper.paper)
    assert [r.verdict.value for r in report.results] == ["confirmed"] * 3
    assert paper.paper.ordered()[0].id == "1"                     # file order


def test_new_paper_writes_the_template(tmp_path, capsys):
    target = tmp_path / "mine.toml"
    assert main(["new-paper", str(target)]) == 0
    assert target.read_text() == TEMPLATE
    assert main(["new-paper", str(target)]) == 2                  # never overwrites silently
    err = capsys.readouterr().err
    assert "exists" in err and "Traceback" not in err
    assert main(["new-paper", str(target), "--force"]) == 0
    assert main(["new-paper", str(tmp_path / "mine.txt")]) == 2   # a .toml file
    capsys.readouterr()
    assert main(["new-paper", "-"]) == 0
    assert capsys.readouterr().out.startswith("# A paper file")


def _edit(old: str, new: str, count: int = 1) -> str:
    assert old in TEMPLATE, old
    return TEMPLATE.replace(old, new, count)


def _line(text: str, fragment: str) -> int:
    return next(k for k, line in enumerate(text.splitlines(), 1) if fragment in line)


ERRORS = [
    # (text, fragment of the offending line or None, expected words)
    (_edit('id = "1"', 'id = "1'), 'id = "1', ["TOML syntax"]),
    (_edit('claim = "passivity-condition"', 'claim = "passivity"'), 'claim = "passivity"',
     ["equation 3", "field 'claim'", "unknown claim 'passivity'", "did you mean 'passivity-condition'"]),
    (_edit("printed = 'b > \\frac{KT}{2} + B'", "printed = 'b > \\frac{KT}{2} + Q'"), "+ Q'",
     ["equation 3", "field 'printed'", "unknown name Q at position 19", "[symbols]"]),
    (_edit('scene = "wall"', 'scene = "wal"'), 'scene = "wal"',
     ["equation 1", "field 'scene'", "scene 'wal' does not exist", "scenes: wall"]),
    (_edit('section = "2"', 'sectoin = "2"'), 'sectoin', ["equation 1", "unknown field 'sectoin'", "did you mean 'section'"]),
    (_edit('K = "positive"', 'K = "postive"'), 'K = "postive"', ["symbols: K", "unknown word 'postive'", "'positive'"]),
    (_edit('approximation = "forward"', 'approximaton = "forward"'), "approximaton", ["unknown field 'approximaton'", "scene 'wall'"]),
    (TEMPLATE + '\n[[equations]]\nid = "4"\nprinted = "b > K"\nclaim = "same-as"\nother = "9"\n', 'other = "9"',
     ["equation 4", "field 'other'", "equation '9' does not exist"]),
    (TEMPLATE + '\n[[equations]]\nid = "4"\nprinted = "b > K"\nclaim = "same-as"\nother = "hve:999"\n', 'other = "hve:999"',
     ["equation 4", "field 'other'", "paper 'hve' has no equation '999'"]),
    (TEMPLATE + '\n[extra]\na = 1\n', "[extra]", ["unknown table 'extra'"]),
    (_edit('id = "2"', 'id = "1"'), None, ["equation '1' is listed twice"]),
    (TEMPLATE + '\n[scenes.w2]\nsystem = "single-user"\n[scenes.w2.params]\nQ = 3\n', "Q = 3",
     ["scene 'w2'", "unknown parameter 'Q'"]),
    (_edit('omega = "real"', "S = '\\frac{Q}{2}'"), "S = ", ["symbols: S", "definition does not read", "unknown name Q"]),
    (TEMPLATE + '\n[[equations]]\nid = "4"\nprinted = "b > K"\nclaim = "same-as"\nother = "3"\nunder = "K < 0"\n',
     'under = "K < 0"', ["equation 4", "field 'under'", "substitutions"]),
    (_edit('section = "2"', 'section = "2"\norder = "leading"'), 'order = "leading"',
     ["equation 1", "field 'order'", "stability-condition"]),
    (_edit('claim = "inverse-transfer"          # the display is G^-1(z) of the scene',
           'claim = "inverse-transfer"\nassumption = "B = 0"'), 'assumption = "B = 0"', ["field 'assumption'", "condition claims"]),
    (_edit('scene = "wall"', ''), None, ["equation 1", "missing field 'scene'"]),
    (_edit('z = "signal"', 'z = "signal"') if 'z = "signal"' in TEMPLATE else _edit('V_h = "signal"', 'z = "real"'), 'z = "real"',
     ["z and s are the transform variables"]),
]


@pytest.mark.parametrize("text, fragment, words", ERRORS, ids=[f"error{k}" for k in range(len(ERRORS))])
def test_mistakes_name_file_line_and_field(text, fragment, words, tmp_path, capsys):
    with pytest.raises(PaperFileError) as info:
        loads(text, "bad.toml")
    message = str(info.value)
    assert message.startswith("bad.toml")
    if fragment is not None:
        assert message.startswith(f"bad.toml:{_line(text, fragment)}:"), message
    for word in words:
        assert word in message, (word, message)
    assert "\n" not in message
    path = tmp_path / "bad.toml"
    path.write_text(text)
    assert main(["audit", "--paper", str(path)]) == 2
    err = capsys.readouterr().err.strip()
    assert err.startswith("hapticproof: error: ") and "\n" not in err and "Traceback" not in err


def test_unreadable_file_is_one_line(capsys):
    assert main(["audit", "--paper", "no/such/paper.toml"]) == 2
    assert "cannot read no/such/paper.toml" in capsys.readouterr().err


def test_symbols_words_families_definitions_and_signals():
    text = r'''
[paper]
id = "names"
title = "names"
[symbols]
b = "positive"
K = "positive"
T = "positive"
omega = "real"
phi = "real"
"K_{ij}" = "positive, symmetric"
"b_{i}" = "positive"
S = '\frac{\sin(\omega T)}{2}'
F_h = "signal"
V_h = "signal"
"G^{-1}" = "function"
[scenes.wall]
system = "single-user"
[[equations]]
id = "1"
printed = 'F_h(z) = G^{-1}(z)V_h(z)'
claim = "inverse-transfer"
scene = "wall"
'''
    paper = loads(text, "names.toml")
    table = paper.symbols
    assert table.lookup(r"\omega") == sp.Symbol("omega", real=True)
    assert table.lookup("K") == sp.Symbol("K", positive=True)
    assert table.lookup("S") == sp.sin(sp.Symbol("omega", real=True) * sp.Symbol("T", positive=True)) / 2
    assert table.concrete("K_{ij}", (2, 1)) == table.concrete("K_{ij}", (1, 2))
    assert paper.words["F_h"] == "signal" and paper.words["G^-1"] == "function"
    assert paper.signals() == {sp.Symbol("F_h"), sp.Symbol("V_h")}
    # the only members are a signal and an unknown function times a signal: nothing states G^-1
    (result,) = audit_paper(paper.paper).results
    assert result.verdict.value == "malformed"


def test_a_display_that_does_not_parse_is_malformed_not_an_error():
    text = _edit("printed = 'b > \\frac{KT}{2} + B'", "printed = 'b > \\frac{KT}{2 + B'")
    paper = loads(text, "ocr.toml")                         # the paper's damage, not the file's mistake
    result = audit_paper(paper.paper, ["3"]).results[0]
    assert result.verdict.value == "malformed"
    assert result.evidence.facts["position"] >= 0


def test_audit_paper_formats(template_file, capsys):
    assert main(["audit", "--paper", str(template_file), "--format", "json"]) == 0
    data = json.loads(capsys.readouterr().out)
    assert set(data) == {"paper", "title", "equations"} and data["paper"] == "my-paper"
    row = data["equations"][2]
    assert set(row) == {"id", "kind", "printed", "derived", "verdict", "detail", "corrected", "evidence", "seconds"}
    assert (row["id"], row["kind"], row["verdict"]) == ("3", "condition", "confirmed")
    assert row["evidence"]["method"] == "canonical-form"
    assert main(["audit", "--paper", str(template_file), "--format", "markdown", "-e", "2"]) == 0
    markdown = capsys.readouterr().out
    assert markdown.startswith("## my-paper") and "| 2 | condition | **confirmed**" in markdown
    assert main(["audit", "--paper", str(template_file), "--format", "html", "-s", "2"]) == 0
    html = capsys.readouterr().out
    assert html.lstrip().lower().startswith("<!doctype html") and 'id="eq-' in html
    assert main(["audit", "--paper", str(template_file), "--wide"]) == 0
    table = capsys.readouterr().out
    assert table.startswith("my-paper: A virtual wall, audited") and "3 equations (confirmed: 3)" in table


def test_audit_paper_latex_compiles(template_file, tmp_path, capsys):
    out = tmp_path / "audit.tex"
    assert main(["audit", "--paper", str(template_file), "--format", "tex", "-o", str(out)]) == 0
    text = out.read_text()
    assert text.startswith("\\documentclass") and "my-paper" in text
    if shutil.which("pdflatex"):
        done = subprocess.run(["pdflatex", "-interaction=nonstopmode", "-halt-on-error", out.name], cwd=tmp_path,
                              capture_output=True, text=True, timeout=120)
        assert done.returncode == 0, done.stdout[-2000:]


def test_several_papers_at_once(template_file, tmp_path, capsys):
    other = tmp_path / "other.toml"
    other.write_text(TEMPLATE.replace('id = "my-paper"', 'id = "other-paper"').replace('section = "2"', 'section = "4.1"'))
    assert main(["audit", "--paper", str(template_file), "--paper", str(other), "--format", "json", "-s", "4"]) == 0
    data = json.loads(capsys.readouterr().out)
    assert [p["paper"] for p in data["papers"]] == ["other-paper"]        # my-paper has no section 4
    assert main(["audit", "--paper", str(template_file), "--paper", str(other), "-e", "1"]) == 2
    assert "exactly one PAPER" in capsys.readouterr().err


def test_read_paper_resolves_examples():
    paper = read_paper("examples/hve-single-user.toml")
    assert paper.id == "hve-file" and "delayed" in paper.scenes
    assert paper.claim("26-extends").under == ((sp.Symbol("z_a", nonnegative=True), 0), (sp.Symbol("t_d", nonnegative=True), 0))
