"""Per map: the polyline segments that can be nearest to the points of each grid cell.

The nearest-segment search (``admap_nearest.nearest_on_lines``) tries every segment of a
window of each line. Most points are clearly nearest to one or two of them, so a grid of
square cells (side ``h``) is built once per map and stores, per line and cell near it, the
range of segments that can hold the nearest point of *any* point in the cell, or lie within
ad-map's 1 mm tie tolerance of it. The distance to a segment changes no faster than the
point moves, so with ``C`` the cell centre, ``r = h / sqrt(2)`` and ``m(C)`` the distance of
``C`` to the line::

    point P in the cell:  m(P) <= m(C) + r          d(P, S) >= d(C, S) - r
    S can matter for P only if d(P, S) < m(P) + 1 mm, hence only if
                          d(C, S) < m(C) + 2 r + 1 mm

    ───s0───●───s1───●───s2───   cell ▢ above the vertex between s1 and s2:
                  ▢                range s1..s2 (s0 farther by more than 2 r + 1 mm)

Only lines of several segments get cells, and only cells within ``band_m`` of their line;
other points keep the window they were given. The search result does not change: a row
whose window holds the cell's whole range finds the same segments within 1 mm of its
nearest one, in the same order (``narrowed``).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np

from rss.scene.admap_nearest import DISTANCE_TOL_M, flat_runs

if TYPE_CHECKING:
    import numpy.typing as npt

    from rss.arrays import FloatArray, IntArray
    from rss.scene.polylines import Polylines

__all__ = ["BAND_M", "CELL_M", "SegmentCells", "narrowed", "segment_cells"]

#: Cell side [m].
CELL_M = 0.5
#: Cells are kept up to this distance from their line [m] (points of a box on a lane lie
#: within a lane width and a box width of its borders).
BAND_M = 6.0
#: Margin on every distance bound [m] (rounding of the kernel's float arithmetic).
_SLACK_M = 1e-6
#: Cell coordinates are clamped to this before the cast to integers.
_FAR = float(1 << 40)
#: Pairs of (segment, cell) evaluated at once while building.
_BLOCK_PAIRS = 1 << 20


@dataclass(frozen=True)
class SegmentCells:
    """Candidate segment ranges of the grid cells near lines of several segments.

    Cell ``(ix, iy)`` spans ``origin_m + (ix, iy) * cell_m`` to ``+ cell_m``. The cells of
    line ``l`` lie in its rows ``iy = y_first[l] .. y_first[l] + rows[l] - 1``, stored as
    rows ``row_base[l] + iy - y_first[l]``; row ``r`` holds the cells
    ``ix = x_first[r] .. x_first[r] + width[r] - 1`` at ``offset[r] + ix - x_first[r]``
    (direct look-ups, no search)::

        line l:  iy ─▶ row ─▶ ix ─▶ cell ─▶ first..last

    Attributes:
        origin_m: ``(2,)`` lower-left corner of cell ``(0, 0)``.
        cell_m: Cell side.
        y_first: ``(L,)`` first row ``iy`` of each line.
        rows: ``(L,)`` rows of each line (0: no cells).
        row_base: ``(L,)`` index of each line's first row.
        x_first: ``(R,)`` first cell ``ix`` of each row.
        width: ``(R,)`` cells of each row.
        offset: ``(R,)`` index of each row's first cell.
        first: ``(C,)`` first candidate segment of each cell (its start vertex in the
            ``Polylines``); -1 for cells beyond the band.
        last: ``(C,)`` last candidate segment.
    """

    origin_m: FloatArray
    cell_m: float
    y_first: IntArray
    rows: IntArray
    row_base: IntArray
    x_first: IntArray
    width: IntArray
    offset: IntArray
    first: npt.NDArray[np.int32]
    last: npt.NDArray[np.int32]


def _distance(p: FloatArray, a: FloatArray, b: FloatArray) -> FloatArray:
    """Distances of points ``p`` to segments ``a -> b``, all ``(Q, 2)``."""
    d = b - a
    dd = d[:, 0] * d[:, 0] + d[:, 1] * d[:, 1]
    rel = p - a
    t = np.clip((rel[:, 0] * d[:, 0] + rel[:, 1] * d[:, 1]) / np.where(dd > 0.0, dd, 1.0), 0, 1)
    off = rel - d * t[:, None]
    out: FloatArray = np.hypot(off[:, 0], off[:, 1])
    return out


def _cells_of_lines(  # noqa: PLR0917 - the grid and one block of segments
    lines: Polylines,
    seg: IntArray,
    line: IntArray,
    origin: FloatArray,
    cell_m: float,
    shape: tuple[int, int],
    band_m: float,
) -> tuple[IntArray, IntArray, IntArray]:
    """Keys, first and last candidate of the cells near the segments ``seg`` of ``line``.

    ``seg`` holds all segments of each of its lines.
    """
    nx, ny = shape
    r = cell_m * math.sqrt(0.5) + _SLACK_M
    slack = 2.0 * r + DISTANCE_TOL_M + _SLACK_M
    a, b = lines.xy_m[seg], lines.xy_m[seg + 1]
    # every cell within band_m of the line has its nearest segment, and that segment's
    # candidates (within slack more), among the cells of the segments' grown boxes
    lo = np.floor((np.minimum(a, b) - band_m - slack - origin) / cell_m).astype(np.int64)
    hi = np.floor((np.maximum(a, b) + band_m + slack - origin) / cell_m).astype(np.int64)
    wide = hi[:, 0] - lo[:, 0] + 1
    row, local = flat_runs(np.zeros(len(seg), dtype=np.int64), wide * (hi[:, 1] - lo[:, 1] + 1))
    ix = lo[row, 0] + local % wide[row]
    iy = lo[row, 1] + local // wide[row]
    centre = origin + (np.stack([ix, iy], axis=1) + 0.5) * cell_m
    d = _distance(centre, a[row], b[row])
    key = (line[row] * ny + iy) * nx + ix
    order = np.argsort(key, kind="stable")
    key, d, s = key[order], d[order], seg[row[order]]
    starts = _run_starts(key)
    group = np.repeat(np.arange(len(starts)), np.diff(np.append(starts, len(key))))
    nearest = np.minimum.reduceat(d, starts)
    candidate = d < nearest[group] + slack
    first = np.minimum.reduceat(np.where(candidate, s, np.iinfo(np.int64).max), starts)
    last = np.maximum.reduceat(np.where(candidate, s, -1), starts)
    keep = nearest <= band_m
    return key[starts][keep], first[keep], last[keep]


def _run_starts(values: IntArray) -> IntArray:
    """Indices where runs of equal ``values`` ``(K,)`` start (empty for ``K = 0``)."""
    if not len(values):
        return np.zeros(0, dtype=np.int64)
    return np.flatnonzero(np.concatenate([[True], values[1:] != values[:-1]]))


def _rows(
    origin: FloatArray,
    cell_m: float,
    shape: tuple[int, int],
    n_lines: int,
    cells: tuple[IntArray, ...],
) -> SegmentCells:
    """Lay out the cells ``(key, first, last)`` (sorted by key) in rows (see SegmentCells)."""
    nx, ny = shape
    key, first, last = cells
    line, iy, ix = key // (nx * ny), key // nx % ny, key % nx
    y_first = np.zeros(n_lines, dtype=np.int64)
    rows = np.zeros(n_lines, dtype=np.int64)
    at = _run_starts(line)
    if len(at):
        y_first[line[at]] = np.minimum.reduceat(iy, at)
        rows[line[at]] = np.maximum.reduceat(iy, at) - y_first[line[at]] + 1
    row_base = np.cumsum(rows) - rows
    row = row_base[line] + iy - y_first[line]
    x_first = np.zeros(int(rows.sum()), dtype=np.int64)
    width = np.zeros(int(rows.sum()), dtype=np.int64)
    at = _run_starts(row)
    if len(at):
        x_first[row[at]] = np.minimum.reduceat(ix, at)
        width[row[at]] = np.maximum.reduceat(ix, at) - x_first[row[at]] + 1
    offset = np.cumsum(width) - width
    out_first = np.full(int(width.sum()), -1, dtype=np.int32)  # segment indices
    out_last = np.full(int(width.sum()), -1, dtype=np.int32)
    where = offset[row] + ix - x_first[row]
    out_first[where], out_last[where] = first, last
    return SegmentCells(
        origin, cell_m, y_first, rows, row_base, x_first, width, offset, out_first, out_last
    )


def segment_cells(lines: Polylines, cell_m: float = CELL_M, band_m: float = BAND_M) -> SegmentCells:
    """Build the cells of ``lines`` (see module docstring); once per map.

    Args:
        lines: The polylines (each with at least two vertices).
        cell_m: Cell side [m].
        band_m: Cells farther than this from their line are not stored [m].
    """
    count = np.diff(lines.start) - 1  # segments per line
    reach = band_m + 2.0 * cell_m + 1.0
    origin = lines.xy_m.min(axis=0) - reach
    nx, ny = (np.ceil((lines.xy_m.max(axis=0) + reach - origin) / cell_m).astype(int) + 1).tolist()
    multi = np.flatnonzero(count > 1)
    # pairs per line, roughly, to cut the lines into blocks of bounded memory
    extent = np.array(
        [
            np.prod(np.ptp(lines.xy_m[lines.start[k] : lines.start[k + 1]], axis=0) + 2 * reach)
            for k in multi.tolist()
        ]
    ).reshape(-1)
    weight = extent / (cell_m * cell_m) * count[multi]
    block = np.floor(np.cumsum(weight) / _BLOCK_PAIRS).astype(np.int64)
    parts: list[tuple[IntArray, IntArray, IntArray]] = [(np.zeros(0, dtype=np.int64),) * 3]
    for b in np.unique(block).tolist():
        some = multi[block == b]
        which, seg = flat_runs(lines.start[some], count[some])
        parts.append(
            _cells_of_lines(lines, seg, some[which], origin, cell_m, (int(nx), int(ny)), band_m)
        )
    cells = tuple(np.concatenate(column) for column in zip(*parts, strict=True))
    return _rows(origin, cell_m, (int(nx), int(ny)), len(count), cells)


def narrowed(
    cells: SegmentCells, which: IntArray, points: FloatArray, first: IntArray, last: IntArray
) -> tuple[IntArray, IntArray]:
    """The segment windows ``first..last`` ``(Q,)`` of ``points`` on ``which``, narrowed.

    A row takes its cell's range where the cell is stored and the window holds the whole
    range; else it keeps its window.

    Args:
        cells: ``segment_cells`` of the lines.
        which: ``(Q,)`` line of each point.
        points: ``(Q, 2)`` points.
        first: ``(Q,)`` first segment of each row's window.
        last: ``(Q,)`` last segment.
    """
    if not len(cells.first):
        return first, last
    # floor of the cell coordinates; NaN and far points land beyond every row
    f = np.fmax(np.fmin((points - cells.origin_m) / cells.cell_m, _FAR), -1.0)
    ix, iy = np.floor(f, out=f).astype(np.int64).T
    r = iy - cells.y_first[which]
    ok = (r >= 0) & (r < cells.rows[which])
    row = np.where(ok, cells.row_base[which] + r, 0)
    c = ix - cells.x_first[row]
    ok &= (c >= 0) & (c < cells.width[row])
    k = np.where(ok, cells.offset[row] + c, 0)
    lo, hi = cells.first[k], cells.last[k]
    ok &= (lo >= first) & (hi <= last)
    return np.where(ok, lo, first), np.where(ok, hi, last)
