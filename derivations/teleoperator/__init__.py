r"""Jazayeri & Tavakoli, "A Passivity Criterion for Sampled-data Bilateral Teleoperation Systems"
(the teleoperator paper, ``002_de715dde36093cfe.txt``).

Every printed equation is registered **verbatim** (OCR damage included) with the toolkit's
derivation, section by section in the modules of this package, onto one :data:`PAPER`.
"""

from hapticproof.derivations.teleoperator.paper import PAPER
from hapticproof.derivations.teleoperator import model  # noqa: F401  (registers its equations)
from hapticproof.derivations.teleoperator import energy  # noqa: F401  (registers its equations)
from hapticproof.derivations.teleoperator import criterion  # noqa: F401  (registers its equations)
from hapticproof.derivations.teleoperator import claims  # noqa: F401  (registers its equations)

__all__ = ["PAPER"]
