r"""HTML view of audit reports: one self-contained page that opens offline.

Every display (printed, derived, corrected) is MathML that browsers render natively: the LaTeX
is cut into the same lines and unbreakable pieces as the PDF (:func:`hapticproof.report.latex.display_lines`,
:func:`~hapticproof.report.latex.display_breaks`), so a long display wraps like a paragraph instead of
running off the page. Each piece is converted by latex2mathml after one normalisation step
(:func:`normalise`) for the commands of the papers' dialect it does not know; a display that
still does not convert (OCR-damaged printed text) is shown as its escaped LaTeX source, clearly
marked, never as an ``merror``. Verdicts are coloured badges; the witness is a small table;
plots carried in the evidence (:class:`~hapticproof.core.evidence.Plot`) are inline SVG. No script,
no stylesheet or font from the network.

The view only renders :class:`~hapticproof.audit.runner.AuditReport` / ``EquationResult`` /
:class:`~hapticproof.core.evidence.Finding` objects; it computes nothing. The same fragments are the
objects' ``_repr_html_`` in notebooks.

>>> print(math_html(r"b > \frac{KT}{2}"))  # doctest: +ELLIPSIS
<div class="hp-display"><div class="hp-line"><math><mi>b</mi></math><wbr><math><mrow /><mo>&gt;</mo><mfrac>...
>>> "hp-fallback" in math_html(r"\frac{a}{b}}")
True
"""

from __future__ import annotations

import functools
import io
import json
import re
from collections.abc import Iterable, Mapping, Sequence
from html import escape
from typing import Any

from hapticproof.core.version import VERSION
from hapticproof.report import latex as tex
from hapticproof.core.evidence import Plot, Verdict, to_jsonable
from hapticproof.report.sanitize import CSP_META, clean_mathml, latex_to_mathml

__all__ = [
    "normalise",
    "mathml",
    "math_html",
    "prose_html",
    "plot_svg",
    "result_html",
    "finding_html",
    "report_fragment",
    "report_html",
    "ERRATA_ORDER",
]

#: Verdicts in the order an errata sheet lists them: the defects first.
ERRATA_ORDER = (
    Verdict.WRONG, Verdict.TYPO, Verdict.INCONSISTENT, Verdict.NEEDS_ASSUMPTION, Verdict.MALFORMED,
    Verdict.UNDECIDED, Verdict.CONSERVATIVE, Verdict.CONFIRMED,
)

# --------------------------------------------------------------------------------------------
# LaTeX -> MathML
# --------------------------------------------------------------------------------------------
#: Commands of the papers' dialect that latex2mathml does not know, rewritten to ones it does
#: (the one place where the dialect is adapted).
_REWRITES = (
    (r"\\mathscr\b", r"\\mathcal"),
    (r"\\operatorname\*", r"\\operatorname"),
    (r"\\implies\b", r"\\Longrightarrow"),
    (r"\\impliedby\b", r"\\Longleftarrow"),
    (r"\\iff\b", r"\\Longleftrightarrow"),
    (r"\\Res\b", r"\\operatorname{Res}"),
    (r"\\!", ""),
    (r"\\begin\{(aligned|split|align\*?)\}", r"\\begin{split}"),
    (r"\\end\{(aligned|split|align\*?)\}", r"\\end{split}"),
    (r"\\begin\{(gathered|gather\*?)\}", r"\\begin{matrix}"),
    (r"\\end\{(gathered|gather\*?)\}", r"\\end{matrix}"),
    (r"\\(dfrac)\b", r"\\frac"),
    (r"\\textrm\b", r"\\text"),
)
#: Characters latex2mathml puts in <mi> that are operators (relations, arrows, fences).
_OPERATOR_CHARS = set("\u27f9\u27f8\u27fa\u2ab0\u2aaf\u227b\u227a\u00ac{}|\u2016\u2192\u21d2\u21d4\u2248\u223c\u2261"
                      "\u226a\u226b\u2a7e\u2a7d\u21a6\u2223\u27e8\u27e9\u2225\u22a5")
