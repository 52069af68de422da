r"""The checkers of expression claims in paper files: ``inverse-transfer``, ``residue`` and
``hermitian-part`` (see :mod:`hapticproof.audit.claims` for what each decides; the condition claims
are in :mod:`hapticproof.audit.claimconditions`).

Each function takes the :class:`~hapticproof.audit.claims.State` of one check and returns a
:class:`~hapticproof.core.evidence.Finding`; :func:`hapticproof.audit.claims.check` adds the stated
assumption and the repair search around it.

>>> from hapticproof.audit.paperfile import loads, TEMPLATE
>>> from hapticproof.audit.claimbase import State
>>> paper = loads(TEMPLATE)
>>> spec = paper.claim("2")                       # b > KT/2 - B cos(omega T)
>>> hermitian_part(State(spec, paper, spec.printed)).verdict.value
'confirmed'
"""

from __future__ import annotations

from collections.abc import Mapping
from typing import Any

import sympy as sp

from hapticproof.audit.compare import as_bound, compare_expressions
from hapticproof.exact.canonical import is_identically_zero
from hapticproof.audit.claimbase import State, claimed_members, frequency_symbol, display_members, period_of, preferred_variables, conjuncts, compare_conditions
from hapticproof.core.evidence import Decision, Evidence, Finding, Method, Outcome, Verdict
from hapticproof.core.naming import marked, marker, role_marker
from hapticproof.core.errors import HapticproofError
from hapticproof.core.symbols import c as C_SYM
from hapticproof.core.symbols import cos_n as COS_N
from hapticproof.core.symbols import n as N_SYM
from hapticproof.core.symbols import sin_n as SIN_N
from hapticproof.core.symbols import sin_theta as SIN_T
from hapticproof.audit.claimbase import malformed_finding, scene_system

__all__ = ["inverse_transfer", "hermitian_part", "residue"]


def _compare_one(printed: Any, derived: Any, what: str, quick: bool = False) -> Finding:
    """Expression or matrix against the derived one (``wrong`` with a witness when they differ);
    ``quick`` (a repair trial): no witness search, a numeric look first."""
    if quick:
        from hapticproof.audit.claimbase import numerically_different

        pairs = (list(zip(printed, derived)) if isinstance(printed, sp.MatrixBase) and isinstance(derived, sp.MatrixBase)
                 and printed.shape == derived.shape else [(printed, derived)])
        if any(isinstance(a, sp.MatrixBase) or isinstance(b, sp.MatrixBase) for a, b in pairs):
            return Finding(Verdict.WRONG, f"{what} differs", Evidence(Method.CANONICAL_FORM))
        if any(numerically_different(a, b) for a, b in pairs) or not all(is_identically_zero(a - b) for a, b in pairs):
            return Finding(Verdict.WRONG, f"{what} differs", Evidence(Method.CANONICAL_FORM))
    if isinstance(derived, sp.MatrixBase) or isinstance(printed, sp.MatrixBase):
        if not (isinstance(derived, sp.MatrixBase) and isinstance(printed, sp.MatrixBase)) or printed.shape != derived.shape:
            shape = getattr(printed, "shape", "a scalar")
            return Finding(Verdict.WRONG, f"{what} has the shape {shape}, the derived one {getattr(derived, 'shape', 'a scalar')}",
                           Evidence(Method.CANONICAL_FORM), derived=derived)
        for i in range(derived.rows):
            for j in range(derived.cols):
                f = compare_expressions(printed[i, j], derived[i, j], on_mismatch=Verdict.WRONG,
                                        what=f"entry ({i + 1}, {j + 1}) of {what}")
                if f.verdict != Verdict.CONFIRMED:
                    return Finding(f.verdict, f.detail, f.evidence, derived=derived)
        return Finding(Verdict.CONFIRMED, f"{what} equals the derived matrix entry by entry (differences cancel to 0)",
                       Evidence(Method.CANONICAL_FORM), derived=derived)
    return compare_expressions(printed, derived, on_mismatch=Verdict.WRONG, what=what)


def _compare_members(state: State, members: list[Any], derived: Any, what: str) -> Finding:
    state.repairable = True
    findings = [_compare_one(state.prepare(m), derived, f"the printed {what}", quick=state.repairing) for m in members]
    bad = [f for f in findings if f.verdict != Verdict.CONFIRMED]
    if bad:
        return bad[0]
    first = findings[0]
    count = f" ({len(findings)} members of the display)" if len(findings) > 1 else ""
    return Finding(Verdict.CONFIRMED, first.detail + count, first.evidence, derived=derived)


