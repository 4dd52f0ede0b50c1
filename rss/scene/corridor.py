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
    plan_lanes,
)

if TYPE_CHECKING:
    from rss.scene.lanegraph import Step
    from rss.scene.match_records import Matches
    from rss.scene.memo import SceneMemo
    from rss.scene.prepared import PreparedGraph
    from rss.scene.routes import RouteTree

__all__ = ["corridor_plans"]


def _cross_section(prep: PreparedGraph, base: Step, j: int, j_lo: int, j_hi: int) -> list[Step]:
    """Lanes beside ``base`` (at lateral index ``j``) within ``[j_lo, j_hi]``, left to right."""
    out: list[tuple[int, Step]] = [(j, base)]
    for right, dj in ((False, -1), (True, 1)):
        step: Step | None = base
        jj = j
        while step is not None:
            step = lateral(prep, step[0], forward=step[1], right=right)
            jj += dj
            if step is not None:
                out.append((jj, step))
    return [s for jj, s in sorted(out, key=lambda item: item[0]) if j_lo <= jj <= j_hi]


def corridor_plans(  # noqa: PLR0917 - the tree, its target and the two boxes
    prep: PreparedGraph,
    memo: SceneMemo,
    tree: RouteTree,
    target: int,
    matches: Matches,
    boxes: tuple[int, int],
) -> tuple[list[SegmentPlan], dict[int, tuple[int, float]] | None]:
    """Segment plans from the ego's lane to ``target`` for the two ``boxes`` (ego first).

    Also returns where the connecting route touches each box (:func:`cut_between`). The
    uncut layout is a function of the tree path, the occupied tree lanes (in set order) and
    their tree indices; it is memoised per map (``memo``) under exactly those (it repeats
    from frame to frame), only the cuts are made anew.
    """
    path = tree.path(target)
    occupied = tuple({r.lane for box in boxes for r in matches.regions(box) if r.lane in tree.k})
    k, j, fwd = tree.k, tree.j, tree.forward
    key = (
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
        layout = _layout(prep, tree, path, occupied)
        uncut = tuple(SegmentPlan(lanes=list(lanes)) for lanes in layout)
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
) -> tuple[tuple[Step, ...], ...]:
    """Lanes of each uncut segment (left to right) along ``path`` (see module docstring)."""
    ks = [tree.k[lane] for lane in path]
    k_lo, k_hi = min(ks) - 1, max(ks) + 1
    extra = [lane for lane in occupied if k_lo <= tree.k[lane] <= k_hi]
    members = path + [lane for lane in extra if lane not in path]
    k_lo = min(tree.k[lane] for lane in members)
    k_hi = max(tree.k[lane] for lane in members)
    j_lo, j_hi = sorted((tree.j[path[0]], tree.j[path[-1]]))
    sections: list[list[Step]] = []
    for k in range(k_lo, k_hi + 1):
        bases = [lane for lane in members if tree.k[lane] == k]
        if not bases:
            continue
        base = bases[0]
        lanes = _cross_section(prep, (base, tree.forward[base]), tree.j[base], j_lo, j_hi)
        seen: set[int] = set()
        unique = [s for s in lanes if not (s[0] in seen or seen.add(s[0]))]  # type: ignore[func-returns-value]
        sections.append(unique or [(base, tree.forward[base])])
    used: set[int] = set()
    out: list[tuple[Step, ...]] = []
    for section in sections:
        kept = tuple(s for s in section if s[0] not in used)
        used.update(s[0] for s in kept)
        if kept:
            out.append(kept)
    return tuple(out)