_VARIANTS = {  # mathvariant -> offsets of (A, a) in Mathematical Alphanumeric Symbols
    "bold": (0x1D400, 0x1D41A), "italic": (0x1D434, 0x1D44E), "bold-italic": (0x1D468, 0x1D482),
    "script": (0x1D49C, 0x1D4B6), "fraktur": (0x1D504, 0x1D51E), "double-struck": (0x1D538, 0x1D552),
}
_LETTERLIKE = {  # holes of the Unicode block, filled from the Letterlike Symbols
    0x1D49D: 0x212C, 0x1D4A0: 0x2130, 0x1D4A1: 0x2131, 0x1D4A3: 0x210B, 0x1D4A4: 0x2110, 0x1D4A7: 0x2112,
    0x1D4A8: 0x2133, 0x1D4AD: 0x211B, 0x1D4BA: 0x212F, 0x1D4BC: 0x210A, 0x1D4C4: 0x2134, 0x1D455: 0x210E,
    0x1D506: 0x212D, 0x1D50B: 0x210C, 0x1D50C: 0x2111, 0x1D515: 0x211C, 0x1D51D: 0x2128, 0x1D53A: 0x2102,
    0x1D53F: 0x210D, 0x1D545: 0x2115, 0x1D547: 0x2119, 0x1D548: 0x211A, 0x1D549: 0x211D, 0x1D551: 0x2124,
}


def normalise(latex: str) -> str:
    r"""Rewrite the dialect's commands latex2mathml lacks (``\mathscr``, ``\implies``,
    ``aligned`` ...) into ones it converts.

    >>> normalise(r"\mathscr{Z} \implies \begin{aligned} a &= b \end{aligned}")
    '\\mathcal{Z} \\Longrightarrow \\begin{split} a &= b \\end{split}'
    """
    for pattern, replacement in _REWRITES:
        latex = re.sub(pattern, replacement, latex)
    return latex


def _variant(match: re.Match) -> str:
    variant, char = match.group(1), match.group(2)
    base = _VARIANTS.get(variant)
    if base is None or not re.fullmatch(r"[A-Za-z]", char):
        return match.group(0) if variant != "normal" else f'<mi mathvariant="normal">{char}</mi>'
    code = (base[0] + ord(char) - 65) if char.isupper() else (base[1] + ord(char) - 97)
    return f"<mi>&#x{_LETTERLIKE.get(code, code):05X};</mi>"


def _operator(match: re.Match) -> str:
    entity = match.group(1)
    char = chr(int(entity[3:-1], 16)) if entity.startswith("&#x") else entity
    return f"<mo>{entity}</mo>" if char in _OPERATOR_CHARS else match.group(0)


def _postprocess(mathml: str) -> str:
    """MathML Core details: operators latex2mathml marks as identifiers, font variants as
    Unicode letters (Chromium ignores mathvariant), boxes as CSS borders, named spaces."""
    mathml = re.sub(r"<mi>(&#x[0-9A-Fa-f]+;|[{}|])</mi>", _operator, mathml)
    mathml = re.sub(r'<mi mathvariant="([a-z-]+)">([^<]+)</mi>', _variant, mathml)
    mathml = re.sub(r"<mi>(cos|sin|tan|cot|sec|csc|exp|log|ln|sinh|cosh|tanh|arg)</mi>",
                    r'<mo lspace="0.1667em" rspace="0em">\1</mo>', mathml)  # function names: TeX's op spacing
    mathml = mathml.replace('<menclose notation="box">', '<mrow class="hp-boxed">').replace("</menclose>", "</mrow>")
    mathml = re.sub(r'width="[a-z]+mathspace"', 'width="0em"', mathml)
    return mathml.replace('<mspace linebreak="newline" />', '<mspace width="1em" />')


_ESCAPES = {"<": "&lt;", ">": "&gt;", "&": "&amp;", '"': "&quot;"}


