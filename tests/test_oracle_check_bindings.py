"""``hapticproof check`` against an independent oracle of the reports' bindings.

The oracle below is written from the definitions alone (no hapticproof module is imported except
the command line, to produce the reports, and :func:`check_report`, the subject):

* single user (HVE paper): ``G^-1(z) = (b - z_a) + z^-n H(z) X(z)``, ``H = K + B (z - 1)/(T z)``,
  ``X = T/(z - 1)`` (forward), ``T z/(z - 1)`` (backward), ``T (z + 1)/(2 (z - 1))`` (Tustin);
* m users: ``G^-1_ij = (b_i - z_ai) delta_ij + z^-n_i H_ij X``, ``H = Kmat + Bmat (z - 1)/(T z)`` with
  ``Kmat = diag(K_0i) + Laplacian(K_ij)`` on the graph's edges, ``Bmat`` likewise;
* the Hermitian part on the circle ``M(theta) = G^-1(e^{j theta}) + G^-1(e^{j theta})^H`` (the
  single-user report displays ``Re G^-1 = M/2``), its principal minors, the residue at ``z = 1``;
* a network's ``Z(s)`` from its matrix file.

Every comparison is exact: values are Gaussian rationals (pairs of ``Fraction``), points on the
unit circle are the rational points ``z = ((1 - t^2) + 2 j t)/(1 + t^2)`` (``c = cos theta`` and
``s_theta = sin theta`` rational), and the truth of a worst case (``M(c) PSD for every c``) is
decided exactly from the oracle's own principal minors as rational functions of ``c`` (``z^k``
expanded binomially in ``c + j s`` with ``s^2 = 1 - c^2``; real roots isolated by SymPy).

The tests: every genuine report's scene block, definition transfer, displays (``G_inverse``,
``hermitian_part``, principal minors, residues, worst case) equal the oracle's and ``check``
accepts it; every forgery that changes one thing a reader relies on -- made sure to be false by the
oracle -- is refused.
"""

from __future__ import annotations

import ast
import copy
import random
import sys
from fractions import Fraction
from functools import cache
from itertools import combinations, pairwise
from pathlib import Path

import pytest
import sympy

from hapticproof.exact.checker import check_report

sys.path.insert(0, str(Path(__file__).parent))
from clirun import json_of

RNG_SEED = 3030
POINTS = 5


# ---------------------------------------------------------------- exact Gaussian rationals


class Q2:
    """An exact complex number ``re + j im`` with rational parts."""

    __slots__ = ("im", "re")

    def __init__(self, re, im=0):
        self.re = Fraction(re)
        self.im = Fraction(im)

    @staticmethod
    def of(x) -> Q2:
        return x if isinstance(x, Q2) else Q2(x)

    def __add__(self, o):
        o = Q2.of(o)
        return Q2(self.re + o.re, self.im + o.im)

    __radd__ = __add__

    def __neg__(self):
        return Q2(-self.re, -self.im)

    def __sub__(self, o):
        return self + (-Q2.of(o))

    def __rsub__(self, o):
        return Q2.of(o) - self

    def __mul__(self, o):
        o = Q2.of(o)
        return Q2(self.re * o.re - self.im * o.im, self.re * o.im + self.im * o.re)

    __rmul__ = __mul__

    def conj(self):
        return Q2(self.re, -self.im)

    def __truediv__(self, o):
        o = Q2.of(o)
        n = o.re * o.re + o.im * o.im
        if n == 0:
            raise ZeroDivisionError("division by 0 in the oracle")
        p = self * o.conj()
        return Q2(p.re / n, p.im / n)

    def __rtruediv__(self, o):
        return Q2.of(o) / self

    def __pow__(self, k: int):
        out, base = Q2(1), self
        if k < 0:
            base, k = Q2(1) / self, -k
        for _ in range(k):
            out = out * base
        return out

    def __eq__(self, o):
        o = Q2.of(o)
        return self.re == o.re and self.im == o.im

    def __hash__(self):
        return hash((self.re, self.im))

    def __repr__(self):
        return f"({self.re} + j {self.im})"


def frac(text) -> Fraction:
    return Fraction(str(text))


def poly_at(coefficients, z: Q2) -> Q2:
    """A polynomial given lowest degree first (strings or numbers) at ``z``."""
    out = Q2(0)
    for a in reversed(coefficients):
        out = out * z + frac(a)
    return out


def ratio_at(entry: dict, z: Q2) -> Q2:
    return poly_at(entry["num"], z) / poly_at(entry["den"], z)


def det(rows) -> Q2:
    """Laplace expansion (the matrices here are at most 3 x 3)."""
    if len(rows) == 1:
        return rows[0][0]
    out = Q2(0)
    for j in range(len(rows)):
        minor = [row[:j] + row[j + 1:] for row in rows[1:]]
        term = rows[0][j] * det(minor)
        out = out + term if j % 2 == 0 else out - term
    return out


