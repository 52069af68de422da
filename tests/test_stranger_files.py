"""Issue 22: a file from a stranger is safe. Every numbered case of the issue, through the
command line: one clear line on standard error and a non-zero exit (or, for item 6, the right
answer), no traceback, no file read outside the file's folder, no output lost or half written.

Items 1 and 3 (script in the HTML, TeX escaping the allow-list) are in ``test_report_safety.py``
(the whole report in Chromium and pdflatex), ``test_sanitize.py`` and ``test_texsafe.py``.
"""

from __future__ import annotations

import json
import os
import signal
import subprocess
import sys
import time
from pathlib import Path

import pytest

from hapticproof.cli import main
from hapticproof.core import limits

WALL = 'system = "single-user"\nenvironment = "K + B*(z - 1)/(T*z)"\n'

PAPER = """[paper]
id = "p"
title = "P"
[symbols]
b = "positive"
K = "positive"
B = "real"
T = "positive"
{scenes}
[[equations]]
id = "1"
printed = '{printed}'
claim = "{claim}"
{extra}
"""

WALL_SCENE = '[scenes.wall]\nsystem = "single-user"\n'


def paper(folder: Path, name: str = "p.toml", *, scenes: str = WALL_SCENE, printed: str = r"b > \frac{KT}{2} + B",
          claim: str = "passivity-condition", extra: str = 'scene = "wall"') -> Path:
    path = folder / name
    path.write_text(PAPER.format(scenes=scenes, printed=printed, claim=claim, extra=extra), encoding="utf-8")
    return path


def refused(capsys, argv: list[str], *expected: str, code: int = 2) -> str:
    """Run the CLI: exit ``code`` and one line on standard error containing ``expected``."""
    status = main([str(a) for a in argv])
    err = capsys.readouterr().err.strip()
    assert status == code, err
    assert "Traceback" not in err and len(err.splitlines()) == 1, err
    assert err.startswith("hapticproof:"), err
    for text in expected:
        assert text in err, err
    return err


# ---------------------------------------------------------------------------------------------
# 2. files named in scene and paper files
# ---------------------------------------------------------------------------------------------

@pytest.mark.parametrize("name, why", [
    ("/proc/self/environ", "absolute path"), ("/etc/shadow", "absolute path"), ("../../x", "leaves the folder"),
    ("/dev/zero", "absolute path"), ("/dev/stdin", "absolute path"), ("~/secret", "absolute path"),
])
def test_matrix_file_outside_the_folder_is_refused(tmp_path, capsys, name, why):
    scene = tmp_path / "sub" / "s.toml"
    scene.parent.mkdir()
    scene.write_text(f'system = "network"\nmatrix = "{name}"\n', encoding="utf-8")
    refused(capsys, ["derive", "--scene", scene], "s.toml:2", "field 'matrix'", why)


def test_matrix_file_through_a_link_or_a_device_is_refused(tmp_path, capsys):
    (tmp_path / "zero").symlink_to("/dev/zero")
    os.mkfifo(tmp_path / "fifo")
    (tmp_path / "folder").mkdir()
    for name, why in (("zero", "symbolic link"), ("fifo", "not a regular file"), ("folder", "directory")):
        scene = tmp_path / f"s_{name}.toml"
        scene.write_text(f'system = "network"\nmatrix = "{name}"\n', encoding="utf-8")
        refused(capsys, ["derive", "--scene", scene], why)        # no 9.5 GB, no blocking read


def test_matrix_file_in_a_paper_scene_is_refused(tmp_path, capsys):
    scenes = '[scenes.net]\nsystem = "network"\nmatrix = "/proc/self/environ"\n'
    refused(capsys, ["audit", "--paper", paper(tmp_path, scenes=scenes, extra='scene = "net"')],
            "p.toml:", "absolute path", "scene 'net'")


def test_the_content_of_a_matrix_file_is_never_shown(tmp_path, capsys):
    (tmp_path / "m.txt").write_text("s, 1\n1, SECRET_TOKEN=hunter2\n", encoding="utf-8")
    (tmp_path / "s.toml").write_text('system = "network"\nmatrix = "m.txt"\n', encoding="utf-8")
    err = refused(capsys, ["derive", "--scene", tmp_path / "s.toml"], "m.txt:2, entry 2")
    assert "SECRET" not in err and "hunter2" not in err


