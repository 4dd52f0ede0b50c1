"""ad-map's aligned cuts of lanes side by side (``rss.scene.align``).

ad-map cuts the lane a vehicle occupies at its region bound ``t`` and every other lane of
that road segment where the middle ``P`` of the projections of the cut lane's centre point
``c(t)`` onto its own borders has its nearest points: at the mean of their fractions of
the other lane's borders. Checked against numbers worked out by hand on a synthetic road,
against ad-map itself on Town01, and against a slow full-border search.
"""

from __future__ import annotations

import numpy as np
import pytest

from loaders.maps.opendrive import read_opendrive
from rss.model import LaneDrivingDirection, RoadSegmentType
from rss.scene import LaneGraph, PreparedGraph, prepare
from rss.scene.memo import SceneMemo
from rss.scene.polylines import interpolate
from rss.scene.roadarea import build_road
from rss.scene.segment_plans import SegmentPlan
from workbench.engines.rss.adapter import lane_graph_from_map


def _skewed_pair() -> LaneGraph:
    """Two lanes along +x: lane 1 (0 <= x <= 10, -2 <= y <= 0) and, on its left, lane 0
    sharing its border y = 0 but with its left border y = 2 running from x = 2 to 14."""
    left = (np.array([[2.0, 2.0], [14.0, 2.0]]), np.array([[0.0, 0.0], [10.0, 0.0]]))
    right = (np.array([[0.0, 0.0], [10.0, 0.0]]), np.array([[0.0, -2.0], [10.0, -2.0]]))
    empty: tuple[tuple[int, ...], ...] = ((), ())
    return LaneGraph(
        ids=("skewed", "straight"),
        left_m=left,
        right_m=right,
        centre_m=tuple((a + b) / 2 for a, b in zip(left, right, strict=True)),
        direction=np.full(2, int(LaneDrivingDirection.Positive), dtype=np.int64),
        speed_limit_mps=np.full(2, 30.0),
        successors=empty,
        predecessors=empty,
        left_neighbour=np.array([-1, 0], dtype=np.int64),
        right_neighbour=np.array([1, -1], dtype=np.int64),
        left_opposite=np.zeros(2, dtype=bool),
        right_opposite=np.zeros(2, dtype=bool),
        is_intersection=np.zeros(2, dtype=bool),
        priority=np.zeros(2, dtype=np.int64),
        traffic_light=np.full(2, -1, dtype=np.int64),
    )


@pytest.mark.parametrize("t", [0.1, 0.5, 0.9])
def test_straight_lane_cut_aligns_the_skewed_neighbour(t):
    # c(t) = P = (10 t, -1): fraction t of the shared border, (10 t - 2) / 12 (clamped)
    # of the skewed lane's left border
    prep = prepare(_skewed_pair())
    expected = 0.5 * (t + min(max((10.0 * t - 2.0) / 12.0, 0.0), 1.0))
    assert prep.aligner.aligned(1, t, 0, t) == pytest.approx(expected, abs=1e-12)


@pytest.mark.parametrize(("t", "expected"), [(0.05, 0.1775), (0.5, 0.65), (0.8, 0.98)])
def test_skewed_lane_cut_projects_its_centre_point_first(t, expected):
    # c(t) = ((2 + 12 t + 10 t) / 2, 1); its nearest points (x clamped to [2, 14] on the
    # left border, to [0, 10] on the right one) have the middle P; the straight lane is cut
    # at P's x / 10. At t = 0.05: c = (1.55, 1), feet (2, 2) and (1.55, 0), P = (1.775, 1)
    prep = prepare(_skewed_pair())
    assert prep.aligner.aligned(0, t, 1, t) == pytest.approx(expected, abs=1e-12)


