"""``evaluate_frames`` (one batch of consecutive frames) equals one call per frame."""

from __future__ import annotations

import dataclasses
from typing import TYPE_CHECKING

import numpy as np
import pytest

from rss.params import DEFAULT_EGO_DYNAMICS, ObjectClass, RssParams
from rss.unstructured import (
    FrameInputs,
    UnstructuredAgents,
    UnstructuredResponse,
    evaluate_frames,
)
from rss.unstructured.kinematics import ROW_LOOP_MIN_COLUMNS, running_sum
from tests.rss.unstructured.frames_check import (
    assert_frames_equal_one_by_one,
    assert_same_memory,
    assert_same_result,
    one_by_one,
)
from tests.rss.unstructured.generators import random_ego, random_frame, random_sequence

if TYPE_CHECKING:
    from rss.dynamics import RssDynamics

EGO = DEFAULT_EGO_DYNAMICS


def _frames(
    sequence: list[tuple[UnstructuredAgents, UnstructuredAgents, list[RssDynamics]]],
) -> list[FrameInputs]:
    return [FrameInputs(ego, agents, dyn, EGO, EGO) for ego, agents, dyn in sequence]


def _with(agents: UnstructuredAgents, field: str, row: int, value: float) -> UnstructuredAgents:
    values = np.array(getattr(agents, field))
    values[row] = value
    return dataclasses.replace(agents, **{field: values})


@pytest.mark.parametrize("seed", range(12))
def test_drive_away_sequences_equal_frame_by_frame(seed: int) -> None:
    """The memory-heavy sequences of ``test_sequences`` (22.1b, drive-away persistence)."""
    rng = np.random.default_rng(7000 + seed)
    frames = _frames(random_sequence(rng, 12, 3))
    assert_frames_equal_one_by_one(frames)


def test_memory_coverage_of_the_drive_away_sequences() -> None:
    """The sequences above reach drive-aways and a stored memory (the comparison has teeth)."""
    drive_away = memories = 0
    for seed in range(12):
        rng = np.random.default_rng(7000 + seed)
        results, memory = one_by_one(_frames(random_sequence(rng, 12, 3)))
        drive_away += sum(
            int((r.decisions.response == UnstructuredResponse.DriveAway).sum()) for r in results
        )
        memories += memory is not None and memory.must_brake_ids.size > 0
    assert drive_away > 0
    assert memories > 0


@pytest.mark.parametrize("seed", range(4))
def test_random_frames_with_invalid_rows_and_varying_counts(seed: int) -> None:
    """Frames of 0..12 agents; invalid agents and an invalid ego; a start memory."""
    rng = np.random.default_rng(seed)
    frames = []
    for f in range(9):
        ego = random_ego(rng)
        agents, dyn = random_frame(rng, int(rng.integers(0, 13)))
        if f % 3 == 1 and len(agents):
            agents = _with(agents, "speed_max_mps", int(rng.integers(len(agents))), np.nan)
        if f == 4:
            ego = _with(ego, "yaw_rad", 0, 7.0)
        frames.append(FrameInputs(ego, agents, dyn, EGO, EGO))
    _, start = one_by_one(frames[:3])
    assert_frames_equal_one_by_one(frames, start)


def test_dynamics_changing_between_frames() -> None:
    """Other response times and another settings object in some frames (separate batches)."""
    rng = np.random.default_rng(21)
    slow = dataclasses.replace(EGO, response_time_s=1.5)
    wide = dataclasses.replace(
        EGO, unstructured=dataclasses.replace(EGO.unstructured, vehicle_min_radius=6.0)
    )
    frames = []
    for f, (ego, agents, dyn) in enumerate(random_sequence(rng, 6, 4)):
        later = [dataclasses.replace(d, response_time_s=0.5 + f / 4) for d in dyn]
        frames.append(FrameInputs(ego, agents, later, (EGO, slow, wide)[f % 3], EGO))
    assert_frames_equal_one_by_one(frames)


def test_empty_chunk_and_empty_frames() -> None:
    rng = np.random.default_rng(3)
    ego = random_ego(rng)
    none, _ = random_frame(rng, 0)
    assert_frames_equal_one_by_one([])
    assert_frames_equal_one_by_one([FrameInputs(ego, none, [], EGO, EGO)] * 3)


@pytest.mark.parametrize("columns", [3, ROW_LOOP_MIN_COLUMNS + 5])
def test_running_sum_equals_cumsum_to_the_bit(columns: int) -> None:
    rng = np.random.default_rng(columns)
    first, steps = rng.normal(size=columns), rng.normal(size=(17, columns)) * 1e3
    want = np.cumsum(np.concatenate((first[None], steps)), axis=0)
    np.testing.assert_array_equal(running_sum(first, steps), want)


def test_ego_dynamics_from_params() -> None:
    """Frames without ego dynamics take the ego class's of the parameters."""
    rng = np.random.default_rng(8)
    sequence = random_sequence(rng, 4, 3)
    slow = dataclasses.replace(EGO, response_time_s=1.5)
    params = RssParams(dynamics={**RssParams().dynamics, ObjectClass.EGO: slow})
    implicit = [FrameInputs(ego, agents, dyn) for ego, agents, dyn in sequence]
    explicit = [FrameInputs(ego, agents, dyn, slow, slow) for ego, agents, dyn in sequence]
    got, got_memory = evaluate_frames(implicit, params)
    want, want_memory = one_by_one(explicit)
    for a, b in zip(got, want, strict=True):
        assert_same_result(a, b)
    assert_same_memory(got_memory, want_memory)
