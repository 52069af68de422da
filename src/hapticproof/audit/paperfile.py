r"""Paper files: audit your own paper from a TOML file, without writing Python.

A paper file lists the printed displays of a paper -- verbatim, OCR damage and all -- with what
each one claims about a scene. Each claim is checked by a generic claim checker
(:mod:`hapticproof.audit.claims`) that produces the same :class:`~hapticproof.core.evidence.Finding`
objects as the hand-written derivation modules, so every report format works for both
(``hapticproof audit --paper FILE.toml``).

.. code-block:: toml

    [paper]
    id = "wall-1997"                       # used in output and by same-as
    title = "Passivity of a virtual wall"
    authors = "..."                        # optional
    source = "journal, year"               # optional

    [symbols]                              # every name the printed LaTeX uses
    b = "positive"                         # positive | nonnegative | real | integer | ...
    K = "positive"
    B = "nonnegative"
    T = "positive"
    omega = "real"                         # Greek letters by name: \omega
    "G^{-1}" = "function"                  # a name applied as G^{-1}(z), compared with nothing
    F_h = "signal"                         # a signal F_h(z): F_h(z) = G^{-1}(z) V_h(z) reads G^{-1}
    V_h = "signal"
    S = '\frac{\sin(\omega T)}{2}'         # a definition: LaTeX in the names above
    "K_{ij}" = "positive, symmetric"       # an indexed family (index letters i, j)
    a = "0 <= a < 1"                       # an assumption: an inequality, interval or relation
    b_m = "b_m >= b_s"                     # (LaTeX or expression syntax; audit.regions)

    [scenes.wall]                          # exactly the fields of a scene file
    system = "single-user"
    approximation = "forward"

    [[equations]]
    id = "3"
    printed = 'b > \frac{KT}{2} + B'       # the display verbatim
    claim = "passivity-condition"
    scene = "wall"
    section = "2"                          # optional: for --section

Names
-----
``j`` is the imaginary unit and ``e^{...}`` the exponential unless ``[symbols]`` declares them;
``z`` and ``s`` are the transform variables; ``G``, ``G^{-1}``, ``\omega``, ``t_d``, ``n``, the
parameters of an equation's scene and the m-user families (``b_i``, ``K_{0i}``...) need no
declaration. In a display, ``H(...)`` is the scene's
environment ``H(z)`` (single-user) and ``C(...)`` its controller ``C(z)`` (teleoperator). A
symbol whose name is a scene parameter is that parameter (with the file's assumption); a
display's ``t_d`` is ``n T`` with the scene's delay ``n``.

Claims (:data:`CLAIMS`; :mod:`hapticproof.audit.claims` says how each is decided)
    ``inverse-transfer``, ``hermitian-part``, ``residue``, ``passivity-condition``,
    ``sufficient-condition``, ``necessary-condition``, ``stability-condition``, ``same-as``.
Equation fields (:data:`EQUATION_FIELDS`)
    ``id``, ``printed``, ``claim``, ``scene`` (all but same-as), ``section``, ``notes``;
    ``other`` and ``under`` (same-as: ``other = "3"`` or ``"hve:3"``, ``under = "z_a = 0, t_d =
    0"``); ``order`` (stability: ``"exact"`` or ``"leading"``); ``form`` (hermitian-part:
    ``"expression"`` or ``"condition"``, default: as printed); ``assumption`` (conditions: the
    paper's vague assumption made precise, such as ``"B = 0"`` or ``'B \leq \frac{KT}{2}'`` for
    "B small": a condition that holds only there is ``needs-assumption``); ``solve_for`` (conditions: the parameter the
    comparison solves for, default the device damping).

Every mistake in a file is one line naming the file, the line and the field
(:class:`PaperFileError`), and the CLI exits with code 2.

>>> paper = loads(TEMPLATE, "new.toml")
>>> paper.id, [c.claim for c in paper.claims]
('my-paper', ['inverse-transfer', 'hermitian-part', 'passivity-condition'])
>>> loads(TEMPLATE.replace('claim = "passivity-condition"', 'claim = "passivity"'), "new.toml")
Traceback (most recent call last):
...
hapticproof.audit.paperfile.PaperFileError: new.toml:47: equation 3: field 'claim': unknown claim 'passivity' (did you mean 'passivity-condition'?)
"""

from __future__ import annotations

import difflib
import functools
import re
from collections.abc import Mapping
from dataclasses import dataclass, field
from decimal import Decimal
from pathlib import Path
from typing import Any

import sympy as sp

from hapticproof.audit.runner import Equation, Paper
from hapticproof.core.errors import HapticproofError, InputFormatError, LatexParseError
from hapticproof.core.limits import LimitError
from hapticproof.core.expr import apart_symbol

__all__ = [
    "CLAIMS",
    "EQUATION_FIELDS",
    "WORDS",
    "TEMPLATE",
    "PaperFileError",
    "ClaimSpec",
    "PaperFile",
    "FilePaper",
    "loads",
    "read_paper",
    "register_claims",
]

#: The claim kinds of a paper file.
CLAIMS = ("inverse-transfer", "hermitian-part", "residue", "passivity-condition", "sufficient-condition",
          "necessary-condition", "stability-condition", "same-as", "definition", "identity", "condition")
#: Claims read from the paper's own definitions (:mod:`hapticproof.audit.definitions`): no scene.
DEFINITION_CLAIMS = ("definition", "identity", "condition")
#: Claims about a condition (``assumption`` and ``solve_for`` apply).
CONDITION_CLAIMS = ("passivity-condition", "sufficient-condition", "necessary-condition", "stability-condition")
#: Fields of an ``[[equations]]`` entry.
EQUATION_FIELDS = ("id", "printed", "claim", "scene", "section", "other", "under", "order", "form", "assumption",
                   "solve_for", "notes", "about", "property", "strength", "derived")
#: The properties and strengths a ``condition`` claim names.
PROPERTIES = ("positive-real", "absolutely-stable")
STRENGTHS = ("iff", "sufficient", "necessary")
#: Fields of ``[paper]``.
PAPER_FIELDS = ("id", "title", "authors", "source")
#: Words of ``[symbols]``: sign assumptions, ``function`` and ``signal`` (a declared name whose
#: value is no word is a definition in LaTeX); ``symmetric`` qualifies an indexed family.
WORDS = ("positive", "nonnegative", "real", "integer", "negative", "nonpositive", "function", "signal")
_INDEX_LETTERS = ("i", "j")


class PaperFileError(InputFormatError):
    """A paper file that cannot be read: one line naming the file, the line and the field."""


