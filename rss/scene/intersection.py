"""Intersection constellations from pairs of predicted routes.

For an ego route and an object route the first pair of intersection lanes whose areas
overlap (or that merge into one successor) is the conflict. Each vehicle gets its own
road area: its route up to and including its conflict lane, typed ``Intersection``, with
the lengths before and after the part of that lane that overlaps the other's lane::

    ego route ──▶ ──▶ ┌──────── conflict lane a ────────┐
                      │ before │ overlaps lane b │ after│
                      └────────┴─────────────────┴──────┘

Priority comes from right of way and traffic lights (a light not listed green means the
route must yield, as ad-map does with an empty set of green lights); without any
regulation the ego yields (ad-map's behaviour for intersections of unknown type).
"""

from __future__ import annotations

import enum
import math
import weakref
from typing import TYPE_CHECKING, NamedTuple

import numpy as np
import shapely

from rss.model import ConstellationType, LaneDrivingDirection, RoadSegmentType
from rss.scene.admap_heading import lane_chord_heading
from rss.scene.cache import memoised
from rss.scene.roadarea import SegmentPlan
from rss.scene.routes import cross_section

if TYPE_CHECKING:
    from rss.arrays import IntArray
    from rss.scene.lanegraph import PreparedGraph
    from rss.scene.routes import Step


__all__ = [
    "Arm",
    "IntersectionPair",
    "Relation",
    "conflict",
    "intersection_arms",
    "intersection_pair",
    "intersection_plans",
    "intersection_type",
    "junctions_on",
    "relation",
    "route_priority",
]

_JUNCTIONS: dict[int, tuple[weakref.ref[PreparedGraph], IntArray, list[int]]] = {}


class Arm(enum.Enum):
    """ad-map's turn directions, used to name the arms of an intersection."""

    UNKNOWN = "unknown"
    RIGHT = "right"
    STRAIGHT = "straight"
    LEFT = "left"
    UTURN = "u-turn"


class Relation(enum.Enum):
    """How another route meets an intersection on a route (ad-map ``Intersection``)."""

    NONE = "does not enter the intersection"
    SAME_ARM = "enters from the route's incoming arm"
    OPPOSITE = "passes: from the route's outgoing arm to its U-turn arm, or no crossing"
    CROSSING = "crosses the route's lanes inside the intersection"


def _components(n: int, pairs: list[tuple[int, int]]) -> IntArray:
    """Connected-component root per node (union-find)."""
    parent = list(range(n))

    def root(a: int) -> int:
        while parent[a] != a:
            a = parent[a]
        return a

    for a, b in pairs:
        parent[root(a)] = root(b)
    return np.array([root(a) for a in range(n)], dtype=np.int64)


def junction_ids(prep: PreparedGraph) -> IntArray:
    """``(L,)`` junction index per lane (-1 outside): connected intersection lanes.

    Intersection lanes belong to one junction when they overlap, merge, split or link.
    Cached per prepared graph.
    """
    return _junctions(prep)[0]


def junction_list(prep: PreparedGraph) -> list[int]:
    """:func:`junction_ids` as a Python list (fast scalar access)."""
    return _junctions(prep)[1]


def _junctions(prep: PreparedGraph) -> tuple[IntArray, list[int]]:
    cached = _JUNCTIONS.get(id(prep))
    if cached is not None and cached[0]() is prep:
        return cached[1], cached[2]
    g = prep.graph
    inter = [int(v) for v in np.flatnonzero(g.is_intersection)]
    members = set(inter)
    pairs: list[tuple[int, int]] = []
    for a in inter:
        linked = {*g.successors[a], *g.predecessors[a], *np.flatnonzero(prep.conflicts[a]).tolist()}
        pairs.extend((a, b) for b in linked & members)
    for c in set(range(len(g))) - members:
        for end in (g.successors[c], g.predecessors[c]):
            group = [b for b in end if b in members]
            pairs.extend((group[0], b) for b in group[1:])
    out = _components(len(g), pairs)
    out[~g.is_intersection] = -1
    as_list = [int(v) for v in out]
    _JUNCTIONS[id(prep)] = (weakref.ref(prep), out, as_list)
    return out, as_list


