r"""Verdicts of a paper read as its definitions: definitions, identities and conditions.

* a **definition** binds its name: ``confirmed`` (it is what the paper says it is); a second
  definition of a bound name is an identity with the first, ``inconsistent`` when they differ;
* an **identity** is decided exactly in the algebra of :mod:`~hapticproof.audit.definitions.values`:
  ``confirmed`` when the sides are equal as rational functions (of ``z``, ``s``, ``c = cos(omega T)``
  or ``x = omega^2`` and the parameters), else ``wrong`` with an exact point where they differ;
* a **condition** is compared with the exact condition for the property its sentence claims
  (:func:`hapticproof.analysis.immittance.exact_condition`) with the claimed strength: closed forms by
  :func:`hapticproof.audit.claimbase.compare_conditions`; otherwise exact decisions at sample points
  find counterexamples, and a lower bound is proved sufficient by substituting it into each
  frequency condition (every term a non-negative parameter monomial times a polynomial in ``c``
  or ``x`` that the kernel proves non-negative) and necessary by an endpoint of the frequency range.

A display that uses names no definition gives, or a construct outside the exact algebra, is
``undecided`` with the reason: never a verdict from a guess.
"""

from __future__ import annotations

import functools

from collections.abc import Mapping
from fractions import Fraction
from types import SimpleNamespace
from typing import Any

import sympy as sp

from hapticproof.audit.definitions.reading import (CONDITION, DEFINITION, DERIVED, IDENTITY, MALFORMED, MODEL, REDEFINED,
                                                   PaperReading, Reading)
from hapticproof.audit.definitions.radicals import has_roots
from hapticproof.audit.definitions.values import BOUNDARY, PARAM, Environment, Unbound, Unsupported, Value, evaluate
from hapticproof.exact.transfer import CONTINUOUS, DISCRETE
from hapticproof.core.errors import HapticproofError
from hapticproof.core.evidence import Decision, Evidence, Finding, Method, Verdict
from hapticproof.core.symbols import omega as OMEGA
from hapticproof.core.symbols import s as S_SYM
from hapticproof.core.symbols import z as Z_SYM
from sympy.core.function import AppliedUndef
from hapticproof.exact.boundaryvalue import C_NAME, X_NAME
from hapticproof.exact.rational import RationalFunction

__all__ = ["verdict", "identity_finding", "condition_finding", "resolved_condition"]

_STRENGTH_CLAIM = {"iff": "passivity", "sufficient": "sufficient", "necessary": "necessary"}
#: the frequency and angle names: never a parameter an object must carry
_FREQUENCY = {"omega", "theta", "vartheta"}


_NEGATIVE = (Verdict.WRONG, Verdict.TYPO, Verdict.INCONSISTENT, Verdict.NEEDS_ASSUMPTION, Verdict.CONSERVATIVE)


def verdict(reading: Reading, paper: PaperReading, *, about: str | None = None, prop: str | None = None,
            strength: str | None = None) -> Finding:
    """The finding of one display read by ``paper``; a defect found through a name that a derived,
    unverified display bound is only ``undecided`` (the fault may be that display's)."""
    if reading.environment is not None:
        reading.environment.used.clear()
    finding = _verdict(reading, paper, about=about, prop=prop, strength=strength)
    used = set(reading.environment.used) if reading.environment is not None else set()
    doubtful = sorted(used & paper.tentative)
    if finding.verdict in _NEGATIVE and doubtful:
        shown = ", ".join(f"{_shown(n)} ({reading.defined_at.get(n, '?')})" for n in doubtful)
        return Finding(Verdict.UNDECIDED, f"{finding.detail}; but it rests on {shown}, which the paper derives and the toolkit "
                       "did not verify", finding.evidence, derived=finding.derived)
    return finding


def _verdict(reading: Reading, paper: PaperReading, *, about: str | None, prop: str | None, strength: str | None) -> Finding:
    if reading.kind == MALFORMED:
        what = reading.error or reading.note or "not a well-formed equation"
        if reading.error and not _syntax_error(reading.error):
            return Finding(Verdict.UNDECIDED, f"the reader cannot read the display: {what}", Evidence(Method.PARSE))
        return Finding(Verdict.MALFORMED, f"the display does not read: {what}", Evidence(Method.PARSE))
    if reading.kind == REDEFINED:
        return Finding(Verdict.UNDECIDED, f"{', '.join(_shown(n) for n in reading.binds)} is {reading.note}",
                       Evidence(Method.PARSE, facts={"binds": list(reading.binds)}))
    if reading.kind == DERIVED:
        names = ", ".join(_shown(n) for n in reading.binds)
        return Finding(Verdict.UNDECIDED, f"the paper derives {names} here; the toolkit binds it as printed but cannot re-derive "
                       "it from the paper's definitions", Evidence(Method.PARSE, facts={"binds": list(reading.binds)}))
    if reading.kind == DEFINITION:
        names = ", ".join(_shown(n) for n in reading.binds)
        note = f" ({reading.note})" if reading.note else ""
        return Finding(Verdict.CONFIRMED, f"a definition: it binds {names}{note}",
                       Evidence(Method.CANONICAL_FORM, facts={"binds": list(reading.binds)}))
    if reading.kind == MODEL:
        return Finding(Verdict.CONFIRMED, f"{reading.note}: it defines how the signals are related (nothing to derive)",
                       Evidence(Method.PARSE))
    if reading.kind == IDENTITY and reading.expected is not None:
        return _against_expected(reading)
    if reading.kind == IDENTITY:
        return identity_finding(reading, paper)
    if reading.kind == CONDITION:
        return condition_finding(reading, paper, about=about, prop=prop, strength=strength)
    return Finding(Verdict.UNDECIDED, f"not read as a definition, an identity or a condition{': ' + reading.note if reading.note else ''}",
                   Evidence(Method.PARSE))


def _syntax_error(message: str) -> bool:
    """A parse error that is the display's own (unbalanced delimiters, a missing side), not a
    construct the reader does not know."""
    return any(w in message for w in ("unbalanced", "unmatched", "missing left-hand side", "missing right-hand side",
                                      "never closed", "empty"))


def _shown(name: str) -> str:
    return name.replace("^-1", "^{-1}")


# ---------------------------------------------------------------------------------------------
# identities
# ---------------------------------------------------------------------------------------------


