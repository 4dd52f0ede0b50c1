"""Connecting routes (driving direction ignored) and predicted routes (driving direction kept).

Every lane reached from the ego gets a longitudinal index ``k`` (road segments along the
ego's driving direction, 0 = the ego's lane), a lateral index ``j`` (lanes to the right
in that direction are ``j + 1``) and an orientation ``forward`` (its point order runs
along the ego's driving direction)::

        k = -1          k = 0            k = 1
     ┌───────────┬────────────────┬───────────────┐  j = -1  (left)
     │           │   ego ───▶     │               │  j =  0
     └───────────┴────────────────┴───────────────┘  j = +1  (right)

The search is a Dijkstra over successor / predecessor and neighbour links in both
longitudinal directions, bounded by a metric horizon; the shortest path to an object's
lane is its connecting route.
"""

from __future__ import annotations

import bisect
import heapq
import math
from dataclasses import dataclass, field
from typing import TYPE_CHECKING

from rss.model import LaneDrivingDirection
from rss.scene.lanegraph import Step
from rss.scene.memo import memoised

if TYPE_CHECKING:
    from rss.scene.memo import SceneMemo
    from rss.scene.prepared import PreparedGraph

__all__ = [
    "RouteMemo",
    "RouteTree",
    "connect",
    "cross_section",
    "follows_traffic",
    "predict_routes",
]

#: Smallest cost of a lateral step (ad-map's ``cMinimumNeighborDistance``).
_LATERAL_COST_M = 0.1
_MAX_ROUTES = 16


@dataclass
class RouteTree:
    """Shortest connecting routes from the ego's lane (see module docstring).

    Attributes:
        k: Longitudinal index per reached lane.
        j: Lateral index per reached lane.
        forward: Orientation per reached lane.
        parent: Previous lane on the shortest route (-1 for the root).
        cost_m: Route length from the ego's lane.
        first: Per reached lane, the first longitudinal move of its route (+1 ahead, -1
            behind, 0 none: a lateral neighbour of the ego's lane).
        last: The last longitudinal move (+1: the lane is travelled along the road-area
            direction, -1 against it, 0 none).
        root_pos: The root lane and the ego's position on it along the road-area
            direction, in [0, 1].
        root_length_m: The root lane's length as the search measured it.
    """

    k: dict[int, int] = field(default_factory=dict)
    j: dict[int, int] = field(default_factory=dict)
    forward: dict[int, bool] = field(default_factory=dict)
    parent: dict[int, int] = field(default_factory=dict)
    cost_m: dict[int, float] = field(default_factory=dict)
    first: dict[int, int] = field(default_factory=dict)
    last: dict[int, int] = field(default_factory=dict)
    root_pos: tuple[int, float] = (-1, 0.5)
    root_length_m: float = 0.0

    def path(self, lane: int) -> list[int]:
        """Lanes from the root to ``lane`` (which must be reached)."""
        out = [lane]
        while self.parent[out[-1]] >= 0:
            out.append(self.parent[out[-1]])
        return out[::-1]


def lateral(prep: PreparedGraph, lane: int, *, forward: bool, right: bool) -> Step | None:
    """The neighbour of ``lane`` to the right (or left) of the road-area direction."""
    lists = prep.scalars
    use_right = right == forward
    nb = (lists.right_neighbour if use_right else lists.left_neighbour)[lane]
    if nb < 0:
        return None
    opposite = (lists.right_opposite if use_right else lists.left_opposite)[lane]
    return nb, forward != opposite


def cross_section(prep: PreparedGraph, memo: SceneMemo, step: Step) -> tuple[Step, ...]:
    """All lanes side by side with ``step`` (itself included), orientations relative to it.

    Memoised per map (``memo.cross_sections``).
    """
    sections = memo.cross_sections
    found = sections.get(step)
    if found is not None:
        return found
    out = [step]
    for right in (False, True):
        cur: Step | None = step
        while cur is not None:
            cur = lateral(prep, cur[0], forward=cur[1], right=right)
            if cur is not None and all(cur[0] != s[0] for s in out):
                out.append(cur)
            else:
                break
    sections[step] = result = tuple(out)
    return result


def segment_lengths_m(prep: PreparedGraph, memo: SceneMemo) -> list[float]:
    """Per lane, the shortest centre length of its :func:`cross_section` [m].

    ad-map 5.0 takes a route's road segment (all lanes side by side, the opposite ones
    too) as long as its shortest lane, and cuts connecting routes by that length: in a
    junction the inner turn of the opposite direction shortens the route (Town01 drive
    cross-check, junction routes seed 4: drive 8 frames 33-37, a car 135 m behind the
    ego by ad-map's measure, 148 m along its own lanes). Memoised per map.
    """
    lengths = prep.scalars.centre_length_m
    return [
        min(lengths[x] for x, _ in cross_section(prep, memo, (lane, True)))
        for lane in range(len(lengths))
    ]


def longitudinal(prep: PreparedGraph, lane: int, *, forward: bool, ahead: bool) -> list[Step]:
    """Lanes before (``ahead=False``) or after ``lane`` along the road-area direction."""
    g = prep.graph
    links = g.successors[lane] if ahead == forward else g.predecessors[lane]
    return [(nxt, forward) for nxt in links]


