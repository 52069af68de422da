r"""One naming context for every view: the scene's own names for its roles, and free names for the
toolkit's own quantities.

A scene names its parameters as it likes (the period ``h``, the device damping ``c_d``:
:mod:`hapticproof.systems.roles`); the toolkit has quantities of its own -- ``c = cos(omega T)``,
``theta = omega T``, ``x = omega^2``, the teleoperator's error-coordinate damping ``h`` and its
leak ``L(c)``, the proofs' ``a = b - z_a``, the delay margin ``N``... A :class:`Naming` holds
both: the name of every role, and for every toolkit quantity (a *helper*) a name that no user
name can be confused with -- its default (``c``) unless a user name is that name or starts with
it (``c``, ``c_d``, ``c1``: ``c c_d`` would read as one symbol), else the first free one of its
candidates (``gamma``), so that no symbol stands for two things. Every view (text, LaTeX, HTML,
JSON, notebooks) prints through it; no view invents a name. A scene without renamed roles and
without user names that clash gets the defaults, and prints exactly what it always printed.

>>> names = Naming.choose({"K", "B", "h", "c_d"}, roles=(("period", "T", "h"), ("device_damping", "b", "c_d")))
>>> names.helper("cos"), names.period, names.cos_text, names.cos_latex
('gamma', 'h', 'cos wh', '\\cos(\\omega h)')
>>> import sympy as sp
>>> from hapticproof.core.symbols import c
>>> K, h, c_d = sp.symbols("K h c_d", positive=True)
>>> names.text(c_d - K*h/2 + 3*c)
'-K*h/2 + c_d + 3*gamma'
>>> names.latex(c_d - K*h/2 + 3*c, cos=True)
'- \\frac{K h}{2} + 3 \\cos(\\omega h) + c_{d}'
>>> names.words("(D) b_m >= 0; Re G^-1 (c = cos wT) >= 0 for all w")
'(D) b_m >= 0; Re G^-1 (gamma = cos wh) >= 0 for all w'
>>> Naming.choose({"K", "B"}).is_default
True
"""

from __future__ import annotations

import functools
import re
from collections.abc import Iterable, Mapping
from dataclasses import dataclass, field
from typing import Any

import sympy as sp

from hapticproof.core.notation import default_name, to_latex
from hapticproof.core.symbols import c as C_SYM
from hapticproof.core.symbols import cos_n, omega, sin_n, sin_theta, theta
from hapticproof.core.symbols import x as X_SYM

__all__ = ["Helper", "HELPERS", "Naming", "DEFAULT", "name_head", "clashes", "marker", "role_marker", "marked",
           "witness_keys", "angle_marker"]


@dataclass(frozen=True, slots=True)
class Helper:
    """A quantity of the toolkit's own: its key, the SymPy symbol the exact forms use for it
    (``None``: a word of the reports only), what it means, and its candidate names as
    ``(text, LaTeX)`` pairs, the default first."""

    key: str
    symbol: sp.Symbol | None
    meaning: str
    candidates: tuple[tuple[str, str], ...]

    @property
    def default(self) -> str:
        return self.candidates[0][0]


