"""Arc length and lateral offset of a few positions, point by point (compiled with mypyc).

The one-frame twin of ``TrackGeometry.project`` / ``lateral_m``: the same float operations in
the same order on the track's columns as lists (``TrackGeometry.rows``: centre x, y, segment
x, y, squared segment length, arc length, normal x, y, ``block_boxes``), so the results are
bit-identical to the numpy path (tested with Hypothesis in ``tests/reachsets/test_one_frame.py``).
"""

from __future__ import annotations

from bisect import bisect_right
from typing import Final

__all__ = ["BLOCK", "block_boxes", "lateral_rows", "project_rows"]


#: Centre points per block of ``block_boxes``.
BLOCK: Final = 16


def block_boxes(cx: list[float], cy: list[float]) -> list[float]:
    """Bounding box of every ``BLOCK`` consecutive centre points, flat ``[x0, y0, x1, y1, ...]``."""
    out: list[float] = []
    for b in range(0, len(cx), BLOCK):
        x0 = x1 = cx[b]
        y0 = y1 = cy[b]
        for i in range(b, min(b + BLOCK, len(cx))):
            x0 = min(x0, cx[i])
            x1 = max(x1, cx[i])
            y0 = min(y0, cy[i])
            y1 = max(y1, cy[i])
        out += [x0, y0, x1, y1]
    return out


def _below(x: float, y: float, boxes: list[float], b: int) -> float:
    """A lower bound of ``_nearest``'s float distance to the points of block ``b``.

    Rounding is monotone, so ``(x - cx)**2 + (y - cy)**2`` in floats is never below the same
    expression with ``cx, cy`` moved to the box's nearest edge.
    """
    dx = (
        boxes[4 * b] - x
        if x < boxes[4 * b]
        else (x - boxes[4 * b + 2] if x > boxes[4 * b + 2] else 0.0)
    )
    dy = (
        boxes[4 * b + 1] - y
        if y < boxes[4 * b + 1]
        else (y - boxes[4 * b + 3] if y > boxes[4 * b + 3] else 0.0)
    )
    return dx * dx + dy * dy


def _nearest(x: float, y: float, cx: list[float], cy: list[float], boxes: list[float]) -> int:
    """Index of the first centre point nearest to ``(x, y)`` (numpy's ``argmin``).

    Blocks (``boxes``) whose lower bound exceeds the nearest distance within the closest
    block are skipped: none of their points can be the minimum, so the index is the same.
    """
    nb = len(boxes) // 4
    lbs = [_below(x, y, boxes, b) for b in range(nb)]
    first = 0
    for b in range(1, nb):
        if lbs[b] < lbs[first]:
            first = b
    ub = _scan(x, y, cx, cy, first, 0, -1.0)[1]
    best = 0
    best_d = -1.0
    for b in range(nb):
        if lbs[b] <= ub:
            best, best_d = _scan(x, y, cx, cy, b, best, best_d)
    return best


def _scan(  # noqa: PLR0917
    x: float, y: float, cx: list[float], cy: list[float], b: int, best: int, best_d: float
) -> tuple[int, float]:
    """The first nearest point so far after the points of block ``b`` (``best_d < 0``: none)."""
    for i in range(b * BLOCK, min((b + 1) * BLOCK, len(cx))):
        dx = x - cx[i]
        dy = y - cy[i]
        d = dx * dx + dy * dy
        if best_d < 0.0 or d < best_d:
            best = i
            best_d = d
    return best, best_d


def project_rows(
    x: list[float], y: list[float], rows: list[list[float]], window: int
) -> list[float]:
    """``TrackGeometry.project`` of the positions ``(x[i], y[i])`` (finite), arc lengths.

    Args:
        x: Positions' x, metres.
        y: Positions' y, metres.
        rows: ``TrackGeometry.rows``.
        window: ``LOCATE_WINDOW``.
    """
    cx, cy, sx, sy, l2, s = rows[0], rows[1], rows[2], rows[3], rows[4], rows[5]
    last = len(sx) - 1
    out: list[float] = []
    for p in range(len(x)):
        px, py = x[p], y[p]
        near = _nearest(px, py, cx, cy, rows[8])
        k_best = 0
        u_best = 0.0
        d_best = -1.0
        for w in range(-window, window):
            k = min(max(near + w, 0), last)
            dx = px - cx[k]
            dy = py - cy[k]
            u = min(max((dx * sx[k] + dy * sy[k]) / l2[k], 0.0), 1.0)
            ox = dx - u * sx[k]
            oy = dy - u * sy[k]
            d = ox * ox + oy * oy
            if d_best < 0.0 or d < d_best:
                k_best, u_best, d_best = k, u, d
        out.append(s[k_best] + u_best * (s[k_best + 1] - s[k_best]))
    return out


def lateral_rows(
    x: list[float], y: list[float], s_m: list[float], rows: list[list[float]]
) -> list[float]:
    """``TrackGeometry.lateral_m`` of the positions at their arc lengths ``s_m`` (finite)."""
    cx, cy, s, nx, ny = rows[0], rows[1], rows[5], rows[6], rows[7]
    last = len(s) - 1
    out: list[float] = []
    for p in range(len(x)):
        i = min(max(bisect_right(s, s_m[p]) - 1, 0), last)
        out.append((x[p] - cx[i]) * nx[i] + (y[p] - cy[i]) * ny[i])
    return out
