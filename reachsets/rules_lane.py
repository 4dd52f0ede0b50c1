"""Lane rules for public roads: keep the lane unless observably changing, no cut-in at the ego.

Atoms per object (``F`` its current footprint; ``lane``: every lane of agreeing direction
(``cos > 0``) containing its centre; offset, tangent and half width ``w`` from the lane whose
centre line is nearest; ``v_lat`` = speed x sin(heading - lane direction), left positive):

    in_lane        it has a lane
    settled        it has a lane and F sticks out of it by at most ``lane_margin_m`` on either side
    crossing       it has a lane and F sticks out of it by more than ``lane_margin_m``
    crossing_ego   crossing on the side of the ego (the side of the line through the object's
                   centre along the lane's tangent there on which the ego's centre lies)
    leaving_left   crossing its left boundary, or ``v_lat >= lane_change_v_lat_mps``, or its
                   centre lies ``>= lane_change_offset_m`` left of the lane's centre line
    leaving_right  the same to the right

Rules, formulas (past-time LTL, ``S`` = since) and patches:

====================  ================================================  =========================
rule                  holds when                                        patch
====================  ================================================  =========================
road.keep_lane        ``KEEP_s = (not leaving_s) S (settled and not     everything outside the
                      leaving_s)`` for a side ``s``: since it was last   corridor of its lane(s)
                      settled in its lane, it has shown no sign of       with the sides whose
                      leaving it to that side                            ``KEEP_s`` is false open,
                                                                         minus the ego's lanes
                                                                         (all steps)
road.no_cut_in        ``(not crossing_ego) S (in_lane and not            the ego's lanes, grown by
                      crossing_ego)``, for an object whose centre is     ``lane_margin_m``, within
                      outside the ego's lane corridor and whose          ``max(cut_in_gap_s v_ego,
                      corridor does not cross or merge into it: since    cut_in_gap_min_m)``
                      it was last in a lane without crossing towards     before and behind its
                      the ego, it has not started to leave it towards    footprints along the
                      the ego                                            plan (all steps)
====================  ================================================  =========================

The ego's lanes are those containing the centre of its occupancy at any grid stamp, heading
agreeing; their corridor is built like an object's (both sides closed). The cut-in patch grows
it by ``lane_margin_m``: an ego sticking out of its lanes by at most the margin is in them, as
an object is ``settled`` (docs/reachsets.md, "The ego's lane margin").
"""

from __future__ import annotations

from typing import TYPE_CHECKING, Any

import numpy as np
import shapely

from reachsets.footprints import body_to_map
from reachsets.lanes import complement, corridor, half_widths, project, project_many
from reachsets.ltl import And, Atom, Not, Since, step
from reachsets.patches import RulePatch

if TYPE_CHECKING:
    from collections.abc import Mapping

    from numpy.typing import NDArray

    from reachsets.ltl import LtlMemory
    from reachsets.patches import RuleContext
    from reachsets.road import RoadGeometry

__all__ = ["KEEP_LEFT", "KEEP_RIGHT", "NO_CUT_IN", "evaluate_lanes", "lane_atoms"]


def _keep(side: str) -> Since:
    leaving = Not(Atom(f"leaving_{side}"))
    return Since(leaving, And((Atom("settled"), leaving)))


KEEP_LEFT = _keep("left")
KEEP_RIGHT = _keep("right")
NO_CUT_IN = Since(Not(Atom("crossing_ego")), And((Atom("in_lane"), Not(Atom("crossing_ego")))))

_FAR_M = 100.0
#: Corridors sharing more area than this cross or merge [m^2].
_OVERLAP_M2 = 1.0


def _nearest_lane(
    geo: RoadGeometry, cand: NDArray[np.intp], x: float, y: float
) -> tuple[int, float, NDArray[np.float64]]:
    """The candidate lane whose centre line is nearest, the offset and the tangent there."""
    best = (int(cand[0]), np.inf, np.array([1.0, 0.0]))
    for k in cand:
        off, t = project(geo.lanes[int(k)].centre_m, x, y)
        if abs(off) < abs(best[1]):
            best = (int(k), off, t)
    return best


