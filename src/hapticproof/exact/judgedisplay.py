"""What a report displays, re-derived from what it carries: ``hapticproof check`` refuses a
verdict or witness that the report's own evidence does not give (part of the checker: imports
only :mod:`hapticproof.exact.judge` and :mod:`hapticproof.exact.checkarith`)."""

from __future__ import annotations

import math
from collections.abc import Iterator, Mapping
from fractions import Fraction
from typing import Any

import flint

from hapticproof.core.naming import witness_keys
from hapticproof.exact.checkarith import CheckFailed, Gaussian, eval_transfer, exact_q
from hapticproof.exact.judge import consistent_witness, displayed_number

__all__ = ["derive_display", "finding_display", "boundary_display", "displayed_forms", "condition_display"]

#: Displayed expressions longer than this are not re-read (a degree-2000 Re G^-1 is shown by
#: its closed form and checked through the definition object alone).
MAX_SHOWN_CHARS = 20_000


#: The verdicts a judged claim supports (a finding showing another verdict is refused).
_VERDICTS = {
    ("circle-identity", "equal"): ("confirmed",),
    ("circle-identity", "differ"): ("wrong", "typo"),
    ("condition", "holds-not-passive"): ("wrong", "typo", "needs-assumption"),
    ("condition", "fails-passive"): ("wrong", "typo", "needs-assumption"),
    ("condition", "holds-passive"): ("confirmed", "conservative"),
}

#: The names of a positive-realness decision's pole conditions (the JSON of ``derive``).
_POLES, _SIMPLE, _RESIDUES = ("poles in |z| <= 1", "unit-circle poles simple", "Res/z0 >= 0 at unit-circle poles")


def _certificates_in(node: Any) -> Iterator[dict]:
    if isinstance(node, dict):
        if isinstance(node.get("certificate"), str):
            yield node
            return
        for value in node.values():
            yield from _certificates_in(value)
    elif isinstance(node, list):
        for value in node:
            yield from _certificates_in(value)


def _same(a: Any, b: Any) -> bool:
    """Equal as exact numbers where both are numbers, else as JSON."""
    if isinstance(a, dict) and isinstance(b, dict):
        return a.keys() == b.keys() and all(_same(a[k], b[k]) for k in a)
    if isinstance(a, (list, tuple)) and isinstance(b, (list, tuple)):
        return len(a) == len(b) and all(_same(x, y) for x, y in zip(a, b))
    na, nb = displayed_number(a), displayed_number(b)
    return na == nb


def condition_display(cond: Mapping[str, Any], keys: Mapping[str, str]) -> list[str]:
    """A derive condition's decision and witness against its own certificates (the witness's
    circle keys as the report names them, ``keys``)."""
    name, decision = cond.get("name"), cond.get("decision")
    evidence = cond.get("evidence", {})
    certs = list(_certificates_in(evidence))
    problems = []
    if name not in (_POLES, _SIMPLE, _RESIDUES):
        # a sign condition (Re G^-1 >= 0, a Hermitian part PSD): its certificates decide it
        signs = [c for c in certs if c["certificate"] in ("sign", "chebyshev-sign", "psd", "constant-psd")]
        if signs and decision in ("proved", "disproved") and all(c["holds"] for c in signs) != (decision == "proved"):
            problems.append(f"{name}: the decision says {decision}, its certificates say "
                            f"{'it holds' if decision == 'disproved' else 'it fails'}")
        witness = evidence.get("witness")
        for cert in signs:
            if cert["holds"] or not witness:
                continue
            own = cert["witness"] if isinstance(cert.get("witness"), dict) else \
                {"c": cert.get("witness"), "z": cert.get("witness_point")}
            for key in ("c", "z", "x", "omega"):
                shown = keys.get(key, key)
                if shown in witness and own.get(key) is not None and not _same(witness[shown], own[key]):
                    problems.append(f"{name}: the displayed {shown} = {witness[shown]} is not the certificate's {own[key]}")
            break
    elif name == _POLES:
        for cert in certs:
            if cert["certificate"] == "roots" and decision in ("proved", "disproved") and \
                    (cert["outside"] == 0) != (decision == "proved"):
                problems.append(f"{name}: the decision says {decision}, the roots certificate counts {cert['outside']} outside")
    elif name == _SIMPLE:
        for cert in certs:
            if cert["certificate"] == "roots" and decision in ("proved", "disproved"):
                simple = all(r.get("multiplicity") == 1 for r in cert.get("boundary", []))
                if simple != (decision == "proved"):
                    problems.append(f"{name}: the decision says {decision}, the roots certificate says simple = {simple}")
    elif name == _RESIDUES:
        residues = [c for c in certs if c["certificate"] == "residue"]
        if residues and decision in ("proved", "disproved") and all(c["holds"] for c in residues) != (decision == "proved"):
            problems.append(f"{name}: the decision says {decision}, the residue certificates disagree")
    # a network's conditions nest (Definition 3 inside the absolute stability, the conditions a
    # verdict rests on): each is held against its own certificates the same way
    nested = [cond.get("conditions"), (cond.get("rests_on") or {}).get("conditions")
              if isinstance(cond.get("rests_on"), Mapping) else None]
    for group in nested:
        for sub in group if isinstance(group, list) else ():
            if isinstance(sub, Mapping):
                problems += condition_display(sub, keys)
    return problems


