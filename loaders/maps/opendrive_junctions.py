"""ad-map's point order of OpenDRIVE lanes (its reader turns some junction lanes round).

ad-map's OpenDRIVE reader keeps every lane's borders along ``s`` (ours are stored in
driving direction, so lanes left of the reference line run the other way). In junctions
it then links lanes of different roads that share a border (end points within 1 mm) as
neighbours, taking the junction's lanes pairwise in the order it read them (roads in file
order, per section the ``<left>`` then the ``<right>`` lanes in document order). Where the
shared borders run against each other (the left border of one is the other's left
border reversed, or right and right) it reverses the *later* lane of the pair together
with every lane reachable through its neighbour links::

    earlier lane  ──left──────────▶            earlier lane  ──left──────────▶
    later lane    ◀──────────left──    ==>     later lane    ──right─────────▶  (reversed)

Only the point order matters here (ad-map's nearest-segment tie rule scans a border in
its point order, its width stations run along it); the geometry is the same.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING

if TYPE_CHECKING:
    from collections.abc import Iterable

    import numpy as np
    from numpy.typing import NDArray

__all__ = ["JunctionLane", "admap_reversed_along_s"]

#: ad-map's point equality (each coordinate closer than this, m).
_NEAR_M = 1e-3
_Key = tuple[str, int, int]  # road, section index, lane id


@dataclass(slots=True)
class JunctionLane:
    """One lane of a junction road as ad-map's reader holds it while linking neighbours.

    Attributes:
        key: ``(road, section index, lane id)``.
        left_m: First and last vertex of the left border seen along ``s``, ``(2, 2)``.
        right_m: First and last vertex of the right border seen along ``s``, ``(2, 2)``.
        left: The lane on the left (``None`` for none), in the lane's current order.
        right: The lane on the right.
        reversed: ad-map has reversed the lane (its points run against ``s``).
    """

    key: _Key
    left_m: NDArray[np.float64]
    right_m: NDArray[np.float64]
    left: _Key | None = None
    right: _Key | None = None
    reversed: bool = False

    def invert(self) -> None:
        """Reverse the point order: borders swap sides and ends, neighbours swap sides."""
        self.left_m, self.right_m = self.right_m[::-1], self.left_m[::-1]
        self.left, self.right = self.right, self.left
        self.reversed = not self.reversed


def _near(a: NDArray[np.float64], b: NDArray[np.float64]) -> bool:
    return bool(abs(a[0] - b[0]) < _NEAR_M and abs(a[1] - b[1]) < _NEAR_M)


def _same(a: NDArray[np.float64], b: NDArray[np.float64]) -> bool:
    """Both ends of two ``(2, 2)`` end pairs coincide."""
    return _near(a[0], b[0]) and _near(a[1], b[1])


def contact(a: JunctionLane, b: JunctionLane) -> str:
    """ad-map's contact place of two lanes: ``same``, ``lr``, ``ll``, ``rl``, ``rr`` or ``""``.

    ``lr``: ``a``'s left border is ``b``'s right border (same order); ``ll``: ``a``'s
    left border is ``b``'s left border reversed; ``rl`` and ``rr`` alike.
    """
    if _same(a.left_m, b.left_m) or _same(a.right_m, b.right_m):
        return "same"
    for name, mine, theirs in (
        ("lr", a.left_m, b.right_m),
        ("ll", a.left_m, b.left_m[::-1]),
        ("rl", a.right_m, b.left_m),
        ("rr", a.right_m, b.right_m[::-1]),
    ):
        if _same(mine, theirs):
            return name
    return ""


def _side_neighbours(lanes: dict[_Key, JunctionLane]) -> None:
    """In-section neighbours along ``s`` (outward on each side, the nearest across the centre)."""
    sections: dict[tuple[str, int], list[int]] = {}
    for road, idx, lid in lanes:
        sections.setdefault((road, idx), []).append(lid)
    for (road, idx), ids in sections.items():
        left = sorted((i for i in ids if i > 0), key=abs)
        right = sorted((i for i in ids if i < 0), key=abs)
        for side, other in ((left, right), (right, left)):
            for k, lid in enumerate(side):
                inward = side[k - 1] if k > 0 else (other[0] if other else None)
                outward = side[k + 1] if k + 1 < len(side) else None
                towards = None if inward is None else (road, idx, inward)
                away = None if outward is None else (road, idx, outward)
                lane = lanes[road, idx, lid]
                if lid > 0:  # along s the centre line is on the right of a left lane
                    lane.right, lane.left = towards, away
                else:
                    lane.left, lane.right = towards, away


def _invert_with_neighbours(lanes: dict[_Key, JunctionLane], start: _Key) -> None:
    group = {start}
    for side in ("left", "right"):
        nxt = getattr(lanes[start], side)
        while nxt is not None and nxt not in group:
            group.add(nxt)
            nxt = getattr(lanes[nxt], side)
    for key in group:
        lanes[key].invert()


def admap_reversed_along_s(junctions: Iterable[list[JunctionLane]]) -> set[_Key]:
    """Lanes whose points ad-map's reader turns against ``s`` (all other lanes run along it).

    Args:
        junctions: Per junction, all lanes of its roads (every lane type), in the order
            ad-map reads them, borders along ``s``. The lanes are changed in place.

    Returns:
        Keys of the lanes ad-map stores against ``s``.
    """
    out: set[_Key] = set()
    for order in junctions:
        lanes = {lane.key: lane for lane in order}
        _side_neighbours(lanes)
        for i, first in enumerate(order):
            for second in order[i:]:
                place = contact(first, second)
                if place in {"ll", "rr"}:
                    _invert_with_neighbours(lanes, second.key)
                if place in {"ll", "lr"}:
                    first.left, second.right = second.key, first.key
                elif place in {"rr", "rl"}:
                    first.right, second.left = second.key, first.key
        out.update(key for key, lane in lanes.items() if lane.reversed)
    return out
