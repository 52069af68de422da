"""Names in printed LaTeX and the symbol table that gives them meaning: a name's parts (base,
primes, scripts), its canonical form and SymPy symbol, indexed families (``K_{ij}``), functions
and definitions. The reader is driven by the table: an unknown name is an error, never a guess."""

from __future__ import annotations

import functools
import re
from collections.abc import Callable, Iterable, Iterator, Mapping
from dataclasses import dataclass, field, replace
from typing import Any

import sympy as sp

from hapticproof.core.errors import LatexParseError
from hapticproof.core.expr import apart_symbol
from hapticproof.audit.reader.lexer import DECORATIONS, GREEK, Token, closer_key, describe_token, matching_close, opener_key, tokenize
from hapticproof.audit.reader.lexer import ARROWS, ELLIPSES, FRACTIONS, MULTIPLY, OPERATOR_COMMANDS, RELATIONS, UNSUPPORTED_RELATIONS

__all__ = ["DEFAULT_CONSTANTS", "SymbolTable", "IndexedFamily", "normalise_name", "symbol_for", "index_symbol"]


#: Upright-text commands that only typeset a script's letters (``K_{\mathrm{w}}`` is ``K_w``).
_UPRIGHT = ("\\mathrm", "\\text", "\\textrm", "\\mathit", "\\textit", "\\rm", "\\textnormal")


def canonical_name(toks: Iterable[Token], script: bool = False) -> str:
    r"""Canonical source text of a token run (whitespace dropped where it is not needed); in a
    ``script``, upright text is its letters (``K_{\mathrm{w}}`` and ``K_w`` are one name)."""
    out = ""
    for t in toks:
        if t.kind == "text" and script and t.value in _UPRIGHT and re.fullmatch(r"[A-Za-z0-9]+", t.arg.strip()):
            piece = t.arg.strip()
        elif t.kind == "text":
            piece = f"{t.value}{{{t.arg.strip()}}}"
        elif t.kind in ("begin", "end", "left", "right"):
            piece = describe_token(t)
        else:
            piece = t.value
        if re.search(r"\\[A-Za-z]+$", out) and piece[:1].isalpha():
            out += " "  # keep '\ell j' from becoming '\ellj'
        out += piece
    return out


@dataclass(frozen=True, slots=True)
class NameParts:
    """A printed name split into canonical base, primes and script token runs."""

    base: str
    primes: int
    sub: tuple[Token, ...] | None
    sup: tuple[Token, ...] | None

    @property
    def canonical(self) -> str:
        return compose_name(self.base, self.primes, self.sub, self.sup)


def compose_name(base: str, primes: int, sub: Iterable[Token] | None, sup: Iterable[Token] | None) -> str:
    name = base + "'" * primes
    if sub is not None:
        name += "_{" + canonical_name(sub, script=True) + "}"
    if sup is not None:
        name += "^{" + canonical_name(sup, script=True) + "}"
    return name


def name_parts(printed: str) -> NameParts:
    """Parse a table key such as ``K_01``, ``\\mathbf Z_{11}`` or ``G^{-1}`` into parts.

    Keys are read leniently: an unbraced script extends to the next script (``K_01`` is
    ``K_{01}``), which is what a person typing a table means. Each key is parsed once per digit
    limit (every symbol table of a long paper holds its names again).
    """
    from hapticproof.core.limits import current

    return _parts(printed, current().digits)


@functools.lru_cache(maxsize=65536)
def _parts(printed: str, digits: int) -> NameParts:
    toks = tokenize(printed)
    if not toks:
        raise LatexParseError("empty name", printed, 0)
    match = matching_close(printed, toks)
    base, k = read_name_base(printed, toks, 0, match)
    primes, sub, sup = 0, None, None
    while k < len(toks):
        t = toks[k]
        if t.kind == "op" and t.value == "'":
            primes, k = primes + 1, k + 1
            continue
        if t.kind == "op" and t.value in "_^":
            k += 1
            if k >= len(toks):
                raise LatexParseError(f"missing script after '{t.value}'", printed, t.pos)
            if toks[k].kind == "op" and toks[k].value == "{":
                close = match[k]
                run, k = tuple(toks[k + 1 : close]), close + 1
            else:
                j = k
                while j < len(toks) and not (toks[j].kind == "op" and toks[j].value in "_^'"):
                    j += 1
                run, k = tuple(toks[k:j]), j
            if (t.value == "_" and sub is not None) or (t.value == "^" and sup is not None):
                raise LatexParseError(f"double '{t.value}' script", printed, t.pos)
            if not run:
                raise LatexParseError(f"empty script after '{t.value}'", printed, t.pos)
            if t.value == "_":
                sub = run
            elif canonical_name(run) == "\\prime":
                primes += 1
            else:
                sup = run
            continue
        raise LatexParseError(f"unexpected '{t.value}' in a name", printed, t.pos)
    return NameParts(base, primes, sub, sup)


