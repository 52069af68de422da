r"""The teleoperator paper, Section II: the robots, terminations and controllers (1)-(7).
"""

from __future__ import annotations

import functools
from typing import Any

import sympy as sp

from hapticproof.analysis import classics
from hapticproof.audit.runner import AuditContext, malformed
from hapticproof.audit.compare import compare_expressions
from hapticproof.exact.canonical import is_identically_zero
from hapticproof.core.evidence import Evidence, Finding, Method, Verdict
from hapticproof.derivations.teleoperator.paper import ASSUME, CONTROLLERS, ERROR_TABLE, E_ERR, FUN, F_E, F_H, F_M, F_S, PAPER, PHANTOM, PRINTED, T, TIME, XDD_M, XDD_S, XD_M, XD_S, X_M, X_S, alpha, b_m, b_s, device_residual, k_idx, line_pairs, m_m, m_s, parse_with, relations_of, s, t, tau


@PAPER.equation("1", kind="expression", printed=PRINTED["1"], section="II", assumptions=ASSUME,
                derivation="device model m dv/dt = f - b v - u (controller force subtracted), as in hapticproof.analysis.sampled")
def eq1(ctx: AuditContext) -> Finding:
    (l1, r1), (l2, r2) = line_pairs(ctx.statement)
    derived = (device_residual(m_m, b_m, F_H, F_M, XD_M, XDD_M), device_residual(m_s, b_s, F_E, F_S, XD_S, XDD_S))
    same = [is_identically_zero((lhs - rhs) + res) for (lhs, rhs), res in zip(((l1, r1), (l2, r2)), derived)]
    if all(same):
        return Finding(Verdict.CONFIRMED, "both lines are the rigid 1-DOF robot with the controller force subtracted "
                       "(the convention of the toolkit's sampled loops)",
                       Evidence(Method.CANONICAL_FORM, facts={"residuals": derived}))
    return Finding(Verdict.WRONG, "a robot equation is not Newton's law for the mass-damper robot",
                   Evidence(Method.CANONICAL_FORM, facts={"lines_match": same}))


@PAPER.equation("2", kind="expression", printed=PRINTED["2"], section="II", assumptions=ASSUME,
                derivation="a termination of impedance Z applies F = F_ext - Z V with V = s X")
def eq2(ctx: AuditContext) -> Finding:
    (l1, r1), (l2, r2) = line_pairs(ctx.statement)
    derived = (FUN["tildeF_h"](s) - FUN["F_h"](s) - FUN["Z_h"](s) * s * FUN["X_m"](s),
               FUN["tildeF_e"](s) - FUN["F_e"](s) - FUN["Z_e"](s) * s * FUN["X_s"](s))
    if is_identically_zero(l1 - r1 - derived[0]) and is_identically_zero(l2 - r2 - derived[1]):
        return Finding(Verdict.CONFIRMED, "both terminations apply the exogenous force minus impedance times velocity "
                       "(passive Z absorbs energy), the convention of hapticproof.systems.impedance.Impedance",
                       Evidence(Method.CANONICAL_FORM, facts={"derived": derived}))
    return Finding(Verdict.WRONG, "a termination law differs from F = F_ext - Z s X", Evidence(Method.CANONICAL_FORM))


@PAPER.equation("3", kind="expression", printed=PRINTED["3"], section="II", assumptions=ASSUME,
                derivation="Laplace transform of (1) at rest (SymPy laplace_transform of the ODE)")
def eq3(ctx: AuditContext) -> Finding:
    x = sp.Function("x")
    out = []
    for (lhs, rhs), (mass, damping, port, control, pos) in zip(
        line_pairs(ctx.statement),
        ((m_m, b_m, FUN["F_h"], FUN["F_m"], FUN["X_m"]), (m_s, b_s, FUN["F_e"], FUN["F_s"], FUN["X_s"])),
    ):
        tt = sp.Symbol("t_", positive=True)
        transform = sp.laplace_transform(mass * x(tt).diff(tt, 2) + damping * x(tt).diff(tt), tt, s, noconds=True)
        at_rest = transform.subs({x(0): 0, sp.Subs(x(tt).diff(tt), tt, 0): 0}).doit()
        at_rest = at_rest.subs(sp.LaplaceTransform(x(tt), tt, s), pos(s))
        # (m s^2 + b s) X = F_port - F_control  =>  s X = (F_port - F_control)/(m s + b)
        derived = sp.cancel(s * (port(s) - control(s)) / at_rest.subs(pos(s), 1))
        out.append(compare_expressions(rhs, derived, what="s X(s)"))
        if not is_identically_zero(lhs - s * pos(s)):
            return malformed(ctx, "the left-hand side is not s X(s)")
    bad = [f for f in out if f.verdict != Verdict.CONFIRMED]
    if bad:
        return bad[0]
    return Finding(Verdict.CONFIRMED, "both lines are the Laplace transforms of (1) at rest, solved for the velocity s X(s)",
                   Evidence(Method.CANONICAL_FORM, facts={"derived_by": "sympy.laplace_transform of m x'' + b x'"}))


