"""Runner of unstructured RSS (trajectory sets, ``rss.unstructured``) over loader frames.

Per-frame record (keys shared with the ``rss`` runner keep its names and meaning)::

    is_safe                    bool, no dangerous object
    dangerous_objects          [actor id, ...] sorted
    decisions                  {actor id: "Brake" | "ContinueForward" | "DriveAway" | "None"}
    longitudinal_response      "BrakeMin" when the resolved response is Brake, else "None"
    unstructured_constellation_response   the resolved response (ad-rss ProperResponse)
    heading_ranges             [[begin, end], ...] allowed headings while driving away [rad]
    acceleration_restrictions  {"longitudinal": [min, max], "lateral_left": ..., ...} [m/s²]
    constellations             number of unstructured pairs checked
    invalid_objects            [actor id, ...] selected rows that could not be checked

ad-rss leaves ``longitudinal_response`` "None" for unstructured constellations and restricts
the acceleration instead (max ≤ ``brake_min`` on Brake); we name that restriction BrakeMin so
the key means the same as in structured RSS.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

from rss.conformance import json_number
from rss.params import ObjectClass, RssParams
from rss.physics import ACCELERATION_LOWEST_MPS2
from rss.unstructured import FrameInputs, UnstructuredResponse, evaluate_frames
from workbench.evaluate.pipeline import EngineOutput
from workbench.rss_adapter import IdMap
from workbench.unstructured_adapter import UnstructuredScope, frame_to_agents

if TYPE_CHECKING:
    from collections.abc import Sequence

    from loaders.maps.model import LaneMap
    from loaders.records import Frame
    from rss.unstructured import UnstructuredAgents, UnstructuredMemory, UnstructuredResult
    from workbench.unstructured_adapter import FrameAgents

__all__ = ["UnstructuredDetail", "UnstructuredRunner", "response_label"]

_LABELS = {
    UnstructuredResponse.Brake: "brake",
    UnstructuredResponse.DriveAway: "drive-away",
    UnstructuredResponse.ContinueForward: "continue-forward",
    UnstructuredResponse.None_: "none",
}


def response_label(response: UnstructuredResponse) -> str:
    """Short lower-case name of a response (``brake``, ``drive-away``, ...)."""
    return _LABELS[UnstructuredResponse(response)]


@dataclass(frozen=True)
class UnstructuredDetail:
    """What the Rerun sink draws for one frame.

    Attributes:
        ego: The ego as checked (one row, heading of travel).
        result: The engine's result (sets, decisions, proper response).
        actor_ids: ``(K,)`` actor id of each agent of ``result``.
    """

    ego: UnstructuredAgents
    result: UnstructuredResult
    actor_ids: tuple[str, ...]


class UnstructuredRunner:
    """Checks the unstructured pairs of every frame (see ``workbench.unstructured_adapter``).

    The memory (22.1b of the last safe step, drive-away state) is carried from frame to
    frame; a fresh runner starts a replay at any frame with empty memory. ``step_many``
    evaluates consecutive frames in one batch (``rss.unstructured.evaluate_frames``)
    with the same results.
    """

    name = "unstructured"

    def __init__(self, lane_map: LaneMap | None, params: RssParams | None = None) -> None:
        """Index the lane map for the pair selection.

        Args:
            lane_map: The drive's lane map, if any.
            params: RSS dynamics and scene settings (defaults of ``rss.params``).
        """
        self._params = params or RssParams()
        self._scope = UnstructuredScope(lane_map, self._params.scene.constellation_creation_mode)
        self._ids = IdMap()
        self._memory: UnstructuredMemory | None = None

    def step(self, frame: Frame) -> EngineOutput:
        """Evaluate one frame."""
        return self.step_many([frame])[0]

    def step_many(self, frames: Sequence[Frame]) -> list[EngineOutput]:
        """Evaluate consecutive frames at once (as ``step`` on each in turn).

        Each run of frames with unstructured pairs is one ``evaluate_frames``
        call (sets and intersections of all its frames batched); a frame without pairs
        forgets the memory, as ad-rss forgets absent objects.
        """
        inputs = [
            frame_to_agents(f, self._scope.select(f), self._params, self._ids) for f in frames
        ]
        outputs: list[EngineOutput] = []
        run: list[FrameAgents] = []
        for frame_inputs in [*inputs, None]:
            if frame_inputs is not None and len(frame_inputs.agents):
                run.append(frame_inputs)
                continue
            outputs.extend(self._check(run))
            run = []
            if frame_inputs is not None:
                self._memory = None
                record = _safe_record(self._params, sorted(frame_inputs.invalid))
                outputs.append(EngineOutput(record=record, is_safe=True))
        return outputs

    def _check(self, run: Sequence[FrameAgents]) -> list[EngineOutput]:
        """Outputs of consecutive frames with pairs, the memory carried through them."""
        if not run:
            return []
        results, self._memory = evaluate_frames(
            [FrameInputs(i.ego, i.agents, i.dynamics) for i in run], self._params, self._memory
        )
        return [self._output(i, r) for i, r in zip(run, results, strict=True)]

    def _output(self, inputs: FrameAgents, result: UnstructuredResult) -> EngineOutput:
        """The record and verdict of one checked frame."""
        pr = result.proper_response
        decisions = {
            actor: str(UnstructuredResponse(int(code)))
            for actor, code in zip(inputs.actor_ids, result.decisions.response, strict=True)
        }
        dangerous = sorted({self._ids.to_str(int(x)) for x in pr.dangerous_objects})
        record = _record(
            is_safe=pr.is_safe,
            dangerous=dangerous,
            decisions=dict(sorted(decisions.items())),
            response=pr.response,
            heading_ranges=[[json_number(b), json_number(e)] for b, e in pr.heading_ranges],
            lon=(pr.lon_min_mps2, pr.lon_max_mps2),
            lat=(pr.lat_min_mps2, pr.lat_max_mps2),
        )
        record["constellations"] = len(inputs.agents)
        record["invalid_objects"] = sorted(inputs.invalid)
        return EngineOutput(
            record=record,
            is_safe=pr.is_safe,
            culprits=tuple(dangerous),
            label="" if pr.is_safe else f"unstructured: {response_label(pr.response)}",
            margin=float("inf") if pr.is_safe else 0.0,
            detail=UnstructuredDetail(inputs.ego, result, inputs.actor_ids),
        )


def _record(  # noqa: PLR0917 - one record, built in one place
    is_safe: bool,  # noqa: FBT001
    dangerous: list[str],
    decisions: dict[str, str],
    response: UnstructuredResponse,
    heading_ranges: list[list[float | None]],
    lon: tuple[float, float],
    lat: tuple[float, float],
) -> dict[str, Any]:
    lat_range = [json_number(lat[0]), json_number(lat[1])]
    return {
        "is_safe": bool(is_safe),
        "dangerous_objects": dangerous,
        "decisions": decisions,
        "longitudinal_response": ("BrakeMin" if response == UnstructuredResponse.Brake else "None"),
        "unstructured_constellation_response": str(UnstructuredResponse(response)),
        "heading_ranges": heading_ranges,
        "acceleration_restrictions": {
            "longitudinal": [json_number(lon[0]), json_number(lon[1])],
            "lateral_left": lat_range,
            "lateral_right": list(lat_range),
        },
    }


def _safe_record(params: RssParams, invalid: list[str]) -> dict[str, Any]:
    """Record of a frame without unstructured pairs: the ego's unrestricted ranges."""
    ego = params.for_class(ObjectClass.EGO)
    record = _record(
        True,  # noqa: FBT003
        [],
        {},
        UnstructuredResponse.None_,
        [],
        (ego.brake_max_mps2, ego.accel_max_mps2),
        (ACCELERATION_LOWEST_MPS2, ego.lat_accel_max_mps2),
    )
    record["constellations"] = 0
    record["invalid_objects"] = invalid
    return record
