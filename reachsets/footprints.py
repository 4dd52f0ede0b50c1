"""Body-frame to map-frame transforms and rectangular footprints, batched.

Body frame: xi forward along the heading, eta to the left::

        eta ^      RL +---------+ FL
            |         |    o----|--> xi (heading)
            |      RR +---------+ FR

Corners are ordered front-left, rear-left, rear-right, front-right (counter-clockwise).
"""

from __future__ import annotations

from typing import TYPE_CHECKING, Any

import numpy as np
import shapely

if TYPE_CHECKING:
    from numpy.typing import NDArray

__all__ = ["body_to_map", "rectangle_corners", "rectangles"]

_CORNER_SIGNS = np.array([[1.0, 1.0], [-1.0, 1.0], [-1.0, -1.0], [1.0, -1.0]])


def body_to_map(
    xi: NDArray[np.float64],
    eta: NDArray[np.float64],
    x_m: Any,
    y_m: Any,
    yaw_rad: Any,
) -> NDArray[np.float64]:
    """Map body-frame coordinates to the map frame.

    Args:
        xi: Longitudinal body coordinates, any shape ``S`` (metres).
        eta: Lateral body coordinates (left positive), shape ``S``.
        x_m: Body origin x, broadcastable to ``S``.
        y_m: Body origin y, broadcastable to ``S``.
        yaw_rad: Body heading (ENU), broadcastable to ``S``.

    Returns:
        ``S + (2,)`` map coordinates.
    """
    c = np.cos(yaw_rad)
    s = np.sin(yaw_rad)
    px = x_m + c * xi - s * eta
    py = y_m + s * xi + c * eta
    out = np.empty((*np.broadcast_shapes(np.shape(px), np.shape(py)), 2))
    out[..., 0] = px
    out[..., 1] = py
    return out


def rectangle_corners(
    x_m: Any, y_m: Any, yaw_rad: Any, length_m: Any, width_m: Any
) -> NDArray[np.float64]:
    """Corners of centred rectangles.

    Args:
        x_m: Centre x, shape ``S``.
        y_m: Centre y, shape ``S``.
        yaw_rad: Heading, shape ``S``.
        length_m: Length along the heading, broadcastable to ``S``.
        width_m: Width, broadcastable to ``S``.

    Returns:
        ``S + (4, 2)`` corners (FL, RL, RR, FR).
    """
    half_l = np.asarray(length_m, dtype=np.float64)[..., None] / 2
    half_w = np.asarray(width_m, dtype=np.float64)[..., None] / 2
    return body_to_map(
        _CORNER_SIGNS[:, 0] * half_l,
        _CORNER_SIGNS[:, 1] * half_w,
        np.asarray(x_m, dtype=np.float64)[..., None],
        np.asarray(y_m, dtype=np.float64)[..., None],
        np.asarray(yaw_rad, dtype=np.float64)[..., None],
    )


def rectangles(
    x_m: Any, y_m: Any, yaw_rad: Any, length_m: Any, width_m: Any
) -> NDArray[np.object_]:
    """Rectangles as shapely polygons, shape ``S`` (see ``rectangle_corners``)."""
    return np.asarray(shapely.polygons(rectangle_corners(x_m, y_m, yaw_rad, length_m, width_m)))