@PAPER.equation("4", kind="expression", printed=PRINTED["4"], section="II", assumptions=ASSUME,
                derivation="Laplace transform of the Dirac comb sum_k x(kT) delta(t - kT), term by term")
def eq4(ctx: AuditContext) -> Finding:
    (rel,) = relations_of(ctx.statement)
    printed_sum = rel.rhs
    expected = (FUN["X^*"](s), FUN["L"](FUN["x^*"](t)))
    if tuple(rel.terms[:-1]) != expected[:len(rel.terms) - 1] or len(rel.terms) != 3:
        return Finding(Verdict.TYPO, f"the chain must read X^*(s) = L{{x^*(t)}} = ...; it reads "
                       f"{' = '.join(sp.sstr(t_) for t_ in rel.terms[:-1])} = ...",
                       Evidence(Method.PARSE, facts={"printed_form": [sp.srepr(t_) for t_ in rel.terms[:-1]]}))
    tt = sp.Symbol("t_", positive=True)
    term = sp.laplace_transform(sp.DiracDelta(tt - k_idx * T), tt, s, noconds=True)
    derived = sp.Sum(FUN["x"](k_idx * T) * term, (k_idx, 0, sp.oo))
    if isinstance(printed_sum, sp.Sum):
        ((var, lo, hi),) = printed_sum.limits    # the parser's own summation symbol
        printed_sum = sp.Sum(printed_sum.function.subs(var, k_idx), (k_idx, lo, hi))
    if isinstance(printed_sum, sp.Sum) and printed_sum.limits == derived.limits and is_identically_zero(
        printed_sum.function - derived.function
    ):
        return Finding(Verdict.CONFIRMED, "the transform of x(kT) delta(t - kT) is x(kT) e^{-skT} (SymPy), summed over k >= 0",
                       Evidence(Method.CANONICAL_FORM, facts={"term": term}), derived=derived)
    return compare_expressions(printed_sum, derived, what="X^*(s)")


@PAPER.equation("5", kind="expression", printed=PRINTED["5"], section="II", assumptions=ASSUME,
                derivation="ZOH of the impulse sampler (4): Laplace transform of the unit pulse of width T")
def eq5(ctx: AuditContext) -> Finding:
    zoh = classics.zoh_transfer(s, T)
    ratios = []
    for (lhs, rhs), (held, sampled) in zip(line_pairs(ctx.statement), ((FUN["F_m"](s), FUN["F_m^*"](s)),
                                                                         (FUN["F_s"](s), FUN["F_s^*"](s)))):
        if lhs != held or not rhs.has(sampled):
            return Finding(Verdict.TYPO, f"the hold must map {sp.sstr(sampled)} to {sp.sstr(held)}: the display reads "
                           f"{sp.sstr(lhs)} = {sp.sstr(rhs)}", Evidence(Method.PARSE, facts={"printed_form": sp.srepr(rhs)}))
        ratios.append(sp.cancel(rhs / sampled))
    if not is_identically_zero(ratios[0] - ratios[1]):
        return Finding(Verdict.TYPO, f"the two holds differ: {sp.sstr(ratios[0])} for the master, {sp.sstr(ratios[1])} for the "
                       f"slave (derived {sp.sstr(zoh)} for both)", Evidence(Method.COUNTEREXAMPLE, facts={"ratios": ratios}),
                       derived=zoh)
    printed = ratios[0]
    finding = compare_expressions(printed, zoh, what="the printed ZOH transfer function",
                                  corrected=r"F_m(s) = \frac{1 - e^{-sT}}{s} F_m^*(s), F_s(s) = \frac{1 - e^{-sT}}{s} F_s^*(s)")
    if finding.verdict == Verdict.CONFIRMED:
        return finding
    scale = sp.simplify(printed / zoh)
    return Finding(
        Verdict.TYPO,
        f"with the sampler (4) (unit-area impulses x(kT) delta(t - kT)) the hold outputs the pulse x(kT) on [kT, kT + T), "
        f"whose transform is X^*(s)(1 - e^(-sT))/s; the printed ZOH is {sp.sstr(scale)} times that (it belongs to a sampler "
        "with impulses of area T x(kT)); the 1/T of (14) is the one of (15), so (16) follows only with the corrected ZOH",
        Evidence(Method.COUNTEREXAMPLE, witness=finding.evidence.witness, facts={**finding.evidence.facts, "ratio": scale}),
        derived=zoh,
        corrected=finding.corrected,
    )


