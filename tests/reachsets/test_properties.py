"""Hypothesis properties of the reachable sets and the rule patches."""

from __future__ import annotations

import dataclasses

import numpy as np
import shapely
from hypothesis import given, settings
from hypothesis import strategies as st

from reachsets.footprints import rectangles
from reachsets.params import ReachMethod, ReachParams
from reachsets.reach_simple import simple_reach_polygons
from reachsets.reachable import reachable_sets
from tests.reachsets.helpers import evaluate_one, inputs, objects, straight_ego, straight_track

TIMES = np.asarray(ReachParams().times_s)
SLACK = 1e-6
SWING_M = 0.05

speeds = st.floats(0.0, 70.0)
yaws = st.floats(-np.pi, np.pi)
accels = st.floats(1.0, 15.0)


@settings(max_examples=60, deadline=None)
@given(speeds, yaws, accels, st.floats(0.1, 10.0))
def test_simple_sets_grow_with_the_acceleration_bound(v0, yaw, a, extra):
    objs = objects((1.0, 2.0, yaw, v0))
    small = simple_reach_polygons(objs, TIMES, a)
    large = simple_reach_polygons(objs, TIMES, a + extra)
    leftover = shapely.area(shapely.difference(small, shapely.buffer(large, SLACK)))
    assert np.all(leftover < 1e-6)


@settings(max_examples=60, deadline=None)
@given(speeds, yaws, accels)
def test_simple_sets_cover_growing_time_horizons(v0, yaw, a):
    """The union up to t_k grows with k and covers the current footprint."""
    objs = objects((0.0, 0.0, yaw, v0))
    sets = simple_reach_polygons(objs, TIMES, a)[0]
    foot = rectangles(objs.x_m, objs.y_m, objs.yaw_rad, objs.length_m, objs.width_m)[0]
    assert shapely.area(shapely.difference(foot, shapely.buffer(sets[1], SLACK))) < 1e-6
    for k in range(2, len(TIMES)):
        assert shapely.area(sets[k]) >= shapely.area(sets[k - 1]) - 1e-6


@settings(max_examples=40, deadline=None)
@given(
    st.floats(5.0, 60.0),
    st.floats(-1.0, 1.0),
    st.floats(-0.03, 0.03),
    st.sampled_from(list(ReachMethod)),
)
def test_sets_contain_true_future_position(v0, accel_frac, curvature, method):
    """A car whose motion stays within the limits is inside its set at every step.

    Holds for the sound ``keep_object_body`` variant (the reference's deletion polygon
    removes the body). ``turn``/``bound`` funnels run straight along the body sides, so the
    few centimetres a body side swings out while the car turns are tolerated (``SWING_M``).
    """
    params = ReachParams(
        method=method, trim_to_drivable=False, rules_enabled=False, keep_object_body=True
    )
    a_lon = accel_frac * 6.0
    a_lat_ok = abs(curvature) * (v0 + 6.0 * 4.0) ** 2
    if a_lat_ok > 12.0 or 1 / max(abs(curvature), 1e-9) < params.turn_radius_m:
        curvature = 0.0
    objs = objects((0.0, 0.0, 0.3, v0))
    sets = reachable_sets(objs, TIMES, params, None)[0]
    # kinematic model about the rear axle (1.4 m behind the centre); step k covers [t_{k-1}, t_k]
    dt, d_axle = 0.01, 1.4
    tol = 1e-6 if method == ReachMethod.SIMPLE else SWING_M
    yaw, v = 0.3, v0
    px, py = -d_axle * np.cos(yaw), -d_axle * np.sin(yaw)
    for k in range(1, len(TIMES)):
        for _ in range(21 if k == 1 else 20):
            cx, cy = px + d_axle * np.cos(yaw), py + d_axle * np.sin(yaw)
            foot = rectangles(cx, cy, yaw, 4.7 * 0.99, 2.0 * 0.99)
            assert shapely.covered_by(foot, shapely.buffer(sets[k], tol)), k
            px += np.cos(yaw) * v * dt
            py += np.sin(yaw) * v * dt
            yaw += curvature * v * dt
            v = max(v + a_lon * dt, 0.0)


@settings(max_examples=30, deadline=None)
@given(st.floats(-4.0, 4.0), st.floats(-3.0, 3.0), st.floats(0.0, 45.0), st.floats(5.0, 45.0))
def test_patches_never_remove_the_objects_footprint(obj_y, ego_y, gap, speed):
    objs = objects((gap, obj_y, 0.0, speed))
    inp = inputs(straight_ego(y0=ego_y, speed=speed), objs, straight_track())
    params = ReachParams(trim_to_drivable=False)
    res, _ = evaluate_one(inp, params)
    if len(res.object_ids) == 0:
        return
    foot = rectangles(objs.x_m, objs.y_m, objs.yaw_rad, objs.length_m, objs.width_m)[0]
    plain, _ = evaluate_one(inp, dataclasses.replace(params, rules_enabled=False))
    # whatever of the footprint the unruled set holds, the ruled set still holds
    before = shapely.intersection(plain.reach_sets[0, 1], foot)
    after = shapely.intersection(res.reach_sets[0, 1], foot)
    assert abs(shapely.area(before) - shapely.area(after)) < 1e-6
