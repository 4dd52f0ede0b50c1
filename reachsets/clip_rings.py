"""Rings for the clipper (``clip_scalar``): flat open vertex lists and prepared edges (mypyc).

A ring is ``[x0, y0, x1, y1, ...]`` without the closing vertex. ``Edges`` keeps a ring's edge
bounding boxes, orientation and whether it is well conditioned for the clipper.
"""

from __future__ import annotations

from typing import Final

__all__ = [
    "EPS",
    "Box",
    "Edges",
    "Run",
    "Seg",
    "area2",
    "box_of",
    "conditioned",
    "dedup",
    "inside",
    "runs_of",
    "surely_simple",
]

#: Crossing parameters this close to an edge's end, and sines of edge angles this small,
#: are degenerate (GEOS decides them).
EPS: Final = 1e-9
#: A bounding box ``(x0, y0, x1, y1)`` (a tuple of floats: unboxed when compiled).
Box = tuple[float, float, float, float]


def dedup(p: list[float]) -> list[float]:
    """The ring without repeated consecutive vertices (the closing one included).

    The ring itself when it has none (the usual case: no copy, no float boxing).
    """
    n = len(p) // 2
    for i in range(n):
        j = i - 1 if i else n - 1
        if p[2 * i] == p[2 * j] and p[2 * i + 1] == p[2 * j + 1]:
            break
    else:
        return p
    out: list[float] = []
    for i in range(n):
        x = p[2 * i]
        y = p[2 * i + 1]
        if out and out[-2] == x and out[-1] == y:
            continue
        out.append(x)
        out.append(y)
    while len(out) > 2 and out[0] == out[-2] and out[1] == out[-1]:  # noqa: PLR2004
        del out[-2:]
    return out


