"""Issue 29 (first item): one naming context for every view. A scene in the user's own names
(period ``h``, dampings ``c_d``, ``c_m``, ``c_s``...) prints no toolkit default name (``T``, ``b``,
``b_m``, ``b_s``, ``omega T``) in any format, the toolkit's own quantities get names no user name
can be confused with (``c = cos(omega T)`` is ``gamma`` beside ``c_d``; the teleoperator's
error-coordinate damping is not ``h`` when ``h`` is the period), and every answer is the answer
of the same scene in the papers' names, renamed (the same verdicts, the same numbers).

The outputs are parsed: text and JSON word by word, LaTeX token by token in its mathematics
(``b`` in ``\\textbf`` or in "symbolic" is no ``b``).
"""

from __future__ import annotations

import json
import re
import sys
from pathlib import Path

import pytest
import sympy as sp

from hapticproof.core.naming import DEFAULT, Naming, clashes, marked, marker
from hapticproof.core.symbols import c as C_SYM
from hapticproof.core.symbols import x as X_SYM

sys.path.insert(0, str(Path(__file__).resolve().parent))

from clirun import run  # noqa: E402

ROOT = Path(__file__).resolve().parents[1]

# ---------------------------------------------------------------------------------------------
# reading the outputs
# ---------------------------------------------------------------------------------------------

_WORD = re.compile(r"(?<![A-Za-z0-9_\\])[A-Za-z_][A-Za-z0-9_]*")


def words(text: str) -> list[str]:
    """The names of a plain text (``c_d`` is one word, ``b`` in ``symbolic`` none); ``2 x 2`` is no x."""
    return _WORD.findall(re.sub(r"\d+ x \d+", " ", text))


def _argument(text: str, start: int) -> tuple[str, int]:
    """The balanced ``{...}`` argument opening at ``text[start]``."""
    depth = 0
    for i in range(start, len(text)):
        if text[i] == "{":
            depth += 1
        elif text[i] == "}":
            depth -= 1
            if depth == 0:
                return text[start + 1:i], i + 1
    raise AssertionError("unbalanced braces")


def latex_parts(tex: str) -> tuple[list[str], list[str]]:
    """(math, text) of a LaTeX document or fragment: the displays' mathematics (``\\hpfit{...}``,
    ``equation*``, ``$...$``) and everything else as text."""
    body = tex.split(r"\begin{document}")[-1]
    math: list[str] = []
    rest = []
    i = 0
    while i < len(body):
        j = body.find(r"\hpfit{", i)
        if j < 0:
            rest.append(body[i:])
            break
        rest.append(body[i:j])
        arg, i = _argument(body, j + len(r"\hpfit"))
        math.append(arg)
    body = "".join(rest)
    math += re.findall(r"\\begin\{equation\*\}(.*?)\\end\{equation\*\}", body, flags=re.S)
    body = re.sub(r"\\begin\{equation\*\}.*?\\end\{equation\*\}", " ", body, flags=re.S)
    math += re.findall(r"(?<!\\)\$(.+?)(?<!\\)\$", body)
    body = re.sub(r"(?<!\\)\$(.+?)(?<!\\)\$", " ", body)
    text = [re.sub(r"\\[A-Za-z]+\*?", " ", line.replace("\\_", "_").replace("\\textasciicircum{}", "^"))
            for line in body.splitlines() if not line.lstrip().startswith("%")]
    return math, text


_TEXT_COMMAND = re.compile(r"\\(?:text|operatorname|mathrm|textbf)\{")


def math_tokens(math: str) -> list[str]:
    """The symbols of LaTeX mathematics: control words and letters with their subscripts; the
    words of ``\\text{...}`` are text, not symbols."""
    out, i = [], 0
    plain = []
    while True:
        m = _TEXT_COMMAND.search(math, i)
        if m is None:
            plain.append(math[i:])
            break
        plain.append(math[i:m.start()])
        _, i = _argument(math, m.end() - 1)
    for piece in plain:
        piece = re.sub(r"\\(?:begin|end)\{[^{}]*\}", " ", piece)
        out += re.findall(r"\\[A-Za-z]+|[A-Za-z](?:_\{[^{}]*\}|_[A-Za-z0-9])?", piece)
    return out


