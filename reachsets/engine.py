"""The reach-set supervisor engine: ``evaluate(inputs, params, state) -> (result, state)``.

Per frame:

1. ego footprints along the plan at ``t = 0, dt, ..., t_max``;
2. objects to check: on a track, those whose arc length lies in ``[s_ego_start,
   s_ego_end + L_ego]`` of the plan (followers are responsible for the gap); without a track,
   every object not entirely behind the ego;
3. reachable sets by method, trimmed to the drivable area;
4. rules (Roborace if zones are given, else F1 on a track; road rules on a road layout)
   evaluated at the current instant with past-time LTL memory carried in ``RuleState``;
   their patches are subtracted from every step (or the step they name);
5. the first step at which each object's reduced set touches the ego footprint.
"""

from __future__ import annotations

import logging
import math
from dataclasses import dataclass, field
from functools import cached_property
from typing import TYPE_CHECKING, Any

import numpy as np
import shapely

from reachsets.occupancy import EgoOccupancy, ego_occupancy
from reachsets.patches import (
    RuleContext,
    RulePatch,
    keep_largest_part,
    patch_grid,
    subtract_patches,
)
from reachsets.reachable import deletion_polygons, reachable_sets, simple_vertices
from reachsets.rules_f1 import evaluate_f1
from reachsets.rules_road import evaluate_road
from reachsets.rules_roborace import evaluate_roborace
from reachsets.track import TrackGeometry, build_track
from reachsets.verdict import first_hits

if TYPE_CHECKING:
    from collections.abc import Mapping

    from numpy.typing import NDArray

    from reachsets.inputs import ObjectStates, ReachInputs, TrackBounds
    from reachsets.ltl import LtlMemory
    from reachsets.params import ReachParams

__all__ = ["AppliedPatch", "Collision", "ReachResult", "RuleState", "evaluate"]

_log = logging.getLogger(__name__)


@dataclass(frozen=True, slots=True)
class Collision:
    """First overlap of an object's reduced reachable set with the ego footprint.

    Attributes:
        object_id: Object id.
        t_offset_s: Time of the grid step from now.
        step: Grid step index.
    """

    object_id: str
    t_offset_s: float
    step: int


@dataclass(frozen=True, slots=True)
class AppliedPatch:
    """A rule patch that was subtracted (``step`` None = every step).

    Attributes:
        object_id: The object whose reachable set was reduced.
        rule: Rule name (e.g. ``f1.alongside``).
        step: Grid step the patch applies to; ``None`` means every step.
        geometry: The deleted region (map frame, shapely geometry), for display.
    """

    object_id: str
    rule: str
    step: int | None
    geometry: Any = None


@dataclass(frozen=True, slots=True)
class RuleState:
    """Explicit memory between frames.

    Attributes:
        ltl: Past-time LTL memory (node key -> object id -> bit).
        track_bounds: The bounds ``track`` was derived from (reused while unchanged).
        track: Derived track geometry.
    """

    ltl: Mapping[str, Mapping[str, bool]] = field(default_factory=dict)
    track_bounds: TrackBounds | None = None
    track: TrackGeometry | None = None


@dataclass(frozen=True)
class ReachResult:
    """Verdict of one frame.

    Attributes:
        is_safe: No reduced reachable set touches the ego footprint.
        collisions: First collision per colliding object, in object order.
        patches: Rule patches subtracted.
        object_ids: Objects evaluated, ``(M,)``.
        skipped_ids: Objects not evaluated (behind the ego or invalid).
        occupancy: Ego footprints.
        sets: The reduced sets as ``(M, T)`` geometries (full geometry), or the unreduced
            ``simple`` sets as ``(M, T, 6, 2)`` vertices (verdict only); see ``reach_sets``.
    """

    is_safe: bool
    collisions: tuple[Collision, ...]
    patches: tuple[AppliedPatch, ...]
    object_ids: NDArray[np.str_]
    skipped_ids: tuple[str, ...]
    occupancy: EgoOccupancy
    sets: NDArray[Any]

    @cached_property
    def reach_sets(self) -> NDArray[np.object_]:
        """Reachable sets, ``(M, T)`` geometries, built on first use.

        Full geometry: the reduced sets, ``None`` where nothing is left (e.g. the reference's
        ``turn`` deletion removes a standing object's set). Verdict only: the unreduced
        ``simple`` sets (the reductions were only applied near the ego footprint).
        """
        if self.sets.dtype == object:
            return self.sets
        if not self.sets.size:
            return np.empty(self.sets.shape[:2], dtype=object)
        return np.asarray(shapely.polygons(self.sets))


