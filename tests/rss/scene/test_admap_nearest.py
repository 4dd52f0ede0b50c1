"""ad-map's lane-width rule and nearest-segment tie rule against slow scalar restatements."""

from __future__ import annotations

import dataclasses
import itertools
import math
from typing import Any

import numpy as np
import pytest
import shapely

from rss.scene import admap_nearest, prepare
from rss.scene.admap_nearest import lane_widths, nearest_on_lines, range_of, segments
from rss.scene.matching_points import ad_map_positions
from rss.scene.polylines import polylines
from tests.rss.scene.synthetic import straight_road

_TOL = 1e-3


def _arc(radius: float, step_deg: float, lead_m: float = 0.0) -> np.ndarray:
    """A quarter circle round the origin (from +x to +y), optionally after a straight lead."""
    angles = np.radians(np.arange(0.0, 90.0 + 1e-9, step_deg))
    arc = np.stack([radius * np.cos(angles), radius * np.sin(angles)], axis=1)
    if lead_m > 0.0:
        arc = np.vstack([[[radius, -lead_m]], arc])
    return arc


def _point_at(line: np.ndarray, s: float) -> np.ndarray:
    """ad-map's ``getParametricPoint`` by arc length (first segment reaching ``s``)."""
    run = 0.0
    out: np.ndarray = line[-1]
    for a, b in itertools.pairwise(line):
        d = math.dist(a, b)
        if d > 0.0 and run + d >= s:
            out = a + (b - a) * ((s - run) / d)
            break
        run += d
    return out


def _nearest(line: np.ndarray, p: np.ndarray) -> float:
    """ad-map's ``findNearestPointOnEdge``: arc length, a later segment wins by >= 1 mm."""
    best_d, best_s, run = math.inf, 0.0, 0.0
    for a, b in itertools.pairwise(line):
        ab = b - a
        t = min(max(float(np.dot(p - a, ab) / np.dot(ab, ab)), 0.0), 1.0)
        d = math.dist(p, a + ab * t)
        if best_d == math.inf or (d < best_d and best_d - d >= _TOL):
            best_d, best_s = d, run + t * math.dist(a, b)
        run += math.dist(a, b)
    return best_s


def _slow_widths(left: np.ndarray, right: np.ndarray) -> tuple[list[float], list[float]]:
    """``calculateWidthRange`` station by station, in the borders' point order."""
    len_l = sum(math.dist(a, b) for a, b in itertools.pairwise(left))
    len_r = sum(math.dist(a, b) for a, b in itertools.pairwise(right))
    mean = 0.5 * (len_l + len_r)
    step = max(0.01, 1.0 / mean) if mean > 1.0 else 0.5
    t, ts, widths = 0.0, [], []
    while True:
        centre = 0.5 * (_point_at(left, len_l * t) + _point_at(right, len_r * t))
        foot_l = _point_at(left, _nearest(left, centre))
        foot_r = _point_at(right, _nearest(right, centre))
        ts.append(t)
        widths.append(math.dist(foot_l, foot_r))
        if t >= 1.0:
            return ts, widths
        t = min(t + step, 1.0)


def _curved_lane() -> tuple[np.ndarray, np.ndarray]:
    """A left-turning lane 4 m wide whose outer border has a 3 m lead the inner one lacks."""
    return _arc(10.0, 10.0), _arc(14.0, 3.0, lead_m=3.0)


def test_widths_follow_admap_rule_not_equal_fractions() -> None:
    left, right = _curved_lane()
    (at,), (widths,) = lane_widths((left,), (right,), np.array([False]))
    slow_t, slow_w = _slow_widths(left, right)
    np.testing.assert_allclose(at, slow_t, atol=1e-12)
    np.testing.assert_allclose(widths, slow_w, atol=1e-9)
    # the former rule (distance of the border points at equal fractions) is off by > 0.5 m
    fractions = shapely.distance(
        shapely.line_interpolate_point(shapely.LineString(left), at, normalized=True),
        shapely.line_interpolate_point(shapely.LineString(right), at, normalized=True),
    )
    assert np.max(np.abs(fractions - widths)) > 0.5
    # the projections give 4 m up to the chords' sagitta (3.8 cm on the inner border)
    assert np.median(widths) == pytest.approx(4.0, abs=0.04)


