r"""The teleoperator paper, Section III: the energy of the sampled-data two-port (8)-(28) and the
claim that the bound is less conservative.
"""

from __future__ import annotations

import functools
from typing import Any

import sympy as sp

from hapticproof.audit.runner import AuditContext
from hapticproof.audit.compare import compare_expressions
from hapticproof.exact.canonical import is_identically_zero
from hapticproof.core.evidence import Evidence, Finding, Method, Verdict
from hapticproof.derivations.teleoperator.paper import ASSUME, FREQ_TABLE, F_H, F_M, PAPER, PRINTED, SIG, SPECTRA, T, TABLE, TIME, TIME_TABLE, XDD_M, XD_M, alias_typo_finding, alpha, b_m, b_s, controller_kernel, damping_integrals, derived_16, derived_forces, device_residual, energy_spectrum, generic_integral, integrand_form, kernel_to_controller, lemma3_bound, line_pairs, m_m, m_s, n_alias, omega, omega_s, parse_with, positive_reading, relations_of, same_form, sampled_spectrum, t, tau
from hapticproof.derivations.teleoperator.model import port_energy, time_form


@PAPER.equation("8", kind="condition", printed=PRINTED["8"], section="III", assumptions=ASSUME,
                derivation="energy supplied through the two ports, from (1): int f_h x_m' + int f_e x_s' >= 0 at rest")
def eq8(ctx: AuditContext) -> Finding:
    (rel,) = parse_with(ctx, TIME_TABLE).relations()
    bad = positive_reading(rel, "the supplied energy (8)")
    if bad is not None:
        return bad
    same = time_form(rel.lhs) == time_form(port_energy())
    if same:
        return Finding(Verdict.CONFIRMED, "(8) is passivity of the 2-port at rest: the energy supplied through both ports is "
                       "non-negative (the power f_h x_m' enters with (1)'s sign); compared up to the boundary (> vs >=: both "
                       "integrals vanish at t = 0)", Evidence(Method.CANONICAL_FORM), derived=sp.Ge(port_energy(), 0))
    return Finding(Verdict.WRONG, "(8) is not the port energy of (1)", Evidence(Method.CANONICAL_FORM))


KINETIC_READING = (r"\frac{1}{2}m_m\dot{x}_m^2", r"\frac{1}{2}m_m\dot{x}_m^2(t)"), (r"\frac{1}{2}m_s\dot{x}_s^2", r"\frac{1}{2}m_s\dot{x}_s^2(t)")


@PAPER.equation("9", kind="condition", printed=PRINTED["9"], section="III", assumptions=ASSUME, parse=False,
                derivation="(8) with the kinetic energies added to the right-hand side")
def eq9(ctx: AuditContext) -> Finding:
    text = ctx.equation.printed
    for old, new in KINETIC_READING:
        text = text.replace(old, new)       # the velocities at the upper limit t
    (rel,) = parse_with(ctx, TIME_TABLE, text).relations()
    kinetic = sp.Rational(1, 2) * (m_m * TIME["xdot_m(t)"](t) ** 2 + m_s * TIME["xdot_s(t)"](t) ** 2)
    if rel.ops != (">",) and rel.ops != (">=",):
        return Finding(Verdict.WRONG, f"(9) must bound the supplied energy from below; it relates it by {rel.ops[0]}",
                       Evidence(Method.PARSE, facts={"ops": list(rel.ops)}))
    if time_form(rel.lhs) != time_form(port_energy()) or not is_identically_zero(rel.rhs - kinetic):
        return Finding(Verdict.WRONG, f"(9) is not (8) with the kinetic energies: its right side is {sp.sstr(rel.rhs)}",
                       Evidence(Method.CANONICAL_FORM, facts={"printed_form": sp.srepr(rel.rhs)}))
    return Finding(Verdict.CONFIRMED, "(9) is (8) with the right-hand side raised by the kinetic energies m_i x_i'^2/2 >= 0, so "
                   "(9) implies (8) (sufficient; not necessary whenever a robot moves); the velocities on the right are read at "
                   "the upper limit t", Evidence(Method.STRUCTURAL, facts={"added": kinetic}),
                   derived=sp.Gt(port_energy(), kinetic))


