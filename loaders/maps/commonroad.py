"""CommonRoad lanelet networks (XML 2018b and 2020a) in the common lane-graph model.

What is read from each ``<lanelet>``: ``leftBound``/``rightBound`` points (with their
``lineMarking``), ``predecessor``/``successor`` refs, ``adjacentLeft``/``adjacentRight``
with ``drivingDir`` (``opposite`` sets the ``*_neighbour_opposite`` flag), ``laneletType``,
``userBidirectional``, the 2018b ``speedLimit`` element and, in 2020a, the speed limit of
referenced traffic signs (``274`` in Germany, ``R2-1`` in the USA; ``additionalValue`` in
m/s). Traffic lights become ``TrafficLight`` records controlling the lanelets that refer to
them. Each ``<intersection>`` becomes one group of the lanelets inside it (the
``successorsRight``/``Straight``/``Left`` of its incomings); those lanelets get
``LaneKind.INTERSECTION`` unless their type says crosswalk, sidewalk or bicycle lane.
CommonRoad lanelets are one-way in their point order (``LaneDirection.POSITIVE``) unless
marked ``userBidirectional``. References to lanelets that are not in the file are dropped.
"""

from __future__ import annotations

import math
from typing import TYPE_CHECKING

import numpy as np

from loaders.errors import MapError
from loaders.maps.geometry import centre_line_m
from loaders.maps.model import Lane, LaneDirection, LaneKind, LaneMap, LineType, TrafficLight
from loaders.maps.xmlsource import read_xml_root

if TYPE_CHECKING:
    import xml.etree.ElementTree as ET
    from collections.abc import Iterable
    from pathlib import Path

    from numpy.typing import NDArray

__all__ = [
    "NETWORK_TAGS",
    "id_sort_key",
    "lane_map_from_elements",
    "parse_float",
    "read_commonroad_map",
]

#: Top-level scenario elements that make up the lanelet network.
NETWORK_TAGS = frozenset({"lanelet", "trafficSign", "trafficLight", "intersection"})
_SPEED_SIGNS = frozenset({"274", "R2-1"})
_LINES = {
    "solid": LineType.SOLID,
    "broad_solid": LineType.SOLID,
    "dashed": LineType.DASHED,
    "broad_dashed": LineType.DASHED,
    "no_marking": LineType.VIRTUAL,
    "curb": LineType.ROAD_BORDER,
    "lowered_curb": LineType.ROAD_BORDER,
    "road_boundary": LineType.ROAD_BORDER,
}
_KINDS = {
    "crosswalk": LaneKind.CROSSWALK,
    "sidewalk": LaneKind.SIDEWALK,
    "bicycleLane": LaneKind.BICYCLE,
    "parking": LaneKind.PARKING,
    "intersection": LaneKind.INTERSECTION,
}
_INNER_ROLES = ("successorsRight", "successorsStraight", "successorsLeft")


def read_commonroad_map(source: Path | bytes, *, name: str | None = None) -> LaneMap:
    """Read the lanelet network of a CommonRoad scenario file.

    Args:
        source: Path of the scenario ``.xml``, or its bytes.
        name: Source name recorded in the map and in errors; defaults to the path, or
            ``<bytes>`` for in-memory input.

    Returns:
        The lane map (``format="commonroad"``), one lane per lanelet.

    Raises:
        MapError: If the XML is malformed or a lanelet border is unusable, naming the file
            and the lanelet id.
    """
    root, label = read_xml_root(source, name)
    return lane_map_from_elements((e for e in root if e.tag in NETWORK_TAGS), label)


def lane_map_from_elements(elements: Iterable[ET.Element], source: str) -> LaneMap:
    """Build a lane map from the top-level network elements of a scenario.

    Args:
        elements: ``<lanelet>``, ``<trafficSign>``, ``<trafficLight>`` and ``<intersection>``
            elements (others are ignored).
        source: Source name recorded in the map and in errors.

    Returns:
        The lane map (``format="commonroad"``).

    Raises:
        MapError: If a lanelet border is missing, has fewer than two points or holds a
            non-numeric coordinate.
    """
    by_tag: dict[str, list[ET.Element]] = {tag: [] for tag in NETWORK_TAGS}
    for elem in elements:
        by_tag.setdefault(elem.tag, []).append(elem)
    lanelets = {e.get("id", ""): e for e in by_tag["lanelet"]}
    sign_speed = _sign_speeds_mps(by_tag["trafficSign"])
    groups = _intersections(by_tag["intersection"], lanelets.keys())
    inner = {lid for group in groups for lid in group}
    lanes = {
        lid: _lane(lid, elem, source, sign_speed, set(lanelets), inside=lid in inner)
        for lid, elem in lanelets.items()
    }
    lights = []
    for light in by_tag["trafficLight"]:
        light_id = light.get("id", "")
        users = sorted(
            lid
            for lid, elem in lanelets.items()
            if any(r.get("ref") == light_id for r in elem.iter("trafficLightRef"))
        )
        lights.append(TrafficLight(id=light_id, controlled_lanes=tuple(users)))
    return LaneMap(
        lanes=lanes,
        source=source,
        format="commonroad",
        traffic_lights=tuple(lights),
        intersections=groups,
    )


