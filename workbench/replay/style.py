"""Colours, radii and class labels of the replay scene: one place to tune the look.

Colours are packed ``0xRRGGBBAA``. Pure data, no Rerun import.
"""

from __future__ import annotations

from loaders.records import ObjectClass

__all__ = [
    "ACTOR_LINE_RADIUS_M",
    "BORDER_COLORS",
    "BORDER_RADIUS_M",
    "BOUNDARY_COLOR",
    "BOUNDARY_RADIUS_M",
    "CENTRE_COLOR",
    "CENTRE_RADIUS_M",
    "CLASS_COLORS",
    "EGO_COLOR",
    "EGO_TRAIL_RADIUS_M",
    "INCIDENT_DIM_COLOR",
    "INCIDENT_OBJECT_COLOR",
    "PLAN_COLOR",
    "PLAN_RADIUS_M",
    "VIEW_HALF_SIZE_M",
]

#: Box colour per object class (the annotation context on ``world``).
CLASS_COLORS: dict[ObjectClass, int] = {
    ObjectClass.UNKNOWN: 0x9E9E9EFF,
    ObjectClass.CAR: 0x42A5F5FF,
    ObjectClass.TRUCK: 0xFFA726FF,
    ObjectClass.BUS: 0xFFEE58FF,
    ObjectClass.MOTORCYCLE: 0xAB47BCFF,
    ObjectClass.BICYCLE: 0x66BB6AFF,
    ObjectClass.PEDESTRIAN: 0xEF5350FF,
}

#: The ego stands out from every class colour.
EGO_COLOR = 0x00E676FF
#: The objects of the incident under review stand out (red) ...
INCIDENT_OBJECT_COLOR = 0xFF1744FF
#: ... and the other actors are dimmed (translucent grey, no labels) in its view.
INCIDENT_DIM_COLOR = 0x9E9E9E59
#: The plan is drawn in magenta, the conventional "intent" colour.
PLAN_COLOR = 0xFF40FFFF

#: Lane border colour per ``LineType`` value.
BORDER_COLORS: dict[str, int] = {
    "solid": 0xEEEEEEFF,
    "dashed": 0x9E9E9EFF,
    "road_border": 0xFFD54FFF,
    "virtual": 0x424242FF,
    "unknown": 0xBDBDBDFF,
}
#: Centre lines are dim: orientation help, not geometry to read.
CENTRE_COLOR = 0x37474FFF
BOUNDARY_COLOR = 0xFFD54FFF

BORDER_RADIUS_M = 0.12
CENTRE_RADIUS_M = 0.05
BOUNDARY_RADIUS_M = 0.2
PLAN_RADIUS_M = 0.25
EGO_TRAIL_RADIUS_M = 0.3
ACTOR_LINE_RADIUS_M = 0.06

#: Half the side [m] of the square around the ego that the live viewer's camera frames: a
#: tracking camera fits the tracked entity's bounds, and the ego's box alone (4 m) made the
#: web viewer's camera sit a few metres from it.
VIEW_HALF_SIZE_M = 30.0