def inverse_transfer(state: State) -> Finding:
    """The display is ``G^{-1}(z)`` of the scene (or ``F_h/V_h``)."""
    system = scene_system(state, ("single-user", "multi-user"), "inverse-transfer")
    if system == "single-user":
        from hapticproof.systems.models import inverse_transfer as derive

        derived = derive(state.model)
    else:
        from hapticproof.systems.multiuser import inverse_transfer_matrix

        derived = inverse_transfer_matrix(state.model)
    members, what, unread = transfer_members(state, display_members(state.statement))
    if unread:
        return malformed_finding(f"the display names G^-1(z) inside {unread}, which does not say what G^-1(z) is",
                                 derived=derived)
    if not members:
        return malformed_finding("no member of the display states G^-1(z): every member is a signal, a name or an unknown function",
                          derived=derived)
    return _compare_members(state, members, derived, what)


_AppliedUndef = sp.core.function.AppliedUndef


def _named_object(expr: sp.Expr) -> tuple[str, Any] | None:
    """How a member names the transfer function: ``("inverse", c)`` for ``c G^{-1}(z)`` (any
    declared function but ``G``, or ``c / G(z)``), ``("direct", c)`` for ``c G(z)``, ``("unread",
    expr)`` for a function inside anything else (``G^{-1}(z) + 1``), None for no function."""
    if not expr.atoms(_AppliedUndef):
        return None
    factors = sp.Mul.make_args(expr)
    core = [f for f in factors if f.has(_AppliedUndef)]
    scale = sp.Mul(*(f for f in factors if not f.has(_AppliedUndef)))
    if len(core) == 1:
        (named,) = core
        if isinstance(named, _AppliedUndef):
            return ("direct" if named.func.__name__ == "G" else "inverse", scale)
        if named.is_Pow and named.exp == -1 and isinstance(named.base, _AppliedUndef) and named.base.func.__name__ == "G":
            return ("inverse", scale)
    return ("unread", expr)


def transfer_members(state: State, members: list[Any]) -> tuple[list[Any], str, str | None]:
    """The members of a display that state ``G^{-1}(z)``, each as the ``G^{-1}(z)`` it claims, with
    how they were read, and the first member that names the transfer function in a way that
    cannot be read (else None).

    A member naming the object fixes how the others read: ``c G^{-1}(z) = X`` claims ``X/c``,
    ``c G(z) = X`` claims ``c/X``, and ``c F_h(z) = X V_h(z)`` (the output signal: not the one
    that a member multiplies by parameters) claims ``X/c``. A bare signal, a label name and a
    ratio of signals state nothing (:func:`~hapticproof.audit.claimbase.claimed_members`).
    Differently scaled names in one chain give every reading, so the display cannot be confirmed.
    """
    signals = state.source.signals()
    values: list[tuple[Any, Any]] = []
    named: list[tuple[str, Any, Any]] = []
    for member in members:
        if isinstance(member, sp.MatrixBase):
            values.append((member, None))
            continue
        member = sp.sympify(member)
        present = {x for x in member.free_symbols if x in signals}
        if len(present) > 1:
            continue
        signal = next(iter(present), None)
        coeff = sp.cancel(sp.together(member / signal)) if signal is not None else member
        if signal is not None and coeff.has(signal):
            continue
        reading = _named_object(coeff)
        if reading is not None:
            if reading[0] == "unread":
                return [], "", marked(member)
            named.append((*reading, signal))
        else:
            values.append((coeff, signal))
    inputs = {x for c, x in values if x is not None and not isinstance(c, sp.MatrixBase) and not c.is_number}
    inputs |= {x for _, _, x in named if x is not None}
    stated = []
    for coeff, signal in values:
        if signal is not None and inputs and signal not in inputs and coeff.is_number and coeff != 0:
            named.append(("inverse", coeff, signal))          # c F_h(z): the output signal, scaled
        elif signal is not None and coeff == 1:
            continue                                         # a bare signal names the output
        else:
            stated.append(coeff)
    stated = claimed_members(state, stated)
    readings = sorted({(kind, scale) for kind, scale, _ in named} or {("inverse", sp.Integer(1))}, key=sp.srepr)
    out = []
    for kind, scale in readings:
        for x in stated:
            if kind == "direct":
                y = scale * x.inv() if isinstance(x, sp.MatrixBase) else sp.cancel(scale / x)
            else:
                y = x if scale == 1 else (x / scale if isinstance(x, sp.MatrixBase) else sp.cancel(x / scale))
            out.append(y)
    what = "G(z) (inverted)" if all(kind == "direct" for kind, _ in readings) else "G^-1(z)"
    if any(scale != 1 for _, scale in readings):
        what += " (the named side's factor divided out)"
    return out, what, None


