r"""The paper file ``hapticproof new-paper --from SOURCE`` writes: a draft for the reviewer to confirm.

Every display of the source (:func:`~hapticproof.audit.source.displays.read_source`) becomes an
``[[equations]]`` entry with its text verbatim (macros expanded), its ``\label``/``\tag`` or
number as id and its section. The paper is first read as its definitions
(:mod:`hapticproof.audit.definitions.guesses`): a display that defines a name is a ``definition``
(``derived`` when its sentence derives it), one whose sides the definitions give an ``identity``,
an inequality a ``condition`` with the object, property and strength its sentence gives; the
inline ``$...$`` definitions of the prose are entries too. Where the definitions say nothing --
names the paper never defines, a condition about no object of its own -- the shape of the display
says what it claims (:func:`~hapticproof.audit.source.guess.guess_claim`) against a guessed scene,
the toolkit's model. Every guess is marked ``# guessed:`` with the words it came from, for the
reviewer to confirm; names are declared in ``[symbols]`` with the signs the paper states (or their
letter's convention, marked so). A display whose claim neither reading settles is kept commented
out with the reason. The draft is read back before it is returned: an entry the paper-file reader
refuses is commented out with the reader's message, so the written file loads and audits as it
is (:func:`draft`).

Scenes are guessed from the names too: ``b_m``, ``b_s``, ``C_m``... a teleoperator; indexed
names (``K_{01}``, ``b_i``) ``m`` users; ``t_d`` or ``n`` a delayed wall; else the virtual wall
``K + B(z - 1)/(Tz)`` on the HVE device model. Each is one ``[scenes.X]`` table the reviewer
edits into the paper's system.

>>> from hapticproof.audit.source.read import read_text
>>> src = read_text(r'''\section{Wall}
... \begin{equation} b > \frac{KT}{2} + B \label{eq:wall} \end{equation}
... \begin{equation} x_h(k+1) = x_h(k) + T v_h(k) \end{equation}''', "wall.tex")
>>> result = draft(src)
>>> result.active, result.commented          # b > KT/2 + B is about no object of the paper: the scene's
(2, 0)
>>> print("\n".join(result.text.split("[[equations]]")[1].strip().splitlines()[:6]))   # doctest: +ELLIPSIS
# source: wall.tex:2 (equation)
id = '1'
printed = 'b > \frac{KT}{2} + B'
claim = 'passivity-condition'        # guessed: a bound on the parameters without frequency: ... -- confirm
scene = 'wall'                       # guessed: the names of a virtual wall
section = '1'
>>> from hapticproof.audit.paperfile import loads
>>> [c.claim for c in loads(result.text).claims]
['passivity-condition', 'identity']
"""

from __future__ import annotations

import json
import re
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from sympy.core.function import AppliedUndef

from hapticproof.audit.source.displays import Display, Source
from hapticproof.core.errors import LatexParseError
from hapticproof.audit.source.guess import guess_claim, guess_form, symbol_guesses

__all__ = ["Draft", "Entry", "draft", "paper_id_of", "contexts"]

#: Scenes a draft may guess, as the lines of their ``[scenes.X]`` tables.
SCENES = {
    "wall": ['system = "single-user"', 'approximation = "forward"          # guessed: the HVE device model, X_h = T/(z-1) V_h',
             'environment = "K + B*(z - 1)/(T*z)"  # guessed: the virtual wall; write the paper\'s H(z)'],
    "delayed": ['system = "single-user"', 'approximation = "forward"          # guessed: the HVE device model',
                'environment = "K + B*(z - 1)/(T*z)"  # guessed: the virtual wall; write the paper\'s H(z)',
                'delay = "n"                         # t_d = n T, n symbolic'],
    "teleoperator": ['system = "teleoperator"             # guessed: a PEB teleoperator (master b_m, slave b_s)',
                     'controller = "pd"                   # guessed: write the paper\'s C(z)'],
}
#: Names no scene declares that a display may use (the reader knows them).
KNOWN = {"omega", "t_d", "n", "c", "j", "e", "pi"}
#: Greek letters a display writes as commands (``\kappa``): their symbol-table keys take the backslash.
GREEK = {"alpha", "beta", "gamma", "delta", "epsilon", "varepsilon", "zeta", "eta", "theta", "vartheta", "iota", "kappa",
         "lambda", "mu", "nu", "xi", "rho", "sigma", "tau", "upsilon", "phi", "varphi", "chi", "psi", "omega"}
