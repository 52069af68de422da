"""The decision and verdict vocabulary, and evidence as data.

A :class:`Decision` answers "does this condition hold for this scene?"; a :class:`Verdict`
answers "is this printed equation right?" (DESIGN.md, *Decisions and verdicts*). Neither is
ever returned without :class:`Evidence`: the method used, exact witnesses and instance counts.

>>> import sympy as sp
>>> ev = Evidence("counterexample", witness={"c": sp.Rational(-1, 2), "K": sp.Integer(3)})
>>> ev.to_json()
{'method': 'counterexample', 'witness': {'c': '-1/2', 'K': '3'}}
>>> Verdict("needs-assumption") is Verdict.NEEDS_ASSUMPTION
True
"""

from __future__ import annotations

import enum
import fractions
from collections.abc import Mapping
from dataclasses import dataclass, field
from typing import Any

import sympy as sp

__all__ = ["Decision", "Verdict", "Method", "Evidence", "Outcome", "Finding", "Series", "Plot", "to_jsonable", "exact"]


class Decision(enum.StrEnum):
    """Answer to "does this condition hold for this scene?"."""

    PROVED = "proved"
    DISPROVED = "disproved"
    UNDECIDED = "undecided"
    SYMBOLIC = "symbolic"


class Verdict(enum.StrEnum):
    """Answer to "is this printed equation right?" (one per audited equation)."""

    CONFIRMED = "confirmed"
    CONSERVATIVE = "conservative"
    TYPO = "typo"
    WRONG = "wrong"
    NEEDS_ASSUMPTION = "needs-assumption"
    INCONSISTENT = "inconsistent"
    MALFORMED = "malformed"
    UNDECIDED = "undecided"


class Method(enum.StrEnum):
    """How a decision or verdict was reached."""

    CANONICAL_FORM = "canonical-form"
    ROOT_ISOLATION = "root-isolation"
    ENDPOINT_ANALYSIS = "endpoint-analysis"
    COUNTEREXAMPLE = "counterexample"
    INSTANCES = "instances"
    STRUCTURAL = "structural"
    INTERVAL_ARITHMETIC = "interval-arithmetic"
    SIMULATION = "simulation"
    SPECTRAL = "spectral"
    PARSE = "parse"


def exact(value: Any) -> sp.Expr:
    """Convert a number to an exact SymPy number (floats exactly, via their binary value).

    >>> exact(0.5), exact("1e-3"), exact(fractions.Fraction(2, 6))
    (1/2, 1/1000, 1/3)
    """
    if isinstance(value, sp.Basic):
        return value
    if isinstance(value, bool):
        raise TypeError("a boolean is not a parameter value")
    if isinstance(value, int):
        return sp.Integer(value)
    if isinstance(value, fractions.Fraction):
        return sp.Rational(value.numerator, value.denominator)
    if isinstance(value, float):
        num, den = value.as_integer_ratio()
        return sp.Rational(num, den)
    if isinstance(value, str):
        from hapticproof.core.limits import check_number_text

        text = value.strip()
        if not text.isascii():      # Fraction() reads Arabic-Indic and other digits too
            raise ValueError(f"{text!r} is not a number (write digits 0-9)")
        for part in text.split("/"):
            check_number_text(part, "number")       # 1e999999999 is never built
        return sp.Rational(fractions.Fraction(text))
    return sp.sympify(value)


def _json_number(value: sp.Basic) -> Any:
    if value.is_Rational:
        return str(value)
    if value.is_number:
        # algebraic or transcendental exact numbers: keep the exact form and a decimal
        return {"exact": sp.sstr(value), "approx": str(sp.N(value, 20))}
    return sp.sstr(value)


def to_jsonable(value: Any) -> Any:
    """Recursively convert evidence data to JSON-compatible values (exact numbers as strings).

    >>> to_jsonable({"c": sp.Rational(1, 3), "roots": (sp.Integer(1), 2.5), "ok": True})
    {'c': '1/3', 'roots': ['1', 2.5], 'ok': True}
    """
    if isinstance(value, enum.Enum):
        return value.value
    if isinstance(value, (str, bool, int, float)) or value is None:
        return value
    if isinstance(value, fractions.Fraction):
        return str(value)
    if isinstance(value, sp.MatrixBase):
        return [[to_jsonable(e) for e in row] for row in value.tolist()]
    if isinstance(value, sp.Basic):
        return _json_number(value)
    if isinstance(value, Mapping):
        return {str(k): to_jsonable(v) for k, v in value.items()}
    if isinstance(value, (list, tuple, set, frozenset)):
        items = sorted(value, key=str) if isinstance(value, (set, frozenset)) else value
        return [to_jsonable(v) for v in items]
    if hasattr(value, "to_json"):
        return value.to_json()
    return str(value)


