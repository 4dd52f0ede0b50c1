"""One pass over a CommonRoad scenario XML (2018b or 2020a): obstacle tracks and network.

2018b lists ``<obstacle>`` elements whose ``<role>`` says ``dynamic`` or ``static``; 2020a
lists ``<dynamicObstacle>`` and ``<staticObstacle>``. Each obstacle is converted to a
``Track`` of numpy arrays as soon as its element closes (``iterparse``), then the element
is cleared; the lanelet-network elements are kept for a lazy ``LaneMap``. States without
an integer time step are dropped; values that are missing or not numbers become NaN.
Uncertain states (CommonRoad 2020a: ``intervalStart``/``intervalEnd`` values, a position
given as a rectangle, circle or polygon, a time interval) are read at the interval's centre
(the shape's centre, the polygon's vertex mean); ``Track.uncertain`` names the quantities
that were uncertain and ``Track.uncertain_states`` counts the states concerned.
Results are cached per (file, mtime, size), so listing the ego candidates and opening
the drive once per candidate parse the file once.
"""

from __future__ import annotations

import functools
import math
from dataclasses import dataclass
from decimal import Decimal, InvalidOperation
from typing import TYPE_CHECKING

import numpy as np

from loaders.errors import CorruptLogError, InvalidValueError, UnsupportedFormatError
from loaders.maps.commonroad import NETWORK_TAGS, id_sort_key, parse_float
from loaders.maps.xmlsource import iter_xml

if TYPE_CHECKING:
    import xml.etree.ElementTree as ET
    from pathlib import Path

    from numpy.typing import NDArray

__all__ = ["VEHICLE_TYPES", "Scenario", "Track", "load_scenario"]

#: Obstacle types that can be promoted to ego.
VEHICLE_TYPES = frozenset({"car", "truck", "bus", "motorcycle", "taxi", "priorityVehicle"})


@dataclass(frozen=True, slots=True)
class Track:
    """One obstacle's recorded states, ``(T,)`` arrays sorted by time step."""

    id: str
    kind: str
    dynamic: bool
    length_m: float
    width_m: float
    steps: NDArray[np.int64]
    x_m: NDArray[np.float64]
    y_m: NDArray[np.float64]
    yaw_rad: NDArray[np.float64]
    speed_mps: NDArray[np.float64]
    vx_mps: NDArray[np.float64]
    vy_mps: NDArray[np.float64]
    accel_mps2: NDArray[np.float64]
    uncertain: tuple[str, ...] = ()
    uncertain_states: int = 0


@dataclass(frozen=True, slots=True)
class Scenario:
    """What one pass over a scenario file yields."""

    version: str
    benchmark_id: str
    dt_ns: int
    tracks: tuple[Track, ...]
    network: tuple[ET.Element, ...]

    def candidates(self) -> list[Track]:
        """Dynamic vehicle obstacles with states, longest-lived first, then by id."""
        vehicles = [
            t for t in self.tracks if t.dynamic and t.kind in VEHICLE_TYPES and len(t.steps)
        ]
        return sorted(vehicles, key=lambda t: (-len(t.steps), id_sort_key(t.id)))


@functools.lru_cache(maxsize=4)
def _load_cached(path: Path, mtime_ns: int, size: int) -> Scenario:  # noqa: ARG001 - cache key
    return _scan(path)


def load_scenario(path: Path) -> Scenario:
    """Read (or fetch from the cache) the tracks and network of a scenario file.

    Args:
        path: CommonRoad scenario XML.

    Returns:
        The scenario's obstacle tracks, time step and network elements.

    Raises:
        UnsupportedFormatError: If the file cannot be opened or is not a CommonRoad file.
        CorruptLogError: If the XML is malformed.
        InvalidValueError: If ``timeStepSize`` is missing or not a positive number of ns.
    """
    try:
        stat = path.stat()
    except OSError as err:
        raise UnsupportedFormatError(path, f"cannot open: {err.strerror}") from err
    return _load_cached(path.resolve(), stat.st_mtime_ns, stat.st_size)


def _scan(path: Path) -> Scenario:
    """Read the scenario in one ``iterparse`` pass, converting obstacles as they close."""
    root: ET.Element | None = None
    depth = 0
    tracks: list[Track] = []
    network: list[ET.Element] = []
    for event, elem in iter_xml(path, ("start", "end"), CorruptLogError):
        if event == "start":
            if root is None:
                root = elem
                if elem.tag != "commonRoad":
                    raise UnsupportedFormatError(
                        path, f"root element is <{elem.tag}>, not <commonRoad>"
                    )
            depth += 1
            continue
        depth -= 1
        if depth != 1:
            continue
        if elem.tag in NETWORK_TAGS:
            network.append(elem)
        else:
            track = _track(elem)
            if track is not None:
                tracks.append(track)
            elem.clear()
    assert root is not None
    return Scenario(
        version=root.get("commonRoadVersion", "unknown"),
        benchmark_id=root.get("benchmarkID", path.stem),
        dt_ns=_time_step_ns(path, root.get("timeStepSize")),
        tracks=tuple(tracks),
        network=tuple(network),
    )