_TELEOPERATOR = re.compile(r"^(?:b|C|K|B|m|x|v|f|F|V|X)_\{?[ms]\}?$|^alpha$")
_USER_INDEX = re.compile(r"^(?:b|K|B|z_a|m)_\{?(\d{1,2})\}?$|^(?:K|B)_\{?0?(\d)(\d)?\}?$")


@dataclass(frozen=True)
class Entry:
    """One display as a draft entry: ``claim`` None when it is commented out (``why``)."""

    display: Display
    id: str
    claim: str | None
    why: str
    scene: str | None = None
    scene_why: str = ""
    symbols: dict[str, tuple[str, str]] = field(default_factory=dict)
    #: the claim the shape suggests, whether or not the entry is active
    guessed: str | None = None
    #: ``"condition"`` for a hermitian-part display without a relation listed among conditions
    form: str | None = None
    #: the fields of a definitions claim (:mod:`hapticproof.audit.definitions.guesses`)
    about: str | None = None
    property: str | None = None
    strength: str | None = None
    derived: bool = False
    assumption: str = ""
    #: the printed text when it is not the display's (an inline definition of the prose)
    printed: str | None = None


@dataclass(frozen=True)
class Draft:
    """A written draft: its TOML ``text`` and how many entries are ``active`` / ``commented``
    out; ``entries`` in source order."""

    text: str
    active: int
    commented: int
    entries: tuple[Entry, ...]


def paper_id_of(path: str) -> str:
    """A paper-file id from a source's file name (``Hulin 2008.tex`` -> ``hulin-2008``)."""
    stem = Path(path).stem if path not in ("", "-") else "paper"
    text = re.sub(r"[^A-Za-z0-9_.-]+", "-", stem).strip("-.").lower()
    return text if text and text[0].isalnum() else "paper"


def _toml_string(text: str) -> str:
    """A TOML string: literal ``'...'`` when the text allows it (LaTeX reads best so), else basic."""
    if "'" not in text and not re.search(r"[\x00-\x1f\x7f]", text):
        return f"'{text}'"
    return json.dumps(text, ensure_ascii=False).replace("\x7f", "\\u007f")


def _toml_key(key: str) -> str:
    return key if re.fullmatch(r"[A-Za-z0-9_-]+", key) else json.dumps(key, ensure_ascii=False).replace("\x7f", "\\u007f")


def _comment(text: str) -> str:
    """Text for a TOML comment: one line, every control character written as a visible escape
    (TOML allows none in a comment: a draft must load as written)."""
    from hapticproof.core.escape import for_terminal

    return for_terminal(" ".join(str(text).split()))


def _users(names: set[str]) -> tuple[int, bool] | None:
    """The number of users the indexed names need (``K_{13}``: 3; ``b_i``, ``K_{ij}``: 2) and
    whether they are the uniform group names (``K_0``, ``B_0``); ``None`` for no such name."""
    count, uniform = None, False
    for name in names:
        match = re.match(r"^(b|K|B|z_a|m)_\{?([0-9ij]+)\}?$", name)
        if match is None:
            continue
        group, index = match.groups()
        if group in ("K", "B") and index == "0":
            uniform = True
            count = max(count or 2, 2)
            continue
        if group in ("K", "B") and len(index) != 2:
            continue
        if group in ("b", "z_a", "m") and len(index) != 1:
            continue
        digits = [int(d) for d in index if d in "0123456789"]
        count = max(count or 2, 2, *digits)
    return None if count is None else (count, uniform)