def residue(state: State) -> Finding:
    """The display is the residue (matrix) of ``G^{-1}`` at ``z = 1``."""
    system = scene_system(state, ("single-user", "multi-user"), "residue")
    if system == "single-user":
        from hapticproof.analysis.positivereal import residues

        found = [r.residue for r in residues(state.model) if r.pole == 1]
    else:
        from hapticproof.analysis.multiuser import residues

        found = [r.matrix for r in residues(state.model) if r.pole == 1]
    derived = found[0] if found else sp.Integer(0)
    members = claimed_members(state, display_members(state.statement))
    if not members:
        return malformed_finding("no member of the display states the residue", derived=derived)
    return _compare_members(state, members, derived, "residue at z = 1")


def _to_c(expr: Any, state: State) -> sp.Expr:
    """A printed expression in ``cos(k omega T)``, ``e^{j omega T}``, ``\\Re``... as a function of ``c``."""
    from hapticproof.exact.unitcircle import omega_to_c

    expr = _real_form(expr)
    omega = frequency_symbol(state)
    if omega is None or omega not in expr.free_symbols:
        return expr
    try:
        out = sp.cancel(omega_to_c(expr, omega, period_of(state)))
    except ValueError:      # not a function of cos(omega T) alone (e.g. cos(omega t_d - T)): keep omega
        return expr
    if any(isinstance(sym, sp.Dummy) for sym in out.free_symbols):
        return expr         # theta left over (omega T/2 outside any cosine): keep omega, never c and theta apart
    return out


def _with_omega(exact: Any, printed: Any, state: State) -> Any:
    """The exact condition in ``omega`` when the printed one could not be written in ``c``."""
    omega = frequency_symbol(state)
    if omega is not None and omega in sp.sympify(printed).free_symbols:
        return exact.xreplace({C_SYM: sp.cos(omega * period_of(state))})
    return exact


def _real_form(expr: Any) -> sp.Expr:
    expr = sp.sympify(expr)
    if expr.has(sp.exp, sp.re, sp.im, sp.I):
        expr = sp.expand_complex(expr.rewrite(sp.cos))
    return expr


def _theta(expr: Any, state: State) -> sp.Expr:
    """A printed expression with a symbolic delay in the canonical theta-form (every integer n)."""
    from hapticproof.exact.unitcircle import canonical_theta

    omega = frequency_symbol(state)
    dummy = sp.Dummy("t_d")
    return canonical_theta(_real_form(expr), omega if omega is not None else sp.Dummy("omega"), period_of(state), dummy, N_SYM)


def _at_delay(state: State, n: int) -> Any:
    from dataclasses import replace

    return replace(state.model, delay=sp.Integer(n))


def _at_delay_n(f: Finding, n: int, note: str) -> Finding:
    """A finding at the delay instance ``n``: the same verdict, ``n`` added to its witness."""
    witness = dict(f.evidence.witness or {})
    witness["n"] = n
    return Finding(f.verdict, f.detail + note, Evidence(f.evidence.method, witness=witness, facts=dict(f.evidence.facts)),
                   derived=f.derived)


def hermitian_part(state: State) -> Finding:
    """The display is ``Re G^{-1}(e^{j omega T})`` (or the condition ``Re G^{-1} >= 0`` at each frequency)."""
    system = scene_system(state, ("single-user", "multi-user", "teleoperator"), "hermitian-part")
    statement = state.statement
    relations = statement.relations()
    is_condition = bool(relations) and any(op != "=" for r in relations for op in r.ops)
    if system == "multi-user":
        return _hermitian_matrix(state)
    if system == "teleoperator":
        return _teleoperator_bounds(state, is_condition)
    from hapticproof.analysis.positivereal import hermitian

    form = hermitian(state.model)
    symbolic_delay = state.model.delay.is_Symbol
    if state.spec.form == "condition" and not is_condition:
        members = claimed_members(state, display_members(statement))
        same = False
        if len(members) == 1 and not symbolic_delay:
            same = is_identically_zero(_to_c(state.prepare(members[0]), state) - form.expr())
        what = "equals Re G^-1 exactly" if same else "is not Re G^-1"
        return malformed_finding(f"the display is an expression, not a condition: '> 0' is missing (the expression {what})",
                          corrected=(state.printed.rstrip() + " > 0") if same else None,
                          derived=sp.Ge(form.expr(), 0) if not symbolic_delay else None)
    if state.spec.form == "expression" and is_condition:
        return malformed_finding("the display is a condition, but the claim says it is the expression Re G^-1")
    if is_condition:
        return _hermitian_condition(state, form, symbolic_delay)
    members = claimed_members(state, display_members(statement))
    if not members:
        return malformed_finding("no member of the display states Re G^-1")
    state.repairable = True
    derived = form.canonical() if symbolic_delay else form.expr()
    shown = form.expr(_THETA) if symbolic_delay else derived
    findings = [_circle_compare(state, state.prepare(m), derived, shown, symbolic_delay) for m in members]
    bad = [f for f in findings if f.verdict != Verdict.CONFIRMED]
    out = bad[0] if bad else findings[0]
    if not symbolic_delay and any(getattr(sym, "name", None) == "n" for m in members for sym in sp.sympify(m).free_symbols):
        out = Finding(out.verdict, out.detail + f" (the printed n is the scene's delay n = {state.model.delay})",
                      out.evidence, derived=out.derived, corrected=out.corrected)
    return out


