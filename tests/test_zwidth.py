"""The Z-width of a device (issue 29): its passive region against the closed forms of each model, its
stability boundary against an independent exact-ZOH oracle (mpmath, nothing from hapticproof), the
maps' grid verdicts point by point, the CSV, the plot, the command line and the note of ``derive``
when the model's passivity reaches past the exact loop's stability."""

from __future__ import annotations

import csv
import io
import json
import sys
from fractions import Fraction
from pathlib import Path

import mpmath as mp
import pytest
import sympy as sp

from hapticproof.analysis.zwidth import zwidth
from hapticproof.systems.scene import Scene

sys.path.insert(0, str(Path(__file__).resolve().parent))

from clirun import one_line_error, run  # noqa: E402

DEVICE = {"b": "0.02", "T": "0.001", "m": "0.015"}
b, T, m = Fraction(1, 50), Fraction(1, 1000), Fraction(3, 200)


def zoh_radius(K, B=0, n=0, mass=m, damping=b, period=T, dps=30):
    """The spectral radius of the device's exact ZOH loop on the wall ``z^-n (K + B(z - 1)/(Tz))``,
    from the matrix exponential of the continuous device (mpmath at ``dps`` digits; independent of the
    toolkit): the state is the position, the velocity and the n + 1 previous positions."""
    with mp.workdps(dps):
        mm, bb, TT, KK, BB = (mp.mpf(Fraction(v).numerator) / Fraction(v).denominator
                              for v in (mass, damping, period, Fraction(K), Fraction(B)))
        E = mp.expm(mp.matrix([[0, 1, 0], [0, -bb / mm, 1 / mm], [0, 0, 0]]) * TT)   # Phi and Gamma at once
        size = 3 + n
        M = mp.zeros(size, size)
        for i in range(2):
            for j in range(2):
                M[i, j] = E[i, j]

        def column(lag):                                   # where x_{k - lag} is in the state
            return 0 if lag == 0 else 1 + lag

        force = {column(n): -(KK + BB / TT)}
        force[column(n + 1)] = force.get(column(n + 1), 0) + BB / TT
        for col, c in force.items():
            for i in range(2):
                M[i, col] += E[i, 2] * c
        M[2, 0] = 1
        for j in range(1, n + 1):
            M[2 + j, 1 + j] = 1
        return max(abs(e) for e in mp.eig(M, left=False, right=False))


@pytest.fixture(scope="module")
def forward():
    return zwidth(Scene("single-user", params=DEVICE), stiffness="K=0:60:13", damping="B=-0.01:0.02:7")


def test_the_forward_model_is_colgate_and_schenkels_region(forward):
    # passive iff b >= KT/2 + |B|: K_max = 2(b - |B|)/T exactly, empty when |B| >= b
    for line in forward.lines:
        expected = 2 * (b - abs(line.damping)) / T
        if expected > 0:
            assert line.passive_max.value == sp.Rational(expected.numerator, expected.denominator)
            assert line.passive.intervals[-1][3]                          # the boundary itself is passive
        else:
            assert line.passive.is_empty()
    # and every point of the passivity map, decided exactly
    spec = forward.passivity.spec
    for i, B in enumerate(spec.y.values):
        for j, K in enumerate(spec.x.values):
            assert forward.passivity.values[i, j] == int(b >= K * T / 2 + abs(B)), (K, B)


@pytest.mark.parametrize("approximation", ["backward", "tustin"])
def test_the_backward_and_tustin_models_are_passive_for_every_stiffness(approximation):
    # Re G^-1 = b + KT/2 + B (backward), b + B(1 + c)/2 (Tustin): positive for B >= 0 whatever K
    zw = zwidth(Scene("single-user", approximation=approximation, params=DEVICE), stiffness="K=0:100:5",
                damping="B=0:0.02:3")
    assert all(line.passive_unbounded for line in zw.lines)
    assert (zw.passivity.values == 1).all()
    assert all(line.exceeds() for line in zw.lines)      # the exact loop is not stable for every K


def test_the_stability_boundary_is_the_exact_loops(forward):
    for line in forward.lines:
        K_star, tol = line.stable_max, line.stable_tolerance
        assert tol < 1e-9 * K_star
        assert zoh_radius(Fraction(K_star) * (1 - Fraction(1, 10**6)), line.damping) < 1
        assert zoh_radius(Fraction(K_star) * (1 + Fraction(1, 10**6)), line.damping) > 1


