r"""The numeric fast path: a single-user scene given by numbers -> the whole exact decision.

:func:`decide` answers the question of :func:`hapticproof.analysis.positivereal.positive_real` (HVE
paper, Definition 2 for ``G^{-1}``: poles in the closed disk, unit-circle poles simple,
``Res/z0 >= 0``, ``Re G^{-1} >= 0`` for all ``w``) with the same
:class:`~hapticproof.core.evidence.Outcome` and certificates, without building a SymPy expression
(DESIGN.md, *Numeric fast path*):

* the scene is a :class:`NumericScene` of exact fractions; ``H(z)``, the integrator ``X_h/V_h``
  (forward, backward, Tustin: HVE Section 3.1.1) and ``G^{-1} = (b - z_a) + z^{-n} H X_h/V_h``
  (eqs. 21-22) are flint polynomials from the first operation;
* poles and residues go through the decision kernel (:func:`hapticproof.exact.kernel.locate_roots`,
  :func:`~hapticproof.exact.kernel.residue_outcome`), shared with
  :func:`hapticproof.exact.conditions.pole_conditions`;
* the Hermitian part is decided by exact Descartes bisection of ``N(c) D(c)`` for short delays,
  and in closed form in ``theta`` (:mod:`hapticproof.exact.trigpoly`) for long ones -- the cost no
  longer grows with the delay's monomial expansion. Up to :data:`MONOMIAL_LIMIT` the certificate
  is the kernel's sign certificate of ``N(c) D(c)`` (re-checked by Sturm sequences); above it a
  Chebyshev-basis certificate (:class:`ChebyshevCertificate`) that the checker re-verifies up to
  its degree limit and declines, saying so, above.

>>> scene = NumericScene.virtual_wall(K=2, B="0.001", b="0.02", T="0.001", delay=10)
>>> out = decide(scene)
>>> out.decision.value, out.evidence.facts["conditions"][-1].outcome.reason
('proved', 'Re G^-1(c) >= 0 for all c in [-1, 1] (touches 0 at 1 point)')
>>> decide(scene.with_b("0.0199")).decision.value
'disproved'
"""

from __future__ import annotations

from dataclasses import dataclass, replace
from fractions import Fraction
from typing import Any

import flint

from hapticproof.exact import trigpoly
from hapticproof.exact.canonical import flint_fraction
from hapticproof.core.errors import SceneError
from hapticproof.core.evidence import Decision, Evidence, Method, Outcome
from hapticproof.exact.kernel import SignCertificate, sign_outcome, q_str
from hapticproof.exact.conditions import HERMITIAN, Condition, combine, pole_conditions
from hapticproof.exact.realroots import minimise_rational, real_roots, to_rational

__all__ = [
    "NumericScene",
    "integrator_polynomials",
    "path_polynomials",
    "transfer",
    "path_transfer",
    "circle_form",
    "hermitian_outcome",
    "conditions",
    "decide",
    "critical_damping",
    "ChebyshevCertificate",
    "SMALL_DEGREE",
    "MONOMIAL_LIMIT",
]

#: Up to this degree of ``N(c) D(c)`` the Hermitian part is decided by exact Descartes
#: bisection of the monomial form (fastest for short delays).
SMALL_DEGREE = 24
#: Up to this degree in ``c`` the certificate is the kernel's monomial sign certificate;
#: above it a Chebyshev-basis certificate (the monomial form costs ``O(n^3)`` bits).
MONOMIAL_LIMIT = 200
#: When the closed form cannot decide (a zero of even multiplicity inside the interval, an
#: end expansion that vanishes to high order), the kernel decides the monomial form up to this
#: degree; above it the condition is ``undecided``, with the reason.
KERNEL_LIMIT = 1000

APPROXIMATIONS = ("forward", "backward", "tustin")


def _fraction(value: Any, name: str) -> Fraction:
    """An exact fraction: ints, Fractions, floats (binary value), decimal strings, SymPy or
    flint rationals."""
    if isinstance(value, bool):
        raise SceneError(f"{name} must be a number, got {value!r}")
    if isinstance(value, Fraction):
        return value
    if isinstance(value, int):
        return Fraction(value)
    if isinstance(value, float):
        if value != value or value in (float("inf"), float("-inf")):
            raise SceneError(f"{name} must be finite, got {value!r}")
        return Fraction(value)
    if isinstance(value, str):
        try:
            return Fraction(value.strip())
        except (ValueError, ZeroDivisionError):
            raise SceneError(f"{name}: {value!r} is not a number") from None
    if isinstance(value, flint.fmpq):
        return Fraction(int(value.p), int(value.q))
    if getattr(value, "is_Rational", False):
        return Fraction(int(value.p), int(value.q))
    if hasattr(value, "__index__"):
        return Fraction(int(value))
    raise SceneError(f"{name} must be an exact number, got {value!r}")


