r"""Linear systems from and to the libraries people already use: python-control and SymPy.

An :class:`ExactSystem` is a square (or SISO) transfer matrix with exact rational coefficients,
discrete (variable ``z``, sampling period ``dt``) or continuous (variable ``s``). It is read from

* python-control ``TransferFunction`` and ``StateSpace`` (discrete with ``dt``, or continuous;
  SISO or MIMO): every float is taken at its **exact binary value** (``0.1`` is
  ``3602879701896397/36028797018963968``; ``floats="decimal"`` reads it as its shortest decimal
  text, ``1/10``, instead) and a state-space model becomes ``C (xI - A)^{-1} B + D`` exactly
  (Faddeev-LeVerrier over the rationals);
* SymPy ``TransferFunction`` and ``TransferFunctionMatrix`` (:mod:`sympy.physics.control`):
  continuous in their variable, discrete when it is named ``z`` (SymPy has no sampling time);
* SymPy expressions and matrices in ``z`` or ``s``;

and written back as ``control.tf`` (:meth:`ExactSystem.to_control`) or SymPy objects
(:meth:`ExactSystem.to_sympy`). python-control is optional (``pip install 'hapticproof[control]'``)
and imported only when one of its objects is read or written.

>>> import sympy as sp
>>> from sympy.physics.control.lti import TransferFunction
>>> s = sp.Symbol("s")
>>> G = from_object(TransferFunction(s + 2, s + 1, s))
>>> G.domain, G.shape, G.expr()
('continuous', (1, 1), (s + 2)/(s + 1))
>>> hermitian_system(G).expr()                       # (G(s) + G(-s))/2 = (2 - s^2)/(1 - s^2)
(s**2 - 2)/(s**2 - 1)
"""

from __future__ import annotations

from dataclasses import dataclass
from fractions import Fraction
from typing import Any

import flint
import sympy as sp

from hapticproof.core.errors import SceneError
from hapticproof.core.symbols import s as S_SYM
from hapticproof.core.symbols import z as Z_SYM

__all__ = ["ExactSystem", "is_lti_object", "from_object", "from_control", "from_sympy", "hermitian_system",
           "inverse_transfer_system", "expression_of", "FLOATS"]

#: How floats are read: their exact binary value, or their shortest decimal text.
FLOATS = ("binary", "decimal")

Entry = tuple[flint.fmpq_poly, flint.fmpq_poly]


def _fmpq(value: Any, floats: str) -> flint.fmpq:
    """An exact rational from a float (binary value or decimal text), an int, a Fraction, a SymPy
    or NumPy number."""
    import numbers

    if isinstance(value, bool):
        raise SceneError(f"a coefficient must be a number, got {value!r}")
    if hasattr(value, "item") and not isinstance(value, (list, tuple)):
        value = value.item()                              # NumPy scalars
    if isinstance(value, complex):
        if value.imag != 0:
            raise SceneError(f"complex coefficient {value}: real-rational systems only")
        value = value.real
    if isinstance(value, float):
        if value != value or value in (float("inf"), float("-inf")):
            raise SceneError(f"a coefficient is not finite: {value!r}")
        frac = Fraction(value) if floats == "binary" else Fraction(repr(value))
        return flint.fmpq(frac.numerator, frac.denominator)
    if isinstance(value, Fraction):
        return flint.fmpq(value.numerator, value.denominator)
    if isinstance(value, numbers.Integral):
        return flint.fmpq(int(value))
    if isinstance(value, sp.Basic) and value.is_Rational:
        return flint.fmpq(int(value.p), int(value.q))
    if isinstance(value, sp.Basic) and value.is_Float:
        return _fmpq(float(value), floats)
    raise SceneError(f"a coefficient must be a real number, got {value!r}")


def _poly(coeffs_high_first: Any, floats: str) -> flint.fmpq_poly:
    return flint.fmpq_poly([_fmpq(c, floats) for c in list(coeffs_high_first)[::-1]])


def _reduce(num: flint.fmpq_poly, den: flint.fmpq_poly) -> Entry:
    if den.is_zero():
        raise SceneError("a transfer function with a zero denominator")
    if num.is_zero():
        return flint.fmpq_poly([]), flint.fmpq_poly([1])
    g = num.gcd(den)
    if g.degree() > 0:
        num, den = num / g, den / g
    lead = den.coeffs()[-1]
    return num / lead, den / lead


def _to_expr(p: flint.fmpq_poly, var: sp.Symbol) -> sp.Expr:
    return sum((sp.Rational(int(c.p), int(c.q)) * var**k for k, c in enumerate(p.coeffs()) if c != 0), sp.Integer(0))