@PAPER.equation("6", kind="expression", printed=PRINTED["6"], section="II", assumptions=ASSUME,
                derivation="(31) at alpha = 1", quotes=('31',))
def eq6(ctx: AuditContext) -> Finding:
    (rel,) = parse_with(ctx, ERROR_TABLE).relations()            # e is the error here, not Euler's number
    (rel31,) = parse_with(ctx, ERROR_TABLE, PAPER.get("31").printed).relations()
    error, error31 = error_defined(rel), error_defined(rel31)
    if error is None or error31 is None:
        which = "(6)" if error is None else "(31)"
        shown = (rel if error is None else rel31).as_sympy()
        return Finding(Verdict.WRONG, f"{which} does not define the error e: it reads {sp.sstr(shown)}",
                       Evidence(Method.PARSE, facts={"printed_form": sp.srepr(shown)}))
    return compare_expressions(error, error31.subs(alpha, 1), what="the position error (6)",
                               note="it is the error of the scaled case (31) at alpha = 1")


def error_defined(rel: Any) -> sp.Expr | None:
    """The error ``e`` a printed definition gives (``2 e = x_m - x_s`` -> ``(x_m - x_s)/2``), or
    None when it does not define e as a function of the positions."""
    relation = rel.as_sympy() if hasattr(rel, "as_sympy") else rel
    if not isinstance(relation, sp.Eq) or E_ERR not in relation.free_symbols:
        return None
    solved = sp.solve(relation.lhs - relation.rhs, E_ERR)
    return solved[0] if len(solved) == 1 and E_ERR not in solved[0].free_symbols else None


def restoring_forces(gain: sp.Expr, error: sp.Expr) -> tuple[sp.Expr, sp.Expr]:
    """Forces ``(f_m, f_s)`` of the spring potential ``gain e^2/2``: with (1)'s convention
    (``f`` subtracted) the restoring controller force is the potential's gradient."""
    potential = gain * error**2 / 2
    return sp.diff(potential, X_M), sp.diff(potential, X_S)


@functools.lru_cache(maxsize=1)
def _printed_sign_is_unstable() -> dict:
    """Exact ZOH loop of the paper's teleoperator at Table I's stable point (K = 0.4, T = 7 ms,
    free/free) with the restoring sign and with (7)'s sign (controller -C)."""
    from hapticproof.systems.impedance import DiscreteTF
    from hapticproof.systems.loops import Teleoperator
    from hapticproof.analysis.sampled import spectral_radius

    m, bb = PHANTOM["m"], PHANTOM["b"]
    Kv, Tv = sp.Rational(2, 5), sp.Rational(7, 1000)
    restoring = Teleoperator.symmetric(m=m, b=bb, T=Tv, K=Kv)
    printed = Teleoperator.symmetric(m=m, b=bb, T=Tv, controller=DiscreteTF((-Kv,), (1,)))
    return {"K": Kv, "T": Tv, "m": m, "b": bb,
            "rho_restoring": float(spectral_radius(restoring, "mp", 30)),
            "rho_printed_sign": float(spectral_radius(printed, "mp", 30))}


@PAPER.equation("7", kind="expression", printed=PRINTED["7"], section="II", assumptions=ASSUME,
                derivation="restoring controllers under (1): forces = gradient of the spring potential C e^2/2, e = x_m - x_s")