def _guess_scene(names: set[str]) -> tuple[str, str]:
    """The scene a display's names suggest, and why."""
    plain = {n for n in names}
    if any(_TELEOPERATOR.match(n) for n in plain) and any(n.startswith(("b_m", "b_s", "C_m", "C_s")) for n in plain):
        return "teleoperator", "master and slave names (b_m, b_s, C_m, C_s)"
    users = _users(plain)
    if users is not None:
        count, uniform = users
        if uniform:
            return f"uniform{count}", f"the group names of {count} identical users (K_0, B_0, K, B)"
        return f"users{count}", f"indexed names of {count} users"
    if {"t_d", "n"} & plain:
        return "delayed", "a delay t_d = n T"
    return "wall", "the names of a virtual wall"


def _designs(source: Source) -> dict[str, tuple[str, str]]:
    """The environment ``H(z) = ...`` and controller ``C(z) = ...`` the source defines in a
    display of their own (the first of each), as scene-file expressions, with the display's id."""
    from hapticproof.audit.reader.names import SymbolTable
    from hapticproof.audit.reader.printed import parse_printed
    from hapticproof.core.errors import HapticproofError
    from hapticproof.core.expr import parameter_symbol, write_expression
    from hapticproof.core.symbols import z as Z_SYM
    from hapticproof.systems.scene import scene_from_table

    out: dict[str, tuple[str, str]] = {}
    for display in source.displays:
        match = re.match(r"^\s*([HC])\s*\(\s*z\s*\)\s*=(?!=)(.+)$", display.text, re.S)
        if match is None or match.group(1) in out or re.search(r"[<>=]|\\[lg]e", match.group(2)):
            continue
        symbols: dict[str, object] = {"z": Z_SYM}
        try:
            for key, (word, _why) in symbol_guesses(match.group(2)).items():
                if word.split(",")[0] in ("function", "signal") or "," in word:
                    raise ValueError(key)
                name = key.replace("{", "").replace("}", "").replace("\\", "")
                symbols[("\\" + key) if key.split("_")[0] in GREEK else key] = parameter_symbol(name, word)
            expr = parse_printed(match.group(2), SymbolTable(symbols=symbols)).expressions()[0]
        except (HapticproofError, ValueError, IndexError, TypeError):
            continue
        text = write_expression(expr)
        system, field = ("single-user", "environment") if match.group(1) == "H" else ("teleoperator", "controller")
        try:                                   # a design no scene takes is no guess
            scene_from_table({"system": system, field: text}).build()
        except HapticproofError:
            continue
        out[match.group(1)] = (text, display.id)
    if "H" in out:
        roles = _guessed_roles(source, {s.name for s in expr_symbols(out["H"][0])})
        if roles:
            out["roles"] = (roles, out["H"][1])
    elif not any(_VIRTUAL_DAMPING.search(d.text) for d in source.displays):
        out["spring"] = ("K", "")               # no display names a virtual damping B: the wall is a spring
    return out


#: the virtual damping ``B`` of a wall, as a display writes it (not ``B_c``, not ``\mathbf{B}``)
_VIRTUAL_DAMPING = re.compile(r"(?<![A-Za-z\\])B(?![A-Za-z_])")
_BOLD = re.compile(r"\\(?:mathbf|boldsymbol|bm|mathcal|mathsf)\s*\{[^{}]*\}")


def expr_symbols(text: str) -> set:
    from hapticproof.core.expr import read_expression

    return read_expression(text, "z").free_symbols - {read_expression("z", "z")}


#: "<word> damping $X ...$" in the prose: the device's damping unless the word says otherwise
_DEVICE_DAMPING = re.compile(r"([A-Za-z]+)\s+damping\s+(?:of\s+|coefficient\s+)?\$\s*([A-Za-z](?:_\{?\w+\}?)?)")
#: the words before "damping" that name a damping other than the device's
_NOT_THE_DEVICE = frozenset({"virtual", "rendered", "wall", "environment", "controller", "coupling", "added", "simulated"})


