"""Scalar twin of the ``bound`` curves' chord-by-chord continuation (few curves, one frame).

``reach_bound.wall_aware_arcs`` checks the wall rule on every chord of the ``turn`` arcs at
once and continues the curves that turn back chord by chord. Vectorised over the curves,
each chord costs about 25 numpy calls on arrays of one or two rows: the cost of one frame's
``bound`` check is mostly that loop. For a few curves (one frame, few objects) this module
walks each curve's chords with plain floats instead (compiled with mypyc with the other
scalar twins, see ``rss.compiled``): the nearest wall point among the segments a grid cell
lists (below; same pair arithmetic as ``walls.wall_frame``, same winner, ties to the lowest
segment), the wall point and tangent interpolated like ``np.interp`` (walked from the
winning segment's vertex), and the turn rule of ``reach_bound._turn``.
``math.atan2``/``math.hypot`` may differ from numpy's in the last bit, so the curves agree
with the vectorised ones to about 1e-12 m (tested to 1e-9 m). ``frames`` is the search alone
(no ``atan2``/``hypot``), bit-identical to numpy's, which ``walls.wall_frame`` uses when
compiled.

Each wall has a grid of square cells (``walls.wall_lists``); a cell lists, on first use, the
segments no farther from its centre than the centre's distance to the wall plus the cell's
diagonal: a point in the cell is at most half a diagonal from the centre, so no other
segment can be its nearest. Outside the grid the block search of ``walls`` picks them.
"""

from __future__ import annotations

import math
from bisect import bisect_right
from dataclasses import dataclass
from typing import Final

__all__ = ["WallLists", "continue_curve", "frames"]

_TANGENT_HALF_STEP_M: Final = 0.5
_SLACK: Final = 1e-9


@dataclass(frozen=True)
class WallLists:
    """``walls.Walls`` as Python lists (see its attributes).

    Attributes:
        cum: Arc length at each vertex of both walls.
        px: Vertex x.
        py: Vertex y.
        start_x: Segment start x.
        start_y: Segment start y.
        seg_x: Segment vector x.
        seg_y: Segment vector y.
        seg_len: Segment lengths.
        seg_len2: Squared lengths floored at 1e-24 m^2.
        seg_s: Arc length at each segment start.
        lo: Arc length where each wall starts.
        hi: Arc length where each wall ends.
        blk_seg: Segments of each block (real blocks only).
        blk_x: Vertex x of each block.
        blk_y: Vertex y of each block.
        blk_radius: Radius of each block.
        wall_blk: Blocks of each wall, ascending.
        grid: Per wall, ``x0, y0, cell`` of a grid of square cells (m) around it.
        grid_n: Per wall, ``nx, ny`` and the index of its first cell in ``grid_at``.
        cells: The segments of each cell, ascending, that can be the nearest of a position
            in it (``None`` until the cell is first used; ``_cell_segments``).
    """

    cum: list[float]
    px: list[float]
    py: list[float]
    start_x: list[float]
    start_y: list[float]
    seg_x: list[float]
    seg_y: list[float]
    seg_len: list[float]
    seg_len2: list[float]
    seg_s: list[float]
    lo: list[float]
    hi: list[float]
    blk_seg: list[list[int]]
    blk_x: list[float]
    blk_y: list[float]
    blk_radius: list[float]
    wall_blk: list[list[int]]
    grid: list[float]
    grid_n: list[int]
    cells: list[list[int] | None]


def _interp(w: WallLists, s: float, hint: int = -1) -> tuple[float, float]:
    """``np.interp(s, cum, px)`` and ``(..., py)`` (same branches and arithmetic).

    ``hint``: a vertex near ``s`` to walk from (else a binary search); the same interval.
    """
    cum = w.cum
    last = len(cum) - 1
    if s > cum[last]:
        return w.px[last], w.py[last]
    if s < cum[0]:
        return w.px[0], w.py[0]
    if hint < 0:
        j = bisect_right(cum, s) - 1
    else:  # the last vertex at or before s, as the binary search finds it
        j = min(hint, last)
        while j < last and cum[j + 1] <= s:
            j += 1
        while cum[j] > s:
            j -= 1
    if j == last or s == cum[j]:
        return w.px[j], w.py[j]
    span = cum[j + 1] - cum[j]
    return _lerp(w.px, cum, j, span, s), _lerp(w.py, cum, j, span, s)


def _lerp(fp: list[float], cum: list[float], j: int, span: float, s: float) -> float:
    """One column of ``_interp`` inside interval ``j`` (numpy's branches and arithmetic)."""
    slope = (fp[j + 1] - fp[j]) / span
    v = slope * (s - cum[j]) + fp[j]
    if math.isnan(v):
        v = slope * (s - cum[j + 1]) + fp[j + 1]
        if math.isnan(v) and fp[j] == fp[j + 1]:
            v = fp[j]
    return v


