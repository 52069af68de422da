r"""The designer's answers as mathematics: the delay margin and passive ranges in LaTeX displays.

Views of :class:`~hapticproof.analysis.design.DelayMargin` and
:class:`~hapticproof.analysis.passiverange.ParameterRange` (nothing is computed here): what
``--delay-margin`` and ``--range NAME`` asked for, as displays of the LaTeX document and of the
``--fragment`` output, in the scene's own names (the period by its role, ``b_dev`` as
``b_{dev}``). An algebraic end of a range is named (``K^{*}_{1}``) and defined in the same display
as the root of its irreducible polynomial in an isolating interval.

>>> from hapticproof.analysis.design import delay_margin
>>> from hapticproof.analysis.passiverange import passive_range
>>> from hapticproof.systems.scene import Scene
>>> wall = Scene("single-user", params={"K": 2, "b": "0.02", "B": "0.001", "T": "0.001"})
>>> print(margin_latex(delay_margin(wall), "T"))
N_{\max} = 10:\ G^{-1} \text{ is positive real for every delay } n \le 10 \text{, not at } n = 11;\quad t_d \le N_{\max} T = \frac{1}{100}
>>> print(range_latex(passive_range(wall.with_params(K=None), "K")))
0 < K \le 38 \quad \text{(the others fixed)}
"""

from __future__ import annotations

from collections.abc import Sequence
from typing import Any

import flint
import sympy as sp

from hapticproof.core.notation import to_latex

__all__ = ["margin_latex", "range_latex", "answer_items"]


def _name(name: str) -> str:
    return to_latex(sp.Symbol(name))


def margin_latex(margin: Any, period: str = "T", names: Any = None) -> str:
    """The delay margin as a display: ``N_max`` with what it means, and ``t_d <= N_max T`` (the
    period and ``N`` as the scene's naming ``names`` prints them, when given)."""
    T = names.role_latex("period", period) if names is not None else _name(period)
    Nmax = (names.helper_latex("margin") if names is not None else "N") + r"_{\max}"
    lower = getattr(margin, "lower", None)
    if margin.decision.value != "proved":
        if lower is not None and lower >= 0:
            return (Nmax + r"\ \text{undecided: } G^{-1} \text{ is positive real for every delay } n \le "
                    + str(lower) + r" \text{ (searched so far)}")
        return Nmax + r"\ \text{undecided}"
    if margin.margin is None:
        return Nmax + r" = \infty:\ G^{-1} \text{ is positive real for every delay } n = t_d/" + T + r" \ge 0"
    if margin.margin < 0:
        return r"\text{no delay margin: } G^{-1} \text{ is not positive real even without delay } (n = 0)"
    N = margin.margin
    out = (rf"{Nmax} = {N}:\ G^{{-1}} \text{{ is positive real for every delay }} n \le {N} \text{{, not at }} "
           rf"n = {N + 1}")
    t_max = margin.time_margin()
    if t_max is not None:
        out += rf";\quad t_d \le {Nmax} {T} = {to_latex(sp.sympify(t_max))}"
    return out


def _decimal_latex(q: Any) -> str:
    """A terminating decimal as a decimal (``9.4862847855``), else the fraction."""
    q = sp.Rational(q)
    d = int(q.q)
    k = next((k for k in range(60) if 10**k % d == 0), None)
    if k is None:
        return to_latex(q)
    digits = str(abs(int(q.p)) * (10**k // d)).rjust(k + 1, "0")
    return ("-" if q < 0 else "") + (digits if k == 0 else digits[:-k] + "." + digits[-k:])


def _poly_latex(poly: Any, name: str) -> str:
    """An integer polynomial in the parameter (highest power first)."""
    x = sp.Symbol(name)
    coeffs = [int(c) for c in flint.fmpz_poly(poly).coeffs()] if not isinstance(poly, flint.fmpq_poly) else \
        [sp.Rational(int(c.p), int(c.q)) for c in poly.coeffs()]
    return to_latex(sp.Add(*[c * x**k for k, c in enumerate(coeffs)]))


def _end(end: Any, algebraic: dict, name: str) -> str:
    if end.value is not None:
        return to_latex(sp.sympify(end.value))
    key = (str(end.lo), str(end.hi))
    if key not in algebraic:
        algebraic[key] = (rf"{_name(name)}^{{*}}_{{{len(algebraic) + 1}}}", end)
    return algebraic[key][0]


def range_latex(rng: Any) -> str:
    """The passive range as a display: its intervals (or that there is none), each algebraic end
    defined as the root of its polynomial in an isolating interval."""
    p = _name(rng.parameter)
    algebraic: dict = {}
    pieces = []
    for lo, lo_closed, hi, hi_closed in rng.intervals:
        if lo is not None and hi is not None and lo.value is not None and lo.value == hi.value:
            pieces.append(f"{p} = {_end(lo, algebraic, rng.parameter)}")
            continue
        le = {True: r"\le", False: "<"}
        left = "" if lo is None else f"{_end(lo, algebraic, rng.parameter)} {le[bool(lo_closed)]} "
        right = "" if hi is None else f" {le[bool(hi_closed)]} {_end(hi, algebraic, rng.parameter)}"
        pieces.append(f"{left}{p}{right}" if (left or right) else rf"\text{{every }} {p}")
    if not pieces:
        body = rf"\text{{no value of }} {p} \text{{ makes the scene passive}}"
    else:
        body = r" \ \text{or}\ ".join(pieces)
    body += r" \quad \text{(the others fixed)}"
    for label, end in algebraic.values():
        poly = end.polynomial
        degree = flint.fmpz_poly(poly).degree() if not isinstance(poly, flint.fmpq_poly) else poly.degree()
        shown = (_poly_latex(poly, rng.parameter) if degree <= 12
                 else rf"\text{{an irreducible polynomial of degree {degree} (in the JSON output)}}")
        lo, hi = end.short_interval()
        body += (rf",\quad {label} \approx {end.approx(12)} \text{{ the root of }} {shown} \text{{ in }} "
                 rf"[{_decimal_latex(lo)}, {_decimal_latex(hi)}]")
    if rng.undecided:
        body += rf";\quad \text{{undecided at {len(rng.undecided)} point(s)}}"
    return body


def answer_items(margin: Any = None, ranges: Sequence[Any] = (), period: str = "T",
                 names: Any = None) -> list[tuple[str, str]]:
    """``(label, display)`` of the answers asked for, for :func:`hapticproof.report.latex.derivation_document`
    and :func:`~hapticproof.report.latex.derivation_fragment` (in the scene's naming ``names``)."""
    items = []
    if margin is not None:
        items.append(("delay margin (--delay-margin)", margin_latex(margin, period, names)))
    for rng in ranges:
        items.append((f"passive range of {rng.parameter} (--range {rng.parameter})", range_latex(rng)))
    return items