def test_a_matrix_file_in_the_folder_is_read(tmp_path, capsys):
    (tmp_path / "m.txt").write_text("2 + s, 1\n1, 2 + s\n", encoding="utf-8")
    (tmp_path / "s.toml").write_text('system = "network"\nmatrix = "m.txt"\n', encoding="utf-8")
    assert main(["derive", "--scene", str(tmp_path / "s.toml")]) == 0
    assert "Traceback" not in capsys.readouterr().err


# ---------------------------------------------------------------------------------------------
# 3. TeX through a saved audit (export --from-audit)
# ---------------------------------------------------------------------------------------------

def test_export_from_a_hostile_saved_audit_typesets_no_caret_code(tmp_path, capsys):
    hostile = r"b > \frac{KT}{2} ^^5cinput{/etc/hostname} ^^5cimmediate^^5copenout5 pwned.tex"
    saved = {"paper": "hve", "title": "HVE", "equations": [
        {"id": "20", "kind": "condition", "printed": hostile, "derived": hostile, "verdict": "typo",
         "detail": "x", "corrected": hostile, "evidence": {"method": "canonical-form"}, "seconds": 0.0}]}
    (tmp_path / "a.json").write_text(json.dumps(saved), encoding="utf-8")
    assert main(["export", "hve", "--from-audit", str(tmp_path / "a.json"), "-o", str(tmp_path / "e.tex")]) == 0
    source = (tmp_path / "e.tex").read_text(encoding="utf-8")
    assert "^^" not in source and "\\input" not in source and "\\openout" not in source
    capsys.readouterr()


# ---------------------------------------------------------------------------------------------
# 4. outputs: checked before the work, written whole, never an input
# ---------------------------------------------------------------------------------------------

def test_output_in_a_missing_folder_is_refused_and_no_folder_is_created(tmp_path, capsys):
    target = tmp_path / "nonexistent" / "dir" / "r.html"
    refused(capsys, ["audit", "--paper", paper(tmp_path), "--format", "html", "-o", target], "does not exist")
    assert not (tmp_path / "nonexistent").exists()


@pytest.mark.parametrize("case", ["parent-is-a-file", "directory", "read-only"])
def test_bad_output_is_refused_before_any_work(tmp_path, capsys, monkeypatch, case):
    import hapticproof.audit.pool as pool

    monkeypatch.setattr(pool, "audit_reports", lambda *a, **k: pytest.fail("the audit ran before the output was checked"))
    (tmp_path / "afile").write_text("x", encoding="utf-8")
    (tmp_path / "adir").mkdir()
    (tmp_path / "ro.html").write_text("old", encoding="utf-8")
    (tmp_path / "ro.html").chmod(0o444)
    target, why = {"parent-is-a-file": ("afile/r.html", "not a directory"), "directory": ("adir", "is a directory"),
                   "read-only": ("ro.html", "read-only")}[case]
    refused(capsys, ["audit", "--paper", paper(tmp_path), "-o", tmp_path / target], why)
    assert (tmp_path / "ro.html").read_text(encoding="utf-8") == "old"


def test_an_output_that_is_an_input_is_refused(tmp_path, capsys):
    source = paper(tmp_path)
    before = source.read_text(encoding="utf-8")
    refused(capsys, ["audit", "--paper", source, "-o", source], "is an input")
    scene = tmp_path / "s.toml"
    scene.write_text(WALL, encoding="utf-8")
    refused(capsys, ["derive", "--scene", scene, "-o", scene], "is an input")
    assert source.read_text(encoding="utf-8") == before and scene.read_text(encoding="utf-8") == WALL


@pytest.mark.skipif(not os.path.exists("/dev/full"), reason="no /dev/full")
def test_a_device_as_output_is_one_line(tmp_path, capsys):
    """A device is no output file (issue 30): refused before the work, and never replaced."""
    refused(capsys, ["derive", "single-user", "--delay", "1", "-o", "/dev/full"], "is a character device")
    assert Path("/dev/full").is_char_device()


