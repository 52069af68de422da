r"""Jazayeri & Tavakoli, "A Passivity Criterion for Sampled-data Bilateral Teleoperation Systems"
(the teleoperator paper, ``002_de715dde36093cfe.txt``): the printed displays, the symbol tables,
the registered :data:`PAPER` and the readings of its energy integrals and aliasing sums.
"""

from __future__ import annotations

import functools
from typing import Any

import sympy as sp

from hapticproof.analysis import classics
from hapticproof.systems import teleoperator as telemodel
from hapticproof.audit.runner import AuditContext, Paper
from hapticproof.exact.canonical import is_identically_zero
from hapticproof.core.evidence import Evidence, Finding, Method, Verdict
from hapticproof.audit.reader.names import SymbolTable
from hapticproof.core.symbols import z as Z_SYM



SYM = telemodel.TELE_SYMBOLS


K, B, T, b, b_m, b_s, m_m, m_s, alpha = (SYM[k] for k in ("K", "B", "T", "b", "b_m", "b_s", "m_m", "m_s", "alpha"))


omega = sp.Symbol("omega", real=True)


omega_s = sp.Symbol("omega_s", positive=True)


s = sp.Symbol("s")


t = sp.Symbol("t", positive=True)


tau = sp.Symbol("tau", real=True)


k_idx = sp.Symbol("k", integer=True, nonnegative=True)


n_alias = sp.Symbol("n", integer=True)


#: Marks signal spectra so that integrals of them are never mistaken for numbers.
SIG = sp.Symbol("signal")


X_M, X_S, E_ERR = sp.symbols("x_m x_s e")


F_H, F_M, F_E, F_S = sp.symbols("f_h f_m f_e f_s")


XD_M, XD_S, XDD_M, XDD_S = sp.symbols("xdot_m xdot_s xddot_m xddot_s")


_NAMES = ("F_h", "F_m", "F_e", "F_s", "X_m", "X_s", "Z_h", "Z_e", "tildeF_h", "tildeF_e", "F_m^*", "F_s^*",
          "X_m^*", "X_s^*", "X^*", "x", "x^*", "L")


FUN = {name: sp.Function(name) for name in _NAMES}


SPECTRA = {name: sp.Function(name) for name in ("V_m", "V_s", "V", "Cbar_m", "Cbar_s", "Cbar", "Cbar^+", "Cbar^-",
                                                 "Xs_m", "Xs_s", "Fw_m", "Fw_s")}


CONTROLLERS = {name: sp.Function(name) for name in ("C_m", "C_s", "C")}


TIME = {name: sp.Function(name) for name in ("f_h(t)", "f_m(t)", "f_e(t)", "f_s(t)", "xdot_m(t)", "xdot_s(t)")}


def _frequency(arg: sp.Expr) -> sp.Expr:
    """``j omega`` and ``omega`` both name the frequency ``omega`` (the paper writes both)."""
    arg = sp.sympify(arg)
    return sp.expand(arg / sp.I) if arg.has(sp.I) else arg


def _spectrum(name: str):
    return lambda arg: SPECTRA[name](_frequency(arg), SIG)


