"""Per-object decisions of scene creation, following ad-rss' ``appendStructuredConstellations``.

One :class:`FrameContext` holds what a frame shares (matches, the route tree from the ego,
headings); :func:`object_constellations` builds the constellations of one object from its
connecting routes (``rss.scene.connecting``)::

    object follows the ego, or ego follows it on an ego route -> SameDirection
    no intersection on the route: opposing -> OppositeDirection
                                  merging  -> IntersectionSamePriority
    through intersections, per (ego route, object route, intersection on the ego route):
      object route crosses the ego's intersection lanes      -> Intersection* (priority)
      passes (from the ego's exit arm back to its entry arm)
        or does not cross                                     -> OppositeDirection (opposing)
      same arm as the ego                                     -> Intersection* (merging only)

Predicted routes reach ``ego length + longest connecting route + object length``.
Constellations are deduplicated by (type, lane pair) / (type, target lane).
"""

from __future__ import annotations

import dataclasses
import logging
import math
from dataclasses import dataclass

import numpy as np

from rss.model import ConstellationType
from rss.scene.connecting import Connecting, Kind, connecting_routes
from rss.scene.corridor import admap_beside_ends, corridor_plans
from rss.scene.cut_areas import cut_area_spans
from rss.scene.frame import BuiltConstellation, FrameContext, ego_routes
from rss.scene.junction_pairs import IntersectionPair, intersection_pair
from rss.scene.junction_relations import Relation, junctions_on, relation
from rss.scene.lanegraph import Step  # noqa: TC001 - dataclass field types, read at run time when compiled (mypyc)
from rss.scene.routes import cross_section, follows_traffic
from rss.scene.segment_plans import SegmentPlan, cut_between, cut_window, fresh_ends

__all__ = ["object_constellations"]

_LOG = logging.getLogger(__name__)

#: Following along a predicted route needs headings within 45 degrees.
_FOLLOWING_COS = float(np.cos(np.pi / 4))


def _intersection(
    f: FrameContext, i: int, pair: IntersectionPair, kind: ConstellationType | None = None
) -> BuiltConstellation | None:
    """The intersection constellation of one (ego route, object route) pair.

    The conflict is the first pair of overlapping / merging intersection lanes (else the
    first shared lane); ``kind`` overrides the priority-derived type (merging routes).
    The memoised uncut plans are shared: only their ends are copied and cut.
    """
    compat = f.settings.reproduce_adrss_5_0_defects
    ego_plans = fresh_ends(pair.ego_plans, last=compat)
    obj_plans = fresh_ends(pair.obj_plans, last=compat)
    cut_window(ego_plans, f.matches, (0,), cut_end=False, cut_intersection=compat)
    cut_window(obj_plans, f.matches, (i + 1,), cut_end=False, cut_intersection=compat)
    if compat and not cut_area_spans(f.prep, f.memo, ego_plans[-1], obj_plans[-1]):
        return None
    return f.constellation(pair.priority if kind is None else kind, i, ego_plans, obj_plans)


def _on_routes(f: FrameContext, box: int, routes: list[tuple[Step, ...]]) -> bool:
    """Whether a lane the box touches lies on one of ``routes``.

    Routes include their same-direction neighbour lanes (ad-map's SameDrivingDirection).
    """
    lanes = {r.lane for r in f.matches.regions(box)}
    return any(
        lane in lanes
        for route in routes
        for step in route
        for lane, fwd in cross_section(f.prep, f.memo, step)
        if follows_traffic(f.prep, lane, forward=fwd)
    )


def _route_to(routes: list[tuple[Step, ...]], lane: int) -> tuple[Step, ...] | None:
    """The shortest prefix of one of ``routes`` that reaches ``lane``."""
    best: tuple[Step, ...] | None = None
    for route in routes:
        for idx, (step_lane, _) in enumerate(route):
            if step_lane == lane:
                if best is None or idx + 1 < len(best):
                    best = route[: idx + 1]
                break
    return best