#: ``theta = omega T`` of the printed displays compared on the circle.
_THETA = sp.Symbol("theta", real=True)


def _in_theta(expr: Any, state: State) -> sp.Expr:
    """A printed expression with ``omega T`` replaced by ``theta`` (``t_d = n T`` is already in)."""
    expr = _real_form(expr)
    omega = frequency_symbol(state)
    if omega is None or omega not in expr.free_symbols:
        return expr
    return sp.sympify(expr).xreplace({omega: _THETA / period_of(state)})


_CIRCLE_VARIABLES = (C_SYM, SIN_T, COS_N, SIN_N, _THETA, N_SYM)


def _circle_compare(state: State, printed: Any, derived: Any, shown: Any, symbolic_delay: bool) -> Finding:
    """The printed ``Re G^{-1}`` against the derived form (in ``c``, or the theta-form of a
    symbolic delay) as functions on the unit circle (:class:`~hapticproof.exact.unitcircle.CircleForm`:
    half angles, Dirichlet kernels, shifted cosines and products of sines are exact); when they
    differ, an exact point of the circle where they do, every linked quantity from one angle."""
    from hapticproof.exact.unitcircle import circle_form, theta_form_on_circle

    c, theta, T = marker("cos"), marker("theta"), role_marker("period", "T")
    what = ("the printed Re G^-1" + (" (every integer delay n)" if symbolic_delay else f" (in {c} = cos(omega {T}))"))
    in_theta = _in_theta(printed, state)
    if state.repairing and _circle_differs_numerically(in_theta, derived, symbolic_delay):
        return Finding(Verdict.WRONG, f"{what} differs", Evidence(Method.CANONICAL_FORM))
    n = N_SYM if symbolic_delay else None
    try:
        form_p = circle_form(in_theta, _THETA, n)
    except ValueError:
        form_p = None
    form_d = theta_form_on_circle(derived)
    if form_p is not None and form_p.equals(form_d):
        root = f"e^{{j {theta}}}" if form_p.L == 1 else f"e^{{j {theta}/{form_p.L}}}"   # (z = e^{j theta/L})
        how = (f"for every integer delay n: equal as rational functions of {root} and e^{{j n {theta}}}, "
               f"which are independent for {theta}/pi irrational (structural)" if symbolic_delay
               else f"identically on the unit circle (equal as rational functions of {root})")
        facts: dict[str, Any] = {"printed_form": ("equals the derived", sp.sstr(derived))}
        if not state.repairing:
            judge = _circle_judge_equal(state, printed, in_theta, derived, symbolic_delay, form_p.L)
            if judge is not None:
                facts["judge"] = judge
        return Finding(Verdict.CONFIRMED, f"{what} equals the derived one {how}",
                       Evidence(Method.STRUCTURAL if symbolic_delay else Method.CANONICAL_FORM, facts=facts), derived=shown)
    if state.repairing:
        return Finding(Verdict.WRONG, f"{what} differs", Evidence(Method.CANONICAL_FORM))
    found = _circle_difference(state, in_theta, derived, symbolic_delay, form_p.L if form_p is not None else 1)
    if found is None:
        return Finding(Verdict.UNDECIDED, f"{what} and the derived one differ in form, and no point of the circle where "
                       "they differ was found", Evidence(Method.CANONICAL_FORM, instances=_ANGLE_TRIES), derived=shown)
    values, point, pv, dv = found
    from hapticproof.audit.judged import circle_judge, witness_of

    witness = witness_of(values, point, period_of(state))
    facts = {"printed_value": pv, "derived_value": dv, "printed_form": ("reads", sp.sstr(in_theta)),
             "point": f"{theta} = omega {T} = {marked(point['theta'])}, z = e^(j {theta}) = {point['z'][0]} + "
                      f"{point['z'][1]} j, {c} = {point['c']}"}
    judge = circle_judge("differ", printed, getattr(frequency_symbol(state), "name", "omega"), period_of(state),
                         [_judge_point(state, values, point)])
    if judge is not None:
        facts["judge"] = judge
    shown_pv = sp.N(pv, 12) if not pv.is_Rational else pv
    return Finding(Verdict.WRONG, f"{what} differs from the derived one: {marked(shown_pv)} vs {marked(dv)} at the "
                   f"witness (one angle {theta} = {marked(point['theta'])} gives omega, {c} and z)",
                   Evidence(Method.COUNTEREXAMPLE, witness=witness, facts=facts), derived=shown)