TABLE = SymbolTable(
    symbols={
        "K": K, "B": B, "T": T, "b": b, "b_m": b_m, "b_s": b_s, "m_m": m_m, "m_s": m_s, r"\alpha": alpha,
        r"\omega": omega, r"\omega_s": omega_s, "s": s, "t": t, r"\tau": tau, "k": k_idx, "n": n_alias, "z": Z_SYM,
        "x_m": X_M, "x_s": X_S, "f_h": F_H, "f_m": F_M, "f_e": F_E, "f_s": F_S,
        r"\dot{x}_m": XD_M, r"\dot{x}_s": XD_S, r"\ddot{x}_m": XDD_M, r"\ddot{x}_s": XDD_S,
    },
    functions={
        "F_h": FUN["F_h"], "F_m": FUN["F_m"], "F_e": FUN["F_e"], "F_s": FUN["F_s"], "X_m": FUN["X_m"],
        "X_s": FUN["X_s"], "Z_h": FUN["Z_h"], "Z_e": FUN["Z_e"], r"\tilde{F}_h": FUN["tildeF_h"],
        r"\tilde{F}_e": FUN["tildeF_e"], "F_m^*": FUN["F_m^*"], "F_s^*": FUN["F_s^*"], "X^*": FUN["X^*"],
        "x": FUN["x"], "x^*": FUN["x^*"], r"\mathcal{L}": FUN["L"],
        "X_m^*": lambda a: FUN["X_m^*"](a) if not sp.sympify(a).has(sp.I) else SPECTRA["Xs_m"](_frequency(a), SIG),
        "X_s^*": lambda a: FUN["X_s^*"](a) if not sp.sympify(a).has(sp.I) else SPECTRA["Xs_s"](_frequency(a), SIG),
        "V_m": _spectrum("V_m"), "V_s": _spectrum("V_s"), "V": _spectrum("V"),
        r"\bar{C}_m": _spectrum("Cbar_m"), r"\bar{C}_s": _spectrum("Cbar_s"), r"\bar{C}": _spectrum("Cbar"),
        r"\bar{C}^+": _spectrum("Cbar^+"), r"\bar{C}^-": _spectrum("Cbar^-"),
        "C_m": CONTROLLERS["C_m"], "C_s": CONTROLLERS["C_s"], "C": CONTROLLERS["C"],
    },
    superscripts={"c": sp.conjugate},
)


#: Time-domain signals as functions of time (the energy integrals (8), (9), (11)).
TIME_TABLE = TABLE.with_functions({
    "f_h": TIME["f_h(t)"], "f_m": TIME["f_m(t)"], "f_e": TIME["f_e(t)"], "f_s": TIME["f_s(t)"],
    r"\dot{x}_m": TIME["xdot_m(t)"], r"\dot{x}_s": TIME["xdot_s(t)"],
})


#: (6) and (31) use ``e`` for the position error, not Euler's number.
ERROR_TABLE = TABLE.with_symbols({"e": E_ERR})


#: Frequency-domain signals written with ``j omega`` (12)-(13): F_m(j omega) is a spectrum.
FREQ_TABLE = TABLE.with_functions({"F_m": _spectrum("Fw_m"), "F_s": _spectrum("Fw_s")})


PAPER = Paper(
    "teleoperator",
    title="A Passivity Criterion for Sampled-data Bilateral Teleoperation Systems",
    source="002_de715dde36093cfe.txt",
    authors="A. Jazayeri and M. Tavakoli",
    symbols=TABLE,
    aliases=("002", "jazayeri-tavakoli", "teleoperation"),
)


PAPER.conditions.extend([
    ("teleoperator (32), scaled controllers, any C(z)",
     r"b_m > \frac{T}{2}\frac{\alpha+1}{1-\cos\omega T}\operatorname{Re}\{(1-e^{-j\omega T})C_m(e^{j\omega T})\},\ "
     r"b_s > \frac{T}{2}\frac{\alpha+1}{1-\cos\omega T}\operatorname{Re}\{(1-e^{-j\omega T})C_s(e^{j\omega T})\}",
     "Jazayeri & Tavakoli, eq. (32) (confirmed)"),
    ("teleoperator (29), equal controllers", r"\min(b_m, b_s) > \frac{T}{1-\cos\omega T}\operatorname{Re}\{(1-e^{-j\omega T})C(e^{j\omega T})\}",
     "Jazayeri & Tavakoli, eq. (29) (confirmed)"),
    ("teleoperator (35), PD (33)", r"\min(b_m, b_s) > KT + 2B", "Jazayeri & Tavakoli, eq. (35) (confirmed)"),
    ("teleoperator, error coordinate (less conservative)",
     r"\frac{b_m b_s}{b_m + \alpha^2 b_s} \ge \frac{T}{2}\frac{1}{1-\cos\omega T}\operatorname{Re}\{(1-e^{-j\omega T})C(e^{j\omega T})\}",
     "derived (hapticproof.analysis.teleoperator)"),
])


ASSUME = "m_i, b_i, T > 0; K > 0, B >= 0 (PD); alpha > 0; robots at rest at t = 0"


#: The paper's robots (Fig. 3, Section V): Phantom Premium 1.5A.
PHANTOM = {"m": sp.Rational(15, 1000), "b": sp.Rational(1822, 100000)}


