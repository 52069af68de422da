r"""Scalar conditions of m-user scenes against the matrix condition: ``passivity-condition``,
``sufficient-condition`` and ``necessary-condition`` claims whose display bounds the dampings
of single users (``b_1 > \frac{(K_{01} + K_{12})T}{2} + B_{01} + B_{12}``, ``b_i > ...,
\quad i = 1, 2``, ``\min_i b_i > \max_i \{...\}``), while ``G^{-1}`` is positive real iff
``M(c) = G^{-1} + G^{-H}`` is positive semidefinite at every frequency.

Necessary
    A diagonal entry of a positive semidefinite matrix is non-negative, so ``M_ii(c) >= 0`` for
    every ``c`` in ``[-1, 1]`` is necessary: its exact worst case over ``c`` is a lower bound
    ``b_i >= g_i`` (:func:`~hapticproof.analysis.positivereal.symbolic_minimum`). A printed bound
    ``b_i > f_i`` with ``f_i <= g_i`` (proved from the signs) is necessary. One with ``f_i > g_i``
    somewhere is not: at such a point, ``b_i`` between ``g_i`` and ``f_i`` and the other users'
    dampings large make a scene the exact decision proves positive real while the display
    fails -- the witness.
Sufficient
    ``b`` enters ``G^{-1}`` only on its diagonal, so ``M(c)`` is non-decreasing in each ``b_i``
    (Loewner order): a display giving every user a lower bound ``b_i >= f_i`` free of the
    dampings is sufficient when the exact condition holds at the corner ``b_i = f_i`` for every
    value of the other parameters, which is proved conjunct by conjunct from the signs. Otherwise
    the corner (and points just above it) of drawn instances are decided exactly: a scene that is
    not positive real where the display holds is the witness; agreement alone is ``undecided``.

>>> from hapticproof.audit.paperfile import loads
>>> paper = loads('''[paper]
... id = "two"
... title = "two users"
... [scenes.pair]
... system = "multi-user"
... users = 2
... [[equations]]
... id = "1"
... printed = 'b_1 > \\frac{(K_{01} + K_{12})T}{2} + B_{01} + B_{12}'
... claim = "necessary-condition"
... scene = "pair"
... ''')
>>> from hapticproof.audit.claimbase import State
>>> spec = paper.claim("1")
>>> users_condition(State(spec, paper, spec.printed), claim="necessary", exact={}).verdict.value
'confirmed'
"""

from __future__ import annotations

import itertools
from collections.abc import Mapping
from typing import Any

import sympy as sp

from hapticproof.audit.claimbase import ClaimError, State, conjuncts, decide_at_point, witness_json
from hapticproof.audit.compare import NotABound, as_bound
from hapticproof.core.errors import HapticproofError
from hapticproof.core.evidence import Decision, Evidence, Finding, Method, Verdict
from hapticproof.core.naming import marked, marker, role_marker
from hapticproof.core.symbols import c as C_SYM
from hapticproof.exact.canonical import Sampler

__all__ = ["printed_conjuncts", "necessary_bounds", "users_condition"]

#: At most this many points are drawn for a witness, and dampings raised this many times.
DRAWS = 40
RAISES = 24


def _users(state: State) -> int:
    return len(state.model.b)


def printed_conjuncts(state: State) -> list[Any]:
    """The display as a list of concrete relations over the users: index ranges (``i = 1,
    2``) and free indices (over every user) expanded, extrema split (``\\min_i b_i > X`` is
    ``b_i > X`` for each ``i``), names in the scene's symbols."""
    from hapticproof.audit.reader.statements import Qualified, expand_indexed

    m = _users(state)
    statement = state.statement
    table = state.table
    bodies: list[tuple[Any, dict]] = []
    if isinstance(statement, Qualified):
        for rng in statement.ranges:
            values = [v for v in rng.values if getattr(v, "is_Integer", False)]
            if len(values) != len(rng.values):
                raise ClaimError("an index range other than integers cannot be expanded")
        combos = itertools.product(*[[(rng.indices, v) for v in rng.values] for rng in statement.ranges])
        for combo in combos:
            mapping = {}
            for indices, value in combo:
                for index in indices:
                    mapping[index] = sp.Integer(value)
            for relation in statement.body.relations():
                bodies.append((relation.as_sympy(), mapping))
    else:
        for relation in statement.relations():
            bodies.append((relation.as_sympy(), {}))
    out: list[Any] = []
    for body, mapping in bodies:
        for link in conjuncts(body):
            link = link.xreplace(mapping) if mapping else link
            free = _free_indices(link)
            for values in itertools.product(range(1, m + 1), repeat=len(free)):
                concrete = link.xreplace(dict(zip(free, map(sp.Integer, values)))) if free else link
                expanded = expand_indexed(concrete, m, table)
                for part in _split_extrema(expanded):
                    out.append(state.prepare(part))
    return list(dict.fromkeys(out))


