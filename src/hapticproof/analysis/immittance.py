r"""Positive realness and absolute stability of any immittance given as an exact transfer matrix.

One decision for every one-port and n-port a paper can define (a virtual wall's ``G^{-1}(z)``,
a coupling impedance, an m-user matrix, a two-port in ``z`` or ``s``):

* :func:`positive_real` -- the definition (HVE paper, Definition 2; Khalil for ``s``): no pole
  outside the closed disk (half-plane) nor at infinity (for ``z``), boundary poles simple with
  Hermitian PSD residues, and ``G + G^H >= 0`` on the whole boundary. Numeric matrices are
  decided exactly by the kernel with certificates.
* :func:`absolutely_stable` -- Llewellyn's criterion for a two-port: ``z_11`` and ``z_22`` positive
  real, and ``2 Re z_11 Re z_22 - Re(z_12 z_21) >= |z_12 z_21|`` at every frequency, decided as the
  two rational conditions ``X >= 0`` and ``X^2 - |z_12 z_21|^2 >= 0`` in ``c`` (``x``).
* :func:`exact_condition` -- the same property for a matrix with *parameters*: the condition on
  the parameters where it has a closed form (worst cases over frequency by endpoint analysis,
  pole locations of linear and quadratic factors) and, always, an exact decision at any numeric
  point (:attr:`ExactCondition.verify`).

>>> import sympy as sp
>>> from hapticproof.exact.transfer import TransferMatrix
>>> z = sp.Symbol("z")
>>> positive_real(TransferMatrix.from_sympy(sp.Rational(3, 5) + 1/(z - 1), z)).decision.value
'proved'
>>> s = sp.Symbol("s")
>>> N = TransferMatrix.from_sympy(sp.Matrix([[1 + 1/s, -1/s], [-1/s, 1/s]]), s)     # a spring behind a damper
>>> absolutely_stable(N).decision.value
'proved'
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass, field
from typing import Any, NamedTuple

import flint
import sympy as sp

from hapticproof.core.evidence import Decision, Evidence, Method, Outcome
from hapticproof.exact.boundaryvalue import C_NAME, X_NAME, determinant
from hapticproof.exact.conditions import Condition, combine
from hapticproof.exact.kernel import decide_rational_sign
from hapticproof.exact.rational import RationalFunction
from hapticproof.exact.transfer import CONTINUOUS, DISCRETE, TransferMatrix

__all__ = ["positive_real", "absolutely_stable", "exact_condition", "ExactCondition", "Part", "POSITIVE_REAL",
           "ABSOLUTELY_STABLE", "PROPERTIES"]

POSITIVE_REAL, ABSOLUTELY_STABLE = "positive-real", "absolutely-stable"
#: The properties a paper's condition can be about.
PROPERTIES = (POSITIVE_REAL, ABSOLUTELY_STABLE)


def _system(G: TransferMatrix) -> Any:
    from hapticproof.systems.lti import ExactSystem

    return ExactSystem(G.polynomials(), G.domain)


def positive_real(G: TransferMatrix) -> Outcome:
    """The exact decision whether a numeric square transfer matrix is positive real (passive).

    >>> import sympy as sp
    >>> z = sp.Symbol("z")
    >>> out = positive_real(TransferMatrix.from_sympy(sp.Rational(1, 10) + 1/(z - 1), z))
    >>> out.decision.value, out.witness["c"]
    ('disproved', -1)
    """
    from hapticproof.analysis.passivity import ispassive

    if not G.is_square:
        raise ValueError(f"positive realness needs a square matrix, got {G.shape[0]} x {G.shape[1]}")
    return ispassive(_system(G)).outcome


def _interval(domain: str) -> tuple[Any, Any, str]:
    return (-1, 1, "c") if domain == DISCRETE else (0, None, "x")


def _rational_in_t(f: RationalFunction, domain: str) -> tuple[flint.fmpq_poly, flint.fmpq_poly]:
    name = C_NAME if domain == DISCRETE else X_NAME
    if f.names - {name}:
        raise ValueError("the function still has parameters")
    if f.names:
        return f.univariate(name)
    value = f.constant_value()
    return flint.fmpq_poly([flint.fmpq(value.numerator, value.denominator)]), flint.fmpq_poly([1])


def _llewellyn_parts(N: TransferMatrix) -> tuple[RationalFunction, RationalFunction]:
    """``X = 2 Re z11 Re z22 - Re(z12 z21)`` and ``X^2 - |z12 z21|^2`` on the boundary (rational in ``t``)."""
    b = N.on_boundary().entries
    p = b[0][1] * b[1][0]
    X = (b[0][0].real_part() * b[1][1].real_part()) * 2 - p.real_part()
    if not X.is_rational_in_t:
        raise ValueError("the real parts are not rational in cos(theta) (a non-real-rational entry)")
    gap = X * X - p.abs2()
    return X.rational(), gap.rational()


def absolutely_stable(N: TransferMatrix) -> Outcome:
    """Llewellyn's criterion for a numeric two-port (impedance, admittance or hybrid matrix).

    >>> import sympy as sp
    >>> s = sp.Symbol("s")
    >>> absolutely_stable(TransferMatrix.from_sympy(sp.Matrix([[1, 3], [1, 1]]), s)).decision.value   # 2 - 3 - 3 < 0
    'disproved'
    """
    if N.shape != (2, 2):
        raise ValueError(f"Llewellyn's criterion is for a two-port (2 x 2), got {N.shape[0]} x {N.shape[1]}")
    conditions = []
    for k, name in ((0, "z11"), (1, "z22")):
        out = positive_real(N.submatrix([k]))
        conditions.append(Condition(f"{name} positive real", out))
    X, gap = _llewellyn_parts(N)
    lo, hi, var = _interval(N.domain)
    xn, xd = _rational_in_t(X, N.domain)
    gn, gd = _rational_in_t(gap, N.domain)
    conditions.append(Condition("2 Re z11 Re z22 - Re(z12 z21) >= 0",
                                decide_rational_sign(xn, xd, lo, hi, var, "2 Re z11 Re z22 - Re(z12 z21)")))
    conditions.append(Condition("(2 Re z11 Re z22 - Re(z12 z21))^2 >= |z12 z21|^2",
                                decide_rational_sign(gn, gd, lo, hi, var, "X^2 - |z12 z21|^2")))
    return combine(conditions, subject="the two-port", holds="absolutely stable")


# ---------------------------------------------------------------------------------------------
# with parameters
# ---------------------------------------------------------------------------------------------


class Part(NamedTuple):
    """One condition of a property: its ``name``, its closed form in the parameters (``None``:
    none found) and, for a condition at every frequency, the ``form`` ``F(parameters, t) >= 0``
    required for every ``t`` of the boundary (``t = c`` in ``[-1, 1]`` or ``x`` in ``[0, oo)``),
    as SymPy and as the exact :class:`RationalFunction` ``exact`` (for decisions at points)."""

    name: str
    condition: Any
    form: Any = None
    exact: Any = None


@dataclass(frozen=True)
class ExactCondition:
    """A property of a matrix with parameters: ``condition`` (a SymPy boolean in the parameters,
    necessary and sufficient, or ``None`` when it has no closed form), ``method`` how it was found,
    and :meth:`verify`, the exact decision at a numeric point."""

    matrix: TransferMatrix
    property: str
    symbols: Mapping[str, sp.Symbol]
    condition: Any = None
    method: str = ""
    parts: tuple[Part, ...] = field(default_factory=tuple)
    #: the boundary variable of the parts' forms (``c`` or ``x``)
    t: Any = None

    def decide(self, G: TransferMatrix) -> Outcome:
        return positive_real(G) if self.property == POSITIVE_REAL else absolutely_stable(G)

    def verify(self, point: Mapping[Any, Any]) -> Outcome:
        """The exact decision at the parameter values ``point`` (symbols or names -> rationals).

        The conditions at every frequency are decided first from their parametric forms (one
        substitution and one sign decision each); a point that passes them all is decided whole
        (poles and residues), so a disproof and a proof are always the definition's."""
        values = {getattr(k, "name", k): sp.Rational(v) for k, v in point.items()}
        missing = self.matrix.parameters - set(values)
        if missing:
            return Outcome(Decision.UNDECIDED, Evidence(Method.INSTANCES), f"no value for {', '.join(sorted(missing))}")
        mine = {k: v for k, v in values.items() if k in self.matrix.parameters}
        lo, hi, var = _interval(self.matrix.domain)
        for part in self.parts:
            if part.exact is None:
                continue
            try:
                f = part.exact.subs(mine)
                num, den = _rational_in_t(f, self.matrix.domain)
            except (ZeroDivisionError, ValueError):
                continue
            if den.is_zero() or num.is_zero():
                continue
            out = decide_rational_sign(num, den, lo, hi, var, part.name)
            if out.decision == Decision.DISPROVED:
                return combine([Condition(part.name, out)], subject="the matrix",
                               holds="positive real" if self.property == POSITIVE_REAL else "absolutely stable")
        try:
            G = self.matrix.subs(mine)
        except ZeroDivisionError:
            return Outcome(Decision.UNDECIDED, Evidence(Method.INSTANCES), "the matrix is undefined at this point")
        return self.decide(G)


