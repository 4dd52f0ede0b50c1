"""Reach-set results of a chunk of frames as columnar arrays (pure: no Rerun import).

Per frame the viewer shows the ego occupancy along the plan, every object's reachable set
at every step of the grid (outlines coloured by time into the plan: early = yellow, late =
purple), the rule patches that were subtracted, and a marker on each object whose set hits
the ego occupancy. Rings are simplified by ``SIMPLIFY_M`` and padded to one vertex count per
chunk so each entity is one ``(S, V, 3)`` array (see ``layout.pad_polylines``).
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

import numpy as np
import shapely

from workbench.replay.layout import pad_polylines

if TYPE_CHECKING:
    from collections.abc import Sequence

    from numpy.typing import NDArray

    from loaders.records import Frame
    from reachsets.engine import ReachResult

__all__ = [
    "SIMPLIFY_M",
    "ReachColumns",
    "StripColumns",
    "layout_reach",
    "polygon_rings",
    "stack_strips",
    "time_colors",
]

#: Outline simplification tolerance for display (the verdict uses the exact sets).
SIMPLIFY_M = 0.2
#: Patches are drawn only this far around the set they reduced.
PATCH_MARGIN_M = 1.5
#: Reach sets are drawn above the road and under the boxes.
Z_REACH_M = 0.05


@dataclass(frozen=True, slots=True)
class StripColumns:
    """Outlines of a chunk: ``strips (S, V, 3)``, ``counts (N,)`` per frame, ``colors (S,)``."""

    strips: NDArray[np.float32]
    counts: NDArray[np.int64]
    colors: NDArray[np.uint32]


@dataclass(frozen=True, slots=True)
class ReachColumns:
    """Everything the sink sends for the reach-set engine, for ``N`` frames.

    Attributes:
        is_safe: Frame verdicts, ``(N,)``.
        sets: Reachable-set outlines, time-coloured.
        occupancy: Ego footprints along the plan, time-coloured.
        patches: Deleted regions of the rule patches.
        hit_points_m: Positions of objects whose set hits the ego, ``(H, 3)``.
        hit_labels: ``"<id> @ <t> s"`` per hit, ``(H,)``.
        hit_counts: Hits per frame, ``(N,)``.
        first_collision_s: Earliest collision offset per frame, NaN when safe, ``(N,)``.
    """

    is_safe: NDArray[np.bool_]
    sets: StripColumns
    occupancy: StripColumns
    patches: StripColumns
    hit_points_m: NDArray[np.float32]
    hit_labels: list[str]
    hit_counts: NDArray[np.int64]
    first_collision_s: NDArray[np.float64]


def time_colors(t_s: NDArray[np.float64], t_max_s: float, alpha: int = 0xB0) -> NDArray[np.uint32]:
    """Packed RGBA from yellow (t = 0) to purple (t = t_max), ``(K,)``."""
    f = np.clip(t_s / max(t_max_s, 1e-9), 0.0, 1.0)
    r = np.round(255 - 120 * f).astype(np.uint32)
    g = np.round(235 * (1 - f) + 40 * f).astype(np.uint32)
    b = np.round(60 * (1 - f) + 230 * f).astype(np.uint32)
    packed = (r << 24) | (g << 16) | (b << 8) | np.uint32(alpha)
    return packed.astype(np.uint32)


def polygon_rings(
    geoms: NDArray[np.object_],
) -> tuple[list[NDArray[np.float64]], NDArray[np.int64]]:
    """Exterior rings of every polygon part (simplified); returns rings and each one's source index.

    ``None`` entries, empty parts and non-polygons are skipped.
    """
    flat = np.asarray(geoms, dtype=object).ravel()
    present = np.array([g is not None for g in flat], dtype=bool)
    if not present.any():
        return [], np.zeros(0, dtype=np.int64)
    idx = np.flatnonzero(present)
    simple = shapely.simplify(flat[idx], SIMPLIFY_M)
    parts, part_of = shapely.get_parts(simple, return_index=True)
    keep = shapely.get_type_id(parts) == shapely.GeometryType.POLYGON
    keep &= ~shapely.is_empty(parts)
    parts, part_of = parts[keep], part_of[keep]
    rings = shapely.get_exterior_ring(parts)
    coords, ring_of = shapely.get_coordinates(rings, return_index=True)
    splits = np.flatnonzero(np.diff(ring_of)) + 1
    return list(np.split(coords, splits)) if len(coords) else [], idx[part_of]


def stack_strips(
    per_frame: Sequence[tuple[list[NDArray[np.float64]], NDArray[np.uint32]]],
) -> StripColumns:
    """One ``StripColumns`` from per-frame ``(rings, colours)``, padded to one vertex count."""
    rings = [r for frame_rings, _ in per_frame for r in frame_rings]
    colors = [c for _, c in per_frame if len(c)]
    return StripColumns(
        strips=pad_polylines(rings, z_m=Z_REACH_M),
        counts=np.array([len(frame_rings) for frame_rings, _ in per_frame], dtype=np.int64),
        colors=np.concatenate(colors).astype(np.uint32) if colors else np.zeros(0, np.uint32),
    )


def _frame_sets(result: ReachResult, t_max_s: float) -> tuple[list[Any], NDArray[np.uint32]]:
    sets = np.asarray(result.reach_sets, dtype=object)
    if sets.size == 0:
        return [], np.zeros(0, dtype=np.uint32)
    rings, src = polygon_rings(sets)
    step = src % sets.shape[1]
    return rings, time_colors(result.occupancy.t_s[step], t_max_s)


def _frame_occupancy(result: ReachResult, t_max_s: float) -> tuple[list[Any], NDArray[np.uint32]]:
    rings, src = polygon_rings(result.occupancy.polygons)
    return rings, time_colors(result.occupancy.t_s[src], t_max_s, alpha=0x60)


def _frame_patches(result: ReachResult) -> tuple[list[Any], NDArray[np.uint32]]:
    """Where each patch cut its object's set: the patch within ``PATCH_MARGIN_M`` of the set.

    Patches such as "stay on the road" or "keep below the speed limit" are half-planes or the
    whole world minus the road; drawn whole, their outlines would run across the map. The band
    along the reduced set shows where the rule took effect.
    """
    sets = np.asarray(result.reach_sets, dtype=object)
    rows = {str(i): k for k, i in enumerate(result.object_ids)}
    patch_geoms, near = [], []
    for patch in result.patches:
        k = rows.get(patch.object_id)
        if k is None or patch.geometry is None or sets.size == 0:
            continue
        step = sets.shape[1] - 1 if patch.step is None else patch.step
        if sets[k, step] is None:
            continue
        patch_geoms.append(patch.geometry)
        near.append(sets[k, step])
    if not patch_geoms:
        return [], np.zeros(0, dtype=np.uint32)
    band = shapely.buffer(np.array(near, dtype=object), PATCH_MARGIN_M, quad_segs=2)
    rings, _ = polygon_rings(shapely.intersection(np.array(patch_geoms, dtype=object), band))
    return rings, np.full(len(rings), 0x26C6DAC0, dtype=np.uint32)


def layout_reach(frames: Sequence[Frame], results: Sequence[ReachResult]) -> ReachColumns:
    """Columnar reach-set display data for a chunk of frames and their results."""
    t_max = max((float(r.occupancy.t_s[-1]) for r in results if len(r.occupancy.t_s)), default=1)
    hits_xy: list[tuple[float, float]] = []
    labels: list[str] = []
    hit_counts = np.zeros(len(frames), dtype=np.int64)
    first = np.full(len(frames), np.nan)
    for i, (frame, result) in enumerate(zip(frames, results, strict=True)):
        rows = {str(a): k for k, a in enumerate(frame.actors.ids)}
        for hit in result.collisions:
            k = rows.get(hit.object_id)
            if k is None:
                continue
            hits_xy.append((float(frame.actors.x_m[k]), float(frame.actors.y_m[k])))
            labels.append(f"{hit.object_id} @ {hit.t_offset_s:.1f} s")
            hit_counts[i] += 1
        if result.collisions:
            first[i] = min(c.t_offset_s for c in result.collisions)
    points = np.zeros((len(hits_xy), 3), dtype=np.float32)
    if hits_xy:
        points[:, :2] = np.asarray(hits_xy)
        points[:, 2] = 2.5
    return ReachColumns(
        is_safe=np.array([r.is_safe for r in results], dtype=bool),
        sets=stack_strips([_frame_sets(r, t_max) for r in results]),
        occupancy=stack_strips([_frame_occupancy(r, t_max) for r in results]),
        patches=stack_strips([_frame_patches(r) for r in results]),
        hit_points_m=points,
        hit_labels=labels,
        hit_counts=hit_counts,
        first_collision_s=first,
    )
