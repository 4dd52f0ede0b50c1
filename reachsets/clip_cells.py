"""Full reduced sets of one object with the clipper: ``(cell & area) - deletion`` (mypyc).

The drivable area is prepared once per track (``Area``); per object only its edges near the
object's sets are looked at (``_near``). See ``clip_scalar`` for the clipper and when it gives
up (``None``: the caller runs GEOS for that cell).
"""

from __future__ import annotations

import math
from typing import Final

from reachsets.clip_rings import Box, Edges, Run, Seg, area2, box_of, dedup, inside
from reachsets.clip_scalar import clip_prepared, runs_near

__all__ = ["SETTLED_TOL_M", "Area", "clip", "reduce_cells", "reduce_objects", "settled"]

#: Slack of ``settled``, metres: an edge this far inside the cell still counts as outside it
#: (what it leaves out is a sliver thinner than this along a chord of the cell).
SETTLED_TOL_M: Final = 1e-11


def _near(e: Edges, box: Box) -> Edges:
    """A view of ``e`` with only the edges whose bounding box meets ``box`` (x0, y0, x1, y1).

    Runs keep their order; each is cut down to its edges that meet ``box`` (its box shrinks).
    """
    v = Edges([], e)
    lo_x = box[0]
    lo_y = box[1]
    hi_x = box[2]
    hi_y = box[3]
    for run in runs_near(box, e):
        kept = [
            g for g in run.segs if g.x0 <= hi_x and g.x1 >= lo_x and g.y0 <= hi_y and g.y1 >= lo_y
        ]
        if kept:
            v.runs.append(Run(kept))
    return v


class Area:
    """A drivable area prepared for ``reduce_cells``: its shell and holes as flat open rings."""

    def __init__(self, shell: list[float], holes: list[list[float]]) -> None:
        """Prepare the rings (edge bounding boxes, orientation, conditioning)."""
        self.shell = Edges(dedup(shell))
        self.holes = [Edges(dedup(h)) for h in holes]


def reduce_cells(
    cells: list[list[float]], deletion: list[float], area: Area | None
) -> list[list[list[float]] | None]:
    """``(cell - deletion) & area`` of every cell of one object (rings as in ``clip``).

    Args:
        cells: The object's sets as flat open rings.
        deletion: Its deletion polygon (flat open ring), empty for none.
        area: The drivable area, ``None`` for no trimming.

    Returns:
        Per cell its rings, or ``None`` where ``clip`` gave up.
    """
    cut = Edges(dedup(deletion)) if deletion else None
    if cut is not None and not cut.ok:
        return [None for _ in cells]
    shell: Edges | None = None
    holes: list[Edges] = []
    if area is not None:
        boxes = [box_of(c) for c in cells]
        near = (
            min([b[0] for b in boxes]),
            min([b[1] for b in boxes]),
            max([b[2] for b in boxes]),
            max([b[3] for b in boxes]),
        )
        shell = _near(area.shell, near)
        for hole in area.holes:
            v = _near(hole, near)
            if v.runs:
                holes.append(v)
            elif inside(cells[0][0], cells[0][1], hole.xy):  # the sets lie in the hole
                return [[] for _ in cells]
    out: list[list[list[float]] | None] = []
    for cell in cells:
        parts: list[list[float]] | None = [cell]
        if cut is not None:
            parts = _minus(cell, cut)
        if shell is not None:
            parts = _each(parts, shell, difference=False)
        for hole in holes:
            parts = _each(parts, hole, difference=True)
        out.append(parts)
    return out


