"""The ``reachsets`` part of the pinned per-frame JSON line, from a verdict.

Keys: ``is_safe``; ``trajectory`` (the ego trajectory rated: ``"emergency"``, ``"planned"``,
``"constant_speed"`` or ``"braking_from_state"``); ``collisions`` (``[{"object_id": str,
"t_offset_s": float}]``, the first collision in time per object, offsets rounded to 1 µs);
``patches`` (``"<rule>:<object>"`` of every deletion patch applied, sorted);
``skipped_objects`` (ids that could not be evaluated); ``skipped_road`` (map elements left
out as unusable, e.g. ``"lane 13"``), only when there are any.
"""

from __future__ import annotations

from typing import TYPE_CHECKING, Any

if TYPE_CHECKING:
    from workbench.engines.reachsets.verdict import ReachVerdict

__all__ = ["reach_record"]


def reach_record(verdict: ReachVerdict) -> dict[str, Any]:
    """The JSON-ready record of one frame."""
    result = verdict.result
    record: dict[str, Any] = {
        "is_safe": result.is_safe,
        "trajectory": verdict.trajectory,
        "collisions": [
            {"object_id": c.object_id, "t_offset_s": round(c.t_offset_s, 6)}
            for c in result.collisions
        ],
        "patches": sorted({f"{p.rule}:{p.object_id}" for p in result.patches}),
        "skipped_objects": list(result.skipped_ids),
    }
    if result.skipped_road:
        record["skipped_road"] = list(result.skipped_road)
    return record
