"""Serialise a :class:`MapBuilder` to Lanelet2 OSM XML (standard library only).

Nodes carry both geographic coordinates and the local metric ones (``local_x``,
``local_y``, ``ele`` tags). The geographic coordinates come from a simple local
equirectangular projection around :data:`ORIGIN_LATLON` on a sphere of radius
:data:`EARTH_RADIUS_M`::

    lat = lat0 + degrees(y / R)
    lon = lon0 + degrees(x / (R * cos(lat0)))
"""

from __future__ import annotations

import math
import xml.etree.ElementTree as ET
from typing import TYPE_CHECKING

if TYPE_CHECKING:
    from workbench.samples.lanelet_map import MapBuilder

__all__ = ["EARTH_RADIUS_M", "ORIGIN_LATLON", "local_to_latlon", "to_osm_bytes"]

#: Geographic origin of every sample map (local x = y = 0).
ORIGIN_LATLON = (49.0, 8.4)
#: Sphere radius of the local projection.
EARTH_RADIUS_M = 6_378_137.0


def local_to_latlon(x_m: float, y_m: float) -> tuple[float, float]:
    """Project local ENU metres to ``(lat, lon)`` degrees around :data:`ORIGIN_LATLON`."""
    lat0, lon0 = ORIGIN_LATLON
    lat = lat0 + math.degrees(y_m / EARTH_RADIUS_M)
    lon = lon0 + math.degrees(x_m / (EARTH_RADIUS_M * math.cos(math.radians(lat0))))
    return lat, lon


def _tag(parent: ET.Element, key: str, value: str) -> None:
    ET.SubElement(parent, "tag", k=key, v=value)


def _fmt(value: float) -> str:
    text = f"{value:.3f}".rstrip("0").rstrip(".")
    return "0" if text == "-0" else text


def to_osm_bytes(builder: MapBuilder) -> bytes:
    """Return the map as UTF-8 Lanelet2 OSM XML, byte-identical for identical input."""
    root = ET.Element("osm", version="0.6", generator="rss-workbench samples")
    for node_id, (x, y) in sorted(builder.nodes.items()):
        lat, lon = local_to_latlon(x, y)
        node = ET.SubElement(
            root, "node", id=str(node_id), visible="true", lat=f"{lat:.9f}", lon=f"{lon:.9f}"
        )
        _tag(node, "local_x", _fmt(x))
        _tag(node, "local_y", _fmt(y))
        _tag(node, "ele", "0")
    for line in sorted(builder.lines.values(), key=lambda item: item.id):
        way = ET.SubElement(root, "way", id=str(line.id), visible="true")
        for node_id in line.node_ids:
            ET.SubElement(way, "nd", ref=str(node_id))
        _tag(way, "type", line.type)
        if line.subtype is not None:
            _tag(way, "subtype", line.subtype)
    for lanelet in sorted(builder.lanelets.values(), key=lambda item: item.id):
        rel = ET.SubElement(root, "relation", id=str(lanelet.id), visible="true")
        ET.SubElement(rel, "member", type="way", ref=str(lanelet.left), role="left")
        ET.SubElement(rel, "member", type="way", ref=str(lanelet.right), role="right")
        for element_id in lanelet.regulatory_elements:
            ET.SubElement(
                rel, "member", type="relation", ref=str(element_id), role="regulatory_element"
            )
        _tag(rel, "type", "lanelet")
        _tag(rel, "subtype", lanelet.subtype)
        _tag(rel, "one_way", "yes" if lanelet.one_way else "no")
        _tag(rel, "speed_limit", _fmt(lanelet.speed_limit_kmh))
        _tag(rel, "location", lanelet.location)
        if lanelet.subtype in {"crosswalk", "walkway"}:
            _tag(rel, "participant:pedestrian", "yes")
    for element in sorted(builder.regulatory.values(), key=lambda item: item.id):
        rel = ET.SubElement(root, "relation", id=str(element.id), visible="true")
        for role, kind, ref in element.members:
            ET.SubElement(rel, "member", type=kind, ref=str(ref), role=role)
        _tag(rel, "type", "regulatory_element")
        _tag(rel, "subtype", element.subtype)
    ET.indent(root)
    return bytes(ET.tostring(root, encoding="utf-8", xml_declaration=True)) + b"\n"
