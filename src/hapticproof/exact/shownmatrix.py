r"""The matrices an m-user ``derive`` report shows, re-derived from its ``G^{-1}(z)`` (part of the
checker: imports only ``core`` and the checker's own modules).

A report of m users shows ``G_inverse`` entry by entry, the residue matrix at ``z = 1``, the
Hermitian part ``M(c) = G^{-1}(e^{j theta}) + G^{-H}(e^{j theta})`` in ``c = cos theta`` (and
``s_theta = sin theta`` when it is complex), its principal minors, and whether the worst case
over frequency holds. Each is held against the definition object's transfer matrix, exactly:

* ``G_inverse`` and the residue matrix: entry by entry, as rational functions / numbers;
* ``M(c)`` and its minors: at rational points of the circle ``z = (1 + j t)/(1 - j t)``
  (``c = (1 - t^2)/(1 + t^2)``, ``s_theta = 2t/(1 + t^2)``), as many as the degrees in ``t`` of
  the two sides allow to differ -- agreement there is an identity;
* ``worst_case_condition``: the decision of the PSD condition it summarises.

>>> G = {"entries": [[{"num": ["1"], "den": ["1"]}]]}
>>> matrix_displays({"definition": {"transfer": G}, "hermitian_part": [["2"]], "G_inverse": [["1"]]})
[]
>>> matrix_displays({"definition": {"transfer": G}, "hermitian_part": [["c"]]})
['the Hermitian part shown is not G^-1 + G^-H of the report: entry (1, 1) differs at c = 1']
"""

from __future__ import annotations

from collections.abc import Mapping
from fractions import Fraction
from itertools import count
from typing import Any

from hapticproof.exact.acceptance import differing_entry, residue_matrix
from hapticproof.exact.checkarith import CheckFailed, Gaussian, certificates, determinant, eval_transfer, exact_q, max_degree

__all__ = ["matrix_displays"]

#: Users above this are not re-derived here (2^m minors, m^2 entries at each point).
MAX_USERS = 8


def _square(shown: Any, m: int, what: str) -> list[list[Any]]:
    if not (isinstance(shown, list) and len(shown) == m and all(isinstance(r, list) and len(r) == m for r in shown)):
        raise ValueError(f"the {what} shown is not an {m} x {m} matrix")
    return shown


def _reader(cos: str, sin: str) -> Any:
    """Read an entry shown in ``cos``, ``sin`` and the unit ``I`` (never evaluated): ``(form,
    degree in t)`` with ``form = (expr, c, s)``."""
    import sympy as sp

    from hapticproof.core.errors import HapticproofError
    from hapticproof.core.expr import read_expression

    c, s = sp.Symbol(cos), sp.Symbol(sin)

    def read(text: Any) -> tuple[tuple, int]:
        if not isinstance(text, (str, int)) or isinstance(text, bool) or len(str(text)) > 20_000:
            raise ValueError("an entry is not a short expression")
        try:
            expr = read_expression(str(text), None, symbols={cos: c, sin: s, "I": sp.I})
        except HapticproofError as err:
            raise ValueError(str(err)) from None
        if expr.free_symbols - {c, s}:
            raise ValueError(f"an entry names {', '.join(sorted(map(str, expr.free_symbols - {c, s})))}")
        num, den = sp.fraction(sp.together(expr))
        degree = max(sp.Poly(num, c, s).total_degree(), sp.Poly(den, c, s).total_degree())
        if degree > max_degree():
            raise ValueError("an entry's degree is above the checker's limit")
        return (expr, c, s), 2 * degree

    return read


def _value(form: tuple, c: Fraction, s: Fraction) -> Gaussian:
    """The entry shown at ``(c, s)``, exactly (a pole there raises ``ZeroDivisionError``)."""
    import sympy as sp

    expr, cs, ss = form
    value = sp.expand(expr.xreplace({cs: sp.Rational(c.numerator, c.denominator),
                                     ss: sp.Rational(s.numerator, s.denominator)}))
    re, im = value.as_real_imag()
    if not (re.is_Rational and im.is_Rational):
        raise ZeroDivisionError("a pole of the entry shown")
    return Gaussian(Fraction(int(re.p), int(re.q)), Fraction(int(im.p), int(im.q)))


def _worst_case(report: Mapping[str, Any]) -> list[str]:
    """``worst_case_condition`` is the decision of the condition a ``psd`` certificate decides;
    ``worst_c`` (and that condition's ``minimiser``) the ``c`` of its counterexample, none when
    it is proved."""
    shown = report.get("worst_case_condition")
    notation = report.get("notation") if isinstance(report.get("notation"), Mapping) else {}
    cos = str(notation.get("cos", "c"))
    for cond in report.get("conditions") or []:
        if isinstance(cond, Mapping) and cond.get("decision") in ("proved", "disproved") and \
                any(c.get("certificate") == "psd" for c in certificates(cond)):
            expected = "True" if cond["decision"] == "proved" else "False"
            if shown is not None and shown != expected:
                return [f"the worst case shown ({str(shown)[:20]}) is not the decision of {str(cond.get('name'))[:60]!r} "
                        f"({cond['decision']})"]
            witness = (cond.get("evidence") or {}).get("witness") if isinstance(cond.get("evidence"), Mapping) else None
            at = witness.get(cos) if isinstance(witness, Mapping) else None
            for where, value in (("worst_c", report.get("worst_c")), ("minimiser", cond.get("minimiser"))):
                if value is None:
                    continue
                if at is None or exact_q(str(value)) != exact_q(str(at)):
                    return [f"the {where} shown ({str(value)[:20]}) is not the {cos} of the counterexample of "
                            f"{str(cond.get('name'))[:60]!r} ({at})"]
    return []


