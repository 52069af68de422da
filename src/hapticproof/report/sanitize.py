r"""Make the MathML of an HTML report inert, whatever LaTeX it was converted from.

latex2mathml serialises its tree and then *unescapes* the whole string, so the text of
``\text{<script>...</script>}`` (and ``\textrm``, ``\mbox``, ``\hbox``, ``\textit``, ...)
comes out as live markup, and ``\href{javascript:...}{B}``, ``\style``, ``\class``,
``\color`` copy their argument into attributes. Two layers close this:

* :func:`latex_to_mathml` converts with latex2mathml but serialises its tree itself, with
  every text escaped (only the numeric character references latex2mathml writes for symbols
  are kept), so ``\text{<b>}`` shows the characters ``<b>``. For LaTeX whose texts hold no
  ``<``, ``>`` or ``&`` the output is the very string latex2mathml gives, so the rewriting
  that :mod:`hapticproof.report.html` applies afterwards works unchanged.
* :func:`clean_mathml` parses any MathML markup (:mod:`html.parser`, no regular expression
  on markup) and writes it again keeping only an allow-list of MathML presentation elements
  and attributes, each attribute value checked against its grammar, all text escaped;
  ``script``, ``style``, ``svg``, ``iframe``, ``annotation`` ... go with their content, other
  elements (``a``, ``maction``, ``img`` ...) and every ``href``/``on*``/``style``/``id``
  attribute go, comments, CDATA and processing instructions go.

:data:`CONTENT_SECURITY_POLICY` is the policy the report page declares (:data:`CSP_META`):
no script, object, frame, form, base or network load of any kind; the inline ``<style>`` and
inline SVG keep working. :func:`html_violations` audits a whole page (tests and CI).

>>> clean_mathml('<math><mtext><script>alert(1)</script>x</mtext><mi onclick="f()">y</mi></math>')
'<math><mtext>x</mtext><mi>y</mi></math>'
>>> latex_to_mathml(r"\text{<b>}")  # doctest: +ELLIPSIS
'<math ...><mrow><mtext>&lt;b&gt;</mtext></mrow></math>'
"""

from __future__ import annotations

import re
from collections.abc import Callable, Collection
from html.parser import HTMLParser
from typing import Any

__all__ = [
    "MATHML_ELEMENTS",
    "MATHML_ATTRIBUTES",
    "CONTENT_SECURITY_POLICY",
    "CSP_META",
    "clean_mathml",
    "latex_to_mathml",
    "html_violations",
]

# --------------------------------------------------------------------------------------------
# the allow-list
# --------------------------------------------------------------------------------------------
#: Elements whose content is characters only (MathML token elements).
TOKEN_ELEMENTS = frozenset({"mi", "mn", "mo", "ms", "mtext", "mspace"})
#: MathML presentation elements a report may contain.
MATHML_ELEMENTS = TOKEN_ELEMENTS | frozenset({
    "math", "mrow", "msub", "msup", "msubsup", "mfrac", "msqrt", "mroot", "mover", "munder", "munderover",
    "mtable", "mtr", "mtd", "mstyle", "mpadded", "mphantom", "menclose", "mfenced", "semantics",
    "mmultiscripts", "mprescripts", "none",
})
#: Elements dropped together with everything inside them (scripts, styles, foreign content,
#: frames, embedded documents, alternative encodings, raw-text elements).
DROPPED_WITH_CONTENT = frozenset({
    "script", "style", "svg", "foreignobject", "iframe", "frame", "frameset", "object", "embed", "applet",
    "template", "noscript", "noembed", "noframes", "textarea", "title", "xmp", "plaintext", "select",
    "option", "head", "annotation", "annotation-xml", "mglyph", "portal", "audio", "video", "canvas",
    "math:script", "svg:script",
})
#: HTML elements without an end tag (never pushed on the open-element stack).
_VOID = frozenset({"area", "base", "br", "col", "embed", "hr", "img", "input", "link", "meta", "param", "source",
                   "track", "wbr", "keygen", "frame", "image"})

_NUMBER = r"[+-]?(?:\d+(?:\.\d*)?|\.\d+)"
_LENGTH = re.compile(_NUMBER + r"(?:em|ex|px|in|cm|mm|pt|pc|mu|%)?|" + _NUMBER + r"?(?:width|height|depth)|"
                     r"(?:negative)?(?:very){0,2}(?:thin|medium|thick)mathspace|0")
