"""What every claim checker shares: the state of a paper-file claim being checked (its scene,
symbols and printed display), reading the printed members and relations, exact decisions of
the scene's model at points, and the comparison of a printed condition with the exact one
(:func:`compare_conditions`: equivalent, sufficient, necessary, or an exact counterexample)."""

from __future__ import annotations

import functools
from collections.abc import Callable, Iterable, Mapping
from dataclasses import dataclass, field
from typing import Any

import sympy as sp

from hapticproof.exact.canonical import Sampler, is_identically_zero
from hapticproof.audit.compare import as_bound, compare_bounds
from hapticproof.core.errors import HapticproofError
from hapticproof.core.evidence import Decision, Evidence, Finding, Method, Outcome, Verdict
from hapticproof.core.naming import marked
from hapticproof.core.symbols import c as C_SYM
from hapticproof.core.symbols import n as N_SYM
from hapticproof.core.symbols import z as Z_SYM

__all__ = ["compare_conditions", "State", "ClaimError"]


PROVED_VERDICTS = (Verdict.CONFIRMED, Verdict.CONSERVATIVE)


class ClaimError(HapticproofError, ValueError):
    """A claim that cannot be checked for this scene (e.g. a residue claim about a network)."""


@dataclass
class State:
    """What a checker works on: the claim, its paper file, and the display text (a mutant's
    text when a repair is being tried)."""

    spec: Any
    source: Any
    printed: str
    equation: Any = None
    repairing: bool = False
    #: set by a checker when its verdict rests on exact symbolic comparisons (a repair search is cheap)
    repairable: bool = False
    cache: dict = field(default_factory=dict)
    #: the change of variables of the region the scene is restricted to (None: none)
    chart: Any = None
    #: the claim and paper file as written, before any region restricted the scene
    origin: Any = None

    @functools.cached_property
    def scene(self) -> Any:
        return self.source.scenes.get(self.spec.scene) if self.spec.scene else None

    @functools.cached_property
    def model(self) -> Any:
        key = ("model", self.spec.scene)
        if key not in self.cache:          # shared by the repair trials of one check
            from hapticproof.systems.naming import with_naming

            # the paper's choice of names for the toolkit's quantities, the scene's roles
            self.cache[key] = with_naming(self.scene, self.scene.build(), self.source.naming().taken)
        return self.cache[key]

    @functools.cached_property
    def table(self) -> Any:
        return self.source.table_for(self.spec.scene)

    @functools.cached_property
    def statement(self) -> Any:
        from hapticproof.audit.reader.printed import parse_printed

        return parse_printed(self.printed, self.table)

    @functools.cached_property
    def names(self) -> dict[str, sp.Symbol]:
        """The model's symbols by name (plus ``n`` for a symbolic delay)."""
        key = ("names", self.spec.scene)
        if key not in self.cache:
            self.cache[key] = _model_symbols(self.scene, self.model)
        return self.cache[key]

    @functools.cached_property
    def values(self) -> dict[str, Any]:
        """Parameter values of the scene by name."""
        key = ("values", self.spec.scene)
        if key not in self.cache:
            self.cache[key] = {sym.name: value for sym, value in self.scene._substitution().items()}
        return self.cache[key]

    def prepare(self, expr: Any) -> Any:
        """A printed expression in the model's symbols: names unified, the scene's values
        substituted, ``t_d = n T`` and the delay ratio ``n`` with the scene's delay, ``omega`` kept."""
        return _prepare(expr, self)


def _model_symbols(scene: Any, model: Any) -> dict[str, sp.Symbol]:
    out: dict[str, sp.Symbol] = {}
    if scene is None:
        return out
    params = getattr(model, "parameters", None)
    if params is None and isinstance(model, sp.MatrixBase):
        params = set().union(*(e.free_symbols for e in model)) - {sp.Symbol("s")}
    for sym in params or ():
        out[sym.name] = sym
    roles = [scene.role(field) for field in ("device_damping", "period") if field in _roles_of(scene)]
    for name in [*roles, "K", "B", "z_a"]:
        if name is not None:
            out.setdefault(name, scene.symbol(name))
    out.setdefault("n", N_SYM)
    return out


def _roles_of(scene: Any) -> tuple[str, ...]:
    from hapticproof.systems.roles import ROLES

    return tuple(ROLES[scene.system])


def _period_name(state: State) -> str:
    """The scene's sampling period (its role; ``T`` without a scene)."""
    scene = state.scene
    return scene.role("period") if scene is not None and "period" in _roles_of(scene) else "T"


def _delay_of(state: State) -> Any:
    model = state.model
    delay = getattr(model, "delay", None)
    if delay is None:
        delays = getattr(model, "delays", None)
        if delays and len(set(delays)) == 1:
            return sp.Integer(delays[0])
        return None
    return sp.sympify(delay)


def _prepare(expr: Any, state: State) -> Any:
    expr = sp.sympify(expr)
    free = expr.free_symbols if isinstance(expr, sp.Basic) else set()
    rename = {}
    values = state.values
    for sym in free:
        if not isinstance(sym, sp.Symbol) or sym in (Z_SYM, sp.Symbol("s"), C_SYM):
            continue
        if sym.name in values:
            rename[sym] = values[sym.name]
        elif sym.name in state.names and state.names[sym.name] != sym:
            rename[sym] = state.names[sym.name]
    delay = _delay_of(state) if state.scene is not None else None
    if delay is not None and delay.is_Integer and "n" not in values:
        # the printed delay ratio n of a scene with a numeric delay is that delay
        rename.update({sym: delay for sym in free if getattr(sym, "name", None) == "n"})
    if rename:
        expr = expr.xreplace(rename)
    t_d = next((s for s in expr.free_symbols if getattr(s, "name", None) == "t_d"), None) if isinstance(expr, sp.Basic) else None
    if t_d is not None and state.scene is not None and "t_d" not in values:
        delay = _delay_of(state)
        if delay is not None:
            period = _period_name(state)
            T = values.get(period, state.names.get(period))
            expr = expr.xreplace({t_d: delay * T})
    return expr


