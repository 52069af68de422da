r"""Generic claim checkers: the verdict of a printed display from what a paper file says it claims.

Each checker reads the printed display (verbatim, with the file's symbols and the scene's
``H``/``C``), derives its counterpart from the scene with the toolkit and returns a
:class:`~hapticproof.evidence.Finding` -- the same objects the hand-written derivation modules
return, so every report format shows both. The conventions are those of the bundled audit
(:mod:`hapticproof.certify`): a proof for ``confirmed`` and ``conservative``, an exact
counterexample re-checked by an exact decision for ``wrong``, ``undecided`` with the instances
when only sampling agrees.

``inverse-transfer``
    Every member of the display that is an expression of ``z`` (or such an expression times one
    signal, ``bV_h(z) + ...``) is compared with ``G^{-1}(z)`` of the scene: ``confirmed`` when
    the difference cancels, else ``wrong`` with an exact point where they differ.
``hermitian-part``
    An expression is compared with ``Re G^{-1}(e^{j\omega T})`` as a rational function of
    ``c = cos(omega T)`` (or, with a symbolic delay, in the canonical theta-form, for every
    integer ``n``); a condition (``b > KT/2 - B\cos(\omega T)``) with ``Re G^{-1} >= 0`` at each
    frequency, as a bound on the device damping. m users: the matrix ``G + G^H`` (or its half)
    or one of its principal minors (a condition: that minor ``>= 0``). Teleoperator: the
    condition that each robot's damping exceeds its bound at every frequency (eq. 32 of the
    teleoperator paper).
``residue``
    The residue (matrix) of ``G^{-1}`` at ``z = 1``.
``passivity-condition``, ``sufficient-condition``, ``necessary-condition``
    The exact condition for ``G^{-1}`` positive real: the worst case over frequency when it has
    a closed form; for a virtual-wall-like path ``R/(z-1) + F_0`` and any delay ``n`` (also
    symbolic) the Dirichlet-kernel bounds ``a >= R(n + 1/2) - F_0(1)`` (necessary) and ``a >=
    R(n + 1/2) + max|F_0|`` (sufficient), exact when ``F_0 = 0``; otherwise exact decisions on
    numeric instances (exact passive ranges, :func:`hapticproof.design.passive_range`).
    Compared as bounds on one parameter (:func:`hapticproof.certify.compare_bounds`: equal is
    ``confirmed``, a provably larger bound ``conservative``, a smaller one ``wrong`` with a
    witness re-checked by the exact decision). ``assumption = "B = 0"``: a condition that fails
    in general but holds under the assumption is ``needs-assumption``.
``stability-condition``
    ``order = "leading"``: the leading order of the exact ZOH boundary of the wall,
    ``b (+ b_h) + B > K(T/2 + t_d)`` (:func:`hapticproof.classics.leading_order_boundary`).
    ``order = "exact"``: certified spectral radii of the exact sampled-data loop (the scene
    names the device mass ``m``) near the printed boundary: an unstable loop where the display
    holds is ``wrong``; agreement on instances is ``undecided`` (never a proof).
``same-as``
    The display and the equation ``other`` (this file's or a bundled paper's ``paper:id``),
    with ``under`` substituted in both: the same expression or condition is ``confirmed``,
    otherwise ``inconsistent`` (both ids) with a point where they differ.

A display that is not confirmed gets a search for a nearby correct reading: the edits of
:mod:`hapticproof.mutate` (a sign, a factor 2, a dropped term, swapped indices, a reversed
relation, another symbol); when one edit makes it exactly right the verdict is ``typo`` and the
corrected LaTeX is that edited display.

>>> from hapticproof.paperfile import loads, TEMPLATE
>>> from hapticproof.audit import audit_paper
>>> report = audit_paper(loads(TEMPLATE).paper)
>>> [(r.id, r.verdict.value) for r in report.results]
[('1', 'confirmed'), ('2', 'confirmed'), ('3', 'confirmed')]
"""

from __future__ import annotations

import functools
from collections.abc import Callable, Iterable, Mapping
from dataclasses import dataclass, field
from typing import Any

import sympy as sp

from hapticproof.certify import Sampler, as_bound, compare_bounds
from hapticproof.errors import HapticproofError, LatexParseError
from hapticproof.evidence import Decision, Evidence, Finding, Method, Outcome, Verdict
from hapticproof.symbols import c as C_SYM
from hapticproof.symbols import n as N_SYM
from hapticproof.symbols import z as Z_SYM

