"""Summaries of a scene's derivation: what ``hapticproof derive`` prints and notebooks show.

>>> from hapticproof.systems.singleuser import SingleUserScene
>>> summary = summarize_single_user(SingleUserScene.virtual_wall(K=2, B=0, b="0.0012", T="0.001"))
>>> summary.verdict, summary.witness
('proved', None)
>>> [c.decision.value for c in summary.conditions]
['proved', 'proved', 'proved', 'proved']
>>> sorted(summary.to_json())[:5]             # 'definition': G^-1 itself, for the judge of 'check'
['G_inverse', 'approximation', 'conditions', 'definition', 'delay']
"""

from __future__ import annotations

import json
from collections.abc import Sequence
from dataclasses import dataclass, field
from typing import Any

import sympy as sp

from hapticproof.report import latex as tex
from hapticproof.core.evidence import Decision, to_jsonable
from hapticproof.core.lazy import profile
from hapticproof.core.naming import DEFAULT, Naming
from hapticproof.core.notation import shorten_numbers
from hapticproof.report.readable import brief, full_text, witness_text
from hapticproof.systems.models import inverse_transfer
from hapticproof.exact.conditions import Condition
from hapticproof.analysis.positivereal import (SYMBOLIC_CFORM_LIMIT, conditions, definition_object, hermitian, poles,
                                              numeric_scene, positive_real, residues, symbolic_c_degree,
                                              transfer_polynomials, worst_case)
from hapticproof.exact.kernel import scene_json, transfer_json
from hapticproof.systems.singleuser import SingleUserScene
from hapticproof.exact.unitcircle import CRational

__all__ = ["SceneSummary", "summarize_single_user"]


#: helpers a single-user report never prints: the teleoperator's leak and error-coordinate
#: damping, the m-user Hermitian matrix and Laplacian eigenvalue
_NOT_A_WALLS = ("leak", "coupling", "matrix", "eigenvalue")


