r"""Guess, from a display's shape, the paper-file claim it makes and the assumptions on its symbols.

The guesses fill a draft paper file (``hapticproof new-paper --from``) for a reviewer to confirm:
each comes with the reason it was made, and a shape that says nothing gives ``None`` with the
reason, never a made-up claim. Stdlib only.

:func:`guess_claim` reads, in this order:

* ``\mathrm{Res}`` (``\operatorname{Res}``, ``\text{Res}``): ``residue``; ``R_0 = ...`` (or a
  ``NAME = matrix`` the prose before calls a residue): ``residue``;
* ``G^{-1}(z) = ...`` (``G_1^{-1}``, a matrix too), ``F_h(z) = ... V_h(z)`` with an explicit
  expression of ``z``: ``inverse-transfer`` (``F_h(z) = G^{-1}(z)V_h(z)`` alone names ``G^{-1}``
  without saying what it is: ``None``);
* a real part ``\Re\{...\}`` (``\text{Re}``, ``\operatorname{Re}``), the Hermitian matrix
  ``G(e^{j\omega T}) + G^T(e^{-j\omega T})``, or a condition depending on ``\omega``:
  ``hermitian-part``; so is an expression (no relation) in ``\cos(\omega T)`` with the device
  damping ``b``;
* any other inequality on the parameters: ``passivity-condition`` (``sufficient-condition`` or
  ``necessary-condition`` when the sentence before says only that), unless it is an integral
  (an energy inequality), a norm or ``|...| < 1`` (small gain), or ``X > 0`` with no minus sign
  (a positivity step of a proof): ``None``;
* other equations (models, definitions, ``= 0`` symmetry conditions): ``None``.

Passivity or stability cannot be told apart by shape (``b + B > KT/2`` is Gil's stability
condition, ``b > KT/2 + B`` Colgate's passivity condition): the reason says so and the reviewer
picks ``stability-condition`` when the paper proves the condition by loop stability.

>>> guess_claim(r'b > \frac{KT}{2} + B')[0]
'passivity-condition'
>>> guess_claim(r'b > \frac{KT}{2} - B\cos(\omega T)')[0]
'hermitian-part'
>>> guess_claim(r'G^{-1}(z) = b + \frac{KT}{z-1}')[0]
'inverse-transfer'
>>> guess_claim(r'e = x_m - x_s')
(None, 'an equation (a model or a definition): no claim kind checks it')
>>> symbols_of(r'b > \frac{K_{01}T}{2} - B\cos(\omega T)')
{'b': 'positive', 'K_{01}': 'positive', 'T': 'positive', 'B': 'nonnegative', 'omega': 'real'}
"""

from __future__ import annotations

import re

from hapticproof.audit.source.displays import trailing_number

__all__ = ["guess_claim", "guess_form", "has_inequality", "symbols_of", "symbol_guesses", "relations", "period_names"]

_TOKEN = re.compile(r"\\(?:[A-Za-z]+|.)|\s+|.", re.S)
_INEQUALITIES = {"<", ">", "\\le", "\\leq", "\\ge", "\\geq", "\\leqslant", "\\geqslant", "\\lt", "\\gt", "\\ll", "\\gg"}
_RELATIONS = _INEQUALITIES | {"=", "\\neq", "\\ne", "\\approx", "\\equiv"}
_REAL_PART = re.compile(r"\\Re(?![A-Za-z])|\\(?:text|mathrm|operatorname|rm)\s*\{\s*Re\s*\}|\\real(?![A-Za-z])")
_RESIDUE = re.compile(r"\\(?:mathrm|operatorname\*?|text|rm)\s*\{\s*Res\s*\}|\\Res(?![A-Za-z])")
_INVERSE = re.compile(r"G(?:_\{?[A-Za-z0-9]*\}?)?\s*\^\s*\{\s*-\s*1\s*\}\s*\(\s*z\s*\)|G\s*\(\s*z\s*\)\s*\^\s*\{\s*-\s*1\s*\}")
_FORCE = re.compile(r"^F_\{?h\}?\s*\(\s*z\s*\)")
_VELOCITY = re.compile(r"V_\{?h\}?\s*\(\s*z\s*\)")
_HERMITIAN_MATRIX = re.compile(r"G\s*\(\s*e\^\{\s*j\\omega\s*T\s*\}\s*\)\s*\+\s*G\s*\^\s*\{?\s*[TH*]\s*\}?\s*\(\s*e\^\{\s*-\s*j\\omega\s*T\s*\}\s*\)")
_FREQUENCY = re.compile(r"\\omega(?![A-Za-z])")
_COSINE = re.compile(r"\\cos\s*\(?\s*\\omega")
_DAMPING = re.compile(r"(?<![A-Za-z\\])b(?![A-Za-z])")
_RESIDUE_NAME = re.compile(r"^R_\{?0\}?\s*$")


