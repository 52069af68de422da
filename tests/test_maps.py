"""Boundary search, curves, maps, printed borderlines and the ``boundary`` CLI."""

from __future__ import annotations

import csv

import numpy as np
import pytest

import hapticproof.analysis.maps as maps
from hapticproof.analysis.borderlines import CONDITIONS, printed_borderline, printed_condition
from hapticproof.cli import main
from hapticproof.analysis.maps import SceneFamily, boundary_curve, find_boundary, stability_map
from hapticproof.analysis.sampled import free_device_boundary

FREE = SceneFamily("single-user", {"m": 0.015, "b": 0.02, "B": 0})


def test_multiple_crossings_are_reported(monkeypatch):
    """A synthetic rho(K) = 1 + (K-1)(K-2)(K-3)/10: stable, unstable, stable, unstable."""
    rho = lambda k: 1 + (k - 1) * (k - 2) * (k - 3) / 10  # noqa: E731
    monkeypatch.setattr(maps, "trusted_radius", lambda scene, **kw: rho(float(scene.K)))
    monkeypatch.setattr(maps, "trusted_radii", lambda scenes: np.array([rho(float(s.K)) for s in scenes]))
    # the certified route (both sides of each crossing): the same function's sign
    monkeypatch.setattr(maps, "certified_stability", lambda scene, **kw: rho(float(scene.K)) < 1)
    bnd = find_boundary(FREE, "K", at={"T": 0.001}, search=(0.1, 10), rtol=1e-12)
    assert [round(c.value, 9) for c in bnd.crossings] == [1, 2, 3]
    assert [c.direction for c in bnd.crossings] == ["destabilising", "stabilising", "destabilising"]
    assert bnd.value == pytest.approx(1, abs=1e-9) and bnd.multiple and bnd.stable_at_start


def test_varying_damping_gives_a_stabilising_crossing():
    fam = SceneFamily("single-user", {"m": 0.015, "K": 20, "B": 0})
    bnd = find_boundary(fam, "b", at={"T": 0.001}, rtol=1e-12)
    assert bnd.direction == "stabilising" and not bnd.stable_at_start
    # at that damping, K = 20 is exactly the boundary
    assert free_device_boundary(0.015, bnd.value, 0.001) == pytest.approx(20, rel=1e-9)


def test_no_crossing_when_always_unstable():
    fam = SceneFamily("single-user", {"m": 0.015, "b": 0.01, "B": 0, "z_a": 0.02},
                      operator="-z_a + 1/s")
    bnd = find_boundary(fam, "K", at={"T": 0.001})
    assert bnd.value is None and not bnd.stable_at_start


def test_curve_is_deterministic_across_workers():
    grid = [0.001, 0.004, 0.009]
    one = boundary_curve(FREE, "K", ("T", grid), workers=1)
    two = boundary_curve(FREE, "K", ("T", grid), workers=2)
    assert one.exact.tolist() == two.exact.tolist()


def test_stability_map_agrees_with_boundary():
    ks = np.array([10.0, 35.0, 39.9, 40.1, 60.0])
    plane = stability_map(FREE, ("T", [0.001]), ("K", ks), workers=1)
    assert plane.good[:, 0].tolist() == (ks < free_device_boundary(0.015, 0.02, 0.001)).tolist()


@pytest.mark.parametrize(
    "family, key",
    [
        (FREE, "hve-20"),
        (SceneFamily("single-user", {"m": 1, "b": 1}, delay=3), "hve-25"),
        (SceneFamily("single-user", {"m": 1, "b": 1}, operator="1/s"), "hve-26"),
        (SceneFamily("single-user", {"m": 1, "b": 1}, operator="1/s", delay=2), "hve-27"),
        (SceneFamily("multi-user", {"m": 1, "b": 1}), "hve-55"),
        (SceneFamily("multi-user", {"m": 1, "b": 1}, delay=5), "hve-63"),
        (SceneFamily("teleoperator", {"m": 1, "b": 1}), "tele-35"),
    ],
)
def test_printed_condition_mapping(family, key):
    assert printed_condition(family) == CONDITIONS[key]