# Verbatim displays of the paper (equation number -> LaTeX without the trailing number).
PRINTED: dict[str, str] = {
    "1": r"""\begin{aligned} f_h - f_m &= m_m \ddot{x}_m + b_m \dot{x}_m \\ f_e - f_s &= m_s \ddot{x}_s + b_s \dot{x}_s \end{aligned}""",
    "2": r"""\begin{aligned} \tilde{F}_h(s) - F_h(s) &= Z_h(s) s X_m(s) \\ \tilde{F}_e(s) - F_e(s) &= Z_e(s) s X_s(s) \end{aligned}""",
    "3": r"""\begin{aligned} sX_m(s) &= \frac{1}{m_m s + b_m} (F_h(s) - F_m(s)) \\ sX_s(s) &= \frac{1}{m_s s + b_s} (F_e(s) - F_s(s)) \end{aligned}""",
    "4": r"""X^*(s) = \mathcal{L}\{x^*(t)\} = \sum_{k=0}^{\infty} x(kT)e^{-skT}""",
    "5": r"""F_m(s) = \frac{1 - e^{-sT}}{sT} F_m^*(s), F_s(s) = \frac{1 - e^{-sT}}{sT} F_s^*(s)""",
    "6": r"""e = x_m - x_s""",
    "7": r"""\begin{aligned} F_m^*(s) &= C_m(z)|_{z=e^{sT}} [X_s^*(s) - X_m^*(s)] \\ F_s^*(s) &= C_s(z)|_{z=e^{sT}} [X_m^*(s) - X_s^*(s)] \end{aligned}""",
    "8": r"""\int_0^t f_h(\tau)\dot{x}_m(\tau)d\tau + \int_0^t f_e(\tau)\dot{x}_s(\tau)d\tau > 0""",
    "9": r"""\int_0^t f_h(\tau)\dot{x}_m(\tau)d\tau + \int_0^t f_e(\tau)\dot{x}_s(\tau)d\tau > \frac{1}{2}m_m\dot{x}_m^2 + \frac{1}{2}m_s\dot{x}_s^2""",
    "10": r"""f_h - f_m = m_m \frac{d\dot{x}_m}{dt} + b_m \dot{x}_m""",
    "11": r"""\begin{aligned} &\int_0^t f_m(\tau)\dot{x}_m(\tau)d\tau + \int_0^t f_s(\tau)\dot{x}_s(\tau)d\tau \\ &+ \int_0^t b_m\dot{x}_m^2(\tau)d\tau + \int_0^t b_s\dot{x}_s^2(\tau)d\tau > 0 \end{aligned}""",
    "12": r"""\begin{aligned} &\int_{-\infty}^{\infty} F_m(j\omega)V_m^c(j\omega)d\omega + \int_{-\infty}^{\infty} F_s(j\omega)V_s^c(j\omega)d\omega + \\ &\int_{-\infty}^{\infty} b_m V_m(j\omega)V_m^c(j\omega)d\omega + \int_{-\infty}^{\infty} b_s V_s(j\omega)V_s^c(j\omega)d\omega > 0 \end{aligned}""",
    "13": r"""\begin{aligned} F_m(j\omega) &= -\frac{1}{j\omega}\bar{C}_m(j\omega)X_m^*(j\omega) + \frac{1}{j\omega}\bar{C}_m(j\omega)X_s^*(j\omega) \\ F_s(j\omega) &= -\frac{1}{j\omega}\bar{C}_s(j\omega)X_m^*(j\omega) + \frac{1}{j\omega}\bar{C}_s(j\omega)X_s^*(j\omega) \end{aligned}""",
    "14": r"""\begin{aligned}\bar{C}_m(j\omega) &= -\frac{1 - e^{-j\omega T}}{T} C_m(e^{j\omega T}) \\ \bar{C}_s(j\omega) &= -\frac{1 - e^{-j\omega T}}{T} C_s(e^{j\omega T})\end{aligned}""",
    "15": r"""\begin{aligned}X_m^*(j\omega) &= \frac{1}{T} \sum_{n=-\infty}^{\infty} \frac{V_m(j\omega + jn\omega_s)}{j\omega + jn\omega_s} \\ X_s^*(j\omega) &= \frac{1}{T} \sum_{n=-\infty}^{\infty} \frac{V_s(j\omega + jn\omega_s)}{j\omega + jn\omega_s}\end{aligned}""",
    "16": r"""\begin{aligned}& \int_{-\infty}^{\infty} \bar{C}_m(\omega) \sum_{n=-\infty}^{\infty} \frac{V_m(j\omega + jn\omega_s) - V_s(j\omega + jn\omega_s)}{j\omega + jn\omega_s} \\ & \times \left[\frac{V_m(j\omega)}{j\omega} \right]^c d\omega \\ & + \int_{-\infty}^{\infty} \bar{C}_s(\omega) \sum_{n=-\infty}^{\infty} \frac{V_s(j\omega + jn\omega_s) - V_m(j\omega + jn\omega_s)}{j\omega + jn\omega_s} \\ & \times \left[\frac{V_s(j\omega)}{j\omega} \right]^c d\omega\end{aligned}""",
    "17": r"""C_m(j\omega) = C_s(j\omega) = C(j\omega)""",
    "18": r"""\int_{-\infty}^{\infty} \bar{C}(j\omega) \sum_{n=-\infty}^{\infty} \frac{V(j\omega + jn\omega)}{j\omega + jn\omega} \left[\frac{V(j\omega)}{j\omega} \right]^c d\omega""",
    "19": r"""V(j\omega) = V_m(j\omega) - V_s(j\omega)""",
    "20": r"""\int_{-\infty}^{\infty} \text{Re}\{\bar{C}(\omega)\} \sum_{n=-\infty}^{\infty} \frac{V(j\omega + jn\omega)}{j\omega + jn\omega} \left[\frac{V(j\omega)}{j\omega} \right]^c d\omega""",
    "21": r"""\begin{aligned}& \int_{-\infty}^{\infty} \bar{C}^+(j\omega) \sum_{n=-\infty}^{\infty} \frac{V(j\omega + jn\omega)}{j\omega + jn\omega} \left[\frac{V(j\omega)}{j\omega} \right]^c d\omega \\ & + \int_{-\infty}^{\infty} \bar{C}^-(j\omega) \sum_{n=-\infty}^{\infty} \frac{V(j\omega + jn\omega)}{j\omega + jn\omega} \left[\frac{V(j\omega)}{j\omega} \right]^c d\omega\end{aligned}""",
    "22": r"""\bar{C}^+(j\omega) = \begin{cases} \text{Re}\{\bar{C}(j\omega)\} & , \text{ if } \text{Re}\{\bar{C}(j\omega)\} > 0 \\ 0 & , \text{ otherwise} \end{cases}""",
    "23": r"""\bar{C}^-(j\omega) = \begin{cases} \text{Re}\{\bar{C}(j\omega)\} & , \text{ if } \text{Re}\{\bar{C}(j\omega)\} < 0 \\ 0 & , \text{ otherwise} \end{cases}""",
    "24": r"""\int_{-\infty}^{\infty} \bar{C}^-(\omega) \sum_{n=-\infty}^{\infty} \frac{V(j\omega + jn\omega)}{j\omega + jn\omega} \left[\frac{V(j\omega)}{j\omega} \right]^c d\omega + \int_{-\infty}^{\infty} b_m V_m(j\omega) V_m^c(j\omega) d\omega + \int_{-\infty}^{\infty} b_s V_s(j\omega) V_s^c(j\omega) d\omega > 0""",
    "25": r"""\int_{-\infty}^{\infty} \bar{C}^-(\omega) \sum_{n=-\infty}^{\infty} \frac{1}{(\omega + n\omega_s)^2} V(j\omega) V^c(j\omega) d\omega""",
    "26": r"""\int_{-\infty}^{\infty} \bar{C}^-(\omega) \sum_{n=-\infty}^{\infty} \frac{1}{(\omega + n\omega_s)^2} V(j\omega) V^c(j\omega) d\omega + \int_{-\infty}^{\infty} b_m V_m(j\omega) V_m^c(j\omega) d\omega + \int_{-\infty}^{\infty} b_s V_s(j\omega) V_s^c(j\omega) d\omega > 0""",
    "27": r"""\begin{aligned} & \int_{-\infty}^{\infty} \bar{C}^-(\omega) \sum_{n=-\infty}^{\infty} \frac{1}{(\omega + n\omega_s)^2} V_m(j\omega) V_m^c(j\omega) d\omega \\ & + \int_{-\infty}^{\infty} \bar{C}^-(\omega) \sum_{n=-\infty}^{\infty} \frac{1}{(\omega + n\omega_s)^2} V_s(j\omega) V_s^c(j\omega) d\omega \\ & - \int_{-\infty}^{\infty} \bar{C}^-(\omega) \sum_{n=-\infty}^{\infty} \frac{1}{(\omega + n\omega_s)^2} \\ & \quad \times \{V_m(j\omega) V_s^c(j\omega) + V_m^c(j\omega) V_s(j\omega)\} d\omega \end{aligned}""",
    "28": r"""\begin{aligned} & \int_{-\infty}^{\infty} \bar{C}^-(\omega) \sum_{n=-\infty}^{\infty} \frac{1}{(\omega + n\omega_s)^2} V_m(j\omega) V_m^c(j\omega) d\omega + \\ & \int_{-\infty}^{\infty} \bar{C}^-(\omega) \sum_{n=-\infty}^{\infty} \frac{1}{(\omega + n\omega_s)^2} V_s(j\omega) V_s^c(j\omega) d\omega \\ & + \int_{-\infty}^{\infty} \bar{C}^-(\omega) \sum_{n=-\infty}^{\infty} \frac{1}{(\omega + n\omega_s)^2} \\ & \quad \times \{V_m(j\omega) V_m^c(j\omega) + V_s^c(j\omega) V_s(j\omega)\} d\omega \end{aligned}""",
    "29": r"""\boxed{\begin{aligned} b_m &> \frac{T}{1 - \cos \omega T} \operatorname{Re} \{ (1 - e^{-j\omega T}) C_m(e^{j\omega T}) \} \\ b_s &> \frac{T}{1 - \cos \omega T} \operatorname{Re} \{ (1 - e^{-j\omega T}) C_s(e^{j\omega T}) \} \end{aligned}}""",
    "30": r"""\frac{C_m(j\omega)}{\alpha} = C_s(j\omega) = C(j\omega)""",
    "31": r"""e = \alpha x_m - x_s""",
    "32": r"""\boxed{\begin{aligned} b_m &> \frac{T}{2} \frac{\alpha + 1}{1 - \cos \omega T} \operatorname{Re} \{ (1 - e^{-j\omega T}) C_m(e^{j\omega T}) \} \\ b_s &> \frac{T}{2} \frac{\alpha + 1}{1 - \cos \omega T} \operatorname{Re} \{ (1 - e^{-j\omega T}) C_s(e^{j\omega T}) \} \end{aligned}}""",
    "33": r"""C_s(z) = C_m(z) = K + B \frac{z-1}{Tz}""",
    "34": r"""b > KT - 2B \cos \omega T""",
    "35": r"""b > KT + 2B""",
    "36": r"""\int_{-\infty}^{\infty} \bar{C}(\omega) \sum_{n=-\infty}^{\infty} \frac{V(j\omega + jn\omega_s)}{j\omega + jn\omega_s} \left[\frac{V(j\omega)}{j\omega} \right]^c d\omega""",
    "37": r"""\int_{-\infty}^{\infty} \bar{C}^+(\omega) \sum_{n=-\infty}^{\infty} \frac{V(j\omega + jn\omega)}{j\omega + jn\omega} \left[\frac{V(j\omega)}{j\omega} \right]^c d\omega > 0""",
    "38": r"""\begin{aligned} & \int_{-\infty}^{\infty} \bar{C}^-(\omega) \sum_{n=-\infty}^{\infty} \frac{V(j\omega + jn\omega)}{j\omega + jn\omega} \left[\frac{V(j\omega)}{j\omega} \right]^c d\omega > \\ & \int_{-\infty}^{\infty} \bar{C}^-(\omega) \sum_{n=-\infty}^{\infty} \frac{1}{(\omega + n\omega_s)^2} V(j\omega)V^c(j\omega)d\omega \end{aligned}""",
    "39": r"""\begin{aligned} & \int_{-\infty}^{\infty} \bar{C}^-(\omega) \sum_{n=-\infty}^{\infty} \frac{1}{(\omega + n\omega_s)^2} V(j\omega)V^c(j\omega)d\omega + \\ & \int_{-\infty}^{\infty} b_m V_m(j\omega)V_m^c(j\omega)d\omega + \int_{-\infty}^{\infty} b_s V_s(j\omega)V_s^c(j\omega)d\omega > 0 \end{aligned}""",
    "40": r"""\begin{aligned} b_m & > \frac{T}{1 - \cos \omega T} \text{Re} \{ (1 - e^{-j\omega T}) C_m(e^{j\omega T}) \} \\ b_s & > \frac{T}{1 - \cos \omega T} \text{Re} \{ (1 - e^{-j\omega T}) C_s(e^{j\omega T}) \} \end{aligned}""",
}


