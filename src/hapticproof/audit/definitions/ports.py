r"""Signals, the linear relations among them, and the port matrices they determine.

Teleoperation papers define their two-ports through signals: a model (``Z_m v_m = f_h - k_f f_e``),
port variables (``f_1 = f_h``, ``v_2 = v_s``), and port descriptions that *define* a matrix by the
relation it states, ``[f_1; f_2] = \mathbf{Z}(s)[v_1; v_2]`` and ``[f_1; v_2] = \mathbf{H}(s)[v_1; f_2]``.
A :class:`SignalSystem` keeps them and answers, exactly:

* :meth:`SignalSystem.matrix` -- the port matrix the model determines (eliminating the other
  signals): what "eliminating variables in the model gives ``\mathbf{Z}(s) = ...``" must equal;
* :meth:`SignalSystem.conversion` -- one port matrix in terms of another's *generic* entries
  (``h_{11} = \det Z / z_{22}``), from the two port relations alone;
* :meth:`SignalSystem.seen_at` -- the immittance seen at a port when another is terminated
  (``f_2 = -Z_e v_2``): the transmitted impedance ``f_1/v_1``.

Every answer is a linear solve over the field of rational functions
(:class:`~hapticproof.exact.rational.RationalFunction`); a system that does not determine the
asked quantity answers ``None`` (never a guess).

>>> import sympy as sp
>>> sys = SignalSystem()
>>> f1, f2, v1, v2, a = sp.symbols("f_1 f_2 v_1 v_2 a")
>>> sys.add_port("Z", ("f_1", "f_2"), ("v_1", "v_2"))
>>> sys.add_port("H", ("f_1", "v_2"), ("v_1", "f_2"))
>>> H = sys.conversion("H", "Z", {"Z": "z"})
>>> sp.simplify(H[0][0].to_sympy() - (sp.Symbol("z_11") - sp.Symbol("z_12")*sp.Symbol("z_21")/sp.Symbol("z_22")))
0
"""

from __future__ import annotations

import re
from collections.abc import Iterable, Mapping
from dataclasses import dataclass, field

from hapticproof.exact.rational import RationalFunction

__all__ = ["PortRelation", "SignalSystem", "entry_name", "two_port_entry", "TWO_PORT_LETTERS"]


#: the letters of the immittance and hybrid parameters of a two-port (``z_{11}``, ``y_{21}``, ``h_{12}``, ``g_{22}``)
TWO_PORT_LETTERS = frozenset("zyhg")


def two_port_entry(name: str, letters: Iterable[str] = TWO_PORT_LETTERS) -> tuple[str, int, int] | None:
    """``(letter, i, j)`` (from 0) of a generic entry's SymPy name (``z_12`` -> ``('z', 0, 1)``)."""
    m = re.fullmatch(r"([a-z])_\{?([1-9])([1-9])\}?", name)
    if not m or m.group(1) not in set(letters):
        return None
    return m.group(1), int(m.group(2)) - 1, int(m.group(3)) - 1


def entry_name(letter: str, i: int, j: int) -> str:
    """The SymPy name of a generic entry (``z_11``) of the matrix whose entries are written ``letter``."""
    return f"{letter}_{i + 1}{j + 1}"


@dataclass(frozen=True)
class PortRelation:
    """``outputs = M inputs`` for the matrix named ``matrix`` (SymPy names of the signals)."""

    matrix: str
    outputs: tuple[str, ...]
    inputs: tuple[str, ...]
    source: str = ""


