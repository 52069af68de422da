"""Every entry point as fast as its decision (issue 21): what the commands skip and say they skipped,
the bounded searches, and the same verdicts by the short and the long routes. No timings here (the
benchmarks measure them: benchmarks/bench_cli.py)."""

from __future__ import annotations

import json
import sys
from pathlib import Path
from fractions import Fraction

import pytest
import sympy as sp

from hapticproof.analysis.design import delay_margin
from hapticproof.analysis.fastpath import NumericScene, critical_damping
from hapticproof.analysis.positivereal import positive_real
from hapticproof.core.evidence import Decision
from hapticproof.report.summary import CFORM_LIMIT, summarize_single_user
from hapticproof.systems.scene import Scene
from hapticproof.systems.singleuser import SingleUserScene

sys.path.insert(0, str(Path(__file__).resolve().parent))

from clirun import run  # noqa: E402

WALL = ["--param", "K=2", "--param", "T=0.001", "--param", "b=0.0201", "--param", "B=0.001"]


def test_long_delay_skips_the_c_polynomial_and_says_so(capsys):
    n = 2 * CFORM_LIMIT
    code, out, _ = run(capsys, "derive", "single-user", "--delay", str(n), *WALL, "--format", "json")
    data = json.loads(out)
    assert code == 0 and data["hermitian_part"] is None
    assert data["skipped"]["hermitian_part"]["option"] == "--full"
    assert data["verdict"] == "disproved"
    assert data["residues"] == [{"z": "1", "residue": "1/500", "condition": "proved"}]     # T K at z = 1
    code, text, _ = run(capsys, "derive", "single-user", "--delay", str(n), *WALL)
    assert "not computed" in text and "--full computes it" in text
    code, full, _ = run(capsys, "derive", "single-user", "--delay", str(n), *WALL, "--format", "json", "--full")
    data_full = json.loads(full)
    assert "skipped" not in data_full and f"c**{n + 1}" in data_full["hermitian_part"]   # the degree-(n + 2) c-form
    assert data_full["verdict"] == data["verdict"] and data_full["conditions"] == data["conditions"]


def test_the_summary_decides_like_the_sympy_route_below_and_above_the_limit():
    for n in (3, CFORM_LIMIT + 5):
        lo, hi = critical_damping(NumericScene.virtual_wall(K=2, B="0.001", b=1, T="0.001", delay=n))
        for b, want in ((hi * (1 + Fraction(1, 10**6)), "proved"), (lo * (1 - Fraction(1, 10**6)), "disproved")):
            scene = SingleUserScene.virtual_wall(K=2, B="0.001", b=b, T="0.001", delay=n)
            s = summarize_single_user(scene)
            assert s.verdict == want == positive_real(scene).decision.value
            assert (s.hermitian_part is None) == (n > CFORM_LIMIT)


def test_uniform_users_by_modes_on_the_command_line(capsys):
    code, out, _ = run(capsys, "derive", "multi-user", "--users", "30", "--uniform", "--format", "json")
    data = json.loads(out)
    assert code == 0 and data["by_modes"] and data["verdict"] == "symbolic"
    assert data["worst_case_condition"] == "b >= 30*B + B_0 + 15*K*T + K_0*T/2"
    assert set(data["skipped"]) == {"G_inverse", "hermitian_part", "residue_at_1"}
    assert {k: v for k, v in data["spectrum"].items()} == {"0": 1, "30": 29}
    code, out, _ = run(capsys, "derive", "multi-user", "--users", "6", "--uniform", "--graph", "ring", "--delay", "2",
                       "--param", "b=0.05", "--param", "K_0=2", "--param", "B_0=0.001", "--param", "K=3",
                       "--param", "B=0.0001", "--param", "T=0.001")
    assert code == 0 and "decided by modes" in out and "mode lambda = 4" in out and "verdict:" in out


def test_the_delay_margin_search_ends_by_its_deadline():
    # passive for every n below ~1.5 million by the bound: the one delay to decide is very long
    scene = Scene("single-user", params={"K": "0.001", "B": 1, "T": "0.001", "b": "2.5"})
    calls = []
    dm = delay_margin(scene, max_delay=4_000_000, deadline=1e-9, progress=lambda done, total: calls.append((done, total)))
    assert dm.decision == Decision.UNDECIDED and dm.margin is None
    assert dm.lower == dm.proof["N_low"] and dm.upper == dm.proof["n_fail"] - 1
    assert "deadline" in dm.reason and "not passive from n = " in dm.reason
    assert calls and calls[-1][0] <= calls[-1][1]


def test_deadline_and_max_delay_are_checked(capsys):
    code, _, err = run(capsys, "derive", "single-user", *WALL, "--delay-margin", "--deadline", "0")
    assert code == 2 and "--deadline" in err
    code, _, err = run(capsys, "derive", "multi-user", "--users", "2", "--delay-margin", "--deadline", "-1")
    assert code == 2 and "--deadline" in err


def test_delay_margin_unchanged_by_the_fast_route():
    """b - K T (n + 1/2) + B >= 0 at c = 1 decides the wall: n <= (b + B)/(K T) - 1/2."""
    scene = Scene("single-user", params={"K": 2, "B": "0.001", "T": "0.001", "b": "0.0201"})
    dm = delay_margin(scene)
    assert dm.decision == Decision.PROVED
    bound = (sp.Rational("0.0201") - sp.Rational("0.001")) / (2 * sp.Rational("0.001")) - sp.Rational(1, 2)
    assert dm.margin <= sp.floor(bound) + 1
    for n in (dm.margin, dm.margin + 1):
        wall = SingleUserScene.virtual_wall(K=2, B="0.001", b="0.0201", T="0.001", delay=n)
        assert positive_real(wall).decision == (Decision.PROVED if n == dm.margin else Decision.DISPROVED)


@pytest.mark.parametrize("approximation", ["forward", "backward", "tustin"])
def test_flint_reading_of_H_is_the_sympy_reading(approximation):
    """NumericScene.from_scene reads H(z) from the tree; the old SymPy route (cancel, Poly) agrees."""
    z = sp.Symbol("z")
    H = 3 + sp.Rational(1, 7) * (z - 1) / (sp.Rational(1, 100) * z) + 5 * (z - 1) ** 2 / (z**2 * (z - sp.Rational(1, 3)))
    scene = SingleUserScene(b=1, T=sp.Rational(1, 100), H=H, approximation=approximation, delay=2)
    ns = NumericScene.from_scene(scene)
    num, den = sp.fraction(sp.cancel(sp.together(H)))
    as_expr = lambda coeffs: sum(sp.Rational(c.numerator, c.denominator) * z**k for k, c in enumerate(coeffs))  # noqa: E731
    assert sp.cancel(as_expr(ns.H[0]) / as_expr(ns.H[1]) - num / den) == 0


def test_symbolic_long_delays_answer_without_the_large_polynomial(capsys):
    code, out, _ = run(capsys, "derive", "single-user", "--delay", "300", "--format", "json")
    data = json.loads(out)
    assert code == 0 and data["verdict"] == "symbolic" and data["hermitian_part"] is None
    assert data["skipped"]["hermitian_part"]["option"] == "--full"
    # below the limit the condition min_c(...) >= 0 is built, and summarised in text (a traceback before)
    code, text, _ = run(capsys, "derive", "single-user", "--delay", "60")
    worst = next(line for line in text.splitlines() if line.startswith("worst case:"))
    assert code == 0 and "min_c(polynomial of c: degree 61" in worst and worst.endswith(">= 0")
