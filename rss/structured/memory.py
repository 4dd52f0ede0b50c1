"""Per-constellation memory: "the last state before the danger threshold" (RSS def. 10).

ad-rss keeps this inside its checker objects and requires a strictly increasing time
index. Here the memory is an explicit immutable value: :func:`apply_memory` takes the
memory before the first frame of a batch and returns the memory after its last frame, so a
replay can start at any frame (with :meth:`RssMemory.empty`) or restart from any stored
memory. A batch may hold ``F`` consecutive frames; the memory is then carried through them
with a vectorised forward fill instead of a Python loop over frames.

Keys are ``(ego id, object id, constellation type)``, like ad-rss' constellation-id
provider. A key absent from a frame loses its memory (ad-rss forgets ids not seen in the
previous step); an *invalid* constellation keeps its previous entry.

What is remembered (non-intersection): ``{lon_safe, lat_safe}`` of the last non-dangerous
frame. A pair that is dangerous without memory is remembered as ad-rss assumes it: "both
were safe" (keep all responses), or, for a same-direction pair already overlapping
laterally, "longitudinally safe" (no lateral response). Intersection: which check
made the pair safe the last time it was safe.
"""

from __future__ import annotations

import dataclasses
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

import numpy as np

from rss.model import ConstellationType
from rss.structured.checks import IntersectionState, LateralSide, RawStates
from rss.structured.states import (
    LateralPosition,
    LateralResponse,
    LongitudinalPosition,
    LongitudinalResponse,
)

if TYPE_CHECKING:
    from rss.arrays import BoolArray, IntArray
    from rss.structured.batch import ConstellationBatch
    from rss.structured.extraction import Relative

__all__ = ["RssMemory", "apply_memory", "apply_memory_both", "is_dangerous"]

_OBJECT_PRIO = int(ConstellationType.IntersectionObjectHasPriority)
_NO_STATE = IntersectionState.NONE


@dataclass(frozen=True)
class RssMemory:
    """Remembered safe states of ``M`` constellations.

    Attributes:
        ego_id: ``(M,)`` key part.
        object_id: ``(M,)`` key part.
        constellation_type: ``(M,)`` key part.
        lon_safe: ``(M,)`` non-intersection: remembered longitudinal verdict.
        lat_safe: ``(M,)`` non-intersection: remembered lateral verdict.
        intersection_state: ``(M,)`` intersection: :class:`IntersectionState`.
    """

    ego_id: IntArray
    object_id: IntArray
    constellation_type: IntArray
    lon_safe: BoolArray
    lat_safe: BoolArray
    intersection_state: IntArray

    @classmethod
    def empty(cls) -> RssMemory:
        """Memory of a fresh start (no history)."""
        i = np.zeros(0, dtype=np.int64)
        b = np.zeros(0, dtype=np.bool_)
        return cls(i, i, i, b, b, i)

    @property
    def size(self) -> int:
        """Number of remembered constellations ``M``."""
        return int(self.object_id.shape[0])


def is_dangerous(states: RawStates) -> BoolArray:
    """ad-rss ``isDangerous``: longitudinally unsafe and laterally unsafe (``(C,)``)."""
    lateral_safe = states.left.is_safe & states.right.is_safe
    return np.asarray(~states.lon_is_safe & ~lateral_safe, dtype=np.bool_)


def _side(side: LateralSide, clear: BoolArray) -> LateralSide:
    return dataclasses.replace(side, response=np.where(clear, LateralResponse.None_, side.response))


@dataclass(frozen=True)
class _Runs:
    """Constellations sorted by (key, frame) and cut into runs of consecutive frames."""

    order: IntArray  # (C,) sorted position -> row
    start: IntArray  # (C,) sorted position of the run start
    initial: IntArray  # (C,) memory row valid at the run start, -1 if none


def _runs(memory: RssMemory, batch: ConstellationBatch, frame: IntArray) -> _Runs:
    """Sort by (key, frame) with the memory rows as pseudo-frame -1 in front of their key."""
    m, c = memory.size, batch.size
    ego, other = batch.ego.object_id, batch.other.object_id
    ctype, when = batch.constellation_type, frame
    if m:
        ego = np.concatenate([memory.ego_id, ego])
        other = np.concatenate([memory.object_id, other])
        ctype = np.concatenate([memory.constellation_type, ctype])
        when = np.concatenate([np.full(m, -1, dtype=np.int64), when])
    order_all = np.lexsort((when, ctype, other, ego))
    same_key = np.ones(order_all.size, dtype=np.bool_)
    same_key[:1] = False
    for part in (ego, other, ctype):  # each key part gathered once in sorted order
        ordered = part.take(order_all)
        same_key[1:] &= ordered[1:] == ordered[:-1]
    prev_row = np.concatenate([[-1], order_all[:-1]])
    is_batch = order_all >= m
    # the memory row directly before a key's frame-0 row is its initial memory
    initial_all = np.full(order_all.size, -1, dtype=np.int64)
    if m:
        initial_all = np.where(
            same_key & (prev_row < m) & (prev_row >= 0) & (when[order_all] == 0), prev_row, -1
        )
    order = order_all[is_batch] - m
    initial_sorted = initial_all[is_batch]
    f = frame[order]
    # a key's first constellation follows another key or the key's own memory row
    key_start = (~same_key | (prev_row < m))[is_batch]
    new_run = np.ones(c, dtype=np.bool_)
    new_run[1:] = key_start[1:] | (f[1:] - f[:-1] > 1)
    if c:
        new_run[0] = True
    pos = np.arange(c)
    start = np.maximum.accumulate(np.where(new_run, pos, 0)) if c else pos
    initial = np.where(f[start] == 0, initial_sorted[start], -1) if c else pos
    return _Runs(order, start, initial)


