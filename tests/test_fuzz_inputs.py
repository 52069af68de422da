"""Fuzzing what strangers hand over (issue 22): Hypothesis draws paper files and scene files from
the TOML grammar, saved reports from the JSON grammar and printed displays from the LaTeX
grammar, mixed with the issue's injection strings (scripts, ``^^5c``, file names outside the
folder, sizes, ``nan``, cycles, foreign digits), and runs them through the command line.

Every example must end without a traceback (exit 0, 1 or 2, one line on standard error for a
refusal); the HTML it writes must parse to a page with no script, event handler, ``javascript:``
URL or embedded object (parsed with :mod:`html.parser`, not searched for strings); its LaTeX must
read no ``^^`` code and no refused command as TeX reads it (:mod:`hapticproof.core.texsafe`),
and, compiled with pdflatex when it is installed, read and write no file outside the example's
folder (``-recorder``); Python must open no file outside the temporary folder and the installed
code (an audit hook records every ``open``, directory listing and process start), and each
example must stay within a time and a memory bound.

Issue 30 adds the surfaces of a hostile author: outputs named by planted links, FIFOs and
directories (nothing is written through them, nothing is left beside them), the Markdown report
(no raw HTML outside code spans), forged saved reports (genuine certificates bound to another
object, edited decisions, witnesses and kinds: never accepted), parameters defined from each
other (bounded after substitution), crafted boundary reports (sizes that would abort FLINT) and
sources with long runs of spaces (no back-tracking).

The limits in force are tightened for the run (:func:`hapticproof.core.limits.raised`), so
that each example is bounded by what the limits allow. Knobs (environment):

``HAPTICPROOF_FUZZ_EXAMPLES``
    examples per test (default 8: about a minute of CPU for the four tests together);
    ``HYPOTHESIS_PROFILE=explore HAPTICPROOF_FUZZ_EXAMPLES=300`` is a large run.
``HAPTICPROOF_FUZZ_SECONDS``
    the bound on one example's wall-clock time (default 300: a symbolic three-user scene's audit
    takes 20 s on a quiet machine, several times that on a shared one).
``HAPTICPROOF_FUZZ_MEGABYTES``
    the bound on the growth of the process's memory during a test (default 1500).
"""

from __future__ import annotations

import json
import os
import re
import resource
import shutil
import subprocess
import sys
import sysconfig
import tempfile
import time
from html.parser import HTMLParser
from pathlib import Path

import pytest
from hypothesis import HealthCheck, Phase, event, example, given, settings
from hypothesis import strategies as st

sys.path.insert(0, str(Path(__file__).resolve().parent))

from hapticproof.cli import main
from hapticproof.core import limits
from hapticproof.core.texsafe import ALWAYS_REFUSED, tokenize

EXAMPLES = int(os.environ.get("HAPTICPROOF_FUZZ_EXAMPLES", "8"))
SECONDS = float(os.environ.get("HAPTICPROOF_FUZZ_SECONDS", "300"))
MEGABYTES = float(os.environ.get("HAPTICPROOF_FUZZ_MEGABYTES", "1500"))
PDFLATEX = shutil.which("pdflatex")

#: tight limits: every example is cheap whatever it asks for
TIGHT = dict(delay=24, users=4, exponent=40, degree=120, digits=60, depth=30, grid=400, minors=64,
             file_size=200_000)

# no "explain" phase: it reruns the failing example under a tracer, many times slower, so that
# the time bound would fail where the example itself did not
FUZZ = settings(max_examples=EXAMPLES, deadline=None, database=None,
                phases=(Phase.explicit, Phase.reuse, Phase.generate, Phase.target, Phase.shrink),
                suppress_health_check=[HealthCheck.too_slow, HealthCheck.data_too_large,
                                       HealthCheck.function_scoped_fixture])

# ---------------------------------------------------------------------------------------------
# the injections of the issue
# ---------------------------------------------------------------------------------------------
PAYLOADS = ["<script>document.title='PWNED'</script>", "<img src=x onerror=alert(1)>",
            "</mtext></math><svg onload=alert(1)></svg>", "<a href=\"javascript:alert(1)\">x</a>", "&lt;script&gt;"]
TEX_INJECTIONS = [
    r"^^5cinput{/etc/hostname}", r"^^5cimmediate^^5copenout5 pwned.tex", r"\^^69nput{/etc/hostname}",
    r"^^5e^5cinput{x}", r"\csname input\endcsname{x}", r"a^&^5cinput{x}", r"\href{javascript:alert(1)}{B}",
    r"\input{/etc/hostname}", r"\immediate\write18{touch shell-ran}", r"\catcode`\^=7", "%", "#1", "\\",
    r"\tag{^^5cinput x }", r"\begin{verbatim}", r"\end{document}", r"\def\x{y}", "$",
]
SIZE_INJECTIONS = [r"K^{99999999}", r"2^{2^{2^{2^{2^{2^{2}}}}}}", "{" * 60 + "K" + "}" * 60, "9" * 200,
                   r"K^{41}", "1e999999999"]
TEXT_COMMANDS = [r"\text", r"\textrm", r"\mbox", r"\textit", r"\textbf", r"\hbox", r"\texttt"]
FILE_INJECTIONS = ["/proc/self/environ", "/etc/shadow", "/etc/hostname", "../../x", "../outside.txt", "/dev/zero",
                   "/dev/stdin", "~/x", "m.txt", "link", "fifo", "sub/../m.txt", "", "m.json"]
VALUE_INJECTIONS = ["nan", "inf", "-inf", "1/0", "\u0661\u0666", "K/2", "B*2", "1e999999999", "9" * 100, "positive",
                    "0", "-1", "0.001", "z", "s", "n", "K_{12}", "(((((((((((((((((((((((((((((((((K)))))))))))))))))))))))))))))))))"]

