"""How another route meets an intersection on a route (ad-map ``Intersection``).

A route enters intersections (:func:`junctions_on`); another route meets each of them
from the route's incoming arm (``SAME_ARM``), crosses its lanes inside (``CROSSING``),
passes from its outgoing arm to its U-turn arm or does not cross (``OPPOSITE``), or does
not enter it (``NONE``); arms as in ``rss.scene.junction_arms``.
"""

from __future__ import annotations

import enum
from typing import TYPE_CHECKING

from rss.scene.junction_arms import Arm, entries, exits, inside_successors, intersection_arms
from rss.scene.memo import memoised
from rss.scene.routes import cross_section

if TYPE_CHECKING:
    from rss.scene.lanegraph import Step
    from rss.scene.memo import SceneMemo
    from rss.scene.prepared import PreparedGraph

__all__ = ["Relation", "junctions_on", "relation"]


class Relation(enum.Enum):
    """How another route meets an intersection on a route (ad-map ``Intersection``)."""

    NONE = "does not enter the intersection"
    SAME_ARM = "enters from the route's incoming arm"
    OPPOSITE = "passes: from the route's outgoing arm to its U-turn arm, or no crossing"
    CROSSING = "crosses the route's lanes inside the intersection"


def junctions_on(
    prep: PreparedGraph, memo: SceneMemo, route: tuple[Step, ...]
) -> list[tuple[int, int, int]]:
    """Intersections a route enters: ``(junction, first index, last index)`` in order.

    A junction the route starts in is not listed (ad-rss analyses only intersections
    ahead). Memoised like :func:`relation` (do not modify the result).
    """
    return memoised(prep, memo, _junctions_on, route)


def _junctions_on(
    prep: PreparedGraph, _memo: SceneMemo, route: tuple[Step, ...]
) -> list[tuple[int, int, int]]:
    jid = prep.junction_list
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


def _same_arm(
    prep: PreparedGraph, jid: list[int], j: int, incoming: set[int], other: list[int]
) -> bool:
    found = False
    for lane in other:
        inside = jid[lane] == j
        if lane in incoming or (inside and entries(prep, lane) & incoming):
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
        and any(lanes[0] in inside_successors(prep, jid, j, lane) for lane in out_arm)
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
    jid = prep.junction_list
    entry = route[first][0]
    inside = {entry} | inside_successors(prep, jid, j, entry)
    leaving = sorted({x for lane in inside for x in exits(prep, lane) if jid[x] != j})
    return arms.get(leaving[0], Arm.UNKNOWN) if leaving else Arm.UNKNOWN


def relation(
    prep: PreparedGraph,
    memo: SceneMemo,
    route: tuple[Step, ...],
    span: tuple[int, int, int],
    other: tuple[Step, ...],
    *,
    admap_defects: bool = False,
) -> Relation:
    """How ``other`` meets the intersection ``span`` (from :func:`junctions_on`) of ``route``.

    ``admap_defects``: arms as ad-map 5.0 orders them (:func:`intersection_arms`).
    Memoised per map (routes repeat from frame to frame).
    """
    return memoised(prep, memo, _relation, route, span, other, admap_defects)


def _relation(  # noqa: PLR0917 - positional: the memo key
    prep: PreparedGraph,
    memo: SceneMemo,
    route: tuple[Step, ...],
    span: tuple[int, int, int],
    other: tuple[Step, ...],
    admap_defects: bool,  # noqa: FBT001 - positional: part of the memo key
) -> Relation:
    jid = prep.junction_list
    j, first, last = span
    lanes = [lane for lane, _ in other]
    if not any(jid[lane] == j for lane in lanes):
        return Relation.NONE
    before = route[first - 1]
    incoming = {lane for lane, fwd in cross_section(prep, memo, before) if fwd == before[1]}
    if _same_arm(prep, jid, j, incoming, lanes):
        return Relation.SAME_ARM
    arms = intersection_arms(prep, memo, j, before[0], admap_defects=admap_defects)
    turn = _turn(prep, route, span, arms, admap_defects=admap_defects)
    out_arm = {lane for lane, arm in arms.items() if arm == turn}
    back_arm = {lane for lane, arm in arms.items() if arm == Arm.UTURN}
    own = inside_successors(prep, jid, j, before[0])
    mine = [lane for lane, _ in route[first : last + 1]]
    crossing = any(
        jid[lane] == j and lane not in own and prep.conflicts[mine, lane].any() for lane in lanes
    )
    opposite = _opposite(prep, jid, j, (out_arm, back_arm), other, admap_defects=admap_defects)
    if opposite or not crossing:
        return Relation.OPPOSITE
    return Relation.CROSSING
