"""Adapt loader ``Frame`` records and lane maps to the reach-set engine's plain inputs."""

from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

import numpy as np

from loaders.maps.model import DRIVABLE_LANE_KINDS, LaneDirection, LaneKind, LineType
from loaders.records import PlanKind
from reachsets.adapter import reach_inputs_from_arrays
from reachsets.braking import braking_trajectory
from reachsets.inputs import RightOfWayRule, RoadLane, RoadLayout, TrackBounds

if TYPE_CHECKING:
    from loaders.maps.model import LaneMap
    from loaders.records import Frame
    from reachsets.inputs import ReachInputs

__all__ = [
    "PLAN_FALLBACK_HORIZON_S",
    "TRAJECTORY_MODES",
    "ReachMap",
    "ego_trajectory",
    "frame_to_reach_inputs",
    "prepare_map",
    "reach_inputs_and_kind",
    "road_layout_from_lane_map",
]

#: Without a plan the ego is assumed to keep its speed and heading for this long.
PLAN_FALLBACK_HORIZON_S = 4.0
#: The reach-set road layout: the drivable lanes of motor vehicles (not bicycle lanes).
_MOTOR_LANE_KINDS = DRIVABLE_LANE_KINDS - {LaneKind.BICYCLE}
_NO_PATH = (np.zeros(0), np.zeros(0), np.zeros(0))
_Trajectory = tuple[Any, Any, Any, Any, Any]


def road_layout_from_lane_map(lane_map: LaneMap) -> RoadLayout | None:
    """Lanes as polygons with centre lines in driving direction; solid borders as polylines."""
    lanes = []
    solid = []
    in_intersection = {lane_id for group in lane_map.intersections for lane_id in group}
    for lane in lane_map.lanes.values():
        if lane.kind not in _MOTOR_LANE_KINDS or len(lane.left_m) < 2:  # noqa: PLR2004
            continue
        ring = lane.outline_m
        centre = lane.centre_m if lane.direction != LaneDirection.NEGATIVE else lane.centre_m[::-1]
        lanes.append(
            RoadLane(
                lane_id=lane.id,
                polygon_m=ring,
                centre_m=centre,
                speed_limit_mps=lane.speed_limit_mps,
                in_intersection=lane.kind == LaneKind.INTERSECTION or lane.id in in_intersection,
            )
        )
        if lane.left_line == LineType.SOLID:
            solid.append(lane.left_m)
        if lane.right_line == LineType.SOLID:
            solid.append(lane.right_m)
    if not lanes:
        return None
    rules = tuple(RightOfWayRule(r.priority_lanes, r.yield_lanes) for r in lane_map.right_of_way)
    return RoadLayout(lanes=tuple(lanes), solid_lines_m=tuple(solid), right_of_way=rules)


@dataclass(frozen=True, slots=True)
class ReachMap:
    """A lane map converted once for the engine (shared by all frames of a drive).

    Attributes:
        track: Track bounds of a ``track`` map.
        road: Road layout of any other map (``None`` without road lanes).
    """

    track: TrackBounds | None = None
    road: RoadLayout | None = None


def prepare_map(lane_map: LaneMap | None) -> ReachMap:
    """Convert a lane map for the engine.

    A ``track`` map gives the track bounds (``boundaries_m = (left, right)``), other maps a
    road layout.
    """
    if lane_map is None:
        return ReachMap()
    if lane_map.format == "track" and len(lane_map.boundaries_m) >= 2:  # noqa: PLR2004
        return ReachMap(track=TrackBounds(lane_map.boundaries_m[0], lane_map.boundaries_m[1]))
    return ReachMap(road=road_layout_from_lane_map(lane_map))


#: ``trajectory`` modes of ``frame_to_reach_inputs``.
TRAJECTORY_MODES = ("planned", "auto", "braking")


