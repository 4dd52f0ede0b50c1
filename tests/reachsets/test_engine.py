"""Engine verdicts, state handling, split sets and the rule patches."""

from __future__ import annotations

import numpy as np
import pytest
import shapely

from reachsets import evaluate_frames
from reachsets.engine import RuleState
from reachsets.errors import InputShapeError, ParamsError, ReachSetError, ZoneFileError
from reachsets.inputs import (
    EgoTrajectory,
    ReachInputs,
    RightOfWayRule,
    RoadLane,
    RoadLayout,
    TrackBounds,
)
from reachsets.params import ReachMethod, ReachParams
from reachsets.patches import RulePatch, keep_largest_part, patch_grid, subtract_patches
from reachsets.rules_roborace import zones_from_json
from tests.reachsets.helpers import (
    evaluate_one,
    inputs,
    objects,
    straight_ego,
    straight_track,
    two_lane_road,
)


def test_empty_scene_is_safe():
    res, state = evaluate_one(inputs(straight_ego(), objects()), ReachParams())
    assert res.is_safe
    assert res.collisions == ()
    assert isinstance(state, RuleState)


@pytest.mark.parametrize("method", list(ReachMethod))
def test_standing_car_ahead_in_lane_collides(method):
    inp = inputs(straight_ego(speed=20.0), objects((40.0, 0.0, 0.0, 0.0)), straight_track())
    res, _ = evaluate_one(inp, ReachParams(method=method))
    assert not res.is_safe
    (col,) = res.collisions
    assert col.object_id == "o0"
    assert 0.0 < col.t_offset_s <= 2.4


@pytest.mark.parametrize("method", list(ReachMethod))
def test_car_far_ahead_and_faster_is_safe(method):
    inp = inputs(straight_ego(speed=10.0), objects((150.0, 0.0, 0.0, 40.0)), straight_track())
    res, _ = evaluate_one(inp, ReachParams(method=method, rules_enabled=False))
    assert res.is_safe


def test_follower_is_ignored_on_track():
    inp = inputs(straight_ego(speed=10.0), objects((-20.0, 0.0, 0.0, 30.0)), straight_track())
    res, _ = evaluate_one(inp, ReachParams())
    assert res.skipped_ids == ("o0",)
    assert res.is_safe


def test_invalid_object_rows_are_skipped_not_fatal():
    inp = inputs(straight_ego(), objects((np.nan, 0.0, 0.0, 5.0), (30.0, 0.0, 0.0, 0.0)))
    res, _ = evaluate_one(inp, ReachParams())
    assert "o0" in res.skipped_ids
    assert list(res.object_ids) == ["o1"]


def test_infinite_speed_object_is_skipped_not_fatal():
    inp = inputs(straight_ego(), objects((30.0, 0.0, 0.0, np.inf), (30.0, 5.0, 0.0, 0.0)))
    res, _ = evaluate_one(inp, ReachParams())
    assert res.skipped_ids == ("o0",)
    assert list(res.object_ids) == ["o1"]


def test_split_sets_keep_every_part():
    """Reference defect: only the largest part of a split set survived."""
    reach = np.array([[shapely.box(0, 0, 10, 3)]], dtype=object)
    cut = shapely.box(6, -1, 7, 4)
    grid = patch_grid([RulePatch(0, "test", cut)], np.array([shapely.Point(100, 100)]), 1)
    out = subtract_patches(reach, grid)
    assert shapely.get_num_geometries(out[0, 0]) == 2
    assert shapely.intersects(out[0, 0], shapely.box(8, 1, 9, 2))


def test_patch_never_removes_own_footprint():
    foot = shapely.box(0, 0, 4, 2)
    grid = patch_grid([RulePatch(0, "r", shapely.box(-10, -10, 10, 10))], np.array([foot]), 2)
    assert shapely.area(shapely.intersection(grid.every[0], foot)) == pytest.approx(0.0)
    step = patch_grid(
        [RulePatch(0, "r", shapely.box(-10, -10, 10, 10), step=1)], np.array([foot]), 2
    )
    assert step.every[0] is None
    assert step.at[0, 0] is None
    assert shapely.area(shapely.intersection(step.at[0, 1], foot)) == pytest.approx(0.0)


def test_state_carries_track_geometry():
    inp = inputs(straight_ego(), objects((30.0, 0.0, 0.0, 5.0)), straight_track())
    _, s1 = evaluate_one(inp, ReachParams())
    _, s2 = evaluate_one(inp, ReachParams(), s1)
    assert s2.track is s1.track


def test_errors_are_typed():
    with pytest.raises(ParamsError):
        ReachParams(dt_s=0.0)
    with pytest.raises(InputShapeError):
        straight_ego(points=0)
    with pytest.raises(ZoneFileError):
        zones_from_json({"Centre": [[0, 0]], "Zone": [{"Type": 1, "ID": 1, "Start": 0, "End": 5}]})
    assert issubclass(ZoneFileError, ReachSetError)


