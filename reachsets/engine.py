"""The reach-set supervisor: ``evaluate_frames(inputs, params, state) -> (results, state)``.

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
from dataclasses import dataclass, field, replace
from functools import cached_property
from typing import TYPE_CHECKING, Any

import numpy as np
import shapely

from reachsets.batch import FrameBatch, stack_frames
from reachsets.footprints import rectangles
from reachsets.patches import (
    RulePatch,
    keep_largest_part,
    patch_grid,
    subtract_patches,
)
from reachsets.reachable import deletion_polygons, reachable_sets, simple_vertices
from reachsets.road import prepare_road
from reachsets.rules_f1 import evaluate_f1
from reachsets.rules_road import evaluate_road
from reachsets.rules_roborace import evaluate_roborace
from reachsets.track import TrackGeometry, build_track
from reachsets.verdict import first_hits, touching

if TYPE_CHECKING:
    from collections.abc import Mapping, Sequence

    from numpy.typing import NDArray

    from reachsets.inputs import ReachInputs, RoadLayout, TrackBounds
    from reachsets.ltl import LtlMemory
    from reachsets.occupancy import EgoOccupancy
    from reachsets.params import ReachParams
    from reachsets.reduce import CellRings
    from reachsets.road import RoadGeometry

__all__ = [
    "AppliedPatch",
    "Collision",
    "FrameRings",
    "ReachResult",
    "RuleState",
    "evaluate_frames",
]

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
        road: The road layout ``road_geometry`` was built from (reused while the same object).
        road_geometry: Its static shapes.
    """

    ltl: Mapping[str, Mapping[str, bool]] = field(default_factory=dict)
    track_bounds: TrackBounds | None = None
    track: TrackGeometry | None = None
    road: RoadLayout | None = None
    road_geometry: RoadGeometry | None = None


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
        skipped_road: Lanes and solid lines of the road layout left out for unusable
            geometry (``RoadGeometry.skipped``); the rules ran on the rest.
        rings: Full geometry: the clipper's rings the sets were built from (``CellRings`` of
            the engine call, this frame's cells ``cells``), or ``None``.
    """

    is_safe: bool
    collisions: tuple[Collision, ...]
    patches: tuple[AppliedPatch, ...]
    object_ids: NDArray[np.str_]
    skipped_ids: tuple[str, ...]
    occupancy: EgoOccupancy
    sets: NDArray[Any]
    skipped_road: tuple[str, ...] = ()
    rings: FrameRings | None = None

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


@dataclass(frozen=True, slots=True)
class FrameRings:
    """A frame's share of an engine call's :class:`~reachsets.reduce.CellRings`.

    Attributes:
        cells: The rings of the call's cells (flat ``row * T + step``).
        start: The frame's first flat cell.
        stop: One past its last (``start + M * T``).
    """

    cells: CellRings
    start: int
    stop: int


def _same_bounds(a: TrackBounds | None, b: TrackBounds | None) -> bool:
    if a is None or b is None:
        return a is b
    return a is b or (np.array_equal(a.left_m, b.left_m) and np.array_equal(a.right_m, b.right_m))


def _prepared_track(
    bounds: TrackBounds | None, params: ReachParams, state: RuleState
) -> TrackGeometry | None:
    """The track geometry of ``bounds``: the state's while the bounds are unchanged."""
    if bounds is None:
        return None
    if state.track is not None and _same_bounds(state.track_bounds, bounds):
        return state.track
    return build_track(bounds, params.closed_track_gap_m)


def _runs(inputs: Sequence[ReachInputs]) -> list[list[ReachInputs]]:
    """Consecutive frames sharing one map (track bounds, road layout and zones)."""
    runs: list[list[ReachInputs]] = []
    for inp in inputs:
        if runs:
            prev = runs[-1][-1]
            if (
                prev.road is inp.road
                and prev.zones is inp.zones
                and _same_bounds(prev.track, inp.track)
            ):
                runs[-1].append(inp)
                continue
        runs.append([inp])
    return runs


def _rule_patches(
    batch: FrameBatch, memory: Mapping[str, Mapping[str, bool]]
) -> tuple[list[RulePatch], LtlMemory]:
    """Every rule over the batch: F1 in one pass, Roborace and road rules frame by frame.

    Patches name batch rows; the memory is the one after the last frame.
    """
    params = batch.params
    patches: list[RulePatch] = []
    mem: LtlMemory = {}
    if not params.rules_enabled:
        return patches, mem
    roborace = batch.zones is not None and batch.track is not None
    road = params.road.enabled and batch.road is not None
    if not roborace and params.f1.enabled and batch.track is not None and len(batch.objects):
        patches, mem = evaluate_f1(batch, memory)
    if roborace or road:
        frame_mem: Mapping[str, Mapping[str, bool]] = memory
        step_mem: LtlMemory = {}
        for f in range(batch.n_frames):
            ctx = batch.context(f)
            step_mem = {}
            for rule, on in ((evaluate_roborace, roborace), (evaluate_road, road)):
                if on:
                    found, m = rule(ctx, frame_mem)
                    shift = int(batch.offsets[f])
                    patches += [replace(p, object_index=p.object_index + shift) for p in found]
                    step_mem.update(m)
            frame_mem = step_mem
        mem.update(step_mem)
    return patches, mem


