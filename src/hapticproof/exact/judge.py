r"""The definition-level judge: a verdict tested against the definition itself, with its own
arithmetic, from what a finding or a report carries.

The certificates (:mod:`hapticproof.exact.checker`) re-verify *how* a decision was reached;
the judge asks whether the answer agrees with the **definition** (DESIGN.md, *One decision
kernel, one checker that judges the definition*), evaluating the original object:

* ``positive-real`` -- a discrete ``F(z)`` (scalar, or a matrix through its Hermitian part) is
  positive real iff analytic in ``|z| > 1`` *and at infinity* and ``F(z) + F(z)^H >= 0`` there;
  a continuous ``Z(s)`` likewise in ``Re s > 0`` (a simple pole at infinity allowed). The judge
  reads properness from the raw degrees, finds poles outside by Routh-Hurwitz after the bilinear
  map (:func:`hapticproof.exact.checkarith.has_root_outside`), and evaluates ``F`` exactly at
  Gaussian-rational points on and outside the circle -- ``|z|`` up to ``10^6``, and just outside
  every pole on the circle. A ``proved`` with a violation anywhere is rejected; a ``disproved``
  needs a violation: its witness (``Re F(z0) < 0`` at ``|z0| >= 1``, exact), a pole outside, a
  repeated pole on the circle, improperness, or a sample point.
* ``circle-identity`` -- a printed expression of ``Re G^{-1}(e^{j omega T})`` (a tree,
  :mod:`hapticproof.core.exprtree`) evaluated by ball arithmetic at ``theta = 2 L atan(t)``,
  ``omega = theta/T``, ``t_d = n T``, against ``Re G^{-1}(z)`` from the transfer function at
  the same ``z = ((1 + j t)/(1 - j t))^L`` (exact): ``equal`` must agree at every point,
  ``differ`` must differ at the witness.
* ``condition`` -- a printed condition at the witness's parameters (exact or ball) and the
  scene's ``G^{-1}(z)`` (a tree in ``z`` and the parameters): a condition that holds where the
  scene is not positive real needs a point ``|z0| >= 1`` with ``Re G^{-1}(z0) < 0``; where it is
  claimed positive real no sample point may violate the definition.

:func:`consistent_witness` holds a finding's *displayed* witness against the judge's point:
parameters equal, ``c = Re z``, ``z`` as the point gives it, ``omega T = theta`` and
``omega = theta / T`` (one angle, no quantity set on its own).

>>> wall = {"judge": "positive-real", "domain": "disk", "decision": "proved",
...         "transfer": {"variable": "z", "num": ["-1", "3"], "den": ["-1", "1"]}}      # (3z - 1)/(z - 1)
>>> judge(wall).ok
True
>>> improper = dict(wall, transfer={"variable": "z", "num": ["1", "-1", "1"], "den": ["-1", "1"]})
>>> judge(improper).reason
'FAILED: improper: a pole at infinity (deg num 2 > deg den 1), not positive real'
"""

from __future__ import annotations

import contextlib
import itertools
import math
from collections.abc import Iterable, Iterator, Mapping
from dataclasses import dataclass
from fractions import Fraction
from typing import Any

import flint

from hapticproof.exact.checkarith import (
    CheckFailed,
    CheckSkipped,
    Gaussian,
    axis_gcd,
    bilinear,
    budget,
    spend,
    charpoly_coefficients,
    count_with_multiplicity,
    eval_transfer,
    exact_q,
    has_root_outside,
    is_kind,
    is_proper,
    json_poly,
)
from hapticproof.exact.judgepoints import MAX_OWN_POINTS, names_of, own_points, tree_size
from hapticproof.core.naming import witness_keys

__all__ = ["Judgement", "judge", "judges", "judged_definition", "evaluate_tree", "consistent_witness", "displayed_number",
           "JUDGE_BITS"]

#: Working precision of the ball evaluations (bits); doubled once when a ball is too wide.
JUDGE_BITS = 256


@dataclass
class Judgement:
    """The judge's answer about one judge object: ``ok`` (the verdict agrees with the
    definition), ``reason`` (what was evaluated, or the disagreement) and ``judged`` (``False``
    when the object could not be evaluated: then ``ok`` is ``True`` and nothing was shown)."""

    ok: bool
    reason: str
    judged: bool = True


class _NotExact(Exception):
    pass


# ---------------------------------------------------------------------------------------------
# evaluating trees: exactly over the Gaussian rationals, or with complex balls
# ---------------------------------------------------------------------------------------------


def _exact(tree: list, env: Mapping[str, Gaussian]) -> Gaussian:
    head = tree[0]
    if head == "q":
        return Gaussian(exact_q(tree[1]))
    if head == "s":
        if tree[1] not in env:
            raise CheckFailed(f"the point gives no value for {tree[1]}")
        value = env[tree[1]]
        if not isinstance(value, Gaussian):
            raise _NotExact
        return value
    if head == "i":
        return Gaussian(Fraction(0), Fraction(1))
    if head == "+":
        out = Gaussian(Fraction(0))
        for a in tree[1:]:
            out = out + _exact(a, env)
        return out
    if head == "*":
        out = Gaussian(Fraction(1))
        for a in tree[1:]:
            out = out * _exact(a, env)
        return out
    if head == "^":
        base, exponent = _exact(tree[1], env), _exact(tree[2], env)
        if exponent.im != 0 or exponent.re.denominator != 1:
            raise _NotExact
        k = int(exponent.re)
        if abs(k) > 4096:
            raise _NotExact
        out = Gaussian(Fraction(1))
        for _ in range(abs(k)):
            out = out * base
        return out if k >= 0 else Gaussian(Fraction(1)) / out
    if head in ("re", "im", "conjugate"):
        value = _exact(tree[1], env)
        return {"re": Gaussian(value.re), "im": Gaussian(value.im), "conjugate": value.conj()}[head]
    if head == "abs":
        value = _exact(tree[1], env)
        if value.im == 0:
            return Gaussian(abs(value.re))
        raise _NotExact
    raise _NotExact


_FUNCTIONS = {
    "cos": lambda x: x.cos(), "sin": lambda x: x.sin(), "tan": lambda x: x.tan(), "cot": lambda x: x.cot(),
    "sec": lambda x: 1 / x.cos(), "csc": lambda x: 1 / x.sin(), "exp": lambda x: x.exp(), "log": lambda x: x.log(),
    "sqrt": lambda x: x.sqrt(), "atan": lambda x: x.atan(), "acos": lambda x: x.acos(), "asin": lambda x: x.asin(),
    "sinh": lambda x: x.sinh(), "cosh": lambda x: x.cosh(), "tanh": lambda x: x.tanh(),
    "re": lambda x: flint.acb(x.real), "im": lambda x: flint.acb(x.imag), "conjugate": lambda x: x.conjugate(),
    "abs": lambda x: flint.acb(abs(x)),
}


