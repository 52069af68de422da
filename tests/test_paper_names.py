"""A paper whose names are the toolkit's own: a damping called ``c`` (the toolkit's ``c = cos wT``)
and a period ``h`` stated in the prose. The audit must neither crash nor confuse the two ``c``:
the paper's ``c`` stays ``c`` in every answer, the circle's becomes ``gamma``, a witness keys the
circle by the paper's names (``gamma``, ``omega*h``) and ``check`` reads them so."""

from __future__ import annotations

import json
import re
import subprocess
import sys
from pathlib import Path

import pytest

PAPER = r"""\documentclass{article}
\title{A damped wall}
\begin{document}
The device has physical damping $b>0$ and is sampled with period $h$. The virtual wall is
\begin{equation}
H(z) = k + c\,\frac{z-1}{h z}.
\end{equation}
The system is passive if and only if
\begin{equation}
b > \frac{k h}{2} + c .
\end{equation}
\end{document}
"""


def _run(*args: str, cwd: Path) -> subprocess.CompletedProcess:
    return subprocess.run([sys.executable, "-m", "hapticproof", *args], cwd=cwd, capture_output=True, text=True,
                          timeout=300)


@pytest.fixture(scope="module")
def audited(tmp_path_factory) -> tuple[Path, str, dict]:
    folder = tmp_path_factory.mktemp("cpaper")
    (folder / "p.tex").write_text(PAPER)
    drafted = _run("new-paper", "d.toml", "--from", "p.tex", cwd=folder)
    assert drafted.returncode == 0, drafted.stderr
    run = _run("audit", "--paper", "d.toml", "--format", "json", "-o", "a.json", cwd=folder)
    assert run.returncode == 0, run.stderr
    return folder, (folder / "d.toml").read_text(), json.loads((folder / "a.json").read_text())


def test_the_draft_takes_the_period_the_prose_names(audited):
    _, draft, _ = audited
    assert 'roles = { period = "h" }' in draft


def test_the_papers_c_stays_c_and_the_bound_is_in_its_period(audited):
    _, _, report = audited
    entry = next(e for e in report["equations"] if e["printed"].startswith("b >"))
    # c of unknown sign: Colgate's bound is b >= kh/2 + |c|, so "b > kh/2 + c" is weaker
    assert entry["verdict"] == "wrong"
    assert "b > c + h*k/2" in entry["detail"] and "h*k/2 + Abs(c)" in entry["detail"]
    assert not re.search(r"\b(gamma|T)\b", entry["detail"]), entry["detail"]
    witness = entry["evidence"]["witness"]
    assert set(witness) == {"b", "c", "h", "k"}
    b, c, h, k = (float(eval_fraction(witness[n])) for n in ("b", "c", "h", "k"))
    assert b > k * h / 2 + c and not b >= k * h / 2 + abs(c)          # the witness separates the two


def eval_fraction(text: str) -> float:
    num, _, den = text.partition("/")
    return int(num) / int(den or 1)


def test_the_audit_names_the_circle_gamma_and_check_reads_it(audited):
    folder, _, report = audited
    assert report["names"]["cos"] == "gamma" and report["names"]["period"] == "h"
    keys = {k for e in report["equations"] for k in _witness_keys(e)}
    assert "omega_T" not in keys
    run = _run("check", "a.json", cwd=folder)
    assert "display(s) refused" in run.stdout and " 0 display(s) refused" in run.stdout, run.stdout


def _witness_keys(node):
    if isinstance(node, dict):
        for key, value in node.items():
            if key in ("judge", "certificate", "definition"):
                continue
            if key == "witness" and isinstance(value, dict):
                yield from value
            yield from _witness_keys(value)
    elif isinstance(node, list):
        for value in node:
            yield from _witness_keys(value)


def test_a_derived_witness_is_keyed_by_the_scenes_names_and_a_forged_one_is_refused(tmp_path):
    run = _run("derive", "single-user", "--role", "period=h", "--role", "device_damping=c_d", "--environment",
               "k + c*(z-1)/(h*z)", "--param", "k=2", "--param", "c=-1", "--param", "h=1/100", "--param", "c_d=1/10",
               "--format", "json", "-o", "d.json", cwd=tmp_path)
    assert run.returncode == 0, run.stderr
    report = json.loads((tmp_path / "d.json").read_text())
    assert set(report["witness"]) == {"gamma", "z", "omega*h"}
    assert report["witness"]["gamma"] == report["witness"]["z"][0]
    assert "accepted" in _run("check", "d.json", cwd=tmp_path).stdout.splitlines()[-1]
    for key, forged in (("gamma", "4/5"), ("omega*h", "2*atan(1/3)")):
        data = json.loads((tmp_path / "d.json").read_text())
        data["witness"][key] = forged
        (tmp_path / "f.json").write_text(json.dumps(data))
        out = _run("check", "f.json", cwd=tmp_path)
        assert out.returncode != 0 and f"the displayed {key} = {forged}" in out.stdout, out.stdout


