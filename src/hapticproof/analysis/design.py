r"""The delay margin of a scene, exact: the largest N such that it is passive for every delay n <= N
(the passive range of a parameter is :mod:`hapticproof.analysis.passiverange`).

Delay margin
------------
For a numeric scene with delay ``n`` (the other parameters fixed), the **delay margin** is the
largest ``N`` such that the scene is passive (``G^{-1}`` positive real, the whole decision of
:func:`hapticproof.analysis.positivereal.positive_real` or :func:`hapticproof.analysis.multiuser.positive_real`)
for *every* ``n = 0, 1, ..., N``; ``-1`` when it is not passive even without delay, and
unbounded when it is passive for every ``n``. (Passivity need not be monotone in ``n``; the
margin is the first failure minus one, and the failing ``n`` comes with its certificate.)

Proof (single user). ``G^{-1}_n = a + z^{-n} F(z)`` with ``a = b - z_a`` and ``F = H X_h/V_h``.
When ``F`` has no pole outside the disk and at most a simple pole at ``z = 1`` on the circle,
``F = R/(z-1) + F_0`` with ``R = Res(F, 1)`` and ``F_0`` free of unit-circle poles, and since
``z^{-n}/(z-1) = 1/(z-1) - sum_{k=1}^n z^{-k}``,

.. math:: \Re G^{-1}_n(e^{j\theta}) = a - R\,D_n(\theta) + \Re\big(e^{-jn\theta} F_0\big),
          \qquad D_n = \tfrac12 + \sum_{k=1}^n \cos k\theta \le n + \tfrac12 .

So (``R >= 0``) ``Re G^{-1}_n >= a - R(n + 1/2) - M_0`` with ``M_0 >= max |F_0|`` (a rational
bound certified by one kernel sign decision of ``M_0^2 |Q_0|^2 - |P_0|^2`` on ``[-1, 1]``):
every ``n <= N_low = floor((a - M_0)/R - 1/2)`` is passive, the poles and residues being the
same for every ``n``. At ``c -> 1`` the Hermitian part tends to ``a + F_0(1) - R(n + 1/2)``,
negative from ``n_fail = floor((a + F_0(1))/R - 1/2) + 1`` on. Each ``n`` between is decided
exactly, one by one; the first failure is the margin plus one. Without such a structure (other
unit-circle poles, m users) every ``n`` from 0 is decided (m users: an upper end from the
constant matrix at ``c = 1``), up to ``max_delay``.

>>> from hapticproof.systems.scene import Scene
>>> wall = Scene("single-user", params={"b": "0.02", "B": "0.001", "T": "0.001", "K": 2})
>>> delay_margin(wall).margin          # b - K T (n + 1/2) + B >= 0 at c = 1
10
"""

from __future__ import annotations

import math
import time
from dataclasses import dataclass, field, replace
from fractions import Fraction
from typing import Any

import flint
import sympy as sp

from hapticproof.core.naming import DEFAULT
from hapticproof.core.notation import shorten_numbers
from hapticproof.core.errors import SceneError
from hapticproof.core.evidence import Decision, Evidence, Method, Outcome, to_jsonable
from hapticproof.exact.realroots import as_fmpq, flint_precision, minimise_rational, to_rational

__all__ = ["DelayMargin", "delay_margin"]


def scene_model(scene: Any) -> Any:
    """The analysis model of a :class:`~hapticproof.systems.scene.Scene` (a model is returned as it is)."""
    from hapticproof.systems.scene import Scene

    return scene.build() if isinstance(scene, Scene) else scene


