"""Assumptions as people state them (:mod:`hapticproof.audit.regions`): inequalities, intervals and
relations between parameters in ``[symbols]`` and in an equation's ``assumption``; the exact
decisions they restrict; contradictory declarations refused with the file, line and field."""

from __future__ import annotations

import sys
from pathlib import Path

import pytest
import sympy as sp
from hypothesis import given, settings
from hypothesis import strategies as st

from hapticproof.audit.paperfile import PaperFileError, loads
from hapticproof.audit.regions import Region, RegionError, read_region
from hapticproof.audit.runner import audit_paper

sys.path.insert(0, str(Path(__file__).resolve().parent))
from oracles.discrete import single_user_positive_real  # noqa: E402

a = sp.Symbol("a", real=True)
B = sp.Symbol("B", real=True)
K, T, b_s = sp.symbols("K T b_s", positive=True)
b_m = sp.Symbol("b_m", real=True)
NAMES = {"a": a, "B": B, "K": K, "T": T, "b_s": b_s, "b_m": b_m}


@pytest.mark.parametrize("text, expected", [
    (r"B \geq 0", "B >= 0"),
    ("B >= 0", "B >= 0"),
    ("0 <= a < 1", "0 <= a < 1"),
    (r"0 \le a < 1", "0 <= a < 1"),
    (r"a \in [0, 1)", "0 <= a < 1"),
    ("b_m >= b_s", "b_m >= b_s"),
    (r"B \leq \frac{KT}{2}", "B <= K*T/2"),
    ("B <= K*T/2", "B <= K*T/2"),
    ("B = 0", "B = 0"),
    ("B = 0, a < 1/2", "B = 0, a <= 1/2".replace("<=", "<")),
    # a linear relation among parameters bounds its first name by the others (issue 28: g_0 + g_1 >= 0)
    ("a + B < 1", "B < 1 - a"),
    (r"2a - b_m \ge 0", "a >= b_m/2"),
])
def test_regions_read_in_latex_and_expression_syntax(text, expected):
    assert read_region(text, NAMES).text() == expected


@pytest.mark.parametrize("text, words", [
    ("1 < a < 0", "no value of a"),
    ("a*B < 1", "does not bound a parameter alone"),
    ("0 < a > 1", "a chain reads one way"),
    ("B", "is not a relation"),
    ("a = 1, a = 2", "contradict"),
])
def test_regions_that_do_not_read_are_one_line(text, words):
    with pytest.raises(RegionError, match=words):
        read_region(text, NAMES)


def test_restrictions_merge_and_imply_signs():
    region = read_region("0 <= a < 1", NAMES) & read_region("a >= 1/3", NAMES)
    (r,) = region.restrictions
    assert (r.lower, r.upper, r.lower_strict, r.upper_strict) == (sp.Rational(1, 3), 1, False, True)
    assert read_region("b_m >= b_s", NAMES).restrictions[0].sign_word() == "positive"
    # B >= 0 restricts a real B, and says nothing more about a non-negative one
    assert not read_region(r"B \geq 0", NAMES).restrictions[0].only_sign()
    assert read_region(r"B \geq 0", {"B": sp.Symbol("B", nonnegative=True)}).restrictions[0].only_sign()
    with pytest.raises(RegionError, match="outside"):
        Region(read_region("a = 2", NAMES).restrictions + read_region("0 <= a < 1", NAMES).restrictions)


@settings(max_examples=60, deadline=None)
@given(st.fractions(min_value=0, max_value=1000))
def test_the_change_of_variables_is_a_bijection_onto_the_region(u_value):
    """u >= 0 maps onto 1/3 <= a < 1 and back (the parametrisation every decision runs in)."""
    chart = read_region("1/3 <= a < 1", NAMES).parametrize({"a"})
    u = sp.Rational(u_value.numerator, u_value.denominator)
    point = chart.witness({"u_a": u})
    value = point["a"]
    assert sp.Rational(1, 3) <= value < 1
    (fresh,) = chart.inverse
    assert chart.inverse[fresh].subs(a, value) == u


WALL = r"""
[paper]
id = "filters"
title = "filters"

[symbols]
b = "positive"
K = "positive"
B = "nonnegative"
T = "positive"
a = "0 <= a < 1"

[scenes.filtered]
system = "single-user"
environment = "K + B*(1 - a)*(z - 1)/(T*(z - a))"
"""


def _entry(ident, printed, claim="passivity-condition", extra=""):
    return f"\n[[equations]]\nid = \"{ident}\"\nprinted = '{printed}'\nclaim = \"{claim}\"\nscene = \"filtered\"\n{extra}\n"