@dataclass(frozen=True, slots=True)
class ClaimSpec:
    """One ``[[equations]]`` entry: a printed display and what it claims.

    ``under`` holds the substitutions of a same-as claim as ``((name, value), ...)`` and
    ``assumption`` a condition's stated assumption as a :class:`~hapticproof.audit.regions.Region`
    (equalities, inequalities, intervals, relations), each read with the file's symbols;
    ``line`` is the entry's first line in the file.
    """

    id: str
    printed: str
    claim: str
    scene: str | None = None
    section: str = ""
    other: str | None = None
    under: tuple[tuple[sp.Symbol, sp.Expr], ...] = ()
    order: str = "exact"
    form: str = "auto"
    assumption: Any = None                 # a hapticproof.audit.regions.Region (None: no assumption)
    solve_for: str | None = None
    notes: str = ""
    line: int | None = None
    #: definitions claims: the object a condition is about, its property and strength, the
    #: stated assumption as written, and whether the paper presents a definition as derived
    about: str | None = None
    property: str | None = None
    strength: str | None = None
    stated: str = ""
    derived: bool = False

    def __post_init__(self) -> None:
        if self.claim not in CLAIMS:
            raise ValueError(f"unknown claim {self.claim!r}")
        if self.order not in ("exact", "leading"):
            raise ValueError(f"order must be exact or leading, got {self.order!r}")
        if self.form not in ("auto", "expression", "condition"):
            raise ValueError(f"form must be expression or condition, got {self.form!r}")


@dataclass(frozen=True)
class PaperFile:
    """A read paper file: its metadata, names, scenes and claims, and the registered
    :class:`~hapticproof.audit.runner.Paper` (``paper``) that the audit runs.

    ``words`` maps each declared SymPy name to its word (``positive``, ``function``,
    ``signal``...; definitions map to ``definition``); ``scenes`` holds the
    :class:`~hapticproof.systems.scene.Scene` of each ``[scenes.X]``.
    """

    path: str
    id: str
    title: str
    authors: str
    source: str
    symbols: Any                         # hapticproof.audit.reader.names.SymbolTable
    words: Mapping[str, str]
    scenes: Mapping[str, Any]
    claims: tuple[ClaimSpec, ...]
    text: str = field(repr=False, default="")
    #: the relations of ``[symbols]`` (``0 <= a < 1``): a region every claim is decided in
    region: Any = None
    paper: Any = field(repr=False, default=None)
    _tables: dict = field(repr=False, compare=False, default_factory=dict)

    @functools.cached_property
    def definitions(self) -> Any:
        """The paper read as its definitions (:class:`~hapticproof.audit.definitions.reading.PaperReading`)
        over its definition, identity and condition claims, in file order."""
        from hapticproof.audit.definitions.checks import verified_by_scene
        from hapticproof.audit.definitions.reading import PaperReading

        reading = PaperReading.of_claims(self.claims, self.symbols, self.region)
        for spec in self.claims:
            if spec.claim == "definition" and spec.derived and spec.scene and verified_by_scene(self, spec):
                reading.verified(spec.id)
        return reading

    def claim(self, id: str) -> ClaimSpec:
        for spec in self.claims:
            if spec.id == id:
                return spec
        raise KeyError(id)

    def signals(self) -> set[sp.Symbol]:
        """The declared signals (``F_h``, ``V_h``...) as symbols."""
        return {sp.Symbol(name) for name, word in self.words.items() if word == "signal"}

    def table_for(self, scene: str | None) -> Any:
        """The symbol table with ``H``/``C`` bound to the scene's environment or controller."""
        return _scene_table(self, scene)

    def bound_table(self, scene: Any, key: Any) -> Any:
        """The symbol table bound to a scene object (remembered under ``key``), see :func:`bound_table`."""
        return bound_table(self, scene, key)

    def naming(self) -> Any:
        """The names the paper's reports print (:func:`file_naming`, computed once)."""
        if "naming" not in self._tables:
            self._tables["naming"] = file_naming(self)
        return self._tables["naming"]


class FilePaper(Paper):
    """A :class:`~hapticproof.audit.runner.Paper` read from a file: equations stay in file order."""

    def ordered(self) -> list[Equation]:
        return list(self.equations.values())


# ---------------------------------------------------------------------------------------------
# where things are in the file
# ---------------------------------------------------------------------------------------------


def _key_pattern(key: str) -> re.Pattern:
    return re.compile(r"\s*(?:\"" + re.escape(key) + r"\"|'" + re.escape(key) + r"'|" + re.escape(key) + r")\s*=")


def _blocks(text: str, name: str) -> list[tuple[int, int]]:
    """First and last line (1-based) of each ``[[name]]`` entry."""
    from hapticproof.core.tomltext import toml_lines

    return toml_lines(text).entries(name)


def _line_in(text: str, key: str, block: tuple[int, int] | None) -> int | None:
    from hapticproof.core.tomltext import toml_lines

    if block is None:
        return None
    found = toml_lines(text).line_between(key, block[0], block[1])
    return found if found is not None else block[0]


def _table_line(text: str, key: str, table: str) -> int | None:
    from hapticproof.core.tomltext import line_of

    return line_of(text, key, table)


def _at(path: str, line: int | None) -> str:
    return f"{path}:{line}" if line else path


# ---------------------------------------------------------------------------------------------
# [symbols]
# ---------------------------------------------------------------------------------------------


def printed_key(key: str) -> str:
    r"""The printed name of a ``[symbols]`` key: ``omega`` is ``\omega``, ``mathcal{M}`` is
    ``\mathcal{M}``; other keys are printed names already."""
    from hapticproof.audit.reader.lexer import DECORATIONS, GREEK

    if key.startswith("\\"):
        return key
    base = re.match(r"[A-Za-z]+", key)
    if base and ("\\" + base.group(0) in GREEK or "\\" + base.group(0) in DECORATIONS):
        return "\\" + key
    return key


def _is_family(printed: str) -> bool:
    from hapticproof.audit.reader.names import name_parts

    try:
        parts = name_parts(printed)
    except LatexParseError:
        return False
    if parts.sub is None:
        return False
    sub = "".join(t.value for t in parts.sub)
    return any(letter in sub for letter in _INDEX_LETTERS) and not re.fullmatch(r"[a-hk-z]+", sub)


def _assumption_kwargs(word: str) -> dict[str, bool]:
    from hapticproof.core.expr import ASSUMPTIONS

    return dict(ASSUMPTIONS[word])


#: An assumption in ``[symbols]`` rather than a word or a definition: a relation.
_RELATION = re.compile(r"<|>|\\(?:le|ge|leq|geq|leqslant|geqslant|lt|gt|in)(?![A-Za-z])")