def parse_with(ctx: AuditContext, table: SymbolTable, text: str | None = None) -> Any:
    """Parse the display (or ``text``) with another of the paper's tables."""
    from hapticproof.audit.reader.printed import parse_printed

    return parse_printed(ctx.equation.printed if text is None else text, table)


def relations_of(statement: Any) -> list:
    return list(statement.relations())


def line_pairs(statement: Any, count: int = 2) -> list[tuple[sp.Expr, sp.Expr]]:
    """``(lhs, rhs)`` of each two-term relation of a display of ``count`` lines (master, slave);
    a display with another number of relations is not the display the check reads."""
    from hapticproof.core.errors import LatexParseError

    relations = statement.relations()
    if len(relations) != count:
        raise LatexParseError(f"expected {count} relations (one per robot), found {len(relations)}", "", 0)
    return [(rel.lhs, rel.rhs) for rel in relations]


def integrand_form(expr: sp.Expr) -> tuple[sp.Expr, sp.Expr]:
    """``(summand, rest)``: every integral over omega in (-oo, oo) merged into one integrand,
    and in it every alias sum over n in (-oo, oo) merged into one summand. Two displays with
    equal forms are equal (the converse is not claimed)."""
    integrand = sp.Integer(0)
    for term in sp.Add.make_args(sp.expand(expr)):
        factors = sp.Mul.make_args(term)
        integrals = [f for f in factors if isinstance(f, sp.Integral)]
        if len(integrals) != 1:
            raise ValueError(f"expected one integral per term, got {term}")
        (integral,) = integrals
        ((var, lo, hi),) = integral.limits
        if var != omega or lo != -sp.oo or hi != sp.oo:
            raise ValueError(f"unexpected integral limits {integral.limits}")
        integrand += sp.Mul(*[f for f in factors if f is not integral]) * integral.function
    summand, rest = sp.Integer(0), sp.Integer(0)
    for term in sp.Add.make_args(sp.expand(integrand)):
        factors = sp.Mul.make_args(term)
        sums = [f for f in factors if isinstance(f, sp.Sum)]
        others = sp.Mul(*[f for f in factors if not isinstance(f, sp.Sum)])
        if not sums:
            rest += term
            continue
        if len(sums) != 1:
            raise ValueError(f"expected at most one alias sum per term, got {term}")
        ((var, lo, hi),) = sums[0].limits
        if var != n_alias or lo != -sp.oo or hi != sp.oo:
            raise ValueError(f"unexpected sum limits {sums[0].limits}")
        summand += others * sums[0].function
    return sp.expand(summand), sp.expand(rest)


