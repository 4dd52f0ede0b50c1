"""Per-object decisions of scene creation: following, intersections, connecting route.

One :class:`FrameContext` holds what a frame shares (matches, the route tree from the ego,
headings); :func:`object_constellations` builds the constellations of one object::

    connecting route without intersection lanes  -> Same/OppositeDirection (corridor)
    one vehicle on the other's predicted route    -> SameDirection along that route
    conflicting intersection lanes of route pairs -> Intersection* (one per lane pair)
      + the connecting route where a route pair passes without conflict
"""

from __future__ import annotations

import dataclasses
import functools
import math
from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np

from rss.model import Constellation, ConstellationType, ObjectType
from rss.params import RestrictSpeedLimitMode
from rss.scene.corridor import corridor_plans
from rss.scene.intersection import (
    conflict,
    intersection_plans,
    intersection_type,
    route_priority,
)
from rss.scene.roadarea import SegmentPlan, build_road, cut_window, place_object
from rss.scene.routes import predict_routes

if TYPE_CHECKING:
    from rss.dynamics import RssDynamics
    from rss.model import RoadSegment
    from rss.params import SceneSettings
    from rss.scene.inputs import SceneEgo, SceneObjects
    from rss.scene.lanegraph import PreparedGraph
    from rss.scene.matching import Matches
    from rss.scene.routes import RouteTree, Step

__all__ = ["FrameContext", "ego_routes", "lane_headings", "object_constellations"]

#: Following through an intersection needs headings within 45 degrees.
_FOLLOWING_COS = float(np.cos(np.pi / 4))
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


@dataclass
class FrameContext:
    """What the constellations of one frame share.

    Attributes:
        prep: The prepared lane graph.
        ego: The ego.
        objects: The other objects (box ``i + 1`` is object ``i``; box 0 is the ego).
        settings: Scene settings.
        matches: Map matching of all boxes.
        tree: Connecting routes from the ego's anchor lane.
        headings: Per box, the heading of each touched lane's point order at its centre.
        ego_velocity: ``(vx, vy)`` of the ego in the map frame.
    """

    prep: PreparedGraph
    ego: SceneEgo
    objects: SceneObjects
    settings: SceneSettings
    matches: Matches
    tree: RouteTree
    headings: dict[int, dict[int, float]]
    ego_velocity: tuple[float, float]

    def forward(self, box: int) -> bool:
        """Whether the box heads along its anchor lane's point order."""
        yaw = self.ego.yaw_rad if box == 0 else float(self.objects.yaw_rad[box - 1])
        return bool(np.cos(yaw - self.matches.anchor_heading_rad[box]) >= 0.0)

    def starts(self, box: int) -> list[tuple[int, bool, float]]:
        """Lanes the box may drive on: ``(lane, forward, length behind its centre)``.

        The anchor first, then every other touched lane aligned with the box heading
        (ad-rss considers every map-matched lane of a vehicle).
        """
        m = self.matches
        yaw = self.ego.yaw_rad if box == 0 else float(self.objects.yaw_rad[box - 1])
        anchor = int(m.anchor[box])
        out = []
        for i in m.rows(box):
            lane = int(m.lane[i])
            cos = math.cos(yaw - float(m.heading_rad[i]))
            if lane != anchor and abs(cos) < _FOLLOWING_COS:
                continue
            fwd = cos >= 0.0
            p = (
                float(m.anchor_s[box])
                if lane == anchor
                else 0.5 * float(m.lon_min[i] + m.lon_max[i])
            )
            behind = float(self.prep.centre_length_m[lane]) * (p if fwd else 1.0 - p)
            out.append((lane, fwd, behind))
        out.sort(key=lambda item: item[0] != anchor)
        return out

    def routes(self, box: int, horizon_m: float) -> list[tuple[Step, ...]]:
        """Predicted routes from every lane in :meth:`starts`."""
        out: list[tuple[Step, ...]] = []
        for lane, fwd, behind in self.starts(box):
            out.extend(
                predict_routes(
                    self.prep, lane, forward=fwd, horizon_m=horizon_m, travelled_m=behind
                )
            )
        return out

    def behind_ego(self, i: int) -> bool:
        """Whether object ``i`` is entirely behind the ego (along the ego heading)."""
        o, e = self.objects, self.ego
        d = (o.x_m[i] - e.x_m) * np.cos(e.yaw_rad) + (o.y_m[i] - e.y_m) * np.sin(e.yaw_rad)
        return bool(d < -(o.length_m[i] + e.length_m) / 2.0)

    def constellation(
        self,
        kind: ConstellationType,
        i: int,
        ego_plans: list[SegmentPlan],
        obj_plans: list[SegmentPlan] | None,
    ) -> Constellation | None:
        """Build one constellation of object ``i`` (``obj_plans`` only for intersections)."""
        ego_road, ego_placed, limit = build_road(self.prep, ego_plans)
        obj_road: tuple[RoadSegment, ...] = ()
        obj_placed = ego_placed
        if obj_plans is not None:
            obj_road, obj_placed, limit2 = build_road(self.prep, obj_plans, len(self.prep.graph))
            limit = np.nanmax([limit, limit2]) if np.isfinite([limit, limit2]).any() else limit
        o = self.objects
        ego = place_object(
            self.matches,
            0,
            ego_placed,
            self.ego.object_id,
            ObjectType.EgoVehicle,
            self.ego_velocity,
            self.headings[0],
        )
        other = place_object(
            self.matches,
            i + 1,
            obj_placed,
            int(o.ids[i]),
            ObjectType(int(o.object_type[i])),
            (float(o.vx_mps[i]), float(o.vy_mps[i])),
            self.headings[i + 1],
        )
        if ego is None or other is None:
            return None
        mode = self.settings.restrict_speed_limit_mode
        return Constellation(
            constellation_type=kind,
            ego=ego,
            other=other,
            ego_dynamics=_limited(self.ego.dynamics, float(limit), mode),
            other_dynamics=_limited(o.dynamics[i], float(limit), mode),
            ego_road=ego_road,
            intersecting_road=obj_road,
        )