# ---------------------------------------------------------------- the oracle's scenes


def x_of(approximation: str, T: Fraction, z):
    """``X(z)``, the approximation of ``Z{v_h/s}``."""
    if approximation == "forward":
        return T / (z - 1)
    if approximation == "backward":
        return T * z / (z - 1)
    assert approximation == "tustin"
    return T * (z + 1) / (2 * (z - 1))


def x_residue(approximation: str, T: Fraction) -> Fraction:
    """``lim_{z -> 1} (z - 1) X(z)`` from the three definitions."""
    return {"forward": T, "backward": T * 1, "tustin": T * 2 / 2}[approximation]


class Scene:
    """m users (m = 1: the single-user wall): ``b, z_a, K_0, B_0`` per user, ``K_ij, B_ij`` per edge."""

    def __init__(self, approximation, T, b, z_a, K0, B0, edges, delays):
        self.approximation, self.T = approximation, Fraction(T)
        self.b, self.z_a, self.K0, self.B0 = list(b), list(z_a), list(K0), list(B0)
        self.edges = dict(edges)  # (i, j) 0-based, i < j -> (K_ij, B_ij)
        self.delays = list(delays)
        self.m = len(self.b)
        # the period inside H: a report's scene block shows H(z) as a function of z, so editing the
        # block's T changes X only (H_T stays the genuine period)
        self.H_T = self.T

    def with_(self, **changes) -> Scene:
        new = copy.deepcopy(self)
        for key, value in changes.items():
            setattr(new, key, value)
        return new

    def kb(self):
        """``Kmat, Bmat``: diag(K_0) + the Laplacian of the coupling stiffnesses (and dampings)."""
        K = [[Fraction(0)] * self.m for _ in range(self.m)]
        B = [[Fraction(0)] * self.m for _ in range(self.m)]
        for i in range(self.m):
            K[i][i] += self.K0[i]
            B[i][i] += self.B0[i]
        for (i, j), (k, d) in self.edges.items():
            for M, v in ((K, k), (B, d)):
                M[i][i] += v
                M[j][j] += v
                M[i][j] -= v
                M[j][i] -= v
        return K, B

    def H(self, z):
        K, B = self.kb()
        return [[K[i][j] + B[i][j] * (z - 1) / (self.H_T * z) for j in range(self.m)] for i in range(self.m)]

    def G(self, z) -> list:
        """``G^-1(z)`` (works for Q2 values and for elements of SymPy's fields alike)."""
        H = self.H(z)
        X = x_of(self.approximation, self.T, z)
        return [[(self.b[i] - self.z_a[i] if i == j else 0) + H[i][j] * X / z ** self.delays[i]
                 for j in range(self.m)] for i in range(self.m)]

    def M(self, z: Q2) -> list:
        """``M = G^-1 + G^-H`` at a point of the unit circle."""
        G = self.G(z)
        return [[G[i][j] + G[j][i].conj() for j in range(self.m)] for i in range(self.m)]

    def residue_matrix(self) -> list:
        """``lim (z - 1) G^-1(z) / z`` at ``z0 = 1``: ``H(1) lim (z - 1) X``."""
        K, _ = self.kb()
        r = x_residue(self.approximation, self.T)
        return [[K[i][j] * r for j in range(self.m)] for i in range(self.m)]

    def same_G(self, other: Scene, points) -> bool:
        return all(
            a == b for z in points for ra, rb in zip(self.G(z), other.G(z)) for a, b in zip(ra, rb))


def off_circle_points(rng: random.Random, k: int = POINTS) -> list[Q2]:
    out = []
    while len(out) < k:
        z = Q2(Fraction(rng.randint(-40, 40), rng.randint(1, 13)), Fraction(rng.choice([-1, 1]) * rng.randint(1, 40), rng.randint(1, 13)))
        if z.re * z.re + z.im * z.im != 1:
            out.append(z)
    return out


def circle_points(rng: random.Random, k: int = POINTS) -> list[tuple[Q2, Fraction, Fraction]]:
    """``(z, c, s)``: rational points ``z = c + j s`` of the unit circle, ``z != +-1``."""
    out = []
    for _ in range(k):
        t = Fraction(rng.choice([-1, 1]) * rng.randint(1, 60), rng.randint(1, 17))
        c, s = (1 - t * t) / (1 + t * t), 2 * t / (1 + t * t)
        out.append((Q2(c, s), c, s))
    return out


# ---------------------------------------------------------------- M(c) as rational functions of c

QC, CC = sympy.field("c", sympy.QQ)


