r"""Where ad-map cuts a lane's borders for a cut at parametric ``t``: per-lane tables.

A cut lane's length range is ad-map's (``route::getMetricRanges``): the lengths of the
*projected* border pieces. The centre point ``c(t)`` of parametric position ``t`` is the
midpoint of the border points at fraction ``t`` of each border's length; each border is
cut at the nearest point of ``c(t)`` on it, not at its own fraction ``t``::

    left border   ──l(t)───l'───────▶   l(t), r(t): at fraction t of each border
                            |
                           c(t)          c(t) = (l(t) + r(t)) / 2
                            |
    right border  ─────────r'───r(t)─▶   l', r': nearest points of c(t), where ad-map cuts

On a curve the inner border's piece thus differs from its share ``p1 - p0``. Per lane, a
table from ``t`` to the arc length of both nearest points is built once per map by
:func:`projected_stations` (exact at its stations, linear in between, where the function
is linear); a cut then costs two ``bisect`` lookups (``rss.scene.lane_segments``).
"""

from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np

from rss.scene.polylines import interpolate

if TYPE_CHECKING:
    from rss.arrays import FloatArray, IntArray
    from rss.scene.border_index import BorderIndex
    from rss.scene.polylines import Polylines

__all__ = ["nearest_arcs", "projected_stations"]

#: Tolerance [m] of the table: an interval whose ends agree with both end tangents within
#: it counts as linear; a value within it of a tangent lies on that tangent.
_TOL_M = 1e-6
#: Intervals are split no further than this [m of the longer border]: the nearest point
#: jumps where ad-map switches border segments, and no table resolves a jump exactly.
_MIN_STEP_M = 1e-5
#: Parametric step of the one-sided difference quotients (slopes at stations).
_EPS = 1e-7
#: Refinement rounds at most (a jump's interval halves at least every second round).
_ROUNDS = 64
#: Border segments farther than this [m] (arc length) from an interval's ends are not
#: tried while refining it.
_REACH_M = 2.0
#: Stations in the interior of linear runs are dropped above this deviation [m] only.
_PRUNE_TOL_M = 1e-9
#: Stations closer than this (parametric) are one.
_SAME_T = 1e-12


def nearest_arcs(
    index: BorderIndex,
    lines: IntArray,
    t: FloatArray,
    near_m: FloatArray | None = None,
    reach_m: float = 0.0,
) -> FloatArray:
    """Where ad-map cuts a lane border for centre parametric positions ``t`` (vectorised).

    Args:
        index: The borders.
        lines: ``(Q,)`` border lines: ``l`` the left border of lane ``l``, ``L + l`` its
            right border.
        t: ``(Q,)`` parametric positions along the lane's point order (0..1).
        near_m: Optional ``(Q,)`` arc lengths near which the nearest points lie; only
            border segments within ``reach_m`` of them are tried.
        reach_m: See ``near_m``.

    Returns:
        ``(Q,)`` arc lengths [m] along the border of the nearest points (with
        ad-map's tie rule) of the centre points ``c(t)``.
    """
    borders = index.lines
    n = len(borders.length_m) // 2
    lane = lines % n
    both = np.concatenate([lane, lane + n])
    ends = interpolate(borders, both, np.concatenate([t, t]) * borders.length_m[both])
    q = len(lines)
    centre = 0.5 * (ends[:q] + ends[q:])
    s, _ = index.nearest(lines, centre, near_m, reach_m)
    return s


def _knots(borders: Polylines) -> tuple[IntArray, FloatArray]:
    """``(lane, t)`` of both borders' vertices, sorted per lane (``c(t)`` is linear between)."""
    n = len(borders.length_m) // 2
    lanes, ts = [], []
    for lane in range(n):
        parts = [np.array([0.0, 1.0])]
        for line in (lane, lane + n):
            if borders.length_m[line] > 0.0:
                at = borders.s_at_m[borders.start[line] : borders.start[line + 1]]
                parts.append(at / borders.length_m[line])
        t = np.unique(np.clip(np.concatenate(parts), 0.0, 1.0))
        lanes.append(np.full(len(t), lane))
        ts.append(t)
    return np.concatenate(lanes), np.concatenate(ts)


def _slopes(
    index: BorderIndex, lines: IntArray, t: FloatArray, f: FloatArray
) -> tuple[FloatArray, FloatArray]:
    """One-sided derivatives ``(left, right)`` of :func:`nearest_arcs` at ``t`` [m per unit t]."""
    lo = np.maximum(t - _EPS, 0.0)
    hi = np.minimum(t + _EPS, 1.0)
    both = nearest_arcs(index, np.concatenate([lines, lines]), np.concatenate([lo, hi]))
    q = len(t)
    left = (f - both[:q]) / np.where(t > lo, t - lo, 1.0)
    right = (both[q:] - f) / np.where(hi > t, hi - t, 1.0)
    return left, right


