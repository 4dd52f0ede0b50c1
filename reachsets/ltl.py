"""A small past-time LTL monitor over per-frame predicates, vectorised over objects.

Operators (``phi``, ``psi`` formulas; ``t`` the current frame, ``t-1`` the previous one)::

    Y phi      previously:    phi held at t-1                  (false at the first frame)
    O phi      once:          phi held at some frame <= t      O phi = phi or Y O phi
    H phi      historically:  phi held at every frame <= t     H phi = phi and (first or Y H phi)
    phi S psi  since:         psi held at some k <= t and phi at every frame in (k, t]
                              phi S psi = psi or (phi and Y (phi S psi))

The monitor is incremental: its memory holds, per temporal node and per object id, the one
bit the recurrence needs from the previous frame. Objects seen for the first time start with
the first-frame semantics. ``step`` also takes a batch of consecutive frames at once: each
object's rows over consecutive frames form a chain, and every temporal operator is a scan
along the chains (``since`` keeps the value of the last event, ``Y`` shifts by one row), so
the result equals stepping frame by frame. ``evaluate_trace`` is the slow reference over a
whole trace.
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

#: Up to this many rows of one frame, ``step`` evaluates row by row in plain Python (fewer
#: calls than the chain scans' numpy); the batched frames' tests check both agree.
SCALAR_ROWS_MAX = 16


@dataclass(frozen=True, slots=True)
class _Chains:
    """Rows grouped into chains: one object over consecutive frames (scan order).

    Attributes:
        order: Row positions in scan order (by object, then frame), ``(R,)``.
        start: For each scan position, the scan position where its chain starts, ``(R,)``.
        from_memory: For each scan position, whether its chain starts at the batch's first
            frame (so it continues the memory), ``(R,)``.
        ids: Object id of each scan position.
        last: Rows in the batch's last frame (the ones the memory keeps), ``(L,)``.
    """

    order: NDArray[np.intp]
    start: NDArray[np.intp]
    from_memory: NDArray[np.bool_]
    ids: list[str]
    last: NDArray[np.intp]


def _chains(ids: Sequence[str], frame: NDArray[np.intp], n_frames: int) -> _Chains:
    if n_frames == 1:  # every row is a chain of its own, continuing the memory
        rows = np.arange(len(ids))
        return _Chains(rows, rows, np.ones(len(ids), dtype=bool), [str(i) for i in ids], rows)
    id_arr = np.asarray(ids, dtype=str)
    order = np.lexsort((frame, id_arr)) if len(id_arr) else np.zeros(0, dtype=np.intp)
    sid, sframe = id_arr[order], frame[order]
    pos = np.arange(len(order))
    new = np.ones(len(order), dtype=bool)
    new[1:] = (sid[1:] != sid[:-1]) | (sframe[1:] != sframe[:-1] + 1)
    start = np.maximum.accumulate(np.where(new, pos, 0)) if len(pos) else pos
    return _Chains(
        order=order,
        start=start,
        from_memory=sframe[start] == 0,
        ids=sid.tolist(),
        last=np.flatnonzero(frame == n_frames - 1),
    )


def _initial(
    memory: Mapping[str, Mapping[str, bool]], key: str, ch: _Chains, *, default: bool
) -> NDArray[np.bool_]:
    """The bit before each scan position's chain: remembered, else ``default``."""
    bits = memory.get(key, {})
    first = ch.from_memory & (ch.start == np.arange(len(ch.start)))
    init = np.full(len(ch.start), default)
    for p in np.flatnonzero(first):
        init[p] = bits.get(ch.ids[p], default)
    return init[ch.start]


def _since(
    lhs: NDArray[np.bool_], rhs: NDArray[np.bool_], init: NDArray[np.bool_], ch: _Chains
) -> NDArray[np.bool_]:
    """``v = rhs or (lhs and v_prev)`` along every chain (scan order in and out).

    ``v`` is the value of the chain's last event at or before each position (``rhs`` sets
    it, ``not lhs and not rhs`` clears it), or ``init`` when there is none yet.
    """
    pos = np.arange(len(lhs))
    last = np.maximum.accumulate(np.where(rhs | ~lhs, pos, -1)) if len(pos) else pos
    return np.where(last >= ch.start, rhs[np.maximum(last, 0)], init)