def _read_symbols(raw: Mapping[str, Any], path: str, text: str,
                  scenes: bool = True) -> tuple[Any, dict[str, str], Any, dict[str, int | None]]:
    """The symbol table of ``[symbols]``, the word of each declared name, the region of the
    relations it states (``a = "0 <= a < 1"``) and the line of each. The toolkit's own names are
    refused only where its derivations run (``scenes``): a paper read as its definitions alone
    gives ``c`` whatever meaning the paper gives it."""
    from hapticproof.audit.reader.names import IndexedFamily, SymbolTable, sympy_name, normalise_name
    from hapticproof.core.symbols import s as S_SYM
    from hapticproof.core.symbols import z as Z_SYM

    symbols: dict[str, Any] = {"z": Z_SYM, "s": S_SYM}
    # what everybody writes without declaring it: G(z), G^{-1}(z), H(z), C(z) are functions
    # (H and C bound to the scene's environment and controller), \Re and \operatorname{Re} real parts
    functions: dict[str, Any] = {"H": sp.Function("H"), "C": sp.Function("C"), "G": sp.Function("G"),
                                 "G^{-1}": sp.Function(sympy_name(normalise_name("G^{-1}")))}
    families: list[Any] = []
    words: dict[str, str] = {}
    definitions: list[tuple[str, str, str, int | None]] = []
    relations: list[tuple[str, str, str, int | None]] = []
    for key, value in raw.items():
        line = _table_line(text, key, "symbols")
        where = f"{_at(path, line)}: symbols: {key}"
        if not isinstance(value, str) or not value.strip():
            raise PaperFileError(f"{where}: expected a word ({', '.join(WORDS)}) or a definition in LaTeX, got {value!r}")
        printed = printed_key(key.strip())
        try:
            canonical = normalise_name(printed)
        except LatexParseError as err:
            raise PaperFileError(f"{where}: not a printed name ({err.reason})") from None
        name = sympy_name(canonical)
        if name in ("z", "s"):
            raise PaperFileError(f"{where}: z and s are the transform variables; they need no declaration")
        if _RELATION.search(value):
            if scenes:
                _refuse_toolkit_name(name, "relation", where)
            relations.append((printed, name, value, line))
            symbols[printed] = apart_symbol(name, real=True)
            continue
        parts = [w for w in re.split(r"[\s,]+", value.strip().lower()) if w]
        if re.fullmatch(r"[a-z]+(?:[\s,]+[a-z]+)*", value.strip()):
            unknown = [w for w in parts if w not in WORDS and w != "symmetric"]
            if unknown:
                close = difflib.get_close_matches(unknown[0], list(WORDS), n=1, cutoff=0.7)
                hint = f"; did you mean {close[0]!r}?" if close else f" (words: {', '.join(WORDS)}, or a LaTeX definition)"
                raise PaperFileError(f"{where}: unknown word {unknown[0]!r}{hint}")
            kinds = [w for w in parts if w != "symmetric"]
            if len(kinds) != 1:
                raise PaperFileError(f"{where}: give one word of {', '.join(WORDS)} (and 'symmetric' for a family)")
            word = kinds[0]
            if scenes:
                _refuse_toolkit_name(name, word, where)
            if _is_family(printed):
                if word in ("function", "signal"):
                    raise PaperFileError(f"{where}: an indexed family takes a sign assumption, not {word!r}")
                families.append(IndexedFamily(printed, symmetric="symmetric" in parts, assumptions=_assumption_kwargs(word)))
                words[name] = word
                continue
            if "symmetric" in parts:
                raise PaperFileError(f"{where}: 'symmetric' applies to an indexed family (a name with index i or j)")
            words[name] = word
            if word == "function":
                functions[printed] = sp.Function(name)
            elif word == "signal":
                symbol = sp.Symbol(name)
                symbols[printed] = symbol
                functions[printed] = (lambda sym: (lambda *args: sym))(symbol)
            else:
                symbols[printed] = apart_symbol(name, **_assumption_kwargs(word))
            continue
        definitions.append((printed, name, value, line))
    from hapticproof.core.symbols import n as N_SYM
    from hapticproof.core.symbols import omega as OMEGA

    # the toolkit's fixed names, unless declared: the frequency, the delay time t_d = n T, n
    for printed, symbol in (("\\omega", OMEGA), ("t_d", sp.Symbol("t_d", nonnegative=True)), ("n", N_SYM)):
        if normalise_name(printed) not in {normalise_name(k) for k in symbols}:
            symbols[printed] = symbol
    table = SymbolTable(symbols=symbols, functions=functions, families=families)
    region, lines = _read_relations(relations, table, words, path)
    if relations:
        table = table.with_symbols({printed: apart_symbol(name, **_assumption_kwargs(words[name]))
                                    for printed, name, _value, _line in relations})
        region, lines = _read_relations(relations, table, words, path)
    for printed, name, value, line in definitions:
        try:
            expr = _parse_value(value, table)
        except LimitError as err:
            raise PaperFileError(f"{_at(path, line)}: symbols: {printed}: {err}") from None
        except LatexParseError as err:
            raise PaperFileError(f"{_at(path, line)}: symbols: {printed}: the definition does not read: {err}") from None
        table = table.with_symbols({printed: expr})
        words[name] = "definition"
    return table, words, region, lines


#: The toolkit's own names a paper file may declare, with the one word that keeps their meaning.
_OWN_MEANING = {"n": "integer", "omega": "real"}


def _refuse_toolkit_name(name: str, word: str, where: str) -> None:
    """A ``[symbols]`` name that is one of the toolkit's own quantities (``n`` the delay, ``c`` =
    cos(omega T): :data:`hapticproof.core.symbols.TOOLKIT_NAMES`) is refused unless declared with
    that meaning (``n = "integer"``, ``omega = "real"``): it would silently mean both."""
    from hapticproof.core.expr import KEPT_APART
    from hapticproof.core.symbols import TOOLKIT_NAMES

    if name in TOOLKIT_NAMES and name not in KEPT_APART and _OWN_MEANING.get(name) != word:
        keep = f" (declare it {_OWN_MEANING[name]!r} for that meaning)" if name in _OWN_MEANING else ""
        raise PaperFileError(f"{where}: {name!r} is the toolkit's own name for {TOOLKIT_NAMES[name]}{keep}; "
                             f"give your quantity another name")


