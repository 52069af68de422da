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
from dataclasses import dataclass, field
from typing import Any

from .result import NO, YES, OracleResult

__all__ = ["DEFAULT_EXAMPLES", "examples", "expected_decision", "Tally", "jsonable"]

DEFAULT_EXAMPLES = 10


def examples(weight: float = 1.0) -> int:
    """Hypothesis examples for a family: ``HAPTICPROOF_DIFF_EXAMPLES`` times ``weight``."""
    raw = os.environ.get("HAPTICPROOF_DIFF_EXAMPLES", "").strip()
    n = int(raw) if raw else DEFAULT_EXAMPLES
    return max(1, int(round(n * weight)))


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
                                                            "error": 0})

    @property
    def total(self) -> int:
        return sum(self.counts.values())

    def check(self, case: dict[str, Any], decision: str | None, oracle: OracleResult, *, call: str,
              error: str | None = None, fail_undecided: bool = True) -> str:
        """Compare ``decision`` (the toolkit's) with the oracle; record; fail unless collecting.

        Statuses: ``agree``; ``disagree`` (opposite decisions); ``undecided`` (the toolkit
        answered ``undecided`` where the oracle decided: a failure unless ``fail_undecided`` is
        False); ``uncertain`` (the oracle did not decide); ``error`` (the toolkit raised).
        """
        want = expected_decision(oracle)
        if error is not None:
            status = "error"
        elif want is None:
            status = "uncertain"
        elif decision == "undecided":
            status = "undecided"
        else:
            status = "agree" if decision == want else "disagree"
        self.counts[status] += 1
        path = os.environ.get("HAPTICPROOF_DIFF_COLLECT", "").strip()
        record = {"family": self.family, "status": status, "call": call, "case": jsonable(case),
                  "toolkit": decision if error is None else f"error: {error}", "oracle": oracle.verdict,
                  "oracle_reason": oracle.reason, "margin": oracle.margin, "band": oracle.band,
                  "where": jsonable(oracle.where)}
        if path:
            with open(path, "a", encoding="utf-8") as fh:
                fh.write(json.dumps(record) + "\n")
            return status
        if status in ("disagree", "error") or (status == "undecided" and fail_undecided):
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
        return f"{self.family}: {self.total} cases, " + ", ".join(f"{k} {v}" for k, v in self.counts.items())