__all__ = ["check", "describe", "checkers", "compare_conditions", "State", "ClaimError"]

_OK = (Verdict.CONFIRMED, Verdict.CONSERVATIVE)


class ClaimError(HapticproofError, ValueError):
    """A claim that cannot be checked for this scene (e.g. a residue claim about a network)."""


# ---------------------------------------------------------------------------------------------
# the state of one check
# ---------------------------------------------------------------------------------------------


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

    @functools.cached_property
    def scene(self) -> Any:
        return self.source.scenes.get(self.spec.scene) if self.spec.scene else None

    @functools.cached_property
    def model(self) -> Any:
        key = ("model", self.spec.scene)
        if key not in self.cache:          # shared by the repair trials of one check
            self.cache[key] = self.scene.build()
        return self.cache[key]

    @functools.cached_property
    def table(self) -> Any:
        return self.source.table_for(self.spec.scene)

    @functools.cached_property
    def statement(self) -> Any:
        from hapticproof.parse import parse_printed

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
        substituted, ``t_d = n T`` with the scene's delay, ``omega`` kept."""
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
    for name in ("b", "K", "B", "T", "z_a"):
        out.setdefault(name, scene.symbol(name))
    out.setdefault("n", N_SYM)
    return out


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
    if rename:
        expr = expr.xreplace(rename)
    t_d = next((s for s in expr.free_symbols if getattr(s, "name", None) == "t_d"), None) if isinstance(expr, sp.Basic) else None
    if t_d is not None and state.scene is not None and "t_d" not in values:
        delay = _delay_of(state)
        if delay is not None:
            T = values.get("T", state.names.get("T"))
            expr = expr.xreplace({t_d: delay * T})
    return expr


def _frequency(state: State) -> sp.Symbol | None:
    """The printed frequency symbol (``\\omega``), if the file declares it."""
    return state.table.lookup(r"\omega")


def _period(state: State) -> Any:
    return state.values.get("T", state.names.get("T"))


# ---------------------------------------------------------------------------------------------
# reading members of a display
# ---------------------------------------------------------------------------------------------


def _members(statement: Any) -> list[Any]:
    """Every member of every relation chain of the display, or its expression(s)."""
    relations = statement.relations()
    if relations:
        return [t for r in relations for t in r.terms]
    return list(statement.expressions())


def _candidates(state: State, members: Iterable[Any]) -> list[Any]:
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


# ---------------------------------------------------------------------------------------------
# exact decisions at a point (re-checking witnesses)
# ---------------------------------------------------------------------------------------------


def _decide_model(model: Any, system: str) -> Outcome:
    if system == "single-user":
        from hapticproof.positivereal import positive_real

        return positive_real(model)
    if system == "multi-user":
        from hapticproof.multiuser import positive_real

        return positive_real(model)
    if system == "teleoperator":
        from hapticproof.teleoperator import passivity

        return passivity(model)
    raise ClaimError("passivity decisions apply to single-user, multi-user and teleoperator scenes")


def _numeric_scene(state: State, point: Mapping[Any, Any]) -> Any:
    """The scene with the point's values (missing parameters 1, a symbolic delay 1)."""
    scene = state.scene
    values: dict[str, Any] = {}
    delay = None
    for key, value in point.items():
        name = key if isinstance(key, str) else key.name
        if name == "c":
            continue
        if name == "n":
            delay = int(value)
            continue
        values[name] = value
    model_free = {s.name for s in getattr(state.model, "parameters", set())} - {"n"}
    for name in model_free - set(values):
        values[name] = sp.Integer(1)
    params = {k: v for k, v in values.items() if k in model_free or k in dict(scene.params)}
    numeric = scene.with_params(params)
    if scene.delay == "n":
        numeric = numeric.replace(delay=delay if delay is not None else 1)
    return numeric


def _decide_point(state: State, point: Mapping[Any, Any]) -> Outcome:
    numeric = _numeric_scene(state, point)
    return _decide_model(numeric.build(), numeric.system)


def _holds(condition: Any, point: Mapping[Any, Any]) -> bool | None:
    """Exact truth of a condition (relational or And) at a point; None when undecidable."""
    try:
        value = sp.sympify(condition).xreplace(dict(point))
    except (TypeError, ZeroDivisionError):
        return None
    return _truth(value)


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


