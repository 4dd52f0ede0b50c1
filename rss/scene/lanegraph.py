"""The pure lane-graph input of scene creation and its prepared geometry.

A :class:`LaneGraph` is what scene creation needs from a lane map, as plain arrays
(``rss`` never imports the map loaders). Borders are polylines in the map frame (ENU, m)
ordered along each lane's *reference direction*; ``direction`` says which way traffic
flows relative to that order::

      left border   o----o----o----o---->   reference direction (point order)
      centre line   o----o----o----o          lat param 0 = left border,
      right border  o----o----o----o          lat param 1 = right border

:func:`prepare` builds the derived geometry once per map (prepared polygons, an STRtree,
centre lines also as flat arrays, border lengths, ad-map's lane widths
(``rss.scene.admap_nearest``), intersection conflicts).
"""

from __future__ import annotations

import bisect
import functools
from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np
import shapely

from rss.errors import RssConstellationError
from rss.scene.admap_nearest import (
    DISTANCE_TOL_M,
    lane_widths,
    nearest_in_windows,
    range_of,
    segment_window,
    segments,
)
from rss.scene.align import Aligner
from rss.scene.cache import GraphScalars, LaneSegmentCache
from rss.scene.polylines import Polylines, polylines
from rss.scene.segment_cells import SegmentCells, narrowed, segment_cells

if TYPE_CHECKING:
    from rss.arrays import BoolArray, FloatArray, IntArray
    from rss.model import LaneDrivingDirection

__all__ = [
    "MATCH_DISTANCE_M",
    "SIMPLIFY_M",
    "LaneGraph",
    "PreparedGraph",
    "prepare",
]

#: Tolerance of the simplified lane polygons and centre lines (densely sampled maps, e.g.
#: OpenDRIVE, carry many collinear points; linear referencing is linear in the count).
SIMPLIFY_M = 0.01
#: Map matching: a point within this distance of a lane counts for it (ad-map's sampling
#: distance, ``getMapMatchedBoundingBox(..., Distance(0.1))`` in ad-rss map integration).
MATCH_DISTANCE_M = 0.1
_MIN_CONFLICT_AREA_M2 = 0.5
#: ad-map keeps a lane's whole width range for every interval of a lane whose widths vary
#: by at most this [m] (``route::getMetricRanges``).
_STEADY_WIDTH_M = 0.1


@dataclass(frozen=True)
class LaneGraph:
    """Lanes of a map as arrays (``L`` lanes, indices into these arrays everywhere).

    Attributes:
        ids: Lane ids from the source map, ``(L,)``.
        left_m: Left borders, each ``(K, 2)``.
        right_m: Right borders, each ``(M, 2)``.
        centre_m: Centre lines, each ``(C, 2)``.
        direction: ``(L,)`` traffic direction relative to the point order
            (:class:`rss.model.LaneDrivingDirection` codes: Positive = along it).
        speed_limit_mps: ``(L,)`` speed limits, NaN where unknown.
        successors: Per lane, the lanes its end leads into.
        predecessors: Per lane, the lanes leading into its start.
        left_neighbour: ``(L,)`` adjacent lane on the left, -1 for none.
        right_neighbour: ``(L,)`` adjacent lane on the right, -1 for none.
        left_opposite: ``(L,)`` the left neighbour's point order is reversed.
        right_opposite: ``(L,)`` the right neighbour's point order is reversed.
        is_intersection: ``(L,)`` lane lies inside an intersection.
        priority: ``(L,)`` right of way: +1 has way, 0 unregulated, -1 must yield.
        traffic_light: ``(L,)`` index into ``light_ids`` of the controlling light, -1 none.
        light_ids: Traffic-light ids.
        admap_reversed: ``(L,)`` ad-map holds the lane's points in the opposite order
            (``None``: nowhere); its nearest-point tie rule and width stations follow it.
    """

    ids: tuple[str, ...]
    left_m: tuple[FloatArray, ...]
    right_m: tuple[FloatArray, ...]
    centre_m: tuple[FloatArray, ...]
    direction: IntArray
    speed_limit_mps: FloatArray
    successors: tuple[tuple[int, ...], ...]
    predecessors: tuple[tuple[int, ...], ...]
    left_neighbour: IntArray
    right_neighbour: IntArray
    left_opposite: BoolArray
    right_opposite: BoolArray
    is_intersection: BoolArray
    priority: IntArray
    traffic_light: IntArray
    light_ids: tuple[str, ...] = ()
    admap_reversed: BoolArray | None = None

    def __len__(self) -> int:
        """Number of lanes."""
        return len(self.ids)

    def lane_direction(self, lane: int) -> LaneDrivingDirection:
        """Traffic direction of ``lane`` relative to its point order."""
        from rss.model import LaneDrivingDirection  # noqa: PLC0415 - cheap, avoids a cycle

        return LaneDrivingDirection(int(self.direction[lane]))