def frequency_symbol(state: State) -> sp.Symbol | None:
    """The printed frequency symbol (``\\omega``), if the file declares it."""
    return state.table.lookup(r"\omega")


def period_of(state: State) -> Any:
    period = _period_name(state)
    return state.values.get(period, state.names.get(period))


def display_members(statement: Any) -> list[Any]:
    """Every member of every relation chain of the display, or its expression(s)."""
    relations = statement.relations()
    if relations:
        return [t for r in relations for t in r.terms]
    return list(statement.expressions())


def claimed_members(state: State, members: Iterable[Any]) -> list[Any]:
    """Members that state the claimed object: expressions free of unknown functions, or such an
    expression times one signal (``bV_h(z) + ...`` reads ``b + ...``); a bare signal, a bare
    name that is not a parameter of the scene (a label such as ``r``) and a ratio of signals
    (``F_h/V_h``) are not."""
    signals = state.source.signals()
    out = []
    for member in members:
        if isinstance(member, sp.MatrixBase):
            out.append(member)
            continue
        member = sp.sympify(member)
        if member.atoms(sp.core.function.AppliedUndef):
            continue
        present = {s for s in member.free_symbols if s in signals}
        if not present:
            if isinstance(member, sp.Symbol) and member.name not in state.names and member.name not in state.values:
                continue
            out.append(member)
            continue
        if len(present) != 1:
            continue
        (signal,) = present
        coeff = sp.cancel(sp.together(member / signal))
        if coeff.has(signal) or coeff == 1:
            continue
        out.append(coeff)
    return out


def _single_relation(state: State) -> Any:
    relations = state.statement.relations()
    if len(relations) != 1:
        return None
    return relations[0].as_sympy()


def decide_model(model: Any, system: str) -> Outcome:
    if system == "single-user":
        from hapticproof.analysis.positivereal import positive_real

        return positive_real(model)
    if system == "multi-user":
        from hapticproof.analysis.multiuser import positive_real

        return positive_real(model)
    if system == "teleoperator":
        from hapticproof.analysis.teleoperator import passivity

        return passivity(model)
    raise ClaimError("passivity decisions apply to single-user, multi-user and teleoperator scenes")


def numeric_scene_at(state: State, point: Mapping[Any, Any]) -> Any:
    """The scene with the point's values (missing parameters 1, a symbolic delay 1)."""
    scene = state.scene
    values: dict[str, Any] = {}
    delay = None
    model_free = {s.name for s in getattr(state.model, "parameters", set())} - {"n"}
    for key, value in point.items():
        name = key if isinstance(key, str) else key.name
        # the circle's c is no parameter; a paper's own c is (its symbol is kept apart from the circle's)
        circle = key == C_SYM if not isinstance(key, str) else ("\x1f" in name or name == "c" and "c" not in model_free)
        if circle:
            continue
        if name == "n":
            delay = int(value)
            continue
        values[name] = value
    for name in model_free - set(values):
        values[name] = sp.Integer(1)
    params = {k: v for k, v in values.items() if k in model_free or k in dict(scene.params)}
    numeric = scene.with_params(params)
    if scene.delay == "n":
        numeric = numeric.replace(delay=delay if delay is not None else 1)
    return numeric


def decide_at_point(state: State, point: Mapping[Any, Any]) -> Outcome:
    numeric = numeric_scene_at(state, point)
    return decide_model(numeric.build(), numeric.system)


def holds_at(condition: Any, point: Mapping[Any, Any]) -> bool | None:
    """Exact truth of a condition (relational or And) at a point; None when undecidable.

    Rational conditions at rational points are evaluated in exact fractions, without building
    SymPy expressions (the samplers call this thousands of times); anything else by
    substitution."""
    fast = _fraction_truth(condition, point)
    if fast is not _UNKNOWN:
        return fast
    try:
        value = sp.sympify(condition).xreplace(dict(point))
    except (TypeError, ZeroDivisionError):
        return None
    return _truth(value)


_UNKNOWN = object()


def _fraction_truth(condition: Any, point: Mapping[Any, Any]) -> Any:
    from fractions import Fraction

    values = {}
    for key, value in point.items():
        if isinstance(value, sp.Rational):
            values[key] = Fraction(int(value.p), int(value.q))
        elif isinstance(value, int) and not isinstance(value, bool):
            values[key] = Fraction(value)
        else:
            return _UNKNOWN
    try:
        return _truth_of(sp.sympify(condition), values)
    except _NotRational:
        return _UNKNOWN


class _NotRational(Exception):
    """A node the fraction evaluator does not take (a function, an irrational, a free symbol)."""


def _truth_of(cond: Any, values: Mapping[Any, Any]) -> bool | None:
    if cond is sp.true or cond is sp.false:
        return bool(cond)
    if isinstance(cond, (sp.And, sp.Or)):
        parts = [_truth_of(a, values) for a in cond.args]
        if None in parts:
            return None
        return all(parts) if isinstance(cond, sp.And) else any(parts)
    if isinstance(cond, sp.core.relational.Relational) and cond.rel_op in (">", ">=", "<", "<=", "==", "!="):
        try:
            diff = _fraction_value(cond.lhs, values) - _fraction_value(cond.rhs, values)
        except ZeroDivisionError:
            return None
        return {">": diff > 0, ">=": diff >= 0, "<": diff < 0, "<=": diff <= 0, "==": diff == 0, "!=": diff != 0}[cond.rel_op]
    raise _NotRational