def connect(
    prep: PreparedGraph,
    memo: SceneMemo,
    root: int,
    *,
    forward: bool,
    horizon_m: float,
    start: float = 0.5,
    admap_lengths: bool = False,
    behind_only: bool = False,
) -> RouteTree:
    """Dijkstra from ``root`` over all links, ignoring driving directions.

    Costs are metric distances from the ego's position: each search state remembers
    where (parametric, along the road-area direction) it entered its lane, so leaving a
    lane ahead costs the rest of it and leaving it behind costs the part before; a lateral
    step keeps the position and costs, as in ad-map's route expansion
    (``RouteExpander::createNeighbor``), the distance between the two lanes' centre lines
    there (at least :data:`_LATERAL_COST_M`). So a route does not cross to a shorter
    parallel lane, e.g. through the opposite lanes around a junction to the inner one of
    two junction lanes side by side, when the lane changes cost more than the saving.

    Args:
        prep: The prepared lane graph.
        memo: The map's memos.
        root: The ego's lane.
        forward: The root's point order runs along the ego's driving direction.
        horizon_m: Largest route length searched.
        start: The ego's parametric position on ``root`` (its point order).
        admap_lengths: Measure a lane as ad-map 5.0 measures a road segment of a route:
            by the shortest lane side by side with it (:func:`segment_lengths_m`;
            ``[scene] reproduce_adrss_5_0_defects``).
        behind_only: Only routes behind the ego (lateral moves at the root, then moves
            behind): ad-map searches the routes from the object to the ego apart from
            those from the ego to the object, so a lane reached ahead first is still
            reached behind (``FrameContext.behind_tree``).
    """
    tree = RouteTree()
    lengths = (
        memoised(prep, memo, segment_lengths_m) if admap_lengths else prep.scalars.centre_length_m
    )
    pos0 = start if forward else 1.0 - start
    tree.root_pos = (root, pos0)
    tree.root_length_m = float(lengths[root])
    # (cost, counter, lane, k, j, forward, parent, entry position, first move, last move)
    heap: list[tuple[float, int, int, int, int, bool, int, float, int, int]] = [
        (0.0, 0, root, 0, 0, forward, -1, pos0, 0, 0)
    ]
    counter = 0
    while heap:
        cost, _, lane, k, j, fwd, parent, pos, first, last = heapq.heappop(heap)
        if lane in tree.k:
            continue
        tree.k[lane], tree.j[lane], tree.forward[lane] = k, j, fwd
        tree.parent[lane], tree.cost_m[lane] = parent, cost
        tree.first[lane], tree.last[lane] = first, last
        moves: list[tuple[Step, int, int, float, float, int]] = []
        for right, dj in ((True, 1), (False, -1)):
            step = lateral(prep, lane, forward=fwd, right=right)
            if step is not None:
                gap = _centre_gap(prep, memo, (lane, fwd), step, pos)
                moves.append((step, k, j + dj, max(gap, _LATERAL_COST_M), pos, last))
        length = float(lengths[lane])
        for ahead, dk in ((True, 1), (False, -1)):
            if last == -dk or (behind_only and ahead):
                continue  # no turning back: a route keeps its longitudinal direction
            extra = length * ((1.0 - pos) if ahead else pos)
            moves.extend(
                (step, k + dk, j, extra, 0.0 if ahead else 1.0, dk)
                for step in longitudinal(prep, lane, forward=fwd, ahead=ahead)
            )
        for (nxt, nfwd), nk, nj, extra, npos, move in moves:
            if nxt not in tree.k and cost + extra <= horizon_m:
                counter += 1
                item = (cost + extra, counter, nxt, nk, nj, nfwd, lane, npos, first or move, move)
                heapq.heappush(heap, item)
    return tree


def _centre_point(prep: PreparedGraph, lane: int, t: float) -> tuple[float, float]:
    """The centre-line point of ``lane`` at parametric ``t`` (its point order) [m]."""
    sc = prep.scalars
    arc, xy = sc.centre_arc_m[lane], sc.centre_xy_m[lane]
    s = min(max(t, 0.0), 1.0) * arc[-1]
    i = min(max(bisect.bisect_right(arc, s) - 1, 0), len(arc) - 2)
    span = arc[i + 1] - arc[i]
    u = (s - arc[i]) / span if span > 0.0 else 0.0
    (x0, y0), (x1, y1) = xy[i], xy[i + 1]
    return x0 + u * (x1 - x0), y0 + u * (y1 - y0)


def _centre_gap(prep: PreparedGraph, memo: SceneMemo, a: Step, b: Step, pos: float) -> float:
    """Distance between the centre lines of ``a`` and ``b`` at road-area position ``pos`` [m].

    Memoised per map (:func:`~rss.scene.memo.memoised`) at the lane ends (``pos`` 0 or
    1, where most lateral steps start: a finite set of keys per map).
    """
    if pos in (0.0, 1.0):
        return memoised(prep, memo, _centre_distance, a, b, pos)
    return _centre_distance(prep, memo, a, b, pos)