def eq7(ctx: AuditContext) -> Finding:
    (lm, rm), (ls, rs) = line_pairs(ctx.statement)
    if (lm, ls) != (FUN["F_m^*"](s), FUN["F_s^*"](s)):
        return Finding(Verdict.TYPO, f"the lines must define F_m^*(s) and F_s^*(s); they define {sp.sstr(lm)} and {sp.sstr(ls)}",
                       Evidence(Method.PARSE, facts={"printed_form": [sp.srepr(lm), sp.srepr(ls)]}))
    cm, cs = CONTROLLERS["C_m"](sp.exp(s * T)), CONTROLLERS["C_s"](sp.exp(s * T))
    xm, xs = FUN["X_m^*"](s), FUN["X_s^*"](s)
    grad_m, grad_s = restoring_forces(1, X_M - X_S)           # (x_m - x_s, x_s - x_m)
    derived_m = cm * grad_m.subs({X_M: xm, X_S: xs})
    derived_s = cs * grad_s.subs({X_M: xm, X_S: xs})
    ratio_m, ratio_s = sp.cancel(rm / derived_m), sp.cancel(rs / derived_s)
    if ratio_m == 1 and ratio_s == 1:
        return Finding(Verdict.CONFIRMED, "both controller laws are restoring under (1)", Evidence(Method.CANONICAL_FORM))
    loops = _printed_sign_is_unstable()
    opposite = is_identically_zero(ratio_m + 1) and is_identically_zero(ratio_s + 1)
    if not (opposite and loops["rho_printed_sign"] > 1 > loops["rho_restoring"]):
        return Finding(Verdict.WRONG, f"the printed controller laws are {sp.sstr(ratio_m)} and {sp.sstr(ratio_s)} times the "
                       "restoring ones (f_m = C_m (x_m - x_s), f_s = C_s (x_s - x_m))",
                       Evidence(Method.CANONICAL_FORM, facts={"ratio_master": ratio_m, "ratio_slave": ratio_s}),
                       derived=sp.And(sp.Eq(FUN["F_m^*"](s), derived_m), sp.Eq(FUN["F_s^*"](s), derived_s)))
    return Finding(
        Verdict.TYPO,
        f"with (1)'s convention (f_m, f_s subtracted) restoring controllers are f_m = C_m (x_m - x_s), f_s = C_s (x_s - x_m) "
        f"(gradient of the spring potential); the printed laws are {ratio_m} and {ratio_s} times these, i.e. they push the robots "
        f"apart: at Table I's stable point (K = 0.4, T = 7 ms) the exact ZOH loop has spectral radius "
        f"{loops['rho_printed_sign']:.6f} > 1 with the printed sign and {loops['rho_restoring']:.9f} < 1 with the restoring one; "
        "(13) has the restoring sign for the master only, and (16) uses it for both",
        Evidence(Method.SPECTRAL, witness={k: loops[k] for k in ("K", "T", "m", "b")},
                 facts={"ratio_master": ratio_m, "ratio_slave": ratio_s, **{k: loops[k] for k in ("rho_restoring", "rho_printed_sign")}}),
        derived=sp.And(sp.Eq(FUN["F_m^*"](s), derived_m), sp.Eq(FUN["F_s^*"](s), derived_s)),
        corrected=r"F_m^*(s) = C_m(z)|_{z=e^{sT}} [X_m^*(s) - X_s^*(s)], \quad F_s^*(s) = C_s(z)|_{z=e^{sT}} [X_s^*(s) - X_m^*(s)]",
    )


def port_energy() -> sp.Expr:
    """Energy supplied at the two ports up to t: from (1), d/dt(m v^2/2) + b v^2 + f_i v = f_port v."""
    return (sp.Integral(TIME["f_h(t)"](tau) * TIME["xdot_m(t)"](tau), (tau, 0, t))
            + sp.Integral(TIME["f_e(t)"](tau) * TIME["xdot_s(t)"](tau), (tau, 0, t)))


def time_form(expr: sp.Expr) -> sp.Expr:
    """All integrals over tau in (0, t) merged into one integrand plus the rest."""
    integrand, rest = sp.Integer(0), sp.Integer(0)
    for term in sp.Add.make_args(sp.expand(expr)):
        ints = [f for f in sp.Mul.make_args(term) if isinstance(f, sp.Integral)]
        if not ints:
            rest += term
            continue
        (integral,) = ints
        if integral.limits != ((tau, 0, t),):
            raise ValueError(f"unexpected limits {integral.limits}")
        integrand += sp.Mul(*[f for f in sp.Mul.make_args(term) if f is not integral]) * integral.function
    return sp.expand(integrand), sp.expand(rest)
