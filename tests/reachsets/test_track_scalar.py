"""One-frame closed forms: ``track_scalar`` against numpy, ``settled`` against GEOS."""

from __future__ import annotations

from typing import Any
from unittest import mock

import numpy as np
import shapely
from hypothesis import given, settings
from hypothesis import strategies as st

from reachsets import track as track_module
from reachsets.clip_cells import settled
from reachsets.clip_rings import Edges, dedup
from reachsets.inputs import TrackBounds
from reachsets.params import ReachMethod, ReachParams
from reachsets.reachable import deletion_coords, simple_vertices
from reachsets.track import SCALAR_POINTS_MAX, build_track
from tests.reachsets.helpers import objects

_PAD = SCALAR_POINTS_MAX + 1  # more positions than that: lateral_m's numpy path


def _numpy_project(track: Any, x: np.ndarray, y: np.ndarray) -> np.ndarray:
    """``track.project`` on its numpy path (compiled, it always goes point by point)."""
    with mock.patch.object(track_module, "SCALAR_PROJECT", False):
        return np.asarray(track.project(x, y))


def _wavy_track(amp_m: float, closed: bool) -> TrackBounds:
    if closed:
        a = np.linspace(0.0, 2 * np.pi, 200)
        r = 80.0 + amp_m * np.sin(3 * a)
        left = np.stack([(r + 6) * np.cos(a), (r + 6) * np.sin(a)], 1)
        right = np.stack([(r - 6) * np.cos(a), (r - 6) * np.sin(a)], 1)
        return TrackBounds(left_m=left, right_m=right)
    x = np.linspace(-100.0, 300.0, 90)
    y = amp_m * np.sin(x / 40.0)
    return TrackBounds(left_m=np.stack([x, y + 6], 1), right_m=np.stack([x, y - 6], 1))


@settings(max_examples=60, deadline=None)
@given(
    st.lists(st.tuples(st.floats(-150.0, 350.0), st.floats(-120.0, 120.0)), min_size=1, max_size=8),
    st.floats(0.0, 30.0),
    st.booleans(),
)
def test_scalar_project_and_lateral_equal_numpy(points, amp_m, closed):
    """Bit-identical arc lengths and lateral offsets, point by point and in numpy."""
    track = build_track(_wavy_track(amp_m, closed))
    xy = np.array(points, dtype=float)
    x, y = xy[:, 0], xy[:, 1]
    n = len(x)
    pad_x = np.concatenate([x, np.full(_PAD, x[0])])
    pad_y = np.concatenate([y, np.full(_PAD, y[0])])
    s = track.project(x, y)
    np.testing.assert_array_equal(s, _numpy_project(track, x, y))
    np.testing.assert_array_equal(s, track.project(pad_x, pad_y)[:n])
    s_pad = np.concatenate([s, np.full(_PAD, s[0])])
    np.testing.assert_array_equal(
        track.lateral_m(x, y, s), track.lateral_m(pad_x, pad_y, s_pad)[:n]
    )


def test_scalar_project_leaves_non_finite_to_numpy():
    """A NaN position goes the numpy way (its result is the numpy one, not an error)."""
    track = build_track(_wavy_track(5.0, False))
    x, y = np.array([10.0, np.nan]), np.array([0.0, 1.0])
    got = track.project(x, y)
    assert got.shape == (2,)
    assert got[0] == track.project(np.array([10.0]), np.array([0.0]))[0]


@settings(max_examples=80, deadline=None)
@given(
    st.lists(
        st.tuples(st.floats(-50, 50), st.floats(-50, 50), st.floats(-3.2, 3.2), st.floats(0, 60)),
        min_size=1,
        max_size=3,
    ),
    st.sampled_from([ReachMethod.TURN, ReachMethod.BOUND]),
    st.integers(0, 20),
)
def test_settled_is_geos_difference(rows, method, step):
    """Where ``settled`` answers, it is GEOS' ``cell - deletion`` (area and boundary, 1e-9)."""
    objs = objects(*rows)
    params = ReachParams(method=method)
    times = params.times_array_s
    verts = simple_vertices(objs, times, params)
    cut = deletion_coords(objs, params, None)
    assert cut is not None
    for i in range(len(objs)):
        ring = dedup(cut[i].ravel().tolist())
        cell = verts[i, step].ravel().tolist()
        got = settled(cell, Edges(ring))
        if got is None:
            continue
        want = shapely.difference(
            shapely.Polygon(verts[i, step]), shapely.make_valid(shapely.Polygon(cut[i]))
        )
        mine = shapely.union_all([shapely.Polygon(np.reshape(r, (-1, 2))) for r in got])
        assert abs(shapely.area(mine) - shapely.area(want)) < 1e-9
        assert shapely.area(shapely.symmetric_difference(mine, want)) < 1e-9


def test_settled_closes_step_zero_and_gives_up_on_crossings():
    """Step 0: the body lies in its deletion polygon (empty); a crossing edge: no answer."""
    objs = objects((10.0, 5.0, 0.3, 20.0))
    params = ReachParams(method=ReachMethod.TURN)
    verts = simple_vertices(objs, params.times_array_s, params)
    cut = deletion_coords(objs, params, None)
    assert cut is not None
    ring = Edges(dedup(cut[0].ravel().tolist()))
    assert settled(verts[0, 0].ravel().tolist(), ring) == []
    square = [0.0, 0.0, 2.0, 0.0, 2.0, 2.0, 0.0, 2.0]
    assert settled(square, Edges([1.0, 1.0, 5.0, 1.0, 5.0, 5.0])) is None
    far = Edges([10.0, 10.0, 12.0, 10.0, 12.0, 12.0])
    assert settled(square, far) == [square]


def test_scalar_project_ties_and_points_on_the_centre_line():
    """Equidistant centre points (a circle's middle) and points on the line itself: the
    skipped blocks of ``track_scalar._nearest`` never change numpy's first ``argmin``.
    """
    for amp_m in (0.0, 20.0):
        track = build_track(_wavy_track(amp_m, closed=True))
        c = track.centre_m
        x = np.concatenate([[0.0, 1e-9, -3.0], c[::37, 0], (c[:-1:53, 0] + c[1::53, 0]) / 2])
        y = np.concatenate([[0.0, 0.0, 2.0], c[::37, 1], (c[:-1:53, 1] + c[1::53, 1]) / 2])
        for i in range(len(x)):
            pad_x = np.full(_PAD + 1, x[i])
            pad_y = np.full(_PAD + 1, y[i])
            np.testing.assert_array_equal(
                track.project(x[i : i + 1], y[i : i + 1]), _numpy_project(track, pad_x, pad_y)[:1]
            )
