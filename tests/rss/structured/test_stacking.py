"""Stacking reads each shared road segment once: same arrays as distinct copies, same errors."""

from __future__ import annotations

import copy
import dataclasses
from typing import TYPE_CHECKING

import numpy as np
import pytest

from rss.conformance.cases import parse_case, parse_defaults
from rss.errors import RssConstellationError
from rss.model import Constellation, LaneSegment, RoadSegment, RoadSegmentType
from rss.structured.stacking import stack_constellations

if TYPE_CHECKING:
    from rss.structured.batch import RoadAreaArrays

CASE = {
    "id": "base",
    "kind": "structured",
    "constellation_type": "SameDirection",
    "road": {"length": 1000, "lane_widths": [3.5, 3.5, 3.0]},
    "ego": {"s": 100, "y": 1.75, "length": 4, "width": 2, "v_lon": 10},
    "other": {"s": 150, "y": 1.75, "length": 4, "width": 2, "v_lon": 10},
}


def _base() -> Constellation:
    parsed = parse_case(CASE, parse_defaults({}), "x")
    assert parsed.constellation is not None
    return parsed.constellation


def _roads(arrays: RoadAreaArrays) -> dict[str, np.ndarray]:
    return {f.name: getattr(arrays, f.name) for f in dataclasses.fields(arrays)}


def test_shared_segments_stack_like_distinct_copies() -> None:
    c = _base()
    (seg,) = c.ego_road
    a, b, d = seg.lanes
    tail = RoadSegment((dataclasses.replace(b, lane_id=7),), RoadSegmentType.Intersection, 2.5, 1.0)
    roads = [(seg,), (seg, tail), (tail,), (RoadSegment((d, a)), tail), ()]
    shared = [dataclasses.replace(c, ego_road=r, intersecting_road=r[::-1]) for r in roads]
    distinct = copy.deepcopy(shared)
    assert distinct[0].ego_road[0] is not shared[0].ego_road[0]
    one, two = stack_constellations(shared), stack_constellations(distinct)
    for name in ("ego_road", "intersecting_road"):
        got, want = _roads(getattr(one, name)), _roads(getattr(two, name))
        for key, value in want.items():
            np.testing.assert_array_equal(got[key], value, err_msg=f"{name}.{key}")
    road = one.ego_road
    assert road.lane_id.shape == (5, 2, 3)
    assert road.lane_id[1].tolist() == [[a.lane_id, b.lane_id, d.lane_id], [7, -1, -1]]
    assert road.segment_type[1].tolist() == [RoadSegmentType.Normal, RoadSegmentType.Intersection]
    assert road.before_intersection_m[1, 1] == 2.5
    assert road.lane_id[4].tolist() == [[-1] * 3] * 2


def test_duplicate_ids_across_shared_segments_raise() -> None:
    c = _base()
    (seg,) = c.ego_road
    fine = dataclasses.replace(c, ego_road=(seg,))
    twice = dataclasses.replace(c, ego_road=(seg, seg))
    with pytest.raises(RssConstellationError, match="lane id"):
        stack_constellations([fine, twice])


def test_first_invalid_lane_in_road_order_is_reported() -> None:
    c = _base()
    (seg,) = c.ego_road
    bad_width = LaneSegment(99, 1, 10, 10, 3, 2)  # type: ignore[arg-type]
    dup_then_bad = RoadSegment((seg.lanes[0], bad_width))
    with pytest.raises(RssConstellationError, match="lane id"):
        stack_constellations([dataclasses.replace(c, ego_road=(seg, dup_then_bad))])
    with pytest.raises(RssConstellationError, match="width"):
        stack_constellations([dataclasses.replace(c, ego_road=(RoadSegment((bad_width,)), seg))])
    with pytest.raises(RssConstellationError, match="no lanes"):
        stack_constellations([dataclasses.replace(c, ego_road=(seg, RoadSegment(())))])


def test_first_error_in_constellation_order_is_reported() -> None:
    """Repeated lane ids (found in the padded arrays) still rank by constellation order."""
    c = _base()
    (seg,) = c.ego_road
    a, b, _ = seg.lanes
    same_twice = RoadSegment((a, a))
    repeated = dataclasses.replace(c, intersecting_road=(RoadSegment((b,)), RoadSegment((b,))))
    unknown = dataclasses.replace(c, constellation_type=17)  # type: ignore[arg-type]
    bad_width = dataclasses.replace(
        c,
        ego_road=(RoadSegment((LaneSegment(99, 1, 10, 10, 3, 2),)),),  # type: ignore[arg-type]
    )
    cases = [
        ([c, repeated, unknown], "lane id"),
        ([c, unknown, repeated], "constellation_type"),
        ([repeated, bad_width], "lane id"),
        ([bad_width, repeated], "width"),
        ([dataclasses.replace(c, ego_road=(same_twice,)), unknown], "lane id"),
        ([dataclasses.replace(repeated, ego_road=bad_width.ego_road)], "width"),
    ]
    for constellations, message in cases:
        with pytest.raises(RssConstellationError, match=message):
            stack_constellations(constellations)
    assert stack_constellations([c, c]).ego_road.lane_id.shape == (2, 1, 3)
