r"""The checkers of condition claims in paper files: ``passivity-condition``,
``sufficient-condition``, ``necessary-condition``, ``stability-condition`` and ``same-as`` (see
:mod:`hapticproof.audit.claims` for what each decides).

>>> from hapticproof.audit.paperfile import loads, TEMPLATE
>>> from hapticproof.audit.claimbase import State
>>> paper = loads(TEMPLATE)
>>> spec = paper.claim("3")                       # b > KT/2 + B
>>> condition(State(spec, paper, spec.printed), claim="passivity").verdict.value
'confirmed'
"""

from __future__ import annotations

from collections.abc import Mapping
from typing import Any

import sympy as sp

from hapticproof.exact.canonical import Sampler, is_identically_zero
from hapticproof.audit.compare import as_bound, compare_expressions
from hapticproof.audit.claimbase import malformed_finding, scene_system
from hapticproof.audit.claimbase import ClaimError, State, decide_model, decide_at_point, holds_at, display_members, preferred_variables, conjuncts, separating_points, witness_json, compare_conditions
from hapticproof.core.errors import HapticproofError, LatexParseError
from hapticproof.core.evidence import Decision, Evidence, Finding, Method, Outcome, Verdict
from hapticproof.core.naming import marked, marker, role_marker
from hapticproof.core.symbols import c as C_SYM
from hapticproof.core.symbols import n as N_SYM
from hapticproof.core.symbols import z as Z_SYM

__all__ = ["condition", "stability", "same_as"]


# ---------------------------------------------------------------------------------------------
# passivity conditions
# ---------------------------------------------------------------------------------------------


def _printed_condition(state: State) -> Any:
    relations = state.statement.relations()
    links = [link for r in relations for link in conjuncts(r.as_sympy())]
    if not links or any(getattr(link, "rel_op", None) in ("==", "!=") for link in links):
        return None
    return state.prepare(links[0] if len(links) == 1 else sp.And(*links))


def _indexed(state: State) -> bool:
    """Whether the display names users by an index (``b_i``, ``\\min_i``, ``i = 1, 2``)."""
    from hapticproof.audit.reader.statements import IndexedExtremum, Qualified

    statement = state.statement
    if isinstance(statement, Qualified):
        return True
    for relation in statement.relations():
        for term in relation.terms:
            term = sp.sympify(term)
            if term.atoms(sp.Indexed) or term.atoms(IndexedExtremum):
                return True
    return False


def _symbolic_condition(outcome: Outcome) -> Any:
    condition = outcome.evidence.facts.get("condition") if outcome.evidence.facts else None
    return condition if isinstance(condition, sp.Basic) else None


def _placeholder(condition: Any) -> bool:
    return condition is None or any(getattr(f.func, "__name__", "") in ("min_c", "sup_c") for f in condition.atoms(sp.Function))


def _exact(state: State) -> dict[str, Any]:
    """The exact positive-realness condition: ``{"condition": ...}`` (necessary and sufficient),
    or ``{"necessary": ..., "sufficient": ...}`` (Dirichlet bounds), or ``{"decision": Outcome}``
    for a numeric scene, or ``{}``; ``method`` says how it was derived."""
    key = ("exact-condition", state.spec.scene)
    if key in state.cache:
        return state.cache[key]
    state.cache[key] = out = _derive_exact(state)
    return out