def _prepared_track(
    inputs: ReachInputs, params: ReachParams, state: RuleState
) -> TrackGeometry | None:
    bounds = inputs.track
    if bounds is None:
        return None
    old = state.track_bounds
    if (
        state.track is not None
        and old is not None
        and (
            old is bounds
            or (
                np.array_equal(old.left_m, bounds.left_m)
                and np.array_equal(old.right_m, bounds.right_m)
            )
        )
    ):
        return state.track
    return build_track(bounds, params.closed_track_gap_m)


def _select(
    inputs: ReachInputs, track: TrackGeometry | None
) -> tuple[NDArray[np.bool_], NDArray[np.float64], float, NDArray[np.float64]]:
    """Mask of objects to evaluate, their arc lengths, the ego's, and their lateral offsets."""
    objs, ego = inputs.objects, inputs.ego
    n = len(objs)
    valid = (
        np.isfinite(objs.x_m + objs.y_m + objs.yaw_rad + objs.length_m + objs.width_m)
        & (objs.length_m > 0)
        & (objs.width_m > 0)
    )
    if track is None:
        c, s = math.cos(ego.yaw_rad[0]), math.sin(ego.yaw_rad[0])
        xi = (objs.x_m - ego.x_m[0]) * c + (objs.y_m - ego.y_m[0]) * s
        ahead = xi >= -(ego.length_m + objs.length_m) / 2
        return valid & ahead, np.zeros(n), 0.0, np.zeros(n)
    x = np.nan_to_num(np.concatenate([objs.x_m, ego.x_m[[0, -1]]]))
    y = np.nan_to_num(np.concatenate([objs.y_m, ego.y_m[[0, -1]]]))
    s_all = track.project(x, y)
    s_obj = s_all[:n]
    span = float(track.ahead_m(s_all[n], s_all[n + 1]))
    d = track.ahead_m(s_all[n], s_obj)
    keep = (d >= 0) & (d <= max(span, 0.0) + ego.length_m)
    return valid & keep, s_obj, float(s_all[n]), track.lateral_m(x[:n], y[:n], s_obj)


def _rule_patches(
    ctx: RuleContext, params: ReachParams, memory: Mapping[str, Mapping[str, bool]]
) -> tuple[list[RulePatch], LtlMemory]:
    patches: list[RulePatch] = []
    mem: LtlMemory = {}
    if not params.rules_enabled:
        return patches, mem
    if ctx.zones is not None and ctx.track is not None:
        found, m = evaluate_roborace(ctx, memory)
    elif params.f1.enabled and ctx.track is not None:
        found, m = evaluate_f1(ctx, memory)
    else:
        found, m = [], {}
    patches += found
    mem.update(m)
    if params.road.enabled and ctx.road is not None:
        found, m = evaluate_road(ctx, memory)
        patches += found
        mem.update(m)
    return patches, mem


