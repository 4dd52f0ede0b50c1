"""Differential-test oracle: our constellations -> ad-rss 5.0 world model -> RssCheck.

Test-only code. ``import rss`` must happen before ``import ad_rss``: the binding registers
a top-level module named ``rss`` and would otherwise shadow our package (imported first,
our package object merely gains the binding's ``world``/``core``/... attributes).
"""

from __future__ import annotations

import os
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any

import pytest

import rss  # noqa: F401  (must precede ad_rss, see module docstring)
from rss.conformance import json_number

if TYPE_CHECKING:
    from collections.abc import Sequence

    from rss.dynamics import RssDynamics
    from rss.model import Constellation, LaneObject, RoadSegment

__all__ = ["AdRssOracle", "OracleFrame", "compare_frames", "load_ad_rss"]


def load_ad_rss() -> Any:
    """Import the binding; skip without it, but fail under ``CI=true``."""
    if os.environ.get("CI", "").lower() == "true":
        import ad_rss  # noqa: PLC0415  (optional test dependency)

        return ad_rss
    return pytest.importorskip("ad_rss", reason="ad-rss 5.0 binding (pip ad-rss) not installed")


@dataclass
class OracleFrame:
    """ad-rss' answer for one frame: ``ok`` plus states by object id and the response."""

    ok: bool
    states: dict[int, dict[str, Any]] = field(default_factory=dict)
    proper_response: dict[str, Any] = field(default_factory=dict)


