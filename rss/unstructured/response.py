"""Unstructured response resolving (ad-rss ``RssResponseResolving`` + ``combineState``).

Dangerous states are folded in agent order, starting from the default ego dynamics
(``[brake_max, accel_max]`` longitudinally, lateral ranges ``[-1000, lat_accel_max]``):

* Brake: lon max ≤ ``brake_min``, heading ranges cleared;
* DriveAway: lon max ≤ ``accel_max`` if the ego's ``yaw + steering`` lies inside the range,
  else ``brake_min``; the range is intersected with the collected ones — no overlap marks a
  transition and the final response escalates to Brake (lon max ≤ the smallest
  ``brake_min`` of the DriveAway states);
* the most severe response wins (``None < ContinueForward < DriveAway < Brake``).
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING

from rss.physics import ACCELERATION_LOWEST_MPS2
from rss.unstructured.decision import UnstructuredResponse, inside_heading_range, normalize_angle

if TYPE_CHECKING:
    from rss.dynamics import RssDynamics
    from rss.unstructured.agents import UnstructuredAgents
    from rss.unstructured.decision import Decisions

__all__ = ["UnstructuredProperResponse", "heading_overlap", "resolve_unstructured"]

HeadingRange = tuple[float, float]


@dataclass(frozen=True)
class UnstructuredProperResponse:
    """The ego's proper response of one frame.

    Attributes:
        is_safe: No dangerous agent.
        dangerous_objects: Object ids of the dangerous agents.
        response: Most severe :class:`UnstructuredResponse`.
        heading_ranges: Allowed heading ranges ``(begin, end)`` [rad] (empty: none or Brake).
        lon_min_mps2: Allowed longitudinal acceleration, lower bound.
        lon_max_mps2: Upper bound.
        lat_min_mps2: Lateral lower bound (both sides; -1000 = unbounded).
        lat_max_mps2: Lateral upper bound (both sides).
    """

    is_safe: bool
    dangerous_objects: tuple[int, ...]
    response: UnstructuredResponse
    heading_ranges: tuple[HeadingRange, ...]
    lon_min_mps2: float
    lon_max_mps2: float
    lat_min_mps2: float
    lat_max_mps2: float


def _inside(angle: float, r: HeadingRange) -> bool:
    return bool(inside_heading_range(angle, r[0], r[1]))


def heading_overlap(a: HeadingRange, b: HeadingRange) -> list[HeadingRange]:
    """Overlap of two (possibly wrapping) heading ranges (ad-rss ``getHeadingOverlap``)."""
    a_start, a_end, b_start, b_end = (
        _inside(a[0], b),
        _inside(a[1], b),
        _inside(b[0], a),
        _inside(b[1], a),
    )
    if not (a_start or a_end or b_start or b_end):
        return []
    out: list[HeadingRange] = []
    if a_start and a_end and b_start and b_end:
        if a != b:
            out.append((a[0], b[1]))
        rng = (b[0], a[1])
    elif a_start and a_end:
        rng = a
    elif b_start and b_end:
        rng = b
    elif a_start:
        rng = (a[0], b[1])
    else:
        rng = (b[0], a[1])
    return [*out, rng]


def resolve_unstructured(
    decisions: Decisions,
    agents: UnstructuredAgents,
    ego: UnstructuredAgents,
    ego_dynamics: RssDynamics,
    default_ego: RssDynamics,
) -> UnstructuredProperResponse:
    """Fold the dangerous states of one frame into the proper response.

    Args:
        decisions: Per-agent decisions ``(N,)``.
        agents: The agents (ids).
        ego: The ego (one row; ``yaw + steering``).
        ego_dynamics: Ego dynamics of the constellations (``alpha_lon`` of the states).
        default_ego: Default ego dynamics of the frame (initial ranges).

    Returns:
        The proper response.
    """
    lon_min, lon_max = default_ego.brake_max_mps2, default_ego.accel_max_mps2
    drive_away_brake_min = default_ego.accel_max_mps2
    transition = False
    response = UnstructuredResponse.None_
    ranges: list[HeadingRange] = []
    dangerous: list[int] = []
    steering = float(normalize_angle(ego.yaw_rad[0] + ego.steering_angle_rad[0]))
    d = ego_dynamics
    for i in range(len(agents)):
        if decisions.is_safe[i]:
            continue
        dangerous.append(int(agents.object_id[i]))
        state = UnstructuredResponse(int(decisions.response[i]))
        rng = (float(decisions.heading_begin_rad[i]), float(decisions.heading_end_rad[i]))
        if response != UnstructuredResponse.Brake and state == UnstructuredResponse.DriveAway:
            drive_away_brake_min = min(drive_away_brake_min, d.brake_min_mps2)
            if not transition:
                ranges = (
                    [rng] if not ranges else [o for r in ranges for o in heading_overlap(rng, r)]
                )
                transition = not ranges
        response = max(response, state)
        lon_min = max(lon_min, d.brake_max_mps2)
        if state == UnstructuredResponse.Brake:
            ranges = []
            lon_max = min(lon_max, d.brake_min_mps2)
        elif state == UnstructuredResponse.DriveAway and not _inside(steering, rng):
            lon_max = min(lon_max, d.brake_min_mps2)
        else:
            lon_max = min(lon_max, d.accel_max_mps2)
    if transition and response == UnstructuredResponse.DriveAway:
        response = UnstructuredResponse.Brake
        lon_max = min(lon_max, drive_away_brake_min)
    return UnstructuredProperResponse(
        not dangerous,
        tuple(dangerous),
        response,
        tuple(ranges),
        lon_min,
        lon_max,
        ACCELERATION_LOWEST_MPS2,
        default_ego.lat_accel_max_mps2,
    )
