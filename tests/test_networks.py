"""Exact n-port analysis: rational matrices, positive realness, Llewellyn, Youla, absolute stability,
destabilizing terminations and the exact port-energy simulation.

Every decision is compared with an independent numeric oracle written here (numpy + mpmath, it
imports nothing from hapticproof: numpy roots of the denominators, residues, and a dense log
sweep of the frequency with w = 0 and w -> oo), every returned certificate is re-checked
numerically (terminations positive real, a zero of det(Z + T) in Re s > 0) and by the
independent checker. Assertions are about exact results or about comparisons with a stated
uncertainty band; none depends on the last bits of floating point (a search outcome is asserted
only where theory decides it; a found certificate must verify).

``HAPTICPROOF_NETWORK_EXAMPLES=N`` runs N examples per property test (CI: a few dozen);
``HAPTICPROOF_NETWORK_LOG=FILE`` appends one JSON line per compared decision (for counting).
"""

from __future__ import annotations

import copy
import itertools
import json
import math
import os
from fractions import Fraction

import flint
import mpmath
import numpy as np
import pytest
import sympy as sp
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from hapticproof.exact.checker import check_certificate, check_report
from hapticproof.analysis.energy import Sinusoid, input_energy, port_admittance, realize
from hapticproof.core.evidence import Decision, to_jsonable
from hapticproof.exact.kernel import locate_roots
from hapticproof.analysis.networks import absolute_stability, llewellyn, symmetrization_conditions, symmetrize, theorem9_conditions, verify_certificate, zprime_positive_real
from hapticproof.analysis.nport import input_impedance, positive_real, residue_matrix
from hapticproof.exact.rationalmatrix import RationalFunction, RationalMatrix, constant_psd, decide_psd, hermitian_minors, minimise_halfline, pole_report
from hapticproof.core.symbols import s
from hapticproof.analysis.terminations import exact_determinant, search_terminations

small = st.integers(min_value=-5, max_value=5)
positive = st.integers(min_value=1, max_value=6)
EXAMPLES = int(os.environ.get("HAPTICPROOF_NETWORK_EXAMPLES", "0"))


def examples(default: int) -> int:
    return EXAMPLES or default


# =============================================================================================
# the independent numeric oracle: numpy + mpmath only (nothing from hapticproof)
# =============================================================================================
#
# A matrix is ``entries[i][j] = (num, den)``: Fraction coefficient lists, lowest degree first,
# in lowest terms. Verdicts are "proved", "disproved" or "uncertain" (a value within the band
# of zero, e.g. a lossless entry whose Hermitian part vanishes, or a limit that touches zero).

ORACLE_BAND = 1e-9                                   # relative to the local magnitude
ORACLE_W = np.concatenate([[0.0], np.logspace(-5, 5, int(os.environ.get("HAPTICPROOF_ORACLE_POINTS", "801"))),
                           [1e6, 1e7, 1e8]])          # w = 0, a dense log sweep, w -> oo
ORACLE_ROOT_TOL = 1e-7


def o_polyval(coeffs, x):
    acc = np.zeros_like(x, dtype=complex) if isinstance(x, np.ndarray) else 0
    for a in reversed(coeffs):
        acc = acc * x + a
    return acc


def o_degree(coeffs) -> int:
    nz = [k for k, c in enumerate(coeffs) if c != 0]
    return nz[-1] if nz else -1


def o_values(entries, points: np.ndarray) -> np.ndarray:
    """Z at many points at once: shape (len(points), n, n)."""
    n = len(entries)
    out = np.empty((len(points), n, n), dtype=complex)
    with np.errstate(divide="ignore", invalid="ignore"):
        for i in range(n):
            for j in range(n):
                num, den = entries[i][j]
                out[:, i, j] = o_polyval([float(c) for c in num], points) / o_polyval([float(c) for c in den], points)
    return out


def o_roots(coeffs) -> np.ndarray:
    c = [float(a) for a in coeffs]
    while c and c[-1] == 0:
        c.pop()
    return np.roots(c[::-1]) if len(c) > 1 else np.array([], dtype=complex)


def o_cluster(rs) -> list[tuple[complex, int]]:
    out: list[list] = []
    for r in rs:
        for item in out:
            if abs(item[0] - r) <= 1e-5 * (1 + abs(r)):
                item[1] += 1
                break
        else:
            out.append([complex(r), 1])
    return [(a, m) for a, m in out]


def o_poles(entries):
    """(RHP poles, {axis pole: multiplicity}, order at infinity) from numpy roots."""
    rhp, axis, improper = [], {}, 0
    for row in entries:
        for num, den in row:
            if o_degree(num) < 0:
                continue
            improper = max(improper, o_degree(num) - o_degree(den))
            for r, m in o_cluster(o_roots(den)):
                if r.real > ORACLE_ROOT_TOL * (1 + abs(r)):
                    rhp.append(r)
                elif abs(r.real) <= ORACLE_ROOT_TOL * (1 + abs(r)):
                    key = complex(0.0, round(r.imag, 6))
                    axis[key] = max(axis.get(key, 0), m)
    return rhp, axis, improper


def o_residues(entries, p: complex) -> np.ndarray:
    n = len(entries)
    R = np.zeros((n, n), dtype=complex)
    for i in range(n):
        for j in range(n):
            num, den = entries[i][j]
            if o_degree(num) >= 0 and any(abs(r - p) <= 1e-5 * (1 + abs(p)) for r in o_roots(den)):
                dden = [k * float(c) for k, c in enumerate(den)][1:]
                R[i, j] = o_polyval([float(c) for c in num], p) / o_polyval(dden, p)
    return R


def o_infinity_residue(entries) -> np.ndarray:
    n = len(entries)
    R = np.zeros((n, n))
    for i in range(n):
        for j in range(n):
            num, den = entries[i][j]
            if o_degree(num) - o_degree(den) == 1:
                R[i, j] = float(num[o_degree(num)]) / float(den[o_degree(den)])
    return R


def o_psd(R: np.ndarray) -> bool:
    scale = max(1.0, float(np.abs(R).max()))
    if np.abs(R - R.conj().T).max() > 1e-9 * scale:
        return False
    return np.linalg.eigvalsh((R + R.conj().T) / 2)[0] >= -1e-9 * scale


def o_sign(q: np.ndarray, magnitude: np.ndarray, noise: np.ndarray) -> np.ndarray:
    """+1 / -1, or 0 within the float noise or the band (touching zero)."""
    touching = (np.abs(q) <= 1e3 * noise) | (np.abs(q) <= ORACLE_BAND * magnitude)
    return np.where(touching, 0, np.sign(q)).astype(int)


