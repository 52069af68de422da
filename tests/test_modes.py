"""Uniform m-user scenes decided by modes (:mod:`hapticproof.analysis.modes`) against the matrix
route and the independent oracle.

Differential: random uniform scenes (2 to 6 users; complete, path, ring and star graphs; delays
0-3; the three approximations; ``b`` placed 1e-6 relative above or below the boundary of the
extreme mode, or far from it) are decided three ways: by the two extreme modes, by the matrix route
(every characteristic coefficient of the m x m Hermitian part decided by the kernel:
:func:`hapticproof.exact.psd.decide_psd_on_circle`) and by the numeric oracle of
``tests/oracles/discrete.py`` (written from the paper, importing nothing from the package). The
three must agree (the oracle only when it is certain). Size knob: ``HAPTICPROOF_DIFF_EXAMPLES``
(this family uses half of it).
"""

from __future__ import annotations

import sys
from fractions import Fraction
from pathlib import Path

import pytest
import sympy as sp
from hypothesis import HealthCheck, Phase, given, settings
from hypothesis import strategies as st

sys.path.insert(0, str(Path(__file__).resolve().parent))

from certified import assert_certified  # noqa: E402
from oracles.discrete import multi_user_positive_real  # noqa: E402
from oracles.harness import examples, expected_decision  # noqa: E402

from hapticproof.analysis.fastpath import critical_damping  # noqa: E402
from hapticproof.analysis.modes import graph_kind, largest_eigenvalue, mode_conditions, mode_wall, spectrum  # noqa: E402
from hapticproof.analysis.multiuser import conditions, hermitian, transfer_entries, worst_case  # noqa: E402
from hapticproof.core.evidence import Decision  # noqa: E402
from hapticproof.exact.conditions import combine  # noqa: E402
from hapticproof.exact.psd import decide_psd_on_circle  # noqa: E402
from hapticproof.systems.multiuser import UNIFORM_SYMBOLS, MultiUserScene, laplacian  # noqa: E402
from hapticproof.systems.scene import Scene  # noqa: E402

R = sp.Rational
SETTINGS = dict(deadline=None, phases=(Phase.explicit, Phase.reuse, Phase.generate),
                suppress_health_check=[HealthCheck.too_slow, HealthCheck.filter_too_much])


def _edges(kind: str, m: int) -> list[tuple[int, int]] | None:
    if kind == "complete":
        return None
    if kind == "path":
        return [(i, i + 1) for i in range(m - 1)]
    if kind == "ring":
        return [(i, i + 1) for i in range(m - 1)] + [(0, m - 1)]
    return [(0, i) for i in range(1, m)]


@st.composite
def uniform_cases(draw) -> dict:
    m = draw(st.integers(2, 6))
    kind = draw(st.sampled_from(["complete", "path", "ring", "star"]))
    if kind == "ring" and m < 3:
        kind = "path"
    T = R(draw(st.integers(1, 9)), 10) ** draw(st.integers(1, 3))
    K0 = R(draw(st.integers(1, 40))) / (10 * T)
    K = R(draw(st.integers(0, 40))) / (100 * T)
    B0 = R(draw(st.integers(0, 5)), 1000)
    B = R(draw(st.integers(0, 5)), 1000)
    n = draw(st.integers(0, 3))
    approximation = draw(st.sampled_from(["forward", "backward", "tustin"]))
    side = draw(st.sampled_from(["above", "below", "far-above", "far-below"]))
    return dict(m=m, kind=kind, T=T, K0=K0, K=K, B0=B0, B=B, n=n, approximation=approximation, side=side)


def _scene(case: dict, b: Fraction) -> MultiUserScene:
    return MultiUserScene.uniform(case["m"], b=b, K0=case["K0"], B0=case["B0"], K=case["K"], B=case["B"], T=case["T"],
                                  delay=case["n"], edges=_edges(case["kind"], case["m"]), approximation=case["approximation"])


def _boundary(case: dict) -> Fraction:
    """The largest critical damping of the modes (placement only: the verdicts are judged elsewhere)."""
    probe = _scene(case, 1)
    top = largest_eigenvalue(probe)
    lams = [Fraction(0), Fraction(str(sp.N(top, 30)))]
    return max(critical_damping(mode_wall(probe, lam))[1] for lam in lams)


