"""Seeded random drives on a lane map, for the drive-level cross-check against ad-rss.

A drive is ``FRAMES`` frames at 10 Hz: the ego follows a random lane route (successor
links, through junctions), among 1-6 vehicles that each follow a random route of their own
starting on a lane near the ego's path (ahead, behind, oncoming, crossing at a junction)
or stand still. Vehicles drive on their lanes' centre lines, heading along them, at a
speed that is constant or changes once (braking to a stop, speeding up). Everything comes
from one ``numpy`` generator seeded per drive, so a drive is reproducible from
``(seed, index)``.

With ``junction_routes`` (a separate family of drives; the default drives stay as they
were) the ego starts 5-50 m before its lane's end, so its route runs through a junction
lane early, and each vehicle is, with even odds, on the ego's own lane route (ahead by
8-70 m or behind by 8-40 m along it, the route continued at random where the ego's ends)
instead of on a lane nearby: the "vehicle ahead in the ego's own lane, its route through
a junction lane" of the Town01 regression drives (``../shared/conformance/
town01_regressions``). Such drives also carry ``"speed_limit_mode":
"IncreasedSpeedLimit10"`` (ad-rss' ``RssRestrictSpeedLimitMode``; the oracle passes it
to ``appendConstellations``), the mode those drives were reported in.

The drive is plain JSON (the oracle script reads it as it is)::

    {"frames": [{"ego": {"x", "y", "yaw", "v", "length", "width"},
                 "objects": [{"id", "x", "y", "yaw", "v", "length", "width"}, ...]}, ...]}

(ENU metres, radians, m/s; object ids are small positive integers).
"""

from __future__ import annotations

from typing import TYPE_CHECKING, Any

import numpy as np
import shapely

if TYPE_CHECKING:
    from rss.scene import PreparedGraph

__all__ = ["FRAMES", "JUNCTION_SPEED_LIMIT_MODE", "STEP_S", "drive", "drives"]

#: Frames per drive and their spacing (s): 5 s at 10 Hz.
FRAMES = 50
STEP_S = 0.1
#: Objects start on lanes whose centre line passes within this distance (m) of the ego's
#: path over the drive.
_NEAR_M = 40.0
#: No object starts with its centre closer than this (m) to the ego's or another's centre.
_MIN_GAP_M = 6.0
#: ``junction_routes`` drives: the ad-rss speed-limit mode they are checked in.
JUNCTION_SPEED_LIMIT_MODE = "IncreasedSpeedLimit10"


class _Path:
    """A lane route's centre line as one polyline, with arc-length lookup."""

    def __init__(self, prep: PreparedGraph, lanes: list[int]) -> None:
        pts = [prep.graph.centre_m[lanes[0]]]
        pts += [prep.graph.centre_m[lane][1:] for lane in lanes[1:]]
        line = np.concatenate(pts)
        keep = np.concatenate([[True], np.hypot(*np.diff(line, axis=0).T) > 1e-6])
        self.xy = line[keep]
        self.arc = np.concatenate([[0.0], np.cumsum(np.hypot(*np.diff(self.xy, axis=0).T))])

    @property
    def length_m(self) -> float:
        return float(self.arc[-1])

    def pose(self, s: float) -> tuple[float, float, float]:
        """``(x, y, yaw)`` at arc length ``s`` (m), heading along the segment there."""
        k = int(np.clip(np.searchsorted(self.arc, s, side="right") - 1, 0, len(self.xy) - 2))
        d = self.xy[k + 1] - self.xy[k]
        f = (s - self.arc[k]) / max(self.arc[k + 1] - self.arc[k], 1e-12)
        p = self.xy[k] + f * d
        return float(p[0]), float(p[1]), float(np.arctan2(d[1], d[0]))


def _route(prep: PreparedGraph, rng: np.random.Generator, lane: int, need_m: float) -> list[int]:
    """Lanes from ``lane`` along random successors until they hold ``need_m`` metres."""
    lanes = [lane]
    total = float(prep.centre_length_m[lane])
    while total < need_m and prep.graph.successors[lanes[-1]]:
        nxt = prep.graph.successors[lanes[-1]]
        lanes.append(int(nxt[rng.integers(len(nxt))]))
        total += float(prep.centre_length_m[lanes[-1]])
    return lanes


def _speeds(rng: np.random.Generator, *, standing: bool) -> np.ndarray:
    """``(FRAMES,)`` speed profile (m/s): standing, constant, or one change of speed."""
    if standing:
        return np.zeros(FRAMES)
    v0 = float(rng.uniform(1.0, 14.0))
    t = np.arange(FRAMES) * STEP_S
    kind = rng.integers(3)
    if kind == 0:
        return np.full(FRAMES, v0)
    start = float(rng.uniform(0.0, 3.0))
    accel = float(rng.uniform(-5.0, -1.0) if kind == 1 else rng.uniform(0.5, 2.5))
    return np.asarray(np.clip(v0 + accel * np.clip(t - start, 0.0, None), 0.0, 16.0), dtype=float)