def junctions_on(prep: PreparedGraph, route: tuple[Step, ...]) -> list[tuple[int, int, int]]:
    """Intersections a route enters: ``(junction, first index, last index)`` in order.

    A junction the route starts in is not listed (ad-rss analyses only intersections
    ahead). Memoised like :func:`relation` (do not modify the result).
    """
    return memoised(prep, _junctions_on, route)


def _junctions_on(prep: PreparedGraph, route: tuple[Step, ...]) -> list[tuple[int, int, int]]:
    jid = junction_list(prep)
    out: list[tuple[int, int, int]] = []
    for idx, (lane, _) in enumerate(route):
        j = jid[lane]
        if j < 0 or idx == 0 or jid[route[0][0]] == j:
            continue
        if out and out[-1][0] == j and out[-1][2] == idx - 1:
            out[-1] = (j, out[-1][1], idx)
        elif not any(o[0] == j for o in out):
            out.append((j, idx, idx))
    return out


def _linked(prep: PreparedGraph, lane: int, *, ahead: bool) -> set[int]:
    """Lanes the traffic of ``lane`` leads into (``ahead``) or comes from."""
    g = prep.graph
    code = prep.scalars.direction[lane]
    if code == LaneDrivingDirection.Positive:
        return set(g.successors[lane] if ahead else g.predecessors[lane])
    if code == LaneDrivingDirection.Negative:
        return set(g.predecessors[lane] if ahead else g.successors[lane])
    return {*g.predecessors[lane], *g.successors[lane]}


def _entries(prep: PreparedGraph, lane: int) -> set[int]:
    """Lanes whose traffic leads into ``lane``."""
    return _linked(prep, lane, ahead=False)


def _exits(prep: PreparedGraph, lane: int) -> set[int]:
    """Lanes the traffic of ``lane`` leads into."""
    return _linked(prep, lane, ahead=True)


def _inside_successors(prep: PreparedGraph, jid: list[int], j: int, lane: int) -> set[int]:
    """Lanes of junction ``j`` reachable from ``lane`` in driving direction inside ``j``."""
    found: set[int] = set()
    todo = [b for b in _exits(prep, lane) if jid[b] == j]
    while todo:
        b = todo.pop()
        if b not in found:
            found.add(b)
            todo.extend(c for c in _exits(prep, b) if jid[c] == j)
    return found


def _lane_angle(prep: PreparedGraph, lane: int) -> float:
    """Direction [rad] of the chord from a lane's start to its end, in driving direction."""
    c = prep.scalars.centre_xy_m[lane]
    (x0, y0), (x1, y1) = c[0], c[-1]
    if prep.scalars.direction[lane] == LaneDrivingDirection.Negative:
        (x0, y0), (x1, y1) = (x1, y1), (x0, y0)
    return math.atan2(y1 - y0, x1 - x0)


def _bucket(angle: float) -> Arm:
    """ad-map's turn direction of a relative arm angle (0 = back where the route came from)."""
    deg = math.degrees(angle % (2.0 * math.pi))
    if deg > 315.0 or deg < 45.0:  # noqa: PLR2004 - ad-map's 90-degree sectors
        return Arm.UTURN
    if deg > 225.0:  # noqa: PLR2004
        return Arm.LEFT
    if deg > 135.0:  # noqa: PLR2004
        return Arm.STRAIGHT
    if deg > 45.0:  # noqa: PLR2004
        return Arm.RIGHT
    return Arm.UNKNOWN


#: ad-map's sector bounds [rad] (``turnDirectionForAngle``: degrees times pi / 180).
_SECTOR_45 = 45.0 * math.pi / 180.0
_SECTOR_135 = 135.0 * math.pi / 180.0
_SECTOR_225 = 225.0 * math.pi / 180.0
_SECTOR_315 = 315.0 * math.pi / 180.0


def _bucket_wrapped_once(angle: float) -> Arm:
    """ad-map 5.0's sector of a relative angle [rad] that is wrapped once only.

    A negative angle gets one turn added (``directionOfLanes``); one below ``-2 pi`` stays
    negative and, being below 45 degrees, falls into the U-turn sector.
    """
    if angle < 0.0:
        angle += 2.0 * math.pi
    if angle > _SECTOR_315 or angle < _SECTOR_45:
        return Arm.UTURN
    if angle > _SECTOR_225:
        return Arm.LEFT
    if angle > _SECTOR_135:
        return Arm.STRAIGHT
    if angle > _SECTOR_45:
        return Arm.RIGHT
    return Arm.UNKNOWN