class CS:
    """``A(c) + j s B(c)`` with ``s = sin theta``, ``s^2 = 1 - c^2``, A and B real rational in c."""

    __slots__ = ("a", "b")

    def __init__(self, a, b=0):
        self.a, self.b = QC(a), QC(b)

    @staticmethod
    def of(x):
        return x if isinstance(x, CS) else CS(QC(sympy.Rational(x.numerator, x.denominator))
                                               if isinstance(x, Fraction) else x)

    def __add__(self, o):
        o = CS.of(o)
        return CS(self.a + o.a, self.b + o.b)

    __radd__ = __add__

    def __neg__(self):
        return CS(-self.a, -self.b)

    def __sub__(self, o):
        return self + (-CS.of(o))

    def __rsub__(self, o):
        return CS.of(o) - self

    def __mul__(self, o):
        o = CS.of(o)
        return CS(self.a * o.a - (1 - CC ** 2) * self.b * o.b, self.a * o.b + self.b * o.a)

    __rmul__ = __mul__

    def conj(self):
        return CS(self.a, -self.b)

    def __truediv__(self, o):
        o = CS.of(o)
        n = o.a * o.a + (1 - CC ** 2) * o.b * o.b
        p = self * o.conj()
        return CS(p.a / n, p.b / n)

    def __rtruediv__(self, o):
        return CS.of(o) / self

    def __pow__(self, k: int):
        """``(c + j s)^k`` for the point z itself is built binomially (see ``unit``); a general power
        multiplies out."""
        out = CS(1)
        for _ in range(k):
            out = out * self
        return out