def identity_finding(reading: Reading, paper: PaperReading) -> Finding:
    """Every side of the display's equations against the first, exactly."""
    env = reading.environment or Environment()
    signals = _signals(reading, paper)
    if signals:
        return Finding(Verdict.CONFIRMED, f"a model equation among the signals {', '.join(sorted(signals))} "
                       "(it defines how they are related; nothing to derive)",
                       Evidence(Method.PARSE, facts={"signals": sorted(signals)}))
    cases = _sign_cases([t for r in reading.main for t in r.terms])
    if cases:
        return _identity_by_cases(reading, paper, cases)
    relations, env, how = _complex_entries(reading, paper, env)
    values = []
    try:
        for relation in relations:
            values.append([evaluate(t, env, roots=True) for t in relation.terms])
    except Unbound as err:
        return Finding(Verdict.UNDECIDED, f"{err} (names: {', '.join(sorted(err.names))})",
                       Evidence(Method.PARSE, facts={"unbound": sorted(err.names)}))
    except (Unsupported, ZeroDivisionError, ValueError) as err:
        return Finding(Verdict.UNDECIDED, f"the display is outside the exact algebra: {err}", Evidence(Method.PARSE))
    for row in values:
        first = row[0]
        for other in row[1:]:
            try:
                diff = first - other
            except Unsupported as err:
                return Finding(Verdict.UNDECIDED, f"the sides are not comparable: {err}", Evidence(Method.PARSE))
            if not diff.is_zero and has_roots(diff):
                return _with_roots(reading, paper, first, diff, how)
            if not diff.is_zero:
                general = _instantiated(first, other, paper)
                if general is not None:
                    first, other, diff = general
                    if diff.is_zero:
                        return Finding(Verdict.CONFIRMED, "both sides are equal identically once the general two-port's "
                                       "entries are those the model gives", Evidence(Method.CANONICAL_FORM))
                return _differ(reading, first, other, diff)
    earlier = _earlier_definition(reading)
    if earlier:
        return Finding(Verdict.CONFIRMED, f"the display restates {earlier}: equal identically", Evidence(Method.CANONICAL_FORM))
    if how:
        return Finding(Verdict.CONFIRMED, f"both sides are equal identically {how}",
                       Evidence(Method.CANONICAL_FORM, facts={"kind": values[0][0].kind}))
    return Finding(Verdict.CONFIRMED, "both sides are equal identically (the difference cancels exactly)",
                   Evidence(Method.CANONICAL_FORM, facts={"kind": values[0][0].kind}))


def _complex_entries(reading: Reading, paper: PaperReading, env: Environment) -> tuple[list[Any], Environment, str]:
    r"""A display taking real parts or moduli of a general two-port's entries (``\Re z_{11}``,
    ``|h_{12} h_{21}|``): where one side is the section's model, the entries are those its port
    matrix has; otherwise each other matrix's entries are converted to one matrix's
    (``h_{11} = \det Z / z_{22}`` from the port relations) and these read as complex unknowns.
    Returns the relations to evaluate, the environment and how the entries were read."""
    import dataclasses

    from hapticproof.audit.definitions.ports import TWO_PORT_LETTERS, two_port_entry
    from hapticproof.audit.definitions.signals import letter_of

    system = paper.system
    matrices = {letter_of(m): m for m in system.ports}
    letters = TWO_PORT_LETTERS | set(matrices)
    terms = [t for r in reading.main for t in r.terms if not isinstance(t, sp.MatrixBase)]
    # an entry the paper binds by a conversion (h_11 in z_ij) is read from the port relations
    # instead, so a slip in that definition, flagged where it is printed, does not propagate
    entries = {s for t in terms for s in sp.sympify(t).free_symbols if two_port_entry(s.name, letters)
               and (env.bindings.get(s.name) is None or two_port_entry(s.name, letters)[0] in matrices)}
    bound = {two_port_entry(s.name, letters)[0] for s in entries if env.bindings.get(s.name) is not None}
    if not entries or not any(sp.sympify(t).has(sp.re, sp.im, sp.Abs, sp.conjugate) for t in terms):
        return list(reading.main), env, ""
    per_term = [{two_port_entry(s.name, letters)[0] for s in sp.sympify(t).free_symbols if s in entries} for t in terms]
    used = set().union(*per_term)
    image: dict[sp.Symbol, Any] = {}
    how = ""
    if any(not p for p in per_term) and all(letter in matrices for letter in used):
        # one side is the model: its port matrices' entries, as the relations give them
        for letter in used:
            rows = system.matrix(matrices[letter])
            if rows is None:
                return list(reading.main), env, ""
            for s in entries:
                found = two_port_entry(s.name, {letter})
                if found:
                    image[s] = rows[found[1]][found[2]].to_sympy(_TRANSFER_SYMBOLS)
        how = "once the general two-port's entries are those the model gives"
    else:
        source = sorted(used, key=lambda letter: (letter in bound, -sum(letter in p for p in per_term), letter))[0]
        complex_names = set()
        for letter in used - {source}:
            if letter not in matrices or source not in matrices:
                return list(reading.main), env, ""
            rows = system.conversion(matrices[letter], matrices[source], {matrices[source]: source})
            if rows is None:
                return list(reading.main), env, ""
            for s in entries:
                found = two_port_entry(s.name, {letter})
                if found:
                    converted = rows[found[1]][found[2]]
                    image[s] = converted.to_sympy({n: sp.Symbol(n) for n in converted.names})
                    complex_names |= converted.names
        complex_names |= {s.name for s in entries if two_port_entry(s.name, {source})}
        continuous = any(sp.sympify(t).has(S_SYM, OMEGA) for t in terms) or not paper.periods
        env = dataclasses.replace(env, complex_names=frozenset(complex_names),
                                  complex_domain=CONTINUOUS if continuous else DISCRETE)
        how = (f"for complex {', '.join(sorted(complex_names))}"
               + (f" (the other entries converted by the port relations of {matrices[source]})" if image else ""))
    if not image:
        return list(reading.main), env, how
    relations = [dataclasses.replace(r, terms=tuple(t if isinstance(t, sp.MatrixBase) else sp.sympify(t).xreplace(image)
                                                    for t in r.terms)) for r in reading.main]
    return relations, env, how


def _with_roots(reading: Reading, paper: PaperReading, first: Value, diff: Value, how: str) -> Finding:
    """An identity with square roots (moduli of complex values): reduced exactly, or a point."""
    from hapticproof.audit.definitions.radicals import value_zero

    signs, _relations = _signs(reading, paper)
    found = value_zero(diff, signs)
    facts = {"kind": first.kind, "roots": True}
    if found.zero is True:
        return Finding(Verdict.CONFIRMED, "both sides are equal identically: the square roots reduce exactly (each radicand "
                       "factored, the roots of distinct factors independent)" + (f", {how}" if how else ""),
                       Evidence(Method.CANONICAL_FORM, facts=facts))
    if found.zero is False and found.assumed:
        difference = found.witness.pop("difference")
        return Finding(Verdict.NEEDS_ASSUMPTION, f"the sides are equal only where {' and '.join(found.assumed)}, which the "
                       f"paper does not state: at {_point_text(found.witness)} they differ by {difference}",
                       Evidence(Method.COUNTEREXAMPLE, witness=found.witness, facts={**facts, "assumption": found.assumed}))
    if found.zero is False:
        earlier = _earlier_definition(reading)
        difference = found.witness.pop("difference")
        verdict = Verdict.INCONSISTENT if earlier else Verdict.WRONG
        what = f"the display contradicts {earlier}" if earlier else "the sides differ"
        return Finding(verdict, f"{what}: at {_point_text(found.witness)} the difference is {difference}",
                       Evidence(Method.COUNTEREXAMPLE, witness=found.witness, facts=facts))
    return Finding(Verdict.UNDECIDED, f"the sides are written with square roots: {found.reason}",
                   Evidence(Method.CANONICAL_FORM, facts=facts))


