r"""Tests of :mod:`hapticproof.report.sanitize`: the issue's HTML attacks and a larger hostile corpus leave no
element or attribute outside the allow-list (checked by parsing the output again), benign
mathematics keeps its meaning (a sample of the bundled papers' pieces and hand-picked displays),
and, when chromium is installed, a page of the sanitised outputs runs nothing while a page
of the raw outputs does (the control), and the report's policy blocks scripts yet keeps its
inline style and SVG.
"""

from __future__ import annotations

import json
import pathlib
import shutil
import struct
import subprocess
import tempfile
import zlib
from html.parser import HTMLParser

import pytest

from hapticproof.report.sanitize import (
    CONTENT_SECURITY_POLICY, CSP_META, MATHML_ATTRIBUTES, MATHML_ELEMENTS, clean_mathml, html_violations,
    latex_to_mathml,
)

latex2mathml = pytest.importorskip("latex2mathml.converter")
HERE = pathlib.Path(__file__).parent
CORPUS = json.loads((HERE / "data" / "benign_displays.json").read_text(encoding="utf-8"))
CHROMIUM = shutil.which("chromium") or shutil.which("chromium-browser") or shutil.which("google-chrome")
needs_chromium = pytest.mark.skipif(CHROMIUM is None, reason="chromium is not installed")


# --------------------------------------------------------------------------------------------
# reading markup back
# --------------------------------------------------------------------------------------------
class _Tree(HTMLParser):
    """Markup as nested ``(tag, attributes, children)`` with texts as strings (adjacent
    texts merged, character references decoded): what a document means."""

    def __init__(self) -> None:
        super().__init__(convert_charrefs=True)
        self.root: list = []
        self.stack = [self.root]
        self.elements: list[tuple[str, tuple]] = []
        self.comments = 0

    def handle_starttag(self, tag, attrs):
        node = (tag, tuple(sorted(attrs)), [])
        self.stack[-1].append(node)
        self.stack.append(node[2])
        self.elements.append((tag, tuple(attrs)))

    def handle_startendtag(self, tag, attrs):
        self.stack[-1].append((tag, tuple(sorted(attrs)), []))
        self.elements.append((tag, tuple(attrs)))

    def handle_endtag(self, tag):
        if len(self.stack) > 1:
            self.stack.pop()

    def handle_data(self, data):
        if self.stack[-1] and isinstance(self.stack[-1][-1], str):
            self.stack[-1][-1] += data
        else:
            self.stack[-1].append(data)

    def handle_comment(self, data):
        self.comments += 1


def parsed(markup: str) -> _Tree:
    tree = _Tree()
    tree.feed(markup)
    tree.close()
    return tree


def texts(markup: str) -> str:
    """All text of the markup, in order."""
    out = []

    def walk(nodes):
        for node in nodes:
            if isinstance(node, str):
                out.append(node)
            else:
                walk(node[2])
    walk(parsed(markup).root)
    return "".join(out)


def disallowed(markup: str) -> list[str]:
    """Elements and attributes of the (re-parsed) output outside the allow-list."""
    tree = parsed(markup)
    bad = [f"comment x{tree.comments}"] if tree.comments else []
    for tag, attrs in tree.elements:
        if tag not in MATHML_ELEMENTS:
            bad.append(f"<{tag}>")
        for name, value in attrs:
            ok = (name in MATHML_ATTRIBUTES and MATHML_ATTRIBUTES[name](value or "")) or (
                tag == "math" and name in ("xmlns", "display")) or (name == "class" and value in ("hp-inline", "hp-boxed"))
            if not ok or "javascript" in (value or "").lower():
                bad.append(f"{name}={value!r} on <{tag}>")
    return bad


# --------------------------------------------------------------------------------------------
# the issue: HTML in \text and friends, \href
# --------------------------------------------------------------------------------------------
TEXT_COMMANDS = [r"\text", r"\textrm", r"\mbox", r"\textit", r"\textbf", r"\hbox", r"\texttt", r"\textsf", r"\emph",
                 r"\fbox", r"\boxed{\text", r"\tag"]
