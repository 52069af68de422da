"""Issue 11: one scene model (derive, boundary, scene files, the Python API), the expression
reader, continuous designs, the designer's answers and readable output. Every failure the issue
lists has a test here (named after it)."""

import json
import sys
from pathlib import Path
import os

import numpy as np
import pytest
import sympy as sp

from hapticproof.cli import main
from hapticproof.core.errors import HapticproofError, SceneError
from hapticproof.core.expr import ExpressionError, parameter_symbol, read_expression
from hapticproof.systems.scene import Scene
from hapticproof.systems.singleuser import SingleUserScene
from hapticproof.core.symbols import s, z

sys.path.insert(0, str(Path(__file__).resolve().parent))

from clirun import one_line_error, run  # noqa: E402

R = sp.Rational


# ---------------------------------------------------------------------------------------------
# own parameter names
# ---------------------------------------------------------------------------------------------


def test_own_names_virtual_mass_in_derive_single_user(capsys):
    code, out, _ = run(capsys, "derive", "single-user", "--environment",
                       "K + B*(z-1)/(T*z) + M*(z-1)**2/(T**2*z**2)", "--param", "M=0.5", "--format", "json")
    data = json.loads(out)
    assert code == 0 and data["verdict"] == "symbolic"
    # M = 1/2 exactly: the virtual mass term M (z-1)/(T z^2) gives -2M/T = -1/T at c = -1
    assert "1/T" in data["conditions"][-1]["reason"]


def test_own_names_filter_pole_and_pid_gain(capsys):
    code, out, _ = run(capsys, "derive", "single-user", "--environment", "K + B*(1-a)*(z-1)/(T*(z-a))",
                       "--param", "K=20", "--param", "B=0.005", "--param", "T=0.001", "--param", "b=0.02",
                       "--param", "a=1/2", "--format", "json")
    assert code == 0 and json.loads(out)["verdict"] == "proved"
    code, out, _ = run(capsys, "derive", "teleoperator", "--controller", "K + K_i*T*z/(z-1)", "--format", "json")
    assert code == 0 and "K_i" in json.loads(out)["controller"]


def test_own_names_in_boundary_multi_user(capsys):
    code, out, _ = run(capsys, "boundary", "multi-user", "--uniform", "--param", "m=0.015", "--param", "b=0.02",
                       "--param", "B_0=0", "--param", "B=0", "--param", "K_0=K/2", "--param", "T=0.001",
                       "--vary", "K", "--delay", "0,1")
    assert code == 0 and out.startswith("K* = 8.0042")


def test_unknown_parameter_is_one_line(capsys):
    err = one_line_error(capsys, "derive", "single-user", "--param", "Q=1")
    assert "unknown parameter 'Q'" in err


# ---------------------------------------------------------------------------------------------
# exact numbers everywhere
# ---------------------------------------------------------------------------------------------


def test_decimal_inside_expression_is_exact(capsys):
    code, out, err = run(capsys, "derive", "single-user", "--environment", "K + B*(1-0.9)*(z-1)/(T*(z-0.9))",
                         "--format", "json")
    assert code == 0 and "Traceback" not in err
    data = json.loads(out)
    assert "." not in data["G_inverse"]
    b, K, B, T = (parameter_symbol(n) for n in ("b", "K", "B", "T"))
    G = sp.sympify(data["G_inverse"], locals={"b": b, "K": K, "B": B, "T": T, "z": z})
    expected = b + (K + B * R(1, 10) * (z - 1) / (T * (z - R(9, 10)))) * T / (z - 1)
    assert sp.cancel(G - expected) == 0


def test_symbolic_decimals_never_become_floats(capsys):
    code, out, _ = run(capsys, "derive", "single-user", "--environment", "0.5*K + B*(z-1)/(T*z)", "--format", "json")
    data = json.loads(out)
    text = data["G_inverse"] + data["hermitian_part"] + json.dumps(data["conditions"])
    assert code == 0 and "1.0*" not in text and "0.25" not in text and "0.5" not in text


def test_reader_numbers_and_errors():
    assert read_expression("0.9*z") == R(9, 10) * z
    assert read_expression("1e-3 + K", None) == R(1, 1000) + parameter_symbol("K")
    for text, message in [("2s + 1", "missing operator"), ("sin(s)", "unknown function 'sin'"),
                          ("K + z", "'z' in a continuous-time"), ("T^0.5", "integer constant"), ("K +* s", "unexpected")]:
        with pytest.raises(ExpressionError, match=message):
            read_expression(text, "s")
    with pytest.raises(ExpressionError, match="'s' in a discrete-time"):
        read_expression("K + s", "z")