def _ball_of(value: Any) -> flint.acb:
    if isinstance(value, Gaussian):
        return flint.acb(flint.arb(flint.fmpq(value.re.numerator, value.re.denominator)),
                         flint.arb(flint.fmpq(value.im.numerator, value.im.denominator)))
    return flint.acb(value)


def _ball(tree: list, env: Mapping[str, Any]) -> flint.acb:
    head = tree[0]
    if head == "q":
        q = exact_q(tree[1])
        return flint.acb(flint.arb(flint.fmpq(q.numerator, q.denominator)))
    if head == "s":
        if tree[1] not in env:
            raise CheckFailed(f"the point gives no value for {tree[1]}")
        return _ball_of(env[tree[1]])
    if head == "i":
        return flint.acb(0, 1)
    if head == "pi":
        return flint.acb(flint.arb.pi())
    if head == "e":
        return flint.acb(1).exp()
    if head == "+":
        out = flint.acb(0)
        for a in tree[1:]:
            out += _ball(a, env)
        return out
    if head == "*":
        out = flint.acb(1)
        for a in tree[1:]:
            out *= _ball(a, env)
        return out
    if head == "^":
        base = _ball(tree[1], env)
        if tree[2][0] == "q" and exact_q(tree[2][1]).denominator == 1:
            k = int(exact_q(tree[2][1]))
            return base**k if k >= 0 else 1 / base ** (-k)
        return base ** _ball(tree[2], env)
    if head in _FUNCTIONS:
        return _FUNCTIONS[head](_ball(tree[1], env))
    raise CheckFailed(f"the tree has an unknown node {head!r}")


def evaluate_tree(tree: list, env: Mapping[str, Any]) -> Gaussian | flint.acb:
    """The value of an expression tree at ``env`` (names to :class:`Gaussian` or ``acb``): an exact
    Gaussian rational when every operation is rational, else a complex ball.

    >>> x = Gaussian(Fraction(1, 2))
    >>> evaluate_tree(["+", ["s", "x"], ["q", "1/3"]], {"x": x}).re
    Fraction(5, 6)
    >>> abs(evaluate_tree(["cos", ["s", "x"]], {"x": x}).real - flint.arb("0.8775825618903728")) < 1e-15
    True
    """
    try:
        return _exact(tree, env)
    except (_NotExact, ZeroDivisionError):
        pass
    with _precision(JUDGE_BITS):
        return _ball(tree, env)


def _sign(value: Gaussian | flint.acb) -> int | None:
    """Sign of a real value (``None``: a ball holding 0, or a value that is not real)."""
    if isinstance(value, Gaussian):
        if value.im != 0:
            return None
        return (value.re > 0) - (value.re < 0)
    if not value.imag.contains(0):
        return None
    if value.real > 0:
        return 1
    if value.real < 0:
        return -1
    return None


def _holds(tree: list, env: Mapping[str, Any]) -> bool | None:
    """Truth of a relation tree (``>``, ``>=``, ``<``, ``<=``, ``=``, ``and``); ``None`` when the
    balls do not decide it."""
    if tree[0] == "and":
        parts = [_holds(t, env) for t in tree[1:]]
        return None if None in parts else all(parts)
    op = tree[0]
    diff = evaluate_tree(["+", tree[1], ["*", ["q", "-1"], tree[2]]], env)
    sign = _sign(diff)
    if sign is None:
        if isinstance(diff, Gaussian) or not diff.imag.contains(0):
            return None
        return None
    return {">": sign > 0, ">=": sign >= 0, "<": sign < 0, "<=": sign <= 0, "=": sign == 0}.get(op)


# ---------------------------------------------------------------------------------------------
# positive realness from the definition
# ---------------------------------------------------------------------------------------------


def _circle_points(count: int) -> Iterator[Gaussian]:
    """``count`` rational points ``(1 + j t)/(1 - j t)`` of the unit circle, spread evenly in
    angle (``t`` a rational near ``tan(theta/2)`` for ``theta = 2 pi (k + 1/2)/count``, so
    ``z = +-1`` are not among them), and ``z = -1`` and ``z = 1`` themselves (skipped at poles)."""
    yield Gaussian(Fraction(-1))
    yield Gaussian(Fraction(1))
    for k in range(count):
        theta = 2 * math.pi * (k + 0.5) / count
        t = Fraction(math.tan(theta / 2)).limit_denominator(1000)
        d = 1 + t * t
        yield Gaussian((1 - t * t) / d, 2 * t / d)


#: Sample points per circle: a violation over more than 1/32 of the circle is seen at each radius.
_CIRCLE_COUNT = 32
#: Radii of the exact sample points outside the unit circle (1 itself: on it).
_RADII = (Fraction(1), Fraction(9, 8), Fraction(2), Fraction(10), Fraction(1000), Fraction(10) ** 6)


def _scaled(z: Gaussian, r: Fraction) -> Gaussian:
    return Gaussian(z.re * r, z.im * r)


def _boundary_points(den: flint.fmpq_poly, domain: str) -> list[Gaussian]:
    """Gaussian-rational points just outside each pole on the circle (or just right of each
    pole on the axis): where a negative residue shows as ``Re F < 0``."""
    if den.degree() <= 0:
        return []
    out = []
    try:
        with _precision(128):
            roots = flint.fmpq_poly(den).complex_roots()
    except (ValueError, AttributeError):
        return []
    for root, _ in roots:
        re, im = (Fraction(str(part.mid().str(30, radius=False))) for part in (root.real, root.imag))
        modulus = math.hypot(float(re), float(im))
        if domain == "disk":
            if abs(modulus - 1) > 1e-9 or modulus == 0:
                continue
            for eps in (Fraction(1, 10**3), Fraction(1, 10**6)):
                scale = (1 + eps) / Fraction(modulus).limit_denominator(10**30)
                out.append(Gaussian(re * scale, im * scale))
        elif abs(float(re)) < 1e-9:
            for eps in (Fraction(1, 10**3), Fraction(1, 10**6)):
                out.append(Gaussian(eps, im))
    return out


#: Matrices are sampled more thinly (an exact characteristic polynomial at each point).
_MATRIX_RADII, _MATRIX_COUNT = (Fraction(1), Fraction(9, 8), Fraction(1000)), 16


#: Distances from a pole on the circle at which a negative or non-real residue is looked for:
#: R/(z - z0) outweighs the rest of F only close enough (a damping of 1e300 against a residue
#: of 0.03 needs |z - z0| below 1e-301).
_POLE_LADDER = tuple(Fraction(1, 10 ** (3 * 2 ** k)) for k in range(8))


