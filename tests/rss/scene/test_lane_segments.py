"""``rss.scene.lane_segments``: whole lanes built once per memo, cut lanes like ``build_road``."""

from __future__ import annotations

import numpy as np
import pytest

from rss.model import LaneDrivingDirection
from rss.scene import SceneMemo, prepare
from rss.scene.roadarea import build_road
from rss.scene.segment_plans import SegmentPlan
from tests.rss.scene.synthetic import straight_road


@pytest.fixture(scope="module")
def prep():
    return prepare(straight_road(3, opposite_left=True))


@pytest.mark.parametrize("forward", [True, False])
def test_whole_lane_is_built_once(prep, forward: bool) -> None:
    cache = prep.lane_segments
    whole = SceneMemo().whole_lanes
    for lane in range(len(prep.graph)):
        seg = cache.lane_segment(whole, lane, forward=forward, id_offset=7)
        assert cache.lane_segment(whole, lane, forward=forward, id_offset=7) is seg
        assert seg.lane_id == lane + 7
        assert (seg.length_min_m, seg.length_max_m) == (
            prep.length_min_m[lane],
            prep.length_max_m[lane],
        )
        assert (seg.width_min_m, seg.width_max_m) == (
            prep.width_m[lane].min(),
            prep.width_m[lane].max(),
        )
        along = LaneDrivingDirection(int(prep.graph.direction[lane]))
        flipped = {1: LaneDrivingDirection.Negative, 2: LaneDrivingDirection.Positive}
        assert seg.driving_direction == (along if forward else flipped.get(along, along))
    assert prep.lane_segments is cache


@pytest.mark.parametrize(("p0", "p1"), [(0.0, 1.0), (0.25, 1.0), (0.0, 0.6), (0.1, 0.3)])
@pytest.mark.parametrize("forward", [True, False])
def test_lane_segments_equal_build_road(prep, p0: float, p1: float, forward: bool) -> None:
    plan = SegmentPlan(lanes=[(1, forward), (2, forward)], p0=p0, p1=p1)
    memo = SceneMemo()
    (road,), _, _ = build_road(prep, memo, [plan], id_offset=3)
    cached = tuple(
        prep.lane_segments.lane_segment(
            memo.whole_lanes, lane, forward=forward, id_offset=3, p0=p0, p1=p1
        )
        for lane in (1, 2)
    )
    assert road.lanes == cached
    assert np.isclose(cached[0].length_min_m, prep.length_min_m[1] * (p1 - p0))