def lane_headings(matches: Matches, n: int) -> dict[int, dict[int, float]]:
    """Per box, the heading of each touched lane at the box centre."""
    out: dict[int, dict[int, float]] = {b: {} for b in range(n)}
    for b, lane, h in zip(matches.box, matches.lane, matches.heading_rad, strict=True):
        out[int(b)][int(lane)] = float(h)
    return out


def ego_routes(f: FrameContext, horizon_m: float) -> list[tuple[Step, ...]]:
    """The ego's routes: its plan continued by the prediction, else the prediction."""
    if not f.ego.route:
        return f.routes(0, horizon_m)
    lane, fwd, behind = f.starts(0)[0]
    base = ((lane, fwd), *(s for s in f.ego.route if s[0] != lane))
    tails = predict_routes(
        f.prep,
        base[-1][0],
        forward=base[-1][1],
        horizon_m=horizon_m,
        travelled_m=behind if len(base) == 1 else 0.0,
    )
    return [base + tail[1:] for tail in tails]


def _intersections(
    f: FrameContext,
    i: int,
    ego_routes: list[tuple[Step, ...]],
    obj_routes: list[tuple[Step, ...]],
    green: frozenset[int],
) -> tuple[list[Constellation], bool]:
    """Intersection constellations per conflicting lane pair; also whether a pair passes."""
    box = i + 1
    out: list[Constellation] = []
    seen: set[tuple[int, int]] = set()
    passing = False
    for obj_route in obj_routes:
        for ego_route in ego_routes:
            hit = conflict(f.prep, ego_route, obj_route)
            if hit is None:
                passing = True
                continue
            ie, io = hit
            key = (ego_route[ie][0], obj_route[io][0])
            if key in seen:
                continue
            seen.add(key)
            ego_plans = intersection_plans(f.prep, ego_route, ie, key[1])
            obj_plans = intersection_plans(f.prep, obj_route, io, key[0])
            cut_window(ego_plans, f.matches, (0,), cut_end=False)
            cut_window(obj_plans, f.matches, (box,), cut_end=False)
            kind = intersection_type(
                route_priority(f.prep, ego_route[: ie + 1], green),
                route_priority(f.prep, obj_route[: io + 1], green),
            )
            c = f.constellation(kind, i, ego_plans, obj_plans)
            if c is not None:
                out.append(c)
    return out, passing