def _fraction_value(expr: Any, values: Mapping[Any, Any]) -> Any:
    from fractions import Fraction

    if isinstance(expr, sp.Rational):
        return Fraction(int(expr.p), int(expr.q))
    if isinstance(expr, sp.Symbol):
        if expr in values:
            return values[expr]
        raise _NotRational
    if isinstance(expr, sp.Add):
        return sum((_fraction_value(a, values) for a in expr.args), Fraction(0))
    if isinstance(expr, sp.Mul):
        out = Fraction(1)
        for a in expr.args:
            out *= _fraction_value(a, values)
        return out
    if isinstance(expr, sp.Pow) and expr.exp.is_Integer:
        base = _fraction_value(expr.base, values)
        return base ** int(expr.exp)
    if isinstance(expr, sp.Abs):
        return abs(_fraction_value(expr.args[0], values))
    if isinstance(expr, (sp.Min, sp.Max)):
        items = [_fraction_value(a, values) for a in expr.args]
        return min(items) if isinstance(expr, sp.Min) else max(items)
    raise _NotRational


def _truth(value: Any) -> bool | None:
    if value in (sp.true, sp.false) or isinstance(value, bool):
        return bool(value)
    if isinstance(value, sp.And):
        parts = [_truth(a) for a in value.args]
        return None if None in parts else all(parts)
    if isinstance(value, sp.Or):
        parts = [_truth(a) for a in value.args]
        return None if None in parts else any(parts)
    if isinstance(value, sp.core.relational.Relational):
        diff = value.lhs - value.rhs
        if isinstance(diff, sp.Basic) and diff.free_symbols:
            return None
        if diff.has(sp.zoo, sp.nan, sp.oo, -sp.oo):
            return None
        diff = sp.nsimplify(diff) if diff.is_Float else diff
        if not diff.is_Rational:
            approx = sp.N(diff, 50)
            if not approx.is_real or abs(approx) < sp.Float("1e-40"):
                return None
            diff = sp.Rational(approx)
        return bool(value.func(diff, 0))
    return None


def conjuncts(condition: Any) -> list[Any]:
    if isinstance(condition, sp.And):
        return [r for a in condition.args for r in conjuncts(a)]
    return [condition]


@functools.lru_cache(maxsize=512)
def _bound(condition: Any, var: sp.Symbol) -> Any:
    """:func:`~hapticproof.audit.compare.as_bound`, remembered (the exact side repeats across repairs);
    ``None`` when the condition is not a bound on ``var``."""
    try:
        return as_bound(condition, var)
    except (TypeError, ValueError, sp.PolynomialError):
        return None


@functools.lru_cache(maxsize=256)
def _drop_trivial(condition: Any) -> Any:
    """An And without the parts that hold for every admissible value (e.g. ``K T >= 0``)."""
    parts = []
    for rel in conjuncts(condition):
        if isinstance(rel, sp.core.relational.Relational) and rel.rel_op in (">=", ">", "<=", "<"):
            diff = (rel.lhs - rel.rhs) if rel.rel_op in (">=", ">") else (rel.rhs - rel.lhs)
            diff = sp.factor(sp.cancel(diff))
            if (rel.rel_op in (">=", "<=") and diff.is_nonnegative) or diff.is_positive:
                continue
        if rel is sp.true:
            continue
        parts.append(rel)
    if not parts:
        return sp.true
    return parts[0] if len(parts) == 1 else sp.And(*parts)


@functools.lru_cache(maxsize=256)
def _drop_implied(condition: Any) -> Any:
    """An And without the conjuncts another one implies: two lower bounds on one parameter, one
    provably above the other (``b_s >= X`` makes ``b_s + u >= X`` redundant when ``u >= 0``)."""
    parts = conjuncts(condition)
    if len(parts) < 2:
        return condition
    dropped: set[int] = set()
    for i, p in enumerate(parts):
        for j, q in enumerate(parts):
            if i == j or i in dropped or j in dropped:
                continue
            for var in sorted(sp.sympify(q).free_symbols - {C_SYM}, key=str):
                bp, bq = _bound(p, var), _bound(q, var)
                if bp is None or bq is None or not (bp.lower and bq.lower):
                    continue
                difference = sp.factor(sp.cancel(bp.bound - bq.bound))
                if difference.is_nonnegative:
                    dropped.add(j)
                    break
    kept = [p for k, p in enumerate(parts) if k not in dropped]
    return kept[0] if len(kept) == 1 else sp.And(*kept)


def preferred_variables(state: State) -> list[str]:
    order = []
    if state.spec.solve_for:
        order.append(state.spec.solve_for)
    scene = state.scene
    if scene is None or scene.system == "network":
        return order + ["b"]
    # the device damping (its role), then a user's or a robot's
    role = scene.role
    if scene.system == "multi-user":
        return order + [n for n in (role("device_damping"), scene.members("device_damping")[0]) if n is not None]
    if scene.system == "teleoperator":
        return order + [role("device_damping"), role("master_damping"), role("slave_damping")]
    return order + [role("device_damping")]


def _variable(printed: Any, exact: Any, state: State) -> sp.Symbol | None:
    """A parameter that both conditions bound from below (affine, positive coefficient)."""
    if isinstance(printed, sp.And) or isinstance(exact, sp.And):
        return None
    if not isinstance(printed, sp.core.relational.Relational) or not isinstance(exact, sp.core.relational.Relational):
        return None
    free = sorted((printed.free_symbols | exact.free_symbols) - {C_SYM}, key=str)
    by_name = {s.name: s for s in free}
    candidates = [by_name[n] for n in preferred_variables(state) if n in by_name] + [s for s in free if s.name not in preferred_variables(state)]
    for var in candidates:
        e = _bound(exact, var)
        if e is None or not getattr(e, "lower", True):
            continue
        p = _bound(printed, var)
        if p is not None and getattr(p, "lower", True):
            return var
    return None


