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

__all__ = ["first_hits", "touching"]


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
    rows, steps = np.nonzero(touch)  # row-major: each row's touching steps in order
    if not len(rows):
        return hits
    cut = None
    if deletion is not None:
        touched = np.unique(rows)
        found = deletion(touched)
        if found is not None:
            cut = np.full(len(touch), None, dtype=object)
            cut[touched] = found
    grid = patches(touch) if patches is not None else None
    if len(touch) == 1:  # one object (a frame by frame monitor): the same rounds, unstacked
        lo, size = 0, 1
        while lo < len(steps):
            k = steps[lo : lo + size]
            ok = _reduced_touch(
                sets_m, ego_m, rows[lo : lo + size], k, area=area, cut=cut, grid=grid
            )
            if ok.any():
                hits[0, k[int(np.argmax(ok))]] = True
                break
            lo += size
            size *= 2
        return hits
    rank = np.arange(len(rows)) - np.searchsorted(rows, rows)  # place within its row
    done = np.zeros(len(touch), dtype=bool)
    lo, size = 0, 1
    while True:  # rounds of each unresolved row's next 1, 2, 4, ... touching cells
        sel = np.flatnonzero((rank >= lo) & (rank < lo + size) & ~done[rows])
        if not len(sel):
            break
        i, k = rows[sel], steps[sel]
        ok = _reduced_touch(sets_m, ego_m, i, k, area=area, cut=cut, grid=grid)
        # a row's first hit of the round: its smallest step (cells are in order)
        hit_rows, first = np.unique(i[ok], return_index=True)
        hits[hit_rows, k[ok][first]] = True
        done[hit_rows] = True
        lo += size
        size *= 2
    return hits


def _reduced_touch(
    sets_m: NDArray[np.float64],
    ego_m: NDArray[np.float64],
    i: NDArray[np.intp],
    k: NDArray[np.intp],
    *,
    area: Any,
    cut: NDArray[np.object_] | None,
    grid: PatchGrid | None,
) -> NDArray[np.bool_]:
    """``((S - D - P) & E)`` touches ``area`` at the cells ``(i, k)``, ``(M,)``.

    The differences come first: they are regularised (a polygon minus a polygon is a
    polygon), whereas the intersection keeps lower-dimensional contact, so a set that only
    touches the footprint along an edge still counts, as in the full-geometry test.
    """
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
    return np.asarray(ok, dtype=bool)


def touching(
    sets: NDArray[np.object_], corners: NDArray[np.float64], frame: NDArray[np.intp]
) -> NDArray[np.bool_]:
    """Full geometry: ``shapely.intersects(sets, ego footprint)`` per cell, ``(R, T)``.

    GEOS only runs for the cells whose bounding box meets the footprint's (the others cannot
    touch it); the footprints of those cells are the only ones built.

    Args:
        sets: The reduced sets, ``(R, T)``.
        corners: The ego's footprint corners per frame, ``(F, T, 4, 2)``.
        frame: Frame of each row, ``(R,)``.
    """
    lo, hi = corners.min(axis=2)[frame], corners.max(axis=2)[frame]  # (R, T, 2)
    box = shapely.bounds(sets)  # NaN for empty sets: never near
    near = (
        (box[..., 0] <= hi[..., 0])
        & (box[..., 2] >= lo[..., 0])
        & (box[..., 1] <= hi[..., 1])
        & (box[..., 3] >= lo[..., 1])
    )
    hits = np.zeros(sets.shape, dtype=bool)
    if near.any():
        ego = shapely.polygons(corners[frame][near])
        hits[near] = shapely.intersects(sets[near], ego)
    return hits
