"""Map matching: bounding boxes -> parametric occupied regions per lane, vectorised.

Each box is intersected with every lane polygon it touches (STRtree query -> index
pairs); the vertices of the clipped footprint are projected onto the lane's centre line.
The longitudinal range is the arc-length range divided by the centre length, the lateral
range comes from the signed offset and the local width (0 = left border, 1 = right
border, in the lane's point order)::

     left border  ──────────────────────────▶  lat 0
                        ┌────────┐
     centre       ──────│  box   │──────────▶  lat 0.5      lon = s / centre length
                        └────────┘
     right border ──────────────────────────▶  lat 1

Only the part of a box that lies on the map counts, so a vehicle partly off the map still
gets regions for the lanes it touches; a box touching no lane gets none.
"""

from __future__ import annotations

import functools
from dataclasses import dataclass
from typing import TYPE_CHECKING, NamedTuple

import numpy as np
import shapely

from rss.scene.lanegraph import WIDTH_STATIONS
from rss.scene.polylines import heading_at, interpolate

if TYPE_CHECKING:
    from rss.batch import FloatArray, IntArray
    from rss.scene.lanegraph import PreparedGraph

__all__ = [
    "BoxArrays",
    "MatchRow",
    "Matches",
    "box_polygons",
    "lane_heading",
    "match_boxes",
    "match_route",
]

_MIN_AREA_M2 = 1e-3
_TANGENT_STEP_M = 0.5
#: Anchor choice: a lane across the box heading counts like a centre this far outside.
_MISALIGNED_M = 2.0


@dataclass(frozen=True)
class BoxArrays:
    """Oriented boxes, all ``(N,)`` (map frame, ENU).

    Attributes:
        x_m: Centre x.
        y_m: Centre y.
        yaw_rad: Heading, counter-clockwise from +x.
        length_m: Length along the heading.
        width_m: Width.
    """

    x_m: FloatArray
    y_m: FloatArray
    yaw_rad: FloatArray
    length_m: FloatArray
    width_m: FloatArray


class MatchRow(NamedTuple):
    """One (box, lane) pair of :class:`Matches` as Python scalars (see its attributes)."""

    lane: int
    lon_min: float
    lon_max: float
    lat_min: float
    lat_max: float
    heading_rad: float


@dataclass(frozen=True)
class Matches:
    """Occupied regions of ``N`` boxes as ``P`` (box, lane) pairs.

    Attributes:
        box: ``(P,)`` box index.
        lane: ``(P,)`` lane index.
        lon_min: ``(P,)`` parametric start along the lane's point order, in [0, 1].
        lon_max: ``(P,)`` parametric end.
        lat_min: ``(P,)`` parametric left edge (0 = left border).
        lat_max: ``(P,)`` parametric right edge.
        anchor: ``(N,)`` the lane the box is on: among the touched lanes, the one nearest
            to its centre and best aligned with its heading; -1 when it touches no lane.
        anchor_s: ``(N,)`` parametric position of the centre on the anchor lane.
        anchor_heading_rad: ``(N,)`` heading of the anchor lane's point order there.
        heading_rad: ``(P,)`` heading of each pair's lane point order at the box centre.
        starts: ``N + 1`` offsets: the pairs of box ``b`` are ``starts[b]:starts[b + 1]``.
    """

    box: IntArray
    lane: IntArray
    lon_min: FloatArray
    lon_max: FloatArray
    lat_min: FloatArray
    lat_max: FloatArray
    anchor: IntArray
    anchor_s: FloatArray
    anchor_heading_rad: FloatArray
    heading_rad: FloatArray
    starts: list[int]

    def rows(self, box: int) -> range:
        """Pair indices of ``box`` (pairs are sorted by box)."""
        return range(self.starts[box], self.starts[box + 1])

    @functools.cached_property
    def _by_box(self) -> list[list[MatchRow]]:
        rows = list(
            map(
                MatchRow,
                self.lane.tolist(),
                self.lon_min.tolist(),
                self.lon_max.tolist(),
                self.lat_min.tolist(),
                self.lat_max.tolist(),
                self.heading_rad.tolist(),
            )
        )
        return [rows[a:b] for a, b in zip(self.starts[:-1], self.starts[1:], strict=True)]

    @functools.cached_property
    def anchors(self) -> list[int]:
        """``anchor`` as a Python list."""
        out: list[int] = self.anchor.tolist()
        return out

    def regions(self, box: int) -> list[MatchRow]:
        """The pairs of ``box`` as Python scalars, in pair order (do not modify)."""
        return self._by_box[box]

    def lanes_of(self, box: int) -> IntArray:
        """Lanes touched by ``box``."""
        r = self.rows(box)
        out: IntArray = self.lane[r.start : r.stop]
        return out


