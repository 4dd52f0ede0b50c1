"""Reachable sets of all objects on the time grid, by method, with optional trimming."""

from __future__ import annotations

from typing import TYPE_CHECKING, Any

import numpy as np
import shapely

from reachsets import clip_scalar, small_scalar
from reachsets.params import ReachMethod
from reachsets.reach_bound import wall_aware_arcs
from reachsets.reach_simple import simple_reach_polygons, simple_reach_vertices
from reachsets.reach_turn import funnel_coords, steering_arcs
from reachsets.reduce import scalar_cells

if TYPE_CHECKING:
    from numpy.typing import NDArray

    from reachsets.inputs import ObjectStates
    from reachsets.params import ReachParams
    from reachsets.reduce import CellRings
    from reachsets.track import TrackGeometry

__all__ = [
    "SCALAR_CLIP",
    "SCALAR_SETS_MAX",
    "deletion_coords",
    "deletion_polygons",
    "reachable_sets",
    "simple_sets",
    "simple_vertices",
]

#: Up to this many objects ``simple_vertices`` builds the sets with the scalar twin
#: (``small_scalar.simple_vertices_rows``, compiled) instead of numpy (measured crossover).
SCALAR_SETS_MAX = 3 if not small_scalar.__file__.endswith(".py") else 0
#: Whether ``reachable_sets`` reduces the sets with the compiled clipper (``clip_scalar``)
#: by default; from the sources it is slower than GEOS.
SCALAR_CLIP = not clip_scalar.__file__.endswith(".py")


def deletion_polygons(
    objects: ObjectStates, params: ReachParams, track: TrackGeometry | None
) -> NDArray[np.object_] | None:
    """The method's deletion polygon per object, ``(N,)``, or ``None`` for ``simple``.

    ``bound`` without a track falls back to the ``turn`` arcs.
    """
    coords = deletion_coords(objects, params, track)
    if coords is None:
        return None
    if coords.shape[0] == 0:
        return np.empty(0, dtype=object)
    return np.asarray(shapely.make_valid(shapely.polygons(coords)))


def deletion_coords(
    objects: ObjectStates, params: ReachParams, track: TrackGeometry | None
) -> NDArray[np.float64] | None:
    """The rings of ``deletion_polygons`` before they are made valid, ``(N, V, 2)``."""
    if params.method == ReachMethod.SIMPLE:
        return None
    if params.method == ReachMethod.BOUND and track is not None:
        left, right = wall_aware_arcs(objects, params, track)
    else:
        left = steering_arcs(objects, params, 1.0)
        right = (left[0], -left[1])  # steering_arcs(..., -1.0), bit for bit
    return funnel_coords(objects, left, right, keep_body=params.keep_object_body)


def reachable_sets(
    objects: ObjectStates,
    times_s: NDArray[np.float64],
    params: ReachParams,
    track: TrackGeometry | None,
    *,
    drivable: Any = None,
    cells: NDArray[np.bool_] | None = None,
    simple: NDArray[np.object_] | None = None,
    trim: bool = True,
    scalar: bool | None = None,
    rings: list[CellRings] | None = None,
) -> NDArray[np.object_]:
    """Reachable sets of every object at every stamp, ``(N, T)`` shapely geometries.

    Step ``k`` covers the interval ``[t_{k-1}, t_k]`` (step 0 is the current footprint).

    Args:
        objects: The objects (N).
        times_s: Grid stamps ``(T,)``.
        params: Method and limits. ``simple`` uses ``a_max_mps2``; ``turn`` and ``bound``
            use ``ax_max_mps2`` for the underlying simple set (reference semantics).
        track: Track geometry (``bound`` walls and trimming), if any.
        drivable: Area to trim to when ``params.trim_to_drivable`` (defaults to the track
            polygon); ``None`` and no track means no trimming.
        cells: ``(N, T)`` mask of the cells to reduce (deletion and trimming); the others
            keep the plain ``simple`` polygon. ``None`` reduces every cell.
        simple: The ``simple_sets`` of these objects when already computed.
        trim: ``False`` skips the trimming (the caller clips the ego footprints instead).
        scalar: Reduce every cell with the compiled clipper (``reduce.scalar_cells``; GEOS where
            it gives up), the same geometry within 1e-9 m; ``None``: when compiled and
            ``cells`` and ``simple`` are ``None``.
        rings: Receives the clipper's rings of the sets (``reduce.CellRings``) when it ran.

    Returns:
        ``(N, T)`` geometries (possibly multi-part or empty).
    """
    if (scalar if scalar is not None else SCALAR_CLIP) and cells is None and simple is None:
        area = drivable if drivable is not None else (track.polygon if track is not None else None)
        trimmed = area if trim and params.trim_to_drivable else None
        verts = simple_vertices(objects, times_s, params)
        sets, found = scalar_cells(verts, deletion_coords(objects, params, track), trimmed)
        if rings is not None and found is not None:
            rings.append(found)
        return sets
    sets = simple_sets(objects, times_s, params) if simple is None else simple.copy()
    if sets.size == 0:
        return sets
    mask = np.ones(sets.shape, dtype=bool) if cells is None else np.asarray(cells, dtype=bool)
    rows = np.nonzero(mask)[0]
    if len(rows) == 0:
        return sets
    deletion = deletion_polygons(objects, params, track)
    if deletion is not None:
        sets[mask] = shapely.difference(sets[mask], deletion[rows])
    area = drivable if drivable is not None else (track.polygon if track is not None else None)
    if trim and params.trim_to_drivable and area is not None:
        trimmed = _trim(sets, area, mask)
        sets[mask] = trimmed[mask]
    return sets


