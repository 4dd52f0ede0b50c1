"""Geometry shared by the map readers: geodetic projection, arc length, resampling, centre lines.

All polylines are ``(K, 2)`` float arrays in the map frame (ENU, metres).
"""

from __future__ import annotations

import math
from typing import TYPE_CHECKING

import numpy as np

if TYPE_CHECKING:
    from numpy.typing import ArrayLike, NDArray

__all__ = ["arc_length_m", "centre_line_m", "project_to_local_enu_m", "resample_polyline_m"]

_WGS84_A_M = 6_378_137.0
_WGS84_F = 1.0 / 298.257223563


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


def project_to_local_enu_m(
    lat_deg: ArrayLike, lon_deg: ArrayLike, lat0_deg: float, lon0_deg: float
) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """Project WGS-84 coordinates onto the east-north tangent plane at an origin.

    Args:
        lat_deg: Latitudes, ``(N,)`` degrees.
        lon_deg: Longitudes, ``(N,)`` degrees.
        lat0_deg: Origin latitude, degrees.
        lon0_deg: Origin longitude, degrees.

    Returns:
        East and north offsets from the origin, each ``(N,)`` metres.
    """
    e2 = _WGS84_F * (2.0 - _WGS84_F)

    def ecef(lat: NDArray[np.float64], lon: NDArray[np.float64]) -> NDArray[np.float64]:
        n = _WGS84_A_M / np.sqrt(1.0 - e2 * np.sin(lat) ** 2)
        return np.stack(
            (
                n * np.cos(lat) * np.cos(lon),
                n * np.cos(lat) * np.sin(lon),
                n * (1 - e2) * np.sin(lat),
            )
        )

    lat0, lon0 = math.radians(lat0_deg), math.radians(lon0_deg)
    d = ecef(
        np.radians(np.asarray(lat_deg, dtype=np.float64)),
        np.radians(np.asarray(lon_deg, dtype=np.float64)),
    ) - ecef(np.array([lat0]), np.array([lon0]))
    east = -math.sin(lon0) * d[0] + math.cos(lon0) * d[1]
    north = (
        -math.sin(lat0) * math.cos(lon0) * d[0]
        - math.sin(lat0) * math.sin(lon0) * d[1]
        + math.cos(lat0) * d[2]
    )
    return east, north
