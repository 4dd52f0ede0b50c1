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

from workbench.replay.short_labels import ShortLabels
from workbench.replay.strips import StripColumns, polygon_rings, stack_strips, time_colors

if TYPE_CHECKING:
    from collections.abc import Sequence

    from numpy.typing import NDArray

    from loaders.records import Frame
    from reachsets.engine import ReachResult

__all__ = ["ReachColumns", "layout_reach"]

#: Patches are drawn only this far around the set they reduced.
PATCH_MARGIN_M = 1.5


@dataclass(frozen=True, slots=True)
class ReachColumns:
    """Everything the sink sends for the reach-set engine, for ``N`` frames.

    Attributes:
        is_safe: Frame verdicts, ``(N,)``.
        sets: Reachable-set outlines, time-coloured.
        occupancy: Ego footprints along the plan, time-coloured.
        patches: Deleted regions of the rule patches.
        hit_points_m: Positions of objects whose set hits the ego, ``(H, 3)``.
        hit_labels: ``"<short label> @ <t> s"`` per hit (``#1 @ 2.8 s``: the drive's short
            label of the object), ``(H,)``.
        hit_object_ids: The full object id of each hit, ``(H,)``.
        hit_counts: Hits per frame, ``(N,)``.
        first_collision_s: Earliest collision offset per frame, NaN when safe, ``(N,)``.
    """

    is_safe: NDArray[np.bool_]
    sets: StripColumns
    occupancy: StripColumns
    patches: StripColumns
    hit_points_m: NDArray[np.float32]
    hit_labels: list[str]
    hit_object_ids: list[str]
    hit_counts: NDArray[np.int64]
    first_collision_s: NDArray[np.float64]


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


def layout_reach(
    frames: Sequence[Frame], results: Sequence[ReachResult], labels: ShortLabels | None = None
) -> ReachColumns:
    """Columnar reach-set display data for a chunk of frames and their results.

    ``labels``: the drive's short labels (objects not in it yet are numbered next); a fresh
    table by default.
    """
    short = labels if labels is not None else ShortLabels()
    t_max = max((float(r.occupancy.t_s[-1]) for r in results if len(r.occupancy.t_s)), default=1)
    hits_xy: list[tuple[float, float]] = []
    texts: list[str] = []
    ids: list[str] = []
    hit_counts = np.zeros(len(frames), dtype=np.int64)
    first = np.full(len(frames), np.nan)
    for i, (frame, result) in enumerate(zip(frames, results, strict=True)):
        rows = {str(a): k for k, a in enumerate(frame.actors.ids)}
        for hit in result.collisions:
            k = rows.get(hit.object_id)
            if k is None:
                continue
            hits_xy.append((float(frame.actors.x_m[k]), float(frame.actors.y_m[k])))
            texts.append(f"{short.label(hit.object_id)} @ {hit.t_offset_s:.1f} s")
            ids.append(hit.object_id)
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
        hit_labels=texts,
        hit_object_ids=ids,
        hit_counts=hit_counts,
        first_collision_s=first,
    )
