r"""Oracle for the passivity of python-control and SymPy systems, from the definition.

A system is read here on its own (nothing from the package): every float at its exact binary value
(``fractions.Fraction(x)``), a ``StateSpace`` as ``C (xI - A)^{-1} B + D`` by SymPy's matrix inverse
(the package uses Faddeev-LeVerrier over flint), a SymPy ``TransferFunction(Matrix)`` by its
``num/den``. Then positive realness by definition:

* continuous: :func:`.continuous.positive_real_matrix` (Definition 3: poles, axis residues, the
  Hermitian part for every ``w``, at 60 digits);
* discrete SISO: :func:`.discrete.discrete_positive_real` (Definition 2);
* discrete MIMO: through the bilinear map ``z = (1 + s)/(1 - s)``, which takes ``|z| > 1`` onto
  ``Re s > 0`` and the circle onto the axis (``z = -1`` to ``s = infinity``, ``z = infinity`` to
  ``s = 1``): ``G(z)`` is positive real iff ``G((1 + s)/(1 - s))`` is, decided by the continuous
  oracle. (The scalar case is checked both ways by the tests.)
"""

from __future__ import annotations

from fractions import Fraction
from typing import Any

import sympy as sp

from .continuous import S, positive_real_matrix
from .discrete import Z, discrete_positive_real
from .result import OracleResult

__all__ = ["exact_matrix", "lti_positive_real", "bilinear_positive_real"]


def _q(x: Any) -> sp.Rational:
    if hasattr(x, "item"):
        x = x.item()
    if isinstance(x, complex):
        x = x.real
    f = Fraction(x)
    return sp.Rational(f.numerator, f.denominator)


def _poly(coeffs: Any, var: sp.Symbol) -> sp.Expr:
    values = [_q(c) for c in list(coeffs)]
    degree = len(values) - 1
    return sum((c * var ** (degree - k) for k, c in enumerate(values)), sp.Integer(0))


def exact_matrix(sys: Any) -> tuple[sp.Matrix, str]:
    """``(G, domain)`` of a python-control or SymPy system, exact (``domain``: discrete | continuous)."""
    module, name = type(sys).__module__, type(sys).__name__
    if module.startswith("sympy"):
        rows = [[sys]] if name == "TransferFunction" else [list(r) for r in sys.args[0]]
        var = rows[0][0].var
        domain = "discrete" if var.name == "z" else "continuous"
        target = Z if domain == "discrete" else S
        return sp.Matrix([[sp.cancel((tf.num / tf.den).subs(var, target)) for tf in row] for row in rows]), domain
    dt = sys.dt
    domain = "continuous" if (dt is None or dt is False or dt == 0) else "discrete"
    var = Z if domain == "discrete" else S
    if name == "TransferFunction":
        G = sp.Matrix([[sp.cancel(_poly(sys.num[i][j], var) / _poly(sys.den[i][j], var)) for j in range(sys.ninputs)]
                       for i in range(sys.noutputs)])
        return G, domain
    A, B, C, D = (sp.Matrix([[_q(v) for v in row] for row in M.tolist()]) for M in (sys.A, sys.B, sys.C, sys.D))
    n = A.rows
    if n == 0:
        return D, domain
    G = C * (var * sp.eye(n) - A).inv() * B + D
    return G.applyfunc(sp.cancel), domain


def bilinear_positive_real(G: sp.Matrix) -> OracleResult:
    """Discrete positive realness of ``G(z)`` as the continuous one of ``G((1 + s)/(1 - s))``."""
    H = G.applyfunc(lambda e: sp.cancel(e.subs(Z, (1 + S) / (1 - S))))
    return positive_real_matrix(H, S)


def lti_positive_real(sys: Any) -> OracleResult:
    """The oracle's verdict on a python-control or SymPy system (see the module docstring)."""
    G, domain = exact_matrix(sys)
    if domain == "continuous":
        return positive_real_matrix(G, S)
    if G.shape == (1, 1):
        return discrete_positive_real(G[0, 0], Z)
    return bilinear_positive_real(G)
