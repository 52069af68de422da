"""The toolkit's version (the one place it is written besides ``pyproject.toml``)."""

__all__ = ["VERSION"]

VERSION = "0.1.0"
