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

__all__ = ["refuse_cycles", "check_declared", "check_positive_roles", "param_value", "check_substituted_size", "refuse_toolkit_names"]


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


def refuse_cycles(params: Mapping[str, Any]) -> None:
    """Parameters defined in terms of each other (``K = "B*2"``, ``B = "K/2"``; ``K = "K/2"``)
    define nothing: one line naming the cycle. Without a cycle, the size of every value once
    substituted is bounded (:func:`check_substituted_size`).

    >>> refuse_cycles({"K": sp.Symbol("B") * 2, "B": sp.Symbol("K") / 2})
    Traceback (most recent call last):
    ...
    hapticproof.core.errors.SceneError: parameters defined in a cycle: B = K/2, K = 2*B (give one of them a value or an assumption)
    """
    defined = {k: v for k, v in params.items() if isinstance(v, sp.Basic) and not v.is_Number}
    uses = {k: sorted(s.name for s in v.free_symbols if s.name in defined) for k, v in defined.items()}
    state: dict[str, int] = {}      # 1: on the path, 2: done

    for root in sorted(uses):
        if state.get(root):
            continue
        path, stack = [root], [iter(uses[root])]
        state[root] = 1
        while stack:
            following = next(stack[-1], None)
            if following is None:
                state[path.pop()] = 2
                stack.pop()
            elif state.get(following) == 1:
                cycle = path[path.index(following):]
                shown = ", ".join(f"{name} = {sp.sstr(defined[name])}" for name in cycle)
                raise SceneError(f"parameters defined in a cycle: {shown} (give one of them a value or an assumption)")
            elif not state.get(following):
                state[following] = 1
                path.append(following)
                stack.append(iter(uses[following]))
    check_substituted_size(params)


def check_substituted_size(params: Mapping[str, Any], where: str = "") -> None:
    """The size of every parameter's value once the values it uses are substituted, bounded
    before anything is substituted: ``K_1 = K_0^10, K_2 = K_1^10, ...`` stays within the digit and
    exponent limits of each line but would build ``10^(10^8)`` (or ``K_0^(10^8)``) after eight
    steps. For each value, an upper bound on the digits of the rational number it becomes and on
    the power of each free name it reaches is propagated through the definitions (a sum adds
    digits, a product adds them, a power ``k`` multiplies them by ``|k|``), and checked against
    :attr:`~hapticproof.core.limits.Limits.digits` and
    :attr:`~hapticproof.core.limits.Limits.exponent`. (No cycle: :func:`refuse_cycles` first.)

    >>> K = [sp.Symbol(f"K_{i}") for i in range(4)]
    >>> check_substituted_size({"K_0": sp.Integer(10), "K_1": K[0]**10, "K_2": K[1]**10})
    >>> check_substituted_size({"K_0": sp.Integer(10), "K_1": K[0]**10, "K_2": K[1]**10, "K_3": K[2]**10})
    Traceback (most recent call last):
    ...
    hapticproof.core.limits.LimitError: parameter K_3: its value after the definitions it uses are substituted has about 1001 digits, above the limit of 1000 digits (raise it with --limit digits=N)
    """
    from hapticproof.core.limits import LimitError, current

    limits = current()
    sizes: dict[str, tuple[float, float]] = {}         # name -> (digits, largest power of a free name)

    def size(expr: Any) -> tuple[float, float]:
        if isinstance(expr, (int, Fraction)) or getattr(expr, "is_Rational", False):
            q = sp.Rational(expr) if not isinstance(expr, sp.Basic) else expr
            largest = max(abs(int(q.p)), abs(int(q.q)))
            return (math.log10(largest) if largest > 1 else 0.0), 0.0
        if isinstance(expr, sp.Symbol):
            return sizes.get(expr.name, (0.0, 1.0))
        if not isinstance(expr, sp.Basic) or not expr.args:
            return 0.0, 0.0
        if isinstance(expr, sp.Pow) and expr.args[1].is_Integer:
            digits, power = size(expr.args[0])
            k = abs(int(expr.args[1]))
            return digits * k, power * k
        parts = [size(arg) for arg in expr.args]
        digits = sum(d for d, _ in parts) + (math.log10(len(parts)) if isinstance(expr, sp.Add) else 0.0)
        power = sum(q for _, q in parts) if isinstance(expr, sp.Mul) else max(q for _, q in parts)
        return digits, power

    defined = {k: v for k, v in params.items() if isinstance(v, sp.Basic)}
    uses = {k: sorted(sym.name for sym in v.free_symbols if sym.name in defined) for k, v in defined.items()}
    done: set[str] = set()
    for root in sorted(defined):                     # the definitions in dependency order (no recursion)
        stack = [(root, iter(uses[root]))]
        while stack:
            name, following = stack[-1]
            nxt = next(following, None)
            if nxt is None:
                stack.pop()
                if name not in done:
                    done.add(name)
                    sizes[name] = size(defined[name])
            elif nxt not in done and all(nxt != n for n, _ in stack):
                stack.append((nxt, iter(uses[nxt])))

    for name, value in params.items():
        if not isinstance(value, sp.Basic) or value.is_Number:
            continue
        digits, power = sizes[name]
        label = f"{where}parameter {name}"
        if digits >= limits.digits:
            raise LimitError(f"{label}: its value after the definitions it uses are substituted has about "
                             f"{min(digits + 1, 1e18):.0f} digits, above the limit of {limits.digits} digits "
                             "(raise it with --limit digits=N)")
        if power > limits.exponent:
            raise LimitError(f"{label}: its value after the definitions it uses are substituted raises a name to the "
                             f"power {min(power, 1e18):.0f}, above the limit of {limits.exponent} "
                             "(raise it with --limit exponent=N)")


def refuse_toolkit_names(scene: Any) -> None:
    """No parameter, role or name in an expression of ``scene`` is one of the toolkit's own
    quantities (``n`` the delay, ``c`` = cos(omega T), ...:
    :data:`hapticproof.core.symbols.TOOLKIT_NAMES`): such a name would silently mean both.

    >>> from hapticproof.systems.scene import Scene
    >>> Scene("single-user", roles={"device_damping": "n"})
    Traceback (most recent call last):
    ...
    hapticproof.core.errors.SceneError: 'n' is the toolkit's own name for the delay n = t_d/T in samples; give your parameter another name (e.g. n_1 or n_v)
    """
    from hapticproof.core.symbols import TOOLKIT_NAMES
    from hapticproof.systems.roles import ROLES, member_names

    used: set[str] = set()
    groups: set[str] = set()    # a non-uniform m-user scene's group names: shorthands for c_1, ..., never symbols
    for field, value in scene.roles:
        if scene.system == "multi-user" and ROLES["multi-user"][field].per_user and not scene.uniform:
            groups |= {value} if isinstance(value, str) else set()
            value = member_names("multi-user", scene.roles, field, scene.users or 1)
        used |= set(value) if isinstance(value, tuple) else {value}
    used |= set(dict(scene.params)) - groups
    values = [scene.environment, scene.controller, scene.operator, *dict(scene.params).values()]
    values += [e for row in scene.matrix or () for e in row] if scene.system == "network" else []
    for value in values:
        if isinstance(value, sp.Basic):
            used |= {sym.name for sym in value.free_symbols}
    clash = sorted(used & set(TOOLKIT_NAMES))
    if clash:
        name = clash[0]
        raise SceneError(f"{name!r} is the toolkit's own name for {TOOLKIT_NAMES[name]}; give your parameter "
                         f"another name (e.g. {name}_1 or {name}_v)")
