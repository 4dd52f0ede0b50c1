"""Unstructured RSS results of a chunk of frames as columnar arrays (pure: no Rerun import).

Per frame the viewer shows the ego's and every checked agent's brake sets T(C_b) as filled,
translucent meshes with outlines, their continue-forward sets T(C_f) as fainter outlines
only (they are large and would hide the scene), all coloured by decision, and the allowed
drive-away headings as a fan from the ego::

    brake             red    the ego must brake for this agent
    drive-away        blue   both stopped: leave within the heading fan
    continue-forward  amber  sets overlap, safe because the other must brake (22.1)
    safe              green  the brake sets are disjoint (22.2)

The ego's own sets are light grey (the state lane carries the frame's response). Sets
are simplified by ``strips.SIMPLIFY_M`` for display and triangulated with shapely's
constrained Delaunay triangulation; each frame is one mesh per entity (three vertices per triangle,
per-vertex colours) and the outlines one padded ``(S, V, 3)`` array per chunk.
"""

from __future__ import annotations

import enum
from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np
import shapely

from rss.unstructured import UnstructuredResponse
from workbench.replay.strips import SIMPLIFY_M, StripColumns, polygon_rings, stack_strips

if TYPE_CHECKING:
    from collections.abc import Sequence

    from numpy.typing import NDArray

    from workbench.engines.unstructured.verdict import UnstructuredDetail

__all__ = [
    "COLORS",
    "EGO_SET_COLOR",
    "FAN_RADIUS_M",
    "Category",
    "MeshColumns",
    "UnstructuredColumns",
    "layout_unstructured",
    "triangulate",
]

#: Heights [m]: ego fill, agent fill, outlines, fan (above the map, under the boxes).
Z_EGO_M, Z_AGENT_M, Z_OUTLINE_M, Z_FAN_M = 0.04, 0.07, 0.1, 0.2
#: Length of the heading-fan rays [m] and their angular spacing [rad].
FAN_RADIUS_M, FAN_STEP_RAD = 8.0, np.deg2rad(10.0)
#: Outline alpha of the brake and the continue-forward sets.
ALPHA_BRAKE, ALPHA_FORWARD = 0xFF, 0x90


class Category(enum.IntEnum):
    """Display category of a decision (ordered by severity)."""

    SAFE = 0
    CONTINUE_FORWARD = 1
    DRIVE_AWAY = 2
    BRAKE = 3

    @property
    def label(self) -> str:
        """State-lane value: ``safe``, ``continue-forward``, ``drive-away``, ``brake``."""
        return self.name.lower().replace("_", "-")


#: Opaque colour per category (``0xRRGGBBFF``).
COLORS: dict[Category, int] = {
    Category.SAFE: 0x43A047FF,
    Category.CONTINUE_FORWARD: 0xFFB300FF,
    Category.DRIVE_AWAY: 0x1E88E5FF,
    Category.BRAKE: 0xE53935FF,
}
#: The ego's own sets are neutral so the agents' decision colours stand out.
EGO_SET_COLOR = 0xCFD8DCFF
_RGB = np.array([COLORS[c] & 0xFFFFFF00 for c in Category], dtype=np.uint32)
_EGO_RGB = np.array([EGO_SET_COLOR & 0xFFFFFF00], dtype=np.uint32)


@dataclass(frozen=True, slots=True)
class MeshColumns:
    """One mesh per frame for ``N`` frames.

    Attributes:
        vertices_m: ``(V, 3)`` triangle corners, three per triangle.
        colors: ``(V,)`` packed RGBA per vertex.
        triangles: ``(T, 3)`` vertex indices, local to the frame's mesh.
        vertex_counts: ``(N,)`` vertices per frame.
        triangle_counts: ``(N,)`` triangles per frame.
    """

    vertices_m: NDArray[np.float32]
    colors: NDArray[np.uint32]
    triangles: NDArray[np.uint32]
    vertex_counts: NDArray[np.int64]
    triangle_counts: NDArray[np.int64]