def json_texts(data, path: str = ""):
    """(path, text) of every string of a JSON report that a reader reads: the certificates, the
    judge's objects and the verbatim ``printed`` display are data, not text; a witness's keys are read."""
    if isinstance(data, dict):
        for key, value in data.items():
            if key in ("certificate", "judge", "checker", "definition", "printed_form", "printed", "transfer",
                       "certificates", "stages_seconds", "notation", "claim", "variable", "slave"):
                continue
            if key == "witness" and isinstance(value, dict):       # its keys are read too (gamma, omega*h)
                yield f"{path}.witness", " ".join(value)
            yield from json_texts(value, f"{path}.{key}")
    elif isinstance(data, list):
        for k, value in enumerate(data):
            yield from json_texts(value, f"{path}[{k}]")
    elif isinstance(data, str):
        yield path, data


def check_text(text: str, forbidden: set[str], where: str) -> None:
    found = set(words(text)) & forbidden
    assert not found, f"{where}: toolkit default names {sorted(found)} in {text[:300]!r}"
    assert "\x1f" not in text, f"{where}: an unrendered name marker"


def check_latex(tex: str, forbidden_math: set[str], forbidden_text: set[str], where: str) -> list[str]:
    math, text = latex_parts(tex)
    tokens = [t for m in math for t in math_tokens(m)]
    found = set(tokens) & forbidden_math
    assert not found, f"{where}: toolkit default symbols {sorted(found)} in the mathematics"
    pairs = {(a, b) for m in math for a, b in zip(math_tokens(m), math_tokens(m)[1:])}
    assert (r"\omega", "T") not in pairs, f"{where}: \\omega T in the mathematics"
    for line in text:
        check_text(line, forbidden_text, where)
    return tokens


# ---------------------------------------------------------------------------------------------
# the same up to the renaming
# ---------------------------------------------------------------------------------------------

_NUMBER = re.compile(r"(?<![A-Za-z_0-9])-?\d+(?:\.\d+)?(?:/\d+)?")


def _mapped(text: str, back: dict[str, str]) -> str:
    return _WORD.sub(lambda m: back.get(m.group(0), m.group(0)), text)


def _claims_back(value, back: dict[str, str]):
    """A certificate (or a value holding some) with each ``claim`` in the papers' names."""
    if isinstance(value, dict):
        out = {k: _claims_back(v, back) for k, v in value.items()}
        if isinstance(value.get("certificate"), str) and isinstance(value.get("claim"), str):
            out["claim"] = _mapped(value["claim"], back)
        return out
    if isinstance(value, list):
        return [_claims_back(v, back) for v in value]
    return value


def _witness_key(key: str, back: dict[str, str]) -> str:
    """A displayed witness's key in the papers' names: ``gamma`` -> ``c``, ``omega*h`` -> ``omega_T``."""
    mapped = _mapped(key, back)
    return "omega_T" if mapped == "omega*T" else mapped


def _same_expression(a: str, b: str) -> bool:
    try:
        ea, eb = sp.sympify(a, locals={n: sp.Symbol(n) for n in words(a) + words(b)}), \
            sp.sympify(b, locals={n: sp.Symbol(n) for n in words(a) + words(b)})
    except (sp.SympifyError, SyntaxError, TypeError, ValueError, AttributeError):
        return False
    if isinstance(ea, sp.Expr) and isinstance(eb, sp.Expr):
        return sp.simplify(ea - eb) == 0
    if isinstance(ea, sp.core.relational.Relational) and type(ea) is type(eb):
        return sp.simplify((ea.lhs - ea.rhs) - (eb.lhs - eb.rhs)) == 0
    return ea == eb