#: The toolkit's own quantities, by key (their meanings name the frequency as ``{w}`` and the
#: frequency times the period as ``{wT}``: :meth:`Naming.meaning` fills them in).
HELPERS: dict[str, Helper] = {h.key: h for h in (
    Helper("cos", C_SYM, "cos {wT}", (("c", "c"), ("gamma", r"\gamma"), ("chi", r"\chi"), ("varsigma", r"\varsigma"))),
    Helper("sin", sin_theta, "sin {wT}", (("s_theta", "s_{theta}"), ("sigma", r"\sigma"), ("varsigma_s", r"\varsigma_{s}"))),
    Helper("theta", theta, "{wT}", (("theta", r"\theta"), ("vartheta", r"\vartheta"), ("phi", r"\phi"))),
    Helper("omega", omega, "the angular frequency", (("omega", r"\omega"), ("nu", r"\nu"), ("varpi", r"\varpi"))),
    Helper("x", X_SYM, "{w}^2", (("x", "x"), ("xi", r"\xi"), ("chi_w", r"\chi_{w}"))),
    Helper("cos_n", cos_n, "cos(n {wT})", (("C_n", "C_{n}"), ("Gamma_n", r"\Gamma_{n}"), ("C_ntheta", r"C_{n\theta}"))),
    Helper("sin_n", sin_n, "sin(n {wT})", (("S_n", "S_{n}"), ("Sigma_n", r"\Sigma_{n}"), ("S_ntheta", r"S_{n\theta}"))),
    Helper("margin", None, "the delay margin (in samples)", (("N", "N"), ("Q", "Q"), ("D_m", "D_{m}"))),
    Helper("leak", None, "the teleoperator's leak", (("L", "L"), ("ell", r"\ell"), ("Lambda", r"\Lambda"))),
    Helper("coupling", None, "the error-coordinate damping", (("h", "h"), ("eta", r"\eta"), ("h_e", "h_{e}"))),
    Helper("excess", None, "the damping left over, b - z_a", (("a", "a"), ("beta", r"\beta"), ("a_e", "a_{e}"))),
    Helper("residue", None, "the residue at z = 1", (("R", "R"), ("rho", r"\rho"), ("R_1", "R_{1}"))),
    Helper("rest", None, "G^-1 without its pole at z = 1", (("F_0", "F_{0}"), ("Phi_0", r"\Phi_{0}"), ("F_r", "F_{r}"))),
    Helper("kernel", None, "the Dirichlet kernel", (("D_n", "D_{n}"), ("Delta_n", r"\Delta_{n}"), ("D_k", "D_{k}"))),
    Helper("matrix", None, "the Hermitian part of G^-1 on the circle", (("M", "M"), ("W", "W"), ("Q_M", "Q_{M}"))),
    Helper("eigenvalue", None, "an eigenvalue of the coupling Laplacian", (("lambda", r"\lambda"), ("mu", r"\mu"), ("kappa", r"\kappa"))),
)}

#: What words of the toolkit's texts each helper is written as (``w`` is the frequency in words).
_WORDS: dict[str, str] = {"c": "cos", "s_theta": "sin", "theta": "theta", "x": "x", "C_n": "cos_n", "S_n": "sin_n",
                          "L": "leak", "h": "coupling", "M": "matrix", "lambda": "eigenvalue"}


#: The keys of a displayed witness that are the toolkit's own quantities -> their helper.
_WITNESS_HELPERS = {"c": "cos", "omega": "omega", "x": "x", "theta": "theta"}


def witness_keys(notation: Mapping[str, Any] | None = None) -> dict[str, str]:
    """The key a displayed witness names each of the toolkit's quantities by, in a report whose
    ``notation`` is :meth:`Naming.changed` (``c`` -> ``gamma``, ``omega_T`` -> ``omega*h``): one
    rule for the views that write witnesses and the checker that reads them.

    >>> witness_keys({"period": "h", "cos": "gamma"})["c"], witness_keys({"period": "h"})["omega_T"]
    ('gamma', 'omega*h')
    >>> witness_keys()["omega_T"]
    'omega_T'
    """
    notation = notation if isinstance(notation, Mapping) else {}

    def name(key: str, default: str) -> str:
        value = notation.get(key, default)
        return value if isinstance(value, str) else default
    out = {key: name(helper, HELPERS[helper].default) for key, helper in _WITNESS_HELPERS.items()}
    period = name("period", "T")
    out["omega_T"] = "omega_T" if (out["omega"], period) == ("omega", "T") else f"{out['omega']}*{period}"
    return out


def name_head(name: str) -> str:
    """The symbol a name is written as before its subscript: ``c`` of ``c_d``, ``c12`` and ``c``.

    >>> name_head("c_d"), name_head("K01"), name_head("omega_1"), name_head("Ts")
    ('c', 'K', 'omega', 'Ts')
    """
    head = name.partition("_")[0] or name
    match = re.fullmatch(r"([A-Za-z]+?)(\d+)", head)
    if match and len(match.group(1)) == 1:
        return match.group(1)
    return head


