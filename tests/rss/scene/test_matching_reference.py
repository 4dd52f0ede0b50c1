"""``match_boxes`` against a slow, obvious scalar reference of ad-map's box matching.

The reference samples every box on ad-map's full lattice (steps of at most 0.1 m, edges
included), matches every lattice point to every lane one point at a time (nearest points
on both borders, ad-map's first-of-nearly-equal-segments rule, its 0.1 m / 1 mm
tolerances) and merges the matches as ``AdMapMatching::addLaneRegions`` does. The fast
version evaluates only the points that can hold the extremes, so the two agree closely
but not to the last bit (cut points of shallow crossings, parabola vertices).
"""

from __future__ import annotations

import itertools
import math

import numpy as np
import pytest
import shapely

from loaders.maps.opendrive import read_opendrive
from rss.scene import BoxArrays, PreparedGraph, match_boxes, prepare
from rss.scene.match_records import box_polygons
from rss.scene.matching_points import ad_map_positions
from workbench.engines.rss.adapter import lane_graph_from_map


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


def _border(prep: PreparedGraph, line: int) -> list[tuple[float, float]]:
    b = prep.borders
    return [tuple(v) for v in b.xy_m[b.start[line] : b.start[line + 1]].tolist()]


def _nearest_on(prep: PreparedGraph, line: int, x: float, y: float) -> tuple[float, float, float]:
    """``_nearest`` scanning the border in ad-map's point order (fraction in ours)."""
    if not prep.line_backwards[line]:
        return _nearest(_border(prep, line), x, y)
    t, fx, fy = _nearest(_border(prep, line)[::-1], x, y)
    return 1.0 - t, fx, fy


def _nearest(border: list[tuple[float, float]], x: float, y: float) -> tuple[float, float, float]:
    """ad-map's nearest point on a border: (fraction, x, y); a later segment wins only when
    nearer by more than 1 mm."""
    best = (math.inf, 0.0, 0.0, 0.0)
    run = 0.0
    for (ax, ay), (bx, by) in itertools.pairwise(border):
        dx, dy = bx - ax, by - ay
        seg = math.hypot(dx, dy)
        t = 0.0 if seg == 0.0 else min(max(((x - ax) * dx + (y - ay) * dy) / seg**2, 0.0), 1.0)
        fx, fy = ax + t * dx, ay + t * dy
        dist = math.hypot(x - fx, y - fy)
        if dist < best[0] - 1e-3:
            best = (dist, run + t * seg, fx, fy)
        run += seg
    return best[1] / run, best[2], best[3]


def _position(prep: PreparedGraph, lane: int, x: float, y: float) -> tuple[float, float, float]:
    """(lon, lat, dist) of one point in one lane, as ad-map's ``findNearestPointOnLane``."""
    tl, lx, ly = _nearest_on(prep, lane, x, y)
    tr, rx, ry = _nearest_on(prep, lane + len(prep.graph), x, y)
    dx, dy = rx - lx, ry - ly
    lat = ((x - lx) * dx + (y - ly) * dy) / (dx * dx + dy * dy)
    n = min(max(lat, 0.0), 1.0)
    dist = math.hypot(x - (lx + n * dx), y - (ly + n * dy))
    return (1.0 - n) * tl + n * tr, lat, dist


def _reference(
    prep: PreparedGraph, boxes: BoxArrays, box: int, lane: int
) -> tuple[float, ...] | None:
    """ad-map's occupied region of ``box`` in ``lane`` from its full lattice."""
    c, s = math.cos(boxes.yaw_rad[box]), math.sin(boxes.yaw_rad[box])
    length, width = float(boxes.length_m[box]), float(boxes.width_m[box])
    n_l, n_w = math.ceil(length / 0.1), math.ceil(width / 0.1)
    fx = boxes.x_m[box] + c * length / 2 - s * width / 2
    fy = boxes.y_m[box] + s * length / 2 + c * width / 2
    inside: list[tuple[float, float]] = []
    rest: list[tuple[float, float]] = []
    for i in range(n_l + 1):
        for j in range(n_w + 1):
            back, right = i * length / n_l, j * width / n_w
            lon, lat, dist = _position(
                prep, lane, fx - c * back + s * right, fy - s * back - c * right
            )
            if dist >= 0.101:
                continue
            end = lon < 1e-6 or lon > 1.0 - 1e-6
            actual = 0.0 <= lat <= 1.0 and not (end and dist >= 0.101)
            (inside if actual else rest).append((lon, min(max(lat, 0.0), 1.0)))
    if not inside:
        return None
    lons = [p[0] for p in inside + rest]
    lats = [p[1] for p in inside + rest]
    return min(lons), max(lons), min(lats), max(lats)