def _derive_exact(state: State) -> dict[str, Any]:
    model = state.model
    system = state.scene.system
    if system == "network":
        raise ClaimError("passivity claims apply to single-user, multi-user and teleoperator scenes")
    if getattr(model, "is_numeric", False) or (system == "teleoperator" and not _tele_symbolic(model)):
        return {"decision": decide_model(model, system), "method": "exact decision of the numeric scene"}
    if system == "single-user":
        from hapticproof.analysis.positivereal import conditions, worst_case

        conds = conditions(model)
        others = []
        for cond in conds[:-1]:
            if cond.decision == Decision.DISPROVED:
                return {"condition": sp.false, "method": f"{cond.name}: {cond.outcome.reason}"}
            if cond.decision == Decision.UNDECIDED:
                return {}
            if cond.decision == Decision.SYMBOLIC:
                extra = _symbolic_condition(cond.outcome)
                if extra is None:
                    return {}
                others.append(extra)
        if not model.delay.is_Symbol:
            wc = worst_case(model)
            if not _placeholder(wc.condition) and isinstance(wc.condition, sp.Basic):
                c = marker("cos")
                where = f"minimum over {c} at {c} = {wc.minimiser}" if wc.minimiser is not None else wc.outcome.reason
                return {"condition": sp.And(*others, wc.condition) if others else wc.condition,
                        "method": f"worst case over frequency by endpoint analysis ({where})"}
        bounds = _dirichlet(model)
        if bounds is not None:
            bounds = dict(bounds)
            for name in ("condition", "necessary", "sufficient"):
                if bounds.get(name) is not None and others:
                    bounds[name] = sp.And(*others, bounds[name])
            return bounds
        return {}
    if system == "multi-user":
        from hapticproof.analysis.multiuser import conditions, worst_case

        conds = conditions(model)
        for cond in conds[:-1]:
            if cond.decision == Decision.DISPROVED:
                return {"condition": sp.false, "method": f"{cond.name}: {cond.outcome.reason}"}
            if cond.decision != Decision.PROVED:
                return {}
        wc = worst_case(model)
        if wc.condition is None or _placeholder(wc.condition) or wc.condition.has(sp.Function("PSD")):
            return {}
        return {"condition": wc.condition, "method": f"worst case of the Hermitian part ({wc.method})"}
    from hapticproof.analysis.teleoperator import exact_condition

    condition = exact_condition(model)
    if condition is None or _placeholder(condition):
        return {}
    return {"condition": condition, "method": "the exact passivity conditions (D), (P1)-(P5) of the teleoperator "
                                              f"(error-coordinate damping {marker('coupling')} >= sup {marker('leak')}, "
                                              "C(1) >= 0, the poles of C)"}


def _tele_symbolic(model: Any) -> bool:
    from hapticproof.analysis.teleoperator import bound_parameters

    return bool(bound_parameters(model)) or bool({s for s in (sp.sympify(model.b_m).free_symbols | sp.sympify(model.b_s).free_symbols)})


def _dirichlet(model: Any) -> dict[str, Any] | None:
    r"""Bounds for ``G^{-1} = a + z^{-n} F(z)`` with ``F = R/(z - 1) + F_0`` (any delay ``n``).

    ``z^{-n}/(z - 1) = 1/(z - 1) - sum_{k=1}^n z^{-k}`` gives ``Re G^{-1} = a - R D_n(theta) +
    Re(z^{-n} F_0)`` with the Dirichlet kernel ``D_n = 1/2 + sum cos k theta <= n + 1/2``
    (its supremum, approached as ``theta -> 0``). So ``a >= R(n + 1/2) - F_0(1)`` is necessary
    (the limit ``c -> 1``) and ``a >= R(n + 1/2) + max|F_0|`` sufficient; with ``F_0 = 0`` the
    condition ``a >= R(n + 1/2)`` is exact."""
    from hapticproof.systems.models import environment_path
    from hapticproof.analysis.positivereal import poles_of
    from hapticproof.exact.unitcircle import hermitian_part_rational

    F = sp.cancel(environment_path(model))
    num, den = sp.fraction(F)
    if sp.Poly(den, Z_SYM).eval(1) != 0:
        return None
    R = sp.cancel(sp.cancel((Z_SYM - 1) * F).subs(Z_SYM, 1))
    if R.has(sp.zoo, sp.nan):
        return None
    F0 = sp.cancel(F - R / (Z_SYM - 1))
    if F0 != 0:
        den0 = sp.fraction(F0)[1]
        if sp.Poly(den0, Z_SYM).eval(1) == 0:
            return None
        if any(p.location != "inside" for p in poles_of(F0)):
            return None
    a = model.b - model.z_a
    n = model.delay
    kappa = R * (n + sp.Rational(1, 2))
    # the proof's names: a = b - z_a, R, F_0, D_n, theta, c, as the paper's naming writes them
    A, Rn, F, D, th, c = (marker(k) for k in ("excess", "residue", "rest", "kernel", "theta", "cos"))
    facts = {"residue_R": R, "F_0": F0, "kernel_bound": f"{D} <= n + 1/2 (Dirichlet kernel)",
             "a": f"{A} = {role_marker('device_damping', 'b')} - z_a"}
    if F0 == 0:
        return {"condition": sp.Ge(a, sp.expand(kappa)), "facts": facts,
                "method": f"G^-1 = {A} + z^-n {Rn}/(z - 1): Re G^-1 = {A} - {Rn} {D}({th}) with the Dirichlet kernel "
                          f"{D} <= n + 1/2 (supremum as {th} -> 0), exact for every integer n"}
    necessary = sp.Ge(a, sp.expand(kappa - F0.subs(Z_SYM, 1)))
    modulus = hermitian_part_rational(sp.cancel(F0 * F0.subs(Z_SYM, 1 / Z_SYM))).expr()
    sufficient = None
    if C_SYM not in sp.sympify(modulus).free_symbols:
        sufficient = sp.Ge(a, sp.expand(kappa + sp.sqrt(sp.factor(modulus))))
    return {"necessary": necessary, "sufficient": sufficient, "facts": facts,
            "method": f"Dirichlet-kernel bounds: {A} >= {Rn}(n + 1/2) - {F}(1) necessary ({c} -> 1), "
                      f"{A} >= {Rn}(n + 1/2) + max|{F}| sufficient"}


