"""``workbench export --window START:END``: a clip of any stretch of a drive."""

from __future__ import annotations

import json
from pathlib import Path

import pytest
from mcap.reader import make_reader

from loaders.clips import EVENT_TOPIC
from tests.workbench.cli_runs import run_workbench
from workbench.errors import WorkbenchError
from workbench.export.window import Window, parse_window
from workbench.incidents import IncidentRequest, find_incidents

SAMPLES = Path(__file__).resolve().parents[3] / "sample_logs"
LOG = SAMPLES / "urban_intersection.mcap"


@pytest.mark.parametrize(
    ("spec", "window"),
    [("2:6.5", Window(2.0, 6.5, frames=False)), ("#40:#60", Window(40, 60, frames=True))],
)
def test_parse_window(spec: str, window: Window) -> None:
    assert parse_window(spec) == window


@pytest.mark.parametrize(
    ("spec", "message"),
    [
        ("5", "START:END"),
        ("a:6", "'a' is not seconds"),
        ("#4.5:#6", "is not a frame number"),
        ("#4:6", "both ends"),
        ("6:5", "ends before it starts"),
        ("inf:5", "is not seconds"),
        ("-1:5", "is not seconds"),
    ],
)
def test_bad_windows_are_one_line(spec: str, message: str) -> None:
    with pytest.raises(WorkbenchError, match=message):
        parse_window(spec)


@pytest.mark.parametrize("spec", ["2:6", "#40:#120"])
def test_window_clip_holds_exactly_its_frames_span(tmp_path: Path, spec: str) -> None:
    report = find_incidents(IncidentRequest(LOG, engines=("rss",)))
    times = dict(report.frame_times)
    out = tmp_path / "out"
    args = ["export", str(LOG), "--engines", "rss", "--window", spec, "--no-rrd"]
    assert run_workbench([*args, "--out", str(out), "--store", str(tmp_path / "l.sqlite")]) == 0
    (clip,) = json.loads((out / "clips.json").read_text())
    assert clip["id"] is None
    assert (clip["start_frame"], clip["end_frame"]) == (40, 120)
    assert (clip["clip_start_ns"], clip["clip_end_ns"]) == (times[40], times[120])
    with (out / clip["files"]["mcap"]).open("rb") as f:
        reader = make_reader(f)
        stamps = [(c.topic, m.log_time) for _, c, m in reader.iter_messages()]
    with LOG.open("rb") as f:
        source = [(c.topic, m.log_time) for _, c, m in make_reader(f).iter_messages()]
    assert EVENT_TOPIC not in {topic for topic, _ in stamps}  # no incident, no event
    assert sorted(stamps) == sorted(s for s in source if times[40] <= s[1] <= times[120])
    doc = json.loads((out / clip["files"]["openlabel"]).read_text())["openlabel"]
    overlapping = {i.id for i in report.incidents if i.start_frame <= 120 and i.end_frame >= 40}
    assert {a["name"] for a in doc["actions"].values()} == overlapping