PAPER_FILE = r"""
[paper]
id = 'damped'
title = 'Damped walls'

[symbols]
k = 'nonnegative'
c = 'nonnegative'
h = 'positive'
c_d = 'positive'

[scenes.wall]
system = "single-user"
approximation = "forward"
environment = 'k + c*(z - 1)/(h*z)'
roles = { period = "h", device_damping = "c_d" }

[[equations]]
id = '2'
printed = '\Re\, G^{-1}(e^{j\omega h}) = c_d - \frac{kh}{2} + c\cos(\omega h).'
claim = 'hermitian-part'
scene = 'wall'

[[equations]]
id = '2b'
printed = '\Re\, G^{-1}(e^{j\omega h}) = c_d - \frac{kh}{2} - c\cos(\omega h).'
claim = 'hermitian-part'
scene = 'wall'

[[equations]]
id = '3'
printed = 'c_d > \frac{kh}{2} + c .'
claim = 'passivity-condition'
scene = 'wall'
"""


def test_a_damping_called_c_is_the_judges_c_too(tmp_path):
    """The judge's sample scenes take the paper's c at its sampled values (not 1, the value of a
    parameter left out): the right Re G^-1 is confirmed, its sign slip a typo."""
    from hapticproof.audit.paperfile import loads
    from hapticproof.audit.runner import audit_paper

    report = audit_paper(loads(PAPER_FILE, "damped.toml").paper)
    verdicts = {r.id: r.verdict.value for r in report.results}
    assert verdicts == {"2": "confirmed", "2b": "typo", "3": "confirmed"}, [(r.id, r.detail[:200]) for r in report.results]
    judge = report.results[0].evidence.facts["judge"]
    values = [point["values"]["c"] for point in judge["points"]]
    assert len(set(values)) > 1


OWN_NAMES_PAPER = r"""\documentclass{article}
\begin{document}
\title{Damped walls}
\section{Model}
A haptic device with physical damping $c_d > 0$ is sampled with period $h$.
It renders a virtual wall with stiffness $k \ge 0$ and virtual damping $c \ge 0$,
\begin{equation}
H(z) = k + c\,\frac{z-1}{hz}.
\end{equation}
\section{Passivity}
The real part of the inverse transfer function on the unit circle is
\begin{equation}
\Re\, G^{-1}(e^{j\omega h}) = c_d - \frac{kh}{2} + c\cos(\omega h).
\end{equation}
The device is passive if and only if
\begin{equation}
c_d > \frac{kh}{2} + c .
\end{equation}
The device is passive if and only if
\begin{equation}
c_d > kh + c .
\end{equation}
The device is passive if and only if
\begin{equation}
c_d > \frac{kh}{2} - c\cos(\omega h) \quad \forall \omega .
\end{equation}
\end{document}
"""


def test_a_wall_paper_in_its_own_names_is_drafted_and_audited_unedited(tmp_path):
    """The device damping c_d named by the prose, the period h, a frequency-wise condition with
    \\forall: the draft gives the wall its roles and every display a claim; the audit confirms the
    four right displays and repairs the lost half."""
    (tmp_path / "p.tex").write_text(OWN_NAMES_PAPER)
    assert _run("new-paper", "d.toml", "--from", "p.tex", cwd=tmp_path).returncode == 0
    draft = (tmp_path / "d.toml").read_text()
    assert 'roles = { device_damping = "c_d", period = "h" }' in draft and "# [[equations]]" not in draft
    run = _run("audit", "--paper", "d.toml", "--format", "json", "-o", "a.json", cwd=tmp_path)
    assert run.returncode == 0, run.stderr
    verdicts = {e["id"]: e["verdict"] for e in json.loads((tmp_path / "a.json").read_text())["equations"]}
    assert verdicts == {"1": "confirmed", "2": "confirmed", "3": "confirmed", "4": "typo", "5": "confirmed"}, verdicts


def test_a_new_users_msd_paper_is_audited_unedited(tmp_path):
    """A helper's own paper (period Delta, damping beta, a mass-spring-damper environment; 10
    correct displays, 4 planted mistakes, answer key written by hand): G^{-1}, written bare inline
    ("F = G^{-1} V") before it is applied, is a function; Res_{z=1} is evaluated; unedited, every
    correct display that is checked is confirmed and every mistake that is checked is caught."""
    source = Path(__file__).parent / "data" / "msd_paper.tex"
    (tmp_path / "paper.tex").write_text(source.read_text())
    assert _run("new-paper", "d.toml", "--from", "paper.tex", cwd=tmp_path).returncode == 0
    assert '"G^{-1}" = \'function\'' in (tmp_path / "d.toml").read_text()
    run = _run("audit", "--paper", "d.toml", "--format", "json", "-o", "a.json", cwd=tmp_path)
    assert run.returncode == 0, run.stderr
    verdicts = {e["id"]: e["verdict"] for e in json.loads((tmp_path / "a.json").read_text())["equations"]}
    assert all(verdicts[i] == "confirmed" for i in ("1", "3", "4", "5", "6", "7", "8", "9")), verdicts
    assert verdicts["10"] == verdicts["14"] == "typo" and verdicts["11"] == "conservative", verdicts
    assert verdicts["12"] not in ("wrong", "typo", "inconsistent"), verdicts         # correct: never flagged
