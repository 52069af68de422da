"""Issue 30, outputs: an output never escapes its path.

A stranger's folder may hold planted links (``errata.html -> ~/.bashrc``, a dangling
``review.toml -> anywhere``), FIFOs and device nodes under the names a user writes to. Every
output of every command -- reports in every format, drafts, maps, curves, figures, benchmark
results -- goes through one writer (:func:`hapticproof.core.files.write_output`), which refuses
a symbolic link (even a dangling one), a FIFO, a device or a socket in one line, before any work
and again when the write starts, and never leaves a temporary file behind, whatever stops it
(an error, Ctrl-C, SIGTERM).
"""

from __future__ import annotations

import os
import signal
import subprocess
import sys
import time
from pathlib import Path

import pytest

from hapticproof.cli import main
from hapticproof.core import files

SECRET = "the user's own file\n"


def _refused(capsys, argv, *expected: str) -> str:
    status = main([str(a) for a in argv])
    err = capsys.readouterr().err.strip()
    assert status == 2, err
    assert "Traceback" not in err and len(err.splitlines()) == 1 and err.startswith("hapticproof: error: "), err
    for text in expected:
        assert text in err, err
    return err


def _paper(capsys, folder: Path) -> Path:
    path = folder / "p.toml"
    assert main(["new-paper", str(path)]) == 0
    capsys.readouterr()
    return path


#: (command line with OUT for the output, the output's suffix)
COMMANDS = [
    (["audit", "hve", "--equation", "25", "--format", "html", "-o", "OUT"], ".html"),
    (["audit", "hve", "--equation", "25", "--format", "markdown", "-o", "OUT"], ".md"),
    (["audit", "hve", "--equation", "25", "--format", "json", "-o", "OUT"], ".json"),
    (["audit", "hve", "--equation", "25", "--format", "tex", "-o", "OUT"], ".tex"),
    (["new-paper", "OUT"], ".toml"),
    (["derive", "single-user", "--param", "K=2", "--param", "T=0.001", "--param", "b=1", "-o", "OUT"], ".txt"),
    (["export", "hve", "-o", "OUT"], ".tex"),
    (["map", "passivity", "--x", "b=0.001,0.002", "--y", "K=3", "--param", "T=0.001", "--param", "B=0", "-o", "OUT"], ".csv"),
    (["map", "passivity", "--x", "b=0.001,0.002", "--y", "K=3", "--param", "T=0.001", "--param", "B=0", "--plot", "OUT"],
     ".png"),
    (["boundary", "single-user", "--param", "m=0.015", "--param", "b=0.02", "--vary", "K", "--json", "OUT"], ".json"),
    (["boundary", "single-user", "--param", "m=0.015", "--param", "b=0.02", "--vary", "K", "--over", "T=0.001:0.002:2",
      "--plot", "OUT"], ".svg"),
]


@pytest.mark.parametrize("argv, suffix", COMMANDS, ids=lambda v: " ".join(v[:2]) if isinstance(v, list) else v)
@pytest.mark.parametrize("planted", ["link", "dangling-link", "fifo"])
def test_no_output_is_written_through_a_planted_link_or_into_a_fifo(tmp_path, capsys, argv, suffix, planted):
    outside = tmp_path / "outside"
    outside.mkdir()
    target = outside / "bashrc"
    target.write_text(SECRET, encoding="utf-8")
    folder = tmp_path / "stranger"
    folder.mkdir()
    out = folder / ("out" + suffix)
    if planted == "link":
        out.symlink_to(target)
    elif planted == "dangling-link":
        out.symlink_to(outside / "created-by-the-attack")
    else:
        os.mkfifo(out)
    expected = "is a symbolic link" if planted != "fifo" else "is a FIFO"
    _refused(capsys, [out if a == "OUT" else a for a in argv], expected)
    assert target.read_text(encoding="utf-8") == SECRET
    assert not (outside / "created-by-the-attack").exists()
    assert out.is_symlink() if planted != "fifo" else out.is_fifo()
    assert sorted(p.name for p in folder.iterdir()) == [out.name]        # no temporary file either


