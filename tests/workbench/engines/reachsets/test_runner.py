"""The reach-set runner: batched frames equal frame-by-frame steps; chunked pipeline."""

from __future__ import annotations

from pathlib import Path
from typing import TYPE_CHECKING

import pytest

from loaders import open_drive
from workbench.evaluate.pipeline import CHUNK_FRAMES, evaluate_frames
from workbench.evaluate.reach_runner import ReachRunner

if TYPE_CHECKING:
    from collections.abc import Iterator

    from loaders.records import Frame

SAMPLES = Path(__file__).resolve().parents[3] / "sample_logs"


@pytest.mark.parametrize("name", ["racing_overtake.saa", "highway_cut_in.mcap"])
def test_step_many_equals_step_by_step(name):
    drive = open_drive(SAMPLES / name)
    frames = list(drive.frames())[:70]
    drive.close()
    one = ReachRunner(drive.lane_map)
    expected = [one.step(f).record for f in frames]
    many = ReachRunner(drive.lane_map)
    got = many.step_many(frames[:25]) + many.step_many(frames[25:])
    assert [o.record for o in got] == expected
    assert any(not r["is_safe"] for r in expected)


def test_pipeline_hands_chunks_to_step_many_and_keeps_order():
    drive = open_drive(SAMPLES / "racing_overtake.saa")
    frames = list(drive.frames())
    drive.close()
    assert len(frames) > CHUNK_FRAMES
    calls: list[int] = []

    class Counting(ReachRunner):
        def step_many(self, chunk):
            calls.append(len(chunk))
            return super().step_many(chunk)

    results = [r for _, r in evaluate_frames(frames, [Counting(drive.lane_map)])]
    assert [r.frame for r in results] == [f.index for f in frames]
    assert max(calls) == CHUNK_FRAMES
    assert sum(calls) == len(frames)
    single = ReachRunner(drive.lane_map)
    assert [r.outputs["reachsets"].record for r in results] == [
        single.step(f).record for f in frames
    ]


def test_pipeline_evaluates_the_frames_read_before_a_reader_error():
    drive = open_drive(SAMPLES / "racing_overtake.saa")
    frames = list(drive.frames())[:10]
    drive.close()

    def broken() -> Iterator[Frame]:
        yield from frames
        raise OSError("truncated")

    seen: list[int] = []
    results = evaluate_frames(broken(), [ReachRunner(drive.lane_map)])
    with pytest.raises(OSError, match="truncated"):
        seen.extend(frame.index for frame, _ in results)
    assert seen == [f.index for f in frames]