def _read_relations(relations: list[tuple[str, str, str, int | None]], table: Any, words: dict[str, str],
                    path: str) -> tuple[Any, dict[str, int | None]]:
    """The region of the ``[symbols]`` relations; each restricted name gets the sign the
    relation implies (``0 <= a < 1``: nonnegative), else ``real``."""
    from hapticproof.audit.regions import Region, RegionError, read_region

    from hapticproof.audit.reader.lexer import GREEK

    restrictions = []
    lines: dict[str, int | None] = {}
    greek = "|".join(sorted((g.lstrip("\\") for g in GREEK), key=len, reverse=True))
    for printed, name, value, line in relations:
        # Greek names by name, as the README writes them: "0 <= alpha < 1" is 0 <= \alpha < 1
        value = re.sub(r"(?<![\\A-Za-z])(" + greek + r")(?![A-Za-z])", r"\\\1", value)
        local = table
        for _ in range(8):
            try:
                region = read_region(value, local, key=name)
                break
            except RegionError as err:
                # a relation may name a scene's parameter ``[symbols]`` does not declare
                # (b_m >= b_s): it is read with that parameter's default sign
                unknown = re.search(r"unknown name (\S+)\)$", str(err))
                if unknown is None:
                    raise PaperFileError(f"{_at(path, line)}: symbols: {printed}: {err}") from None
                from hapticproof.audit.reader.names import sympy_name
                from hapticproof.core.errors import InputFormatError as _Bad
                from hapticproof.core.expr import parameter_symbol

                try:
                    symbol = parameter_symbol(sympy_name(unknown.group(1)))
                except (_Bad, LatexParseError):
                    raise PaperFileError(f"{_at(path, line)}: symbols: {printed}: {err}") from None
                local = local.with_symbols({unknown.group(1): symbol})
        else:
            raise PaperFileError(f"{_at(path, line)}: symbols: {printed}: too many undeclared names in {value!r}")
        (restriction,) = region.restrictions
        if restriction.is_equality():
            raise PaperFileError(f"{_at(path, line)}: symbols: {printed}: an equality is a definition: write the value "
                                 f"alone ({printed} = '...'), or make it an equation's assumption")
        words[name] = restriction.sign_word() or "real"
        restrictions.append(restriction)
        lines[name] = line
    try:
        return Region(tuple(restrictions)), lines
    except RegionError as err:
        raise PaperFileError(f"{path}: symbols: {err}") from None


def _parse_value(text: str, table: Any) -> sp.Expr:
    from hapticproof.audit.reader.printed import parse_printed

    statement = parse_printed(text, table)
    if statement.relations():
        raise LatexParseError("a definition is an expression, not a relation", text, 0)
    (expr,) = statement.expressions()
    return expr


# ---------------------------------------------------------------------------------------------
# scenes
# ---------------------------------------------------------------------------------------------


def _read_scenes(raw: Any, path: str, text: str, words: Mapping[str, str], region: Any = None,
                 region_lines: Mapping[str, int | None] | None = None) -> dict[str, Any]:
    from hapticproof.systems.scene import SceneFileError, scene_from_table

    if not isinstance(raw, Mapping):
        raise PaperFileError(f"{path}: [scenes] must hold tables [scenes.NAME]")
    base = Path(path).parent if path not in ("", "-", "<stdin>") else None
    scenes: dict[str, Any] = {}
    for name, table in raw.items():
        prefix = f"scenes.{name}"
        header = _header_line(text, prefix)
        where = f"{_at(path, header)}: scene {name!r}"
        if not isinstance(table, Mapping):
            raise PaperFileError(f"{where}: a scene is a table of fields ([scenes.{name}])")
        _check_declarations(table, name, path, text, prefix, words, region, region_lines or {})
        try:
            first = scene_from_table(table, where=path, base=base, text=text, prefix=prefix)
            used = first.names() | set(first.assumptions)
            if first.active:
                used.add("z_a")
            assumptions = {k: w for k, w in words.items()
                           if k in used and w in ("positive", "nonnegative", "real", "integer", "negative", "nonpositive")}
            scene = scene_from_table(table, where=path, base=base, assumptions=assumptions, text=text, prefix=prefix)
            scene.build()
        except SceneFileError as err:
            raise PaperFileError(f"{err} (scene {name!r})") from None
        except HapticproofError as err:
            named = re.search(r"parameter '([^']+)'", str(err))
            line = _table_line(text, named.group(1), f"{prefix}.params") if named else None
            raise PaperFileError(f"{_at(path, line or header)}: scene {name!r}: {err}") from None
        scenes[name] = scene
    return scenes


_SIGNS = ("positive", "nonnegative", "real", "integer", "negative", "nonpositive")


#: The signs each sign word allows: a scene may narrow a global sign (``real`` -> ``nonnegative``).
_SIGN_SETS = {"real": {"-", "0", "+"}, "nonnegative": {"0", "+"}, "positive": {"+"}, "nonpositive": {"-", "0"},
              "negative": {"-"}}


def _refines(word: str, declared: str) -> bool:
    """Whether a scene's sign word narrows the declared one (``nonnegative`` within ``real``,
    ``positive`` within ``nonnegative``), as an author refines an assumption for one system."""
    if declared == "real" and word == "integer":
        return True
    return word in _SIGN_SETS and declared in _SIGN_SETS and _SIGN_SETS[word] <= _SIGN_SETS[declared]


def _check_declarations(table: Mapping[str, Any], name: str, path: str, text: str, prefix: str,
                        words: Mapping[str, str], region: Any, region_lines: Mapping[str, int | None]) -> None:
    """A scene parameter must not contradict ``[symbols]``: another sign word (``B = "real"``
    in the scene, ``B = "nonnegative"`` in ``[symbols]``: is ``|B|`` then ``B``?) or a value
    outside the declared region is one error naming both lines."""
    params = table.get("params", {}) if isinstance(table, Mapping) else {}
    if not isinstance(params, Mapping):
        return
    for key, value in params.items():
        here = _at(path, _table_line(text, key, f"{prefix}.params"))
        declared = words.get(key)
        there = _at(path, region_lines.get(key) or _table_line(text, key, "symbols"))
        if isinstance(value, str) and value.strip() in _SIGNS and declared in _SIGNS and value.strip() != declared \
                and not _refines(value.strip(), declared):
            raise PaperFileError(f"{here}: scene {name!r}: params: {key} = {value.strip()!r} contradicts [symbols] "
                                 f"({there}: {key} is {declared!r}); declare it once, in [symbols] or in the scene")
        restriction = region.get(key) if region else None
        if restriction is None:
            continue
        if isinstance(value, str) and value.strip() in _SIGNS:
            if value.strip() != declared and not _refines(value.strip(), restriction.sign_word() or "real"):
                raise PaperFileError(f"{here}: scene {name!r}: params: {key} = {value.strip()!r} contradicts [symbols] "
                                     f"({there}: {restriction.text_form()}); declare it once")
            continue
        number = None
        if isinstance(value, (int, Decimal)) and not isinstance(value, bool):
            number = sp.Rational(str(value))
        elif isinstance(value, str):
            try:
                number = sp.Rational(value.strip())
            except (TypeError, ValueError):
                number = None
        if number is not None and restriction.contains(number) is False:
            raise PaperFileError(f"{here}: scene {name!r}: params: {key} = {value} lies outside [symbols] "
                                 f"({there}: {restriction.text_form()})")


