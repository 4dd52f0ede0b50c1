"""What the structured RSS runner hands to the viewer for one frame (beside its JSON record)."""

from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np
import shapely

if TYPE_CHECKING:
    from collections.abc import Sequence

    from numpy.typing import NDArray

    from rss.scene import LaneGraph
    from rss.structured.engine import FrameResult

__all__ = ["RssFrameDetail", "road_area_outlines"]

#: Lanes of one road area are merged with this tolerance (borders shared up to rounding).
_MERGE_M = 0.05


@dataclass(frozen=True, slots=True)
class RssFrameDetail:
    """The checked constellations of one frame, for drawing.

    Attributes:
        labels: Actor id (or ``road_boundary_left/right``) of the other object of each of the
            ``C`` constellations.
        constellation_type: ``(C,)`` :class:`rss.model.ConstellationType` codes.
        result: The engine's result for this one frame (``C`` constellations, ``F = 1``).
        road_areas: Outline of the road area of each constellation: ``(C,)`` entries, each
            a tuple of closed ``(K, 2)`` rings in the map frame [m] (empty tuple: not
            computed).
    """

    labels: tuple[str, ...]
    constellation_type: NDArray[np.int64]
    result: FrameResult
    road_areas: tuple[tuple[NDArray[np.float64], ...], ...] = ()


def _cut(line: NDArray[np.float64], p0: float, p1: float) -> NDArray[np.float64]:
    """The part of a polyline ``(K, 2)`` between fractions ``p0 <= p1`` of its length."""
    s = np.concatenate([[0.0], np.cumsum(np.hypot(*np.diff(line, axis=0).T))])
    a, b = p0 * s[-1], p1 * s[-1]
    ends = np.column_stack([np.interp([a, b], s, line[:, 0]), np.interp([a, b], s, line[:, 1])])
    inner = line[(s > a) & (s < b)]
    return np.vstack([ends[:1], inner, ends[1:]])


def road_area_outlines(
    graph: LaneGraph, areas: Sequence[tuple[tuple[int, float, float], ...]]
) -> tuple[tuple[NDArray[np.float64], ...], ...]:
    """Outline rings of road areas given as ``(lane, p0, p1)`` windows (``Scene.road_areas``).

    Each lane window becomes the polygon between its left and right border cut at the same
    fractions of their lengths; the lanes of one area are merged. For display only.
    """
    polygons: dict[tuple[int, float, float], shapely.Polygon] = {}
    out: list[tuple[NDArray[np.float64], ...]] = []
    for area in areas:
        for key in area:
            if key not in polygons:
                lane, p0, p1 = key
                left = _cut(graph.left_m[lane], p0, p1)
                right = _cut(graph.right_m[lane], p0, p1)
                polygons[key] = shapely.Polygon(np.vstack([left, right[::-1]]))
        if not area:
            out.append(())
            continue
        merged = shapely.union_all(
            shapely.buffer(np.array([polygons[k] for k in area], dtype=object), _MERGE_M)
        )
        parts = shapely.get_parts(merged)
        rings = shapely.get_exterior_ring(parts[shapely.get_type_id(parts) == 3])  # noqa: PLR2004
        out.append(tuple(np.asarray(shapely.get_coordinates(r)) for r in rings))
    return tuple(out)
