"""Road geometry: solid lines of any lengths, unusable lanes and lines left out and named."""

from __future__ import annotations

import dataclasses

import numpy as np
import shapely

from reachsets.inputs import ReachInputs, RoadLane, RoadLayout
from reachsets.params import ReachParams
from reachsets.road import polylines, prepare_road
from tests.reachsets.helpers import evaluate_one, objects, straight_ego, two_lane_road


def _ragged(road: RoadLayout) -> RoadLayout:
    """``road`` with its solid line split into two of different lengths (36 and 5 points)."""
    (line,) = road.solid_lines_m
    short = np.array([[300.0, 0.0], [310.0, 0.0], [320.0, 0.0], [330.0, 0.0], [340.0, 0.0]])
    return dataclasses.replace(road, solid_lines_m=(line, short))


def test_polylines_of_different_lengths_match_one_by_one():
    lines = [np.array([[0.0, 0.0], [1.0, 0.0], [2.0, 1.0]]), np.array([[5.0, 5.0], [6.0, 6.0]])]
    got = polylines(lines)
    assert got.shape == (2,)
    for geom, line in zip(got, lines, strict=True):
        assert shapely.equals_exact(geom, shapely.linestrings(line), tolerance=0.0)
    assert polylines([]).shape == (0,)


def test_ragged_solid_lines_build_and_the_rules_run():
    road = _ragged(two_lane_road())
    geo = prepare_road(road)
    want = shapely.union_all([shapely.linestrings(line) for line in road.solid_lines_m])
    assert shapely.equals(geo.solid, want)
    assert geo.skipped == ()
    inp = ReachInputs(
        ego=straight_ego(x0=0.0, y0=-2.0, speed=10.0),
        objects=objects((20.0, -2.0, 0.0, 14.0)),
        road=road,
    )
    res, _ = evaluate_one(inp, ReachParams())
    assert "road.no_opposite" in {p.rule for p in res.patches}


def test_unusable_lanes_and_lines_are_left_out_and_named():
    good = two_lane_road()
    flat = RoadLane("flat", np.array([[0.0, 0.0], [1.0, 0.0], [0.0, 0.0]]), good.lanes[0].centre_m)
    holed = RoadLane(
        "nan", np.where(np.arange(4)[:, None] == 1, np.nan, np.eye(4, 2)), good.lanes[0].centre_m
    )
    dot = RoadLane("dot", good.lanes[0].polygon_m, np.array([[1.0, 1.0]]))
    bad = RoadLayout(
        lanes=(good.lanes[0], flat, holed, good.lanes[1], dot),
        solid_lines_m=(*good.solid_lines_m, np.array([[0.0, 0.0]]), np.array([[0.0, np.nan]] * 2)),
    )
    geo = prepare_road(bad)
    assert geo.skipped == ("lane flat", "lane nan", "lane dot", "solid line 1", "solid line 2")
    assert [ln.lane_id for ln in geo.lanes] == ["r", "l"]
    assert geo.lanes_by_id == {"r": 0, "l": 1}
    ego, objs = straight_ego(x0=0.0, y0=-2.0, speed=10.0), objects((20.0, -2.0, 0.0, 14.0))
    res, _ = evaluate_one(ReachInputs(ego=ego, objects=objs, road=bad), ReachParams())
    ref, _ = evaluate_one(ReachInputs(ego=ego, objects=objs, road=good), ReachParams())
    assert res.skipped_road == geo.skipped
    assert ref.skipped_road == ()
    assert res.collisions == ref.collisions
    assert [(p.object_id, p.rule, p.step) for p in res.patches] == [
        (p.object_id, p.rule, p.step) for p in ref.patches
    ]
