r"""The passive range of one parameter of a scene, the others fixed, exact.

With the other parameters fixed, the set of values ``p`` for which the scene is passive is
found exactly. The conditions are polynomial in ``(c, p)``: ``P(c, p) = N D`` (single user,
the Hermitian part ``N/D``), the characteristic coefficients ``E_k(c, p)`` of the m-user
Hermitian part, or the teleoperator's ``(b - bound) den``. Whether ``P(., p) >= 0`` on
``[-1, 1]`` can change only where a root in ``c`` enters through ``c = +-1``, where two roots
meet (the discriminant in ``c``), where the leading coefficient vanishes, or where ``P``
vanishes identically; the poles and residues of ``G^{-1}`` change only at the resultant of its
numerator and denominator, the discriminant and leading coefficient of the denominator and the
resultant with its reciprocal (a pole crossing the circle). These **candidates** are
polynomials in ``p`` whose real roots are isolated exactly; between two consecutive roots the
decision is constant, so one exact decision at a rational sample per interval settles it. A
rational end is decided exactly; an algebraic end belongs to the set when an adjacent interval
does (the Hermitian condition is closed and the pole structure does not change there), and is
shown outside by the sign of ``P`` at a neighbouring witness frequency, exactly; otherwise it is
reported as undecided.

>>> from hapticproof.systems.scene import Scene
>>> wall = Scene("single-user", params={"b": "0.02", "B": "0.001", "T": "0.001"})
>>> passive_range(wall, "K").to_text()
'passive range of K (others fixed): 0 < K <= 38   [exact; 3 cells decided]'
"""

from __future__ import annotations

import math
import time
from dataclasses import dataclass
from fractions import Fraction
from typing import Any

import flint
import sympy as sp

from hapticproof.core.errors import SceneError
from hapticproof.core.evidence import Decision, Outcome, to_jsonable
from hapticproof.exact.realroots import RealRoot, as_fmpq, real_roots, to_rational
from hapticproof.analysis.design import scene_model

__all__ = ["Endpoint", "ParameterRange", "passive_range"]


@dataclass(frozen=True, slots=True)
class Endpoint:
    """An end of a passive interval: an exact rational (``value``) or a real algebraic number,
    the root of ``polynomial`` (integer coefficients) in ``[lo, hi]``."""

    value: sp.Rational | None
    polynomial: Any = None
    lo: sp.Rational | None = None
    hi: sp.Rational | None = None

    @classmethod
    def of(cls, root: RealRoot) -> Endpoint:
        if root.is_exact:
            return cls(to_rational(root.lo))
        r = root.refine(flint.fmpq(1, 2**60))
        poly = root.poly
        for factor, _ in root.poly.factor()[1]:          # the irreducible factor of the root
            if factor.degree() > 0 and real_roots(flint.fmpq_poly(factor), r.lo, r.hi):
                poly = factor
                break
        return cls(None, poly, to_rational(r.lo), to_rational(r.hi))

    def approx(self, digits: int = 15) -> str:
        if self.value is not None:
            return str(sp.N(self.value, digits))
        root = RealRoot(as_fmpq(self.lo), as_fmpq(self.hi), self.polynomial)
        return root.approx(digits)

    def text(self) -> str:
        return str(self.value) if self.value is not None else f"{self.approx(12)}..."

    def short_interval(self) -> tuple[sp.Rational, sp.Rational]:
        """The shortest decimal interval around ``[lo, hi]`` that still isolates the root (the
        exact ``lo``, ``hi`` have 2^60-size denominators; these are for people to read).

        >>> Endpoint.of(real_roots(flint.fmpq_poly([-2, 0, 1]), 0, 2)[0]).short_interval()
        (1, 2)
        """
        if self.value is not None:
            return self.value, self.value
        poly = flint.fmpq_poly(self.polynomial)
        lo, hi = Fraction(str(self.lo)), Fraction(str(self.hi))
        for digits in range(0, 40):
            scale = 10**digits
            a = Fraction(math.floor(lo * scale), scale)
            b = Fraction(math.ceil(hi * scale), scale)
            if a < b and len(real_roots(poly, flint.fmpq(a.numerator, a.denominator),
                                        flint.fmpq(b.numerator, b.denominator))) == 1:
                return sp.Rational(a.numerator, a.denominator), sp.Rational(b.numerator, b.denominator)
        return self.lo, self.hi

    def to_json(self) -> dict[str, Any]:
        if self.value is not None:
            return {"exact": str(self.value)}
        short = self.short_interval()
        return {"root_of": [str(c) for c in self.polynomial.coeffs()], "interval": [str(self.lo), str(self.hi)],
                "isolating_interval": [str(short[0]), str(short[1])], "approx": self.approx(20)}


