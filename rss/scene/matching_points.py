"""Point-level map matching as ad-map does it (``AdMapMatching``), vectorised.

ad-map matches a box by sampling it on a lattice of about 0.1 m (corners included) and
matching every lattice point to every lane within ``MATCH_DISTANCE_M``. A point's
parametric position comes from its nearest points on the two lane borders, not from the
centre line::

    left border   ──────l──────────▶   t_l = arc(l) / length(left)
                        │
                        · point        lat = position along l -> r (0 at l, 1 at r)
                        │              lon = (1 - n) t_l + n t_r,  n = lat clamped to [0, 1]
    right border  ─────────r───────▶   t_r = arc(r) / length(right)

On a curved lane the two border fractions of one cross-section differ (a straight piece
takes a larger share of the inner border than of the outer one), so ``lon`` is not the
centre-line fraction. ``rss.scene.matching`` evaluates only the lattice points that can
hold a region's extremes (see there); this module holds the per-point pieces.
"""

from __future__ import annotations

from typing import TYPE_CHECKING, NamedTuple

import numpy as np

from rss.scene.admap_nearest import DISTANCE_TOL_M, columns, flat_runs
from rss.scene.prepared import MATCH_DISTANCE_M

if TYPE_CHECKING:
    from rss.arrays import BoolArray, FloatArray, IntArray
    from rss.scene.match_records import BoxArrays
    from rss.scene.prepared import PreparedGraph

__all__ = [
    "DISTANCE_TOL_M",
    "RING_POINTS",
    "SideExtremes",
    "ad_map_positions",
    "box_ring",
    "edge_extremes",
    "lattice_neighbours",
    "matches_point",
    "outline_crossings",
    "side_lattice",
]

#: ad-map's lattice step never drops below 0.1 m.
_MIN_STRIDE_M = 0.1
_INTEGRAL_TOL = 1e-6


def ad_map_positions(
    graph: PreparedGraph,
    lanes: IntArray,
    points: FloatArray,
    near_m: FloatArray | None = None,
    reach_m: float = 0.0,
) -> tuple[FloatArray, FloatArray, FloatArray]:
    """ad-map's parametric position of ``points`` ``(Q, 2)`` in ``lanes`` ``(Q,)``.

    Args:
        graph: The prepared lane graph.
        lanes: ``(Q,)`` lane of each point.
        points: ``(Q, 2)`` points (map frame).
        near_m: Optional ``(2, Q)`` arc lengths on the left / right border near which the
            nearest points lie (e.g. ``border_stations`` of a nearby point): only border
            segments within ``reach_m`` of them are searched.
        reach_m: See ``near_m``.

    Returns:
        ``(lon, lat, dist_m)``, each ``(Q,)``: ``lon`` in [0, 1] along the lane's point
        order, ``lat`` unclamped (< 0 left of the lane, > 1 right of it), ``dist_m`` the
        distance to the matched point (0 inside the lane).
    """
    q = len(lanes)
    both = np.concatenate([lanes, lanes + len(graph.straight)])  # left, then right borders
    hint = None if near_m is None else near_m.reshape(-1)
    s, feet = graph.border_index.nearest(both, np.concatenate([points, points]), hint, reach_m)
    s_l, s_r, l_xy, r_xy = s[:q], s[q:], feet[:q], feet[q:]
    d = r_xy - l_xy
    dd = d[:, 0] * d[:, 0] + d[:, 1] * d[:, 1]
    rel = points - l_xy
    lat = (rel[:, 0] * d[:, 0] + rel[:, 1] * d[:, 1]) / np.where(dd > 0.0, dd, 1.0)
    n = np.clip(lat, 0.0, 1.0)
    len_l, len_r = graph.borders.length_m[both[:q]], graph.borders.length_m[both[q:]]
    t_l = s_l / np.where(len_l > 0.0, len_l, 1.0)
    t_r = s_r / np.where(len_r > 0.0, len_r, 1.0)
    off = rel - d * n[:, None]
    return (1.0 - n) * t_l + n * t_r, lat, np.hypot(off[:, 0], off[:, 1])