def ego_trajectory(frame: Frame, mode: str = "planned") -> tuple[_Trajectory, str]:
    """The ego trajectory to rate and what it is.

    Modes: ``planned`` rates the log's plan as it is (without a plan the ego keeps its speed
    and heading for ``PLAN_FALLBACK_HORIZON_S``); ``braking`` rates the stop from the ego's
    state along its path (``reachsets.braking``); ``auto`` rates the plan when the log says
    it is an emergency trajectory (``Frame.plan_kind`` is ``PlanKind.EMERGENCY``: the
    ScenarioArchitect logs), else the stop.

    Returns:
        ``(x, y, yaw, speed, t)`` (``t`` ``None``: time the waypoints from their speeds) and
        the kind: ``"emergency"``, ``"planned"``, ``"constant_speed"`` (no plan) or
        ``"braking_from_state"``.
    """
    if mode not in TRAJECTORY_MODES:
        msg = f"trajectory mode {mode!r}: expected one of {', '.join(TRAJECTORY_MODES)}"
        raise ValueError(msg)
    ego = frame.ego
    plan = frame.plan
    has_plan = plan is not None and len(plan) > 0
    emergency = has_plan and frame.plan_kind is PlanKind.EMERGENCY
    if mode == "braking" or (mode == "auto" and not emergency):
        path = (plan.x_m, plan.y_m, plan.yaw_rad) if plan is not None and has_plan else _NO_PATH
        (x, y, yaw, speed), t = braking_trajectory(
            ego.x_m, ego.y_m, ego.yaw_rad, ego.speed_mps, *path
        )
        return (x, y, yaw, speed, t), "braking_from_state"
    if plan is not None and has_plan:
        speed = np.where(np.isfinite(plan.speed_mps), plan.speed_mps, ego.speed_mps)
        t_plan = plan.t_offset_s if np.all(np.isfinite(plan.t_offset_s)) else None
        kind = "emergency" if emergency else "planned"
        return (plan.x_m, plan.y_m, plan.yaw_rad, speed, t_plan), kind
    t = np.linspace(0.0, PLAN_FALLBACK_HORIZON_S, 21)
    dist = ego.speed_mps * t
    x = ego.x_m + np.cos(ego.yaw_rad) * dist
    y = ego.y_m + np.sin(ego.yaw_rad) * dist
    return (x, y, np.full_like(t, ego.yaw_rad), np.full_like(t, ego.speed_mps), t), "constant_speed"


def frame_to_reach_inputs(
    frame: Frame, lane_map: LaneMap | ReachMap | None, trajectory: str = "planned"
) -> ReachInputs:
    """Engine inputs of one frame.

    The ego trajectory is chosen by ``trajectory`` (see ``ego_trajectory``; ``planned``: the
    plan, its ``t_offset_s`` when known, else timed from its speeds). The map is converted
    with ``prepare_map`` (pass a ``ReachMap`` to convert it once per drive).
    """
    return reach_inputs_and_kind(frame, lane_map, trajectory)[0]


def reach_inputs_and_kind(
    frame: Frame, lane_map: LaneMap | ReachMap | None, trajectory: str = "planned"
) -> tuple[ReachInputs, str]:
    """``frame_to_reach_inputs`` and the kind of the ego trajectory (``ego_trajectory``)."""
    ego = frame.ego
    (x, y, yaw, speed, t), kind = ego_trajectory(frame, trajectory)
    actors = frame.actors
    valid = np.asarray(actors.valid, dtype=bool)
    prepared = lane_map if isinstance(lane_map, ReachMap) else prepare_map(lane_map)
    inputs = reach_inputs_from_arrays(
        ego_x_m=x,
        ego_y_m=y,
        ego_yaw_rad=yaw,
        ego_speed_mps=speed,
        ego_t_s=t,
        ego_length_m=ego.length_m,
        ego_width_m=ego.width_m,
        object_ids=[str(i) for i in actors.ids[valid]],
        object_x_m=actors.x_m[valid],
        object_y_m=actors.y_m[valid],
        object_yaw_rad=actors.yaw_rad[valid],
        object_speed_mps=actors.speed_mps[valid],
        object_length_m=actors.length_m[valid],
        object_width_m=actors.width_m[valid],
        track=prepared.track,
        road=prepared.road,
    )
    return inputs, kind
