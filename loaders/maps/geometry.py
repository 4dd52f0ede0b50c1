"""Polyline helpers shared by the map readers: arc length, resampling and centre lines.

All polylines are ``(K, 2)`` float arrays in the map frame (ENU, metres).
"""

from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np

if TYPE_CHECKING:
    from numpy.typing import ArrayLike, NDArray

__all__ = ["arc_length_m", "centre_line_m", "resample_polyline_m"]


def arc_length_m(points_m: ArrayLike) -> NDArray[np.float64]:
    """Cumulative arc length along a polyline.

    Args:
        points_m: Polyline vertices, ``(K, 2)`` metres.

    Returns:
        Distance from the first vertex to each vertex, ``(K,)`` metres, starting at 0.
    """
    pts = np.asarray(points_m, dtype=np.float64).reshape(-1, 2)
    if len(pts) == 0:
        return np.zeros(0, dtype=np.float64)
    steps = np.hypot(*np.diff(pts, axis=0).T)
    return np.concatenate(([0.0], np.cumsum(steps)))


def resample_polyline_m(points_m: ArrayLike, count: int) -> NDArray[np.float64]:
    """Resample a polyline to ``count`` vertices spaced evenly by arc length.

    The first and last vertices are kept exactly. A polyline of zero length (or a single
    vertex) is repeated ``count`` times.

    Args:
        points_m: Polyline vertices, ``(K, 2)`` metres, ``K >= 1``.
        count: Number of output vertices, ``>= 2``.

    Returns:
        Resampled vertices, ``(count, 2)`` metres.

    Raises:
        ValueError: If the polyline is empty or ``count < 2``.
    """
    pts = np.asarray(points_m, dtype=np.float64).reshape(-1, 2)
    if len(pts) == 0 or count < 2:  # noqa: PLR2004 - two vertices make the shortest polyline
        msg = f"cannot resample {len(pts)} vertices to {count}"
        raise ValueError(msg)
    s = arc_length_m(pts)
    total = s[-1]
    if total <= 0.0:
        return np.repeat(pts[:1], count, axis=0)
    targets = np.linspace(0.0, total, count)
    out = np.column_stack((np.interp(targets, s, pts[:, 0]), np.interp(targets, s, pts[:, 1])))
    out[0] = pts[0]
    out[-1] = pts[-1]
    return out


def centre_line_m(left_m: ArrayLike, right_m: ArrayLike) -> NDArray[np.float64]:
    """Centre line of a lane: the mean of both borders resampled to a common vertex count.

    Both borders must be ordered in the same direction. The vertex count is the larger of
    the two border vertex counts (at least 2).

    Args:
        left_m: Left border, ``(K, 2)`` metres.
        right_m: Right border, ``(M, 2)`` metres.

    Returns:
        Centre line, ``(max(K, M, 2), 2)`` metres.
    """
    left = np.asarray(left_m, dtype=np.float64).reshape(-1, 2)
    right = np.asarray(right_m, dtype=np.float64).reshape(-1, 2)
    count = max(len(left), len(right), 2)
    return 0.5 * (resample_polyline_m(left, count) + resample_polyline_m(right, count))
