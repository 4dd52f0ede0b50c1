"""Safe-distance formulas of structured RSS on ``(C,)`` arrays (ad-rss ``RssFormulas``).

Longitudinal same / opposite direction and lateral, each with ad-physics' tolerant
``max(d, 0)``; :mod:`rss.reference` holds the scalar reference.
"""

from __future__ import annotations

import dataclasses
from typing import TYPE_CHECKING

import numpy as np

from rss.physics import (
    DISTANCE_PRECISION,
    stated_braking_lateral,
    stated_braking_longitudinal,
    stopping_distance,
    tmax,
)
from rss.structured.batch import DynamicsArrays

if TYPE_CHECKING:
    from rss.arrays import BoolArray, FloatArray

__all__ = [
    "LATERAL_FIELDS",
    "OPPOSITE_FIELDS",
    "SAME_FOLLOWER_FIELDS",
    "SAME_LEADER_FIELDS",
    "dynamics_rows",
    "pick",
    "pick_fields",
    "safe_lateral_distance",
    "safe_longitudinal_distance_opposite",
    "safe_longitudinal_distance_same",
    "stated_braking",
]

_P = DISTANCE_PRECISION
_DYNAMICS_FIELDS = tuple(f.name for f in dataclasses.fields(DynamicsArrays))


def dynamics_rows(dyn: DynamicsArrays) -> FloatArray:
    """``(D, C)``: the fields of ``dyn`` stacked in dataclass order."""
    out: FloatArray = np.array([getattr(dyn, name) for name in _DYNAMICS_FIELDS])
    return out


def pick_fields(
    mask: BoolArray, a: DynamicsArrays, b: DynamicsArrays, names: tuple[str, ...]
) -> DynamicsArrays:
    """Row-wise choice of the fields ``names`` (``a`` where ``mask``), one ``np.where`` each.

    The other fields hold ``a``'s values unpicked: only for a formula that reads ``names``
    alone (the ``*_FIELDS`` tuples below name what each formula reads of each party).
    """
    chosen = {name: np.where(mask, getattr(a, name), getattr(b, name)) for name in names}
    return DynamicsArrays(**{name: chosen.get(name, getattr(a, name)) for name in _DYNAMICS_FIELDS})


def pick(mask: BoolArray, a: FloatArray, b: FloatArray) -> FloatArray:
    """``np.where`` as float64 (``(C,)``)."""
    return np.asarray(np.where(mask, a, b), dtype=np.float64)


def stated_braking(
    dyn: DynamicsArrays, speed: FloatArray, decel: FloatArray, cap: FloatArray | None = None
) -> FloatArray:
    """Longitudinal stated braking of participants with dynamics ``dyn`` (``(C,)``, m)."""
    return stated_braking_longitudinal(
        speed,
        dyn.max_speed_on_acceleration_mps if cap is None else cap,
        dyn.response_time_s,
        dyn.accel_max_mps2,
        decel,
    )


#: The fields :func:`safe_longitudinal_distance_same` reads of the follower (of the leader).
SAME_FOLLOWER_FIELDS = (
    "max_speed_on_acceleration_mps",
    "response_time_s",
    "accel_max_mps2",
    "brake_min_mps2",
    "min_longitudinal_safety_distance_m",
)
SAME_LEADER_FIELDS = ("brake_max_mps2",)
#: The fields :func:`safe_longitudinal_distance_opposite` reads of either party.
OPPOSITE_FIELDS = (*SAME_FOLLOWER_FIELDS, "brake_min_correct_mps2")
#: The fields :func:`safe_lateral_distance` reads of either party.
LATERAL_FIELDS = (
    "response_time_s",
    "lat_accel_max_mps2",
    "lat_brake_min_mps2",
    "lateral_fluctuation_margin_m",
)


def safe_longitudinal_distance_same(
    follower: DynamicsArrays,
    follower_speed_max: FloatArray,
    leader: DynamicsArrays,
    leader_speed_min: FloatArray,
) -> FloatArray:
    """Safe distance of a follower behind a leader, same direction (``(C,)``, m)."""
    d_follower = stated_braking(follower, follower_speed_max, follower.brake_min_mps2)
    d_leader = stopping_distance(leader_speed_min, leader.brake_max_mps2)
    return tmax(d_follower - d_leader, 0.0, _P) + follower.min_longitudinal_safety_distance_m


def safe_longitudinal_distance_opposite(
    correct: DynamicsArrays,
    correct_speed_max: FloatArray,
    opposite: DynamicsArrays,
    opposite_speed_max: FloatArray,
) -> FloatArray:
    """Safe distance of two oncoming vehicles (``(C,)``, m).

    The one in its correct lane brakes with ``brake_min_correct``, the other with ``brake_min``.
    """
    d_correct = stated_braking(correct, correct_speed_max, correct.brake_min_correct_mps2)
    d_opposite = stated_braking(opposite, opposite_speed_max, opposite.brake_min_mps2)
    margin = tmax(
        correct.min_longitudinal_safety_distance_m, opposite.min_longitudinal_safety_distance_m, _P
    )
    return np.asarray(d_correct + d_opposite + margin, dtype=np.float64)


def safe_lateral_distance(
    left: DynamicsArrays,
    left_speed_max: FloatArray,
    right: DynamicsArrays,
    right_speed_min: FloatArray,
) -> FloatArray:
    """Safe lateral distance between a left and a right vehicle (``(C,)``, m).

    Lateral speeds are positive to the right; the margin is the mean of both fluctuation
    margins.
    """
    d_left = stated_braking_lateral(
        left_speed_max, left.response_time_s, left.lat_accel_max_mps2, left.lat_brake_min_mps2
    )
    d_right = stated_braking_lateral(
        right_speed_min, right.response_time_s, -right.lat_accel_max_mps2, -right.lat_brake_min_mps2
    )
    margin = 0.5 * (left.lateral_fluctuation_margin_m + right.lateral_fluctuation_margin_m)
    return tmax(d_left - d_right + margin, 0.0, _P)
