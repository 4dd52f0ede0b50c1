"""Scalar twins of the ego occupancy's interpolation for one frame (compiled with mypyc).

Called one frame at a time, ``occupancy.ego_occupancy_many`` spends most of its time in numpy
call overhead on arrays of a few dozen values. These twins do the same float operations in
the same order on Python floats (compiled with the other scalar twins, see
``rss.compiled``), so they give bit-identical poses; ``hypot`` stays with numpy in the
caller (``math.hypot`` may differ in the last bit).
"""

from __future__ import annotations

import math

__all__ = ["interp_poses", "unwrapped", "waypoint_times"]


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
