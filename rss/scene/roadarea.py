"""Road areas from routes, and objects placed in them (regions + lane-frame speeds).

A :class:`SegmentPlan` is one road segment before conversion: its lanes left to right
(in the road-area direction) with their orientation, and the parametric window
``[p0, p1]`` of the road-area direction it keeps. The first and last segments are cut at
the rear of the rear vehicle and at the front of the front vehicle, so no length
uncertainty outside the two vehicles stretches them ("restricted road area")::

      p0 (rear vehicle's rear)                 p1 (front vehicle's front)
      │ ┌──┐                                     ┌──┐ │
   ───┼─┤  ├─────────── segment k ... k' ────────┤  ├─┼───▶ road-area direction
      │ └──┘                                     └──┘ │

Regions are mapped from the lane's point order to the road-area direction (reversed lanes
flip lon and lat) and then into the window. A cut lane's lengths are those of its projected
border pieces and its widths ad-map's width range (``rss.scene.cache.LaneSegmentCache``).
"""

from __future__ import annotations

import bisect
import math
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, NamedTuple

import numpy as np

from rss.model import (
    LaneObject,
    ObjectType,
    OccupiedRegion,
    RoadSegment,
    RoadSegmentType,
    SpeedInterval,
)
from rss.scene.routes import Step  # noqa: TC001 - dataclass field types, read at run time when compiled (mypyc)

if TYPE_CHECKING:
    from collections.abc import Sequence

    from rss.arrays import FloatArray
    from rss.scene.align import Aligner
    from rss.scene.cache import LaneMiddle
    from rss.scene.lanegraph import PreparedGraph
    from rss.scene.matching import Matches

__all__ = [
    "Between",
    "BuiltSegment",
    "PlacedLane",
    "SegmentPlan",
    "between",
    "build_road",
    "cut_at",
    "cut_between",
    "cut_window",
    "fresh_ends",
    "lane_heading",
    "lane_window",
    "place_object",
    "plan_lanes",
]


@dataclass(slots=True)
class SegmentPlan:
    """One road segment before conversion.

    Attributes:
        lanes: ``(lane, forward)`` left to right in the road-area direction.
        segment_type: Normal or Intersection.
        before_m: Intersection only: length before the intersecting area.
        after_m: Intersection only: length after it.
        p0: Kept window start (road-area direction, parametric).
        p1: Kept window end.
        whole: ``(id offset, conversion)`` of the uncut plan, kept by :func:`build_road`
            (plans shared by memos skip the lookup; only ``p0`` / ``p1`` / ``anchors``
            may change).
        anchors: The lanes cut exactly at ``p0`` and at ``p1`` (-1: none, every lane is
            cut at the same fraction); the other lanes are cut where ad-map aligns them
            (``rss.scene.align``).
    """

    lanes: list[Step]
    segment_type: RoadSegmentType = RoadSegmentType.Normal
    before_m: float = 0.0
    after_m: float = 0.0
    p0: float = 0.0
    p1: float = 1.0
    whole: tuple[int, BuiltSegment] | None = field(default=None, repr=False, compare=False)
    anchors: tuple[int, int] = (-1, -1)


def fresh_ends(plans: Sequence[SegmentPlan], *, last: bool = True) -> list[SegmentPlan]:
    """``plans`` as a new list whose first and last plans (the ones cuts change) are copies.

    For plans shared by memos: the others are handed out as they are (so is the last one
    without ``last``, for cuts that keep the end).
    """
    out = list(plans)
    for k in {0, len(out) - 1 if last else 0} if out else ():
        p = out[k]
        out[k] = SegmentPlan(
            p.lanes, p.segment_type, p.before_m, p.after_m, p.p0, p.p1, p.whole, p.anchors
        )
    return out


class PlacedLane(NamedTuple):
    """Where a map lane sits in one road area.

    Attributes:
        lane_id: Id in the road area.
        forward: Point order runs along the road-area direction.
        p0: Window start.
        p1: Window end.
    """

    lane_id: int
    forward: bool
    p0: float
    p1: float


