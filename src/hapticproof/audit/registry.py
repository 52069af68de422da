"""Find the registered papers in ``derivations/`` (the ``hapticproof.derivations`` package).

Every module there that defines ``PAPER`` (a :class:`~hapticproof.audit.runner.Paper`) is a registered
paper; it is found by its id or any of its aliases.

>>> sorted(p.id for p in papers().values())[:1]
['...']
"""

from __future__ import annotations

import importlib
import pkgutil
from functools import lru_cache

from hapticproof.audit.runner import Paper
from hapticproof.core.errors import UnknownPaperError

__all__ = ["papers", "get_paper", "paper_order"]

#: The package of registered papers, found by name at run time: the papers are plugins of the
#: audit (they build on every layer), so the audit layer does not import them statically.
PAPERS_PACKAGE = "hapticproof.derivations"

#: Audit order of the bundled papers (others follow alphabetically).
paper_order = ("hve", "bilateral-3dof", "teleoperator", "classics", "cross-paper")


@lru_cache(maxsize=1)
def papers() -> dict[str, Paper]:
    """All registered papers by id, in audit order."""
    package = importlib.import_module(PAPERS_PACKAGE)

    found: dict[str, Paper] = {}
    for info in pkgutil.iter_modules(package.__path__):
        if info.name.startswith("_"):
            continue
        module = importlib.import_module(f"{package.__name__}.{info.name}")
        paper = getattr(module, "PAPER", None)
        if isinstance(paper, Paper):
            if paper.id in found:
                raise RuntimeError(f"two modules register the paper id {paper.id!r}")
            found[paper.id] = paper
    rank = {pid: i for i, pid in enumerate(paper_order)}
    return dict(sorted(found.items(), key=lambda kv: (rank.get(kv[0], len(rank)), kv[0])))


def get_paper(name: str) -> Paper:
    """A registered paper by id or alias.

    >>> get_paper("no-such-paper")
    Traceback (most recent call last):
    ...
    hapticproof.core.errors.UnknownPaperError: unknown paper 'no-such-paper' (registered: ...)
    """
    key = name.strip().lower()
    direct = _by_module_name(key)
    if direct is not None:
        return direct
    registered = papers()
    for paper in registered.values():
        if key == paper.id or key in paper.aliases:
            return paper
    raise UnknownPaperError(f"unknown paper {name!r} (registered: {', '.join(registered) or 'none'})")


def _by_module_name(key: str) -> Paper | None:
    """The paper whose module is named after its id (``bilateral-3dof`` -> ``bilateral_3dof``),
    imported alone: auditing one paper need not import (and set up) every other one."""
    package = importlib.import_module(PAPERS_PACKAGE)

    module_name = key.replace("-", "_")
    if not module_name.isidentifier() or module_name.startswith("_"):
        return None
    if not any(info.name == module_name for info in pkgutil.iter_modules(package.__path__)):
        return None
    paper = getattr(importlib.import_module(f"{package.__name__}.{module_name}"), "PAPER", None)
    return paper if isinstance(paper, Paper) and paper.id == key else None
