"""Map matching: bounding boxes -> parametric occupied regions per lane, as ad-map does it.

ad-map samples a box on a 0.1 m lattice and matches every lattice point to every lane
(``rss.scene.matching_points`` holds the point rule: lon from the nearest points on both
borders, a point within 0.1 m matches). The region of a lane spans the matching points,
those beside the lane counting at its border. Here only the lattice points that can hold
a region's extremes are evaluated, for all (box, lane) pairs at once (STRtree query of
the lanes grown by 0.1 m -> index pairs)::

     left border  ───────────────────────────▶  lat 0
                        c─────────x──c           c  corner (inside the grown lane)
     lane         ──────│   box   │  │───────▶   x  lattice points beside the cut where
                        c─────────x──c              a box edge leaves the grown lane
     right border ───────────────────────────▶  lat 1

On curved lanes the lateral position along a box side is not linear: for boxes along the
lane, samples on the sides locate the extreme inside a side (a parabola through the best
sample and its neighbours), and the lattice points round that place give its value (the
parabola's own vertex overshoots by up to 2 cm where the nearest border segments change
along the side). Every evaluated point is a lattice point, so no region reaches beyond
ad-map's. Only the part of a box that lies on the map counts, so a
vehicle partly off the map still gets regions for the lanes it touches; a box touching
no lane gets none.
"""

from __future__ import annotations

from typing import TYPE_CHECKING, NamedTuple

import numpy as np
import shapely

from rss.scene.match_records import BoxArrays, Matches, box_polygons
from rss.scene.matching_points import (
    DISTANCE_TOL_M,
    RING_POINTS,
    ad_map_positions,
    box_ring,
    edge_extremes,
    lattice_neighbours,
    matches_point,
    outline_crossings,
    side_lattice,
)
from rss.scene.polylines import heading_at, interpolate

if TYPE_CHECKING:
    from rss.arrays import BoolArray, FloatArray, IntArray
    from rss.scene.prepared import PreparedGraph

__all__ = [
    "lane_heading",
    "match_boxes",
    "match_route",
]

_TANGENT_STEP_M = 0.5
#: Curved borders are searched within this factor times the half diagonal of a box, plus
#: the margin, of where its centre meets them (nearest points of points in the box lie
#: no farther along a border than the points are from the centre, give or take).
_REACH_FACTOR = 1.5
_REACH_MARGIN_M = 1.5
#: Box rings are sampled for boxes within 60 degrees of their curved lane's heading.
_ALONG_COS = 0.5
#: A footprint vertex this close to a box corner is that corner (a lattice point).
_CORNER_TOL_M = 1e-7
#: A point projecting onto a lane end counts as in the lane only this close (ad-map 3.0's
#: ``isLongitudinalInLaneMatch``: 0.1 m, earlier releases 5 cm), so every point matching
#: there does.
_END_MATCH_M = 0.1 + DISTANCE_TOL_M
#: ad-physics' tolerance of parametric equality (``ParametricValue::cPrecisionValue``).
_END_TOL = 1e-6
#: Lattice points evaluated to either side of where a box side's inner lateral extreme
#: seems to lie (``side_lattice``).
_SIDE_STEPS = 5
#: Anchor choice: a lane across the box heading counts like a centre this far outside.
_MISALIGNED_M = 2.0


def lane_heading(graph: PreparedGraph, lanes: IntArray, s_m: FloatArray) -> FloatArray:
    """Heading of the centre lines of ``lanes`` at arc lengths ``s_m`` (both ``(P,)``)."""
    return heading_at(graph.centre, lanes, s_m, _TANGENT_STEP_M)