def same_up_to_renaming(mine, papers, back: dict[str, str], path: str = "") -> None:
    """``mine`` (a report of a renamed scene) is ``papers`` (the same scene in the papers' names)
    once its names are mapped back (``back``): the same structure, the same numbers, each text
    the same words (expressions equal as expressions: their terms may print in another order)."""
    if isinstance(papers, dict):
        witness = path.endswith(".witness") and ".definition" not in path    # a displayed witness: gamma, omega*h
        mine = {(_witness_key(k, back) if witness else _mapped(k, back) if isinstance(k, str) else k): v
                for k, v in mine.items() if k != "notation"}
        papers = {k: v for k, v in papers.items() if k not in ("notation", "seconds", "stages_seconds")}
        mine.pop("seconds", None)
        assert set(mine) == set(papers), f"{path}: keys {sorted(set(mine) ^ set(papers))}"
        for key in papers:
            if key in ("printed", "judge", "printed_form", "definition"):
                continue
            if key in ("certificate", "claim", "variable", "slave"):
                # data of the checker: the same, unrenamed -- but a certificate's claim, written for
                # a reader, in the scene's names
                shown = _mapped(mine[key], back) if key == "claim" and isinstance(mine[key], str) else _claims_back(mine[key], back)
                assert shown == papers[key], f"{path}.{key}"
                continue
            same_up_to_renaming(mine[key], papers[key], back, f"{path}.{key}")
        return
    if isinstance(papers, list):
        assert isinstance(mine, list) and len(mine) == len(papers), path
        for k, (m, p) in enumerate(zip(mine, papers)):
            same_up_to_renaming(m, p, back, f"{path}[{k}]")
        return
    if not isinstance(papers, str):
        assert mine == papers, f"{path}: {mine!r} != {papers!r}"
        return
    mapped = _mapped(mine, back).replace("j*w", "jw")
    if mapped == papers:
        return
    assert sorted(_NUMBER.findall(mapped)) == sorted(_NUMBER.findall(papers)), f"{path}: numbers differ: {mapped!r} vs {papers!r}"
    if _same_expression(mapped, papers):
        return
    assert sorted(words(mapped)) == sorted(words(papers)), f"{path}: {mapped!r} vs {papers!r}"


# ---------------------------------------------------------------------------------------------
# the scenes, in the papers' names and in the user's
# ---------------------------------------------------------------------------------------------

def _argv(system: str, options: list[str], params: dict[str, str], roles: dict[str, str]) -> list[str]:
    """The command line of a scene given in the papers' names, renamed by ``roles`` (role -> (default, own name))."""
    rename = {default: own for default, own in roles.values()}
    out = ["derive", system, *options]
    for field, (_, own) in roles.items():
        out += ["--role", f"{field}={own}"]
    for name, value in params.items():
        out += ["--param", f"{rename.get(name, name)}={value}"]
    return out


def _papers_argv(system: str, options: list[str], params: dict[str, str]) -> list[str]:
    out = ["derive", system, *options]
    for name, value in params.items():
        out += ["--param", f"{name}={value}"]
    return out


SINGLE = {"period": ("T", "h"), "device_damping": ("b", "c_d")}
MULTI = {"period": ("T", "h"), "device_damping": ("b", "c")}
TELE = {"period": ("T", "h"), "master_damping": ("b_m", "c_m"), "slave_damping": ("b_s", "c_s")}
WALL = {"K": "2", "B": "0.001", "T": "0.001", "b": "0.02"}