def _road_param(
    lo: float, hi: float, *, forward: bool
) -> tuple[float, float]:  # lane point order -> road-area direction
    return (lo, hi) if forward else (1.0 - hi, 1.0 - lo)


def lane_window(p0: float, p1: float, *, forward: bool) -> tuple[float, float]:
    """A road-area window ``[p0, p1]`` of a lane as a window along its point order."""
    return _road_param(p0, p1, forward=forward)


def plan_lanes(plans: Sequence[Sequence[Step]]) -> dict[int, tuple[int, bool]]:
    """Segment index and orientation of each lane of segment plans' lanes, by lane."""
    return {lane: (k, fwd) for k, lanes in enumerate(plans) for lane, fwd in lanes}


def _extent(
    where: dict[int, tuple[int, bool]], matches: Matches, box: int
) -> tuple[tuple[int, float], tuple[int, float]] | None:
    """``((segment, param) of the rear, (segment, param) of the front)`` of a box."""
    ends: list[tuple[int, float]] = []
    for region in matches.regions(box):
        hit = where.get(region.lane)
        if hit is not None:
            lo, hi = _road_param(region.lon_min, region.lon_max, forward=hit[1])
            ends += [(hit[0], lo), (hit[0], hi)]
    return (min(ends), max(ends)) if ends else None


#: Where a road area between two boxes is cut: ``((k0, p0), (k1, p1), rear box, front box)``
#: keeps segments ``k0..k1``, from ``p0`` of the first to ``p1`` of the last.
Between = tuple[tuple[int, float], tuple[int, float], int, int]


def between(
    where: dict[int, tuple[int, bool]], matches: Matches, boxes: tuple[int, int]
) -> Between | None:
    """Where :func:`cut_between` cuts plans with lanes ``where`` (from :func:`plan_lanes`)."""
    a, b = (_extent(where, matches, box) for box in boxes)
    if a is None or b is None:
        return None
    (rear, front), (rear_box, front_box) = (
        ((a, b), boxes) if a[1] <= b[0] else ((b, a), boxes[::-1])
    )
    if rear[1] >= front[0]:
        return None
    return rear[1], front[0], rear_box, front_box


def cut_between(
    plans: list[SegmentPlan], matches: Matches, boxes: tuple[int, int]
) -> dict[int, tuple[int, float]] | None:
    """Keep only the road between two boxes, as ad-rss' connecting-route road areas do.

    The road area then starts at the front of the rear vehicle and ends at the rear of the
    front vehicle (both keep zero-length regions at the ends), so no length uncertainty
    of the lanes under the vehicles stretches the gap. Returns, per box, the route end it
    touches as ``(lane, parametric position in its point order)``, or ``None`` (plans
    unchanged) where the boxes overlap longitudinally.
    """
    cut = between(plan_lanes([plan.lanes for plan in plans]), matches, boxes)
    return None if cut is None else cut_at(plans, matches, cut)


def cut_at(
    plans: list[SegmentPlan], matches: Matches, cut: Between
) -> dict[int, tuple[int, float]]:
    """Cut ``plans`` in place where :func:`between` says; the route ends at each box.

    Each end is cut exactly in the lane of the box region that reaches furthest towards
    the other box, the lanes beside it where ad-map aligns them (``SegmentPlan.anchors``).
    """
    (k0, p0), (k1, p1), rear_box, front_box = cut
    del plans[k1 + 1 :]
    del plans[:k0]
    plans[0].p0 = min(p0, 1.0 - 0.001)
    plans[-1].p1 = max(p1, plans[-1].p0 + 0.001)
    first = _anchor(plans[0], matches, rear_box, front=True)
    last = _anchor(plans[-1], matches, front_box, front=False)
    plans[0].anchors = (first, plans[0].anchors[1])
    plans[-1].anchors = (plans[-1].anchors[0], last)
    ends = {}
    for box, plan, at in ((rear_box, plans[0], plans[0].p0), (front_box, plans[-1], plans[-1].p1)):
        lanes = {region.lane for region in matches.regions(box)}
        lane, fwd = plan.lanes[0]
        for step in plan.lanes:
            if step[0] in lanes:
                lane, fwd = step
                break
        ends[box] = (lane, at if fwd else 1.0 - at)
    return ends


