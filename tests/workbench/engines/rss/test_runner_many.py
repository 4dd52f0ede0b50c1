"""``RssRunner.step_many`` (chunks of frames, one matching / stacking / engine call) equals
``step`` frame by frame: records, verdicts, detail incl. road-area outlines, memory."""

from __future__ import annotations

from pathlib import Path
from typing import TYPE_CHECKING

import numpy as np
import pytest

from loaders import open_drive
from loaders.maps.opendrive import read_opendrive
from loaders.records import ActorTable, EgoState, Frame, ObjectClass
from rss.params import RssParams
from rss.scene import SceneMemo, create_scene, prepare
from tests.equality import assert_same
from tests.workbench.engines.helpers import record, step
from tests.workbench.engines.rss.test_runner import SCENARIOS
from workbench.engines.ids import ActorIds
from workbench.engines.rss.adapter import frame_to_scene, lane_graph_from_map
from workbench.engines.rss.runner import RssRunner

if TYPE_CHECKING:
    from collections.abc import Sequence

    from loaders.maps.model import LaneMap
    from workbench.engines.rss.verdict import RssVerdict

ROOT = Path(__file__).resolve().parents[4]
SAMPLES = ROOT / "sample_logs"
TOWN01 = ROOT.parent / "shared" / "external" / "maps" / "Town01.xodr"
CHUNKS = [1, 7, 32]


def _compare(lane_map: LaneMap | None, frames: Sequence[Frame], chunk: int) -> list[RssVerdict]:
    """Run both paths with outlines; assert equality incl. memory after every chunk."""
    one, many = RssRunner(lane_map, outlines=True), RssRunner(lane_map, outlines=True)
    out: list[RssVerdict] = []
    for lo in range(0, len(frames), chunk):
        part = frames[lo : lo + chunk]
        expected = [step(one, f) for f in part]
        got = many.step_many(part)
        assert_same(got, expected, f"frames {lo}..")
        assert_same(many._memory, one._memory, f"memory after frame {lo + len(part) - 1}")
        out.extend(expected)
    return out


@pytest.mark.parametrize("chunk", CHUNKS)
@pytest.mark.parametrize("name", SCENARIOS)
def test_step_many_equals_step_on_the_sample_drives(name, chunk):
    drive = open_drive(SAMPLES / f"{name}.mcap")
    frames = list(drive.frames())
    drive.close()
    assert drive.lane_map is not None
    outputs = _compare(drive.lane_map, frames, chunk)
    assert len(outputs) == len(frames)
    assert any(record(o)["constellations"] > 0 for o in outputs)


def test_step_many_equals_step_without_a_lane_map():
    """The racing drive has a track map only: no constellations, every frame safe."""
    drive = open_drive(SAMPLES / "racing_overtake.saa")
    frames = list(drive.frames())
    drive.close()
    outputs = _compare(drive.lane_map, frames, 7)
    assert len(outputs) == len(frames)
    assert all(o.is_safe and record(o)["constellations"] == 0 for o in outputs)


def _town01_frames(lane_map: LaneMap, n_frames: int) -> list[Frame]:
    """Ego + 30 cars on Town01 lanes within 80 m, constant velocity; gaps on purpose.

    Some cars leave for a few frames (their memory goes), and in three frames the ego is
    far off the map (no constellations: the whole memory goes).
    """
    graph = prepare(lane_graph_from_map(lane_map)).graph
    rng = np.random.default_rng(11)
    lanes = np.flatnonzero(~graph.is_intersection)

    def pose() -> tuple[float, float, float]:
        c = graph.centre_m[int(rng.choice(lanes))]
        k = int(rng.integers(0, len(c) - 1))
        d = c[k + 1] - c[k]
        return float(c[k, 0]), float(c[k, 1]), float(np.arctan2(d[1], d[0]))

    ex, ey, eyaw = pose()
    cars: list[tuple[float, float, float, float]] = []
    while len(cars) < 30:
        x, y, yaw = pose()
        if 5.0 < np.hypot(x - ex, y - ey) < 80.0:
            cars.append((x, y, yaw, float(rng.uniform(0.0, 12.0))))
    car = np.array(cars)
    frames = []
    for i in range(n_frames):
        t = 0.1 * i
        off_map = i in {9, 10, 40}
        ego = EgoState(
            x_m=ex + 8.0 * np.cos(eyaw) * t + (1e5 if off_map else 0.0),
            y_m=ey + 8.0 * np.sin(eyaw) * t,
            z_m=0.0,
            yaw_rad=eyaw,
            speed_mps=8.0,
            accel_mps2=0.0,
            yaw_rate_radps=0.0,
        )
        present = (np.arange(len(car)) + i) % 13 != 0
        c = car[present]
        actors = ActorTable.from_columns(
            ids=[f"car{k}" for k in np.flatnonzero(present)],
            object_class=np.full(len(c), ObjectClass.CAR),
            x_m=c[:, 0] + c[:, 3] * np.cos(c[:, 2]) * t,
            y_m=c[:, 1] + c[:, 3] * np.sin(c[:, 2]) * t,
            z_m=np.zeros(len(c)),
            yaw_rad=c[:, 2],
            vx_mps=c[:, 3] * np.cos(c[:, 2]),
            vy_mps=c[:, 3] * np.sin(c[:, 2]),
            length_m=np.full(len(c), 4.5),
            width_m=np.full(len(c), 1.9),
        )
        frames.append(Frame(index=i, t_ns=i * 100_000_000, ego=ego, actors=actors))
    return frames


@pytest.fixture(scope="module")
def town01() -> LaneMap:
    if not TOWN01.is_file():
        pytest.skip(f"external map {TOWN01} absent (present under CI=true)")
    return read_opendrive(TOWN01)


@pytest.mark.parametrize("chunk", CHUNKS)
def test_step_many_equals_step_on_a_moving_town01_scene(town01, chunk):
    frames = _town01_frames(town01, 45)
    outputs = _compare(town01, frames, chunk)
    counts = [record(o)["constellations"] for o in outputs]
    assert counts[9] == counts[10] == counts[40] == 0
    assert sum(c > 10 for c in counts) > 30


def test_scene_memos_kept_across_frames_change_nothing(town01):
    """Scenes with per-map memos (corridor layouts, whole segments, routes typing) filled
    by earlier frames equal scenes with fresh memos and a fresh graph per frame."""
    frames = _town01_frames(town01, 12)
    graph = lane_graph_from_map(town01)
    warm = prepare(graph)
    warm_memo = SceneMemo()
    params = RssParams()
    built = 0
    for frame in frames:
        fresh = prepare(graph)
        scenes = []
        for prep, memo in ((warm, warm_memo), (fresh, SceneMemo())):
            ego, objects, _ = frame_to_scene(frame, prep, params, ActorIds())
            scenes.append(create_scene(prep, ego, objects, params.scene, memo=memo))
        assert repr(scenes[0]) == repr(scenes[1])
        built += len(scenes[0].constellations)
    assert built > 100