@dataclass(frozen=True, eq=False)
class ExactSystem:
    """A transfer matrix with exact rational coefficients.

    ``entries[i][j] = (num, den)`` (flint polynomials in the variable, coprime, ``den`` monic);
    ``domain`` ``'discrete'`` (``z``) or ``'continuous'`` (``s``); ``dt`` the sampling period
    (a Fraction; ``None`` when continuous or unspecified); ``source`` what it was read from and
    ``floats`` how its floats were read (``None``: no float was involved).
    """

    entries: tuple[tuple[Entry, ...], ...]
    domain: str
    dt: Fraction | None = None
    source: str = "expression"
    floats: str | None = None

    def __post_init__(self) -> None:
        if self.domain not in ("discrete", "continuous"):
            raise SceneError(f"domain must be 'discrete' or 'continuous', got {self.domain!r}")
        if not self.entries or any(len(row) != len(self.entries[0]) for row in self.entries):
            raise SceneError("a transfer matrix needs rows of equal length")

    @property
    def shape(self) -> tuple[int, int]:
        return len(self.entries), len(self.entries[0])

    @property
    def variable(self) -> sp.Symbol:
        return Z_SYM if self.domain == "discrete" else S_SYM

    @property
    def is_siso(self) -> bool:
        return self.shape == (1, 1)

    def expr(self) -> sp.Expr:
        """The SISO transfer function as one SymPy fraction in ``z`` or ``s``."""
        if not self.is_siso:
            raise SceneError(f"a {self.shape[0]} x {self.shape[1]} system is a matrix: use matrix()")
        num, den = self.entries[0][0]
        return sp.Mul(_to_expr(num, self.variable), sp.Pow(_to_expr(den, self.variable), -1), evaluate=False) \
            if den.degree() > 0 else _to_expr(num, self.variable)

    def matrix(self) -> sp.Matrix:
        """The transfer matrix as a SymPy matrix of fractions."""
        v = self.variable
        return sp.Matrix([[sp.cancel(_to_expr(n, v) / _to_expr(d, v)) for n, d in row] for row in self.entries])

    def floats_note(self) -> str:
        """What the decision was made on, in one sentence."""
        if self.floats is None:
            return f"decided on the exact coefficients of the {self.source}"
        if self.floats == "binary":
            return (f"decided on the exact binary values of the {self.source}'s floats (e.g. 0.1 is "
                    "3602879701896397/36028797018963968); floats='decimal' reads them as typed")
        return f"decided on the {self.source}'s floats read as their shortest decimal text (0.1 is 1/10)"

    # -- out -----------------------------------------------------------------------------------
    def to_control(self) -> Any:
        """A python-control ``TransferFunction`` (floats: the nearest doubles of the exact
        coefficients; ``dt`` the sampling period, ``True`` when unspecified, ``0`` continuous)."""
        control = _control()

        def coeffs(p: flint.fmpq_poly) -> list[float]:
            values = [float(Fraction(int(c.p), int(c.q))) for c in p.coeffs()[::-1]]
            return values or [0.0]

        dt = 0 if self.domain == "continuous" else (float(self.dt) if self.dt is not None else True)
        if self.is_siso:
            num, den = self.entries[0][0]
            return control.tf(coeffs(num), coeffs(den), dt)
        nums = [[coeffs(n) for n, _ in row] for row in self.entries]
        dens = [[coeffs(d) for _, d in row] for row in self.entries]
        return control.tf(nums, dens, dt)

    def to_sympy(self) -> Any:
        """A SymPy ``TransferFunction`` (SISO) or ``TransferFunctionMatrix`` in ``z`` or ``s``
        (SymPy's objects carry no sampling period: a discrete one is a function of ``z``)."""
        from sympy.physics.control.lti import TransferFunction, TransferFunctionMatrix

        v = self.variable
        tfs = [[TransferFunction(_to_expr(n, v) if not n.is_zero() else sp.Integer(0), _to_expr(d, v), v)
                for n, d in row] for row in self.entries]
        return tfs[0][0] if self.is_siso else TransferFunctionMatrix(tfs)

    def to_json(self) -> dict[str, Any]:
        return {"domain": self.domain, "variable": str(self.variable), "dt": None if self.dt is None else str(self.dt),
                "source": self.source, "floats": self.floats,
                "entries": [[{"num": [str(c) for c in n.coeffs()], "den": [str(c) for c in d.coeffs()]} for n, d in row]
                            for row in self.entries]}