@dataclass(frozen=True, slots=True)
class Series:
    """One curve of a :class:`Plot`: ``style`` is ``line``, ``dashed`` or ``points``."""

    label: str
    x: tuple[float, ...]
    y: tuple[float, ...]
    style: str = "line"

    def __post_init__(self) -> None:
        object.__setattr__(self, "x", tuple(float(v) for v in self.x))
        object.__setattr__(self, "y", tuple(float(v) for v in self.y))
        if len(self.x) != len(self.y):
            raise ValueError(f"series {self.label!r}: {len(self.x)} x values but {len(self.y)} y values")
        if self.style not in ("line", "dashed", "points"):
            raise ValueError(f"series style must be line, dashed or points, got {self.style!r}")

    def to_json(self) -> dict[str, Any]:
        return {"label": self.label, "x": list(self.x), "y": list(self.y), "style": self.style}


@dataclass(frozen=True, slots=True)
class Plot:
    """Figure data carried in an :class:`Evidence`'s facts (computed by the check; the HTML
    report only draws it): curves, axis labels and an optional horizontal reference line.

    >>> Plot("E_s", "t (s)", "E (J)", (Series("k = 6", (0, 1), (0, -0.5)),), hline=0).to_json()["series"][0]["y"]
    [0.0, -0.5]
    """

    title: str
    xlabel: str
    ylabel: str
    series: tuple[Series, ...]
    hline: float | None = None

    def __post_init__(self) -> None:
        object.__setattr__(self, "series", tuple(self.series))

    def to_json(self) -> dict[str, Any]:
        out = {"title": self.title, "xlabel": self.xlabel, "ylabel": self.ylabel,
               "series": [s.to_json() for s in self.series]}
        if self.hline is not None:
            out["hline"] = self.hline
        return out


@dataclass(frozen=True)
class Evidence:
    """What backs a decision or verdict.

    Parameters
    ----------
    method : str
        One of :class:`Method` (``canonical-form``, ``root-isolation``, ...).
    witness : mapping, optional
        Exact values (parameters and ``c`` or ``omega``) at which a condition fails or two
        expressions differ; re-checked by exact evaluation before it is reported.
    instances : int, optional
        Number of exact instances checked (for ``instances`` evidence).
    facts : mapping
        Further data: values of both sides at the witness, minimisers, certificates, and
        :class:`Plot` data where a finding is about a figure or a boundary.
    """

    method: str
    witness: Mapping[str, Any] | None = None
    instances: int | None = None
    facts: Mapping[str, Any] = field(default_factory=dict)

    def __post_init__(self) -> None:
        # reject unknown methods early; store the plain string
        object.__setattr__(self, "method", Method(self.method).value)

    def to_json(self) -> dict[str, Any]:
        out: dict[str, Any] = {"method": str(self.method)}
        if self.witness is not None:
            out["witness"] = to_jsonable(self.witness)
        if self.instances is not None:
            out["instances"] = self.instances
        if self.facts:
            out["facts"] = to_jsonable(self.facts)
        return out


@dataclass(frozen=True)
class Outcome:
    """A :class:`Decision` with its evidence and a one-sentence reason.

    ``minimiser`` and ``minimum`` are filled when a worst case over frequency was computed
    (``c`` where the minimum is attained and the exact or certified minimum value).
    """

    decision: Decision
    evidence: Evidence
    reason: str
    minimiser: Any = None
    minimum: Any = None

    @property
    def witness(self) -> Mapping[str, Any] | None:
        return self.evidence.witness

    def to_json(self) -> dict[str, Any]:
        out = {
            "decision": self.decision.value,
            "reason": self.reason,
            "evidence": self.evidence.to_json(),
        }
        if self.minimiser is not None:
            out["minimiser"] = to_jsonable(self.minimiser)
        if self.minimum is not None:
            out["minimum"] = to_jsonable(self.minimum)
        return out


@dataclass(frozen=True)
class Finding:
    """The audit of one printed equation: exactly one :class:`Verdict` with its evidence.

    Parameters
    ----------
    verdict : Verdict
    detail : str
        One sentence: what was compared and what was found (and any assumption made).
    evidence : Evidence
    derived : SymPy object, str or None
        The toolkit's own derivation of the printed object (SymPy, or LaTeX text).
    corrected : str or None
        Corrected LaTeX for a defective equation (``typo``, ``wrong``, ``needs-assumption``,
        ``inconsistent``, ``malformed``); ``None`` when the printed text is right.
    """

    verdict: Verdict
    detail: str
    evidence: Evidence
    derived: Any = None
    corrected: str | None = None

    def __post_init__(self) -> None:
        object.__setattr__(self, "verdict", Verdict(self.verdict))
        if not self.detail:
            raise ValueError("a finding needs a one-sentence detail")
