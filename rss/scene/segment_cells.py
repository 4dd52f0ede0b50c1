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

import itertools
import math
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, NamedTuple

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
#: Pairs of (segment, cell) evaluated at once while building (bounds the peak memory).
_BLOCK_PAIRS = 1 << 18


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


def _boxes(
    lines: Polylines, seg: IntArray, origin: FloatArray, cell_m: float, grow_m: float
) -> tuple[IntArray, IntArray]:
    """``(S, 2)`` first and last cell ``(ix, iy)`` of each segment's box grown by ``grow_m``."""
    a, b = lines.xy_m[seg], lines.xy_m[seg + 1]
    lo = np.floor((np.minimum(a, b) - grow_m - origin) / cell_m).astype(np.int64)
    hi = np.floor((np.maximum(a, b) + grow_m - origin) / cell_m).astype(np.int64)
    return lo, hi


class _Grid(NamedTuple):
    """The cell grid: lower-left corner of cell ``(0, 0)``, cell side, ``(nx, ny)`` cells."""

    origin: FloatArray
    cell_m: float
    shape: tuple[int, int]


def _cells_of_lines(  # noqa: PLR0917 - one piece of segments, its boxes, the grid, its rows
    lines: Polylines,
    seg: IntArray,
    line: IntArray,
    boxes: tuple[IntArray, IntArray],
    grid: _Grid,
    band_m: float,
    rows: tuple[int, int] | None = None,
) -> tuple[IntArray, IntArray, IntArray]:
    """Keys, first and last candidate of the cells near the segments ``seg`` of ``line``.

    ``seg`` holds all segments of each of its lines, ``boxes`` their cell boxes grown by
    ``band_m`` and the slack (:func:`_boxes`); ``rows``: only the cells of rows ``iy`` in
    ``[rows[0], rows[1])`` (all of them get every segment that can matter). Sorted by key.
    """
    origin, cell_m, (nx, ny) = grid
    slack = _slack(cell_m)
    # every cell within band_m of the line has its nearest segment, and that segment's
    # candidates (within slack more), among the cells of the segments' grown boxes
    lo, hi = boxes
    if rows is not None:
        lo = np.column_stack([lo[:, 0], np.maximum(lo[:, 1], rows[0])])
        hi = np.column_stack([hi[:, 0], np.minimum(hi[:, 1], rows[1] - 1)])
        inside = lo[:, 1] <= hi[:, 1]
        seg, line, lo, hi = seg[inside], line[inside], lo[inside], hi[inside]
    a, b = lines.xy_m[seg], lines.xy_m[seg + 1]
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
    group = _run_of(starts, len(key))
    nearest = np.minimum.reduceat(d, starts) if len(starts) else d
    candidate = d < nearest[group] + slack
    first = np.minimum.reduceat(np.where(candidate, s, np.iinfo(np.int64).max), starts)
    last = np.maximum.reduceat(np.where(candidate, s, -1), starts)
    keep = nearest <= band_m
    return key[starts][keep], first[keep], last[keep]


def _slack(cell_m: float) -> float:
    """How much farther than the nearest one a segment may matter for a cell [m]."""
    r = cell_m * math.sqrt(0.5) + _SLACK_M
    return 2.0 * r + DISTANCE_TOL_M + _SLACK_M


def _run_of(starts: IntArray, size: int) -> IntArray:
    """``(size,)`` the run each element belongs to, runs starting at ``starts``."""
    return np.repeat(np.arange(len(starts)), np.diff(np.append(starts, size)))


def _run_starts(values: IntArray) -> IntArray:
    """Indices where runs of equal ``values`` ``(K,)`` start (empty for ``K = 0``)."""
    if not len(values):
        return np.zeros(0, dtype=np.int64)
    return np.flatnonzero(np.concatenate([[True], values[1:] != values[:-1]]))


