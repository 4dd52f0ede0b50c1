"""Ego pose from GNSS: ``sensor_msgs/NavSatFix`` (+ ``sensor_msgs/Imu`` for the heading).

Latitude/longitude are projected onto the local east-north-up tangent plane at an origin
with ``pymap3d.geodetic2enu`` (WGS-84), the same projection ``loaders.maps.lanelet2`` applies
to a map's nodes, about the same origin (the map's ``LaneMap.origin_deg``), so the ego lands
on the map. Without a map the first fix is the origin. East/north are taken at zero height
like the map's nodes (the altitude only sets ``z_m``, relative to the first fix)::

    north (y) ^
              |   . fix (lat, lon)  -> (east, north) metres from the origin
              |  /
              +------> east (x)
          origin (lat0, lon0)

Heading: the yaw of the latest ``Imu`` orientation (ENU, REP 103) when the log has an IMU
topic and a message arrived at or before the fix; otherwise the sample is marked
``heading_from_track`` and the frame assembler takes the direction of travel. Fixes with
``status.status < 0`` (no fix) are skipped.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

import pymap3d

from loaders.message_logs.poses import ros_stamp_ns, yaw_from_quaternion
from loaders.message_logs.samples import EgoSample

__all__ = ["IMU_TYPE", "NAVSATFIX_TYPE", "GnssEgo"]

#: GNSS fix message type (normalised spelling).
NAVSATFIX_TYPE = "sensor_msgs/NavSatFix"
#: IMU message type (normalised spelling).
IMU_TYPE = "sensor_msgs/Imu"


@dataclass(slots=True)
class GnssEgo:
    """Stateful ego decoder for a fix topic and an optional IMU topic.

    Attributes:
        origin_deg: ``(lat, lon)`` of the local frame's origin; None takes the first fix.
    """

    origin_deg: tuple[float, float] | None = None
    _alt0_m: float | None = None
    _yaw_rad: float | None = None

    def decode_imu(self, msg: Any) -> None:
        """Remember the heading of an ``Imu`` message (ignored without orientation)."""
        q = msg.orientation
        if float(msg.orientation_covariance[0]) == -1.0:  # REP 145: orientation unknown
            return
        self._yaw_rad = yaw_from_quaternion(float(q.x), float(q.y), float(q.z), float(q.w))

    def decode_fix(self, msg: Any) -> EgoSample | None:
        """A sample from a ``NavSatFix``; None for a message without a fix."""
        if int(msg.status.status) < 0:
            return None
        lat, lon, alt = float(msg.latitude), float(msg.longitude), float(msg.altitude)
        if not (math.isfinite(lat) and math.isfinite(lon)):
            return EgoSample(ros_stamp_ns(msg.header.stamp), lat, lon, alt, float("nan"))
        if self.origin_deg is None:
            self.origin_deg = (lat, lon)
        if self._alt0_m is None:
            self._alt0_m = alt if math.isfinite(alt) else 0.0
        lat0, lon0 = self.origin_deg
        east, north, _ = pymap3d.geodetic2enu(lat, lon, 0.0, lat0, lon0, 0.0)
        z = alt - self._alt0_m
        stamp = ros_stamp_ns(msg.header.stamp)
        if self._yaw_rad is None:
            return EgoSample(
                stamp, float(east), float(north), z, float("nan"), heading_from_track=True
            )
        return EgoSample(stamp, float(east), float(north), z, self._yaw_rad)
