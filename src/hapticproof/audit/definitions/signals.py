r"""Reading signal equations and what a paper's model determines, for :class:`~hapticproof.audit.definitions.reading.PaperReading`.

* :func:`port_relation` -- a port description ``[f_1; f_2] = \mathbf{Z}(s)[v_1; v_2]`` (the reader
  distributes the matrix function over the vector; its common factor is the matrix);
* :func:`signal_rows` -- a model equation, a port variable or a termination as one linear
  relation among signals (``Z_m v_m - f_h + k_f f_e = 0``);
* :func:`expected_value` -- what the model and the port relations say a new name is: a port
  matrix the model determines, a generic entry of a conversion (``h_{11}`` from ``z_{ij}``), or
  the transmitted impedance of a terminated port.

Signals are the names written with a signal's letter (``f``, ``v``, ``x``, ``F``, ``V``, ``X``, ...)
or a time derivative (``\dot{x}``) that no definition binds.

>>> import sympy as sp
>>> from hapticproof.audit.reader.statements import Relation, Span
>>> f1, f2, v1, v2 = sp.symbols("f_1 f_2 v_1 v_2")
>>> Z = sp.Function(r"\mathbf{Z}")(sp.Symbol("s"))
>>> port_relation(Relation((sp.Matrix([[f1], [f2]]), sp.Matrix([[v1*Z], [v2*Z]])), ("=",), Span(0, 1)))
('\\mathbf{Z}', ('f_1', 'f_2'), ('v_1', 'v_2'))
"""

from __future__ import annotations

import re
from typing import Any

import sympy as sp
from sympy.core.function import AppliedUndef

from hapticproof.audit.definitions.values import PARAM, TRANSFER, Unbound, Unsupported, Value, evaluate
from hapticproof.exact.rational import RationalFunction

__all__ = ["port_relation", "signal_rows", "expected_value", "is_signal", "letter_of", "instantiate", "generic_names"]

_SIGNAL = re.compile(r"(?:\\(?:dot|ddot|tilde|hat)\{)?(?:f|v|x|F|V|X|u|y|q|p|tau|e|E)(?:\}|_|$|\^)")
_TERMINAL = re.compile(r"^Z_(?:e|h|E|H|env|\{?e\}?|\{?h\}?)$")


def letter_of(matrix: str) -> str | None:
    r"""The letter of a port matrix's generic entries: ``\mathbf{Z}`` -> ``z``, ``H`` -> ``h``."""
    m = re.fullmatch(r"\\(?:mathbf|boldsymbol|bm)\{?([A-Za-z])\}?|([A-Za-z])", matrix)
    if not m:
        return None
    return (m.group(1) or m.group(2)).lower()


def is_signal(name: str, paper: Any) -> bool:
    """A signal of ``paper``: a signal's letter or a derivative, bound by no definition."""
    if name in paper.bindings:
        return False
    return bool(_SIGNAL.match(name))


def port_relation(relation: Any) -> tuple[str, tuple[str, ...], tuple[str, ...]] | None:
    """``(matrix, outputs, inputs)`` of a port description, or ``None``."""
    if relation.ops != ("=",) or len(relation.terms) != 2:
        return None
    lhs, rhs = relation.terms
    if not isinstance(lhs, sp.MatrixBase) or not isinstance(rhs, sp.MatrixBase) or lhs.shape != rhs.shape or lhs.cols != 1:
        return None
    outputs = []
    for e in lhs:
        if not isinstance(e, sp.Symbol):
            return None
        outputs.append(e.name)
    matrix = None
    inputs = []
    for e in rhs:
        factors = sp.Mul.make_args(e)
        applied = [f for f in factors if isinstance(f, AppliedUndef)]
        symbols = [f for f in factors if isinstance(f, sp.Symbol)]
        if len(applied) != 1 or len(symbols) != 1 or len(factors) != 2:
            return None
        name = applied[0].func.__name__
        if matrix is not None and name != matrix:
            return None
        matrix = name
        inputs.append(symbols[0].name)
    return (matrix, tuple(outputs), tuple(inputs)) if matrix is not None else None


def _as_products(expr: Any, paper: Any) -> Any:
    """``Z_p(v_m - v_s)``: a bound name applied to signals is a product."""
    def product(e: Any) -> Any:
        if len(e.args) == 1 and any(is_signal(s.name, paper) for s in e.args[0].free_symbols):
            return sp.Symbol(e.func.__name__, real=True) * e.args[0]
        return e
    return expr.replace(lambda e: isinstance(e, AppliedUndef), product)


def signal_rows(relation: Any, env: Any, paper: Any) -> tuple[dict[str, RationalFunction], bool] | None:
    """One equation as ``{signal: coefficient}`` (summing to zero) and whether it is a
    termination (its coefficients name an environment or operator impedance ``Z_e``, ``Z_h``);
    ``None`` unless at least two signals appear and every term carries exactly one."""
    if len(relation.terms) != 2 or any(isinstance(t, sp.MatrixBase) for t in relation.terms):
        return None
    lhs, rhs = (_as_products(sp.sympify(t), paper) for t in relation.terms)
    diff = sp.expand(lhs - rhs)
    signals = sorted({s for s in diff.free_symbols if is_signal(s.name, paper)}, key=lambda s: s.name)
    if len(signals) < 2:
        return None
    row: dict[str, Any] = {}
    for term in sp.Add.make_args(diff):
        present = [s for s in signals if term.has(s)]
        if len(present) != 1 or sp.degree(term, present[0]) != 1:
            return None
        coefficient = sp.cancel(term / present[0])
        row[present[0].name] = row.get(present[0].name, 0) + coefficient
    out = {}
    termination = False
    for name, coefficient in row.items():
        if any(_TERMINAL.match(s.name) for s in sp.sympify(coefficient).free_symbols):
            termination = True
        try:
            value = evaluate(coefficient, env)
        except (Unbound, Unsupported, ValueError, ZeroDivisionError):
            return None
        if not value.is_scalar or value.kind not in (PARAM, TRANSFER):
            return None
        out[name] = value.rows[0][0]
    return out, termination


