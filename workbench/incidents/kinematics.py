"""Physical facts of an incident's own object, from the recorded states (engine-independent).

Every engine's incident gets the same facts, computed from the ego's and its object's boxes
in the incident's unsafe frames, so incidents of different engines compare in one unit:

- ``gap_m``: the smallest distance between the two footprints (oriented boxes) [m], 0 when
  they overlap;
- ``closing_speed_mps``: how fast that gap shrinks [m/s] (negative: opening), from the
  recorded velocities (ego: speed along its heading; object: ``vx, vy``);
- ``ttc_s``: time to collision along the path: the first time the boxes touch when both
  keep their velocity and heading (``None``: they never do, e.g. the gap opens or the
  vehicles pass side by side laterally clear);
- ``decel_mps2``: the deceleration of the relative motion that avoids that collision,
  ``|v_rel|² / (2 d)`` with ``d = |v_rel| · ttc`` the distance travelled to contact
  (``None`` without a collision course).

The incident's ``criticality`` (:func:`workbench.incidents.order.criticality` of a frame's
TTC and deceleration) is the largest one held over ``SUSTAIN_FRAMES`` consecutive unsafe
frames (the smallest of theirs), so a single frame's noise in a recorded heading or speed
does not make a danger; an incident shorter than that has criticality 0.

The boxes' time of first contact comes from the separating-axis theorem on moving convex
polygons: along each of the four edge normals the projections overlap during one time
interval; the boxes touch while every interval does.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import TYPE_CHECKING

from workbench.incidents.order import criticality

if TYPE_CHECKING:
    from collections.abc import Callable

    from loaders.records import Frame

__all__ = [
    "SUSTAIN_FRAMES",
    "Box",
    "Motion",
    "MotionFacts",
    "box_gap_m",
    "motion",
    "motion_of",
    "time_to_contact_s",
]

#: Finite-difference step of the closing speed [s].
CLOSING_STEP_S = 0.05
#: Consecutive unsafe frames a criticality must hold to count.
SUSTAIN_FRAMES = 2

Point = tuple[float, float]


@dataclass(frozen=True, slots=True)
class Box:
    """An oriented box moving at constant velocity (map frame, SI units)."""

    x_m: float
    y_m: float
    yaw_rad: float
    length_m: float
    width_m: float
    vx_mps: float = 0.0
    vy_mps: float = 0.0

    def corners(self, t_s: float = 0.0) -> list[Point]:
        """The four corners [m] at time ``t_s`` [s] (counter-clockwise)."""
        c, s = math.cos(self.yaw_rad), math.sin(self.yaw_rad)
        hl, hw = self.length_m / 2, self.width_m / 2
        x, y = self.x_m + self.vx_mps * t_s, self.y_m + self.vy_mps * t_s
        return [
            (x + c * dx - s * dy, y + s * dx + c * dy)
            for dx, dy in ((hl, hw), (-hl, hw), (-hl, -hw), (hl, -hw))
        ]


@dataclass(frozen=True, slots=True)
class Motion:
    """The physical facts of one frame (see the module docstring)."""

    gap_m: float
    closing_speed_mps: float
    ttc_s: float | None
    decel_mps2: float | None


def _axes(a: Box, b: Box) -> list[Point]:
    return [
        (math.cos(yaw), math.sin(yaw))
        for yaw in (a.yaw_rad, a.yaw_rad + math.pi / 2, b.yaw_rad, b.yaw_rad + math.pi / 2)
    ]


def _span(corners: list[Point], axis: Point) -> tuple[float, float]:
    dots = [x * axis[0] + y * axis[1] for x, y in corners]
    return min(dots), max(dots)


def time_to_contact_s(a: Box, b: Box) -> float | None:
    """First time [s] ``>= 0`` the boxes touch at constant velocity (0: they overlap now)."""
    ca, cb = a.corners(), b.corners()
    rvx, rvy = b.vx_mps - a.vx_mps, b.vy_mps - a.vy_mps
    enter, leave = -math.inf, math.inf
    for axis in _axes(a, b):
        a0, a1 = _span(ca, axis)
        b0, b1 = _span(cb, axis)
        rate = rvx * axis[0] + rvy * axis[1]
        if abs(rate) < 1e-12:  # noqa: PLR2004 - no motion along this axis
            if b1 < a0 or b0 > a1:
                return None
            continue
        t0, t1 = (a0 - b1) / rate, (a1 - b0) / rate
        enter, leave = max(enter, min(t0, t1)), min(leave, max(t0, t1))
        if enter > leave or leave < 0:
            return None
    return max(enter, 0.0)


def _point_segment_m(p: Point, a: Point, b: Point) -> float:
    ex, ey = b[0] - a[0], b[1] - a[1]
    length2 = ex * ex + ey * ey
    u = 0.0 if length2 == 0 else ((p[0] - a[0]) * ex + (p[1] - a[1]) * ey) / length2
    u = min(max(u, 0.0), 1.0)
    return math.hypot(p[0] - a[0] - u * ex, p[1] - a[1] - u * ey)


def box_gap_m(a: Box, b: Box, t_s: float = 0.0) -> float:
    """Smallest distance [m] between the footprints at time ``t_s`` (0 when they overlap)."""
    ca, cb = a.corners(t_s), b.corners(t_s)
    if all(
        not (s_b[1] < s_a[0] or s_b[0] > s_a[1])
        for s_a, s_b in ((_span(ca, ax), _span(cb, ax)) for ax in _axes(a, b))
    ):
        return 0.0
    edges_a = list(zip(ca, [*ca[1:], ca[0]], strict=True))
    edges_b = list(zip(cb, [*cb[1:], cb[0]], strict=True))
    return min(
        *(_point_segment_m(p, *e) for p in ca for e in edges_b),
        *(_point_segment_m(p, *e) for p in cb for e in edges_a),
    )


def motion(ego: Box, obj: Box) -> Motion:
    """The physical facts of one frame."""
    gap = box_gap_m(ego, obj)
    closing = (gap - box_gap_m(ego, obj, CLOSING_STEP_S)) / CLOSING_STEP_S
    ttc = time_to_contact_s(ego, obj)
    decel = None
    if ttc is not None and ttc > 0:
        decel = math.hypot(obj.vx_mps - ego.vx_mps, obj.vy_mps - ego.vy_mps) / (2 * ttc)
    return Motion(gap, closing, ttc, decel)


def motion_of(frame: Frame, object_id: str, index: dict[str, int]) -> Motion | None:
    """The facts of ``object_id`` in ``frame`` (``index``: its actors' rows by id).

    ``None`` when the frame has no valid row of that object.
    """
    j = index.get(object_id)
    actors = frame.actors
    if j is None or not bool(actors.valid[j]):
        return None
    ego = frame.ego
    ego_box = Box(
        ego.x_m,
        ego.y_m,
        ego.yaw_rad,
        ego.length_m,
        ego.width_m,
        ego.speed_mps * math.cos(ego.yaw_rad),
        ego.speed_mps * math.sin(ego.yaw_rad),
    )
    obj_box = Box(
        float(actors.x_m[j]),
        float(actors.y_m[j]),
        float(actors.yaw_rad[j]),
        float(actors.length_m[j]),
        float(actors.width_m[j]),
        float(actors.vx_mps[j]),
        float(actors.vy_mps[j]),
    )
    return motion(ego_box, obj_box)


class MotionFacts:
    """The worst physical facts over an incident's frames."""

    def __init__(self) -> None:
        """Start empty."""
        self.gap_min_m: float | None = None
        self.closing_max_mps: float | None = None
        self.ttc_min_s: float | None = None
        self.decel_max_mps2: float | None = None
        self.criticality = 0.0
        self._recent: list[float] = []

    def add(self, found: Motion) -> None:
        """One unsafe frame's facts."""
        self._recent = [*self._recent, criticality(found.ttc_s, found.decel_mps2)]
        self._recent = self._recent[-SUSTAIN_FRAMES:]
        if len(self._recent) == SUSTAIN_FRAMES:
            self.criticality = max(self.criticality, min(self._recent))
        self.gap_min_m = _pick(min, self.gap_min_m, found.gap_m)
        self.closing_max_mps = _pick(max, self.closing_max_mps, found.closing_speed_mps)
        self.ttc_min_s = _pick(min, self.ttc_min_s, found.ttc_s)
        self.decel_max_mps2 = _pick(max, self.decel_max_mps2, found.decel_mps2)

    def facts(self) -> dict[str, float | None]:
        """The facts by name (the module docstring's, ``path_`` ones and ``criticality``).

        ``gap_min_m``, ``closing_speed_max_mps``, ``path_ttc_min_s``, ``path_decel_max_mps2``;
        values rounded to 1e-6; ``None`` where no frame had the fact (never on a collision
        course); no facts at all when no frame had the object's state.
        """
        if self.gap_min_m is None:
            return {}
        values = {
            "gap_min_m": self.gap_min_m,
            "closing_speed_max_mps": self.closing_max_mps,
            "path_ttc_min_s": self.ttc_min_s,
            "path_decel_max_mps2": self.decel_max_mps2,
            "criticality": self.criticality,
        }
        return {k: None if v is None else round(v, 6) for k, v in values.items()}


def _pick(
    how: Callable[[float, float], float], old: float | None, new: float | None
) -> float | None:
    if new is None or not math.isfinite(new):
        return old
    return new if old is None else how(old, new)