_ANGLE_TRIES = 12


def _circle_differs_numerically(in_theta: sp.Expr, derived: sp.Expr, symbolic_delay: bool) -> bool:
    """A quick look at two points of the circle (used only to skip a repair, never to decide)."""
    from hapticproof.audit.judged import circle_point
    from hapticproof.exact.canonical import Sampler

    symbols = sorted((sp.sympify(in_theta).free_symbols | sp.sympify(derived).free_symbols) - set(_CIRCLE_VARIABLES), key=str)
    ranges = {s: (sp.Rational(1, 3), sp.Integer(3)) for s in symbols}
    for k, values in enumerate(Sampler(symbols, seed=13, ranges=ranges).draw(3)[1:]):
        point = circle_point(sp.Rational(2 + k, 7), 1, 2 + k if symbolic_delay else None)
        sub = {C_SYM: point["c"], SIN_T: point["z"][1]}
        if symbolic_delay:
            sub.update({COS_N: point["z^n"][0], SIN_N: point["z^n"][1]})
        try:
            dv = sp.N(sp.sympify(derived).xreplace(values).xreplace(sub), 30)
            pv = sp.N(sp.sympify(in_theta).xreplace(values).xreplace(
                {_THETA: point["theta"], **({N_SYM: point["n"]} if symbolic_delay else {})}), 30)
        except (TypeError, ValueError, ZeroDivisionError):
            continue
        if pv.is_number and dv.is_number and pv.is_finite and dv.is_finite and abs(pv - dv) > sp.Float("1e-12") * (1 + abs(dv)):
            return True
    return False


def _circle_difference(state: State, in_theta: sp.Expr, derived: sp.Expr, symbolic_delay: bool, L: int) -> Any:
    """``(values, point, printed value, derived value)`` at the first exact point where the two
    differ (certified), or ``None``."""
    from hapticproof.audit.judged import ANGLES, circle_point
    from hapticproof.exact.canonical import Sampler, certified_nonzero

    symbols = _sampled_symbols(state, in_theta, derived)
    delays = (1, 2, 3) if symbolic_delay else (None,)
    for values in Sampler(symbols, seed=3).draw(12):
        for t in ANGLES[:_ANGLE_TRIES]:
            for n in delays:
                point = circle_point(t, L, n)
                sub = {C_SYM: point["c"], SIN_T: point["z"][1]}
                if n is not None:
                    sub.update({COS_N: point["z^n"][0], SIN_N: point["z^n"][1], N_SYM: n})
                dv = sp.sympify(derived).xreplace(values).xreplace(sub)
                if dv.has(sp.zoo, sp.nan, sp.oo) or not dv.is_number:
                    continue
                dv = sp.nsimplify(sp.cancel(dv))
                pv = sp.sympify(in_theta).xreplace(values).xreplace({_THETA: point["theta"], **({N_SYM: n} if n else {})})
                if pv.has(sp.zoo, sp.nan, sp.oo) or not pv.is_number:
                    continue
                try:
                    if certified_nonzero(pv - dv):
                        return values, point, pv, dv
                except (TypeError, ValueError, ZeroDivisionError):
                    continue
    return None


def _sampled_symbols(state: State, in_theta: sp.Expr, derived: sp.Expr) -> list[sp.Symbol]:
    """The parameters a point of the circle needs: those of both forms, and the period ``T``
    (``omega = theta/T`` even where ``T`` cancels from both)."""
    symbols = (sp.sympify(in_theta).free_symbols | sp.sympify(derived).free_symbols) - set(_CIRCLE_VARIABLES)
    period = sp.sympify(period_of(state))
    symbols |= period.free_symbols
    return sorted(symbols, key=str)


def _judge_point(state: State, values: Mapping[Any, Any], point: Mapping[str, Any]) -> dict[str, Any]:
    from hapticproof.audit.claimbase import numeric_scene_at
    from hapticproof.audit.judged import transfer_at

    at = dict(values)
    if "n" in point:
        at["n"] = point["n"]
    try:
        transfer = transfer_at(numeric_scene_at(state, at).build())
    except HapticproofError:
        transfer = None
    return {**point, "values": dict(values), "transfer": transfer}