def exact_condition(G: TransferMatrix, prop: str, symbols: Mapping[str, sp.Symbol]) -> ExactCondition:
    """The condition on the parameters under which ``G`` has the property ``prop``.

    ``symbols`` maps parameter names to SymPy symbols carrying the paper's assumptions (the
    endpoint analysis uses their signs).

    >>> import sympy as sp
    >>> z = sp.Symbol("z")
    >>> K, T, b = sp.symbols("K T b", positive=True)
    >>> B = sp.Symbol("B", nonnegative=True)
    >>> G = TransferMatrix.from_sympy(b + K*T/(z - 1) + B/z, z)
    >>> exact_condition(G, "positive-real", {"K": K, "T": T, "b": b, "B": B}).condition
    b >= B + K*T/2
    """
    if prop not in PROPERTIES:
        raise ValueError(f"unknown property {prop!r} ({', '.join(PROPERTIES)})")
    t = sp.Dummy("c" if G.domain == DISCRETE else "x", real=True)
    if prop == POSITIVE_REAL:
        parts = _pr_parts(G, symbols, t)
    else:
        parts = _llewellyn_symbolic(G, symbols, t)
    known = [p.condition for p in parts if p.condition is not None]
    condition = sp.And(*known) if len(known) == len(parts) else None
    method = "; ".join(f"{p.name}: {sp.sstr(p.condition) if p.condition is not None else 'no closed form'}" for p in parts)
    return ExactCondition(G, prop, dict(symbols), condition, method, tuple(parts), t)


