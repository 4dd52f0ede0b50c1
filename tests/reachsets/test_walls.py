"""The block search of the nearest wall point (numpy, and the scalar kernel's grid search) and
the batched wall-aware curves agree bit for bit with their slow references."""

from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from reachsets import reach_bound, walls
from reachsets.inputs import TrackBounds
from reachsets.params import ReachMethod, ReachParams
from reachsets.reach_bound import wall_aware_arcs, wall_aware_arcs_reference
from reachsets.reach_turn import steering_arcs
from reachsets.track import build_track
from reachsets.walls import BLOCK_SEGMENTS, track_walls, wall_frame, wall_frame_reference
from tests.reachsets.helpers import objects

if TYPE_CHECKING:
    from reachsets.inputs import ObjectStates
    from reachsets.track import TrackGeometry


def _loop_track() -> TrackBounds:
    """A closed circuit: two half circles (radius 60 m) joined by 120 m straights, 12 m wide."""
    phi = np.linspace(-np.pi / 2, np.pi / 2, 31)
    right_turn = np.stack([60.0 + 60.0 * np.cos(phi), 60.0 * np.sin(phi)], 1)
    centre = np.concatenate(
        [
            np.stack([np.linspace(-60.0, 60.0, 25)[:-1], np.full(24, -60.0)], 1),
            right_turn[:-1],
            np.stack([np.linspace(60.0, -60.0, 25)[:-1], np.full(24, 60.0)], 1),
            np.stack([-right_turn[:-1, 0], -right_turn[:-1, 1]], 1),
        ]
    )
    centre = np.concatenate([centre, centre[:1]])
    tangent = np.gradient(centre, axis=0)
    normal = np.stack([-tangent[:, 1], tangent[:, 0]], 1) / np.hypot(*tangent.T)[:, None]
    return TrackBounds(centre + 6.0 * normal, centre - 6.0 * normal)


_WALLS = track_walls(build_track(_loop_track()))


def _assert_same(x: np.ndarray, y: np.ndarray, which: np.ndarray | int) -> None:
    """Both searches (numpy blocks, the scalar kernel's grid) equal the brute force."""
    want = wall_frame_reference(_WALLS, x, y, which)
    for scalar in (False, True):
        with pytest.MonkeyPatch.context() as patch:
            patch.setattr(walls, "SCALAR_SEARCH", scalar)
            got = wall_frame(_WALLS, x, y, which)
        for g, w in zip(got, want, strict=True):
            np.testing.assert_array_equal(g, w)


