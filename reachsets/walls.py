"""Track walls as plain arrays and the nearest wall point of many positions (for ``bound``).

Both walls (left first) are polylines; their segments are grouped into blocks of
``BLOCK_SEGMENTS`` consecutive segments, each inside a disk around one of its vertices::

         block b: disk of radius r_b around vertex c_b
           .-------.
    o----o-+--o----o-+--o----o     wall vertices
           '-------'

A position ``p`` is at most ``min_b |p - c_b|`` from its wall (``c_b`` lies on the wall) and
at least ``|p - c_b| - r_b`` from any segment of block ``b``, so only the blocks with
``|p - c_b| - r_b <= min_b' |p - c_b'|`` can hold the nearest segment. ``wall_frame`` measures
only their segments, with the same arithmetic as the brute-force ``wall_frame_reference``
(every position against every segment of its wall), so both give bit-identical results,
including which segment wins a tie (the lowest index). When compiled, ``wall_frame`` hands
the search to ``bound_scalar.frames`` instead: a grid of 6 m cells per wall, each listing
(on first use) the segments that can be nearest to a point in it; same pair arithmetic.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np
import shapely

from reachsets import bound_scalar
from reachsets.bound_scalar import WallLists

if TYPE_CHECKING:
    from numpy.typing import NDArray

    from reachsets.track import TrackGeometry

__all__ = [
    "BLOCK_SEGMENTS",
    "SCALAR_SEARCH",
    "Blocks",
    "Walls",
    "block_columns",
    "track_walls",
    "wall_frame",
    "wall_frame_reference",
    "wall_lists",
]

#: Consecutive wall segments per block of the candidate search.
BLOCK_SEGMENTS = 4
_TANGENT_HALF_STEP_M = 0.5
#: Up to this many positions, the brute force makes fewer numpy calls than the block search.
_BRUTE_POSITIONS = 6
#: Above this many positions of both walls, each wall is searched on its own (no gathers).
_SPLIT_POSITIONS = 128
#: Relative slack of the block bounds (they only need to be a safe superset).
_SLACK = 1e-9
#: Tracks whose walls are kept (the object is held, so its id is never reused meanwhile).
_CACHE_SIZE = 4
#: Cell size of the scalar search's grid (m; larger for huge walls: at most
#: ``_GRID_CELLS_MAX`` cells a wall) and how far around each wall's segments it reaches (m).
_GRID_CELL_M = 6.0
_GRID_MARGIN_M = 60.0
_GRID_CELLS_MAX = 1 << 18
#: ``wall_frame`` searches with the compiled kernel (``bound_scalar.frames``) when it is
#: compiled; from the sources the numpy block search is faster.
SCALAR_SEARCH = not bound_scalar.__file__.endswith(".py")
_CACHE: dict[int, tuple[TrackGeometry, Walls]] = {}
_LISTS: dict[int, tuple[Walls, WallLists]] = {}


@dataclass(frozen=True, slots=True)
class Walls:
    """Both walls (left first): vertices, segments, arc lengths and segment blocks.

    The right wall's arc length continues after the left's plus a 1 m gap, so one
    ``np.interp`` serves both; lookups are clamped to each wall's own range.

    Attributes:
        pts: Vertices of both walls, ``(M, 2)``.
        cum: Arc length at each vertex, ``(M,)``.
        start: Segment start points as ``(x, y)`` rows, ``(2, S)`` (segments within one
            wall only).
        seg: Segment vectors as ``(x, y)`` rows, ``(2, S)``.
        seg_len: Segment lengths, ``(S,)``.
        seg_s: Arc length at each segment start, ``(S,)``.
        seg_wall: Wall of each segment (0 left, 1 right), ``(S,)``.
        lo: Arc length where each wall starts, ``(2,)``.
        hi: Arc length where each wall ends, ``(2,)``.
        seg_len2: Squared segment lengths floored at 1e-24 m^2, ``(S,)``.
        blk_seg: Segments of each block, ascending, a short last block padded by
            repeating its last segment, then one empty block (never a candidate),
            ``(B + 1, BLOCK_SEGMENTS)``.
        blk_x: A vertex of each block (infinite for the empty block), ``(B + 1,)``.
        blk_y: Its y, ``(B + 1,)``.
        blk_radius: Radius around it holding every vertex of the block, ``(B + 1,)``.
        blk_wall: Wall of each block (-1 for the empty block), ``(B + 1,)``.
        wall_blk: Blocks of each wall, ascending, padded with the empty block, ``(2, Bw)``.
        seg_pack: ``start``, ``seg`` and ``seg_len2`` as rows (one gather per search),
            ``(5, S)``.
        seg_at: ``seg_s`` and ``seg_len`` as rows, ``(2, S)``.
    """

    pts: NDArray[np.float64]
    cum: NDArray[np.float64]
    start: NDArray[np.float64]
    seg: NDArray[np.float64]
    seg_len: NDArray[np.float64]
    seg_s: NDArray[np.float64]
    seg_wall: NDArray[np.intp]
    lo: NDArray[np.float64]
    hi: NDArray[np.float64]
    seg_len2: NDArray[np.float64]
    blk_seg: NDArray[np.intp]
    blk_x: NDArray[np.float64]
    blk_y: NDArray[np.float64]
    blk_radius: NDArray[np.float64]
    blk_wall: NDArray[np.intp]
    wall_blk: NDArray[np.intp]
    seg_pack: NDArray[np.float64]
    seg_at: NDArray[np.float64]


def track_walls(track: TrackGeometry) -> Walls:
    """The walls of ``track``, built once per track (the last few tracks are kept)."""
    hit = _CACHE.get(id(track))
    if hit is not None and hit[0] is track:
        return hit[1]
    walls = _build(track)
    if len(_CACHE) >= _CACHE_SIZE:
        del _CACHE[next(iter(_CACHE))]
    _CACHE[id(track)] = (track, walls)
    return walls


def wall_lists(walls: Walls) -> WallLists:
    """``walls`` as Python lists for the scalar kernel, built once per walls (last few kept)."""
    hit = _LISTS.get(id(walls))
    if hit is not None and hit[0] is walls:
        return hit[1]
    real = walls.blk_wall >= 0
    n_blk = int(real.sum())
    grid = _grid(walls)
    out = WallLists(
        cum=walls.cum.tolist(),
        px=walls.pts[:, 0].tolist(),
        py=walls.pts[:, 1].tolist(),
        start_x=walls.start[0].tolist(),
        start_y=walls.start[1].tolist(),
        seg_x=walls.seg[0].tolist(),
        seg_y=walls.seg[1].tolist(),
        seg_len=walls.seg_len.tolist(),
        seg_len2=walls.seg_len2.tolist(),
        seg_s=walls.seg_s.tolist(),
        lo=walls.lo.tolist(),
        hi=walls.hi.tolist(),
        blk_seg=walls.blk_seg[:n_blk].tolist(),
        blk_x=walls.blk_x[:n_blk].tolist(),
        blk_y=walls.blk_y[:n_blk].tolist(),
        blk_radius=walls.blk_radius[:n_blk].tolist(),
        wall_blk=[[int(b) for b in row if b < n_blk] for row in walls.wall_blk],
        grid=grid[0],
        grid_n=grid[1],
        cells=[None] * _cell_count(grid[1]),
    )
    if len(_LISTS) >= _CACHE_SIZE:
        del _LISTS[next(iter(_LISTS))]
    _LISTS[id(walls)] = (walls, out)
    return out


def _grid(walls: Walls) -> tuple[list[float], list[int]]:
    """Per wall, ``x0, y0, cell`` and ``nx, ny, first cell`` of the scalar search's grid."""
    geo: list[float] = []
    dims: list[int] = []
    for wall in (0, 1):
        seg = np.flatnonzero(walls.seg_wall == wall)
        (sx, sy), (vx, vy) = walls.start[:, seg], walls.seg[:, seg]
        x0 = float(np.minimum(sx, sx + vx).min()) - _GRID_MARGIN_M
        y0 = float(np.minimum(sy, sy + vy).min()) - _GRID_MARGIN_M
        width = float(np.maximum(sx, sx + vx).max()) + _GRID_MARGIN_M - x0
        height = float(np.maximum(sy, sy + vy).max()) + _GRID_MARGIN_M - y0
        cell = max(_GRID_CELL_M, float(np.sqrt(width * height / _GRID_CELLS_MAX)))
        nx, ny = int(np.ceil(width / cell)), int(np.ceil(height / cell))
        geo += [x0, y0, cell]
        dims += [nx, ny, dims[0] * dims[1] if dims else 0]
    return geo, dims