def box_polygons(boxes: BoxArrays) -> np.ndarray:
    """``(N,)`` polygons of the boxes."""
    c, s = np.cos(boxes.yaw_rad), np.sin(boxes.yaw_rad)
    hl, hw = boxes.length_m / 2.0, boxes.width_m / 2.0
    corners_l = np.array([1.0, 1.0, -1.0, -1.0])[None, :] * hl[:, None]
    corners_w = np.array([1.0, -1.0, -1.0, 1.0])[None, :] * hw[:, None]
    xs = boxes.x_m[:, None] + corners_l * c[:, None] - corners_w * s[:, None]
    ys = boxes.y_m[:, None] + corners_l * s[:, None] + corners_w * c[:, None]
    out: np.ndarray = shapely.polygons(np.stack([xs, ys], axis=-1))
    return out


def lane_heading(graph: PreparedGraph, lanes: IntArray, s_m: FloatArray) -> FloatArray:
    """Heading of the centre lines of ``lanes`` at arc lengths ``s_m`` (both ``(P,)``)."""
    return heading_at(graph.centre, lanes, s_m, _TANGENT_STEP_M)


def _lateral(
    graph: PreparedGraph, lanes: IntArray, points: FloatArray
) -> tuple[FloatArray, FloatArray, FloatArray]:
    """Arc length, parametric lateral position and lane heading of ``points`` ``(P, 2)``."""
    n = len(lanes)
    s = shapely.line_locate_point(graph.centre_lines[lanes], shapely.points(points))
    length = graph.centre_length_m[lanes]
    # One interpolation for the foot point and both ends of the heading chord.
    ends = np.clip(
        np.concatenate([s - _TANGENT_STEP_M, s + _TANGENT_STEP_M]), 0.0, np.tile(length, 2)
    )
    at = interpolate(graph.centre, np.tile(lanes, 3), np.concatenate([s, ends]))
    chord = at[2 * n :] - at[n : 2 * n]
    heading = np.arctan2(chord[:, 1], chord[:, 0])
    d = points - at[:n]
    offset_left = np.cos(heading) * d[:, 1] - np.sin(heading) * d[:, 0]
    p = np.clip(s / np.where(length > 0, length, 1.0), 0.0, 1.0)
    station = p * (WIDTH_STATIONS - 1)
    i0 = np.minimum(np.floor(station).astype(np.int64), WIDTH_STATIONS - 2)
    frac = station - i0
    w = graph.width_m[lanes, i0] * (1 - frac) + graph.width_m[lanes, i0 + 1] * frac
    lat = 0.5 - offset_left / np.where(w > 0, w, 1.0)
    return s, lat, heading