def test_a_failed_write_leaves_the_previous_file_whole(tmp_path, monkeypatch):
    import errno

    from hapticproof.core import files

    target = tmp_path / "report.txt"
    target.write_text("the good report\n", encoding="utf-8")
    real_fsync = os.fsync

    def full(fd):
        raise OSError(errno.ENOSPC, "No space left on device")

    monkeypatch.setattr(files.os, "fsync", full)
    with pytest.raises(files.OutputError, match="No space left on device"):
        files.write_atomic(target, "a new report that does not fit\n" * 100)
    monkeypatch.setattr(files.os, "fsync", real_fsync)
    assert target.read_text(encoding="utf-8") == "the good report\n"
    assert [p.name for p in tmp_path.iterdir()] == ["report.txt"]          # no temporary file left


def test_an_interrupted_map_leaves_no_partial_file(tmp_path, capsys, monkeypatch):
    from hapticproof.analysis import designmap

    target = tmp_path / "map.csv"
    target.write_text("x,y,passive\n1,1,1\n", encoding="utf-8")
    real = designmap.compute

    def interrupted(spec, sink=None, **kwargs):
        sink.write(spec, 0, [1] * len(spec.line(0)[1]))        # one line streamed, then Ctrl-C
        raise KeyboardInterrupt

    monkeypatch.setattr(designmap, "compute", interrupted)
    argv = ["map", "passivity", "--x", "b=0.001:0.05:5", "--y", "K=1:2:4", "--param", "T=0.001", "--param", "B=0",
            "-o", str(target)]
    refused(capsys, argv, "interrupted", code=130)
    assert target.read_text(encoding="utf-8") == "x,y,passive\n1,1,1\n"
    assert sorted(p.name for p in tmp_path.iterdir()) == ["map.csv"]
    monkeypatch.setattr(designmap, "compute", real)
    assert main(argv) == 0                                              # a complete map replaces it whole
    lines = target.read_text(encoding="utf-8").splitlines()
    assert lines[0] == "b,K,passive" and len(lines) == 1 + 20
    capsys.readouterr()


def test_ctrl_c_is_one_line(capsys, monkeypatch):
    def interrupt(args):
        raise KeyboardInterrupt

    monkeypatch.setattr("hapticproof.cli.build_parser", lambda command=None, system=None: _Parser(interrupt))
    refused(capsys, ["derive", "single-user"], "interrupted", code=130)


class _Parser:
    def __init__(self, handler):
        self.handler = handler

    def parse_args(self, argv):
        import argparse

        return argparse.Namespace(handler=self.handler)


# ---------------------------------------------------------------------------------------------
# 5. workers die with their parent
# ---------------------------------------------------------------------------------------------

def _children(pid: int) -> list[int]:
    out = subprocess.run(["pgrep", "-P", str(pid)], capture_output=True, text=True).stdout.split()
    return [int(p) for p in out]


def _alive(pid: int) -> bool:
    try:
        with open(f"/proc/{pid}/stat", encoding="ascii") as stat:
            return stat.read().split(") ")[-1][:1] not in ("Z", "X")     # a zombie is dead
    except OSError:
        return False


@pytest.mark.skipif(not sys.platform.startswith("linux") or not os.path.exists("/usr/bin/pgrep"),
                    reason="needs Linux and pgrep")
@pytest.mark.parametrize("sig", [signal.SIGTERM, signal.SIGKILL, signal.SIGINT])
def test_audit_workers_die_with_their_parent(tmp_path, sig):
    process = subprocess.Popen([sys.executable, "-m", "hapticproof", "audit", "hve", "--jobs", "2", "-o",
                                str(tmp_path / "out.txt")], stdout=subprocess.DEVNULL, stderr=subprocess.PIPE,
                               text=True, start_new_session=True,
                               preexec_fn=lambda: signal.signal(signal.SIGINT, signal.SIG_DFL))  # as in a terminal
    try:
        deadline = time.monotonic() + 60
        workers: list[int] = []
        while time.monotonic() < deadline and len(workers) < 2 and process.poll() is None:
            time.sleep(0.2)
            workers = _children(process.pid)
        assert len(workers) == 2, "the audit did not start two workers"
        if sig == signal.SIGINT:
            os.killpg(process.pid, sig)         # Ctrl-C reaches the whole process group
        else:
            os.kill(process.pid, sig)           # only the parent
        err = process.communicate(timeout=30)[1]
        deadline = time.monotonic() + 10
        while time.monotonic() < deadline and any(_alive(w) for w in workers):
            time.sleep(0.1)
        assert not any(_alive(w) for w in workers), "a worker outlived its parent"
        if sig == signal.SIGINT:
            assert process.returncode == 130 and err.strip() == "hapticproof: interrupted"
        assert not (tmp_path / "out.txt").exists()
    finally:
        if process.poll() is None:
            process.kill()
        for w in _children(process.pid):
            os.kill(w, signal.SIGKILL)