def _tokens(text: str) -> list[str]:
    return _TOKEN.findall(text)


def _unbox(text: str) -> str:
    r"""``\boxed{X}`` -> ``X`` (braces matched)."""
    while True:
        m = re.search(r"\\boxed\s*\{", text)
        if m is None:
            return text
        depth = 0
        for j in range(m.end() - 1, len(text)):
            depth += (text[j] == "{") - (text[j] == "}")
            if depth == 0:
                text = text[:m.start()] + text[m.end():j] + text[j + 1:]
                break
        else:
            return text[:m.start()] + text[m.end():]


def _clean(text: str) -> str:
    r"""The display without number, label, ``\boxed``, alignment wrappers, ``&``, ``\left``/``\right``."""
    s = re.sub(r"\\(?:tag\*?|label)\s*\{[^{}]*\}", " ", text)
    found = trailing_number(s, commands=False)     # (linear: no back-tracking on long runs of spaces)
    if found and found[0] > 0:
        s = s[:found[0]]
    s = re.sub(r"\\begin\{(?:aligned|split|gathered|alignedat)\}(?:\{\d+\})?|\\end\{(?:aligned|split|gathered|alignedat)\}",
               " ", s)
    s = _unbox(s)
    s = re.sub(r"\\(?:left|right|big|Big|bigg|Bigg)(?![A-Za-z])", "", s)
    return " ".join(s.replace("&", " ").split())


def _main_part(tokens: list[str]) -> list[str]:
    r"""Drop a leading ``\text{A)}`` label and trailing index qualifiers (``\quad i = 1, \dots, m``)."""
    pieces: list[list[str]] = [[]]
    depth = 0
    for tok in tokens:
        depth += (tok == "{") - (tok == "}")
        if depth == 0 and tok in ("\\quad", "\\qquad"):
            pieces.append([])
            continue
        pieces[-1].append(tok)
    kept = []
    for k, piece in enumerate(pieces):
        text = "".join(piece).strip().rstrip(",.")
        if k == 0 and re.fullmatch(r"\\text\{\s*[A-Z]\)\s*\}", text):
            continue
        if k > 0 and re.fullmatch(r",?\s*(?:\\text\{[^{}]*\}\s*)?[a-z](?:\s*,\s*[a-z])*\s*(?:=|\\neq|\\ne|\\in)\s*.*", text):
            continue
        kept.append(piece)
    return [tok for k, piece in enumerate(kept) for tok in (piece if k == 0 else [" ", "\\quad", " ", *piece])]


#: a period as prose names it: "sampling period $h$", "sampled with period $h$", "samples every $h$"
_PERIOD_PROSE = re.compile(r"(?:sampling|sample)\s+(?:period|interval|time)s?\s+(?:of\s+|is\s+)?\$([^$]{1,20})\$|"
                          r"(?:sampled|samples?)\s+(?:with|at|every)\s+(?:a\s+)?(?:period\s+)?\$([^$]{1,20})\$", re.I)
#: a period as a formula names it: the name multiplying the frequency (``\omega h``, ``e^{s h}``)
_PERIOD_MATH = re.compile(r"\\omega\s*([A-Za-z](?:_\{?[A-Za-z0-9]+\}?)?)|e\^\{\s*s\s*([A-Za-z](?:_\{?[A-Za-z0-9]+\}?)?)\s*\}")


def period_names(prose: str = "", math: str = "") -> list[str]:
    r"""The printed names of the sampling period that ``prose`` states ("sampled with period
    $h$") and ``math`` multiplies the frequency by (``\cos(\omega h)``), in order, once each.

    >>> period_names("The device is sampled with period $h$.", r"\cos(\omega T_s) + e^{s h}")
    ['h', 'T_s']
    """
    found = ["\\omega " + (m.group(1) or m.group(2)).strip() for m in _PERIOD_PROSE.finditer(prose)]
    out: list[str] = []
    for text in (*found, math):
        for m in _PERIOD_MATH.finditer(text):
            name = m.group(1) or m.group(2)
            if name not in out:
                out.append(name)
    return out


