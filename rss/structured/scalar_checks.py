"""Scalar twin of the structured checks (:mod:`rss.structured.checks`), one constellation.

Longitudinal (same / opposite direction), lateral and intersection checks of one valid
constellation, with the values and codes :func:`rss.structured.checks.check_all` puts in
its row. Dynamics are lists of the ten :class:`rss.structured.batch.DynamicsArrays` fields
in their order; speeds are ``[lon min, lon max, lat min, lat max]`` [m/s].
"""

from __future__ import annotations

from typing import Final

from rss.physics import DISTANCE_MAX_M, DISTANCE_PRECISION, DURATION_MAX_S, DURATION_PRECISION
from rss.structured.codes import (
    AT_LEFT,
    AT_RIGHT,
    BRAKE_MIN,
    BRAKE_MIN_CORRECT,
    E_I_EGO_FRONT,
    E_I_EGO_STOPS,
    E_I_OTHER_FRONT,
    E_I_OTHER_STOPS,
    E_I_OVERLAP,
    E_LAT,
    E_OD,
    E_OD_CORRECT,
    E_SD_EGO_FRONT,
    E_SD_OTHER_FRONT,
    EGO_PRIORITY,
    I_ABLE_TO_BRAKE,
    I_NO_TIME_OVERLAP,
    I_NONE,
    I_SAFE_DISTANCE,
    IN_FRONT,
    NOT_RELEVANT,
    OBJECT_PRIORITY,
    OPPOSITE_DIRECTION,
    OVERLAP_FRONT,
    OVERLAP_LEFT,
    OVERLAP_RIGHT,
)
from rss.structured.scalar_physics import (
    gt,
    lt,
    safe_lateral,
    safe_longitudinal_opposite,
    safe_longitudinal_same,
    stated_braking_longitudinal,
    time_to_cover_distance,
)

__all__ = ["LateralRow", "check_row"]

_DISTANCE_MAX_M: Final = DISTANCE_MAX_M
_DURATION_MAX_S: Final = DURATION_MAX_S

_P: Final = DISTANCE_PRECISION
_DP: Final = DURATION_PRECISION

#: One lateral side: ``(is_safe, response, evaluator, current distance, safe distance)``.
LateralRow = tuple[bool, int, int, float, float]


def _lateral_side(  # noqa: PLR0917 - ``checks._lateral.side`` of one row
    evaluated: bool,  # noqa: FBT001
    overlap: bool,  # noqa: FBT001
    gap_safe: bool,  # noqa: FBT001
    overlap_safe: bool,  # noqa: FBT001
    lat_distance_m: float,
    safe_m: float,
) -> LateralRow:
    if evaluated:
        return gap_safe, 0 if gap_safe else 1, E_LAT, lat_distance_m, safe_m
    if overlap:
        return overlap_safe, 0 if overlap_safe else 1, E_LAT, 0.0, 0.0
    return True, 0, 0, _DISTANCE_MAX_M, _DISTANCE_MAX_M


def _intersection(  # noqa: PLR0917 - ``intersection_checks._intersection_rows``, one row
    ctype: int,
    lon_position: int,
    lon_distance_m: float,
    enter_leave_m: tuple[float, float, float, float],
    ego: list[float],
    other: list[float],
    ego_d: list[float],
    oth_d: list[float],
) -> tuple[bool, int, float, float, int]:
    """``(safe, evaluator, current distance, safe distance, IntersectionState)``."""
    ego_enter, ego_leave, other_enter, other_leave = enter_leave_m
    ego_stop = (
        stated_braking_longitudinal(ego[1], ego_d[8], ego_d[7], ego_d[0], ego_d[2]) + ego_d[9]
    )
    other_stop = (
        stated_braking_longitudinal(other[1], oth_d[8], oth_d[7], oth_d[0], oth_d[2]) + oth_d[9]
    )
    if ctype != EGO_PRIORITY and lt(ego_stop, ego_enter, _P):
        return True, E_I_EGO_STOPS, ego_enter, ego_stop, I_ABLE_TO_BRAKE
    if ctype != OBJECT_PRIORITY and lt(other_stop, other_enter, _P):
        return True, E_I_OTHER_STOPS, other_enter, other_stop, I_ABLE_TO_BRAKE
    if lon_position == IN_FRONT:
        front_dist = safe_longitudinal_same(oth_d, other[1], ego_d, ego[0])
    else:
        front_dist = safe_longitudinal_same(ego_d, ego[1], oth_d, other[0])
    if gt(lon_distance_m, front_dist, _P):
        evaluator = E_I_EGO_FRONT if lon_position == IN_FRONT else E_I_OTHER_FRONT
        return True, evaluator, lon_distance_m, front_dist, I_SAFE_DISTANCE
    cap = ego_d[8]  # ad-rss uses the ego's cap for both vehicles
    reach_ego = time_to_cover_distance(ego[1], cap, ego_d[7], ego_d[0], ego_d[2], ego_enter)
    leave_ego = time_to_cover_distance(ego[0], cap, ego_d[7], ego_d[1], ego_d[1], ego_leave)
    reach_oth = time_to_cover_distance(other[1], cap, oth_d[7], oth_d[0], oth_d[2], other_enter)
    leave_oth = time_to_cover_distance(other[0], cap, oth_d[7], oth_d[1], oth_d[1], other_leave)
    never = abs(reach_ego - _DURATION_MAX_S) < _DP and abs(reach_oth - _DURATION_MAX_S) < _DP
    if gt(reach_ego, leave_oth, _DP) or gt(reach_oth, leave_ego, _DP) or never:
        return True, E_I_OVERLAP, 0.0, 0.0, I_NO_TIME_OVERLAP
    return False, E_I_OVERLAP, 0.0, 0.0, I_NONE


