"""Trajectory sets as unions of convex pieces, built for many agents at once.

ad-rss builds each set by successive ``boost::geometry::union_`` of convex hulls of
footprint groups (a step's vehicle locations, the estimation between two steps, the gap
to the current footprint). Here the hulls are kept as separate convex pieces: two sets
intersect iff some pair of their pieces does (:func:`rss.unstructured.intersect.intersections`
tests all agents at once). A piece is stored as its points; its shapely hull is built on
demand. :meth:`TrajectorySets.polygons` merges the pieces for display and IoU checks.

Footprint arrays are ``(N, 4, 2)`` (one per agent) or ``(R, N, 4, 2)`` (R per agent).
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any, Protocol

import numpy as np
import shapely

if TYPE_CHECKING:
    from collections.abc import Sequence

    from rss.arrays import BoolArray, FloatArray, IntArray

__all__ = [
    "Location",
    "PieceCollector",
    "Pieces",
    "TrajectorySets",
    "front_and_sides",
    "hulls_of",
    "pieces_from_points",
]

#: (left, centre, right) footprints of one step: arrays ``(N, 4, 2)`` for
#: :class:`PieceCollector`, footprint rows (an int or a list) for
#: :class:`rss.unstructured.batch.RowPieces`.
Location = tuple[Any, Any, Any]


class Pieces(Protocol):
    """Where :func:`front_and_sides` adds pieces (footprint arrays or footprint rows)."""

    def add(self, *footprints: Any, brake: bool) -> None:
        """Add the hull of the given footprints."""


@dataclass(frozen=True)
class TrajectorySets:
    """Convex pieces of the brake and continue-forward sets of ``A`` agents.

    Every piece belongs to the continue-forward set; pieces with ``brake`` set also belong
    to the brake set (ad-rss starts the continue-forward polygon from the brake polygon).
    A piece is the convex hull of its points; the shapely hulls are built on first use and
    only for the pieces asked for (:meth:`hulls_at`), so a check that rules pairs out by
    their bounding boxes never builds them.

    Attributes:
        coords: ``(K, P, 2)`` the points of each piece (point-major: reductions over the
            points run over contiguous slabs), padded to ``K`` by repeating the piece's
            last point (a repeated point leaves the hull as is).
        size: ``(P,)`` number of points of each piece before padding.
        owner: ``(P,)`` agent index of each piece.
        brake: ``(P,)`` piece belongs to the brake set.
        count: Number of agents ``A``.
    """

    coords: FloatArray
    size: IntArray
    owner: IntArray
    brake: BoolArray
    count: int
    _hulls: np.ndarray = field(init=False, repr=False, compare=False)
    _built: BoolArray = field(init=False, repr=False, compare=False)

    def __post_init__(self) -> None:
        """Start with no hull built."""
        object.__setattr__(self, "_hulls", np.empty(self.owner.shape, dtype=object))
        object.__setattr__(self, "_built", np.zeros(self.owner.shape, dtype=bool))

    @staticmethod
    def empty(count: int) -> TrajectorySets:
        """No pieces for ``count`` agents."""
        none = np.zeros(0, dtype=np.int64)
        return TrajectorySets(np.zeros((1, 0, 2)), none, none, none.astype(bool), count)

    @staticmethod
    def concat(parts: Sequence[tuple[TrajectorySets, IntArray]], count: int) -> TrajectorySets:
        """Merge sets of agent groups; ``parts`` pairs a group's sets with its agent indices."""
        if not parts:
            return TrajectorySets.empty(count)
        width = max(s.coords.shape[0] for s, _ in parts)
        return TrajectorySets(
            np.concatenate([_pad(s.coords, width) for s, _ in parts], axis=1),
            np.concatenate([s.size for s, _ in parts]),
            np.concatenate([idx[s.owner] for s, idx in parts]),
            np.concatenate([s.brake for s, _ in parts]),
            count,
        )

    def select(self, keep: BoolArray, count: int, *, shift: int = 0) -> TrajectorySets:
        """The pieces where ``keep``, their owners lowered by ``shift``, for ``count`` agents."""
        return TrajectorySets(
            np.compress(keep, self.coords, axis=1),
            self.size[keep],
            self.owner[keep] - shift,
            self.brake[keep],
            count,
        )

    def piece_range(self, lo: int, hi: int, owner: IntArray, count: int) -> TrajectorySets:
        """Pieces ``lo .. hi - 1`` with new owners ``(hi - lo,)``, for ``count`` agents.

        The part is a view: it shares this set's points and its hull cache (a hull built
        through either is built for both).
        """
        part = object.__new__(TrajectorySets)  # no fresh hull cache: it gets views
        for name, value in (
            ("coords", self.coords[:, lo:hi]),
            ("size", self.size[lo:hi]),
            ("owner", owner),
            ("brake", self.brake[lo:hi]),
            ("count", count),
            ("_hulls", self._hulls[lo:hi]),
            ("_built", self._built[lo:hi]),
        ):
            object.__setattr__(part, name, value)
        return part

    def bounds(self) -> tuple[FloatArray, FloatArray]:
        """``(low, high)`` corners of every piece's axis-aligned box, ``(P, 2)`` each."""
        return self.coords.min(axis=0), self.coords.max(axis=0)

    def hulls_at(self, index: IntArray) -> np.ndarray:
        """Shapely hulls of the pieces at ``index`` (each built once)."""
        return hulls_of([(self, index)])[0]

    def _missing(self, index: IntArray) -> tuple[IntArray, FloatArray, IntArray]:
        """Pieces at ``index`` without a hull: ids, their real points ``(Σ size, 2)``, sizes."""
        wanted = np.zeros(self._built.shape, dtype=bool)
        wanted[index] = True
        missing = np.flatnonzero(wanted & ~self._built)
        points = np.swapaxes(self.coords[:, missing], 0, 1)  # (M, K, 2)
        sizes = self.size[missing]
        return missing, points[np.arange(points.shape[1]) < sizes[:, None]], sizes

    def _store(self, missing: IntArray, hulls: np.ndarray) -> None:
        self._hulls[missing] = hulls
        self._built[missing] = True

    @property
    def hulls(self) -> np.ndarray:
        """``(P,)`` shapely hulls of every piece (convex polygons; degenerate ones may be lines)."""
        return self.hulls_at(np.arange(self.owner.shape[0]))

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


