"""Command-line interface: ``hapticproof audit | new-paper | derive | check | export | boundary | map | zwidth | bench``.

Each subcommand lives in its own module of this package and exposes ``register(subparsers)``,
which adds its parser and sets ``handler`` to a function ``handler(args) -> int``.
User mistakes (:class:`~hapticproof.core.errors.HapticproofError`) become one line on stderr and exit
code 2; Ctrl-C is one line and exit code 130. ``--limit NAME=N`` (anywhere, repeatable) raises one
of the bounds of :mod:`hapticproof.core.limits` for the run.
"""

from __future__ import annotations

import argparse
import importlib
import sys
from collections.abc import MutableMapping, Sequence
from typing import Any, NoReturn

from hapticproof.core.errors import HapticproofError

__all__ = ["main", "build_parser", "take_limits", "help_text", "Terminated"]

#: Subcommand modules, in the order they appear in ``--help``.
COMMANDS = ("audit", "new-paper", "derive", "check", "export", "boundary", "map", "zwidth", "bench")


class OneLineParser(argparse.ArgumentParser):
    """argparse with a mistake on the command line as one line on standard error and exit code 2
    (``hapticproof: error: derive single-user: argument --format: invalid choice ...``), as every
    other mistake is; the usage stays in ``--help``."""

    def parse_args(self, args: Any = None, namespace: Any = None) -> Any:
        self.words = list(sys.argv[1:] if args is None else args)     # the command, for an error's hint
        return super().parse_args(args, namespace)

    def error(self, message: str) -> NoReturn:
        prog = self._command_prog()
        words = prog.split()[1:]
        where = f"{' '.join(words)}: " if words else ""
        hint = f" (see: {prog} --help)"
        self.exit(2, f"hapticproof: error: {where}{message}{hint}\n")

    def _command_prog(self) -> str:
        """The prog of the subcommand the command line names (``hapticproof derive single-user``):
        an argument the root parser does not recognise belongs to it."""
        parser = self
        for word in getattr(self, "words", ()):
            commands = next((a.choices for a in parser._actions if isinstance(a, argparse._SubParsersAction)), None)
            if commands is None:
                break
            if word in commands:
                parser = commands[word]
        return parser.prog


def build_parser(command: str | None = None, system: str | None = None) -> argparse.ArgumentParser:
    """The parser with every subcommand, or only ``command`` (its module alone is imported:
    ``hapticproof audit`` need not load the simulation and plotting stack of ``boundary``);
    ``system`` is the one ``derive`` parses in full.

    Building it loads no SymPy, NumPy or any module that computes: the command modules import
    those in their handlers, so ``--version`` and every ``--help`` answer at once.

    >>> parser = build_parser("derive", "single-user")
    >>> parser.parse_args(["derive", "single-user", "--delay", "3"]).delay
    '3'
    """
    parser = OneLineParser(
        prog="hapticproof",
        description="Regenerate, certify and audit stability and passivity conditions of "
        "sampled-data haptic and teleoperation systems.",
    )
    from hapticproof.core.version import VERSION

    parser.add_argument("--version", action="version", version=f"hapticproof {VERSION}")
    parser.add_argument("--limit", action="append", default=[], metavar="NAME=N",
                        help="raise one of the bounds checked before any work (anywhere on the command line, "
                        "repeatable): file_size, depth, digits, exponent, degree, delay, users, minors, grid; "
                        "see docs/reference/limits.rst")
    sub = parser.add_subparsers(dest="command", required=True, metavar="COMMAND")
    for name in (command,) if command in COMMANDS else COMMANDS:
        module = importlib.import_module(f"hapticproof.cli.{name.replace('-', '_')}")
        if name == "derive":
            module.register(sub, system)
        else:
            module.register(sub)
    return parser


def help_text(*words: str, width: int = 100) -> str:
    """The ``--help`` of ``hapticproof WORDS...`` (``()``: the program's, ``("derive", "single-user")``: a
    system's), ``width`` columns wide: the reference of the documentation is generated from it.

    >>> help_text("check").splitlines()[0]
    'usage: hapticproof check [-h] [--quiet] report'
    """
    import contextlib
    import io
    import os

    parser = build_parser(words[0] if words else None, words[1] if len(words) > 1 else None)
    out = io.StringIO()
    saved = os.environ.get("COLUMNS")
    os.environ["COLUMNS"] = str(width)            # argparse wraps to the terminal's width
    try:
        with contextlib.redirect_stdout(out), contextlib.suppress(SystemExit):
            parser.parse_args([*words, "--help"])
    finally:
        if saved is None:
            os.environ.pop("COLUMNS", None)
        else:
            os.environ["COLUMNS"] = saved
    return out.getvalue()


def take_limits(argv: list[str]) -> tuple[list[str], list[str]]:
    """``--limit NAME=N`` options (anywhere on the command line) taken out of ``argv``.

    >>> take_limits(["derive", "--limit", "delay=200000", "single-user", "--limit=users=5"])
    (['derive', 'single-user'], ['delay=200000', 'users=5'])
    """
    rest, limits = [], []
    k = 0
    while k < len(argv):
        arg = argv[k]
        if arg == "--":
            rest += argv[k:]
            break
        if arg == "--limit":
            if k + 1 >= len(argv):
                raise HapticproofError("--limit expects NAME=N (e.g. --limit delay=200000)")
            limits.append(argv[k + 1])
            k += 2
            continue
        if arg.startswith("--limit="):
            limits.append(arg[len("--limit="):])
        else:
            rest.append(arg)
        k += 1
    return rest, limits


