r"""What a parameter value may be: an exact number, an assumption word, or a rational expression
of declared names -- the same rule for options, scene files, paper files and the Python API.

* **Numbers** are exact from the first moment: ``0.015`` is ``3/200``, a TOML or Python float is
  read by its shortest decimal text, ``1e-3`` is ``1/1000``. ``nan``, infinities (``inf``,
  ``oo``, ``zoo``, a float or decimal that is not finite) are errors, and so is ``pi`` (or
  ``sqrt(2)``): the exact decisions need rational coefficients, so an irrational value is
  refused rather than kept exactly (write the rational you mean).
* **Assumption words** (``positive``, ``nonnegative``, ``real``, ...) keep a parameter symbolic.
* **Expressions** are read by :func:`hapticproof.core.expr.read_expression`; every name in them
  must be declared (:func:`check_declared`): a name the scene's model uses, another parameter
  (with a value or an assumption) or a role's name. An undeclared name is a typo, not a new
  symbol.
* The **period and the masses** (their roles) must be positive when they are numbers
  (:func:`check_positive_roles`), checked once the values are resolved.

>>> param_value("K", "0.5", "")
1/2
>>> param_value("K", "inf", "")
Traceback (most recent call last):
...
hapticproof.core.expr.ExpressionError: K: 'inf' is not a finite number
>>> check_declared({"K": sp.Symbol("Kww")}, {"K", "Kw", "b"}, {"K", "Kw", "b"})
Traceback (most recent call last):
...
hapticproof.core.errors.SceneError: parameter 'K': 'Kww' is not a name of this scene (a value is a number or an expression of declared names: give Kww a value or an assumption, e.g. Kww = positive); did you mean 'Kw'?
"""

from __future__ import annotations

import difflib
import math
from collections.abc import Iterable, Mapping
from decimal import Decimal
from fractions import Fraction
from typing import Any

import sympy as sp

from hapticproof.core.errors import HapticproofError, SceneError

__all__ = ["check_declared", "check_positive_roles", "param_value"]


def param_value(name: str, value: Any, where: str) -> Any:
    """A parameter value, normalised: an exact rational, an assumption word or a rational
    expression of names (which :func:`check_declared` requires to be declared); ``where``
    prefixes the name in errors."""
    from hapticproof.core.expr import (
        ASSUMPTIONS,
        check_rational,
        read_expression,
        read_number,
    )

    label = f"{where}{name}"
    if isinstance(value, bool):
        raise SceneError(f"{label}: {value!r} is not a number, an expression or an assumption")
    if isinstance(value, (int, Fraction)):
        return sp.Rational(value)
    if isinstance(value, float):
        if not math.isfinite(value):
            raise SceneError(f"{label}: {value!r} is not a finite number")
        # a Python float is read by its shortest decimal text: 0.001 is 1/1000, as typed
        return read_number(repr(value), label)
    if isinstance(value, Decimal):
        if not value.is_finite():
            raise SceneError(f"{label}: {value} is not a finite number")
        return read_number(str(value), label)
    if isinstance(value, sp.Basic):
        return check_rational(value, label)
    if isinstance(value, str):
        text = value.strip()
        if text in ASSUMPTIONS:
            return text
        try:
            return read_number(text)
        except (HapticproofError, ValueError, ArithmeticError):     # not a plain number: an expression
            pass
        expr = read_expression(text, None, where=label)
        if expr.is_Symbol:
            close = difflib.get_close_matches(text, list(ASSUMPTIONS), n=1, cutoff=0.75)
            if close:
                raise SceneError(f"{label}: {text!r} is not an assumption; did you mean {close[0]!r}?")
        return expr if not expr.is_Rational else sp.Rational(expr)
    raise SceneError(f"{label}: cannot use {value!r} (a number, an expression or one of "
                     f"{', '.join(ASSUMPTIONS)})")


def check_declared(values: Mapping[str, Any], declared: Iterable[str], suggestions: Iterable[str]) -> None:
    """Every name in an expression value is ``declared``; an undeclared one is an error that
    suggests the closest of ``suggestions`` (the scene's own parameter names)."""
    declared = set(declared)
    for key, value in values.items():
        if not isinstance(value, sp.Basic):
            continue
        for sym in sorted(value.free_symbols, key=str):
            if sym.name in declared:
                continue
            close = difflib.get_close_matches(sym.name, sorted(suggestions), n=1, cutoff=0.6)
            hint = f"; did you mean {close[0]!r}?" if close else ""
            raise SceneError(f"parameter {key!r}: {sym.name!r} is not a name of this scene (a value is a number or an "
                             f"expression of declared names: give {sym.name} a value or an assumption, e.g. "
                             f"{sym.name} = positive){hint}")


def check_positive_roles(scene: Any, mapping: Mapping[sp.Symbol, Any]) -> None:
    """The period and the masses of ``scene`` (a :class:`~hapticproof.systems.scene.Scene`; their
    roles) are positive when ``mapping`` (symbol -> resolved value) makes them numbers."""
    from hapticproof.systems.roles import ROLES

    for field, role in ROLES[scene.system].items():
        if field != "period" and "mass" not in field:
            continue
        names = [scene.role(field)] + (list(scene.members(field)) if role.per_user else [])
        for name in names:
            value = mapping.get(scene.symbol(name)) if name else None
            if value is not None and value.is_number and not value > 0:
                what = role.meaning.replace(" (stability only)", "")
                raise SceneError(f"{what} {name} must be positive, got {sp.sstr(value)}")