def hulls_of(requests: Sequence[tuple[TrajectorySets, IntArray]]) -> list[np.ndarray]:
    """Hulls of the pieces at each ``(sets, index)``; the missing ones built in one call."""
    todo = [(sets, *sets._missing(index)) for sets, index in requests]  # noqa: SLF001
    todo = [t for t in todo if t[1].size]
    if todo:
        sizes = np.concatenate([t[3] for t in todo])
        lines = shapely.linestrings(
            np.concatenate([t[2] for t in todo]), indices=np.repeat(np.arange(sizes.size), sizes)
        )
        hulls = shapely.convex_hull(lines)
        bounds = np.cumsum([0, *(t[1].size for t in todo)])
        for (sets, missing, _, _), lo, hi in zip(todo, bounds[:-1], bounds[1:], strict=True):
            sets._store(missing, hulls[lo:hi])  # noqa: SLF001
    return [np.asarray(sets._hulls[index]) for sets, index in requests]  # noqa: SLF001


def _pad(coords: FloatArray, width: int) -> FloatArray:
    """``(K, P, 2)`` points padded to ``width`` by repeating the last point."""
    extra = width - coords.shape[0]
    if extra == 0:
        return coords
    return np.concatenate((coords, np.repeat(coords[-1:], extra, axis=0)))


def pieces_from_points(groups: Sequence[FloatArray], brake: Sequence[bool]) -> TrajectorySets:
    """Pieces of ``N`` agents from point groups ``(N, K_g, 2)`` (piece-major, owner = agent).

    Args:
        groups: One point group per piece of every agent.
        brake: Per group, its pieces belong to the brake set.
    """
    n = groups[0].shape[0]
    width = max(g.shape[1] for g in groups)
    coords = np.concatenate([_pad(np.swapaxes(g, 0, 1), width) for g in groups], axis=1)
    size = np.repeat([g.shape[1] for g in groups], n)
    owner = np.tile(np.arange(n), len(groups))
    return TrajectorySets(coords, size, owner, np.repeat(np.asarray(brake, dtype=bool), n), n)


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
        """The collected groups as pieces."""
        return pieces_from_points(self._points, self._brake)


def front_and_sides(
    pieces: Pieces,
    initial: Location,
    sides: Sequence[Location],
    front: Location,
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
