r"""Miandashti & Tavakoli, "Stability of Sampled-Data, Delayed Haptic Interaction under Passive or
Active Operator" (the HVE paper, ``000_e6b68def623c8e74.txt``).

Every printed equation is registered **verbatim** (OCR damage included) with the toolkit's
derivation of its counterpart, section by section in the modules of this package, onto one
:data:`PAPER`.
"""

from hapticproof.derivations.hve.paper import PAPER
from hapticproof.derivations.hve import single_user  # noqa: F401  (registers its equations)
from hapticproof.derivations.hve import delays  # noqa: F401  (registers its equations)
from hapticproof.derivations.hve import users_model  # noqa: F401  (registers its equations)
from hapticproof.derivations.hve import users_conditions  # noqa: F401  (registers its equations)
from hapticproof.derivations.hve import users_delays  # noqa: F401  (registers its equations)
from hapticproof.derivations.hve import intro  # noqa: F401  (registers its equations)

__all__ = ["PAPER"]