def separating_points(printed: Any, exact: Any, tries: int = 300) -> tuple[dict | None, dict | None, int]:
    """Exact points where the printed condition holds and the exact one fails, and conversely."""
    free = sorted((sp.sympify(printed).free_symbols | sp.sympify(exact).free_symbols), key=str)
    weaker = stronger = None
    count = 0
    for point in Sampler(free, seed=3).draw(tries):
        hp, he = holds_at(printed, point), holds_at(exact, point)
        if hp is None or he is None:
            continue
        count += 1
        if hp and not he and weaker is None:
            weaker = point
        if he and not hp and stronger is None:
            stronger = point
        if weaker is not None and stronger is not None:
            break
    return weaker, stronger, count


def ratio_equivalent(printed: Any, exact: Any) -> bool:
    """``P op 0`` and ``E op 0`` with ``P = r E``, ``r`` provably positive (same relation up to strictness)."""
    if not (isinstance(printed, sp.core.relational.Relational) and isinstance(exact, sp.core.relational.Relational)):
        return False
    ops = {">": 1, ">=": 1, "<": -1, "<=": -1}
    if printed.rel_op not in ops or exact.rel_op not in ops:
        return False
    fp = (printed.lhs - printed.rhs) * ops[printed.rel_op]
    fe = (exact.lhs - exact.rhs) * ops[exact.rel_op]
    if fe == 0:
        return False
    # the ratio at a few exact points first: a positive constant r is proved by P - r E = 0; a
    # ratio that changes sign is no positive factor; only a varying positive ratio is factored
    ratios = _ratios_at_points(fp, fe)
    if ratios is not None:
        if any(r <= 0 for r in ratios):
            return False
        if len(set(ratios)) == 1:
            r = sp.Rational(ratios[0].numerator, ratios[0].denominator)
            if is_identically_zero(sp.expand(fp - r * fe)):
                return True
        if sp.count_ops(fp) + sp.count_ops(fe) > _FACTOR_LIMIT:
            return False          # no varying positive factor is sought between large forms
    ratio = sp.factor(sp.cancel(sp.together(fp / fe)))
    return bool(ratio.is_positive)


def constant_positive_ratio(fp: Any, fe: Any) -> bool | None:
    """Whether ``fp/fe`` is one positive constant at a few exact points: ``False`` when it is
    not (a varying or non-positive ratio), ``None`` when it cannot be evaluated so (a look,
    never a proof)."""
    ratios = _ratios_at_points(fp, fe)
    if ratios is None:
        return None
    return len(set(ratios)) == 1 and ratios[0] > 0


#: Size (operations) above which a varying positive ratio of two conditions is not factored.
_FACTOR_LIMIT = 300


def _ratios_at_points(fp: Any, fe: Any, count: int = 4) -> list[Any] | None:
    """``fp/fe`` at a few exact points (fractions), or None when they cannot be evaluated so."""
    free = sorted(sp.sympify(fp).free_symbols | sp.sympify(fe).free_symbols, key=str)
    out = []
    for point in Sampler(free, seed=37).draw(count + 2)[1:]:
        fast = {}
        for key, value in point.items():
            if not isinstance(value, sp.Rational):
                return None
            from fractions import Fraction

            fast[key] = Fraction(int(value.p), int(value.q))
        try:
            num, den = _fraction_value(sp.sympify(fp), fast), _fraction_value(sp.sympify(fe), fast)
        except (_NotRational, ZeroDivisionError):
            return None
        if den == 0:
            continue
        out.append(num / den)
        if len(out) == count:
            break
    return out or None


def witness_json(point: Mapping[Any, Any]) -> dict[str, Any]:
    return {(k if isinstance(k, str) else k.name): v for k, v in point.items()}