def test_printed_borderlines_are_solved_exactly():
    values = {"b": 0.02, "B": 0.001, "T": 0.002, "z_a": 0.005, "t_d": 0.02, "users": 2.0}
    op = SceneFamily("single-user", {"m": 1, "b": 1}, operator="-z_a + 1/s")
    assert printed_borderline(op, "K")(values) == pytest.approx(2 * (0.02 - 0.005 - 0.001) / 0.002)
    assert printed_borderline(op, "b")({**values, "K": 5}) == pytest.approx(0.005 + 5 * 0.001 + 0.001)
    delayed = SceneFamily("single-user", {"m": 1, "b": 1}, operator="-z_a + 1/s", delay=10)
    assert printed_borderline(delayed, "K")(values) == pytest.approx((0.02 - 0.005 + 0.001) / 0.021)
    dual = SceneFamily("multi-user", {"m": 1, "b": 1})
    # (55) with K_0i = K_ij = K/2: b - z_a > KT/4 + B/2 + 2 (KT/4 + B/2)
    assert printed_borderline(dual, "K")(values) == pytest.approx((0.015 - 1.5 * 0.001) * 4 / (3 * 0.002))
    tele = SceneFamily("teleoperator", {"m": 1, "b": 1})
    assert printed_borderline(tele, "T")({"b": 0.02, "K": 2, "B": 0.001}) == pytest.approx(0.009)


def test_printed_values_use_the_shortage_of_passivity():
    fam = SceneFamily("single-user", {"m": 1, "b": 1}, operator="-0.25 + 1/s", delay=4)
    v = fam.printed_values(T=0.01)
    assert v["z_a"] == 0.25 and v["t_d"] == pytest.approx(0.04)


def test_cli_writes_csv_matching_the_api(tmp_path, capsys):
    out = tmp_path / "k.csv"
    png = tmp_path / "k.png"
    code = main([
        "boundary", "single-user", "--param", "m=0.015", "--param", "b=0.02", "--param", "B=0",
        "--operator", "-z_a + 1/s", "--param", "z_a=0.01", "--vary", "K",
        "--over", "T=0.001:0.02:3", "--csv", str(out), "--plot", str(png), "--no-progress",
    ])
    assert code == 0 and png.stat().st_size > 1000
    rows = list(csv.DictReader(out.open()))
    assert list(rows[0]) == ["T", "K_exact", "K_printed"]
    fam = SceneFamily("single-user", {"m": 0.015, "b": 0.02, "B": 0, "z_a": 0.01}, operator="-z_a + 1/s")
    for row in rows:
        T = float(row["T"])
        assert float(row["K_printed"]) == pytest.approx(2 * (0.02 - 0.01) / T)
        assert float(row["K_exact"]) == pytest.approx(find_boundary(fam, "K", at={"T": T}).value, rel=1e-9)


def test_cli_leaves_printed_empty_where_no_condition_applies(tmp_path):
    out = tmp_path / "t.csv"
    code = main([
        "boundary", "teleoperator", "--param", "m=0.015", "--param", "b=0.01822", "--param", "alpha=2",
        "--vary", "K", "--over", "T=0.005:0.01:2", "--csv", str(out), "--no-progress",
    ])
    assert code == 0
    rows = list(csv.DictReader(out.open()))
    assert [r["K_printed"] for r in rows] == ["", ""] and all(float(r["K_exact"]) > 0 for r in rows)


@pytest.mark.parametrize(
    "argv",
    [
        ["single-user", "--param", "m=0", "--param", "b=1", "--vary", "K", "--over", "T=0.001:0.002:2"],
        ["single-user", "--param", "m=1", "--param", "b=1", "--operator", "exp(s)", "--vary", "K",
         "--over", "T=0.001:0.002:2"],
        ["single-user", "--param", "m=1", "--param", "b=1", "--vary", "K", "--over", "T=0.001:2"],
        ["single-user", "--param", "m=1", "--param", "b=1", "--param", "x=1", "--vary", "K",
         "--over", "T=0.001:0.002:2"],
        ["multi-user", "--param", "m=1", "--param", "b=1", "--environment", "clamped", "--vary", "K",
         "--over", "T=0.001:0.002:2"],
    ],
)
def test_cli_user_errors_exit_2(argv, capsys):
    assert main(["boundary", *argv, "--no-progress"]) == 2
    err = capsys.readouterr().err
    assert err.startswith("hapticproof: error:") and len(err.strip().splitlines()) == 1