def _circle_judge_equal(state: State, printed: Any, in_theta: sp.Expr, derived: sp.Expr, symbolic_delay: bool,
                        L: int) -> dict[str, Any] | None:
    """The judge's sample points of a confirmed identity: a few parameter values, angles and
    delays where the display must equal ``Re G^{-1}`` of the scene."""
    from hapticproof.audit.judged import ANGLES, circle_judge, circle_point, scene_inverse
    from hapticproof.exact.canonical import Sampler

    symbols = _sampled_symbols(state, in_theta, derived)
    rows = []
    for k, values in enumerate(Sampler(symbols, seed=11).draw(3)):
        point = circle_point(ANGLES[(3 * k) % len(ANGLES)], L, (1, 2, 5)[k] if symbolic_delay else None)
        rows.append(_judge_point(state, values, point))
    return circle_judge("equal", printed, getattr(frequency_symbol(state), "name", "omega"), period_of(state), rows,
                        inverse=scene_inverse(state))


def _in_c(relation: Any, state: State) -> Any:
    return relation.func(_to_c(relation.lhs, state), _to_c(relation.rhs, state), evaluate=False)


def _verify_pointwise(state: State):
    """Re-check a (parameters, c) witness: the numeric scene's Re G^-1 at that c, exactly."""
    from hapticproof.analysis.positivereal import hermitian

    def verify(point: dict) -> Outcome:
        by_name = {getattr(k, "name", k): v for k, v in point.items()}
        if "c" in by_name:
            c_value = by_name["c"]
        elif "omega" not in by_name:       # neither condition depends on the frequency: any c will do
            c_value = sp.Integer(0)
        else:
            period = state.scene.role("period") if state.scene is not None and state.scene.system != "network" else "T"
            T = by_name.get(period, period_of(state))
            c_value = sp.cos(by_name["omega"] * T)
        numeric = _numeric_model(state, point)
        form = hermitian(numeric)
        value = form(c_value) if sp.sympify(c_value).is_Rational else sp.N(form.expr().subs(C_SYM, c_value), 50)
        decision = Decision.DISPROVED if bool(sp.N(value, 50) < 0) else Decision.PROVED
        return Outcome(decision, Evidence(Method.CANONICAL_FORM, witness={"c": c_value}, facts={"Re G^-1": value}),
                       f"Re G^-1 = {value} at {marker('cos')} = {c_value}")

    return verify


def _numeric_model(state: State, point: Mapping[Any, Any]) -> Any:
    from hapticproof.audit.claimbase import numeric_scene_at

    return numeric_scene_at(state, point).build()


def _hermitian_condition(state: State, form: Any, symbolic_delay: bool) -> Finding:
    relation = _single(state)
    if relation is None:
        return malformed_finding("a Hermitian-part condition is one inequality; the display has none or several")
    printed = state.prepare(relation)
    what = "the printed frequency-wise condition"
    if not symbolic_delay:
        exact = sp.Ge(form.expr(), 0, evaluate=False)
        in_c = _in_c(printed, state)
        return compare_conditions(in_c, _with_omega(exact, in_c, state), state, claim="passivity", what=what,
                                  verify=_verify_pointwise(state), derived=exact)
    if state.repairing and _differs_at_instances(printed, form, state):
        return Finding(Verdict.WRONG, f"{what} differs from Re G^-1 >= 0", Evidence(Method.INSTANCES))
    canonical = printed.func(_theta(printed.lhs, state), _theta(printed.rhs, state), evaluate=False)
    exact = sp.Ge(form.canonical(), 0, evaluate=False)
    var = next((v for v in (state.names.get(n) for n in preferred_variables(state)) if v is not None and v in canonical.free_symbols), None)
    if var is not None:
        try:
            p, e = as_bound(canonical, var), as_bound(exact, var)
            if getattr(p, "lower", True) and is_identically_zero(sp.expand(p.bound - e.bound)):
                state.repairable = True
                return Finding(Verdict.CONFIRMED, f"{what} is equivalent to Re G^-1 >= 0 at every frequency, for every "
                               f"integer delay n (bounds on {var} equal in the canonical {marker('theta')}-form)",
                               Evidence(Method.CANONICAL_FORM, facts={"printed_bound": p.bound, "exact_bound": e.bound}),
                               derived=sp.Ge(form.expr(_THETA), 0))
        except (TypeError, ValueError, sp.PolynomialError):
            pass
    from hapticproof.analysis.positivereal import hermitian

    if state.repairing:     # a repair must be exact for every n: the canonical forms decide
        return Finding(Verdict.WRONG, f"{what} differs from Re G^-1 >= 0 in the canonical {marker('theta')}-form",
                       Evidence(Method.CANONICAL_FORM))
    last = None
    for n in (1, 2, 3):
        at_n = printed.xreplace({N_SYM: n})
        exact_n = sp.Ge(hermitian(_at_delay(state, n)).expr(), 0, evaluate=False)
        in_c = _in_c(at_n, state)
        f = compare_conditions(in_c, _with_omega(exact_n, in_c, state), state, claim="passivity",
                               what=f"{what} at n = {n}", verify=_verify_at_delay(state, n), derived=exact_n)
        last = f
        if f.verdict != Verdict.CONFIRMED:
            return _at_delay_n(f, n, " (the display is not Re G^-1 >= 0 for every n)")
    return Finding(Verdict.UNDECIDED, f"the canonical {marker('theta')}-forms differ, but the conditions agree at n = 1, 2, 3",
                   Evidence(Method.INSTANCES, instances=3), derived=last.derived if last else None)


