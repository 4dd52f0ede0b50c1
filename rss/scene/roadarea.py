"""Road areas from segment plans, and objects placed in them (regions + lane-frame speeds).

:func:`build_road` converts :class:`~rss.scene.segment_plans.SegmentPlan` s into
``rss.model`` road segments: whole (uncut) plans once per map, cut ones once per frame.
A cut lane's lengths are those of its projected border pieces and its widths ad-map's
width range (``rss.scene.lane_segments``); the lanes beside a cut lane are cut where
ad-map aligns them (``rss.scene.align``). :func:`place_object` maps a box's regions into
a road area; :func:`lane_heading` is ad-map's heading of a lane at a position.
"""

from __future__ import annotations

import bisect
import math
from typing import TYPE_CHECKING

import numpy as np

from rss.model import (
    LaneObject,
    LaneSegment,
    ObjectType,
    OccupiedRegion,
    RoadSegment,
    SpeedInterval,
)
from rss.scene.segment_plans import PlacedLane, lane_window

if TYPE_CHECKING:
    from rss.arrays import FloatArray
    from rss.scene.align import Aligner
    from rss.scene.lanegraph import Step
    from rss.scene.match_records import Matches
    from rss.scene.memo import LaneMiddle, SceneMemo
    from rss.scene.prepared import PreparedGraph
    from rss.scene.segment_plans import BuiltSegment, SegmentPlan

__all__ = ["build_road", "lane_heading", "place_object"]


#: ad-map measures a lane's heading over this stretch [m] around the position.
_HEADING_SPAN_M = 0.1


def _fractions(line: FloatArray) -> tuple[list[float], float]:
    """Arc-length fraction of each vertex of a polyline, and its length [m]."""
    arc = np.concatenate([[0.0], np.cumsum(np.hypot(*np.diff(line, axis=0).T))])
    return (arc / arc[-1] if arc[-1] > 0.0 else arc).tolist(), float(arc[-1])


def _middle(prep: PreparedGraph, memo: SceneMemo, lane: int) -> LaneMiddle:
    """ad-map's middle line of a lane by border fraction (kept in ``memo``).

    The mean of the left and right border points at the same fraction of each border's
    length is linear in the fraction between the vertices of either border, so it is the
    polyline through its values at the union of both borders' vertex fractions: returns
    those fractions, the x and y of the middle points there, and the mean border length.
    """
    middles = memo.lane_middles
    known = middles.get(lane)
    if known is None:
        left, right = prep.graph.left_m[lane], prep.graph.right_m[lane]
        (tl, len_l), (tr, len_r) = _fractions(left), _fractions(right)
        ts = np.union1d(tl, tr)
        xs = 0.5 * (np.interp(ts, tl, left[:, 0]) + np.interp(ts, tr, right[:, 0]))
        ys = 0.5 * (np.interp(ts, tl, left[:, 1]) + np.interp(ts, tr, right[:, 1]))
        known = (ts.tolist(), xs.tolist(), ys.tolist(), 0.5 * (len_l + len_r))
        middles[lane] = known
    return known


def lane_heading(prep: PreparedGraph, memo: SceneMemo, lane: int, param: float) -> float:
    """Heading [rad] of ``lane``'s point order at parametric position ``param``.

    As ad-map (``getLaneECEFDirection``): the direction between the lane's middle points
    ``param -+ 5 cm`` (of the mean border length; at the ends the 10 cm next to them),
    a middle point being the mean of the two border points at that fraction of each
    border's length (:func:`_middle`). On a curve these differ from the centre line's
    points, whose fraction is taken along the centre line.
    """
    ts, xs, ys, length = _middle(prep, memo, lane)
    if length < _HEADING_SPAN_M:
        t0, t1 = 0.0, 1.0
    else:
        delta = _HEADING_SPAN_M / length
        t0 = min(max(param - 0.5 * delta, 0.0), 1.0 - delta)
        t1 = t0 + delta
    last = len(ts) - 2
    k0 = min(max(bisect.bisect_right(ts, t0) - 1, 0), last)
    k1 = min(max(bisect.bisect_right(ts, t1) - 1, 0), last)
    if k0 == k1:
        return math.atan2(ys[k0 + 1] - ys[k0], xs[k0 + 1] - xs[k0])
    u0 = (t0 - ts[k0]) / (ts[k0 + 1] - ts[k0])
    u1 = (t1 - ts[k1]) / (ts[k1 + 1] - ts[k1])
    x0, y0 = xs[k0] + u0 * (xs[k0 + 1] - xs[k0]), ys[k0] + u0 * (ys[k0 + 1] - ys[k0])
    x1, y1 = xs[k1] + u1 * (xs[k1 + 1] - xs[k1]), ys[k1] + u1 * (ys[k1 + 1] - ys[k1])
    return math.atan2(y1 - y0, x1 - x0)