SAFE_TEXT = st.text(alphabet=st.characters(codec="utf-8", exclude_categories=("Cs",)), max_size=12)
SPECIAL_TEXT = st.text(alphabet="^\\{}%#&<>\"'~$_ \n\r\t\x00\x1b\u2028<>&;=/:.()[]abcKT5e", max_size=16)

# ---------------------------------------------------------------------------------------------
# the LaTeX grammar of printed displays
# ---------------------------------------------------------------------------------------------
ATOMS = ["b", "K", "B", "T", "z", "c", r"\omega", "2", "0.5", "j", "K_{12}", "b_1", "t_d", r"\cos(\omega T)", "e^{j\\omega T}"]


def _latex() -> st.SearchStrategy[str]:
    leaf = st.one_of(st.sampled_from(ATOMS), st.sampled_from(TEX_INJECTIONS), st.sampled_from(SIZE_INJECTIONS),
                     SPECIAL_TEXT,
                     st.tuples(st.sampled_from(TEXT_COMMANDS), st.sampled_from(PAYLOADS)).map(lambda t: f"{t[0]}{{{t[1]}}}"))
    return st.recursive(leaf, lambda inner: st.one_of(
        st.tuples(inner, st.sampled_from(["+", "-", " ", r"\cdot ", "/", "&", r"\\", ","]), inner).map("".join),
        st.tuples(inner, inner).map(lambda t: rf"\frac{{{t[0]}}}{{{t[1]}}}"),
        st.tuples(inner, inner).map(lambda t: f"{t[0]}^{{{t[1]}}}"),
        st.tuples(inner, inner).map(lambda t: f"{t[0]}_{{{t[1]}}}"),
        inner.map(lambda a: rf"\left( {a} \right)"),
        inner.map(lambda a: "{" + a + "}"),
    ), max_leaves=8)


LATEX = _latex()
DISPLAYS = st.one_of(st.tuples(LATEX, st.sampled_from([" > ", " < ", " = ", r" \geq ", r" \leq "]), LATEX).map("".join),
                     LATEX)

# ---------------------------------------------------------------------------------------------
# the grammar of user expressions (core.expr) and of scene fields
# ---------------------------------------------------------------------------------------------


def _expression(variable: str) -> st.SearchStrategy[str]:
    leaf = st.one_of(st.sampled_from(["K", "B", "T", "a", "2", "0.5", "1e-3", variable, "b", "M"]),
                     st.sampled_from(VALUE_INJECTIONS), st.sampled_from(["z**10**9", "(z**40)**40", "s**-41"]))
    return st.recursive(leaf, lambda inner: st.one_of(
        st.tuples(inner, st.sampled_from(["+", "-", "*", "/", "**", "^"]), inner).map(lambda t: f"{t[0]} {t[1]} {t[2]}"),
        inner.map(lambda a: f"({a})"), inner.map(lambda a: f"-{a}"),
    ), max_leaves=6)


SCALARS = st.one_of(st.integers(-3, 30), st.sampled_from(VALUE_INJECTIONS), st.booleans(),
                    st.sampled_from([float("nan"), float("inf"), 0.5, 1e300]), SAFE_TEXT)
TOML_VALUES = st.recursive(SCALARS, lambda inner: st.one_of(st.lists(inner, max_size=3),
                                                             st.dictionaries(st.sampled_from(["K", "x", "a b"]), inner,
                                                                             max_size=2)), max_leaves=4)


PARAM_VALUES = st.one_of(st.sampled_from(["0.001", "1/3", "2", "positive", "real", "nonnegative", 1, 2, 20]),
                         st.sampled_from(VALUE_INJECTIONS), TOML_VALUES)


def _valid_scene() -> st.SearchStrategy[dict]:
    """Scenes a user would write (with the odd hostile value in a parameter)."""
    single = st.fixed_dictionaries({"system": st.just("single-user")}, optional={
        "environment": st.one_of(st.sampled_from(["K + B*(z - 1)/(T*z)", "K", "K + B*(1 - a)*(z - 1)/(T*(z - a))"]),
                                 _expression("z")),
        "delay": st.one_of(st.integers(0, 4), st.just("n")),
        "approximation": st.sampled_from(["forward", "backward", "tustin"]),
        "params": st.dictionaries(st.sampled_from(["K", "B", "T", "b", "a"]), PARAM_VALUES, max_size=3)})
    multi = st.fixed_dictionaries({"system": st.just("multi-user"), "users": st.integers(2, 3)}, optional={
        "uniform": st.booleans(), "delay": st.integers(0, 2),
        "params": st.dictionaries(st.sampled_from(["K", "B", "T", "b", "K_0"]), PARAM_VALUES, max_size=2)})
    network = st.fixed_dictionaries({"system": st.just("network"),
                                     "matrix": st.one_of(st.sampled_from(FILE_INJECTIONS),
                                                         st.just([["s + 1", "1"], ["1", "s + 1"]]))})
    tele = st.fixed_dictionaries({"system": st.just("teleoperator")}, optional={
        "controller": st.one_of(st.sampled_from(["pd", "filtered-pd"]), _expression("z"))})
    return st.one_of(single, single, multi, network, tele)


