"""Road geometry derived once from a road layout: lane polygons, drivable area, solid lines.

A lane or solid line whose geometry cannot be used (non-finite points, a lane outline of
fewer than three distinct points, a centre line or solid line of fewer than two points) is
left out and named in ``RoadGeometry.skipped``; the rest of the layout is used as given.
"""

from __future__ import annotations

import logging
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any

import numpy as np
import shapely

if TYPE_CHECKING:
    from collections.abc import Sequence

    from numpy.typing import NDArray

    from reachsets.inputs import RoadLane, RoadLayout

__all__ = ["RoadGeometry", "polylines", "prepare_road"]

_log = logging.getLogger(__name__)

_MIN_OUTLINE_POINTS = 3


@dataclass(frozen=True, slots=True)
class RoadGeometry:
    """The static shapes of a road layout, built once per layout (``prepare_road``).

    Attributes:
        lanes: The usable lanes, in layout order, ``Lanes`` of them.
        lane_polys: Their polygons (made valid, prepared), ``(Lanes,)``.
        drivable: Union of all lanes (prepared).
        solid: Union of the usable solid lines, or ``None`` without any.
        lanes_by_id: Lane id -> index into ``lanes`` and ``lane_polys``.
        skipped: The lanes and solid lines left out, as ``"lane <id>"`` and
            ``"solid line <index into RoadLayout.solid_lines_m>"``.
        cache: Shapes derived on first use (lane corridors, see ``reachsets.lanes``).
    """

    lanes: tuple[RoadLane, ...]
    lane_polys: NDArray[np.object_]
    drivable: Any
    solid: Any
    lanes_by_id: dict[str, int]
    skipped: tuple[str, ...] = ()
    cache: dict[str, Any] = field(default_factory=dict, compare=False, repr=False)


def polylines(lines: Sequence[NDArray[np.float64]]) -> NDArray[np.object_]:
    """Line strings of polylines of any lengths, ``(L,)``; each line ``(K_i, 2)``, ``K_i >= 2``.

    One shapely call over the concatenated points with an index per point: the lines may
    differ in length (``shapely.linestrings`` of a list needs a rectangular array).
    """
    counts = [len(line) for line in lines]
    coords = np.concatenate(lines) if lines else np.zeros((0, 2))
    index = np.repeat(np.arange(len(counts)), counts)
    return np.asarray(shapely.linestrings(coords, indices=index))


def _finite_line(points: NDArray[np.float64], min_points: int) -> bool:
    """Whether ``points`` ``(K, 2)`` are finite with at least ``min_points`` distinct ones."""
    return bool(
        points.ndim == 2  # noqa: PLR2004
        and points.shape[1] == 2  # noqa: PLR2004
        and np.isfinite(points).all()
        and len(np.unique(points, axis=0)) >= min_points
    )


def _usable_lane(lane: RoadLane) -> bool:
    return _finite_line(lane.polygon_m, _MIN_OUTLINE_POINTS) and _finite_line(lane.centre_m, 2)


def prepare_road(road: RoadLayout) -> RoadGeometry:
    """Build the static shapes of ``road``, leaving out unusable lanes and solid lines."""
    usable = [_usable_lane(ln) for ln in road.lanes]
    lanes = tuple(ln for ln, ok in zip(road.lanes, usable, strict=True) if ok)
    lines_ok = [_finite_line(line, 2) for line in road.solid_lines_m]
    lines = [line for line, ok in zip(road.solid_lines_m, lines_ok, strict=True) if ok]
    skipped = tuple(
        [f"lane {ln.lane_id}" for ln, ok in zip(road.lanes, usable, strict=True) if not ok]
        + [f"solid line {k}" for k, ok in enumerate(lines_ok) if not ok]
    )
    if skipped:
        _log.debug("road elements left out (unusable geometry): %s", ", ".join(skipped))
    lane_polys = np.array(
        [shapely.make_valid(shapely.polygons(ln.polygon_m)) for ln in lanes], dtype=object
    )
    drivable = shapely.union_all(lane_polys)
    solid = shapely.union_all(polylines(lines)) if lines else None
    shapely.prepare(lane_polys)
    shapely.prepare(drivable)
    return RoadGeometry(
        lanes=lanes,
        lane_polys=lane_polys,
        drivable=drivable,
        solid=solid,
        lanes_by_id={ln.lane_id: k for k, ln in enumerate(lanes)},
        skipped=skipped,
    )
