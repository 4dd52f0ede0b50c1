"""Full reduced sets with the compiled clipper: ``(simple - deletion) & drivable`` per cell.

``reachable.reachable_sets`` with GEOS runs two overlays per cell (the difference with the
deletion polygon, the intersection with the track); here ``clip_scalar.reduce_cells`` computes
both on the vertex lists, and GEOS only runs for the cells where the clipper gives up
(degenerate contacts, a hole) and for objects whose deletion polygon is not simple or whose
drivable area nearby is not one polygon without holes. Shapely geometries are created once
per frame from all result rings (``shapely.linearrings`` / ``polygons`` / ``multipolygons`` on
the coordinate arrays).
"""

from __future__ import annotations

from typing import TYPE_CHECKING, Any

import numpy as np
import shapely

from reachsets import clip_scalar

if TYPE_CHECKING:
    from numpy.typing import NDArray

__all__ = ["local_areas", "scalar_sets"]

_POLYGON = 3
_MARGIN_M = 1.0


def local_areas(verts: NDArray[np.float64], area: Any) -> NDArray[np.object_]:
    """``area`` clipped to each object's vertices ``(N, T, V, 2)`` (bounding box + 1 m), ``(N,)``.

    The track polygon has hundreds of vertices; one object's sets touch a few dozen of them.
    The margin keeps the box's edges off the sets' extreme vertices (a contact the clipper
    leaves to GEOS).
    """
    lo = verts.min(axis=(1, 2)) - _MARGIN_M
    hi = verts.max(axis=(1, 2)) + _MARGIN_M
    return np.asarray(
        shapely.intersection(area, shapely.box(lo[:, 0], lo[:, 1], hi[:, 0], hi[:, 1]))
    )


def _open_ring(geom: Any) -> list[float]:
    """The shell of a polygon as a flat open ring."""
    xy = shapely.get_coordinates(shapely.get_exterior_ring(geom))
    return [float(v) for v in xy[:-1].ravel()]


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
    cut, local, rings = _operands(verts, deletion, area)
    xy: list[float] = []
    sizes: list[int] = []
    owner: list[int] = []
    fallback: list[int] = []
    rows = verts.reshape(n, t, -1).tolist()
    for i in range(n):
        dl, al = rings[i]
        if dl is None or al is None:
            fallback += range(i * t, (i + 1) * t)
            continue
        for k, parts in enumerate(clip_scalar.reduce_cells(rows[i], dl, al)):
            if parts is None:
                fallback.append(i * t + k)
                continue
            for ring in parts:
                xy += ring
                sizes.append(len(ring) // 2)
                owner.append(i * t + k)
    out = _assemble(xy, sizes, owner, n * t)
    if fallback:
        out[fallback] = _geos_cells(verts.reshape(n * t, *verts.shape[2:]), cut, local, fallback, t)
    return out.reshape(n, t)


def _operands(
    verts: NDArray[np.float64], deletion: NDArray[np.float64] | None, area: Any
) -> tuple[
    NDArray[np.object_], NDArray[np.object_], list[tuple[list[float] | None, list[float] | None]]
]:
    """GEOS' operands per object (deletion polygon, area nearby) and the clipper's rings.

    A ring is ``[]`` for no operand and ``None`` where the clipper cannot take the operand (a
    deletion polygon that is not simple, an area nearby that is not one polygon without holes).
    """
    n = len(verts)
    cut = np.full(n, None, dtype=object)
    local = np.full(n, None, dtype=object)
    dl: list[list[float] | None] = [[] for _ in range(n)]
    al: list[list[float] | None] = [[] for _ in range(n)]
    if deletion is not None:
        cut = np.asarray(shapely.polygons(deletion))
        simple = np.asarray(shapely.is_valid(cut), dtype=bool)
        if not simple.all():
            cut[~simple] = shapely.make_valid(cut[~simple])
        flat = deletion.reshape(n, -1).tolist()
        dl = [flat[i] if simple[i] else None for i in range(n)]
    if area is not None:
        local = local_areas(verts, area)
        kind = shapely.get_type_id(local)
        simple = (kind == _POLYGON) & (shapely.get_num_interior_rings(local) == 0)
        # an empty area nearby has no ring either: GEOS (empty sets)
        al = [(_open_ring(local[i]) or None) if simple[i] else None for i in range(n)]
    return cut, local, list(zip(dl, al, strict=True))


def _assemble(
    xy: list[float], sizes: list[int], owner: list[int], cells: int
) -> NDArray[np.object_]:
    """One geometry per cell from its rings (none: empty polygon; several: multipolygon)."""
    out = np.full(cells, shapely.Polygon(), dtype=object)
    if not sizes:
        return out
    pts = np.array(xy, dtype=np.float64).reshape(-1, 2)
    ring_of = np.repeat(np.arange(len(sizes)), sizes)
    polys = np.asarray(shapely.polygons(shapely.linearrings(pts, indices=ring_of)))
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
    cut: NDArray[np.object_],
    local: NDArray[np.object_],
    cells: list[int],
    t: int,
) -> NDArray[np.object_]:
    """The cells ``cells`` (flat indices) with GEOS, as ``reachable_sets`` computes them."""
    idx = np.array(cells, dtype=np.int64)
    row = idx // t
    sets = np.asarray(shapely.polygons(flat[idx]))
    if cut[0] is not None:
        sets = np.asarray(shapely.difference(sets, cut[row]))
    if local[0] is not None:
        sets = np.asarray(shapely.intersection(sets, local[row]))
    return sets
