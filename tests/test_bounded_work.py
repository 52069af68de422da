"""Issue 30, work: bounded by the size of what is asked, not only by the size of the text, and
every mistake one line.

* parameters defined from each other (``K_i = K_{i-1}^10``, 34 squarings) stayed within the
  digit and exponent limits line by line and built 4.4 GB before a traceback;
* ``new-paper`` was quadratic in the number of displays, and two regular expressions back-tracked
  on long runs of spaces (40 KB: 76 s);
* ``audit --mutate`` on one long display used 23 GB;
* ``\\newcommand\\a[²]`` and ``\\setcounter{equation}{²}`` in ``new-paper``, malformed
  ``--scheduler`` addresses (a non-Dask TCP service: "Unable to allocate 8.00 EiB") and
  ``--limit depth=1000000`` with deep nesting were tracebacks;
* ``new-paper`` copied control characters into TOML comments: the draft did not load.

Work is measured here by what the code does (function calls counted by a profiler hook), never by
the clock; the run time of hostile inputs is bounded in ``test_fuzz_inputs.py``.
"""

from __future__ import annotations

import json
import socket
import sys
import threading
from pathlib import Path

import pytest

from hapticproof.cli import main


def _one_line(capsys, argv, *expected):
    status = main([str(a) for a in argv])
    err = capsys.readouterr().err
    assert status == 2 and err.count("\n") == 1 and "Traceback" not in err and err.startswith("hapticproof: error: "), err
    for text in expected:
        assert text in err, err
    return err


def _scene(folder: Path, name: str, k0: str, step: str, count: int) -> Path:
    lines = ['system = "single-user"', f'environment = "K_{count} + B*(z - 1)/(T*z)"', "[params]",
             f"K_0 = {k0}", "B = 1", "T = 0.001", "b = 1"]
    lines += [f'K_{i} = "K_{i - 1}**{step}"' for i in range(1, count + 1)]
    path = folder / name
    path.write_text("\n".join(lines) + "\n", encoding="utf-8")
    return path


@pytest.mark.parametrize("k0, step, count, expected", [
    ("10", "10", 8, "about 1001 digits"),                 # 10^(10^8)
    ("3", "2", 34, "digits"),                              # 34 squarings of 3
    ('"positive"', "10", 8, "power 10000"),               # K_0^(10^8)
])
def test_chained_definitions_are_bounded_after_substitution(tmp_path, capsys, k0, step, count, expected):
    _one_line(capsys, ["derive", "--scene", _scene(tmp_path, "s.toml", k0, step, count)], expected)


def test_chained_definitions_within_the_limits_are_substituted(tmp_path, capsys):
    assert main(["derive", "--scene", str(_scene(tmp_path, "s.toml", "2", "2", 3)), "--format", "json"]) == 0
    chained = json.loads(capsys.readouterr().out)
    assert main(["derive", "single-user", "--environment", "K + B*(z - 1)/(T*z)", "--param", "K=256", "--param", "B=1",
                 "--param", "T=0.001", "--param", "b=1", "--format", "json"]) == 0
    assert chained["G_inverse"] == json.loads(capsys.readouterr().out)["G_inverse"]    # K_3 = 2^8 = 256 reached the model


def _calls(argv) -> int:
    """Python function calls made while ``argv`` runs (deterministic: a count, not a time)."""
    count = [0]

    def hook(frame, event, arg):
        if event == "call":
            count[0] += 1

    sys.setprofile(hook)
    try:
        status = main([str(a) for a in argv])
    finally:
        sys.setprofile(None)
    assert status == 0
    return count[0]


def test_new_paper_is_linear_in_the_number_of_displays(tmp_path, capsys):
    counts = []
    for n in (40, 160):
        source = tmp_path / f"many{n}.md"
        source.write_text("\n".join(f"$$b > {k}$$" for k in range(n)) + "\n", encoding="utf-8")
        counts.append(_calls(["new-paper", tmp_path / f"many{n}.toml", "--from", source]))
        capsys.readouterr()
    assert counts[1] < 5 * counts[0], counts          # 4 times the displays: about 4 times the work (16 if quadratic)


@pytest.mark.parametrize("source, name", [
    ("Title\n\n$$b >" + " " * 40000 + "1$$\n\n$$b > 1" + " " * 40000 + "(3)$$\n", "s.md"),
    ("\\begin{equation} b >" + " " * 40000 + "1 \\label{" + " " * 40000 + "} \\end{equation}\n", "s.tex"),
    ("We have $$b > 1 \\quad" + " " * 40000 + "x$$ where $a$," + " " * 40000 + "and" + " " * 40000 + "x\n", "s.txt"),
])
def test_long_runs_of_spaces_do_not_make_new_paper_backtrack(tmp_path, capsys, source, name):
    """The displays' trailing numbers are found by string operations (no back-tracking regular
    expression). The run time of these inputs is bounded in the fuzz test; here, the answer."""
    from hapticproof.audit.source.displays import trailing_number

    (tmp_path / name).write_text(source, encoding="utf-8")
    assert main(["new-paper", str(tmp_path / "p.toml"), "--from", str(tmp_path / name)]) == 0
    capsys.readouterr()
    assert trailing_number("b > 1" + " " * 40000 + "(3)") == (5, "3")
    assert trailing_number("b > 1" + " " * 40000 + "x") is None
    assert trailing_number(r"b > 0 \quad (12).") == (5, "12") and trailing_number("f(1)") is None