def o_sweep(entries, quantity, axis_freqs) -> tuple[int, float | None]:
    """Worst sign over the sweep of ``quantity(Z(jw)) -> (value, magnitude, noise)`` and the
    frequency of the most negative relative value."""
    near = [f * (1 + sign * 10.0**-k) for f in axis_freqs if f > 0 for k in range(1, 7) for sign in (-1, 1)]
    grid = np.unique(np.concatenate([ORACLE_W, near]))            # and close to every axis pole
    keep = np.array([all(abs(w - f) > 1e-7 * (1 + f) for f in axis_freqs) for w in grid])
    ws = grid[keep]
    M = o_values(entries, 1j * ws)
    finite = np.all(np.isfinite(M), axis=(1, 2))
    ws, M = ws[finite], M[finite]
    q, magnitude, noise = quantity(M)
    signs = o_sign(q, magnitude, noise)
    worst = int(signs.min()) if len(signs) else 1
    where = None
    if worst < 0:
        rel = np.where(signs < 0, q / np.maximum(magnitude, 1e-300), np.inf)
        where = float(ws[int(np.argmin(rel))])
    return worst, where


def o_hermitian(M: np.ndarray):
    e = np.linalg.eigvalsh(M + np.conj(np.swapaxes(M, 1, 2)))
    return e[:, 0], np.abs(e).max(axis=1), 1e-14 * M.shape[1] * np.abs(M).max(axis=(1, 2))


def oracle_positive_real(entries) -> tuple[str, str]:
    """Definition 3 numerically: numpy poles, residues, the Hermitian part over the sweep."""
    rhp, axis, improper = o_poles(entries)
    if rhp:
        return "disproved", f"a pole at {rhp[0]:.4g}"
    if improper > 1 or any(m > 1 for m in axis.values()):
        return "disproved", "a multiple imaginary-axis pole"
    if not all(o_psd(o_residues(entries, p)) for p in axis) or (improper == 1 and not o_psd(o_infinity_residue(entries))):
        return "disproved", "a residue matrix is not Hermitian PSD"
    sign, where = o_sweep(entries, o_hermitian, [abs(p.imag) for p in axis])
    if sign < 0:
        return "disproved", f"the Hermitian part is negative at w = {where:.4g}"
    return ("uncertain", "the Hermitian part touches 0") if sign == 0 else ("proved", "swept")


def oracle_llewellyn(entries) -> tuple[str, str]:
    if o_poles(entries)[0]:
        return "disproved", "open-circuit unstable"
    zero = ([Fraction(0)], [Fraction(1)])
    diag = [[entries[0][0], zero], [zero, entries[1][1]]]
    _, axis, improper = o_poles(diag)
    if improper > 1 or any(m > 1 for m in axis.values()):
        return "disproved", "z11 or z22 has a multiple axis pole"
    if not all(o_psd(o_residues(diag, p)) for p in axis) or (improper == 1 and not o_psd(o_infinity_residue(diag))):
        return "disproved", "a residue of z11 or z22 is not positive"

    def margin(M):
        z11, z12, z21, z22 = M[:, 0, 0], M[:, 0, 1], M[:, 1, 0], M[:, 1, 1]
        p = z12 * z21
        scale = np.abs(z11) + np.abs(z22) + np.abs(z12) + np.abs(z21)
        parts = [(z11.real, np.abs(z11), 1e-14 * scale), (z22.real, np.abs(z22), 1e-14 * scale),
                 (2 * z11.real * z22.real - p.real - np.abs(p), scale**2, 1e-14 * scale**2)]
        signs = np.array([o_sign(*part) for part in parts])
        k = np.argmin(signs * 10 + np.array([part[0] / np.maximum(part[1], 1e-300) for part in parts]), axis=0)
        pick = lambda t: np.choose(k, [part[t] for part in parts])  # noqa: E731
        return pick(0), pick(1), pick(2)

    sign, where = o_sweep(entries, margin, [abs(p.imag) for p in o_poles(entries)[1]])
    if sign < 0:
        return "disproved", f"negative at w = {where:.4g}"
    return ("uncertain", "touches 0") if sign == 0 else ("proved", "swept")


def o_value_mp(entries, omega: Fraction, cells=None):
    """Z(jw) at a rational w with mpmath, the listed cells only (call inside ``mpmath.workdps``)."""
    w = mpmath.mpc(0, mpmath.mpf(omega.numerator) / omega.denominator)
    n = len(entries)
    M = mpmath.matrix(n, n)
    for i in range(n):
        for j in range(n):
            if cells is not None and (i, j) not in cells:
                continue
            num, den = entries[i][j]
            M[i, j] = (o_polyval([mpmath.mpf(c.numerator) / c.denominator for c in num], w)
                       / o_polyval([mpmath.mpf(c.numerator) / c.denominator for c in den], w))
    return M


def oracle_hermitian_at(entries, omega: Fraction) -> float:
    """Smallest eigenvalue of Z(jw) + Z(jw)^H at a rational w, at 50 digits (mpmath)."""
    with mpmath.workdps(50):
        M = o_value_mp(entries, omega)
        return float(min(mpmath.re(e) for e in mpmath.eighe(M + M.transpose_conj())[0]))


def oracle_llewellyn_at(entries, omega: Fraction, which: str) -> float:
    """One of Llewellyn's quantities at a rational w, 50 digits: ``'z11'`` (Re z11), ``'z22'``
    (Re z22) or ``'product'`` (2 Re z11 Re z22 - Re z12z21 - |z12z21|)."""
    cells = {"z11": {(0, 0)}, "z22": {(1, 1)}}.get(which)
    with mpmath.workdps(50):
        M = o_value_mp(entries, omega, cells)
        if which == "z11":
            return float(mpmath.re(M[0, 0]))
        if which == "z22":
            return float(mpmath.re(M[1, 1]))
        p = M[0, 1] * M[1, 0]
        return float(2 * mpmath.re(M[0, 0]) * mpmath.re(M[1, 1]) - mpmath.re(p) - abs(p))


def _pmul(a, b):
    out = [Fraction(0)] * (len(a) + len(b) - 1)
    for i, x in enumerate(a):
        for j, y in enumerate(b):
            out[i + j] += x * y
    return out


def _padd(a, b):
    out = [Fraction(0)] * max(len(a), len(b))
    for i, x in enumerate(a):
        out[i] += x
    for i, x in enumerate(b):
        out[i] += x
    return out


def _pdet(P):
    if len(P) == 1:
        return P[0][0]
    out = [Fraction(0)]
    for j in range(len(P)):
        term = _pmul(P[0][j], _pdet([row[:j] + row[j + 1:] for row in P[1:]]))
        out = _padd(out, term if j % 2 == 0 else [-c for c in term])
    return out


def oracle_add(A, B):
    return [[(_padd(_pmul(a[0], b[1]), _pmul(b[0], a[1])), _pmul(a[1], b[1])) for a, b in zip(ra, rb)] for ra, rb in zip(A, B)]


def oracle_block_diag(blocks, sizes):
    zero = ([Fraction(0)], [Fraction(1)])
    n = sum(sizes)
    out = [[zero] * n for _ in range(n)]
    start = 0
    for T, m in zip(blocks, sizes):
        for a in range(m):
            for b in range(m):
                out[start + a][start + b] = T[a][b]
        start += m
    return out


def _ptrim(a):
    a = list(a)
    while len(a) > 1 and a[-1] == 0:
        a.pop()
    return a