def matches_point(dist_m: FloatArray) -> BoolArray:
    """Whether points ``dist_m`` from their matched point match the lane (ad-map's test)."""
    out: BoolArray = dist_m < MATCH_DISTANCE_M + DISTANCE_TOL_M
    return out


def _frame(boxes: BoxArrays, box_idx: IntArray) -> tuple[FloatArray, FloatArray, FloatArray]:
    """Front-left corners and the unit vectors forward and to the left, ``(P, 2)`` each."""
    c, s = np.cos(boxes.yaw_rad[box_idx]), np.sin(boxes.yaw_rad[box_idx])
    along = columns(c, s)
    left = columns(-s, c)
    centre = columns(boxes.x_m[box_idx], boxes.y_m[box_idx])
    half = columns(boxes.length_m[box_idx], boxes.width_m[box_idx]) / 2.0
    front_left: FloatArray = centre + along * half[:, :1] + left * half[:, 1:]
    return front_left, along, left


def lattice_neighbours(boxes: BoxArrays, box_idx: IntArray, points: FloatArray) -> FloatArray:
    """The two points of ad-map's box lattice beside each of ``points`` on a box edge.

    ad-map steps from the front-left corner backwards by ``length / ceil(length / 0.1)``
    and to the right by ``width / ceil(width / 0.1)``, both far edges included.

    Args:
        boxes: The boxes.
        box_idx: ``(Q,)`` the box of each point.
        points: ``(Q, 2)`` points on the edges of their boxes.

    Returns:
        ``(Q, 2, 2)`` the lattice points before and after each point along its edge.
    """
    front_left, along, left = _frame(boxes, box_idx)
    length, width = boxes.length_m[box_idx], boxes.width_m[box_idx]
    n_l, n_w = np.ceil(length / _MIN_STRIDE_M), np.ceil(width / _MIN_STRIDE_M)
    step_l, step_w = length / n_l, width / n_w
    rel = front_left - points
    i = np.clip((rel * along).sum(axis=1) / step_l, 0.0, n_l)
    j = np.clip((rel * left).sum(axis=1) / step_w, 0.0, n_w)
    on_i = (np.abs(i) < _INTEGRAL_TOL) | (np.abs(i - n_l) < _INTEGRAL_TOL)
    i = np.where(on_i, np.round(i), i)
    # along a front / rear edge (i fixed) step in j, along a side edge step in i
    ii = np.where(on_i[:, None], i[:, None], columns(np.floor(i), np.ceil(i)))
    jj = np.where(on_i[:, None], columns(np.floor(j), np.ceil(j)), j[:, None])
    out: FloatArray = (
        front_left[:, None, :]
        - (ii * step_l[:, None])[..., None] * along[:, None, :]
        - (jj * step_w[:, None])[..., None] * left[:, None, :]
    )
    return out


#: The corner after each corner round a box.
_NEXT_CORNER = np.array([1, 2, 3, 0])
#: Ring points of ``box_ring`` along the right and the left side of a box (rear-ward and
#: front-ward), both ends included.
_SIDES = np.array([[1, 4, 5, 6, 2], [3, 7, 8, 9, 0]])
RING_POINTS = 10