def test_network_matrix_rejects_functions_and_z(tmp_path, capsys):
    f = tmp_path / "sin.txt"
    f.write_text("sin(s), 1\n1, 1\n")
    assert "unknown function 'sin'" in one_line_error(capsys, "derive", "network", "--matrix", str(f))
    g = tmp_path / "z.txt"
    g.write_text("1/(z+1), 1\n1, 1\n")
    assert "'z' in a continuous-time" in one_line_error(capsys, "derive", "network", "--matrix", str(g))


def test_api_normalises_a_differently_assumed_z():
    zc = sp.Symbol("z", complex=True)
    K = sp.Symbol("K", positive=True)
    scene = SingleUserScene(b=1, T=1, H=K + 1 / zc)
    assert scene.H.free_symbols == {K, z}
    with pytest.raises(SceneError, match="'s' in a discrete-time"):
        SingleUserScene(b=1, T=1, H=1 / (s + 1))


# ---------------------------------------------------------------------------------------------
# scene files and the API: one model, round trips
# ---------------------------------------------------------------------------------------------

SCENES = [
    Scene("single-user", environment="0.5*K + B*(z-1)/(T*z)"),
    Scene("single-user", controller="K + B*s", discretize="tustin", delay=3,
          params={"K": 2, "B": "0.001", "T": 0.001, "b": "0.02", "M": "positive"}),
    Scene("single-user", delay="n", active=True, params={"z_a": "1/100", "t_d": "nonnegative"}),
    Scene("multi-user", users=3, uniform=True, delay=[1, 2, 5], graph="path"),
    Scene("multi-user", params={"b": "0.02", "K_0": "Kw/2", "K": "Kw/2", "Kw": "positive", "T": "1e-3"}),
    Scene("teleoperator", controller="K_p + K_i/s", discretize="backward", operator="-z_a + 1/s",
          environment="clamped", params={"alpha": 2}),
    Scene("network", matrix=[["9/(s+3)", "-1/(s+1)"], ["-1/(s+1)", "1/(s+3)"]], ports=[1, 1]),
]


@pytest.mark.parametrize("scene", SCENES, ids=lambda sc: sc.system)
def test_scene_files_round_trip(scene, tmp_path):
    assert Scene.from_toml(scene.to_toml()) == scene
    path = scene.write(tmp_path / "scene.toml")
    assert Scene.read(path) == scene


def test_scene_file_fields_are_the_cli_options(tmp_path, capsys):
    text = ('system = "single-user"\nenvironment = "K + B*(z - 1)/(T*z)"\ndelay = 2\n'
            '[params]\nK = 2\nB = 0.001\nT = 0.001\nb = 0.02\n')
    path = tmp_path / "wall.toml"
    path.write_text(text)
    code, from_file, _ = run(capsys, "derive", "--scene", str(path), "--format", "json")
    code2, from_options, _ = run(capsys, "derive", "single-user", "--environment", "K + B*(z - 1)/(T*z)", "--delay", "2",
                                 "--param", "K=2", "--param", "B=0.001", "--param", "T=0.001", "--param", "b=0.02",
                                 "--format", "json")
    assert code == code2 == 0 and json.loads(from_file) == json.loads(from_options)
    # an option overrides the file's field
    code, out, _ = run(capsys, "derive", "--scene", str(path), "--delay", "0", "--format", "json")
    assert json.loads(out)["delay"] == "0"


def test_scene_file_errors_name_file_line_and_field(tmp_path, capsys):
    path = tmp_path / "bad.toml"
    path.write_text('system = "single-user"\n[params]\nK = "abc +"\n')
    err = one_line_error(capsys, "derive", "--scene", str(path))
    assert f"{path}:3" in err and "K" in err
    path.write_text('system = "single-user"\nenvironment = "K + s"\n')
    assert f"{path}:2" in one_line_error(capsys, "derive", "--scene", str(path))


def test_python_api_and_cli_build_the_same_model():
    scene = Scene("teleoperator", controller="pd", params={"K": 1, "B": "0.001", "T": "0.001", "b_m": "0.02",
                                                         "b_s": "0.02"})
    model = scene.build()
    assert model.m_m is None and model.parameters == set()
    from hapticproof.analysis.teleoperator import passivity

    assert passivity(model).decision.value == "proved"


# ---------------------------------------------------------------------------------------------
# the designer's answers
# ---------------------------------------------------------------------------------------------


