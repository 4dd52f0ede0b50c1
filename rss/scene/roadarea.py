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
flip lon and lat) and then into the window. Lane lengths scale with the window; widths are
the min / max over the window.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np

from rss.model import (
    LaneDrivingDirection,
    LaneObject,
    LaneSegment,
    ObjectType,
    OccupiedRegion,
    RoadSegment,
    RoadSegmentType,
    SpeedInterval,
)

if TYPE_CHECKING:
    from rss.scene.lanegraph import PreparedGraph
    from rss.scene.matching import Matches
    from rss.scene.routes import Step

__all__ = ["PlacedLane", "SegmentPlan", "build_road", "cut_window", "place_object"]

_EPS = 1e-6


@dataclass
class SegmentPlan:
    """One road segment before conversion.

    Attributes:
        lanes: ``(lane, forward)`` left to right in the road-area direction.
        segment_type: Normal or Intersection.
        before_m: Intersection only: length before the intersecting area.
        after_m: Intersection only: length after it.
        p0: Kept window start (road-area direction, parametric).
        p1: Kept window end.
    """

    lanes: list[Step]
    segment_type: RoadSegmentType = RoadSegmentType.Normal
    before_m: float = 0.0
    after_m: float = 0.0
    p0: float = 0.0
    p1: float = 1.0


@dataclass(frozen=True)
class PlacedLane:
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


def _direction(prep: PreparedGraph, lane: int, *, forward: bool) -> LaneDrivingDirection:
    code = LaneDrivingDirection(int(prep.graph.direction[lane]))
    if code == LaneDrivingDirection.Bidirectional or forward:
        return code
    if code == LaneDrivingDirection.Positive:
        return LaneDrivingDirection.Negative
    return LaneDrivingDirection.Positive


def cut_window(
    plans: list[SegmentPlan], matches: Matches, boxes: tuple[int, ...], *, cut_end: bool = True
) -> None:
    """Cut the first (and last) segment at the outermost extent of ``boxes`` (in place)."""
    if not plans:
        return
    first, last = plans[0], plans[-1]
    lo: list[float] = []
    hi: list[float] = []
    for i in (i for box in boxes for i in matches.rows(box)):
        lane = int(matches.lane[i])
        for plan, out, pick in ((first, lo, 0), (last, hi, 1)):
            for lane_k, fwd in plan.lanes:
                if lane_k == lane:
                    rng = _road_param(
                        float(matches.lon_min[i]), float(matches.lon_max[i]), forward=fwd
                    )
                    out.append(rng[pick])
    if first.segment_type == RoadSegmentType.Normal and lo:
        first.p0 = max(0.0, min(*lo, 1.0 - 0.001))
    if cut_end and last.segment_type == RoadSegmentType.Normal and hi:
        last.p1 = min(1.0, max(*hi, last.p0 + 0.001))


def build_road(
    prep: PreparedGraph, plans: list[SegmentPlan], id_offset: int = 0
) -> tuple[tuple[RoadSegment, ...], dict[int, PlacedLane], float]:
    """Convert segment plans into ``rss.model`` road segments.

    Returns:
        ``(road, placed, max_speed_limit_mps)``: the road segments, where every map lane
        sits, and the largest finite speed limit of its lanes (NaN if none).
    """
    road: list[RoadSegment] = []
    placed: dict[int, PlacedLane] = {}
    limits = []
    for plan in plans:
        lanes = []
        scale = plan.p1 - plan.p0
        for lane, fwd in plan.lanes:
            lp0, lp1 = _road_param(plan.p0, plan.p1, forward=fwd)
            w_min, w_max = prep.width_range(lane, lp0, lp1)
            lane_id = lane + id_offset
            lanes.append(
                LaneSegment(
                    lane_id=lane_id,
                    driving_direction=_direction(prep, lane, forward=fwd),
                    length_min_m=float(prep.length_min_m[lane]) * scale,
                    length_max_m=float(prep.length_max_m[lane]) * scale,
                    width_min_m=w_min,
                    width_max_m=w_max,
                )
            )
            placed[lane] = PlacedLane(lane_id, fwd, plan.p0, plan.p1)
            limits.append(float(prep.graph.speed_limit_mps[lane]))
        road.append(
            RoadSegment(
                lanes=tuple(lanes),
                segment_type=plan.segment_type,
                min_length_before_intersecting_area_m=plan.before_m,
                min_length_after_intersecting_area_m=plan.after_m,
            )
        )
    finite = [v for v in limits if np.isfinite(v)]
    return tuple(road), placed, max(finite) if finite else float("nan")


def place_object(  # noqa: PLR0917 - one object: identity, matches, velocity
    matches: Matches,
    box: int,
    placed: dict[int, PlacedLane],
    object_id: int,
    object_type: ObjectType,
    velocity_mps: tuple[float, float],
    headings: dict[int, float],
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
    """
    regions = []
    heading = None
    for i in matches.rows(box):
        lane = int(matches.lane[i])
        where = placed.get(lane)
        if where is None:
            continue
        lo, hi = _road_param(
            float(matches.lon_min[i]), float(matches.lon_max[i]), forward=where.forward
        )
        la, lb = _road_param(
            float(matches.lat_min[i]), float(matches.lat_max[i]), forward=where.forward
        )
        span = where.p1 - where.p0
        lo, hi = (lo - where.p0) / span, (hi - where.p0) / span
        if hi < -_EPS or lo > 1.0 + _EPS:
            continue
        lo, hi, la, lb = (min(1.0, max(0.0, v)) for v in (lo, hi, la, lb))
        regions.append(OccupiedRegion(where.lane_id, lo, hi, la, lb))
        if heading is None or lane == matches.anchor[box]:
            heading = headings[lane] + (0.0 if where.forward else np.pi)
    if not regions or heading is None:
        return None
    vx, vy = velocity_mps
    c, s = math.cos(heading), math.sin(heading)
    lon = float(abs(vx * c + vy * s))
    lat = float(vx * s - vy * c)
    return LaneObject(object_id, object_type, tuple(regions), SpeedInterval(lon, lon, lat, lat))
