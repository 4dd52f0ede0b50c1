"""``match_boxes`` (contained-box shortcut, flat linear referencing) against a scalar reference.

The reference clips every box with every lane polygon it touches through GEOS and projects
each footprint vertex with shapely's linear referencing, one pair at a time.
"""

from __future__ import annotations

import numpy as np
import pytest
import shapely

from loaders.maps.opendrive import read_opendrive
from rss.scene import BoxArrays, PreparedGraph, match_boxes, prepare
from rss.scene.lanegraph import WIDTH_STATIONS
from rss.scene.matching import box_polygons
from workbench.rss_adapter import lane_graph_from_map

TOL = 1e-9


@pytest.fixture(scope="module")
def town01(external_dir):
    return prepare(lane_graph_from_map(read_opendrive(external_dir / "maps" / "Town01.xodr")))


def _boxes(prep: PreparedGraph, rng: np.random.Generator, n: int, yaw_noise: float) -> BoxArrays:
    rows = []
    for _ in range(n):
        c = prep.graph.centre_m[int(rng.integers(0, len(prep.graph)))]
        k = int(rng.integers(0, len(c) - 1))
        d = c[k + 1] - c[k]
        xy = c[k] + rng.uniform(0.0, 1.0) * d + rng.normal(0.0, 0.8, 2)
        rows.append((*xy, np.arctan2(d[1], d[0]) + rng.normal(0.0, yaw_noise)))
    arr = np.array(rows)
    return BoxArrays(arr[:, 0], arr[:, 1], arr[:, 2], np.full(n, 4.5), np.full(n, 1.9))


def _reference_region(prep: PreparedGraph, box: shapely.Geometry, lane: int) -> tuple[float, ...]:
    """(lon_min, lon_max, lat_min, lat_max) of one box in one lane, pair by pair."""
    clipped = shapely.intersection(box, prep.polygons[lane])
    line, length = prep.centre_lines[lane], float(prep.centre_length_m[lane])
    lons, lats = [], []
    for x, y in shapely.get_coordinates(clipped):
        s = float(shapely.line_locate_point(line, shapely.Point(x, y)))
        a = shapely.line_interpolate_point(line, min(max(s - 0.5, 0.0), length))
        b = shapely.line_interpolate_point(line, min(max(s + 0.5, 0.0), length))
        heading = np.arctan2(b.y - a.y, b.x - a.x)
        foot = shapely.line_interpolate_point(line, s)
        offset_left = np.cos(heading) * (y - foot.y) - np.sin(heading) * (x - foot.x)
        width = np.interp(s / length, np.linspace(0.0, 1.0, WIDTH_STATIONS), prep.width_m[lane])
        lons.append(s / length)
        lats.append(0.5 - offset_left / width)
    clip = [min(max(v, 0.0), 1.0) for v in (min(lons), max(lons), min(lats), max(lats))]
    return tuple(clip)


@pytest.mark.parametrize(("seed", "yaw_noise"), [(0, 0.0), (1, 0.3), (2, 1.5)])
def test_regions_match_pairwise_reference(town01, seed: int, yaw_noise: float) -> None:
    boxes = _boxes(town01, np.random.default_rng(seed), 60, yaw_noise)
    m = match_boxes(town01, boxes)
    polys = box_polygons(boxes)
    assert len(m.box) > 60
    for i in range(len(m.box)):
        box, lane = int(m.box[i]), int(m.lane[i])
        got = (m.lon_min[i], m.lon_max[i], m.lat_min[i], m.lat_max[i])
        np.testing.assert_allclose(got, _reference_region(town01, polys[box], lane), atol=TOL)
    touched = town01.tree.query(polys, predicate="intersects")[0]
    assert set(m.box.tolist()) <= set(touched.tolist())
    assert np.all(m.anchor[np.unique(m.box)] >= 0)


def test_boxes_off_the_map_touch_nothing(town01) -> None:
    far = np.full(3, 1e5)
    boxes = BoxArrays(far, far + np.arange(3.0), np.zeros(3), np.full(3, 4.5), np.full(3, 1.9))
    m = match_boxes(town01, boxes)
    assert m.box.size == 0
    np.testing.assert_array_equal(m.anchor, [-1, -1, -1])
    assert m.starts == [0, 0, 0, 0]
