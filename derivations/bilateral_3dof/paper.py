r"""Li, Tavakoli & Huang, "Absolute Stability of 3-DOF Bilateral Haptic Systems" (the 3-DOF paper,
``001_48f53b5d92944b5d.txt``): the printed displays, the symbol table, the registered :data:`PAPER`
and the models every section derives from (gain and mass matrices, the case-study impedance,
terminations, Youla's Z').
"""

from __future__ import annotations

from functools import lru_cache
from collections.abc import Callable
from typing import Any

import numpy as np
import sympy as sp

from hapticproof.exact.canonical import cancel as exact_cancel
from hapticproof.audit.runner import AuditContext, Paper
from hapticproof.analysis.energy import Sinusoid, input_energy, port_admittance
from hapticproof.core.evidence import Decision, Evidence, Finding, Method, Verdict
from hapticproof.report.latex import to_latex
from hapticproof.analysis.networks import absolute_stability, find_destabilizing_terminations, port_blocks, symmetrization_conditions, verify_certificate
from hapticproof.analysis.nport import input_impedance, positive_real
from hapticproof.audit.reader.names import IndexedFamily, SymbolTable
from hapticproof.audit.reader.printed import parse_printed
from hapticproof.exact.rationalmatrix import RationalMatrix
from hapticproof.core.symbols import s