@PAPER.equation("10", kind="expression", printed=PRINTED["10"], section="III", assumptions=ASSUME, parse=False,
                derivation="(1), first line, with d x_m'/dt = x_m''")
def eq10(ctx: AuditContext) -> Finding:
    text = ctx.equation.printed.replace(r"\frac{d\dot{x}_m}{dt}", r"\ddot{x}_m")   # Leibniz notation
    (lhs, rhs), = line_pairs(parse_with(ctx, TABLE, text), 1)
    if is_identically_zero(lhs - rhs + device_residual(m_m, b_m, F_H, F_M, XD_M, XDD_M)):
        return Finding(Verdict.CONFIRMED, "(10) is the master line of (1) with the acceleration written d x_m'/dt",
                       Evidence(Method.CANONICAL_FORM))
    return Finding(Verdict.WRONG, "(10) differs from (1)", Evidence(Method.CANONICAL_FORM))


@PAPER.equation("11", kind="condition", printed=PRINTED["11"], section="III", assumptions=ASSUME,
                derivation="(9) with f_h from (10): int m x'' x' = m x'(t)^2/2 at rest (SymPy integration)")
def eq11(ctx: AuditContext) -> Finding:
    (rel,) = parse_with(ctx, TIME_TABLE).relations()
    bad = positive_reading(rel, "(11)")
    if bad is not None:
        return bad
    stored, u = _kinetic_integral()
    # f_h = f_m + m x'' + b x' (10): the m x'' x' part integrates to the kinetic energy of (9)
    derived = 0
    for ctrl, vel, damping in ((TIME["f_m(t)"], TIME["xdot_m(t)"], b_m), (TIME["f_s(t)"], TIME["xdot_s(t)"], b_s)):
        derived += sp.Integral(ctrl(tau) * vel(tau), (tau, 0, t)) + sp.Integral(damping * vel(tau) ** 2, (tau, 0, t))
    if not is_identically_zero(stored - m_m * u(t) ** 2 / 2):
        return Finding(Verdict.UNDECIDED, f"int m x'' x' came out as {sp.sstr(stored)}", Evidence(Method.CANONICAL_FORM))
    if time_form(rel.lhs) == time_form(derived):
        return Finding(Verdict.CONFIRMED, "substituting f_h and f_e from (1) into (9), the mass terms integrate exactly to the "
                       "kinetic energies and cancel; what remains is (11)",
                       Evidence(Method.CANONICAL_FORM, facts={"int m x'' x'": stored}), derived=sp.Gt(derived, 0))
    return Finding(Verdict.WRONG, "(11) is not (9) after eliminating f_h, f_e", Evidence(Method.CANONICAL_FORM),
                   derived=sp.Gt(derived, 0))


@functools.lru_cache(maxsize=1)
def _kinetic_integral() -> tuple[sp.Expr, Any]:
    """int_0^t m u' u dtau at rest (SymPy integration; shared by the checks)."""
    u = sp.Function("u")
    return sp.integrate(m_m * u(tau).diff(tau) * u(tau), (tau, 0, t)).subs(u(0), 0), u


@PAPER.equation("12", kind="condition", printed=PRINTED["12"], section="III", assumptions=ASSUME,
                derivation="Parseval: int_0^t f g = (1/2 pi) int F G^c (signals truncated at t)")
def eq12(ctx: AuditContext) -> Finding:
    (rel,) = parse_with(ctx, FREQ_TABLE).relations()
    derived = (energy_spectrum(SPECTRA["Fw_m"](omega, SIG), "V_m") + energy_spectrum(SPECTRA["Fw_s"](omega, SIG), "V_s")
               + damping_integrals())
    bad = positive_reading(rel, "(12)")
    if bad is not None:
        return bad
    if same_form(rel.lhs, derived):
        return Finding(Verdict.CONFIRMED, "each time integral of (11) becomes (1/2 pi) int F V^c d omega; the printed display omits "
                       "the common positive factor 1/(2 pi), which does not change the sign (signals truncated at t)",
                       Evidence(Method.CANONICAL_FORM, facts={"omitted_factor": 1 / (2 * sp.pi)}),
                       derived=sp.Gt(derived / (2 * sp.pi), 0))
    return Finding(Verdict.WRONG, "(12) is not the Parseval form of (11)", Evidence(Method.CANONICAL_FORM), derived=derived)