PAYLOADS = [
    "<script>document.title='PWNED'</script>",
    "<img src=x onerror=\"document.documentElement.setAttribute('data-pwned','img')\">",
    "</mtext></math><script>document.title='PWNED'</script>",
    "<svg onload=\"document.documentElement.setAttribute('data-pwned','svg')\"></svg>",
    "<iframe srcdoc=\"<script>parent.document.title='PWNED'</script>\"></iframe>",
    "<a href=\"javascript:document.title='PWNED'\">click</a>",
    "<!--<script>document.title='PWNED'</script>-->",
    "<![CDATA[</mtext><script>document.title='PWNED'</script>]]>",
    "<math><maction actiontype=\"statusline\"><mi>x</mi><mtext>y</mtext></maction></math>",
    "&lt;script&gt;document.title='PWNED'&lt;/script&gt;",
    "<object data=\"javascript:document.title='PWNED'\"></object>",
    "<mglyph src=x onerror=\"document.title='PWNED'\"></mglyph>",
]


def _text_latex(command: str, payload: str) -> str:
    closing = "}}" if command.count("{") else "}"
    return r"b > \frac{KT}{2} + B " + command + "{" + payload + closing


@pytest.mark.parametrize("command", TEXT_COMMANDS)
@pytest.mark.parametrize("payload", PAYLOADS, ids=range(len(PAYLOADS)))
def test_html_in_text_is_text(command, payload):
    latex = _text_latex(command, payload)
    raw = latex2mathml.convert(latex)
    escaped = latex_to_mathml(latex)
    cleaned = clean_mathml(escaped)
    assert disallowed(cleaned) == [] and html_violations(cleaned, require_csp=False) == []
    # the converted text is the payload itself, shown as characters
    if command not in (r"\tag",):
        assert payload.replace(" ", "\u00a0") in texts(escaped).replace(" ", "\u00a0")
    assert texts(cleaned) == texts(escaped)
    # the old (before issue 22) path (raw converter output) cleaned: inert, if not faithful
    assert disallowed(clean_mathml(raw)) == []
    if payload.startswith("<") and not payload.startswith("<!"):  # (html.parser hides what follows <!)
        assert disallowed(raw) != []  # the control: the raw output is live markup


def test_issue_example_exactly():
    printed = r"b > \frac{KT}{2} + B \text{<script>document.title='PWNED'</script>}"
    raw = latex2mathml.convert(printed)
    assert "<script>" in raw  # what the old converter put into the report
    cleaned = clean_mathml(latex_to_mathml(printed))
    assert "<script" not in cleaned and "&lt;script&gt;" in cleaned


ATTRIBUTE_ATTACKS = [
    r"\href{javascript:document.title='PWNED'}{B}",
    r"\href{data:text/html,<script>alert(1)</script>}{B}",
    r"\href{javascript&#58;alert(1)}{B}",
    r"\href{ javascript:alert(1)}{B}",
    r"\style{background:url(http://example.invalid/x)}{x}",
    r"\style{x:expression(alert(1))}{x}",
    r"\class{x&quot; onmouseover=&quot;alert(1)}{x}",
    r"\class{hp-x onclick}{x}",
    r"\color{red;background:url(x)}{x}",
    r"\colorbox{url(javascript:alert(1))}{y}",
    r"\fcolorbox{red}{blue}{y}",
    r"\hspace{1em onload=x}",
    r"\rule{1em}{2em}",
]


@pytest.mark.parametrize("latex", ATTRIBUTE_ATTACKS)
def test_attributes_from_latex_do_not_survive(latex):
    for markup in (latex_to_mathml(latex), latex2mathml.convert(latex)):
        cleaned = clean_mathml(markup)
        assert disallowed(cleaned) == [] and html_violations(cleaned, require_csp=False) == []
        names = {name for _, attrs in parsed(cleaned).elements for name, _ in attrs}
        assert not names & {"href", "style", "class", "onmouseover", "onclick", "onload", "border-color"}


def test_href_keeps_its_content():
    cleaned = clean_mathml(latex_to_mathml(r"b > \href{javascript:alert(1)}{B}"))
    assert "href" not in cleaned and "<mi>B</mi>" in cleaned


