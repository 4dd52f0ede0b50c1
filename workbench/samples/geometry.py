"""Arc-length parameterised polylines and the path shapes scenarios are built from.

Headings are ENU (0 = +x, counter-clockwise positive); a positive lateral offset is to the
left of the travel direction::

      offset d > 0   o-----o-----o
      path         --o-----o-----o-->  (increasing s)
      offset d < 0   o-----o-----o
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np

if TYPE_CHECKING:
    from collections.abc import Sequence

    from numpy.typing import ArrayLike, NDArray

__all__ = ["Polyline", "build_path", "quintic_step"]


@dataclass(frozen=True, slots=True)
class Polyline:
    """A 2-D polyline with cumulative arc length.

    Attributes:
        points_m: Vertices, ``(K, 2)``, K >= 2, no repeated consecutive vertices.
        s_m: Arc length at each vertex, ``(K,)``, starting at 0.
        heading_rad: Unwrapped heading at each vertex (mean of the adjacent segments), ``(K,)``.
    """

    points_m: NDArray[np.float64]
    s_m: NDArray[np.float64]
    heading_rad: NDArray[np.float64]

    @classmethod
    def from_points(cls, points: ArrayLike) -> Polyline:
        """Build from ``(K, 2)`` vertices."""
        pts = np.asarray(points, dtype=np.float64)
        steps = np.diff(pts, axis=0)
        seg_len = np.hypot(steps[:, 0], steps[:, 1])
        if len(pts) < 2 or np.any(seg_len <= 0):  # noqa: PLR2004
            msg = "a polyline needs >= 2 distinct consecutive vertices"
            raise ValueError(msg)
        seg_heading = np.unwrap(np.arctan2(steps[:, 1], steps[:, 0]))
        vertex_heading = np.concatenate(
            [seg_heading[:1], (seg_heading[:-1] + seg_heading[1:]) / 2, seg_heading[-1:]]
        )
        s = np.concatenate([[0.0], np.cumsum(seg_len)])
        return cls(points_m=pts, s_m=s, heading_rad=vertex_heading)

    @property
    def length_m(self) -> float:
        """Total arc length."""
        return float(self.s_m[-1])

    def xy(self, s_m: ArrayLike) -> NDArray[np.float64]:
        """Points at arc lengths ``s_m`` ``(N,)`` (clamped to the ends), ``(N, 2)``."""
        s = np.asarray(s_m, dtype=np.float64)
        return np.stack(
            [
                np.interp(s, self.s_m, self.points_m[:, 0]),
                np.interp(s, self.s_m, self.points_m[:, 1]),
            ],
            axis=-1,
        )

    def heading(self, s_m: ArrayLike) -> NDArray[np.float64]:
        """Unwrapped heading at arc lengths ``s_m`` ``(N,)``, linear between vertices."""
        return np.interp(np.asarray(s_m, dtype=np.float64), self.s_m, self.heading_rad)

    def offset(self, d_m: float) -> Polyline:
        """The parallel polyline at lateral offset ``d_m`` (positive = left)."""
        normal = np.stack([-np.sin(self.heading_rad), np.cos(self.heading_rad)], axis=-1)
        return Polyline.from_points(self.points_m + d_m * normal)

    def pose(self, s_m: ArrayLike, d_m: ArrayLike = 0.0) -> NDArray[np.float64]:
        """Points at arc lengths ``s_m`` shifted laterally by ``d_m``, ``(N, 2)``."""
        s = np.asarray(s_m, dtype=np.float64)
        h = self.heading(s)
        d = np.asarray(d_m, dtype=np.float64)
        base = self.xy(s)
        return base + np.stack([-np.sin(h) * d, np.cos(h) * d], axis=-1)

    def sample(self, s0_m: float, s1_m: float, step_m: float) -> NDArray[np.float64]:
        """Vertices between ``s0_m`` and ``s1_m`` (both included) about ``step_m`` apart."""
        n = max(1, round((s1_m - s0_m) / step_m))
        return self.xy(np.linspace(s0_m, s1_m, n + 1))


def build_path(
    start_m: Sequence[float],
    heading_rad: float,
    pieces: Sequence[tuple[float, float]],
    step_m: float = 0.5,
) -> Polyline:
    """Integrate a path of constant-curvature pieces (straights and circular arcs).

    Args:
        start_m: Start point ``(x, y)``.
        heading_rad: Start heading.
        pieces: ``(length_m, curvature_1pm)`` per piece; curvature > 0 turns left.
        step_m: Approximate vertex spacing.

    Returns:
        The path as a polyline.
    """
    pts = [np.asarray(start_m, dtype=np.float64)]
    x, y = float(start_m[0]), float(start_m[1])
    h = heading_rad
    for length, kappa in pieces:
        n = max(1, int(np.ceil(length / step_m)))
        ds = np.full(n, length / n)
        s = np.cumsum(ds)
        if abs(kappa) < 1e-12:  # noqa: PLR2004
            xs = x + s * np.cos(h)
            ys = y + s * np.sin(h)
        else:
            xs = x + (np.sin(h + kappa * s) - np.sin(h)) / kappa
            ys = y - (np.cos(h + kappa * s) - np.cos(h)) / kappa
        pts.append(np.stack([xs, ys], axis=-1))
        x, y, h = float(xs[-1]), float(ys[-1]), h + kappa * length
    return Polyline.from_points(np.vstack([p.reshape(-1, 2) for p in pts]))


def quintic_step(t_s: ArrayLike, t0_s: float, duration_s: float) -> NDArray[np.float64]:
    """Smooth 0 -> 1 step (zero velocity and acceleration at both ends), ``(N,)``."""
    u = np.clip((np.asarray(t_s, dtype=np.float64) - t0_s) / duration_s, 0.0, 1.0)
    return u**3 * (10 - 15 * u + 6 * u**2)
