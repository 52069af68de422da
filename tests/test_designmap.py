"""Exact design-space maps: every point equals its own exact decision, in every mode.

The line tricks (one critical damping per ``b`` line, convexity along ``K``/``B``/``T``, one
crossing analysis per stability line) are checked against point-by-point decisions; the serial,
process-pool and Dask (a small ``LocalCluster``) runs must write byte-identical CSV files.
"""

from __future__ import annotations

from fractions import Fraction

import numpy as np
import pytest

from hapticproof.analysis import designmap as dm
from hapticproof.cli import main
from hapticproof.core.errors import HapticproofError
from hapticproof.systems.scene import Scene


def decision_at(spec: dm.MapSpec, values: dict) -> int:
    """The point's own exact decision, through the public entry points of the scene model."""
    scene = spec.at(values)
    model = scene.build()
    if spec.quantity == "passivity":
        if scene.system == "single-user":
            from hapticproof.analysis.positivereal import positive_real
        elif scene.system == "multi-user":
            from hapticproof.analysis.multiuser import positive_real
        else:
            from hapticproof.analysis.teleoperator import passivity as positive_real
        decision = positive_real(model).decision.value
    elif scene.environment is None and scene.system == "single-user" and scene.operator is None:
        from hapticproof.analysis.boundary import certified_stable

        v = scene.resolved_values()
        decision = certified_stable(v[scene.role("mass")], model.b, model.T, v["K"], v.get("B", 0),
                                    int(model.delay)).decision.value
    else:
        from hapticproof.analysis.sampled import spectral_radius
        from hapticproof.analysis.stability import SceneLoops

        rho = spectral_radius(SceneLoops(scene).scene(), precision="mp", dps=40)
        decision = "proved" if rho < 1 - 1e-25 else "disproved" if rho > 1 + 1e-25 else "undecided"
    return {"proved": 1, "disproved": 0}.get(decision, -1)


def pointwise(spec: dm.MapSpec) -> np.ndarray:
    out = np.zeros((len(spec.y.values), len(spec.x.values)), dtype=np.int8)
    for i, y in enumerate(spec.y.values):
        for j, x in enumerate(spec.x.values):
            out[i, j] = decision_at(spec, {spec.x.name: x, spec.y.name: y})
    return out


def wall(approximation="forward", delay=0, **params):
    return Scene("single-user", approximation=approximation, delay=delay, params=params)


@pytest.mark.parametrize("x, y, scene", [
    ("b=0.001:0.03:9", "K=0.5:10:6", wall(T="0.001", B="0.001", delay=3)),
    ("T=0.0005:0.003:7", "K=0.5:20:6", wall("tustin", 2, b="0.01", B="0.0005")),
    ("K=0.2:30:9", "delay=0:8:5", wall("backward", b="0.02", B="0.001", T="0.001")),
    ("z_a=0:0.01:5", "B=0:0.002:3", wall(delay=1, b="0.012", K=2, T="0.001")),
    # any environment, own names and roles, expressions as values
    ("K=1:60:7", "a=0:0.9:4", Scene("single-user", environment="K + B*(1 - a)*(z - 1)/(T*(z - a))",
                                    params={"B": "0.005", "b": "0.02", "T": "0.001"})),
    ("b_dev=0.001:0.04:6", "K=1:30:5", Scene("single-user", roles={"period": "Ts", "device_damping": "b_dev"},
                                              delay=2, params={"Ts": "0.001", "B": "Bw/2", "Bw": "0.002"})),
])
def test_passivity_lines_equal_pointwise_decisions(x, y, scene):
    spec = dm.MapSpec.build("passivity", x, y, scene)
    result = dm.compute(spec)
    assert (result.values == pointwise(spec)).all()
    assert result.counts["undecided"] == 0 and 0 < result.counts["passive"] < spec.points


