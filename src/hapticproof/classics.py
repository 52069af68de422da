r"""Classic sampled-data haptic conditions, derived by the toolkit from their models.

Colgate & Schenkel (J. Robotic Systems 14(1):37-47, 1997, eq. (18) and Section 4): a 1-DOF
haptic display with physical damping ``b``, sampler, ZOH and a discrete environment ``H(z)``
is passive iff

.. math:: b \ge \frac{T}{2}\,\frac{1}{1 - \cos\omega T}\,\Re\{(1 - e^{-j\omega T}) H(e^{j\omega T})\}
          \quad \forall\, \omega \in (0, \pi/T),

which for the virtual wall ``H(z) = K + B(z-1)/(Tz)`` is ``b > KT/2 + |B|``. The right-hand
side is computed here as an exact rational function of ``c = cos(wT)``: with
``1/(z - 1) = -(1 - z^{-1})/(2(1 - c))`` on the circle it equals ``-Re{H(z) T/(z-1)}``, the
environment term of the forward-difference Hermitian part of the HVE paper, which is why the
two derivations agree.

>>> import sympy as sp
>>> from hapticproof.scene import SYMBOLS, virtual_wall
>>> K, B, T = SYMBOLS["K"], SYMBOLS["B"], SYMBOLS["T"]
>>> sp.expand(colgate_bound(virtual_wall(K, B, T), T))
-B*c + K*T/2
"""

from __future__ import annotations

from typing import Any

import sympy as sp

from hapticproof.symbols import c as C_SYM
from hapticproof.symbols import z as Z_SYM
from hapticproof.unitcircle import hermitian_part

__all__ = ["colgate_bound", "COLGATE_SCHENKEL_1997"]

#: Source of Colgate's passivity condition.
COLGATE_SCHENKEL_1997 = (
    "J. E. Colgate and G. G. Schenkel, 'Passivity of a class of sampled-data systems: "
    "application to haptic interfaces', Journal of Robotic Systems 14(1):37-47, 1997"
)


def colgate_bound(H: Any, T: Any, z: sp.Symbol = Z_SYM, var: sp.Symbol = C_SYM) -> sp.Expr:
    r"""Colgate & Schenkel's lower bound on ``b`` at frequency ``c = cos(wT)``:
    ``T/(2(1 - c)) Re{(1 - z^{-1}) H(z)}`` on ``|z| = 1`` (an exact rational function of ``c``).

    >>> from hapticproof.symbols import z
    >>> colgate_bound(3 + 0*z, sp.Rational(1, 10))          # a pure spring K = 3, T = 0.1
    3/20
    """
    numerator = hermitian_part(sp.sympify(H) * (1 - 1 / z), z, var)
    return sp.cancel(sp.sympify(T) * numerator / (2 * (1 - var)))