def _near_circle_poles(den: flint.fmpq_poly) -> Iterator[tuple[str, Gaussian]]:
    """Points outside the circle ever closer to each pole ``z0`` on it, radially and almost
    tangentially, ``z0 (1 + eps)`` and ``z0 (1 + eps (eps +- j))``: there ``Re F`` has the sign of
    ``Re(R/z0)`` and of ``-+Im(R/z0)`` times ``1/eps``, so a negative or non-real residue shows.
    Each pole is located to well below ``eps^2``."""
    if den.degree() <= 0:
        return
    for eps in _POLE_LADDER:
        digits = 2 * len(str(eps.denominator)) + 20
        try:
            with _precision(int(digits * 3.33) + 64):
                roots = flint.fmpq_poly(den).complex_roots()
        except (ValueError, AttributeError):
            return
        for root, _ in roots:
            re, im = (Fraction(part.mid().str(digits, radius=False)) for part in (root.real, root.imag))
            if abs(float(re * re + im * im) - 1) > 1e-9:
                continue
            z0 = Gaussian(re, im)
            for step in (Gaussian(eps), Gaussian(eps * eps, eps), Gaussian(eps * eps, -eps)):
                yield f"1e-{len(str(eps.denominator)) - 1} from the pole {_show(z0)} on the circle", z0 * (Gaussian(Fraction(1)) + step)


def _disk_points(den: flint.fmpq_poly, matrix: bool = False) -> Iterator[tuple[str, Gaussian]]:
    for r in _MATRIX_RADII if matrix else _RADII:
        for z in _circle_points(_MATRIX_COUNT if matrix else _CIRCLE_COUNT):
            yield (f"|z| = {r}", _scaled(z, r))
    for z in _boundary_points(den, "disk"):
        yield ("just outside a pole on the circle", z)


def _halfplane_points(den: flint.fmpq_poly) -> Iterator[tuple[str, Gaussian]]:
    for sigma in (Fraction(0), Fraction(1, 8), Fraction(1), Fraction(10), Fraction(1000), Fraction(10) ** 6):
        for w in (Fraction(0), Fraction(1, 3), Fraction(1), Fraction(3), Fraction(10), Fraction(100), Fraction(10) ** 4):
            for sign in (1, -1):
                yield (f"Re s = {sigma}", Gaussian(sigma, sign * w))
    for s in _boundary_points(den, "halfplane"):
        yield ("just right of a pole on the axis", s)


def _entries(transfer: Mapping[str, Any]) -> list[list[dict]]:
    if "entries" in transfer:
        return transfer["entries"]
    return [[transfer]]


def _hermitian_psd(entries: list[list[dict]], point: Gaussian) -> tuple[bool, Fraction] | None:
    """Whether ``F(point) + F(point)^H`` is PSD (all characteristic coefficients >= 0), and the
    smallest coefficient; ``None`` at a pole."""
    try:
        G = [[eval_transfer(e, point) for e in row] for row in entries]
    except CheckFailed:
        return None
    m = len(G)
    M = [[G[i][j] + G[j][i].conj() for j in range(m)] for i in range(m)]
    if m == 1:
        value = M[0][0].re
        return value >= 0, value
    E = charpoly_coefficients(M)
    return all(e >= 0 for e in E), min(E)


def _first_violation(entries: list[list[dict]], points: Iterable[tuple[str, Gaussian]]) -> tuple[int, tuple | None]:
    """The points checked (poles skipped) up to the first ``(where, point, value)`` where the
    Hermitian part is not PSD, or ``None`` when it is PSD at every one."""
    checked = 0
    for where, point in points:
        psd = _hermitian_psd(entries, point)
        if psd is None:
            continue
        checked += 1
        if not psd[0]:
            return checked, (where, point, psd[1])
    return checked, None


def _pole_violations(entries: list[list[dict]], domain: str) -> list[str]:
    """Improper entries, poles outside, repeated poles on the boundary: from the raw polynomials."""
    out = []
    for i, row in enumerate(entries):
        for j, e in enumerate(row):
            num, den = json_poly(e["num"]), json_poly(e["den"])
            where = f" (entry {i + 1},{j + 1})" if len(entries) > 1 else ""
            if den.is_zero():
                out.append(f"a zero denominator{where}")
                continue
            excess = 0 if domain == "disk" else 1
            if not is_proper(num, den, excess):
                g = num.gcd(den)
                out.append(f"improper: a pole at infinity (deg num {(num / g).degree()} > deg den "
                           f"{(den / g).degree() + excess - (1 if excess else 0)}){where}")
                continue
            g = num.gcd(den) if not num.is_zero() else den
            reduced = den / g if not num.is_zero() else flint.fmpq_poly([1])
            if excess and not num.is_zero() and (num / g).degree() == reduced.degree() + 1:
                lead = (num / g).coeffs()[-1] / reduced.coeffs()[-1]
                if lead < 0:
                    out.append(f"a pole at infinity with a negative residue{where}")
            if has_root_outside(reduced, domain):
                out.append(f"a pole {'outside the unit circle' if domain == 'disk' else 'in Re s > 0'}{where}")
            repeated = reduced.gcd(reduced.derivative()) if reduced.degree() > 0 else flint.fmpq_poly([1])
            if repeated.degree() > 0 and _on_boundary(repeated, domain):
                out.append(f"a repeated pole on the {'unit circle' if domain == 'disk' else 'imaginary axis'}{where}")
    return out


def _on_boundary(p: flint.fmpq_poly, domain: str) -> bool:
    """``p`` has a root on the unit circle (``disk``) or the imaginary axis (``halfplane``)."""
    coeffs = p.coeffs()
    zeros = next(k for k, a in enumerate(coeffs) if a != 0)
    core = flint.fmpq_poly(coeffs[zeros:])
    if domain == "disk":
        if core(-1) == 0:
            return True
        R = bilinear(core)
    else:
        if zeros:
            return True
        R = core
    if R.degree() <= 0:
        return False
    return count_with_multiplicity(axis_gcd(R))[0] > 0


def _witness_point(witness: Mapping[str, Any] | None, domain: str) -> Gaussian | None:
    if not witness:
        return None
    if domain == "disk" and isinstance(witness.get("z"), (list, tuple)):
        return Gaussian(exact_q(witness["z"][0]), exact_q(witness["z"][1]))
    if domain == "halfplane" and "omega" in witness:
        return Gaussian(Fraction(0), exact_q(witness["omega"]))
    if domain == "halfplane" and isinstance(witness.get("s"), (list, tuple)):
        return Gaussian(exact_q(witness["s"][0]), exact_q(witness["s"][1]))
    return None


#: Transfer functions above this degree are not judged (each sample point costs a Horner
#: evaluation over exact Gaussian rationals: a delay of 10 000 samples would take minutes).
MAX_JUDGED_DEGREE = 400

#: Matrices above this size are not judged (an exact LDL^H at each of hundreds of points; the
#: uniform scenes of a thousand users are decided by their modes instead).
MAX_JUDGED_SIZE = 8