def _centre_distance(prep: PreparedGraph, _memo: SceneMemo, a: Step, b: Step, pos: float) -> float:
    """:func:`_centre_gap`, computed."""
    xa, ya = _centre_point(prep, a[0], pos if a[1] else 1.0 - pos)
    xb, yb = _centre_point(prep, b[0], pos if b[1] else 1.0 - pos)
    return math.hypot(xb - xa, yb - ya)


def follows_traffic(prep: PreparedGraph, lane: int, *, forward: bool) -> bool:
    """Whether travelling ``lane`` with orientation ``forward`` is its traffic direction."""
    direction = prep.scalars.direction[lane]
    if direction == LaneDrivingDirection.Bidirectional:
        return True
    return (direction == LaneDrivingDirection.Positive) == forward


#: Per frame: ``(start, forward, travelled) -> [(lo, hi, routes)]`` (:func:`predict_routes`).
RouteMemo = dict[tuple[int, bool, float], list[tuple[float, float, tuple[tuple[Step, ...], ...]]]]

#: The horizon comparisons of one search, in order: ``(check it continues, its last lane,
#: came out beyond the horizon)``; -1 = the search's start.
Checks = tuple[tuple[int, int, bool], ...]

#: Recent searches kept per start for :func:`predict_routes` (newest first).
_KEPT_SEARCHES = 4


def predict_routes(
    prep: PreparedGraph,
    memo: SceneMemo,
    start: int,
    *,
    forward: bool,
    horizon_m: float,
    travelled_m: float = 0.0,
    frame_routes: RouteMemo | None = None,
) -> list[tuple[Step, ...]]:
    """Routes a vehicle on ``start`` may take in its driving direction, up to ``horizon_m``.

    Branches at every lane with several successors (at most 16 routes); a route ends at
    the horizon or where the map ends. ``travelled_m`` is the part of ``start`` already
    behind the vehicle.

    With ``frame_routes``, a search also records the horizon interval ``[lo, hi)`` in
    which every horizon comparison it made comes out the same; a later call from the same
    start with a horizon inside it returns the stored routes (the search would run
    identically). Across frames, the last searches from each start are kept in ``memo``
    with their comparisons; one whose comparisons all come out the same again (recomputed
    with the same arithmetic) is reused: the search would run identically.
    """
    key = (start, forward, travelled_m)
    if frame_routes is not None:
        for lo, hi, found in frame_routes.get(key, ()):
            if lo <= horizon_m < hi:
                return list(found)
    lengths = prep.scalars.centre_length_m
    recent = memo.route_searches.setdefault((start, forward), [])
    for k, (stored, checks) in enumerate(recent):
        span = _replay(lengths, checks, horizon_m, travelled_m)
        if span is not None:
            routes, (lo, hi) = list(stored), span
            if k:
                recent.insert(0, recent.pop(k))
            break
    else:
        routes, lo, hi, checks = _search(prep, (start, forward), horizon_m, travelled_m)
        recent.insert(0, (tuple(routes), checks))
        del recent[_KEPT_SEARCHES:]
    if frame_routes is not None:
        frame_routes.setdefault(key, []).append((lo, hi, tuple(routes)))
    return routes


def _replay(
    lengths: list[float], checks: Checks, horizon_m: float, travelled_m: float
) -> tuple[float, float] | None:
    """``(lo, hi)`` of :func:`_search` if its ``checks`` all come out the same, else None."""
    dists: list[float] = []
    lo, hi = -math.inf, math.inf
    for parent, lane, beyond in checks:
        dist = (-travelled_m if parent < 0 else dists[parent]) + lengths[lane]
        if (dist > horizon_m) != beyond:
            return None
        if beyond:
            hi = min(hi, dist)
        else:
            lo = max(lo, dist)
        dists.append(dist)
    return lo, hi


def _search(
    prep: PreparedGraph, first: Step, horizon_m: float, travelled_m: float
) -> tuple[list[tuple[Step, ...]], float, float, Checks]:
    """Depth-first route search, the horizon interval with the same comparisons, and them."""
    routes: list[tuple[Step, ...]] = []
    stack: list[tuple[tuple[Step, ...], float, int]] = [((first,), -travelled_m, -1)]
    checks: list[tuple[int, int, bool]] = []
    lengths = prep.scalars.centre_length_m
    lo, hi = -math.inf, math.inf
    while stack and len(routes) < _MAX_ROUTES:
        route, dist, parent = stack.pop()
        lane, fwd = route[-1]
        nxt = [s for s in longitudinal(prep, lane, forward=fwd, ahead=True) if s not in route]
        dist += lengths[lane]
        if not nxt:
            routes.append(route)
            continue
        beyond = dist > horizon_m
        checks.append((parent, lane, beyond))
        if beyond:
            hi = min(hi, dist)
            routes.append(route)
            continue
        lo = max(lo, dist)
        at = len(checks) - 1
        stack.extend(((*route, s), dist, at) for s in nxt)
    return routes, lo, hi, tuple(checks)
