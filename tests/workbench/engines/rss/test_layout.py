"""Structured RSS results in the replay: pure layout and the .rrd round trip."""

from pathlib import Path

import numpy as np
import pytest
import shapely
from rerun.chunk import RrdReader

from loaders import open_drive
from loaders.records import Frame
from rss.model import ConstellationType
from tests.workbench.engines.helpers import (
    forward_fill,
    open_window,
    record,
    rrd_states,
    rss_window,
    step,
)
from tests.workbench.fakes import bound
from workbench.engines.rss.layout import layout_rss
from workbench.engines.rss.runner import RssRunner
from workbench.engines.rss.sink import object_path
from workbench.engines.rss.verdict import RssVerdict
from workbench.replay.short_labels import ShortLabels
from workbench.viewer.replay import replay_drive

SAMPLES = Path(__file__).resolve().parents[4] / "sample_logs"
CUT_IN = SAMPLES / "highway_cut_in.mcap"
#: The cut-in (5.5 .. 8.5 s) with some free flow before it.
WINDOW_S = (4.0, 9.0)


@pytest.fixture(scope="module")
def cut_in() -> tuple[list[Frame], list[RssVerdict]]:
    return rss_window(CUT_IN, WINDOW_S, outlines=True)


def test_layout_follows_the_engine_frame_by_frame(cut_in):
    frames, outputs = cut_in
    labels = ShortLabels()
    cols = layout_rss(frames, outputs, labels)
    n = len(frames)
    assert cols.frame_state == [
        "no constellation" if o.result is None else ("safe" if o.is_safe else "dangerous")
        for o in outputs
    ]
    assert {"safe", "dangerous"} <= set(cols.frame_state)
    for i, (frame, out) in enumerate(zip(frames, outputs, strict=True)):
        detail = out
        assert isinstance(detail, RssVerdict)
        present = {str(a) for a in frame.actors.ids}
        assert cols.link_counts[i] == len(set(detail.labels) & present)
        dangerous = set(record(out)["dangerous_objects"])
        assert cols.danger_counts[i] == len(dangerous & present)
        for object_id, states in cols.object_states.items():
            if object_id in dangerous:
                assert states[i] == "dangerous"
            elif object_id not in detail.labels:
                assert states[i] == "not relevant"
        assert cols.responses["longitudinal"][i] == record(out)["longitudinal_response"]
    assert len(cols.link_labels) == cols.link_strips_m.shape[0] == int(cols.link_counts.sum())
    assert cols.danger_centre_m.shape == (int(cols.danger_counts.sum()), 3)
    assert all(len(states) == n for states in cols.object_states.values())
    # every line starts at the ego and ends on the object its full id names; its label
    # names that object by its short label
    first = 0
    for i, frame in enumerate(frames):
        ids = [str(a) for a in frame.actors.ids]
        for k in range(first, first + int(cols.link_counts[i])):
            start, end = cols.link_strips_m[k]
            assert np.allclose(start[:2], [frame.ego.x_m, frame.ego.y_m], atol=1e-3)
            row = ids.index(cols.link_object_ids[k])
            assert cols.link_labels[k].split(":", 1)[0] == labels[cols.link_object_ids[k]]
            assert np.allclose(end[:2], [frame.actors.x_m[row], frame.actors.y_m[row]], atol=1e-3)
        first += int(cols.link_counts[i])


def test_longitudinal_states_agree_with_the_plotted_distances(cut_in):
    frames, outputs = cut_in
    cols = layout_rss(frames, outputs)
    checked = 0
    for object_id, states in cols.object_states.items():
        rows, lon = cols.distances[f"{object_id}/lon_m"]
        _, safe = cols.distances[f"{object_id}/lon_safe_m"]
        for i, current, needed in zip(rows.tolist(), lon, safe, strict=True):
            if states[i] in {"lon unsafe", "dangerous"}:
                assert current <= needed, (object_id, i)
            else:
                assert current > needed, (object_id, i)
            checked += 1
    assert checked > len(frames)


def test_acceleration_restrictions_follow_the_response(cut_in):
    frames, outputs = cut_in
    cols = layout_rss(frames, outputs)
    braking = 0
    for response, series, key in (
        ("longitudinal_response", "lon_max_mps2", "longitudinal"),
        ("lateral_response_left", "lat_left_max_mps2", "lateral_left"),
        ("lateral_response_right", "lat_right_max_mps2", "lateral_right"),
    ):
        upper = cols.accel[series]
        for i, out in enumerate(outputs):
            assert upper[i] == pytest.approx(record(out)["acceleration_restrictions"][key][1])
            if record(out)[response] != "None":
                assert upper[i] < 0
                braking += 1
    assert braking > 0
    # lateral bounds of +-1000 m/s² mean "unbounded" and are not plotted
    for name, values in cols.accel.items():
        assert np.all(np.abs(values[np.isfinite(values)]) < 999), name


