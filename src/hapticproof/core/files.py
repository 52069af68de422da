r"""Files in and out, as strangers hand them over: read bounded and decoded, named only inside
their folder, written whole or not at all.

Reading
    :func:`read_text` reads an input file (``-`` is standard input) up to
    :attr:`~hapticproof.core.limits.Limits.file_size` bytes, as UTF-8 (a UTF-8 byte-order mark
    is skipped; other bytes are one line naming the file, the line and the column, never the
    content). :func:`file_in_folder` resolves a file *named inside* a scene or paper file:
    relative to that file's folder only -- never absolute, never through ``..``, never out of the
    folder through a symbolic link -- and :func:`read_text` with ``regular_only`` reads it only
    if it is a regular file (no ``/dev/zero``, no ``/dev/stdin``, no FIFO that blocks).
    :func:`read_json` checks the nesting depth before :mod:`json` (recursive) sees the text.

Writing
    :func:`check_output` refuses, before any work, an output that cannot be written: a
    symbolic link (even a dangling one), a FIFO, a device, a directory, a parent that is missing
    or a file, a read-only file or folder, a wrong suffix, or one of the command's own inputs.
    :func:`write_output` is the one writer of every format and figure (``-`` is standard
    output; :func:`write_figure` renders a figure in memory first): :func:`write_atomic` and
    :class:`AtomicOutput` write to a temporary file beside the target and rename it over the
    target when it is complete -- a failed or interrupted write (Ctrl-C, SIGTERM) leaves the
    previous file as it was and no temporary file, no reader ever sees a half-written one, and
    no link is ever written through. No directory is ever created.

>>> import tempfile, pathlib
>>> folder = pathlib.Path(tempfile.mkdtemp())
>>> write_atomic(folder / "r.txt", "all or nothing\n")
PosixPath('...r.txt')
>>> read_text(folder / "r.txt")
'all or nothing\n'
>>> file_in_folder(".", "/etc/shadow", "scene.toml:3: matrix", "scene.toml")
Traceback (most recent call last):
...
hapticproof.core.files.FileAccessError: scene.toml:3: matrix: '/etc/shadow' is an absolute path; name a file in the folder of scene.toml (relative, without '..')
"""

from __future__ import annotations

import atexit
import contextlib
import io
import json
import os
import re
import stat
import sys
import tempfile
from collections.abc import Iterable
from pathlib import Path
from typing import IO, Any

from hapticproof.core.errors import InputFormatError
from hapticproof.core.limits import current

__all__ = ["FileAccessError", "OutputError", "check_output_folder", "read_text", "decode_text", "file_in_folder", "read_json", "toml_depth",
           "check_output", "write_atomic", "AtomicOutput", "same_file"]


class FileAccessError(InputFormatError):
    """An input file that may not or cannot be read (one line; its content is never shown)."""


class OutputError(InputFormatError):
    """An output that cannot be written where it was asked (one line, before any work if possible)."""


_BOM = b"\xef\xbb\xbf"


def _reason(err: OSError) -> str:
    return err.strerror or type(err).__name__


def decode_text(data: bytes, name: str) -> str:
    r"""``data`` as UTF-8 text (a leading byte-order mark dropped); other encodings are one line
    naming the place of the first bad byte (the byte's value, never the text around it).

    >>> decode_text(b"\xef\xbb\xbfa = 1\n", "s.toml")
    'a = 1\n'
    >>> decode_text(b"a = 1\nb = '\xe9'\n", "s.toml")
    Traceback (most recent call last):
    ...
    hapticproof.core.files.FileAccessError: s.toml:2: not UTF-8 text (byte 0xe9 at column 6); save the file as UTF-8
    """
    if data.startswith(_BOM):
        data = data[len(_BOM):]
    elif data[:2] in (b"\xff\xfe", b"\xfe\xff"):
        raise FileAccessError(f"{name}: UTF-16 text; save the file as UTF-8")
    try:
        return data.decode("utf-8")
    except UnicodeDecodeError as err:
        line = data.count(b"\n", 0, err.start) + 1
        column = err.start - (data.rfind(b"\n", 0, err.start) + 1) + 1
        raise FileAccessError(f"{name}:{line}: not UTF-8 text (byte 0x{data[err.start]:02x} at column {column}); "
                              "save the file as UTF-8") from None


