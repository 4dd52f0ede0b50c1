"""Lane segments of road areas, cached per map (for ``rss.scene.roadarea.build_road``).

Every pair of every frame gets its own road area, but most of its lanes are kept whole:
only the first and the last segment are cut at the two vehicles. A whole lane's
:class:`~rss.model.LaneSegment` depends only on ``(lane, orientation, id offset)``, so it
is built once per map and the same frozen object is handed out afterwards; a cut lane is
built from per-lane constants::

      cut (p0 > 0)        whole            whole          cut (p1 < 1)
    ├──┼──────────┼──────────────────┼──────────────┼───────┼──┤   road-area direction
       rear vehicle                                  front vehicle

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
table from ``t`` to the arc length of both nearest points is built once per map (exact
at its stations, linear in between, where the function is linear); a cut costs two
``bisect`` lookups.

Keys are lane indices of one :class:`~rss.scene.lanegraph.PreparedGraph`; the cache holds at
most ``2 L`` entries per id offset (``L`` lanes), so it needs no eviction.

:class:`GraphScalars` holds per-lane constants of the same graph as Python lists, for the
per-object code of scene creation (scalar access to numpy arrays costs ≈ 100 ns a time).
"""

from __future__ import annotations

from bisect import bisect_right
from typing import TYPE_CHECKING, TypeVar, cast

import numpy as np

from rss.model import LaneDrivingDirection, LaneSegment
from rss.scene.polylines import interpolate

if TYPE_CHECKING:
    from collections.abc import Callable

    from rss.arrays import FloatArray, IntArray
    from rss.scene.lanegraph import PreparedGraph
    from rss.scene.roadarea import BuiltSegment, SegmentPlan
    from rss.scene.routes import Step

__all__ = [
    "GraphScalars",
    "LaneMiddle",
    "LaneSegmentCache",
    "memoised",
    "nearest_arcs",
    "projected_stations",
]

_T = TypeVar("_T")

#: ad-map's middle line of a lane (``rss.scene.roadarea``): border-length fractions of its
#: points, their x and y [m], and the mean border length [m].
LaneMiddle = tuple[list[float], list[float], list[float], float]

_FLIPPED = {
    LaneDrivingDirection.Positive: LaneDrivingDirection.Negative,
    LaneDrivingDirection.Negative: LaneDrivingDirection.Positive,
    LaneDrivingDirection.Bidirectional: LaneDrivingDirection.Bidirectional,
}
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


class LaneSegmentCache:
    """Lane segments of one prepared graph (see module docstring)."""

    def __init__(self, prep: PreparedGraph) -> None:
        """Read the per-lane constants of ``prep`` once."""
        self._prep = prep
        along = [LaneDrivingDirection(int(code)) for code in prep.graph.direction]
        self._along = along
        self._against = [_FLIPPED[code] for code in along]
        self._length_min = prep.length_min_m.tolist()
        self._length_max = prep.length_max_m.tolist()
        self._stations, self._left_m, self._right_m = projected_stations(prep)
        self._width_range = prep.width_range
        self._whole: dict[tuple[int, bool, int], LaneSegment] = {}
        #: Whole (uncut) road segments of ``rss.scene.roadarea.build_road`` by plan
        #: ``(lanes, type, before, after, id offset)``: segment, placed lanes, finite limits.
        #: Uncut corridor layouts of ``rss.scene.corridor.corridor_plans`` by their inputs.
        #: Each as uncut plans (shared, do not cut) with its lanes' segment index and
        #: orientation (``roadarea.plan_lanes``).
        self.corridor_layouts: dict[
            tuple[object, ...], tuple[tuple[SegmentPlan, ...], dict[int, tuple[int, bool]]]
        ] = {}
        self.whole_roads: dict[tuple[object, ...], BuiltSegment] = {}

    def direction(self, lane: int, *, forward: bool) -> LaneDrivingDirection:
        """Traffic direction of ``lane`` relative to a road area it runs ``forward`` in."""
        return (self._along if forward else self._against)[lane]

    def lane_segment(
        self, lane: int, *, forward: bool, id_offset: int = 0, p0: float = 0.0, p1: float = 1.0
    ) -> LaneSegment:
        """The lane segment of ``lane`` kept between ``p0 <= p1`` of the road-area direction.

        Args:
            lane: Lane index.
            forward: The lane's point order runs along the road-area direction.
            id_offset: Added to the lane index to form the segment's ``lane_id``.
            p0: Kept window start (parametric, road-area direction).
            p1: Kept window end.

        Returns:
            The length range of the whole lane, or of the projected border pieces of a
            cut one (see module docstring); widths min / max over the window; the
            direction relative to the road area. For the whole lane always the same object.
        """
        if p0 == 0.0 and p1 == 1.0:
            cached = self._whole.get((lane, forward, id_offset))
            if cached is None:
                cached = self._whole[lane, forward, id_offset] = LaneSegment(
                    lane_id=lane + id_offset,
                    driving_direction=self.direction(lane, forward=forward),
                    length_min_m=self._length_min[lane],
                    length_max_m=self._length_max[lane],
                    width_min_m=self._prep.width_whole[lane][0],
                    width_max_m=self._prep.width_whole[lane][1],
                )
            return cached
        lo, hi = (p0, p1) if forward else (1.0 - p1, 1.0 - p0)
        w_min, w_max = self._width_range(lane, lo, hi)
        # Inlined table lookups and a positional constructor: a hot path (~50 cuts a frame).
        t = self._stations[lane]
        left = self._left_m[lane]
        right = self._right_m[lane]
        if lo <= 0.0:
            left_lo, right_lo = left[0], right[0]
        else:  # stations run from exactly 0 to exactly 1, and lo < hi <= 1
            j = bisect_right(t, lo) - 1
            w = (lo - t[j]) / (t[j + 1] - t[j])
            left_lo = left[j] + (left[j + 1] - left[j]) * w
            right_lo = right[j] + (right[j + 1] - right[j]) * w
        if hi >= 1.0:
            left_m, right_m = left[-1] - left_lo, right[-1] - right_lo
        else:
            k = bisect_right(t, hi) - 1
            w = (hi - t[k]) / (t[k + 1] - t[k])
            left_m = left[k] + (left[k + 1] - left[k]) * w - left_lo
            right_m = right[k] + (right[k + 1] - right[k]) * w - right_lo
        left_m, right_m = abs(left_m), abs(right_m)
        direction = (self._along if forward else self._against)[lane]
        if left_m < right_m:
            return LaneSegment(lane + id_offset, direction, left_m, right_m, w_min, w_max)
        return LaneSegment(lane + id_offset, direction, right_m, left_m, w_min, w_max)