@dataclass(frozen=True, slots=True)
class DelayMargin:
    """The delay margin of a scene (see the module docstring for the definition and proof).

    ``margin`` is ``N`` (``-1``: not passive at ``n = 0``; ``None``: unbounded, or not
    settled when ``decision`` is ``undecided``); ``lower``/``upper`` bound it when not settled;
    ``proved_up_to`` is ``N_low`` of the bound (every ``n`` up to it passive without a decision
    of its own); ``decided`` lists the ``n`` decided one by one; ``failing`` is the whole
    decision at ``N + 1``.
    """

    decision: Decision
    margin: int | None
    T: Any
    method: str
    reason: str
    lower: int | None = None
    upper: int | None = None
    proved_up_to: int | None = None
    decided: tuple[int, ...] = ()
    failing: Outcome | None = None
    proof: dict = field(default_factory=dict)
    seconds: float = 0.0
    #: the scene's names (:class:`~hapticproof.core.naming.Naming`) the texts speak
    names: Any = field(default=DEFAULT, repr=False, compare=False)

    @property
    def unbounded(self) -> bool:
        return self.decision == Decision.PROVED and self.margin is None

    def time_margin(self) -> Any:
        """``t_d,max = N T`` (``None`` when unbounded or not settled)."""
        if self.margin is None or self.margin < 0 or self.T is None:
            return None
        return self.margin * self.T

    def to_json(self) -> dict[str, Any]:
        out = {"decision": self.decision.value, "margin": self.margin, "unbounded": self.unbounded,
               "t_d_max": self.time_margin(), "method": self.method, "reason": self.reason,
               "lower": self.lower, "upper": self.upper, "proved_up_to": self.proved_up_to,
               "decided": list(self.decided), "proof": self.proof, "seconds": round(self.seconds, 4)}
        if self.failing is not None:
            out["failing"] = _outcome_summary(self.failing)
        return to_jsonable(out)

    def to_text(self) -> str:
        if self.decision != Decision.PROVED:
            head = f"delay margin: undecided ({self.reason})"
        elif self.margin is None:
            head = "delay margin: unbounded (passive for every delay n)"
        elif self.margin < 0:
            head = "delay margin: none (not passive even without delay)"
        else:
            t = self.time_margin()
            head = f"delay margin: {self.names.helper('margin')} = {self.margin}" + (f" (t_d <= {t})" if t is not None else "") + \
                f": passive for every n <= {self.margin}, not at n = {self.margin + 1}"
        lines = [head, f"  how: {self.reason}" if self.decision == Decision.PROVED else ""]
        where = self._where() if self.decision == Decision.PROVED and self.proof and "M_0" in self.reason else None
        if where:
            lines.append(f"  where {where}")
        if self.failing is not None:
            lines.append(f"  at n = {self.margin + 1 if self.margin is not None else '?'}: {_short(self.failing.reason)}")
        return "\n".join(line for line in lines if line)


    def _where(self) -> str | None:
        """The bound's quantities of a single user defined, with their values: ``G^-1 = a + z^-n F(z)``,
        ``a = b - z_a``, ``R = Res(F, 1)``, ``F_0 = F - R/(z - 1)`` and ``M_0 >= max|F_0|`` on the
        circle (``None`` when the proof does not give them all: the modes of m users)."""
        f = _formula_names(self.names)
        value = {key.split(" ")[0]: v for key, v in self.proof.items() if not isinstance(v, dict)}
        a, R, M0 = (value.get(k) for k in (f["a"], f["R"], "M_0"))
        if a is None or R is None or M0 is None:
            return None
        excess = next(k for k in self.proof if k.startswith(f"{f['a']} = "))
        return (f"G^-1 = {f['a']} + z^-n {f['F']}(z), {excess} = {a}, {f['R']} = Res({f['F']}, 1) = {R}, "
                f"{f['F_0']} = {f['F']} - {f['R']}/(z - 1), M_0 = {M0} >= max|{f['F_0']}| on |z| = 1")


def _short(text: str, limit: int = 240) -> str:
    """A reason with its exact numbers abbreviated when they are huge (the full data is in JSON)."""
    return shorten_numbers(text)


def _outcome_summary(out: Outcome) -> dict[str, Any]:
    """The decision at the failing delay: its reason and witness (no certificate: at long delays its
    numbers have thousands of digits; re-derive that one delay for it)."""
    witness = {}
    for key, value in (out.witness or {}).items():
        text = str(value) if not isinstance(value, sp.Rational) or len(str(value.q)) < 4000 else "<large>"
        witness[key] = text
    return {"decision": out.decision.value, "reason": _short(out.reason), "witness": witness}