_TOKENS = {
    "columnalign": {"left", "center", "right"},
    "rowalign": {"top", "bottom", "center", "baseline", "axis"},
    "columnlines": {"none", "solid", "dashed"},
    "rowlines": {"none", "solid", "dashed"},
    "frame": {"none", "solid", "dashed"},
    "notation": {"box", "roundedbox", "circle", "left", "right", "top", "bottom", "updiagonalstrike",
                 "downdiagonalstrike", "verticalstrike", "horizontalstrike", "madruwb", "actuarial",
                 "longdiv", "radical"},
}
_ENUMS = {
    "mathvariant": {"normal", "bold", "italic", "bold-italic", "double-struck", "bold-fraktur", "script",
                    "bold-script", "fraktur", "sans-serif", "bold-sans-serif", "sans-serif-italic",
                    "sans-serif-bold-italic", "monospace", "initial", "tailed", "looped", "stretched"},
    "form": {"prefix", "infix", "postfix"},
}
_BOOLEANS = ("displaystyle", "stretchy", "fence", "separator", "accent", "accentunder", "largeop",
             "movablelimits", "symmetric", "equalrows", "equalcolumns")
_LENGTHS = ("lspace", "rspace", "width", "height", "depth", "voffset", "minsize", "maxsize", "mathsize")
_LENGTH_LISTS = ("columnspacing", "rowspacing", "framespacing")
_COLOUR = re.compile(r"#[0-9A-Fa-f]{3,8}|[A-Za-z]{1,20}")
MATHML_NAMESPACE = "http://www.w3.org/1998/Math/MathML"


def _one_of(words: Collection[str]) -> Callable[[str], bool]:
    return lambda value: value in words


def _token_list(words: Collection[str]) -> Callable[[str], bool]:
    return lambda value: bool(value.split()) and all(w in words for w in value.split())


def _length(value: str) -> bool:
    return _LENGTH.fullmatch(value.strip()) is not None or value in ("small", "normal", "big")


def _lengths(value: str) -> bool:
    return bool(value.split()) and all(_LENGTH.fullmatch(v) for v in value.split())


#: attribute -> check of its value (``class`` and the two ``math`` attributes are handled
#: separately). Everything else -- href, src, on*, style, id, xlink:*, actiontype -- goes.
MATHML_ATTRIBUTES: dict[str, Callable[[str], bool]] = {
    **{name: _one_of({"true", "false"}) for name in _BOOLEANS},
    **{name: _length for name in _LENGTHS},
    **{name: _lengths for name in _LENGTH_LISTS},
    **{name: _token_list(words) for name, words in _TOKENS.items()},
    **{name: _one_of(words) for name, words in _ENUMS.items()},
    "linethickness": lambda v: _length(v) or v in ("thin", "medium", "thick"),
    "scriptlevel": lambda v: re.fullmatch(r"[+-]?\d{1,2}", v) is not None,
    "rowspan": lambda v: re.fullmatch(r"[1-9]\d{0,2}", v) is not None,
    "columnspan": lambda v: re.fullmatch(r"[1-9]\d{0,2}", v) is not None,
    "mathcolor": lambda v: _COLOUR.fullmatch(v) is not None,
    "mathbackground": lambda v: _COLOUR.fullmatch(v) is not None,
}
_MATH_ONLY = {"xmlns": _one_of({MATHML_NAMESPACE}), "display": _one_of({"block", "inline"})}
#: the classes hapticproof's own rewriting puts on MathML elements
DEFAULT_CLASSES = frozenset({"hp-inline", "hp-boxed"})

#: The report page's policy: nothing but its own inline style and inline SVG. ``default-src
#: 'none'`` already covers scripts, objects, frames, workers, fonts, media and connections;
#: they are repeated so that the policy reads as what it forbids. ``base-uri`` and
#: ``form-action`` do not fall back to ``default-src``.
CONTENT_SECURITY_POLICY = ("default-src 'none'; script-src 'none'; object-src 'none'; frame-src 'none'; "
                           "child-src 'none'; worker-src 'none'; connect-src 'none'; font-src 'none'; "
                           "media-src 'none'; manifest-src 'none'; img-src data:; style-src 'unsafe-inline'; "
                           "base-uri 'none'; form-action 'none'")
#: The policy as the first element of the page's ``<head>`` after ``<meta charset>``.
CSP_META = f'<meta http-equiv="Content-Security-Policy" content="{CONTENT_SECURITY_POLICY}">'