def _pdivmod(a, b):
    a, b = _ptrim(a), _ptrim(b)
    q = [Fraction(0)] * max(1, len(a) - len(b) + 1)
    r = list(a)
    while len(r) >= len(b) and any(r):
        k = len(r) - len(b)
        c = r[-1] / b[-1]
        q[k] = c
        for i, x in enumerate(b):
            r[i + k] -= c * x
        r = _ptrim(r[:-1]) if len(r) > 1 else [Fraction(0)]
    return q, r


def _pgcd(a, b):
    a, b = _ptrim(a), _ptrim(b)
    while any(b):
        a, b = b, _pdivmod(a, b)[1]
    return [c / a[-1] for c in a]


def oracle_rhp_zero(entries) -> float:
    """Largest real part of a zero of det Z(s): each row is multiplied by its denominators (which
    have no roots in Re s > 0 for a stable Z plus passive terminations), the polynomial
    determinant is expanded exactly (Fractions), the denominators are divided out exactly as
    often as they divide it, repeated roots are removed (a gcd with the derivative), and numpy
    finds the remaining simple roots (60-digit mpmath when one is within 1e-6 of the axis)."""
    P, denominators = [], []
    for row in entries:
        new = []
        for k, (num, _) in enumerate(row):
            others = [Fraction(1)]
            for m, (_, d) in enumerate(row):
                if m != k:
                    others = _pmul(others, d)
            new.append(_pmul(num, others))
        P.append(new)
        denominators += [_ptrim(d) for _, d in row if len(_ptrim(d)) > 1 and _ptrim(d) not in denominators]
    det = _ptrim(_pdet(P))
    if not any(det):
        return math.inf                              # det(Z + T) = 0 identically
    for d in denominators:
        while len(det) > 1:
            quotient, remainder = _pdivmod(det, d)
            if any(remainder):
                break
            det = _ptrim(quotient)
    derivative = [k * c for k, c in enumerate(det)][1:] or [Fraction(0)]
    g = _pgcd(det, derivative) if any(derivative) else [Fraction(1)]
    simple = _ptrim(_pdivmod(det, g)[0]) if len(g) > 1 else det
    top = max((r.real for r in o_roots(simple)), default=-math.inf)
    if abs(top) < 1e-6 and len(simple) > 2:          # close to the axis: 60 digits decide
        with mpmath.workdps(60):
            coeffs = [mpmath.mpf(c.numerator) / c.denominator for c in reversed(simple)]
            top = float(max(mpmath.re(r) for r in mpmath.polyroots(coeffs, maxsteps=400, extraprec=400)))
    return top


def oracle_random_rlc(rng: np.random.Generator, size: int):
    """A random passive RLC impedance P + Q s + R/s with small-integer PSD P, Q, R."""
    def psd():
        B = rng.integers(-2, 3, size=(size, size))
        return B @ B.T + np.diag(rng.integers(0, 2, size=size))

    P, Q, R = psd(), psd() * int(rng.integers(0, 2)), psd() * int(rng.integers(0, 2))
    return [[([Fraction(int(R[i, j])), Fraction(int(P[i, j])), Fraction(int(Q[i, j]))], [Fraction(0), Fraction(1)])
             for j in range(size)] for i in range(size)]


# =============================================================================================
# toolkit -> oracle data; the checker on every decision
# =============================================================================================


def entries_of(M) -> list:
    """A matrix of rational functions (SymPy or :class:`RationalMatrix`) as oracle data: exact
    coefficient lists, lowest degree first, monic denominators."""
    if isinstance(M, RationalMatrix):
        def fractions(p):
            return [Fraction(int(c.p), int(c.q)) for c in p.coeffs()] or [Fraction(0)]

        return [[(fractions(e.num), fractions(e.den)) for e in row] for row in M.rows]
    M = sp.Matrix(M)
    out = []
    for i in range(M.rows):
        row = []
        for j in range(M.cols):
            num, den = sp.fraction(sp.cancel(sp.together(M[i, j])))
            pn, pd = sp.Poly(num, s), sp.Poly(den, s)
            lead = pd.LC()
            row.append(([Fraction(str(c / lead)) for c in pn.all_coeffs()[::-1]],
                        [Fraction(str(c / lead)) for c in pd.all_coeffs()[::-1]]))
        out.append(row)
    return out


def checked(result) -> dict:
    """The result's JSON after a round trip, with every certificate in it re-verified."""
    data = json.loads(json.dumps(to_jsonable(result.to_json())))
    report = check_report(data)
    assert report.ok, report.summary()
    return data


def log(decision: str, **fields) -> None:
    path = os.environ.get("HAPTICPROOF_NETWORK_LOG")
    if path:
        with open(path, "a", encoding="utf-8") as handle:
            handle.write(json.dumps({"decision": decision, **fields}, default=str) + "\n")


def witness_confirmed(entries, result) -> bool | None:
    """A disproved condition re-checked numerically: a Hermitian-part witness at 50 digits, or
    the oracle's own verdict on poles/residues. None when no numeric check applies."""
    for cond in result.conditions:
        if cond.decision != Decision.DISPROVED:
            continue
        witness = cond.outcome.witness or {}
        if cond.name.startswith("Hermitian") and "omega" in witness:
            return bool(oracle_hermitian_at(entries, Fraction(str(witness["omega"]))) < 0)
        if cond.name.startswith(("Re z", "2 Re z11")) and "omega" in witness:
            which = "z11" if cond.name.startswith("Re z11") else "z22" if cond.name.startswith("Re z22") else "product"
            try:
                return bool(oracle_llewellyn_at(entries, Fraction(str(witness["omega"])), which) < 0)
            except ZeroDivisionError:             # the witness is a pole of another entry
                return None
        if cond.name.startswith(("poles", "open-circuit")):
            return bool(o_poles(entries)[0])
        return None
    return None


# =============================================================================================
# random impedances (exact rationals)
# =============================================================================================

POLES = [1, 2, 3, 5, Fraction(1, 2), 10]


def _rf(num, den=(1,)) -> RationalFunction:
    return RationalFunction.make(flint.fmpq_poly([flint.fmpq(Fraction(c).numerator, Fraction(c).denominator) for c in num]),
                                 flint.fmpq_poly([flint.fmpq(Fraction(c).numerator, Fraction(c).denominator) for c in den]))


@st.composite
def entries(draw, diagonal: bool = False):
    """A random real-rational entry (exact): a constant, first-order terms a/(s + p), and now and
    then a pole at 0, an LC pair, a mass, a right-half-plane pole or the issue-10 stretch."""
    e = _rf([draw(st.sampled_from([0, 1, 2, 3, 5, -1] if diagonal else [0, 0, 1, 2, -1]))])
    for _ in range(draw(st.sampled_from([0, 1, 1, 2]))):
        e = e + _rf([draw(st.integers(-5, 6))], [draw(st.sampled_from(POLES)), 1])
    extra = draw(st.sampled_from(["none"] * 12 + ["zero", "pair", "mass", "rhp", "stretch", "stretch"]))
    if extra == "zero":
        e = e + _rf([draw(st.sampled_from([-1, 1, 2]))], [0, 1])
    elif extra == "pair":
        e = e + _rf([0, draw(st.sampled_from([-1, 1, 3]))], [draw(st.sampled_from([1, 4])), 0, 1])
    elif extra == "mass":
        e = e + _rf([0, Fraction(draw(st.sampled_from([-1, 1])), draw(st.sampled_from([1, 2, 10])))])
    elif extra == "rhp":
        e = e + _rf([draw(st.sampled_from([1, 2]))], [-draw(st.sampled_from([1, 2])), 1])
    elif extra == "stretch":      # issue 10: a negative stretch between w = 0 and the first root
        e = e + _rf([1]) - _rf([2], [1, 1]) + _rf([draw(st.sampled_from([10, 1, 3]))],
                                                  [draw(st.sampled_from([10**4, 100, 1000])), 1])
    return e