# --------------------------------------------------------------------------------------------
# hostile MathML given to the sanitiser directly
# --------------------------------------------------------------------------------------------
HOSTILE_MARKUP = {
    "script": "<math><mi>x</mi><script>document.title='PWNED'</script></math>",
    "script-upper": "<MATH><SCRIPT>document.title='PWNED'</SCRIPT><MI>x</MI></MATH>",
    "script-after-math": "<math><mi>x</mi></math><script>document.title='PWNED'</script>",
    "close-math-first": "<math><mtext></math><script>document.title='PWNED'</script></mtext></math>",
    "split-tag": "<math><scr<script>ipt>document.title='PWNED'</script></math>",
    "iframe": "<math><mtext><iframe src=\"javascript:parent.document.title='PWNED'\"></iframe></mtext></math>",
    "object": "<math><object data=\"data:text/html,<script>alert(1)</script>\"></object></math>",
    "embed": "<math><embed src=\"javascript:alert(1)\"></math>",
    "svg-onload": "<math><mtext><svg onload=\"document.title='PWNED'\"><circle r=9 /></svg></mtext></math>",
    "svg-script": "<svg><script>document.title='PWNED'</script></svg><math><mi>x</mi></math>",
    "svg-xlink": "<math><mtext><svg><a xlink:href=\"javascript:alert(1)\"><text>x</text></a></svg></mtext></math>",
    "xlink-on-mathml": "<math><mi xlink:href=\"javascript:alert(1)\">x</mi></math>",
    "href-on-mrow": "<math><mrow href=\"javascript:document.title='PWNED'\"><mi>B</mi></mrow></math>",
    "href-entity": "<math><mrow href=\"javascript&#58;alert(1)\"><mi>B</mi></mrow></math>",
    "href-tab": "<math><mrow href=\"java&#9;script:alert(1)\"><mi>B</mi></mrow></math>",
    "href-data": "<math><mrow href=\"data:text/html;base64,PHNjcmlwdD5hbGVydCgxKTwvc2NyaXB0Pg==\"><mi>B</mi></mrow></math>",
    "on-attribute": "<math><mi onmouseover=\"alert(1)\" onclick=alert(2) OnFocus=x>x</mi></math>",
    "style-attribute": "<math><mi style=\"background:url(http://example.invalid/leak)\">x</mi></math>",
    "style-element": "<math><style>@import url(http://example.invalid/x.css);</style><mi>x</mi></math>",
    "maction": "<math><maction actiontype=\"statusline#http://x\"><mi>x</mi><mtext>y</mtext></maction></math>",
    "annotation-xml": "<math><semantics><mi>x</mi><annotation-xml encoding=\"text/html\"><script>alert(1)</script>"
                      "</annotation-xml></semantics></math>",
    "annotation": "<math><semantics><mi>x</mi><annotation encoding=\"application/x-tex\">x</annotation></semantics></math>",
    "mglyph": "<math><mi><mglyph src=\"x\" onerror=\"alert(1)\"/></mi></math>",
    "mxss-table-style": "<math><mtext><table><mglyph><style><img src=x onerror=\"document.title='PWNED'\">"
                        "</style></mglyph></table></mtext></math>",
    "mxss-form": "<math><mtext><form><mglyph><svg><mtext><style><path id=\"</style><img onerror=alert(1) src>\">"
                 "</style></mtext></svg></mglyph></form></mtext></math>",
    "img-in-mi": "<math><mi><img src=x onerror=\"document.title='PWNED'\"></mi></math>",
    "comment": "<math><!--<script>alert(1)</script>--><mi>x</mi></math>",
    "comment-trick": "<math><!--><script>document.title='PWNED'</script>--><mi>x</mi></math>",
    "comment-bang": "<math><!-- --!><script>document.title='PWNED'</script> --><mi>x</mi></math>",
    "conditional-comment": "<math><!--[if IE]><script>alert(1)</script><![endif]--><mi>x</mi></math>",
    "cdata": "<math><mtext><![CDATA[</mtext><script>document.title='PWNED'</script>]]></mtext></math>",
    "processing-instruction": "<math><?xml-stylesheet href=\"http://x\"?><mi>x</mi></math>",
    "doctype": "<!DOCTYPE html [<!ENTITY x \"<script>\">]><math><mi>&x;</mi></math>",
    "unbalanced-open": "<math><mrow><mfrac><mi>a</mi><mi>b",
    "unbalanced-close": "</mrow></mtext></math><math><mi>x</mi></mrow></math></math>",
    "unquoted-attribute": "<math><mi mathvariant=bold onclick=alert(1)>x</mi></math>",
    "attribute-newline": "<math><mi\nonclick=\"alert(1)\"\nmathvariant=\"bold\">x</mi></math>",
    "attribute-breakout": "<math><mi mathvariant=\"bold\" onclick=\"alert(1)\" x=\"\">x</mi></math>",
    "bad-mathvariant": "<math><mi mathvariant=\"bold&quot; onclick=&quot;alert(1)\">x</mi></math>",
    "bad-length": "<math><mspace width=\"expression(alert(1))\" /></math>",
    "bad-colour": "<math><mstyle mathcolor=\"url(#x)\" mathbackground=\"red\"><mi>x</mi></mstyle></math>",
    "xmlns-swap": "<math xmlns=\"http://www.w3.org/1999/xhtml\"><mi>x</mi></math>",
    "foreign-in-token": "<math><mi><b>x</b><mrow>y</mrow></mi></math>",
    "base": "<math><base href=\"http://example.invalid/\"><mi>x</mi></math>",
    "meta-refresh": "<math><meta http-equiv=\"refresh\" content=\"0;url=javascript:alert(1)\"><mi>x</mi></math>",
    "link": "<math><link rel=\"stylesheet\" href=\"http://example.invalid/x.css\"><mi>x</mi></math>",
    "template": "<math><template><script>alert(1)</script></template><mi>x</mi></math>",
    "noscript": "<math><noscript><p title=\"</noscript><img src=x onerror=alert(1)>\"></noscript></math>",
    "textarea": "<math><mtext><textarea></mtext><script>alert(1)</script></textarea></mtext></math>",
    "null-bytes": "<math><mi>x\x00</mi><scr\x00ipt>alert(1)</scr\x00ipt></math>",
    "html-outside": "<b onclick=alert(1)>bold</b><math><mi>x</mi></math>",
    "nested-math": "<math><mi>x</mi><math><mi>y</mi></math></math>",
    "entity-text": "<math><mtext>&lt;script&gt;alert(1)&lt;/script&gt; &amp;lt;</mtext></math>",
}


