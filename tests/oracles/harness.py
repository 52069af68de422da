"""Bookkeeping shared by the differential tests: the size knob, agreement checks, statistics,
and the collect mode of large runs.

* ``HAPTICPROOF_DIFF_EXAMPLES`` (default 10): Hypothesis examples per family; each test scales
  it by a weight (slow families use fewer).
* ``HAPTICPROOF_DIFF_COLLECT=FILE.jsonl``: do not fail on a disagreement; append one JSON line
  per case (the exact inputs, the tested decision, the oracle's verdict, margin and band) and let
  the run go on. Used for large runs; the default is to fail on the first disagreement.

>>> expected_decision(OracleResult("yes", "ok")), expected_decision(OracleResult("uncertain", "?"))
('proved', None)
"""

from __future__ import annotations

import json
import os
import time
from dataclasses import dataclass, field
from typing import Any

from .result import NO, UNCERTAIN, YES, OracleResult

__all__ = ["DEFAULT_EXAMPLES", "examples", "expected_decision", "Tally", "jsonable", "timed"]

DEFAULT_EXAMPLES = 10


def examples(weight: float = 1.0) -> int:
    """Hypothesis examples for a family: ``HAPTICPROOF_DIFF_EXAMPLES`` times ``weight``."""
    raw = os.environ.get("HAPTICPROOF_DIFF_EXAMPLES", "").strip()
    n = int(raw) if raw else DEFAULT_EXAMPLES
    return max(1, int(round(n * weight)))


def timed(func, *args, **kwargs):
    """``(func(*args, **kwargs), CPU seconds)``; an exception is returned as ``(None, s, error)``."""
    start = time.process_time()
    try:
        return func(*args, **kwargs), time.process_time() - start, None
    except Exception as exc:  # noqa: BLE001 - the caller records it
        return None, time.process_time() - start, f"{type(exc).__name__}: {exc}"


def expected_decision(oracle: OracleResult) -> str | None:
    """The decision the oracle's verdict calls for (None when it is uncertain)."""
    return {YES: "proved", NO: "disproved"}.get(oracle.verdict)


def jsonable(value: Any) -> Any:
    if isinstance(value, dict):
        return {str(k): jsonable(v) for k, v in value.items()}
    if isinstance(value, (list, tuple)):
        return [jsonable(v) for v in value]
    if isinstance(value, (bool, int, float)) or value is None:
        return value
    return str(value)


@dataclass
class Tally:
    """Counts of one family: agreements, disagreements, uncertain oracle verdicts, errors."""

    family: str
    counts: dict[str, int] = field(default_factory=lambda: {"agree": 0, "disagree": 0, "undecided": 0, "uncertain": 0,
                                                            "error": 0, "oracle-error": 0})
    seconds: dict[str, float] = field(default_factory=lambda: {"toolkit": 0.0, "oracle": 0.0})

    @property
    def total(self) -> int:
        return sum(self.counts.values())

    def check(self, case: dict[str, Any], decision: str | None, oracle: OracleResult | None, *, call: str,
              error: str | None = None, fail_undecided: bool = True, seconds: dict[str, float] | None = None,
              oracle_error: str | None = None) -> str:
        """Compare ``decision`` (the toolkit's) with the oracle; record; fail unless collecting.

        Statuses: ``agree``; ``disagree`` (opposite decisions); ``undecided`` (the toolkit
        answered ``undecided`` where the oracle decided: a failure unless ``fail_undecided`` is
        False); ``uncertain`` (the oracle did not decide); ``error`` (the toolkit raised);
        ``oracle-error`` (the oracle raised: a bug of the test suite, reported as such).
        """
        oracle_failed = oracle is None or oracle_error is not None
        if oracle_failed:
            oracle = OracleResult(UNCERTAIN, f"the oracle raised {oracle_error}")
        want = expected_decision(oracle)
        if oracle_failed:
            status = "oracle-error"
        elif error is not None:
            status = "error"
        elif want is None:
            status = "uncertain"
        elif decision == "undecided":
            status = "undecided"
        else:
            status = "agree" if decision == want else "disagree"
        self.counts[status] += 1
        for key, value in (seconds or {}).items():
            self.seconds[key] = self.seconds.get(key, 0.0) + value
        path = os.environ.get("HAPTICPROOF_DIFF_COLLECT", "").strip()
        record = {"family": self.family, "status": status, "call": call, "case": jsonable(case),
                  "toolkit": decision if error is None else f"error: {error}", "oracle": oracle.verdict,
                  "oracle_reason": oracle.reason, "margin": oracle.margin, "band": oracle.band,
                  "where": jsonable(oracle.where), "seconds": seconds}
        if path:
            with open(path, "a", encoding="utf-8") as fh:
                fh.write(json.dumps(record) + "\n")
            return status
        if status in ("disagree", "error", "oracle-error") or (status == "undecided" and fail_undecided):
            raise AssertionError(
                f"[{self.family}] {call} returned {record['toolkit']!r}, the oracle says {oracle.verdict!r} "
                f"({oracle.summary()})\ninputs: {json.dumps(record['case'])}")
        return status

    def assert_few_uncertain(self, fraction: float = 0.25) -> None:
        """Most cases must be decided by the oracle (else the family tests little)."""
        decided = self.counts["agree"] + self.counts["disagree"] + self.counts["error"]
        assert self.counts["uncertain"] <= max(2, fraction * self.total), (
            f"[{self.family}] the oracle was uncertain in {self.counts['uncertain']} of {self.total} cases")
        assert decided >= 1 or self.total < 3

    def __str__(self) -> str:
        return (f"{self.family}: {self.total} cases, " + ", ".join(f"{k} {v}" for k, v in self.counts.items())
                + " (CPU s: " + ", ".join(f"{k} {v:.1f}" for k, v in self.seconds.items()) + ")")
