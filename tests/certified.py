"""The independent checker on a decision returned to a differential test.

Every certificate inside the toolkit's result (found by walking its JSON) is re-verified by
:mod:`hapticproof.exact.checker`; a rejected one fails the test whatever the oracle said. (The oracles
under ``tests/oracles`` import nothing from the package; this helper is on the toolkit's side.)
"""

from __future__ import annotations

from typing import Any

from hapticproof.exact.checker import check_certificates
from hapticproof.core.evidence import to_jsonable


def assert_certified(result: Any, call: str = "") -> int:
    """Re-verify every certificate in ``result``; returns how many were found."""
    if result is None:
        return 0
    data = to_jsonable(result.to_json() if hasattr(result, "to_json") else result)
    results = check_certificates(data)
    rejected = [r.reason for r in results if not r.ok]
    assert not rejected, f"the checker rejected certificate(s) of {call or 'the result'}: {rejected}"
    return len(results)