#: (id, system, options, parameters in the papers' names, roles)
SCENES = [
    ("wall-forward-numeric", "single-user", ["--delay-margin", "--range", "K"], WALL, SINGLE),
    ("wall-forward-symbolic", "single-user", [], {}, SINGLE),
    ("wall-backward-symbolic", "single-user", ["--approximation", "backward"], {}, SINGLE),
    ("wall-tustin-delay-3", "single-user", ["--approximation", "tustin", "--delay", "3"], {**WALL, "b": "0.0015"}, SINGLE),
    ("wall-symbolic-delay", "single-user", ["--delay", "n"], {}, SINGLE),
    ("wall-active", "single-user", ["--active"], {}, SINGLE),
    ("wall-zoh-design", "single-user", ["--controller", "K + B*s", "--discretize", "tustin"], WALL, SINGLE),
    ("users-symbolic", "multi-user", ["--users", "2"], {}, MULTI),
    ("users-delayed-numeric", "multi-user", ["--users", "2", "--delay", "1,3"],
     {"b": "0.003", "K_0": "10", "K": "5", "B_0": "0.001", "B": "0.0001", "T": "0.001"}, MULTI),
    ("users-uniform-modes", "multi-user", ["--users", "5", "--uniform", "--delay-margin"],
     {"b": "0.02", "K_0": "10", "K": "5", "B_0": "0", "B": "0", "T": "0.001"}, MULTI),
    ("teleoperator-symbolic", "teleoperator", [], {}, TELE),
    ("teleoperator-numeric", "teleoperator", ["--range", "b_m"],
     {"K": "20", "B": "0.01", "T": "0.001", "b_s": "0.03"}, TELE),
    ("teleoperator-filtered", "teleoperator", ["--controller", "filtered-pd"],
     {"K": "20", "B": "0.01", "T": "0.001", "b_m": "0.05", "b_s": "0.03", "a": "1/2"}, TELE),
]

FORMATS = [["--format", "text"], ["--format", "json"], ["--format", "latex"], ["--format", "latex", "--fragment"]]


def _forbidden(roles: dict[str, tuple[str, str]], system: str) -> tuple[set[str], set[str], set[str]]:
    """(text words, LaTeX symbols, LaTeX text words) a renamed scene must not print."""
    defaults = {d for d, _ in roles.values()}
    text = defaults | {"wT", "omega_T", "c"}            # c: the toolkit's cos is renamed beside c_d / c_1
    if system == "multi-user":
        text |= {"b_1", "b_2", "b_3", "b_4", "b_5"}
    if system == "teleoperator":
        text |= {"b"}
    latex = {d if len(d) == 1 else f"{d[0]}_{{{d[2:]}}}" for d in defaults} | {"c"}
    return text, latex, text


def _with_range(options: list[str], roles) -> list[str]:
    rename = {default: own for default, own in roles.values()}
    return [rename.get(o, o) if options[k - 1] == "--range" else o for k, o in enumerate(options)]


@pytest.mark.parametrize("fmt", FORMATS, ids=lambda f: "-".join(a.lstrip("-") for a in f if a != "--format"))
@pytest.mark.parametrize("scene", SCENES, ids=[s[0] for s in SCENES])
def test_renamed_scenes_print_only_their_own_names(capsys, scene, fmt):
    name, system, options, params, roles = scene
    code, out, err = run(capsys, *_argv(system, _with_range(options, roles), params, roles), *fmt)
    assert code == 0, err
    text_words, latex_symbols, latex_words = _forbidden(roles, system)
    if fmt[1] == "text":
        check_text(out, text_words, name)
        if system == "teleoperator":
            # h is the period: the error-coordinate damping and the conditions' names speak of eta
            assert "error-coordinate damping eta = c_m c_s/(c_m + alpha^2 c_s)" in out
            assert "(P5) eta >= L(gamma) for all gamma in [-1, 1]" in out and "(D) c_m >= 0 and c_s >= 0" in out
    elif fmt[1] == "json":
        data = json.loads(out)
        for path, text in json_texts(data):
            check_text(text, text_words, f"{name}{path}")
        assert data["notation"]["period"] == "h" and data["notation"]["cos"] == "gamma"
    else:
        tokens = check_latex(out, latex_symbols, latex_words, name)
        assert not params or "h" in tokens or "--delay-margin" not in options      # t_d <= N h
        if name in ("wall-forward-symbolic", "wall-forward-numeric", "wall-active", "users-symbolic", "teleoperator-symbolic"):
            assert r"\cos(\omega h)" in out


