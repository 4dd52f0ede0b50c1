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

from typing import TYPE_CHECKING

import numpy as np

from reachsets.reach_turn import arc_profile
from reachsets.walls import track_walls, wall_frame

if TYPE_CHECKING:
    from numpy.typing import NDArray

    from reachsets.inputs import ObjectStates
    from reachsets.params import ReachParams
    from reachsets.track import TrackGeometry
    from reachsets.walls import Walls

__all__ = ["wall_aware_arcs"]


def wall_aware_arcs(
    objects: ObjectStates, params: ReachParams, track: TrackGeometry
) -> tuple[tuple[NDArray[np.float64], NDArray[np.float64]], ...]:
    """Body-frame wall-aware edge curves of every object, both sides at once.

    Each curve is the ``turn`` arc until its first chord that may not turn towards its wall:
    every chord's rule is first checked on the ``turn`` arcs at once, and only the curves
    that turn back are continued chord by chord from there.

    Args:
        objects: The objects (N).
        params: Arc parameters as for ``steering_arcs``.
        track: Track geometry; the left wall bounds the left curve, the right wall the right.

    Returns:
        ``((xi, eta) left, (xi, eta) right)``, each array ``(N, P)``.
    """
    xi, eta, psi, dmax = arc_profile(objects, params)
    n = len(objects)
    if n == 0:
        return (xi, eta), (xi, -eta)
    # rows: the left curves, then the right ones
    side = np.repeat([1.0, -1.0], n)[:, None]
    which = np.repeat([0, 1], n)
    xi, eta, psi, dmax = (np.concatenate([v, v]) for v in (xi, eta, psi, dmax))
    eta = side * eta
    walls = track_walls(track)
    pose = tuple(
        np.tile(np.asarray(v, dtype=np.float64), 2)[:, None]
        for v in (objects.x_m, objects.y_m, objects.yaw_rad)
    )
    # every chord of the turn arcs at once, one wall at a time (many positions)
    back = np.concatenate(
        [
            ~_turn(
                tuple(v[rows] for v in pose),
                walls,
                w,
                side[rows],
                (xi[rows, :-1], eta[rows, :-1], psi[rows, :-1], dmax[rows]),
                params,
            )[1]
            for w, rows in ((0, slice(0, n)), (1, slice(n, 2 * n)))
        ]
    )
    rows = np.flatnonzero(back.any(axis=1))
    start = np.argmax(back[rows], axis=1) + 1  # first chord (1-based) that turns back
    c = params.arc_step_m
    for k in range(int(start.min()) if len(rows) else params.arc_points, params.arc_points):
        r = rows[k >= start]
        dpsi = _turn(
            (pose[0][r], pose[1][r], pose[2][r]),
            walls,
            which[r],
            side[r],
            (xi[r, k - 1 : k], eta[r, k - 1 : k], psi[r, k - 1 : k], dmax[r, k - 1 : k]),
            params,
        )[0][:, 0]
        chord = psi[r, k - 1] + dpsi / 2
        xi[r, k] = xi[r, k - 1] + c * np.cos(chord)
        eta[r, k] = eta[r, k - 1] + side[r, 0] * c * np.sin(chord)
        psi[r, k] = psi[r, k - 1] + dpsi
    return (xi[:n], eta[:n]), (xi[n:], eta[n:])


def _turn(  # noqa: PLR0917 - the chord rule needs the whole state
    pose: tuple[NDArray[np.float64], ...],
    walls: Walls,
    which: NDArray[np.intp] | int,
    side: NDArray[np.float64],
    chords: tuple[NDArray[np.float64], ...],
    params: ReachParams,
) -> tuple[NDArray[np.float64], NDArray[np.bool_]]:
    """Turn of the next chord from each point, and whether it may turn towards the wall.

    Args:
        pose: Object ``(x, y, yaw)`` of each curve, each ``(R, 1)``.
        walls: Both walls.
        which: Wall of each curve (0 left, 1 right), ``(R,)``, or one wall for all.
        side: ``+1.0`` for a left curve, ``-1.0`` for a right one, ``(R, 1)``.
        chords: Body-frame start ``(xi, eta)`` of each chord, the heading change so far
            (towards the wall side) and the chord's largest turn, each ``(R, K)``.
        params: Arc parameters.

    Returns:
        ``dpsi`` and ``towards``, each ``(R, K)``.
    """
    xi, eta, psi, dmax = chords
    ox, oy, yaw0 = pose
    cos0, sin0 = np.cos(yaw0), np.sin(yaw0)
    x = ox + cos0 * xi - sin0 * eta
    y = oy + sin0 * xi + cos0 * eta
    flat = which if isinstance(which, int) else np.repeat(which, x.shape[1])
    wx, wy, tx, ty = (v.reshape(x.shape) for v in wall_frame(walls, x.ravel(), y.ravel(), flat))
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