def reduce_objects(  # noqa: PLR0917
    rows: list[list[list[float]]],
    deletions: list[list[float] | None],
    area: Area | None,
    xy: list[float],
    sizes: list[int],
    owner: list[int],
    fallback: list[int],
) -> None:
    """``reduce_cells`` of every object, its rings appended flat (one pass, compiled).

    Args:
        rows: Per object its cells as flat open rings (the same number per object).
        deletions: Per object its deletion ring (empty: none), ``None``: not simple (all its
            cells go to ``fallback``).
        area: The drivable area, ``None`` for no trimming.
        xy: Receives every result ring's coordinates, closed (the first vertex repeated).
        sizes: Receives each ring's number of points (closing one included).
        owner: Receives each ring's flat cell index (object * cells + cell): increasing.
        fallback: Receives the flat indices of the cells the clipper gave up on.
    """
    for i in range(len(rows)):
        cells = rows[i]
        base = i * len(cells)
        cut = deletions[i]
        if cut is None:
            fallback.extend(range(base, base + len(cells)))
            continue
        k = base
        for parts in reduce_cells(cells, cut, area):
            if parts is None:
                fallback.append(k)
            else:
                for ring in parts:
                    xy.extend(ring)
                    xy.append(ring[0])
                    xy.append(ring[1])
                    sizes.append(len(ring) // 2 + 1)
                    owner.append(k)
            k += 1


def _minus(cell: list[float], cut: Edges) -> list[list[float]] | None:
    """``cell - cut``: the clipper's, else ``settled``'s closed form (``None``: neither)."""
    parts = clip_prepared(cell, cut, difference=True)
    return parts if parts is not None else settled(cell, cut)


def settled(cell: list[float], cut: Edges) -> list[list[float]] | None:
    """``cell - cut`` for a convex cell whose interior no edge of ``cut`` enters, else ``None``.

    The closed form of the contacts the clipper gives up on when they are only touches: at
    step 0 the body's front edge lies on an edge of the deletion polygon, which holds the rest
    of the body (so the cell is empty). No edge of ``cut`` enters the interior when, for each,
    the segment lies outside one of the cell's edge lines or the cell on one side of the
    segment's line (within ``SETTLED_TOL_M``); then the interior lies wholly inside ``cut``
    (empty) or wholly outside (the cell), as its centroid does.
    """
    a = dedup(cell)
    n = len(a) // 2
    turn = area2(a)
    if n < 3 or turn == 0.0:  # noqa: PLR2004
        return None
    sign = 1.0 if turn > 0 else -1.0
    for j in range(n):  # convex: every corner turns the same way
        k, m = (j + 1) % n, (j + 2) % n
        ex, ey = a[2 * k] - a[2 * j], a[2 * k + 1] - a[2 * j + 1]
        fx, fy = a[2 * m] - a[2 * k], a[2 * m + 1] - a[2 * k + 1]
        if sign * (ex * fy - ey * fx) < 0:
            return None
    for g in cut.segs:
        if not _outside(a, g, sign):
            return None
    cx = sum([a[2 * j] for j in range(n)]) / n
    cy = sum([a[2 * j + 1] for j in range(n)]) / n
    return [] if cut.contains(cx, cy) else [a]


def _outside(a: list[float], g: Seg, sign: float) -> bool:
    """Whether segment ``g`` misses the interior of the convex ring ``a`` (``sign``: its turn)."""
    px, py, qx, qy = g.ax, g.ay, g.bx, g.by
    n = len(a) // 2
    for j in range(n):  # the segment beyond one of the cell's edges
        k = (j + 1) % n
        ax, ay = a[2 * j], a[2 * j + 1]
        ex, ey = a[2 * k] - ax, a[2 * k + 1] - ay
        tol = SETTLED_TOL_M * math.sqrt(ex * ex + ey * ey)
        # outward is to the right of a counter-clockwise edge: sign * cross <= 0
        if (
            sign * (ex * (py - ay) - ey * (px - ax)) <= tol
            and sign * (ex * (qy - ay) - ey * (qx - ax)) <= tol
        ):
            return True
    sx, sy = qx - px, qy - py
    tol = SETTLED_TOL_M * math.sqrt(sx * sx + sy * sy)
    lo = hi = 0.0
    for j in range(n):  # the cell on one side of the segment's line
        c = sx * (a[2 * j + 1] - py) - sy * (a[2 * j] - px)
        lo = min(lo, c)
        hi = max(hi, c)
    return lo >= -tol or hi <= tol


def _each(parts: list[list[float]] | None, e: Edges, difference: bool) -> list[list[float]] | None:  # noqa: FBT001
    """Every part ``& e`` (or ``- e``); ``None`` if any of them gives up."""
    if parts is None:
        return None
    kept: list[list[float]] = []
    for part in parts:
        got = clip_prepared(part, e, difference)
        if got is None:
            return None
        kept += got
    return kept


def clip(a: list[float], b: list[float], difference: bool) -> list[list[float]] | None:  # noqa: FBT001
    """``clip_scalar.clip_prepared`` of two rings (``b`` prepared here)."""
    b = dedup(b)
    if len(b) < 6:  # noqa: PLR2004
        return None
    return clip_prepared(a, Edges(b), difference)
