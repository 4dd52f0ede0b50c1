r"""ad-map's aligned cuts of the lanes side by side in one road segment.

When ad-map cuts a route at a vehicle (``route::planning::createFullRoute`` and the
connecting routes' ``dropStartRegion`` / ``dropEndRegion``), it cuts the lane the vehicle
occupies at the vehicle's region bound ``t`` and then *aligns* the other lanes of that
road segment (``alignRouteStartingPoints`` / ``alignRouteEndingPoints``): the centre point
``c(t)`` of the cut lane (the middle of its border points at fraction ``t`` of each
border's length) is projected onto both of that lane's borders, ``P`` is the middle of the
two projections (``lane::getProjectedParametricPoint(lane, t, 0.5)``), and every other lane
is cut at the mean of the border fractions of ``P``'s nearest points on its own left and
right border (``point::findNearestPointOnEdge``, with ad-map's tie rule)::

    other lane   left   ──────────────a───────▶   t_other = (frac(a) + frac(b)) / 2
                 right  ─────────────b────────▶
    cut lane     left   ──────l'──────────────▶   P = (l' + r') / 2, l' and r' the
                             c(t) · P               nearest points of c(t)
                 right  ────────────r'────────▶

On a curve the other lane's cut thus differs from the same fraction ``t`` (pair 38 of the
Town01 cross-check: 0.762 in 200149 beside 0.782 in 200151, 0.27 m of its inner border).

A few scalar nearest-point searches per cut, each over the border segments within a few
metres of where the point is expected (:data:`_REACH_M` plus a share of the border's
length), not over whole borders: the cuts are made anew in every frame.
"""

from __future__ import annotations

import bisect
import math
from typing import TYPE_CHECKING

from rss.scene.admap_nearest import DISTANCE_TOL_M

if TYPE_CHECKING:
    from rss.scene.border_index import BorderIndex

__all__ = ["Aligner"]

#: Border segments within this arc length [m] of the expected nearest point (plus
#: :data:`_REACH_SHARE` of the border's length) are searched.
_REACH_M = 2.0
#: See :data:`_REACH_M`.
_REACH_SHARE = 0.1


class Aligner:
    """ad-map's aligned cuts on one prepared graph (see module docstring).

    Holds the borders of a :class:`~rss.scene.border_index.BorderIndex` as Python lists
    for scalar access: line ``l`` is the left border of lane ``l``, line ``L + l`` its
    right border. Built once per map by ``prepare``.
    """

    def __init__(self, index: BorderIndex) -> None:
        """Convert the borders of ``index`` once."""
        borders = index.lines
        self._n = len(borders.length_m) // 2
        self._x: list[float] = borders.xy_m[:, 0].tolist()
        self._y: list[float] = borders.xy_m[:, 1].tolist()
        self._s: list[float] = borders.s_at_m.tolist()
        self._seg: list[float] = borders.segment_m.tolist()
        self._start: list[int] = borders.start.tolist()
        self._length: list[float] = borders.length_m.tolist()
        self._backwards: list[bool] = index.backwards.tolist()
        self._reach: list[float] = [_REACH_M + _REACH_SHARE * v for v in self._length]

    def aligned(self, lane: int, t: float, other: int, guess: float) -> float:
        """Where ad-map cuts ``other`` when it cuts ``lane`` at ``t`` (both in our point order).

        Args:
            lane: The cut lane (the one the vehicle occupies).
            t: Its cut, parametric along its point order.
            other: A lane beside it in the same road segment.
            guess: Roughly where ``other`` is cut (parametric along its point order, e.g.
                ``t`` or ``1 - t``): the searches look near it.

        Returns:
            The cut of ``other``, parametric along its point order.
        """
        n = self._n
        left, right = lane, lane + n
        lx, ly = self._point(left, t * self._length[left])
        rx, ry = self._point(right, t * self._length[right])
        cx, cy = 0.5 * (lx + rx), 0.5 * (ly + ry)
        lx, ly = self._point(left, self._nearest(left, cx, cy, t))
        rx, ry = self._point(right, self._nearest(right, cx, cy, t))
        px, py = 0.5 * (lx + rx), 0.5 * (ly + ry)
        fractions = 0.0
        for line in (other, other + n):
            length = self._length[line]
            if length > 0.0:
                fractions += self._nearest(line, px, py, guess) / length
        return 0.5 * fractions

    def _point(self, line: int, s: float) -> tuple[float, float]:
        """The point at arc length ``s`` (clamped) of ``line``."""
        a, b = self._start[line], self._start[line + 1] - 1
        k = bisect.bisect_right(self._s, s, a, b) - 1
        k = min(max(k, a), b - 1)
        seg = self._seg[k]
        u = (s - self._s[k]) / seg if seg > 0.0 else 0.0
        u = min(max(u, 0.0), 1.0)
        x, y = self._x[k], self._y[k]
        return x + (self._x[k + 1] - x) * u, y + (self._y[k + 1] - y) * u

    def _nearest(self, line: int, px: float, py: float, near: float) -> float:
        """Arc length of the nearest point of ``(px, py)`` on ``line``, ad-map's tie rule.

        Only segments within the reach of fraction ``near`` are tried. Of those within
        1 mm of the nearest distance the first in ad-map's point order wins (ours, or our
        last where ad-map's order runs against ours), as ``admap_nearest.nearest_on_lines``.
        """
        a, b = self._start[line], self._start[line + 1] - 1
        reach = self._reach[line]
        s_near = near * self._length[line]
        lo = max(bisect.bisect_right(self._s, s_near - reach, a, b) - 1, a)
        hi = max(min(bisect.bisect_left(self._s, s_near + reach, a, b), b - 1), lo)
        xs, ys, seg = self._x, self._y, self._seg
        count = hi - lo + 1
        dist2 = [0.0] * count
        along = [0.0] * count
        best = math.inf
        for i in range(count):
            k = lo + i
            ax, ay = xs[k], ys[k]
            dx, dy = xs[k + 1] - ax, ys[k + 1] - ay
            rx, ry = px - ax, py - ay
            size = seg[k]
            u = (rx * dx + ry * dy) / (size * size) if size > 0.0 else 0.0
            u = min(max(u, 0.0), 1.0)
            ox, oy = rx - dx * u, ry - dy * u
            d2 = ox * ox + oy * oy
            dist2[i] = d2
            along[i] = u
            best = min(best, d2)
        limit = math.sqrt(best) + DISTANCE_TOL_M
        limit *= limit
        backwards = self._backwards[line]
        for j in range(count):
            i = count - 1 - j if backwards else j
            if dist2[i] < limit:
                k = lo + i
                return self._s[k] + along[i] * seg[k]
        return 0.0  # unreachable: the nearest segment is within the limit