def _header_line(text: str, table: str) -> int | None:
    from hapticproof.core.tomltext import toml_lines

    return toml_lines(text).header(table)


def _scene_table(paper: PaperFile, scene_name: str | None) -> Any:
    return bound_table(paper, paper.scenes.get(scene_name) if scene_name else None, scene_name)


def bound_table(paper: PaperFile, scene: Any, key: Any) -> Any:
    """The paper's symbol table with ``H`` (single-user) or ``C`` (teleoperator) bound to the
    scene's environment or controller (remembered under ``key``), unless the file declares the
    name as something other than a function.

    >>> paper = loads(TEMPLATE)
    >>> table = bound_table(paper, paper.scenes["wall"], "wall")
    >>> table.functions["H"](1)                     # H(1) = K for the wall
    K
    """
    if key in paper._tables:
        return paper._tables[key]
    table = with_scene_names(paper.symbols, scene)
    if scene is not None:
        from hapticproof.core.symbols import z as Z_SYM

        design = scene.environment_z() if scene.system in ("single-user", "teleoperator") else None
        if design is not None:
            mapping = _substitution(scene)
            design = sp.sympify(design).xreplace(mapping) if mapping else sp.sympify(design)
            bound = (lambda expr: (lambda arg: expr.xreplace({Z_SYM: arg})))(design)
            name = "H" if scene.system == "single-user" else "C"
            if paper.words.get(name) in (None, "function"):
                table = table.with_functions({name: bound})
    paper._tables[key] = table
    return table


def with_scene_names(table: Any, scene: Any) -> Any:
    """The table with the scene's parameters a display may name without declaring them
    (``[scenes.X.params] b_v = "positive"``: ``b_v`` in a display is that parameter, with the
    scene's assumption); names ``[symbols]`` declares keep their declaration."""
    if scene is None:
        return table
    from hapticproof.audit.reader.names import normalise_name

    known = set(table.symbols) | set(table.functions)
    extra = {}
    for name in sorted(scene.names()):
        try:
            printed = normalise_name(printed_key(name))
        except LatexParseError:
            continue
        if printed not in known and not _family_member(table, printed):
            extra[printed] = scene.symbol(name)
    table = table.with_symbols(extra) if extra else table
    if scene.system == "multi-user":
        from hapticproof.audit.reader.names import IndexedFamily, name_parts

        declared = {name_parts(pattern).base for pattern in table.families}
        # the dampings' and masses' families follow their roles (device_damping = "c": c_i)
        renamed = {"b": scene.role("device_damping"), "m": scene.role("mass")}
        patterns = [(pattern.replace(pattern.split("_")[0], renamed.get(pattern.split("_")[0]) or "", 1)
                     if pattern.split("_")[0] in renamed else pattern, symmetric, word)
                    for pattern, symmetric, word in _USER_FAMILIES]
        families = [IndexedFamily(pattern, symmetric=symmetric, assumptions=_assumption_kwargs(word))
                    for pattern, symmetric, word in patterns
                    if not pattern.startswith("_") and name_parts(pattern).base not in declared]
        table = table.with_families(*families) if families else table
    return table


#: The indexed names of an m-user scene a display may use without declaring them (``b_i``,
#: ``K_{0i}``, ``K_{ij}`` = ``K_{ji}``...), with the signs of :func:`hapticproof.systems.multiuser.user_symbols`.
_USER_FAMILIES = (("b_{i}", False, "positive"), ("K_{0i}", False, "positive"), ("B_{0i}", False, "nonnegative"),
                  ("K_{ij}", True, "positive"), ("B_{ij}", True, "nonnegative"), ("m_{i}", False, "positive"))


def _family_member(table: Any, printed: str) -> bool:
    """Whether a declared indexed family (``K_{ij}``) already reads the name."""
    from hapticproof.audit.reader.names import name_parts

    try:
        parts = name_parts(printed)
    except LatexParseError:
        return False
    return parts.sub is not None and any(name_parts(pattern).base == parts.base for pattern in table.families)


def _substitution(scene: Any) -> dict[sp.Symbol, Any]:
    """Symbol -> value of the scene's parameters with values (expressions resolved)."""
    return scene._substitution()


# ---------------------------------------------------------------------------------------------
# equations
# ---------------------------------------------------------------------------------------------


def _text_field(value: Any, where: str, key: str, *, allow_numbers: bool = False) -> str:
    if isinstance(value, str):
        return value
    if allow_numbers and isinstance(value, (int, Decimal)) and not isinstance(value, bool):
        return str(value)
    raise PaperFileError(f"{where}: field {key!r} must be text, got {value!r}")


def _substitutions(text: str, table: Any, where: str) -> tuple[tuple[sp.Symbol, sp.Expr], ...]:
    """``"z_a = 0, t_d = 0"`` as ((z_a, 0), (t_d, 0)), read with the file's symbols."""
    from hapticproof.audit.reader.printed import parse_printed

    out = []
    for part in [p for p in re.split(r",(?![^{(]*[})])", text) if p.strip()]:
        try:
            statement = parse_printed(part.strip(), table)
        except LatexParseError as err:
            raise PaperFileError(f"{where}: {err}") from None
        relations = statement.relations()
        if len(relations) != 1 or relations[0].ops != ("=",) or not isinstance(relations[0].lhs, sp.Symbol):
            raise PaperFileError(f"{where}: expected substitutions such as 'z_a = 0, t_d = 0', got {part.strip()!r}")
        out.append((relations[0].lhs, sp.sympify(relations[0].rhs)))
    if not out:
        raise PaperFileError(f"{where}: expected substitutions such as 'z_a = 0, t_d = 0'")
    return tuple(out)


def _check_other(other: str, ids: set[str], where: str) -> None:
    if ":" not in other:
        if other not in ids:
            raise PaperFileError(f"{where}: equation {other!r} does not exist in this file "
                                 f"(equations: {', '.join(sorted(ids)) or 'none'}; a bundled paper's as PAPER:ID)")
        return
    from hapticproof.core.errors import UnknownEquationError, UnknownPaperError
    from hapticproof.audit.registry import get_paper

    paper_id, eq_id = other.split(":", 1)
    try:
        paper = get_paper(paper_id)
    except UnknownPaperError as err:
        raise PaperFileError(f"{where}: {err}") from None
    try:
        paper.get(eq_id)
    except UnknownEquationError:
        ids = [eq.id for eq in paper.ordered()]
        shown = ", ".join(ids[:8]) + (", ..." if len(ids) > 8 else "")
        raise PaperFileError(f"{where}: paper {paper.id!r} has no equation {eq_id!r} (it has {len(ids)}: {shown})") from None