def _guessed_roles(source: Source, environment: set[str]) -> str | None:
    """The wall's roles in the paper's own names, as an inline TOML table: the period when
    ``H(z)`` has one ``T_...`` and no ``T``, or uses the one period the prose or the displays
    name ("sampled with period $h$", ``\\cos(\\omega h)``); the device damping when a display
    ``G^{-1}(z) = X + ...`` starts with a name ``X`` that ``H`` does not use, or the prose calls a
    name ``H`` does not use the device's damping ("physical damping $c_d > 0$")."""
    from hapticproof.audit.source.guess import period_names

    roles = {}
    prose = "\n".join(d.prose for d in source.displays)
    periods = sorted(n for n in environment if re.fullmatch(r"T_?\w*", n) and n != "T")
    if "T" not in environment and len(periods) != 1:     # the period the prose or the displays name
        named = period_names(prose, "\n".join(d.text for d in source.displays))
        periods = [n for n in (p.replace("{", "").replace("}", "") for p in named) if n in environment]
    if "T" not in environment and len(periods) == 1:
        roles["period"] = periods[0]
    for display in source.displays:
        match = re.match(r"^\s*G\^\{?-1\}?\s*\(\s*z\s*\)\s*=\s*([A-Za-z](?:_\{?\w+\}?)?)\s*\+", display.text)
        if match:
            name = match.group(1).replace("{", "").replace("}", "")
            if name not in environment and name not in ("b", "z", "e", "j"):
                roles["device_damping"] = name
            break
    if "device_damping" not in roles:          # "a device with physical damping $c_d > 0$"
        for m in _DEVICE_DAMPING.finditer(prose):
            name = m.group(2).replace("{", "").replace("}", "")
            if m.group(1).lower() not in _NOT_THE_DEVICE and name not in environment and name not in ("b", "z", "e", "j"):
                roles["device_damping"] = name
                break
    return "{ " + ", ".join(f'{k} = "{v}"' for k, v in sorted(roles.items())) + " }" if roles else None


def _scene_lines(name: str, designs: dict[str, tuple[str, str]] | None = None) -> list[str]:
    designs = designs or {}
    if name in ("wall", "delayed") and "H" in designs:
        text, ident = designs["H"]
        lines = [line if not line.startswith("environment") else
                 f"{'environment = ' + _toml_string(text):36s} # guessed: H(z) of display ({ident})" for line in SCENES[name]]
        if "roles" in designs:
            lines.append(f"{'roles = ' + designs['roles'][0]:36s} # guessed: the paper's period and device damping")
        return lines
    if name in ("wall", "delayed") and "spring" in designs:
        return [line if not line.startswith("environment") else
                f"{'environment = ' + _toml_string('K'):36s} # guessed: a virtual spring (no display names a damping B)"
                for line in SCENES[name]]
    if name == "teleoperator" and "C" in designs:
        text, ident = designs["C"]
        return [SCENES[name][0], f"{'controller = ' + _toml_string(text):36s} # guessed: C(z) of display ({ident})"]
    if name.startswith(("users", "uniform")):
        uniform = name.startswith("uniform")
        users = int(name[len("uniform" if uniform else "users"):])
        lines = ['system = "multi-user"                # guessed: users coupled by K_0i, B_0i, K_ij, B_ij',
                 f"users = {users}", 'approximation = "forward"']
        return lines + (["uniform = true                      # one symbol per group: b, K_0, B_0, K, B"] if uniform else [])
    return SCENES[name]


def _scene_names(name: str, cache: dict[str, set[str]], designs: dict[str, tuple[str, str]] | None = None) -> set[str]:
    """The parameter names of a guessed scene (as ``[symbols]`` keys: ``K_{01}``)."""
    if name in cache:
        return cache[name]
    import tomllib

    from hapticproof.audit.paperfile import printed_key
    from hapticproof.audit.reader.names import normalise_name
    from hapticproof.systems.scene import scene_from_table

    scene = scene_from_table(tomllib.loads("\n".join(line.split("  #")[0] for line in _scene_lines(name, designs))))
    names = set()
    for param in scene.names() | {"b", "T", "z_a"}:
        try:
            names.add(normalise_name(printed_key(param)))
        except ValueError:
            continue
    cache[name] = names
    return names