def clashes(candidate: str, name: str) -> bool:
    """Whether the toolkit name ``candidate`` could be read as, or next to, the user's ``name``:
    equal names; a one-letter ``candidate`` also when ``name`` is that letter with a subscript
    (``c`` and ``c_d``: ``c c_d`` reads as one symbol); the frequency ``omega`` also against
    ``w``, the letter the text output writes it as.

    >>> clashes("c", "c_d"), clashes("c", "cd"), clashes("h", "h"), clashes("a_e", "a"), clashes("omega", "omega_s")
    (True, False, True, False, False)
    """
    if candidate == name:
        return True
    if candidate == "omega" and name == "w":
        return True
    return len(candidate) == 1 and name_head(name) == candidate


@dataclass(frozen=True, slots=True)
class Naming:
    r"""The names one scene (or one paper) prints: its roles' names and the toolkit's helpers.

    ``roles`` are ``(field, default, name)`` triples (``("period", "T", "h")``); ``helpers``
    are ``(key, text name)`` pairs for every helper of :data:`HELPERS`; ``taken`` the user's
    names the helpers were chosen to avoid. Build one with :meth:`choose`.
    """

    roles: tuple[tuple[str, str, str], ...] = ()
    helpers: tuple[tuple[str, str], ...] = ()
    taken: frozenset = field(default=frozenset())

    @classmethod
    def choose(cls, taken: Iterable[str] = (), roles: Iterable[tuple[str, str, str]] = ()) -> Naming:
        """The naming of a scene whose user names are ``taken`` (role names included or not):
        each helper gets its default unless it clashes with a user name (:func:`clashes`) or an
        already chosen helper, else its first free candidate (then numbered ``gamma_2``...).

        >>> Naming.choose({"c", "h"}).helper("cos"), Naming.choose({"h"}).helper("coupling")
        ('gamma', 'eta')
        """
        roles = tuple((str(f), str(d), str(n)) for f, d, n in roles)
        users = set(taken) | {n for _, _, n in roles}
        # the roles' defaults that no longer name their role stay free for nothing else either:
        # 'T' of a scene whose period is 'h' is no helper's name (it would read as the period)
        blocked = users | {d for _, d, n in roles if d != n}
        chosen: dict[str, str] = {}
        for key, helper in HELPERS.items():
            used = blocked | set(chosen.values())
            pick = next((text for text, _ in helper.candidates if not any(clashes(text, u) for u in used)), None)
            k = 2
            base = helper.candidates[1][0]
            while pick is None:
                trial = f"{base}_{k}"
                if not any(clashes(trial, u) for u in used):
                    pick = trial
                k += 1
            chosen[key] = pick
        return cls(roles=roles, helpers=tuple(chosen.items()), taken=frozenset(users))

    @classmethod
    def of_symbols(cls, symbols: Iterable[Any], roles: Iterable[tuple[str, str, str]] = (),
                   extra: Iterable[str] = ()) -> Naming:
        """The naming of a paper whose names are the symbols ``symbols`` (and the names ``extra``):
        a symbol that *is* a helper's is no clash, nor is a paper's frequency (``omega``,
        ``theta``, whatever its assumptions: a paper's frequency is the frequency), nor are the
        transform variables ``z`` and ``s``.

        >>> Naming.of_symbols([sp.Symbol("omega", positive=True), sp.Symbol("c_d", positive=True)]).changed()
        {'cos': 'gamma'}
        """
        own = {h.symbol for h in HELPERS.values() if h.symbol is not None}
        taken = {s.name for s in symbols if isinstance(s, sp.Symbol) and s not in own and s.name not in ("omega", "theta")}
        taken |= set(extra)
        return _choose(frozenset(taken - {"z", "s"}), tuple(roles))

    # -- names ---------------------------------------------------------------------------------
    def helper(self, key: str) -> str:
        """The text name of a helper (``'c'``, or the fresh name chosen for it)."""
        for k, name in self.helpers:
            if k == key:
                return name
        return HELPERS[key].default

    def helper_latex(self, key: str) -> str:
        """The LaTeX name of a helper (``c``, ``\\gamma``)."""
        name = self.helper(key)
        for text, tex in HELPERS[key].candidates:
            if text == name:
                return tex
        return default_name(name)

    def role(self, field: str, default: str | None = None) -> str:
        """The name of a role (``'h'`` for ``'period'``), or ``default`` (the field's default name
        when the naming does not list it)."""
        for f, d, name in self.roles:
            if f == field:
                return name
        return default if default is not None else field

    def role_latex(self, field: str, default: str | None = None) -> str:
        return default_name(self.role(field, default))

    @property
    def period(self) -> str:
        return self.role("period", "T")

    @property
    def is_default(self) -> bool:
        """No role renamed and every helper its default: prints what the papers' names print."""
        return all(d == n for _, d, n in self.roles) and all(HELPERS[k].default == n for k, n in self.helpers)

    # -- the frequency -------------------------------------------------------------------------
    @property
    def w(self) -> str:
        """The frequency in words: ``w`` (``omega``), or the name chosen for it."""
        name = self.helper("omega")
        return "w" if name == "omega" else name

    @property
    def theta_text(self) -> str:
        """``wT``: the frequency times the period, in words (``wh``, ``w*Ts``)."""
        w, T = self.w, self.period
        return f"{w}{T}" if len(w) == 1 and len(T) == 1 else f"{w}*{T}"

    @property
    def cos_text(self) -> str:
        """``cos wT`` in words."""
        return f"cos {self.theta_text}" if "*" not in self.theta_text else f"cos({self.theta_text})"

    @property
    def sin_text(self) -> str:
        return f"sin {self.theta_text}" if "*" not in self.theta_text else f"sin({self.theta_text})"

    @property
    def theta_latex(self) -> str:
        """``\\omega T`` with the period's name."""
        return f"{self.helper_latex('omega')} {default_name(self.period)}"

    @property
    def cos_latex(self) -> str:
        """``\\cos(\\omega T)`` with the period's name."""
        return rf"\cos({self.theta_latex})"

    @property
    def sin_latex(self) -> str:
        return rf"\sin({self.theta_latex})"

    @property
    def omega_T(self) -> str:
        """The key ``omega_T`` of a witness, in words (``omega_T``; ``omega*h`` for period ``h``)."""
        return witness_keys(self.changed())["omega_T"]

    def meaning(self, key: str) -> str:
        """What a helper stands for, in this naming's words (``cos wh``, ``cos(w*Ts)``).

        >>> Naming.choose(roles=(("period", "T", "Ts"),)).meaning("cos")
        'cos(w*Ts)'
        """
        if key in ("cos", "sin"):
            return self.cos_text if key == "cos" else self.sin_text
        wT = self.theta_text if "*" not in self.theta_text or key == "theta" else f"({self.theta_text})"
        return HELPERS[key].meaning.format(w=self.w, wT=wT)

    def definitions(self, expr: Any) -> str:
        """`` (c = cos wT, s_theta = sin wT)``: the helper symbols ``expr`` uses, defined in this
        naming's words (empty when it uses none), to follow a printed expression.

        >>> from hapticproof.core.symbols import c, sin_theta
        >>> DEFAULT.definitions(2*sin_theta + c)
        ' (c = cos wT, s_theta = sin wT)'
        """
        free = getattr(sp.sympify(expr), "free_symbols", set())
        used = [f"{self.helper(key)} = {self.meaning(key)}" for key in ("cos", "sin", "cos_n", "sin_n", "theta")
                if HELPERS[key].symbol in free]
        return f" ({', '.join(used)})" if used else ""

    # -- expressions -----------------------------------------------------------------------------
    def display_symbols(self) -> dict[sp.Symbol, sp.Symbol]:
        """The helpers' symbols that are printed under another name -> a symbol of that name."""
        out = {}
        for key, name in self.helpers:
            helper = HELPERS[key]
            if helper.symbol is not None and name != helper.default:
                out[helper.symbol] = sp.Symbol(name, **helper.symbol.assumptions0)
        return out

    def latex_names(self) -> dict[sp.Symbol, str]:
        """The helpers' symbols printed under another name -> their LaTeX."""
        return {HELPERS[key].symbol: self.helper_latex(key) for key, name in self.helpers
                if HELPERS[key].symbol is not None and name != HELPERS[key].default}

    def renamed(self, expr: Any) -> Any:
        """``expr`` with the helpers' symbols under their printed names (for text and JSON), and
        the minimum over them named after them (``min_c(...)`` -> ``min_gamma(...)``)."""
        subs = self.display_symbols()
        if not subs:
            return expr
        if isinstance(expr, (list, tuple)):
            return type(expr)(self.renamed(e) for e in expr)
        if not hasattr(expr, "xreplace"):
            return expr
        cos = self.helper("cos")
        extrema = {f: sp.Function(f.func.__name__[:4] + cos)(*f.args) for f in expr.atoms(sp.Function)
                   if getattr(f.func, "__name__", "") in ("min_c", "sup_c") and cos != "c"}
        return expr.xreplace(extrema).xreplace(subs) if extrema else expr.xreplace(subs)

    def text(self, expr: Any) -> str:
        """``sstr(expr)`` in this naming (``gamma`` for ``c`` when ``c`` is taken)."""
        if isinstance(expr, str):
            return expr
        return sp.sstr(self.renamed(expr))

    def latex(self, expr: Any, names: Mapping[sp.Symbol, str] | None = None, cos: bool = False) -> str:
        """LaTeX of ``expr`` in this naming; ``cos`` prints ``c`` as ``\\cos(\\omega T)``;
        ``names`` (symbol -> LaTeX: a paper's printed names) come first."""
        # with cos: c is cos(omega T) and theta (a symbolic delay's angle) omega T, both in the scene's names
        # (theta is no user's name: refused as a parameter, so every symbol of that name is the angle)
        angle = {sym: self.theta_latex for sym in getattr(sp.sympify(expr), "free_symbols", ())
                 if getattr(sym, "name", "") == "theta"} if cos and not isinstance(expr, str) else {}
        return to_latex(expr, {**self.latex_names(), **angle, **(names or {})}, cos_name=self.cos_latex if cos else None)

    # -- the toolkit's words ---------------------------------------------------------------------
    def word_map(self) -> dict[str, str]:
        """Every word of the toolkit's own texts that this naming prints differently -> its
        printed form: renamed roles (``T`` -> ``h``), renamed helpers (``c`` -> ``gamma``), the
        frequency (``w``, ``wT``, ``omega_T``)."""
        out: dict[str, str] = {}
        for _, default, name in self.roles:
            if default != name:
                out[default] = name
        for word, key in _WORDS.items():
            if self.helper(key) != word:
                out[word] = self.helper(key)
        if self.helper("eigenvalue") != "lambda":
            out["g_lambda"] = f"g_{self.helper('eigenvalue')}"
        if self.helper("matrix") != "M":             # M(c) = M0 + c M1: its two coefficient matrices
            out["M0"], out["M1"] = f"{self.helper('matrix')}0", f"{self.helper('matrix')}1"
            out["lambda_max"] = f"{self.helper('eigenvalue')}_max"
        if self.w != "w":
            out["w"] = self.w
            out["jw"] = f"j*{self.w}"
            out["omega"] = self.helper("omega")
        if self.theta_text != "wT":
            out["wT"] = self.theta_text
        if self.omega_T != "omega_T":
            out["omega_T"] = self.omega_T
        return out

    def words(self, text: str) -> str:
        """A text of the toolkit's own words (a condition's name, a label: no user expression in
        it) in this naming, word by word (``cos wT`` -> ``cos wh``, ``b_m`` -> ``c_m``).

        Only for the toolkit's texts: a user's expression in ``text`` would be renamed too."""
        table = self.word_map()
        if not table or not isinstance(text, str):
            return text
        return re.sub(r"(?<![A-Za-z0-9_\\])[A-Za-z_][A-Za-z0-9_]*", lambda m: table.get(m.group(0), m.group(0)), text)

    def changed(self, omit: Iterable[str] = ()) -> dict[str, str]:
        """What this naming prints differently from the papers' names: a role's field or a helper's
        key -> its printed name (a JSON report's ``notation``; empty for the defaults); ``omit``
        leaves out helpers a system never prints (a wall has no error-coordinate damping).

        >>> Naming.choose({"c_d"}, roles=(("period", "T", "h"),)).changed()
        {'period': 'h', 'cos': 'gamma', 'coupling': 'eta'}
        >>> Naming.choose({"c_d"}, roles=(("period", "T", "h"),)).changed(omit=("coupling",))
        {'period': 'h', 'cos': 'gamma'}
        """
        out = {field: name for field, default, name in self.roles if name != default}
        out.update({key: name for key, name in self.helpers if name != HELPERS[key].default and key not in omit})
        return out

    def unmark(self, text: str) -> str:
        """A marked text (:func:`marker`, :func:`marked`) in this naming."""
        if not isinstance(text, str) or _MARK not in text:
            return text

        def name(m: re.Match) -> str:
            if m.group(1):
                default = m.group(0).partition(_MARK)[0]
                return self.role(m.group(2), default)
            if m.group(2) == "angle":
                return self.omega_T
            return self.w if m.group(2) == "w" else self.helper(m.group(2))
        return _MARKED.sub(name, text)

    def unmarked(self, value: Any) -> Any:
        """``value`` (a finding, an outcome, evidence, a mapping or a text) with every marked text in
        it written in this naming."""
        return _unmark_value(self, value)

    def witness(self, witness: Any) -> Any:
        """A displayed witness of the toolkit's circle keys (``c``, ``omega_T``, ``omega``, ``x``)
        with each key as this naming prints it (:func:`witness_keys`); other keys unchanged.

        >>> Naming.choose({"c_d"}, roles=(("period", "T", "h"),)).witness({"c": 0, "omega_T": "pi/2", "K": 1})
        {'gamma': 0, 'omega*h': 'pi/2', 'K': 1}
        """
        if not isinstance(witness, Mapping) or self.is_default:
            return witness
        keys = witness_keys(self.changed())
        return {keys.get(k, k) if isinstance(k, str) else k: v for k, v in witness.items()}

    def worded(self, value: Any) -> Any:
        """``value`` (an outcome, a condition...) with every text in it -- reasons, names, the
        reasons of the outcomes in its evidence -- in this naming's words (:meth:`words`): only for
        the toolkit's own texts (a numeric scene's reasons hold numbers and the toolkit's words)."""
        return value if self.is_default else _unmark_value(self, value, text=self.words)

    def claims(self, value: Any) -> Any:
        """A JSON value with the ``claim`` of every certificate in it in this naming's words
        (``h - L(c) >= 0`` -> ``eta - L(gamma) >= 0``): the claim is written for a reader, the
        rest of a certificate is data for the checker and keeps the toolkit's keys.

        >>> Naming.choose({"c_d"}).claims({"a": [{"certificate": "sign", "claim": "Re G^-1(c) >= 0", "variable": "c"}]})
        {'a': [{'certificate': 'sign', 'claim': 'Re G^-1(gamma) >= 0', 'variable': 'c'}]}
        """
        if self.is_default:
            return value
        if isinstance(value, dict):
            out = {k: self.claims(v) for k, v in value.items()}
            if isinstance(value.get("certificate"), str) and isinstance(value.get("claim"), str):
                out["claim"] = self.words(value["claim"])
            return out
        if isinstance(value, list):
            return [self.claims(v) for v in value]
        return value

    def legend(self) -> dict[str, str]:
        """The helpers printed under another name -> what they stand for (for a report's notation
        line; empty for the defaults)."""
        out = {}
        for key, name in self.helpers:
            if name != HELPERS[key].default:
                out[name] = self.meaning(key)
        return out