# --------------------------------------------------------------------------------------------
# escaping
# --------------------------------------------------------------------------------------------
def _allowed_char(ch: str) -> bool:
    code = ord(ch)
    return not (code < 32 and ch not in "\t\n\r" or 0x7F <= code < 0xA0 or 0xD800 <= code < 0xE000
                or 0xFDD0 <= code <= 0xFDEF or code & 0xFFFE == 0xFFFE)


def _escape_text(text: str) -> str:
    text = "".join(ch for ch in text if _allowed_char(ch))
    return text.replace("&", "&amp;").replace("<", "&lt;").replace(">", "&gt;").replace('"', "&quot;")


def _escape_attribute(value: str) -> str:
    return _escape_text(value).replace("\n", "&#10;").replace("\r", "&#13;").replace("\t", "&#9;")


_REFERENCE = re.compile(r"&#x([0-9A-Fa-f]{1,6});")


def _escape_converter_text(text: str) -> str:
    """Text of latex2mathml's tree: the ``&#x...;`` references it writes for symbols stay
    (when they name a character allowed in HTML), everything else is escaped."""
    out, last = [], 0
    for match in _REFERENCE.finditer(text):
        code = int(match.group(1), 16)
        if code <= 0x10FFFF and _allowed_char(chr(code)) and code != 0:
            out.append(_escape_text(text[last:match.start()]))
            out.append(match.group(0))
            last = match.end()
    out.append(_escape_text(text[last:]))
    return "".join(out)


# --------------------------------------------------------------------------------------------
# the sanitiser
# --------------------------------------------------------------------------------------------
class _Cleaner(HTMLParser):
    """Re-serialise markup keeping the allow-list; the open-element stack holds
    ``(tag, mode)`` with mode ``keep`` (written), ``unwrap`` (tag dropped, content kept) or
    ``drop`` (tag and content dropped)."""

    def __init__(self, classes: Collection[str]) -> None:
        super().__init__(convert_charrefs=True)
        self.classes = set(classes)
        self.out: list[str] = []
        self.stack: list[tuple[str, str]] = []

    # state --------------------------------------------------------------------------------
    def dropping(self) -> bool:
        return any(mode == "drop" for _, mode in self.stack)

    def kept(self) -> list[str]:
        return [tag for tag, mode in self.stack if mode == "keep"]

    def mode_for(self, tag: str) -> str:
        if self.dropping() or tag in DROPPED_WITH_CONTENT:
            return "drop"
        kept = self.kept()
        if kept and kept[-1] in TOKEN_ELEMENTS:  # token elements hold characters only
            return "unwrap"
        if tag == "math":
            return "unwrap" if kept else "keep"
        return "keep" if tag in MATHML_ELEMENTS and kept else "unwrap"

    def attributes(self, tag: str, attrs: list[tuple[str, str | None]]) -> str:
        out, seen = [], set()
        for name, value in attrs:
            if value is None or name in seen:
                continue
            seen.add(name)
            value = value.strip()
            if name == "class":
                value = " ".join(c for c in value.split() if c in self.classes)
                ok = bool(value)
            elif tag == "math" and name in _MATH_ONLY:
                ok = _MATH_ONLY[name](value)
            else:
                check = MATHML_ATTRIBUTES.get(name)
                ok = check is not None and check(value)
            if ok:
                out.append(f' {name}="{_escape_attribute(value)}"')
        return "".join(out)

    # events -------------------------------------------------------------------------------
    def handle_starttag(self, tag: str, attrs: list[tuple[str, str | None]]) -> None:
        mode = self.mode_for(tag)
        if tag in _VOID:
            return
        self.stack.append((tag, mode))
        if mode == "keep":
            self.out.append(f"<{tag}{self.attributes(tag, attrs)}>")

    def handle_startendtag(self, tag: str, attrs: list[tuple[str, str | None]]) -> None:
        if self.mode_for(tag) == "keep":
            self.out.append(f"<{tag}{self.attributes(tag, attrs)} />")

    def handle_endtag(self, tag: str) -> None:
        for k in range(len(self.stack) - 1, -1, -1):
            if self.stack[k][0] == tag:
                while len(self.stack) > k:
                    self.close_top()
                return

    def close_top(self) -> None:
        tag, mode = self.stack.pop()
        if mode == "keep":
            self.out.append(f"</{tag}>")

    def handle_data(self, data: str) -> None:
        if not self.dropping():
            self.out.append(_escape_text(data))

    # comments, declarations, processing instructions, CDATA: nothing of them is written
    def handle_comment(self, data: str) -> None:
        pass

    def handle_decl(self, decl: str) -> None:
        pass

    def handle_pi(self, data: str) -> None:
        pass

    def unknown_decl(self, data: str) -> None:
        pass

    def result(self) -> str:
        self.close()
        while self.stack:
            self.close_top()
        return "".join(self.out)


