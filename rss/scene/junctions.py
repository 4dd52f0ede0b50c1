"""Junctions of a lane graph: connected intersection lanes (built once by ``prepare``).

Intersection lanes belong to one junction when they overlap, merge, split or link; lanes
outside intersections belong to none (-1).
"""

from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np

if TYPE_CHECKING:
    from rss.arrays import BoolArray, IntArray
    from rss.scene.lanegraph import LaneGraph

__all__ = ["junction_ids"]


def _components(n: int, pairs: list[tuple[int, int]]) -> IntArray:
    """Connected-component root per node (union-find)."""
    parent = list(range(n))

    def root(a: int) -> int:
        while parent[a] != a:
            a = parent[a]
        return a

    for a, b in pairs:
        parent[root(a)] = root(b)
    return np.array([root(a) for a in range(n)], dtype=np.int64)


def junction_ids(g: LaneGraph, conflicts: BoolArray) -> IntArray:
    """``(L,)`` junction index per lane (-1 outside; see module docstring).

    Args:
        g: The lane graph.
        conflicts: ``(L, L)`` intersection lanes whose areas overlap or that merge.
    """
    inter = [int(v) for v in np.flatnonzero(g.is_intersection)]
    members = set(inter)
    pairs: list[tuple[int, int]] = []
    for a in inter:
        linked = {*g.successors[a], *g.predecessors[a], *np.flatnonzero(conflicts[a]).tolist()}
        pairs.extend((a, b) for b in linked & members)
    for c in set(range(len(g))) - members:
        for end in (g.successors[c], g.predecessors[c]):
            group = [b for b in end if b in members]
            pairs.extend((group[0], b) for b in group[1:])
    out = _components(len(g), pairs)
    out[~g.is_intersection] = -1
    return out