def _sign_speeds_mps(signs: list[ET.Element]) -> dict[str, float]:
    """Traffic sign id -> the lowest speed limit it shows (m/s)."""
    out: dict[str, float] = {}
    for sign in signs:
        for element in sign.iter("trafficSignElement"):
            if (element.findtext("trafficSignID") or "").strip() not in _SPEED_SIGNS:
                continue
            value = parse_float(element.findtext("additionalValue"))
            if math.isfinite(value):
                sid = sign.get("id", "")
                out[sid] = min(out.get(sid, math.inf), value)
    return out


def _intersections(elems: list[ET.Element], known: Iterable[str]) -> tuple[tuple[str, ...], ...]:
    ids = set(known)
    groups = []
    for inter in elems:
        inner = {
            ref.get("ref", "")
            for role in _INNER_ROLES
            for ref in inter.iter(role)
            if ref.get("ref", "") in ids
        }
        groups.append(tuple(sorted(inner, key=id_sort_key)))
    return tuple(groups)


def _lane(
    lid: str,
    elem: ET.Element,
    source: str,
    sign_speed: dict[str, float],
    known: set[str],
    *,
    inside: bool,
) -> Lane:
    left, left_line = _bound(lid, elem, "leftBound", source)
    right, right_line = _bound(lid, elem, "rightBound", source)
    speeds = [parse_float(elem.findtext("speedLimit"))]
    speeds += [sign_speed.get(r.get("ref", ""), math.nan) for r in elem.iter("trafficSignRef")]
    finite = [s for s in speeds if math.isfinite(s)]
    types = [(t.text or "").strip() for t in elem.iter("laneletType")]
    kind = next((_KINDS[t] for t in types if t in _KINDS), LaneKind.ROAD)
    if inside and kind is LaneKind.ROAD:
        kind = LaneKind.INTERSECTION
    adj = {side: elem.find(side) for side in ("adjacentLeft", "adjacentRight")}
    neighbour = {
        side: (a.get("ref") if a is not None and a.get("ref") in known else None)
        for side, a in adj.items()
    }
    opposite = {
        side: neighbour[side] is not None and a is not None and a.get("drivingDir") == "opposite"
        for side, a in adj.items()
    }
    bidirectional = elem.find("userBidirectional") is not None
    return Lane(
        id=lid,
        left_m=left,
        right_m=right,
        centre_m=centre_line_m(left, right),
        direction=LaneDirection.BIDIRECTIONAL if bidirectional else LaneDirection.POSITIVE,
        kind=kind,
        speed_limit_mps=min(finite) if finite else math.nan,
        predecessors=_refs(elem, "predecessor", known),
        successors=_refs(elem, "successor", known),
        left_neighbour=neighbour["adjacentLeft"],
        right_neighbour=neighbour["adjacentRight"],
        left_line=left_line,
        right_line=right_line,
        left_neighbour_opposite=opposite["adjacentLeft"],
        right_neighbour_opposite=opposite["adjacentRight"],
    )


def _bound(
    lid: str, elem: ET.Element, tag: str, source: str
) -> tuple[NDArray[np.float64], LineType]:
    bound = elem.find(tag)
    if bound is None:
        raise MapError(source, f"lanelet {lid} has no {tag}")
    points = [
        (parse_float(p.findtext("x")), parse_float(p.findtext("y"))) for p in bound.iter("point")
    ]
    arr = np.array(points, dtype=np.float64).reshape(-1, 2)
    if len(arr) < 2:  # noqa: PLR2004 - a border needs two vertices
        raise MapError(source, f"lanelet {lid} {tag} has {len(arr)} points")
    if not np.isfinite(arr).all():
        bad = int(np.argmax(~np.isfinite(arr).all(axis=1)))
        raise MapError(source, f"lanelet {lid} {tag} point {bad} is not numeric", value=points[bad])
    marking = (bound.findtext("lineMarking") or "").strip()
    return arr, _LINES.get(marking, LineType.UNKNOWN)


def _refs(elem: ET.Element, tag: str, known: set[str]) -> tuple[str, ...]:
    return tuple(r.get("ref", "") for r in elem.iter(tag) if r.get("ref", "") in known)


def parse_float(text: str | None) -> float:
    """Number in a CommonRoad text node; NaN when absent or not a number."""
    try:
        return float(text) if text is not None else math.nan
    except ValueError:
        return math.nan


def id_sort_key(value: str) -> tuple[int, str]:
    """Sort key putting numeric ids in numeric order (CommonRoad ids are integers)."""
    return (int(value), "") if value.isdigit() else (0, value)