def relations(text: str) -> list[tuple[str, str]]:
    r"""The top-level relations of a display (outside braces and inner environments): the
    operator and the member after it, the first member with operator ``""``.

    >>> relations(r'b > \frac{KT}{2} \quad i = 1, \dots, m')
    [('', 'b'), ('>', '\\frac{KT}{2}')]
    """
    tokens = _main_part(_tokens(_clean(text)))
    members: list[tuple[str, list[str]]] = [("", [])]
    depth = env = 0
    k = 0
    while k < len(tokens):
        tok = tokens[k]
        if tok == "{":
            depth += 1
        elif tok == "}":
            depth -= 1
        elif tok == "\\begin":
            env += 1
        elif tok == "\\end":
            env -= 1
        elif depth == 0 and env == 0 and tok in _RELATIONS:
            members.append((tok, []))
            k += 1
            continue
        elif depth == 0 and env == 0 and tok == "\\\\":       # a row break of an aligned display
            members[-1][1].append(" ")
            k += 1
            continue
        members[-1][1].append(tok)
        k += 1
    return [(op, "".join(toks).strip()) for op, toks in members]


def has_inequality(text: str) -> bool:
    r"""Whether the display has a top-level inequality (``>``, ``\geq``...).

    >>> has_inequality(r'b_{\min_{i}} > 0'), has_inequality(r'\min_{i,j \neq i} B_{ij} = 1')
    (True, False)
    """
    return any(op in _INEQUALITIES for op, _ in relations(text))


def _last_sentence(context: str) -> str:
    parts = re.split(r"(?<=[.;:])\s+", context.strip())
    return parts[-1].lower() if parts else ""


def _only_positive(member: str) -> bool:
    """A member with no minus sign whose names are all guessed positive or nonnegative."""
    if "-" in member or not member:
        return False
    guesses = symbol_guesses(member)
    return bool(guesses) and all(word.split(",")[0] in ("positive", "nonnegative") for word, _ in guesses.values())


