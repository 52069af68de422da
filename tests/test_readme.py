"""The README's two set-up commands, and .ci/run calling exactly the README's test command."""

import re
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]


def readme_commands():
    return re.findall(r"```\n(python3 -m venv[^\n]*)\n```", (ROOT / "README.md").read_text())


def test_readme_has_two_setup_commands():
    commands = readme_commands()
    assert len(commands) == 2
    assert commands[0].endswith("hapticproof audit")
    assert commands[1].endswith("python -m pytest")


def test_ci_runs_the_readme_test_command():
    ci = (ROOT / ".ci" / "run").read_text().splitlines()
    assert readme_commands()[1] in ci


def test_pytest_runs_doctests_and_notebooks():
    config = (ROOT / "pyproject.toml").read_text()
    assert "--doctest-modules" in config and "--nbval" in config
    assert '"notebooks"' in config
