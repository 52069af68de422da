r"""Oracles for continuous-time n-ports ``Z(s)`` (3-DOF bilateral paper, Definition 3, Llewellyn).

:func:`positive_real_matrix` -- a real-rational ``n x n`` ``Z(s)`` is positive real when

1. no entry has a pole in ``Re s > 0``;
2. imaginary-axis poles are simple with Hermitian PSD residue matrices; a pole at infinity is
   allowed when simple with a symmetric PSD coefficient of ``s``;
3. ``Z(jw) + Z(jw)^H`` is PSD for every real ``w`` (``w >= 0`` suffices: at ``-w`` it is the
   conjugate matrix).

Near an axis pole ``jw0`` with Hermitian residue ``R``, ``R/(j(w - w0)) + (R/(j(w - w0)))^H = 0``,
so the Hermitian part is continuous there; it is evaluated as the mean of the two sides at
relative distance ``1e-15`` (60 digits). At a pole at infinity with symmetric ``L``, ``jwL -
jwL^T = 0`` likewise.

Method: exact cancellation (SymPy), poles of each entry by square-free factorisation and mpmath
``polyroots`` at 60+ digits (on the axis when ``|Re p| <= 1e-40 max(1, |p|)``), residues
``num/den'``. Exact checks first: ``Z(0) + Z(0)^T`` (no pole at 0) and the limit ``D0 + D0^T`` at
infinity are rational matrices, decided by their principal minors; ``Z(s) + Z(-s)^T = 0``
identically (lossless) means the Hermitian part vanishes. Then ``lambda_min(Z(jw) + Z(jw)^H)``:

* screened on a log grid of 40 points per decade over ``[min(1e-8, 1e-3 r_min), max(1e8, 1e3
  r_max)]`` (``r``: moduli of all poles and zeros of the entries) plus points clustered at lightly
  damped poles, in double precision except within ``1e-4`` (relative) of axis poles (``w <=
  1e-6`` for a pole at 0), where ``Z`` is evaluated at 30 digits;
* the eight lowest interior local minima are refined by golden section on ``log w`` (double
  precision) and re-evaluated with ``Z`` formed at 60 digits (eigenvalues at 60 digits unless
  the double-precision ones of that 60-digit matrix are clearly positive);
* a minimum below ``beta = 1e-13 S`` is looked at again: flat to 60 digits on both sides (a
  plateau: a constant eigen-direction) it is judged against ``1e-25 S``; otherwise (two of them
  at most) a downhill walk on the grid with 60-digit values (double-precision noise makes
  spurious minima where ``lambda_min`` is tiny but ``M`` is not) either reaches a grid end (then
  the end samples cover it) or a true local minimum, located by golden section at 60 digits and
  judged against ``1e-20 S``;
* the ends are sampled at 60 digits: ``w = 0``, ``w = 10^-k`` (``k`` from 9 to 30), ``w = 10^k``
  (``k`` from 9 to 40).

Near an axis pole every evaluation is the mean of the two sides at relative distance ``1e-15``
with 35 extra digits (``s - j w0`` and the polar part cost 15 digits each).

Uncertainty band: ``no`` needs a 60-digit value ``< -nu``, ``nu = max(1e-30 S, 1e-50 A)`` (``S =
max |M_ij|`` over the grid away from axis poles, ``A = max |Z_ij|`` at the point), or an exact end
matrix that is not PSD; ``yes`` needs every interior minimum above its band (``1e-13 S``, or the
smaller bands above after a second look) and no end sample below ``-nu`` (the ends only ever
refute: a true value within ``1e-50 A`` of 0 but negative is not expected from coefficients of
moderate height; the exact end checks catch the limits themselves). Residue matrices are
Hermitian when ``|R - R^H| <= 1e-30 |R|`` (not when ``> 1e-20 |R|``) and PSD when ``lambda_min
>= -1e-30 |R|`` (a rank tolerance: exact rank-deficient residues are common; a true eigenvalue
that small is not, for coefficients of moderate height); the coefficient of ``s`` at infinity is
decided exactly.

:func:`llewellyn` -- Llewellyn's criterion for a 2-port in impedance form: open-circuit stable
(no entry with a pole in ``Re s > 0``); ``z11`` and ``z22`` have only simple axis poles (and at
most a simple pole at infinity) with real non-negative residues; and for all ``w``: ``Re z11
>= 0``, ``Re z22 >= 0``, ``2 Re z11 Re z22 - Re(z12 z21) - |z12 z21| >= 0``. The three functions
are minimised separately with the same numerics and bands (``S`` is the largest of ``|Re z_kk|``,
resp. ``2 |Re z11 Re z22| + 2 |z12 z21|``, on the grid); their values at ``w = 0`` and their limits
at infinity (when ``z12 z21`` stays bounded) are exact rationals, checked first; ``Re z_kk = 0``
identically (``z_kk(s) + z_kk(-s) = 0``) is recognised exactly.

>>> import sympy as sp
>>> s = S
>>> positive_real_matrix(sp.Matrix([[1 - 2/(s + 1) + sp.Rational(10)/(s + 10**4)]])).verdict
'no'
>>> positive_real_matrix(sp.Matrix([[1 + 1/s, 1], [1, s + 2]])).verdict
'yes'
>>> llewellyn(sp.Matrix([[9/(s + 3), -1/(s + 1)], [-1/(s + 1), 1/(s + 3)]])).verdict
'yes'
"""