def _fq(value: Fraction) -> flint.fmpq:
    return flint.fmpq(value.numerator, value.denominator)


def _coefficients(values: Any, name: str) -> tuple[Fraction, ...]:
    out = tuple(_fraction(v, name) for v in values)
    while len(out) > 1 and out[-1] == 0:
        out = out[:-1]
    if not out:
        raise SceneError(f"{name}: no coefficients")
    return out


@dataclass(frozen=True, slots=True)
class NumericScene:
    """A 1-DOF haptic device on a discrete environment with every parameter a number (HVE
    paper, Fig. 4): what :class:`hapticproof.systems.singleuser.SingleUserScene` describes, held as exact
    fractions so that it is hashable, picklable (worker processes, Dask) and needs no SymPy.

    Parameters
    ----------
    b, T, z_a : number
        Device damping, sampling period (> 0), operator's shortage of passivity.
    H : (num, den)
        ``H(z)`` as coefficient tuples in ``z``, lowest degree first.
    approximation : {'forward', 'backward', 'tustin'}
    delay : int
        ``n = t_d/T``.

    Examples
    --------
    >>> NumericScene.virtual_wall(K=2, B=0, b=1, T="1/1000").H
    ((Fraction(0, 1), Fraction(1, 500)), (Fraction(0, 1), Fraction(1, 1000)))
    """

    b: Fraction
    T: Fraction
    H: tuple[tuple[Fraction, ...], tuple[Fraction, ...]]
    approximation: str = "forward"
    delay: int = 0
    z_a: Fraction = Fraction(0)

    def __post_init__(self) -> None:
        object.__setattr__(self, "b", _fraction(self.b, "b"))
        object.__setattr__(self, "T", _fraction(self.T, "T"))
        object.__setattr__(self, "z_a", _fraction(self.z_a, "z_a"))
        num, den = self.H
        object.__setattr__(self, "H", (_coefficients(num, "H numerator"), _coefficients(den, "H denominator")))
        if all(v == 0 for v in self.H[1]):
            raise SceneError("H(z) has a zero denominator")
        if self.approximation not in APPROXIMATIONS:
            raise SceneError(f"unknown approximation {self.approximation!r}; choose one of {', '.join(APPROXIMATIONS)}")
        if isinstance(self.delay, bool) or int(self.delay) != self.delay or self.delay < 0:
            raise SceneError(f"the delay n = t_d/T must be a non-negative integer, got {self.delay}")
        object.__setattr__(self, "delay", int(self.delay))
        if self.T <= 0:
            raise SceneError(f"the sampling period T must be positive, got {self.T}")
        # a negative damping (or shortage of passivity) is decided by the definition, not refused

    @classmethod
    def virtual_wall(cls, *, K: Any, B: Any, b: Any, T: Any, approximation: str = "forward", delay: int = 0,
                     z_a: Any = 0) -> NumericScene:
        """The virtual wall ``H(z) = K + B(z-1)/(Tz) = ((KT + B) z - B)/(T z)``."""
        K, B, T = _fraction(K, "K"), _fraction(B, "B"), _fraction(T, "T")
        if T <= 0:
            raise SceneError(f"the sampling period T must be positive, got {T}")
        return cls(b=b, T=T, H=((-B, K * T + B), (Fraction(0), T)), approximation=approximation, delay=delay, z_a=z_a)

    @classmethod
    def from_scene(cls, scene: Any) -> NumericScene:
        """From a numeric :class:`~hapticproof.systems.singleuser.SingleUserScene` (reads ``H`` once with SymPy).

        >>> from hapticproof.systems.singleuser import SingleUserScene
        >>> NumericScene.from_scene(SingleUserScene.virtual_wall(K=2, B=0, b=1, T=1)).H
        ((Fraction(2, 1),), (Fraction(1, 1),))
        """
        import sympy as sp

        from hapticproof.core.symbols import z as Z_SYM

        if not scene.is_numeric:
            raise SceneError("the fast path needs a scene whose parameters are all numbers")
        pair = flint_fraction(scene.H, Z_SYM)            # the tree read directly: no SymPy algebra
        if pair is not None:
            coeffs = [[Fraction(int(a.p), int(a.q)) for a in p.coeffs()] or [Fraction(0)] for p in pair]
        else:
            num, den = sp.fraction(sp.cancel(sp.together(sp.sympify(scene.H))))
            pn, pd = sp.Poly(num, Z_SYM), sp.Poly(den, Z_SYM)
            coeffs = [[_fraction(sp.Rational(a), "H") for a in p.all_coeffs()[::-1]] for p in (pn, pd)]
        return cls(b=scene.b, T=scene.T, H=(tuple(coeffs[0]), tuple(coeffs[1])), approximation=scene.approximation,
                   delay=int(scene.delay), z_a=scene.z_a)

    def to_scene(self) -> Any:
        """The equivalent :class:`~hapticproof.systems.singleuser.SingleUserScene` (for the exact SymPy path)."""
        import sympy as sp

        from hapticproof.systems.singleuser import SingleUserScene
        from hapticproof.core.symbols import z as Z_SYM

        def expr(coeffs):
            return sum((sp.Rational(c.numerator, c.denominator) * Z_SYM**k for k, c in enumerate(coeffs)), sp.Integer(0))

        H = sp.cancel(expr(self.H[0]) / expr(self.H[1]))
        return SingleUserScene(b=_rational(self.b), T=_rational(self.T), H=H, approximation=self.approximation,
                               delay=self.delay, z_a=_rational(self.z_a))

    def with_b(self, b: Any) -> NumericScene:
        """The same scene with another device damping ``b``."""
        return replace(self, b=_fraction(b, "b"))