def same_form(a: sp.Expr, b: sp.Expr) -> bool:
    """Equal integrand forms (a proof of equality); False when either display has none (an
    integral over another variable, several integrals in a term): nothing is proved then."""
    try:
        (sa, ra), (sb, rb) = integrand_form(a), integrand_form(b)
    except ValueError:
        return False
    return is_identically_zero(sa - sb) and is_identically_zero(ra - rb)


def alias_defect(expr: sp.Expr) -> dict | None:
    """An alias sum whose summand's denominator ``j omega + j n (...)`` vanishes identically for
    one integer ``n`` (the printed ``jn omega`` in place of ``jn omega_s``): returns the exact
    witness, or None."""
    for summ in expr.atoms(sp.Sum):
        body = summ.function
        for factor in sp.Mul.make_args(sp.together(body)):
            base, power = factor.as_base_exp()
            if not (power.is_number and power < 0):
                continue
            for n_value in range(-3, 4):
                if is_identically_zero(base.subs(n_alias, n_value)):
                    return {"n": n_value, "denominator": base, "at_witness": 0}
    return None


def fix_alias(text: str) -> str:
    r"""Restore the sampling frequency in ``jn\omega`` (the alias spacing of (15))."""
    return text.replace(r"jn\omega)", r"jn\omega_s)").replace(r"jn\omega}", r"jn\omega_s}")


