"""Overlay of two small simple polygons, the scalar twin of GEOS for the full sets (mypyc).

One frame's full sets are ~21 small overlays per object (a ``simple`` hexagon & the track
nearby, minus the deletion polygon); GEOS spends ~10-20 us on each, mostly fixed cost. This is
Greiner and Hormann's clipper for simple polygons without holes, on Python floats (compiled
with the other scalar twins, ``rss.compiled``)::

    a: +-------x=====x-------+     the crossings x, sorted along each ring, are walked in turn:
       |  b:   |     |       |     along a, switch to b at a crossing, along b, ... (which way:
       |       +-----+       |     the sign of the two edges' cross product)
       +---------------------+

It gives up (``None``: the caller runs GEOS) wherever exactness would need GEOS' robust
predicates: a crossing within ``EPS`` (relative, along either edge) of a vertex, edges closer to
parallel than ``EPS`` that come close, an edge shorter than ``EPS`` of its ring's extent or a
spike (an edge folding back onto the previous one), a result with a hole. Otherwise the result
is unique and its crossing points differ from GEOS' by rounding only (~1e-13 m on a track's
coordinates). Why not GEOS: ``docs/design-notes.md``, "Full reach sets without GEOS".
"""

from __future__ import annotations

from typing import Final

from reachsets.clip_rings import (
    EPS,
    Box,
    Edges,
    Run,
    area2,
    box_of,
    conditioned,
    dedup,
    inside,
)

__all__ = ["clip_prepared", "runs_near"]

#: Nearly parallel edges closer than this fraction of their lengths: degenerate.
_NEAR: Final = 1e-7


class _Hits:
    """The proper crossings of two rings, as parallel lists (one entry per crossing).

    ``ea``/``eb``: edge of ring ``a``/``b``; ``ka``/``kb``: edge index plus the position along
    the edge in ``(0, 1)`` (sort keys along each ring); ``x``/``y``: the point; ``d``: cross
    product of the two edge vectors (its sign: which way ``a`` crosses ``b``).
    """

    def __init__(self) -> None:
        self.ea: list[int] = []
        self.eb: list[int] = []
        self.ka: list[float] = []
        self.kb: list[float] = []
        self.x: list[float] = []
        self.y: list[float] = []
        self.d: list[float] = []


def runs_near(box: Box, e: Edges) -> list[Run]:
    """The runs of ``e`` whose bounding box meets ``box`` (x0, y0, x1, y1)."""
    lo_x = box[0]
    lo_y = box[1]
    hi_x = box[2]
    hi_y = box[3]
    return [r for r in e.runs if r.x0 <= hi_x and r.x1 >= lo_x and r.y0 <= hi_y and r.y1 >= lo_y]


def _crossings(a: list[float], box: Box, e: Edges) -> _Hits | None:
    """Proper crossings of ring ``a``'s edges (``box``: its bounding box) with ``e``'s.

    ``None`` if a contact is degenerate.
    """
    na = len(a) // 2
    near = runs_near(box, e)
    hits = _Hits()
    for i in range(na):
        i1 = (i + 1) % na
        ax = a[2 * i]
        ay = a[2 * i + 1]
        rx = a[2 * i1] - ax
        ry = a[2 * i1 + 1] - ay
        ex0, ex1 = (ax, a[2 * i1]) if rx > 0 else (a[2 * i1], ax)
        ey0, ey1 = (ay, a[2 * i1 + 1]) if ry > 0 else (a[2 * i1 + 1], ay)
        for run in near:  # iterating, not indexing: mypyc's unchecked list reads
            if run.x0 > ex1 or run.x1 < ex0 or run.y0 > ey1 or run.y1 < ey0:
                continue
            for g in run.segs:
                if g.x0 > ex1 or g.x1 < ex0 or g.y0 > ey1 or g.y1 < ey0:
                    continue
                if not _cross(hits, i, ax, ay, rx, ry, g.k, g.ax, g.ay, g.bx, g.by):
                    return None
    return hits


def _cross(  # noqa: PLR0917
    hits: _Hits,
    i: int,
    ax: float,
    ay: float,
    rx: float,
    ry: float,
    j: int,
    bx: float,
    by: float,
    bx1: float,
    by1: float,
) -> bool:
    """Add the crossing of edge ``i`` (``a + t r``) and edge ``j`` (``b -> b1``) if proper.

    Returns:
        ``False`` where the contact is degenerate (near an end, or nearly parallel and close).
    """
    sx = bx1 - bx
    sy = by1 - by
    lr = abs(rx) + abs(ry)
    ls = abs(sx) + abs(sy)
    qx = bx - ax
    qy = by - ay
    den = rx * sy - ry * sx
    cross = qx * ry - qy * rx
    if abs(den) <= EPS * lr * ls:
        return abs(cross) > _NEAR * lr * (lr + ls)
    t = (qx * sy - qy * sx) / den
    u = cross / den
    if t < -EPS or t > 1.0 + EPS or u < -EPS or u > 1.0 + EPS:
        return True
    if t <= EPS or t >= 1.0 - EPS or u <= EPS or u >= 1.0 - EPS:
        return False
    hits.ea.append(i)
    hits.eb.append(j)
    hits.ka.append(i + t)
    hits.kb.append(j + u)
    hits.x.append(ax + t * rx)
    hits.y.append(ay + t * ry)
    hits.d.append(den)
    return True