def test_users_map_equals_the_m_user_decision():
    from hapticproof.analysis.multiuser import positive_real
    from hapticproof.systems.multiuser import MultiUserScene

    scene = Scene("multi-user", uniform=True, delay=2,
                  params={"b": "0.05", "T": "0.001", "B": "0.001", "K_0": 1, "B_0": "0.0005"})
    spec = dm.MapSpec.build("passivity", "K=0.5:20:5", "users=1:4:4", scene)
    result = dm.compute(spec)
    for i, m in enumerate(spec.y.values):
        for j, K in enumerate(spec.x.values):
            model = MultiUserScene.uniform(int(m), b=Fraction(5, 100), K0=1, B0=Fraction(5, 10000), K=K,
                                           B=Fraction(1, 1000), T=Fraction(1, 1000), delay=2)
            assert result.values[i, j] == (positive_real(model).decision.value == "proved")
    assert 0 < result.counts["passive"] < spec.points


def test_multi_user_and_teleoperator_lines_equal_pointwise_decisions():
    users = Scene("multi-user", users=2, params={"b": "0.02", "T": "0.001", "B": 0, "B_0": 0, "K_0": "K/2"})
    spec = dm.MapSpec.build("passivity", "K=1:40:6", "b_2=0.005:0.03:3", users)
    assert (dm.compute(spec).values == pointwise(spec)).all()
    tele = Scene("teleoperator", roles={"slave_damping": "c_s"}, params={"K": 20, "B": "0.01", "T": "0.001"})
    spec = dm.MapSpec.build("passivity", "c_s=0.001:0.05:6", "b_m=0.001:0.05:3", tele)
    result = dm.compute(spec)
    assert (result.values == pointwise(spec)).all() and 0 < result.counts["passive"] < spec.points


def test_stability_lines_equal_pointwise_certified_radii():
    for x, scene in (("T=0.0005:0.004:5", wall(m="0.015", b="0.02", B="0.002")),
                     ("delay=0:4:3", wall(m="0.015", b="0.02", B="0.001", T="0.001")),
                     ("M=0.01:0.03:3", Scene("single-user", roles={"mass": "M"}, params={"b": "0.02", "T": "0.001"}))):
        spec = dm.MapSpec.build("stability", x, "K=1:60:7", scene)
        assert (dm.compute(spec).values == pointwise(spec)).all()
    filtered = Scene("single-user", environment="K + B*(1 - a)*(z - 1)/(T*(z - a))",
                     params={"B": "0.005", "b": "0.02", "T": "0.001", "m": "0.015", "a": "0.5"})
    spec = dm.MapSpec.build("stability", "K=10:80:4", "a=0:0.8:2", filtered)
    result = dm.compute(spec)
    assert (result.values == pointwise(spec)).all() and 0 < result.counts["stable"] < spec.points


def test_serial_processes_and_dask_write_the_same_file(tmp_path):
    pytest.importorskip("distributed")
    from distributed import Client, LocalCluster

    spec = dm.MapSpec.build("passivity", "b=0.001:0.04:15", "K=0.5:12:12", wall(delay=2, T="0.001", B="0.001"))
    files = {}
    for mode in ("serial", "processes", "dask"):
        sink = dm.MapWriter(tmp_path / f"{mode}.csv", spec)
        if mode == "dask":
            with LocalCluster(n_workers=1, threads_per_worker=1, processes=True, dashboard_address=None) as cluster, \
                    Client(cluster) as client:
                result = dm.compute(spec, client=client, lines_per_chunk=4, sink=sink)
        else:
            result = dm.compute(spec, workers=2 if mode == "processes" else 1, lines_per_chunk=4, sink=sink)
        sink.close()
        files[mode] = (tmp_path / f"{mode}.csv").read_text()
        assert result.values.shape == (12, 15)
    assert files["serial"] == files["processes"] == files["dask"]
    assert files["serial"] == dm.write_map(result)
    assert files["serial"].splitlines()[0] == "b,K,passive"


