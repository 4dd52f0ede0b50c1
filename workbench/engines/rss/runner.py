"""Runner of structured RSS over frames (scene creation + checks: ``rss.evaluate_frames``)."""

from __future__ import annotations

import dataclasses
from typing import TYPE_CHECKING

import numpy as np

from rss import evaluate_frames
from rss.params import RssParams
from rss.scene import SceneMemo, prepare
from rss.scene.boundaries import LEFT_BOUNDARY_ID, RIGHT_BOUNDARY_ID
from rss.structured.states import LateralResponse, LongitudinalResponse
from workbench.engines.ids import ActorIds
from workbench.engines.rss.adapter import frame_to_scene, lane_graph_from_map
from workbench.engines.rss.causes import RssCause
from workbench.engines.rss.compliance import ComplianceTracker
from workbench.engines.rss.outlines import road_area_outlines
from workbench.engines.rss.verdict import RssVerdict

if TYPE_CHECKING:
    from collections.abc import Sequence

    from loaders.maps.model import LaneMap
    from loaders.records import Frame
    from rss import FrameResult, RssMemory
    from rss.arrays import IntArray
    from rss.scene import PreparedGraph, Scene

__all__ = ["RssRunner"]


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
        responsibility: bool = True,
        ids: ActorIds | None = None,
    ) -> None:
        """Prepare the lane graph once.

        Args:
            lane_map: The drive's lane map, if any.
            params: RSS dynamics and scene settings (defaults of ``rss.params``).
            road_boundaries: Also check the ego against the road boundaries along its
                route (off by default, as in CARLA).
            outlines: Also compute the road-area outline of every constellation (for the
                viewer; ``detail.road_areas``).
            responsibility: Also check every constellation from the other object's side
                (who must act; ``RssVerdict.responsible``). On by default.
            ids: The drive's actor label table, shared with its other engines (a table
                of its own when ``None``).
        """
        self._road_boundaries = road_boundaries
        self._outlines = outlines
        self._responsibility = responsibility
        self._params = params or RssParams()
        self._prep: PreparedGraph | None = None
        if lane_map is not None and lane_map.format != "track":
            graph = lane_graph_from_map(lane_map)
            self._prep = prepare(graph) if len(graph) else None
        self._scene_memo = SceneMemo()  # per map, kept across frames (rss.scene.memo)
        self._ids = ids if ids is not None else ActorIds()
        self._memory: RssMemory | None = None
        self._compliance = ComplianceTracker(self._params)

    def step_many(self, frames: Sequence[Frame]) -> list[RssVerdict]:
        """Evaluate consecutive frames at once (as ``step`` on each in turn).

        One :func:`rss.evaluate_frames` call: the boxes of all frames map-matched at
        once, their constellations checked in one batch with the memory carried through
        them; a frame without constellations forgets the memory.
        """
        prep = self._prep
        label = self._params.profile_label
        if prep is None:
            return [_safe((), label) for _ in frames]
        inputs = [frame_to_scene(f, prep, self._params, self._ids) for f in frames]
        verdicts, self._memory = evaluate_frames(
            [(ego, objects) for ego, objects, _ in inputs],
            self._params,
            self._memory,
            graph=prep,
            memo=self._scene_memo,
            road_boundaries=self._road_boundaries,
            responsibility=self._responsibility,
        )
        out = [
            _safe(invalid, label)
            if v.result is None
            else self._output(v.scene, invalid, v.object_id, v.constellation_type, v.result)
            for v, (_, _, invalid) in zip(verdicts, inputs, strict=True)
        ]
        out = [self._with_rejected(o, v.rejected) for o, v in zip(out, verdicts, strict=True)]
        if not self._responsibility:
            return out
        duties = self._compliance.obligations(frames, out)
        return [
            dataclasses.replace(v, obligations=d) if d else v
            for v, d in zip(out, duties, strict=True)
        ]

    def _with_rejected(
        self, verdict: RssVerdict, rejected: tuple[tuple[int, str], ...]
    ) -> RssVerdict:
        """The verdict naming the malformed constellations left out of its frame."""
        if not rejected:
            return verdict
        named = tuple((_label(self._ids, object_id), reason) for object_id, reason in rejected)
        invalid = tuple(sorted({*verdict.invalid_objects, *(label for label, _ in named)}))
        return dataclasses.replace(verdict, invalid_objects=invalid, rejected=named)

    def _output(
        self,
        scene: Scene,
        invalid: tuple[str, ...],
        object_id: IntArray,
        constellation_type: IntArray,
        result: FrameResult,
    ) -> RssVerdict:
        """One frame's verdict: its scene, ``(C,)`` other ids and types, result (``F = 1``)."""
        dangerous = object_id[result.dangerous & (result.frame == 0)]
        culprits = tuple(sorted({_label(self._ids, int(x)) for x in dangerous}))
        bad = object_id[np.asarray(result.invalid) != 0]
        is_safe = bool(result.responses.is_safe[0])
        cause: RssCause | str = "" if is_safe else _cause(result)
        margin = float("inf") if is_safe else 0.0
        if not is_safe and result.severity is not None:
            margin = float(np.min(result.severity.distance_ratio[result.dangerous]))
        prep = self._prep
        return RssVerdict(
            is_safe=is_safe,
            culprits=culprits,
            cause=cause,
            margin=margin,
            invalid_objects=tuple(sorted({*invalid, *(self._ids.label(int(x)) for x in bad)})),
            labels=tuple(_label(self._ids, int(x)) for x in object_id),
            constellation_type=constellation_type,
            object_id=object_id,
            result=result,
            road_areas=road_area_outlines(prep.graph, scene.road_areas)
            if self._outlines and prep is not None
            else (),
            responsible=None
            if result.responsibility is None
            else result.responsibility.responsible,
            profile=self._params.profile_label,
        )


def _cause(result: FrameResult) -> RssCause:
    """The proper responses the frame demands."""
    r = result.responses
    return RssCause(
        LongitudinalResponse(int(r.longitudinal_response[0])),
        LateralResponse(int(r.lateral_response_left[0])),
        LateralResponse(int(r.lateral_response_right[0])),
    )


_BOUNDARIES = {LEFT_BOUNDARY_ID: "road_boundary_left", RIGHT_BOUNDARY_ID: "road_boundary_right"}


def _label(ids: ActorIds, object_id: int) -> str:
    """The label of a constellation's other object: an actor's or a road boundary's."""
    return _BOUNDARIES.get(object_id) or ids.label(object_id)


def _safe(invalid: tuple[str, ...] | list[str], profile: str) -> RssVerdict:
    """The verdict of a frame without constellations."""
    return RssVerdict(is_safe=True, invalid_objects=tuple(sorted(invalid)), profile=profile)
