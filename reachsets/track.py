"""Track geometry derived once from the left/right bounds: centre line, arc length, widths.

::

    left bound   o-----o-----o-----o
                 |  tw_left        |
    centre  s=0  o-----o-----o-----o---> s
                 |  tw_right       |   normal n points to the right
    right bound  o-----o-----o-----o
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

import numpy as np
import shapely

from reachsets import track_scalar

if TYPE_CHECKING:
    from numpy.typing import NDArray

    from reachsets.inputs import TrackBounds

__all__ = ["TrackGeometry", "build_track", "resample_polyline"]

#: Spacing of the resampled centre line (the reference builds its line at 1 m).
CENTRE_STEP_M = 1.0
#: Segments either side of the nearest centre point searched by ``TrackGeometry.project``.
LOCATE_WINDOW = 3
_WINDOW = np.arange(-LOCATE_WINDOW, LOCATE_WINDOW)
#: Up to this many positions ``lateral_m`` goes point by point with the compiled twin
#: (``track_scalar``, bit-identical); from the sources never.
SCALAR_POINTS_MAX = 8 if not track_scalar.__file__.endswith(".py") else 0
#: ``project`` goes point by point with the compiled twin at any number of positions (its
#: nearest-point search skips blocks of centre points; numpy compares every position with every
#: centre point, ``(N, C)`` temporaries): 286 against 671 us for 200 positions on a 414-point
#: centre line, 565 against 1,255 us for 400, even at 32 (2026-11-29); from the sources never.
SCALAR_PROJECT = not track_scalar.__file__.endswith(".py")

#: Half window over which the centre-line heading is differentiated for the curvature.
CURVATURE_HALF_WINDOW_M = 5.0


def resample_polyline(points: NDArray[np.float64], n: int) -> NDArray[np.float64]:
    """Resample a polyline at ``n`` points equally spaced in arc length, ``(n, 2)``."""
    seg = np.hypot(*np.diff(points, axis=0).T)
    s = np.concatenate([[0.0], np.cumsum(seg)])
    target = np.linspace(0.0, s[-1], n)
    return np.stack([np.interp(target, s, points[:, 0]), np.interp(target, s, points[:, 1])], 1)


@dataclass(frozen=True, slots=True)
class TrackGeometry:
    """Derived track geometry.

    Attributes:
        centre_m: Centre line, ``(C, 2)``.
        s_m: Arc length at each centre point, ``(C,)``.
        normal: Unit normals pointing to the right, ``(C, 2)``.
        tw_left_m: Distance centre to left bound, ``(C,)``.
        tw_right_m: Distance centre to right bound, ``(C,)``.
        kappa_inv_m: Centre-line curvature (left turn positive), ``(C,)``.
        left: Left bound as a LineString.
        right: Right bound as a LineString.
        centre: Centre line as a LineString.
        polygon: Drivable area (prepared for repeated predicates).
        closed: Whether the track is a loop.
        length_m: Centre-line length.
        seg_m: Centre-line segment vectors, ``(C - 1, 2)`` (for ``locate``).
        seg_len_sq_m2: Their squared lengths, ``(C - 1,)``.
        rows: The columns ``track_scalar`` reads, as lists (centre x, y, segment x, y, squared
            length, arc length, normal x, y, ``track_scalar.block_boxes`` of the centre).
    """

    centre_m: NDArray[np.float64]
    s_m: NDArray[np.float64]
    normal: NDArray[np.float64]
    tw_left_m: NDArray[np.float64]
    tw_right_m: NDArray[np.float64]
    kappa_inv_m: NDArray[np.float64]
    left: Any
    right: Any
    centre: Any
    polygon: Any
    closed: bool
    length_m: float
    seg_m: NDArray[np.float64]
    seg_len_sq_m2: NDArray[np.float64]
    rows: list[list[float]]

    def project(self, x_m: Any, y_m: Any) -> NDArray[np.float64]:
        """Arc length of the nearest centre-line point, ``(N,)`` for ``(N,)`` positions.

        Plain numpy on the cached segments: the nearest centre point first, then the exact
        foot on the ``LOCATE_WINDOW`` segments either side of it (the centre line is
        resampled at ``CENTRE_STEP_M``, so the nearest segment is among them unless the
        track passes within a few metres of itself).
        """
        x = np.asarray(x_m, dtype=np.float64).reshape(-1)
        y = np.asarray(y_m, dtype=np.float64).reshape(-1)
        if SCALAR_PROJECT and len(x):
            xs, ys = x.tolist(), y.tolist()
            if all(map(math.isfinite, xs + ys)):
                return np.array(track_scalar.project_rows(xs, ys, self.rows, LOCATE_WINDOW))
        c = self.centre_m
        near = np.argmin((x[:, None] - c[:, 0]) ** 2 + (y[:, None] - c[:, 1]) ** 2, axis=1)
        # integer bounds: maximum/minimum (np.clip without its per-call iinfo look-up)
        seg = np.minimum(np.maximum(near[:, None] + _WINDOW, 0), len(self.seg_m) - 1)
        dx = x[:, None] - c[seg, 0]
        dy = y[:, None] - c[seg, 1]
        sx, sy = self.seg_m[seg, 0], self.seg_m[seg, 1]
        u = np.clip((dx * sx + dy * sy) / self.seg_len_sq_m2[seg], 0.0, 1.0)
        ox, oy = dx - u * sx, dy - u * sy
        best = np.argmin(ox * ox + oy * oy, axis=1)
        rows = np.arange(len(x))
        k = seg[rows, best]
        return np.asarray(self.s_m[k] + u[rows, best] * (self.s_m[k + 1] - self.s_m[k]))

    def project_scalar(self, x_m: float, y_m: float) -> float:
        """Slow, obvious reference of ``project`` for one position (shapely, whole line)."""
        return float(shapely.line_locate_point(self.centre, shapely.Point(x_m, y_m)))

    def index_at(self, s_m: Any) -> NDArray[np.intp]:
        """Index of the centre point at or just before arc length ``s_m``."""
        idx = np.searchsorted(self.s_m, np.asarray(s_m, dtype=float), side="right") - 1
        return np.minimum(np.maximum(idx, 0), len(self.s_m) - 1)

    def ahead_m(self, s_from: Any, s_to: Any) -> NDArray[np.float64]:
        """Signed distance along the track from ``s_from`` to ``s_to`` (wraps on loops)."""
        d = np.asarray(s_to, dtype=float) - np.asarray(s_from, dtype=float)
        if self.closed:
            d = (d + self.length_m / 2) % self.length_m - self.length_m / 2
        return np.asarray(d, dtype=np.float64)

    def lateral_m(self, x_m: Any, y_m: Any, s_m: Any = None) -> NDArray[np.float64]:
        """Signed lateral offset from the centre line (right positive), ``(N,)``.

        ``s_m``: the positions' ``project`` when already known.
        """
        s = self.project(x_m, y_m) if s_m is None else s_m
        x = np.asarray(x_m, dtype=np.float64).reshape(-1)
        if 0 < len(x) <= SCALAR_POINTS_MAX and np.ndim(x_m) == 1:
            xs = x.tolist()
            ys = np.asarray(y_m, dtype=np.float64).reshape(-1).tolist()
            ss = np.asarray(s, dtype=np.float64).reshape(-1).tolist()
            if len(ss) == len(xs) and all(map(math.isfinite, xs + ys + ss)):
                return np.array(track_scalar.lateral_rows(xs, ys, ss, self.rows))
        i = self.index_at(s)
        dx = np.asarray(x_m, dtype=float) - self.centre_m[i, 0]
        dy = np.asarray(y_m, dtype=float) - self.centre_m[i, 1]
        return np.asarray(dx * self.normal[i, 0] + dy * self.normal[i, 1], dtype=np.float64)

    def span_indices(self, s_from_m: float, length_m: float) -> NDArray[np.intp]:
        """Centre-point indices from ``s_from_m`` forward over ``length_m`` (wraps on loops)."""
        n = len(self.s_m)
        start = int(self.index_at(s_from_m))
        if self.closed:
            ahead = (self.s_m - self.s_m[start]) % self.length_m
            order = np.argsort(ahead, kind="stable")
            return np.asarray(order[ahead[order] <= length_m], dtype=np.intp)
        stop = int(self.index_at(s_from_m + length_m)) + 1
        return np.arange(start, min(max(stop, start + 2), n))

    def strip(self, idx: NDArray[np.intp], lat_a_m: Any, lat_b_m: Any) -> Any:
        """Polygon between two lateral offsets (right positive) over centre points ``idx``.

        Args:
            idx: Centre-point indices in driving order, ``(K,)``, ``K >= 2``.
            lat_a_m: First edge offset, scalar or ``(K,)``.
            lat_b_m: Second edge offset, scalar or ``(K,)``.

        Returns:
            A shapely polygon (made valid).
        """
        c = self.centre_m[idx]
        nrm = self.normal[idx]
        a = c + nrm * np.broadcast_to(np.asarray(lat_a_m, dtype=float), idx.shape)[:, None]
        b = c + nrm * np.broadcast_to(np.asarray(lat_b_m, dtype=float), idx.shape)[:, None]
        return shapely.make_valid(shapely.polygons(np.concatenate([a, b[::-1]])))


def build_track(bounds: TrackBounds, closed_gap_m: float = 35.0) -> TrackGeometry:
    """Derive the centre line, widths, curvature and drivable polygon from the bounds.

    Args:
        bounds: Left and right bounds in driving direction.
        closed_gap_m: The track is a loop if its centre line ends closer than this to its
            start (reference threshold).

    Returns:
        The track geometry.
    """
    left_len = float(np.hypot(*np.diff(bounds.left_m, axis=0).T).sum())
    right_len = float(np.hypot(*np.diff(bounds.right_m, axis=0).T).sum())
    n = max(math.ceil(max(left_len, right_len) / 2 / CENTRE_STEP_M) * 2, 2)
    left = resample_polyline(bounds.left_m, n)
    right = resample_polyline(bounds.right_m, n)
    centre = (left + right) / 2
    s = np.concatenate([[0.0], np.cumsum(np.hypot(*np.diff(centre, axis=0).T))])
    tangent = np.gradient(centre, axis=0)
    tangent /= np.maximum(np.hypot(tangent[:, 0], tangent[:, 1]), 1e-12)[:, None]
    normal = np.stack([tangent[:, 1], -tangent[:, 0]], axis=1)
    heading = np.unwrap(np.arctan2(tangent[:, 1], tangent[:, 0]))
    lo = np.clip(np.searchsorted(s, s - CURVATURE_HALF_WINDOW_M), 0, n - 1)
    hi = np.clip(np.searchsorted(s, s + CURVATURE_HALF_WINDOW_M), 0, n - 1)
    kappa = (heading[hi] - heading[lo]) / np.maximum(s[hi] - s[lo], 1e-9)
    closed = bool(np.hypot(*(centre[0] - centre[-1])) < closed_gap_m)
    left_line = shapely.linestrings(bounds.left_m)
    right_line = shapely.linestrings(bounds.right_m)
    if closed:
        outer = shapely.polygons(bounds.left_m)
        inner = shapely.polygons(bounds.right_m)
        if shapely.area(inner) > shapely.area(outer):
            outer, inner = inner, outer
        polygon = shapely.difference(shapely.make_valid(outer), shapely.make_valid(inner))
    else:
        ring = np.concatenate([bounds.left_m, bounds.right_m[::-1]])
        polygon = shapely.make_valid(shapely.polygons(ring))
    shapely.prepare(polygon)
    seg = np.diff(centre, axis=0)
    seg_len_sq = np.maximum(seg[:, 0] ** 2 + seg[:, 1] ** 2, 1e-24)
    return TrackGeometry(
        centre_m=centre,
        s_m=s,
        normal=normal,
        tw_left_m=np.hypot(*(left - centre).T),
        tw_right_m=np.hypot(*(right - centre).T),
        kappa_inv_m=kappa,
        left=left_line,
        right=right_line,
        centre=shapely.linestrings(centre),
        polygon=polygon,
        closed=closed,
        length_m=float(s[-1]),
        seg_m=seg,
        seg_len_sq_m2=seg_len_sq,
        rows=[
            *centre.T.tolist(),
            *seg.T.tolist(),
            seg_len_sq.tolist(),
            s.tolist(),
            *normal.T.tolist(),
            track_scalar.block_boxes(*centre.T.tolist()),
        ],
    )
