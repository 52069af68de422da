"""Mutation testing of the audit (issue 15): the machinery on small papers of our own, and a fixed
sample of the bundled papers' mutants that must all be killed or proved equivalent, none crashing.

``HAPTICPROOF_MUTANTS=all python -m pytest tests/test_mutate.py`` runs every mutant of every
bundled paper instead of the sample (tens of minutes; see ``benchmarks/README.md``);
``HAPTICPROOF_MUTANTS=N`` samples N per paper.
"""

from __future__ import annotations

import json
import sys
from pathlib import Path
import time

import pytest
import sympy as sp

from hapticproof.audit.runner import Paper
from hapticproof.audit.compare import compare_bounds
from hapticproof.core.evidence import Evidence, Finding, Method, Verdict
from hapticproof.audit.mutate import ENV_KNOB, Mutant, QuoteError, choose, generate, knob, mutants_of, mutate_paper, run_mutant
from hapticproof.audit.reader.names import SymbolTable
from hapticproof.audit.registry import get_paper, papers

sys.path.insert(0, str(Path(__file__).resolve().parent))

from clirun import run  # noqa: E402

K, T, b, B = sp.symbols("K T b B", positive=True)
TABLE = SymbolTable({"K": K, "T": T, "b": b, "B": B})
COLGATE = r"b > \frac{KT}{2} + B"


def own_paper(check, printed: str = COLGATE, **kwargs) -> Paper:
    paper = Paper("own", title="own", source="none", symbols=TABLE)
    paper.equation("1", kind="condition", printed=printed, **kwargs)(check)
    return paper


def computing(ctx):
    return compare_bounds(ctx.relation(), sp.Ge(b, K * T / 2 + B), b)


# ---------------------------------------------------------------------------------------------
# the machinery
# ---------------------------------------------------------------------------------------------


def test_every_operator_applies_to_a_condition():
    found = {m.operator: m.printed for m in generate(own_paper(computing).get("1"), own_paper(computing))}
    assert set(found) == {"sign", "scale", "drop", "relation", "symbol"}     # no subscripts: no swap
    assert found["relation"] == r"b < \frac{KT}{2} + B"


def test_a_computing_check_kills_every_mutant():
    report = mutate_paper(own_paper(computing))
    counts = report.counts()
    assert counts["crashed"] == 0 and counts["survived"] == 0, report.to_text()
    assert counts["killed"] + counts["equivalent"] == report.total > 5 and report.score == 1.0


def test_a_stub_check_is_found_out():
    def stub(ctx):
        return Finding(Verdict.CONFIRMED, "Colgate's condition", Evidence(Method.CANONICAL_FORM))

    report = mutate_paper(own_paper(stub))
    assert report.counts()["survived"] == report.total and report.score == 0.0
    assert "SURVIVED" in report.to_text()


def test_a_check_that_raises_is_a_crash_with_its_traceback():
    def fragile(ctx):
        rel = ctx.relation()
        if rel.rel_op != ">":
            raise ValueError("not a lower bound")
        return computing(ctx)

    report = mutate_paper(own_paper(fragile))
    (crash,) = report.crashes()
    assert crash.mutant.operator == "relation" and "ValueError: not a lower bound" in crash.detail
    assert "Traceback" in crash.reason or "raise ValueError" in crash.reason


def test_a_mutant_that_does_not_parse_is_malformed_not_a_traceback():
    paper = own_paper(computing)
    original = __import__("hapticproof.audit.runner", fromlist=["run_equation"]).run_equation(paper, paper.get("1"))
    broken = Mutant("own", "1", "1", "drop", 12, "{2}", "{2", r"b > \frac{KT}{2 + B")
    result = run_mutant(broken, original, {"own": paper})
    assert result.outcome == "killed" and result.verdict == Verdict.MALFORMED.value


def test_a_hanging_check_is_stopped_and_counted_as_a_crash():
    def slow(ctx):
        if ctx.equation.printed != COLGATE:
            deadline = time.process_time() + 30
            while time.process_time() < deadline:
                pass
        return computing(ctx)

    paper = own_paper(slow)
    from hapticproof.audit.runner import run_equation

    original = run_equation(paper, paper.get("1"))
    mutant = generate(paper.get("1"), paper)[0]
    result = run_mutant(mutant, original, {"own": paper}, limit=0.5)
    assert result.outcome == "crashed" and "MutantTimeout" in result.detail