def _previous(store: BoolArray, runs: _Runs) -> IntArray:
    """For every sorted position: last earlier position of its run that stored, else -1."""
    pos = np.arange(store.size)
    last = np.maximum.accumulate(np.where(store, pos, -1))
    prev = np.full(store.size, -1, dtype=np.int64)
    prev[1:] = last[:-1]
    return np.where(prev >= runs.start, prev, -1)


def apply_memory(  # noqa: PLR0917  (structure-of-arrays engine step)
    batch: ConstellationBatch,
    rel: Relative,
    raw: RawStates,
    valid: BoolArray,
    frame: IntArray,
    memory: RssMemory,
) -> tuple[RawStates, RssMemory]:
    """Adjust the ego's responses by the remembered safe state (see :func:`apply_memory_both`).

    Returns:
        ``(states, memory)``: adjusted states and the memory after the last frame.
    """
    states, _, new_memory = apply_memory_both(batch, rel, raw, None, valid, frame, memory)
    return states, new_memory


def apply_memory_both(  # noqa: PLR0917  (structure-of-arrays engine step)
    batch: ConstellationBatch,
    rel: Relative,
    raw: RawStates,
    other_raw: RawStates | None,
    valid: BoolArray,
    frame: IntArray,
    memory: RssMemory,
) -> tuple[RawStates, RawStates | None, RssMemory]:
    """Adjust the responses of dangerous states by the remembered safe state.

    Non-intersection (dangerous now), by what was safe at the remembered frame: only
    lateral -> longitudinal response None; only longitudinal -> lateral responses None;
    both -> keep. Non-dangerous states get all responses None. Intersection (unsafe now):
    able-to-stop -> None if the ego has priority; safe longitudinal distance -> None if the
    ego is in front; otherwise BrakeMin.

    The other object's side (``other_raw``, :mod:`rss.structured.responsibility`) gets the
    same adjustment from the pair's one memory (what was safe is symmetric), with the
    priority and "in front" of the intersection rule taken from the object's side.

    Args:
        batch: ``C`` constellations.
        rel: Their relative situation.
        raw: Unadjusted states.
        other_raw: Unadjusted states from the other object's side, or ``None``.
        valid: ``(C,)`` constellations that were evaluated.
        frame: ``(C,)`` frame number 0..F-1 of each constellation (consecutive frames).
        memory: Memory before frame 0.

    Returns:
        ``(states, other states or None, memory)``: adjusted states and the memory after
        the last frame.
    """
    runs = _runs(memory, batch, frame)
    o = runs.order
    ctype = batch.constellation_type[o]
    intersection = ctype >= ConstellationType.IntersectionEgoHasPriority
    dangerous = (is_dangerous(raw) & valid)[o]
    lat_safe_now = (raw.left.is_safe & raw.right.is_safe)[o]
    lon_safe_now = raw.lon_is_safe[o]
    ok = valid[o]

    base = ok & np.where(intersection, lon_safe_now, ~dangerous)
    lat_code = rel.lat_position[o]
    lat_overlap = (lat_code >= int(LateralPosition.OverlapLeft)) & (
        lat_code <= int(LateralPosition.OverlapRight)
    )
    # dangerous without memory: ad-rss assumes (and remembers) "both were safe", except a
    # same-direction pair already overlapping laterally: "longitudinally safe" only
    candidate = dangerous & ~intersection
    overlap_assumption = (ctype == ConstellationType.SameDirection) & lat_overlap
    first_event = _previous(base | candidate, runs) < 0
    synthetic = candidate & first_event & (runs.initial < 0)
    store = base | synthetic
    prev = _previous(store, runs)
    has_initial = runs.initial >= 0
    init_row = np.where(has_initial, runs.initial, 0)

    had = prev >= 0
    prev_row = np.maximum(prev, 0)

    def remembered(now: np.ndarray, initial: np.ndarray, fill: Any) -> np.ndarray:
        before = np.where(has_initial, initial[init_row], fill) if memory.size else fill
        return np.where(had, now.take(prev_row), before)

    stored_lon = np.where(synthetic, np.True_, lon_safe_now)
    stored_lat = np.where(synthetic, ~overlap_assumption, lat_safe_now)
    known = had | has_initial
    prev_lon = remembered(stored_lon, memory.lon_safe, np.False_)
    prev_lat = remembered(stored_lat, memory.lat_safe, np.False_)
    # intersection states: all NONE (and no response of them cleared) when neither the
    # batch nor the memory holds one
    no_state = np.zeros(o.size, dtype=np.int64)
    stored_int, prev_int, int_none, other_none = no_state, no_state, None, None
    if intersection.any() or memory.intersection_state.any():
        stored_int = np.where(intersection & base, raw.intersection_state[o], _NO_STATE)
        prev_int = remembered(stored_int, memory.intersection_state, _NO_STATE)
        int_none, other_none = _intersection_cleared(
            ctype, rel.lon_position[o], ok & intersection & ~lon_safe_now & known, prev_int
        )

    structured = dangerous & ~intersection
    clear_lon = structured & known & prev_lat & ~prev_lon
    clear_lat = structured & ((known & prev_lon & ~prev_lat) | (synthetic & overlap_assumption))
    calm = ~intersection & ~dangerous
    clear_lat_rows = np.zeros(batch.size, dtype=np.bool_)
    clear_lat_rows[o] = clear_lat | calm
    clear_lon |= calm
    ego_clear = clear_lon if int_none is None else clear_lon | int_none
    states = _cleared(raw, o, ego_clear, clear_lat_rows)
    other_states = None
    if other_raw is not None:
        object_clear = clear_lon if other_none is None else clear_lon | other_none
        other_states = _cleared(other_raw, o, object_clear, clear_lat_rows)
    return (
        states,
        other_states,
        _memory_after(
            batch,
            frame,
            runs,
            store,
            known,
            stored_lon,
            stored_lat,
            stored_int,
            prev_lon,
            prev_lat,
            prev_int,
        ),
    )


