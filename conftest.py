"""Test-session settings shared by the unit tests, doctests and notebooks (kernels inherit them).

Small dense matrices are the common case here; multi-threaded BLAS makes them several times
slower on a shared 2-core machine, so BLAS is pinned to one thread. Plots use the Agg backend.
"""

import os

for _variable in ("OPENBLAS_NUM_THREADS", "OMP_NUM_THREADS", "MKL_NUM_THREADS"):
    os.environ.setdefault(_variable, "1")
os.environ.setdefault("MPLBACKEND", "Agg")

# The section modules of a paper's package register onto its PAPER when the package imports them;
# collecting them again as separate modules (import-mode=importlib) would register twice. They
# hold no doctests (the registered papers are tested through the audit).
collect_ignore_glob = ["derivations/*/*.py"]

# Property tests draw the same examples on every run (CI must not pass or fail by luck);
# HYPOTHESIS_PROFILE=explore draws fresh random examples, as when hunting for new failures.
try:
    from hypothesis import settings as _hypothesis_settings
except ImportError:  # the test extra is not installed: nothing to configure
    pass
else:
    _hypothesis_settings.register_profile("deterministic", derandomize=True)
    _hypothesis_settings.register_profile("explore", derandomize=False)
    _hypothesis_settings.load_profile(os.environ.get("HYPOTHESIS_PROFILE", "deterministic"))


import re as _re

import pytest as _pytest

_CELL = _re.compile(r"Cell (\d+)$")


@_pytest.hookimpl(trylast=True)
def pytest_collection_modifyitems(items):
    """A notebook's cells run in the notebook's order whatever a random-order plugin
    (``pytest -p randomly``) did to the items: each notebook keeps the places its cells were
    given, filled with its cells in order (a later cell needs what an earlier one computed)."""
    places: dict[str, list[int]] = {}
    for k, item in enumerate(items):
        if str(getattr(item, "fspath", "")).endswith(".ipynb") and _CELL.search(item.name):
            places.setdefault(str(item.fspath), []).append(k)
    for positions in places.values():
        cells = sorted((items[k] for k in positions), key=lambda item: int(_CELL.search(item.name).group(1)))
        for k, cell in zip(positions, cells):
            items[k] = cell