from __future__ import annotations

import itertools
import math
from fractions import Fraction
from typing import Any, Callable, Sequence

import mpmath
import numpy as np
import sympy as sp

from .minimise import golden, local_minima
from .polys import RationalFunction, mpf_of, to_fraction
from .result import NO, UNCERTAIN, YES, OracleResult, combine

__all__ = ["S", "RationalMatrix", "positive_real_matrix", "llewellyn", "halfline_nonnegative", "psd_exact"]

#: The oracle's own Laplace variable (a plain SymPy symbol).
S = sp.Symbol("s")

DPS = 60
AXIS = 1e-40
OFFSET = 1e-15


class RationalMatrix:
    """A matrix of exact :class:`RationalFunction` entries, evaluated on the imaginary axis."""

    def __init__(self, Z: Any, s: sp.Symbol = S):
        if isinstance(Z, RationalMatrix):
            self.entries = Z.entries
        else:
            Z = sp.Matrix(Z)
            self.entries = [[RationalFunction.from_expr(Z[i, j], s) for j in range(Z.cols)] for i in range(Z.rows)]
        self.n = len(self.entries)
        self._poles: list | None = None

    def __getitem__(self, ij: tuple[int, int]) -> RationalFunction:
        return self.entries[ij[0]][ij[1]]

    def items(self):
        for i in range(self.n):
            for j in range(self.n):
                yield (i, j), self.entries[i][j]

    def poles(self) -> list[tuple[tuple[int, int], Any, int]]:
        if self._poles is None:
            self._poles = [(ij, r, m) for ij, f in self.items() for r, m in f.poles(DPS)]
        return self._poles

    def axis_frequencies(self) -> list[Any]:
        """Distinct ``w0 >= 0`` of axis poles ``j w0`` (mpf)."""
        out: list[Any] = []
        for _, r, _ in self.poles():
            if abs(r.real) <= AXIS * max(1, abs(r)) and r.imag >= -AXIS:
                w = abs(r.imag)
                if all(abs(w - v) > 1e-30 * max(1, w) for v in out):
                    out.append(w)
        return out

    def features(self) -> list[float]:
        """Moduli of all finite poles and zeros of the entries."""
        out = [float(abs(r)) for _, r, _ in self.poles()]
        for _, f in self.items():
            if not f.is_zero and len(f.num) > 1:
                out += [float(abs(r)) for r in np.roots([float(c) for c in f.num])]
        return [v for v in out if v > 0 and math.isfinite(v)]

    def np_at(self, w: np.ndarray) -> np.ndarray:
        out = np.empty((len(w), self.n, self.n), dtype=complex)
        for (i, j), f in self.items():
            out[:, i, j] = f.np(1j * w)
        return out

    def c_at(self, w: float) -> np.ndarray:
        out = np.empty((self.n, self.n), dtype=complex)
        x = 1j * w
        for (i, j), f in self.items():
            out[i, j] = f.c(x)
        return out

    def mp_at(self, w: Any) -> mpmath.matrix:
        M = mpmath.matrix(self.n, self.n)
        for (i, j), f in self.items():
            M[i, j] = f.mp(mpmath.mpc(0, w))
        return M