def test_the_undelayed_free_wall_boundary_is_the_closed_form(forward):
    # B = 0, n = 0: K* = (b/T) alpha (1 - p)/(1 - p - alpha p), alpha = bT/m, p = e^-alpha (Gil et al. 2004)
    with mp.workdps(40):
        alpha = mp.mpf(1) / 750                          # bT/m = 0.02 * 0.001 / 0.015
        assert Fraction(1, 750) == b * T / m
        p = mp.e ** -alpha
        closed = float(20 * alpha * (1 - p) / (1 - p - alpha * p))    # b/T = 20
    (line,) = [line for line in forward.lines if line.damping == 0]
    assert abs(line.stable_max - closed) < 1e-9 * closed


def test_the_stability_map_agrees_with_the_oracle_at_every_point(forward):
    spec = forward.stability.spec
    for i, B in enumerate(spec.y.values):
        for j, K in enumerate(spec.x.values):
            rho = zoh_radius(K, B)
            if abs(rho - 1) > 1e-12:
                assert forward.stability.values[i, j] == int(rho < 1), (K, B, rho)


def test_a_delayed_tustin_device_is_passive_beyond_its_stable_loop():
    zw = zwidth(Scene("single-user", approximation="tustin", delay=1, params=DEVICE), stiffness="K=0:30:7",
                damping="B=0:0.002:2")
    first = zw.lines[0]
    assert first.passive_max.value == 20 and first.exceeds()
    assert zoh_radius(Fraction(first.stable_max) * Fraction(999999, 10**6), 0, n=1) < 1
    assert zoh_radius(Fraction(first.stable_max) * Fraction(1000001, 10**6), 0, n=1) > 1
    # the grid says it too: passive (model) and unstable (exact loop) at K = 15, B = 0
    j = zw.passivity.spec.x.values.index(15)
    assert zw.passivity.values[0, j] == 1 and zw.stability.values[0, j] == 0


def test_the_csv_holds_one_row_per_damping(forward, tmp_path):
    text = forward.to_csv(tmp_path / "z.csv")
    rows = list(csv.DictReader(io.StringIO(text)))
    assert (tmp_path / "z.csv").read_text() == text
    assert [Fraction(r["B"]) for r in rows] == list(forward.passivity.spec.y.values)
    by_b = {Fraction(r["B"]): r for r in rows}
    assert by_b[Fraction(0)]["K_passive"] == "0 < K <= 40" and by_b[Fraction(0)]["K_passive_max"] == "40"
    assert by_b[Fraction(1, 50)]["K_passive"] == "never passive" and by_b[Fraction(1, 50)]["K_passive_max"] == ""
    assert all(r["passive_but_unstable"] == "0" for r in rows)         # the forward model stays inside
    assert float(by_b[Fraction(0)]["K_stable_max"]) == forward.lines[2].stable_max


def test_without_a_mass_there_is_no_overlay():
    zw = zwidth(Scene("single-user", params={"b": "0.02", "T": "0.001"}), stiffness="K=0:60:4", damping="B=0:0.01:2")
    assert zw.stability is None and all(line.stable_max is None for line in zw.lines)
    assert "--param m=VALUE" in zw.to_text()


def test_the_roles_name_the_device(capsys, tmp_path):
    code, out, _ = run(capsys, "zwidth", "--role", "device_damping=c_d", "--role", "period=h", "--role", "mass=M",
                       "--param", "c_d=0.02", "--param", "h=0.001", "--param", "M=0.015",
                       "--stiffness", "K=0:60:4", "--damping", "B=0:0.01:2", "-o", str(tmp_path / "z.csv"))
    assert code == 0 and "c_d = 0.02" in out and "h = 0.001" in out
    rows = list(csv.DictReader(io.StringIO((tmp_path / "z.csv").read_text())))
    assert rows[0]["K_passive_max"] == "40"