def intersection_arms(
    prep: PreparedGraph, j: int, incoming: int, *, admap_defects: bool = False
) -> dict[int, Arm]:
    """The arm of every lane entering or leaving junction ``j``, seen from ``incoming``.

    As ad-map orders intersection arms: an entry lane's chord direction (start to end, in
    driving direction) relative to the chord direction of the route's incoming lane, an
    exit lane's relative to the opposite direction, each put into a 90-degree sector (the
    route's own arm is the U-turn arm). Deviation: ad-map 5.0 gets these angles wrong on
    maps geo-referenced at latitude/longitude 0 such as CARLA's (docs/rss_scene.md); the
    geometric angles are used here unless ``admap_defects``.

    Args:
        prep: The prepared lane graph.
        j: Junction index (:func:`junction_ids`).
        incoming: The lane through which the route enters the junction.
        admap_defects: Reproduce ad-map 5.0 (``[scene] reproduce_adrss_5_0_defects``): its
            defective chord headings (:func:`rss.scene.admap_heading.lane_chord_heading`)
            and relative angles wrapped once only.
    """
    jid = junction_list(prep)
    members = [lane for lane, k in enumerate(jid) if k == j]
    entries = {e for lane in members for e in _entries(prep, lane) if jid[e] != j}
    exits = {x for lane in members for x in _exits(prep, lane) if jid[x] != j}
    if admap_defects:
        ref = memoised(prep, lane_chord_heading, incoming)
        arms = {
            lane: _bucket_wrapped_once(memoised(prep, lane_chord_heading, lane) - ref)
            for lane in entries
        }
        arms.update(
            {
                lane: _bucket_wrapped_once(
                    memoised(prep, lane_chord_heading, lane) - (ref + math.pi)
                )
                for lane in exits
            }
        )
        return arms
    ref = _lane_angle(prep, incoming)
    arms = {lane: _bucket(_lane_angle(prep, lane) - ref) for lane in entries}
    arms.update({lane: _bucket(_lane_angle(prep, lane) - ref - math.pi) for lane in exits})
    return arms


def _same_arm(
    prep: PreparedGraph, jid: list[int], j: int, incoming: set[int], other: list[int]
) -> bool:
    found = False
    for lane in other:
        inside = jid[lane] == j
        if lane in incoming or (inside and _entries(prep, lane) & incoming):
            found = True
        elif inside:
            return False
        elif found:
            break
    return found


def _opposite(
    prep: PreparedGraph,
    jid: list[int],
    j: int,
    arms: tuple[set[int], set[int]],
    other: tuple[Step, ...],
    *,
    admap_defects: bool = False,
) -> bool:
    """ad-map: ``other`` passes the route's outgoing arm, then reaches its U-turn arm.

    ``admap_defects``: as ad-map 5.0's ``findWaypoint`` of a lane, which on a lane the
    route runs against ad-map's point order points at the lane's *end*: the search for
    the U-turn arm then starts after that lane.
    """
    out_arm, back_arm = arms
    lanes = [lane for lane, _ in other]
    start = next((k for k, lane in enumerate(lanes) if lane in out_arm), None)
    if (
        start is None
        and lanes
        and jid[lanes[0]] == j
        and any(lanes[0] in _inside_successors(prep, jid, j, lane) for lane in out_arm)
    ):
        start = 0
    if start is None:
        return False
    if admap_defects and not _along_admap_order(prep, other[start]):
        start += 1
    return any(lane in back_arm for lane in lanes[start:])


def _along_admap_order(prep: PreparedGraph, step: Step) -> bool:
    """Whether a route step runs along ad-map's point order of its lane."""
    lane, forward = step
    flags = prep.graph.admap_reversed
    return forward != (flags is not None and bool(flags[lane]))


def _turn(
    prep: PreparedGraph,
    route: tuple[Step, ...],
    span: tuple[int, int, int],
    arms: dict[int, Arm],
    *,
    admap_defects: bool,
) -> Arm:
    """The arm where ``route`` leaves the intersection ``span`` (ad-map's turn direction).

    A route that ends inside it has no turn (``UNKNOWN``), except with ``admap_defects``:
    ad-map then takes the exits its junction lanes lead to (the first by lane index
    where they lead to several).
    """
    j, first, last = span
    if last + 1 < len(route):
        return arms.get(route[last + 1][0], Arm.UNKNOWN)
    if not admap_defects:
        return Arm.UNKNOWN
    jid = junction_list(prep)
    entry = route[first][0]
    inside = {entry} | _inside_successors(prep, jid, j, entry)
    exits = sorted({x for lane in inside for x in _exits(prep, lane) if jid[x] != j})
    return arms.get(exits[0], Arm.UNKNOWN) if exits else Arm.UNKNOWN