def _on_circle(expr: sp.Expr) -> sp.Expr:
    """Controller kernels written with ``z`` evaluated at ``z = e^{j omega T}``."""
    return sp.sympify(expr).subs(Z_SYM, sp.exp(sp.I * omega * T))


@functools.lru_cache(maxsize=None)
def controller_kernel(name: str) -> sp.Expr:
    """Derived eq. (14) kernel of the controller ``name`` on the unit circle."""
    return _on_circle(classics.sampling_kernel(CONTROLLERS[name](Z_SYM), T))


def kernel_to_controller(expr: sp.Expr) -> sp.Expr:
    """Replace the paper's ``Cbar`` spectra by the derived kernels of ``C_m``, ``C_s``, ``C``."""
    mapping = {"Cbar_m": "C_m", "Cbar_s": "C_s", "Cbar": "C"}
    out = expr
    for bar, ctrl in mapping.items():
        out = out.replace(SPECTRA[bar], lambda w, sig, ctrl=ctrl: controller_kernel(ctrl).subs(omega, w))
    return out


def _alias(name: str, shift: sp.Expr = omega_s) -> sp.Expr:
    """``V(j omega + j n shift)/(j omega + j n shift)`` for the spectrum ``name``."""
    w = omega + n_alias * shift
    return SPECTRA[name](w, SIG) / (sp.I * w)