# ---------------------------------------------------------------------------------------------
# comparing conditions
# ---------------------------------------------------------------------------------------------


def _relations(condition: Any) -> list[Any]:
    if isinstance(condition, sp.And):
        return [r for a in condition.args for r in _relations(a)]
    return [condition]


@functools.lru_cache(maxsize=512)
def _bound(condition: Any, var: sp.Symbol) -> Any:
    """:func:`~hapticproof.certify.as_bound`, remembered (the exact side repeats across repairs);
    ``None`` when the condition is not a bound on ``var``."""
    try:
        return as_bound(condition, var)
    except (TypeError, ValueError, sp.PolynomialError):
        return None


@functools.lru_cache(maxsize=256)
def _drop_trivial(condition: Any) -> Any:
    """An And without the parts that hold for every admissible value (e.g. ``K T >= 0``)."""
    parts = []
    for rel in _relations(condition):
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


def _preferred(state: State) -> list[str]:
    order = []
    if state.spec.solve_for:
        order.append(state.spec.solve_for)
    system = state.scene.system if state.scene is not None else ""
    order += {"single-user": ["b"], "multi-user": ["b", "b_1"], "teleoperator": ["b", "b_m", "b_s"]}.get(system, ["b"])
    return order


def _variable(printed: Any, exact: Any, state: State) -> sp.Symbol | None:
    """A parameter that both conditions bound from below (affine, positive coefficient)."""
    if isinstance(printed, sp.And) or isinstance(exact, sp.And):
        return None
    if not isinstance(printed, sp.core.relational.Relational) or not isinstance(exact, sp.core.relational.Relational):
        return None
    free = sorted((printed.free_symbols | exact.free_symbols) - {C_SYM}, key=str)
    by_name = {s.name: s for s in free}
    candidates = [by_name[n] for n in _preferred(state) if n in by_name] + [s for s in free if s.name not in _preferred(state)]
    for var in candidates:
        e = _bound(exact, var)
        if e is None or not getattr(e, "lower", True):
            continue
        p = _bound(printed, var)
        if p is not None and getattr(p, "lower", True):
            return var
    return None


def _sample(printed: Any, exact: Any, tries: int = 300) -> tuple[dict | None, dict | None, int]:
    """Exact points where the printed condition holds and the exact one fails, and conversely."""
    free = sorted((sp.sympify(printed).free_symbols | sp.sympify(exact).free_symbols), key=str)
    weaker = stronger = None
    count = 0
    for point in Sampler(free, seed=3).draw(tries):
        hp, he = _holds(printed, point), _holds(exact, point)
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


def _ratio_equivalent(printed: Any, exact: Any) -> bool:
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
    ratio = sp.factor(sp.cancel(sp.together(fp / fe)))
    return bool(ratio.is_positive)


def _witness_json(point: Mapping[Any, Any]) -> dict[str, Any]:
    return {(k if isinstance(k, str) else k.name): v for k, v in point.items()}


