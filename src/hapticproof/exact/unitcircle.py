r"""Exact maps from the unit circle to ``c = cos(wT)`` and from the imaginary axis to ``x = w**2``.

For a real-rational ``F(z) = P(z)/Q(z)`` on ``|z| = 1`` (DESIGN.md, *Core mathematical ideas*):

* ``Re F = (F(z) + F(1/z))/2``. With ``L(z) = P(z) Q(1/z) = sum_k l_k z^k`` (a Laurent
  polynomial), ``F(z) + F(1/z) = sum_k (l_k + l_{-k}) z^k / |Q|^2`` is palindromic, and
  ``z^k + z^-k = 2 T_k(c)`` (Chebyshev). So ``Re F = N(c) / D(c)`` exactly.
* ``Im F = (F(z) - F(1/z))/(2j)`` is anti-palindromic; ``z^k - z^-k = 2j sin(theta) U_{k-1}(c)``,
  so ``Im F = sin(theta) * V(c) / D(c)``.
* A symbolic delay ``z^-n`` stays exact in *theta-form*:
  ``Re(z^-n F) = Re F * cos(n theta) + Im F * sin(n theta)``.

Continuous time: ``Re Z(jw)`` of a real-rational ``Z(s)`` is a rational function of ``x = w**2``.

>>> import sympy as sp
>>> from hapticproof.core.symbols import z, c
>>> K, T, B, b = sp.symbols('K T B b', positive=True)
>>> sp.expand(hermitian_part(b + K*T/(z - 1) + B/z))       # forward difference, eq. (17)
B*c - K*T/2 + b
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from functools import lru_cache
from typing import Any

import flint
import sympy as sp

from hapticproof.exact.realroots import as_fmpq
from hapticproof.core.symbols import c as C_SYM
from hapticproof.core.symbols import cos_n as COS_N
from hapticproof.core.symbols import s as S_SYM
from hapticproof.core.symbols import sin_n as SIN_N
from hapticproof.core.symbols import sin_theta as SIN_T
from hapticproof.core.symbols import x as X_SYM
from hapticproof.core.symbols import z as Z_SYM

__all__ = [
    "CRational",
    "ThetaForm",
    "numerator_denominator",
    "hermitian_part",
    "hermitian_part_rational",
    "imaginary_part_rational",
    "circle_real_part",
    "delayed_hermitian_part",
    "theta_form",
    "theta_to_cos",
    "omega_to_c",
    "canonical_theta",
    "real_part_x",
    "imaginary_axis_rational",
    "evaluate_on_circle",
    "CircleForm",
    "circle_form",
    "theta_form_on_circle",
]


# ---------------------------------------------------------------------------------------------
# Laurent coefficient arithmetic, generic over a coefficient ring (SymPy domain or flint fmpq)
# ---------------------------------------------------------------------------------------------


def numerator_denominator(F: Any, z: sp.Symbol = Z_SYM) -> tuple[sp.Poly, sp.Poly]:
    """``F = P/Q`` with ``P, Q`` polynomials in ``z`` over one common coefficient domain.

    >>> from hapticproof.core.symbols import z
    >>> P, Q = numerator_denominator(3 + 1/(z - 1))
    >>> P.as_expr(), Q.as_expr()
    (3*z - 2, z - 1)
    """
    from hapticproof.exact.canonical import canonical_fraction

    num, den = canonical_fraction(sp.sympify(F))
    P = sp.Poly(sp.expand(num), z)
    Q = sp.Poly(sp.expand(den), z)
    P, Q = P.unify(Q)
    if Q.is_zero:
        raise ZeroDivisionError("denominator is zero")
    return P, Q


def _cross_coefficients(p: list, q: list, zero: Any) -> dict[int, Any]:
    """Laurent coefficients of ``P(z) Q(1/z)``: ``l_k = sum_{i - j = k} p_i q_j``.

    ``p``, ``q`` are coefficient lists lowest degree first.
    """
    out: dict[int, Any] = {}
    for i, pi in enumerate(p):
        if pi == zero:
            continue
        for jdx, qj in enumerate(q):
            if qj == zero:
                continue
            k = i - jdx
            out[k] = out.get(k, zero) + pi * qj
    return out


@lru_cache(maxsize=None)
def _chebyshev_t_flint(k: int) -> flint.fmpz_poly:
    return flint.fmpz_poly.chebyshev_t(k)


@lru_cache(maxsize=None)
def _chebyshev_u_flint(k: int) -> flint.fmpz_poly:
    return flint.fmpz_poly.chebyshev_u(k)


def _clenshaw(coeffs: list, one: Any, cvar: Any, kind: str) -> Any:
    """``sum_k coeffs[k] * T_k(c)`` (kind 'T') or ``sum_k coeffs[k] * U_k(c)`` (kind 'U')
    in a polynomial ring where ``cvar`` is the generator and ``one`` its unit.

    Clenshaw's recurrence keeps every step an exact polynomial operation: O(n) ring operations
    instead of building each Chebyshev polynomial separately.
    """
    b1 = b2 = one * 0
    for k in range(len(coeffs) - 1, 0, -1):
        b1, b2 = one * coeffs[k] + 2 * cvar * b1 - b2, b1
    if kind == "T":
        return one * coeffs[0] + cvar * b1 - b2 if coeffs else b1
    return one * coeffs[0] + 2 * cvar * b1 - b2 if coeffs else b1


# ---------------------------------------------------------------------------------------------
# Results
# ---------------------------------------------------------------------------------------------


@dataclass(frozen=True, slots=True)
class CRational:
    """A rational function ``num(c)/den(c)`` of ``c = cos(wT)`` (or of ``x = w**2``).

    ``num`` and ``den`` are both ``sympy.Poly`` in ``var`` (symbolic coefficients) or both
    ``flint.fmpq_poly`` (numeric coefficients; ``var`` names the variable for display).
    ``den`` is ``|Q(e^{jwT})|**2`` (up to a positive constant) possibly divided by factors shared
    with ``num``; its sign on the interval is that of the original squared modulus wherever the
    function is finite.
    """

    num: Any
    den: Any
    var: sp.Symbol = C_SYM

    @property
    def is_numeric(self) -> bool:
        return isinstance(self.num, flint.fmpq_poly)

    def expr(self) -> sp.Expr:
        """The function as a SymPy expression in ``var``."""
        if self.is_numeric:
            return _flint_to_expr(self.num, self.var) / _flint_to_expr(self.den, self.var)
        return self.num.as_expr() / self.den.as_expr()

    def numeric(self) -> CRational:
        """The flint form (requires rational coefficients)."""
        if self.is_numeric:
            return self
        return CRational(_poly_to_flint(self.num), _poly_to_flint(self.den), self.var)

    def subs(self, values: dict) -> CRational:
        """Substitute parameter values (exact) into a symbolic form."""
        if self.is_numeric:
            return self
        num = sp.Poly(self.num.as_expr().subs(values), self.var)
        den = sp.Poly(self.den.as_expr().subs(values), self.var)
        return _simplest(num, den, self.var)

    def __call__(self, value: Any) -> sp.Expr:
        """Exact value at a rational point."""
        if self.is_numeric:
            point = as_fmpq(value)
            result = self.num(point) / self.den(point)
            return sp.Rational(int(result.p), int(result.q))
        return sp.cancel(self.expr().subs(self.var, value))


def _flint_to_expr(p: flint.fmpq_poly, var: sp.Symbol) -> sp.Expr:
    # one Add of all terms: adding them one by one re-sorts the sum each time (quadratic)
    return sp.Add(*[sp.Rational(int(a.p), int(a.q)) * var**i for i, a in enumerate(p.coeffs()) if a != 0])


def _poly_to_flint(p: sp.Poly) -> flint.fmpq_poly:
    coeffs = p.all_coeffs()[::-1]
    try:
        return flint.fmpq_poly([as_fmpq(p.domain.to_sympy(a) if not isinstance(a, sp.Basic) else a) for a in coeffs])
    except TypeError as err:
        raise TypeError(f"non-rational coefficients in {p.as_expr()}") from err


def _simplest(num: sp.Poly, den: sp.Poly, var: sp.Symbol) -> CRational:
    """Cancel common factors and move to flint when the coefficients are rational."""
    num, den = num.unify(den)
    if num.is_zero:
        return CRational(sp.Poly(0, var, domain=num.domain), sp.Poly(1, var, domain=num.domain), var)
    if all(sym == var for sym in num.free_symbols | den.free_symbols):
        fn, fd = _poly_to_flint(num), _poly_to_flint(den)
        g = fn.gcd(fd)
        fn, fd = fn / g, fd / g
        # normalise the denominator's leading coefficient to be positive
        if fd.coeffs()[-1] < 0:
            fn, fd = -fn, -fd
        return CRational(fn, fd, var)
    # Poly.cancel returns (ratio, num, den) with a constant ratio in the ground domain
    ratio, num_c, den_c = num.cancel(den)
    if ratio != 1:
        num_c = num_c * ratio
    return CRational(num_c, den_c, var)


# ---------------------------------------------------------------------------------------------
# Unit circle
# ---------------------------------------------------------------------------------------------


def _laurent_parts(F: Any, z: sp.Symbol):
    """Coefficient lists of P, Q and the Laurent coefficients of P(z)Q(1/z) and Q(z)Q(1/z)."""
    P, Q = numerator_denominator(F, z)
    numeric = P.domain.is_QQ or P.domain.is_ZZ
    if numeric:
        p = [as_fmpq(P.domain.to_sympy(a)) for a in P.all_coeffs()[::-1]]
        q = [as_fmpq(Q.domain.to_sympy(a)) for a in Q.all_coeffs()[::-1]]
        zero = flint.fmpq(0)
        if len(p) * len(q) > 2000:
            return numeric, P.domain, fast_cross(p, q), fast_cross(q, q), zero
    else:
        p = P.all_coeffs()[::-1]
        q = Q.all_coeffs()[::-1]
        zero = sp.Integer(0)
    return numeric, P.domain, _cross_coefficients(p, q, zero), _cross_coefficients(q, q, zero), zero


def fast_cross(p: list, q: list) -> dict[int, flint.fmpq]:
    """``P(z) Q(1/z)`` by one flint product ``P(z) * z^deg(Q) Q(1/z)`` (long delays)."""
    prod = flint.fmpq_poly(p) * flint.fmpq_poly(q[::-1])
    shift = len(q) - 1
    return {k - shift: a for k, a in enumerate(prod.coeffs()) if a != 0}


def _to_c_ring(numeric: bool, domain, var: sp.Symbol):
    """Generator and unit of the polynomial ring in ``var``."""
    if numeric:
        return flint.fmpq_poly([0, 1]), flint.fmpq_poly([1])
    return sp.Poly(var, var, domain=domain), sp.Poly(1, var, domain=domain)


def symmetric_to_c(laurent: dict[int, Any], zero: Any, cvar, one, sign: int):
    """``sum_k (l_k + sign*l_{-k}) z^k`` on the circle, divided by 2 (sign=+1) or by 2j sin
    (sign=-1), as a polynomial in c: sign=+1 gives ``l_0 + sum_{k>=1} (l_k + l_-k) T_k(c)``;
    sign=-1 gives ``sum_{k>=1} (l_k - l_-k) U_{k-1}(c)``."""
    top = max((abs(k) for k in laurent), default=0)
    if sign > 0:
        coeffs = [laurent.get(0, zero)] + [
            laurent.get(k, zero) + laurent.get(-k, zero) for k in range(1, top + 1)
        ]
        return _clenshaw(coeffs, one, cvar, "T")
    coeffs = [laurent.get(k, zero) - laurent.get(-k, zero) for k in range(1, top + 1)]
    return _clenshaw(coeffs, one, cvar, "U")


def hermitian_part_rational(F: Any, z: sp.Symbol = Z_SYM, var: sp.Symbol = C_SYM) -> CRational:
    """``Re F(e^{jwT})`` as an exact rational function of ``c = cos(wT)``.

    Numeric coefficients give flint polynomials (fast for long delays); symbolic ones give
    ``sympy.Poly`` with parameter coefficients. Common factors are cancelled.

    >>> from hapticproof.core.symbols import z
    >>> r = hermitian_part_rational(z / (z - 1))        # backward-difference integrator
    >>> r.expr()
    1/2
    """
    numeric, domain, cross, qq, zero = _laurent_parts(F, z)
    cvar, one = _to_c_ring(numeric, domain, var)
    num = symmetric_to_c(cross, zero, cvar, one, +1)
    den = symmetric_to_c(qq, zero, cvar, one, +1)
    # Re F = (l_0 + sum (l_k + l_-k) T_k) / (qq_0 + 2 sum qq_k T_k) ... both halves use T_k with
    # the palindromic sums; the factor 1/2 of Re F cancels against z^k + z^-k = 2 T_k.
    if numeric:
        return _simplest_flint(num, den, var)
    return _simplest(num, den, var)


def _simplest_flint(num: flint.fmpq_poly, den: flint.fmpq_poly, var: sp.Symbol) -> CRational:
    if num.is_zero():
        return CRational(num, flint.fmpq_poly([1]), var)
    g = num.gcd(den)
    num, den = num / g, den / g
    if den.coeffs()[-1] < 0:
        num, den = -num, -den
    return CRational(num, den, var)


def circle_real_part(P: flint.fmpq_poly, Q: flint.fmpq_poly) -> tuple[flint.fmpq_poly, flint.fmpq_poly]:
    """``Re P/Q`` on the unit circle as ``N(c)/D(c)`` from flint polynomials in ``z`` (no SymPy):
    the numeric fast path of :func:`hermitian_part_rational`. ``D`` is ``|Q(e^{jwT})|^2`` up to
    a positive factor, divided by factors shared with ``N``.

    >>> z = flint.fmpq_poly([0, 1])
    >>> N, D = circle_real_part(z - 1, z + 1)             # (z-1)/(z+1) = j tan(wT/2): Re = 0
    >>> N.is_zero()
    True
    """
    p, q = P.coeffs(), Q.coeffs()
    cross = fast_cross(p, q) if p else {}
    qq = fast_cross(q, q)
    zero = flint.fmpq(0)
    cvar, one = flint.fmpq_poly([0, 1]), flint.fmpq_poly([1])
    form = _simplest_flint(symmetric_to_c(cross, zero, cvar, one, +1), symmetric_to_c(qq, zero, cvar, one, +1), C_SYM)
    return form.num, form.den


def imaginary_part_rational(F: Any, z: sp.Symbol = Z_SYM, var: sp.Symbol = C_SYM) -> CRational:
    """``Im F(e^{jwT}) / sin(wT)`` as an exact rational function of ``c``.

    >>> from hapticproof.core.symbols import z
    >>> imaginary_part_rational(1 / z).expr()            # Im e^{-jwT} = -sin(wT)
    -1
    """
    numeric, domain, cross, qq, zero = _laurent_parts(F, z)
    cvar, one = _to_c_ring(numeric, domain, var)
    num = symmetric_to_c(cross, zero, cvar, one, -1)
    den = symmetric_to_c(qq, zero, cvar, one, +1)
    if numeric:
        return _simplest_flint(num, den, var)
    return _simplest(num, den, var)


def hermitian_part(F: Any, z: sp.Symbol = Z_SYM, var: sp.Symbol = C_SYM) -> sp.Expr:
    """``Re F(e^{jwT})`` as a SymPy expression in ``c`` (see :func:`hermitian_part_rational`).

    >>> import sympy as sp
    >>> from hapticproof.core.symbols import z
    >>> K, T = sp.symbols('K T', positive=True)
    >>> hermitian_part(K*T*z/(z - 1))                    # residue KT at z = 1, Re = KT/2
    K*T/2
    """
    from hapticproof.exact.canonical import canonical_rational

    return canonical_rational(hermitian_part_rational(F, z, var).expr())


def delayed_hermitian_part(F: Any, delay: int, z: sp.Symbol = Z_SYM, var: sp.Symbol = C_SYM) -> CRational:
    """``Re(z^-delay F(z))`` on the unit circle for an integer delay, exactly in ``c``.

    >>> from hapticproof.core.symbols import z
    >>> delayed_hermitian_part(1 / (z - 1), 1).expr()    # -1/2 - cos(wT)
    -c - 1/2
    """
    if delay < 0 or int(delay) != delay:
        raise ValueError("delay must be a non-negative integer")
    return hermitian_part_rational(sp.sympify(F) * z ** (-int(delay)), z, var)


@dataclass(frozen=True, slots=True)
class ThetaForm:
    r"""``a(c) + u(c) cos(n theta) + v(c) sin(theta) sin(n theta)`` for a symbolic integer ``n``.

    ``a``, ``u``, ``v`` are SymPy expressions in ``c``; ``theta = wT``. This is the exact real
    part of ``a + z^-n F(z)`` with ``u = Re F`` and ``v = Im F / sin(theta)``.
    """

    a: sp.Expr
    u: sp.Expr
    v: sp.Expr
    n: sp.Symbol
    var: sp.Symbol = C_SYM

    def at(self, n_value: int) -> sp.Expr:
        """Exact rational function of ``c`` for a concrete delay ``n``."""
        k = int(n_value)
        cos_n = sp.chebyshevt(k, self.var)
        sin_theta_sin_n = (1 - self.var**2) * sp.chebyshevu(k - 1, self.var) if k >= 1 else 0
        return sp.cancel(self.a + self.u * cos_n + self.v * sin_theta_sin_n)

    def canonical(self) -> sp.Expr:
        """The form in the canonical variables ``c``, ``sin(theta)``, ``cos(n theta)``,
        ``sin(n theta)`` of :func:`canonical_theta`."""
        return sp.expand(self.a + self.u * COS_N + self.v * SIN_T * SIN_N)

    def expr(self, theta: sp.Symbol) -> sp.Expr:
        """As an expression in ``theta`` (for display and numeric evaluation)."""
        subs = {self.var: sp.cos(theta)}
        return (
            self.a.subs(subs)
            + self.u.subs(subs) * sp.cos(self.n * theta)
            + self.v.subs(subs) * sp.sin(theta) * sp.sin(self.n * theta)
        )


def theta_form(constant: Any, F: Any, n: sp.Symbol, z: sp.Symbol = Z_SYM, var: sp.Symbol = C_SYM) -> ThetaForm:
    """Exact real part of ``constant + z^-n F(z)`` on the unit circle for symbolic ``n``.

    >>> import sympy as sp
    >>> from hapticproof.core.symbols import z, n
    >>> K, T, B, b = sp.symbols('K T B b', positive=True)
    >>> tf = theta_form(b, K*T/(z - 1) + B/z, n)          # HVE eq. (22)
    >>> sp.expand(tf.u), sp.factor(tf.v)
    (B*c - K*T/2, -(2*B*c - 2*B - K*T)/(2*(c - 1)))
    """
    return ThetaForm(
        a=hermitian_part(constant, z, var),
        u=hermitian_part(F, z, var),
        v=sp.cancel(imaginary_part_rational(F, z, var).expr()),
        n=n,
        var=var,
    )


def theta_to_cos(expr: sp.Expr, theta: sp.Symbol, var: sp.Symbol = C_SYM) -> sp.Expr:
    """Rewrite an expression polynomial in ``cos(k theta)``, ``sin(k theta)`` (integer ``k``,
    even total degree in sines) as a rational function of ``c = cos(theta)``.

    >>> import sympy as sp
    >>> t = sp.Symbol('theta')
    >>> theta_to_cos(sp.cos(2*t) + sp.sin(t)**2, t)
    c**2
    """
    expanded = sp.expand_trig(sp.expand(expr))
    s_sym = sp.Dummy("s")
    replaced = expanded.subs({sp.sin(theta): s_sym, sp.cos(theta): var})
    replaced = sp.expand(replaced)
    try:
        poly = sp.Poly(replaced, s_sym)
    except sp.PolynomialError:
        poly = None         # sin(theta) in a denominator, half angles: the exponential route
    if poly is None or replaced.has(theta):
        try:
            form = circle_form(expr, theta).c_form(var)
        except ValueError:
            if poly is None:
                raise
            form = None            # theta outside the circle functions (a slip such as omega T / 2): as it reads
        if form is not None:
            return form
        if poly is None:
            raise ValueError("not a rational function of cos(theta) alone")
    out = sp.Integer(0)
    for (power,), coeff in poly.terms():
        if power % 2:
            raise ValueError("odd power of sin(theta): not a function of cos(theta) alone")
        out += coeff * (1 - var**2) ** (power // 2)
    return sp.cancel(out)


def omega_to_c(expr: Any, omega: sp.Symbol, T: sp.Symbol, var: sp.Symbol = C_SYM) -> sp.Expr:
    """A printed expression in ``cos(k omega T)``, ``sin(k omega T)`` as a function of ``c``.

    >>> import sympy as sp
    >>> w, T, B = sp.symbols('omega T B', positive=True)
    >>> omega_to_c(B*sp.cos(w*T) + sp.sin(w*T)**2, w, T)
    B*c - c**2 + 1
    """
    theta = sp.Dummy("theta")
    return theta_to_cos(sp.sympify(expr).subs(omega, theta / T), theta, var)


def canonical_theta(
    expr: Any, omega: sp.Symbol, T: sp.Symbol, t_d: sp.Symbol, n: sp.Symbol, var: sp.Symbol = C_SYM
) -> sp.Expr:
    """A printed expression with a symbolic delay ``t_d = nT`` in canonical variables.

    ``omega T -> theta`` and ``omega t_d -> n theta``; the result is a polynomial in
    ``sin(theta)`` (reduced with ``sin^2 = 1 - c^2``), ``cos(n theta)`` and ``sin(n theta)`` with
    coefficients rational in ``c`` — the form of :meth:`ThetaForm.canonical`, so two
    expressions agree for every integer ``n`` exactly when their canonical forms are equal
    (``cos(n theta)`` and ``sin(n theta)`` are then independent of ``c``). Angles that are not
    integer combinations of ``theta`` and ``n theta`` (OCR damage such as ``omega t_d - T``)
    are kept as they are, so they cannot cancel by accident.

    >>> import sympy as sp
    >>> w, T, t_d = sp.symbols('omega T t_d', positive=True)
    >>> n = sp.Symbol('n', integer=True)
    >>> canonical_theta(sp.cos(w*(t_d + T)), w, T, t_d, n)
    C_n*c - S_n*s_theta
    """
    theta = sp.Dummy("theta", real=True)
    e = sp.sympify(expr).subs(t_d, n * T).subs(omega, theta / T)
    fast = _canonical_theta_flint(e, theta, n, var)
    if fast is not None:
        return fast
    e = sp.expand(sp.expand_trig(sp.expand(e)))
    e = e.subs({sp.cos(n * theta): COS_N, sp.sin(n * theta): SIN_N}).subs(
        {sp.cos(theta): var, sp.sin(theta): SIN_T}
    )
    e = sp.together(sp.expand(e))
    num, den = sp.fraction(e)
    num = sp.expand(num)
    den = sp.expand(den)

    def reduce_sin(poly_expr: sp.Expr) -> sp.Expr:
        p = sp.Poly(poly_expr, SIN_T)
        out = sp.Integer(0)
        for (power,), coeff in p.terms():
            out += coeff * (1 - var**2) ** (power // 2) * SIN_T ** (power % 2)
        return sp.expand(out)

    return sp.expand(sp.cancel(reduce_sin(num) / reduce_sin(den)))


def _chebyshev(kind: str, k: int, x: Any, one: Any) -> Any:
    """``T_k(x)`` or ``U_k(x)`` with SymPy's extension to negative ``k``
    (``T_-k = T_k``, ``U_-1 = 0``, ``U_-k = -U_(k-2)``)."""
    if k < 0:
        if kind == "T":
            return _chebyshev("T", -k, x, one)
        return 0 * one if k == -1 else -_chebyshev("U", -k - 2, x, one)
    prev, cur = one, (x if kind == "T" else 2 * x)
    if k == 0:
        return one
    for _ in range(k - 1):
        prev, cur = cur, 2 * x * cur - prev
    return cur


def _multiple_angle(func: type, k: int, cos_x: Any, sin_x: Any, one: Any) -> Any:
    """``cos(k x)``, ``sin(k x)`` as SymPy's ``expand_trig`` writes them: ``T_k(cos x)``;
    ``(-1)^((k-1)/2) T_k(sin x)`` for odd ``k``, ``(-1)^(k/2-1) cos x U_(k-1)(sin x)`` for even."""
    if func is sp.cos:
        return _chebyshev("T", k, cos_x, one)
    if k % 2:
        return (-1) ** ((k - 1) // 2 % 2) * _chebyshev("T", k, sin_x, one)
    return (-1) ** ((k // 2 - 1) % 2) * cos_x * _chebyshev("U", k - 1, sin_x, one)


def _canonical_theta_flint(e: sp.Expr, theta: sp.Symbol, n: sp.Symbol, var: sp.Symbol) -> sp.Expr | None:
    """:func:`canonical_theta` of ``e`` (``omega`` and ``t_d`` already in ``theta``, ``n``) in
    flint, for a rational expression in parameters and ``cos``/``sin`` of whole-number
    combinations ``(a n + b) theta`` whose denominators hold no ``sin(theta)``: each angle is
    expanded as ``expand_trig`` does it (the multiple-angle forms in ``cos(n theta)``,
    ``sin(n theta)`` are kept, as there), ``sin(theta)**2 = 1 - c**2`` in the numerator, and
    the result is SymPy's cancelled fraction, expanded. ``None`` (SymPy's route) otherwise."""
    from hapticproof.exact.canonical import generator_order, sympy_fraction
    from hapticproof.exact.evaluator import rational_program, run_quotient

    program = rational_program(e, opaque=True)
    if program is None:
        return None
    plain, angles = [], {}
    for atom in program.symbols:
        if isinstance(atom, sp.Symbol):
            if atom in (theta, n, var, SIN_T, COS_N, SIN_N):
                return None
            plain.append(atom)
            continue
        if not isinstance(atom, (sp.cos, sp.sin)):
            return None
        parts = sp.expand(atom.args[0]).as_coefficients_dict()
        a, b = parts.pop(n * theta, sp.Integer(0)), parts.pop(theta, sp.Integer(0))
        if parts or not (a.is_Integer and b.is_Integer):
            return None
        angles[atom] = (type(atom), int(a), int(b))
    names = [s.name for s in plain] + [var.name, SIN_T.name, COS_N.name, SIN_N.name]
    if len(set(names)) != len(names):
        return None
    gens = generator_order(frozenset([*plain, var, SIN_T, COS_N, SIN_N]))
    ctx = flint.fmpq_mpoly_ctx.get(tuple(f"x{k}" for k in range(len(gens))), "lex")
    g = dict(zip(gens, ctx.gens()))
    one = ctx.constant(1)
    c_, s_, cn, sn = g[var], g[SIN_T], g[COS_N], g[SIN_N]
    values: dict[Any, Any] = {p: g[p] for p in plain}
    for atom, (func, a, b) in angles.items():
        parts = []
        for k, cos_x, sin_x in ((a, cn, sn), (b, c_, s_)):
            if k:
                parts.append((_multiple_angle(sp.cos, k, cos_x, sin_x, one), _multiple_angle(sp.sin, k, cos_x, sin_x, one)))
        if not parts:
            parts.append((one, 0 * one))
        cos_v, sin_v = parts[0]
        for ck, sk in parts[1:]:
            cos_v, sin_v = cos_v * ck - sin_v * sk, sin_v * ck + cos_v * sk
        values[atom] = cos_v if func is sp.cos else sin_v
    # a denominator with sin(theta) (after expand_trig) would be reduced by SymPy's route in a
    # representation of its own: left to it
    for base in (p.base for p in e.atoms(sp.Pow) if p.exp.is_negative):
        if any(a in angles and values[a].degrees()[gens.index(SIN_T)] > 0 for a in base.atoms(sp.cos, sp.sin)):
            return None
    found = run_quotient(program, values, ctx)
    if found is None:
        return None
    num, den = found
    k_s = gens.index(SIN_T)
    if den.degrees()[k_s] > 0:
        return None
    reduced = 0 * one
    for monom, coeff in num.terms():
        power = monom[k_s]
        rest = ctx.from_dict({tuple(0 if i == k_s else m for i, m in enumerate(monom)): coeff})
        reduced += rest * (1 - c_**2) ** (power // 2) * s_ ** (power % 2)
    h = reduced.gcd(den)
    if not reduced.is_zero() and not h.is_one():
        reduced, den = reduced / h, den / h
    p_expr, q_expr = sympy_fraction(reduced, den, gens)
    return sp.expand(p_expr / q_expr)


#: The exponential variables of :class:`CircleForm`: ``u = e^{j theta/L}``, ``w = e^{j n theta}``
#: and the imaginary unit ``j`` (reduced modulo ``j^2 + 1``).
U_SYM = sp.Symbol("u_circle")
W_SYM = sp.Symbol("w_circle")
J_SYM = sp.Symbol("j_circle")


@dataclass(frozen=True, slots=True)
class CircleForm:
    r"""A trigonometric expression in ``theta = wT`` (and ``n theta``) as a rational function of
    the exponentials ``u = e^{j theta/L}`` and ``w = e^{j n theta/M}``: ``real + j imag`` with
    ``real``, ``imag`` real-rational in ``u``, ``w`` and the parameters (``M`` divides ``L``).

    Every angle ``(a n + r) theta`` with rational ``a``, ``r`` becomes the monomial
    ``w^{aM} u^{rL}`` (``M``, ``L`` the least common denominators), so half angles (the
    Dirichlet kernel ``sin((n + 1/2) theta)/sin(theta/2)``), shifted cosines and products of
    sines are rational functions -- and two expressions are equal for every ``theta`` (and every
    integer ``n``) exactly when their forms are equal: an identity of rational functions holds on
    the circle iff it holds identically, and for ``theta/pi`` irrational the powers ``w = e^{j n
    theta}`` of the integers are dense on the circle, so ``w`` is an independent variable.

    >>> th = sp.Symbol('theta', real=True)
    >>> n = sp.Symbol('n', integer=True)
    >>> dirichlet = circle_form(sp.sin((n + sp.Rational(1, 2))*th)/sp.sin(th/2), th, n)
    >>> plain = circle_form(sp.cos(n*th) + sp.sin(n*th)*sp.sin(th)/(1 - sp.cos(th)), th, n)
    >>> dirichlet.equals(plain), dirichlet.L
    (True, 2)
    """

    real: sp.Expr
    imag: sp.Expr
    L: int
    M: int = 1

    def with_period(self, L: int, M: int = 1) -> CircleForm:
        """The same form over ``u' = e^{j theta/L}``, ``w' = e^{j n theta/M}`` for multiples
        ``L``, ``M`` of :attr:`L`, :attr:`M`."""
        if L % self.L or M % self.M or L % M:
            raise ValueError(f"({L}, {M}) is not a multiple of ({self.L}, {self.M})")
        sub = {U_SYM: U_SYM ** (L // self.L), W_SYM: W_SYM ** (M // self.M)}
        return CircleForm(sp.cancel(self.real.xreplace(sub)), sp.cancel(self.imag.xreplace(sub)), L, M)

    def __sub__(self, other: CircleForm) -> CircleForm:
        M = self.M * other.M // math.gcd(self.M, other.M)
        L = self.L * other.L // math.gcd(self.L, other.L)
        L = L * M // math.gcd(L, M)
        a, b = self.with_period(L, M), other.with_period(L, M)
        return CircleForm(sp.cancel(a.real - b.real), sp.cancel(a.imag - b.imag), L, M)

    def is_zero(self) -> bool:
        from hapticproof.exact.canonical import is_identically_zero

        return is_identically_zero(self.real) and is_identically_zero(self.imag)

    def equals(self, other: CircleForm) -> bool:
        """Equal for every ``theta`` (and integer ``n``): the difference is the zero form."""
        return (self - other).is_zero()

    def at(self, t: Any, n: Any = None, values: dict | None = None) -> sp.Expr | None:
        """The exact (Gaussian-rational) value at ``u = (1 + j t)/(1 - j t)`` -- ``theta = 2 L
        atan(t)`` -- and the integer ``n`` (``w = u^{L n / M}``), the parameters at ``values``;
        ``None`` at a pole."""
        u = (1 + sp.I * sp.Rational(t)) / (1 - sp.I * sp.Rational(t))
        sub = dict(values or {})
        sub[U_SYM] = u
        if n is not None:
            sub[W_SYM] = u ** (self.L // self.M * int(n))
        out = []
        for part in (self.real, self.imag):
            num, den = sp.fraction(sp.together(part))
            d = sp.expand(sp.sympify(den).xreplace(sub))
            if d == 0:
                return None
            out.append(sp.expand(sp.sympify(num).xreplace(sub)) / d)
        value = sp.expand(out[0] + sp.I * out[1])
        return sp.nsimplify(value) if value.free_symbols == set() else value

    def c_form(self, var: sp.Symbol = C_SYM) -> sp.Expr | None:
        """The rational function of ``c = cos(theta)`` the expression is, or ``None`` when it is
        not one (it depends on ``sin theta`` or on ``n theta``, or is not ``2 pi``-periodic)."""
        if self.real.has(W_SYM) or self.imag.has(W_SYM):
            return None
        from hapticproof.exact.canonical import is_identically_zero

        parts = []
        for part in (self.real, self.imag):
            num, den = sp.fraction(sp.cancel(sp.together(part)))
            polys = [sp.Poly(num, U_SYM), sp.Poly(den, U_SYM)]
            if any(k % self.L for poly in polys for (k,) in poly.monoms()):
                return None              # not 2 pi-periodic in theta
            z_of = lambda e: sp.sympify(e).xreplace({U_SYM: Z_SYM ** sp.Rational(1, self.L)})  # noqa: E731
            parts.append(sp.cancel(sp.powsimp(z_of(num), force=True) / sp.powsimp(z_of(den), force=True)))
        real_z, imag_z = parts
        # Re(real(z) + j imag(z)) on |z| = 1 with real-rational real, imag: herm(real) - Im(imag);
        # Im(imag) = sin(theta) V(c) vanishes identically for a function of c alone
        if not is_identically_zero(imaginary_part_rational(imag_z, Z_SYM, var).expr()):
            return None
        if not is_identically_zero(imaginary_part_rational(real_z, Z_SYM, var).expr()
                                   + hermitian_part_rational(imag_z, Z_SYM, var).expr()):
            return None              # not real on the circle
        return sp.cancel(hermitian_part_rational(real_z, Z_SYM, var).expr())


def _angle_multiple(arg: sp.Expr, theta: sp.Symbol, n: sp.Symbol | None) -> tuple[sp.Rational, sp.Rational]:
    """``arg = (a n + r) theta`` with rational ``a`` and ``r``; else ``ValueError``."""
    ratio = sp.expand(arg / theta)
    if ratio.has(theta):
        raise ValueError(f"the angle {sp.sstr(arg)} is not a multiple of theta")
    a = sp.Integer(0)
    if n is not None and ratio.has(n):
        poly = sp.Poly(ratio, n)
        if poly.degree() != 1:
            raise ValueError(f"the angle {sp.sstr(arg)} is not linear in n")
        a, ratio = poly.coeff_monomial(n), poly.coeff_monomial(1)
    if not (a.is_Rational and ratio.is_Rational):
        raise ValueError(f"the angle {sp.sstr(arg)} is not (rational n + rational) times theta")
    return sp.Rational(a), sp.Rational(ratio)


def circle_form(expr: Any, theta: sp.Symbol, n: sp.Symbol | None = None) -> CircleForm:
    """The :class:`CircleForm` of an expression in ``cos``, ``sin``, ``tan``, ``cot``, ``sec``,
    ``csc`` and ``exp(j ...)`` of angles ``(a n + p/q) theta``; ``ValueError`` for any other
    dependence on ``theta`` (an angle ``theta + 1``, ``theta^2``, ``cos(cos theta)``).

    >>> th = sp.Symbol('theta', real=True)
    >>> circle_form(sp.sin(3*th/2)/sp.sin(th/2), th).c_form()
    2*c + 1
    """
    expr = sp.sympify(expr)
    angles: dict[sp.Basic, tuple[sp.Rational, sp.Rational, bool]] = {}
    for atom in expr.atoms(sp.cos, sp.sin, sp.tan, sp.cot, sp.sec, sp.csc, sp.exp):
        if not atom.has(theta):
            continue
        arg = atom.args[0]
        if isinstance(atom, sp.exp):
            inner = sp.expand(arg / sp.I)
            if inner.has(sp.I):
                raise ValueError(f"exp({sp.sstr(arg)}) is not a point of the circle")
            a, r = _angle_multiple(inner, theta, n)
        else:
            a, r = _angle_multiple(arg, theta, n)
        angles[atom] = (a, r, isinstance(atom, sp.exp))
    L = M = 1
    for a, r, _ in angles.values():
        L = L * int(r.q) // math.gcd(L, int(r.q))
        M = M * int(a.q) // math.gcd(M, int(a.q))
    L = L * M // math.gcd(L, M)
    sub = {}
    for atom, (a, r, _) in angles.items():
        X = W_SYM ** int(a * M) * U_SYM ** int(r * L)
        if isinstance(atom, sp.exp):
            sub[atom] = X
        elif isinstance(atom, sp.cos):
            sub[atom] = (X + 1 / X) / 2
        elif isinstance(atom, sp.sin):
            sub[atom] = (X - 1 / X) / (2 * J_SYM)
        elif isinstance(atom, sp.tan):
            sub[atom] = (X - 1 / X) / (J_SYM * (X + 1 / X))
        elif isinstance(atom, sp.cot):
            sub[atom] = J_SYM * (X + 1 / X) / (X - 1 / X)
        elif isinstance(atom, sp.sec):
            sub[atom] = 2 / (X + 1 / X)
        else:
            sub[atom] = 2 * J_SYM / (X - 1 / X)
    out = expr.xreplace(sub).xreplace({sp.I: J_SYM})
    if out.has(theta):
        raise ValueError("the expression depends on theta other than through the circle")
    return _split_j(out, L, M)


def _split_j(expr: sp.Expr, L: int, M: int = 1) -> CircleForm:
    """``expr`` (rational in ``j``) as ``real + j imag`` modulo ``j^2 + 1``."""
    num, den = sp.fraction(sp.cancel(sp.together(expr)))

    def parts(poly_expr: sp.Expr) -> tuple[sp.Expr, sp.Expr]:
        poly = sp.Poly(sp.expand(poly_expr), J_SYM)
        re, im = sp.Integer(0), sp.Integer(0)
        for (k,), coeff in poly.terms():
            sign = -1 if (k // 2) % 2 else 1
            if k % 2:
                im += sign * coeff
            else:
                re += sign * coeff
        return re, im

    n0, n1 = parts(num)
    d0, d1 = parts(den)
    # (n0 + j n1)/(d0 + j d1) = ((n0 d0 + n1 d1) + j (n1 d0 - n0 d1)) / (d0^2 + d1^2)
    norm = sp.expand(d0**2 + d1**2)
    return CircleForm(sp.cancel((n0 * d0 + n1 * d1) / norm), sp.cancel((n1 * d0 - n0 * d1) / norm), L, M)


def theta_form_on_circle(expr: Any, var: sp.Symbol = C_SYM) -> CircleForm:
    """A derived form in ``c``, ``sin(theta)``, ``cos(n theta)``, ``sin(n theta)`` (the variables
    of :meth:`ThetaForm.canonical`, or a plain rational function of ``c``) as a :class:`CircleForm`."""
    z_ = U_SYM
    sub = {var: (z_ + 1 / z_) / 2, SIN_T: (z_ - 1 / z_) / (2 * J_SYM),
           COS_N: (W_SYM + 1 / W_SYM) / 2, SIN_N: (W_SYM - 1 / W_SYM) / (2 * J_SYM)}
    return _split_j(sp.sympify(expr).xreplace(sub), 1)


def evaluate_on_circle(F: Any, omega_T: Any, z: sp.Symbol = Z_SYM, digits: int = 30):
    """Direct complex evaluation of ``F(e^{j omega_T})`` with mpmath (an independent check).

    >>> from hapticproof.core.symbols import z
    >>> complex(evaluate_on_circle(1/(z - 1), 1.0)).real
    -0.5
    """
    import mpmath

    with mpmath.workdps(digits):
        point = mpmath.expj(mpmath.mpf(omega_T) if not isinstance(omega_T, sp.Basic) else mpmath.mpf(sp.N(omega_T, digits + 5)))
        func = sp.lambdify(z, sp.sympify(F), "mpmath")
        return func(point)


# ---------------------------------------------------------------------------------------------
# Imaginary axis (continuous time)
# ---------------------------------------------------------------------------------------------


def imaginary_axis_rational(Z: Any, s: sp.Symbol = S_SYM, var: sp.Symbol = X_SYM) -> tuple[CRational, CRational]:
    """``Re Z(jw)`` and ``Im Z(jw)/w`` as rational functions of ``x = w**2``.

    ``Z(jw) = P(jw)/Q(jw)``; ``P(s)Q(-s) +- P(-s)Q(s)`` is even (odd) in ``s`` and
    ``Q(s)Q(-s)`` is even, so substituting ``s**2 = -x`` gives exact polynomials in ``x``.

    >>> import sympy as sp
    >>> from hapticproof.core.symbols import s
    >>> re, im = imaginary_axis_rational(9 / (s + 3))
    >>> re.expr(), im.expr()
    (27/(x + 9), -9/(x + 9))
    """
    P, Q = numerator_denominator(Z, s)
    Pm = P.compose(sp.Poly(-s, s))
    Qm = Q.compose(sp.Poly(-s, s))
    even_num = P * Qm + Pm * Q  # = 2 * even part
    odd_num = P * Qm - Pm * Q   # = 2 * odd part, divisible by s
    den = Q * Qm

    def even_to_x(poly: sp.Poly) -> sp.Poly:
        terms = {}
        for (power,), coeff in poly.terms():
            if power % 2:
                raise AssertionError("expected an even polynomial")
            terms[power // 2] = coeff * (-1) ** (power // 2)
        expr = sum((poly.domain.to_sympy(cf) * var**k for k, cf in terms.items()), sp.Integer(0))
        return sp.Poly(expr, var)

    odd_over_s = sp.Poly(sp.cancel(odd_num.as_expr() / s), s) if not odd_num.is_zero else sp.Poly(0, s)
    # Im Z(jw) = (odd part at jw)/j ... odd(jw) = jw * R(-w^2) -> Im = w * R(-x)
    re = _simplest(sp.Poly(even_to_x(even_num).as_expr() / 2, var), even_to_x(den), var)
    im = _simplest(sp.Poly(even_to_x(odd_over_s).as_expr() / 2, var), even_to_x(den), var)
    return re, im


def real_part_x(Z: Any, s: sp.Symbol = S_SYM, var: sp.Symbol = X_SYM) -> sp.Expr:
    """``Re Z(jw)`` as a SymPy rational function of ``x = w**2``.

    >>> from hapticproof.core.symbols import s
    >>> real_part_x(1 / (s + 1)**2)
    (1 - x)/(x**2 + 2*x + 1)
    """
    return sp.cancel(imaginary_axis_rational(Z, s, var)[0].expr())
