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

from reachsets.reach_turn import arc_profile

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

    The curve is the ``turn`` arc until its first chord that may not turn towards the wall:
    every chord's rule is first checked on the ``turn`` arc at once, and only the curves
    that turn back are continued chord by chord from there.

    Args:
        objects: The objects (N).
        params: Arc parameters as for ``steering_arcs``.
        track: Track geometry; the left wall bounds the left curve, the right wall the right.
        side: ``+1.0`` left, ``-1.0`` right.

    Returns:
        ``(xi, eta)``, each ``(N, P)``.
    """
    xi, eta, psi, dmax = arc_profile(objects, params)
    eta = side * eta
    if len(objects) == 0:
        return xi, eta
    wall = _wall_arrays(track.left if side > 0 else track.right)
    pose = (
        np.asarray(objects.x_m, dtype=np.float64)[:, None],
        np.asarray(objects.y_m, dtype=np.float64)[:, None],
        np.asarray(objects.yaw_rad, dtype=np.float64)[:, None],
    )
    ok = _turn(pose, wall, xi[:, :-1], eta[:, :-1], psi[:, :-1], dmax, side, params)[1]
    back = ~ok
    rows = np.flatnonzero(back.any(axis=1))
    if len(rows) == 0:
        return xi, eta
    start = np.argmax(back[rows], axis=1) + 1  # first chord (1-based) that turns back
    sub_pose = (pose[0][rows], pose[1][rows], pose[2][rows])
    sub_xi, sub_eta, sub_psi = xi[rows], eta[rows], psi[rows]
    c = params.arc_step_m
    for k in range(int(start.min()), params.arc_points):
        live = np.flatnonzero(k >= start)
        dpsi = _turn(
            (sub_pose[0][live], sub_pose[1][live], sub_pose[2][live]),
            wall,
            sub_xi[live, k - 1 : k],
            sub_eta[live, k - 1 : k],
            sub_psi[live, k - 1 : k],
            dmax[rows[live], k - 1 : k],
            side,
            params,
        )[0][:, 0]
        chord = sub_psi[live, k - 1] + dpsi / 2
        sub_xi[live, k] = sub_xi[live, k - 1] + c * np.cos(chord)
        sub_eta[live, k] = sub_eta[live, k - 1] + side * c * np.sin(chord)
        sub_psi[live, k] = sub_psi[live, k - 1] + dpsi
    xi[rows], eta[rows] = sub_xi, sub_eta
    return xi, eta


def _turn(  # noqa: PLR0917 - the chord rule needs the whole state
    pose: tuple[NDArray[np.float64], ...],
    wall: tuple[NDArray[np.float64], ...],
    xi: NDArray[np.float64],
    eta: NDArray[np.float64],
    psi: NDArray[np.float64],
    dmax: NDArray[np.float64],
    side: float,
    params: ReachParams,
) -> tuple[NDArray[np.float64], NDArray[np.bool_]]:
    """Turn of the next chord from each point, and whether it may turn towards the wall.

    Args:
        pose: Object ``(x, y, yaw)``, each ``(N, 1)``.
        wall: ``_wall_arrays`` of the wall on this side.
        xi: Body-frame point the chord starts at, ``(N, K)``.
        eta: Its lateral coordinate, ``(N, K)``.
        psi: Heading change so far (towards the wall side), ``(N, K)``.
        dmax: Largest turn of the chord, ``(N, K)``.
        side: ``+1.0`` left, ``-1.0`` right.
        params: Arc parameters.

    Returns:
        ``dpsi`` and ``towards``, each ``(N, K)``.
    """
    ox, oy, yaw0 = pose
    cos0, sin0 = np.cos(yaw0), np.sin(yaw0)
    x = ox + cos0 * xi - sin0 * eta
    y = oy + sin0 * xi + cos0 * eta
    wx, wy, tw = _wall_frame(wall, x.reshape(-1), y.reshape(-1))
    wx, wy = wx.reshape(x.shape), wy.reshape(x.shape)
    tx, ty = tw[:, 0].reshape(x.shape), tw[:, 1].reshape(x.shape)
    clearance = -side * (tx * (y - wy) - ty * (x - wx))
    heading = yaw0 + side * psi
    rel = np.arctan2(np.sin(heading), np.cos(heading)) - np.arctan2(ty, tx)
    alpha = side * np.arctan2(np.sin(rel), np.cos(rel))
    radius = params.arc_step_m / (2 * np.sin(np.maximum(dmax, 1e-12) / 2))
    room = clearance - params.arc_step_m * np.sin(alpha + dmax / 2)
    need = radius * (1 - np.cos(np.clip(alpha + dmax, 0.0, np.pi)))
    towards = (np.abs(alpha) >= np.pi / 2) | (room >= need)
    back = np.minimum(dmax, np.maximum(alpha, 0.0))
    dpsi = np.minimum(np.where(towards, dmax, -back), params.arc_max_turn_rad - psi)
    return dpsi, towards