@pytest.mark.parametrize("scene", SCENES, ids=[s[0] for s in SCENES])
def test_renamed_scenes_give_the_papers_answers(capsys, scene):
    """The JSON of a renamed scene is the JSON of the same scene in the papers' names, names mapped
    back: the same decisions and verdicts, the same numbers, the same expressions."""
    name, system, options, params, roles = scene
    code, mine, err = run(capsys, *_argv(system, _with_range(options, roles), params, roles), "--format", "json")
    assert code == 0, err
    code, papers, err = run(capsys, *_papers_argv(system, options, params), "--format", "json")
    assert code == 0, err
    back = {own: default for default, own in roles.values()}
    back.update({"gamma": "c", "eta": "h"})
    if system == "multi-user":
        back.update({f"c_{i}": f"b_{i}" for i in range(1, 6)})
    mine, papers = json.loads(mine), json.loads(papers)
    for key in ("delay_margin",):
        for data in (mine, papers):
            if key in data:
                data[key].pop("seconds", None)
    same_up_to_renaming(mine, papers, back, name)
    assert mine.get("verdict") == papers.get("verdict")


def test_the_issues_single_user_reproduction(capsys):
    """`derive single-user --role period=h --role device_damping=c_d`: Re G^-1 in gamma = cos wh,
    its LaTeX in cos(omega h), and t_d <= N h."""
    base = ["derive", "single-user", "--role", "period=h", "--role", "device_damping=c_d"]
    _, text, _ = run(capsys, *base)
    assert "Re G^-1 (gamma = cos wh) = B*gamma - K*h/2 + c_d" in text
    assert "c_d >= B + K*h/2 (slope >= 0: minimum at gamma = -1)" in text
    _, tex, _ = run(capsys, *base, "--format", "latex")
    assert r"\Re\, G^{-1}(e^{j\omega h})" in tex and r"B \cos(\omega h)" in tex
    _, tex, _ = run(capsys, *base, "--param", "K=2", "--param", "B=0.001", "--param", "h=0.001", "--param", "c_d=0.02",
                    "--delay-margin", "--format", "latex", "--fragment")
    assert r"t_d \le N_{\max} h = \frac{1}{100}" in tex
    _, out, _ = run(capsys, *base, "--param", "K=2", "--param", "B=0.001", "--param", "h=0.001", "--param", "c_d=0.02",
                    "--delay-margin", "--format", "json")
    proof = json.loads(out)["delay_margin"]["proof"]
    assert "a = c_d" in proof and "a = b - z_a" not in proof     # (no z_a: the operator is passive)


def test_a_parameter_named_like_the_toolkits_c_is_a_parameter(capsys):
    """A real parameter c (a damping) is not c = cos(omega T): the exact forms keep them apart
    and the views name the toolkit's c otherwise (it used to crash)."""
    code, out, err = run(capsys, "derive", "single-user", "--environment", "K + c*(z-1)/(T*z)", "--param", "c=real")
    assert code == 0, err
    assert "Re G^-1 (gamma = cos wT) = -K*T/2 + b + c*gamma" in out
    assert "b >= K*T/2 + Abs(c)" in out
    code, out, err = run(capsys, "derive", "single-user", "--environment", "K + c*(z-1)/(T*z)", "--param", "c=real",
                         "--param", "K=2", "--param", "T=0.001", "--param", "b=0.02", "--param", "c=0.001", "--format", "json")
    assert code == 0 and json.loads(out)["verdict"] == "proved"


def test_networks_name_the_frequency_apart_from_their_parameters(tmp_path, capsys):
    """A network whose parameters are called x and omega: x = w^2 and w are renamed in its report."""
    matrix = tmp_path / "z.txt"
    matrix.write_text("x/(s+3), -1/(s+omega)\n-1/(s+omega), 1/(s+3)\n")
    papers = tmp_path / "p.txt"
    papers.write_text("9/(s+3), -1/(s+1)\n-1/(s+1), 1/(s+3)\n")
    for fmt in (["--format", "text"], ["--format", "json"], ["--format", "latex"], ["--format", "latex", "--fragment"]):
        code, out, err = run(capsys, "derive", "network", "--matrix", str(matrix), "--no-search", "--param", "x=9",
                             "--param", "omega=1", *fmt)
        assert code == 0, err
        if fmt[1] == "json":
            data = json.loads(out)
            for path, text in json_texts(data):
                check_text(text, {"x", "w", "jw", "omega"}, path)
            _, plain, _ = run(capsys, "derive", "network", "--matrix", str(papers), "--no-search", *fmt)
            same_up_to_renaming(data, json.loads(plain), {"xi": "x", "nu": "w"}, "network")
        elif fmt[1] == "text":
            check_text(out, {"x", "w", "jw", "omega"}, "network")
            assert "for all xi in [0, oo]" in out
        else:
            check_latex(out, {"x"}, {"x", "w"}, "network")


