"""Independent numeric oracles for the differential test suite.

They implement the papers' definitions directly with numpy, mpmath, scipy and SymPy (as a
computer-algebra system) and import nothing from the package under test (a test greps these
sources to make sure). Each returns an :class:`~.result.OracleResult`: ``yes``, ``no`` or
``uncertain`` with the measured margin, where it was measured and the band it applied.
"""

from .result import NO, UNCERTAIN, YES, OracleFailure, OracleResult

__all__ = ["YES", "NO", "UNCERTAIN", "OracleResult", "OracleFailure"]
