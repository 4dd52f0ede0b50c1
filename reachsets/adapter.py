"""Build engine inputs from plain arrays (the boundary the workbench adapts frames to)."""

from __future__ import annotations

from typing import TYPE_CHECKING, Any

import numpy as np

from reachsets.inputs import (
    REFERENCE_EGO_LENGTH_M,
    REFERENCE_EGO_WIDTH_M,
    EgoTrajectory,
    ObjectStates,
    ReachInputs,
    TrackBounds,
)

if TYPE_CHECKING:
    from collections.abc import Sequence

    from reachsets.inputs import RoadLayout, ZoneMap

__all__ = ["reach_inputs_from_arrays"]


def reach_inputs_from_arrays(
    *,
    ego_x_m: Any,
    ego_y_m: Any,
    ego_yaw_rad: Any,
    ego_speed_mps: Any,
    ego_t_s: Any = None,
    ego_length_m: float = REFERENCE_EGO_LENGTH_M,
    ego_width_m: float = REFERENCE_EGO_WIDTH_M,
    object_ids: Sequence[str] = (),
    object_x_m: Any = (),
    object_y_m: Any = (),
    object_yaw_rad: Any = (),
    object_speed_mps: Any = (),
    object_length_m: Any = None,
    object_width_m: Any = None,
    track_left_m: Any = None,
    track_right_m: Any = None,
    track: TrackBounds | None = None,
    road: RoadLayout | None = None,
    zones: ZoneMap | None = None,
) -> ReachInputs:
    """Assemble ``ReachInputs`` from ``(K,)`` ego and ``(N,)`` object arrays (ENU, SI).

    Args:
        ego_x_m: Ego plan x, ``(K,)``.
        ego_y_m: Ego plan y, ``(K,)``.
        ego_yaw_rad: Ego plan heading, ``(K,)``.
        ego_speed_mps: Ego plan speed, ``(K,)``.
        ego_t_s: Waypoint time offsets ``(K,)``; ``None`` derives them from the speeds.
        ego_length_m: Ego length.
        ego_width_m: Ego width.
        object_ids: Object ids, ``N``.
        object_x_m: Object centre x, ``(N,)``.
        object_y_m: Object centre y, ``(N,)``.
        object_yaw_rad: Object heading, ``(N,)``.
        object_speed_mps: Object speed, ``(N,)``.
        object_length_m: Object lengths ``(N,)``; missing (None or NaN) -> ego length.
        object_width_m: Object widths ``(N,)``; missing -> ego width.
        track_left_m: Left track bound ``(M, 2)``, optional.
        track_right_m: Right track bound ``(P, 2)``, optional (both or neither).
        track: Prebuilt track bounds, instead of ``track_left_m``/``track_right_m`` (shared
            by the frames of a drive, so the engine sees one map).
        road: Public-road layout, optional.
        zones: Roborace zones, optional.

    Returns:
        The engine inputs.
    """
    x = np.asarray(ego_x_m, dtype=np.float64)
    t = np.full(x.shape, np.nan) if ego_t_s is None else np.asarray(ego_t_s, dtype=np.float64)
    ego = EgoTrajectory(
        x_m=x,
        y_m=np.asarray(ego_y_m, dtype=np.float64),
        yaw_rad=np.asarray(ego_yaw_rad, dtype=np.float64),
        speed_mps=np.asarray(ego_speed_mps, dtype=np.float64),
        t_s=t,
        length_m=ego_length_m,
        width_m=ego_width_m,
    )
    n = len(object_ids)

    def size(value: Any, default: float) -> Any:
        arr = np.full(n, np.nan) if value is None else np.asarray(value, dtype=np.float64)
        return np.where(np.isfinite(arr) & (arr > 0), arr, default)

    objects = ObjectStates(
        ids=np.asarray(list(object_ids), dtype=np.str_) if n else np.zeros(0, "<U1"),
        x_m=np.asarray(object_x_m, dtype=np.float64),
        y_m=np.asarray(object_y_m, dtype=np.float64),
        yaw_rad=np.asarray(object_yaw_rad, dtype=np.float64),
        speed_mps=np.asarray(object_speed_mps, dtype=np.float64),
        length_m=size(object_length_m, ego_length_m),
        width_m=size(object_width_m, ego_width_m),
    )
    if track is None and track_left_m is not None and track_right_m is not None:
        track = TrackBounds(np.asarray(track_left_m), np.asarray(track_right_m))
    return ReachInputs(ego=ego, objects=objects, track=track, road=road, zones=zones)