def guess_claim(display_text: str, *, context: str = "") -> tuple[str | None, str]:
    r"""The paper-file claim a display's shape suggests, and why; ``None`` when the shape does
    not say.

    Parameters
    ----------
    display_text : str
        The display (its ``\tag`` or printed number may be there: they are ignored).
    context : str, optional
        The prose just before the display: ``residue``, ``sufficient`` or ``necessary`` in its
        last sentence refine a guess, never make one from nothing.

    Returns
    -------
    (str or None, str)
        A claim of ``hapticproof.paperfile.CLAIMS`` (or ``None``) and a short reason.

    Examples
    --------
    >>> guess_claim(r'b > KT + 2B', context='it is sufficient to have')
    ('sufficient-condition', 'a bound on the parameters that the sentence before calls sufficient')
    >>> guess_claim(r'\|\mathscr{M}\mathscr{N}\|_{\infty} < 1')[0] is None
    True
    """
    text = _clean(display_text)
    if not text:
        return None, "an empty display"
    sentence = _last_sentence(context)
    members = relations(text)
    ops = [op for op, _ in members[1:]]
    first = members[0][1]
    if _RESIDUE.search(text):
        return "residue", "it takes a residue (\\mathrm{Res}): the residue at z = 1"
    if not ops:
        if _REAL_PART.search(text):
            return "hermitian-part", "an expression of a real part: Re G^{-1}(e^{j\\omega T})"
        if _COSINE.search(text) and _DAMPING.search(text):
            return "hermitian-part", "an expression in \\cos(\\omega T) with the damping b: read as Re G^{-1}(e^{j\\omega T})"
        return None, "an expression without a relation: no claim kind says what it is"
    inequality = any(op in _INEQUALITIES for op in ops)
    if not inequality:
        if all(op == "=" for op in ops):
            rest = [m for _, m in members[1:]]
            if _INVERSE.fullmatch(first.replace(" ", "")) or _INVERSE.fullmatch(first):
                return "inverse-transfer", "G^{-1}(z) = ...: compared with G^{-1}(z) of the scene"
            if _FORCE.match(first) and any(_VELOCITY.search(m) for m in rest):
                explicit = [m for m in rest if not re.fullmatch(r"G(?:_\{?\w*\}?)?\^\{-1\}\(z\)\s*V_\{?h\}?\(z\)", m.replace(" ", ""))]
                if not explicit:
                    return None, "F_h(z) = G^{-1}(z)V_h(z) names G^{-1} without saying what it is: nothing to compare"
                return "inverse-transfer", "F_h(z) = ... V_h(z): the factor of V_h(z) is G^{-1}(z) of the scene"
            if _RESIDUE_NAME.match(first) or ("residue" in sentence and "\\begin{bmatrix}" in text):
                return "residue", "R_0 = ... (or a matrix the text calls a residue): the residue at z = 1"
            if _REAL_PART.match(first) or (_HERMITIAN_MATRIX.search(first) and rest and rest[-1].strip() != "0"):
                return "hermitian-part", "the real part (or a minor of G + G^H) written out: Re G^{-1}(e^{j\\omega T})"
        return None, "an equation (a model or a definition): no claim kind checks it"
    if "\\int" in text:
        return None, "an energy inequality (an integral): no claim kind checks it"
    if "\\|" in text or (ops == ["<"] and members[-1][1] == "1"):
        return None, "a small-gain (norm) condition: no claim kind checks it"
    if _REAL_PART.search(text):
        return "hermitian-part", "a bound through a real part Re{...}: Re G^{-1}(e^{j\\omega T}) >= 0 at each frequency"
    if _HERMITIAN_MATRIX.search(text):
        return "hermitian-part", "a minor of G(e^{j\\omega T}) + G^T(e^{-j\\omega T}): the Hermitian part, at each frequency"
    if _FREQUENCY.search(text):
        return "hermitian-part", "a condition that depends on the frequency \\omega: Re G^{-1}(e^{j\\omega T}) >= 0 at each frequency"
    clauses = [c for c in re.split(r",\s*\\q?quad(?![A-Za-z])", text) if c.strip()]
    if all(re.fullmatch(r"\s*[A-Za-z](?:_\{?[A-Za-z0-9]+\}?)?\s*(?:>|\\geq?|\\ge)\s*0\s*(?:[.,]\s*)?", c) for c in clauses):
        return None, "sign conditions on single parameters: state them as assumptions in [symbols]"
    if (members[-1][1] == "0" and ops[-1] in (">", "\\geq", "\\ge") and _only_positive(members[-2][1])
            and not _DAMPING.search(members[-2][1])):
        return None, "X > 0 with no minus sign and no damping b holds for positive parameters: a step of a proof, not a claim"
    if "sufficient" in sentence and "necessary" not in sentence:
        return "sufficient-condition", "a bound on the parameters that the sentence before calls sufficient"
    if "necessary" in sentence and "sufficient" not in sentence:
        return "necessary-condition", "a bound on the parameters that the sentence before calls necessary"
    if _DAMPING.search(text) or re.search(r"(?<![A-Za-z\\])b_", text):
        return "passivity-condition", ("a bound on the parameters without frequency: read as the exact passivity condition "
                                       "(stability-condition if the paper proves it by loop stability)")
    return "passivity-condition", ("a bound on the parameters without the device damping b: read as a passivity condition; "
                                   "set solve_for to the parameter it bounds")


def guess_form(display_text: str, claim: str | None, context: str = "") -> str | None:
    r"""``"condition"`` for a ``hermitian-part`` display without a relation that the prose before
    lists among conditions (``b + Brac{1 + \cos(\omega T)}{2}`` after "the conditions ... are
    found as follows": its ``> 0`` was lost), else ``None`` (the form as printed).

    >>> guess_form(r'b + B rac{1 + \cos(\omega T)}{2}', 'hermitian-part', 'the conditions are found as follows:')
    'condition'
    >>> guess_form(r'b - rac{KT}{2} + B\cos(\omega T)', 'hermitian-part', 'the real part is')
    """
    if claim != "hermitian-part" or len(relations(display_text)) > 1:
        return None
    sentence = _last_sentence(context)
    return "condition" if re.search(r"\bconditions?\b", sentence) else None


# ---------------------------------------------------------------------------------------------
# symbols
# ---------------------------------------------------------------------------------------------

_GREEK = frozenset("alpha beta gamma delta epsilon varepsilon zeta eta theta vartheta iota kappa lambda mu nu xi pi "
                   "rho sigma tau upsilon phi varphi chi psi omega ell Gamma Delta Theta Lambda Xi Pi Sigma Upsilon "
                   "Phi Psi Omega".split())
