"""``simple`` reachable sets: Althoff & Magdici's over-approximation as a six-vertex polygon.

For an object with speed ``v0`` and acceleration bound ``a`` (body frame, xi forward)::

    c(t) = v0 t                      constant-velocity centre
    r(t) = a t^2 / 2                 radius of the acceleration circle
    b(t) = v0 t - a^2 t^3 / (2 v0)   front of the max-lateral region, t <= t_b = sqrt(2/3) v0/a,
                                     held at b(t_b) afterwards (b = 0 when v0 = 0)

The polygon of step j covers [t_{j-1}, t_j]::

        q1 (c'-r', r')   q2 (b', r)          q3 (c+r, r)
          +--------------+--------------------+
          |                                   |        (primed: at t_{j-1})
          +--------------+--------------------+
        q6 (c'-r', -r')  q5 (b', -r)         q4 (c+r, -r)

The rear edge never moves backwards (no reversing: once ``c - r`` shrinks it stays at its
peak) while its half-width keeps following ``r`` (the reference froze the whole rear vertex,
which under-approximates and makes the set shrink with a larger acceleration bound). The body
is added: q1, q2, q5, q6 move back by L/2, q3 and q4 forward by L/2, every vertex sideways
by W/2.
"""

from __future__ import annotations

import math
from typing import TYPE_CHECKING, Any

import numpy as np
import shapely

from reachsets.footprints import body_to_map

if TYPE_CHECKING:
    from numpy.typing import NDArray

    from reachsets.inputs import ObjectStates

__all__ = ["simple_reach_polygons", "simple_reach_scalar", "simple_reach_vertices"]

_SIDE = np.array([1.0, 1.0, 1.0, -1.0, -1.0, -1.0])
_BODY = np.array([-1.0, -1.0, 1.0, 1.0, -1.0, -1.0])


def _profiles(
    v0: NDArray[np.float64], a: NDArray[np.float64], t: NDArray[np.float64]
) -> tuple[NDArray[np.float64], NDArray[np.float64], NDArray[np.float64]]:
    """``c, r, b`` for ``(N, 1)`` speeds/bounds and ``(T,)`` stamps, each ``(N, T)``."""
    c = v0 * t
    r = 0.5 * a * t**2
    t_b = math.sqrt(2.0 / 3.0) * v0 / a
    t_eff = np.minimum(t, t_b)
    safe_v0 = np.where(v0 > 0, v0, 1.0)
    b = np.where(v0 > 0, v0 * t_eff - a**2 * t_eff**3 / (2 * safe_v0), 0.0)
    return c, r, b


def simple_reach_vertices(
    objects: ObjectStates, times_s: NDArray[np.float64], a_max_mps2: Any
) -> NDArray[np.float64]:
    """Six map-frame vertices per object and step.

    Args:
        objects: The objects (N).
        times_s: Grid stamps ``(T,)`` starting at 0.
        a_max_mps2: Acceleration bound, scalar or ``(N,)``.

    Returns:
        ``(N, T, 6, 2)`` vertices q1..q6.
    """
    v0 = np.asarray(objects.speed_mps, dtype=np.float64)[:, None]
    a = np.broadcast_to(np.asarray(a_max_mps2, dtype=np.float64), v0.shape[:1])[:, None]
    t = np.asarray(times_s, dtype=np.float64)
    # profiles at 0 and every stamp; primed = at the previous stamp (0 before the first)
    c_all, r_all, b_all = _profiles(v0, a, np.concatenate([[0.0], t]))
    c, r = c_all[:, 1:], r_all[:, 1:]
    c_p, r_p, b_p = c_all[:, :-1], r_all[:, :-1], b_all[:, :-1]
    # No reversing: the rear edge stays where c - r peaked; its half-width keeps growing.
    rear_xi = np.maximum.accumulate(c_p - r_p, axis=1)
    rear_eta = r_p
    front = c + r
    xi = np.stack([rear_xi, b_p, front, front, b_p, rear_xi], axis=-1)
    eta = np.stack([rear_eta, r, r, -r, -r, -rear_eta], axis=-1)
    half_l = np.asarray(objects.length_m)[:, None, None] / 2
    half_w = np.asarray(objects.width_m)[:, None, None] / 2
    xi = xi + _BODY * half_l
    eta = eta + _SIDE * half_w
    return body_to_map(
        xi,
        eta,
        np.asarray(objects.x_m)[:, None, None],
        np.asarray(objects.y_m)[:, None, None],
        np.asarray(objects.yaw_rad)[:, None, None],
    )


def simple_reach_polygons(
    objects: ObjectStates, times_s: NDArray[np.float64], a_max_mps2: Any
) -> NDArray[np.object_]:
    """``simple`` reach sets as shapely polygons, ``(N, T)``."""
    verts = simple_reach_vertices(objects, times_s, a_max_mps2)
    if verts.shape[0] == 0:
        return np.empty((0, len(times_s)), dtype=object)
    return np.asarray(shapely.polygons(verts))


def simple_reach_scalar(
    x_m: float,
    y_m: float,
    yaw_rad: float,
    v0_mps: float,
    *,
    length_m: float,
    width_m: float,
    times_s: list[float],
    a_max_mps2: float,
) -> list[list[tuple[float, float]]]:
    """Slow, obvious reference of ``simple_reach_vertices`` for one object."""

    def prof(t: float) -> tuple[float, float, float]:
        c = v0_mps * t
        r = 0.5 * a_max_mps2 * t * t
        if v0_mps <= 0:
            return c, r, 0.0
        tb = math.sqrt(2.0 / 3.0) * v0_mps / a_max_mps2
        te = min(t, tb)
        return c, r, v0_mps * te - a_max_mps2**2 * te**3 / (2 * v0_mps)

    out = []
    rx = -math.inf
    for j, t in enumerate(times_s):
        c, r, _ = prof(t)
        cp, rp, bp = prof(times_s[j - 1] if j > 0 else 0.0)
        rx = max(rx, cp - rp)
        ry = rp
        hl, hw = length_m / 2, width_m / 2
        local = [
            (rx - hl, ry + hw),
            (bp - hl, r + hw),
            (c + r + hl, r + hw),
            (c + r + hl, -r - hw),
            (bp - hl, -r - hw),
            (rx - hl, -ry - hw),
        ]
        co, si = math.cos(yaw_rad), math.sin(yaw_rad)
        out.append([(x_m + co * a - si * b, y_m + si * a + co * b) for a, b in local])
    return out
