"""``evaluate_frames``: structured RSS of consecutive frames, from boxes on a lane map.

Scene creation (:mod:`rss.scene`) and the structured kernels (:mod:`rss.structured`) over
``F`` consecutive frames, the memory passed in and out so a replay can restart at any
frame::

    F x (SceneEgo, SceneObjects) ──match_frames──▶ F x Matches      (one map-matching call)
                                 ──create_scene──▶ F x Scene         (C_f constellations)
                                 ──stack_constellations──▶ ConstellationBatch (C = Σ C_f)
                                 ──check_frames──▶ FrameResult of F frames, memory out
                                 ──select_frame──▶ F x FrameVerdict

Frames without constellations are safe and unchecked; one of them forgets the memory
(the runs of frames the engine carries its memory through break there). A malformed
constellation (e.g. a road area with a lane twice) is left out of its frame and named in
``FrameVerdict.rejected`` with the reason; the rest of the frame is checked.
"""

from __future__ import annotations

import dataclasses
from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np

from rss.arrays import IntArray  # noqa: TC001 - dataclass field type
from rss.errors import RssConstellationError
from rss.params import ObjectClass
from rss.scene import SceneMemo, create_scene
from rss.scene.chunked import match_frames
from rss.scene.create import scene_boxes
from rss.structured.engine import FrameResult, check_frames, select_frame
from rss.structured.stacking import stack_constellations
from rss.structured.standstill import apply_standstill

if TYPE_CHECKING:
    from collections.abc import Sequence

    from rss.params import RssParams
    from rss.scene import PreparedGraph, Scene, SceneEgo, SceneObjects
    from rss.structured.batch import ConstellationBatch
    from rss.structured.memory import RssMemory

__all__ = ["FrameVerdict", "evaluate_frames"]

_NO_ROWS = np.zeros(0, dtype=np.int64)
_NO_ROWS.flags.writeable = False


@dataclass(frozen=True)
class FrameVerdict:
    """Structured RSS of one frame.

    Attributes:
        scene: The frame's scene (constellations, road areas).
        object_id: ``(C,)`` the other object's id of each constellation (road boundaries:
            ``rss.scene.boundaries`` ids).
        constellation_type: ``(C,)`` :class:`rss.model.ConstellationType` codes.
        result: The engine's result of the frame alone (``F = 1``, as
            :func:`rss.structured.engine.check_frame` returns it); ``None`` when the frame
            has no constellation (safe, nothing checked).
        rejected: ``(other object id, reason)`` of each malformed constellation left out
            of the frame (``scene`` no longer holds them).
    """

    scene: Scene
    object_id: IntArray
    constellation_type: IntArray
    result: FrameResult | None
    rejected: tuple[tuple[int, str], ...] = ()


def evaluate_frames(
    frames: Sequence[tuple[SceneEgo, SceneObjects]],
    params: RssParams,
    state: RssMemory | None,
    *,
    graph: PreparedGraph,
    memo: SceneMemo | None = None,
    road_boundaries: bool = False,
    responsibility: bool = False,
) -> tuple[list[FrameVerdict], RssMemory | None]:
    """Create the scenes of ``F`` consecutive frames and check them in one call.

    The boxes of all frames are map-matched at once, the constellations of all frames
    stacked once and checked by one :func:`rss.structured.engine.check_frames` with the
    memory carried through them. The results equal one call per frame in order, each
    given the memory the previous one returned.

    Args:
        frames: ``(F,)`` the ego and the objects of each frame, in time order.
        params: Dynamics per object class (the ego class's are the default ego dynamics)
            and scene settings.
        state: Memory before the first frame (``None`` = fresh start).
        graph: The prepared lane graph of the drive's map.
        memo: The map's scene memo, kept by the caller across calls (``None``: a fresh one
            for this call; same results, slower).
        road_boundaries: Also check the ego against the road boundaries along its route.
        responsibility: Also check every constellation from the other object's side
            (``FrameResult.responsibility``: who must act); the verdicts do not change.

    Returns:
        ``(verdicts (F,), memory after the last frame)``; the memory is ``None`` (forgotten)
        when the last frame has no constellation.
    """
    matches = match_frames(graph, [scene_boxes(ego, objects) for ego, objects in frames])
    memo = memo if memo is not None else SceneMemo()
    scenes = [
        create_scene(
            graph,
            ego,
            objects,
            params.scene,
            road_boundaries=road_boundaries,
            matches=m,
            memo=memo,
        )
        for (ego, objects), m in zip(frames, matches, strict=True)
    ]
    batch, scenes, rejected = _stacked(scenes)
    counts = [len(s.constellations) for s in scenes]
    if batch is not None:
        batch = apply_standstill(batch, params.standstill_speed_mps)
    if batch is None:
        verdicts = [
            FrameVerdict(s, _NO_ROWS, _NO_ROWS, None, bad)
            for s, bad in zip(scenes, rejected, strict=True)
        ]
        return verdicts, None
    frame_of = np.repeat(np.arange(len(frames)), counts)
    ego_dyn = params.for_class(ObjectClass.EGO)
    result, memory = check_frames(
        batch, frame_of, len(frames), ego_dyn, state, with_responsibility=responsibility
    )
    offsets = np.concatenate([[0], np.cumsum(counts)]).tolist()
    verdicts = []
    for k, scene in enumerate(scenes):
        if not counts[k]:
            verdicts.append(FrameVerdict(scene, _NO_ROWS, _NO_ROWS, None, rejected[k]))
            continue
        rows = slice(offsets[k], offsets[k + 1])
        verdicts.append(
            FrameVerdict(
                scene,
                batch.other.object_id[rows],
                batch.constellation_type[rows],
                select_frame(result, k),
                rejected[k],
            )
        )
    return verdicts, memory if counts[-1] else None


def _stacked(
    scenes: list[Scene],
) -> tuple[ConstellationBatch | None, list[Scene], list[tuple[tuple[int, str], ...]]]:
    """The stacked constellations of all frames (``None``: none), their scenes, the rejected.

    Stacking checks every constellation. Only when the whole batch fails is each one stacked
    alone: the malformed ones leave their scene and are named ``(object id, reason)`` per
    frame, and the rest is stacked again.
    """
    rejected: list[tuple[tuple[int, str], ...]] = [() for _ in scenes]
    rows = [c for s in scenes for c in s.constellations]
    if not rows:
        return None, scenes, rejected
    try:
        return stack_constellations(rows), scenes, rejected
    except RssConstellationError:
        scenes, rejected = _well_formed(scenes)
    rows = [c for s in scenes for c in s.constellations]
    return (stack_constellations(rows) if rows else None), scenes, rejected


def _well_formed(scenes: list[Scene]) -> tuple[list[Scene], list[tuple[tuple[int, str], ...]]]:
    """The scenes without malformed constellations, and ``(object id, reason)`` per frame."""
    kept_scenes, rejected = [], []
    for scene in scenes:
        keep: list[int] = []
        bad: list[tuple[int, str]] = []
        for k, constellation in enumerate(scene.constellations):
            try:
                stack_constellations([constellation])
            except RssConstellationError as err:
                bad.append((int(constellation.other.object_id), str(err)))
            else:
                keep.append(k)
        areas = tuple(scene.road_areas[k] for k in keep) if scene.road_areas else ()
        constellations = tuple(scene.constellations[k] for k in keep)
        kept_scenes.append(
            dataclasses.replace(scene, constellations=constellations, road_areas=areas)
        )
        rejected.append(tuple(bad))
    return kept_scenes, rejected