# ---------------------------------------------------------------------------------------------
# 6. a valid input gets the right answer
# ---------------------------------------------------------------------------------------------

def test_symbolic_wall_with_a_delay_of_16_is_derived(capsys):
    assert main(["derive", "single-user", "--delay", "16"]) == 0
    out = capsys.readouterr().out
    assert "worst case:      min_c(polynomial of c: degree 17" in out
    assert "verdict:         symbolic" in out and "Re G^-1 >= 0 for all w" in out


# ---------------------------------------------------------------------------------------------
# 7. sizes, bounded before the work
# ---------------------------------------------------------------------------------------------

@pytest.mark.parametrize("argv, expected", [
    (["derive", "single-user", "--environment", "z**10**9"], "exponent of 1000000000"),
    (["derive", "single-user", "--environment", "(z**1000)**1000"], "degree of 1000000"),
    (["derive", "single-user", "--delay", "1000000000"], "limit of 100000"),
    (["derive", "multi-user", "--users", "1000000000"], "limit of 1000"),
    (["derive", "single-user", "--param", "K=1e999999999"], "digits"),
    (["derive", "single-user", "--param", "K=" + "9" * 10000], "10000 digits"),
    (["derive", "single-user", "--environment", "(" * 20000 + "K" + ")" * 20000], "levels of nesting"),
    (["derive", "multi-user", "--users", "20"], "principal minors"),
    (["map", "passivity", "--x", "b=0.001:0.05:100000", "--y", "K=1:2:100000", "--param", "T=0.001", "--param", "B=0"],
     "10000000000 points"),
    (["map", "passivity", "--x", "b=0.001:0.05:3", "--y", "K=1:2:3", "--param", "T=1e-999999999", "--param", "B=0"],
     "digits"),
])
def test_sizes_are_refused_before_the_work(capsys, argv, expected):
    refused(capsys, argv, expected, "--limit")


def test_twenty_symbolic_users_are_refused_before_any_algebra(capsys, monkeypatch):
    """2^20 - 1 principal minors: refused on the input, before G^-1 or a condition is built (it
    took 26 s of algebra before the refusal)."""
    import hapticproof.analysis.multiuser as analysis
    import hapticproof.systems.multiuser as systems

    def started(*args, **kwargs):
        raise AssertionError("the algebra started before the limits were checked")

    monkeypatch.setattr(systems, "inverse_transfer_matrix", started)
    monkeypatch.setattr(analysis, "conditions", started)
    refused(capsys, ["derive", "multi-user", "--users", "20"], "2^20 - 1 principal minors", "--limit minors=N")
    with pytest.raises(limits.LimitError, match="principal minors"):
        analysis.positive_real(systems.MultiUserScene.symbolic(20))


@pytest.mark.parametrize("printed, expected", [
    (r"b > K^{99999999}", "exponent of 99999999"),
    (r"b > 2^{2^{2^{2^{2^{2^{2}}}}}}", "exponent of 65536"),
    ("b > " + "{" * 100000 + "K" + "}" * 100000, "100000 levels of nesting"),
    ("b > " + "9" * 10000, "10000 digits"),
])
def test_sizes_in_a_printed_display_are_refused(tmp_path, capsys, printed, expected):
    refused(capsys, ["audit", "--paper", paper(tmp_path, printed=printed)], "p.toml:14", "field 'printed'", expected)


