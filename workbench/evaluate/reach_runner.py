"""Runner of the reach-set supervisor over loader frames."""

from __future__ import annotations

from typing import TYPE_CHECKING

from reachsets import evaluate_frames
from reachsets.params import ReachMethod, ReachParams
from workbench.evaluate.pipeline import EngineOutput
from workbench.reach_adapter import frame_to_reach_inputs, prepare_map

if TYPE_CHECKING:
    from collections.abc import Sequence

    from loaders.maps.model import LaneMap
    from loaders.records import Frame
    from reachsets.engine import ReachResult, RuleState

__all__ = ["ReachRunner"]


class ReachRunner:
    """Evaluates every frame's plan against the rule-conform reachable sets of the others.

    The rule memory (past-time LTL state) is carried from frame to frame; a fresh runner
    starts a replay at any frame with empty memory. ``step_many`` evaluates consecutive
    frames in one batch (``reachsets.evaluate_frames``) with the same results.
    """

    name = "reachsets"

    def __init__(
        self,
        lane_map: LaneMap | None,
        *,
        method: ReachMethod = ReachMethod.TURN,
        full_geometry: bool = False,
    ) -> None:
        """Set up the runner.

        Args:
            lane_map: The drive's map (road layout or racing track), if any.
            method: Reach-set method.
            full_geometry: Reduce every set (needed to draw them), not only the cells that
                can touch the ego; the verdict is the same either way.
        """
        self._map = prepare_map(lane_map)
        self._params = ReachParams(method=method, full_geometry=full_geometry)
        self._state: RuleState | None = None

    def step(self, frame: Frame) -> EngineOutput:
        """Evaluate one frame."""
        return self.step_many([frame])[0]

    def step_many(self, frames: Sequence[Frame]) -> list[EngineOutput]:
        """Evaluate consecutive frames at once (as ``step`` on each in turn)."""
        inputs = [frame_to_reach_inputs(f, self._map) for f in frames]
        results, self._state = evaluate_frames(inputs, self._params, self._state)
        return [_output(r) for r in results]


def _output(result: ReachResult) -> EngineOutput:
    collisions = [
        {"object_id": c.object_id, "t_offset_s": round(c.t_offset_s, 6)} for c in result.collisions
    ]
    record = {
        "is_safe": result.is_safe,
        "collisions": collisions,
        "patches": sorted({f"{p.rule}:{p.object_id}" for p in result.patches}),
        "skipped_objects": list(result.skipped_ids),
    }
    first = min((c.t_offset_s for c in result.collisions), default=float("inf"))
    return EngineOutput(
        record=record,
        is_safe=result.is_safe,
        culprits=tuple(c.object_id for c in result.collisions),
        label="" if result.is_safe else "reach-set collision",
        margin=first,
        detail=result,
    )
