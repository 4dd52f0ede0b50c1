"""Points along many polylines at once (flat numpy arrays, no per-line objects).

The lane centre lines of a map are stored once as one vertex array with offsets; every
query is a ``(line, arc length)`` pair, so one call serves all pairs of a frame. The
kernel follows GEOS' ``line_interpolate_point``: arc lengths are summed segment by
segment, a position falls in the first segment whose end lies beyond it, and positions
are clamped to the line (projection stays with ``shapely.line_locate_point``, which is
faster than a numpy version over ragged segment lists)::

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
    from rss.arrays import FloatArray, IntArray

__all__ = ["Polylines", "heading_at", "interpolate", "polylines"]


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


def interpolate(lines: Polylines, which: IntArray, s_m: FloatArray) -> FloatArray:
    """Points at arc lengths ``s_m`` ``(Q,)`` (clamped to the line) on lines ``which``.

    Returns:
        ``(Q, 2)`` points.
    """
    first = lines.start[which]
    last = lines.start[which + 1] - 1
    s = np.minimum(np.maximum(s_m, 0.0), lines.length_m[which])
    k = lines.global_m.searchsorted(lines.offset_m[which] + s, side="right") - 1
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
