r"""ad-map's nearest point on a polyline (with its tie rule) and its lane-width rule.

**Nearest point** (``point::findNearestPointOnEdge``): ad-map scans a border's segments
in *its* point order and a later segment replaces the current one only when it is nearer
by ad-physics' distance tolerance (1 mm). Of segments within 1 mm of the nearest, the
first in ad-map's order thus wins; where ad-map's order runs against ours, that is our
*last* one::

    ours     s0 ──▶ s1 ──▶ s2        s1, s2 within 1 mm of the nearest distance:
    ad-map   s2 ◀── s1 ◀── s0        ours picks s1, ad-map s2 (its first)

**Lane widths** (``point::calculateWidthRange``, once per lane when ad-map builds its
map): at parametric stations ``0, h, 2h, ... , 1`` in ad-map's point order (``h`` =
``max(0.01, 1 / mean border length)``, ≈ 1 m, added up step by step, the last one
clamped to 1) the border points at that fraction of each border's length are averaged;
this middle is projected onto both borders and the width is the distance between the two
projections; the range is taken value by value with ad-physics' tolerant comparison
(:func:`range_of`)::

    left border   ──l────l'──────▶
                     \\   |          c = (l + r) / 2, l' and r' its nearest points
                      c  |          width = |l' - r'|   (not |l - r|, which is larger
                       \\ |          wherever the two border fractions drift apart)
    right border  ───────r'──r───▶
"""

from __future__ import annotations

import itertools
from typing import TYPE_CHECKING

import numpy as np
import shapely

from rss.scene.polylines import Polylines, interpolate, polylines

if TYPE_CHECKING:
    from rss.arrays import BoolArray, FloatArray, IntArray

__all__ = [
    "DISTANCE_TOL_M",
    "columns",
    "flat_runs",
    "lane_widths",
    "nearest_in_windows",
    "nearest_on_lines",
    "range_of",
    "segment_window",
    "segments",
]

#: ad-physics compares distances with this tolerance (``Distance::cPrecisionValue``).
DISTANCE_TOL_M = 1e-3
#: ad-map's parametric step of the width stations: ``1 / length``, at least this.
_MIN_WIDTH_STEP = 0.01
#: Lanes up to this mean border length [m] get the stations 0, 0.5 and 1.
_SHORT_LANE_M = 1.0


def flat_runs(first: IntArray, count: IntArray) -> tuple[IntArray, IntArray]:
    """``(row, item)`` of all items ``first[r] .. first[r] + count[r] - 1``, row after row."""
    starts = count.cumsum() - count
    item = np.arange(int(count.sum())) + (first - starts).repeat(count)
    return np.arange(len(first)).repeat(count), item


def columns(*arrays: FloatArray) -> FloatArray:
    """``arrays`` (all of one shape ``S``) side by side: ``S + (K,)``.

    ``np.stack(arrays, axis=-1)`` without its overhead (a few microseconds a call, which
    add up on the small arrays of one frame).
    """
    out = np.empty((*arrays[0].shape, len(arrays)), dtype=np.result_type(*arrays))
    for k, a in enumerate(arrays):
        out[..., k] = a
    return out


#: Columns of the table of :func:`segments`.
_X, _Y, _DX, _DY, _DD, _S_AT, _SEG_LEN = range(7)


def segments(lines: Polylines) -> FloatArray:
    """``(V, 7)`` table of ``lines``: per vertex, the segment starting there.

    Columns: ``x``, ``y``, the step ``dx``, ``dy`` to the next vertex, the squared segment
    length (1 where it is 0), the arc length at the vertex and the segment length (0 at a
    line's last vertex, as ``Polylines.segment_m``). One row per segment, so that a search
    gathers each segment at once.
    """
    xy = lines.xy_m
    out = np.zeros((len(xy), 7))
    out[:, _X], out[:, _Y] = xy[:, 0], xy[:, 1]
    out[:-1, _DX] = xy[1:, 0] - xy[:-1, 0]
    out[:-1, _DY] = xy[1:, 1] - xy[:-1, 1]
    length = lines.segment_m
    out[:, _DD] = np.where(length > 0.0, length * length, 1.0)
    out[:, _S_AT], out[:, _SEG_LEN] = lines.s_at_m, length
    return out


