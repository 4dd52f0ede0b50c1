"""Road-boundary objects (ad-rss ``appendRoadBoundaries``, mode ``RouteOnly``).

Two static ``ArtificialObject``s lie along the ego's route: one in the leftmost 0.1 % of
the leftmost lane, one in the rightmost 0.1 % of the rightmost lane of every segment. The
road area is the route with the lanes beside it that carry traffic in the same direction
(the driving-direction half of the road)::

      left boundary  ▔▔▔▔▔▔▔▔▔▔▔▔▔▔▔▔▔▔▔▔▔▔▔▔▔▔▔▔   lat [0, 0.001] of the leftmost lane
                     ──ego──▶      route …
      right boundary ▁▁▁▁▁▁▁▁▁▁▁▁▁▁▁▁▁▁▁▁▁▁▁▁▁▁▁▁   lat [0.999, 1] of the rightmost lane

Both are ``SameDirection`` constellations with static dynamics (no acceleration, brakes
-0.01 m/s², no fluctuation margin, response time 0.01 s), so only the ego's lateral
distance to the edge matters.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

from rss.dynamics import RssDynamics
from rss.model import (
    Constellation,
    ConstellationType,
    LaneObject,
    ObjectType,
    OccupiedRegion,
    SpeedInterval,
)
from rss.scene.roadarea import build_road, place_object
from rss.scene.routes import lateral
from rss.scene.segment_plans import SegmentPlan, cut_window

if TYPE_CHECKING:
    from rss.scene.frame import FrameContext
    from rss.scene.lanegraph import Step

__all__ = ["BOUNDARY_DYNAMICS", "LEFT_BOUNDARY_ID", "RIGHT_BOUNDARY_ID", "boundary_constellations"]

#: Id of the left road-boundary object.
LEFT_BOUNDARY_ID = 2**61 + 1
#: Id of the right road-boundary object.
RIGHT_BOUNDARY_ID = 2**61 + 2
#: Dynamics of a road boundary (ad-rss map integration's static object dynamics).
BOUNDARY_DYNAMICS = RssDynamics(
    accel_max_mps2=0.0,
    brake_max_mps2=-0.01,
    brake_min_mps2=-0.01,
    brake_min_correct_mps2=-0.01,
    lat_accel_max_mps2=0.0,
    lat_brake_min_mps2=-0.01,
    lateral_fluctuation_margin_m=0.0,
    response_time_s=0.01,
)
_EDGE = 0.001


def _same_direction_section(f: FrameContext, step: Step) -> list[Step]:
    """``step`` with the lanes beside it that are not separated by an opposite lane."""
    g = f.prep.graph
    out = [step]
    for right in (False, True):
        current: Step | None = step
        while current is not None:
            lane, fwd = current
            use_right = right == fwd
            opposite = bool(g.right_opposite[lane] if use_right else g.left_opposite[lane])
            nxt = None if opposite else lateral(f.prep, lane, forward=fwd, right=right)
            if nxt is not None:
                out.insert(len(out) if right else 0, nxt)
            current = nxt
    return out


def boundary_constellations(f: FrameContext, route: tuple[Step, ...]) -> list[Constellation]:
    """The two boundary constellations along ``route`` (empty if the ego is not on it)."""
    plans = [SegmentPlan(lanes=_same_direction_section(f, step)) for step in route]
    cut_window(plans, f.matches, (0,), cut_end=False)
    road, placed, _ = build_road(f.prep, f.memo, plans)
    ego = place_object(
        f.matches,
        0,
        placed,
        f.ego.object_id,
        ObjectType.EgoVehicle,
        f.ego_velocity,
        f.headings[0],
    )
    if ego is None:
        return []
    out = []
    for object_id, side in ((LEFT_BOUNDARY_ID, 0), (RIGHT_BOUNDARY_ID, -1)):
        lat = (0.0, _EDGE) if side == 0 else (1.0 - _EDGE, 1.0)
        regions = tuple(
            OccupiedRegion(segment.lanes[side].lane_id, 0.0, 1.0, *lat) for segment in road
        )
        other = LaneObject(
            object_id, ObjectType.ArtificialObject, regions, SpeedInterval(0, 0, 0, 0)
        )
        out.append(
            Constellation(
                constellation_type=ConstellationType.SameDirection,
                ego=ego,
                other=other,
                ego_dynamics=f.ego.dynamics,
                other_dynamics=BOUNDARY_DYNAMICS,
                ego_road=road,
            )
        )
    return out