def _flint_poly(poly: sp.Poly) -> flint.fmpq_poly:
    return flint.fmpq_poly([as_fmpq(poly.domain.to_sympy(a)) for a in poly.all_coeffs()[::-1]])


def _numeric(model: Any) -> Any:
    """The single-user model at delay 0 as a :class:`~hapticproof.analysis.fastpath.NumericScene`:
    every delay of the search is then decided on the fast path, without SymPy."""
    from hapticproof.analysis.fastpath import NumericScene

    return NumericScene.from_scene(replace(model, delay=sp.Integer(0)))


def _single_user_parts(ns: Any) -> tuple[flint.fmpq_poly, flint.fmpq_poly, flint.fmpq]:
    from hapticproof.analysis.fastpath import path_polynomials

    P, Q = path_polynomials(ns)
    return P, Q, flint.fmpq(ns.b.numerator, ns.b.denominator) - flint.fmpq(ns.z_a.numerator, ns.z_a.denominator)


def _symmetric_c(p: flint.fmpq_poly, q: flint.fmpq_poly) -> flint.fmpq_poly:
    """``Re(P(z) Q(1/z))`` on the circle as a polynomial in ``c``."""
    from hapticproof.exact.unitcircle import fast_cross, symmetric_to_c

    cross = fast_cross(p.coeffs(), q.coeffs()) if not p.is_zero() else {}
    return symmetric_to_c(cross, flint.fmpq(0), flint.fmpq_poly([0, 1]), flint.fmpq_poly([1]), +1)


def _upper_rational(ball: flint.arb) -> flint.fmpq:
    man, exp = ball.upper().man_exp()
    value = flint.fmpq(int(man)) * (flint.fmpq(2) ** int(exp) if exp >= 0 else flint.fmpq(1, 2 ** int(-exp)))
    # a simpler rational just above (short certificates)
    frac = Fraction(int(value.p), int(value.q))
    step = Fraction(1, 10**12)
    simple = Fraction(math.ceil(frac / step)) * step
    return flint.fmpq(simple.numerator, simple.denominator)


def _bound_route(ns: Any) -> dict[str, Any] | None:
    """``a, R, M_0, F_0(1)`` and the certificates of the bound, or ``None`` when ``F`` has
    another unit-circle pole, a pole outside, or a double pole at ``z = 1``."""
    from hapticproof.exact.kernel import decide_rational_sign, locate_roots

    P, Q, a = _single_user_parts(ns)
    if Q.degree() <= 0:
        P0, Q0, R = P, Q, flint.fmpq(0)
    else:
        roots = locate_roots(Q, "disk")
        if roots.outside or any(r.value != 1 or r.multiplicity != 1 for r in roots.boundary):
            return None
        one = flint.fmpq_poly([-1, 1])
        if roots.boundary:
            Q1 = Q / one
            R = P(1) / Q1(1)
            P0 = (P - R * Q1)
            P0, rem = divmod(P0, one)
            if not rem.is_zero():  # pragma: no cover - R is the residue
                raise ArithmeticError("residue subtraction left a remainder")
            Q0 = Q1
        else:
            P0, Q0, R = P, Q, flint.fmpq(0)
    num, den = _symmetric_c(P0, P0), _symmetric_c(Q0, Q0)
    if num.is_zero():
        M0 = flint.fmpq(0)
        cert = None
    else:
        worst = minimise_rational(-num, den, -1, 1)
        with flint_precision(128):
            M0 = _upper_rational((-worst.value).sqrt() if not (-worst.value) < 0 else flint.arb(0))
        cert = decide_rational_sign(M0 * M0 * den - num, den, -1, 1, "c", "M_0^2 |Q_0|^2 - |P_0|^2")
        if cert.decision != Decision.PROVED:  # pragma: no cover - M_0 is above the certified maximum
            return None
    F0_at_1 = P0(1) / Q0(1)
    return {"a": a, "R": R, "M0": M0, "F0_1": F0_at_1, "certificate": cert}


