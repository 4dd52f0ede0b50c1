"""The ego's lane margin of ``road.no_cut_in``: an ego over its line by a sliver is in its lane.

Three eastbound 3.5 m lanes (``test_rules_lane.three_lanes``); the ego (2.8 m wide, 25 m/s)
drives in the middle lane off-centre to the right, so its footprint sticks ``poke`` metres into
the right lane; a 1.9 m wide car drives alongside in the right lane at the ego's speed.
"""

from __future__ import annotations

import dataclasses

import pytest

from reachsets.inputs import ReachInputs
from reachsets.params import ReachParams
from tests.reachsets.helpers import evaluate_one, objects, straight_ego
from tests.reachsets.test_rules_lane import LANE_W, three_lanes

#: The ego's width (``EgoTrajectory`` default) [m].
EGO_W = 2.8


def _params(*, lane_rules: bool, margin_m: float = 0.1) -> ReachParams:
    base = ReachParams(full_geometry=False)
    road = dataclasses.replace(base.road, lane_rules=lane_rules, lane_margin_m=margin_m)
    return dataclasses.replace(base, road=road)


def _frame(poke_m: float, neighbour: tuple[float, float, float, float]) -> ReachInputs:
    """Ego sticking ``poke_m`` over the middle lane's right line; one neighbour row."""
    y_ego = -LANE_W / 2 + EGO_W / 2 - poke_m
    ego = straight_ego(y0=y_ego, speed=25.0)
    return ReachInputs(ego=ego, objects=objects(neighbour, width=1.9), road=three_lanes())


#: Alongside in the right lane, 0.3 m right of its centre, keeping it.
KEEPING = (0.0, -LANE_W - 0.3, 0.0, 25.0)


def test_a_sliver_over_the_line_is_within_the_margin():
    """0.05 m over the line: the cut-in duty covers it; without the margin the neighbour hits."""
    inp = _frame(0.05, KEEPING)
    result, _ = evaluate_one(inp, _params(lane_rules=True))
    assert result.is_safe
    assert "road.no_cut_in" in {p.rule for p in result.patches}
    no_margin, _ = evaluate_one(inp, _params(lane_rules=True, margin_m=0.0))
    assert [c.object_id for c in no_margin.collisions] == ["o0"]


def test_a_real_straddle_is_still_a_danger():
    """0.3 m over the line (three margins): the neighbour keeping its lane reaches the ego."""
    result, _ = evaluate_one(_frame(0.3, KEEPING), _params(lane_rules=True))
    assert [c.object_id for c in result.collisions] == ["o0"]


@pytest.mark.parametrize("poke_m", [0.0, 0.05])
def test_a_neighbour_crossing_towards_the_ego_is_still_a_danger(poke_m):
    """Over its left line, heading 0.1 rad towards the ego: no cut-in duty, no margin."""
    crossing = (6.0, -LANE_W + 0.9, 0.1, 25.0)
    result, _ = evaluate_one(_frame(poke_m, crossing), _params(lane_rules=True))
    assert [c.object_id for c in result.collisions] == ["o0"]
    assert "road.no_cut_in" not in {p.rule for p in result.patches}


def test_the_reference_rules_ignore_the_margin():
    """Without the lane rules the neighbour's physical reach covers the ego, margin or not."""
    inp = _frame(0.05, KEEPING)
    for margin_m in (0.0, 0.1):
        result, _ = evaluate_one(inp, _params(lane_rules=False, margin_m=margin_m))
        assert [c.object_id for c in result.collisions] == ["o0"]
        assert not {p.rule for p in result.patches} & {"road.keep_lane", "road.no_cut_in"}
