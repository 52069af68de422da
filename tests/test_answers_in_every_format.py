"""Issue 21 (part B, item 4): what the designer asked for appears in every format -- the delay
margin and passive ranges as mathematics in LaTeX (not % comments) -- and text output is readable:
reduced rationals, helper symbols defined where they are used, words for booleans, plurals."""

import json
import re

import pytest

from hapticproof.cli import main


def run(capsys, *argv):
    code = main(list(argv))
    out = capsys.readouterr()
    assert code == 0, out.err
    return out.out


WALL = ["--param", "K=2", "--param", "T=0.001", "--param", "b=0.02", "--param", "B=0.001"]
FILTERED = ["--environment", "K + B*(1-a)*(z-1)/(T*(z-a))", "--param", "B=0.005", "--param", "a=0.5",
            "--param", "T=0.001", "--param", "b=0.02", "--delay", "2"]


def displays(latex: str) -> list[str]:
    return re.findall(r"\\begin\{equation\*\}(.*?)\\end\{equation\*\}", latex, flags=re.S)


@pytest.mark.parametrize("fragment", [[], ["--fragment"]])
def test_single_user_margin_and_range_are_displays(capsys, fragment):
    latex = run(capsys, "derive", "single-user", *WALL, "--delay-margin", "--range", "K", "--format", "latex", *fragment)
    if fragment:
        shown = " ".join(displays(latex))
        assert r"N_{\max} = 10" in shown and r"t_d \le N_{\max} T = \frac{1}{100}" in shown
        assert r"0 < K \le 38" in shown
    else:        # the document sets each display as breakable pieces under its label
        assert r"\hplabel{delay margin (-{}-delay-margin)}" in latex and r"\hplabel{passive range of K (-{}-range K)}" in latex
        assert r"\hpfit{N_{\max}}" in latex and r"\hpfit{{}= \frac{1}{100}}" in latex and r"\hpfit{{}\le 38" in latex
    assert not re.search(r"^% (delay margin:|passive range of K \(others fixed\))", latex, flags=re.M)


def test_an_algebraic_end_is_defined_in_the_display_with_a_short_interval(capsys):
    latex = run(capsys, "derive", "single-user", *FILTERED, "--range", "K", "--format", "latex", "--fragment")
    (answer,) = [d for d in displays(latex) if "K^{*}_{1}" in d]
    assert r"0 < K \le K^{*}_{1}" in answer and "961 K^{4} + 34670 K^{3} - 32755 K^{2} - 2688600 K - 8926500" in answer
    assert "[9, 10]" in answer and "73786976294838206464" not in answer          # no 2^66 denominators
    text = run(capsys, "derive", "single-user", *FILTERED, "--range", "K")
    assert "961*K**4 + 34670*K**3 - 32755*K**2 - 2688600*K - 8926500 in [9, 10]" in text
    data = json.loads(run(capsys, "derive", "single-user", *FILTERED, "--range", "K", "--format", "json"))
    assert data["passive_ranges"]["K"]["intervals"][0]["hi"]["isolating_interval"] == ["9", "10"]


def test_multi_user_and_teleoperator_answers_are_displays(capsys):
    latex = run(capsys, "derive", "multi-user", "--users", "2", "--uniform", "--param", "b=0.02", "--param", "K_0=10",
                "--param", "K=5", "--param", "B_0=0", "--param", "B=0", "--param", "T=0.001", "--delay-margin",
                "--range", "K", "--format", "latex", "--fragment")
    assert r"N_{\max} = 0" in latex and r"0 < K \le 15" in latex
    latex = run(capsys, "derive", "teleoperator", "--param", "K=20", "--param", "B=0.01", "--param", "T=0.001",
                "--param", "b_s=0.05", "--range", "b_m", "--format", "latex", "--fragment")
    # the exact condition h = b_m b_s/(b_m + b_s) >= KT/2 + B (the paper's (32) would say 1/25)
    assert any(r"\frac{1}{30} \le b_{m}" in d for d in displays(latex))


def test_roles_name_the_period_in_the_margin(capsys):
    latex = run(capsys, "derive", "single-user", "--role", "period=Ts", "--param", "K=2", "--param", "Ts=0.001",
                "--param", "b=0.02", "--param", "B=0.001", "--delay-margin", "--format", "latex", "--fragment")
    assert r"t_d \le N_{\max} Ts = \frac{1}{100}" in latex


def test_text_rationals_are_reduced(capsys):
    text = run(capsys, "derive", "single-user", *WALL)
    assert "Re G^-1 (c = cos wT) = c/1000 + 19/1000" in text and "/(2)" not in text


def test_multi_user_text_has_words_and_defined_helpers(capsys):
    text = run(capsys, "derive", "multi-user", "--users", "2", "--delay", "1,3", "--param", "b=0.003", "--param",
               "K_0=10", "--param", "K=5", "--param", "B_0=0.001", "--param", "B=0.0001", "--param", "T=0.001")
    assert not re.search(r"\b(True|False|None)\b", text)
    assert "worst case (root-isolation): M(c) is not PSD for every c: fails at c = -3/5" in text
    assert "s_theta = sin wT" in text and "z = -3/5 + j*4/5" in text and "Matrix([" not in text
    symbolic = run(capsys, "derive", "multi-user", "--users", "2", "--delay", "1,2")
    assert "4096" not in symbolic and "16384" not in symbolic and not re.search(r"\b(True|False|None)\b", symbolic)
    latex = run(capsys, "derive", "multi-user", "--users", "2", "--delay", "1,2", "--format", "latex")
    assert "s_{theta}" not in latex and r"\sin(\omega T)" in latex
    uniform = run(capsys, "derive", "multi-user", "--users", "2", "--uniform", "--param", "b=0.02", "--param", "K_0=10",
                  "--param", "K=5", "--param", "B_0=0", "--param", "B=0", "--param", "T=0.001")
    assert "M(c) is PSD for every c in [-1, 1]" in uniform


def test_symbolic_delay_defines_theta(capsys):
    text = run(capsys, "derive", "single-user", "--delay", "n")
    assert "symbolic delay n = t_d/T" in text and "Re G^-1 (theta = wT, for every integer n)" in text


def test_plurals_in_audit_text(capsys):
    main(["audit", "hve", "--equation", "25"])
    out = capsys.readouterr()
    assert "1 equation (needs-assumption: 1)" in out.out and "1 equations" not in out.out + out.err
    assert "1 equation in 1 paper" in out.err