@dataclass
class _Layout:
    """The rows of the cells laid out so far, piece after piece (in key order).

    Only rows holding cells are listed (``line``, ``iy``, ``x_first``, ``width``); the
    candidate segments of their cells are kept as ``int32`` pieces. Memory: the laid-out
    cells (8 bytes each) and the rows, never every cell's key.
    """

    shape: tuple[int, int]
    rows: list[tuple[IntArray, ...]] = field(default_factory=list)
    cells: list[tuple[npt.NDArray[np.int32], npt.NDArray[np.int32]]] = field(default_factory=list)

    def add(self, key: IntArray, first: IntArray, last: IntArray) -> None:
        """Lay out cells ``(key, first, last)`` sorted by key, their rows complete."""
        nx, ny = self.shape
        row_key, ix = key // nx, key % nx
        at = _run_starts(row_key)
        if not len(at):
            return
        x_first = np.minimum.reduceat(ix, at)
        width = np.maximum.reduceat(ix, at) - x_first + 1
        offset = np.cumsum(width) - width
        row = _run_of(at, len(key))
        where = offset[row] + ix - x_first[row]
        out_first = np.full(int(width.sum()), -1, dtype=np.int32)  # segment indices
        out_last = np.full(int(width.sum()), -1, dtype=np.int32)
        out_first[where], out_last[where] = first, last
        self.rows.append((row_key[at] // ny, row_key[at] % ny, x_first, width))
        self.cells.append((out_first, out_last))

    def cells_of(self, origin: FloatArray, cell_m: float, n_lines: int) -> SegmentCells:
        """The :class:`SegmentCells` (rows without cells inside a line's span: width 0)."""
        none = np.zeros(0, dtype=np.int64)
        line, iy, x_some, width_some = (
            np.concatenate([none, *(row[k] for row in self.rows)]) for k in range(4)
        )
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
        x_first[row], width[row] = x_some, width_some
        offset = np.cumsum(width) - width
        # one column joined at a time, its pieces freed before the next: the peak is the
        # cells once and one column twice
        empty = np.zeros(0, dtype=np.int32)
        lasts = [last for _, last in self.cells]
        firsts = [first for first, _ in self.cells]
        self.cells.clear()
        out_first = np.concatenate([empty, *firsts])
        del firsts
        out_last = np.concatenate([empty, *lasts])
        del lasts
        return SegmentCells(
            origin, cell_m, y_first, rows, row_base, x_first, width, offset, out_first, out_last
        )


def _row_bands(lo: IntArray, hi: IntArray) -> list[tuple[int, int]]:
    """Rows ``[y0, y1)`` of one line in bands of about :data:`_BLOCK_PAIRS` pairs each.

    ``lo``, ``hi``: ``(S, 2)`` cell boxes of the line's segments.
    """
    y0, y1 = int(lo[:, 1].min()), int(hi[:, 1].max()) + 1
    # pairs per row: each segment adds its box's width to every row of its box
    per_row = np.zeros(y1 - y0 + 1, dtype=np.int64)
    np.add.at(per_row, lo[:, 1] - y0, hi[:, 0] - lo[:, 0] + 1)
    np.add.at(per_row, hi[:, 1] + 1 - y0, -(hi[:, 0] - lo[:, 0] + 1))
    band = np.cumsum(np.cumsum(per_row[:-1])) // _BLOCK_PAIRS
    cuts = (np.flatnonzero(np.diff(band)) + 1 + y0).tolist()
    edges = [y0, *cuts, y1]
    return list(itertools.pairwise(edges))


def segment_cells(lines: Polylines, cell_m: float = CELL_M, band_m: float = BAND_M) -> SegmentCells:
    """Build the cells of ``lines`` (see module docstring); once per map.

    Memory: lines are taken in pieces of about :data:`_BLOCK_PAIRS` (segment, cell) pairs
    (consecutive lines together, a long line in bands of rows), each laid out at once, so
    the peak is the laid-out cells (8 bytes each, 12 while they are joined) plus one
    piece, whatever the map's size.

    Args:
        lines: The polylines (each with at least two vertices).
        cell_m: Cell side [m].
        band_m: Cells farther than this from their line are not stored [m].
    """
    count = np.diff(lines.start) - 1  # segments per line
    reach = band_m + 2.0 * cell_m + 1.0
    origin = lines.xy_m.min(axis=0) - reach
    nx, ny = (np.ceil((lines.xy_m.max(axis=0) + reach - origin) / cell_m).astype(int) + 1).tolist()
    shape = (int(nx), int(ny))
    multi = np.flatnonzero(count > 1)
    which, seg = flat_runs(lines.start[multi], count[multi])
    line = multi[which]
    lo, hi = _boxes(lines, seg, origin, cell_m, band_m + _slack(cell_m))
    pairs = np.bincount(which, np.prod(hi - lo + 1, axis=1), minlength=len(multi))
    ends = np.cumsum(count[multi]).tolist()  # each line's segments: seg[starts[k]:ends[k]]
    starts = [0, *ends[:-1]]
    grid = _Grid(origin, cell_m, shape)
    layout = _Layout(shape)

    def piece(a: int, b: int, rows: tuple[int, int] | None = None) -> None:
        boxes = (lo[a:b], hi[a:b])
        layout.add(*_cells_of_lines(lines, seg[a:b], line[a:b], boxes, grid, band_m, rows))

    first = 0  # the first line of the block of consecutive lines not laid out yet
    held = 0.0
    for k in range(len(multi)):
        if pairs[k] > _BLOCK_PAIRS:  # a long line alone, in bands of rows
            if first < k:
                piece(starts[first], starts[k])
            for band in _row_bands(lo[starts[k] : ends[k]], hi[starts[k] : ends[k]]):
                piece(starts[k], ends[k], band)
            first, held = k + 1, 0.0
            continue
        if held + pairs[k] > _BLOCK_PAIRS and first < k:
            piece(starts[first], starts[k])
            first, held = k, 0.0
        held += float(pairs[k])
    if first < len(multi):
        piece(starts[first], len(seg))
    return layout.cells_of(origin, cell_m, len(count))


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