def _compact(mathml: str) -> str:
    """Smaller MathML for HTML5: no namespace or display attributes (the page's style sets
    display style), characters instead of numeric entities, no empty ``<mrow>`` wrappers of
    one element."""
    mathml = re.sub(r'<math xmlns="http://www.w3.org/1998/Math/MathML" display="(inline|block)">', "<math>", mathml)
    mathml = re.sub(r"&#x([0-9A-Fa-f]+);", lambda m: _ESCAPES.get(chr(int(m.group(1), 16)), chr(int(m.group(1), 16))),
                    mathml)
    if mathml.startswith("<math><mrow>") and mathml.endswith("</mrow></math>"):
        depth = 0
        for tag in re.finditer(r"<(/?)mrow\b[^>]*?(/?)>", mathml[len("<math>"):-len("</math>")]):
            depth += 0 if tag.group(2) else (-1 if tag.group(1) else 1)
            if depth == 0:  # the first <mrow> closes here: strip it only if this is the end
                if tag.end() == len(mathml) - len("<math></math>"):
                    mathml = "<math>" + mathml[len("<math><mrow>"):-len("</mrow></math>")] + "</math>"
                break
    return mathml


@functools.lru_cache(maxsize=4096)
def mathml(latex: str, display: bool = False) -> str | None:
    r"""One piece of LaTeX as a ``<math>`` element, or None when it does not convert cleanly
    (an exception, an ``merror`` or a command left unconverted).

    >>> mathml(r"\Re\left\{x\right\}")  # doctest: +ELLIPSIS
    '<math><mi>ℜ</mi><mrow><mo stretchy="true" fence="true" form="prefix">{</mo><mi>x</mi>...</math>'
    >>> mathml(r"\foo x") is None
    True
    """
    try:  # latex2mathml's tree, serialised with its texts escaped (\text{<script>} is text)
        out = latex_to_mathml(normalise(latex), display="block" if display else "inline")
    except Exception:  # noqa: BLE001 - any failure means: show the source instead
        return None
    if "merror" in out or re.search(r">\\[A-Za-z]", out):
        return None
    out = clean_mathml(_compact(_postprocess(out)))  # last: only allowed MathML leaves this function
    return out.replace("<math>", '<math display="block">', 1) if display else out


def _line_pieces(line: str) -> list[str]:
    """The pieces of a line; pieces inside parentheses join their predecessor while short
    (the browser may break between any two pieces)."""
    out: list[str] = []
    for piece, level in tex.display_breaks(line):
        if out and level and len(out[-1]) + len(piece) <= 90:
            out[-1] = out[-1] + " " + piece
        else:
            out.append(piece)
    return out


def _fallback(latex: str, why: str) -> str:
    return ('<div class="hp-display hp-fallback"><span class="hp-note">LaTeX source (' + escape(why)
            + ')</span><pre>' + escape(latex) + "</pre></div>")


def math_html(latex: str | None) -> str:
    """A display as lines of MathML pieces (wrapping like a paragraph), or the marked source."""
    if not latex or not latex.strip():
        return '<div class="hp-display hp-fallback"><span class="hp-note">(no display)</span></div>'
    if not tex.is_balanced(tex.strip_tag(latex)[0]):
        return _fallback(latex, "unbalanced braces or environments: not a well-formed display")
    lines, tag = tex.display_lines(latex)
    rendered = []
    for k, line in enumerate(lines):
        pieces = [mathml(p) for p in _line_pieces(line)]
        if any(p is None for p in pieces):
            return _fallback(latex, "does not convert to MathML")
        suffix = f'<span class="hp-tag">({escape(tag)})</span>' if tag and k == len(lines) - 1 else ""
        rendered.append('<div class="hp-line">' + "<wbr>".join(pieces) + suffix + "</div>")
    return '<div class="hp-display">' + "".join(rendered) + "</div>"


def prose_html(text: str) -> str:
    r"""Text with inline ``$...$`` mathematics (quoted claims): the mathematics as MathML where
    it converts, the rest escaped.

    >>> prose_html(r"with $K = 60$, E < 0")  # doctest: +ELLIPSIS
    'with <math class="hp-inline"><mi>K</mi><mo>=</mo><mn>60</mn></math>, E &lt; 0'
    """
    parts = re.split(r"(?<!\\)\$", text)
    if len(parts) % 2 == 0:
        return escape(text)
    out = []
    for k, part in enumerate(parts):
        converted = mathml(part) if k % 2 and tex.is_balanced(part) else None
        if k % 2 and converted is not None:
            out.append(converted.replace("<math>", '<math class="hp-inline">', 1))
        else:
            out.append(escape(part if k % 2 == 0 else "$" + part + "$"))
    return "".join(out)


def _inline_math(latex: str | None, text: str) -> str:
    converted = mathml(latex) if latex is not None else None
    return converted if converted else escape(text)