@st.composite
def impedances(draw, sizes=(1, 2, 2, 4)):
    """Random n-ports: general, reciprocal, similar to a reciprocal one (D S D^-1, also with a heavy
    diagonal) or diagonally heavy."""
    n = draw(st.sampled_from(sizes))
    kind = draw(st.sampled_from(["general", "reciprocal", "similar", "dominant", "similar dominant"]))
    rows = [[None] * n for _ in range(n)]
    for i in range(n):
        for j in range(n):
            if kind == "general" or j >= i:
                rows[i][j] = draw(entries(i == j))
            else:
                rows[i][j] = rows[j][i]
    if kind.startswith("similar"):
        if kind == "similar dominant":           # Z' = S + a I, often positive real while Z is not
            extra = draw(st.sampled_from([6, 10, 20]))
            rows = [[rows[i][j] + (_rf([extra]) if i == j else _rf([0])) for j in range(n)] for i in range(n)]
        d = [Fraction(draw(st.sampled_from([1, 2, 3, 5, -1]))) / draw(st.sampled_from([1, 2])) for _ in range(n)]
        rows = [[rows[i][j].scale(d[i] / d[j]) for j in range(n)] for i in range(n)]
    elif kind == "dominant":
        extra = draw(st.sampled_from([3, 6, 10]))
        damper = draw(st.sampled_from([0, 1]))
        rows = [[rows[i][j] + (_rf([extra]) + _rf([damper], [1, 1]) if i == j else _rf([0])) for j in range(n)]
                for i in range(n)]
    return RationalMatrix.from_entries(rows), kind


# =============================================================================================
# rational functions and matrices
# =============================================================================================


@settings(max_examples=20, deadline=None)
@given(small, small, positive, small, positive)
def test_rational_function_arithmetic_matches_sympy(a, b, c, d, e):
    f = a / (s + c) + b
    g = d * s / (s**2 + e)
    F, G = RationalFunction.from_sympy(f), RationalFunction.from_sympy(g)
    for ours, theirs in ((F + G, f + g), (F * G, f * g), (F - G, f - g)):
        assert sp.cancel(ours.expr() - theirs) == 0
    if g != 0:
        assert sp.cancel((F / G).expr() - f / g) == 0


def test_inverse_and_determinant_are_exact():
    Z = sp.Matrix([[1 / (s + 1), 2], [s, 3 / (s + 2)]])
    R = RationalMatrix.from_sympy(Z)
    assert sp.cancel(R.determinant().expr() - Z.det()) == 0
    assert (R.inverse().to_sympy() - Z.inv()).applyfunc(sp.cancel) == sp.zeros(2, 2)


@settings(max_examples=25, deadline=None)
@given(st.lists(small, min_size=9, max_size=9), st.lists(positive, min_size=3, max_size=3),
       st.fractions(min_value=Fraction(1, 20), max_value=20, max_denominator=1000))
def test_hermitian_minors_and_axis_values_are_exact(nums, poles, w):
    """Every principal minor of the Hermitian part, exact in x, equals the exact minor of
    Z(jw) + Z(jw)^H at a rational w (and the float value)."""
    Z = sp.Matrix(3, 3, lambda i, j: sp.Integer(nums[3 * i + j]) / (s + poles[j]) + (2 if i == j else 0))
    R = RationalMatrix.from_sympy(Z)
    minors = hermitian_minors(R)
    H = R.hermitian_at(w)
    at = Z.subs(s, sp.I * sp.Rational(w.numerator, w.denominator))
    assert all(sp.expand_complex(sp.together(h - e)) == 0 for h, e in zip(H, at + at.H))
    for subset in itertools.combinations(range(3), 2):
        exact = minors.true_minor(subset, w * w)
        assert 4 * exact == sp.expand(H.extract(list(subset), list(subset)).det())      # H = 2 Re part
        numeric = np.linalg.det(np.array(H.extract(list(subset), list(subset)).evalf(), dtype=complex)).real
        assert 4 * float(exact) == pytest.approx(numeric, rel=1e-9, abs=1e-12)


def test_leading_minors_are_not_enough():
    # constant Hermitian part with leading minors 0, 0 -- not PSD; the decision must see it
    out = decide_psd(hermitian_minors(RationalMatrix.from_sympy(sp.Matrix([[0, 0], [0, -1]]))))
    assert out.decision == Decision.DISPROVED
    assert out.evidence.facts["negative_principal_minor"]["rows"] == [2]
    assert check_certificate(to_jsonable(out.evidence.facts)["certificate"]).ok
    assert constant_psd(sp.Matrix([[0, 0], [0, -1]])).decision == Decision.DISPROVED


def test_minimise_halfline_limit_at_infinity():
    m = minimise_halfline(flint.fmpq_poly([2, 0, 1]), flint.fmpq_poly([1, 0, 1]))   # (x^2+2)/(x^2+1) -> 1
    assert m.argmin == sp.oo and float(m.value.mid()) == pytest.approx(1.0)


def test_pole_report_is_one_root_certificate():
    rep = pole_report(RationalMatrix.from_sympy(sp.Matrix([[1 / (s - 2), 1 / s**2]])))
    assert rep.rhp and not rep.axis_simple
    assert rep.certificate.outside == 1 and check_certificate(rep.certificate.to_json()).ok
    p = flint.fmpq_poly([4, 0, 1]) * flint.fmpq_poly([-1, 1]) * flint.fmpq_poly([2, 1])   # (s^2+4)(s-1)(s+2)
    cert = locate_roots(p, "halfplane")
    assert cert.outside == 1 and cert.outside_points[0].real == pytest.approx(1.0)


# =============================================================================================
# positive realness
# =============================================================================================


def test_positive_real_rlc_and_residues():
    # a reciprocal RLC 2-port: P + Q s + R/s with PSD P, Q, R
    P, Q, R = sp.Matrix([[2, 1], [1, 1]]), sp.Matrix([[1, 0], [0, 0]]), sp.Matrix([[1, 1], [1, 1]])
    T = P + Q * s + R / s
    result = positive_real(T)
    assert result.decision == Decision.PROVED
    checked(result)
    assert residue_matrix(RationalMatrix.from_sympy(T), "zero") == R
    assert residue_matrix(RationalMatrix.from_sympy(T), "infinity") == Q
    # an indefinite residue at s = 0 breaks it
    bad = positive_real(P + sp.Matrix([[1, 2], [2, 1]]) / s)
    assert bad.decision == Decision.DISPROVED and bad.residues.decision == Decision.DISPROVED
    checked(bad)