@dataclass(frozen=True)
class PreparedGraph:
    """A lane graph with its derived geometry.

    Attributes:
        graph: The input graph.
        polygons: ``(L,)`` lane polygons.
        centre_lines: ``(L,)`` centre line strings.
        tree: STRtree over ``polygons``.
        centre_length_m: ``(L,)`` centre-line lengths.
        length_min_m: ``(L,)`` shorter border length (inner side of a curve).
        length_max_m: ``(L,)`` longer border length.
        border_length_m: ``(2, L)`` left and right border lengths (as given, unsimplified).
        width_m: ``L`` arrays ``(W,)``: ad-map's widths at its stations ``width_t``.
        conflicts: ``(L, L)`` intersection lanes whose areas overlap or that merge into
            one successor (a lane never conflicts with itself).
        conflict_span_m: For every conflicting ``(a, b)``: lengths of ``a`` before and after
            the part of its centre line inside ``b`` (scaled to ``a``'s min length).
        width_rows: ``width_m`` as Python lists (fast scalar access).
        width_t: Per lane, the parametric stations of ``width_rows`` (0 to 1, our order).
        width_whole: Per lane, ad-map's range of ``width_rows`` (``range_of``: up to 1 mm
            inside the min and max); ad-map keeps it for every interval of a lane whose
            range spans at most 0.1 m (``width_steady``).
        width_steady: Per lane, see ``width_whole``.
        line_backwards: ``(2 L,)`` per line of ``borders``: ad-map's point order runs
            against ours.
        centre: ``centre_lines`` as flat arrays (vectorised linear referencing).
        borders: The borders (every given vertex) as flat arrays: line ``l`` is the left
            border of lane ``l``, line ``L + l`` its right border.
        straight: ``(L,)`` both borders, simplified to ``SIMPLIFY_M``, are single segments.
        match_polygons: ``(L,)`` lane polygons grown by ``MATCH_DISTANCE_M`` (prepared).
        match_tree: STRtree over ``match_polygons``.
        match_outlines: Outer rings of ``match_polygons`` as flat arrays (of the largest
            part where a lane polygon has several).
    """

    graph: LaneGraph
    polygons: np.ndarray
    centre_lines: np.ndarray
    tree: shapely.STRtree
    centre_length_m: FloatArray
    length_min_m: FloatArray
    length_max_m: FloatArray
    border_length_m: FloatArray
    width_m: tuple[FloatArray, ...]
    conflicts: BoolArray
    conflict_span_m: dict[tuple[int, int], tuple[float, float]]
    width_rows: list[list[float]]
    width_t: list[list[float]]
    width_whole: list[tuple[float, float]]
    width_steady: list[bool]
    line_backwards: BoolArray
    centre: Polylines
    borders: Polylines
    straight: BoolArray
    match_polygons: np.ndarray
    match_outlines: Polylines
    match_tree: shapely.STRtree

    @functools.cached_property
    def lane_segments(self) -> LaneSegmentCache:
        """Lane segments of road areas, built once per lane and orientation."""
        return LaneSegmentCache(self)

    @functools.cached_property
    def aligner(self) -> Aligner:
        """ad-map's aligned cuts of lanes side by side (``rss.scene.align``)."""
        return Aligner(self)

    @functools.cached_property
    def border_segments(self) -> FloatArray:
        """``borders`` per vertex: ``admap_nearest.segments``."""
        return segments(self.borders)

    @functools.cached_property
    def match_outline_bounds(self) -> FloatArray:
        """``(V, 4)`` envelopes of the ``match_outlines`` segments, per start vertex.

        Columns min x, min y, max x, max y (meaningless at a line's last vertex).
        """
        xy = self.match_outlines.xy_m
        after = np.concatenate([xy[1:], xy[-1:]])
        return np.concatenate([np.minimum(xy, after), np.maximum(xy, after)], axis=1)

    @functools.cached_property
    def border_cells(self) -> SegmentCells:
        """Candidate segments of ``borders`` per grid cell (built on first use)."""
        return segment_cells(self.borders)

    def nearest_on_borders(
        self,
        which: IntArray,
        points: FloatArray,
        near_m: FloatArray | None = None,
        reach_m: float = 0.0,
    ) -> tuple[FloatArray, FloatArray]:
        """Nearest points of ``points`` ``(Q, 2)`` on the borders ``which``: arc lengths, points.

        ``which`` indexes ``borders`` (lane ``l``: left ``l``, right ``L + l``). ad-map's
        tie rule in ad-map's point order (``admap_nearest.nearest_in_windows``); only the
        segments within ``reach_m`` of arc length ``near_m`` when given, and of those only
        the ones that can be nearest (``border_cells``; same result).
        """
        first, last = segment_window(self.borders, which, near_m, reach_m)
        first, last = narrowed(self.border_cells, which, points, first, last)
        return nearest_in_windows(
            self.border_segments,
            points,
            self.line_backwards[which],
            first,
            last,
        )

    @functools.cached_property
    def scalars(self) -> GraphScalars:
        """Per-lane constants as Python lists (fast scalar access)."""
        return GraphScalars(self)

    def width_range(self, lane: int, p0: float, p1: float) -> tuple[float, float]:
        """Min and max width of ``lane`` between parametric positions ``p0 <= p1``.

        As ad-map: the whole lane's range where it spans at most 0.1 m; else the range of
        the widths at the stations inside the interval and, interpolated, at its ends
        (ad-map evaluates its rule on the interval's projected borders).
        """
        if self.width_steady[lane] or (p0 <= 0.0 and p1 >= 1.0):
            return self.width_whole[lane]
        row = self.width_rows[lane]
        at = self.width_t[lane]
        inner = row[bisect.bisect_right(at, p0) : bisect.bisect_left(at, p1)]
        return range_of([_interp(p0, at, row), *inner, _interp(p1, at, row)])


