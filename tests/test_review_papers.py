"""A reviewer's paper end to end: twenty displays written as a stranger would (Diolaiti-style
delayed walls, Mehling's electrical damping, a filtered damper, a Tustin damper, two users, a PEB
teleoperator, Gil's ZOH boundary, Hulin's linear condition), correct and with slips, once in the
toolkit's default names and once with every name renamed (``examples/reviewer-walls.toml``):
the same verdicts, the witnesses true of the definition (independent oracles), the repairs the
nearby correct displays."""

from __future__ import annotations

import sys
from pathlib import Path

import pytest
import sympy as sp

from hapticproof.audit.paperfile import read_paper
from hapticproof.audit.runner import audit_paper

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(Path(__file__).resolve().parent))
from oracles.discrete import multi_user_positive_real, single_user_positive_real, teleoperator_passivity  # noqa: E402

EXPECTED = {
    "1": "confirmed", "2": "confirmed", "3": "confirmed", "4": "typo", "5": "confirmed", "6": "conservative",
    "7": "needs-assumption", "8": "confirmed", "9": "confirmed", "10": "typo", "11": "wrong", "12": "confirmed",
    "13": "typo", "14": "conservative", "15": "wrong", "16": "confirmed", "17": "wrong", "18": "confirmed",
    "19": "typo", "20": "conservative",
}
FILES = {"default": ROOT / "tests" / "fixtures" / "review-walls.toml", "renamed": ROOT / "examples" / "reviewer-walls.toml"}
#: default name -> renamed
RENAMED = {"b": "b_v", "K": "k_v", "B": "d_v", "T": "T_s", "a": "p", "b_m": "c_m", "b_s": "c_s", "b_1": "c_1",
           "b_2": "c_2", "m": "m_v"}


@pytest.fixture(scope="module")
def reports():
    return {name: {r.id: r for r in audit_paper(read_paper(path).paper).results} for name, path in FILES.items()}


@pytest.mark.parametrize("name", sorted(FILES))
def test_verdicts(reports, name):
    got = {k: r.verdict.value for k, r in reports[name].items()}
    assert got == EXPECTED, {k: (v, reports[name][k].detail) for k, v in got.items() if v != EXPECTED[k]}


def _names(witness: dict, name: str) -> dict:
    """A witness in the default names (the renamed file's mapped back)."""
    inverse = {v: k for k, v in RENAMED.items()} if name == "renamed" else {}
    return {inverse.get(k, k): sp.Rational(v) for k, v in witness.items()}


CORRECTED = {
    "default": {"4": r"b > \frac{KT}{2} + B", "10": r"b > \frac{KT}{2} + B\frac{1-a}{1+a}",
                "13": r"b_1 > \frac{(K_{01} + K_{12})T}{2} + B_{01} + B_{12}",
                "19": r"K < \frac{b + B}{\frac{T}{2} + t_d}"},
    "renamed": {"4": r"b_v > \frac{k_vT_s}{2} + d_v", "10": r"b_v > \frac{k_vT_s}{2} + d_v\frac{1-p}{1+p}",
                "13": r"c_1 > \frac{(K_{01} + K_{12})T_s}{2} + B_{01} + B_{12}",
                "19": r"k_v < \frac{b_v + d_v}{\frac{T_s}{2} + t_d}"},
}
OPERATORS = {"4": "half", "10": "sign", "13": "index", "19": "sign"}


@pytest.mark.parametrize("name", sorted(FILES))
def test_repairs_are_the_nearby_correct_displays(reports, name):
    for eq_id, corrected in CORRECTED[name].items():
        result = reports[name][eq_id]
        assert (result.corrected, result.evidence.facts["repair"]["operator"]) == (corrected, OPERATORS[eq_id])


@pytest.mark.parametrize("name", sorted(FILES))
def test_witnesses_are_true_of_the_definition(reports, name):
    """Each counterexample re-checked by an oracle written from the definition (values of G^-1
    on and outside the unit circle, the matrix G + G^H), importing nothing from the package."""
    z = sp.Symbol("z")
    r = reports[name]
    # (11) the Tustin damper: the display holds where G^-1 is not positive real
    w = _names(r["11"].evidence.witness, name)
    H = w["K"] + 2 * w["B"] * (z - 1) / (w["T"] * (z + 1))
    assert w["b"] > w["K"] * w["T"] / 2 - w["B"]
    assert single_user_positive_real(b=w["b"], T=w["T"], H=H).verdict == "no"
    # (13) as printed: a positive-real pair of users where the printed bound on b_1 fails
    w = _names(r["13"].evidence.witness, name)
    assert w["b_1"] <= (w["K_02"] + w["K_12"]) * w["T"] / 2 + w["B_01"] + w["B_12"]
    pair = multi_user_positive_real(b=[w["b_1"], w["b_2"]], T=w["T"], K0=[w["K_01"], w["K_02"]],
                                    B0=[w["B_01"], w["B_02"]], K={(0, 1): w["K_12"]}, B={(0, 1): w["B_12"]})
    assert pair.verdict == "yes"
    # (15) the teleoperator: both printed bounds hold, the teleoperator is not passive
    w = _names(r["15"].evidence.witness, name)
    for robot in ("b_m", "b_s"):
        assert w[robot] > w["K"] * w["T"] / 2 + w["B"]
    C = w["K"] + w["B"] * (z - 1) / (w["T"] * z)
    assert teleoperator_passivity(b_m=w["b_m"], b_s=w["b_s"], T=w["T"], C=C).verdict == "no"


def test_renaming_changes_nothing_but_the_names(reports):
    for eq_id in EXPECTED:
        default, renamed = reports["default"][eq_id], reports["renamed"][eq_id]
        assert default.verdict == renamed.verdict
        assert (default.evidence.witness is None) == (renamed.evidence.witness is None)
