"""``--rss-profile auto`` (the review commands' default): a parameter profile from the road.

RSS parameters are meant to be set for a context (docs/rss.md, "Parameter profiles"):

* ``highway`` on fast roads: the largest speed limit of the map's drivable lanes is at least
  :data:`FAST_ROAD_MPS` (70 km/h: roads outside built-up areas and motorways), or the map
  gives no speed limit and has neither junctions, sidewalks, crosswalks nor parking lanes
  (a bare multi-lane carriageway such as the NGSIM US-101 maps);
* ``urban`` on every other map (urban streets, junctions, sidewalks, parking): the review
  profile calibrated on town driving;
* ``adrss-5.0`` for drives without a map (structured RSS then builds no constellation).
"""

from __future__ import annotations

import math
from typing import TYPE_CHECKING

from loaders.maps.model import LaneKind
from rss.profiles import LIBRARY_PROFILE, REVIEW_PROFILE, URBAN_PROFILE

if TYPE_CHECKING:
    from loaders.maps.model import LaneMap

__all__ = ["AUTO", "FAST_ROAD_MPS", "auto_profile"]

#: ``--rss-profile`` value choosing by the road.
AUTO = "auto"
#: Speed limit from which a road counts as fast [m/s] (70 km/h).
FAST_ROAD_MPS = 70.0 / 3.6
_URBAN_KINDS = frozenset({LaneKind.SIDEWALK, LaneKind.CROSSWALK, LaneKind.PARKING})


def auto_profile(lane_map: LaneMap | None) -> str:
    """The profile ``auto`` picks for a drive's lane map (see the module docstring)."""
    if lane_map is None:
        return LIBRARY_PROFILE
    lanes = list(lane_map.lanes.values())
    limits = [lane.speed_limit_mps for lane in lanes if not math.isnan(lane.speed_limit_mps)]
    if limits:
        return REVIEW_PROFILE if max(limits) >= FAST_ROAD_MPS - 1e-9 else URBAN_PROFILE
    urban = bool(lane_map.intersections) or any(lane.kind in _URBAN_KINDS for lane in lanes)
    if not lanes:
        return LIBRARY_PROFILE
    return URBAN_PROFILE if urban else REVIEW_PROFILE
