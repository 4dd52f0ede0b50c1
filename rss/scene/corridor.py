"""Same- and opposite-direction road areas along a connecting route.

The connecting route (a path in the :class:`~rss.scene.routes.RouteTree`) gives the
longitudinal range ``k`` of the road area (widened to the vehicles' lanes); every segment
is the cross-section of lanes side by side at that ``k``, restricted to the lateral range
``j`` between the route's start (the ego's lane) and its end (the object's lane), as
ad-rss' ``createNonIntersectionRoadArea`` keeps the lanes with a route lane offset between
0 and the destination offset ("restricted road area")::

        j = -1   ░░░░░░░░░░░░░░░░░░░░░░░░░   dropped (beside the route's ends)
        j =  0   ──ego──▶ ── route ──┐
        j = +1   ───────── ──────── ─┴ object ─▶
                 k = 0      k = 1      k = 2

ad-rss places lanes laterally by their column in the segment (``lanes[0]`` leftmost, a
column as wide as its lanes over all segments). A segment without a lane at the left
end of the range (the lane forks off, or its left lanes belong to another segment) has
its first lane in column 0, beside the wrong lanes of the other segments (Peach-4_8: the
ego on a right-turn lane taken for the lane of a car two lanes to its left, lateral
distance 0). In the default mode (``align``) such a segment is padded on the left with
lane segments of the missing columns' widths (``SegmentPlan.pad_left``), so every lane
sits in the column of its lateral index; the compatibility mode keeps ad-rss' columns.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

from rss.scene.routes import lateral
from rss.scene.segment_plans import (
    SegmentPlan,
    between,
    cut_at,
    cut_window,
    fresh_ends,
    lane_window,
    plan_lanes,
)

if TYPE_CHECKING:
    from rss.scene.lanegraph import Step
    from rss.scene.match_records import Matches
    from rss.scene.memo import SceneMemo
    from rss.scene.prepared import PreparedGraph
    from rss.scene.routes import RouteTree

__all__ = ["admap_beside_ends", "corridor_plans"]


def _cross_section(
    prep: PreparedGraph, base: Step, j: int, j_lo: int, j_hi: int
) -> list[tuple[int, Step]]:
    """Lanes beside ``base`` (at lateral index ``j``) in ``[j_lo, j_hi]``, left to right.

    Each with its lateral index.
    """
    out: list[tuple[int, Step]] = [(j, base)]
    for right, dj in ((False, -1), (True, 1)):
        step: Step | None = base
        jj = j
        while step is not None:
            step = lateral(prep, step[0], forward=step[1], right=right)
            jj += dj
            if step is not None:
                out.append((jj, step))
    return [(jj, s) for jj, s in sorted(out, key=lambda item: item[0]) if j_lo <= jj <= j_hi]


def corridor_plans(  # noqa: PLR0917 - the tree, its target and the two boxes
    prep: PreparedGraph,
    memo: SceneMemo,
    tree: RouteTree,
    target: int,
    matches: Matches,
    boxes: tuple[int, int],
    *,
    align: bool = True,
) -> tuple[list[SegmentPlan], dict[int, tuple[int, float]] | None]:
    """Segment plans from the ego's lane to ``target`` for the two ``boxes`` (ego first).

    ``align``: pad segments to align the lateral columns (module docstring; the default
    mode).

    Also returns where the connecting route touches each box (:func:`cut_between`). The
    uncut layout is a function of the tree path, the occupied tree lanes (in set order) and
    their tree indices; it is memoised per map (``memo``) under exactly those (it repeats
    from frame to frame), only the cuts are made anew.
    """
    path = tree.path(target)
    occupied = tuple({r.lane for box in boxes for r in matches.regions(box) if r.lane in tree.k})
    k, j, fwd = tree.k, tree.j, tree.forward
    key = (
        align,
        tuple(path),
        occupied,
        tuple((k[lane], j[lane], fwd[lane]) for lane in path),
        tuple((k[lane], j[lane], fwd[lane]) for lane in occupied),
    )
    layouts = memo.corridor_layouts
    known = layouts.get(key)
    if known is None:
        if len(layouts) >= _MAX_LAYOUTS:
            layouts.clear()
        layout, pads = _layout(prep, tree, path, occupied)
        if not align:
            pads = tuple(() for _ in layout)
        uncut = tuple(
            SegmentPlan(lanes=list(lanes), pad_left=pad)
            for lanes, pad in zip(layout, pads, strict=True)
        )
        layouts[key] = known = (uncut, plan_lanes(layout))
    uncut, where = known
    cut = between(where, matches, boxes)
    if cut is None:
        plans = fresh_ends(uncut)
        cut_window(plans, matches, boxes)
        return plans, None
    (k0, p0), (k1, p1), rear_box, front_box = cut
    plans = fresh_ends(uncut[k0 : k1 + 1])
    return plans, cut_at(plans, matches, ((0, p0), (k1 - k0, p1), rear_box, front_box))


#: Corridor layouts kept per map before the memo starts afresh.
_MAX_LAYOUTS = 20_000


def _layout(
    prep: PreparedGraph, tree: RouteTree, path: list[int], occupied: tuple[int, ...]
) -> tuple[tuple[tuple[Step, ...], ...], tuple[tuple[Step, ...], ...]]:
    """Lanes of each uncut segment (left to right) along ``path`` (module docstring).

    Also, per segment, the lanes of the nearest other segments for its missing left
    columns (:func:`_pads`).
    """
    ks = [tree.k[lane] for lane in path]
    k_lo, k_hi = min(ks) - 1, max(ks) + 1
    extra = [lane for lane in occupied if k_lo <= tree.k[lane] <= k_hi]
    members = path + [lane for lane in extra if lane not in path]
    k_lo = min(tree.k[lane] for lane in members)
    k_hi = max(tree.k[lane] for lane in members)
    j_lo, j_hi = sorted((tree.j[path[0]], tree.j[path[-1]]))
    sections: list[list[tuple[int, Step]]] = []
    for k in range(k_lo, k_hi + 1):
        bases = [lane for lane in members if tree.k[lane] == k]
        if not bases:
            continue
        base = bases[0]
        lanes = _cross_section(prep, (base, tree.forward[base]), tree.j[base], j_lo, j_hi)
        seen: set[int] = set()
        unique = [s for s in lanes if not (s[1][0] in seen or seen.add(s[1][0]))]  # type: ignore[func-returns-value]
        sections.append(unique or [(tree.j[base], (base, tree.forward[base]))])
    used: set[int] = set()
    out: list[tuple[tuple[int, Step], ...]] = []
    for section in sections:
        kept = tuple(s for s in section if s[1][0] not in used)
        used.update(s[1][0] for s in kept)
        if kept:
            out.append(kept)
    lanes_of = tuple(tuple(s for _, s in kept) for kept in out)
    return lanes_of, tuple(_pads(out, n, j_lo) for n in range(len(out)))


def _pads(sections: list[tuple[tuple[int, Step], ...]], n: int, j_lo: int) -> tuple[Step, ...]:
    """The lanes standing for the columns ``j_lo ..`` left of section ``n``'s first lane.

    Each is the lane at that lateral index in the nearest section holding one.
    """
    order = sorted(range(len(sections)), key=lambda m: abs(m - n))
    pads: list[Step] = []
    for jj in range(j_lo, sections[n][0][0]):
        lane = next((s for m in order for j, s in sections[m] if j == jj), None)
        if lane is None:
            return ()
        pads.append(lane)
    return tuple(pads)


def admap_beside_ends(
    prep: PreparedGraph, tree: RouteTree, target: int, matches: Matches, box: int
) -> list[dict[int, tuple[int, float]]]:
    """Where ad-map's connecting routes between two vehicles beside each other end.

    For an opposing object on the opposite neighbour of an ego lane whose region overlaps
    the ego's longitudinally (no gap to cut the road area at), ad-map still plans a route
    from each region of the ego to the object and drops the two vehicles' regions from
    its ends (``dropStartRegion`` / ``dropEndRegion``) only where the route keeps a
    length. From the region beside the object it runs from the ego's front (its rear
    where the front lies beyond the object's far end) to the object's near end (its far
    end where that lies behind the start); from a region on the lane before (the ego
    straddling the two) from that lane's end to the object's near end. The headings at
    the two ends are the vehicles' route headings, and ad-rss merges the constellations
    of the routes into their worst case (measured with the oracle, Town01 drive
    cross-check, seed 1 drives 1, 4 and 7)::

        road-area direction ──▶      ego rear ┌──ego──┐ front
                                     near  ┌────object─────┐ far
        route from the region beside:            ├───────▶ (ego front to object far end)

    Returns per route ``{0: (ego lane, position), box: (object lane, position)}`` in each
    lane's point order (as :func:`cut_between`); none where the ego occupies no opposite
    neighbour of ``target``.
    """
    g = prep.graph
    region = next((r for r in matches.regions(box) if r.lane == target), None)
    if region is None or target not in tree.forward:
        return []
    fwd_o = tree.forward[target]
    near_o, far_o = lane_window(region.lon_min, region.lon_max, forward=fwd_o)
    at_near = near_o if fwd_o else 1.0 - near_o
    beside = [
        ego
        for ego in matches.regions(0)
        if ego.lane in tree.forward
        and (
            (target == g.left_neighbour[ego.lane] and g.left_opposite[ego.lane])
            or (target == g.right_neighbour[ego.lane] and g.right_opposite[ego.lane])
        )
    ]
    if not beside:
        return []
    ego = beside[0]
    lane = ego.lane
    fwd = tree.forward[lane]
    rear, front = lane_window(ego.lon_min, ego.lon_max, forward=fwd)
    near, far = (_on_lane(prep, (target, fwd_o), p, (lane, fwd)) for p in (near_o, far_o))
    start = front if front < far else rear
    end = near_o if near > start else far_o
    out = [{0: (lane, start if fwd else 1.0 - start), box: (target, end if fwd_o else 1.0 - end)}]
    for r in matches.regions(0):
        before = r.lane in tree.forward and lane in (
            g.successors[r.lane] if tree.forward[r.lane] else g.predecessors[r.lane]
        )
        if before:
            out.append({0: (r.lane, 1.0 if tree.forward[r.lane] else 0.0), box: (target, at_near)})
    return out


def _on_lane(prep: PreparedGraph, source: Step, p: float, lane: Step) -> float:
    """Road-area position on ``lane`` beside road-area position ``p`` of ``source``."""
    t = p if source[1] else 1.0 - p
    guess = p if lane[1] else 1.0 - p
    at = prep.aligner.aligned(source[0], t, lane[0], guess)
    return at if lane[1] else 1.0 - at