def _assumption(text: str, table: Any, where: str, region: Any) -> Any:
    """An equation's ``assumption``: a region (``"B = 0"``, ``'B \\leq \\frac{KT}{2}'``, ``"0 <= a < 1/2"``)
    that must not contradict the file's ``[symbols]``."""
    from hapticproof.audit.regions import RegionError, read_region

    try:
        stated = read_region(text, table)
        if region:
            region & stated                      # contradicts [symbols]? (RegionError)
    except RegionError as err:
        raise PaperFileError(f"{where}: {err}") from None
    return stated


def _definition_fields(entry: Mapping[str, Any], claim: str, fields: dict[str, Any], where: Any) -> None:
    """The fields of a definition, identity or condition claim (``about``, ``property``,
    ``strength`` for conditions; ``derived`` for definitions)."""
    for key in ("about", "property", "strength"):
        if key in entry:
            if claim != "condition":
                raise PaperFileError(f"{where(key)}: {key} applies to condition claims")
            fields[key] = _text_field(entry[key], where(key), key).strip()
    if fields.get("property") is not None and fields["property"] not in PROPERTIES:
        raise PaperFileError(f"{where('property')}: the property is one of {', '.join(PROPERTIES)}, got {fields['property']!r}")
    if fields.get("strength") is not None and fields["strength"] not in STRENGTHS:
        raise PaperFileError(f"{where('strength')}: the strength is one of {', '.join(STRENGTHS)}, got {fields['strength']!r}")
    if "derived" in entry:
        if claim != "definition" or not isinstance(entry["derived"], bool):
            raise PaperFileError(f"{where('derived')}: derived is true or false, on definition claims")
        fields["derived"] = entry["derived"]


def _read_equations(raw: Any, path: str, text: str, table: Any, scenes: Mapping[str, Any],
                    region: Any = None) -> tuple[ClaimSpec, ...]:
    from hapticproof.audit.reader.printed import parse_printed

    if not isinstance(raw, list):
        raise PaperFileError(f"{path}: equations must be an array of tables ([[equations]])")
    blocks = _blocks(text, "equations")
    specs: list[ClaimSpec] = []
    pending_other: list[tuple[str, str]] = []
    ids: set[str] = set()
    tables: dict[Any, Any] = {}

    def scene_table(name: Any) -> Any:
        """The symbol table with a scene's names, built once per scene (reading stays linear)."""
        key = name if isinstance(name, str) else None
        if key not in tables:
            tables[key] = with_scene_names(table, scenes.get(name) if isinstance(name, str) else None)
        return tables[key]

    for k, entry in enumerate(raw):
        block = blocks[k] if k < len(blocks) else None
        start = block[0] if block else None
        line = functools.partial(_line_in, text, block=block)
        if not isinstance(entry, Mapping):
            raise PaperFileError(f"{_at(path, start)}: equations[{k + 1}] must be a table")
        label = f"equation {entry.get('id', k + 1)}"
        for key in entry:
            if key not in EQUATION_FIELDS:
                close = difflib.get_close_matches(key, EQUATION_FIELDS, n=1)
                hint = f"; did you mean {close[0]!r}?" if close else f" (fields: {', '.join(EQUATION_FIELDS)})"
                raise PaperFileError(f"{_at(path, line(key))}: {label}: unknown field {key!r}{hint}")
        for key in ("id", "printed", "claim"):
            if key not in entry:
                raise PaperFileError(f"{_at(path, start)}: {label}: missing field {key!r}")

        def where(key: str) -> str:
            return f"{_at(path, line(key))}: {label}: field {key!r}"

        eq_id = _text_field(entry["id"], where("id"), "id", allow_numbers=True).strip()
        label = f"equation {eq_id}"
        if not eq_id:
            raise PaperFileError(f"{where('id')}: an id is needed")
        if not eq_id.isprintable():        # an id is shown in one-line messages, anchors and reports
            label = "equation"
            raise PaperFileError(f"{where('id')}: the id {eq_id!r} has a control character (use letters, digits, "
                                 "'-', '.', '_' and spaces)")
        if eq_id in ids:
            raise PaperFileError(f"{where('id')}: equation {eq_id!r} is listed twice")
        ids.add(eq_id)
        printed = _text_field(entry["printed"], where("printed"), "printed")
        if not printed.strip():
            raise PaperFileError(f"{where('printed')}: the printed display is empty")
        claim = _text_field(entry["claim"], where("claim"), "claim").strip()
        if claim not in CLAIMS:
            close = difflib.get_close_matches(claim, CLAIMS, n=1, cutoff=0.5)
            hint = f" (did you mean {close[0]!r}?)" if close else f" (claims: {', '.join(CLAIMS)})"
            raise PaperFileError(f"{where('claim')}: unknown claim {claim!r}{hint}")
        fields: dict[str, Any] = {"id": eq_id, "printed": printed, "claim": claim, "line": start}
        scene_name = entry.get("scene")
        if claim in DEFINITION_CLAIMS:
            _definition_fields(entry, claim, fields, where)
        elif any(key in entry for key in ("about", "property", "strength", "derived")):
            key = next(key for key in ("about", "property", "strength", "derived") if key in entry)
            raise PaperFileError(f"{where(key)}: {key} applies to definition, identity and condition claims")
        if scene_name is None and claim not in ("same-as",) + DEFINITION_CLAIMS:
            raise PaperFileError(f"{_at(path, start)}: {label}: missing field 'scene' (a {claim} claim is about a scene)")
        if scene_name is not None:
            scene_name = _text_field(scene_name, where("scene"), "scene").strip()
            if scene_name not in scenes:
                raise PaperFileError(f"{where('scene')}: scene {scene_name!r} does not exist "
                                     f"(scenes: {', '.join(scenes) or 'none'})")
            fields["scene"] = scene_name
        for key in ("section", "notes", "solve_for", "order", "form"):
            if key in entry:
                fields[key] = _text_field(entry[key], where(key), key, allow_numbers=key == "section").strip()
        if "order" in fields:
            if claim != "stability-condition":
                raise PaperFileError(f"{where('order')}: order applies to stability-condition claims")
            if fields["order"] not in ("exact", "leading"):
                raise PaperFileError(f"{where('order')}: order is 'exact' or 'leading', got {fields['order']!r}")
        if "form" in fields:
            if claim != "hermitian-part":
                raise PaperFileError(f"{where('form')}: form applies to hermitian-part claims")
            if fields["form"] not in ("expression", "condition"):
                raise PaperFileError(f"{where('form')}: form is 'expression' or 'condition', got {fields['form']!r}")
        if "solve_for" in fields and claim not in CONDITION_CLAIMS:
            raise PaperFileError(f"{where('solve_for')}: solve_for applies to condition claims")
        if "solve_for" in fields and fields.get("scene") in scenes:
            scene = scenes[fields["scene"]]
            names = scene.names() | set(dict(scene.params))
            if fields["solve_for"] not in names:
                close = difflib.get_close_matches(fields["solve_for"], sorted(names), n=1, cutoff=0.6)
                hint = f" (did you mean {close[0]!r}?)" if close else f" (its parameters: {', '.join(sorted(names))})"
                raise PaperFileError(f"{where('solve_for')}: {fields['solve_for']!r} is not a parameter of scene "
                                     f"{fields['scene']!r}{hint}")
        if claim == "same-as":
            if "other" not in entry:
                raise PaperFileError(f"{_at(path, start)}: {label}: a same-as claim needs the field 'other'")
            other = _text_field(entry["other"], where("other"), "other", allow_numbers=True).strip()
            fields["other"] = other
            if other == eq_id:
                raise PaperFileError(f"{where('other')}: equation {eq_id!r} is the same as itself (a same-as claim "
                                     "names another equation)")
            pending_other.append((other, where("other")))
            if "under" in entry:
                fields["under"] = _substitutions(_text_field(entry["under"], where("under"), "under"), table, where("under"))
        else:
            for key in ("other", "under"):
                if key in entry:
                    raise PaperFileError(f"{where(key)}: {key} applies to same-as claims")
        if "assumption" in entry and claim in ("condition", "identity"):
            fields["stated"] = _text_field(entry["assumption"], where("assumption"), "assumption").strip()
        elif "assumption" in entry:
            if claim not in CONDITION_CLAIMS:
                raise PaperFileError(f"{where('assumption')}: assumption applies to condition and identity claims")
            fields["assumption"] = _assumption(_text_field(entry["assumption"], where("assumption"), "assumption"),
                                               scene_table(fields.get("scene")), where("assumption"), region)
        # names: an unknown name is the file's mistake (declare it); other parse errors are the
        # paper's (the audit calls them malformed)
        check_table = scene_table(fields.get("scene"))
        try:
            parse_printed(printed, check_table)
        except LatexParseError as err:
            # a definitions claim is read with every name the paper uses (its own reader): only
            # the claims of scenes need each name declared
            if err.reason.startswith("unknown name") and claim not in DEFINITION_CLAIMS:
                raise PaperFileError(f"{where('printed')}: {err.reason} at position {err.position} "
                                     f"(declare it in [symbols])") from None
        except LimitError as err:      # work the display would ask for: refused with its place
            raise PaperFileError(f"{where('printed')}: {err}") from None
        specs.append(ClaimSpec(**fields))
    for other, where_text in pending_other:
        _check_other(other, ids, where_text)
    return tuple(specs)


