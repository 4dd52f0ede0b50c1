"""Engine results in the replay: pure reach layout and the .rrd round trip."""

from pathlib import Path
from typing import Any

import numpy as np
import shapely
from rerun.chunk import RrdReader

from loaders import open_drive
from tests.workbench.engines.helpers import step
from tests.workbench.fakes import FakeDrive, bound
from workbench.engines.reachsets.layout import layout_reach
from workbench.engines.reachsets.runner import ReachRunner
from workbench.replay.strips import time_colors
from workbench.viewer.replay import replay_drive

SAMPLES = Path(__file__).resolve().parents[4] / "sample_logs"


def test_time_colors_run_from_yellow_to_purple():
    colors = time_colors(np.array([0.0, 4.0]), 4.0, alpha=0xFF)
    assert colors.dtype == np.uint32
    assert [hex(int(c)) for c in colors] == ["0xffeb3cff", "0x8728e6ff"]


def test_layout_matches_the_engine_result_frame_by_frame():
    drive = FakeDrive(n_frames=6, n_actors=3)
    runner = ReachRunner(drive.lane_map, full_geometry=True)
    frames = list(drive.frames())
    results = [step(runner, f).result for f in frames]
    cols = layout_reach(frames, results)
    assert cols.is_safe.tolist() == [r.is_safe for r in results]
    assert cols.hit_counts.tolist() == [len(r.collisions) for r in results]
    assert len(cols.hit_labels) == int(cols.hit_counts.sum())
    # every non-empty polygon part of every set becomes one time-coloured strip
    for i, result in enumerate(results):
        sets = np.asarray(result.reach_sets, dtype=object).ravel()
        parts = shapely.get_parts(shapely.simplify(sets[sets != None], 0.2))  # noqa: E711
        polys = int(np.sum(shapely.get_type_id(parts) == 3))
        assert cols.sets.counts[i] == polys
    assert cols.sets.strips.shape[0] == cols.sets.counts.sum() == len(cols.sets.colors)
    assert cols.occupancy.counts.tolist() == [21] * len(frames)
    safe = cols.is_safe
    assert np.all(np.isnan(cols.first_collision_s[safe]))
    assert np.all(np.isfinite(cols.first_collision_s[~safe]))


def _table(path: Path, entity: str) -> Any:
    store = RrdReader(path).store().stream().collect()
    return store.reader(index="frame", contents=entity).to_arrow_table()


def test_replay_with_reach_engine_logs_results_and_violations(tmp_path):
    drive = FakeDrive(n_frames=12, n_actors=3)
    out = tmp_path / "reach.rrd"
    runner = ReachRunner(drive.lane_map, full_geometry=True)
    summary = replay_drive(drive, out=out, send_frames=5, engines=[bound(runner)])
    check = ReachRunner(drive.lane_map)
    verdicts = [step(check, f).is_safe for f in drive.frames()]
    assert summary.unsafe_frames == {"reachsets": verdicts.count(False)}
    flagged = {f for v in summary.violations for f in range(v.start_frame, v.end_frame + 1)}
    assert flagged == {i for i, ok in enumerate(verdicts) if not ok}
    states = _table(out, "/reach/state").to_pydict()
    by_frame = dict(zip(states["frame"], states["/reach/state:StateChange:state"], strict=True))
    assert [by_frame[i] for i in range(12)] == [["safe"] if ok else ["unsafe"] for ok in verdicts]
    for entity in ("/world/reach/sets", "/world/reach/occupancy", "/world/reach/collisions"):
        assert _table(out, entity).num_rows == 12, entity


def test_cut_in_sample_flags_the_cutting_in_car():
    """The scripted cut-in (car 1, t = 5.5 .. 8.5 s, docs/samples.md) must be flagged."""
    drive = open_drive(SAMPLES / "highway_cut_in.mcap")
    runner = ReachRunner(drive.lane_map)
    t0 = drive.info.start_ns
    culprits: set[str] = set()
    frames = 0
    for frame in drive.frames(t0 + 5_500_000_000, t0 + 8_500_000_000):
        culprits.update(step(runner, frame).culprits)
        frames += 1
    drive.close()
    assert frames == 60
    assert "1" in culprits
