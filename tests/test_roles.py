"""Issue 21 (part B, item 1): the device damping, period and mass are roles a scene assigns to any
of the user's names, and every answer (derive, --range, --delay-margin, boundary, scene files,
paper files) follows them. A scene in its own names gets exactly the answers of the same scene in
the papers' names."""

import json
import sys
from pathlib import Path

import pytest
import sympy as sp

from hapticproof.analysis.design import delay_margin
from hapticproof.analysis.passiverange import passive_range
from hapticproof.analysis.positivereal import positive_real
from hapticproof.audit.paperfile import loads as load_paper
from hapticproof.audit.runner import audit_paper
from hapticproof.core.errors import SceneError
from hapticproof.systems.roles import ROLES
from hapticproof.systems.scene import Scene, SceneFileError, loads

sys.path.insert(0, str(Path(__file__).resolve().parent))

from clirun import one_line_error, run  # noqa: E402

R = sp.Rational


WALL = {"K": 2, "B": "0.001", "T": "0.001", "b": "0.02"}
OWN = {"K": 2, "B": "0.001", "Ts": "0.001", "b_dev": "0.02"}
OWN_ROLES = {"period": "Ts", "device_damping": "b_dev"}


def test_default_roles_are_the_papers_names():
    assert {f: r.default for f, r in ROLES["single-user"].items()} == {"device_damping": "b", "period": "T", "mass": "m"}
    assert Scene("single-user", roles={"period": "T", "device_damping": "b"}) == Scene("single-user")
    assert Scene("single-user").roles == ()


def test_a_renamed_period_is_the_models_positive_period():
    model = Scene("single-user", roles={"period": "Ts"}).build()
    Ts = sp.Symbol("Ts", positive=True)
    assert model.T == Ts and Ts in model.parameters and sp.Symbol("T", positive=True) not in model.parameters
    # the default wall is written with the period's name
    K, B = sp.Symbol("K", positive=True), sp.Symbol("B", nonnegative=True)
    assert sp.cancel(model.H - (K + B * (sp.Symbol("z") - 1) / (Ts * sp.Symbol("z")))) == 0


def test_own_names_give_the_same_exact_answers():
    mine = Scene("single-user", roles=OWN_ROLES, params=OWN)
    papers = Scene("single-user", params=WALL)
    assert positive_real(mine.build()).decision == positive_real(papers.build()).decision
    assert delay_margin(mine).margin == delay_margin(papers).margin == 10
    assert delay_margin(mine).time_margin() == R(1, 100)
    assert passive_range(mine, "b_dev").minimum().value == passive_range(papers, "b").minimum().value == R(1, 500)
    assert passive_range(mine, "Ts").maximum().value == passive_range(papers, "T").maximum().value == R(19, 1000)


def test_derive_cli_range_and_margin_follow_the_roles(capsys):
    code, out, err = run(capsys, "derive", "single-user", "--role", "period=Ts", "--role", "device_damping=b_dev",
                         *[a for k, v in OWN.items() for a in ("--param", f"{k}={v}")],
                         "--range", "b_dev", "--range", "Ts", "--delay-margin", "--format", "json")
    assert code == 0, err
    data = json.loads(out)
    assert data["verdict"] == "proved" and data["delay_margin"]["margin"] == 10
    assert data["passive_ranges"]["b_dev"]["intervals"][0]["lo"] == {"exact": "1/500"}
    assert data["passive_ranges"]["Ts"]["intervals"][0]["hi"] == {"exact": "19/1000"}


def test_a_default_name_no_longer_in_its_role_is_one_line_with_the_hint(capsys):
    err = one_line_error(capsys, "derive", "single-user", "--role", "device_damping=b_dev", "--param", "b=0.02")
    assert "unknown parameter 'b'" in err and "device_damping = 'b_dev'" in err