def build_road(  # noqa: PLR0917 - the plans, then where the results go
    prep: PreparedGraph,
    memo: SceneMemo,
    plans: list[SegmentPlan],
    id_offset: int = 0,
    cut_memo: dict[tuple[object, ...], BuiltSegment] | None = None,
    windows: list[tuple[int, float, float]] | None = None,
    unknown_limit_mps: float = math.inf,
) -> tuple[tuple[RoadSegment, ...], dict[int, PlacedLane], float]:
    """Convert segment plans into ``rss.model`` road segments.

    Whole (uncut) plans are converted once per map (``memo``); cut ones once per
    ``cut_memo`` (e.g. one frame, where the ego's cut starts many road areas), if given.
    ``windows``, if given, receives each lane's kept window along its point order
    ``(lane, start, end)``. ``unknown_limit_mps`` stands for the speed limit of a lane
    that has none (default: unbounded).

    Returns:
        ``(road, placed, max_speed_limit_mps)``: the road segments, where every map lane
        sits, and the largest speed limit of its lanes (NaN without lanes).
    """
    road: list[RoadSegment] = []
    placed: dict[int, PlacedLane] = {}
    limits: list[float] = []
    for plan in plans:
        whole = plan.whole
        if whole is not None and whole[0] == id_offset and plan.p0 == 0.0 and plan.p1 == 1.0:
            built = whole[1]  # converted before (hot path)
        else:
            built = _built(prep, memo, plan, id_offset, cut_memo)
        road.append(built[0])
        placed.update(built[1])
        limits.extend(unknown_limit_mps if math.isnan(v) else v for v in built[2])
        if windows is not None:
            windows.extend(built[3])
    return tuple(road), placed, max(limits) if limits else float("nan")


def _built(
    prep: PreparedGraph,
    memo: SceneMemo,
    plan: SegmentPlan,
    id_offset: int,
    cut_memo: dict[tuple[object, ...], BuiltSegment] | None,
) -> BuiltSegment:
    """One plan converted: whole plans once per map, cut ones once per memo.

    A whole plan keeps its conversion (``plan.whole``); :func:`build_road` takes it from
    there, so this function only sees plans converted for the first time or cut.
    """
    uncut = plan.p0 == 0.0 and plan.p1 == 1.0
    built_memo = memo.whole_roads if uncut else cut_memo
    if built_memo is None:
        return _segment(prep, memo, plan, id_offset)
    key: tuple[object, ...] = (
        tuple(plan.lanes),
        plan.segment_type,
        plan.before_m,
        plan.after_m,
        id_offset,
        plan.pad_left,
    )
    if not uncut:
        key = (*key, plan.p0, plan.p1, plan.anchors)
    built = built_memo.get(key)
    if built is None:
        built_memo[key] = built = _segment(prep, memo, plan, id_offset)
    if uncut:
        plan.whole = (id_offset, built)
    return built


def _segment(
    prep: PreparedGraph, memo: SceneMemo, plan: SegmentPlan, id_offset: int
) -> BuiltSegment:
    """One plan as ``(road segment, placed lanes, speed limits of its lanes (NaN: none))``."""
    segments = prep.lane_segments
    whole = memo.whole_lanes
    speed_limits = prep.scalars.speed_limit_mps
    lanes = []
    placed = []
    windows = []
    for (lane, fwd), (p0, p1) in zip(plan.lanes, _windows(prep, plan), strict=True):
        lanes.append(
            segments.lane_segment(whole, lane, forward=fwd, id_offset=id_offset, p0=p0, p1=p1)
        )
        placed.append((lane, PlacedLane(lane + id_offset, fwd, p0, p1)))
        windows.append((lane, *lane_window(p0, p1, forward=fwd)))
    if plan.pad_left:
        lanes = _padding(prep, memo, plan, id_offset, lanes) + lanes
    segment = RoadSegment(
        lanes=tuple(lanes),
        segment_type=plan.segment_type,
        min_length_before_intersecting_area_m=plan.before_m,
        min_length_after_intersecting_area_m=plan.after_m,
    )
    limits = tuple(speed_limits[lane] for lane, _ in plan.lanes)
    return segment, tuple(placed), limits, tuple(windows)


#: Lane ids of padding lane segments start here (above every map lane id and offset).
PAD_LANE_ID = 2**50