def _interp(x: float, at: list[float], row: list[float]) -> float:
    """``numpy.interp(x, at, row)`` for one scalar, in plain Python (same arithmetic)."""
    if x <= at[0]:
        return row[0]
    if x >= at[-1]:
        return row[-1]
    j = bisect.bisect_right(at, x) - 1
    x0 = at[j]
    if x == x0:
        return row[j]
    slope = (row[j + 1] - row[j]) / (at[j + 1] - x0)
    return slope * (x - x0) + row[j]


def _polyline_length(points: FloatArray) -> float:
    steps = np.diff(points, axis=0)
    return float(np.hypot(steps[:, 0], steps[:, 1]).sum())


def _polygon(left: FloatArray, right: FloatArray) -> shapely.Geometry:
    ring = np.vstack([left, right[::-1]])
    poly = shapely.polygons(ring)
    if not shapely.is_valid(poly):
        poly = shapely.make_valid(poly)
        if not isinstance(poly, shapely.Polygon | shapely.MultiPolygon):
            poly = shapely.convex_hull(poly)
    return poly


def _largest_parts(polygons: np.ndarray) -> np.ndarray:
    """``(L,)`` the polygons, multi-polygons replaced by their largest part."""
    out = polygons.copy()
    for i in np.flatnonzero(shapely.get_num_geometries(polygons) > 1).tolist():
        parts = shapely.get_parts(polygons[i])
        out[i] = parts[int(np.argmax(shapely.area(parts)))]
    return out


def _conflicts(graph: LaneGraph, polygons: np.ndarray) -> BoolArray:
    n = len(graph)
    out = np.zeros((n, n), dtype=np.bool_)
    lanes = np.flatnonzero(graph.is_intersection)
    if lanes.size == 0:
        return out
    tree = shapely.STRtree(polygons[lanes])
    a, b = tree.query(polygons[lanes], predicate="intersects")
    keep = a != b
    a, b = lanes[a[keep]], lanes[b[keep]]
    area = shapely.area(shapely.intersection(polygons[a], polygons[b]))
    big = area > _MIN_CONFLICT_AREA_M2
    out[a[big], b[big]] = True
    for a_lane in lanes.tolist():
        for b_lane in lanes.tolist():
            if a_lane != b_lane and set(graph.successors[a_lane]) & set(graph.successors[b_lane]):
                out[a_lane, b_lane] = True
    for i in range(n):
        for nb in (graph.left_neighbour[i], graph.right_neighbour[i]):
            if nb >= 0:
                out[i, nb] = out[nb, i] = False
    return out


