"""Lengths of cut lane segments: ad-map's projected border pieces (``rss.scene.border_stations``).

ad-map (``route::getMetricRanges``) measures a lane interval ``[lo, hi]`` on each border
between the nearest border points of the centre points ``c(lo)`` and ``c(hi)``; a centre
point is the midpoint of the border points at the same fraction of each border's length.
The reference here is slow and separate: shapely points along the borders and a scan over
single-segment lines, with the tie rule of ``rss.scene.matching_points`` (of segments
within 1 mm of the nearest, the first counts).
"""

from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np
import pytest
import shapely

from rss.scene import LaneGraph, SceneMemo, prepare

from .synthetic import lone_lane, straight_road

if TYPE_CHECKING:
    from rss.scene.prepared import PreparedGraph

TIE_M = 1e-3
#: Table lookups against the slow reference (the table is exact between its stations).
TOL_M = 1e-5


def _arc(radius: float, start: np.ndarray, chord_m: float) -> np.ndarray:
    """A left turn of 90 degrees from ``start`` (heading +x), in chords of about ``chord_m``."""
    n = max(2, int(np.ceil(radius * np.pi / 2 / chord_m)) + 1)
    phi = np.linspace(-np.pi / 2, 0.0, n)
    centre = start + np.array([0.0, radius])
    return np.stack([centre[0] + radius * np.cos(phi), centre[1] + radius * np.sin(phi)], axis=1)


def turn_lane() -> LaneGraph:
    """One lane: 12 m straight, then a tight left turn (radius 6 m inside, 9.5 m outside).

    The straight part takes a larger share of the inner (left) border than of the outer
    one, so a window's projected pieces differ from its parametric share of each border.
    """
    width = 3.5
    left = np.vstack(
        [[[0.0, width]], _arc(6.0, np.array([12.0, width]), 0.8)]
    )  # starts at (0, 3.5)
    right = np.vstack([[[0.0, 0.0]], _arc(6.0 + width, np.array([12.0, 0.0]), 1.1)])
    centre = np.vstack(
        [[[0.0, width / 2]], _arc(6.0 + width / 2, np.array([12.0, width / 2]), 0.5)]
    )
    return lone_lane(left, right, centre, "turn")


def _nearest_arc(border: np.ndarray, point: shapely.Point) -> float:
    """Arc length along ``border`` of the nearest point (first segment within 1 mm)."""
    segments = [shapely.LineString(border[k : k + 2]) for k in range(len(border) - 1)]
    dist = np.array([seg.distance(point) for seg in segments])
    k = int(np.flatnonzero(dist < dist.min() + TIE_M)[0])
    before = float(np.sum(np.hypot(*np.diff(border[: k + 1], axis=0).T)))
    return before + float(segments[k].project(point))


def reference_lengths(graph: LaneGraph, lane: int, lo: float, hi: float) -> tuple[float, float]:
    """Left and right projected piece lengths [m] of ``lane`` over ``[lo, hi]``, slowly."""
    left, right = graph.left_m[lane], graph.right_m[lane]
    lines = shapely.LineString(left), shapely.LineString(right)
    centres = []
    for t in (lo, hi):
        a, b = (line.interpolate(t, normalized=True) for line in lines)
        centres.append(shapely.Point((a.x + b.x) / 2, (a.y + b.y) / 2))
    out = [
        abs(_nearest_arc(border, centres[1]) - _nearest_arc(border, centres[0]))
        for border in (left, right)
    ]
    return out[0], out[1]


@pytest.fixture(scope="module")
def turn() -> PreparedGraph:
    return prepare(turn_lane())


def _windows(seed: int) -> list[tuple[float, float]]:
    rng = np.random.default_rng(seed)
    rows = [tuple(sorted(rng.uniform(0.0, 1.0, 2).tolist())) for _ in range(40)]
    rows += [(0.0, float(v)) for v in rng.uniform(0.05, 0.95, 5)]
    rows += [(float(v), 1.0) for v in rng.uniform(0.05, 0.95, 5)]
    rows += [(0.0, 0.3), (0.3, 0.6), (0.6, 0.9), (0.25, 1.0)]
    return [(lo, hi) for lo, hi in rows if hi - lo > 1e-3]