def test_grid_cells_reach_beyond_the_walls_and_far_positions_still_match():
    """Positions on the grid's cell borders, at its edge and far outside it (block search)."""
    lists = walls.wall_lists(_WALLS)
    x0, y0, cell = lists.grid[:3]
    nx, ny = lists.grid_n[:2]
    gx = x0 + cell * np.arange(nx + 1)
    gy = y0 + cell * np.arange(ny + 1)
    x = np.concatenate([gx, np.full(ny + 1, gx[nx // 2]), [x0 - 1.0, x0 + nx * cell, 5e3]])
    y = np.concatenate([np.full(nx + 1, gy[ny // 3]), gy, [y0, y0 - 0.5, -5e3]])
    left_x = _WALLS.start[0][_WALLS.seg_wall == 0]
    assert x0 < float(left_x.min()) - 50.0  # the grid reaches beyond its wall
    _assert_same(x, y, 0)


@settings(max_examples=60, deadline=None)
@given(
    seed=st.integers(0, 2**32 - 1),
    spread=st.sampled_from([0.5, 5.0, 40.0, 200.0]),
    mixed=st.booleans(),
)
def test_block_search_equals_brute_force(seed, spread, mixed):
    rng = np.random.default_rng(seed)
    n = int(rng.integers(1, 300))  # above 128 positions of both walls: split by wall
    pick = rng.integers(0, len(_WALLS.pts), n)
    x = _WALLS.pts[pick, 0] + rng.normal(0.0, spread, n)
    y = _WALLS.pts[pick, 1] + rng.normal(0.0, spread, n)
    which = rng.integers(0, 2, n) if mixed else int(rng.integers(0, 2))
    _assert_same(x, y, which)


@pytest.mark.parametrize("which", [0, 1])
def test_ties_pick_the_same_segment(which):
    """Vertices (two segments equally near), the loop's centres (a whole arc equally near)."""
    x = np.concatenate([_WALLS.pts[:, 0], [60.0, -60.0, 0.0]])
    y = np.concatenate([_WALLS.pts[:, 1], [0.0, 0.0, 0.0]])
    _assert_same(x, y, which)
    _assert_same(x, y, np.full(len(x), which))


def test_blocks_cover_each_wall_once():
    own = _WALLS.seg_wall[_WALLS.blk_seg[:-1]]
    assert (own == _WALLS.blk_wall[:-1, None]).all()
    assert np.array_equal(np.unique(_WALLS.blk_seg[:-1]), np.arange(len(_WALLS.seg_len)))
    assert (np.diff(_WALLS.blk_seg, axis=1) >= 0).all()
    assert _WALLS.blk_seg.shape[1] == BLOCK_SEGMENTS


def test_non_finite_positions_fall_back_to_the_reference():
    x = np.concatenate([[np.nan], np.linspace(-50.0, 50.0, 9)])
    y = np.full(10, -66.0)
    _assert_same(x, y, 1)
    assert np.isfinite(wall_frame(_WALLS, x, y, 1)[0][1:]).all()


def _objects_on_loop(track: TrackGeometry, rng: np.random.Generator, n: int) -> ObjectStates:
    pick = rng.integers(0, len(track.centre_m), n)
    lat = rng.uniform(-7.0, 7.0, n)
    tangent = np.gradient(track.centre_m, axis=0)[pick]
    rows = zip(
        track.centre_m[pick, 0] + track.normal[pick, 0] * lat,
        track.centre_m[pick, 1] + track.normal[pick, 1] * lat,
        np.arctan2(tangent[:, 1], tangent[:, 0]) + rng.normal(0.0, 0.4, n),
        rng.uniform(0.0, 60.0, n),
        strict=True,
    )
    return objects(*rows)


_LOOP = build_track(_loop_track())


@pytest.mark.parametrize("scalar_search", [False, True])
def test_wall_aware_arcs_equal_the_curve_by_curve_reference(monkeypatch, scalar_search):
    """Objects across and beside the loop's walls, slow to fast: every curve bit for bit
    (numpy or compiled wall search)."""
    monkeypatch.setattr(walls, "SCALAR_SEARCH", scalar_search)
    monkeypatch.setattr(reach_bound, "SCALAR_SEARCH", scalar_search)
    track = _LOOP
    objs = _objects_on_loop(track, np.random.default_rng(11), 40)
    params = ReachParams(method=ReachMethod.BOUND)
    got = wall_aware_arcs(objs, params, track, scalar=False)
    want = wall_aware_arcs_reference(objs, params, track)
    for g_side, w_side in zip(got, want, strict=True):
        for g, w in zip(g_side, w_side, strict=True):
            np.testing.assert_array_equal(g, w)
    # the case is not trivial: many curves leave their turn arc
    left_turn = steering_arcs(objs, params, 1.0)
    left_eta = got[0][1]
    assert np.any(np.abs(left_eta - left_turn[1]) > 0.1, axis=1).sum() >= 5


@settings(max_examples=80, deadline=None)
@given(seed=st.integers(0, 2**32 - 1), n=st.integers(1, 8))
def test_scalar_curves_equal_the_vectorised_ones(seed, n):
    """The scalar twin (few objects, one frame) against the numpy path and the reference."""
    objs = _objects_on_loop(_LOOP, np.random.default_rng(seed), n)
    params = ReachParams(method=ReachMethod.BOUND)
    scalar = wall_aware_arcs(objs, params, _LOOP, scalar=True)
    vector = wall_aware_arcs(objs, params, _LOOP, scalar=False)
    reference = wall_aware_arcs_reference(objs, params, _LOOP)
    for s_side, v_side, r_side in zip(scalar, vector, reference, strict=True):
        for s, v, r in zip(s_side, v_side, r_side, strict=True):
            np.testing.assert_allclose(s, v, rtol=0.0, atol=1e-9)
            np.testing.assert_allclose(s, r, rtol=0.0, atol=1e-9)


def test_scalar_curves_turn_back_like_the_vectorised_ones():
    """Many seeds at once: the scalar curves leave their turn arc where the numpy ones do."""
    objs = _objects_on_loop(_LOOP, np.random.default_rng(5), 6)
    params = ReachParams(method=ReachMethod.BOUND)
    left_turn = steering_arcs(objs, params, 1.0)
    scalar = wall_aware_arcs(objs, params, _LOOP, scalar=True)
    vector = wall_aware_arcs(objs, params, _LOOP, scalar=False)
    moved_s = np.any(np.abs(scalar[0][1] - left_turn[1]) > 0.1, axis=1)
    moved_v = np.any(np.abs(vector[0][1] - left_turn[1]) > 0.1, axis=1)
    assert moved_s.any()
    assert np.array_equal(moved_s, moved_v)
