"""The generic claim checkers: each verdict follows from the printed display (changing the display
moves it), witnesses are re-checked by exact decisions, and a single edit that repairs a display
makes it a typo with that edited display as the corrected LaTeX."""

from __future__ import annotations

import pytest
import sympy as sp

from hapticproof.audit.runner import audit_paper
from hapticproof.audit.paperfile import loads

SYMBOLS = '''
b = "positive"
K = "positive"
B = "nonnegative"
T = "positive"
z_a = "nonnegative"
t_d = "nonnegative"
n = "integer"
m = "positive"
omega = "real"
F_h = "signal"
V_h = "signal"
"G^{-1}" = "function"
r = "real"
K_0 = "positive"
B_0 = "nonnegative"
'''

SCENES = '''
[scenes.wall]
system = "single-user"
[scenes.spring]
system = "single-user"
environment = "K"
[scenes.backward]
system = "single-user"
approximation = "backward"
[scenes.delayed]
system = "single-user"
delay = "n"
[scenes.stable]
system = "single-user"
[scenes.stable.params]
m = "positive"
[scenes.numeric]
system = "single-user"
[scenes.numeric.params]
K = 2
B = 0
T = 0.001
[scenes.users]
system = "multi-user"
users = 2
uniform = true
[scenes.tele]
system = "teleoperator"
[scenes.pd]
system = "teleoperator"
controller = "pd"
[scenes.pd.params]
b = "positive"           # both robots' damping
'''


def audit(*equations: tuple[str, str, str, str]) -> dict[str, object]:
    """Audit displays ``(id, printed, claim, extra TOML lines)``; results by id."""
    entries = []
    for eq_id, printed, claim, extra in equations:
        entries.append(f"[[equations]]\nid = \"{eq_id}\"\nprinted = '{printed}'\nclaim = \"{claim}\"\n{extra}\n")
    text = f'[paper]\nid = "t"\ntitle = "t"\n[symbols]\n{SYMBOLS}\n{SCENES}\n' + "\n".join(entries)
    paper = loads(text, "t.toml")
    return {r.id: r for r in audit_paper(paper.paper).results}


def verdicts(results: dict) -> dict[str, str]:
    return {k: r.verdict.value for k, r in results.items()}


def test_inverse_transfer_moves_with_the_display():
    res = audit(
        ("ok", r"F_h(z) = bV_h(z) + \left(K + \frac{B(z-1)}{Tz}\right)\frac{T}{z-1}V_h(z) = G^{-1}(z)V_h(z)",
         "inverse-transfer", 'scene = "wall"'),
        ("sign", r"G^{-1}(z) = b - \left(K + \frac{B(z-1)}{Tz}\right)\frac{T}{z-1}", "inverse-transfer", 'scene = "wall"'),
        ("wrong", r"G^{-1}(z) = b + \frac{KT}{z}", "inverse-transfer", 'scene = "wall"'),
        ("label", r"F_h(z) = G^{-1}(z) V_h(z)", "inverse-transfer", 'scene = "wall"'),
        ("users", r"\begin{bmatrix} b + \frac{B_0(z-1)}{z} + \frac{K_0 T}{z-1} & 0 \\ 0 & b \end{bmatrix}",
         "inverse-transfer", 'scene = "users"'),
    )
    assert verdicts(res) == {"ok": "confirmed", "sign": "typo", "wrong": "wrong", "label": "malformed", "users": "wrong"}
    assert res["sign"].corrected == r"G^{-1}(z) = b + \left(K + \frac{B(z-1)}{Tz}\right)\frac{T}{z-1}"
    assert res["sign"].evidence.facts["repair"]["operator"] == "sign"
    witness = {sp.Symbol(k): v for k, v in res["wrong"].evidence.witness.items()}
    assert res["wrong"].evidence.facts["edits_tried"] > 0 and witness        # an exact point where they differ


def test_residue_and_labels():
    res = audit(("ok", r"r = KT", "residue", 'scene = "wall"'),
                ("bad", r"r = K", "residue", 'scene = "wall"'),
                ("users", r"\begin{bmatrix} T(K + K_0) & -KT \\ -KT & T(K + K_0) \end{bmatrix}", "residue",
                 'scene = "users"'))
    assert verdicts(res) == {"ok": "confirmed", "bad": "wrong", "users": "confirmed"}