def compare_conditions(printed: Any, exact: Any, state: State, *, claim: str, what: str,
                       verify: Callable[[dict], Outcome] | None = None, derived: Any = None) -> Finding:
    """Compare a printed condition with the exact necessary-and-sufficient one, as the claim
    says (``passivity`` / ``sufficient`` / ``necessary``): bounds when both bound one parameter
    (:func:`~hapticproof.certify.compare_bounds`), else a proof of equivalence up to a
    positive factor or exact sampling (witnesses re-checked by ``verify``).

    >>> from hapticproof.paperfile import loads, TEMPLATE
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
    exact = _drop_trivial(exact)
    if exact in (sp.true, sp.false):
        return _constant_exact(printed, exact, state, claim, what, derived)
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
    if _ratio_equivalent(printed, exact):
        state.repairable = True
        return Finding(Verdict.CONFIRMED, f"{what} is the exact condition {sp.sstr(exact)} multiplied by a positive factor",
                       Evidence(Method.CANONICAL_FORM, facts={"exact": exact}), derived=derived)
    weaker, stronger, count = _sample(printed, exact, tries=60 if state.repairing else 300)
    state.repairable = True
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
                   f"{what} is not a positive multiple or a bound comparable with the exact condition {sp.sstr(exact)}, "
                   f"and no counterexample was found in {count} exact samples{note}",
                   Evidence(Method.INSTANCES, instances=count,
                            witness=_witness_json(stronger) if stronger is not None else None, facts={"exact": exact}),
                   derived=derived)


def _numerically_different(a: Any, b: Any, tries: int = 2) -> bool:
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


def _positive_ratio_at_points(printed: Any, exact: Any) -> bool:
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
        if not _positive_ratio_at_points(printed, exact):
            return reject
        return None if _ratio_equivalent(printed, exact) else reject
    p, e = _bound(printed, var), _bound(exact, var)
    if p is None or e is None or getattr(p, "lower", True) != getattr(e, "lower", True):
        return reject
    if claim == "sufficient":
        return None
    if _numerically_different(p.bound, e.bound):
        return reject
    return None


def _constant_exact(printed: Any, exact: Any, state: State, claim: str, what: str, derived: Any) -> Finding:
    """The exact condition holds for every admissible value (``True``) or for none (``False``)."""
    state.repairable = True
    always = _drop_trivial(printed) is sp.true
    free = sorted(sp.sympify(printed).free_symbols, key=str)
    points = Sampler(free, seed=3).draw(200 if not state.repairing else 40)
    fails = next((p for p in points if _holds(printed, p) is False), None)
    holds = next((p for p in points if _holds(printed, p) is True), None)
    if exact is sp.true:
        if always:
            return Finding(Verdict.CONFIRMED, f"{what} and the exact condition both hold for every admissible value of the "
                           "parameters", Evidence(Method.CANONICAL_FORM, facts={"exact": derived}), derived=derived)
        if claim == "necessary":
            if fails is None:
                return Finding(Verdict.UNDECIDED, f"{what}: the exact condition always holds; no point where the display "
                               "fails was found", Evidence(Method.INSTANCES, instances=len(points)), derived=derived)
            return _witness_finding(fails, state, None, what, derived, Decision.PROVED,
                                    "it fails at the witness, while the exact condition holds for every value (not necessary)")
        return Finding(Verdict.CONSERVATIVE, f"{what} implies the exact condition, which holds for every admissible value; "
                       "it is not necessary" + (" (it fails at the witness)" if fails is not None else ""),
                       Evidence(Method.CANONICAL_FORM, witness=_witness_json(fails) if fails is not None else None,
                                facts={"exact": derived}), derived=derived)
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
            return Finding(Verdict.UNDECIDED, f"{what}: the witness {_witness_json(point)} was not confirmed by the exact "
                           f"decision ({check.reason})", Evidence(Method.COUNTEREXAMPLE, witness=_witness_json(point),
                                                                  facts=facts), derived=derived)
    return Finding(Verdict.WRONG, f"{what}: {how}", Evidence(Method.COUNTEREXAMPLE, witness=_witness_json(point), facts=facts),
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
            check = _decide_point(state, f.evidence.witness)
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


# ---------------------------------------------------------------------------------------------
# shared: the claim checkers, the assumption wrapper and the repair search
# ---------------------------------------------------------------------------------------------

Checker = Callable[[State], Finding]


@functools.lru_cache(maxsize=1)
def checkers() -> dict[str, Checker]:
    """The checker of each claim kind (:mod:`hapticproof.claimcheckers`, :mod:`hapticproof.claimconditions`)."""
    from hapticproof import claimcheckers as ce
    from hapticproof import claimconditions as cc

    return {
        "inverse-transfer": ce.inverse_transfer,
        "hermitian-part": ce.hermitian_part,
        "residue": ce.residue,
        "passivity-condition": functools.partial(cc.condition, claim="passivity"),
        "sufficient-condition": functools.partial(cc.condition, claim="sufficient"),
        "necessary-condition": functools.partial(cc.condition, claim="necessary"),
        "stability-condition": cc.stability,
        "same-as": cc.same_as,
    }


def check(ctx: Any, *, spec: Any, source: Any) -> Finding:
    """The audit check of one paper-file claim (registered by :mod:`hapticproof.paperfile`)."""
    state = State(spec, source, ctx.equation.printed, equation=ctx.equation)
    try:
        finding = _with_assumption(state)
    except ClaimError as err:
        return Finding(Verdict.UNDECIDED, f"the claim cannot be checked: {err}", Evidence(Method.STRUCTURAL))
    except LatexParseError:
        raise                                   # the audit reports the printed display as malformed
    except (HapticproofError, ArithmeticError, TypeError, ValueError, NotImplementedError, sp.PolynomialError) as err:
        # a display the generic checker cannot handle is undecided with the reason, never a traceback
        return Finding(Verdict.UNDECIDED, f"the check could not decide this display: {type(err).__name__}: {err}",
                       Evidence(Method.STRUCTURAL, facts={"error": f"{type(err).__name__}: {err}"}))
    if _should_repair(state, finding):
        finding = _repair(state, finding)
    return finding


def _run(state: State) -> Finding:
    return checkers()[state.spec.claim](state)


def _with_assumption(state: State) -> Finding:
    """Check the claim; with a stated ``assumption`` also under it (``needs-assumption`` when
    it holds only there)."""
    text = ", ".join(f"{sp.sstr(k)} = {sp.sstr(v)}" for k, v in state.spec.assumption)
    if state.spec.assumption and state.repairing:
        # a repair of a claim made under an assumption is right under that assumption
        inner = _run(_assumed(state))
        return Finding(inner.verdict, f"under the stated assumption {text}: {inner.detail}", inner.evidence,
                       derived=inner.derived)
    inner = None
    finding = _run(state)
    if not state.spec.assumption or finding.verdict in _OK:
        if state.spec.assumption and finding.verdict in _OK:
            return Finding(finding.verdict, finding.detail + " (it holds without the stated assumption)",
                           finding.evidence, derived=finding.derived, corrected=finding.corrected)
        return finding
    if inner is None:
        inner = _run(_assumed(state))
    if inner.verdict in _OK and finding.verdict == Verdict.WRONG:
        return Finding(
            Verdict.NEEDS_ASSUMPTION,
            f"holds under the stated assumption {text} ({inner.verdict.value}: {inner.detail}); without it: {finding.detail}",
            Evidence(finding.evidence.method, witness=finding.evidence.witness,
                     facts={**dict(finding.evidence.facts), "under_assumption": inner.verdict.value,
                            "under_assumption_evidence": inner.evidence.to_json()}),
            derived=inner.derived,
            corrected=_with_text(state.printed, r"\quad (" + ", ".join(
                f"{sp.latex(k)} = {sp.latex(v)}" for k, v in state.spec.assumption) + ")"),
        )
    if inner.verdict == Verdict.WRONG:
        state.repairable = state.repairable
        return Finding(inner.verdict, f"{inner.detail} (even under the stated assumption {text})", inner.evidence,
                       derived=inner.derived, corrected=inner.corrected)
    return finding


def _assumed(state: State) -> State:
    """The state with the assumption substituted into the scene (parameters) and the display."""
    from hapticproof.paperfile import ClaimSpec

    spec = state.spec
    scene = state.scene
    params = {k.name: v for k, v in spec.assumption}
    new_scene = scene.with_params(params)
    name = f"{spec.scene}#assumed"
    scenes = dict(state.source.scenes)
    scenes[name] = new_scene
    source = _SourceView(state.source, scenes)
    new_spec = ClaimSpec(**{**{f: getattr(spec, f) for f in spec.__dataclass_fields__}, "scene": name, "assumption": ()})
    return State(new_spec, source, state.printed, equation=state.equation, repairing=state.repairing, cache=state.cache)


class _SourceView:
    """A paper file seen with other scenes (an assumption substituted into one)."""

    def __init__(self, source: Any, scenes: Mapping[str, Any]):
        self._source = source
        self.scenes = scenes

    def __getattr__(self, name: str) -> Any:
        return getattr(self._source, name)

    def table_for(self, scene: str | None) -> Any:
        from hapticproof.paperfile import bound_table

        return bound_table(self._source, self.scenes.get(scene) if scene else None, ("view", scene))


def _with_text(printed: str, suffix: str) -> str:
    return printed.rstrip() + suffix


def _should_repair(state: State, finding: Finding) -> bool:
    if state.repairing or not state.repairable or state.spec.claim == "same-as":
        return False
    if finding.verdict == Verdict.WRONG:
        return True
    return finding.verdict == Verdict.CONSERVATIVE and state.spec.claim in ("passivity-condition", "stability-condition",
                                                                            "hermitian-part")


def _repaired(state: State, finding: Finding) -> bool:
    """A trial edit repairs the display when it is right: confirmed, a correct sufficient
    condition, or right under the claim's stated assumption."""
    if finding.verdict == Verdict.CONFIRMED:
        return True
    if finding.verdict == Verdict.NEEDS_ASSUMPTION:
        return bool(state.spec.assumption)
    return finding.verdict == Verdict.CONSERVATIVE and state.spec.claim == "sufficient-condition"


