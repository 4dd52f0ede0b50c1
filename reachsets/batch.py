"""Consecutive frames of one drive stacked for the engine: one row per object and frame.

Frames of a run share one map. Every per-object quantity is a ``(R,)`` row array with the
frame index of each row in ``frame`` (rows sorted by frame); every per-frame quantity of the
ego is an ``(F,)`` array. A single frame is the batch ``F = 1``.
"""

from __future__ import annotations

import math
import sys
from dataclasses import dataclass, fields
from functools import cached_property
from typing import TYPE_CHECKING

import numpy as np

from reachsets.inputs import ObjectStates
from reachsets.occupancy import ego_occupancy_many
from reachsets.patches import RuleContext

if TYPE_CHECKING:
    from collections.abc import Sequence

    from numpy.typing import NDArray

    from reachsets.inputs import ReachInputs, RoadLayout, ZoneMap
    from reachsets.occupancy import EgoOccupancy
    from reachsets.params import ReachParams
    from reachsets.road import RoadGeometry
    from reachsets.track import TrackGeometry

__all__ = ["FrameBatch", "stack_frames"]


@dataclass(frozen=True)
class FrameBatch:
    """The objects to evaluate in ``F`` consecutive frames, and the ego of each frame.

    Attributes:
        objects: Objects to evaluate, ``R`` rows in frame order.
        frame: Frame of each row, ``(R,)``.
        offsets: Rows of frame ``f`` are ``offsets[f]:offsets[f + 1]``, ``(F + 1,)``.
        skipped_ids: Per frame, the objects not evaluated (behind the ego or invalid).
        s_obj_m: Row arc lengths on the track, ``(R,)`` (zeros without a track).
        lat_obj_m: Row lateral offsets from the centre line, ``(R,)`` (zeros without one).
        s_ego_m: Ego arc length per frame, ``(F,)``.
        ego_x_m: Ego centre x now, ``(F,)``.
        ego_y_m: Ego centre y now, ``(F,)``.
        ego_yaw_rad: Ego heading now, ``(F,)``.
        ego_speed_mps: Ego speed now, ``(F,)``.
        ego_length_m: Ego length, ``(F,)``.
        ego_width_m: Ego width, ``(F,)``.
        occupancy: Ego footprints, ``(F, T)``.
        params: All parameters.
        track: Track geometry, if any.
        road: Public-road layout, if any.
        zones: Roborace zones, if any.
        road_geometry: The road layout's static shapes, if any.
    """

    objects: ObjectStates
    frame: NDArray[np.intp]
    offsets: NDArray[np.intp]
    skipped_ids: tuple[tuple[str, ...], ...]
    s_obj_m: NDArray[np.float64]
    lat_obj_m: NDArray[np.float64]
    s_ego_m: NDArray[np.float64]
    ego_x_m: NDArray[np.float64]
    ego_y_m: NDArray[np.float64]
    ego_yaw_rad: NDArray[np.float64]
    ego_speed_mps: NDArray[np.float64]
    ego_length_m: NDArray[np.float64]
    ego_width_m: NDArray[np.float64]
    occupancy: EgoOccupancy
    params: ReachParams
    track: TrackGeometry | None
    road: RoadLayout | None
    zones: ZoneMap | None
    road_geometry: RoadGeometry | None = None

    @property
    def n_frames(self) -> int:
        """Number of frames ``F``."""
        return len(self.offsets) - 1

    @cached_property
    def ego_corners_m(self) -> NDArray[np.float64]:
        """The ego footprint of each row's frame, ``(R, T, 4, 2)``."""
        return self.occupancy.corners_m[self.frame]

    def context(self, f: int) -> RuleContext:
        """What the per-frame rules see at frame ``f`` (object indices local to the frame)."""
        rows = slice(int(self.offsets[f]), int(self.offsets[f + 1]))
        objs = self.objects
        return RuleContext(
            objects=ObjectStates.rows_of(
                {k.name: getattr(objs, k.name) for k in fields(objs)}, rows
            ),
            ego_x_m=float(self.ego_x_m[f]),
            ego_y_m=float(self.ego_y_m[f]),
            ego_yaw_rad=float(self.ego_yaw_rad[f]),
            ego_speed_mps=float(self.ego_speed_mps[f]),
            ego_length_m=float(self.ego_length_m[f]),
            ego_width_m=float(self.ego_width_m[f]),
            occupancy=self.occupancy.frame(f),
            times_s=self.occupancy.t_s,
            params=self.params,
            track=self.track,
            s_obj_m=self.s_obj_m[rows],
            s_ego_m=float(self.s_ego_m[f]),
            lat_obj_m=self.lat_obj_m[rows],
            road=self.road,
            zones=self.zones,
            road_geometry=self.road_geometry,
        )


