"""``check_unstructured``: trajectory sets, decisions and the proper response of one frame.

Pure: ``(ego, agents, dynamics, memory) -> (UnstructuredResult, memory)``. The ego and the
agents sharing its unstructured settings and motion model are computed in one batch (per-
agent dynamics values); the ego's and the agents' convex pieces are paired by a numpy box
test and the remaining pairs tested exactly with shapely (:func:`intersections`).
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np
import shapely

from rss.unstructured.agents import MotionModel, UnstructuredAgents, motion_model
from rss.unstructured.batch import AgentDynamics
from rss.unstructured.decision import Decisions, UnstructuredResponse, decide
from rss.unstructured.errors import UnstructuredInputError
from rss.unstructured.memory import UnstructuredMemory
from rss.unstructured.pedestrian_batch import pedestrian_sets_batch
from rss.unstructured.response import UnstructuredProperResponse, resolve_unstructured
from rss.unstructured.sets import TrajectorySets, hulls_of
from rss.unstructured.vehicle_batch import vehicle_sets_batch

if TYPE_CHECKING:
    from collections.abc import Sequence

    from rss.batch import BoolArray, IntArray
    from rss.dynamics import RssDynamics, UnstructuredSettings

__all__ = [
    "FIRST_ROUND_MIN_PAIRS",
    "UnstructuredResult",
    "check_unstructured",
    "intersections",
    "trajectory_sets",
]


#: The memory of a fresh start.
_NO_MEMORY = UnstructuredMemory.empty()


@dataclass(frozen=True)
class UnstructuredResult:
    """Result of one frame.

    Attributes:
        ok: All inputs valid. ad-rss fails the whole frame on one invalid agent; here
            only the invalid agents are skipped (see ``valid``) and the others are
            answered as usual.
        valid: ``(N,)`` agent accepted (all false when the ego is invalid).
        object_id: ``(N,)`` agent ids.
        decisions: Per-agent decisions (invalid agents: safe, response None).
        ego_sets: The ego's pieces (one agent).
        agent_sets: The agents' pieces (owner = agent index).
        proper_response: The ego's proper response.
    """

    ok: bool
    valid: BoolArray
    object_id: IntArray
    decisions: Decisions
    ego_sets: TrajectorySets
    agent_sets: TrajectorySets
    proper_response: UnstructuredProperResponse


def trajectory_sets(
    agents: UnstructuredAgents,
    dynamics: Sequence[RssDynamics],
    *,
    ego: bool | BoolArray = False,
) -> TrajectorySets:
    """Brake / continue-forward pieces of every agent, batched by settings and motion model.

    Agents with different dynamics values share one batch when their unstructured settings
    (step counts, radii) are equal: the ego and every vehicle are typically one batch,
    the pedestrians another.

    Args:
        agents: ``(N,)`` valid agents.
        dynamics: One dynamics per agent.
        ego: ``(N,)`` (or one for all) rows extended in front by their
            ``min_longitudinal_safety_distance``.

    Raises:
        UnstructuredInputError: ``dynamics`` has the wrong length.
    """
    n = len(agents)
    if len(dynamics) != n:
        raise UnstructuredInputError("dynamics", f"needs {n} entries, got {len(dynamics)}")
    extra = np.where(ego, [d.min_longitudinal_safety_distance_m for d in dynamics], 0.0)
    by_object: dict[tuple[int, int], list[int]] = {}  # settings objects by identity first
    for i, (dyn, model) in enumerate(
        zip(dynamics, motion_model(agents.object_type).tolist(), strict=True)
    ):
        by_object.setdefault((id(dyn.unstructured), model), []).append(i)
    groups: dict[tuple[UnstructuredSettings, int], list[int]] = {}
    for (_, model), rows in by_object.items():
        groups.setdefault((dynamics[rows[0]].unstructured, model), []).extend(rows)
    parts = []
    for (_, model), unordered in groups.items():
        rows = sorted(unordered)
        idx = np.array(rows, dtype=np.int64)
        sub = agents if len(rows) == n else agents.take(idx)
        build = pedestrian_sets_batch if model == MotionModel.PEDESTRIAN else vehicle_sets_batch
        parts.append((build(sub, AgentDynamics.of([dynamics[i] for i in rows], extra[idx])), idx))
    if len(parts) == 1 and parts[0][1].size == n:
        return parts[0][0]  # one batch of every agent, in order
    return TrajectorySets.concat(parts, n)


def intersections(
    ego_sets: TrajectorySets, agent_sets: TrajectorySets
) -> tuple[BoolArray, BoolArray, BoolArray]:
    """``(T_ego,b ∩ T_oth,f, T_oth,b ∩ T_ego,f, T_ego,b ∩ T_oth,b)`` per agent ``(N,)``.

    Touching counts as intersecting (ad-rss: not ``disjoint``). Candidate piece pairs are
    those whose axis-aligned boxes overlap (numpy, all pairs at once; the boxes hold the
    hulls' own vertices, so the test is exact) and of which at least one piece is a brake
    piece (continue-forward pairs decide nothing); only their hulls are built and tested
    (shapely, ego hulls prepared). With many candidates the brake-brake pairs go first: an
    agent whose brake set meets the ego's has all three conditions (``T_b ⊆ T_f``), so its
    other pairs are skipped.
    """
    n = agent_sets.count
    flags = np.zeros((3, n), dtype=bool)
    if n == 0 or ego_sets.owner.size == 0 or agent_sets.owner.size == 0:
        return flags[0], flags[1], flags[2]
    e_lo, e_hi = ego_sets.bounds()
    a_lo, a_hi = agent_sets.bounds()
    e_brake, a_brake = ego_sets.brake[:, None], agent_sets.brake[None, :]
    candidates = (
        (e_lo[:, None, 0] <= a_hi[None, :, 0])
        & (a_lo[None, :, 0] <= e_hi[:, None, 0])
        & (e_lo[:, None, 1] <= a_hi[None, :, 1])
        & (a_lo[None, :, 1] <= e_hi[:, None, 1])
        & (e_brake | a_brake)
    )
    if np.count_nonzero(candidates) > FIRST_ROUND_MIN_PAIRS:
        both = candidates & e_brake & a_brake
        _mark(flags, ego_sets, agent_sets, both)
        decided = flags[2][agent_sets.owner]
        candidates &= ~both & ~decided[None, :]
    _mark(flags, ego_sets, agent_sets, candidates)
    return flags[0], flags[1], flags[2]


#: Candidate pairs above which the brake-brake pairs are tested in a first round.
FIRST_ROUND_MIN_PAIRS = 64


def _mark(
    flags: BoolArray, ego_sets: TrajectorySets, agent_sets: TrajectorySets, pairs: BoolArray
) -> None:
    """Test the piece pairs ``(E, P)`` and set the three conditions ``(3, N)`` they meet."""
    e, a = np.nonzero(pairs)
    if e.size == 0:
        return
    ego_hulls, agent_hulls = hulls_of([(ego_sets, e), (agent_sets, a)])
    shapely.prepare(ego_hulls)
    hit = shapely.intersects(ego_hulls, agent_hulls)
    e, a = e[hit], a[hit]
    e_brake, a_brake, owner = ego_sets.brake[e], agent_sets.brake[a], agent_sets.owner[a]
    for row, mask in enumerate((e_brake, a_brake, e_brake & a_brake)):
        flags[row, owner[mask]] = True


def check_unstructured(  # noqa: PLR0917  (one engine step)
    ego: UnstructuredAgents,
    agents: UnstructuredAgents,
    ego_dynamics: RssDynamics,
    agent_dynamics: Sequence[RssDynamics],
    default_ego: RssDynamics,
    memory: UnstructuredMemory | None = None,
) -> tuple[UnstructuredResult, UnstructuredMemory]:
    """Check every agent against the ego with unstructured (trajectory-set) RSS.

    Args:
        ego: The ego (one row, ENU).
        agents: ``(N,)`` other participants, ENU.
        ego_dynamics: Ego dynamics of the constellations (sets, drive-away angle,
            acceleration restrictions).
        agent_dynamics: One dynamics per agent.
        default_ego: Default ego dynamics of the frame (initial acceleration ranges).
        memory: Memory of the previous frame (``None`` = fresh).

    Returns:
        ``(result, memory_after)``. Invalid agents (NaN, negative or unordered speeds,
        angles beyond ±2π, no motion model) are skipped: decision safe / ``None``,
        not dangerous, their memory entries carried over unchanged (ad-rss would fail
        the whole frame and keep its whole memory). An invalid ego makes every agent
        invalid.

    Raises:
        UnstructuredInputError: ``ego`` is not one row or ``agent_dynamics`` mismatches.
    """
    memory = memory or _NO_MEMORY
    if len(ego) != 1:
        raise UnstructuredInputError("ego", f"must hold exactly one row, got {len(ego)}")
    n = len(agents)
    if len(agent_dynamics) != n:
        raise UnstructuredInputError(
            "agent_dynamics", f"needs {n} entries, got {len(agent_dynamics)}"
        )
    both = UnstructuredAgents.concat((ego, agents))
    checked = both.valid()
    ego_valid = bool(checked[0])
    valid = checked[1:] & ego_valid
    ok = bool(valid.all() and ego_valid)
    idx = np.flatnonzero(valid)
    sub = agents if ok else agents.take(idx)
    if ego_valid:
        rows = None if ok else np.concatenate(([0], idx + 1))
        ego_sets, sub_sets = _ego_and_agent_sets(
            both if rows is None else both.take(rows),
            [ego_dynamics, *(agent_dynamics[int(i)] for i in idx)],
        )
    else:
        ego_sets, sub_sets = TrajectorySets.empty(1), TrajectorySets.empty(0)
    hits = intersections(ego_sets, sub_sets)
    sub_dec, memory_out = decide(
        *hits, ego, sub, ego_dynamics.unstructured.drive_away_max_angle, memory
    )
    decisions = sub_dec if ok else _expand(sub_dec, idx, n)
    agent_sets = sub_sets if ok else TrajectorySets.concat([(sub_sets, idx)], n)
    proper = resolve_unstructured(decisions, agents, ego, ego_dynamics, default_ego)
    result = UnstructuredResult(
        ok, valid, agents.object_id, decisions, ego_sets, agent_sets, proper
    )
    invalid_ids = agents.object_id[~valid]
    return result, memory_out.merged(memory, invalid_ids) if invalid_ids.size else memory_out


def _ego_and_agent_sets(
    both: UnstructuredAgents, dynamics: Sequence[RssDynamics]
) -> tuple[TrajectorySets, TrajectorySets]:
    """The sets of the ego (row 0 of ``both``) and of the agents, built in shared batches."""
    mask = np.zeros(len(both), dtype=bool)
    mask[0] = True
    sets = trajectory_sets(both, dynamics, ego=mask)
    first = sets.owner == 0
    return sets.select(first, 1), sets.select(~first, len(both) - 1, shift=1)


def _expand(dec: Decisions, idx: IntArray, n: int) -> Decisions:
    """Decisions of the valid subset scattered to all ``n`` agents (others safe, None)."""

    def scatter(values: np.ndarray, fill: object) -> np.ndarray:
        out = np.full(n, fill, dtype=values.dtype)
        out[idx] = values
        return out

    return Decisions(
        scatter(dec.is_safe, True),  # noqa: FBT003
        scatter(dec.response, int(UnstructuredResponse.None_)),
        scatter(dec.heading_begin_rad, np.nan),
        scatter(dec.heading_end_rad, np.nan),
        scatter(dec.ego_must_brake, False),  # noqa: FBT003
        scatter(dec.other_must_brake, False),  # noqa: FBT003
        scatter(dec.both_brake_safe, True),  # noqa: FBT003
    )
