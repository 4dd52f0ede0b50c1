"""Outlines of many polygons as one padded strip array per chunk (pure: no Rerun import).

Shared by the engine layouts: rings are simplified by ``SIMPLIFY_M`` and padded to one vertex
count per chunk so each entity is one ``(S, V, 3)`` array (see ``layout.pad_polylines``).
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np
import shapely

from workbench.replay.layout import pad_polylines

if TYPE_CHECKING:
    from collections.abc import Sequence

    from numpy.typing import NDArray

__all__ = [
    "SIMPLIFY_M",
    "Z_STRIPS_M",
    "StripColumns",
    "polygon_rings",
    "stack_strips",
    "time_colors",
]

#: Outline simplification tolerance for display (the verdicts use the exact sets).
SIMPLIFY_M = 0.2
#: Outlines are drawn above the road and under the boxes.
Z_STRIPS_M = 0.05


@dataclass(frozen=True, slots=True)
class StripColumns:
    """Outlines of a chunk: ``strips (S, V, 3)``, ``counts (N,)`` per frame, ``colors (S,)``."""

    strips: NDArray[np.float32]
    counts: NDArray[np.int64]
    colors: NDArray[np.uint32]


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
        strips=pad_polylines(rings, z_m=Z_STRIPS_M),
        counts=np.array([len(frame_rings) for frame_rings, _ in per_frame], dtype=np.int64),
        colors=np.concatenate(colors).astype(np.uint32) if colors else np.zeros(0, np.uint32),
    )