def _differs_at_instances(printed: Any, form: Any, state: State) -> bool:
    """A quick numeric look (used only to skip repairs, never to confirm): the printed and the
    exact bounds on the damping differ at random points (n = 2, 3)."""
    var = state.names.get(preferred_variables(state)[0])
    omega = frequency_symbol(state)
    if var is None or omega is None or not isinstance(printed, sp.core.relational.Relational):
        return False
    sign = 1 if printed.rel_op in (">", ">=") else -1
    f = sp.sympify(printed.lhs - printed.rhs) * sign
    g = sp.sympify(form.expr(omega * period_of(state)))
    free = sorted((f.free_symbols | g.free_symbols) - {var}, key=str)
    for k, value in enumerate((sp.Rational(7, 10), sp.Rational(13, 10))):
        point = {s: (sp.Integer(2 + k) if s.is_integer else value + sp.Rational(j, 7)) for j, s in enumerate(free)}
        roots = []
        for h in (f, g):
            try:
                h0 = sp.N(h.xreplace({**point, var: 0}), 30)
                h1 = sp.N(h.xreplace({**point, var: 1}), 30) - h0
            except (TypeError, ValueError, ZeroDivisionError):
                return False
            if not (h0.is_number and h1.is_number) or abs(h1) < sp.Float("1e-20"):
                return h is f and h0.is_number
            if h1 < 0:
                return True       # an upper bound on the damping: not Re G^-1 >= 0
            roots.append(-h0 / h1)
        if abs(roots[0] - roots[1]) > sp.Float("1e-12") * (1 + abs(roots[1])):
            return True
    return False


def _verify_at_delay(state: State, n: int):
    base = _verify_pointwise(state)

    def verify(point: dict) -> Outcome:
        return base({**point, "n": n})

    return verify


def _hermitian_matrix(state: State) -> Finding:
    """m users: the printed matrix against ``M = G + G^H`` (or ``M/2``), or a scalar against their principal minors."""
    from itertools import combinations

    from hapticproof.analysis.multiuser import hermitian

    M = hermitian(state.model).matrix()
    relation = _single(state)
    if relation is not None and relation.rel_op not in ("==", "!="):
        return _minor_condition(state, relation, M)
    members = claimed_members(state, display_members(state.statement))
    if not members:
        return malformed_finding("no member of the display states the Hermitian part")
    state.repairable = True
    printed = state.prepare(members[-1])
    if isinstance(printed, sp.MatrixBase):
        printed = printed.applyfunc(lambda e: _to_c(e, state))
        for scale, name in ((1, "G + G^H"), (sp.Rational(1, 2), "(G + G^H)/2")):
            f = _compare_one(printed, (M * scale).applyfunc(sp.expand), f"the printed matrix ({name})")
            if f.verdict == Verdict.CONFIRMED:
                return f
        return _compare_one(printed, (M / 2).applyfunc(sp.expand), "the printed Hermitian part (G + G^H)/2")
    from hapticproof.core.limits import check_minors

    value = _to_c(printed, state)
    m = M.rows
    check_minors(m, "the principal minors of G + G^H")
    for size in range(1, m + 1):
        for rows in combinations(range(m), size):
            minor = M.extract(list(rows), list(rows)).det()
            for scale in (1, sp.Rational(1, 2) ** size):
                if is_identically_zero(value - minor * scale):
                    label = "(" + ", ".join(str(r + 1) for r in rows) + ")"
                    return Finding(Verdict.CONFIRMED, f"the printed expression is the principal minor {label} of "
                                   f"{'G + G^H' if scale == 1 else '(G + G^H)/2'}", Evidence(Method.CANONICAL_FORM),
                                   derived=minor * scale)
    first = M[:1, :1].det() / 2
    return compare_expressions(value, first, on_mismatch=Verdict.WRONG,
                               what="the printed expression (no principal minor of the Hermitian part matches; vs the first)")