@PAPER.equation("13", kind="expression", printed=PRINTED["13"], section="III", assumptions=ASSUME,
                derivation="derived ZOH and restoring controllers: F = ZOH(j w) C(e^{jwT}) (X_own^* - X_other^*), with (14)")
def eq13(ctx: AuditContext) -> Finding:
    statement = parse_with(ctx, FREQ_TABLE)
    fm, fs = derived_forces()
    ratios = []
    lhs_names = [lhs for lhs, _ in line_pairs(statement)]
    if lhs_names != [SPECTRA["Fw_m"](omega, SIG), SPECTRA["Fw_s"](omega, SIG)]:
        return Finding(Verdict.TYPO, f"the lines must give F_m(jw) and F_s(jw); they give {[sp.sstr(x) for x in lhs_names]}",
                       Evidence(Method.PARSE, facts={"printed_form": [sp.srepr(x) for x in lhs_names]}))
    for (lhs, rhs), derived in zip(line_pairs(statement), (fm, fs)):
        printed = kernel_to_controller(rhs)
        ratios.append(sp.simplify(sp.cancel(sp.expand(printed) / sp.expand(derived))))
    if all(r == 1 for r in ratios):
        return Finding(Verdict.CONFIRMED, "both forces equal the derived ZOH forces", Evidence(Method.CANONICAL_FORM))
    witness = {"T": 2}
    known = is_identically_zero(ratios[0] - 1 / T) and is_identically_zero(ratios[1] + 1 / T)
    why = ("the factor 1/T is (5)'s ZOH scale (already counted by (15)'s 1/T), and the slave keeps (7)'s non-restoring sign "
           "while the master has the restoring one; the corrected forms give (16) exactly" if known else
           "they are not the ZOH forces of the restoring controllers")
    return Finding(
        Verdict.TYPO,
        f"with (14) substituted the printed forces are {sp.sstr(ratios[0])} (master) and {sp.sstr(ratios[1])} (slave) times the "
        f"derived ones: {why}",
        Evidence(Method.COUNTEREXAMPLE, witness=witness,
                 facts={"ratio_master": ratios[0], "ratio_slave": ratios[1],
                        "ratio_master_at_witness": ratios[0].subs(T, 2), "ratio_slave_at_witness": ratios[1].subs(T, 2)}),
        derived=sp.And(sp.Eq(SPECTRA["Fw_m"](omega, SIG), fm), sp.Eq(SPECTRA["Fw_s"](omega, SIG), fs)),
        corrected=(r"F_m(j\omega) = -\frac{T}{j\omega}\bar{C}_m(j\omega)X_m^*(j\omega) + \frac{T}{j\omega}\bar{C}_m(j\omega)X_s^*(j\omega), \quad "
                   r"F_s(j\omega) = \frac{T}{j\omega}\bar{C}_s(j\omega)X_m^*(j\omega) - \frac{T}{j\omega}\bar{C}_s(j\omega)X_s^*(j\omega)"),
    )


@PAPER.equation("14", kind="expression", printed=PRINTED["14"], section="III", assumptions=ASSUME,
                derivation="kernel C(w) = -j w ZOH(j w) C(e^{jwT})/T that turns int F V^c into (16) (classics.sampling_kernel)")
def eq14(ctx: AuditContext) -> Finding:
    out = []
    for (lhs, rhs), name, bar in zip(line_pairs(ctx.statement), ("C_m", "C_s"), ("Cbar_m", "Cbar_s")):
        if lhs != SPECTRA[bar](omega, SIG):
            return Finding(Verdict.TYPO, f"the kernel of {name} must define {bar}(jw); the line defines {sp.sstr(lhs)}",
                           Evidence(Method.PARSE, facts={"printed_form": sp.srepr(lhs)}))
        out.append(compare_expressions(rhs, controller_kernel(name), what=f"the kernel of {name}"))
    bad = [f for f in out if f.verdict != Verdict.CONFIRMED]
    if bad:
        return bad[0]
    return Finding(Verdict.CONFIRMED, "(14) is the kernel that makes (16) exact with the derived ZOH (1 - e^(-sT))/s and the "
                   "sampler's 1/T of (15): -j w ZOH(j w) C/T = -(1 - e^(-j w T)) C/T",
                   Evidence(Method.CANONICAL_FORM), derived=controller_kernel("C_m"))


