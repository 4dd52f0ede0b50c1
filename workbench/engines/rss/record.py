"""The ``rss`` part of the pinned per-frame JSON line (``evaluate --per-frame``), from a verdict.

Keys, in order: ``is_safe``, ``dangerous_objects`` (actor ids, sorted),
``longitudinal_response``, ``lateral_response_left``, ``lateral_response_right`` (ad-rss
response names), ``acceleration_restrictions`` (``{"longitudinal" | "lateral_left" |
"lateral_right": [min, max]}`` in m/s², ``null`` bounds for unbounded values; ``null``
without constellations), ``constellations``, ``invalid_objects``, ``profile`` (the RSS
parameter profile, ``NAME`` or ``NAME+file``), ``responsibility`` (``{object id: "ego" |
"object" | "both"}``: who must act, RSS being symmetric, for every object dangerous from
the ego's or its own side; docs/rss.md), ``severity`` (``{object id: {"distance_ratio",
"ttc_s", "required_decel_mps2"}}``, ``null`` for infinite values), ``compliance``
(``{object id: [{"party", "since_t_ns", "due_t_ns", "required_max_mps2",
"measured_mps2", "shortfall_mps2"}, ...]}``: each party that must act, its proper
response's longitudinal restriction, its measured acceleration and, once due, the
shortfall); ``rejected_constellations``
(``{object id: reason}`` of malformed constellations left out of the frame) only when there
are any.
"""

from __future__ import annotations

from typing import TYPE_CHECKING, Any

from rss.conformance import json_number
from rss.structured.states import LateralResponse, LongitudinalResponse

if TYPE_CHECKING:
    from workbench.engines.rss.verdict import RssVerdict

__all__ = ["rss_record"]


def rss_record(verdict: RssVerdict) -> dict[str, Any]:
    """The JSON-ready record of one frame."""
    record = _record(verdict)
    record["responsibility"] = {k: str(who) for k, who in verdict.responsibility().items()}
    record["severity"] = {
        label: {
            "distance_ratio": json_number(f.distance_ratio),
            "ttc_s": json_number(f.ttc_s),
            "required_decel_mps2": json_number(f.required_decel_mps2),
        }
        for label, f in verdict.severity().items()
    }
    compliance: dict[str, list[dict[str, Any]]] = {}
    for label, duty in verdict.obligations:
        compliance.setdefault(label, []).append(
            {
                "party": str(duty.party),
                "since_t_ns": duty.since_ns,
                "due_t_ns": duty.due_ns,
                "required_max_mps2": _number(duty.required_max_mps2),
                "measured_mps2": _number(duty.measured_mps2),
                "shortfall_mps2": _number(duty.shortfall_mps2),
            }
        )
    record["compliance"] = compliance
    record["profile"] = verdict.profile
    if verdict.rejected:
        record["rejected_constellations"] = dict(verdict.rejected)
    return record


def _record(verdict: RssVerdict) -> dict[str, Any]:
    result = verdict.result
    if result is None:
        return {
            "is_safe": True,
            "dangerous_objects": [],
            "longitudinal_response": "None",
            "lateral_response_left": "None",
            "lateral_response_right": "None",
            "acceleration_restrictions": None,
            "constellations": 0,
            "invalid_objects": list(verdict.invalid_objects),
        }
    pr = result.responses
    return {
        "is_safe": bool(pr.is_safe[0]),
        "dangerous_objects": list(verdict.culprits),
        "longitudinal_response": str(LongitudinalResponse(int(pr.longitudinal_response[0]))),
        "lateral_response_left": str(LateralResponse(int(pr.lateral_response_left[0]))),
        "lateral_response_right": str(LateralResponse(int(pr.lateral_response_right[0]))),
        "acceleration_restrictions": {
            "longitudinal": [json_number(pr.lon_min_mps2[0]), json_number(pr.lon_max_mps2[0])],
            "lateral_left": [
                json_number(pr.lat_left_min_mps2[0]),
                json_number(pr.lat_left_max_mps2[0]),
            ],
            "lateral_right": [
                json_number(pr.lat_right_min_mps2[0]),
                json_number(pr.lat_right_max_mps2[0]),
            ],
        },
        "constellations": verdict.constellations,
        "invalid_objects": list(verdict.invalid_objects),
    }


def _number(value: float | None) -> float | None:
    return None if value is None else json_number(value)