#: At most this many edits are tried (in printed order).
MAX_EDITS = 80


def _repair(state: State, finding: Finding) -> Finding:
    """Search the edits of :mod:`hapticproof.mutate` for one that makes the display right."""
    try:
        from hapticproof.mutate import generate
    except ImportError:  # pragma: no cover - the mutation operators are not available
        return finding
    mutants = generate(state.equation, state.source.paper, text=state.printed)[:MAX_EDITS]
    found = []
    for mutant in mutants:
        trial = State(state.spec, state.source, mutant.printed, equation=state.equation, repairing=True,
                      cache=state.cache)
        try:
            result = _with_assumption(trial)
        except (LatexParseError, HapticproofError, TypeError, ValueError, ZeroDivisionError, NotImplementedError):
            continue
        if _repaired(state, result):
            found.append((mutant, result))
    facts = dict(finding.evidence.facts)
    facts["edits_tried"] = len(mutants)
    if not found:
        return Finding(finding.verdict, finding.detail + f"; no single edit of the display repairs it ({len(mutants)} tried)",
                       Evidence(finding.evidence.method, witness=finding.evidence.witness,
                                instances=finding.evidence.instances, facts=facts),
                       derived=finding.derived, corrected=finding.corrected)
    mutant, result = found[0]
    facts["repair"] = {"operator": mutant.operator, "position": mutant.position, "original": mutant.original,
                       "replacement": mutant.replacement, "repairs_found": len(found)}
    others = f" ({len(found) - 1} other edit{'s' if len(found) > 2 else ''} also repair it)" if len(found) > 1 else ""
    return Finding(
        Verdict.TYPO,
        f"one edit repairs it: {_describe_edit(mutant)} gives a display that is {result.verdict.value} ({result.detail}){others}; "
        f"as printed: {finding.detail}",
        Evidence(finding.evidence.method, witness=finding.evidence.witness, instances=finding.evidence.instances, facts=facts),
        derived=result.derived if result.derived is not None else finding.derived,
        corrected=mutant.printed,
    )


