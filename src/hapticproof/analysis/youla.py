r"""Youla's symmetrization of an n-port: the conditions A and B, and the reciprocal ``Z'``.

Two impedance matrices with the same principal minors of all orders give the same
``det(Z + T)`` for every diagonal termination ``T`` (Youla 1960), hence the same absolute
stability; for grouped ports (a port is several DOFs, terminated by a full matrix) the
block-compatible minors must agree too. A reciprocal ``Z'`` with those minors reduces absolute
stability of ``Z`` to positive realness of ``Z'`` (Youla 1959; Theorem 9 of the 3-DOF bilateral
paper, with ``Z'`` of its eq. (14)).

* :func:`symmetrization_conditions` -- A (``z_ij z_jk z_ki = z_ji z_kj z_ik``) and B (symmetric
  port blocks) as exact equations in ``s`` and the parameters (symbolic entries allowed).
* :func:`symmetrize` -- ``Z' = D Z D^-1`` with ``D`` constant on every port block: one free sign
  per port (not per DOF), a reciprocal ``Z`` is its own symmetrization, and every principal and
  block-compatible minor is compared exactly.

>>> import sympy as sp
>>> symmetrize(sp.Matrix([[2, 4], [1, 3]])).zprime()
Matrix([
[2, 2],
[2, 3]])
"""

from __future__ import annotations

import itertools
import math
from collections.abc import Mapping, Sequence
from dataclasses import dataclass, field
from typing import Any

import flint
import sympy as sp

from hapticproof.exact.canonical import cancel as exact_cancel
from hapticproof.exact.canonical import canonical_fraction
from hapticproof.core.errors import InputFormatError
from hapticproof.core.evidence import Decision, Evidence, Method
from hapticproof.exact.rationalmatrix import RationalFunction, RationalMatrix
from hapticproof.exact.realroots import as_fmpq, to_rational
from hapticproof.core.symbols import s as S_SYM

__all__ = [
    "as_rational_matrix",
    "port_blocks",
    "SymmetrizationCondition",
    "symmetrization_conditions",
    "Symmetrization",
    "symmetrize",
]

_ZERO_RF = RationalFunction(flint.fmpq_poly([]), flint.fmpq_poly([1]))


def as_rational_matrix(Z: Any, s: sp.Symbol = S_SYM) -> RationalMatrix:
    """Accept a :class:`RationalMatrix` or anything ``sympy.Matrix`` accepts (numbers only)."""
    if isinstance(Z, RationalMatrix):
        return Z
    return RationalMatrix.from_sympy(Z, s)


def port_blocks(n: int, ports: Sequence[int] | None) -> tuple[tuple[int, ...], ...]:
    """Index blocks of the ports: ``port_blocks(6, (3, 3)) == ((0, 1, 2), (3, 4, 5))``.

    >>> port_blocks(3, None)
    ((0,), (1,), (2,))
    """
    if ports is None:
        return tuple((i,) for i in range(n))
    if any(int(p) <= 0 for p in ports) or sum(ports) != n:
        raise InputFormatError(f"port sizes {tuple(ports)} do not add up to the matrix size {n}")
    out, start = [], 0
    for p in ports:
        out.append(tuple(range(start, start + int(p))))
        start += int(p)
    return tuple(out)


# ---------------------------------------------------------------------------------------------
# symmetrization conditions (symbolic, any n)
# ---------------------------------------------------------------------------------------------


@dataclass(frozen=True)
class SymmetrizationCondition:
    """One of Youla's symmetrization conditions as ``expr = 0`` for all ``s``.

    ``kind`` is ``'B'`` (``z_ij = z_ji`` inside a port block) or ``'A'`` (the triple products;
    ``reduced`` when a factor ``z_ij = z_ji`` known from B was cancelled, leaving
    ``z_jk z_ki - z_kj z_ik``). ``expr`` is the numerator polynomial in ``s`` and the parameters.
    """

    kind: str
    indices: tuple[int, ...]
    expr: sp.Expr
    reduced: bool = False

    def at_frequency(self, omega: sp.Symbol) -> sp.Expr:
        """The condition on the imaginary axis: ``expr`` with ``s = j omega``, expanded."""
        return sp.expand(self.expr.subs(S_SYM, sp.I * omega))

    def coefficients(self) -> list[sp.Expr]:
        """The equations in the parameters alone (coefficients of the powers of ``s``)."""
        return [c for c in sp.Poly(self.expr, S_SYM).all_coeffs() if c != 0]


