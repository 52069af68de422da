r"""Li, Tavakoli & Huang, "Absolute Stability of 3-DOF Bilateral Haptic Systems" (the 3-DOF paper,
``001_48f53b5d92944b5d.txt``).

Every printed equation is registered **verbatim** (OCR damage included) with the toolkit's
derivation, section by section in the modules of this package, onto one :data:`PAPER`.
"""

from hapticproof.derivations.bilateral_3dof.paper import PAPER
from hapticproof.derivations.bilateral_3dof import two_port  # noqa: F401  (registers its equations)
from hapticproof.derivations.bilateral_3dof import theorem9  # noqa: F401  (registers its equations)
from hapticproof.derivations.bilateral_3dof import case_study  # noqa: F401  (registers its equations)
from hapticproof.derivations.bilateral_3dof import gains  # noqa: F401  (registers its equations)

__all__ = ["PAPER"]