def _fuzzy_scene() -> st.SearchStrategy[dict]:
    """Any field with any value."""
    systems = st.sampled_from(["single-user", "multi-user", "teleoperator", "network", "single_user"])
    return st.fixed_dictionaries({"system": systems}, optional={
        "environment": st.one_of(_expression("z"), _expression("s"), TOML_VALUES),
        "controller": st.one_of(_expression("z"), st.sampled_from(["pd", "filtered-pd"])),
        "approximation": st.sampled_from(["forward", "backward", "tustin", "zoh"]),
        "delay": st.one_of(st.integers(0, 30), st.sampled_from(["n", "1/0", "\u0661\u0666", "2,3", "1e9"]),
                           st.lists(st.integers(0, 3), max_size=3), st.just([[1]]), st.just(1000000000)),
        "users": st.one_of(st.integers(-1, 6), st.just(100), st.just(1000000000), st.just(2.5)),
        "uniform": st.booleans(),
        "matrix": st.one_of(st.sampled_from(FILE_INJECTIONS), st.just([["s", "1"], ["1", "s"]])),
        "ports": st.one_of(st.just([1, 1]), st.just(["a"]), st.just("1,1"), st.just([[1]])),
        "discretize": st.sampled_from(["tustin", "zoh", "foo"]),
        "params": st.dictionaries(st.sampled_from(["K", "B", "T", "b", "a", "M", "z", "K_12", "_x", "m"]),
                                  PARAM_VALUES, max_size=4),
        "enviroment": st.just("K"),
    })


@st.composite
def _chained_scene(draw) -> dict:
    """Parameters defined from each other (``K_i = K_{i-1}^e``): each line within the limits,
    the values they reach after substitution far beyond them."""
    count = draw(st.integers(1, 40))
    exponent = draw(st.sampled_from(["2", "3", "10", "-2", "1/2"]))
    base = draw(st.sampled_from([2, 3, 10, "positive", "0.5", "K"]))
    params = {"K_0": base, "B": "0.001", "T": "0.001", "b": "1"}
    for i in range(1, count + 1):
        params[f"K_{i}"] = draw(st.sampled_from([f"K_{i - 1}**{exponent}", f"K_{i - 1}*K_{i - 1}", f"K_{i - 1} + K_{i - 1}",
                                                 f"(K_{i - 1} + 1)**{exponent}"]))
    return {"system": "single-user", "environment": f"K_{count} + B*(z - 1)/(T*z)", "params": params}


def _scene() -> st.SearchStrategy[dict]:
    return st.one_of(_valid_scene(), _valid_scene(), _fuzzy_scene(), _chained_scene())


# ---------------------------------------------------------------------------------------------
# writing TOML (our own writer: the fuzz needs values tomllib would never write)
# ---------------------------------------------------------------------------------------------


def _toml_string(text: str) -> str:
    """A TOML basic string: backslash, quote and control characters escaped, the rest as is."""
    out = []
    for ch in text:
        if ch in '"\\':
            out.append("\\" + ch)
        elif ord(ch) < 32 or ord(ch) == 127:
            out.append(f"\\u{ord(ch):04x}")
        else:
            out.append(ch)
    return '"' + "".join(out) + '"'


def _toml_value(value) -> str:
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, float):
        return "nan" if value != value else ("inf" if value == float("inf") else ("-inf" if value == -float("inf")
                                                                                     else repr(value)))
    if isinstance(value, int):
        return str(value)
    if isinstance(value, str):
        return _toml_string(value)
    if isinstance(value, list):
        return "[" + ", ".join(_toml_value(v) for v in value) + "]"
    if isinstance(value, dict):
        return "{" + ", ".join(f"{_toml_string(k)} = {_toml_value(v)}" for k, v in value.items()) + "}"
    raise TypeError(value)


def _table(name: str, fields: dict) -> list[str]:
    lines = [f"[{name}]"] if name else []
    nested = {k: v for k, v in fields.items() if isinstance(v, dict) and k == "params"}
    for key, value in fields.items():
        if key not in nested:
            lines.append(f"{_toml_string(key)} = {_toml_value(value)}")
    for key, value in nested.items():
        lines.append(f"[{name + '.' if name else ''}{key}]")
        lines += [f"{_toml_string(k)} = {_toml_value(v)}" for k, v in value.items()]
    return lines


EQUATION = st.fixed_dictionaries({
    "id": st.one_of(st.sampled_from(["1", "2", "3", "20"]), SAFE_TEXT),
    "printed": st.one_of(DISPLAYS, st.sampled_from(TEX_INJECTIONS)),
    "claim": st.sampled_from(["passivity-condition"] * 3 + ["sufficient-condition", "inverse-transfer", "hermitian-part",
                              "residue", "same-as", "stability-condition", "passivity"]),
}, optional={
    "scene": st.sampled_from(["s"] * 4 + ["t", "missing"]),
    "other": st.sampled_from(["1", "2", "hve:20", "hve:999", "nope:1"]),
    "under": st.one_of(st.just("z_a = 0, t_d = 0"), DISPLAYS),
    "assumption": st.one_of(st.just("B = 0"), DISPLAYS),
    "notes": SAFE_TEXT, "section": st.sampled_from(["1", "2.1", ""]), "solve_for": st.sampled_from(["b", "K", "x"]),
})


@st.composite
def paper_files(draw) -> str:
    meta = {"id": draw(st.sampled_from(["fuzz", "fuzz", "fuzz", "hve", "bad id", "", "x^^5c"])),
            "title": draw(st.one_of(st.sampled_from(PAYLOADS + TEX_INJECTIONS), SAFE_TEXT))}
    symbols = {"b": "positive", "K": "positive", "B": "real", "T": "positive", "omega": "real"}
    good = {"S": r"\frac{\sin(\omega T)}{2}", "G^{-1}": "function", "F_h": "signal", "V_h": "signal",
            "K_{ij}": "positive, symmetric", "M": "nonnegative"}
    for key in draw(st.lists(st.sampled_from(sorted(good)), max_size=3, unique=True)):
        symbols[key] = good[key]
    symbols.update(draw(st.dictionaries(st.sampled_from(["x", "z", "omega", "1bad", "S"]),
                                        st.one_of(st.sampled_from(["function", "postive"]), DISPLAYS, SCALARS),
                                        max_size=1)))
    lines = _table("paper", meta) + [""] + _table("symbols", symbols)
    for name in draw(st.lists(st.sampled_from(["s", "t"]), min_size=1, max_size=2, unique=True)):
        lines += [""] + _table(f"scenes.{name}", draw(_scene()))
    for entry in draw(st.lists(EQUATION, min_size=1, max_size=3)):
        entry.setdefault("scene", "s")
        lines += ["", "[[equations]]"] + [f"{k} = {_toml_value(v)}" for k, v in entry.items()]
    text = "\n".join(lines) + "\n"
    return _damage(draw, text)