class _NotJudged(Exception):
    pass


def _within_limits(entries: list[list[dict]]) -> None:
    if len(entries) > MAX_JUDGED_SIZE:
        raise _NotJudged(f"a {len(entries)} x {len(entries)} matrix is above the judge's limit {MAX_JUDGED_SIZE}")
    degree = max(max(len(e["num"]), len(e["den"])) - 1 for row in entries for e in row)
    if degree > MAX_JUDGED_DEGREE:
        raise _NotJudged(f"degree {degree} above the judge's limit {MAX_JUDGED_DEGREE}")


def _positive_real(obj: Mapping[str, Any]) -> str:
    domain = obj.get("domain", "disk")
    entries = _entries(obj["transfer"])
    decision = obj["decision"]
    witness = _witness_point(obj.get("witness"), domain)
    try:
        _within_limits(entries)
    except _NotJudged:
        if decision != "disproved" or witness is None or len(entries) > MAX_JUDGED_SIZE:
            raise
        if len(entries) == 1:                                 # one certified value decides a disproof, whatever the degree
            return _scalar_at_witness(entries[0][0], witness, domain)
        return _at_witness(entries, witness, domain, [])
    structural = _pole_violations(entries, domain)
    den = json_poly(entries[0][0]["den"]) if len(entries) == 1 else flint.fmpq_poly([1])
    if len(entries) > 1:
        for row in entries:
            for e in row:
                den = den * json_poly(e["den"])
    points = _disk_points(den, len(entries) > 1) if domain == "disk" else _halfplane_points(den)
    if decision == "proved":
        if structural:
            raise CheckFailed(f"{structural[0]}, not positive real")
        checked, bad = _first_violation(entries, points)
        if bad is not None:
            raise CheckFailed(f"the Hermitian part is not PSD at {_show(bad[1])} ({bad[0]}): the definition fails")
        return f"definition: proper, no pole outside, Hermitian part PSD at {checked} exact points on and outside the boundary"
    if decision != "disproved":
        return "nothing to judge (the decision is neither proved nor disproved)"
    if witness is not None:
        return _at_witness(entries, witness, domain, structural)
    if structural:
        return f"definition fails: {structural[0]}"
    near = _near_circle_poles(den) if domain == "disk" and len(entries) == 1 else ()
    _, bad = _first_violation(entries, itertools.chain(points, near))
    if bad is not None:
        return f"definition fails at {_show(bad[1])} ({bad[0]})"
    raise CheckFailed("no violation of the definition found (no pole outside, proper, Hermitian part PSD at every point tried)")


@contextlib.contextmanager
def _precision(bits: int) -> Iterator[None]:
    old = flint.ctx.prec
    flint.ctx.prec = bits
    try:
        yield
    finally:
        flint.ctx.prec = old


def _scalar_at_witness(entry: Mapping[str, Any], witness: Gaussian, domain: str) -> str:
    """A scalar disproof of high degree at its witness: ``Re G`` in ball arithmetic (exact
    rational coefficients, the witness as exact balls, precision raised until the sign is certain;
    exact Gaussian rationals would grow to ``degree`` times the witness's digits)."""
    inside = witness.re * witness.re + witness.im * witness.im < 1 if domain == "disk" else witness.re < 0
    if inside:
        raise CheckFailed(f"the witness {_show(witness)} lies inside the {'unit disk' if domain == 'disk' else 'left half plane'}")
    num, den = json_poly(entry["num"]), json_poly(entry["den"])
    for prec in (128, 512, 2048):
        with _precision(prec):
            point = flint.acb(flint.arb(flint.fmpq(witness.re.numerator, witness.re.denominator)),
                              flint.arb(flint.fmpq(witness.im.numerator, witness.im.denominator)))
            d = flint.acb_poly(den)(point)
            if d.contains(0):
                continue
            value = (flint.acb_poly(num)(point) / d).real
            if value < 0:
                return f"definition fails at the witness {_show(witness)}: Re G = {value.str(5)} < 0 (ball arithmetic)"
            if value >= 0:
                raise CheckFailed(f"the witness {_show(witness)} is no counterexample: Re G = {value.str(5)} >= 0 there")
    raise _NotJudged(f"the sign of Re G at the witness {_show(witness)} is not certain at 2048 bits")


def _at_witness(entries: list[list[dict]], witness: Gaussian, domain: str, structural: list[str]) -> str:
    """A disproof's witness: a point on or outside the boundary where the Hermitian part is not PSD."""
    inside = witness.re * witness.re + witness.im * witness.im < 1 if domain == "disk" else witness.re < 0
    if inside:
        raise CheckFailed(f"the witness {_show(witness)} lies inside the {'unit disk' if domain == 'disk' else 'left half plane'}")
    psd = _hermitian_psd(entries, witness)
    if psd is None:
        raise CheckFailed(f"the witness {_show(witness)} is a pole of the transfer function, not a point of the definition")
    if psd[0]:              # a point shown as a counterexample must be one, whatever else fails
        raise CheckFailed(f"the witness {_show(witness)} is no counterexample: the Hermitian part is PSD there"
                          + (f" ({structural[0]} elsewhere)" if structural else ""))
    return f"definition fails at the witness {_show(witness)}: the Hermitian part is not PSD ({psd[1]} < 0)"


def _show(z: Gaussian) -> str:
    def short(q: Fraction) -> str:
        text = str(q)
        return text if len(text) <= 24 else f"{float(q):.6g}"
    return f"{short(z.re)} + {short(z.im)}j"


def _circle_psd(obj: Mapping[str, Any]) -> str:
    """``F(e^{j theta}) + F(e^{j theta})^H >= 0`` for every ``theta`` (the worst case over
    frequency alone, poles not included): a ``proved`` must hold at every sample point of the
    circle, a ``disproved`` at its witness (or a sample point) must fail."""
    entries = _entries(obj["transfer"])
    _within_limits(entries)
    witness = _witness_point(obj.get("witness"), "disk")
    circle = (("on the circle", z) for z in _circle_points(4 * _CIRCLE_COUNT))
    if obj["decision"] == "proved":
        checked, bad = _first_violation(entries, circle)
        if bad is not None:
            raise CheckFailed(f"the Hermitian part is not PSD at z = {_show(bad[1])} on the circle ({bad[2]} < 0)")
        return f"the Hermitian part is PSD at {checked} exact points of the circle"
    if obj["decision"] != "disproved":
        return "nothing to judge (the decision is neither proved nor disproved)"
    if witness is not None:
        if witness.re * witness.re + witness.im * witness.im != 1:
            raise CheckFailed(f"the witness {_show(witness)} is not on the unit circle")
        psd = _hermitian_psd(entries, witness)
        if psd is None:
            raise CheckFailed(f"the witness {_show(witness)} is a pole of the transfer function")
        if psd[0]:
            raise CheckFailed(f"the witness {_show(witness)} is no counterexample: the Hermitian part is PSD there")
        return f"the Hermitian part is not PSD at the witness {_show(witness)} ({psd[1]} < 0)"
    _, bad = _first_violation(entries, circle)
    if bad is not None:
        return f"the Hermitian part is not PSD at z = {_show(bad[1])}"
    raise CheckFailed("no point of the circle where the Hermitian part fails to be PSD was given or found")


