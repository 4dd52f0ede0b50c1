"""The compiled clipper (``clip_scalar``) and the full sets it builds against GEOS."""

from __future__ import annotations

import numpy as np
import pytest
import shapely
from hypothesis import given, settings
from hypothesis import strategies as st

from reachsets.clip_cells import Area, _near, clip, reduce_cells
from reachsets.clip_rings import Edges
from reachsets.inputs import TrackBounds
from reachsets.params import ReachMethod, ReachParams
from reachsets.reachable import reachable_sets
from reachsets.reduce import _assemble, _rings
from reachsets.track import build_track
from tests.reachsets.helpers import objects, same_sets

TIMES = np.asarray(ReachParams().times_s)
#: The stated bound: same area within 1e-9 m2, boundaries within 1e-9 m (Hausdorff).
TOL = 1e-9


def _star(draw: st.DrawFn, centre: tuple[float, float], n_max: int) -> np.ndarray:
    """A simple polygon: vertices at increasing angles around ``centre``."""
    n = draw(st.integers(3, n_max))
    ang = np.sort(draw(st.lists(st.floats(0.0, 2 * np.pi), min_size=n, max_size=n, unique=True)))
    rad = np.array(draw(st.lists(st.floats(0.3, 6.0), min_size=n, max_size=n)))
    ring = np.stack([centre[0] + rad * np.cos(ang), centre[1] + rad * np.sin(ang)], axis=1)
    return ring[::-1] if draw(st.booleans()) else ring


@st.composite
def _pairs(draw: st.DrawFn) -> tuple[np.ndarray, np.ndarray]:
    a = _star(draw, (0.0, 0.0), 12)
    if draw(st.booleans()):  # convex, like the simple sets
        a = np.asarray(shapely.convex_hull(shapely.multipoints(a)).exterior.coords)[:-1]
    centre = (draw(st.floats(-6.0, 6.0)), draw(st.floats(-6.0, 6.0)))
    return a, _star(draw, centre, 40)


def _same(got: list[list[float]], want: shapely.Geometry) -> None:
    """``got`` (rings) is ``want`` as a point set, within ``TOL``."""
    parts = [shapely.Polygon(np.reshape(r, (-1, 2))) for r in got]
    geom = shapely.MultiPolygon(parts) if parts else shapely.Polygon()
    assert geom.is_valid
    assert len(parts) == (0 if want.is_empty else shapely.get_num_geometries(want))
    assert abs(geom.area - want.area) <= TOL
    if parts:
        assert shapely.hausdorff_distance(geom.boundary, want.boundary) <= TOL


def _ill_conditioned(p: np.ndarray) -> bool:
    """An edge shorter than 1e-8 of the extent, or a vertex folding its edges back (a spike)."""
    e = np.roll(p, -1, axis=0) - p
    length = np.hypot(*e.T)
    if (length < 1e-8 * np.ptp(p, axis=0).sum()).any():
        return True
    prev = np.roll(e, 1, axis=0)
    sin = (prev[:, 0] * e[:, 1] - prev[:, 1] * e[:, 0]) / (length * np.roll(length, 1))
    return bool(((np.abs(sin) < 1e-8) & ((prev * e).sum(axis=1) < 0)).any())


def _near_contact(a: np.ndarray, b: np.ndarray) -> bool:
    """A vertex of one polygon near the other's boundary, or nearly parallel edges close by."""
    if _ill_conditioned(a) or _ill_conditioned(b):
        return True
    ra, rb = shapely.LinearRing(a), shapely.LinearRing(b)
    if (
        min(
            shapely.distance(shapely.points(a), rb).min(),
            shapely.distance(shapely.points(b), ra).min(),
        )
        < 1e-6
    ):
        return True
    ea, eb = np.roll(a, -1, axis=0) - a, np.roll(b, -1, axis=0) - b
    cross = ea[:, None, 0] * eb[None, :, 1] - ea[:, None, 1] * eb[None, :, 0]
    sin = cross / np.outer(np.hypot(*ea.T), np.hypot(*eb.T))
    segs_a = shapely.linestrings(np.stack([a, np.roll(a, -1, axis=0)], axis=1))
    segs_b = shapely.linestrings(np.stack([b, np.roll(b, -1, axis=0)], axis=1))
    close = shapely.distance(segs_a[:, None], segs_b[None]) < 1e-6
    return bool((close & (np.abs(sin) < 1e-8)).any())