def _free_indices(expr: Any) -> list[sp.Symbol]:
    """Index symbols of family members not bound by an extremum or a range."""
    from hapticproof.audit.reader.statements import IndexedExtremum

    bound: set = set()
    for e in sp.sympify(expr).atoms(IndexedExtremum):
        bound |= set(e.indices)
    free = set()
    for x in sp.sympify(expr).atoms(sp.Indexed):
        free |= {i for i in x.indices if isinstance(i, sp.Symbol)}
    return sorted(free - bound, key=str)


def _split_extrema(relation: Any) -> list[Any]:
    """``Min(a, b) > Max(c, d)`` as ``a > c, a > d, b > c, b > d`` (both sides of ``>`` / ``<``)."""
    if not isinstance(relation, sp.core.relational.Relational) or relation.rel_op not in (">", ">=", "<", "<="):
        return [relation]
    big, small = (relation.lhs, relation.rhs) if relation.rel_op in (">", ">=") else (relation.rhs, relation.lhs)
    bigs = list(big.args) if isinstance(big, sp.Min) else [big]
    smalls = list(small.args) if isinstance(small, sp.Max) else [small]
    func = sp.Gt if relation.rel_op in (">", "<") else sp.Ge
    return [func(x, y, evaluate=False) for x in bigs for y in smalls]


def _dampings(state: State) -> list[sp.Symbol]:
    """The users' device dampings as symbols of the model (empty when they are numbers)."""
    return [b for b in state.model.b if isinstance(b, sp.Symbol)]


def necessary_bounds(state: State) -> dict[sp.Symbol, Any]:
    """``b_i -> g_i``: the exact lower bound on each user's damping from ``M_ii(c) >= 0`` at
    every frequency (necessary for ``M(c)`` positive semidefinite)."""
    key = ("users-necessary", state.spec.scene)
    if key in state.cache:
        return state.cache[key]
    from hapticproof.analysis.multiuser import hermitian
    from hapticproof.analysis.positivereal import symbolic_minimum

    M = hermitian(state.model).matrix()
    out: dict[sp.Symbol, Any] = {}
    for i, b in enumerate(state.model.b):
        if not isinstance(b, sp.Symbol):
            continue
        wc = symbolic_minimum(sp.expand(M[i, i] / 2), C_SYM)
        try:
            bound = as_bound(wc.condition, b)
        except (NotABound, TypeError, ValueError):
            continue
        if bound.lower:
            out[b] = bound.bound
    state.cache[key] = out
    return out


def _bounds_on_dampings(printed: list[Any], dampings: list[sp.Symbol]) -> tuple[dict[sp.Symbol, list[Any]], list[Any]]:
    """Each printed conjunct that is a lower bound on one damping free of the dampings, by
    damping; and the conjuncts that are not."""
    by_user: dict[sp.Symbol, list[Any]] = {b: [] for b in dampings}
    others = []
    for rel in printed:
        found = False
        for b in dampings:
            if b not in getattr(rel, "free_symbols", set()):
                continue
            try:
                bound = as_bound(rel, b)
            except (NotABound, TypeError, ValueError):
                continue
            if bound.lower and not (bound.bound.free_symbols & set(dampings)):
                by_user[b].append(bound.bound)
                found = True
                break
        if not found:
            others.append(rel)
    return by_user, others