def _verify_pr(state: State):
    def verify(point: dict) -> Outcome:
        return decide_at_point(state, point)
    return verify


def condition(state: State, claim: str) -> Finding:
    """A passivity condition: necessary and sufficient (``passivity``), ``sufficient`` or ``necessary``."""
    if state.scene.system == "multi-user" and _indexed(state):
        from hapticproof.audit.claimusers import users_condition

        return users_condition(state, claim=claim, exact=_exact(state))
    printed = _printed_condition(state)
    if printed is None:
        return malformed_finding("the display is not a condition (an inequality) on the parameters")
    exact = _exact(state)
    what = "the printed condition"
    if state.scene.system == "multi-user" and "decision" not in exact:
        # scalar bounds on the users' dampings against the matrix condition first; then the
        # comparison with the exact closed form (minor conditions printed as such)
        from hapticproof.audit.claimusers import users_condition

        g = users_condition(state, claim=claim, exact=exact)
        if g.verdict in (Verdict.CONFIRMED, Verdict.CONSERVATIVE) or (g.verdict == Verdict.WRONG and not state.repairing) \
                or "condition" not in exact:
            return _noted(g, exact)
        f = compare_conditions(printed, exact["condition"], state, claim=claim, what=what, verify=_verify_pr(state))
        return _noted(f if f.verdict != Verdict.UNDECIDED or g.verdict == Verdict.WRONG else g, exact)
    if "decision" in exact:
        return _numeric_condition(printed, exact["decision"], claim, what)
    if "condition" in exact:
        f = compare_conditions(printed, exact["condition"], state, claim=claim, what=what, verify=_verify_pr(state))
        return _noted(f, exact)
    if exact.get("necessary") is not None:
        return _noted(_sandwich(state, printed, exact, claim, what), exact)
    return _instances(state, printed, claim, what)


def _noted(f: Finding, exact: Mapping[str, Any]) -> Finding:
    facts = dict(f.evidence.facts)
    facts["exact_method"] = exact.get("method", "")
    facts.update({k: v for k, v in (exact.get("facts") or {}).items()})
    return Finding(f.verdict, f.detail, Evidence(f.evidence.method, witness=f.evidence.witness,
                                                  instances=f.evidence.instances, facts=facts),
                   derived=f.derived, corrected=f.corrected)


def _numeric_condition(printed: Any, decision: Outcome, claim: str, what: str) -> Finding:
    holds = holds_at(printed, {})
    passive = decision.decision == Decision.PROVED
    if holds is None or decision.decision not in (Decision.PROVED, Decision.DISPROVED):
        return Finding(Verdict.UNDECIDED, f"{what} or the exact decision is not settled for this numeric scene ({decision.reason})",
                       Evidence(Method.INSTANCES, facts={"decision": decision.to_json()}))
    agree = holds == passive
    relevant = {"passivity": True, "sufficient": holds, "necessary": not holds}[claim]
    facts = {"decision": decision.to_json(), "printed_holds": holds}
    if agree or not relevant:
        return Finding(Verdict.CONFIRMED, f"{what} {'holds' if holds else 'fails'} and the scene is {'' if passive else 'not '}"
                       f"positive real ({decision.reason})", Evidence(decision.evidence.method, facts=facts))
    return Finding(Verdict.WRONG, f"{what} {'holds' if holds else 'fails'} but the scene is {'' if passive else 'not '}positive "
                   f"real ({decision.reason})", Evidence(decision.evidence.method, witness=decision.witness, facts=facts))


