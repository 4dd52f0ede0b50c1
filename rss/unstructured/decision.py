"""Conditions 22.1 / 22.2, decision rules and drive-away persistence, over ``N`` agents.

ad-rss ``RssUnstructuredConstellationChecker``.

::

    22.1a  ego must brake   = !(T_ego,b ∩ T_oth,f) and  (T_oth,b ∩ T_ego,f)
    22.1b  other must brake = !(T_oth,b ∩ T_ego,f) and  (T_ego,b ∩ T_oth,f)
    22.2   both brake       = !(T_ego,b ∩ T_oth,b)
    safe = 22.1a or 22.1b or 22.2                       -> ContinueForward
    unsafe: both speed_max <= 0.1 m/s                 -> DriveAway
            remembered 22.1b: ego speed_max > 0.1     -> ContinueForward (reported safe)
                              else                    -> DriveAway
            otherwise                                 -> Brake

The Rule-2 test of the ego's speed (the ad-rss log text talks about the opponent) and the
"safe" flag of a Rule-2 ContinueForward are ad-rss quirks, reproduced.
"""

from __future__ import annotations

import enum
from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np

from rss.physics import DISTANCE_PRECISION, SPEED_PRECISION, eq, gt, le
from rss.unstructured.memory import UnstructuredMemory

if TYPE_CHECKING:
    from rss.arrays import BoolArray, FloatArray, IntArray
    from rss.unstructured.agents import UnstructuredAgents
    from rss.unstructured.kinematics import Real

__all__ = [
    "ANGLE_PRECISION",
    "DRIVE_AWAY_STOPPED_MAX_SPEED_MPS",
    "Decisions",
    "UnstructuredResponse",
    "decide",
    "inside_heading_range",
    "normalize_angle",
]

#: Both below this speed: DriveAway (ad-rss ``c_drive_away_stopped_max_speed``).
DRIVE_AWAY_STOPPED_MAX_SPEED_MPS = 0.1
#: ad-physics ``Angle`` precision [rad].
ANGLE_PRECISION = 1e-3


class UnstructuredResponse(enum.IntEnum):
    """ad-rss ``UnstructuredConstellationResponse`` (ordered by severity)."""

    None_ = 0
    ContinueForward = 1
    DriveAway = 2
    Brake = 3

    def __str__(self) -> str:
        """The ad-rss spelling."""
        return "None" if self is UnstructuredResponse.None_ else self.name


def normalize_angle(angle_rad: Real) -> FloatArray:
    """Angle wrapped to (-π, π] (ad-physics ``normalizeAngleSigned``)."""
    wrapped = np.mod(np.asarray(angle_rad) + np.pi, 2.0 * np.pi) - np.pi
    return np.where(wrapped <= -np.pi, wrapped + 2.0 * np.pi, wrapped)


def inside_heading_range(angle: Real, begin: Real, end: Real) -> BoolArray:
    """ad-rss ``isInsideHeadingRange`` with tolerant angle comparisons (ranges may wrap)."""
    ge_begin = ~(np.less(angle, begin) & ~eq(angle, begin, ANGLE_PRECISION))
    le_end = ~(np.greater(angle, end) & ~eq(angle, end, ANGLE_PRECISION))
    ordered = ~(np.less(end, begin) & ~eq(end, begin, ANGLE_PRECISION))
    return np.asarray(np.where(ordered, ge_begin & le_end, ge_begin | le_end))


@dataclass(frozen=True)
class Decisions:
    """Per-agent decisions (every field ``(N,)``).

    Attributes:
        is_safe: The unstructured state is safe (not dangerous).
        response: :class:`UnstructuredResponse` codes.
        heading_begin_rad: Allowed heading range begin (NaN unless DriveAway).
        heading_end_rad: Range end.
        ego_must_brake: Condition 22.1a.
        other_must_brake: Condition 22.1b.
        both_brake_safe: Condition 22.2.
    """

    is_safe: BoolArray
    response: IntArray
    heading_begin_rad: Real
    heading_end_rad: FloatArray
    ego_must_brake: BoolArray
    other_must_brake: BoolArray
    both_brake_safe: BoolArray


#: Response codes as plain ints (numpy looks attributes up on an enum class: slow per call).
_BRAKE = int(UnstructuredResponse.Brake)
_CONTINUE = int(UnstructuredResponse.ContinueForward)
_DRIVE_AWAY = int(UnstructuredResponse.DriveAway)


