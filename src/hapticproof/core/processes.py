"""Worker processes that die with their parent.

A worker of ``audit --jobs``, ``map --workers`` or a mutation run that outlives its parent
(killed by SIGTERM or SIGKILL, or a closed terminal) would compute on forever. Every worker
calls :func:`die_with_parent` first: on Linux the kernel then sends it SIGKILL when the
parent dies (``prctl(PR_SET_PDEATHSIG)``), and a parent already gone ends it at once. On
Ctrl-C (which the terminal sends to every process of the command) a worker ends without a
word; the parent prints the one line.

>>> import os
>>> die_with_parent(os.getppid(), quiet_interrupt=False)   # a no-op here: the parent is alive
"""

from __future__ import annotations

import os
import signal
import sys

__all__ = ["die_with_parent"]

_PR_SET_PDEATHSIG = 1


def _exit_quietly(signum: int, frame: object) -> None:
    os._exit(128 + signum)


def die_with_parent(parent: int, quiet_interrupt: bool = True) -> None:
    """End this process when process ``parent`` (the pid its parent had when it started it) ends.

    Pass it as the ``initializer`` of a process pool (``initargs=(os.getpid(),)``) or call it
    first thing in a worker. ``quiet_interrupt``: Ctrl-C (SIGINT) ends the worker at once and
    without a traceback (the parent reports it)."""
    if quiet_interrupt:
        signal.signal(signal.SIGINT, _exit_quietly)
    if sys.platform.startswith("linux"):
        try:
            import ctypes

            ctypes.CDLL(None, use_errno=True).prctl(_PR_SET_PDEATHSIG, signal.SIGKILL)
        except (OSError, AttributeError):  # pragma: no cover - no prctl: the pipes' end remains
            pass
    if os.getppid() != parent:        # the parent died before the request took effect
        os._exit(0)
