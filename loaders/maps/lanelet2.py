"""Lanelet2 ``.osm`` maps read with the standard library (no lanelet2 C++ dependency).

Coordinates: when every node carries ``local_x``/``local_y`` tags those are used as map
metres directly. Otherwise latitude/longitude are projected onto the local east-north
tangent plane of the WGS-84 ellipsoid at the first node of the file (geodetic -> ECEF ->
ENU, dropping "up"). Over a map a few kilometres across this agrees with a local
transverse Mercator about the same origin to well under a millimetre per kilometre; it is
not Lanelet2's default UTM projection (which scales by 0.9996 and rotates by the grid
convergence), so absolute coordinates differ from ``lanelet2.io.load`` by a similarity
transform.

Each lanelet's borders are aligned like Lanelet2 does: the left border is reversed if it
runs against the right one, then both are reversed if the "left" border lies on the
right, so that the reference direction has the left border on its left::

      left   o--->o--->o--->o        B follows A when A's left/right end nodes are
      A      ==============>         B's left/right start nodes.
      right  o--->o--->o--->o        A's left neighbour shares A's left way as its
                                     right border (same direction) or as its left
                                     border (opposite direction).
"""

from __future__ import annotations

import math
import re
from collections import defaultdict
from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np

from loaders.errors import MapError
from loaders.maps.geometry import centre_line_m, project_to_local_enu_m
from loaders.maps.model import (
    Lane,
    LaneDirection,
    LaneKind,
    LaneMap,
    LineType,
    RightOfWay,
    TrafficLight,
)
from loaders.maps.xmlsource import read_xml_root

if TYPE_CHECKING:
    import xml.etree.ElementTree as ET
    from pathlib import Path

__all__ = ["read_lanelet2"]

_KMH_TO_MPS = 1.0 / 3.6
_MPH_TO_MPS = 0.44704
_BIDIRECTIONAL = {"no", "false", "0"}
_ONE_WAY = {"yes", "true", "1"}
_KINDS = {
    "bicycle_lane": LaneKind.BICYCLE,
    "crosswalk": LaneKind.CROSSWALK,
    "walkway": LaneKind.SIDEWALK,
    "stairs": LaneKind.SIDEWALK,
    "rail": LaneKind.RAIL,
    "parking": LaneKind.PARKING,
}
_BORDER_TYPES = {"road_border", "curbstone", "wall", "fence", "guard_rail", "keepout"}
_LINE_TYPES = {"line_thin", "line_thick"}
# Zone signs: de274.1 starts a 30 km/h zone, de274.2 a 20 km/h zone.
_ZONE_KMH = {"1": 30.0, "2": 20.0}


@dataclass(frozen=True, slots=True)
class _Border:
    """One lanelet border: the way it comes from, its node ids and vertices in lane order."""

    way: str
    reversed: bool
    nodes: tuple[str, ...]
    points_m: np.ndarray

    def flipped(self) -> _Border:
        return _Border(self.way, not self.reversed, self.nodes[::-1], self.points_m[::-1])


def read_lanelet2(source: Path | bytes, *, name: str | None = None) -> LaneMap:
    """Read a Lanelet2 OSM XML map into the common lane-graph model.

    Args:
        source: Path of the ``.osm`` file, or its bytes.
        name: Source name recorded in the map and in errors; defaults to the path, or
            ``<bytes>`` for in-memory input.

    Returns:
        The lane map (``format="lanelet2"``), one lane per lanelet relation.

    Raises:
        MapError: If the XML is malformed or a lanelet refers to a missing way or node,
            naming the file and the element id.
    """
    root, label = read_xml_root(source, name)
    return _Reader(root, label).lane_map()


def _tags(elem: ET.Element) -> dict[str, str]:
    return {t.get("k", ""): t.get("v", "") for t in elem.iter("tag")}


def _parse_speed_mps(text: str) -> float:
    match = re.fullmatch(r"\s*([0-9.]+)\s*(km/h|kmh|kph|mph|m/s|mps)?\s*", text)
    if not match:
        return math.nan
    value = float(match.group(1))
    unit = match.group(2) or "km/h"
    if unit == "mph":
        return value * _MPH_TO_MPS
    return value if unit in {"m/s", "mps"} else value * _KMH_TO_MPS