def _decide_single(ns: Any, n: int, names: Any = DEFAULT) -> Outcome:
    """The whole decision at delay ``n`` (:func:`hapticproof.analysis.fastpath.decide`, the numeric
    route of :func:`hapticproof.analysis.positivereal.positive_real`), its reason in the scene's
    naming (numbers and the toolkit's words only)."""
    from hapticproof.analysis.fastpath import decide

    out = decide(replace(ns, delay=n), minimum=False)
    if names.is_default:
        return out
    return Outcome(out.decision, out.evidence, names.words(out.reason), minimiser=out.minimiser, minimum=out.minimum)


def _path_name(names: Any) -> str:
    """The name of ``F = z^n (G^-1 - a)`` in the bound's proof: ``F`` unless the scene uses it
    (a stiffness called F), then ``Psi`` or ``F_p`` (only this proof writes it: no helper of every report)."""
    from hapticproof.core.naming import clashes

    taken = set(getattr(names, "taken", ())) | {name for key, name in getattr(names, "helpers", ()) if key != "rest"}
    return next((c for c in ("F", "Psi", "F_p") if not any(clashes(c, u) for u in taken)), "F_path")


def _formula_names(names: Any) -> dict[str, str]:
    """The toolkit's symbols of the bound's proof in the scene's naming: ``a = b - z_a``, ``R``,
    ``F_0``, ``c``, ``w``, the period, ``M``, ``lambda``."""
    return {"a": names.helper("excess"), "b": names.role("device_damping", "b"), "R": names.helper("residue"),
            "F_0": names.helper("rest"),
            "F": _path_name(names),
            # the rest of F after its pole at 1 is F_0; when F is the user's, it follows its path's name
            **({"F_0": f"{_path_name(names)}_0"} if _path_name(names) != "F" and names.helper("rest") == "F_0" else {}),
            "c": names.helper("cos"), "w": names.w, "T": names.period,
            "M": names.helper("matrix"), "lambda": names.helper("eigenvalue")}


#: A delay-margin search stops after this many seconds unless told otherwise; it then ends
#: ``undecided`` and says which delays it decided.
DEADLINE = 60.0


def delay_margin(scene: Any, max_delay: int = 2000, *, deadline: float | None = DEADLINE,
                 progress: Any = None) -> DelayMargin:
    """The delay margin of a numeric single- or multi-user scene (exact; see the module
    docstring). ``max_delay`` caps the one-by-one search when no bound ends it; ``deadline``
    (seconds, ``None``: none) bounds its time -- past it the answer is ``undecided`` with the delays
    decided so far; ``progress(done, total)`` is called as the search goes (a progress bar).
    Uniform m-user scenes are searched on their two extreme modes (:mod:`hapticproof.analysis.modes`).

    >>> from hapticproof.systems.scene import Scene
    >>> dm = delay_margin(Scene("single-user", params={"b": "0.02", "K": 2, "B": 0, "T": "0.001"}))
    >>> dm.margin, dm.method                  # b >= K T (n + 1/2): n <= 9.5
    (9, 'bound+exact')
    """
    from hapticproof.systems.multiuser import MultiUserScene
    from hapticproof.systems.singleuser import SingleUserScene

    start = time.perf_counter()
    model = scene_model(scene)
    clock = _Clock(start, deadline, progress)
    if isinstance(model, MultiUserScene):
        return replace(_multi_margin(model, max_delay, clock), names=model.naming())
    if not isinstance(model, SingleUserScene):
        raise SceneError("the delay margin applies to single- and multi-user scenes (the teleoperator bound (32) "
                         "has no delay)")
    free = model.parameters - ({model.delay} if model.delay.is_Symbol else set())
    if free:
        raise SceneError(f"the delay margin needs numbers for {', '.join(sorted(map(str, free)))}")
    return _single_margin(_numeric(model), max_delay, clock, model.naming())


@dataclass
class _Clock:
    """The search's start, deadline and progress callback (throttled to a few calls a second)."""

    start: float
    deadline: float | None
    progress: Any = None
    last: float = 0.0

    def expired(self, next_cost: float = 0.0) -> bool:
        """Past the deadline, or past it by the time the next step (as long as the last) ends."""
        return self.deadline is not None and time.perf_counter() - self.start + next_cost > self.deadline

    def tick(self, done: int, total: int, force: bool = False) -> None:
        now = time.perf_counter()
        if self.progress is not None and (force or now - self.last > 0.2):
            self.last = now
            self.progress(done, max(total, done, 1))

    def elapsed(self) -> float:
        return time.perf_counter() - self.start