@pytest.mark.parametrize("forward", [True, False])
def test_cut_lengths_are_the_projected_border_pieces(turn: PreparedGraph, forward: bool) -> None:
    segments = turn.lane_segments
    shares = []
    for lo, hi in _windows(seed=3 if forward else 4):
        p0, p1 = (lo, hi) if forward else (1.0 - hi, 1.0 - lo)
        got = segments.lane_segment({}, 0, forward=forward, id_offset=7, p0=p0, p1=p1)
        left, right = reference_lengths(turn.graph, 0, lo, hi)
        assert got.lane_id == 7
        assert got.length_min_m == pytest.approx(min(left, right), abs=TOL_M)
        assert got.length_max_m == pytest.approx(max(left, right), abs=TOL_M)
        assert got.length_min_m <= got.length_max_m
        shares.append(abs(left - turn.border_length_m[0, 0] * (hi - lo)))
    # The lane is built so that these lengths are not the parametric shares.
    assert max(shares) > 0.5


def test_whole_lane_keeps_the_border_lengths(turn: PreparedGraph) -> None:
    segments = turn.lane_segments
    memo = SceneMemo()
    for forward in (True, False):
        whole = segments.lane_segment(memo.whole_lanes, 0, forward=forward, id_offset=3)
        assert segments.lane_segment(memo.whole_lanes, 0, forward=forward, id_offset=3) is whole
        lengths = [
            float(np.sum(np.hypot(*np.diff(b[0], axis=0).T)))
            for b in (turn.graph.left_m, turn.graph.right_m)
        ]
        assert (whole.length_min_m, whole.length_max_m) == (min(lengths), max(lengths))
        assert (whole.width_min_m, whole.width_max_m) == (
            min(segments.width_rows[0]),
            max(segments.width_rows[0]),
        )


def test_straight_lanes_keep_the_parametric_share() -> None:
    prep = prepare(straight_road(n_lanes=2, length=120.0))
    for lo, hi in _windows(seed=5):
        got = prep.lane_segments.lane_segment({}, 1, forward=True, p0=lo, p1=hi)
        assert got.length_min_m == pytest.approx(120.0 * (hi - lo), abs=1e-9)
        assert got.length_max_m == pytest.approx(120.0 * (hi - lo), abs=1e-9)


def test_stations_are_increasing_from_zero_to_one(turn: PreparedGraph) -> None:
    segments = turn.lane_segments
    t = np.array(segments.stations[0])
    assert t[0] == 0.0
    assert t[-1] == 1.0
    assert np.all(np.diff(t) > 0.0)
    # Away from the jumps a table is exact; stations are few (linear runs are dropped).
    assert len(t) < 40 * (len(turn.graph.left_m[0]) + len(turn.graph.right_m[0]))


def test_cuts_are_measured_on_every_given_vertex() -> None:
    # The left border bends by 8 mm over its last 2 cm (less than the 1 cm a simplified
    # border would drop): the centre point at t = 1 has its nearest left point at the
    # bend (20, 0), not at the end, so the left piece of [0.5, 1] ends 2 cm early.
    left = np.array([[0.0, 0.0], [20.0, 0.0], [20.02, 0.008]])
    right = np.array([[0.0, -3.0], [20.02, -3.0]])
    graph = lone_lane(left, right, (left[[0, 2]] + right) / 2, "kinked")
    seg = prepare(graph).lane_segments.lane_segment({}, 0, forward=True, p0=0.5, p1=1.0)
    # c(0.5): halfway along each border, (x_l + x_r) / 2 with y = -1.5; its nearest left
    # point lies straight above it, its nearest right point straight below
    x_mid = (0.5 * (20.0 + np.hypot(0.02, 0.008)) + 0.5 * 20.02) / 2
    assert seg.length_min_m == pytest.approx(20.0 - x_mid, abs=1e-9)  # left: to the bend
    assert seg.length_max_m == pytest.approx(20.02 - x_mid, abs=1e-9)  # right: to its end
