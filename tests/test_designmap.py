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
from hapticproof.core.errors import InputFormatError


def pointwise(spec: dm.MapSpec) -> np.ndarray:
    out = np.zeros((len(spec.y.values), len(spec.x.values)), dtype=np.int8)
    for i, y in enumerate(spec.y.values):
        for j, x in enumerate(spec.x.values):
            params = dict(spec.fixed, **{spec.x.name: x, spec.y.name: y})
            if spec.quantity == "passivity":
                out[i, j] = dm._passive(dm._modes(params, spec.approximation))
            else:
                out[i, j] = dm._stability_point(params)
    return out


@pytest.mark.parametrize("x, y, fixed, approximation", [
    ("b=0.001:0.03:9", "K=0.5:10:6", {"T": "0.001", "B": "0.001", "delay": 3}, "forward"),
    ("T=0.0005:0.003:7", "K=0.5:20:6", {"b": "0.01", "B": "0.0005", "delay": 2}, "tustin"),
    ("K=0.2:30:9", "delay=0:8:5", {"b": "0.02", "B": "0.001", "T": "0.001"}, "backward"),
    ("z_a=0:0.01:5", "B=0:0.002:3", {"b": "0.012", "K": 2, "T": "0.001", "delay": 1}, "forward"),
])
def test_passivity_lines_equal_pointwise_decisions(x, y, fixed, approximation):
    spec = dm.MapSpec.build("passivity", x, y, fixed, approximation)
    result = dm.compute(spec)
    assert (result.values == pointwise(spec)).all()
    assert result.counts["undecided"] == 0 and 0 < result.counts["passive"] < spec.points


def test_users_map_equals_the_m_user_decision():
    from hapticproof.systems.multiuser import MultiUserScene
    from hapticproof.analysis.multiuser import positive_real

    spec = dm.MapSpec.build("passivity", "K=0.5:20:5", "users=1:4:4",
                            {"b": "0.05", "T": "0.001", "B": "0.001", "delay": 2, "K0": 1, "B0": "0.0005"})
    result = dm.compute(spec)
    for i, m in enumerate(spec.y.values):
        for j, K in enumerate(spec.x.values):
            scene = MultiUserScene.uniform(int(m), b=Fraction(5, 100), K0=1, B0=Fraction(5, 10000), K=K,
                                           B=Fraction(1, 1000), T=Fraction(1, 1000), delay=2)
            assert result.values[i, j] == (positive_real(scene).decision.value == "proved")
    assert 0 < result.counts["passive"] < spec.points


def test_stability_lines_equal_pointwise_certified_radii():
    for x, fixed in (("T=0.0005:0.004:5", {"m": "0.015", "b": "0.02", "B": "0.002"}),
                     ("delay=0:4:3", {"m": "0.015", "b": "0.02", "B": "0.001", "T": "0.001"})):
        spec = dm.MapSpec.build("stability", x, "K=1:60:7", fixed)
        assert (dm.compute(spec).values == pointwise(spec)).all()


def test_serial_processes_and_dask_write_the_same_file(tmp_path):
    pytest.importorskip("distributed")
    from distributed import Client, LocalCluster

    spec = dm.MapSpec.build("passivity", "b=0.001:0.04:15", "K=0.5:12:12", {"T": "0.001", "B": "0.001", "delay": 2})
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
                         (("passivity", "b=1:2:3", "K=1:2:2", {}), "needs --param T=..."),
                         (("passivity", "b=1:2", "K=1:2:2", {"T": 1}), "start:stop:count"),
                         (("stability", "K=1:2:2", "T=0:1:2", {"m": 1, "b": 1}), "T must be positive"),
                         (("passivity", "b=1:2:3", "delay=0:1.5:2", {"T": 1, "K": 1}), "non-negative integer"),
                         (("passivity", "b=1:2:3", "K=1:2:2", {"T": 1, "K0": 1}), "K0 and B0")):
        with pytest.raises(InputFormatError, match=message):
            dm.MapSpec.build(*bad)


def test_cli_map(tmp_path, capsys):
    out = tmp_path / "m.csv"
    assert main(["map", "passivity", "--x", "b=0.001:0.003:3", "--y", "K=1:3:3", "--param", "T=0.001",
                 "-o", str(out), "--plot", str(tmp_path / "m.png")]) == 0
    assert out.read_text().splitlines()[1:4] == ["0.001,1,1", "0.002,1,1", "0.003,1,1"]
    assert (tmp_path / "m.png").stat().st_size > 0
    assert main(["map", "passivity", "--x", "b=1:2:3", "--y", "K=1:2:2"]) == 2
    assert "needs --param" in capsys.readouterr().err
    assert main(["map", "stability", "--x", "K=1:2:2", "--y", "T=0.001:0.002:2", "--param", "m=1",
                 "--param", "b=1", "--scheduler", "nowhere"]) == 2
    assert "--scheduler" in capsys.readouterr().err
