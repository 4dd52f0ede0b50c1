"""What scene creation remembers across frames of one map: :class:`SceneMemo`.

Scene creation is a pure function of the prepared graph and the frame; these memos only
save work (routes, road areas and their lane segments, route facts repeat from frame to
frame). Like ``rss.memory.RssMemory`` the memo is explicit: the caller creates one per
prepared graph (``SceneMemo()``) and passes it to every ``create_scene`` of that map
(``None`` there: a fresh one for the call, same results). Keys are lane indices, routes
and plans of that one graph; every memo either holds at most a fixed number of entries
per lane or is emptied when it grows beyond a bound.
"""

from __future__ import annotations

from typing import TYPE_CHECKING, TypeVar, cast

from rss.scene.lanegraph import Step

if TYPE_CHECKING:
    from collections.abc import Callable

    from rss.scene.lane_segments import WholeLanes
    from rss.scene.prepared import PreparedGraph
    from rss.scene.segment_plans import BuiltSegment, SegmentPlan

__all__ = ["LaneMiddle", "RouteSearch", "SceneMemo", "memoised"]

_T = TypeVar("_T")

#: ad-map's middle line of a lane (``rss.scene.roadarea.lane_heading``): border-length
#: fractions of its points, their x and y [m], and the mean border length [m].
LaneMiddle = tuple[list[float], list[float], list[float], float]

#: One predicted-route search (``rss.scene.routes.predict_routes``): its routes and its
#: horizon comparisons in order, ``(check it continues, its last lane, came out beyond the
#: horizon)``; -1 = the search's start.
RouteSearch = tuple[tuple[tuple[Step, ...], ...], tuple[tuple[int, int, bool], ...]]

#: Entries of the route-facts memo (:func:`memoised`) before it is emptied.
_MEMO_SIZE = 100_000
_MISSING = object()


class SceneMemo:
    """The per-map memos of scene creation (see module docstring).

    Attributes:
        cross_sections: ``rss.scene.routes.cross_section`` by step.
        route_facts: Pure functions of routes and lanes by function and arguments
            (:func:`memoised`).
        route_searches: Recent predicted-route searches by start step, newest first
            (``rss.scene.routes.predict_routes``).
        lane_middles: ad-map's middle line per lane (``rss.scene.roadarea``).
        whole_lanes: Whole lanes' segments (``rss.scene.lane_segments``).
        whole_roads: Whole (uncut) road segments of ``rss.scene.roadarea.build_road`` by
            plan ``(lanes, type, before, after, id offset)``.
        corridor_layouts: Uncut corridor layouts of ``rss.scene.corridor.corridor_plans``
            by their inputs: uncut plans (shared, do not cut) with each lane's segment
            index and orientation (``segment_plans.plan_lanes``).
        area_spans: ``rss.scene.junction_pairs.area_span`` by lane pair.
    """

    def __init__(self) -> None:
        """Start with empty memos."""
        self.cross_sections: dict[Step, tuple[Step, ...]] = {}
        self.route_facts: dict[object, object] = {}
        self.route_searches: dict[Step, list[RouteSearch]] = {}
        self.lane_middles: dict[int, LaneMiddle] = {}
        self.whole_lanes: WholeLanes = {}
        self.whole_roads: dict[tuple[object, ...], BuiltSegment] = {}
        self.corridor_layouts: dict[
            tuple[object, ...], tuple[tuple[SegmentPlan, ...], dict[int, tuple[int, bool]]]
        ] = {}
        self.area_spans: dict[tuple[int, int], tuple[float, float]] = {}


def memoised(prep: PreparedGraph, memo: SceneMemo, compute: Callable[..., _T], *args: object) -> _T:
    """``compute(prep, memo, *args)``, or its earlier result in ``memo`` (bounded).

    For pure functions of routes and lanes (``rss.scene.junction_*``, ``connecting``,
    ``cut_areas``, ``routes``): their results are kept per map
    (:attr:`SceneMemo.route_facts`), keyed by the function and its arguments.
    """
    facts = memo.route_facts
    key = (compute, *args)
    found = facts.get(key, _MISSING)
    if found is _MISSING:
        if len(facts) > _MEMO_SIZE:
            facts.clear()
        found = facts[key] = compute(prep, memo, *args)
    return cast("_T", found)