@dataclass(frozen=True, slots=True)
class ParameterRange:
    """The exact set of values of ``parameter`` (within its sign domain) for which the scene is
    passive, the others fixed: a union of ``intervals`` ``(lo, lo_closed, hi, hi_closed)`` with
    :class:`Endpoint` ends (``None``: unbounded); ``cells`` the exact decisions at one sample of
    each candidate interval; ``undecided`` the algebraic points not settled."""

    parameter: str
    domain: tuple
    intervals: tuple
    cells: tuple
    undecided: tuple = ()
    seconds: float = 0.0

    @property
    def decision(self) -> Decision:
        return Decision.UNDECIDED if self.undecided else Decision.PROVED

    def is_empty(self) -> bool:
        return not self.intervals

    def maximum(self) -> Endpoint | None:
        """The upper end of the last interval (``K_max``), ``None`` when unbounded or empty."""
        return self.intervals[-1][2] if self.intervals else None

    def minimum(self) -> Endpoint | None:
        """The lower end of the first interval (``b_min``)."""
        return self.intervals[0][0] if self.intervals else None

    def _interval_text(self, item: tuple) -> str:
        lo, lo_closed, hi, hi_closed = item
        p = self.parameter
        if lo is not None and hi is not None and lo.value is not None and lo.value == hi.value:
            return f"{p} = {lo.text()}"
        left = "" if lo is None else f"{lo.text()} {'<=' if lo_closed else '<'} "
        right = "" if hi is None else f" {'<=' if hi_closed else '<'} {hi.text()}"
        if lo is None and hi is None:
            return f"every {p}"
        return f"{left}{p}{right}"

    def to_text(self) -> str:
        body = " or ".join(self._interval_text(i) for i in self.intervals) if self.intervals else "never passive"
        tag = "exact" if not self.undecided else f"undecided at {len(self.undecided)} point(s)"
        text = f"passive range of {self.parameter} (others fixed): {body}   [{tag}; {len(self.cells)} cells decided]"
        algebraic = [e for i in self.intervals for e in (i[0], i[2]) if e is not None and e.value is None]
        for e in algebraic:
            poly = _poly_text(e.polynomial, self.parameter)
            if len(poly) > 160:
                poly = f"an irreducible polynomial of degree {e.polynomial.degree()} (in the JSON output)"
            lo, hi = e.short_interval()
            text += f"\n  {e.approx(12)}... is the root of {poly} in [{_decimal(lo)}, {_decimal(hi)}]"
        return text

    def to_json(self) -> dict[str, Any]:
        return to_jsonable({
            "parameter": self.parameter, "decision": self.decision.value,
            "domain": [str(self.domain[0]) if self.domain[0] is not None else None,
                       str(self.domain[1]) if self.domain[1] is not None else None, self.domain[2]],
            "intervals": [{"lo": None if lo is None else lo.to_json(), "lo_closed": lc,
                           "hi": None if hi is None else hi.to_json(), "hi_closed": hc}
                          for lo, lc, hi, hc in self.intervals],
            "cells": [{"sample": str(s), "decision": o.decision.value, "reason": o.reason} for s, o in self.cells],
            "undecided": [e.to_json() for e in self.undecided],
            "text": self.to_text(), "seconds": round(self.seconds, 4)})