def _damage(draw, text: str) -> str:
    """Sometimes break the file itself: a cut, a stray character, deep nesting, a BOM."""
    kind = draw(st.sampled_from(["none"] * 12 + ["cut", "insert", "nest", "bom"]))
    if kind == "cut":
        return text[: draw(st.integers(0, len(text)))]
    if kind == "insert":
        k = draw(st.integers(0, len(text)))
        return text[:k] + draw(st.sampled_from(["[", "]", '"', "'''", "=", "\x00", "\ufeff", "\\u"])) + text[k:]
    if kind == "nest":
        return text + "deep = " + "[" * 40 + "]" * 40 + "\n"
    if kind == "bom":
        return "\ufeff" + text
    return text


# ---------------------------------------------------------------------------------------------
# the JSON grammar of saved reports
# ---------------------------------------------------------------------------------------------
JSON_VALUES = st.recursive(st.one_of(st.none(), st.booleans(), st.integers(-5, 5), st.sampled_from(["1/3", "x", ""]),
                                     DISPLAYS),
                           lambda inner: st.one_of(st.lists(inner, max_size=3),
                                                   st.dictionaries(st.sampled_from(["method", "witness", "c", "facts"]),
                                                                   inner, max_size=3)), max_leaves=6)
VERDICTS = ["confirmed", "conservative", "typo", "wrong", "needs-assumption", "inconsistent", "malformed", "undecided"]
SAVED_EQUATION = st.fixed_dictionaries({
    "id": st.one_of(st.sampled_from(["20", "17", "1"]), SAFE_TEXT),
    "kind": st.sampled_from(["condition", "expression", "claim"]),
    "printed": DISPLAYS, "derived": st.one_of(st.none(), DISPLAYS), "corrected": st.one_of(st.none(), DISPLAYS),
    "verdict": st.sampled_from(VERDICTS), "detail": st.one_of(SAFE_TEXT, st.sampled_from(PAYLOADS)),
    "evidence": st.fixed_dictionaries({"method": st.sampled_from(["canonical-form", "counterexample"])},
                                      optional={"witness": st.dictionaries(st.sampled_from(["c", "K", "<b>"]),
                                                                           st.one_of(st.sampled_from(["1/2", "-1"]),
                                                                                     DISPLAYS), max_size=2),
                                                "facts": st.dictionaries(st.sampled_from(["certificate", "note"]),
                                                                         JSON_VALUES, max_size=2)}),
    "seconds": st.floats(0, 1),
})


@st.composite
def saved_reports(draw) -> str:
    report = {"paper": "hve", "title": draw(st.one_of(st.just("HVE"), st.sampled_from(PAYLOADS))),
              "equations": draw(st.lists(SAVED_EQUATION, min_size=1, max_size=3))}
    mutation = draw(st.sampled_from(["none"] * 4 + ["value", "drop", "wrap", "junk", "deep"]))
    if mutation == "value":
        equation = report["equations"][0]
        equation[draw(st.sampled_from(sorted(equation)))] = draw(JSON_VALUES)
    elif mutation == "drop":
        report["equations"][0].pop(draw(st.sampled_from(sorted(report["equations"][0]))))
    elif mutation == "wrap":
        report = {"papers": [report, draw(JSON_VALUES)]}
    elif mutation == "junk":
        report = draw(JSON_VALUES)
    elif mutation == "deep":
        return "[" * 200 + "]" * 200
    return json.dumps(report)


# ---------------------------------------------------------------------------------------------
# what is watched: files opened, processes started, time, memory
# ---------------------------------------------------------------------------------------------
_WATCH: dict = {"root": None, "events": []}


def _code_folders() -> tuple[str, ...]:
    folders = {sys.prefix, sys.base_prefix, sys.exec_prefix, *sysconfig.get_paths().values()}
    folders |= {p for p in sys.path if p and os.path.isdir(p)}
    folders.add(str(Path(__file__).resolve().parents[1]))        # the checkout (source, derivations)
    try:                                                          # matplotlib's font cache (figures)
        import matplotlib

        folders |= {matplotlib.get_cachedir(), matplotlib.get_configdir()}
    except ImportError:
        pass
    return tuple(sorted({os.path.realpath(f) for f in folders if f}))


def _hook(event: str, args: tuple) -> None:
    root = _WATCH["root"]
    if root is None:
        return
    if event in ("subprocess.Popen", "os.system", "os.exec", "os.posix_spawn", "os.spawn", "socket.connect"):
        _WATCH["events"].append((event, str(args[:2])))
    elif event in ("open", "os.listdir", "os.scandir"):
        path = args[0] if args else None
        if isinstance(path, int) or path is None:
            return
        path = os.fsdecode(path)
        full = os.path.realpath(path)
        writing = event == "open" and ((isinstance(args[1], str) and any(m in args[1] for m in "wax+"))
                                       or (isinstance(args[2], int) and args[2] & (os.O_WRONLY | os.O_RDWR)))
        if full == root or full.startswith(root + os.sep) or full in ("/dev/null", "/dev/urandom"):
            return
        if writing:
            if "__pycache__" not in full:
                _WATCH["events"].append(("write", full))
        elif not full.startswith(_WATCH["code"]):
            _WATCH["events"].append(("read", full))


if not getattr(sys, "_hapticproof_fuzz_hook", False):
    sys.addaudithook(_hook)
    sys._hapticproof_fuzz_hook = True


