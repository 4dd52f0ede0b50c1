"""``turn`` reachable sets: the ``simple`` set minus what lies outside two steering arcs.

Each arc starts at a front corner and turns as hard as allowed, braking at the same time
(longitudinal and lateral acceleration treated as decoupled)::

    r_k = max(v_k^2 / ay_max, turn_radius)          radius of chord k (length c)
    dpsi_k = 2 asin(c / (2 r_k))                     heading change (lateral offset c^2/(2r))
    v_{k+1}^2 = max(v_k^2 - 2 ax_max c, 0)            full braking along the arc

The deletion polygon is everything outside the funnel between the arcs (body frame). As in
the reference (``keep_body=False``, the default) it runs from the end of the left arc back to
the front-left corner, across the front to the front-right corner, along the right arc, then
``e`` = 50 m to the right, to 50 m behind and right of the centre, 50 m behind and left, and
``e`` to the left of the left arc's end::

    (-e, +e) +.......................+ (xi_L, eta_L + e)
             |           left arc ..-+ end of left arc
             |   +----+ FL ..--'
             |   |body|    funnel (kept)  --> ahead, open
             |   +----+ FR ''--.
             |          right arc ''-+ end of right arc
    (-e, -e) +.......................+ (xi_R, eta_R - e)

So the reference also deletes the object's own body and everything beside it behind its
front edge. ``keep_body=True`` is the sound variant: the funnel holds the body, its sides
running from the rear corners straight to each arc's second point, so the deletion never
removes the object's footprint nor the few centimetres its sides swing out while it turns
(it flags more steps on the TUM logs; see ``docs/reachsets.md``). Arcs stop turning after
``arc_max_turn_rad`` so the polygon stays simple at low speed.
"""

from __future__ import annotations

import math
from typing import TYPE_CHECKING

import numpy as np

from reachsets.footprints import body_to_map

if TYPE_CHECKING:
    from numpy.typing import NDArray

    from reachsets.inputs import ObjectStates
    from reachsets.params import ReachParams

__all__ = [
    "EXTENSION_M",
    "arc_profile",
    "funnel_coords",
    "steering_arc_scalar",
    "steering_arcs",
]

#: How far the deletion polygon reaches sideways and behind (reference ``turn``: 50 m).
EXTENSION_M = 50.0


def steering_arcs(
    objects: ObjectStates, params: ReachParams, side: float
) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """Body-frame steering arc of every object on one side.

    Args:
        objects: The objects (N).
        params: Arc parameters (``arc_points``, ``arc_step_m``, ``turn_radius_m``,
            ``ay_max_mps2``, ``ax_max_mps2``, ``arc_max_turn_rad``).
        side: ``+1.0`` for the left arc, ``-1.0`` for the right one.

    Returns:
        ``(xi, eta)``, each ``(N, P)`` with ``P = arc_points``, starting at the front corner.
    """
    xi, eta, _, _ = arc_profile(objects, params)
    return xi, side * eta


def arc_profile(
    objects: ObjectStates, params: ReachParams
) -> tuple[NDArray[np.float64], NDArray[np.float64], NDArray[np.float64], NDArray[np.float64]]:
    """The left steering arc in closed form, vectorised over objects and points.

    The heading after chord ``k`` is ``min(sum of the chords' turns, arc_max_turn_rad)`` (each
    turn is ``>= 0``, so clamping every step equals clamping the running sum); chord ``k``
    points half-way between the headings before and after it.

    Returns:
        ``(xi, eta, psi, dmax)``: the left arc (the right one is ``(xi, -eta)``) and the
        heading at each point, each ``(N, P)``; the largest turn of each chord, ``(N, P - 1)``.
    """
    c = params.arc_step_m
    k = np.arange(params.arc_points - 1)
    v0 = np.asarray(objects.speed_mps, dtype=np.float64)[:, None]
    v2 = np.maximum(v0**2 - 2 * params.ax_max_mps2 * c * k, 0.0)
    radius = np.maximum(v2 / params.ay_max_mps2, params.turn_radius_m)
    dmax = 2 * np.arcsin(np.minimum(c / (2 * radius), 1.0))
    psi = np.zeros((len(v0), params.arc_points))
    psi[:, 1:] = np.minimum(np.cumsum(dmax, axis=1), params.arc_max_turn_rad)
    chord = (psi[:, :-1] + psi[:, 1:]) / 2
    xi = np.empty_like(psi)
    eta = np.empty_like(psi)
    xi[:, 0] = np.asarray(objects.length_m) / 2
    eta[:, 0] = np.asarray(objects.width_m) / 2
    xi[:, 1:] = c * np.cos(chord)
    eta[:, 1:] = c * np.sin(chord)
    return np.cumsum(xi, axis=1), np.cumsum(eta, axis=1), psi, dmax


