"""``bound`` reachable sets: steering arcs that respect the track walls.

Each edge curve starts at a front corner like the ``turn`` arcs but, before every chord, checks
whether turning further towards its wall would still leave room to straighten out along the
wall; otherwise it turns back towards the wall's direction and then follows the wall::

    wall  ===========================================  (tangent t_w)
             d  ^          .--------------------------  edge follows the wall
                |      .-'   turn back (alpha -> 0)
         corner o---'        turn towards the wall while
                             d - c sin(alpha + dpsi/2) >= r (1 - cos(alpha + dpsi))

``alpha`` is the heading towards the wall relative to the wall tangent, ``d`` the clearance.
A vehicle that would hit the wall is outside the rule-conform behaviour, so the funnel between
the two edge curves is tighter than ``turn``'s where a wall is near. This is our own
wall-following construction in the spirit of the reference's double arc (see docs).
"""

from __future__ import annotations

from typing import TYPE_CHECKING, Any

import numpy as np
import shapely

from reachsets.reach_turn import steering_arcs

if TYPE_CHECKING:
    from numpy.typing import NDArray

    from reachsets.inputs import ObjectStates
    from reachsets.params import ReachParams
    from reachsets.track import TrackGeometry

__all__ = ["wall_aware_arcs"]

_TANGENT_HALF_STEP_M = 0.5


def _wall_arrays(wall: Any) -> tuple[NDArray[np.float64], ...]:
    """Wall vertices ``(M, 2)``, segment vectors, their lengths and cumulative arc length."""
    pts = shapely.get_coordinates(wall)
    seg = np.diff(pts, axis=0)
    seg_len = np.hypot(seg[:, 0], seg[:, 1])
    return pts, seg, seg_len, np.concatenate([[0.0], np.cumsum(seg_len)])


def _wall_frame(
    wall: tuple[NDArray[np.float64], ...], x: NDArray[np.float64], y: NDArray[np.float64]
) -> tuple[NDArray[np.float64], NDArray[np.float64], NDArray[np.float64]]:
    """Nearest wall point and unit tangent for ``(N,)`` positions: ``(wx, wy)``, ``t``.

    Plain numpy over all ``(N, M)`` point-segment pairs of ``_wall_arrays`` (no shapely
    calls in the arc loop): the nearest point's arc length ``s`` on the wall, the tangent
    through the wall points at ``s -+ 0.5 m`` (clamped to the ends).
    """
    pts, seg, seg_len, cum = wall
    dx = x[:, None] - pts[None, :-1, 0]
    dy = y[:, None] - pts[None, :-1, 1]
    u = np.clip((dx * seg[:, 0] + dy * seg[:, 1]) / np.maximum(seg_len**2, 1e-24), 0.0, 1.0)
    ox = dx - u * seg[:, 0]
    oy = dy - u * seg[:, 1]
    best = np.argmin(ox * ox + oy * oy, axis=1)
    s = cum[best] + u[np.arange(len(best)), best] * seg_len[best]
    probe = np.concatenate(
        [
            s,
            np.minimum(s + _TANGENT_HALF_STEP_M, cum[-1]),
            np.maximum(s - _TANGENT_HALF_STEP_M, 0.0),
        ]
    )
    px = np.interp(probe, cum, pts[:, 0]).reshape(3, -1)
    py = np.interp(probe, cum, pts[:, 1]).reshape(3, -1)
    t = np.stack([px[1] - px[2], py[1] - py[2]], axis=1)
    t /= np.maximum(np.hypot(t[:, 0], t[:, 1]), 1e-12)[:, None]
    return px[0], py[0], t


def wall_aware_arcs(
    objects: ObjectStates, params: ReachParams, track: TrackGeometry, side: float
) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """Body-frame wall-aware edge curve of every object on one side.

    Args:
        objects: The objects (N).
        params: Arc parameters as for ``steering_arcs``.
        track: Track geometry; the left wall bounds the left curve, the right wall the right.
        side: ``+1.0`` left, ``-1.0`` right.

    Returns:
        ``(xi, eta)``, each ``(N, P)``.
    """
    n = len(objects)
    if n == 0:
        return steering_arcs(objects, params, side)
    wall = _wall_arrays(track.left if side > 0 else track.right)
    yaw0 = np.asarray(objects.yaw_rad, dtype=np.float64)
    cos0, sin0 = np.cos(yaw0), np.sin(yaw0)
    xi = np.empty((n, params.arc_points))
    eta = np.empty((n, params.arc_points))
    xi[:, 0] = np.asarray(objects.length_m) / 2
    eta[:, 0] = side * np.asarray(objects.width_m) / 2
    v2 = np.asarray(objects.speed_mps, dtype=np.float64) ** 2
    psi = np.zeros(n)
    c = params.arc_step_m
    for k in range(1, params.arc_points):
        x = objects.x_m + cos0 * xi[:, k - 1] - sin0 * eta[:, k - 1]
        y = objects.y_m + sin0 * xi[:, k - 1] + cos0 * eta[:, k - 1]
        wx, wy, tw = _wall_frame(wall, x, y)
        cross = tw[:, 0] * (y - wy) - tw[:, 1] * (x - wx)
        clearance = -side * cross
        heading = yaw0 + side * psi
        rel = np.arctan2(np.sin(heading), np.cos(heading)) - np.arctan2(tw[:, 1], tw[:, 0])
        alpha = side * np.arctan2(np.sin(rel), np.cos(rel))
        radius = np.maximum(v2 / params.ay_max_mps2, params.turn_radius_m)
        dmax = 2 * np.arcsin(np.minimum(c / (2 * radius), 1.0))
        room = clearance - c * np.sin(alpha + dmax / 2)
        need = radius * (1 - np.cos(np.clip(alpha + dmax, 0.0, np.pi)))
        aligned = np.abs(alpha) < np.pi / 2
        towards = ~aligned | (room >= need)
        back = np.minimum(dmax, np.maximum(alpha, 0.0))
        dpsi = np.where(towards, dmax, -back)
        dpsi = np.minimum(dpsi, params.arc_max_turn_rad - psi)
        chord = psi + dpsi / 2
        xi[:, k] = xi[:, k - 1] + c * np.cos(chord)
        eta[:, k] = eta[:, k - 1] + side * c * np.sin(chord)
        psi = psi + dpsi
        v2 = np.maximum(v2 - 2 * params.ax_max_mps2 * c, 0.0)
    return xi, eta
