"""The small-frame path on frames with several intersection routes per ego/object pair.

A scene gives one object several constellations of one intersection type when it has
several routes through intersections ahead of the ego; the batched engine merges those of
equal intersection lanes and equal dynamics into their worst case and keeps the others
apart (``rss.structured.merge``), all remembered under one (ego, object, type) key. The row
path (``rss.structured.small_merge``) must take such frames and give every field of the
result and of the memory exactly as ``check_frames`` does for ``F = 1`` (integers and flags
exactly, distances within 1e-9 m).
"""

from __future__ import annotations

import dataclasses
from typing import TYPE_CHECKING

import numpy as np
from hypothesis import given, settings
from hypothesis import strategies as st

from rss.conformance.cases import parse_case, parse_defaults
from rss.model import ConstellationType, RoadSegmentType, SpeedInterval
from rss.structured.batch import take_rows
from rss.structured.engine import check_frame, check_frames
from rss.structured.small import check_frame_small
from rss.structured.small_output import recall
from rss.structured.small_result import SmallMemory
from rss.structured.stacking import stack_constellations
from rss.structured.standstill import apply_standstill
from tests.rss.structured.generators import random_sequence, renumber
from tests.rss.structured.test_small import _assert_same, _drive

if TYPE_CHECKING:
    from typing import Any

    from rss.model import Constellation, LaneObject, RoadSegment
    from rss.structured.memory import RssMemory

_DEFAULTS = parse_defaults({})
_INTERSECTION = (
    "IntersectionEgoHasPriority",
    "IntersectionObjectHasPriority",
    "IntersectionSamePriority",
)
_STILL_MPS = 3.0  # standstill threshold: some objects stand, some move
_LANE_OFFSET = 100  # lane ids of another intersection: beyond every generated id
_SHIFTS = ((1, 0), (0, 1), (1, 1))  # other lanes on the ego road, the intersecting road, both


def _shift_road(road: tuple[RoadSegment, ...], by: int) -> tuple[RoadSegment, ...]:
    return tuple(
        dataclasses.replace(
            s, lanes=tuple(dataclasses.replace(lane, lane_id=lane.lane_id + by) for lane in s.lanes)
        )
        for s in road
    )


def _shift_object(obj: LaneObject, by: int) -> LaneObject:
    regions = tuple(dataclasses.replace(r, lane_id=r.lane_id + by) for r in obj.regions)
    return dataclasses.replace(obj, regions=regions)


def _elsewhere(c: Constellation, ego_by: int, other_by: int) -> Constellation:
    """``c`` with the lane ids of its ego road and intersecting road moved by ``*_by``."""
    return dataclasses.replace(
        c,
        ego=_shift_object(c.ego, ego_by),
        ego_road=_shift_road(c.ego_road, ego_by),
        other=_shift_object(c.other, other_by),
        intersecting_road=_shift_road(c.intersecting_road, other_by),
    )


def _intersection_sequence(rng: np.random.Generator, steps: int) -> list[dict[str, Any]]:
    """The steps of a random sequence of an intersection type."""
    while True:
        sequence = random_sequence(rng, _DEFAULTS, "i", steps)
        if "intersection" in sequence["steps"][0]:
            steps_out: list[dict[str, Any]] = sequence["steps"]
            return steps_out


def _routes_frames(seed: int, n_pairs: int, n_others: int, steps: int) -> list[list[Any]]:
    """Frames of ``n_others`` random constellations (any type) plus, per pair, 2-4 routes.

    The routes of a pair share one intersection type; each route, from its own random
    sequence, has the lanes of the pair's first route or of another intersection (lane
    ids moved, on the ego road, the intersecting road or both) and the first route's
    dynamics or its own.
    """
    rng = np.random.default_rng(seed)
    frames = _drive(seed, n_others, steps) if n_others else [[] for _ in range(steps)]
    for pair in range(n_pairs):
        other_id = 1000 + pair
        ctype = str(rng.choice(_INTERSECTION))
        routes = [_intersection_sequence(rng, steps) for _ in range(int(rng.integers(2, 5)))]
        first = routes[0][0]
        plans = []
        for r in range(len(routes)):
            shift = (0, 0) if r == 0 or rng.random() < 0.4 else _SHIFTS[int(rng.integers(3))]
            ego_by, other_by = (_LANE_OFFSET * r * k for k in shift)
            plans.append((ego_by, other_by, r > 0 and rng.random() < 0.7))
        for t in range(steps):
            for route, (ego_by, other_by, shared) in zip(routes, plans, strict=True):
                case = dict(route[t], constellation_type=ctype)
                if shared:
                    for who in ("ego_dynamics", "other_dynamics"):
                        case.pop(who, None)
                        if who in first:
                            case[who] = first[who]
                c = renumber(parse_case(case, _DEFAULTS, "i"), 0, other_id).constellation
                assert c is not None
                frames[t].append(_elsewhere(c, ego_by, other_by))
    for frame in frames:
        rng.shuffle(frame)
    return frames


