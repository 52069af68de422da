"""The command line run in-process for the tests: its exit code, standard output and error."""

from __future__ import annotations

import json
from contextlib import redirect_stderr, redirect_stdout
from io import StringIO
from typing import Any

from hapticproof.cli import main


def run(capsys, *argv: str) -> tuple[int, str, str]:
    """``hapticproof ARGV...``: (exit code, stdout, stderr)."""
    code = main(list(argv))
    out = capsys.readouterr()
    return code, out.out, out.err


def one_line_error(capsys, *argv: str) -> str:
    """The one-line error of a refused command (exit code 2, no traceback)."""
    code, _, err = run(capsys, *argv)
    assert code == 2 and err.count("\n") == 1 and err.startswith("hapticproof: error: ") and "Traceback" not in err, err
    return err


def json_of(*argv: Any) -> Any:
    """The JSON a command writes to standard output (it must succeed), without capsys (for a
    module-scoped fixture): ``json_of("derive", "single-user", ..., "--format", "json")``."""
    buffer = StringIO()
    with redirect_stdout(buffer), redirect_stderr(StringIO()):
        assert main([str(a) for a in argv]) == 0
    return json.loads(buffer.getvalue())


def check_file(capsys, tmp_path, report: Any) -> tuple[int, str, str]:
    """``hapticproof check`` of ``report`` saved as JSON: (exit code, stdout, stderr)."""
    path = tmp_path / "r.json"
    path.write_text(json.dumps(report), encoding="utf-8")
    return run(capsys, "check", str(path))
