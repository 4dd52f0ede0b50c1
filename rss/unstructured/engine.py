"""Unstructured RSS of frames: trajectory sets, decisions and the proper response.

Pure: ``evaluate_frames(frames, params, memory) -> (results, memory)`` over ``F``
consecutive frames, the engine entry point (same shape as :func:`rss.evaluate_frames`):
the sets of every frame in shared batches, the intersections in one go, then the
decisions frame by frame (the only part that needs the memory). The ego and the agents
sharing its unstructured settings and motion model are computed in one batch (per-agent
dynamics values); the ego's and the agents' convex pieces are paired by a numpy box test
and the remaining pairs tested exactly with shapely (:func:`intersections`).
:func:`check_unstructured` is the one-frame case with every dynamics given explicitly.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np

from rss import compiled
from rss.params import ObjectClass
from rss.unstructured.agents import MotionModel, UnstructuredAgents, motion_model
from rss.unstructured.batch import AgentDynamics
from rss.unstructured.decision import Decisions, UnstructuredResponse, decide
from rss.unstructured.errors import UnstructuredInputError
from rss.unstructured.intersect import FIRST_ROUND_MIN_PAIRS, intersections
from rss.unstructured.memory import UnstructuredMemory
from rss.unstructured.pedestrian_batch import pedestrian_sets_batch
from rss.unstructured.pedestrian_small import pedestrian_moving_small
from rss.unstructured.response import UnstructuredProperResponse, resolve_unstructured
from rss.unstructured.sets import TrajectorySets
from rss.unstructured.vehicle_batch import vehicle_sets_batch
from rss.unstructured.vehicle_small import SMALL_SETS_MAX, vehicle_sets_small

if TYPE_CHECKING:
    from collections.abc import Sequence

    from rss.arrays import BoolArray, IntArray
    from rss.dynamics import RssDynamics, UnstructuredSettings
    from rss.params import RssParams

__all__ = [
    "FIRST_ROUND_MIN_PAIRS",
    "FrameInputs",
    "UnstructuredResult",
    "check_unstructured",
    "evaluate_frames",
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
        stacked = AgentDynamics.of([dynamics[i] for i in rows], extra[idx])
        parts.append((_sets(model, sub, stacked), idx))
    if len(parts) == 1 and parts[0][1].size == n:
        return parts[0][0]  # one batch of every agent, in order
    return TrajectorySets.concat(parts, n)


def small_batch(agents: int) -> bool:
    """Build a batch of ``agents`` point by point (the same sets; faster compiled and small)."""
    return agents <= SMALL_SETS_MAX and compiled.status()[0]


def _sets(model: int, agents: UnstructuredAgents, dyn: AgentDynamics) -> TrajectorySets:
    """The sets of one batch: point by point when :func:`small_batch`, else batched."""
    small = small_batch(len(agents))
    if model == MotionModel.PEDESTRIAN:
        return pedestrian_sets_batch(agents, dyn, pedestrian_moving_small if small else None)
    sets = vehicle_sets_small(agents, dyn) if small else None
    return vehicle_sets_batch(agents, dyn) if sets is None else sets


@dataclass(frozen=True)
class FrameInputs:
    """The inputs of one frame (the arguments of :func:`check_unstructured` of that name).

    Attributes:
        ego: The ego (one row, ENU).
        agents: ``(N,)`` other participants, ENU.
        agent_dynamics: One dynamics per agent.
        ego_dynamics: Ego dynamics of the constellations (``None``: the ego class's
            dynamics of the parameters of :func:`evaluate_frames`).
        default_ego: Default ego dynamics of the frame (``None``: likewise).
    """

    ego: UnstructuredAgents
    agents: UnstructuredAgents
    agent_dynamics: Sequence[RssDynamics]
    ego_dynamics: RssDynamics | None = None
    default_ego: RssDynamics | None = None

    def resolved(self, ego: RssDynamics) -> _Frame:
        """The frame with ``ego`` for the dynamics it does not give."""
        return _Frame(
            self.ego,
            self.agents,
            self.agent_dynamics,
            ego if self.ego_dynamics is None else self.ego_dynamics,
            ego if self.default_ego is None else self.default_ego,
        )


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
    frame = FrameInputs(ego, agents, agent_dynamics, ego_dynamics, default_ego)
    results, memory_out = _check_frames([frame.resolved(ego_dynamics)], memory)
    return results[0], memory_out


def evaluate_frames(
    frames: Sequence[FrameInputs], params: RssParams, state: UnstructuredMemory | None = None
) -> tuple[list[UnstructuredResult], UnstructuredMemory]:
    """:func:`check_unstructured` on consecutive frames, the memory carried from each to the next.

    The sets do not depend on the memory: those of every ego and agent of every frame
    are built in shared batches (rows = the ego and the agents of each frame) and
    intersected in one go (pieces paired within their frame). Only the decisions run frame
    by frame. The results equal ``F`` calls of :func:`check_unstructured` in order, so a
    replay can restart at any frame with the memory returned before it.

    Args:
        frames: ``(F,)`` frames in time order (``N_f`` agents each).
        params: Parameters: the ego class's dynamics serve as the ego and default ego
            dynamics of frames that do not give their own.
        state: Memory before the first frame (``None`` = fresh).

    Returns:
        ``(results (F,), memory after the last frame)``.

    Raises:
        UnstructuredInputError: A frame's ego is not one row or its dynamics mismatch.
    """
    ego = params.for_class(ObjectClass.EGO)
    return _check_frames([frame.resolved(ego) for frame in frames], state)


@dataclass(frozen=True)
class _Frame:
    """A frame of :class:`FrameInputs` with all its dynamics."""

    ego: UnstructuredAgents
    agents: UnstructuredAgents
    agent_dynamics: Sequence[RssDynamics]
    ego_dynamics: RssDynamics
    default_ego: RssDynamics

    def check(self) -> None:
        """Raise :class:`UnstructuredInputError` unless one ego and one dynamics per agent."""
        if len(self.ego) != 1:
            raise UnstructuredInputError("ego", f"must hold exactly one row, got {len(self.ego)}")
        n = len(self.agents)
        if len(self.agent_dynamics) != n:
            raise UnstructuredInputError(
                "agent_dynamics", f"needs {n} entries, got {len(self.agent_dynamics)}"
            )


def _check_frames(
    frames: Sequence[_Frame], memory: UnstructuredMemory | None
) -> tuple[list[UnstructuredResult], UnstructuredMemory]:
    """:func:`evaluate_frames` of frames with all their dynamics."""
    memory = memory or _NO_MEMORY
    for frame in frames:
        frame.check()
    if not frames:
        return [], memory
    batch = _FramesBatch.build(frames)
    results = []
    for f, frame in enumerate(frames):
        result, memory = batch.frame_result(f, frame, memory)
        results.append(result)
    return results, memory


@dataclass(frozen=True)
class _FramesBatch:
    """The sets and set intersections of ``F`` frames.

    Rows are the ego and the agents of every frame, one frame after the other
    (``start[f]`` = the ego of frame ``f``); "kept" rows are the valid ones of frames with a
    valid ego. Pieces are ordered ego pieces first, then agent pieces, each by frame.
    """

    start: IntArray  # (F + 1,) first row of each frame
    checked: BoolArray  # (R,) row valid on its own
    ego_valid: BoolArray  # (F,)
    kept_start: IntArray  # (F + 1,) first kept row of each frame
    kept_row: IntArray  # (K,) row of each kept row
    pieces: TrajectorySets  # owner = local agent index (egos: 0)
    ego_bounds: IntArray  # (F + 1,) ego pieces of frame f: ego_bounds[f] .. [f + 1]
    agent_bounds: IntArray  # (F + 1,) likewise, agent pieces
    flags: tuple[BoolArray, BoolArray, BoolArray]  # (K,) each, the three conditions

    @staticmethod
    def build(frames: Sequence[_Frame]) -> _FramesBatch:
        count = len(frames)
        sizes = np.array([1 + len(f.agents) for f in frames], dtype=np.int64)
        start = np.concatenate(([0], np.cumsum(sizes)))
        rows = UnstructuredAgents.concat([p for f in frames for p in (f.ego, f.agents)])
        dynamics = [d for f in frames for d in (f.ego_dynamics, *f.agent_dynamics)]
        row_frame = np.repeat(np.arange(count), sizes)
        is_ego = np.zeros(len(rows), dtype=bool)
        is_ego[start[:-1]] = True
        checked = rows.valid()
        ego_valid = checked[start[:-1]]
        keep = checked & ego_valid[row_frame]
        kept_row = np.flatnonzero(keep)
        if kept_row.size < len(rows):
            rows = rows.take(kept_row)
            dynamics = [dynamics[i] for i in kept_row.tolist()]
        sets = trajectory_sets(rows, dynamics, ego=is_ego[kept_row])
        piece_row = kept_row[sets.owner]
        frame = row_frame[piece_row]
        agent = ~is_ego[piece_row]
        order = (agent * count + frame).argsort(kind="stable")
        frame, piece_row = frame[order], piece_row[order]
        egos = int(np.count_nonzero(~agent))
        pieces = TrajectorySets(
            sets.coords.take(order, axis=1),  # C order (``[:, order]`` is not)
            sets.size[order],
            sets.owner[order],
            sets.brake[order],
            sets.count,
        )
        flags = intersections(
            pieces.piece_range(0, egos, pieces.owner[:egos], sets.count),
            pieces.piece_range(egos, pieces.owner.size, pieces.owner[egos:], sets.count),
            (frame[:egos], frame[egos:]) if count > 1 else None,
        )
        frames_at = np.arange(count + 1)
        return _FramesBatch(
            start,
            checked,
            ego_valid,
            kept_row.searchsorted(start),
            kept_row,
            pieces.piece_range(
                0, pieces.owner.size, np.maximum(piece_row - start[frame] - 1, 0), sets.count
            ),
            frame[:egos].searchsorted(frames_at),
            egos + frame[egos:].searchsorted(frames_at),
            flags,
        )

    def frame_result(
        self, f: int, frame: _Frame, memory: UnstructuredMemory
    ) -> tuple[UnstructuredResult, UnstructuredMemory]:
        """The result of frame ``f`` and the memory after it."""
        agents, ego = frame.agents, frame.ego
        n = len(agents)
        ego_valid = bool(self.ego_valid[f])
        valid = self.checked[self.start[f] + 1 : self.start[f + 1]] & ego_valid
        ok = bool(ego_valid and valid.all())
        lo, hi = self.kept_start[f] + ego_valid, self.kept_start[f + 1]
        idx = self.kept_row[lo:hi] - (self.start[f] + 1)
        sub = agents if ok else agents.take(idx)
        ego_b_oth_f, oth_b_ego_f, ego_b_oth_b = (flag[lo:hi] for flag in self.flags)
        sub_dec, memory_out = decide(
            ego_b_oth_f,
            oth_b_ego_f,
            ego_b_oth_b,
            ego,
            sub,
            frame.ego_dynamics.unstructured.drive_away_max_angle,
            memory,
        )
        decisions = sub_dec if ok else _expand(sub_dec, idx, n)
        e_lo, e_hi = self.ego_bounds[f : f + 2]
        a_lo, a_hi = self.agent_bounds[f : f + 2]
        ego_sets = self.pieces.piece_range(e_lo, e_hi, self.pieces.owner[e_lo:e_hi], 1)
        agent_sets = self.pieces.piece_range(a_lo, a_hi, self.pieces.owner[a_lo:a_hi], n)
        proper = resolve_unstructured(decisions, agents, ego, frame.ego_dynamics, frame.default_ego)
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
