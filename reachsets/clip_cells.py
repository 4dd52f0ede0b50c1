"""Full reduced sets of one object with the clipper: ``(cell & area) - deletion`` (mypyc).

The drivable area is prepared once per track (``Area``); per object only its edges near the
object's sets are looked at (``_near``). See ``clip_scalar`` for the clipper and when it gives
up (``None``: the caller runs GEOS for that cell).
"""

from __future__ import annotations

from reachsets.clip_rings import Edges, box_of, dedup, inside
from reachsets.clip_scalar import clip_prepared

__all__ = ["Area", "clip", "reduce_cells"]


def _near(e: Edges, box: list[float]) -> Edges:
    """A view of ``e`` with only the edges whose bounding box meets ``box`` (x0, y0, x1, y1)."""
    v = Edges([], e)
    j = -1
    for g in e.sel:
        j += 1
        if g.x0 <= box[2] and g.x1 >= box[0] and g.y0 <= box[3] and g.y1 >= box[1]:
            v.idx.append(e.idx[j])
            v.sel.append(g)
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
        near = [
            min([b[0] for b in boxes]),
            min([b[1] for b in boxes]),
            max([b[2] for b in boxes]),
            max([b[3] for b in boxes]),
        ]
        shell = _near(area.shell, near)
        for hole in area.holes:
            v = _near(hole, near)
            if v.idx:
                holes.append(v)
            elif inside(cells[0][0], cells[0][1], hole.xy):  # the sets lie in the hole
                return [[] for _ in cells]
    out: list[list[list[float]] | None] = []
    for cell in cells:
        parts: list[list[float]] | None = [cell]
        if cut is not None:
            parts = clip_prepared(cell, cut, difference=True)
        if shell is not None:
            parts = _each(parts, shell, difference=False)
        for hole in holes:
            parts = _each(parts, hole, difference=True)
        out.append(parts)
    return out


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