# ---------------------------------------------------------------------------------------------
# a user's paper in the user's names
# ---------------------------------------------------------------------------------------------

def _renamed_paper(tmp_path: Path) -> Path:
    """The single-user paper file of the examples in the user's names: period h, damping c_d."""
    text = (ROOT / "examples" / "hve-single-user.toml").read_text()
    out = []
    for line in text.splitlines():
        if line.startswith("printed") or line.startswith("S = "):
            key, _, value = line.partition("=")
            line = key + "=" + value.replace("T", "h").replace("b", "c_{d}")
        elif line.startswith('b = "positive"'):
            line = 'c_d = "positive"'
        elif line.startswith('T = "positive"'):
            line = 'h = "positive"'
        out.append(line)
    text = "\n".join(out) + "\n"
    text = re.sub(r"(\[scenes\.([\w-]+)\]\n(?:[^\[\n].*\n)*)",
                  lambda m: m.group(1) + f'[scenes.{m.group(2)}.roles]\nperiod = "h"\ndevice_damping = "c_d"\n\n', text)
    path = tmp_path / "mine.toml"
    path.write_text(text.replace('id = "hve-file"', 'id = "hve-mine"'))
    return path


@pytest.fixture(scope="module")
def renamed_audits(tmp_path_factory):
    """The audit of the renamed paper in every format, and the audit of the paper as printed (JSON)."""
    from hapticproof.cli import main

    folder = tmp_path_factory.mktemp("naming")
    paper = _renamed_paper(folder)
    out = {}
    for fmt in ("table", "markdown", "json", "tex", "html"):
        target = folder / f"mine.{fmt}"
        assert main(["audit", "--paper", str(paper), "--format", fmt, "--jobs", "1", "--wide", "-o", str(target)]) == 0
        out[fmt] = target.read_text()
    target = folder / "papers.json"
    assert main(["audit", "--paper", str(ROOT / "examples" / "hve-single-user.toml"), "--format", "json", "--jobs", "1",
                 "-o", str(target)]) == 0
    out["papers"] = target.read_text()
    return out


AUDIT_WORDS = {"T", "b", "c", "wT", "omega_T"}


@pytest.mark.parametrize("fmt", ["table", "markdown", "json", "tex", "html"])
def test_a_users_paper_is_audited_in_its_names(renamed_audits, fmt):
    text = renamed_audits[fmt]
    if fmt == "json":
        data = json.loads(text)
        assert data["notation"] == {"gamma": "cos wh"}
        for path, value in json_texts(data):
            if path.endswith(".derived") or path.endswith(".corrected"):
                check_latex(f"${value}$", {"T", "b", "c"}, set(), path)
            else:
                check_text(value, AUDIT_WORDS, path)
        shown = {e["id"]: e for e in data["equations"]}
        assert "c_d >= -B*gamma + K*h/2" in shown["17"]["detail"]
        assert shown["17"]["derived"] == r"B \gamma - \frac{K h}{2} + c_{d} \geq 0"
        facts = shown["25"]["evidence"]["facts"]
        assert facts["a"] == "a = c_d - z_a" and "gamma -> 1" in facts["exact_method"]
    elif fmt == "tex":
        check_latex(text, {"T", "b", "c"} | {r"\omega T"}, {"T", "b", "wT"}, "tex")
        assert r"\textbf{notation:} gamma = cos wh" in text
    elif fmt == "html":
        body = re.sub(r"<(style|script)[^>]*>.*?</\1>", " ", text, flags=re.S)
        body = re.sub(r"<annotation[^>]*>.*?</annotation>", " ", body, flags=re.S)      # the printed LaTeX, verbatim
        for piece in re.findall(r">([^<>]+)<", body):
            if "printed" in piece:
                continue
            check_text(piece.replace("&amp;", "&"), {"wT", "omega_T"}, "html")
        assert "notation: gamma = cos wh" in text
    else:
        if fmt == "markdown":               # Markdown escapes its punctuation (no emphasis, no HTML)
            text = re.sub(r"\\([\\`*_{}\[\]()#+\-.!|<>~])", r"\1", text).replace("&gt;", ">").replace("&lt;", "<").replace("&amp;", "&")
        rows = [line for line in text.splitlines() if not line.startswith("## ")]
        check_text("\n".join(rows), AUDIT_WORDS - {"c"} | set(), fmt)
        assert "gamma = cos wh" in text and "c_d >= -B*gamma + K*h/2" in text