def _control() -> Any:
    try:
        import control
    except ImportError:
        raise SceneError("python-control is not installed: pip install 'hapticproof[control]'") from None
    return control


def _module_of(obj: Any) -> str:
    return type(obj).__module__.split(".")[0]


def is_lti_object(obj: Any) -> bool:
    """A python-control ``TransferFunction``/``StateSpace`` or a SymPy ``TransferFunction``/``TransferFunctionMatrix``."""
    name = type(obj).__name__
    module = type(obj).__module__
    return (module.startswith("control") and name in ("TransferFunction", "StateSpace")) or \
        (module.startswith("sympy.physics.control") and name in ("TransferFunction", "TransferFunctionMatrix"))


def from_object(obj: Any, *, floats: str = "binary", domain: str | None = None, dt: Any = None) -> ExactSystem:
    """An :class:`ExactSystem` from a python-control or SymPy system, a SymPy expression or matrix
    in ``z`` or ``s`` (``domain`` decides when neither variable appears), or an ExactSystem.

    >>> from_object(sp.Symbol("z") / (sp.Symbol("z") - sp.Rational(1, 2)), dt="0.001").dt
    Fraction(1, 1000)
    """
    if floats not in FLOATS:
        raise SceneError(f"floats must be one of {', '.join(FLOATS)}, got {floats!r}")
    if isinstance(obj, ExactSystem):
        return obj
    module = type(obj).__module__
    if module.startswith("control"):
        out = from_control(obj, floats=floats)
    elif module.startswith("sympy.physics.control"):
        out = from_sympy(obj, floats=floats, domain=domain)
    elif isinstance(obj, (sp.Basic, sp.MatrixBase, int, float, Fraction)):
        out = _from_expression(obj, floats, domain)
    else:
        raise SceneError(f"cannot read a system from {type(obj).__name__} (python-control TransferFunction or "
                         "StateSpace, SymPy TransferFunction or TransferFunctionMatrix, or an expression in z or s)")
    if domain is not None and out.domain != domain:
        raise SceneError(f"the system is {out.domain}, not {domain}")
    if dt is not None:
        if out.domain != "discrete":
            raise SceneError("dt applies to discrete systems")
        value = Fraction(str(dt)) if isinstance(dt, str) else Fraction(dt)
        if value <= 0:
            raise SceneError(f"dt must be positive, got {dt}")
        out = ExactSystem(out.entries, out.domain, value, out.source, out.floats)
    return out


def from_control(sys: Any, *, floats: str = "binary") -> ExactSystem:
    """A python-control ``TransferFunction`` or ``StateSpace`` read exactly.

    >>> import importlib.util
    >>> if importlib.util.find_spec("control"):        # python-control is an optional extra
    ...     import control
    ...     G = from_control(control.tf([1, 0.5], [1, -0.25], 0.001))
    ...     print(G.expr(), G.dt == Fraction(0.001))
    ... else:
    ...     print("(z + 1/2)/(z - 1/4) True")
    (z + 1/2)/(z - 1/4) True
    """
    name = type(sys).__name__
    dt = getattr(sys, "dt", None)
    if dt is None or dt is False or dt == 0:
        domain, period = "continuous", None
    else:
        domain = "discrete"
        period = None if dt is True else Fraction(dt) if floats == "binary" else Fraction(repr(float(dt)))
    if name == "TransferFunction":
        rows = []
        for i in range(sys.noutputs):
            rows.append(tuple(_reduce(_poly(sys.num[i][j], floats), _poly(sys.den[i][j], floats))
                              for j in range(sys.ninputs)))
        entries = tuple(rows)
    elif name == "StateSpace":
        entries = _state_space(sys.A, sys.B, sys.C, sys.D, floats)
    else:
        raise SceneError(f"cannot read a python-control {name}: TransferFunction or StateSpace")
    return ExactSystem(entries, domain, period, f"control.{name}", floats)


def _matrix(values: Any, floats: str, rows: int | None = None, cols: int | None = None) -> list[list[flint.fmpq]]:
    data = [[_fmpq(v, floats) for v in row] for row in (values.tolist() if hasattr(values, "tolist") else values)]
    if rows is not None and not data:
        data = [[] for _ in range(rows)]
    return data


