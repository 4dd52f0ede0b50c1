"""Public-road rules of our own design on plain lane polygons and polylines.

Atoms per object (``F`` its current footprint, ``v`` its speed, ``a`` its acceleration bound):

    on_road      F shrunk by ``on_road_margin`` lies inside the union of all lanes
    in_lane      the centre lies in a lane whose direction agrees with the heading (cos > 0)
    on_yield     the centre lies in a yield lane of a right-of-way rule whose priority lanes the
                 ego occupies now or along its plan, and F does not touch those priority lanes
    can_stop     distance from F to the priority lanes >= v^2 / (2 brake_comfort)
    below_limit  v <= limit (1 + tolerance), limit of the lane the object drives in

Rules, formulas and patches:

==================  =========================================  ==============================
rule                holds when                                 patch (what the object avoids)
==================  =========================================  ==============================
road.stay_on_road   H on_road                                  everything off the lanes
                                                               (a box around the object
                                                               minus the lane union), all steps
road.no_opposite    in_lane                                    every lane of opposite direction
                                                               that is reached from the object's
                                                               centre only across a solid line
road.right_of_way   on_yield S (on_yield and can_stop)         the priority lanes
road.speed_limit    H below_limit                              step k: the half-plane ahead of
                                                               d(t_k) + L/2 along the heading,
                                                               d = distance with accel ``a``
                                                               up to the capped speed
==================  =========================================  ==============================

With ``RoadRuleParams.lane_rules`` the lane rules of ``rules_lane`` and the standstill rule of
``rules_standstill`` run as well.
"""

from __future__ import annotations

from typing import TYPE_CHECKING, Any

import numpy as np
import shapely

from reachsets.footprints import body_to_map
from reachsets.ltl import And, Atom, Historically, LtlMemory, Since, step
from reachsets.patches import RuleContext, RulePatch
from reachsets.road import RoadGeometry, prepare_road
from reachsets.rules_lane import evaluate_lanes
from reachsets.rules_standstill import evaluate_standstill

if TYPE_CHECKING:
    from collections.abc import Mapping

    from numpy.typing import NDArray


__all__ = [
    "RIGHT_OF_WAY",
    "STAY_ON_ROAD",
    "WITHIN_LIMIT",
    "evaluate_road",
    "max_travel_m",
]

STAY_ON_ROAD = Historically(Atom("on_road"))
RIGHT_OF_WAY = Since(Atom("on_yield"), And((Atom("on_yield"), Atom("can_stop"))))
WITHIN_LIMIT = Historically(Atom("below_limit"))

_FAR_M = 1000.0


def max_travel_m(
    v0_mps: NDArray[np.float64],
    v_cap_mps: NDArray[np.float64],
    a_mps2: float,
    t_s: NDArray[np.float64],
) -> NDArray[np.float64]:
    """Farthest path length by ``t`` accelerating at ``a`` up to ``max(v0, v_cap)``, ``(N, T)``."""
    cap = np.maximum(v0_mps, v_cap_mps)[:, None]
    v0 = v0_mps[:, None]
    t_cap = (cap - v0) / a_mps2
    t = t_s[None, :]
    accel = v0 * t + 0.5 * a_mps2 * t**2
    capped = v0 * t_cap + 0.5 * a_mps2 * t_cap**2 + cap * (t - t_cap)
    return np.asarray(np.where(t <= t_cap, accel, capped), dtype=np.float64)


def _lane_directions(
    centre: NDArray[np.float64], x: NDArray[np.float64], y: NDArray[np.float64]
) -> NDArray[np.float64]:
    """Unit driving direction of a lane centre line at its point nearest to each position.

    Args:
        centre: Lane centre line, ``(C, 2)``, ``C >= 2``.
        x: Positions x, ``(N,)``.
        y: Positions y, ``(N,)``.

    Returns:
        ``(N, 2)`` directions (of the segment starting at the nearest point; the last
        segment for the last point).
    """
    d2 = (centre[None, :, 0] - x[:, None]) ** 2 + (centre[None, :, 1] - y[:, None]) ** 2
    k = np.minimum(np.maximum(np.argmin(d2, axis=1), 0), len(centre) - 2)
    t = centre[k + 1] - centre[k]
    return np.asarray(t / np.maximum(np.hypot(t[:, 0], t[:, 1]), 1e-12)[:, None])


