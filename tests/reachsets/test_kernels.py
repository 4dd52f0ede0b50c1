"""Fast kernels against their slow scalar references, and the fixed reference defects."""

from __future__ import annotations

import math

import numpy as np
import pytest
import shapely
from hypothesis import given, settings
from hypothesis import strategies as st

from reachsets.convex import convex_touch
from reachsets.footprints import rectangle_corners
from reachsets.inputs import TrackBounds
from reachsets.occupancy import (
    ego_occupancy,
    ego_occupancy_many,
    ego_occupancy_scalar,
    trajectory_times,
)
from reachsets.params import ReachParams
from reachsets.reach_simple import simple_reach_polygons, simple_reach_scalar, simple_reach_vertices
from reachsets.reach_turn import funnel_coords, steering_arc_scalar, steering_arcs
from reachsets.track import build_track
from tests.reachsets.helpers import objects, straight_ego

TIMES = np.asarray(ReachParams().times_s)


def test_grid_has_21_stamps():
    params = ReachParams()
    assert params.n_steps == 21
    assert params.times_s[-1] == pytest.approx(4.0)


@pytest.mark.parametrize("v0", [0.0, 0.5, 12.0, 40.0, 70.0])
def test_simple_vectorised_matches_scalar(v0):
    objs = objects((3.0, -2.0, 0.7, v0), (10.0, 5.0, -2.5, v0 / 2))
    verts = simple_reach_vertices(objs, TIMES, 13.0)
    for i in range(len(objs)):
        ref = simple_reach_scalar(
            float(objs.x_m[i]),
            float(objs.y_m[i]),
            float(objs.yaw_rad[i]),
            float(objs.speed_mps[i]),
            length_m=4.7,
            width_m=2.0,
            times_s=list(TIMES),
            a_max_mps2=13.0,
        )
        np.testing.assert_allclose(verts[i], np.asarray(ref), atol=1e-9)


def test_simple_matches_documented_example():
    # notes: v0 = 40 m/s, a = 13 m/s^2, t = 1 s -> front 46.5 m, half-width 6.5 m
    objs = objects((0.0, 0.0, 0.0, 40.0), length=0.0 + 1e-9, width=1e-9)
    verts = simple_reach_vertices(objs, np.array([0.0, 1.0]), 13.0)
    q = verts[0, 1]
    assert q[2, 0] == pytest.approx(46.5, abs=1e-6)
    assert q[2, 1] == pytest.approx(6.5, abs=1e-6)


def test_standing_object_gives_finite_valid_polygons():
    """Reference defect: v0 = 0 divided by zero and produced NaN polygons."""
    polys = simple_reach_polygons(objects((0.0, 0.0, 0.0, 0.0)), TIMES, 13.0)
    assert np.all(np.isfinite(shapely.get_coordinates(polys)))
    assert np.all(shapely.is_valid(polys))
    assert shapely.area(polys[0, -1]) > shapely.area(polys[0, 0])


def test_no_reversing_rear_never_moves_back():
    verts = simple_reach_vertices(objects((0.0, 0.0, 0.0, 5.0)), TIMES, 13.0)
    rear = verts[0, :, 0, 0]
    assert np.all(np.diff(rear) >= -1e-12)


@pytest.mark.parametrize("side", [1.0, -1.0])
@pytest.mark.parametrize("v0", [0.0, 8.0, 30.0, 60.0])
def test_steering_arcs_match_scalar(side, v0):
    params = ReachParams()
    objs = objects((0.0, 0.0, 0.0, v0))
    xi, eta = steering_arcs(objs, params, side)
    ref = np.asarray(steering_arc_scalar(v0, 4.7, 2.0, params, side))
    np.testing.assert_allclose(np.stack([xi[0], eta[0]], axis=1), ref, atol=1e-9)


