"""Conformance cases of kind ``unstructured`` (``conformance/rss-cases-format.md``).

A case holds ``ego`` and ``other`` in the ENU frame (``x``, ``y``, ``yaw``, ``speed`` or
``speed_min``/``speed_max``, ``yaw_rate``, ``steering_angle``, ``length``, ``width``,
``object_type``); dynamics as for structured cases (ego: ``defaults.ego``, other: vehicle
or pedestrian defaults by type, plus ``ego_dynamics`` / ``other_dynamics`` overrides).
"""

from __future__ import annotations

import dataclasses
from typing import TYPE_CHECKING, Any

import numpy as np

from rss.conformance.cases import EGO_ID, OTHER_ID, case_number, other_dynamics_for
from rss.errors import RssCaseError, RssError
from rss.model import ObjectType
from rss.params import RssParams
from rss.physics import ACCELERATION_LOWEST_MPS2
from rss.unstructured.agents import UnstructuredAgents
from rss.unstructured.decision import UnstructuredResponse
from rss.unstructured.engine import FrameInputs, check_unstructured, evaluate_frames

if TYPE_CHECKING:
    from collections.abc import Callable, Mapping, Sequence

    from rss.conformance.cases import CaseDefaults
    from rss.dynamics import RssDynamics
    from rss.unstructured.engine import UnstructuredResult
    from rss.unstructured.memory import UnstructuredMemory

    Number = Callable[[float], float | None]

__all__ = [
    "FIRST_BATCHED_ID",
    "parse_unstructured_case",
    "unstructured_record",
    "unstructured_records",
]

#: Renumbered object ids of batched cases (never the ego's :data:`EGO_ID`).
FIRST_BATCHED_ID = OTHER_ID + 1


def _row(case_id: str, obj: object, object_id: int, default_type: str) -> dict[str, float]:
    if not isinstance(obj, dict):
        raise RssCaseError(case_id, "'ego' and 'other' must be objects")
    name = obj.get("object_type", default_type)
    try:
        object_type = ObjectType[name]
    except KeyError as err:
        raise RssCaseError(case_id, f"unknown object_type {name!r}") from err
    speed = obj.get("speed")
    low = case_number(case_id, obj, "speed_min", speed)
    high = case_number(case_id, obj, "speed_max", speed)
    return {
        "object_id": object_id,
        "object_type": int(object_type),
        "x_m": case_number(case_id, obj, "x"),
        "y_m": case_number(case_id, obj, "y"),
        "yaw_rad": case_number(case_id, obj, "yaw", 0.0),
        "speed_min_mps": low,
        "speed_max_mps": high,
        "yaw_rate_radps": case_number(case_id, obj, "yaw_rate", 0.0),
        "steering_angle_rad": case_number(case_id, obj, "steering_angle", 0.0),
        "length_m": case_number(case_id, obj, "length"),
        "width_m": case_number(case_id, obj, "width"),
    }


def _overridden(dynamics: RssDynamics, case: Mapping[str, Any], key: str) -> RssDynamics:
    """``dynamics`` with the case's ``key`` overrides (the same dynamics without the key)."""
    if key not in case:
        return dynamics
    return dynamics.with_overrides(case[key], f"{key}.")


def parse_unstructured_case(
    case: Mapping[str, Any], defaults: CaseDefaults, case_id: str
) -> tuple[UnstructuredAgents, UnstructuredAgents, RssDynamics, RssDynamics]:
    """``(ego, other, ego dynamics, other dynamics)`` of one case.

    Raises:
        RssCaseError: Missing or malformed values.
    """
    ego = UnstructuredAgents.from_rows([_row(case_id, case.get("ego"), EGO_ID, "EgoVehicle")])
    other = UnstructuredAgents.from_rows(
        [_row(case_id, case.get("other"), OTHER_ID, "OtherVehicle")]
    )
    try:
        ego_dyn = _overridden(defaults.ego, case, "ego_dynamics")
        other_type = ObjectType(int(other.object_type[0]))
        other_dyn = _overridden(other_dynamics_for(defaults, other_type), case, "other_dynamics")
    except RssError as err:
        raise RssCaseError(case_id, str(err)) from err
    return ego, other, ego_dyn, other_dyn