# ---------------------------------------------------------------------------------------------
# printed expressions of Re G^-1 on the circle
# ---------------------------------------------------------------------------------------------


def _circle_env(point: Mapping[str, Any], frequency: str, period: list | None) -> tuple[dict[str, Any], Gaussian, flint.arb]:
    """The point's values (exact), ``z = u^L`` (exact) and ``theta = 2 L atan(t)`` (a ball),
    ``omega = theta/T`` in the environment."""
    env: dict[str, Any] = {name: Gaussian(exact_q(v)) for name, v in point.get("values", {}).items()}
    if "n" in point:
        env["n"] = Gaussian(Fraction(int(point["n"])))
    t, L = exact_q(point["t"]), int(point["L"])
    u = Gaussian(Fraction(1), t) / Gaussian(Fraction(1), -t)
    z = Gaussian(Fraction(1))
    for _ in range(L):
        z = z * u
    with _precision(JUDGE_BITS):
        theta = 2 * L * flint.arb(flint.fmpq(t.numerator, t.denominator)).atan()
        T = _ball(period, env) if period is not None else _ball_of(env.get("T", Gaussian(Fraction(1))))
        env[frequency] = flint.acb(theta) / T
    return env, z, theta


def _identity_at_own_points(obj: Mapping[str, Any], frequency: str) -> int:
    """The display against ``Re G^{-1}`` of the object's own ``inverse`` tree at points the
    judge chooses (:func:`own_points`): as many as the two trees have nodes (a bound on the
    degree of their difference in each parameter), at least 8, at most :data:`MAX_OWN_POINTS`."""
    inverse, display = obj["inverse"], obj["display"]
    variable = obj.get("variable", "z")
    names = names_of(display) | names_of(inverse) | names_of(obj.get("period"))
    first = obj["points"][0]
    known = set(first.get("values", {})) | {variable, frequency} | ({"n"} if "n" in first else set())
    if names - known:
        raise CheckSkipped(f"the trees name {', '.join(sorted(names - known))[:60]}, which the object's points give no "
                           "value: the checker does not choose one")
    needed = min(MAX_OWN_POINTS, max(8, tree_size(display) + tree_size(inverse)))
    checked = 0
    for point in own_points(obj, names, 4 * needed):
        if checked >= needed:
            break
        env, z, _ = _circle_env(point, frequency, obj.get("period"))
        try:
            with _precision(JUDGE_BITS):
                real = _ball(inverse, {**_balls(env), variable: _ball_of(z)}).real
                shown = _ball(display, env)
                diff = shown - flint.acb(real)
        except (ZeroDivisionError, CheckFailed, ValueError):
            continue                                   # a pole of G^-1 or of the display
        if not diff.real.contains(0) or not diff.imag.contains(0):
            raise CheckFailed(f"the display is {shown.real.str(8)} but Re G^-1 = {real.str(8)} at a point the checker "
                              f"chose (z = {_show(z)}, {', '.join(f'{k} = {v}' for k, v in point['values'].items())}"
                              f"{', n = ' + str(point['n']) if 'n' in point else ''}): not the same function")
        checked += 1
    if checked < needed:
        raise CheckSkipped(f"the identity holds at {checked} points of the checker's choosing only, fewer than {needed}")
    return checked


def _circle_identity(obj: Mapping[str, Any]) -> str:
    claim = obj["claim"]
    frequency = obj.get("frequency", "omega")
    if not isinstance(obj.get("points"), list) or not obj["points"]:
        raise CheckFailed("the judge object carries no point of the circle (no point is no evidence)")
    outcomes = []
    for k, point in enumerate(obj["points"]):
        env, z, _ = _circle_env(point, frequency, obj.get("period"))
        transfer = point["transfer"]
        n = int(point.get("n", 0))
        real = eval_transfer(transfer, z).re
        with _precision(JUDGE_BITS):
            shown = _ball(obj["display"], env)
            diff = shown - _ball_of(Gaussian(real))
        differs = not diff.real.contains(0) or not diff.imag.contains(0)
        outcomes.append(differs)
        if claim == "equal" and differs:
            raise CheckFailed(f"the display is {shown.real.str(8)} but Re G^-1 = {float(real):.8g} at point {k + 1} "
                              f"(z = {_show(z)}{f', n = {n}' if 'n' in point else ''}): not the same function")
        if claim == "differ":
            break
    if claim == "differ":
        if not outcomes or not outcomes[0]:
            raise CheckFailed("the display equals Re G^-1 at the witness: it is no counterexample")
        return "the display differs from Re G^-1 of the scene at the witness (ball arithmetic, exact transfer)"
    if not isinstance(obj.get("inverse"), list):
        raise CheckSkipped("the identity carries no G^-1 of the scene: the checker cannot test it at points of "
                           "its own choosing (the object's points are the author's)")
    own = _identity_at_own_points(obj, frequency)
    return (f"the display equals Re G^-1 of the scene at {len(outcomes)} points of the circle and at {own} points of "
            "the checker's choosing (ball arithmetic)")


# ---------------------------------------------------------------------------------------------
# printed conditions against the scene's G^-1
# ---------------------------------------------------------------------------------------------


def _inverse_at(tree: list, env: Mapping[str, Any], z: Gaussian, variable: str = "z") -> Any:
    return evaluate_tree(tree, {**env, variable: z})


def _real_sign(value: Any) -> int | None:
    if isinstance(value, Gaussian):
        return (value.re > 0) - (value.re < 0)
    if value.real > 0:
        return 1
    if value.real < 0:
        return -1
    return None


#: The parameter values the condition judge tries along each parameter from a point of its own:
#: the point's value times 2^(k/8), k = -40..40 (a factor 32 either way, steps of 9 %).
_SCAN = tuple(range(-40, 41))
#: Bisection steps towards the printed condition's boundary between a holding and a failing value.
_BISECT = 16


def _holds_ball(tree: list, values: Mapping[str, Gaussian]) -> bool | None:
    """:func:`_holds` with every value a ball (bounded work; ``None`` where a ball holds 0)."""
    with _precision(JUDGE_BITS):
        return _holds(tree, _balls(values))


def _balls(values: Mapping[str, Any]) -> dict[str, flint.acb]:
    return {name: _ball_of(v) for name, v in values.items()}