def _read_bounded(stream: IO[bytes], name: str, limit: int) -> bytes:
    chunks, size = [], 0
    while True:
        chunk = stream.read(min(1 << 20, limit + 1 - size))
        if not chunk:
            break
        chunks.append(chunk)
        size += len(chunk)
        if size > limit:
            raise FileAccessError(f"{name}: larger than the limit of {limit} bytes "
                                  "(raise it with --limit file_size=N)")
    return b"".join(chunks)


def read_text(path: str | Path, name: str | None = None, *, regular_only: bool = False) -> str:
    """The text of an input file (``-``: standard input), at most
    :attr:`~hapticproof.core.limits.Limits.file_size` bytes, decoded by :func:`decode_text`.

    ``name`` is how errors call the file (default: the path). ``regular_only`` (files named
    inside other files) refuses anything but a regular file -- devices, FIFOs, sockets,
    directories -- without blocking on it.
    """
    shown = name or str(path)
    limit = current().file_size
    if str(path) == "-" and not regular_only:
        return decode_text(_read_bounded(sys.stdin.buffer, "<stdin>", limit), "<stdin>")
    flags = os.O_RDONLY | getattr(os, "O_NOCTTY", 0) | (os.O_NONBLOCK if regular_only else 0)
    try:
        fd = os.open(os.fspath(path), flags)
    except OSError as err:
        raise FileAccessError(f"cannot read {shown}: {_reason(err)}") from None
    try:
        info = os.fstat(fd)
    except OSError as err:
        os.close(fd)
        raise FileAccessError(f"cannot read {shown}: {_reason(err)}") from None
    if stat.S_ISDIR(info.st_mode):
        os.close(fd)
        raise FileAccessError(f"cannot read {shown}: it is a directory")
    with os.fdopen(fd, "rb") as stream:
        try:
            if regular_only and not stat.S_ISREG(info.st_mode):
                raise FileAccessError(f"cannot read {shown}: not a regular file")
            if stat.S_ISREG(info.st_mode) and info.st_size > limit:
                raise FileAccessError(f"{shown}: {info.st_size} bytes is larger than the limit of {limit} bytes "
                                      "(raise it with --limit file_size=N)")
            if regular_only:
                os.set_blocking(fd, True)
            data = _read_bounded(stream, shown, limit)
        except OSError as err:
            raise FileAccessError(f"cannot read {shown}: {_reason(err)}") from None
    return decode_text(data, shown)


def file_in_folder(folder: str | Path | None, name: Any, where: str, owner: str | None = None) -> Path:
    """The path of a file that a scene or paper file (``owner``, for messages) in ``folder``
    (``None``: the current folder, for text without a file) names as ``name``: relative to
    that folder, without ``..``, not leaving it through a symbolic link. Read it with
    ``read_text(path, regular_only=True)``.

    >>> file_in_folder("papers", "z.txt", "mine.toml:4", "papers/mine.toml")
    PosixPath('papers/z.txt')
    >>> file_in_folder("papers", "../../x", "mine.toml:4: matrix", "papers/mine.toml")
    Traceback (most recent call last):
    ...
    hapticproof.core.files.FileAccessError: mine.toml:4: matrix: '../../x' leaves the folder of papers/mine.toml ('..'); name a file in that folder
    """
    base = Path(folder) if folder is not None else Path(".")
    of = f"the folder of {owner}" if owner else ("the folder " + str(base) if folder is not None else "the current folder")
    if not isinstance(name, str) or not name.strip():
        raise FileAccessError(f"{where}: expected a file name, got {type(name).__name__}")
    if any(ord(ch) < 32 or ord(ch) == 127 for ch in name):
        raise FileAccessError(f"{where}: a file name without control characters is needed")
    if name.startswith(("/", "\\", "~")) or os.path.isabs(name) or (len(name) > 1 and name[1] == ":"):
        raise FileAccessError(f"{where}: {name!r} is an absolute path; name a file in {of} (relative, without '..')")
    if ".." in name.replace("\\", "/").split("/"):
        raise FileAccessError(f"{where}: {name!r} leaves {of} ('..'); name a file in that folder")
    path = base / name
    try:
        inside = path.resolve().is_relative_to(base.resolve())
    except (OSError, RuntimeError):     # a symbolic-link loop
        inside = False
    if not inside:
        raise FileAccessError(f"{where}: {name!r} leads out of {of} (a symbolic link); name a file in that folder")
    return path


