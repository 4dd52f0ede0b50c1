"""Runner of structured RSS (scene creation from the lane map + ``rss.engine``) over frames."""

from __future__ import annotations

from typing import TYPE_CHECKING, Any

import numpy as np

from rss.batch import stack_constellations
from rss.conformance import response_record
from rss.engine import check_frames, select_frame
from rss.params import ObjectClass, RssParams
from rss.scene import SceneMemo, create_scene, prepare
from rss.scene.boundaries import LEFT_BOUNDARY_ID, RIGHT_BOUNDARY_ID
from rss.scene.chunked import match_frames
from rss.scene.create import scene_boxes
from workbench.evaluate.pipeline import EngineOutput
from workbench.evaluate.rss_detail import RssFrameDetail, road_area_outlines
from workbench.rss_adapter import IdMap, frame_to_scene, lane_graph_from_map

if TYPE_CHECKING:
    from collections.abc import Sequence

    from loaders.maps.model import LaneMap
    from loaders.records import Frame
    from rss.arrays import IntArray
    from rss.engine import FrameResult
    from rss.memory import RssMemory
    from rss.scene import PreparedGraph, Scene

__all__ = ["RssRunner"]

_DROPPED_KEYS = ("unstructured_constellation_response", "heading_ranges")


class RssRunner:
    """Creates the constellations of every frame from the lane map and checks them.

    The RSS memory (last safe state per constellation) is carried from frame to frame; a
    fresh runner starts a replay at any frame with empty memory. Without a map (or with
    the ego off the map) no constellation can be built and every frame is safe.
    """

    name = "rss"

    def __init__(
        self,
        lane_map: LaneMap | None,
        params: RssParams | None = None,
        *,
        road_boundaries: bool = False,
        outlines: bool = False,
    ) -> None:
        """Prepare the lane graph once.

        Args:
            lane_map: The drive's lane map, if any.
            params: RSS dynamics and scene settings (defaults of ``rss.params``).
            road_boundaries: Also check the ego against the road boundaries along its
                route (off by default, as in CARLA).
            outlines: Also compute the road-area outline of every constellation (for the
                viewer; ``detail.road_areas``).
        """
        self._road_boundaries = road_boundaries
        self._outlines = outlines
        self._params = params or RssParams()
        self._prep: PreparedGraph | None = None
        if lane_map is not None and lane_map.format != "track":
            graph = lane_graph_from_map(lane_map)
            self._prep = prepare(graph) if len(graph) else None
        self._scene_memo = SceneMemo()  # per map, kept across frames (rss.scene.memo)
        self._ids = IdMap()
        self._memory: RssMemory | None = None

    def step(self, frame: Frame) -> EngineOutput:
        """Evaluate one frame."""
        return self.step_many([frame])[0]

    def step_many(self, frames: Sequence[Frame]) -> list[EngineOutput]:
        """Evaluate consecutive frames at once (as ``step`` on each in turn).

        The boxes of all frames are map-matched in one call, the constellations of all
        frames stacked once and checked in one ``check_frames`` call with the memory
        carried through them; a frame without constellations forgets the memory (the
        engine's runs of consecutive frames break there).
        """
        prep = self._prep
        if prep is None:
            return [_safe({"constellations": 0, "invalid_objects": []}) for _ in frames]
        inputs = [frame_to_scene(f, prep, self._params, self._ids) for f in frames]
        matches = match_frames(prep, [scene_boxes(ego, objects) for ego, objects, _ in inputs])
        scenes = [
            create_scene(
                prep,
                ego,
                objects,
                self._params.scene,
                road_boundaries=self._road_boundaries,
                matches=m,
                memo=self._scene_memo,
            )
            for (ego, objects, _), m in zip(inputs, matches, strict=True)
        ]
        counts = [len(s.constellations) for s in scenes]
        if not any(counts):
            self._memory = None
            return [
                _safe({"constellations": 0, "invalid_objects": sorted(invalid)})
                for _, _, invalid in inputs
            ]
        batch = stack_constellations([c for s in scenes for c in s.constellations])
        frame_of = np.repeat(np.arange(len(frames)), counts)
        ego_dyn = self._params.for_class(ObjectClass.EGO)
        result, memory = check_frames(batch, frame_of, len(frames), ego_dyn, self._memory)
        self._memory = memory if counts[-1] else None
        outputs = []
        offsets = np.concatenate([[0], np.cumsum(counts)]).tolist()
        for k, (scene, (_, _, invalid)) in enumerate(zip(scenes, inputs, strict=True)):
            if not counts[k]:
                outputs.append(_safe({"constellations": 0, "invalid_objects": sorted(invalid)}))
                continue
            rows = slice(offsets[k], offsets[k + 1])
            ids, kinds = batch.other.object_id[rows], batch.constellation_type[rows]
            outputs.append(self._output(scene, invalid, ids, kinds, select_frame(result, k)))
        return outputs

    def _output(
        self,
        scene: Scene,
        invalid: tuple[str, ...],
        object_id: IntArray,
        constellation_type: IntArray,
        result: FrameResult,
    ) -> EngineOutput:
        """One frame's output: its scene, ``(C,)`` other ids and types, result (``F = 1``)."""
        record: dict[str, Any] = response_record(result, object_id, 0)
        for key in _DROPPED_KEYS:
            record.pop(key, None)
        dangerous = sorted({_label(self._ids, int(x)) for x in record["dangerous_objects"]})
        record["dangerous_objects"] = dangerous
        record["constellations"] = len(object_id)
        bad = object_id[np.asarray(result.invalid) != 0]
        record["invalid_objects"] = sorted({*invalid, *(self._ids.to_str(int(x)) for x in bad)})
        is_safe = bool(record["is_safe"])
        prep = self._prep
        return EngineOutput(
            record=record,
            is_safe=is_safe,
            culprits=tuple(dangerous),
            label="" if is_safe else f"RSS {record['longitudinal_response']}",
            margin=0.0 if not is_safe else float("inf"),
            detail=RssFrameDetail(
                labels=tuple(_label(self._ids, int(x)) for x in object_id),
                constellation_type=constellation_type,
                result=result,
                road_areas=road_area_outlines(prep.graph, scene.road_areas)
                if self._outlines and prep is not None
                else (),
            ),
        )


def _label(ids: IdMap, object_id: int) -> str:
    names = {LEFT_BOUNDARY_ID: "road_boundary_left", RIGHT_BOUNDARY_ID: "road_boundary_right"}
    return names.get(object_id) or ids.to_str(object_id)


def _safe(extra: dict[str, Any]) -> EngineOutput:
    record: dict[str, Any] = {
        "is_safe": True,
        "dangerous_objects": [],
        "longitudinal_response": "None",
        "lateral_response_left": "None",
        "lateral_response_right": "None",
        "acceleration_restrictions": None,
        **extra,
    }
    return EngineOutput(record=record, is_safe=True)