def read_name_base(text: str, toks: list[Token], k: int, match: Mapping[int, int]) -> tuple[str, int]:
    """Canonical base of the name at ``toks[k]`` and the index after it (``match`` pairs braces)."""
    t = toks[k]
    if t.kind == "letter":
        j = k + 1
        while j < len(toks) and toks[j].kind == "letter" and not toks[j].space:
            j += 1
        return "".join(x.value for x in toks[k:j]), j
    if t.kind == "number" and k > 0 and toks[k - 1].kind == "op" and toks[k - 1].value == "{":
        return t.value, k + 1  # \mathbf{0}
    if t.kind == "cmd" and t.value in GREEK:
        return t.value, k + 1
    if t.kind == "text" and t.value in ("\\mathrm", "\\operatorname") and t.arg.strip().isalpha():
        return f"{t.value}{{{t.arg.strip()}}}", k + 1
    if t.kind == "cmd" and t.value in DECORATIONS:
        if k + 1 >= len(toks):
            raise LatexParseError(f"{t.value} needs an argument", text, t.pos)
        nxt = toks[k + 1]
        if nxt.kind == "op" and nxt.value == "{":
            first, stop = k + 2, match[k + 1]
            after = stop + 1
        else:
            first, stop = k + 1, k + 2
            after = stop
        if first >= stop:
            raise LatexParseError(f"empty {t.value}{{}}", text, t.pos)
        base, end = read_name_base(text, toks, first, match)
        if end != stop:
            raise LatexParseError(f"{t.value}{{...}} must hold one name", text, t.pos)
        return f"{t.value}{{{base}}}", after
    raise LatexParseError(f"a name cannot start with '{t.value}'", text, t.pos)


def normalise_name(printed: str) -> str:
    r"""The canonical spelling of a printed name, used for every table lookup.

    Scripts are always braced and ordered ``base'_{sub}^{sup}``; decorations are braced;
    spaces inside scripts are dropped.  Keys are read leniently (``K_01`` means ``K_{01}``), but
    inside a display LaTeX's own grouping rules apply.

    >>> normalise_name('K_01') == normalise_name('K_{01}') == 'K_{01}'
    True
    >>> normalise_name('t_d'), normalise_name(r'\mathbf Z_{11}'), normalise_name('G^{-1}_1')
    ('t_{d}', '\\mathbf{Z}_{11}', 'G_{1}^{-1}')
    """
    return name_parts(printed).canonical


@functools.lru_cache(maxsize=65536)
def sympy_name(canonical: str) -> str:
    """Conventional SymPy name for a canonical printed name (``K_{01}`` -> ``K_01``)."""
    if any(d in canonical for d in DECORATIONS) or "\\mathrm" in canonical:
        return canonical  # decorations are part of the identity: keep the LaTeX spelling
    return re.sub(r"[{}\\]", "", canonical).replace(" ", "")


def symbol_for(printed: str, **assumptions: bool) -> sp.Symbol:
    r"""A SymPy symbol for a printed name, named by the project's convention.

    >>> symbol_for('K_{01}', positive=True), symbol_for(r'\omega_s'), symbol_for(r'\mathbf{Z}_x')
    (K_01, omega_s, \mathbf{Z}_{x})
    """
    return apart_symbol(sympy_name(normalise_name(printed)), **assumptions)


def index_symbol(name: str) -> sp.Symbol:
    r"""The integer symbol that stands for a printed index letter (``i``, ``j``, ``\ell``).

    >>> index_symbol('i'), index_symbol('i').is_integer
    (i, True)
    """
    return sp.Symbol(name.lstrip("\\"), integer=True)


