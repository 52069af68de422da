r"""Exact values of real-rational expressions on the stability boundary: the unit circle or the axis.

On the unit circle ``z = e^{j theta}`` every real-rational ``F(z)`` takes the value
``A(c) + j r B(c)`` with ``c = cos(theta)``, ``r = sin(theta)`` and ``A``, ``B`` rational in ``c``
(and the parameters); on the imaginary axis ``s = j omega`` it is ``A(x) + j r B(x)`` with
``x = omega^2`` and ``r = omega``. Products of such values, conjugates, ``|F|^2``, ``Re`` and
``Im`` stay in the ring ``Q(params, t)[r][j]`` with ``r^2 = q(t)`` (``q = 1 - c^2`` on the circle,
``q = x`` on the axis) and ``j^2 = -1``: a :class:`BoundaryValue` is that element, exactly. It is
how a printed ``\Re\{(1 - e^{-j\omega T}) H(e^{j\omega T})\}`` or ``|z_{12} z_{21}|^2`` becomes
a rational function of ``c`` or ``x`` whose sign the kernel decides.

The boundary variable ``t`` and the square root ``r`` have internal names (``$c``, ``$x``) that no
user name can take: a paper's own ``c`` or ``x`` never collides with them.

>>> from hapticproof.exact.rational import RationalFunction
>>> z = RationalFunction.variable("$z")
>>> F = (z + 1) / (z - 1)                              # the bilinear image of s: Re = 0 on the circle
>>> v = BoundaryValue.at_circle(F)
>>> v.real().to_sympy(), v.imaginary_over_r().to_sympy({"$c": __import__("sympy").Symbol("c")})
(0, 1/(c - 1))
"""

from __future__ import annotations

from dataclasses import dataclass

from hapticproof.exact.rational import RationalFunction

__all__ = ["BoundaryValue", "determinant", "CIRCLE", "AXIS", "C_NAME", "X_NAME", "Z_NAME", "S_NAME"]

#: The internal names of the transfer variables and of the boundary variables.
Z_NAME, S_NAME, C_NAME, X_NAME = "$z", "$s", "$c", "$x"
CIRCLE, AXIS = "circle", "axis"


def _zero() -> RationalFunction:
    return RationalFunction.constant(0)