def _target(f: FrameContext, box: int) -> int | None:
    lanes = [int(lane) for lane in f.matches.lanes_of(box) if int(lane) in f.tree.k]
    if not lanes:
        return None
    anchor = int(f.matches.anchor[box])
    return anchor if anchor in lanes else min(lanes, key=lambda lane: f.tree.cost_m[lane])


def _route_to(routes: list[tuple[Step, ...]], lane: int) -> tuple[Step, ...] | None:
    """The shortest prefix of one of ``routes`` that reaches ``lane``."""
    best: tuple[Step, ...] | None = None
    for route in routes:
        for idx, (step_lane, _) in enumerate(route):
            if step_lane == lane:
                if best is None or idx + 1 < len(best):
                    best = route[: idx + 1]
                break
    return best


def _following(
    f: FrameContext, i: int, ego_routes: list[tuple[Step, ...]], obj_routes: list[tuple[Step, ...]]
) -> Constellation | None:
    """SameDirection along a route if one vehicle is on the other's predicted route."""
    box = i + 1
    candidates = []
    for lane, _, _ in f.starts(box):
        route = _route_to(ego_routes, lane)
        if route is not None:
            candidates.append((route, route[-1]))
    for lane, _, _ in f.starts(0):
        route = _route_to(obj_routes, lane)
        if route is not None:
            candidates.append((route, route[0]))
    for route, (lane, fwd) in sorted(candidates, key=lambda c: len(c[0])):
        heading = f.headings[box][lane] + (0.0 if fwd else np.pi)
        if math.cos(float(f.objects.yaw_rad[i]) - heading) < _FOLLOWING_COS:
            continue
        plans = [SegmentPlan(lanes=[step]) for step in route]
        cut_window(plans, f.matches, (0, box))
        c = f.constellation(ConstellationType.SameDirection, i, plans, None)
        if c is not None:
            return c
    return None


def _corridor(f: FrameContext, i: int, target: int) -> Constellation | None:
    """Same/opposite direction along the connecting route to ``target``."""
    box = i + 1
    road_heading = f.headings[box][target] + (0.0 if f.tree.forward[target] else np.pi)
    cos = float(np.cos(float(f.objects.yaw_rad[i]) - road_heading))
    kind = ConstellationType.SameDirection if cos >= 0.0 else ConstellationType.OppositeDirection
    if kind == ConstellationType.OppositeDirection and f.behind_ego(i):
        return None  # driving apart
    plans = corridor_plans(f.prep, f.tree, target, f.matches, (0, box))
    return f.constellation(kind, i, plans, None)


def object_constellations(
    f: FrameContext,
    i: int,
    ego_routes: list[tuple[Step, ...]],
    horizon_m: float,
    green: frozenset[int],
) -> list[Constellation]:
    """All constellations between the ego and object ``i`` (see module docstring)."""
    box = i + 1
    target = _target(f, box)
    through = target is None or bool(f.prep.graph.is_intersection[f.tree.path(target)].any())
    if not through and target is not None:
        c = _corridor(f, i, target)
        return [] if c is None else [c]
    obj_routes = f.routes(box, horizon_m)
    follow = _following(f, i, ego_routes, obj_routes)
    if follow is not None:
        return [follow]
    found, passing = _intersections(f, i, ego_routes, obj_routes, green)
    if target is not None and (passing or not found):
        c = _corridor(f, i, target)
        if c is not None and (not found or c.constellation_type != ConstellationType.SameDirection):
            found.append(c)
    return found