def clean_mathml(markup: str, classes: Collection[str] = DEFAULT_CLASSES) -> str:
    r"""``markup`` (MathML, from any converter) written again with only allowed MathML:
    the elements of :data:`MATHML_ELEMENTS` inside a ``<math>`` element, the attributes of
    :data:`MATHML_ATTRIBUTES` whose value fits (``xmlns`` and ``display`` on ``math``, the
    ``classes`` given), every text escaped. Elements of :data:`DROPPED_WITH_CONTENT` go with
    their content; other elements lose their tags and keep their text; token elements
    (``mi``, ``mtext`` ...) keep characters only. Unclosed elements are closed at the end.

    Benign converter output comes back unchanged (up to the spelling of character
    references), self-closing elements stay self-closing.

    >>> clean_mathml('<math display="block"><mrow href="javascript:alert(1)"><mi>B</mi></mrow><mrow /></math>')
    '<math display="block"><mrow><mi>B</mi></mrow><mrow /></math>'
    >>> clean_mathml('<math><mtext>a &lt; b</mtext><!-- x --><svg onload="alert(1)"><circle/></svg></math>')
    '<math><mtext>a &lt; b</mtext></math>'
    """
    cleaner = _Cleaner(classes)
    cleaner.feed(markup)
    return cleaner.result()


# --------------------------------------------------------------------------------------------
# LaTeX -> MathML with escaped text
# --------------------------------------------------------------------------------------------
def _serialise(element: Any, out: list[str]) -> None:
    """ElementTree's layout (``<tag a="v" />`` when empty), with escaped text."""
    attributes = "".join(f' {name}="{_escape_attribute(str(value))}"' for name, value in element.attrib.items())
    tag = str(element.tag)
    if element.text or len(element):
        out.append(f"<{tag}{attributes}>")
        if element.text:
            out.append(_escape_converter_text(element.text))
        for child in element:
            _serialise(child, out)
            if child.tail:
                out.append(_escape_converter_text(child.tail))
        out.append(f"</{tag}>")
    else:
        out.append(f"<{tag}{attributes} />")


def latex_to_mathml(latex: str, display: str = "inline") -> str:
    r"""latex2mathml's conversion of ``latex`` with every text escaped: the drop-in for
    ``latex2mathml.converter.convert`` (same string for LaTeX whose texts hold no ``<``,
    ``>``, ``&``). It raises what latex2mathml raises.

    >>> latex_to_mathml(r"\frac{a}{b}") == __import__("latex2mathml.converter").converter.convert(r"\frac{a}{b}")
    True
    >>> latex_to_mathml(r"x \text{</mtext><script>}")  # doctest: +ELLIPSIS
    '<math ...><mrow><mi>x</mi><mtext>&lt;/mtext&gt;&lt;script&gt;</mtext></mrow></math>'
    """
    from latex2mathml.converter import convert_to_element

    out: list[str] = []
    _serialise(convert_to_element(latex, display=display), out)
    return "".join(out)


# --------------------------------------------------------------------------------------------
# auditing a whole page
# --------------------------------------------------------------------------------------------
_FORBIDDEN_ELEMENTS = frozenset({
    "script", "iframe", "frame", "frameset", "object", "embed", "applet", "form", "input", "button", "textarea",
    "select", "base", "link", "portal", "audio", "video", "source", "track", "img", "image", "picture",
    "foreignobject", "annotation-xml", "maction", "mglyph", "noscript", "template", "animate", "set",
    "animatetransform", "animatemotion", "handler", "listener",
})
_URL_ATTRIBUTES = frozenset({"href", "xlink:href", "src", "srcset", "action", "formaction", "srcdoc", "data",
                             "poster", "background", "ping", "cite", "codebase", "manifest", "lowsrc",
                             "dynsrc", "longdesc", "usemap", "archive", "classid", "xml:base", "to", "from",
                             "values", "attributename"})


