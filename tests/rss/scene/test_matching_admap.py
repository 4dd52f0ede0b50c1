"""Occupied regions as ad-map computes them, on synthetic lanes with analytic answers."""

from __future__ import annotations

import numpy as np
import pytest

from rss.scene import BoxArrays, LaneGraph, match_boxes, prepare
from rss.scene.matching_points import ad_map_positions

from .synthetic import WIDTH, straight_road

# straight_road(3): lane i spans y in [(1.5 - i - 1) * W, (1.5 - i) * W], x in [0, 200]
Y_LEFT = [(1.5 - i) * WIDTH for i in range(3)]


def _box(
    x: float, y: float, yaw: float = 0.0, length: float = 4.0, width: float = 2.0
) -> BoxArrays:
    return BoxArrays(
        np.array([x]), np.array([y]), np.array([yaw]), np.array([length]), np.array([width])
    )


def _regions(prep, boxes: BoxArrays) -> dict[int, tuple[float, float, float, float]]:
    m = match_boxes(prep, boxes)
    return {
        int(m.lane[r]): (m.lon_min[r], m.lon_max[r], m.lat_min[r], m.lat_max[r]) for r in m.rows(0)
    }


def test_box_inside_a_straight_lane() -> None:
    prep = prepare(straight_road(3))
    regions = _regions(prep, _box(50.0, Y_LEFT[1] - WIDTH / 2))
    assert set(regions) == {1}
    half = 1.0 / WIDTH
    np.testing.assert_allclose(regions[1], (48 / 200, 52 / 200, 0.5 - half, 0.5 + half), atol=1e-9)


def test_box_across_two_lanes_reaches_the_shared_border() -> None:
    prep = prepare(straight_road(3))
    border = Y_LEFT[1]
    regions = _regions(prep, _box(120.0, border + 0.5))
    assert set(regions) == {0, 1}
    # lane 0 (left): from 1.5 m left of the border to the border (lat 1 = its right border)
    np.testing.assert_allclose(regions[0], (118 / 200, 122 / 200, 1 - 1.5 / WIDTH, 1.0), atol=1e-9)
    # lane 1: from its left border (lat 0) to 0.5 m into it
    np.testing.assert_allclose(regions[1], (118 / 200, 122 / 200, 0.0, 0.5 / WIDTH), atol=1e-9)


def test_box_grazing_a_neighbour_within_the_match_distance_stays_out() -> None:
    prep = prepare(straight_road(3))
    # the box's left side lies 5 cm right of lane 0: within ad-map's 0.1 m of it, but no
    # point of the box lies in it
    regions = _regions(prep, _box(80.0, Y_LEFT[1] - 1.05))
    assert set(regions) == {1}
    assert regions[1][2] == pytest.approx(0.05 / WIDTH, abs=1e-9)


def test_points_just_outside_pull_the_region_onto_the_border() -> None:
    prep = prepare(straight_road(3))
    # 1.5 cm of the box lie left of lane 1: those lattice points match lane 1 within 0.1 m
    # and count at its border (lat 0), the box reaches lane 0 by less than ad-map's 5 cm...
    regions = _regions(prep, _box(80.0, Y_LEFT[1] - 0.985))
    assert regions[1][2] == 0.0


def test_box_partly_off_the_map_keeps_the_lanes_it_touches() -> None:
    prep = prepare(straight_road(3))
    right_edge = Y_LEFT[2] - WIDTH
    m = match_boxes(prep, _box(30.0, right_edge))
    assert m.lane.tolist() == [2]
    assert m.anchor.tolist() == [2]
    np.testing.assert_allclose(
        (m.lon_min[0], m.lon_max[0], m.lat_min[0], m.lat_max[0]),
        (28 / 200, 32 / 200, 1 - 1 / WIDTH, 1.0),
        atol=1e-9,
    )


def test_box_over_a_lane_end_reaches_it() -> None:
    prep = prepare(straight_road(3))
    regions = _regions(prep, _box(199.0, Y_LEFT[1] - WIDTH / 2))
    np.testing.assert_allclose(regions[1][:2], (197 / 200, 1.0), atol=1e-9)