_JSON_SPECIAL = re.compile(r'["\[\]{}]')
_JSON_STRING_END = re.compile(r'(?:[^"\\]|\\.)*"', re.S)


def _json_depth(text: str) -> int:
    """The deepest nesting of arrays and objects in JSON text (strings skipped; linear, and
    only the brackets and quotes are looked at one by one)."""
    depth = deepest = 0
    k = 0
    while True:
        match = _JSON_SPECIAL.search(text, k)
        if match is None:
            return deepest
        ch, k = match.group(), match.end()
        if ch == '"':
            end = _JSON_STRING_END.match(text, k)
            if end is None:
                return deepest
            k = end.end()
        elif ch in "[{":
            depth += 1
            deepest = max(deepest, depth)
        else:
            depth -= 1


_TOML_SPECIAL = re.compile(r"""["'#\[\]{}]""")


def toml_depth(text: str) -> int:
    """The deepest nesting of arrays and inline tables in TOML text (strings and comments
    skipped, a header ``[[x]]`` counting 2; linear).

    >>> toml_depth('a = [[1], {b = "[[["}]  # [[[\\n[[x]]')
    2
    """
    depth = deepest = 0
    k, n = 0, len(text)
    while k < n:
        match = _TOML_SPECIAL.search(text, k)
        if match is None:
            break
        ch, k = match.group(), match.start()
        if ch == "#":
            end = text.find("\n", k)
            k = n if end < 0 else end
            continue
        if ch in "\"'":
            triple = text.startswith(ch * 3, k)
            quote = ch * 3 if triple else ch
            j = k + len(quote)
            while True:
                found = text.find(quote, j)
                newline = -1 if triple else text.find("\n", j)
                if found < 0 or (newline >= 0 and newline < found):
                    j = n if found < 0 and newline < 0 else (newline if newline >= 0 else n)
                    break
                backslashes = 0
                while ch == '"' and found - 1 - backslashes >= j and text[found - 1 - backslashes] == "\\":
                    backslashes += 1
                if backslashes % 2 == 0:
                    j = found
                    break
                j = found + 1
            k = j + len(quote)
            continue
        if ch in "[{":
            depth += 1
            deepest = max(deepest, depth)
        else:
            depth = max(0, depth - 1)
        k += 1
    return deepest


def read_json(text: str, name: str, parse_float: Any = None) -> Any:
    """Parse JSON text of the file ``name``: nesting within
    :attr:`~hapticproof.core.limits.Limits.depth`, every number within
    :attr:`~hapticproof.core.limits.Limits.digits` (decided from its text, integers included;
    ``1e999999`` is refused, never read as infinity), a key given twice in one object refused
    (which one would count?), a syntax error as one line with the place, ``NaN``/``Infinity``
    refused (not JSON).

    >>> read_json('{"a": [1, 2]}', "r.json")
    {'a': [1, 2]}
    >>> read_json('[' * 1000 + ']' * 1000, "r.json")
    Traceback (most recent call last):
    ...
    hapticproof.core.limits.LimitError: r.json: 1000 levels of nesting is above the limit of 100 (raise it with --limit depth=N)
    >>> read_json('{"verdict": "proved", "verdict": "disproved"}', "r.json")
    Traceback (most recent call last):
    ...
    hapticproof.core.errors.InputFormatError: r.json: not JSON (the key 'verdict' is given twice in one object)
    >>> read_json('{"inputs": 1e999999}', "r.json")
    Traceback (most recent call last):
    ...
    hapticproof.core.limits.LimitError: r.json: a JSON number: a number of about 1000000 digits is above the limit of 1000 digits (raise it with --limit digits=N)
    """
    import math

    from hapticproof.core.limits import LimitError, check, check_number_text

    if text.startswith("\ufeff"):
        text = text[1:]
    check("depth", _json_depth(text), name)

    def refuse(constant: str) -> Any:
        raise ValueError(f"{constant} is not JSON")

    def integer(digits: str) -> int:
        check_number_text(digits, f"{name}: a JSON number")
        return int(digits)

    def real(digits: str) -> Any:
        check_number_text(digits, f"{name}: a JSON number")
        value = (parse_float or float)(digits)
        if isinstance(value, float) and not math.isfinite(value):
            raise ValueError(f"the number {digits[:40]} is outside the range of a double")
        return value

    def unique(pairs: list[tuple[str, Any]]) -> dict[str, Any]:
        out: dict[str, Any] = {}
        for key, value in pairs:
            if key in out:
                raise ValueError(f"the key {key[:60]!r} is given twice in one object")
            out[key] = value
        return out

    try:
        return json.loads(text, parse_constant=refuse, parse_float=real, parse_int=integer, object_pairs_hook=unique)
    except LimitError:
        raise
    except json.JSONDecodeError as err:
        raise InputFormatError(f"{name}:{err.lineno}: not JSON ({err.msg} at column {err.colno})") from None
    except ValueError as err:
        raise InputFormatError(f"{name}: not JSON ({err})") from None
    except RecursionError:
        raise InputFormatError(f"{name}: nested too deeply") from None