def _intersection_cleared(
    ctype: IntArray, lon_position: IntArray, unsafe_int: BoolArray, prev_int: IntArray
) -> tuple[BoolArray, BoolArray]:
    """Unsafe intersection rows whose remembered state clears the ego's / the object's response.

    Able to stop -> None for the side with priority; safe longitudinal distance -> None for
    the side in front (all arrays in sorted order).
    """
    able = prev_int == IntersectionState.NON_PRIO_ABLE_TO_BREAK
    distance = prev_int == IntersectionState.SAFE_LONGITUDINAL_DISTANCE
    ego_none = unsafe_int & (
        (able & (ctype == ConstellationType.IntersectionEgoHasPriority))
        | (distance & (lon_position == LongitudinalPosition.InFront))
    )
    other_none = unsafe_int & (
        (able & (ctype == _OBJECT_PRIO))
        | (distance & (lon_position == LongitudinalPosition.AtBack))
    )
    return ego_none, other_none


def _cleared(
    raw: RawStates, order: IntArray, clear_lon_sorted: BoolArray, clear_lat_rows: BoolArray
) -> RawStates:
    """``raw`` with the longitudinal (given in sorted order) and lateral responses cleared."""
    clear_lon_rows = np.zeros(raw.lon_response.shape[0], dtype=np.bool_)
    clear_lon_rows[order] = clear_lon_sorted
    return dataclasses.replace(
        raw,
        lon_response=np.where(clear_lon_rows, LongitudinalResponse.None_, raw.lon_response).astype(
            np.int64
        ),
        left=_side(raw.left, clear_lat_rows),
        right=_side(raw.right, clear_lat_rows),
    )


def _memory_after(  # noqa: PLR0917  (internal: arrays of one scan)
    batch: ConstellationBatch,
    frame: IntArray,
    runs: _Runs,
    store: BoolArray,
    known: BoolArray,
    stored_lon: BoolArray,
    stored_lat: BoolArray,
    stored_int: IntArray,
    prev_lon: BoolArray,
    prev_lat: BoolArray,
    prev_int: IntArray,
) -> RssMemory:
    """Memory after the last frame: one entry per key present in it that has a value."""
    o = runs.order
    last_frame = frame.max(initial=0)
    run_end = np.ones(o.size, dtype=np.bool_)
    run_end[:-1] = runs.start[1:] != runs.start[:-1]
    keep = run_end & (frame[o] == last_frame) & (store | known)
    rows = o[keep]
    return RssMemory(
        ego_id=batch.ego.object_id[rows],
        object_id=batch.other.object_id[rows],
        constellation_type=batch.constellation_type[rows],
        lon_safe=np.where(store, stored_lon, prev_lon)[keep].astype(np.bool_),
        lat_safe=np.where(store, stored_lat, prev_lat)[keep].astype(np.bool_),
        intersection_state=np.where(store, stored_int, prev_int)[keep].astype(np.int64),
    )