def _line_type(tags: dict[str, str]) -> LineType:
    kind, sub = tags.get("type", ""), tags.get("subtype", "")
    if kind == "virtual":
        return LineType.VIRTUAL
    if kind in _BORDER_TYPES:
        return LineType.ROAD_BORDER
    if kind in _LINE_TYPES:
        # Mixed markings (solid_dashed, dashed_solid) count as solid: conservative.
        return LineType.DASHED if sub == "dashed" else LineType.SOLID
    return LineType.UNKNOWN


class _Reader:
    """Builds a ``LaneMap`` from a parsed OSM document."""

    def __init__(self, root: ET.Element, label: str) -> None:
        self.label = label
        self.ways = {w.get("id", ""): w for w in root.iter("way")}
        self.relations = {r.get("id", ""): r for r in root.iter("relation")}
        self.origin_deg: tuple[float, float] | None = None
        self.nodes = self._project_nodes(list(root.iter("node")))

    def _project_nodes(self, elems: list[ET.Element]) -> dict[str, tuple[float, float]]:
        ids = [n.get("id", "") for n in elems]
        tags = [_tags(n) for n in elems]
        try:
            if elems and all("local_x" in t and "local_y" in t for t in tags):
                xs = np.array([float(t["local_x"]) for t in tags])
                ys = np.array([float(t["local_y"]) for t in tags])
                return dict(zip(ids, zip(xs.tolist(), ys.tolist(), strict=True), strict=True))
            lat = np.array([float(n.get("lat", "nan")) for n in elems])
            lon = np.array([float(n.get("lon", "nan")) for n in elems])
        except ValueError as err:
            raise MapError(self.label, f"node with a non-numeric coordinate: {err}") from err
        bad = ~(np.isfinite(lat) & np.isfinite(lon))
        if bad.any():
            first = int(np.argmax(bad))
            raise MapError(self.label, f"node {ids[first]} has no valid lat/lon")
        if not elems:
            return {}
        self.origin_deg = (float(lat[0]), float(lon[0]))
        xs, ys = project_to_local_enu_m(lat, lon, float(lat[0]), float(lon[0]))
        return dict(zip(ids, zip(xs.tolist(), ys.tolist(), strict=True), strict=True))

    def _border(self, lanelet_id: str, rel: ET.Element, role: str) -> _Border:
        refs = [m.get("ref", "") for m in rel.iter("member") if m.get("role") == role]
        if len(refs) != 1:
            raise MapError(self.label, f"lanelet {lanelet_id} has {len(refs)} '{role}' borders")
        way = self.ways.get(refs[0])
        if way is None:
            raise MapError(self.label, f"lanelet {lanelet_id} refers to missing way {refs[0]}")
        nodes = tuple(nd.get("ref", "") for nd in way.iter("nd"))
        missing = [n for n in nodes if n not in self.nodes]
        if missing or len(nodes) < 2:  # noqa: PLR2004 - a border needs two vertices
            detail = f"missing node {missing[0]}" if missing else "fewer than two nodes"
            raise MapError(self.label, f"way {refs[0]} of lanelet {lanelet_id}: {detail}")
        points = np.array([self.nodes[n] for n in nodes])
        return _Border(way=refs[0], reversed=False, nodes=nodes, points_m=points)

    def lane_map(self) -> LaneMap:
        lanelets = {
            rid: rel for rid, rel in self.relations.items() if _tags(rel).get("type") == "lanelet"
        }
        borders = {rid: _aligned(*self._borders(rid, rel)) for rid, rel in lanelets.items()}
        tags = {rid: _tags(rel) for rid, rel in lanelets.items()}
        kinds = {
            rid: _KINDS.get(t.get("subtype", "road"), LaneKind.ROAD) for rid, t in tags.items()
        }
        direction = {rid: _direction(tags[rid].get("one_way"), kinds[rid]) for rid in lanelets}
        regs = self._regulatory_refs(lanelets)
        speed = self._speed_limits(tags, regs)
        succ, pred = _connections(borders, direction)
        neigh = _neighbours(borders)
        lanes: dict[str, Lane] = {}
        for rid, (left, right) in borders.items():
            (ln, lopp), (rn, ropp) = neigh[rid]
            lanes[rid] = Lane(
                id=rid,
                left_m=left.points_m,
                right_m=right.points_m,
                centre_m=centre_line_m(left.points_m, right.points_m),
                direction=direction[rid],
                kind=kinds[rid],
                speed_limit_mps=speed[rid],
                predecessors=tuple(sorted(pred[rid])),
                successors=tuple(sorted(succ[rid])),
                left_neighbour=ln,
                right_neighbour=rn,
                left_line=_line_type(_tags(self.ways[left.way])),
                right_line=_line_type(_tags(self.ways[right.way])),
                left_neighbour_opposite=lopp,
                right_neighbour_opposite=ropp,
            )
        rows, lights = self._rules(set(lanelets), regs)
        return LaneMap(
            lanes=lanes,
            source=self.label,
            format="lanelet2",
            right_of_way=rows,
            traffic_lights=lights,
            origin_deg=self.origin_deg,
        )

    def _borders(self, rid: str, rel: ET.Element) -> tuple[_Border, _Border]:
        return self._border(rid, rel, "left"), self._border(rid, rel, "right")

    def _regulatory_refs(self, lanelets: dict[str, ET.Element]) -> dict[str, list[str]]:
        """Regulatory element id -> ids of the lanelets that reference it."""
        refs: dict[str, list[str]] = defaultdict(list)
        for rid, rel in lanelets.items():
            for m in rel.iter("member"):
                if m.get("role") == "regulatory_element" and m.get("ref", "") in self.relations:
                    refs[m.get("ref", "")].append(rid)
        return refs

    def _speed_limits(
        self, tags: dict[str, dict[str, str]], regs: dict[str, list[str]]
    ) -> dict[str, float]:
        speed = {rid: _parse_speed_mps(t.get("speed_limit", "")) for rid, t in tags.items()}
        for reg_id, users in regs.items():
            reg = self.relations[reg_id]
            if _tags(reg).get("subtype") != "speed_limit":
                continue
            limit = self._sign_speed_mps(reg)
            for rid in users:
                speed[rid] = limit if math.isnan(speed[rid]) else min(speed[rid], limit)
        return speed

    def _sign_speed_mps(self, reg: ET.Element) -> float:
        """Speed of a speed-limit element: its own tag, else the referred sign's subtype."""
        own = _parse_speed_mps(_tags(reg).get("speed_limit", ""))
        if not math.isnan(own):
            return own
        for m in reg.iter("member"):
            way = self.ways.get(m.get("ref", "")) if m.get("role") == "refers" else None
            sub = _tags(way).get("subtype", "") if way is not None else ""
            match = re.fullmatch(r"de274[._-]?(\d+)", sub)
            if match:
                digits = match.group(1)
                kmh = _ZONE_KMH.get(digits, float(digits))
                return kmh * _KMH_TO_MPS
        return math.nan

    def _rules(
        self, known: set[str], regs: dict[str, list[str]]
    ) -> tuple[tuple[RightOfWay, ...], tuple[TrafficLight, ...]]:
        rows: list[RightOfWay] = []
        lights: list[TrafficLight] = []
        for reg_id, rel in self.relations.items():
            subtype = _tags(rel).get("subtype")
            if _tags(rel).get("type") != "regulatory_element":
                continue
            if subtype == "right_of_way":
                members = [(m.get("role"), m.get("ref", "")) for m in rel.iter("member")]
                prio = tuple(r for role, r in members if role == "right_of_way" and r in known)
                yld = tuple(r for role, r in members if role == "yield" and r in known)
                rows.append(RightOfWay(id=reg_id, priority_lanes=prio, yield_lanes=yld))
            elif subtype == "traffic_light":
                lanes = tuple(sorted(regs.get(reg_id, [])))
                lights.append(TrafficLight(id=reg_id, controlled_lanes=lanes))
        return tuple(rows), tuple(lights)