def _rational(value: Fraction) -> Any:
    import sympy as sp

    return sp.Rational(value.numerator, value.denominator)


# ---------------------------------------------------------------------------------------------
# polynomials
# ---------------------------------------------------------------------------------------------


def integrator_polynomials(approximation: str, T: Any) -> tuple[flint.fmpq_poly, flint.fmpq_poly]:
    """``X_h/V_h`` of the approximation as ``(num, den)`` in ``z`` (HVE Section 3.1.1; the same
    transfer functions :func:`hapticproof.systems.models.integrator` derives from the recurrences).

    >>> integrator_polynomials("tustin", 1)
    (1/2*x + 1/2, x + (-1))
    """
    T = _fq(_fraction(T, "T"))
    den = flint.fmpq_poly([-1, 1])
    if approximation == "forward":
        return flint.fmpq_poly([T]), den
    if approximation == "backward":
        return flint.fmpq_poly([0, T]), den
    if approximation == "tustin":
        return flint.fmpq_poly([T / 2, T / 2]), den
    raise SceneError(f"unknown approximation {approximation!r}; choose one of {', '.join(APPROXIMATIONS)}")


def path_polynomials(scene: NumericScene) -> tuple[flint.fmpq_poly, flint.fmpq_poly]:
    """``H(z) X_h/V_h = pe/qe`` (coprime, ``qe`` monic): the environment path before the delay.

    >>> path_polynomials(NumericScene.virtual_wall(K=2, B=0, b=1, T=1))      # 2/(z - 1)
    (2, x + (-1))
    """
    hn = flint.fmpq_poly([_fq(c) for c in scene.H[0]])
    hd = flint.fmpq_poly([_fq(c) for c in scene.H[1]])
    inum, iden = integrator_polynomials(scene.approximation, scene.T)
    pe, qe = hn * inum, hd * iden
    if pe.is_zero():
        return pe, flint.fmpq_poly([1])
    g = pe.gcd(qe)
    if g.degree() > 0:
        pe, qe = pe / g, qe / g
    lead = qe.coeffs()[-1]
    return pe / lead, qe / lead


