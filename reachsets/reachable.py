"""Reachable sets of all objects on the time grid, by method, with optional trimming."""

from __future__ import annotations

from typing import TYPE_CHECKING, Any

import numpy as np
import shapely

from reachsets.params import ReachMethod
from reachsets.reach_bound import wall_aware_arcs
from reachsets.reach_simple import simple_reach_polygons
from reachsets.reach_turn import funnel_polygons, steering_arcs

if TYPE_CHECKING:
    from numpy.typing import NDArray

    from reachsets.inputs import ObjectStates
    from reachsets.params import ReachParams
    from reachsets.track import TrackGeometry

__all__ = ["deletion_polygons", "reachable_sets"]


def deletion_polygons(
    objects: ObjectStates, params: ReachParams, track: TrackGeometry | None
) -> NDArray[np.object_] | None:
    """The method's deletion polygon per object, ``(N,)``, or ``None`` for ``simple``.

    ``bound`` without a track falls back to the ``turn`` arcs.
    """
    if params.method == ReachMethod.SIMPLE:
        return None
    if params.method == ReachMethod.BOUND and track is not None:
        left = wall_aware_arcs(objects, params, track, 1.0)
        right = wall_aware_arcs(objects, params, track, -1.0)
    else:
        left = steering_arcs(objects, params, 1.0)
        right = steering_arcs(objects, params, -1.0)
    return funnel_polygons(objects, left, right)


def reachable_sets(
    objects: ObjectStates,
    times_s: NDArray[np.float64],
    params: ReachParams,
    track: TrackGeometry | None,
    drivable: Any = None,
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

    Returns:
        ``(N, T)`` geometries (possibly multi-part or empty).
    """
    a = params.a_max_mps2 if params.method == ReachMethod.SIMPLE else params.ax_max_mps2
    sets = simple_reach_polygons(objects, times_s, a)
    if sets.size == 0:
        return sets
    deletion = deletion_polygons(objects, params, track)
    if deletion is not None:
        sets = np.asarray(shapely.difference(sets, deletion[:, None]))
    area = drivable if drivable is not None else (track.polygon if track is not None else None)
    if params.trim_to_drivable and area is not None:
        sets = _trim(sets, area)
    return sets


def _trim(sets: NDArray[np.object_], area: Any) -> NDArray[np.object_]:
    """``sets & area``, ``(N, T)``, clipping ``area`` to each object's bounding box first.

    One clip per object makes the polygon intersections cheap (the track
    polygon has hundreds of vertices; one object's sets touch only a few dozen of them).
    """
    bounds = shapely.bounds(sets)
    box = np.stack(
        [
            np.nanmin(bounds[..., 0], axis=1),
            np.nanmin(bounds[..., 1], axis=1),
            np.nanmax(bounds[..., 2], axis=1),
            np.nanmax(bounds[..., 3], axis=1),
        ],
        axis=1,
    )
    local = np.asarray(shapely.intersection(area, shapely.box(*box.T)))
    return np.asarray(shapely.intersection(sets, local[:, None]))
