"""The command line run in-process for the tests: its exit code, standard output and error."""

from __future__ import annotations

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