def psd_exact(M: Sequence[Sequence[Any]]) -> tuple[bool, Any]:
    """Exact PSD test of a rational symmetric matrix (every principal minor ``>= 0``)."""
    m = len(M)
    A = sp.Matrix(m, m, lambda i, j: sp.Rational(to_fraction(M[i][j]).numerator, to_fraction(M[i][j]).denominator))
    for k in range(1, m + 1):
        for rows in itertools.combinations(range(m), k):
            minor = A.extract(list(rows), list(rows)).det(method="bareiss")
            if minor < 0:
                return False, (rows, minor)
    return True, None


# ---------------------------------------------------------------------------------------------
# f(w) >= 0 on [0, oo)
# ---------------------------------------------------------------------------------------------


def halfline_nonnegative(
    name: str,
    screen: Callable[[np.ndarray], tuple[np.ndarray, np.ndarray]],
    mid: Callable[[float], float],
    final: Callable[[Any], tuple[Any, Any]],
    features: Sequence[float],
    axis: Sequence[Any],
    damped: Sequence[Any] = (),
) -> OracleResult:
    """Decide ``f(w) >= 0`` for all ``w >= 0``.

    ``screen(w)`` gives double-precision values and magnitudes on an array (screening);
    ``mid(w)`` an accurate-to-double value (refinement); ``final(w)`` a high-precision value and
    its absolute noise. ``axis``: frequencies of axis poles (evaluated as the mean of both sides
    and screened with ``mid``); ``damped``: poles near the axis to cluster grid points at.
    """
    lo = min([-8.0] + [math.floor(math.log10(v)) - 3 for v in features])
    hi = max([8.0] + [math.ceil(math.log10(v)) + 3 for v in features])
    u = set(np.linspace(lo, hi, int(round((hi - lo) * 40)) + 1).tolist())
    for w0 in axis:
        w0 = float(w0)
        if w0 > 0:
            u.update(math.log10(w0 * (1 + d)) for d in (-1e-3, -1e-6, 0, 1e-6, 1e-3))
    for p in damped:
        w0, sigma = abs(float(p.imag)), abs(float(p.real))
        if w0 > 0 and sigma < 0.05 * w0:
            u.update(math.log10(w0 + k * sigma) for k in (-8, -4, -2, -1, -0.5, 0, 0.5, 1, 2, 4, 8) if w0 + k * sigma > 0)
    u = np.array(sorted(u))
    w = 10.0 ** u
    values, norms = screen(w)
    near = ~np.isfinite(values)
    for w0 in axis:
        near |= _near(w, float(w0))
    for i in np.nonzero(near)[0]:
        values[i] = mid(float(w[i]))
    finite = np.isfinite(norms) & ~near  # near axis poles the double-precision magnitudes are garbage
    S = float(np.max(norms[finite])) if finite.any() else 1.0
    beta = 1e-13 * S
    candidates = [i for i in local_minima(values, keep=8) if 0 < i < len(u) - 1]
    points = []  # [w, value, band applied for "yes", grid index or None]
    for i in candidates:
        a, b = float(u[i - 1]), float(u[i + 1])
        x, _ = golden(lambda t: mid(10.0**t), a, b, 1e-10 * (b - a))
        points.append([10.0**x, None, beta, i])
    ends = [0.0] + [10.0**-k for k in (9, 10, 11, 12, 14, 16, 20, 25, 30)] + [10.0**k for k in (9, 10, 11, 12, 14, 16, 20, 25, 30, 40)]
    points += [[wi, None, None, None] for wi in ends]
    for p in points:
        value, noise = final(p[0])
        nu = max(noise, 1e-30 * S)
        if value < -nu:
            return OracleResult(NO, f"{name} = {float(value):.6g} < 0 at w = {p[0]:.12g}", margin=float(value), band=nu,
                                where={"omega": p[0]})
        p[1] = value
        if p[2] is None:
            p[2] = -nu  # the ends only ever say "no"
    # Small interior minima (<= beta) are judged at full precision: walk downhill on the grid with
    # 60-digit values (double-precision noise makes spurious minima where f is tiny but its terms
    # are not); a walk that ends at a grid end is covered by the end samples; a true interior
    # minimum is located by golden section at 60 digits and needs > 1e-30 S.
    cache: dict[int, Any] = {}

    def exact_at(i: int) -> Any:
        if i not in cache:
            cache[i] = final(float(w[i]))[0]
        return cache[i]

    budget = 400
    refined: dict[int, tuple] = {}
    for p in sorted((p for p in points if p[3] is not None and p[1] <= beta), key=lambda p: p[1]):
        i = p[3]
        # a plateau (an eigen-direction along which M is constant, common with rank-deficient
        # coefficient matrices): flat to 60 digits on both sides -> judged against 1e-25 S
        h = 1e-4 * (u[i + 1] - u[i - 1])
        x = math.log10(p[0])
        sides = [final(10.0 ** (x + d))[0] for d in (-h, h)]
        if max(abs(v - p[1]) for v in sides) <= 1e-25 * S:
            p[2] = 1e-25 * S
            continue
        if len(refined) >= 2:
            continue  # the rest stay judged against beta (at worst: uncertain)
        while 0 < i < len(u) - 1 and budget > 0:
            left, here, right = exact_at(i - 1), exact_at(i), exact_at(i + 1)
            budget -= 1
            if here <= left and here <= right:
                break
            i = i - 1 if left < right else i + 1
        if i in (0, len(u) - 1):
            value = exact_at(i)
            p[1], p[2], p[3] = value, -max(final(float(w[i]))[1], 1e-30 * S), None
            p[0] = float(w[i])
            if value < p[2]:
                return OracleResult(NO, f"{name} = {float(value):.6g} < 0 at w = {p[0]:.12g}", margin=float(value),
                                    band=-p[2], where={"omega": p[0]})
            continue
        if budget <= 0:
            break
        if i not in refined:
            a, b = float(u[i - 1]), float(u[i + 1])
            with mpmath.workdps(DPS):
                x, value = golden(lambda t: final(mpmath.power(10, t))[0], mpmath.mpf(a), mpmath.mpf(b),
                                  mpmath.mpf(10) ** -12 * (b - a))
            refined[i] = (float(mpmath.power(10, x)), value)
        wi, value = refined[i]
        nu = max(final(wi)[1], 1e-30 * S)
        if value < -nu:
            return OracleResult(NO, f"{name} = {float(value):.6g} < 0 at w = {wi:.12g}", margin=float(value), band=nu,
                                where={"omega": wi})
        p[0], p[1], p[2] = wi, value, 1e-20 * S
    blocked = [p for p in points if p[3] is not None and p[1] <= p[2]]
    if blocked:
        wi, value, band, _ = min(blocked, key=lambda p: p[1])
        return OracleResult(UNCERTAIN, f"min {name} = {float(value):.3g} inside the band", margin=float(value),
                            band=band, where={"omega": wi})
    wi, value, band, _ = min(points, key=lambda p: p[1])
    if value < 0:
        # negative, but inside the noise of an end sample (|terms| huge at w -> oo): never a "yes"
        return OracleResult(UNCERTAIN, f"min {name} = {float(value):.3g} < 0 at w = {wi:.6g}, inside the noise band",
                            margin=float(value), band=abs(band), where={"omega": wi})
    return OracleResult(YES, f"min {name} = {float(value):.6g} at w = {wi:.6g}", margin=float(value),
                        band=max(band, 0.0), where={"omega": wi})