def _alongside_scene(ego_y: float, obj_y: float, gap: float) -> ReachInputs:
    return inputs(
        straight_ego(y0=ego_y, speed=30.0), objects((gap, obj_y, 0.0, 30.0)), straight_track()
    )


def test_f1_alongside_leaves_the_ego_room():
    params = ReachParams()
    res, _ = evaluate_one(_alongside_scene(-3.0, 2.5, 1.0), params)
    assert any(p.rule == "f1.alongside" for p in res.patches)
    # the patch keeps the right-hand strip (ego side) free at every later step
    strip = shapely.box(20, -6.0, 60, -4.5)
    for k in range(5, 21):
        assert not shapely.intersects(res.reach_sets[0, k], strip)


def test_f1_not_alongside_without_overlap():
    res, _ = evaluate_one(_alongside_scene(-3.0, 2.5, 15.0), ReachParams())
    assert not any(p.rule == "f1.alongside" for p in res.patches)


def test_roborace_zones_replace_f1_and_patch_the_offence_side():
    track = straight_track()
    centre = np.stack([np.linspace(-100, 500, 61), np.zeros(61)], axis=1)
    zones = zones_from_json(
        {
            "Centre": centre.tolist(),
            "Zone": [
                {"Type": 1, "ID": 1, "Start": 0, "End": 60},
                {"Type": 2, "ID": 2, "Start": 10, "End": 50},
            ],
        }
    )
    # o0 closes in on the slower o1 inside the trigger zone -> offence
    objs = objects((30.0, 0.0, 0.0, 30.0), (60.0, 0.0, 0.0, 10.0))
    inp = ReachInputs(ego=straight_ego(speed=20.0), objects=objs, track=track, zones=zones)
    res, _ = evaluate_one(inp, ReachParams())
    rules = {(p.object_id, p.rule) for p in res.patches}
    assert ("o0", "roborace.offence") in rules
    assert not any(r.startswith("f1.") for _, r in rules)
    # offence in an overtake-left zone loses the right half
    assert not shapely.intersects(res.reach_sets[0, 10], shapely.box(100, -5, 110, -1))


def test_road_rules_fire_and_patch():
    road = two_lane_road()
    objs = objects((20.0, -2.0, 0.0, 14.0))
    inp = ReachInputs(ego=straight_ego(x0=0.0, y0=-2.0, speed=10.0), objects=objs, road=road)
    res, state = evaluate_one(inp, ReachParams())
    rules = {p.rule for p in res.patches}
    assert {"road.stay_on_road", "road.no_opposite", "road.speed_limit"} <= rules
    late = res.reach_sets[0, -1]
    assert not shapely.intersects(late, shapely.box(100, 1, 110, 3))  # opposite lane
    assert not shapely.intersects(late, shapely.box(100, -20, 110, -5))  # off road
    assert shapely.bounds(late)[2] < 20 + 4 * 16.5 + 10  # speed cap 16.5 m/s
    # once over the limit, never again assumed compliant (H below_limit)
    fast = ReachInputs(ego=inp.ego, objects=objects((20.0, -2.0, 0.0, 30.0)), road=road)
    _res2, state = evaluate_one(fast, ReachParams(), state)
    res3, _ = evaluate_one(inp, ReachParams(), state)
    assert "road.speed_limit" not in {p.rule for p in res3.patches}


def test_right_of_way_keeps_yielding_vehicle_out():
    x = np.linspace(-50, 100, 16)
    main = RoadLane(
        "main",
        np.concatenate(
            [np.stack([x, np.full_like(x, 2.0)], 1), np.stack([x[::-1], np.full_like(x, -2.0)], 1)]
        ),
        np.stack([x, np.zeros_like(x)], 1),
    )
    y = np.linspace(-80, -2, 10)
    side = RoadLane(
        "side",
        np.concatenate(
            [np.stack([np.full_like(y, 38.0), y], 1), np.stack([np.full_like(y, 42.0), y[::-1]], 1)]
        ),
        np.stack([np.full_like(y, 40.0), y], 1),
    )
    road = RoadLayout(lanes=(main, side), right_of_way=(RightOfWayRule(("main",), ("side",)),))
    objs = objects((40.0, -40.0, np.pi / 2, 8.0))
    inp = ReachInputs(ego=straight_ego(speed=15.0), objects=objs, road=road)
    res, _ = evaluate_one(inp, ReachParams())
    assert "road.right_of_way" in {p.rule for p in res.patches}
    assert res.is_safe


@pytest.mark.parametrize("method", list(ReachMethod))
@pytest.mark.parametrize(
    ("gap", "obj_y", "speed"), [(40.0, 0.0, 0.0), (1.0, 2.5, 30.0), (20.0, -3.0, 10.0)]
)
def test_verdict_mode_matches_full_geometry(method, gap, obj_y, speed):
    inp = inputs(
        straight_ego(y0=-2.0, speed=25.0), objects((gap, obj_y, 0.0, speed)), straight_track()
    )
    full, _ = evaluate_one(inp, ReachParams(method=method))
    fast, _ = evaluate_one(inp, ReachParams(method=method, full_geometry=False))
    assert full.collisions == fast.collisions


