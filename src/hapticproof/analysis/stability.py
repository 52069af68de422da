"""The stability counterpart of a :class:`~hapticproof.systems.scene.Scene`: its exact sampled-data loop.

:class:`SceneLoops` turns a scene (any environment ``H(z)``, per-user couplings ``K_0i``,
``B_ij`` and delays, any teleoperator controller, operator and environment impedances) into
the exact ZOH loops of :mod:`hapticproof.analysis.sampled` for given parameter values; it has the
interface of :class:`hapticproof.analysis.maps.SceneFamily`, so :func:`hapticproof.analysis.maps.find_boundary`
and :func:`~hapticproof.analysis.maps.boundary_curve` compute its stability boundaries (spectral radius
of the exact discretisation, crossings refined and certified on both sides). The device masses
are parameters like any other: ``m`` (or ``m_1``... for m users, ``m_m``/``m_s``).

>>> from hapticproof.systems.scene import Scene
>>> from hapticproof.analysis.maps import find_boundary
>>> loops = SceneLoops(Scene("single-user", params={"m": "0.015", "b": "0.02", "B": 0, "T": "0.001"}))
>>> round(find_boundary(loops, "K").value, 6)                  # the free device: K* = 40.008891
40.008891
"""

from __future__ import annotations

from dataclasses import dataclass, replace
from typing import Any

import sympy as sp

from hapticproof.core.errors import SceneError
from hapticproof.systems.impedance import CLAMPED, DiscreteTF, Impedance, to_fraction
from hapticproof.systems.loops import MultiUser, SingleUser

__all__ = ["SceneLoops"]


def _tf(expr: sp.Expr, variable: sp.Symbol) -> tuple[tuple, tuple]:
    num, den = sp.fraction(sp.cancel(sp.together(expr)))
    pn, pd = sp.Poly(num, variable), sp.Poly(den, variable)
    return tuple(pn.all_coeffs()), tuple(pd.all_coeffs())


@dataclass(frozen=True)
class SceneLoops:
    """Sampled-data loops of a scene at given parameter values (a scene family for the maps)."""

    spec: Any

    @property
    def system(self) -> str:
        return self.spec.system

    @property
    def params(self) -> tuple:
        return tuple((k, v) for k, v in self.spec.params if not isinstance(v, str))

    @property
    def operator(self) -> Any:
        return None if self.spec.operator is None else str(self.spec.operator)

    @property
    def environment(self) -> Any:
        return None if self.spec.environment is None else str(self.spec.environment)

    @property
    def delay(self) -> Any:
        return self.spec.delay if not isinstance(self.spec.delay, tuple) else max(self.spec.delay)

    @property
    def users(self) -> int:
        return self.spec.users or 1

    def values(self, **overrides: Any) -> dict[str, Any]:
        out = dict(self.params)
        out.update(overrides)
        return out

    def _termination(self, value: Any, scene: Any) -> Any:
        if value is None or value == "free":
            return None
        if value == "clamped":
            if self.system != "teleoperator":
                raise SceneError("a clamped termination applies to the teleoperator only")
            return CLAMPED
        expr = value.xreplace(scene._substitution())
        if expr.free_symbols - {sp.Symbol("s")}:
            raise SceneError(f"the impedance {sp.sstr(value)} needs values for "
                             f"{', '.join(sorted(s.name for s in expr.free_symbols if s.name != 's'))}")
        num, den = _tf(expr, sp.Symbol("s"))
        return Impedance(num, den)

    def scene(self, **values: Any) -> Any:
        """The exact sampled-data loop at the scene's values updated with ``values``."""
        exact = {k: sp.Rational(to_fraction(v, k).numerator, to_fraction(v, k).denominator) for k, v in values.items()}
        scene = self.spec.with_params(exact)
        model = scene.build()
        free = getattr(model, "parameters", set())
        free = {s for s in free if s.name != "n"}
        if free:
            raise SceneError(f"the stability boundary needs values for {', '.join(sorted(map(str, free)))}")
        masses = scene._substitution()          # a mass may be an expression of others
        mass = lambda name: masses.get(scene.symbol(name)) if name else None  # noqa: E731
        if self.system == "single-user":
            m_name = scene.role("mass")
            if mass(m_name) is None:
                raise SceneError(f"the stability boundary needs the device mass {m_name} (--param {m_name}=...)")
            num, den = _tf(model.H, sp.Symbol("z"))
            return SingleUser(m=mass(m_name), b=model.b, T=model.T, delay=int(model.delay),
                              operator=self._termination(scene.operator, scene), environment=DiscreteTF(num, den))
        if self.system == "multi-user":
            m = model.users
            group = scene.role("mass")
            masses = tuple(mass(name) if mass(name) is not None else mass(group) for name in scene.members("mass"))
            if None in masses:
                both = f"{group} (or {', '.join(scene.members('mass'))})" if group else ", ".join(scene.members("mass"))
                raise SceneError(f"the stability boundary needs the device masses {both}")
            op = self._termination(scene.operator, scene)
            W = lambda ws: model.weights(ws).tolist()  # noqa: E731
            return MultiUser(masses=masses, dampings=tuple(model.b), T=model.T, ground_stiffness=tuple(model.K0),
                             ground_damping=tuple(model.B0), coupling_stiffness=W(model.K),
                             coupling_damping=W(model.B), delays=tuple(model.delays), operators=(op,) * m)
        if self.system == "teleoperator":
            if model.m_m is None or model.m_s is None:
                raise SceneError(f"the stability boundary needs the masses {scene.role('mass')} (or "
                                 f"{scene.role('master_mass')} and {scene.role('slave_mass')})")
            tele = model.to_sampled(self._termination(scene.operator, scene), self._termination(scene.environment, scene))
            return replace(tele, delay=int(self.spec.delay))
        raise SceneError("stability boundaries apply to single-user, multi-user and teleoperator scenes")

    def printed_values(self, **overrides: Any) -> dict[str, float]:
        """Values for a printed condition (the papers' names), as :class:`~hapticproof.analysis.maps.SceneFamily`."""
        v = {k: float(to_fraction(x)) for k, x in self.values(**overrides).items()}
        # the printed conditions use the papers' names: the roles' parameters by their default names
        from hapticproof.systems.roles import ROLES

        for field, role in ROLES[self.system].items():
            name = self.spec.role(field)
            if name is not None and name != role.default and name in v:
                v[role.default] = v[name]
        if "z_a" not in v:
            scene = self.spec.with_params({k: sp.Rational(to_fraction(x).numerator, to_fraction(x).denominator)
                                           for k, x in overrides.items()})
            term = self._termination(scene.operator, scene) if isinstance(scene.operator, sp.Basic) else None
            v["z_a"] = float(term.shortage_of_passivity()) if isinstance(term, Impedance) else 0.0
        from hapticproof.analysis.maps import with_paper_names  # loaded already: SceneLoops serves maps.find_boundary

        return with_paper_names(v, delay=self.delay, users=self.users, system=self.system)

    def is_paper_scene(self) -> bool:
        """The papers' own scene (virtual wall, or the PD teleoperator): a printed condition applies."""
        if self.system == "single-user":
            return self.spec.environment is None and self.spec.discretize is None
        if self.system == "teleoperator":
            return self.spec.controller in (None, "pd")
        return False