def transfer(scene: NumericScene) -> tuple[flint.fmpq_poly, flint.fmpq_poly]:
    """``G^{-1} = P/Q`` coprime with ``Q`` monic: the same polynomials as
    :func:`hapticproof.analysis.positivereal.transfer_polynomials`, built without SymPy.

    ``P = a Q + pe`` with ``Q = z^n qe``, so ``gcd(P, Q) = gcd(pe, z^n) = z^k`` (``pe``, ``qe``
    coprime): the common factor is read off the valuation of ``pe``.

    >>> transfer(NumericScene.virtual_wall(K=2, B=0, b=1, T=1))               # 1 + 2/(z - 1)
    (x + 1, x + (-1))
    """
    pe, qe = path_polynomials(scene)
    a = _fq(scene.b - scene.z_a)
    n = scene.delay
    if pe.is_zero():
        return flint.fmpq_poly([a]), flint.fmpq_poly([1])
    coeffs = pe.coeffs()
    k = min(n, next(i for i, c in enumerate(coeffs) if c != 0))
    Q = flint.fmpq_poly([0] * (n - k) + qe.coeffs())
    shifted_pe = flint.fmpq_poly(coeffs[k:])
    P = a * Q + shifted_pe
    return P, Q


def path_transfer(scene: NumericScene) -> tuple[flint.fmpq_poly, flint.fmpq_poly]:
    """``z^{-n} H X_h/V_h`` alone (``b = z_a``) as coprime ``P/Q``, ``Q`` monic.

    >>> path_transfer(NumericScene.virtual_wall(K=2, B=0, b=1, T=1, delay=1))   # 2/(z(z - 1))
    (2, x^2 + (-1)*x)
    """
    pe, qe = path_polynomials(scene)
    if pe.is_zero():
        return pe, flint.fmpq_poly([1])
    n = scene.delay
    coeffs = pe.coeffs()
    k = min(n, next(i for i, c in enumerate(coeffs) if c != 0))
    return flint.fmpq_poly(coeffs[k:]), flint.fmpq_poly([0] * (n - k) + qe.coeffs())


def circle_form(scene: NumericScene, a: Any = None) -> trigpoly.CircleForm:
    """``Re G^{-1}(e^{j theta})`` in closed form (:class:`hapticproof.exact.trigpoly.CircleForm`);
    ``a`` replaces ``b - z_a`` (``a = 0``: the path alone, for boundaries).

    >>> form = circle_form(NumericScene.virtual_wall(K=2, B=0, b=1, T="0.001", delay=3))
    >>> form.b                     # Chebyshev coefficients: b - KT/2 - KT (T_1 + T_2 + T_3)
    [999/1000, -1/500, -1/500, -1/500]
    """
    pe, qe = path_polynomials(scene)
    a = _fq(scene.b - scene.z_a) if a is None else flint.fmpq(a) if not isinstance(a, flint.fmpq) else a
    return trigpoly.CircleForm(a, scene.delay, pe, qe)


# ---------------------------------------------------------------------------------------------
# the Hermitian condition
# ---------------------------------------------------------------------------------------------


@dataclass(frozen=True, eq=False)
class ChebyshevCertificate:
    """Evidence that ``Re G^{-1}(c) = g(c)/w(c) >= 0`` on ``[-1, 1]`` (or a point where it is
    not), with ``g``, ``w`` in the Chebyshev basis (``g = sum b_k T_k``): the long-delay form of
    :class:`hapticproof.exact.kernel.SignCertificate`.

    ``points``/``roots``: as in a sign certificate of ``g w`` (the ends, the interior sample
    and exact zeros at the ends); ``cover``: how the prover covered ``theta in [0, pi]`` (piece
    counts by method: ``end-taylor`` exact expansions at ``c = +-1``, ``envelope``
    ``a - |F| > 0``, ``taylor`` ball-arithmetic bounds). The checker converts ``g w`` to the
    monomial basis and re-verifies it with Sturm sequences up to its degree limit.
    """

    numerator: list
    denominator: list
    holds: bool
    points: tuple = ()
    roots: tuple = ()
    witness: Any = None
    witness_point: Any = None
    cover: dict | None = None
    transfer: tuple | None = None
    label: str = "Re G^-1"

    def to_json(self) -> dict[str, Any]:
        out: dict[str, Any] = {
            "certificate": "chebyshev-sign",
            "claim": f"{self.label}(c) >= 0",
            "variable": "c",
            "interval": ["-1", "1"],
            "basis": "chebyshev",
            "degree": len(self.numerator) + len(self.denominator) - 2,
            "numerator": [q_str(v) for v in self.numerator],
            "denominator": [q_str(v) for v in self.denominator],
            "holds": self.holds,
        }
        if self.holds:
            out["points"] = [q_str(p) for p in self.points]
            out["roots"] = [[q_str(a), q_str(b)] for a, b in self.roots]
        else:
            out["witness"] = q_str(self.witness)
            out["witness_point"] = [q_str(v) for v in self.witness_point]
        if self.cover is not None:
            out["cover"] = self.cover
        if self.transfer is not None:
            P, Q = self.transfer
            out["transfer"] = {"variable": "z", "num": [str(c) for c in P.coeffs()], "den": [str(c) for c in Q.coeffs()]}
        return out