@settings(max_examples=300, deadline=None)
@given(_pairs(), st.booleans())
def test_clip_equals_geos(pair, difference):
    """Intersection and difference of simple polygons: GEOS' geometry, or ``None``."""
    a, b = pair
    pa, pb = shapely.Polygon(a), shapely.Polygon(b)
    if not (pa.is_valid and pb.is_valid):
        return
    got = clip(a.ravel().tolist(), b.ravel().tolist(), difference)
    want = shapely.difference(pa, pb) if difference else shapely.intersection(pa, pb)
    if got is None:  # a hole, or a contact that needs GEOS' robust predicates
        assert (difference and pb.within(pa)) or _near_contact(a, b)
        return
    _same(got, want)


def test_clip_gives_up_on_touching_edges_and_holes():
    square = [0.0, 0.0, 2.0, 0.0, 2.0, 2.0, 0.0, 2.0]
    assert clip(square, [2.0, 0.5, 3.0, 0.5, 3.0, 1.5, 2.0, 1.5], False) is None  # shared edge
    assert clip(square, [2.0, 1.0, 3.0, 0.5, 3.0, 1.5], True) is None  # vertex on the edge
    assert clip(square, [0.5, 0.5, 1.5, 0.5, 1.0, 1.5], True) is None  # a hole
    assert clip(square, [0.5, 0.5, 1.5, 0.5, 1.0, 1.5], False) == [[0.5, 0.5, 1.5, 0.5, 1.0, 1.5]]
    assert clip(square, [5.0, 5.0, 6.0, 5.0, 6.0, 6.0], True) == [square]
    assert reduce_cells([square], [], None) == [[square]]
    assert reduce_cells([square], [], Area([-1.0, -1.0, 3.0, -1.0, 3.0, 3.0, -1.0, 3.0], [])) == [
        [square]
    ]


def test_clip_splits_into_parts():
    """A bar across a square leaves two parts; repeated vertices are dropped first."""
    square = [0.0, 0.0, 2.0, 0.0, 2.0, 0.0, 2.0, 2.0, 0.0, 2.0]
    bar = [-1.0, 0.8, 3.0, 0.8, 3.0, 1.2, -1.0, 1.2]
    got = clip(square, bar, True)
    assert got is not None
    _same(
        got,
        shapely.difference(
            shapely.Polygon(np.reshape(square, (-1, 2))), shapely.Polygon(np.reshape(bar, (-1, 2)))
        ),
    )


def _bent_track() -> TrackBounds:
    """A track bending left through 120 degrees, 12 m wide, bounds every ~2 m."""
    ang = np.linspace(-np.pi / 2, np.pi / 6, 80)
    centre = np.stack([80.0 * np.cos(ang), 80.0 + 80.0 * np.sin(ang)], axis=1)
    normal = np.stack([np.cos(ang), np.sin(ang)], axis=1)  # outwards = right of the driving
    lead = np.stack([np.linspace(-120.0, -2.0, 60), np.zeros(60)], axis=1)
    left = np.concatenate([lead + np.array([0.0, 6.0]), centre - 6.0 * normal])
    right = np.concatenate([lead - np.array([0.0, 6.0]), centre + 6.0 * normal])
    return TrackBounds(left_m=left, right_m=right)


def _ring_track() -> TrackBounds:
    """A closed circular track (radius 50 m, 12 m wide), driven counter-clockwise."""
    ang = np.linspace(0.0, 2 * np.pi, 160)
    unit = np.stack([np.cos(ang), np.sin(ang)], axis=1)
    return TrackBounds(left_m=44.0 * unit, right_m=56.0 * unit)


TRACKS = {"bent": _bent_track(), "ring": _ring_track()}