def test_the_command_line_writes_the_csv_and_the_plot(capsys, tmp_path):
    code, out, err = run(capsys, "zwidth", "--param", "b=0.02", "--param", "T=0.001", "--param", "m=0.015",
                         "--stiffness", "0:60:13", "--damping", "0:0.02:5",
                         "-o", str(tmp_path / "z.csv"), "--plot", str(tmp_path / "z.png"))
    assert code == 0 and "forward model" in out and f"wrote {tmp_path / 'z.png'}" in err
    assert (tmp_path / "z.png").read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    assert (tmp_path / "z.csv").read_text().splitlines()[0].startswith("B,K_passive,K_passive_max")
    code, out, _ = run(capsys, "zwidth", "--param", "b=0.02", "--param", "T=0.001", "--stiffness", "0:60:4",
                       "--damping", "0:0.01:2", "-o", "-")
    assert code == 0 and out.startswith("B,K_passive")


@pytest.mark.parametrize("argv, message", [
    (["--param", "T=0.001"], "the Z-width needs the device damping b"),
    (["--param", "b=0.02", "--param", "T=0.001", "--stiffness", "k=0:1:2"], "the scene has no stiffness 'k'"),
    (["--param", "b=0.02", "--param", "T=0.001", "--stiffness", "K=0:1:2", "--damping", "K=0:1:2"],
     "the stiffness and the damping are both K"),
    (["--param", "b=0.02", "--param", "T=0.001", "--plot", "z.txt"], "--plot z.txt: the file name must end in"),
    (["--param", "b=0.02", "--param", "T=0.001", "--workers", "0"], "--workers must be at least 1"),
])
def test_mistakes_are_one_line(capsys, argv, message):
    assert message in one_line_error(capsys, "zwidth", *argv)


# ---------------------------------------------------------------------------------------------
# derive's note: the model's passivity past the exact loop's stability, for the user's mass
# ---------------------------------------------------------------------------------------------

TUSTIN = ["derive", "single-user", "--controller", "k + c*s", "--discretize", "tustin", "--approximation", "tustin",
          "--delay", "1", "--param", "b=0.03", "--param", "c=0", "--param", "T=0.003", "--param", "m=0.05"]


def test_derive_notes_a_tustin_damper_passive_past_its_stable_loop(capsys):
    code, out, _ = run(capsys, *TUSTIN, "--param", "k=8", "--range", "k")
    assert code == 0
    assert "passive range of k (others fixed): 0 <= k <= 10" in out
    notes = [line for line in out.splitlines() if line.startswith("note:")]
    assert notes[0] == "note: the tustin model is passive here, but the exact sampled-data loop (ZOH, m = 0.05) is " \
        "unstable (certified)"
    note = notes[1]
    assert len(notes) == 2 and note.startswith("note: the tustin model is passive up to k = 10, but the exact sampled-data loop "
                           "(ZOH, m = 0.05) is unstable above k* = ")
    k_star = Fraction(note.split("k* = ")[1].split(" ")[0])
    lo, hi = k_star * Fraction(999, 1000), k_star * Fraction(1001, 1000)
    assert zoh_radius(lo, n=1, mass=Fraction(1, 20), damping=Fraction(3, 100), period=Fraction(3, 1000)) < 1
    assert zoh_radius(hi, n=1, mass=Fraction(1, 20), damping=Fraction(3, 100), period=Fraction(3, 1000)) > 1
    # at k = 8 the model is proved passive and the exact loop is unstable: both are said
    code, out, _ = run(capsys, *TUSTIN, "--param", "k=8", "--format", "json")
    data = json.loads(out)
    assert data["verdict"] == "proved"
    assert data["exact_loop_notes"] == ["note: the tustin model is passive here, but the exact sampled-data loop "
                                        "(ZOH, m = 0.05) is unstable (certified)"]
    assert zoh_radius(8, n=1, mass=Fraction(1, 20), damping=Fraction(3, 100), period=Fraction(3, 1000)) > 1


def test_derive_says_nothing_where_the_model_stays_inside_the_stable_loop(capsys):
    code, out, _ = run(capsys, "derive", "single-user", "--param", "b=0.02", "--param", "T=0.001", "--param", "B=0",
                       "--param", "m=0.015", "--param", "K=15", "--range", "K")
    assert code == 0 and "note:" not in out                  # forward model: K_max = 40 < K* = 40.0089
    code, out, _ = run(capsys, "derive", "single-user", "--approximation", "tustin", "--param", "b=0.02",
                       "--param", "T=0.001", "--param", "B=0", "--param", "K=50", "--range", "K")
    assert code == 0 and "note:" not in out                  # no mass: no loop to compare with
