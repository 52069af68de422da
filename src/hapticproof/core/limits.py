r"""The one place that bounds work before it starts.

Files, options and printed displays come from anyone, and a few characters can ask for
unbounded work: ``z**10**9``, ``K^{99999999}``, a 10 000-digit literal, ``--delay 1000000000``,
``--users 1000000000``, a grid of 10^10 points, 10^5 nested braces, a file of gigabytes.
Every reader checks what it is asked against :class:`Limits` *before* computing, and refuses
in one line that names the limit and how to raise it (:class:`LimitError`, exit 2 on the
command line). The defaults are far above what any paper or design needs:

=============  ==========  ===============================================================
limit          default     what it bounds
=============  ==========  ===============================================================
``file_size``  16 MiB      bytes of one input file (scene, paper, matrix, saved report)
``depth``      100         nesting of braces, parentheses, TOML/JSON arrays and tables
``digits``     1000        digits of one number: a literal, or a power of a number
``exponent``   1000        ``|k|`` of a power ``x^k`` written in an expression
``degree``     5000        degree in ``z`` or ``s`` an expression reaches (bound from its text)
``delay``      100000      a delay ``n = t_d/T`` in samples
``users``      1000        users of a multi-user scene
``minors``     4096        principal minors enumerated for one PSD decision (2^m - 1 for m users)
``grid``       1000000     points of a map or boundary grid
=============  ==========  ===============================================================

A user with a reason raises one for one run: ``hapticproof --limit delay=200000 derive ...``
(the option may stand anywhere on the command line, repeated for several), or from Python
with :func:`raised`:

>>> current().delay
100000
>>> with raised(delay=200000):
...     check("delay", 150000, "--delay")
>>> check("delay", 150000, "--delay")
Traceback (most recent call last):
...
hapticproof.core.limits.LimitError: --delay: 150000 samples is above the limit of 100000 (raise it with --limit delay=N)
"""

from __future__ import annotations

import contextlib
import functools
import math
from fractions import Fraction
from collections.abc import Iterator
from dataclasses import dataclass, fields, replace

from hapticproof.core.errors import InputFormatError

__all__ = ["Limits", "LimitError", "DEFAULT", "current", "raised", "set_limits", "parse_limits", "check",
           "check_number_text", "check_power", "check_minors", "degree_bound", "nesting_depth", "check_depth",
           "MUTANT_TEXT", "check_mutants"]


class LimitError(InputFormatError):
    """A request above one of the :class:`Limits` (refused before any work)."""


@dataclass(frozen=True, slots=True)
class Limits:
    """The bounds every reader checks before it computes (see the module's table).

    >>> Limits().replace(users=5000).users
    5000
    """

    file_size: int = 16 * 2**20
    depth: int = 100
    digits: int = 1000
    exponent: int = 1000
    degree: int = 5000
    delay: int = 100_000
    users: int = 1000
    minors: int = 4096
    grid: int = 1_000_000

    def __post_init__(self) -> None:
        for f in fields(self):
            value = getattr(self, f.name)
            if isinstance(value, bool) or not isinstance(value, int) or value < 1:
                raise LimitError(f"limit {f.name} must be a positive integer, got {value!r}")

    def replace(self, **values: int) -> Limits:
        unknown = sorted(set(values) - {f.name for f in fields(self)})
        if unknown:
            raise LimitError(f"unknown limit {unknown[0]!r} (limits: {', '.join(NAMES)})")
        return replace(self, **values)


#: The defaults.
DEFAULT = Limits()
NAMES = tuple(f.name for f in fields(Limits))

#: What each limit counts, for the refusal.
_UNITS = {"file_size": "bytes", "depth": "levels of nesting", "digits": "digits", "exponent": "",
          "degree": "", "delay": "samples", "users": "users", "minors": "principal minors", "grid": "points"}

_active: list[Limits] = [DEFAULT]


def current() -> Limits:
    """The limits in force (the defaults unless raised)."""
    return _active[-1]


def set_limits(limits: Limits) -> None:
    """Put ``limits`` in force for the rest of the process (the command line's ``--limit``)."""
    _active[-1] = limits


@contextlib.contextmanager
def raised(**values: int) -> Iterator[Limits]:
    """The current limits with ``values`` changed, for the duration of a ``with`` block."""
    _active.append(current().replace(**values))
    try:
        yield _active[-1]
    finally:
        _active.pop()