def _direction(one_way: str | None, kind: LaneKind) -> LaneDirection:
    if one_way in _BIDIRECTIONAL:
        return LaneDirection.BIDIRECTIONAL
    if one_way in _ONE_WAY:
        return LaneDirection.POSITIVE
    pedestrian = kind in {LaneKind.CROSSWALK, LaneKind.SIDEWALK}
    return LaneDirection.BIDIRECTIONAL if pedestrian else LaneDirection.POSITIVE


def _aligned(left: _Border, right: _Border) -> tuple[_Border, _Border]:
    """Orient both borders along the lanelet so that the left border lies on the left."""
    lp, rp = left.points_m, right.points_m
    same = np.hypot(*(lp[0] - rp[0])) + np.hypot(*(lp[-1] - rp[-1]))
    crossed = np.hypot(*(lp[0] - rp[-1])) + np.hypot(*(lp[-1] - rp[0]))
    if crossed < same:
        left = left.flipped()
    ring = np.concatenate((right.points_m, left.points_m[::-1]))
    area2 = float(
        np.sum(ring[:, 0] * np.roll(ring[:, 1], -1) - np.roll(ring[:, 0], -1) * ring[:, 1])
    )
    if area2 < 0.0:
        left, right = left.flipped(), right.flipped()
    return left, right