def _track(
    prep: PreparedGraph,
    rng: np.random.Generator,
    lane: int,
    s0: float,
    v: np.ndarray,
    *,
    lanes: list[int] | None = None,
) -> tuple[list[tuple[float, float, float]], list[int]]:
    """Poses of a vehicle starting ``s0`` m along ``lane`` with the speed profile ``v``,
    and its lane route (``lanes``, if given, is its start, continued at random)."""
    travel = np.concatenate([[0.0], np.cumsum(v[:-1] * STEP_S)])
    need_m = s0 + float(travel[-1]) + 1.0
    route = _route(prep, rng, lane, need_m) if lanes is None else _extend(prep, rng, lanes, need_m)
    path = _Path(prep, route)
    return [path.pose(min(s0 + d, path.length_m)) for d in travel], route


def _extend(
    prep: PreparedGraph, rng: np.random.Generator, lanes: list[int], need_m: float
) -> list[int]:
    """``lanes`` continued along random successors until they hold ``need_m`` metres."""
    have = float(sum(prep.centre_length_m[lane] for lane in lanes[:-1]))
    return lanes[:-1] + _route(prep, rng, lanes[-1], need_m - have)


def _on_ego_route(
    prep: PreparedGraph,
    rng: np.random.Generator,
    ego_lanes: list[int],
    ego_s0: float,
    v: np.ndarray,
) -> list[tuple[float, float, float]] | None:
    """A vehicle on the ego's lane route, 8-70 m ahead or 8-40 m behind along it (None
    where the route does not reach back that far)."""
    offset = float(rng.uniform(8.0, 70.0) if rng.random() < 0.7 else -rng.uniform(8.0, 40.0))
    s0 = ego_s0 + offset
    if s0 < 0.0:
        return None
    return _track(prep, rng, ego_lanes[0], s0, v, lanes=ego_lanes)[0]


def drive(
    prep: PreparedGraph,
    rng: np.random.Generator,
    min_gap_m: float = _MIN_GAP_M,
    *,
    junction_routes: bool = False,
) -> dict[str, Any]:
    """One random drive (module docstring); objects start ``min_gap_m`` apart or more
    (centres; 0 lets boxes start touching or overlapping)."""
    g = prep.graph
    roads = np.flatnonzero(~g.is_intersection)
    lane = int(rng.choice(roads))
    ego_v = _speeds(rng, standing=rng.random() < 0.1)
    length_m = float(prep.centre_length_m[lane])
    ego_s0 = (
        max(0.0, length_m - float(rng.uniform(5.0, 50.0)))
        if junction_routes
        else float(rng.uniform(0, length_m))
    )
    ego, ego_lanes = _track(prep, rng, lane, ego_s0, ego_v)
    ego_path = shapely.LineString([(x, y) for x, y, _ in ego] + [ego[-1][:2]])
    near = np.flatnonzero(shapely.distance(prep.centre_lines, ego_path) < _NEAR_M)
    dims = {"length": 4.5, "width": 2.0}
    tracks: list[tuple[list[tuple[float, float, float]], np.ndarray, float, float]] = []
    n_objects = int(rng.integers(1, 7))
    for _ in range(50 * n_objects):
        if len(tracks) == n_objects:
            break
        if junction_routes and rng.random() < 0.5:
            v = _speeds(rng, standing=rng.random() < 0.25)
            on_route = _on_ego_route(prep, rng, ego_lanes, ego_s0, v)
            if on_route is None:
                continue
            track = on_route
        else:
            other = int(rng.choice(near))
            s0 = float(rng.uniform(0, prep.centre_length_m[other]))
            v = _speeds(rng, standing=rng.random() < 0.25)
            track = _track(prep, rng, other, s0, v)[0]
        x, y, _ = track[0]
        starts = [ego[0]] + [t[0][0] for t in tracks]
        if min(np.hypot(x - p[0], y - p[1]) for p in starts) < min_gap_m:
            continue
        if np.hypot(x - ego[0][0], y - ego[0][1]) > 2 * _NEAR_M:
            continue
        tracks.append((track, v, float(rng.uniform(3.8, 5.5)), float(rng.uniform(1.7, 2.1))))
    frames = []
    for k in range(FRAMES):
        x, y, yaw = ego[k]
        objects = [
            {
                "id": i + 1,
                "x": t[k][0],
                "y": t[k][1],
                "yaw": t[k][2],
                "v": float(v[k]),
                "length": length,
                "width": width,
            }
            for i, (t, v, length, width) in enumerate(tracks)
        ]
        ego_k = {"x": x, "y": y, "yaw": yaw, "v": float(ego_v[k]), **dims}
        frames.append({"ego": ego_k, "objects": objects})
    if junction_routes:
        return {"speed_limit_mode": JUNCTION_SPEED_LIMIT_MODE, "frames": frames}
    return {"frames": frames}


def drives(
    prep: PreparedGraph,
    seed: int,
    n: int,
    min_gap_m: float = _MIN_GAP_M,
    *,
    junction_routes: bool = False,
) -> list[dict[str, Any]]:
    """``n`` drives, drive ``i`` from the generator seeded with ``(seed, i)`` (the
    ``junction_routes`` family seeded with ``(seed, i, 1)``)."""
    extra = [1] if junction_routes else []
    return [
        drive(
            prep,
            np.random.default_rng([seed, i, *extra]),
            min_gap_m,
            junction_routes=junction_routes,
        )
        for i in range(n)
    ]