def match_boxes(graph: PreparedGraph, boxes: BoxArrays) -> Matches:
    """Occupied regions of every box in every lane it overlaps (see module docstring)."""
    n = len(boxes.x_m)
    polys = box_polygons(boxes)
    box_idx, lane_idx = graph.tree.query(polys, predicate="intersects")
    by_box = np.argsort(box_idx, kind="stable")
    box_idx, lane_idx = box_idx[by_box], lane_idx[by_box]
    clipped = polys[box_idx]
    lane_polys = graph.polygons[lane_idx]
    # A box strictly inside its lane is its own footprint; overlay only the others.
    cut = ~shapely.contains_properly(lane_polys, clipped)
    clipped[cut] = shapely.intersection(clipped[cut], lane_polys[cut])
    keep = shapely.area(clipped) > _MIN_AREA_M2
    box_idx, lane_idx, clipped = box_idx[keep], lane_idx[keep], clipped[keep]
    coords, which = shapely.get_coordinates(clipped, return_index=True)
    centres = np.stack([boxes.x_m[box_idx], boxes.y_m[box_idx]], axis=1)
    m = len(coords)
    s_all, lat_all, heading_all = _lateral(
        graph, np.concatenate([lane_idx[which], lane_idx]), np.concatenate([coords, centres])
    )
    s, lat, centre_s, pair_heading = s_all[:m], lat_all[:m], s_all[m:], heading_all[m:]
    p = len(box_idx)
    length = graph.centre_length_m[lane_idx]
    s_min = np.full(p, np.inf)
    s_max = np.full(p, -np.inf)
    lat_min = np.full(p, np.inf)
    lat_max = np.full(p, -np.inf)
    np.minimum.at(s_min, which, s)
    np.maximum.at(s_max, which, s)
    np.minimum.at(lat_min, which, lat)
    np.maximum.at(lat_max, which, lat)
    safe_len = np.where(length > 0, length, 1.0)

    outside = shapely.distance(shapely.points(centres), graph.polygons[lane_idx])
    misaligned = 1.0 - np.abs(np.cos(boxes.yaw_rad[box_idx] - pair_heading))
    score = outside + _MISALIGNED_M * misaligned
    anchor = np.full(n, -1, dtype=np.int64)
    anchor_s = np.zeros(n)
    order = np.lexsort((score, box_idx))
    first = np.ones(len(order), dtype=np.bool_)
    first[1:] = box_idx[order][1:] != box_idx[order][:-1]
    best = order[first]
    anchor[box_idx[best]] = lane_idx[best]
    anchor_s[box_idx[best]] = np.clip(centre_s[best] / safe_len[best], 0.0, 1.0)
    heading = np.zeros(n)
    heading[box_idx[best]] = pair_heading[best]
    return Matches(
        box=box_idx.astype(np.int64),
        lane=lane_idx.astype(np.int64),
        lon_min=np.clip(s_min / safe_len, 0.0, 1.0),
        lon_max=np.clip(s_max / safe_len, 0.0, 1.0),
        lat_min=np.clip(lat_min, 0.0, 1.0),
        lat_max=np.clip(lat_max, 0.0, 1.0),
        anchor=anchor,
        anchor_s=anchor_s,
        anchor_heading_rad=heading,
        heading_rad=pair_heading,
        starts=np.searchsorted(box_idx, np.arange(n + 1)).tolist(),
    )


def match_route(
    graph: PreparedGraph, xy_m: FloatArray, yaw_rad: FloatArray
) -> list[tuple[int, bool]]:
    """Lanes a planned path runs through, in order, as ``(lane, forward)`` steps.

    Args:
        graph: The prepared lane graph.
        xy_m: ``(K, 2)`` waypoints.
        yaw_rad: ``(K,)`` waypoint headings.

    Each waypoint picks, among the lanes containing it, the one whose direction agrees
    best with the waypoint heading; repeated lanes are dropped.
    """
    if len(xy_m) == 0:
        return []
    point_idx, lane_idx = graph.tree.query(shapely.points(xy_m), predicate="intersects")
    if point_idx.size == 0:
        return []
    s = shapely.line_locate_point(graph.centre_lines[lane_idx], shapely.points(xy_m[point_idx]))
    heading = lane_heading(graph, lane_idx, s)
    agree = np.cos(yaw_rad[point_idx] - heading)
    order = np.lexsort((-np.abs(agree), point_idx))
    steps: list[tuple[int, bool]] = []
    last = -1
    for k in order:
        if point_idx[k] == last:
            continue
        last = int(point_idx[k])
        step = (int(lane_idx[k]), bool(agree[k] >= 0.0))
        if not steps or steps[-1][0] != step[0]:
            steps.append(step)
    return steps