def test_hermitian_part_expression_condition_and_delay():
    res = audit(
        ("expr", r"b - \frac{KT}{2} + B\cos(\omega T)", "hermitian-part", 'scene = "wall"'),
        ("expr-sign", r"b - \frac{KT}{2} - B\cos(\omega T)", "hermitian-part", 'scene = "wall"'),
        ("cond", r"b > \frac{KT}{2} - B\cos(\omega T)", "hermitian-part", 'scene = "wall"'),
        ("cond-missing", r"b + \frac{KT}{2}", "hermitian-part", 'scene = "backward"\nform = "condition"'),
        ("delay", r"b + B\cos(\omega (t_d + T)) - \frac{KT}{2}\cos(\omega t_d) - KT\frac{\sin(\omega t_d)\sin(\omega T)}"
                  r"{2(1 - \cos(\omega T))} > 0", "hermitian-part", 'scene = "delayed"'),
        ("delay-bad", r"b + B\cos(\omega t_d) - \frac{KT}{2}\cos(\omega t_d) > 0", "hermitian-part", 'scene = "delayed"'),
        ("minor", r"b - \frac{(K_0 + K)T}{2} + (B_0 + B)\cos(\omega T) > 0", "hermitian-part", 'scene = "users"'),
        ("minor-bad", r"b - \frac{(K_0 + K)T}{2} > 0", "hermitian-part", 'scene = "users"'),
    )
    assert verdicts(res) == {"expr": "confirmed", "expr-sign": "typo", "cond": "confirmed", "cond-missing": "malformed",
                             "delay": "confirmed", "delay-bad": "wrong", "minor": "confirmed", "minor-bad": "wrong"}
    assert res["expr-sign"].corrected == r"b - \frac{KT}{2} + B\cos(\omega T)"
    assert res["cond-missing"].corrected is None                  # b + KT/2 is not Re G_2^-1 (B is missing)
    assert res["delay-bad"].evidence.witness["n"] >= 1


def test_passivity_conditions_each_way():
    res = audit(
        ("exact", r"b > \frac{KT}{2} + B", "passivity-condition", 'scene = "wall"'),
        ("strong", r"b > KT + B", "passivity-condition", 'scene = "wall"'),
        ("weak", r"b > \frac{KT}{6} + B", "passivity-condition", 'scene = "wall"'),
        ("reversed", r"b < \frac{KT}{2} + B", "passivity-condition", 'scene = "wall"'),
        ("suff-strong", r"b > KT + B", "sufficient-condition", 'scene = "wall"'),
        ("suff-weak", r"b > \frac{KT}{2}", "sufficient-condition", 'scene = "wall"'),
        ("nec-weak", r"b > \frac{KT}{2}", "necessary-condition", 'scene = "wall"'),
        ("nec-strong", r"b > KT + B", "necessary-condition", 'scene = "wall"'),
        ("stiffness", r"K < \frac{2b}{T}", "passivity-condition", 'scene = "spring"'),
    )
    # KT for KT/2 is the papers' commonest slip: halving the term makes both 'strong' displays exact
    assert verdicts(res) == {"exact": "confirmed", "strong": "typo", "weak": "wrong", "reversed": "typo",
                             "suff-strong": "conservative", "suff-weak": "wrong", "nec-weak": "confirmed",
                             "nec-strong": "typo", "stiffness": "confirmed"}
    assert res["reversed"].corrected == r"b > \frac{KT}{2} + B"
    assert res["strong"].corrected == res["nec-strong"].corrected == r"b > \frac{KT}{2} + B"
    assert "as printed: the printed condition implies the exact condition" in res["strong"].detail
    assert res["strong"].evidence.facts["repair"]["operator"] == "half"
    # the witness of a weaker bound is re-checked by the exact decision of the numeric scene
    weak = res["weak"].evidence
    assert weak.facts["recheck"]["decision"] == "disproved"
    assert res["nec-strong"].evidence.facts["recheck"]["decision"] == "proved"


def test_teleoperator_conditions():
    res = audit(("worst", r"b > KT + 2B", "passivity-condition", 'scene = "pd"'),
                ("sign", r"b > KT - 2B", "passivity-condition", 'scene = "pd"'),
                ("freq", r"b > KT - 2B \cos \omega T", "hermitian-part", 'scene = "pd"'))
    assert verdicts(res) == {"worst": "confirmed", "sign": "typo", "freq": "confirmed"}
    assert res["sign"].corrected == r"b > KT + 2B"


def test_numeric_scene_and_claims_that_do_not_apply():
    res = audit(("passive", r"b > \frac{KT}{2}", "passivity-condition", 'scene = "numeric"'),
                ("tele", r"r = KT", "residue", 'scene = "tele"'))
    assert res["tele"].verdict.value == "undecided" and "cannot be checked" in res["tele"].detail
    # the scene fixes K, T: the printed condition b > KT/2 is b > 1/1000, the exact one b >= 1/1000
    assert res["passive"].verdict.value == "confirmed"


