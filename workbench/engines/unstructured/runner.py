"""Runner of unstructured RSS (trajectory sets, ``rss.unstructured``) over loader frames."""

from __future__ import annotations

from typing import TYPE_CHECKING

from rss.params import ObjectClass, RssParams
from rss.physics import ACCELERATION_LOWEST_MPS2
from rss.unstructured import FrameInputs, UnstructuredResponse, evaluate_frames
from workbench.engines.ids import ActorIds
from workbench.engines.unstructured.adapter import UnstructuredScope, frame_to_agents
from workbench.engines.unstructured.verdict import UnstructuredDetail, UnstructuredVerdict

if TYPE_CHECKING:
    from collections.abc import Sequence

    from loaders.maps.model import LaneMap
    from loaders.records import Frame
    from rss.unstructured import UnstructuredMemory, UnstructuredResult
    from workbench.engines.unstructured.adapter import FrameAgents

__all__ = ["UnstructuredRunner", "response_label"]

_LABELS = {
    UnstructuredResponse.Brake: "brake",
    UnstructuredResponse.DriveAway: "drive-away",
    UnstructuredResponse.ContinueForward: "continue-forward",
    UnstructuredResponse.None_: "none",
}


def response_label(response: UnstructuredResponse) -> str:
    """Short lower-case name of a response (``brake``, ``drive-away``, ...)."""
    return _LABELS[UnstructuredResponse(response)]


class UnstructuredRunner:
    """Checks the unstructured pairs of every frame (see ``adapter`` beside this module).

    The memory (22.1b of the last safe step, drive-away state) is carried from frame to
    frame; a fresh runner starts a replay at any frame with empty memory. ``step_many``
    evaluates consecutive frames in one batch (``rss.unstructured.evaluate_frames``)
    with the same results.
    """

    name = "unstructured"

    def __init__(
        self,
        lane_map: LaneMap | None,
        params: RssParams | None = None,
        *,
        ids: ActorIds | None = None,
    ) -> None:
        """Index the lane map for the pair selection.

        Args:
            lane_map: The drive's lane map, if any.
            params: RSS dynamics and scene settings (defaults of ``rss.params``).
            ids: The drive's actor label table, shared with its other engines (a table
                of its own when ``None``).
        """
        self._params = params or RssParams()
        self._scope = UnstructuredScope(lane_map, self._params.scene.constellation_creation_mode)
        self._ids = ids if ids is not None else ActorIds()
        self._memory: UnstructuredMemory | None = None

    def step_many(self, frames: Sequence[Frame]) -> list[UnstructuredVerdict]:
        """Evaluate consecutive frames at once (as ``step`` on each in turn).

        Each run of frames with unstructured pairs is one ``evaluate_frames``
        call (sets and intersections of all its frames batched); a frame without pairs
        forgets the memory, as ad-rss forgets absent objects.
        """
        inputs = [
            frame_to_agents(f, self._scope.select(f), self._params, self._ids) for f in frames
        ]
        outputs: list[UnstructuredVerdict] = []
        run: list[FrameAgents] = []
        for frame_inputs in [*inputs, None]:
            if frame_inputs is not None and len(frame_inputs.agents):
                run.append(frame_inputs)
                continue
            outputs.extend(self._check(run))
            run = []
            if frame_inputs is not None:
                self._memory = None
                outputs.append(_safe(self._params, frame_inputs.invalid))
        return outputs

    def _check(self, run: Sequence[FrameAgents]) -> list[UnstructuredVerdict]:
        """Outputs of consecutive frames with pairs, the memory carried through them."""
        if not run:
            return []
        results, self._memory = evaluate_frames(
            [FrameInputs(i.ego, i.agents, i.dynamics) for i in run], self._params, self._memory
        )
        return [self._output(i, r) for i, r in zip(run, results, strict=True)]

    def _output(self, inputs: FrameAgents, result: UnstructuredResult) -> UnstructuredVerdict:
        """The verdict of one checked frame."""
        pr = result.proper_response
        decisions = {
            actor: UnstructuredResponse(int(code))
            for actor, code in zip(inputs.actor_ids, result.decisions.response, strict=True)
        }
        dangerous = tuple(sorted({self._ids.label(int(x)) for x in pr.dangerous_objects}))
        response = UnstructuredResponse(pr.response)
        return UnstructuredVerdict(
            is_safe=bool(pr.is_safe),
            culprits=dangerous,
            cause="" if pr.is_safe else f"unstructured: {response_label(response)}",
            margin=float("inf") if pr.is_safe else 0.0,
            response=response,
            decisions=tuple(sorted(decisions.items())),
            heading_ranges_rad=tuple((float(b), float(e)) for b, e in pr.heading_ranges),
            lon_mps2=(pr.lon_min_mps2, pr.lon_max_mps2),
            lat_mps2=(pr.lat_min_mps2, pr.lat_max_mps2),
            constellations=len(inputs.agents),
            invalid_objects=tuple(sorted(inputs.invalid)),
            detail=UnstructuredDetail(inputs.ego, result, inputs.actor_ids),
        )


def _safe(params: RssParams, invalid: Sequence[str]) -> UnstructuredVerdict:
    """Verdict of a frame without unstructured pairs: the ego's unrestricted ranges."""
    ego = params.for_class(ObjectClass.EGO)
    return UnstructuredVerdict(
        is_safe=True,
        lon_mps2=(ego.brake_max_mps2, ego.accel_max_mps2),
        lat_mps2=(ACCELERATION_LOWEST_MPS2, ego.lat_accel_max_mps2),
        invalid_objects=tuple(sorted(invalid)),
    )
