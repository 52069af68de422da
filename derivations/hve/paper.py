r"""Miandashti & Tavakoli, "Stability of Sampled-Data, Delayed Haptic Interaction under Passive
or Active Operator" (the HVE paper): its symbol table, the registered :data:`PAPER` and the
helpers its single-user sections share.

Physical assumptions used throughout (the paper's model): device damping ``b``, stiffness
``K`` and sampling period ``T`` are positive; virtual damping ``B`` and shortage of passivity
``z_a`` are non-negative; ``n = t_d/T`` is a non-negative integer.
"""

from __future__ import annotations


import sympy as sp

from hapticproof.audit.runner import Paper
from hapticproof.core.evidence import Decision, Evidence, Method, Outcome
from hapticproof.audit.reader.names import IndexedFamily, SymbolTable
from hapticproof.analysis.positivereal import hermitian, worst_case
from hapticproof.systems.singleuser import SYMBOLS, SingleUserScene
from hapticproof.core.symbols import z
from hapticproof.exact.unitcircle import omega_to_c



K, B, b, T, z_a, t_d, n = (SYMBOLS[name] for name in ("K", "B", "b", "T", "z_a", "t_d", "n"))


omega = sp.Symbol("omega", real=True)


s = sp.Symbol("s")


#: The paper's S (defined after eq. 23).
S_EXPR = sp.sin(omega * t_d) * sp.sin(omega * T) / (2 * (1 - sp.cos(omega * T)))


# Samples in the printed recurrences (section 3.1.1): x_h(kT + jT) and its derivative.
x_h, xdot_h = sp.Function("x_h"), sp.Function("xdot_h")


k_idx = sp.Symbol("k", integer=True)


# Signals that appear as functions of z in displays; the audit divides by V_h.
F_h, V_h, X_h = sp.symbols("F_h V_h X_h")


G_INV = {i: sp.Symbol(f"G{i}inv") for i in (1, 2, 3)}


H_FUN = sp.Function("H")


R_FUN = sp.Function("r")


G_T = sp.Function("G_T^*")


M_FUN, N_FUN = sp.Function("M"), sp.Function("N")


def _signal(symbol: sp.Symbol):
    return lambda *args: symbol


TABLE = SymbolTable(
    symbols={
        "K": K, "B": B, "b": b, "T": T, "t_d": t_d, "z_a": z_a, r"\omega": omega, "S": S_EXPR,
        "z": z, "s": s, "n": n, "k": k_idx,
        "b_h": sp.Symbol("b_h", positive=True), "k_h": sp.Symbol("k_h", positive=True),
        "m_h": sp.Symbol("m_h", positive=True), "C": sp.Symbol("C", positive=True),
        "m": sp.Symbol("m", integer=True, positive=True),
    },
    functions={
        "F_h": _signal(F_h), "V_h": _signal(V_h), "X_h": _signal(X_h),
        "x_h": x_h, r"\dot{x}_h": xdot_h, r"\mathscr{D}": sp.Function("D"),
        "G^{-1}": _signal(sp.Symbol("Ginv")), "G_1^{-1}": _signal(G_INV[1]), "G_2^{-1}": _signal(G_INV[2]), "G_3^{-1}": _signal(G_INV[3]),
        "H": H_FUN, "r": R_FUN, "G_T^*": G_T,
        r"\mathscr{M}": lambda *a: M_FUN(*a), r"\mathscr{N}": lambda *a: N_FUN(*a),
        r"\mathcal{M}": lambda *a: M_FUN(*a), r"\mathcal{N}": lambda *a: N_FUN(*a),
        r"\mathscr{Z}": sp.Function("Z"), r"\mathcal{Z}": sp.Function("Z"),
    },
    families=[
        IndexedFamily("b_{i}", assumptions={"positive": True}),
        IndexedFamily("z_{ai}", assumptions={"nonnegative": True}),
        IndexedFamily("K_{0i}", assumptions={"positive": True}),
        IndexedFamily("B_{0i}", assumptions={"nonnegative": True}),
        IndexedFamily("K_{ij}", symmetric=True, assumptions={"positive": True}),
        IndexedFamily("B_{ij}", symmetric=True, assumptions={"nonnegative": True}),
        IndexedFamily("t_{di}", assumptions={"nonnegative": True}),
        IndexedFamily("n_{i}", assumptions={"integer": True, "nonnegative": True}),
    ],
)


