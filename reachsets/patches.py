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
    from reachsets.road import RoadGeometry
    from reachsets.track import TrackGeometry

__all__ = [
    "PatchGrid",
    "RuleContext",
    "RulePatch",
    "keep_largest_part",
    "patch_grid",
    "robust_difference",
    "subtract_patches",
]

#: Precision grid of the fallback overlay [m].
_GRID_M = 1e-6


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


@dataclass(frozen=True, slots=True)
class PatchGrid:
    """The rule patches to subtract, each minus its object's current footprint.

    Attributes:
        every: Per object, the union of the patches that hold at every step, ``(N,)``
            (``None`` where there are none).
        at: Per object and step, the union of the patches of that step only, ``(N, T)``
            (``None`` where there are none or the cell was not asked for).
    """

    every: NDArray[np.object_]
    at: NDArray[np.object_]


def patch_grid(
    patches: Sequence[RulePatch],
    footprints: NDArray[np.object_],
    n_steps: int,
    cells: NDArray[np.bool_] | None = None,
) -> PatchGrid:
    """The patches per object (all steps) and per cell (one step), for the ``cells`` mask.

    Every patch loses the object's own current footprint first, so a rule never deletes
    where the object already is. Subtracting both (``subtract_patches``) removes their union.
    """
    n = len(footprints)
    every_parts: list[list[Any]] = [[] for _ in range(n)]
    at_parts: dict[tuple[int, int], list[Any]] = {}
    for patch in patches:
        if patch.step is None:
            every_parts[patch.object_index].append(patch.geometry)
        else:
            at_parts.setdefault((patch.object_index, patch.step), []).append(patch.geometry)
    want = np.ones((n, n_steps), dtype=bool) if cells is None else np.asarray(cells, dtype=bool)
    every = np.full(n, None, dtype=object)
    at = np.full((n, n_steps), None, dtype=object)
    for i, parts in enumerate(every_parts):
        if parts and want[i].any():
            every[i] = shapely.difference(shapely.union_all(parts), footprints[i])
    for (row, k), parts in at_parts.items():
        if want[row, k]:
            at[row, k] = shapely.difference(shapely.union_all(parts), footprints[row])
    return PatchGrid(every, at)


def subtract_patches(
    reach: NDArray[np.object_], grid: PatchGrid, rows: NDArray[np.intp] | None = None
) -> NDArray[np.object_]:
    """``reach`` minus the patches of its cells, element-wise.

    Args:
        reach: Geometries, ``(N, T)``, or ``(C,)`` cells when ``rows`` is given.
        grid: The patches.
        rows: For ``(C,)`` cells, the object row and the step of each, ``(2, C)``.

    Returns:
        The reduced geometries, same shape; cells without a patch are kept as they are.
    """
    if reach.size == 0:
        return reach
    if rows is None:
        i, k = np.indices(reach.shape).reshape(2, -1)
    else:
        i, k = rows
    out = reach.reshape(-1).copy()
    for cut in (grid.every[i], grid.at[i, k]):
        has = np.asarray([g is not None for g in cut], dtype=bool)
        if has.any():
            out[has] = robust_difference(out[has], cut[has].astype(object))
    return out.reshape(reach.shape)


def robust_difference(a: NDArray[np.object_], b: NDArray[np.object_]) -> NDArray[np.object_]:
    """``shapely.difference(a, b)`` element-wise; where GEOS' overlay fails, snap-rounded.

    GEOS' floating overlay can fail on nearly coincident edges ("Unable to determine overlay
    result geometry dimension", met on lane-corridor patches of real maps). The failing pairs
    are recomputed with a 1 micrometre precision grid (snap-rounding, robust by construction).
    """
    try:
        return np.asarray(shapely.difference(a, b))
    except shapely.errors.GEOSException:
        out = np.empty(len(a), dtype=object)
        for n, (x, y) in enumerate(zip(a, b, strict=True)):
            try:
                out[n] = shapely.difference(x, y)
            except shapely.errors.GEOSException:
                out[n] = shapely.difference(x, y, grid_size=_GRID_M)
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