def _cell_count(dims: list[int]) -> int:
    """Cells of both walls' grids (``_grid``'s ``nx, ny, first cell`` per wall)."""
    nx, ny, first = dims[3:6]  # the second wall's grid follows the first's cells
    return first + nx * ny


def _build(track: TrackGeometry) -> Walls:
    parts = [shapely.get_coordinates(track.left), shapely.get_coordinates(track.right)]
    cums = []
    offset = 0.0
    for pts in parts:
        seg_len = np.hypot(*np.diff(pts, axis=0).T)
        cums.append(offset + np.concatenate([[0.0], np.cumsum(seg_len)]))
        offset = cums[-1][-1] + 1.0
    seg = np.concatenate([np.diff(p, axis=0) for p in parts])
    start = np.concatenate([p[:-1] for p in parts])
    counts = [len(p) - 1 for p in parts]
    first = np.cumsum([0, *counts])
    blocks = [
        np.minimum(np.arange(b, b + BLOCK_SEGMENTS), first[w + 1] - 1)
        for w in range(2)
        for b in range(int(first[w]), int(first[w + 1]), BLOCK_SEGMENTS)
    ]
    blk_seg = np.array(blocks, dtype=np.intp).reshape(-1, BLOCK_SEGMENTS)
    centre = start[blk_seg[:, BLOCK_SEGMENTS // 2]]
    ends = start[blk_seg] + seg[blk_seg]
    reach = np.maximum(
        np.hypot(*(start[blk_seg] - centre[:, None]).transpose(2, 0, 1)).max(axis=1),
        np.hypot(*(ends - centre[:, None]).transpose(2, 0, 1)).max(axis=1),
    )
    per_wall = [-(-c // BLOCK_SEGMENTS) for c in counts]
    empty = len(blk_seg)
    wall_blk = np.full((2, max(per_wall)), empty, dtype=np.intp)
    wall_blk[0, : per_wall[0]] = np.arange(per_wall[0])
    wall_blk[1, : per_wall[1]] = per_wall[0] + np.arange(per_wall[1])
    seg_len = np.hypot(seg[:, 0], seg[:, 1])
    seg_len2 = np.maximum(seg_len**2, 1e-24)
    seg_s = np.concatenate([c[:-1] for c in cums])
    return Walls(
        pts=np.concatenate(parts),
        cum=np.concatenate(cums),
        start=np.ascontiguousarray(start.T),
        seg=np.ascontiguousarray(seg.T),
        seg_len=seg_len,
        seg_s=seg_s,
        seg_wall=np.repeat([0, 1], counts),
        lo=np.array([c[0] for c in cums]),
        hi=np.array([c[-1] for c in cums]),
        seg_len2=seg_len2,
        blk_seg=np.concatenate([blk_seg, blk_seg[-1:]]),
        blk_x=np.append(centre[:, 0], np.inf),
        blk_y=np.append(centre[:, 1], np.inf),
        blk_radius=np.append(reach * (1 + _SLACK) + _SLACK, 0.0),
        blk_wall=np.repeat([0, 1, -1], [*per_wall, 1]),
        wall_blk=wall_blk,
        seg_pack=np.concatenate([start.T, seg.T, seg_len2[None]]),
        seg_at=np.stack([seg_s, seg_len]),
    )


def _nearest(
    walls: Walls,
    x: NDArray[np.float64],
    y: NDArray[np.float64],
    seg: NDArray[np.intp],
    valid: NDArray[np.bool_],
) -> NDArray[np.float64]:
    """Arc length of the nearest point on segments ``seg`` (``(P, K)``, ascending per row).

    ``valid`` marks the pairs that may win (``(P, K)``). The pair arithmetic is the same for every
    search, so the winner does not depend on which other segments were measured.
    """
    start_x, start_y, sx, sy, seg_len2 = walls.seg_pack[:, seg]
    dx = x[:, None] - start_x
    dy = y[:, None] - start_y
    u = np.minimum(np.maximum((dx * sx + dy * sy) / seg_len2, 0.0), 1.0)
    ox = dx - u * sx
    oy = dy - u * sy
    best = np.argmin(np.where(valid, ox * ox + oy * oy, np.inf), axis=1)
    rows = np.arange(len(best))
    seg_s, seg_len = walls.seg_at[:, seg[rows, best]]
    s: NDArray[np.float64] = seg_s + u[rows, best] * seg_len
    return s


def _frame_at(
    walls: Walls, s: NDArray[np.float64], which: NDArray[np.intp] | int
) -> tuple[NDArray[np.float64], NDArray[np.float64], NDArray[np.float64], NDArray[np.float64]]:
    """Wall point at arc length ``s`` and the unit tangent through ``s -+ 0.5 m``."""
    probe = np.concatenate(
        [
            s,
            np.minimum(s + _TANGENT_HALF_STEP_M, walls.hi[which]),
            np.maximum(s - _TANGENT_HALF_STEP_M, walls.lo[which]),
        ]
    )
    px = np.interp(probe, walls.cum, walls.pts[:, 0]).reshape(3, -1)
    py = np.interp(probe, walls.cum, walls.pts[:, 1]).reshape(3, -1)
    tx, ty = px[1] - px[2], py[1] - py[2]
    norm = np.maximum(np.hypot(tx, ty), 1e-12)
    return px[0], py[0], tx / norm, ty / norm


def wall_frame_reference(
    walls: Walls, x: NDArray[np.float64], y: NDArray[np.float64], which: NDArray[np.intp] | int
) -> tuple[NDArray[np.float64], NDArray[np.float64], NDArray[np.float64], NDArray[np.float64]]:
    """Slow reference of ``wall_frame``: every position against every segment of its wall."""
    which_p = np.broadcast_to(np.asarray(which, dtype=np.intp), x.shape)
    seg = np.broadcast_to(np.arange(len(walls.seg_len)), (len(x), len(walls.seg_len)))
    s = _nearest(walls, x, y, seg, walls.seg_wall == which_p[:, None])
    return _frame_at(walls, s, which)


@dataclass(frozen=True, slots=True)
class Blocks:
    """The blocks of each position's wall and their disks, gathered once for many searches.

    Attributes:
        cols: Blocks of each position's wall, ascending, padded with the empty block,
            ``(P, Bw)``.
        x: Their vertex x, ``(P, Bw)`` (m).
        y: Their vertex y, ``(P, Bw)`` (m).
        radius: Their radius, ``(P, Bw)`` (m).
    """

    cols: NDArray[np.intp]
    x: NDArray[np.float64]
    y: NDArray[np.float64]
    radius: NDArray[np.float64]

    def head(self, n: int) -> Blocks:
        """The blocks of the first ``n`` positions (views)."""
        return Blocks(self.cols[:n], self.x[:n], self.y[:n], self.radius[:n])


def block_columns(walls: Walls, which: NDArray[np.intp] | int) -> Blocks:
    """The blocks of wall ``which`` (one per position, or one wall for all) for ``wall_frame``."""
    cols = walls.wall_blk[which]
    return Blocks(cols, walls.blk_x[cols], walls.blk_y[cols], walls.blk_radius[cols])


def wall_frame(
    walls: Walls,
    x: NDArray[np.float64],
    y: NDArray[np.float64],
    which: NDArray[np.intp] | int,
    blocks: Blocks | None = None,
) -> tuple[NDArray[np.float64], NDArray[np.float64], NDArray[np.float64], NDArray[np.float64]]:
    """Nearest point and unit tangent of wall ``which`` for ``(P,)`` positions.

    The nearest point's arc length ``s`` on the wall (searched in the candidate blocks only,
    see the module docstring), then the tangent through the wall points at ``s -+ 0.5 m``
    (clamped to the wall's ends).

    Args:
        walls: Both walls.
        x: Positions, ``(P,)`` (m).
        y: Positions, ``(P,)`` (m).
        which: Wall of every position (0 left, 1 right), or one per position ``(P,)``.
        blocks: ``block_columns(walls, which)`` when already gathered (repeated searches of
            the same walls, e.g. one position per curve and chord); the results are the same.

    Returns:
        ``(wx, wy, tx, ty)``, each ``(P,)``.
    """
    if SCALAR_SEARCH and np.isfinite(x.sum() + y.sum()):
        wall = [which] * len(x) if isinstance(which, int) else which.tolist()
        found = bound_scalar.frames(wall_lists(walls), x.tolist(), y.tolist(), wall)
        wx, wy, tx, ty = np.array(found).reshape(4, len(x))
        norm = np.maximum(np.hypot(tx, ty), 1e-12)
        return wx, wy, tx / norm, ty / norm
    if len(x) <= _BRUTE_POSITIONS:
        return wall_frame_reference(walls, x, y, which)
    if blocks is None:
        if not isinstance(which, int) and len(x) > _SPLIT_POSITIONS:
            out = np.empty((4, len(x)))
            for wall in (0, 1):
                mine = which == wall
                out[:, mine] = wall_frame(walls, x[mine], y[mine], wall)
            return out[0], out[1], out[2], out[3]
        blocks = block_columns(walls, which)
    dx = x[:, None] - blocks.x
    dy = y[:, None] - blocks.y
    d2 = dx * dx + dy * dy
    upper = np.sqrt(d2.min(axis=1, keepdims=True))
    if not np.isfinite(upper.sum()):  # non-finite positions: leave them to the reference
        return wall_frame_reference(walls, x, y, which)
    reach = upper * (1 + _SLACK) + _SLACK + blocks.radius
    cand = d2 <= reach * reach
    empty = len(walls.blk_seg) - 1
    pick = np.sort(np.where(cand, blocks.cols, empty), axis=1)[:, : int(cand.sum(axis=1).max())]
    seg = walls.blk_seg[pick].reshape(len(x), -1)
    valid = np.repeat(pick < empty, BLOCK_SEGMENTS, axis=1)
    return _frame_at(walls, _nearest(walls, x, y, seg, valid), which)