def test_boundary_reads_mass_damping_and_period_from_their_roles(capsys):
    code, own, _ = run(capsys, "boundary", "single-user", "--role", "mass=M", "--role", "period=Ts",
                       "--role", "device_damping=b_dev", "--param", "M=0.015", "--param", "b_dev=0.02",
                       "--param", "B=0", "--param", "Ts=0.001", "--vary", "K")
    code2, papers, _ = run(capsys, "boundary", "single-user", "--param", "m=0.015", "--param", "b=0.02",
                           "--param", "B=0", "--param", "T=0.001", "--vary", "K")
    assert code == code2 == 0 and own == papers and own.startswith("K* = 40.0088908")
    # sweeping the period by its name, next to the printed borderline K = 2 b/T (the paper's names)
    code, out, _ = run(capsys, "boundary", "single-user", "--role", "period=Ts", "--param", "m=0.015", "--param",
                       "b=0.02", "--param", "B=0", "--vary", "K", "--over", "Ts=0.001:0.002:2")
    rows = out.splitlines()
    assert code == 0 and rows[0].split()[0] == "Ts" and rows[1].split()[2] == "40"


def test_scene_files_carry_roles_and_round_trip(tmp_path):
    text = ('system = "single-user"\n\n[roles]\nperiod = "Ts"\ndevice_damping = "b_dev"\n\n'
            '[params]\nTs = 0.001\nb_dev = 0.02\nK = 2\nB = 0.001\n')
    scene = loads(text, "mine.toml")
    assert scene.role("period") == "Ts" and scene.role("device_damping") == "b_dev"
    assert Scene.from_toml(scene.to_toml()) == scene
    assert scene == Scene("single-user", roles=OWN_ROLES, params=OWN)
    path = tmp_path / "mine.toml"
    path.write_text(text)
    assert delay_margin(Scene.read(path)).margin == 10


@pytest.mark.parametrize("roles, message, line", [
    ('period = "b"', "'b' names both the device damping and the sampling period", 3),
    ('mass = "M"\nperiodd = "Ts"', "unknown role 'periodd' of a single-user scene", 4),
    ('period = "z_a"', "'z_a' is the operator's shortage of passivity", 3),
    ('period = "2T"', "is not a parameter name", 3),
    ('period = ["T1", "T2"]', "one name (a list gives one name per user", 3),
])
def test_role_mistakes_name_file_and_line(roles, message, line):
    with pytest.raises(SceneFileError) as err:
        loads(f'system = "single-user"\n[roles]\n{roles}\n', "x.toml")
    assert message in str(err.value) and str(err.value).startswith(f"x.toml:{line}: roles:")


def test_multi_user_group_and_per_user_names():
    params = {"c": "0.02", "c_2": "0.03", "K_0": 1, "B_0": 0, "K": 2, "B": 0, "Ts": "0.001"}
    own = Scene("multi-user", users=3, roles={"device_damping": "c", "period": "Ts"}, params=params).build()
    papers = Scene("multi-user", users=3, params={("b" if k == "c" else "b_2" if k == "c_2" else "T" if k == "Ts" else k): v
                                                 for k, v in params.items()}).build()
    assert own.b == papers.b == (R(1, 50), R(3, 100), R(1, 50)) and own.T == papers.T == R(1, 1000)
    from hapticproof.analysis.multiuser import positive_real as multi_positive_real

    assert own.is_numeric and multi_positive_real(own).decision == multi_positive_real(papers).decision
    listed = Scene("multi-user", users=2, roles={"device_damping": ["b_left", "b_right"]}).build()
    assert [s.name for s in listed.b] == ["b_left", "b_right"] and all(s.is_positive for s in listed.b)
    with pytest.raises(SceneError, match="2 names for 3 users"):
        Scene("multi-user", users=3, roles={"device_damping": ["x", "y"]})
    with pytest.raises(SceneError, match="a uniform scene has one device damping"):
        Scene("multi-user", users=2, uniform=True, roles={"device_damping": ["x", "y"]})
    with pytest.raises(SceneError, match="group name of the m-user couplings"):
        Scene("multi-user", roles={"device_damping": "K"})


def test_multi_user_masses_by_role_in_the_boundary(capsys):
    common = ["boundary", "multi-user", "--uniform", "--param", "B_0=0", "--param", "B=0", "--param", "K_0=K/2",
              "--vary", "K", "--delay", "0,1"]
    code, own, _ = run(capsys, *common, "--role", "mass=M", "--role", "period=Ts", "--role", "device_damping=d",
                       "--param", "M=0.015", "--param", "d=0.02", "--param", "Ts=0.001")
    code2, papers, _ = run(capsys, *common, "--param", "m=0.015", "--param", "b=0.02", "--param", "T=0.001")
    assert code == code2 == 0 and own == papers and own.startswith("K* = 8.0042")