@dataclass(frozen=True)
class SceneSummary:
    """The derived conditions of one scene, ready to print as text, LaTeX or JSON."""

    system: str
    approximation: str
    delay: Any
    G_inverse: sp.Expr
    hermitian_part: Any
    poles: list
    residues: list
    worst_case: Any
    verdict: str
    witness: Any
    reason: str
    minimiser: Any = None
    minimum: Any = None
    stages: dict = field(default_factory=dict)
    conditions: tuple[Condition, ...] = ()
    #: what was not computed because the decision does not need it: name -> (why, how to get it)
    skipped: dict = field(default_factory=dict)
    #: the original ``G^{-1}(z)`` and the decision, for the definition-level judge of ``check``
    definition: dict | None = None
    #: the scene's names (:class:`~hapticproof.core.naming.Naming`): every view prints through them
    names: Naming = DEFAULT
    #: the values ``G^{-1}`` is built from (:func:`~hapticproof.exact.kernel.scene_json`), for ``check``
    scene: dict | None = None

    def to_json(self) -> dict[str, Any]:
        names = self.names
        out = {
            "system": self.system,
            "approximation": self.approximation,
            "delay": self.delay,
            "G_inverse": names.text(self.G_inverse),
            "hermitian_part": None if self.hermitian_part is None else full_text(self.hermitian_part, names),
            "poles": [{"z": p.value, "multiplicity": p.formula or p.multiplicity, "location": p.location} for p in self.poles],
            "residues": [{"z": r.pole, "residue": r.residue, "condition": r.outcome.decision.value} for r in self.residues],
            "worst_case": names.text(self.worst_case) if self.worst_case is not None else None,
            "conditions": [c.to_json() for c in self.conditions],
            "verdict": self.verdict,
            "witness": names.witness(self.witness),
            "reason": self.reason,
            "minimiser": self.minimiser,
            "minimum": self.minimum,
        }
        notation = names.changed(omit=_NOT_A_WALLS)
        if notation:
            out["notation"] = notation
        if self.skipped:
            out["skipped"] = {k: {"reason": why, "option": how} for k, (why, how) in self.skipped.items()}
        if self.definition is not None:
            out["definition"] = self.definition
        if self.scene is not None:
            out["scene"] = self.scene
        if self.stages:
            out["stages_seconds"] = self.stages
        return names.claims(to_jsonable(out))

    def to_text(self, verbose: bool = False) -> str:
        names = self.names
        theta = isinstance(self.delay, sp.Symbol)
        n_is = f"symbolic delay n = t_d/{names.period}"
        lines = [
            f"system:          {self.system} ({self.approximation} difference, "
            + (n_is if theta else f"delay n = {self.delay}") + ")",
            f"G^-1(z)          = {brief(self.G_inverse, verbose=verbose, names=names)}",
            (f"Re G^-1 ({names.helper('theta')} = {names.theta_text}, for every integer n) = " if theta
             else f"Re G^-1 ({names.helper('cos')} = {names.cos_text}) = ")
            + (brief(self.hermitian_part, verbose=verbose, names=names) if self.hermitian_part is not None
               else _skipped_text(self, "hermitian_part")),
            "poles:           " + ", ".join(f"z = {p.value} ({p.location}{'' if p.multiplicity == 1 else f', x{p.multiplicity}' if p.multiplicity > 0 else f', multiplicity {p.formula}'})" for p in self.poles),
            "residues:        " + (", ".join(f"Res(z = {r.pole}) = {names.text(r.residue)} [{r.outcome.reason}]" for r in self.residues) or "none on |z| = 1"),
            f"worst case:      {brief(self.worst_case, verbose=verbose, names=names) if self.worst_case not in (None, sp.true, sp.false) else _minimum_text(self)}",
            "conditions:",
        ]
        width = max((len(c.name) for c in self.conditions), default=0)
        for cond in self.conditions:
            lines.append(f"  {cond.name.ljust(width)}  {cond.decision.value:<9}  {shorten_numbers(cond.outcome.reason, verbose=verbose)}")
        lines.append(f"verdict:         {self.verdict}  ({shorten_numbers(self.reason, verbose=verbose)})")
        if self.witness:
            lines.append("witness:         " + witness_text(self.witness, names))
        if self.stages:
            lines.append("stages (s):      " + ", ".join(f"{k} {v:.4f}" for k, v in self.stages.items()))
        return "\n".join(lines)

    def latex_rows(self) -> list[tuple[str, str, str]]:
        """``(label, left-hand side, right-hand side)`` of each derived display."""
        herm, names = self.hermitian_part, self.names
        rows = [("inverse transfer function", r"G^{-1}(z)", "= " + names.latex(self.G_inverse))]
        if herm is not None:
            rows.append(("Hermitian part on the unit circle", rf"\Re\, G^{{-1}}(e^{{j{names.theta_latex}}})",
                         "= " + (names.latex(_as_expr(herm), cos=True) if not isinstance(herm, str) else herm)))
        for r in self.residues:
            rows.append(("residue on the unit circle", r"\operatorname{Res}_{z=" + names.latex(r.pole) + r"} G^{-1}",
                         "= " + names.latex(r.residue)))
        if self.worst_case is not None and self.worst_case not in (sp.true, sp.false):
            rows.append(("worst case over frequency", r"\text{worst case: }", names.latex(self.worst_case, cos=True)))
        return rows

    def to_latex(self) -> str:
        """The derived displays as one ``aligned`` block (mathematics, for a display or a notebook)."""
        rows = [lhs + " &" + (rhs if rhs.startswith("=") else " " + rhs) for _, lhs, rhs in self.latex_rows()]
        return "\\begin{aligned}\n" + " \\\\\n".join(rows) + "\n\\end{aligned}"

    def latex_document(self, answers: Sequence[tuple[str, str]] = (), remarks: Sequence[str] = ()) -> str:
        """A complete LaTeX document: the scene, the labelled derived displays, the answers asked
        for (``(label, display)``: the delay margin, passive ranges), the decision, and
        ``remarks`` (plain text: where the exact loop disagrees with the model)."""
        items = [(label, lhs + (" " if rhs.startswith("=") else " ") + rhs) for label, lhs, rhs in self.latex_rows()]
        items += list(answers)
        notes = [("verdict", f"{self.verdict} ({self.reason})")]
        notes += [(f"not computed: {name.replace('_', ' ')}", f"{why} ({how} computes it)") for name, (why, how) in self.skipped.items()]
        names = self.names
        cos = names.helper("cos")
        if self.witness is not None:
            notes.append(("witness", witness_text(self.witness, names) + f" ({cos} = {names.cos_text})"))
        if self.minimiser is not None:
            notes.append(("minimiser", f"{cos} = {self.minimiser} ({cos} = {names.cos_text}), "
                                       f"minimum = {names.text(self.minimum)}"))
        notes += [("exact loop", remark) for remark in remarks]
        intro = tex.escape_text(f"{self.system} scene, {self.approximation} difference, delay n = {self.delay}.")
        return tex.derivation_document(f"hapticproof derive {self.system}", items, notes, intro=intro)

    def _repr_latex_(self) -> str:
        return "$$" + self.to_latex() + "$$"

    def __repr__(self) -> str:  # short and free of timings (notebooks compare it)
        return f"SceneSummary({self.system}, {self.approximation}, delay {self.delay}: {self.verdict})"

    def dumps(self, fmt: str, fragment: bool = False, verbose: bool = False,
              answers: Sequence[tuple[str, str]] = (), remarks: Sequence[str] = ()) -> str:
        """``json``, ``latex`` (a complete document; ``fragment``: one amsmath display and one per
        answer) or text; ``answers`` are ``(label, display)`` of the answers asked for, ``remarks``
        plain notes of a LaTeX document."""
        if fmt == "json":
            return json.dumps(self.to_json(), indent=2)
        if fmt == "latex":
            if fragment:
                return "\n".join([tex.display(self.to_latex())] + ([tex.derivation_fragment(answers)] if answers else []))
            return self.latex_document(answers, remarks)
        return self.to_text(verbose=verbose)


