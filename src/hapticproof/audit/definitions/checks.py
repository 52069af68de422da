"""The claim checkers of ``definition``, ``identity`` and ``condition`` claims in paper files.

Each reads its display in the namespace the paper file's earlier definitions built
(:attr:`hapticproof.audit.paperfile.PaperFile.definitions`) and returns the verdict of
:func:`hapticproof.audit.definitions.verdicts.verdict`; a repair's trial edit is read in the same
namespace without binding anything, so the claims framework's one-edit search
(:mod:`hapticproof.audit.claims`) finds typos here as everywhere.

>>> from hapticproof.audit.paperfile import loads
>>> from hapticproof.audit.runner import audit_paper
>>> paper = loads('''
... [paper]
... id = "wall"
... title = "A wall"
... [symbols]
... K = "nonnegative"
... B = "nonnegative"
... T = "positive"
... b = "real"
... [[equations]]
... id = "1"
... printed = 'G(z) = b + \\\\frac{KT}{z-1} + \\\\frac{B}{z}'
... claim = "definition"
... [[equations]]
... id = "2"
... printed = '\\\\operatorname{Re} G(e^{j\\\\omega T}) = b - \\\\frac{KT}{2} - B\\\\cos\\\\omega T'
... claim = "identity"
... [[equations]]
... id = "3"
... printed = 'b \\\\ge \\\\frac{KT}{2} + B'
... claim = "condition"
... about = "G"
... property = "positive-real"
... strength = "iff"
... ''')
>>> [(r.id, r.verdict.value) for r in audit_paper(paper.paper).results]
[('1', 'confirmed'), ('2', 'typo'), ('3', 'confirmed')]
"""

from __future__ import annotations

from typing import Any

from hapticproof.audit.definitions.reading import CONDITION, DERIVED, IDENTITY
from hapticproof.audit.definitions.verdicts import verdict
from hapticproof.core.evidence import Finding, Verdict

__all__ = ["check", "verified_by_scene"]


def check(state: Any) -> Finding:
    """The verdict of a definition, identity or condition claim (``state``: the claims framework's).

    A definition the paper derives is bound as printed and left undecided, unless the file names
    a scene whose model gives the same ``G^{-1}(z)`` (then it is confirmed: the paper derived the
    toolkit's model); a scene never turns it into a defect."""
    paper = state.source.definitions
    reading = paper.reading_for(state.spec.id, state.printed)
    state.repairable = reading.kind in (IDENTITY, CONDITION)
    spec = state.spec
    finding = verdict(reading, paper, about=spec.about, prop=spec.property, strength=spec.strength)
    if spec.claim == "definition" and spec.derived and spec.scene and reading.kind == DERIVED:
        return _by_scene(state, finding)
    return finding


def verified_by_scene(paper: Any, spec: Any) -> bool:
    """Whether the scene a derived definition names gives the same ``G^{-1}(z)`` (the display
    as printed, checked by the scene claims' own checker)."""
    import dataclasses

    from hapticproof.audit.claimbase import State
    from hapticproof.audit.claimcheckers import inverse_transfer
    from hapticproof.core.errors import HapticproofError

    state = State(dataclasses.replace(spec, claim="inverse-transfer"), paper, spec.printed)
    try:
        return inverse_transfer(state).verdict == Verdict.CONFIRMED
    except (HapticproofError, ValueError, TypeError):
        return False


def _by_scene(state: Any, finding: Finding) -> Finding:
    import dataclasses

    from hapticproof.audit.claimcheckers import inverse_transfer
    from hapticproof.core.errors import HapticproofError

    trial = dataclasses.replace(state, spec=dataclasses.replace(state.spec, claim="inverse-transfer"))
    try:
        found = inverse_transfer(trial)
    except (HapticproofError, ValueError, TypeError) as err:
        return Finding(finding.verdict, f"{finding.detail}; the scene's model does not settle it ({err})", finding.evidence)
    if found.verdict == Verdict.CONFIRMED:
        return Finding(Verdict.CONFIRMED, f"the derived display is the scene '{state.spec.scene}' model's: {found.detail}",
                       found.evidence, derived=found.derived)
    return Finding(finding.verdict, f"{finding.detail}; it is not the scene '{state.spec.scene}' model's either ({found.verdict.value})",
                   finding.evidence)