def _teleoperator_bounds(state: State, is_condition: bool) -> Finding:
    """Teleoperator: the frequency-wise passivity condition, each robot's damping at least its
    bound at every frequency (the teleoperator paper's eq. 32, exact in ``c``)."""
    from hapticproof.analysis.teleoperator import bounds

    relation = _single(state)
    if not is_condition or relation is None:
        c = marker("cos")
        return malformed_finding("for a teleoperator the frequency-wise claim is a condition on the dampings "
                                 f"({role_marker('master_damping', 'b_m')} >= bound({c}), "
                                 f"{role_marker('slave_damping', 'b_s')} >= bound({c})); the display is none")
    model = state.model
    bd = bounds(model)
    exact = sp.And(sp.Ge(model.b_m, bd.master, evaluate=False), sp.Ge(model.b_s, bd.slave, evaluate=False))
    printed = _in_c(state.prepare(relation), state)
    return compare_conditions(printed, exact, state, claim="passivity", what="the printed frequency-wise condition")


def _principal_minors(M: sp.Matrix) -> list[tuple[str, sp.Expr]]:
    from itertools import combinations

    from hapticproof.core.limits import check_minors

    check_minors(M.rows, "the principal minors of G + G^H")
    out = []
    for size in range(1, M.rows + 1):
        for rows in combinations(range(M.rows), size):
            out.append(("(" + ", ".join(str(r + 1) for r in rows) + ")", sp.expand(M.extract(list(rows), list(rows)).det())))
    return out


def _minor_condition(state: State, relation: Any, M: sp.Matrix) -> Finding:
    """m users, a condition display: a principal minor of ``G + G^H`` (times a positive
    factor) is non-negative at each frequency."""
    from hapticproof.audit.claimbase import positive_ratio_at_points, ratio_equivalent

    what = "the printed frequency-wise condition"
    state.repairable = True
    key = ("principal-minors", state.spec.scene)
    if key not in state.cache:           # shared by the repair trials of one check
        state.cache[key] = _principal_minors(M)
    minors = state.cache[key]
    prepared = state.prepare(relation)
    if state.repairing and not _may_be_a_minor(prepared, minors, state):
        return Finding(Verdict.WRONG, f"{what} is no principal minor condition", Evidence(Method.CANONICAL_FORM))
    printed = _in_c(prepared, state)
    for label, minor in minors:
        exact = sp.Ge(minor, 0, evaluate=False)
        if positive_ratio_at_points(printed, exact) and ratio_equivalent(printed, exact):
            return Finding(Verdict.CONFIRMED, f"{what} is 'the principal minor {label} of G + G^H is >= 0' multiplied by a "
                           "positive factor", Evidence(Method.CANONICAL_FORM, facts={"minor": label}), derived=exact)
    if state.repairing:
        return Finding(Verdict.WRONG, f"{what} is no principal minor condition", Evidence(Method.CANONICAL_FORM))
    label, minor = minors[0]
    f = compare_conditions(printed, sp.Ge(minor, 0, evaluate=False), state, claim="passivity",
                           what=f"{what} (no principal minor of G + G^H matches; compared with the minor {label})")
    return f


def _may_be_a_minor(relation: Any, minors: list[tuple[str, Any]], state: State) -> bool:
    """A cheap look before the exact comparison (used only to skip repair trials): with
    ``cos(omega T)`` read as ``c``, is the display a positive constant times some principal
    minor at a few exact points? A display in other functions of omega is not skipped."""
    from hapticproof.audit.claimbase import constant_positive_ratio

    omega = frequency_symbol(state)
    if not isinstance(relation, sp.core.relational.Relational) or relation.rel_op not in (">", ">=", "<", "<="):
        return True
    sign = 1 if relation.rel_op in (">", ">=") else -1
    expr = sp.sympify(relation.lhs - relation.rhs) * sign
    if omega is not None:
        expr = expr.xreplace({sp.cos(omega * period_of(state)): C_SYM})
        if omega in expr.free_symbols:
            return True
    return any(constant_positive_ratio(expr, minor) is not False for _label, minor in minors)


def _single(state: State) -> Any:
    relations = state.statement.relations()
    links = [link for r in relations for link in conjuncts(r.as_sympy())]
    if len(links) != 1:
        return None
    return links[0]