def _finite(v: float) -> float:
    """``np.nan_to_num`` of one value: NaN -> 0, infinities -> the largest finite floats."""
    if math.isnan(v):
        return 0.0
    if math.isinf(v):
        return math.copysign(sys.float_info.max, v)
    return v


def stack_frames(
    inputs: Sequence[ReachInputs],
    params: ReachParams,
    track: TrackGeometry | None,
    road_geometry: RoadGeometry | None = None,
) -> FrameBatch:
    """Stack consecutive frames that share one map and select the objects to evaluate.

    On a track, an object is evaluated when its arc length lies in ``[s_ego_start,
    s_ego_end + L_ego]`` of its frame's plan (followers are responsible for the gap);
    without a track, when it is not entirely behind the ego. Rows with non-finite pose, speed
    or size are skipped.

    Args:
        inputs: The frames, in time order.
        params: Engine parameters.
        track: The frames' track geometry, if any.
        road_geometry: The static shapes of the frames' road layout, if any.

    Returns:
        The batch.
    """
    if len(inputs) == 1:
        return _stack_one(inputs[0], params, track, road_geometry)
    egos = [i.ego for i in inputs]
    occ = ego_occupancy_many(egos, params.times_array_s)
    counts = np.array([len(i.objects) for i in inputs])
    frame_all = np.repeat(np.arange(len(inputs)), counts)
    cols = {
        f.name: np.concatenate([getattr(i.objects, f.name) for i in inputs])
        for f in fields(ObjectStates)
    }
    ego_x = np.array([e.x_m[0] for e in egos])
    ego_y = np.array([e.y_m[0] for e in egos])
    ego_yaw = np.array([e.yaw_rad[0] for e in egos])
    ego_len = np.array([e.length_m for e in egos])
    x, y, length = cols["x_m"], cols["y_m"], cols["length_m"]
    valid = (
        np.isfinite(x + y + cols["yaw_rad"] + cols["speed_mps"] + length + cols["width_m"])
        & (length > 0)
        & (cols["width_m"] > 0)
    )
    n = len(x)
    if track is None:
        c, s = np.cos(ego_yaw[frame_all]), np.sin(ego_yaw[frame_all])
        xi = (x - ego_x[frame_all]) * c + (y - ego_y[frame_all]) * s
        keep = valid & (xi >= -(ego_len[frame_all] + length) / 2)
        s_obj = lat = np.zeros(n)
        s_ego = np.zeros(len(inputs))
    else:
        ends_x = np.array([[e.x_m[0], e.x_m[-1]] for e in egos]).reshape(-1)
        ends_y = np.array([[e.y_m[0], e.y_m[-1]] for e in egos]).reshape(-1)
        px = np.where(valid, x, 0.0)
        py = np.where(valid, y, 0.0)
        s_all = track.project(np.concatenate([px, ends_x]), np.concatenate([py, ends_y]))
        s_obj = s_all[:n]
        s_ego, s_end = s_all[n::2], s_all[n + 1 :: 2]
        span = np.maximum(track.ahead_m(s_ego, s_end), 0.0)
        d = track.ahead_m(s_ego[frame_all], s_obj)
        keep = valid & (d >= 0) & (d <= span[frame_all] + ego_len[frame_all])
        lat = track.lateral_m(px, py, s_obj)
    rows = np.flatnonzero(keep)
    skipped = cols["ids"][~keep]
    cut = np.cumsum(counts) - np.cumsum(np.bincount(frame_all[keep], minlength=len(inputs)))
    parts = [skipped] if len(inputs) == 1 else np.split(skipped, cut[:-1])
    skipped_ids = tuple(tuple(str(i) for i in part) for part in parts)
    frame = frame_all[rows]
    return FrameBatch(
        objects=ObjectStates.rows_of(cols, rows),
        frame=frame,
        offsets=np.searchsorted(frame, np.arange(len(inputs) + 1)),
        skipped_ids=skipped_ids,
        s_obj_m=s_obj[rows],
        lat_obj_m=lat[rows],
        s_ego_m=s_ego,
        ego_x_m=ego_x,
        ego_y_m=ego_y,
        ego_yaw_rad=ego_yaw,
        ego_speed_mps=np.array([_finite(float(e.speed_mps[0])) for e in egos]),
        ego_length_m=ego_len,
        ego_width_m=np.array([e.width_m for e in egos]),
        occupancy=occ,
        params=params,
        track=track,
        road=inputs[0].road,
        zones=inputs[0].zones,
        road_geometry=road_geometry,
    )