def _instantiated(first: Value, other: Value, paper: PaperReading) -> tuple[Value, Value, Value] | None:
    """One side written for a general two-port (``z_{ij}``), the other for the section's: the
    general side with the entries the model determines."""
    from hapticproof.audit.definitions.signals import generic_names, instantiate

    a, b = generic_names(first, paper), generic_names(other, paper)
    if bool(a) == bool(b):
        return None
    try:
        if a:
            first = instantiate(first, paper)
        else:
            other = instantiate(other, paper)
        if first is None or other is None:
            return None
        return first, other, first - other
    except (Unsupported, ZeroDivisionError, ValueError):
        return None


def _against_expected(reading: Reading) -> Finding:
    """The printed right-hand side against what the paper's model or port relations give."""
    env = reading.environment or Environment()
    try:
        printed = evaluate(reading.main[0].terms[1], env)
        diff = printed - reading.expected
    except Unbound as err:
        return Finding(Verdict.UNDECIDED, f"{err} (names: {', '.join(sorted(err.names))})", Evidence(Method.PARSE))
    except (Unsupported, ZeroDivisionError, ValueError) as err:
        return Finding(Verdict.UNDECIDED, f"the display is outside the exact algebra: {err}", Evidence(Method.PARSE))
    if diff.is_zero:
        return Finding(Verdict.CONFIRMED, f"the printed display is {reading.expected_how}: equal identically",
                       Evidence(Method.CANONICAL_FORM))
    witness = _witness(diff)
    if witness is None:
        return Finding(Verdict.UNDECIDED, f"the printed display differs from {reading.expected_how}, but no point was found",
                       Evidence(Method.CANONICAL_FORM))
    difference = witness.pop("difference")
    evidence = Evidence(Method.COUNTEREXAMPLE, witness=witness)
    if not printed.is_scalar and printed.shape[0] == printed.shape[1] and (printed.transpose() - reading.expected).is_zero:
        corrected = _transposed_latex(reading.printed or reading.text)
        return Finding(Verdict.TYPO, f"the off-diagonal entries are swapped: the transposed matrix is {reading.expected_how}; as "
                       f"printed the entries differ at {_point_text(witness)} (difference {difference})", evidence,
                       corrected=corrected)
    return Finding(Verdict.WRONG, f"the printed display differs from {reading.expected_how}: at {_point_text(witness)} the "
                   f"difference is {difference}", evidence)


def _transposed_latex(text: str) -> str | None:
    """The display with its (first) matrix transposed, written as printed (``bmatrix`` rows and cells)."""
    import re

    m = re.search(r"\\begin\{([bpv]?matrix)\}(.*?)\\end\{\1\}", text, re.S)
    if not m:
        return None
    rows = [[cell.strip() for cell in row.split("&")] for row in re.split(r"\\\\(?:\[[^\]]*\])?", m.group(2)) if row.strip()]
    if not rows or any(len(r) != len(rows) for r in rows):
        return None
    body = r" \\ ".join(" & ".join(rows[j][i] for j in range(len(rows))) for i in range(len(rows)))
    return text[:m.start(2)] + " " + body + " " + text[m.end(2):]


def _sign_cases(terms: list[Any]) -> list[dict[sp.Symbol, sp.Expr]]:
    """The sign cases of the parameters a display takes the modulus of (``|g_1|``): each symbol
    ``x`` under ``|x|`` is ``u`` or ``-u`` with ``u >= 0``; none when there is no such modulus."""
    from itertools import product

    symbols = set()
    for t in terms:
        if isinstance(t, sp.MatrixBase):
            continue
        for a in sp.sympify(t).atoms(sp.Abs):
            if a.args[0].is_Symbol and a.args[0] != OMEGA:
                symbols.add(a.args[0])
    if not symbols or len(symbols) > 4:
        return []
    ordered = sorted(symbols, key=lambda s: s.name)
    fresh = {x: sp.Symbol(x.name, nonnegative=True) for x in ordered}
    return [{x: sign * fresh[x] for x, sign in zip(ordered, signs)} for signs in product((1, -1), repeat=len(ordered))]


def _identity_by_cases(reading: Reading, paper: PaperReading, cases: list[dict[sp.Symbol, sp.Expr]]) -> Finding:
    """An identity with moduli of parameters, decided in each sign case (the modulus is then the
    parameter or its negative): equal in every case, or a witness in the case where it is not."""
    import dataclasses

    env = reading.environment or Environment()
    for case in cases:
        relations = []
        for relation in reading.main:
            terms = tuple(sp.sympify(t).xreplace(case) if not isinstance(t, sp.MatrixBase) else t for t in relation.terms)
            relations.append(dataclasses.replace(relation, terms=terms))
        try:
            values = [[evaluate(t, env) for t in r.terms] for r in relations]
        except (Unbound, Unsupported, ZeroDivisionError, ValueError) as err:
            return Finding(Verdict.UNDECIDED, f"the display is outside the exact algebra: {err}", Evidence(Method.PARSE))
        for row in values:
            for other in row[1:]:
                diff = row[0] - other
                if diff.is_zero:
                    continue
                shown = ", ".join(f"{x} {'>= 0' if v.could_extract_minus_sign() is False else '<= 0'}" for x, v in case.items())
                witness = _witness(diff)
                if witness is None:
                    return Finding(Verdict.UNDECIDED, f"the sides differ where {shown}, but no point was found",
                                   Evidence(Method.CANONICAL_FORM))
                difference = witness.pop("difference")
                # the witness in the paper's own names: u is |x|, the case's sign gives x
                point = {}
                for k, v in witness.items():
                    x = next((x for x in case if x.name == k), None)
                    point[k] = str(-sp.Rational(v)) if x is not None and case[x].could_extract_minus_sign() else v
                return Finding(Verdict.WRONG, f"the sides differ where {shown}: at {_point_text(point)} the difference is "
                               f"{difference}", Evidence(Method.COUNTEREXAMPLE, witness=point, facts={"case": shown}))
    return Finding(Verdict.CONFIRMED, f"both sides are equal identically in each sign case of "
                   f"{', '.join(sorted({x.name for c in cases for x in c}))}", Evidence(Method.CANONICAL_FORM))


#: the transfer variables' internal names in a port matrix's entries, as the printed symbols
_TRANSFER_SYMBOLS = {"$s": S_SYM, "$z": Z_SYM}

_SIGNAL_BASES = ("f", "v", "x", "F", "V", "X", "u", "y", "q", "p", "tau", "e", "E")
_DECORATED = ("dot", "ddot", "tilde", "hat")