@functools.lru_cache(maxsize=None)
def sampled_spectrum(name: str) -> sp.Expr:
    """Derived (15): ``X^*(j omega) = (1/T) sum_n X(j omega + j n omega_s)`` with ``X = V/s``."""
    return sp.Sum(_alias(name), (n_alias, -sp.oo, sp.oo)) / T


def zoh_jw() -> sp.Expr:
    return classics.zoh_transfer(s, T).subs(s, sp.I * omega)


def derived_forces() -> tuple[sp.Expr, sp.Expr]:
    """Restoring forces through the derived ZOH: ``F_m = ZOH C_m (X_m^* - X_s^*)`` and
    ``F_s = ZOH C_s (X_s^* - X_m^*)`` (spectra in omega)."""
    zoh = zoh_jw()
    xm, xs = SPECTRA["Xs_m"](omega, SIG), SPECTRA["Xs_s"](omega, SIG)
    cm, cs = _on_circle(CONTROLLERS["C_m"](Z_SYM)), _on_circle(CONTROLLERS["C_s"](Z_SYM))
    return zoh * cm * (xm - xs), zoh * cs * (xs - xm)


def energy_spectrum(force: sp.Expr, velocity: str) -> sp.Expr:
    return sp.Integral(force * sp.conjugate(SPECTRA[velocity](omega, SIG)), (omega, -sp.oo, sp.oo))


@functools.lru_cache(maxsize=1)
def derived_16() -> sp.Expr:
    """The first two terms of (12) with the derived forces and (15), in the C_m/C_s form."""
    fm, fs = derived_forces()
    sub = {SPECTRA["Xs_m"](omega, SIG): sampled_spectrum("V_m"), SPECTRA["Xs_s"](omega, SIG): sampled_spectrum("V_s")}
    return energy_spectrum(fm.xreplace(sub), "V_m") + energy_spectrum(fs.xreplace(sub), "V_s")


def generic_integral(kernel: sp.Expr, velocity: str = "V", shift: sp.Expr = omega_s) -> sp.Expr:
    """``int kernel sum_n V(alias)/(alias) [V(j omega)/(j omega)]^c d omega``."""
    summ = sp.Sum(_alias(velocity, shift), (n_alias, -sp.oo, sp.oo))
    bracket = sp.conjugate(SPECTRA[velocity](omega, SIG) / (sp.I * omega))
    return sp.Integral(kernel * summ * bracket, (omega, -sp.oo, sp.oo))


