r"""What the prose around a display claims: the property, its strength, the object and the assumptions.

A condition in a paper is a claim only through its sentence: "``G_f^{-1}(z)`` is positive real if
and only if", "a sufficient condition is", "which is necessary", "the two-port is absolutely stable
if and only if, for all ``\omega``", "for ``K_c > 0`` and ``b > 0``". :func:`claim_of` reads the
sentence that leads into a display (the end of the prose before it) and the words right after it,
and returns a :class:`ProseClaim`: the property (``positive-real``, ``absolutely-stable``,
``stable``), the strength (``iff``, ``sufficient``, ``necessary``), the object named in the
sentence (an inline ``$...$`` name, or a noun such as "the two-port"), quantifiers ("for any causal
``H(z)``") and the inline inequalities stated as assumptions. Each guess keeps the words it came
from, so a draft can show the reviewer why.

>>> c = claim_of(r"worst case is $\cos\omega T = -1$, and $G_f^{-1}(z)$ is positive real if and only if")
>>> c.property, c.strength, c.object, c.evidence
('positive-real', 'iff', 'G_f^{-1}(z)', 'positive real if and only if')
>>> claim_of(r"Hence, for $K_c > 0$ and $b > 0$, the coupled device is absolutely stable if and only if").assumptions
('K_c > 0', 'b > 0')
>>> claim_of("A simpler bound, which is sufficient, is").strength
'sufficient'
"""

from __future__ import annotations

import re
from dataclasses import dataclass

__all__ = ["ProseClaim", "claim_of", "last_sentence", "inline_math"]

_PROPERTY = (
    ("absolutely-stable", r"absolute(?:ly)?[\s~-]+stab(?:le|ility)|unconditionally[\s~-]+stable"),
    ("positive-real", r"positive[\s~-]+real(?:ness)?|\bpassiv(?:e|ity)\b|\bis\s+PR\b"),
    ("stable", r"\bstab(?:le|ility)\b"),
)
_STRENGTH = (
    ("iff", r"if\s+and\s+only\s+if|\biff\b|exactly\s+when|necessary\s+and\s+sufficient|is\s+equivalent\s+to|"
            r"precisely\s+when|\bequivalently\b"),
    ("necessary", r"\bnecessary\b|\bonly\s+if\b|\brequires?\b|\bimplies\b|\bmust\b"),
    ("sufficient", r"\bsufficient\b|\bsuffices?\b|\bwhenever\b|\bguarantees?\b|\bensures?\b|\bif\b"),
)
_ANY = re.compile(r"\bfor\s+(?:any|every|all|an\s+arbitrary|arbitrary)\s+(?:causal\s+|stable\s+|passive\s+|proper\s+)*"
                  r"(?:environments?\s+|controllers?\s+)?\$([^$]{1,60})\$")
_INLINE = re.compile(r"\$([^$]{1,400})\$")
#: an inline value given to a parameter for the display ("with a proportional controller ($B_p = 0$)")
_SETTING = re.compile(r"\s*\\?[A-Za-z][A-Za-z0-9_{}\\]*\s*=\s*-?\d+(?:\.\d+)?\s*")
_RELATION = re.compile(r"(?:\\ge|\\geq|\\le|\\leq|\\geqslant|\\leqslant|>|<|\\gt|\\lt)")
_NOUNS = (
    ("two-port", r"two[\s~-]*port|coupled\s+device|teleoperator|bilateral|network"),
    ("system", r"\bsystem\b|rendering|\bwall\b|\bdevice\b|interaction|\bloop\b|display"),
)


@dataclass(frozen=True, slots=True)
class ProseClaim:
    """The claim the words around a display make (any field may be ``None`` when not stated)."""

    property: str | None = None
    strength: str | None = None
    #: the object named in the sentence: an inline name (``G_f^{-1}(z)``) or a noun (``two-port``)
    object: str | None = None
    noun: str | None = None
    #: the words the property and the strength were read from
    evidence: str = ""
    #: inline inequalities of the sentence read as assumptions (``K_c > 0``), and values given to a
    #: parameter (``B_p = 0``)
    assumptions: tuple[str, ...] = ()
    #: "for any causal $H(z)$": the claim is about every such object
    for_any: str | None = None
    sentence: str = ""


