"""Lane corridors of a road layout for the lane rules (``rules_lane``), built on first use.

A *corridor* is the area a vehicle may use while it keeps its lane: the union of its current
lanes (every lane of agreeing direction that contains its centre) and of their successors up to
``length_m`` ahead and their direct predecessors. Successors are found geometrically: lane
``j`` follows lane ``k`` when ``j``'s centre line starts within ``JOIN_M`` of the end of
``k``'s and both run the same way (the layout carries no topology). A side that is *open*
(the vehicle is observably changing lanes towards it) adds the band of ``OPEN_SIDE_M`` beyond
the corridor's centre lines on that side.

Everything is cached per road geometry in ``RoadGeometry.cache`` (corridors and their
complements by lane set and open sides), so a drive builds each shape once.
"""

from __future__ import annotations

from typing import TYPE_CHECKING, Any

import numpy as np
import shapely

if TYPE_CHECKING:
    from collections.abc import Callable

    from numpy.typing import NDArray

    from reachsets.road import RoadGeometry

__all__ = [
    "JOIN_M",
    "OPEN_SIDE_M",
    "complement",
    "corridor",
    "half_widths",
    "project",
    "project_many",
]

#: A lane follows another when its centre line starts this close to the other's end [m].
JOIN_M = 1.0
#: Width of the band added beyond an open side [m].
OPEN_SIDE_M = 50.0
#: The complement of a corridor is taken within the layout's bounds grown by this [m].
_WORLD_MARGIN_M = 500.0


def _cache(geo: RoadGeometry, name: str) -> dict[Any, Any]:
    out: dict[Any, Any] = geo.cache.setdefault(name, {})
    return out


def _lengths(geo: RoadGeometry) -> NDArray[np.float64]:
    got = geo.cache.get("lengths")
    if got is None:
        got = np.array(
            [float(np.sum(np.hypot(*np.diff(ln.centre_m, axis=0).T))) for ln in geo.lanes]
        )
        geo.cache["lengths"] = got
    return np.asarray(got)


def _links(geo: RoadGeometry) -> tuple[list[list[int]], list[list[int]]]:
    """Successors and predecessors of every lane (geometric, see the module docstring)."""
    got = geo.cache.get("links")
    if got is not None:
        return got  # type: ignore[no-any-return]
    lanes = geo.lanes
    starts = np.array([ln.centre_m[0] for ln in lanes])
    ends = np.array([ln.centre_m[-1] for ln in lanes])
    first = np.array([ln.centre_m[1] - ln.centre_m[0] for ln in lanes])
    last = np.array([ln.centre_m[-1] - ln.centre_m[-2] for ln in lanes])
    near = np.hypot(*(ends[:, None, :] - starts[None, :, :]).transpose(2, 0, 1)) < JOIN_M
    same_way = np.einsum("kd,jd->kj", last, first) > 0
    follows = near & same_way
    np.fill_diagonal(follows, val=False)
    succ = [np.flatnonzero(row).tolist() for row in follows]
    pred = [np.flatnonzero(col).tolist() for col in follows.T]
    geo.cache["links"] = (succ, pred)
    return succ, pred


def half_widths(geo: RoadGeometry) -> NDArray[np.float64]:
    """Half width of every lane: its area over twice its centre line's length [m].

    (The distance of centre points to the outline fails at the lane's ends, which lie on it.)
    """
    got = geo.cache.get("half_widths")
    if got is None:
        area = np.asarray(shapely.area(geo.lane_polys), dtype=np.float64)
        got = area / np.maximum(2 * _lengths(geo), 1e-9)
        geo.cache["half_widths"] = got
    return np.asarray(got)


def _chain(geo: RoadGeometry, lanes: frozenset[int], length_m: float) -> list[int]:
    """``lanes``, their successors up to ``length_m`` further and their direct predecessors."""
    succ, pred = _links(geo)
    lengths = _lengths(geo)
    seen = set(lanes)
    frontier = [(k, 0.0) for k in lanes]
    while frontier:
        k, run = frontier.pop()
        for j in succ[k]:
            if j not in seen and run < length_m:
                seen.add(j)
                frontier.append((j, run + float(lengths[j])))
    for k in lanes:
        seen.update(pred[k])
    return sorted(seen)


def corridor(
    geo: RoadGeometry,
    lanes: frozenset[int],
    *,
    open_left: bool,
    open_right: bool,
    length_m: float,
) -> Any:
    """The corridor of ``lanes`` (lane indices) with the given sides open (cached)."""
    key = (lanes, open_left, open_right, length_m)
    cache = _cache(geo, "corridor")
    if key in cache:
        return cache[key]
    chain = _chain(geo, lanes, length_m)
    parts = list(geo.lane_polys[chain])
    centres = [shapely.linestrings(geo.lanes[k].centre_m) for k in chain]
    for is_open, sign in ((open_left, 1.0), (open_right, -1.0)):
        if is_open:
            parts += [
                shapely.buffer(c, sign * OPEN_SIDE_M, single_sided=True, quad_segs=2)
                for c in centres
            ]
    geom = shapely.make_valid(shapely.union_all(parts))
    shapely.prepare(geom)
    cache[key] = geom
    return geom


def complement(geo: RoadGeometry, keep: Callable[[], Any], key: Any) -> Any:
    """Everything within the layout's bounds (grown by 500 m) outside ``keep()`` (cached by key).

    ``keep`` builds the area to keep; it is only called when ``key`` is not cached yet.
    """
    cache = _cache(geo, "complement")
    if key in cache:
        return cache[key]
    x0, y0, x1, y1 = shapely.bounds(geo.drivable)
    m = _WORLD_MARGIN_M
    world = shapely.box(x0 - m, y0 - m, x1 + m, y1 + m)
    geom = shapely.difference(world, keep())
    cache[key] = geom
    return geom


def project(centre_m: NDArray[np.float64], x: float, y: float) -> tuple[float, NDArray[np.float64]]:
    """Signed lateral offset (left positive) [m] and unit tangent ``(2,)`` at the foot point.

    Args:
        centre_m: Centre line in driving direction, ``(C, 2)``, ``C >= 2``.
        x: Point x.
        y: Point y.
    """
    off, t = project_many(centre_m, np.array([x]), np.array([y]))
    return float(off[0]), t[0]


def project_many(
    centre_m: NDArray[np.float64], x: NDArray[np.float64], y: NDArray[np.float64]
) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """``project`` for ``(M,)`` points: offsets ``(M,)`` and unit tangents ``(M, 2)``."""
    a = centre_m[:-1]
    d = np.diff(centre_m, axis=0)
    seg2 = np.maximum(np.sum(d * d, axis=1), 1e-12)
    p = np.stack([x, y], axis=1)[:, None, :]  # (M, 1, 2)
    u = np.clip(np.sum((p - a) * d, axis=2) / seg2, 0.0, 1.0)  # (M, S)
    foot = a + u[..., None] * d  # (M, S, 2)
    k = np.argmin(np.sum((foot - p) ** 2, axis=2), axis=1)
    t = d[k] / np.sqrt(seg2[k])[:, None]
    rel = p[:, 0, :] - foot[np.arange(len(k)), k]
    return t[:, 0] * rel[:, 1] - t[:, 1] * rel[:, 0], t