_EDITS = {"sign": "flipping the sign", "scale": "a factor 2", "drop": "dropping a term", "swap": "swapping the indices",
          "relation": "reversing the relation", "symbol": "another symbol"}


def _describe_edit(mutant: Any) -> str:
    old = mutant.original.strip() or "nothing"
    new = mutant.replacement.strip() or "nothing"
    return f"{_EDITS.get(mutant.operator, mutant.operator)} ({old!r} -> {new!r} at position {mutant.position})"


def describe(spec: Any, paper: Any) -> str:
    """One line: what the claim is compared with (the report's ``derivation``).

    >>> from hapticproof.paperfile import loads, TEMPLATE
    >>> paper = loads(TEMPLATE)
    >>> describe(paper.claim("3"), paper)
    "exact condition for G^-1 positive real of scene 'wall' (single-user, forward) (necessary and sufficient)"
    """
    scene = paper.scenes.get(spec.scene) if spec.scene else None
    where = ""
    if scene is not None:
        where = f" of scene '{spec.scene}' ({scene.system}, {scene.approximation}"
        where += f", delay {scene.delay})" if scene.delay not in (0, None) else ")"
    texts = {
        "inverse-transfer": f"G^-1(z){where}, exact (canonical form)",
        "hermitian-part": f"Re G^-1(e^(j omega T)){where}, exact in c = cos(omega T)",
        "residue": f"residue of G^-1 at z = 1{where}",
        "passivity-condition": f"exact condition for G^-1 positive real{where} (necessary and sufficient)",
        "sufficient-condition": f"exact condition for G^-1 positive real{where}: the display must imply it",
        "necessary-condition": f"exact condition for G^-1 positive real{where}: it must imply the display",
        "stability-condition": (f"exact ZOH sampled-data stability{where}" if spec.order == "exact"
                                else f"leading order of the exact ZOH stability boundary{where}"),
        "same-as": f"equation {spec.other}" + (" with " + ", ".join(f"{k} = {v}" for k, v in spec.under) if spec.under else ""),
    }
    text = texts[spec.claim]
    if spec.assumption:
        text += "; stated assumption " + ", ".join(f"{k} = {v}" for k, v in spec.assumption)
    return text