@dataclass(frozen=True, slots=True)
class UnstructuredColumns:
    """Everything the sink sends for the unstructured engine, for ``N`` frames.

    Attributes:
        states: State-lane value per frame (:attr:`Category.label`), ``(N,)``.
        ego_sets: The ego's sets, coloured by the resolved response.
        ego_outlines: Outlines of the ego's sets.
        agent_sets: Every checked agent's sets, coloured by its decision.
        agent_outlines: Outlines of the agents' sets.
        fan: Drive-away heading fan (rays and arc from the ego centre), blue.
    """

    states: NDArray[np.str_]
    ego_sets: MeshColumns
    ego_outlines: StripColumns
    agent_sets: MeshColumns
    agent_outlines: StripColumns
    fan: StripColumns


def triangulate(polygons: NDArray[np.object_]) -> tuple[NDArray[np.float64], NDArray[np.int64]]:
    """Triangles of ``(P,)`` (multi)polygons (``None`` skipped).

    Returns:
        ``corners (T, 3, 2)`` and ``owner (T,)``, the index of each triangle's polygon.
    """
    tris = shapely.constrained_delaunay_triangles(np.asarray(polygons, dtype=object))
    parts, owner = shapely.get_parts(tris, return_index=True)
    keep = ~shapely.is_empty(parts)
    coords = shapely.get_coordinates(shapely.get_exterior_ring(parts[keep]))
    return coords.reshape(-1, 4, 2)[:, :3], np.asarray(owner[keep], dtype=np.int64)


def _categories(detail: UnstructuredDetail) -> tuple[NDArray[np.int64], Category]:
    """Per-agent categories ``(K,)`` and the ego's (the frame's resolved response)."""
    dec = detail.result.decisions
    cat = np.where(dec.both_brake_safe, Category.SAFE, Category.CONTINUE_FORWARD)
    cat = np.where(dec.response == UnstructuredResponse.DriveAway, Category.DRIVE_AWAY, cat)
    cat = np.where(dec.response == UnstructuredResponse.Brake, Category.BRAKE, cat)
    response = detail.result.proper_response.response
    ego = {UnstructuredResponse.Brake: Category.BRAKE}.get(response, Category.SAFE)
    if response == UnstructuredResponse.DriveAway:
        ego = Category.DRIVE_AWAY
    elif ego == Category.SAFE and (cat == Category.CONTINUE_FORWARD).any():
        ego = Category.CONTINUE_FORWARD
    return cat.astype(np.int64), ego


def _frame_mesh(
    sets: NDArray[np.object_], rgb: NDArray[np.uint32], z_m: float
) -> tuple[NDArray[np.float32], NDArray[np.uint32]]:
    """Vertices ``(3T, 3)`` and opaque colours of one frame's filled sets."""
    corners, owner = triangulate(shapely.simplify(sets, SIMPLIFY_M))
    verts = np.empty((corners.shape[0] * 3, 3), dtype=np.float32)
    verts[:, :2] = corners.reshape(-1, 2)
    verts[:, 2] = z_m
    return verts, np.repeat(rgb[owner] | np.uint32(0xFF), 3).astype(np.uint32)


def _meshes(frames: Sequence[tuple[NDArray[np.float32], NDArray[np.uint32]]]) -> MeshColumns:
    counts = np.array([len(v) for v, _ in frames], dtype=np.int64)
    no_vertex = (np.zeros((0, 3), np.float32), np.zeros(0, np.uint32))
    local = np.concatenate([np.arange(n, dtype=np.uint32) for n in counts] or [no_vertex[1]])
    return MeshColumns(
        vertices_m=np.concatenate([v for v, _ in frames] or [no_vertex[0]]).astype(np.float32),
        colors=np.concatenate([c for _, c in frames] or [no_vertex[1]]).astype(np.uint32),
        triangles=local.astype(np.uint32).reshape(-1, 3),
        vertex_counts=counts,
        triangle_counts=counts // 3,
    )


def _outlines(
    per_frame: Sequence[tuple[list[NDArray[np.float64]], NDArray[np.uint32]]], z_m: float
) -> StripColumns:
    cols = stack_strips(per_frame)
    if cols.strips.size:
        cols.strips[..., 2] = z_m
    return cols