def _signals(reading: Reading, paper: PaperReading) -> set[str]:
    r"""The signals of a model equation (``f_h - f_m = m_m \ddot{x}_m + b_m \dot{x}_m``,
    ``Z_m v_m = f_h - k_f f_e``, ``s X_m(s) = ...``): at least two names that are a signal's --
    a signal's letter (``f``, ``v``, ``x``, ``F``, ...), a time derivative or estimate
    (``\dot{x}``, ``\tilde{F}``), or a transform no definition binds (``X_m(s)``) -- that no
    definition of the paper binds or uses, and every term of the equation carrying one."""
    import re

    used = set(paper.bindings) | {n for b in paper.bindings.values() if not _renames(b.value) for n in b.value.names}
    pattern = re.compile(r"(?:\\(?:" + "|".join(_DECORATED) + r")\{)?(?:" + "|".join(_SIGNAL_BASES) + r")(?:\}|_|$|\^)")

    def is_signal(name: str) -> bool:
        return name not in used and bool(pattern.match(name))

    diffs = []
    signals: set[str] = set()
    for relation in reading.main:
        terms = [sp.sympify(t) for t in relation.terms]
        if any(isinstance(t, sp.MatrixBase) for t in terms):
            return set()
        replaced = []
        for t in terms:
            def swap(e: Any) -> Any:
                name = e.func.__name__
                if name in paper.bindings:
                    return e
                return sp.Symbol(f"{name}(" + ",".join(map(str, e.args)) + ")", real=True)
            t = t.replace(lambda e: isinstance(e, AppliedUndef), swap)
            replaced.append(t)
        for t in replaced:
            signals |= {s.name for s in t.free_symbols if is_signal(s.name.split("(")[0]) or (
                "(" in s.name and s.name.split("(")[0] not in paper.bindings)}
        for a, b in zip(replaced, replaced[1:]):
            diffs.append(sp.expand(a - b))
    if len(signals) < 2:
        return set()
    for diff in diffs:
        for term in sp.Add.make_args(diff):
            if term != 0 and not ({s.name for s in term.free_symbols} & signals):
                return set()
    return {n.split("(")[0] for n in signals}


def _renames(value: Value) -> bool:
    """A value that is one parameter itself (``f_1 = f_h``: a port variable named again)."""
    if value.kind != PARAM or not value.is_scalar:
        return False
    e = value.rows[0][0]
    if len(e.names) != 1:
        return False
    v = RationalFunction.variable(next(iter(e.names)))
    return e == v or e == -v


def _earlier_definition(reading: Reading) -> str | None:
    from hapticproof.audit.definitions.reading import definition_target

    if not reading.main:
        return None
    target = definition_target(reading.main[0].terms[0])
    if target is None or target[0] not in reading.defined_at:
        return None
    return f"the definition of {_shown(target[0])} in ({reading.defined_at[target[0]]})"


def _differ(reading: Reading, first: Value, other: Value, diff: Value) -> Finding:
    witness = _witness(diff)
    earlier = _earlier_definition(reading)
    facts = {"kind": first.kind}
    if earlier:
        source = earlier.split("(")[-1].rstrip(")")
        return Finding(Verdict.INCONSISTENT, f"the display contradicts {earlier}: they differ"
                       + (f" at {_point_text(witness)}" if witness else ""),
                       Evidence(Method.COUNTEREXAMPLE, witness=witness, facts={**facts, "other": source}))
    if witness is None:
        return Finding(Verdict.UNDECIDED, "the sides differ as rational functions but no rational point where they differ "
                       "was found", Evidence(Method.CANONICAL_FORM, facts=facts))
    return Finding(Verdict.WRONG, f"the sides differ: at {_point_text(witness)} the difference is {witness.pop('difference')}",
                   Evidence(Method.COUNTEREXAMPLE, witness=witness, facts=facts))


def _point_text(point: Mapping[str, Any]) -> str:
    return ", ".join(f"{k} = {v}" for k, v in point.items() if k != "difference")


def _witness(diff: Value) -> dict[str, Any] | None:
    """An exact point where a non-zero difference is non-zero (parameters, and ``z``/``s`` or
    ``c``/``x``)."""
    import random

    rng = random.Random(7)
    entries = [(i, j, e) for i, row in enumerate(diff.rows) for j, e in enumerate(row)]
    for i, j, e in entries:
        parts = [e] if not hasattr(e, "re0") else [e.re0, e.re1, e.im0, e.im1]
        for part in parts:
            if part.is_zero:
                continue
            names = sorted(part.names)
            for attempt in range(200):
                point = {}
                for name in names:
                    if name == C_NAME:
                        point[name] = Fraction(rng.randint(-9, 9), 10)
                    elif name == X_NAME:
                        point[name] = Fraction(rng.randint(1, 40), 4)
                    else:
                        point[name] = Fraction(rng.choice([1, 2, 3, 5, 7, 1, 2]), rng.choice([1, 2, 3, 10]))
                try:
                    value = part.evaluate(point)
                except ZeroDivisionError:
                    continue
                if value != 0:
                    shown = {_public(k): str(v) for k, v in point.items()}
                    if not diff.is_scalar:
                        shown["entry"] = f"({i + 1}, {j + 1})"
                    shown["difference"] = str(value)
                    return shown
    return None


def _public(name: str) -> str:
    return {C_NAME: "c", X_NAME: "x", "$z": "z", "$s": "s"}.get(name, name)


# ---------------------------------------------------------------------------------------------
# conditions
# ---------------------------------------------------------------------------------------------


def _claimed(reading: Reading, paper: PaperReading, prop: str | None, strength: str | None) -> tuple[str | None, str | None, str | None]:
    """The property, strength and named object of a condition: its sentence's, else (for the
    property and the object) those of the condition before it in the same passage ("a simpler
    bound, which is sufficient, is")."""
    claim = reading.claim
    prop = prop or (claim.property if claim else None)
    strength = strength or (claim.strength if claim else None)
    obj = claim.object if claim else None
    if prop is None and strength is not None:
        for earlier in reversed(paper.readings[:paper.readings.index(reading)] if reading in paper.readings else []):
            if earlier.kind == CONDITION and earlier.claim is not None and earlier.claim.property:
                prop = earlier.claim.property
                obj = obj or earlier.claim.object
                break
            if earlier.kind == DEFINITION:
                break
    return prop, strength, obj