#: Every display of the paper, verbatim (OCR damage included), by audit id. ``3a`` continues
#: (3); ``14a``-``14e`` are Theorem 9's conditions A-E; ``23c`` is the unnumbered C_m display.
PRINTED = {
    "1": r"\mathbf{T}_1 = \begin{bmatrix} \frac{9}{s+3} & -\frac{5}{s+5} & -\frac{2}{s+1} \\ -\frac{5}{s+5} & \frac{9}{s+3} & -\frac{3}{s+5} \\ -\frac{2}{s+1} & -\frac{3}{s+5} & \frac{9}{s+3} \end{bmatrix} \quad (1)",
    "2": r"\begin{bmatrix} F_h \\ F_e \end{bmatrix} = \mathcal{Z} \begin{bmatrix} V_h \\ V_e \end{bmatrix} \quad (2)",
    "3": r"\mathcal{Z} = \begin{bmatrix} \mathbf{Z}_{11} & \mathbf{Z}_{12} \\ \mathbf{Z}_{21} & \mathbf{Z}_{22} \end{bmatrix} \quad (3)",
    "3a": r"= \begin{bmatrix} \frac{9}{s+3} & -\frac{5}{s+5} & -\frac{1}{s+5} & -\frac{1}{s+1} & -\frac{1}{s+2} & -\frac{2}{s+5} \\ -\frac{5}{s+5} & \frac{9}{s+3} & -\frac{3}{s+5} & -\frac{1}{s+3} & -\frac{1}{s+1} & -\frac{1}{s+5} \\ -\frac{1}{s+5} & -\frac{3}{s+5} & \frac{9}{s+3} & -\frac{1}{s+3} & -\frac{1}{s+1} & -\frac{1}{s+1} \\ \hline -\frac{1}{s+1} & -\frac{1}{s+3} & -\frac{2}{s+3} & \frac{1}{s+3} & -\frac{9}{s+1} & -\frac{2}{s+3} \\ -\frac{1}{s+2} & -\frac{1}{s+1} & -\frac{1}{s+3} & -\frac{9}{s+1} & \frac{1}{s+3} & -\frac{1}{s+3} \\ -\frac{1}{s+2} & -\frac{1}{s+3} & -\frac{1}{s+1} & -\frac{9}{s+1} & \frac{1}{s+3} & \frac{1}{s+3} \end{bmatrix}",
    "4": r"\begin{bmatrix} f_{hi} \\ f_{ei} \end{bmatrix} = \mathbf{Z}_i \begin{bmatrix} v_{hi} \\ v_{ei} \end{bmatrix}, \quad i = x, y, z. \quad (4)",
    "5": r"\mathbf{Z}_x = \mathbf{Z}_y = \mathbf{Z}_z = \begin{bmatrix} \frac{9}{s+3} & -\frac{1}{s+1} \\ -\frac{1}{s+1} & \frac{1}{s+3} \end{bmatrix} \quad (5)",
    "6": r"E_s(t) = \int_0^t F_h^T(\tau) V_h(\tau) d\tau \geq 0. \quad (6)",
    "7": r"E_s(t) = \int_0^t f_{hx}(\tau) v_{hx}(\tau) d\tau \geq 0. \quad (7)",
    "8": r"\mathcal{F} = \mathcal{Z}\mathcal{V} \quad (8)",
    "9": r"\mathcal{F} = [F_1 \ F_2]^T \quad (9)",
    "10": r"\mathcal{V} = [V_1 \ V_2]^T \quad (10)",
    "11": r"\mathcal{Z} = \begin{bmatrix} \mathbf{Z}_{11} & \mathbf{Z}_{12} \\ \mathbf{Z}_{21} & \mathbf{Z}_{22} \end{bmatrix} \quad (11)",
    "12": r"\mathbf{Z}_{ij} = \begin{bmatrix} z_{3i-2,3j-2} & z_{3i-2,3j-1} & z_{3i-2,3j} \\ z_{3i-1,3j-2} & z_{3i-1,3j-1} & z_{3i-1,3j} \\ z_{3i,3j-2} & z_{3i,3j-1} & z_{3i,3j} \end{bmatrix} \quad (12)",
    "13": r"\mathcal{T} = \text{diag}[\mathbf{T}_1, \mathbf{T}_2] \quad (13)",
    "14": r"\mathcal{Z}' = \begin{bmatrix} z_{1,1} & \gamma_1 \sqrt{z_{1,2} z_{2,1}} & \cdots & \gamma_5 \sqrt{z_{1,6} z_{6,1}} \\ \gamma_1 \sqrt{z_{1,2} z_{2,1}} & z_{2,2} & \cdots & \gamma_9 \sqrt{z_{2,6} z_{6,2}} \\ \vdots & \vdots & \ddots & \vdots \\ \gamma_5 \sqrt{z_{1,6} z_{6,1}} & \gamma_9 \sqrt{z_{2,6} z_{6,2}} & \cdots & z_{6,6} \end{bmatrix} \quad (14)",
    "14a": r"\text{A)} \quad z_{i,j} z_{j,k} z_{k,i} = z_{j,i} z_{k,j} z_{i,k}, \text{ where } i, j, k = 1, 2, \dots, 6, i \neq j \neq k, \text{ and } i \neq k.",
    "14b": r"\text{B)} \quad \mathbf{Z}_{\ell\ell} \text{ is symmetric, where } \ell = 1, 2.",
    "14c": r"\text{C)} \quad \text{The elements of } \mathcal{Z} \text{ matrix in (12) have no poles in the right-half plane (RHP).}",
    "14d": r"\text{D)} \quad \text{Any poles of the elements of the } \mathcal{Z} \text{ matrix in (12) on the imaginary axis are simple, and the leading principal minors of the residues matrix of the } \mathcal{Z} \text{ matrix at these poles are greater than zero.}",
    "14e": r"\text{E)} \quad \text{For all real values of frequencies } \omega, \text{ the leading principal minors of the real part of the } \mathcal{Z}' \text{ matrix in (14) are greater than or equal zero, or equivalently}",
    "15a": r"\text{Re}(z_{i,i}) \geq 0, \quad i = 1, 2, \dots, 6 \quad (15a)",
    "15b": r"\text{Re}(z_{1,1})\text{Re}(z_{2,2}) - \frac{|\text{Re}(z_{1,2}z_{2,1})| + |\text{Re}(z_{1,2}z_{2,1})|}{2} \geq 0 \quad (15b)",
    "15vdots": r"\vdots",
    "15c": r"\det(\text{Re}(\mathcal{Z}')) \geq 0 \quad (15c)",
    "16": r"H(s) = \int_0^\infty h(t)e^{-st} dt \quad (16)",
    "17": r"\det(Z_1 + T_0) = \det(Z_2 + T_0) \quad (17)",
    "18": r"\det(\mathcal{Z}' + \mathcal{T}) = \det(\mathcal{Z} + \mathcal{T}) \quad (18)",
    "19": r"\mathcal{Z}'(j\omega) + \mathcal{Z}'^T(-j\omega) = 2\text{Re}(\mathcal{Z}'(j\omega)) \quad (19)",
    "20": r"(\text{Re}(\sqrt{z_{i,j}z_{j,i}})) = \sqrt{\frac{|z_{i,j}z_{j,i}| + \text{Re}(z_{i,j}z_{j,i})}{2}} \quad (20)",
    "21a": r"\mathbf{Z}_m V_h = F_h + F_{cm} \quad (21a)",
    "21b": r"\mathbf{Z}_s V_e = F_e + F_{cs} \quad (21b)",
    "22": r"\mathbf{M}_i = \begin{bmatrix} m_{ixx} & m_{ixy} & m_{ixz} \\ m_{iyx} & m_{iyy} & m_{iyz} \\ m_{izx} & m_{izy} & m_{izz} \end{bmatrix} \quad (22)",
    "23a": r"F_{cm} = -\mathbf{C}_m V_h + \mathbf{C}_m V_e \quad (23a)",
    "23b": r"F_{cs} = -\mathbf{C}_s V_e + \mathbf{C}_s V_h \quad (23b)",
    "23c": r"\mathbf{C}_m = \begin{bmatrix} \frac{k_{pmxx} + k_{vmxx}s}{s} & \frac{k_{pmxy} + k_{vmxy}s}{s} & \frac{k_{pmxz} + k_{vmxz}s}{s} \\ \frac{k_{pmyx} + k_{vmyxs}}{s} & \frac{k_{pmyy} + k_{vmyys}}{s} & \frac{k_{pmyz} + k_{vmyzs}}{s} \\ \frac{k_{pmzx} + k_{vmxzs}}{s} & \frac{k_{pmzy} + k_{vmxys}}{s} & \frac{k_{pmzz} + k_{vmxzs}}{s} \end{bmatrix}",
    "24": r"\mathbf{C}_s = \begin{bmatrix} \frac{k_{psxx} + k_{vsxx}s}{s} & \frac{k_{psxy} + k_{vsxy}s}{s} & \frac{k_{psxz} + k_{vsxz}s}{s} \\ \frac{k_{psyx} + k_{vsyx}s}{s} & \frac{k_{psyx} + k_{vsyx}s}{s} & \frac{k_{psyx} + k_{vsyz}s}{s} \\ \frac{k_{pszx} + k_{vszz}s}{s} & \frac{k_{pszy} + k_{vsyz}s}{s} & \frac{k_{pszz} + k_{vszz}s}{s} \end{bmatrix} \quad (24)",
    "25": r"\begin{bmatrix} F_h \\ F_e \end{bmatrix} = \begin{bmatrix} \mathbf{C}_m + \mathbf{Z}_m & -\mathbf{C}_m \\ -\mathbf{C}_s & \mathbf{C}_s + \mathbf{Z}_s \end{bmatrix} \begin{bmatrix} V_h \\ V_e \end{bmatrix} \quad (25)",
    "26": r"k_{vmyx} - k_{vmxy} + \frac{j(k_{pmxy} - k_{pmyx})}{\omega} = 0 \quad (26)",
    "27": r"k_{vmxz} - k_{vmzx} + \frac{j(k_{pmzx} - k_{pmxz})}{\omega} = 0 \quad (27)",
    "28": r"k_{vmyz} - k_{vmzy} + \frac{j(k_{pmzy} - k_{pmyz})}{\omega} = 0 \quad (28)",
    "29": r"k_{vsyx} - k_{vsxy} + \frac{j(k_{psxy} - k_{psyx})}{\omega} = 0 \quad (29)",
    "30": r"k_{vsxz} - k_{vszx} + \frac{j(k_{pszx} - k_{psxz})}{\omega} = 0 \quad (30)",
    "31": r"k_{vsyz} - k_{vszy} + \frac{j(k_{pszy} - k_{psyz})}{\omega} = 0 \quad (31)",
    "32": r"\begin{aligned} & \omega^2(k_{vmyx}k_{vsyy} - k_{vsyx}k_{vmyy}) + j\omega(k_{vsyx}k_{pmyy} \\ & + k_{psyx}k_{vmyy} - k_{vmyx}k_{psyx} - k_{pmyx}k_{vsyy}) \\ & + k_{psyx}k_{pmyy} - k_{pmyx}k_{psyx} = 0 \end{aligned} \quad (32)",
    "33": r"\begin{aligned} & \omega^2(k_{vmxx}k_{vsyx} - k_{vsxx}k_{vmyx}) + j\omega(k_{vsxx}k_{pmyx} \\ & + k_{psxx}k_{vmyx} - k_{vmxx}k_{psyx} - k_{pmxx}k_{vsyx}) \\ & + k_{psxx}k_{pmyx} - k_{pmxx}k_{psyx} = 0 \end{aligned} \quad (33)",
    "34": r"\begin{aligned} & \omega^2(k_{vmxz}k_{vsxx} - k_{vsxz}k_{vmxx}) + j\omega(k_{vsxz}k_{pmxx} \\ & + k_{psxz}k_{vmxx} - k_{vmxz}k_{psxz} - k_{pmxz}k_{vsxx}) \\ & + k_{psxz}k_{pmxx} - k_{pmxz}k_{psxz} = 0 \end{aligned} \quad (34)",
    "35": r"\begin{aligned} & \omega^2(k_{vmzz}k_{vsxz} - k_{vszz}k_{vmxz}) + j\omega(k_{vszz}k_{pmxz} \\ & + k_{pszz}k_{vmxz} - k_{vmzz}k_{psxz} - k_{pmzz}k_{vsxz}) \\ & + k_{pszz}k_{pmxz} - k_{pmzz}k_{psxz} = 0 \end{aligned} \quad (35)",
    "36": r"\begin{aligned} & \omega^2(k_{vmyz}k_{vsyy} - k_{vsyz}k_{vmyy}) + j\omega(k_{vsyz}k_{pmyy} \\ & + k_{psyx}k_{vmyy} - k_{vmyz}k_{psyx} - k_{pmyz}k_{vsyy}) \\ & + k_{psyx}k_{pmyy} - k_{pmyz}k_{psyx} = 0 \end{aligned} \quad (36)",
    "37": r"\begin{aligned} & \omega^2(k_{vmzz}k_{vsyz} - k_{vszz}k_{vmyz}) + j\omega(k_{vszz}k_{pmyz} \\ & + k_{pszz}k_{vmyz} - k_{vmzz}k_{psyx} - k_{pmzz}k_{vsyz}) \\ & + k_{pszz}k_{pmyz} - k_{pmzz}k_{psyx} = 0 \end{aligned} \quad (37)",
    "38a": r"k_{pmxy} = k_{pmyx}, \quad k_{vmyz} = k_{vmzy}, \quad k_{vmxz} = k_{vmzx} \quad (38a)",
    "38b": r"k_{psxy} = k_{psyx}, \quad k_{vsyz} = k_{vszy}, \quad k_{vsxz} = k_{vszx} \quad (38b)",
    "38c": r"\begin{aligned} k_{vmxx} &= k_{vmyx} = k_{vmxz} = k_{vmyy} = k_{vmyz} = k_{vmzz} \\ &= \frac{k_{pmxx}}{k_{psxx}} = \frac{k_{pmxy}}{k_{psxy}} = \frac{k_{pmxz}}{k_{psxz}} = \frac{k_{pmyy}}{k_{psyx}} = \frac{k_{pmyz}}{k_{psyx}} = \frac{k_{pmzz}}{k_{pszz}} \\ &= \frac{k_{pmxy}}{k_{psxy}} = \frac{k_{pmxz}}{k_{psxz}} = \frac{k_{pmyy}}{k_{psyx}} = \frac{k_{pmyz}}{k_{psyx}} = \frac{k_{pmzz}}{k_{pszz}} \end{aligned} \quad (38c)",
    "39a": r"k_{pmxx} \geq 0, \quad k_{pmyy} \geq 0, \quad k_{pmzz} \geq 0 \quad (39a)",
    "39b": r"k_{psxx} \geq 0, \quad k_{psyx} \geq 0, \quad k_{pszz} \geq 0 \quad (39b)",
    "39c": r"k_{pmxx}k_{pmyy} - k_{pmxy}^2 \geq 0 \quad (39c)",
    "39d": r"\begin{aligned} & k_{pmxx}k_{pmyy}k_{pmzz} - k_{pmxx}k_{pmyz}^2 - k_{pmyy}k_{pmxz}^2 \\ & - k_{pmzz}k_{pmxy}^2 + 2k_{pmxy}k_{pmxz}k_{pmyz} \geq 0 \end{aligned} \quad (39d)",
    "40": r"k_{pmxx}k_{pmyy} \geq k_{pmxy}^2 \quad (40)",
    "41a": r"k_{vmxx} \geq 0, \quad k_{vmyy} \geq 0, \quad k_{vmzz} \geq 0 \quad (41a)",
    "41b": r"k_{vsxx} \geq 0, \quad k_{vsyy} \geq 0, \quad k_{vszz} \geq 0 \quad (41b)",
    "42": r"k_{vmxx}k_{vmyy} - k_{vmyx}^2 \geq 0 \quad (42)",
    "43": r"\begin{aligned} & k_{vmxx}k_{vmyy}k_{vmzz} - k_{vmxx}k_{vmyz}^2 - k_{vmyy}k_{vmxz}^2 \\ & - k_{vmzz}k_{vmyx}^2 + 2k_{vmyx}k_{vmxz}k_{vmyz} \geq 0 \end{aligned} \quad (43)",
    "44": r"\begin{aligned} & -K_{vmxx}^2(k_{vmxx}k_{vmyy} - k_{vmyz}^2)(k_{vmzz} \\ & + k_{vszz} + \sqrt{k_{vmzz}k_{vszz}}) \geq 0 \end{aligned} \quad (44)",
    "45": r"k_{vmyz}^2 \geq k_{vmxx}k_{vmyy} \quad (45)",
    "46": r"\begin{aligned} & k_{pmxy} = k_{pmyx}, \quad k_{vmyz} = k_{vmzy}, \quad k_{vmxz} = k_{vmzx} \\ & k_{psxy} = k_{psyx}, \quad k_{vsyz} = k_{vszy}, \quad k_{vsxz} = k_{vszx} \\ & \frac{k_{vmxx}}{k_{vsxx}} = \frac{k_{vmyx}}{k_{vsxy}} = \frac{k_{vmxz}}{k_{vsx}} = \frac{k_{vmyy}}{k_{vsy}} = \frac{k_{vmyz}}{k_{vsy}} = \frac{k_{vmzz}}{k_{vsz}} = \frac{k_{pmxx}}{k_{psxx}} \\ & = \frac{k_{pmxy}}{k_{psxy}} = \frac{k_{pmxz}}{k_{psxz}} = \frac{k_{pmyy}}{k_{psyx}} = \frac{k_{pmyz}}{k_{psyx}} = \frac{k_{pmzz}}{k_{pszz}} \\ & k_{pmxx}k_{pmyy} \geq k_{pmxy}^2, \quad k_{vmxx}k_{vmyy} \geq k_{vmyx}^2 \\ & k_{vmxx}k_{vmyy}k_{vmzz} - k_{vmxx}k_{vmyz}^2 - k_{vmyy}k_{vmxz}^2 \\ & - k_{vmzz}k_{vmyx}^2 + 2k_{vmyx}k_{vmxz}k_{vmyz} \geq 0 \\ & k_{vmyz}^2 \geq k_{vmxx}k_{vmyy} \end{aligned} \quad (46)",
    "47": r"\mathbf{T}_1 = \begin{bmatrix} \frac{8}{s+3} & -\frac{2}{s+1} & -\frac{1}{s+1} \\ -\frac{1}{s+1} & \frac{9}{s+3} & \frac{2}{s+1} \\ -\frac{1}{s+1} & \frac{2}{s+1} & \frac{5}{s+1} \end{bmatrix} \quad (47)",
}