def _near(w: Any, w0: float) -> Any:
    """Within relative 1e-4 of an axis pole (or w <= 1e-6 for a pole at 0): double precision
    loses ~eps/distance of the polar parts there."""
    return abs(w - w0) <= (1e-4 * w0 if w0 > 0 else 1e-6)


def _sides(w: Any, axis: Sequence[Any]) -> list[Any]:
    """``[w]``, or the two points at relative distance 1e-15 on both sides of an axis pole."""
    for w0 in axis:
        delta = OFFSET * max(w0, 1)
        if abs(w - w0) < delta:
            return [mpmath.mpf(delta)] if w0 == 0 else [w0 - delta, w0 + delta]
    return [w]


def _mean_sides(func: Callable[[Any], Any], w: Any, axis: Sequence[Any]) -> Any:
    """``func(w)``; at an axis pole the mean of both sides (an even function at w0 = 0),
    evaluated with 35 more digits (``s - j w0`` and the polar part cost 15 digits each)."""
    points = _sides(w, axis)
    if len(points) == 1 and points[0] is w:
        return func(w)
    with mpmath.workdps(mpmath.mp.dps + 35):
        values = [func(x) for x in points]
        out = values[0] if len(values) == 1 else (values[0] + values[1]) / 2
    return out * 1


