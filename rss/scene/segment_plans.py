"""Segment plans: the road segments of a road area before conversion, and their cuts.

A :class:`SegmentPlan` is one road segment before conversion: its lanes left to right
(in the road-area direction) with their orientation, and the parametric window
``[p0, p1]`` of the road-area direction it keeps. The first and last segments are cut at
the rear of the rear vehicle and at the front of the front vehicle, so no length
uncertainty outside the two vehicles stretches them ("restricted road area")::

      p0 (rear vehicle's rear)                 p1 (front vehicle's front)
      │ ┌──┐                                     ┌──┐ │
   ───┼─┤  ├─────────── segment k ... k' ────────┤  ├─┼───▶ road-area direction
      │ └──┘                                     └──┘ │

Regions are mapped from the lane's point order to the road-area direction (reversed lanes
flip lon and lat) and then into the window. ``rss.scene.roadarea`` converts the plans.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, NamedTuple

from rss.model import RoadSegment, RoadSegmentType
from rss.scene.lanegraph import Step  # noqa: TC001 - dataclass field types, read at run time when compiled (mypyc)

if TYPE_CHECKING:
    from collections.abc import Sequence

    from rss.scene.match_records import Matches

__all__ = [
    "Between",
    "BuiltSegment",
    "PlacedLane",
    "SegmentPlan",
    "between",
    "cut_at",
    "cut_between",
    "cut_window",
    "fresh_ends",
    "lane_window",
    "plan_lanes",
]


@dataclass(slots=True)
class SegmentPlan:
    """One road segment before conversion.

    Attributes:
        lanes: ``(lane, forward)`` left to right in the road-area direction.
        segment_type: Normal or Intersection.
        before_m: Intersection only: length before the intersecting area.
        after_m: Intersection only: length after it.
        p0: Kept window start (road-area direction, parametric).
        p1: Kept window end.
        whole: ``(id offset, conversion)`` of the uncut plan, kept by :func:`build_road`
            (plans shared by memos skip the lookup; only ``p0`` / ``p1`` / ``anchors``
            may change).
        anchors: The lanes cut exactly at ``p0`` and at ``p1`` (-1: none, every lane is
            cut at the same fraction); the other lanes are cut where ad-map aligns them
            (``rss.scene.align``).
        pad_left: Lanes of other segments standing, left to right, for the lateral
            columns this segment has no lane in, left of its first lane (default mode:
            the road area's lateral frame is aligned by columns, ``rss.scene.corridor``);
            converted into lane segments of their widths that no vehicle occupies.
    """

    lanes: list[Step]
    segment_type: RoadSegmentType = RoadSegmentType.Normal
    before_m: float = 0.0
    after_m: float = 0.0
    p0: float = 0.0
    p1: float = 1.0
    whole: tuple[int, BuiltSegment] | None = field(default=None, repr=False, compare=False)
    anchors: tuple[int, int] = (-1, -1)
    pad_left: tuple[Step, ...] = ()


def fresh_ends(plans: Sequence[SegmentPlan], *, last: bool = True) -> list[SegmentPlan]:
    """``plans`` as a new list whose first and last plans (the ones cuts change) are copies.

    For plans shared by memos: the others are handed out as they are (so is the last one
    without ``last``, for cuts that keep the end).
    """
    out = list(plans)
    for k in {0, len(out) - 1 if last else 0} if out else ():
        p = out[k]
        out[k] = SegmentPlan(
            p.lanes,
            p.segment_type,
            p.before_m,
            p.after_m,
            p.p0,
            p.p1,
            p.whole,
            p.anchors,
            p.pad_left,
        )
    return out


class PlacedLane(NamedTuple):
    """Where a map lane sits in one road area.

    Attributes:
        lane_id: Id in the road area.
        forward: Point order runs along the road-area direction.
        p0: Window start.
        p1: Window end.
    """

    lane_id: int
    forward: bool
    p0: float
    p1: float


def _road_param(
    lo: float, hi: float, *, forward: bool
) -> tuple[float, float]:  # lane point order -> road-area direction
    return (lo, hi) if forward else (1.0 - hi, 1.0 - lo)


def lane_window(p0: float, p1: float, *, forward: bool) -> tuple[float, float]:
    """A road-area window ``[p0, p1]`` of a lane as a window along its point order."""
    return _road_param(p0, p1, forward=forward)


def plan_lanes(plans: Sequence[Sequence[Step]]) -> dict[int, tuple[int, bool]]:
    """Segment index and orientation of each lane of segment plans' lanes, by lane."""
    return {lane: (k, fwd) for k, lanes in enumerate(plans) for lane, fwd in lanes}


def _extent(
    where: dict[int, tuple[int, bool]], matches: Matches, box: int
) -> tuple[tuple[int, float], tuple[int, float]] | None:
    """``((segment, param) of the rear, (segment, param) of the front)`` of a box."""
    ends: list[tuple[int, float]] = []
    for region in matches.regions(box):
        hit = where.get(region.lane)
        if hit is not None:
            lo, hi = _road_param(region.lon_min, region.lon_max, forward=hit[1])
            ends += [(hit[0], lo), (hit[0], hi)]
    return (min(ends), max(ends)) if ends else None


#: Where a road area between two boxes is cut: ``((k0, p0), (k1, p1), rear box, front box)``
#: keeps segments ``k0..k1``, from ``p0`` of the first to ``p1`` of the last.
Between = tuple[tuple[int, float], tuple[int, float], int, int]


def between(
    where: dict[int, tuple[int, bool]], matches: Matches, boxes: tuple[int, int]
) -> Between | None:
    """Where :func:`cut_between` cuts plans with lanes ``where`` (from :func:`plan_lanes`)."""
    a, b = (_extent(where, matches, box) for box in boxes)
    if a is None or b is None:
        return None
    (rear, front), (rear_box, front_box) = (
        ((a, b), boxes) if a[1] <= b[0] else ((b, a), boxes[::-1])
    )
    if rear[1] >= front[0]:
        return None
    return rear[1], front[0], rear_box, front_box


def cut_between(
    plans: list[SegmentPlan], matches: Matches, boxes: tuple[int, int]
) -> dict[int, tuple[int, float]] | None:
    """Keep only the road between two boxes, as ad-rss' connecting-route road areas do.

    The road area then starts at the front of the rear vehicle and ends at the rear of the
    front vehicle (both keep zero-length regions at the ends), so no length uncertainty
    of the lanes under the vehicles stretches the gap. Returns, per box, the route end it
    touches as ``(lane, parametric position in its point order)``, or ``None`` (plans
    unchanged) where the boxes overlap longitudinally.
    """
    cut = between(plan_lanes([plan.lanes for plan in plans]), matches, boxes)
    return None if cut is None else cut_at(plans, matches, cut)


def cut_at(
    plans: list[SegmentPlan], matches: Matches, cut: Between
) -> dict[int, tuple[int, float]]:
    """Cut ``plans`` in place where :func:`between` says; the route ends at each box.

    Each end is cut exactly in the lane of the box region that reaches furthest towards
    the other box, the lanes beside it where ad-map aligns them (``SegmentPlan.anchors``).
    """
    (k0, p0), (k1, p1), rear_box, front_box = cut
    del plans[k1 + 1 :]
    del plans[:k0]
    plans[0].p0 = min(p0, 1.0 - 0.001)
    plans[-1].p1 = max(p1, plans[-1].p0 + 0.001)
    first = _anchor(plans[0], matches, rear_box, front=True)
    last = _anchor(plans[-1], matches, front_box, front=False)
    plans[0].anchors = (first, plans[0].anchors[1])
    plans[-1].anchors = (plans[-1].anchors[0], last)
    ends = {}
    for box, plan, at in ((rear_box, plans[0], plans[0].p0), (front_box, plans[-1], plans[-1].p1)):
        lanes = {region.lane for region in matches.regions(box)}
        lane, fwd = plan.lanes[0]
        for step in plan.lanes:
            if step[0] in lanes:
                lane, fwd = step
                break
        ends[box] = (lane, at if fwd else 1.0 - at)
    return ends


def _anchor(plan: SegmentPlan, matches: Matches, box: int, *, front: bool) -> int:
    """The lane of ``plan`` where ``box`` reaches furthest forward (``front``) or back."""
    lanes = dict(plan.lanes)
    best, lane = -math.inf, -1
    for region in matches.regions(box):
        fwd = lanes.get(region.lane)
        if fwd is not None:
            lo, hi = _road_param(region.lon_min, region.lon_max, forward=fwd)
            reach = hi if front else -lo
            if reach > best:
                best, lane = reach, region.lane
    return lane


def cut_window(
    plans: list[SegmentPlan],
    matches: Matches,
    boxes: tuple[int, ...],
    *,
    cut_end: bool = True,
    cut_intersection: bool = False,
) -> None:
    """Cut the first (and last) segment at the outermost extent of ``boxes`` (in place).

    Intersection segments are kept whole unless ``cut_intersection`` (ad-rss 5.0 cuts a
    vehicle's intersection road area at its rear also on its conflict lane; reproduced
    under ``[scene] reproduce_adrss_5_0_defects``).
    """
    if not plans:
        return
    first, last = plans[0], plans[-1]
    normal = RoadSegmentType.Normal
    start = dict(first.lanes) if cut_intersection or first.segment_type == normal else {}
    end = dict(last.lanes) if cut_end and last.segment_type == normal else {}
    if not (start or end):
        return
    lo = hi = math.nan
    for box in boxes:
        for region in matches.regions(box):
            fwd = start.get(region.lane)
            if fwd is not None:
                v = region.lon_min if fwd else 1.0 - region.lon_max
                lo = v if not v >= lo else lo  # NaN-aware minimum
            fwd = end.get(region.lane)
            if fwd is not None:
                v = region.lon_max if fwd else 1.0 - region.lon_min
                hi = v if not v <= hi else hi
    if not math.isnan(lo):
        first.p0 = max(0.0, min(lo, 1.0 - 0.001))
    if not math.isnan(hi):
        last.p1 = min(1.0, max(hi, last.p0 + 0.001))


#: A converted plan: road segment, placed lanes, speed limits of its lanes (NaN: none), and
#: each lane's window along its point order ``(lane, start, end)``.
BuiltSegment = tuple[
    RoadSegment,
    tuple[tuple[int, PlacedLane], ...],
    tuple[float, ...],
    tuple[tuple[int, float, float], ...],
]
