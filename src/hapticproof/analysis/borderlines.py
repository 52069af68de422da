"""The papers' printed stability/passivity conditions, as borderlines of a scene family.

One place maps a scene (system, delay, operator) to the printed condition that the paper tests
against its simulations, with the equation number; :func:`printed_borderline` solves that
condition exactly (``sympy.solve`` on the linear equality) for the varied parameter. The
conditions are written in the family's own parameter names (see
:class:`hapticproof.analysis.maps.SceneFamily`): ``m, b, K, B, T`` plus ``z_a`` (the operator's
shortage of passivity), ``t_d = n T`` and ``users``.

This module is the single switch point for the audit registry: when
``hapticproof.audit.registry`` exposes the printed equations, :func:`printed_condition` reads them
from there instead of the table below.

>>> from hapticproof.analysis.maps import SceneFamily
>>> fam = SceneFamily("single-user", {"m": 0.015, "b": 0.02, "B": 0})
>>> printed_condition(fam).equation
'20'
>>> border = printed_borderline(fam, "K")
>>> border({"b": 0.02, "B": 0, "T": 0.001, "z_a": 0})
40.0
"""

from __future__ import annotations

import functools
from collections.abc import Callable, Mapping
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

import sympy as sp

if TYPE_CHECKING:  # pragma: no cover
    from hapticproof.analysis.maps import SceneFamily

__all__ = ["PrintedCondition", "printed_condition", "printed_borderline", "CONDITIONS"]

#: Paper ids as in ../shared/papers/README.md.
HVE_PAPER = "000"
TELEOPERATOR_PAPER = "002"


@dataclass(frozen=True, slots=True)
class PrintedCondition:
    """A printed condition ``lhs > rhs`` in family parameter names.

    Parameters
    ----------
    paper, equation : str
        Paper id and the paper's equation number.
    lhs, rhs : str
        SymPy-parsable sides of the printed inequality (the side that must be larger first).
    note : str
        How the printed condition was specialised to the family (one sentence).
    """

    paper: str
    equation: str
    lhs: str
    rhs: str
    note: str = ""

    @property
    def label(self) -> str:
        return f"({self.equation})"

    def expression(self) -> sp.Expr:
        """``lhs - rhs`` (the condition holds where it is positive)."""
        return sp.sympify(self.lhs) - sp.sympify(self.rhs)


#: The printed conditions the papers compare with their simulations (HVE paper Section 4 and
#: Fig. 9; teleoperator paper Section IV).
CONDITIONS: dict[str, PrintedCondition] = {
    "hve-20": PrintedCondition(HVE_PAPER, "20", "b", "K*T/2 + B", "free device, no delay (Colgate)"),
    "hve-25": PrintedCondition(HVE_PAPER, "25", "b + B", "K*T/2 + K*t_d", "free device, delay t_d"),
    "hve-26": PrintedCondition(HVE_PAPER, "26", "b - z_a", "K*T/2 + B", "active operator, no delay"),
    "hve-27": PrintedCondition(
        HVE_PAPER, "27", "b - z_a + B", "K*t_d + K*T/2", "active operator, delay t_d"
    ),
    "hve-55": PrintedCondition(
        HVE_PAPER,
        "55",
        "b - z_a",
        "(K/2)*T/2 + B/2 + users*((K/2)*T/2 + B/2)",
        "m users, no delay, uniform couplings K_0i = K_ij = K/2, B_0i = B_ij = B/2",
    ),
    "hve-61": PrintedCondition(
        HVE_PAPER,
        "61",
        "b - z_a + B/2 + 2*(B/2)",
        "(K/2)*T/2 + (K/2)*T + (K/2)*t_d + 2*(K/2)*t_d",
        "dual user, delay t_d, K_0 = K_12 = K/2, B_0 = B_12 = B/2, b replaced by b - z_a as "
        "the paper does for (63)",
    ),
    "hve-63": PrintedCondition(
        HVE_PAPER,
        "63",
        "b - z_a + B/2 + B/2",
        "((K/2)*t_d + (K/2)*T/2) + ((K/2)*t_d + (K/2)*T/2)",
        "m users, delay t_d, uniform couplings K_0i = K_ij = K/2, B_0i = B_ij = B/2",
    ),
    "tele-35": PrintedCondition(
        TELEOPERATOR_PAPER, "35", "b", "K*T + 2*B", "equal PD controllers, b = min(b_m, b_s)"
    ),
}


def printed_condition(family: SceneFamily) -> PrintedCondition | None:
    """The printed condition the paper tests for this family, or ``None``.

    Single user: (20)/(25) for the free device, (26)/(27) with an operator; m users: (55)/(63);
    teleoperator with ``alpha = 1``: (35).
    """
    delayed = family.delay > 0
    if family.system == "single-user":
        if family.operator is None:
            return CONDITIONS["hve-25" if delayed else "hve-20"]
        return CONDITIONS["hve-27" if delayed else "hve-26"]
    if family.system == "multi-user":
        return CONDITIONS["hve-63" if delayed else "hve-55"]
    if family.system == "teleoperator":
        if delayed or sp.Rational(str(family.values().get("alpha", 1))) != 1:
            return None
        return CONDITIONS["tele-35"]
    return None


@functools.lru_cache(maxsize=64)
def _solved(lhs: str, rhs: str, vary: str) -> sp.Expr | None:
    expr = sp.sympify(lhs) - sp.sympify(rhs)
    symbol = sp.Symbol(vary)
    if symbol not in expr.free_symbols or sp.degree(expr, symbol) != 1:
        return None
    (solution,) = sp.solve(sp.Eq(expr, 0), symbol)
    return solution


def printed_borderline(
    family: SceneFamily, vary: str, key: str | None = None
) -> Callable[[Mapping[str, Any]], float] | None:
    """A function ``values -> borderline of vary`` from the family's printed condition.

    ``key`` picks a condition of :data:`CONDITIONS` instead of the family's own (e.g.
    ``"hve-61"`` for the dual-user delayed case).

    ``values`` maps the other parameter names (as :meth:`SceneFamily.printed_values` returns
    them) to numbers. ``None`` when no printed condition applies or the condition is not
    linear in ``vary``.
    """
    condition = printed_condition(family) if key is None else CONDITIONS[key]
    if condition is None:
        return None
    solution = _solved(condition.lhs, condition.rhs, vary)
    if solution is None:
        return None
    names = sorted(str(s) for s in solution.free_symbols)
    evaluate = sp.lambdify([sp.Symbol(n) for n in names], solution, "math")

    def borderline(values: Mapping[str, Any]) -> float:
        return float(evaluate(*(float(values[n]) for n in names)))

    borderline.condition = condition  # type: ignore[attr-defined]
    return borderline
