"""Pure layout: turn a chunk of frames and a lane map into columnar numpy batches.

Nothing here imports Rerun. The sink (``workbench.replay.sink``) sends these batches with one
``send_columns`` call per entity per chunk. Shapes use ``T`` for frames in the chunk, ``M`` for
actor rows summed over the chunk, ``P`` for frames that carry a plan, ``S`` for strips and
``V`` for the (padded) vertex count of a strip.

Rotations are quaternions in Rerun's ``(x, y, z, w)`` order; a yaw about +z gives
``(0, 0, sin(yaw / 2), cos(yaw / 2))``.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np

if TYPE_CHECKING:
    from collections.abc import Sequence

    from numpy.typing import NDArray

    from loaders.maps.model import LaneMap
    from loaders.records import Frame

__all__ = [
    "MAP_Z_M",
    "PLAN_Z_M",
    "ActorColumns",
    "ChunkLayout",
    "EgoColumns",
    "MapLayout",
    "PlanColumns",
    "layout_chunk",
    "layout_map",
    "pad_polylines",
    "yaw_to_quaternion",
]

#: Height of map lines above the ground plane, metres (keeps them under the boxes).
MAP_Z_M = 0.0
#: Height of the plan line strip, metres (just above the map so it is never hidden).
PLAN_Z_M = 0.15


def yaw_to_quaternion(yaw_rad: NDArray[np.float64]) -> NDArray[np.float32]:
    """Quaternions ``(N, 4)`` in ``(x, y, z, w)`` order for rotations about +z by ``yaw_rad``.

    Args:
        yaw_rad: Heading, ENU, counter-clockwise from +x, shape ``(N,)``.
    """
    half = np.asarray(yaw_rad, dtype=np.float64) * 0.5
    out = np.zeros((half.shape[0], 4), dtype=np.float32)
    out[:, 2] = np.sin(half)
    out[:, 3] = np.cos(half)
    return out


def pad_polylines(lines: Sequence[NDArray[np.float64]], z_m: float = 0.0) -> NDArray[np.float32]:
    """Stack ragged 2-D polylines into one ``(S, V, 3)`` array by repeating each last vertex.

    Repeating the last vertex draws nothing extra, and a single 3-D array is Rerun's fast path
    for line strips. Polylines with no vertex are dropped.

    Args:
        lines: ``S`` polylines, each ``(K_i, 2)`` or ``(K_i, 3)`` in metres.
        z_m: Height given to 2-D polylines.

    Returns:
        ``(S, V, 3)`` float32 with ``V = max K_i``; ``(0, 0, 3)`` when there is nothing to draw.
    """
    kept = [np.asarray(line, dtype=np.float64) for line in lines if len(line) > 0]
    if not kept:
        return np.zeros((0, 0, 3), dtype=np.float32)
    width = max(len(line) for line in kept)
    out = np.empty((len(kept), width, 3), dtype=np.float32)
    for i, line in enumerate(kept):
        k = len(line)
        out[i, :k, :2] = line[:, :2]
        out[i, :k, 2] = line[:, 2] if line.shape[1] > 2 else z_m  # noqa: PLR2004
        out[i, k:] = out[i, k - 1]
    return out


@dataclass(frozen=True, slots=True)
class EgoColumns:
    """Ego state per frame, all ``(T, ...)``.

    Attributes:
        centre_m: Box centre ``(T, 3)`` (pose z plus half the height).
        half_size_m: Box half sizes ``(T, 3)``.
        quaternion_xyzw: Box rotation ``(T, 4)``.
        speed_mps: Signed speed along the heading ``(T,)``.
        accel_mps2: Longitudinal acceleration ``(T,)``.
    """

    centre_m: NDArray[np.float32]
    half_size_m: NDArray[np.float32]
    quaternion_xyzw: NDArray[np.float32]
    speed_mps: NDArray[np.float64]
    accel_mps2: NDArray[np.float64]


@dataclass(frozen=True, slots=True)
class ActorColumns:
    """Valid actors of every frame, flattened; ``counts`` says how many belong to each frame.

    Attributes:
        counts: Actors per frame ``(T,)``; sums to ``M``. Zero clears the boxes at that frame.
        centre_m: Box centres ``(M, 3)``.
        half_size_m: Box half sizes ``(M, 3)``.
        quaternion_xyzw: Box rotations ``(M, 4)``.
        velocity_mps: Velocity vectors in the map frame ``(M, 3)``.
        class_ids: ``ObjectClass`` values ``(M,)``, matching the annotation context.
        labels: Object ids ``(M,)``, shown next to the boxes.
        min_distance_m: Distance from the ego centre to the nearest actor centre ``(T,)``;
            NaN where a frame has no valid actor.
    """

    counts: NDArray[np.int64]
    centre_m: NDArray[np.float32]
    half_size_m: NDArray[np.float32]
    quaternion_xyzw: NDArray[np.float32]
    velocity_mps: NDArray[np.float32]
    class_ids: NDArray[np.uint16]
    labels: NDArray[np.str_]
    min_distance_m: NDArray[np.float64]

    @property
    def ids_seen(self) -> frozenset[str]:
        """Distinct actor ids in the chunk."""
        return frozenset(self.labels.tolist())


@dataclass(frozen=True, slots=True)
class PlanColumns:
    """The plan of every frame as one line strip, padded to a common vertex count.

    Attributes:
        counts: 1 where the frame has a plan, 0 where it has none (clears the strip) ``(T,)``.
        strips_m: ``(P, V, 3)`` with ``P = counts.sum()``.
    """

    counts: NDArray[np.int64]
    strips_m: NDArray[np.float32]


@dataclass(frozen=True, slots=True)
class ChunkLayout:
    """Everything the sink sends for one chunk of consecutive frames.

    Attributes:
        frame: Frame indices ``(T,)``.
        t_ns: Frame stamps in integer nanoseconds ``(T,)``.
        ego: Ego columns.
        actors: Actor columns.
        plan: Plan columns.
    """

    frame: NDArray[np.int64]
    t_ns: NDArray[np.int64]
    ego: EgoColumns
    actors: ActorColumns
    plan: PlanColumns

    def __len__(self) -> int:
        """Number of frames in the chunk."""
        return len(self.frame)


def _layout_ego(frames: Sequence[Frame]) -> EgoColumns:
    ego = [f.ego for f in frames]
    z = np.array([e.z_m + 0.5 * e.height_m for e in ego])
    centre = np.column_stack([[e.x_m for e in ego], [e.y_m for e in ego], z])
    half = 0.5 * np.array([[e.length_m, e.width_m, e.height_m] for e in ego]).reshape(-1, 3)
    return EgoColumns(
        centre_m=centre.reshape(-1, 3).astype(np.float32),
        half_size_m=half.astype(np.float32),
        quaternion_xyzw=yaw_to_quaternion(np.array([e.yaw_rad for e in ego])),
        speed_mps=np.array([e.speed_mps for e in ego], dtype=np.float64),
        accel_mps2=np.array([e.accel_mps2 for e in ego], dtype=np.float64),
    )


def _layout_actors(frames: Sequence[Frame], ego_xy: NDArray[np.float64]) -> ActorColumns:
    tables = [f.actors for f in frames]
    masks = [t.valid for t in tables]
    counts = np.array([int(m.sum()) for m in masks], dtype=np.int64)

    def cat(name: str) -> NDArray[np.float64]:
        parts = [np.asarray(getattr(t, name))[m] for t, m in zip(tables, masks, strict=True)]
        return np.concatenate(parts) if parts else np.zeros(0)

    x, y, z = cat("x_m"), cat("y_m"), cat("z_m")
    centre = np.column_stack([x, y, z]).astype(np.float32)
    half = 0.5 * np.column_stack([cat("length_m"), cat("width_m"), cat("height_m")])
    velocity = np.column_stack([cat("vx_mps"), cat("vy_mps"), np.zeros(len(x))])
    labels = np.concatenate([t.ids[m] for t, m in zip(tables, masks, strict=True)]).astype(str)
    owner = np.repeat(np.arange(len(frames)), counts)
    dist = np.hypot(x - ego_xy[owner, 0], y - ego_xy[owner, 1])
    min_dist = np.full(len(frames), np.inf)
    np.minimum.at(min_dist, owner, dist)
    min_dist[counts == 0] = np.nan
    return ActorColumns(
        counts=counts,
        centre_m=centre.reshape(-1, 3),
        half_size_m=half.astype(np.float32).reshape(-1, 3),
        quaternion_xyzw=yaw_to_quaternion(cat("yaw_rad")),
        velocity_mps=velocity.astype(np.float32).reshape(-1, 3),
        class_ids=cat("object_class").astype(np.uint16),
        labels=labels,
        min_distance_m=min_dist,
    )


def _layout_plan(frames: Sequence[Frame]) -> PlanColumns:
    plans = [f.plan for f in frames]
    counts = np.array([0 if p is None or len(p) == 0 else 1 for p in plans], dtype=np.int64)
    lines = [np.column_stack([p.x_m, p.y_m]) for p in plans if p is not None and len(p) > 0]
    return PlanColumns(counts=counts, strips_m=pad_polylines(lines, z_m=PLAN_Z_M))


def layout_chunk(frames: Sequence[Frame]) -> ChunkLayout:
    """Columnar batches for a chunk of consecutive frames.

    Invalid actor rows (``ActorTable.valid`` false) are left out.

    Args:
        frames: ``T >= 1`` frames in time order.
    """
    ego = _layout_ego(frames)
    ego_xy = ego.centre_m[:, :2].astype(np.float64)
    return ChunkLayout(
        frame=np.array([f.index for f in frames], dtype=np.int64),
        t_ns=np.array([f.t_ns for f in frames], dtype=np.int64),
        ego=ego,
        actors=_layout_actors(frames, ego_xy),
        plan=_layout_plan(frames),
    )


@dataclass(frozen=True, slots=True)
class MapLayout:
    """Static map geometry grouped for drawing.

    Attributes:
        borders: Lane borders by line type value (``solid``, ``dashed``, ...), each ``(S, V, 3)``;
            a border shared by two neighbouring lanes appears once.
        centres: Centre lines by lane kind value (``road``, ``crosswalk``, ...), each ``(S, V, 3)``.
        boundaries: Extra road or track boundaries ``(S, V, 3)``.
    """

    borders: dict[str, NDArray[np.float32]]
    centres: dict[str, NDArray[np.float32]]
    boundaries: NDArray[np.float32]

    @property
    def is_empty(self) -> bool:
        """True when there is nothing to draw."""
        groups = [*self.borders.values(), *self.centres.values(), self.boundaries]
        return all(len(g) == 0 for g in groups)


def _polyline_key(line: NDArray[np.float64]) -> bytes:
    """Direction-independent key of a polyline, rounded to centimetres."""
    rounded = np.round(np.asarray(line, dtype=np.float64)[:, :2], 2)
    forward, backward = rounded.tobytes(), rounded[::-1].tobytes()
    return min(forward, backward)


def layout_map(lane_map: LaneMap) -> MapLayout:
    """Group a lane map's polylines for static logging.

    Args:
        lane_map: The drive's lane graph.
    """
    borders: dict[str, list[NDArray[np.float64]]] = {}
    centres: dict[str, list[NDArray[np.float64]]] = {}
    seen: set[bytes] = set()
    for lane in lane_map.lanes.values():
        for line, kind in ((lane.left_m, lane.left_line), (lane.right_m, lane.right_line)):
            if len(line) == 0:
                continue
            key = _polyline_key(line)
            if key in seen:
                continue
            seen.add(key)
            borders.setdefault(kind.value, []).append(line)
        centres.setdefault(lane.kind.value, []).append(lane.centre_m)
    return MapLayout(
        borders={k: pad_polylines(v, MAP_Z_M) for k, v in sorted(borders.items())},
        centres={k: pad_polylines(v, MAP_Z_M) for k, v in sorted(centres.items())},
        boundaries=pad_polylines(list(lane_map.boundaries_m), MAP_Z_M),
    )
