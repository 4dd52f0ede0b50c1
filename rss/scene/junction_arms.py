"""The arms of an intersection as ad-map names them, seen from a route's incoming lane.

ad-map orders the lanes entering and leaving a junction by the direction of their chord
(start to end, in driving direction) relative to the route's incoming lane, in four
90-degree sectors::

                 LEFT
                  ▲
    STRAIGHT  ◀── ┼ ──▶  (U-turn: back where the route came from)
                  ▼
                RIGHT

Junctions are connected intersection lanes (``rss.scene.junctions``, built by
``prepare``); this module also holds the driving-direction links of a lane that the arm
and relation rules follow (``rss.scene.junction_relations``).
"""

from __future__ import annotations

import enum
import math
from typing import TYPE_CHECKING

from rss.model import LaneDrivingDirection
from rss.scene.admap_heading import lane_chord_heading
from rss.scene.memo import memoised

if TYPE_CHECKING:
    from rss.scene.memo import SceneMemo
    from rss.scene.prepared import PreparedGraph

__all__ = ["Arm", "entries", "exits", "inside_successors", "intersection_arms"]


class Arm(enum.Enum):
    """ad-map's turn directions, used to name the arms of an intersection."""

    UNKNOWN = "unknown"
    RIGHT = "right"
    STRAIGHT = "straight"
    LEFT = "left"
    UTURN = "u-turn"


def _linked(prep: PreparedGraph, lane: int, *, ahead: bool) -> set[int]:
    """Lanes the traffic of ``lane`` leads into (``ahead``) or comes from."""
    g = prep.graph
    code = prep.scalars.direction[lane]
    if code == LaneDrivingDirection.Positive:
        return set(g.successors[lane] if ahead else g.predecessors[lane])
    if code == LaneDrivingDirection.Negative:
        return set(g.predecessors[lane] if ahead else g.successors[lane])
    return {*g.predecessors[lane], *g.successors[lane]}


def entries(prep: PreparedGraph, lane: int) -> set[int]:
    """Lanes whose traffic leads into ``lane``."""
    return _linked(prep, lane, ahead=False)


def exits(prep: PreparedGraph, lane: int) -> set[int]:
    """Lanes the traffic of ``lane`` leads into."""
    return _linked(prep, lane, ahead=True)


def inside_successors(prep: PreparedGraph, jid: list[int], j: int, lane: int) -> set[int]:
    """Lanes of junction ``j`` reachable from ``lane`` in driving direction inside ``j``."""
    found: set[int] = set()
    todo = [b for b in exits(prep, lane) if jid[b] == j]
    while todo:
        b = todo.pop()
        if b not in found:
            found.add(b)
            todo.extend(c for c in exits(prep, b) if jid[c] == j)
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
    prep: PreparedGraph, memo: SceneMemo, j: int, incoming: int, *, admap_defects: bool = False
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
        memo: The map's memos (the defective chord headings are kept there).
        j: Junction index (``prep.junction_ids``).
        incoming: The lane through which the route enters the junction.
        admap_defects: Reproduce ad-map 5.0 (``[scene] reproduce_adrss_5_0_defects``): its
            defective chord headings (:func:`rss.scene.admap_heading.lane_chord_heading`)
            and relative angles wrapped once only.
    """
    jid = prep.junction_list
    members = [lane for lane, k in enumerate(jid) if k == j]
    entering = {e for lane in members for e in entries(prep, lane) if jid[e] != j}
    leaving = {x for lane in members for x in exits(prep, lane) if jid[x] != j}
    if admap_defects:
        ref = memoised(prep, memo, _chord_heading, incoming)
        arms = {
            lane: _bucket_wrapped_once(memoised(prep, memo, _chord_heading, lane) - ref)
            for lane in entering
        }
        arms.update(
            {
                lane: _bucket_wrapped_once(
                    memoised(prep, memo, _chord_heading, lane) - (ref + math.pi)
                )
                for lane in leaving
            }
        )
        return arms
    ref = _lane_angle(prep, incoming)
    arms = {lane: _bucket(_lane_angle(prep, lane) - ref) for lane in entering}
    arms.update({lane: _bucket(_lane_angle(prep, lane) - ref - math.pi) for lane in leaving})
    return arms


def _chord_heading(prep: PreparedGraph, _memo: SceneMemo, lane: int) -> float:
    """:func:`~rss.scene.admap_heading.lane_chord_heading` in the memo's signature."""
    return lane_chord_heading(prep, lane)
