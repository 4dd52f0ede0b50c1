"""A recorded drive as a reach-set case document (``docs/reachset-cases.md``).

Every frame becomes one step of a single sequence (the rule memory carried along, as the
drive pipeline carries it); the track comes from the drive's lane map. The inputs are the
ones the drive pipeline builds (:func:`~workbench.engines.reachsets.adapter.reach_inputs_and_kind`),
written with full float precision, so ``workbench conformance reachsets`` rates every step
as ``workbench evaluate --engines reachsets`` rates the frame (with the library defaults).
"""

from __future__ import annotations

from typing import TYPE_CHECKING, Any

import numpy as np

from workbench.engines.reachsets.adapter import prepare_map, reach_inputs_and_kind
from workbench.errors import WorkbenchError

if TYPE_CHECKING:
    from loaders.drive import Drive
    from loaders.records import Frame
    from reachsets.inputs import ReachInputs

__all__ = ["LEFT_OUT", "drive_case_document"]

#: How a step's ``note`` starts when objects of the frame were left out.
LEFT_OUT = "left out (non-finite pose, speed or size)"


def _finite(values: Any) -> list[float]:
    return [float(v) for v in np.asarray(values, dtype=np.float64)]


def _step(inputs: ReachInputs, frame: Frame) -> dict[str, Any]:
    """One step: the ego trajectory, the objects (rows with non-finite values left out)."""
    ego = inputs.ego
    plan: dict[str, Any] = {
        "x": _finite(ego.x_m),
        "y": _finite(ego.y_m),
        "heading": _finite(ego.yaw_rad),
        "speed": _finite(np.nan_to_num(ego.speed_mps, nan=0.0)),
        "length": float(ego.length_m),
        "width": float(ego.width_m),
    }
    if np.all(np.isfinite(ego.t_s)):
        plan["t_s"] = _finite(ego.t_s)
    o = inputs.objects
    columns = np.stack([o.x_m, o.y_m, o.yaw_rad, o.speed_mps, o.length_m, o.width_m])
    keep = np.all(np.isfinite(columns), axis=0)
    objects = [
        {
            "id": str(o.ids[i]),
            "x": float(o.x_m[i]),
            "y": float(o.y_m[i]),
            "yaw": float(o.yaw_rad[i]),
            "speed": float(o.speed_mps[i]),
            "length": float(o.length_m[i]),
            "width": float(o.width_m[i]),
        }
        for i in np.flatnonzero(keep)
    ]
    step: dict[str, Any] = {"time_s": round(frame.t_ns / 1e9, 9), "ego": plan, "objects": objects}
    left = [str(i) for i in o.ids[~keep]]
    if left:  # named, not dropped without a word (the engine would list them as skipped)
        step["note"] = f"{LEFT_OUT}: {', '.join(left)}"
    label = frame.extras.get("labels", {}).get("safety_dyn") if frame.extras else None
    if isinstance(label, bool):
        step["expected"] = {"safe": label}
    return step


def drive_case_document(
    drive: Drive,
    *,
    name: str,
    method: str = "turn",
    trajectory: str = "planned",
    source: str | None = None,
) -> dict[str, Any]:
    """The drive as a case document: one sequence, every frame a step.

    A step's ``expected.safe`` is the log's own ``safety_dyn`` label where it has one
    (ScenarioArchitect logs). Objects with a non-finite pose, speed or size are left out
    (JSON holds no NaN; the engine would skip them anyway) and named in the step's ``note``
    (the only notes this writes).

    Args:
        drive: The opened drive (a track map: the case format holds track bounds only).
        name: The sequence's ``id``.
        method: The reach-set method the document names.
        source: The drive's file, for messages (default: ``name``).
        trajectory: The ego trajectory rated (``adapter.TRAJECTORY_MODES``; ``planned`` is the
            library's default and rates a ScenarioArchitect log's emergency trajectory).

    Returns:
        The JSON-ready document.

    Raises:
        WorkbenchError: The drive's map is a road map (not expressible as track bounds).
    """
    reach_map = prepare_map(drive.lane_map)
    if reach_map.road is not None:
        msg = (
            f"{source or name}: the drive has a road map; reach-set case files hold track"
            " bounds only"
        )
        raise WorkbenchError(msg)
    steps = [
        _step(reach_inputs_and_kind(frame, reach_map, trajectory)[0], frame)
        for frame in drive.frames()
    ]
    defaults: dict[str, Any] = {"method": method}
    if reach_map.track is not None:
        defaults["track"] = {
            "left": np.asarray(reach_map.track.left_m, dtype=np.float64).tolist(),
            "right": np.asarray(reach_map.track.right_m, dtype=np.float64).tolist(),
        }
    return {"defaults": defaults, "cases": [{"id": name, "sequence": steps}]}
