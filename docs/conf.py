"""Sphinx configuration of the hapticproof documentation (built offline, warnings as errors, by
``tests/test_docs.py``: ``sphinx-build -W -b html docs DIR``)."""

from __future__ import annotations

import sys
from pathlib import Path

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE / "_ext"))

project = "hapticproof"
author = "the hapticproof developers"
copyright = "the hapticproof developers"          # noqa: A001 - Sphinx's name

try:
    from hapticproof.core.version import VERSION as release
except ImportError:                                 # pragma: no cover - the package is installed to build
    release = "unknown"
version = release

extensions = [
    "sphinx.ext.autodoc",
    "sphinx.ext.napoleon",          # numpydoc docstrings
    "sphinx.ext.mathjax",
    "clihelp",                      # the --help of every command, generated at build time
]
napoleon_google_docstring = False
napoleon_numpy_docstring = True
autodoc_member_order = "bysource"
autodoc_typehints = "none"
autodoc_default_options = {"members": False}

root_doc = "index"
exclude_patterns = ["_build", "architecture.md"]
templates_path: list[str] = []
html_static_path = ["_static"]
html_theme = "alabaster"
html_theme_options = {"description": "exact stability and passivity of sampled-data haptics", "fixed_sidebar": True,
                      "page_width": "1200px", "body_max_width": "none"}    # the commands' lines are long
html_title = f"hapticproof {release}"
# nothing is fetched: no intersphinx, no remote images; MathJax is loaded by the reader's browser
suppress_warnings: list[str] = []
nitpicky = False
