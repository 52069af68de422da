"""hapticproof: regenerate, certify and audit stability conditions of sampled-data haptic systems."""

from hapticproof.errors import HapticproofError
from hapticproof.evidence import Decision, Evidence, Outcome, Verdict

__all__ = ["HapticproofError", "Decision", "Evidence", "Outcome", "Verdict"]
__version__ = "0.1.0"