def test_assumption_gives_needs_assumption():
    res = audit(
        ("small-B", r"b+B > \frac{KT}{2} + Kt_d", "passivity-condition", 'scene = "delayed"\nassumption = "B = 0"'),
        ("no-assumption", r"b+B > \frac{KT}{2} + Kt_d", "passivity-condition", 'scene = "delayed"'),
        ("always", r"b > \frac{KT}{2} + Kt_d + B", "sufficient-condition", 'scene = "delayed"\nassumption = "B = 0"'),
        ("never", r"b > \frac{KT}{4} + Kt_d", "passivity-condition", 'scene = "delayed"\nassumption = "B = 0"'),
    )
    assert verdicts(res) == {"small-B": "needs-assumption", "no-assumption": "wrong", "always": "conservative",
                             "never": "typo"}
    assert res["small-B"].corrected.endswith(r"\quad (B = 0)")
    assert res["small-B"].evidence.facts["under_assumption"] == "confirmed"
    assert "without the stated assumption" in res["always"].detail
    # KT/4 is not even right for B = 0; one factor 2 makes it the paper's (needs-assumption) condition
    assert "even under the stated assumption" in res["never"].detail
    assert res["never"].corrected == r"b > 2 \frac{KT}{4} + Kt_d"


def test_stability_leading_order_and_exact():
    res = audit(
        ("lead", r"K < \frac{b + B}{\frac{T}{2} + t_d}", "stability-condition", 'scene = "delayed"\norder = "leading"'),
        ("lead-T", r"K < \frac{b + B}{T + t_d}", "stability-condition", 'scene = "delayed"\norder = "leading"'),
        ("exact", r"b > \frac{KT}{2} - B", "stability-condition", 'scene = "stable"'),
        ("no-mass", r"b > \frac{KT}{2} - B", "stability-condition", 'scene = "wall"'),
    )
    # T for T/2: sufficient, not the leading order claimed; halving the term repairs it
    assert verdicts(res) == {"lead": "confirmed", "lead-T": "typo", "exact": "wrong", "no-mass": "undecided"}
    certified = res["exact"].evidence.facts["certified"]
    assert certified["decision"] == "disproved" and res["exact"].evidence.witness["m"] > 0
    assert "device mass" in res["no-mass"].detail


def test_same_as_within_the_file_and_with_a_bundled_paper():
    res = audit(
        ("3", r"b > \frac{KT}{2} + B", "passivity-condition", 'scene = "wall"'),
        ("same", r"K < \frac{2(b - B)}{T}", "same-as", 'other = "3"'),
        ("differs", r"b + B > \frac{KT}{2}", "same-as", 'other = "3"'),
        ("under", r"b - z_a + B > Kt_d + \frac{KT}{2}", "same-as", 'other = "3"\nunder = "z_a = 0, t_d = 0, B = 0"'),
        ("bundled", r"b > \frac{KT}{2} + B", "same-as", 'other = "hve:20"'),
    )
    assert verdicts(res) == {"3": "confirmed", "same": "confirmed", "differs": "inconsistent", "under": "confirmed",
                             "bundled": "confirmed"}
    assert res["differs"].evidence.facts["ids"] == ["differs", "3"]
    assert res["differs"].evidence.witness


@pytest.mark.parametrize("printed", [r"b > \frac{KT}{2} + B", r"b > \frac{KT}{2} - B", r"b > KT", r"b < 2KT + B"])
def test_every_display_of_a_condition_gets_a_verdict(printed):
    """No traceback whatever the display: a verdict with evidence."""
    res = audit(("x", printed, "passivity-condition", 'scene = "wall"'))
    finding = res["x"]
    assert finding.verdict.value in ("confirmed", "conservative", "typo", "wrong", "undecided")
    assert finding.evidence.method


# A scaled name on one side of an inverse-transfer display (found by a definition oracle):
# c G^{-1}(z) = X claims X/c, c G(z) = X claims c/X, c F_h(z) = X V_h(z) claims X/c.
DELAYED_WALL = r"b + z^{-n}\left(K + \frac{B(z-1)}{Tz}\right)\frac{T}{z-1}"
SCALED_NAMES = [
    (r"-G(z) = " + DELAYED_WALL, False),
    (r"-G^{-1}(z) = " + DELAYED_WALL, False),
    (r"2G^{-1}(z) = " + DELAYED_WALL, False),
    (r"2F_h(z) = bV_h(z) + z^{-n}\left(K + \frac{B(z-1)}{Tz}\right)\frac{T}{z-1}V_h(z)", False),
    (r"F_h(z) = bV_h(z) + z^{-n}\left(K + \frac{B(z-1)}{Tz}\right)\frac{T}{z-1}V_h(z) = -G^{-1}(z)V_h(z)", False),
    (r"G^{-1}(z) + 1 = " + DELAYED_WALL, False),
    (r"-G^{-1}(z) = -b - z^{-n}\left(K + \frac{B(z-1)}{Tz}\right)\frac{T}{z-1}", True),
    (r"2G^{-1}(z) = 2b + 2z^{-n}\left(K + \frac{B(z-1)}{Tz}\right)\frac{T}{z-1}", True),
    (r"-G(z) = -\frac{1}{" + DELAYED_WALL + "}", True),
    (r"-F_h(z) = -bV_h(z) - z^{-n}\left(K + \frac{B(z-1)}{Tz}\right)\frac{T}{z-1}V_h(z)", True),
]