def _centre_station(
    graph: PreparedGraph, lanes: IntArray, points: np.ndarray
) -> tuple[FloatArray, FloatArray]:
    """Arc length on the centre line and the centre line's heading there, ``(P,)`` each.

    ``points`` are ``(P,)`` point geometries.
    """
    n = len(lanes)
    s = shapely.line_locate_point(graph.centre_lines[lanes], points)
    length = graph.centre_length_m[lanes]
    ends = np.clip(
        np.concatenate([s - _TANGENT_STEP_M, s + _TANGENT_STEP_M]),
        0.0,
        np.concatenate([length, length]),
    )
    at = interpolate(graph.centre, np.concatenate([lanes, lanes]), ends)
    chord = at[n:] - at[:n]
    return s, np.arctan2(chord[:, 1], chord[:, 0])


class _Candidates(NamedTuple):
    """The points that can hold the extremes of each (box, lane) pair.

    ``points`` ``(Q, 2)`` belong to pairs ``owner`` ``(Q,)``; ``tested`` points still have
    to match the lane (the others lie inside its grown polygon). The last ``RING_POINTS * C``
    points are the box rings (``box_ring``) of the pairs ``bent`` (boxes along curved
    lanes).
    """

    points: FloatArray
    owner: IntArray
    tested: BoolArray
    bent: IntArray
    cut: BoolArray


def _candidates(  # noqa: PLR0917 - the pairs' arrays
    graph: PreparedGraph,
    boxes: BoxArrays,
    polys: np.ndarray,
    box_idx: IntArray,
    lane_idx: IntArray,
    heading_rad: FloatArray,
) -> _Candidates:
    """Corners, lattice points beside the cuts of box edges, rings along curved lanes.

    A box side holds a lateral extreme inside only where it runs along the lane: rings
    are sampled for boxes within 60 degrees of their curved lane's heading.
    """
    # A box inside the grown lane holds its extremes at its corners (or inside its sides).
    cut = ~shapely.contains_properly(graph.match_polygons[lane_idx], polys[box_idx])
    along = np.abs(np.cos(boxes.yaw_rad[box_idx] - heading_rad)) > _ALONG_COS
    bent_mask = ~graph.straight[lane_idx] & along
    plain = (~cut & ~bent_mask).nonzero()[0]
    crossing = (cut & ~bent_mask).nonzero()[0]
    bent = bent_mask.nonzero()[0]
    rings = box_ring(boxes, np.arange(len(boxes.x_m)))[box_idx]  # once per box
    corners = rings[:, :4]
    # Where a box edge leaves the grown lane, the lattice points beside the cut stand in
    # for it (the lane outline inside the box lies between such cuts).
    cuts, cut_row = outline_crossings(graph, corners[cut], lane_idx[cut])
    cut_owner = cut.nonzero()[0][cut_row]
    snapped = lattice_neighbours(boxes, box_idx[cut_owner], cuts)
    ring = rings[bent].reshape(-1, 2)
    points = np.concatenate(
        [
            corners[plain].reshape(-1, 2),
            corners[crossing].reshape(-1, 2),
            snapped.reshape(-1, 2),
            ring,
        ]
    )
    owner = np.concatenate(
        [
            plain.repeat(4),
            crossing.repeat(4),
            cut_owner.repeat(2),
            bent.repeat(RING_POINTS),
        ]
    )
    tested = np.ones(len(points), dtype=np.bool_)
    tested[: 4 * len(plain)] = False
    return _Candidates(points, owner, tested, bent, cut)