class FrozenMap(Mapping):
    """A read-only, hashable mapping (keeps the frozen table hashable)."""

    __slots__ = ("_data", "_hash")

    def __init__(self, data: Mapping[str, Any] | Iterable[tuple[str, Any]] = ()) -> None:
        self._data = dict(data)
        self._hash: int | None = None

    def __getitem__(self, key: str) -> Any:
        return self._data[key]

    def __iter__(self) -> Iterator[str]:
        return iter(self._data)

    def __len__(self) -> int:
        return len(self._data)

    def __hash__(self) -> int:
        if self._hash is None:
            self._hash = hash(frozenset(self._data.items()))
        return self._hash

    def __repr__(self) -> str:
        return repr(self._data)


@dataclass(frozen=True, slots=True)
class IndexedFamily:
    r"""A family of printed names indexed by users, such as ``K_{0i}``, ``K_{ij}`` or ``z_{i,j}``.

    Parameters
    ----------
    pattern : str
        The printed member with index letters (the table's ``indices``) as placeholders:
        ``'b_{i}'``, ``'K_{0i}'``, ``'z_{ai}'``.  With commas (``'z_{i,j}'``) each slot may be
        printed as an index expression (``z_{3i-2,3j}``).
    symmetric : bool
        Whether the member does not depend on the order of its indices (``K_{ij} = K_{ji}``).
    function : bool
        Whether members are functions, applied as ``X_{hj}(z)``.
    assumptions : Mapping[str, bool]
        Assumptions of concrete members the table does not list (they are created on demand).

    >>> IndexedFamily('K_{ij}', symmetric=True).pattern
    'K_{ij}'
    """

    pattern: str
    symmetric: bool = False
    function: bool = False
    assumptions: Mapping[str, bool] = field(default_factory=dict)

    def __post_init__(self) -> None:
        parts = name_parts(self.pattern)
        if parts.sub is None or parts.sup is not None:
            raise ValueError(f"a family pattern needs a subscript and no superscript: {self.pattern!r}")
        object.__setattr__(self, "pattern", parts.canonical)
        object.__setattr__(self, "assumptions", FrozenMap(self.assumptions))


@dataclass(frozen=True, slots=True)
class FamilySpec:
    """A family compiled against the table's index letters."""

    family: IndexedFamily
    base: str
    comma: bool
    slots: tuple[str | None, ...]  # literal canonical text, or None for an index placeholder


def subscript_slots(toks: Iterable[Token]) -> list[tuple[str, Token]]:
    """Split a subscript into one-character slots (``01`` gives two slots)."""
    slots = []
    for t in toks:
        if t.kind == "number":
            slots.extend((ch, t) for ch in t.value)
        else:
            slots.append((canonical_name([t]), t))
    return slots


def split_commas(toks: list[Token]) -> list[list[Token]]:
    parts: list[list[Token]] = [[]]
    depth = 0
    for t in toks:
        if opener_key(t) is not None:
            depth += 1
        elif closer_key(t) is not None:
            depth -= 1
        if depth == 0 and t.kind == "op" and t.value == ",":
            parts.append([])
        else:
            parts[-1].append(t)
    return parts


DEFAULT_CONSTANTS: Mapping[str, Any] = FrozenMap({"j": sp.I, "e": sp.E, "\\pi": sp.pi})