def test_box_just_beyond_a_lane_end_touches_it() -> None:
    # ad-map 3.0 (``isLongitudinalInLaneMatch``): a point projecting onto a lane end is in
    # the lane within 0.1 m of it (earlier releases: 5 cm). A box 8 cm beyond the end of
    # lane 1 thus occupies it there, in a zero-length region; 12 cm beyond, it does not.
    prep = prepare(straight_road(3))
    centre = Y_LEFT[1] - WIDTH / 2
    regions = _regions(prep, _box(200.08 + 2.0, centre))
    assert list(regions) == [1]
    half = 1.0 / WIDTH  # half the box width as a share of the lane width
    np.testing.assert_allclose(regions[1], (1.0, 1.0, 0.5 - half, 0.5 + half), atol=1e-9)
    assert _regions(prep, _box(200.12 + 2.0, centre)) == {}


R_CENTRE = 10.0
#: Chords of the arc cut the circle by up to 1 cm (ad-map's reader: 5 cm), which moves
#: nearest points along the arc too. Much denser chords would put many segments within
#: ad-map's 1 mm tie tolerance of a point's nearest one, and the first of them wins.
N_ARC = 21
LAT_TOL = 0.01 / WIDTH
LON_TOL = 2e-3


def _arc() -> LaneGraph:
    """One lane on a quarter circle around the origin, counter-clockwise, inner border left."""
    phi = np.linspace(-np.pi / 2, 0.0, N_ARC)
    ring = np.stack([np.cos(phi), np.sin(phi)], axis=1)
    left, right = ring * (R_CENTRE - WIDTH / 2), ring * (R_CENTRE + WIDTH / 2)
    no = np.array([-1])
    return LaneGraph(
        ids=("arc",),
        left_m=(left,),
        right_m=(right,),
        centre_m=((left + right) / 2,),
        direction=np.ones(1, dtype=np.int64),
        speed_limit_mps=np.full(1, 10.0),
        successors=((),),
        predecessors=((),),
        left_neighbour=no,
        right_neighbour=no,
        left_opposite=np.zeros(1, dtype=bool),
        right_opposite=np.zeros(1, dtype=bool),
        is_intersection=np.zeros(1, dtype=bool),
        priority=np.zeros(1, dtype=np.int64),
        traffic_light=no,
    )


def _polar(angle: float, radius: float) -> tuple[float, float]:
    """ad-map's (lon, lat) of a point on the arc lane: the angle fraction, the radial share."""
    return (angle + np.pi / 2) / (np.pi / 2), (radius - (R_CENTRE - WIDTH / 2)) / WIDTH


def test_points_on_an_arc_lane() -> None:
    prep = prepare(_arc())
    angle = np.array([-1.2, -0.8, -0.3])
    radius = np.array([8.5, 10.0, 11.6])
    points = np.stack([radius * np.cos(angle), radius * np.sin(angle)], axis=1)
    lon, lat, dist = ad_map_positions(prep, np.zeros(3, dtype=np.int64), points)
    want = np.array([_polar(a, r) for a, r in zip(angle, radius, strict=True)])
    np.testing.assert_allclose(lon, want[:, 0], atol=LON_TOL)
    np.testing.assert_allclose(lat, want[:, 1], atol=LAT_TOL)
    # inside the lane, off the segment between the two nearest border points by little
    assert np.all(dist < 0.05)


def test_box_on_an_arc_lane_against_the_circle() -> None:
    prep = prepare(_arc())
    centre_angle, length, width = -0.7, 4.5, 2.0
    x, y = R_CENTRE * np.cos(centre_angle), R_CENTRE * np.sin(centre_angle)
    regions = _regions(prep, _box(x, y, centre_angle + np.pi / 2, length, width))
    lon_min, lon_max, lat_min, lat_max = regions[0]
    # corners: the inner ones span the widest angle, the outer ones reach farthest out
    inner, outer = R_CENTRE - width / 2, R_CENTRE + width / 2
    spread = np.arctan2(length / 2, inner)
    assert lon_min == pytest.approx(_polar(centre_angle - spread, inner)[0], abs=LON_TOL)
    assert lon_max == pytest.approx(_polar(centre_angle + spread, inner)[0], abs=LON_TOL)
    assert lat_max == pytest.approx(_polar(0.0, np.hypot(outer, length / 2))[1], abs=LAT_TOL)
    # the inner side is nearest the centre in its middle, not at its corners
    assert lat_min == pytest.approx(_polar(0.0, inner)[1], abs=LAT_TOL)
    assert lat_min < _polar(0.0, np.hypot(inner, length / 2))[1] - 0.05
