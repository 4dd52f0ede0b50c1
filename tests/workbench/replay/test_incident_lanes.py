"""Incidents in the replay: pure lanes/markers, the .rrd entities and the incident blueprint."""

from pathlib import Path
from typing import Any

import numpy as np
from rerun.chunk import RrdReader

from loaders import open_drive
from workbench.engines import build_runners
from workbench.incidents import Incident, Severity
from workbench.replay.blueprint import replay_blueprint
from workbench.replay.incidents import INCIDENT_STATES, layout_incidents
from workbench.viewer import replay_drive

SAMPLES = Path(__file__).resolve().parents[3] / "sample_logs"
FRAMES = [(k, 1_000 + 100 * k) for k in range(10)]


def _incident(name: str, first: int, last: int) -> Incident:
    return Incident(
        id=name,
        engine="rss",
        objects=("7",),
        cause="RSS BrakeMin",
        start_frame=first,
        end_frame=last,
        start_ns=1_000 + 100 * first,
        end_ns=1_000 + 100 * last,
        severity=Severity(0.0, last - first + 1, (last - first) * 1e-7),
    )


def test_lanes_start_with_the_verdict_and_clear_after_the_last_frame():
    incidents = [_incident("b", 5, 9), _incident("a", 2, 3)]
    layout = layout_incidents(incidents, {"a": "confirmed"}, FRAMES)
    lanes = {lane.path: lane for lane in layout.lanes}
    a, b = lanes["incidents/lanes/rss/a"], lanes["incidents/lanes/rss/b"]
    assert (a.frames.tolist(), a.states) == ([2, 4], ("confirmed", "clear"))
    assert a.t_ns.tolist() == [1_200, 1_400]
    # open until the drive's last frame: no clear entry
    assert (b.frames.tolist(), b.states) == ([5], ("unreviewed",))
    assert set(a.states + b.states) <= set(INCIDENT_STATES)
    assert layout.marker_frames.tolist() == [2, 5]
    assert layout.marker_texts[0].startswith("[confirmed] a  RSS BrakeMin  object 7")
    assert layout.marker_texts[1].startswith("[unreviewed] b")
    assert layout.marker_levels == ("INFO", "WARN")


def _blueprint_rows(path: Path) -> dict[str, Any]:
    reader = RrdReader(path)
    store = reader.store(store=reader.blueprints()[0]).stream().collect()
    rows: dict[str, Any] = (
        store.reader(index="blueprint", contents="/**").to_arrow_table().to_pydict()
    )
    return rows


def test_incident_blueprint_selects_the_incident_window(tmp_path):
    replay_blueprint((0.0, 0.0), ["rss"], selection=(40, 75)).save("t", tmp_path / "b.rbl")
    rows = _blueprint_rows(tmp_path / "b.rbl")
    assert rows["/time_panel:TimePanelBlueprint:time_selection"] == [[{"min": 40, "max": 75}]]
    assert rows["/time_panel:TimePanelBlueprint:timeline"] == [["frame"]]
    replay_blueprint((0.0, 0.0), ["rss"]).save("t", tmp_path / "plain.rbl")
    plain = _blueprint_rows(tmp_path / "plain.rbl")
    assert "/time_panel:TimePanelBlueprint:time_selection" not in plain


def test_replay_rrd_holds_one_lane_per_incident_and_the_markers(tmp_path):
    out = tmp_path / "drive.rrd"
    drive = open_drive(SAMPLES / "highway_cut_in.mcap")
    try:
        runners = build_runners(["rss"], drive.lane_map, full_geometry=True)
        summary = replay_drive(
            drive, out=out, engines=runners, end_ns=drive.info.start_ns + 12 * 10**9
        )
    finally:
        drive.close()
    assert summary.incidents
    reader = RrdReader(out)
    store = reader.store(store=reader.recordings()[0]).stream().collect()
    table = store.reader(index="frame", contents="/incidents/**").to_arrow_table().to_pydict()
    lanes = {c.split(":")[0] for c in table if c.endswith("StateChange:state")}
    assert lanes == {f"/incidents/lanes/rss/{i.id}" for i in summary.incidents}
    texts = [t[0] for t in table["/incidents/log:TextLog:text"] if t]
    assert sorted(t.split()[1] for t in texts) == sorted(i.id for i in summary.incidents)
    frames = np.array(table["frame"])
    starts = {i.start_frame for i in summary.incidents}
    marker_frames = {
        int(f) for f, t in zip(frames, table["/incidents/log:TextLog:text"], strict=True) if t
    }
    assert marker_frames == starts


def test_an_incident_view_hides_the_engines_object_labels(tmp_path):
    """Only the incident's objects are labelled: every engine's per-object labels are off."""
    incident = _incident("rss-000002-x", 2, 3)
    replay_blueprint((0.0, 0.0), ["rss", "reachsets"], incident=incident).save(
        "t", tmp_path / "inc.rbl"
    )
    rows = _blueprint_rows(tmp_path / "inc.rbl")
    hidden = {
        column.split("/overrides/", 1)[1].split("/visualizers/", 1)[0]
        for column, values in rows.items()
        if "/overrides/" in column and column.endswith(":show_labels") and values[0] == [False]
    }
    assert {"world/rss/constellations", "world/reach/collisions", "world/actors"} <= hidden
    replay_blueprint((0.0, 0.0), ["rss", "reachsets"]).save("t", tmp_path / "plain.rbl")
    plain = _blueprint_rows(tmp_path / "plain.rbl")
    assert not [c for c in plain if c.endswith(":show_labels")]