@pytest.mark.parametrize("name", sorted(HOSTILE_MARKUP))
def test_hostile_markup_is_cleaned(name):
    cleaned = clean_mathml(HOSTILE_MARKUP[name])
    assert disallowed(cleaned) == []
    assert html_violations(cleaned, require_csp=False) == []
    assert "<script" not in cleaned.lower() and "javascript:" not in cleaned.lower().replace("&#9;", "")
    assert clean_mathml(cleaned) == cleaned  # idempotent: the output is already in the allow-list's form


def test_cleaning_keeps_what_is_allowed():
    assert clean_mathml(HOSTILE_MARKUP["unquoted-attribute"]) == '<math><mi mathvariant="bold">x</mi></math>'
    assert clean_mathml(HOSTILE_MARKUP["unbalanced-open"]) == "<math><mrow><mfrac><mi>a</mi><mi>b</mi></mfrac></mrow></math>"
    assert clean_mathml(HOSTILE_MARKUP["foreign-in-token"]) == "<math><mi>xy</mi></math>"
    assert clean_mathml(HOSTILE_MARKUP["entity-text"]) == (
        "<math><mtext>&lt;script&gt;alert(1)&lt;/script&gt; &amp;lt;</mtext></math>")
    assert clean_mathml(HOSTILE_MARKUP["bad-colour"]) == '<math><mstyle mathbackground="red"><mi>x</mi></mstyle></math>'
    assert clean_mathml(HOSTILE_MARKUP["annotation"]) == "<math><semantics><mi>x</mi></semantics></math>"
    assert clean_mathml('<math><mrow class="hp-boxed x"><mi>x</mi></mrow></math>') == (
        '<math><mrow class="hp-boxed"><mi>x</mi></mrow></math>')


# --------------------------------------------------------------------------------------------
# benign mathematics keeps its meaning
# --------------------------------------------------------------------------------------------
BENIGN = [
    r"\frac{KT}{2}", r"b > \frac{KT}{2} + |B|", r"x_{1}^{2} + y_{i j}", r"\Re\left\{ (1 - e^{-j \omega T}) H \right\}",
    r"\cos(\omega T) \leq 1", r"\begin{bmatrix} 1 & 0 \\ 0 & -\frac{1}{2} \end{bmatrix}",
    r"\left( x + y \right)", r"\text{if } b > 0", r"\sqrt[3]{x} + \sqrt{y}", r"\overline{z} \hat{x} \tilde{y}",
    r"\mathbb{R} \mathcal{Z} \mathbf{v}", r"\begin{cases} 1 & x > 0 \\ 0 & \text{otherwise} \end{cases}",
    r"\sum_{k=0}^{n} a_k \prod_{i} b_i", r"\lim_{T \to 0} f(T)", r"\boxed{x = 1}", r"a \, b \; c \quad d",
    r"\operatorname{Res}_{z = 1} G(z)", r"K_{01} \succeq 0", r"\begin{split} a &= b \\ &= c \end{split}",
    r"\text{a < b, c > d}",
]


