"""ad-rss oracle for unstructured constellations (ego + N agents, ENU frame). Test-only."""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any

import shapely

from tests.rss.oracle import AdRssOracle

if TYPE_CHECKING:
    from collections.abc import Sequence

    from rss.dynamics import RssDynamics
    from rss.unstructured.agents import UnstructuredAgents

__all__ = ["UnstructuredAnswer", "UnstructuredOracle"]


@dataclass
class UnstructuredAnswer:
    """ad-rss' answer for one frame."""

    ok: bool
    states: dict[int, dict[str, Any]] = field(default_factory=dict)
    proper_response: dict[str, Any] = field(default_factory=dict)
    ego_brake: Any = None
    ego_continue: Any = None
    brake: dict[int, Any] = field(default_factory=dict)
    continue_forward: dict[int, Any] = field(default_factory=dict)


def _polygon(points: Any) -> Any:
    coords = [(p.x.mDistance, p.y.mDistance) for p in points]
    return shapely.make_valid(shapely.Polygon(coords)) if len(coords) >= 3 else shapely.Polygon()


class UnstructuredOracle(AdRssOracle):
    """One ``RssCheck`` instance fed with unstructured constellations."""

    def _state_object(self, agents: UnstructuredAgents, i: int) -> Any:
        p, out = self.phys, self.world.Object()
        out.object_id = int(agents.object_id[i])
        out.object_type = self.world.ObjectType(int(agents.object_type[i]))
        st = out.state
        st.yaw = p.Angle(float(agents.yaw_rad[i]))
        st.yaw_rate = p.AngularVelocity(float(agents.yaw_rate_radps[i]))
        st.steering_angle = p.Angle(float(agents.steering_angle_rad[i]))
        st.dimension.length = p.Distance(float(agents.length_m[i]))
        st.dimension.width = p.Distance(float(agents.width_m[i]))
        st.center_point.x = p.Distance(float(agents.x_m[i]))
        st.center_point.y = p.Distance(float(agents.y_m[i]))
        st.speed_range.minimum = p.Speed(float(agents.speed_min_mps[i]))
        st.speed_range.maximum = p.Speed(float(agents.speed_max_mps[i]))
        v = out.velocity
        v.speed_lon_min, v.speed_lon_max = p.Speed(0.0), p.Speed(0.0)
        v.speed_lat_min, v.speed_lat_max = p.Speed(0.0), p.Speed(0.0)
        return out

    def evaluate(
        self,
        ego: UnstructuredAgents,
        agents: UnstructuredAgents,
        ego_dynamics: RssDynamics,
        agent_dynamics: Sequence[RssDynamics],
        default_ego: RssDynamics,
    ) -> UnstructuredAnswer:
        """Evaluate one frame (next time index of this instance)."""
        self.time_index += 1
        wm = self.world.WorldModel()
        wm.time_index = self.time_index
        wm.default_ego_vehicle_rss_dynamics = self.dynamics(default_ego)
        for i in range(len(agents)):
            c = self.world.Constellation()
            c.constellation_type = self.world.ConstellationType.Unstructured
            c.ego_vehicle = self._state_object(ego, 0)
            c.object = self._state_object(agents, i)
            c.ego_vehicle_rss_dynamics = self.dynamics(ego_dynamics)
            c.object_rss_dynamics = self.dynamics(agent_dynamics[i])
            wm.constellations.append(c)
        ok, snapshot, response = self.run(wm)
        if not ok:
            return UnstructuredAnswer(ok=False)
        ans = UnstructuredAnswer(ok=True)
        info = snapshot.unstructured_constellation_ego_information
        ans.ego_brake, ans.ego_continue = (
            _polygon(info.brake_trajectory_set),
            _polygon(info.continue_forward_trajectory_set),
        )
        for s in snapshot.individual_responses:
            u = s.unstructured_constellation_state
            oid = int(s.object_id)
            drive = str(u.response) == "DriveAway"
            ans.states[oid] = {
                "is_safe": bool(u.is_safe),
                "response": str(u.response),
                "heading_range": [u.heading_range.begin.mAngle, u.heading_range.end.mAngle]
                if drive
                else None,
            }
            ans.brake[oid] = _polygon(u.rss_state_information.brake_trajectory_set)
            ans.continue_forward[oid] = _polygon(
                u.rss_state_information.continue_forward_trajectory_set
            )
        ar = response.acceleration_restrictions.longitudinal_range
        ans.proper_response = {
            "is_safe": bool(response.is_safe),
            "dangerous_objects": sorted(int(x) for x in response.dangerous_objects),
            "response": str(response.unstructured_constellation_response),
            "heading_ranges": [[h.begin.mAngle, h.end.mAngle] for h in response.heading_ranges],
            "longitudinal": [ar.minimum.mAcceleration, ar.maximum.mAcceleration],
        }
        return ans