@dataclass
class SignalSystem:
    """Linear relations among signals (each ``{signal: coefficient}`` summing to zero), port
    relations by matrix name, and terminations (kept apart: they close a port, they are not the model)."""

    relations: list[dict[str, RationalFunction]] = field(default_factory=list)
    terminations: list[dict[str, RationalFunction]] = field(default_factory=list)
    ports: dict[str, PortRelation] = field(default_factory=dict)
    signals: set[str] = field(default_factory=set)

    # -- building ---------------------------------------------------------------------------------

    def add_port(self, matrix: str, outputs: Iterable[str], inputs: Iterable[str], source: str = "") -> None:
        relation = PortRelation(matrix, tuple(outputs), tuple(inputs), source)
        self.ports[matrix] = relation
        self.signals |= set(relation.outputs) | set(relation.inputs)

    def add_relation(self, row: Mapping[str, RationalFunction], termination: bool = False) -> None:
        """One linear relation ``sum coefficient * signal = 0``."""
        row = {k: v for k, v in row.items() if not v.is_zero}
        if not row:
            return
        (self.terminations if termination else self.relations).append(dict(row))
        self.signals |= set(row)

    # -- solving ----------------------------------------------------------------------------------

    @staticmethod
    def _solve(rows: list[dict[str, RationalFunction]], inputs: tuple[str, ...], wanted: tuple[str, ...]
               ) -> list[dict[str, RationalFunction]] | None:
        """Each wanted signal as a combination of the inputs, or ``None`` when the rows do not
        determine it (Gauss-Jordan over the field, the inputs kept free)."""
        signals = sorted({s for r in rows for s in r} | set(wanted))
        unknowns = [s for s in signals if s not in inputs]
        matrix = [dict(r) for r in rows]
        pivots: dict[str, int] = {}
        used_rows: set[int] = set()
        for u in unknowns:
            k = next((k for k, r in enumerate(matrix) if k not in used_rows and u in r and not r[u].is_zero), None)
            if k is None:
                continue
            pivot = matrix[k][u]
            matrix[k] = {s: c / pivot for s, c in matrix[k].items()}
            for m, r in enumerate(matrix):
                if m != k and u in r and not r[u].is_zero:
                    factor = r[u]
                    merged = dict(r)
                    for s, c in matrix[k].items():
                        merged[s] = merged.get(s, RationalFunction.constant(0)) - factor * c
                    matrix[m] = {s: c for s, c in merged.items() if not c.is_zero}
            pivots[u] = k
            used_rows.add(k)
        out = []
        for w in wanted:
            if w in inputs:
                out.append({w: RationalFunction.constant(1)})
                continue
            k = pivots.get(w)
            if k is None:
                return None
            row = matrix[k]
            if any(s != w and s not in inputs for s in row):
                return None                     # depends on a signal the relations leave free
            out.append({s: -c for s, c in row.items() if s in inputs})
        return out

    def _as_matrix(self, port: PortRelation, solved: list[dict[str, RationalFunction]]) -> list[list[RationalFunction]]:
        zero = RationalFunction.constant(0)
        return [[row.get(i, zero) for i in port.inputs] for row in solved]

    def matrix(self, name: str) -> list[list[RationalFunction]] | None:
        """The port matrix ``name`` the model's relations determine (``None``: not determined)."""
        port = self.ports.get(name)
        if port is None or not self.relations:
            return None
        solved = self._solve(self.relations, port.inputs, port.outputs)
        return None if solved is None else self._as_matrix(port, solved)

    def _generic_rows(self, name: str, letter: str) -> list[dict[str, RationalFunction]]:
        port = self.ports[name]
        rows = []
        for i, out in enumerate(port.outputs):
            row = {out: RationalFunction.constant(1)}
            for j, inp in enumerate(port.inputs):
                coefficient = -RationalFunction.variable(entry_name(letter, i, j))
                row[inp] = row.get(inp, RationalFunction.constant(0)) + coefficient
            rows.append(row)
        return rows

    def conversion(self, target: str, source: str, letters: Mapping[str, str]) -> list[list[RationalFunction]] | None:
        """The port matrix ``target`` in the generic entries of ``source`` (``letters[source]``:
        the letter its entries are written with): ``h_{11} = z_{11} - z_{12} z_{21}/z_{22}``."""
        if target not in self.ports or source not in self.ports:
            return None
        rows = self._generic_rows(source, letters[source])
        port = self.ports[target]
        solved = self._solve(rows, port.inputs, port.outputs)
        return None if solved is None else self._as_matrix(port, solved)

    def seen_at(self, port_name: str, matrix: list[list[RationalFunction]] | None = None, letter: str | None = None
                ) -> RationalFunction | None:
        """``output_1 / input_1`` of the port relation ``port_name`` with the other port closed by
        the terminations: from ``matrix`` (its entries) or, with ``letter``, its generic entries."""
        port = self.ports.get(port_name)
        if port is None or not self.terminations:
            return None
        zero = RationalFunction.constant(0)
        rows = []
        for i, out in enumerate(port.outputs):
            row = {out: RationalFunction.constant(1)}
            for j, inp in enumerate(port.inputs):
                entry = matrix[i][j] if matrix is not None else RationalFunction.variable(entry_name(letter, i, j))
                row[inp] = row.get(inp, zero) - entry
            rows.append(row)
        first_in, first_out = port.inputs[0], port.outputs[0]
        solved = self._solve(rows + list(self.terminations), (first_in,), (first_out,))
        if solved is None:
            return None
        return solved[0].get(first_in, zero)
