"""Reading conformance cases (``conformance/rss-cases-format.md``) into constellations.

Case road frame -> ad-rss lane frame (the one documented boundary)::

    case frame                          ad-rss lane frame
    y ▲ (0 = RIGHT border, +left)       lane_segments[0] = LEFTMOST lane
      │  lanes listed right -> left     u = W - y grows to the RIGHT
      └──────▶ s (ego direction)        speed_lat = -v_lat (positive = to the right)

``s`` and ``y`` are the centre of the object's footprint. Intersection cases give each
vehicle a road area approach -> intersection lane -> exit, placed by the distance of its
front bumper to the intersection entry.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any

from rss.errors import RssCaseError, RssError
from rss.model import (
    Constellation,
    ConstellationType,
    LaneDrivingDirection,
    LaneObject,
    LaneSegment,
    ObjectType,
    OccupiedRegion,
    RoadSegment,
    RoadSegmentType,
    SpeedInterval,
)
from rss.params import DEFAULT_EGO_DYNAMICS, DEFAULT_PEDESTRIAN_DYNAMICS, DEFAULT_VEHICLE_DYNAMICS

if TYPE_CHECKING:
    from collections.abc import Mapping

    from rss.dynamics import RssDynamics

__all__ = [
    "EGO_ID",
    "OTHER_ID",
    "CaseDefaults",
    "ParsedCase",
    "case_number",
    "other_dynamics_for",
    "parse_case",
    "parse_defaults",
]

#: Object ids used for the two objects of every case.
EGO_ID = 0
OTHER_ID = 1
_PEDESTRIANS = {ObjectType.Pedestrian, ObjectType.ArtificialPedestrian}
_INTERSECTION_DEFAULTS = {"exit": 50.0, "lane_width": 3.5}


@dataclass(frozen=True)
class CaseDefaults:
    """Dynamics of a case file after its ``defaults`` overrides."""

    ego: RssDynamics = DEFAULT_EGO_DYNAMICS
    vehicle: RssDynamics = DEFAULT_VEHICLE_DYNAMICS
    pedestrian: RssDynamics = DEFAULT_PEDESTRIAN_DYNAMICS


@dataclass(frozen=True)
class ParsedCase:
    """One case (or one sequence step) ready to evaluate.

    Attributes:
        case_id: Id (``"<sequence>#<k>"`` for steps).
        kind: ``structured``, ``unstructured``, ``formula``.
        default_ego: Default ego dynamics of the frame.
        constellation: The pair (structured only).
        raw: The case's JSON object.
        expected: Dotted-path expectations.
        sequence_id: Id of the enclosing sequence, if any.
        step: Step index in the sequence, if any.
    """

    case_id: str
    kind: str
    default_ego: RssDynamics
    constellation: Constellation | None
    raw: Mapping[str, Any]
    expected: Mapping[str, Any] = field(default_factory=dict)
    sequence_id: str | None = None
    step: int | None = None


def parse_defaults(document: Mapping[str, Any]) -> CaseDefaults:
    """Built-in defaults merged with the file's ``defaults`` section.

    Raises:
        RssParameterError: An invalid override.
    """
    section = document.get("defaults", {}) or {}
    return CaseDefaults(
        ego=DEFAULT_EGO_DYNAMICS.with_overrides(
            section.get("ego_dynamics", {}), "defaults.ego_dynamics."
        ),
        vehicle=DEFAULT_VEHICLE_DYNAMICS.with_overrides(
            section.get("vehicle_dynamics", {}), "defaults.vehicle_dynamics."
        ),
        pedestrian=DEFAULT_PEDESTRIAN_DYNAMICS.with_overrides(
            section.get("pedestrian_dynamics", {}), "defaults.pedestrian_dynamics."
        ),
    )


def case_number(
    case_id: str, obj: Mapping[str, Any], key: str, default: float | None = None
) -> float:
    """``obj[key]`` as a float (``default`` when absent).

    Raises:
        RssCaseError: The key is missing without a default, or the value is not a number.
    """
    value = obj.get(key, default)
    if value is None:
        raise RssCaseError(case_id, f"missing number {key!r}")
    if not isinstance(value, int | float) or isinstance(value, bool):
        raise RssCaseError(case_id, f"{key!r} must be a number, got {value!r}")
    return float(value)


def _interval(case_id: str, obj: Mapping[str, Any], name: str) -> tuple[float, float]:
    if name in obj:
        value = case_number(case_id, obj, name)
        return value, value
    return case_number(case_id, obj, f"{name}_min", 0.0), case_number(
        case_id, obj, f"{name}_max", 0.0
    )


def _object_type(case_id: str, obj: Mapping[str, Any], default: str) -> ObjectType:
    name = obj.get("object_type", default)
    try:
        return ObjectType[name]
    except KeyError as err:
        raise RssCaseError(case_id, f"unknown object_type {name!r}") from err


def other_dynamics_for(defaults: CaseDefaults, object_type: ObjectType) -> RssDynamics:
    """Default dynamics of a non-ego object by its type."""
    return defaults.pedestrian if object_type in _PEDESTRIANS else defaults.vehicle


def _overlap(a0: float, a1: float, b0: float, b1: float) -> tuple[float, float] | None:
    lo, hi = max(a0, b0), min(a1, b1)
    return (lo, hi) if hi > lo else None


def _unit(value: float) -> float:
    """Clamp a parametric coordinate to [0, 1] (removes float rounding)."""
    return min(1.0, max(0.0, value))


def _straight_road(case_id: str, road: Mapping[str, Any]) -> tuple[tuple[RoadSegment, ...], float]:
    length = case_number(case_id, road, "length")
    widths = road.get("lane_widths")
    if not isinstance(widths, list) or not widths:
        raise RssCaseError(case_id, "road.lane_widths must be a non-empty list")
    directions = road.get("lane_directions", ["Positive"] * len(widths))
    if not isinstance(directions, list) or len(directions) != len(widths):
        raise RssCaseError(case_id, "road.lane_directions must list one direction per lane")
    lanes = []
    for index, (width, direction) in enumerate(
        zip(reversed(widths), reversed(directions), strict=True)
    ):
        try:
            lane_direction = LaneDrivingDirection[direction]
        except KeyError as err:
            raise RssCaseError(case_id, f"unknown lane direction {direction!r}") from err
        w = case_number(case_id, {"w": width}, "w")
        lanes.append(LaneSegment(index + 1, lane_direction, length, length, w, w))
    return (RoadSegment(tuple(lanes)),), length


def _straight_object(
    case_id: str,
    obj: Mapping[str, Any],
    road: tuple[RoadSegment, ...],
    object_id: int,
    object_type: ObjectType,
) -> LaneObject:
    lanes = road[0].lanes
    road_length = lanes[0].length_max_m
    total = sum(lane.width_max_m for lane in lanes)
    s, y = case_number(case_id, obj, "s"), case_number(case_id, obj, "y")
    half_l, half_w = (
        case_number(case_id, obj, "length") / 2.0,
        case_number(case_id, obj, "width") / 2.0,
    )
    lon = _overlap(s - half_l, s + half_l, 0.0, road_length)
    regions = []
    start = 0.0
    for lane in lanes:
        lat = _overlap(total - y - half_w, total - y + half_w, start, start + lane.width_max_m)
        if lat is not None and lon is not None:
            regions.append(
                OccupiedRegion(
                    lane.lane_id,
                    _unit(lon[0] / road_length),
                    _unit(lon[1] / road_length),
                    _unit((lat[0] - start) / lane.width_max_m),
                    _unit((lat[1] - start) / lane.width_max_m),
                )
            )
        start += lane.width_max_m
    return LaneObject(object_id, object_type, tuple(regions), _speeds(case_id, obj))


def _speeds(case_id: str, obj: Mapping[str, Any]) -> SpeedInterval:
    lon_min, lon_max = _interval(case_id, obj, "v_lon")
    lat_min, lat_max = _interval(case_id, obj, "v_lat")
    return SpeedInterval(lon_min, lon_max, -lat_max, -lat_min)


def _intersection_road(
    case_id: str, spec: Mapping[str, Any], who: str, first_id: int
) -> tuple[RoadSegment, ...]:
    approach = case_number(case_id, spec, f"{who}_approach")
    crossing = case_number(case_id, spec, f"{who}_crossing")
    exit_length = case_number(case_id, spec, "exit", _INTERSECTION_DEFAULTS["exit"])
    width = case_number(case_id, spec, "lane_width", _INTERSECTION_DEFAULTS["lane_width"])
    kinds = (RoadSegmentType.Normal, RoadSegmentType.Intersection, RoadSegmentType.Normal)
    return tuple(
        RoadSegment(
            (
                LaneSegment(
                    first_id + i, LaneDrivingDirection.Positive, length, length, width, width
                ),
            ),
            kind,
        )
        for i, (length, kind) in enumerate(
            zip((approach, crossing, exit_length), kinds, strict=True)
        )
    )


def _intersection_object(
    case_id: str,
    obj: Mapping[str, Any],
    road: tuple[RoadSegment, ...],
    object_id: int,
    object_type: ObjectType,
) -> LaneObject:
    front = road[0].lanes[0].length_max_m - case_number(case_id, obj, "dist_to_enter")
    rear = front - case_number(case_id, obj, "length")
    width = road[0].lanes[0].width_max_m
    half_w = min(case_number(case_id, obj, "width"), width) / 2.0
    regions = []
    start = 0.0
    for segment in road:
        lane = segment.lanes[0]
        lon = _overlap(rear, front, start, start + lane.length_max_m)
        if lon is not None:
            regions.append(
                OccupiedRegion(
                    lane.lane_id,
                    _unit((lon[0] - start) / lane.length_max_m),
                    _unit((lon[1] - start) / lane.length_max_m),
                    0.5 - half_w / width,
                    0.5 + half_w / width,
                )
            )
        start += lane.length_max_m
    return LaneObject(object_id, object_type, tuple(regions), _speeds(case_id, obj))


def _dict(case_id: str, case: Mapping[str, Any], key: str) -> Mapping[str, Any]:
    value = case.get(key)
    if not isinstance(value, dict):
        raise RssCaseError(case_id, f"{key!r} must be an object")
    return value


def _structured(case_id: str, case: Mapping[str, Any], defaults: CaseDefaults) -> Constellation:
    name = case.get("constellation_type", "SameDirection")
    try:
        ctype = ConstellationType[name]
    except KeyError as err:
        raise RssCaseError(case_id, f"unknown constellation_type {name!r}") from err
    if ctype == ConstellationType.Unstructured:
        raise RssCaseError(case_id, "constellation_type Unstructured needs kind 'unstructured'")
    ego, other = _dict(case_id, case, "ego"), _dict(case_id, case, "other")
    other_type = _object_type(case_id, other, "OtherVehicle")
    try:
        ego_dyn = defaults.ego.with_overrides(case.get("ego_dynamics", {}), "ego_dynamics.")
        other_dyn = other_dynamics_for(defaults, other_type).with_overrides(
            case.get("other_dynamics", {}), "other_dynamics."
        )
    except RssError as err:
        raise RssCaseError(case_id, str(err)) from err
    if ctype >= ConstellationType.IntersectionEgoHasPriority:
        spec = _dict(case_id, case, "intersection")
        ego_road = _intersection_road(case_id, spec, "ego", 1)
        other_road = _intersection_road(case_id, spec, "other", 11)
        ego_obj = _intersection_object(case_id, ego, ego_road, EGO_ID, ObjectType.EgoVehicle)
        other_obj = _intersection_object(case_id, other, other_road, OTHER_ID, other_type)
        return Constellation(ctype, ego_obj, other_obj, ego_dyn, other_dyn, ego_road, other_road)
    road, _ = _straight_road(case_id, _dict(case_id, case, "road"))
    ego_obj = _straight_object(case_id, ego, road, EGO_ID, ObjectType.EgoVehicle)
    other_obj = _straight_object(case_id, other, road, OTHER_ID, other_type)
    return Constellation(ctype, ego_obj, other_obj, ego_dyn, other_dyn, road)


def parse_case(
    case: Mapping[str, Any],
    defaults: CaseDefaults,
    fallback_id: str,
    sequence_id: str | None = None,
    step: int | None = None,
) -> ParsedCase:
    """Read one non-sequence case.

    Args:
        case: The case's JSON object.
        defaults: File-level defaults.
        fallback_id: Id to use when the case has none.
        sequence_id: Enclosing sequence, if any.
        step: Step index in the sequence, if any.

    Raises:
        RssCaseError: Malformed case (missing key, unknown kind / type / direction).
    """
    if not isinstance(case, dict):
        raise RssCaseError(fallback_id, "a case must be a JSON object")
    case_id = str(case.get("id", fallback_id)) if sequence_id is None else fallback_id
    kind = case.get("kind")
    expected = case.get("expected", {}) or {}
    if kind not in {"structured", "unstructured", "formula"}:
        raise RssCaseError(case_id, f"unknown kind {kind!r}")
    constellation = _structured(case_id, case, defaults) if kind == "structured" else None
    return ParsedCase(case_id, kind, defaults.ego, constellation, case, expected, sequence_id, step)