def test_swapping_the_indices_of_a_symmetric_family_is_proved_equivalent():
    K01, K12 = sp.symbols("K_01 K_12", positive=True)          # K_{ij} = K_{ji}: both spellings, one symbol
    table = SymbolTable({"b": b, "T": T, "K_{01}": K01, "K_{10}": K01, "K_{12}": K12, "K_{21}": K12})
    paper = Paper("sym", title="sym", source="none", symbols=table)

    @paper.equation("1", kind="condition", printed=r"b > (K_{01} + K_{12})T")
    def check(ctx):
        return compare_bounds(ctx.relation(), sp.Ge(b, (K01 + K12) * T), b)

    swaps = [m for m in generate(paper.get("1"), paper) if m.operator == "swap"]
    assert {m.replacement for m in swaps} == {"K_{10}", "K_{21}"}
    report = mutate_paper(paper)
    assert all(r.outcome == "equivalent" for r in report.results if r.mutant.operator == "swap")
    assert report.score == 1.0 and not report.crashes()


#: A point where Colgate's condition b >= KT/2 + B fails (1/3 < 1/2).
FAILING = {b: sp.Rational(1, 3), K: 1, T: 1, B: 0}


def at_the_point(ctx):
    """A check with a fixed exact witness: the printed condition holding where the exact one fails is
    ``wrong`` (the same detail whatever the display), else it is compared exactly."""
    relation = ctx.relation()
    if bool(relation.subs(FAILING)):
        return Finding(Verdict.WRONG, "the printed condition holds at the witness where the exact one fails",
                       Evidence(Method.COUNTEREXAMPLE, witness={str(k): v for k, v in FAILING.items()}))
    return computing(ctx)


def test_mutants_that_keep_a_wrong_displays_defect_are_equivalent_not_survivors():
    # b > KT/4 + B is wrong (weaker than Colgate's condition); most of its mutants are wrong too
    report = mutate_paper(own_paper(at_the_point, r"b > \frac{KT}{4} + B"))
    kept = [r for r in report.results if r.basis == "defect"]
    assert kept and all(r.outcome == "equivalent" and r.verdict == "wrong" for r in kept)
    assert not report.survivors() and not report.crashes() and report.score == 1.0
    # the ones that moved (a reversed relation no longer holds at the witness) are killed
    assert any(r.outcome == "killed" and r.mutant.operator == "relation" for r in report.results)
    assert report.equivalence()["defect"] == len(kept)
    assert "defect" in report.summary()


def test_a_defect_without_evidence_keeps_nothing():
    def bare(ctx):                                    # 'wrong' with no witness: no proof of anything
        return Finding(Verdict.WRONG, "wrong", Evidence(Method.COUNTEREXAMPLE))

    report = mutate_paper(own_paper(bare, r"b > \frac{KT}{4} + B"))
    assert report.counts()["survived"] == report.total and report.score == 0.0


def test_a_stub_that_always_says_wrong_is_found_out_on_a_right_display():
    def stub(ctx):
        return Finding(Verdict.WRONG, "always", Evidence(Method.COUNTEREXAMPLE, witness={"b": 0}))

    right = mutate_paper(own_paper(stub))             # Colgate's condition itself, judged wrong
    assert right.counts()["equivalent"] == right.total   # the mutation test cannot tell: its mutants stay 'wrong'...
    confirmed = mutate_paper(own_paper(computing))       # ...which is why the check is also run on right displays
    assert confirmed.score == 1.0