def _stack_one(
    inp: ReachInputs,
    params: ReachParams,
    track: TrackGeometry | None,
    road_geometry: RoadGeometry | None,
) -> FrameBatch:
    """``stack_frames`` of one frame: the same selection and values without the stacking.

    An on-line monitor's call; the per-row arithmetic is the batched path's, elementwise,
    on arrays of the frame's rows (so the batch is bit-identical to the stacked one).
    """
    ego, objs = inp.ego, inp.objects
    occ = ego_occupancy_many([ego], params.times_array_s)
    x, y, length, width = objs.x_m, objs.y_m, objs.length_m, objs.width_m
    valid = (
        np.isfinite(x + y + objs.yaw_rad + objs.speed_mps + length + width)
        & (length > 0)
        & (width > 0)
    )
    n = len(x)
    ego_len = float(ego.length_m)
    if track is None:
        yaw = np.full(n, ego.yaw_rad[0], dtype=np.float64)
        xi = (x - ego.x_m[0]) * np.cos(yaw) + (y - ego.y_m[0]) * np.sin(yaw)
        keep = valid & (xi >= -(ego_len + length) / 2)
        s_obj = lat = np.zeros(n)
        s_ego = np.zeros(1)
    else:
        px = np.where(valid, x, 0.0)
        py = np.where(valid, y, 0.0)
        ends_x = np.array([ego.x_m[0], ego.x_m[-1]], dtype=np.float64)
        ends_y = np.array([ego.y_m[0], ego.y_m[-1]], dtype=np.float64)
        s_all = track.project(np.concatenate([px, ends_x]), np.concatenate([py, ends_y]))
        s_obj, s_ego = s_all[:n], s_all[n : n + 1]
        span = np.maximum(track.ahead_m(s_ego, s_all[n + 1 :]), 0.0)
        d = track.ahead_m(np.full(n, s_ego[0]), s_obj)
        keep = valid & (d >= 0) & (d <= span[0] + ego_len)
        lat = track.lateral_m(px, py, s_obj)
    rows = np.flatnonzero(keep)
    return FrameBatch(
        objects=objs if len(rows) == n else objs.take(rows),  # read-only arrays: shared
        frame=np.zeros(len(rows), dtype=np.intp),
        offsets=np.array([0, len(rows)], dtype=np.intp),
        skipped_ids=(tuple(str(i) for i in objs.ids[~keep]),),
        s_obj_m=s_obj[rows],
        lat_obj_m=lat[rows],
        s_ego_m=s_ego,
        ego_x_m=np.array([ego.x_m[0]], dtype=np.float64),
        ego_y_m=np.array([ego.y_m[0]], dtype=np.float64),
        ego_yaw_rad=np.array([ego.yaw_rad[0]], dtype=np.float64),
        ego_speed_mps=np.array([_finite(float(ego.speed_mps[0]))]),
        ego_length_m=np.array([ego_len]),
        ego_width_m=np.array([float(ego.width_m)]),
        occupancy=occ,
        params=params,
        track=track,
        road=inp.road,
        zones=inp.zones,
        road_geometry=road_geometry,
    )
