"""The wheel ships every subpackage: a plain ``pip install .`` (the README's first command) must
install the CLI and the registered papers, not only the editable install the tests run from."""

import tomllib
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]


def test_every_subpackage_is_listed_in_pyproject():
    config = tomllib.loads((ROOT / "pyproject.toml").read_text())["tool"]["setuptools"]
    listed = set(config["packages"])
    found = {"hapticproof." + ".".join(p.parent.relative_to(ROOT / "src" / "hapticproof").parts)
             for p in (ROOT / "src" / "hapticproof").rglob("__init__.py")}
    found = {name.rstrip(".") for name in found}
    assert found | {"hapticproof.derivations"} <= listed
    assert config["package-dir"]["hapticproof.derivations"] == "derivations"