def compare_conditions(printed: Any, exact: Any, state: State, *, claim: str, what: str,
                       verify: Callable[[dict], Outcome] | None = None, derived: Any = None) -> Finding:
    """Compare a printed condition with the exact necessary-and-sufficient one, as the claim
    says (``passivity`` / ``sufficient`` / ``necessary``): bounds when both bound one parameter
    (:func:`~hapticproof.audit.compare.compare_bounds`), else a proof of equivalence up to a
    positive factor or exact sampling (witnesses re-checked by ``verify``).

    >>> from hapticproof.audit.paperfile import loads, TEMPLATE
    >>> paper = loads(TEMPLATE)
    >>> spec = paper.claim("3")
    >>> state = State(spec, paper, spec.printed)
    >>> b, K, T, B = (state.names[name] for name in ("b", "K", "T", "B"))
    >>> exact = sp.Ge(b, K*T/2 + B)
    >>> [compare_conditions(printed, exact, state, claim=claim, what="b > KT").verdict.value
    ...  for printed, claim in ((sp.Gt(b, K*T + B), "passivity"), (sp.Gt(b, K*T + B), "necessary"))]
    ['conservative', 'wrong']
    """
    derived = exact if derived is None else derived
    exact = _drop_implied(_drop_trivial(exact))
    if exact in (sp.true, sp.false):
        return _constant_exact(printed, exact, state, claim, what, derived)
    paired = _compare_conjunctions(printed, exact, state, claim, what, verify, derived)
    if paired is not None:
        return paired
    var = _variable(printed, exact, state)
    if state.repairing:
        quick = _quick_reject(printed, exact, var, claim)
        if quick is not None:
            return quick
    if var is not None:
        state.repairable = True
        try:
            if claim == "necessary":
                f = compare_bounds(exact, printed, var, what=what)
                return _necessary_from_bounds(f, state, verify, what, derived)
            return compare_bounds(printed, exact, var, verify=verify, what=what)
        except AssertionError as err:          # a witness the exact decision did not confirm
            return Finding(Verdict.UNDECIDED, f"{what}: {err}", Evidence(Method.COUNTEREXAMPLE), derived=derived)
        except (TypeError, ValueError):
            pass
    if ratio_equivalent(printed, exact):
        state.repairable = True
        return Finding(Verdict.CONFIRMED, f"{what} is the exact condition {marked(exact)} multiplied by a positive factor",
                       Evidence(Method.CANONICAL_FORM, facts={"exact": exact, "printed_form": ("equals", sp.srepr(exact))}),
                       derived=derived)
    corner = _corner_sufficiency(printed, exact) if claim != "necessary" else None
    weaker, stronger, count = separating_points(printed, exact, tries=60 if state.repairing else 300)
    state.repairable = True
    if corner is not None and weaker is None:
        shown = ", ".join(f"{v} = {marked(b)}" for v, b in corner.items())
        proof = (f"{what} implies the exact condition {marked(exact)}: the exact condition is nondecreasing in "
                 f"{', '.join(str(v) for v in corner)} and holds at the corner {shown} of the printed bounds")
        facts = {"exact": exact, "corner": {str(k): v for k, v in corner.items()}}
        if stronger is not None:
            return Finding(Verdict.CONSERVATIVE, f"{proof}; it is not necessary (it fails at the witness where the exact "
                           "condition holds)", Evidence(Method.ENDPOINT_ANALYSIS, witness=witness_json(stronger), facts=facts),
                           derived=derived)
        if claim == "sufficient":
            return Finding(Verdict.CONFIRMED, proof, Evidence(Method.ENDPOINT_ANALYSIS, facts=facts), derived=derived)
        return Finding(Verdict.UNDECIDED, f"{proof} (sufficient, proved); whether it is also necessary was not decided "
                       f"({count} exact samples)", Evidence(Method.INSTANCES, instances=count, facts=facts), derived=derived)
    if weaker is not None and claim != "necessary":
        return _witness_finding(weaker, state, verify, what, derived, Decision.DISPROVED,
                                "it holds at the witness where the exact condition fails")
    if stronger is not None and claim == "necessary":
        return _witness_finding(stronger, state, None, what, derived, Decision.PROVED,
                                "it fails at the witness where the exact condition holds (not necessary)")
    note = ""
    if stronger is not None:
        note = "; it is not necessary (it fails at a point where the exact condition holds)"
    return Finding(Verdict.UNDECIDED,
                   f"{what} is not a positive multiple or a bound comparable with the exact condition {marked(exact)}, "
                   f"and no counterexample was found in {count} exact samples{note}",
                   Evidence(Method.INSTANCES, instances=count,
                            witness=witness_json(stronger) if stronger is not None else None, facts={"exact": exact}),
                   derived=derived)


def _pairs(printed: Any, exact: Any) -> list[tuple[Any, Any, sp.Symbol]] | None:
    """Printed and exact conjunctions that bound the same parameters from below, one conjunct
    each (``b_m > KT + 2B, b_s > KT + 2B`` against ``b_m >= ..., b_s >= ...``), matched by
    parameter; None when they are not."""
    p_parts, e_parts = conjuncts(printed), conjuncts(exact)
    if len(e_parts) < 2 or len(p_parts) != len(e_parts):
        return None
    out = []
    used: set[int] = set()
    for e in e_parts:
        match = None
        for var in sorted(sp.sympify(e).free_symbols - {C_SYM}, key=str):
            eb = _bound(e, var)
            if eb is None or not eb.lower or eb.bound.has(*[v for *_x, v in out]):
                continue
            for k, p in enumerate(p_parts):
                pb = _bound(p, var) if k not in used else None
                if pb is not None and pb.lower:
                    match = (k, p, var)
                    break
            if match:
                break
        if match is None:
            return None
        used.add(match[0])
        out.append((match[1], e, match[2]))
    variables = [v for *_x, v in out]
    if len(set(variables)) != len(variables):
        return None
    return out


