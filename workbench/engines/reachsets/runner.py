"""Runner of the reach-set supervisor over loader frames."""

from __future__ import annotations

import dataclasses
from typing import TYPE_CHECKING

from reachsets import evaluate_frames
from reachsets.params import ReachMethod, ReachParams
from workbench.engines.reachsets.adapter import prepare_map, reach_inputs_and_kind
from workbench.engines.reachsets.verdict import ReachVerdict, reach_verdict

if TYPE_CHECKING:
    from collections.abc import Sequence

    from loaders.maps.model import LaneMap
    from loaders.records import Frame
    from reachsets.engine import RuleState

__all__ = ["RULE_SETS", "ReachRunner"]

#: ``rules`` values: the reference's rules only, or with the lane rules of public roads.
RULE_SETS = ("reference", "public_road")


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
        rules: str = "reference",
        trajectory: str = "planned",
    ) -> None:
        """Set up the runner.

        Args:
            lane_map: The drive's map (road layout or racing track), if any.
            method: Reach-set method.
            full_geometry: Reduce every set (needed to draw them), not only the cells that
                can touch the ego; the verdict is the same either way.
            rules: ``reference`` (the reference's rules: F1/Roborace on tracks, the road
                rules on roads) or ``public_road`` (also the lane rules,
                ``reachsets.rules_lane``).
            trajectory: Which ego trajectory to rate: ``planned``, ``braking`` or ``auto``
                (see ``adapter.ego_trajectory``).
        """
        if rules not in RULE_SETS:
            msg = f"reach rules {rules!r}: expected one of {', '.join(RULE_SETS)}"
            raise ValueError(msg)
        self._map = prepare_map(lane_map)
        params = ReachParams(method=method, full_geometry=full_geometry)
        road = dataclasses.replace(params.road, lane_rules=rules == "public_road")
        self._params = dataclasses.replace(params, road=road)
        self._trajectory = trajectory
        self._state: RuleState | None = None

    def step_many(self, frames: Sequence[Frame]) -> list[ReachVerdict]:
        """Evaluate consecutive frames at once (as ``step`` on each in turn)."""
        pairs = [reach_inputs_and_kind(f, self._map, self._trajectory) for f in frames]
        results, self._state = evaluate_frames([p[0] for p in pairs], self._params, self._state)
        return [reach_verdict(r, kind) for r, (_, kind) in zip(results, pairs, strict=True)]
