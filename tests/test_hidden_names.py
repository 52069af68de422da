"""Issue 30, names: no name has a hidden meaning.

A device damping named ``n`` was read as the delay (two ``wrong``, two ``undecided`` where ``b``
gives ``confirmed``), one named ``c`` as cos(omega T); a parameter named ``a`` was silently
non-negative (``--range a`` gave ``0 <= a <= 1``, the same scene with ``q`` ``-1/3 <= q <= 1``).
The toolkit's own quantities' names are refused in one line wherever a user names something;
no sign is assumed for a name the user did not give one.
"""

from __future__ import annotations

from pathlib import Path

import pytest

from hapticproof.cli import main
from hapticproof.core.symbols import TOOLKIT_NAMES

ROOT = Path(__file__).resolve().parents[1]


def _one_line(capsys, argv, *expected):
    status = main([str(a) for a in argv])
    err = capsys.readouterr().err
    assert status == 2 and err.count("\n") == 1 and "Traceback" not in err, err
    for text in expected:
        assert text in err, err
    return err


def _paper(capsys, folder: Path, damping: str) -> Path:
    """The new-paper template with the device damping named ``damping`` (a role)."""
    if not (folder / "t.toml").exists():
        assert main(["new-paper", str(folder / "t.toml")]) == 0
        capsys.readouterr()
    template = (folder / "t.toml").read_text(encoding="utf-8")
    assert 'b = "positive"' in template
    out = template.replace('b = "positive"', f'{damping} = "positive"', 1)
    out = out.replace("printed = 'F_h(z) = bV_h(z)", f"printed = 'F_h(z) = {damping}V_h(z)")
    out = out.replace(r"printed = 'b > \frac{KT}{2}", rf"printed = '{damping} > \frac{{KT}}{{2}}")
    out = out.replace("delay = 0 ", f'delay = 0\n[scenes.wall.roles]\ndevice_damping = "{damping}"\n#', 1)
    path = folder / f"{damping}.toml"
    path.write_text(out, encoding="utf-8")
    return path


def test_a_free_name_for_the_damping_gives_the_same_verdicts(tmp_path, capsys):
    for name in ("b", "d_v"):
        assert main(["audit", "--paper", str(_paper(capsys, tmp_path, name))]) == 0
        out = capsys.readouterr().out
        assert "confirmed: 3" in out, out


@pytest.mark.parametrize("name", ["n", "c"])
def test_a_toolkit_name_for_the_damping_is_refused_in_a_paper_file(tmp_path, capsys, name):
    _one_line(capsys, ["audit", "--paper", _paper(capsys, tmp_path, name)], f"'{name}' is the toolkit's own name")


@pytest.mark.parametrize("name", sorted(TOOLKIT_NAMES))
@pytest.mark.parametrize("how", ["role", "param", "environment"])
def test_a_toolkit_name_is_refused_in_a_scene(capsys, name, how):
    argv = {"role": ["--role", f"device_damping={name}"],
            "param": ["--environment", f"K + {name}*(z - 1)/(T*z)", "--param", f"{name}=1"],
            "environment": ["--environment", f"K + {name}*(z - 1)/(T*z)"]}[how]
    _one_line(capsys, ["derive", "single-user", *argv], f"'{name}' is the toolkit's own name")


def test_the_toolkit_names_keep_their_meaning_where_declared_so(capsys):
    """``n = "integer"`` (the delay) and ``omega = "real"`` (the frequency) are declarations
    of the toolkit's own meaning, as the bundled paper files make them; a symbolic delay ``n`` is
    the scene's delay, not a parameter."""
    assert main(["audit", "--paper", str(ROOT / "examples" / "hve-single-user.toml"), "-e", "20"]) == 0
    assert main(["derive", "single-user", "--delay", "n"]) == 0
    capsys.readouterr()


@pytest.mark.parametrize("name", ["a", "q"])
def test_no_sign_is_assumed_for_a_name_the_user_did_not_give_one(capsys, name):
    assert main(["derive", "single-user", "--environment", f"K + B*(1 - {name})*(z - 1)/(T*(z - {name}))",
                 "--param", "K=20", "--param", "B=0.005", "--param", "b=0.02", "--param", "T=0.001",
                 "--range", name]) == 0
    out = capsys.readouterr().out
    assert f"passive range of {name} (others fixed): -1/3 <= {name} <= 1" in out, out


def test_a_stated_sign_is_applied(capsys):
    assert main(["derive", "single-user", "--environment", "K + B*(1 - a)*(z - 1)/(T*(z - a))",
                 "--param", "K=20", "--param", "B=0.005", "--param", "b=0.02", "--param", "T=0.001",
                 "--param", "a=nonnegative", "--range", "a"]) == 0
    assert "passive range of a (others fixed): 0 <= a <= 1" in capsys.readouterr().out
