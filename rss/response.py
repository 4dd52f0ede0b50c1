"""Response resolving: from per-constellation states to one proper response of the ego.

ad-rss ``RssResponseResolving`` (stateless in 5.0): every dangerous state makes the frame
unsafe, lists its object, escalates the responses (``None < BrakeMinCorrect < BrakeMin``)
and narrows the acceleration restrictions, starting from the default ego dynamics::

    longitudinal  [brake_max, accel_max]  ->  max  = min(.., brake_min | brake_min_correct | accel_max)
                                              min  = max(.., brake_max)
    lateral L/R   [-1000, lat_accel_max]  ->  max  = min(.., lat_brake_min if BrakeMin else lat_accel_max)
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np

from rss.batch import IntArray
from rss.physics import ACCELERATION_LOWEST_MPS2
from rss.states import LateralResponse, LongitudinalResponse

if TYPE_CHECKING:
    from rss.batch import BoolArray, ConstellationBatch, FloatArray
    from rss.checks import LateralSide, RawStates
    from rss.dynamics import RssDynamics

__all__ = ["AccelerationRange", "ProperResponse", "resolve"]


@dataclass(frozen=True)
class AccelerationRange:
    """Allowed acceleration interval [m/s²]."""

    minimum_mps2: float
    maximum_mps2: float


@dataclass(frozen=True)
class ProperResponse:
    """The ego's proper response for one frame.

    Attributes:
        is_safe: No dangerous constellation.
        dangerous_objects: ``(D,)`` ids of the objects of dangerous constellations.
        longitudinal_response: Most severe longitudinal response.
        lateral_response_left: Most severe lateral response to the left.
        lateral_response_right: Most severe lateral response to the right.
        longitudinal_range: Allowed longitudinal acceleration.
        lateral_left_range: Allowed lateral acceleration to the left.
        lateral_right_range: Allowed lateral acceleration to the right.
    """

    is_safe: bool
    dangerous_objects: IntArray
    longitudinal_response: LongitudinalResponse
    lateral_response_left: LateralResponse
    lateral_response_right: LateralResponse
    longitudinal_range: AccelerationRange
    lateral_left_range: AccelerationRange
    lateral_right_range: AccelerationRange


def _lateral(side: LateralSide, dangerous: BoolArray, batch: ConstellationBatch, default_max: float) -> tuple[LateralResponse, AccelerationRange]:
    response = np.where(dangerous, side.response, LateralResponse.None_)
    limit = np.where(
        response == LateralResponse.BrakeMin,
        batch.ego_dynamics.lat_brake_min_mps2,
        batch.ego_dynamics.lat_accel_max_mps2,
    )
    maximum = float(np.min(np.where(dangerous, limit, np.inf), initial=default_max))
    return LateralResponse(int(response.max(initial=0))), AccelerationRange(ACCELERATION_LOWEST_MPS2, maximum)


def resolve(
    batch: ConstellationBatch, states: RawStates, dangerous: BoolArray, default_ego: RssDynamics
) -> ProperResponse:
    """Combine all dangerous states of a frame into the ego's proper response.

    Args:
        batch: ``C`` constellations (the ego dynamics per constellation are used).
        states: Memory-adjusted states.
        dangerous: ``(C,)`` dangerous and valid constellations.
        default_ego: Default ego dynamics (seed of the acceleration restrictions).

    Returns:
        The proper response.
    """
    ego = batch.ego_dynamics
    lon = np.where(dangerous, states.lon_response, LongitudinalResponse.None_)
    lon_limit: FloatArray = np.select(
        [lon == LongitudinalResponse.BrakeMin, lon == LongitudinalResponse.BrakeMinCorrect],
        [ego.brake_min_mps2, ego.brake_min_correct_mps2],
        ego.accel_max_mps2,
    )
    lon_max = float(np.min(np.where(dangerous, lon_limit, np.inf), initial=default_ego.accel_max_mps2))
    lon_min = float(np.max(np.where(dangerous, ego.brake_max_mps2, -np.inf), initial=default_ego.brake_max_mps2))
    left_response, left_range = _lateral(states.left, dangerous, batch, default_ego.lat_accel_max_mps2)
    right_response, right_range = _lateral(states.right, dangerous, batch, default_ego.lat_accel_max_mps2)
    return ProperResponse(
        is_safe=not bool(dangerous.any()),
        dangerous_objects=batch.other.object_id[dangerous],
        longitudinal_response=LongitudinalResponse(int(lon.max(initial=0))),
        lateral_response_left=left_response,
        lateral_response_right=right_response,
        longitudinal_range=AccelerationRange(lon_min, lon_max),
        lateral_left_range=left_range,
        lateral_right_range=right_range,
    )