def test_mutating_a_long_display_is_refused_before_any_mutant_is_built(tmp_path, capsys):
    assert main(["new-paper", str(tmp_path / "t.toml")]) == 0
    capsys.readouterr()
    text = (tmp_path / "t.toml").read_text(encoding="utf-8")
    long = " + ".join("K T" for _ in range(4000))
    text = text.replace(r"printed = 'b > \frac{KT}{2} + B'", rf"printed = 'b > \frac{{KT}}{{2}} + B + {long}'")
    (tmp_path / "long.toml").write_text(text, encoding="utf-8")
    _one_line(capsys, ["audit", "--paper", tmp_path / "long.toml", "--mutate", "-e", "3"], "mutants of a", "exceed")
    assert main(["audit", "--paper", str(tmp_path / "long.toml"), "-e", "3"]) == 0      # the audit itself still runs
    capsys.readouterr()


@pytest.mark.parametrize("source, expected", [
    ("\\newcommand\\a[\u00b2]{x}\n\\begin{equation} b > \\frac{KT}{2} \\end{equation}\n", "is not a parameter count"),
    ("\\setcounter{equation}{\u00b2}\n\\begin{equation} b > \\frac{KT}{2} \\end{equation}\n", None),
    ("\\newenvironment{e}[\u00b2]{x}{y}\n\\begin{equation} b > \\frac{KT}{2} \\end{equation}\n", None),
])
def test_non_ascii_digits_in_the_source_are_one_line_or_ignored(tmp_path, capsys, source, expected):
    (tmp_path / "a.tex").write_text(source, encoding="utf-8")
    argv = ["new-paper", tmp_path / "p.toml", "--from", tmp_path / "a.tex"]
    if expected:
        _one_line(capsys, argv, expected)
    else:
        assert main([str(a) for a in argv]) == 0
        assert "Traceback" not in capsys.readouterr().err


def test_control_characters_in_the_source_keep_the_draft_loadable(tmp_path, capsys):
    (tmp_path / "f.tex").write_text("\\newcommand\\X{b}\n\\begin{equation} \\X > \\frac{KT}{2} \x01\x1b + B \\end{equation}\n"
                                    "\\begin{equation} \\X \x7f \\oint q \\end{equation}\n", encoding="utf-8")
    assert main(["new-paper", str(tmp_path / "p.toml"), "--from", str(tmp_path / "f.tex")]) == 0
    text = (tmp_path / "p.toml").read_text(encoding="utf-8")
    assert not any(ord(ch) < 32 and ch not in "\n" or ord(ch) == 127 for ch in text)
    assert "\\x01" in text                                   # shown, as an escape
    capsys.readouterr()
    assert main(["audit", "--paper", str(tmp_path / "p.toml")]) == 0
    capsys.readouterr()


@pytest.mark.parametrize("address", ["tcp://", "tcp://:", "tcp://host:99999", "tcp://[::1", "tcp://a b:1", "inproc://",
                                     "ucx://x", "tcp://h:8786/x", "tcp://h:8786x", "tcp://-h:1"])
def test_malformed_scheduler_addresses_are_one_line_before_any_work(capsys, address):
    _one_line(capsys, ["map", "passivity", "--x", "b=0.001,0.002", "--y", "K=3", "--param", "T=0.001", "--param", "B=0",
                       "--scheduler", address], "tcp://HOST:PORT")


def test_a_service_that_is_not_dask_is_one_line(capsys):
    """An SSH-like banner read as Dask's frame length asked for 8 EiB."""
    pytest.importorskip("distributed")
    server = socket.socket()
    server.bind(("127.0.0.1", 0))
    server.listen(4)
    port = server.getsockname()[1]

    def serve():
        for _ in range(2):
            try:
                conn, _ = server.accept()
            except OSError:
                return
            conn.sendall(b"SSH-2.0-OpenSSH_9.6\r\n")
            conn.close()

    thread = threading.Thread(target=serve, daemon=True)
    thread.start()
    try:
        _one_line(capsys, ["map", "passivity", "--x", "b=0.001,0.002", "--y", "K=3", "--param", "T=0.001",
                           "--param", "B=0", "--scheduler", f"tcp://127.0.0.1:{port}"], "does not speak Dask's protocol")
    finally:
        server.close()


def test_nesting_beyond_what_python_recurses_through_is_one_line(capsys):
    from hapticproof.core import limits

    nested = "(" * 20000 + "K" + ")" * 20000
    try:
        _one_line(capsys, ["--limit", "depth=1000000", "derive", "single-user", "--environment", nested], "nested too deeply")
    finally:
        limits.set_limits(limits.DEFAULT)              # (--limit holds for the process that ran the command)