def _following(
    f: FrameContext, i: int, ego_routes: list[tuple[Step, ...]], obj_routes: list[tuple[Step, ...]]
) -> BuiltConstellation | None:
    """SameDirection along a route if one vehicle is on the other's predicted route."""
    box = i + 1
    candidates = []
    for lane, _, _ in f.starts(box):
        route = _route_to(ego_routes, lane)
        if route is not None:
            candidates.append((route, route[-1]))
    for lane, _, _ in f.starts(0):
        route = _route_to(obj_routes, lane)
        if route is not None:
            candidates.append((route, route[0]))
    for route, (lane, fwd) in sorted(candidates, key=lambda c: len(c[0])):
        heading = f.headings[box][lane] + (0.0 if fwd else np.pi)
        if math.cos(float(f.objects.yaw_rad[i]) - heading) < _FOLLOWING_COS:
            continue
        plans = [SegmentPlan(lanes=[step]) for step in route]
        ends = cut_between(plans, f.matches, (0, box))
        if ends is None:
            cut_window(plans, f.matches, (0, box))
        c = f.constellation(ConstellationType.SameDirection, i, plans, None, ends)
        if c is not None:
            return c
    return None


def _corridor(
    f: FrameContext, i: int, cr: Connecting, kind: ConstellationType
) -> list[BuiltConstellation | None]:
    """Same/opposite-direction constellations along the connecting route ``cr``.

    ad-rss 5.0's speeds differ from each vehicle's own road direction in two cases: it
    swaps the two vehicles' route headings on a route of an object following the ego,
    and resolves the speeds of an opposing object beside the ego along the ends of
    ad-map's routes between the two, one constellation per route
    (:func:`admap_beside_ends`). Under ``[scene] reproduce_adrss_5_0_defects`` those are
    the constellations; in the default mode they are added to the one with the vehicles'
    own headings where their speeds differ, and the engine merges them into their worst
    case (speed intervals joined): never safe where ad-rss 5.0 is dangerous by these
    speeds (docs/rss_scene.md, deviation table).
    """
    tree = f.tree if cr.tree is None else cr.tree
    compat = f.settings.reproduce_adrss_5_0_defects
    plans, ends = corridor_plans(
        f.prep, f.memo, tree, cr.target, f.matches, (0, i + 1), align=not compat
    )
    adrss: list[BuiltConstellation | None] = []
    if ends is None and cr.kind == Kind.OPPOSING:
        routes = admap_beside_ends(f.prep, tree, cr.target, f.matches, i + 1)
        adrss = [f.constellation(kind, i, plans, None, e) for e in routes]
    elif ends and cr.kind == Kind.OBJECT_FOLLOWS:
        adrss = [f.constellation(kind, i, plans, None, ends, swap_headings=True)]
    if compat and adrss:
        return adrss
    own: BuiltConstellation | None = f.constellation(kind, i, plans, None, ends)
    if own is None:
        return [None]
    out: list[BuiltConstellation | None] = [own]
    out.extend(c for c in adrss if c is not None and not _same_speeds(own, c))
    return out


#: Lane-frame speeds closer than this are the same (rounding of headings on a straight
#: lane) [m/s].
_SAME_SPEED_MPS = 1e-6


def _same_speeds(a: BuiltConstellation, b: BuiltConstellation) -> bool:
    """Whether two constellations' lane-frame speed intervals agree (both vehicles)."""
    pairs = (
        (a.constellation.ego.speed, b.constellation.ego.speed),
        (a.constellation.other.speed, b.constellation.other.speed),
    )
    return all(
        abs(getattr(x, name) - getattr(y, name)) < _SAME_SPEED_MPS
        for x, y in pairs
        for name in ("lon_min_mps", "lon_max_mps", "lat_min_mps", "lat_max_mps")
    )


@dataclass(slots=True)
class _Pair:
    """The routes of one ego/object pair and the constellations found so far."""

    f: FrameContext
    i: int
    ego_routes: list[tuple[Step, ...]]
    obj_routes: list[tuple[Step, ...]]
    green: frozenset[int]
    reach_m: float
    out: dict[tuple[object, ...], BuiltConstellation | None] = dataclasses.field(
        default_factory=dict
    )

    def add_corridor(self, cr: Connecting, kind: ConstellationType) -> None:
        """A same/opposite-direction constellation along the connecting route.

        SameDirection falls back to a predicted route through both vehicles.
        """
        key = (kind, cr.target, -1 if cr.tree is None else cr.tree.root_pos[0])
        if key in self.out:
            return
        c, *more = _corridor(self.f, self.i, cr, kind)
        if c is None and kind == ConstellationType.SameDirection:
            if not self.obj_routes:
                self.obj_routes = self.f.routes(self.i + 1, self.reach_m)
            c = _following(self.f, self.i, self.ego_routes, self.obj_routes)
        self.out[key] = c
        for n, extra in enumerate(more):
            self.out[(*key, n)] = extra

    def add_intersection(
        self, routes: tuple[tuple[Step, ...], tuple[Step, ...]], kind: ConstellationType | None
    ) -> None:
        pair = intersection_pair(self.f.prep, self.f.memo, *routes, self.green)
        if pair is None:
            return
        key = (kind, pair.ego_lane, pair.obj_lane)
        if key not in self.out:
            self.out[key] = _intersection(self.f, self.i, pair, kind)