@pytest.mark.skipif(not os.path.exists("/dev/full"), reason="no /dev/full")
@pytest.mark.parametrize("option", ["-o", "--plot"])
def test_a_link_to_a_device_is_refused_and_the_device_stays(tmp_path, capsys, option):
    """As root, ``--plot full.png`` with ``full.png -> /dev/full`` replaced the device node."""
    link = tmp_path / ("full.png" if option == "--plot" else "full.csv")
    link.symlink_to("/dev/full")
    _refused(capsys, ["map", "passivity", "--x", "b=0.001,0.002", "--y", "K=3", "--param", "T=0.001", "--param", "B=0",
                      option, link], "is a symbolic link")
    assert Path("/dev/full").is_char_device()
    _refused(capsys, ["derive", "single-user", "-o", "/dev/full"], "is a character device")
    assert Path("/dev/full").is_char_device()


def test_new_paper_never_overwrites_its_own_source(tmp_path, capsys):
    source = _paper(capsys, tmp_path)
    before = source.read_text(encoding="utf-8")
    _refused(capsys, ["new-paper", "--force", "--from", source, source], "is an input of this command")
    assert source.read_text(encoding="utf-8") == before


def test_a_dangling_link_is_not_a_free_name_for_new_paper(tmp_path, capsys):
    (tmp_path / "review.toml").symlink_to(tmp_path / "elsewhere.toml")
    for force in ([], ["--force"]):
        _refused(capsys, ["new-paper", *force, tmp_path / "review.toml"], "is a symbolic link")
    assert not (tmp_path / "elsewhere.toml").exists()


def test_standard_output_is_still_dash(capsys):
    assert main(["derive", "single-user", "--param", "K=2", "--param", "T=0.001", "--param", "b=1", "-o", "-"]) == 0
    assert "verdict" in capsys.readouterr().out


def test_a_link_planted_after_the_check_is_refused_when_the_write_starts(tmp_path):
    target = tmp_path / "secret"
    target.write_text(SECRET, encoding="utf-8")
    out = tmp_path / "report.html"
    files.check_output(out, "-o")                       # the check before the work passes ...
    out.symlink_to(target)                              # ... and the link appears during the work
    with pytest.raises(files.OutputError, match="is a symbolic link"):
        files.write_atomic(out, "<p>report</p>")
    assert target.read_text(encoding="utf-8") == SECRET and out.is_symlink()


def test_a_link_planted_during_the_write_is_replaced_not_followed(tmp_path):
    target = tmp_path / "secret"
    target.write_text(SECRET, encoding="utf-8")
    out = tmp_path / "map.csv"
    with files.AtomicOutput(out, "-o") as writer:
        writer.stream.write("x,y\n")
        out.symlink_to(target)                          # the rename replaces the name, never the link's target
        writer.commit()
    assert target.read_text(encoding="utf-8") == SECRET
    assert not out.is_symlink() and out.read_text(encoding="utf-8") == "x,y\n"


def test_figures_and_benchmark_results_use_the_same_writer(tmp_path):
    import matplotlib

    matplotlib.use("Agg")
    from matplotlib.figure import Figure

    target = tmp_path / "secret"
    target.write_text(SECRET, encoding="utf-8")
    figure = Figure()
    figure.add_subplot(111).plot([0, 1], [1, 0])
    (tmp_path / "plot.png").symlink_to(target)
    with pytest.raises(files.OutputError, match="is a symbolic link"):
        files.write_figure(figure, tmp_path / "plot.png")
    assert files.write_figure(figure, tmp_path / "plot.svg").read_text(encoding="utf-8").lstrip().startswith("<?xml")
    assert target.read_text(encoding="utf-8") == SECRET
    assert sorted(p.name for p in tmp_path.iterdir()) == ["plot.png", "plot.svg", "secret"]


