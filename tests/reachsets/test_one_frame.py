"""One frame per call: the scalar twins and the one-frame stacking against the batched path."""

from __future__ import annotations

import dataclasses

import numpy as np
import shapely
from hypothesis import given, settings
from hypothesis import strategies as st

from reachsets.batch import stack_frames
from reachsets.convex import convex_touch
from reachsets.footprints import rectangle_corners
from reachsets.params import ReachMethod, ReachParams
from reachsets.reach_simple import simple_reach_vertices
from reachsets.reachable import simple_vertices
from reachsets.track import build_track
from reachsets.verdict import first_hits
from tests.reachsets.helpers import inputs, objects, straight_ego, straight_track

TIMES = np.asarray(ReachParams().times_s)
_COORD = st.floats(-30.0, 30.0)


@settings(max_examples=120, deadline=None)
@given(
    st.lists(st.tuples(_COORD, st.floats(-8.0, 8.0), st.floats(-4.0, 4.0), st.floats(0.0, 60.0))),
    st.floats(-np.pi, np.pi),
    st.sampled_from([0.0, 0.5, 1.0]),
    st.booleans(),
)
def test_scalar_touch_equals_numpy(rows, ego_yaw, snap, poison):
    """Pair by pair and batched give the same booleans (touching and NaN vertices included)."""
    verts = simple_reach_vertices(objects(*rows), TIMES, 13.0) if rows else np.zeros((0, 21, 6, 2))
    ego = rectangle_corners(np.linspace(-20.0, 60.0, len(TIMES)), 0.0, ego_yaw, 4.7, 2.8)
    ego = np.round(ego / snap) * snap if snap else ego  # shared edges and corners
    if poison and len(verts):
        verts = verts.copy()
        verts[0, ::3, 2, 0] = np.nan
    ego_b = np.broadcast_to(ego, verts.shape[:2] + ego.shape[-2:])
    want = convex_touch(verts, ego_b, scalar=False)
    np.testing.assert_array_equal(convex_touch(verts, ego_b, scalar=True), want)
    np.testing.assert_array_equal(convex_touch(verts, ego[None], scalar=True), want)
    if poison and len(verts):
        assert want[0, ::3].all()  # a NaN projection never separates, as in numpy


def test_scalar_touch_counts_touching_edges_and_corners():
    square = np.array([[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]])
    for shift, touching in (((1.0, 0.0), True), ((1.0 + 1e-9, 0.0), False), ((1.0, 1.0), True)):
        assert bool(convex_touch(square, square + np.array(shift), scalar=True)) is touching


@settings(max_examples=60, deadline=None)
@given(
    st.lists(
        st.tuples(
            st.floats(-60.0, 120.0), st.floats(-9.0, 9.0), st.floats(-4.0, 4.0), st.floats(0, 60)
        ),
        max_size=5,
    ),
    st.floats(-3.0, 3.0),
    st.booleans(),
    st.booleans(),
)
def test_one_frame_stack_equals_batched(rows, ego_y, on_track, invalid):
    """The one-frame batch is the stacked batch's first frame, value for value."""
    if invalid and rows:
        rows[0] = (float("nan"), *rows[0][1:])
    objs = objects(*rows) if rows else objects()
    track = build_track(straight_track()) if on_track else None
    frame = inputs(straight_ego(x0=0.0, y0=ego_y, speed=12.0), objs)
    params = ReachParams()
    one = stack_frames([frame], params, track)
    two = stack_frames([frame, frame], params, track)
    n = len(one.objects)
    assert one.skipped_ids == two.skipped_ids[:1]
    assert list(one.offsets) == list(two.offsets[:2])
    for f in dataclasses.fields(one.objects):
        np.testing.assert_array_equal(
            getattr(one.objects, f.name), getattr(two.objects, f.name)[:n]
        )
    for name in ("s_obj_m", "lat_obj_m"):
        np.testing.assert_array_equal(getattr(one, name), getattr(two, name)[:n])
    for name in ("s_ego_m", "ego_x_m", "ego_y_m", "ego_yaw_rad", "ego_speed_mps", "ego_length_m"):
        np.testing.assert_array_equal(getattr(one, name), getattr(two, name)[:1])
    np.testing.assert_array_equal(one.occupancy.corners_m, two.occupancy.corners_m[:1])


@settings(max_examples=80, deadline=None)
@given(
    st.lists(
        st.tuples(
            st.floats(-500, 500), st.floats(-500, 500), st.floats(-4.0, 4.0), st.floats(0, 90)
        ),
        max_size=4,
    ),
    st.sampled_from(list(ReachMethod)),
)
def test_scalar_simple_sets_match_numpy(rows, method):
    """The scalar twin's ``simple`` vertices agree with numpy's within 1e-9 m."""
    objs = objects(*rows) if rows else objects()
    params = ReachParams(method=method)
    got = simple_vertices(objs, TIMES, params, scalar=True)
    want = simple_vertices(objs, TIMES, params, scalar=False)
    assert got.shape == want.shape == (len(rows), len(TIMES), 6, 2)
    np.testing.assert_allclose(got, want, rtol=0.0, atol=1e-9)


@settings(max_examples=40, deadline=None)
@given(
    st.lists(
        st.tuples(st.floats(-40, 60), st.floats(-6, 6), st.floats(-4.0, 4.0), st.floats(0, 40)),
        min_size=1,
        max_size=6,
    ),
    st.floats(-10.0, 30.0),
    st.floats(2.0, 12.0),
)
def test_first_hits_rounds_equal_cell_by_cell(rows, cut_x, area_half_width):
    """Rounds of 1, 2, 4, ... cells give each object's first reduced hit, cell by cell."""
    objs = objects(*rows)
    verts = simple_reach_vertices(objs, TIMES, 13.0)
    ego = rectangle_corners(np.linspace(0.0, 50.0, len(TIMES)), 0.0, 0.0, 4.7, 2.0)
    ego_m = np.broadcast_to(ego, (len(rows), *ego.shape))
    area = shapely.box(-100.0, -area_half_width, 200.0, area_half_width)
    cuts = np.array([shapely.box(cut_x, -3.0, cut_x + 8.0, 3.0)] * len(rows), dtype=object)
    got = first_hits(verts, ego_m, area=area, deletion=lambda r: cuts[r])
    for n in range(len(rows)):
        want = np.zeros(len(TIMES), dtype=bool)
        for k in range(len(TIMES)):
            part = shapely.difference(shapely.Polygon(verts[n, k]), cuts[n])
            cell = shapely.intersection(part, shapely.Polygon(ego[k]))
            if shapely.intersects(cell, area):
                want[k] = True
                break
        np.testing.assert_array_equal(got[n], want)