def _connections(
    borders: dict[str, tuple[_Border, _Border]], direction: dict[str, LaneDirection]
) -> tuple[dict[str, set[str]], dict[str, set[str]]]:
    """Successors (attached at the reference end) and predecessors (at the reference start).

    A traversal of a lanelet runs from a pair of (left, right) start nodes to a pair of end
    nodes; bidirectional lanelets are traversed both ways. Lanelet B is attached after A
    when a traversal of A ends at the node pair where a traversal of B starts.
    """
    starts: dict[tuple[str, str], list[tuple[str, bool]]] = defaultdict(list)
    traversals: list[tuple[str, bool, tuple[str, str]]] = []
    for rid, (left, right) in borders.items():
        starts[(left.nodes[0], right.nodes[0])].append((rid, True))
        traversals.append((rid, True, (left.nodes[-1], right.nodes[-1])))
        if direction[rid] is LaneDirection.BIDIRECTIONAL:
            starts[(right.nodes[-1], left.nodes[-1])].append((rid, False))
            traversals.append((rid, False, (right.nodes[0], left.nodes[0])))
    succ: dict[str, set[str]] = {rid: set() for rid in borders}
    pred: dict[str, set[str]] = {rid: set() for rid in borders}
    for rid, forward, end in traversals:
        for other, other_forward in starts.get(end, []):
            if other == rid:
                continue
            (succ if forward else pred)[rid].add(other)
            (pred if other_forward else succ)[other].add(rid)
    return succ, pred


_Side = tuple[str | None, bool]


def _neighbours(borders: dict[str, tuple[_Border, _Border]]) -> dict[str, tuple[_Side, _Side]]:
    """Left and right neighbour of each lanelet, with an "opposite direction" flag."""
    users: dict[str, list[tuple[str, str, bool]]] = defaultdict(list)
    for rid, (left, right) in borders.items():
        users[left.way].append((rid, "left", left.reversed))
        users[right.way].append((rid, "right", right.reversed))

    def find(rid: str, border: _Border, side: str) -> _Side:
        other_side = "right" if side == "left" else "left"
        same = opposite = None
        for other, other_role, other_rev in sorted(users[border.way]):
            if other == rid:
                continue
            if other_role == other_side and other_rev == border.reversed and same is None:
                same = other
            elif other_role == side and other_rev != border.reversed and opposite is None:
                opposite = other
        return (same, False) if same is not None else (opposite, opposite is not None)

    return {
        rid: (find(rid, lb, "left"), find(rid, rb, "right")) for rid, (lb, rb) in borders.items()
    }
