"""Intersection constellations from pairs of predicted routes.

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

from typing import TYPE_CHECKING

from rss.model import ConstellationType, RoadSegmentType
from rss.scene.roadarea import SegmentPlan

if TYPE_CHECKING:
    from rss.scene.lanegraph import PreparedGraph
    from rss.scene.routes import Step

__all__ = ["conflict", "intersection_plans", "intersection_type", "route_priority"]


def conflict(
    prep: PreparedGraph, ego_route: tuple[Step, ...], obj_route: tuple[Step, ...]
) -> tuple[int, int] | None:
    """Indices ``(ie, io)`` of the first conflicting intersection lanes, or ``None``."""
    inter = prep.graph.is_intersection
    obj_lanes = [(io, lane) for io, (lane, _) in enumerate(obj_route) if inter[lane]]
    for ie, (a, _) in enumerate(ego_route):
        if not inter[a]:
            continue
        for io, b in obj_lanes:
            if prep.conflicts[a, b]:
                return ie, io
    return None


def intersection_plans(
    prep: PreparedGraph, route: tuple[Step, ...], upto: int, other_lane: int
) -> list[SegmentPlan]:
    """Single-lane segments along ``route[:upto + 1]``, the last one the intersection."""
    plans = [SegmentPlan(lanes=[step]) for step in route[:upto]]
    lane, fwd = route[upto]
    before, after = prep.conflict_span_m[lane, other_lane]
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