def _step_one_frame(
    formula: Formula,
    atoms: Mapping[str, NDArray[np.bool_]],
    ids: Sequence[str],
    memory: Mapping[str, Mapping[str, bool]],
    prefix: str,
) -> tuple[NDArray[np.bool_], LtlMemory]:
    """``step`` of one frame, row by row with Python bools (each row is its own chain).

    The recurrences at a chain's first position: ``Y a = remembered``, ``a S b = b or (a and
    remembered)``, ``O a = a or remembered``, ``H a = a and remembered`` (remembered: the
    memory's bit of the row's id, else ``False``, ``True`` for ``H``); a later row of the same
    id overwrites the memory, as in ``step``.
    """
    new: LtlMemory = {}
    cols = {k: np.asarray(v, dtype=bool).tolist() for k, v in atoms.items()}

    def ev(f: Formula, path: str, r: int) -> bool:
        key = f"{prefix}{path}"
        if isinstance(f, Atom):
            return bool(cols[f.name][r])
        if isinstance(f, Not):
            return not ev(f.arg, path + ".n", r)
        if isinstance(f, And):
            return all([ev(a, f"{path}.{i}", r) for i, a in enumerate(f.args)])  # noqa: C419
        if isinstance(f, Or):
            return any([ev(a, f"{path}.{i}", r) for i, a in enumerate(f.args)])  # noqa: C419
        bits = memory.get(key, {})
        if isinstance(f, Previously):
            inner = ev(f.arg, path + ".y", r)
            new.setdefault(key, {})[str(ids[r])] = inner
            return bool(bits.get(ids[r], False))
        if isinstance(f, Once):
            value = ev(f.arg, path + ".o", r) or bool(bits.get(ids[r], False))
        elif isinstance(f, Historically):
            value = ev(f.arg, path + ".h", r) and bool(bits.get(ids[r], True))
        else:
            lhs = ev(f.lhs, path + ".l", r)
            rhs = ev(f.rhs, path + ".r", r)
            value = rhs or (lhs and bool(bits.get(ids[r], False)))
        new.setdefault(key, {})[str(ids[r])] = value
        return value

    out = np.array([ev(formula, "@", r) for r in range(len(ids))], dtype=bool)
    return out, new


def step(
    formula: Formula,
    atoms: Mapping[str, NDArray[np.bool_]],
    ids: Sequence[str],
    memory: Mapping[str, Mapping[str, bool]],
    prefix: str = "",
    *,
    frame: NDArray[np.intp] | None = None,
    n_frames: int = 1,
) -> tuple[NDArray[np.bool_], LtlMemory]:
    """Evaluate ``formula`` for every object at one frame or over consecutive frames.

    Args:
        formula: The formula.
        atoms: Predicate name -> ``(R,)`` bools, one row per object and frame.
        ids: Object id of each row, ``R`` of them.
        memory: Memory returned for the frame before the first one (empty at the start).
        prefix: Namespace of this formula's memory keys (one per rule).
        frame: Frame of each row, ``0 .. n_frames - 1`` (``None``: all rows in one frame).
        n_frames: Number of consecutive frames the rows cover.

    Returns:
        ``(R,)`` truth values and the memory after the last frame (only this formula's keys,
        the ids of the last frame). An object missing from a frame is forgotten: it starts
        afresh when it returns, exactly as when the frames are stepped one by one.
    """
    if n_frames == 1 and 0 < len(ids) <= SCALAR_ROWS_MAX:
        return _step_one_frame(formula, atoms, ids, memory, prefix)
    rows = np.zeros(len(ids), dtype=np.intp) if frame is None else np.asarray(frame)
    ch = _chains(ids, rows, n_frames)
    scan = {k: np.asarray(v, dtype=bool)[ch.order] for k, v in atoms.items()}
    new: LtlMemory = {}
    last_ids = [str(ids[r]) for r in ch.last]
    scan_of_last = np.empty(len(ids), dtype=np.intp)
    scan_of_last[ch.order] = np.arange(len(ids))
    at_last = scan_of_last[ch.last]

    def keep(key: str, value: NDArray[np.bool_]) -> None:
        new[key] = dict(zip(last_ids, value[at_last].tolist(), strict=True))

    def ev(f: Formula, path: str) -> NDArray[np.bool_]:
        key = f"{prefix}{path}"
        if isinstance(f, Atom):
            return scan[f.name]
        if isinstance(f, Not):
            return ~ev(f.arg, path + ".n")
        if isinstance(f, And | Or):
            vals = [ev(a, f"{path}.{i}") for i, a in enumerate(f.args)]
            op = np.logical_and if isinstance(f, And) else np.logical_or
            return np.asarray(op.reduce(vals), dtype=bool)
        if isinstance(f, Previously):
            inner = ev(f.arg, path + ".y")
            init = _initial(memory, key, ch, default=False)
            prev = np.concatenate([[False], inner[:-1]])
            keep(key, inner)
            return np.where(ch.start < np.arange(len(inner)), prev, init)
        if isinstance(f, Once):
            inner = ev(f.arg, path + ".o")
            value = _since(np.ones_like(inner), inner, _initial(memory, key, ch, default=False), ch)
        elif isinstance(f, Historically):
            inner = ev(f.arg, path + ".h")
            init = _initial(memory, key, ch, default=True)
            value = ~_since(np.ones_like(inner), ~inner, ~init, ch)
        else:
            lhs = ev(f.lhs, path + ".l")
            rhs = ev(f.rhs, path + ".r")
            value = _since(lhs, rhs, _initial(memory, key, ch, default=False), ch)
        keep(key, value)
        return value

    out = np.empty(len(ids), dtype=bool)
    out[ch.order] = ev(formula, "@")
    return out, new


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