def nearest_arcs(
    prep: PreparedGraph,
    lines: IntArray,
    t: FloatArray,
    near_m: FloatArray | None = None,
    reach_m: float = 0.0,
) -> FloatArray:
    """Where ad-map cuts a lane border for centre parametric positions ``t`` (vectorised).

    Args:
        prep: The prepared graph (its ``borders``).
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
    borders = prep.borders
    n = len(prep.straight)
    lane = lines % n
    both = np.concatenate([lane, lane + n])
    ends = interpolate(borders, both, np.concatenate([t, t]) * borders.length_m[both])
    q = len(lines)
    centre = 0.5 * (ends[:q] + ends[q:])
    s, _ = prep.nearest_on_borders(lines, centre, near_m, reach_m)
    return s


def _knots(prep: PreparedGraph) -> tuple[IntArray, FloatArray]:
    """``(lane, t)`` of both borders' vertices, sorted per lane (``c(t)`` is linear between)."""
    borders = prep.borders
    n = len(prep.straight)
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
    prep: PreparedGraph, lines: IntArray, t: FloatArray, f: FloatArray
) -> tuple[FloatArray, FloatArray]:
    """One-sided derivatives ``(left, right)`` of :func:`nearest_arcs` at ``t`` [m per unit t]."""
    lo = np.maximum(t - _EPS, 0.0)
    hi = np.minimum(t + _EPS, 1.0)
    both = nearest_arcs(prep, np.concatenate([lines, lines]), np.concatenate([lo, hi]))
    q = len(t)
    left = (f - both[:q]) / np.where(t > lo, t - lo, 1.0)
    right = (both[q:] - f) / np.where(hi > t, hi - t, 1.0)
    return left, right