def _alias_sum_check(points: int = 3) -> float:
    """(1/T) sum_n X(j w + j n w_s) vs sum_k x(kT) e^{-j w kT} for x(t) = t e^{-t} (30 digits)."""
    import mpmath

    worst = 0.0
    with mpmath.workdps(40):
        for w, period in [(mpmath.mpf("0.7"), mpmath.mpf("0.5")), (mpmath.mpf(2), mpmath.mpf("0.1")),
                          (mpmath.mpf("-1.3"), mpmath.mpf(1))][:points]:
            ws = 2 * mpmath.pi / period

            def term(n, w=w, ws=ws):
                return 1 / (1j * (w + n * ws) + 1) ** 2

            # the terms are rational in n: pair +-n and let Richardson extrapolation finish the tail
            alias = (term(0) + mpmath.nsum(lambda n: term(n) + term(-n), [1, mpmath.inf], method="richardson")) / period
            q = mpmath.exp(-(1 + 1j * w) * period)
            direct = period * q / (1 - q) ** 2            # sum_k kT e^{-kT} e^{-j w kT}
            worst = max(worst, float(abs(alias - direct) / abs(direct)))
    return worst


@PAPER.equation("15", kind="expression", printed=PRINTED["15"], section="III", assumptions=ASSUME,
                derivation="impulse sampling (4): X^*(jw) = (1/T) sum_n X(jw + jn w_s), X = V/(jw) at rest")
def eq15(ctx: AuditContext) -> Finding:
    out = []
    for (lhs, rhs), name, sampled in zip(line_pairs(ctx.statement), ("V_m", "V_s"), ("Xs_m", "Xs_s")):
        if lhs != SPECTRA[sampled](omega, SIG):
            return Finding(Verdict.TYPO, f"the line for {name} must define X^*(jw) of that robot; it defines {sp.sstr(lhs)}",
                           Evidence(Method.PARSE, facts={"printed_form": sp.srepr(lhs)}))
        derived = sampled_spectrum(name)
        (printed_sum,) = rhs.atoms(sp.Sum)
        (derived_sum,) = derived.atoms(sp.Sum)
        ok = is_identically_zero(rhs.subs(printed_sum, 1) - derived.subs(derived_sum, 1)) and is_identically_zero(
            printed_sum.function.subs(printed_sum.limits[0][0], n_alias) - derived_sum.function)
        out.append(ok)
    error = _alias_sum_check()
    if all(out) and error < 1e-25:
        return Finding(Verdict.CONFIRMED, "the sampled spectrum of (4) is (1/T) times the alias sum of X = V/(j w) (Poisson "
                       f"summation; checked on x(t) = t e^-t against sum_k x(kT) e^(-j w kT) to {error:.1e})",
                       Evidence(Method.INSTANCES, instances=3, facts={"max_relative_error": error}),
                       derived=sampled_spectrum("V_m"))
    return Finding(Verdict.UNDECIDED, "the printed alias sum did not match", Evidence(Method.INSTANCES, facts={"lines": out}))


@PAPER.equation("16", kind="expression", printed=PRINTED["16"], section="III", assumptions=ASSUME,
                derivation="first two terms of (12) with the derived forces and (15)")
def eq16(ctx: AuditContext) -> Finding:
    printed = kernel_to_controller(ctx.statement.expressions()[0])
    if same_form(printed, derived_16()):
        return Finding(Verdict.CONFIRMED, "with the restoring forces through the ZOH (1 - e^(-sT))/s and the sampler (15), "
                       "int F_m V_m^c + int F_s V_s^c has exactly the printed integrand (kernel (14))",
                       Evidence(Method.CANONICAL_FORM, facts={"compared": "integrand form"}), derived=derived_16())
    return Finding(Verdict.WRONG, "(16) does not follow from the forces and (15)", Evidence(Method.CANONICAL_FORM),
                   derived=derived_16())