def _sign(expr: Any) -> int | None:
    """+1 when provably >= 0, -1 when provably <= 0 (from the symbols' signs), else None."""
    expr = sp.sympify(expr)
    if expr == 0:
        return 1
    for form in (sp.factor(sp.cancel(expr)), sp.expand(expr)):
        if form.is_nonnegative:
            return 1
        if form.is_nonpositive:
            return -1
    poly_form = sp.expand(expr)
    symbols = sorted(poly_form.free_symbols, key=str)
    if symbols and all(s.is_nonnegative for s in symbols):
        try:
            poly = sp.Poly(poly_form, *symbols)
        except sp.PolynomialError:
            return None
        if all(cf >= 0 for cf in poly.coeffs()):
            return 1
        if all(cf <= 0 for cf in poly.coeffs()):
            return -1
    return None


def _negative_somewhere(expr: Any, tries: int = 3) -> bool:
    """Whether ``expr`` is negative at one of a few exact points (a cheap look before a proof)."""
    expr = sp.sympify(expr)
    for point in Sampler(sorted(expr.free_symbols, key=str), seed=29).draw(tries):
        value = expr.xreplace(point)
        if value.is_Rational and value < 0:
            return True
    return False


def _not_necessary_witness(state: State, b: sp.Symbol, f: Any, g: Any) -> dict | None:
    """A point where ``b > f`` fails and the scene is positive real (exact decision): ``b``
    between ``g`` and ``f`` where ``f > g``, the other users' dampings raised until it is."""
    gap = sp.sympify(f - g)
    dampings = _dampings(state)
    symbols = sorted((gap.free_symbols | sp.sympify(g).free_symbols) - set(dampings), key=str)
    for point in Sampler(symbols, seed=19).draw(DRAWS):
        try:
            gv, fv = sp.sympify(g).xreplace(point), sp.sympify(f).xreplace(point)
        except (TypeError, ZeroDivisionError):
            continue
        if not (gv.is_Rational and fv.is_Rational) or fv <= gv:
            continue
        values = {**point, b: (fv + gv) / 2}
        witness = _raise_others(state, values, [d for d in dampings if d != b])
        if witness is not None:
            return witness
    return None


def _raise_others(state: State, values: dict, others: list[sp.Symbol]) -> dict | None:
    """``values`` with the other dampings raised (doubling from their necessary bounds) until
    the exact decision proves the scene positive real; the point and the decision, or None."""
    needed = necessary_bounds(state)
    # a witness names every parameter of the scene (those no bound involves at 1)
    values = {**{s: sp.Integer(1) for s in state.model.parameters if s not in values and s not in others}, **values}
    base = {}
    for d in others:
        g = needed.get(d)
        gv = sp.sympify(g).xreplace(values) if g is not None else sp.Integer(1)
        base[d] = (gv if gv.is_Rational and gv > 0 else sp.Integer(0)) + 1
    for k in range(RAISES):
        point = {**values, **{d: base[d] * 2 ** k for d in others}}
        try:
            outcome = decide_at_point(state, point)
        except (HapticproofError, ArithmeticError, ValueError):
            return None
        if outcome.decision == Decision.PROVED:
            return {"point": point, "outcome": outcome}
        if not others:
            return None
    return None


def _holds(relations: list[Any], point: Mapping) -> bool | None:
    from hapticproof.audit.claimbase import holds_at

    results = [holds_at(r, point) for r in relations]
    return None if None in results else all(results)