def segment_window(
    lines: Polylines, which: IntArray, near_m: FloatArray | None = None, reach_m: float = 0.0
) -> tuple[IntArray, IntArray]:
    """First and last segment ``(Q,)`` each of lines ``which`` to search.

    All segments of each line, or those within ``reach_m`` of arc lengths ``near_m``
    ``(Q,)`` when given. Segments are named by their start vertex in ``lines``.
    """
    first = lines.start[which]
    last = lines.start[which + 1] - 2  # last segment
    if near_m is not None:
        base = lines.offset_m[which]
        lo = lines.global_m.searchsorted(base + near_m - reach_m, side="right") - 1
        hi = lines.global_m.searchsorted(base + near_m + reach_m, side="left")
        first, last = (
            np.minimum(np.maximum(lo, first), last),
            np.minimum(np.maximum(hi, first), last),
        )
    return first, last


def nearest_on_lines(  # noqa: PLR0917 - the kernel's inputs, all arrays
    lines: Polylines,
    steps: FloatArray,
    which: IntArray,
    points: FloatArray,
    backwards: BoolArray | None,
    near_m: FloatArray | None = None,
    reach_m: float = 0.0,
) -> tuple[FloatArray, FloatArray]:
    """Nearest points of ``points`` ``(Q, 2)`` on ``lines`` ``which`` ``(Q,)``, ad-map's tie rule.

    :func:`nearest_in_windows` on the :func:`segment_window` of each row.

    Args:
        lines: The polylines.
        steps: ``segments(lines)``.
        which: ``(Q,)`` line of each point.
        points: ``(Q, 2)`` points.
        backwards: ``(Q,)`` ad-map's point order of the row's line runs against ours
            (``None``: never).
        near_m: Optional ``(Q,)`` arc lengths near which the nearest points lie.
        reach_m: See ``near_m``.

    Returns:
        ``(Q,)`` arc lengths [m] of the nearest points and the ``(Q, 2)`` points.
    """
    first, last = segment_window(lines, which, near_m, reach_m)
    return nearest_in_windows(steps, points, backwards, first, last)


def nearest_in_windows(
    steps: FloatArray,
    points: FloatArray,
    backwards: BoolArray | None,
    first: IntArray,
    last: IntArray,
) -> tuple[FloatArray, FloatArray]:
    """Nearest points of ``points`` ``(Q, 2)`` among segments ``first..last`` ``(Q,)``.

    All candidate segments of all rows are tried at once (one flat run per row; an empty
    window counts as its first segment). Of segments within 1 mm of the nearest, the
    first in ad-map's order counts: our first, or our last on rows whose line ad-map holds
    ``backwards``.

    Args:
        steps: ``segments(lines)``.
        points: ``(Q, 2)`` points.
        backwards: ``(Q,)`` ad-map's point order of the row's line runs against ours
            (``None``: never).
        first: ``(Q,)`` first segment of each row (its start vertex in ``lines``).
        last: ``(Q,)`` last segment of each row.

    Returns:
        ``(Q,)`` arc lengths [m] of the nearest points and the ``(Q, 2)`` points.
    """
    count = np.maximum(last - first + 1, 1)
    starts = count.cumsum() - count
    n = int(count.sum())
    seg = np.arange(n) + (first - starts).repeat(count)
    g = steps[seg]
    ax, ay, dx, dy = g[:, _X], g[:, _Y], g[:, _DX], g[:, _DY]
    p = points.repeat(count, axis=0)
    rx, ry = p[:, 0] - ax, p[:, 1] - ay
    t = (rx * dx + ry * dy) / g[:, _DD]
    t = np.minimum(np.maximum(t, 0.0), 1.0)
    ox, oy = rx - dx * t, ry - dy * t
    dist2 = ox * ox + oy * oy
    limit = np.sqrt(np.minimum.reduceat(dist2, starts)) + DISTANCE_TOL_M
    index = np.arange(n)
    if backwards is not None:  # the smallest negated index is the last one
        index = np.where(backwards.repeat(count), -index, index)
    candidate = np.where(dist2 < (limit * limit).repeat(count), index, n)
    best = np.abs(np.minimum.reduceat(candidate, starts))
    tb = t[best]
    b = steps[seg[best]]
    foot = columns(b[:, _X] + b[:, _DX] * tb, b[:, _Y] + b[:, _DY] * tb)
    return b[:, _S_AT] + tb * b[:, _SEG_LEN], foot


