"""Verdict only: the first step at which each object's reduced set touches the ego footprint.

The reductions (deletion polygon ``D``, trimming to the drivable area ``A``, rule patches
``P``) only ever shrink the unreduced ``simple`` set ``S``, and they commute with the test::

    ((S - D) & A - P)  touches  E    <=>    ((S - D - P) & E)  touches  A

so no set is ever trimmed: ``S`` is tested against the footprint ``E`` in plain numpy (both
convex, ``convex.convex_touch``); only the touching cells are reduced, intersected with
their (small) footprint and tested against the prepared area. Cells are visited in rounds
of each object's next 1, 2, 4, ... touching cells, objects already hit dropping out, so
little is computed after an object's first hit and the calls stay vectorised.
"""

from __future__ import annotations

from typing import TYPE_CHECKING, Any

import numpy as np
import shapely

from reachsets.convex import convex_touch
from reachsets.patches import subtract_patches

if TYPE_CHECKING:
    from collections.abc import Callable

    from numpy.typing import NDArray

    from reachsets.patches import PatchGrid

__all__ = ["first_hits"]


def first_hits(
    sets_m: NDArray[np.float64],
    ego_m: NDArray[np.float64],
    *,
    area: Any = None,
    deletion: Callable[[NDArray[np.intp]], NDArray[np.object_] | None] | None = None,
    patches: Callable[[NDArray[np.bool_]], PatchGrid] | None = None,
) -> NDArray[np.bool_]:
    """Cells whose reduced set touches the ego footprint, up to each object's first hit.

    Args:
        sets_m: Unreduced convex ``simple`` sets, ``(N, T, V, 2)`` vertices.
        ego_m: Ego footprint corners of each object's frame per step, ``(N, T, 4, 2)``.
        area: Drivable area to trim to (prepared shapely geometry), or ``None``.
        deletion: Returns the method's deletion polygon of the objects at the given rows,
            ``(M,)`` (called at most once, for the objects with a touching cell), or ``None``
            for none.
        patches: Returns the rule patches for the cells of a ``(N, T)`` mask (called at
            most once, only when some cell touches), or ``None`` for none.

    Returns:
        ``(N, T)`` mask; each row's first ``True`` is the object's first collision step and
        nothing after it is set.
    """
    touch = convex_touch(sets_m, ego_m) if sets_m.size else np.zeros(sets_m.shape[:2], bool)
    hits = np.zeros(touch.shape, dtype=bool)
    if not touch.any():
        return hits
    cut = None
    if deletion is not None:
        rows = np.flatnonzero(touch.any(axis=1))
        found = deletion(rows)
        if found is not None:
            cut = np.full(len(touch), None, dtype=object)
            cut[rows] = found
    grid = patches(touch) if patches is not None else None
    todo = touch.copy()
    size = 1
    while True:
        todo &= ~hits.any(axis=1, keepdims=True)
        cells = todo & (np.cumsum(todo, axis=1) <= size)
        if not cells.any():
            break
        hits |= _reduced_touch(sets_m, ego_m, cells, area=area, cut=cut, grid=grid)
        todo &= ~cells
        size *= 2
    # keep only the first hit per row
    return np.asarray(hits & (np.cumsum(hits, axis=1) == 1), dtype=bool)


def _reduced_touch(
    sets_m: NDArray[np.float64],
    ego_m: NDArray[np.float64],
    cells: NDArray[np.bool_],
    *,
    area: Any,
    cut: NDArray[np.object_] | None,
    grid: PatchGrid | None,
) -> NDArray[np.bool_]:
    """``((S - D - P) & E)`` touches ``area`` on the ``cells`` mask, ``(N, T)``.

    The differences come first: they are regularised (a polygon minus a polygon is a
    polygon), whereas the intersection keeps lower-dimensional contact, so a set that only
    touches the footprint along an edge still counts, as in the full-geometry test.
    """
    i, k = np.nonzero(cells)
    # one creation call for both: the rectangles padded to V vertices by repeating a corner
    n_v = sets_m.shape[2]
    ego = ego_m[i, k]
    pad = np.concatenate([ego, np.repeat(ego[:, -1:], n_v - ego.shape[1], axis=1)], 1)
    polys = shapely.polygons(np.concatenate([sets_m[i, k], pad]))
    part = polys[: len(i)]
    if cut is not None:
        part = shapely.difference(part, cut[i])
    if grid is not None:
        part = subtract_patches(part, grid, np.stack([i, k]))
    part = shapely.intersection(part, polys[len(i) :])
    ok = shapely.intersects(part, area) if area is not None else ~shapely.is_empty(part)
    out = np.zeros(cells.shape, dtype=bool)
    out[i, k] = np.asarray(ok, dtype=bool)
    return out
