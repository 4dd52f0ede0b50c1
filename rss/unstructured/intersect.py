"""Which trajectory sets intersect: a numpy box filter over piece pairs, then shapely.

Two sets intersect iff some pair of their convex pieces does (touching counts, as ad-rss'
``not disjoint``). The ego's pieces and the agents' pieces are paired by their axis-aligned
boxes (exact: the boxes hold the hulls' own vertices) and by the brake flags (a pair of
two continue-forward pieces decides nothing); only the remaining pairs get hulls and an
exact shapely test. With many frames at once, pieces carry their frame and only pieces of
the same frame are paired::

    ego pieces (E)   [f0 f0 f0 | f1 f1 f1 | ...]      sorted by frame
    agent pieces (A) [f0 f0 ...| f1 ...   | ...]      sorted by frame
    pairs            each agent piece x the ego pieces of its frame
"""

from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np
import shapely

from rss import compiled
from rss.unstructured.convex import Pieces, mark
from rss.unstructured.sets import hulls_of

if TYPE_CHECKING:
    from rss.arrays import BoolArray, FloatArray, IntArray
    from rss.unstructured.sets import TrajectorySets

__all__ = [
    "CLOSED_FORM_MAX_PAIRS",
    "FIRST_ROUND_MIN_PAIRS",
    "SECOND_ROUND_PAIRS",
    "closed_form",
    "intersections",
]

#: Candidate pairs above which the brake-brake pairs are tested in a first round.
FIRST_ROUND_MIN_PAIRS = 64
#: Pairs of one test round up to which the compiled closed-form tests
#: (:mod:`rss.unstructured.convex`) go before shapely (beyond: shapely's vectorised calls).
CLOSED_FORM_MAX_PAIRS = 256
#: Pairs per (agent, condition) tested in the second round (the others only if it missed).
SECOND_ROUND_PAIRS = 2


def intersections(
    ego_sets: TrajectorySets,
    agent_sets: TrajectorySets,
    frames: tuple[IntArray, IntArray] | None = None,
) -> tuple[BoolArray, BoolArray, BoolArray]:
    """``(T_ego,b ∩ T_oth,f, T_oth,b ∩ T_ego,f, T_ego,b ∩ T_oth,b)`` per agent ``(N,)``.

    Candidate piece pairs are those whose boxes overlap and of which at least one piece
    is a brake piece; only their hulls are built and tested (shapely, ego hulls prepared).
    With many candidates the brake-brake pairs go first: an agent whose brake set meets
    the ego's has all three conditions (``T_b ⊆ T_f``), so its other pairs are skipped.
    Every other pair decides one condition of one agent; of each (agent, condition) the
    :data:`SECOND_ROUND_PAIRS` pairs with the largest box overlap go next, the rest only
    where those missed. The answer does not depend on that order (each condition is an
    "any" over its pairs).

    Args:
        ego_sets: The ego pieces (of one ego, or of one ego per frame).
        agent_sets: The agents' pieces (owner = agent index, ``N = agent_sets.count``).
        frames: ``(ego piece frame (E,), agent piece frame (A,))``, each sorted: pair only
            the pieces of the same frame. ``None``: one frame.
    """
    n = agent_sets.count
    flags = np.zeros((3, n), dtype=bool)
    if n == 0 or ego_sets.owner.size == 0 or agent_sets.owner.size == 0:
        return flags[0], flags[1], flags[2]
    boxes = (*ego_sets.bounds(), *agent_sets.bounds())
    e, a = (
        _box_pairs(ego_sets, agent_sets, boxes)
        if frames is None
        else _frame_pairs(ego_sets, agent_sets, boxes, *frames)
    )
    if e.size > FIRST_ROUND_MIN_PAIRS:
        both = ego_sets.brake[e] & agent_sets.brake[a]
        _mark(flags, ego_sets, agent_sets, e[both], a[both])
        rest = ~both & ~flags[2][agent_sets.owner[a]]
        e, a = e[rest], a[rest]
        # each remaining pair decides one condition (row 0 or 1) of its agent: first the
        # pairs of each (agent, condition) whose boxes overlap most, then the undecided rest
        row = np.where(ego_sets.brake[e], 0, 1)
        group = agent_sets.owner[a] * 2 + row
        first = _best_per_group(group, _overlap_area(boxes, e, a), SECOND_ROUND_PAIRS)
        _mark(flags, ego_sets, agent_sets, e[first], a[first])
        rest = ~first & ~flags[row, agent_sets.owner[a]]
        e, a = e[rest], a[rest]
    _mark(flags, ego_sets, agent_sets, e, a)
    return flags[0], flags[1], flags[2]


def _overlap_area(boxes: tuple[FloatArray, ...], e: IntArray, a: IntArray) -> FloatArray:
    """``(M,)`` area [m²] of the overlap of the pairs' boxes."""
    e_lo, e_hi, a_lo, a_hi = boxes
    side = np.minimum(e_hi[e], a_hi[a]) - np.maximum(e_lo[e], a_lo[a])
    return np.asarray(side[:, 0] * side[:, 1])


