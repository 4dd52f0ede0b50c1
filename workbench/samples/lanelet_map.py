"""An in-memory Lanelet2 map under construction: points, line strings, lanelets, rules.

Points are de-duplicated on millimetre-rounded coordinates, so lanelets that meet share
their endpoint nodes and topology (successors, neighbours) is recoverable from the file.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import TYPE_CHECKING

import numpy as np

from workbench.samples.quantise import quantise

if TYPE_CHECKING:
    from numpy.typing import ArrayLike, NDArray

__all__ = ["LaneletSpec", "LineSpec", "MapBuilder", "RegulatoryElement"]


@dataclass(frozen=True, slots=True)
class LineSpec:
    """A Lanelet2 line string: node ids plus ``type``/``subtype`` tags."""

    id: int
    node_ids: tuple[int, ...]
    type: str
    subtype: str | None


@dataclass(frozen=True, slots=True)
class LaneletSpec:
    """A lanelet relation.

    Attributes:
        id: Relation id.
        left: Left bound line id.
        right: Right bound line id.
        subtype: ``road``, ``crosswalk``, ``walkway`` or ``parking``.
        one_way: Whether traffic flows only along the bound order.
        speed_limit_kmh: Speed limit tag value.
        location: ``urban`` or ``nonurban``.
        regulatory_elements: Ids of regulatory elements that apply.
    """

    id: int
    left: int
    right: int
    subtype: str
    one_way: bool
    speed_limit_kmh: float
    location: str
    regulatory_elements: tuple[int, ...] = ()


@dataclass(frozen=True, slots=True)
class RegulatoryElement:
    """A regulatory element relation: ``subtype`` plus ``(role, kind, id)`` members."""

    id: int
    subtype: str
    members: tuple[tuple[str, str, int], ...]


@dataclass(slots=True)
class MapBuilder:
    """Collects the map; ``line``/``lanelet``/... return the new element's id."""

    nodes: dict[int, tuple[float, float]] = field(default_factory=dict)
    lines: dict[int, LineSpec] = field(default_factory=dict)
    lanelets: dict[int, LaneletSpec] = field(default_factory=dict)
    regulatory: dict[int, RegulatoryElement] = field(default_factory=dict)
    _by_xy: dict[tuple[int, int], int] = field(default_factory=dict)
    _next_id: int = 1

    def _new_id(self) -> int:
        new = self._next_id
        self._next_id += 1
        return new

    def node(self, x_m: float, y_m: float) -> int:
        """Id of the node at ``(x_m, y_m)``, created on first use.

        Nodes live on a millimetre grid (the precision of the OSM ``local_x``/``local_y``
        tags). The coordinates are first put on the 1e-6 m grid of
        :mod:`workbench.samples.quantise`, so last-bit noise in the geometry math can neither
        move a node nor split or merge nodes.
        """
        key = (round(quantise(x_m) * 1000), round(quantise(y_m) * 1000))
        if key not in self._by_xy:
            node_id = self._new_id()
            self._by_xy[key] = node_id
            self.nodes[node_id] = (key[0] / 1000, key[1] / 1000)
        return self._by_xy[key]

    def line(self, points_m: ArrayLike, kind: str, subtype: str | None = None) -> int:
        """Add a line string through ``(K, 2)`` points."""
        pts = np.asarray(points_m, dtype=np.float64)
        ids = tuple(self.node(float(x), float(y)) for x, y in pts)
        line_id = self._new_id()
        self.lines[line_id] = LineSpec(line_id, ids, kind, subtype)
        return line_id

    def lanelet(
        self,
        left: int,
        right: int,
        *,
        subtype: str = "road",
        one_way: bool = True,
        speed_limit_kmh: float = 50.0,
        location: str = "urban",
    ) -> int:
        """Add a lanelet between two existing line strings."""
        lanelet_id = self._new_id()
        self.lanelets[lanelet_id] = LaneletSpec(
            lanelet_id, left, right, subtype, one_way, speed_limit_kmh, location
        )
        return lanelet_id

    def _attach(self, lanelet_ids: tuple[int, ...], element_id: int) -> None:
        for lid in lanelet_ids:
            old = self.lanelets[lid]
            self.lanelets[lid] = LaneletSpec(
                old.id,
                old.left,
                old.right,
                old.subtype,
                old.one_way,
                old.speed_limit_kmh,
                old.location,
                (*old.regulatory_elements, element_id),
            )

    def right_of_way(
        self, priority: tuple[int, ...], yielding: tuple[int, ...], stop_line: int | None = None
    ) -> int:
        """Add a ``right_of_way`` element; priority lanelets get role ``right_of_way``."""
        members = [("right_of_way", "relation", lid) for lid in priority]
        members += [("yield", "relation", lid) for lid in yielding]
        if stop_line is not None:
            members.append(("ref_line", "way", stop_line))
        element_id = self._new_id()
        self.regulatory[element_id] = RegulatoryElement(element_id, "right_of_way", tuple(members))
        self._attach(priority + yielding, element_id)
        return element_id

    def traffic_light(self, controlled: tuple[int, ...], light: int, stop_line: int) -> int:
        """Add a ``traffic_light`` element referring to a light way and a stop line."""
        element_id = self._new_id()
        members = (("refers", "way", light), ("ref_line", "way", stop_line))
        self.regulatory[element_id] = RegulatoryElement(element_id, "traffic_light", members)
        self._attach(controlled, element_id)
        return element_id

    def polygon_m(self, lanelet_id: int) -> NDArray[np.float64]:
        """Outline of a lanelet (left bound, then right bound reversed), ``(K, 2)``.

        A bound stored against the lanelet's direction (shared with an oncoming lanelet)
        is turned around first, so the outline never self-intersects.
        """
        spec = self.lanelets[lanelet_id]
        left = self._points(spec.left)
        right = self._points(spec.right)
        if np.hypot(*(left[0] - right[0])) > np.hypot(*(left[-1] - right[0])):
            left = left[::-1]
        return np.vstack([left, right[::-1]])

    def _points(self, line_id: int) -> NDArray[np.float64]:
        return np.array([self.nodes[n] for n in self.lines[line_id].node_ids])