def _transfer_json(P: flint.fmpq_poly, Q: flint.fmpq_poly) -> dict[str, Any]:
    return {"variable": "z", "num": [str(c) for c in P.coeffs()], "den": [str(c) for c in Q.coeffs()]}


def _descartes_01(q: flint.fmpz_poly, degree: int) -> int:
    """Sign variations of ``(1 + x)^d q(1/(1 + x))``: an upper bound (exact when 0 or 1) on the
    roots of ``q`` in ``(0, 1)``."""
    coeffs = q.coeffs()
    coeffs += [0] * (degree + 1 - len(coeffs))
    image = flint.fmpz_poly(coeffs[::-1])(flint.fmpz_poly([1, 1])).coeffs()
    count, previous = 0, 0
    for a in image:
        if a:
            s = 1 if a > 0 else -1
            if previous and s != previous:
                count += 1
            previous = s
    return count


def _small_sign(p: flint.fmpq_poly, max_depth: int = 96) -> tuple[str, Any] | None:
    """Exact sign of ``p`` on ``[-1, 1]`` by Descartes bisection: ``('proved', zero_ends)``,
    ``('negative', x)`` with ``p(x) < 0``, or ``None`` (a multiple root inside, or a root at a
    bisection point: the kernel decides)."""
    lo, hi = flint.fmpq(-1), flint.fmpq(1)
    ends = {lo: p(lo), hi: p(hi)}
    for x in (lo, hi):
        if ends[x] < 0:
            return "negative", x
    if p.degree() <= 0:
        return "proved", tuple(x for x in (lo, hi) if ends[x] == 0)
    q = p(flint.fmpq_poly([-1, 2])).numer()            # q(x) ~ p(2x - 1) on (0, 1)
    coeffs = q.coeffs()
    while coeffs and coeffs[0] == 0:
        coeffs = coeffs[1:]
    q = flint.fmpz_poly(coeffs)
    while q.degree() > 0 and sum(q.coeffs()) == 0:
        q = q // flint.fmpz_poly([-1, 1])
    if p((lo + hi) / 2) < 0:
        return "negative", (lo + hi) / 2
    stack = [(q, 0, 0)]
    degree = q.degree()
    while stack:
        poly, k, c = stack.pop()
        if poly.degree() <= 0:
            continue
        variations = _descartes_01(poly, degree)
        if variations == 0:
            continue
        a = flint.fmpq(c, 2**k) * 2 - 1
        b = flint.fmpq(c + 1, 2**k) * 2 - 1
        if variations == 1:
            for x in (a, b):
                if p(x) < 0:
                    return "negative", x
        if k >= max_depth:
            return None
        left = flint.fmpz_poly([coeff * 2 ** (degree - i) for i, coeff in enumerate(poly.coeffs())])
        right = left(flint.fmpz_poly([1, 1]))
        if right.coeffs() and right.coeffs()[0] == 0:     # a root at the bisection point
            return None
        stack.append((right, k + 1, 2 * c + 1))
        stack.append((left, k + 1, 2 * c))
    return "proved", tuple(x for x in (lo, hi) if ends[x] == 0)