def projected_stations(
    prep: PreparedGraph,
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

    Returns:
        ``(stations, left_m, right_m)``: per lane, increasing parametric positions from 0 to
        1 and the arc lengths of the nearest points on the left and right border there.
    """
    n = len(prep.straight)
    knot_lane, knot_t = _knots(prep)
    lines = np.concatenate([knot_lane, knot_lane + n])
    t = np.concatenate([knot_t, knot_t])
    f = nearest_arcs(prep, lines, t)
    left, right = _slopes(prep, lines, t, f)
    pair = np.flatnonzero(lines[1:] == lines[:-1])
    line, a, b = lines[pair], t[pair], t[pair + 1]
    fa, sa, fb, sb = f[pair], right[pair], f[pair + 1], left[pair + 1]
    may_snap = np.ones(len(a), dtype=bool)
    min_step = _MIN_STEP_M / np.maximum(prep.length_max_m, _MIN_STEP_M)
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
        f_mid = nearest_arcs(prep, line, mid, near, float(np.abs(fb - fa).max()) + _REACH_M)
        on_a = np.abs(f_mid - fa - sa * (mid - a)) <= _TOL_M
        on_b = np.abs(f_mid - fb - sb * (mid - b)) <= _TOL_M
        s_in = np.where(on_a, sa, np.where(on_b, sb, np.nan))
        s_out = s_in.copy()
        probe = snap | ~(on_a | on_b)
        if probe.any():
            s_in[probe], s_out[probe] = _slopes(prep, line[probe], mid[probe], f_mid[probe])
        found_lane.append(line[probe] % n)
        found_t.append(mid[probe])
        line = np.concatenate([line, line])
        a, b = np.concatenate([a, mid]), np.concatenate([mid, b])
        fa, fb = np.concatenate([fa, f_mid]), np.concatenate([f_mid, fb])
        sa, sb = np.concatenate([sa, s_out]), np.concatenate([s_in, sb])
        may_snap = np.concatenate([~snap, ~snap])
    return _tables(prep, np.concatenate(found_lane), np.concatenate(found_t))


def _tables(
    prep: PreparedGraph, lanes: IntArray, t: FloatArray
) -> tuple[list[list[float]], list[list[float]], list[list[float]]]:
    """Both borders' scaled arc lengths at stations ``(lanes, t)`` (any order, repeats)."""
    n = len(prep.straight)
    order = np.lexsort((t, lanes))
    lanes, t = lanes[order], t[order]
    fresh = np.ones(len(t), dtype=bool)
    fresh[1:] = (lanes[1:] != lanes[:-1]) | (t[1:] - t[:-1] > _SAME_T)
    lanes, t = lanes[fresh], t[fresh]
    arcs = nearest_arcs(prep, np.concatenate([lanes, lanes + n]), np.concatenate([t, t]))
    scale = prep.border_length_m / np.maximum(prep.borders.length_m.reshape(2, n), 1e-12)
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


class GraphScalars:
    """Per-lane constants of one prepared graph as Python lists (see module docstring).

    Attributes:
        direction: ``(L,)`` traffic-direction codes relative to the point order.
        speed_limit_mps: ``(L,)`` speed limits (NaN where unknown).
        centre_length_m: ``(L,)`` centre-line lengths.
        centre_xy_m: Per lane, the centre-line points ``[[x, y], ...]``.
        centre_arc_m: Per lane, the cumulative arc length at each centre-line point
            (starts at 0).
        left_neighbour: ``(L,)`` adjacent lane on the left, -1 for none.
        right_neighbour: ``(L,)`` adjacent lane on the right, -1 for none.
        left_opposite: ``(L,)`` the left neighbour's point order is reversed.
        right_opposite: ``(L,)`` the right neighbour's point order is reversed.
        is_intersection: ``(L,)`` lane lies inside an intersection.
        conflict_rows: ``(L, L)`` ``prep.conflicts`` as nested lists.
        cross_sections: Memo of ``rss.scene.routes.cross_section`` by step.
        route_facts: Memo of pure route functions (:func:`memoised`).
        route_searches: Recent predicted-route searches by start step, with their
            horizon comparisons (``rss.scene.routes.predict_routes``).
        lane_middles: Memo of ad-map's middle line per lane (``rss.scene.roadarea``).
    """

    def __init__(self, prep: PreparedGraph) -> None:
        """Convert the arrays of ``prep`` once."""
        g = prep.graph
        self.direction: list[int] = [int(v) for v in g.direction]
        self.speed_limit_mps: list[float] = np.asarray(g.speed_limit_mps, float).tolist()
        self.centre_length_m: list[float] = np.asarray(prep.centre_length_m, float).tolist()
        self.centre_xy_m: list[list[list[float]]] = [c.tolist() for c in g.centre_m]
        self.centre_arc_m: list[list[float]] = [
            np.concatenate(
                [[0.0], np.cumsum(np.hypot(np.diff(c[:, 0]), np.diff(c[:, 1])))]
            ).tolist()
            for c in g.centre_m
        ]
        self.left_neighbour: list[int] = [int(v) for v in g.left_neighbour]
        self.right_neighbour: list[int] = [int(v) for v in g.right_neighbour]
        self.left_opposite: list[bool] = [bool(v) for v in g.left_opposite]
        self.right_opposite: list[bool] = [bool(v) for v in g.right_opposite]
        self.is_intersection: list[bool] = np.asarray(g.is_intersection, bool).tolist()
        self.conflict_rows: list[list[bool]] = np.asarray(prep.conflicts, bool).tolist()
        self.cross_sections: dict[Step, tuple[Step, ...]] = {}
        self.route_facts: dict[object, object] = {}
        self.route_searches: dict[
            Step, list[tuple[tuple[tuple[Step, ...], ...], tuple[tuple[int, int, bool], ...]]]
        ] = {}
        self.lane_middles: dict[int, LaneMiddle] = {}


#: Entries of a graph's route memo (:func:`memoised`) before it is emptied.
_MEMO_SIZE = 100_000
_MISSING = object()


def memoised(prep: PreparedGraph, compute: Callable[..., _T], *args: object) -> _T:
    """``compute(prep, *args)``, or its earlier result in the graph's memo (bounded).

    For pure functions of routes and lanes (``rss.scene.intersection``, ``connecting``,
    ``cut_areas``, ``routes``): their results are kept per prepared graph
    (:attr:`GraphScalars.route_facts`), keyed by the function and its arguments.
    """
    memo = prep.scalars.route_facts
    key = (compute, *args)
    found = memo.get(key, _MISSING)
    if found is _MISSING:
        if len(memo) > _MEMO_SIZE:
            memo.clear()
        found = memo[key] = compute(prep, *args)
    return cast("_T", found)