def test_a_users_paper_gets_the_verdicts_and_numbers_of_the_papers_names(renamed_audits):
    mine, papers = json.loads(renamed_audits["json"]), json.loads(renamed_audits["papers"])
    assert [(e["id"], e["verdict"]) for e in mine["equations"]] == [(e["id"], e["verdict"]) for e in papers["equations"]]
    back = {"h": "T", "c_d": "b", "gamma": "c"}
    for m, p in zip(mine["equations"], papers["equations"]):
        same_up_to_renaming(m["detail"], p["detail"], back, m["id"])
        if p["derived"] is not None:
            tokens = [back.get(t.replace("{", "").replace("}", ""), t) for t in math_tokens(m["derived"])]
            mapped = [{"c_d": "b", r"\gamma": "c"}.get(t, t) for t in tokens]
            assert sorted(mapped) == sorted(math_tokens(p["derived"])), m["id"]


# ---------------------------------------------------------------------------------------------
# the naming itself
# ---------------------------------------------------------------------------------------------

def test_the_helpers_keep_their_default_names_unless_a_user_name_clashes():
    assert DEFAULT.is_default and Naming.choose({"K", "B", "T", "b", "z_a"}).is_default
    names = Naming.choose({"c_d", "h", "K"}, roles=(("period", "T", "h"), ("device_damping", "b", "c_d")))
    assert (names.helper("cos"), names.helper("coupling"), names.helper("x")) == ("gamma", "eta", "x")
    assert Naming.choose({"c1"}).helper("cos") == "gamma"                # c1 is printed c_1
    assert Naming.choose({"gamma_1", "c"}).helper("cos") == "gamma"      # gamma and gamma_1, as omega and omega_s
    assert Naming.choose({"c", "gamma", "chi", "varsigma"}).helper("cos") == "gamma_2"
    assert Naming.choose({"w"}).helper("omega") == "nu" and Naming.choose({"omega_s"}).helper("omega") == "omega"
    chosen = dict(Naming.choose({"c", "h", "a", "x", "L", "R", "N", "M", "theta", "lambda"}).helpers).values()
    assert len(set(chosen)) == len(list(chosen))                        # no two helpers share a name
    assert clashes("c", "c12") and not clashes("c", "cd") and not clashes("s_theta", "s_1")


def test_a_papers_own_frequency_is_no_clash():
    omega = sp.Symbol("omega", real=True)
    assert Naming.of_symbols([omega, sp.Symbol("T", positive=True)]).is_default
    assert Naming.of_symbols([sp.Symbol("z"), sp.Symbol("s")]).is_default


def test_words_rename_only_the_toolkits_words_in_one_pass():
    names = Naming.choose({"c_m", "c_s", "h"}, roles=(("period", "T", "h"), ("master_damping", "b_m", "c_m"),
                                                        ("slave_damping", "b_s", "c_s")))
    assert names.words("(P5) h >= L(c) for all c in [-1, 1]; H = h/T + C/(z - 1)") == \
        "(P5) eta >= L(gamma) for all gamma in [-1, 1]; H = eta/h + C/(z - 1)"
    assert names.words("(D) b_m >= 0 and b_s >= 0, a zero") == "(D) c_m >= 0 and c_s >= 0, a zero"


