"""The conflict of two routes at an intersection: conflict lanes, road areas, priority.

For an ego route and an object route the first pair of intersection lanes whose areas
overlap (or that merge into one successor) is the conflict. Each vehicle gets its own
road area: its route up to and including its conflict lane, typed ``Intersection``, with
the lengths before and after the part of that lane that overlaps the other's lane::

    ego route ──▶ ──▶ ┌──────── conflict lane a ────────┐
                      │ before │ overlaps lane b │ after│
                      └────────┴─────────────────┴──────┘

Priority comes from right of way and traffic lights (a light not listed green means the
route must yield, as ad-map does with an empty set of green lights); without any
regulation the ego yields (ad-map's behaviour for intersections of unknown type).
"""

from __future__ import annotations

from typing import TYPE_CHECKING, NamedTuple

import numpy as np
import shapely

from rss.model import ConstellationType, RoadSegmentType
from rss.scene.memo import memoised
from rss.scene.segment_plans import SegmentPlan

if TYPE_CHECKING:
    from rss.scene.lanegraph import Step
    from rss.scene.memo import SceneMemo
    from rss.scene.prepared import PreparedGraph

__all__ = [
    "IntersectionPair",
    "area_span",
    "conflict",
    "intersection_pair",
    "intersection_plans",
    "intersection_type",
    "route_priority",
]


def conflict(
    prep: PreparedGraph, memo: SceneMemo, ego_route: tuple[Step, ...], obj_route: tuple[Step, ...]
) -> tuple[int, int] | None:
    """Indices ``(ie, io)`` of the first conflicting intersection lanes, or ``None``.

    Conflicting: overlapping or merging intersection lanes, else the first lane both
    routes share (routes from one arm, merging routes). Memoised per map.
    """
    return memoised(prep, memo, _conflict, ego_route, obj_route)


def _conflict(
    prep: PreparedGraph, _memo: SceneMemo, ego_route: tuple[Step, ...], obj_route: tuple[Step, ...]
) -> tuple[int, int] | None:
    lists = prep.scalars
    inter = lists.is_intersection
    obj_lanes = [(io, lane) for io, (lane, _) in enumerate(obj_route) if inter[lane]]
    for ie, (a, _) in enumerate(ego_route):
        if not inter[a]:
            continue
        row = lists.conflict_rows[a]
        for io, b in obj_lanes:
            if row[b]:
                return ie, io
    where = {lane: io for io, (lane, _) in enumerate(obj_route)}
    for ie, (a, _) in enumerate(ego_route):
        if a in where:
            return ie, where[a]
    return None


def area_span(prep: PreparedGraph, memo: SceneMemo, lane: int, other: int) -> tuple[float, float]:
    """Lengths of ``lane`` before and after the part of its *area* inside ``other``'s.

    As ad-rss (``extractInnerRegions`` of the lane in the other lane's polygon): the
    vertices of the two lanes' common area are projected on ``lane``'s centre line; the
    parametric range they span is the intersecting part, its outside measured in the
    lane's minimal length. Lanes without common area keep the whole lane before it.
    Kept per map (``memo.area_spans``).
    """
    spans = memo.area_spans
    key = (lane, other)
    if key not in spans:
        length = float(prep.length_min_m[lane])
        shared = shapely.intersection(prep.polygons[lane], prep.polygons[other])
        if shapely.is_empty(shared) or shapely.area(shared) <= 0.0:
            spans[key] = prep.conflict_span_m.get(key, (length, 0.0))
        else:
            s = shapely.line_locate_point(
                prep.centre_lines[lane],
                shapely.points(shapely.get_coordinates(shared)),
                normalized=True,
            )
            spans[key] = (float(np.min(s)) * length, (1.0 - float(np.max(s))) * length)
    return spans[key]


def intersection_plans(
    prep: PreparedGraph, memo: SceneMemo, route: tuple[Step, ...], upto: int, other_lane: int
) -> list[SegmentPlan]:
    """Single-lane segments along ``route[:upto + 1]``, the last one the intersection."""
    plans = [SegmentPlan(lanes=[step]) for step in route[:upto]]
    lane, fwd = route[upto]
    before, after = area_span(prep, memo, lane, other_lane)
    if not fwd:
        before, after = after, before
    plans.append(
        SegmentPlan(
            lanes=[(lane, fwd)],
            segment_type=RoadSegmentType.Intersection,
            before_m=before,
            after_m=after,
        )
    )
    return plans


def route_priority(prep: PreparedGraph, route: tuple[Step, ...], green: frozenset[int]) -> int:
    """Right of way of ``route``: the last regulated lane up to its end (+1, 0, -1)."""
    g = prep.graph
    level = 0
    for lane, _ in route:
        light = int(g.traffic_light[lane])
        if light >= 0:
            level = 1 if light in green else -1
        elif g.priority[lane] != 0:
            level = int(g.priority[lane])
    return level


def intersection_type(ego_level: int, obj_level: int) -> ConstellationType:
    """Constellation type from the two routes' right of way.

    Two unregulated routes (level 0) make the ego yield, as ad-map does for intersections
    of unknown type; two regulated routes of the same level have the same priority.
    """
    if ego_level == obj_level == 0:
        return ConstellationType.IntersectionObjectHasPriority
    if ego_level > obj_level:
        return ConstellationType.IntersectionEgoHasPriority
    if ego_level < obj_level:
        return ConstellationType.IntersectionObjectHasPriority
    return ConstellationType.IntersectionSamePriority


class IntersectionPair(NamedTuple):
    """The uncut road areas of an (ego route, object route) pair (see :func:`intersection_pair`).

    Attributes:
        ego_lane: The ego route's conflict lane.
        obj_lane: The object route's conflict lane.
        ego_plans: :func:`intersection_plans` of the ego route (do not modify).
        obj_plans: :func:`intersection_plans` of the object route (do not modify).
        priority: :func:`intersection_type` of the two routes' right of way up to the
            conflict.
    """

    ego_lane: int
    obj_lane: int
    ego_plans: tuple[SegmentPlan, ...]
    obj_plans: tuple[SegmentPlan, ...]
    priority: ConstellationType


def intersection_pair(
    prep: PreparedGraph,
    memo: SceneMemo,
    ego_route: tuple[Step, ...],
    obj_route: tuple[Step, ...],
    green: frozenset[int],
) -> IntersectionPair | None:
    """Conflict, uncut road areas and priority of two routes; ``None`` without conflict.

    A function of the two routes and the green lights alone, so memoised per map (route
    pairs repeat from frame to frame; only the cuts at the vehicles change).
    """
    return memoised(prep, memo, _intersection_pair, ego_route, obj_route, green)


def _intersection_pair(
    prep: PreparedGraph,
    memo: SceneMemo,
    ego_route: tuple[Step, ...],
    obj_route: tuple[Step, ...],
    green: frozenset[int],
) -> IntersectionPair | None:
    hit = conflict(prep, memo, ego_route, obj_route)
    if hit is None:
        return None
    ie, io = hit
    ego_lane, obj_lane = ego_route[ie][0], obj_route[io][0]
    return IntersectionPair(
        ego_lane,
        obj_lane,
        tuple(intersection_plans(prep, memo, ego_route, ie, obj_lane)),
        tuple(intersection_plans(prep, memo, obj_route, io, ego_lane)),
        intersection_type(
            route_priority(prep, ego_route[: ie + 1], green),
            route_priority(prep, obj_route[: io + 1], green),
        ),
    )
