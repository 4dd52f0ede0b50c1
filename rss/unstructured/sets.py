"""Trajectory sets as unions of convex pieces, built for many agents at once.

ad-rss builds each set by successive ``boost::geometry::union_`` of convex hulls of
footprint groups (a step's vehicle locations, the estimation between two steps, the gap
to the current footprint). Here the hulls are kept as separate convex pieces: two sets
intersect iff some pair of their pieces does, which an STRtree answers for all agents in
one query. :meth:`TrajectorySets.polygons` merges the pieces for display and IoU checks.

Footprint arrays are ``(N, 4, 2)`` (one per agent) or ``(R, N, 4, 2)`` (R per agent).
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np
import shapely

if TYPE_CHECKING:
    from collections.abc import Sequence

    from rss.batch import BoolArray, FloatArray, IntArray

__all__ = ["Location", "PieceCollector", "TrajectorySets", "front_and_sides"]

#: (left, centre, right) footprints of one step, each ``(N, 4, 2)``.
Location = tuple["FloatArray", "FloatArray", "FloatArray"]


@dataclass(frozen=True)
class TrajectorySets:
    """Convex pieces of the brake and continue-forward sets of ``A`` agents.

    Every piece belongs to the continue-forward set; pieces with ``brake`` set also belong
    to the brake set (ad-rss starts the continue-forward polygon from the brake polygon).

    Attributes:
        hulls: ``(P,)`` shapely geometries (convex polygons; degenerate hulls may be lines).
        owner: ``(P,)`` agent index of each piece.
        brake: ``(P,)`` piece belongs to the brake set.
        count: Number of agents ``A``.
    """

    hulls: np.ndarray
    owner: IntArray
    brake: BoolArray
    count: int

    @staticmethod
    def concat(parts: Sequence[tuple[TrajectorySets, IntArray]], count: int) -> TrajectorySets:
        """Merge sets of agent groups; ``parts`` pairs a group's sets with its agent indices."""
        if not parts:
            empty = np.zeros(0, dtype=np.int64)
            return TrajectorySets(np.empty(0, dtype=object), empty, empty.astype(bool), count)
        return TrajectorySets(
            np.concatenate([s.hulls for s, _ in parts]),
            np.concatenate([idx[s.owner] for s, idx in parts]),
            np.concatenate([s.brake for s, _ in parts]),
            count,
        )

    def polygons(self, *, brake: bool) -> np.ndarray:
        """Merged set per agent: ``(A,)`` shapely geometries, holes filled (as ad-rss' outer ring).

        Args:
            brake: The brake set (else the continue-forward set).
        """
        out = np.empty(self.count, dtype=object)
        keep = self.brake if brake else np.ones(self.owner.shape, dtype=bool)
        order = np.argsort(self.owner[keep], kind="stable")
        hulls, owners = self.hulls[keep][order], self.owner[keep][order]
        bounds = np.searchsorted(owners, np.arange(self.count + 1))
        for a in range(self.count):
            merged = shapely.union_all(hulls[bounds[a] : bounds[a + 1]])
            if isinstance(merged, shapely.Polygon):
                merged = shapely.Polygon(merged.exterior)
            out[a] = merged
        return out


class PieceCollector:
    """Collects footprint groups of ``N`` agents whose convex hulls form the sets."""

    def __init__(self, count: int) -> None:
        """Start empty for ``count`` agents."""
        self.count = count
        self._points: list[FloatArray] = []
        self._brake: list[bool] = []

    def add(self, *footprints: FloatArray, brake: bool) -> None:
        """Add the hull of the given footprints (each ``(N, 4, 2)`` or ``(R, N, 4, 2)``)."""
        parts = [
            fp.reshape(self.count, 4, 2)
            if fp.ndim == 3  # noqa: PLR2004  (N, 4, 2)
            else np.moveaxis(fp, 0, 1).reshape(self.count, -1, 2)
            for fp in footprints
        ]
        self._points.append(np.concatenate(parts, axis=1))
        self._brake.append(brake)

    def add_points(self, points: FloatArray, *, brake: bool) -> None:
        """Add the hull of a point group ``(N, K, 2)`` (e.g. a circle)."""
        self._points.append(points)
        self._brake.append(brake)

    def build(self) -> TrajectorySets:
        """Convex hulls of every collected group: one shapely call per group size."""
        n = self.count
        hulls = np.empty((len(self._points), n), dtype=object)
        sizes = np.array([p.shape[1] for p in self._points], dtype=np.int64)
        for size in np.unique(sizes):
            rows = np.flatnonzero(sizes == size)
            coords = np.stack([self._points[r] for r in rows]).reshape(-1, int(size), 2)
            hulls[rows] = shapely.convex_hull(shapely.linestrings(coords)).reshape(len(rows), n)
        owner = np.tile(np.arange(n), len(self._points))
        brake = np.repeat(np.array(self._brake, dtype=bool), n)
        return TrajectorySets(hulls.reshape(-1), owner, brake, n)


def front_and_sides(
    pieces: PieceCollector,
    initial: Location,
    sides: Sequence[Location],
    front: tuple[FloatArray, FloatArray, FloatArray],
    *,
    brake: bool,
) -> Location:
    """Side steps, the front step and the estimations between consecutive steps.

    ad-rss ``calculateFrontAndSidePolygon``: each step adds hull(left + centre) and
    hull(centre + right); consecutive steps are joined by hull(prev left, prev centre,
    left, centre) and the same on the right.

    Args:
        pieces: Collector to add to.
        initial: Locations the first side step is joined to.
        sides: Side steps (one left / centre / right footprint each).
        front: ``(left (Rl, N, 4, 2), centre (N, 4, 2), right (Rr, N, 4, 2))``; left ordered
            to the max-left footprint last, right with the max-right footprint first.
        brake: The pieces belong to the brake set.

    Returns:
        The front step's locations (max left, centre, max right).
    """
    prev = initial
    for left, centre, right in sides:
        pieces.add(left, centre, brake=brake)
        pieces.add(centre, right, brake=brake)
        pieces.add(prev[0], prev[1], left, centre, brake=brake)
        pieces.add(prev[2], prev[1], right, centre, brake=brake)
        prev = (left, centre, right)
    left_all, centre, right_all = front
    pieces.add(left_all, centre, brake=brake)
    pieces.add(centre, right_all, brake=brake)
    loc = (left_all[-1], centre, right_all[0])
    pieces.add(prev[0], prev[1], loc[0], loc[1], brake=brake)
    pieces.add(prev[2], prev[1], loc[2], loc[1], brake=brake)
    return loc