def test_any_interruption_of_a_write_leaves_no_temporary_file(tmp_path):
    from hapticproof.cli import Terminated

    out = tmp_path / "r.txt"
    out.write_text("old\n", encoding="utf-8")
    for stop in (KeyboardInterrupt(), Terminated(signal.SIGTERM), OSError(28, "No space left on device")):
        with pytest.raises(type(stop)), files.AtomicOutput(out) as writer:
            writer.stream.write("half")
            raise stop
        assert sorted(p.name for p in tmp_path.iterdir()) == ["r.txt"] and out.read_text(encoding="utf-8") == "old\n"
    writer = files.AtomicOutput(out).__enter__()       # a write abandoned without unwinding: removed at exit
    assert len(list(tmp_path.iterdir())) == 2
    files.discard_temporaries()
    assert sorted(p.name for p in tmp_path.iterdir()) == ["r.txt"]
    writer.stream.close()


@pytest.mark.skipif(not sys.platform.startswith("linux"), reason="POSIX signals")
@pytest.mark.parametrize("sig", [signal.SIGTERM, signal.SIGINT])
def test_a_signal_during_map_leaves_no_temporary_file(tmp_path, sig):
    """SIGTERM during ``map`` left a hidden ``.map.csv.XXXX.tmp`` beside the output."""
    target = tmp_path / "map.csv"
    target.write_text("b,K,passive\n", encoding="utf-8")
    process = subprocess.Popen([sys.executable, "-m", "hapticproof", "map", "passivity", "--x", "b=0.0005:0.05:400",
                                "--y", "K=0.1:20:400", "--param", "T=0.001", "--param", "B=0.001", "--delay", "3",
                                "-o", str(target)], stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True,
                               cwd=tmp_path)
    try:
        deadline = time.monotonic() + 120
        while time.monotonic() < deadline and process.poll() is None and \
                not any(p.name.endswith(".tmp") for p in tmp_path.iterdir()):
            time.sleep(0.05)
        assert process.poll() is None, "the map ended before it could be stopped"
        process.send_signal(sig)
        err = process.communicate(timeout=60)[1]
    finally:
        if process.poll() is None:
            process.kill()
    assert process.returncode == 128 + sig, err
    assert "Traceback" not in err and err.strip().splitlines()[-1].startswith("hapticproof: "), err
    assert sorted(p.name for p in tmp_path.iterdir()) == ["map.csv"]
    assert target.read_text(encoding="utf-8") == "b,K,passive\n"


def test_bench_output_folder_is_checked_before_any_work(tmp_path, capsys):
    """``bench -o`` on a file, a FIFO, a device, a symbolic link to a folder, or a folder holding
    a link where an output goes: one line, exit 2, nothing written (was a traceback, or a write
    through the link)."""
    import os

    from hapticproof.cli import main

    (tmp_path / "afile").write_text("keep", encoding="utf-8")
    (tmp_path / "real").mkdir()
    os.symlink(tmp_path / "real", tmp_path / "link")
    os.mkfifo(tmp_path / "fifo")
    (tmp_path / "d").mkdir()
    os.symlink(tmp_path / "afile", tmp_path / "d" / "lazy.json")
    for target, expected in ((tmp_path / "afile", "is a file, not a folder"), (tmp_path / "fifo", "FIFO"),
                             ("/dev/null", "character device"), (tmp_path / "link", "symbolic link"),
                             (tmp_path / "d", "symbolic link")):
        assert main(["bench", "--tasks", "lazy", "--quick", "-o", str(target)]) == 2
        err = capsys.readouterr().err
        assert err.startswith("hapticproof: error: ") and expected in err and len(err.strip().splitlines()) == 1, err
    assert (tmp_path / "afile").read_text(encoding="utf-8") == "keep" and not any((tmp_path / "real").iterdir())
