"""Per-constellation memory: "the last state before the danger threshold" (RSS def. 10).

ad-rss keeps this inside its checker objects and requires a strictly increasing time
index. Here the memory is an explicit immutable value: :func:`apply_memory` takes the
memory of the previous frame and returns the next one, so a replay can start at any frame
(with :meth:`RssMemory.empty`) or restart from any stored memory.

Keys are ``(ego id, object id, constellation type)``, like ad-rss' constellation-id
provider. Entries of constellations absent from a frame are dropped (ad-rss forgets ids
not seen in the previous step); an *invalid* constellation keeps its previous entry.
"""

from __future__ import annotations

import dataclasses
from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np

from rss.batch import BoolArray, IntArray
from rss.checks import IntersectionState, LateralSide, RawStates
from rss.model import ConstellationType
from rss.states import LateralPosition, LateralResponse, LongitudinalPosition, LongitudinalResponse

if TYPE_CHECKING:
    from rss.batch import ConstellationBatch
    from rss.extraction import Relative

__all__ = ["RssMemory", "apply_memory", "is_dangerous"]


@dataclass(frozen=True)
class RssMemory:
    """Remembered safe states of ``M`` constellations.

    Attributes:
        ego_id: ``(M,)`` key part.
        object_id: ``(M,)`` key part.
        constellation_type: ``(M,)`` key part.
        lon_safe: ``(M,)`` non-intersection: longitudinal verdict of the last
            non-dangerous frame.
        lat_safe: ``(M,)`` non-intersection: lateral verdict of that frame.
        intersection_state: ``(M,)`` intersection: :class:`IntersectionState` of the last
            safe frame.
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


def _lookup(memory: RssMemory, batch: ConstellationBatch) -> IntArray:
    """Row of ``memory`` holding each constellation's key, -1 if none (``(C,)``)."""
    dtype = np.dtype([("e", np.int64), ("o", np.int64), ("t", np.int64)])
    keys = np.empty(memory.size + batch.size, dtype=dtype)
    keys["e"] = np.concatenate([memory.ego_id, batch.ego.object_id])
    keys["o"] = np.concatenate([memory.object_id, batch.other.object_id])
    keys["t"] = np.concatenate([memory.constellation_type, batch.constellation_type])
    _, inverse = np.unique(keys, return_inverse=True)
    table = np.full(inverse.max(initial=-1) + 1, -1, dtype=np.int64)
    table[inverse[: memory.size]] = np.arange(memory.size)
    return table[inverse[memory.size :]]


def _side(side: LateralSide, clear: BoolArray) -> LateralSide:
    return dataclasses.replace(side, response=np.where(clear, LateralResponse.None_, side.response))


def apply_memory(
    batch: ConstellationBatch, rel: Relative, raw: RawStates, valid: BoolArray, memory: RssMemory
) -> tuple[RawStates, RssMemory]:
    """Adjust the responses of dangerous states by the remembered safe state.

    Non-intersection (dangerous now), by what was safe in the last non-dangerous frame:
    only lateral -> longitudinal response None; only longitudinal -> lateral responses
    None; both -> keep; nothing remembered -> same-direction pairs that overlap laterally
    get lateral None, others keep. Intersection (unsafe now), by the last safe check:
    able-to-stop -> None if the ego has priority else BrakeMin; safe longitudinal
    distance -> None if the ego is in front else BrakeMin; otherwise BrakeMin.

    Args:
        batch: ``C`` constellations.
        rel: Their relative situation.
        raw: Unadjusted states.
        valid: ``(C,)`` constellations that were evaluated.
        memory: Memory after the previous frame.

    Returns:
        ``(states, memory)``: adjusted states and the memory after this frame.
    """
    row = _lookup(memory, batch)
    known = row >= 0
    safe_row = np.where(known, row, 0)
    has_rows = memory.size > 0
    prev_lon = np.where(known, memory.lon_safe[safe_row], False) if has_rows else np.zeros_like(known)
    prev_lat = np.where(known, memory.lat_safe[safe_row], False) if has_rows else np.zeros_like(known)
    prev_int = (
        np.where(known, memory.intersection_state[safe_row], IntersectionState.NONE)
        if has_rows
        else np.zeros(known.shape, dtype=np.int64)
    )
    ctype = batch.constellation_type
    intersection = ctype >= ConstellationType.IntersectionEgoHasPriority
    dangerous = is_dangerous(raw) & valid

    # non-intersection
    structured = dangerous & ~intersection
    clear_lon = structured & known & prev_lat & ~prev_lon
    lat_overlap = np.isin(
        rel.lat_position, [LateralPosition.OverlapLeft, LateralPosition.Overlap, LateralPosition.OverlapRight]
    )
    fresh_overlap = ~known & (ctype == ConstellationType.SameDirection) & lat_overlap
    clear_lat = structured & ((known & prev_lon & ~prev_lat) | fresh_overlap)

    # intersection
    unsafe_int = valid & intersection & ~raw.lon_is_safe & (prev_int != IntersectionState.NONE)
    ego_prio = ctype == ConstellationType.IntersectionEgoHasPriority
    ego_front = rel.lon_position == LongitudinalPosition.InFront
    int_none = unsafe_int & (
        ((prev_int == IntersectionState.NON_PRIO_ABLE_TO_BREAK) & ego_prio)
        | ((prev_int == IntersectionState.SAFE_LONGITUDINAL_DISTANCE) & ego_front)
    )
    # responses of non-dangerous structured states are reset to None (as ad-rss does)
    calm = ~intersection & ~dangerous
    lon_response = np.where(clear_lon | int_none | calm, LongitudinalResponse.None_, raw.lon_response)
    states = dataclasses.replace(
        raw,
        lon_response=lon_response.astype(np.int64),
        left=_side(raw.left, clear_lat | calm),
        right=_side(raw.right, clear_lat | calm),
    )

    lateral_safe = raw.left.is_safe & raw.right.is_safe
    store_now = valid & np.where(intersection, raw.lon_is_safe, ~dangerous)
    keep = store_now | known
    new_lon = np.where(store_now, raw.lon_is_safe, prev_lon)
    new_lat = np.where(store_now, lateral_safe, prev_lat)
    new_int = np.where(store_now, np.where(intersection, raw.intersection_state, IntersectionState.NONE), prev_int)
    new_memory = RssMemory(
        ego_id=batch.ego.object_id[keep],
        object_id=batch.other.object_id[keep],
        constellation_type=ctype[keep],
        lon_safe=np.asarray(new_lon[keep], dtype=np.bool_),
        lat_safe=np.asarray(new_lat[keep], dtype=np.bool_),
        intersection_state=np.asarray(new_int[keep], dtype=np.int64),
    )
    return states, new_memory
