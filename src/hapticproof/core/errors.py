"""Exceptions raised for user mistakes.

Every user mistake (bad LaTeX, unknown paper, invalid scene) raises a subclass of
:class:`HapticproofError`; the CLI turns it into one line on stderr and a non-zero exit.

>>> try:
...     raise SceneError("T must be positive, got -1")
... except HapticproofError as err:
...     print(err)
T must be positive, got -1
"""

from __future__ import annotations

__all__ = [
    "HapticproofError",
    "LatexParseError",
    "SceneError",
    "UnknownPaperError",
    "UnknownEquationError",
    "InputFormatError",
    "SceneFileError",
    "DerivationError",
]


class HapticproofError(Exception):
    """Base class of all errors caused by the user's input."""


class LatexParseError(HapticproofError, ValueError):
    """A printed LaTeX string could not be parsed.

    Parameters
    ----------
    message : str
        What went wrong.
    text : str
        The string being parsed.
    position : int
        0-based character offset of the offending token.
    """

    def __init__(self, message: str, text: str = "", position: int = 0):
        self.text = text
        self.position = position
        self.reason = message
        if text:
            snippet = text[max(0, position - 20) : position + 20]
            message = f"{message} at position {position} (near {snippet!r})"
        super().__init__(message)


class SceneError(HapticproofError, ValueError):
    """A scene was given invalid parameters (T <= 0, non-integer delay ratio, ...)."""


class UnknownPaperError(HapticproofError, KeyError):
    """No registered paper has this id."""

    def __str__(self) -> str:  # KeyError would quote the message
        return str(self.args[0]) if self.args else ""


class UnknownEquationError(HapticproofError, KeyError):
    """The paper has no registered equation with this id."""

    def __str__(self) -> str:
        return str(self.args[0]) if self.args else ""


class InputFormatError(HapticproofError, ValueError):
    """A user file or command-line value is not in the documented format."""


class SceneFileError(InputFormatError):
    """A scene file (or scene table) that cannot be read: names the file, line and field."""


class DerivationError(HapticproofError, ArithmeticError):
    """An internal identity of a derivation did not hold (a bug, reported instead of a verdict)."""