@pytest.mark.parametrize("printed, right", SCALED_NAMES)
def test_a_scaled_name_in_an_inverse_transfer_display_is_divided_out(printed, right):
    from pathlib import Path

    text = (Path(__file__).resolve().parents[1] / "derivations" / "hve" / "routine.toml").read_text()
    shown = "printed = 'G^{-1}(z) = b + z^{-n} \\left(K + \\frac{B(z-1)}{Tz}\\right) \\frac{T}{z-1}'"
    assert shown in text
    paper = loads(text.replace(shown, "printed = '" + printed + "'"), "scaled.toml")
    (result,) = audit_paper(paper.paper, ["22"]).results
    assert (result.verdict.value == "confirmed") == right, (result.verdict.value, result.detail)
    if not right:
        assert result.verdict.value in ("wrong", "typo", "malformed"), result.detail


def _routine_with(old: str, new: str, extra_scene: str = "") -> str:
    from pathlib import Path

    text = (Path(__file__).resolve().parents[1] / "derivations" / "hve" / "routine.toml").read_text()
    assert old in text
    if extra_scene:
        text = text.replace("[scenes.delayed]", extra_scene + "\n\n[scenes.delayed]")
    return text.replace(old, new)


BACKWARD_18 = "printed = 'b + \\frac{KT}{2} + B > 0'"


@pytest.mark.parametrize("printed", [r"b + \frac{KT}{2} + B\cos(\omega T) + B > 0", r"b > B\cos(\omega T) - B",
                                     r"b + \frac{KT}{2} + 2B\cos^2\left(\frac{\omega T}{2}\right) > 0"])
def test_a_display_that_always_holds_where_the_exact_condition_always_holds_is_confirmed(printed):
    """Re G_2^-1 = b + KT/2 + B > 0 always; so is each display (affine in c, positive at c = -1 and 1):
    equivalent conditions, not a 'conservative' display 'that is not necessary' without a witness."""
    paper = loads(_routine_with(BACKWARD_18, "printed = '" + printed + "'"), "always.toml")
    (result,) = audit_paper(paper.paper, ["18"]).results
    assert result.verdict.value == "confirmed", result.detail


def test_a_frequency_free_witness_is_rechecked_at_any_frequency():
    """An active operator on the backward wall: Re G^-1 = b - z_a + KT/2 + B has no c, so the
    witness has none; it is re-checked, not a KeyError (found by a definition oracle)."""
    scene = '[scenes.active-backward]\nsystem = "single-user"\napproximation = "backward"\nactive = true'
    text = _routine_with('scene = "backward"', 'scene = "active-backward"', scene)
    (result,) = audit_paper(loads(text, "active.toml").paper, ["18"]).results
    assert result.verdict.value == "wrong" and result.evidence.facts["recheck"]["decision"] == "disproved", result.detail
    fixed = text.replace(BACKWARD_18, "printed = 'b - z_a + \\frac{KT}{2} + B > 0'")
    (result,) = audit_paper(loads(fixed, "active.toml").paper, ["18"]).results
    assert result.verdict.value == "confirmed", result.detail


@pytest.mark.parametrize("assumption", ["B >= 0", r"B \geq 0", "B > 0"])
def test_a_sign_assumption_on_a_real_parameter_restricts_it(assumption):
    """B declared real, the display b > KT/2 + B under "B >= 0": exact (b >= KT/2 + |B|) only
    there, so needs-assumption, never "wrong even under the stated assumption" with B = -2 (found
    by a new user)."""
    text = "\n".join([
        '[paper]', 'id = "sign"', 'title = "a sign assumption"',
        '[symbols]', 'b = "positive"', 'K = "positive"', 'B = "real"', 'T = "positive"',
        '[scenes.w]', 'system = "single-user"', 'approximation = "forward"', 'environment = "K + B*(z - 1)/(T*z)"',
        '[[equations]]', 'id = "P"', "printed = 'b > \\frac{KT}{2} + B'", 'claim = "passivity-condition"', 'scene = "w"',
        f"assumption = '{assumption}'"])
    (result,) = audit_paper(loads(text, "sign.toml").paper).results
    assert result.verdict.value == "needs-assumption", result.detail