def _outside(names: dict[str, tuple[str, str]], scene_names: set[str]) -> list[str]:
    """Names a display uses that are neither the scene's parameters nor known to the reader."""
    from hapticproof.audit.reader.names import normalise_name

    out = []
    for key, (word, _why) in names.items():
        if word.split(",")[0].strip() in ("function", "signal"):
            continue
        if key in KNOWN:
            continue
        try:
            printed = normalise_name("\\" + key if key.split("_")[0] in GREEK else key)
        except ValueError:
            out.append(key)
            continue
        if printed in scene_names:
            continue
        if re.search(r"_\{?[^}]*[ij]", key) and any(n.split("_")[0] == key.split("_")[0] for n in scene_names):
            continue                                   # an indexed family over the users
        out.append(key)
    return out


def _label(text: str, claim: str) -> str | None:
    """The lone name a display states its object under (``R_0 = ...``, ``r = KT``): a label,
    not a parameter (claims of expressions only)."""
    if claim not in ("residue", "inverse-transfer", "hermitian-part"):
        return None
    match = re.match(r"^\s*([A-Za-z](?:_\{?[A-Za-z0-9]+\}?)?)\s*=", text)
    if match is None:
        return None
    name = match.group(1)
    sub = re.match(r"^([A-Za-z])_\{?([A-Za-z0-9]+)\}?$", name)
    return f"{sub.group(1)}_{{{sub.group(2)}}}" if sub and len(sub.group(2)) > 1 else \
        (f"{sub.group(1)}_{sub.group(2)}" if sub else name)


def contexts(source: Source) -> list[str]:
    """The prose before each display; a display right after another (no prose between) shares
    the prose before the first of its run ("the conditions are found as follows: (17) (18) (19)")."""
    out, last = [], ""
    for display in source.displays:
        if display.context.strip():
            last = display.context
        out.append(display.context if display.context.strip() else last)
    return out


def _names_of(reading: Any, words: dict[str, str]) -> dict[str, tuple[str, str]]:
    """The ``[symbols]`` words of the names a read display uses (from the paper's definitions reading)."""
    from hapticproof.audit.reader.names import sympy_name

    statement = getattr(reading, "statement", None)
    extra = set(getattr(reading, "extra_names", ()))
    if statement is None and not extra:
        return {}
    used: set[str] = {sympy_name(p) for p in extra}
    for relation in (statement.relations() if statement is not None else ()) or ():
        for term in relation.terms:
            atoms = term.free_symbols if hasattr(term, "free_symbols") else set()
            used |= {getattr(a, "name", "") for a in atoms}
            if hasattr(term, "atoms"):
                used |= {f.func.__name__ for f in term.atoms(AppliedUndef)}
    for expr in (getattr(statement, "expressions", lambda: [])() if statement is not None else ()):
        used |= {getattr(a, "name", "") for a in getattr(expr, "free_symbols", set())}
    from hapticproof.audit.definitions.guesses import conventional

    out = {}
    for printed, word in words.items():
        if re.search(r"_\{[^}]*[-+,*/][^}]*\}", printed):
            continue                          # z_{3i-2,3j-2}: an index expression, not a name of the paper
        if sympy_name(printed) in used:
            if conventional(printed, word):
                why = f"{word} by the convention of its letter (the paper states no sign)"
            else:
                why = "stated by the paper" if word not in ("real", "function") else (
                    "applied to (z), (s) or a frequency" if word == "function" else "no sign stated")
            out[printed] = (word, why)
    return out


#: The scene claims that check an expression against the scene's model (a derived definition is
#: confirmed when the scene's G^-1 is what the paper derived).
_SCENE_EXPRESSIONS = ("inverse-transfer", "hermitian-part", "residue")


def _scene_guess(display: Display, ident: str, context: str, designs: dict[str, tuple[str, str]],
                 cache: dict[str, set[str]]) -> Entry:
    """The entry the display's shape and a guessed scene give (the reading before definitions)."""
    claim, why = guess_claim(display.text, context=context)
    form = guess_form(display.text, claim, context)
    if form is not None:
        why += "; the sentence before lists it among conditions, so read as Re G^{-1} >= 0 ('> 0' is not printed)"
    names = symbol_guesses(display.text)
    if claim is None:
        used = [k for k, (_t, i) in designs.items() if i == display.id]
        if used:
            why += f"; its right-hand side is the guessed scenes' {'environment' if used[0] == 'H' else 'controller'}"
        return Entry(display, ident, None, f"not classified: {why}", symbols=names)
    scene, scene_why = _guess_scene(set(names))
    missing = [n for n in _outside(names, _scene_names(scene, cache, designs)) if n != _label(display.text, claim)]
    if missing:
        return Entry(display, ident, None, f"guessed {claim} ({why}), but the guessed scene '{scene}' has no "
                     f"{', '.join(missing)}: write its scene, then uncomment", scene=scene, symbols=names,
                     guessed=claim, form=form)
    return Entry(display, ident, claim, why, scene, scene_why, names, guessed=claim, form=form)


