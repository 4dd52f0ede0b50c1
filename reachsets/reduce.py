"""Full reduced sets with the compiled clipper: ``(simple & drivable) - deletion`` per cell.

``reachable.reachable_sets`` with GEOS runs two overlays per cell (the difference with the
deletion polygon, the intersection with the track); here ``clip_cells.reduce_cells`` computes
both on the vertex lists, and GEOS only runs for the cells where the clipper gives up
(degenerate contacts, a hole), for objects whose deletion polygon is not simple, and for a
drivable area that is not one polygon. Shapely geometries are created once per frame from all
result rings (``shapely.linearrings`` / ``polygons`` / ``multipolygons`` on the coordinates).
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

import numpy as np
import shapely

from reachsets import clip_cells, clip_rings

if TYPE_CHECKING:
    from numpy.typing import NDArray

__all__ = ["CellRings", "prepared_area", "scalar_cells", "scalar_sets"]

_POLYGON = 3
_EMPTY = shapely.Polygon()
#: Drivable areas prepared for the clipper, by ``id`` (with the geometry, to check identity).
_AREAS: dict[int, tuple[Any, clip_cells.Area | None]] = {}
_AREAS_MAX = 8


@dataclass(frozen=True)
class CellRings:
    """The rings the clipper gave for a grid of cells, the points of their geometries.

    A cell's geometry (``scalar_cells``) is built from exactly these points: one polygon per
    ring, several rings of a cell a multipolygon in this order, no rings an empty polygon.

    Attributes:
        xy: Every ring's points, closed (first point repeated), ring after ring, ``(P, 2)``.
        ends: Point offsets of the rings, ``(R + 1,)`` (ring ``r``: ``ends[r]:ends[r + 1]``).
        first: Ring offsets of the cells, ``(C + 1,)`` (cell ``c``: rings ``first[c]`` to
            ``first[c + 1] - 1``); cells are flat ``object * T + step``.
        exact: ``(C,)``: the cell's geometry is its rings (``False``: computed by GEOS, where
            the clipper gave up, or changed afterwards, e.g. by a rule patch).
    """

    xy: NDArray[np.float64]
    ends: NDArray[np.int64]
    first: NDArray[np.int64]
    exact: NDArray[np.bool_]


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
    return scalar_cells(verts, deletion, area)[0]


def scalar_cells(
    verts: NDArray[np.float64], deletion: NDArray[np.float64] | None, area: Any
) -> tuple[NDArray[np.object_], CellRings | None]:
    """:func:`scalar_sets` and the rings its geometries were built from.

    Returns:
        The ``(N, T)`` geometries and their :class:`CellRings` (``None`` when nothing was
        clipped: no deletion and no area, or no cells).
    """
    n, t = verts.shape[:2]
    if n == 0 or t == 0 or (deletion is None and area is None):
        return np.asarray(shapely.polygons(verts)).reshape(n, t), None
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
    rings = _rings(xy, sizes, owner, n * t)
    out = _assemble(rings, owner, n * t)
    if fallback:
        flat = verts.reshape(n * t, *verts.shape[2:])
        out[fallback] = _geos_cells(flat, deletion, area, fallback, t)
        rings.exact[fallback] = False
    return out.reshape(n, t), rings


def _rings(xy: list[float], sizes: list[int], owner: list[int], cells: int) -> CellRings:
    """The clipper's output as :class:`CellRings` (``owner``: cell per ring, increasing)."""
    pts = np.fromiter(xy, dtype=np.float64, count=len(xy)).reshape(-1, 2)
    ends = np.zeros(len(sizes) + 1, dtype=np.int64)
    np.cumsum(sizes, out=ends[1:])
    first = np.zeros(cells + 1, dtype=np.int64)
    np.cumsum(np.bincount(np.asarray(owner, dtype=np.int64), minlength=cells), out=first[1:])
    return CellRings(pts, ends, first, np.ones(cells, dtype=bool))


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


def _assemble(rings: CellRings, owner: list[int], cells: int) -> NDArray[np.object_]:
    """One geometry per cell from its closed rings (none: empty polygon; several: multipolygon).

    ``owner``: cell per ring (``rings.first`` in another form).
    """
    out = np.full(cells, _EMPTY, dtype=object)
    if not owner:
        return out
    polys = np.asarray(
        shapely.from_ragged_array(
            shapely.GeometryType.POLYGON, rings.xy, (rings.ends, np.arange(len(owner) + 1))
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