def test_positive_real_pair_pole():
    # s/(s^2 + 4) is PR (LC tank): residue 1/2 at +-2j; -s/(s^2+4) is not
    assert positive_real(sp.Matrix([[s / (s**2 + 4)]])).decision == Decision.PROVED
    bad = positive_real(sp.Matrix([[-s / (s**2 + 4)]]))
    assert bad.decision == Decision.DISPROVED and bad.residues.witness["pole_frequency"] == 2.0
    B, A = residue_matrix(RationalMatrix.from_sympy(sp.Matrix([[s / (s**2 + 4)]])), ("pair", 4))
    assert B == sp.Matrix([[1]]) and A == sp.Matrix([[0]])
    # a matrix residue at +-2j: [[1/2, -kj/4], [kj/4, 1/2]] is Hermitian, PSD iff k <= 2
    for k, decision in ((1, Decision.PROVED), (3, Decision.DISPROVED)):
        Z = sp.Matrix([[s, k], [-k, s]]) / (s**2 + 4)
        result = positive_real(Z)
        assert result.decision == decision and result.residues.decision == decision
        checked(result)


ISSUE_Z = 1 - 2 / (s + 1) + 10 / (s + 10**4)      # issue 10: Re Z(j0) = -999/1000


def test_issue10_negative_stretch_next_to_zero_frequency():
    """Z(s) = 1 - 2/(s+1) + 10/(s+10^4): the Hermitian-part polynomial x^2 + 100099999 x - 99900000
    is negative from x = 0 to its first root; it was reported positive real."""
    result = positive_real(sp.Matrix([[ISSUE_Z]]))
    assert result.decision == Decision.DISPROVED
    assert result.hermitian.witness == {"x": 0, "omega": 0}
    data = checked(result)
    cert = data["conditions"][3]["evidence"]["facts"]["certificate"]
    assert cert["certificate"] == "psd" and not cert["holds"]
    assert oracle_hermitian_at(entries_of(sp.Matrix([[ISSUE_Z]])), Fraction(0)) < 0
    # a stretch before a tiny first root: Re Z(jw) < 0 only for w < 0.01
    tiny = positive_real(sp.Matrix([[1 - (1 + sp.Rational(1, 10**4)) / (s + 1)]]))
    assert tiny.decision == Decision.DISPROVED and float(tiny.hermitian.witness["omega"]) < 0.01
    checked(tiny)


