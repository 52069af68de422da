"""The words a scene's fields and its questions choose from, as plain tuples.

They live apart from the models that give them meaning (:mod:`~hapticproof.systems.singleuser`,
:mod:`~hapticproof.systems.discretize`, :mod:`~hapticproof.analysis.designmap`), which import them
from here, so the command line builds its parsers (``--help``, the choices of every option)
without loading SymPy.

>>> APPROXIMATIONS
('forward', 'backward', 'tustin')
>>> "tustin" in METHODS and "zoh" in METHODS
True
"""

from __future__ import annotations

__all__ = ["APPROXIMATIONS", "METHODS", "QUANTITIES"]

#: Approximations of ``X_h(z)`` from ``V_h(z)`` (HVE paper, Section 3.1.1).
APPROXIMATIONS = ("forward", "backward", "tustin")

#: Discretisation methods of continuous designs (:mod:`hapticproof.systems.discretize`).
METHODS = ("forward", "backward", "tustin", "zoh", "matched")

#: The questions a design-space map answers at each point (:mod:`hapticproof.analysis.designmap`).
QUANTITIES = ("passivity", "stability")