def inline_math(text: str) -> list[str]:
    """The inline ``$...$`` pieces of a text, in order.

    >>> inline_math(r"Let $H(z) = K$ and $b > 0$.")
    ['H(z) = K', 'b > 0']
    """
    return [m.group(1).strip() for m in _INLINE.finditer(text)]


def last_sentence(text: str) -> str:
    """The sentence a display continues: the prose after the last full stop outside ``$...$``."""
    depth = 0
    cut = 0
    for k, ch in enumerate(text):
        if ch == "$":
            depth ^= 1
        elif depth == 0 and ch in ".;" and k + 1 < len(text) and text[k + 1] in " \n" and not text[max(0, k - 3):k].endswith(("e.g", "i.e", "cf")):
            cut = k + 1
    return text[cut:].strip()


def _plain(sentence: str) -> str:
    """The sentence with its inline maths replaced by a placeholder (for the word patterns)."""
    return _INLINE.sub(" MATH ", sentence)


def claim_of(before: str, after: str = "") -> ProseClaim:
    """Read the claim of a display from the prose before it (its leading sentence) and the first
    words after it ("..., which is necessary")."""
    sentence = last_sentence(before)
    words = _plain(sentence)
    following = _plain(after[:160]).split(".")[0] if after else ""
    prop = next(((name, m) for name, pattern in _PROPERTY for m in [re.search(pattern, words, re.I)] if m), None)
    strength = None
    for text in (words, following):
        found = [(name, m) for name, pattern in _STRENGTH for m in [re.search(pattern, text, re.I)] if m]
        if found:
            strength = found[0]
            break
    # "if and only if" wins over its own "if"; "sufficient" over a bare "if"
    evidence = ""
    if prop is not None:
        start = prop[1].start()
        end = strength[1].end() if strength is not None and strength[1].string is words else prop[1].end()
        evidence = words[min(start, end):max(end, prop[1].end())].strip()
        evidence = re.sub(r"\s+", " ", evidence.replace("MATH", "").strip())
    obj = _named_object(sentence, prop[1].start() if prop else None)
    noun = next((name for name, pattern in _NOUNS if re.search(pattern, words, re.I)), None)
    assumptions = tuple(m for m in inline_math(sentence) if (_RELATION.search(m) or _SETTING.fullmatch(m)) and _is_assumption(m))
    if after:
        assumptions += tuple(m for m in inline_math(after.split(".")[0]) if _RELATION.search(m) and _is_assumption(m))
    if prop is None and following:
        prop = next(((name, m) for name, pattern in _PROPERTY for m in [re.search(pattern, following, re.I)] if m), None)
        if prop is not None and not evidence:
            evidence = following.strip()[:80]
    any_match = _ANY.search(sentence)
    quantified = any_match.group(1).strip() if any_match else None
    if quantified is not None and re.fullmatch(r"\\omega|\\vartheta|\\theta|[0-9<>=\\lepiTt/ ,{}]*\\omega.*", quantified):
        quantified = None                     # "for all $\omega$" quantifies the frequency, not the object
    return ProseClaim(prop[0] if prop else None, strength[0] if strength else None, obj, noun, evidence, assumptions,
                      quantified, sentence)


def _is_assumption(math: str) -> bool:
    """An inline inequality on parameters (``K_c > 0``, ``b_1, b_2 > 0``, ``0 \\le a < 1``), not
    one about the frequency."""
    return not re.search(r"\\omega|\\vartheta|\\theta|\bz\b|\bs\b", math)


def _named_object(sentence: str, position: int | None) -> str | None:
    """The inline name just before the property words ("$G_f^{-1}(z)$ is positive real")."""
    pieces = list(_INLINE.finditer(sentence))
    if not pieces:
        return None
    plain_positions = []
    offset = 0
    plain = ""
    for m in pieces:
        plain += sentence[offset:m.start()]
        plain_positions.append((len(plain), m.group(1).strip()))
        plain += " MATH "
        offset = m.end()
    candidates = [text for at, text in plain_positions if position is None or at < position]
    for text in reversed(candidates):
        if not _RELATION.search(text) and "=" not in text:
            return text
    return None