def _nearest_s(w: WallLists, x: float, y: float, wall: int) -> tuple[float, int]:
    """Arc length of the nearest point of wall ``wall`` (``walls.wall_frame``'s winner).

    The candidate segments are the position's grid cell's (listed on the cell's first
    use); outside the grid, those of the block search (``walls.wall_frame``). Either way a
    superset of the segments that can be the nearest, measured with the same pair
    arithmetic: the same winner.
    """
    g = 3 * wall
    cell = w.grid[g + 2]
    fx = (x - w.grid[g]) / cell
    fy = (y - w.grid[g + 1]) / cell
    nx, ny = w.grid_n[g], w.grid_n[g + 1]
    if 0.0 <= fx < nx and 0.0 <= fy < ny:
        i, j = int(fx), int(fy)
        c = w.grid_n[g + 2] + i * ny + j
        segs = w.cells[c]
        if segs is None:
            centre = (w.grid[g] + (i + 0.5) * cell, w.grid[g + 1] + (j + 0.5) * cell)
            segs = _cell_segments(w, centre, wall, cell)
            w.cells[c] = segs
        found = _closest(w, x, y, segs)
    else:
        found = _closest(w, x, y, _block_segments(w, x, y, wall))
    return found[0], found[1]


def _cell_segments(w: WallLists, centre: tuple[float, float], wall: int, cell: float) -> list[int]:
    """The segments of ``wall`` that can be the nearest of a position in a grid cell.

    A position ``p`` in the cell (centre ``c``, half diagonal ``h``) is at most ``D + h`` from
    the wall (``D``: the centre's distance), so a segment farther than ``D + 2 h`` from the
    centre is never its nearest (nor a tie): the others (plus 1 mm for rounding), ascending.
    ``D`` is measured on the blocks not farther than the nearest block vertex.
    """
    x, y = centre
    blocks = w.wall_blk[wall]
    near: list[float] = []  # each block's distance bound |c - c_b| - r_b
    upper = math.inf
    for b in blocks:
        d = math.hypot(x - w.blk_x[b], y - w.blk_y[b])
        upper = min(upper, d)
        near.append(d - w.blk_radius[b])
    dist = math.inf
    for k, b in enumerate(blocks):
        if near[k] <= upper:
            for j in w.blk_seg[b]:
                dist = min(dist, _dist2(w, x, y, j)[0])
    bound = math.sqrt(dist) + cell * math.sqrt(2.0) + 1e-3
    out: list[int] = []
    for k, b in enumerate(blocks):
        if near[k] <= bound:
            for j in w.blk_seg[b]:
                if (not out or j != out[-1]) and math.sqrt(_dist2(w, x, y, j)[0]) <= bound:
                    out.append(j)
    return out


def _block_segments(w: WallLists, x: float, y: float, wall: int) -> list[int]:
    """The segments of the candidate blocks of ``walls.wall_frame``'s block search."""
    blocks = w.wall_blk[wall]
    bx, by = w.blk_x, w.blk_y
    low = math.inf
    for b in blocks:
        dx = x - bx[b]
        dy = y - by[b]
        low = min(low, dx * dx + dy * dy)
    upper = math.sqrt(low)
    near: list[int] = []
    for b in blocks:
        reach = upper * (1 + _SLACK) + _SLACK + w.blk_radius[b]
        dx = x - bx[b]
        dy = y - by[b]
        if dx * dx + dy * dy <= reach * reach:  # the same d2 as above
            near.extend(w.blk_seg[b])
    return near


def _dist2(w: WallLists, x: float, y: float, j: int) -> tuple[float, float]:
    """Squared distance to segment ``j`` and the nearest point's fraction along it."""
    dx = x - w.start_x[j]
    dy = y - w.start_y[j]
    sx, sy = w.seg_x[j], w.seg_y[j]
    u = min(max((dx * sx + dy * sy) / w.seg_len2[j], 0.0), 1.0)
    ox = dx - u * sx
    oy = dy - u * sy
    return ox * ox + oy * oy, u


def _closest(w: WallLists, x: float, y: float, segs: list[int]) -> tuple[float, int, float]:
    """Arc length of the nearest point on segments ``segs``, its segment and squared distance.

    Ties go to the lowest segment, as numpy's ``argmin`` over ascending segments.
    """
    best = math.inf
    win = -1
    win_u = 0.0
    for j in segs:
        d, u = _dist2(w, x, y, j)
        if d < best or (d == best and j < win):
            best, win, win_u = d, j, u
    return w.seg_s[win] + win_u * w.seg_len[win], win, best


