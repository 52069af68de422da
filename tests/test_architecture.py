"""The layering of ``docs/architecture.md``, read from the code by ``tests/architecture.py``:
no import cycles, no private name used across modules, no import of a higher layer, an
independent checker, and no module over ~2000 lines (modules are cut by concept, not by a line count)."""

from __future__ import annotations

import importlib.util
import subprocess
import sys
from pathlib import Path

HERE = Path(__file__).resolve().parent
spec = importlib.util.spec_from_file_location("architecture", HERE / "architecture.py")
architecture = importlib.util.module_from_spec(spec)
sys.modules["architecture"] = architecture          # dataclasses look their module up
spec.loader.exec_module(architecture)

GRAPH = architecture.read_graph()


def test_the_graph_is_read():
    # the reader sees the layers and their imports (a check on an empty graph proves nothing)
    assert {"hapticproof.core.errors", "hapticproof.exact.kernel", "hapticproof.audit.reader.grammar"} <= set(GRAPH.modules)
    assert "hapticproof.exact.realroots" in GRAPH.imports["hapticproof.exact.kernel"]


def test_no_import_cycles():
    assert architecture.cycles(GRAPH) == []


def test_no_private_names_across_modules():
    assert GRAPH.private == []


def test_layers_import_only_downwards():
    assert architecture.upward_imports(GRAPH) == []


def test_checker_is_independent_of_the_kernel():
    assert architecture.checker_imports(GRAPH) == []


def test_modules_are_short():
    assert architecture.long_modules(GRAPH) == []


def test_the_checks_can_fail(tmp_path):
    # the cycle finder and the private-name reader on a graph that breaks both rules
    graph = architecture.Graph({"hapticproof.a": tmp_path, "hapticproof.b": tmp_path},
                               {"hapticproof.a": {"hapticproof.b"}, "hapticproof.b": {"hapticproof.a"}})
    assert architecture.cycles(graph) == [["hapticproof.a", "hapticproof.b"]]
    graph.imports = {"hapticproof.core.x": {"hapticproof.report.y"}, "hapticproof.report.y": set()}
    assert architecture.upward_imports(graph) == [("hapticproof.core.x", "hapticproof.report.y")]


def test_the_script_runs_from_the_checkout():
    done = subprocess.run([sys.executable, str(HERE / "architecture.py")], capture_output=True, text=True)
    assert done.returncode == 0, done.stdout
    assert "import cycles: 0" in done.stdout and "private names imported across modules: 0" in done.stdout
