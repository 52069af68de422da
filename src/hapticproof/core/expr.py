r"""The one reader of user expressions: rational expressions in ``z`` or ``s`` and named parameters.

Every expression a user types -- ``--environment``, ``--controller``, ``--operator``, a matrix
entry of a network file, a scene file's fields, a parameter given as an expression of others --
is read here, by a small grammar of its own (no ``sympify``, no ``eval``, no implicit
multiplication):

.. code-block:: text

    expr   := term (('+' | '-') term)*
    term   := unary (('*' | '/') unary)*
    unary  := ('+' | '-') unary | power
    power  := atom (('^' | '**') unary)?        (the exponent must be an integer constant)
    atom   := NUMBER | NAME | '(' expr ')'

* Numbers are exact from the first moment: ``0.9`` is ``9/10``, ``1e-3`` is ``1/1000``; no
  float ever enters an expression (``0.5*K`` stays ``K/2``).
* Names are the user's own (``M``, ``a``, ``K_i``, ``B_0``...), letters, digits and ``_``; they
  become SymPy symbols with the assumptions of :func:`parameter_symbol` (the papers' physical
  signs for ``b, T, K, B, z_a, m``..., ``real`` for any other name) unless the caller passes
  its own symbols.
* ``z`` (discrete time) and ``s`` (continuous time) are the transform variables: an expression
  of one domain that uses the other variable is an error, as is a name followed by ``(`` (there
  are no functions in a rational expression) or two operands side by side (``2s``).
* ``nan``, ``inf``, ``infinity``, ``oo`` and ``zoo`` are not numbers and ``pi`` is not a
  rational one (:data:`NOT_NAMES`): each is an error, never a symbol. An exact decision needs
  rational coefficients, so ``pi`` is refused rather than kept exactly; write the rational you
  mean (``355/113``, ``3.14159265358979``).

Every mistake is one :class:`ExpressionError` line that names where the text came from and
the position.

>>> read_expression("K + B*(1 - 0.9)*(z - 1)/(T*(z - 0.9))", "z")
B*(z - 1)/(10*T*(z - 9/10)) + K
>>> read_expression("0.5*K + B*s", "s")
B*s + K/2
>>> read_expression("sin(s)", "s", where="matrix.txt:1, entry 1")
Traceback (most recent call last):
...
hapticproof.core.expr.ExpressionError: matrix.txt:1, entry 1: unknown function 'sin' at position 0 in 'sin(s)' (a rational expression has numbers, names, + - * / ^ and parentheses)
"""

from __future__ import annotations

import re
from collections.abc import Callable, Mapping
from dataclasses import dataclass
from fractions import Fraction

import sympy as sp

from hapticproof.core.errors import InputFormatError
from hapticproof.core.symbols import c as C_SYM
from hapticproof.core.symbols import cos_n as COS_N
from hapticproof.core.symbols import s as S_SYM
from hapticproof.core.symbols import sin_n as SIN_N
from hapticproof.core.symbols import sin_theta as SIN_THETA
from hapticproof.core.symbols import x as X_SYM
from hapticproof.core.symbols import z as Z_SYM

__all__ = [
    "ExpressionError",
    "ASSUMPTIONS",
    "KEPT_APART",
    "DEFAULT_ASSUMPTIONS",
    "parameter_symbol",
    "apart_symbol",
    "read_expression",
    "read_number",
    "normalise_variables",
    "write_expression",
    "NOT_NAMES",
    "not_a_name",
    "check_rational",
]

#: Assumption words a user may give a parameter (scene files, ``--param NAME=positive``).
ASSUMPTIONS: dict[str, dict[str, bool]] = {
    "positive": {"positive": True},
    "nonnegative": {"nonnegative": True},
    "negative": {"negative": True},
    "nonpositive": {"nonpositive": True},
    "real": {"real": True},
    "integer": {"integer": True},
}

