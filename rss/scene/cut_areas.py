"""ad-rss 5.0's intersecting area of two intersection road areas cut at the vehicles.

Compatibility mode only (``[scene] reproduce_adrss_5_0_defects``, docs/rss_scene.md): ad-rss
starts a vehicle's intersection road area at its rear also when the vehicle already
drives on its conflict lane, and measures the part of each conflict lane inside the
*other* lane's kept window (``extractInnerRegions``) within its own kept window::

    lane a (kept from the ego's rear)   |----before----|== common ==|---after---|
    lane b (kept from the object's rear)          |xxxx|== common ==|-----------|
                                                  ^ object's rear: b's part behind
                                                    it is no longer common area

The default mode keeps intersection road areas whole and measures on the whole lanes
(``rss.scene.junction_pairs.area_span``).
"""

from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np
import shapely

from rss.scene.matching_points import ad_map_positions
from rss.scene.memo import memoised
from rss.scene.segment_plans import lane_window

if TYPE_CHECKING:
    from rss.arrays import FloatArray
    from rss.scene.memo import SceneMemo
    from rss.scene.prepared import PreparedGraph
    from rss.scene.segment_plans import SegmentPlan

__all__ = ["cut_area_spans"]


def _border_fractions(
    prep: PreparedGraph, _memo: SceneMemo, lane: int
) -> tuple[FloatArray, FloatArray]:
    """Arc-length fraction of every vertex of the left and right border of ``lane``."""
    g = prep.graph
    out = []
    for border in (g.left_m[lane], g.right_m[lane]):
        arc = np.concatenate([[0.0], np.cumsum(np.hypot(*np.diff(border, axis=0).T))])
        out.append(arc / arc[-1] if arc[-1] > 0.0 else arc)
    return out[0], out[1]


def _window_polygon(
    prep: PreparedGraph, memo: SceneMemo, lane: int, w0: float, w1: float
) -> shapely.Geometry:
    """The area of ``lane`` between fractions ``w0 < w1`` of its borders (point order).

    From the borders as given (not the simplified ``prep.polygons``), as ad-map builds a
    lane interval's polygon: lanes side by side then only touch.
    """
    g = prep.graph
    rings = []
    fractions = memoised(prep, memo, _border_fractions, lane)
    for border, f in zip((g.left_m[lane], g.right_m[lane]), fractions, strict=True):
        inner = border[(f > w0) & (f < w1)]
        ends = [[np.interp(w, f, border[:, 0]), np.interp(w, f, border[:, 1])] for w in (w0, w1)]
        rings.append(np.concatenate([[ends[0]], inner, [ends[1]]]))
    return shapely.Polygon(np.concatenate([rings[0], rings[1][::-1]]))


def _window_span(
    prep: PreparedGraph, memo: SceneMemo, lane: int, window: tuple[float, float], points: FloatArray
) -> tuple[float, float] | None:
    """Lengths [m] of ``lane``'s window before and after the region of ``points`` (``(Q, 2)``).

    The region is ad-map's: the points matched to the lane with its point rule, clipped to
    the window; the lengths those of the shorter projected border piece
    (``getMetricRanges``), in the lane's point order. ``None`` if the region misses it.
    """
    w0, w1 = window
    lon, _, _ = ad_map_positions(prep, np.full(len(points), lane), points)
    lo, hi = max(float(np.min(lon)), w0), min(float(np.max(lon)), w1)
    if lo > hi:
        return None
    pieces, whole = prep.lane_segments, memo.whole_lanes
    before = (
        pieces.lane_segment(whole, lane, forward=True, p0=w0, p1=lo).length_min_m
        if lo > w0
        else 0.0
    )
    after = (
        pieces.lane_segment(whole, lane, forward=True, p0=hi, p1=w1).length_min_m
        if w1 > hi
        else 0.0
    )
    return before, after


def _cut_spans(  # noqa: PLR0917 - positional: the memo key
    prep: PreparedGraph,
    memo: SceneMemo,
    lane_a: int,
    window_a: tuple[float, float],
    lane_b: int,
    window_b: tuple[float, float],
) -> tuple[tuple[float, float] | None, tuple[float, float] | None]:
    """:func:`_window_span` of both lanes for the area common to their two windows."""
    shared = shapely.intersection(
        _window_polygon(prep, memo, lane_a, *window_a),
        _window_polygon(prep, memo, lane_b, *window_b),
    )
    parts = shapely.get_parts(shared)
    areas = parts[shapely.area(parts) > 0.0]
    if not len(areas):
        return None, None
    points = shapely.get_coordinates(areas)
    return (
        _window_span(prep, memo, lane_a, window_a, points),
        _window_span(prep, memo, lane_b, window_b, points),
    )


def cut_area_spans(prep: PreparedGraph, memo: SceneMemo, a: SegmentPlan, b: SegmentPlan) -> bool:
    """ad-rss 5.0: the intersecting area of two conflict plans within their cut windows.

    Where a vehicle's road area is cut on its conflict lane (``cut_window`` with
    ``cut_intersection``), ad-rss takes each conflict lane's region inside the *other*
    lane's kept window (``extractInnerRegions``: the polygons common to the two windows,
    their vertices matched to the lane as ad-map matches points) and the lengths before
    and after it within the lane's own window (``getMetricRanges``: the shorter projected
    border piece). Sets ``before_m`` / ``after_m`` of ``a`` and ``b`` (single-lane plans)
    in place; plans without any cut keep ``junction_pairs.area_span``'s values. Memoised
    per map by the two windows.

    Returns:
        Whether the two windows still intersect; where they do not, ad-rss appends a
        ``NotRelevant`` constellation instead of the intersection one.
    """
    (lane_a, fwd_a), (lane_b, fwd_b) = a.lanes[0], b.lanes[0]
    window_a = lane_window(a.p0, a.p1, forward=fwd_a)
    window_b = lane_window(b.p0, b.p1, forward=fwd_b)
    if window_a == window_b == (0.0, 1.0):
        return True
    spans = memoised(prep, memo, _cut_spans, lane_a, window_a, lane_b, window_b)
    for plan, forward, span in ((a, fwd_a, spans[0]), (b, fwd_b, spans[1])):
        if span is None:
            return False
        plan.before_m, plan.after_m = span if forward else span[::-1]
        plan.whole = None
    return True