def unit_power(k: int) -> CS:
    """``z^k = (c + j s)^k`` expanded binomially with ``s^2 = 1 - c^2`` (not Chebyshev)."""
    a, b = QC(0), QC(0)
    for m in range(k + 1):
        coefficient = sympy.binomial(k, m) * CC ** (k - m)
        half = (1 - CC ** 2) ** (m // 2)
        sign = -1 if (m // 2) % 2 else 1
        if m % 2 == 0:
            a += sign * coefficient * half
        else:
            b += sign * coefficient * half
    return CS(a, b)


class UnitZ(CS):
    """The point ``z = c + j s`` of the circle; its powers are expanded binomially."""

    def __init__(self):
        super().__init__(CC, 1)

    def __pow__(self, k: int):
        return unit_power(k)


def at_c(f, x: Fraction) -> Fraction:
    """An element of QQ(c) at the rational c = x."""
    v = f.as_expr().subs(sympy.Symbol("c"), sympy.Rational(x.numerator, x.denominator))
    assert v.is_Rational, v
    return Fraction(int(v.p), int(v.q))


def minors_of_c(scene: Scene) -> dict:
    """Every principal minor of ``M(c)`` (1-based index tuples) as an element of QQ(c)."""
    z = UnitZ()
    G = scene.G(z)
    m = scene.m
    M = [[G[i][j] + G[j][i].conj() for j in range(m)] for i in range(m)]
    out = {}
    for size in range(1, m + 1):
        for idx in combinations(range(m), size):
            d = det_cs([[M[i][j] for j in idx] for i in idx])
            assert d.b == 0, "a principal minor of a Hermitian matrix is real"
            out[tuple(i + 1 for i in idx)] = d.a
    return out


def det_cs(rows):
    if len(rows) == 1:
        return rows[0][0]
    out = CS(0)
    for j in range(len(rows)):
        minor = [row[:j] + row[j + 1:] for row in rows[1:]]
        term = rows[0][j] * det_cs(minor)
        out = out + term if j % 2 == 0 else out - term
    return out


def nonnegative_on_interval(f) -> bool | None:
    """Exactly: is the rational function f(c) >= 0 on [-1, 1]? None when it has a pole there."""
    c = sympy.Symbol("c")
    num = sympy.Poly(f.numer.as_expr(), c)
    den = sympy.Poly(f.denom.as_expr(), c)
    if den.count_roots(-1, 1) > 0:
        return None
    if num.is_zero:
        return True
    bounds = [(sympy.Rational(-1), sympy.Rational(-1))]
    if num.degree() > 0:
        free = sympy.Poly(sympy.quo(num, sympy.gcd(num, num.diff(c))), c)
        bounds += sorted((sympy.Rational(a), sympy.Rational(b))
                         for (a, b), _ in free.intervals(inf=-1, sup=1, eps=sympy.Rational(1, 10 ** 12)))
    bounds.append((sympy.Rational(1), sympy.Rational(1)))
    bounds = sorted(set(bounds))
    tests = [sympy.Rational(-1), sympy.Rational(1)]
    for (_, right), (left, _) in pairwise(bounds):
        if right < left:
            tests.append((right + left) / 2)
        elif num.eval(right) != 0:
            tests.append(right)
        else:  # two isolating intervals touching at a root: cannot happen for disjoint roots
            return None
    for x in tests:
        value = num.eval(x) * den.eval(x)
        if value < 0:
            return False
    return True


def psd_for_every_c(scene: Scene) -> bool | None:
    """The oracle's truth of ``M(c) >= 0 for every c`` (all principal minors nonnegative)."""
    verdicts = [nonnegative_on_interval(f) for f in minors_of_c(scene).values()]
    if None in verdicts:
        return None
    return all(verdicts)


# ---------------------------------------------------------------- reading the reports' strings

SYM = {name: sympy.Symbol(name) for name in ("c", "s_theta", "z", "s")}


def parse(text: str, allowed: tuple[str, ...]) -> sympy.Expr:
    """A report's expression: only the listed symbols and the imaginary unit I."""
    local = {name: SYM[name] for name in allowed}
    local["I"] = sympy.I
    expr = sympy.sympify(text, locals=local)
    assert expr.free_symbols <= {SYM[name] for name in allowed}, (text, expr.free_symbols)
    return expr


def value(expr: sympy.Expr, at: dict) -> Q2:
    v = sympy.expand_complex(expr.subs({SYM[k]: sympy.Rational(x.numerator, x.denominator) if isinstance(x, Fraction)
                                         else x for k, x in at.items()}))
    re, im = sympy.re(v), sympy.im(v)
    assert re.is_Rational and im.is_Rational, v
    return Q2(Fraction(int(re.p), int(re.q)), Fraction(int(im.p), int(im.q)))


def q2_to_sympy(z: Q2) -> sympy.Expr:
    return sympy.Rational(z.re.numerator, z.re.denominator) + sympy.I * sympy.Rational(z.im.numerator, z.im.denominator)


def text(x: Fraction) -> str:
    return f"{x.numerator}/{x.denominator}" if x.denominator != 1 else str(x.numerator)


# ---------------------------------------------------------------- the random scenes


def _value(rng: random.Random, kind: str) -> Fraction:
    """A random exact value of a sign class: pos, zero, neg, soft (small positive), big."""
    if kind == "zero":
        return Fraction(0)
    if kind == "soft":
        return Fraction(rng.randint(1, 50), 10)
    if kind == "big":
        return Fraction(rng.randint(1000, 5000))
    magnitude = Fraction(rng.randint(1, 3000), rng.choice([1, 10, 100]))
    return -magnitude if kind == "neg" else magnitude


def _signed(rng: random.Random) -> Fraction:
    return _value(rng, rng.choice(["pos", "pos", "pos", "zero", "neg"]))


# single-user (K, B) sign classes: every sign of both, and stiff walls that lose passivity
SINGLE = [("pos", "pos"), ("zero", "pos"), ("neg", "pos"), ("pos", "zero"), ("pos", "neg"), ("big", "pos"),
          ("big", "neg")]
# multi-user: soft couplings (passive for a large b) and random ones
MULTI = ["soft", "random", "soft", "random", "soft"]


def random_scenes() -> list[tuple[str, Scene, list[str]]]:
    rng = random.Random(RNG_SEED)
    out = []
    for k, (kind_k, kind_b) in enumerate(SINGLE):
        approximation = rng.choice(["forward", "backward", "tustin"])
        T = Fraction(rng.randint(1, 9), rng.choice([10, 100, 1000]))
        K, B = _value(rng, kind_k), _value(rng, kind_b) / 100
        b = Fraction(rng.randint(0, 400), 100)
        z_a = Fraction(rng.randint(1, 50), 1000) if rng.random() < 0.4 else Fraction(0)
        n = rng.randint(0, 3)
        scene = Scene(approximation, T, [b], [z_a], [K], [B], {}, [n])
        argv = ["single-user", "--approximation", approximation, "--delay", str(n), "--param", f"K={text(K)}",
                "--param", f"B={text(B)}", "--param", f"b={text(b)}", "--param", f"T={text(T)}"]
        if z_a:
            argv += ["--active", "--param", f"z_a={text(z_a)}"]
        out.append((f"single-{k}-K{kind_k}-B{kind_b}-{approximation}-n{n}", scene, argv))
    for k, kind in enumerate(MULTI):
        m = 2 if k < 3 else 3
        graph = rng.choice(["complete", "path"])
        pairs = [(i, j) for i in range(m) for j in range(i + 1, m)] if graph == "complete" else [(i, i + 1) for i in range(m - 1)]
        approximation = rng.choice(["forward", "backward", "tustin"])
        T = Fraction(rng.randint(1, 9), rng.choice([100, 1000]))
        b = [Fraction(rng.randint(0, 300), 100) for _ in range(m)]
        active = rng.random() < 0.4
        z_a = [Fraction(rng.randint(0, 30), 1000) if active else Fraction(0) for _ in range(m)]
        if kind == "soft":
            T = Fraction(1, rng.choice([1000, 2000]))
            b = [Fraction(rng.randint(50, 300), 100) for _ in range(m)]
            K0 = [_value(rng, "soft") for _ in range(m)]
            B0 = [_value(rng, rng.choice(["soft", "zero"])) / 1000 for _ in range(m)]
            edges = {p: (_value(rng, rng.choice(["soft", "zero"])), _value(rng, "soft") / 1000) for p in pairs}
        else:
            K0 = [_signed(rng) for _ in range(m)]
            B0 = [_signed(rng) / 1000 for _ in range(m)]
            edges = {p: (_signed(rng), _signed(rng) / 1000) for p in pairs}
        delays = [rng.randint(0, 3) for _ in range(m)]
        if len(set(delays)) == 1:
            delays[0] = (delays[0] + 1) % 4
        scene = Scene(approximation, T, b, z_a, K0, B0, edges, delays)
        argv = ["multi-user", "--users", str(m), "--graph", graph, "--approximation", approximation,
                "--delay", ",".join(map(str, delays)), "--param", f"T={text(T)}"]
        for i in range(m):
            argv += ["--param", f"b_{i + 1}={text(b[i])}", "--param", f"K_0{i + 1}={text(K0[i])}",
                     "--param", f"B_0{i + 1}={text(B0[i])}"]
            if active:
                argv += ["--param", f"z_a{i + 1}={text(z_a[i])}"]
        if active:
            argv.insert(1, "--active")
        for (i, j), (kk, bb) in edges.items():
            argv += ["--param", f"K_{i + 1}{j + 1}={text(kk)}", "--param", f"B_{i + 1}{j + 1}={text(bb)}"]
        out.append((f"multi-{k}-{kind}-m{m}-{graph}-{approximation}", scene, argv))
    return out


SCENES = random_scenes()
IDS = [name for name, _, _ in SCENES]


@cache
def genuine(name: str) -> dict:
    argv = {n: a for n, _, a in SCENES}[name]
    return json_of("derive", *argv, "--format", "json")


def scene_of(name: str) -> Scene:
    return {n: s for n, s, _ in SCENES}[name]


def refusals(report) -> str:
    return " | ".join(r.reason for _, r in check_report(report).failed)


# ---------------------------------------------------------------- 1. genuine reports = the oracle


def shown_G(report: dict, z: Q2) -> list:
    transfer = report["definition"]["transfer"]
    if "entries" in transfer:
        return [[ratio_at(e, z) for e in row] for row in transfer["entries"]]
    return [[ratio_at(transfer, z)]]


@pytest.mark.parametrize("name", IDS)
def test_genuine_report_equals_the_oracle_and_is_accepted(name):
    scene, report = scene_of(name), genuine(name)
    rng = random.Random(f"{RNG_SEED}-{name}")
    multi = scene.m > 1
    # the scene block, value by value
    block = report["scene"]
    assert frac(block["period"]) == scene.T
    assert [frac(x) for x in block["damping"]] == scene.b
    assert [frac(x) for x in block["shortage"]] == scene.z_a
    assert report["approximation"] == scene.approximation
    if multi:
        assert report["delays"] == scene.delays and report["users"] == scene.m
        assert sorted(tuple(e) for e in report["edges"]) == sorted((i + 1, j + 1) for i, j in scene.edges)
    else:
        assert int(report["delay"]) == scene.delays[0]
    zs = off_circle_points(rng)
    for z in zs:
        H = scene.H(z)
        assert [[ratio_at(e, z) for e in row] for row in block["environment"]] == H
        G = scene.G(z)
        assert shown_G(report, z) == G
        displayed = report["G_inverse"] if multi else [[report["G_inverse"]]]
        assert [[value(parse(e, ("z",)), {"z": q2_to_sympy(z)}) for e in row] for row in displayed] == G
    # the Hermitian part and its principal minors at rational points of the circle
    for z, c, s in circle_points(rng):
        M = scene.M(z)
        if multi:
            shown = [[value(parse(e, ("c", "s_theta")), {"c": c, "s_theta": s}) for e in row]
                     for row in report["hermitian_part"]]
            assert shown == M
            for key, minor in report["principal_minors"].items():
                idx = [i - 1 for i in ast.literal_eval(key)]
                assert value(parse(minor, ("c",)), {"c": c}) == det([[M[i][j] for j in idx] for i in idx]), key
        else:
            assert value(parse(report["hermitian_part"], ("c",)), {"c": c}) == M[0][0] / 2
    # the residue at z = 1 and the worst case
    R = scene.residue_matrix()
    if multi:
        assert [[frac(x) for x in row] for row in report["residue_at_1"]] == R
    else:
        at_one = [r for r in report["residues"] if r["z"] == "1"]
        if R[0][0] == 0:  # K = 0: (z - 1) cancels, no pole at z = 1 (H(1) = K)
            assert at_one == [] or frac(at_one[0]["residue"]) == 0
        else:
            assert len(at_one) == 1 and frac(at_one[0]["residue"]) == R[0][0]
    truth = psd_for_every_c(scene)
    shown_truth = report["worst_case_condition" if multi else "worst_case"]
    assert truth is not None and shown_truth == str(truth)
    result = check_report(report)
    assert result.accepted, refusals(report)


def test_the_oracle_is_not_vacuous():
    """The scenes reach both answers of the worst case and both final verdicts, with zero and
    negative values, every approximation and delays 0..3."""
    truths = {psd_for_every_c(scene_of(n)) for n in IDS}
    verdicts = {genuine(n)["verdict"] for n in IDS}
    assert truths == {True, False} and {"proved", "disproved"} <= verdicts
    scenes = [scene_of(n) for n in IDS]
    assert {s.approximation for s in scenes} == {"forward", "backward", "tustin"}
    values = [v for s in scenes for v in s.K0 + s.B0 + [e for kb in s.edges.values() for e in kb]]
    assert any(v < 0 for v in values) and any(v == 0 for v in values)


# ---------------------------------------------------------------- 2. forgeries


def bump(text_value: str) -> str:
    return str(sympy.sympify(text_value) + sympy.Rational(1, 1000))


def forgeries(name: str) -> list[tuple[str, dict]]:
    """Each forgery changes one thing a reader relies on; the oracle makes sure it is false."""
    scene, report = scene_of(name), genuine(name)
    rng = random.Random(f"{RNG_SEED}-forge-{name}")
    multi = scene.m > 1
    zs = off_circle_points(rng)
    out = []

    def forged(label, edit, really_false: bool):
        if not really_false:
            return
        f = copy.deepcopy(report)
        edit(f)
        assert f != report
        out.append((label, f))

    # the approximation label: a different label must really give a different G^-1
    for other in {"forward", "backward", "tustin"} - {scene.approximation}:
        forged(f"approximation={other}", lambda f, o=other: f.__setitem__("approximation", o),
               not scene.same_G(scene.with_(approximation=other), zs))
    # the delay(s)
    if multi:
        i = rng.randrange(scene.m)
        delays = list(scene.delays)
        delays[i] += 1
        forged(f"delays[{i}]+1", lambda f: f.__setitem__("delays", delays),
               not scene.same_G(scene.with_(delays=delays), zs))
    else:
        n = scene.delays[0] + 1
        forged("delay+1", lambda f: f.__setitem__("delay", str(n)), not scene.same_G(scene.with_(delays=[n]), zs))
    # one entry of the scene block
    T2 = scene.T + Fraction(1, 1000)
    forged("scene.T", lambda f: f["scene"].__setitem__("period", text(T2)),
           not scene.same_G(scene.with_(T=T2, H_T=scene.T), zs))
    i = rng.randrange(scene.m)
    b2 = list(scene.b)
    b2[i] += Fraction(1, 1000)
    forged(f"scene.b[{i}]", lambda f: f["scene"]["damping"].__setitem__(i, text(b2[i])), not scene.same_G(scene.with_(b=b2), zs))
    za2 = list(scene.z_a)
    za2[i] += Fraction(1, 1000)
    forged(f"scene.z_a[{i}]", lambda f: f["scene"]["shortage"].__setitem__(i, text(za2[i])),
           not scene.same_G(scene.with_(z_a=za2), zs))
    j = rng.randrange(scene.m)

    def edit_h(f):
        entry = f["scene"]["environment"][i][j]
        entry["num"][0] = bump(entry["num"][0])

    # H_ij + (1/1000)/den(z): G^-1 changes by z^-n (1/1000) X / den, never 0
    forged(f"scene.H[{i}][{j}].num[0]", edit_h, True)
    # the Hermitian part: one entry + 1/1000 (M itself is known exactly, the forgery differs from it)
    if multi:
        a, bb = rng.randrange(scene.m), rng.randrange(scene.m)
        forged(f"hermitian_part[{a}][{bb}]", lambda f: f["hermitian_part"][a].__setitem__(bb, bump(f["hermitian_part"][a][bb])), True)
        key = rng.choice(sorted(report["principal_minors"]))
        forged(f"principal_minors{key}", lambda f: f["principal_minors"].__setitem__(key, bump(f["principal_minors"][key])), True)
        r, q = rng.randrange(scene.m), rng.randrange(scene.m)
        forged(f"residue_at_1[{r}][{q}]", lambda f: f["residue_at_1"][r].__setitem__(q, bump(f["residue_at_1"][r][q])), True)
    else:
        forged("hermitian_part", lambda f: f.__setitem__("hermitian_part", bump(f["hermitian_part"])), True)
        for k, residue in enumerate(report["residues"]):
            if residue["z"] == "1":
                forged("residues[z=1]", lambda f, k=k: f["residues"][k].__setitem__("residue", bump(f["residues"][k]["residue"])), True)
    # the minimum and its minimiser (single user), the witness / worst c: moved to where they are false
    herm = minors_of_c(scene)[tuple(range(1, scene.m + 1))] if not multi else None
    if not multi and report["minimiser"] is not None:
        low, at = frac(report["minimum"]), frac(report["minimiser"])
        if -1 <= at <= 1 and at_c(herm, at) / 2 == low:  # the genuine minimum is attained there
            forged("minimum", lambda f: f.__setitem__("minimum", bump(f["minimum"])), True)
            other = Fraction(rng.randint(-99, 99), 100)
            forged("minimiser", lambda f: f.__setitem__("minimiser", text(other)), at_c(herm, other) / 2 > low)
    psd_point = next((p for p in circle_points(rng, 40) if all(
        det([[M[i][j] for j in idx] for i in idx]).re >= 0
        for M in [scene.M(p[0])] for size in range(1, scene.m + 1) for idx in combinations(range(scene.m), size))), None)
    if psd_point is not None:
        _z, c, s = psd_point
        t_half = s / (1 + c)  # tan(theta/2)
        witness = {"c": text(c), "z": [text(c), text(s)], "omega_T": f"2*atan({text(t_half)})"}
        if isinstance(report["witness"], dict) and "c" in report["witness"]:
            forged("witness at a PSD point", lambda f: f.__setitem__("witness", witness), True)
        if multi and report["worst_c"] is not None:
            forged("worst_c at a PSD point", lambda f: f.__setitem__("worst_c", text(c)), True)
    # the worst case's truth value, flipped (the oracle decides it exactly)
    key = "worst_case_condition" if multi else "worst_case"
    truth = psd_for_every_c(scene)
    forged(f"{key} flipped", lambda f: f.__setitem__(key, str(not truth)), truth is not None)
    return out


@pytest.mark.parametrize("name", IDS)
def test_every_forgery_is_refused(name):
    made = forgeries(name)
    assert len(made) >= 7, [label for label, _ in made]
    accepted = [label for label, f in made if check_report(f).accepted]
    assert not accepted, f"forgeries of {name} accepted: {accepted}"


def test_genuine_report_without_environment_is_accepted():
    """K = B = 0: H = 0, G^-1 = b - z_a, no pole at all; the genuine report equals the oracle and
    should be accepted."""
    scene = Scene("forward", Fraction(1, 100), [Fraction(1, 2)], [Fraction(0)], [Fraction(0)], [Fraction(0)], {}, [2])
    report = json_of("derive", "single-user", "--param", "K=0", "--param", "B=0", "--param", "b=1/2",
                     "--param", "T=1/100", "--delay", "2", "--format", "json")
    for z in off_circle_points(random.Random(2)):
        assert shown_G(report, z) == scene.G(z) == [[Q2(Fraction(1, 2))]]
    assert report["verdict"] == "proved" and psd_for_every_c(scene) is True
    assert check_report(report).accepted, refusals(report)


def test_a_forgery_that_is_not_false_is_not_made():
    """The oracle's guard: with K = B = 0 the environment is 0, G^-1 = b - z_a whatever the
    approximation, delay or period, so those relabellings are not forgeries at all."""
    scene = Scene("forward", Fraction(1, 100), [Fraction(1, 2)], [Fraction(0)], [Fraction(0)], [Fraction(0)], {}, [1])
    zs = off_circle_points(random.Random(1))
    assert scene.same_G(scene.with_(approximation="tustin"), zs)
    assert scene.same_G(scene.with_(delays=[3], T=Fraction(1, 7)), zs)
    wall = scene.with_(K0=[Fraction(1)])
    assert not wall.same_G(wall.with_(T=Fraction(1, 7)), zs)


# ---------------------------------------------------------------- 3. networks


def network_cases() -> list[tuple[str, list[list[str]], bool]]:
    """``(name, rows of Z(s), positive real?)``: PR by construction (``D + A/(s + p)`` with D, A
    symmetric PSD, p > 0: its Hermitian part at s = j w is ``2 D + 2 p A/(w^2 + p^2) >= 0``), not PR
    by an exact witness (an indefinite ``Z(0) + Z(0)^T`` or a pole in Re s > 0)."""
    rng = random.Random(RNG_SEED + 1)

    def r(lo, hi):
        return Fraction(rng.randint(lo, hi), rng.randint(1, 9))

    d, a, p = r(0, 20), r(1, 30), r(1, 40)
    one = [[f"{text(d)} + {text(a)}/(s + {text(p)})"]]
    a11, a22 = r(1, 30), r(1, 30)
    a12 = Fraction(rng.randint(-9, 9), 10) * min(a11, a22)  # |a12| < min(a11, a22): A PSD
    p1, p2, d1 = r(1, 40), r(1, 40), r(0, 5)
    two = [[f"{text(d1)} + {text(a11)}/(s + {text(p1)}) + 1/(s + {text(p2)})", f"{text(a12)}/(s + {text(p1)})"],
           [f"{text(a12)}/(s + {text(p1)})", f"{text(a22)}/(s + {text(p1)}) + 1/(s + {text(p2)})"]]
    b11, b22 = r(1, 9), r(1, 9)
    b12 = 2 * max(b11, b22)  # b12^2 > b11 b22: indefinite at s = 0
    q = r(1, 40)
    indefinite = [[f"{text(b11)}/(s + {text(q)})", f"{text(b12)}/(s + {text(q)})"],
                  [f"{text(b12)}/(s + {text(q)})", f"{text(b22)}/(s + {text(q)})"]]
    rhp = [[f"{text(r(1, 9))}/(s - {text(r(1, 40))}) + 1"]]
    return [("pr-1x1", one, True), ("pr-2x2", two, True), ("indefinite-2x2", indefinite, False), ("rhp-pole-1x1", rhp, False)]


NETWORKS = network_cases()


def z_at(rows, s: Q2) -> list:
    """The oracle's Z(s), parsed from the matrix file's rows and evaluated exactly."""
    return [[value(parse(e, ("s",)), {"s": q2_to_sympy(s)}) for e in row] for row in rows]


@cache
def network_report(name: str, tmp: str) -> dict:
    rows = {n: r for n, r, _ in NETWORKS}[name]
    path = Path(tmp) / f"{name}.txt"
    path.write_text("\n".join(", ".join(row) for row in rows) + "\n", encoding="utf-8")
    return json_of("derive", "network", "--matrix", str(path), "--no-search", "--format", "json")


@pytest.fixture(scope="module")
def network_dir(tmp_path_factory):
    return str(tmp_path_factory.mktemp("networks"))


def positive_real_truth(rows, pr: bool) -> bool:
    """The construction's claim, with its exact witness checked for the non-PR ones."""
    if pr:
        return True
    zero = z_at(rows, Q2(0)) if not any("s - " in e for row in rows for e in row) else None
    if zero is not None:  # indefinite Hermitian part at w = 0
        herm = [[zero[i][j] + zero[j][i].conj() for j in range(len(rows))] for i in range(len(rows))]
        assert det(herm).re < 0 or any(herm[i][i].re < 0 for i in range(len(rows)))
    else:  # a pole in Re s > 0: Z grows without bound approaching it from the right
        pole = Fraction(rows[0][0].split("s - ")[1].split(")")[0])
        near = [z_at(rows, Q2(pole + Fraction(1, 10 ** k)))[0][0].re for k in (3, 6)]
        assert near[1] > 100 * near[0] > 0
    return False


@pytest.mark.parametrize("name", [n for n, _, _ in NETWORKS])
def test_network_report_equals_the_oracle_and_forgeries_are_refused(name, network_dir):
    rows, pr = {n: (r, p) for n, r, p in NETWORKS}[name]
    report = network_report(name, network_dir)
    rng = random.Random(f"{RNG_SEED}-{name}")
    points = off_circle_points(rng)  # any points off the poles (their imaginary parts are nonzero)
    definition = report["conditions"][0]["definition"]["transfer"]
    for s in points:
        Z = z_at(rows, s)
        assert z_at(report["matrix"], s) == Z
        entries = definition.get("entries", [[definition]])
        assert [[ratio_at(e, s) for e in row] for row in entries] == Z
    truth = positive_real_truth(rows, pr)
    assert report["positive_real"]["decision"] == ("proved" if truth else "disproved")
    assert check_report(report).accepted, refusals(report)
    # forgeries: one entry of the matrix replaced by a different rational function, the decision flipped
    i, j = rng.randrange(len(rows)), rng.randrange(len(rows))
    other = f"({report['matrix'][i][j]}) + 1/(s + 7)"
    assert any(value(parse(other, ("s",)), {"s": q2_to_sympy(s)}) != z_at(rows, s)[i][j] for s in points)
    made = []
    f = copy.deepcopy(report)
    f["matrix"][i][j] = other
    made.append(("matrix entry", f))
    flipped = "disproved" if truth else "proved"
    f = copy.deepcopy(report)
    f["positive_real"]["decision"] = flipped
    made.append(("positive_real.decision", f))
    f = copy.deepcopy(report)
    f["conditions"][0]["decision"] = flipped
    made.append(("conditions[0].decision", f))
    accepted = [label for label, f in made if check_report(f).accepted]
    assert not accepted, f"forgeries of network {name} accepted: {accepted}"
