"""The command-line interface: outputs, formats and one-line errors with non-zero exit."""

import json
import sys
from pathlib import Path

import pytest

sys.path.insert(0, str(Path(__file__).resolve().parent))

from clirun import run  # noqa: E402


def test_derive_single_user_json_numeric(capsys):
    code, out, _ = run(capsys, "derive", "single-user", "--param", "K=2", "--param", "T=0.001", "--param", "b=0.0009",
                       "--param", "B=0", "--format", "json")
    data = json.loads(out)
    assert code == 0
    assert {"hermitian_part", "worst_case", "verdict", "witness"} <= set(data)
    assert data["verdict"] == "disproved" and data["witness"]["c"] == "-1"   # b < KT/2 = 0.001
    assert [c["decision"] for c in data["conditions"]] == ["proved", "proved", "proved", "disproved"]


def test_derive_single_user_symbolic(capsys):
    code, out, _ = run(capsys, "derive", "single-user", "--approximation", "tustin", "--delay", "3", "--format", "json")
    data = json.loads(out)
    assert code == 0 and data["verdict"] == "symbolic" and data["witness"] is None


def test_derive_proved_with_profile(capsys):
    code, out, _ = run(capsys, "derive", "single-user", "--param", "K=2", "--param", "T=1/1000", "--param", "b=0.0011",
                       "--param", "B=0", "--delay", "0", "--profile")
    assert code == 0 and "proved" in out and "stages" in out


@pytest.mark.parametrize(
    "argv, message",
    [
        (["derive", "single-user", "--param", "T=-1"], "T must be positive"),
        (["derive", "single-user", "--param", "T=0.003", "--param", "t_d=0.01"], "t_d/T must be an integer"),
        (["derive", "single-user", "--param", "K"], "NAME=VALUE"),
        (["derive", "single-user", "--param", "Q=1"], "unknown parameter"),
        (["derive", "single-user", "--delay", "1.5"], "non-negative integer"),
        (["audit", "no-such-paper"], "unknown paper"),
        (["audit", "hve", "--equation", "999"], "no equation"),
        (["audit", "hve", "--section", "9"], "no equation of hve in section(s) 9"),
        (["audit", "hve", "-s", "3.1", "-e", "20"], "not both"),
        (["derive", "single-user", "--environment", "K +* z"], "unexpected '*'"),
    ],
)
def test_user_errors_are_one_line(capsys, argv, message):
    code, out, err = run(capsys, *argv)
    assert code == 2
    assert message in err and err.count("\n") == 1 and "Traceback" not in err


def test_audit_one_equation_formats(capsys, tmp_path):
    code, out, _ = run(capsys, "audit", "hve", "--equation", "20", "--format", "json")
    assert code == 0 and json.loads(out)["equations"][0]["verdict"] == "confirmed"
    code, out, _ = run(capsys, "audit", "hve", "-e", "19", "--format", "markdown")
    assert "| 19 |" in out and "malformed" in out
    target = tmp_path / "audit.tex"
    code, _, _ = run(capsys, "audit", "hve", "-e", "23", "-e", "25", "--format", "tex", "--output", str(target))
    assert code == 0 and target.read_text().startswith("\\documentclass")


def test_audit_sections_select_subsections_only(capsys):
    from hapticproof.audit.registry import get_paper

    code, out, _ = run(capsys, "audit", "classics", "--section", "2004", "--format", "json")
    ids = [e["id"] for e in json.loads(out)["equations"]]
    expected = [eq.id for eq in get_paper("classics").ordered() if eq.section == "2004"]
    assert code == 0 and ids == expected and 0 < len(ids) < len(get_paper("classics").ordered())


@pytest.mark.parametrize(
    "argv, message",
    [
        (["derive", "single-user", "--format", "htm"], "derive single-user: argument --format: invalid choice"),
        (["derive", "single-user", "--deadline", "abc"], "invalid float value"),
        (["derive", "single-user", "--parm", "K=2"], "unrecognized arguments: --parm"),
        (["derive"], "the following arguments are required"),
        ([], "the following arguments are required: COMMAND"),
    ],
)
def test_option_mistakes_are_one_line_too(capsys, argv, message):
    """Mistakes argparse finds are one line and exit 2, like every other mistake (the usage is in --help)."""
    with pytest.raises(SystemExit) as stop:
        from hapticproof.cli import main

        main(argv)
    err = capsys.readouterr().err
    assert stop.value.code == 2
    assert err.startswith("hapticproof: error: ") and err.count("\n") == 1 and message in err, err


def test_an_unknown_option_points_to_the_help_of_its_own_command(capsys):
    from hapticproof.cli import main

    for argv, prog in ((["derive", "single-user", "--bogus", "1"], "hapticproof derive single-user"),
                       (["audit", "--paperz", "x"], "hapticproof audit")):
        with pytest.raises(SystemExit) as stop:
            main(argv)
        assert stop.value.code == 2
        err = capsys.readouterr().err.strip()
        assert len(err.splitlines()) == 1 and "unrecognized arguments" in err and err.endswith(f"(see: {prog} --help)")


def test_a_scene_file_without_system_takes_the_commands(tmp_path, capsys):
    """``derive single-user --scene FILE`` names the kind: a file of parameters alone is read as it,
    and a file of another kind is one line."""
    from hapticproof.cli import main

    (tmp_path / "p.toml").write_text("[params]\nK = 2\nB = 0\nb = 0.02\nT = 0.001\n")
    assert main(["derive", "single-user", "--scene", str(tmp_path / "p.toml"), "--format", "json"]) == 0
    assert json.loads(capsys.readouterr().out)["verdict"] == "proved"
    (tmp_path / "t.toml").write_text('system = "teleoperator"\n')
    assert main(["derive", "single-user", "--scene", str(tmp_path / "t.toml")]) == 2
    assert "describes a teleoperator scene, not single-user" in capsys.readouterr().err
