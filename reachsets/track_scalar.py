"""Arc length and lateral offset of a few positions, point by point (compiled with mypyc).

The one-frame twin of ``TrackGeometry.project`` / ``lateral_m``: the same float operations in
the same order on the track's columns as lists (``TrackGeometry.rows``: centre x, y, segment
x, y, squared segment length, arc length, normal x, y), so the results are bit-identical to
the numpy path (tested with Hypothesis in ``tests/reachsets/test_one_frame.py``).
"""

from __future__ import annotations

from bisect import bisect_right

__all__ = ["lateral_rows", "project_rows"]


def _nearest(x: float, y: float, cx: list[float], cy: list[float]) -> int:
    """Index of the first centre point nearest to ``(x, y)`` (numpy's ``argmin``)."""
    best = 0
    best_d = -1.0
    for i in range(len(cx)):
        dx = x - cx[i]
        dy = y - cy[i]
        d = dx * dx + dy * dy
        if best_d < 0.0 or d < best_d:
            best = i
            best_d = d
    return best


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
        near = _nearest(px, py, cx, cy)
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