AXES = "xyz"


KINDS = ("pm", "vm", "ps", "vs")


omega = sp.Symbol("omega", positive=True)


rho = sp.Symbol("rho", positive=True)


def gain(kind: str, a: str, b: str) -> sp.Symbol:
    """The gain ``k_{kind a b}`` (``kind`` in pm, vm, ps, vs; axes x, y, z)."""
    return sp.Symbol(f"k_{kind}{a}{b}", real=True)


def gain_matrix(kind: str, symmetric: bool = False) -> sp.Matrix:
    """``K_kind`` of (24) (general, or symmetric with the upper-triangle names ``k_xy``)."""
    def entry(i, j):
        a, b = (min(i, j), max(i, j)) if symmetric else (i, j)
        return gain(kind, AXES[a], AXES[b])
    return sp.Matrix(3, 3, entry)


def mass_matrix(which: str) -> sp.Matrix:
    """Symmetric inertia matrix ``M_which`` (``m`` master, ``s`` slave) of (22)."""
    return sp.Matrix(3, 3, lambda i, j: sp.Symbol(f"m_{which}{AXES[min(i, j)]}{AXES[max(i, j)]}", positive=True))


def canonical(expr: Any) -> Any:
    """Identify ``k_{t ba}`` with ``k_{t ab}`` (gains symmetric, condition B): a normal form."""
    subs = {gain(k, AXES[j], AXES[i]): gain(k, AXES[i], AXES[j]) for k in KINDS for i in range(3) for j in range(i + 1, 3)}
    return sp.sympify(expr).xreplace(subs)