#: a display that defines a transfer function G (``G^{-1}(z) = ...``, ``\hat G_d(z) = ...``)
_DEFINES_G = re.compile(r"^\s*(?:\\(?:hat|tilde|bar|mathbf)\s*\{?\s*)?G(?![A-Za-z])[^=<>]{0,40}=")


def _entries(source: Source, designs: dict[str, tuple[str, str]]) -> list[Entry]:
    from hapticproof.audit.definitions.guesses import read_claims

    claims = read_claims(source)
    read = {c.display.id: c for c in claims.displays}
    inline_before: dict[str, list[Any]] = {}
    for c in claims.inline:
        inline_before.setdefault(c.display.id, []).append(c)
    seen: dict[str, int] = {}
    cache: dict[str, set[str]] = {}
    out = []
    defines_g = any(_DEFINES_G.match(d.text) for d in source.displays)
    for display, context in zip(source.displays, contexts(source)):
        ident = display.id
        if ident in seen:
            seen[ident] += 1
            ident = f"{ident}-{seen[ident]}"
        else:
            seen[ident] = 1
        for c in inline_before.pop(display.id, []) if seen[display.id] == 1 else []:
            out.append(Entry(display, c.id, c.claim, c.why, symbols=_names_of(c.reading, claims.words),
                             guessed=c.claim, printed=c.printed, assumption=c.assumption))
        rc = read.get(display.id)
        guess = _scene_guess(display, ident, context, designs, cache)
        if rc is not None and seen[display.id] == 1 and rc.claim is not None:
            scene_claim = guess.claim in _SCENE_EXPRESSIONS and guess.scene is not None
            if rc.claim == "identity" and rc.unbound and guess.claim is not None:
                out.append(guess)             # names the paper never defines: the scene's model says what they are
                continue
            if rc.claim == "condition" and rc.property == "positive-real" and not rc.about and not defines_g \
                    and guess.claim is not None and guess.scene is not None:
                out.append(guess)             # passivity of no object the paper defines: the guessed scene's model
                continue
            out.append(Entry(display, ident, rc.claim, rc.why, scene=guess.scene if (rc.derived and scene_claim) else None,
                             scene_why=guess.scene_why if rc.derived and scene_claim else "",
                             symbols={**(guess.symbols if rc.derived and scene_claim else {}),
                                      **_names_of(rc.reading, claims.words)},
                             guessed=rc.claim, about=rc.about, property=rc.property, strength=rc.strength,
                             derived=rc.derived, assumption=rc.assumption,
                             printed=rc.printed if rc.printed != display.text else None))
            continue
        if rc is not None and rc.claim is None and rc.no_object and guess.claim is not None:
            out.append(guess)                 # no object of the paper's: the scene's model is the object
            continue
        if rc is not None and rc.claim is None and rc.reading is not None and rc.reading.kind != "other" \
                and not rc.why.startswith("the reader cannot read"):
            # the definitions reading understood the display but could not settle its claim: a
            # scene guess would be worse than the reviewer's word
            out.append(Entry(display, ident, None, f"not settled: {rc.why}", symbols=_names_of(rc.reading, claims.words)))
            continue
        out.append(guess)
    return out