class _Watch:
    """The example's folder; on exit, every file access outside it and the code, and the time."""

    def __init__(self) -> None:
        self.folder = Path(tempfile.mkdtemp(prefix="hp-fuzz-"))

    def __enter__(self) -> Path:
        _WATCH["code"] = _code_folders()
        _WATCH["root"] = os.path.realpath(self.folder)
        _WATCH["events"] = []
        self.start = time.monotonic()
        return self.folder

    def __exit__(self, *exc) -> None:
        _WATCH["root"] = None
        seconds = time.monotonic() - self.start
        shutil.rmtree(self.folder, ignore_errors=True)
        if exc[0] is None:
            assert _WATCH["events"] == [], f"access outside the example's folder: {_WATCH['events'][:5]}"
            assert seconds < SECONDS, f"an example took {seconds:.0f} s (bound {SECONDS:.0f} s)"


@pytest.fixture
def bounded():
    """Tight limits, a memory ceiling (address space) and the growth of the resident set checked."""
    soft, hard = resource.getrlimit(resource.RLIMIT_AS)
    size = int(Path("/proc/self/statm").read_text().split()[0]) * resource.getpagesize() if Path("/proc/self/statm").exists() else 0
    ceiling = size + int(MEGABYTES * 2**20) * 2
    if size and (hard == resource.RLIM_INFINITY or ceiling < hard):
        resource.setrlimit(resource.RLIMIT_AS, (ceiling, hard))
    before = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss
    try:
        with limits.raised(**TIGHT):
            yield
    finally:
        resource.setrlimit(resource.RLIMIT_AS, (soft, hard))
    grown = (resource.getrusage(resource.RUSAGE_SELF).ru_maxrss - before) / 1024
    assert grown < MEGABYTES, f"memory grew by {grown:.0f} MB (bound {MEGABYTES:.0f} MB)"


# ---------------------------------------------------------------------------------------------
# the checks of the outputs
# ---------------------------------------------------------------------------------------------
_FORBIDDEN = {"script", "iframe", "frame", "object", "embed", "applet", "img", "image", "form", "input", "button",
              "base", "link", "portal", "audio", "video", "source", "track", "foreignobject", "maction", "animate",
              "set", "template", "noscript", "use"}


class _Page(HTMLParser):
    """The page as a browser's tokenizer sees its tags and attributes."""

    def __init__(self) -> None:
        super().__init__(convert_charrefs=True)
        self.problems: list[str] = []
        self.tags = 0

    def handle_starttag(self, tag, attrs):
        self.tags += 1
        if tag in _FORBIDDEN:
            self.problems.append(f"<{tag}>")
        for name, value in attrs:
            value = "".join((value or "").split()).lower()
            if name.startswith("on"):
                self.problems.append(f"{name} on <{tag}>")
            if "javascript:" in value or "vbscript:" in value or (name in ("href", "src", "xlink:href", "action")
                                                                  and not value.startswith("#")):
                self.problems.append(f"{name}={value[:40]} on <{tag}>")
            if tag == "meta" and name == "http-equiv" and value != "content-security-policy":
                self.problems.append(f"meta {value}")

    handle_startendtag = handle_starttag


def assert_inert_html(page: str) -> None:
    parser = _Page()
    parser.feed(page)
    parser.close()
    assert parser.tags > 5 and parser.problems == [], parser.problems[:5]
    head = page.split("</head>")[0]
    assert "Content-Security-Policy" in head and "script-src 'none'" in head


def assert_inert_latex(source: str) -> None:
    body = source.split(r"\begin{document}", 1)[-1]
    reading = tokenize(body)
    assert reading.carets == [], [c.source for c in reading.carets[:3]]
    used = {t.text for t in reading.tokens if t.kind == "cs"}
    # the report's own structure uses a few refused names (links between its sections, the end)
    own = {"hyperlink", "hypertarget", "end"}
    assert used & ALWAYS_REFUSED <= own, sorted(used & ALWAYS_REFUSED - own)


def outside_code_spans(markdown: str) -> str:
    """The Markdown text with its inline code spans removed (CommonMark: a run of n backticks
    opens a span that the next run of exactly n backticks closes)."""
    out, k = [], 0
    while k < len(markdown):
        if markdown[k] == "`":
            run = re.match(r"`+", markdown[k:]).group()
            end = re.compile(r"(?<!`)" + run + r"(?!`)").search(markdown, k + len(run))
            if end is not None:
                k = end.end()
                continue
            out.append(run)
            k += len(run)
            continue
        out.append(markdown[k])
        k += 1
    return "".join(out)


def assert_inert_markdown(text: str) -> None:
    """No raw HTML and no autolink (both start with a literal ``<`` outside code spans), no
    control character (a terminal shows Markdown too)."""
    assert "<" not in outside_code_spans(text), outside_code_spans(text)[:300]
    assert not [ch for ch in text if ch != "\n" and (ord(ch) < 32 or 127 <= ord(ch) < 160)]


def compile_latex(example: Path, source: str) -> None:
    """pdflatex with TeX Live's defaults (no restriction) on ``source`` in a folder of the example:
    it reads and writes inside that folder and the TeX installation only, as its ``-recorder``
    file lists (a secret waits beside the folder)."""
    if PDFLATEX is None:
        return
    _WATCH["root"] = None                     # pdflatex's own reads are checked by its recorder
    folder = example / "tex"
    folder.mkdir()
    (example / "outside.tex").write_text("SECRETMARKER", encoding="ascii")
    (folder / "r.tex").write_text(source, encoding="utf-8")
    subprocess.run([PDFLATEX, "-recorder", "-interaction=batchmode", "r.tex"], cwd=folder, capture_output=True,
                   timeout=120)
    trees = [os.path.realpath(p) for p in ("/usr/share/texmf", "/usr/share/texlive", "/etc/texmf", "/var/lib/texmf",
                                           "/usr/local/share/texmf", os.path.expanduser("~/.texlive"))]
    here = os.path.realpath(folder)
    fls = folder / "r.fls"
    assert fls.exists(), "pdflatex did not run"
    for line in fls.read_text(encoding="latin-1").splitlines():
        kind, _, path = line.partition(" ")
        if kind not in ("INPUT", "OUTPUT"):
            continue
        full = os.path.realpath(path if os.path.isabs(path) else folder / path)
        inside = full.startswith(here + os.sep)
        assert inside or (kind == "INPUT" and any(full.startswith(t + os.sep) for t in trees)), (kind, full)
    assert not (folder / "pwned.tex").exists() and not (folder / "shell-ran").exists()