# ---------------------------------------------------------------------------------------------
# positive realness of Z(s)
# ---------------------------------------------------------------------------------------------


def _pole_conditions(Zm: RationalMatrix) -> tuple[OracleResult, OracleResult]:
    with mpmath.workdps(DPS):
        for ij, f in Zm.items():
            if f.relative_degree < -1:
                return (OracleResult(NO, f"entry {ij} has a pole of order {-f.relative_degree} at infinity",
                                     margin=-math.inf, where={"entry": ij, "pole": "oo"}), None)
        for ij, r, m in Zm.poles():
            if r.real > AXIS * max(1, abs(r)):
                return (OracleResult(NO, f"entry {ij} has a pole at s ~ {complex(r):.6g} in Re s > 0",
                                     margin=-float(r.real), band=AXIS, where={"entry": ij, "pole": complex(r)}), None)
            if abs(r.real) <= AXIS * max(1, abs(r)) and m > 1:
                return (OracleResult(NO, f"entry {ij} has an axis pole s ~ {complex(r):.6g} of order {m}",
                                     margin=-float(m - 1), where={"entry": ij, "pole": complex(r)}), None)
        poles = OracleResult(YES, "no poles in Re s > 0; axis poles simple")
        # residue matrices
        n = Zm.n
        for w0 in Zm.axis_frequencies():
            p = mpmath.mpc(0, w0)
            R = mpmath.matrix(n, n)
            for (i, j), f in Zm.items():
                for r, _ in f.poles(DPS):
                    if abs(r - p) <= 1e-30 * max(1, abs(p)):
                        R[i, j] = f.residue(r)
            size = mpmath.mnorm(R, 1)
            asym = mpmath.mnorm(R - R.H, 1)
            where = {"pole": complex(p)}
            if asym > 1e-20 * size:
                return poles, OracleResult(NO, f"residue matrix at s ~ {complex(p):.6g} is not Hermitian",
                                           margin=-float(asym), where=where)
            if asym > 1e-30 * size:
                return poles, OracleResult(UNCERTAIN, f"residue matrix at s ~ {complex(p):.6g} nearly Hermitian", where=where)
            ev = mpmath.eighe((R + R.H) / 2, eigvals_only=True)
            low = min(e.real for e in ev)
            if low < -1e-30 * size:
                return poles, OracleResult(NO, f"residue matrix at s ~ {complex(p):.6g} has eigenvalue {float(low):.6g} < 0",
                                           margin=float(low), band=float(1e-30 * size), where=where)
        # infinity
        L = [[Fraction(0)] * n for _ in range(n)]
        improper = False
        for (i, j), f in Zm.items():
            if f.relative_degree == -1:
                improper = True
                L[i][j] = f.num[0] / f.den[0]
        if improper:
            if any(L[i][j] != L[j][i] for i in range(n) for j in range(n)):
                return poles, OracleResult(NO, "coefficient of s at infinity is not symmetric", where={"pole": "oo"})
            ok, bad = psd_exact(L)
            if not ok:
                return poles, OracleResult(NO, f"coefficient of s at infinity is not PSD (minor {bad[0]} = {bad[1]})",
                                           margin=float(bad[1]), where={"pole": "oo"})
    return poles, OracleResult(YES, "axis residue matrices Hermitian PSD")