def simple_sets(
    objects: ObjectStates, times_s: NDArray[np.float64], params: ReachParams
) -> NDArray[np.object_]:
    """The unreduced ``simple`` polygons with the method's acceleration bound, ``(N, T)``.

    ``simple`` uses ``a_max_mps2``; ``turn`` and ``bound`` use ``ax_max_mps2`` (reference).
    Every reduced set lies inside this one, so it is a sound collision pre-filter.
    """
    return simple_reach_polygons(objects, times_s, _simple_bound(params))


def simple_vertices(
    objects: ObjectStates,
    times_s: NDArray[np.float64],
    params: ReachParams,
    *,
    scalar: bool | None = None,
) -> NDArray[np.float64]:
    """The vertices of ``simple_sets``, ``(N, T, 6, 2)``.

    ``scalar``: with the scalar twin (``None``: for at most ``SCALAR_SETS_MAX`` objects);
    the vertices agree within 1e-9 m either way (numpy's ``t ** 3`` may differ in the
    last bit from the twin's ``t * t * t``).
    """
    a = _simple_bound(params)
    n = len(objects)
    if (scalar if scalar is not None else n <= SCALAR_SETS_MAX) and a > 0:
        o = objects
        cols = (o.x_m, o.y_m, o.yaw_rad, o.speed_mps, o.length_m, o.width_m)
        poses = np.stack(cols, axis=1).astype(np.float64).tolist()
        flat = small_scalar.simple_vertices_rows(poses, np.asarray(times_s).tolist(), a)
        return np.array(flat, dtype=np.float64).reshape(n, len(times_s), 6, 2)
    return simple_reach_vertices(objects, times_s, a)


def _simple_bound(params: ReachParams) -> float:
    return params.a_max_mps2 if params.method == ReachMethod.SIMPLE else params.ax_max_mps2


def _trim(sets: NDArray[np.object_], area: Any, mask: NDArray[np.bool_]) -> NDArray[np.object_]:
    """``sets & area`` on the ``mask`` cells, clipping ``area`` per object's bounding box first.

    One clip per object makes the polygon intersections cheap (the track
    polygon has hundreds of vertices; one object's sets touch only a few dozen of them).
    """
    bounds = np.where(mask[..., None], shapely.bounds(sets), np.nan)
    rows = np.flatnonzero(mask.any(axis=1))
    sub = bounds[rows]
    box = np.stack(
        [
            np.nanmin(sub[..., 0], axis=1),
            np.nanmin(sub[..., 1], axis=1),
            np.nanmax(sub[..., 2], axis=1),
            np.nanmax(sub[..., 3], axis=1),
        ],
        axis=1,
    )
    local = np.full(len(sets), None, dtype=object)
    local[rows] = shapely.intersection(area, shapely.box(*box.T))
    out = sets.copy()
    out[mask] = shapely.intersection(sets[mask], local[np.nonzero(mask)[0]])
    return out