def _sandwich(state: State, printed: Any, exact: Mapping[str, Any], claim: str, what: str) -> Finding:
    """Dirichlet bounds: not sufficient when below the necessary bound; sufficient when above the sufficient one."""
    necessary, sufficient = exact["necessary"], exact.get("sufficient")
    if state.repairing and claim != "sufficient":     # only bounds, no exact condition: nothing to confirm
        return Finding(Verdict.UNDECIDED, f"{what}: no exact condition to confirm a repair", Evidence(Method.INSTANCES))
    verify = _verify_pr(state)
    if claim != "necessary":
        low = compare_conditions(printed, necessary, state, claim="passivity", what=what, verify=verify)
        if low.verdict == Verdict.WRONG:
            return Finding(Verdict.WRONG, low.detail + " (below the necessary bound, so not positive real there)",
                           low.evidence, derived=necessary)
        if sufficient is not None:
            high = compare_conditions(printed, sufficient, state, claim="passivity", what=what, verify=None)
            if high.verdict in (Verdict.CONFIRMED, Verdict.CONSERVATIVE):
                # a sufficient claim is settled by the proof; only a claimed exact condition needs the
                # instances' witness of non-necessity
                inst = _instances(state, printed, claim, what) if claim == "passivity" else high
                if inst.verdict == Verdict.UNDECIDED and inst.evidence.witness and claim == "passivity":
                    return Finding(Verdict.CONSERVATIVE, f"{what} implies the sufficient Dirichlet bound {marked(sufficient)} "
                                   "(proved) but is not necessary: the scene is positive real at the witness where it fails",
                                   Evidence(Method.COUNTEREXAMPLE, witness=inst.evidence.witness,
                                            facts={"sufficient": sufficient}), derived=sufficient)
                if claim == "sufficient":
                    return Finding(Verdict.CONSERVATIVE, f"{what} implies the sufficient bound {marked(sufficient)} (proved)",
                                   high.evidence, derived=sufficient)
                return Finding(Verdict.UNDECIDED, f"{what} is sufficient (it implies {marked(sufficient)}, proved); whether it "
                               "is also necessary was not settled", high.evidence, derived=sufficient)
    else:
        nec = compare_conditions(printed, necessary, state, claim="necessary", what=what)
        if nec.verdict == Verdict.CONFIRMED:
            return Finding(Verdict.CONFIRMED, f"{what} is implied by the necessary bound {marked(necessary)} (proved)",
                           nec.evidence, derived=necessary)
    return _instances(state, printed, claim, what)


# -- numeric instances ---------------------------------------------------------------------------


def _instance_variable(state: State, printed: Any) -> sp.Symbol | None:
    free = {s.name: s for s in printed.free_symbols}
    params = {s.name for s in getattr(state.model, "parameters", set())}
    for name in preferred_variables(state) + sorted(free):
        if name in free and name in params and name != "n":
            return free[name]
    return None


def _endpoint_values(rng: Any) -> list[sp.Rational]:
    out = []
    for lo, _lc, hi, _hc in rng.intervals:
        for end in (lo, hi):
            if end is None:
                continue
            if end.value is not None:
                out.append(sp.Rational(end.value))
            else:
                out += [sp.Rational(end.lo), sp.Rational(end.hi)]
    return out


def _probe_values(boundaries: list[sp.Rational], positive: bool) -> list[sp.Rational]:
    points = sorted(set(boundaries))
    out = set()
    for x in points:
        step = abs(x) / 20 + sp.Rational(1, 10**6)
        out.update((x - step, x + step))
    for a, b in zip(points, points[1:]):
        out.add((a + b) / 2)
    if not points:
        out.update((sp.Rational(1, 2), sp.Integer(1), sp.Integer(5)))
    return sorted(v for v in out if not positive or v > 0)