def _through(p: _Pair, cr: Connecting) -> None:
    """ad-rss' analysis of a connecting route through intersections (per route pair)."""
    for er in p.ego_routes:
        spans = junctions_on(p.f.prep, p.f.memo, er)
        if not spans and cr.kind == Kind.MERGING:
            for orr in p.obj_routes:
                p.add_intersection((er, orr), ConstellationType.IntersectionSamePriority)
        elif spans or cr.kind == Kind.OPPOSING:
            for orr in p.obj_routes:
                _route_pair(p, cr, (er, orr), spans)


def _route_pair(
    p: _Pair,
    cr: Connecting,
    routes: tuple[tuple[Step, ...], tuple[Step, ...]],
    spans: list[tuple[int, int, int]],
) -> None:
    """One (ego route, object route) pair at the intersections of the ego route.

    Without intersections on the ego route (it starts inside one), the object route's
    intersections are analysed against the ego route instead; without any, the pair is
    an opposite-direction one.
    """
    base, other = routes
    if not spans:
        spans = junctions_on(p.f.prep, p.f.memo, other)
        if not spans:
            p.add_corridor(cr, ConstellationType.OppositeDirection)
            return
        base, other = other, base
    for span in spans:
        rel = relation(
            p.f.prep,
            p.f.memo,
            base,
            span,
            other,
            admap_defects=p.f.settings.reproduce_adrss_5_0_defects,
        )
        if rel == Relation.NONE:
            continue
        if rel == Relation.CROSSING or cr.kind == Kind.MERGING:
            p.add_intersection(routes, None)
        elif rel == Relation.OPPOSITE and cr.kind == Kind.OPPOSING:
            p.add_corridor(cr, ConstellationType.OppositeDirection)


def _debug_object(f: FrameContext, box: int, routes: list[Connecting]) -> None:
    for cr in routes:
        t = f.tree if cr.tree is None else cr.tree
        path = (
            " > ".join(
                f"{f.prep.graph.ids[x]}[k{t.k[x]} {'f' if t.forward[x] else 'r'}"
                f" {t.first[x]}{t.last[x]}]"
                for x in t.path(cr.target)
            )
            if cr.target >= 0
            else "-"
        )
        _LOG.debug(
            "box %d: %s %.2f m through=%s: %s",
            box,
            cr.kind.name,
            cr.length_m,
            cr.through_intersection,
            path,
        )


def object_constellations(
    f: FrameContext,
    i: int,
    horizon_m: float,
    green: frozenset[int],
) -> list[BuiltConstellation]:
    """All constellations between the ego and object ``i`` (see module docstring)."""
    box = i + 1
    routes = connecting_routes(f, box, horizon_m)
    if _LOG.isEnabledFor(logging.DEBUG):
        _debug_object(f, box, routes)
    if not routes:
        return []
    reach = f.ego.length_m + max(cr.length_m for cr in routes) + float(f.objects.length_m[i])
    p = _Pair(f, i, ego_routes(f, reach), [], green, reach)
    for cr in routes:
        if cr.kind == Kind.OBJECT_FOLLOWS or (
            cr.kind == Kind.EGO_FOLLOWS and _on_routes(f, box, p.ego_routes)
        ):
            p.add_corridor(cr, ConstellationType.SameDirection)
        elif not cr.through_intersection:
            if cr.kind == Kind.OPPOSING:
                p.add_corridor(cr, ConstellationType.OppositeDirection)
            elif cr.kind == Kind.MERGING:
                p.obj_routes = p.obj_routes or f.routes(box, reach)
                for er in p.ego_routes:
                    for orr in p.obj_routes:
                        p.add_intersection((er, orr), ConstellationType.IntersectionSamePriority)
        else:
            p.obj_routes = p.obj_routes or f.routes(box, reach)
            _through(p, cr)
    return [c for c in p.out.values() if c is not None]