@settings(max_examples=examples(60), deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(impedances())
def test_positive_real_agrees_with_the_oracle(case):
    Z, kind = case
    result = positive_real(Z)
    checked(result)
    E = entries_of(Z)
    verdict, why = oracle_positive_real(E)
    log("positive_real", n=Z.shape[0], kind=kind, toolkit=result.decision.value, oracle=verdict, why=why)
    if result.decision == Decision.PROVED:
        assert verdict != "disproved", (Z, why)
    else:
        assert result.decision == Decision.DISPROVED, result.reason
        confirmed = witness_confirmed(E, result)
        assert confirmed is not False, (Z, result.reason)
        assert confirmed or verdict != "proved", (Z, result.reason, why)


# =============================================================================================
# Llewellyn
# =============================================================================================


def test_llewellyn_paper_subsystem_is_tight_at_zero():
    result = llewellyn(sp.Matrix([[9 / (s + 3), -1 / (s + 1)], [-1 / (s + 1), 1 / (s + 3)]]))
    assert result.decision == Decision.PROVED
    assert result.tightest.argmin == 0 and result.eta_min == 1
    checked(result)


def test_llewellyn_gyrator_and_failure():
    assert llewellyn(sp.Matrix([[1, 2], [-2, 1]])).decision == Decision.PROVED     # eta = (2 + 4)/4 >= 1
    bad = llewellyn(sp.Matrix([[1, 3], [3, 1]]))                                   # eta = (2 - 9)/9 < 1
    assert bad.decision == Decision.DISPROVED
    checked(bad)
    issue = llewellyn(sp.Matrix([[ISSUE_Z, 0], [0, 1]]))
    assert issue.decision == Decision.DISPROVED and issue.condition("Re z11 >= 0 for every w").witness["omega"] == 0


@settings(max_examples=examples(50), deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(impedances(sizes=(2,)))
def test_llewellyn_agrees_with_the_oracle(case):
    Z, kind = case
    result = llewellyn(Z)
    checked(result)
    E = entries_of(Z)
    verdict, why = oracle_llewellyn(E)
    log("llewellyn", n=2, kind=kind, toolkit=result.decision.value, oracle=verdict, why=why)
    if result.decision == Decision.PROVED:
        assert verdict != "disproved", (Z, why)
    else:
        assert result.decision == Decision.DISPROVED, result.reason
        confirmed = witness_confirmed(E, result)
        assert confirmed is not False, (Z, result.reason)
        assert confirmed or verdict != "proved", (Z, result.reason, why)


# =============================================================================================
# Youla symmetrization
# =============================================================================================


def test_symmetrization_conditions_reduce_only_by_nonzero_entries():
    a, b, c = sp.symbols("a b c")
    Z = sp.Matrix([[1, a, 1], [a, 1, b], [c, 1, 1]])
    conds = symmetrization_conditions(Z, ports=(2, 1))
    assert [(x.kind, x.reduced) for x in conds] == [("A", True)]
    assert sp.expand(conds[0].expr - (b * c - 1)) == 0 or sp.expand(conds[0].expr + (b * c - 1)) == 0
    # with the cancelled entry zero, A is not reduced (and holds vacuously here)
    Z0 = Z.subs(a, 0)
    assert symmetrization_conditions(Z0, ports=(2, 1)) == []


@settings(max_examples=10, deadline=None)
@given(st.lists(st.integers(min_value=1, max_value=5), min_size=3, max_size=3),
       st.lists(small, min_size=6, max_size=6))
def test_symmetrize_diagonal_similarity_recovers_minors(scales, couplings):
    """Z = D S D^-1 with S symmetric: Youla's Z' exists and has all principal minors of Z."""
    S = sp.Matrix([[2 + 1 / (s + 1), couplings[0] / (s + 2), couplings[1]],
                   [couplings[0] / (s + 2), 3, couplings[2] / (s + 1)],
                   [couplings[1], couplings[2] / (s + 1), 1 + s]])
    D = sp.diag(*scales)
    Z = D * S * D.inv()
    Y = symmetrize(Z)
    assert Y.symmetrizable == Decision.PROVED
    Zp = Y.zprime()
    assert (Zp - Zp.T).applyfunc(sp.simplify) == sp.zeros(3, 3)
    point = sp.Rational(3, 2)
    for k in (1, 2, 3):
        for rows in itertools.combinations(range(3), k):
            rows = list(rows)
            a = sp.nsimplify(sp.simplify(Z.extract(rows, rows).subs(s, point).det()))
            b = sp.nsimplify(sp.simplify(Zp.extract(rows, rows).subs(s, point).det()))
            assert a == b


@settings(max_examples=10, deadline=None)
@given(st.lists(st.sampled_from([1, 2, 3, sp.Rational(1, 2), -1, -2]), min_size=2, max_size=2),
       st.lists(small, min_size=10, max_size=10))
def test_symmetrize_grouped_ports_respects_the_blocks(scales, c):
    """Z = D S D^-1 with D constant on the two 2-DOF ports: Z' keeps Z's port blocks and has
    Z's block-compatible minors, so det(Z' + T) = det(Z + T) for full 2x2 terminations."""
    S = sp.Matrix([[3, c[0], c[1], c[2] / (s + 1)],
                   [c[0], 4 + 1 / (s + 2), c[3], c[4]],
                   [c[1], c[3], 2, c[5] / (s + 2)],
                   [c[2] / (s + 1), c[4], c[5] / (s + 2), 5]])
    D = sp.diag(scales[0], scales[0], scales[1], scales[1])
    Z = (D * S * D.inv()).applyfunc(sp.cancel)
    Y = symmetrize(Z, (2, 2))
    assert Y.symmetrizable == Decision.PROVED
    Zp = Y.zprime()
    assert (Zp - Zp.T).applyfunc(sp.simplify) == sp.zeros(4, 4)
    assert Zp.extract([0, 1], [0, 1]) == Z.extract([0, 1], [0, 1])
    T = sp.Matrix([[1 + 1 / s, sp.Rational(1, 2)], [sp.Rational(1, 2), 2 * s]])
    full = sp.diag(T, T.subs(s, 2 * s))
    for point in (sp.Rational(3, 2), sp.Rational(7, 3)):
        lhs = (Z + full).subs(s, point).det()
        rhs = (Zp + full).subs(s, point).applyfunc(sp.nsimplify).det()
        assert sp.nsimplify(sp.simplify(lhs - rhs)) == 0


def test_issue10_reciprocal_grouped_network_is_its_own_symmetrization():
    """[[2, -1], [-1, 2]] (+) 2I with ports (2, 2): positive real, yet 'not symmetrizable' before
    (the spanning-tree sign +1 flipped the in-port coupling -1)."""
    Z = sp.diag(sp.Matrix([[2, -1], [-1, 2]]), 2 * sp.eye(2))
    Y = symmetrize(Z, (2, 2))
    assert Y.symmetrizable == Decision.PROVED and Y.zprime() == Z and Y.rhat.to_sympy() == Z
    verdict = absolute_stability(Z, ports=(2, 2))
    assert verdict.decision == Decision.PROVED and verdict.method == "positive real" and verdict.search is None
    # a negative coupling inside a port and a cross-port coupling, not positive real: Youla decides
    W = sp.Matrix([[2, -1, 3, 0], [-1, 2, 0, 1], [3, 0, 1, 0], [0, 1, 0, 1]])
    Y = symmetrize(W, (2, 2))
    assert Y.symmetrizable == Decision.PROVED and Y.zprime() == W
    assert absolute_stability(W, ports=(2, 2), search=False).method == "Youla symmetrization"


def test_symmetrize_imaginary_couplings_and_cycles():
    # gyrator-like couplings: z12 z21 = -4 (negative constant times a square): Z' is complex
    Z = sp.Matrix([[1, 2, 0], [-2, 1, 0], [0, 0, 1]])
    Y = symmetrize(Z)
    assert Y.symmetrizable == Decision.PROVED and any(u < 0 for u in Y.scales)
    assert sp.simplify(Y.zprime()[0, 1] ** 2 + 4) == 0
    assert absolute_stability(Z, search=False).decision == Decision.PROVED
    checked(zprime_positive_real(Y))
    # a 4-cycle with unequal forward/backward products: A holds vacuously, no Z' exists
    C = sp.eye(4) * 2
    C[0, 1], C[1, 0] = 2, sp.Rational(1, 2)
    for a, b in ((1, 2), (2, 3), (3, 0)):
        C[a, b] = C[b, a] = 1
    assert symmetrization_conditions(C) == []
    assert symmetrize(C).symmetrizable == Decision.DISPROVED


def test_irrational_zprime_is_undecided_not_guessed():
    Z = sp.Matrix([[2, 1 / (s + 1), 1], [1 / (s + 2), 2, 1], [1, 1, 2]])
    assert symmetrize(Z).symmetrizable == Decision.DISPROVED  # A fails here
    Z2 = sp.Matrix([[2, 1 / (s + 1), 0], [1 / (s + 2), 2, 0], [0, 0, 2]])
    assert symmetrize(Z2).symmetrizable == Decision.UNDECIDED   # (s+1)(s+2) is not a square


def test_theorem9_conditions_corrected_vs_printed():
    leading = sp.diag(sp.Matrix([[0, 0, 0], [0, 1, 2], [0, 2, 1]]), sp.eye(3))
    th = theorem9_conditions(leading, (3, 3))
    assert [getattr(th, k).decision for k in ("A", "B", "C", "D")] == [Decision.PROVED] * 4
    assert th.E_printed.decision == Decision.PROVED and th.E.decision == Decision.DISPROVED
    assert check_report(json.loads(json.dumps(to_jsonable(th.to_json())))).ok
    cycle = sp.eye(6) * 2
    cycle[0, 3], cycle[3, 0] = 2, sp.Rational(1, 2)
    for a, b in ((3, 1), (1, 4), (4, 0)):
        cycle[a, b] = cycle[b, a] = 1
    th = theorem9_conditions(cycle, (3, 3))
    assert th.B.decision == Decision.PROVED and th.A.decision == Decision.DISPROVED


# =============================================================================================
# absolute stability and destabilizing terminations
# =============================================================================================


def certificate_confirmed(Z, ports, cert) -> bool:
    """The oracle's own check of a certificate: every termination positive real (or inside the
    band), and det(Z + T) with a zero in Re s > 0."""
    sizes = ports or (1,) * (Z.shape[0] if isinstance(Z, RationalMatrix) else Z.rows)
    Ts = [entries_of(sp.Matrix(T)) for T in cert.terminations]
    passive = all(oracle_positive_real(T)[0] != "disproved" for T in Ts)
    return bool(passive and oracle_rhp_zero(oracle_add(entries_of(Z), oracle_block_diag(Ts, sizes))) > 0)


def assert_certificate(Z, ports, cert) -> None:
    """A returned certificate verifies exactly (the kernel), independently (the checker) and
    numerically (the oracle)."""
    n = Z.shape[0] if isinstance(Z, RationalMatrix) else Z.rows
    sizes = ports or (1,) * n
    blocks = [tuple(range(sum(sizes[:k]), sum(sizes[:k + 1]))) for k in range(len(sizes))]
    roots, _ = verify_certificate(Z if isinstance(Z, RationalMatrix) else RationalMatrix.from_sympy(Z), cert.terminations, blocks)
    assert roots and all(r.real > 0 for r in roots)
    assert cert.terminations_positive_real
    data = json.loads(json.dumps(to_jsonable(cert.to_json())))
    assert check_report(data).ok and data["determinant"]["rhp_zero"]
    assert certificate_confirmed(Z, ports, cert)


def test_hand_certificate_is_verified_exactly():
    Z = sp.diag(sp.Matrix([[0, 0, 0], [0, 1, 2], [0, 2, 1]]), sp.eye(3))
    terms = (sp.diag(1, 2 / (s + 1), 2 / (s + 1)), sp.eye(3))
    roots, degree = verify_certificate(RationalMatrix.from_sympy(Z), terms, ((0, 1, 2), (3, 4, 5)))
    assert len(roots) == 1 and roots[0].real == pytest.approx(1.0)
    # and no RHP zero with passive terminations that keep the network passive
    roots, _ = verify_certificate(RationalMatrix.from_sympy(sp.eye(6)), terms, ((0, 1, 2), (3, 4, 5)))
    assert roots == []


def test_absolute_stability_detects_reciprocal_non_passive_network():
    """Decided by Youla (Z' = Z is not positive real), not by the search; a certificate, when the
    search returns one, must verify exactly, with the checker and with the oracle."""
    Z = sp.diag(sp.Matrix([[0, 0, 0], [0, 1, 2], [0, 2, 1]]), sp.eye(3))
    verdict = absolute_stability(Z, ports=(3, 3))
    assert verdict.decision == Decision.DISPROVED and verdict.method == "Youla symmetrization"
    checked(verdict)
    if verdict.certificate is not None:
        assert_certificate(Z, (3, 3), verdict.certificate)
    else:  # pragma: no cover - depends on the search; the report must say what it tried
        assert verdict.search is not None and verdict.search.summary()


def test_issue10_diag_network_and_the_half_ohm_termination():
    """diag(Z, 1) with Re Z(j0) < 0 was called absolutely stable; a 0.5 ohm termination of the
    first port puts a zero of det(Z + T) at s ~ +0.33."""
    Z2 = sp.Matrix([[ISSUE_Z, 0], [0, 1]])
    verdict = absolute_stability(Z2)
    assert verdict.decision == Decision.DISPROVED and verdict.method == "Llewellyn"
    checked(verdict)
    cert = exact_determinant(Z2, [sp.Matrix([[sp.Rational(1, 2)]]), sp.Matrix([[1]])], ((0,), (1,)))
    assert cert.rhp_zero and cert.roots.outside_points[0].real == pytest.approx(1 / 3, abs=0.01)
    assert check_certificate(json.loads(json.dumps(cert.to_json()))).ok
    if verdict.certificate is not None:
        assert_certificate(Z2, None, verdict.certificate)


def test_issue10_coupled_4x4_with_a_negative_stretch_near_zero():
    """A reciprocal 4x4 (a rational rotation of diag(z, 2, 3, 4) with z = (s - 10^-4)/(s + 1)):
    its Hermitian part is negative only for w < 0.01; potentially unstable (Youla)."""
    z = (s - sp.Rational(1, 10**4)) / (s + 1)
    H = sp.eye(4) - sp.ones(4, 4) / 2                          # a rational orthogonal reflection
    Z = (H * sp.diag(z, 2, 3, 4) * H).applyfunc(sp.cancel)
    pr = positive_real(Z)
    assert pr.decision == Decision.DISPROVED and pr.hermitian.witness["omega"] == 0
    checked(pr)
    verdict = absolute_stability(Z)
    assert verdict.decision == Decision.DISPROVED and verdict.method == "Youla symmetrization"
    if verdict.certificate is not None:
        assert_certificate(Z, None, verdict.certificate)


def test_issue10_positive_real_4x4_is_decided_before_any_search():
    """A positive-real 4x4 (it ran a 170 s termination search before): decided by positive
    realness, with no search at all (timing is for the benchmarks)."""
    S = sp.Matrix([[4, 1, 0, 1], [1, 5, 1, 0], [0, 1, 4, 1], [1, 0, 1, 5]])
    Z = S + sp.Matrix([[1, -1, 0, 0], [-1, 2, 0, 0], [0, 0, 1, 0], [0, 0, 0, 0]]) / (s + 1) + sp.diag(1, 0, 1, 0) / s
    for ports in (None, (2, 2)):
        verdict = absolute_stability(Z, ports=ports)
        assert verdict.decision == Decision.PROVED and verdict.method == "positive real" and verdict.search is None
        checked(verdict)


def test_search_ends_by_its_deadline_and_says_what_it_tried():
    """A positive-real network has no destabilizing termination: the search tries everything
    (or stops at the deadline) and reports it; nothing is asserted about time."""
    out = search_terminations(sp.Matrix([[2 + 1 / (s + 1), 1], [1, 3]]), deadline=5.0)
    assert out.certificate is None and out.points and out.subsets
    assert out.summary().startswith(("no destabilizing termination found", "undecided after"))
    assert out.to_json()["found"] is False
    stopped = search_terminations(sp.Matrix([[2 + 1 / (s + 1), 1], [1, 3]]), deadline=1e-9)
    assert stopped.certificate is None and not stopped.complete and stopped.summary().startswith("undecided after")


def tampered_determinants():
    Z = sp.Matrix([[1, 3], [3, 1]])
    cert = exact_determinant(Z, [sp.Matrix([[4 / (s + 1)]])] * 2, ((0,), (1,)))
    good = json.loads(json.dumps(cert.to_json()))
    assert check_certificate(good).ok
    bad = copy.deepcopy(good)
    bad["numerator"][0] = str(Fraction(bad["numerator"][0]) + 1)
    yield "numerator", bad
    bad = copy.deepcopy(good)
    bad["matrix"][0][0]["num"][0] = "2"
    yield "matrix", bad
    bad = copy.deepcopy(good)
    bad["roots"]["outside"] = 0
    yield "roots", bad
    stable = json.loads(json.dumps(exact_determinant(Z, [sp.Matrix([[1]])] * 2, ((0,), (1,))).to_json()))
    bad = copy.deepcopy(good)
    bad["roots"], bad["numerator"], bad["denominator"] = stable["roots"], stable["numerator"], stable["denominator"]
    yield "other determinant", bad


@pytest.mark.parametrize("name,cert", list(tampered_determinants()), ids=lambda v: v if isinstance(v, str) else "")
def test_checker_rejects_tampered_determinant_certificates(name, cert):
    assert not check_certificate(cert).ok


@settings(max_examples=examples(20), deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(impedances(sizes=(2, 4)), st.booleans(), st.integers(0, 2**16))
def test_absolute_stability_agrees_with_the_oracle(case, grouped, seed):
    """Proved verdicts: the oracle's own criterion (positive realness, Llewellyn) or random passive
    terminations that must not destabilize; disproved verdicts: the certificate, when there is
    one, re-checked numerically, else the oracle's criterion on the failing (sub)network."""
    Z, kind = case
    n = Z.shape[0]
    ports = (2, 2) if n == 4 and grouped else None
    verdict = absolute_stability(Z, ports=ports, deadline=3.0)
    checked(verdict)
    E = entries_of(Z)
    sizes = ports or (1,) * n
    agree = None
    if verdict.decision == Decision.PROVED:
        if verdict.method == "positive real":
            agree = oracle_positive_real(E)[0] != "disproved"
        elif verdict.method == "Llewellyn":
            agree = oracle_llewellyn(E)[0] != "disproved"
        else:
            rng = np.random.default_rng(seed)
            agree = bool(all(oracle_rhp_zero(oracle_add(E, oracle_block_diag([oracle_random_rlc(rng, m) for m in sizes], sizes)))
                             < 1e-7 for _ in range(2)))
    elif verdict.decision == Decision.DISPROVED:
        if verdict.certificate is not None:
            agree = certificate_confirmed(Z, ports, verdict.certificate)
        elif verdict.method == "Llewellyn":
            agree = witness_confirmed(E, verdict.llewellyn)
            agree = bool(agree) if agree is not None else oracle_llewellyn(E)[0] != "proved"
        elif verdict.method == "open-circuit instability":
            agree = bool(o_poles(E)[0])
        elif verdict.method == "Youla symmetrization" and Z.is_symmetric():
            agree = oracle_positive_real(E)[0] != "proved"
        elif verdict.method == "subnetwork":
            subset, _ = verdict.subnetwork
            idx = [i for k in subset for i in range(sum(sizes[:k]), sum(sizes[:k + 1]))]
            sub = [[E[i][j] for j in idx] for i in idx]
            agree = (oracle_llewellyn(sub) if len(subset) == 2 else oracle_positive_real(sub))[0] != "proved"
    log("absolute_stability", n=n, ports=ports, kind=kind, toolkit=verdict.decision.value, method=verdict.method,
        certificate=verdict.certificate is not None, agree=agree,
        **({"Z": str(Z.to_sympy()), "certificate_json": verdict.certificate.to_json() if verdict.certificate else None}
           if agree is False else {}))
    assert agree is not False, (Z, ports, verdict.reason)


def test_input_impedance():
    Zin = input_impedance(sp.Matrix([[1, 3], [3, 1]]), sp.Matrix([[10]]), (1, 1))
    assert Zin.to_sympy() == sp.Matrix([[sp.Rational(2, 11)]])


# =============================================================================================
# energy
# =============================================================================================


def test_realization_matches_transfer_matrix():
    G = RationalMatrix.from_sympy(sp.Matrix([[1 / (s + 1), 2 / (s**2 + s + 3)], [s / (s + 2), 1]]))
    ss = realize(G)
    for point in (0.3j, 1 + 2j, 5j):
        assert np.allclose(ss.transfer_at(point), G.numpy_at(point), rtol=1e-9, atol=1e-12)


def test_energy_matches_independent_quadrature():
    """Exact-between-samples energy vs a tight ODE integration with mpmath-free quadrature."""
    from scipy.integrate import solve_ivp

    Z = sp.Matrix([[1 + 1 / s, 1], [1, 2 + s]])      # a passive 2-port
    G = port_admittance(Z, {1: sp.Matrix([[1 / (s + 1)]])}, driven=(0,))
    ss = realize(G)
    sine = Sinusoid(1.5, 2.0, 0.3)
    trace = input_energy(ss, [sine], t_end=5.0, steps=500)

    def rhs(t, z):
        x = z[:-1]
        u = sine.amplitude * math.sin(sine.omega * t + sine.phase)
        y = (ss.c @ x + ss.d[:, 0] * u)[0]
        return np.concatenate([ss.a @ x + ss.b[:, 0] * u, [u * y]])

    sol = solve_ivp(rhs, (0, 5.0), np.zeros(ss.a.shape[0] + 1), rtol=1e-11, atol=1e-13, t_eval=trace.times)
    assert np.allclose(sol.y[-1], trace.energy, atol=1e-8)
    assert trace.minimum >= -1e-12   # passive network, passive load: E_s >= 0


# =============================================================================================
# CLI: hapticproof derive network
# =============================================================================================


def test_cli_text_and_json(tmp_path, capsys):
    from hapticproof.cli import main

    text = tmp_path / "z5.txt"
    text.write_text("# eq. (5)\n9/(s+3), -1/(s+1)\n-1/(s+1), 1/(s+3)\n")
    assert main(["derive", "network", "--matrix", str(text)]) == 0
    out = capsys.readouterr().out
    assert "absolutely stable (positive real)" in out and "Llewellyn: proved" in out
    js = tmp_path / "z.json"
    js.write_text(json.dumps({"matrix": [["1", "3"], ["3", "1"]]}))
    assert main(["derive", "network", "--matrix", str(js), "--format", "json", "--no-search"]) == 0
    data = json.loads(capsys.readouterr().out)
    assert data["absolute_stability"]["decision"] == "disproved"
    assert data["positive_real"]["decision"] == "disproved"
    assert [c["name"] for c in data["conditions"]] == ["Z positive real (Definition 3)", "Llewellyn's criterion",
                                                       "absolute stability"]


def test_cli_json_report_is_rechecked_by_hapticproof_check(tmp_path, capsys):
    """issue 10: a saved 'derive network --format json' report is re-verified by 'hapticproof check'."""
    from hapticproof.cli import main

    matrix = tmp_path / "z.txt"
    matrix.write_text("1 - 2/(s+1) + 10/(s+10000), 0\n0, 1\n")
    assert main(["derive", "network", "--matrix", str(matrix), "--format", "json", "--deadline", "5"]) == 0
    report = tmp_path / "report.json"
    report.write_text(capsys.readouterr().out)
    data = json.loads(report.read_text())
    assert data["absolute_stability"]["decision"] == "disproved"
    assert check_report(data).ok
    assert main(["check", str(report)]) == 0
    out = capsys.readouterr().out
    assert "0 certificate(s) failed" in out and "without a certificate" in out
    # a tampered certificate is caught
    bad = copy.deepcopy(data)
    cert = bad["conditions"][0]["conditions"][3]["evidence"]["facts"]["certificate"]
    failing = next(c for c in cert["coefficients"] if not c["holds"])
    failing["witness"] = "100000"                     # the coefficient is positive there
    report.write_text(json.dumps(bad))
    assert main(["check", str(report)]) == 1


def test_cli_parameters_and_errors(tmp_path, capsys):
    from hapticproof.cli import main

    f = tmp_path / "zk.txt"
    f.write_text("2, k\n1/(s+1), 2\n")
    assert main(["derive", "network", "--matrix", str(f)]) == 0
    assert "free parameters" in capsys.readouterr().out
    assert main(["derive", "network", "--matrix", str(f), "--param", "k=1", "--format", "latex"]) == 0
    assert r"\begin{document}" in capsys.readouterr().out
    bad = tmp_path / "bad.txt"
    bad.write_text("1, __import__('os')\n")
    assert main(["derive", "network", "--matrix", str(bad)]) == 2
    ragged = tmp_path / "ragged.txt"
    ragged.write_text("1, 2\n3\n")
    assert main(["derive", "network", "--matrix", str(ragged)]) == 2
    assert main(["derive", "network", "--matrix", str(f), "--param", "k=1", "--ports", "3,3"]) == 2
    for deadline in ("-1", "soon", "0", "inf"):
        assert main(["derive", "network", "--matrix", str(f), "--param", "k=1", "--deadline", deadline]) == 2
    err = capsys.readouterr().err
    assert "--deadline" in err and "Traceback" not in err
