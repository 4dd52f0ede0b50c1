"""Scalar twins of one frame's ego occupancy and touch test (compiled with mypyc).

Called one frame at a time, ``occupancy.ego_occupancy_many`` spends most of its time in numpy
call overhead on arrays of a few dozen values. These twins do the same float operations in
the same order on Python floats (compiled with the other scalar twins, see
``rss.compiled``), so they give bit-identical poses; ``hypot`` stays with numpy in the
caller (``math.hypot`` may differ in the last bit). ``convex_touch_rows`` is
``convex.convex_touch`` pair by pair: the same products and differences, so the same
booleans.
"""

from __future__ import annotations

import math

__all__ = [
    "convex_touch_rows",
    "interp_poses",
    "simple_vertices_rows",
    "unwrapped",
    "waypoint_times",
]


def waypoint_times(ds: list[float], v: list[float], t: list[float]) -> list[float]:
    """``occupancy._waypoint_times`` of one trajectory (``ds``: its chord lengths)."""
    if all(math.isfinite(x) for x in t):
        return t
    speeds = [x if math.isfinite(x) else 0.0 for x in v]
    out = [0.0]
    total = 0.0
    for i, d in enumerate(ds):
        total += d / max((speeds[i] + speeds[i + 1]) / 2, 0.01)
        out.append(total)
    return out


def unwrapped(yaw: list[float]) -> list[float]:
    """``occupancy._unwrap_rows`` of one row of headings."""
    out = [yaw[0]]
    fix = 0.0
    for i in range(1, len(yaw)):
        d = yaw[i] - yaw[i - 1]
        dmod = (d + math.pi) % (2 * math.pi) - math.pi
        if dmod == -math.pi and d > 0:
            dmod = math.pi
        fix += 0.0 if abs(d) < math.pi else dmod - d
        out.append(yaw[i] + fix)
    return out


def interp_poses(q: list[float], xp: list[float], fps: list[list[float]]) -> list[list[float]]:
    """``occupancy._interp_rows`` of one row: each of ``fps`` at the stamps ``q``."""
    k = len(xp)
    out: list[list[float]] = [[] for _ in fps]
    for t in q:
        count = 0
        for x in xp:
            if x <= t:
                count += 1
        j = min(max(count - 1, 0), k - 2)
        x0 = xp[j]
        span = xp[j + 1] - x0
        w = min(max((t - x0) / (span if span > 0 else 1.0), 0.0), 1.0)
        for fp, row in zip(fps, out, strict=True):
            f0 = fp[j]
            row.append(f0 + w * (fp[j + 1] - f0))
    return out


def _apart(ex: float, ey: float, a: list[float], b: list[float]) -> bool:
    """Whether the projections ``ex * y - ey * x`` of flat ``a`` and ``b`` are apart.

    Never when one projection is NaN (numpy's min and max propagate it).
    """
    a_lo = a_hi = ex * a[1] - ey * a[0]
    for k in range(2, len(a), 2):
        p = ex * a[k + 1] - ey * a[k]
        if p < a_lo:
            a_lo = p
        elif p > a_hi:
            a_hi = p
        elif p != p:  # noqa: PLR0124 - NaN
            return False
    b_lo = b_hi = ex * b[1] - ey * b[0]
    for k in range(2, len(b), 2):
        p = ex * b[k + 1] - ey * b[k]
        if p < b_lo:
            b_lo = p
        elif p > b_hi:
            b_hi = p
        elif p != p:  # noqa: PLR0124 - NaN
            return False
    if a_lo != a_lo or b_lo != b_lo:  # noqa: PLR0124 - NaN first
        return False
    return a_hi < b_lo or b_hi < a_lo


def _touch(a: list[float], b: list[float]) -> bool:
    """Whether two convex polygons (flat ``x, y, ...``) intersect (touching included)."""
    for poly in (a, b):
        n = len(poly)
        for k in range(0, n, 2):
            j = (k + 2) % n
            if _apart(poly[j] - poly[k], poly[j + 1] - poly[k + 1], a, b):
                return False
    return True


def convex_touch_rows(a: list[list[float]], b: list[list[float]]) -> list[bool]:
    """``convex.convex_touch`` of pairs: ``a[i]``, ``b[i]`` are flat ``x0, y0, x1, ...``."""
    return [_touch(pa, pb) for pa, pb in zip(a, b, strict=True)]


def _profile(v0: float, a: float, t_b: float, t: float) -> tuple[float, float, float]:
    """``reach_simple._profiles`` at one stamp: centre shift, radius and side bulge."""
    t_eff = min(t, t_b)
    b = v0 * t_eff - a * a * (t_eff * t_eff * t_eff) / (2 * v0) if v0 > 0 else 0.0
    return v0 * t, 0.5 * a * (t * t), b


def simple_vertices_rows(
    poses: list[list[float]], times_s: list[float], a_max_mps2: float
) -> list[float]:
    """``reach_simple.simple_reach_vertices``, flat ``(N, T, 6, 2)``.

    Args:
        poses: Per object ``[x, y, yaw, speed, length, width]``.
        times_s: Grid stamps.
        a_max_mps2: Acceleration bound.

    Returns:
        The vertices, flat. The same operations in the same order except ``t ** 3``
        (``t * t * t`` here; numpy's power may differ in the last bit), so within 1e-9 m.
    """
    a = a_max_mps2
    out: list[float] = []
    for x, y, yaw, v0, length, width in poses:
        t_b = math.sqrt(2.0 / 3.0) * v0 / a
        co, si = math.cos(yaw), math.sin(yaw)
        hl, hw = length / 2, width / 2
        c_p, r_p, b_p = _profile(v0, a, t_b, 0.0)
        rear = c_p - r_p
        for t in times_s:
            c, r, b = _profile(v0, a, t_b, t)
            rear = max(rear, c_p - r_p)
            front = c + r
            for xi, eta in (
                (rear - hl, r_p + hw),
                (b_p - hl, r + hw),
                (front + hl, r + hw),
                (front + hl, -r - hw),
                (b_p - hl, -r - hw),
                (rear - hl, -r_p - hw),
            ):
                out.append(x + co * xi - si * eta)
                out.append(y + si * xi + co * eta)
            c_p, r_p, b_p = c, r, b
    return out
