"""Per-lane constants of one prepared graph as Python lists (built once by ``prepare``).

The per-object code of scene creation reads lane constants one at a time; scalar access
to numpy arrays costs ≈ 100 ns a time, to a list item a few.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np

if TYPE_CHECKING:
    from rss.arrays import BoolArray, FloatArray
    from rss.scene.lanegraph import LaneGraph

__all__ = ["GraphScalars"]


class GraphScalars:
    """Per-lane constants of one prepared graph as Python lists (see module docstring).

    Attributes:
        direction: ``(L,)`` traffic-direction codes relative to the point order.
        speed_limit_mps: ``(L,)`` speed limits (NaN where unknown).
        centre_length_m: ``(L,)`` centre-line lengths.
        centre_xy_m: Per lane, the centre-line points ``[[x, y], ...]``.
        centre_arc_m: Per lane, the cumulative arc length at each centre-line point
            (starts at 0).
        left_neighbour: ``(L,)`` adjacent lane on the left, -1 for none.
        right_neighbour: ``(L,)`` adjacent lane on the right, -1 for none.
        left_opposite: ``(L,)`` the left neighbour's point order is reversed.
        right_opposite: ``(L,)`` the right neighbour's point order is reversed.
        is_intersection: ``(L,)`` lane lies inside an intersection.
        conflict_rows: ``(L, L)`` ``prep.conflicts`` as nested lists.
    """

    def __init__(self, g: LaneGraph, centre_length_m: FloatArray, conflicts: BoolArray) -> None:
        """Convert the arrays of ``g`` and of its prepared geometry once."""
        self.direction: list[int] = [int(v) for v in g.direction]
        self.speed_limit_mps: list[float] = np.asarray(g.speed_limit_mps, float).tolist()
        self.centre_length_m: list[float] = np.asarray(centre_length_m, float).tolist()
        self.centre_xy_m: list[list[list[float]]] = [c.tolist() for c in g.centre_m]
        self.centre_arc_m: list[list[float]] = [
            np.concatenate(
                [[0.0], np.cumsum(np.hypot(np.diff(c[:, 0]), np.diff(c[:, 1])))]
            ).tolist()
            for c in g.centre_m
        ]
        self.left_neighbour: list[int] = [int(v) for v in g.left_neighbour]
        self.right_neighbour: list[int] = [int(v) for v in g.right_neighbour]
        self.left_opposite: list[bool] = [bool(v) for v in g.left_opposite]
        self.right_opposite: list[bool] = [bool(v) for v in g.right_opposite]
        self.is_intersection: list[bool] = np.asarray(g.is_intersection, bool).tolist()
        self.conflict_rows: list[list[bool]] = np.asarray(conflicts, bool).tolist()