@dataclass(frozen=True, slots=True)
class SymbolTable:
    r"""What the printed names of one paper mean.

    Parameters
    ----------
    symbols : Mapping[str, sympy.Basic]
        Printed name -> SymPy object (a symbol, an expression such as the paper's ``S``, a
        matrix or a ``MatrixSymbol``).  Keys are normalised (:func:`normalise_name`); plain
        multi-letter keys (``'KT'``) are matched in letter runs, longest first.
    functions : Mapping[str, Callable]
        Names applied with parentheses or braces: ``{'H': lambda z: ..., 'G^{-1}': ...}``.
    families : Mapping[str, IndexedFamily] or Iterable[IndexedFamily]
        Indexed families for ``\min_i``, ``\max_{i,j}`` and ``\sum`` bodies, keyed by pattern.
    constants : Mapping[str, sympy.Basic]
        Names used when neither ``symbols`` nor a bound index claims them: by default ``j`` is
        the imaginary unit, ``e`` Euler's number (``e^{x}`` is ``exp(x)``) and ``\pi`` is pi.
    indices : tuple of str
        Letters that are indices in subscripts, ranges, conditions and operator subscripts.
    superscripts : Mapping[str, Callable]
        Meanings of superscripts that are not powers, for the whole paper, e.g.
        ``{'c': sympy.conjugate}`` (teleoperator paper: "the superscript c denotes the complex
        conjugate").  A name registered with its superscript (``V_m^c``) still wins.

    >>> K, T = sp.symbols('K T', positive=True)
    >>> table = SymbolTable({'K': K, 'T': T}).with_symbols({'K_01': sp.Symbol('K_01')})
    >>> table.lookup('K_{01}'), 'K_{ 01 }' in table
    (K_01, True)
    """

    symbols: Mapping[str, Any] = field(default_factory=dict)
    functions: Mapping[str, Callable[..., Any]] = field(default_factory=dict)
    families: Mapping[str, IndexedFamily] | Iterable[IndexedFamily] = ()
    constants: Mapping[str, Any] = DEFAULT_CONSTANTS
    indices: tuple[str, ...] = ("i", "j", "k", "\\ell")
    superscripts: Mapping[str, Callable[[Any], Any]] = FrozenMap()
    _specs: Mapping[str, FamilySpec] = field(init=False, repr=False, compare=False)
    _words: frozenset[str] = field(init=False, repr=False, compare=False)

    def __post_init__(self) -> None:
        set_ = object.__setattr__
        set_(self, "symbols", normalised(self.symbols, "symbol", as_sympy))
        set_(self, "functions", normalised(self.functions, "function", as_callable))
        set_(self, "constants", normalised(self.constants, "constant", as_sympy))
        set_(self, "indices", tuple(normalise_name(i) for i in self.indices))
        set_(self, "superscripts", FrozenMap({canonical_name(tokenize(k)): as_callable(v) for k, v in dict(self.superscripts).items()}))
        families = self.families.values() if isinstance(self.families, Mapping) else self.families
        families = [f if isinstance(f, IndexedFamily) else IndexedFamily(f) for f in families]
        set_(self, "families", FrozenMap({f.pattern: f for f in families}))
        set_(self, "_specs", FrozenMap({f.pattern: self._compile(f) for f in families}))
        words = set()
        for key in (*self.symbols, *self.functions):
            parts = name_parts(key)
            if len(parts.base) > 1 and parts.base.isalpha():
                if parts.sub is not None or parts.sup is not None or parts.primes:
                    raise ValueError(
                        f"{key!r}: a multi-letter name cannot carry scripts (LaTeX attaches them "
                        "to the last letter)"
                    )
                words.add(parts.base)
        set_(self, "_words", frozenset(words))

    def _compile(self, family: IndexedFamily) -> FamilySpec:
        parts = name_parts(family.pattern)
        sub = list(parts.sub or ())
        pieces = split_commas(sub)
        if len(pieces) > 1:
            slots = tuple(None if canonical_name(p) in self.indices else canonical_name(p) for p in pieces)
            comma = True
        else:
            slots = tuple(None if c in self.indices else c for c, _ in subscript_slots(sub))
            comma = False
        if None not in slots:
            raise ValueError(f"family {family.pattern!r} has no index letter from {self.indices}")
        base = parts.base + "'" * parts.primes
        return FamilySpec(family, base, comma, slots)

    # -- lookups --------------------------------------------------------------------------------
    def __contains__(self, name: object) -> bool:
        return isinstance(name, str) and normalise_name(name) in self.symbols

    def lookup(self, name: str) -> Any:
        """The symbol of a printed name (any spelling), or ``None``."""
        return self.symbols.get(normalise_name(name))

    def concrete(self, pattern: str, values: Iterable[int]) -> Any:
        """The concrete member of a family for integer index values (creates missing ones).

        >>> t = SymbolTable(families=[IndexedFamily('K_{ij}', symmetric=True)])
        >>> t.concrete('K_{ij}', (2, 1))
        K_12
        """
        spec = self._specs[normalise_name(pattern)]
        values = [int(v) for v in values]
        if spec.family.symmetric:
            values = sorted(values)
        it = iter(values)
        filled = [str(next(it)) if s is None else s for s in spec.slots]
        if not spec.comma and any(len(v) > 1 for v, s in zip(filled, spec.slots) if s is None):
            raise ValueError(f"index values above 9 cannot be written in {spec.family.pattern!r}")
        name = normalise_name(f"{spec.base}_{{{(',' if spec.comma else '').join(filled)}}}")
        if spec.family.function:
            found = self.functions.get(name)
            return found if found is not None else sp.Function(sympy_name(name))
        found = self.symbols.get(name)
        return found if found is not None else sp.Symbol(sympy_name(name), **spec.family.assumptions)

    # -- derived tables -------------------------------------------------------------------------
    def with_symbols(self, mapping: Mapping[str, Any] | None = None, /, **more: Any) -> SymbolTable:
        """A copy with more (or overriding) symbols; keyword names must be plain identifiers."""
        return replace(self, symbols={**self.symbols, **renormalised(mapping, more)})

    def with_functions(
        self, mapping: Mapping[str, Callable[..., Any]] | None = None, /, **more: Callable[..., Any]
    ) -> SymbolTable:
        """A copy with more (or overriding) functions."""
        return replace(self, functions={**self.functions, **renormalised(mapping, more)})

    def with_families(self, *families: IndexedFamily) -> SymbolTable:
        """A copy with more families."""
        return replace(self, families=[*self.families.values(), *families])

    def with_constants(self, mapping: Mapping[str, Any] | None = None, /, **more: Any) -> SymbolTable:
        """A copy with constants changed; a value of ``None`` removes the constant.

        >>> SymbolTable().with_constants(j=None).constants.get('j') is None
        True
        """
        merged = {**self.constants, **renormalised(mapping, more)}
        return replace(self, constants={k: v for k, v in merged.items() if v is not None})

    @classmethod
    def from_names(cls, names: Iterable[str], **assumptions: bool) -> SymbolTable:
        """A table of fresh symbols (see :func:`symbol_for`) for the given printed names.

        >>> SymbolTable.from_names(['K_{01}', r'\\omega'], positive=True).lookup('K_01')
        K_01
        """
        return cls({name: symbol_for(name, **assumptions) for name in names})


