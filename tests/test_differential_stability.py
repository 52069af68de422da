"""Differential tests: the one stability decision of the exact ZOH loop against an oracle written
from the definition (``tests/oracles/loops.py``: the characteristic polynomial of the
sample-to-sample map in interval or exact rational arithmetic, ``z = 1`` from the kernel of the
stiffness matrix, the Schur-Cohn count of the rest; no code of the package).

The loop is asymptotically stable iff every eigenvalue is strictly inside the unit circle:
``rho = 1`` exactly (a mode whose position nothing feeds back -- ``K = 0``, ``K_0 = 0`` with a
singular stiffness matrix, a free teleoperator) is never ``stable``. The same physics must get
the same answer through every system kind (one user, m users, two decoupled users, a
teleoperator) and entry point (:func:`~hapticproof.analysis.sampled.decide_stability`,
:func:`~hapticproof.analysis.sampled.certified_stability`,
:func:`~hapticproof.analysis.boundary.certified_stable` -- the audit's single-user stability
claims --, ``hapticproof map stability``).

Size knob: ``HAPTICPROOF_STABILITY_EXAMPLES`` (default 12 random cases per family) and
``HAPTICPROOF_STABILITY_SEED``.
"""

from __future__ import annotations

import io
import os
import random
import sys
from contextlib import redirect_stderr, redirect_stdout
from fractions import Fraction
from pathlib import Path

import pytest

sys.path.insert(0, str(Path(__file__).resolve().parent))

from oracles.loops import loop_stability, multi_user_matrices, teleoperator_matrices, uniform_matrices  # noqa: E402
from oracles.result import NO, YES  # noqa: E402

from hapticproof.analysis.boundary import certified_stable  # noqa: E402
from hapticproof.analysis.sampled import certified_stability, decide_stability  # noqa: E402
from hapticproof.cli import main  # noqa: E402
from hapticproof.systems.loops import MultiUser, SingleUser, Teleoperator  # noqa: E402

F = Fraction
EXAMPLES = int(os.environ.get("HAPTICPROOF_STABILITY_EXAMPLES", "12"))
SEED = int(os.environ.get("HAPTICPROOF_STABILITY_SEED", "27"))


# ---------------------------------------------------------------------------------------------
# both sides of one case
# ---------------------------------------------------------------------------------------------


def single(m, b, T, K, B=0, delay=0):
    """The package's scene and the oracle's arguments of one user on a wall."""
    return (SingleUser(m=m, b=b, T=T, K=K, B=B, delay=delay),
            ([m], [b], T, [[F(K)]], [[F(B)]], [[delay]]))


def multi(masses, dampings, T, K0, B0, KC, BC, delays):
    users = len(masses)
    scene = MultiUser(masses=tuple(masses), dampings=tuple(dampings), T=T, ground_stiffness=tuple(K0),
                      ground_damping=tuple(B0), coupling_stiffness=tuple(map(tuple, KC)),
                      coupling_damping=tuple(map(tuple, BC)), delays=tuple(delays), operators=(None,) * users)
    Kmat, Bmat = multi_user_matrices(K0, B0, KC, BC)
    return scene, (masses, dampings, T, Kmat, Bmat, [[n] * users for n in delays])


def uniform(users, m, b, T, K0, B0, K, B):
    full = lambda v: [[0 if i == j else v for j in range(users)] for i in range(users)]  # noqa: E731
    scene, _ = multi([m] * users, [b] * users, T, [K0] * users, [B0] * users, full(K), full(B), [0] * users)
    Kmat, Bmat = uniform_matrices(users, K0, B0, K, B)
    return scene, ([m] * users, [b] * users, T, Kmat, Bmat, [[0] * users for _ in range(users)])


def tele(m_m, m_s, b_m, b_s, T, K, B, alpha=1, delay=0):
    Kmat, Bmat = teleoperator_matrices(K, B, alpha)
    return (Teleoperator(m_m=m_m, m_s=m_s, b_m=b_m, b_s=b_s, T=T, K=K, B=B, alpha=alpha, delay=delay),
            ([m_m, m_s], [b_m, b_s], T, Kmat, Bmat, [[0, delay], [delay, 0]]))


def agree(case) -> tuple[str, str | None]:
    """Decide a case both ways and assert they agree; the package's and the oracle's kinds."""
    scene, args = case
    oracle = loop_stability(*args)
    ours = decide_stability(scene)
    assert certified_stability(scene) is ours.stable
    where = f"{scene!r}: package {ours.verdict} ({ours.reason}), oracle {oracle.summary()}"
    assert len(ours.fixed_points) == oracle.details["at_one"], where
    if oracle.verdict == YES:
        assert ours.verdict in ("stable", "undecided"), where
    elif oracle.verdict == NO:
        assert ours.stable is not True, where          # rho >= 1 is never "stable"
        kind = oracle.details["kind"]
        if kind == "marginal":
            assert ours.verdict in ("marginal", "on-circle"), where
        elif kind == "unstable":
            assert ours.verdict in ("unstable", "on-circle", "undecided"), where
    return ours.verdict, oracle.details["kind"]