@functools.lru_cache(maxsize=256)
def _choose(taken: frozenset, roles: tuple) -> Naming:
    return Naming.choose(taken, roles)


#: The papers' names: every role its default, every helper its default.
DEFAULT = Naming.choose()


# ---------------------------------------------------------------------------------------------
# marked text: the toolkit's names in a text written before the naming is known
# ---------------------------------------------------------------------------------------------

_MARK = "\x1f"
_MARKED = re.compile(r"[A-Za-z0-9_]*\x1f(@?)([A-Za-z_]+)\x1f")


def marker(key: str) -> str:
    """A helper's name in a text written before the scene's naming is known (the audit's
    findings, written for any paper): :meth:`Naming.unmark` writes the name the naming chose.
    It sorts where the default name sorts, so expressions print in the same order. The key ``w``
    is the frequency in words (``w``, :attr:`Naming.w`).

    >>> DEFAULT.unmark(f"minimum at {marker('cos')} = -1"), Naming.choose({"c_d"}).unmark(marker("cos"))
    ('minimum at c = -1', 'gamma')
    """
    return f"{'w' if key == 'w' else HELPERS[key].default}{_MARK}{key}{_MARK}"


def angle_marker() -> str:
    """The key ``omega_T`` of a witness (the frequency times the period) in a marked text.

    >>> Naming.choose(roles=(("period", "T", "h"),)).unmark(angle_marker())
    'omega*h'
    """
    return f"omega_T{_MARK}angle{_MARK}"


