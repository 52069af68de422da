"""``hapticproof.positive_real`` decides every system kind from the top level -- a scene, its build,
a matrix, a python-control system -- with the decision and witness the command line gives."""

from __future__ import annotations

import json
import sys
from pathlib import Path

import pytest
import sympy as sp

import hapticproof
from hapticproof.core.errors import HapticproofError
from hapticproof.systems.scene import Scene

sys.path.insert(0, str(Path(__file__).parent))
from clirun import run  # noqa: E402

#: (scene, the same scene on the command line): numeric scenes of every kind, PR and not
SCENES = [
    (Scene("single-user", params={"K": 2, "B": 0, "b": "0.02", "T": "0.001"}),
     ["derive", "single-user", "--param", "K=2", "--param", "B=0", "--param", "b=0.02", "--param", "T=0.001"]),
    (Scene("single-user", params={"K": 100, "B": "0.5", "b": "0.02", "T": "0.001"}),
     ["derive", "single-user", "--param", "K=100", "--param", "B=0.5", "--param", "b=0.02", "--param", "T=0.001"]),
    (Scene("multi-user", users=2, uniform=True, params={"b": 1, "K_0": 1, "B_0": 0, "K": 1, "B": 0, "T": "0.01"}),
     ["derive", "multi-user", "--users", "2", "--uniform", *[a for kv in ("b=1", "K_0=1", "B_0=0", "K=1", "B=0", "T=0.01")
                                                           for a in ("--param", kv)]]),
    (Scene("multi-user", users=2, uniform=True, params={"b": "0.001", "K_0": 1, "B_0": 0, "K": 1, "B": 0, "T": "0.01"}),
     ["derive", "multi-user", "--users", "2", "--uniform", *[a for kv in ("b=0.001", "K_0=1", "B_0=0", "K=1", "B=0", "T=0.01")
                                                           for a in ("--param", kv)]]),
    (Scene("teleoperator", params={"K": 1, "B": 0, "T": "0.015", "b_m": "0.01822", "b_s": "0.01822"}),
     ["derive", "teleoperator", *[a for kv in ("K=1", "B=0", "T=0.015", "b_m=0.01822", "b_s=0.01822")
                                  for a in ("--param", kv)]]),
    (Scene("teleoperator", params={"K": 1, "B": 0, "T": "0.015", "b_m": "0.001", "b_s": "0.01822"}),
     ["derive", "teleoperator", *[a for kv in ("K=1", "B=0", "T=0.015", "b_m=0.001", "b_s=0.01822")
                                  for a in ("--param", kv)]]),
]


@pytest.mark.parametrize("scene, argv", SCENES, ids=lambda v: getattr(v, "system", None))
def test_every_kind_from_the_top_level_as_on_the_command_line(scene, argv, capsys):
    code, out, err = run(capsys, *argv, "--format", "json")
    assert code == 0, err
    shown = json.loads(out)
    for subject in (scene, scene.build()):
        outcome = hapticproof.positive_real(subject)
        verdict = shown.get("verdict") or shown["passivity"]["decision"]
        assert outcome.decision.value == verdict
        if outcome.witness and "witness" in shown:
            assert {k: str(v) for k, v in outcome.witness.items() if k == "c"} == \
                {k: str(v) for k, v in shown["witness"].items() if k == "c"}


def test_a_network_scene_its_matrix_and_the_command_line_agree(tmp_path, capsys):
    (tmp_path / "z.txt").write_text("1/(s + 1), 0\n0, s\n")
    code, out, err = run(capsys, "derive", "network", "--matrix", str(tmp_path / "z.txt"), "--no-search", "--format", "json")
    assert code == 0, err
    scene = Scene("network", matrix=[["1/(s + 1)", "0"], ["0", "s"]])
    assert hapticproof.positive_real(scene).decision.value == json.loads(out)["positive_real"]["decision"] == "proved"
    s = sp.Symbol("s")
    assert hapticproof.positive_real(sp.Matrix([[1 - 2 / (s + 1) + 10 / (s + 10**4)]])).decision.value == "disproved"


def test_matrices_in_z_and_control_systems_are_ispassive():
    control = pytest.importorskip("control")
    z = sp.Symbol("z")
    for G in (sp.Matrix([[(z - sp.Rational(1, 2)) / z]]), sp.Matrix([[1 / (z - sp.Rational(1, 2)), 0], [0, 1]])):
        assert hapticproof.positive_real(G).decision == hapticproof.ispassive(G).decision
    for tf in (control.tf([1, 2], [1, 1]), control.tf([1, -1], [1, 1]), control.tf([1, 0.5], [1, -0.2], 0.01)):
        assert hapticproof.positive_real(tf).decision == hapticproof.ispassive(tf).decision


def test_what_is_no_system_is_one_clear_error():
    with pytest.raises(HapticproofError, match="system"):
        hapticproof.positive_real("hello")