def _instances(state: State, printed: Any, claim: str, what: str, count: int = 6) -> Finding:
    """Exact decisions on numeric instances: the exact passive range of one parameter
    (:func:`hapticproof.analysis.passiverange.passive_range`) with the others drawn, probed around its ends and
    the printed bound."""
    from hapticproof.analysis.passiverange import passive_range

    if state.repairing:       # instances never confirm: a repair needs an exact condition
        return Finding(Verdict.UNDECIDED, f"{what}: no exact condition to confirm a repair", Evidence(Method.INSTANCES))
    var = _instance_variable(state, printed)
    if var is None:
        return Finding(Verdict.UNDECIDED, f"{what}: no exact condition in closed form and no scene parameter in the display "
                       "to compare on", Evidence(Method.INSTANCES, instances=0))
    params = sorted((s for s in getattr(state.model, "parameters", set()) if s.name not in (var.name, "n")), key=str)
    symbolic_delay = state.scene.delay == "n"
    draws = Sampler(params, seed=11).draw(count)
    not_sufficient = not_necessary = None
    decided = 0
    for k, point in enumerate(draws):
        if symbolic_delay:
            point = {**point, N_SYM: sp.Integer(k % 4)}
        values = {s.name: v for s, v in point.items() if s != N_SYM}
        scene = state.scene.with_params(values)
        if symbolic_delay:
            scene = scene.replace(delay=int(point[N_SYM]))
        try:
            rng = passive_range(scene, var.name)
        except (HapticproofError, ValueError, ArithmeticError):
            continue
        local = printed.xreplace({**point, **({N_SYM: point[N_SYM]} if symbolic_delay else {})})
        bounds = _endpoint_values(rng)
        try:
            pb = as_bound(local, var)
            bounds.append(sp.Rational(pb.bound) if pb.bound.is_Rational else sp.Rational(sp.N(pb.bound, 30)))
        except (TypeError, ValueError, sp.PolynomialError):
            pass
        for v in _probe_values(bounds, bool(var.is_positive)):
            hp = holds_at(local, {var: v})
            if hp is None:
                continue
            outcome = decide_model(scene.with_params({var.name: v}).build(), scene.system)
            if outcome.decision not in (Decision.PROVED, Decision.DISPROVED):
                continue
            decided += 1
            witness = {**{s.name: val for s, val in point.items()}, var.name: v}
            if hp and outcome.decision == Decision.DISPROVED and not_sufficient is None:
                not_sufficient = (witness, outcome)
            if not hp and outcome.decision == Decision.PROVED and not_necessary is None:
                not_necessary = (witness, outcome)
            if (not_sufficient and claim != "necessary") or (not_necessary and claim == "necessary"):
                break
        if (not_sufficient and claim != "necessary") or (not_necessary and claim == "necessary"):
            break
    facts = {"instances": decided, "parameter": var.name}
    if claim != "necessary" and not_sufficient:
        witness, outcome = not_sufficient
        return Finding(Verdict.WRONG, f"{what} holds at the witness where the scene is not positive real (exact decision: "
                       f"{outcome.reason})", Evidence(Method.COUNTEREXAMPLE, witness=witness,
                                                      facts={**facts, "recheck": outcome.to_json()}))
    if claim == "necessary" and not_necessary:
        witness, outcome = not_necessary
        return Finding(Verdict.WRONG, f"{what} fails at the witness where the scene is positive real (exact decision), so it is "
                       "not necessary", Evidence(Method.COUNTEREXAMPLE, witness=witness,
                                                 facts={**facts, "recheck": outcome.to_json()}))
    note = ""
    witness = None
    if claim == "passivity" and not_necessary:
        witness = not_necessary[0]
        note = "; it is not necessary (positive real at the witness where it fails), and its sufficiency is not proved"
    return Finding(Verdict.UNDECIDED, f"{what}: no exact condition in closed form; it agrees with the exact decision on "
                   f"{decided} numeric instances (exact passive ranges of {var.name}), which is no proof{note}",
                   Evidence(Method.INSTANCES, instances=decided, witness=witness, facts=facts))


# ---------------------------------------------------------------------------------------------
# stability
# ---------------------------------------------------------------------------------------------


def _wall_parts(state: State) -> tuple[Any, Any] | None:
    """The stiffness and damping of a virtual-wall environment ``X + Y(z - 1)/(Tz)`` in the
    scene's own names and values (``k_v + d_v(z - 1)/(T_s z)``: ``(k_v, d_v)``), with ``T`` the
    scene's period; None when the environment is no such wall."""
    scene = state.scene
    if scene.system != "single-user" or scene.discretize is not None:
        return None
    key = ("wall-parts", state.spec.scene)
    if key in state.cache:
        return state.cache[key]
    model = state.model
    H = sp.cancel(sp.sympify(model.H))
    parts = None
    num, den = sp.fraction(H)
    if sp.Poly(den, Z_SYM).eval(1) != 0:
        X = sp.cancel(H.subs(Z_SYM, 1))
        Y = sp.cancel((H - X) * model.T * Z_SYM / (Z_SYM - 1))
        if Z_SYM not in X.free_symbols and Z_SYM not in Y.free_symbols and is_identically_zero(
                H - (X + Y * (Z_SYM - 1) / (model.T * Z_SYM))):
            parts = (X, Y)
    state.cache[key] = parts
    return parts


def _is_wall(state: State) -> bool:
    return _wall_parts(state) is not None


def _operator_damping(state: State) -> Any:
    """The damping of an operator ``m_h s + b_h + k_h/s`` (``None``: no operator; error otherwise)."""
    op = state.scene.operator
    if op is None or op == "free":
        return None
    if not isinstance(op, sp.Basic):
        raise ClaimError(f"no leading-order boundary for the operator {op!r}")
    s = sp.Symbol("s")
    expanded = sp.expand(op)
    terms = sp.Add.make_args(expanded)
    if any(sp.degree(t, s) > 1 or (t.has(s) and sp.Poly(sp.expand(t * s), s).degree() not in (0, 2)) for t in terms if t.has(s)):
        raise ClaimError("the leading-order boundary takes an operator m_h s + b_h + k_h/s")
    damping = sp.Add(*[t for t in terms if not t.has(s)])
    return state.prepare(damping)