def _negative_circle_point(x: flint.fmpq, negative, is_pole, p: flint.fmpq_poly | None = None) -> dict[str, Any] | None:
    """A rational point of the circle near ``c = x`` where ``negative(c)`` holds (exactly):
    ``z0 = ((1 - t^2) + 2jt)/(1 + t^2)`` for simple rationals ``t`` approaching
    ``tan(theta/2) = sqrt((1 - x)/(1 + x))``."""
    import math

    xf = Fraction(int(x.p), int(x.q))
    if xf in (-1, 1):
        witness = {"c": xf, "z": [xf, Fraction(0)], "omega_T": "0" if xf == 1 else "pi"}
        if not is_pole(witness):
            return witness
    value = p(x) if p is not None else None
    slope = p.derivative()(x) if p is not None else None

    def candidates():
        if xf in (-1, 1):
            # c = (1 - t^2)/(1 + t^2): 1 - c ~ 2 t^2 (t -> 0), 1 + c ~ 2/t^2 (t -> oo); start where
            # the linear estimate |p(x)/p'(x)| of the negative stretch puts it, then go closer
            start = 1
            if slope is not None and slope != 0:
                width = abs(float(value / slope))
                if width > 0:
                    start = max(1, int(-math.log2(math.sqrt(width / 2))) if width < 2 else 1)
            for k in range(start, 400):
                yield Fraction(1, 2**k) if xf == 1 else Fraction(2**k)
            return
        t0 = math.sqrt((1 - float(xf)) / (1 + float(xf)))
        for bits in (4, 8, 12, 16, 24, 32, 48, 62):
            yield Fraction(t0).limit_denominator(2**bits)
        exact = Fraction(t0)
        for k in range(20, 400, 4):
            yield exact + Fraction(1, 2**k)
            yield exact - Fraction(1, 2**k)

    seen = set()
    for t in candidates():
        if t < 0 or t in seen:
            continue
        seen.add(t)
        witness = trigpoly.circle_rational(t)
        if is_pole(witness):
            continue
        if negative(flint.fmpq(witness["c"].numerator, witness["c"].denominator)):
            return witness
    return None


def _pole_test(Q: flint.fmpq_poly):
    def is_pole(witness: dict[str, Any]) -> bool:
        return trigpoly.is_root_at_witness(Q, witness)

    return is_pole


def _monomial_outcome(N: flint.fmpq_poly, D: flint.fmpq_poly, P: flint.fmpq_poly, Q: flint.fmpq_poly,
                      verdict: tuple[str, Any] | None, label: str = "Re G^-1") -> Outcome:
    """The kernel's sign outcome of ``N D`` on ``[-1, 1]`` from a decision already made
    (``verdict``): the same certificate :func:`hapticproof.exact.kernel.decide_rational_sign` gives."""
    from hapticproof.exact.kernel import decide_rational_sign

    p = N * D
    lo, hi = flint.fmpq(-1), flint.fmpq(1)
    transfer_data = _transfer_json(P, Q)
    kwargs = dict(label=label, numerator=N, denominator=D, transfer=transfer_data)
    if verdict is not None and verdict[0] == "proved":
        zeros = verdict[1]
        roots = tuple((x, x) for x in zeros)
        cert = SignCertificate(p, lo, hi, "c", True, (lo, (lo + hi) / 2, hi), roots, **kwargs)
        return sign_outcome(cert, None, f"{label}(c)")
    if verdict is not None and verdict[0] == "negative":
        witness = _negative_circle_point(verdict[1], lambda c: p(c) < 0, _pole_test(Q), p)
        if witness is not None:
            value = flint.fmpq(witness["c"].numerator, witness["c"].denominator)
            cert = SignCertificate(p, lo, hi, "c", False, witness=value, witness_point=witness["z"], **kwargs)
            return sign_outcome(cert, witness, f"{label}(c)")
    # hard cases (a zero of even multiplicity inside, a root at a bisection point): the kernel
    return decide_rational_sign(N, D, -1, 1, "c", label, transfer=transfer_data, transfer_den=Q)


def _minimum(N: flint.fmpq_poly, D: flint.fmpq_poly) -> tuple[Any, Any]:
    if D.degree() > 0 and real_roots(D, -1, 1):
        return None, None
    m = minimise_rational(N, D, -1, 1)
    return m.argmin, (m.exact if m.exact is not None else m.value)