def positive_real_matrix(Z: Any, s: sp.Symbol = S) -> OracleResult:
    """Definition 3 (3-DOF bilateral paper) for a real-rational matrix; see the module docstring."""
    Zm = Z if isinstance(Z, RationalMatrix) else RationalMatrix(Z, s)
    poles, residues = _pole_conditions(Zm)
    if poles.verdict == NO:
        return combine([("poles", poles)])
    if residues.verdict == NO:
        return combine([("poles", poles), ("residues", residues)])
    hermitian = _exact_ends(Zm) or _lossless(Zm) or _hermitian_condition(Zm)
    return combine([("poles", poles), ("residues", residues), ("Z + Z^H >= 0", hermitian)])


def _paraconjugate_sum_is_zero(f: RationalFunction, g: RationalFunction) -> bool:
    """``f(s) + g(-s) == 0`` identically (exact)."""
    x = sp.Symbol("x")
    return sp.cancel(f.expr(x) + g.expr(x).subs(x, -x)) == 0


def _lossless(Zm: RationalMatrix) -> OracleResult | None:
    """``Z(s) + Z(-s)^T = 0`` identically: the Hermitian part vanishes on the axis (lossless)."""
    n = Zm.n
    if all(_paraconjugate_sum_is_zero(Zm[i, j], Zm[j, i]) for i in range(n) for j in range(i, n)):
        return OracleResult(YES, "Z(s) + Z(-s)^T = 0 identically (lossless): Z(jw) + Z(jw)^H = 0", margin=0.0, band=0.0)
    return None


def _value_at_zero(f: RationalFunction) -> Fraction | None:
    """``f(0)`` exactly (None at a pole)."""
    return None if f.den[-1] == 0 else f.num[-1] / f.den[-1]


def _value_at_infinity(f: RationalFunction) -> Fraction:
    """The constant term of ``f`` at infinity (``f = L s + D0 + O(1/s)``), exactly."""
    if f.is_zero or f.relative_degree > 0:
        return Fraction(0)
    return f.polynomial_part()[-1]


def _exact_ends(Zm: RationalMatrix) -> OracleResult | None:
    """``Z + Z^H`` at ``w = 0`` (no pole there) and its limit at infinity are rational matrices
    ``Z(0) + Z(0)^T`` and ``D0 + D0^T``: decided exactly (principal minors). Returns a ``no``
    if one is not PSD, else None."""
    n = Zm.n
    ends = [("w = 0", 0.0, [[_value_at_zero(Zm[i, j]) for j in range(n)] for i in range(n)]),
            ("w -> oo", math.inf, [[_value_at_infinity(Zm[i, j]) for j in range(n)] for i in range(n)])]
    for label, w, D in ends:
        if any(v is None for row in D for v in row):
            continue
        M = [[D[i][j] + D[j][i] for j in range(n)] for i in range(n)]
        ok, bad = psd_exact(M)
        if not ok:
            with mpmath.workdps(120):
                A = mpmath.matrix([[mpf_of(v) for v in row] for row in M])
                low = float(min(mpmath.eigsy(A, eigvals_only=True)))
            return OracleResult(NO, f"Z + Z^H at {label} is not PSD (exact: minor {bad[0]} = {bad[1]})",
                                margin=low, band=0.0, where={"omega": w})
    return None