def frames(w: WallLists, xs: list[float], ys: list[float], which: list[int]) -> list[float]:
    """Nearest wall point and tangent chord of many finite positions (``walls.wall_frame``).

    The arithmetic of ``walls._nearest`` and ``walls._frame_at`` up to the tangent's
    normalisation (left to numpy's ``hypot``): bit-identical to the numpy search.

    Args:
        w: Both walls.
        xs: Positions x (m), ``n`` of them, all finite.
        ys: Positions y (m).
        which: Wall of each position (0 left, 1 right).

    Returns:
        ``4 n`` floats: the wall points' x, then their y, then the tangent chords' x (wall
        point at ``s + 0.5 m`` minus the one at ``s - 0.5 m``, clamped to the wall), then y.
    """
    n = len(xs)
    out = [0.0] * (4 * n)
    for i in range(n):
        wx, wy, tx, ty = _frame(w, xs[i], ys[i], which[i])
        out[i] = wx
        out[n + i] = wy
        out[2 * n + i] = tx
        out[3 * n + i] = ty
    return out


def _frame(w: WallLists, x: float, y: float, wall: int) -> tuple[float, float, float, float]:
    """Nearest point of wall ``wall`` and its tangent chord (not normalised), as ``frames``."""
    s, seg = _nearest_s(w, x, y, wall)
    vertex = seg + wall  # the segment's first vertex (each wall has one more vertex)
    wx, wy = _interp(w, s, vertex)
    ax, ay = _interp(w, min(s + _TANGENT_HALF_STEP_M, w.hi[wall]), vertex)
    bx, by = _interp(w, max(s - _TANGENT_HALF_STEP_M, w.lo[wall]), vertex)
    return wx, wy, ax - bx, ay - by


def _turn(
    w: WallLists,
    pose: tuple[float, float, float, float, float, float],
    wall: int,
    point: tuple[float, float, float, float],
    limits: tuple[float, float],
) -> tuple[float, bool]:
    """``reach_bound._turn`` of one chord: ``dpsi`` and ``towards`` (``pose`` as below)."""
    cx, cy, yaw0, co, si, side = pose
    xi, eta, psi, dmax = point
    step, max_turn = limits
    x = cx + co * xi - si * eta
    y = cy + si * xi + co * eta
    wx, wy, tx, ty = _frame(w, x, y, wall)
    norm = max(math.hypot(tx, ty), 1e-12)
    tx, ty = tx / norm, ty / norm
    clearance = -side * (tx * (y - wy) - ty * (x - wx))
    heading = yaw0 + side * psi
    rel = math.atan2(math.sin(heading), math.cos(heading)) - math.atan2(ty, tx)
    alpha = side * math.atan2(math.sin(rel), math.cos(rel))
    radius = step / (2 * math.sin(max(dmax, 1e-12) / 2))
    room = clearance - step * math.sin(alpha + dmax / 2)
    need = radius * (1 - math.cos(min(max(alpha + dmax, 0.0), math.pi)))
    towards = abs(alpha) >= math.pi / 2 or room >= need
    back = min(dmax, max(alpha, 0.0))
    return min(dmax if towards else -back, max_turn - psi), towards


def continue_curve(
    w: WallLists,
    pose: tuple[float, float, float, float, float, float],
    wall: int,
    arc: tuple[list[float], list[float], list[float], list[float]],
    limits: tuple[float, float],
) -> None:
    """Turn one curve by the wall rule from its first chord that may not turn towards the wall.

    Chord by chord on the ``turn`` arc while every chord may turn towards the wall (the arc
    is kept as it is); from the first one that may not, every chord is turned by the rule and
    the points after it are overwritten (``reach_bound.wall_aware_arcs_reference``).

    Args:
        w: Both walls.
        pose: Object ``x, y, yaw, cos(yaw), sin(yaw)`` (m, rad) and the curve's side
            (``+1.0`` left, ``-1.0`` right).
        wall: Its wall (0 left, 1 right).
        arc: The curve's ``turn`` arc ``(xi, eta, psi)`` (``P`` points each, ``eta`` signed)
            and ``dmax`` (``P - 1`` chords); ``xi``, ``eta`` and ``psi`` are overwritten in
            place where the rule turns the curve.
        limits: ``(arc_step_m, arc_max_turn_rad)``.
    """
    xi, eta, psi, dmax = arc
    step, side = limits[0], pose[5]
    ruled = False
    for k in range(1, len(xi)):
        dpsi, towards = _turn(
            w, pose, wall, (xi[k - 1], eta[k - 1], psi[k - 1], dmax[k - 1]), limits
        )
        ruled = ruled or not towards
        if ruled:
            chord = psi[k - 1] + dpsi / 2
            xi[k] = xi[k - 1] + step * math.cos(chord)
            eta[k] = eta[k - 1] + side * step * math.sin(chord)
            psi[k] = psi[k - 1] + dpsi
