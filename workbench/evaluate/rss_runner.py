"""Runner of structured RSS (scene creation from the lane map + ``rss.engine``) over frames."""

from __future__ import annotations

from typing import TYPE_CHECKING, Any

import numpy as np

from rss.batch import stack_constellations
from rss.conformance import response_record
from rss.engine import check_frame
from rss.params import ObjectClass, RssParams
from rss.scene import create_scene, prepare
from rss.scene.boundaries import LEFT_BOUNDARY_ID, RIGHT_BOUNDARY_ID
from workbench.evaluate.pipeline import EngineOutput
from workbench.evaluate.rss_detail import RssFrameDetail, road_area_outlines
from workbench.rss_adapter import IdMap, frame_to_scene, lane_graph_from_map

if TYPE_CHECKING:
    from loaders.maps.model import LaneMap
    from loaders.records import Frame
    from rss.memory import RssMemory
    from rss.scene import PreparedGraph

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
        self._ids = IdMap()
        self._memory: RssMemory | None = None

    def step(self, frame: Frame) -> EngineOutput:
        """Evaluate one frame."""
        ego_dyn = self._params.for_class(ObjectClass.EGO)
        if self._prep is None:
            return _safe({"constellations": 0, "invalid_objects": []})
        ego, objects, invalid = frame_to_scene(frame, self._prep, self._params, self._ids)
        scene = create_scene(
            self._prep, ego, objects, self._params.scene, road_boundaries=self._road_boundaries
        )
        if not scene.constellations:
            self._memory = None
            return _safe({"constellations": 0, "invalid_objects": sorted(invalid)})
        batch = stack_constellations(scene.constellations)
        result, self._memory = check_frame(batch, ego_dyn, self._memory)
        record: dict[str, Any] = response_record(result, batch.other.object_id, 0)
        for key in _DROPPED_KEYS:
            record.pop(key, None)
        dangerous = sorted({_label(self._ids, int(x)) for x in record["dangerous_objects"]})
        record["dangerous_objects"] = dangerous
        record["constellations"] = batch.size
        bad = batch.other.object_id[np.asarray(result.invalid) != 0]
        record["invalid_objects"] = sorted({*invalid, *(self._ids.to_str(int(x)) for x in bad)})
        is_safe = bool(record["is_safe"])
        return EngineOutput(
            record=record,
            is_safe=is_safe,
            culprits=tuple(dangerous),
            label="" if is_safe else f"RSS {record['longitudinal_response']}",
            margin=0.0 if not is_safe else float("inf"),
            detail=RssFrameDetail(
                labels=tuple(_label(self._ids, int(x)) for x in batch.other.object_id),
                constellation_type=batch.constellation_type,
                result=result,
                road_areas=road_area_outlines(self._prep.graph, scene.road_areas)
                if self._outlines
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
