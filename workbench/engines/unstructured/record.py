"""The ``unstructured`` part of the pinned per-frame JSON line, from a verdict.

Keys (those shared with the ``rss`` record keep its names and meaning)::

    is_safe                    bool, no dangerous object
    dangerous_objects          [actor id, ...] sorted
    decisions                  {actor id: "Brake" | "ContinueForward" | "DriveAway" | "None"}
    longitudinal_response      "BrakeMin" when the resolved response is Brake, else "None"
    unstructured_constellation_response   the resolved response (ad-rss ProperResponse)
    heading_ranges             [[begin, end], ...] allowed headings while driving away [rad]
    acceleration_restrictions  {"longitudinal": [min, max], "lateral_left": ..., ...} [m/s²]
    constellations             number of unstructured pairs checked
    invalid_objects            [actor id, ...] selected rows that could not be checked

ad-rss leaves ``longitudinal_response`` "None" for unstructured constellations and restricts
the acceleration instead (max ≤ ``brake_min`` on Brake); we name that restriction BrakeMin so
the key means the same as in structured RSS.
"""

from __future__ import annotations

from typing import TYPE_CHECKING, Any

from rss.conformance import json_number
from rss.unstructured import UnstructuredResponse

if TYPE_CHECKING:
    from workbench.engines.unstructured.verdict import UnstructuredVerdict

__all__ = ["unstructured_record"]


def unstructured_record(verdict: UnstructuredVerdict) -> dict[str, Any]:
    """The JSON-ready record of one frame."""
    lat = [json_number(verdict.lat_mps2[0]), json_number(verdict.lat_mps2[1])]
    brake = verdict.response == UnstructuredResponse.Brake
    return {
        "is_safe": bool(verdict.is_safe),
        "dangerous_objects": list(verdict.culprits),
        "decisions": {actor: str(decision) for actor, decision in verdict.decisions},
        "longitudinal_response": "BrakeMin" if brake else "None",
        "unstructured_constellation_response": str(UnstructuredResponse(verdict.response)),
        "heading_ranges": [[json_number(b), json_number(e)] for b, e in verdict.heading_ranges_rad],
        "acceleration_restrictions": {
            "longitudinal": [json_number(verdict.lon_mps2[0]), json_number(verdict.lon_mps2[1])],
            "lateral_left": lat,
            "lateral_right": list(lat),
        },
        "constellations": verdict.constellations,
        "invalid_objects": list(verdict.invalid_objects),
    }