def _render(source: Source, entries: list[Entry], paper_id: str, title: str, dropped: dict[str, str],
            designs: dict[str, tuple[str, str]] | None = None) -> str:
    lines = [
        f"# A draft paper file, written by hapticproof new-paper --from {source.path}",
        "# Every display of the source is below, verbatim (macros expanded). Lines marked '# guessed:'",
        "# are the reader's guesses: confirm or correct each one (the claim, the scene, the assumption of",
        "# each name), give the scenes the paper's systems, uncomment the displays you can classify, then",
        f"#     hapticproof audit --paper {paper_id}.toml --format html -o errata.html",
    ]
    lines += [f"# warning: {_comment(w)}" for w in source.warnings]
    lines += ["", "[paper]", f"id = {_toml_string(paper_id)}", f"title = {_toml_string(title)}",
              f"source = {_toml_string(str(source.path))}", ""]
    active = [e for e in entries if e.claim is not None and e.id not in dropped]
    is_active = {id(e) for e in active}                 # (membership by identity: linear in the displays)
    symbols: dict[str, tuple[str, str]] = {}
    seen_names: dict[str, str] = {}
    for entry in active:
        for name, guess in entry.symbols.items():
            key = _canonical_key(name)
            if key in seen_names:
                # T_s and T_{s} are one name; a name applied somewhere ("G^{-1}(z)") is a function
                # even where another display writes it bare ("F = G^{-1} V")
                first = seen_names[key]
                if guess[0] == "function" and symbols[first][0] == "real":
                    symbols[first] = guess
                continue
            seen_names[key] = name
            symbols[name] = guess
    lines.append("[symbols]                            # every name the active displays use, with its assumption")
    for name, (word, why) in symbols.items():
        lines.append(f"{_toml_key(name) + ' = ' + _toml_string(word):36s} # guessed: {_comment(why)}")
    others = sorted({n for e in entries if id(e) not in is_active for n in e.symbols} - set(symbols))
    if others:
        lines.append("# names only the commented-out displays use: " + ", ".join(others))
    lines.append("# inequalities and relations are assumptions too: a = \"0 <= a < 1\", b_m = \"b_m >= b_s\"")
    for scene in sorted({e.scene for e in active if e.scene}):
        lines += ["", f"[scenes.{scene}]"] + _scene_lines(scene, designs)
    lines.append("")
    for entry in entries:
        lines += _entry_lines(entry, id(entry) in is_active, dropped.get(entry.id), str(source.path))
    return "\n".join(lines).rstrip() + "\n"


def _canonical_key(name: str) -> str:
    from hapticproof.audit.paperfile import printed_key
    from hapticproof.audit.reader.names import normalise_name

    try:
        return normalise_name(printed_key(name))
    except (ValueError, LatexParseError):
        return name


def _shown_file(file: str, source_path: str) -> str:
    """A display's file as the reviewer knows it: relative to the source's folder."""
    import os

    if not os.path.isabs(file):
        return file
    folder = source_path if os.path.isdir(source_path) else os.path.dirname(source_path)
    try:
        return os.path.relpath(file, folder or ".")
    except ValueError:
        return file


def _entry_lines(entry: Entry, active: bool, refused: str | None, source_path: str = "") -> list[str]:
    d = entry.display
    body = [f"id = {_toml_string(entry.id)}", f"printed = {_toml_string(entry.printed or d.text)}"]
    if active and entry.claim in ("definition", "identity", "condition"):
        body.append(f"{'claim = ' + _toml_string(entry.claim):36s} # guessed: {_comment(entry.why)} -- confirm")
        for key in ("about", "property", "strength"):
            if getattr(entry, key):
                body.append(f"{key} = {_toml_string(getattr(entry, key))}")
        if entry.derived:
            body.append("derived = true                       # the paper derives it: bound as printed, not verified")
            if entry.scene:
                body.append(f"{'scene = ' + _toml_string(entry.scene):36s} # guessed: checked against this scene's model "
                            f"({_comment(entry.scene_why)})")
        if entry.assumption:
            body.append(f"{'assumption = ' + _toml_string(entry.assumption):36s} # from the sentence")
    elif active:
        body.append(f"{'claim = ' + _toml_string(entry.claim):36s} # guessed: {_comment(entry.why)} -- confirm")
        body.append(f"{'scene = ' + _toml_string(entry.scene):36s} # guessed: {_comment(entry.scene_why)}")
    else:
        body.append(f"claim = {_toml_string(entry.guessed)}" if entry.guessed else 'claim = "?"')
        if entry.scene:
            body.append(f"scene = {_toml_string(entry.scene)}")
    if entry.form:
        body.append(f"{'form = ' + _toml_string(entry.form):36s} # guessed: listed among conditions")
    if d.section is not None and d.section.id:
        body.append(f"section = {_toml_string(d.section.id)}")
    notes = [f"{_shown_file(d.file, source_path)}:{d.line} ({'inline, in the prose before the display' if entry.printed and '.inline' in entry.id else d.environment})"]
    notes += list(d.notes)
    original = re.sub(r"\\(?:label|tag\*?)\s*\{[^{}]*\}|\\(?:nonumber|notag)(?![A-Za-z])", " ", d.original)
    if original.strip() and " ".join(original.split()) != " ".join(d.text.split()):
        notes.append("as written: " + _comment(d.original)[:200])
    header = ["", "[[equations]]"]
    comment = [f"# source: {_comment(n)}" for n in notes]
    if active:
        return header + comment + body
    reason = refused or entry.why
    return ["", f"# {_comment(reason)}", "# [[equations]]"] + comment + [f"# {line}" for line in body]