def _anchor(plan: SegmentPlan, matches: Matches, box: int, *, front: bool) -> int:
    """The lane of ``plan`` where ``box`` reaches furthest forward (``front``) or back."""
    lanes = dict(plan.lanes)
    best, lane = -math.inf, -1
    for region in matches.regions(box):
        fwd = lanes.get(region.lane)
        if fwd is not None:
            lo, hi = _road_param(region.lon_min, region.lon_max, forward=fwd)
            reach = hi if front else -lo
            if reach > best:
                best, lane = reach, region.lane
    return lane


#: ad-map measures a lane's heading over this stretch [m] around the position.
_HEADING_SPAN_M = 0.1


def _fractions(line: FloatArray) -> tuple[list[float], float]:
    """Arc-length fraction of each vertex of a polyline, and its length [m]."""
    arc = np.concatenate([[0.0], np.cumsum(np.hypot(*np.diff(line, axis=0).T))])
    return (arc / arc[-1] if arc[-1] > 0.0 else arc).tolist(), float(arc[-1])


def _middle(prep: PreparedGraph, lane: int) -> LaneMiddle:
    """ad-map's middle line of a lane by border fraction (cached per prepared graph).

    The mean of the left and right border points at the same fraction of each border's
    length is linear in the fraction between the vertices of either border, so it is the
    polyline through its values at the union of both borders' vertex fractions: returns
    those fractions, the x and y of the middle points there, and the mean border length.
    """
    middles = prep.scalars.lane_middles
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


def lane_heading(prep: PreparedGraph, lane: int, param: float) -> float:
    """Heading [rad] of ``lane``'s point order at parametric position ``param``.

    As ad-map (``getLaneECEFDirection``): the direction between the lane's middle points
    ``param -+ 5 cm`` (of the mean border length; at the ends the 10 cm next to them),
    a middle point being the mean of the two border points at that fraction of each
    border's length (:func:`_middle`). On a curve these differ from the centre line's
    points, whose fraction is taken along the centre line.
    """
    ts, xs, ys, length = _middle(prep, lane)
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


def cut_window(
    plans: list[SegmentPlan],
    matches: Matches,
    boxes: tuple[int, ...],
    *,
    cut_end: bool = True,
    cut_intersection: bool = False,
) -> None:
    """Cut the first (and last) segment at the outermost extent of ``boxes`` (in place).

    Intersection segments are kept whole unless ``cut_intersection`` (ad-rss 5.0 cuts a
    vehicle's intersection road area at its rear also on its conflict lane; reproduced
    under ``[scene] reproduce_adrss_5_0_defects``).
    """
    if not plans:
        return
    first, last = plans[0], plans[-1]
    normal = RoadSegmentType.Normal
    start = dict(first.lanes) if cut_intersection or first.segment_type == normal else {}
    end = dict(last.lanes) if cut_end and last.segment_type == normal else {}
    if not (start or end):
        return
    lo = hi = math.nan
    for box in boxes:
        for region in matches.regions(box):
            fwd = start.get(region.lane)
            if fwd is not None:
                v = region.lon_min if fwd else 1.0 - region.lon_max
                lo = v if not v >= lo else lo  # NaN-aware minimum
            fwd = end.get(region.lane)
            if fwd is not None:
                v = region.lon_max if fwd else 1.0 - region.lon_min
                hi = v if not v <= hi else hi
    if not math.isnan(lo):
        first.p0 = max(0.0, min(lo, 1.0 - 0.001))
    if not math.isnan(hi):
        last.p1 = min(1.0, max(hi, last.p0 + 0.001))