def outline_crossings(
    graph: PreparedGraph, corners: FloatArray, lanes: IntArray
) -> tuple[FloatArray, IntArray]:
    """Where the edges of boxes cross the outlines of their grown lanes.

    Args:
        graph: The prepared lane graph.
        corners: ``(C, 4, 2)`` box corners in order round each box.
        lanes: ``(C,)`` the lane of each box.

    Returns:
        ``(K, 2)`` crossing points and ``(K,)`` the box (row of ``corners``) of each.
    """
    rings = graph.match_outlines
    first = rings.start[lanes]
    count = rings.start[lanes + 1] - first - 1
    row, seg = flat_runs(first, count)
    # envelopes of the outline segments against the boxes' envelopes
    bounds = graph.match_outline_bounds[seg]  # (K, 4) min x, min y, max x, max y
    lo = corners.min(axis=1).repeat(count, axis=0)
    hi = corners.max(axis=1).repeat(count, axis=0)
    near = ((bounds[:, :2] <= hi) & (bounds[:, 2:] >= lo)).all(axis=1)
    row, seg = row[near], seg[near]
    p, q = rings.xy_m[seg][:, None], rings.xy_m[seg + 1][:, None]  # (N, 1, 2)
    a = corners[row]  # (N, 4, 2)
    e = a[:, _NEXT_CORNER] - a
    f, g = q - p, p - a
    denom = e[..., 0] * f[..., 1] - e[..., 1] * f[..., 0]
    safe = np.where(denom != 0.0, denom, 1.0)
    t = (g[..., 0] * f[..., 1] - g[..., 1] * f[..., 0]) / safe
    u = (g[..., 0] * e[..., 1] - g[..., 1] * e[..., 0]) / safe
    hit = (denom != 0.0) & (t >= 0.0) & (t <= 1.0) & (u >= 0.0) & (u <= 1.0)
    k, edge = hit.nonzero()
    return a[k, edge] + t[k, edge][:, None] * e[k, edge], row[k]


def _lattice_count(boxes: BoxArrays, box_idx: IntArray) -> FloatArray:
    """Lattice steps along the length of each box (ad-map: ``ceil(length / 0.1)``)."""
    out: FloatArray = np.ceil(boxes.length_m[box_idx] / _MIN_STRIDE_M)
    return out


def box_ring(boxes: BoxArrays, box_idx: IntArray) -> FloatArray:
    """``(P, RING_POINTS, 2)`` samples on the outline of each box (lattice points).

    Points ``0..3`` are the corners front-left, front-right, rear-right, rear-left;
    ``4..6`` and ``7..9`` the lattice points nearest to the quarter points of the right
    and the left side. The ends get no inner samples: a lateral extreme inside them (a
    box across a curved lane) is left to the corners.
    """
    front_left, along, left = _frame(boxes, box_idx)
    length, width = boxes.length_m[box_idx], boxes.width_m[box_idx]
    n_l = _lattice_count(boxes, box_idx)[:, None]
    back = np.floor(_RING_BACK[None] * n_l + 0.5) / n_l
    right = np.array([0.0, 1.0, 1.0, 0.0, 1.0, 1.0, 1.0, 0.0, 0.0, 0.0])
    db = (back * length[:, None])[..., None] * along[:, None, :]
    dr = (right[None] * width[:, None])[..., None] * left[:, None, :]
    out: FloatArray = front_left[:, None, :] - db - dr
    return out


#: Share of the length behind the front of each ``box_ring`` point.
_RING_BACK = np.array([0.0, 0.0, 1.0, 1.0, 0.25, 0.5, 0.75, 0.75, 0.5, 0.25])


def _local_extremes(
    y: FloatArray, member: BoolArray
) -> tuple[FloatArray, FloatArray, FloatArray, FloatArray]:
    """Extremes of samples ``y`` ``(E, K)`` along straight edges, located between samples.

    Around the best inner sample, the parabola through it and its two neighbours (all
    matching) gives the extreme; ``+inf`` / ``-inf`` where the best sample is an end or
    a neighbour does not match (the ends themselves count as points anyway). Also returns
    where the two extremes lie (sample index, fractional; NaN where there is none).
    """
    rows = np.arange(len(y))
    out = []
    where = []
    for sign in (1.0, -1.0):
        v = np.where(member, sign * y, np.inf)
        k = np.argmin(v, axis=1)
        inner = (k > 0) & (k < y.shape[1] - 1)
        k = np.minimum(np.maximum(k, 1), y.shape[1] - 2)
        y0, y1, y2 = v[rows, k - 1], v[rows, k], v[rows, k + 1]
        ok = inner & np.isfinite(y0) & np.isfinite(y2)
        y0, y1, y2 = np.where(ok, y0, 0.0), np.where(ok, y1, 0.0), np.where(ok, y2, 0.0)
        curv = y0 - 2.0 * y1 + y2
        ok &= curv > 0.0
        safe = np.where(ok, curv, 1.0)
        vertex = y1 - (y0 - y2) ** 2 / (8.0 * safe)
        out.append(np.where(ok, sign * vertex, sign * np.inf))
        where.append(np.where(ok, k + (y0 - y2) / (2.0 * safe), np.nan))
    return out[0], out[1], where[0], where[1]