@dataclass(frozen=True, slots=True)
class BoundaryValue:
    """``(re0 + r re1) + j (im0 + r im1)`` with ``r^2 = q(t)`` on ``domain`` (``circle``/``axis``)."""

    re0: RationalFunction
    re1: RationalFunction
    im0: RationalFunction
    im1: RationalFunction
    domain: str = CIRCLE

    # -- construction ---------------------------------------------------------------------------

    @classmethod
    def constant(cls, value: RationalFunction | int, domain: str = CIRCLE) -> BoundaryValue:
        """A real value that does not depend on the frequency (a parameter, a number)."""
        if not isinstance(value, RationalFunction):
            value = RationalFunction.constant(value)
        return cls(value, _zero(), _zero(), _zero(), domain)

    @classmethod
    def t(cls, domain: str = CIRCLE) -> BoundaryValue:
        """``c = cos(theta)`` on the circle, ``x = omega^2`` on the axis."""
        return cls.constant(RationalFunction.variable(C_NAME if domain == CIRCLE else X_NAME), domain)

    @classmethod
    def r(cls, domain: str = CIRCLE) -> BoundaryValue:
        """``sin(theta)`` on the circle, ``omega`` on the axis."""
        return cls(_zero(), RationalFunction.constant(1), _zero(), _zero(), domain)

    @classmethod
    def j(cls, domain: str = CIRCLE) -> BoundaryValue:
        return cls(_zero(), _zero(), RationalFunction.constant(1), _zero(), domain)

    @classmethod
    def point(cls, domain: str = CIRCLE) -> BoundaryValue:
        """The transfer variable on the boundary: ``z = c + j r`` (circle) or ``s = j r`` (axis)."""
        if domain == CIRCLE:
            return cls.t(CIRCLE) + cls.j(CIRCLE) * cls.r(CIRCLE)
        return cls.j(AXIS) * cls.r(AXIS)

    @classmethod
    def at_circle(cls, F: RationalFunction, name: str = Z_NAME) -> BoundaryValue:
        """``F(e^{j theta})`` for a rational function of ``name`` (and parameters)."""
        return cls.evaluate(F, name, CIRCLE)

    @classmethod
    def at_axis(cls, F: RationalFunction, name: str = S_NAME) -> BoundaryValue:
        """``F(j omega)`` for a rational function of ``name`` (and parameters)."""
        return cls.evaluate(F, name, AXIS)

    @classmethod
    def evaluate(cls, F: RationalFunction, name: str, domain: str) -> BoundaryValue:
        """``F`` at the boundary point of ``domain``: numerator and denominator by Horner's rule
        in the ring, then one division."""
        num, den = F.coefficients(name)
        point = cls.point(domain)
        return cls._horner(num, point, domain) / cls._horner(den, point, domain)

    @classmethod
    def _horner(cls, coeffs: list[RationalFunction], point: BoundaryValue, domain: str) -> BoundaryValue:
        out = cls.constant(0, domain)
        for a in reversed(coeffs):
            out = out * point + cls.constant(a, domain)
        return out

    # -- the ring ---------------------------------------------------------------------------------

    @property
    def q(self) -> RationalFunction:
        """``r^2`` as a function of ``t``."""
        if self.domain == CIRCLE:
            c = RationalFunction.variable(C_NAME)
            return 1 - c * c
        return RationalFunction.variable(X_NAME)

    def _check(self, other: BoundaryValue) -> BoundaryValue:
        if not isinstance(other, BoundaryValue):
            other = BoundaryValue.constant(other if isinstance(other, RationalFunction) else RationalFunction.constant(other),
                                           self.domain)
        if other.domain != self.domain:
            raise ValueError("values on the circle and on the axis do not mix")
        return other

    def __add__(self, other: object) -> BoundaryValue:
        o = self._check(other)
        return BoundaryValue(self.re0 + o.re0, self.re1 + o.re1, self.im0 + o.im0, self.im1 + o.im1, self.domain)

    __radd__ = __add__

    def __neg__(self) -> BoundaryValue:
        return BoundaryValue(-self.re0, -self.re1, -self.im0, -self.im1, self.domain)

    def __sub__(self, other: object) -> BoundaryValue:
        return self + (-self._check(other))

    def __rsub__(self, other: object) -> BoundaryValue:
        return self._check(other) - self

    @staticmethod
    def _mul_r(a0: RationalFunction, a1: RationalFunction, b0: RationalFunction, b1: RationalFunction, q: RationalFunction
               ) -> tuple[RationalFunction, RationalFunction]:
        """``(a0 + r a1)(b0 + r b1)`` in ``Q(t)[r]``."""
        return a0 * b0 + q * a1 * b1, a0 * b1 + a1 * b0

    def __mul__(self, other: object) -> BoundaryValue:
        o = self._check(other)
        q = self.q
        rr = self._mul_r(self.re0, self.re1, o.re0, o.re1, q)
        ii = self._mul_r(self.im0, self.im1, o.im0, o.im1, q)
        ri = self._mul_r(self.re0, self.re1, o.im0, o.im1, q)
        ir = self._mul_r(self.im0, self.im1, o.re0, o.re1, q)
        return BoundaryValue(rr[0] - ii[0], rr[1] - ii[1], ri[0] + ir[0], ri[1] + ir[1], self.domain)

    __rmul__ = __mul__

    def conjugate(self) -> BoundaryValue:
        """The complex conjugate (``r`` is real: ``sin(theta)``, ``omega``)."""
        return BoundaryValue(self.re0, self.re1, -self.im0, -self.im1, self.domain)

    def abs2(self) -> BoundaryValue:
        """``|v|^2`` (real, in ``Q(t)[r]``)."""
        return self * self.conjugate()

    def inverse(self) -> BoundaryValue:
        n = self.abs2()                        # u + r w, real
        u, w = n.re0, n.re1
        d = u * u - self.q * w * w             # (u + r w)(u - r w), in Q(t)
        if d.is_zero:
            raise ZeroDivisionError("the value vanishes on the whole boundary")
        inv = BoundaryValue(u / d, -w / d, _zero(), _zero(), self.domain)
        return self.conjugate() * inv

    def __truediv__(self, other: object) -> BoundaryValue:
        return self * self._check(other).inverse()

    def __rtruediv__(self, other: object) -> BoundaryValue:
        return self._check(other) * self.inverse()

    def __pow__(self, k: int) -> BoundaryValue:
        if not isinstance(k, int):
            raise ValueError("integer powers only")
        if k < 0:
            return self.inverse() ** (-k)
        out = BoundaryValue.constant(1, self.domain)
        base = self
        while k:
            if k & 1:
                out = out * base
            base = base * base
            k >>= 1
        return out

    def __eq__(self, other: object) -> bool:
        if not isinstance(other, BoundaryValue):
            return NotImplemented
        return (self.domain == other.domain and self.re0 == other.re0 and self.re1 == other.re1
                and self.im0 == other.im0 and self.im1 == other.im1)

    def __hash__(self) -> int:
        return hash((self.re0, self.re1, self.im0, self.im1, self.domain))

    # -- parts ------------------------------------------------------------------------------------

    def real_part(self) -> BoundaryValue:
        return BoundaryValue(self.re0, self.re1, _zero(), _zero(), self.domain)

    def imaginary_part(self) -> BoundaryValue:
        return BoundaryValue(self.im0, self.im1, _zero(), _zero(), self.domain)

    @property
    def is_real(self) -> bool:
        return self.im0.is_zero and self.im1.is_zero

    @property
    def is_rational_in_t(self) -> bool:
        """No ``r`` and no ``j``: a rational function of ``t`` (and parameters)."""
        return self.is_real and self.re1.is_zero

    def real(self) -> RationalFunction:
        """``Re v`` when it is rational in ``t`` (``ValueError`` when it carries ``r``)."""
        if not self.re1.is_zero:
            raise ValueError("the real part carries sin(theta) (or omega) to an odd power")
        return self.re0

    def imaginary_over_r(self) -> RationalFunction:
        """``Im v / r`` when ``Im v`` is ``r`` times a rational function of ``t`` (real-rational ``F``)."""
        if not self.im0.is_zero:
            raise ValueError("the imaginary part is not r times a rational function of t")
        return self.im1

    def rational(self) -> RationalFunction:
        """The value itself when it is a rational function of ``t`` (no ``r``, no ``j``)."""
        if not self.is_rational_in_t:
            raise ValueError("the value is not a rational function of t")
        return self.re0


def determinant(rows: list[list[BoundaryValue]]) -> BoundaryValue:
    """The determinant of a small square matrix of boundary values (Laplace expansion: the
    matrices a paper prints are 2 x 2 to 4 x 4).

    >>> c = BoundaryValue.t()
    >>> determinant([[c, BoundaryValue.constant(1)], [BoundaryValue.constant(1), c]]) == c * c - 1
    True
    """
    n = len(rows)
    if n == 1:
        return rows[0][0]
    out = None
    for j in range(n):
        if rows[0][j].re0.is_zero and rows[0][j].re1.is_zero and rows[0][j].im0.is_zero and rows[0][j].im1.is_zero:
            continue
        minor = [r[:j] + r[j + 1:] for r in rows[1:]]
        term = rows[0][j] * determinant(minor)
        term = term if j % 2 == 0 else -term
        out = term if out is None else out + term
    return out if out is not None else BoundaryValue.constant(0, rows[0][0].domain)