def lane_atoms(
    ctx: RuleContext, geo: RoadGeometry, aligned: NDArray[np.bool_]
) -> tuple[dict[str, NDArray[np.bool_]], list[frozenset[int]]]:
    """The lane atoms of every object and its lanes (indices into ``geo.lanes``).

    Args:
        ctx: The frame.
        geo: Road geometry.
        aligned: ``(N, Lanes)``: the lane contains the object's centre and runs its way.

    Returns:
        Atom name -> ``(N,)`` bools, and each object's lanes (empty: no lane).
    """
    objs, p = ctx.objects, ctx.params.road
    n = len(objs)
    hw = half_widths(geo)
    names = ("in_lane", "settled", "crossing", "crossing_ego", "leaving_left", "leaving_right")
    atoms = {name: np.zeros(n, dtype=bool) for name in names}
    own: list[frozenset[int]] = []
    for i in range(n):
        cand = np.flatnonzero(aligned[i])
        own.append(frozenset(int(k) for k in cand))
        if not len(cand):
            continue
        x, y, yaw = float(objs.x_m[i]), float(objs.y_m[i]), float(objs.yaw_rad[i])
        k, off, t = _nearest_lane(geo, cand, x, y)
        sin_d = t[0] * np.sin(yaw) - t[1] * np.cos(yaw)
        cos_d = t[0] * np.cos(yaw) + t[1] * np.sin(yaw)
        extent = abs(objs.length_m[i] / 2 * sin_d) + abs(objs.width_m[i] / 2 * cos_d)
        out_left = off + extent > hw[k] + p.lane_margin_m
        out_right = off - extent < -(hw[k] + p.lane_margin_m)
        v_lat = float(objs.speed_mps[i]) * sin_d if np.isfinite(objs.speed_mps[i]) else 0.0
        atoms["crossing"][i] = out_left or out_right
        ego_left = t[0] * (ctx.ego_y_m - y) - t[1] * (ctx.ego_x_m - x) > 0
        atoms["crossing_ego"][i] = out_left if ego_left else out_right
        atoms["in_lane"][i] = True
        atoms["settled"][i] = not (out_left or out_right)
        atoms["leaving_left"][i] = bool(
            out_left or v_lat >= p.lane_change_v_lat_mps or off >= p.lane_change_offset_m
        )
        atoms["leaving_right"][i] = bool(
            out_right or -v_lat >= p.lane_change_v_lat_mps or -off >= p.lane_change_offset_m
        )
    return atoms, own


def _ego_lanes(ctx: RuleContext, geo: RoadGeometry) -> frozenset[int]:
    """Lanes containing the ego's occupancy centre at some stamp, heading agreeing."""
    occ = ctx.occupancy
    x, y, yaw = np.ravel(occ.x_m), np.ravel(occ.y_m), np.ravel(occ.yaw_rad)
    inside = np.asarray(shapely.contains(geo.lane_polys[None, :], shapely.points(x, y)[:, None]))
    found: set[int] = set()
    for k in np.flatnonzero(inside.any(axis=0)):
        s = np.flatnonzero(inside[:, k])
        _, t = project_many(geo.lanes[int(k)].centre_m, x[s], y[s])
        if np.any(t[:, 0] * np.cos(yaw[s]) + t[:, 1] * np.sin(yaw[s]) > 0):
            found.add(int(k))
    return frozenset(found)


def _grown(geo: RoadGeometry, ego_key: frozenset[int], ego_corr: Any, margin_m: float) -> Any:
    """The ego's corridor grown by ``margin_m`` on every side (cached per lane set and margin)."""
    cache = geo.cache.setdefault("grown_corridor", {})
    key = (ego_key, margin_m)
    if key not in cache:
        grown = shapely.buffer(ego_corr, margin_m, quad_segs=2) if margin_m > 0 else ego_corr
        shapely.prepare(grown)
        cache[key] = grown
    return cache[key]