def matrix_displays(report: Mapping[str, Any]) -> list[str]:
    """Refusals: a matrix display of an m-user report that is not its ``G^{-1}``'s."""
    definition = report.get("definition")
    transfer = definition.get("transfer") if isinstance(definition, Mapping) else None
    if not isinstance(transfer, Mapping) or "entries" not in transfer:
        return []
    cells = transfer["entries"]
    m = len(cells)
    if m > MAX_USERS:
        return []
    out: list[str] = []
    if "G_inverse" in report:
        differs = differing_entry(_square(report["G_inverse"], m, "G^-1"), cells)
        if differs:
            return [f"the G^-1 shown is not the report's G^-1(z): entry {differs} differs"]
    if report.get("residue_at_1") is not None:
        shown = _square(report["residue_at_1"], m, "residue matrix")
        own = residue_matrix(cells, transfer, Fraction(1))
        for i in range(m):
            for j in range(m):
                if exact_q(str(shown[i][j])) != own[i][j]:
                    return [f"the residue matrix shown is not that of G^-1 at z = 1: entry ({i + 1}, {j + 1}) differs"]
    out += _worst_case(report)
    notation = report.get("notation") if isinstance(report.get("notation"), Mapping) else {}
    read = _reader(str(notation.get("cos", "c")), str(notation.get("sin", "s_theta")))
    degree = max(max(len(cell["num"]), len(cell["den"])) for row in cells for cell in row)
    shown_forms: dict[tuple[int, ...], tuple[tuple, int]] = {}
    if "hermitian_part" in report:
        shown = _square(report["hermitian_part"], m, "Hermitian part")
        for i in range(m):
            for j in range(m):
                shown_forms[(i, j)] = read(shown[i][j])
    minors = report.get("principal_minors")
    if isinstance(minors, Mapping):
        for key, text in minors.items():
            index = tuple(int(v) - 1 for v in str(key).strip("()").replace(" ", "").split(",") if v)
            if not index or any(not 0 <= v < m for v in index) or list(index) != sorted(set(index)):
                return [f"the principal minor {str(key)[:20]} names no principal submatrix"]
            shown_forms[("minor",) + index] = read(text)
    elif minors is not None:
        return ["the principal minors shown are not a table"]
    if not shown_forms:
        return out
    # M's entries have degree <= 2 deg G in t, a k x k minor <= 2k deg G; the shown side its own
    bound = max(2 * (len(k) - 1 if k[0] == "minor" else 1) * degree + d for k, (_, d) in shown_forms.items())
    points, complex_part = 0, False
    for t in count():
        if points > bound:
            break
        if t > 4 * bound + 16:
            return ["the Hermitian part shown cannot be compared (too many poles among the points)"]
        tt = Fraction(t)
        z = Gaussian(1 - tt * tt, 2 * tt) / Gaussian(1 + tt * tt)
        c, s = (1 - tt * tt) / (1 + tt * tt), 2 * tt / (1 + tt * tt)
        try:
            g = [[eval_transfer(cells[i][j], z) for j in range(m)] for i in range(m)]
            values = {k: _value(form, c, s) for k, (form, _) in shown_forms.items()}
        except (ZeroDivisionError, CheckFailed):         # a pole at this point: the next one
            continue
        M = [[g[i][j] + g[j][i].conj() for j in range(m)] for i in range(m)]
        points += 1
        complex_part = complex_part or any(M[i][j].im != 0 for i in range(m) for j in range(m))
        for key, value in values.items():
            if key[0] == "minor":
                if not (determinant([[M[a][b] for b in key[1:]] for a in key[1:]]) - value).is_zero():
                    return [f"the principal minor {tuple(v + 1 for v in key[1:])} shown is not that of G^-1 + G^-H "
                            f"at {notation.get('cos', 'c')} = {c}"]
            elif not (M[key[0]][key[1]] - value).is_zero():
                return [f"the Hermitian part shown is not G^-1 + G^-H of the report: entry ({key[0] + 1}, {key[1] + 1}) "
                        f"differs at {notation.get('cos', 'c')} = {c}"]
    if "hermitian_is_real" in report and report["hermitian_is_real"] is complex_part:
        out.append(f"hermitian_is_real is shown {report['hermitian_is_real']}, but G^-1 + G^-H is "
                   f"{'complex' if complex_part else 'real'} on the circle")
    return out