def test_arc_chord_offset_is_c2_over_2r():
    params = ReachParams()
    _xi, eta = steering_arcs(objects((0.0, 0.0, 0.0, 0.0)), params, 1.0)
    # first chord at turn radius 11 m: lateral offset c^2 / (2 r)
    assert eta[0, 1] - eta[0, 0] == pytest.approx(3.0**2 / (2 * 11.0), rel=1e-9)


@pytest.mark.parametrize("keep_body", [True, False])
def test_funnel_body_handling_and_validity(keep_body):
    """The sound variant keeps the footprint; the reference deletes all behind the front."""
    params = ReachParams()
    objs = objects((5.0, 1.0, 0.3, 0.0), (0.0, 0.0, -1.0, 45.0))
    left = steering_arcs(objs, params, 1.0)
    right = steering_arcs(objs, params, -1.0)
    funnel = shapely.polygons(funnel_coords(objs, left, right, keep_body=keep_body))
    assert np.all(shapely.is_valid(funnel))
    body = simple_reach_polygons(objs, np.array([0.0]), 13.0)[:, 0]
    overlap = shapely.area(shapely.intersection(funnel, body))
    expected = 0.0 if keep_body else shapely.area(body)
    np.testing.assert_allclose(overlap, expected, atol=1e-6)


def test_occupancy_matches_scalar_and_holds_last_pose():
    ego = straight_ego(speed=12.0, horizon=3.0)
    occ = ego_occupancy(ego, TIMES)
    ref = ego_occupancy_scalar(ego, list(TIMES))
    np.testing.assert_allclose(
        shapely.get_coordinates(occ.polygons).reshape(len(TIMES), 5, 2)[:, :4], np.asarray(ref)
    )
    assert occ.x_m[-1] == pytest.approx(36.0)


def test_trajectory_timing_from_speeds_floors_standstill():
    ego = straight_ego(speed=10.0)
    timed = type(ego)(
        ego.x_m, ego.y_m, ego.yaw_rad, np.r_[np.linspace(10, 0, 29), 0.0], np.full(30, np.nan)
    )
    t = trajectory_times(timed)
    assert t[0] == 0.0
    assert np.all(np.diff(t) > 0)
    assert t[-1] > 100.0  # last segment timed at the 0.01 m/s floor (reference behaviour)
    ref = ego_occupancy_scalar(timed, list(TIMES))
    got = shapely.get_coordinates(ego_occupancy(timed, TIMES).polygons).reshape(-1, 5, 2)[:, :4]
    np.testing.assert_allclose(got, np.asarray(ref), atol=1e-9)


def test_heading_interpolation_takes_the_short_way():
    ego = straight_ego(points=2, horizon=1.0)
    wrapped = type(ego)(
        ego.x_m, ego.y_m, np.array([math.pi - 0.1, -math.pi + 0.1]), ego.speed_mps, ego.t_s
    )
    occ = ego_occupancy(wrapped, np.array([0.5]))
    assert abs(math.cos(occ.yaw_rad[0]) + 1) < 1e-9


@settings(max_examples=80, deadline=None)
@given(
    st.floats(-25.0, 25.0),
    st.floats(-8.0, 8.0),
    st.floats(-np.pi, np.pi),
    st.floats(0.0, 60.0),
    st.floats(-np.pi, np.pi),
)
def test_convex_touch_matches_shapely(x, y, yaw, v0, ego_yaw):
    """The numpy separating-axis test agrees with ``shapely.intersects`` on simple sets."""
    verts = simple_reach_vertices(objects((x, y, yaw, v0)), TIMES, 13.0)
    ego = rectangle_corners(np.linspace(-20.0, 60.0, len(TIMES)), 0.0, ego_yaw, 4.7, 2.8)
    got = convex_touch(verts, ego[None])
    want = shapely.intersects(shapely.polygons(verts), shapely.polygons(ego)[None])
    np.testing.assert_array_equal(got, want)


def test_convex_touch_counts_touching_edges():
    square = np.array([[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]])
    assert convex_touch(square, square + np.array([1.0, 0.0]))
    assert not convex_touch(square, square + np.array([1.0 + 1e-9, 0.0]))
    assert convex_touch(square, square + np.array([1.0, 1.0]))  # one shared corner