def _as_expr(value: Any) -> Any:
    return value.expr() if isinstance(value, CRational) else value


def _readable(expr: sp.Expr) -> sp.Expr:
    """A polynomial expanded, a rational function as one fraction (not a sum of fractions)."""
    num, den = sp.fraction(sp.cancel(sp.together(expr)))
    if not den.free_symbols:
        return sp.expand(expr)
    return sp.Mul(sp.expand(num), sp.Pow(sp.expand(den), -1), evaluate=False)


def _scene_values(scene: SingleUserScene) -> dict[str, Any]:
    """``T``, ``b``, ``z_a`` and ``H(z)`` of a numeric scene, as ``check`` rebuilds ``G^{-1}`` from them."""
    values = numeric_scene(scene)
    return scene_json(values.T, [values.b], [values.z_a], [[values.H]])


def _skipped_text(summary: SceneSummary, name: str) -> str:
    why, how = summary.skipped.get(name, ("not computed", "--full"))
    return f"not computed: {why} [{how} computes it]"


def _minimum_text(summary: SceneSummary) -> str:
    if summary.minimiser is None:
        if isinstance(summary.delay, sp.Symbol):
            return "depends on n (see the delay margin below)"
        return "see the conditions"
    where = summary.minimiser.approx(12) if hasattr(summary.minimiser, "approx") else summary.minimiser
    value = summary.minimum
    if hasattr(value, "mid"):
        value = f"{float(value.mid()):.12g}"
    return f"min Re G^-1 = {value} at {summary.names.helper('cos')} = {where}"


