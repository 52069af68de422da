"""The documentation site (issue 29): it builds offline with warnings as errors, the commands its
tutorial shows run and print what it shows, every command anywhere in it parses, and the README is the
short page that points to it. (Its ``>>>`` examples run as doctests: ``--doctest-glob=*.rst``.)"""

from __future__ import annotations

import os
import re
import shlex
import shutil
import subprocess
import sys
from pathlib import Path

import pytest

sys.path.insert(0, str(Path(__file__).resolve().parent))

from clirun import run  # noqa: E402

ROOT = Path(__file__).resolve().parents[1]
DOCS = ROOT / "docs"

#: Commands of those pages that take minutes (a mutation run of a whole bundled paper): parsed only.
SLOW = ("hve --mutate --sample 200", "--all --mutate")
#: Pages whose commands the test runs (the others' commands are parsed only: big maps, a paper's CI).
RUN = ["tutorial/wall.rst", "tutorial/paper.rst", "howto/roles.rst", "howto/zwidth.rst", "howto/mutation.rst",
       "reference/scenes.rst"]


@pytest.fixture(scope="module")
def site(tmp_path_factory):
    """The site built as a user builds it, with every network fetch made to fail (a closed proxy):
    a warning, an intersphinx fetch included, fails the build."""
    out = tmp_path_factory.mktemp("site")
    env = dict(os.environ, http_proxy="http://127.0.0.1:9", https_proxy="http://127.0.0.1:9",
               HTTP_PROXY="http://127.0.0.1:9", HTTPS_PROXY="http://127.0.0.1:9")
    done = subprocess.run([sys.executable, "-m", "sphinx", "-W", "--keep-going", "-q", "-b", "html", str(DOCS),
                           str(out)], capture_output=True, text=True, env=env, timeout=600)
    assert done.returncode == 0, done.stderr[-4000:]
    assert done.stderr.strip() == ""
    return out


def test_the_site_builds_clean_and_offline(site):
    for page in ("index", "tutorial/wall", "tutorial/paper", "howto/ci", "howto/zwidth", "reference/cli",
                 "reference/api", "theory"):
        assert (site / f"{page}.html").is_file(), page
    assert (site / "_images" / "zwidth.png").is_file() and (site / "_images" / "zwidth-tustin.png").is_file()
    import runpy

    extensions = runpy.run_path(str(DOCS / "conf.py"))["extensions"]
    assert not [e for e in extensions if "intersphinx" in e]


def test_the_reference_is_generated_from_the_program(site):
    from hapticproof.cli import COMMANDS

    cli = (site / "reference" / "cli.html").read_text()
    for command in COMMANDS:
        assert f"usage: hapticproof {command}" in cli, command
    assert "--fail-on VERDICTS" in cli and "--stiffness NAME=start:stop:count" in cli
    api = (site / "reference" / "api.html").read_text()
    for name in ("analysis.positivereal.positive_real", "analysis.passiverange.passive_range",
                 "analysis.passivity.ispassive", "audit.runner.audit_paper", "analysis.zwidth.zwidth"):
        assert f'id="hapticproof.{name}"' in api, name


def _console_blocks(text: str) -> list[list[str]]:
    """The lines of every ``.. code-block:: console`` of an rst page (indentation removed)."""
    blocks, lines = [], text.splitlines()
    k = 0
    while k < len(lines):
        if lines[k].strip() == ".. code-block:: console":
            k += 1
            block = []
            while k < len(lines) and (not lines[k].strip() or lines[k].startswith("   ")):
                block.append(lines[k][3:])
                k += 1
            blocks.append([line for line in block if line.strip()])
            continue
        k += 1
    return blocks


def _commands(page: str) -> list[tuple[str, list[str]]]:
    """``(command, expected output lines)`` of a page's console blocks."""
    out: list[tuple[str, list[str]]] = []
    for block in _console_blocks((DOCS / page).read_text()):
        for line in block:
            if line.startswith("$ "):
                out.append((line[2:], []))
            elif out:
                out[-1][1].append(line)
    return out


def _words(command: str) -> tuple[dict[str, str], list[str]]:
    words = shlex.split(command, comments=True)
    env = {}
    while words and re.fullmatch(r"[A-Za-z_]+=\S*", words[0]):
        name, _, value = words.pop(0).partition("=")
        env[name] = value
    return env, words


def _normal(text: str) -> str:
    return re.sub(r"\s+", " ", text).strip()


def test_every_command_of_the_site_parses(monkeypatch):
    from hapticproof.cli import build_parser
    from hapticproof.cli.derive import complete_argv

    monkeypatch.chdir(ROOT)                              # examples/... as the pages name them
    seen = 0
    for page in sorted(DOCS.rglob("*.rst")):
        for command, _ in _commands(str(page.relative_to(DOCS))):
            _, words = _words(command)
            if not words or words[0] != "hapticproof":
                continue
            argv = complete_argv(words[1:]) if "--scene" in words else words[1:]    # the scene file's system
            build_parser(argv[0], argv[1] if len(argv) > 1 else None).parse_args(argv)
            seen += 1
    assert seen > 40


@pytest.mark.parametrize("page", RUN)
def test_the_commands_print_what_the_page_shows(page, tmp_path, monkeypatch, capsys):
    shutil.copytree(ROOT / "examples", tmp_path / "examples")
    shutil.copy(ROOT / "examples" / "walls.toml", tmp_path / "walls.toml")      # "save this as walls.toml"
    monkeypatch.chdir(tmp_path)
    ran = 0
    for command, expected in _commands(page):
        env, words = _words(command)
        if words[:1] == ["pdflatex"] and shutil.which("pdflatex"):
            done = subprocess.run(words + ["-interaction=nonstopmode", "-halt-on-error"], capture_output=True, text=True,
                                  env=dict(os.environ, **env), timeout=300)
            assert done.returncode == 0, (command, done.stdout[-2000:])
            continue
        if words[:1] != ["hapticproof"] or any(slow in command for slow in SLOW):
            continue                                     # pip, python: the reader's set-up; minutes of mutants
        code, out, err = run(capsys, *words[1:])
        refused = any("NOT accepted" in line for line in expected)         # check shows a report it does not accept
        assert code == (1 if refused else 0), (command, err)
        printed = _normal(out + "\n" + err)
        for line in expected:
            if line.strip() == "...":
                continue
            shown = _normal(line.rstrip(". ") if line.rstrip().endswith("...") else line)
            assert shown in printed, (command, line)
        ran += 1
    assert ran >= 1


# ---------------------------------------------------------------------------------------------
# the README: what the project is, the set-up, a tour and the links (the rest moved to the site)
# ---------------------------------------------------------------------------------------------

README = (ROOT / "README.md").read_text()


def test_the_readme_is_short_and_points_to_the_site():
    assert len(README.splitlines()) <= 250
    assert "docs/" in README and "sphinx" in README.lower()


def test_the_readme_names_every_debian_package_a_report_needs():
    for package in ("texlive-latex-base", "texlive-latex-recommended", "texlive-fonts-recommended", "lmodern",
                    "poppler-utils", "chromium"):
        assert package in README, package
    ci = (ROOT / ".ci" / "run").read_text()
    assert "texlive-fonts-recommended" in ci           # rsfs: export hve prints \mathscr
