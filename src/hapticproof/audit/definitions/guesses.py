r"""What a paper's definitions reading says each display claims, for the draft of ``new-paper --from``.

:func:`read_claims` reads a source's displays in order with :class:`~hapticproof.audit.definitions.reading.PaperReading`
(the inline ``$...$`` definitions of the prose first) and returns, for each display, the paper-file
claim it makes: ``definition`` (``derived`` when the sentence derives it), ``identity`` or
``condition`` with the ``about``, ``property`` and ``strength`` its sentence gives -- each with the
words it was read from, so that the reviewer sees why. A display whose claim the reading cannot
settle (a condition whose sentence names no property, a construct outside the exact algebra) is
``None``: the draft leaves it commented out with the reason. The names of the paper, with the signs
and ranges the paper states, become the draft's ``[symbols]``.

>>> from hapticproof.audit.source.read import read_text
>>> src = read_text(r'''\documentclass{article}\begin{document}
... Sampled with period $T$, let the wall be $H(z) = K + B\frac{z-1}{Tz}$ with $K, B \ge 0$ and
... \begin{equation} G(z) = b + H(z)\frac{T}{z-1}. \end{equation}
... Then $G(z)$ is positive real if and only if
... \begin{equation} b \ge \frac{KT}{2} + B . \end{equation}
... \end{document}''', "wall.tex")
>>> claims = read_claims(src)
>>> [(c.display.id, c.claim, c.about, c.strength) for c in claims.displays]
[('1', 'definition', None, None), ('2', 'condition', 'G', 'iff')]
>>> [(c.id, c.claim) for c in claims.inline]
[('1.inline1', 'definition')]
>>> claims.words["K"], claims.words["T"], claims.words["H"]
('nonnegative', 'positive', 'function')
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any

import sympy as sp

from hapticproof.audit.definitions.reading import (CONDITION, DEFINITION, DERIVED, IDENTITY, MALFORMED, MODEL, REDEFINED,
                                                   PaperReading, Reading)

__all__ = ["ReadClaim", "ReadClaims", "read_claims", "conventional"]


@dataclass(frozen=True)
class ReadClaim:
    """The claim of one display (``claim`` None: not settled, ``why`` says why)."""

    display: Any
    id: str
    printed: str
    claim: str | None
    why: str
    about: str | None = None
    property: str | None = None
    strength: str | None = None
    derived: bool = False
    assumption: str = ""
    reading: Reading | None = None
    #: an identity that uses names no definition gives (a scene's model may still say what they are)
    unbound: bool = False
    #: a condition whose claim is clear but that no defined object of the paper carries
    no_object: bool = False


@dataclass(frozen=True)
class ReadClaims:
    """Every display's claim, the inline definitions, and the ``[symbols]`` words (printed name ->
    word: ``positive``, ``nonnegative``, ``real``, ``function``, or a range such as ``a < 1``)."""

    displays: tuple[ReadClaim, ...]
    inline: tuple[ReadClaim, ...]
    words: dict[str, str] = field(default_factory=dict)
    reading: PaperReading | None = None


def read_claims(source: Any) -> ReadClaims:
    """The definitions reading of a source (:class:`~hapticproof.audit.source.displays.Source`)."""
    from hapticproof.audit.definitions.verdicts import resolved_condition

    paper = PaperReading()
    displays = list(source.displays)
    pending = []
    inline: list[ReadClaim] = []
    for k, d in enumerate(displays):
        if d.row in (None, 0):
            for r in paper.read_inline(d.id, d.prose):
                if r.kind == MODEL:
                    inline.append(ReadClaim(d, r.id, r.text, "identity", f"{r.note}, inline in the prose before ({d.id})",
                                            reading=r))
                    continue
                inline.append(ReadClaim(d, r.id, r.text, "definition", "an inline definition in the prose before "
                                        f"({d.id})", reading=r))
        after = displays[k + 1].prose if k + 1 < len(displays) else ""
        pending.append((d, paper.read(d.id, d.text, prose=d.prose, after=after)))
    out = []
    for d, r in pending:
        out.append(_claim_of(d, r, paper, resolved_condition))
    return ReadClaims(tuple(out), tuple(inline), _words(paper), paper)


def _sentence(reading: Reading) -> str:
    claim = reading.claim
    if claim is None:
        return ""
    return " ".join(claim.sentence.split())[-120:]


def _claim_of(display: Any, reading: Reading, paper: PaperReading, resolve: Any) -> ReadClaim:
    said = _sentence(reading)
    base = dict(display=display, id=display.id, printed=reading.printed or display.text, reading=reading)
    if reading.kind == REDEFINED:
        return ReadClaim(claim="definition", why=f"defines {', '.join(reading.binds)} again: {reading.note}", **base)
    if reading.kind in (DEFINITION, DERIVED):
        names = ", ".join(n.replace("^-1", "^{-1}") for n in reading.binds)
        if reading.kind == DERIVED:
            return ReadClaim(claim="definition", derived=True, why=f"defines {names}, derived by the paper ('{said}')", **base)
        return ReadClaim(claim="definition", why=f"defines {names}" + (f" ('{said}')" if said else ""), **base)
    if reading.kind == MODEL:
        return ReadClaim(claim="identity", why=f"{reading.note} (it defines how they are related)", **base)
    if reading.kind == IDENTITY:
        # values the sentence gives a parameter for this display ("$B_p = 0$"), and its inequalities
        assumption = ", ".join(reading.claim.assumptions) if reading.claim is not None else ""
        return ReadClaim(claim="identity", why="an equation between expressions the paper's definitions give",
                         unbound=_uses_unbound(reading), assumption=assumption, **base)
    if reading.kind == MALFORMED and reading.claim is not None and reading.claim.property:
        return ReadClaim(claim="condition", why=f"the sentence states a condition ('{said}') but the display has no relation",
                         property=reading.claim.property, strength=reading.claim.strength, **base)
    if reading.kind == CONDITION:
        resolved = resolve(reading, paper)
        if resolved is None:
            no_object = resolve(reading, paper, any_object=True) == "no object"
            return ReadClaim(claim=None, why=f"a condition whose sentence does not say what it is for ('{said}')"
                             if not no_object else "a condition about no object the paper defines", no_object=no_object, **base)
        about, prop, strength, how = resolved
        assumption = ", ".join(reading.claim.assumptions) if reading.claim is not None else ""
        return ReadClaim(claim="condition", about=about, property=prop, strength=strength, assumption=assumption,
                         why=f"{strength} for {about or 'a general two-port'} {prop.replace('-', ' ')}: {how}" + (f" ('{said}')" if said else ""), **base)
    if reading.kind == MALFORMED:
        return ReadClaim(claim=None, why=f"the reader cannot read it: {reading.error or reading.note}", **base)
    return ReadClaim(claim=None, why=f"not a definition, an identity or a condition{': ' + reading.note if reading.note else ''}",
                     **base)


def _uses_unbound(reading: Reading) -> bool:
    from hapticproof.audit.definitions.values import Unbound, evaluate

    env = reading.environment
    if env is None:
        return True
    for relation in reading.main:
        for term in relation.terms:
            try:
                evaluate(term, env)
            except Unbound:
                return True
            except Exception:                 # noqa: BLE001 -- only unbound names matter here
                continue
    return False


def _words(paper: PaperReading) -> dict[str, str]:
    """The ``[symbols]`` words: functions, signs from the paper's assumptions, periods positive,
    ranges (``0 <= \\alpha < 1``) and linear relations (``g_0 + g_1 >= 0``) in LaTeX; every other
    name real."""
    from hapticproof.audit.reader.names import sympy_name

    by_sympy = {sympy_name(printed): printed for printed in paper.symbols}
    words: dict[str, str] = {printed: "real" for printed in paper.symbols}
    for printed in paper.functions:
        words[printed] = "function"
    lower: dict[str, tuple[Any, str]] = {}
    upper: dict[str, tuple[Any, str]] = {}
    others: dict[str, list[str]] = {}
    flat = []
    for a in paper.assumptions:
        flat += list(a.args) if isinstance(a, sp.And) else [a]
    names = {sp.Symbol(n, real=True): printed for n, printed in by_sympy.items()}
    for a in flat:
        if not isinstance(a, sp.core.relational.Relational) or a.rel_op not in (">", ">=", "<", "<="):
            continue
        lhs, rhs, op = (a.lhs, a.rhs, a.rel_op) if a.rel_op in (">", ">=") else (a.rhs, a.lhs, {"<": ">", "<=": ">="}[a.rel_op])
        # lhs (op) rhs with op in > >=
        if lhs.is_Symbol and rhs.is_number and lhs.name in by_sympy:
            lower[by_sympy[lhs.name]] = (rhs, op)
        elif rhs.is_Symbol and lhs.is_number and rhs.name in by_sympy:
            upper[by_sympy[rhs.name]] = (lhs, "<" if op == ">" else "<=")
        else:
            present = sorted((s for s in a.free_symbols if s.name in by_sympy), key=lambda s: s.name)
            if present:
                others.setdefault(by_sympy[present[0].name], []).append(
                    f"{_latex(lhs, names)} {'>' if op == '>' else '>='} {_latex(rhs, names)}")
    for name in paper.periods:
        if name in by_sympy:
            lower.setdefault(by_sympy[name], (sp.Integer(0), ">"))
    for printed in set(lower) | set(upper) | set(others):
        if words.get(printed) == "function":
            continue
        lo, hi = lower.get(printed), upper.get(printed)
        if lo is not None and hi is None and lo[0] == 0 and printed not in others:
            words[printed] = "positive" if lo[1] == ">" else "nonnegative"
            continue
        parts = []
        if lo is not None or hi is not None:
            chain = ""
            if lo is not None:
                chain += f"{_latex(lo[0], names)} {'<' if lo[1] == '>' else '<='} "
            chain += printed
            if hi is not None:
                chain += f" {hi[1]} {_latex(hi[0], names)}"
            parts.append(chain)
        parts += others.get(printed, [])
        words[printed] = ", ".join(parts)
    for printed, word in words.items():
        if word == "real":
            words[printed] = _CONVENTIONS.get(_letter(printed), "real")
    return words


#: Signs a name's letter carries by convention in haptics papers when the paper states none: a
#: device damping b, a virtual damping B, a stiffness or gain K, k, a mass m, the period T
#: (the draft marks each as a guess for the reviewer).
_CONVENTIONS = {"b": "positive", "B": "nonnegative", "K": "nonnegative", "k": "nonnegative", "m": "positive",
                "M": "positive", "T": "positive"}


def _letter(printed: str) -> str:
    import re

    m = re.match(r"([A-Za-z])(?:_|$)", printed)
    return m.group(1) if m else ""


def conventional(printed: str, word: str) -> bool:
    """Whether a word of :func:`read_claims` is the letter's convention rather than the paper's statement."""
    return _CONVENTIONS.get(_letter(printed)) == word


def _latex(expr: Any, names: dict[sp.Symbol, str]) -> str:
    return sp.latex(expr, symbol_names={s: names.get(sp.Symbol(s.name, real=True), s.name) for s in getattr(expr, "free_symbols", ())})
