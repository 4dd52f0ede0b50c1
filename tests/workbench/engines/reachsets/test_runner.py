"""The reach-set runner: batched frames equal frame-by-frame steps; chunked pipeline."""

from __future__ import annotations

from pathlib import Path
from types import SimpleNamespace
from typing import TYPE_CHECKING, cast

import pytest

from loaders import open_drive
from loaders.errors import CorruptLogError
from tests.workbench.engines.helpers import record, step
from tests.workbench.fakes import bound
from workbench.driver import CHUNK_FRAMES, DriveRun
from workbench.engines.reachsets.runner import ReachRunner

if TYPE_CHECKING:
    from collections.abc import Iterator

    from loaders.drive import Drive
    from loaders.records import Frame

SAMPLES = Path(__file__).resolve().parents[4] / "sample_logs"


@pytest.mark.parametrize("name", ["racing_overtake.saa", "highway_cut_in.mcap"])
def test_step_many_equals_step_by_step(name):
    drive = open_drive(SAMPLES / name)
    frames = list(drive.frames())[:70]
    drive.close()
    one = ReachRunner(drive.lane_map)
    expected = [record(step(one, f)) for f in frames]
    many = ReachRunner(drive.lane_map)
    got = many.step_many(frames[:25]) + many.step_many(frames[25:])
    assert [record(o) for o in got] == expected
    assert any(not r["is_safe"] for r in expected)


def _drive_of(frames: list[Frame] | Iterator[Frame]) -> Drive:
    """A drive whose ``frames()`` yields ``frames`` (the driver reads nothing else)."""
    return cast("Drive", SimpleNamespace(frames=lambda _s, _e: iter(frames)))


def test_driver_hands_chunks_to_step_many_and_keeps_order():
    drive = open_drive(SAMPLES / "racing_overtake.saa")
    frames = list(drive.frames())
    drive.close()
    assert len(frames) > CHUNK_FRAMES
    calls: list[int] = []

    class Counting(ReachRunner):
        def step_many(self, chunk):
            calls.append(len(chunk))
            return super().step_many(chunk)

    chunks = list(DriveRun(_drive_of(frames), [bound(Counting(drive.lane_map))]))
    assert [f.index for c in chunks for f in c.frames] == [f.index for f in frames]
    assert max(calls) == CHUNK_FRAMES
    assert sum(calls) == len(frames)
    single = ReachRunner(drive.lane_map)
    assert [record(v) for c in chunks for v in c.verdicts["reachsets"]] == [
        record(step(single, f)) for f in frames
    ]


def test_driver_evaluates_the_frames_read_before_a_reader_error():
    drive = open_drive(SAMPLES / "racing_overtake.saa")
    frames = list(drive.frames())[:10]
    drive.close()

    def broken() -> Iterator[Frame]:
        yield from frames
        raise OSError("truncated")

    seen: list[int] = []
    chunks = iter(DriveRun(_drive_of(broken()), [bound(ReachRunner(drive.lane_map))]))
    with pytest.raises(OSError, match="truncated"):
        seen.extend(f.index for chunk in chunks for f in chunk.frames)
    assert seen == [f.index for f in frames]


def test_driver_keeps_the_frames_before_a_loader_error_and_reports_it():
    drive = open_drive(SAMPLES / "racing_overtake.saa")
    frames = list(drive.frames())[:40]
    drive.close()
    stop = CorruptLogError("racing_overtake.saa", "cut short")

    def truncated() -> Iterator[Frame]:
        yield from frames
        raise stop

    run = DriveRun(_drive_of(truncated()), [bound(ReachRunner(drive.lane_map))])
    seen = [f.index for chunk in run for f in chunk.frames]
    assert seen == [f.index for f in frames]
    assert run.stopped_by is stop