def _combined(decisions: list[str]) -> str:
    for word in ("disproved", "undecided", "symbolic"):
        if word in decisions:
            return word
    return "proved"


def derive_display(report: Mapping[str, Any]) -> list[str]:
    """A ``derive --format json`` report's verdict and witness re-derived from its conditions
    and their certificates, and its ``definition`` (when present) held against both."""
    conditions = report.get("conditions") or []
    keys = witness_keys(report.get("notation"))
    problems = [p for cond in conditions for p in condition_display(cond, keys)]
    if not conditions or "verdict" not in report:
        return problems
    expected = _combined([c.get("decision") for c in conditions])
    definition = report.get("definition")
    refused = isinstance(definition, dict) and definition.get("judged", {}).get("ok") is False
    if refused:
        # the report itself says the judge disagreed: then (and only then) it shows 'undecided'
        if report["verdict"] != "undecided":
            problems.append(f"the verdict shown is {report['verdict']!r} although its definition check failed")
        if report.get("witness"):
            problems.append("a witness is shown for a verdict the definition check refused")
        return problems
    if report["verdict"] != expected:
        problems.append(f"the verdict shown is {report['verdict']!r}, its conditions give {expected!r}")
    summary = report.get("decision")               # a teleoperator's: the decision beside its verdict
    if isinstance(summary, Mapping) and summary.get("decision") != report["verdict"]:
        problems.append(f"the decision shown ({str(summary.get('decision'))[:20]}) is not the verdict {report['verdict']!r}")
    p5 = next((c for c in conditions if str(c.get("name", "")).startswith("(P5)")), None)
    if report.get("condition") in ("True", "False") and p5 is not None and p5.get("decision") in ("proved", "disproved") \
            and (report["condition"] == "True") != (p5["decision"] == "proved"):
        # a teleoperator's condition is (P5), h >= L(c) for all c, decided with its certificate
        problems.append(f"the condition shown ({report['condition']}) contradicts {p5['name']!r} ({p5['decision']})")
    if p5 is not None and "error_coordinate_damping" in report:
        problems += _error_damping(report["error_coordinate_damping"], p5)
    first = next((c for c in conditions if c.get("decision") == "disproved"), None)
    shown = report.get("witness")
    if first is not None and shown is not None:       # (a report that shows no witness shows none wrongly)
        own = first.get("evidence", {}).get("witness")
        if not _same(shown, own):
            problems.append(f"the witness shown {shown} is not the failing condition's ({first.get('name')}: {own})")
    elif shown:
        problems.append(f"a witness {shown} is shown, but no condition is disproved")
    if isinstance(definition, dict):
        problems += displayed_forms(report, definition)
        if definition.get("decision") != report["verdict"] and report["verdict"] in ("proved", "disproved"):
            problems.append(f"the verdict shown is {report['verdict']!r}, the definition object says {definition.get('decision')!r}")
        problems += consistent_witness(shown, definition, keys)
    return problems


def finding_display(entry: Mapping[str, Any], keys: Mapping[str, str] | None = None) -> list[str]:
    """An audit entry's verdict and displayed witness against its judge object (the witness's
    circle keys as the paper names them, ``keys``)."""
    evidence = entry.get("evidence") or {}
    obj = (evidence.get("facts") or {}).get("judge")
    if not isinstance(obj, dict) or "verdict" not in entry:
        return []
    problems = []
    allowed = _VERDICTS.get((obj.get("judge"), obj.get("claim")))
    if allowed is not None and entry["verdict"] not in allowed:
        problems.append(f"the verdict shown is {entry['verdict']!r}, but the judged claim {obj.get('claim')!r} supports "
                        f"{' or '.join(allowed)}")
    if isinstance(obj.get("printed"), str) and "printed" in entry and entry["printed"] != obj["printed"]:
        problems.append("the display shown is not the one judged (the entry's 'printed' was changed)")
    problems += consistent_witness(evidence.get("witness"), obj, keys)
    return problems


