r"""The entry points of the source reader: a path (a ``.tex`` file, a folder holding the main file
and its ``\input`` files, a ``.txt``/``.md`` transcription) or a text, read into a
:class:`~hapticproof.audit.source.displays.Source`.

>>> src = read_text(r'''\section{Wall}
... \newcommand{\half}[1]{\frac{#1}{2}}
... \begin{equation} b > \half{KT} + B \label{eq:wall} \end{equation}''', "wall.tex")
>>> d = src.displays[0]
>>> d.text, d.original, d.label, d.number, d.section.id, d.line
('b > \\frac{KT}{2} + B', 'b > \\half{KT} + B \\label{eq:wall}', 'eq:wall', '1', '1', 3)
"""

from __future__ import annotations

import os
from pathlib import Path

from hapticproof.audit.source.displays import LATEX_SUFFIXES, TEXT_SUFFIXES, LatexReader, Reader, Source
from hapticproof.audit.source.tex import MAX_BYTES, MAX_FILES, Expander, Files, SourceError
from hapticproof.audit.source.transcript import TextReader

__all__ = ["read_source", "read_text"]


def _mode_of(name: str, text: str) -> str:
    lower = name.lower()
    if lower.endswith(LATEX_SUFFIXES):
        return "latex"
    if lower.endswith(TEXT_SUFFIXES):
        return "text"
    head = text[:20000]
    return "latex" if ("\\documentclass" in head or "\\begin{document}" in head) else "text"


def _main_file(folder: Path, max_bytes: int) -> Path:
    """The main file of a folder: the one ``.tex`` file with ``\\documentclass`` (else the only
    ``.tex`` file, else the only text file)."""
    entries = sorted(p for p in folder.iterdir() if p.is_file() and not p.is_symlink())
    tex = [p for p in entries if p.suffix.lower() in LATEX_SUFFIXES]
    mains = []
    for p in tex[:MAX_FILES]:
        try:
            with open(p, "rb") as handle:
                head = handle.read(min(max_bytes, 200_000))
        except OSError:
            continue
        if b"\\documentclass" in head:
            mains.append(p)
    if len(mains) == 1:
        return mains[0]
    for preferred in ("main.tex", "paper.tex", "ms.tex", "manuscript.tex"):
        if any(p.name == preferred for p in mains or tex):
            return folder / preferred
    if not mains and len(tex) == 1:
        return tex[0]
    if mains or tex:
        names = ", ".join(p.name for p in (mains or tex)[:6])
        raise SourceError(f"{folder}: more than one main file ({names}); name the main file instead of the folder")
    texts = [p for p in entries if p.suffix.lower() in TEXT_SUFFIXES]
    if len(texts) == 1:
        return texts[0]
    raise SourceError(f"{folder}: no .tex file (and not exactly one .txt/.md transcription) to read")


def read_source(path: str | os.PathLike, *, max_bytes: int = MAX_BYTES, max_files: int = MAX_FILES,
                mode: str | None = None) -> Source:
    r"""Read the displays of a paper source (a file or a folder holding the main file).

    Parameters
    ----------
    path : str or PathLike
        A ``.tex`` file, a folder with the main ``.tex`` file and its ``\input`` files, or a
        ``.txt``/``.md`` transcription.
    max_bytes : int
        Bytes read in all files together.
    max_files : int
        Files read in all (``\input`` ones included).
    mode : {"latex", "text"}, optional
        Overrides the mode guessed from the suffix (``.tex``: LaTeX; ``.txt``/``.md``: text) or,
        for other names, from a ``\documentclass``.

    Returns
    -------
    Source

    Raises
    ------
    SourceError
        One line naming the file and line.

    Examples
    --------
    >>> import tempfile, pathlib
    >>> folder = pathlib.Path(tempfile.mkdtemp())
    >>> _ = (folder / "paper.txt").write_text("2 WALL\n\n$$b > \\frac{KT}{2} + B \\tag{3}$$\n")
    >>> [(d.number, d.text, d.section.id) for d in read_source(folder / "paper.txt").displays]
    [('3', 'b > \\frac{KT}{2} + B', '2')]
    >>> try:
    ...     read_source("no/such/paper.tex")
    ... except SourceError as err:
    ...     print(err)
    no/such/paper.tex: no such file or folder
    """
    given = Path(path)
    if not given.exists():
        raise SourceError(f"{given}: no such file or folder")
    if given.is_dir():
        given = _main_file(given, max_bytes)
    elif not given.is_file():
        raise SourceError(f"{given}: not a regular file")
    files = Files(given.parent, max_bytes, max_files)
    main = files.read(given, str(given))
    return _read(files, main, mode or _mode_of(given.name, files.texts[main]), str(given))


def read_text(text: str, name: str = "<text>", *, mode: str | None = None) -> Source:
    r"""Read the displays of a source given as a string (``\input`` is refused: no folder).

    >>> [d.text for d in read_text("$$a = b$$\n\n$$c > d \\tag{2}$$", "t.md").displays]
    ['a = b', 'c > d']
    """
    files = Files(None, MAX_BYTES, MAX_FILES)
    if len(text.encode("utf-8", "surrogatepass")) > MAX_BYTES:
        raise SourceError(f"{name}: too large (the limit is {MAX_BYTES} bytes)")
    main = files.add(name, text.lstrip("\ufeff").replace("\r\n", "\n").replace("\r", "\n"))
    return _read(files, main, mode or _mode_of(name, text), name)


def _read(files: Files, main: int, mode: str, path: str) -> Source:
    if mode not in ("latex", "text"):
        raise SourceError(f"{path}: mode must be 'latex' or 'text', got {mode!r}")
    warnings: list[str] = []
    expander = Expander(files, inputs=mode == "latex", warnings=warnings, budget=100_000)
    reader: Reader = (LatexReader if mode == "latex" else TextReader)(files, expander)
    reader.warnings = warnings
    reader.read(main)
    return Source(path, mode, reader.displays, reader.sections, list(files.names),
                  {name: macro.params for name, macro in expander.macros.items()}, warnings,
                  title=getattr(reader, "title", ""))