def _negative_on_circle(tree: list, values: Mapping[str, Gaussian], variable: str) -> Gaussian | None:
    """A point of the unit circle where ``Re G^{-1} < 0`` -- certainly: the whole ball is
    negative (balls, not exact fractions, so the judge's own search is bounded whatever the tree's
    powers and the bisection's denominators)."""
    env = _balls(values)
    with _precision(JUDGE_BITS):
        for z in _circle_points(_CIRCLE_COUNT):
            try:
                value = _ball(tree, {**env, variable: _ball_of(z)})
            except (ZeroDivisionError, CheckFailed, ValueError):
                continue
            if value.real < 0:
                return z
    return None


def _sufficient_at_own_points(obj: Mapping[str, Any]) -> int:
    """A confirmed (sufficient) printed condition tested where the checker chooses: from points
    of its own (:func:`own_points`), each parameter is scanned and the printed condition's
    boundary found by bisection; just inside it, the scene's own ``G^{-1}`` (the ``inverse``
    tree) must have ``Re G^{-1} >= 0`` at the judge's points of the circle. A printed bound
    below the exact one (``b > KT/8 + B`` for ``b >= KT/2 + B``) holds there while the scene is
    not passive: refused, whatever points the report carries."""
    display, tree, variable = obj["display"], obj["inverse"], obj.get("variable", "z")
    names = sorted((names_of(display) | names_of(tree)) - {variable})
    known = set().union(*(set(sample) for sample in obj["samples"] if isinstance(sample, Mapping))) | {"n"}
    if set(names) - known:
        raise CheckSkipped(f"the trees name {', '.join(sorted(set(names) - known))[:60]}, which the samples give no "
                           "value: the checker does not choose one")
    tried = 0
    for k, point in enumerate(own_points(obj, names, 4)):
        signs = obj["samples"][0] if isinstance(obj["samples"][0], Mapping) else {}
        # each value with the sign of the author's first sample (a parameter declared negative stays negative)
        base = {name: -exact_q(v) if name in signs and exact_q(signs[name]) < 0 else exact_q(v)
                for name, v in point["values"].items()}
        if "n" in names:
            base["n"] = Fraction(1 + k % 3)             # the delay: a whole number of samples
        for name in sorted(names_of(display) - {variable, "n"}):
            if name not in base:
                continue
            previous = None
            for k in _SCAN:
                value = base[name] * (Fraction(2) ** (k // 8)) * (Fraction(1) + Fraction(k % 8, 8))
                env = {n: Gaussian(v) for n, v in {**base, name: value}.items()}
                try:
                    holds = _holds_ball(display, env)
                except (ZeroDivisionError, CheckFailed):
                    holds = None
                if holds is not None and previous is not None and holds != previous[1]:
                    inside, outside = (value, previous[0]) if holds else (previous[0], value)
                    for _ in range(_BISECT):
                        middle = (inside + outside) / 2
                        try:
                            between = _holds_ball(display, {**env, name: Gaussian(middle)})
                        except (ZeroDivisionError, CheckFailed):
                            break
                        if between is None:
                            break
                        inside, outside = (middle, outside) if between else (inside, middle)
                    at = {**env, name: Gaussian(inside)}
                    tried += 1
                    bad = _negative_on_circle(tree, at, variable)
                    if bad is not None:
                        shown = ", ".join(f"{n} = {v.re}" for n, v in sorted(at.items()))
                        raise CheckFailed(f"the printed condition holds at a point the checker chose ({shown}), but "
                                          f"Re G^-1({_show(bad)}) < 0 there: it is not sufficient")
                previous = (value, holds) if holds is not None else previous
    return tried


def _condition(obj: Mapping[str, Any]) -> str:
    if obj.get("claim") == "holds-passive":
        if not isinstance(obj.get("samples"), list) or not obj["samples"]:
            raise CheckFailed("a confirmed condition is judged at no sample point (no point is no evidence)")
        done = [_condition({**obj, "values": sample, "samples": None, "claim": "holds-passive-at"})
                for sample in obj["samples"]]
        if obj.get("region") is not None:
            # a scene restricted to a region (assumptions, a change of variables): points of the
            # checker's own may lie outside it, so none is chosen -- and the claim is not re-verified
            raise CheckSkipped("a condition judged in a restricted region: the checker chooses no points of its own "
                               "there (its samples are the author's)")
        _sufficient_at_own_points(obj)          # (its reason unchanged: the audit's tally stays as it was)
        return f"{len(done)} points where the printed condition holds: " + done[-1]
    values = {name: Gaussian(exact_q(v)) for name, v in obj["values"].items()}
    variable = obj.get("variable", "z")
    holds = _holds(obj["display"], values)
    if holds is None:
        raise CheckFailed("the printed condition is not decided at the witness (its two sides are equal, or a ball holds 0)")
    claim = "holds-passive" if obj["claim"] == "holds-passive-at" else obj["claim"]
    expected = claim in ("holds-not-passive", "holds-passive")
    if holds != expected:
        raise CheckFailed(f"the printed condition {'holds' if holds else 'fails'} at the witness, "
                          f"the finding says it {'holds' if expected else 'fails'}")
    tree = obj["inverse"]
    if claim.endswith("not-passive"):
        z0 = obj.get("point")
        if z0 is not None:
            z = Gaussian(exact_q(z0[0]), exact_q(z0[1]))
            if z.re * z.re + z.im * z.im < 1:
                raise CheckFailed(f"the point {_show(z)} lies inside the unit disk")
            try:
                sign = _real_sign(_inverse_at(tree, values, z, variable))
            except ZeroDivisionError:
                sign = None
            if sign == -1:
                return f"the printed condition {'holds' if holds else 'fails'} at the witness and Re G^-1({_show(z)}) < 0 there"
            raise CheckFailed(f"Re G^-1({_show(z)}) is not negative at the witness: the scene is no counterexample there")
        for where, z in _disk_points(flint.fmpq_poly([1])):
            try:
                sign = _real_sign(_inverse_at(tree, values, z, variable))
            except ZeroDivisionError:
                continue
            if sign == -1:
                return f"the printed condition holds at the witness and Re G^-1 < 0 at {_show(z)} ({where})"
        raise _NotJudged("no point with Re G^-1 < 0 was given or found (a pole condition may fail)")
    checked = 0
    for where, z in _disk_points(flint.fmpq_poly([1])):
        try:
            sign = _real_sign(_inverse_at(tree, values, z, variable))
        except ZeroDivisionError:
            continue
        checked += 1
        if sign == -1:
            raise CheckFailed(f"the finding says G^-1 is positive real at the witness, but Re G^-1({_show(z)}) < 0 ({where})")
    return f"the printed condition {'holds' if holds else 'fails'} at the witness; Re G^-1 >= 0 at {checked} points on and outside the circle"


# ---------------------------------------------------------------------------------------------
# stability of a sampled-data loop
# ---------------------------------------------------------------------------------------------


def _arb_rows(rows: list[list[str]], shape: tuple[int, int]) -> flint.arb_mat:
    r, c = shape
    if r == 0 or c == 0:
        return flint.arb_mat(r, c)
    return flint.arb_mat(r, c, [flint.arb(flint.fmpq(q.numerator, q.denominator)) for row in rows for q in map(exact_q, row)])


#: States of a loop the judge builds (plant plus controller, inputs, outputs): the sizes come
#: from the report, so they are checked before any matrix is allocated (a negative size makes
#: the native library abort the process, 10^8 asks it for gigabytes).
MAX_LOOP_SIZE = 64


def _check_loop(loop: Mapping[str, Any]) -> None:
    """The loop's sizes are small non-negative integers and every matrix has them."""
    shape = loop["shape"]
    plant = shape["plant"]
    sizes = {"plant": plant[0] if isinstance(plant, list) and len(plant) == 2 and plant[0] == plant[1] else None,
             "inputs": shape["inputs"], "outputs": shape["outputs"], "controller": shape["controller"]}
    for name, size in sizes.items():
        if not isinstance(size, int) or isinstance(size, bool) or not 0 <= size <= MAX_LOOP_SIZE:
            raise CheckFailed(f"the loop's {name} size {str(size)[:20]} is not a whole number from 0 to {MAX_LOOP_SIZE}")
    n, m, p, k = sizes["plant"], sizes["inputs"], sizes["outputs"], sizes["controller"]
    ctrl = loop["controller"]
    for rows, (r, c), name in ((loop["state"], (n, n), "state"), (loop["input"], (n, m), "input"),
                               (loop["output"], (p, n), "output"), (ctrl["state"], (k, k), "controller state"),
                               (ctrl["input"], (k, p), "controller input"), (ctrl["output"], (m, k), "controller output"),
                               (ctrl["feedthrough"], (m, p), "controller feedthrough")):
        if r == 0 or c == 0:
            continue
        if not isinstance(rows, list) or len(rows) != r or any(not isinstance(row, list) or len(row) != c for row in rows):
            raise CheckFailed(f"the loop's matrix {name} is not {r} x {c}")
    exact_q(loop["period"])


def _closed_loop(loop: Mapping[str, Any]) -> flint.arb_mat:
    """The sample-to-sample matrix of the loop from its definition: over one period the zero-order
    hold gives ``x+ = Phi x + Gamma u`` with ``[[Phi, Gamma], [0, I]] = exp([[a, bu], [0, 0]] T)``;
    the controller ``eta+ = A eta + B y``, ``u = C eta + D y`` with ``y = c x``."""
    n, m = loop["shape"]["plant"][0], loop["shape"]["inputs"]
    p, k = loop["shape"]["outputs"], loop["shape"]["controller"]
    T = exact_q(loop["period"])
    a, bu, c = _arb_rows(loop["state"], (n, n)), _arb_rows(loop["input"], (n, m)), _arb_rows(loop["output"], (p, n))
    ctrl = loop["controller"]
    A, B, C, D = (_arb_rows(ctrl["state"], (k, k)), _arb_rows(ctrl["input"], (k, p)), _arb_rows(ctrl["output"], (m, k)),
                  _arb_rows(ctrl["feedthrough"], (m, p)))
    Tb = flint.arb(flint.fmpq(T.numerator, T.denominator))
    gen = flint.arb_mat(n + m, n + m)
    for i in range(n):
        for j in range(n):
            gen[i, j] = a[i, j] * Tb
        for j in range(m):
            gen[i, n + j] = bu[i, j] * Tb
    E = gen.exp()
    size = n + k
    M = flint.arb_mat(size, size)
    gamma = flint.arb_mat(n, m, [E[i, n + j] for i in range(n) for j in range(m)]) if m else flint.arb_mat(n, 0)
    top_left = flint.arb_mat(n, n, [E[i, j] for i in range(n) for j in range(n)]) + (gamma * D * c if m and p else 0)
    for i in range(n):
        for j in range(n):
            M[i, j] = top_left[i, j]
    if k:
        top_right, bottom_left = gamma * C, B * c
        for i in range(n):
            for j in range(k):
                M[i, n + j] = top_right[i, j]
        for i in range(k):
            for j in range(n):
                M[n + i, j] = bottom_left[i, j]
            for j in range(k):
                M[n + i, n + j] = A[i, j]
    return M


def _schur_cohn(coeffs: list[flint.arb]) -> bool | None:
    """All roots of a real polynomial (ascending coefficients) strictly inside the unit circle
    (``True``), not all of them (``False``), or undecided: the Schur-Cohn recursion, every
    reflection coefficient ``a_0/a_k`` certainly inside ``(-1, 1)``."""
    p = list(coeffs)
    while len(p) > 1:
        lead, const = p[-1], p[0]
        if not (lead > 0 or lead < 0):
            return None
        r = const / lead
        if abs(r) < 1:
            # p - r p* (p* the reversed polynomial) has a zero constant term and, by Rouche, as
            # many zeros inside as p: divided by z it carries the test one degree down
            k = len(p) - 1
            p = [p[i] - r * p[k - i] for i in range(1, k + 1)]
            continue
        if abs(r) > 1:
            return False
        return None
    return True


def _stability(obj: Mapping[str, Any]) -> str:
    outcomes = []
    sides = obj["sides"]
    if not isinstance(sides, list) or len(sides) != 2:
        raise CheckFailed("a boundary is judged by its two sides")
    for side in sides:
        _check_loop(side["loop"])
    for side in sides:
        decided = None
        shape = side["loop"]["shape"]
        states = shape["plant"][0] + shape["inputs"] + shape["controller"]
        for bits in (256, 1024, 4096):
            # a matrix exponential and a characteristic polynomial of the closed loop: ~N^3 x bits
            spend(states ** 3 * bits // 4)
            with _precision(bits):
                M = _closed_loop(side["loop"])
                chi = M.charpoly()
                coeffs = [chi[i] for i in range(chi.degree() + 1)]
                if side["loop"].get("rigid"):       # the exact eigenvalue 1 of a free translation: divide it out
                    quotient, carry = [], flint.arb(0)
                    for a in reversed(coeffs):
                        carry = a + carry
                        quotient.append(carry)
                    coeffs = list(reversed(quotient[:-1]))
                decided = _schur_cohn(coeffs)
            if decided is not None:
                break
        if decided is None:
            raise CheckFailed(f"the loop at {obj.get('parameter', 'p')} = {side['value']:.10g} is not decided by Schur-Cohn")
        if decided != side["stable"]:
            raise CheckFailed(f"the loop at {obj.get('parameter', 'p')} = {side['value']:.10g} is "
                              f"{'stable' if decided else 'not stable'}, the boundary says {'stable' if side['stable'] else 'unstable'}")
        outcomes.append(f"{'stable' if decided else 'unstable'} at {side['value']:.10g}")
    return "Schur-Cohn on the exact ZOH loop: " + ", ".join(outcomes)


# ---------------------------------------------------------------------------------------------
# displayed witnesses against the judge's point
# ---------------------------------------------------------------------------------------------


def displayed_number(value: Any) -> Any:
    """A displayed value as the judge compares it: an exact rational, a float from ``approx``, or as is."""
    if isinstance(value, dict) and "approx" in value:
        return float(value["approx"])
    if isinstance(value, str):
        try:
            return exact_q(value)
        except (ValueError, ZeroDivisionError):
            return value
    return value


def consistent_witness(witness: Mapping[str, Any] | None, obj: Mapping[str, Any],
                       keys: Mapping[str, str] | None = None) -> list[str]:
    """Disagreements between a finding's displayed witness and the judge object's point (empty
    when they agree): parameters, ``n``, ``c``, ``z``, ``omega_T`` and ``omega`` -- the circle's
    keys as the report names them (``keys``: :func:`~hapticproof.core.naming.witness_keys`)."""
    if not witness:
        return []
    try:
        return _witness_problems(witness, obj, witness_keys() if keys is None else keys)
    except (CheckFailed, KeyError, TypeError, ValueError, ZeroDivisionError, IndexError) as err:
        return [f"the displayed witness cannot be held against the judge object ({type(err).__name__}: {err})"]


def _witness_problems(witness: Mapping[str, Any], obj: Mapping[str, Any], keys: Mapping[str, str]) -> list[str]:
    problems = []
    if obj.get("judge") == "circle-identity":
        point = obj["points"][0]
        values = point.get("values", {})
        for name, value in values.items():
            if name in witness and displayed_number(witness[name]) != exact_q(value):
                problems.append(f"the displayed {name} = {witness[name]} is not the point's {value}")
        if "n" in point and "n" in witness and displayed_number(witness["n"]) != int(point["n"]):
            problems.append(f"the displayed n = {witness['n']} is not the point's {point['n']}")
        env, z, theta = _circle_env(point, obj.get("frequency", "omega"), obj.get("period"))
        cos = keys["c"]
        if cos in witness and displayed_number(witness[cos]) != z.re:
            problems.append(f"the displayed {cos} = {witness[cos]} is not cos(omega T) = {z.re} of the point")
        if isinstance(witness.get("z"), (list, tuple)):
            shown = Gaussian(exact_q(witness["z"][0]), exact_q(witness["z"][1]))
            if (shown.re, shown.im) != (z.re, z.im):
                problems.append(f"the displayed z = {_show(shown)} is not e^(j omega T) = {_show(z)} of the point")
        for key, target in ((keys["omega_T"], theta), (keys["omega"], env.get(obj.get("frequency", "omega")))):
            if key in witness and target is not None:
                value = displayed_number(witness[key])
                ball = target.real if isinstance(target, flint.acb) else target
                if isinstance(value, (int, float, Fraction)) and abs(float(value) - float(ball.mid())) > 1e-9 * (1 + abs(float(ball.mid()))):
                    problems.append(f"the displayed {key} = {value} is not the point's {float(ball.mid()):.12g}")
    elif obj.get("judge") == "condition" and obj.get("claim") != "holds-passive":   # (holds-passive: the judge's own points)
        for name, value in obj["values"].items():
            if name in witness and displayed_number(witness[name]) != exact_q(value):
                problems.append(f"the displayed {name} = {witness[name]} is not the judged point's {value}")
    elif obj.get("judge") == "positive-real":
        own = obj.get("witness") or {}
        for key in ("c", "omega", "x"):
            shown = keys[key]
            if shown in witness and key in own and displayed_number(witness[shown]) != displayed_number(own[key]):
                problems.append(f"the displayed {shown} = {witness[shown]} is not the decision's {own[key]}")
        if isinstance(witness.get("z"), (list, tuple)) and isinstance(own.get("z"), (list, tuple)) and \
                [exact_q(v) for v in witness["z"]] != [exact_q(v) for v in own["z"]]:
            problems.append(f"the displayed z = {witness['z']} is not the decision's {own['z']}")
    return problems


# ---------------------------------------------------------------------------------------------
# entry points
# ---------------------------------------------------------------------------------------------


_JUDGES = {"positive-real": _positive_real, "circle-identity": _circle_identity, "condition": _condition,
           "stability": _stability, "circle-psd": _circle_psd}


def judge(obj: Mapping[str, Any]) -> Judgement:
    """Judge one object (a dict with a ``"judge"`` kind) against the definition."""
    kind = obj.get("judge")
    run = _JUDGES.get(kind)
    if run is None:
        return Judgement(False, f"FAILED: unknown judge kind {str(kind)[:40]!r} (known: {', '.join(sorted(_JUDGES))})")
    try:
        with budget():
            return Judgement(True, run(obj))
    except (_NotJudged, CheckSkipped) as err:
        return Judgement(True, f"not judged: {err}", judged=False)
    except CheckFailed as err:
        return Judgement(False, f"FAILED: {err}")
    except (KeyError, TypeError, ValueError, ZeroDivisionError, IndexError, AttributeError, ArithmeticError,
            RecursionError) as err:
        return Judgement(False, f"FAILED: malformed judge object ({type(err).__name__}: {err})")


def judged_definition(domain: str, decision: str, transfer: Mapping[str, Any],
                      witness: Mapping[str, Any] | None = None, kind: str = "positive-real") -> dict[str, Any] | None:
    """The ``positive-real`` judge object of a decision, judged now: its ``judged`` field holds
    the answer (a report that shows the decision carries both; ``None`` for a decision that is
    neither proved nor disproved). ``kind="circle-psd"``: the Hermitian part on the circle alone
    (a worst case over frequency, the poles not included).

    >>> obj = judged_definition("disk", "proved", {"variable": "z", "num": ["1", "-1", "1"], "den": ["-1", "1"]})
    >>> obj["judged"]["ok"]
    False
    """
    if decision not in ("proved", "disproved"):
        return None
    obj: dict[str, Any] = {"judge": kind, "domain": domain, "decision": decision, "transfer": dict(transfer)}
    if witness:
        obj["witness"] = {k: (list(v) if isinstance(v, tuple) else v) for k, v in witness.items()}
    answer = judge(obj)
    obj["judged"] = {"ok": answer.ok, "reason": answer.reason}
    return obj


def judges(node: Any) -> Iterator[dict]:
    """Every judge object inside a JSON value (a dict with a string ``judge`` kind)."""
    if isinstance(node, dict):
        if is_kind(node.get("judge")):
            yield node
            return
        for value in node.values():
            yield from judges(value)
    elif isinstance(node, list):
        for value in node:
            yield from judges(value)