def _frame_outlines(
    brake: NDArray[np.object_], forward: NDArray[np.object_], rgb: NDArray[np.uint32]
) -> tuple[list[NDArray[np.float64]], NDArray[np.uint32]]:
    """Outlines of the brake sets (opaque) and the continue-forward sets (fainter)."""
    rings_b, src_b = polygon_rings(brake)
    rings_f, src_f = polygon_rings(forward)
    colors = np.concatenate(
        [rgb[src_b] | np.uint32(ALPHA_BRAKE), rgb[src_f] | np.uint32(ALPHA_FORWARD)]
    )
    return rings_b + rings_f, colors.astype(np.uint32)


def _fan(detail: UnstructuredDetail) -> list[NDArray[np.float64]]:
    """Rays every ``FAN_STEP_RAD`` across each allowed heading range, plus its arc."""
    x0, y0 = float(detail.ego.x_m[0]), float(detail.ego.y_m[0])
    lines: list[NDArray[np.float64]] = []
    for begin, end in detail.result.proper_response.heading_ranges:
        stop = end if end >= begin else end + 2.0 * np.pi
        n = max(int(np.ceil((stop - begin) / FAN_STEP_RAD)), 1) + 1
        angles = np.linspace(begin, stop, n)
        tips = np.column_stack([np.cos(angles), np.sin(angles)]) * FAN_RADIUS_M + (x0, y0)
        lines.extend(np.array([(x0, y0), tuple(tip)]) for tip in tips)
        lines.append(tips)
    return lines


def layout_unstructured(details: Sequence[UnstructuredDetail | None]) -> UnstructuredColumns:
    """Columnar display data of a chunk (``None``: a frame without unstructured pairs)."""
    states: list[str] = []
    ego_mesh: list[tuple[NDArray[np.float32], NDArray[np.uint32]]] = []
    agent_mesh: list[tuple[NDArray[np.float32], NDArray[np.uint32]]] = []
    ego_lines: list[tuple[list[NDArray[np.float64]], NDArray[np.uint32]]] = []
    agent_lines: list[tuple[list[NDArray[np.float64]], NDArray[np.uint32]]] = []
    fans: list[tuple[list[NDArray[np.float64]], NDArray[np.uint32]]] = []
    blue = np.uint32(COLORS[Category.DRIVE_AWAY])
    for detail in details:
        if detail is None:
            states.append(Category.SAFE.label)
            empty = (np.zeros((0, 3), np.float32), np.zeros(0, np.uint32))
            ego_mesh.append(empty)
            agent_mesh.append(empty)
            ego_lines.append(([], empty[1]))
            agent_lines.append(([], empty[1]))
            fans.append(([], empty[1]))
            continue
        cat, ego_cat = _categories(detail)
        states.append(ego_cat.label)
        res = detail.result
        ego_b, ego_f = res.ego_sets.polygons(brake=True), res.ego_sets.polygons(brake=False)
        brake, forward = res.agent_sets.polygons(brake=True), res.agent_sets.polygons(brake=False)
        ego_mesh.append(_frame_mesh(ego_b, _EGO_RGB, Z_EGO_M))
        agent_mesh.append(_frame_mesh(brake, _RGB[cat], Z_AGENT_M))
        ego_lines.append(_frame_outlines(ego_b, ego_f, _EGO_RGB))
        agent_lines.append(_frame_outlines(brake, forward, _RGB[cat]))
        fan = _fan(detail)
        fans.append((fan, np.full(len(fan), blue, dtype=np.uint32)))
    return UnstructuredColumns(
        states=np.array(states, dtype=np.str_),
        ego_sets=_meshes(ego_mesh),
        ego_outlines=_outlines(ego_lines, Z_OUTLINE_M),
        agent_sets=_meshes(agent_mesh),
        agent_outlines=_outlines(agent_lines, Z_OUTLINE_M),
        fan=_outlines(fans, Z_FAN_M),
    )