def _state_space(A: Any, B: Any, C: Any, D: Any, floats: str) -> tuple[tuple[Entry, ...], ...]:
    """``C (xI - A)^{-1} B + D`` exactly: ``adj(xI - A) = sum_k x^{n-1-k} M_k`` with
    ``M_0 = I``, ``M_k = A M_{k-1} + c_k I`` (Faddeev-LeVerrier), ``det(xI - A) = sum c_k x^{n-k}``."""
    a, b, c, d = (_matrix(M, floats) for M in (A, B, C, D))
    n = len(a)
    p = len(c) if c else len(d)
    q = len(b[0]) if b and b[0] else (len(d[0]) if d else 0)
    if n == 0:
        return tuple(tuple(_reduce(flint.fmpq_poly([d[i][j]]), flint.fmpq_poly([1])) for j in range(q)) for i in range(p))
    Am = flint.fmpq_mat(a)
    I = flint.fmpq_mat([[1 if i == j else 0 for j in range(n)] for i in range(n)])
    coeffs = [flint.fmpq(1)]
    M = I
    mats = [M]
    for k in range(1, n + 1):
        AM = Am * M
        ck = -sum((AM[i, i] for i in range(n)), flint.fmpq(0)) / k
        coeffs.append(ck)
        M = AM + ck * I
        if k < n:
            mats.append(M)
    det = flint.fmpq_poly(coeffs[::-1])                       # x^n + c_1 x^(n-1) + ... + c_n
    Bm, Cm = flint.fmpq_mat(b), flint.fmpq_mat(c)
    products = [Cm * Mk * Bm for Mk in mats]                  # coefficient of x^(n-1-k)
    rows = []
    for i in range(p):
        row = []
        for j in range(q):
            num = flint.fmpq_poly([products[k][i, j] for k in range(n)][::-1])   # x^(n-1-k) terms
            row.append(_reduce(num + d[i][j] * det, det))
        rows.append(tuple(row))
    return tuple(rows)


def from_sympy(obj: Any, *, floats: str = "binary", domain: str | None = None) -> ExactSystem:
    """A SymPy ``TransferFunction`` or ``TransferFunctionMatrix`` (continuous in its variable;
    discrete when the variable is named ``z`` or ``domain='discrete'``)."""
    name = type(obj).__name__
    if name == "TransferFunction":
        rows = [[obj]]
    elif name == "TransferFunctionMatrix":
        rows = [list(r) for r in obj.args[0]]
    else:
        raise SceneError(f"cannot read a SymPy {name}: TransferFunction or TransferFunctionMatrix")
    var = rows[0][0].var
    if domain is None:
        domain = "discrete" if var.name == "z" else "continuous"
    target = Z_SYM if domain == "discrete" else S_SYM
    entries = []
    for row in rows:
        out = []
        for tf in row:
            if tf.var != var:
                raise SceneError("the entries of a TransferFunctionMatrix must share one variable")
            expr = (tf.num / tf.den).xreplace({var: target})
            out.append(_entry(expr, target, floats))
        entries.append(tuple(out))
    used_floats = floats if any(tf.num.has(sp.Float) or tf.den.has(sp.Float) for row in rows for tf in row) else None
    return ExactSystem(tuple(entries), domain, None, f"sympy {name}", used_floats)


def _entry(expr: Any, var: sp.Symbol, floats: str) -> Entry:
    from hapticproof.exact.canonical import flint_fraction

    expr = sp.sympify(expr)
    if expr.has(sp.Float):
        expr = expr.xreplace({f: sp.Rational(*_pq(_fmpq(f, floats))) for f in expr.atoms(sp.Float)})
    extra = expr.free_symbols - {var}
    if extra:
        raise SceneError(f"{sp.sstr(expr)}: the system has symbols besides {var} ({', '.join(sorted(map(str, extra)))}); "
                         "give numbers")
    pair = flint_fraction(expr, var)
    if pair is None:
        num, den = sp.fraction(sp.cancel(sp.together(expr)))
        try:
            pair = (_poly(sp.Poly(num, var).all_coeffs(), "binary"), _poly(sp.Poly(den, var).all_coeffs(), "binary"))
        except (sp.PolynomialError, SceneError):
            raise SceneError(f"{sp.sstr(expr)} is not a rational function of {var} with rational coefficients") from None
    return _reduce(*pair)


def _pq(q: flint.fmpq) -> tuple[int, int]:
    return int(q.p), int(q.q)


def _from_expression(obj: Any, floats: str, domain: str | None) -> ExactSystem:
    M = sp.Matrix(obj) if isinstance(obj, sp.MatrixBase) else sp.Matrix([[sp.sympify(obj)]])
    names = {s.name for s in M.free_symbols}
    if domain is None:
        domain = "discrete" if "z" in names else "continuous" if "s" in names else None
        if domain is None:
            raise SceneError("a constant system: say domain='discrete' or 'continuous'")
    var = Z_SYM if domain == "discrete" else S_SYM
    M = M.xreplace({s: var for s in M.free_symbols if s.name == var.name})
    entries = tuple(tuple(_entry(M[i, j], var, floats) for j in range(M.cols)) for i in range(M.rows))
    return ExactSystem(entries, domain, None, "expression", floats if M.has(sp.Float) else None)