def test_filtered_damper_is_decided_in_its_region():
    text = WALL + _entry("exact", r"b > \frac{KT}{2} + B\frac{1-a}{1+a}") + _entry("weak", r"b > \frac{KT}{2}") \
        + _entry("strong", r"b > \frac{KT}{2} + B") \
        + _entry("upper", r"b > \frac{KT}{2} + \frac{B}{2}", extra=r"assumption = 'a \geq \frac{1}{3}'")
    report = {r.id: r for r in audit_paper(loads(text, "filters.toml").paper).results}
    assert {k: r.verdict.value for k, r in report.items()} == {"exact": "confirmed", "weak": "wrong",
                                                               "strong": "conservative", "upper": "needs-assumption"}
    # witnesses and derived conditions in the paper's names, inside the region of the file
    weak = report["weak"].evidence.witness
    assert "a" in weak and not any(k.startswith("u_") for k in weak) and 0 <= weak["a"] < 1
    assert "u_" not in report["exact"].derived and r"\left(1 - a\right)" in report["exact"].derived
    # the witness outside the stated assumption: a < 1/3, where the printed bound B/2 is too low
    upper = report["upper"]
    assert upper.evidence.facts["assumption"] == "a >= 1/3" and r"\quad (a \geq \frac{1}{3})" in upper.corrected
    w = {k: sp.Rational(v) for k, v in upper.evidence.witness.items()}
    assert w["a"] < sp.Rational(1, 3)
    z = sp.Symbol("z")
    H = w["K"] + w["B"] * (1 - w["a"]) * (z - 1) / (w["T"] * (z - w["a"]))
    assert single_user_positive_real(b=w["b"], T=w["T"], H=H).verdict == "no"
    assert w["b"] > w["K"] * w["T"] / 2 + w["B"] / 2          # the display holds there


def test_contradictory_declarations_name_both_lines():
    text = WALL.replace('environment = "K + B*(1 - a)*(z - 1)/(T*(z - a))"',
                        'environment = "K + B*(1 - a)*(z - 1)/(T*(z - a))"\n[scenes.filtered.params]\nB = "real"')
    with pytest.raises(PaperFileError) as info:
        loads(text + _entry("1", r"b > \frac{KT}{2} + |B|"), "mine.toml")
    message = str(info.value)
    assert message.startswith("mine.toml:17: scene 'filtered': params: B = 'real' contradicts [symbols]")
    assert "mine.toml:9: B is 'nonnegative'" in message and "\n" not in message
    outside = WALL.replace('environment = "K + B*(1 - a)*(z - 1)/(T*(z - a))"',
                           'environment = "K + B*(1 - a)*(z - 1)/(T*(z - a))"\n[scenes.filtered.params]\na = 2')
    with pytest.raises(PaperFileError, match=r"mine\.toml:17: .*a = 2 lies outside \[symbols\] \(mine\.toml:11: 0 <= a < 1\)"):
        loads(outside + _entry("1", r"b > \frac{KT}{2}"), "mine.toml")
    with pytest.raises(PaperFileError, match=r"field 'assumption': a = 2 lies outside 0 <= a < 1"):
        loads(WALL + _entry("1", r"b > \frac{KT}{2}", extra='assumption = "a = 2"'), "mine.toml")
    with pytest.raises(PaperFileError, match=r"mine\.toml:11: symbols: a: .* does not bound a alone"):
        loads(WALL.replace('a = "0 <= a < 1"', 'a = "0 <= B < 1"') + _entry("1", r"b > \frac{KT}{2}"), "mine.toml")


def test_abs_is_read_with_the_declared_sign():
    """B declared real (once): |B| stays |B| and the correct b > KT/2 + |B| is confirmed."""
    text = r"""
[paper]
id = "abs"
title = "abs"
[symbols]
B = "real"
[scenes.wall]
system = "single-user"
[[equations]]
id = "1"
printed = 'b > \frac{KT}{2} + |B|'
claim = "passivity-condition"
scene = "wall"
"""
    (result,) = audit_paper(loads(text, "abs.toml").paper).results
    assert result.verdict.value == "confirmed"


def test_relations_between_parameters_restrict_a_teleoperator():
    """b_m >= b_s: the slave's bound b_s > KT + 2B alone implies the exact condition
    h = b_m b_s/(b_m + b_s) >= KT/2 + B (h >= b_s/2 there), proved at the corner of the bound;
    it is not necessary (h tends to b_s as b_m grows)."""
    text = r"""
[paper]
id = "tele"
title = "tele"
[symbols]
b_m = "b_m >= b_s"
[scenes.peb]
system = "teleoperator"
[[equations]]
id = "1"
printed = 'b_s > KT + 2B'
claim = "passivity-condition"
scene = "peb"
"""
    (result,) = audit_paper(loads(text, "tele.toml").paper).results
    assert result.verdict.value == "conservative", result.detail
    assert "corner b_s = 2*B + K*T" in result.detail
    w = {k: sp.Rational(v) for k, v in result.evidence.witness.items()}    # passive, yet the display fails
    assert w["b_m"] >= w["b_s"] and not w["b_s"] > w["K"] * w["T"] + 2 * w["B"]
    assert w["b_m"] * w["b_s"] / (w["b_m"] + w["b_s"]) >= w["K"] * w["T"] / 2 + w["B"]


def test_the_corner_proof_needs_monotonicity_and_a_holding_corner():
    from hapticproof.audit.claimbase import _corner_sufficiency as corner  # noqa: PLC2701 - its own unit test

    b_m, b_s, beta = sp.symbols("b_m b_s beta", positive=True)
    h = b_m * b_s / (b_m + b_s)
    assert corner(sp.And(b_m > 2 * beta, b_s > 2 * beta), sp.Ge(h, beta)) == {b_m: 2 * beta, b_s: 2 * beta}
    assert corner(sp.And(b_m > beta, b_s > beta), sp.Ge(h, beta)) is None           # h = beta/2 at the corner
    assert corner(sp.And(b_m > 1, b_s > 0), sp.Ge(b_m - b_s, 0)) is None            # decreasing in b_s
    assert corner(b_m > -beta, sp.Ge(b_m, 0)) is None                                # a negative bound