def _num_den(expr: sp.Expr) -> tuple[sp.Expr, sp.Expr]:
    num, den = canonical_fraction(expr)
    return sp.expand(num), sp.expand(den)


def symmetrization_conditions(
    Z: Any, ports: Sequence[int] | None = None, reduce: bool = True, s: sp.Symbol = S_SYM
) -> list[SymmetrizationCondition]:
    """Youla's symmetrization conditions of an n-port as exact equations (symbolic entries allowed).

    A: ``z_ij z_jk z_ki = z_ji z_kj z_ik`` for all triples; B: every diagonal port block is
    symmetric. With ``reduce``, a triple containing a pair that B makes symmetric
    (``z_ij = z_ji``, assumed nonzero) is divided by it. Conditions that hold identically are
    omitted. The case study of the 3-DOF bilateral paper gives 6 B-conditions (26)-(31) and
    18 reduced A-conditions, of which (32)-(37) are a spanning subset.

    >>> from hapticproof.core.symbols import s
    >>> a, b = sp.symbols('a b')
    >>> [(c.kind, c.indices, c.expr) for c in symmetrization_conditions(sp.Matrix([[1, a], [b, 1]]), ports=(2,))]
    [('B', (0, 1), -a + b)]
    """
    M = sp.Matrix(Z)
    n = M.rows
    blocks = port_blocks(n, ports)
    nd = {(i, j): _num_den(M[i, j]) for i in range(n) for j in range(n)}
    out: list[SymmetrizationCondition] = []
    symmetric_pairs = set()
    for blk in blocks:
        for i, j in itertools.combinations(blk, 2):
            (ni, di), (nj, dj) = nd[(i, j)], nd[(j, i)]
            expr = sp.expand(nj * di - ni * dj)
            symmetric_pairs.add((i, j))
            if expr != 0:
                out.append(SymmetrizationCondition("B", (i, j), expr))
    for i, j, k in itertools.combinations(range(n), 3):
        pairs = [(i, j), (j, k), (i, k)]
        # A: z_ij z_jk z_ki - z_ji z_kj z_ik ; reduce by a B-symmetric pair
        cancel = next((p for p in pairs if p in symmetric_pairs and M[p[0], p[1]] != 0), None) if reduce else None
        if cancel is None:
            fwd = [(i, j), (j, k), (k, i)]
            bwd = [(j, i), (k, j), (i, k)]
        else:
            a, b = cancel
            c = ({i, j, k} - {a, b}).pop()
            # z_ab z_bc z_ca = z_ba z_cb z_ac  with z_ab = z_ba  ->  z_bc z_ca = z_cb z_ac
            fwd = [(b, c), (c, a)]
            bwd = [(c, b), (a, c)]
        lhs_n, lhs_d = sp.Integer(1), sp.Integer(1)
        rhs_n, rhs_d = sp.Integer(1), sp.Integer(1)
        for p in fwd:
            lhs_n, lhs_d = lhs_n * nd[p][0], lhs_d * nd[p][1]
        for p in bwd:
            rhs_n, rhs_d = rhs_n * nd[p][0], rhs_d * nd[p][1]
        expr = sp.expand(lhs_n * rhs_d - rhs_n * lhs_d)
        if expr != 0:
            out.append(SymmetrizationCondition("A", (i, j, k), expr, reduced=cancel is not None))
    return out


# ---------------------------------------------------------------------------------------------
# Youla symmetrization (numeric, exact)
# ---------------------------------------------------------------------------------------------


