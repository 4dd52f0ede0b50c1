"""Closed-form tests of convex pieces before shapely (compiled with mypyc).

A pair of trajectory-set pieces is tested with shapely (``intersects`` of the convex hulls,
touching included) in :mod:`rss.unstructured.intersect`. Most pairs of a small frame are
clearly apart or clearly overlapping; these tests decide them with plain floats and leave
only the near-touching ones to shapely, so the answer is shapely's:

* apart: an edge normal of one hull along which the other hull lies beyond it by more
  than a margin (separating axis: any axis is a valid witness);
* overlapping: a vertex of one hull inside the other by more than the margin, or two
  edges crossing properly by more than the margin (a witness point both hulls hold).

The margin (``MARGIN_RELATIVE`` of the coordinates' magnitude, about a micrometre at
1 km) is many orders above the rounding of these few products, so a verdict never
depends on it; anything within it is "unsure" and goes to shapely. Hulls are built from
the pieces' own points (gift wrapping), so every hull vertex is a point of the
piece.
"""

from __future__ import annotations

from typing import Any, Final

__all__ = [
    "APART",
    "MARGIN_RELATIVE",
    "OVERLAP",
    "UNSURE",
    "Pieces",
    "hull",
    "mark",
    "verdict",
    "verdicts",
]

#: Verdicts of :func:`verdict`.
APART: Final = 0
OVERLAP: Final = 1
UNSURE: Final = 2
#: Margin per metre of coordinate magnitude.
MARGIN_RELATIVE: Final = 1e-9
#: Vertices of a hull with an area (fewer: the pair goes to shapely).
_POLYGON: Final = 3


def hull(points: list[list[float]], size: int) -> list[float]:
    """Counter-clockwise hull vertices ``[x0, y0, x1, ...]`` of ``points[:size]`` (gift wrapping).

    Collinear and repeated points are skipped. Fewer than three vertices (no area), or a
    walk that does not close within ``size`` steps (rounding), returns what it has or
    nothing: :func:`verdict` leaves such pieces to shapely.
    """
    return _hull_xy([p[0] for p in points[:size]], [p[1] for p in points[:size]])


def _hull_xy(xs: list[float], ys: list[float]) -> list[float]:
    """:func:`hull` of the points ``(xs[i], ys[i])``."""
    n = len(xs)
    start = 0
    for i in range(1, n):
        if xs[i] < xs[start] or (xs[i] == xs[start] and ys[i] < ys[start]):
            start = i
    out: list[float] = []
    here = start
    for _ in range(n):
        px, py = xs[here], ys[here]
        out.extend((px, py))
        best, bx, by = here, 0.0, 0.0  # the best point's offset from ``here``
        for r in range(n):
            rx, ry = xs[r] - px, ys[r] - py
            turn = bx * ry - by * rx
            if turn < 0.0 or (turn == 0.0 and rx * rx + ry * ry > bx * bx + by * by):
                best, bx, by = r, rx, ry
        if best == start:
            return out
        if best == here:  # every point coincides
            return out
        here = best
    return []


def _magnitude(h: list[float]) -> float:
    out = 0.0
    for c in h:
        out = max(out, abs(c))
    return out


