"""Issue 21 (part B, item 2): a value is an exact number or an expression of declared names -- in
options, scene files, paper files and the Python API alike. Anything else is one clear line and
exit 2 (a specific exception from the API), never a symbol and never "verdict: symbolic"."""

import json
import math
import sys
from decimal import Decimal
from pathlib import Path

import pytest
import sympy as sp

from hapticproof.audit.paperfile import PaperFileError
from hapticproof.audit.paperfile import loads as load_paper
from hapticproof.core.errors import HapticproofError
from hapticproof.core.expr import ExpressionError, parameter_symbol, read_expression
from hapticproof.systems.scene import Scene, SceneFileError, loads

sys.path.insert(0, str(Path(__file__).resolve().parent))

from clirun import run  # noqa: E402

WALL = ["--param", "T=0.001", "--param", "b=0.02", "--param", "B=0"]


def one_line_error(capsys, *argv):
    code, out, err = run(capsys, *argv)
    assert code == 2 and err.count("\n") == 1 and err.startswith("hapticproof: error: ") and "Traceback" not in err, err
    return out, err


@pytest.mark.parametrize("value, message", [
    ("abc", "'abc' is not a name of this scene"),
    ("nan", "'nan' is not a number"),
    ("NaN", "'NaN' is not a number"),
    ("inf", "'inf' is not a finite number"),
    ("-inf", "'inf' is not a finite number"),
    ("oo", "'oo' is not a finite number"),
    ("zoo", "'zoo' is not a finite number"),
    ("pi", "'pi' is the irrational number pi"),
    ("2*pi", "'pi' is the irrational number pi"),
    ("1/0", "division by zero"),
    ("true", "'true' is not a name of this scene"),
])
def test_bad_values_are_one_line_and_exit_2(capsys, value, message):
    out, err = one_line_error(capsys, "derive", "single-user", *WALL, "--param", f"K={value}")
    assert message in err and out == ""


def test_declared_names_make_expressions_legal(capsys):
    code, out, _ = run(capsys, "derive", "single-user", *WALL, "--param", "abc=positive", "--param", "K=abc",
                       "--format", "json")
    assert code == 0 and json.loads(out)["verdict"] == "symbolic"
    code, out, _ = run(capsys, "derive", "single-user", *WALL, "--param", "Kw=4", "--param", "K=Kw/2",
                       "--format", "json")
    assert code == 0 and json.loads(out)["verdict"] == "proved"          # K = 2: b = 0.02 >= KT/2 = 0.001


def test_a_typo_in_a_value_suggests_the_name(capsys):
    _, err = one_line_error(capsys, "derive", "single-user", *WALL, "--param", "Kw=3", "--param", "K=2*Kww")
    assert "'Kww' is not a name of this scene" in err and "did you mean 'Kw'?" in err


@pytest.mark.parametrize("argv, message", [
    (["derive", "single-user", "--param", "K=2", "--param", "b=0.02", "--param", "B=0", "--param", "T=0"],
     "the sampling period T must be positive, got 0"),
    (["derive", "single-user", "--role", "period=Ts", "--param", "Ts=0"], "the sampling period Ts must be positive, got 0"),
    (["derive", "multi-user", "--param", "T=0"], "the sampling period T must be positive, got 0"),
    (["derive", "teleoperator", "--param", "T=0"], "the sampling period T must be positive, got 0"),
    (["boundary", "single-user", "--param", "m=0", "--param", "b=0.02", "--param", "B=0", "--param", "T=0.001",
      "--vary", "K"], "must be positive, got 0"),
    (["derive", "single-user", *WALL, "--param", "a=1", "--param", "K=1/(a - 1)"], "divides by zero"),
])
def test_a_period_or_mass_that_is_not_positive(capsys, argv, message):
    _, err = one_line_error(capsys, *argv)
    assert message in err