# ---------------------------------------------------------------------------------------------
# the marginal cases, one by one
# ---------------------------------------------------------------------------------------------
M, BD, TS = F(1, 50), F(1, 100), F(1, 1000)

MARGINAL = {
    "K = 0 (the issue's map)": (single(M, BD, TS, 0, F(1, 1000)), "marginal"),
    "K = 0, B = 0": (single(M, BD, TS, 0, 0), "marginal"),
    "K = 0, delayed": (single(M, BD, TS, 0, F(1, 1000), 2), "marginal"),
    "K = 0, b = 0, B > 0 (exact rationals)": (single(M, 0, TS, 0, F(1, 100)), "marginal"),
    "free mass (b = 0, no controller): Jordan block": (single(1, 0, F(1, 10), 0, 0), "unstable"),
    "b = 0, K > 0, B = 0: on the circle": (single(1, 0, F(1, 10), 1, 0), None),
    "a wall": (single(M, BD, TS, 1, F(1, 1000)), "stable"),
    "two decoupled users, K_0 = 0": (uniform(2, M, BD, TS, 0, F(1, 1000), 0, 0), "marginal"),
    "two decoupled users, K_0 = 1": (uniform(2, M, BD, TS, 1, F(1, 1000), 0, 0), "stable"),
    "three users coupled by dampers only": (uniform(3, M, BD, TS, 0, F(1, 1000), 0, F(1, 1000)), "marginal"),
    "three users coupled by springs, no ground": (uniform(3, M, BD, TS, 0, F(1, 1000), 1, F(1, 1000)), "marginal"),
    "three users coupled by springs and grounded": (uniform(3, M, BD, TS, 1, F(1, 1000), 1, F(1, 1000)), "stable"),
    "negative coupling springs": (uniform(3, M, BD, TS, 1, F(1, 1000), -1, F(1, 1000)), "unstable"),
    "a negative coupling damper": (uniform(3, M, BD, TS, 1, F(1, 1000), 1, F(-1, 1000)), "stable"),
    "a free teleoperator": (tele(F(3, 200), F(3, 200), F(911, 50000), F(911, 50000), F(3, 200), 1, 0), "marginal"),
    "a free teleoperator, K = 0": (tele(F(3, 200), F(3, 200), F(911, 50000), F(911, 50000), F(3, 200), 0, F(1, 1000)),
                                   "marginal"),
}


@pytest.mark.parametrize("name", list(MARGINAL))
def test_marginal_cases_match_the_oracle(name):
    case, expected = MARGINAL[name]
    ours, kind = agree(case)
    if expected is not None:
        assert kind == expected, name
        assert ours == expected, name


def test_rho_one_is_not_stable_through_every_entry_point():
    """``K = 0``: the eigenvalue ``z = 1`` is exact, every route says "not stable"."""
    assert certified_stability(SingleUser(m=M, b=BD, T=TS, K=0, B=F(1, 1000))) is False
    outcome = certified_stable(m=M, b=BD, T=TS, K=0, B=F(1, 1000))
    assert outcome.decision.value == "disproved"
    assert outcome.evidence.facts["fixed_points"] == [["1", "0", "1"]]
    assert certified_stable(m=M, b=BD, T=TS, K=1, B=F(1, 1000)).decision.value == "proved"


def _map(*argv: str) -> dict[tuple[str, str], str]:
    out = io.StringIO()
    with redirect_stdout(out):
        assert main(["map", "stability", *argv, "-o", "-"]) == 0
    rows = out.getvalue().strip().splitlines()[1:]
    return {tuple(r.split(",")[:2]): r.split(",")[2] for r in rows}


def test_the_issue_maps_match_the_oracle():
    """The issue's two maps: ``K = 0`` is not stable (1 before), two decoupled users (``K_0 = 0``,
    ``K = 0``) as one user, users coupled by dampers not stable."""
    one = _map("single-user", "--x", "K=0,1", "--y", "B=0.001,0.002", "--param", "m=0.02", "--param", "b=0.01",
               "--param", "T=0.001")
    for (K, B), value in one.items():
        verdict, _ = agree(single(M, BD, TS, F(K), F(B)))
        assert value == {"stable": "1", "undecided": "-1"}.get(verdict, "0"), (K, B, value, verdict)
    assert one[("0", "0.001")] == "0" and one[("1", "0.001")] == "1"
    three = _map("multi-user", "--users", "3", "--uniform", "--x", "K_0=0,1", "--y", "K=0,1,5", "--param", "m=0.02",
                 "--param", "b=0.01", "--param", "T=0.001", "--param", "B=0.001", "--param", "B_0=0.001")
    for (K0, K), value in three.items():
        verdict, _ = agree(uniform(3, M, BD, TS, F(K0), F(1, 1000), F(K), F(1, 1000)))
        assert value == {"stable": "1", "undecided": "-1"}.get(verdict, "0"), (K0, K, value, verdict)
    assert [three[("0", k)] for k in ("0", "1", "5")] == ["0", "0", "0"]