def _object(reading: Reading, paper: PaperReading, names: list[str], prop: str, wanted: set[str]) -> tuple[str, Value, str] | None:
    """The bound object the condition is about: a name the file or the sentence gives, else the
    most recently bound square object that carries every parameter of the condition (2 x 2 for
    absolute stability), else the first such object the paper defines later ("the sampled-data
    wall is passive whenever ..." in an introduction)."""
    env = reading.environment or Environment()
    for text in names:
        name = _object_name(text)
        if name is not None and env.lookup(name) is not None and env.lookup(name).value.kind != PARAM:
            return name, env.lookup(name).value, "named"
        if name is not None and name in paper.bindings and paper.bindings[name].value.kind != PARAM:
            return name, paper.bindings[name].value, "named, defined later in the paper"

    def fits(value: Value) -> bool:
        if value.kind == PARAM or value.shape[0] != value.shape[1]:
            return False
        if prop == "absolutely-stable" and value.shape != (2, 2):
            return False
        if prop == "positive-real" and reading.claim is not None and reading.claim.noun == "two-port" and value.shape != (2, 2):
            return False
        return wanted <= set(value.names)

    for name in reversed(list(env.bindings)):
        if fits(env.bindings[name].value):
            return name, env.bindings[name].value, "the latest defined object with every name of the condition"
    for name in paper.order:
        if name not in env.bindings and fits(paper.bindings[name].value):
            return name, paper.bindings[name].value, "defined later in the paper"
    return None


def _object_name(text: str) -> str | None:
    import re

    from hapticproof.audit.reader.names import normalise_name, sympy_name

    text = text.strip()
    m = re.match(r"(.+?)\s*\((?:z|s)\)\s*$", text)
    core = m.group(1) if m else text
    try:
        return sympy_name(normalise_name(core))
    except (HapticproofError, ValueError):
        return None


def _printed_condition(reading: Reading) -> Any:
    links = []
    for relation in reading.main:
        expr = relation.as_sympy()
        if isinstance(expr, sp.And):
            links += list(expr.args)
        else:
            links.append(expr)
    if not links or any(getattr(link, "rel_op", None) in ("==", "!=") for link in links):
        return None
    cond = links[0] if len(links) == 1 else sp.And(*links)
    subs = {sp.Symbol(k, real=True): v for k, v in reading.substitutions.items()}
    return cond.xreplace(subs) if subs else cond


def _signs(reading: Reading, paper: PaperReading) -> tuple[dict[str, dict[str, bool]], list[Any]]:
    """The sign of each name the paper states (global and local assumptions, periods positive)
    and the other relations (ranges, orderings) of this display."""
    signs: dict[str, dict[str, bool]] = {name: {"positive": True} for name in paper.periods}
    relations = []
    flat = []
    for a in list(paper.assumptions) + list(reading.assumptions):
        flat += list(a.args) if isinstance(a, sp.And) else [a]
    for a in flat:
        if not isinstance(a, sp.core.relational.Relational):
            continue
        if a.lhs.is_Symbol and a.rhs.is_number and a.rhs == 0 and a.rel_op in (">", ">="):
            signs.setdefault(a.lhs.name, {}).update({"positive": True} if a.rel_op == ">" else {"nonnegative": True})
        elif a.rhs.is_Symbol and a.lhs.is_number and a.lhs == 0 and a.rel_op in ("<", "<="):
            signs.setdefault(a.rhs.name, {}).update({"positive": True} if a.rel_op == "<" else {"nonnegative": True})
        else:
            relations.append(a)
    for name, kw in signs.items():
        if kw.get("positive"):
            kw.pop("nonnegative", None)
    return signs, relations


def _symbol_map(names: set[str], signs: dict[str, dict[str, bool]]) -> dict[str, sp.Symbol]:
    return {n: sp.Symbol(n, real=True, **signs.get(n, {})) for n in names}


def _retyped(expr: Any, table: dict[str, sp.Symbol]) -> Any:
    return expr.xreplace({s: table[s.name] for s in expr.free_symbols if s.name in table})


def resolved_condition(reading: Reading, paper: PaperReading, any_object: bool = False) -> Any:
    """``(about, property, strength, how)`` of a condition as its sentence and the namespace settle
    them (``about`` in printed form), or ``None`` when the sentence leaves the property or the
    strength open, or no defined object carries the condition's names."""
    prop, strength, named = _claimed(reading, paper, None, None)
    printed = _printed_condition(reading)
    guessed = ""
    if printed is not None and prop is None and strength is None and _damping_bound(printed):
        # a bare lower bound on a damping with no word around it: read as the passivity condition
        prop, strength, guessed = "positive-real", "iff", " (the sentence says nothing: read as the exact passivity condition)"
    if printed is None or prop not in ("positive-real", "absolutely-stable") or strength is None:
        return None
    if reading.claim is not None and reading.claim.for_any:
        return None
    if prop == "absolutely-stable" and general_entries(reading, paper, printed) is not None:
        return None if any_object else (None, prop, strength, "a general two-port's entries (Llewellyn's criterion)" + guessed)
    wanted = {s.name for s in printed.free_symbols} - set(reading.substitutions) - _FREQUENCY
    found = _object(reading, paper, [named] if named else [], prop, wanted)
    if found is None:
        return "no object" if any_object else None
    if any_object:
        return None
    name, _value, how = found
    return _printed_name(name, paper), prop, strength, how + guessed


def _damping_bound(printed: Any) -> bool:
    """A lower bound on a device damping (``b > ...``, ``c_d \\ge ...``, ``b_m > ...``)."""
    import re

    from hapticproof.audit.definitions.proofs import lower_bound

    dampings = [s for s in printed.free_symbols if re.match(r"(?:b|c_d|c)(?:_|$)", s.name)]
    return isinstance(printed, sp.core.relational.Relational) and lower_bound(printed, dampings) is not None


def _printed_name(name: str, paper: PaperReading) -> str:
    from hapticproof.audit.reader.names import sympy_name

    for printed in list(paper.functions) + list(paper.symbols):
        if sympy_name(printed) == name:
            return printed
    return _shown(name)