# ---------------------------------------------------------------------------------------------
# reading
# ---------------------------------------------------------------------------------------------


def loads(text: str, path: str = "paper.toml") -> PaperFile:
    """A paper file from its text (``path`` names it in errors and resolves matrix files)."""
    from hapticproof.systems.scene import read_toml

    data = read_toml(text, path, PaperFileError)
    for key in data:
        if key not in ("paper", "symbols", "scenes", "equations"):
            close = difflib.get_close_matches(key, ["paper", "symbols", "scenes", "equations"], n=1)
            hint = f"; did you mean {close[0]!r}?" if close else ""
            raise PaperFileError(f"{_at(path, _header_line(text, key) or _table_line(text, key, ''))}: unknown table "
                                 f"{key!r} (tables: paper, symbols, scenes, equations){hint}")
    meta = data.get("paper")
    if not isinstance(meta, Mapping):
        raise PaperFileError(f"{path}: missing table [paper] (id, title)")
    for key in meta:
        if key not in PAPER_FIELDS:
            raise PaperFileError(f"{_at(path, _table_line(text, key, 'paper'))}: paper: unknown field {key!r} "
                                 f"(fields: {', '.join(PAPER_FIELDS)})")
    for key in ("id", "title"):
        if key not in meta:
            raise PaperFileError(f"{_at(path, _header_line(text, 'paper'))}: paper: missing field {key!r}")
    values = {}
    for key in PAPER_FIELDS:
        if key in meta:
            values[key] = _text_field(meta[key], f"{_at(path, _table_line(text, key, 'paper'))}: paper", key,
                                      allow_numbers=key == "id").strip()
    if not re.fullmatch(r"[A-Za-z0-9][A-Za-z0-9_.-]*", values["id"]):
        raise PaperFileError(f"{_at(path, _table_line(text, 'id', 'paper'))}: paper: field 'id': letters, digits, '-', '_' "
                             f"and '.' only, got {values['id']!r}")
    raw_symbols = data.get("symbols", {})
    if not isinstance(raw_symbols, Mapping):
        raise PaperFileError(f"{path}: [symbols] must be a table of names")
    table, words, region, region_lines = _read_symbols(raw_symbols, path, text, scenes=bool(data.get("scenes")))
    scenes = _read_scenes(data.get("scenes", {}), path, text, words, region, region_lines)
    claims = _read_equations(data.get("equations", []), path, text, table, scenes, region)
    if not claims:
        raise PaperFileError(f"{path}: no [[equations]] to audit")
    result = PaperFile(path=path, id=values["id"], title=values["title"], authors=values.get("authors", ""),
                       source=values.get("source", "") or path, symbols=table, words=words, scenes=scenes,
                       claims=claims, text=text, region=region)
    object.__setattr__(result, "paper", _register(result))
    return result


def read_paper(path: str | Path) -> PaperFile:
    """Read a paper file (``-``: standard input).

    >>> read_paper("no/such/paper.toml")
    Traceback (most recent call last):
    ...
    hapticproof.audit.paperfile.PaperFileError: cannot read no/such/paper.toml: No such file or directory
    """
    from hapticproof.core.files import FileAccessError, read_text

    try:
        text = read_text(path, "<stdin>" if str(path) == "-" else str(path))
    except FileAccessError as err:
        raise PaperFileError(str(err)) from None
    return loads(text, "<stdin>" if str(path) == "-" else str(path))


# ---------------------------------------------------------------------------------------------
# the registered paper
# ---------------------------------------------------------------------------------------------

_ASSUMPTION_TEXT = {"positive": "> 0", "nonnegative": ">= 0", "negative": "< 0", "nonpositive": "<= 0",
                    "real": "real", "integer": "integer"}