_DECORATIONS = frozenset("mathbf mathcal mathscr mathbb mathfrak boldsymbol bar tilde hat dot ddot vec overline".split())
_SKIP_ARGUMENT = frozenset("text mathrm operatorname label tag begin end textrm textit mbox rm".split())
_BOUND_SCRIPTS = frozenset("sum prod min max lim sup inf".split())     # their scripts bind an index
_WORDS = ("diag", "det", "Res", "Re", "Im", "min", "max", "lim", "cos", "sin", "exp", "log", "ln", "tan")
_MARKS = frozenset({"T", "H", "*", "c", "\\prime", "+", "-"})   # transpose, conjugate, star, C^+...
_NOT_SYMBOLS = frozenset("zsj")       # transform variables and the imaginary unit
_SIGNAL_LETTERS = frozenset("FVXUYfvxuy")
_ARGUMENT_LIKE = re.compile(r"-?j\\omega|\\omega|z|s|t|\\tau|i|k|kT|n|z\^\{-1\}|e\^\{[^{}]*\}|[iktn]\s*[+-]\s*\d|"
                            r"kT\s*[+-]\s*[TK]|j\\omega\s*\+\s*jn\\omega(?:_s)?|\\omega\s*\+\s*n\\omega_s|y(?:_\w)?|0|"
                            r"e\^\{[^{}]*\}\)?")


def _group(tokens: list[str], k: int) -> tuple[str, int]:
    """The text of the brace group (or single token) at ``tokens[k]`` and the index after it."""
    while k < len(tokens) and tokens[k].isspace():
        k += 1
    if k >= len(tokens):
        return "", k
    if tokens[k] != "{":
        return tokens[k], k + 1
    depth, j = 0, k
    while j < len(tokens):
        depth += (tokens[j] == "{") - (tokens[j] == "}")
        if depth == 0:
            return "".join(tokens[k + 1:j]), j + 1
        j += 1
    return "".join(tokens[k + 1:]), len(tokens)


def _parenthesised(tokens: list[str], k: int) -> str | None:
    """The content of ``( ... )`` starting at ``tokens[k]`` (spaces skipped), else None."""
    while k < len(tokens) and tokens[k].isspace():
        k += 1
    if k >= len(tokens) or tokens[k] != "(":
        return None
    depth = 0
    for j in range(k, len(tokens)):
        depth += (tokens[j] == "(") - (tokens[j] == ")")
        if depth == 0:
            return "".join(tokens[k + 1:j])
    return None


def _script(sub: str) -> str:
    sub = " ".join(sub.split())
    return "_" + sub if len(sub) == 1 else "_{" + sub + "}"


def _assumption(base: str, sub: str, key: str) -> tuple[str, str]:
    letter = base.lstrip("\\")
    if base.startswith("\\") and letter in _GREEK:
        if letter in ("alpha",):
            return "positive", "a scale factor"
        return "real", "a frequency, angle or coefficient"
    if "{" in base:                               # \mathbf{Z}, \bar{C}
        return "real", "a decorated name (a matrix?): a paper file declares scalars"
    if letter == "b":
        return "positive", "a device damping"
    if letter == "B":
        return "nonnegative", "a virtual damping (real if it may be negative)"
    if letter in ("K", "k"):
        return "positive", "a stiffness or a controller gain"
    if letter == "T":
        return "positive", "the sampling period"
    if letter == "t":
        return ("nonnegative", "a delay") if sub.startswith("d") else ("real", "time")
    if letter in ("m", "M"):
        return "positive", "a mass (or the number of users)"
    if letter == "n":
        return "integer", "a delay in samples"
    if letter == "z" and sub.startswith("a"):
        return "nonnegative", "an operator's shortage of passivity"
    if letter == "c":
        return "real", "cos(\\omega T)"
    if letter == "S":
        return "real", "defined in the text? declare its LaTeX definition instead"
    return "real", "no convention for this letter"


def _family(sub: str) -> bool:
    return any(letter in sub for letter in "ij") and not re.fullmatch(r"[a-hk-z]+", sub)