def role_marker(field: str, default: str) -> str:
    """A role's name (``T`` for ``period``) in a marked text (:func:`marker`)."""
    return f"{default}{_MARK}@{field}{_MARK}"


def marked(expr: Any) -> str:
    """``sstr(expr)`` with the helpers' symbols as markers (:func:`marker`): the text of an
    expression of the exact forms for a finding, written in the naming of the paper that
    reports it (:meth:`Naming.unmark`).

    >>> from hapticproof.core.symbols import c
    >>> K = sp.Symbol("K", positive=True)
    >>> DEFAULT.unmark(marked(K/2 - c)) == sp.sstr(K/2 - c)
    True
    """
    if isinstance(expr, str):
        return expr
    subs = {h.symbol: sp.Symbol(marker(key), **h.symbol.assumptions0) for key, h in HELPERS.items() if h.symbol is not None}
    value = expr.xreplace(subs) if hasattr(expr, "xreplace") else expr
    return sp.sstr(value)


#: Evidence facts that are data for the checker and the judge, never text: left as they are.
_MACHINE_KEYS = frozenset({"certificate", "judge", "checker", "definition", "printed_form", "transfer"})


def _unmark_value(names: Naming, value: Any, key: Any = None, text: Any = None, nested: bool = False) -> Any:
    """``value`` with every text written by ``text`` (``names.unmark``), the helpers' symbols of
    its expressions renamed, and (``nested``: an outcome inside evidence, shown, never judged) the
    keys of its witness in words."""
    from dataclasses import is_dataclass, replace

    from hapticproof.core.evidence import Evidence, Finding, Outcome

    text = text or names.unmark
    if key in _MACHINE_KEYS:
        return value
    if isinstance(value, str):
        return text(value)
    if isinstance(value, sp.Basic):
        return names.renamed(value)
    if isinstance(value, Finding):
        return replace(value, detail=text(value.detail), evidence=_unmark_value(names, value.evidence, text=text),
                       corrected=text(value.corrected) if value.corrected else value.corrected)
    if isinstance(value, Evidence):
        witness = value.witness
        if nested and isinstance(witness, Mapping):
            witness = names.witness(witness)
        elif isinstance(witness, Mapping) and text == names.unmark:   # an audit's: the circle's keys are marked
            witness = {text(k) if isinstance(k, str) else k: v for k, v in witness.items()}
        elif isinstance(witness, Mapping):      # a derivation's: the circle's keys by their default names
            witness = names.witness(witness)
        return replace(value, witness=witness, facts=_unmark_value(names, dict(value.facts), text=text, nested=True))
    if isinstance(value, Outcome):
        return replace(value, reason=text(value.reason), evidence=_unmark_value(names, value.evidence, text=text, nested=nested))
    if isinstance(value, dict):
        if nested and key == "witness":           # a shown witness (not the judged one): its circle's keys named
            return names.witness(value)
        return {(text(k) if isinstance(k, str) else k): _unmark_value(names, v, k, text, nested) for k, v in value.items()}
    if isinstance(value, (list, tuple)) and not hasattr(value, "_fields"):
        return type(value)(_unmark_value(names, v, None, text, nested) for v in value)
    if is_dataclass(value) and not isinstance(value, type) and hasattr(value, "outcome") and isinstance(getattr(value, "name", None), str):
        return replace(value, name=text(value.name), outcome=_unmark_value(names, value.outcome, None, text, nested))   # a Condition
    return value