def test_a_limit_is_raised_for_one_run(capsys):
    refused(capsys, ["derive", "single-user", "--environment", "z**1001"], "--limit exponent=N")
    assert main(["--limit", "exponent=2000", "derive", "single-user", "--environment", "K*z**-1001",
                 "--param", "K=1", "--param", "T=1", "--param", "b=3"]) == 0
    assert limits.current().exponent == 2000
    limits.set_limits(limits.DEFAULT)
    capsys.readouterr()
    refused(capsys, ["derive", "single-user", "--limit", "dealy=3"], "unknown limit 'dealy'")


def test_a_uniform_scene_of_100_users_uses_its_modes():
    from hapticproof.analysis.multiuser import conditions
    from hapticproof.systems.multiuser import MultiUserScene

    residue = conditions(MultiUserScene.uniform(100))[2]          # 2^100 - 1 minors: never enumerated
    assert residue.decision.value == "proved" and "lambda_max" in residue.outcome.reason


def test_loading_indexes_every_key_once():
    from hapticproof.core.tomltext import TomlLines

    text = "".join(f'[[equations]]\nid = "{k}"\nprinted = "b > {k}"\n' for k in range(3000))
    index = TomlLines(text)
    entries = index.entries("equations")
    assert len(entries) == 3000 and entries[2999] == (8998, 9000)
    assert index.line_between("printed", *entries[1500]) == 3 * 1500 + 3


# ---------------------------------------------------------------------------------------------
# 8. decoding, shapes and types
# ---------------------------------------------------------------------------------------------

def test_a_file_that_is_not_utf8_is_one_line(tmp_path, capsys):
    (tmp_path / "s.toml").write_bytes('system = "single-user"\n# caf\xe9\n'.encode("latin-1"))
    refused(capsys, ["derive", "--scene", tmp_path / "s.toml"], "s.toml:2: not UTF-8 text (byte 0xe9 at column 6)")
    (tmp_path / "p.toml").write_bytes(b"\xff\xfe[\x00")
    refused(capsys, ["audit", "--paper", tmp_path / "p.toml"], "UTF-16")


def test_a_byte_order_mark_is_skipped(tmp_path, capsys):
    (tmp_path / "s.toml").write_bytes(b"\xef\xbb\xbf" + WALL.encode())
    assert main(["derive", "--scene", str(tmp_path / "s.toml"), "--param", "K=1", "--param", "B=0", "--param", "T=1",
                 "--param", "b=1"]) == 0
    bom_paper = paper(tmp_path)
    bom_paper.write_bytes(b"\xef\xbb\xbf" + bom_paper.read_bytes())
    assert main(["audit", "--paper", str(bom_paper)]) == 0
    assert "Traceback" not in capsys.readouterr().err


@pytest.mark.parametrize("content, expected", [
    ("42", "not a hapticproof report"), ("null", "got null"), ('"x"', "got text"), ("[]", "got a list"),
    ('{"paper": "p", "equations": [1, 2]}', "equations[0]: expected an object, got a number"),
    ('{"paper": "p", "equations": [{"verdict": "confirmed", "printed": "x"}]}', "missing field 'id'"),
    ('{"paper": "p", "equations": [{"id": 3, "verdict": "confirmed", "printed": "x"}]}', "field 'id' must be text"),
    ('{"papers": [null]}', "papers[0]: expected an object"),
    ('{"paper": "p", "equations": [{"id": "1", "kind": "condition", "verdict": "fine", "printed": "x", "detail": "",'
     ' "evidence": {"method": "parse"}}]}', "unknown verdict"),
    ("[" * 100000 + "]" * 100000, "100000 levels of nesting"),
    ('{"a": NaN}', "not JSON"), ("{", "not JSON"),
])
def test_check_refuses_what_is_not_a_report(tmp_path, capsys, content, expected):
    (tmp_path / "r.json").write_text(content, encoding="utf-8")
    refused(capsys, ["check", tmp_path / "r.json"], "r.json", expected)


@pytest.mark.parametrize("content, expected", [
    ("42", "got a number"), ('{"paper": "hve", "title": "x", "equations": [null]}', "got null"),
    ('{"paper": "hve", "title": "x", "equations": [{"printed": "x", "verdict": "typo"}]}', "missing field 'id'"),
    ("[" * 100000 + "]" * 100000, "levels of nesting"), ('{"conditions": []}', "not a saved audit"),
])
def test_export_refuses_what_is_not_a_saved_audit(tmp_path, capsys, content, expected):
    (tmp_path / "a.json").write_text(content, encoding="utf-8")
    refused(capsys, ["export", "hve", "--from-audit", tmp_path / "a.json", "-o", tmp_path / "e.tex"], expected)
    assert not (tmp_path / "e.tex").exists()