def lemma3_bound(kernel: sp.Expr, velocity: str = "V") -> sp.Expr:
    """``int kernel sum_n 1/(omega + n omega_s)^2 |V(j omega)|^2 d omega`` (the Lemma 3 form)."""
    v = SPECTRA[velocity](omega, SIG)
    summ = sp.Sum(v * sp.conjugate(v) / (omega + n_alias * omega_s) ** 2, (n_alias, -sp.oo, sp.oo))
    return sp.Integral(kernel * summ, (omega, -sp.oo, sp.oo))


def damping_integrals() -> sp.Expr:
    out = sp.Integer(0)
    for damping, name in ((b_m, "V_m"), (b_s, "V_s")):
        v = SPECTRA[name](omega, SIG)
        out += sp.Integral(damping * v * sp.conjugate(v), (omega, -sp.oo, sp.oo))
    return out


def positive_reading(rel: Any, what: str, strict_only: bool = False) -> Finding | None:
    """A printed passivity condition must say ``expression > 0`` (or ``>= 0``): None when it
    does, else the finding for a reversed or different relation."""
    ops = (">",) if strict_only else (">", ">=")
    if rel.ops == ops[:1] or (len(rel.ops) == 1 and rel.ops[0] in ops):
        if rel.rhs == 0:
            return None
    return Finding(Verdict.WRONG, f"{what} must read (integral) > 0; the display relates it by {' '.join(rel.ops)} to "
                   f"{sp.sstr(rel.rhs)[:60]}", Evidence(Method.PARSE, facts={"ops": list(rel.ops), "printed_form": sp.srepr(rel.rhs)}))


def alias_typo_finding(ctx: AuditContext, derived: sp.Expr, what: str, lhs_only: bool = False) -> Finding:
    """Verdict for a display whose alias sums may print ``jn omega`` for ``jn omega_s``."""
    statement = ctx.statement
    exprs = statement.expressions()
    printed = exprs[0] if lhs_only or len(exprs) == 1 else exprs[0]
    relations = statement.relations()
    if relations and not lhs_only:
        bad = positive_reading(relations[0], what)
        if bad is not None:
            return bad
    defect = alias_defect(printed)
    if defect is None:
        if same_form(printed, derived):
            return Finding(Verdict.CONFIRMED, f"{what}: the printed display has the derived integrand and alias summand",
                           Evidence(Method.CANONICAL_FORM, facts={"compared": "integrand form"}), derived=derived)
        return Finding(Verdict.UNDECIDED, f"{what}: integrand forms differ; no witness extracted",
                       Evidence(Method.CANONICAL_FORM), derived=derived)
    corrected_text = fix_alias(ctx.equation.printed)
    corrected = ctx.parse(corrected_text).expressions()[0]
    if alias_defect(corrected) is not None or not same_form(corrected, derived):
        return Finding(Verdict.UNDECIDED, f"{what}: the alias spacing is wrong and the correction does not match",
                       Evidence(Method.COUNTEREXAMPLE, witness={"n": defect["n"]}), derived=derived)
    return Finding(
        Verdict.TYPO,
        f"{what}: the alias sum prints j n omega where (15)-(16) have j n omega_s; its denominator "
        f"j omega + j n omega vanishes identically at n = {defect['n']} (the printed sum is undefined); "
        "with omega_s the display equals the derivation",
        Evidence(Method.COUNTEREXAMPLE, witness={"n": defect["n"]},
                 facts={"denominator": defect["denominator"], "corrected_matches_derivation": True}),
        derived=derived,
        corrected=corrected_text,
    )


def device_residual(mass: sp.Symbol, damping: sp.Symbol, port: sp.Symbol, control: sp.Symbol,
                     vel: sp.Symbol, acc: sp.Symbol) -> sp.Expr:
    """``m a - (f_port - b v - u)`` of the device model of :mod:`hapticproof.analysis.sampled`."""
    return mass * acc - (port - damping * vel - control)