class AdRssOracle:
    """One ad-rss ``RssCheck`` instance (history over consecutive :meth:`step` calls)."""

    def __init__(self) -> None:
        """Create the check instance; time index starts at 1."""
        self.ad = load_ad_rss()
        self.ad.rss.core.setLogLevel("off")
        self.world = self.ad.rss.world
        self.phys = self.ad.physics
        self.check = self.ad.rss.core.RssCheck()
        self.time_index = 0

    # -- conversion -------------------------------------------------------------------
    def dynamics(self, dyn: RssDynamics) -> Any:
        """Our dynamics -> ``RssDynamics``."""
        p, out = self.phys, self.world.RssDynamics()
        out.alpha_lon.accel_max = p.Acceleration(dyn.accel_max_mps2)
        out.alpha_lon.brake_max = p.Acceleration(dyn.brake_max_mps2)
        out.alpha_lon.brake_min = p.Acceleration(dyn.brake_min_mps2)
        out.alpha_lon.brake_min_correct = p.Acceleration(dyn.brake_min_correct_mps2)
        out.alpha_lat.accel_max = p.Acceleration(dyn.lat_accel_max_mps2)
        out.alpha_lat.brake_min = p.Acceleration(dyn.lat_brake_min_mps2)
        out.lateral_fluctuation_margin = p.Distance(dyn.lateral_fluctuation_margin_m)
        out.response_time = p.Duration(dyn.response_time_s)
        out.max_speed_on_acceleration = p.Speed(dyn.max_speed_on_acceleration_mps)
        out.min_longitudinal_safety_distance = p.Distance(dyn.min_longitudinal_safety_distance_m)
        u, s = out.unstructured_settings, dyn.unstructured
        u.pedestrian_turning_radius = p.Distance(s.pedestrian_turning_radius)
        u.drive_away_max_angle = p.Angle(s.drive_away_max_angle)
        u.vehicle_yaw_rate_change = p.AngularAcceleration(s.vehicle_yaw_rate_change)
        u.vehicle_min_radius = p.Distance(s.vehicle_min_radius)
        u.vehicle_trajectory_calculation_step = p.Duration(s.vehicle_trajectory_calculation_step)
        for name in type(s).__dataclass_fields__:
            if name.endswith("_steps"):
                setattr(u, name, getattr(s, name))
        return out

    def _object(self, obj: LaneObject) -> Any:
        p, out = self.phys, self.world.Object()
        out.object_id = obj.object_id
        out.object_type = self.world.ObjectType(int(obj.object_type))
        for region in obj.regions:
            r = self.world.OccupiedRegion()
            r.segment_id = region.lane_id
            r.lon_range.minimum = p.ParametricValue(region.lon_min)
            r.lon_range.maximum = p.ParametricValue(region.lon_max)
            r.lat_range.minimum = p.ParametricValue(region.lat_min)
            r.lat_range.maximum = p.ParametricValue(region.lat_max)
            out.occupied_regions.append(r)
        v = out.velocity
        v.speed_lon_min, v.speed_lon_max = (
            p.Speed(obj.speed.lon_min_mps),
            p.Speed(obj.speed.lon_max_mps),
        )
        v.speed_lat_min, v.speed_lat_max = (
            p.Speed(obj.speed.lat_min_mps),
            p.Speed(obj.speed.lat_max_mps),
        )
        st = out.state
        st.yaw, st.yaw_rate, st.steering_angle = p.Angle(0.0), p.AngularVelocity(0.0), p.Angle(0.0)
        st.dimension.length, st.dimension.width = p.Distance(4.0), p.Distance(2.0)
        st.center_point.x, st.center_point.y = p.Distance(0.0), p.Distance(0.0)
        st.speed_range.minimum, st.speed_range.maximum = p.Speed(0.0), p.Speed(0.0)
        return out

    def _road(self, road: Sequence[RoadSegment]) -> Any:
        p, area = self.phys, self.world.RoadArea()
        for segment in road:
            seg = self.world.RoadSegment()
            seg.type = self.world.RoadSegmentType(int(segment.segment_type))
            seg.minimum_length_before_intersecting_area = p.Distance(
                segment.min_length_before_intersecting_area_m
            )
            seg.minimum_length_after_intersecting_area = p.Distance(
                segment.min_length_after_intersecting_area_m
            )
            for lane in segment.lanes:
                ls = self.world.LaneSegment()
                ls.id = lane.lane_id
                ls.driving_direction = self.world.LaneDrivingDirection(int(lane.driving_direction))
                ls.length.minimum, ls.length.maximum = (
                    p.Distance(lane.length_min_m),
                    p.Distance(lane.length_max_m),
                )
                ls.width.minimum, ls.width.maximum = (
                    p.Distance(lane.width_min_m),
                    p.Distance(lane.width_max_m),
                )
                seg.lane_segments.append(ls)
            area.append(seg)
        return area

    def world_model(self, constellations: Sequence[Constellation], default_ego: RssDynamics) -> Any:
        """Build the next ``WorldModel`` (increments the time index)."""
        self.time_index += 1
        wm = self.world.WorldModel()
        wm.time_index = self.time_index
        wm.default_ego_vehicle_rss_dynamics = self.dynamics(default_ego)
        for c in constellations:
            wc = self.world.Constellation()
            wc.constellation_type = self.world.ConstellationType(int(c.constellation_type))
            wc.ego_vehicle = self._object(c.ego)
            wc.object = self._object(c.other)
            wc.ego_vehicle_rss_dynamics = self.dynamics(c.ego_dynamics)
            wc.object_rss_dynamics = self.dynamics(c.other_dynamics)
            wc.ego_vehicle_road = self._road(c.ego_road)
            wc.intersecting_road = self._road(c.intersecting_road)
            wm.constellations.append(wc)
        return wm

    # -- evaluation -------------------------------------------------------------------
    def run(self, world_model: Any) -> tuple[bool, Any, Any]:
        """``calculateProperResponse`` on a built world: ``(ok, state snapshot, response)``."""
        core, state = self.ad.rss.core, self.ad.rss.state
        situation, snapshot, response = (
            core.RssSituationSnapshot(),
            state.RssStateSnapshot(),
            state.ProperResponse(),
        )
        ok = self.check.calculateProperResponse(world_model, situation, snapshot, response)
        return bool(ok), snapshot, response

    def step(
        self, constellations: Sequence[Constellation], default_ego: RssDynamics
    ) -> OracleFrame:
        """Evaluate one frame with this instance's history."""
        ok, snapshot, response = self.run(self.world_model(constellations, default_ego))
        if not ok:
            return OracleFrame(ok=False)
        frame = OracleFrame(ok=True)
        for s in snapshot.individual_responses:
            frame.states[int(s.object_id)] = {
                "constellation_type": str(s.constellation_type),
                "is_dangerous": bool(self.ad.rss.state.isDangerous(s)),
                "longitudinal": self._state(s.longitudinal_state),
                "lateral_left": self._state(s.lateral_state_left),
                "lateral_right": self._state(s.lateral_state_right),
            }
        ar = response.acceleration_restrictions
        frame.proper_response = {
            "is_safe": bool(response.is_safe),
            "dangerous_objects": sorted(int(x) for x in response.dangerous_objects),
            "longitudinal_response": str(response.longitudinal_response),
            "lateral_response_left": str(response.lateral_response_left),
            "lateral_response_right": str(response.lateral_response_right),
            "acceleration_restrictions": {
                name: [json_number(r.minimum.mAcceleration), json_number(r.maximum.mAcceleration)]
                for name, r in (
                    ("longitudinal", ar.longitudinal_range),
                    ("lateral_left", ar.lateral_left_range),
                    ("lateral_right", ar.lateral_right_range),
                )
            },
        }
        return frame

    @staticmethod
    def _state(s: Any) -> dict[str, Any]:
        info = s.rss_state_information
        return {
            "is_safe": bool(s.is_safe),
            "response": str(s.response),
            "evaluator": str(info.evaluator),
            "current_distance": json_number(info.current_distance.mDistance),
            "safe_distance": json_number(info.safe_distance.mDistance),
        }


