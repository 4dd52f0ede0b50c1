"""Lane segments of road areas, cached per map (for ``rss.scene.roadarea.build_road``).

Every pair of every frame gets its own road area, but most of its lanes are kept whole:
only the first and the last segment are cut at the two vehicles. A whole lane's
:class:`~rss.model.LaneSegment` depends only on ``(lane, orientation, id offset)``, so it
is built once per map and the same frozen object is handed out afterwards; a cut lane is
built from per-lane constants::

      cut (p0 > 0)        whole            whole          cut (p1 < 1)
    ├──┼──────────┼──────────────────┼──────────────┼───────┼──┤   road-area direction
       rear vehicle                                  front vehicle

Keys are lane indices of one :class:`~rss.scene.lanegraph.PreparedGraph`; the cache holds at
most ``2 L`` entries per id offset (``L`` lanes), so it needs no eviction.

:class:`GraphScalars` holds per-lane constants of the same graph as Python lists, for the
per-object code of scene creation (scalar access to numpy arrays costs ≈ 100 ns a time).
"""

from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np

from rss.model import LaneDrivingDirection, LaneSegment, RoadSegment

if TYPE_CHECKING:
    from rss.scene.lanegraph import PreparedGraph
    from rss.scene.roadarea import PlacedLane, SegmentPlan
    from rss.scene.routes import Step

__all__ = ["GraphScalars", "LaneSegmentCache"]

_FLIPPED = {
    LaneDrivingDirection.Positive: LaneDrivingDirection.Negative,
    LaneDrivingDirection.Negative: LaneDrivingDirection.Positive,
    LaneDrivingDirection.Bidirectional: LaneDrivingDirection.Bidirectional,
}


class LaneSegmentCache:
    """Lane segments of one prepared graph (see module docstring)."""

    def __init__(self, prep: PreparedGraph) -> None:
        """Read the per-lane constants of ``prep`` once."""
        self._prep = prep
        along = [LaneDrivingDirection(int(code)) for code in prep.graph.direction]
        self._direction = {
            (lane, forward): code if forward else _FLIPPED[code]
            for lane, code in enumerate(along)
            for forward in (True, False)
        }
        self._length_min = prep.length_min_m.tolist()
        self._length_max = prep.length_max_m.tolist()
        self._whole: dict[tuple[int, bool, int], LaneSegment] = {}
        #: Whole (uncut) road segments of ``rss.scene.roadarea.build_road`` by plan
        #: ``(lanes, type, before, after, id offset)``: segment, placed lanes, finite limits.
        #: Uncut corridor layouts of ``rss.scene.corridor.corridor_plans`` by their inputs.
        #: Each as uncut plans (shared, do not cut) with its lanes' segment index and
        #: orientation (``roadarea.plan_lanes``).
        self.corridor_layouts: dict[
            tuple[object, ...], tuple[tuple[SegmentPlan, ...], dict[int, tuple[int, bool]]]
        ] = {}
        self.whole_roads: dict[
            tuple[object, ...],
            tuple[RoadSegment, tuple[tuple[int, PlacedLane], ...], tuple[float, ...]],
        ] = {}

    def direction(self, lane: int, *, forward: bool) -> LaneDrivingDirection:
        """Traffic direction of ``lane`` relative to a road area it runs ``forward`` in."""
        return self._direction[lane, forward]

    def lane_segment(
        self, lane: int, *, forward: bool, id_offset: int = 0, p0: float = 0.0, p1: float = 1.0
    ) -> LaneSegment:
        """The lane segment of ``lane`` kept between ``p0 <= p1`` of the road-area direction.

        Args:
            lane: Lane index.
            forward: The lane's point order runs along the road-area direction.
            id_offset: Added to the lane index to form the segment's ``lane_id``.
            p0: Kept window start (parametric, road-area direction).
            p1: Kept window end.

        Returns:
            Lengths scaled by the window, widths min / max over it, the direction relative
            to the road area; for the whole lane always the same object.
        """
        whole = p0 == 0.0 and p1 == 1.0
        if whole:
            cached = self._whole.get((lane, forward, id_offset))
            if cached is not None:
                return cached
        lo, hi = (p0, p1) if forward else (1.0 - p1, 1.0 - p0)
        w_min, w_max = self._prep.width_range(lane, lo, hi)
        scale = p1 - p0
        segment = LaneSegment(
            lane_id=lane + id_offset,
            driving_direction=self._direction[lane, forward],
            length_min_m=self._length_min[lane] * scale,
            length_max_m=self._length_max[lane] * scale,
            width_min_m=w_min,
            width_max_m=w_max,
        )
        if whole:
            self._whole[lane, forward, id_offset] = segment
        return segment