def _same_meaning(a: str, b: str) -> bool:
    return parsed(a).root == parsed(b).root


@pytest.mark.parametrize("latex", BENIGN)
def test_benign_math_keeps_its_meaning(latex):
    reference = latex2mathml.convert(latex)
    escaped = latex_to_mathml(latex)
    if not any(ch in latex for ch in "<>&"):  # nothing to escape: the converter's very string
        assert escaped == reference
    assert _same_meaning(clean_mathml(escaped), escaped)


def test_benign_text_with_specials_is_shown_as_written():
    escaped = latex_to_mathml(r"\text{a < b, c > d}")
    assert texts(escaped).replace("\u00a0", " ") == "a < b, c > d"
    assert _same_meaning(clean_mathml(escaped), escaped)


def test_papers_pieces_convert_as_before_and_clean_to_themselves():
    pieces = CORPUS["mathml_pieces"]
    assert len(pieces) > 450
    changed_by_escaping, changed_by_cleaning = [], []
    for piece in pieces:
        reference, escaped = latex2mathml.convert(piece), latex_to_mathml(piece)
        if escaped != reference:
            changed_by_escaping.append(piece)
        if not _same_meaning(clean_mathml(escaped), reference):
            changed_by_cleaning.append(piece)
    assert changed_by_escaping == [] and changed_by_cleaning == []


# --------------------------------------------------------------------------------------------
# the page audit and the policy
# --------------------------------------------------------------------------------------------
def test_policy_forbids_what_it_should():
    directives = dict((d.split()[0], d.split()[1:]) for d in CONTENT_SECURITY_POLICY.split("; "))
    assert directives["default-src"] == ["'none'"] and directives["script-src"] == ["'none'"]
    for name in ("object-src", "frame-src", "connect-src", "font-src", "base-uri", "form-action"):
        assert directives[name] == ["'none'"]
    assert directives["style-src"] == ["'unsafe-inline'"] and directives["img-src"] == ["data:"]
    assert "frame-ancestors" not in directives and "sandbox" not in directives  # ignored in <meta>


def test_page_audit_finds_what_runs():
    page = ("<!DOCTYPE html><html><head><meta charset=\"utf-8\">" + CSP_META + "<title>t</title></head><body>"
            "<a href=\"#eq-1\">1</a><svg><use xlink:href=\"#g\" clip-path=\"url(#p1)\"/></svg></body></html>")
    assert html_violations(page) == []
    assert html_violations(page.replace(CSP_META, "")) == ["no Content-Security-Policy meta element first in <head>"]
    assert html_violations(page.replace("<title>t</title>", "<title>t</title>" + CSP_META).replace(CSP_META, "", 1)) != []
    assert html_violations(page.replace("#eq-1", "http://example.invalid/")) != []
    assert html_violations(page.replace("url(#p1)", "url(http://x)")) != []
    assert html_violations(page.replace("<a ", "<a onclick=\"x()\" ")) != []


# --------------------------------------------------------------------------------------------
# in a browser
# --------------------------------------------------------------------------------------------
def _chromium(page: str, *extra: str) -> str:
    with tempfile.TemporaryDirectory() as profile, tempfile.TemporaryDirectory() as site:
        path = pathlib.Path(site) / "page.html"
        path.write_text(page, encoding="utf-8")
        result = subprocess.run(
            [CHROMIUM, "--headless", "--no-sandbox", "--disable-gpu", "--disable-background-networking",
             "--no-first-run", f"--user-data-dir={profile}", *extra,
             path.as_uri()], capture_output=True, text=True, timeout=120, cwd=site)
        return result.stdout


def _page(body: str, head: str = "") -> str:
    return (f"<!DOCTYPE html><html><head><meta charset=\"utf-8\">{head}<title>clean</title></head>"
            f"<body>{body}</body></html>")


class _Dom(HTMLParser):
    def __init__(self):
        super().__init__(convert_charrefs=True)
        self.tags, self.handlers, self.title, self.in_title, self.pwned = [], [], "", False, []

    def handle_starttag(self, tag, attrs):
        self.tags.append(tag)
        self.in_title = tag == "title"
        self.handlers += [name for name, _ in attrs if name.startswith("on")]
        self.pwned += [value for name, value in attrs if name == "data-pwned"]

    def handle_endtag(self, tag):
        self.in_title = False

    def handle_data(self, data):
        if self.in_title:
            self.title += data


def _dom(page: str) -> _Dom:
    dom = _Dom()
    dom.feed(_chromium(page, "--dump-dom"))
    return dom