def _hermitian_condition(Zm: RationalMatrix) -> OracleResult:
    n = Zm.n
    with mpmath.workdps(DPS):
        axis = Zm.axis_frequencies()
        damped = [r for _, r, _ in Zm.poles()]
    axis_f = [float(w) for w in axis]

    def screen(w):
        with np.errstate(all="ignore"):
            Zw = Zm.np_at(w)
            M = Zw + np.conj(np.transpose(Zw, (0, 2, 1)))
            ok = np.all(np.isfinite(M), axis=(1, 2))
            values = np.full(len(w), np.nan)
            norms = np.full(len(w), np.nan)
            if ok.any():
                values[ok] = np.linalg.eigvalsh(M[ok])[:, 0]
                norms[ok] = np.abs(M[ok]).max(axis=(1, 2))
        return values, norms

    def mp_hermitian(w):
        Zw = Zm.mp_at(w)
        return Zw + Zw.H

    def to_numpy(M):
        A = np.array([[complex(M[i, j]) for j in range(n)] for i in range(n)])
        return (A + A.conj().T) / 2

    def mid(w):
        near = any(_near(w, w0) for w0 in axis_f)
        if not near:
            Zw = Zm.c_at(w)
            M = Zw + Zw.conj().T
            if np.all(np.isfinite(M)):
                return float(np.linalg.eigvalsh(M)[0])
        with mpmath.workdps(30):
            A = to_numpy(_mean_sides(mp_hermitian, mpmath.mpf(w), axis))
        return float(np.linalg.eigvalsh(A)[0])

    def final(w):
        with mpmath.workdps(DPS):
            points = _sides(mpmath.mpf(w), axis)
            with mpmath.workdps(DPS + (35 if len(points) == 2 or points[0] != w else 0)):
                sides = [Zm.mp_at(x) for x in points]
                Ms = [Zx + Zx.H for Zx in sides]
                M = (Ms[0] if len(Ms) == 1 else (Ms[0] + Ms[1]) / 2) * 1
            A = to_numpy(M)
            size_m = float(np.abs(A).max())
            low = float(np.linalg.eigvalsh(A)[0])
            if low > 1e-12 * size_m:
                # M is formed at 60 digits; its double-precision eigenvalues are within ~1e-15 |M|
                return low, 1e-14 * size_m
            ev = mpmath.eighe((M + M.H) / 2, eigvals_only=True)
            size = max(mpmath.mnorm(Zx, 1) for Zx in sides)
            return min(e.real for e in ev), float(mpmath.mpf(10) ** -(DPS - 10) * (size + mpmath.mnorm(M, 1)))

    return halfline_nonnegative("lambda_min(Z + Z^H)", screen, mid, final, Zm.features(), axis, damped)


# ---------------------------------------------------------------------------------------------
# Llewellyn
# ---------------------------------------------------------------------------------------------