def condition_finding(reading: Reading, paper: PaperReading, *, about: str | None = None, prop: str | None = None,
                      strength: str | None = None) -> Finding:
    """A printed condition against the exact condition of the property it claims."""

    prop, strength, named = _claimed(reading, paper, prop, strength)
    printed = _printed_condition(reading)
    if printed is None:
        return Finding(Verdict.MALFORMED, "the display is not a condition (an inequality) on the parameters", Evidence(Method.PARSE))
    if reading.claim is not None and reading.claim.for_any:
        return Finding(Verdict.UNDECIDED, f"a claim for every {reading.claim.for_any}: the paper defines one such object, and "
                       "one instance proves nothing about all of them", Evidence(Method.PARSE))
    frequency = _frequency_wise(reading, paper, printed)
    if frequency is not None:
        return frequency
    if prop not in ("positive-real", "absolutely-stable"):
        return Finding(Verdict.UNDECIDED, "the sentence does not say what the condition is for (positive real, passive, "
                       "absolutely stable)", Evidence(Method.PARSE))
    if strength is None:
        return Finding(Verdict.UNDECIDED, "the sentence does not say whether the condition is necessary, sufficient or both",
                       Evidence(Method.PARSE))
    general = _general_two_port(reading, paper, printed, prop, strength)
    if general is not None:
        return general
    wanted = {s.name for s in printed.free_symbols} - set(reading.substitutions) - _FREQUENCY
    found = _object(reading, paper, [n for n in (about, named) if n], prop, wanted)
    if found is None:
        return Finding(Verdict.UNDECIDED, f"no defined object carries every name of the condition ({', '.join(sorted(wanted))})",
                       Evidence(Method.PARSE))
    name, value, how = found
    if value.kind == BOUNDARY:
        return Finding(Verdict.UNDECIDED, f"{_shown(name)} is a value on the boundary, not a transfer function", Evidence(Method.PARSE))
    matrix = value.matrix()
    signs, relations = _signs(reading, paper)
    what = f"the printed condition for {_shown(name)} {prop.replace('-', ' ')}"
    cases = _sign_cases([printed])
    if cases:
        return _condition_by_cases(printed, matrix, prop, strength, what, signs, relations, cases,
                                   {"object": _shown(name), "object_from": how, "property": prop, "strength": strength})
    table = _symbol_map({s.name for s in printed.free_symbols} | set(matrix.parameters), signs)
    printed = _retyped(printed, table)
    relations = [_retyped(r, table) for r in relations if {s.name for s in r.free_symbols} <= set(table)]
    exact = _exact_condition(matrix, prop, tuple(sorted(table.items())))
    facts = {"object": _shown(name), "object_from": how, "property": prop, "strength": strength, "exact_method": exact.method}
    f = _compared(printed, exact, strength, what, relations, facts)
    if f.verdict != Verdict.WRONG:
        return f
    # a condition that fails only where the object's own poles leave the disk (a filter pole
    # |a| > 1 the paper did not exclude) needs that assumption
    poles = [p.condition for p in exact.parts if p.form is None and p.condition not in (None, sp.true, sp.false)]
    if not poles:
        return f
    inside = sp.And(*poles)
    trial = _compared(printed, exact, strength, what, relations + [inside], facts)
    if trial.verdict in (Verdict.CONFIRMED, Verdict.CONSERVATIVE):
        return Finding(Verdict.NEEDS_ASSUMPTION, f"{what} holds only where the poles of {_shown(name)} lie in the closed disk "
                       f"({sp.sstr(inside)}), which the paper does not state: there {trial.detail}; as printed: {f.detail}",
                       Evidence(f.evidence.method, witness=f.evidence.witness, facts={**facts, "region": inside}),
                       corrected=None)
    return f


def general_entries(reading: Reading, paper: PaperReading, printed: Any) -> tuple[Any, str] | None:
    r"""The printed condition with the paper's formulas written out (``\eta(\omega)``), and the
    letter of the general two-port's entries it is written in, when every name is such an entry."""
    from hapticproof.audit.definitions.ports import TWO_PORT_LETTERS, two_port_entry
    from hapticproof.audit.definitions.signals import letter_of

    expanded = printed
    for f in printed.atoms(AppliedUndef):
        formula = paper.formulas.get(f.func.__name__)
        if formula is None:
            continue
        expr, variable = formula
        if variable is not None and len(f.args) == 1:
            expr = sp.sympify(expr).xreplace({s: f.args[0] for s in sp.sympify(expr).free_symbols if s.name == variable})
        expanded = expanded.xreplace({f: expr})
    if expanded.atoms(AppliedUndef):
        return None
    letters = TWO_PORT_LETTERS | {letter_of(m) for m in paper.system.ports}
    names = {s.name for s in expanded.free_symbols} - _FREQUENCY - set(reading.substitutions)
    found = {two_port_entry(n, letters) for n in names}
    if not names or None in found or any(n in paper.bindings for n in names):
        return None
    used = {entry[0] for entry in found}
    return (expanded, used.pop()) if len(used) == 1 else None


@functools.lru_cache(maxsize=64)
def _exact_condition(matrix: Any, prop: str, table: tuple) -> Any:
    """:func:`~hapticproof.analysis.immittance.exact_condition`, once per object, property and
    names (a repair search tries up to 80 edits of one display about the same object)."""
    from hapticproof.analysis.immittance import exact_condition

    return exact_condition(matrix, prop, dict(table))


def _general_two_port(reading: Reading, paper: PaperReading, printed: Any, prop: str, strength: str) -> Finding | None:
    """A condition on a general two-port's entries (Llewellyn's criterion restated), not on an
    object the paper defines."""
    from hapticproof.audit.definitions.twoport import llewellyn_finding

    general = general_entries(reading, paper, printed)
    if general is None or prop != "absolutely-stable":
        return None
    return llewellyn_finding(general[0], general[1], strength)


def _condition_by_cases(printed: Any, matrix: Any, prop: str, strength: str, what: str, signs: dict[str, dict[str, bool]],
                        relations: list[Any], cases: list[dict[sp.Symbol, sp.Expr]], facts: dict[str, Any]) -> Finding:
    """A condition with moduli of parameters (``\\alpha|g_0|``): decided in each sign case, where
    ``x <= 0`` is read as ``x -> -x`` with ``x >= 0`` in the condition and the object alike; a
    witness is told in the paper's signs."""
    from hapticproof.analysis.immittance import exact_condition
    from hapticproof.exact.rational import RationalFunction

    found = []
    for case in cases:
        flipped = {x.name for x, v in case.items() if v.could_extract_minus_sign()}
        case_signs = {k: dict(v) for k, v in signs.items()}
        for x in case:
            case_signs.setdefault(x.name, {})
            if not case_signs[x.name].get("positive"):
                case_signs[x.name]["nonnegative"] = True
        table = _symbol_map({s.name for s in printed.free_symbols} | set(matrix.parameters), case_signs)
        swap = {x: table[x.name] * (-1 if x.name in flipped else 1) for x in case}
        case_printed = _retyped(printed.xreplace({x: sp.Symbol(x.name, real=True) for x in case}).xreplace(
            {sp.Symbol(x.name, real=True): swap[x] for x in case}), table)
        case_matrix = matrix.subs({n: -RationalFunction.variable(n) for n in flipped if n in matrix.parameters})
        case_relations = [_retyped(r.xreplace({sp.Symbol(n, real=True): -sp.Symbol(n, real=True) for n in flipped}), table)
                          for r in relations if {s.name for s in r.free_symbols} <= set(table)]
        exact = exact_condition(case_matrix, prop, table)
        f = _compared(case_printed, exact, strength, what, case_relations, {**facts, "exact_method": exact.method})
        if f.verdict == Verdict.WRONG:
            witness = {k: (str(-sp.Rational(v)) if k in flipped else v) for k, v in (f.evidence.witness or {}).items()}
            shown = ", ".join(f"{n} <= 0" for n in sorted(flipped)) or "every modulus of a non-negative parameter"
            return Finding(Verdict.WRONG, f"{f.detail} (in the case {shown})", Evidence(f.evidence.method, witness=witness,
                                                                                       facts=dict(f.evidence.facts)))
        found.append(f.verdict)
    names = ", ".join(sorted({x.name for c in cases for x in c}))
    if all(v == Verdict.CONFIRMED for v in found):
        return Finding(Verdict.CONFIRMED, f"{what}: right in every sign case of {names}", Evidence(Method.ENDPOINT_ANALYSIS, facts=facts))
    if all(v in (Verdict.CONFIRMED, Verdict.CONSERVATIVE) for v in found):
        return Finding(Verdict.CONSERVATIVE, f"{what}: sufficient in every sign case of {names}, not necessary in some",
                       Evidence(Method.ENDPOINT_ANALYSIS, facts=facts))
    return Finding(Verdict.UNDECIDED, f"{what}: not settled in every sign case of {names} ({', '.join(v.value for v in found)})",
                   Evidence(Method.INSTANCES, facts=facts))