def _separates(a: list[float], b: list[float], margin: float) -> bool:
    """Some edge normal of ``a`` has all of ``b`` beyond ``a`` by more than ``margin``."""
    n = len(a) // 2
    for i in range(n):
        j = (i + 1) % n
        ex, ey = a[2 * j] - a[2 * i], a[2 * j + 1] - a[2 * i + 1]
        nx, ny = ey, -ex  # outward normal of a counter-clockwise hull
        top = -1e300
        for k in range(n):
            top = max(top, nx * a[2 * k] + ny * a[2 * k + 1])
        low = 1e300
        for k in range(len(b) // 2):
            low = min(low, nx * b[2 * k] + ny * b[2 * k + 1])
        if low - top > margin * (abs(nx) + abs(ny)):
            return True
    return False


def _holds(a: list[float], x: float, y: float, margin: float) -> bool:
    """``(x, y)`` lies inside hull ``a`` by more than ``margin`` from every edge line."""
    n = len(a) // 2
    for i in range(n):
        j = (i + 1) % n
        ex, ey = a[2 * j] - a[2 * i], a[2 * j + 1] - a[2 * i + 1]
        side = ex * (y - a[2 * i + 1]) - ey * (x - a[2 * i])
        if side <= margin * (abs(ex) + abs(ey)):
            return False
    return True


def _side(  # noqa: PLR0917  (plain floats: compiled code)
    ax: float, ay: float, bx: float, by: float, px: float, py: float, margin: float
) -> int:
    """Side of ``p`` of the line ``a -> b``: 1 left, -1 right, 0 within the margin."""
    ex, ey = bx - ax, by - ay
    side = ex * (py - ay) - ey * (px - ax)
    limit = margin * (abs(ex) + abs(ey))
    return 1 if side > limit else -1 if side < -limit else 0


def _edges_cross(a: list[float], b: list[float], margin: float) -> bool:
    """An edge of ``a`` and one of ``b`` cross properly (each ends strictly on both sides)."""
    na, nb = len(a) // 2, len(b) // 2
    for i in range(na):
        i2 = (i + 1) % na
        ax, ay, bx, by = a[2 * i], a[2 * i + 1], a[2 * i2], a[2 * i2 + 1]
        for k in range(nb):
            k2 = (k + 1) % nb
            cx, cy, dx, dy = b[2 * k], b[2 * k + 1], b[2 * k2], b[2 * k2 + 1]
            s1 = _side(ax, ay, bx, by, cx, cy, margin)
            s2 = _side(ax, ay, bx, by, dx, dy, margin)
            if s1 * s2 != -1:
                continue
            s3 = _side(cx, cy, dx, dy, ax, ay, margin)
            s4 = _side(cx, cy, dx, dy, bx, by, margin)
            if s3 * s4 == -1:
                return True
    return False


def verdict(a: list[float], b: list[float]) -> int:
    """:data:`APART`, :data:`OVERLAP` or :data:`UNSURE` (shapely decides) of two hulls."""
    if len(a) < 2 * _POLYGON or len(b) < 2 * _POLYGON:
        return UNSURE
    margin = MARGIN_RELATIVE * (1.0 + max(_magnitude(a), _magnitude(b)))
    if _separates(a, b, margin) or _separates(b, a, margin):
        return APART
    for k in range(len(a) // 2):
        if _holds(b, a[2 * k], a[2 * k + 1], margin):
            return OVERLAP
    for k in range(len(b) // 2):
        if _holds(a, b[2 * k], b[2 * k + 1], margin):
            return OVERLAP
    if _edges_cross(a, b, margin):
        return OVERLAP
    return UNSURE


class Pieces:
    """The pieces of a :class:`rss.unstructured.sets.TrajectorySets`, hulls built on first use."""

    def __init__(self, coords: Any, size: list[int]) -> None:
        """``coords``: ``(K, P, 2)`` points; ``size``: ``(P,)`` points of each piece."""
        self.coords = coords
        self.size = size
        self.points: dict[int, tuple[list[float], list[float]]] = {}
        self.hulls: dict[int, list[float]] = {}

    def _points(self, piece: int) -> tuple[list[float], list[float]]:
        out = self.points.get(piece)
        if out is None:
            xy = self.coords[: self.size[piece], piece].T.tolist()
            out = (xy[0], xy[1])
            self.points[piece] = out
        return out

    def hull(self, piece: int) -> list[float]:
        """:func:`hull` of one piece."""
        out = self.hulls.get(piece)
        if out is None:
            xs, ys = self._points(piece)
            out = _hull_xy(xs, ys)
            self.hulls[piece] = out
        return out


def mark(  # noqa: PLR0917  (the arrays of one test round)
    ego: Pieces,
    agents: Pieces,
    pairs: tuple[list[int], list[int]],
    rows: list[int],
    owner: list[int],
    flags: list[list[bool]],
) -> list[int]:
    """Set ``flags[row][owner]`` of the pairs that overlap; the unsure pairs for shapely.

    A pair whose conditions are all set already is skipped (each condition is an "any"
    over its pairs, so the flags do not depend on which pairs are tested).

    Args:
        ego: The ego pieces.
        agents: The agent pieces.
        pairs: ``(ego piece, agent piece)``, ``(M,)`` each.
        rows: ``(M,)`` bit ``r`` set: an overlap of the pair sets condition ``r`` (0..2).
        owner: ``(M,)`` agent of the agent piece.
        flags: The three conditions ``(3, N)``, updated in place.

    Returns:
        The pairs (indices into ``pairs``) left to shapely.
    """
    unsure = []
    for k in range(len(owner)):
        who, bits = owner[k], rows[k]
        if all(flags[r][who] for r in range(3) if bits >> r & 1):
            continue
        found = verdict(ego.hull(pairs[0][k]), agents.hull(pairs[1][k]))
        if found == OVERLAP:
            for r in range(3):
                if bits >> r & 1:
                    flags[r][who] = True
        elif found == UNSURE:
            unsure.append(k)
    return unsure


def verdicts(
    ego: tuple[list[list[list[float]]], list[int]],
    agents: tuple[list[list[list[float]]], list[int]],
    pairs: tuple[list[int], list[int]],
) -> list[int]:
    """:func:`verdict` of every pair of pieces.

    Args:
        ego: ``(points (U, K, 2), sizes (U,))`` of the ego pieces the pairs use.
        agents: Likewise, the agent pieces.
        pairs: ``(ego piece, agent piece)`` indices into those, ``(M,)`` each.
    """
    ego_hulls = [hull(p, s) for p, s in zip(ego[0], ego[1], strict=True)]
    agent_hulls = [hull(p, s) for p, s in zip(agents[0], agents[1], strict=True)]
    return [verdict(ego_hulls[i], agent_hulls[j]) for i, j in zip(*pairs, strict=True)]
