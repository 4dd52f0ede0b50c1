"""Lane segments of road areas from per-lane tables (for ``rss.scene.roadarea.build_road``).

Every pair of every frame gets its own road area, but most of its lanes are kept whole:
only the first and the last segment are cut at the two vehicles. A whole lane's
:class:`~rss.model.LaneSegment` depends only on ``(lane, orientation, id offset)``, so it
is built once per map (kept in ``SceneMemo.whole_lanes``) and the same frozen object is
handed out afterwards; a cut lane is built from per-lane constants::

      cut (p0 > 0)        whole            whole          cut (p1 < 1)
    ├──┼──────────┼──────────────────┼──────────────┼───────┼──┤   road-area direction
       rear vehicle                                  front vehicle

A cut lane's lengths are those of its projected border pieces (the tables of
``rss.scene.border_stations``), its widths ad-map's width range over the window.
:class:`LaneSegmentTable` holds these constants of one map as Python lists (scalar access
to numpy arrays costs ≈ 100 ns a time); ``prepare`` builds it.
"""

from __future__ import annotations

import bisect
from bisect import bisect_right
from typing import TYPE_CHECKING

from rss.model import LaneDrivingDirection, LaneSegment
from rss.scene.admap_nearest import range_of

if TYPE_CHECKING:
    from rss.arrays import FloatArray, IntArray

__all__ = ["LaneSegmentTable", "WholeLanes"]

#: Whole lanes' segments by ``(lane, forward, id offset)`` (one memo per map).
WholeLanes = dict[tuple[int, bool, int], LaneSegment]

_FLIPPED = {
    LaneDrivingDirection.Positive: LaneDrivingDirection.Negative,
    LaneDrivingDirection.Negative: LaneDrivingDirection.Positive,
    LaneDrivingDirection.Bidirectional: LaneDrivingDirection.Bidirectional,
}


class LaneSegmentTable:
    """Per-lane constants of one prepared graph for its lane segments (module docstring).

    Attributes:
        stations: Per lane, increasing parametric positions from 0 to 1 of the projected
            border table (``border_stations.projected_stations``).
        left_m: Per lane, the arc lengths of the left border's cut at ``stations``.
        right_m: Per lane, the same on the right border.
        width_rows: Per lane, ad-map's widths at its stations ``width_t``.
        width_t: Per lane, the parametric stations of ``width_rows`` (0 to 1, our order).
        width_whole: Per lane, ad-map's range of ``width_rows`` (``range_of``: up to 1 mm
            inside the min and max); ad-map keeps it for every interval of a lane whose
            range spans at most 0.1 m (``width_steady``).
        width_steady: Per lane, see ``width_whole``.
    """

    def __init__(  # noqa: PLR0917 - the per-lane tables, built once by prepare
        self,
        direction: IntArray,
        length_min_m: FloatArray,
        length_max_m: FloatArray,
        stations: tuple[list[list[float]], list[list[float]], list[list[float]]],
        widths: tuple[list[list[float]], list[list[float]]],
        width_whole: list[tuple[float, float]],
        width_steady: list[bool],
    ) -> None:
        """Hold the tables (``direction``: traffic direction codes along the point order)."""
        along = [LaneDrivingDirection(int(code)) for code in direction]
        self._along = along
        self._against = [_FLIPPED[code] for code in along]
        self._length_min: list[float] = length_min_m.tolist()
        self._length_max: list[float] = length_max_m.tolist()
        self.stations, self.left_m, self.right_m = stations
        self.width_rows, self.width_t = widths
        self.width_whole = width_whole
        self.width_steady = width_steady

    def direction(self, lane: int, *, forward: bool) -> LaneDrivingDirection:
        """Traffic direction of ``lane`` relative to a road area it runs ``forward`` in."""
        return (self._along if forward else self._against)[lane]

    def width_range(self, lane: int, p0: float, p1: float) -> tuple[float, float]:
        """Min and max width of ``lane`` between parametric positions ``p0 <= p1``.

        As ad-map: the whole lane's range where it spans at most 0.1 m; else the range of
        the widths at the stations inside the interval and, interpolated, at its ends
        (ad-map evaluates its rule on the interval's projected borders).
        """
        if self.width_steady[lane] or (p0 <= 0.0 and p1 >= 1.0):
            return self.width_whole[lane]
        row = self.width_rows[lane]
        at = self.width_t[lane]
        inner = row[bisect.bisect_right(at, p0) : bisect.bisect_left(at, p1)]
        return range_of([_interp(p0, at, row), *inner, _interp(p1, at, row)])

    def lane_segment(
        self,
        whole: WholeLanes,
        lane: int,
        *,
        forward: bool,
        id_offset: int = 0,
        p0: float = 0.0,
        p1: float = 1.0,
    ) -> LaneSegment:
        """The lane segment of ``lane`` kept between ``p0 <= p1`` of the road-area direction.

        Args:
            whole: The map's memo of whole lanes (``SceneMemo.whole_lanes``).
            lane: Lane index.
            forward: The lane's point order runs along the road-area direction.
            id_offset: Added to the lane index to form the segment's ``lane_id``.
            p0: Kept window start (parametric, road-area direction).
            p1: Kept window end.

        Returns:
            The length range of the whole lane, or of the projected border pieces of a
            cut one (see module docstring); widths min / max over the window; the
            direction relative to the road area. For the whole lane always the same object
            (per ``whole``).
        """
        if p0 == 0.0 and p1 == 1.0:
            cached = whole.get((lane, forward, id_offset))
            if cached is None:
                cached = whole[lane, forward, id_offset] = LaneSegment(
                    lane_id=lane + id_offset,
                    driving_direction=self.direction(lane, forward=forward),
                    length_min_m=self._length_min[lane],
                    length_max_m=self._length_max[lane],
                    width_min_m=self.width_whole[lane][0],
                    width_max_m=self.width_whole[lane][1],
                )
            return cached
        lo, hi = (p0, p1) if forward else (1.0 - p1, 1.0 - p0)
        w_min, w_max = self.width_range(lane, lo, hi)
        # Inlined table lookups and a positional constructor: a hot path (~50 cuts a frame).
        t = self.stations[lane]
        left = self.left_m[lane]
        right = self.right_m[lane]
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


def _interp(x: float, at: list[float], row: list[float]) -> float:
    """``numpy.interp(x, at, row)`` for one scalar, in plain Python (same arithmetic)."""
    if x <= at[0]:
        return row[0]
    if x >= at[-1]:
        return row[-1]
    j = bisect.bisect_right(at, x) - 1
    x0 = at[j]
    if x == x0:
        return row[j]
    slope = (row[j + 1] - row[j]) / (at[j + 1] - x0)
    return slope * (x - x0) + row[j]
