"""Runner of the reach-set supervisor over loader frames."""

from __future__ import annotations

from typing import TYPE_CHECKING

from reachsets import evaluate_frames
from reachsets.params import ReachMethod, ReachParams
from workbench.engines.reachsets.adapter import frame_to_reach_inputs, prepare_map
from workbench.engines.reachsets.verdict import ReachVerdict, reach_verdict

if TYPE_CHECKING:
    from collections.abc import Sequence

    from loaders.maps.model import LaneMap
    from loaders.records import Frame
    from reachsets.engine import RuleState

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

    def step_many(self, frames: Sequence[Frame]) -> list[ReachVerdict]:
        """Evaluate consecutive frames at once (as ``step`` on each in turn)."""
        inputs = [frame_to_reach_inputs(f, self._map) for f in frames]
        results, self._state = evaluate_frames(inputs, self._params, self._state)
        return [reach_verdict(r) for r in results]