def test_point_positions_match_scalar_reference(town01) -> None:
    rng = np.random.default_rng(5)
    lanes = rng.integers(0, len(town01.graph), 400)
    points = np.array(
        [town01.graph.centre_m[k][len(town01.graph.centre_m[k]) // 2] for k in lanes]
    ) + rng.normal(0.0, 1.5, (400, 2))
    lon, lat, dist = ad_map_positions(town01, lanes, points)
    ref = np.array([_position(town01, int(k), *p) for k, p in zip(lanes, points, strict=True)])
    same = np.all(np.abs(np.stack([lon, lat, dist], axis=1) - ref) < 1e-9, axis=1)
    # the vectorised tie rule (first segment within 1 mm of the nearest) may pick another
    # segment than ad-map's running comparison in rare chains of near-ties
    assert same.mean() >= 0.99


@pytest.mark.parametrize(("seed", "yaw_noise"), [(0, 0.0), (1, 0.3), (2, 1.5)])
def test_regions_match_lattice_reference(town01, seed: int, yaw_noise: float) -> None:
    boxes = _boxes(town01, np.random.default_rng(seed), 25, yaw_noise)
    m = match_boxes(town01, boxes)
    polys = box_polygons(boxes)
    errors = []
    for box in range(25):
        mine = {int(m.lane[r]): r for r in m.rows(box)}
        near = town01.match_tree.query(polys[box], predicate="intersects").tolist()
        for lane in near:
            ref = _reference(town01, boxes, box, lane)
            assert (ref is not None) == (lane in mine) or _grazing(town01, polys[box], lane)
            if ref is None or lane not in mine:
                continue
            r = mine[lane]
            got = (m.lon_min[r], m.lon_max[r], m.lat_min[r], m.lat_max[r])
            scale = [town01.centre_length_m[lane]] * 2 + [float(np.mean(town01.width_m[lane]))] * 2
            errors.append(np.abs(np.subtract(got, ref)) * scale)
    err = np.array(errors)
    assert len(err) > 25
    assert np.mean(np.all(err < 0.01, axis=1)) >= 0.9
    assert err.max() < 0.25


def _grazing(prep: PreparedGraph, poly: shapely.Geometry, lane: int) -> bool:
    """The box reaches into the lane by less than one lattice step (either answer is fair)."""
    inner = shapely.buffer(prep.polygons[lane], -0.1)
    return not shapely.intersects(poly, inner)


def test_boxes_off_the_map_touch_nothing(town01) -> None:
    far = np.full(3, 1e5)
    boxes = BoxArrays(far, far + np.arange(3.0), np.zeros(3), np.full(3, 4.5), np.full(3, 1.9))
    m = match_boxes(town01, boxes)
    assert m.box.size == 0
    np.testing.assert_array_equal(m.anchor, [-1, -1, -1])
    assert m.starts == [0, 0, 0, 0]


def test_regions_along_curves_are_lattice_extremes(town01) -> None:
    """Boxes along curved lanes: every evaluated point is a lattice point, so no region
    reaches beyond the full lattice's; the lateral extreme inside a box side is found
    among the lattice points round where the side samples' parabola puts it."""
    rng = np.random.default_rng(11)
    curved = np.flatnonzero(~town01.straight)
    rows = []
    for _ in range(150):
        c = town01.graph.centre_m[int(rng.choice(curved))]
        k = int(rng.integers(0, len(c) - 1))
        d = c[k + 1] - c[k]
        xy = c[k] + rng.uniform() * d + rng.normal(0.0, 0.5, 2)
        rows.append((*xy, np.arctan2(d[1], d[0]) + rng.normal(0.0, 0.1)))
    arr = np.array(rows)
    n = len(arr)
    boxes = BoxArrays(arr[:, 0], arr[:, 1], arr[:, 2], np.full(n, 4.5), np.full(n, 1.9))
    m = match_boxes(town01, boxes)
    lat_errors = []
    for box in range(n):
        for r in m.rows(box):
            lane = int(m.lane[r])
            ref = _reference(town01, boxes, box, lane)
            if ref is None:
                continue
            assert m.lon_min[r] >= ref[0] - 1e-9
            assert m.lon_max[r] <= ref[1] + 1e-9
            assert m.lat_min[r] >= ref[2] - 1e-9
            assert m.lat_max[r] <= ref[3] + 1e-9
            width = float(np.mean(town01.width_m[lane]))
            lat_errors.append(max(m.lat_min[r] - ref[2], ref[3] - m.lat_max[r]) * width)
    assert len(lat_errors) > 300
    assert np.mean(np.array(lat_errors) < 1e-3) >= 0.95