def _single_margin(ns: Any, max_delay: int, clock: _Clock, names: Any = DEFAULT) -> DelayMargin:
    return replace(_single_margin_of(ns, max_delay, clock, names), names=names)


def _single_margin_of(ns: Any, max_delay: int, clock: _Clock, names: Any) -> DelayMargin:
    T = _rational(ns.T)
    route = _bound_route(ns)
    decided: list[int] = []
    decide = lambda n: _decide_single(ns, n, names)  # noqa: E731
    f = _formula_names(names)
    if route is None:
        return _scan(decide, 0, None, max_delay, T, "exact", clock, {}, None, names=names)
    a, R, M0, F01 = route["a"], route["R"], route["M0"], route["F0_1"]
    excess = f"{f['a']} = {f['b']}" + (" - z_a" if ns.z_a != 0 else "")      # (no z_a in a passive operator's scene)
    proof = {excess: to_rational(a), f"{f['R']} = Res({f['F']}, 1)": to_rational(R),
             f"M_0 >= max|{f['F_0']}|": to_rational(M0), f"{f['F_0']}(1)": to_rational(F01)}
    if route["certificate"] is not None:
        cert = route["certificate"]
        proof["M_0 certificate"] = {**cert.to_json(), "reason": names.words(cert.reason)}
    if R < 0:
        out = decide(0)
        return DelayMargin(Decision.PROVED, -1, T, "exact", "the residue at z = 1 is negative for every delay",
                           decided=(0,), failing=out, proof=proof, seconds=clock.elapsed())
    if R == 0:
        if a >= M0:
            first = decide(0)
            if first.decision == Decision.PROVED:
                return DelayMargin(Decision.PROVED, None, T, "bound", f"Re G^-1 >= {f['a']} - max|{f['F']}| >= 0 for every n "
                                   "(no pole on the circle)", decided=(0,), proof=proof, seconds=clock.elapsed())
        return _scan(decide, 0, None, max_delay, T, "exact", clock, proof, None, names=names)
    low = math.floor(to_rational((a - M0) / R - flint.fmpq(1, 2)))
    fail = math.floor(to_rational((a + F01) / R - flint.fmpq(1, 2))) + 1
    low = max(low, -1)
    fail = max(fail, 0)
    proof.update({"N_low": low, "n_fail": fail})
    if low >= 0:
        first = decide(0)       # the poles and residues, once (the same for every n)
        decided.append(0)
        if first.decision != Decision.PROVED:
            return DelayMargin(Decision.PROVED, -1, T, "exact", "not passive without delay", decided=(0,),
                               failing=first, proof=proof, seconds=clock.elapsed())
    limit = to_rational(a + F01 - R * (fail + flint.fmpq(1, 2)))
    if fail - low > 1 and low + 1 > max_delay:
        # the bound proves every n <= low and disproves n = fail, and the delays between are beyond
        # what one-by-one exact decisions reach (a degree-n polynomial each): say so
        return DelayMargin(Decision.UNDECIDED, None, T, "bound", f"passive for every n <= {low} (bound Re G^-1 >= {f['a']} - "
                           f"{f['R']}(n + 1/2) - M_0 >= 0), not passive from n = {fail} on; the {fail - low - 1} delays between "
                           f"are beyond --max-delay {max_delay}", lower=low, upper=fail - 1, proved_up_to=low,
                           decided=tuple(decided), proof=proof, seconds=clock.elapsed())
    at_fail = Outcome(Decision.DISPROVED,
                      Evidence(Method.ENDPOINT_ANALYSIS, witness=names.witness({"c": "-> 1", "limit": limit}),
                               facts={"limit": f"{f['a']} + {f['F_0']}(1) - {f['R']}(n + 1/2) at n = {fail}"}),
                      f"Re G^-1 -> {f['a']} + {f['F_0']}(1) - {f['R']}(n + 1/2) = {limit} < 0 as {f['c']} -> 1 "
                      f"({f['w']} -> 0) at n = {fail}")
    return _scan(lambda n: at_fail if n == fail else decide(n), low + 1, fail, max_delay, T,
                 "bound+exact", clock, proof, low if low >= 0 else None, decided, names=names)