def symbol_guesses(display_text: str) -> dict[str, tuple[str, str]]:
    r"""Each name a display uses, with a guessed ``[symbols]`` word and the reason.

    Names are keyed as a paper file declares them: ``K_{01}``, ``b_m``, ``omega`` (Greek by
    name), ``G^{-1}`` (``function``), ``F_h`` (``signal``), ``K_{ij}`` (an indexed family,
    ``positive, symmetric``). ``z``, ``s``, ``j``, ``e^{...}``, ``H(...)`` and ``C(...)`` (the
    scene's environment and controller) and bound indices are not listed.

    >>> symbol_guesses(r'F_h(z) = G^{-1}(z)V_h(z)')['G^{-1}']
    ('function', 'applied to (z)')
    """
    tokens = _tokens(_clean(display_text))
    out: dict[str, tuple[str, str]] = {}
    k = 0
    while k < len(tokens):
        tok = tokens[k]
        if tok.startswith("\\") and tok[1:].isalpha():
            name = tok[1:]
            if name in _SKIP_ARGUMENT:            # \text{...}, \operatorname{Re}: words, not names
                _, k = _group(tokens, k + 1)
                continue
            if name in _BOUND_SCRIPTS:            # \sum_{k=1}^{m}: the bound index is no symbol
                k += 1
                while k < len(tokens) and tokens[k] in ("_", "^"):
                    _, k = _group(tokens, k + 1)
                continue
            if name in _DECORATIONS:
                inner, after = _group(tokens, k + 1)
                if not re.fullmatch(r"[A-Za-z]", inner.strip()):
                    k += 1
                    continue
                base, k = f"\\{name}{{{inner.strip()}}}", after
            elif name in _GREEK:
                base, k = tok, k + 1
            else:
                k += 1
                continue
        elif tok == "^" and _group(tokens, k + 1)[0].replace(" ", "") in _MARKS:
            k = _group(tokens, k + 1)[1]          # ^T, ^*, ^c after a bracket: a mark, no symbol
            continue
        elif tok.isalpha() and len(tok) == 1:
            word = next((w for w in _WORDS if "".join(tokens[k:k + len(w)]) == w), None)
            if word and (k == 0 or not tokens[k - 1].isalpha()):
                k += len(word)
                continue
            base, k = tok, k + 1
        else:
            k += 1
            continue
        while k < len(tokens) and tokens[k] == "'":     # Z' is a name of its own
            base, k = base + "'", k + 1
        sub = ""
        if k < len(tokens) and tokens[k] == "_":
            sub, k = _group(tokens, k + 1)
            sub = " ".join(sub.split())
        inverse = False
        while k < len(tokens) and tokens[k] == "^":
            sup, after = _group(tokens, k + 1)
            sup_clean = sup.replace(" ", "")
            if sup_clean == "-1":
                inverse, k = True, after
            elif sup_clean in _MARKS:          # a transpose, conjugate or star: a mark, not a power
                k = after
            else:
                break
        argument = _parenthesised(tokens, k)
        applied = argument is not None and _ARGUMENT_LIKE.fullmatch(argument.strip()) is not None
        letter = base.lstrip("\\")
        if base == "e" and k < len(tokens) and tokens[k] == "^":
            continue
        if base == "d" and k < len(tokens) and tokens[k] in ("\\tau", "t", "\\omega"):
            continue
        if base in _NOT_SYMBOLS and not sub:
            continue
        key = (letter if base.startswith("\\") and letter in _GREEK else base) + (_script(sub) if sub else "")
        if applied and not inverse and base in ("H", "C") and not sub:
            continue
        if applied or inverse:
            if inverse:
                out.setdefault(key + "^{-1}", ("function", f"applied to ({argument})" if applied else "an inverse"))
            elif letter[:1] in _SIGNAL_LETTERS and "{" not in base and not _family(sub):
                out.setdefault(key, ("signal", f"applied to ({argument}): a signal"))
            else:
                out.setdefault(key, ("function", f"applied to ({argument})"))
            continue
        word, reason = _assumption(base, sub, key)
        if sub and _family(sub):
            if letter in ("K", "B", "k") and re.fullmatch(r"[ij]{2}", sub.replace(" ", "")):
                word += ", symmetric"
            reason += "; an indexed family (index letters i, j)"
        out.setdefault(key, (word, reason))
    return out


def symbols_of(display_text: str) -> dict[str, str]:
    r"""The names a display uses, each with a guessed assumption word (see :func:`symbol_guesses`).

    >>> symbols_of(r'b_m > \frac{T}{1 - \cos \omega T} \operatorname{Re} \{ (1 - e^{-j\omega T}) C_m(e^{j\omega T}) \}')
    {'b_m': 'positive', 'T': 'positive', 'omega': 'real', 'C_m': 'function'}
    """
    return {name: word for name, (word, _) in symbol_guesses(display_text).items()}