def _compare_conjunctions(printed: Any, exact: Any, state: State, claim: str, what: str,
                          verify: Callable | None, derived: Any) -> Finding | None:
    """Conjunctions of bounds on distinct parameters, compared bound by bound; a witness of one
    bound is completed with the others' parameters above both their bounds (so the rest of both
    conditions holds there) and re-checked by ``verify``."""
    if not (isinstance(printed, sp.And) and isinstance(exact, sp.And)):
        return None
    pairs = _pairs(printed, exact)
    if pairs is None:
        return None
    if state.repairing:
        return _quick_conjunctions(pairs, claim, what, exact, derived)
    findings = []
    for p, e, var in pairs:
        try:
            f = compare_bounds(e, p, var, what=what) if claim == "necessary" else compare_bounds(p, e, var, what=what)
        except (TypeError, ValueError, AssertionError):
            return None
        findings.append((f, p, e, var))
    state.repairable = True
    verdicts = {f.verdict for f, *_ in findings}
    if verdicts == {Verdict.CONFIRMED}:
        return Finding(Verdict.CONFIRMED, f"{what} is equivalent to the exact condition {marked(exact)}, bound by bound "
                       f"({', '.join(str(v) for *_x, v in findings)})", Evidence(Method.CANONICAL_FORM, facts={"exact": exact}),
                       derived=derived)
    if verdicts <= {Verdict.CONFIRMED, Verdict.CONSERVATIVE}:
        if claim == "necessary":
            return Finding(Verdict.CONFIRMED, f"{what} is necessary: the exact condition implies it bound by bound",
                           Evidence(Method.ENDPOINT_ANALYSIS, facts={"exact": exact}), derived=derived)
        return Finding(Verdict.CONSERVATIVE, f"{what} implies the exact condition bound by bound (a bound exceeds the exact "
                       "one) but not conversely", Evidence(Method.ENDPOINT_ANALYSIS, facts={"exact": exact}), derived=derived)
    bad = next(((f, p, e, var) for f, p, e, var in findings if f.verdict == Verdict.WRONG and f.evidence.witness), None)
    if bad is None or state.repairing:
        if state.repairing:
            return Finding(Verdict.WRONG, f"{what} differs from the exact condition", Evidence(Method.INSTANCES))
        return None
    f, _p, _e, var = bad
    point = {sp.Symbol(k) if isinstance(k, str) else k: v for k, v in f.evidence.witness.items()}
    by_name = {getattr(k, "name", k): v for k, v in point.items()}
    for _f2, p2, e2, var2 in findings:
        if var2 == var:
            continue
        levels = []
        for cond in (p2, e2):
            bound = _bound(cond, var2)
            value = sp.sympify(bound.bound).xreplace({s: by_name[s.name] for s in bound.bound.free_symbols
                                                      if s.name in by_name})
            if not value.is_Rational:
                return None
            levels.append(value)
        by_name[var2.name] = max(levels) + 1
    witness = dict(by_name)
    facts: dict[str, Any] = {"exact": exact, "differs_in": var.name}
    expected = Decision.PROVED if claim == "necessary" else Decision.DISPROVED
    if verify is not None:
        check = verify(witness)
        facts["recheck"] = check.to_json()
        if check.decision != expected:
            return Finding(Verdict.UNDECIDED, f"{what}: the witness {witness_json(witness)} was not confirmed by the exact "
                           f"decision ({check.reason})", Evidence(Method.COUNTEREXAMPLE, witness=witness_json(witness),
                                                                   facts=facts), derived=derived)
    how = ("it fails at the witness where the exact condition holds (not necessary)" if claim == "necessary"
           else "it holds at the witness where the exact condition fails")
    return Finding(Verdict.WRONG, f"{what}: its bound on {var} is weaker than the exact one; {how}",
                   Evidence(Method.COUNTEREXAMPLE, witness=witness_json(witness), facts=facts), derived=derived)


def _lower_bounds(printed: Any) -> dict[sp.Symbol, Any] | None:
    """``{b_m: X, b_s: Y}`` of a printed ``b_m > X, b_s > Y`` (one lower bound per parameter, no
    bound mentioning a bounded parameter), else ``None``."""
    parts = printed.args if isinstance(printed, sp.And) else (printed,)
    bounds: dict[sp.Symbol, Any] = {}
    for rel in parts:
        if isinstance(rel, (sp.Gt, sp.Ge)) and rel.lhs.is_Symbol:
            var, bound = rel.lhs, rel.rhs
        elif isinstance(rel, (sp.Lt, sp.Le)) and rel.rhs.is_Symbol:
            var, bound = rel.rhs, rel.lhs
        else:
            return None
        if var in bounds:
            return None
        bounds[var] = bound
    if any(b.has(v) for b in bounds.values() for v in bounds):
        return None
    return bounds


def _corner_sufficiency(printed: Any, exact: Any) -> dict[sp.Symbol, Any] | None:
    """The corner of a printed conjunction of lower bounds where the exact condition ``f >= 0``
    is proved to hold, when ``f`` is proved nondecreasing in each bounded parameter (its partial
    derivative nonnegative under the parameters' signs) and every bound is nonnegative: then the
    printed condition is sufficient (``f`` only grows from the corner to any point it admits).
    ``None`` when any step is not proved (the teleoperator's ``b_m b_s/(b_m + b_s) >= B + KT/2``
    against ``b_m, b_s > KT + 2B``: the corner gives ``B + KT/2 - (B + KT/2) = 0``)."""
    bounds = _lower_bounds(printed)
    if not bounds or not isinstance(exact, (sp.Ge, sp.Gt, sp.Le, sp.Lt)):
        return None
    f = exact.lhs - exact.rhs if isinstance(exact, (sp.Ge, sp.Gt)) else exact.rhs - exact.lhs
    if not (f.free_symbols & set(bounds)):
        return None
    for var, bound in bounds.items():
        if not (var.is_nonnegative and sp.cancel(bound).is_nonnegative):
            return None
        if not sp.factor(sp.cancel(sp.diff(f, var))).is_nonnegative:
            return None
    at_corner = sp.factor(sp.cancel(f.xreplace(bounds)))
    if not (at_corner.is_nonnegative or (isinstance(exact, (sp.Ge, sp.Le)) and at_corner == 0)):
        return None
    if isinstance(exact, (sp.Gt, sp.Lt)) and at_corner == 0 and not all(isinstance(r, (sp.Gt, sp.Lt))
                                                                         for r in (printed.args if isinstance(printed, sp.And) else (printed,))):
        return None
    return bounds