#: A numeric scene's ``Re G^{-1}`` as a polynomial in ``c`` is computed for the summary when its
#: degree is at most this (0.1 s); above it the decision uses the closed form in ``theta``
#: (:mod:`hapticproof.exact.trigpoly`) and the polynomial is computed only when asked (``full``).
CFORM_LIMIT = 500


def summarize_single_user(scene: SingleUserScene, with_profile: bool = False, full: bool = False) -> SceneSummary:
    """Derive and collect everything ``hapticproof derive single-user`` reports.

    A numeric scene is decided on the fast path; its large exact objects (``Re G^{-1}`` as a
    polynomial in ``c`` of degree above :data:`CFORM_LIMIT`) are computed only with ``full``, and
    ``skipped`` says what was left out and how to get it.

    >>> big = SingleUserScene.virtual_wall(K=2, B="0.001", b="0.0201", T="0.001", delay=2000)
    >>> s = summarize_single_user(big)
    >>> s.verdict, s.hermitian_part, s.skipped["hermitian_part"][1]
    ('disproved', None, '--full')
    """
    skipped: dict[str, tuple[str, str]] = {}
    names = scene.naming()
    if scene.delay.is_Symbol:
        herm = hermitian(scene).expr(sp.Symbol(names.helper("theta")))
    elif scene.is_numeric and not full and _c_degree(scene) > CFORM_LIMIT:
        herm = None
        skipped["hermitian_part"] = (f"Re G^-1 as a polynomial in c has degree up to {_c_degree(scene)}; the decision "
                                     "needs only its closed form in theta", "--full")
    elif not scene.is_numeric and not full and symbolic_c_degree(scene) > SYMBOLIC_CFORM_LIMIT:
        herm = None
        skipped["hermitian_part"] = (f"Re G^-1 as a polynomial in c with parameters has degree up to {symbolic_c_degree(scene)} "
                                     "and no closed-form worst case", "--full")
    else:
        form = hermitian(scene)
        # numeric forms stay flint polynomials: a degree-1000 c-form is never built in SymPy
        # just to be summarised (readable.brief and readable.full_text read them directly)
        herm = form if form.is_numeric else _readable(form.expr())
    wc = worst_case(scene)
    verdict = positive_real(scene)
    witness = dict(verdict.witness) if (verdict.witness and verdict.decision == Decision.DISPROVED) else None
    definition = (definition_object(verdict, transfer_json(*transfer_polynomials(scene)), scene.naming())  # G^-1 itself, judged
                  if scene.is_numeric else None)
    decision, reason = verdict.decision.value, verdict.reason
    if definition is not None and not definition["judged"]["ok"]:
        # the decision and the definition disagree: neither is reported as established
        decision, witness = Decision.UNDECIDED.value, None
        reason = (f"the definition-level judge disagrees with '{verdict.decision.value}' ({definition['judged']['reason']}); "
                  f"the decision said: {verdict.reason}")
    return SceneSummary(
        system="single-user",
        approximation=scene.approximation,
        delay=scene.delay,
        G_inverse=inverse_transfer(scene),
        hermitian_part=herm,
        poles=poles(scene),
        residues=residues(scene),
        worst_case=wc.condition,
        verdict=decision,
        witness=witness,
        reason=reason,
        minimiser=wc.minimiser,
        minimum=wc.minimum,
        stages=profile(scene) if with_profile else {},
        conditions=tuple(conditions(scene)),
        skipped=skipped,
        definition=definition,
        names=names,
        scene=_scene_values(scene) if scene.is_numeric else None,
    )


def _c_degree(scene: SingleUserScene) -> int:
    """A bound on the degree in ``c`` of a numeric scene's ``Re G^{-1}`` (that of ``G^{-1} = P/Q``)."""
    P, Q = transfer_polynomials(scene)
    return max(P.degree(), Q.degree())