def as_sympy(value: Any) -> Any:
    if isinstance(value, sp.MatrixBase):
        return sp.ImmutableMatrix(value)
    return sp.sympify(value, strict=True)


def as_callable(value: Any) -> Any:
    if not callable(value):
        raise TypeError(f"{value!r} is not callable")
    return value


def normalised(mapping: Mapping[str, Any], what: str, convert: Callable[[Any], Any]) -> FrozenMap:
    out: dict[str, Any] = {}
    for key, value in dict(mapping).items():
        try:
            canonical = normalise_name(key)
        except LatexParseError as err:
            raise ValueError(f"invalid {what} name {key!r}: {err}") from None
        if canonical in out:
            raise ValueError(f"{what} names {key!r} and another key both normalise to {canonical!r}")
        out[canonical] = convert(value)
    return FrozenMap(out)


def renormalised(mapping: Mapping[str, Any] | None, more: Mapping[str, Any]) -> dict[str, Any]:
    return {normalise_name(k): v for k, v in {**(mapping or {}), **more}.items()}


@dataclass(frozen=True, slots=True)
class Script:
    """A ``_``/``^`` script: the token range of its content and its canonical text."""

    start: int
    stop: int
    toks: tuple[Token, ...]
    op: Token

    @property
    def canon(self) -> str:
        return canonical_name(self.toks)


ELEMENTARY: dict[str, Callable[[Any], Any]] = {
    "\\cos": sp.cos,
    "\\sin": sp.sin,
    "\\tan": sp.tan,
    "\\cot": sp.cot,
    "\\sec": sp.sec,
    "\\csc": sp.csc,
    "\\cosh": sp.cosh,
    "\\sinh": sp.sinh,
    "\\tanh": sp.tanh,
    "\\arccos": sp.acos,
    "\\arcsin": sp.asin,
    "\\arctan": sp.atan,
    "\\exp": sp.exp,
    "\\ln": sp.log,
    "\\log": sp.log,
}


PARTS: dict[str, Callable[[Any], Any]] = {"\\Re": sp.re, "\\Im": sp.im, "Re": sp.re, "Im": sp.im}


def is_known_command(name: str) -> bool:
    return any(
        name in group
        for group in (
            GREEK, DECORATIONS, ELEMENTARY, PARTS, FRACTIONS, OPERATOR_COMMANDS, RELATIONS,
            UNSUPPORTED_RELATIONS, ARROWS, ELLIPSES, MULTIPLY, ("\\pm", "\\mp"),
        )
    )