def evaluate_road(
    ctx: RuleContext, memory: Mapping[str, Mapping[str, bool]]
) -> tuple[list[RulePatch], LtlMemory]:
    """Evaluate the four road rules for every object and build their patches."""
    road = ctx.road
    n = len(ctx.objects)
    if road is None or n == 0 or not road.lanes:
        return [], {}
    geo = ctx.road_geometry if ctx.road_geometry is not None else prepare_road(road)
    lanes, lane_polys = geo.lanes, geo.lane_polys
    lanes_by_id, drivable = geo.lanes_by_id, geo.drivable
    if not lanes:
        return [], {}
    p = ctx.params.road
    objs = ctx.objects
    ids = [str(i) for i in objs.ids]
    centres = shapely.points(objs.x_m, objs.y_m)
    contains = np.asarray(shapely.contains(lane_polys[None, :], centres[:, None]))  # (N, Lanes)
    heading = np.stack([np.cos(objs.yaw_rad), np.sin(objs.yaw_rad)], axis=1)
    cos_dir = np.stack(
        [
            np.sum(heading * _lane_directions(ln.centre_m, objs.x_m, objs.y_m), axis=1)
            for ln in lanes
        ],
        axis=1,
    ).reshape(n, len(lanes))
    aligned = contains & (cos_dir > 0)
    shrunk = shapely.buffer(ctx.footprints, -p.on_road_margin_m)
    atoms: dict[str, NDArray[np.bool_]] = {
        "on_road": np.asarray(shapely.covered_by(shrunk, drivable), dtype=bool),
        "in_lane": np.asarray(aligned.any(axis=1), dtype=bool),
    }
    limits = np.array([ln.speed_limit_mps for ln in lanes])
    lane_limit = np.where(aligned, limits[None, :], np.nan)
    limit = np.array([np.nanmin(r) if np.isfinite(r).any() else np.nan for r in lane_limit])
    atoms["below_limit"] = np.isfinite(limit) & (
        objs.speed_mps <= np.nan_to_num(limit) * (1 + p.speed_tolerance)
    )
    prio_geom, on_yield, can_stop = _right_of_way(ctx, lane_polys, lanes_by_id, contains)
    atoms["on_yield"] = on_yield
    atoms["can_stop"] = can_stop
    mem: LtlMemory = {}
    results = {}
    for name, formula in (
        ("road.stay_on_road", STAY_ON_ROAD),
        ("road.right_of_way", RIGHT_OF_WAY),
        ("road.speed_limit", WITHIN_LIMIT),
    ):
        results[name], m = step(formula, atoms, ids, memory, prefix=name)
        mem.update(m)
    patches: list[RulePatch] = []
    reach_radius = (
        max_travel_m(objs.speed_mps, objs.speed_mps, ctx.params.a_max_mps2, ctx.times_s[-1:])[:, 0]
        + objs.length_m
        + 10.0
    )
    for i in np.flatnonzero(results["road.stay_on_road"]):
        box = shapely.buffer(centres[i], reach_radius[i], quad_segs=2)
        patches.append(RulePatch(int(i), "road.stay_on_road", shapely.difference(box, drivable)))
    for i in np.flatnonzero(atoms["in_lane"]):
        geom = _opposite_across_solid(ctx, int(i), geo, cos_dir[i], contains[i])
        if geom is not None:
            patches.append(RulePatch(int(i), "road.no_opposite", geom))
    patches.extend(
        RulePatch(int(i), "road.right_of_way", prio_geom[i])
        for i in np.flatnonzero(results["road.right_of_way"])
    )
    patches.extend(_speed_patches(ctx, np.flatnonzero(results["road.speed_limit"]), limit))
    if p.lane_rules:
        lane_patches, lane_mem = evaluate_lanes(ctx, memory, geo, aligned)
        patches += lane_patches + evaluate_standstill(ctx)
        mem.update(lane_mem)
    return patches, mem