PAPER = Paper(
    "hve",
    title="Stability of Sampled-Data, Delayed Haptic Interaction under Passive or Active Operator",
    source="000_e6b68def623c8e74.txt",
    authors="N. Miandashti and M. Tavakoli",
    symbols=TABLE,
    aliases=("000", "miandashti-tavakoli", "haptic-virtual-environment"),
    conditions=[
        ("HVE (3)/(20), Colgate", r"b > \frac{KT}{2} + B", "eq. (20), confirmed"),
        ("HVE (4), Gil 2004 as quoted", r"b + B > \frac{KT}{2}", "eq. (4), small B only"),
        ("HVE (5) corrected, Gil 2009", r"K < \frac{B+b}{\frac{T}{2}+t_d}", "eq. (5), T -> T/2"),
        ("HVE (2), Minsky with operator", r"B+b+b_h > \frac{(K+k_h)T}{2}", "eq. (2); leading order b + b_h + B > KT/2"),
        ("HVE (25)", r"b + B > \frac{KT}{2} + Kt_d", "eq. (25), exact for B = 0"),
        ("HVE (25), any B >= 0", r"b > \frac{KT}{2} + Kt_d + B", "derived, sufficient for all n"),
        ("HVE (26)", r"b - z_a > \frac{KT}{2} + B", "eq. (26), confirmed"),
        ("HVE (27)", r"b - z_a + B > Kt_d + \frac{KT}{2}", "eq. (27), exact for B = 0"),
        ("HVE (54), m users", r"\min_i b_i > \max_i \{\tfrac{K_{0i}T}{2} + B_{0i}\} + m \max_{i \neq j} \{\tfrac{K_{ij}T}{2} + B_{ij}\}",
         "eq. (54), sufficient; exact when uniform"),
        ("HVE (63) corrected, m users, delay",
         r"\min_i \{b_i - z_{ai}\} > \max_i \{K_{0i}(t_d + \tfrac{T}{2}) + B_{0i}\} + m \max_{i \neq j} \{K_{ij}(t_d + \tfrac{T}{2}) + B_{ij}\}",
         "eq. (63) with the factor m; B small"),
    ],
)


ASSUME = "b, K, T > 0; B >= 0; z_a >= 0; n = t_d/T a non-negative integer"


def scene(approximation: str = "forward", delay=0, active: bool = False) -> SingleUserScene:
    """The paper's symbolic single-user scene."""
    return SingleUserScene.virtual_wall(
        K=K, B=B, b=b, T=T, approximation=approximation, delay=delay, z_a=z_a if active else 0
    )


def verify_pointwise(approximation: str, delay=0, active: bool = False):
    """Re-check a witness (parameters and c) by exact evaluation of the numeric scene."""

    def verify(point: dict) -> Outcome:
        values = {str(k): v for k, v in point.items()}
        numeric = SingleUserScene.virtual_wall(
            K=values["K"], B=values.get("B", 0), b=values["b"], T=values["T"],
            approximation=approximation, delay=delay, z_a=values.get("z_a", 0) if active else 0,
        )
        value = hermitian(numeric)(values["c"])
        decision = Decision.DISPROVED if value < 0 else Decision.PROVED
        return Outcome(decision, Evidence(Method.ROOT_ISOLATION, witness={"c": values["c"]}, facts={"Re G^-1": value}),
                       f"Re G^-1 = {value} at c = {values['c']}")

    return verify


def verify_worst_case(approximation: str = "forward", delay=0, active: bool = False):
    """Re-check a parameter witness by the exact worst-case decision (root isolation)."""

    def verify(point: dict) -> Outcome:
        values = {str(k): v for k, v in point.items()}
        numeric = SingleUserScene.virtual_wall(
            K=values["K"], B=values.get("B", 0), b=values["b"], T=values["T"],
            approximation=approximation, delay=values.get("n", delay), z_a=values.get("z_a", 0) if active else 0,
        )
        return worst_case(numeric).outcome

    return verify


def in_c(relation: sp.Basic) -> sp.Basic:
    """A printed frequency-wise condition with ``cos(wT)`` rewritten in ``c``."""
    return relation.func(omega_to_c(relation.lhs, omega, T), omega_to_c(relation.rhs, omega, T), evaluate=False)


def exact_worst(sc: SingleUserScene) -> sp.Basic:
    return worst_case(sc).condition