#: Physical signs of the papers' names (dampings, stiffnesses, masses and the sampling period
#: are positive; virtual damping, shortage of passivity and delays non-negative). Any other
#: name is ``real`` unless its scene says otherwise.
DEFAULT_ASSUMPTIONS: dict[str, str] = {
    "b": "positive", "T": "positive", "K": "positive", "B": "nonnegative", "z_a": "nonnegative",
    "t_d": "nonnegative", "m": "positive", "m_m": "positive", "m_s": "positive",
    "b_m": "positive", "b_s": "positive", "alpha": "positive",
    "K_0": "positive", "B_0": "nonnegative",
}

_VARIABLES = {"z": Z_SYM, "s": S_SYM}

#: Words that look like names but are (not) numbers: never parameters, never symbols.
NOT_NAMES: dict[str, str] = {
    "nan": "is not a number",
    "inf": "is not a finite number",
    "infinity": "is not a finite number",
    "oo": "is not a finite number",
    "zoo": "is not a finite number",
    "pi": "is the irrational number pi: values and coefficients are exact rationals (an exact decision needs "
          "rational coefficients); write the rational you mean, e.g. 355/113 or 3.14159265358979",
}


def not_a_name(word: str) -> str | None:
    """Why ``word`` is no parameter name (:data:`NOT_NAMES`; ``nan``/``inf`` in any case), or ``None``.

    >>> not_a_name("NaN"), not_a_name("K")
    ('is not a number', None)
    """
    if word.lower() == "pi":               # only the lower-case word is the number (PI may be a gain)
        return NOT_NAMES["pi"] if word == "pi" else None
    return NOT_NAMES.get(word.lower())
_DOMAIN = {"z": "a discrete-time expression in z", "s": "a continuous-time expression in s"}


class ExpressionError(InputFormatError):
    """A user expression that cannot be read (one line: where, what, position).

    ``reason`` and ``position`` are the message's parts without the expression's text (for
    files whose content must not be shown)."""

    def __init__(self, message: str, reason: str | None = None, position: int | None = None):
        super().__init__(message)
        self.reason = reason if reason is not None else message
        self.position = position


def parameter_symbol(name: str, assumption: str | None = None) -> sp.Symbol:
    """The symbol of a parameter: ``assumption`` (one of :data:`ASSUMPTIONS`), else the default
    of :data:`DEFAULT_ASSUMPTIONS`, else ``real``. Equal names and assumptions give equal
    symbols, so the papers' ``b, K, B, T, z_a`` are the toolkit's own. A parameter is never one of
    the toolkit's variables on the circle: a real ``c`` (a damping, say) is not ``c = cos(omega T)``
    (it carries the assumption ``parameter``; views print it as ``c`` and name the toolkit's
    ``c`` otherwise, :mod:`hapticproof.core.naming`).

    >>> parameter_symbol("K").is_positive, parameter_symbol("M").is_real, parameter_symbol("M").is_positive
    (True, True, None)
    >>> from hapticproof.core.symbols import c
    >>> parameter_symbol("c", "real") == c, parameter_symbol("c", "real").is_real
    (False, True)
    """
    if not _NAME.fullmatch(name) or name.startswith("_"):
        raise ExpressionError(f"{name!r} is not a parameter name (letters, digits and _, not starting with _ or a digit)")
    if name in _VARIABLES:
        raise ExpressionError(f"{name!r} is a transform variable, not a parameter name")
    if not_a_name(name):
        raise ExpressionError(f"{name!r} {not_a_name(name)}, not a parameter name")
    word = assumption or DEFAULT_ASSUMPTIONS.get(name) or _indexed_default(name)
    if word not in ASSUMPTIONS:
        raise ExpressionError(f"{name}: unknown assumption {word!r}; use one of {', '.join(ASSUMPTIONS)}")
    return apart_symbol(name, **ASSUMPTIONS[word])