def relation(
    prep: PreparedGraph,
    route: tuple[Step, ...],
    span: tuple[int, int, int],
    other: tuple[Step, ...],
    *,
    admap_defects: bool = False,
) -> Relation:
    """How ``other`` meets the intersection ``span`` (from :func:`junctions_on`) of ``route``.

    ``admap_defects``: arms as ad-map 5.0 orders them (:func:`intersection_arms`).
    Memoised per prepared graph (routes repeat from frame to frame).
    """
    return memoised(prep, _relation, route, span, other, admap_defects)


def _relation(
    prep: PreparedGraph,
    route: tuple[Step, ...],
    span: tuple[int, int, int],
    other: tuple[Step, ...],
    admap_defects: bool,  # noqa: FBT001 - positional: part of the memo key
) -> Relation:
    jid = junction_list(prep)
    j, first, last = span
    lanes = [lane for lane, _ in other]
    if not any(jid[lane] == j for lane in lanes):
        return Relation.NONE
    before = route[first - 1]
    incoming = {lane for lane, fwd in cross_section(prep, before) if fwd == before[1]}
    if _same_arm(prep, jid, j, incoming, lanes):
        return Relation.SAME_ARM
    arms = intersection_arms(prep, j, before[0], admap_defects=admap_defects)
    turn = _turn(prep, route, span, arms, admap_defects=admap_defects)
    out_arm = {lane for lane, arm in arms.items() if arm == turn}
    back_arm = {lane for lane, arm in arms.items() if arm == Arm.UTURN}
    own = _inside_successors(prep, jid, j, before[0])
    mine = [lane for lane, _ in route[first : last + 1]]
    crossing = any(
        jid[lane] == j and lane not in own and prep.conflicts[mine, lane].any() for lane in lanes
    )
    opposite = _opposite(prep, jid, j, (out_arm, back_arm), other, admap_defects=admap_defects)
    if opposite or not crossing:
        return Relation.OPPOSITE
    return Relation.CROSSING


def conflict(
    prep: PreparedGraph, ego_route: tuple[Step, ...], obj_route: tuple[Step, ...]
) -> tuple[int, int] | None:
    """Indices ``(ie, io)`` of the first conflicting intersection lanes, or ``None``.

    Conflicting: overlapping or merging intersection lanes, else the first lane both
    routes share (routes from one arm, merging routes). Memoised like :func:`relation`.
    """
    return memoised(prep, _conflict, ego_route, obj_route)


def _conflict(
    prep: PreparedGraph, ego_route: tuple[Step, ...], obj_route: tuple[Step, ...]
) -> tuple[int, int] | None:
    lists = prep.scalars
    inter = lists.is_intersection
    obj_lanes = [(io, lane) for io, (lane, _) in enumerate(obj_route) if inter[lane]]
    for ie, (a, _) in enumerate(ego_route):
        if not inter[a]:
            continue
        row = lists.conflict_rows[a]
        for io, b in obj_lanes:
            if row[b]:
                return ie, io
    where = {lane: io for io, (lane, _) in enumerate(obj_route)}
    for ie, (a, _) in enumerate(ego_route):
        if a in where:
            return ie, where[a]
    return None


_SPANS: dict[
    int, tuple[weakref.ref[PreparedGraph], dict[tuple[int, int], tuple[float, float]]]
] = {}