def hermitian_outcome(scene: NumericScene, *, minimum: bool = True, polynomials: tuple | None = None) -> Outcome:
    """The condition ``Re G^{-1}(e^{jwT}) >= 0 for all w`` with its certificate.

    ``minimum``: also report the worst case (``minimiser``, ``minimum``) as
    :func:`hapticproof.analysis.positivereal.decide_hermitian` does (exact or a certified ball);
    ``polynomials``: ``transfer(scene)`` when already computed.

    >>> out = hermitian_outcome(NumericScene.virtual_wall(K=2, B=0, b="0.0009", T="0.001"))
    >>> out.decision.value, out.witness["c"]
    ('disproved', -1)
    """
    P, Q = transfer(scene) if polynomials is None else polynomials
    if max(P.degree(), Q.degree()) <= MONOMIAL_LIMIT:
        from hapticproof.exact.unitcircle import circle_real_part

        N, D = circle_real_part(P, Q)
        form = None
        if N.degree() + max(D.degree(), 0) <= SMALL_DEGREE:
            verdict = _small_sign(N * D)
        else:
            form = circle_form(scene)
            verdict = _trig_verdict(form) if form.regular else _small_sign(N * D)
        outcome = _monomial_outcome(N, D, P, Q, verdict)
        if minimum:
            minimiser, value = _minimum(N, D) if form is None or not form.regular else _trig_minimum(form)
            outcome = Outcome(outcome.decision, outcome.evidence, outcome.reason, minimiser=minimiser, minimum=value)
        return outcome
    form = circle_form(scene)
    if not form.regular:          # unit-circle poles of Re G^-1 that do not cancel: the kernel
        return _kernel_outcome(P, Q, form.degree + len(form.w) - 1, "poles of Re G^-1 on the circle")
    return _chebyshev_outcome(form, P, Q, minimum)


def _kernel_outcome(P: flint.fmpq_poly, Q: flint.fmpq_poly, degree: int, why: str) -> Outcome:
    """The kernel on the monomial form, up to :data:`KERNEL_LIMIT`; above it, undecided (saying why)."""
    if degree > KERNEL_LIMIT:
        return Outcome(Decision.UNDECIDED, Evidence(Method.ROOT_ISOLATION, facts={"degree": degree}),
                       f"Re G^-1(c): not decided in closed form ({why}); the monomial form has degree {degree}, "
                       f"above the exact fallback's limit {KERNEL_LIMIT}")
    from hapticproof.exact.unitcircle import circle_real_part

    N, D = circle_real_part(P, Q)
    return _monomial_outcome(N, D, P, Q, None)


def _trig_verdict(form: trigpoly.CircleForm) -> tuple[str, Any] | None:
    d = trigpoly.decide(form)
    if d.holds is None:
        return None
    if d.holds:
        return "proved", tuple(flint.fmpq(e) for e in sorted(d.touching))
    c = d.witness["c"]
    return "negative", flint.fmpq(c.numerator, c.denominator)


def _trig_minimum(form: trigpoly.CircleForm) -> tuple[Any, Any]:
    """Worst case from the closed form: the minimiser (``c``, exact at an end, else a ball) and a
    certified enclosure of the minimum."""
    scale = max(abs(form.end_value(1)), abs(form.end_value(-1)), flint.fmpq(1, 2**60))
    m = trigpoly.minimum(form, tol=scale / 2**40)
    if m.holds is None:
        return None, None
    with trigpoly.flint_precision(128):
        value = flint.arb(m.lower).union(flint.arb(m.upper))
        if m.lower == m.upper:
            value = to_rational(m.lower)
        theta = m.argmin
        if theta == 0:
            where = to_rational(flint.fmpq(1))
        elif theta >= trigpoly.PI_HI:
            where = to_rational(flint.fmpq(-1))
        else:
            where = flint.arb(theta).cos()
    return where, value


def _chebyshev_outcome(form: trigpoly.CircleForm, P, Q, minimum: bool) -> Outcome:
    d = trigpoly.decide(form)
    degree = form.degree + len(form.w) - 1
    what = "Re G^-1(c)"
    kwargs = dict(transfer=(P, Q), cover=_cover_summary(d))
    if d.holds is None:
        return _kernel_outcome(P, Q, degree, d.reason)
    minimiser = value = None
    if minimum:
        minimiser, value = _trig_minimum(form)
    if d.holds:
        zeros = tuple(flint.fmpq(e) for e in sorted(d.touching))
        lo, hi = flint.fmpq(-1), flint.fmpq(1)
        cert = ChebyshevCertificate(form.b, form.w, True, (lo, flint.fmpq(0), hi), tuple((x, x) for x in zeros), **kwargs)
        reason = f"{what} >= 0 for all c in [-1, 1]"
        if zeros:
            reason += f" (touches 0 at {len(zeros)} point{'s' if len(zeros) > 1 else ''})"
        return Outcome(Decision.PROVED, Evidence(Method.ROOT_ISOLATION, facts={"certificate": cert}), reason,
                       minimiser=minimiser, minimum=value)
    w = d.witness
    c = flint.fmpq(w["c"].numerator, w["c"].denominator)
    cert = ChebyshevCertificate(form.b, form.w, False, witness=c, witness_point=w["z"], **kwargs)
    shown = {"c": to_rational(c), "z": [str(v) for v in w["z"]], "omega_T": w["omega_T"]}
    text = d.witness_value.str(10) if hasattr(d.witness_value, "str") else str(d.witness_value)
    return Outcome(Decision.DISPROVED, Evidence(Method.ROOT_ISOLATION, witness=shown, facts={"certificate": cert, "value": text}),
                   f"{what} = {text} < 0 at c = {q_str(c)}", minimiser=minimiser, minimum=value)