def _time_step_ns(path: Path, text: str | None) -> int:
    try:
        value = Decimal(text or "") * 10**9
    except InvalidOperation:
        value = Decimal(0)
    if not value.is_finite() or value <= 0 or value != value.to_integral_value():
        raise InvalidValueError(path, "timeStepSize must be a positive number of ns", value=text)
    return int(value)


def _track(elem: ET.Element) -> Track | None:
    if elem.tag == "obstacle":
        dynamic = (elem.findtext("role") or "").strip() == "dynamic"
    elif elem.tag in {"dynamicObstacle", "staticObstacle"}:
        dynamic = elem.tag == "dynamicObstacle"
    else:
        return None
    states = [
        s for s in (elem.find("initialState"), *elem.iterfind("trajectory/state")) if s is not None
    ]
    rows: dict[int, list[float]] = {}
    uncertain: set[str] = set()
    uncertain_states = 0
    for state in states:
        step, step_uncertain = _time_step(state)
        if step is None or step in rows:
            continue
        readings = [_position(state, axis) for axis in ("x", "y")]
        readings += [_reading(state, tag) for tag in _STATE_TAGS]
        rows[step] = [value for value, _ in readings]
        flags = [step_uncertain, *(flag for _, flag in readings)]
        uncertain.update(name for name, flag in zip(_QUANTITIES, flags, strict=True) if flag)
        uncertain_states += any(flags)
    steps = np.array(sorted(rows), dtype=np.int64)
    x, y, yaw, v, vy_given, acc = (
        np.array([rows[s] for s in steps.tolist()], dtype=np.float64).reshape(-1, 6).T
    )
    point_mass = np.isfinite(vy_given)
    vx = np.where(point_mass, v, v * np.cos(yaw))
    vy = np.where(point_mass, vy_given, v * np.sin(yaw))
    speed = np.where(point_mass, v * np.cos(yaw) + vy_given * np.sin(yaw), v)
    length, width = _shape(elem)
    return Track(
        id=elem.get("id", ""),
        kind=(elem.findtext("type") or "unknown").strip(),
        dynamic=dynamic,
        length_m=length,
        width_m=width,
        steps=steps,
        x_m=x,
        y_m=y,
        yaw_rad=yaw,
        speed_mps=speed,
        vx_mps=vx,
        vy_mps=vy,
        accel_mps2=acc,
        uncertain=tuple(sorted(uncertain)),
        uncertain_states=uncertain_states,
    )


def _shape(elem: ET.Element) -> tuple[float, float]:
    if elem.find("shape/rectangle") is not None:
        return parse_float(elem.findtext("shape/rectangle/length")), parse_float(
            elem.findtext("shape/rectangle/width")
        )
    diameter = 2.0 * parse_float(elem.findtext("shape/circle/radius"))
    return diameter, diameter


#: Scalar state values after the position, in ``_track``'s row order.
_STATE_TAGS = ("orientation", "velocity", "velocityY", "acceleration")
#: Names of the quantities of one state, as ``Track.uncertain`` reports them.
_QUANTITIES = ("time", "position", "position", *_STATE_TAGS)
#: Uncertain position shapes, each with a ``center`` (a polygon has ``point`` vertices).
_SHAPES = ("rectangle", "circle")


def _reading(state: ET.Element, tag: str) -> tuple[float, bool]:
    """``(value, uncertain)``: exact value, else the interval's centre (``uncertain``)."""
    node = state.find(tag)
    if node is None:
        return math.nan, False
    if node.find("exact") is not None:
        return parse_float(node.findtext("exact")), False
    if node.find("intervalStart") is not None:
        start = parse_float(node.findtext("intervalStart"))
        return 0.5 * (start + parse_float(node.findtext("intervalEnd"))), True
    return parse_float(node.text), False


def _position(state: ET.Element, axis: str) -> tuple[float, bool]:
    """One coordinate of the position: the point, else the centre of the first shape."""
    if state.find("position/point") is not None:
        return _reading(state, f"position/point/{axis}")
    for shape in _SHAPES:
        if state.find(f"position/{shape}/center") is not None:
            return parse_float(state.findtext(f"position/{shape}/center/{axis}")), True
    vertices = [parse_float(p.findtext(axis)) for p in state.iterfind("position/polygon/point")]
    if vertices:
        return float(np.mean(vertices)), True
    return math.nan, False


def _time_step(state: ET.Element) -> tuple[int | None, bool]:
    """``(step, uncertain)``: ``time/exact``, else the interval's centre if a whole step."""
    if state.find("time/intervalStart") is None:
        return _int(state.findtext("time/exact")), False
    value, _ = _reading(state, "time")
    if not math.isfinite(value) or value != round(value):
        return None, True
    return int(value), True


def _int(text: str | None) -> int | None:
    try:
        return int(text.strip()) if text is not None else None
    except ValueError:
        return None