def _compared(printed: Any, exact: Any, strength: str, what: str, relations: list[Any], facts: dict[str, Any]) -> Finding:
    """The printed condition against the exact one, under ``relations``: closed forms first."""
    if exact.condition is not None and exact.condition is not sp.false:
        from hapticproof.audit.claimbase import compare_conditions

        cond = sp.And(exact.condition, *relations) if relations else exact.condition
        printed_cond = sp.And(printed, *relations) if relations else printed
        try:
            f = compare_conditions(printed_cond, cond, _state(), claim=_STRENGTH_CLAIM[strength], what=what, verify=exact.verify)
        except (TypeError, ValueError, NotImplementedError, AssertionError) as err:
            f = Finding(Verdict.UNDECIDED, f"{what}: the comparison with the exact condition {sp.sstr(exact.condition)} "
                        f"did not conclude ({err})", Evidence(Method.PARSE))
        if f.verdict != Verdict.UNDECIDED:
            return _with_facts(f, facts)
        proved = _closed_form_proofs(printed, exact.condition, strength, what, facts)
        if proved is not None:
            return proved
    return _decided(printed, exact, strength, what, relations, facts)


def _nonnegative_form(relation: Any) -> Any:
    """``lhs - rhs`` of ``lhs >= rhs`` (``rhs - lhs`` of ``<=``) over a denominator of known sign
    cleared, or ``None``."""
    if not isinstance(relation, sp.core.relational.Relational):
        return None
    if relation.rel_op in (">", ">="):
        form = relation.lhs - relation.rhs
    elif relation.rel_op in ("<", "<="):
        form = relation.rhs - relation.lhs
    else:
        return None
    num, den = sp.fraction(sp.cancel(sp.together(form)))
    if den.is_positive:
        return sp.expand(num)
    if den.is_negative:
        return sp.expand(-num)
    return form


def _closed_form_proofs(printed: Any, exact: Any, strength: str, what: str, facts: dict[str, Any]) -> Finding | None:
    """``printed => exact`` and ``exact => printed`` by small certificates (:func:`~hapticproof.audit.definitions.proofs.implies`)
    on each conjunct, when the comparison of bounds did not conclude."""
    from hapticproof.audit.definitions.proofs import implies

    p_parts = list(printed.args) if isinstance(printed, sp.And) else [printed]
    e_parts = list(exact.args) if isinstance(exact, sp.And) else [exact]
    p_forms = [_nonnegative_form(r) for r in p_parts]
    e_forms = [_nonnegative_form(r) for r in e_parts]
    if any(f is None for f in p_forms + e_forms):
        return None
    suff = all(any(implies(pf, ef) for pf in p_forms) for ef in e_forms)
    nec = all(any(implies(ef, pf) for ef in e_forms) for pf in p_forms)
    shown = sp.sstr(exact)
    if strength == "sufficient" and suff:
        return Finding(Verdict.CONFIRMED, f"{what} implies the exact condition {shown} (proved)", Evidence(Method.CANONICAL_FORM, facts=facts))
    if strength == "necessary" and nec:
        return Finding(Verdict.CONFIRMED, f"{what} follows from the exact condition {shown} (proved)", Evidence(Method.CANONICAL_FORM, facts=facts))
    if strength == "iff" and suff and nec:
        return Finding(Verdict.CONFIRMED, f"{what} is equivalent to the exact condition {shown} (both implications proved)",
                       Evidence(Method.CANONICAL_FORM, facts=facts))
    return None


def _with_facts(f: Finding, facts: Mapping[str, Any]) -> Finding:
    merged = dict(f.evidence.facts)
    merged.update(facts)
    return Finding(f.verdict, f.detail, Evidence(f.evidence.method, witness=f.evidence.witness, instances=f.evidence.instances,
                                                 facts=merged), derived=f.derived, corrected=f.corrected)


def _state() -> Any:
    spec = SimpleNamespace(solve_for=None, scene=None, claim="condition")
    return SimpleNamespace(spec=spec, scene=None, repairing=False, repairable=False)