def _states(
    result: UnstructuredResult, number: Number, ids: Mapping[int, int]
) -> list[dict[str, Any]]:
    dec, states = result.decisions, []
    for i, object_id in enumerate(result.object_id):
        drive = dec.response[i] == UnstructuredResponse.DriveAway
        heading = (
            [number(dec.heading_begin_rad[i]), number(dec.heading_end_rad[i])] if drive else None
        )
        states.append(
            {
                "object_id": ids.get(int(object_id), int(object_id)),
                "constellation_type": "Unstructured",
                "is_dangerous": not bool(dec.is_safe[i]),
                "invalid": None if result.valid[i] else "InvalidInput",
                "longitudinal": None,
                "lateral_left": None,
                "lateral_right": None,
                "unstructured": {
                    "is_safe": bool(dec.is_safe[i]),
                    "response": str(UnstructuredResponse(int(dec.response[i]))),
                    "heading_range": heading,
                },
            }
        )
    return states


def unstructured_record(
    case: Mapping[str, Any],
    defaults: CaseDefaults,
    case_id: str,
    memory: UnstructuredMemory | None,
    number: Number,
) -> tuple[dict[str, Any], UnstructuredMemory]:
    """Record keys (``ok``, ``states``, ``proper_response``) of one case or sequence step.

    Args:
        case: The case's JSON object.
        defaults: File-level defaults.
        case_id: Id for error messages.
        memory: Memory of the previous sequence step (``None`` = fresh).
        number: JSON number formatter (``rss.conformance.json_number``).

    Raises:
        RssCaseError: A malformed case.
    """
    ego, other, ego_dyn, other_dyn = parse_unstructured_case(case, defaults, case_id)
    result, memory_out = check_unstructured(ego, other, ego_dyn, [other_dyn], defaults.ego, memory)
    return _record(result, number, {}), memory_out


def unstructured_records(
    cases: Sequence[tuple[Mapping[str, Any], str]], defaults: CaseDefaults, number: Number
) -> list[dict[str, Any] | None]:
    """Record keys of independent cases from one batched engine call (``evaluate_frames``).

    Each case is one frame, its other object renumbered (:data:`FIRST_BATCHED_ID` on, the
    records keep :data:`OTHER_ID`) so that no memory entry meets another case's: every
    case is evaluated as with a fresh memory, as :func:`unstructured_record` does alone.

    Args:
        cases: ``(case, case id)`` of each case.
        defaults: File-level defaults.
        number: JSON number formatter.

    Returns:
        Per case its record keys, or ``None`` for a malformed case (the per-case path
        reports its error).
    """
    frames, where = [], []
    for k, (case, case_id) in enumerate(cases):
        try:
            ego, other, ego_dyn, other_dyn = parse_unstructured_case(case, defaults, case_id)
        except RssError:
            continue
        other = dataclasses.replace(other, object_id=np.array([FIRST_BATCHED_ID + k]))
        frames.append(FrameInputs(ego, other, [other_dyn], ego_dyn, defaults.ego))
        where.append(k)
    results, _ = evaluate_frames(frames, RssParams()) if frames else ([], None)
    out: list[dict[str, Any] | None] = [None] * len(cases)
    for k, result in zip(where, results, strict=True):
        out[k] = _record(result, number, {FIRST_BATCHED_ID + k: OTHER_ID})
    return out


def _record(result: UnstructuredResult, number: Number, ids: Mapping[int, int]) -> dict[str, Any]:
    """The record keys of one result (``ids``: renumbered object ids -> the case's ids)."""
    pr = result.proper_response
    record: dict[str, Any] = {
        "ok": result.ok,
        "constellation_type": "Unstructured",
        "states": _states(result, number, ids),
        "proper_response": {
            "is_safe": pr.is_safe,
            "dangerous_objects": [ids.get(i, i) for i in pr.dangerous_objects],
            "longitudinal_response": "None",
            "lateral_response_left": "None",
            "lateral_response_right": "None",
            "unstructured_constellation_response": str(pr.response),
            "heading_ranges": [[number(b), number(e)] for b, e in pr.heading_ranges],
            "acceleration_restrictions": {
                "longitudinal": [number(pr.lon_min_mps2), number(pr.lon_max_mps2)],
                "lateral_left": [number(ACCELERATION_LOWEST_MPS2), number(pr.lat_max_mps2)],
                "lateral_right": [number(ACCELERATION_LOWEST_MPS2), number(pr.lat_max_mps2)],
            },
        },
    }
    if not result.ok:
        record["error"] = (
            "invalid input: an unstructured object is out of range or has no trajectory model"
        )
    return record