def test_frames_without_constellations_are_marked():
    drive = open_drive(CUT_IN)
    frames = [f for _, f in zip(range(5), drive.frames(), strict=False)]
    drive.close()
    runner = RssRunner(None)
    cols = layout_rss(frames, [step(runner, f) for f in frames])
    assert cols.frame_state == ["no constellation"] * 5
    assert cols.object_states == {}
    assert np.all(np.isnan(cols.accel["lon_min_mps2"]))
    assert cols.link_counts.tolist() == [0] * 5


def test_constellation_types_are_named_in_the_labels(cut_in):
    frames, outputs = cut_in
    cols = layout_rss(frames, outputs)
    types = {
        ConstellationType(int(t))
        for out in outputs
        if out.result is not None
        for t in out.constellation_type
    }
    assert types == {ConstellationType.SameDirection}
    assert cols.link_labels
    assert all(": same dir  lon " in label for label in cols.link_labels)


def test_replay_logs_state_lanes_constellations_and_plots(tmp_path, cut_in):
    frames, outputs = cut_in
    path = tmp_path / "rss.rrd"
    drive = open_window(CUT_IN, WINDOW_S)
    runner = RssRunner(drive.lane_map, outlines=True)
    summary = replay_drive(drive, out=path, send_frames=7, engines=[bound(runner)])
    drive.close()
    assert summary.unsafe_frames == {"rss": sum(not o.is_safe for o in outputs)}
    cols = layout_rss(frames, outputs)
    index = [f.index for f in frames]
    frame_states = rrd_states(path, "/rss/structured/state")
    assert [frame_states[i] for i in index] == cols.frame_state
    # object lanes carry only changes, also across chunk boundaries (7 frames); filled
    # forward they give the layout's per-frame state
    for object_id, states in cols.object_states.items():
        changes = rrd_states(path, "/" + object_path(object_id))
        first = next(k for k, s in enumerate(states) if s != "not relevant")
        assert min(changes) == index[first]
        assert forward_fill(changes, index)[first:] == states[first:]
        flips = sum(a != b for a, b in zip(states[first:], states[first + 1 :], strict=False))
        assert len(changes) == 1 + flips
    store = RrdReader(path).store().stream().collect()
    for entity in ("/world/rss/constellations", "/world/rss/dangerous", "/world/rss/road_areas"):
        table = store.reader(index="frame", contents=entity).to_arrow_table()
        assert table.num_rows == len(frames), entity
    for series in ("/plots/rss/acceleration/lon_max_mps2", "/plots/rss/distances/1/lon_m"):
        assert store.reader(index="frame", contents=series).to_arrow_table().num_rows > 0


def test_intersection_constellations_show_the_distances_to_enter():
    drive = open_drive(SAMPLES / "urban_intersection.mcap")
    runner = RssRunner(drive.lane_map)
    frames = list(drive.frames())
    outputs = [step(runner, f) for f in frames]
    drive.close()
    cols = layout_rss(frames, outputs)
    crossing = [label for label in cols.link_labels if ": intersection" in label]
    assert crossing
    assert all("to enter: ego " in label for label in crossing)
    enter = {k: v for k, v in cols.distances.items() if k.endswith("/ego_to_enter_m")}
    assert enter
    for rows, values in enter.values():
        assert len(rows) == len(values)
        assert np.all(values >= 0)


def test_road_area_outlines_reach_from_the_ego_to_the_object(cut_in):
    frames, outputs = cut_in
    cols = layout_rss(frames, outputs)
    assert np.all(cols.area_counts >= cols.link_counts)
    first_area = np.concatenate([[0], np.cumsum(cols.area_counts)])
    first_link = np.concatenate([[0], np.cumsum(cols.link_counts)])
    checked = 0
    for i, frame in enumerate(frames):
        ids = [str(a) for a in frame.actors.ids]
        rings = cols.area_strips_m[first_area[i] : first_area[i + 1], :, :2]
        area = shapely.union_all([shapely.Polygon(r) for r in rings]) if len(rings) else None
        for k in range(first_link[i], first_link[i + 1]):
            row = ids.index(cols.link_object_ids[k])
            obj = shapely.Point(frame.actors.x_m[row], frame.actors.y_m[row])
            ego = shapely.Point(frame.ego.x_m, frame.ego.y_m)
            assert area is not None
            assert area.distance(obj) < frame.actors.length_m[row]
            assert area.distance(ego) < 5.0
            checked += 1
    assert checked > len(frames)
