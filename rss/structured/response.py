"""Response resolving: from per-constellation states to the ego's proper response per frame.

ad-rss ``RssResponseResolving`` (stateless in 5.0): every dangerous state makes its frame
unsafe, lists its object, escalates the responses (``None < BrakeMinCorrect < BrakeMin``)
and narrows the acceleration restrictions, starting from the default ego dynamics::

    longitudinal  [brake_max, accel_max] -> max = min(.., brake_min | brake_min_correct | accel_max)
                                            min = max(.., brake_max)
    lateral L/R   [-1000, lat_accel_max] -> max = min(.., lat_brake_min | lat_accel_max)
                                            (lat_brake_min when the response is BrakeMin)

Frames are reduced with unbuffered ufuncs (``np.minimum.at``), so ``F`` frames resolve in
one call.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np

from rss.physics import ACCELERATION_LOWEST_MPS2
from rss.structured.states import LateralResponse, LongitudinalResponse

if TYPE_CHECKING:
    from rss.arrays import BoolArray, FloatArray, IntArray
    from rss.dynamics import RssDynamics
    from rss.structured.batch import ConstellationBatch
    from rss.structured.checks import LateralSide, RawStates

__all__ = ["ProperResponses", "resolve"]


@dataclass(frozen=True)
class ProperResponses:
    """The ego's proper response for ``F`` frames (every field ``(F,)``).

    Attributes:
        is_safe: No dangerous constellation in the frame.
        longitudinal_response: Most severe :class:`LongitudinalResponse` code.
        lateral_response_left: Most severe :class:`LateralResponse` code to the left.
        lateral_response_right: Most severe code to the right.
        lon_min_mps2: Allowed longitudinal acceleration, lower bound.
        lon_max_mps2: Upper bound.
        lat_left_min_mps2: Allowed lateral acceleration to the left (lower bound, -1000 =
            unbounded).
        lat_left_max_mps2: Upper bound.
        lat_right_min_mps2: Lateral to the right, lower bound.
        lat_right_max_mps2: Upper bound.
    """

    is_safe: BoolArray
    longitudinal_response: IntArray
    lateral_response_left: IntArray
    lateral_response_right: IntArray
    lon_min_mps2: FloatArray
    lon_max_mps2: FloatArray
    lat_left_min_mps2: FloatArray
    lat_left_max_mps2: FloatArray
    lat_right_min_mps2: FloatArray
    lat_right_max_mps2: FloatArray


def _lateral(
    side: LateralSide,
    frame: IntArray,
    ego_lat_brake: FloatArray,
    ego_lat_accel: FloatArray,
    initial: FloatArray,
) -> tuple[IntArray, FloatArray]:
    response = np.zeros(initial.shape, dtype=np.int64)
    np.maximum.at(response, frame, side.response)
    limit = np.where(side.response == LateralResponse.BrakeMin, ego_lat_brake, ego_lat_accel)
    maximum = initial.copy()
    np.minimum.at(maximum, frame, limit)
    return response, maximum


def resolve(  # noqa: PLR0917  (structure-of-arrays engine step)
    batch: ConstellationBatch,
    states: RawStates,
    dangerous: BoolArray,
    frame: IntArray,
    n_frames: int,
    default_ego: RssDynamics,
) -> ProperResponses:
    """Combine the dangerous states of every frame into the ego's proper responses.

    Args:
        batch: ``C`` constellations (the ego dynamics per constellation are used).
        states: Memory-adjusted states.
        dangerous: ``(C,)`` dangerous and valid constellations.
        frame: ``(C,)`` frame number of each constellation.
        n_frames: ``F``.
        default_ego: Default ego dynamics (seed of the acceleration restrictions).

    Returns:
        The proper responses, ``(F,)`` each.
    """
    ego = batch.ego_dynamics
    rows = np.flatnonzero(dangerous)
    f = frame[rows]
    is_safe = np.ones(n_frames, dtype=np.bool_)
    is_safe[f] = False
    lon = states.lon_response[rows]
    lon_response = np.zeros(n_frames, dtype=np.int64)
    np.maximum.at(lon_response, f, lon)
    lon_limit = np.where(
        lon == int(LongitudinalResponse.BrakeMin),
        ego.brake_min_mps2[rows],
        np.where(
            lon == int(LongitudinalResponse.BrakeMinCorrect),
            ego.brake_min_correct_mps2[rows],
            ego.accel_max_mps2[rows],
        ),
    )
    lon_max = np.full(n_frames, default_ego.accel_max_mps2)
    np.minimum.at(lon_max, f, lon_limit)
    lon_min = np.full(n_frames, default_ego.brake_max_mps2)
    np.maximum.at(lon_min, f, ego.brake_max_mps2[rows])
    lat_initial = np.full(n_frames, default_ego.lat_accel_max_mps2)
    lat_brake, lat_accel = ego.lat_brake_min_mps2[rows], ego.lat_accel_max_mps2[rows]
    left, left_max = _lateral(take_side(states.left, rows), f, lat_brake, lat_accel, lat_initial)
    right, right_max = _lateral(take_side(states.right, rows), f, lat_brake, lat_accel, lat_initial)
    lowest = np.full(n_frames, ACCELERATION_LOWEST_MPS2)
    return ProperResponses(
        is_safe=is_safe,
        longitudinal_response=lon_response,
        lateral_response_left=left,
        lateral_response_right=right,
        lon_min_mps2=lon_min,
        lon_max_mps2=lon_max,
        lat_left_min_mps2=lowest,
        lat_left_max_mps2=left_max,
        lat_right_min_mps2=lowest,
        lat_right_max_mps2=right_max,
    )


def take_side(side: LateralSide, rows: IntArray) -> LateralSide:
    """The lateral states of the given constellations."""
    return type(side)(
        is_safe=side.is_safe[rows],
        response=side.response[rows],
        evaluator=side.evaluator[rows],
        current_distance_m=side.current_distance_m[rows],
        safe_distance_m=side.safe_distance_m[rows],
    )
