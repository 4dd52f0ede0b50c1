"""Lane rules (``road.keep_lane``, ``road.no_cut_in``) on a synthetic three-lane road."""

from __future__ import annotations

import dataclasses

import numpy as np
import pytest
import shapely

from reachsets.inputs import ReachInputs, RoadLane, RoadLayout
from reachsets.lanes import corridor, half_widths
from reachsets.ltl import evaluate_trace
from reachsets.params import ReachParams
from reachsets.road import prepare_road
from reachsets.rules_lane import KEEP_LEFT, NO_CUT_IN
from tests.reachsets.helpers import evaluate_one, objects, straight_ego

LANE_W = 3.5


def _lane(lane_id: str, y_right: float, x0: float, x1: float) -> RoadLane:
    x = np.linspace(x0, x1, 41)
    left = np.stack([x, np.full_like(x, y_right + LANE_W)], 1)
    right = np.stack([x, np.full_like(x, y_right)], 1)
    return RoadLane(
        lane_id,
        np.concatenate([right, left[::-1]]),
        np.stack([x, np.full_like(x, y_right + LANE_W / 2)], 1),
        speed_limit_mps=40.0,
    )


def three_lanes(*, split: bool = False) -> RoadLayout:
    """Three eastbound lanes (centres y = -3.5, 0, 3.5); ``split``: each in two segments."""
    lanes = []
    for name, y in (("r", -5.25), ("m", -1.75), ("l", 1.75)):
        if split:
            lanes += [_lane(f"{name}1", y, -100.0, 150.0), _lane(f"{name}2", y, 150.0, 500.0)]
        else:
            lanes.append(_lane(name, y, -100.0, 500.0))
    return RoadLayout(lanes=tuple(lanes))


def _params(*, lane_rules: bool) -> ReachParams:
    base = ReachParams(full_geometry=False)
    return dataclasses.replace(base, road=dataclasses.replace(base.road, lane_rules=lane_rules))


def _frame(*rows: tuple[float, float, float, float], road: RoadLayout) -> ReachInputs:
    ego = straight_ego(y0=0.0, speed=25.0)
    return ReachInputs(ego=ego, objects=objects(*rows, width=1.9), road=road)


def test_a_neighbour_keeping_its_lane_is_only_a_danger_without_the_lane_rules():
    road = three_lanes()
    inp = _frame((0.0, LANE_W, 0.0, 25.0), road=road)  # alongside in the left lane
    without, _ = evaluate_one(inp, _params(lane_rules=False))
    assert not without.is_safe  # its physically reachable set covers the ego
    with_rules, _ = evaluate_one(inp, _params(lane_rules=True))
    assert with_rules.is_safe
    assert {p.rule for p in with_rules.patches} >= {"road.keep_lane", "road.no_cut_in"}


def test_a_neighbour_crossing_into_the_ego_lane_is_a_danger():
    road = three_lanes()
    # left-lane car 8 m ahead, heading 0.1 rad towards the ego lane, its right side over the line
    inp = _frame((8.0, 2.2, -0.1, 25.0), road=road)
    result, _ = evaluate_one(inp, _params(lane_rules=True))
    assert not result.is_safe
    assert [c.object_id for c in result.collisions] == ["o0"]
    assert "road.no_cut_in" not in {p.rule for p in result.patches}


def test_drifting_towards_the_ego_lifts_keep_lane_but_not_no_cut_in():
    road = three_lanes()
    # inside its lane (right side 0.4 m from the line) but moving right at 25 sin(0.04) = 1 m/s
    inp = _frame((10.0, LANE_W, -0.04, 25.0), road=road)
    result, _ = evaluate_one(inp, _params(lane_rules=True))
    assert result.is_safe
    rules = {p.rule for p in result.patches}
    assert "road.no_cut_in" in rules
    # keep_lane still holds to the left only: its patch no longer covers the right lane
    keep = [p.geometry for p in result.patches if p.rule == "road.keep_lane"]
    assert len(keep) == 1
    assert not shapely.intersects(keep[0], shapely.Point(60.0, -LANE_W))
    assert shapely.intersects(keep[0], shapely.Point(60.0, LANE_W + 3.0))


def test_an_oncoming_vehicle_that_is_not_in_any_lane_of_its_direction_is_not_patched():
    road = three_lanes()
    inp = _frame((40.0, 0.0, np.pi, 20.0), road=road)  # wrong way in the ego's lane
    result, _ = evaluate_one(inp, _params(lane_rules=True))
    assert not result.is_safe
    assert not {p.rule for p in result.patches} & {"road.keep_lane", "road.no_cut_in"}


def test_the_corridor_follows_successor_lanes():
    geo = prepare_road(three_lanes(split=True))
    first = geo.lanes_by_id["m1"]
    both = corridor(geo, frozenset({first}), open_left=False, open_right=False, length_m=300.0)
    assert shapely.covers(both, shapely.Point(300.0, 0.0))  # in the successor m2
    assert not shapely.covers(both, shapely.Point(300.0, LANE_W))
    opened = corridor(geo, frozenset({first}), open_left=True, open_right=False, length_m=300.0)
    assert shapely.covers(opened, shapely.Point(300.0, LANE_W))
    assert not shapely.covers(opened, shapely.Point(300.0, -LANE_W))