def test_teleoperator_master_and_slave_roles():
    own = Scene("teleoperator", roles={"master_damping": "c_m", "slave_damping": "c_s", "period": "Ts"},
                params={"c_m": "0.5", "c_s": "0.3", "K": 20, "B": "0.01", "Ts": "0.001"})
    papers = Scene("teleoperator", params={"b_m": "0.5", "b_s": "0.3", "K": 20, "B": "0.01", "T": "0.001"})
    mo, mp = own.build(), papers.build()
    assert (mo.b_m, mo.b_s, mo.T) == (mp.b_m, mp.b_s, mp.T) == (R(1, 2), R(3, 10), R(1, 1000))
    lo_own = passive_range(own.with_params(c_s=None), "c_s").minimum()
    lo_papers = passive_range(papers.with_params(b_s=None), "b_s").minimum()
    assert lo_own == lo_papers


def test_paper_file_scenes_take_roles_and_get_the_verdicts_of_the_papers_names():
    text = '''
[paper]
id = "roles-demo"
title = "A wall in the author's notation"

[symbols]
b_d = "positive"
K = "positive"
B = "real"
T_s = "positive"

[scenes.wall]
system = "single-user"
environment = "K + B*(z - 1)/(T_s*z)"
[scenes.wall.roles]
device_damping = "b_d"
period = "T_s"

[[equations]]
id = "1"
printed = 'b_d > \\frac{K T_s}{2} + |B|'
claim = "passivity-condition"
scene = "wall"

[[equations]]
id = "2"
printed = 'b_d > K T_s + |B|'
claim = "passivity-condition"
scene = "wall"

[[equations]]
id = "3"
printed = 'b_d > \\frac{K T_s}{2} - |B|'
claim = "passivity-condition"
scene = "wall"
'''
    report = audit_paper(load_paper(text, "roles.toml").paper)
    verdicts = {r.id: r.verdict.value for r in report.results}
    # (2) K T_s for K T_s/2: halving the term makes it exact (the repair search's lost half)
    assert verdicts == {"1": "confirmed", "2": "typo", "3": "typo"}


@pytest.mark.parametrize("system, field, name, design", [
    ("single-user", "device_damping", "K", {}),                                      # the wall's stiffness
    ("single-user", "mass", "k", {"environment": "k + c*(z - 1)/(T*z)"}),
    ("teleoperator", "master_damping", "K", {}),                                     # the PD controller's gain
    ("teleoperator", "mass", "K_p", {"controller": "K_p + K_i*T*z/(z - 1)"}),
])
def test_a_role_named_like_a_parameter_of_the_design_is_refused(system, field, name, design):
    """One name, one meaning: the device damping called K where K is the wall's stiffness would
    make b = K silently; the period alone belongs to the role and the design."""
    with pytest.raises(SceneError, match=rf"roles: {field} = '{name}', but {name} is already a parameter"):
        Scene(system, roles={field: name}, **design).build()
    renamed = Scene(system, roles={"period": "h"}, **{k: v.replace("T", "h") for k, v in design.items()}).build()
    assert renamed is not None


def test_the_symbolic_delays_pole_at_zero_shows_its_multiplicity_as_a_formula(capsys):
    for approximation, formula in (("forward", "n + 1"), ("backward", "n"), ("tustin", "n + 1")):
        code, out, _ = run(capsys, "derive", "single-user", "--delay", "n", "--approximation", approximation,
                           "--format", "json")
        assert code == 0
        assert json.loads(out)["poles"][0] == {"z": "0", "multiplicity": formula, "location": "inside"}
    code, out, _ = run(capsys, "derive", "single-user", "--delay", "n", "--approximation", "backward",
                       "--environment", "K*z/(z - 1/2)")
    assert "z = 0 (inside, multiplicity n - 2 (for n > 2))" in out
