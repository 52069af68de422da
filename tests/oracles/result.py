"""The verdict an oracle returns: ``yes``, ``no`` or ``uncertain``, with what it measured.

Every oracle states the band inside which it refuses to decide. A ``no`` is given only when a
measured quantity is negative beyond its numerical noise (a witness), a ``yes`` only when every
measured quantity clears the band; anything in between is ``uncertain``.

>>> r = OracleResult("no", "Re F < 0 at theta = 3.14", margin=-0.5, band=1e-20, where={"theta": 3.14})
>>> r.decided, r.verdict
(True, 'no')
>>> combine([("poles", OracleResult("yes", "ok")), ("hermitian", r)]).reason
'hermitian: Re F < 0 at theta = 3.14'
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any

YES, NO, UNCERTAIN = "yes", "no", "uncertain"
VERDICTS = (YES, NO, UNCERTAIN)


class OracleFailure(RuntimeError):
    """The numerics could not be completed (e.g. a polynomial root finder did not converge)."""


@dataclass
class OracleResult:
    """An oracle's answer.

    verdict : ``"yes" | "no" | "uncertain"``
    reason : one sentence
    margin : the decisive measured number (a minimum eigenvalue, a residue, |z| - 1, ...);
        negative means the condition fails there
    band : the half-width of the uncertainty band around 0 that was applied to ``margin``
    where : where it was measured (``theta``, ``c``, ``omega``, ``pole``...)
    details : the sub-results (one per condition) or other data (a termination...)
    """

    verdict: str
    reason: str
    margin: float | None = None
    band: float | None = None
    where: dict[str, Any] = field(default_factory=dict)
    details: dict[str, Any] = field(default_factory=dict)

    def __post_init__(self) -> None:
        if self.verdict not in VERDICTS:
            raise ValueError(f"unknown verdict {self.verdict!r}")

    @property
    def decided(self) -> bool:
        return self.verdict != UNCERTAIN

    def summary(self) -> str:
        extra = []
        if self.margin is not None:
            extra.append(f"margin={self.margin:.6g}")
        if self.band is not None:
            extra.append(f"band={self.band:.3g}")
        if self.where:
            extra.append(", ".join(f"{k}={v}" for k, v in self.where.items()))
        return f"{self.verdict}: {self.reason}" + (f" [{'; '.join(extra)}]" if extra else "")


def combine(parts: list[tuple[str, OracleResult]]) -> OracleResult:
    """All conditions must hold: the first ``no`` wins, then the first ``uncertain``."""
    details = {name: part for name, part in parts}
    for name, part in parts:
        if part.verdict == NO:
            return OracleResult(NO, f"{name}: {part.reason}", part.margin, part.band, dict(part.where), details)
    for name, part in parts:
        if part.verdict == UNCERTAIN:
            return OracleResult(UNCERTAIN, f"{name}: {part.reason}", part.margin, part.band, dict(part.where), details)
    last = parts[-1][1] if parts else OracleResult(YES, "no condition")
    return OracleResult(YES, "; ".join(f"{n}: {p.reason}" for n, p in parts), last.margin, last.band,
                        dict(last.where), details)