_DISTANCE_KEYS = ("current_distance", "safe_distance")


def _compare_state(
    prefix: str, ours: dict[str, Any], theirs: dict[str, Any], tol: float
) -> list[str]:
    diffs = [
        f"{prefix}.{key}: ours {ours[key]!r} ad-rss {theirs[key]!r}"
        for key in ("is_safe", "response", "evaluator")
        if ours[key] != theirs[key]
    ]
    for key in _DISTANCE_KEYS:
        a, b = ours[key], theirs[key]
        if (a is None) != (b is None) or (a is not None and b is not None and abs(a - b) > tol):
            diffs.append(f"{prefix}.{key}: ours {a!r} ad-rss {b!r}")
    return diffs


def _compare_response(pr: dict[str, Any], ref_pr: dict[str, Any], tol: float) -> list[str]:
    diffs = [
        f"proper_response.{key}: ours {pr[key]!r} ad-rss {ref_pr[key]!r}"
        for key in (
            "is_safe",
            "longitudinal_response",
            "lateral_response_left",
            "lateral_response_right",
        )
        if pr[key] != ref_pr[key]
    ]
    if sorted(pr["dangerous_objects"]) != ref_pr["dangerous_objects"]:
        diffs.append(
            f"dangerous_objects: ours {pr['dangerous_objects']} "
            f"ad-rss {ref_pr['dangerous_objects']}"
        )
    for name, (lo, hi) in pr["acceleration_restrictions"].items():
        ref_lo, ref_hi = ref_pr["acceleration_restrictions"][name]
        if abs(lo - ref_lo) > tol or abs(hi - ref_hi) > tol:
            diffs.append(
                f"acceleration_restrictions.{name}: ours {[lo, hi]} ad-rss {[ref_lo, ref_hi]}"
            )
    return diffs


def compare_frames(ours: dict[str, Any], theirs: OracleFrame, tol: float = 1e-4) -> list[str]:
    """Differences between our frame record and ad-rss' answer; empty when they agree.

    Frames with an invalid object agree when ad-rss rejected the world (it fails whole
    worlds where we flag the object).
    """
    invalid = any(st.get("invalid") for st in ours["states"])
    if not theirs.ok or invalid:
        return (
            [] if invalid == (not theirs.ok) else [f"ad-rss ok={theirs.ok}, ours invalid={invalid}"]
        )
    diffs: list[str] = []
    for st in ours["states"]:
        ref = theirs.states.get(st["object_id"])
        if ref is None:
            diffs.append(f"object {st['object_id']}: missing in ad-rss")
            continue
        if st["is_dangerous"] != ref["is_dangerous"]:
            diffs.append(
                f"{st['object_id']}.is_dangerous: "
                f"ours {st['is_dangerous']} ad-rss {ref['is_dangerous']}"
            )
        for side in ("longitudinal", "lateral_left", "lateral_right"):
            diffs += _compare_state(f"{st['object_id']}.{side}", st[side], ref[side], tol)
    return diffs + _compare_response(ours["proper_response"], theirs.proper_response, tol)