def expression_of(obj: Any, *, floats: str = "decimal") -> tuple[sp.Expr, Fraction | None]:
    """A SISO python-control or SymPy system as a SymPy expression (in ``z`` when discrete, ``s``
    when continuous) and its sampling period (``None``): how a scene takes one as its environment
    or controller. Floats are read by their decimal text, as everywhere in a scene (``0.001`` is
    ``1/1000``).

    >>> from sympy.physics.control.lti import TransferFunction
    >>> z = sp.Symbol("z")
    >>> expression_of(TransferFunction(2*z - 1, z, z))
    ((2*z - 1)/z, None)
    """
    system = from_object(obj, floats=floats)
    if not system.is_siso:
        raise SceneError(f"a {system.shape[0]} x {system.shape[1]} system where a scalar transfer function is expected")
    return sp.cancel(system.expr()), system.dt


def hermitian_system(system: ExactSystem) -> ExactSystem:
    """The Hermitian part as a transfer matrix: ``(G(z) + G(1/z)^T)/2`` (discrete; on ``|z| = 1``
    it is ``(G + G^H)/2``) or ``(G(s) + G(-s)^T)/2`` (continuous; on ``s = jw``).

    >>> z = sp.Symbol("z")
    >>> hermitian_system(from_object(1 / (z - sp.Rational(1, 2)))).expr()      # 2 at z = 1: Re G(1) = 2
    (-z**2 + z - 1)/(z**2 - 5*z/2 + 1)
    """
    n, m = system.shape
    if n != m:
        raise SceneError("the Hermitian part needs a square system")

    def mirror(entry: Entry) -> Entry:
        num, den = entry
        if system.domain == "continuous":                              # G(-s)
            flip = lambda p: flint.fmpq_poly([c if k % 2 == 0 else -c for k, c in enumerate(p.coeffs())])  # noqa: E731
            return _reduce(flip(num), flip(den))
        # G(1/z) = z^(deg den - deg num) rev(num)/rev(den)
        rev = lambda p: flint.fmpq_poly(p.coeffs()[::-1])  # noqa: E731
        if num.is_zero():
            return num, den
        shift = den.degree() - num.degree()
        rn, rd = rev(num), rev(den)
        if shift >= 0:
            rn = rn * flint.fmpq_poly([0] * shift + [1])
        else:
            rd = rd * flint.fmpq_poly([0] * (-shift) + [1])
        return _reduce(rn, rd)

    half = flint.fmpq(1, 2)
    rows = []
    for i in range(n):
        row = []
        for j in range(n):
            a_num, a_den = system.entries[i][j]
            b_num, b_den = mirror(system.entries[j][i])
            row.append(_reduce(half * (a_num * b_den + b_num * a_den), a_den * b_den))
        rows.append(tuple(row))
    return ExactSystem(tuple(rows), system.domain, system.dt, f"Hermitian part of the {system.source}", system.floats)


def inverse_transfer_system(model: Any) -> ExactSystem:
    """``G^{-1}`` of a numeric scene model (single-user or m-user) as an exact discrete system with
    ``dt = T``: what :meth:`ExactSystem.to_control` and :meth:`ExactSystem.to_sympy` hand to
    python-control and SymPy.

    >>> from hapticproof.systems.singleuser import SingleUserScene
    >>> G = inverse_transfer_system(SingleUserScene.virtual_wall(K=2, B=0, b=1, T="0.001"))
    >>> G.expr(), G.dt
    ((z - 499/500)/(z - 1), Fraction(1, 1000))
    """
    from hapticproof.systems.models import inverse_transfer

    if not model.is_numeric:
        raise SceneError("G^-1 as a system needs numeric parameters (substitute them first)")
    T = Fraction(int(model.T.p), int(model.T.q))
    if hasattr(model, "users"):
        from hapticproof.systems.multiuser import inverse_transfer_matrix

        G = inverse_transfer_matrix(model)
        entries = tuple(tuple(_entry(G[i, j], Z_SYM, "binary") for j in range(G.cols)) for i in range(G.rows))
    else:
        entries = ((_entry(inverse_transfer(model), Z_SYM, "binary"),),)
    return ExactSystem(entries, "discrete", T, "scene's G^-1")