def test_exact_grid_values_and_user_mistakes():
    assert dm.Axis.parse("b=0.001,0.002").values == (Fraction(1, 1000), Fraction(1, 500))
    for bad, message in ((("passivity", "b=1:2:3", "Q=1:2:2", {}), "unknown parameter 'Q'"),
                         (("passivity", "b=1:2:3", "K=1:2:2", {}), "needs numbers for T"),
                         (("passivity", "b=1:2", "K=1:2:2", {"T": 1}), "start:stop:count"),
                         (("stability", "K=1:2:2", "T=0:1:2", {"m": 1, "b": 1}), "sampling period T must be positive"),
                         (("passivity", "b=1:2:3", "delay=0:1.5:2", {"T": 1, "K": 1}), "non-negative integer"),
                         (("passivity", "b=1:2:3", "users=1:2:2", {"T": 1, "K": 1}), "multi-user"),
                         (("passivity", "b=1:2:3", "m=1:2:2", {"T": 1, "K": 1}), "does not enter the passivity"),
                         (("passivity", "b=1:2:3", "K=nan,1", {"T": 1}), "'nan' is not a number"),
                         (("stability", "b=1:2:3", "K=1:2:2", {"T": 1}), "the device mass m")):
        with pytest.raises(HapticproofError, match=message):
            dm.MapSpec.build(*bad)


def test_cli_map(tmp_path, capsys):
    out = tmp_path / "m.csv"
    assert main(["map", "passivity", "--x", "b=0.001:0.003:3", "--y", "K=1:3:3", "--param", "T=0.001",
                 "-o", str(out), "--plot", str(tmp_path / "m.png")]) == 0
    assert out.read_text().splitlines()[1:4] == ["0.001,1,1", "0.002,1,1", "0.003,1,1"]
    assert (tmp_path / "m.png").stat().st_size > 0
    assert main(["map", "passivity", "--x", "b=1:2:3", "--y", "K=1:2:2"]) == 2
    assert "needs numbers for T" in capsys.readouterr().err
    assert main(["map", "stability", "--x", "K=1:2:2", "--y", "T=0.001:0.002:2", "--param", "m=1",
                 "--param", "b=1", "--scheduler", "nowhere"]) == 2
    assert "--scheduler" in capsys.readouterr().err


def test_cli_map_takes_the_scene_model(tmp_path, capsys):
    """--scene, derive's names (K_0, not K0), --delay, roles, expressions as values."""
    scene = tmp_path / "wall.toml"
    scene.write_text('system = "single-user"\nenvironment = "K + B*(1 - a)*(z - 1)/(T*(z - a))"\n'
                     '[params]\nB = 0.005\nb = 0.02\nT = 0.001\n')
    assert main(["map", "passivity", "--scene", str(scene), "--x", "K=30:40:3", "--y", "a=0.5"]) == 0
    assert capsys.readouterr().out.splitlines()[1:] == ["30,0.5,1", "35,0.5,1", "40,0.5,0"]    # K_max = 110/3
    assert main(["map", "passivity", "multi-user", "--uniform", "--x", "K=1:20:3", "--y", "users=1:3:3",
                 "--param", "b=0.05", "--param", "T=0.001", "--param", "B=0.001", "--param", "K_0=Kw/2",
                 "--param", "Kw=2"]) == 0
    assert capsys.readouterr().out.startswith("K,users,passive\n")
    assert main(["map", "passivity", "--x", "b_dev=0.001:0.003:3", "--y", "K=1:3:3", "--role", "device_damping=b_dev",
                 "--role", "period=Ts", "--param", "Ts=0.001"]) == 0
    assert capsys.readouterr().out.splitlines()[7:10] == ["0.001,3,0", "0.002,3,1", "0.003,3,1"]
    assert main(["map", "passivity", "multi-user", "--x", "K=1:2:2", "--y", "users=1:2:2", "--param", "K0=1"]) == 2
    assert "unknown parameter 'K0'" in capsys.readouterr().err
