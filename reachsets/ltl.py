"""A small past-time LTL monitor over per-frame predicates, vectorised over objects.

Operators (``phi``, ``psi`` formulas; ``t`` the current frame, ``t-1`` the previous one)::

    Y phi      previously:    phi held at t-1                  (false at the first frame)
    O phi      once:          phi held at some frame <= t      O phi = phi or Y O phi
    H phi      historically:  phi held at every frame <= t     H phi = phi and (first or Y H phi)
    phi S psi  since:         psi held at some k <= t and phi at every frame in (k, t]
                              phi S psi = psi or (phi and Y (phi S psi))

The monitor is incremental: its memory holds, per temporal node and per object id, the one
bit the recurrence needs from the previous frame. Objects seen for the first time start with
the first-frame semantics. ``evaluate_trace`` is the slow reference over a whole trace.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np

if TYPE_CHECKING:
    from collections.abc import Mapping, Sequence

    from numpy.typing import NDArray

__all__ = [
    "And",
    "Atom",
    "Formula",
    "Historically",
    "LtlMemory",
    "Not",
    "Once",
    "Or",
    "Previously",
    "Since",
    "evaluate_trace",
    "step",
]

#: Memory: node key -> object id -> bit from the previous frame.
LtlMemory = dict[str, dict[str, bool]]


@dataclass(frozen=True, slots=True)
class Atom:
    """A per-frame predicate looked up by name."""

    name: str


@dataclass(frozen=True, slots=True)
class Not:
    """Negation."""

    arg: Formula


@dataclass(frozen=True, slots=True)
class And:
    """Conjunction of two or more formulas."""

    args: tuple[Formula, ...]


@dataclass(frozen=True, slots=True)
class Or:
    """Disjunction of two or more formulas."""

    args: tuple[Formula, ...]


@dataclass(frozen=True, slots=True)
class Previously:
    """``Y phi``."""

    arg: Formula


@dataclass(frozen=True, slots=True)
class Once:
    """``O phi``."""

    arg: Formula


@dataclass(frozen=True, slots=True)
class Historically:
    """``H phi``."""

    arg: Formula


@dataclass(frozen=True, slots=True)
class Since:
    """``lhs S rhs``."""

    lhs: Formula
    rhs: Formula


Formula = Atom | Not | And | Or | Previously | Once | Historically | Since


def _prev(
    memory: Mapping[str, Mapping[str, bool]], key: str, ids: Sequence[str], *, default: bool
) -> NDArray[np.bool_]:
    """Previous bits of ``key`` for ``ids``; ``default`` for ids not seen before."""
    bits = memory.get(key, {})
    return np.array([bits.get(i, default) for i in ids], dtype=bool).reshape(len(ids))


def step(
    formula: Formula,
    atoms: Mapping[str, NDArray[np.bool_]],
    ids: Sequence[str],
    memory: Mapping[str, Mapping[str, bool]],
    prefix: str = "",
) -> tuple[NDArray[np.bool_], LtlMemory]:
    """Evaluate ``formula`` at the current frame for every object.

    Args:
        formula: The formula.
        atoms: Predicate name -> ``(N,)`` bools for the current frame.
        ids: Object ids, ``N`` of them, aligned with the atom arrays.
        memory: Memory returned by the previous call (empty at the start).
        prefix: Namespace of this formula's memory keys (one per rule).

    Returns:
        ``(N,)`` truth values and the new memory (only this formula's keys, current ids).
    """
    new: LtlMemory = {}

    def ev(f: Formula, path: str) -> NDArray[np.bool_]:
        key = f"{prefix}{path}"
        if isinstance(f, Atom):
            return np.asarray(atoms[f.name], dtype=bool)
        if isinstance(f, Not):
            return ~ev(f.arg, path + ".n")
        if isinstance(f, And | Or):
            vals = [ev(a, f"{path}.{i}") for i, a in enumerate(f.args)]
            op = np.logical_and if isinstance(f, And) else np.logical_or
            return np.asarray(op.reduce(vals), dtype=bool)
        if isinstance(f, Previously):
            inner = ev(f.arg, path + ".y")
            prev = _prev(memory, key, ids, default=False)
            new[key] = dict(zip(ids, inner.tolist(), strict=True))
            return prev
        if isinstance(f, Once):
            inner = ev(f.arg, path + ".o")
            prev = _prev(memory, key, ids, default=False)
            value = inner | prev
        elif isinstance(f, Historically):
            inner = ev(f.arg, path + ".h")
            prev = _prev(memory, key, ids, default=True)
            value = inner & prev
        else:
            lhs = ev(f.lhs, path + ".l")
            rhs = ev(f.rhs, path + ".r")
            prev = _prev(memory, key, ids, default=False)
            value = rhs | (lhs & prev)
        new[key] = dict(zip(ids, value.tolist(), strict=True))
        return value

    return ev(formula, "@"), new


def evaluate_trace(  # noqa: PLR0911 - one return per operator reads best
    formula: Formula, trace: Sequence[Mapping[str, bool]], t: int
) -> bool:
    """Slow reference: the textbook semantics of ``formula`` at position ``t`` of ``trace``."""
    if isinstance(formula, Atom):
        return bool(trace[t][formula.name])
    if isinstance(formula, Not):
        return not evaluate_trace(formula.arg, trace, t)
    if isinstance(formula, And):
        return all(evaluate_trace(a, trace, t) for a in formula.args)
    if isinstance(formula, Or):
        return any(evaluate_trace(a, trace, t) for a in formula.args)
    if isinstance(formula, Previously):
        return t > 0 and evaluate_trace(formula.arg, trace, t - 1)
    if isinstance(formula, Once):
        return any(evaluate_trace(formula.arg, trace, k) for k in range(t + 1))
    if isinstance(formula, Historically):
        return all(evaluate_trace(formula.arg, trace, k) for k in range(t + 1))
    return any(
        evaluate_trace(formula.rhs, trace, k)
        and all(evaluate_trace(formula.lhs, trace, m) for m in range(k + 1, t + 1))
        for k in range(t + 1)
    )