def test_track_projection_matches_shapely():
    # a straight, a 90 degree left-hander of 60 m radius, a straight; 12 m wide
    phi = np.linspace(0.0, np.pi / 2, 40)
    centre = np.concatenate(
        [
            np.stack([np.linspace(-100.0, 0.0, 21), np.full(21, -60.0)], 1)[:-1],
            np.stack([60.0 * np.sin(phi), -60.0 * np.cos(phi)], 1),
            np.stack([np.full(20, 60.0), np.linspace(0.0, 100.0, 21)[1:]], 1),
        ]
    )
    tangent = np.gradient(centre, axis=0)
    normal = np.stack([-tangent[:, 1], tangent[:, 0]], 1) / np.hypot(*tangent.T)[:, None]
    track = build_track(TrackBounds(centre + 6.0 * normal, centre - 6.0 * normal))
    rng = np.random.default_rng(3)
    pick = rng.integers(0, len(track.centre_m), 200)
    x = track.centre_m[pick, 0] + rng.uniform(-8.0, 8.0, 200)
    y = track.centre_m[pick, 1] + rng.uniform(-8.0, 8.0, 200)
    want = [track.project_scalar(a, b) for a, b in zip(x, y, strict=True)]
    np.testing.assert_allclose(track.project(x, y), want, atol=1e-6)


def test_occupancy_of_many_plans_of_different_lengths_matches_scalar():
    """Plans padded to one length (last point held) give each plan's own footprints."""
    short = straight_ego(speed=12.0, horizon=2.0, points=7)
    turning = type(short)(
        np.linspace(0.0, 30.0, 12),
        np.linspace(0.0, 8.0, 12) ** 1.5,
        np.linspace(0.2, 3.0, 12),
        np.linspace(15.0, 0.0, 12),
        np.full(12, np.nan),
        5.0,
        2.0,
    )
    single = straight_ego(points=1)
    occ = ego_occupancy_many([short, turning, single], TIMES)
    for f, plan in enumerate([short, turning, single]):
        want = np.asarray(ego_occupancy_scalar(plan, list(TIMES)))
        np.testing.assert_allclose(occ.corners_m[f], want, atol=1e-9)


@settings(max_examples=80, deadline=None)
@given(
    seed=st.integers(0, 2**32 - 1),
    points=st.integers(2, 40),
    timed=st.booleans(),
    stop=st.booleans(),
)
def test_one_frame_occupancy_equals_the_stacked_one(seed, points, timed, stop):
    """The one-frame scalar twin gives the many-frame numpy path's poses and corners bit for bit
    (random plans: wrapping headings, stamps given or derived, ending at standstill or not)."""
    rng = np.random.default_rng(seed)
    speed = rng.uniform(0.0, 60.0, points)
    if stop:
        speed[-1] = 0.0
    t_s = np.cumsum(rng.uniform(0.0, 0.4, points)) if timed else np.full(points, np.nan)
    plan = type(straight_ego())(
        np.cumsum(rng.normal(0.0, 5.0, points)),
        np.cumsum(rng.normal(0.0, 5.0, points)),
        rng.uniform(-4.0, 4.0, points),  # beyond +-pi: unwrapped
        speed,
        t_s,
        float(rng.uniform(3.0, 6.0)),
        float(rng.uniform(1.5, 2.5)),
    )
    one = ego_occupancy_many([plan], TIMES)
    stacked = ego_occupancy_many([plan, straight_ego()], TIMES)
    for name in ("x_m", "y_m", "yaw_rad", "corners_m"):
        np.testing.assert_array_equal(getattr(one, name)[0], getattr(stacked, name)[0])
    want = np.asarray(ego_occupancy_scalar(plan, list(TIMES)))
    np.testing.assert_allclose(one.corners_m[0], want, atol=1e-6)
