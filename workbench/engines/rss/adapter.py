"""Adapt lane maps and loader frames to RSS scene creation's plain inputs.

``LaneMap`` -> :class:`rss.scene.LaneGraph` (drivable lanes only: road, intersection,
bicycle; indices instead of ids) and ``Frame`` -> ego + objects with per-class dynamics.
Intersection lanes are those the map marks (kind, intersection groups, right-of-way
members) plus lanes whose area overlaps an unrelated lane (junction lanelets in Lanelet2
maps carry no explicit marker).
"""

from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np
import shapely

from loaders.maps.model import DRIVABLE_LANE_KINDS, LaneDirection, LaneKind
from loaders.records import ObjectClass as FrameClass
from rss.model import LaneDrivingDirection
from rss.params import ObjectClass
from rss.scene import LaneGraph, SceneEgo, SceneObjects
from rss.scene.matching import match_route
from workbench.engines.classes import adrss_type, dynamics_class
from workbench.engines.ids import EGO_OBJECT_ID

if TYPE_CHECKING:
    from loaders.maps.model import Lane, LaneMap
    from loaders.records import Frame
    from rss.params import RssParams
    from rss.scene import PreparedGraph
    from workbench.engines.ids import ActorIds

__all__ = ["frame_to_scene", "lane_graph_from_map"]

_OVERLAP_M2 = 1.0
_DIRECTION = {
    LaneDirection.POSITIVE: LaneDrivingDirection.Positive,
    LaneDirection.NEGATIVE: LaneDrivingDirection.Negative,
    LaneDirection.BIDIRECTIONAL: LaneDrivingDirection.Bidirectional,
}


def _overlapping(lanes: list[Lane], index: dict[str, int]) -> set[int]:
    polys = shapely.make_valid(np.array([shapely.Polygon(ln.outline_m) for ln in lanes]))
    a, b = shapely.STRtree(polys).query(polys, predicate="intersects")
    keep = a < b
    a, b = a[keep], b[keep]
    area = shapely.area(shapely.intersection(polys[a], polys[b]))
    out: set[int] = set()
    for i, j in zip(a[area > _OVERLAP_M2], b[area > _OVERLAP_M2], strict=True):
        li, lj = lanes[i], lanes[j]
        related = {*li.successors, *li.predecessors, li.left_neighbour, li.right_neighbour}
        if lj.id not in related and index.get(lj.id) is not None:
            out.update((int(i), int(j)))
    return out


def lane_graph_from_map(lane_map: LaneMap) -> LaneGraph:
    """The drivable lanes of ``lane_map`` as a :class:`LaneGraph`."""
    lanes = [
        ln
        for ln in lane_map.lanes.values()
        if ln.kind in DRIVABLE_LANE_KINDS
        and min(len(ln.left_m), len(ln.right_m), len(ln.centre_m)) >= 2  # noqa: PLR2004
    ]
    index = {ln.id: i for i, ln in enumerate(lanes)}

    def idx(lane_id: str | None) -> int:
        return index.get(lane_id, -1) if lane_id is not None else -1

    marked = {lane_id for group in lane_map.intersections for lane_id in group}
    priority = np.zeros(len(lanes), dtype=np.int64)
    for rule in lane_map.right_of_way:
        for lane_id in rule.priority_lanes:
            priority[idx(lane_id)] = 1 if idx(lane_id) >= 0 else priority[idx(lane_id)]
        for lane_id in rule.yield_lanes:
            priority[idx(lane_id)] = -1 if idx(lane_id) >= 0 else priority[idx(lane_id)]
        marked.update(rule.priority_lanes, rule.yield_lanes)
    light = np.full(len(lanes), -1, dtype=np.int64)
    for k, tl in enumerate(lane_map.traffic_lights):
        for lane_id in tl.controlled_lanes:
            if idx(lane_id) >= 0:
                light[idx(lane_id)] = k
    inter = np.array([ln.kind == LaneKind.INTERSECTION or ln.id in marked for ln in lanes])
    inter = inter.astype(np.bool_).reshape(len(lanes))
    if lanes:
        inter[list(_overlapping(lanes, index))] = True
    return LaneGraph(
        ids=tuple(ln.id for ln in lanes),
        left_m=tuple(ln.left_m for ln in lanes),
        right_m=tuple(ln.right_m for ln in lanes),
        centre_m=tuple(ln.centre_m for ln in lanes),
        direction=np.array([_DIRECTION[ln.direction] for ln in lanes], dtype=np.int64),
        speed_limit_mps=np.array([ln.speed_limit_mps for ln in lanes], dtype=np.float64),
        successors=tuple(tuple(idx(s) for s in ln.successors if idx(s) >= 0) for ln in lanes),
        predecessors=tuple(tuple(idx(s) for s in ln.predecessors if idx(s) >= 0) for ln in lanes),
        left_neighbour=np.array([idx(ln.left_neighbour) for ln in lanes], dtype=np.int64),
        right_neighbour=np.array([idx(ln.right_neighbour) for ln in lanes], dtype=np.int64),
        left_opposite=np.array([ln.left_neighbour_opposite for ln in lanes], dtype=np.bool_),
        right_opposite=np.array([ln.right_neighbour_opposite for ln in lanes], dtype=np.bool_),
        is_intersection=inter,
        priority=priority,
        traffic_light=light,
        light_ids=tuple(tl.id for tl in lane_map.traffic_lights),
        admap_reversed=np.array([ln.admap_reversed for ln in lanes], dtype=np.bool_),
    )


def frame_to_scene(
    frame: Frame, prep: PreparedGraph, params: RssParams, ids: ActorIds
) -> tuple[SceneEgo, SceneObjects, tuple[str, ...]]:
    """Ego and valid objects of one frame; also the ids of invalid actor rows.

    The ego size comes from the ``[scene]`` settings (no standard message carries it);
    the plan, when present, becomes the ego route.
    """
    ego = frame.ego
    route: tuple[tuple[int, bool], ...] = ()
    if frame.plan is not None and len(frame.plan) > 0:
        xy = np.stack([frame.plan.x_m, frame.plan.y_m], axis=1)
        route = tuple(match_route(prep, xy, np.asarray(frame.plan.yaw_rad)))
    scene_ego = SceneEgo(
        object_id=EGO_OBJECT_ID,
        x_m=ego.x_m,
        y_m=ego.y_m,
        yaw_rad=ego.yaw_rad,
        speed_mps=max(ego.speed_mps, 0.0),
        length_m=ego.length_m,
        width_m=ego.width_m,
        dynamics=params.for_class(ObjectClass.EGO),
        route=route,
    )
    actors = frame.actors
    valid = np.asarray(actors.valid, dtype=np.bool_)
    classes = [FrameClass(int(c)) for c in actors.object_class[valid]]
    objects = SceneObjects(
        ids=ids.to_ints(actors.ids[valid]),
        object_type=np.array([adrss_type(c) for c in classes], dtype=np.int64),
        x_m=np.asarray(actors.x_m[valid]),
        y_m=np.asarray(actors.y_m[valid]),
        yaw_rad=np.asarray(actors.yaw_rad[valid]),
        vx_mps=np.asarray(actors.vx_mps[valid]),
        vy_mps=np.asarray(actors.vy_mps[valid]),
        length_m=np.asarray(actors.length_m[valid]),
        width_m=np.asarray(actors.width_m[valid]),
        dynamics=tuple(params.for_class(dynamics_class(c)) for c in classes),
    )
    invalid = tuple(str(a) for a in actors.ids[~valid])
    return scene_ego, objects, invalid