def apart_symbol(name: str, **assumptions: bool) -> sp.Symbol:
    """The symbol of a user's name ``name``: never one of the toolkit's variables of the circle
    and the axis (a paper's real ``c`` is not ``c = cos wT``: one symbol, one meaning).

    >>> from hapticproof.core.symbols import c
    >>> apart_symbol("c", real=True) == c, apart_symbol("K", positive=True) == sp.Symbol("K", positive=True)
    (False, True)
    """
    symbol = sp.Symbol(name, **assumptions)
    if symbol in _CIRCLE_VARIABLES:
        symbol = sp.Symbol(name, parameter=True, **assumptions)
    return symbol


#: The toolkit's own variables of the circle and the axis (:mod:`hapticproof.core.symbols`).
_CIRCLE_VARIABLES = frozenset({C_SYM, X_SYM, SIN_THETA, COS_N, SIN_N})
#: The toolkit's own names a parameter may take all the same: its symbol is kept apart from the
#: variable's (:func:`parameter_symbol`) and the views rename the variable (``c`` -> ``gamma``).
KEPT_APART = frozenset(v.name for v in _CIRCLE_VARIABLES)


_INDEXED = re.compile(r"(b|K_0|B_0|K|B|z_a|m)_?[0-9][0-9_]*")


def _indexed_default(name: str) -> str:
    """Per-user names of m-user scenes (``b_1``, ``K_01``, ``B_12``, ``z_a2``, ``m_3``) carry
    their group's sign, as :func:`hapticproof.systems.multiuser.user_symbols` builds them."""
    match = _INDEXED.fullmatch(name)
    if match is None:
        return "real"
    return DEFAULT_ASSUMPTIONS.get(match.group(1), "real")


def read_number(text: str, where: str = "") -> sp.Rational:
    """An exact rational from a decimal, scientific or fraction literal.

    >>> read_number("0.015"), read_number("1e-3"), read_number("-2/3")
    (3/200, 1/1000, -2/3)
    """
    from hapticproof.core.limits import check_number_text

    text = str(text).strip()
    if not text.isascii():   # int() and Fraction() read Arabic-Indic and other digits too
        raise ExpressionError(f"{where + ': ' if where else ''}{text!r} is not a number (write digits 0-9)")
    for part in text.split("/"):
        check_number_text(part, where or "number")
    try:
        value = Fraction(text)
    except (ValueError, ZeroDivisionError):
        raise ExpressionError(f"{where + ': ' if where else ''}{text!r} is not a number") from None
    return sp.Rational(value.numerator, value.denominator)


# ---------------------------------------------------------------------------------------------
# tokens
# ---------------------------------------------------------------------------------------------

_NAME = re.compile(r"[A-Za-z_][A-Za-z0-9_]*")
_TOKEN = re.compile(
    r"\s*(?:(?P<number>(?:\d+\.?\d*|\.\d+)(?:[eE][+-]?\d+)?)|(?P<name>[A-Za-z_][A-Za-z0-9_]*)"
    r"|(?P<op>\*\*|[-+*/^()]))", re.ASCII     # digits 0-9 only: no Arabic-Indic or other digits
)


@dataclass(frozen=True, slots=True)
class _Token:
    kind: str      # 'number' | 'name' | 'op' | 'end'
    text: str
    position: int


_BLANK = re.compile(r"\s*")


def _tokens(text: str, fail: Callable[[str, int], None]) -> list[_Token]:
    out: list[_Token] = []
    position = 0
    while position < len(text):       # linear: no copy of the rest of the text per token
        start = _BLANK.match(text, position).end()
        if start == len(text):
            break
        match = _TOKEN.match(text, position)
        if match is None or match.end() == position:
            fail(f"unexpected character {text[start]!r}", start)
        kind = match.lastgroup
        out.append(_Token(kind, match.group(kind), match.start(kind)))
        position = match.end()
    out.append(_Token("end", "", len(text)))
    return out


# ---------------------------------------------------------------------------------------------
# the parser
# ---------------------------------------------------------------------------------------------