@PAPER.equation("17", kind="expression", printed=PRINTED["17"], section="III", assumptions=ASSUME,
                derivation="(30) at alpha = 1", quotes=('30',))
def eq17(ctx: AuditContext) -> Finding:
    (rel,) = relations_of(ctx.statement)
    (rel30,) = parse_with(ctx, TABLE, PAPER.get("30").printed).relations()
    same = all(is_identically_zero(a - b_.subs(alpha, 1)) for a, b_ in zip(rel.terms, rel30.terms))
    if same and rel.ops == rel30.ops:
        return Finding(Verdict.CONFIRMED, "equal controllers are the scaled case (30) at alpha = 1",
                       Evidence(Method.CANONICAL_FORM))
    return Finding(Verdict.INCONSISTENT, "(17) is not (30) at alpha = 1", Evidence(Method.CANONICAL_FORM, facts={"ids": ["17", "30"]}))


def _equal_controllers(expr: sp.Expr) -> sp.Expr:
    return expr.replace(SPECTRA["Cbar_m"], SPECTRA["Cbar"]).replace(SPECTRA["Cbar_s"], SPECTRA["Cbar"])


def _v_difference(expr: sp.Expr) -> sp.Expr:
    return expr.replace(SPECTRA["V"], lambda w, sig: SPECTRA["V_m"](w, sig) - SPECTRA["V_s"](w, sig))


@PAPER.equation("18", kind="expression", printed=PRINTED["18"], section="III", assumptions=ASSUME,
                derivation="(16) with C_m = C_s (17) and V = V_m - V_s (19)")
def eq18(ctx: AuditContext) -> Finding:
    derived = generic_integral(SPECTRA["Cbar"](omega, SIG))
    return alias_typo_finding(ctx, derived, "(16) with equal controllers")


@PAPER.equation("19", kind="expression", printed=PRINTED["19"], section="III", assumptions=ASSUME,
                derivation="the combination of V_m, V_s for which (16) with (17) is the single integral (18)", quotes=('16',))
def eq19(ctx: AuditContext) -> Finding:
    (rel,) = relations_of(ctx.statement)
    if rel.lhs != SPECTRA["V"](omega, SIG):
        return Finding(Verdict.TYPO, f"the display must define V(jw); it defines {sp.sstr(rel.lhs)}",
                       Evidence(Method.PARSE, facts={"printed_form": sp.srepr(rel.lhs)}))
    p16 = _equal_controllers(parse_with(ctx, TABLE, PAPER.get("16").printed).expressions()[0])
    target = generic_integral(SPECTRA["Cbar"](omega, SIG))
    substituted = target.replace(SPECTRA["V"], lambda w, sig: rel.rhs.subs(omega, w))
    if same_form(p16, substituted):
        return Finding(Verdict.CONFIRMED, "with V = V_m - V_s the corrected (18) is exactly (16) under (17)",
                       Evidence(Method.CANONICAL_FORM), derived=rel.rhs)
    return Finding(Verdict.WRONG, "with the printed V, (18) is not (16) under (17)", Evidence(Method.CANONICAL_FORM))


CBAR, CPLUS, CMINUS = (SPECTRA[k](omega, SIG) for k in ("Cbar", "Cbar^+", "Cbar^-"))


@PAPER.equation("20", kind="expression", printed=PRINTED["20"], section="III", assumptions=ASSUME,
                derivation="(18) with Cbar replaced by Re Cbar (Lemma 1)")
def eq20(ctx: AuditContext) -> Finding:
    return alias_typo_finding(ctx, generic_integral(sp.re(CBAR)), "(18) with Re Cbar")


@PAPER.equation("21", kind="expression", printed=PRINTED["21"], section="III", assumptions=ASSUME,
                derivation="(20) split with Re Cbar = Cbar^+ + Cbar^- ((22)-(23))")
def eq21(ctx: AuditContext) -> Finding:
    derived = generic_integral(CPLUS) + generic_integral(CMINUS)
    return alias_typo_finding(ctx, derived, "(20) split into positive and negative parts")