def _regions(  # noqa: PLR0917 - the pairs' arrays
    graph: PreparedGraph,
    boxes: BoxArrays,
    polys: np.ndarray,
    box_idx: IntArray,
    lane_idx: IntArray,
    centre_s: FloatArray,
    c: _Candidates,
) -> tuple[BoolArray, FloatArray, FloatArray, FloatArray, FloatArray]:
    """Per pair: whether it has a region, and its lon / lat ranges (ad-map's ``addLaneRegions``).

    A region needs one point inside the lane (lat in [0, 1], not beyond a lane end by
    more than 0.1 m); every matching point widens it, lat clamped to the borders.
    """
    # Curved borders are searched only near the box centre's station (scaled from the
    # centre line to each border).
    length = graph.centre_length_m[lane_idx]
    fraction = centre_s / np.where(length > 0.0, length, 1.0)
    borders = np.stack([lane_idx, lane_idx + len(graph.straight)])
    near = fraction * graph.borders.length_m[borders]
    half_diagonal = np.max(np.hypot(boxes.length_m, boxes.width_m), initial=0.0) / 2.0
    reach = _REACH_FACTOR * float(half_diagonal) + _REACH_MARGIN_M
    lon, lat, dist = ad_map_positions(graph, lane_idx[c.owner], c.points, near[:, c.owner], reach)
    member = ~c.tested | matches_point(dist)
    end = (lon <= _END_TOL) | (lon >= 1.0 - _END_TOL)
    actual = member & (lat >= 0.0) & (lat <= 1.0) & ~(end & (dist >= _END_MATCH_M))
    p = len(lane_idx)
    has = np.zeros(p, dtype=np.bool_)
    has[c.owner[actual]] = True
    # A lane narrower than the box crossing it holds lattice points between the cuts
    # (not evaluated): its region exists when the box reaches into the lane itself.
    unsure = (~has & c.cut).nonzero()[0]
    has[unsure] = shapely.intersects(polys[box_idx[unsure]], graph.polygons[lane_idx[unsure]])
    lon_min, lon_max = np.full(p, np.inf), np.full(p, -np.inf)
    lat_min, lat_max = np.full(p, np.inf), np.full(p, -np.inf)
    o, lon_m, lat_m = c.owner[member], lon[member], np.clip(lat[member], 0.0, 1.0)
    np.minimum.at(lon_min, o, lon_m)
    np.maximum.at(lon_max, o, lon_m)
    np.minimum.at(lat_min, o, lat_m)
    np.maximum.at(lat_max, o, lat_m)
    if c.bent.size:
        k = RING_POINTS * c.bent.size
        ext = edge_extremes(lat[-k:].reshape(-1, RING_POINTS), member[-k:].reshape(-1, RING_POINTS))
        lo_rows, hi_rows = np.flatnonzero(np.isfinite(ext.lo)), np.flatnonzero(np.isfinite(ext.hi))
        rows = np.concatenate([lo_rows, hi_rows])
        pair = c.bent[rows]
        side = np.concatenate([ext.lo_side[lo_rows], ext.hi_side[hi_rows]])
        back = np.concatenate([ext.lo_back[lo_rows], ext.hi_back[hi_rows]])
        points = side_lattice(boxes, box_idx[pair], side, back, _SIDE_STEPS)
        owner = np.repeat(pair, points.shape[1])
        _, lat_s, dist_s = ad_map_positions(
            graph, lane_idx[owner], points.reshape(-1, 2), near[:, owner], reach
        )
        ok = matches_point(dist_s)
        lat_s = np.clip(lat_s, 0.0, 1.0)
        lo_n = len(lo_rows) * points.shape[1]
        np.minimum.at(lat_min, owner[:lo_n][ok[:lo_n]], lat_s[:lo_n][ok[:lo_n]])
        np.maximum.at(lat_max, owner[lo_n:][ok[lo_n:]], lat_s[lo_n:][ok[lo_n:]])
    return has, np.clip(lon_min, 0.0, 1.0), np.clip(lon_max, 0.0, 1.0), lat_min, lat_max