def _argsort(key: list[float]) -> list[int]:
    """Indices sorting ``key`` (insertion sort: a few crossings, already nearly in order)."""
    order: list[int] = []
    for k in range(len(key)):
        pos = len(order)
        while pos and key[order[pos - 1]] > key[k]:
            pos -= 1
        order.insert(pos, k)
    return order


class _Along:
    """The crossings in their order along one ring, to walk from one to the next.

    ``edge``/``key``: each crossing's edge of the ring and sort key (``_Hits``); ``order``: the
    crossings sorted along the ring, ``rank`` its inverse; ``ok``: no two keys are equal.
    """

    def __init__(self, p: list[float], edge: list[int], key: list[float]) -> None:
        self.p = p
        self.edge = edge
        self.key = key
        self.order = _argsort(key)
        self.rank = [0] * len(key)
        self.ok = True
        for r, k in enumerate(self.order):
            self.rank[k] = r
            if r and key[self.order[r - 1]] == key[k]:
                self.ok = False

    def walk(self, ring: list[float], k: int, forward: bool) -> int:  # noqa: FBT001
        """Append the ring's vertices from crossing ``k`` to the next one; return that one."""
        p = self.p
        n = len(self.order)
        m = len(p) // 2
        j = self.edge[k]
        if forward:
            nxt = self.order[(self.rank[k] + 1) % n]
            count = (self.edge[nxt] - j) % m
            if count == 0 and self.key[nxt] < self.key[k]:
                count = m
            # vertices j + 1 .. j + count, wrapping: list slices (no unboxing, no new floats)
            end = j + 1 + count
            ring += p[2 * (j + 1) : 2 * min(end, m)]
            if end > m:
                ring += p[: 2 * (end - m)]
            return nxt
        nxt = self.order[(self.rank[k] - 1) % n]
        count = (j - self.edge[nxt]) % m
        if count == 0 and self.key[nxt] > self.key[k]:
            count = m
        for c in range(count):
            v = (j - c) % m
            ring.append(p[2 * v])
            ring.append(p[2 * v + 1])
        return nxt


def clip_prepared(a: list[float], e: Edges, difference: bool) -> list[list[float]] | None:  # noqa: FBT001
    """``a & e`` (or ``a - e``) of simple rings as flat ``[x0, y0, x1, y1, ...]`` (open).

    Returns:
        The result's rings (each the shell of one part, no holes; none if empty), or ``None``
        where the case is degenerate or the result has a hole (GEOS decides).
    """
    a = dedup(a)
    if len(a) < 6 or not e.ok:  # noqa: PLR2004
        return None
    box = box_of(a)
    if not conditioned(a, box):
        return None
    hits = _crossings(a, box, e)
    if hits is None:
        return None
    if not hits.d:
        return _apart(a, e, difference)
    return _traverse(a, e, hits, difference)


def _apart(a: list[float], e: Edges, difference: bool) -> list[list[float]] | None:  # noqa: FBT001
    """The result for rings that do not cross: one inside the other, or apart."""
    b = e.xy
    if e.contains(a[0], a[1]):
        return [] if difference else [a]
    if inside(b[0], b[1], a):
        return None if difference else [b]
    return [a] if difference else []


def _traverse(a: list[float], e: Edges, hits: _Hits, difference: bool) -> list[list[float]] | None:  # noqa: FBT001
    """Greiner and Hormann's walk over the crossings: the result's rings.

    Each crossing's direction comes from the sign of its edges' cross product and the rings'
    orientations (``a`` enters a counter-clockwise ``b`` where ``a x b < 0``: it crosses
    ``b``'s edge from its right to its left), so no point-in-polygon test is needed.
    """
    n = len(hits.d)
    along_a = _Along(a, hits.ea, hits.ka)
    along_b = _Along(e.xy, hits.eb, hits.kb)
    if n % 2 or not along_a.ok or not along_b.ok:
        return None
    ccw_a = area2(a) > 0
    a_fwd = [((d < 0) == e.ccw) != difference for d in hits.d]
    b_fwd = [(d > 0) == ccw_a for d in hits.d]
    seen = [False] * n
    rings: list[list[float]] = []
    for start in range(n):
        if seen[start]:
            continue
        ring: list[float] = []
        k = start
        on_a = True
        while not seen[k]:
            seen[k] = True
            ring.append(hits.x[k])
            ring.append(hits.y[k])
            along, fwd = (along_a, a_fwd) if on_a else (along_b, b_fwd)
            k = along.walk(ring, k, fwd[k])
            on_a = not on_a
        if k != start or not on_a:
            return None
        rings.append(ring)
    return rings