def _part_check(ctx: AuditContext, positive: bool) -> Finding:
    (rel,) = relations_of(ctx.statement)
    target = SPECTRA["Cbar^+" if positive else "Cbar^-"](omega, SIG)
    if rel.lhs != target:
        return Finding(Verdict.TYPO, f"the display must define {sp.sstr(target)}; it defines {sp.sstr(rel.lhs)}",
                       Evidence(Method.PARSE, facts={"printed_form": sp.srepr(rel.lhs)}))
    re_cbar = sp.re(SPECTRA["Cbar"](omega, SIG))
    values = [sp.Integer(-2), sp.Rational(-1, 2), sp.Integer(0), sp.Rational(1, 3), sp.Integer(5)]
    part = (lambda x: sp.Max(x, 0)) if positive else (lambda x: sp.Min(x, 0))
    got = [rel.rhs.subs(re_cbar, v) for v in values]
    if all(g == part(v) for g, v in zip(got, values)):
        name = "positive" if positive else "negative"
        return Finding(Verdict.CONFIRMED, f"the {name} part of Re Cbar ({'max' if positive else 'min'}(Re Cbar, 0)); with the "
                       "other part it sums to Re Cbar, as (21) needs", Evidence(Method.INSTANCES, instances=len(values),
                                                                                 facts={"values": dict(zip(map(str, values), got))}))
    wrong_at = [(v, g) for v, g in zip(values, got) if g != part(v)]
    return Finding(Verdict.WRONG, f"not the {'positive' if positive else 'negative'} part of Re Cbar: at Re Cbar = "
                   f"{sp.sstr(wrong_at[0][0])} it gives {sp.sstr(wrong_at[0][1])}",
                   Evidence(Method.COUNTEREXAMPLE, witness={"Re Cbar": wrong_at[0][0]}, facts={"values": got}))


@PAPER.equation("22", kind="expression", printed=PRINTED["22"], section="III", assumptions=ASSUME,
                derivation="positive part of Re Cbar")
def eq22(ctx: AuditContext) -> Finding:
    return _part_check(ctx, True)


@PAPER.equation("23", kind="expression", printed=PRINTED["23"], section="III", assumptions=ASSUME,
                derivation="negative part of Re Cbar")
def eq23(ctx: AuditContext) -> Finding:
    return _part_check(ctx, False)


@PAPER.equation("24", kind="condition", printed=PRINTED["24"], section="III", assumptions=ASSUME,
                derivation="(12) with (21), the Cbar^+ integral dropped (Lemma 2: it is >= 0)")
def eq24(ctx: AuditContext) -> Finding:
    derived = generic_integral(CMINUS) + damping_integrals()
    return alias_typo_finding(ctx, derived, "the sufficient condition with the Cbar^- integral")


@PAPER.equation("25", kind="expression", printed=PRINTED["25"], section="III", assumptions=ASSUME,
                derivation="Lemma 3 lower bound of the Cbar^- integral: Cauchy-Schwarz over the aliases")
def eq25(ctx: AuditContext) -> Finding:
    printed = ctx.statement.expressions()[0]
    derived = lemma3_bound(CMINUS)
    if same_form(printed, derived):
        return Finding(Verdict.CONFIRMED, "the Lemma 3 bound: int Cbar^- sum_n |V|^2/(w + n w_s)^2 (see (38))",
                       Evidence(Method.CANONICAL_FORM), derived=derived)
    return Finding(Verdict.WRONG, "(25) is not the Lemma 3 bound", Evidence(Method.CANONICAL_FORM), derived=derived)


@PAPER.equation("26", kind="condition", printed=PRINTED["26"], section="III", assumptions=ASSUME,
                derivation="(24) with its first integral replaced by the smaller (25)")
def eq26(ctx: AuditContext) -> Finding:
    (rel,) = relations_of(ctx.statement)
    derived = lemma3_bound(CMINUS) + damping_integrals()
    bad = positive_reading(rel, "(26)")
    if bad is not None:
        return bad
    if same_form(rel.lhs, derived):
        return Finding(Verdict.CONFIRMED, "replacing the first integral of (24) by its lower bound (25) gives a stronger, hence "
                       "sufficient, condition", Evidence(Method.CANONICAL_FORM), derived=sp.Gt(derived, 0))
    return Finding(Verdict.WRONG, "(26) is not (24) with (25)", Evidence(Method.CANONICAL_FORM))


