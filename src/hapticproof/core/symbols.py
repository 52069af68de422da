"""Canonical SymPy symbols shared by every module.

The unit circle is parametrised by ``c = cos(wT)`` (see DESIGN.md): every Hermitian part of a
real-rational discrete transfer function is a rational function of ``c`` on ``[-1, 1]``.
The imaginary axis is parametrised by ``x = w**2`` on ``[0, oo)``.

>>> from hapticproof.core.symbols import c, z
>>> c.is_real, z.is_real
(True, None)
"""

from __future__ import annotations

import sympy as sp

__all__ = ["z", "s", "c", "x", "omega", "theta", "n", "j", "sin_theta", "cos_n", "sin_n", "HELPERS", "helper_definitions",
           "TOOLKIT_NAMES", "toolkit_name"]

#: Complex frequency variable of discrete-time transfer functions.
z = sp.Symbol("z")
#: Laplace variable of continuous-time transfer functions.
s = sp.Symbol("s")
#: ``cos(omega*T)``, ranging over [-1, 1] on the unit circle.
c = sp.Symbol("c", real=True)
#: ``omega**2``, ranging over [0, oo) on the imaginary axis.
x = sp.Symbol("x", nonnegative=True)
#: Angular frequency in rad/s.
omega = sp.Symbol("omega", real=True)
#: Normalised frequency ``omega*T`` in radians.
theta = sp.Symbol("theta", real=True)
#: Symbolic integer delay ratio ``t_d / T``.
n = sp.Symbol("n", integer=True, nonnegative=True)
#: Imaginary unit as printed in the papers.
j = sp.I
#: ``sin(theta)``; appears in imaginary parts and unequal-delay Hermitian parts.
sin_theta = sp.Symbol("s_theta", real=True)
#: ``cos(n*theta)`` and ``sin(n*theta)`` for a symbolic delay ``n`` (theta-forms).
cos_n = sp.Symbol("C_n", real=True)
sin_n = sp.Symbol("S_n", real=True)

#: What each helper symbol of the canonical forms stands for (text output defines those it uses).
HELPERS: dict[str, str] = {"c": "cos wT", "s_theta": "sin wT", "C_n": "cos(n wT)", "S_n": "sin(n wT)", "theta": "wT"}

#: The toolkit's own quantities, by name: a scene's parameter, a role or a paper file's symbol
#: may not take one of these names (a device damping named ``n`` was read as the delay, one
#: named ``c`` as cos(omega T)); ``n`` (as an integer) and ``omega`` (real) may be declared by
#: a paper file with that meaning.
TOOLKIT_NAMES: dict[str, str] = {
    "n": "the delay n = t_d/T in samples", "c": "cos(omega T) on the unit circle", "x": "omega^2 on the imaginary axis",
    "omega": "the angular frequency", "theta": "the angle omega T", "s_theta": "sin(omega T)",
    "C_n": "cos(n omega T)", "S_n": "sin(n omega T)",
}


def toolkit_name(name: str) -> str | None:
    """What the toolkit's own name ``name`` means (:data:`TOOLKIT_NAMES`), ``None`` for a free name.

    >>> toolkit_name("c"), toolkit_name("b")
    ('cos(omega T) on the unit circle', None)
    """
    return TOOLKIT_NAMES.get(name)


def helper_definitions(expr) -> str:
    """`` (s_theta = sin wT, S_n = sin(n wT))``: the helper symbols ``expr`` uses, defined (empty
    when it uses none), to follow a printed expression.

    >>> helper_definitions(2*sin_n*sin_theta + c)
    ' (c = cos wT, s_theta = sin wT, S_n = sin(n wT))'
    """
    names = {s.name for s in getattr(sp.sympify(expr), "free_symbols", ())}
    used = [f"{name} = {meaning}" for name, meaning in HELPERS.items() if name in names]
    return f" ({', '.join(used)})" if used else ""