def _span(
    centre: shapely.Geometry, polygon: shapely.Geometry, length: float, length_min: float
) -> tuple[float, float]:
    shared = shapely.intersection(centre, polygon)
    if shapely.is_empty(shared):
        return max(0.0, length - 1e-3), 0.0
    s = shapely.line_locate_point(centre, shapely.points(shapely.get_coordinates(shared)))
    scale = length_min / length if length > 0 else 1.0
    return float(np.min(s)) * scale, max(0.0, length - float(np.max(s))) * scale


def prepare(graph: LaneGraph) -> PreparedGraph:
    """Build the derived geometry of ``graph`` (once per map).

    Raises:
        RssConstellationError: A lane has fewer than two border or centre points.
    """
    for i, lane_id in enumerate(graph.ids):
        for name, line in (("left", graph.left_m[i]), ("right", graph.right_m[i])):
            if len(line) < 2:  # noqa: PLR2004 - a polyline needs two points
                raise RssConstellationError(f"lane {lane_id} {name} border", len(line), ">= 2")
        if len(graph.centre_m[i]) < 2:  # noqa: PLR2004
            raise RssConstellationError(f"lane {lane_id} centre", len(graph.centre_m[i]), ">= 2")
    polygons = shapely.simplify(
        np.array(
            [_polygon(graph.left_m[i], graph.right_m[i]) for i in range(len(graph))], dtype=object
        ),
        SIMPLIFY_M,
    )
    centre = shapely.simplify(
        np.array([shapely.LineString(line) for line in graph.centre_m], dtype=object), SIMPLIFY_M
    )
    lefts = [shapely.LineString(line) for line in graph.left_m]
    rights = [shapely.LineString(line) for line in graph.right_m]
    # The borders keep every vertex: ad-map measures cut lane pieces and aligns cuts on its
    # own vertices, which a 1 cm simplification moves by up to 2 cm along a lane (a short
    # end segment at a kink). Whether a lane counts as straight for box matching is
    # decided on the simplified borders (collinear vertices do not bend a lane).
    borders = np.array([*lefts, *rights], dtype=object)
    simplified = shapely.simplify(borders, SIMPLIFY_M)
    match_polygons = shapely.buffer(polygons, MATCH_DISTANCE_M, join_style="mitre")
    shapely.prepare(match_polygons)
    left_len = np.array([_polyline_length(p) for p in graph.left_m])
    right_len = np.array([_polyline_length(p) for p in graph.right_m])
    backwards = (
        np.zeros(len(graph), dtype=np.bool_)
        if graph.admap_reversed is None
        else np.asarray(graph.admap_reversed, dtype=np.bool_)
    )
    width_t, widths = lane_widths(graph.left_m, graph.right_m, backwards)
    whole = [
        range_of((w[::-1] if back else w).tolist())
        for w, back in zip(widths, backwards.tolist(), strict=True)
    ]
    shapely.prepare(polygons)
    conflicts = _conflicts(graph, polygons)
    length = np.asarray(shapely.length(centre), dtype=np.float64).reshape(-1)
    length_min = np.minimum(left_len, right_len)
    spans = {
        (int(a), int(b)): _span(centre[a], polygons[b], float(length[a]), float(length_min[a]))
        for a, b in zip(*np.nonzero(conflicts), strict=True)
    }
    return PreparedGraph(
        graph=graph,
        polygons=polygons,
        centre_lines=np.asarray(centre, dtype=object),
        tree=shapely.STRtree(polygons),
        centre_length_m=length,
        length_min_m=length_min,
        length_max_m=np.maximum(left_len, right_len),
        border_length_m=np.stack([left_len, right_len]),
        width_m=tuple(widths),
        conflicts=conflicts,
        conflict_span_m=spans,
        width_rows=[w.tolist() for w in widths],
        width_t=[t.tolist() for t in width_t],
        width_whole=whole,
        width_steady=[hi - lo < _STEADY_WIDTH_M + DISTANCE_TOL_M for lo, hi in whole],
        line_backwards=np.concatenate([backwards, backwards]),
        centre=polylines(centre),
        borders=polylines(borders),
        straight=np.all(
            shapely.get_num_points(simplified).reshape(2, len(graph)) == 2,  # noqa: PLR2004 - one segment
            axis=0,
        ),
        match_polygons=match_polygons,
        match_tree=shapely.STRtree(match_polygons),
        match_outlines=polylines(shapely.get_exterior_ring(_largest_parts(match_polygons))),
    )