def _names() -> dict[str, Any]:
    names: dict[str, Any] = {}
    for kind in KINDS:
        for a in AXES:
            for b in AXES:
                names[f"k_{{{kind}{a}{b}}}"] = gain(kind, a, b)
    # OCR/typesetting damage kept as distinct symbols: the parser never guesses.
    for bad in ("k_{vmyxs}", "k_{vmyys}", "k_{vmyzs}", "k_{vmxzs}", "k_{vmxys}", "k_{vsx}", "k_{vsy}", "k_{vsz}", "K_{vmxx}"):
        names[bad] = sp.Symbol(bad.replace("{", "").replace("}", ""), real=True)
    for a in AXES:
        for b in AXES:
            names[f"m_{{i{a}{b}}}"] = sp.Symbol(f"m_i{a}{b}", positive=True)
    names.update({"s": s, r"\omega": omega, "t": sp.Symbol("t", nonnegative=True), r"\tau": sp.Symbol("tau")})
    shapes = {
        r"\mathbf{T}_1": (3, 3), r"\mathbf{T}_2": (3, 3), r"\mathcal{T}": (6, 6), r"\mathcal{Z}": (6, 6),
        r"\mathcal{Z}'": (6, 6), r"\mathbf{Z}_{11}": (3, 3), r"\mathbf{Z}_{12}": (3, 3), r"\mathbf{Z}_{21}": (3, 3),
        r"\mathbf{Z}_{22}": (3, 3), r"\mathbf{Z}_x": (2, 2), r"\mathbf{Z}_y": (2, 2), r"\mathbf{Z}_z": (2, 2),
        r"\mathbf{Z}_i": (2, 2), r"\mathbf{Z}_{ij}": (3, 3), r"\mathbf{Z}_m": (3, 3), r"\mathbf{Z}_s": (3, 3),
        r"\mathbf{M}_i": (3, 3), r"\mathbf{C}_m": (3, 3), r"\mathbf{C}_s": (3, 3), r"\mathcal{F}": (6, 1),
        r"\mathcal{V}": (6, 1), "F_1": (3, 1), "F_2": (3, 1), "V_1": (3, 1), "V_2": (3, 1), "F_{cm}": (3, 1),
        "F_{cs}": (3, 1), "Z_1": (6, 6), "Z_2": (6, 6), "T_0": (6, 6), "F_h": (3, 1), "F_e": (3, 1),
        "V_h": (3, 1), "V_e": (3, 1),
    }
    for name, shape in shapes.items():
        plain = name.replace(r"\mathbf", "").replace(r"\mathcal", "cal").replace("{", "").replace("}", "").replace("'", "p")
        names[name] = sp.MatrixSymbol(plain, *shape)
    for name in ("f_{hi}", "f_{ei}", "v_{hi}", "v_{ei}"):
        names[name] = sp.Symbol(name.replace("{", "").replace("}", ""))
    return names