def run_cli(capsys, argv: list[str]) -> tuple[int, str]:
    try:
        status = main([str(a) for a in argv])
        usage = False
    except SystemExit as exit:        # argparse: an option the system has not (its usage, then one line)
        status, usage = exit.code, True
    captured = capsys.readouterr()
    err = captured.err
    assert status in (0, 1, 2), (status, err[-500:])
    assert "Traceback" not in err, err[-800:]
    if status == 2 and not usage:
        assert len(err.strip().splitlines()) == 1, err[-800:]
    event(f"{argv[0]}: exit {status}" + (f" ({_reason(err)})" if status == 2 else ""))
    return status, err


def _reason(err: str) -> str:
    """The kind of a refusal, for the statistics (``--hypothesis-show-statistics``)."""
    text = re.sub(r"^hapticproof: error: ", "", err.strip())
    text = re.sub(r"/tmp/hp-fuzz-[^ :]*(:\d+)?:? ?", "", text)
    return " ".join(text.split()[:4])[:50]


def _files_beside(folder: Path) -> None:
    """The files the injections name: one in the folder, one link out of it, a FIFO."""
    (folder / "m.txt").write_text("s, 1\n1, s\n", encoding="utf-8")
    (folder / "m.json").write_text('{"matrix": [["s"]], "ports": [1]}', encoding="utf-8")
    (folder / "link").symlink_to("/etc/hostname")
    os.mkfifo(folder / "fifo")


# ---------------------------------------------------------------------------------------------
# the tests
# ---------------------------------------------------------------------------------------------


@FUZZ
@given(text=paper_files())
def test_fuzz_paper_files(text, capsys, bounded):
    with _Watch() as folder:
        _files_beside(folder)
        work = folder / "paper"
        work.mkdir()
        path = work / "p.toml"
        path.write_text(text, encoding="utf-8")
        for fmt in ("html", "tex", "markdown"):
            status, _ = run_cli(capsys, ["audit", "--paper", path, "--jobs", "1", "--format", fmt, "-o", work / f"r.{fmt}"])
            if status == 2:
                assert not (work / f"r.{fmt}").exists()
                return
        assert_inert_html((work / "r.html").read_text(encoding="utf-8"))
        assert_inert_markdown((work / "r.markdown").read_text(encoding="utf-8"))
        source = (work / "r.tex").read_text(encoding="utf-8")
        assert_inert_latex(source)
        compile_latex(folder, source)


CHAIN = {"system": "single-user", "environment": "K_8 + B*(z - 1)/(T*z)",        # 10^(10^8): 4.4 GB, then a traceback
         "params": {"K_0": 10, "B": "0.001", "T": "0.001", "b": "1", **{f"K_{i}": f"K_{i - 1}**10" for i in range(1, 9)}}}


@FUZZ
@example(fields=CHAIN, extra=[])
@given(fields=_scene(), extra=st.lists(st.sampled_from([["--delay-margin"], ["--range", "K"], ["--format", "json"],
                                                         ["--format", "latex"], ["--param", "K=1e999999999"],
                                                         ["--param", "T=0.001"], ["--users", "3"]]), max_size=3)
       .map(lambda groups: [a for g in groups for a in g]))
def test_fuzz_scene_files(fields, extra, capsys, bounded):
    with _Watch() as folder:
        _files_beside(folder)
        lines = _table("", {k: v for k, v in fields.items() if k != "params"}) + _table("params", fields.get("params", {}))
        path = folder / "s.toml"
        path.write_text("\n".join(lines) + "\n", encoding="utf-8")
        run_cli(capsys, ["derive", "--scene", path, *extra, "-o", folder / "out.txt"])


@FUZZ
@given(text=saved_reports())
def test_fuzz_saved_reports(text, capsys, bounded):
    from hapticproof.core.files import read_json
    from hapticproof.core.shapes import check_audit
    from hapticproof.report.export import reports_from_json
    from hapticproof.report.html import report_html
    from hapticproof.audit.registry import get_paper

    with _Watch() as folder:
        path = folder / "a.json"
        path.write_text(text, encoding="utf-8")
        run_cli(capsys, ["check", path])
        status, _ = run_cli(capsys, ["export", "hve", "--from-audit", path, "-o", folder / "e.tex"])
        if status != 0:
            return
        assert_inert_latex((folder / "e.tex").read_text(encoding="utf-8"))
        data = read_json(text, "a.json")
        check_audit(data, "a.json")
        assert_inert_html(report_html(reports_from_json(data, [get_paper("hve")])))


@FUZZ
@given(displays=st.lists(DISPLAYS, min_size=1, max_size=6))
def test_fuzz_printed_displays_in_reports(displays, bounded):
    from hapticproof.audit.runner import AuditReport, EquationResult
    from hapticproof.core.evidence import Evidence, Verdict
    from hapticproof.report import latex as tex
    from hapticproof.report.html import report_html

    results = tuple(EquationResult(str(k), "condition" if k % 2 else "claim", d, d, Verdict.TYPO, d, d,
                                   Evidence("counterexample", witness={"c": d}), 0.0)
                    for k, d in enumerate(displays))
    report = AuditReport("fuzz", displays[0], results)
    with _Watch() as folder:
        assert_inert_html(report_html([report]))
        source = tex.audit_document([report])
        assert_inert_latex(source)
        compile_latex(folder, source)