def box_of(p: list[float]) -> Box:
    """Bounding box of ring ``p``: ``(x0, y0, x1, y1)`` (comparisons: compiled to C)."""
    lo_x = hi_x = p[0]
    lo_y = hi_y = p[1]
    for i in range(1, len(p) // 2):
        x = p[2 * i]
        y = p[2 * i + 1]
        if x < lo_x:  # noqa: PLR1730
            lo_x = x
        if x > hi_x:  # noqa: PLR1730
            hi_x = x
        if y < lo_y:  # noqa: PLR1730
            lo_y = y
        if y > hi_y:  # noqa: PLR1730
            hi_y = y
    return (lo_x, lo_y, hi_x, hi_y)


def conditioned(p: list[float], box: Box) -> bool:
    """No edge shorter than ``EPS`` of the ring's extent (``box``), no edge folding back."""
    n = len(p) // 2
    tiny = EPS * (box[2] - box[0] + box[3] - box[1])
    px = p[2 * n - 2] - p[2 * n - 4]
    py = p[2 * n - 1] - p[2 * n - 3]
    j = n - 1
    for i in range(n):
        qx = p[2 * i] - p[2 * j]
        qy = p[2 * i + 1] - p[2 * j + 1]
        lq = abs(qx) + abs(qy)
        if lq <= tiny:
            return False
        if qx * px + qy * py < 0 and abs(px * qy - py * qx) <= EPS * lq * (abs(px) + abs(py)):
            return False
        px = qx
        py = qy
        j = i
    return True


def inside(x: float, y: float, p: list[float]) -> bool:
    """Whether ``(x, y)`` lies inside ring ``p`` (crossing number; not on its boundary)."""
    n = len(p) // 2
    inside = False
    jx = p[2 * n - 2]
    jy = p[2 * n - 1]
    for i in range(n):
        ix = p[2 * i]
        iy = p[2 * i + 1]
        if (iy > y) != (jy > y) and x < ix + (y - iy) * (jx - ix) / (jy - iy):
            inside = not inside
        jx = ix
        jy = iy
    return inside


class Seg:
    """Edge ``k`` of a ring, ``(ax, ay) -> (bx, by)``, and its bounding box (native, mypyc)."""

    def __init__(self, ax: float, ay: float, bx: float, by: float, k: int = 0) -> None:
        """Keep the end points and the index; the box is derived."""
        self.k = k
        self.ax = ax
        self.ay = ay
        self.bx = bx
        self.by = by
        self.x0, self.x1 = (ax, bx) if ax < bx else (bx, ax)
        self.y0, self.y1 = (ay, by) if ay < by else (by, ay)


#: Consecutive edges per ``Run`` (a clip tests a run's box before its edges' boxes).
RUN: Final = 8


class Run:
    """Consecutive edges of a ring (in ring order, at least one) and the box of them all."""

    def __init__(self, segs: list[Seg]) -> None:
        """Keep the edges; the box is their union."""
        self.segs = segs
        g = segs[0]
        x0, y0, x1, y1 = g.x0, g.y0, g.x1, g.y1
        for h in segs:
            x0 = min(x0, h.x0)
            y0 = min(y0, h.y0)
            x1 = max(x1, h.x1)
            y1 = max(y1, h.y1)
        self.x0 = x0
        self.y0 = y0
        self.x1 = x1
        self.y1 = y1


def runs_of(segs: list[Seg]) -> list[Run]:
    """``segs`` (in ring order) cut into runs of ``RUN`` consecutive edges."""
    return [Run(segs[i : i + RUN]) for i in range(0, len(segs), RUN)]


class Edges:
    """A ring's edges with their bounding boxes, computed once per ring clipped against.

    ``runs``: the edges a clip looks at (all, or those near one object: ``clip_cells``) as
    runs of consecutive edges in ring order, each edge knowing its index in the ring
    (``Seg.k``). A clip tests a run's box before its edges' boxes: the edges it tests, and
    their order, are the same as edge by edge.
    """

    def __init__(self, p: list[float], base: Edges | None = None) -> None:
        """The edges of ring ``p``, or an empty view of ``base``'s (same edges, no ``runs``)."""
        self.xy: list[float] = p
        self.segs: list[Seg] = []
        self.ccw: bool = False
        self.ok: bool = False
        self.runs: list[Run] = []
        if base is not None:  # a view of ``base``
            self.xy = base.xy
            self.segs = base.segs
            self.ccw = base.ccw
            self.ok = base.ok
            return
        n = len(p) // 2
        for j in range(n):
            k = j + 1 if j + 1 < n else 0
            self.segs.append(Seg(p[2 * j], p[2 * j + 1], p[2 * k], p[2 * k + 1], j))
        self.ccw = area2(p) > 0
        self.ok = n >= 3 and conditioned(p, box_of(p))  # noqa: PLR2004
        self.runs = runs_of(self.segs)

    def contains(self, x: float, y: float) -> bool:
        """``inside(x, y, self.xy)``, edge by edge (the same test per edge, native floats)."""
        inside = False
        for g in self.segs:
            if (g.by > y) != (g.ay > y) and x < g.bx + (y - g.by) * (g.ax - g.bx) / (g.ay - g.by):
                inside = not inside
        return inside


def area2(p: list[float]) -> float:
    """Twice the signed area of ring ``p`` (positive: counter-clockwise)."""
    n = len(p) // 2
    total = 0.0
    jx = p[2 * n - 2]
    jy = p[2 * n - 1]
    for i in range(n):
        ix = p[2 * i]
        iy = p[2 * i + 1]
        total += jx * iy - ix * jy
        jx = ix
        jy = iy
    return total


def surely_simple(ring: list[float]) -> bool:
    """Whether ring ``ring`` is surely a valid polygon shell for GEOS (``False``: ask GEOS).

    ``True`` only when every coordinate is finite, at least three vertices are distinct
    (repeated consecutive ones dropped, as GEOS does), no two edges that do not share a
    vertex come near each other (disjoint boxes, or one edge's ends strictly on one side of
    the other's line by more than ``EPS`` of the extent squared), and no two consecutive
    edges fold back onto each other. Near contacts answer ``False`` (conservative).
    """
    p = dedup(ring)
    n = len(p) // 2
    if n < 3 or any(v - v != 0.0 for v in p):  # noqa: PLR2004  (NaN, infinities)
        return False
    box = box_of(p)
    ext = box[2] - box[0] + box[3] - box[1]
    tol = EPS * ext * ext
    if not conditioned(p, box):
        return False
    segs = Edges(p).segs
    for i in range(n):
        g = segs[i]
        for j in range(i + 2, n if i else n - 1):
            h = segs[j]
            if g.x1 < h.x0 or h.x1 < g.x0 or g.y1 < h.y0 or h.y1 < g.y0:
                continue
            if not (_apart(g, h, tol) or _apart(h, g, tol)):
                return False
    return True


def _apart(g: Seg, h: Seg, tol: float) -> bool:
    """Whether both ends of ``h`` lie strictly on one side of ``g``'s line (margin ``tol``)."""
    dx = g.bx - g.ax
    dy = g.by - g.ay
    s = dx * (h.ay - g.ay) - dy * (h.ax - g.ax)
    t = dx * (h.by - g.ay) - dy * (h.bx - g.ax)
    return (s > tol and t > tol) or (s < -tol and t < -tol)