def range_of(values: list[float]) -> tuple[float, float]:
    """ad-map's range of ``values`` taken one by one (``unionRangeWith``).

    ``std::min`` / ``std::max`` with ad-physics' tolerant ``<``: a value replaces the
    current bound only when beyond it by at least 1 mm, so a slow drift stops up to 1 mm
    short of the true extreme.
    """
    lo = hi = values[0]
    for v in values[1:]:
        if lo - v >= DISTANCE_TOL_M:
            lo = v
        if v - hi >= DISTANCE_TOL_M:
            hi = v
    return lo, hi


def _stations(length_m: float) -> FloatArray:
    """ad-map's parametric width stations of a lane of mean border length ``length_m``."""
    if length_m <= _SHORT_LANE_M:
        return np.array([0.0, 0.5, 1.0])
    step = max(_MIN_WIDTH_STEP, 1.0 / length_m)
    steps = np.add.accumulate(np.full(int(1.0 / step) + 2, step))  # summed one by one
    out: FloatArray = np.concatenate([[0.0], steps[steps < 1.0], [1.0]])
    return out


#: (point, segment) pairs tried at once by :func:`lane_widths` (bounds its peak memory).
_WIDTH_PAIRS = 1 << 20


def _nearest_in_pieces(lines: Polylines, which: IntArray, points: FloatArray) -> FloatArray:
    """:func:`nearest_on_lines` (no tie reversal), rows taken in pieces of bounded pairs.

    Every row is searched on its whole line: a long map has many width stations on lines
    of many segments, so all at once would hold every (point, segment) pair.
    """
    if not len(which):
        return np.zeros(0)
    steps = segments(lines)
    first, last = segment_window(lines, which)
    pairs = np.cumsum(last - first + 1)
    cuts = np.searchsorted(pairs, np.arange(_WIDTH_PAIRS, int(pairs[-1]), _WIDTH_PAIRS))
    out = [
        nearest_in_windows(steps, points[a:b], None, first[a:b], last[a:b])[0]
        for a, b in itertools.pairwise([0, *np.unique(cuts).tolist(), len(which)])
        if b > a
    ]
    return np.concatenate(out)


def lane_widths(
    left_m: tuple[FloatArray, ...], right_m: tuple[FloatArray, ...], backwards: BoolArray
) -> tuple[list[FloatArray], list[FloatArray]]:
    """ad-map's lane widths at its stations (see module docstring), all lanes at once.

    Args:
        left_m: ``L`` left borders in our point order, each ``(K, 2)``.
        right_m: ``L`` right borders, each ``(M, 2)``.
        backwards: ``(L,)`` ad-map's point order runs against ours.

    Returns:
        Per lane, the stations in *our* parametric direction (increasing, 0 to 1) and the
        widths [m] there, each ``(W,)``; ad-map's range is :func:`range_of` the widths in
        ad-map's order.
    """
    n = len(left_m)
    flip = [bool(b) for b in backwards]
    lines = polylines(
        np.array(
            [
                shapely.LineString(line[::-1] if flip[i % n] else line)
                for i, line in enumerate((*left_m, *right_m))
            ],
            dtype=object,
        )
    )
    length = lines.length_m
    at = [_stations(0.5 * (length[i] + length[n + i])) for i in range(n)]
    count = np.array([len(a) for a in at])
    lane = np.repeat(np.arange(n), count)
    t = np.concatenate(at)
    both = np.concatenate([lane, lane + n])
    ends = interpolate(lines, both, np.concatenate([t, t]) * length[both])
    q = len(t)
    centre = 0.5 * (ends[:q] + ends[q:])
    s = _nearest_in_pieces(lines, both, np.concatenate([centre, centre]))
    feet = interpolate(lines, both, s)
    width = np.hypot(*(feet[:q] - feet[q:]).T)
    split = np.cumsum(count)[:-1]
    ts, ws = np.split(t, split), np.split(width, split)
    for i in range(n):
        if flip[i]:
            ts[i], ws[i] = 1.0 - ts[i][::-1], ws[i][::-1]
    return ts, ws
