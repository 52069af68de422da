"""What a terminal gets and a pipe does not: progress bars, coloured verdicts, summary lines.

A progress bar is drawn on stderr only when stderr is a terminal (never in pipes, files or CI
logs); colours are used only on a terminal and never when ``NO_COLOR`` is set
(https://no-color.org). No dependency.

>>> import io
>>> progress_bar(io.StringIO()) is None        # not a terminal: no bar
True
>>> summary_line({"typo": 2, "confirmed": 5, "wrong": 1})
'8 equations: wrong 1, typo 2, confirmed 5'
"""

from __future__ import annotations

import os
import sys
import time
from collections.abc import Mapping
from typing import TextIO

__all__ = ["ProgressBar", "progress_bar", "use_colour", "colour_verdict", "summary_line"]

#: ANSI colours of the verdicts (the badge colours of the reports, as near as 8 colours go).
VERDICT_ANSI = {
    "confirmed": "32",
    "conservative": "34",
    "typo": "33",
    "wrong": "1;31",
    "needs-assumption": "35",
    "inconsistent": "31",
    "malformed": "1;90",
    "undecided": "90",
}
#: Verdicts in errata order (defects first).
ORDER = ("wrong", "typo", "inconsistent", "needs-assumption", "malformed", "undecided", "conservative", "confirmed")


class ProgressBar:
    """A one-line text progress bar on a stream (no dependency).

    >>> import io
    >>> buf = io.StringIO()
    >>> bar = ProgressBar(buf, width=10)
    >>> bar(5, 10); bar(10, 10)
    >>> buf.getvalue().splitlines()[-1].strip()
    '[##########] 10/10'
    """

    def __init__(self, stream: TextIO = sys.stderr, width: int = 30, label: str = ""):
        self.stream, self.width, self.label, self.start = stream, width, label, time.monotonic()
        self._drawn = False

    def __call__(self, done: int, total: int, label: str | None = None) -> None:
        if label is not None:
            self.label = label
        filled = int(self.width * done / max(total, 1))
        bar = "#" * filled + "-" * (self.width - filled)
        elapsed = time.monotonic() - self.start
        end = "\n" if done >= total else ""
        suffix = f" {elapsed:.1f}s" if self.stream is sys.stderr else ""
        prefix = f"{self.label} " if self.label else ""
        self.stream.write(f"\r\033[K{prefix}[{bar}] {done}/{total}{suffix}{end}" if self._tty()
                          else f"\r{prefix}[{bar}] {done}/{total}{suffix}{end}")
        self.stream.flush()
        self._drawn = done < total

    def clear(self) -> None:
        """Erase the bar's line (before other output goes to the same terminal)."""
        if self._drawn and self._tty():
            self.stream.write("\r\033[K")
            self.stream.flush()

    def _tty(self) -> bool:
        return hasattr(self.stream, "isatty") and self.stream.isatty()


def progress_bar(stream: TextIO = sys.stderr, label: str = "") -> ProgressBar | None:
    """A bar when ``stream`` is a terminal, else None (pipes, files, CI logs)."""
    return ProgressBar(stream, label=label) if hasattr(stream, "isatty") and stream.isatty() else None


def use_colour(stream: TextIO) -> bool:
    """Colour only on a terminal and only when ``NO_COLOR`` is unset or empty."""
    return not os.environ.get("NO_COLOR") and hasattr(stream, "isatty") and stream.isatty()


def colour_verdict(text: str, verdict: str | None = None) -> str:
    """``text`` (default: the verdict) in the verdict's ANSI colour.

    >>> colour_verdict("typo")
    '\\x1b[33mtypo\\x1b[0m'
    """
    code = VERDICT_ANSI.get((verdict or text).strip())
    return f"\033[{code}m{text}\033[0m" if code else text


def summary_line(counts: Mapping[str, int], colour: bool = False, papers: int | None = None,
                 seconds: float | None = None) -> str:
    """``N equations: wrong 1, typo 2, ...`` (verdicts in errata order)."""
    total = sum(counts.values())
    parts = []
    for verdict in ORDER + tuple(sorted(set(counts) - set(ORDER))):
        if counts.get(verdict):
            word = colour_verdict(verdict) if colour else verdict
            parts.append(f"{word} {counts[verdict]}")
    where = f" in {papers} paper{'s' if papers != 1 else ''}" if papers is not None else ""
    took = f" ({seconds:.1f} s)" if seconds is not None else ""
    return f"{total} equation{'s' if total != 1 else ''}{where}{took}: " + ", ".join(parts)