# ---------------------------------------------------------------------------------------------
# outputs
# ---------------------------------------------------------------------------------------------


def same_file(a: str | Path, b: str | Path) -> bool:
    """Whether two paths name the same existing file (links and ``..`` resolved)."""
    try:
        return os.path.samefile(a, b)
    except OSError:
        return os.path.realpath(a) == os.path.realpath(b)


_KINDS = ((stat.S_ISFIFO, "a FIFO (named pipe)"), (stat.S_ISCHR, "a character device"), (stat.S_ISBLK, "a block device"),
          (stat.S_ISSOCK, "a socket"))


def refuse_special(path: str | Path, option: str = "--output") -> None:
    """Fail if the output ``path`` itself is a symbolic link (even one that points nowhere), a
    FIFO, a device or a socket: an output is a regular file, written whole beside its name and
    renamed over it, never written through a link or into a special file. (``-`` is standard
    output: the callers never pass it here.)

    >>> import tempfile, pathlib, os
    >>> folder = pathlib.Path(tempfile.mkdtemp())
    >>> os.symlink("/nowhere/at/all", folder / "r.html")
    >>> refuse_special(folder / "r.html", "-o")
    Traceback (most recent call last):
    ...
    hapticproof.core.files.OutputError: -o ...r.html: is a symbolic link; an output is never written through a link (remove the link or name another file)
    """
    text = str(path)
    try:
        info = os.lstat(path)
    except (FileNotFoundError, NotADirectoryError):     # (a parent that is a file: the caller says so)
        return
    except OSError as err:
        raise OutputError(f"{option} {text}: {_reason(err)}") from None
    if stat.S_ISLNK(info.st_mode):
        raise OutputError(f"{option} {text}: is a symbolic link; an output is never written through a link "
                          "(remove the link or name another file)")
    if stat.S_ISDIR(info.st_mode):
        raise OutputError(f"{option} {text}: is a directory")
    for test, kind in _KINDS:
        if test(info.st_mode):
            raise OutputError(f"{option} {text}: is {kind}, not a regular file; name a regular file "
                              "('-' is standard output)")