def decide(  # noqa: PLR0917  (one engine step over arrays)
    ego_b_oth_f: BoolArray,
    oth_b_ego_f: BoolArray,
    ego_b_oth_b: BoolArray,
    ego: UnstructuredAgents,
    agents: UnstructuredAgents,
    drive_away_max_angle_rad: float,
    memory: UnstructuredMemory,
) -> tuple[Decisions, UnstructuredMemory]:
    """Decisions of ``N`` ego/agent pairs from their set intersections.

    Args:
        ego_b_oth_f: ``(N,)`` T_ego,b intersects T_oth,f.
        oth_b_ego_f: ``(N,)`` T_oth,b intersects T_ego,f.
        ego_b_oth_b: ``(N,)`` T_ego,b intersects T_oth,b.
        ego: The ego (one row).
        agents: The other agents ``(N,)``.
        drive_away_max_angle_rad: Half width of drive-away ranges (ego dynamics).
        memory: Memory of the previous step.

    Returns:
        The decisions and the memory after this step.
    """
    ego_brake = ~ego_b_oth_f & oth_b_ego_f
    other_brake = ~oth_b_ego_f & ego_b_oth_f
    both = ~ego_b_oth_b
    safe = ego_brake | other_brake | both
    found, stored = memory.lookup_must_brake(agents.object_id)
    last = stored & found & ~safe
    stopped = DRIVE_AWAY_STOPPED_MAX_SPEED_MPS
    ego_stopped = bool(le(ego.speed_max_mps[0], stopped, SPEED_PRECISION))
    both_stopped = ego_stopped & le(agents.speed_max_mps, stopped, SPEED_PRECISION)
    rule2 = ~safe & ~both_stopped & last
    response = np.full(safe.shape, _BRAKE, dtype=np.int64)
    response[safe | (rule2 & gt(ego.speed_max_mps[0], stopped, SPEED_PRECISION))] = _CONTINUE
    response[~safe & (both_stopped | (rule2 & ego_stopped))] = _DRIVE_AWAY
    is_safe = response == _CONTINUE
    drive = response == _DRIVE_AWAY
    begin, end = np.full(safe.shape, np.nan), np.full(safe.shape, np.nan)
    if drive.any():
        phi = np.arctan2(ego.y_m[0] - agents.y_m, ego.x_m[0] - agents.x_m)
        begin = np.where(drive, normalize_angle(phi - drive_away_max_angle_rad), np.nan)
        end = np.where(drive, normalize_angle(phi + drive_away_max_angle_rad), np.nan)
    # drive-away persistence
    has, slot = memory.lookup_drive_away(agents.object_id)
    pos_x, pos_y = agents.x_m, agents.y_m
    if has.any():
        steering = normalize_angle(ego.yaw_rad[0] + ego.steering_angle_rad[0])
        s_begin, s_end = memory.heading_begin_rad[slot], memory.heading_end_rad[slot]
        unmoved = eq(agents.x_m, memory.other_x_m[slot], DISTANCE_PRECISION) & eq(
            agents.y_m, memory.other_y_m[slot], DISTANCE_PRECISION
        )
        keep = has & ~drive & ~is_safe & unmoved & inside_heading_range(steering, s_begin, s_end)
        response[keep] = _DRIVE_AWAY
        begin, end = np.where(keep, s_begin, begin), np.where(keep, s_end, end)
        drive = drive | keep
        pos_x = np.where(keep, memory.other_x_m[slot], pos_x)
        pos_y = np.where(keep, memory.other_y_m[slot], pos_y)
    remembered = safe | found
    new_value = np.where(safe, other_brake, stored)
    stored_drive = (
        [values[drive] for values in (agents.object_id, begin, end, pos_x, pos_y)]
        if drive.any()
        else [np.empty(0, dtype=np.int64), *(np.empty(0) for _ in range(4))]
    )
    memory_out = UnstructuredMemory.of_fresh(  # fresh arrays of masks, frozen there
        agents.object_id[remembered], new_value[remembered], *stored_drive
    )
    decisions = Decisions(is_safe, response, begin, end, ego_brake, other_brake, both)
    return decisions, memory_out