TABLE = SymbolTable(
    _names(),
    functions={"H": sp.Function("H"), "h": sp.Function("h")},
    families=[IndexedFamily("z_{i,j}"), IndexedFamily(r"\gamma_{i}")],
)


PAPER = Paper(
    "bilateral-3dof",
    title="Absolute Stability of 3-DOF Bilateral Haptic Systems",
    source="001_48f53b5d92944b5d.txt",
    authors="J. Li, M. Tavakoli and Q. Huang",
    symbols=TABLE,
    aliases=("001", "li-tavakoli-huang", "3dof", "bilateral"),
)


ASSUME_CASE = "inertia matrices M_m, M_s symmetric; real gains; s = j omega with omega > 0"


def _printed_names() -> dict[sp.Symbol, str]:
    out = {}
    for kind in KINDS:
        for a in AXES:
            for b in AXES:
                out[gain(kind, a, b)] = f"k_{{{kind}{a}{b}}}"
    out[omega] = r"\omega"
    out[rho] = r"\rho"
    return out


NAMES = _printed_names()


def tex(obj: Any) -> str:
    """LaTeX in the paper's notation."""
    return to_latex(obj, NAMES)


def printed_matrix(eq_id: str, prefix: str = "") -> sp.Matrix:
    """The matrix of a printed display (the right-hand side), parsed verbatim."""
    statement = parse_printed(prefix + PAPER.get(eq_id).printed, TABLE)
    rel = statement.relations()[0]
    return sp.Matrix(rel.rhs)


def case_study_impedance(Kpm, Kvm, Kps, Kvs, Mm, Ms) -> sp.Matrix:
    """``[[C_m + M_m s, -C_m], [-C_s, C_s + M_s s]]`` of (25) with ``C = (K_p + K_v s)/s``."""
    Cm = (sp.Matrix(Kpm) + sp.Matrix(Kvm) * s) / s
    Cs = (sp.Matrix(Kps) + sp.Matrix(Kvs) * s) / s
    return sp.BlockMatrix([[Cm + sp.Matrix(Mm) * s, -Cm], [-Cs, Cs + sp.Matrix(Ms) * s]]).as_explicit()


@lru_cache(maxsize=1)
def symbolic_impedance() -> sp.Matrix:
    """The case study with general gain matrices and symmetric inertia matrices."""
    return case_study_impedance(gain_matrix("pm"), gain_matrix("vm"), gain_matrix("ps"), gain_matrix("vs"),
                                mass_matrix("m"), mass_matrix("s"))


@lru_cache(maxsize=1)
def derived_conditions():
    """Youla's conditions A (reduced by B) and B for the symbolic case study (24 equations)."""
    return tuple(symmetrization_conditions(symbolic_impedance(), ports=(3, 3)))


def sym3(xx, yy, zz, xy, xz, yz) -> sp.Matrix:
    return sp.Matrix([[xx, xy, xz], [xy, yy, yz], [xz, yz, zz]]).applyfunc(_nsimplified)


@lru_cache(maxsize=256)
def _nsimplified(value: sp.Expr) -> sp.Expr:
    """``sp.nsimplify(value)``, once per value (Table 1 and the masses repeat a few numbers)."""
    return sp.nsimplify(value)


def table1_gains(kvmyz: int = 60) -> dict[str, sp.Matrix]:
    """Table 1 in its corrected reading (the slave's ``k_psyx`` printed at the yy and yz places
    are ``k_psyy`` and ``k_psyz``; gain matrices symmetric)."""
    return {
        "pm": sym3(40, 40, 25, 4, 3, 30),
        "vm": sym3(80, 80, 50, 8, 6, kvmyz),
        "ps": sym3(80, 80, 50, 8, 6, 60),
        "vs": sym3(160, 160, 100, 16, 12, 120),
    }


