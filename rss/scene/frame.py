"""What the constellations of one frame share: :class:`FrameContext`, the ego's routes.

One :class:`FrameContext` per frame holds the prepared graph and the map's memos, the ego
and the objects, the map matching, the route tree from the ego and the lane headings at
each box, and builds single constellations from segment plans (speed-limit modes applied
to both dynamics). What it computes once per frame is kept in its :class:`FrameMemo`,
keyed by value (boxes, lanes, routes).
"""

from __future__ import annotations

import dataclasses
import functools
import math
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, NamedTuple

import numpy as np

from rss.dynamics import RssDynamics  # noqa: TC001 - dataclass field types, read at run time when compiled (mypyc)
from rss.model import Constellation, ConstellationType, LaneObject, ObjectType, RoadSegment
from rss.params import RestrictSpeedLimitMode, SceneSettings
from rss.scene.inputs import SceneEgo, SceneObjects  # noqa: TC001 - dataclass field types, read at run time when compiled (mypyc)
from rss.scene.lanegraph import Step  # noqa: TC001 - dataclass field types, read at run time when compiled (mypyc)
from rss.scene.match_records import Matches  # noqa: TC001 - dataclass field types, read at run time when compiled (mypyc)
from rss.scene.memo import SceneMemo  # noqa: TC001 - dataclass field types, read at run time when compiled (mypyc)
from rss.scene.prepared import PreparedGraph  # noqa: TC001 - dataclass field types, read at run time when compiled (mypyc)
from rss.scene.roadarea import build_road, lane_heading, place_object
from rss.scene.routes import RouteMemo, RouteTree, follows_traffic, predict_routes
from rss.scene.segment_plans import BuiltSegment  # noqa: TC001 - dataclass field types, read at run time when compiled (mypyc)

if TYPE_CHECKING:
    from rss.scene.segment_plans import PlacedLane, SegmentPlan

__all__ = ["BuiltConstellation", "FrameContext", "FrameMemo", "ego_routes", "lane_headings"]

#: A touched lane is a start of a vehicle's routes when the vehicle heads along its traffic
#: direction, as ad-map predicts from every occupied region (within 90 degrees); a lane
#: at right angles to the heading (cosine within this tolerance of 0) is none: its
#: direction there would hinge on rounding.
_ACROSS_COS = 1e-6
#: The speed limit (m/s) ad-map 5.0's OpenDRIVE reader gives a lane whose road has no
#: speed record (50 km/h; measured on Town01's junction lanes with the oracle): the
#: compatibility mode's value for a lane without a limit. The default mode takes such a
#: lane as unbounded (the dynamics then stay unchanged: never below ad-map's cap).
ADMAP_UNKNOWN_SPEED_LIMIT_MPS = 50.0 / 3.6
_SPEED_FACTOR = {
    RestrictSpeedLimitMode.NONE: None,
    RestrictSpeedLimitMode.EXACT_SPEED_LIMIT: 1.0,
    RestrictSpeedLimitMode.INCREASED_SPEED_LIMIT_5: 1.05,
    RestrictSpeedLimitMode.INCREASED_SPEED_LIMIT_10: 1.1,
}


@functools.lru_cache(maxsize=256)
def _limited(dyn: RssDynamics, limit: float, mode: RestrictSpeedLimitMode) -> RssDynamics:
    factor = _SPEED_FACTOR[mode]
    if factor is None or not np.isfinite(limit):
        return dyn
    return dataclasses.replace(dyn, max_speed_on_acceleration_mps=limit * factor)


class BuiltConstellation(NamedTuple):
    """A constellation with its road area as lane windows (``Scene.road_areas``).

    Attributes:
        constellation: The constellation.
        road_area: Its road-area lanes ``(lane, start, end)`` along each lane's point order.
    """

    constellation: Constellation
    road_area: tuple[tuple[int, float, float], ...]


@dataclass(slots=True)
class FrameMemo:
    """What one frame computes once (all keyed by value; do not modify the entries).

    Attributes:
        routes: Predicted routes of this frame (``rss.scene.routes.predict_routes``).
        cut_segments: Cut road segments of this frame (``build_road``'s ``cut_memo``).
        placed_objects: Objects placed in road areas, by box, route heading and the placed
            lanes the box touches (the same window gives the same object).
        limited_dynamics: Dynamics of a box under the speed-limit mode by (box, limit).
        start_lanes: :meth:`FrameContext.starts` by box.
        box_lanes: :meth:`FrameContext.lanes_of` by box.
        box_forward: :meth:`FrameContext.forward` by box.
        route_reach: :meth:`FrameContext.reach_along` by (route, start).
    """

    routes: RouteMemo = field(default_factory=dict)
    cut_segments: dict[tuple[object, ...], BuiltSegment] = field(default_factory=dict)
    placed_objects: dict[tuple[object, ...], LaneObject | None] = field(default_factory=dict)
    limited_dynamics: dict[tuple[int, float], RssDynamics] = field(default_factory=dict)
    start_lanes: dict[int, list[tuple[int, bool, float]]] = field(default_factory=dict)
    box_lanes: dict[int, list[int]] = field(default_factory=dict)
    box_forward: dict[int, bool] = field(default_factory=dict)
    route_reach: dict[tuple[tuple[Step, ...], float], dict[int, float]] = field(
        default_factory=dict
    )


