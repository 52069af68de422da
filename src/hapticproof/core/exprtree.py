r"""SymPy expressions as plain JSON trees, for the independent checker's judge.

A finding carries the printed display *as given* (after the paper file's names and the scene's
values are put in, before any rewriting), so that the judge (:mod:`hapticproof.exact.judge`)
can evaluate it at a witness with its own ball arithmetic, without SymPy and without trusting
the derivation that rewrote it. The tree is a list whose head names the node:

* ``["q", "p/q"]`` an exact rational; ``["s", name]`` a symbol; ``["i"]``, ``["pi"]``, ``["e"]``;
* ``["+", a, b, ...]``, ``["*", a, b, ...]``, ``["^", base, exponent]``;
* ``["cos", a]`` and the other functions of :data:`FUNCTIONS`; relations ``[">", lhs, rhs]``.

Reports are inert: a tree is data, read by a fixed evaluator, never executed.

>>> import sympy as sp
>>> K, w, T = sp.symbols("K omega T")
>>> to_tree(K*sp.cos(w*T) + sp.Rational(1, 2))
['+', ['q', '1/2'], ['*', ['s', 'K'], ['cos', ['*', ['s', 'T'], ['s', 'omega']]]]]
>>> to_tree(sp.Gt(K, 2))
['>', ['s', 'K'], ['q', '2']]
"""

from __future__ import annotations

from typing import Any

import sympy as sp

__all__ = ["to_tree", "FUNCTIONS", "RELATIONS"]

#: The functions a tree may apply (SymPy's names, lower case).
FUNCTIONS = ("cos", "sin", "tan", "cot", "sec", "csc", "exp", "log", "abs", "re", "im", "conjugate", "atan",
             "acos", "asin", "sinh", "cosh", "tanh", "sqrt")
#: Relations: ``>``, ``>=``, ``<``, ``<=``, ``=``.
RELATIONS = {">": sp.StrictGreaterThan, ">=": sp.GreaterThan, "<": sp.StrictLessThan, "<=": sp.LessThan,
             "=": sp.Equality}

_NAMES = {sp.Abs: "abs", sp.re: "re", sp.im: "im", sp.conjugate: "conjugate"}


def to_tree(expr: Any) -> list:
    """The JSON tree of an expression or relation; ``ValueError`` for anything else (an unknown
    function, a matrix, a float that is not finite)."""
    expr = sp.sympify(expr)
    if isinstance(expr, sp.core.relational.Relational):
        for op, cls in RELATIONS.items():
            if type(expr) is cls:
                return [op, to_tree(expr.lhs), to_tree(expr.rhs)]
        raise ValueError(f"unsupported relation {type(expr).__name__}")
    if isinstance(expr, sp.And):
        return ["and", *[to_tree(a) for a in expr.args]]
    if expr.is_Rational:
        return ["q", str(expr)]
    if expr.is_Float:
        return ["q", str(sp.Rational(expr))]
    if expr is sp.I:
        return ["i"]
    if expr is sp.pi:
        return ["pi"]
    if expr is sp.E:
        return ["e"]
    if isinstance(expr, sp.Symbol):
        return ["s", expr.name]
    if isinstance(expr, sp.Add):
        return ["+", *[to_tree(a) for a in expr.args]]
    if isinstance(expr, sp.Mul):
        return ["*", *[to_tree(a) for a in expr.args]]
    if isinstance(expr, sp.Pow):
        return ["^", to_tree(expr.base), to_tree(expr.exp)]
    name = _NAMES.get(expr.func, getattr(expr.func, "__name__", "").lower())
    if isinstance(expr, sp.Function) and name in FUNCTIONS and len(expr.args) == 1:
        return [name, to_tree(expr.args[0])]
    raise ValueError(f"no tree for {sp.sstr(expr)[:60]}")