@pytest.mark.parametrize("b, K", [("0.02", 2), ("0.013", 3), ("0.0009", 2), ("1/500", 4)])
def test_delay_margin_of_the_wall_matches_the_dirichlet_bound(b, K):
    from hapticproof.analysis.design import delay_margin

    scene = Scene("single-user", params={"b": b, "K": K, "B": 0, "T": "0.001"})
    margin = delay_margin(scene)
    # B = 0: passive iff b >= K T (n + 1/2) (Dirichlet kernel at c = 1), so N = floor(b/(KT) - 1/2)
    expected = int(sp.floor(R(b) / (K * R(1, 1000)) - R(1, 2)))
    assert margin.decision.value == "proved" and margin.margin == max(expected, -1)


def test_delay_margin_checked_delay_by_delay():
    from hapticproof.analysis.design import delay_margin
    from hapticproof.analysis.positivereal import positive_real

    scene = Scene("single-user", environment="K + B*(1-a)*(z-1)/(T*(z-a))",
                  params={"K": 20, "B": "0.001", "a": "1/2", "T": "0.001", "b": "0.05"})
    margin = delay_margin(scene)
    assert margin.margin is not None and margin.margin >= 0
    for n in range(margin.margin + 2):
        out = positive_real(scene.replace(delay=n).build())
        assert out.decision.value == ("proved" if n <= margin.margin else "disproved")


def test_delay_n_with_numbers_gives_the_margin(capsys):
    code, out, _ = run(capsys, "derive", "single-user", "--param", "K=2", "--param", "T=0.001", "--param", "b=0.01",
                       "--param", "B=0", "--delay", "n")
    assert code == 0 and "worst_case_instances" not in out
    assert "delay margin: N = 4" in out


def test_passive_ranges_match_the_closed_forms():
    from hapticproof.analysis.passiverange import passive_range

    wall = Scene("single-user", params={"b": "0.02", "B": "0.001", "T": "0.001", "K": 2})
    assert passive_range(wall.with_params(K=None), "K").maximum().value == R(38)            # 2(b - B)/T
    assert passive_range(wall.with_params(b=None), "b").minimum().value == R(1, 500)        # KT/2 + B
    rng = passive_range(wall.with_params(B=None), "B")
    assert rng.minimum().value == 0 and rng.maximum().value == R(19, 1000)                 # b - KT/2
    tele = Scene("teleoperator", params={"B": "0.001", "T": "0.001", "b_m": "0.02", "b_s": "0.02"})
    assert passive_range(tele, "K").maximum().value == 18                                   # b >= KT + 2B
    multi = Scene("multi-user", uniform=True, params={"b": "0.02", "K_0": 10, "B_0": 0, "B": 0, "T": "0.001"})
    assert passive_range(multi, "K").maximum().value == 15                                 # b >= K_0 T/2 + m K T/2


def test_passive_range_against_a_frequency_grid():
    """An algebraic K_max (virtual mass on the wall): sampled inside and outside, checked by direct
    complex evaluation on a dense grid (far enough from the boundary for floating point)."""
    from hapticproof.analysis.passiverange import passive_range

    scene = Scene("single-user", environment="K + B*(z-1)/(T*z) + M*(z-1)**2/(T**2*z**2)",
                  params={"K": 2, "B": "0.01", "T": "0.001", "b": "0.9"})
    rng = passive_range(scene, "M")
    (lo, lo_closed, hi, hi_closed), = rng.intervals
    lo_f, hi_f = float(lo.approx(20)), float(hi.approx(20))
    assert lo.value is None and hi.value == R(889, 2000000)
    theta = np.linspace(1e-4, np.pi, 200001)
    zz = np.exp(1j * theta)

    def min_re(M):
        H = 2 + 0.01 * (zz - 1) / (0.001 * zz) + M * (zz - 1) ** 2 / (0.001**2 * zz**2)
        return (0.9 + H * 0.001 / (zz - 1)).real.min()

    span = hi_f - lo_f
    assert min_re(lo_f + 0.01 * span) > 0 and min_re(hi_f - 0.01 * span) > 0
    assert min_re(lo_f - 0.05 * span) < 0 and min_re(hi_f + 0.05 * span) < 0


def test_designer_answers_on_the_command_line(capsys):
    code, out, _ = run(capsys, "derive", "single-user", "--param", "b=0.02", "--param", "B=0.001", "--param", "T=0.001",
                       "--param", "K=2", "--delay-margin", "--range", "K", "--format", "json")
    data = json.loads(out)
    assert code == 0 and data["delay_margin"]["margin"] == 10
    assert data["passive_ranges"]["K"]["intervals"][0]["hi"] == {"exact": "38"}