#: A converted plan: road segment, placed lanes, finite speed limits of its lanes, and
#: each lane's window along its point order ``(lane, start, end)``.
BuiltSegment = tuple[
    RoadSegment,
    tuple[tuple[int, PlacedLane], ...],
    tuple[float, ...],
    tuple[tuple[int, float, float], ...],
]


def build_road(
    prep: PreparedGraph,
    plans: list[SegmentPlan],
    id_offset: int = 0,
    cut_memo: dict[tuple[object, ...], BuiltSegment] | None = None,
    windows: list[tuple[int, float, float]] | None = None,
) -> tuple[tuple[RoadSegment, ...], dict[int, PlacedLane], float]:
    """Convert segment plans into ``rss.model`` road segments.

    Whole (uncut) plans are converted once per map; cut ones once per ``cut_memo`` (e.g.
    one frame, where the ego's cut starts many road areas), if given. ``windows``, if
    given, receives each lane's kept window along its point order ``(lane, start, end)``.

    Returns:
        ``(road, placed, max_speed_limit_mps)``: the road segments, where every map lane
        sits, and the largest finite speed limit of its lanes (NaN if none).
    """
    road: list[RoadSegment] = []
    placed: dict[int, PlacedLane] = {}
    limits: list[float] = []
    for plan in plans:
        whole = plan.whole
        if whole is not None and whole[0] == id_offset and plan.p0 == 0.0 and plan.p1 == 1.0:
            built = whole[1]  # converted before (hot path)
        else:
            built = _built(prep, plan, id_offset, cut_memo)
        road.append(built[0])
        placed.update(built[1])
        limits.extend(built[2])
        if windows is not None:
            windows.extend(built[3])
    return tuple(road), placed, max(limits) if limits else float("nan")


def _built(
    prep: PreparedGraph,
    plan: SegmentPlan,
    id_offset: int,
    cut_memo: dict[tuple[object, ...], BuiltSegment] | None,
) -> BuiltSegment:
    """One plan converted: whole plans once per map, cut ones once per memo.

    A whole plan keeps its conversion (``plan.whole``); :func:`build_road` takes it from
    there, so this function only sees plans converted for the first time or cut.
    """
    uncut = plan.p0 == 0.0 and plan.p1 == 1.0
    memo = prep.lane_segments.whole_roads if uncut else cut_memo
    if memo is None:
        return _segment(prep, plan, id_offset)
    key: tuple[object, ...] = (
        tuple(plan.lanes),
        plan.segment_type,
        plan.before_m,
        plan.after_m,
        id_offset,
    )
    if not uncut:
        key = (*key, plan.p0, plan.p1, plan.anchors)
    built = memo.get(key)
    if built is None:
        memo[key] = built = _segment(prep, plan, id_offset)
    if uncut:
        plan.whole = (id_offset, built)
    return built


def _segment(prep: PreparedGraph, plan: SegmentPlan, id_offset: int) -> BuiltSegment:
    """One plan as ``(road segment, placed lanes, finite speed limits of its lanes)``."""
    segments = prep.lane_segments
    speed_limits = prep.scalars.speed_limit_mps
    lanes = []
    placed = []
    windows = []
    for (lane, fwd), (p0, p1) in zip(plan.lanes, _windows(prep, plan), strict=True):
        lanes.append(segments.lane_segment(lane, forward=fwd, id_offset=id_offset, p0=p0, p1=p1))
        placed.append((lane, PlacedLane(lane + id_offset, fwd, p0, p1)))
        windows.append((lane, *lane_window(p0, p1, forward=fwd)))
    segment = RoadSegment(
        lanes=tuple(lanes),
        segment_type=plan.segment_type,
        min_length_before_intersecting_area_m=plan.before_m,
        min_length_after_intersecting_area_m=plan.after_m,
    )
    finite = tuple(v for lane, _ in plan.lanes if math.isfinite(v := speed_limits[lane]))
    return segment, tuple(placed), finite, tuple(windows)


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