# --------------------------------------------------------------------------------------------
# evidence: witness, facts, plots
# --------------------------------------------------------------------------------------------
def _witness_table(witness: Mapping[str, Any]) -> str:
    """The witness as a small two-row table: names (the paper's naming) over exact values."""
    names, values = [], []
    for name, value in to_jsonable(dict(witness)).items():
        latex = tex.value_math(value)
        names.append("<th>" + _inline_math(tex.name_math(name), name) + "</th>")
        values.append("<td>" + _inline_math(latex.replace(r"\tfrac", r"\frac") if latex else None,
                                            json.dumps(value) if not isinstance(value, str) else value) + "</td>")
    return ('<table class="hp-witness"><caption>witness</caption><tr>' + "".join(names) + "</tr><tr>"
            + "".join(values) + "</tr></table>")


def _plots(value: Any, path: str = "") -> list[tuple[str, Plot]]:
    if isinstance(value, Plot):
        return [(path, value)]
    if isinstance(value, Mapping):
        return [p for k, v in value.items() for p in _plots(v, f"{path}.{k}" if path else str(k))]
    if isinstance(value, (list, tuple)):
        return [p for k, v in enumerate(value) for p in _plots(v, f"{path}[{k}]")]
    return []


def _without_plots(value: Any) -> Any:
    if isinstance(value, Mapping):
        return {k: _without_plots(v) for k, v in value.items() if not isinstance(v, Plot)}
    if isinstance(value, (list, tuple)):
        return [_without_plots(v) for v in value if not isinstance(v, Plot)]
    return value


def _fact_value(value: Any, depth: int = 0) -> str:
    if isinstance(value, Mapping) and value and depth < 3:
        rows = "".join("<tr><th>" + escape(str(k)) + "</th><td>" + _fact_value(v, depth + 1) + "</td></tr>"
                       for k, v in value.items())
        return '<table class="hp-facts">' + rows + "</table>"
    if isinstance(value, list) and value and all(not isinstance(v, (list, dict)) for v in value):
        shown = ", ".join(escape(str(v)) for v in value[:24])
        return shown + (f" &hellip; ({len(value) - 24} more)" if len(value) > 24 else "")
    if isinstance(value, (list, dict)):
        return "<code>" + escape(json.dumps(value)) + "</code>"
    return escape(str(value))


def plot_svg(plot: Plot, key: str = "plot") -> str:
    """The plot as an inline ``<svg>`` (matplotlib, text kept as text, ids salted by ``key``)."""
    import matplotlib
    from matplotlib.backends.backend_svg import FigureCanvasSVG
    from matplotlib.figure import Figure

    styles = {"line": dict(ls="-", marker=""), "dashed": dict(ls="--", marker=""),
              "points": dict(ls=":", marker="o", ms=4)}
    with matplotlib.rc_context({"svg.fonttype": "none", "svg.hashsalt": key, "font.size": 9,
                                "font.family": "sans-serif"}):
        fig = Figure(figsize=(6.0, 3.0), layout="constrained")
        FigureCanvasSVG(fig)
        ax = fig.add_subplot(111)
        for k, series in enumerate(plot.series):
            ax.plot(series.x, series.y, color=f"C{k % 10}", lw=1.4, label=series.label, **styles[series.style])
        if plot.hline is not None:
            ax.axhline(plot.hline, color="0.35", lw=0.8, ls=":")
        ax.set_xlabel(plot.xlabel)
        ax.set_ylabel(plot.ylabel)
        ax.grid(True, alpha=0.3)
        if any(s.label for s in plot.series):
            ax.legend(fontsize=8)
        buffer = io.StringIO()
        fig.savefig(buffer, format="svg", metadata={"Date": None, "Creator": None})
    svg = buffer.getvalue()
    svg = svg[svg.index("<svg"):]
    svg = re.sub(r"<metadata>.*?</metadata>\s*", "", svg, flags=re.S)
    svg = re.sub(r'<svg([^>]*?) width="[^"]*" height="[^"]*"', r'<svg\1', svg, count=1)
    return svg.replace("<svg", f'<svg class="hp-svg" role="img" aria-label="{escape(plot.title)}"', 1)