def _ring_track() -> TrackBounds:
    phi = np.linspace(0.0, 2 * np.pi, 200, endpoint=False)
    circle = np.stack([np.cos(phi), np.sin(phi)], axis=1)
    return TrackBounds(left_m=94.0 * circle, right_m=106.0 * circle)


def test_closed_track_wraps_around_the_start():
    """Reference defect: the closed-track branch compared unshifted arc lengths."""
    phi0 = -0.15
    t = np.linspace(0.0, 3.0, 30)
    ang = phi0 + 20.0 * t / 100.0
    ego = EgoTrajectory(
        x_m=100 * np.cos(ang),
        y_m=100 * np.sin(ang),
        yaw_rad=ang + np.pi / 2,
        speed_mps=np.full(30, 20.0),
        t_s=t,
    )
    objs = objects((100 * np.cos(0.1), 100 * np.sin(0.1), 0.1 + np.pi / 2, 0.0))
    res, state = evaluate_one(
        ReachInputs(ego=ego, objects=objs, track=_ring_track()), ReachParams()
    )
    assert state.track is not None
    assert state.track.closed
    assert list(res.object_ids) == ["o0"]
    assert not res.is_safe


def test_standing_vehicle_never_triggers_roborace():
    """Reference defect: the trigger time gap divided by a zero speed."""
    centre = np.stack([np.linspace(-100, 500, 61), np.zeros(61)], axis=1)
    zones = zones_from_json(
        {"Centre": centre.tolist(), "Zone": [{"Type": 1, "ID": 1, "Start": 0, "End": 60}]}
    )
    objs = objects((30.0, 0.0, 0.0, 0.0), (60.0, 0.0, 0.0, 0.0))
    inp = ReachInputs(
        ego=straight_ego(speed=0.0), objects=objs, track=straight_track(), zones=zones
    )
    res, _ = evaluate_one(inp, ReachParams())
    assert res.patches == ()


def test_reference_largest_part_mode_is_available():
    reach = np.array([[shapely.MultiPolygon([shapely.box(0, 0, 1, 1), shapely.box(5, 0, 9, 3)])]])
    out = keep_largest_part(reach)
    assert shapely.area(out[0, 0]) == pytest.approx(12.0)


def _drive(road: RoadLayout | None, track: TrackBounds | None) -> list[ReachInputs]:
    """Twelve frames: o0 drives ahead and speeds up, o1 leaves for two frames, o2 comes
    alongside the ego from the third frame."""
    frames = []
    for k in range(12):
        t = 0.1 * k
        rows = [(20.0 + 14.0 * t, -2.0, 0.0, 14.0 + 15.0 * t)]
        ids = ["o0"]
        if k not in (4, 5):
            rows.append((45.0 + 5.0 * t, 2.5 - 0.5 * t, np.pi if road else 0.0, 5.0))
            ids.append("o1")
        if k >= 3:
            rows.append((2.0 + 10.0 * t, 1.5, 0.0, 10.0))
            ids.append("o2")
        objs = objects(*rows)
        objs = type(objs)(np.array(ids), *(getattr(objs, f) for f in _FIELDS))
        ego = straight_ego(x0=10.0 * t, y0=-2.0, speed=10.0)
        frames.append(ReachInputs(ego=ego, objects=objs, road=road, track=track))
    return frames


_FIELDS = ("x_m", "y_m", "yaw_rad", "speed_mps", "length_m", "width_m")


@pytest.mark.parametrize("full", [True, False])
@pytest.mark.parametrize("method", list(ReachMethod))
@pytest.mark.parametrize("where", ["road", "track"])
def test_batched_frames_equal_frame_by_frame(where, method, full):
    road, track = (two_lane_road(), None) if where == "road" else (None, straight_track())
    frames = _drive(road, track)
    params = ReachParams(method=method, full_geometry=full)
    state = None
    one_by_one = []
    for inp in frames:
        res, state = evaluate_one(inp, params, state)
        one_by_one.append(res)
    assert state is not None
    # the batch starts from the state after the first two frames
    _, start = evaluate_one(frames[0], params)
    _, start = evaluate_one(frames[1], params, start)
    batched, end = evaluate_frames(frames[2:], params, start)
    assert [r.collisions for r in batched] == [r.collisions for r in one_by_one[2:]]
    assert [[(p.object_id, p.rule, p.step) for p in r.patches] for r in batched] == [
        [(p.object_id, p.rule, p.step) for p in r.patches] for r in one_by_one[2:]
    ]
    assert [r.skipped_ids for r in batched] == [r.skipped_ids for r in one_by_one[2:]]
    assert end.ltl == state.ltl
    assert any(r.patches for r in batched)
    assert any(not r.is_safe for r in batched)