def _square_decomposition(p: RationalFunction) -> tuple[flint.fmpq, RationalFunction] | None:
    """``p = c q**2`` with ``c`` rational and ``q`` rational (numerator and denominator with
    positive leading coefficients), or None when the square-free part is not constant."""
    def split(poly: flint.fmpq_poly) -> tuple[flint.fmpq, flint.fmpq_poly] | None:
        content, factors = poly.numer().factor_squarefree()
        root = flint.fmpq_poly([1])
        for f, mult in factors:
            if mult % 2:
                return None
            root *= flint.fmpq_poly(f) ** (mult // 2)
        rest = poly / (root * root)
        if rest.degree() != 0:  # pragma: no cover - guaranteed by the factorization
            return None
        c = rest.coeffs()[0]
        if root.coeffs()[-1] < 0:
            root = -root
        return c, root

    top = split(p.num)
    bottom = split(p.den)
    if top is None or bottom is None:
        return None
    (cn, qn), (cd, qd) = top, bottom
    return cn / cd, RationalFunction.make(qn, qd)


def _rational_sqrt(q: flint.fmpq) -> flint.fmpq | None:
    if q < 0:
        return None
    num, den = int(q.p), int(q.q)
    rn, rd = math.isqrt(num), math.isqrt(den)
    if rn * rn == num and rd * rd == den:
        return flint.fmpq(rn, rd)
    return None




def _count_block_pairs(blocks: Sequence[Sequence[int]]) -> int:
    total = 1
    for blk in blocks:
        total *= sum(math.comb(len(blk), k) ** 2 for k in range(len(blk) + 1))
    return total - 1


def _block_pairs(blocks: Sequence[Sequence[int]]):
    """Row/column index sets with the same number of indices in every block (nonempty)."""
    per_block = []
    for blk in blocks:
        options = []
        for k in range(len(blk) + 1):
            subsets = list(itertools.combinations(blk, k))
            options.append([(a, b) for a in subsets for b in subsets])
        per_block.append([pair for opt in options for pair in opt])
    for combo in itertools.product(*per_block):
        rows = tuple(i for a, _ in combo for i in a)
        cols = tuple(j for _, b in combo for j in b)
        if rows:
            yield rows, cols


def _verify_minors(Zr: RationalMatrix, rhat: RationalMatrix, u: Sequence[flint.fmpq], blocks) -> tuple[str, Evidence] | None:
    """Check det Rhat[I, J] * j^(#neg I + #neg J) == det Z[I, J] * sqrt(prod_I |u| prod_J |u|)."""
    scalar = all(len(b) == 1 for b in blocks)
    pairs = ((S, S) for k in range(1, len(u) + 1) for S in itertools.combinations(range(len(u)), k)) if scalar else _block_pairs(blocks)
    for rows, cols in pairs:
        left = rhat.minor(rows, cols)
        right = Zr.minor(rows, cols)
        negs = sum(u[i] < 0 for i in rows) + sum(u[j] < 0 for j in cols)
        weight = flint.fmpq(1)
        for i in rows:
            weight *= abs(u[i])
        for j in cols:
            weight *= abs(u[j])
        root = _rational_sqrt(weight)
        if negs % 2 or root is None:
            ok = left.is_zero() and right.is_zero()
        else:
            sign = -1 if (negs // 2) % 2 else 1
            ok = left.scale(sign) == right.scale(root)
        if not ok:
            what = "principal minor" if rows == cols else "block-compatible minor"
            return (f"the {what} on rows {list(rows)}, columns {list(cols)} of Z' differs from that of Z",
                    Evidence(Method.CANONICAL_FORM, witness={"rows": list(rows), "cols": list(cols)},
                             facts={"Z": right.expr()}))
    return None




@dataclass(frozen=True)
class Symmetrization:
    """Youla's reciprocal equivalent ``Z'`` of an n-port, or why there is none.

    When ``symmetrizable`` is PROVED, ``Z' = D Z D^-1`` (up to entries forced to zero by a
    unilateral coupling) with ``D = diag(delta_k I)`` constant on every port block and
    ``delta_k**2 = C_k Q_k(s)**2`` (``C_k`` rational, ``Q_k`` rational in ``s``; ``block_scales``).
    Inside a block ``Z'`` equals ``Z``; across blocks ``Z'_ij = (delta_k/delta_l) z_ij``, whose
    square is ``z_ij z_ji``. ``scales`` are the rationals ``u_i = C_k`` of each index: the
    congruent matrix ``K = E Z' E``, ``E = diag(sqrt|u_i|)``, is ``J Rhat J`` with a *rational*
    symmetric ``Rhat`` (``J_ii = j`` where ``u_i < 0``): PR of ``Z'`` is decided on ``Rhat``.
    ``gamma``, ``c``, ``q`` describe ``Z'_ij = gamma_ij sqrt(c_ij) q_ij(s)`` (eq. (14)).
    ``evidence`` records the exact check that every principal minor of ``Z'`` equals the one of
    ``Z`` (and, for grouped ports, every block-compatible minor).
    """

    symmetrizable: Decision
    reason: str
    evidence: Evidence
    gamma: Mapping[tuple[int, int], int] = field(default_factory=dict)
    c: Mapping[tuple[int, int], Any] = field(default_factory=dict)
    q: Mapping[tuple[int, int], RationalFunction] = field(default_factory=dict)
    scales: tuple[Any, ...] = ()
    rhat: RationalMatrix | None = None
    diagonal: tuple[RationalFunction, ...] = ()
    blocks: tuple[tuple[int, ...], ...] = ()
    block_scales: tuple[tuple[Any, RationalFunction], ...] = ()
    original: RationalMatrix | None = None

    @property
    def signs(self) -> tuple[int, ...]:
        return tuple(1 if u > 0 else -1 for u in self.scales)

    def similarity_at(self, point: complex) -> Any:
        """The diagonal of ``D(s0)`` (``Z' = D Z D^-1``) in floating point, one value per index, when
        ``Z'`` is real (every ``C_k > 0``); else None. For the termination search."""
        import numpy as np

        if self.symmetrizable != Decision.PROVED or any(C <= 0 for C, _ in self.block_scales):
            return None
        values = []
        for C, Q in self.block_scales:
            num = np.polyval([float(a) for a in reversed(Q.num.coeffs())] or [0.0], point)
            den = np.polyval([float(a) for a in reversed(Q.den.coeffs())], point)
            values.append(math.sqrt(float(C)) * num / den)
        block_of = {i: k for k, blk in enumerate(self.blocks) for i in blk}
        return np.array([values[block_of[i]] for i in range(len(block_of))], dtype=complex)

    def zprime(self, s: sp.Symbol = S_SYM) -> sp.Matrix:
        """``Z'`` as an exact SymPy matrix (square roots of rational constants kept exact)."""
        if self.symmetrizable != Decision.PROVED:
            raise ValueError("no symmetrization")
        Z = self.original
        n = Z.shape[0]
        block_of = {i: k for k, blk in enumerate(self.blocks) for i in blk}
        delta = [sp.sqrt(to_rational(as_fmpq(C))) * Q.expr(s) for C, Q in self.block_scales]
        out = sp.zeros(n, n)
        for i in range(n):
            for j in range(n):
                k, l = block_of[i], block_of[j]
                if k == l:
                    out[i, j] = Z[i, j].expr(s)
                elif not (Z[i, j] * Z[j, i]).is_zero():
                    out[i, j] = exact_cancel(delta[k] / delta[l] * Z[i, j].expr(s))
        return out


def _not_symmetrizable(decision: Decision, reason: str, witness: Mapping[str, Any] | None = None,
                       facts: Mapping[str, Any] | None = None) -> Symmetrization:
    return Symmetrization(decision, reason, Evidence(Method.CANONICAL_FORM, witness=dict(witness) if witness else None,
                                                     facts=dict(facts or {})))


def symmetrize(Z: Any, ports: Sequence[int] | None = None) -> Symmetrization:
    """Construct Youla's reciprocal ``Z'`` (eq. (14) of the 3-DOF bilateral paper) exactly.

    The similarity must respect the port blocks: ``det(D Z D^-1 + T) = det(Z + T)`` for every
    block-diagonal termination ``T`` only when ``D`` is constant on each block (a diagonal ``D``
    with different entries in one block maps a passive ``T_k`` to ``D_k^-1 T_k D_k``, which need
    not be passive). So inside a block ``Z' = Z`` (B: symmetric blocks), and across the blocks
    ``k, l`` every coupled pair must have the same ratio ``z_ji/z_ij = (delta_k/delta_l)**2``.
    The free signs are one per block (a spanning forest of the block graph), not one per DOF;
    every other block pair closes a cycle whose ratios must multiply to 1 (Youla's cycle
    conditions; for triangles condition A). A reciprocal ``Z`` is its own symmetrization.
    Finally all principal (and block-compatible) minors of ``Z'`` and ``Z`` are compared.

    >>> from hapticproof.core.symbols import s
    >>> Y = symmetrize(sp.Matrix([[2, 4], [1, 3]]))           # z12 z21 = 4
    >>> Y.symmetrizable.value, Y.zprime()
    ('proved', Matrix([
    [2, 2],
    [2, 3]]))
    >>> Zg = sp.diag(sp.Matrix([[2, -1], [-1, 2]]), 2 * sp.eye(2))   # issue 10: reciprocal, grouped ports
    >>> symmetrize(Zg, (2, 2)).zprime() == Zg
    True
    """
    Zr = as_rational_matrix(Z)
    n = Zr.shape[0]
    blocks = port_blocks(n, ports)
    block_of = {i: k for k, blk in enumerate(blocks) for i in blk}
    K = len(blocks)
    for blk in blocks:
        for i, j in itertools.combinations(blk, 2):
            if Zr[i, j] != Zr[j, i]:
                return _not_symmetrizable(Decision.DISPROVED, f"condition B fails: z[{i + 1},{j + 1}] != z[{j + 1},{i + 1}] in a port block",
                                          {"pair": [i + 1, j + 1]})
    for i, j, k in itertools.combinations(range(n), 3):
        fwd = Zr[i, j] * Zr[j, k] * Zr[k, i]
        bwd = Zr[j, i] * Zr[k, j] * Zr[i, k]
        if fwd != bwd:
            return _not_symmetrizable(Decision.DISPROVED, f"condition A fails for (i, j, k) = ({i + 1}, {j + 1}, {k + 1})",
                                      {"triple": [i + 1, j + 1, k + 1]}, {"difference": (fwd - bwd).expr()})
    one = RationalFunction.constant(1)
    # the ratio z_ji/z_ij = (delta_k/delta_l)^2 of every coupled block pair k < l
    ratios: dict[tuple[int, int], tuple[RationalFunction, tuple[int, int]]] = {}
    for i, j in itertools.combinations(range(n), 2):
        k, l = block_of[i], block_of[j]
        if k == l or Zr[i, j].is_zero() or Zr[j, i].is_zero():
            continue
        ratio = Zr[j, i] / Zr[i, j]
        if (k, l) not in ratios:
            ratios[(k, l)] = (ratio, (i, j))
        elif ratios[(k, l)][0] != ratio:
            a, b = ratios[(k, l)][1]
            return _not_symmetrizable(
                Decision.DISPROVED,
                f"the coupling ratios z[{j + 1},{i + 1}]/z[{i + 1},{j + 1}] and z[{b + 1},{a + 1}]/z[{a + 1},{b + 1}] between "
                f"ports {k + 1} and {l + 1} differ: no similarity constant on the port blocks symmetrizes Z "
                "(the block-compatible 2x2 minors could not all agree)",
                {"pairs": [[i + 1, j + 1], [a + 1, b + 1]]}, {"ratios": [ratio.expr(), ratios[(k, l)][0].expr()]})
    split: dict[tuple[int, int], tuple[flint.fmpq, RationalFunction]] = {}
    for key, (ratio, (i, j)) in ratios.items():
        dec = _square_decomposition(ratio)
        if dec is None:
            return _not_symmetrizable(Decision.UNDECIDED,
                                      f"z[{j + 1},{i + 1}]/z[{i + 1},{j + 1}] is not a constant times a square: Z' is irrational",
                                      {"pair": [i + 1, j + 1]}, {"ratio": ratio.expr()})
        split[key] = dec
    # spanning forest of the block graph: delta_root^2 = 1, delta_l^2 = delta_k^2 / ratio_kl
    adjacency: dict[int, list[int]] = {k: [] for k in range(K)}
    for k, l in ratios:
        adjacency[k].append(l)
        adjacency[l].append(k)
    C: dict[int, flint.fmpq] = {}
    Q: dict[int, RationalFunction] = {}
    parent: dict[int, int | None] = {}
    depth: dict[int, int] = {}
    tree = set()
    for root in range(K):
        if root in C:
            continue
        C[root], Q[root], parent[root], depth[root] = flint.fmpq(1), one, None, 0
        queue = [root]
        while queue:
            a = queue.pop(0)
            for b in sorted(adjacency[a]):
                if b in C:
                    continue
                c_ab, q_ab = split[(min(a, b), max(a, b))]
                if a < b:        # ratio_ab = delta_a^2/delta_b^2
                    C[b], Q[b] = C[a] / c_ab, Q[a] / q_ab
                else:            # ratio_ba = delta_b^2/delta_a^2
                    C[b], Q[b] = C[a] * c_ab, Q[a] * q_ab
                parent[b], depth[b] = a, depth[a] + 1
                tree.add((min(a, b), max(a, b)))
                queue.append(b)

    def square(k: int) -> RationalFunction:
        return (Q[k] * Q[k]).scale(C[k])

    for (k, l) in sorted(set(ratios) - tree):
        if square(k) / square(l) != ratios[(k, l)][0]:
            cycle = _cycle_path(parent, depth, l, k) + [l]
            return _not_symmetrizable(
                Decision.DISPROVED,
                f"Youla's cycle condition fails on the cycle of ports {[c + 1 for c in cycle]}: the coupling ratios "
                "z_ji/z_ij do not multiply to 1 around it",
                {"cycle": [c + 1 for c in cycle]})
    rows = []
    for i in range(n):
        row = []
        for j in range(n):
            k, l = block_of[i], block_of[j]
            if k == l:
                row.append(Zr[i, j].scale(C[k]))
            elif Zr[i, j].is_zero() or Zr[j, i].is_zero():
                row.append(_ZERO_RF)
            else:
                value = (Q[k] / Q[l] * Zr[i, j]).scale(C[k])
                row.append(-value if C[k] * C[l] < 0 else value)
        rows.append(tuple(row))
    rhat = RationalMatrix(tuple(rows))
    if not rhat.is_symmetric():  # pragma: no cover - guaranteed by the ratio and cycle checks
        raise ArithmeticError("the Youla matrix is not symmetric")
    u = [C[block_of[i]] for i in range(n)]
    gamma, c_pair, q_pair = _eq14_signs(Zr, blocks, block_of, C, Q)
    result_kwargs = dict(gamma=gamma, c={key: to_rational(v) for key, v in c_pair.items()}, q=q_pair,
                         scales=tuple(to_rational(v) for v in u), rhat=rhat, diagonal=tuple(Zr[i, i] for i in range(n)),
                         blocks=blocks, block_scales=tuple((to_rational(C[k]), Q[k]) for k in range(K)), original=Zr)
    check = _verify_minors(Zr, rhat, u, blocks)
    if check is not None:
        return Symmetrization(Decision.DISPROVED, check[0], check[1], **result_kwargs)
    facts = {"principal_minors_checked": 2**n - 1, "block_scales": [[to_rational(C[k]), Q[k].expr()] for k in range(K)],
             "gamma": {f"{i + 1},{j + 1}": g for (i, j), g in sorted(gamma.items())}}
    grouped = any(len(b) > 1 for b in blocks)
    if grouped:
        facts["block_compatible_minors_checked"] = _count_block_pairs(blocks)
    what = "Z is reciprocal: Z' = Z" if Zr.is_symmetric() else "Z' = D Z D^-1 (D constant on the port blocks) is reciprocal"
    return Symmetrization(Decision.PROVED,
                          what + " and has the same principal minors as Z"
                          + (" (and the same block-compatible minors: det(Z + T) = det(Z' + T) for block terminations)"
                             if grouped else ""),
                          Evidence(Method.CANONICAL_FORM, facts=facts), **result_kwargs)


def _eq14_signs(Zr: RationalMatrix, blocks, block_of, C, Q) -> tuple[dict, dict, dict]:
    """The signs ``gamma_ij`` of eq. (14), ``Z'_ij = gamma_ij sqrt(c_ij) q_ij`` with
    ``z_ij z_ji = c_ij q_ij**2`` (``q_ij`` with positive leading coefficients)."""
    gamma, c_pair, q_pair = {}, {}, {}
    n = Zr.shape[0]
    for i, j in itertools.combinations(range(n), 2):
        product = Zr[i, j] * Zr[j, i]
        if product.is_zero():
            continue
        dec = _square_decomposition(product)
        if dec is None:  # pragma: no cover - the ratio decomposed, so does the product
            continue
        c_ij, q_ij = dec
        k, l = block_of[i], block_of[j]
        # Z'_ij / q_ij = (delta_k/delta_l) z_ij / q_ij: a constant lam times sqrt(C_k)/sqrt(C_l)
        lam = (Zr[i, j] / q_ij) if k == l else (Q[k] / Q[l] * Zr[i, j] / q_ij)
        value = to_rational(lam.num.coeffs()[0] / lam.den.coeffs()[0]) if lam.num.degree() == 0 else sp.nan
        if k != l:
            value = value * sp.sqrt(to_rational(C[k])) / sp.sqrt(to_rational(C[l]))
        sign = sp.nsimplify(sp.simplify(value / sp.sqrt(to_rational(c_ij))))
        gamma[(i, j)] = 1 if sign == 1 else -1
        c_pair[(i, j)], q_pair[(i, j)] = c_ij, q_ij
    return gamma, c_pair, q_pair


def _cycle_path(parent: Mapping[int, int | None], depth: Mapping[int, int], a: int, b: int) -> list[int]:
    """Tree path from ``a`` to ``b`` (list of vertices)."""
    left, right = [a], [b]
    while left[-1] != right[-1]:
        if depth[left[-1]] >= depth[right[-1]]:
            left.append(parent[left[-1]])
        else:
            right.append(parent[right[-1]])
    return left + right[-2::-1]