def _symbol_table(G: TransferMatrix, symbols: Mapping[str, sp.Symbol], t: sp.Symbol) -> dict[str, sp.Symbol]:
    table = {name: symbols.get(name, sp.Symbol(name, real=True)) for name in G.parameters}
    table[C_NAME] = t
    table[X_NAME] = t
    return table


def _scalar_sympy(f: RationalFunction, G: TransferMatrix, symbols: Mapping[str, sp.Symbol]) -> sp.Expr:
    return TransferMatrix.scalar(f, G.domain).to_sympy({n: symbols.get(n, sp.Symbol(n, real=True)) for n in G.parameters})


def _minimum_condition(expr: sp.Expr, domain: str, t: sp.Symbol) -> Any:
    """``expr(t) >= 0`` for every ``t`` of the boundary, by endpoint analysis; ``None`` when it has
    no closed form. On the axis ``x = (1 + c)/(1 - c)`` maps ``[-1, 1)`` onto ``[0, oo)``."""
    from hapticproof.analysis.positivereal import symbolic_minimum
    from hapticproof.core.symbols import c as C_SYM

    num, den = sp.fraction(sp.together(expr))
    if sp.Poly(num, t).degree() > 2 or sp.Poly(den, t).degree() > 2:
        return None                          # endpoint analysis covers low degrees in t only
    if domain == CONTINUOUS:
        expr = sp.cancel(expr.subs(t, (1 + C_SYM) / (1 - C_SYM)))
    else:
        expr = expr.subs(t, C_SYM)
    if C_SYM not in expr.free_symbols:
        return _signed(sp.Ge(expr, 0))
    wc = symbolic_minimum(expr)
    if wc.condition is None or isinstance(wc.condition, sp.Ge) and wc.condition.lhs.has(sp.Function("min_c")):
        return None
    if any(getattr(f.func, "__name__", "") == "min_c" for f in sp.sympify(wc.condition).atoms(sp.Function)):
        return None
    return wc.condition


def _signed(cond: Any) -> Any:
    return sp.simplify(cond) if cond in (sp.true, sp.false) else cond