def parse_limits(items: list[str], base: Limits | None = None) -> Limits:
    """``["delay=200000", "users=5000"]`` (the ``--limit`` options) as :class:`Limits`.

    >>> parse_limits(["delay=200000"]).delay
    200000
    >>> parse_limits(["dealy=3"])
    Traceback (most recent call last):
    ...
    hapticproof.core.limits.LimitError: --limit dealy=3: unknown limit 'dealy' (limits: file_size, depth, digits, exponent, degree, delay, users, minors, grid)
    """
    limits = base or current()
    for item in items:
        name, sep, value = item.partition("=")
        name = name.strip().replace("-", "_")
        if name not in NAMES:
            raise LimitError(f"--limit {item}: unknown limit {name!r} (limits: {', '.join(NAMES)})")
        text = value.strip().replace("_", "")
        if not sep or not text.isascii() or not text.isdigit() or len(text) > 18 or int(text) < 1:
            raise LimitError(f"--limit {item}: expected {name}=N with a positive integer N")
        limits = limits.replace(**{name: int(text)})
    return limits


def check(name: str, value: int, where: str) -> None:
    """Refuse ``value`` when it is above the limit ``name`` (one line: where, what, how to raise it)."""
    limit = getattr(current(), name)
    if value > limit:
        unit = _UNITS[name]
        shown = f"{value} {unit}".strip() if value < 10**30 else f"a number of {len(str(value))} digits"
        raise LimitError(f"{where}: {shown} is above the limit of {limit} (raise it with --limit {name}=N)")


def check_number_text(text: str, where: str) -> None:
    """A number literal (``123``, ``0.5``, ``1e-3``, ``1e999999999``) within :attr:`Limits.digits`,
    decided from its text before it is converted (``10**999999999`` is never built).

    >>> check_number_text("1e-3", "--param T")
    >>> check_number_text("1e999999999", "--param K")
    Traceback (most recent call last):
    ...
    hapticproof.core.limits.LimitError: --param K: a number of about 1000000000 digits is above the limit of 1000 digits (raise it with --limit digits=N)
    """
    mantissa, _, exponent = text.strip().lower().replace("_", "").partition("e")
    digits = sum(ch.isdigit() for ch in mantissa)
    size = digits
    if exponent:
        exp = exponent.lstrip("+-")
        if len(exp) > 18:
            size = 10**18
        elif exp.isascii() and exp.isdigit():
            size = digits + int(exp)
    limit = current().digits
    if size > limit:
        raise LimitError(f"{where}: a number of about {size} digits is above the limit of {limit} digits "
                         "(raise it with --limit digits=N)")


def check_power(base: object, exponent: int, where: str, degree: int | None = None) -> None:
    """A power ``base^exponent`` within the limits before it is built: ``|exponent|`` at most
    :attr:`Limits.exponent`; a numeric base's power at most :attr:`Limits.digits` digits;
    ``degree`` (the base's degree in the transform variable, when known) times ``|exponent|``
    at most :attr:`Limits.degree`.

    >>> check_power(2, 16, "x")
    >>> check_power(2, 65536, "2^{2^{16}}")
    Traceback (most recent call last):
    ...
    hapticproof.core.limits.LimitError: 2^{2^{16}}: an exponent of 65536 is above the limit of 1000 (raise it with --limit exponent=N)
    """
    limits = current()
    k = abs(int(exponent))
    if k > limits.exponent:
        shown = k if k < 10**30 else f"{len(str(k))} digits"
        raise LimitError(f"{where}: an exponent of {shown} is above the limit of {limits.exponent} "
                         "(raise it with --limit exponent=N)")
    size = _digits_of(base)
    if size is not None and size * k > limits.digits + 1:
        raise LimitError(f"{where}: a number of about {size * k:.0f} digits is above the limit of {limits.digits} digits "
                         "(raise it with --limit digits=N)")
    if degree and degree * k > limits.degree:
        raise LimitError(f"{where}: a degree of {degree * k} is above the limit of {limits.degree} "
                         "(raise it with --limit degree=N)")