def test_modes_agree_with_the_matrix_route_and_the_oracle():
    @settings(max_examples=examples(0.5), **SETTINGS)
    @given(case=uniform_cases())
    def run(case):
        b_star = _boundary(case)
        rel = {"above": Fraction(1, 10**6), "below": -Fraction(1, 10**6), "far-above": Fraction(1, 10),
               "far-below": -Fraction(1, 10)}[case["side"]]
        b = max(b_star * (1 + rel), Fraction(0)) if b_star > 0 else Fraction(1, 10**6) * (1 + rel)
        scene = _scene(case, sp.Rational(b.numerator, b.denominator))
        by_modes = combine(mode_conditions(scene))
        assert_certified(by_modes)
        matrix = decide_psd_on_circle(hermitian(scene), transfer=transfer_entries(scene))
        assert by_modes.decision != Decision.UNDECIDED, by_modes.reason
        # the pole and residue conditions hold for every uniform scene: the verdict is the Hermitian part's
        assert by_modes.decision == matrix.decision, (case, b, by_modes.reason, matrix.outcome.reason)
        edges = scene.edges
        oracle = multi_user_positive_real(b=[b] * case["m"], T=case["T"], K0=[case["K0"]] * case["m"],
                                          B0=[case["B0"]] * case["m"], K={e: case["K"] for e in edges},
                                          B={e: case["B"] for e in edges}, delays=[case["n"]] * case["m"],
                                          approximation=case["approximation"])
        want = expected_decision(oracle)
        assert want in (None, by_modes.decision.value), (case, b, oracle.summary())

    run()


@pytest.mark.parametrize("kind,m", [("complete", 4), ("path", 5), ("ring", 5), ("ring", 6), ("star", 5)])
def test_spectra_are_the_laplacians(kind, m):
    scene = MultiUserScene.uniform(m, edges=_edges(kind, m))
    assert graph_kind(scene) == kind
    L = laplacian([0] * m, scene.weights([1] * len(scene.edges)))
    want = L.eigenvals()
    got = spectrum(scene)
    assert sum(got.values()) == m
    for lam, mult in got.items():
        assert any(sp.simplify(lam - w) == 0 and mult == k for w, k in want.items()), (lam, want)
    assert sp.simplify(largest_eigenvalue(scene) - max(want, key=lambda v: float(v))) == 0


def test_a_disproof_by_modes_carries_a_witness_of_the_matrix():
    """At the witness c of the failing mode, the m x m Hermitian part itself has a negative eigenvalue."""
    scene = MultiUserScene.uniform(5, b=R(1, 100), K0=10, B0=0, K=5, B=R(1, 1000), T=R(1, 1000), delay=1,
                                   edges=[(i, i + 1) for i in range(4)] + [(0, 4)])
    out = combine(mode_conditions(scene))
    assert out.decision == Decision.DISPROVED
    re, im = (sp.Rational(str(v)) for v in out.witness["z"])
    M = hermitian(scene).at(re, im)                        # the exact 5 x 5 Hermitian part at z0
    assert min(sp.re(v) for v in M.evalf(40).eigenvals()) < 0


def test_conditions_route_by_modes_from_five_users_and_agree_below():
    for m in (4, 5):
        scene = MultiUserScene.uniform(m, b=R(3, 100), K0=10, B0=R(1, 1000), K=2, B=R(1, 1000), T=R(1, 1000), delay=2)
        got = [c.decision for c in conditions(scene)]
        want = [c.decision for c in mode_conditions(scene)]
        assert got == want
        assert worst_case(scene).decision == want[-1]


def test_a_thousand_users_at_the_exact_boundary():
    """m = 1000 (the time is measured in benchmarks/README.md, not here): the undelayed forward
    wall's condition b >= (K_0 + m K) T/2 + B_0 + m B is exact, so b at it is passive, below not."""
    params = {"K_0": 1, "B_0": "0.001", "K": "0.01", "B": "0.00001", "T": "0.001"}
    bound = R(1, 1000) * (1 + 1000 * R(1, 100)) / 2 + R(1, 1000) + 1000 * R(1, 100000)
    for b, want in ((bound, Decision.PROVED), (bound - R(1, 10**9), Decision.DISPROVED)):
        scene = Scene("multi-user", users=1000, uniform=True, params=dict(params, b=str(b))).build()
        out = combine(conditions(scene))
        assert_certified(out)
        assert out.decision == want