def _longitudinal(  # noqa: PLR0917 - ``checks._longitudinal``, one row
    ctype: int,
    lon_position: int,
    ego_in_correct_lane: bool,  # noqa: FBT001
    ego: list[float],
    other: list[float],
    ego_d: list[float],
    oth_d: list[float],
) -> tuple[int, float]:
    """``(evaluator, safe distance)`` of a non-intersection constellation."""
    if ctype == OPPOSITE_DIRECTION:
        if ego_in_correct_lane:
            return E_OD_CORRECT, safe_longitudinal_opposite(ego_d, ego[1], oth_d, other[1])
        return E_OD, safe_longitudinal_opposite(oth_d, other[1], ego_d, ego[1])
    if lon_position <= OVERLAP_FRONT:  # the ego leads: InFront, OverlapFront
        return E_SD_EGO_FRONT, safe_longitudinal_same(oth_d, other[1], ego_d, ego[0])
    return E_SD_OTHER_FRONT, safe_longitudinal_same(ego_d, ego[1], oth_d, other[0])


def check_row(  # noqa: PLR0917 - one row of the batch's and the extraction's columns
    ctype: int,
    relative: tuple[int, float, int, float, bool],
    enter_leave_m: tuple[float, float, float, float],
    ego: list[float],
    other: list[float],
    ego_d: list[float],
    oth_d: list[float],
) -> tuple[bool, int, int, float, float, LateralRow, LateralRow, int]:
    """All checks of one valid constellation (one row of :func:`checks.check_all`).

    Args:
        ctype: :class:`ConstellationType` code (0..5).
        relative: ``(lon position, lon distance, lat position, lat distance, ego in
            correct lane)`` after extraction.
        enter_leave_m: Distances to enter / leave the intersection (ego, then other).
        ego: The ego's speeds.
        other: The other's speeds.
        ego_d: The ego's dynamics.
        oth_d: The other's dynamics.

    Returns:
        ``(lon safe, lon response, lon evaluator, lon current, lon safe distance, left,
        right, intersection state)``.
    """
    lon_position, lon_distance_m, lat_position, lat_distance_m, ego_correct = relative
    far = _DISTANCE_MAX_M
    if ctype == NOT_RELEVANT:
        calm: LateralRow = (True, 0, 0, far, far)
        return True, 0, 0, far, far, calm, calm, 0
    if ctype >= EGO_PRIORITY:
        safe, evaluator, current, safe_dist, state = _intersection(
            ctype, lon_position, lon_distance_m, enter_leave_m, ego, other, ego_d, oth_d
        )
        blocked: LateralRow = (False, 0, E_LAT, 0.0, 0.0)
        response = 0 if safe else BRAKE_MIN
        return safe, response, evaluator, current, safe_dist, blocked, blocked, state if safe else 0
    evaluator, safe_dist = _longitudinal(ctype, lon_position, ego_correct, ego, other, ego_d, oth_d)
    lon_safe = gt(lon_distance_m, safe_dist, _P)
    if lon_safe:
        response = 0
    elif ctype == OPPOSITE_DIRECTION:
        response = BRAKE_MIN_CORRECT if ego_correct else BRAKE_MIN
    else:
        response = 0 if lon_position <= OVERLAP_FRONT else BRAKE_MIN
    ego_left, ego_right = lat_position == AT_LEFT, lat_position == AT_RIGHT
    if ego_left:
        lat_safe_m = safe_lateral(ego_d, ego[3], oth_d, other[2])
    else:
        lat_safe_m = safe_lateral(oth_d, other[3], ego_d, ego[2])
    gap_safe = gt(lat_distance_m, lat_safe_m, _P)
    overlap = not (ego_left or ego_right)
    left = _lateral_side(
        ego_right, overlap, gap_safe, lat_position == OVERLAP_LEFT, lat_distance_m, lat_safe_m
    )
    right = _lateral_side(
        ego_left,
        overlap,
        gap_safe,
        lat_position == OVERLAP_RIGHT,
        lat_distance_m,
        lat_safe_m,
    )
    return lon_safe, response, evaluator, lon_distance_m, safe_dist, left, right, 0