def steering_arc_scalar(
    v0_mps: float, length_m: float, width_m: float, params: ReachParams, side: float
) -> list[tuple[float, float]]:
    """Slow, obvious reference of ``steering_arcs`` for one object (body frame)."""
    pts = [(length_m / 2, side * width_m / 2)]
    v2 = v0_mps**2
    psi = 0.0
    for _ in range(1, params.arc_points):
        radius = max(v2 / params.ay_max_mps2, params.turn_radius_m)
        dpsi = min(
            2 * math.asin(min(params.arc_step_m / (2 * radius), 1.0)), params.arc_max_turn_rad - psi
        )
        x, y = pts[-1]
        pts.append(
            (
                x + params.arc_step_m * math.cos(psi + dpsi / 2),
                y + side * params.arc_step_m * math.sin(psi + dpsi / 2),
            )
        )
        psi += dpsi
        v2 = max(v2 - 2 * params.ax_max_mps2 * params.arc_step_m, 0.0)
    return pts


def funnel_coords(
    objects: ObjectStates,
    left: tuple[NDArray[np.float64], NDArray[np.float64]],
    right: tuple[NDArray[np.float64], NDArray[np.float64]],
    extension_m: float = EXTENSION_M,
    *,
    keep_body: bool = False,
) -> NDArray[np.float64]:
    """Rings of the deletion polygons outside the funnel between two body-frame edge curves.

    Args:
        objects: The objects (N).
        left: Left edge ``(xi, eta)``, each ``(N, P)``, starting at the front-left corner.
        right: Right edge, each ``(N, Q)``, starting at the front-right corner.
        extension_m: Sideways and backwards reach of the polygon.
        keep_body: Keep the object's body out of the deletion (sound variant); ``False``
            deletes everything behind the front corners, as the reference does.

    Returns:
        ``(N, V, 2)`` map-frame vertices of each ring (open; may self-intersect).
    """
    lxi, leta = left
    rxi, reta = right
    e = extension_m
    if keep_body:
        half_l = np.asarray(objects.length_m)[:, None] / 2
        half_w = np.asarray(objects.width_m)[:, None] / 2
        eta_l = leta.max(axis=1, keepdims=True) + e
        eta_r = reta.min(axis=1, keepdims=True) - e
        back = -half_l - e
        # The front corners themselves are skipped: the body sides run straight from the rear
        # corners to the arcs' second points, leaving room for the sides to swing out.
        xi = np.concatenate(
            [lxi[:, :0:-1], -half_l, -half_l, rxi[:, 1:], rxi[:, -1:], back, back, lxi[:, -1:]],
            axis=1,
        )
        eta = np.concatenate(
            [leta[:, :0:-1], half_w, -half_w, reta[:, 1:], eta_r, eta_r, eta_l, eta_l], axis=1
        )
    else:
        back = np.full((len(lxi), 1), -e)
        xi = np.concatenate([lxi[:, ::-1], rxi, rxi[:, -1:], back, back, lxi[:, -1:]], axis=1)
        eta = np.concatenate(
            [leta[:, ::-1], reta, reta[:, -1:] - e, back, -back, leta[:, -1:] + e], axis=1
        )
    return body_to_map(
        xi,
        eta,
        np.asarray(objects.x_m)[:, None],
        np.asarray(objects.y_m)[:, None],
        np.asarray(objects.yaw_rad)[:, None],
    )
