"""The driver's garbage-collector policy while a drive is evaluated."""

from __future__ import annotations

import gc
from types import SimpleNamespace
from typing import TYPE_CHECKING, cast

import pytest

from tests.workbench.fakes import bound
from workbench.driver import CHUNK_FRAMES, ENGINE_GC_THRESHOLD, DriveRun, engine_gc
from workbench.engines.base import VerdictSummary

if TYPE_CHECKING:
    from collections.abc import Iterator, Sequence

    from loaders.drive import Drive
    from loaders.records import Frame


@pytest.fixture
def threshold() -> Iterator[tuple[int, int, int]]:
    """The test's thresholds; the interpreter's own are restored afterwards."""
    saved = gc.get_threshold()
    gc.set_threshold(700, 10, 10)
    yield gc.get_threshold()
    gc.set_threshold(*saved)


def test_young_threshold_is_raised_inside_and_restored_after(threshold):
    with engine_gc():
        assert gc.get_threshold() == (ENGINE_GC_THRESHOLD, 10, 10)
        assert gc.isenabled()
    assert gc.get_threshold() == threshold


def test_a_higher_user_threshold_is_never_lowered(threshold):
    gc.set_threshold(ENGINE_GC_THRESHOLD * 3, 5, 7)
    with engine_gc():
        assert gc.get_threshold() == (ENGINE_GC_THRESHOLD * 3, 5, 7)
    assert gc.get_threshold() == (ENGINE_GC_THRESHOLD * 3, 5, 7)


def test_threshold_is_restored_when_the_body_raises(threshold):
    with pytest.raises(ValueError, match="boom"), engine_gc():
        raise ValueError("boom")
    assert gc.get_threshold() == threshold


def test_cyclic_garbage_made_inside_is_collected_on_exit(threshold):
    class Node:
        def __init__(self) -> None:
            self.me = self

    collected: list[int] = []

    def count(phase: str, info: dict[str, int]) -> None:
        if phase == "stop":
            collected.append(info["collected"])

    gc.collect()
    with engine_gc():
        for _ in range(100):
            Node()
        gc.callbacks.append(count)
    gc.callbacks.remove(count)
    assert sum(collected) >= 100


def test_disabled_collector_stays_disabled(threshold):
    gc.disable()
    try:
        with engine_gc():
            assert not gc.isenabled()
        assert not gc.isenabled()
    finally:
        gc.enable()


def test_the_drive_run_is_under_the_policy(threshold):
    frames = [SimpleNamespace(index=i, t_ns=i * 100_000_000) for i in range(CHUNK_FRAMES + 5)]
    seen: list[tuple[int, int, int]] = []

    class Probe:
        name = "probe"

        def step_many(self, chunk: Sequence[Frame]) -> list[VerdictSummary]:
            seen.append(gc.get_threshold())
            return [VerdictSummary(is_safe=True) for _ in chunk]

    # the driver reads only frames(start, end), and of a frame only index and t_ns
    drive = cast("Drive", SimpleNamespace(frames=lambda _s, _e: iter(frames)))
    run = DriveRun(drive, [bound(Probe())])
    indices = [f.index for chunk in run for f in chunk.frames]
    assert indices == list(range(CHUNK_FRAMES + 5))
    assert seen == [(ENGINE_GC_THRESHOLD, 10, 10)] * 2
    assert gc.get_threshold() == threshold
    assert run.stopped_by is None
