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
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any

import numpy as np
import shapely

from reachsets.footprints import rectangles
from reachsets.occupancy import EgoOccupancy, ego_occupancy
from reachsets.patches import (
    RuleContext,
    RulePatch,
    keep_largest_part,
    patch_grid,
    subtract_patches,
)
from reachsets.reachable import reachable_sets, simple_sets
from reachsets.rules_f1 import evaluate_f1
from reachsets.rules_road import evaluate_road
from reachsets.rules_roborace import evaluate_roborace
from reachsets.track import TrackGeometry, build_track

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


@dataclass(frozen=True, slots=True)
class ReachResult:
    """Verdict of one frame.

    Attributes:
        is_safe: No reduced reachable set touches the ego footprint.
        collisions: First collision per colliding object, in object order.
        patches: Rule patches subtracted.
        object_ids: Objects evaluated, ``(M,)``.
        skipped_ids: Objects not evaluated (behind the ego or invalid).
        reach_sets: Reduced reachable sets, ``(M, T)`` geometries; ``None`` where nothing is
            left (e.g. the reference's ``turn`` deletion removes a standing object's set).
        occupancy: Ego footprints.
    """

    is_safe: bool
    collisions: tuple[Collision, ...]
    patches: tuple[AppliedPatch, ...]
    object_ids: NDArray[np.str_]
    skipped_ids: tuple[str, ...]
    reach_sets: NDArray[np.object_]
    occupancy: EgoOccupancy


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


def _clip_footprints(footprints: NDArray[np.object_], area: Any) -> NDArray[np.object_]:
    """``footprints & area``, clipping ``area`` to the footprints' bounding box first."""
    box = shapely.box(*shapely.total_bounds(footprints))
    return np.asarray(shapely.intersection(footprints, shapely.intersection(area, box)))


def _select(
    inputs: ReachInputs, track: TrackGeometry | None
) -> tuple[NDArray[np.bool_], NDArray[np.float64], float]:
    """Mask of objects to evaluate, their arc lengths and the ego's."""
    objs, ego = inputs.objects, inputs.ego
    pose = np.stack([objs.x_m, objs.y_m, objs.yaw_rad, objs.length_m, objs.width_m])
    valid = np.all(np.isfinite(pose), axis=0) & (objs.length_m > 0) & (objs.width_m > 0)
    if track is None:
        c, s = np.cos(ego.yaw_rad[0]), np.sin(ego.yaw_rad[0])
        xi = (objs.x_m - ego.x_m[0]) * c + (objs.y_m - ego.y_m[0]) * s
        ahead = xi >= -(ego.length_m + objs.length_m) / 2
        return valid & ahead, np.zeros(len(objs)), 0.0
    s_obj = track.project(np.nan_to_num(objs.x_m), np.nan_to_num(objs.y_m))
    s_ends = track.project(ego.x_m[[0, -1]], ego.y_m[[0, -1]])
    span = float(track.ahead_m(s_ends[0], s_ends[1]))
    d = track.ahead_m(s_ends[0], s_obj)
    keep = (d >= 0) & (d <= max(span, 0.0) + ego.length_m)
    return valid & keep, s_obj, float(s_ends[0])


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
    times = np.asarray(params.times_s)
    occ = ego_occupancy(inputs.ego, times)
    track = _prepared_track(inputs, params, state)
    keep, s_obj, s_ego = _select(inputs, track)
    rows = np.flatnonzero(keep)
    objs: ObjectStates = inputs.objects.take(rows)
    skipped = tuple(str(i) for i in inputs.objects.ids[~keep])
    cells = None
    zone = occ.polygons
    if params.full_geometry:
        sets = reachable_sets(objs, times, params, track)
    else:
        # Verdict only: clip the ego footprints to the track once instead of trimming every
        # set ((S - D - P) & T touches E  <=>  S - D - P touches E & T), and reduce only the
        # cells whose unreduced simple set touches the clipped footprint.
        # (Keeping only the largest part needs the trimmed sets: then they are trimmed.)
        clip = params.trim_to_drivable and track is not None and not params.keep_largest_part_only
        if clip and track is not None:
            zone = _clip_footprints(occ.polygons, track.polygon)
        raw = simple_sets(objs, times, params)
        cells = (
            np.asarray(shapely.intersects(raw, zone[None, :]), dtype=bool)
            if raw.size
            else np.zeros(raw.shape, dtype=bool)
        )
        sets = (
            reachable_sets(objs, times, params, track, cells=cells, simple=raw, trim=not clip)
            if cells.any()
            else raw
        )
    footprints = rectangles(objs.x_m, objs.y_m, objs.yaw_rad, objs.length_m, objs.width_m)
    ego = inputs.ego
    ctx = RuleContext(
        objects=objs,
        footprints=footprints.reshape(len(objs)),
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
        road=inputs.road,
        zones=inputs.zones,
    )
    patches, memory = _rule_patches(ctx, params, state.ltl)
    if patches:
        grid = patch_grid(patches, ctx.footprints, len(times), cells)
        sets = subtract_patches(sets, grid)
    if params.keep_largest_part_only and sets.size:
        sets = keep_largest_part(sets)
    hits = (
        np.asarray(shapely.intersects(sets, zone[None, :]), dtype=bool)
        if sets.size
        else np.zeros((len(objs), len(times)), dtype=bool)
    )
    if cells is not None:
        hits &= cells
    if sets.size:
        sets = sets.copy()
        sets[np.asarray(shapely.is_empty(sets), dtype=bool)] = None
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
        reach_sets=sets,
        occupancy=occ,
    )
    new_state = RuleState(ltl=memory, track_bounds=inputs.track, track=track)
    return result, new_state