def draft(source: Source, *, paper_id: str | None = None, title: str | None = None, max_rounds: int = 50) -> Draft:
    """The draft paper file of a read source; every active entry loads (checked by reading the
    draft back with :func:`hapticproof.audit.paperfile.loads`: an entry the reader refuses is
    commented out with the reader's message)."""
    from hapticproof.audit.paperfile import PaperFileError, loads

    paper_id = paper_id or paper_id_of(str(source.path))
    if not re.fullmatch(r"[A-Za-z0-9][A-Za-z0-9_.-]*", paper_id):
        raise PaperFileError(f"paper id {paper_id!r}: letters, digits, '-', '_' and '.' only")
    title = title or source.title or (source.sections[0].title if source.sections and not source.sections[0].number else "") \
        or f"Displays of {Path(str(source.path)).name}"
    designs = _designs(source)
    entries = _entries(source, designs)
    dropped: dict[str, str] = {}
    text = _render(source, entries, paper_id, title, dropped, designs)
    for _ in range(max_rounds):
        if not any(e.claim is not None and e.id not in dropped for e in entries):
            break
        try:
            loads(text, f"{paper_id}.toml")
            break
        except PaperFileError as err:
            culprit = _culprit(text, str(err), entries, dropped)
            if culprit is None:
                raise
            dropped[culprit] = f"refused by the paper-file reader: {_comment(_reason(str(err)))}"
            text = _render(source, entries, paper_id, title, dropped, designs)
    active = sum(1 for e in entries if e.claim is not None and e.id not in dropped)
    return Draft(text, active, len(entries) - active, tuple(entries))


def _reason(message: str) -> str:
    return re.sub(r"^[^:]*:\d+:\s*", "", message)


def _culprit(text: str, message: str, entries: list[Entry], dropped: dict[str, str]) -> str | None:
    """The active entry an error names (by its line, else by a name it uses)."""
    match = re.match(r"^[^:]*:(\d+):", message)
    lines = text.splitlines()
    active = [e for e in entries if e.claim is not None and e.id not in dropped]
    if match:
        line = int(match.group(1))
        for k in range(min(line, len(lines)) - 1, -1, -1):
            found = re.match(r"id = (.+)$", lines[k])
            if found and lines[k - 1].strip().startswith(("[[equations]]", "# source:")):
                ident = _unquote(found.group(1))
                if any(e.id == ident for e in active):
                    return ident
            if lines[k].startswith("[") and not lines[k].startswith("[[equations]]"):
                break
        # an error in [symbols] or a scene: drop the first active entry using the name it names
        named = re.search(r"symbols: ([^:]+):", message)
        if named:
            key = named.group(1).strip()
            for entry in active:
                if key in entry.symbols:
                    return entry.id
    return active[0].id if active else None


def _unquote(text: str) -> str:
    text = text.split("  #")[0].strip()
    if text.startswith("'") and text.endswith("'"):
        return text[1:-1]
    try:
        return json.loads(text)
    except ValueError:
        return text