def test_cut_plan_keeps_the_anchor_and_aligns_the_other_lanes():
    prep = prepare(_skewed_pair())
    plan = SegmentPlan(lanes=[(0, True), (1, True)], p0=0.5, p1=0.9, anchors=(1, 0))
    windows: list[tuple[int, float, float]] = []
    road, placed, _ = build_road(prep, SceneMemo(), [plan], 0, None, windows)
    at_p0 = 0.5 * (0.5 + 0.25)  # skewed lane aligned to the straight one at 0.5
    # straight lane aligned to the skewed one at 0.9: c = (10.9, 1), feet (10.9, 2) and
    # (10, 0), P = (10.45, 1) beyond the straight lane's end: fraction 1
    assert placed[0].p0 == pytest.approx(at_p0, abs=1e-12)
    assert placed[0].p1 == 0.9
    assert placed[1].p0 == 0.5
    assert placed[1].p1 == pytest.approx(1.0, abs=1e-12)
    assert {lane: (a, b) for lane, a, b in windows}[0] == pytest.approx((at_p0, 0.9))
    assert road[0].segment_type == RoadSegmentType.Normal
    # the straight lane's kept piece: 5 m of each 10 m border
    assert road[0].lanes[1].length_min_m == pytest.approx(5.0, abs=1e-9)


def test_plans_without_anchors_cut_every_lane_at_the_same_fraction():
    prep = prepare(_skewed_pair())
    _, placed, _ = build_road(
        prep, SceneMemo(), [SegmentPlan(lanes=[(0, True), (1, True)], p0=0.5)]
    )
    assert placed[0].p0 == placed[1].p0 == 0.5


@pytest.fixture(scope="module")
def town01(external_dir) -> PreparedGraph:
    return prepare(lane_graph_from_map(read_opendrive(external_dir / "maps" / "Town01.xodr")))


def _guess(prep: PreparedGraph, lane: int, other: int, t: float) -> float:
    g = prep.graph
    opposite = g.left_opposite[lane] if g.left_neighbour[lane] == other else g.right_opposite[lane]
    return 1.0 - t if opposite else t


#: ad-map 3.0 (``lane::getProjectedParametricPoint(lane, t, 0.5)``, then the mean of
#: ``point::findNearestPointOnEdge`` on the other lane's two edges), converted to our point
#: order: (cut lane, t, other lane, where ad-map cuts the other lane). The first is pair 38
#: of the cross-check (ego region from 0.782 of ad-map's 200151).
ADMAP_ALIGNED = [
    ("20_0_1", 0.218, "20_0_-1", 0.7621057049387492),
    ("20_0_1", 0.77, "20_0_-1", 0.21963772876292198),
    ("20_0_-1", 0.5, "20_0_1", 0.4699343665699791),
    ("27_0_1", 0.5, "33_0_1", 0.5267331688500898),
    ("33_0_1", 0.218, "27_0_1", 0.7451748323709034),
    ("1_0_1", 0.5, "1_0_-1", 0.5000053888155194),
    ("313_0_-1", 0.218, "312_0_1", 0.737074795613146),
]


@pytest.mark.parametrize(("lane", "t", "other", "expected"), ADMAP_ALIGNED)
def test_town01_cuts_are_ad_maps(town01, lane, t, other, expected):
    ids = list(town01.graph.ids)
    a, b = ids.index(lane), ids.index(other)
    assert town01.aligner.aligned(a, t, b, _guess(town01, a, b, t)) == pytest.approx(
        expected, abs=1e-6
    )


def _slow_aligned(prep: PreparedGraph, lane: int, t: float, other: int) -> float:
    """The same rule with the vectorised nearest-point search over whole borders."""
    n = len(prep.graph)
    borders = prep.borders
    both = np.array([lane, lane + n])
    ends = interpolate(borders, both, t * borders.length_m[both])
    centre = ends.mean(axis=0)
    s, feet = prep.border_index.nearest(both, np.stack([centre, centre]))
    p = feet.mean(axis=0)
    lines = np.array([other, other + n])
    s, _ = prep.border_index.nearest(lines, np.stack([p, p]))
    return float(np.mean(s / borders.length_m[lines]))


def test_town01_windowed_search_equals_the_whole_border_search(town01):
    g = town01.graph
    ts = np.linspace(0.0, 1.0, 41)
    checked = 0
    for lane in range(len(g)):
        for other in (int(g.left_neighbour[lane]), int(g.right_neighbour[lane])):
            if other < 0:
                continue
            for t in ts:
                fast = town01.aligner.aligned(lane, float(t), other, _guess(town01, lane, other, t))
                assert fast == pytest.approx(
                    _slow_aligned(town01, lane, float(t), other), abs=1e-12
                )
                checked += 1
    assert checked > 41 * 50