def _leading(state: State) -> Any:
    key = ("leading-order", state.spec.scene)
    if key not in state.cache:          # shared by the repair trials of one check
        state.cache[key] = _derive_leading(state)
    return state.cache[key]


def _derive_leading(state: State) -> Any:
    from hapticproof.analysis import classics

    parts = _wall_parts(state)
    if parts is None:
        raise ClaimError("the leading-order stability boundary is derived for a virtual wall X + Y(z - 1)/(Tz) "
                         f"(a spring and a damper in any names, {role_marker('period', 'T')} the scene's period); this "
                         "environment is "
                         f"H(z) = {marked(state.model.H)}")
    damping = _operator_damping(state)
    model = state.model
    n = model.delay
    lo = classics.leading_order_boundary(classics.SYMBOLS["n"] if n.is_Symbol else int(n), operator=damping is not None)
    # one renaming table: the classic condition's b, K, B, T are the scene's device damping and
    # period (their roles, values substituted) and the wall's spring and damper, in its names
    stiffness, wall_damping = parts
    mapping = {classics.SYMBOLS["b"]: model.b, classics.SYMBOLS["K"]: stiffness, classics.SYMBOLS["B"]: wall_damping,
               classics.SYMBOLS["T"]: model.T, classics.SYMBOLS["t_d"]: n * model.T}
    if damping is not None:
        mapping[classics.OPERATOR["b_h"]] = damping
    cond = lo.condition.xreplace(mapping)
    return sp.Ge(cond.lhs, sp.expand(cond.rhs), evaluate=False), lo


def stability(state: State) -> Finding:
    """Exact sampled-data stability (certified instances) or its leading order (closed form)."""
    scene_system(state, ("single-user",), "stability-condition")
    printed = _printed_condition(state)
    if printed is None:
        return malformed_finding("the display is not a condition (an inequality) on the parameters")
    if state.spec.order == "leading":
        leading, lo = _leading(state)
        f = compare_conditions(printed, leading, state, claim="passivity",
                               what="the printed stability condition (leading order)")
        facts = {**dict(f.evidence.facts), "leading_order": leading,
                 "critical": f"beta* = {marked(lo.critical)} at the crossing {marker('w')}^2 = {marked(lo.frequency)} "
                             "(alpha = eps a, delta = eps d, beta = eps g)"}
        return Finding(f.verdict, f.detail + "; the leading order of the exact ZOH boundary is "
                       f"{marked(leading)} (classics.leading_order_boundary)",
                       Evidence(f.evidence.method, witness=f.evidence.witness, instances=f.evidence.instances, facts=facts),
                       derived=leading)
    return _stability_instances(state, printed)


def _stable(state: State, values: Mapping[str, Any]) -> Outcome:
    """Certified stability of the exact ZOH loop at the values."""
    from hapticproof.analysis import boundary as bnd

    delay = values.get("n", state.model.delay)
    parts = _wall_parts(state)
    if parts is not None and state.scene.operator is None:
        model = state.model

        def at(expr: Any) -> Any:
            expr = sp.sympify(expr)
            return sp.cancel(expr.xreplace({s: values[s.name] for s in expr.free_symbols if s.name in values}))

        return bnd.certified_stable(values[state.scene.role("mass")], at(model.b), at(model.T), at(parts[0]), at(parts[1]),
                                    int(delay))
    from hapticproof.analysis.sampled import decide_stability, spectral_radius
    from hapticproof.analysis.stability import SceneLoops

    scene = state.scene
    if scene.delay == "n":
        scene = scene.replace(delay=int(delay))
    loop = SceneLoops(scene).scene(**{k: v for k, v in values.items() if k != "n"})
    decision = decide_stability(loop)          # the one decision (rho = 1 exactly is not stable)
    rho = spectral_radius(loop, precision="mp", dps=40)
    facts = {"spectral_radius": str(rho)[:30], "parameters": dict(values)}
    if decision.stable is True:
        return Outcome(Decision.PROVED, Evidence(Method.SPECTRAL, facts=facts), f"spectral radius {float(rho):.10g} < 1")
    if decision.stable is False:
        if decision.fixed_points or decision.verdict != "unstable":
            facts |= {"stability": decision.verdict, "fixed_points": [[str(v) for v in vec] for vec in decision.fixed_points]}
            return Outcome(Decision.DISPROVED, Evidence(Method.SPECTRAL, witness=dict(values), facts=facts), decision.reason)
        return Outcome(Decision.DISPROVED, Evidence(Method.SPECTRAL, witness=dict(values), facts=facts),
                       f"spectral radius {float(rho):.10g} > 1")
    return Outcome(Decision.UNDECIDED, Evidence(Method.SPECTRAL, facts=facts), decision.reason)


