"""The wheel ships every subpackage: a plain ``pip install .`` (the README's first command) must
install the CLI and the registered papers, not only the editable install the tests run from."""

import tomllib
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]


def test_every_package_folder_is_listed_in_pyproject():
    """Every folder with an ``__init__.py`` under each ``package-dir`` (the paper packages of
    ``derivations/`` too: without them the installed audit knows no paper but classics)."""
    config = tomllib.loads((ROOT / "pyproject.toml").read_text())["tool"]["setuptools"]
    listed = set(config["packages"])
    found = set()
    for prefix, folder in config["package-dir"].items():
        for init in (ROOT / folder).rglob("__init__.py"):
            found.add(".".join((prefix, *init.parent.relative_to(ROOT / folder).parts)))
    assert {"hapticproof.derivations.hve", "hapticproof.audit.reader"} <= found      # the walk sees nested folders
    assert found - listed == set(), "package folders missing from pyproject's packages"
    assert listed - found == set(), "pyproject lists packages without a folder"
    assert config["package-dir"]["hapticproof.derivations"] == "derivations"


def test_every_data_file_of_a_package_folder_ships():
    """A paper file beside a bundled paper's modules (``derivations/hve/routine.toml``, read when
    the paper registers) is package data: without it a plain install cannot import the paper."""
    config = tomllib.loads((ROOT / "pyproject.toml").read_text())["tool"]["setuptools"]
    shipped = config.get("package-data", {})
    for prefix, folder in config["package-dir"].items():
        for data in (ROOT / folder).rglob("*.toml"):
            package = ".".join((prefix, *data.parent.relative_to(ROOT / folder).parts))
            assert any(data.match(pattern) for pattern in shipped.get(package, ())), \
                f"{data.relative_to(ROOT)} is not in pyproject's package-data for {package}"
    assert (ROOT / "derivations" / "hve" / "routine.toml").is_file()
