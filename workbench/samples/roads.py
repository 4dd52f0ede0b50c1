"""Multi-lane roads along a reference line, written into a :class:`MapBuilder`.

Borders are listed from left to right of the reference direction; lane ``i`` lies between
border ``i`` and ``i + 1``::

    border 0  ======================  (road edge)
    lane 0        <-- backward
    border 1  - - - - - - - - - - -   (shared by lane 0 and lane 1)
    lane 1        --> forward
    border 2  ======================

A lanelet's right bound is always stored in its driving direction; a left bound shared
with an oncoming lanelet keeps the reference order (readers recover its orientation
geometrically, as Lanelet2 does).
"""

from __future__ import annotations

import itertools
from dataclasses import dataclass
from typing import TYPE_CHECKING

if TYPE_CHECKING:
    from collections.abc import Sequence

    from workbench.samples.geometry import Polyline
    from workbench.samples.lanelet_map import MapBuilder

__all__ = ["RoadSpec", "add_road"]


@dataclass(frozen=True, slots=True)
class RoadSpec:
    """Cross-section of a road.

    Attributes:
        border_offsets_m: Lateral offsets of the borders, left to right, ``(L + 1,)``.
        border_kinds: ``(type, subtype)`` of each border line.
        forward: Per lane, whether it runs along the reference direction.
        speed_limit_kmh: Speed limit of every lane.
        location: ``urban`` or ``nonurban``.
        lane_subtypes: Lanelet subtype per lane (default: all ``road``).
        one_way: Per lane, whether traffic is one-way (default: all one-way).
    """

    border_offsets_m: tuple[float, ...]
    border_kinds: tuple[tuple[str, str | None], ...]
    forward: tuple[bool, ...]
    speed_limit_kmh: float
    location: str
    lane_subtypes: tuple[str, ...] = ()
    one_way: tuple[bool, ...] = ()

    def centre_offset_m(self, lane: int) -> float:
        """Lateral offset of a lane's centre line."""
        return (self.border_offsets_m[lane] + self.border_offsets_m[lane + 1]) / 2


def add_road(
    builder: MapBuilder,
    reference: Polyline,
    breaks_s_m: Sequence[float],
    spec: RoadSpec,
    step_m: float = 10.0,
) -> list[list[int]]:
    """Add the lanelets of a road cut into segments at ``breaks_s_m``.

    Args:
        builder: Map under construction.
        reference: Reference line.
        breaks_s_m: Arc lengths where segments begin and end, increasing, ``(S + 1,)``.
        spec: Cross-section.
        step_m: Vertex spacing of the border lines.

    Returns:
        Lanelet ids as ``[lane][segment]``, segments in driving order of each lane.
    """
    lanes: list[list[int]] = [[] for _ in spec.forward]
    for s0, s1 in itertools.pairwise(breaks_s_m):
        n = max(1, round((s1 - s0) / step_m))
        s = [s0 + (s1 - s0) * k / n for k in range(n + 1)]
        borders = []
        for j, (offset, (kind, subtype)) in enumerate(
            zip(spec.border_offsets_m, spec.border_kinds, strict=True)
        ):
            pts = reference.pose(s, offset)
            below_backward = j < len(spec.forward) and not spec.forward[j]
            borders.append(builder.line(pts[::-1] if below_backward else pts, kind, subtype))
        for lane, forward in enumerate(spec.forward):
            upper, lower = borders[lane], borders[lane + 1]
            left, right = (upper, lower) if forward else (lower, upper)
            lanes[lane].append(
                builder.lanelet(
                    left,
                    right,
                    subtype=spec.lane_subtypes[lane] if spec.lane_subtypes else "road",
                    one_way=spec.one_way[lane] if spec.one_way else True,
                    speed_limit_kmh=spec.speed_limit_kmh,
                    location=spec.location,
                )
            )
    for lane, forward in enumerate(spec.forward):
        if not forward:
            lanes[lane].reverse()
    return lanes