# ---------------------------------------------------------------------------------------------
# random cases
# ---------------------------------------------------------------------------------------------


def _gain(rng: random.Random, scale: Fraction, signed: bool = False) -> Fraction:
    """0 often (the marginal cases), else ``scale`` times a small rational (near boundaries)."""
    if rng.random() < 0.3:
        return F(0)
    value = scale * F(rng.choice([1, 2, 3, 5, 9, 11, 19, 21, 40]), rng.choice([2, 4, 10, 20]))
    return -value if signed and rng.random() < 0.25 else value


def _physics(rng: random.Random) -> tuple[Fraction, Fraction, Fraction]:
    m = F(rng.choice([1, 2, 3]), rng.choice([50, 100, 10]))
    b = F(0) if rng.random() < 0.15 else F(rng.choice([1, 2, 5]), rng.choice([100, 1000]))
    T = F(1, rng.choice([10, 100, 1000]))
    return m, b, T


def test_random_single_users_match_the_oracle_and_every_route():
    rng = random.Random(SEED)
    kinds = []
    for _ in range(EXAMPLES):
        m, b, T = _physics(rng)
        K, B, n = _gain(rng, (b or F(1, 100)) / T), _gain(rng, b or F(1, 100), signed=True), rng.choice([0, 0, 1, 2])
        ours, kind = agree(single(m, b, T, K, B, n))
        kinds.append(kind)
        # the same physics as one user of a multi-user scene, as two decoupled users, and through
        # the audit's single-user route
        assert decide_stability(multi([m], [b], T, [K], [B], [[0]], [[0]], [n])[0]).verdict == ours
        assert decide_stability(uniform(2, m, b, T, K, B, 0, 0)[0]).verdict == ours if n == 0 else True
        expected = {"stable": "proved", "undecided": "undecided"}.get(ours, "disproved")
        assert certified_stable(m=m, b=b, T=T, K=K, B=B, n=n).decision.value == expected
    assert None not in kinds[: max(1, len(kinds) // 2)] or kinds.count(None) <= len(kinds) // 3


def test_random_multi_users_match_the_oracle():
    rng = random.Random(SEED + 1)
    for _ in range(EXAMPLES):
        users = rng.choice([2, 3])
        m, b, T = _physics(rng)
        masses = [m * rng.choice([1, 2]) for _ in range(users)]
        dampings = [b * rng.choice([1, 2]) for _ in range(users)]
        K0 = [_gain(rng, (b or F(1, 100)) / T) for _ in range(users)]
        B0 = [_gain(rng, b or F(1, 100), signed=True) for _ in range(users)]
        KC = [[F(0)] * users for _ in range(users)]
        BC = [[F(0)] * users for _ in range(users)]
        for i in range(users):
            for j in range(i + 1, users):
                KC[i][j] = KC[j][i] = _gain(rng, (b or F(1, 100)) / T, signed=True)
                BC[i][j] = BC[j][i] = _gain(rng, b or F(1, 100), signed=True)
        agree(multi(masses, dampings, T, K0, B0, KC, BC, [rng.choice([0, 0, 1]) for _ in range(users)]))


def test_random_teleoperators_match_the_oracle():
    rng = random.Random(SEED + 2)
    for _ in range(EXAMPLES):
        m, b, T = _physics(rng)
        K, B = _gain(rng, (b or F(1, 100)) / T, signed=True), _gain(rng, b or F(1, 100), signed=True)
        alpha = rng.choice([F(1), F(2), F(-1, 2)])
        agree(tele(m, m * rng.choice([1, 2]), b, b * rng.choice([1, 2]), T, K, B, alpha, rng.choice([0, 0, 1])))


def test_a_free_teleoperator_map_is_never_stable_and_says_why():
    """A free teleoperator keeps the translation ``(1, alpha)`` (``z = 1``): every point is 0, and
    the map says so (the boundary of the relative motion is ``boundary``'s)."""
    err = io.StringIO()
    with redirect_stderr(err):
        values = _map("teleoperator", "--x", "K=1/2,2", "--y", "T=0.015,0.015", "--param", "m=0.015",
                      "--param", "b=0.01822")
    assert set(values.values()) == {"0"}
    assert "free translation" in err.getvalue()
    for K in (F(1, 2), F(2)):
        agree(tele(F(3, 200), F(3, 200), F(911, 50000), F(911, 50000), F(3, 200), K, 0))
