"""OpenDRIVE (``.xodr``) reader: reference lines, lane sections and links -> ``LaneMap``.

Lane borders are offsets of the reference line by ``laneOffset`` plus the cumulative
lane-width polynomials of each lane section, with their vertices where ad-map's OpenDRIVE
reader puts them (``opendrive_refline``: plan view and stations, ``opendrive_borders``:
per-lane refinement; Town01's borders agree with ad-map's vertex for vertex)::

        t ▲   lane  2   (left lanes, id > 0: driven against s in right-hand traffic)
          │   lane  1
      ────┼──────────────▶ s   reference line (lane 0)
          │   lane -1   (right lanes, id < 0: driven along s)
          │   lane -2

Every lane is stored in its driving direction (left lanes reversed), so ``successors``
are in driving direction and ``direction`` is always positive; the lane beyond the centre
line is the opposite neighbour. Lane-level links come from the lanes' own ``link``
elements and from the road links (roads or connecting roads of junctions); lanes of
junction roads are ``INTERSECTION`` lanes and grouped per junction. Lane types kept:
driving, biking, sidewalk, parking. Lane ids are ``"<road>_<section>_<lane>"``.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np

from loaders.errors import MapError
from loaders.maps.model import Lane, LaneKind, LaneMap
from loaders.maps.opendrive_borders import SectionLane, section_lanes
from loaders.maps.opendrive_junctions import JunctionLane, admap_reversed_along_s
from loaders.maps.opendrive_refline import ReferenceLine, float_attr
from loaders.maps.xmlsource import read_xml_root

if TYPE_CHECKING:
    import xml.etree.ElementTree as ET
    from pathlib import Path

    from numpy.typing import NDArray

__all__ = ["read_opendrive"]

#: Two junction lanes whose borders have both end points in common (each coordinate
#: closer than this, m) share that border (neighbours), as ad-map's reader links them.
_SHARED_END_M = 1e-3
_KINDS = {
    "driving": LaneKind.ROAD,
    "biking": LaneKind.BICYCLE,
    "sidewalk": LaneKind.SIDEWALK,
    "parking": LaneKind.PARKING,
}
_SPEED = {"mph": 0.44704, "km/h": 1 / 3.6, "kmh": 1 / 3.6, "m/s": 1.0, "ms": 1.0}
_Key = tuple[str, int, int]  # road, section index, lane id
_End = tuple[_Key, str]  # lane and "start" / "end" along s


def _speed(road: ET.Element) -> float:
    speed = road.find("type/speed")
    if speed is None or speed.get("max") in {None, "no limit", "undefined"}:
        return float("nan")
    return float(speed.get("max", "nan")) * _SPEED.get(speed.get("unit", "m/s"), 1.0)


class _Builder:
    def __init__(self, root: ET.Element, label: str) -> None:
        self.label = label
        self.lanes: dict[_Key, Lane] = {}
        self.links: list[tuple[_End, _End]] = []
        self.sections: dict[str, int] = {}
        self.junction_lanes: dict[str, list[str]] = {}
        #: Every lane of each junction's roads in ad-map's reading order (all lane types).
        self.junction_order: dict[str, list[JunctionLane]] = {}
        self.stations: dict[str, NDArray[np.float64]] = {}
        self.roads = root.findall("road")

    def _section(self, rid: str, road: ET.Element, ref: ReferenceLine, idx: int) -> None:
        sections = road.findall("lanes/laneSection")
        s0 = float_attr(sections[idx], "s")
        s1 = float_attr(sections[idx + 1], "s") if idx + 1 < len(sections) else ref.length_m
        junction = road.get("junction", "-1")
        speed = _speed(road)
        if junction == "-1":
            lanes = section_lanes(ref, self.stations[rid], sections[idx], s0, s1, _KINDS)
        else:  # ad-map's junction neighbours and point order need the ends of every lane
            section = sections[idx]
            every = section.findall("left/lane") + section.findall("right/lane")
            lanes = section_lanes(
                ref, self.stations[rid], section, s0, s1, {e.get("type", "") for e in every}
            )
            by_id = {lane.lane_id: lane for lane in lanes}
            self.junction_order.setdefault(junction, []).extend(
                JunctionLane(
                    (rid, idx, lid), by_id[lid].left_m[[0, -1]], by_id[lid].right_m[[0, -1]]
                )
                for lid in (int(e.get("id", "0")) for e in every)
                if lid in by_id
            )
        for lane in lanes:
            if lane.element.get("type", "") in _KINDS:
                self._add(rid, idx, lane, junction, speed)

    def _add(self, rid: str, idx: int, lane: SectionLane, junction: str, speed: float) -> None:
        lid, elem = lane.lane_id, lane.element
        kind = _KINDS[elem.get("type", "")]
        for tag, end, other_idx in (
            ("predecessor", "start", idx - 1),
            ("successor", "end", idx + 1),
        ):
            link = elem.find(f"link/{tag}")
            if link is not None and 0 <= other_idx < self.sections[rid]:
                other_end = "end" if tag == "predecessor" else "start"
                key = (rid, other_idx, int(link.get("id", "0")))
                self.links.append((((rid, idx, lid), end), (key, other_end)))
        left, right, centre = lane.left_m, lane.right_m, lane.centre_m
        if lid > 0:  # driven against s: store in driving direction
            left, right, centre = right[::-1], left[::-1], centre[::-1]
        lane_id = f"{rid}_{idx}_{lid}"
        if junction != "-1" and kind == LaneKind.ROAD:
            kind = LaneKind.INTERSECTION
            self.junction_lanes.setdefault(junction, []).append(lane_id)
        self.lanes[rid, idx, lid] = Lane(
            id=lane_id,
            left_m=left,
            right_m=right,
            centre_m=centre,
            kind=kind,
            speed_limit_mps=speed,
        )

    def _road_links(self, rid: str, road: ET.Element) -> None:
        last = self.sections[rid] - 1
        for tag, own_idx, own_end in (("predecessor", 0, "start"), ("successor", last, "end")):
            link = road.find(f"link/{tag}")
            if link is None or link.get("elementType") != "road":
                continue
            other = link.get("elementId", "")
            if other not in self.sections:
                continue
            contact = link.get("contactPoint", "start")
            other_idx = 0 if contact == "start" else self.sections[other] - 1
            section = road.findall("lanes/laneSection")[own_idx]
            for lane in section.findall("*/lane"):
                target = lane.find(f"link/{tag}")
                if target is not None:
                    key = (other, other_idx, int(target.get("id", "0")))
                    self.links.append(
                        (((rid, own_idx, int(lane.get("id", "0"))), own_end), (key, contact))
                    )

    def build(self) -> LaneMap:
        for road in self.roads:
            self.sections[road.get("id", "")] = len(road.findall("lanes/laneSection"))
        for road in self.roads:
            rid = road.get("id", "")
            ref = ReferenceLine(road)
            self.stations[rid] = ref.stations()
            for idx in range(self.sections[rid]):
                self._section(rid, road, ref, idx)
            self._road_links(rid, road)
        return self._finish()

    def _finish(self) -> LaneMap:
        succ: dict[_Key, set[_Key]] = {k: set() for k in self.lanes}
        for (ka, ea), (kb, eb) in self.links:
            if ka not in self.lanes or kb not in self.lanes:
                continue
            a_exit = ea == ("end" if ka[2] < 0 else "start")
            b_entry = eb == ("start" if kb[2] < 0 else "end")
            if a_exit and b_entry:
                succ[ka].add(kb)
            elif not a_exit and not b_entry:
                succ[kb].add(ka)
        pred: dict[_Key, set[_Key]] = {k: set() for k in self.lanes}
        for a, targets in succ.items():
            for b in targets:
                pred[b].add(a)
        turned = admap_reversed_along_s(self.junction_order.values())
        out: dict[str, Lane] = {}
        for key, lane in self.lanes.items():
            rid, idx, lid = key
            step = -1 if lid < 0 else 1  # towards the centre line
            inward = (rid, idx, lid - step) if abs(lid) > 1 else (rid, idx, -lid)
            outward = (rid, idx, lid + (-1 if lid < 0 else 1))
            left, right = inward, outward
            out[lane.id] = _replace(
                lane,
                successors=tuple(sorted(self.lanes[k].id for k in succ[key])),
                predecessors=tuple(sorted(self.lanes[k].id for k in pred[key])),
                left_neighbour=self.lanes[left].id if left in self.lanes else None,
                right_neighbour=self.lanes[right].id if right in self.lanes else None,
                left_neighbour_opposite=abs(lid) == 1 and left in self.lanes,
                admap_reversed=(lid > 0) != (key in turned),
            )
        groups = tuple(tuple(ids) for _, ids in sorted(self.junction_lanes.items()))
        for ids in groups:
            _junction_neighbours(out, ids)
        return LaneMap(lanes=out, source=self.label, format="opendrive", intersections=groups)


def _junction_neighbours(lanes: dict[str, Lane], ids: tuple[str, ...]) -> None:
    """Link lanes of different junction roads that share a border as neighbours.

    ad-map's rule (``opendrive_junctions.contact``): a border of one lane and a border of
    the other have both end points in common (the left border of one and the right border
    of the other in the same order, or two left / two right borders in opposite orders).
    Only the ends count: connecting roads of one junction side by side on coinciding
    reference lines share whole borders, but two overlapping junction lanes whose borders
    meet only at their ends are linked as well (Town01: 184_0_1 / 183_0_1, 128_0_-1 /
    131_0_1, 247_0_-1 / 253_0_-1; all 72 junction lanes then have ad-map's drivable
    neighbours).
    """
    ends = {
        (lane_id, side): getattr(lanes[lane_id], f"{side}_m")[[0, -1]]
        for lane_id in ids
        for side in ("left", "right")
    }
    for (a, side_a), ends_a in ends.items():
        if getattr(lanes[a], f"{side_a}_neighbour") is not None:
            continue
        for (b, side_b), ends_b in ends.items():
            if b.split("_")[0] == a.split("_")[0]:
                continue
            opposite = side_a == side_b
            other = ends_b[::-1] if opposite else ends_b
            if float(np.abs(ends_a - other).max()) < _SHARED_END_M:
                lanes[a] = _replace(
                    lanes[a], **{f"{side_a}_neighbour": b, f"{side_a}_neighbour_opposite": opposite}
                )
                break


def _replace(lane: Lane, **changes: object) -> Lane:
    import dataclasses  # noqa: PLC0415 - slots dataclass: replace builds a new instance

    return dataclasses.replace(lane, **changes)  # type: ignore[arg-type]


def read_opendrive(source: Path | bytes, *, name: str | None = None) -> LaneMap:
    """Read an OpenDRIVE file into a :class:`LaneMap`.

    Args:
        source: Path of the ``.xodr`` file, or its bytes.
        name: Label for the map and its errors.

    Raises:
        MapError: Unreadable XML, not an OpenDRIVE document, or unsupported geometry.
    """
    root, label = read_xml_root(source, name)
    if root.tag != "OpenDRIVE":
        raise MapError(label, f"root element is <{root.tag}>, expected <OpenDRIVE>")
    try:
        return _Builder(root, label).build()
    except MapError as err:
        raise MapError(label, err.detail) from err
    except (ValueError, IndexError) as err:
        raise MapError(label, f"malformed OpenDRIVE: {err}") from err