def test_split_lanes_give_the_verdicts_of_whole_lanes():
    for rows in ([(0.0, LANE_W, 0.0, 25.0)], [(8.0, 2.2, -0.1, 25.0)], [(140.0, -LANE_W, 0, 20)]):
        whole, _ = evaluate_one(_frame(*rows, road=three_lanes()), _params(lane_rules=True))
        split, _ = evaluate_one(
            _frame(*rows, road=three_lanes(split=True)), _params(lane_rules=True)
        )
        assert whole.is_safe == split.is_safe


@pytest.mark.parametrize(
    ("settled", "leaving", "expected"),
    [
        # hand-evaluated: (not leaving) S (settled and not leaving)
        ([1, 0, 0], [0, 0, 0], [1, 1, 1]),  # settled once, never leaving since: holds
        ([0, 0], [0, 0], [0, 0]),  # never settled: nothing to keep
        ([1, 1, 1], [0, 1, 0], [1, 0, 1]),  # lifted while leaving, back when settled again
        ([1, 0, 0], [0, 1, 0], [1, 0, 0]),  # left and not settled since: stays lifted
    ],
)
def test_keep_lane_formula_on_traces(settled, leaving, expected):
    trace = [
        {"settled": bool(s), "leaving_left": bool(lv)}
        for s, lv in zip(settled, leaving, strict=True)
    ]
    got = [evaluate_trace(KEEP_LEFT, trace, k) for k in range(len(trace))]
    assert got == [bool(e) for e in expected]


def test_no_cut_in_formula_is_lifted_from_crossing_towards_the_ego_until_back_in_a_lane():
    # hand-evaluated: (not crossing_ego) S (in_lane and not crossing_ego)
    rows = [(True, False), (False, False), (True, True), (False, False), (True, False)]
    trace = [{"in_lane": a, "crossing_ego": c} for a, c in rows]
    got = [evaluate_trace(NO_CUT_IN, trace, k) for k in range(len(trace))]
    assert got == [True, True, False, False, True]
    assert not evaluate_trace(NO_CUT_IN, [{"in_lane": False, "crossing_ego": False}], 0)


def test_the_memory_keeps_a_car_over_its_far_line_in_its_lane_towards_the_ego():
    """Settled in the left lane, then over its *left* edge: it still keeps to it on the right.

    The ego (2.8 m wide, in the right lane) pokes 0.25 m into the middle lane, which is not
    one of its lanes, so only ``keep_lane`` protects it there. Without the memory (a fresh
    start at the second frame) the car has never been settled, nothing is assumed on its
    right, and its set reaches the ego's part in the middle lane.
    """
    road = three_lanes()
    params = _params(lane_rules=True)

    def frame(y: float) -> ReachInputs:
        ego = straight_ego(y0=-2.9, speed=25.0)
        return ReachInputs(ego=ego, objects=objects((0.0, y, 0.0, 25.0), width=1.9), road=road)

    first, state = evaluate_one(frame(LANE_W), params)
    assert first.is_safe
    straddling = frame(LANE_W + 1.2)  # 0.35 m over the left edge
    second, _ = evaluate_one(straddling, params, state)
    assert second.is_safe
    fresh, _ = evaluate_one(straddling, params)
    assert not fresh.is_safe
    assert [c.object_id for c in fresh.collisions] == ["o0"]


def test_crossing_traffic_is_not_kept_out_of_the_ego_lanes():
    """A lane that crosses the ego's is no lane change: no_cut_in leaves it alone."""
    y = np.linspace(-100.0, 100.0, 21)
    crossing = RoadLane(
        "n",
        np.concatenate(
            [
                np.stack([np.full_like(y, 61.75), y], 1),
                np.stack([np.full_like(y, 58.25), y[::-1]], 1),
            ]
        ),
        np.stack([np.full_like(y, 60.0), y], 1),
    )
    road = RoadLayout(lanes=(*three_lanes().lanes, crossing))
    inp = _frame((60.0, -20.0, np.pi / 2, 10.0), road=road)
    result, _ = evaluate_one(inp, _params(lane_rules=True))
    assert "road.no_cut_in" not in {p.rule for p in result.patches}
    assert "road.keep_lane" in {p.rule for p in result.patches}
    assert [c.object_id for c in result.collisions] == ["o0"]


def test_short_lanes_get_their_width():
    """A 4 m lane of two centre points is 3.5 m wide, not 0 (both lie on its outline)."""
    short = RoadLane(
        "short",
        np.array([[100.0, -1.75], [104.0, -1.75], [104.0, 1.75], [100.0, 1.75]]),
        np.array([[100.0, 0.0], [104.0, 0.0]]),
    )
    geo = prepare_road(RoadLayout(lanes=(short, _lane("long", 1.75, 0, 99))))
    assert half_widths(geo) == pytest.approx([LANE_W / 2, LANE_W / 2])