def _error_damping(shown: Any, p5: Mapping[str, Any]) -> list[str]:
    """A teleoperator's error-coordinate damping ``h`` is ``T H(z) = h + T C(z)/(z - 1)`` at
    ``z = oo``: the value at infinity of the transfer function (P5)'s certificate decides."""
    from hapticproof.exact.checkarith import certificates, json_poly

    transfer = next((c["transfer"] for c in certificates(p5) if isinstance(c.get("transfer"), Mapping)
                     and "num" in c["transfer"]), None)
    if transfer is None:
        return []
    num, den = json_poly(transfer["num"]), json_poly(transfer["den"])
    if den.is_zero() or num.degree() > den.degree():
        return ["the transfer function of (P5) is not proper"]
    value = num.coeffs()[-1] / den.coeffs()[-1] if num.degree() == den.degree() else 0
    try:
        if exact_q(str(shown)) != Fraction(int(flint.fmpq(value).p), int(flint.fmpq(value).q)):
            return [f"the error-coordinate damping shown ({str(shown)[:30]}) is not that of (P5)'s certificate ({value})"]
    except (TypeError, ValueError, ZeroDivisionError):
        return [f"the error-coordinate damping shown ({str(shown)[:30]}) cannot be read"]
    return []


def boundary_display(report: Mapping[str, Any]) -> list[str]:
    """A boundary's displayed value, tolerance and direction against the two loops it carries."""
    obj = report.get("judge")
    if report.get("value") is None or "parameter" not in report:
        return []
    if not isinstance(obj, dict) or obj.get("judge") != "stability":
        return [f"a boundary {str(report['parameter'])[:20]}* = {str(report['value'])[:30]} is shown with no stability "
                "judge object (no loops judged on either side of it)"]
    problems = []
    (left, right) = obj["sides"]
    value, tol = float(report["value"]), float(report["tolerance"])
    for side, target in ((left, value - tol), (right, value + tol)):
        if not math.isclose(float(side["value"]), target, rel_tol=1e-12, abs_tol=1e-300):
            problems.append(f"the loop judged at {side['value']:.12g} is not the displayed {report['parameter']}* "
                            f"{'-' if side is left else '+'} tolerance = {target:.12g}")
    expected = (True, False) if report.get("direction") == "destabilising" else (False, True)
    if (left["stable"], right["stable"]) != expected:
        problems.append(f"the direction shown ({report.get('direction')}) is not what the two judged loops say")
    if report.get("parameter") != obj.get("parameter"):
        problems.append(f"the parameter shown ({str(report.get('parameter'))[:20]}) is not the judged one")
    crossings = report.get("crossings")
    if not isinstance(crossings, list) or not crossings or not isinstance(crossings[0], Mapping):
        problems.append("the judged loops cross, but no crossing is shown")
        return problems
    first = crossings[0]
    if first.get("value") != report["value"] or first.get("direction") != report.get("direction"):
        problems.append("the first crossing shown is not the boundary judged (its value or direction differs)")
    for key in ("tolerance", "certified"):
        if key in first and first.get(key) != report.get(key):
            problems.append(f"the first crossing's {key} ({str(first.get(key))[:20]}) is not the boundary's "
                            f"({str(report.get(key))[:20]})")
    if left["stable"] != right["stable"] and report.get("outcome") not in ("crossing", "uncertified"):
        problems.append(f"the outcome shown ({str(report.get('outcome'))[:20]}) denies the crossing the judged loops show")
    if len(crossings) == 1 and isinstance(report.get("stable_at_start"), bool) and \
            report["stable_at_start"] != left["stable"]:
        problems.append("stable_at_start contradicts the one crossing: the judged loop before it says otherwise")
    return problems


def _read_display(text: Any, variable: str | None = None) -> Any:
    """A displayed expression read (never evaluated) by the toolkit's expression reader, ``None``
    when it is no short text the reader takes."""
    from hapticproof.core.expr import read_expression

    if not isinstance(text, str) or len(text) > MAX_SHOWN_CHARS or text in ("None", "True", "False"):
        return None
    try:
        return read_expression(text, variable)
    except Exception:  # noqa: BLE001 - a display the reader does not take is not compared
        return None


def _read_shown(text: Any, name: str) -> tuple[Any, Any] | None:
    """A displayed expression with its one symbol ``name`` (``None`` for a constant); ``None``
    when it is not a numeric expression of ``name`` alone."""
    expr = _read_display(text, "z" if name == "z" else None)
    if expr is None or any(s.name != name for s in expr.free_symbols):
        return None
    return expr, next(iter(expr.free_symbols), None)


#: the points at most at which a displayed form is compared (a longer form is compared there)
MAX_FORM_POINTS = 400


