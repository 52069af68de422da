r"""Text from strangers made inert for each view, in one place.

Titles, ids, printed displays, names and details come from paper files and saved reports, i.e.
from anyone. Each view escapes them for its own format here:

* :func:`for_terminal` -- a terminal (tables, summaries, error lines): control characters
  (C0, DEL, C1: escape sequences that move the cursor, repaint or retitle the window) and the
  invisible bidirectional controls that reorder what is shown are written as visible escapes
  (``\x1b``, ``\u202e``); a line break too unless the view is multi-line;
* :func:`for_markdown` -- Markdown text (a heading, a table cell): ``<``, ``>`` and ``&`` as
  character references, so no raw HTML reaches a Markdown viewer; Markdown's own punctuation
  backslash-escaped, ``|`` too (table cells), line breaks as spaces;
* :func:`for_markdown_code` -- an inline code span (LaTeX in a table cell): a backtick fence
  longer than any run inside it, ``|`` escaped for the table;
* :func:`for_html` -- HTML text and attribute values (the whole page is also sanitised and
  carries a Content-Security-Policy: :mod:`hapticproof.report.sanitize`);
* :func:`for_latex` -- plain text in a LaTeX report (:func:`hapticproof.core.texsafe.escape_tex_text`,
  which checks its own output the way TeX reads it); displays are checked, not escaped
  (:func:`hapticproof.core.texsafe.check_tex`).

>>> for_terminal("ok\x1b[2J\x1b]0;pwned\x07")
'ok\\x1b[2J\\x1b]0;pwned\\x07'
>>> for_markdown("<img src=x onerror=alert(1)> *b* | c")
'&lt;img src=x onerror=alert(1)&gt; \\*b\\* \\| c'
>>> for_markdown_code("a `b` | c")
'`` a `b` \\| c ``'
"""

from __future__ import annotations

import html
import re
import unicodedata

__all__ = ["for_html", "for_latex", "for_markdown", "for_markdown_code", "for_terminal"]

#: invisible characters that reorder or hide what a terminal or viewer shows (bidirectional
#: embeddings, overrides and isolates; the line and paragraph separators)
_INVISIBLE = frozenset("\u200e\u200f\u202a\u202b\u202c\u202d\u202e\u2066\u2067\u2068\u2069\u2028\u2029\u061c")


def _visible(ch: str) -> str:
    code = ord(ch)
    return f"\\x{code:02x}" if code < 0x100 else f"\\u{code:04x}"


def _unsafe(ch: str, keep: str) -> bool:
    if ch in keep:
        return False
    return ch in _INVISIBLE or unicodedata.category(ch) == "Cc"


def for_terminal(text: object, multiline: bool = False) -> str:
    r"""``text`` with every control character shown as a visible escape (``\x1b``, ``\u202e``):
    nothing in it can move the cursor, repaint the screen or reorder the line. ``multiline``
    keeps line breaks (and tabs), else they are escaped too (one line stays one line).

    >>> for_terminal("a\nb"), for_terminal("a\nb", multiline=True)
    ('a\\x0ab', 'a\nb')
    """
    text = str(text)
    keep = "\n\t" if multiline else ""
    if all(ch.isprintable() or ch in keep for ch in text):
        return text
    return "".join(_visible(ch) if _unsafe(ch, keep) else ch for ch in text)


_MARKDOWN_PUNCTUATION = re.compile(r"([\\`*_\[\]#!|~])")


def for_markdown(text: object) -> str:
    r"""``text`` as literal Markdown text (a heading or a table cell): HTML's ``<``, ``>``, ``&``
    as character references, Markdown's punctuation backslash-escaped, line breaks as spaces,
    control characters as visible escapes.

    >>> for_markdown("K*T/2 > b_1")
    'K\\*T/2 &gt; b\\_1'
    """
    text = for_terminal(" ".join(str(text).splitlines()) if text is not None else "")
    text = html.escape(text, quote=False)
    return _MARKDOWN_PUNCTUATION.sub(r"\\\1", text)


def for_markdown_code(text: object) -> str:
    r"""``text`` as one inline code span (literal in every Markdown viewer: no HTML, no
    emphasis): fenced by more backticks than any run inside it, ``|`` escaped (a table cell),
    line breaks as spaces, control characters as visible escapes.

    >>> for_markdown_code(r"b > \frac{KT}{2}")
    '`b > \\frac{KT}{2}`'
    """
    text = for_terminal(" ".join(str(text).splitlines()))
    longest = max((len(run) for run in re.findall(r"`+", text)), default=0)
    fence = "`" * (longest + 1)
    padded = f" {text} " if text.startswith("`") or text.endswith("`") or longest else text
    return fence + padded.replace("|", r"\|") + fence


def for_html(text: object, quote: bool = True) -> str:
    """``text`` as HTML text or an attribute value (``&``, ``<``, ``>`` and quotes as references).

    >>> for_html('<a href="x">')
    '&lt;a href=&quot;x&quot;&gt;'
    """
    return html.escape(str(text), quote=quote)


def for_latex(text: object, breakable: bool = True) -> str:
    r"""Plain text for a LaTeX report (:func:`hapticproof.core.texsafe.escape_tex_text`).

    >>> for_latex("50% & {x}")
    '50\\% \\& \\{x\\}'
    """
    from hapticproof.core.texsafe import escape_tex_text

    return escape_tex_text(str(text), breakable)