def section52_masses() -> tuple[sp.Matrix, sp.Matrix]:
    """Section 5.2 inertia matrices (reading the printed ``M_syx = 1.6`` and ``M_szx = 1.5`` as the
    missing diagonal entries ``M_syy`` and ``M_szz``)."""
    R = sp.Rational
    Mm = sym3(R(17, 10), R(19, 10), R(13, 10), R(2, 10), R(1, 10), R(3, 10))
    Ms = sym3(R(13, 10), R(16, 10), R(15, 10), R(5, 10), R(1, 10), R(3, 10))
    return Mm, Ms


def table1_impedance(kvmyz: int = 60) -> sp.Matrix:
    """The numeric 6x6 impedance (25) for Table 1 and the Section 5.2 masses."""
    g = table1_gains(kvmyz)
    return case_study_impedance(g["pm"], g["vm"], g["ps"], g["vs"], *section52_masses())


@lru_cache(maxsize=4)
def table1_verdict(kvmyz: int):
    """Absolute stability of the Table 1 teleoperator (block 3-DOF ports)."""
    return absolute_stability(table1_impedance(kvmyz), ports=(3, 3))


def termination_47() -> sp.Matrix:
    """``T_1`` of (47), parsed from the printed display (as registered)."""
    return printed_matrix("47")


def master_input_impedance(kvmyz: int) -> RationalMatrix:
    """Impedance at the master port with the slave port terminated by (47)."""
    return _master_input_impedance(kvmyz, PAPER.get("47").printed)


@lru_cache(maxsize=8)
def _master_input_impedance(kvmyz: int, text47: str) -> RationalMatrix:
    return input_impedance(table1_impedance(kvmyz), termination_47(), (3, 3))


def fig3_inputs(omega0: float = 4.0) -> list[Sinusoid]:
    """Three sine forces at ``omega0`` along the direction in which the master port of the
    ``k_vmyz = 6`` teleoperator delivers power (the most negative eigenvector of the Hermitian
    part of its input impedance), normalised to a largest amplitude of 1 N."""
    M = master_input_impedance(6).numpy_at(1j * omega0)
    _, V = np.linalg.eigh((M + M.conj().T) / 2)
    F = M @ V[:, 0]
    F = F / np.abs(F).max()
    return [Sinusoid(float(abs(f)), omega0, float(np.angle(f) + np.pi / 2)) for f in F]


def fig3_energy(kvmyz: int, inputs: list[Sinusoid] | None = None, t_end: float = 30.0, steps: int = 3000):
    """``E_s(t)`` of (6) for the Table 1 teleoperator, slave port terminated by (47), master port
    driven by three sine forces (exact between samples)."""
    if inputs is None:
        return _fig3_energy_default(kvmyz, t_end, steps, PAPER.get("47").printed)
    return _fig3_energy(kvmyz, inputs, t_end, steps)


@lru_cache(maxsize=8)
def _fig3_energy_default(kvmyz: int, t_end: float, steps: int, text47: str):
    """Fig. 3's runs with the default forces: shared by the k_vmyz = 60 and 6 claims (per
    printed (47))."""
    return _fig3_energy(kvmyz, None, t_end, steps)


def _fig3_energy(kvmyz: int, inputs: list[Sinusoid] | None, t_end: float, steps: int):
    G = port_admittance(table1_impedance(kvmyz), {1: termination_47()}, driven=(0,), ports=(3, 3))
    return input_energy(G, inputs if inputs is not None else fig3_inputs(), t_end, steps)


def cycle_network() -> sp.Matrix:
    """A resistive 3-DOF 2-port satisfying A-E of Theorem 9 that is potentially unstable: the
    couplings form the 4-cycle 1-4-2-5 (0-based 0-3-1-4) with products 2 and 1/2 around it."""
    Z = sp.eye(6) * 2
    Z[0, 3], Z[3, 0] = 2, sp.Rational(1, 2)
    for a, b in ((3, 1), (1, 4), (4, 0)):
        Z[a, b] = Z[b, a] = 1
    return Z


def cycle_terminations() -> tuple[sp.Matrix, sp.Matrix]:
    """Passive terminations ``1/(10(s+1))`` on the four coupled DOFs, 1 on the others."""
    t = 1 / (10 * (s + 1))
    return sp.diag(t, t, 1), sp.diag(t, t, 1)


def leading_minor_network() -> sp.Matrix:
    """A reciprocal resistive 2-port whose leading principal minors are all zero (so >= 0)
    but which is not passive: ``diag([[0, 0, 0], [0, 1, 2], [0, 2, 1]], I)``."""
    return sp.diag(sp.Matrix([[0, 0, 0], [0, 1, 2], [0, 2, 1]]), sp.eye(3))


def leading_minor_terminations() -> tuple[sp.Matrix, sp.Matrix]:
    """``det(Z + T) = 8((1 + 2/(s+1))^2 - 4)`` vanishes at ``s = 1``."""
    return sp.diag(1, 2 / (s + 1), 2 / (s + 1)), sp.eye(3)


def compact_set_counterexample() -> dict[str, sp.Matrix]:
    """Gains satisfying every line of (46) (read with its OCR damage repaired) for which the
    residue of Z' at s = 0 is not PSD (K_pm has a negative determinant)."""
    Kpm = sp.Matrix([[1, 0, 1], [0, 1, 1], [1, 1, 1]])
    Kvm = sp.Matrix([[1, 0, 0], [0, 1, 1], [0, 1, 1]])
    return {"pm": Kpm, "vm": Kvm, "ps": 2 * Kpm, "vs": 2 * Kvm}


