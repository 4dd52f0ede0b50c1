"""A case's engine inputs built by the general adapter, the oracle of the conformance tests."""

from __future__ import annotations

import math
from typing import TYPE_CHECKING, Any

from reachsets import reach_inputs_from_arrays

if TYPE_CHECKING:
    from reachsets.inputs import ReachInputs


def direct_inputs(ego: dict[str, Any], objects: list[dict[str, Any]], **extra: Any) -> ReachInputs:
    """``reach_inputs_from_arrays`` on a case's ``ego`` and ``objects`` as they stand.

    Object ids as strings, missing object sizes NaN (the reference's defaults apply);
    ``extra``: the adapter's other keywords (track, ego size).
    """
    return reach_inputs_from_arrays(
        ego_x_m=ego["x"],
        ego_y_m=ego["y"],
        ego_yaw_rad=ego["heading"],
        ego_speed_mps=ego["speed"],
        ego_t_s=ego.get("t_s"),
        object_ids=[str(o["id"]) for o in objects],
        object_x_m=[o["x"] for o in objects],
        object_y_m=[o["y"] for o in objects],
        object_yaw_rad=[o["yaw"] for o in objects],
        object_speed_mps=[o["speed"] for o in objects],
        object_length_m=[o.get("length", math.nan) for o in objects],
        object_width_m=[o.get("width", math.nan) for o in objects],
        **extra,
    )