@pytest.mark.parametrize("field, expected", [
    ('delay = "1/0"', "must be a non-negative integer"), ('delay = [[1]]', "must be a list of integers"),
    ('delay = "\u0661\u0666"', "must be a non-negative integer"), ("users = 2.5", "must be integer"),
    ("[params]\nK = \"\u0662\"", "unexpected character"), ("[params]\nK = inf", "'Infinity' is not a finite number"),
    ("delay = [" * 200 + "]" * 200, "levels of nesting"),
])
def test_scene_fields_of_the_wrong_form_are_one_line(tmp_path, capsys, field, expected):
    (tmp_path / "s.toml").write_text(WALL + field + "\n", encoding="utf-8")
    refused(capsys, ["derive", "--scene", tmp_path / "s.toml"], "s.toml", expected)


def test_ports_that_are_not_sizes_are_one_line(tmp_path, capsys):
    (tmp_path / "m.txt").write_text("s, 1\n1, s\n", encoding="utf-8")
    (tmp_path / "s.toml").write_text('system = "network"\nmatrix = "m.txt"\nports = ["a"]\n', encoding="utf-8")
    refused(capsys, ["derive", "--scene", tmp_path / "s.toml"], "s.toml:3", "field 'ports'")
    (tmp_path / "m.json").write_text('{"matrix": [["s", "1"], ["1", "s"]], "ports": ["a"]}', encoding="utf-8")
    refused(capsys, ["derive", "network", "--matrix", tmp_path / "m.json"], "'ports' must be a list of integers")


# ---------------------------------------------------------------------------------------------
# 9. accepted silently before
# ---------------------------------------------------------------------------------------------

def test_nan_in_a_paper_scene_is_refused(tmp_path, capsys):
    scenes = WALL_SCENE + "[scenes.wall.params]\nK = nan\n"
    refused(capsys, ["audit", "--paper", paper(tmp_path, scenes=scenes)], "p.toml:12", "'NaN' is not a number")


def test_a_definition_cycle_is_refused(tmp_path, capsys):
    (tmp_path / "s.toml").write_text(WALL + '[params]\nK = "B*2"\nB = "K/2"\n', encoding="utf-8")
    refused(capsys, ["derive", "--scene", tmp_path / "s.toml"], "defined in a cycle: B = K/2, K = 2*B")
    scenes = WALL_SCENE + '[scenes.wall.params]\nK = "B*2"\nB = "K/2"\n'
    refused(capsys, ["audit", "--paper", paper(tmp_path, scenes=scenes)], "defined in a cycle")
    refused(capsys, ["derive", "single-user", "--param", "K=K/2"], "defined in a cycle: K = K/2")


@pytest.mark.parametrize("argv", [["derive", "single-user", "--delay", "\u0661\u0666"],
                                  ["derive", "multi-user", "--users", "\u0663"],
                                  ["audit", "hve", "--jobs", "\u0662"]])
def test_arabic_indic_digits_are_refused(capsys, argv):
    refused(capsys, argv, "digits 0-9")


def test_same_as_itself_is_refused(tmp_path, capsys):
    refused(capsys, ["audit", "--paper", paper(tmp_path, claim="same-as", extra='other = "1"')],
            "field 'other'", "the same as itself")


def test_an_equation_id_with_a_control_character_is_one_line(tmp_path, capsys):
    """Found by the large fuzz run: an id "0\\r0" split the error message in two lines."""
    path = tmp_path / "p.toml"
    path.write_text('[paper]\nid = "fz"\ntitle = "t"\n[scenes.s]\nsystem = "single-user"\n[[equations]]\n'
                    'id = "0\\r0"\nprinted = "b > c"\nclaim = "passivity-condition"\nscene = "s"\n')
    assert main(["audit", "--paper", str(path)]) == 2
    err = capsys.readouterr().err
    assert len(err.strip().splitlines()) == 1 and "control character" in err and "\r" not in err