def _stability_instances(state: State, printed: Any, count: int = 8) -> Finding:
    scene = state.scene
    names = dict(scene.params)
    mass = scene.role("mass")
    if mass not in names:
        raise ClaimError(f"an exact stability claim needs the device mass {mass} in the scene ([scenes.X.params] "
                         f"{mass} = ... or {mass} = \"positive\")")
    symbols = {s.name: s for s in printed.free_symbols}
    parts = _wall_parts(state)
    stiffness = parts[0].name if parts is not None and isinstance(parts[0], sp.Symbol) else "K"
    var = symbols.get(stiffness) or next((s for n, s in sorted(symbols.items()) if n in state.names), None)
    if var is None:
        return Finding(Verdict.UNDECIDED, "no scene parameter in the display to probe", Evidence(Method.INSTANCES, instances=0))
    model_params = {s.name: s for s in getattr(state.model, "parameters", set())}
    m_symbol = scene.symbol(mass)
    free = sorted([s for n, s in model_params.items() if n not in (var.name, "n")], key=str)
    if isinstance(names[mass], str):
        free.append(m_symbol)
    fixed = {k: v for k, v in state.values.items()}
    ranges = {s: (sp.Rational(1, 100), sp.Integer(2)) for s in free if s.name == scene.role("period")}
    draws = Sampler(free, seed=5, ranges=ranges).draw(count)
    not_sufficient = not_necessary = None
    decided = 0
    for k, point in enumerate(draws):
        values = {**fixed, **{s.name: v for s, v in point.items()}}
        if scene.delay == "n":
            values["n"] = k % 3
        local = printed.xreplace({**{state.names[n]: v for n, v in values.items() if n in state.names and n != "n"},
                                  **({N_SYM: values["n"]} if "n" in values else {})})
        local = local.xreplace({s: values[s.name] for s in local.free_symbols if s.name in values and s != var})
        try:
            pb = as_bound(local, var)
            root = pb.bound
        except (TypeError, ValueError, sp.PolynomialError):
            root = _affine_root(local, var)
        if root is None or not root.is_number or root <= 0:
            continue
        root = sp.Rational(root) if root.is_Rational else sp.Rational(sp.N(root, 30))
        for eps in (sp.Rational(1, 2), sp.Rational(1, 10), sp.Rational(1, 100)):
            for v in (root * (1 - eps), root * (1 + eps)):
                hp = holds_at(local, {var: v})
                if hp is None:
                    continue
                try:
                    outcome = _stable(state, {**values, var.name: v})
                except (HapticproofError, ArithmeticError, ValueError, KeyError):
                    continue
                if outcome.decision not in (Decision.PROVED, Decision.DISPROVED):
                    continue
                decided += 1
                witness = {**values, var.name: v}
                if hp and outcome.decision == Decision.DISPROVED and not_sufficient is None:
                    not_sufficient = (witness, outcome)
                if not hp and outcome.decision == Decision.PROVED and not_necessary is None:
                    not_necessary = (witness, outcome)
        if not_sufficient and not_necessary:
            break
    what = "the printed stability condition"
    if not_sufficient:
        witness, outcome = not_sufficient
        return Finding(Verdict.WRONG, f"{what} holds at the witness where the exact sampled-data loop is unstable "
                       f"({outcome.reason})", Evidence(Method.COUNTEREXAMPLE, witness=witness,
                                                      facts={"certified": outcome.to_json(), "instances": decided}))
    witness = not_necessary[0] if not_necessary else None
    note = ("; it is not necessary: the loop is stable at the witness where it fails" if not_necessary else "")
    return Finding(Verdict.UNDECIDED, f"{what} agrees with certified stability decisions of the exact ZOH loop on {decided} "
                   f"instances near its boundary, which is no proof{note}",
                   Evidence(Method.INSTANCES, instances=decided, witness=witness))


def _affine_root(relation: Any, var: sp.Symbol) -> Any:
    if not isinstance(relation, sp.core.relational.Relational):
        return None
    expr = sp.expand(relation.lhs - relation.rhs)
    try:
        poly = sp.Poly(sp.numer(sp.together(expr)), var)
    except sp.PolynomialError:
        return None
    if poly.degree() != 1:
        return None
    a, b = poly.all_coeffs()
    return sp.cancel(-b / a)


# ---------------------------------------------------------------------------------------------
# same-as
# ---------------------------------------------------------------------------------------------