# ---------------------------------------------------------------------------------------------
# readable, honest output
# ---------------------------------------------------------------------------------------------


def test_teleoperator_decides_without_masses_and_prints_no_raw_dict(capsys):
    code, out, _ = run(capsys, "derive", "teleoperator", "--param", "K=1", "--param", "B=0.01", "--param", "T=0.001",
                       "--param", "b_m=0.02", "--param", "b_s=0.02")
    assert code == 0 and "verdict: disproved" in out
    code, out, _ = run(capsys, "derive", "teleoperator", "--controller", "K/(z-1)", "--param", "K=1",
                       "--param", "T=0.001", "--param", "b_m=0.02", "--param", "b_s=0.02")
    assert code == 0 and "{'exact'" not in out and "unbounded" in out


def test_large_expressions_are_summarised_in_text(capsys):
    code, out, _ = run(capsys, "derive", "single-user", "--param", "K=2", "--param", "T=0.001", "--param", "b=0.3",
                       "--param", "B=0", "--delay", "200")
    assert code == 0 and "degree 200" in out and max(len(line) for line in out.splitlines()) < 1500
    code, verbose, _ = run(capsys, "derive", "single-user", "--param", "K=2", "--param", "T=0.001", "--param", "b=0.3",
                           "--param", "B=0", "--delay", "200", "--verbose")
    assert max(len(line) for line in verbose.splitlines()) > 3000


def test_uniform_with_unequal_delays_is_one_scene(capsys):
    code, out, _ = run(capsys, "derive", "multi-user", "--users", "3", "--uniform", "--delay", "1,2,5")
    assert code == 0 and "delays [1, 2, 5]" in out and "undecided" in out
    code, out, _ = run(capsys, "derive", "multi-user", "--users", "3", "--uniform", "--delay", "1,2,5", "--param",
                       "b=0.05", "--param", "K_0=2", "--param", "B_0=0", "--param", "K=1", "--param", "B=0",
                       "--param", "T=0.001")
    assert code == 0 and "verdict:           proved" in out


def test_version(capsys):
    with pytest.raises(SystemExit) as exit_:
        main(["--version"])
    assert exit_.value.code == 0 and capsys.readouterr().out.startswith("hapticproof ")


def test_outputs_checked_before_the_work_and_dash_is_stdout(tmp_path, capsys, monkeypatch):
    monkeypatch.chdir(tmp_path)
    err = one_line_error(capsys, "boundary", "single-user", "--param", "m=0.015", "--param", "b=0.02", "--param", "B=0",
                         "--vary", "K", "--over", "T=0.001:0.002:2", "--plot", "out.txt")
    assert "--plot out.txt" in err and not (tmp_path / "out.txt").exists()
    code, out, _ = run(capsys, "boundary", "single-user", "--param", "m=0.015", "--param", "b=0.02", "--param", "B=0",
                       "--vary", "K", "--over", "T=0.001:0.002:2", "--json", "-")
    assert code == 0 and not os.path.exists("-") and json.loads(out)["vary"] == "K"
    code, out, _ = run(capsys, "derive", "single-user", "-o", "-", "--format", "json")
    assert code == 0 and json.loads(out)["system"] == "single-user" and not os.path.exists("-")


def test_boundary_on_a_custom_environment_and_couplings(capsys):
    code, out, _ = run(capsys, "boundary", "single-user", "--environment", "K + B*(1-a)*(z-1)/(T*(z-a))",
                       "--param", "m=0.015", "--param", "b=0.02", "--param", "B=0.002", "--param", "a=1/2",
                       "--param", "T=0.001", "--vary", "K")
    assert code == 0 and out.startswith("K* = ")
    code, out, _ = run(capsys, "boundary", "multi-user", "--param", "m=0.015", "--param", "b=0.02", "--param", "B=0",
                       "--param", "B_0=0", "--param", "K_01=5", "--param", "K_02=20", "--param", "T=0.001",
                       "--vary", "K_12")
    assert code == 0 and out.startswith("K_12* = ")


def test_errors_are_hapticproof_errors():
    with pytest.raises(HapticproofError):
        Scene("single-user", delay="1.5")
    with pytest.raises(HapticproofError):
        Scene("multi-user", users=2, delay=[1, 2, 3])
    with pytest.raises(HapticproofError):
        Scene("single-user", environment="K + s")
    with pytest.raises(SceneError, match="did you mean 'positive'"):
        Scene("single-user", environment="K + M/z", params={"M": "postive"})