def _refuse_foreign_digits(argv: list[str]) -> None:
    """Numbers are written with the digits 0-9: ``int()`` (argparse's ``type=int``) and
    ``Fraction()`` would read Arabic-Indic and other decimal digits silently."""
    import os
    import unicodedata

    for arg in argv:
        if arg.isascii() or os.path.exists(arg):
            continue
        for ch in arg:
            if not ch.isascii() and unicodedata.category(ch) == "Nd":
                raise HapticproofError(f"argument {arg!r}: {ch!r} (U+{ord(ch):04X}) is not one of the digits 0-9; "
                                       "write numbers with the digits 0-9")


def main(argv: Sequence[str] | None = None) -> int:
    argv = list(sys.argv[1:] if argv is None else argv)
    # Exact results may have many digits (a delay of 47 samples at T = 1e-300): Python's guard
    # against slow int <-> str conversions would stop writing them. Inputs are bounded before any
    # work by core.limits (digits, exponents, degrees), so the conversions stay bounded too.
    if hasattr(sys, "set_int_max_str_digits") and 0 < sys.get_int_max_str_digits() < 10**6:
        sys.set_int_max_str_digits(10**6)
    previous = _catch_termination()
    try:
        return _main(argv)
    except HapticproofError as err:
        from hapticproof.core.escape import for_terminal

        print(f"hapticproof: error: {for_terminal(err)}", file=sys.stderr)     # one line, nothing that repaints
        return 2
    except Terminated as stop:      # SIGTERM, SIGHUP: as Ctrl-C, the temporary output is removed
        print(f"hapticproof: terminated ({stop})", file=sys.stderr)
        return 128 + stop.signal
    except KeyboardInterrupt:       # Ctrl-C: one line, no traceback; no output was replaced
        print("hapticproof: interrupted", file=sys.stderr)
        return 130
    except RecursionError:          # nesting within a raised --limit depth, beyond what Python recurses through
        print("hapticproof: error: the input is nested too deeply to read (nesting above a few hundred levels; "
              "lower --limit depth)", file=sys.stderr)
        return 2
    except BrokenPipeError:  # e.g. piped into `head`
        _quiet_stdout()
        return 0
    except OSError as err:          # standard output itself failed (a full disk, /dev/full)
        if getattr(err, "filename", None) is None and err.errno is not None:
            _quiet_stdout()
            print(f"hapticproof: error: cannot write the output: {err.strerror}", file=sys.stderr)
            return 2
        raise
    finally:
        _restore_signals(previous)
        from hapticproof.core.files import discard_temporaries

        discard_temporaries()


class Terminated(KeyboardInterrupt):
    """SIGTERM or SIGHUP arrived: raised in the main thread, so that every ``with``/``finally``
    block unwinds (a temporary output file is removed, worker pools are shut down) as for
    Ctrl-C."""

    def __init__(self, signum: int):
        import signal

        super().__init__(signal.Signals(signum).name)
        self.signal = signum


def _catch_termination() -> dict:
    """Turn SIGTERM and SIGHUP into :class:`Terminated` while a command runs (main thread only;
    returns the previous handlers)."""
    import signal
    import threading

    if threading.current_thread() is not threading.main_thread():
        return {}

    def stop(signum, _frame):
        raise Terminated(signum)

    previous = {}
    for name in ("SIGTERM", "SIGHUP"):
        number = getattr(signal, name, None)
        if number is None:
            continue
        try:
            previous[number] = signal.signal(number, stop)
        except (ValueError, OSError):
            pass
    return previous


def _restore_signals(previous: dict) -> None:
    import signal

    for number, handler in previous.items():
        try:
            signal.signal(number, handler)
        except (ValueError, OSError, TypeError):
            pass


def _quiet_stdout() -> None:
    """Standard output is gone: point it at /dev/null so that the interpreter's final flush
    does not print a second error."""
    import os

    try:
        devnull = os.open(os.devnull, os.O_WRONLY)
        os.dup2(devnull, sys.stdout.fileno())
    except (OSError, ValueError):
        pass


#: Thread-count variables of the BLAS libraries NumPy and SciPy may load.
BLAS_THREADS = ("OPENBLAS_NUM_THREADS", "OMP_NUM_THREADS", "MKL_NUM_THREADS")


def single_threaded_blas(environ: MutableMapping[str, str] | None = None) -> None:
    """One BLAS thread for this process (unless the user chose a count): the audit's matrices
    have a few dozen entries, where OpenBLAS's extra threads only spin -- on a busy 2-core
    machine they doubled the CPU time of a boundary search -- and its worker processes are the
    parallelism. ``environ`` defaults to ``os.environ``; it takes effect when NumPy is first
    imported (the command line imports it only after this).

    >>> env = {"MKL_NUM_THREADS": "4"}
    >>> single_threaded_blas(env); env["OPENBLAS_NUM_THREADS"], env["MKL_NUM_THREADS"]
    ('1', '4')
    """
    import os

    environ = os.environ if environ is None else environ
    for name in BLAS_THREADS:
        environ.setdefault(name, "1")


def _main(argv: list[str]) -> int:
    from hapticproof.core.limits import parse_limits, set_limits

    argv, limits = take_limits(argv)
    if limits:
        set_limits(parse_limits(limits))
    if argv and argv[0] == "audit":
        single_threaded_blas()
    _refuse_foreign_digits(argv)
    if argv and argv[0] in ("derive", "boundary") and "--scene" in " ".join(argv):
        from hapticproof.cli.derive import complete_argv

        argv = complete_argv(argv)
    parser = build_parser(argv[0] if argv else None, argv[1] if len(argv) > 1 else None)
    args = parser.parse_args(argv)
    status = int(args.handler(args) or 0)
    sys.stdout.flush()              # a failed write is reported here, not at exit
    return status