def _necessary(state: State, printed: list[Any], what: str) -> Finding:
    dampings = _dampings(state)
    needed = necessary_bounds(state)
    by_user, others = _bounds_on_dampings(printed, dampings)
    if others:
        return Finding(Verdict.UNDECIDED, f"{what}: {len(others)} of its conditions bound no single user's damping "
                       f"({marked(others[0])}); only bounds on the dampings are compared with the diagonal of G + G^H",
                       Evidence(Method.INSTANCES, instances=0))
    checked = []
    for b, bounds in by_user.items():
        for f in bounds:
            g = needed.get(b)
            if g is None:
                return Finding(Verdict.UNDECIDED, f"{what}: no exact bound on {b} from the diagonal of G + G^H",
                               Evidence(Method.INSTANCES, instances=0))
            if state.repairing and _negative_somewhere(sp.sympify(g) - f):
                return Finding(Verdict.WRONG, f"{what} is not implied by the diagonal of G + G^H", Evidence(Method.INSTANCES))
            sign = _sign(sp.sympify(g) - f)
            if sign == 1 and not (state.repairing and sp.expand(sp.sympify(g) - f) != 0):
                # a repair must give the bound itself: any weaker bound is necessary too
                checked.append((b, f, g))
                continue
            if state.repairing:
                return Finding(Verdict.WRONG, f"{what} is not implied by the diagonal of G + G^H", Evidence(Method.INSTANCES))
            found = _not_necessary_witness(state, b, f, g)
            if found is None:
                return Finding(Verdict.UNDECIDED, f"{what}: the bound {b} > {marked(f)} is not implied by the necessary "
                               f"bound {b} >= {marked(g)} (from {marker('matrix')}_ii({marker('cos')}) >= 0), and no positive-real scene where it fails "
                               f"was found in {DRAWS} draws", Evidence(Method.INSTANCES, instances=DRAWS))
            point, outcome = found["point"], found["outcome"]
            return Finding(Verdict.WRONG, f"{what} is not necessary: at the witness the scene is positive real (exact "
                           f"decision: {outcome.reason}) while {b} > {marked(f)} fails (the diagonal of G + G^H needs only "
                           f"{b} >= {marked(g)})",
                           Evidence(Method.COUNTEREXAMPLE, witness=witness_json(point),
                                    facts={"recheck": outcome.to_json(), "necessary_bound": sp.Ge(b, g)}),
                           derived=sp.And(*[sp.Ge(x, needed[x]) for x in needed]) if needed else None)
    if not checked:
        return Finding(Verdict.UNDECIDED, f"{what} bounds no user's damping", Evidence(Method.INSTANCES, instances=0))
    state.repairable = True
    derived = sp.And(*[sp.Ge(x, needed[x], evaluate=False) for x in needed]) if len(needed) > 1 else \
        sp.Ge(*next(iter(needed.items())), evaluate=False)
    users = ", ".join(f"{b} > {marked(f)} (<= {marked(g)})" for b, f, g in checked)
    return Finding(Verdict.CONFIRMED, f"{what} is necessary: each bound is implied by a diagonal entry of G + G^H being "
                   f">= 0 at its worst frequency, which positive semidefiniteness requires: {users}",
                   Evidence(Method.ENDPOINT_ANALYSIS, facts={"necessary_bounds": {str(k): v for k, v in needed.items()}}),
                   derived=derived)


def _corner_proof(state: State, by_user: dict[sp.Symbol, list[Any]], exact: Any) -> dict | None:
    """A choice of one bound per user at which the exact condition holds for every value of the
    other parameters (each conjunct proved >= 0 from the signs), or None."""
    if exact is None or not all(by_user.values()):
        return None
    parts = [p for p in conjuncts(exact) if p is not sp.true]
    if any(not isinstance(p, sp.core.relational.Relational) or p.rel_op not in (">=", ">") for p in parts):
        return None
    users = list(by_user)
    for choice in itertools.islice(itertools.product(*[by_user[b] for b in users]), 64):
        corner = dict(zip(users, choice))
        if all(_sign(sp.expand((p.lhs - p.rhs).xreplace(corner))) == 1 for p in parts):
            return corner
    return None


def _sufficient(state: State, printed: list[Any], exact: Any, what: str) -> Finding:
    dampings = _dampings(state)
    by_user, others = _bounds_on_dampings(printed, dampings)
    if not others:
        corner = _corner_proof(state, by_user, exact)
        if corner is not None:
            state.repairable = True
            shown = ", ".join(f"{b} = {marked(v)}" for b, v in corner.items())
            return Finding(Verdict.CONSERVATIVE, f"{what} implies the exact condition: {marker('matrix')}({marker('cos')}) = G^-1 + G^-H is non-decreasing "
                           f"in each damping {role_marker('device_damping', 'b')}_i (Loewner order), and at the corner {shown} every principal-minor "
                           "condition of the exact worst case holds for all values of the other parameters (proved from "
                           "their signs)", Evidence(Method.ENDPOINT_ANALYSIS, facts={"corner": {str(k): v for k, v in corner.items()},
                                                                                    "exact": exact}),
                           derived=exact)
    if state.repairing:
        return Finding(Verdict.WRONG, f"{what} is not proved sufficient", Evidence(Method.INSTANCES))
    found, decided = _insufficient_witness(state, printed, by_user, others)
    if found is not None:
        point, outcome = found
        return Finding(Verdict.WRONG, f"{what} holds at the witness where the scene is not positive real (exact decision: "
                       f"{outcome.reason})", Evidence(Method.COUNTEREXAMPLE, witness=witness_json(point),
                                                     facts={"recheck": outcome.to_json(), "instances": decided}),
                       derived=exact)
    return Finding(Verdict.UNDECIDED, f"{what}: not proved sufficient (no corner of its bounds where the exact condition "
                   f"is proved), and it agrees with the exact decision on {decided} numeric instances, which is no proof",
                   Evidence(Method.INSTANCES, instances=decided), derived=exact)