def test_cli_mutate_of_a_paper_file_with_a_wrong_display_passes(capsys):
    # reviewer-walls (11) is wrong (a Tustin damper's bound with the sign of d_v lost): 15 of its 17
    # mutants are wrong too, at their own witnesses; they kept the defect, they did not survive
    paper = Path(__file__).resolve().parents[1] / "examples" / "reviewer-walls.toml"
    code, out, _ = run(capsys, "audit", "--paper", str(paper), "-e", "11", "--mutate", "--format", "json")
    data = json.loads(out)["papers"][0]
    assert code == 0
    assert data["counts"]["survived"] == 0 and data["counts"]["crashed"] == 0
    assert data["equivalence"]["defect"] == data["counts"]["equivalent"] > 10
    kept = [r for r in data["results"] if r["basis"] == "defect"]
    assert all(r["verdict"] == "wrong" and r["reason"].endswith("its own exact witness") for r in kept)
    assert {r["edit"] for r in kept} >= {"b_v -> -b_v", "> -> <"}


PAPER_FILE = """
[paper]
id = "walls"
title = "walls"
[symbols]
b = "positive"
K = "positive"
B = "nonnegative"
T = "positive"
[scenes.wall]
system = "single-user"
environment = "K + B*(z - 1)/(T*z)"
"""


def test_repairs_read_as_a_reviewer_writes_them(capsys, tmp_path):
    paper = tmp_path / "walls.toml"
    paper.write_text(PAPER_FILE + r"""
[[equations]]
id = "1"
printed = 'b > KT + B'
claim = "passivity-condition"
scene = "wall"

[[equations]]
id = "2"
printed = 'b > \frac{KT}{2} - B'
claim = "passivity-condition"
scene = "wall"
""")
    code, out, _ = run(capsys, "audit", "--paper", str(paper), "--format", "json")
    found = {e["id"]: e for e in json.loads(out)["equations"]}
    assert code == 0 and {e["verdict"] for e in found.values()} == {"typo"}
    assert found["1"]["detail"].startswith("one edit repairs it: KT -> KT/2 (a lost half) gives a display that is confirmed")
    assert found["1"]["corrected"] == r"b > \frac{KT}{2} + B"
    assert found["2"]["detail"].startswith("one edit repairs it: - B -> + B (a sign)")
    assert "position" not in found["1"]["detail"] + found["2"]["detail"] and "nothing" not in found["1"]["detail"]


def test_a_declared_quote_must_be_read():
    paper = own_paper(computing)
    paper.equation("claim", kind="claim", printed="the condition $b > KT/2 + B$ of (1)", quotes=("1",))(
        lambda ctx: Finding(Verdict.CONFIRMED, "no reading", Evidence(Method.PARSE)))
    with pytest.raises(QuoteError):
        mutants_of(paper, paper.get("claim"), {"own": paper})


def test_a_claim_is_audited_against_the_mutants_of_the_display_it_quotes():
    paper = own_paper(computing)

    @paper.equation("claim", kind="claim", printed="(1) is Colgate's condition", quotes=("1",))
    def claim(ctx):
        return computing(type(ctx)(paper, paper.get("1")))

    mutants = mutants_of(paper, paper.get("claim"), {"own": paper})
    assert mutants and all(m.target == "1" and m.equation == "claim" for m in mutants)
    report = mutate_paper(paper, ["claim"])
    assert report.score == 1.0 and not report.crashes()


def test_knob(monkeypatch):
    monkeypatch.delenv(ENV_KNOB, raising=False)
    assert knob() == 12
    monkeypatch.setenv(ENV_KNOB, "all")
    assert knob() is None
    monkeypatch.setenv(ENV_KNOB, "40")
    assert knob() == 40


def test_the_sample_is_deterministic_and_spread_over_equations():
    paper = get_paper("classics")
    one, generated = choose(paper, count=5, seed=3)
    two, _ = choose(paper, count=5, seed=3)
    assert one == two and generated > len(one) == 5
    assert len({m.equation for m in one}) == 5
    assert len({m.operator for m in one}) >= 3


# ---------------------------------------------------------------------------------------------
# the bundled papers: a fixed sample in CI, every mutant with HAPTICPROOF_MUTANTS=all
# ---------------------------------------------------------------------------------------------


@pytest.mark.parametrize("paper_id", list(papers()))
def test_bundled_paper_mutants_are_killed_or_proved_equivalent(paper_id):
    report = mutate_paper(get_paper(paper_id), count=knob(), seed=0)
    print(report.summary())
    assert report.total > 0
    assert not report.crashes() and not report.survivors(), report.to_text()
    assert report.score == 1.0


