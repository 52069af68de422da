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


def python_blocks():
    return re.findall(r"```python\n(.*?)```", (ROOT / "README.md").read_text(), re.S)


def test_readme_python_examples_run_and_say_what_their_comments_say(tmp_path, monkeypatch):
    """Every ```python block runs from the checkout; an expression line whose comment is a value
    (``# proved``, ``# 110/3``, ``# b >= B + K*T/2``) is checked against what it gives."""
    import shutil

    blocks = python_blocks()
    assert len(blocks) >= 2
    shutil.copytree(ROOT / "examples", tmp_path / "examples")
    monkeypatch.chdir(tmp_path)
    checked = 0
    for block in blocks:
        namespace: dict = {}
        for line in block.splitlines():
            code, _, comment = line.partition("#")
            expected = re.split(r"\s{2,}|\s\(", comment.strip())[0] if comment.strip() else ""
            if code.strip() and not code.startswith((" ", "from", "import")) and "=" not in code.split("(")[0] \
                    and re.fullmatch(r"[\w*/+\-<>=. ]+", expected):
                value = eval(code, namespace)                     # noqa: S307 - the README's own code
                text = getattr(value, "value", value)
                assert str(text) == expected, (code, text, expected)
                checked += 1
            else:
                exec(code, namespace)                             # noqa: S102 - the README's own code
    assert checked >= 4
