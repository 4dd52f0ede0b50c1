"""Road geometry derived once from a road layout: lane polygons, drivable area, solid lines."""

from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

import numpy as np
import shapely

if TYPE_CHECKING:
    from numpy.typing import NDArray

    from reachsets.inputs import RoadLayout

__all__ = ["RoadGeometry", "prepare_road"]


@dataclass(frozen=True, slots=True)
class RoadGeometry:
    """The static shapes of a road layout, built once per layout (``prepare_road``).

    Attributes:
        lane_polys: Lane polygons (made valid, prepared), ``(Lanes,)``.
        drivable: Union of all lanes (prepared).
        solid: Union of the solid lines, or ``None`` without any.
        lanes_by_id: Lane id -> index into ``lane_polys``.
    """

    lane_polys: NDArray[np.object_]
    drivable: Any
    solid: Any
    lanes_by_id: dict[str, int]


def prepare_road(road: RoadLayout) -> RoadGeometry:
    """Build the static shapes of ``road``."""
    lane_polys = np.array(
        [shapely.make_valid(shapely.polygons(ln.polygon_m)) for ln in road.lanes], dtype=object
    )
    drivable = shapely.union_all(lane_polys)
    solid = (
        shapely.union_all(shapely.linestrings(list(road.solid_lines_m)))
        if road.solid_lines_m
        else None
    )
    shapely.prepare(lane_polys)
    shapely.prepare(drivable)
    return RoadGeometry(
        lane_polys=lane_polys,
        drivable=drivable,
        solid=solid,
        lanes_by_id={ln.lane_id: k for k, ln in enumerate(road.lanes)},
    )