# ---------------------------------------------------------------------------------------------
# issue 30: outputs, forged reports, crafted boundaries, long runs of spaces
# ---------------------------------------------------------------------------------------------
OUTPUT_COMMANDS = [
    (["derive", "single-user", "--param", "K=2", "--param", "T=0.001", "--param", "b=1", "-o"], ".txt"),
    (["derive", "single-user", "--param", "K=2", "--param", "T=0.001", "--param", "b=1", "--format", "json", "-o"], ".json"),
    (["new-paper", "--force"], ".toml"),
    (["map", "passivity", "--x", "b=0.001,0.002", "--y", "K=3", "--param", "T=0.001", "--param", "B=0", "-o"], ".csv"),
    (["map", "passivity", "--x", "b=0.001,0.002", "--y", "K=3", "--param", "T=0.001", "--param", "B=0", "--plot"], ".png"),
]
PLANTED = ["nothing", "file", "link-out", "dangling-link", "link-in", "fifo", "directory"]


@FUZZ
@given(command=st.sampled_from(OUTPUT_COMMANDS), planted=st.sampled_from(PLANTED),
       name=st.sampled_from(["out", "errata", ".hidden", "a b", "r\u00e9sum\u00e9"]))
def test_fuzz_output_paths(command, planted, name, capsys, bounded):
    """An output named by a planted link (out of the folder, dangling or not), a FIFO or a
    directory is refused in one line and nothing is written through it; a free name or a
    regular file is written whole; no temporary file is ever left beside it."""
    argv, suffix = command
    outside = Path(tempfile.mkdtemp(prefix="hp-fuzz-outside-"))      # (outside the watched folder)
    (outside / "secret").write_text("SECRET", encoding="utf-8")
    try:
        with _Watch() as folder:
            out = folder / (name + suffix)
            if planted == "file":
                out.write_text("old", encoding="utf-8")
            elif planted == "link-out":
                out.symlink_to(outside / "secret")
            elif planted == "dangling-link":
                out.symlink_to(outside / "created")
            elif planted == "link-in":
                (folder / "inside.txt").write_text("in", encoding="utf-8")
                out.symlink_to(folder / "inside.txt")
            elif planted == "fifo":
                os.mkfifo(out)
            elif planted == "directory":
                out.mkdir()
            before = sorted(p.name for p in folder.iterdir())
            status, err = run_cli(capsys, [*argv, out])
            refused = planted in ("link-out", "dangling-link", "link-in", "fifo", "directory")
            assert (status == 2) if refused else (status == 0), (planted, err[-300:])
            after = sorted(p.name for p in folder.iterdir())
            assert after == (before if planted != "nothing" or refused else sorted(before + [out.name])), (before, after)
            if refused:
                assert out.is_symlink() or out.is_fifo() or out.is_dir()
            else:
                assert out.is_file() and not out.is_symlink() and out.stat().st_size > 0
        assert (outside / "secret").read_text(encoding="utf-8") == "SECRET" and not (outside / "created").exists()
    finally:
        shutil.rmtree(outside, ignore_errors=True)


_GENUINE: dict = {}


def _genuine_walls() -> list[dict]:
    """The genuine reports of a wall that is not passive and of one that is (computed once)."""
    if not _GENUINE:
        import contextlib
        import io

        from forgeries import NOT_PASSIVE, PASSIVE

        for key, argv in (("bad", NOT_PASSIVE), ("good", PASSIVE)):
            buffer = io.StringIO()
            with contextlib.redirect_stdout(buffer), contextlib.redirect_stderr(io.StringIO()):
                assert main(argv) == 0
            _GENUINE[key] = json.loads(buffer.getvalue())
    return [_GENUINE["bad"], _GENUINE["good"]]


def _edit(report: dict, how: str, draw) -> None:
    """One hostile edit of a derive report of the wall that is not passive."""
    from forgeries import SIGN, _certificates, _claim_proved

    sign = next(c for c in report["conditions"] if c["name"] == SIGN)
    certs = list(_certificates(report))
    if not certs and how in ("other-object", "kind", "value"):
        return
    if how == "claim-proved":
        _claim_proved(report, keep_definition=draw(st.booleans()))
    elif how == "shrink":
        cert = ((sign.get("evidence") or {}).get("facts") or {}).get("certificate")
        if not isinstance(cert, dict):
            return
        lo = draw(st.sampled_from(["-1/2", "0", "1/3", "-1"]))
        cert.update(interval=[lo, draw(st.sampled_from(["1", "1/2", "2"]))], points=[lo, "1"], holds=True, roots=[])
    elif how == "other-object":
        cert = draw(st.sampled_from(certs))
        good = list(_certificates(_genuine_walls()[1]))
        same = [c for c in good if c["certificate"] == cert["certificate"]]
        if same:
            cert.clear()
            cert.update(json.loads(json.dumps(draw(st.sampled_from(same)))))
    elif how == "kind":
        obj = draw(st.sampled_from(certs + [report.get("definition") or {}]))
        key = "judge" if "judge" in obj else "certificate"
        obj[key] = draw(st.sampled_from(["sgin", "positive-reel", "Sign", "sign ", "psd", "roots", "x-y"]))
    elif how == "strip":
        for cond in report["conditions"]:
            if draw(st.booleans()):
                cond["evidence"] = {"method": "root-isolation"}
    elif how == "witness":
        witness = report.get("witness") or {}
        witness[draw(st.sampled_from(["omega_T", "c", "z"]))] = draw(st.sampled_from(["pi/3", "0", ["0", "1"], "1/2"]))
        report["witness"] = witness
    elif how == "g-inverse":
        report["G_inverse"] = draw(st.sampled_from([_genuine_walls()[1]["G_inverse"], "1", "z", "(((", 5, None]))
    elif how == "value":
        cert = draw(st.sampled_from(certs))
        key = draw(st.sampled_from(sorted(cert)))
        cert[key] = draw(JSON_VALUES)