def _evidence_html(evidence: Any, key: str) -> str:
    parts = ['<div class="hp-evidence"><span class="hp-label-inline">Evidence</span> <span class="hp-method">'
             + escape(str(evidence.method)) + "</span>"]
    if evidence.instances is not None:
        parts.append(f' &middot; {evidence.instances} instances')
    if evidence.witness:
        parts.append(_witness_table(evidence.witness))
    for path, plot in _plots(evidence.facts):
        parts.append('<figure class="hp-plot">' + plot_svg(plot, f"{key}-{path}") + "<figcaption>"
                     + escape(plot.title) + "</figcaption></figure>")
    facts = to_jsonable(_without_plots(dict(evidence.facts)))
    if facts:
        parts.append("<details><summary>facts</summary>" + _fact_value(facts) + "</details>")
    parts.append("</div>")
    return "".join(parts)


# --------------------------------------------------------------------------------------------
# equations and reports
# --------------------------------------------------------------------------------------------
def _badge(verdict: Verdict | str) -> str:
    value = Verdict(verdict).value
    return f'<span class="hp-badge hp-{value}">{value}</span>'


def _block(label: str, body: str) -> str:
    return f'<div class="hp-block"><div class="hp-label">{escape(label)}</div>{body}</div>'


def result_html(result: Any, anchor_id: str = "", timings: bool = True) -> str:
    """One audited equation as an ``<article>`` (anchor ``anchor_id``): the verdict badge,
    the detail, printed / derived / corrected displays, the evidence."""
    where = " &middot; ".join(escape(x) for x in (result.kind, f"Section {result.section}" if result.section else "") if x)
    ident = escape(anchor_id or tex.anchor("", result.id))
    head = (f'<header><a class="hp-id" href="#{ident}">({escape(result.id)})</a> <span class="hp-kind">{where}</span>'
            f" {_badge(result.verdict)}</header>")
    body = [head, f'<p class="hp-detail">{escape(result.detail)}</p>']
    if result.assumptions:
        body.append(f'<p class="hp-assumptions"><i>Assumptions:</i> {escape(result.assumptions)}</p>')
    if result.kind == "claim":
        body.append(_block("Printed (quoted)", f'<blockquote class="hp-quote">{prose_html(result.printed)}</blockquote>'))
    else:
        body.append(_block("Printed", math_html(result.printed)))
    if result.derived:
        body.append(_block("Derived", math_html(result.derived)))
    if result.corrected:
        body.append(_block("Corrected", math_html(result.corrected)))
    body.append(_evidence_html(result.evidence, ident))
    if timings:
        body.append(f'<footer class="hp-time">{result.seconds:.3f} s</footer>')
    attrs = f' id="{ident}"' if anchor_id else ""
    return (f'<article class="hp-eq hp-v-{result.verdict.value}"{attrs}>' + "".join(body) + "</article>")


def finding_html(finding: Any, names: Mapping | None = None) -> str:
    """A :class:`~hapticproof.core.evidence.Finding` (no equation attached): badge, detail,
    derived and corrected displays, evidence."""
    body = [f"<header>{_badge(finding.verdict)}</header>", f'<p class="hp-detail">{escape(finding.detail)}</p>']
    if finding.derived is not None:
        derived = finding.derived if isinstance(finding.derived, str) else tex.to_latex(finding.derived, names)
        body.append(_block("Derived", math_html(derived)))
    if finding.corrected:
        body.append(_block("Corrected", math_html(finding.corrected)))
    body.append(_evidence_html(finding.evidence, "finding"))
    return (f"<div class=\"hp-report\">{_STYLE}<article class=\"hp-eq hp-v-{finding.verdict.value}\">"
            + "".join(body) + "</article></div>")


def _counts(reports: Sequence[Any]) -> dict[Verdict, list[tuple[Any, Any]]]:
    out: dict[Verdict, list[tuple[Any, Any]]] = {v: [] for v in ERRATA_ORDER}
    for report in reports:
        for result in report.results:
            out[result.verdict].append((report, result))
    return out