def check_output(path: str | Path | None, option: str, suffixes: tuple[str, ...] = (),
                 inputs: Iterable[str | Path | None] = ()) -> None:
    """Fail, before any work, if ``path`` cannot be an output: a wrong suffix, a symbolic link
    (even a dangling one), a FIFO, a device or a socket (:func:`refuse_special`), a directory, a
    missing parent folder (none is created) or one that is a file, a file or folder that is not
    writable, or one of ``inputs`` (the command's own input files). ``-`` and ``None``
    (standard output) are always fine.

    >>> check_output("-", "--csv"); check_output("out.csv", "--csv", (".csv",))
    >>> check_output("out.txt", "--plot", (".png", ".pdf", ".svg"))
    Traceback (most recent call last):
    ...
    hapticproof.core.files.OutputError: --plot out.txt: the file name must end in .png, .pdf or .svg
    >>> check_output("/nonexistent/dir/r.html", "-o")
    Traceback (most recent call last):
    ...
    hapticproof.core.files.OutputError: -o /nonexistent/dir/r.html: the folder /nonexistent/dir does not exist (create it first)
    >>> check_output("/dev/null", "-o")
    Traceback (most recent call last):
    ...
    hapticproof.core.files.OutputError: -o /dev/null: is a character device, not a regular file; name a regular file ('-' is standard output)
    """
    if path is None or str(path) == "-":
        return
    text = str(path)
    target = Path(text)
    if not text.strip() or text.endswith(("/", os.sep)):
        raise OutputError(f"{option} {text!r}: a file name is needed")
    if any(ord(ch) < 32 or ord(ch) == 127 for ch in text):
        raise OutputError(f"{option} {text!r}: a file name without control characters is needed")
    if suffixes and target.suffix.lower() not in suffixes:
        shown = ", ".join(suffixes[:-1]) + (" or " if len(suffixes) > 1 else "") + suffixes[-1]
        raise OutputError(f"{option} {text}: the file name must end in {shown}")
    refuse_special(target, option)
    for source in inputs:
        if source is not None and str(source) != "-" and os.path.exists(source) and same_file(source, target):
            raise OutputError(f"{option} {text}: is an input of this command ({source}); write the output elsewhere")
    parent = Path(os.path.abspath(target)).parent
    if not parent.exists():
        shown_parent = target.parent if str(target.parent) not in ("", ".") else parent
        raise OutputError(f"{option} {text}: the folder {shown_parent} does not exist (create it first)")
    if not parent.is_dir():
        raise OutputError(f"{option} {text}: {parent} is not a directory")
    if os.path.lexists(target):
        mode = os.lstat(target).st_mode
        if not os.access(target, os.W_OK) or not mode & 0o222:   # (root may write anyway)
            raise OutputError(f"{option} {text}: the file is read-only")
    if not os.access(parent, os.W_OK | os.X_OK):
        raise OutputError(f"{option} {text}: the folder {parent} is not writable")


def check_output_folder(path: str | Path, option: str, names: Iterable[str] = ()) -> None:
    """Fail, before any work, if the folder ``path`` cannot take a command's outputs: a
    symbolic link (outputs are never written through a link), a file, a FIFO or a device where a
    folder is named, a folder that is not writable, or an output file ``names`` inside it that
    :func:`check_output` refuses. A folder that does not exist yet is fine (it is created).

    >>> check_output_folder("/dev/null", "-o")
    Traceback (most recent call last):
    ...
    hapticproof.core.files.OutputError: -o /dev/null: is a character device, not a folder
    """
    text = str(path)
    if not text.strip() or any(ord(ch) < 32 or ord(ch) == 127 for ch in text):
        raise OutputError(f"{option} {text!r}: a folder name is needed")
    try:
        info = os.lstat(text)
    except FileNotFoundError:
        return
    except OSError as err:
        raise OutputError(f"{option} {text}: {_reason(err)}") from None
    if stat.S_ISLNK(info.st_mode):
        raise OutputError(f"{option} {text}: is a symbolic link; outputs are never written through a link "
                          "(remove the link or name another folder)")
    if not stat.S_ISDIR(info.st_mode):
        kind = next((k for test, k in _KINDS if test(info.st_mode)), "a file")
        raise OutputError(f"{option} {text}: is {kind}, not a folder")
    if not os.access(text, os.W_OK | os.X_OK):
        raise OutputError(f"{option} {text}: the folder is not writable")
    for name in names:
        check_output(os.path.join(text, name), option)


#: Temporary files being written now: removed when the write fails, when the process is
#: interrupted (Ctrl-C, SIGTERM: the command line turns both into an exception) and, as a last
#: resort, at exit (:func:`discard_temporaries`).
_LIVE: set[str] = set()


def discard_temporaries() -> None:
    """Remove every temporary output file this process is still writing (the targets are left
    as they were)."""
    for temp in list(_LIVE):
        with contextlib.suppress(OSError):
            os.unlink(temp)
        _LIVE.discard(temp)


atexit.register(discard_temporaries)


