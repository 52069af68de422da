r"""Reading a paper's source for ``hapticproof new-paper --from SOURCE``: its LaTeX (a ``.tex``
file, or a folder with the main file and its ``\input`` s) or a text/Markdown transcription with
``$$...$$`` displays, into a draft paper file for the reviewer to confirm.

- :mod:`~hapticproof.audit.source.tex` -- files (confined to the main file's folder, within
  budgets), tokens and TeX macro expansion;
- :mod:`~hapticproof.audit.source.displays` -- the displays, their labels, numbers and sections,
  and the LaTeX reader; :mod:`~hapticproof.audit.source.transcript` -- transcriptions;
  :mod:`~hapticproof.audit.source.read` -- the entry points :func:`read_source`, :func:`read_text`;
- :mod:`~hapticproof.audit.source.guess` -- the claim a display's shape suggests and the
  assumptions of its names;
- :mod:`~hapticproof.audit.source.draft` -- the paper file written from them (:func:`draft`).

Every mistake in a source is a :class:`SourceError` (an
:class:`~hapticproof.core.errors.InputFormatError`): one line, ``file:line: reason``.
"""

from hapticproof.audit.source.displays import Display, Section, Source
from hapticproof.audit.source.read import read_source, read_text
from hapticproof.audit.source.draft import Draft, draft
from hapticproof.audit.source.tex import SourceError

__all__ = ["Display", "Section", "Source", "SourceError", "read_source", "read_text", "Draft", "draft"]