def _padding(
    prep: PreparedGraph,
    memo: SceneMemo,
    plan: SegmentPlan,
    id_offset: int,
    lanes: list[LaneSegment],
) -> list[LaneSegment]:
    """Lane segments for ``plan.pad_left``, no vehicle in them.

    Each has its lane's width range over the whole lane and the segment's length range
    (so the segment's lengths do not change); ids from :data:`PAD_LANE_ID`, unique by
    the segment's first lane.
    """
    length_min = min(s.length_min_m for s in lanes)
    length_max = max(s.length_max_m for s in lanes)
    first = plan.lanes[0][0] + id_offset
    out = []
    for n, (lane, fwd) in enumerate(plan.pad_left):
        width = prep.lane_segments.lane_segment(memo.whole_lanes, lane, forward=fwd)
        out.append(
            LaneSegment(
                lane_id=PAD_LANE_ID + first * 16 + n,
                driving_direction=width.driving_direction,
                length_min_m=length_min,
                length_max_m=length_max,
                width_min_m=width.width_min_m,
                width_max_m=width.width_max_m,
            )
        )
    return out


def _windows(prep: PreparedGraph, plan: SegmentPlan) -> list[tuple[float, float]]:
    """Each lane's kept window ``(p0, p1)`` (road-area direction) of a plan.

    ``p0`` and ``p1`` for every lane, except that a cut end with an anchor lane is cut
    exactly there only in the anchor, elsewhere where ad-map aligns it
    (``rss.scene.align``); each window keeps at least 0.001.
    """
    p0, p1 = plan.p0, plan.p1
    a0, a1 = plan.anchors
    if (a0 < 0 or p0 <= 0.0) and (a1 < 0 or p1 >= 1.0):
        return [(p0, p1)] * len(plan.lanes)
    lanes = dict(plan.lanes)
    aligner = prep.aligner
    out = []
    for lane, fwd in plan.lanes:
        lo, hi = p0, p1
        if a0 >= 0 and p0 > 0.0 and lane != a0:
            lo = _aligned(aligner, (a0, lanes[a0]), p0, (lane, fwd))
        if a1 >= 0 and p1 < 1.0 and lane != a1:
            hi = _aligned(aligner, (a1, lanes[a1]), p1, (lane, fwd))
        lo = min(lo, 1.0 - 0.001)
        out.append((lo, max(hi, lo + 0.001)))
    return out


def _aligned(aligner: Aligner, anchor: Step, p: float, step: Step) -> float:
    """Road-area position where ad-map cuts ``step`` when it cuts ``anchor`` at ``p``."""
    t = p if anchor[1] else 1.0 - p
    fwd = step[1]
    at = aligner.aligned(anchor[0], t, step[0], p if fwd else 1.0 - p)
    return min(max(at if fwd else 1.0 - at, 0.0), 1.0)


def place_object(  # noqa: PLR0917 - one object: identity, matches, velocity
    matches: Matches,
    box: int,
    placed: dict[int, PlacedLane],
    object_id: int,
    object_type: ObjectType,
    velocity_mps: tuple[float, float],
    headings: dict[int, float],
    route_heading_rad: float | None = None,
) -> LaneObject | None:
    """Regions and lane-frame speeds of ``box`` in a road area; ``None`` if outside it.

    Args:
        matches: Map matching of the frame.
        box: The box index.
        placed: Lanes of the road area (from :func:`build_road`).
        object_id: Id in the constellation.
        object_type: ad-rss object type.
        velocity_mps: ``(vx, vy)`` in the map frame.
        headings: Heading of each lane's point order at the box centre (by lane index).
        route_heading_rad: Road-area direction where the connecting route touches the
            box (ad-rss ``route_heading_start/end``); replaces the lane heading at its centre.
    """
    regions = []
    heading = None
    anchor = matches.anchors[box]
    for lane, lon_min, lon_max, lat_min, lat_max, _ in matches.regions(box):
        where = placed.get(lane)
        if where is None:
            continue
        lane_id, fwd, p0, p1 = where
        if fwd:
            lo, hi, la, lb = lon_min, lon_max, lat_min, lat_max
        else:  # as _road_param, inlined (hot path)
            lo, hi, la, lb = 1.0 - lon_max, 1.0 - lon_min, 1.0 - lat_max, 1.0 - lat_min
        span = p1 - p0
        # A part beyond the window (the road area is cut at the other end of the vehicle
        # in another of its lanes) stays as a zero-length region at the window's end:
        # ad-rss cuts every lane of a road segment at the vehicle's region in that lane.
        lo, hi = (lo - p0) / span, (hi - p0) / span
        regions.append(
            OccupiedRegion(
                lane_id,
                min(1.0, max(0.0, lo)),
                min(1.0, max(0.0, hi)),
                min(1.0, max(0.0, la)),
                min(1.0, max(0.0, lb)),
            )
        )
        if heading is None or lane == anchor:
            heading = headings[lane] + (0.0 if fwd else math.pi)
    if not regions or heading is None:
        return None
    if route_heading_rad is not None:
        heading = route_heading_rad
    vx, vy = velocity_mps
    c, s = math.cos(heading), math.sin(heading)
    lon = float(abs(vx * c + vy * s))
    lat = float(vx * s - vy * c)
    return LaneObject(object_id, object_type, tuple(regions), SpeedInterval(lon, lon, lat, lat))