def test_widths_of_reversed_lanes_run_in_admap_order() -> None:
    left, right = _curved_lane()
    (at,), (widths,) = lane_widths((left,), (right,), np.array([True]))
    slow_t, slow_w = _slow_widths(right[::-1], left[::-1])
    np.testing.assert_allclose(at, 1.0 - np.array(slow_t[::-1]), atol=1e-12)
    np.testing.assert_allclose(widths, slow_w[::-1], atol=1e-9)
    forward_t, _ = lane_widths((left,), (right,), np.array([False]))
    assert not np.allclose(forward_t[0][1:-1], at[1:-1])  # stations from the other end


def test_widths_in_pieces_of_bounded_memory_are_the_same(monkeypatch: pytest.MonkeyPatch) -> None:
    """Width stations searched a few hundred pairs at a time give the widths of one search."""
    left, right = _curved_lane()
    lefts, rights = (
        (left, left[::-1] + 30.0, left + 60.0),
        (right, right[::-1] + 30.0, right + 60.0),
    )
    backwards = np.array([False, True, False])
    whole_t, whole_w = lane_widths(lefts, rights, backwards)
    searched = admap_nearest.nearest_in_windows
    calls: list[int] = []

    def counted(*args: Any) -> tuple[np.ndarray, np.ndarray]:
        calls.append(len(args[1]))
        return searched(*args)

    monkeypatch.setattr(admap_nearest, "nearest_in_windows", counted)
    monkeypatch.setattr(admap_nearest, "_WIDTH_PAIRS", 100)
    piece_t, piece_w = lane_widths(lefts, rights, backwards)
    assert len(calls) > 3  # several pieces
    assert sum(calls) == 2 * sum(len(t) for t in whole_t)  # every station on both borders
    for got, want in zip([*piece_t, *piece_w], [*whole_t, *whole_w], strict=True):
        np.testing.assert_array_equal(got, want)


def test_range_of_keeps_bounds_within_one_millimetre() -> None:
    assert range_of([4.0, 3.9995, 3.998, 3.9975, 4.0005]) == (3.998, 4.0)
    assert range_of([1.0, 1.002, 0.5]) == (0.5, 1.002)


def test_nearest_tie_goes_to_the_first_segment_in_admap_order() -> None:
    v_shape = np.array([[-1.0, 1.0], [0.0, 0.0], [1.0, 1.0]])
    lines = polylines(np.array([shapely.LineString(v_shape)], dtype=object))
    which = np.zeros(2, dtype=np.int64)
    points = np.array([[0.0, 1.0], [0.0, 1.0]])
    s, feet = nearest_on_lines(lines, segments(lines), which, points, np.array([False, True]))
    half = math.sqrt(0.5)
    np.testing.assert_allclose(s, [half, 3 * half], atol=1e-12)
    np.testing.assert_allclose(feet, [[-0.5, 0.5], [0.5, 0.5]], atol=1e-12)
    # a segment nearer by less than 1 mm does not win against an earlier one
    s, _ = nearest_on_lines(lines, segments(lines), which[:1], np.array([[0.0004, 1.0]]), None)
    assert s[0] < 2 * half


def test_matching_scans_reversed_lanes_from_their_end() -> None:
    """A point equally near two border segments takes ad-map's first (lane flag)."""
    graph = straight_road(1, length=20.0)
    v_left = np.array([[0.0, 1.75], [10.0, -1.0], [20.0, 1.75]])
    v_right = v_left - [0.0, 3.5]
    graph = dataclasses.replace(
        graph, left_m=(v_left,), right_m=(v_right,), centre_m=((v_left + v_right) / 2,)
    )
    above = np.array([[10.0, 6.0]])  # beside the lane, equally near both left segments
    lanes = np.zeros(1, dtype=np.int64)
    ours = ad_map_positions(prepare(graph), lanes, above)[0][0]
    flagged = dataclasses.replace(graph, admap_reversed=np.array([True]))
    theirs = ad_map_positions(prepare(flagged), lanes, above)[0][0]
    assert ours < 0.5 < theirs
    assert ours + theirs == pytest.approx(1.0, abs=1e-9)