def _check_both(frames: list[list[Constellation]], via: str = "stacking") -> tuple[int, int]:
    """Both paths frame by frame (memory carried); ``(frames, frames the row path took)``.

    ``via``: the row path reads the rows the stacking step packed (``stacking``), the
    arrays of a batch it did not stack (``arrays``: road areas padded to the batch's
    widest), or the standstill rule's copy of a stacked batch (``standstill``).
    """
    ours_memory: RssMemory | None = None
    batched_memory: RssMemory | None = None
    taken = 0
    for frame in frames:
        batch = stack_constellations(frame)
        if via == "arrays":
            batch = take_rows(batch, np.arange(batch.size))
        elif via == "standstill":
            batch = apply_standstill(batch, _STILL_MPS)
        before = {}
        if isinstance(ours_memory, SmallMemory):
            before = ours_memory.before
        elif ours_memory is not None and ours_memory.size:
            before = recall(ours_memory)
        small = check_frame_small(batch, _DEFAULTS.ego, before)
        ours, ours_memory = check_frame(batch, _DEFAULTS.ego, ours_memory)
        batched, batched_memory = check_frames(
            batch, np.zeros(batch.size, dtype=np.int64), 1, _DEFAULTS.ego, batched_memory
        )
        _assert_same(ours, batched)
        _assert_same(ours_memory, batched_memory)
        if (batched.invalid == 0).all():
            assert small is not None
            taken += 1
    return len(frames), taken


@settings(max_examples=60, deadline=None)
@given(
    st.integers(0, 2**32 - 1),
    st.integers(1, 4),
    st.integers(0, 8),
    st.integers(1, 5),
    st.sampled_from(["stacking", "arrays", "standstill"]),
)
def test_intersection_routes_merged_as_batched(
    seed: int, n_pairs: int, n_others: int, steps: int, via: str
) -> None:
    """Several intersection routes per pair (same lanes or not, same dynamics or not)."""
    frames = _routes_frames(seed, n_pairs, n_others, steps)
    for frame in frames:  # every pair does have an intersection key twice
        keys = [
            (c.other.object_id, c.constellation_type)
            for c in frame
            if c.constellation_type >= ConstellationType.IntersectionEgoHasPriority
        ]
        assert len(keys) - len(set(keys)) >= n_pairs
    _check_both(frames, via)


def test_routes_of_other_lanes_are_kept_apart() -> None:
    """Two routes of one pair and type through other intersection lanes are not merged,
    two through the same lanes are: as the batched engine decides."""
    rng = np.random.default_rng(11)
    route = _intersection_sequence(rng, 1)[0]
    c = renumber(parse_case(route, _DEFAULTS, "i"), 0, 1).constellation
    assert c is not None
    faster = SpeedInterval(20.0, 25.0, 0.0, 0.0)
    twin = dataclasses.replace(c, other=dataclasses.replace(c.other, speed=faster))
    assert any(s.segment_type == RoadSegmentType.Intersection for s in c.intersecting_road)
    merged, _ = check_frame(stack_constellations([c, twin]), _DEFAULTS.ego)
    apart, _ = check_frame(
        stack_constellations([c, _elsewhere(twin, 0, _LANE_OFFSET)]), _DEFAULTS.ego
    )
    single, _ = check_frame(stack_constellations([c]), _DEFAULTS.ego)
    # merged: both rows see the union of the other's speeds; apart: the first row alone
    assert merged.states.lon_safe_distance_m[0] == merged.states.lon_safe_distance_m[1]
    np.testing.assert_allclose(
        apart.states.lon_safe_distance_m[0], single.states.lon_safe_distance_m[0], atol=1e-9
    )
    _check_both([[c, twin], [c, _elsewhere(twin, 0, _LANE_OFFSET)]])


@settings(max_examples=30, deadline=None)
@given(st.integers(0, 2**32 - 1), st.integers(1, 12), st.integers(1, 4))
def test_rows_of_other_dynamics_are_groups_of_their_own(
    seed: int, n_objects: int, steps: int
) -> None:
    """A key's twin with other dynamics (any type): the row path, as the batched engine."""
    frames = _drive(seed, n_objects, steps)
    for frame in frames:
        d = frame[0].other_dynamics
        own = dataclasses.replace(d, response_time_s=d.response_time_s + 0.5)
        frame.append(dataclasses.replace(frame[0], other_dynamics=own))
    _check_both(frames)