def test_symbolic_uniform_many_users_is_the_exact_condition():
    scene = Scene("multi-user", users=20, uniform=True).build()
    wc = worst_case(scene)
    u = UNIFORM_SYMBOLS
    assert wc.method == "uniform-modes"
    exact = u["b"] - (20 * u["B"] + u["B_0"] + 10 * u["K"] * u["T"] + u["K_0"] * u["T"] / 2)
    assert sp.expand(wc.condition.lhs - wc.condition.rhs - exact) == 0
    got = [c.decision for c in conditions(scene)]
    assert got[:3] == [Decision.PROVED] * 3 and got[3] == Decision.SYMBOLIC


def test_delay_margin_by_modes_is_the_matrix_routes():
    """The margin from the two extreme modes against every delay decided on the 5 x 5 matrix."""
    from dataclasses import replace

    from hapticproof.analysis.design import delay_margin

    for edges in (None, [(i, i + 1) for i in range(4)]):          # lambda_max = 5, and 2 + 2 cos(pi/5)
        scene = MultiUserScene.uniform(5, b=R(6, 100), K0=2, B0=R(1, 1000), K=1, B=R(1, 10000), T=R(1, 1000),
                                       edges=edges)
        dm = delay_margin(scene)
        assert dm.decision == Decision.PROVED and dm.method.startswith("modes")
        assert 0 <= dm.margin < 12
        for n in range(dm.margin + 2):
            at_n = replace(scene, delays=(n,) * 5)
            matrix = decide_psd_on_circle(hermitian(at_n), transfer=transfer_entries(at_n)).decision
            assert matrix == (Decision.PROVED if n <= dm.margin else Decision.DISPROVED), (edges, n, dm.margin)


def test_equal_scenes_hash_equal_however_built():
    """The memoised hash follows equality: pickled copies (worker processes) and complete graphs
    given edge by edge hash like the original."""
    import itertools
    import pickle

    a = MultiUserScene.uniform(4, b=R(1, 50), K0=1, B0=0, K=2, B=0, T=R(1, 1000))
    hash(a)
    b = pickle.loads(pickle.dumps(a))
    c = MultiUserScene.uniform(4, b=R(1, 50), K0=1, B0=0, K=2, B=0, T=R(1, 1000),
                               edges=list(itertools.combinations(range(4), 2)))
    assert a == b == c and hash(a) == hash(b) == hash(c)
    ring = MultiUserScene.uniform(4, edges=[(0, 1), (1, 2), (2, 3), (0, 3)])
    assert ring != a and pickle.loads(pickle.dumps(ring)) == ring


def test_uniform_scenes_with_a_numeric_damping_and_symbolic_couplings():
    """Found by the fuzz test: b given as a number, the rest symbolic. b = 0 is settled by the
    parameters' signs (disproved); b = 2 keeps the condition of the top mode lambda = 2,
    b >= (K_0 + 2K) T/2 + B_0 + 2B, with nothing solved 'for the number 2'."""
    import sympy as sp

    from hapticproof.analysis.multiuser import worst_case
    from hapticproof.systems.scene import Scene

    zero = worst_case(Scene("multi-user", users=2, uniform=True, params={"b": 0}).build())
    assert zero.outcome.decision.value == "disproved"
    two = worst_case(Scene("multi-user", users=2, uniform=True, params={"b": 2}).build())
    names = {s.name: s for s in two.condition.free_symbols}
    K, K0, B, B0, T = (names[n] for n in ("K", "K_0", "B", "B_0", "T"))
    assert isinstance(two.condition, sp.Ge) and two.condition.lhs == 2
    assert sp.simplify(two.condition.rhs - ((K0 + 2 * K) * T / 2 + B0 + 2 * B)) == 0