@dataclass(slots=True)
class FrameContext:
    """What the constellations of one frame share.

    Attributes:
        prep: The prepared lane graph.
        memo: The map's memos (``rss.scene.memo``).
        ego: The ego.
        objects: The other objects (box ``i + 1`` is object ``i``; box 0 is the ego).
        settings: Scene settings.
        matches: Map matching of all boxes.
        tree: Connecting routes from the ego's anchor lane.
        headings: Per box, the heading of each touched lane's point order at its centre.
        ego_velocity: ``(vx, vy)`` of the ego in the map frame.
        once: What this frame computes once.
        behind_tree: Routes behind the ego only, from its anchor lane (both modes:
            ad-map's routes from the object to the ego, ``connecting_routes``).
        other_trees: Connecting routes from the further lanes the ego occupies that no
            link joins to its anchor (overlapping junction lanes,
            ``rss.scene.create.more_roots``), asked for every object; their routes join
            those of ``tree`` (``rss.scene.connecting.connecting_routes``).
    """

    prep: PreparedGraph
    memo: SceneMemo
    ego: SceneEgo
    objects: SceneObjects
    settings: SceneSettings
    matches: Matches
    tree: RouteTree
    headings: dict[int, dict[int, float]]
    ego_velocity: tuple[float, float]
    once: FrameMemo = field(default_factory=FrameMemo)
    other_trees: list[RouteTree] = field(default_factory=list)
    behind_tree: RouteTree | None = None

    def forward(self, box: int) -> bool:
        """Whether the box heads along its anchor lane's point order (once per box)."""
        known = self.once.box_forward.get(box)
        if known is None:
            yaw = self.ego.yaw_rad if box == 0 else float(self.objects.yaw_rad[box - 1])
            known = bool(np.cos(yaw - self.matches.anchor_heading_rad[box]) >= 0.0)
            self.once.box_forward[box] = known
        return known

    def starts(self, box: int) -> list[tuple[int, bool, float]]:
        """Lanes the box may drive on: ``(lane, forward, length behind its centre)``.

        The anchor first (either way along it), then every other touched lane whose
        traffic direction lies within 90 degrees of the box heading at its region: ad-map
        predicts a vehicle's routes from every occupied region, in the lane's direction
        when the heading is within 90 degrees of it, else against it, which gives no
        route on a one-way lane (``predictRoutes`` of a bounding box; no route there on
        Town01, measured with the oracle). Lanes at right angles to the heading are left
        out. Computed once per box.
        """
        known = self.once.start_lanes.get(box)
        if known is not None:
            return known
        m = self.matches
        yaw = self.ego.yaw_rad if box == 0 else float(self.objects.yaw_rad[box - 1])
        anchor = m.anchors[box]
        lengths = self.prep.scalars.centre_length_m
        out = []
        for region in m.regions(box):
            lane = region.lane
            cos = math.cos(yaw - region.heading_rad)
            fwd = cos >= 0.0
            if lane != anchor and (
                abs(cos) < _ACROSS_COS or not follows_traffic(self.prep, lane, forward=fwd)
            ):
                continue
            p = (
                float(m.anchor_s[box])
                if lane == anchor
                else 0.5 * (region.lon_min + region.lon_max)
            )
            behind = lengths[lane] * (p if fwd else 1.0 - p)
            out.append((lane, fwd, behind))
        out.sort(key=lambda item: item[0] != anchor)
        self.once.start_lanes[box] = out
        return out

    def predict(
        self, lane: int, *, forward: bool, horizon_m: float, travelled_m: float
    ) -> list[tuple[Step, ...]]:
        """``predict_routes`` from ``lane`` with the map's and this frame's memos."""
        return predict_routes(
            self.prep,
            self.memo,
            lane,
            forward=forward,
            horizon_m=horizon_m,
            travelled_m=travelled_m,
            frame_routes=self.once.routes,
        )

    def routes(self, box: int, horizon_m: float) -> list[tuple[Step, ...]]:
        """Predicted routes from every lane in :meth:`starts`."""
        out: list[tuple[Step, ...]] = []
        for lane, fwd, behind in self.starts(box):
            out.extend(self.predict(lane, forward=fwd, horizon_m=horizon_m, travelled_m=behind))
        return out

    def constellation(
        self,
        kind: ConstellationType,
        i: int,
        ego_plans: list[SegmentPlan],
        obj_plans: list[SegmentPlan] | None,
        ends: dict[int, tuple[int, float]] | None = None,
        *,
        swap_headings: bool = False,
    ) -> BuiltConstellation | None:
        """Build one constellation of object ``i`` (``obj_plans`` only for intersections).

        ``ends`` (from :func:`cut_between`): where the connecting route touches each box;
        its speeds are then resolved along the road-area direction there, as ad-rss does.
        ``swap_headings``: each vehicle takes the road direction at the *other* vehicle's
        end instead, as ad-rss 5.0 does for an object following the ego (its
        ``createRoadArea`` gives the ego ``route_heading_start`` of a route that starts at
        the object; ``[scene] reproduce_adrss_5_0_defects``).
        """
        route_heading: dict[int, float | None] = {0: None, i + 1: None}
        if ends:
            along = {s[0] for p in ego_plans for s in p.lanes if s[1]}
            for box, (lane, at) in ends.items():
                turn = 0.0 if lane in along else np.pi
                route_heading[box] = lane_heading(self.prep, self.memo, lane, at) + turn
            if swap_headings:
                route_heading[0], route_heading[i + 1] = route_heading[i + 1], route_heading[0]
        cut = self.once.cut_segments
        windows: list[tuple[int, float, float]] = []
        unknown = (
            ADMAP_UNKNOWN_SPEED_LIMIT_MPS if self.settings.reproduce_adrss_5_0_defects else math.inf
        )
        ego_road, ego_placed, limit = build_road(
            self.prep, self.memo, ego_plans, 0, cut, windows, unknown
        )
        obj_road: tuple[RoadSegment, ...] = ()
        obj_placed = ego_placed
        if obj_plans is not None:
            offset = len(self.prep.graph)
            obj_road, obj_placed, limit2 = build_road(
                self.prep, self.memo, obj_plans, offset, cut, windows, unknown
            )
            limit = limit2 if (math.isnan(limit) or limit2 > limit) else limit
        o = self.objects
        ego = self._place(0, ego_placed, route_heading[0])
        other = self._place(i + 1, obj_placed, route_heading[i + 1])
        if ego is None or other is None:
            return None
        built = Constellation(
            constellation_type=kind,
            ego=ego,
            other=other,
            ego_dynamics=self._limited(0, self.ego.dynamics, float(limit)),
            other_dynamics=self._limited(i + 1, o.dynamics[i], float(limit)),
            ego_road=ego_road,
            intersecting_road=obj_road,
        )
        return BuiltConstellation(built, tuple(windows))

    def lanes_of(self, box: int) -> list[int]:
        """Lanes the box touches, in pair order (computed once per box; do not modify)."""
        known = self.once.box_lanes.get(box)
        if known is None:
            self.once.box_lanes[box] = known = [r.lane for r in self.matches.regions(box)]
        return known

    def reach_along(self, route: tuple[Step, ...], start_m: float) -> dict[int, float]:
        """Distance along ``route`` to the start of each of its lanes [m].

        ``start_m`` is the part of its first lane already behind; computed once per frame
        for each route and start (do not modify).
        """
        key = (route, start_m)
        known = self.once.route_reach.get(key)
        if known is not None:
            return known
        lengths = self.prep.scalars.centre_length_m
        out: dict[int, float] = {}
        dist = -start_m
        for lane, _ in route:
            out.setdefault(lane, max(0.0, dist))
            dist += lengths[lane]
        self.once.route_reach[key] = out
        return out

    def _limited(self, box: int, dyn: RssDynamics, limit: float) -> RssDynamics:
        """``dyn`` (the dynamics of ``box``) under the speed-limit mode, once per frame."""
        key = (box, limit)
        out = self.once.limited_dynamics.get(key)
        if out is None:
            mode = self.settings.restrict_speed_limit_mode
            self.once.limited_dynamics[key] = out = _limited(dyn, limit, mode)
        return out

    def _place(
        self, box: int, placed: dict[int, PlacedLane], route_heading_rad: float | None
    ) -> LaneObject | None:
        """``place_object`` of a box, once per frame for the same window of its lanes."""
        key = (box, route_heading_rad, *map(placed.get, self.lanes_of(box)))
        known = self.once.placed_objects
        if key in known:
            return known[key]
        if box == 0:
            identity = (self.ego.object_id, ObjectType.EgoVehicle, self.ego_velocity)
        else:
            o, i = self.objects, box - 1
            identity = (
                int(o.ids[i]),
                ObjectType(int(o.object_type[i])),
                (float(o.vx_mps[i]), float(o.vy_mps[i])),
            )
        out = place_object(
            self.matches, box, placed, *identity, self.headings[box], route_heading_rad
        )
        known[key] = out
        return out


def lane_headings(matches: Matches, n: int) -> dict[int, dict[int, float]]:
    """Per box, the heading of each touched lane at the box centre."""
    return {b: {r.lane: r.heading_rad for r in matches.regions(b)} for b in range(n)}


def ego_routes(f: FrameContext, horizon_m: float) -> list[tuple[Step, ...]]:
    """The ego's routes: its plan continued by the prediction, else the prediction."""
    if not f.ego.route:
        return f.routes(0, horizon_m)
    lane, fwd, behind = f.starts(0)[0]
    base = ((lane, fwd), *(s for s in f.ego.route if s[0] != lane))
    tails = f.predict(
        base[-1][0],
        forward=base[-1][1],
        horizon_m=horizon_m,
        travelled_m=behind if len(base) == 1 else 0.0,
    )
    return [base + tail[1:] for tail in tails]
