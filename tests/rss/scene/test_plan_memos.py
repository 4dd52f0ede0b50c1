"""Memos of uncut road areas: shared plans stay uncut, their conversions match fresh ones."""

from __future__ import annotations

import dataclasses

import pytest

from rss.model import RoadSegmentType
from rss.scene import SceneMemo, prepare
from rss.scene.create import scene_boxes
from rss.scene.junction_pairs import (
    conflict,
    intersection_pair,
    intersection_plans,
    intersection_type,
    route_priority,
)
from rss.scene.matching import match_boxes
from rss.scene.roadarea import build_road
from rss.scene.segment_plans import (
    SegmentPlan,
    between,
    cut_at,
    cut_between,
    fresh_ends,
    plan_lanes,
)
from tests.rss.scene.synthetic import ego, objects, straight_road
from tests.rss.scene.test_intersection import crossing


@pytest.fixture(scope="module")
def prep():
    return prepare(straight_road(3, opposite_left=True))


def _plans() -> list[SegmentPlan]:
    return [SegmentPlan(lanes=[(1, True), (2, True)]), SegmentPlan(lanes=[(0, False)])]


def test_uncut_conversion_kept_on_the_plan_equals_a_fresh_one(prep) -> None:
    plans = _plans()
    memo = SceneMemo()
    first = build_road(prep, memo, plans, 5)
    assert all(plan.whole is not None and plan.whole[0] == 5 for plan in plans)
    assert build_road(prep, memo, plans, 5) == first == build_road(prep, memo, _plans(), 5)
    other = build_road(prep, memo, plans, 0)
    assert other == build_road(prep, memo, _plans(), 0)
    assert [lane.lane_id for lane in other[0][0].lanes] == [1, 2]
    plans[0].p0 = 0.5
    cut = build_road(prep, memo, plans, 0, {})
    fresh = [dataclasses.replace(_plans()[0], p0=0.5), _plans()[1]]
    assert cut == build_road(prep, SceneMemo(), fresh, 0)
    assert cut[0][0].lanes[0].length_min_m == pytest.approx(0.5 * other[0][0].lanes[0].length_min_m)


def test_fresh_ends_copies_only_the_ends() -> None:
    shared = (*_plans(), SegmentPlan(lanes=[(2, True)]))
    plans = fresh_ends(shared)
    assert plans == list(shared)
    assert plans[0] is not shared[0]
    assert plans[2] is not shared[2]
    assert plans[1] is shared[1]
    plans[0].p0, plans[2].p1 = 0.3, 0.4
    assert (shared[0].p0, shared[2].p1) == (0.0, 1.0)
    assert fresh_ends(()) == []
    kept_end = fresh_ends(shared, last=False)
    assert kept_end[0] is not shared[0]
    assert kept_end[1:] == list(shared[1:])
    assert all(a is b for a, b in zip(kept_end[1:], shared[1:], strict=True))
    (one,) = fresh_ends(shared[:1])
    assert one == shared[0]
    assert one is not shared[0]


def test_between_and_cut_at_equal_cut_between(prep) -> None:
    boxes = scene_boxes(ego(20.0, 1.75), objects((70.0, 1.75, 0.0, 5.0)))
    matches = match_boxes(prep, boxes)
    layout = [[(1, True)], [(1, True)]]
    plans = [SegmentPlan(lanes=list(lanes)) for lanes in layout]
    want = cut_between(plans, matches, (0, 1))
    cut = between(plan_lanes(layout), matches, (0, 1))
    assert cut is not None
    assert want is not None
    again = [SegmentPlan(lanes=list(lanes)) for lanes in layout]
    assert cut_at(again, matches, cut) == want
    assert again == plans
    assert 0.0 < plans[0].p0 < plans[-1].p1 < 1.0


@pytest.mark.parametrize("green", [frozenset(), frozenset({0})])
def test_intersection_pair_equals_its_parts(green: frozenset[int]) -> None:
    prep = prepare(crossing(1, -1, light_on_ego=True))
    ego_route, obj_route = ((0, True), (1, True), (2, True)), ((3, True), (4, True), (5, True))
    memo = SceneMemo()
    pair = intersection_pair(prep, memo, ego_route, obj_route, green)
    assert pair is not None
    assert intersection_pair(prep, memo, ego_route, obj_route, green) is pair
    ie, io = conflict(prep, memo, ego_route, obj_route) or (-1, -1)
    assert (pair.ego_lane, pair.obj_lane) == (1, 4)
    assert list(pair.ego_plans) == intersection_plans(prep, memo, ego_route, ie, 4)
    assert list(pair.obj_plans) == intersection_plans(prep, memo, obj_route, io, 1)
    assert pair.ego_plans[-1].segment_type == RoadSegmentType.Intersection
    assert pair.priority == intersection_type(
        route_priority(prep, ego_route[: ie + 1], green),
        route_priority(prep, obj_route[: io + 1], green),
    )
    assert intersection_pair(prep, memo, ego_route, ((5, False),), green) is None