#: Survivors and crashes of the larger samples (``--sample 200``, seeds 0 and 1), each now
#: killed or proved equivalent: (paper, equation, text replaced, replacement, expected outcome).
LARGE_SAMPLE_CASES = [
    ("hve", "37", "V_{hi}(z)", "V_{hi}(-z)", "killed"),              # a signal at another argument
    ("hve", "37", r"\cdots, m", r"\cdots, 2 m", "killed"),          # the user range (crashed before)
    ("hve", "23", r"\cos(\omega t_d - T)", r"\cos(\omega t_d - K)", "killed"),   # not a function of cos(wT) (crashed)
    ("hve", "23a", r"= \lim", r"= 2 \lim", "killed"),              # a limit inside a member (crashed)
    ("hve", "47", "R_{0} =", "2 R_{0} =", "killed"),                 # the left side of the matrix display
    ("hve", "51-worst", r"$\cos(\omega T) = -1$", r"$2 \cos(\omega T) = -1$", "killed"),
    ("hve", "18", r"B", r"2 B", "equivalent"),                       # both hold for every admissible b
    ("teleoperator", "31", "e =", "2 e =", "killed"),                 # e's definition, not only its right side
    ("teleoperator", "31", "e =", "-e =", "equivalent"),              # the same spring potential
    ("teleoperator", "intro-less-conservative", "KT/2 - B", "KT/2 - 2 B", "killed"),
    ("cross-paper", "tele32-alpha1-29", None, None, "killed"),        # (29) with its relation reversed
]


@pytest.mark.parametrize("paper_id,eq_id,old,new,expected", LARGE_SAMPLE_CASES,
                         ids=[f"{c[0]}:{c[1]}:{c[3]}" for c in LARGE_SAMPLE_CASES])
def test_large_sample_mutants(paper_id, eq_id, old, new, expected):
    paper = get_paper(paper_id)
    equation = paper.get(eq_id)
    candidates = mutants_of(paper, equation)
    if old is None:       # a reversed relation of a quoted display
        chosen = [m for m in candidates if m.operator == "relation"]
    else:
        chosen = [m for m in candidates if m.printed == _replaced(paper, m, old, new)]
    assert chosen, "the mutant is not generated any more"
    from hapticproof.audit.mutate import _audit

    original = _audit(paper, equation)
    for mutant in chosen:
        result = run_mutant(mutant, original)
        assert result.outcome == expected, (mutant.printed, result.outcome, result.detail, result.reason)


def _replaced(paper, mutant, old, new):
    tpaper, _, tid = mutant.target.rpartition(":")
    text = (get_paper(tpaper) if tpaper else paper).get(tid).printed
    return text.replace(old, new, 1) if old in text else None


# ---------------------------------------------------------------------------------------------
# the command line
# ---------------------------------------------------------------------------------------------


def test_cli_mutate_prints_the_score(capsys):
    code, out, _ = run(capsys, "audit", "classics", "--mutate", "--equation", "colgate-wall", "--sample", "4")
    assert code == 0 and "classics:" in out and "score 100.0%" in out
    code, out, _ = run(capsys, "audit", "classics", "--mutate", "-e", "colgate-wall", "--sample", "2", "--format", "json")
    data = json.loads(out)["papers"][0]
    assert code == 0 and data["total"] == 2 and data["counts"]["crashed"] == 0


@pytest.mark.parametrize("argv, message", [
    (["audit", "hve", "--mutate", "--sample", "0"], "--sample must be a positive number"),
    (["audit", "hve", "--sample", "3"], "--sample needs --mutate"),
    (["audit", "hve", "--mutate", "--format", "tex"], "--mutate writes a table or JSON"),
    (["audit", "hve", "--mutate", "--jobs", "0"], "--jobs must be at least 1"),
])
def test_cli_mutate_usage_errors_are_one_line(capsys, argv, message):
    code, out, err = run(capsys, *argv)
    assert code == 2 and message in err and err.count("\n") == 1 and "Traceback" not in err
