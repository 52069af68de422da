r"""Li, Tavakoli & Huang, "Absolute Stability of 3-DOF Bilateral Haptic Systems"
(``001_48f53b5d92944b5d.txt``): every printed display registered verbatim, with the toolkit's
derivation of its counterpart and a verdict.

The paper models a 3-DOF bilateral teleoperator as a 2-port whose ports are 3-DOF
(``ports=(3, 3)``, terminations ``diag[T_1, T_2]`` with full 3x3 passive ``T_i``, eq. (13)) and
claims (Theorem 9) that absolute stability is equivalent to positive realness of Youla's
reciprocal ``Z'`` of eq. (14) when the symmetrization conditions A and B hold. The case study
is the position-position teleoperator (21)-(25) with symbolic mass and PD gain matrices.

What the audit establishes (each by exact computation, see the entries):

* the motivating claims of Section 2 hold: ``T_1`` of (1) is not passive (at w = 12), each
  ``Z_i`` of (5) satisfies Llewellyn's criterion with equality at w = 0, and the coupled
  network (3) is potentially unstable (verified destabilizing 3-DOF terminations);
* Theorem 9 is wrong as stated: conditions D and E use leading principal minors (E: ">= 0" is
  not PSD; D: "> 0" fails for the paper's own case study), and A/B do not guarantee Youla's
  equivalence when entries vanish (a 4-cycle counterexample satisfying A-E that is potentially
  unstable, with verified terminations);
* the symmetrization conditions (26)-(37) are right up to index typos in (32), (34), (36), (37);
  under (38) the real part of ``Z'`` is ``u u^T (x) K_vm`` with rank 3, so its 4th-6th leading
  minors vanish identically: (44), (45) and the compact set (46) are wrong, and the exact
  condition is ``K_pm, K_vm`` positive semidefinite (all principal minors);
* Table 1 with ``k_vmyz = 60`` is absolutely stable (Youla, verified minors) although it
  violates (45); with ``k_vmyz = 6`` it is potentially unstable (verified terminations);
  the termination (47) is *not* passive, yet the energy claims of Fig. 3 are reproduced: with
  ``k_vmyz = 60`` the input impedance of the master port is positive real (``E_s >= 0`` for every
  input from rest), with ``k_vmyz = 6`` it is not and ``E_s`` becomes negative.

Assumptions used throughout: the inertia matrices ``M_m, M_s`` are symmetric (as inertia matrices
are; Section 5.2 lists only one off-diagonal entry per pair); gains are real.
"""

from __future__ import annotations

import itertools
from dataclasses import dataclass
from fractions import Fraction
from functools import lru_cache
from collections.abc import Callable
from typing import Any

import numpy as np
import sympy as sp

from hapticproof.audit.runner import AuditContext, Paper, malformed
from hapticproof.audit.compare import compare_expressions
from hapticproof.exact.canonical import is_identically_zero
from hapticproof.analysis.energy import Sinusoid, input_energy, port_admittance
from hapticproof.core.evidence import Decision, Evidence, Finding, Method, Plot, Series, Verdict
from hapticproof.report.latex import to_latex
from hapticproof.analysis.networks import absolute_stability, find_destabilizing_terminations, llewellyn, port_blocks, symmetrization_conditions, symmetrize, verify_certificate
from hapticproof.analysis.nport import input_impedance, positive_real
from hapticproof.audit.reader.names import IndexedFamily, SymbolTable
from hapticproof.audit.reader.printed import parse_printed
from hapticproof.exact.rationalmatrix import RationalMatrix, matrix_psd
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


# ---------------------------------------------------------------------------------------------
# symbols and the printed-name table
# ---------------------------------------------------------------------------------------------

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


# ---------------------------------------------------------------------------------------------
# the models: Section 2 examples, the case study, Table 1, Section 5.2
# ---------------------------------------------------------------------------------------------


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


def _sym3(xx, yy, zz, xy, xz, yz) -> sp.Matrix:
    return sp.Matrix([[xx, xy, xz], [xy, yy, yz], [xz, yz, zz]]).applyfunc(sp.nsimplify)


def table1_gains(kvmyz: int = 60) -> dict[str, sp.Matrix]:
    """Table 1 in its corrected reading (the slave's ``k_psyx`` printed at the yy and yz places
    are ``k_psyy`` and ``k_psyz``; gain matrices symmetric)."""
    return {
        "pm": _sym3(40, 40, 25, 4, 3, 30),
        "vm": _sym3(80, 80, 50, 8, 6, kvmyz),
        "ps": _sym3(80, 80, 50, 8, 6, 60),
        "vs": _sym3(160, 160, 100, 16, 12, 120),
    }


def section52_masses() -> tuple[sp.Matrix, sp.Matrix]:
    """Section 5.2 inertia matrices (reading the printed ``M_syx = 1.6`` and ``M_szx = 1.5`` as the
    missing diagonal entries ``M_syy`` and ``M_szz``)."""
    R = sp.Rational
    Mm = _sym3(R(17, 10), R(19, 10), R(13, 10), R(2, 10), R(1, 10), R(3, 10))
    Ms = _sym3(R(13, 10), R(16, 10), R(15, 10), R(5, 10), R(1, 10), R(3, 10))
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


# Counterexamples used by several entries (all verified exactly where they are used).

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


def _certified(name: str):
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


def _search(name: str):
    """Destabilizing terminations found by search (None if none)."""
    return _search_for(name, PAPER.get("3a").printed if name == "3a" else "")


@lru_cache(maxsize=16)
def _search_for(name: str, text: str):
    Z = {"3a": section2_network, "k6": lambda: table1_impedance(6)}[name]()
    return find_destabilizing_terminations(Z, ports=(3, 3))


def section2_network() -> sp.Matrix:
    """The 6x6 impedance printed in (3), parsed verbatim."""
    return printed_matrix("3a", prefix=r"\mathcal{Z} ")


def _compact_impedance() -> sp.Matrix:
    g = compact_set_counterexample()
    return case_study_impedance(g["pm"], g["vm"], g["ps"], g["vs"], *section52_masses())


# ---------------------------------------------------------------------------------------------
# Z' under (38): symbolic
# ---------------------------------------------------------------------------------------------


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
    num, den = sp.fraction(sp.cancel(sp.together(expr)))

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
    return sp.cancel((nr * dr + ni * di) / (dr**2 + di**2))


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
    return Zp.applyfunc(lambda e: sp.cancel(e * s).subs(s, 0))


# ---------------------------------------------------------------------------------------------
# helpers for the entries
# ---------------------------------------------------------------------------------------------


def _rhs_matrix(ctx: AuditContext) -> sp.Matrix:
    return sp.Matrix(ctx.statement.relations()[0].rhs)


def _explicit(x: Any) -> Any:
    """A parsed matrix expression as an explicit matrix (blocks of matrix symbols expanded to
    their entries), for entry-by-entry comparison of two readings."""
    if isinstance(x, sp.MatrixBase):
        if any(isinstance(e, sp.MatrixExpr) for e in x):
            return sp.Matrix(sp.BlockMatrix([[_explicit(e) for e in row] for row in x.tolist()]).as_explicit())
        return sp.Matrix(x)
    if isinstance(x, sp.BlockMatrix):
        return sp.Matrix(sp.BlockMatrix([[_explicit(e) for e in row] for row in x.blocks.tolist()]).as_explicit())
    if isinstance(x, sp.MatrixSymbol):
        return sp.Matrix(x.as_explicit())
    if isinstance(x, sp.Transpose):
        return _explicit(x.arg).T
    if isinstance(x, (sp.MatMul, sp.Mul)) and any(isinstance(a, (sp.MatrixExpr, sp.MatrixBase)) for a in x.args):
        out = sp.Integer(1)
        for a in x.args:
            out = out * _explicit(a)
        return out
    if isinstance(x, (sp.MatAdd, sp.Add)) and any(isinstance(a, (sp.MatrixExpr, sp.MatrixBase)) for a in x.args):
        parts = [_explicit(a) for a in x.args]
        out = parts[0]
        for a in parts[1:]:
            out = out + a
        return out
    return x


def _line(x: Any) -> str:
    """One-line text of an expression or matrix (details are one sentence)."""
    if isinstance(x, sp.MatrixBase):
        return "[" + "; ".join(", ".join(sp.sstr(e) for e in row) for row in x.tolist()) + "]"
    if isinstance(x, sp.BlockMatrix):
        return _line(sp.Matrix(x.blocks))
    return " ".join(sp.sstr(x).split())


def _stacked(x: Any) -> Any:
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
        got = _explicit(printed.lhs) - _explicit(printed.rhs)
        want = _explicit(lhs) - _explicit(rhs)
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


