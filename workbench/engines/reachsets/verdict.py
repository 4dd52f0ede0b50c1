"""The reach-set verdict of one frame: typed, frozen, read by the record, the layout and sinks."""

from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING

if TYPE_CHECKING:
    from reachsets.engine import ReachResult

__all__ = ["ReachVerdict", "reach_verdict"]


@dataclass(frozen=True, slots=True)
class ReachVerdict:
    """The reach-set supervisor on one frame.

    Attributes:
        is_safe: No object's rule-conform reachable set hits the ego's occupancy.
        culprits: Ids of the objects whose set hits the ego, in collision order.
        cause: ``"reach-set collision"`` when unsafe, else ``""``.
        margin: Earliest collision offset into the plan [s] (``inf`` when safe).
        result: The engine's result (sets, occupancy, patches, collisions).
        trajectory: The ego trajectory rated: ``"emergency"``, ``"planned"``,
            ``"constant_speed"`` (no plan: speed and heading held) or
            ``"braking_from_state"`` (``reachsets.braking``).
    """

    is_safe: bool
    culprits: tuple[str, ...]
    cause: str
    margin: float
    result: ReachResult
    trajectory: str = "planned"

    def object_margin(self, object_id: str) -> float:
        """Earliest collision offset [s] of one object's set (``inf``: it hits nothing)."""
        return min(
            (c.t_offset_s for c in self.result.collisions if c.object_id == object_id),
            default=float("inf"),
        )


def reach_verdict(result: ReachResult, trajectory: str = "planned") -> ReachVerdict:
    """The verdict of one frame's result (``trajectory``: the kind of ego trajectory rated)."""
    return ReachVerdict(
        is_safe=result.is_safe,
        culprits=tuple(c.object_id for c in result.collisions),
        cause="" if result.is_safe else "reach-set collision",
        margin=min((c.t_offset_s for c in result.collisions), default=float("inf")),
        result=result,
        trajectory=trajectory,
    )