def evaluate_frames(
    inputs: Sequence[ReachInputs], params: ReachParams, state: RuleState | None
) -> tuple[list[ReachResult], RuleState]:
    """Rate the ego plan of each of consecutive frames against the rule-conform reachable sets.

    Frames that share a map are stacked into one batch: every geometric step runs once
    over all their objects, and the rules' past-time LTL memory is carried along each
    object's frames exactly as frame by frame (one frame is the batch of one; the results
    and the state do not depend on how a drive is cut into calls).

    Args:
        inputs: The frames, in time order: ego plan, objects and map geometry of each.
        params: Engine parameters.
        state: State returned for the frame before the first one (``None`` at the start of a
            replay).

    Returns:
        One result per frame and the state for the frame after the last one.
    """
    state = state or RuleState()
    results: list[ReachResult] = []
    for run in _runs(inputs):
        track = _prepared_track(run[0].track, params, state)
        road = run[0].road
        road_geo = state.road_geometry if road is not None and state.road is road else None
        if road is not None and road_geo is None and params.rules_enabled:
            road_geo = prepare_road(road)
        batch = stack_frames(run, params, track, road_geo)
        patches, memory = _rule_patches(batch, state.ltl)
        sets: NDArray[Any]
        rings: CellRings | None = None
        if params.full_geometry or params.keep_largest_part_only:
            sets, hits, rings = _full_sets(batch, patches)
        else:
            sets, hits = _verdict(batch, patches)
        results += _split(batch, (sets, hits, rings), patches)
        state = RuleState(
            ltl=memory, track_bounds=run[-1].track, track=track, road=road, road_geometry=road_geo
        )
    return results, state


def _split(
    batch: FrameBatch,
    reduced: tuple[NDArray[Any], NDArray[np.bool_], CellRings | None],
    patches: list[RulePatch],
) -> list[ReachResult]:
    """Per-frame results of a batch (``reduced``: its sets, hits and rings)."""
    sets, hits, rings = reduced
    steps = sets.shape[1] if sets.ndim > 1 else 0
    times = batch.occupancy.t_s
    ids = batch.objects.ids
    first = np.where(hits.any(axis=1), np.argmax(hits, axis=1), -1)
    applied: list[list[AppliedPatch]] = [[] for _ in range(batch.n_frames)]
    for p in patches:
        applied[int(batch.frame[p.object_index])].append(
            AppliedPatch(str(ids[p.object_index]), p.rule, p.step, p.geometry)
        )
    geo = batch.road_geometry
    skipped_road = geo.skipped if geo is not None else ()
    out = []
    for f in range(batch.n_frames):
        lo, hi = int(batch.offsets[f]), int(batch.offsets[f + 1])
        collisions = []
        for i in np.flatnonzero(first[lo:hi] >= 0) + lo:
            k = int(first[i])
            collisions.append(Collision(str(ids[i]), float(times[k]), k))
            _log.debug("collision with %s at %.2f s into the plan", ids[i], times[k])
        out.append(
            ReachResult(
                is_safe=not collisions,
                collisions=tuple(collisions),
                patches=tuple(applied[f]),
                object_ids=ids[lo:hi],
                skipped_ids=batch.skipped_ids[f],
                occupancy=batch.occupancy.frame(f),
                sets=sets[lo:hi],
                skipped_road=skipped_road,
                rings=None if rings is None else FrameRings(rings, lo * steps, hi * steps),
            )
        )
    return out


def _full_sets(
    batch: FrameBatch, patches: list[RulePatch]
) -> tuple[NDArray[np.object_], NDArray[np.bool_], CellRings | None]:
    """Every reduced set and every cell where it touches the ego footprint, ``(R, T)`` each.

    Also the clipper's rings of the sets (``None`` without), their patched cells not exact.
    """
    params, objs, times = batch.params, batch.objects, batch.occupancy.t_s
    found: list[CellRings] = []
    sets = reachable_sets(objs, times, params, batch.track, rings=found)
    rings = found[0] if found else None
    if patches:
        grid = patch_grid(patches, _footprints(batch), len(times))
        sets = subtract_patches(sets, grid)
        if rings is not None:
            at = [g is not None for g in grid.at.reshape(-1)]
            every = np.repeat([g is not None for g in grid.every], len(times))
            rings.exact[np.asarray(at, dtype=bool) | every] = False
    if params.keep_largest_part_only and sets.size:
        sets = keep_largest_part(sets)
        rings = None
    if not sets.size:
        return sets, np.zeros(sets.shape, dtype=bool), rings
    hits = touching(sets, batch.occupancy.corners_m, batch.frame)
    sets = sets.copy()
    sets[np.asarray(shapely.is_empty(sets), dtype=bool)] = None
    return sets, hits, rings


def _verdict(
    batch: FrameBatch, patches: list[RulePatch]
) -> tuple[NDArray[np.float64], NDArray[np.bool_]]:
    """Unreduced simple sets ``(R, T, 6, 2)`` and the first hits (see ``verdict``)."""
    params, objs, track, times = batch.params, batch.objects, batch.track, batch.occupancy.t_s
    verts = simple_vertices(objs, times, params)
    area = track.polygon if track is not None and params.trim_to_drivable else None
    hits = first_hits(
        verts,
        batch.ego_corners_m,
        area=area,
        deletion=lambda rows: deletion_polygons(objs.take(rows), params, track),
        patches=(
            (lambda cells: patch_grid(patches, _footprints(batch), len(times), cells))
            if patches
            else None
        ),
    )
    return verts, hits


def _footprints(batch: FrameBatch) -> NDArray[np.object_]:
    o = batch.objects
    return rectangles(o.x_m, o.y_m, o.yaw_rad, o.length_m, o.width_m).reshape(len(o))