def projected_stations(
    index: BorderIndex, length_max_m: FloatArray, border_length_m: FloatArray
) -> tuple[list[list[float]], list[list[float]], list[list[float]]]:
    """Per lane, a table of :func:`nearest_arcs` that is exact at and linear between stations.

    Each border is refined on its own. Between the knots (:func:`_knots`) the nearest
    point moves linearly, stops at a vertex (a kink) or jumps where ad-map switches border
    segments. An interval is known by its end values and its one-sided end slopes: it is
    linear if both end tangents meet the other end (within ``_TOL_M``); otherwise it is
    split where the two tangents cross (a kink, resolved in one step; slopes there from
    difference quotients) or in the middle (every second split at least; a jump halves
    its interval, the half on one tangent keeps that tangent's slope), down to
    ``_MIN_STEP_M``. Both borders are then evaluated at the union of the stations,
    stations inside linear runs dropped, and arc lengths scaled to the borders' given
    lengths (so that ``[0, 1]`` spans the whole-lane lengths).

    Args:
        index: The borders.
        length_max_m: ``(L,)`` longer border length of each lane.
        border_length_m: ``(2, L)`` left and right border lengths as given.

    Returns:
        ``(stations, left_m, right_m)``: per lane, increasing parametric positions from 0 to
        1 and the arc lengths of the nearest points on the left and right border there.
    """
    n = len(length_max_m)
    knot_lane, knot_t = _knots(index.lines)
    lines = np.concatenate([knot_lane, knot_lane + n])
    t = np.concatenate([knot_t, knot_t])
    f = nearest_arcs(index, lines, t)
    left, right = _slopes(index, lines, t, f)
    pair = np.flatnonzero(lines[1:] == lines[:-1])
    line, a, b = lines[pair], t[pair], t[pair + 1]
    fa, sa, fb, sb = f[pair], right[pair], f[pair + 1], left[pair + 1]
    may_snap = np.ones(len(a), dtype=bool)
    min_step = _MIN_STEP_M / np.maximum(length_max_m, _MIN_STEP_M)
    found_lane, found_t = [knot_lane], [knot_t]
    for _ in range(_ROUNDS):
        w = b - a
        rise = fb - fa
        linear = (np.abs(rise - sa * w) <= _TOL_M) & (np.abs(rise - sb * w) <= _TOL_M)
        split = w > min_step[line % n]
        tiny = ~linear & ~split
        found_lane.append(np.concatenate([line[tiny], line[tiny]]) % n)
        found_t.append(np.concatenate([a[tiny], b[tiny]]))
        keep = ~linear & split
        line, a, b, fa, sa, fb, sb = (v[keep] for v in (line, a, b, fa, sa, fb, sb))
        may_snap = may_snap[keep]
        if not len(a):
            break
        with np.errstate(divide="ignore", invalid="ignore"):
            cross = (fb - fa + sa * a - sb * b) / (sa - sb)
        snap = may_snap & (cross > a + 2.0 * _EPS) & (cross < b - 2.0 * _EPS)
        mid = np.where(snap, cross, 0.5 * (a + b))
        near = 0.5 * (fa + fb)
        f_mid = nearest_arcs(index, line, mid, near, float(np.abs(fb - fa).max()) + _REACH_M)
        on_a = np.abs(f_mid - fa - sa * (mid - a)) <= _TOL_M
        on_b = np.abs(f_mid - fb - sb * (mid - b)) <= _TOL_M
        s_in = np.where(on_a, sa, np.where(on_b, sb, np.nan))
        s_out = s_in.copy()
        probe = snap | ~(on_a | on_b)
        if probe.any():
            s_in[probe], s_out[probe] = _slopes(index, line[probe], mid[probe], f_mid[probe])
        found_lane.append(line[probe] % n)
        found_t.append(mid[probe])
        line = np.concatenate([line, line])
        a, b = np.concatenate([a, mid]), np.concatenate([mid, b])
        fa, fb = np.concatenate([fa, f_mid]), np.concatenate([f_mid, fb])
        sa, sb = np.concatenate([sa, s_out]), np.concatenate([s_in, sb])
        may_snap = np.concatenate([~snap, ~snap])
    found = (np.concatenate(found_lane), np.concatenate(found_t))
    return _tables(index, border_length_m, *found)


def _tables(
    index: BorderIndex, border_length_m: FloatArray, lanes: IntArray, t: FloatArray
) -> tuple[list[list[float]], list[list[float]], list[list[float]]]:
    """Both borders' scaled arc lengths at stations ``(lanes, t)`` (any order, repeats)."""
    n = border_length_m.shape[1]
    order = np.lexsort((t, lanes))
    lanes, t = lanes[order], t[order]
    fresh = np.ones(len(t), dtype=bool)
    fresh[1:] = (lanes[1:] != lanes[:-1]) | (t[1:] - t[:-1] > _SAME_T)
    lanes, t = lanes[fresh], t[fresh]
    arcs = nearest_arcs(index, np.concatenate([lanes, lanes + n]), np.concatenate([t, t]))
    scale = border_length_m / np.maximum(index.lines.length_m.reshape(2, n), 1e-12)
    return _pruned(lanes, t, arcs.reshape(2, -1).T * scale[:, lanes].T, n)


def _pruned(
    lanes: IntArray, t: FloatArray, pos: FloatArray, n: int
) -> tuple[list[list[float]], list[list[float]], list[list[float]]]:
    """Stations (sorted per lane) without those inside linear runs, as per-lane lists.

    A station collinear with both neighbours (in both positions) adds nothing; chains of
    such stations lie on one line, so all of them can go at once.
    """
    keep = np.ones(len(t), dtype=bool)
    mid = np.flatnonzero((lanes[1:-1] == lanes[:-2]) & (lanes[1:-1] == lanes[2:])) + 1
    w = (t[mid] - t[mid - 1]) / (t[mid + 1] - t[mid - 1])
    line = pos[mid - 1] + (pos[mid + 1] - pos[mid - 1]) * w[:, None]
    keep[mid] = np.abs(pos[mid] - line).max(axis=1) > _PRUNE_TOL_M
    lanes, t, pos = lanes[keep], t[keep], pos[keep]
    bounds = np.searchsorted(lanes, np.arange(n + 1)).tolist()
    t_list, left, right = t.tolist(), pos[:, 0].tolist(), pos[:, 1].tolist()
    rows = range(n)
    return (
        [t_list[bounds[i] : bounds[i + 1]] for i in rows],
        [left[bounds[i] : bounds[i + 1]] for i in rows],
        [right[bounds[i] : bounds[i + 1]] for i in rows],
    )