def _decided(printed: Any, exact: Any, strength: str, what: str, relations: list[Any], facts: dict[str, Any]) -> Finding:
    """Without a usable closed form: proofs of sufficiency and necessity of a printed bound, and
    exact decisions at sample points for counterexamples."""
    from hapticproof.audit.definitions.proofs import lower_bound, lower_bounds, necessary, sufficient

    weaker, stronger, count = _samples(printed, exact, relations)
    if strength in ("iff", "sufficient") and weaker is not None:
        return Finding(Verdict.WRONG, f"{what} holds at the witness where the exact decision fails ({weaker[1]})",
                       Evidence(Method.COUNTEREXAMPLE, witness=weaker[0], facts=facts))
    if strength == "necessary" and stronger is not None:
        return Finding(Verdict.WRONG, f"{what} fails at the witness where the property holds: it is not necessary",
                       Evidence(Method.COUNTEREXAMPLE, witness=stronger[0], facts=facts))
    from hapticproof.audit.definitions.proofs import chart, intervals

    ranges = intervals(relations)
    change = chart({x: r for x, r in ranges.items() if x in printed.free_symbols or x.name in exact.matrix.parameters})
    forms = [sp.sympify(p.form).subs(change, simultaneous=True) for p in exact.parts if p.form is not None]
    pole_parts = [p.condition for p in exact.parts if p.form is None]
    poles_ok = all(c is sp.true or (c is not None and c is not sp.false and all(
        _holds_in_range(link, ranges) or _stated(link, relations) for link in (c.args if isinstance(c, sp.And) else [c])))
        for c in pole_parts)
    lo, hi = (-1, 1) if exact.matrix.domain == "discrete" else (0, None)
    printed = printed.subs({x: e for x, e in change.items()}, simultaneous=True) if change else printed
    order = sorted(printed.free_symbols, key=lambda s: (s.name not in ("b", "c_d"), s.name))
    bound = lower_bound(printed, order) if isinstance(printed, sp.core.relational.Relational) else None
    bounds = lower_bounds(printed, order)
    suff = nec = False
    if bounds is not None and forms:
        suff = poles_ok and sufficient(bounds, None, forms, exact.t, lo, hi)
    if bound is not None and forms:
        v, g = bound
        nec = necessary(v, g, forms, exact.t, lo, hi)
    facts = {**facts, "instances": count}
    if strength == "sufficient" and suff and stronger is not None and not nec:
        return Finding(Verdict.CONSERVATIVE, f"{what} is sufficient (proved term by term) but not necessary: the property "
                       "holds at the witness where it fails", Evidence(Method.COUNTEREXAMPLE, witness=stronger[0], facts=facts))
    if strength == "sufficient" and suff:
        return Finding(Verdict.CONFIRMED, f"{what} is sufficient: with it every condition at every frequency holds (proved "
                       "term by term)", Evidence(Method.ENDPOINT_ANALYSIS, facts=facts))
    if strength == "necessary" and nec:
        return Finding(Verdict.CONFIRMED, f"{what} is necessary: it is the exact condition at an end of the frequency range",
                       Evidence(Method.ENDPOINT_ANALYSIS, facts=facts))
    if strength == "iff" and suff and nec:
        return Finding(Verdict.CONFIRMED, f"{what} is necessary and sufficient: the exact condition at an end of the frequency "
                       "range, and with it every condition at every frequency holds (proved term by term)",
                       Evidence(Method.ENDPOINT_ANALYSIS, facts=facts))
    if strength == "iff" and suff and stronger is not None:
        return Finding(Verdict.CONSERVATIVE, f"{what} is sufficient (proved term by term) but not necessary: the property holds "
                       "at the witness where it fails", Evidence(Method.COUNTEREXAMPLE, witness=stronger[0], facts=facts))
    if strength == "iff" and nec and weaker is None and stronger is None:
        return Finding(Verdict.UNDECIDED, f"{what} is necessary (the exact condition at an end of the frequency range); "
                       f"sufficiency was not proved ({count} exact samples agree)", Evidence(Method.INSTANCES, instances=count, facts=facts))
    note = "; it is not necessary (the property holds at a point where it fails)" if stronger is not None and strength == "iff" else ""
    return Finding(Verdict.UNDECIDED, f"{what}: no closed form of the exact condition; the exact decision agrees at {count} "
                   f"sample points{note}",
                   Evidence(Method.INSTANCES, instances=count, witness=stronger[0] if note else None, facts=facts))


def _stated(link: Any, relations: list[Any]) -> bool:
    """A pole condition that a stated relation implies (``g_0 + g_1 >= 0`` for the residue ``h(g_0 + g_1)``)."""
    from hapticproof.audit.definitions.proofs import implies

    target = _nonnegative_form(link) if isinstance(link, sp.core.relational.Relational) else None
    if target is None:
        return False
    for r in relations:
        form = _nonnegative_form(r) if isinstance(r, sp.core.relational.Relational) else None
        if form is not None and implies(form, target):
            return True
    return False


def _holds_in_range(link: Any, ranges: Mapping[sp.Symbol, tuple[Any, Any]]) -> bool:
    """A pole condition (``a >= -1``) that a stated range (``-1 <= a <= 1``) implies."""
    if not isinstance(link, sp.core.relational.Relational):
        return False
    if link.lhs.is_Symbol and link.rhs.is_number and link.lhs in ranges:
        lo, hi = ranges[link.lhs]
        if link.rel_op in (">", ">=") and lo is not None:
            return bool(lo >= link.rhs)
        if link.rel_op in ("<", "<=") and hi is not None:
            return bool(hi <= link.rhs)
    return False


def _samples(printed: Any, exact: Any, relations: list[Any], tries: int = 120) -> tuple[Any, Any, int]:
    from hapticproof.audit.claimbase import holds_at
    from hapticproof.exact.canonical import Sampler

    symbols = {s.name: s for s in printed.free_symbols}
    for name, sym in exact.symbols.items():
        if name in exact.matrix.parameters:
            symbols.setdefault(name, sym)
    weaker = stronger = None
    count = 0
    for point in Sampler(list(symbols.values()), seed=5).draw(tries):
        if any(holds_at(r, point) is False for r in relations):
            continue
        hp = holds_at(printed, point)
        if hp is None:
            continue
        out = exact.verify({s.name: v for s, v in point.items()})
        if out.decision not in (Decision.PROVED, Decision.DISPROVED):
            continue
        count += 1
        he = out.decision == Decision.PROVED
        if hp and not he and weaker is None:
            weaker = ({s.name: str(v) for s, v in point.items()}, out.reason)
        if he and not hp and stronger is None:
            stronger = ({s.name: str(v) for s, v in point.items()}, out.reason)
    return weaker, stronger, count


def _frequency_wise(reading: Reading, paper: PaperReading, printed: Any) -> Finding | None:
    r"""A condition at each frequency (``b - KT/2 + B\cos\omega T \ge 0``): it states ``Re X >= 0``
    of the bound object whose real part on the boundary is a positive multiple of its sides'
    difference; ``None`` when the display is not such a condition."""
    if not isinstance(printed, sp.core.relational.Relational) or len(reading.main) != 1:
        return None
    quantified = reading.frequency_range is not None or (reading.claim is not None and "\\omega" in reading.claim.sentence
                                                         and reading.claim.property == "positive-real")
    env = reading.environment or Environment()
    relation = reading.main[0]
    if len(relation.terms) != 2:
        return None
    try:
        lhs, rhs = (evaluate(t, env) for t in relation.terms)
        diff = lhs - rhs if relation.ops[0] in (">", ">=") else rhs - lhs
    except (Unbound, Unsupported, ValueError, ZeroDivisionError):
        return None
    if diff.kind != BOUNDARY and not quantified:
        return None
    if not diff.is_scalar:
        return None
    d = diff.on_boundary("discrete").rows[0][0] if diff.kind != BOUNDARY else diff.rows[0][0]
    if not d.is_rational_in_t:
        return None
    target = d.rational()
    for name in reversed(list(env.bindings)):
        value = env.bindings[name].value
        if value.kind != "transfer" or not value.is_scalar or value.domain != diff.domain and diff.kind == BOUNDARY:
            continue
        try:
            re_part = value.on_boundary().rows[0][0].real()
        except (ValueError, Unsupported):
            continue
        if re_part.is_zero:
            continue
        ratio = target / re_part
        if ratio.is_constant and ratio.constant_value() > 0:
            return Finding(Verdict.CONFIRMED, f"the condition at each frequency is Re {_shown(name)} >= 0 "
                           f"(its sides' difference is {ratio.constant_value()} times Re {_shown(name)}(e^(j omega T)))",
                           Evidence(Method.CANONICAL_FORM, facts={"object": _shown(name)}))
    return Finding(Verdict.UNDECIDED, "a condition at each frequency that is the real part of no defined object",
                   Evidence(Method.CANONICAL_FORM)) if diff.kind == BOUNDARY else None
