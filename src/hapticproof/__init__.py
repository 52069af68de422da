"""hapticproof: regenerate, certify and audit stability conditions of sampled-data haptic systems.

The package is layered (``docs/architecture.md``): :mod:`~hapticproof.core` (vocabulary),
:mod:`~hapticproof.exact` (exact algebra and the decision kernel), :mod:`~hapticproof.systems`
(scenes and models), :mod:`~hapticproof.analysis` (decisions), :mod:`~hapticproof.audit`
(printed equations), :mod:`~hapticproof.report` (views), :mod:`~hapticproof.bench` and
:mod:`~hapticproof.cli`. The names most people need are importable from here; each is loaded on
first use, so ``import hapticproof`` stays cheap.

>>> from hapticproof import Scene, positive_real
>>> positive_real(Scene("single-user", params={"K": 2, "B": 0, "b": "0.02", "T": "0.001"}).build()).decision.value
'proved'
"""

from __future__ import annotations

import importlib
import sys
from typing import Any

from hapticproof.core.version import VERSION as __version__

#: public name -> the module that defines it
_PUBLIC = {
    "HapticproofError": "hapticproof.core.errors",
    "SceneError": "hapticproof.core.errors",
    "Decision": "hapticproof.core.evidence",
    "Verdict": "hapticproof.core.evidence",
    "Evidence": "hapticproof.core.evidence",
    "Outcome": "hapticproof.core.evidence",
    "Finding": "hapticproof.core.evidence",
    "to_latex": "hapticproof.core.notation",
    "Scene": "hapticproof.systems.scene",
    "read_scene": "hapticproof.systems.scene",
    "SingleUserScene": "hapticproof.systems.singleuser",
    "MultiUserScene": "hapticproof.systems.multiuser",
    "TeleoperatorScene": "hapticproof.systems.teleoperator",
    "inverse_transfer": "hapticproof.systems.models",
    "discretize": "hapticproof.systems.discretize",
    "positive_real": "hapticproof.analysis.anysystem",
    "hermitian": "hapticproof.analysis.positivereal",
    "worst_case": "hapticproof.analysis.positivereal",
    "NumericScene": "hapticproof.analysis.fastpath",
    "decide": "hapticproof.analysis.fastpath",
    "ispassive": "hapticproof.analysis.passivity",
    "inverse_transfer_system": "hapticproof.systems.lti",
    "hermitian_system": "hapticproof.systems.lti",
    "delay_margin": "hapticproof.analysis.design",
    "passive_range": "hapticproof.analysis.passiverange",
    "check_certificate": "hapticproof.exact.checker",
    "check_report": "hapticproof.exact.checker",
    "audit_paper": "hapticproof.audit.runner",
    "get_paper": "hapticproof.audit.registry",
    "read_paper": "hapticproof.audit.paperfile",
}

__all__ = ["__version__", *_PUBLIC]


def __getattr__(name: str) -> Any:
    module = _PUBLIC.get(name)
    if module is None:
        raise AttributeError(f"module 'hapticproof' has no attribute {name!r}")
    value = getattr(importlib.import_module(module), name)
    globals()[name] = value
    return value


def __dir__() -> list[str]:
    return sorted(set(globals()) | set(_PUBLIC))


def _register_notebook_views() -> None:
    """Inside a running IPython, show scenes as mathematics and findings as report cards."""
    ipython = sys.modules.get("IPython")
    shell = ipython.get_ipython() if ipython is not None else None
    if shell is not None and hasattr(shell, "display_formatter"):
        from hapticproof.report.notebook import register

        register(shell)


_register_notebook_views()
