"""The prepared lane graph: the geometry and tables scene creation reads, built once per map.

:func:`prepare` derives from a :class:`~rss.scene.lanegraph.LaneGraph` everything scene
creation reads and never changes: prepared polygons and STRtrees, centre lines also as
flat arrays, border lengths, ad-map's lane widths (``rss.scene.admap_nearest``), the
borders' nearest-point index, intersection conflicts and junctions, per-lane tables as
Python lists (``GraphScalars``, ``LaneSegmentTable``, ``Aligner``). A
:class:`PreparedGraph` is plain frozen data; what scene creation remembers while it runs
lives in a separate ``rss.scene.memo.SceneMemo`` owned by the caller.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np
import shapely

from rss.errors import RssConstellationError
from rss.scene.admap_nearest import DISTANCE_TOL_M, lane_widths, range_of
from rss.scene.align import Aligner
from rss.scene.border_index import BorderIndex, border_index
from rss.scene.border_stations import projected_stations
from rss.scene.graph_scalars import GraphScalars
from rss.scene.junctions import junction_ids
from rss.scene.lane_segments import LaneSegmentTable
from rss.scene.lanegraph import LaneGraph  # noqa: TC001 - dataclass field type
from rss.scene.polylines import Polylines, polylines

if TYPE_CHECKING:
    from rss.arrays import BoolArray, FloatArray, IntArray

__all__ = [
    "MATCH_DISTANCE_M",
    "SIMPLIFY_M",
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
class PreparedGraph:
    """A lane graph with its derived geometry and tables (``L`` lanes).

    Attributes:
        graph: The input graph.
        polygons: ``(L,)`` lane polygons.
        centre_lines: ``(L,)`` centre line strings.
        tree: STRtree over ``polygons``.
        centre_length_m: ``(L,)`` centre-line lengths.
        length_min_m: ``(L,)`` shorter border length (inner side of a curve).
        length_max_m: ``(L,)`` longer border length.
        border_length_m: ``(2, L)`` left and right border lengths (as given, unsimplified).
        width_m: ``L`` arrays ``(W,)``: ad-map's widths at its stations.
        conflicts: ``(L, L)`` intersection lanes whose areas overlap or that merge into
            one successor (a lane never conflicts with itself).
        conflict_span_m: For every conflicting ``(a, b)``: lengths of ``a`` before and after
            the part of its centre line inside ``b`` (scaled to ``a``'s min length).
        line_backwards: ``(2 L,)`` per line of ``borders``: ad-map's point order runs
            against ours.
        centre: ``centre_lines`` as flat arrays (vectorised linear referencing).
        borders: The borders (every given vertex) as flat arrays: line ``l`` is the left
            border of lane ``l``, line ``L + l`` its right border.
        border_index: ``borders`` with their nearest-point index.
        straight: ``(L,)`` both borders, simplified to ``SIMPLIFY_M``, are single segments.
        match_polygons: ``(L,)`` lane polygons grown by ``MATCH_DISTANCE_M`` (prepared).
        match_tree: STRtree over ``match_polygons``.
        match_outlines: Outer rings of ``match_polygons`` as flat arrays (of the largest
            part where a lane polygon has several).
        match_outline_bounds: ``(V, 4)`` envelopes of the ``match_outlines`` segments, per
            start vertex: min x, min y, max x, max y (meaningless at a line's last vertex).
        scalars: Per-lane constants as Python lists.
        lane_segments: Per-lane tables of cut lane segments.
        aligner: ad-map's aligned cuts of lanes side by side (``rss.scene.align``).
        junction_ids: ``(L,)`` junction index per lane, -1 outside (``rss.scene.junctions``).
        junction_list: ``junction_ids`` as a Python list (fast scalar access).
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
    line_backwards: BoolArray
    centre: Polylines
    borders: Polylines
    border_index: BorderIndex
    straight: BoolArray
    match_polygons: np.ndarray
    match_outlines: Polylines
    match_outline_bounds: FloatArray
    match_tree: shapely.STRtree
    scalars: GraphScalars
    lane_segments: LaneSegmentTable
    aligner: Aligner
    junction_ids: IntArray
    junction_list: list[int]


def _outline_bounds(lines: Polylines) -> FloatArray:
    """``(V, 4)`` envelopes of the segments of ``lines`` per start vertex."""
    xy = lines.xy_m
    after = np.concatenate([xy[1:], xy[-1:]])
    return np.concatenate([np.minimum(xy, after), np.maximum(xy, after)], axis=1)


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
    """Build the derived geometry and tables of ``graph`` (once per map).

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
    length_max = np.maximum(left_len, right_len)
    border_length = np.stack([left_len, right_len])
    line_backwards = np.concatenate([backwards, backwards])
    index = border_index(polylines(borders), line_backwards)
    outlines = polylines(shapely.get_exterior_ring(_largest_parts(match_polygons)))
    junctions = junction_ids(graph, conflicts)
    return PreparedGraph(
        graph=graph,
        polygons=polygons,
        centre_lines=np.asarray(centre, dtype=object),
        tree=shapely.STRtree(polygons),
        centre_length_m=length,
        length_min_m=length_min,
        length_max_m=length_max,
        border_length_m=border_length,
        width_m=tuple(widths),
        conflicts=conflicts,
        conflict_span_m=spans,
        line_backwards=line_backwards,
        centre=polylines(centre),
        borders=index.lines,
        border_index=index,
        straight=np.all(
            shapely.get_num_points(simplified).reshape(2, len(graph)) == 2,  # noqa: PLR2004 - one segment
            axis=0,
        ),
        match_polygons=match_polygons,
        match_tree=shapely.STRtree(match_polygons),
        match_outlines=outlines,
        match_outline_bounds=_outline_bounds(outlines),
        scalars=GraphScalars(graph, length, conflicts),
        lane_segments=LaneSegmentTable(
            graph.direction,
            length_min,
            length_max,
            projected_stations(index, length_max, border_length),
            ([w.tolist() for w in widths], [t.tolist() for t in width_t]),
            whole,
            [hi - lo < _STEADY_WIDTH_M + DISTANCE_TOL_M for lo, hi in whole],
        ),
        aligner=Aligner(index),
        junction_ids=junctions,
        junction_list=[int(v) for v in junctions],
    )