def _definition(ctx: AuditContext, what: str, lhs: Any, rhs: Any, facts: dict | None = None,
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
    form = ("definition", sp.srepr(_explicit(printed.lhs) - _explicit(printed.rhs)) if same else sp.srepr(printed))
    if same:
        return Finding(Verdict.CONFIRMED, f"{what} (the model's {_line(lhs)} = {_line(rhs)}, entry by entry)",
                       Evidence(Method.CANONICAL_FORM, facts={**(facts or {}), "printed_form": ("definition", sp.srepr(sp.Eq(lhs, rhs, evaluate=False)))}))
    return Finding(Verdict.TYPO, f"{what}: the display reads {_line(printed)}, not the model's {_line(lhs)} = {_line(rhs)}: {why}",
                   Evidence(Method.CANONICAL_FORM, facts={**(facts or {}), "printed_form": form}),
                   corrected=tex(sp.Eq(lhs, rhs, evaluate=False)) if not isinstance(lhs, sp.MatrixBase) else None)


def _pr_facts(result) -> dict[str, Any]:
    out = {"decision": result.decision.value, "reason": result.reason}
    if result.hermitian.witness:
        out["witness"] = dict(result.hermitian.witness)
    return out


def _certificate_facts(cert) -> dict[str, Any]:
    return cert.to_json() if cert is not None else {}


# ---------------------------------------------------------------------------------------------
# Section 2: motivating examples
# ---------------------------------------------------------------------------------------------

def text_diagonal() -> tuple[sp.Expr, ...]:
    """The DOF terminations the text names after (1), parsed from the claim ``1-diagonal``."""
    from hapticproof.audit.runner import quoted_math

    return tuple(parse_printed(q, TABLE).expressions()[0] for q in quoted_math(PAPER.get("1-diagonal").printed))


def _not_in_s(M: Any, what: str) -> Finding | None:
    """A printed transfer matrix must be a rational matrix in s alone (else malformed)."""
    stray = sorted({str(x) for x in sp.Matrix(M).free_symbols} - {str(s)})
    if stray:
        return Finding(Verdict.MALFORMED, f"{what} is not a transfer matrix in s: its entries hold {stray}",
                       Evidence(Method.PARSE, facts={"symbols": stray, "printed_form": sp.srepr(sp.Matrix(M))}))
    return None


def _pr_text(result) -> str:
    w = result.hermitian.witness or {}
    if result.decision == Decision.DISPROVED:
        return f"not positive real (negative principal minor of the Hermitian part at w = {w.get('omega', w)})"
    return f"{result.decision.value} positive real"


@PAPER.equation("1", kind="expression", printed=PRINTED["1"], section="2", quotes=("1-diagonal",),
                derivation="diagonal of the printed T_1 vs the terminations the text names after it")
def eq1(ctx: AuditContext) -> Finding:
    T = _rhs_matrix(ctx)
    bad = _not_in_s(T, "T_1")
    if bad is not None:
        return bad
    text = text_diagonal()
    stray = _not_in_s(sp.Matrix([list(text)]), "the terminations the text names (1-diagonal)")
    if stray is not None:
        return Finding(Verdict.UNDECIDED, f"cannot compare the diagonal: {stray.detail}", Evidence(Method.PARSE))
    if T.shape != (3, 3) or len(text) != 3:
        return Finding(Verdict.MALFORMED, f"T_1 is {T.shape[0]}x{T.shape[1]} and the text names {len(text)} terminations",
                       Evidence(Method.PARSE, facts={"printed_form": sp.srepr(T)}))
    printed_diag = [sp.cancel(T[i, i]) for i in range(3)]
    differ = [i for i in range(3) if not is_identically_zero(printed_diag[i] - text[i])]
    variant = T.copy()
    for i in range(3):
        variant[i, i] = text[i]
    results = {"as printed": positive_real(T), "with the text's diagonal": positive_real(variant)}
    facts = {name: _pr_facts(r) for name, r in results.items()}
    facts.update({"printed_diagonal": printed_diag, "text_diagonal": list(text), "printed_form": sp.srepr(T)})
    passivity = f"as printed T_1 is {_pr_text(results['as printed'])}; with the text's diagonal it is " \
                f"{_pr_text(results['with the text' + chr(39) + 's diagonal'])}"
    if not differ:
        return Finding(Verdict.CONFIRMED, f"the printed diagonal agrees with the text; {passivity}",
                       Evidence(Method.CANONICAL_FORM, facts=facts))
    return Finding(
        Verdict.INCONSISTENT,
        f"the display prints {', '.join(sp.sstr(d) for d in printed_diag)} on the diagonal while the text after it (claim "
        f"1-diagonal) names the DOF terminations {', '.join(sp.sstr(t) for t in text)} (entries "
        f"{[i + 1 for i in differ]} differ; off the diagonal it reads {_off_diagonal(T)}); {passivity}",
        Evidence(Method.CANONICAL_FORM, witness={"entries": [[i + 1, i + 1] for i in differ]}, facts=facts),
        derived=variant,
    )


def _off_diagonal(T: sp.Matrix) -> str:
    """The off-diagonal entries as read (the couplings the passivity verdicts depend on)."""
    upper = [sp.sstr(sp.cancel(T[i, j])) for i in range(T.rows) for j in range(i + 1, T.cols)]
    symmetric = all(is_identically_zero(T[i, j] - T[j, i]) for i in range(T.rows) for j in range(i + 1, T.cols))
    if symmetric:
        return f"{', '.join(upper)} (symmetric)"
    lower = [sp.sstr(sp.cancel(T[j, i])) for i in range(T.rows) for j in range(i + 1, T.cols)]
    return f"{', '.join(upper)} above and {', '.join(lower)} below (not symmetric)"


@PAPER.equation("1-diagonal", kind="claim", after="1", section="2",
                printed="the terminations $\\frac{9}{s+3}$, $\\frac{1}{s+3}$ and $\\frac{2}{s+3}$ along each of the first "
                        "three DOFs are passive",
                derivation="positive realness of each scalar termination")
def diagonal_passive(ctx: AuditContext) -> Finding:
    from hapticproof.audit.runner import quoted_math

    terms = [ctx.parse(q).expressions()[0] for q in quoted_math(ctx.equation.printed)]
    for t in terms:
        bad = _not_in_s(sp.Matrix([[t]]), f"the termination {sp.sstr(t)}")
        if bad is not None:
            return bad
    results = [(sp.sstr(t), positive_real(sp.Matrix([[t]]))) for t in terms]
    facts: dict[str, Any] = {"decisions": {k: v.reason for k, v in results}}
    # the claim is the proposition "each of the n named terminations is positive real": what the
    # check proves about it (a mutant naming other PR terminations makes a claim proved the same way)
    facts["printed_form"] = ("claim: each named termination is positive real", tuple(r.decision.value for _, r in results))
    if all(r.decision == Decision.PROVED for _, r in results):
        return Finding(Verdict.CONFIRMED, f"each named scalar termination ({', '.join(k for k, _ in results)}) is positive real",
                       Evidence(Method.ROOT_ISOLATION, facts=facts))
    bad, result = next((k, r) for k, r in results if r.decision != Decision.PROVED)
    return Finding(Verdict.WRONG if result.decision == Decision.DISPROVED else Verdict.UNDECIDED,
                   f"{bad} is {'not' if result.decision == Decision.DISPROVED else 'not proved'} positive real ({result.reason})",
                   Evidence(result.evidence.method, witness=result.evidence.witness, facts=facts))


@PAPER.equation("1-nonpassive", kind="claim", after="1", section="2",
                printed="the coupled 3-DOF termination \\mathbf{T}_1 is non-passive",
                derivation="Definition 3 for the printed T_1 (and for the text's diagonal)")
def t1_nonpassive(ctx: AuditContext) -> Finding:
    T = printed_matrix("1")
    bad = _not_in_s(T, "T_1 of (1)")
    if bad is not None:
        return Finding(Verdict.UNDECIDED, bad.detail, bad.evidence)
    variant = T.copy()
    text = text_diagonal()
    stray = _not_in_s(sp.Matrix([list(text)]), "the terminations the text names (1-diagonal)")
    if stray is not None:
        return Finding(Verdict.UNDECIDED, f"cannot build the text's variant: {stray.detail}", Evidence(Method.PARSE))
    for i in range(min(3, len(text), T.rows)):
        variant[i, i] = text[i]
    printed, altered = positive_real(T), positive_real(variant)
    diagonal = [positive_real(sp.Matrix([[T[i, i]]])).decision == Decision.PROVED for i in range(min(T.rows, T.cols))]
    facts = {"as printed": _pr_facts(printed), "text diagonal": _pr_facts(altered), "diagonal_entries_pr": diagonal}
    if printed.decision == Decision.DISPROVED and altered.decision == Decision.DISPROVED:
        w = printed.hermitian.witness
        return Finding(Verdict.CONFIRMED,
                       f"T_1 (1) is not positive real: T_1(jw) + T_1(jw)^H has a negative principal minor at w = {w.get('omega', w)}; "
                       "with the text's diagonal it is not passive either (already at w = "
                       f"{altered.hermitian.witness.get('omega', altered.hermitian.witness)}), "
                       + ("although every diagonal entry is" if all(diagonal) else
                          f"and its diagonal entries {[i + 1 for i, ok in enumerate(diagonal) if not ok]} are not PR either"),
                       Evidence(Method.ROOT_ISOLATION, witness=dict(w), facts=facts))
    return Finding(Verdict.WRONG, f"T_1 as printed is {_pr_text(printed)}; with the text's diagonal it is {_pr_text(altered)}",
                   Evidence(printed.evidence.method, facts=facts))


@PAPER.equation("2", kind="expression", printed=PRINTED["2"], section="2", derivation="impedance form of the 2-port")
def eq2(ctx: AuditContext) -> Finding:
    L = TABLE.lookup
    return _definition(ctx, "defines the 3-DOF teleoperator in impedance form: forces [F_h; F_e] (6x1) = Z (6x6) velocities",
                       sp.BlockMatrix([[L("F_h")], [L("F_e")]]), L(r"\mathcal{Z}") * sp.BlockMatrix([[L("V_h")], [L("V_e")]]))


@PAPER.equation("3", kind="expression", printed=PRINTED["3"], section="2", derivation="block partition")
def eq3(ctx: AuditContext) -> Finding:
    return _definition(ctx, "partitions Z into 3x3 blocks Z_ij (port 1 = operator, port 2 = environment)", *_partition())


def _partition() -> tuple[Any, Any]:
    L = TABLE.lookup
    return L(r"\mathcal{Z}"), sp.BlockMatrix([[L(r"\mathbf{Z}_{11}"), L(r"\mathbf{Z}_{12}")],
                                              [L(r"\mathbf{Z}_{21}"), L(r"\mathbf{Z}_{22}")]])


@PAPER.equation("3a", kind="expression", printed=PRINTED["3a"], section="2", parse=False,
                derivation="the printed 6x6 impedance: open-circuit stability, symmetrization conditions", quotes=('5',))
def eq3a(ctx: AuditContext) -> Finding:
    from hapticproof.exact.rationalmatrix import pole_report

    Z = printed_matrix("3a", prefix=r"\mathcal{Z} ")
    bad = _not_in_s(Z, "the impedance (3)")
    if bad is not None:
        return bad
    if Z.shape != (6, 6):
        return Finding(Verdict.MALFORMED, f"the impedance of (3) is {Z.shape[0]}x{Z.shape[1]}, not 6x6",
                       Evidence(Method.PARSE, facts={"printed_form": sp.srepr(Z)}))
    rep = RationalMatrix.from_sympy(Z)
    poles = pole_report(rep)
    # what the paper states about this network: its DOF subsystems are (5), it is potentially unstable
    p5 = printed_matrix("5")
    subsystems = [name for i, name in enumerate(AXES)
                  if p5.shape == (2, 2) and all(is_identically_zero(a - c) for a, c in zip(Z.extract([i, i + 3], [i, i + 3]), p5))]
    roots, degree, passive = _certified("unit")
    sym = symmetrize(rep, (3, 3))
    properties = ("entries stable" if not poles.rhp else "an entry has an RHP pole",
                  f"DOF subsystems equal to (5): {subsystems}", f"unit terminations destabilise it: {bool(roots and passive)}")
    facts = {"symmetrization": sym.reason, "axis_poles": [p.label() for p, _ in poles.axis], "rhp_roots_unit": [str(r) for r in roots],
             "printed_form": ("data display; the properties the paper states about it", properties)}
    if poles.rhp:
        (i, j), root = poles.rhp[0]
        where = root.label() if hasattr(root, "label") else str(root)
        return Finding(Verdict.WRONG, f"entry ({i + 1}, {j + 1}) has a pole in Re s > 0 ({where}): the open-circuit network is "
                       "unstable", Evidence(Method.ROOT_ISOLATION, witness={"entry": [i + 1, j + 1], "pole": where}, facts=facts))
    if len(subsystems) != 3:
        return Finding(Verdict.INCONSISTENT, f"the DOF subsystems of (3) extracted at (i, i), (i, i+3), (i+3, i), (i+3, i+3) "
                       f"agree with (5) only for {subsystems or 'no DOF'}", Evidence(Method.CANONICAL_FORM,
                                                                                     facts={**facts, "ids": ["3a", "5"]}))
    if not (roots and passive):
        return Finding(Verdict.INCONSISTENT, "with unit resistive terminations det(Z + I) has no zero in Re s > 0, so the network "
                       "does not show the potential instability the text states (see 5-unstable)",
                       Evidence(Method.ROOT_ISOLATION, facts={**facts, "ids": ["3a", "5-unstable"]}))
    return Finding(Verdict.CONFIRMED,
                   "a well-formed 6x6 rational impedance (read as the continuation '\\mathcal{Z} = ...' of (3)) whose entries are "
                   f"all stable, whose DOF subsystems are (5) and which unit terminations destabilise (det(Z + I) = 0 at "
                   f"s ~ {roots[0].real:.6g}); it is not symmetrizable ({sym.reason}), so Theorem 9 does not apply to it",
                   Evidence(Method.PARSE, facts=facts))


@PAPER.equation("4", kind="expression", printed=PRINTED["4"], section="2", derivation="the 1-DOF subsystems")
def eq4(ctx: AuditContext) -> Finding:
    L = TABLE.lookup
    statement = ctx.statement
    ranges = [tuple(map(str, r.values)) for r in getattr(statement, "ranges", ())]
    if ranges != [("x", "y", "z")]:
        return Finding(Verdict.TYPO, f"the per-DOF 2-ports must range over the three DOFs i = x, y, z; the display has {ranges}",
                       Evidence(Method.PARSE, facts={"printed_form": ranges}))
    return _definition(ctx, "defines the per-DOF 2-ports Z_i, i = x, y, z (entries (i, i), (i, i+3), (i+3, i), (i+3, i+3) of (3))",
                       sp.Matrix([[L("f_{hi}")], [L("f_{ei}")]]), L(r"\mathbf{Z}_i") * sp.Matrix([[L("v_{hi}")], [L("v_{ei}")]]))


@PAPER.equation("5", kind="expression", printed=PRINTED["5"], section="2",
                derivation="extract [[z_ii, z_i,i+3], [z_i+3,i, z_i+3,i+3]] from (3) for i = x, y, z", quotes=('3a',))
def eq5(ctx: AuditContext) -> Finding:
    rel = ctx.statement.relations()[0]
    names = tuple(rel.terms[:-1])
    expected = tuple(TABLE.lookup(rf"\mathbf{{Z}}_{a}") for a in AXES)
    printed = _rhs_matrix(ctx)
    if names != expected:
        return Finding(Verdict.TYPO, f"the chain must name the three DOF subsystems Z_x = Z_y = Z_z; it reads "
                       f"{' = '.join(map(sp.sstr, names))}", Evidence(Method.PARSE, facts={"printed_form": [sp.srepr(x) for x in names]}))
    Z = section2_network()
    mismatched = []
    for i, name in enumerate(AXES):
        sub = Z.extract([i, i + 3], [i, i + 3])
        if printed.shape != (2, 2) or not all(is_identically_zero(a - b) for a, b in zip(sub, printed)):
            mismatched.append((name, sub))
    if mismatched:
        listing = "; ".join(f"Z_{n} = {_line(sub)}" for n, sub in mismatched)
        return Finding(Verdict.TYPO, f"the printed {_line(printed)} is not the subsystem extracted from (3): {listing}",
                       Evidence(Method.CANONICAL_FORM, facts={"printed_form": sp.srepr(printed)}))
    return Finding(Verdict.CONFIRMED, "Z_x, Z_y and Z_z extracted from (3) all equal the printed 2x2 matrix",
                   Evidence(Method.CANONICAL_FORM, facts={"subsystems": list(AXES), "printed_form": ("equals (3)",)}),
                   derived=printed)


@PAPER.equation("5-llewellyn", kind="claim", after="5", section="2",
                printed="the subsystems involving \\mathbf{Z}_x , \\mathbf{Z}_y , and \\mathbf{Z}_z always satisfy Llewellyn's criterion",
                derivation="Llewellyn's criterion decided exactly for (5)")
def subsystems_llewellyn(ctx: AuditContext) -> Finding:
    Z = printed_matrix("5")
    bad = _not_in_s(Z, "the subsystem (5)")
    if bad is not None or Z.shape != (2, 2):
        return Finding(Verdict.UNDECIDED, "(5) is not a 2x2 transfer matrix in s", Evidence(Method.PARSE))
    result = llewellyn(Z)
    if result.decision != Decision.PROVED:
        return Finding(Verdict.WRONG, f"Llewellyn's criterion fails for (5): {result.reason}", result.evidence)
    where = result.tightest.argmin if result.tightest is not None else None
    w = sp.Symbol("w", positive=True)
    at = Z.subs(s, sp.I * w).applyfunc(lambda e: sp.expand_complex(sp.cancel(e)))
    P = sp.expand_complex(at[0, 1] * at[1, 0])
    modulus = sp.sqrt(sp.factor(sp.cancel(sp.expand(P * sp.conjugate(P)))))
    product = sp.factor(sp.cancel(2 * sp.re(at[0, 0]) * sp.re(at[1, 1]) - sp.re(P) - modulus))
    return Finding(Verdict.CONFIRMED,
                   f"Llewellyn's conditions hold exactly: 2 Re z11 Re z22 - Re z12z21 - |z12z21| = {sp.sstr(sp.factor(product))} >= 0; "
                   f"the stability factor is smallest at x = w^2 = {where} with eta = {result.eta_min}",
                   Evidence(result.evidence.method, witness=result.evidence.witness,
                            facts={**dict(result.evidence.facts), "printed_form": ("llewellyn holds", str(result.eta_min))}))


@PAPER.equation("5-unstable", kind="claim", after="5", section="2",
                printed="the coupled 3-DOF teleoperator (2) is not absolutely stable",
                derivation="search for passive 3-DOF terminations with a zero of det(Z + T) in Re s > 0, verified exactly")
def coupled_unstable(ctx: AuditContext) -> Finding:
    roots, degree, passive = _certified("unit")
    sym = symmetrize(RationalMatrix.from_sympy(section2_network()), (3, 3))
    if roots and passive:
        return Finding(Verdict.CONFIRMED,
                       "unit resistors on all six DOFs (T_1 = T_2 = I_3, passive) already destabilize the network (3): "
                       f"det(Z + I) has a zero at s ~ {roots[0].real:.4g} > 0 (certified on the exact degree-{degree} numerator); "
                       f"(3) is not symmetrizable ({sym.reason}), so Theorem 9 does not apply to it",
                       Evidence(Method.COUNTEREXAMPLE, witness={"T_1": "I_3", "T_2": "I_3"},
                                facts={"rhp_roots": [str(r) for r in roots], "numerator_degree": degree}))
    cert = _search("3a")
    if cert is None:
        return Finding(Verdict.UNDECIDED, "no destabilizing termination found (not symmetrizable, so Youla does not decide)",
                       Evidence(Method.INSTANCES))
    return Finding(Verdict.CONFIRMED,
                   f"passive RLC terminations T_1, T_2 (3x3, positive real) put zeros of det(Z + T) at s ~ {cert.roots[0]:.4g} "
                   "(certified, Re s > 0): the network (3) is potentially unstable",
                   Evidence(Method.COUNTEREXAMPLE, facts=_certificate_facts(cert)))


def _scalar_counterexample() -> tuple[sp.Matrix, sp.Matrix]:
    """A potentially unstable reciprocal 2-port and a passive load making its input passive."""
    return sp.Matrix([[1, 3], [3, 1]]), sp.Matrix([[10]])


ENERGY_TABLE = TABLE.with_functions({name: sp.Function(name.replace("{", "").replace("}", ""))
                                     for name in ("F_h", "V_h", "F_e", "V_e", "f_{hx}", "v_{hx}", "f_{ex}", "v_{ex}", "E_s")})


def _energy_reading(ctx: AuditContext, three_dof: bool) -> Finding | None:
    """The display must be the input energy at port 1 from rest, E_s(t) = int_0^t force . velocity >= 0."""
    tau, t = TABLE.lookup(r"\tau"), TABLE.lookup("t")
    force, velocity = ("F_h", "V_h") if three_dof else ("f_hx", "v_hx")
    statement = parse_printed(ctx.equation.printed, ENERGY_TABLE)
    relations = statement.relations()
    expected = sp.Integral(sp.Function(force)(tau) * sp.Function(velocity)(tau), (tau, 0, t))
    if len(relations) != 1:
        return malformed(ctx, f"expected one relation chain, found {len(relations)}")
    rel = relations[0]
    ok = (rel.ops == ("=", ">=") and rel.terms[0] == sp.Function("E_s")(t) and rel.terms[1] == expected and rel.terms[2] == 0)
    if ok:
        return None
    return Finding(Verdict.WRONG, f"the display must be the input energy at port 1, E_s(t) = int_0^t {force} {velocity} dtau >= 0; "
                   f"it reads {' '.join(f'{sp.sstr(x)} {op}' for x, op in zip(rel.terms, rel.ops))} {sp.sstr(rel.terms[-1])}",
                   Evidence(Method.PARSE, facts={"printed_form": sp.srepr(rel.as_sympy())}))


def _energy_quantifier(ctx: AuditContext, three_dof: bool) -> Finding:
    reading = _energy_reading(ctx, three_dof)
    if reading is not None:
        return reading
    Z2, load = _scalar_counterexample()
    Z = sp.kronecker_product(Z2, sp.eye(3)) if three_dof else Z2
    ports = (3, 3) if three_dof else (1, 1)
    termination = sp.kronecker_product(load, sp.eye(3)) if three_dof else load
    verdict = absolute_stability(Z, ports=ports, search=False)
    zin = positive_real(input_impedance(Z, termination, ports))
    if verdict.decision == Decision.DISPROVED and zin.decision == Decision.PROVED:
        return Finding(
            Verdict.NEEDS_ASSUMPTION,
            "true only when E_s(t) >= 0 is required for every passive termination of port 2 and every input from rest "
            "(i.e. the input impedance is positive real for all passive loads); for one termination it is necessary only: "
            f"the 2-port {'kron([[1, 3], [3, 1]], I_3)' if three_dof else '[[1, 3], [3, 1]]'} is potentially unstable, yet with "
            "the passive load 10 its input impedance 2/11 is positive real, so E_s >= 0 for every input",
            Evidence(Method.COUNTEREXAMPLE, witness={"Z": Z2, "load": load},
                     facts={"absolute_stability": verdict.reason, "input_impedance_PR": zin.reason,
                            "printed_form": "input energy at port 1 >= 0"}),
            corrected=(r"\text{absolutely stable} \iff E_s(t) \geq 0 \ \forall t > 0,\ \forall \text{inputs from rest},\ "
                       r"\forall \text{passive terminations of port 2}"),
        )
    return Finding(Verdict.UNDECIDED, "the counterexample did not behave as expected", verdict.evidence)


@PAPER.equation("6", kind="condition", printed=PRINTED["6"], section="2", parse=False,
                derivation="input energy vs absolute stability: quantifiers over terminations and inputs")
def eq6(ctx: AuditContext) -> Finding:
    return _energy_quantifier(ctx, three_dof=True)


@PAPER.equation("7", kind="condition", printed=PRINTED["7"], section="2", parse=False,
                derivation="as (6) for a 1-DOF subsystem")
def eq7(ctx: AuditContext) -> Finding:
    return _energy_quantifier(ctx, three_dof=False)


# ---------------------------------------------------------------------------------------------
# Section 3
# ---------------------------------------------------------------------------------------------


@PAPER.equation("prop4", kind="claim", after="7", section="3",
                printed="Property 4. A Hermitian matrix, i.e., a square matrix equal to its conjugate transpose, is positive "
                        "definite if its leading principal minors are all positive.",
                derivation="Sylvester's criterion, checked on exact instances; the paper later uses it with '>= 0'")
def property4(ctx: AuditContext) -> Finding:
    import random

    import flint

    def minors_positive(M: list[list[Fraction]], subsets) -> bool:
        for S in subsets:
            sub = flint.fmpq_mat([[flint.fmpq(M[i][j].numerator, M[i][j].denominator) for j in S] for i in S])
            if not sub.det() > 0:
                return False
        return True

    rng = random.Random(4)
    checked = 0
    for _ in range(150):
        n = rng.randint(2, 4)
        A = [[Fraction(0)] * n for _ in range(n)]
        B = [[Fraction(0)] * n for _ in range(n)]
        for i in range(n):
            A[i][i] = Fraction(rng.randint(-4, 8), rng.randint(1, 3))
            for j in range(i + 1, n):
                A[i][j] = A[j][i] = Fraction(rng.randint(-4, 4), rng.randint(1, 3))
                B[i][j] = Fraction(rng.randint(-2, 2), rng.randint(1, 3))
                B[j][i] = -B[i][j]
        # H = A + jB is positive definite iff the real embedding [[A, -B], [B, A]] is
        M = [A[i] + [-b for b in B[i]] for i in range(n)] + [B[i] + A[i] for i in range(n)]
        H_leading = [list(range(k)) for k in range(1, n + 1)]
        leading_positive = all(
            sp.expand(sp.Matrix(k, k, lambda a, b: sp.Rational(A[a][b]) + sp.I * sp.Rational(B[a][b])).det()) > 0
            for k in range(1, n + 1)) if minors_positive(A, H_leading[:1]) else False
        if leading_positive:
            checked += 1
            everything = [list(S) for k in range(1, 2 * n + 1) for S in itertools.combinations(range(2 * n), k)]
            if not minors_positive(M, everything):
                return Finding(Verdict.WRONG, "a Hermitian matrix with positive leading minors that is not PD",
                               Evidence(Method.COUNTEREXAMPLE, witness={"A": str(A), "B": str(B)}))
    A = sp.Matrix([[0, 0], [0, -1]])
    return Finding(Verdict.CONFIRMED,
                   "Sylvester's criterion: positive leading minors imply positive definiteness (confirmed on "
                   f"{checked} exact Hermitian instances); note that with '>= 0' it fails ([[0, 0], [0, -1]]), which is "
                   "how conditions D, E and (39)-(45) use it",
                   Evidence(Method.INSTANCES, instances=checked, facts={"semidefinite_counterexample": A}))


# ---------------------------------------------------------------------------------------------
# Section 4: the network, Youla's Z', Theorem 9
# ---------------------------------------------------------------------------------------------


def _section4_definitions() -> dict[str, tuple[str, Any, Any, Any]]:
    L = TABLE.lookup
    Z, Zb = _partition()
    return {
        "8": ("impedance model of the 2-port with 3-DOF ports (6x1 = 6x6 * 6x1)", L(r"\mathcal{F}"),
              L(r"\mathcal{Z}") * L(r"\mathcal{V}"), None),
        "9": ("stacks the port forces F_1, F_2 (3x1 each; [F_1 F_2]^T read as the stack)", L(r"\mathcal{F}"),
              sp.BlockMatrix([[L("F_1")], [L("F_2")]]), _stacked),
        "10": ("stacks the port velocities V_1, V_2 (3x1 each; [V_1 V_2]^T read as the stack)", L(r"\mathcal{V}"),
               sp.BlockMatrix([[L("V_1")], [L("V_2")]]), _stacked),
        "11": ("block partition of Z (as (3))", Z, Zb, None),
        "13": ("block-diagonal termination of two 3-DOF (full 3x3) impedances", L(r"\mathcal{T}"),
               sp.BlockDiagMatrix(L(r"\mathbf{T}_1"), L(r"\mathbf{T}_2")), None),
    }


for _id in ("8", "9", "10", "11", "13"):
    def _check(ctx: AuditContext) -> Finding:
        what, lhs, rhs, reading = _section4_definitions()[ctx.equation.id]
        return _definition(ctx, "defines " + what, lhs, rhs, reading=reading)
    PAPER.equation(_id, kind="expression", printed=PRINTED[_id], section="4", derivation="definition")(_check)


@PAPER.equation("12", kind="expression", printed=PRINTED["12"], section="4",
                derivation="the printed index map z_{3i-2,3j-2}, ... for i, j = 1, 2 vs the 3x3 partition of a 6x6 matrix")
def eq12(ctx: AuditContext) -> Finding:
    from hapticproof.audit.reader.statements import expand_indexed
    from hapticproof.audit.reader.names import index_symbol

    rel = ctx.statement.relations()[0]
    if rel.lhs != TABLE.lookup(r"\mathbf{Z}_{ij}"):
        return Finding(Verdict.TYPO, f"the display must define the block Z_ij; it defines {sp.sstr(rel.lhs)}",
                       Evidence(Method.PARSE, facts={"printed_form": sp.srepr(rel.lhs)}))
    M = _rhs_matrix(ctx)
    i, j = index_symbol("i"), index_symbol("j")
    for bi in (1, 2):
        for bj in (1, 2):
            block = expand_indexed(M.subs({i: bi, j: bj}), 6, TABLE)
            expected = sp.Matrix(3, 3, lambda a, b: TABLE.concrete("z_{i,j}", (3 * (bi - 1) + a + 1, 3 * (bj - 1) + b + 1)))
            if block != expected:
                return Finding(Verdict.TYPO, f"block ({bi},{bj}) maps to the wrong entries",
                               Evidence(Method.CANONICAL_FORM, facts={"printed": block, "expected": expected}))
    return Finding(Verdict.CONFIRMED, "for i, j = 1, 2 the printed indices give exactly the four 3x3 blocks of the 6x6 matrix",
                   Evidence(Method.CANONICAL_FORM, instances=4))


@lru_cache(maxsize=1)
def _table1_symmetrization():
    return symmetrize(table1_impedance(60), (3, 3))


def _zprime_entry(i: int, j: int) -> sp.Expr:
    """Youla's z'_ij (1-based): z_ii on the diagonal, gamma_k sqrt(z_ij z_ji) off it, with k the
    position of the pair among the 15 upper pairs in row order (as (14) numbers them)."""
    z = lambda a, c: TABLE.concrete("z_{i,j}", (a, c))  # noqa: E731
    if i == j:
        return z(i, i)
    a, c = min(i, j), max(i, j)
    k = [(p, q) for p in range(1, 7) for q in range(p + 1, 7)].index((a, c)) + 1
    return TABLE.concrete(r"\gamma_{i}", (k,)) * sp.sqrt(z(a, c) * z(c, a))


def _zprime_reading(ctx: AuditContext) -> Finding | None:
    """The printed Z' (rows and columns 1, 2, ..., 6 with ellipses) against Youla's construction."""
    from hapticproof.audit.reader.statements import Elision

    rel = ctx.statement.relations()[0]
    M = sp.Matrix(rel.rhs)
    index = [1, 2, None, 6]
    problems = []
    if rel.lhs != TABLE.lookup(r"\mathcal{Z}'"):
        problems.append(f"the left side is {sp.sstr(rel.lhs)}, not Z'")
    if M.shape != (4, 4):
        problems.append(f"the printed matrix is {M.shape[0]}x{M.shape[1]}")
    else:
        for r in range(4):
            for c in range(4):
                entry, i, j = M[r, c], index[r], index[c]
                if i is None or j is None:
                    if not isinstance(entry, Elision):
                        problems.append(f"printed entry ({r + 1},{c + 1}) should be an ellipsis, it is {sp.sstr(entry)}")
                    continue
                if isinstance(entry, Elision) or not is_identically_zero(entry - _zprime_entry(i, j)):
                    problems.append(f"entry ({i},{j}) reads {sp.sstr(entry)} instead of {sp.sstr(_zprime_entry(i, j))}")
    if not problems:
        return None
    return Finding(Verdict.TYPO, "the printed Z' is not Youla's z'_ii = z_ii, z'_ij = gamma sqrt(z_ij z_ji): " + "; ".join(problems),
                   Evidence(Method.CANONICAL_FORM, facts={"problems": problems, "printed_form": sp.srepr(M)}))


@PAPER.equation("14", kind="expression", printed=PRINTED["14"], section="4",
                derivation="Youla's Z' for Table 1 (k_vmyz = 60): are the 15 signs gamma free?")
def eq14(ctx: AuditContext) -> Finding:
    reading = _zprime_reading(ctx)
    if reading is not None:
        return reading
    Y = _table1_symmetrization()
    Zp = Y.zprime()
    Z = table1_impedance(60)
    flipped = Zp.copy()
    flipped[0, 3] = flipped[3, 0] = -Zp[0, 3]
    rows = [0, 1, 3]
    at = {s: 1}
    mz = sp.nsimplify(sp.simplify(Z.extract(rows, rows).det().subs(at)))
    mp = sp.nsimplify(sp.simplify(Zp.extract(rows, rows).det().subs(at)))
    mf = sp.nsimplify(sp.simplify(flipped.extract(rows, rows).det().subs(at)))
    if mz == mp and mz != mf:
        return Finding(
            Verdict.NEEDS_ASSUMPTION,
            "Z' has the principal minors of Z only for consistent signs: gamma_ij gamma_jk gamma_ki sqrt(z_ij z_ji) "
            "sqrt(z_jk z_kj) sqrt(z_ki z_ik) = z_ij z_jk z_ki on every triangle (cycle), which fixes the gammas up to a "
            "diagonal +-1 similarity; the roots must be analytic branches. For Table 1, flipping gamma of entry (1,4) alone "
            f"changes the principal minor on rows (1,2,4) at s = 1 from {mz} to {mf}",
            Evidence(Method.COUNTEREXAMPLE, witness={"entry": [1, 4], "rows": [1, 2, 4], "s": 1},
                     facts={"minor_Z": mz, "minor_Zprime": mp, "minor_flipped": mf, "gamma": dict(Y.evidence.facts)["gamma"],
                            "printed_form": "Youla's Z' with free signs gamma"}),
            corrected=(r"z'_{ij} = \gamma_{ij}\sqrt{z_{ij}z_{ji}},\ \gamma_{ij}\gamma_{jk}\gamma_{ki}\sqrt{z_{ij}z_{ji}}"
                       r"\sqrt{z_{jk}z_{kj}}\sqrt{z_{ki}z_{ik}} = z_{ij}z_{jk}z_{ki}"),
        )
    return Finding(Verdict.UNDECIDED, "sign test inconclusive", Evidence(Method.INSTANCES))


PROSE_TABLE = TABLE.with_symbols({r"\mathbf{Z}_{\ell\ell}": sp.MatrixSymbol("Z_ll", 3, 3), r"\ell": sp.Symbol("ell")})


def _prose_math(text: str) -> list[Any]:
    """The mathematics of a prose condition (``\\text{...}`` removed): its expressions and the
    values of its index ranges, in printed order."""
    import re

    fragments = [f.replace(r"\quad", " ").strip(" ,.;") for f in re.split(r"\\text\{[^}]*\}", text)]
    joined = r", \quad ".join(f for f in fragments if f)
    if not joined:
        return []
    statement = parse_printed(joined, PROSE_TABLE)
    out = list(statement.expressions())
    for r in getattr(statement, "ranges", ()):
        out.append(tuple(r.values))
    return out


def _prose_reading(ctx: AuditContext, expected: list[Any], what: str) -> Finding | None:
    found = _prose_math(ctx.equation.printed)
    if found == expected:
        return None
    return Finding(Verdict.TYPO, f"{what} must refer to {', '.join(map(sp.sstr, expected))}; the text's mathematics is "
                   f"{', '.join(map(sp.sstr, found)) or 'missing'}", Evidence(Method.PARSE, facts={"printed_form": [sp.srepr(x) for x in found]}))


def _expected_prose(eq_id: str) -> list[Any]:
    L = PROSE_TABLE.lookup
    return {"14b": [L(r"\mathbf{Z}_{\ell\ell}"), (sp.Integer(1), sp.Integer(2))], "14c": [L(r"\mathcal{Z}")],
            "14d": [L(r"\mathcal{Z}"), L(r"\mathcal{Z}")], "14e": [L(r"\omega"), L(r"\mathcal{Z}'")]}[eq_id]


@PAPER.equation("14a", kind="condition", printed=PRINTED["14a"], section="4",
                derivation="A and B vs Youla's equivalence (identical principal and block-compatible minors)")
def condition_a(ctx: AuditContext) -> Finding:
    from hapticproof.audit.reader.statements import expand_indexed
    from hapticproof.audit.reader.names import index_symbol

    statement = ctx.statement
    i, j, k = (index_symbol(x) for x in "ijk")
    (rel,) = [r.as_sympy() for r in statement.relations()]
    problems = []
    ranges = [(tuple(map(str, r.indices)), tuple(map(str, r.values))) for r in getattr(statement, "ranges", ())]
    if ranges != [(("i", "j", "k"), ("1", "2", r"\dots", "6"))]:
        problems.append(f"the indices must run over 1..6, the display has {ranges}")
    for triple in ((1, 2, 3), (1, 4, 2), (2, 5, 6), (3, 6, 4)):
        got = expand_indexed((rel.lhs - rel.rhs).subs(dict(zip((i, j, k), triple))), 6, TABLE)
        z = lambda a, c: TABLE.concrete("z_{i,j}", (a, c))  # noqa: E731
        a, c, e = triple
        cycle = z(a, c) * z(c, e) * z(e, a) - z(c, a) * z(e, c) * z(a, e)
        if not (is_identically_zero(got - cycle) or is_identically_zero(got + cycle)):
            problems.append(f"for (i, j, k) = {triple} it reads {sp.sstr(got)} = 0, not the triangle condition {sp.sstr(cycle)} = 0")
            break
    if problems:
        return Finding(Verdict.TYPO, "condition A as printed is not Youla's triangle condition: " + "; ".join(problems),
                       Evidence(Method.CANONICAL_FORM, facts={"problems": problems, "printed_form": sp.srepr(rel)}))
    Z = cycle_network()
    conditions = symmetrization_conditions(Z, ports=(3, 3))
    sym = symmetrize(Z, (3, 3))
    roots, degree, passive = _certified("cycle")
    if not conditions and sym.symmetrizable == Decision.DISPROVED and roots and passive:
        return Finding(
            Verdict.NEEDS_ASSUMPTION,
            "A (with B) makes the principal minors of Z' and Z agree only when the entries it cancels are nonzero; "
            "with vanishing entries longer cycles matter: the network cycle_network() (couplings on the cycle 1-4-2-5 only, "
            "z_14 = 2, z_41 = 1/2, others 1) satisfies A and B, but its 4x4 minor on (1,2,4,5) cannot be matched by any Z' "
            f"({sym.reason}) and passive terminations 1/(10(s+1)) make it unstable (det(Z + T) = 0 at s ~ {roots[0].real:.4g})",
            Evidence(Method.COUNTEREXAMPLE, witness={"Z": Z}, facts={"rhp_roots": [str(r) for r in roots], "symmetrization": sym.reason,
                                                                     "printed_form": "Youla's triangle condition"}),
            corrected=(r"z_{i_1 i_2} z_{i_2 i_3} \cdots z_{i_k i_1} = z_{i_2 i_1} z_{i_3 i_2} \cdots z_{i_1 i_k}"
                       r"\ \text{for every cycle } (i_1, \dots, i_k),\ k \geq 3"),
        )
    return Finding(Verdict.UNDECIDED, "the cycle counterexample did not verify", Evidence(Method.INSTANCES))


@PAPER.equation("14b", kind="condition", printed=PRINTED["14b"], section="4", parse=False,
                derivation="det(Z + T) = det(Z' + T) for full block terminations T, one 2-DOF port, symbolic")
def condition_b(ctx: AuditContext) -> Finding:
    reading = _prose_reading(ctx, _expected_prose("14b"), "condition B")
    if reading is not None:
        return reading
    a, b, c, d = sp.symbols("a b c d", positive=True)
    t = sp.Matrix(2, 2, sp.symbols("t11 t12 t21 t22"))
    Z = sp.Matrix([[a, b], [c, d]])
    Zp = sp.Matrix([[a, sp.sqrt(b * c)], [sp.sqrt(b * c), d]])
    diff = sp.expand((Z + t).det() - (Zp + t).det())
    coeffs = [diff.coeff(t[0, 1]), diff.coeff(t[1, 0])]
    solutions = sp.solve(coeffs, [b], dict=True)
    if solutions and all(is_identically_zero(sol[b] - c) for sol in solutions):
        return Finding(Verdict.CONFIRMED,
                       "needed for block (multi-DOF) terminations: det(Z + T) - det(Z' + T) has the coefficients "
                       f"{[sp.sstr(x) for x in coeffs]} of t_12 and t_21, which vanish only for z_12 = z_21 (B); for diagonal "
                       "terminations (single-DOF ports) B is not needed",
                       Evidence(Method.CANONICAL_FORM, facts={"difference": diff}))
    return Finding(Verdict.WRONG, "B is not implied by the determinant identity", Evidence(Method.CANONICAL_FORM, facts={"difference": diff}))


@PAPER.equation("14c", kind="condition", printed=PRINTED["14c"], section="4", parse=False,
                derivation="open-port stability: an unstable z_ij invisible to Z'")
def condition_c(ctx: AuditContext) -> Finding:
    reading = _prose_reading(ctx, _expected_prose("14c"), "condition C")
    if reading is not None:
        return reading
    from hapticproof.exact.rationalmatrix import pole_report

    Z = sp.Matrix([[1, 1 / (s - 1)], [0, 1]])
    sym = symmetrize(sp.Matrix([[1, 0], [0, 1]]))
    zprime_pr = positive_real(sp.eye(2))
    coupled = (RationalMatrix.from_sympy(Z) + RationalMatrix.from_sympy(sp.eye(2))).inverse()
    unstable = pole_report(coupled).rhp
    if unstable and zprime_pr.decision == Decision.PROVED and sym.symmetrizable == Decision.PROVED:
        return Finding(Verdict.CONFIRMED,
                       "necessary, and not implied by positive realness of Z': for Z = [[1, 1/(s-1)], [0, 1]] Youla's Z' = I is "
                       "positive real, yet with unit resistive terminations the map from source to port velocities, (Z + I)^-1, "
                       "has a pole at s = 1",
                       Evidence(Method.COUNTEREXAMPLE, witness={"Z": Z}, facts={"pole": str(unstable[0][1])}))
    return Finding(Verdict.UNDECIDED, "example did not verify", Evidence(Method.INSTANCES))


@PAPER.equation("14d", kind="condition", printed=PRINTED["14d"], section="4", parse=False,
                derivation="residue matrix of Z' at s = 0 for Table 1 (k_vmyz = 60), exact")
def condition_d(ctx: AuditContext) -> Finding:
    reading = _prose_reading(ctx, _expected_prose("14d"), "condition D")
    if reading is not None:
        return reading
    Zp = _table1_symmetrization().zprime()
    R = Zp.applyfunc(lambda e: sp.cancel(e * s).subs(s, 0))
    leading = [sp.nsimplify(sp.simplify(R[:k, :k].det())) for k in range(1, 7)]
    verdict = table1_verdict(60)
    psd, _ = matrix_psd(R)
    if verdict.decision == Decision.PROVED and leading[3] == 0 and psd:
        return Finding(
            Verdict.WRONG,
            "not necessary: for the paper's own Table 1 gains (k_vmyz = 60), absolutely stable (Z' positive real, verified), "
            f"the residue matrix of Z' at s = 0 has rank 3 and leading principal minors {[sp.sstr(v) for v in leading]}, so "
            "'greater than zero' fails; the residues must be Hermitian PSD (all principal minors >= 0), and they are those of "
            "Z' (the residue matrix of Z, [[K_pm, -K_pm], [-K_ps, K_ps]], is not even symmetric)",
            Evidence(Method.COUNTEREXAMPLE, witness={"gains": "Table 1, k_vmyz = 60"},
                     facts={"leading_minors": leading, "residue_psd": psd, "absolute_stability": verdict.reason}),
            corrected=(r"\text{D) Any poles of the elements of } \mathcal{Z}' \text{ on the imaginary axis (and at infinity) are simple,"
                       r" with Hermitian positive semidefinite residue matrices (all principal minors} \geq 0)"),
        )
    return Finding(Verdict.UNDECIDED, "the residue test did not behave as expected", Evidence(Method.INSTANCES, facts={"leading": leading}))


@PAPER.equation("14e", kind="condition", printed=PRINTED["14e"], section="4", parse=False,
                derivation="leading minors >= 0 vs PSD; exact destabilizing terminations")
def condition_e(ctx: AuditContext) -> Finding:
    reading = _prose_reading(ctx, _expected_prose("14e"), "condition E")
    if reading is not None:
        return reading
    Z = leading_minor_network()
    leading = [Z[:k, :k].det() for k in range(1, 7)]
    roots, degree, passive = _certified("leading")
    if all(v >= 0 for v in leading) and roots and passive:
        return Finding(
            Verdict.WRONG,
            "leading principal minors >= 0 do not give PSD: the reciprocal network Z = diag([[0,0,0],[0,1,2],[0,2,1]], I_3) "
            "(Z' = Z) has all leading minors 0 and satisfies A-D, but passive terminations diag(1, 2/(s+1), 2/(s+1)), I_3 make "
            f"det(Z + T) vanish at s = {roots[0].real:.4g} > 0; all principal minors of Re Z'(jw) must be >= 0",
            Evidence(Method.COUNTEREXAMPLE, witness={"Z": Z}, facts={"leading_minors": leading, "rhp_roots": [str(r) for r in roots]}),
            corrected=(r"\text{E) For all real } \omega, \text{ all principal minors of } \text{Re}(\mathcal{Z}'(j\omega))"
                       r"\text{ are } \geq 0"),
        )
    return Finding(Verdict.UNDECIDED, "the counterexample did not verify", Evidence(Method.INSTANCES))


@PAPER.equation("15a", kind="condition", printed=PRINTED["15a"], section="4",
                derivation="1x1 principal minors of Re Z': z'_ii = z_ii by (14)")
def eq15a(ctx: AuditContext) -> Finding:
    from hapticproof.audit.compare import as_sign_condition
    from hapticproof.audit.reader.statements import expand_indexed
    from hapticproof.audit.reader.names import index_symbol

    statement = ctx.statement
    ranges = [tuple(map(str, r.values)) for r in getattr(statement, "ranges", ())]
    (rel,) = [r.as_sympy() for r in statement.relations()]
    condition = as_sign_condition(rel)
    i = index_symbol("i")
    read = [expand_indexed(condition.expr.subs(i, k), 6, TABLE) for k in range(1, 7)]
    want = [sp.re(TABLE.concrete("z_{i,j}", (k, k))) for k in range(1, 7)]
    problems = []
    if ranges != [("1", "2", r"\dots", "6")]:
        problems.append(f"the index must run over all six diagonal entries, the display has {ranges}")
    if condition.op not in (">=",):
        problems.append(f"a principal minor of a PSD matrix is >= 0, the display says {condition.op} 0")
    if read != want:
        problems.append(f"it reads {[sp.sstr(x) for x in read[:2]]}... >= 0 instead of Re z_ii >= 0")
    if problems:
        if condition.op != ">=":
            return Finding(Verdict.WRONG,
                           "(15a) is not the 1x1 principal-minor condition Re z_ii >= 0, i = 1..6: " + "; ".join(problems),
                           Evidence(Method.PARSE, facts={"problems": problems, "printed_form": sp.srepr(rel)}))
        return Finding(Verdict.TYPO,
                       "(15a) has the relation of a 1x1 principal-minor condition but not its entries or range: "
                       + "; ".join(problems),
                       Evidence(Method.PARSE, facts={"problems": problems, "printed_form": sp.srepr(rel)}),
                       corrected=r"\text{Re}(z_{i,i}) \geq 0, \quad i = 1, 2, \dots, 6")
    Y = _table1_symmetrization()
    Z = table1_impedance(60)
    same = all(is_identically_zero(Y.zprime()[i, i] - Z[i, i]) for i in range(6))
    if not same:
        return Finding(Verdict.WRONG, "diagonal of Z' differs from Z", Evidence(Method.CANONICAL_FORM))
    return Finding(Verdict.CONFIRMED, "Re z'_ii = Re z_ii >= 0 are the 1x1 principal minors of Re Z' (necessary; all six, "
                   "not only the leading one)", Evidence(Method.CANONICAL_FORM, facts={"checked_on": "Table 1",
                                                                                      "printed_form": "Re z_ii >= 0, i = 1..6"}))


@PAPER.equation("15b", kind="condition", printed=PRINTED["15b"], section="4",
                derivation="2nd leading minor of Re Z' with (20): Re z11 Re z22 - (|z12 z21| + Re z12 z21)/2")
def eq15b(ctx: AuditContext) -> Finding:
    from hapticproof.audit.compare import as_sign_condition

    condition = as_sign_condition(ctx.relation())
    printed_lhs = condition.expr
    z = {(i, j): TABLE.concrete("z_{i,j}", (i, j)) for i in (1, 2) for j in (1, 2)}
    p = z[(1, 2)] * z[(2, 1)]
    derived = sp.re(z[(1, 1)]) * sp.re(z[(2, 2)]) - (sp.Abs(p) + sp.re(p)) / 2
    slip = sp.re(z[(1, 1)]) * sp.re(z[(2, 2)]) - sp.Abs(sp.re(p))           # |Re(z12 z21)| printed twice
    point = {z[(1, 1)]: 2, z[(2, 2)]: 3, z[(1, 2)]: 1 + 2 * sp.I, z[(2, 1)]: 3 - sp.I}
    value_p, value_d = sp.nsimplify(sp.simplify(printed_lhs.subs(point))), sp.nsimplify(sp.simplify(derived.subs(point)))
    facts = {"printed": value_p, "derived": value_d, "printed_form": (condition.op, sp.srepr(sp.expand(printed_lhs)))}
    corrected = r"\text{Re}(z_{1,1})\text{Re}(z_{2,2}) - \frac{|z_{1,2}z_{2,1}| + \text{Re}(z_{1,2}z_{2,1})}{2} \geq 0"
    witness = {"z11": 2, "z22": 3, "z12": "1+2j", "z21": "3-j"}
    if condition.op != ">=":
        return Finding(Verdict.WRONG, f"a principal minor of a PSD matrix is >= 0; the display says {condition.op} 0 "
                       f"(at the witness the printed expression is {value_p}, the minor {value_d})",
                       Evidence(Method.COUNTEREXAMPLE, witness=witness, facts=facts), derived=sp.Ge(derived, 0), corrected=corrected)
    if is_identically_zero(sp.expand(printed_lhs - derived)):
        return Finding(Verdict.CONFIRMED, "the printed minor is Re z11 Re z22 - (|z12 z21| + Re z12 z21)/2, by (20)",
                       Evidence(Method.CANONICAL_FORM, facts=facts), derived=sp.Ge(derived, 0))
    cause = ("the printed numerator |Re(z12 z21)| + |Re(z12 z21)| repeats one term: (20) gives |z12 z21| + Re(z12 z21)"
             if is_identically_zero(sp.expand(printed_lhs - slip)) else "it is not the 2nd minor given by (20)")
    return Finding(Verdict.TYPO,
                   f"{cause}; at z11 = 2, z22 = 3, z12 = 1 + 2j, z21 = 3 - j the printed minor is {value_p}, the true one "
                   f"{value_d}", Evidence(Method.COUNTEREXAMPLE, witness=witness, facts=facts),
                   derived=sp.Ge(derived, 0), corrected=corrected)


@PAPER.equation("15c", kind="condition", printed=PRINTED["15c"], section="4",
                derivation="the 6th principal minor of Re Z' (exact for Table 1)")
def eq15c(ctx: AuditContext) -> Finding:
    from hapticproof.audit.compare import as_sign_condition

    condition = as_sign_condition(ctx.relation())
    Zp = TABLE.lookup(r"\mathcal{Z}'")
    # the printed left side evaluated at test matrices A (in place of Z') against det Re A
    rng = __import__("random").Random(15)
    tests = []
    for _ in range(3):
        A = sp.Matrix(6, 6, lambda i, j: sp.Rational(rng.randint(-5, 5), rng.randint(1, 3))
                      + sp.I * sp.Rational(rng.randint(-5, 5), rng.randint(1, 3)))
        read = sp.nsimplify(sp.expand(condition.expr.subs(Zp, sp.ImmutableMatrix(A)).doit()))
        tests.append((read, ((A + A.conjugate()) / 2).det()))
    ratios = {sp.nsimplify(r / d) if d != 0 else None for r, d in tests}
    facts = {"printed_over_det_re": [str(r) for r in ratios], "printed_form": (condition.op, sorted(map(str, ratios)))}
    if len(ratios) != 1 or None in ratios or not list(ratios)[0].is_positive or condition.op not in (">=",):
        return Finding(Verdict.WRONG, f"(15c) reads {sp.sstr(condition.expr)} {condition.op} 0, not det Re Z' >= 0 (the full "
                       f"principal minor): at three test matrices the printed left side over det Re A is {sorted(map(str, ratios))}",
                       Evidence(Method.COUNTEREXAMPLE, facts=facts), derived=sp.Ge(sp.Symbol("det_Re_Zp"), 0),
                       corrected=r"\det(\text{Re}(\mathcal{Z}')) \geq 0")
    det = real_part_leading_minors()[5]
    return Finding(Verdict.CONFIRMED,
                   "det Re Z' >= 0 is a necessary condition (the full principal minor); under (38) it is identically "
                   f"{det} (Re Z' has rank 3), so it holds but says nothing -- the order-1..3 principal minors decide",
                   Evidence(Method.CANONICAL_FORM, facts={**facts, "det_under_38": det, "printed_form": "det Re Z' >= 0"}))


@PAPER.equation("thm9", kind="claim", after="15c", section="4",
                printed="Theorem 9. An 3-DOF bilateral haptic system with impedance matrix \\mathcal{Z} in (11) satisfying the "
                        "symmetrization conditions A) B) is absolutely stable if and only if C) D) E)",
                derivation="a network satisfying A-E (even E with all principal minors) with verified destabilizing terminations")
def theorem9(ctx: AuditContext) -> Finding:
    Z = cycle_network()
    roots, degree, passive = _certified("cycle")
    conditions = symmetrization_conditions(Z, ports=(3, 3))
    gammas = []
    for g in itertools.product((1, -1), repeat=4):
        Zp = sp.Matrix(Z)
        for (a, b), sign in zip(((0, 3), (3, 1), (1, 4), (4, 0)), g):
            Zp[a, b] = Zp[b, a] = sign
        gammas.append(matrix_psd(Zp)[0])
    if not conditions and roots and passive and all(gammas):
        return Finding(
            Verdict.WRONG,
            "the 'if' fails: cycle_network() satisfies A and B, has no poles (C, D), and Re Z' = Z' is PSD for every sign "
            f"choice of (14) (E, even with all principal minors), yet passive terminations make det(Z + T) vanish at "
            f"s ~ {roots[0].real:.4g} > 0; besides, D and E as printed use leading minors (see 14d, 14e)",
            Evidence(Method.COUNTEREXAMPLE, witness={"Z": Z},
                     facts={"rhp_roots": [str(r) for r in roots], "zprime_psd_for_all_signs": True}),
            corrected=(r"\text{If } \mathcal{Z}' \text{ with the same principal and block-compatible minors as } \mathcal{Z}"
                       r"\text{ exists, } \mathcal{Z} \text{ is absolutely stable iff C holds and } \mathcal{Z}' \text{ is positive real}"),
        )
    return Finding(Verdict.UNDECIDED, "the counterexample did not verify", Evidence(Method.INSTANCES))


@PAPER.equation("16", kind="expression", printed=PRINTED["16"], section="4", derivation="Laplace transform, checked on h = e^{-2t}")
def eq16(ctx: AuditContext) -> Finding:
    rel = ctx.statement.relations()[0]
    t = TABLE.lookup("t")
    h = sp.Function("h")
    if rel.lhs != sp.Function("H")(s) or rel.ops != ("=",):
        return Finding(Verdict.TYPO, f"the display must define H(s); it reads {sp.sstr(rel.lhs)} {rel.ops[0]} ...",
                       Evidence(Method.PARSE, facts={"printed_form": sp.srepr(rel.lhs)}))
    value = rel.rhs.subs(h(t), sp.exp(-2 * t)).subs(s, 3).doit()
    if value == sp.Rational(1, 5):
        return Finding(Verdict.CONFIRMED, "the one-sided Laplace transform (for h = e^{-2t} at s = 3 it gives 1/(s+2) = 1/5)",
                       Evidence(Method.INSTANCES, instances=1))
    return Finding(Verdict.TYPO, f"gives {value} for h = e^(-2t) at s = 3, where the Laplace transform is 1/5",
                   Evidence(Method.INSTANCES, facts={"printed_form": sp.srepr(rel.rhs)}))


def _det_with_diagonal(M: sp.Matrix, t: list) -> sp.Expr:
    return (M + sp.diag(*t)).det(method="berkowitz")


def _det_identity(ctx: AuditContext, first: Any, second: Any, termination: Any, blocks: bool, label: str) -> Finding | None:
    """The printed ``det(X + T) = det(Y + T)`` evaluated with X := Z, Y := Z' of Table 1 at exact
    instances (diagonal or full block terminations T); a finding when it is not that identity."""
    import random

    (rel,) = ctx.statement.relations()
    symbols = rel.lhs.free_symbols | rel.rhs.free_symbols
    if rel.ops != ("=",) or first not in rel.lhs.free_symbols | rel.rhs.free_symbols or second not in symbols \
            or (first in rel.lhs.free_symbols) == (first in rel.rhs.free_symbols):
        return Finding(Verdict.WRONG, f"{label} must equate det(Z + T) and det(Z' + T); it reads {sp.sstr(rel.as_sympy())}",
                       Evidence(Method.PARSE, facts={"printed_form": sp.srepr(rel.as_sympy())}))
    Z = table1_impedance(60)
    Zp = _table1_symmetrization().zprime()
    rng = random.Random(17)
    for _ in range(3):
        point = sp.Rational(rng.randint(1, 9), rng.randint(1, 4))
        if blocks:
            T = sp.diag(*[sp.Matrix(3, 3, lambda i, j: sp.Rational(rng.randint(0, 9), rng.randint(1, 5))) for _ in range(2)])
        else:
            T = sp.diag(*[sp.Rational(rng.randint(0, 9), rng.randint(1, 5)) for _ in range(6)])
        values = {first: sp.ImmutableMatrix(Z.subs(s, point)), second: sp.ImmutableMatrix(Zp.subs(s, point)),
                  termination: sp.ImmutableMatrix(T)}
        a, c = (sp.nsimplify(sp.simplify(side.xreplace(values).doit())) for side in (rel.lhs, rel.rhs))
        if sp.simplify(a - c) != 0:
            return Finding(Verdict.WRONG, f"{label} fails for Table 1 at s = {point}: {sp.sstr(a)} vs {sp.sstr(c)}",
                           Evidence(Method.COUNTEREXAMPLE, witness={"s": point, "T": T}, facts={"printed_form": sp.srepr(rel.as_sympy())}))
    return None


@PAPER.equation("17", kind="condition", printed=PRINTED["17"], section="4",
                derivation="det(Z + diag t) = sum over S of det Z[S] prod_{i not in S} t_i; exact instances for Table 1 and its Z'")
def eq17(ctx: AuditContext) -> Finding:
    L = TABLE.lookup
    failure = _det_identity(ctx, L("Z_1"), L("Z_2"), L("T_0"), False, "(17)")
    if failure is not None:
        return failure
    return Finding(Verdict.CONFIRMED,
                   "det(Z + T_0) expands into principal minors of Z times products of the t_i, so identical principal minors "
                   "give equal determinants for every diagonal T_0 (checked exactly on 3 instances for Table 1 and its Z')",
                   Evidence(Method.INSTANCES, instances=3, facts={"printed_form": "det(Z + T) = det(Z' + T), T diagonal"}))


@PAPER.equation("18", kind="condition", printed=PRINTED["18"], section="4",
                derivation="all block-compatible minors of Z and Z' (Table 1, k_vmyz = 60), exact")
def eq18(ctx: AuditContext) -> Finding:
    L = TABLE.lookup
    failure = _det_identity(ctx, L(r"\mathcal{Z}'"), L(r"\mathcal{Z}"), L(r"\mathcal{T}"), True, "(18)")
    if failure is not None:
        return failure
    Y = _table1_symmetrization()
    if Y.symmetrizable == Decision.PROVED:
        count = Y.evidence.facts.get("block_compatible_minors_checked")
        return Finding(Verdict.CONFIRMED,
                       "for 3-DOF block terminations det(Z + T) = det(Z' + T) holds iff every minor of Z with the same number of "
                       f"rows and columns in each port equals that of Z'; verified exactly for Table 1 ({count} minors) and on 3 "
                       "exact block terminations. A and B alone do not guarantee it (see 14a)",
                       Evidence(Y.evidence.method, facts={**dict(Y.evidence.facts), "printed_form": "det(Z' + T) = det(Z + T)"}))
    return Finding(Verdict.WRONG, Y.reason, Y.evidence)


@PAPER.equation("19", kind="condition", printed=PRINTED["19"], section="4", parse=False,
                derivation="Z'(-jw) = conj Z'(jw) for a real-rational symmetric Z' (Table 1)")
def eq19(ctx: AuditContext) -> Finding:
    import mpmath

    Y = _table1_symmetrization()
    Zp_sym = Y.zprime()
    table = TABLE.with_functions({r"\mathcal{Z}'": lambda a: sp.ImmutableMatrix(Zp_sym.subs(s, a))})
    (rel,) = parse_printed(ctx.equation.printed, table).relations()
    w_sym = TABLE.lookup(r"\omega")
    variables = sorted(sp.Matrix(rel.lhs - rel.rhs).free_symbols, key=str)
    if len(variables) != 1 or not variables[0].is_real:
        return Finding(Verdict.WRONG, f"the printed identity is not one in a real frequency: its sides hold "
                       f"{[str(v) for v in variables]}", Evidence(Method.PARSE, facts={"variables": [str(v) for v in variables]}))
    (var,) = variables                      # the printed frequency (a renamed one is the same identity)
    form = sp.srepr(rel.as_sympy().xreplace({var: w_sym}))
    residual = 0.0
    for w in (1, 3):
        gap = sp.Matrix(rel.lhs - rel.rhs).subs(var, w).evalf(30)
        residual = max(residual, float(gap.norm()))
    if rel.ops != ("=",) or residual > 1e-12:
        return Finding(Verdict.WRONG, f"the printed identity does not hold for Table 1's Z': |lhs - rhs| = {residual:.3g} at "
                       f"{var} = 1 or 3", Evidence(Method.COUNTEREXAMPLE, witness={str(var): [1, 3]},
                                                    facts={"residual": residual, "printed_form": form}))
    positive = all(c > 0 for c in Y.c.values())
    Zp = Y.zprime()
    worst = mpmath.mpf(0)
    with mpmath.workdps(40):
        for w in (1, 3):
            for i in range(6):
                for j in range(6):
                    a = complex(sp.N(Zp[i, j].subs(s, sp.I * w), 40))
                    b = complex(sp.N(Zp[j, i].subs(s, -sp.I * w), 40))
                    worst = max(worst, abs(a + b - 2 * a.real))
    if positive and worst < 1e-12:
        return Finding(Verdict.CONFIRMED,
                       "every off-diagonal z'_ij = gamma sqrt(c_ij) q_ij(s) has c_ij > 0 and q_ij real-rational (Table 1), so Z' "
                       "is symmetric with real coefficients, Z'^T(-jw) = conj Z'(jw) and the Hermitian part is 2 Re Z'(jw) "
                       "(numerically re-checked at w = 1, 3); when some z_ij z_ji is a negative constant times a square, Z' has "
                       "imaginary entries and Z'^H(jw) must replace Z'^T(-jw)",
                       Evidence(Method.STRUCTURAL, facts={"c": {f"{i},{j}": v for (i, j), v in Y.c.items()}, "max_residual": float(worst),
                                                          "printed_form": form}))
    return Finding(Verdict.UNDECIDED,
                   f"the printed identity holds at w = 1, 3, but Table 1's Z' is not symmetric with real coefficients "
                   f"(all c_ij > 0: {positive}; largest |z'_ij(jw) + z'_ji(-jw) - 2 Re z'_ij(jw)| = {float(worst):.3g})",
                   Evidence(Method.COUNTEREXAMPLE, facts={"max_residual": float(worst), "printed_form": form}))


@PAPER.equation("20", kind="condition", printed=PRINTED["20"], section="4",
                derivation="principal square root: exact Gaussian-rational instances")
def eq20(ctx: AuditContext) -> Finding:
    rel = ctx.statement.relations()[0]
    zij, zji = TABLE.concrete("z_{i,j}", (1, 2)), TABLE.concrete("z_{i,j}", (2, 1))
    from hapticproof.audit.reader.statements import expand_indexed
    from hapticproof.audit.reader.names import index_symbol

    i, j = index_symbol("i"), index_symbol("j")
    lhs = expand_indexed(rel.lhs.subs({i: 1, j: 2}), 6, TABLE)
    rhs = expand_indexed(rel.rhs.subs({i: 1, j: 2}), 6, TABLE)
    count = 0
    for a, b in ((1, 2), (3, -1), (-2, 5), (1, 0), (-3, -4), (0, 2)):
        w = sp.expand((a + sp.I * b) ** 2)
        point = {zij: w, zji: 1}
        left, right = sp.nsimplify(sp.simplify(lhs.subs(point))), sp.nsimplify(sp.simplify(rhs.subs(point)))
        if not is_identically_zero(left - right) or not is_identically_zero(left - abs(a)):
            return Finding(Verdict.WRONG, f"fails at w = {w}", Evidence(Method.COUNTEREXAMPLE, witness={"w": w}))
        count += 1
    return Finding(Verdict.CONFIRMED,
                   "for the principal branch Re sqrt(w) = sqrt((|w| + Re w)/2) >= 0 (w = r e^{j phi}: Re = sqrt(r) cos(phi/2)); "
                   f"checked exactly on {count} instances w = (a + jb)^2; it fixes (Re z'_ij)^2 whatever gamma, but the sign of "
                   "Re z'_ij (needed in minors of order >= 3) follows the analytic branch, not the principal one",
                   Evidence(Method.INSTANCES, instances=count))


# ---------------------------------------------------------------------------------------------
# Section 5.1: the case study model
# ---------------------------------------------------------------------------------------------


def _model_definitions() -> dict[str, tuple[str, Any, Any]]:
    """The case study's model (the convention of :func:`case_study_impedance`): device forces
    balance the port force and the controller force; position-position controllers."""
    L = TABLE.lookup
    Zm, Zs, Cm, Cs = (L(k) for k in (r"\mathbf{Z}_m", r"\mathbf{Z}_s", r"\mathbf{C}_m", r"\mathbf{C}_s"))
    Vh, Ve, Fh, Fe, Fcm, Fcs = (L(k) for k in ("V_h", "V_e", "F_h", "F_e", "F_{cm}", "F_{cs}"))
    return {
        "21a": ("master dynamics Z_m V_h = F_h + F_cm with Z_m = M_m s", Zm * Vh, Fh + Fcm),
        "21b": ("slave dynamics Z_s V_e = F_e + F_cs with Z_s = M_s s", Zs * Ve, Fe + Fcs),
        "23a": ("master position-position law", Fcm, -Cm * Vh + Cm * Ve),
        "23b": ("slave position-position law", Fcs, -Cs * Ve + Cs * Vh),
    }


for _id in ("21a", "21b", "23a", "23b"):
    def _check(ctx: AuditContext) -> Finding:
        what, lhs, rhs = _model_definitions()[ctx.equation.id]
        return _definition(ctx, "defines the " + what + " (used in (25))", lhs, rhs)
    PAPER.equation(_id, kind="expression", printed=PRINTED[_id], section="5.1", derivation="model definition")(_check)


@PAPER.equation("22", kind="expression", printed=PRINTED["22"], section="5.1",
                derivation="general inertia matrix; which of its entries the symmetrization conditions see")
def eq22(ctx: AuditContext) -> Finding:
    rel = ctx.statement.relations()[0]
    M = _rhs_matrix(ctx)
    expected = sp.Matrix(3, 3, lambda a, c: TABLE.lookup(f"m_{{i{AXES[a]}{AXES[c]}}}"))
    if rel.lhs != TABLE.lookup(r"\mathbf{M}_i") or M.shape != (3, 3):
        return Finding(Verdict.TYPO, f"the display must define the 3x3 inertia matrix M_i; it reads {_line(rel.lhs)} = "
                       f"{M.shape[0]}x{M.shape[1]} matrix", Evidence(Method.PARSE, facts={"printed_form": sp.srepr(rel.lhs)}))
    misplaced = [(a, c) for a in range(3) for c in range(3) if M[a, c] != expected[a, c]]
    if misplaced:
        listing = "; ".join(f"({AXES[a]},{AXES[c]}): {sp.sstr(M[a, c])}" for a, c in misplaced)
        return Finding(Verdict.TYPO, f"entry (a, b) of M_i must be m_iab; the display has {listing}",
                       Evidence(Method.CANONICAL_FORM, facts={"printed_form": sp.srepr(M)}), corrected=tex(sp.Eq(
                           TABLE.lookup(r"\mathbf{M}_i"), expected, evaluate=False)))
    general = case_study_impedance(gain_matrix("pm"), gain_matrix("vm"), gain_matrix("ps"), gain_matrix("vs"),
                                   gain_matrix("mm"), gain_matrix("ms"))
    extra = [c for c in symmetrization_conditions(general, ports=(3, 3)) if c.kind == "B"]
    mass_terms = any(c.expr.has(gain("mm", "x", "y")) for c in extra)
    return Finding(Verdict.CONFIRMED,
                   "a general 3x3 inertia matrix (9 entries); with m_ixy != m_iyx condition B would carry the extra terms "
                   "j w (m_iyx - m_ixy) absent from (26)-(31) -- the audit takes M_i symmetric, as inertia matrices are",
                   Evidence(Method.PARSE, facts={"entries": len(M.free_symbols), "mass_terms_in_B_if_asymmetric": mass_terms,
                                                 "printed_form": sp.srepr(M)}))


def _printed_gain_matrix(ctx: AuditContext, kind: str) -> Finding:
    rel = ctx.statement.relations()[0]
    name = TABLE.lookup(r"\mathbf{C}_" + kind)
    if rel.lhs != name:
        return Finding(Verdict.TYPO, f"the display must define {sp.sstr(name)}; it defines {sp.sstr(rel.lhs)}",
                       Evidence(Method.PARSE, facts={"printed_form": sp.srepr(rel.lhs)}))
    printed = _rhs_matrix(ctx)
    derived = (gain_matrix("p" + kind) + gain_matrix("v" + kind) * s) / s
    bad = [(i, j) for i in range(3) for j in range(3) if not is_identically_zero(printed[i, j] - derived[i, j])]
    if not bad:
        return Finding(Verdict.CONFIRMED, "matches (K_p + K_v s)/s entrywise", Evidence(Method.CANONICAL_FORM))
    listing = "; ".join(f"({AXES[i]},{AXES[j]}): printed {sp.sstr(sp.together(printed[i, j]))}" for i, j in bad)
    return Finding(Verdict.TYPO,
                   f"{len(bad)} entries carry wrong gain names (PD gains k_p{kind}ab + k_v{kind}ab s expected at (a, b)): {listing}",
                   Evidence(Method.CANONICAL_FORM, witness={"entries": [[AXES[i], AXES[j]] for i, j in bad]}),
                   derived=derived, corrected=r"\mathbf{C}_%s = \frac{1}{s}\left(\mathbf{K}_{p%s} + \mathbf{K}_{v%s}s\right) = "
                   % (kind, kind, kind) + tex(derived))


@PAPER.equation("23c", kind="expression", printed=PRINTED["23c"], section="5.1", derivation="C_m = (K_pm + K_vm s)/s entrywise")
def eq23c(ctx: AuditContext) -> Finding:
    return _printed_gain_matrix(ctx, "m")


@PAPER.equation("24", kind="expression", printed=PRINTED["24"], section="5.1", derivation="C_s = (K_ps + K_vs s)/s entrywise")
def eq24(ctx: AuditContext) -> Finding:
    return _printed_gain_matrix(ctx, "s")


@PAPER.equation("25", kind="expression", printed=PRINTED["25"], section="5.1", derivation="substitute (23) into (21)", quotes=('21a', '21b', '23a', '23b'))
def eq25(ctx: AuditContext) -> Finding:
    L = TABLE.lookup
    Fh, Fe, Fcm, Fcs = (L(k) for k in ("F_h", "F_e", "F_{cm}", "F_{cs}"))
    unknowns = [e for M in (Fh, Fe, Fcm, Fcs) for e in M.as_explicit()]
    equations = []
    for eq_id in ("21a", "21b", "23a", "23b"):
        (rel,) = parse_printed(PAPER.get(eq_id).printed, TABLE).relations()
        equations += list(_explicit(rel.lhs) - _explicit(rel.rhs))
    solution = sp.solve(equations, unknowns, dict=True)
    if len(solution) != 1 or any(u not in solution[0] for u in unknowns[:6]):
        return Finding(Verdict.UNDECIDED, "(21) and (23) as printed do not determine the port forces",
                       Evidence(Method.CANONICAL_FORM, facts={"ids": ["21a", "21b", "23a", "23b"]}))
    rel = ctx.statement.relations()[0].as_sympy()
    difference = (_explicit(rel.lhs) - _explicit(rel.rhs)).applyfunc(lambda e: sp.expand(e.xreplace(solution[0])))
    bad = [k for k, e in enumerate(difference) if e != 0]
    if not bad:
        return Finding(Verdict.CONFIRMED, "F_h = (C_m + Z_m) V_h - C_m V_e and F_e = -C_s V_h + (C_s + Z_s) V_e follow from the "
                       "printed (21) and (23)", Evidence(Method.CANONICAL_FORM, facts={"printed_form": ("follows from (21), (23)",)}))
    row = bad[0]
    return Finding(Verdict.TYPO, f"does not follow from (21) and (23): row {row + 1} of the printed system differs from them by "
                   f"{sp.sstr(difference[row])}", Evidence(Method.COUNTEREXAMPLE, facts={"rows": [k + 1 for k in bad],
                                                                                          "printed_form": sp.srepr(difference)}))


# ---------------------------------------------------------------------------------------------
# (26)-(37): the symmetrization conditions
# ---------------------------------------------------------------------------------------------

B_PAIRS = {"26": (0, 1), "27": (0, 2), "28": (1, 2), "29": (3, 4), "30": (3, 5), "31": (4, 5)}


def _at_omega(expr: sp.Expr) -> sp.Expr:
    poly = sp.Poly(expr, s)
    low = min(m[0] for m in poly.monoms())
    return sp.expand(sp.expand(expr / s**low).subs(s, sp.I * omega))


def _b_check(ctx: AuditContext) -> Finding:
    pair = B_PAIRS[ctx.equation.id]
    cond = next(c for c in derived_conditions() if c.kind == "B" and c.indices == pair)
    rel = ctx.relation()
    printed = sp.expand(rel.lhs - rel.rhs)
    derived = cond.at_frequency(omega)
    if not isinstance(rel, sp.Eq) or printed == 0:
        return Finding(Verdict.WRONG, f"condition B is an equation z_ji - z_ij = 0; the display reads {sp.sstr(rel)}",
                       Evidence(Method.PARSE, facts={"printed_form": sp.srepr(rel)}), derived=sp.Eq(derived, 0))
    ratio = sp.cancel(derived / printed)
    if ratio != 0 and ratio.free_symbols <= {omega} and not ratio.has(sp.zoo, sp.nan):
        a, b = (AXES[i % 3] for i in pair)
        return Finding(Verdict.CONFIRMED,
                       f"equivalent to z_{{{pair[1] + 1},{pair[0] + 1}}} = z_{{{pair[0] + 1},{pair[1] + 1}}} at s = j omega "
                       f"(the derived numerator is {sp.sstr(sp.factor(ratio))} times the printed expression); with a non-symmetric "
                       f"inertia matrix the term j omega (m_{b}{a} - m_{a}{b}) would be missing",
                       Evidence(Method.CANONICAL_FORM, facts={"ratio": ratio, "printed_form": ("B", pair)}),
                       derived=sp.Eq(derived, 0))
    return compare_expressions(printed, derived, what="the printed B-condition")


for _id in B_PAIRS:
    PAPER.equation(_id, kind="condition", printed=PRINTED[_id], section="5.1", assumptions=ASSUME_CASE,
                   derivation=f"condition B for the pair {B_PAIRS[_id]}: z_ji - z_ij at s = j omega")(_b_check)


@lru_cache(maxsize=1)
def _a_candidates():
    out = []
    for c in derived_conditions():
        if c.kind != "A" or len({i // 3 for i in c.indices}) == 1:
            continue
        out.append((c, canonical(_at_omega(c.expr))))
    return tuple(out)


def _omega_form(expr: sp.Expr) -> str:
    parts = sp.collect(sp.expand(expr), omega, evaluate=False)
    pieces = []
    for power, coefficient in sorted(parts.items(), key=lambda kv: -sp.degree(kv[0], omega)):
        k = sp.degree(power, omega)
        coefficient = sp.expand(coefficient)
        if k == 1:
            coefficient = sp.expand(coefficient / sp.I)
            pieces.append(r"j\omega(" + tex(coefficient) + ")")
        elif k == 2:
            pieces.append(r"\omega^2(" + tex(coefficient) + ")")
        else:
            pieces.append(tex(coefficient))
    return " + ".join(pieces).replace("+ - ", "- ").replace("+ -", "- ") + " = 0"


def _a_check(ctx: AuditContext) -> Finding:
    rel = ctx.relation()
    printed = canonical(sp.expand(rel.lhs - rel.rhs))
    if not isinstance(rel, sp.Eq) or printed == 0:
        return Finding(Verdict.WRONG, f"condition A is an equation (... = 0); the display reads {sp.sstr(rel)}",
                       Evidence(Method.PARSE, facts={"printed_form": sp.srepr(rel)}))
    form = ("A with gains identified by B", sp.srepr(sp.expand(printed)))
    best = None
    for cond, derived in _a_candidates():
        for sign in (1, -1):
            diff = sp.expand(printed - sign * derived)
            score = len(sp.Add.make_args(diff)) if diff != 0 else 0
            if best is None or score < best[0]:
                best = (score, cond, sign, diff, sign * derived)
    score, cond, sign, diff, target = best
    triple = [i + 1 for i in cond.indices]
    if score == 0:
        return Finding(Verdict.CONFIRMED,
                       f"equals {'minus ' if sign < 0 else ''}condition A for (i, j, k) = {tuple(triple)} reduced by B "
                       "(z_jk z_ki = z_kj z_ik) at s = j omega, with gains identified by B (k_yx = k_xy)",
                       Evidence(Method.CANONICAL_FORM, facts={"triple": triple, "printed_form": ("A", tuple(triple), sign)}),
                       derived=sp.Eq(target, 0))
    printed_only = [t for t in sp.Add.make_args(sp.expand(printed)) if t not in sp.Add.make_args(target)]
    derived_only = [t for t in sp.Add.make_args(target) if t not in sp.Add.make_args(sp.expand(printed))]
    point = {sym: sp.Integer(k + 2) for k, sym in enumerate(sorted(printed.free_symbols | target.free_symbols, key=str)) if sym != omega}
    point[omega] = sp.Integer(1)
    return Finding(Verdict.TYPO,
                   f"closest to condition A for (i, j, k) = {tuple(triple)} (reduced by B), which it matches except for "
                   f"{len(printed_only)} printed terms {[sp.sstr(t) for t in printed_only]} where the derivation has "
                   f"{[sp.sstr(t) for t in derived_only]} (an index slip, e.g. k_psyx for k_psyy)",
                   Evidence(Method.COUNTEREXAMPLE, witness={str(k): v for k, v in point.items()},
                            facts={"printed_value": sp.expand(printed.subs(point)), "derived_value": sp.expand(target.subs(point)),
                                   "triple": triple, "printed_form": form}),
                   derived=sp.Eq(target, 0), corrected=_omega_form(target))


for _id in ("32", "33", "34", "35", "36", "37"):
    PAPER.equation(_id, kind="condition", printed=PRINTED[_id], section="5.1", assumptions=ASSUME_CASE,
                   derivation="condition A (cross-port triples, reduced by B) at s = j omega, gains identified by B")(_a_check)


@PAPER.equation("37-count", kind="claim", after="37", section="5.1",
                printed="the symmetrization conditions of A and B boils down to the following 12 conditions",
                derivation="all conditions A and B of the symbolic case study vs the 12 printed ones")
def twelve_conditions(ctx: AuditContext) -> Finding:
    conds = derived_conditions()
    b = [c for c in conds if c.kind == "B"]
    cross = [c for c in conds if c.kind == "A" and len({i // 3 for i in c.indices}) == 2]
    within = [c for c in conds if c.kind == "A" and len({i // 3 for i in c.indices}) == 1]
    within_vanish = all(canonical(c.expr) == 0 for c in within)
    # under B each cross condition equates the ratios C_m,ab / C_s,ab of two gain pairs; the edges
    # of the six printed ones come from the conditions (32)-(37) match (best match, see _a_check)
    edges = []
    for eq_id in ("32", "33", "34", "35", "36", "37"):
        rel = parse_printed(PAPER.get(eq_id).printed, TABLE).relations()[0].as_sympy()
        printed = canonical(sp.expand(rel.lhs - rel.rhs))
        best = min(((len(sp.Add.make_args(sp.expand(printed - sg * d))), d) for _, d in _a_candidates() for sg in (1, -1)),
                   key=lambda item: item[0])[1]
        pairs = sorted({str(x)[-2:] for x in best.free_symbols if str(x).startswith("k_")})
        edges.append(tuple(pairs))
    nodes = {"xx", "yy", "zz", "xy", "xz", "yz"}
    reached, frontier = {"xx"}, ["xx"]
    while frontier:
        a = frontier.pop()
        for edge in edges:
            if len(edge) == 2 and a in edge:
                other = edge[1] if edge[0] == a else edge[0]
                if other not in reached:
                    reached.add(other)
                    frontier.append(other)
    if len(b) == 6 and len(cross) == 18 and within_vanish and reached == nodes:
        return Finding(Verdict.CONFIRMED,
                       "A and B give 6 B-conditions and 18 cross-port A-conditions (the 2 within-port triples vanish under B); "
                       "under B the 18 say that C_m,ab / C_s,ab is one function for all six gain pairs, and the six printed "
                       "(32)-(37) already chain the six pairs together: the 12 conditions are equivalent to A and B "
                       "(for nonzero couplings)",
                       Evidence(Method.STRUCTURAL, facts={"B": len(b), "A_cross": len(cross), "A_within_vanish_under_B": within_vanish,
                                                          "ratio_links_32_37": edges}))
    return Finding(Verdict.WRONG, "the printed 12 conditions do not span A and B", Evidence(Method.STRUCTURAL))


# ---------------------------------------------------------------------------------------------
# (38)-(40): solution of the conditions and residues
# ---------------------------------------------------------------------------------------------


def _symmetry_equalities() -> set[frozenset]:
    out = set()
    for c in derived_conditions():
        if c.kind == "B":
            for coefficient in c.coefficients():
                syms = sorted(coefficient.free_symbols, key=str)
                out.add(frozenset(syms))
    return out


def _equality_pair(rel: sp.Basic) -> frozenset | None:
    """``k_a = k_b`` as the pair {k_a, k_b}; None when the relation is not such an equality
    (another relation, coefficients, more or fewer gains)."""
    if not isinstance(rel, sp.Eq):
        return None
    difference = sp.expand(rel.lhs - rel.rhs)
    terms = sp.Add.make_args(difference)
    if len(terms) != 2 or not all(t.free_symbols and len(t.free_symbols) == 1 for t in terms):
        return None
    coefficients = sorted(t.as_coeff_Mul()[0] for t in terms)
    if coefficients != [-1, 1] or not all(isinstance(t.as_coeff_Mul()[1], sp.Symbol) for t in terms):
        return None
    return frozenset(t.as_coeff_Mul()[1] for t in terms)


def _38ab_check(ctx: AuditContext) -> Finding:
    relations = [r.as_sympy() for r in ctx.statement.relations()]
    pairs = [_equality_pair(r) for r in relations]
    which = "m" if ctx.equation.id == "38a" else "s"
    derived = {e for e in _symmetry_equalities() if any(str(x).startswith(f"k_p{which}") or str(x).startswith(f"k_v{which}") for x in e)}
    not_equalities = [sp.sstr(r) for r, p in zip(relations, pairs) if p is None]
    if not_equalities:
        return Finding(Verdict.WRONG, f"{not_equalities} are not equalities of two gains (B requires k_ab = k_ba)",
                       Evidence(Method.PARSE, facts={"printed_form": [sp.srepr(r) for r in relations]}))
    printed = pairs
    wrong = [p for p in printed if p not in derived]
    missing = sorted((d for d in derived if d not in printed), key=lambda e: sorted(map(str, e)))   # a set: fixed order
    if wrong:
        return Finding(Verdict.WRONG, f"printed equalities not implied by B: {[' = '.join(sorted(map(str, w))) for w in wrong]}",
                       Evidence(Method.CANONICAL_FORM, facts={"printed_form": sorted(sorted(map(str, p)) for p in printed)}))
    if not missing:
        return Finding(Verdict.CONFIRMED, "all symmetry equalities listed", Evidence(Method.CANONICAL_FORM))
    first = sorted(missing, key=lambda e: sorted(map(str, e)))[0]
    a, b = sorted(first, key=str)
    # witness: the printed equalities hold, the missing one fails
    witness = {x: sp.Integer(1) for x in a.free_symbols | b.free_symbols}
    witness[b] = sp.Integer(2)
    corrected = ", \\quad ".join(f"{NAMES[x]} = {NAMES[y]}" for x, y in sorted((tuple(sorted(e, key=str)) for e in derived), key=str))
    return Finding(Verdict.TYPO,
                   f"lists {len(printed)} of the {len(derived)} symmetry equalities that B requires for all w "
                   f"(each of (26)-(31) needs both k_p and k_v symmetric); missing: "
                   f"{[' = '.join(sorted(map(str, e))) for e in missing]}; with only the printed ones, {a} = 1, {b} = 2 violates B",
                   Evidence(Method.COUNTEREXAMPLE, witness={str(k): v for k, v in witness.items()},
                            facts={"missing": [sorted(map(str, e)) for e in missing],
                                   "printed_form": sorted(sorted(map(str, p)) for p in printed)}),
                   corrected=corrected)


for _id in ("38a", "38b"):
    PAPER.equation(_id, kind="condition", printed=PRINTED[_id], section="5.1",
                   derivation="coefficients of (26)-(31) in w")(_38ab_check)


def _ratio_chain_substitution() -> dict:
    """(38) repaired: symmetric gains and K_pm = rho K_ps, K_vm = rho K_vs."""
    subs = {}
    for kind in ("p", "v"):
        for i in range(3):
            for j in range(3):
                a, b = AXES[min(i, j)], AXES[max(i, j)]
                subs[gain(kind + "s", AXES[i], AXES[j])] = gain(kind + "s", a, b)
                subs[gain(kind + "m", AXES[i], AXES[j])] = rho * gain(kind + "s", a, b)
    return subs


CORRECTED_38C = (r"\frac{k_{vmxx}}{k_{vsxx}} = \frac{k_{vmxy}}{k_{vsxy}} = \frac{k_{vmxz}}{k_{vsxz}} = \frac{k_{vmyy}}{k_{vsyy}}"
                 r" = \frac{k_{vmyz}}{k_{vsyz}} = \frac{k_{vmzz}}{k_{vszz}} = \frac{k_{pmxx}}{k_{psxx}} = \frac{k_{pmxy}}{k_{psxy}}"
                 r" = \frac{k_{pmxz}}{k_{psxz}} = \frac{k_{pmyy}}{k_{psyy}} = \frac{k_{pmyz}}{k_{psyz}} = \frac{k_{pmzz}}{k_{pszz}}")


@PAPER.equation("38c", kind="condition", printed=PRINTED["38c"], section="5.1",
                derivation="literal reading vs Table 1; repaired ratio chain substituted into all 24 conditions")
def eq38c(ctx: AuditContext) -> Finding:
    terms = ctx.statement.relations()[0].terms
    values = {}
    for kind, M in table1_gains(60).items():
        for i in range(3):
            for j in range(3):
                values[gain(kind, AXES[i], AXES[j])] = M[i, j]
    literal = [sp.nsimplify(t.subs(values)) for t in terms]
    subs = _ratio_chain_substitution()
    vanish = all(sp.expand(c.expr.xreplace(subs)) == 0 for c in derived_conditions())
    mismatched = []
    for t in terms:
        num, den = sp.fraction(sp.together(t))
        if den != 1 and not (str(num)[-2:] == str(den)[-2:] and str(num).startswith("k_pm") and str(den).startswith("k_ps")):
            mismatched.append(f"{sp.sstr(num)}/{sp.sstr(den)}")
    reading = " = ".join(sp.sstr(t) for t in terms)
    facts = {"literal_at_table1": literal, "repaired_chain_solves_all": vanish, "printed_form": sp.srepr(tuple(terms)),
             "mismatched_ratios": mismatched}
    if len(set(literal)) > 1 and vanish:
        return Finding(Verdict.TYPO,
                       f"garbled: read literally it is the chain {reading}, which equates the velocity gains to each other and "
                       f"to the position-gain ratios (Table 1 gives {literal}); ratios whose indices do not match: {mismatched}; "
                       "the intended chain, as in (46), is equal ratios k_vm/k_vs = k_pm/k_ps for all six gain pairs, which "
                       "makes all 24 conditions A and B vanish identically",
                       Evidence(Method.CANONICAL_FORM, facts=facts), corrected=CORRECTED_38C)
    return Finding(Verdict.UNDECIDED, "literal and repaired readings not separated", Evidence(Method.INSTANCES))


@PAPER.equation("38-sufficient", kind="claim", after="38c", section="5.1",
                printed="Conditions (26)-(37) will be fulfilled for all frequencies \\omega if the gains of the PD controllers (24) satisfy (38)",
                derivation="repaired (38) substituted into all conditions; a solution outside (38)")
def sufficient_38(ctx: AuditContext) -> Finding:
    subs = _ratio_chain_substitution()
    vanish = all(sp.expand(c.expr.xreplace(subs)) == 0 for c in derived_conditions())
    L = _sym3(2, 3, 4, 1, 1, 1)
    other = {}
    for kind, factor in (("pm", 1), ("vm", 2), ("ps", 3), ("vs", 4)):
        for i in range(3):
            for j in range(3):
                other[gain(kind, AXES[i], AXES[j])] = factor * L[i, j]
    other_vanish = all(sp.expand(c.expr.xreplace(other)) == 0 for c in derived_conditions())
    if vanish and other_vanish:
        return Finding(Verdict.CONSERVATIVE,
                       "with (38) repaired (symmetric gains, one ratio rho = k_vm/k_vs = k_pm/k_ps) every condition vanishes "
                       "identically in s; not necessary: K_pm = L, K_vm = 2L, K_ps = 3L, K_vs = 4L (L symmetric) also solves "
                       "all of them while k_vm/k_vs = 1/2 != k_pm/k_ps = 1/3 (then z_ij z_ji is not a square and Z' is irrational)",
                       Evidence(Method.COUNTEREXAMPLE, witness={"L": L, "K_pm": "L", "K_vm": "2L", "K_ps": "3L", "K_vs": "4L"},
                                facts={"repaired_38_solves": vanish}))
    return Finding(Verdict.WRONG, "the repaired (38) does not solve the conditions", Evidence(Method.CANONICAL_FORM))


@PAPER.equation("38-poles", kind="claim", after="38c", section="5.1",
                printed="under (38), all the elements of the impedance matrix (25) have only a simple pole on the imaginary axis, "
                        "thus satisfying Condition C",
                derivation="poles of the entries (k_p + k_v s + m s^2)/s; Table 1 instance")
def poles_38(ctx: AuditContext) -> Finding:
    from hapticproof.exact.rationalmatrix import pole_report

    report = pole_report(RationalMatrix.from_sympy(table1_impedance(60)))
    labels = [p.label() for p, m in report.axis if m == 1]
    if not report.rhp and labels == ["s = 0"]:
        return Finding(Verdict.CONFIRMED,
                       "each entry is (k_p + k_v s + m s^2)/s: a simple pole at s = 0 and no RHP pole (C holds); the masses add a "
                       "simple pole at infinity, outside Definition 3's proper matrices, whose residue diag(M_m, M_s) must be PSD",
                       Evidence(Method.ROOT_ISOLATION, facts={"axis_poles": labels, "pole_at_infinity_order": report.improper}))
    return Finding(Verdict.WRONG, "unexpected poles", Evidence(Method.ROOT_ISOLATION))


def _residue_relations(ctx: AuditContext) -> list:
    return [r.as_sympy() for r in ctx.statement.relations()]


def _as_master(expr: sp.Expr) -> sp.Expr:
    """Express slave gains through master gains under (38): k_s = k_m / rho."""
    subs = {}
    for kind in ("p", "v"):
        for i in range(3):
            for j in range(3):
                a, b = AXES[min(i, j)], AXES[max(i, j)]
                subs[gain(kind + "s", AXES[i], AXES[j])] = gain(kind + "m", a, b) / rho
    return canonical(sp.sympify(expr).xreplace(subs))


@lru_cache(maxsize=2)
def _low_order_minors(which: str) -> dict:
    """Principal minors of order <= 3 of the residue (``'residue'``) or real part (``'real'``) of Z'."""
    R = residue_zprime() if which == "residue" else real_part_zprime()
    D = sp.diag(1, 1, 1, sp.sqrt(rho), sp.sqrt(rho), sp.sqrt(rho))
    P = (D * R * D).applyfunc(sp.simplify)       # polynomial entries; minors scale by rho^(#slave rows)
    out = {}
    for k in range(1, 4):
        for S in itertools.combinations(range(6), k):
            slave = sum(i >= 3 for i in S)
            out[S] = sp.factor(P.extract(list(S), list(S)).det(method="bareiss") / rho**slave)
    return out


#: The principal minors (0-based rows of the 6x6 residue or real part of Z') each display lists.
EXPECTED_MINORS = {"39a": [(0,), (1,), (2,)], "39b": [(3,), (4,), (5,)], "39c": [(0, 1)], "39d": [(0, 1, 2)],
                   "41a": [(0,), (1,), (2,)], "41b": [(3,), (4,), (5,)], "42": [(0, 1)], "43": [(0, 1, 2)]}


def _minor_of(expr: sp.Expr, minors: dict) -> tuple[tuple[int, ...] | None, sp.Expr | None]:
    """The principal minor a printed expression is, up to a positive factor (exact match first)."""
    best = None
    for S, m in minors.items():
        if m == 0:
            continue
        ratio = sp.cancel(expr / m)
        if ratio == 1:
            return S, ratio
        if best is None and ratio.free_symbols <= {rho} and ratio.is_positive:
            best = (S, ratio)
    return best if best is not None else (None, None)


def _minor_check(ctx: AuditContext, which: str, what: str) -> Finding:
    """Each printed relation must say 'a principal minor >= 0' (up to a positive factor), and
    together they must be the minors the display stands for (:data:`EXPECTED_MINORS`)."""
    from hapticproof.audit.compare import as_sign_condition

    minors = _low_order_minors(which)
    unmatched, matched, reversed_ = [], [], []
    for rel in _residue_relations(ctx):
        condition = as_sign_condition(rel)
        S, _ = _minor_of(_as_master(condition.expr), minors)
        if S is None:
            S_neg, _ = _minor_of(-_as_master(condition.expr), minors)
            if S_neg is not None:
                reversed_.append(sp.sstr(rel))
                continue
        if condition.op not in (">=", ">"):
            reversed_.append(sp.sstr(rel))
            continue
        (matched if S is not None else unmatched).append((sp.sstr(rel), S))
    expected = EXPECTED_MINORS.get(ctx.equation.id)
    listed = sorted(S for _, S in matched)
    form = ("minors", tuple(listed), tuple(u for u, _ in unmatched), tuple(reversed_))
    if reversed_:
        return Finding(Verdict.WRONG, f"{reversed_} bound a principal minor of the {what} from above: a principal minor of a PSD "
                       "matrix is >= 0", Evidence(Method.COUNTEREXAMPLE, facts={"printed_form": form}))
    missing = [[i + 1 for i in S] for S in (expected or []) if S not in listed]
    if unmatched:
        why = ("the printed k_psyx is the xy gain; the yy gain k_psyy belongs here" if ctx.equation.id == "39b"
               else f"it is not of the form (principal minor) >= 0")
        return Finding(Verdict.TYPO,
                       f"{[u for u, _ in unmatched]} is not a principal minor of the {what} ({why}); the others are the "
                       f"minors {[[i + 1 for i in S] for S in listed]} (of {[[i + 1 for i in S] for S in expected or []]}; "
                       f"missing {missing})",
                       Evidence(Method.CANONICAL_FORM, facts={"matched": matched, "printed_form": form}),
                       corrected=_corrected_39b() if ctx.equation.id == "39b" else None)
    if expected is not None and listed != sorted(expected):
        return Finding(Verdict.TYPO, f"the display lists the principal minors {[[i + 1 for i in S] for S in listed]} of the {what}; "
                       f"it stands for {[[i + 1 for i in S] for S in expected]} (missing {missing})",
                       Evidence(Method.CANONICAL_FORM, facts={"printed_form": form}))
    return Finding(Verdict.CONFIRMED,
                   f"each is a principal minor of the {what} under (38) ({[[i + 1 for i in S] for _, S in matched]}); "
                   "necessary conditions -- sufficiency needs all principal minors (see the claims after them)",
                   Evidence(Method.CANONICAL_FORM, facts={"minors": [[i + 1 for i in S] for _, S in matched], "printed_form": form}))


def _corrected_39b() -> str:
    return r"k_{psxx} \geq 0, \quad k_{psyy} \geq 0, \quad k_{pszz} \geq 0"


for _id in ("39a", "39b", "39c", "39d"):
    def _check(ctx: AuditContext) -> Finding:
        return _minor_check(ctx, "residue", "residue matrix of Z' at s = 0")
    PAPER.equation(_id, kind="condition", printed=PRINTED[_id], section="5.1", assumptions=ASSUME_CASE,
                   derivation="principal minors of the residue of Z' at s = 0 under (38)")(_check)


@PAPER.equation("39-D", kind="claim", after="39d", section="5.1",
                printed="Analysis of the residues according to Condition D leads to the following constraints: (39)",
                derivation="the residue of Z' at 0 is u u^T (x) K_pm: PSD iff K_pm is; a K_pm meeting (39) that is not PSD")
def residues_39(ctx: AuditContext) -> Finding:
    R = residue_zprime()
    Kpm = gain_matrix("pm", True)
    u = sp.Matrix([1, -1 / sp.sqrt(rho)])
    structure = (R - sp.kronecker_product(u * u.T, Kpm)).applyfunc(sp.simplify) == sp.zeros(6, 6)
    bad = {gain("pm", a, b): v for (a, b), v in zip(("xx", "yy", "zz", "xy", "xz", "yz"), (0, 1, 1, 0, 0, 2))}
    point = {**bad, rho: sp.Integer(1)}
    statements = [PAPER.get(k).printed for k in ("39a", "39b", "39c", "39d")]
    holds = []
    for text in statements:
        for rel in parse_printed(text, TABLE).relations():
            value = rel.as_sympy()
            value = value.func(_as_master(value.lhs), _as_master(value.rhs)).subs(point)
            holds.append(bool(value) if value in (sp.true, sp.false) else False)
    psd, negative = matrix_psd(R.subs(point))
    Kbad = sp.Matrix(3, 3, lambda i, j: gain("pm", AXES[min(i, j)], AXES[max(i, j)])).subs(bad)
    failing = {f"{AXES[i]}{AXES[j]}": Kbad.extract([i, j], [i, j]).det() for i in range(3) for j in range(i + 1, 3)
               if Kbad.extract([i, j], [i, j]).det() < 0}
    if structure and all(holds) and not psd:
        return Finding(
            Verdict.WRONG,
            "under (38) the residue of Z' at s = 0 is u u^T (x) K_pm with u = (1, -1/sqrt(rho)), PSD iff K_pm is PSD, i.e. all "
            f"seven principal minors of K_pm >= 0; the printed (39a)-(39d) all hold at K_pm = {_line(Kbad)}, whose 2x2 "
            f"principal minor(s) {failing} are negative (D as printed, leading minors of the 6x6 residue > 0, can never "
            "hold: the residue has rank <= 3)",
            Evidence(Method.COUNTEREXAMPLE, witness={"K_pm": Kbad, "rho": 1},
                     facts={"negative_minors": negative}),
            corrected=r"\mathbf{K}_{pm} \succeq 0:\ \text{all principal minors of } \mathbf{K}_{pm} \geq 0",
        )
    return Finding(Verdict.UNDECIDED, f"the printed (39) {'fails' if not all(holds) else 'holds'} at the witness K_pm = "
                   f"{_line(Kbad)} (non-PSD); residue structure {'established' if structure else 'not established'}",
                   Evidence(Method.CANONICAL_FORM, facts={"holds": holds}))


@PAPER.equation("40", kind="condition", printed=PRINTED["40"], section="5.1", derivation="restates (39c)", quotes=('39c',))
def eq40(ctx: AuditContext) -> Finding:
    from hapticproof.audit.compare import compare_sign_conditions

    rel = ctx.relation()
    (other,) = [r.as_sympy() for r in parse_printed(PAPER.get("39c").printed, TABLE).relations()]
    cmp = compare_sign_conditions(rel.func(_as_master(rel.lhs), _as_master(rel.rhs), evaluate=False),
                                  other.func(_as_master(other.lhs), _as_master(other.rhs), evaluate=False), what="(40)")
    if cmp.verdict == Verdict.CONFIRMED:
        return Finding(Verdict.CONFIRMED, "the same inequality as (39c) (2x2 leading minor of K_pm)",
                       Evidence(Method.CANONICAL_FORM, facts={"printed_form": "same as (39c)"}))
    return Finding(Verdict.TYPO, f"differs from (39c): {cmp.detail}", Evidence(cmp.evidence.method, witness=cmp.evidence.witness,
                                                                              facts={"ids": ["40", "39c"]}))


@PAPER.equation("40-claim", kind="claim", after="40", section="5.1",
                printed="the condition set (39) holds if (40) and condition (39d) hold",
                derivation="(39a), (39b) follow from nonnegative gains (stated with (46)); without them they do not")
def claim_40(ctx: AuditContext) -> Finding:
    import random

    printed = {k: [r.as_sympy() for r in parse_printed(PAPER.get(k).printed, TABLE).relations()]
               for k in ("39a", "39b", "39c", "39d", "40")}

    def all_hold(conditions: list, values: dict) -> bool:
        return all(c.subs(values) is sp.true for c in conditions)

    # with the paper's nonnegative gains: (40) and (39d) must imply all of (39)
    rng = random.Random(40)
    names = sorted({x for conds in printed.values() for c in conds for x in c.free_symbols}, key=str)
    counter = None
    for _ in range(300):
        values = {x: sp.Rational(rng.randint(0, 12), rng.randint(1, 3)) for x in names}
        if all_hold(printed["40"] + printed["39d"], values) and not all_hold(
                [c for k in ("39a", "39b", "39c", "39d") for c in printed[k]], values):
            counter = values
            break
    facts = {"ids": ["40", "39a", "39b", "39c", "39d"]}
    if counter is not None:
        failing = [k for k in ("39a", "39b", "39c", "39d") if not all_hold(printed[k], counter)]
        return Finding(Verdict.WRONG, f"with nonnegative gains (40) and (39d) hold at the witness while {failing} fail",
                       Evidence(Method.COUNTEREXAMPLE, witness={str(k): v for k, v in counter.items()}, facts=facts))
    point = {gain("pm", "x", "x"): -1, gain("pm", "y", "y"): -1, gain("pm", "z", "z"): 1,
             gain("pm", "x", "y"): 0, gain("pm", "x", "z"): 0, gain("pm", "y", "z"): 0}
    without = all_hold(printed["40"] + printed["39d"], point) and not all_hold(printed["39a"], point)
    return Finding(Verdict.CONFIRMED,
                   "true because the paper takes all gains nonnegative (stated with (46)): then (39a), (39b) hold and (39) "
                   "reduces to (40) and (39d) (no counterexample among 300 exact nonnegative gain sets)"
                   + ("; without that assumption K_pm = diag(-1, -1, 1) meets (40), (39d) but not (39a)" if without else ""),
                   Evidence(Method.INSTANCES, instances=300, facts=facts))


TABLE1_PRINTED = (
    "Master k_{pmxx} 40 k_{pmyy} 40 k_{pmzz} 25 | k_{vmxx} 80 k_{vmyy} 80 k_{vmzz} 50 | k_{pmxy} 4 k_{pmxz} 3 k_{pmyz} 30 | "
    "k_{vmyx} 8 k_{vmxz} 6 k_{vmyz} 60 (6) || Slave k_{psxx} 80 k_{psyx} 80 k_{pszz} 50 | k_{vsxx} 160 k_{vsyy} 160 "
    "k_{vszz} 100 | k_{psxy} 8 k_{psxz} 6 k_{psyx} 60 | k_{vsxy} 16 k_{vsxz} 12 k_{vsyz} 120"
)


#: Table 1's layout: the twelve gains of each robot in printed order (the slave's are named alike).
TABLE1_LAYOUT = ("pxx", "pyy", "pzz", "vxx", "vyy", "vzz", "pxy", "pxz", "pyz", "vxy", "vxz", "vyz")


@PAPER.equation("table1", kind="claim", after="40", section="5.1", printed=TABLE1_PRINTED,
                derivation="literal names vs the ratio structure (38) of the values")
def table1(ctx: AuditContext) -> Finding:
    import re

    text = ctx.equation.printed
    master, _, slave = text.partition("||")
    read = {}
    clashes: dict[str, list[str]] = {}
    misplaced: list[tuple[str, str]] = []
    for robot, part in (("m", master), ("s", slave)):
        entries = re.findall(r"k_\{(\w+)\} (\d+)", part)
        if len(entries) != len(TABLE1_LAYOUT):
            return Finding(Verdict.MALFORMED, f"the {'master' if robot == 'm' else 'slave'} column lists {len(entries)} gains, "
                           f"not {len(TABLE1_LAYOUT)}", Evidence(Method.PARSE, facts={"entries": entries}))
        for (name, value), place in zip(entries, TABLE1_LAYOUT):
            expected = place[0] + robot + place[1:]
            symmetric = place[0] + robot + place[2] + place[1]
            read[expected] = sp.Integer(value)
            if name not in (expected, symmetric):
                clashes.setdefault(name, []).append(f"{value} at the {expected} place")
                misplaced.append((expected, value))
    ratios = {read[place[0] + "m" + place[1:]] / read[place[0] + "s" + place[1:]] for place in TABLE1_LAYOUT}
    facts = {"gains": {k: str(v) for k, v in read.items()}, "ratios": sorted(ratios), "misnamed": clashes}
    corrected = r",\quad ".join(f"k_{{{name}}} = {value}" for name, value in misplaced)
    one_ratio = len(ratios) == 1
    rho = next(iter(ratios)) if one_ratio else None
    if not one_ratio:
        return Finding(Verdict.INCONSISTENT,
                       f"master/slave gain ratios {sorted(map(str, ratios))} are not one ratio rho, as (38) requires"
                       + (f"; misnamed entries {sorted(clashes)}" if clashes else ""),
                       Evidence(Method.STRUCTURAL, witness={"ratios": sorted(map(str, ratios))}, facts=facts))
    if clashes:
        return Finding(Verdict.TYPO,
                       f"the table names entries at other places' names: {clashes}; read by their places, every master gain is "
                       f"{sp.sstr(rho)} times the slave gain (one ratio rho = {sp.sstr(rho)}, as (38) requires)",
                       Evidence(Method.STRUCTURAL, witness={"clashes": clashes}, facts=facts),
                       corrected=corrected.replace(", ", r",\quad "))
    return Finding(Verdict.CONFIRMED, f"names in their places and one master/slave ratio rho = {sp.sstr(rho)}, as (38) requires",
                   Evidence(Method.STRUCTURAL, facts=facts))


# ---------------------------------------------------------------------------------------------
# (41)-(46): condition E for the case study
# ---------------------------------------------------------------------------------------------


for _id in ("41a", "41b", "42", "43"):
    def _check(ctx: AuditContext) -> Finding:
        return _minor_check(ctx, "real", "real part of Z'(j omega)")
    PAPER.equation(_id, kind="condition", printed=PRINTED[_id], section="5.1", assumptions=ASSUME_CASE,
                   derivation="principal minors of Re Z'(j omega) under (38)")(_check)


@PAPER.equation("44", kind="condition", printed=PRINTED["44"], section="5.1", assumptions=ASSUME_CASE,
                derivation="the 4th leading principal minor of Re Z'(j omega) under (38)")
def eq44(ctx: AuditContext) -> Finding:
    from hapticproof.audit.compare import as_sign_condition

    rel = ctx.relation()
    capital = TABLE.lookup("K_{vmxx}")
    condition = as_sign_condition(rel)
    printed = _as_master(condition.expr.subs(capital, gain("vm", "x", "x")))
    fourth = real_part_leading_minors()[3]
    R = real_part_zprime()
    Kvm = gain_matrix("vm", True)
    u = sp.Matrix([1, -1 / sp.sqrt(rho)])
    structure = (R - sp.kronecker_product(u * u.T, Kvm)).applyfunc(sp.simplify) == sp.zeros(6, 6)
    values = {gain("vm", AXES[i], AXES[j]): table1_gains(60)["vm"][i, j] for i in range(3) for j in range(i, 3)}
    values[rho] = sp.Rational(1, 2)
    at_table = sp.nsimplify(sp.simplify(printed.subs(values)))
    holds = {">": at_table > 0, ">=": at_table >= 0, "=": at_table == 0, "!=": at_table != 0}[condition.op] \
        if at_table.is_real else None
    form = (condition.op, sp.srepr(sp.expand(printed)))
    if fourth == 0 and structure and holds is not None:
        fails = ("although that teleoperator is absolutely stable, the printed condition fails there" if not holds else
                 "so it separates nothing there")
        return Finding(Verdict.WRONG,
                       "under (38) Re Z'(j omega) = u u^T (x) K_vm with u = (1, -1/sqrt(rho)) has rank <= 3, so its 4th (and 5th, "
                       "6th) leading minor is identically 0: the condition is void. The printed expression "
                       f"({condition.op} 0) is not a minor of Re Z' (it also writes K_vmxx for k_vmxx); at the Table 1 gains with "
                       f"k_vmyz = 60 it is {at_table}: {fails}",
                       Evidence(Method.CANONICAL_FORM, witness={"gains": "Table 1, k_vmyz = 60"},
                                facts={"fourth_leading_minor": fourth, "printed_at_table1": at_table, "printed_form": form}),
                       derived=sp.Ge(fourth, 0), corrected=r"\det\left(\text{Re}\,\mathcal{Z}'\right)_{4\times 4} = 0 \geq 0")
    return Finding(Verdict.UNDECIDED, "4th minor not established", Evidence(Method.CANONICAL_FORM, facts={"fourth": fourth}))


@PAPER.equation("45", kind="condition", printed=PRINTED["45"], section="5.1", assumptions=ASSUME_CASE,
                derivation="Table 1 (k_vmyz = 60) against (45) and against the exact absolute-stability verdict")
def eq45(ctx: AuditContext) -> Finding:
    rel = ctx.relation()
    values = {gain("vm", AXES[i], AXES[j]): table1_gains(60)["vm"][i, j] for i in range(3) for j in range(3)}
    at = rel.subs(values)
    holds = bool(at) if at in (sp.true, sp.false) else None
    verdict = table1_verdict(60)
    sides = (sp.nsimplify(rel.lhs.subs(values)), sp.nsimplify(rel.rhs.subs(values)))
    if holds is False and verdict.decision == Decision.PROVED:
        return Finding(Verdict.WRONG,
                       f"not a necessary condition (it only follows from the wrong (44)): Table 1 with k_vmyz = 60 violates it "
                       f"({sp.sstr(rel)} reads {sides[0]} vs {sides[1]}) yet is absolutely stable (Z' positive real, minors "
                       "verified); under (38) the exact real-part condition is K_vm PSD, which requires the opposite-looking "
                       "k_vmyy k_vmzz >= k_vmyz^2",
                       Evidence(Method.COUNTEREXAMPLE, witness={"gains": "Table 1", "k_vmyz": 60},
                                facts={"absolute_stability": verdict.reason, "printed_form": sp.srepr(canonical(rel))}),
                       corrected=r"\mathbf{K}_{vm} \succeq 0:\ \text{all principal minors of } \mathbf{K}_{vm} \geq 0")
    return Finding(Verdict.UNDECIDED, f"Table 1 does not separate (45): {sp.sstr(rel)} reads {sides[0]} vs {sides[1]} there",
                   Evidence(Method.INSTANCES, facts={"printed_form": sp.srepr(canonical(rel))}))


@PAPER.equation("45-minors56", kind="claim", after="45", section="5.1",
                printed="the fifth leading principal minor condition and the sixth leading principal minor condition, i.e., (15c) "
                        "always greater than zero",
                derivation="5th and 6th leading minors of Re Z' under (38)")
def minors56(ctx: AuditContext) -> Finding:
    minors = real_part_leading_minors()
    if minors[4] == 0 and minors[5] == 0:
        return Finding(Verdict.WRONG,
                       "both vanish identically (Re Z' has rank <= 3 under (38)): they are >= 0 but never > 0, so Property 4 "
                       "(positive leading minors) can never certify Re Z' here; PSD must be decided by all principal minors, "
                       "which reduces to K_vm PSD",
                       Evidence(Method.CANONICAL_FORM, facts={"leading_minors": list(minors)}),
                       corrected=r"\det\left(\text{Re}\,\mathcal{Z}'\right)_{5\times 5} = \det\left(\text{Re}\,\mathcal{Z}'\right) = 0")
    return Finding(Verdict.CONFIRMED, "positive", Evidence(Method.CANONICAL_FORM, facts={"leading_minors": list(minors)}))


CORRECTED_46 = (
    r"\mathbf{K}_{pm} = \mathbf{K}_{pm}^T,\ \mathbf{K}_{vm} = \mathbf{K}_{vm}^T,\ \mathbf{K}_{ps} = \mathbf{K}_{ps}^T,\ "
    r"\mathbf{K}_{vs} = \mathbf{K}_{vs}^T,\ " + CORRECTED_38C +
    r",\ \mathbf{K}_{pm} \succeq 0,\ \mathbf{K}_{vm} \succeq 0\ (\text{all principal minors} \geq 0),\ \mathbf{M}_m, \mathbf{M}_s \succeq 0"
)


def _repair_ratio(term: sp.Expr) -> tuple[sp.Expr, str | None]:
    """A ratio k_{vm ab}/k_{vs ??} (or k_{pm ab}/k_{ps ??}) of (46): a denominator whose indices are
    not those of its numerator (the OCR damage k_vsx, k_vsy, k_vsz and the slave's k_psyx at the
    yy, yz places) takes the numerator's indices; returns the term and the repair made."""
    num, den = sp.fraction(sp.together(term))
    if den == 1 or not (isinstance(num, sp.Symbol) and isinstance(den, sp.Symbol)):
        return term, None
    n, d = str(num), str(den)
    kinds = {"k_vm": "k_vs", "k_pm": "k_ps"}
    if len(n) != 6 or n[:4] not in kinds or not d.startswith(kinds[n[:4]]):
        return term, None
    if sorted(d[4:]) == sorted(n[4:]):
        return term, None
    want = gain(kinds[n[:4]][2:], n[4], n[5])
    return num / want, f"{d} -> {want}"


@dataclass(frozen=True)
class _RatioChain:
    """``a_1/b_1 = a_2/b_2 = ...`` read as proportionality: the ratios with b_i != 0 are equal and
    a_i = 0 where b_i = 0 (the gain matrices are proportional, zero entries included)."""

    terms: tuple

    def holds(self, values: dict) -> bool:
        ratios, ok = set(), True
        for t in self.terms:
            num, den = (sp.sympify(x).xreplace(values) for x in sp.fraction(sp.together(t)))
            if den == 0:
                ok = ok and num == 0
            else:
                ratios.add(sp.nsimplify(num / den))
        return ok and len(ratios) <= 1

    def __str__(self) -> str:
        return " = ".join(sp.sstr(t) for t in self.terms)


def _read_46(text: str) -> tuple[list[Any], list[str]]:
    """The printed (46) as a list of conditions (ratio chains as proportionality, damaged ratio
    denominators repaired by the index rule) and the repairs made."""
    conditions, repairs = [], []
    for rel in parse_printed(text, TABLE).relations():
        terms = []
        for t in rel.terms:
            fixed, repair = _repair_ratio(t)
            terms.append(fixed)
            if repair:
                repairs.append(repair)
        if len(terms) > 2 and set(rel.ops) == {"="} and all(sp.fraction(sp.together(t))[1] != 1 for t in terms):
            conditions.append(_RatioChain(tuple(terms)))
            continue
        for a, op, c in zip(terms, rel.ops, terms[1:]):
            conditions.append({"=": sp.Eq, ">=": sp.Ge, ">": sp.Gt, "<=": sp.Le, "<": sp.Lt, "!=": sp.Ne}[op](a, c, evaluate=False))
    return conditions, repairs


def _gain_values(g: dict[str, sp.Matrix]) -> dict[sp.Symbol, sp.Expr]:
    return {gain(kind, AXES[i], AXES[j]): M[i, j] for kind, M in g.items() for i in range(3) for j in range(3)}


def _failing(conditions: list[Any], g: dict[str, sp.Matrix]) -> list[str]:
    values = _gain_values(g)
    out = []
    for c in conditions:
        if isinstance(c, _RatioChain):
            if not c.holds(values):
                out.append(str(c))
            continue
        try:
            at = c.xreplace(values)
        except (TypeError, ZeroDivisionError):
            at = None
        if at is not sp.true:
            out.append(sp.sstr(c))
    return out


@PAPER.equation("46", kind="condition", printed=PRINTED["46"], section="5.1", assumptions=ASSUME_CASE,
                derivation="gains meeting every line of (46) whose Z' is not positive real; Table 1 against (46)")
def eq46(ctx: AuditContext) -> Finding:
    conditions, repairs = _read_46(ctx.equation.printed)
    g = compact_set_counterexample()
    at_counter = _failing(conditions, g)
    at_table = _failing(conditions, table1_gains(60))
    nonnegative = all(v >= 0 for M in g.values() for v in M)
    verdict = absolute_stability(_compact_impedance(), ports=(3, 3), search=False)
    reading = "; ".join(str(c) if isinstance(c, _RatioChain) else sp.sstr(c) for c in conditions)
    facts = {"reading": reading, "repairs": repairs, "failing_at_counterexample": at_counter,
             "failing_at_table1": at_table, "youla": verdict.reason, "printed_form": reading}
    if not at_counter and nonnegative and verdict.decision == Decision.DISPROVED:
        return Finding(
            Verdict.WRONG,
            f"not sufficient: read as {reading} (OCR repaired: {', '.join(repairs) or 'none'}), every line holds at K_pm = "
            f"{_line(g['pm'])}, K_vm = {_line(g['vm'])}, K_ps = 2K_pm, K_vs = 2K_vm (nonnegative gains), but {verdict.reason}: "
            "(46) dropped det K_pm >= 0 (39d) and both sets of non-leading minors; Table 1's stable gains violate "
            f"{at_table or 'no line'}. Exact condition: K_pm and K_vm PSD",
            Evidence(Method.COUNTEREXAMPLE, witness={k: v for k, v in g.items()}, facts=facts),
            corrected=CORRECTED_46,
        )
    return Finding(Verdict.UNDECIDED, f"read as {reading}, (46) fails at the prepared counterexample ({at_counter}); its "
                   f"sufficiency was not refuted (Table 1 violates {at_table or 'no line'})",
                   Evidence(Method.INSTANCES, facts=facts))


# ---------------------------------------------------------------------------------------------
# Section 5.2: simulation
# ---------------------------------------------------------------------------------------------

MASSES_PRINTED = ("$M_{mxx} = 1.7$, $M_{mxy} = 0.2$, $M_{myy} = 1.9$, $M_{mxz} = 0.1$, $M_{myz} = 0.3$, $M_{mzz} = 1.3$, "
                  "$M_{sxx} = 1.3$, $M_{sxy} = 0.5$, $M_{syx} = 1.6$, $M_{sxz} = 0.1$, $M_{syz} = 0.3$, and $M_{szx} = 1.5$")


@PAPER.equation("52-masses", kind="claim", after="46", section="5.2", printed=MASSES_PRINTED,
                derivation="as printed M_s lacks its yy and zz entries and is not symmetric; the repaired reading")
def masses(ctx: AuditContext) -> Finding:
    import re

    from hapticproof.audit.runner import quoted_math
    from hapticproof.audit.reader.names import SymbolTable
    from hapticproof.audit.reader.printed import parse_expression

    printed: dict[str, sp.Expr] = {}
    for quote in quoted_math(ctx.equation.printed):
        name, _, value = quote.partition("=")
        match = re.fullmatch(r"\s*M_\{(\w+)\}\s*", name)
        if match is None or not value.strip():
            return Finding(Verdict.MALFORMED, f"'{quote}' is not a mass entry M_{{..}} = value", Evidence(Method.PARSE))
        printed[match.group(1)] = parse_expression(value, SymbolTable())
    missing = sorted({"syy", "szz"} - set(printed))
    symbol = {"syy": sp.Symbol("m_syy"), "szz": sp.Symbol("m_szz")}

    def entry(which: str, a: str, b: str) -> sp.Expr:
        return printed.get(f"{which}{a}{b}", printed.get(f"{which}{b}{a}", symbol.get(f"{which}{a}{b}", sp.Symbol(f"m_{which}{a}{b}"))))

    # literal reading: each printed entry at its printed place; what is not printed stays symbolic
    literal_s = sp.Matrix(3, 3, lambda i, j: entry("s", AXES[i], AXES[j]))
    Mm = sp.Matrix(3, 3, lambda i, j: entry("m", AXES[min(i, j)], AXES[max(i, j)]))
    gains = [table1_gains(60)[k] for k in ("pm", "vm", "ps", "vs")]
    b_fails = any(c.kind == "B" for c in symmetrization_conditions(case_study_impedance(*gains, Mm, literal_s), ports=(3, 3)))
    # repaired reading: the printed yx and zx entries of M_s are its missing yy and zz entries
    repaired = dict(printed)
    if missing == ["syy", "szz"] and "syx" in printed and "szx" in printed:
        repaired["syy"], repaired["szz"] = repaired.pop("syx"), repaired.pop("szx")
    Ms = sp.Matrix(3, 3, lambda i, j: repaired.get(f"s{AXES[min(i, j)]}{AXES[max(i, j)]}", sp.Symbol("missing")))
    pd = {name: all(M[:k, :k].det() > 0 for k in (1, 2, 3)) if not M.free_symbols else False for name, M in (("M_m", Mm), ("M_s", Ms))}
    facts = {"printed": {k: str(v) for k, v in printed.items()}, "B_fails_literally": b_fails, "pd": pd,
             "printed_form": sorted((k, str(v)) for k, v in printed.items())}
    if missing and b_fails and all(pd.values()):
        return Finding(Verdict.TYPO,
                       f"{', '.join('M_' + m for m in missing)} are never given while M_syx = {printed.get('syx')} and M_szx = "
                       f"{printed.get('szx')} are: read literally M_s = {_line(literal_s)} is not symmetric, which violates "
                       f"condition B, and lacks those entries; read as M_syy = {repaired.get('syy')}, M_szz = {repaired.get('szz')} "
                       f"it is {_line(Ms)}, symmetric positive definite (and M_m = {_line(Mm)} is positive definite)",
                       Evidence(Method.STRUCTURAL, witness={"missing": missing}, facts=facts),
                       corrected=rf"M_{{syy}} = {float(repaired['syy']):g},\quad M_{{szz}} = {float(repaired['szz']):g}")
    if not all(pd.values()):
        return Finding(Verdict.WRONG, f"the printed masses do not give positive definite inertia matrices: M_m = {_line(Mm)}, "
                       f"M_s (repaired) = {_line(Ms)}", Evidence(Method.COUNTEREXAMPLE, facts=facts))
    return Finding(Verdict.CONFIRMED, f"masses consistent: M_m = {_line(Mm)}, M_s = {_line(Ms)}", Evidence(Method.STRUCTURAL, facts=facts))


@PAPER.equation("47", kind="expression", printed=PRINTED["47"], section="5.2",
                derivation="Definition 3 for the printed termination (the text calls it passive)")
def eq47(ctx: AuditContext) -> Finding:
    T = _rhs_matrix(ctx)
    bad = _not_in_s(T, "T_1 of (47)")
    if bad is not None:
        return bad
    result = positive_real(T)
    high = T.applyfunc(lambda e: sp.limit(e * s, s, sp.oo))          # the 1/s coefficient at high frequency
    symmetric = high == high.T
    facts = {**_pr_facts(result), "one_over_s_coefficient": high, "printed_form": sp.srepr(T)}
    if result.decision == Decision.DISPROVED:
        w = result.hermitian.witness or {}
        why = (f"the 1/s coefficient of T_1, {_line(high)}, is not symmetric, so at high frequency the Hermitian part is "
               "dominated by an indefinite skew term j(.)/w; exactly, " if not symmetric else "")
        at = {s: sp.I * sp.Rational(w["omega"])} if "omega" in w else None
        value = ""
        if at is not None:
            Tw = T.subs(at)
            H = (Tw + Tw.H).applyfunc(sp.nsimplify)
            smallest = min((sp.nsimplify(sp.re(H.extract(list(S), list(S)).det())), [i + 1 for i in S])
                           for k in range(1, H.rows + 1) for S in itertools.combinations(range(H.rows), k))
            value = f" (the minor on rows {smallest[1]} is {sp.sstr(smallest[0])})"
        return Finding(Verdict.WRONG,
                       f"'which are passive' is false: {why}T_1(jw) + T_1(jw)^H has a negative principal minor at "
                       f"w = {w.get('omega', w)}{value} (exact)",
                       Evidence(Method.ROOT_ISOLATION, witness=dict(w), facts=facts))
    return Finding(Verdict.CONFIRMED if result.decision == Decision.PROVED else Verdict.UNDECIDED,
                   f"T_1 of (47) is {_pr_text(result)} (1/s coefficient {_line(high)})", Evidence(Method.ROOT_ISOLATION, facts=facts))


def fig3_plot(traces: dict[int, Any]) -> Plot:
    """The Fig. 3 runs ``E_s(t)`` (every 10th sample) as evidence data for the reports."""
    series = tuple(Series(f"k_vmyz = {k}", tr.times[::10], tr.energy[::10], "line" if k == 60 else "dashed")
                   for k, tr in traces.items())
    return Plot("Fig. 3 regenerated: input energy at the master port, slave terminated by (47)", "t (s)", "E_s(t) (J)",
                series, hline=0.0)


FIG3_PRINTED_46 = ("if the control gains are selected according to (46), e.g., as listed in Table 1, with $K_{vmyz} = 60$")


def _quoted_kvmyz(text: str) -> tuple[sp.Expr | None, str]:
    """The value of k_vmyz a Fig. 3 claim quotes in its mathematics (``$K_{vmyz} = 60$``), read
    as a relation and solved; ``(None, reason)`` when it quotes no such value."""
    from hapticproof.audit.runner import quoted_math

    k = TABLE.lookup("k_{vmyz}")
    table = TABLE.with_symbols({"K_{vmyz}": k})           # the paper writes K_{vmyz} for the gain k_{vmyz}
    for q in quoted_math(text):
        for rel in parse_printed(q, table).relations():
            relation = rel.as_sympy()
            if k not in getattr(relation, "free_symbols", set()):
                continue
            solved = sp.solve(sp.Eq(rel.lhs, rel.rhs), k) if rel.ops == ("=",) else []
            if len(solved) != 1 or not solved[0].is_number:
                return None, f"the quoted {q!r} does not fix k_vmyz"
            return solved[0], ""
    return None, "the claim quotes no value of k_vmyz"


def _table1_kvmyz() -> tuple[sp.Expr, ...]:
    """The values of k_vmyz Table 1 lists (the registered table text: ``60 (6)``)."""
    import re

    match = re.search(r"k_\{vmyz\} (\d+)(?: \((\d+)\))?", PAPER.get("table1").printed)
    return tuple(sp.Integer(v) for v in match.groups() if v) if match else ()


def _fig3_value(ctx: AuditContext, which: int) -> tuple[sp.Expr | None, Finding | None]:
    """The quoted k_vmyz of a Fig. 3 claim, checked against Table 1's listing (its ``which``-th value)."""
    kvmyz, reason = _quoted_kvmyz(ctx.equation.printed)
    if kvmyz is None:
        return None, Finding(Verdict.UNDECIDED, reason, Evidence(Method.PARSE))
    listed = _table1_kvmyz()
    if len(listed) <= which or listed[which] != kvmyz:
        return None, Finding(Verdict.INCONSISTENT,
                             f"the claim quotes k_vmyz = {sp.sstr(kvmyz)}, but the gains of Fig. 3 are Table 1's, which lists "
                             f"k_vmyz = {', '.join(map(str, listed)) or 'nothing'} (caption of Fig. 3: the stable case first)",
                             Evidence(Method.PARSE, witness={"quoted": str(kvmyz), "table1": [str(v) for v in listed]},
                                      facts={"ids": ["fig3", "table1"]}))
    return (int(kvmyz) if kvmyz.is_integer else kvmyz), None


@PAPER.equation("fig3-46", kind="claim", after="47", section="5.2", printed=FIG3_PRINTED_46,
                derivation="every line of (46) at the Table 1 gains", quotes=('46',))
def fig3_46(ctx: AuditContext) -> Finding:
    kvmyz, problem = _fig3_value(ctx, 0)
    if problem is not None:
        return problem
    conditions, repairs = _read_46(PAPER.get("46").printed)
    failing = _failing(conditions, table1_gains(kvmyz))
    lines = [str(c) if isinstance(c, _RatioChain) else sp.sstr(c) for c in conditions]
    holding = [line for line in lines if line not in failing]
    # the lines as read (after the index rule) are what the claim is about
    facts = {"failing": failing, "holding": holding, "k_vmyz": kvmyz, "printed_form": ("lines of (46) as read", tuple(lines))}
    if failing:
        return Finding(Verdict.INCONSISTENT,
                       f"Table 1 with k_vmyz = {kvmyz} violates line(s) {failing} of (46), so it is not 'selected according to "
                       "(46)'; it is nevertheless absolutely stable (see fig3-60): (45)/(46) are wrong, not the gains "
                       f"(the other {len(holding)} line(s) hold: {'; '.join(holding)})",
                       Evidence(Method.COUNTEREXAMPLE, witness={"k_vmyz": kvmyz}, facts=facts))
    return Finding(Verdict.CONFIRMED, f"Table 1 with k_vmyz = {kvmyz} satisfies every line of (46)",
                   Evidence(Method.INSTANCES, facts=facts))


@PAPER.equation("fig3-60", kind="claim", after="47", section="5.2",
                printed="with $K_{vmyz} = 60$, then the input energy at port 1 is non-negative at all times, indicating the "
                        "absolute stability of the bilateral teleoperator",
                derivation="Youla verdict for Table 1; positive realness of the master-port impedance with (47); simulation")
def fig3_60(ctx: AuditContext) -> Finding:
    kvmyz, problem = _fig3_value(ctx, 0)
    if problem is not None:
        return problem
    verdict = table1_verdict(kvmyz)
    zin = positive_real(master_input_impedance(kvmyz))
    trace = fig3_energy(kvmyz)
    if verdict.decision == Decision.PROVED and zin.decision == Decision.PROVED and trace.minimum >= -1e-9:
        return Finding(Verdict.CONFIRMED,
                       "absolutely stable (Z' positive real, principal and block-compatible minors verified); with the slave "
                       "terminated by (47) -- which is not passive -- the master-port impedance is still positive real, so "
                       "E_s(t) >= 0 for every input from rest; simulated (exact between samples) E_s stays >= 0 "
                       f"(min {trace.minimum:.3g} J over {trace.times[-1]:.0f} s)",
                       Evidence(Method.SIMULATION, facts={"absolute_stability": verdict.reason, "input_impedance": zin.reason,
                                                          "E_min": trace.minimum, "E_final": trace.final,
                                                          "plot": fig3_plot({60: trace})}))
    return Finding(Verdict.WRONG, f"the k_vmyz = {sp.sstr(kvmyz)} case is not shown stable: absolute stability "
                   f"{verdict.decision.value}, master-port impedance {zin.decision.value} positive real, simulated E_s min "
                   f"{trace.minimum:.3g} J", verdict.evidence)


@PAPER.equation("fig3-6", kind="claim", after="47", section="5.2",
                printed="when we change K_{vmyz} to 6, which violate (46), the input energy $E_s(t)$ will become negative at least "
                        "for a period of time, indicating potential instability of the bilateral teleoperator",
                derivation="destabilizing terminations; non-positive-real master-port impedance; simulation")
def fig3_6(ctx: AuditContext) -> Finding:
    cert = _search("k6")
    zin = positive_real(master_input_impedance(6))
    trace = fig3_energy(6)
    negative = trace.first_negative(1e-9)
    same_forces_60 = fig3_energy(60).minimum
    if cert is not None and zin.decision == Decision.DISPROVED and negative is not None and same_forces_60 >= -1e-9:
        w = zin.hermitian.witness
        return Finding(Verdict.CONFIRMED,
                       "potentially unstable: passive 3-DOF RLC terminations put zeros of det(Z + T) at "
                       f"s ~ {cert.roots[0]:.4g} (certified); with (47) at the slave the master-port impedance is not positive real "
                       f"(w = {w.get('omega', w)}), and three sine forces at w = 4 rad/s along its power-delivering direction make "
                       f"E_s negative from t ~ {negative:.3g} s (min {trace.minimum:.3g} J); the same forces give E_s >= 0 for "
                       f"k_vmyz = 60 (min {same_forces_60:.3g} J). The paper does not state its sine inputs; the sign depends on them",
                       Evidence(Method.SIMULATION, facts={"certificate": _certificate_facts(cert), "input_impedance": zin.reason,
                                                          "first_negative_time": negative, "E_min": trace.minimum,
                                                          "plot": fig3_plot({6: trace, 60: fig3_energy(60)})}))
    return Finding(Verdict.UNDECIDED, "potential instability not established", Evidence(Method.INSTANCES))