def _band(ctx: RuleContext, ego_corridor: Any) -> Any:
    """The ego's lanes around its path, within the cut-in gap of its footprints.

    From the gap behind its footprint at ``t = 0`` to the gap ahead of it at the horizon: the
    convex hull of the per-step bands, within ``ego_corridor`` (the ego's corridor grown by
    the lane margin).
    """
    occ, p = ctx.occupancy, ctx.params.road
    gap = max(p.cut_in_gap_s * ctx.ego_speed_mps, p.cut_in_gap_min_m)
    if not np.isfinite(gap):
        gap = p.cut_in_gap_min_m
    half = ctx.ego_length_m / 2 + gap
    xi = np.array([-half, half, half, -half])
    eta = np.array([_FAR_M, _FAR_M, -_FAR_M, -_FAR_M])
    x, y, yaw = np.ravel(occ.x_m), np.ravel(occ.y_m), np.ravel(occ.yaw_rad)
    coords = body_to_map(
        np.broadcast_to(xi, (len(x), 4)),
        np.broadcast_to(eta, (len(x), 4)),
        x[:, None],
        y[:, None],
        yaw[:, None],
    )
    hull = shapely.convex_hull(shapely.multipoints(coords.reshape(-1, 2)))
    near = shapely.clip_by_rect(ego_corridor, *shapely.bounds(hull))
    return shapely.intersection(hull, near)


def _crosses(
    geo: RoadGeometry, lanes: frozenset[int], ego_key: frozenset[int], ego_corr: Any, length: float
) -> bool:
    """Whether the corridor of ``lanes`` overlaps the ego's (crossing or merging lanes), cached."""
    cache = geo.cache.setdefault("crosses", {})
    key = (lanes, ego_key)
    if key not in cache:
        own = corridor(geo, lanes, open_left=False, open_right=False, length_m=length)
        cache[key] = bool(shapely.area(shapely.intersection(own, ego_corr)) > _OVERLAP_M2)
    return bool(cache[key])


def evaluate_lanes(
    ctx: RuleContext,
    memory: Mapping[str, Mapping[str, bool]],
    geo: RoadGeometry,
    aligned: NDArray[np.bool_],
) -> tuple[list[RulePatch], LtlMemory]:
    """Evaluate ``road.keep_lane`` and ``road.no_cut_in`` and build their patches."""
    objs, p = ctx.objects, ctx.params.road
    ids = [str(i) for i in objs.ids]
    atoms, own = lane_atoms(ctx, geo, aligned)
    mem: LtlMemory = {}
    holds = {}
    for name, formula in (
        ("road.keep_lane.left", KEEP_LEFT),
        ("road.keep_lane.right", KEEP_RIGHT),
        ("road.no_cut_in", NO_CUT_IN),
    ):
        holds[name], m = step(formula, atoms, ids, memory, prefix=name)
        mem.update(m)
    ego_key = _ego_lanes(ctx, geo)
    length = p.corridor_length_m
    ego_corr = (
        corridor(geo, ego_key, open_left=False, open_right=False, length_m=length)
        if ego_key
        else None
    )
    patches: list[RulePatch] = []
    left, right = holds["road.keep_lane.left"], holds["road.keep_lane.right"]
    for i in np.flatnonzero(left | right):
        lanes = own[i]
        if not lanes:
            continue
        key = (lanes, not left[i], not right[i], ego_key)

        def keep(key: tuple[Any, ...] = key) -> Any:
            corr = corridor(geo, key[0], open_left=key[1], open_right=key[2], length_m=length)
            return corr if ego_corr is None else shapely.union(corr, ego_corr)

        patches.append(RulePatch(int(i), "road.keep_lane", complement(geo, keep, key)))
    if ego_corr is None:
        return patches, mem
    outside = ~np.asarray(
        shapely.contains(ego_corr, shapely.points(objs.x_m, objs.y_m)), dtype=bool
    )
    rows = [
        i
        for i in np.flatnonzero(holds["road.no_cut_in"] & outside)
        if own[i] and not _crosses(geo, own[i], ego_key, ego_corr, length)
    ]
    if rows:
        band = _band(ctx, _grown(geo, ego_key, ego_corr, p.lane_margin_m))
        patches += [RulePatch(int(i), "road.no_cut_in", band) for i in rows]
    return patches, mem
