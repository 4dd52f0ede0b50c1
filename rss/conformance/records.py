"""The per-frame records of the conformance format (``conformance/rss-cases-format.md``).

``situation``, ``states`` and ``proper_response`` of a structured frame, and the JSON
number rule shared by every record (rounded to 1e-6; "max" distances and non-finite
values become null).
"""

from __future__ import annotations

import math
from typing import TYPE_CHECKING, Any

import numpy as np

from rss.model import ConstellationType
from rss.physics import DISTANCE_MAX_M
from rss.structured.states import (
    InvalidReason,
    LateralPosition,
    LateralResponse,
    LongitudinalPosition,
    LongitudinalResponse,
    RssStateEvaluator,
)

if TYPE_CHECKING:
    from rss.structured.batch import ConstellationBatch
    from rss.structured.checks import LateralSide
    from rss.structured.engine import FrameResult

__all__ = ["frame_record", "json_number", "response_record"]


def json_number(value: float) -> float | None:
    """JSON number rounded to 1e-6; "max" distances and non-finite values become null."""
    if not math.isfinite(value) or value >= DISTANCE_MAX_M:
        return None
    return round(float(value), 6)


def _lateral(side: LateralSide, i: int) -> dict[str, Any]:
    return {
        "is_safe": bool(side.is_safe[i]),
        "response": str(LateralResponse(int(side.response[i]))),
        "evaluator": str(RssStateEvaluator(int(side.evaluator[i]))),
        "current_distance": json_number(float(side.current_distance_m[i])),
        "safe_distance": json_number(float(side.safe_distance_m[i])),
    }


def frame_record(result: FrameResult, batch: ConstellationBatch, index: int = 0) -> dict[str, Any]:
    """``situation``, ``states`` and ``proper_response`` of frame ``index`` of a result.

    Args:
        result: The engine's result.
        batch: The evaluated constellations.
        index: Frame number.

    Returns:
        The record's keys (without ``id``/``kind``/``ok``).
    """
    rel, st = result.relative, result.states
    situation, states = [], []
    constellation_types, object_ids = batch.constellation_type, batch.other.object_id
    for i in np.flatnonzero(result.frame == index):
        situation.append(
            {
                "longitudinal_position": LongitudinalPosition(int(rel.lon_position[i])).name,
                "longitudinal_distance": json_number(float(rel.lon_distance_m[i])),
                "lateral_position": LateralPosition(int(rel.lat_position[i])).name,
                "lateral_distance": json_number(float(rel.lat_distance_m[i])),
                "ego": {"is_in_correct_lane": bool(rel.ego_in_correct_lane[i])},
                "other": {"is_in_correct_lane": bool(rel.other_in_correct_lane[i])},
            }
        )
        states.append(
            {
                "object_id": int(object_ids[i]),
                "constellation_type": ConstellationType(int(constellation_types[i])).name,
                "is_dangerous": bool(result.dangerous[i]),
                "invalid": InvalidReason(int(result.invalid[i])).name
                if result.invalid[i]
                else None,
                "longitudinal": {
                    "is_safe": bool(st.lon_is_safe[i]),
                    "response": str(LongitudinalResponse(int(st.lon_response[i]))),
                    "evaluator": str(RssStateEvaluator(int(st.lon_evaluator[i]))),
                    "current_distance": json_number(float(st.lon_current_distance_m[i])),
                    "safe_distance": json_number(float(st.lon_safe_distance_m[i])),
                },
                "lateral_left": _lateral(st.left, int(i)),
                "lateral_right": _lateral(st.right, int(i)),
                "unstructured": None,
            }
        )
    proper = response_record(result, object_ids, index)
    return {"situation": situation, "states": states, "proper_response": proper}


def response_record(result: FrameResult, object_ids: np.ndarray, index: int) -> dict[str, Any]:
    """The ``proper_response`` record of frame ``index`` (``object_ids``: ``(C,)`` other ids)."""
    pr = result.responses
    dangerous = result.dangerous & (result.frame == index)
    return {
        "is_safe": bool(pr.is_safe[index]),
        "dangerous_objects": [int(x) for x in object_ids[dangerous]],
        "longitudinal_response": str(LongitudinalResponse(int(pr.longitudinal_response[index]))),
        "lateral_response_left": str(LateralResponse(int(pr.lateral_response_left[index]))),
        "lateral_response_right": str(LateralResponse(int(pr.lateral_response_right[index]))),
        "unstructured_constellation_response": "None",
        "heading_ranges": [],
        "acceleration_restrictions": {
            "longitudinal": [
                json_number(pr.lon_min_mps2[index]),
                json_number(pr.lon_max_mps2[index]),
            ],
            "lateral_left": [
                json_number(pr.lat_left_min_mps2[index]),
                json_number(pr.lat_left_max_mps2[index]),
            ],
            "lateral_right": [
                json_number(pr.lat_right_min_mps2[index]),
                json_number(pr.lat_right_max_mps2[index]),
            ],
        },
    }