def certified(name: str):
    """Exact verification of a hand-made certificate: RHP zeros of det(Z + T)."""
    return _certified_for(name, PAPER.get("3a").printed if name == "unit" else "")


@lru_cache(maxsize=16)
def _certified_for(name: str, text: str):
    Z, terms = {
        "cycle": (cycle_network(), cycle_terminations()),
        "leading": (leading_minor_network(), leading_minor_terminations()),
        "unit": (section2_network(), (sp.eye(3), sp.eye(3))),
    }[name]
    roots, degree = verify_certificate(RationalMatrix.from_sympy(Z), terms, port_blocks(6, (3, 3)))
    passive = all(positive_real(T).decision == Decision.PROVED for T in terms)
    return roots, degree, passive


def searched_terminations(name: str):
    """Destabilizing terminations found by search (None if none)."""
    return _search_for(name, PAPER.get("3a").printed if name == "3a" else "")


@lru_cache(maxsize=16)
def _search_for(name: str, text: str):
    Z = {"3a": section2_network, "k6": lambda: table1_impedance(6)}[name]()
    return find_destabilizing_terminations(Z, ports=(3, 3))


def section2_network() -> sp.Matrix:
    """The 6x6 impedance printed in (3), parsed verbatim."""
    return printed_matrix("3a", prefix=r"\mathcal{Z} ")


def compact_impedance() -> sp.Matrix:
    g = compact_set_counterexample()
    return case_study_impedance(g["pm"], g["vm"], g["ps"], g["vs"], *section52_masses())


@lru_cache(maxsize=1)
def zprime_under_38() -> tuple[sp.Matrix, sp.Matrix]:
    """``(Z, Z')`` of the case study under (38) in master notation: symmetric gains, slave gains
    ``K_s = K_m / rho``; ``Z' = E Z E^-1`` with ``E = diag(I, sqrt(rho) I)`` (which gives
    identical principal and block-compatible minors)."""
    Kpm, Kvm = gain_matrix("pm", True), gain_matrix("vm", True)
    Z = case_study_impedance(Kpm, Kvm, Kpm / rho, Kvm / rho, mass_matrix("m"), mass_matrix("s"))
    E = sp.diag(sp.eye(3), sp.sqrt(rho) * sp.eye(3))
    Zp = (E * Z * E.inv()).applyfunc(sp.cancel)
    return Z, Zp


def _real_part_on_axis(expr: sp.Expr) -> sp.Expr:
    """``Re e(j omega)`` of a rational function of ``s`` with real symbolic coefficients."""
    num, den = sp.fraction(exact_cancel(sp.together(expr)))

    def parts(poly_expr):
        poly = sp.Poly(poly_expr, s)
        re, im = sp.Integer(0), sp.Integer(0)
        for (k,), c in poly.terms():
            unit = (1, sp.I, -1, -sp.I)[k % 4]
            if unit in (1, -1):
                re += unit * c * omega**k
            else:
                im += (unit / sp.I) * c * omega**k
        return re, im

    nr, ni = parts(num)
    dr, di = parts(den)
    return exact_cancel((nr * dr + ni * di) / (dr**2 + di**2))


@lru_cache(maxsize=1)
def real_part_zprime() -> sp.Matrix:
    """``Re Z'(j omega)`` under (38) (entrywise; frequency independent)."""
    _, Zp = zprime_under_38()
    return Zp.applyfunc(_real_part_on_axis)


@lru_cache(maxsize=1)
def real_part_leading_minors() -> tuple[sp.Expr, ...]:
    """The six leading principal minors of ``Re Z'`` under (38).

    Computed on the congruent ``D Re Z' D`` with ``D = diag(1, 1, 1, sqrt(rho) I)`` (polynomial
    entries), whose leading minor of order ``k`` is ``rho**max(0, k - 3)`` times that of ``Re Z'``.
    """
    R = real_part_zprime()
    D = sp.diag(1, 1, 1, sp.sqrt(rho), sp.sqrt(rho), sp.sqrt(rho))
    P = (D * R * D).applyfunc(sp.simplify)
    return tuple(sp.factor(P[:k, :k].det(method="bareiss") / rho ** max(0, k - 3)) for k in range(1, 7))


@lru_cache(maxsize=1)
def residue_zprime() -> sp.Matrix:
    """Residue of ``Z'`` at ``s = 0`` under (38)."""
    _, Zp = zprime_under_38()
    return Zp.applyfunc(lambda e: exact_cancel(e * s).subs(s, 0))


def rhs_matrix(ctx: AuditContext) -> sp.Matrix:
    return sp.Matrix(ctx.statement.relations()[0].rhs)


def explicit(x: Any) -> Any:
    """A parsed matrix expression as an explicit matrix (blocks of matrix symbols expanded to
    their entries), for entry-by-entry comparison of two readings."""
    if isinstance(x, sp.MatrixBase):
        if any(isinstance(e, sp.MatrixExpr) for e in x):
            return sp.Matrix(sp.BlockMatrix([[explicit(e) for e in row] for row in x.tolist()]).as_explicit())
        return sp.Matrix(x)
    if isinstance(x, sp.BlockMatrix):
        return sp.Matrix(sp.BlockMatrix([[explicit(e) for e in row] for row in x.blocks.tolist()]).as_explicit())
    if isinstance(x, sp.MatrixSymbol):
        return sp.Matrix(x.as_explicit())
    if isinstance(x, sp.Transpose):
        return explicit(x.arg).T
    if isinstance(x, (sp.MatMul, sp.Mul)) and any(isinstance(a, (sp.MatrixExpr, sp.MatrixBase)) for a in x.args):
        out = sp.Integer(1)
        for a in x.args:
            out = out * explicit(a)
        return out
    if isinstance(x, (sp.MatAdd, sp.Add)) and any(isinstance(a, (sp.MatrixExpr, sp.MatrixBase)) for a in x.args):
        parts = [explicit(a) for a in x.args]
        out = parts[0]
        for a in parts[1:]:
            out = out + a
        return out
    return x


