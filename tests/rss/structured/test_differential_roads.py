"""Road areas beyond the case format: several segments, curved / narrowing lanes
(min != max lengths and widths), objects spanning segments and lanes, mixed directions."""

from __future__ import annotations

from typing import Any

import numpy as np
import pytest

from rss.conformance import frame_record
from rss.model import (
    Constellation,
    ConstellationType,
    LaneDrivingDirection,
    LaneObject,
    LaneSegment,
    ObjectType,
    OccupiedRegion,
    RoadSegment,
    RoadSegmentType,
    SpeedInterval,
)
from rss.params import DEFAULT_EGO_DYNAMICS, DEFAULT_VEHICLE_DYNAMICS
from rss.structured.engine import check_frames
from rss.structured.stacking import stack_constellations
from tests.rss.oracle import AdRssOracle, compare_frames, load_ad_rss

pytestmark = pytest.mark.oracle


def _road(rng: np.random.Generator) -> tuple[RoadSegment, ...]:
    n_segments, n_lanes = int(rng.integers(1, 4)), int(rng.integers(1, 4))
    directions = [LaneDrivingDirection(int(d)) for d in rng.choice([0, 1, 1, 1, 2], n_lanes)]
    segments = []
    for r in range(n_segments):
        lanes = []
        for m in range(n_lanes):
            length = float(rng.uniform(20.0, 120.0))
            width = float(rng.uniform(2.5, 4.0))
            lanes.append(
                LaneSegment(
                    10 * r + m + 1,
                    directions[m],
                    length,
                    length * float(rng.uniform(1.0, 1.05)),
                    width * float(rng.uniform(0.9, 1.0)),
                    width,
                )
            )
        segments.append(RoadSegment(tuple(lanes)))
    return tuple(segments)


def _object(
    rng: np.random.Generator, road: tuple[RoadSegment, ...], object_id: int, kind: ObjectType
) -> LaneObject:
    r0 = int(rng.integers(0, len(road)))
    r1 = min(len(road) - 1, r0 + int(rng.integers(0, 2)))
    m0 = int(rng.integers(0, len(road[0].lanes)))
    m1 = min(len(road[0].lanes) - 1, m0 + int(rng.integers(0, 2)))
    lon0, lat0 = float(rng.uniform(0.0, 0.9)), float(rng.uniform(0.0, 0.7))
    regions = []
    for r in range(r0, r1 + 1):
        for m in range(m0, m1 + 1):
            lon = (
                lon0 if r == r0 else 0.0,
                1.0 if r < r1 else min(1.0, lon0 + float(rng.uniform(0.02, 0.1))),
            )
            lat = (
                lat0 if m == m0 else 0.0,
                1.0 if m < m1 else min(1.0, lat0 + float(rng.uniform(0.2, 0.3))),
            )
            regions.append(
                OccupiedRegion(road[r].lanes[m].lane_id, lon[0], max(lon), lat[0], max(lat))
            )
    v = float(rng.uniform(0.0, 30.0))
    lat_v = float(rng.uniform(-1.0, 1.0))
    return LaneObject(
        object_id, kind, tuple(regions), SpeedInterval(v * 0.9, v, lat_v - 0.1, lat_v)
    )


def _disagreements(constellations: list[Constellation]) -> list[tuple[int, Any]]:
    """Constellations (index, differences) where one batched call and ad-rss disagree."""
    batch = stack_constellations(constellations)
    result, _ = check_frames(batch, np.arange(batch.size), batch.size, DEFAULT_EGO_DYNAMICS)
    failures = []
    for i, c in enumerate(constellations):
        answer = AdRssOracle().step([c], DEFAULT_EGO_DYNAMICS)
        diffs = compare_frames(frame_record(result, batch, i), answer)
        if diffs:
            failures.append((i, diffs))
    return failures


@pytest.mark.parametrize("seed", [11, 12, 13])
def test_multi_segment_roads_agree(seed: int) -> None:
    load_ad_rss()
    rng = np.random.default_rng(seed)
    constellations = []
    for i in range(500):
        road = _road(rng)
        ctype = (
            ConstellationType.SameDirection
            if rng.random() < 0.6
            else ConstellationType.OppositeDirection
        )
        constellations.append(
            Constellation(
                ctype,
                _object(rng, road, 2 * i, ObjectType.EgoVehicle),
                _object(rng, road, 2 * i + 1, ObjectType.OtherVehicle),
                DEFAULT_EGO_DYNAMICS,
                DEFAULT_VEHICLE_DYNAMICS,
                road,
            )
        )
    failures = _disagreements(constellations)
    assert not failures, failures[:3]


def _intersection_road(rng: np.random.Generator, first_id: int) -> tuple[RoadSegment, ...]:
    road = list(_road(rng))
    n_lanes = len(road[0].lanes)
    crossing = []
    for m in range(n_lanes):
        length = float(rng.uniform(8.0, 25.0))
        crossing.append(
            LaneSegment(
                first_id + m, LaneDrivingDirection.Positive, length, length * 1.02, 3.0, 3.2
            )
        )
    before = float(rng.uniform(0.0, 3.0)) if rng.random() < 0.5 else 0.0
    after = float(rng.uniform(0.0, 3.0)) if rng.random() < 0.5 else 0.0
    position = int(rng.integers(1, len(road) + 1))
    road.insert(position, RoadSegment(tuple(crossing), RoadSegmentType.Intersection, before, after))
    renumbered = []
    for r, seg in enumerate(road):
        lanes = tuple(
            LaneSegment(
                first_id + 10 * r + m,
                lane.driving_direction,
                lane.length_min_m,
                lane.length_max_m,
                lane.width_min_m,
                lane.width_max_m,
            )
            for m, lane in enumerate(seg.lanes)
        )
        renumbered.append(
            RoadSegment(
                lanes,
                seg.segment_type,
                seg.min_length_before_intersecting_area_m,
                seg.min_length_after_intersecting_area_m,
            )
        )
    return tuple(renumbered)


@pytest.mark.parametrize("seed", [21, 22])
def test_intersection_road_areas_agree(seed: int) -> None:
    load_ad_rss()
    rng = np.random.default_rng(seed)
    kinds = (
        ConstellationType.IntersectionEgoHasPriority,
        ConstellationType.IntersectionObjectHasPriority,
        ConstellationType.IntersectionSamePriority,
    )
    constellations = []
    for i in range(400):
        ego_road, other_road = _intersection_road(rng, 1000), _intersection_road(rng, 5000)
        constellations.append(
            Constellation(
                kinds[int(rng.integers(0, 3))],
                _object(rng, ego_road, 2 * i, ObjectType.EgoVehicle),
                _object(rng, other_road, 2 * i + 1, ObjectType.OtherVehicle),
                DEFAULT_EGO_DYNAMICS,
                DEFAULT_VEHICLE_DYNAMICS,
                ego_road,
                other_road,
            )
        )
    failures = _disagreements(constellations)
    assert not failures, failures[:3]