def _squeezed(value: str) -> str:
    return "".join(ch for ch in value.lower() if not ch.isspace() and ord(ch) >= 32)


def _style_problem(css: str) -> str | None:
    text = _squeezed(css)
    for bad in ("@import", "expression(", "javascript:", "behavior:", "-moz-binding"):
        if bad in text:
            return bad
    for match in re.finditer(r"url\(", text):
        if not text[match.end():].lstrip("'\"").startswith("#"):
            return "url() outside the page"
    return None


class _Auditor(HTMLParser):
    def __init__(self) -> None:
        super().__init__(convert_charrefs=True)
        self.problems: list[str] = []
        self.csp_first = None  # whether the CSP meta came before any other head content
        self.seen_head_content = False
        self.in_style = False

    def check_tag(self, tag: str, attrs: list[tuple[str, str | None]]) -> None:
        values = {name: value or "" for name, value in attrs}
        if tag == "meta":
            if values.get("http-equiv", "").lower() == "content-security-policy":
                if self.csp_first is None:
                    self.csp_first = not self.seen_head_content
                    if values.get("content") != CONTENT_SECURITY_POLICY:
                        self.problems.append(f"CSP differs from CONTENT_SECURITY_POLICY: {values.get('content')!r}")
            elif "http-equiv" in values:
                self.problems.append(f"<meta http-equiv={values['http-equiv']!r}>")
            elif "charset" not in values:
                self.seen_head_content = True
        elif tag not in ("html", "head"):
            self.seen_head_content = True
        if tag in _FORBIDDEN_ELEMENTS:
            self.problems.append(f"<{tag}> element")
        for name, value in attrs:
            value = value or ""
            if name.startswith("on"):
                self.problems.append(f"event handler {name} on <{tag}>")
            elif name in _URL_ATTRIBUTES and not value.startswith("#"):
                self.problems.append(f"{name}={value!r} on <{tag}> (only links inside the page)")
            elif (name == "style" or "url(" in _squeezed(value)) and _style_problem(value):
                # style, and SVG's fill, clip-path, mask, filter, marker-*, cursor ...
                self.problems.append(f"{name}: {_style_problem(value)} on <{tag}>")
            elif "javascript:" in _squeezed(value) or "vbscript:" in _squeezed(value):
                self.problems.append(f"script URL in {name} on <{tag}>")

    def handle_starttag(self, tag: str, attrs: list[tuple[str, str | None]]) -> None:
        self.check_tag(tag, attrs)
        self.in_style = tag == "style"

    def handle_startendtag(self, tag: str, attrs: list[tuple[str, str | None]]) -> None:
        self.check_tag(tag, attrs)

    def handle_endtag(self, tag: str) -> None:
        self.in_style = False

    def handle_data(self, data: str) -> None:
        if self.in_style and _style_problem(data):
            self.problems.append(f"<style> with {_style_problem(data)}")

    def handle_pi(self, data: str) -> None:
        self.problems.append("processing instruction")


def html_violations(page: str, require_csp: bool = True) -> list[str]:
    r"""What in an HTML page (or fragment, with ``require_csp=False``) could run or load
    something: forbidden elements (``script``, ``iframe``, ``object``, ``form``, ``img``,
    ``maction`` ...), ``on*`` attributes, URL attributes other than ``#fragment`` links,
    ``javascript:`` anywhere, CSS ``url()`` leaving the page (in ``style``, ``<style>`` or
    an SVG attribute such as ``clip-path``) or ``@import``, ``<meta
    http-equiv>`` other than the policy; with ``require_csp``, a missing policy or one that
    is not the first thing in ``<head>`` after the charset.

    >>> html_violations('<p><a href="#eq-1">1</a><svg><use xlink:href="#m1"/></svg></p>', require_csp=False)
    []
    >>> html_violations('<p><a href="javascript:x()">1</a><img src=x onerror=f()></p>', require_csp=False)
    ["href='javascript:x()' on <a> (only links inside the page)", '<img> element', "src='x' on <img> (only links inside the page)", 'event handler onerror on <img>']
    """
    auditor = _Auditor()
    auditor.feed(page)
    auditor.close()
    problems = list(auditor.problems)
    if require_csp and not auditor.csp_first:
        problems.append("no Content-Security-Policy meta element first in <head>")
    return problems