def one_line(x: Any) -> str:
    """One-line text of an expression or matrix (details are one sentence)."""
    if isinstance(x, sp.MatrixBase):
        return "[" + "; ".join(", ".join(sp.sstr(e) for e in row) for row in x.tolist()) + "]"
    if isinstance(x, sp.BlockMatrix):
        return one_line(sp.Matrix(x.blocks))
    return " ".join(sp.sstr(x).split())


def stacked(x: Any) -> Any:
    """The paper writes the stacked vector [F_1; F_2] as [F_1 \\ F_2]^T: a column of transposed
    column vectors is read as the stack of the vectors."""
    if isinstance(x, sp.BlockMatrix):
        blocks = x.blocks
        if blocks.cols == 1 and all(isinstance(e, sp.Transpose) and e.arg.shape[1] == 1 for e in blocks):
            return sp.BlockMatrix([[e.arg] for e in blocks])
    return x


def _same_relation(printed: Any, lhs: Any, rhs: Any) -> tuple[bool, str]:
    """Whether the printed relation says ``lhs = rhs`` (entry by entry); the first difference."""
    try:
        got = explicit(printed.lhs) - explicit(printed.rhs)
        want = explicit(lhs) - explicit(rhs)
    except (ValueError, TypeError, sp.ShapeError) as err:
        return False, f"the sides do not combine ({err})"
    if getattr(got, "shape", None) != getattr(want, "shape", None):
        return False, f"shape {getattr(got, 'shape', '()')} instead of {getattr(want, 'shape', '()')}"
    if isinstance(want, sp.MatrixBase):
        for k, (a, c) in enumerate(zip(got, want)):
            if sp.expand(a - c) != 0:
                i, j = divmod(k, want.cols)
                return False, f"entry ({i + 1},{j + 1}) reads {sp.sstr(sp.expand(a))} = 0 instead of {sp.sstr(sp.expand(c))} = 0"
        return True, ""
    return (sp.expand(got - want) == 0), f"{sp.sstr(sp.expand(got))} = 0 instead of {sp.sstr(sp.expand(want))} = 0"


def definition(ctx: AuditContext, what: str, lhs: Any, rhs: Any, facts: dict | None = None,
                reading: Callable[[Any], Any] | None = None) -> Finding:
    """A defining display against the model's definition ``lhs = rhs`` (matrix symbols of the
    table): equal entry by entry, or a typo naming the first difference."""
    relations = ctx.statement.relations()
    if len(relations) != 1 or relations[0].ops != ("=",):
        return Finding(Verdict.MALFORMED, f"{what}: expected one equation, found {[r.ops for r in relations]}",
                       Evidence(Method.PARSE))
    rel = relations[0]
    printed = rel.as_sympy()
    if reading is not None:
        printed = sp.Eq(reading(printed.lhs), reading(printed.rhs), evaluate=False)
    same, why = _same_relation(printed, lhs, rhs)
    form = ("definition", sp.srepr(explicit(printed.lhs) - explicit(printed.rhs)) if same else sp.srepr(printed))
    if same:
        return Finding(Verdict.CONFIRMED, f"{what} (the model's {one_line(lhs)} = {one_line(rhs)}, entry by entry)",
                       Evidence(Method.CANONICAL_FORM, facts={**(facts or {}), "printed_form": ("definition", sp.srepr(sp.Eq(lhs, rhs, evaluate=False)))}))
    return Finding(Verdict.TYPO, f"{what}: the display reads {one_line(printed)}, not the model's {one_line(lhs)} = {one_line(rhs)}: {why}",
                   Evidence(Method.CANONICAL_FORM, facts={**(facts or {}), "printed_form": form}),
                   corrected=tex(sp.Eq(lhs, rhs, evaluate=False)) if not isinstance(lhs, sp.MatrixBase) else None)


def pr_facts(result) -> dict[str, Any]:
    out = {"decision": result.decision.value, "reason": result.reason}
    if result.hermitian.witness:
        out["witness"] = dict(result.hermitian.witness)
    return out


def certificate_facts(cert) -> dict[str, Any]:
    return cert.to_json() if cert is not None else {}


def text_diagonal() -> tuple[sp.Expr, ...]:
    """The DOF terminations the text names after (1), parsed from the claim ``1-diagonal``."""
    from hapticproof.audit.runner import quoted_math

    return tuple(parse_printed(q, TABLE).expressions()[0] for q in quoted_math(PAPER.get("1-diagonal").printed))


def not_in_s(M: Any, what: str) -> Finding | None:
    """A printed transfer matrix must be a rational matrix in s alone (else malformed)."""
    stray = sorted({str(x) for x in sp.Matrix(M).free_symbols} - {str(s)})
    if stray:
        return Finding(Verdict.MALFORMED, f"{what} is not a transfer matrix in s: its entries hold {stray}",
                       Evidence(Method.PARSE, facts={"symbols": stray, "printed_form": sp.srepr(sp.Matrix(M))}))
    return None


def pr_text(result) -> str:
    w = result.hermitian.witness or {}
    if result.decision == Decision.DISPROVED:
        return f"not positive real (negative principal minor of the Hermitian part at w = {w.get('omega', w)})"
    return f"{result.decision.value} positive real"