class _Parser:
    def __init__(self, text: str, variable: str | None, where: str, symbol: Callable[[str], sp.Symbol]):
        self.text, self.variable, self.where, self.symbol = text, variable, where, symbol
        self.tokens = _tokens(text, self.fail)
        self.index = 0
        self.depth = 0

    def fail(self, message: str, position: int, hint: str = "") -> None:
        prefix = f"{self.where}: " if self.where else ""
        shown = self.text if len(self.text) <= 200 else self.text[max(0, position - 40):position + 40]
        raise ExpressionError(f"{prefix}{message} at position {position} in {shown!r}{hint}", message + hint, position)

    @property
    def token(self) -> _Token:
        return self.tokens[self.index]

    def take(self) -> _Token:
        token = self.tokens[self.index]
        self.index += 1
        return token

    def parse(self) -> sp.Expr:
        if self.token.kind == "end":
            prefix = f"{self.where}: " if self.where else ""
            raise ExpressionError(f"{prefix}the expression is empty")
        value = self.expr()
        if self.token.kind != "end":
            self._unexpected()
        from hapticproof.core.limits import check

        check("degree", max(value.num, value.den), self.where or "expression")
        return value.expr

    def _unexpected(self) -> None:
        token = self.token
        if token.kind in ("number", "name") or token.text == "(":
            previous = self.tokens[self.index - 1].text if self.index else ""
            self.fail(f"missing operator between {previous!r} and {token.text!r} (write * for products)", token.position)
        if token.kind == "end":
            self.fail("the expression ends too early", token.position)
        self.fail(f"unexpected {token.text!r}", token.position)

    # Each rule returns the expression with bounds on the degrees of its numerator and
    # denominator in the transform variable, so that a power is refused before it is built
    # when the degree it would reach is above the limit (``z**10**9``, ``(z**1000)**1000``).
    def expr(self) -> _Value:
        first = self.term()
        terms, num, den = [first.expr], first.num, first.den
        while self.token.text in ("+", "-"):
            op = self.take().text
            right = self.term()
            terms.append(right.expr if op == "+" else -right.expr)
            num, den = max(num + right.den, right.num + den), den + right.den
        # one Add of all the terms: adding them one by one sorts the growing sum each time
        return first if len(terms) == 1 else _Value(sp.Add(*terms), num, den)

    def term(self) -> _Value:
        first = self.unary()
        factors, num, den = [first.expr], first.num, first.den
        while self.token.text in ("*", "/"):
            op = self.take()
            right = self.unary()
            if op.text == "*":
                factors.append(right.expr)
                num, den = num + right.num, den + right.den
            else:
                if right.expr == 0:
                    self.fail("division by zero", op.position)
                factors.append(sp.Pow(right.expr, -1))
                num, den = num + right.den, den + right.num
        return first if len(factors) == 1 else _Value(sp.Mul(*factors), num, den)

    def unary(self) -> _Value:
        negative = False
        while self.token.text in ("+", "-"):      # a loop: a run of signs is no recursion
            negative ^= self.take().text == "-"
        value = self.power()
        return _Value(-value.expr, value.num, value.den) if negative else value

    def power(self) -> _Value:
        from hapticproof.core.limits import check_power

        base = self.atom()
        if self.token.text in ("^", "**"):
            op = self.take()
            self.enter(op)
            exponent = self.unary().expr
            self.depth -= 1
            if not (exponent.is_Integer):
                self.fail(f"the exponent must be an integer constant, got {sp.sstr(exponent)}", op.position)
            if base.expr == 0 and exponent < 0:
                self.fail("division by zero", op.position)
            k = int(exponent)
            check_power(base.expr if base.expr.is_Rational else None, k, self.place(op),
                        degree=max(base.num, base.den))
            num, den = (base.num * k, base.den * k) if k >= 0 else (base.den * -k, base.num * -k)
            return _Value(base.expr ** exponent, num, den)
        return base

    def enter(self, token: _Token) -> None:
        """One level deeper (a parenthesis, an exponent): within the depth limit."""
        from hapticproof.core.limits import check

        self.depth += 1
        check("depth", self.depth, self.place(token))

    def place(self, token: _Token) -> str:
        if self.where:
            return f"{self.where}: position {token.position}"
        shown = self.text if len(self.text) <= 60 else self.text[:57] + "..."
        return f"{shown!r} at position {token.position}"

    def atom(self) -> _Value:
        token = self.take()
        if token.kind == "number":
            return _Value(read_number(token.text, self.place(token)), 0, 0)
        if token.kind == "name":
            if self.token.text == "(":
                self.fail(f"unknown function {token.text!r}", token.position,
                          " (a rational expression has numbers, names, + - * / ^ and parentheses)")
            if token.text in _VARIABLES:
                if self.variable is None:
                    self.fail(f"{token.text!r} is a transform variable; a parameter value has none", token.position)
                if token.text != self.variable:
                    self.fail(f"{token.text!r} in {_DOMAIN[self.variable]}", token.position)
                return _Value(_VARIABLES[token.text], 1, 0)
            if token.text.startswith("_"):
                self.fail(f"names may not start with '_': {token.text!r}", token.position)
            if not_a_name(token.text):
                if len(self.tokens) == 2:            # the whole text: no position to point at
                    raise ExpressionError(f"{self.where + ': ' if self.where else ''}{token.text!r} {not_a_name(token.text)}")
                self.fail(f"{token.text!r} {not_a_name(token.text)}", token.position)
            return _Value(self.symbol(token.text), 0, 0)
        if token.text == "(":
            self.enter(token)
            value = self.expr()
            if self.token.text != ")":
                self.fail("missing ')'", self.token.position)
            self.take()
            self.depth -= 1
            return value
        self.index -= 1
        self._unexpected()
        raise AssertionError  # pragma: no cover