def area_span(prep: PreparedGraph, lane: int, other: int) -> tuple[float, float]:
    """Lengths of ``lane`` before and after the part of its *area* inside ``other``'s.

    As ad-rss (``extractInnerRegions`` of the lane in the other lane's polygon): the
    vertices of the two lanes' common area are projected on ``lane``'s centre line; the
    parametric range they span is the intersecting part, its outside measured in the
    lane's minimal length. Lanes without common area keep the whole lane before it.
    Cached per prepared graph.
    """
    cached = _SPANS.get(id(prep))
    if cached is None or cached[0]() is not prep:
        cached = (weakref.ref(prep), {})
        _SPANS[id(prep)] = cached
    spans = cached[1]
    key = (lane, other)
    if key not in spans:
        length = float(prep.length_min_m[lane])
        shared = shapely.intersection(prep.polygons[lane], prep.polygons[other])
        if shapely.is_empty(shared) or shapely.area(shared) <= 0.0:
            spans[key] = prep.conflict_span_m.get(key, (length, 0.0))
        else:
            s = shapely.line_locate_point(
                prep.centre_lines[lane],
                shapely.points(shapely.get_coordinates(shared)),
                normalized=True,
            )
            spans[key] = (float(np.min(s)) * length, (1.0 - float(np.max(s))) * length)
    return spans[key]


def intersection_plans(
    prep: PreparedGraph, route: tuple[Step, ...], upto: int, other_lane: int
) -> list[SegmentPlan]:
    """Single-lane segments along ``route[:upto + 1]``, the last one the intersection."""
    plans = [SegmentPlan(lanes=[step]) for step in route[:upto]]
    lane, fwd = route[upto]
    before, after = area_span(prep, lane, other_lane)
    if not fwd:
        before, after = after, before
    plans.append(
        SegmentPlan(
            lanes=[(lane, fwd)],
            segment_type=RoadSegmentType.Intersection,
            before_m=before,
            after_m=after,
        )
    )
    return plans


def route_priority(prep: PreparedGraph, route: tuple[Step, ...], green: frozenset[int]) -> int:
    """Right of way of ``route``: the last regulated lane up to its end (+1, 0, -1)."""
    g = prep.graph
    level = 0
    for lane, _ in route:
        light = int(g.traffic_light[lane])
        if light >= 0:
            level = 1 if light in green else -1
        elif g.priority[lane] != 0:
            level = int(g.priority[lane])
    return level


def intersection_type(ego_level: int, obj_level: int) -> ConstellationType:
    """Constellation type from the two routes' right of way.

    Two unregulated routes (level 0) make the ego yield, as ad-map does for intersections
    of unknown type; two regulated routes of the same level have the same priority.
    """
    if ego_level == obj_level == 0:
        return ConstellationType.IntersectionObjectHasPriority
    if ego_level > obj_level:
        return ConstellationType.IntersectionEgoHasPriority
    if ego_level < obj_level:
        return ConstellationType.IntersectionObjectHasPriority
    return ConstellationType.IntersectionSamePriority


class IntersectionPair(NamedTuple):
    """The uncut road areas of an (ego route, object route) pair (see :func:`intersection_pair`).

    Attributes:
        ego_lane: The ego route's conflict lane.
        obj_lane: The object route's conflict lane.
        ego_plans: :func:`intersection_plans` of the ego route (do not modify).
        obj_plans: :func:`intersection_plans` of the object route (do not modify).
        priority: :func:`intersection_type` of the two routes' right of way up to the
            conflict.
    """

    ego_lane: int
    obj_lane: int
    ego_plans: tuple[SegmentPlan, ...]
    obj_plans: tuple[SegmentPlan, ...]
    priority: ConstellationType


def intersection_pair(
    prep: PreparedGraph,
    ego_route: tuple[Step, ...],
    obj_route: tuple[Step, ...],
    green: frozenset[int],
) -> IntersectionPair | None:
    """Conflict, uncut road areas and priority of two routes; ``None`` without conflict.

    A function of the two routes and the green lights alone, so memoised per prepared
    graph (route pairs repeat from frame to frame; only the cuts at the vehicles change).
    """
    return memoised(prep, _intersection_pair, ego_route, obj_route, green)


def _intersection_pair(
    prep: PreparedGraph,
    ego_route: tuple[Step, ...],
    obj_route: tuple[Step, ...],
    green: frozenset[int],
) -> IntersectionPair | None:
    hit = conflict(prep, ego_route, obj_route)
    if hit is None:
        return None
    ie, io = hit
    ego_lane, obj_lane = ego_route[ie][0], obj_route[io][0]
    return IntersectionPair(
        ego_lane,
        obj_lane,
        tuple(intersection_plans(prep, ego_route, ie, obj_lane)),
        tuple(intersection_plans(prep, obj_route, io, ego_lane)),
        intersection_type(
            route_priority(prep, ego_route[: ie + 1], green),
            route_priority(prep, obj_route[: io + 1], green),
        ),
    )