def _poly_text(poly: Any, name: str) -> str:
    """An integer polynomial in ``name``, highest power first: ``961*K**4 - 32755*K**2 + 8``."""
    terms = []
    for k, c in reversed(list(enumerate(flint.fmpz_poly(poly).coeffs()))):
        c = int(c)
        if c == 0:
            continue
        power = "" if k == 0 else name if k == 1 else f"{name}**{k}"
        body = str(abs(c)) if not power else power if abs(c) == 1 else f"{abs(c)}*{power}"
        terms.append(("- " if c < 0 else "+ ") + body)
    text = " ".join(terms) or "0"
    return text[2:] if text.startswith("+ ") else "-" + text[2:]


def _decimal(q: sp.Rational) -> str:
    """A terminating decimal as written (``0.125``), else ``p/q``."""
    p, d = int(q.p), int(q.q)
    k = 0
    while 10**k % d and k < 60:
        k += 1
    if 10**k % d:
        return f"{p}/{d}"
    digits = str(abs(p) * (10**k // d)).rjust(k + 1, "0")
    text = digits if k == 0 else digits[:-k] + "." + digits[-k:]
    return ("-" if p < 0 else "") + text


def _ctx(var: str) -> Any:
    return flint.fmpq_mpoly_ctx.get((var, "p"), "lex")


def _to_mpoly(expr: sp.Expr, var: sp.Symbol, p: sp.Symbol, ctx: Any) -> Any:
    poly = sp.Poly(sp.expand(expr), var, p)
    terms = {(int(i), int(j)): as_fmpq(poly.domain.to_sympy(cf)) for (i, j), cf in poly.terms()}
    return ctx.from_dict(terms) if terms else ctx.from_dict({})


def _in_p(poly: Any) -> flint.fmpq_poly:
    """A bivariate polynomial free of the first variable, as a polynomial in ``p``."""
    coeffs: dict[int, flint.fmpq] = {}
    for (i, j), cf in poly.to_dict().items():
        if i:
            raise ArithmeticError("expected a polynomial in p alone")
        coeffs[j] = cf
    top = max(coeffs, default=0)
    return flint.fmpq_poly([coeffs.get(k, 0) for k in range(top + 1)])


def _at(poly: Any, value: flint.fmpq, ctx: Any) -> flint.fmpq_poly:
    """``poly(value, p)`` as a polynomial in ``p``."""
    return _in_p(poly.compose(ctx.from_dict({(0, 0): value}), ctx.gens()[1]))


def _leading_in_first(poly: Any) -> flint.fmpq_poly:
    d = poly.to_dict()
    top = max((i for i, _ in d), default=0)
    coeffs: dict[int, flint.fmpq] = {}
    for (i, j), cf in d.items():
        if i == top:
            coeffs[j] = cf
    return flint.fmpq_poly([coeffs.get(k, 0) for k in range(max(coeffs, default=0) + 1)])


def _deg_first(poly: Any) -> int:
    return max((i for i, _ in poly.to_dict()), default=0)


def _deg_p(poly: Any) -> int:
    return max((j for _, j in poly.to_dict()), default=0)


def _sign_candidates(P: Any, ctx: Any, var: str) -> list[flint.fmpq_poly]:
    """Values of ``p`` where ``P(., p) >= 0`` on ``[-1, 1]`` can change (see the module docstring)."""
    if P.is_zero():
        return []
    out: list[flint.fmpq_poly] = []
    _, factors = P.factor()
    odd, fixed = [], []
    for f, mult in factors:
        if _deg_first(f) == 0:
            out.append(_in_p(f))                 # P vanishes identically / changes sign everywhere
        elif _deg_p(f) == 0:
            if mult % 2:
                fixed.append(f)
        elif mult % 2:
            odd.append(f)
        else:
            out.append(_leading_in_first(f))
    if not odd:
        return out
    S = odd[0]
    for f in odd[1:]:
        S = S * f
    for end in (-1, 1):
        out.append(_at(S, flint.fmpq(end), ctx))
    out.append(_leading_in_first(S))
    if _deg_first(S) > 1:
        out.append(_in_p(S.discriminant(var)))
    for g in fixed:
        out.append(_in_p(S.resultant(g, var)))
    return out


def _reverse(poly: Any, ctx: Any) -> Any:
    d = poly.to_dict()
    top = max(i for i, _ in d)
    return ctx.from_dict({(top - i, j): cf for (i, j), cf in d.items()})


def _pole_candidates(P: Any, Q: Any, ctx: Any) -> list[flint.fmpq_poly]:
    """Values of ``p`` where the poles of ``P/Q`` (in z) or their residues can change."""
    from hapticproof.exact.unitcircle import symmetric_to_c

    out: list[flint.fmpq_poly] = [_leading_in_first(Q)]
    # properness: the coefficients of z^k, k > deg Q, of P (the pole at z = oo comes and goes
    # where they vanish; the excess does not depend on a cancellation)
    above: dict[int, dict[int, flint.fmpq]] = {}
    for (i, j), cf in (P.to_dict().items() if not P.is_zero() else ()):
        if i > _deg_first(Q):
            above.setdefault(i, {})[j] = cf
    for coeffs in above.values():
        out.append(flint.fmpq_poly([coeffs.get(k, 0) for k in range(max(coeffs) + 1)]))
    if _deg_first(Q) == 0:
        return out
    if not P.is_zero() and _deg_first(P) > 0:
        out.append(_in_p(P.resultant(Q, "z")))
    _, factors = Q.factor()
    sq = None
    for f, _ in factors:
        sq = f if sq is None else sq * f
        if _deg_first(f) == 0:
            out.append(_in_p(f))
            continue
        if _deg_p(f) == 0:
            continue
        rev = _reverse(f, ctx)
        res = f.resultant(rev, "z")
        if not res.is_zero():
            out.append(_in_p(res))
        elif _deg_first(f) % 2 == 0:          # self-reciprocal for every p: roots on the circle at c in [-1, 1]
            half = _deg_first(f) // 2
            laurent: dict[int, Any] = {}
            for (i, j), cf in f.to_dict().items():
                laurent[i - half] = laurent.get(i - half, ctx.from_dict({})) + ctx.from_dict({(0, j): cf})
            cctx = _ctx("c")
            moved = {k: cctx.from_dict(v.to_dict()) for k, v in laurent.items()}
            h = symmetric_to_c(moved, cctx.from_dict({}), cctx.gens()[0], cctx.from_dict({(0, 0): 1}), +1)
            out += _sign_candidates(h * h, cctx, "c") + [_at(h, flint.fmpq(-1), cctx), _at(h, flint.fmpq(1), cctx)]
    if sq is not None and _deg_first(sq) > 1:
        out.append(_in_p(sq.discriminant("z")))
    return out


def _hermitian_mpoly(P: Any, Q: Any, zctx: Any) -> Any:
    """``N(c, p) D(c, p)`` with ``Re P/Q = N/D`` on the circle (Laurent + Chebyshev, in flint)."""
    from hapticproof.exact.unitcircle import symmetric_to_c

    cctx = _ctx("c")

    def columns(poly: Any) -> dict[int, Any]:
        out: dict[int, dict] = {}
        for (i, j), cf in poly.to_dict().items():
            out.setdefault(i, {})[(0, j)] = cf
        return {i: cctx.from_dict(d) for i, d in out.items()}

    def cross(a: dict, b: dict) -> dict[int, Any]:
        out: dict[int, Any] = {}
        for i, ai in a.items():
            for j, bj in b.items():
                out[i - j] = out.get(i - j, cctx.from_dict({})) + ai * bj
        return out

    pa, qa = columns(P), columns(Q)
    zero, one, cvar = cctx.from_dict({}), cctx.from_dict({(0, 0): 1}), cctx.gens()[0]
    N = symmetric_to_c(cross(pa, qa), zero, cvar, one, +1) if pa else zero
    D = symmetric_to_c(cross(qa, qa), zero, cvar, one, +1)
    return N * D, cctx


def _domain(symbol: sp.Symbol) -> tuple:
    """``(lo, hi, kind)`` of a parameter's sign assumption."""
    if symbol.is_positive:
        return (sp.Integer(0), None, "positive")
    if symbol.is_nonnegative:
        return (sp.Integer(0), None, "nonnegative")
    if symbol.is_negative:
        return (None, sp.Integer(0), "negative")
    if symbol.is_nonpositive:
        return (None, sp.Integer(0), "nonpositive")
    return (None, None, "real")


def _system_parts(scene: Any, name: str) -> tuple[list[Any], list[flint.fmpq_poly], Any]:
    """Sign polynomials ``P(c, p)``, pole candidate polynomials and the ``c``-context."""
    from hapticproof.exact.canonical import canonical_fraction
    from hapticproof.core.symbols import c as C_SYM
    from hapticproof.core.symbols import z as Z_SYM

    model = scene_model(scene.with_params({name: scene.assumptions.get(name)}))   # keep an assumption (K = "real")
    p = scene.symbol(name)
    free = set(model.parameters) - {p}
    free -= {s for s in free if s.name == "n"}
    if p not in model.parameters and name not in dict(scene.params):
        shown = sorted(map(str, set(model.parameters) - {s for s in model.parameters if s.name == "n"}))
        raise SceneError(f"{name} is not a parameter of this scene (its parameters: {', '.join(shown) or 'none'})")
    if free:
        raise SceneError(f"the passive range of {name} needs numbers for {', '.join(sorted(map(str, free)))}")
    if p not in model.parameters:
        raise SceneError(f"{name} is not a parameter of this scene")
    zctx = _ctx("z")
    if scene.system == "single-user":
        from hapticproof.systems.models import inverse_transfer

        if model.delay.is_Symbol:
            raise SceneError("the passive range needs an integer delay")
        num, den = canonical_fraction(inverse_transfer(model))
        P, Q = _to_mpoly(num, Z_SYM, p, zctx), _to_mpoly(den, Z_SYM, p, zctx)
        herm, cctx = _hermitian_mpoly(P, Q, zctx)
        return [herm], _pole_candidates(P, Q, zctx), cctx
    if scene.system == "multi-user":
        from hapticproof.analysis.multiuser import hermitian
        from hapticproof.systems.multiuser import stiffness_matrix
        from hapticproof.exact.psd import characteristic_coefficients

        H = hermitian(model)
        coeffs = characteristic_coefficients(H, "minors")[1:]
        cctx = _ctx("c")
        ring = H.ring
        polys = []
        for k, e in enumerate(coeffs, start=1):
            expr = ring.to_expr(e) * ring.to_expr(H.den) ** (k % 2)
            polys.append(_to_mpoly(expr, C_SYM, p, cctx))
        # residue matrix T Kmat at z = 1: PSD iff its characteristic coefficients are >= 0
        TK = (model.T * stiffness_matrix(model)).applyfunc(sp.expand)
        coefficients = [sp.expand(cf) for cf in TK.charpoly(sp.Dummy("lam")).all_coeffs()]
        poles = [flint.fmpq_poly([as_fmpq(a) for a in sp.Poly(cf, p).all_coeffs()[::-1]])
                 for cf in coefficients if cf.has(p)]
        return polys, poles, cctx
    if scene.system == "teleoperator":
        # the exact conditions (hapticproof.analysis.teleoperator): (P5) h - L(c) >= 0, (P3)
        # C(1) >= 0, (D) b_m, b_s >= 0 (and b_m + alpha^2 b_s, the denominator of h), and the
        # poles of C (P1, P2, P4)
        from hapticproof.analysis.teleoperator import bounds, error_coordinate_damping

        leak = bounds(model).leak
        cctx = _ctx("c")
        polys = []
        for expr in (error_coordinate_damping(model) - leak, sp.cancel(sp.together(model.C)).subs(Z_SYM, 1),
                     model.b_m, model.b_s, model.b_m + model.alpha**2 * model.b_s):
            num, den = sp.fraction(sp.cancel(sp.together(expr)))
            if (num * den).has(p):
                polys.append(_to_mpoly(sp.expand(num * den), C_SYM, p, cctx))
        cnum, cden = canonical_fraction(model.C)
        P, Q = _to_mpoly(cnum, Z_SYM, p, zctx), _to_mpoly(cden, Z_SYM, p, zctx)
        return polys, _pole_candidates(P, Q, zctx), cctx
    raise SceneError("the passive range applies to single-user, multi-user and teleoperator scenes")


def _decide(scene: Any, name: str, value: sp.Rational) -> Outcome:
    model = scene.with_params({name: value}).build()
    if scene.system == "single-user":
        from hapticproof.analysis.positivereal import positive_real

        return positive_real(model)
    if scene.system == "multi-user":
        from hapticproof.analysis.multiuser import positive_real

        return positive_real(model)
    from hapticproof.analysis.teleoperator import passivity

    return passivity(model)


def _squarefree(polys: list[flint.fmpq_poly]) -> flint.fmpq_poly:
    out = flint.fmpq_poly([1])
    for poly in polys:
        if poly.is_zero() or poly.degree() <= 0:
            continue
        for f, _ in poly.numer().factor_squarefree()[1]:
            f = flint.fmpq_poly(f)
            g = out.gcd(f)
            out = out * (f / g)
    return out


def _sign_at_root(q: flint.fmpq_poly, root: RealRoot) -> int:
    """Exact sign of ``q`` at the algebraic number ``root``."""
    if q.is_zero():
        return 0
    g = flint.fmpq_poly(root.poly).gcd(q)
    if g.degree() > 0 and real_roots(g, root.lo, root.hi):
        return 0
    r = root
    while True:
        if q.degree() <= 0 or not real_roots(q, r.lo, r.hi):
            value = q(r.lo) if q.degree() > 0 else q(flint.fmpq(0))
            return (value > 0) - (value < 0)
        r = r.refine((r.hi - r.lo) / 4)


def passive_range(scene: Any, name: str) -> ParameterRange:
    """The exact passive range of parameter ``name`` of a :class:`~hapticproof.systems.scene.Scene`
    whose other parameters are numbers (single-user, multi-user, teleoperator).

    >>> from hapticproof.systems.scene import Scene
    >>> rng = passive_range(Scene("single-user", params={"K": 2, "B": "0.001", "T": "0.001"}), "b")
    >>> rng.minimum().value                       # b_min = K T/2 + B (Colgate)
    1/500
    """
    from hapticproof.systems.scene import Scene

    if not isinstance(scene, Scene):
        raise SceneError("passive_range takes a Scene (its parameters by name)")
    start = time.perf_counter()
    p = scene.symbol(name)
    signs, poles, cctx = _system_parts(scene, name)
    candidates = []
    for P in signs:
        candidates += _sign_candidates(P, cctx, "c")
    pole_product = _squarefree(poles)
    candidates += poles
    product = _squarefree(candidates)
    lo, hi, kind = _domain(p)
    lo_q = None if lo is None else as_fmpq(lo)
    hi_q = None if hi is None else as_fmpq(hi)
    roots = real_roots(product, lo_q, hi_q) if product.degree() > 0 else []
    if lo_q is not None and kind == "positive":
        roots = [r for r in roots if not (r.is_exact and r.lo == 0)]
    if hi_q is not None and kind == "negative":
        roots = [r for r in roots if not (r.is_exact and r.lo == 0)]
    # cells: open intervals between consecutive roots (and the domain's ends)
    edges: list[tuple] = []
    left = ("end", lo_q)
    for r in roots:
        edges.append((left, ("root", r)))
        left = ("root", r)
    edges.append((left, ("end", hi_q)))
    cells = []
    for (lk, lv), (rk, rv) in edges:
        a = None if lv is None else (lv.hi if lk == "root" else lv)
        b = None if rv is None else (rv.lo if rk == "root" else rv)
        if a is not None and b is not None and not a < b:
            cells.append(None)
            continue
        sample = _sample(a, b)
        cells.append((sample, _decide(scene, name, sample)))
    good = [c is not None and c[1].decision == Decision.PROVED for c in cells]
    for c in cells:
        if c is not None and c[1].decision not in (Decision.PROVED, Decision.DISPROVED):
            raise SceneError(f"the decision at {name} = {c[0]} is {c[1].decision.value}: {c[1].reason}")
    # the roots themselves
    point_good: list[bool | None] = []
    undecided = []
    for i, r in enumerate(roots):
        left_good, right_good = good[i], good[i + 1]
        if r.is_exact:
            out = _decide(scene, name, to_rational(r.lo))
            point_good.append(out.decision == Decision.PROVED)
            continue
        on_poles = pole_product.degree() > 0 and _sign_at_root(pole_product, r) == 0
        if (left_good or right_good) and not on_poles:
            point_good.append(True)
            continue
        verdict = None
        for cell in (cells[i], cells[i + 1]):
            if cell is None or cell[1].decision != Decision.DISPROVED:
                continue
            witness = cell[1].witness or {}
            if "c" in witness:
                c_s = as_fmpq(sp.Rational(witness["c"]))
                if any(_sign_at_root(_at(P, c_s, cctx), r) < 0 for P in signs):
                    verdict = False
                    break
            elif not on_poles:
                verdict = False
                break
        if verdict is None:
            if not (left_good or right_good) and not on_poles:
                verdict = False if _no_isolated_point(signs, cctx, r) else None
        if verdict is None:
            undecided.append(Endpoint.of(r))
        point_good.append(verdict)
    intervals = _assemble(roots, good, point_good, lo_q, hi_q, kind)
    return ParameterRange(name, (lo, hi, kind), tuple(intervals), tuple(c for c in cells if c is not None),
                          tuple(undecided), time.perf_counter() - start)


def _no_isolated_point(signs: list[Any], cctx: Any, root: RealRoot) -> bool:
    """A root flanked by failing intervals is itself failing when some sign polynomial is
    negative there at one of a few rational frequencies (exact sign at the algebraic root)."""
    for c in (flint.fmpq(-1), flint.fmpq(1), flint.fmpq(0), flint.fmpq(1, 2), flint.fmpq(-1, 2)):
        if any(_sign_at_root(_at(P, c, cctx), root) < 0 for P in signs):
            return True
    return False


def _sample(a: flint.fmpq | None, b: flint.fmpq | None) -> sp.Rational:
    from hapticproof.exact.kernel import simplest_between

    if a is None and b is None:
        return sp.Integer(0)
    if a is None:
        value = Fraction(math.floor(Fraction(int(b.p), int(b.q))) - 1)
    else:
        value = simplest_between(Fraction(int(a.p), int(a.q)), None if b is None else Fraction(int(b.p), int(b.q)))
    return sp.Rational(value.numerator, value.denominator)


def _assemble(roots: list[RealRoot], good: list[bool], point_good: list[bool | None], lo_q, hi_q, kind) -> list[tuple]:
    """Maximal intervals of the good cells and points."""
    pieces: list[tuple] = []          # (lo_endpoint, lo_closed, hi_endpoint, hi_closed)
    lo_closed_domain = kind in ("nonnegative", "real") and lo_q is not None
    hi_closed_domain = kind in ("nonpositive", "real") and hi_q is not None
    current = None
    n = len(roots)
    for i in range(n + 1):
        if good[i]:
            if current is None:
                if i == 0:
                    start = None if lo_q is None else Endpoint(to_rational(lo_q))
                    closed = lo_closed_domain
                    if lo_q is not None and lo_closed_domain:
                        closed = True
                    current = [start, closed]
                else:
                    current = [Endpoint.of(roots[i - 1]), bool(point_good[i - 1])]
        if i < n:
            if current is not None and not good[i] and False:
                pass
            if good[i] and point_good[i] is True and good[i + 1]:
                continue                       # the interval goes on through the root
            if good[i] and current is not None:
                pieces.append((current[0], current[1], Endpoint.of(roots[i]), bool(point_good[i])))
                current = None
            elif not good[i] and point_good[i] is True and not good[i + 1]:
                e = Endpoint.of(roots[i])
                pieces.append((e, True, e, True))
        elif current is not None:
            end = None if hi_q is None else Endpoint(to_rational(hi_q))
            pieces.append((current[0], current[1], end, hi_closed_domain if end is not None else False))
            current = None
    # a closed lower domain end (B >= 0) belongs when its cell does
    return pieces