@dataclass(frozen=True, slots=True)
class _Value:
    """A parsed expression and bounds on the degrees of its numerator and denominator in the
    transform variable."""

    expr: sp.Expr
    num: int
    den: int


def read_expression(text: str, variable: str | None = "z", *, where: str = "",
                    symbols: Mapping[str, sp.Symbol] | None = None,
                    assumptions: Mapping[str, str] | None = None) -> sp.Expr:
    """Read a rational expression in ``variable`` (``'z'``, ``'s'`` or ``None``) and parameters.

    ``symbols`` maps names to the caller's symbols (used as they are); other names become
    :func:`parameter_symbol` symbols, with ``assumptions`` (name -> word) taking precedence
    over the defaults. ``where`` names the source in error messages.

    >>> read_expression("K_i*T*z/(z - 1) + K", "z").free_symbols == {sp.Symbol("K_i", real=True),
    ...     sp.Symbol("T", positive=True), sp.Symbol("K", positive=True), sp.Symbol("z")}
    True
    >>> read_expression("2s + 1", "s")
    Traceback (most recent call last):
    ...
    hapticproof.core.expr.ExpressionError: missing operator between '2' and 's' (write * for products) at position 1 in '2s + 1'
    >>> read_expression("K + z", "s", where="--operator")
    Traceback (most recent call last):
    ...
    hapticproof.core.expr.ExpressionError: --operator: 'z' in a continuous-time expression in s at position 4 in 'K + z'
    """
    if not isinstance(text, str):
        if isinstance(text, (int, Fraction)) and not isinstance(text, bool):
            return sp.Rational(text)
        raise ExpressionError(f"{where + ': ' if where else ''}expected an expression as text, got {text!r}")
    if variable not in (None, "z", "s"):
        raise ValueError("variable must be 'z', 's' or None")
    known = dict(symbols or {})
    extra = dict(assumptions or {})
    cache: dict[str, sp.Symbol] = {}

    def symbol(name: str) -> sp.Symbol:
        if name in known:
            return known[name]
        if name not in cache:
            cache[name] = parameter_symbol(name, extra.get(name))
        return cache[name]

    return _Parser(text, variable, where, symbol).parse()