@FUZZ
@given(data=st.data())
def test_fuzz_forged_reports(data, capsys, bounded):
    """The report of a wall that is not passive, edited one to four times the ways a hostile
    author would: whatever it claims, ``check`` never accepts it (and never crashes)."""
    report = json.loads(json.dumps(_genuine_walls()[0]))
    edits = data.draw(st.lists(st.sampled_from(["claim-proved", "shrink", "other-object", "kind", "strip", "witness",
                                                "g-inverse", "value"]), min_size=1, max_size=4))
    for how in edits:
        _edit(report, how, data.draw)
    event("forged: " + "+".join(sorted(set(edits))))
    with _Watch() as folder:
        path = folder / "r.json"
        path.write_text(json.dumps(report), encoding="utf-8")
        status, err = run_cli(capsys, ["check", path])
        if report == _genuine_walls()[0]:
            return                                   # (the edits undid each other)
        if status == 0:
            # only a report that still shows the genuine disproof of this wall may be accepted
            assert report.get("verdict") == "disproved" and report.get("G_inverse") == _genuine_walls()[0]["G_inverse"], err


@FUZZ
@given(field=st.sampled_from(["inputs", "outputs", "controller", "plant"]),
       value=st.one_of(st.integers(-(2**70), 2**70), st.sampled_from([-1, 0, 65, 100000000, 1e8, 2.5, "2", True, None,
                                                                        [2, 3], [-1, -1], [10**6, 10**6]])))
def test_fuzz_crafted_boundary_reports(field, value, capsys, bounded):
    """A saved boundary whose loop sizes are edited (``-1`` aborted the process inside FLINT,
    ``1e8`` asked for 9 GB): one line or a refusal, within the bounds."""
    with _Watch() as folder:
        status, _ = run_cli(capsys, ["boundary", "single-user", "--param", "m=0.015", "--param", "b=0.02", "--param",
                                     "T=0.001", "--vary", "K", "--json", folder / "b.json"])
        assert status == 0
        report = json.loads((folder / "b.json").read_text(encoding="utf-8"))
        shape = report["judge"]["sides"][data_side(value)]["loop"]["shape"]
        unchanged = shape[field] == value and type(shape[field]) is type(value)
        shape[field] = value
        (folder / "b.json").write_text(json.dumps(report), encoding="utf-8")
        status, _ = run_cli(capsys, ["check", folder / "b.json"])
        assert status in (1, 2) or unchanged


def data_side(value) -> int:
    return hash(str(value)) % 2


@FUZZ
@given(kind=st.sampled_from(["md", "tex", "txt"]), runs=st.lists(st.integers(0, 60_000), min_size=1, max_size=3),
       where=st.sampled_from(["display", "number", "where", "heading", "label", "prose"]))
@example(kind="md", runs=[60_000, 60_000, 60_000], where="display")     # back-tracking took minutes on these
@example(kind="tex", runs=[60_000, 60_000, 60_000], where="label")
@example(kind="txt", runs=[60_000, 60_000, 60_000], where="where")
def test_fuzz_sources_with_long_runs_of_spaces(kind, runs, where, capsys, bounded):
    """Sources with runs of spaces where the reader's patterns look (a display's trailing number,
    a 'where $a$, $b$' clause, a heading, a label): linear, within the time bound."""
    gap = [" " * n for n in runs] + [" "] * 3
    pieces = {
        "display": f"$$b >{gap[0]}1{gap[1]}(3){gap[2]}x$$",
        "number": f"$$b > 1 \\quad{gap[0]}({gap[1]}3{gap[2]})$$",
        "where": f"where $a$,{gap[0]}$b${gap[1]}and{gap[2]}$c$ hold",
        "heading": f"## 2.{gap[0]}Wall{gap[1]}#",
        "label": f"\\begin{{equation}} b > 1 \\label{{{gap[0]}}} \\tag{{{gap[1]}}} \\end{{equation}}",
        "prose": f"Text{gap[0]}with{gap[1]}spaces{gap[2]}.",
    }
    body = pieces[where] + "\n\n$$b > \\frac{KT}{2} + B$$\n"
    if kind == "tex":
        body = body.replace("$$", "\n\\[\n", 1).replace("$$", "\n\\]\n", 1)
    with _Watch() as folder:
        source = folder / f"s.{kind}"
        source.write_text(body, encoding="utf-8")
        run_cli(capsys, ["new-paper", folder / "p.toml", "--from", source])


def test_the_checks_can_fail():
    """The controls: each check refuses what it exists to refuse."""
    with pytest.raises(AssertionError):
        assert_inert_html('<html><head><meta http-equiv="Content-Security-Policy" content="script-src \'none\'">'
                          "</head><body><p>a</p><p>b</p><div>c</div><math><mi>x</mi></math>"
                          "<svg onload=alert(1)></svg></body></html>")
    with pytest.raises(AssertionError):
        assert_inert_latex(r"\begin{document} b > ^^5cinput{/etc/hostname}")
    with pytest.raises(AssertionError):
        assert_inert_latex(r"\begin{document} \csname input\endcsname")
    with pytest.raises(AssertionError):
        assert_inert_markdown("| 1 | <img src=x onerror=alert(1)> | `ok` |")
    with pytest.raises(AssertionError), _Watch():
        Path("/etc/hostname").read_text(encoding="utf-8") if os.path.exists("/etc/hostname") else open("/etc/passwd")
