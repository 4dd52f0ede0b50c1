"""Scene creation: ego + objects on a lane graph -> ``rss.model`` constellations.

Per frame (ad-rss ``RssWorldModelCreation.appendConstellations`` for every object)::

    match boxes ─▶ connecting routes from the ego (direction ignored) ─▶ per object:
      far apart (> max(stop_ego + stop_obj, 100 m))              -> NotRelevant
      the rest: ``rss.scene.pairs.object_constellations``


The result feeds ``rss.batch.stack_constellations`` and ``rss.engine.check_frame``.
"""

from __future__ import annotations

import math
from typing import TYPE_CHECKING

import numpy as np

from rss.scene.boundaries import boundary_constellations
from rss.scene.frame import FrameContext, ego_routes, lane_headings
from rss.scene.inputs import Scene, conservative_stop_m
from rss.scene.match_records import BoxArrays
from rss.scene.matching import match_boxes
from rss.scene.memo import SceneMemo
from rss.scene.pairs import object_constellations
from rss.scene.routes import RouteTree, connect

if TYPE_CHECKING:
    from rss.model import Constellation
    from rss.params import SceneSettings
    from rss.scene.inputs import SceneEgo, SceneObjects
    from rss.scene.match_records import Matches
    from rss.scene.prepared import PreparedGraph

__all__ = ["create_scene", "more_roots", "scene_boxes"]

_MIN_RELEVANT_M = 100.0
#: A lane at right angles to the ego's heading (within this cosine) gives no route root.
_ACROSS_COS = 1e-6


def scene_boxes(ego: SceneEgo, objects: SceneObjects) -> BoxArrays:
    """The boxes map matching works on: box 0 is the ego, box ``i + 1`` object ``i``."""
    return BoxArrays(
        x_m=np.concatenate([[ego.x_m], objects.x_m]),
        y_m=np.concatenate([[ego.y_m], objects.y_m]),
        yaw_rad=np.concatenate([[ego.yaw_rad], objects.yaw_rad]),
        length_m=np.concatenate([[ego.length_m], objects.length_m]),
        width_m=np.concatenate([[ego.width_m], objects.width_m]),
    )


def more_roots(
    prep: PreparedGraph, matches: Matches, ego: SceneEgo
) -> list[tuple[int, bool, float]]:
    """Lanes the ego occupies besides the anchor that no link joins to it.

    ad-map starts connecting routes from every lane the ego's box occupies; in a junction
    the ego overlaps lanes that are neither neighbours nor successors of its anchor, and
    a route tree from the anchor alone misses what is reached only from them (Town01
    drive cross-check: seed 1 drive 6 frame 22, the anchor switches from 2180149 to the
    overlapping 2010149 and the car behind on 180149, a predecessor of 2180149 only, gets
    no connecting route; seed 2 drive 7 frames 33-35, the car ahead on 100151 is reached
    from the overlapping 2320151 only). Lanes at right angles to the heading are left
    out (no orientation).

    Returns:
        ``(lane, forward, start)`` per further root: ``forward`` whether the ego heads
        along the lane's point order, ``start`` the middle of its region there (point
        order).
    """
    anchor = matches.anchors[0]
    g = prep.graph
    linked = {
        anchor,
        *g.successors[anchor],
        *g.predecessors[anchor],
        int(g.left_neighbour[anchor]),
        int(g.right_neighbour[anchor]),
    }
    out = []
    for r in matches.regions(0):
        cos = math.cos(ego.yaw_rad - r.heading_rad)
        if r.lane not in linked and abs(cos) >= _ACROSS_COS:
            out.append((r.lane, cos >= 0.0, 0.5 * (r.lon_min + r.lon_max)))
    return out


def create_scene(
    prep: PreparedGraph,
    ego: SceneEgo,
    objects: SceneObjects,
    settings: SceneSettings,
    green_lights: frozenset[int] = frozenset(),
    *,
    road_boundaries: bool = False,
    matches: Matches | None = None,
    memo: SceneMemo | None = None,
) -> Scene:
    """Constellations between the ego and every object (see module docstring).

    Args:
        prep: The prepared lane graph.
        ego: The ego; its ``route`` (if any) replaces the route prediction.
        objects: The other objects.
        settings: Scene settings (speed-limit mode).
        green_lights: Indices of traffic lights known to be green (empty: none).
        road_boundaries: Add the two road-boundary constellations along the ego's
            route (``rss.scene.boundaries``).
        matches: The map matching of ``scene_boxes(ego, objects)`` when already done
            (e.g. for many frames at once, ``rss.scene.chunked.match_frames``).
        memo: The map's memos: pass the same :class:`~rss.scene.memo.SceneMemo` to every
            frame of one prepared graph (``None``: a fresh one for this call; same
            results, slower).
    """
    n = len(objects.ids)
    if matches is None:
        matches = match_boxes(prep, scene_boxes(ego, objects))
    ids = tuple(int(v) for v in objects.ids)
    if matches.anchor[0] < 0:
        return Scene((), ids, ego_on_map=False)
    speeds = np.hypot(objects.vx_mps, objects.vy_mps)
    ego_stop = conservative_stop_m(ego.speed_mps, ego.dynamics)
    reach = np.array(
        [
            max(ego_stop + conservative_stop_m(float(v), d), _MIN_RELEVANT_M)
            for v, d in zip(speeds, objects.dynamics, strict=True)
        ]
    )
    gap = np.hypot(objects.x_m - ego.x_m, objects.y_m - ego.y_m)
    gap -= (objects.length_m + objects.width_m + ego.length_m + ego.width_m) / 2.0
    relevant = (gap <= reach) & (matches.anchor[1:] >= 0)
    horizon = float(reach[relevant].max()) + ego.length_m if relevant.any() else 0.0
    velocity = (ego.speed_mps * np.cos(ego.yaw_rad), ego.speed_mps * np.sin(ego.yaw_rad))
    if memo is None:
        memo = SceneMemo()
    headings = lane_headings(matches, n + 1)
    frame = FrameContext(
        prep, memo, ego, objects, settings, matches, RouteTree(), headings, velocity
    )
    anchor, anchor_forward, anchor_s = int(matches.anchor[0]), frame.forward(0), matches.anchor_s[0]
    frame.tree = connect(
        prep, memo, anchor, forward=anchor_forward, horizon_m=horizon, start=float(anchor_s)
    )
    frame.other_trees = [
        connect(prep, memo, lane, forward=fwd, horizon_m=horizon, start=start)
        for lane, fwd, start in more_roots(prep, matches, ego)
    ]
    frame.behind_tree = connect(
        prep,
        memo,
        anchor,
        forward=anchor_forward,
        horizon_m=horizon,
        start=float(anchor_s),
        admap_lengths=True,
        behind_only=True,
    )
    out: list[Constellation] = []
    areas: list[tuple[tuple[int, float, float], ...]] = []
    if road_boundaries:
        out = boundary_constellations(frame, ego_routes(frame, max(horizon, _MIN_RELEVANT_M))[0])
        areas = [()] * len(out)
    skipped: list[int] = []
    for i in np.flatnonzero(relevant):
        found = object_constellations(frame, int(i), float(reach[i]), green_lights)
        out.extend(c.constellation for c in found)
        areas.extend(c.road_area for c in found)
        if not found:
            skipped.append(ids[i])
    skipped.extend(ids[i] for i in np.flatnonzero(~relevant))
    return Scene(tuple(out), tuple(sorted(skipped)), ego_on_map=True, road_areas=tuple(areas))