def evaluate(
    inputs: ReachInputs, params: ReachParams, state: RuleState | None = None
) -> tuple[ReachResult, RuleState]:
    """Rate the ego plan of one frame against the rule-conform reachable sets of the others.

    Args:
        inputs: Ego plan, objects and map geometry of the frame.
        params: Engine parameters.
        state: State returned for the previous frame (``None`` at the start of a replay).

    Returns:
        The frame's result and the state for the next frame.
    """
    state = state or RuleState()
    times = params.times_array_s
    occ = ego_occupancy(inputs.ego, times)
    track = _prepared_track(inputs, params, state)
    keep, s_obj, s_ego, lat_obj = _select(inputs, track)
    rows = np.flatnonzero(keep)
    objs: ObjectStates = inputs.objects if keep.all() else inputs.objects.take(rows)
    skipped = tuple(str(i) for i in inputs.objects.ids[~keep])
    ego = inputs.ego
    ctx = RuleContext(
        objects=objs,
        ego_x_m=float(ego.x_m[0]),
        ego_y_m=float(ego.y_m[0]),
        ego_yaw_rad=float(ego.yaw_rad[0]),
        ego_speed_mps=float(np.nan_to_num(ego.speed_mps[0])),
        ego_length_m=ego.length_m,
        ego_width_m=ego.width_m,
        occupancy=occ,
        times_s=times,
        params=params,
        track=track,
        s_obj_m=s_obj[rows],
        s_ego_m=s_ego,
        lat_obj_m=lat_obj[rows],
        road=inputs.road,
        zones=inputs.zones,
    )
    patches, memory = _rule_patches(ctx, params, state.ltl)
    sets: NDArray[Any]
    if params.full_geometry or params.keep_largest_part_only:
        sets, hits = _full_sets(ctx, patches)
    else:
        sets, hits = _verdict(ctx, patches)
    collisions = []
    for i in np.flatnonzero(hits.any(axis=1)):
        k = int(np.argmax(hits[i]))
        collisions.append(Collision(str(objs.ids[i]), float(times[k]), k))
        _log.debug("collision with %s at %.2f s into the plan", objs.ids[i], times[k])
    result = ReachResult(
        is_safe=not collisions,
        collisions=tuple(collisions),
        patches=tuple(
            AppliedPatch(str(objs.ids[p.object_index]), p.rule, p.step, p.geometry) for p in patches
        ),
        object_ids=objs.ids,
        skipped_ids=skipped,
        occupancy=occ,
        sets=sets,
    )
    new_state = RuleState(ltl=memory, track_bounds=inputs.track, track=track)
    return result, new_state


def _full_sets(
    ctx: RuleContext, patches: list[RulePatch]
) -> tuple[NDArray[np.object_], NDArray[np.bool_]]:
    """Every reduced set and every cell where it touches the ego footprint, ``(N, T)`` each."""
    params, objs = ctx.params, ctx.objects
    sets = reachable_sets(objs, ctx.times_s, params, ctx.track)
    if patches:
        sets = subtract_patches(sets, patch_grid(patches, ctx.footprints, len(ctx.times_s)))
    if params.keep_largest_part_only and sets.size:
        sets = keep_largest_part(sets)
    if not sets.size:
        return sets, np.zeros(sets.shape, dtype=bool)
    hits = np.asarray(shapely.intersects(sets, ctx.occupancy.polygons[None, :]), dtype=bool)
    sets = sets.copy()
    sets[np.asarray(shapely.is_empty(sets), dtype=bool)] = None
    return sets, hits


def _verdict(
    ctx: RuleContext, patches: list[RulePatch]
) -> tuple[NDArray[np.float64], NDArray[np.bool_]]:
    """Unreduced simple sets ``(N, T, 6, 2)`` and the first hits (see ``verdict``)."""
    params, objs, track = ctx.params, ctx.objects, ctx.track
    verts = simple_vertices(objs, ctx.times_s, params)
    area = track.polygon if track is not None and params.trim_to_drivable else None
    hits = first_hits(
        verts,
        ctx.occupancy.corners_m,
        area=area,
        deletion=lambda: deletion_polygons(objs, params, track),
        patches=(
            (lambda cells: patch_grid(patches, ctx.footprints, len(ctx.times_s), cells))
            if patches
            else None
        ),
    )
    return verts, hits