def _right_of_way(
    ctx: RuleContext,
    lane_polys: NDArray[np.object_],
    lanes_by_id: dict[str, int],
    contains: NDArray[np.bool_],
) -> tuple[list[Any], NDArray[np.bool_], NDArray[np.bool_]]:
    """Priority area per object, ``on_yield`` and ``can_stop`` atoms."""
    road = ctx.road
    assert road is not None
    n = len(ctx.objects)
    prio: list[Any] = [None] * n
    on_yield = np.zeros(n, dtype=bool)
    can_stop = np.zeros(n, dtype=bool)
    ego_path = shapely.union_all(ctx.occupancy.polygons)
    for rule in road.right_of_way:
        p_idx = [lanes_by_id[i] for i in rule.priority_lanes if i in lanes_by_id]
        y_idx = [lanes_by_id[i] for i in rule.yield_lanes if i in lanes_by_id]
        if not p_idx or not y_idx:
            continue
        area = shapely.union_all(lane_polys[p_idx])
        if not shapely.intersects(ego_path, area):
            continue
        yielding = contains[:, y_idx].any(axis=1) & ~shapely.intersects(ctx.footprints, area)
        dist = shapely.distance(ctx.footprints, area)
        stop = ctx.objects.speed_mps**2 / (2 * ctx.params.road.brake_comfort_mps2)
        for i in np.flatnonzero(yielding):
            on_yield[i] = True
            can_stop[i] |= bool(dist[i] >= stop[i])
            prio[i] = area if prio[i] is None else shapely.union(prio[i], area)
    return prio, on_yield, can_stop


def _opposite_across_solid(
    ctx: RuleContext,
    i: int,
    geo: RoadGeometry,
    cos_dir: NDArray[np.float64],
    inside: NDArray[np.bool_],
) -> Any:
    """Union of opposite lanes object ``i`` reaches only across a solid line, or ``None``."""
    solid, lane_polys = geo.solid, geo.lane_polys
    if solid is None:
        return None
    centre = shapely.points(ctx.objects.x_m[i], ctx.objects.y_m[i])
    chosen = []
    for k in np.flatnonzero((cos_dir < 0) & ~inside):
        if shapely.intersects(ctx.footprints[i], lane_polys[k]):
            continue
        if shapely.intersects(shapely.shortest_line(centre, lane_polys[k]), solid):
            chosen.append(lane_polys[k])
    return shapely.union_all(chosen) if chosen else None


def _speed_patches(
    ctx: RuleContext, rows: NDArray[np.intp], limit: NDArray[np.float64]
) -> list[RulePatch]:
    """Per-step half-planes beyond the farthest travel under the speed cap."""
    if len(rows) == 0:
        return []
    objs = ctx.objects
    cap = limit[rows] * (1 + ctx.params.road.speed_tolerance)
    travel = max_travel_m(objs.speed_mps[rows], cap, ctx.params.a_max_mps2, ctx.times_s)
    patches = []
    for r, i in enumerate(rows):
        near = travel[r] + objs.length_m[i] / 2
        xi = np.stack([near, near + _FAR_M, near + _FAR_M, near], axis=-1)
        eta = np.broadcast_to(np.array([_FAR_M, _FAR_M, -_FAR_M, -_FAR_M]), xi.shape)
        coords = body_to_map(xi, eta, objs.x_m[i], objs.y_m[i], objs.yaw_rad[i])
        for k, poly in enumerate(shapely.polygons(coords)):
            patches.append(RulePatch(int(i), "road.speed_limit", poly, step=k))
    return patches