def match_boxes(graph: PreparedGraph, boxes: BoxArrays) -> Matches:
    """Occupied regions of every box in every lane it overlaps (see module docstring)."""
    n = len(boxes.x_m)
    polys = box_polygons(boxes)
    # envelopes from the tree, then the prepared lane polygons decide (faster than the
    # tree's predicate, which prepares each box instead)
    box_idx, lane_idx = graph.match_tree.query(polys)
    touch = shapely.intersects(graph.match_polygons[lane_idx], polys[box_idx])
    box_idx, lane_idx = box_idx[touch], lane_idx[touch]
    by_box = np.argsort(box_idx, kind="stable")
    box_idx, lane_idx = box_idx[by_box], lane_idx[by_box]
    centres = shapely.points(boxes.x_m, boxes.y_m)  # once per box
    centre_s, pair_heading = _centre_station(graph, lane_idx, centres[box_idx])
    candidates = _candidates(graph, boxes, polys, box_idx, lane_idx, pair_heading)
    has, lon_min, lon_max, lat_min, lat_max = _regions(
        graph, boxes, polys, box_idx, lane_idx, centre_s, candidates
    )
    box_idx, lane_idx = box_idx[has], lane_idx[has]
    centre_s, pair_heading = centre_s[has], pair_heading[has]
    length = graph.centre_length_m[lane_idx]
    safe_len = np.where(length > 0, length, 1.0)
    # only a box on several lanes chooses among them (by the centre's distance to each)
    shared = (np.bincount(box_idx, minlength=n)[box_idx] > 1).nonzero()[0]
    outside = np.zeros(len(box_idx))
    outside[shared] = shapely.distance(centres[box_idx[shared]], graph.polygons[lane_idx[shared]])
    misaligned = 1.0 - np.abs(np.cos(boxes.yaw_rad[box_idx] - pair_heading))
    score = outside + _MISALIGNED_M * misaligned
    anchor = np.full(n, -1, dtype=np.int64)
    anchor_s = np.zeros(n)
    order = np.lexsort((score, box_idx))
    first = np.ones(len(order), dtype=np.bool_)
    first[1:] = box_idx[order][1:] != box_idx[order][:-1]
    best = order[first]
    anchor[box_idx[best]] = lane_idx[best]
    anchor_s[box_idx[best]] = np.clip(centre_s[best] / safe_len[best], 0.0, 1.0)
    heading = np.zeros(n)
    heading[box_idx[best]] = pair_heading[best]
    return Matches(
        box=box_idx.astype(np.int64),
        lane=lane_idx.astype(np.int64),
        lon_min=lon_min[has],
        lon_max=lon_max[has],
        lat_min=lat_min[has],
        lat_max=lat_max[has],
        anchor=anchor,
        anchor_s=anchor_s,
        anchor_heading_rad=heading,
        heading_rad=pair_heading,
        starts=box_idx.searchsorted(np.arange(n + 1)).tolist(),
    )


def match_route(
    graph: PreparedGraph, xy_m: FloatArray, yaw_rad: FloatArray
) -> list[tuple[int, bool]]:
    """Lanes a planned path runs through, in order, as ``(lane, forward)`` steps.

    Args:
        graph: The prepared lane graph.
        xy_m: ``(K, 2)`` waypoints.
        yaw_rad: ``(K,)`` waypoint headings.

    Each waypoint picks, among the lanes containing it, the one whose direction agrees
    best with the waypoint heading; no lane appears twice (a return to a lane drops the detour).
    """
    if len(xy_m) == 0:
        return []
    point_idx, lane_idx = graph.tree.query(shapely.points(xy_m), predicate="intersects")
    if point_idx.size == 0:
        return []
    s = shapely.line_locate_point(graph.centre_lines[lane_idx], shapely.points(xy_m[point_idx]))
    heading = lane_heading(graph, lane_idx, s)
    agree = np.cos(yaw_rad[point_idx] - heading)
    order = np.lexsort((-np.abs(agree), point_idx))
    steps: list[tuple[int, bool]] = []
    last = -1
    for k in order:
        if point_idx[k] == last:
            continue
        last = int(point_idx[k])
        step = (int(lane_idx[k]), bool(agree[k] >= 0.0))
        lanes = [lane for lane, _ in steps]  # back on a lane passed before: drop the detour
        steps = steps[: lanes.index(step[0]) + 1] if step[0] in lanes else [*steps, step]
    return steps
