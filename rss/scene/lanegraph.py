"""The pure lane-graph input of scene creation (plain arrays) and a route step.

A :class:`LaneGraph` is what scene creation needs from a lane map, as plain arrays
(``rss`` never imports the map loaders). Borders are polylines in the map frame (ENU, m)
ordered along each lane's *reference direction*; ``direction`` says which way traffic
flows relative to that order::

      left border   o----o----o----o---->   reference direction (point order)
      centre line   o----o----o----o          lat param 0 = left border,
      right border  o----o----o----o          lat param 1 = right border

``rss.scene.prepared.prepare`` derives the geometry scene creation works on, once per map.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING

if TYPE_CHECKING:
    from rss.arrays import BoolArray, FloatArray, IntArray
    from rss.model import LaneDrivingDirection

__all__ = ["LaneGraph", "Step"]

#: One lane of a route: ``(lane index, forward)``, ``forward`` when the route runs along
#: the lane's point order (or, in a road area, along the road-area direction).
Step = tuple[int, bool]


@dataclass(frozen=True)
class LaneGraph:
    """Lanes of a map as arrays (``L`` lanes, indices into these arrays everywhere).

    Attributes:
        ids: Lane ids from the source map, ``(L,)``.
        left_m: Left borders, each ``(K, 2)``.
        right_m: Right borders, each ``(M, 2)``.
        centre_m: Centre lines, each ``(C, 2)``.
        direction: ``(L,)`` traffic direction relative to the point order
            (:class:`rss.model.LaneDrivingDirection` codes: Positive = along it).
        speed_limit_mps: ``(L,)`` speed limits, NaN where unknown.
        successors: Per lane, the lanes its end leads into.
        predecessors: Per lane, the lanes leading into its start.
        left_neighbour: ``(L,)`` adjacent lane on the left, -1 for none.
        right_neighbour: ``(L,)`` adjacent lane on the right, -1 for none.
        left_opposite: ``(L,)`` the left neighbour's point order is reversed.
        right_opposite: ``(L,)`` the right neighbour's point order is reversed.
        is_intersection: ``(L,)`` lane lies inside an intersection.
        priority: ``(L,)`` right of way: +1 has way, 0 unregulated, -1 must yield.
        traffic_light: ``(L,)`` index into ``light_ids`` of the controlling light, -1 none.
        light_ids: Traffic-light ids.
        admap_reversed: ``(L,)`` ad-map holds the lane's points in the opposite order
            (``None``: nowhere); its nearest-point tie rule and width stations follow it.
    """

    ids: tuple[str, ...]
    left_m: tuple[FloatArray, ...]
    right_m: tuple[FloatArray, ...]
    centre_m: tuple[FloatArray, ...]
    direction: IntArray
    speed_limit_mps: FloatArray
    successors: tuple[tuple[int, ...], ...]
    predecessors: tuple[tuple[int, ...], ...]
    left_neighbour: IntArray
    right_neighbour: IntArray
    left_opposite: BoolArray
    right_opposite: BoolArray
    is_intersection: BoolArray
    priority: IntArray
    traffic_light: IntArray
    light_ids: tuple[str, ...] = ()
    admap_reversed: BoolArray | None = None

    def __len__(self) -> int:
        """Number of lanes."""
        return len(self.ids)

    def lane_direction(self, lane: int) -> LaneDrivingDirection:
        """Traffic direction of ``lane`` relative to its point order."""
        from rss.model import LaneDrivingDirection  # noqa: PLC0415 - cheap, avoids a cycle

        return LaneDrivingDirection(int(self.direction[lane]))