def test_zoh_refusal_exits_2_with_json_when_json_was_asked(capsys):
    argv = ["derive", "single-user", "--controller", "K + B*s/(s + 1)", "--discretize", "zoh", "--param", "K=2",
            "--param", "B=0.001", "--param", "T=0.001", "--param", "b=0.02"]
    out, err = one_line_error(capsys, *argv, "--format", "json")
    data = json.loads(out)
    assert "transcendental coefficients" in data["error"] and data["continuous_design"]["discretize"] == "zoh"
    assert "exp(-1/1000)" in data["continuous_design"]["H_z"] and data["verdict"] is None
    out, err = one_line_error(capsys, *argv[:5], "matched", *argv[6:])
    assert out == "" and "matched: H(z) = " in err
    out, err = one_line_error(capsys, "derive", "teleoperator", "--controller", "K_p + K_d*s/(s + 1)",
                              "--discretize", "zoh", "--param", "T=0.001", "--format", "json")
    assert "transcendental" in json.loads(out)["error"]


def test_scene_files_name_the_line(tmp_path, capsys):
    for text, message in [("K = nan", "'NaN' is not a number"), ("K = -inf", "is not a finite number"),
                          ('K = "pi/2"', "irrational number pi")]:
        with pytest.raises(SceneFileError, match=message) as err:
            loads(f'system = "single-user"\n[params]\n{text}\n', "wall.toml")
        assert str(err.value).startswith("wall.toml:3: ")
    path = tmp_path / "wall.toml"
    path.write_text('system = "single-user"\n[params]\nb = 0.02\nK = "abc"\n')
    _, err = one_line_error(capsys, "derive", "--scene", str(path))
    assert f"{path}:4: parameter 'K': 'abc' is not a name" in err


def test_the_api_refuses_non_numbers():
    for value in (float("nan"), float("inf"), Decimal("NaN"), sp.nan, sp.oo, sp.zoo, sp.pi, sp.sqrt(2), sp.pi * sp.Symbol("K")):
        with pytest.raises(HapticproofError):
            Scene("single-user", params={"K": value})
    with pytest.raises(HapticproofError, match="not a name of this scene"):
        Scene("single-user", params={"K": sp.Symbol("abc")}).build()
    assert Scene("single-user", params={"K": sp.Float(0.5)}).param_values == {"K": sp.Rational(1, 2)}
    assert Scene("single-user", params={"K": math.ldexp(1, -3)}).param_values == {"K": sp.Rational(1, 8)}


def test_the_reader_never_makes_symbols_of_non_numbers():
    for text in ("K + pi", "nan*z", "1/(z - inf)", "oo"):
        with pytest.raises(ExpressionError):
            read_expression(text, "z")
    for name in ("nan", "inf", "oo", "pi"):
        with pytest.raises(ExpressionError, match="not a parameter name"):
            parameter_symbol(name)
    assert parameter_symbol("PI").name == "PI"          # a gain may be called PI; only pi is the number


PAPER = '''
[paper]
id = "typo"
title = "A wall"

[symbols]
b = "positive"
K = "positive"
B = "real"
T = "positive"

[scenes.wall]
system = "single-user"
environment = "K + B*(z - 1)/(T*z)"
[scenes.wall.params]
b = "b_d"

[[equations]]
id = "1"
printed = 'b > \\frac{KT}{2} + |B|'
claim = "passivity-condition"
scene = "wall"
'''


def test_a_typo_in_a_paper_files_scene_is_an_error_naming_file_line_and_field():
    with pytest.raises(PaperFileError) as err:
        load_paper(PAPER, "typo.toml")
    assert str(err.value).startswith("typo.toml:16: scene 'wall': parameter 'b': 'b_d' is not a name of this scene")
    with pytest.raises(PaperFileError, match="typo.toml:16: .*'NaN' is not a number"):
        load_paper(PAPER.replace('b = "b_d"', "b = nan"), "typo.toml")
    fixed = PAPER.replace('b = "b_d"', 'b = "b_d"\nb_d = "positive"')
    assert load_paper(fixed, "typo.toml").scenes["wall"].param_values["b"] == sp.Symbol("b_d", positive=True)
    with pytest.raises(PaperFileError, match=r"typo.toml:22: equation 1: field 'solve_for': 'b_dd' is not a parameter"):
        load_paper(PAPER.replace('b = "b_d"\n', "").replace('scene = "wall"\n', 'scene = "wall"\nsolve_for = "b_dd"\n'),
                   "typo.toml")