def report_fragment(reports: Iterable[Any], timings: bool = True, title: str | None = None,
                    prefixed: bool | None = None) -> str:
    """The body of the report (with its scoped style): summary of counts per verdict with
    links, an index per verdict, then one card per equation. Notebooks show this (with
    ``prefixed`` anchors, ``hve-eq-17``, as several reports may share a page)."""
    reports = list(reports)
    single = len(reports) == 1 if prefixed is None else not prefixed
    if title is None:
        title = f"Audit of {reports[0].title} ({reports[0].paper})" if single else "hapticproof audit"
    counts = _counts(reports)
    total = sum(len(r.results) for r in reports)
    chips = "".join(f'<a class="hp-badge hp-{v.value}" href="#verdict-{v.value}">{v.value} <b>{len(items)}</b></a>'
                    for v, items in counts.items() if items)
    out = [f'<div class="hp-report">{_STYLE}<header class="hp-top"><h1>{escape(title)}</h1>',
           f'<p class="hp-meta">{total} equation{"s" if total != 1 else ""} in {len(reports)} '
           f'paper{"s" if len(reports) != 1 else ""} '
           f"&middot; hapticproof {escape(VERSION)}</p>",
           f'<nav class="hp-summary" aria-label="counts per verdict">{chips}</nav></header>',
           '<section class="hp-index"><h2>Index by verdict</h2>']
    for verdict, items in counts.items():
        if not items:
            continue
        links = ", ".join(
            f'<a href="#{tex.anchor(rep.paper, r.id, single)}">{"" if single else escape(rep.paper) + " "}({escape(r.id)})</a>'
            for rep, r in items)
        out.append(f'<div class="hp-index-row" id="verdict-{verdict.value}">{_badge(verdict)} '
                   f"<span class=\"hp-count\">{len(items)}</span> <span class=\"hp-links\">{links}</span></div>")
    out.append("</section>")
    for report in reports:
        out.append(f'<section class="hp-paper" id="paper-{escape(report.paper)}"><h2>{escape(report.paper)}: '
                   f"{escape(report.title)}</h2>")
        if getattr(report, "notation", None):      # the toolkit's names printed in the paper's stead
            out.append('<p class="hp-meta">notation: ' + escape(", ".join(f"{k} = {v}" for k, v in report.notation.items()))
                       + "</p>")
        out += [result_html(r, tex.anchor(report.paper, r.id, single), timings) for r in report.results]
        out.append("</section>")
    out.append("</div>")
    return "\n".join(out)


def report_html(reports: Iterable[Any], title: str | None = None, timings: bool = True) -> str:
    """A complete, self-contained HTML page of one or more audit reports.

    >>> from hapticproof.audit.runner import AuditReport
    >>> page = report_html([AuditReport("demo", "Demo", ())])
    >>> page.startswith("<!DOCTYPE html>") and "<script" not in page and "://" not in page.split("</title>")[0]
    True
    >>> "Content-Security-Policy" in page.split("</title>")[0]
    True
    """
    reports = list(reports)
    single = len(reports) == 1
    if title is None:
        title = f"Audit of {reports[0].title} ({reports[0].paper})" if single and reports else "hapticproof audit"
    return ("<!DOCTYPE html>\n<html lang=\"en\"><head><meta charset=\"utf-8\">" + CSP_META
            + '<meta name="viewport" content="width=device-width, initial-scale=1">'
            f"<title>{escape(title)}</title></head>\n<body>\n"
            + report_fragment(reports, timings, title) + "\n</body></html>\n")


_BADGE_CSS = "".join(f".hp-report .hp-{v}{{background:#{c}}} .hp-report .hp-v-{v}{{border-left-color:#{c}}}"
                     for v, c in tex.VERDICT_COLOURS.items())