def _rational(value: Any) -> sp.Rational:
    return sp.Rational(value.numerator, value.denominator) if isinstance(value, Fraction) else sp.Rational(value)


def _scan(decide, first: int, last: int | None, max_delay: int, T: Any, method: str, clock: _Clock,
          proof: dict, proved_up_to: int | None, decided: list[int] | None = None, names: Any = DEFAULT) -> DelayMargin:
    decided = list(decided or [])
    stop = last if last is not None else max_delay
    stop = min(stop, max(first, 0) + max_delay) if last is not None else stop
    f = _formula_names(names)
    how = (f"every n <= {proved_up_to} by the bound Re G^-1 >= {f['a']} - {f['R']}(n + 1/2) - M_0 >= 0; "
           if proved_up_to is not None else "")
    total = stop - first + 1
    cost = 0.0
    for n in range(first, stop + 1):
        if clock.expired(cost):
            clock.tick(n - first, total, force=True)
            covered = ("no further delay decided" if n == first else f"n = {first} decided exactly, passive" if n == first + 1
                       else f"n = {first}..{n - 1} decided exactly, each passive")
            return DelayMargin(Decision.UNDECIDED, None, T, method,
                               f"deadline of {clock.deadline:g} s reached: {how}{covered}; not decided beyond n = {n - 1}"
                               + (f" (not passive from n = {last} on)" if last is not None else ""),
                               lower=n - 1, upper=None if last is None else last - 1, proved_up_to=proved_up_to,
                               decided=tuple(decided), proof=proof, seconds=clock.elapsed())
        began = time.perf_counter()
        out = decide(n)
        cost = time.perf_counter() - began
        decided.append(n)
        clock.tick(n - first + 1, total)
        if out.decision == Decision.PROVED:
            continue
        clock.tick(total, total, force=True)
        if out.decision == Decision.DISPROVED:
            reason = how + (f"n = {first}..{n - 1} decided exactly, n = {n} disproved" if n > first
                            else f"n = {n} disproved")
            return DelayMargin(Decision.PROVED, n - 1, T, method, reason, lower=n - 1, upper=n - 1,
                               proved_up_to=proved_up_to, decided=tuple(decided), failing=out, proof=proof,
                               seconds=clock.elapsed())
        return DelayMargin(Decision.UNDECIDED, None, T, method, f"the decision at n = {n} is {out.decision.value}: "
                           f"{out.reason}", lower=n - 1, upper=last, proved_up_to=proved_up_to,
                           decided=tuple(decided), proof=proof, seconds=clock.elapsed())
    clock.tick(total, total, force=True)
    return DelayMargin(Decision.UNDECIDED, None, T, method,
                       f"passive for every n <= {stop} (searched up to --max-delay {max_delay})" +
                       (f"; not passive from n = {last} on" if last is not None else "; no bound ends the search"),
                       lower=stop, upper=None if last is None else last - 1, proved_up_to=proved_up_to,
                       decided=tuple(decided), proof=proof, seconds=clock.elapsed())