def _quick_conjunctions(pairs: list[tuple[Any, Any, sp.Symbol]], claim: str, what: str, exact: Any,
                        derived: Any) -> Finding:
    """While searching repairs: a trial is kept only when every bound is the exact one (or, for
    a sufficient condition, provably above it); a numeric look rejects the others first."""
    from hapticproof.audit.compare import sign_on_box

    reject = Finding(Verdict.WRONG, f"{what} differs from the exact condition", Evidence(Method.INSTANCES))
    above = False
    for p, e, var in pairs:
        pb, eb = _bound(p, var), _bound(e, var)
        if pb is None or eb is None or not pb.lower:
            return reject
        if claim == "sufficient":
            difference = sp.cancel(pb.bound - eb.bound)
            if is_identically_zero(difference):
                continue
            if numerically_negative(difference) or sign_on_box(difference) != 1:
                return reject
            above = True
            continue
        if numerically_different(pb.bound, eb.bound) or not is_identically_zero(pb.bound - eb.bound):
            return reject
    if above:
        return Finding(Verdict.CONSERVATIVE, f"{what} implies the exact condition bound by bound",
                       Evidence(Method.ENDPOINT_ANALYSIS, facts={"exact": exact}), derived=derived)
    return Finding(Verdict.CONFIRMED, f"{what} is equivalent to the exact condition {marked(exact)}, bound by bound",
                   Evidence(Method.CANONICAL_FORM, facts={"exact": exact}), derived=derived)


def numerically_negative(expr: Any, tries: int = 2) -> bool:
    """``expr < 0`` at one of a few exact points (never used to prove, only to skip)."""
    expr = sp.sympify(expr)
    for point in Sampler(sorted(expr.free_symbols, key=str), seed=13).draw(tries + 1)[1:]:
        try:
            value = expr.xreplace(point)
        except (TypeError, ZeroDivisionError):
            continue
        if value.is_Rational and value < 0:
            return True
    return False


def numerically_different(a: Any, b: Any, tries: int = 2) -> bool:
    """``a != b`` seen at exact random points (never used to prove equality, only to skip)."""
    free = sorted((sp.sympify(a).free_symbols | sp.sympify(b).free_symbols), key=str)
    ranges = {s: (sp.Rational(1, 3), sp.Integer(3)) for s in free if not s.is_integer}
    ranges.update({s: (2, 3) for s in free if s.is_integer})
    if C_SYM in ranges:
        ranges[C_SYM] = (sp.Rational(-9, 10), sp.Rational(9, 10))
    for point in Sampler(free, seed=13, ranges=ranges).draw(tries + 1)[1:]:
        try:
            value = sp.N((sp.sympify(a) - sp.sympify(b)).xreplace(point), 30)
        except (TypeError, ValueError, ZeroDivisionError):
            continue
        if value.is_number and value.is_finite and abs(value) > sp.Float("1e-15"):
            return True
    return False


def positive_ratio_at_points(printed: Any, exact: Any) -> bool:
    """Whether ``P/E`` (as ``... > 0`` forms) is positive at two exact points (a cheap look
    before the symbolic ratio test)."""
    ops = {">": 1, ">=": 1, "<": -1, "<=": -1}
    rels = (printed, exact)
    if not all(isinstance(r, sp.core.relational.Relational) and r.rel_op in ops for r in rels):
        return False
    fp, fe = ((r.lhs - r.rhs) * ops[r.rel_op] for r in rels)
    free = sorted(fp.free_symbols | fe.free_symbols, key=str)
    for point in Sampler(free, seed=17).draw(3)[1:]:
        try:
            ratio = sp.N((fp / fe).xreplace(point), 20)
        except (TypeError, ZeroDivisionError):
            return False
        if not ratio.is_number or not ratio.is_finite or not ratio > 0:
            return False
    return True


def _quick_reject(printed: Any, exact: Any, var: sp.Symbol | None, claim: str) -> Finding | None:
    """While searching repairs, a mutant is kept only when it may be confirmed (or, for a
    sufficient condition, conservative): skip the others without a full comparison."""
    reject = Finding(Verdict.WRONG, "not equivalent to the exact condition", Evidence(Method.INSTANCES))
    if var is None:
        if claim == "passivity" and _disagree_somewhere(printed, exact):
            return reject
        if not positive_ratio_at_points(printed, exact):
            return reject
        return None if ratio_equivalent(printed, exact) else reject
    p, e = _bound(printed, var), _bound(exact, var)
    if p is None or e is None or getattr(p, "lower", True) != getattr(e, "lower", True):
        return reject
    if claim == "sufficient":
        return None
    if numerically_different(p.bound, e.bound):
        return reject
    return None


def _disagree_somewhere(printed: Any, exact: Any, tries: int = 40) -> bool:
    """Whether the two conditions differ in truth at one of a few exact points (a look that
    only ever rejects; equivalent conditions never disagree)."""
    free = sorted((sp.sympify(printed).free_symbols | sp.sympify(exact).free_symbols) - {C_SYM}, key=str)
    for point in Sampler(free, seed=31).draw(tries):
        a, b = holds_at(printed, point), holds_at(exact, point)
        if a is not None and b is not None and a != b:
            return True
    return False


def _proved_always(printed: Any) -> bool:
    """A printed condition proved to hold for every admissible value by the parameters' signs:
    ``lhs - rhs`` positive (or non-negative for ``>=``) by SymPy's sign rules, at both ends
    ``c = -1, 1`` when it is affine in ``c = cos(omega T)`` (its least value is at an end)."""
    parts = printed.args if isinstance(printed, sp.And) else (printed,)
    for part in parts:
        if not isinstance(part, sp.core.relational.Relational) or part.rel_op not in (">", ">=", "<", "<="):
            return False
        gap = sp.expand(part.lhs - part.rhs if part.rel_op in (">", ">=") else part.rhs - part.lhs)
        strict = part.rel_op in (">", "<")
        ends = [gap]
        if gap.has(C_SYM):
            if not gap.is_polynomial(C_SYM) or sp.degree(gap, C_SYM) > 1:
                return False
            ends = [gap.subs(C_SYM, -1), gap.subs(C_SYM, 1)]
        if not all((e.is_positive if strict else e.is_nonnegative) is True for e in map(sp.expand, ends)):
            return False
    return True