def _pr_parts(G: TransferMatrix, symbols: Mapping[str, sp.Symbol], t: sp.Symbol) -> list[Part]:
    """The conditions of positive realness with parameters: properness and poles, residues at
    fixed boundary poles, and the Hermitian part (its principal minors for a matrix) at every
    frequency."""
    from itertools import combinations

    table = _symbol_table(G, symbols, t)
    parts: list[Part] = [Part(name, cond) for name, cond in _pole_parts(G, symbols)]
    H = G.hermitian_part()
    n = G.shape[0]
    for k in range(1, n + 1):
        for rows in combinations(range(n), k):
            minor = determinant([[H.entries[i][j] for j in rows] for i in rows])
            name = "Re G >= 0 at every frequency" if n == 1 else f"principal minor {tuple(r + 1 for r in rows)} of G + G^H >= 0"
            if not minor.is_rational_in_t:
                parts.append(Part(name, None))
                continue
            form = minor.rational().to_sympy(table)
            parts.append(Part(name, _minimum_condition(form, G.domain, t), form, minor.rational()))
    return parts


def _llewellyn_symbolic(N: TransferMatrix, symbols: Mapping[str, sp.Symbol], t: sp.Symbol) -> list[Part]:
    """Llewellyn's conditions with parameters: ``z_11``, ``z_22`` positive real, ``X >= 0`` and
    ``X^2 - |z_12 z_21|^2 >= 0`` at every frequency."""
    if N.shape != (2, 2):
        raise ValueError(f"Llewellyn's criterion is for a two-port (2 x 2), got {N.shape[0]} x {N.shape[1]}")
    table = _symbol_table(N, symbols, t)
    parts: list[Part] = []
    for k, name in ((0, "z11"), (1, "z22")):
        for part in _pr_parts(N.submatrix([k]), symbols, t):
            parts.append(part._replace(name=f"{name}: {part.name}"))
    X, gap = _llewellyn_parts(N)
    for name, f in (("2 Re z11 Re z22 - Re(z12 z21) >= 0", X), ("(2 Re z11 Re z22 - Re(z12 z21))^2 - |z12 z21|^2 >= 0", gap)):
        form = f.to_sympy(table)
        parts.append(Part(name, _minimum_condition(form, N.domain, t), form, f))
    return parts


# ---------------------------------------------------------------------------------------------
# poles with parameters
# ---------------------------------------------------------------------------------------------


def _pole_parts(G: TransferMatrix, symbols: Mapping[str, sp.Symbol]) -> list[tuple[str, Any]]:
    """Properness and pole conditions with parameters.

    The poles are the roots of the least common multiple of the entries' denominators, factored
    over ``Q[parameters, variable]``. A linear factor ``a v + b`` has the root ``p = -b/a``: it must
    lie in ``[-1, 1]`` (``z``) or ``p <= 0`` (``s``); a quadratic one ``a v^2 + b v + c`` satisfies
    Jury's conditions ``|c| <= a`` and ``|b| <= a + c`` (with ``a > 0``), or Hurwitz's ``b, c >= 0``
    (closed regions: a root on the boundary for special values is decided exactly by ``verify``).
    A fixed rational boundary pole (``z = +-1``, ``s = 0``) is simple with a residue (matrix)
    ``Res/z0`` PSD. Higher factors have no closed form (``None``)."""
    var = G.variable
    table = {name: symbols.get(name, sp.Symbol(name, real=True)) for name in G.parameters}
    parts: list[tuple[str, Any]] = [("proper", _properness(G, table))]
    den = RationalFunction.constant(1)
    for row in G.entries:
        for e in row:
            den = den.polynomial_lcm(RationalFunction(e.den))
    if den.is_constant:
        return parts + [("poles", sp.true)]
    factors = den.num.factor()[1]
    conditions: list[Any] = []
    for f, multiplicity in factors:
        g = RationalFunction(f)
        degree = g.degree(var)
        if degree == 0:
            continue                       # a parameter in a denominator: no pole in the variable
        coeffs = [c.to_sympy(table) for c in g.coefficients(var)[0]]
        if degree == 1:
            root = sp.cancel(-coeffs[0] / coeffs[1])
            if not root.free_symbols:
                conditions.append(_fixed_pole(G, root, int(multiplicity), table))
            elif G.domain == DISCRETE:
                conditions.append(sp.And(sp.Ge(root, -1), sp.Le(root, 1)))
            else:
                conditions.append(sp.Le(root, 0))
            continue
        if degree == 2:
            c0, c1, c2 = coeffs
            if not (c0.free_symbols | c1.free_symbols | c2.free_symbols):
                conditions.append(_numeric_factor(G, g, table))
                continue
            a0, a1 = sp.cancel(c0 / c2), sp.cancel(c1 / c2)
            if G.domain == DISCRETE:
                conditions.append(sp.And(sp.Le(sp.Abs(a0), 1), sp.Le(sp.Abs(a1), 1 + a0)))
            else:
                conditions.append(sp.And(sp.Ge(a1, 0), sp.Ge(a0, 0)))
            continue
        if not (set().union(*(sp.sympify(c).free_symbols for c in coeffs))):
            conditions.append(_numeric_factor(G, g, table))
            continue
        return parts + [("poles", None)]
    if any(c is None for c in conditions):
        return parts + [("poles", None)]
    return parts + [("poles", sp.And(*conditions) if conditions else sp.true)]


