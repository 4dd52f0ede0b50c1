"""Touch test of convex polygons in plain numpy (separating axis theorem), batched.

Two closed convex polygons are disjoint exactly when the projections of their vertices onto
the normal of one of their edges do not overlap::

         a            b
       +---+       +-----+          axis n (normal of one of a's edges):
       |   |       |     |          [min_a, max_a] and [min_b, max_b] apart -> disjoint
       +---+       +-----+
    ---[---]-------[-----]---> n

Touching (shared boundary points) counts as intersecting, like ``shapely.intersects``.

A few pairs (one frame of a few objects) are tested pair by pair by the scalar twin
``small_scalar.convex_touch_rows`` (compiled with mypyc; the same products and
comparisons, so the same booleans) instead of paying numpy's per-call overhead.
"""

from __future__ import annotations

import math
from typing import TYPE_CHECKING

import numpy as np

from reachsets import small_scalar

if TYPE_CHECKING:
    from numpy.typing import NDArray

__all__ = ["SCALAR_TOUCH_MAX", "convex_touch"]

#: Up to this many polygon pairs the scalar twin tests them one by one; above it, numpy
#: (measured crossover on the racing sample's 21-stamp frames, compiled or from the source).
SCALAR_TOUCH_MAX = 48 if not small_scalar.__file__.endswith(".py") else 1


def _split(
    v: NDArray[np.float64], lead: tuple[int, ...]
) -> tuple[NDArray[np.float64], NDArray[np.float64], NDArray[np.float64], NDArray[np.float64]]:
    """Vertex coordinates and edge vectors with the vertex axis first: 4 x ``(P, *lead)``.

    Reductions over a leading axis are plain element-wise operations in numpy; over a short
    trailing axis they are an order of magnitude slower.
    """
    if v.shape[:-2] != lead:
        v = np.broadcast_to(v, (*lead, *v.shape[-2:]))
    order = (len(lead), *range(len(lead)))
    x = v[..., 0].transpose(order)
    y = v[..., 1].transpose(order)
    ex = np.concatenate([x[1:], x[:1]]) - x
    ey = np.concatenate([y[1:], y[:1]]) - y
    return x, y, ex, ey


def convex_touch(
    a: NDArray[np.float64], b: NDArray[np.float64], *, scalar: bool | None = None
) -> NDArray[np.bool_]:
    """Whether convex polygons ``a`` and ``b`` intersect (touching included).

    Args:
        a: Vertices ``(..., P, 2)`` of convex polygons (either orientation, not closed;
            repeated vertices allowed).
        b: Vertices ``(..., Q, 2)``; the leading dimensions broadcast with ``a``'s.
        scalar: Pair by pair with the scalar twin (``None``: when the pairs are at most
            ``SCALAR_TOUCH_MAX``); the same booleans either way.

    Returns:
        ``(...)`` booleans.
    """
    lead = np.broadcast_shapes(a.shape[:-2], b.shape[:-2])
    if scalar if scalar is not None else math.prod(lead) <= SCALAR_TOUCH_MAX:
        pa = np.broadcast_to(a, (*lead, *a.shape[-2:])).reshape(-1, 2 * a.shape[-2])
        pb = np.broadcast_to(b, (*lead, *b.shape[-2:])).reshape(-1, 2 * b.shape[-2])
        got = small_scalar.convex_touch_rows(pa.tolist(), pb.tolist())
        return np.array(got, dtype=bool).reshape(lead)
    ax, ay, aex, aey = _split(a, lead)
    bx, by, bex, bey = _split(b, lead)
    # axis k is the normal (-ey, ex) of edge k of a, then of b: (K, *lead)
    ex = np.concatenate([aex, bex])[None]
    ey = np.concatenate([aey, bey])[None]
    pa = ex * ay[:, None] - ey * ax[:, None]  # (P, K, *lead)
    pb = ex * by[:, None] - ey * bx[:, None]  # (Q, K, *lead)
    apart = (pa.max(axis=0) < pb.min(axis=0)) | (pb.max(axis=0) < pa.min(axis=0))
    return np.asarray(~apart.any(axis=0))