@pytest.mark.parametrize("method", list(ReachMethod))
@pytest.mark.parametrize("kind", sorted(TRACKS))
@settings(max_examples=40, deadline=None)
@given(
    st.lists(
        st.tuples(
            st.floats(-80.0, 70.0), st.floats(-70.0, 70.0), st.floats(-3.2, 3.2), st.floats(0, 60)
        ),
        min_size=1,
        max_size=4,
    ),
    st.booleans(),
    st.booleans(),
)
def test_full_sets_equal_geos(method, kind, rows, trim, keep_body):
    """Every reduced set of ``reachable_sets`` is GEOS' geometry within 1e-9 m (and m2).

    ``ring`` is a loop whose drivable area has a hole (the infield): objects on, in and beyond.
    """
    track = build_track(TRACKS[kind], ReachParams().closed_track_gap_m)
    assert len(track.polygon.interiors) == (kind == "ring")
    params = ReachParams(method=method, trim_to_drivable=trim, keep_object_body=keep_body)
    got = reachable_sets(objects(*rows), TIMES, params, track, scalar=True)
    want = reachable_sets(objects(*rows), TIMES, params, track, scalar=False)
    assert got.shape == want.shape == (len(rows), len(TIMES))
    same_sets(got, want, TOL)


@pytest.mark.parametrize("grouped", [False, True])
def test_assemble_cells(grouped):
    """Closed rings become one polygon per cell, several rings a multipolygon, none empty."""
    square = [0.0, 0.0, 1.0, 0.0, 1.0, 1.0, 0.0, 1.0, 0.0, 0.0]
    far = [v + 5.0 for v in square]
    rings = [square, far, square] if grouped else [far, square]
    owner = [0, 0, 2] if grouped else [0, 2]
    xy = [v for ring in rings for v in ring]
    cells = _rings(xy, [len(r) // 2 for r in rings], owner, 3)
    assert cells.first.tolist() == ([0, 2, 2, 3] if grouped else [0, 1, 1, 2])
    out = _assemble(cells, owner, 3)
    assert out.shape == (3,)
    # the geometries hold the rings' points as they are, in ring order
    parts = shapely.get_exterior_ring(shapely.get_parts(out))
    assert np.array_equal(shapely.get_coordinates(parts), cells.xy)
    assert out[1].is_empty
    assert out[2].equals(shapely.box(0, 0, 1, 1))
    assert out[2].geom_type == "Polygon"
    want_0 = shapely.union(shapely.box(0, 0, 1, 1), shapely.box(5, 5, 6, 6))
    assert out[0].equals(want_0 if grouped else shapely.box(5, 5, 6, 6))
    assert out[0].geom_type == ("MultiPolygon" if grouped else "Polygon")


def _star_ring(seed: int) -> np.ndarray:
    """A star-shaped ring of 3-60 vertices around the origin (seeded)."""
    rng = np.random.default_rng(seed)
    n = int(rng.integers(3, 61))
    ang = np.sort(rng.uniform(0, 2 * np.pi, n))
    rad = rng.uniform(0.5, 9.0, n)
    return np.stack([rad * np.cos(ang), rad * np.sin(ang)], axis=1)


@settings(max_examples=60, deadline=None)
@given(
    ring=st.builds(_star_ring, st.integers(0, 2**31)),
    box=st.tuples(st.floats(-8, 8), st.floats(-8, 8), st.floats(0, 10), st.floats(0, 10)),
)
def test_runs_near_a_box_are_the_edges_near_it(ring, box):
    """``_near``'s runs hold exactly the edges whose boxes meet the box, in ring order."""
    x0, y0, w, h = box
    lo_hi = (x0, y0, x0 + w, y0 + h)
    edges = Edges(ring.reshape(-1).tolist())
    view = _near(edges, lo_hi)
    got = [g.k for run in view.runs for g in run.segs]
    want = [
        g.k
        for g in edges.segs
        if g.x0 <= lo_hi[2] and g.x1 >= lo_hi[0] and g.y0 <= lo_hi[3] and g.y1 >= lo_hi[1]
    ]
    assert got == want
    for run in [*edges.runs, *view.runs]:  # each run's box holds its edges
        assert run.segs
        assert all(
            run.x0 <= g.x0 and g.x1 <= run.x1 and run.y0 <= g.y0 and g.y1 <= run.y1
            for g in run.segs
        )