def _matrix_value(rows: list[list[RationalFunction]]) -> Value:
    domain = None
    for row in rows:
        for e in row:
            if "$s" in e.names:
                domain = "continuous"
            elif "$z" in e.names:
                domain = "discrete"
    return Value(TRANSFER if domain else PARAM, tuple(tuple(row) for row in rows), domain)


def _port_named(name: str, paper: Any) -> str | None:
    return name if name in paper.system.ports else None


def _entry(name: str) -> tuple[str, int, int] | None:
    m = re.fullmatch(r"([a-z])_\{?(\d)(\d)\}?", name)
    return (m.group(1), int(m.group(2)) - 1, int(m.group(3)) - 1) if m else None


def expected_value(lhs: Any, rhs: Any, paper: Any, env: Any) -> tuple[Value, str] | None:
    """What the paper's model or port relations determine the left-hand name to be, with how."""
    system = paper.system
    if not system.ports:
        return None
    name = lhs.func.__name__ if isinstance(lhs, AppliedUndef) else getattr(lhs, "name", None)
    if name is None:
        return None
    letters = {letter_of(m): m for m in system.ports if letter_of(m)}
    if _port_named(name, paper):
        rows = system.matrix(name)
        if rows is None:
            return None
        return _matrix_value(rows), f"what the model's relations give for {name} (eliminating the other signals)"
    entry = _entry(name)
    if entry is not None and entry[0] in letters:
        target = letters[entry[0]]
        rhs_names = {s.name for s in sp.sympify(rhs).free_symbols}
        sources = [m for letter, m in letters.items() if m != target and any(_entry(n) and _entry(n)[0] == letter
                                                                           for n in rhs_names)]
        if sources:
            rows = system.conversion(target, sources[0], {sources[0]: letter_of(sources[0])})
            how = f"the conversion of {sources[0]} into {target} from their port relations"
        else:
            rows = system.matrix(target)
            how = f"the entry of {target} the model's relations give"
        if rows is None:
            return None
        return _matrix_value([[rows[entry[1]][entry[2]]]]), how
    if system.terminations and isinstance(lhs, (sp.Symbol, AppliedUndef)):
        try:
            printed = evaluate(rhs, env)
        except (Unbound, Unsupported, ValueError, ZeroDivisionError):
            return None
        for matrix, port in system.ports.items():
            letter = letter_of(matrix)
            rhs_letters = {_entry(s.name)[0] for s in sp.sympify(rhs).free_symbols if _entry(s.name)}
            if letter in rhs_letters:
                seen = system.seen_at(matrix, letter=letter)
            else:
                rows = system.matrix(matrix)
                seen = system.seen_at(matrix, matrix=rows) if rows is not None else None
            if seen is None:
                continue
            try:
                # in the names the display is read with (generic entries a display has bound stand for their values)
                value = evaluate(seen.to_sympy({n: sp.Symbol(n, real=True) for n in seen.names}), env)
            except (Unbound, Unsupported, ValueError, ZeroDivisionError):
                value = _matrix_value([[seen]])
            try:
                if (value - printed).is_zero:
                    return value, f"{port.outputs[0]}/{port.inputs[0]} with the other port terminated"
            except Unsupported:
                continue
    return None


def generic_names(value: Value, paper: Any) -> set[str]:
    """The generic port-matrix entries (``z_11``, ``h_21``) a value is written in."""
    letters = {letter_of(m) for m in paper.system.ports}
    return {n for n in value.names if _entry(n) and _entry(n)[0] in letters}


def instantiate(value: Value, paper: Any) -> Value | None:
    """A value in generic entries with each port matrix the paper's model determines substituted
    (``Z_t`` of a general two-port, for the position--force teleoperator of the section)."""
    names = generic_names(value, paper)
    if not names:
        return None
    substitution: dict[str, RationalFunction] = {}
    for matrix in paper.system.ports:
        letter = letter_of(matrix)
        wanted = {n for n in names if _entry(n)[0] == letter}
        if not wanted:
            continue
        rows = paper.system.matrix(matrix)
        if rows is None:
            return None
        for n in wanted:
            _, i, j = _entry(n)
            substitution[n] = rows[i][j]
    if set(substitution) != names:
        return None
    rows = tuple(tuple(_subs(e, substitution) for e in row) for row in value.rows)
    domain = value.domain
    for row in rows:
        for e in row:
            if hasattr(e, "names") and "$s" in e.names:
                domain = domain or "continuous"
    return Value(value.kind if value.kind != PARAM or domain is None else TRANSFER, rows, domain)


def _subs(e: Any, substitution: dict[str, RationalFunction]) -> Any:
    if isinstance(e, RationalFunction):
        return e.subs(substitution)
    return type(e)(*(part.subs(substitution) for part in (e.re0, e.re1, e.im0, e.im1)), e.domain)