def llewellyn(Z: Any, s: sp.Symbol = S) -> OracleResult:
    """Llewellyn's absolute-stability criterion for a 2-port (impedance form)."""
    Zs = sp.Matrix(Z)
    if Zs.shape != (2, 2):
        raise ValueError("Llewellyn's criterion is for 2x2 impedance matrices")
    Zm = RationalMatrix(Zs, s)
    with mpmath.workdps(DPS):
        for ij, r, _ in Zm.poles():
            if r.real > AXIS * max(1, abs(r)):
                return combine([("open-circuit stability", OracleResult(
                    NO, f"entry {ij} has a pole at s ~ {complex(r):.6g} in Re s > 0", margin=-float(r.real),
                    where={"entry": ij, "pole": complex(r)}))])
        parts = [("open-circuit stability", OracleResult(YES, "no entry has a pole in Re s > 0"))]
        for k in (0, 1):
            f = Zm[k, k]
            diag = RationalMatrix([[f.expr(S)]], S)
            poles, residues = _pole_conditions(diag)
            part = poles if poles.verdict == NO else residues
            parts.append((f"z{k + 1}{k + 1} axis poles", part))
            if part.verdict == NO:
                return combine(parts)
    z11, z22 = Zm[0, 0], Zm[1, 1]
    P = RationalFunction.from_expr(Zs[0, 1] * Zs[1, 0], s)
    axis = sorted(set(Zm.axis_frequencies()) | set(RationalMatrix([[P.expr(S)]], S).axis_frequencies()))
    damped = [r for _, r, _ in Zm.poles()]
    features = Zm.features()

    axis_f = [float(w) for w in axis]

    def scalar(func_np, func_c, func_mp, name):
        def screen(w):
            with np.errstate(all="ignore"):
                v, mag = func_np(w)
            return v, mag

        def mid(w):
            near = any(_near(w, w0) for w0 in axis_f)
            if not near:
                value = func_c(w)
                if math.isfinite(value):
                    return value
            with mpmath.workdps(30):
                return float(_mean_sides(lambda x: func_mp(x)[0], mpmath.mpf(w), axis))

        def final(w):
            with mpmath.workdps(DPS):
                value = _mean_sides(lambda x: func_mp(x)[0], mpmath.mpf(w), axis)
                mag = max(func_mp(x)[1] for x in _sides(mpmath.mpf(w), axis))
                return value, float(mpmath.mpf(10) ** -(DPS - 15) * (mag + 1))

        return halfline_nonnegative(name, screen, mid, final, features, axis, damped)

    def re_np(f):
        return lambda w: (f.np(1j * w).real, np.abs(f.np(1j * w).real))

    def re_c(f):
        return lambda w: f.c(1j * w).real

    def re_mp(f):
        return lambda w: (f.mp(mpmath.mpc(0, w)).real, abs(f.mp(mpmath.mpc(0, w))))

    # exact values at w = 0 (no pole there) and the limits at infinity
    for label, at in (("w = 0", _value_at_zero), ("w -> oo", _value_at_infinity)):
        if label == "w -> oo" and P.relative_degree < 0:
            continue  # |z12 z21| grows without bound: the samples decide
        a, b, p = at(z11), at(z22), at(P)
        if None in (a, b, p):
            continue
        for name, value in (("Re z11 >= 0", a), ("Re z22 >= 0", b),
                            ("2 Re z11 Re z22 - Re z12z21 - |z12z21| >= 0", 2 * a * b - p - abs(p))):
            if value < 0:
                parts.append((name, OracleResult(NO, f"{name.split(' >=')[0]} = {float(value):.6g} < 0 at {label} (exact)",
                                                 margin=float(value), band=0.0, where={"omega": 0.0 if at is _value_at_zero else math.inf})))
                return combine(parts)
    for k, f in ((1, z11), (2, z22)):
        if _paraconjugate_sum_is_zero(f, f):
            part = OracleResult(YES, f"Re z{k}{k} = 0 identically (z{k}{k}(s) + z{k}{k}(-s) = 0)", margin=0.0, band=0.0)
        else:
            part = scalar(re_np(f), re_c(f), re_mp(f), f"Re z{k}{k}")
        parts.append((f"Re z{k}{k} >= 0", part))

    def g_np(w):
        a, b, p = z11.np(1j * w).real, z22.np(1j * w).real, P.np(1j * w)
        return 2 * a * b - p.real - np.abs(p), 2 * np.abs(a * b) + 2 * np.abs(p)

    def g_c(w):
        a, b, p = z11.c(1j * w).real, z22.c(1j * w).real, P.c(1j * w)
        return 2 * a * b - p.real - abs(p)

    def g_mp(w):
        x = mpmath.mpc(0, w)
        a, b, p = z11.mp(x), z22.mp(x), P.mp(x)
        return 2 * a.real * b.real - p.real - abs(p), 2 * abs(a) * abs(b) + 2 * abs(p)

    parts.append(("2 Re z11 Re z22 - Re z12z21 - |z12z21| >= 0",
                  scalar(g_np, g_c, g_mp, "2 Re z11 Re z22 - Re(z12 z21) - |z12 z21|")))
    return combine(parts)