def check_minors(size: int, where: str, orders: object = None) -> None:
    """Refuse to enumerate the principal minors of a ``size x size`` matrix (of the given
    ``orders``, default all: ``2^size - 1``) when they are more than :attr:`Limits.minors`;
    counted before one is computed.

    >>> check_minors(12, "M(c)")
    >>> check_minors(100, "the residue matrix")
    Traceback (most recent call last):
    ...
    hapticproof.core.limits.LimitError: the residue matrix: 2^100 - 1 principal minors (of a 100 x 100 matrix) is above the limit of 4096 (raise it with --limit minors=N)
    """
    wanted = range(1, size + 1) if orders is None else sorted(set(orders))   # type: ignore[call-overload]
    count = sum(math.comb(size, k) for k in wanted)
    limit = current().minors
    if count > limit:
        shown = f"2^{size} - 1" if orders is None else str(count)
        raise LimitError(f"{where}: {shown} principal minors (of a {size} x {size} matrix) is above the limit of "
                         f"{limit} (raise it with --limit minors=N)")


def _digits_of(value: object) -> float | None:
    """Decimal digits of a rational number (the larger of numerator and denominator), or None
    when ``value`` is not a number (a symbol, an expression)."""
    if isinstance(value, bool):
        return None
    if isinstance(value, int):
        p, q = value, 1
    elif isinstance(value, Fraction):
        p, q = value.numerator, value.denominator
    elif isinstance(getattr(value, "p", None), int) and isinstance(getattr(value, "q", None), int):
        p, q = value.p, value.q           # a SymPy Rational or Integer
    else:
        return None
    largest = max(abs(p), abs(q))
    return math.log10(largest) if largest > 1 else 0.0


@functools.lru_cache(maxsize=8192)
def degree_bound(expr: object) -> int:
    """An upper bound on the total degree of a SymPy expression in its symbols (numerator and
    denominator alike; a function's arguments count as their own degree), computed from its
    tree without expanding anything.

    >>> import sympy as sp
    >>> x, y = sp.symbols("x y")
    >>> degree_bound((x**3 * y + 1)**4), degree_bound(1 / (x - 1))
    (16, 1)
    """
    import sympy as sp

    if not isinstance(expr, sp.Basic) or expr.is_Number or not expr.free_symbols:
        return 0
    if expr.is_Symbol:
        return 1
    if expr.is_Pow:
        base, exp = expr.args
        if exp.is_Integer:
            return abs(int(exp)) * degree_bound(base)
        return degree_bound(base) + degree_bound(exp)
    degrees = [degree_bound(arg) for arg in expr.args]
    if expr.is_Mul:
        return sum(degrees)
    return max(degrees, default=0)


def nesting_depth(text: str, opening: str = "{([", closing: str = "})]", escape: str | None = "\\") -> int:
    r"""The deepest nesting of the brackets in ``text`` (linear; a character after ``escape`` is
    skipped, so ``\{`` is no brace). Unbalanced text counts what it opens.

    >>> nesting_depth(r"\frac{a}{(b + \{c\})}")
    2
    """
    import re

    special = re.compile("[" + re.escape(opening + closing + (escape or "")) + "]")
    depth = deepest = 0
    k = 0
    while True:
        match = special.search(text, k)
        if match is None:
            return deepest
        ch, k = match.group(), match.end()
        if ch == escape:
            k += 1
        elif ch in opening:
            depth += 1
            if depth > deepest:
                deepest = depth
        else:
            depth = max(0, depth - 1)


def check_depth(text: str, where: str, opening: str = "{([", closing: str = "})]", escape: str | None = "\\") -> None:
    """Refuse ``text`` nested deeper than :attr:`Limits.depth` (before a recursive parser sees it)."""
    check("depth", nesting_depth(text, opening, closing, escape), where)


#: The characters the mutants of one display may hold together (each mutant is the whole display
#: changed once): ``audit --mutate`` of a 100 KB display would build gigabytes of text.
MUTANT_TEXT = 20_000_000


def check_mutants(count: int, length: int, where: str) -> None:
    """``count`` mutants of a display of ``length`` characters within :data:`MUTANT_TEXT`.

    >>> check_mutants(20_001, 1000, "p:3")
    Traceback (most recent call last):
    ...
    hapticproof.core.limits.LimitError: p:3: the mutants of a 1000-character display exceed 20000000 characters (mutate shorter displays, or others with --equation)
    """
    if count * length > MUTANT_TEXT:
        raise LimitError(f"{where}: the mutants of a {length}-character display exceed {MUTANT_TEXT} characters "
                         "(mutate shorter displays, or others with --equation)")