class SideExtremes(NamedTuple):
    """Lateral extremes inside the long sides of box rings, ``(P,)`` each.

    Attributes:
        lo: Smallest ``lat`` (``+inf`` where no side has an inner minimum).
        hi: Largest ``lat`` (``-inf`` where none).
        lo_side: Side holding ``lo``: 0 right, 1 left.
        lo_back: Where on it: share of the length behind the front (NaN where none).
        hi_side: Side holding ``hi``.
        hi_back: Where on it.
    """

    lo: FloatArray
    hi: FloatArray
    lo_side: IntArray
    lo_back: FloatArray
    hi_side: IntArray
    hi_back: FloatArray


def edge_extremes(lat: FloatArray, member: BoolArray) -> SideExtremes:
    """Smallest and largest ``lat`` between the samples of each box ring ``(P, RING_POINTS)``.

    Along a box side over a curved lane the lateral position is smooth but not linear:
    its extreme may lie inside the side (the middle of the side facing the inside of a
    curve). The parabola through the samples locates it only roughly (the lateral
    position bends where the nearest border segments change): :func:`side_lattice` gives
    the lattice points round it.
    """
    lo, hi, lo_at, hi_at = (
        v.reshape(len(lat), 2)
        for v in _local_extremes(lat[:, _SIDES].reshape(-1, 5), member[:, _SIDES].reshape(-1, 5))
    )
    rows = np.arange(len(lat))
    lo_side, hi_side = np.argmin(lo, axis=1), np.argmax(hi, axis=1)
    # the samples of a side lie a quarter of the length apart: rearwards on the right
    # side, frontwards on the left one
    lo_at, hi_at = lo_at[rows, lo_side] / 4.0, hi_at[rows, hi_side] / 4.0
    return SideExtremes(
        lo[rows, lo_side],
        hi[rows, hi_side],
        lo_side,
        np.where(lo_side == 0, lo_at, 1.0 - lo_at),
        hi_side,
        np.where(hi_side == 0, hi_at, 1.0 - hi_at),
    )


def side_lattice(
    boxes: BoxArrays, box_idx: IntArray, side: IntArray, back: FloatArray, steps: int
) -> FloatArray:
    """ad-map's lattice points on a long side of boxes round a place on it.

    Args:
        boxes: The boxes.
        box_idx: ``(Q,)`` the box of each place.
        side: ``(Q,)`` 0 the right side, 1 the left one.
        back: ``(Q,)`` share of the length behind the front.
        steps: Lattice steps taken to either side of the nearest lattice point.

    Returns:
        ``(Q, 2 steps + 1, 2)`` lattice points (clamped to the side's ends).
    """
    front_left, along, left = _frame(boxes, box_idx)
    n_l = _lattice_count(boxes, box_idx)
    i = np.floor(back * n_l + 0.5)[:, None] + np.arange(-steps, steps + 1)[None]
    i = np.clip(i, 0.0, n_l[:, None])
    db = (i * (boxes.length_m[box_idx] / n_l)[:, None])[..., None] * along[:, None, :]
    dr = ((1 - side) * boxes.width_m[box_idx])[:, None, None] * left[:, None, :]
    out: FloatArray = front_left[:, None, :] - db - dr
    return out