def test_expressions_print_under_the_chosen_names_and_stay_the_same_expressions():
    names = Naming.choose({"c_d"})
    K = sp.Symbol("K", positive=True)
    expr = 3 * C_SYM**2 - K * C_SYM + X_SYM
    assert names.text(expr) == "-K*gamma + 3*gamma**2 + x"
    gamma, c = sp.Symbol("gamma"), sp.Symbol("c")
    assert sp.sympify(names.text(expr), locals={"gamma": gamma}).subs(gamma, c) == sp.sympify(sp.sstr(expr), locals={"c": c})
    assert names.latex(expr, cos=True) == r"- K \cos(\omega T) + 3 \cos(\omega T)^{2} + x"
    assert names.latex(expr) == r"- K \gamma + 3 \gamma^{2} + x"
    assert DEFAULT.text(expr) == sp.sstr(expr) and DEFAULT.latex(expr, cos=True) == \
        r"- K \cos(\omega T) + 3 c^{2} + x".replace("3 c^{2}", r"3 \cos(\omega T)^{2}")


def test_marked_texts_are_written_in_the_papers_names():
    text = f"minimum at {marker('cos')} = -1 of {marked(sp.Symbol('B') * C_SYM)}"
    assert DEFAULT.unmark(text) == "minimum at c = -1 of B*c"
    assert Naming.choose({"c_d"}).unmark(text) == "minimum at gamma = -1 of B*gamma"


def test_notebook_views_speak_the_scenes_names():
    from hapticproof.report.latex import scene_latex
    from hapticproof.report.summary import summarize_single_user
    from hapticproof.systems.scene import Scene

    model = Scene("single-user", roles={"period": "h", "device_damping": "c_d"}, delay=2,
                  params={"h": "0.001", "c_d": "0.02", "K": 2, "B": "0.001"}).build()
    shown = scene_latex(model)
    assert "t_d = 2 h" in shown and "c_{d} = " in shown and " b " not in f" {shown} " and "T" not in math_tokens(shown)
    view = summarize_single_user(model)._repr_latex_()
    assert r"e^{j\omega h}" in view and r"\cos(\omega h)" in view
    assert not {"T", "b", "c"} & set(math_tokens(view))
    tele = Scene("teleoperator", roles={"master_damping": "c_m", "slave_damping": "c_s", "period": "h"},
                 params={"c_m": "0.5", "c_s": "0.3", "K": 20, "B": "0.01", "h": "0.001"}).build()
    assert not {"b_{m}", "b_{s}", "b_m", "b_s", "T"} & set(math_tokens(scene_latex(tele)))


def test_check_reads_a_renamed_report_in_its_notation(tmp_path, capsys):
    """`check` re-verifies a renamed scene's report, and reads its Re G^-1 in the notation's name for
    c: a display changed after the fact is refused as before."""
    report = tmp_path / "mine.json"
    code, _, err = run(capsys, "derive", "single-user", "--role", "period=h", "--role", "device_damping=c_d", "--param",
                       "K=2", "--param", "B=0.001", "--param", "h=0.001", "--param", "c_d=0.0015", "--delay", "3",
                       "--format", "json", "-o", str(report))
    assert code == 0, err
    code, out, _ = run(capsys, "check", str(report))
    assert code == 0 and "0 display(s) refused" in out and "5 fully re-verified" in out
    data = json.loads(report.read_text())
    assert data["notation"]["cos"] == "gamma" and "gamma" in data["hermitian_part"]
    data["hermitian_part"] = data["hermitian_part"].replace("7/2000", "8/2000")
    report.write_text(json.dumps(data))
    code, out, _ = run(capsys, "check", str(report))
    assert "1 display(s) refused" in out and "the Re G^-1 shown is not the real part" in out