@PAPER.equation("27", kind="expression", printed=PRINTED["27"], section="III", assumptions=ASSUME,
                derivation="first integral of (26) with V = V_m - V_s expanded")
def eq27(ctx: AuditContext) -> Finding:
    printed = ctx.statement.expressions()[0]
    derived = _v_difference(lemma3_bound(CMINUS))
    if same_form(printed, derived):
        return Finding(Verdict.CONFIRMED, "|V_m - V_s|^2 = |V_m|^2 + |V_s|^2 - (V_m V_s^c + V_m^c V_s) under the integral",
                       Evidence(Method.CANONICAL_FORM), derived=derived)
    return Finding(Verdict.WRONG, "(27) is not the expansion of (26)", Evidence(Method.CANONICAL_FORM), derived=derived)


def _lemma4_bound() -> sp.Expr:
    return 2 * (lemma3_bound(CMINUS, "V_m") + lemma3_bound(CMINUS, "V_s"))


@PAPER.equation("28", kind="expression", printed=PRINTED["28"], section="III", assumptions=ASSUME,
                derivation="(27) with -(V_m V_s^c + V_m^c V_s) replaced by |V_m|^2 + |V_s|^2 (Lemma 4) under Cbar^- <= 0")
def eq28(ctx: AuditContext) -> Finding:
    printed = ctx.statement.expressions()[0]
    derived = _lemma4_bound()
    if same_form(printed, derived):
        return Finding(Verdict.CONFIRMED, "the Lemma 4 bound: 2 int Cbar^- S (|V_m|^2 + |V_s|^2), S = sum_n 1/(w + n w_s)^2",
                       Evidence(Method.CANONICAL_FORM), derived=derived)
    return Finding(Verdict.WRONG, "(28) is not the Lemma 4 bound of (27)", Evidence(Method.CANONICAL_FORM), derived=derived)


@PAPER.equation("28-less", kind="claim", after="28", section="III",
                printed="Applying Lemma 4 in Appendix to the last integral in (27), it can be said that (27) is less than (28)",
                derivation="(27) - (28) as one integrand", quotes=('27', '28'))
def less_claim(ctx: AuditContext) -> Finding:
    p27 = parse_with(ctx, TABLE, PAPER.get("27").printed).expressions()[0]
    p28 = parse_with(ctx, TABLE, PAPER.get("28").printed).expressions()[0]
    try:
        (s27, r27), (s28, r28) = integrand_form(p27), integrand_form(p28)
    except ValueError as err:
        return Finding(Verdict.UNDECIDED, f"(27) - (28) cannot be written as one integrand over omega: {err}",
                       Evidence(Method.CANONICAL_FORM, facts={"error": str(err)}))
    vm, vs = SPECTRA["V_m"](omega, SIG), SPECTRA["V_s"](omega, SIG)
    square = (vm + vs) * sp.conjugate(vm + vs)
    weight = 1 / (omega + n_alias * omega_s) ** 2
    identity = is_identically_zero(s27 - s28 - (-CMINUS * weight * square)) and is_identically_zero(r27 - r28)
    if not identity:
        return Finding(Verdict.UNDECIDED, "the difference (27) - (28) was not recognised", Evidence(Method.CANONICAL_FORM))
    # pointwise witness: Cbar^- = -1 and V_m = V_s = 1 at one frequency
    point = {CMINUS: -1, vm: 1, vs: 1}
    values = (sp.simplify(s27.xreplace(point) / weight), sp.simplify(s28.xreplace(point) / weight))
    return Finding(
        Verdict.TYPO,
        "(27) - (28) = int (-Cbar^-) sum_n |V_m + V_s|^2/(w + n w_s)^2 >= 0 since Cbar^- <= 0 (23): (27) is greater than or equal "
        f"to (28), as the sufficiency argument needs; 'less' is reversed (witness Cbar^- = -1, V_m = V_s = 1: integrands "
        f"{values[0]} and {values[1]} times the alias weight)",
        Evidence(Method.COUNTEREXAMPLE, witness={"Cbar^-": -1, "V_m": 1, "V_s": 1},
                 facts={"difference_integrand": -CMINUS * weight * square, "integrands_at_witness": values}),
        corrected=r"\text{(27) is greater than or equal to (28)}",
    )