_STYLE = """<style>
.hp-report{font:15px/1.5 system-ui,-apple-system,"Segoe UI",Roboto,"DejaVu Sans",sans-serif;color:#1a202c;
 max-width:62rem;margin:0 auto;padding:0 1rem;overflow-wrap:break-word}
.hp-report h1{font-size:1.6rem;margin:1rem 0 .2rem}.hp-report h2{font-size:1.25rem;margin:1.6rem 0 .6rem;
 border-bottom:1px solid #e2e8f0}
.hp-report .hp-meta{color:#4a5568;margin:.2rem 0 .6rem}
.hp-report .hp-summary{display:flex;flex-wrap:wrap;gap:.4rem}
.hp-report .hp-badge{display:inline-block;color:#fff;border-radius:.3rem;padding:.05rem .5rem;font-size:.85rem;
 font-weight:600;text-decoration:none;white-space:nowrap}
.hp-report .hp-summary .hp-badge{font-size:.95rem;padding:.2rem .7rem}
.hp-report .hp-index-row{margin:.3rem 0}.hp-report .hp-count{font-weight:600;margin:0 .3rem}
.hp-report .hp-links a{color:#2b6cb0;text-decoration:none;white-space:nowrap}
.hp-report .hp-eq{border:1px solid #e2e8f0;border-left:.35rem solid #a0aec0;border-radius:.3rem;
 padding:.6rem .9rem;margin:1rem 0;background:#fff;scroll-margin-top:.5rem}
.hp-report .hp-eq:target{box-shadow:0 0 0 3px #bee3f8}
.hp-report .hp-eq>header{display:flex;align-items:baseline;gap:.6rem;flex-wrap:wrap}
.hp-report .hp-eq>header .hp-badge{margin-left:auto}
.hp-report a.hp-id{font-weight:700;font-size:1.15rem;color:#1a202c;text-decoration:none}
.hp-report a.hp-badge,.hp-report a.hp-badge:hover{color:#fff;text-decoration:none}
.hp-report .hp-kind{color:#4a5568;font-size:.9rem}
.hp-report .hp-detail{margin:.4rem 0}.hp-report .hp-assumptions{margin:.2rem 0;font-size:.9rem;color:#4a5568}
.hp-report .hp-block{margin:.5rem 0}
.hp-report .hp-label{font-size:.8rem;font-weight:700;text-transform:uppercase;letter-spacing:.04em;color:#4a5568}
.hp-report .hp-display{margin:.2rem 0 .2rem 1rem;overflow-x:auto;overflow-y:hidden;max-width:100%}
.hp-report .hp-line{padding-left:2rem;text-indent:-2rem;margin:.25rem 0;font-size:1.1rem}
.hp-report .hp-line math{text-indent:0}
.hp-report math{math-style:normal}.hp-report math.hp-inline{math-style:compact}
.hp-report mtd[columnalign=left]{text-align:left}.hp-report mtd[columnalign=right]{text-align:right}
.hp-report .hp-boxed{border:1px solid currentColor;padding:.1em .2em}
.hp-report .hp-tag{float:right;text-indent:0}
.hp-report .hp-fallback pre{white-space:pre-wrap;overflow-wrap:anywhere;background:#fffaf0;border:1px dashed #c05621;
 padding:.4rem;margin:.2rem 0;font-size:.85rem}
.hp-report .hp-note{font-size:.8rem;color:#c05621}
.hp-report .hp-quote{margin:.2rem 0 .2rem 1rem;font-style:italic;border-left:3px solid #e2e8f0;padding-left:.6rem}
.hp-report .hp-evidence{font-size:.9rem;margin-top:.5rem;color:#2d3748}
.hp-report .hp-label-inline{font-weight:700}.hp-report .hp-method{font-family:ui-monospace,monospace}
.hp-report table{border-collapse:collapse;margin:.3rem 0;max-width:100%}
.hp-report .hp-witness caption{text-align:left;font-size:.8rem;color:#4a5568}
.hp-report th,.hp-report td{border:1px solid #e2e8f0;padding:.1rem .5rem;text-align:left;vertical-align:top}
.hp-report .hp-witness th{background:#f7fafc;text-align:center}.hp-report .hp-witness td{text-align:center}
.hp-report .hp-witness{display:block;overflow-x:auto;max-width:100%}
.hp-report .hp-facts{font-size:.85rem;table-layout:auto}
.hp-report .hp-facts td{overflow-wrap:anywhere}.hp-report code{overflow-wrap:anywhere;font-size:.8rem}
.hp-report details summary{cursor:pointer;color:#2b6cb0}
.hp-report .hp-plot{margin:.5rem 0}.hp-report .hp-svg{width:100%;max-width:36rem;height:auto}
.hp-report figcaption{font-size:.85rem;color:#4a5568}
.hp-report .hp-time{font-size:.75rem;color:#718096;text-align:right}
""" + _BADGE_CSS + "\n</style>"
