"""Intersection checks of structured RSS on ``(C,)`` arrays.

ad-rss ``RssIntersectionConstellationChecker`` without its memory (see
:mod:`rss.structured.memory`).

In ad-rss' order, the first success wins: the non-priority vehicle can stop before the
intersection, one vehicle is safely in front of the other, or their occupation times of
the intersection do not overlap.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np

from rss.model import ConstellationType
from rss.physics import (
    DISTANCE_PRECISION,
    DURATION_MAX_S,
    DURATION_PRECISION,
    eq,
    gt,
    lt,
    time_to_cover_distance,
)
from rss.structured.batch import take_rows
from rss.structured.formulas import pick, safe_longitudinal_distance_same, stated_braking
from rss.structured.states import LongitudinalPosition, RssStateEvaluator

if TYPE_CHECKING:
    from rss.arrays import BoolArray, FloatArray, IntArray
    from rss.structured.batch import ConstellationBatch, DynamicsArrays, ObjectArrays
    from rss.structured.extraction import Relative

__all__ = ["IntersectionState", "intersection_checks"]

_P = DISTANCE_PRECISION
_E = RssStateEvaluator


class IntersectionState:
    """Codes of the intersection check that last made a constellation safe."""

    NONE = 0
    NON_PRIO_ABLE_TO_BREAK = 1
    SAFE_LONGITUDINAL_DISTANCE = 2
    NO_TIME_OVERLAP = 3


def _intersection_rows(  # noqa: PLR0917  (the parts of a batch it reads)
    ctype: IntArray,
    ego: ObjectArrays,
    oth: ObjectArrays,
    ego_d: DynamicsArrays,
    oth_d: DynamicsArrays,
    rel: Relative,
) -> tuple[BoolArray, IntArray, FloatArray, FloatArray, IntArray]:
    """Intersection checks in ad-rss' order; the first success wins."""
    ego_prio = ctype == ConstellationType.IntersectionEgoHasPriority
    other_prio = ctype == ConstellationType.IntersectionObjectHasPriority

    ego_stop = (
        stated_braking(ego_d, ego.speed_lon_max_mps, ego_d.brake_min_mps2)
        + ego_d.min_longitudinal_safety_distance_m
    )
    other_stop = (
        stated_braking(oth_d, oth.speed_lon_max_mps, oth_d.brake_min_mps2)
        + oth_d.min_longitudinal_safety_distance_m
    )
    safe1 = ~ego_prio & lt(ego_stop, rel.ego_dist_to_enter_m, _P)
    try2 = ~safe1 & ~other_prio
    safe2 = try2 & lt(other_stop, rel.other_dist_to_enter_m, _P)
    able = safe1 | safe2

    ego_in_front = rel.lon_position == LongitudinalPosition.InFront
    safe_ego_front = safe_longitudinal_distance_same(
        oth_d, oth.speed_lon_max_mps, ego_d, ego.speed_lon_min_mps
    )
    safe_other_front = safe_longitudinal_distance_same(
        ego_d, ego.speed_lon_max_mps, oth_d, oth.speed_lon_min_mps
    )
    front_dist = pick(ego_in_front, safe_ego_front, safe_other_front)
    safe3 = ~able & gt(rel.lon_distance_m, front_dist, _P)

    cap = ego_d.max_speed_on_acceleration_mps  # ad-rss uses the ego's cap for both vehicles
    # the four times in one vectorised call: rows reach ego, leave ego, reach other,
    # leave other (``(4, n)``; the cap broadcasts)
    reach_ego, leave_ego, reach_oth, leave_oth = time_to_cover_distance(
        np.stack(
            [
                ego.speed_lon_max_mps,
                ego.speed_lon_min_mps,
                oth.speed_lon_max_mps,
                oth.speed_lon_min_mps,
            ]
        ),
        cap,
        np.stack(
            [
                ego_d.response_time_s,
                ego_d.response_time_s,
                oth_d.response_time_s,
                oth_d.response_time_s,
            ]
        ),
        np.stack(
            [ego_d.accel_max_mps2, ego_d.brake_max_mps2, oth_d.accel_max_mps2, oth_d.brake_max_mps2]
        ),
        np.stack(
            [ego_d.brake_min_mps2, ego_d.brake_max_mps2, oth_d.brake_min_mps2, oth_d.brake_max_mps2]
        ),
        np.stack(
            [
                rel.ego_dist_to_enter_m,
                rel.ego_dist_to_leave_m,
                rel.other_dist_to_enter_m,
                rel.other_dist_to_leave_m,
            ]
        ),
    )
    never = eq(reach_ego, DURATION_MAX_S, DURATION_PRECISION) & eq(
        reach_oth, DURATION_MAX_S, DURATION_PRECISION
    )
    no_overlap = (
        gt(reach_ego, leave_oth, DURATION_PRECISION)
        | gt(reach_oth, leave_ego, DURATION_PRECISION)
        | never
    )
    safe4 = ~able & ~safe3 & no_overlap

    overlap = ~able & ~safe3
    in_front_eval = np.where(ego_in_front, _E.IntersectionEgoInFront, _E.IntersectionOtherInFront)
    evaluator = np.select(
        [safe1, safe2, overlap],
        [
            _E.IntersectionOtherPriorityEgoAbleToStop,
            _E.IntersectionEgoPriorityOtherAbleToStop,
            _E.IntersectionOverlap,
        ],
        in_front_eval,
    ).astype(np.int64)
    current = np.select(
        [safe1, safe2, overlap],
        [rel.ego_dist_to_enter_m, rel.other_dist_to_enter_m, 0.0],
        rel.lon_distance_m,
    )
    safe_dist = np.select([safe1, safe2, overlap], [ego_stop, other_stop, 0.0], front_dist)
    state = np.select(
        [able, safe3, safe4],
        [
            IntersectionState.NON_PRIO_ABLE_TO_BREAK,
            IntersectionState.SAFE_LONGITUDINAL_DISTANCE,
            IntersectionState.NO_TIME_OVERLAP,
        ],
        IntersectionState.NONE,
    ).astype(np.int64)
    return able | safe3 | safe4, evaluator, current, safe_dist, state


def intersection_checks(
    batch: ConstellationBatch, rel: Relative, intersection: BoolArray
) -> tuple[BoolArray, IntArray, FloatArray, FloatArray, IntArray]:
    """Run the (costly) intersection checks only on intersection constellations."""
    size = batch.size
    out = (
        np.zeros(size, dtype=np.bool_),
        np.zeros(size, dtype=np.int64),
        np.zeros(size),
        np.zeros(size),
        np.zeros(size, dtype=np.int64),
    )
    rows = np.flatnonzero(intersection)
    if rows.size:
        # only the parts the checks read (not the road areas)
        checked = _intersection_rows(
            batch.constellation_type[rows],
            take_rows(batch.ego, rows),
            take_rows(batch.other, rows),
            take_rows(batch.ego_dynamics, rows),
            take_rows(batch.other_dynamics, rows),
            take_rows(rel, rows),
        )
        for target, values in zip(out, checked, strict=True):
            target[rows] = values
    return out