def _all_outputs(transform, markup: bool = True) -> str:
    parts = [transform(latex2mathml.convert(_text_latex(c, p)), _text_latex(c, p)) for c in TEXT_COMMANDS
             for p in PAYLOADS]
    if markup:  # (not on the unsanitised control page: its base, link and meta refresh would load things)
        parts += [transform(HOSTILE_MARKUP[name], None) for name in sorted(HOSTILE_MARKUP)]
    return "\n<br>\n".join(parts)


@needs_chromium
def test_browser_runs_nothing_from_sanitised_outputs():
    # the control: the converter's raw output and the hostile markup, unsanitised, do run
    raw = _dom(_page(_all_outputs(lambda markup, latex: markup, markup=False)))
    assert raw.title == "PWNED" or raw.pwned, "the control page ran nothing: the test could not fail"
    clean = _dom(_page(_all_outputs(lambda markup, latex: clean_mathml(latex_to_mathml(latex) if latex else markup))))
    assert "body" in clean.tags and "math" in clean.tags  # the page was rendered
    assert clean.title == "clean" and clean.pwned == []
    assert [t for t in clean.tags if t in ("script", "img", "iframe", "object", "embed", "svg", "a", "style")] == []
    assert clean.handlers == []


def _png_pixels(data: bytes) -> tuple[int, int, list[bytes]]:
    """Width, height and rows (RGB or RGBA bytes) of an 8-bit non-interlaced PNG."""
    assert data[:8] == b"\x89PNG\r\n\x1a\n"
    pos, idat, width = 8, b"", 0
    while pos < len(data):
        length, kind = struct.unpack(">I4s", data[pos:pos + 8])
        chunk = data[pos + 8:pos + 8 + length]
        if kind == b"IHDR":
            width, height, depth, colour, _, _, interlace = struct.unpack(">IIBBBBB", chunk)
            assert depth == 8 and colour in (2, 6) and interlace == 0
            channels = 3 if colour == 2 else 4
        elif kind == b"IDAT":
            idat += chunk
        pos += 12 + length
    raw, stride, rows, previous = zlib.decompress(idat), width * channels, [], bytearray(width * channels)
    for y in range(height):
        kind, line = raw[y * (stride + 1)], bytearray(raw[y * (stride + 1) + 1:(y + 1) * (stride + 1)])
        for x in range(stride):
            left = line[x - channels] if x >= channels else 0
            up, corner = previous[x], previous[x - channels] if x >= channels else 0
            if kind == 1:
                line[x] = (line[x] + left) & 255
            elif kind == 2:
                line[x] = (line[x] + up) & 255
            elif kind == 3:
                line[x] = (line[x] + (left + up) // 2) & 255
            elif kind == 4:
                p = left + up - corner
                pa, pb, pc = abs(p - left), abs(p - up), abs(p - corner)
                line[x] = (line[x] + (left if pa <= pb and pa <= pc else up if pb <= pc else corner)) & 255
        rows.append(bytes(line))
        previous = line
    return width, channels, rows


def _has_colour(png: bytes, rgb: tuple[int, int, int]) -> bool:
    width, channels, rows = _png_pixels(png)
    return any(tuple(row[x * channels:x * channels + 3]) == rgb for row in rows for x in range(width))


@needs_chromium
def test_policy_blocks_scripts_and_keeps_inline_style_and_svg(tmp_path):
    body = ("<div class=\"box\">styled</div>"
            "<svg width=\"60\" height=\"60\"><style>.g{fill:#00c800}</style><rect class=\"g\" width=\"60\" height=\"60\"/>"
            "</svg><math><mfrac><mi>a</mi><mi>b</mi></mfrac></math>"
            "<script>document.title='PWNED'</script>"
            "<img src=x onerror=\"document.documentElement.setAttribute('data-pwned','img')\">")
    style = "<style>.box{background:#c80000;width:80px;height:40px}</style>"
    unprotected = _dom(_page(body, style))
    assert unprotected.title == "PWNED" and unprotected.pwned  # the control
    protected_page = _page(body, CSP_META + style)
    protected = _dom(protected_page)
    assert protected.title == "clean" and protected.pwned == []
    shot = tmp_path / "shot.png"
    _chromium(protected_page, f"--screenshot={shot}", "--window-size=400,300", "--hide-scrollbars")
    png = shot.read_bytes()
    assert _has_colour(png, (200, 0, 0)) and _has_colour(png, (0, 200, 0))  # inline <style> and SVG rendered