def _assumptions_text(words: Mapping[str, str]) -> str:
    groups: dict[str, list[str]] = {}
    for name, word in words.items():
        if word in _ASSUMPTION_TEXT:
            groups.setdefault(word, []).append(name)
    return "; ".join(f"{', '.join(names)} {_ASSUMPTION_TEXT[word]}" for word, names in groups.items())


def _kind(spec: ClaimSpec, table: Any) -> str:
    if spec.claim in CONDITION_CLAIMS or spec.claim == "condition":
        return "condition"
    if spec.claim in ("definition", "identity"):
        return "expression"
    if spec.claim in ("inverse-transfer", "residue"):
        return "expression"
    if spec.claim == "hermitian-part" and spec.form != "auto":
        return spec.form
    from hapticproof.audit.reader.printed import parse_printed

    try:
        statement = parse_printed(spec.printed, table)
    except LatexParseError:
        return "expression"
    rel = statement.relations()
    return "condition" if rel and any(op != "=" for r in rel for op in r.ops) else "expression"


def _derivation(spec: ClaimSpec, paper: PaperFile) -> str:
    from hapticproof.audit.claims import describe

    return describe(spec, paper)


def register_claims(source: PaperFile, onto: Paper) -> Paper:
    """Register the claims of a read paper file onto a paper (``onto``), each checked as the
    file says: how a paper file's claims are audited, and how a bundled paper takes the routine
    claims kept in a paper file beside its derivation modules (``derivations/hve/routine.toml``).
    An id ``onto`` already has is refused."""
    from hapticproof.audit.claims import check

    assumptions = _assumptions_text(source.words)
    for spec in source.claims:
        onto.equation(spec.id, kind=_kind(spec, source.symbols), printed=spec.printed, section=spec.section,
                      assumptions=assumptions, derivation=_derivation(spec, source), parse=True)(
            functools.partial(check, spec=spec, source=source))
    return onto


def file_naming(paper: PaperFile) -> Any:
    """A paper file's naming (:class:`~hapticproof.core.naming.Naming`): the toolkit's helpers
    under names that none of its symbols and scene parameters can be confused with, and the
    roles its scenes agree on (the period ``h`` of every scene: ``\\cos(\\omega h)``)."""
    from hapticproof.core.naming import Naming
    from hapticproof.systems.naming import scene_names, scene_roles

    table = getattr(paper.symbols, "symbols", None) or {}
    extra: set[str] = set()
    roles: dict[str, set] = {}
    for scene in paper.scenes.values():
        try:
            extra |= scene_names(scene)
        except HapticproofError:      # a scene the audit reports on as malformed: its declared names are enough
            extra |= set(dict(scene.params))
        for field_, default, name in scene_roles(scene):
            roles.setdefault(field_, set()).add((default, name))
    if "period" not in roles:                 # no scene says: the period the displays multiply the frequency by
        periods = {_period_name(m.group(1)) for spec in paper.claims
                   for m in _FREQUENCY_TIMES.finditer(spec.printed or "")}
        periods.discard(None)
        if len(periods) == 1:
            roles["period"] = {("T", periods.pop())}
    agreed = tuple((f, *next(iter(v))) for f, v in roles.items() if len(v) == 1)
    return Naming.of_symbols((v for v in table.values() if isinstance(v, sp.Symbol)), agreed, extra)


#: ``\omega h`` in ``e^{j\omega h}``, ``\cos\omega h``, ``\cos(\omega T_s)``: the name after the frequency
_FREQUENCY_TIMES = re.compile(r"\\omega\s*(?:\\,|\\;|\s)*([A-Za-z](?:_\{?[A-Za-z0-9]+\}?)?)")


def _period_name(printed: str) -> str | None:
    """The text name of a period printed after ``\\omega`` (``T_{s}`` -> ``T_s``), ``None`` for a
    letter that is no name of a period (``j``, a transform variable).

    >>> _period_name("T_{s}"), _period_name("h"), _period_name("j")
    ('T_s', 'h', None)
    """
    name = printed.replace("{", "").replace("}", "")
    return None if name in ("j", "i", "z", "s", "t") else name


def _register(paper: PaperFile) -> FilePaper:
    return register_claims(paper, FilePaper(paper.id, title=paper.title, source=paper.source, authors=paper.authors,
                                            symbols=paper.symbols, notation=paper.naming()))


# ---------------------------------------------------------------------------------------------
# the template of ``hapticproof new-paper``
# ---------------------------------------------------------------------------------------------

TEMPLATE = r"""# A paper file: the printed displays of a paper and what each claims.
# Audit it with:   hapticproof audit --paper THIS_FILE.toml
# Each display gets a verdict with evidence: confirmed, conservative, typo, wrong,
# needs-assumption, inconsistent, malformed or undecided.

[paper]
id = "my-paper"                     # short id: used in reports and by same-as (my-paper:3)
title = "A virtual wall, audited"
authors = "A. Author and B. Author"
source = "where it was published"

[symbols]                           # every name the printed LaTeX uses, with its assumption
b = "positive"                      # positive | nonnegative | real | integer
K = "positive"
B = "nonnegative"
T = "positive"
omega = "real"                      # Greek letters by name: \omega
F_h = "signal"                      # F_h(z) = G^{-1}(z) V_h(z): signals around G^{-1}
V_h = "signal"
"G^{-1}" = "function"               # a name applied to (z), compared with nothing
# j is the imaginary unit, e^{...} the exponential, z and s the transform variables;
# H(...) in a display is the scene's environment H(z).

[scenes.wall]                       # the same fields as a scene file (hapticproof derive --scene)
system = "single-user"              # single-user | multi-user | teleoperator | network
approximation = "forward"           # X_h = T/(z-1) V_h (forward difference)
environment = "K + B*(z - 1)/(T*z)" # H(z), the virtual wall
delay = 0                           # n = t_d/T; "n" keeps it symbolic

[[equations]]
id = "1"
printed = 'F_h(z) = bV_h(z) + \left(K + \frac{B(z-1)}{Tz}\right)\frac{T}{z-1}V_h(z) = G^{-1}(z)V_h(z)'
claim = "inverse-transfer"          # the display is G^-1(z) of the scene
scene = "wall"
section = "2"

[[equations]]
id = "2"
printed = 'b > \frac{KT}{2} - B\cos(\omega T)'
claim = "hermitian-part"            # Re G^-1(e^{j omega T}) >= 0, at each frequency
scene = "wall"
section = "2"

[[equations]]
id = "3"
printed = 'b > \frac{KT}{2} + B'
claim = "passivity-condition"       # necessary and sufficient for G^-1 positive real
scene = "wall"
section = "2"

# More claims: residue, sufficient-condition, necessary-condition,
# stability-condition (order = "exact" or "leading"; the scene names the device mass m),
# same-as (other = "3" or "hve:20", under = "z_a = 0, t_d = 0").
"""