def _degree_in(expr: Any, symbol: Any) -> int:
    """The degree of numerator plus denominator of ``expr`` as a rational function of ``symbol``."""
    import sympy as sp

    if symbol is None:
        return 0
    num, den = sp.fraction(sp.together(expr))
    return sum(sp.Poly(part, symbol).degree() for part in (num, den))


def _value_at(expr: Any, symbol: Any, point: Fraction) -> Fraction | None:
    import sympy as sp

    value = expr if symbol is None else expr.xreplace({symbol: sp.Rational(point.numerator, point.denominator)})
    value = sp.nsimplify(value) if getattr(value, "is_Float", False) else value
    if not getattr(value, "is_Rational", False):
        return None
    return Fraction(int(value.p), int(value.q))


def displayed_forms(report: Mapping[str, Any], definition: Mapping[str, Any]) -> list[str]:
    """The displayed ``G_inverse`` (at real points off the circle), ``hermitian_part`` (at exact
    points of the circle, ``c = (1 - t^2)/(1 + t^2)``) and ``minimum`` at ``minimiser`` held
    against the definition object's ``G^{-1}(z)``: a display changed after the fact is refused.
    (Exact values at a few points: a tampered display that agrees with ``G^{-1}`` at every one of
    them is an identity in all but name.)"""
    transfer = definition.get("transfer") or {}
    if "num" not in transfer or transfer.get("variable", "z") != "z":
        return []                                    # matrices: their entries are checked by the judge
    problems: list[str] = []
    try:
        shown = _read_shown(report.get("G_inverse"), "z")
        if shown:
            expr, symbol = shown
            for q in (Fraction(2), Fraction(-3), Fraction(7, 2), Fraction(-5, 3)):
                try:
                    own = eval_transfer(dict(transfer), Gaussian(q))
                except CheckFailed:
                    continue                                 # a pole of G^-1
                value = _value_at(expr, symbol, q)
                if value is not None and (value != own.re or own.im != 0):
                    problems.append(f"the G^-1 shown is not the report's G^-1(z): at z = {q} it gives {value}, G^-1 is {own.re}")
                    break
        notation = report.get("notation") if isinstance(report.get("notation"), Mapping) else {}
        cos = notation.get("cos", "c") if isinstance(notation.get("cos", "c"), str) else "c"
        herm = _read_display(report.get("hermitian_part"))         # c under the scene's name for it
        if herm is None and report.get("hermitian_part") is not None:
            problems.append("the Re G^-1 shown cannot be read as an expression in "
                            f"{cos} (a number, a list, an equation, a foreign character): it is not compared, so not accepted")
        foreign = {s.name for s in herm.free_symbols} - {cos} if herm is not None else set()
        if foreign:
            problems.append(f"the Re G^-1 shown names {', '.join(sorted(foreign))[:60]}: a numeric report's Re G^-1 is a "
                            f"function of {cos} = cos(omega T) alone")
        if herm is not None and not foreign:
            expr, symbol = herm, next(iter(herm.free_symbols), None)
            # enough points that agreeing at all of them is an identity of the two rational functions
            # of c (degrees of the shown form plus that of Re G^-1, at most that of G^-1)
            needed = _degree_in(expr, symbol) + max(len(transfer["num"]), len(transfer["den"])) + 1
            for k in range(min(needed, MAX_FORM_POINTS)):
                t = Fraction(1, k + 2)
                c = (1 - t * t) / (1 + t * t)
                try:
                    own = eval_transfer(dict(transfer), Gaussian(c, 2 * t / (1 + t * t)))
                except CheckFailed:
                    continue
                value = _value_at(expr, symbol, c)
                if value != own.re:                    # (None: not a rational there -- sqrt(2), pi -- so not Re G^-1)
                    problems.append(f"the Re G^-1 shown is not the real part of the report's G^-1 on the circle: "
                                    f"at c = {c} it gives {value}, Re G^-1 is {own.re}")
                    break
            low, at = report.get("minimum"), report.get("minimiser")
            if not problems and isinstance(low, str) and isinstance(at, str):
                try:
                    low_q, at_q = exact_q(low), exact_q(at)
                except (ValueError, ZeroDivisionError, TypeError):
                    return problems
                value = _value_at(expr, symbol, at_q) if -1 <= at_q <= 1 else None
                if value is not None and value != low_q:
                    problems.append(f"the minimum shown {low} is not Re G^-1 at the minimiser shown c = {at} ({value})")
    except (ArithmeticError, ValueError, TypeError) as err:
        problems.append(f"a displayed form could not be compared with G^-1 ({type(err).__name__})")
    return problems