def same_as(state: State) -> Finding:
    """The display equals equation ``other`` (with ``under`` substituted in both)."""
    from hapticproof.audit.reader.printed import parse_printed

    spec = state.spec
    other = spec.other
    if ":" in other:
        from hapticproof.audit.registry import get_paper

        paper_id, eq_id = other.split(":", 1)
        paper = get_paper(paper_id)
        text, table = paper.get(eq_id).printed, paper.symbols
    else:
        ospec = state.source.claim(other)
        text, table = ospec.printed, state.source.table_for(ospec.scene)
    mine = state.statement
    try:
        theirs = parse_printed(text, table)
    except LatexParseError as err:
        return Finding(Verdict.UNDECIDED, f"equation {other} does not parse ({err.reason} at position {err.position}), so "
                       "the two cannot be compared", Evidence(Method.PARSE, facts={"other": other}))
    names: dict[str, sp.Symbol] = {}
    for value in state.source.symbols.symbols.values():
        for sym in getattr(value, "free_symbols", ()):
            names.setdefault(sym.name, sym)
    under = {names.get(k.name, k): v for k, v in spec.under}

    def unify(expr: Any) -> Any:
        expr = sp.sympify(expr)
        rename = {s: names[s.name] for s in expr.free_symbols if isinstance(s, sp.Symbol) and s.name in names and names[s.name] != s}
        expr = expr.xreplace(rename) if rename else expr
        return expr.xreplace(under) if under else expr

    ids = [spec.id, other]
    mine_rel = [link for r in mine.relations() for link in conjuncts(r.as_sympy())]
    their_rel = [link for r in theirs.relations() for link in conjuncts(r.as_sympy())]
    mine_cond = [unify(r) for r in mine_rel if r.rel_op not in ("==", "!=")]
    their_cond = [unify(r) for r in their_rel if r.rel_op not in ("==", "!=")]
    if mine_cond and their_cond:
        a = mine_cond[0] if len(mine_cond) == 1 else sp.And(*mine_cond)
        b = their_cond[0] if len(their_cond) == 1 else sp.And(*their_cond)
        return _same_condition(state, a, b, ids)
    if mine_cond or their_cond:
        return Finding(Verdict.INCONSISTENT, f"one display is a condition and the other ({other}) an expression",
                       Evidence(Method.PARSE, facts={"ids": ids}))
    a = unify(display_members(mine)[-1])
    b = unify(display_members(theirs)[-1])
    f = compare_expressions(a, b, on_mismatch=Verdict.INCONSISTENT, what=f"the display and equation {other}")
    facts = {**dict(f.evidence.facts), "ids": ids}
    return Finding(f.verdict, f.detail, Evidence(f.evidence.method, witness=f.evidence.witness, facts=facts), derived=b)


def _same_condition(state: State, mine: Any, theirs: Any, ids: list[str]) -> Finding:
    what = f"the display and equation {ids[1]}"
    exact = theirs
    if isinstance(theirs, sp.core.relational.Relational) and theirs.rel_op in (">", "<"):
        exact = (sp.Ge if theirs.rel_op == ">" else sp.Le)(theirs.lhs, theirs.rhs, evaluate=False)
    f = compare_conditions(mine, exact, state, claim="passivity", what=what, derived=theirs)
    if f.verdict == Verdict.CONFIRMED:
        return Finding(Verdict.CONFIRMED, f"{what} are the same condition: {f.detail}",
                       Evidence(f.evidence.method, facts={**dict(f.evidence.facts), "ids": ids}), derived=theirs)
    witness = f.evidence.witness
    if witness is None:
        weaker, stronger, _count = separating_points(mine, theirs)
        point = weaker or stronger
        witness = witness_json(point) if point is not None else None
    if witness is None:
        return Finding(Verdict.UNDECIDED, f"{what}: not proved equal and no point where they differ was found",
                       Evidence(Method.INSTANCES, facts={"ids": ids}), derived=theirs)
    values = {}
    point = {sp.Symbol(k) if isinstance(k, str) else k: v for k, v in witness.items()}
    for label, cond in (("display", mine), (ids[1], theirs)):
        values[label] = holds_at(cond.xreplace({s: point[sp.Symbol(s.name)] for s in cond.free_symbols
                                              if sp.Symbol(s.name) in point}), {})
    return Finding(Verdict.INCONSISTENT, f"{what} are different conditions: at the witness the display "
                   f"{'holds' if values['display'] else 'fails'} and ({ids[1]}) {'holds' if values[ids[1]] else 'fails'}",
                   Evidence(Method.COUNTEREXAMPLE, witness=witness, facts={"ids": ids, "holds": values,
                                                                          "comparison": f.verdict.value}),
                   derived=theirs)