class AtomicOutput:
    r"""A file written whole or not at all: the data goes to a temporary file beside the target
    (same folder, so the rename is atomic), which :meth:`commit` renames over the target; leaving
    the ``with`` block without :meth:`commit` (an error, Ctrl-C, SIGTERM) removes it and the
    target is untouched. The target must be a regular file or not exist (:func:`refuse_special`,
    checked again when the write starts): a symbolic link is never followed -- the rename
    replaces a name, never the file a link points to -- and FIFOs and devices are refused.

    >>> import tempfile, pathlib
    >>> target = pathlib.Path(tempfile.mkdtemp()) / "map.csv"
    >>> with AtomicOutput(target, "map") as out:
    ...     _ = out.stream.write("x,y\n")
    ...     _ = out.commit()
    >>> target.read_text()
    'x,y\n'
    """

    def __init__(self, path: str | Path, option: str = "--output", binary: bool = False):
        self.path = Path(path)
        self.option = option
        self.binary = binary
        self.temp: str | None = None
        self.stream: Any = None
        self.done = False

    def __enter__(self) -> AtomicOutput:
        refuse_special(self.path, self.option)
        folder = Path(os.path.abspath(self.path)).parent
        try:
            fd, temp = tempfile.mkstemp(prefix=f".{self.path.name}.", suffix=".tmp", dir=folder)
        except OSError as err:
            raise OutputError(f"cannot write {self.path}: {_reason(err)}") from None
        self.temp = temp
        _LIVE.add(temp)
        with contextlib.suppress(OSError):
            os.fchmod(fd, _mode_for(self.path))
        self.stream = os.fdopen(fd, "wb") if self.binary else io.open(fd, "w", encoding="utf-8", newline="")
        return self

    def commit(self) -> Path:
        """Flush, sync and rename the temporary file over the target."""
        try:
            self.stream.flush()
            os.fsync(self.stream.fileno())
            self.stream.close()
            os.replace(self.temp, self.path)      # replaces the name: a link planted meanwhile is replaced, not followed
            _LIVE.discard(self.temp)
            self.temp = None
        except OSError as err:
            self._discard()
            raise OutputError(f"cannot write {self.path}: {_reason(err)}") from None
        self.done = True
        return self.path

    def _discard(self) -> None:
        with contextlib.suppress(Exception):
            self.stream.close()
        if self.temp is not None:
            with contextlib.suppress(OSError):
                os.unlink(self.temp)
            _LIVE.discard(self.temp)
            self.temp = None

    def __exit__(self, *exc: Any) -> None:
        if not self.done:
            self._discard()


def _mode_for(target: Path) -> int:
    """The permissions of the regular file being replaced, else those a new file gets (umask)."""
    try:
        info = os.lstat(target)
        if stat.S_ISREG(info.st_mode):
            return stat.S_IMODE(info.st_mode)
    except OSError:
        pass
    mask = os.umask(0)
    os.umask(mask)
    return 0o666 & ~mask


def write_atomic(path: str | Path, data: str | bytes, option: str = "--output") -> Path:
    """Write ``data`` (text as UTF-8, or bytes) to ``path`` through :class:`AtomicOutput`; an
    error (disk full, ...) is one :class:`OutputError` line and the previous file stays whole."""
    binary = isinstance(data, bytes)
    with AtomicOutput(path, option, binary=binary) as out:
        try:
            out.stream.write(data)
        except OSError as err:
            raise OutputError(f"cannot write {path}: {_reason(err)}") from None
        return out.commit()


def write_output(path: str | Path | None, data: str | bytes, option: str = "--output") -> Path | None:
    """The one writer of every output: ``-`` or ``None`` is standard output, anything else a file
    through :func:`write_atomic`; text gets a final newline either way (a file the same as the
    output it replaces); returns the file written (``None`` for standard output).

    >>> write_output("-", "to standard output")
    to standard output
    """
    if path is None or str(path) == "-":
        if isinstance(data, bytes):
            sys.stdout.flush()
            sys.stdout.buffer.write(data)
            sys.stdout.buffer.flush()
        else:
            sys.stdout.write(data if data.endswith("\n") else data + "\n")
        return None
    if isinstance(data, str) and data and not data.endswith("\n"):
        data += "\n"
    return write_atomic(path, data, option)


def write_figure(figure: Any, path: str | Path, option: str = "--plot", dpi: int = 110) -> Path:
    """A matplotlib figure rendered in memory (the format from the suffix: ``.png``, ``.pdf``,
    ``.svg``) and written by :func:`write_atomic`: figures go through the same writer as every
    other output (no link followed, no FIFO or device replaced, no partial file)."""
    path = Path(path)
    buffer = io.BytesIO()
    figure.savefig(buffer, dpi=dpi, bbox_inches="tight", format=path.suffix.lstrip(".").lower() or "png")
    return write_atomic(path, buffer.getvalue(), option)


__all__ += ["discard_temporaries", "refuse_special", "write_figure", "write_output"]