def normalise_variables(expr: sp.Expr, variable: str, where: str = "") -> sp.Expr:
    """An expression built in Python, with the toolkit's own transform variable: a symbol named
    ``z`` (or ``s``) with other assumptions is replaced by the toolkit's; the other domain's
    variable, or a function (``sin(z)``), is an error.

    >>> zc = sp.Symbol("z", complex=True)
    >>> normalise_variables(1/(zc - 1), "z").free_symbols == {Z_SYM}
    True
    """
    from hapticproof.core.errors import SceneError

    expr = sp.sympify(expr)
    other = "s" if variable == "z" else "z"
    prefix = f"{where}: " if where else ""
    names = {sym.name: sym for sym in expr.free_symbols}
    if other in names:
        raise SceneError(f"{prefix}{other!r} in {_DOMAIN[variable]}: {sp.sstr(expr)}")
    mine = _VARIABLES[variable]
    if variable in names and names[variable] != mine:
        expr = expr.xreplace({names[variable]: mine})
    bad = sorted(sp.sstr(f) for f in expr.atoms(sp.Function) if mine in f.free_symbols)
    if bad:      # a function of the variable (exp(-T/tau), a coefficient of ZOH, is fine)
        raise SceneError(f"{prefix}{bad[0]} in {_DOMAIN[variable]}: only rational expressions are allowed")
    if expr.has(sp.Float):
        expr = expr.xreplace({f: sp.Rational(repr(float(f))) for f in expr.atoms(sp.Float)})  # as typed
    return expr


def check_rational(value: sp.Basic, where: str = "") -> sp.Expr:
    """A value built in Python is an exact rational number or a rational expression of symbols
    with rational coefficients: ``nan``, infinities, ``pi``, ``sqrt(2)``, floats that are not
    finite and functions are errors (:class:`ExpressionError`); finite floats become the
    rationals of their shortest decimal text.

    >>> K = sp.Symbol("K")
    >>> check_rational(K / 2 + sp.Float(0.5)), check_rational(sp.Integer(3))
    (K/2 + 1/2, 3)
    >>> check_rational(sp.pi * K, "K_0")
    Traceback (most recent call last):
    ...
    hapticproof.core.expr.ExpressionError: K_0: pi*K is not rational: values and coefficients are exact rationals (an exact decision needs rational coefficients)
    """
    prefix = f"{where}: " if where else ""
    value = sp.sympify(value)
    if value.has(sp.nan, sp.zoo, sp.oo, -sp.oo):
        raise ExpressionError(f"{prefix}{sp.sstr(value)} is not a finite number")
    if value.has(sp.Float):
        floats = value.atoms(sp.Float)
        if any(not f.is_finite for f in floats):
            raise ExpressionError(f"{prefix}{sp.sstr(value)} is not a finite number")
        value = value.xreplace({f: sp.Rational(repr(float(f))) for f in floats})
    if value.is_Rational:
        return value
    gens = sorted(value.free_symbols, key=str)
    try:
        num, den = sp.fraction(sp.together(value))
        ok = all(sp.Poly(part, *gens).domain.is_QQ or sp.Poly(part, *gens).domain.is_ZZ
                 for part in (num, den)) if gens else False
    except (sp.PolynomialError, sp.GeneratorsNeeded):
        ok = False
    if not ok:
        raise ExpressionError(f"{prefix}{sp.sstr(value)} is not rational: values and coefficients are exact "
                              "rationals (an exact decision needs rational coefficients)")
    return value


def write_expression(expr: sp.Expr) -> str:
    """Text that :func:`read_expression` reads back to an equal expression (SymPy's ``sstr``:
    exact rationals, ``**`` for powers, explicit ``*``).

    >>> e = read_expression("K + B*(1 - 0.9)*(z - 1)/(T*(z - 0.9))")
    >>> read_expression(write_expression(e)) == e
    True
    """
    return sp.sstr(sp.sympify(expr))