class GraphScalars:
    """Per-lane constants of one prepared graph as Python lists (see module docstring).

    Attributes:
        direction: ``(L,)`` traffic-direction codes relative to the point order.
        speed_limit_mps: ``(L,)`` speed limits (NaN where unknown).
        centre_length_m: ``(L,)`` centre-line lengths.
        centre_xy_m: Per lane, the centre-line points ``[[x, y], ...]``.
        centre_arc_m: Per lane, the cumulative arc length at each centre-line point
            (starts at 0).
        left_neighbour: ``(L,)`` adjacent lane on the left, -1 for none.
        right_neighbour: ``(L,)`` adjacent lane on the right, -1 for none.
        left_opposite: ``(L,)`` the left neighbour's point order is reversed.
        right_opposite: ``(L,)`` the right neighbour's point order is reversed.
        is_intersection: ``(L,)`` lane lies inside an intersection.
        conflict_rows: ``(L, L)`` ``prep.conflicts`` as nested lists.
        cross_sections: Memo of ``rss.scene.routes.cross_section`` by step.
        route_facts: Memo of the pure route functions of ``rss.scene.intersection``.
        route_searches: Recent predicted-route searches by start step, with their
            horizon comparisons (``rss.scene.routes.predict_routes``).
        merge_points: Memo of where two routes meet (``rss.scene.connecting``), by the
            (ego route, object route) pair.
    """

    def __init__(self, prep: PreparedGraph) -> None:
        """Convert the arrays of ``prep`` once."""
        g = prep.graph
        self.direction: list[int] = [int(v) for v in g.direction]
        self.speed_limit_mps: list[float] = np.asarray(g.speed_limit_mps, float).tolist()
        self.centre_length_m: list[float] = np.asarray(prep.centre_length_m, float).tolist()
        self.centre_xy_m: list[list[list[float]]] = [c.tolist() for c in g.centre_m]
        self.centre_arc_m: list[list[float]] = [
            np.concatenate(
                [[0.0], np.cumsum(np.hypot(np.diff(c[:, 0]), np.diff(c[:, 1])))]
            ).tolist()
            for c in g.centre_m
        ]
        self.left_neighbour: list[int] = [int(v) for v in g.left_neighbour]
        self.right_neighbour: list[int] = [int(v) for v in g.right_neighbour]
        self.left_opposite: list[bool] = [bool(v) for v in g.left_opposite]
        self.right_opposite: list[bool] = [bool(v) for v in g.right_opposite]
        self.is_intersection: list[bool] = np.asarray(g.is_intersection, bool).tolist()
        self.conflict_rows: list[list[bool]] = np.asarray(prep.conflicts, bool).tolist()
        self.cross_sections: dict[Step, tuple[Step, ...]] = {}
        self.route_facts: dict[object, object] = {}
        self.route_searches: dict[
            Step, list[tuple[tuple[tuple[Step, ...], ...], tuple[tuple[int, int, bool], ...]]]
        ] = {}
        self.merge_points: dict[
            tuple[tuple[Step, ...], tuple[Step, ...]], tuple[int, int, bool] | None
        ] = {}