def _multi_margin(model: Any, max_delay: int, clock: _Clock) -> DelayMargin:
    from hapticproof.analysis.multiuser import by_modes, positive_real
    from hapticproof.exact.charpoly import is_psd

    if model.parameters:
        raise SceneError(f"the delay margin needs numbers for {', '.join(sorted(map(str, model.parameters)))}")
    if len(set(model.delays)) > 1:
        raise SceneError("the delay margin asks for one common delay n; this scene has per-user delays")
    m = model.users
    names = model.naming()
    f = _formula_names(names)
    if by_modes(model):
        return _modes_margin(model, max_delay, clock)
    base = replace(model, delays=(0,) * m)
    from hapticproof.systems.multiuser import inverse_transfer_matrix
    from hapticproof.core.symbols import z as Z

    G0 = inverse_transfer_matrix(base)
    D = sp.diag(*[bi - zi for bi, zi in zip(model.b, model.z_a)])
    F = (G0 - D).applyfunc(sp.cancel)
    R = F.applyfunc(lambda e: sp.cancel((Z - 1) * e).subs(Z, 1))
    F01 = F.applyfunc(lambda e: sp.diff(sp.cancel((Z - 1) * e), Z).subs(Z, 1))
    last = None
    if is_psd(R).holds and R != sp.zeros(m, m):
        # D + F0(1) - (n + 1/2) R decreases in the Loewner order: its first non-PSD n is an upper end
        mat = lambda n: D + F01 - (n + sp.Rational(1, 2)) * R  # noqa: E731
        hi = 1
        while hi < 10**7 and is_psd(mat(hi)).holds:
            hi *= 2
        if hi < 10**7:
            lo = 0
            while lo < hi:
                mid = (lo + hi) // 2
                if is_psd(mat(mid)).holds:
                    lo = mid + 1
                else:
                    hi = mid
            last = lo
    proof = ({"upper": f"{f['M']}(1)/2 -> D + {f['F_0']}(1) - (n + 1/2) {f['T']} Kmat is not PSD from n = {last} on"}
             if last is not None else {})
    decide = lambda n: positive_real(replace(model, delays=(n,) * m))  # noqa: E731
    return _scan(decide, 0, last, max_delay, model.T, "exact", clock, proof, None, names=names)


def _modes_margin(model: Any, max_delay: int, clock: _Clock) -> DelayMargin:
    """A uniform scene's margin from its modes: for each delay the passive ``lambda`` form an interval
    containing 0 (:mod:`hapticproof.analysis.modes`), so the margin is ``min(N(0), N(lambda_max))``;
    an irrational ``lambda_max`` is bracketed, ``N(hi) <= N(lambda_max) <= N(lo)``."""
    from hapticproof.analysis.modes import largest_eigenvalue, mode_wall

    names = model.naming()
    lam = names.helper("eigenvalue")
    top = largest_eigenvalue(model)
    zero = _single_margin(mode_wall(model, 0), max_delay, clock, names)
    if top == 0:
        return replace(zero, method="modes: " + zero.method, seconds=clock.elapsed())
    if top.is_Rational:
        ends = [Fraction(int(top.p), int(top.q))] * 2
    else:
        mid = Fraction(str(sp.N(top, 40)))
        ends = [mid - Fraction(1, 2**100), mid + Fraction(1, 2**100)]
    margins = [_single_margin(mode_wall(model, end), max_delay, clock, names) for end in dict.fromkeys(ends)]
    margins = [zero] + (margins if len(margins) == 2 else margins * 2)
    value = lambda dm: math.inf if dm.unbounded else dm.margin  # noqa: E731
    if all(dm.decision == Decision.PROVED for dm in margins):
        lo_bound, hi_bound = min(value(margins[0]), value(margins[2])), min(value(margins[0]), value(margins[1]))
        if lo_bound == hi_bound:
            winner = min(margins, key=value)
            n = None if lo_bound == math.inf else int(lo_bound)
            reason = (f"uniform couplings: the modes {lam} = 0 and {lam}_max = {sp.sstr(top)} decide every delay; "
                      f"their margins {', '.join(str(dm.margin) for dm in margins[:2 if top.is_Rational else 3])}: "
                      + winner.reason)
            return DelayMargin(Decision.PROVED, n, model.T, "modes: " + winner.method, reason, lower=n, upper=n,
                               proved_up_to=winner.proved_up_to, decided=winner.decided, failing=winner.failing,
                               proof={"modes": [dm.to_json() for dm in margins]}, seconds=clock.elapsed())
    lowers = [dm.lower if dm.decision != Decision.PROVED else dm.margin for dm in margins]
    return DelayMargin(Decision.UNDECIDED, None, model.T, "modes",
                       "the modes' margins do not settle it: " + ("; ".join(dm.reason for dm in margins if dm.decision != Decision.PROVED)
                                                                  or f"{lam}_max = {sp.sstr(top)} is bracketed too widely"),
                       lower=min((v for v in lowers if v is not None), default=None),
                       proof={"modes": [dm.to_json() for dm in margins]}, seconds=clock.elapsed())
