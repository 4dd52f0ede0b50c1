"""ad-map 5.0's ENU heading of a lane chord, defect included (intersection arms).

ad-map orders the arms of an intersection by the heading of each entry / exit lane's
chord (``getLaneDirectionalAngle``): from the middle of the lane's end to the middle of
its start (against the traffic), made an ENU heading at the end point. It converts both
points to ECEF, but takes the east and up axes of that ENU frame from the points 1 m east
and 1 m up of the *map origin* (the geo reference), not of the end point (measured with
the oracle: ``toECEF(ENUPoint, GeoPoint)`` ignores its reference point). The heading is
then measured against the direction from the end point to the origin's east point::

        y (north)
        ^          a o<-------o b       d = a - b: the chord, a / b the lane's start / end
        |                  .            (in driving direction)
        |               .    e          e = (1, 0) - b: "east" (should be (1, 0))
        |            .                  u = (0, 0, 1) - b: "up"
        o--------o--------> x (east)    heading = angle from e to d about u
      origin   (1, 0)

so a chord's heading comes out as its true heading plus ``atan2(b_y, 1 - b_x)`` (-153.4°
at ``b = (300, -150)`` m). In map coordinates this does not depend on where the geo
reference lies on the globe (same headings within 1e-11 rad for a reference at
latitude/longitude 0 and at 49° N 8° E, measured). The heights of the points below the
origin's tangent plane (Earth curvature) only decide the sign where the chord nearly
points along ``e``; they are modelled on a sphere of the WGS84 equatorial radius. Against
the oracle's own value for every Town01 drivable lane: within 3e-9 rad.
"""

from __future__ import annotations

import math
from typing import TYPE_CHECKING

from rss.model import LaneDrivingDirection

if TYPE_CHECKING:
    from rss.scene.prepared import PreparedGraph

__all__ = ["defective_enu_heading", "lane_chord_heading"]

#: WGS84 equatorial radius [m]: drop of a point below the map origin's tangent plane.
_EARTH_RADIUS_M = 6378137.0


def _point(x: float, y: float) -> tuple[float, float, float]:
    """A map point at height 0 in the map origin's tangent frame (east, north, up) [m]."""
    return x, y, -(x * x + y * y) / (2.0 * _EARTH_RADIUS_M)


def defective_enu_heading(start: tuple[float, float], end: tuple[float, float]) -> float:
    """ad-map 5.0's heading [rad] of the chord ``end -> start`` at ``end`` (module docstring).

    Args:
        start: ``(x, y)`` [m] of the lane's start (in driving direction), map frame.
        end: ``(x, y)`` [m] of the lane's end, map frame.

    Returns:
        The heading in ``(-pi, pi]`` as ad-map 5.0 computes it (``atan2(|e x d|, e . d)``
        with the sign of ``(e x d) . u``).
    """
    bx, by, bz = _point(*end)
    ax, ay, az = _point(*start)
    ox, oy, oz = _point(1.0, 0.0)
    d = (ax - bx, ay - by, az - bz)
    e = (ox - bx, oy - by, oz - bz)
    u = (-bx, -by, 1.0 - bz)
    c = (e[1] * d[2] - e[2] * d[1], e[2] * d[0] - e[0] * d[2], e[0] * d[1] - e[1] * d[0])
    sin_abs = math.sqrt(c[0] * c[0] + c[1] * c[1] + c[2] * c[2])
    cos = e[0] * d[0] + e[1] * d[1] + e[2] * d[2]
    negative = c[0] * u[0] + c[1] * u[1] + c[2] * u[2] < 0.0
    heading = math.atan2(-sin_abs if negative else sin_abs, cos)
    return math.pi if heading == -math.pi else heading


def lane_chord_heading(prep: PreparedGraph, lane: int) -> float:
    """ad-map 5.0's ``getLaneDirectionalAngle`` of ``lane`` [rad], defect included.

    The chord runs between the middles of the two border ends (ad-map's parametric points
    0 and 1 at lateral 0.5), from the end in driving direction to the start. A
    bidirectional lane runs along ad-map's point order (``LaneGraph.admap_reversed``).
    """
    g = prep.graph
    left, right = g.left_m[lane], g.right_m[lane]
    first = (0.5 * float(left[0][0] + right[0][0]), 0.5 * float(left[0][1] + right[0][1]))
    last = (0.5 * float(left[-1][0] + right[-1][0]), 0.5 * float(left[-1][1] + right[-1][1]))
    code = int(g.direction[lane])
    reversed_order = g.admap_reversed is not None and bool(g.admap_reversed[lane])
    backwards = code == LaneDrivingDirection.Negative or (
        code == LaneDrivingDirection.Bidirectional and reversed_order
    )
    return defective_enu_heading(last, first) if backwards else defective_enu_heading(first, last)