def _properness(G: TransferMatrix, table: Mapping[str, sp.Symbol]) -> Any:
    """No pole at ``z = oo`` (discrete); at most a simple one with a PSD coefficient at ``s = oo``."""
    var = G.variable
    allowed = 0 if G.domain == DISCRETE else 1
    conditions = []
    top = []
    for row in G.entries:
        top_row = []
        for e in row:
            num, den = e.coefficients(var)
            excess = len(num) - len(den)
            lead_den = den[-1].to_sympy(table)
            vanish = [c.to_sympy(table) for c in num[len(den) + allowed:]]
            conditions += [sp.Eq(c, 0) for c in vanish if c != 0]
            top_row.append(sp.cancel(num[len(den) - 1 + allowed].to_sympy(table) / lead_den)
                           if allowed and excess >= 1 and len(num) >= len(den) + 1 else sp.Integer(0))
        top.append(top_row)
    if allowed:
        M = sp.Matrix(top)
        if any(e != 0 for e in M):
            conditions.append(_psd_condition(M))
    out = sp.And(*conditions) if conditions else sp.true
    return _signed(out)


def _psd_condition(M: sp.Matrix) -> Any:
    """A constant symmetric matrix (entries in the parameters) PSD: every principal minor >= 0."""
    from itertools import combinations

    if M != M.T:
        return sp.And(*[sp.Eq(M[i, j] - M[j, i], 0) for i in range(M.rows) for j in range(i + 1, M.rows)], _psd_condition(
            (M + M.T) / 2))
    n = M.rows
    conds = []
    for k in range(1, n + 1):
        for rows in combinations(range(n), k):
            conds.append(sp.Ge(sp.factor(M.extract(list(rows), list(rows)).det()), 0))
    return _signed(sp.And(*conds))


def _fixed_pole(G: TransferMatrix, root: sp.Expr, multiplicity: int, table: Mapping[str, sp.Symbol]) -> Any:
    """A pole at a fixed rational point: inside/left, or on the boundary simple with ``Res/z0`` PSD."""
    if G.domain == DISCRETE:
        if abs(root) < 1:
            return sp.true
        if abs(root) > 1:
            return sp.false
    else:
        if root < 0:
            return sp.true
        if root > 0:
            return sp.false
    if multiplicity > 1:
        return sp.false
    var = G.variable
    point = RationalFunction.constant(root)
    R = []
    for row in G.entries:
        R_row = []
        for e in row:
            num, den = e.num, e.den
            f = RationalFunction(den)
            if f.subs({var: point}).is_zero:
                lin = RationalFunction.variable(var) - point
                reduced = RationalFunction(num) / (f / lin)
                R_row.append(reduced.subs({var: point}).to_sympy(table))
            else:
                R_row.append(sp.Integer(0))
        R.append(R_row)
    M = sp.Matrix(R)
    if G.domain == DISCRETE:
        M = M / root
    return _psd_condition(M)


def _numeric_factor(G: TransferMatrix, factor: RationalFunction, table: Mapping[str, sp.Symbol]) -> Any:
    """A factor with numeric coefficients: where its roots lie decides it, except on the boundary
    (residues with parameters at algebraic points: no closed form here)."""
    from hapticproof.exact.kernel import locate_roots

    p, _ = factor.univariate(G.variable)
    cert = locate_roots(p, "disk" if G.domain == DISCRETE else "halfplane")
    if cert.outside:
        return sp.false
    if cert.boundary:
        return None
    return sp.true
