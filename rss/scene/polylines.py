"""Linear referencing on many polylines at once (flat numpy arrays, no per-line objects).

The lane centre lines of a map are stored once as one vertex array with offsets; every
query is a ``(line, value)`` pair, so one call serves all pairs of a frame. The kernels
follow GEOS' linear referencing (``line_locate_point`` / ``line_interpolate_point``):
the nearest segment wins (the first one on ties), arc lengths are summed segment by
segment, and positions are clamped to the line::

    line l:  xy[start[l]] ──seg──▶ xy[start[l] + 1] ──seg──▶ ... xy[start[l + 1] - 1]
    s:       s_at[start[l]] = 0      s_at[...] = |seg 0|          s_at[...] = length[l]

``shapely`` stays the slow, obvious reference (``tests/rss/scene/test_matching_polylines.py``).
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np
import shapely

if TYPE_CHECKING:
    from rss.batch import FloatArray, IntArray

__all__ = ["Polylines", "heading_at", "interpolate", "locate", "polylines"]


@dataclass(frozen=True)
class Polylines:
    """``L`` polylines with ``V`` vertices in total.

    Attributes:
        xy_m: ``(V, 2)`` vertices, line after line.
        start: ``(L + 1,)`` vertex offsets: line ``l`` is ``xy_m[start[l]:start[l + 1]]``.
        s_at_m: ``(V,)`` arc length at each vertex along its line.
        segment_m: ``(V,)`` length of the segment starting at each vertex (0 at a line's
            last vertex).
        length_m: ``(L,)`` line lengths.
        global_m: ``(V,)`` ``s_at_m`` shifted per line so that lines do not overlap (only
            to find segments with one ``searchsorted``).
        offset_m: ``(L,)`` the shift of each line in ``global_m``.
    """

    xy_m: FloatArray
    start: IntArray
    s_at_m: FloatArray
    segment_m: FloatArray
    length_m: FloatArray
    global_m: FloatArray
    offset_m: FloatArray


def polylines(lines: np.ndarray) -> Polylines:
    """Flatten ``(L,)`` shapely line strings (each with at least two vertices)."""
    coords, which = shapely.get_coordinates(lines, return_index=True)
    count = len(lines)
    start = np.searchsorted(which, np.arange(count + 1)).astype(np.int64)
    d = np.diff(coords, axis=0)
    seg = np.sqrt(d[:, 0] * d[:, 0] + d[:, 1] * d[:, 1])
    seg = np.append(seg, 0.0)
    last = start[1:] - 1
    seg[last] = 0.0
    s_at = np.zeros(len(coords))
    length = np.zeros(count)
    for line in range(count):
        a, b = int(start[line]), int(start[line + 1])
        s_at[a + 1 : b] = np.add.accumulate(seg[a : b - 1])
        length[line] = s_at[b - 1]
    offset = np.concatenate([[0.0], np.cumsum(length + 1.0)[:-1]])
    return Polylines(
        xy_m=coords,
        start=start,
        s_at_m=s_at,
        segment_m=seg,
        length_m=length,
        global_m=s_at + np.repeat(offset, np.diff(start)),
        offset_m=offset,
    )


def _point_segment_distance(p: FloatArray, a: FloatArray, b: FloatArray) -> FloatArray:
    """Distance of points ``p`` to segments ``a``-``b``, all ``(Q, 2)``."""
    d = b - a
    len2 = d[:, 0] * d[:, 0] + d[:, 1] * d[:, 1]
    safe = np.where(len2 > 0.0, len2, 1.0)
    r = ((p[:, 0] - a[:, 0]) * d[:, 0] + (p[:, 1] - a[:, 1]) * d[:, 1]) / safe
    cross = ((a[:, 1] - p[:, 1]) * d[:, 0] - (a[:, 0] - p[:, 0]) * d[:, 1]) / safe
    to_a = p - a
    to_b = p - b
    dist_a = np.sqrt(to_a[:, 0] * to_a[:, 0] + to_a[:, 1] * to_a[:, 1])
    dist_b = np.sqrt(to_b[:, 0] * to_b[:, 0] + to_b[:, 1] * to_b[:, 1])
    inner = np.abs(cross) * np.sqrt(len2)
    out: FloatArray = np.where(
        (len2 == 0.0) | (r <= 0.0), dist_a, np.where(r >= 1.0, dist_b, inner)
    )
    return out


def locate(lines: Polylines, which: IntArray, points_m: FloatArray) -> FloatArray:
    """Arc length of the point nearest to each of ``points_m`` ``(Q, 2)`` on line ``which``.

    Returns:
        ``(Q,)`` arc lengths in [0, line length].
    """
    q = len(which)
    if q == 0:
        return np.zeros(0)
    first = lines.start[which]
    counts = lines.start[which + 1] - first - 1
    group = np.repeat(np.arange(q), counts)
    group_start = np.concatenate([[0], np.cumsum(counts)[:-1]])
    seg = first[group] + np.arange(len(group)) - group_start[group]
    p = points_m[group]
    dist = _point_segment_distance(p, lines.xy_m[seg], lines.xy_m[seg + 1])
    best = np.minimum.reduceat(dist, group_start)
    hit = np.flatnonzero((dist == best[group]) | np.isnan(best[group]))
    first_hit = np.ones(len(hit), dtype=np.bool_)
    first_hit[1:] = group[hit[1:]] != group[hit[:-1]]
    k = seg[hit[first_hit]]
    a, b, pt = lines.xy_m[k], lines.xy_m[k + 1], points_m
    d = b - a
    len2 = d[:, 0] * d[:, 0] + d[:, 1] * d[:, 1]
    factor = ((pt[:, 0] - a[:, 0]) * d[:, 0] + (pt[:, 1] - a[:, 1]) * d[:, 1]) / np.where(
        len2 > 0.0, len2, 1.0
    )
    factor = np.where(np.all(pt == a, axis=1), 0.0, np.where(np.all(pt == b, axis=1), 1.0, factor))
    seg_len = lines.segment_m[k]
    out: FloatArray = lines.s_at_m[k] + np.where(
        factor <= 0.0, 0.0, np.where(factor <= 1.0, factor * seg_len, seg_len)
    )
    return out


def interpolate(lines: Polylines, which: IntArray, s_m: FloatArray) -> FloatArray:
    """Points at arc lengths ``s_m`` ``(Q,)`` (clamped to the line) on lines ``which``.

    Returns:
        ``(Q, 2)`` points.
    """
    first = lines.start[which]
    last = lines.start[which + 1] - 1
    s = np.minimum(np.maximum(s_m, 0.0), lines.length_m[which])
    k = np.searchsorted(lines.global_m, lines.offset_m[which] + s, side="right") - 1
    k = np.clip(k, first, last - 1)
    # GEOS walks forward to the first segment whose end lies beyond s (the shifted search
    # may land one segment off when s is within rounding of a vertex).
    k = np.where((lines.s_at_m[k] > s) & (k > first), k - 1, k)
    k = np.where((lines.s_at_m[k] + lines.segment_m[k] <= s) & (k < last - 1), k + 1, k)
    seg_len = lines.segment_m[k]
    frac = (s - lines.s_at_m[k]) / np.where(seg_len > 0.0, seg_len, 1.0)
    a, b = lines.xy_m[k], lines.xy_m[k + 1]
    along = (b - a) * frac[:, None] + a
    out: FloatArray = np.where(
        (frac <= 0.0)[:, None], a, np.where((frac >= 1.0)[:, None], b, along)
    )
    return out


def heading_at(lines: Polylines, which: IntArray, s_m: FloatArray, step_m: float) -> FloatArray:
    """Heading of lines ``which`` at ``s_m``: the chord from ``s - step`` to ``s + step``."""
    length = lines.length_m[which]
    a = interpolate(lines, which, np.clip(s_m - step_m, 0.0, length))
    b = interpolate(lines, which, np.clip(s_m + step_m, 0.0, length))
    d = b - a
    out: FloatArray = np.arctan2(d[:, 1], d[:, 0])
    return out
