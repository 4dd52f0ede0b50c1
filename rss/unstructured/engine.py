"""``check_unstructured``: trajectory sets, decisions and the proper response of one frame.

Pure: ``(ego, agents, dynamics, memory) -> (UnstructuredResult, memory)``. Agents sharing
the same dynamics and motion model are computed in one batch; the ego's and the agents'
convex pieces are intersected with one STRtree query.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np
import shapely

from rss.unstructured.agents import MotionModel, UnstructuredAgents, motion_model
from rss.unstructured.decision import Decisions, UnstructuredResponse, decide
from rss.unstructured.errors import UnstructuredInputError
from rss.unstructured.memory import UnstructuredMemory
from rss.unstructured.pedestrian import pedestrian_sets
from rss.unstructured.response import UnstructuredProperResponse, resolve_unstructured
from rss.unstructured.sets import TrajectorySets
from rss.unstructured.vehicle import vehicle_sets

if TYPE_CHECKING:
    from collections.abc import Sequence

    from rss.batch import BoolArray, IntArray
    from rss.dynamics import RssDynamics

__all__ = ["UnstructuredResult", "check_unstructured", "intersections", "trajectory_sets"]


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
    agents: UnstructuredAgents, dynamics: Sequence[RssDynamics], *, ego: bool = False
) -> TrajectorySets:
    """Brake / continue-forward pieces of every agent (grouped by dynamics and model).

    Args:
        agents: ``(N,)`` valid agents.
        dynamics: One dynamics per agent.
        ego: Extend the footprints in front by ``min_longitudinal_safety_distance``.

    Raises:
        UnstructuredInputError: ``dynamics`` has the wrong length.
    """
    if len(dynamics) != len(agents):
        raise UnstructuredInputError(
            "dynamics", f"needs {len(agents)} entries, got {len(dynamics)}"
        )
    models = motion_model(agents.object_type)
    groups: dict[tuple[RssDynamics, int], list[int]] = {}
    for i, (dyn, model) in enumerate(zip(dynamics, models, strict=True)):
        groups.setdefault((dyn, int(model)), []).append(i)
    parts = []
    for (dyn, model), rows in groups.items():
        idx = np.array(rows, dtype=np.int64)
        extra = np.full(idx.shape, dyn.min_longitudinal_safety_distance_m if ego else 0.0)
        build = pedestrian_sets if model == MotionModel.PEDESTRIAN else vehicle_sets
        parts.append((build(agents.take(idx), dyn, extra), idx))
    return TrajectorySets.concat(parts, len(agents))


def intersections(
    ego_sets: TrajectorySets, agent_sets: TrajectorySets
) -> tuple[BoolArray, BoolArray, BoolArray]:
    """``(T_ego,b ∩ T_oth,f, T_oth,b ∩ T_ego,f, T_ego,b ∩ T_oth,b)`` per agent ``(N,)``.

    Touching counts as intersecting (ad-rss: not ``disjoint``).
    """
    n = agent_sets.count
    out = [np.zeros(n, dtype=bool) for _ in range(3)]
    if n == 0 or ego_sets.hulls.size == 0:
        return out[0], out[1], out[2]
    tree = shapely.STRtree(agent_sets.hulls)
    e, a = tree.query(ego_sets.hulls, predicate="intersects")
    e_brake, a_brake, owner = ego_sets.brake[e], agent_sets.brake[a], agent_sets.owner[a]
    for flags, mask in zip(out, (e_brake, a_brake, e_brake & a_brake), strict=True):
        flags[owner[mask]] = True
    return out[0], out[1], out[2]


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
    memory = memory or UnstructuredMemory.empty()
    if len(ego) != 1:
        raise UnstructuredInputError("ego", f"must hold exactly one row, got {len(ego)}")
    if len(agent_dynamics) != len(agents):
        raise UnstructuredInputError(
            "agent_dynamics", f"needs {len(agents)} entries, got {len(agent_dynamics)}"
        )
    ego_valid = bool(ego.valid()[0])
    valid = agents.valid() & ego_valid
    ok = bool(valid.all() and ego_valid)
    idx = np.flatnonzero(valid)
    sub = agents.take(idx)
    ego_sets = (
        trajectory_sets(ego, [ego_dynamics], ego=True)
        if ego_valid
        else TrajectorySets.concat([], 1)
    )
    sub_sets = trajectory_sets(sub, [agent_dynamics[int(i)] for i in idx])
    hits = intersections(ego_sets, sub_sets)
    sub_dec, memory_out = decide(
        *hits, ego, sub, ego_dynamics.unstructured.drive_away_max_angle, memory
    )
    decisions = _expand(sub_dec, idx, len(agents))
    agent_sets = TrajectorySets(sub_sets.hulls, idx[sub_sets.owner], sub_sets.brake, len(agents))
    proper = resolve_unstructured(decisions, agents, ego, ego_dynamics, default_ego)
    result = UnstructuredResult(
        ok, valid, agents.object_id, decisions, ego_sets, agent_sets, proper
    )
    invalid_ids = agents.object_id[~valid]
    return result, memory_out.merged(memory, invalid_ids) if invalid_ids.size else memory_out


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
