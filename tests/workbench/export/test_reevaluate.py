"""Acceptance: every exported clip, re-evaluated with only what the export wrote, yields its
incident (same engine, object and cause; start and end within one frame), for every sample
log in each container (MCAP, ROS 1 bag, rosbag2) and for truncated copies.

The clip's incident is matched by engine, objects, cause and times, never by id (an id
depends on the drive's content hash, which a clip does not share).
"""

from __future__ import annotations

import itertools
import json
from pathlib import Path
from typing import Any

import pytest
from mcap.reader import make_reader
from mcap.writer import Writer

from tests.workbench.cli_runs import run_workbench
from workbench.incidents import IncidentRequest, find_incidents

SAMPLES = Path(__file__).resolve().parents[3] / "sample_logs"
SCENARIOS = sorted(p.stem for p in SAMPLES.glob("*.mcap") if "_foxglove" not in p.stem)
ENGINES = ("rss", "unstructured")  # parking_lot: no RSS incident under `urban`


def _containers(stem: str) -> list[Path]:
    return [SAMPLES / f"{stem}.mcap", SAMPLES / f"{stem}.bag", SAMPLES / f"{stem}_rosbag2"]


def _truncated(tmp_path: Path, log: Path, keep: float) -> Path:
    """A copy of ``log`` cut at ``keep`` of its bytes (ROS 1 bags and rosbag2 databases keep
    their index at the end: a truncated one cannot be opened, which is one line)."""
    cut = tmp_path / "truncated" / log.name
    cut.parent.mkdir()
    data = log.read_bytes()
    cut.write_bytes(data[: int(len(data) * keep)])
    return cut


def _map_at_the_end(tmp_path: Path, log: Path) -> Path:
    """``log`` rewritten with its map attachment after the messages, then truncated."""
    whole = tmp_path / f"late-map-{log.name}"
    with log.open("rb") as f, whole.open("wb") as out:
        reader = make_reader(f)
        writer = Writer(out, chunk_size=8192)
        writer.start(profile=reader.get_header().profile)
        ids: dict[int, int] = {}
        for schema, channel, message in reader.iter_messages():
            if channel.id not in ids:
                sid = (
                    0
                    if schema is None
                    else writer.register_schema(schema.name, schema.encoding, schema.data)
                )
                ids[channel.id] = writer.register_channel(
                    channel.topic, channel.message_encoding, sid, channel.metadata
                )
            writer.add_message(ids[channel.id], message.log_time, message.data, 0)
        for a in reader.iter_attachments():
            writer.add_attachment(a.create_time, a.log_time, a.name, a.media_type, a.data)
        writer.finish()  # type: ignore[no-untyped-call]
    return _truncated(tmp_path, whole, 0.9)


def _export(log: Path, out: Path, *extra: str) -> list[dict[str, Any]]:
    args = [
        "export",
        str(log),
        "--all",
        "--engines",
        ",".join(ENGINES),
        "--no-rrd",
        "--margin",
        "2",
    ]
    args += extra
    code = run_workbench([*args, "--out", str(out), "--store", str(out.parent / "l.sqlite")])
    assert code in {0, 2}  # 2: a truncated log's own error, after the clips
    return list(json.loads((out / "clips.json").read_text()))


def _frame_ns(log: Path) -> int:
    report = find_incidents(IncidentRequest(log, engines=ENGINES))
    times = [t for _, t in report.frame_times]
    return max(b - a for a, b in itertools.pairwise(times))


def _re_evaluated(out: Path, clip: dict[str, Any]) -> Path:
    """The file a user re-evaluates: the bag of a ROS 1 clip (its map beside), else the MCAP."""
    name = str(clip["files"]["bag"] or clip["files"]["mcap"])
    return out / name


def _check_every_clip(log: Path, out: Path, *extra: str) -> int:
    clips = _export(log, out, *extra)
    frame_ns = _frame_ns(log)
    written = [c for c in clips if c["problem"] is None]
    for clip in written:
        path = _re_evaluated(out, clip)
        if clip["files"]["bag"]:
            assert clip["files"]["map"], f"{clip['stem']}: a ROS 1 clip without its map"
            assert (out / clip["files"]["map"]).is_file()
        found = find_incidents(IncidentRequest(path, engines=ENGINES)).incidents
        same = [
            i
            for i in found
            if (i.engine, list(i.objects), i.cause)
            == (clip["engine"], clip["objects"], clip["cause"])
            and abs(i.start_ns - clip["start_ns"]) <= frame_ns
            and abs(i.end_ns - clip["end_ns"]) <= frame_ns
        ]
        assert same, f"{log.name}: {clip['id']} not found again in {path.name}"
    return len(written)


@pytest.mark.parametrize("stem", SCENARIOS)
def test_every_clip_of_every_sample_re_evaluates_to_its_incident(tmp_path: Path, stem: str) -> None:
    checked = 0
    for k, log in enumerate(_containers(stem)):
        checked += _check_every_clip(log, tmp_path / f"out{k}")
    assert checked > 0


@pytest.mark.parametrize(
    "name", ["highway_cut_in", "hard_braking_lead", "pedestrian_crossing", "wrong_way_oncoming"]
)
def test_every_clip_of_a_truncated_copy_re_evaluates_to_its_incident(
    tmp_path: Path, name: str
) -> None:
    log = _truncated(tmp_path, SAMPLES / f"{name}.mcap", 0.9)
    assert _check_every_clip(log, tmp_path / "out") > 0


def test_a_truncated_log_without_its_map_is_refused_before_any_clip(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    log = _map_at_the_end(tmp_path, SAMPLES / "highway_cut_in.mcap")
    out = tmp_path / "out"
    args = [
        "export",
        str(log),
        "--all",
        "--engines",
        ",".join(ENGINES),
        "--no-rrd",
        "--out",
        str(out),
    ]
    args += ["--store", str(tmp_path / "l.sqlite")]
    assert run_workbench(args) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert err[-1].startswith(f"error: {log}: no map could be read")
    assert not out.exists()
    assert run_workbench([*args, "--without-map"]) == 2  # the log's own error, at the end
    assert "truncated or corrupted" in capsys.readouterr().err  # went on, without the map
    mapped = tmp_path / "mapped"
    args += ["--map", str(SAMPLES / "highway_cut_in.osm")]
    assert _check_every_clip(log, mapped, *args[args.index("--map") :]) > 0
