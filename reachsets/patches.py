"""Deletion patches: what a rule removes from an object's reachable set, and their subtraction."""

from __future__ import annotations

from dataclasses import dataclass
from functools import cached_property
from typing import TYPE_CHECKING, Any

import numpy as np
import shapely

from reachsets.footprints import rectangles

if TYPE_CHECKING:
    from collections.abc import Sequence

    from numpy.typing import NDArray

    from reachsets.inputs import ObjectStates, RoadLayout, ZoneMap
    from reachsets.occupancy import EgoOccupancy
    from reachsets.params import ReachParams
    from reachsets.rules_road import RoadGeometry
    from reachsets.track import TrackGeometry

__all__ = ["RuleContext", "RulePatch", "keep_largest_part", "patch_grid", "subtract_patches"]


@dataclass(frozen=True, slots=True)
class RulePatch:
    """A region a rule-conform object will not enter.

    Attributes:
        object_index: Row of the object in the context's object table.
        rule: Rule name (e.g. ``f1.alongside``).
        geometry: The region (map frame).
        step: Grid step the patch applies to; ``None`` means every step.
    """

    object_index: int
    rule: str
    geometry: Any
    step: int | None = None


@dataclass(frozen=True)
class RuleContext:
    """What every rule sees at the current frame.

    Attributes:
        objects: The objects under evaluation (N).
        ego_x_m: Ego centre x now.
        ego_y_m: Ego centre y now.
        ego_yaw_rad: Ego heading now.
        ego_speed_mps: Ego speed now.
        ego_length_m: Ego length.
        ego_width_m: Ego width.
        occupancy: Ego occupancy along the plan.
        times_s: Grid stamps ``(T,)``.
        params: All parameters.
        track: Track geometry, if any.
        s_obj_m: Object arc lengths on the track, ``(N,)`` (zeros without a track).
        s_ego_m: Ego arc length on the track (0 without a track).
        lat_obj_m: Object lateral offsets from the centre line (right positive), ``(N,)``
            (zeros without a track).
        road: Public-road layout, if any.
        zones: Roborace zones, if any.
        road_geometry: The road layout's static shapes, when already built.
    """

    objects: ObjectStates
    ego_x_m: float
    ego_y_m: float
    ego_yaw_rad: float
    ego_speed_mps: float
    ego_length_m: float
    ego_width_m: float
    occupancy: EgoOccupancy
    times_s: NDArray[np.float64]
    params: ReachParams
    track: TrackGeometry | None
    s_obj_m: NDArray[np.float64]
    s_ego_m: float
    lat_obj_m: NDArray[np.float64]
    road: RoadLayout | None
    zones: ZoneMap | None
    road_geometry: RoadGeometry | None = None

    @cached_property
    def footprints(self) -> NDArray[np.object_]:
        """The objects' current footprints, ``(N,)`` polygons (built on first use)."""
        o = self.objects
        return rectangles(o.x_m, o.y_m, o.yaw_rad, o.length_m, o.width_m).reshape(len(o))


def patch_grid(
    patches: Sequence[RulePatch],
    footprints: NDArray[np.object_],
    n_steps: int,
    cells: NDArray[np.bool_] | None = None,
) -> NDArray[np.object_]:
    """Union of the patches per object and step, ``(N, T)`` (``None`` where no patch applies).

    Only the ``cells`` mask (default: all) is filled.

    Every patch loses the object's own current footprint first, so a rule never deletes
    where the object already is.
    """
    n = len(footprints)
    every: list[list[Any]] = [[] for _ in range(n)]
    at: dict[tuple[int, int], list[Any]] = {}
    for patch in patches:
        if patch.step is None:
            every[patch.object_index].append(patch.geometry)
        else:
            at.setdefault((patch.object_index, patch.step), []).append(patch.geometry)
    want = np.ones((n, n_steps), dtype=bool) if cells is None else np.asarray(cells, dtype=bool)
    grid = np.full((n, n_steps), None, dtype=object)
    # the patches that hold at every step: one union per object, shared by its cells
    for i in np.flatnonzero([bool(g) for g in every] if n else []):
        if want[i].any():
            grid[i, want[i]] = shapely.difference(shapely.union_all(every[i]), footprints[i])
    for (row, k), geoms in at.items():
        if want[row, k]:
            grid[row, k] = shapely.difference(
                shapely.union_all(geoms + every[row]), footprints[row]
            )
    return grid


def subtract_patches(reach: NDArray[np.object_], grid: NDArray[np.object_]) -> NDArray[np.object_]:
    """``reach - grid`` element-wise, ``(N, T)``; cells without a patch are kept as they are."""
    if reach.size == 0:
        return reach
    has = np.asarray([g is not None for g in grid.reshape(-1)], dtype=bool).reshape(grid.shape)
    out = reach.copy()
    out[has] = shapely.difference(reach[has], grid[has].astype(object))
    return out


def keep_largest_part(geoms: NDArray[np.object_]) -> NDArray[np.object_]:
    """Reference behaviour: keep only the largest polygon of each multi-part result."""
    out = geoms.copy()
    flat = out.reshape(-1)
    for i, g in enumerate(flat):
        if g is not None and shapely.get_num_geometries(g) > 1:
            polys = [p for p in shapely.get_parts(g) if shapely.area(p) > 0]
            flat[i] = max(polys, key=shapely.area) if polys else shapely.Polygon()
    return out
