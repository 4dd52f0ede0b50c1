"""Adapt loader frames to unstructured RSS: which pairs are unstructured, and the agents.

Which ego/actor pairs are checked with trajectory sets (:class:`UnstructuredScope`):

* ``[scene] constellation_creation_mode = "Unstructured"``: every pair;
* ``"Structured"`` (the default): pedestrians always; every actor when the ego has no
  drivable lane (road, intersection, bicycle) within :data:`ON_LANE_TOLERANCE_M` of its
  centre (no map, a racing track, off the lanes) or its centre lies in a parking lot (a
  parking lanelet, ``LaneKind.PARKING``, or an aisle: a drivable lanelet touching one);
  otherwise also the actors that are themselves off every drivable lane or on a parking
  lanelet (structured RSS cannot place them on a lane). The other pairs are left to
  structured RSS (``rss`` engine).

Agents (:func:`frame_to_agents`) are in the ENU map frame, ``(x, y)`` the box centre::

      y ▲   heading = direction of travel: a vehicle moving against its yaw (reversing)
        │   gets yaw + π (its footprint is symmetric); a walking pedestrian gets the
        └──▶ x   direction of its velocity. speed_min = speed_max = |v|.

Yaw rates: the ego's from odometry, actors' 0 (object lists carry none); steering 0. The
ego size comes from ``[scene]`` (as for structured RSS). Dynamics per class via
:meth:`rss.params.RssParams.for_class`.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np
import shapely

from loaders.maps.model import DRIVABLE_LANE_KINDS, LaneKind
from loaders.records import ObjectClass as FrameClass
from rss.model import ObjectType
from rss.params import ConstellationCreationMode
from rss.unstructured import UnstructuredAgents
from workbench.engines.classes import adrss_type, dynamics_class
from workbench.engines.ids import EGO_OBJECT_ID

if TYPE_CHECKING:
    from collections.abc import Collection

    from numpy.typing import NDArray

    from loaders.maps.model import LaneMap
    from loaders.records import Frame
    from rss.dynamics import RssDynamics
    from rss.params import RssParams
    from workbench.engines.ids import ActorIds

__all__ = [
    "MOVING_MIN_MPS",
    "ON_LANE_TOLERANCE_M",
    "FrameAgents",
    "UnstructuredScope",
    "frame_to_agents",
]

#: An agent within this distance of a drivable lane polygon counts as on the lane [m].
ON_LANE_TOLERANCE_M = 0.5
#: Below this speed the heading stays the box yaw (velocity direction is noise) [m/s].
MOVING_MIN_MPS = 0.1
_MIN_POINTS = 2


def _polygons(lane_map: LaneMap | None, kinds: Collection[LaneKind]) -> np.ndarray:
    """``(L,)`` valid lane polygons of the given kinds."""
    lanes = [] if lane_map is None else lane_map.lanes.values()
    polys = [
        shapely.Polygon(ln.outline_m)
        for ln in lanes
        if ln.kind in kinds and min(len(ln.left_m), len(ln.right_m)) >= _MIN_POINTS
    ]
    return np.asarray(shapely.make_valid(np.array(polys, dtype=object)), dtype=object)


def _near(polygons: np.ndarray, points: np.ndarray, distance_m: float) -> np.ndarray:
    """``(N,)`` geometry within ``distance_m`` of some polygon."""
    out = np.zeros(len(points), dtype=bool)
    if len(polygons) == 0 or len(points) == 0:
        return out
    hit, _ = shapely.STRtree(polygons).query(points, predicate="dwithin", distance=distance_m)
    out[hit] = True
    return out


class UnstructuredScope:
    """Decides which ego/actor pairs of a frame are unstructured (see the module docstring).

    A parking lot is its parking lanelets plus the aisles serving them: Lanelet2 has no
    aisle subtype, so a drivable lanelet within :data:`ON_LANE_TOLERANCE_M` of a parking
    lanelet counts as an aisle.
    """

    def __init__(self, lane_map: LaneMap | None, mode: ConstellationCreationMode) -> None:
        """Index the drivable and parking lanelets once.

        Args:
            lane_map: The drive's lane map, if any.
            mode: ``[scene] constellation_creation_mode``.
        """
        self.mode = mode
        self._drivable = _polygons(lane_map, DRIVABLE_LANE_KINDS)
        self._parking = _polygons(lane_map, (LaneKind.PARKING,))
        aisle = _near(self._parking, self._drivable, ON_LANE_TOLERANCE_M)
        self._lot = np.concatenate([self._parking, self._drivable[aisle]])

    def _points(self, x_m: np.ndarray, y_m: np.ndarray) -> np.ndarray:
        return np.asarray(shapely.points(np.column_stack([x_m, y_m]).reshape(-1, 2)))

    def select(self, frame: Frame) -> np.ndarray:
        """``(N,)`` the actor rows of ``frame`` to check with unstructured RSS."""
        actors = frame.actors
        n = len(actors)
        if self.mode == ConstellationCreationMode.UNSTRUCTURED:
            return np.ones(n, dtype=bool)
        ego = self._points(np.array([frame.ego.x_m]), np.array([frame.ego.y_m]))
        ego_on_road = _near(self._drivable, ego, ON_LANE_TOLERANCE_M)[0]
        if not ego_on_road or _near(self._lot, ego, 0.0)[0]:
            return np.ones(n, dtype=bool)
        points = self._points(actors.x_m, actors.y_m)
        on_road = _near(self._drivable, points, ON_LANE_TOLERANCE_M)
        pedestrian = np.asarray(actors.object_class) == FrameClass.PEDESTRIAN
        return np.asarray(pedestrian | ~on_road | _near(self._parking, points, 0.0))


@dataclass(frozen=True)
class FrameAgents:
    """Unstructured inputs of one frame.

    Attributes:
        ego: The ego (one row, id :data:`workbench.engines.rss.adapter.EGO_OBJECT_ID`).
        agents: ``(K,)`` the selected, valid actors.
        dynamics: One dynamics per agent.
        actor_ids: ``(K,)`` the agents' actor ids (strings, as in the log).
        invalid: Ids of selected actor rows that cannot be checked (invalid values).
    """

    ego: UnstructuredAgents
    agents: UnstructuredAgents
    dynamics: tuple[RssDynamics, ...]
    actor_ids: tuple[str, ...]
    invalid: tuple[str, ...]


def _travel_heading(
    yaw_rad: NDArray[np.float64],
    vx_mps: NDArray[np.float64],
    vy_mps: NDArray[np.float64],
    walker: NDArray[np.bool_],
) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """Heading of travel wrapped to [-π, π) and speed, ``(N,)`` each (module docstring)."""
    vx, vy = vx_mps, vy_mps
    speed = np.hypot(vx, vy)
    moving = speed > MOVING_MIN_MPS
    reversing = moving & (vx * np.cos(yaw_rad) + vy * np.sin(yaw_rad) < 0.0)
    heading = np.where(reversing, yaw_rad + math.pi, yaw_rad)
    heading = np.where(walker & moving, np.arctan2(vy, vx), heading)
    return np.mod(heading + math.pi, 2.0 * math.pi) - math.pi, speed


def frame_to_agents(
    frame: Frame, selected: np.ndarray, params: RssParams, ids: ActorIds
) -> FrameAgents:
    """The ego and the ``selected`` actors of ``frame`` as :class:`UnstructuredAgents`.

    Args:
        frame: One loader frame.
        selected: ``(N,)`` actor rows to convert (from :meth:`UnstructuredScope.select`).
        params: Dynamics per class and the ego size.
        ids: The drive's actor label table (:mod:`workbench.engines.ids`).
    """
    e = frame.ego
    e_heading, e_speed = _travel_heading(
        np.array([e.yaw_rad]),
        np.array([e.speed_mps * math.cos(e.yaw_rad)]),
        np.array([e.speed_mps * math.sin(e.yaw_rad)]),
        np.zeros(1, dtype=bool),
    )
    yaw_rate = e.yaw_rate_radps if math.isfinite(e.yaw_rate_radps) else 0.0
    row = np.array([e.x_m, e.y_m, yaw_rate, 0.0, e.length_m, e.width_m]).reshape(-1, 1)
    ego = UnstructuredAgents(
        object_id=np.array([EGO_OBJECT_ID], dtype=np.int64),
        object_type=np.array([ObjectType.EgoVehicle], dtype=np.int64),
        x_m=row[0],
        y_m=row[1],
        yaw_rad=e_heading,
        speed_min_mps=e_speed,
        speed_max_mps=e_speed,
        yaw_rate_radps=row[2],
        steering_angle_rad=row[3],
        length_m=row[4],
        width_m=row[5],
    )
    a = frame.actors
    rows = np.flatnonzero(np.asarray(selected, dtype=bool))
    classes = [FrameClass(int(c)) for c in a.object_class[rows]]
    heading, speed = _travel_heading(
        a.yaw_rad[rows],
        a.vx_mps[rows],
        a.vy_mps[rows],
        np.array([c == FrameClass.PEDESTRIAN for c in classes], dtype=bool),
    )
    agents = UnstructuredAgents(
        object_id=ids.to_ints(a.ids[rows]),
        object_type=np.array([adrss_type(c) for c in classes], dtype=np.int64),
        x_m=a.x_m[rows],
        y_m=a.y_m[rows],
        yaw_rad=heading,
        speed_min_mps=speed,
        speed_max_mps=speed,
        yaw_rate_radps=np.zeros(len(rows)),
        steering_angle_rad=np.zeros(len(rows)),
        length_m=a.length_m[rows],
        width_m=a.width_m[rows],
    )
    ok = agents.valid() & np.asarray(a.valid[rows], dtype=bool)
    actor_ids = [str(i) for i in a.ids[rows]]
    keep = np.flatnonzero(ok)
    return FrameAgents(
        ego=ego,
        agents=agents.take(keep),
        dynamics=tuple(params.for_class(dynamics_class(classes[k])) for k in keep),
        actor_ids=tuple(actor_ids[k] for k in keep),
        invalid=tuple(actor_ids[k] for k in np.flatnonzero(~ok)),
    )