def _insufficient_witness(state: State, printed: list[Any], by_user: dict, others: list[Any]) -> tuple[Any, int]:
    """Instances where the display holds at (just above) its bounds, decided exactly; the first
    that is not positive real, and the count decided."""
    dampings = _dampings(state)
    params = sorted((s for s in state.model.parameters if s not in dampings), key=str)
    decided = 0
    for point in Sampler(params, seed=23).draw(DRAWS // 2):
        point = {**{s: sp.Integer(1) for s in params if s not in point}, **point}
        for lift in (sp.Rational(1, 1000), sp.Rational(1, 10)):
            values = dict(point)
            for b in dampings:
                bounds = [sp.sympify(f).xreplace(point) for f in by_user.get(b, [])]
                bounds = [v for v in bounds if v.is_Rational]
                values[b] = (max(bounds) if bounds else sp.Integer(0)) + lift
            if _holds(printed, values) is not True:
                continue
            try:
                outcome = decide_at_point(state, values)
            except (HapticproofError, ArithmeticError, ValueError):
                continue
            if outcome.decision not in (Decision.PROVED, Decision.DISPROVED):
                continue
            decided += 1
            if outcome.decision == Decision.DISPROVED:
                return (values, outcome), decided
    return None, decided


def users_condition(state: State, *, claim: str, exact: Mapping[str, Any]) -> Finding:
    """A scalar condition of an m-user scene against the matrix condition (module docstring):
    ``claim`` is ``passivity`` (necessary and sufficient), ``sufficient`` or ``necessary``;
    ``exact`` the exact condition when it has a closed form (``{"condition": ...}``)."""
    printed = printed_conjuncts(state)
    if not printed or any(getattr(r, "rel_op", None) in ("==", "!=", None) for r in printed):
        from hapticproof.audit.claimbase import malformed_finding

        return malformed_finding("the display is not a condition (inequalities) on the parameters")
    what = "the printed condition"
    state.repairable = True             # proofs and exact decisions: a repair search can confirm an edit
    condition = exact.get("condition") if exact else None
    if claim == "necessary":
        return _necessary(state, printed, what)
    suff = _sufficient(state, printed, condition, what)
    if claim == "sufficient" or suff.verdict == Verdict.WRONG:
        return suff
    if suff.verdict == Verdict.CONSERVATIVE:
        nec = _necessary(state, printed, what)
        if nec.verdict == Verdict.CONFIRMED:
            return Finding(Verdict.CONFIRMED, f"{what} is sufficient ({suff.detail[len(what) + 1:]}) and necessary "
                           f"({nec.detail[len(what) + 1:]})", suff.evidence, derived=suff.derived)
        if nec.verdict == Verdict.WRONG:
            return Finding(Verdict.CONSERVATIVE, f"{suff.detail}; it is not necessary: {nec.detail[len(what) + 1:]}",
                           Evidence(Method.COUNTEREXAMPLE, witness=nec.evidence.witness,
                                    facts={**dict(suff.evidence.facts), **dict(nec.evidence.facts)}), derived=suff.derived)
        return Finding(Verdict.UNDECIDED, f"{suff.detail}; whether it is also necessary was not settled ({nec.detail})",
                       suff.evidence, derived=suff.derived)
    if state.repairing:
        return suff
    nec = _necessary(state, printed, what)
    if nec.verdict == Verdict.WRONG:
        return Finding(Verdict.UNDECIDED, f"{nec.detail}; its sufficiency was not settled ({suff.detail})", nec.evidence,
                       derived=suff.derived)
    return suff