def _best_per_group(group: IntArray, score: FloatArray, count: int) -> BoolArray:
    """``(M,)`` the ``count`` items of highest ``score`` in each group."""
    order = np.lexsort((-score, group))
    ranked = group[order]
    rank = np.arange(order.size) - np.searchsorted(ranked, ranked)
    best = np.zeros(order.size, dtype=bool)
    best[order[rank < count]] = True
    return best


def _box_pairs(
    ego_sets: TrajectorySets, agent_sets: TrajectorySets, boxes: tuple[FloatArray, ...]
) -> tuple[IntArray, IntArray]:
    """Candidate pairs ``(e, a)`` of one frame: every ego piece against every agent piece."""
    e_lo, e_hi, a_lo, a_hi = boxes
    (ex0, ey0), (ex1, ey1) = e_lo.T[:, :, None], e_hi.T[:, :, None]  # (E, 1) columns
    (ax0, ay0), (ax1, ay1) = a_lo.T, a_hi.T  # (A,) rows
    candidates = (
        (ex0 <= ax1)
        & (ax0 <= ex1)
        & (ey0 <= ay1)
        & (ay0 <= ey1)
        & (ego_sets.brake[:, None] | agent_sets.brake)
    )
    e, a = np.nonzero(candidates)
    return e, a


def _frame_pairs(
    ego_sets: TrajectorySets,
    agent_sets: TrajectorySets,
    boxes: tuple[FloatArray, ...],
    e_frame: IntArray,
    a_frame: IntArray,
) -> tuple[IntArray, IntArray]:
    """Candidate pairs ``(e, a)`` of many frames, ego-major within each frame.

    Agent pieces outside the box of their frame's whole ego set are dropped first (one
    test per agent piece), then every remaining agent piece is paired with each ego piece
    of its frame.
    """
    e_lo, e_hi, a_lo, a_hi = boxes
    count = int(max(e_frame[-1], a_frame[-1])) + 1
    e_start = np.searchsorted(e_frame, np.arange(count + 1))
    e_count = np.diff(e_start)
    # the box of every frame's ego set (frames without ego pieces: an empty box)
    has = e_count > 0
    f_lo = np.full((count, 2), np.inf)
    f_hi = np.full((count, 2), -np.inf)
    f_lo[has] = np.minimum.reduceat(e_lo, e_start[:-1][has])
    f_hi[has] = np.maximum.reduceat(e_hi, e_start[:-1][has])
    near = np.flatnonzero(_overlap(f_lo[a_frame], f_hi[a_frame], a_lo, a_hi))
    per = e_count[a_frame[near]]
    a = np.repeat(near, per)
    first = np.repeat(e_start[a_frame[near]] - (np.cumsum(per) - per), per)
    e = first + np.arange(a.size)
    keep = _overlap(e_lo[e], e_hi[e], a_lo[a], a_hi[a]) & (ego_sets.brake[e] | agent_sets.brake[a])
    return e[keep], a[keep]


def _overlap(lo1: FloatArray, hi1: FloatArray, lo2: FloatArray, hi2: FloatArray) -> BoolArray:
    """``(M,)`` the boxes ``(M, 2)`` of the two sides overlap (touching included)."""
    return np.asarray(
        (lo1[:, 0] <= hi2[:, 0])
        & (lo2[:, 0] <= hi1[:, 0])
        & (lo1[:, 1] <= hi2[:, 1])
        & (lo2[:, 1] <= hi1[:, 1])
    )


def closed_form(pairs: int) -> bool:
    """Test ``pairs`` piece pairs with :mod:`rss.unstructured.convex` first (compiled, few)."""
    return pairs <= CLOSED_FORM_MAX_PAIRS and compiled.status()[0]


def _mark(
    flags: BoolArray,
    ego_sets: TrajectorySets,
    agent_sets: TrajectorySets,
    e: IntArray,
    a: IntArray,
) -> None:
    """Test the piece pairs ``(e[k], a[k])`` and set the three conditions ``(3, N)`` they meet.

    Few pairs (:func:`closed_form`) go to the closed-form tests of
    :mod:`rss.unstructured.convex` first, which skip pairs that cannot set a new flag and
    leave only the near-touching ones to shapely: the same flags.
    """
    if e.size == 0:
        return
    if closed_form(e.size):
        e_brake, a_brake = ego_sets.brake[e], agent_sets.brake[a]
        rows = e_brake * 1 + a_brake * 2 + (e_brake & a_brake) * 4
        found = flags.tolist()
        unsure = mark(
            Pieces(ego_sets.coords, ego_sets.size.tolist()),
            Pieces(agent_sets.coords, agent_sets.size.tolist()),
            (e.tolist(), a.tolist()),
            rows.tolist(),
            agent_sets.owner[a].tolist(),
            found,
        )
        flags[:] = found
        if not unsure:
            return
        e, a = e[unsure], a[unsure]
    ego_hulls, agent_hulls = hulls_of([(ego_sets, e), (agent_sets, a)])
    shapely.prepare(ego_hulls)
    hit = shapely.intersects(ego_hulls, agent_hulls)
    e, a = e[hit], a[hit]
    e_brake, a_brake, owner = ego_sets.brake[e], agent_sets.brake[a], agent_sets.owner[a]
    for row, mask in enumerate((e_brake, a_brake, e_brake & a_brake)):
        flags[row, owner[mask]] = True
