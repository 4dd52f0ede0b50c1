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

__all__ = ["EPS", "clip", "reduce_cells"]

#: Crossing parameters this close to an edge's end, and sines of edge angles this small,
#: are degenerate (GEOS decides them).
EPS = 1e-9
#: Nearly parallel edges closer than this fraction of their lengths: degenerate.
_NEAR = 1e-7


def _dedup(p: list[float]) -> list[float]:
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


def _conditioned(p: list[float]) -> bool:
    """No edge shorter than ``EPS`` of the ring's extent, no vertex folding an edge back."""
    n = len(p) // 2
    lo_x = hi_x = p[0]
    lo_y = hi_y = p[1]
    for i in range(1, n):
        lo_x = min(lo_x, p[2 * i])
        hi_x = max(hi_x, p[2 * i])
        lo_y = min(lo_y, p[2 * i + 1])
        hi_y = max(hi_y, p[2 * i + 1])
    tiny = EPS * (hi_x - lo_x + hi_y - lo_y)
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


def _inside(x: float, y: float, p: list[float]) -> bool:
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


class _Edges:
    """A ring's edges with their bounding boxes, computed once per ring clipped against."""

    def __init__(self, p: list[float]) -> None:
        n = len(p) // 2
        self.xy = p
        self.x0: list[float] = []
        self.x1: list[float] = []
        self.y0: list[float] = []
        self.y1: list[float] = []
        self.ccw = _area2(p) > 0
        self.ok = _conditioned(p)
        for j in range(n):
            k = (j + 1) % n
            self.x0.append(min(p[2 * j], p[2 * k]))
            self.x1.append(max(p[2 * j], p[2 * k]))
            self.y0.append(min(p[2 * j + 1], p[2 * k + 1]))
            self.y1.append(max(p[2 * j + 1], p[2 * k + 1]))


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


def _candidates(a: list[float], e: _Edges) -> list[int]:
    """The edges of ``e`` whose bounding box meets ring ``a``'s."""
    lo_x = hi_x = a[0]
    lo_y = hi_y = a[1]
    for i in range(1, len(a) // 2):
        lo_x = min(lo_x, a[2 * i])
        hi_x = max(hi_x, a[2 * i])
        lo_y = min(lo_y, a[2 * i + 1])
        hi_y = max(hi_y, a[2 * i + 1])
    x0 = e.x0
    x1 = e.x1
    y0 = e.y0
    y1 = e.y1
    return [
        j
        for j in range(len(x0))
        if x0[j] <= hi_x and x1[j] >= lo_x and y0[j] <= hi_y and y1[j] >= lo_y
    ]


def _crossings(a: list[float], e: _Edges) -> _Hits | None:
    """Proper crossings of ring ``a``'s edges with ``e``'s, ``None`` if a contact is degenerate."""
    b = e.xy
    nb = len(b) // 2
    na = len(a) // 2
    cand = _candidates(a, e)
    hits = _Hits()
    for i in range(na):
        i1 = (i + 1) % na
        ax = a[2 * i]
        ay = a[2 * i + 1]
        rx = a[2 * i1] - ax
        ry = a[2 * i1 + 1] - ay
        ex0 = min(ax, ax + rx)
        ex1 = max(ax, ax + rx)
        ey0 = min(ay, ay + ry)
        ey1 = max(ay, ay + ry)
        for j in cand:
            if e.x0[j] > ex1 or e.x1[j] < ex0 or e.y0[j] > ey1 or e.y1[j] < ey0:
                continue
            k = j + 1 if j + 1 < nb else 0
            if not _cross(
                hits, i, ax, ay, rx, ry, j, b[2 * j], b[2 * j + 1], b[2 * k], b[2 * k + 1]
            ):
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


def _area2(p: list[float]) -> float:
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


class _Along:
    """The crossings in their order along one ring, to walk from one to the next.

    ``edge``/``key``: each crossing's edge of the ring and sort key (``_Hits``); ``order``: the
    crossings sorted along the ring, ``rank`` its inverse; ``ok``: no two keys are equal.
    """

    def __init__(self, p: list[float], edge: list[int], key: list[float]) -> None:
        self.p = p
        self.edge = edge
        self.key = key
        self.order = sorted(range(len(key)), key=key.__getitem__)
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
            for c in range(1, count + 1):
                v = (j + c) % m
                ring.append(p[2 * v])
                ring.append(p[2 * v + 1])
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


def clip(a: list[float], b: list[float], difference: bool) -> list[list[float]] | None:  # noqa: FBT001
    """``a & b`` (or ``a - b``) of two simple rings as flat ``[x0, y0, x1, y1, ...]`` (open).

    Returns:
        The result's rings (each the shell of one part, no holes; none if empty), or ``None``
        where the case is degenerate or the result has a hole (GEOS decides).
    """
    b = _dedup(b)
    if len(b) < 6:  # noqa: PLR2004
        return None
    return _clip(a, _Edges(b), difference)


def _clip(a: list[float], e: _Edges, difference: bool) -> list[list[float]] | None:  # noqa: FBT001
    """``clip`` against a prepared ring."""
    a = _dedup(a)
    if len(a) < 6 or not e.ok or not _conditioned(a):  # noqa: PLR2004
        return None
    hits = _crossings(a, e)
    if hits is None:
        return None
    if not hits.d:
        return _apart(a, e.xy, difference)
    return _traverse(a, e, hits, difference)


def _apart(a: list[float], b: list[float], difference: bool) -> list[list[float]] | None:  # noqa: FBT001
    """The result for rings that do not cross: one inside the other, or apart."""
    if _inside(a[0], a[1], b):
        return [] if difference else [a]
    if _inside(b[0], b[1], a):
        return None if difference else [b]
    return [a] if difference else []


def _traverse(a: list[float], e: _Edges, hits: _Hits, difference: bool) -> list[list[float]] | None:  # noqa: FBT001
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
    ccw_a = _area2(a) > 0
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


def reduce_cells(
    cells: list[list[float]], deletion: list[float], area: list[float]
) -> list[list[list[float]] | None]:
    """``(cell - deletion) & area`` of every cell of one object (rings as in ``clip``).

    Computed as ``(cell & area) - deletion``: the same set, and the hexagon against the track
    first leaves fewer edges for the difference.

    Args:
        cells: The object's sets as flat open rings.
        deletion: Its deletion polygon (flat open ring), empty for none.
        area: The drivable area near it (flat open ring), empty for no trimming.

    Returns:
        Per cell its rings, or ``None`` where ``clip`` gave up.
    """
    cut = _Edges(_dedup(deletion)) if deletion else None
    near = _Edges(_dedup(area)) if area else None
    if (cut is not None and len(cut.xy) < 6) or (near is not None and len(near.xy) < 6):  # noqa: PLR2004
        return [None for _ in cells]
    out: list[list[list[float]] | None] = []
    for cell in cells:
        parts: list[list[float]] | None = [cell]
        if near is not None:
            parts = _clip(cell, near, difference=False)
        if parts is not None and cut is not None:
            kept: list[list[float]] = []
            for part in parts:
                got = _clip(part, cut, difference=True)
                if got is None:
                    parts = None
                    break
                kept += got
            else:
                parts = kept
        out.append(parts)
    return out
