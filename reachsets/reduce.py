"""Full reduced sets with the compiled clipper: ``(simple & drivable) - deletion`` per cell.

``reachable.reachable_sets`` with GEOS runs two overlays per cell (the difference with the
deletion polygon, the intersection with the track); here ``clip_cells.reduce_cells`` computes
both on the vertex lists, and GEOS only runs for the cells where the clipper gives up
(degenerate contacts, a hole), for objects whose deletion polygon is not simple, and for a
drivable area that is not one polygon. Shapely geometries are created once per frame from all
result rings (``shapely.linearrings`` / ``polygons`` / ``multipolygons`` on the coordinates).
"""

from __future__ import annotations

from typing import TYPE_CHECKING, Any

import numpy as np
import shapely

from reachsets import clip_cells, clip_rings

if TYPE_CHECKING:
    from numpy.typing import NDArray

__all__ = ["prepared_area", "scalar_sets"]

_POLYGON = 3
_EMPTY = shapely.Polygon()
#: Drivable areas prepared for the clipper, by ``id`` (with the geometry, to check identity).
_AREAS: dict[int, tuple[Any, clip_cells.Area | None]] = {}
_AREAS_MAX = 8


def prepared_area(area: Any) -> clip_cells.Area | None:
    """``area``'s rings prepared for the clipper (cached), ``None`` if it is not one polygon."""
    hit = _AREAS.get(id(area))
    if hit is not None and hit[0] is area:
        return hit[1]
    prepared = None
    if shapely.get_type_id(area) == _POLYGON and not shapely.is_empty(area):
        shell, *holes = (
            [float(v) for v in shapely.get_coordinates(r)[:-1].ravel()]
            for r in (area.exterior, *area.interiors)
        )
        prepared = clip_cells.Area(shell, holes)
    if len(_AREAS) >= _AREAS_MAX:
        _AREAS.clear()
    _AREAS[id(area)] = (area, prepared)
    return prepared


def scalar_sets(
    verts: NDArray[np.float64], deletion: NDArray[np.float64] | None, area: Any
) -> NDArray[np.object_]:
    """``(polygon(verts) - deletion) & area`` per cell, ``(N, T)`` shapely geometries.

    Args:
        verts: The ``simple`` sets' vertices, ``(N, T, V, 2)``.
        deletion: Each object's deletion ring, ``(N, P, 2)`` (made valid by GEOS where it is
            not simple), or ``None``.
        area: Drivable area to trim to, or ``None``.

    Returns:
        The same geometry as GEOS' ``difference`` then ``intersection`` (within 1e-9 m);
        an empty result is an empty polygon.
    """
    n, t = verts.shape[:2]
    if n == 0 or t == 0 or (deletion is None and area is None):
        return np.asarray(shapely.polygons(verts)).reshape(n, t)
    dl = _deletion(deletion, n)
    prepared = prepared_area(area) if area is not None else None
    xy: list[float] = []
    sizes: list[int] = []
    owner: list[int] = []
    fallback: list[int] = []
    rows = verts.reshape(n, t, -1).tolist()
    if area is not None and prepared is None:  # not one polygon: GEOS for every cell
        fallback += range(n * t)
    else:
        clip_cells.reduce_objects(rows, dl, prepared, xy, sizes, owner, fallback)
    out = _assemble(xy, sizes, owner, n * t)
    if fallback:
        flat = verts.reshape(n * t, *verts.shape[2:])
        out[fallback] = _geos_cells(flat, deletion, area, fallback, t)
    return out.reshape(n, t)


def _deletion(deletion: NDArray[np.float64] | None, n: int) -> list[list[float] | None]:
    """The clipper's deletion rings (``None``: not simple for GEOS; empty without deletion).

    ``clip_rings.surely_simple`` answers most rings; GEOS' ``is_valid`` only the others.
    """
    if deletion is None:
        return [[] for _ in range(n)]
    flat: list[list[float] | None] = list(deletion.reshape(n, -1).tolist())
    unsure = [i for i in range(n) if not clip_rings.surely_simple(flat[i] or [])]
    if unsure:
        valid = np.asarray(shapely.is_valid(shapely.polygons(deletion[unsure])), dtype=bool)
        for i, ok in zip(unsure, valid.tolist(), strict=True):
            if not ok:
                flat[i] = None
    return flat


def _cut(
    deletion: NDArray[np.float64] | None, rows: NDArray[np.int64]
) -> NDArray[np.object_] | None:
    """The deletion polygons of objects ``rows`` for GEOS, made valid where they are not."""
    if deletion is None:
        return None
    cut = np.asarray(shapely.polygons(deletion[rows]))
    simple = np.asarray(shapely.is_valid(cut), dtype=bool)
    if not simple.all():
        cut[~simple] = shapely.make_valid(cut[~simple])
    return cut


def _assemble(
    xy: list[float], sizes: list[int], owner: list[int], cells: int
) -> NDArray[np.object_]:
    """One geometry per cell from its closed rings (none: empty polygon; several: multipolygon).

    ``xy``: all rings' coordinates, flat; ``sizes``: points per ring; ``owner``: cell per ring.
    """
    out = np.full(cells, _EMPTY, dtype=object)
    if not sizes:
        return out
    pts = np.fromiter(xy, dtype=np.float64, count=len(xy)).reshape(-1, 2)
    offsets = np.zeros(len(sizes) + 1, dtype=np.int64)
    np.cumsum(sizes, out=offsets[1:])
    polys = np.asarray(
        shapely.from_ragged_array(
            shapely.GeometryType.POLYGON, pts, (offsets, np.arange(len(sizes) + 1))
        )
    )
    if len(set(owner)) == len(owner):  # one ring per cell (the common case): no grouping
        out[owner] = polys
        return out
    own = np.array(owner, dtype=np.int64)
    count = np.bincount(own, minlength=cells)
    one = count[own] == 1
    out[own[one]] = polys[one]
    if not one.all():
        multi = own[~one]
        cell_ids, group = np.unique(multi, return_inverse=True)
        out[cell_ids] = shapely.multipolygons(polys[~one], indices=group)
    return out


def _geos_cells(
    flat: NDArray[np.float64],
    deletion: NDArray[np.float64] | None,
    area: Any,
    cells: list[int],
    t: int,
) -> NDArray[np.object_]:
    """The cells ``cells`` (flat indices) with GEOS, as ``reachable_sets`` computes them."""
    idx = np.array(cells, dtype=np.int64)
    sets = np.asarray(shapely.polygons(flat[idx]))
    cut = _cut(deletion, idx // t)
    if cut is not None:
        sets = np.asarray(shapely.difference(sets, cut))
    if area is not None:
        left = ~np.asarray(shapely.is_empty(sets), dtype=bool)  # empty & area is empty
        if left.any():
            sets[left] = shapely.intersection(sets[left], area)
    return sets