def _constant_exact(printed: Any, exact: Any, state: State, claim: str, what: str, derived: Any) -> Finding:
    """The exact condition holds for every admissible value (``True``) or for none (``False``)."""
    state.repairable = True
    if exact is sp.true and (_drop_trivial(printed) is sp.true or _proved_always(printed)):
        return Finding(Verdict.CONFIRMED, f"{what} and the exact condition both hold for every admissible value of the "
                       "parameters", Evidence(Method.CANONICAL_FORM, facts={"exact": derived,
                                                              "printed_form": ("holds for every admissible value",)}),
                       derived=derived)
    free = sorted(sp.sympify(printed).free_symbols, key=str)
    points = Sampler(free, seed=3).draw(200 if not state.repairing else 40)
    fails = next((p for p in points if holds_at(printed, p) is False), None)
    holds = next((p for p in points if holds_at(printed, p) is True), None)
    if exact is sp.true:
        if claim == "necessary":
            if fails is None:
                return Finding(Verdict.UNDECIDED, f"{what}: the exact condition always holds; no point where the display "
                               "fails was found", Evidence(Method.INSTANCES, instances=len(points)), derived=derived)
            return _witness_finding(fails, state, None, what, derived, Decision.PROVED,
                                    "it fails at the witness, while the exact condition holds for every value (not necessary)")
        if fails is None:       # no point where the display fails, and no proof that it never does
            return Finding(Verdict.UNDECIDED, f"{what}: the exact condition holds for every admissible value; the display "
                           f"held at all {len(points)} exact samples but was not proved to hold everywhere",
                           Evidence(Method.INSTANCES, instances=len(points), facts={"exact": derived}), derived=derived)
        return Finding(Verdict.CONSERVATIVE, f"{what} implies the exact condition, which holds for every admissible value; "
                       "it is not necessary (it fails at the witness)",
                       Evidence(Method.CANONICAL_FORM, witness=witness_json(fails), facts={"exact": derived}), derived=derived)
    if claim == "necessary":
        return Finding(Verdict.CONFIRMED, f"{what}: the exact condition holds for no admissible value, so any condition is "
                       "necessary", Evidence(Method.CANONICAL_FORM, facts={"exact": derived}), derived=derived)
    if holds is not None:
        return _witness_finding(holds, state, None, what, derived, Decision.DISPROVED,
                                "it holds at the witness, while the scene is never positive real")
    return Finding(Verdict.UNDECIDED, f"{what}: the scene is never positive real and the display held at none of "
                   f"{len(points)} exact samples", Evidence(Method.INSTANCES, instances=len(points)), derived=derived)


def _witness_finding(point: dict, state: State, verify: Callable | None, what: str, derived: Any,
                     expected: Decision, how: str) -> Finding:
    facts: dict[str, Any] = {}
    check = verify(point) if verify is not None else None
    if check is not None:
        facts["recheck"] = check.to_json()
        if check.decision != expected:
            return Finding(Verdict.UNDECIDED, f"{what}: the witness {witness_json(point)} was not confirmed by the exact "
                           f"decision ({check.reason})", Evidence(Method.COUNTEREXAMPLE, witness=witness_json(point),
                                                                  facts=facts), derived=derived)
    return Finding(Verdict.WRONG, f"{what}: {how}", Evidence(Method.COUNTEREXAMPLE, witness=witness_json(point), facts=facts),
                   derived=derived)


def _necessary_from_bounds(f: Finding, state: State, verify: Callable | None, what: str, derived: Any) -> Finding:
    """``compare_bounds(exact, printed)``: exact weaker somewhere = printed not necessary."""
    if f.verdict == Verdict.CONFIRMED:
        return Finding(Verdict.CONFIRMED, f"{what} is necessary, and also sufficient: {f.detail}", f.evidence, derived=derived)
    if f.verdict == Verdict.CONSERVATIVE:
        return Finding(Verdict.CONFIRMED, f"{what} is necessary (the exact condition implies it) but not sufficient",
                       f.evidence, derived=derived)
    if f.verdict == Verdict.WRONG and f.evidence.witness:
        point = {sp.Symbol(k): v for k, v in f.evidence.witness.items()}
        check = None
        try:
            check = decide_at_point(state, f.evidence.witness)
        except HapticproofError:
            pass
        facts = dict(f.evidence.facts)
        if check is not None:
            facts["recheck"] = check.to_json()
            if check.decision != Decision.PROVED:
                return Finding(Verdict.UNDECIDED, f"{what}: the witness was not confirmed by the exact decision ({check.reason})",
                               Evidence(Method.COUNTEREXAMPLE, witness=f.evidence.witness, facts=facts), derived=derived)
        del point
        return Finding(Verdict.WRONG, f"{what} is not necessary: the scene is positive real at the witness where it fails",
                       Evidence(Method.COUNTEREXAMPLE, witness=f.evidence.witness, facts=facts), derived=derived)
    return Finding(f.verdict, f.detail, f.evidence, derived=derived)


def malformed_finding(what: str, corrected: str | None = None, derived: Any = None) -> Finding:
    return Finding(Verdict.MALFORMED, what, Evidence(Method.PARSE), derived=derived, corrected=corrected)


def scene_system(state: State, allowed: tuple[str, ...], claim: str) -> str:
    system = state.scene.system
    if system not in allowed:
        raise ClaimError(f"a {claim} claim applies to {' and '.join(allowed)} scenes, not {system}")
    return system


# ---------------------------------------------------------------------------------------------
# expressions: G^-1, residues, Hermitian parts
# ---------------------------------------------------------------------------------------------