def _cover_summary(d: trigpoly.TrigDecision) -> dict[str, Any]:
    counts: dict[str, int] = {}
    for _, _, method in d.cover:
        counts[method] = counts.get(method, 0) + 1
    return {"pieces": len(d.cover), "methods": counts}


# ---------------------------------------------------------------------------------------------
# whole decisions
# ---------------------------------------------------------------------------------------------


def conditions(scene: NumericScene, *, minimum: bool = True) -> list[Condition]:
    """The four conditions of Definition 2 (HVE paper) for ``G^{-1}``, as
    :func:`hapticproof.analysis.positivereal.conditions` gives them for a numeric scene.

    >>> [c.decision.value for c in conditions(NumericScene.virtual_wall(K=2, B=0, b="0.0009", T="0.001"))]
    ['proved', 'proved', 'proved', 'disproved']
    """
    P, Q = transfer(scene)
    return pole_conditions(P, Q) + [Condition(HERMITIAN, hermitian_outcome(scene, minimum=minimum, polynomials=(P, Q)))]


def decide(scene: NumericScene, *, minimum: bool = True) -> Outcome:
    """Is ``G^{-1}`` positive real? The whole decision with certificates
    (:func:`hapticproof.analysis.positivereal.positive_real` for a numeric scene, without SymPy).

    >>> decide(NumericScene.virtual_wall(K=2, B=0, b="0.0011", T="0.001")).decision.value
    'proved'
    """
    return combine(conditions(scene, minimum=minimum))


def critical_damping(scene: NumericScene, tol: Any = None) -> tuple[Fraction, Fraction]:
    """Certified ``[lo, hi]`` around ``beta = -min_w Re(z^{-n} H X_h/V_h)``: the Hermitian
    condition holds iff ``b - z_a >= beta`` (``b`` enters additively). ``lo == hi`` when the
    worst case is exact (at ``c = +-1``). One computation decides a whole row of ``b`` values.

    >>> critical_damping(NumericScene.virtual_wall(K=2, B="0.001", b=1, T="0.001", delay=10))
    (Fraction(1, 50), Fraction(1, 50))
    """
    P, Q = path_transfer(scene)
    if max(P.degree(), Q.degree()) <= SMALL_DEGREE:      # short delays: the monomial minimum
        from hapticproof.exact.unitcircle import circle_real_part

        N, D = circle_real_part(P, Q)
        if D.degree() <= 0 or not real_roots(D, -1, 1):
            m = minimise_rational(N, D, -1, 1)
            if m.exact is not None:
                value = -Fraction(int(m.exact.p), int(m.exact.q))
                return value, value
            lo, hi = trigpoly.arb_fmpq((-m.value).lower()), trigpoly.arb_fmpq((-m.value).upper())
            return Fraction(int(lo.p), int(lo.q)), Fraction(int(hi.p), int(hi.q))
    form = circle_form(scene, a=0)
    if tol is None:
        ends = max(abs(form.end_value(1)), abs(form.end_value(-1)), flint.fmpq(1, 2**60))
        tol = ends / 2**48
    m = trigpoly.minimum(form, tol=_fq(_fraction(tol, "tol")) if not isinstance(tol, flint.fmpq) else tol)
    if m.holds is None:
        raise ArithmeticError(f"critical damping not found: {m.reason}")
    lo, hi = -m.upper, -m.lower
    return Fraction(int(lo.p), int(lo.q)), Fraction(int(hi.p), int(hi.q))
