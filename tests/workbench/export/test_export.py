"""``workbench export`` end to end: every clip opens as it is and re-evaluates to its incident."""

from __future__ import annotations

import json
import subprocess
import sys
from collections import Counter
from pathlib import Path
from typing import Any

import jsonschema
import numpy as np
import pytest
import rerun as rr
from mcap.reader import NonSeekingReader, make_reader
from mcap.writer import Writer
from PIL import Image
from rosbags.highlevel import AnyReader

from loaders.clips import EVENT_TOPIC
from loaders.message_logs.mapsource import read_map
from tests.conftest import running_in_ci
from tests.workbench.cli_runs import run_workbench as _run
from workbench.incidents import IncidentRequest, find_incidents

SAMPLES = Path(__file__).resolve().parents[3] / "sample_logs"
FRAME_NS = 50_000_000  # the samples' ego rate: 20 Hz
RERUN = Path(sys.executable).parent / "rerun"


def _export(log: Path, out: Path, *extra: str) -> list[dict[str, Any]]:
    store = out.parent / f"{out.name}.sqlite"
    args = ["export", str(log), "--out", str(out), "--store", str(store), *extra]
    assert _run(args) == 0
    return list(json.loads((out / "clips.json").read_text()))


def _records(path: Path) -> list[tuple[str, int, bytes]]:
    with path.open("rb") as f:
        return [(c.topic, m.log_time, bytes(m.data)) for _, c, m in make_reader(f).iter_messages()]


@pytest.fixture(scope="module")
def mcap_export(tmp_path_factory: pytest.TempPathFactory) -> tuple[Path, list[dict[str, Any]]]:
    out = tmp_path_factory.mktemp("export") / "clips"
    return out, _export(SAMPLES / "highway_cut_in.mcap", out, "--all", "--engines", "rss")


def test_clip_holds_exactly_the_window_and_the_map(mcap_export) -> None:
    out, clips = mcap_export
    assert clips
    source = _records(SAMPLES / "highway_cut_in.mcap")
    for clip in clips:
        path = out / clip["files"]["mcap"]
        copied = Counter(r for r in _records(path) if r[0] != EVENT_TOPIC)
        window = Counter(r for r in source if clip["clip_start_ns"] <= r[1] <= clip["clip_end_ns"])
        assert copied == window
        assert sum(copied.values()) + 1 == clip["messages"]
        with path.open("rb") as f:
            reader = make_reader(f)
            maps = [a for a in reader.iter_attachments() if a.name.endswith(".osm")]
            metadata = {m.name: m.metadata for m in reader.iter_metadata()}
        assert maps
        assert read_map(bytes(maps[0].data), maps[0].name).lanes
        assert metadata["incident"]["incident_id"] == clip["id"]
        assert metadata["drive"]["log"] == "highway_cut_in.mcap"


def test_clip_reads_whole_with_rosbags_and_carries_the_event(mcap_export) -> None:
    out, clips = mcap_export
    clip = clips[0]
    with AnyReader([out / clip["files"]["mcap"]]) as reader:
        count = sum(1 for _ in reader.messages())
        (conn,) = [c for c in reader.connections if c.topic == EVENT_TOPIC]
        (_, _, raw) = next(iter(reader.messages(connections=[conn])))
        event: Any = reader.deserialize(raw, conn.msgtype)
    assert count == clip["messages"]
    info = rr.chunk.McapReader(out / clip["files"]["mcap"]).info()  # Rerun's own MCAP import
    assert (info.message_count, info.attachment_count) == (clip["messages"], 1)
    pairs = {p.key: p.value for p in event.metadata}
    assert pairs["incident_id"] == clip["id"]
    assert pairs["engine"] == clip["engine"]
    # the event spans the incident, not the clip's window
    assert event.start_time.sec * 10**9 + event.start_time.nanosec == clip["start_ns"]
    assert event.end_time.sec * 10**9 + event.end_time.nanosec == clip["end_ns"]
    assert json.loads(pairs["objects"]) == clip["objects"]


def test_clip_re_evaluates_to_the_same_incident(mcap_export) -> None:
    out, clips = mcap_export
    for clip in clips:
        report = find_incidents(IncidentRequest(out / clip["files"]["mcap"], engines=("rss",)))
        same = [
            i
            for i in report.incidents
            if (i.engine, list(i.objects), i.cause)
            == (clip["engine"], clip["objects"], clip["cause"])
        ]
        assert same, f"{clip['id']} not found again in its clip"
        assert any(
            abs(i.start_ns - clip["start_ns"]) <= FRAME_NS
            and abs(i.end_ns - clip["end_ns"]) <= FRAME_NS
            for i in same
        )


def test_recording_verifies_and_openlabel_validates(mcap_export, external_dir: Path) -> None:
    out, clips = mcap_export
    schema = json.loads(
        (external_dir / "openlabel" / "openlabel_json_schema-v1.0.0.json").read_text()
    )
    for clip in clips:
        rrd = out / clip["files"]["rrd"]
        done = subprocess.run(  # noqa: S603 - the venv's rerun on our own file
            [str(RERUN), "rrd", "verify", str(rrd)], capture_output=True, text=True, check=False
        )
        assert done.returncode == 0, done.stderr
        doc = json.loads((out / clip["files"]["openlabel"]).read_text())
        jsonschema.validate(doc, schema)
        (action,) = doc["openlabel"]["actions"].values()
        assert action["name"] == clip["id"]
    index = (out / "clips.csv").read_text().splitlines()
    assert len(index) == len(clips) + 1


def test_ros1_bag_clip_keeps_its_profile_and_re_evaluates(tmp_path: Path) -> None:
    log = SAMPLES / "highway_cut_in.bag"
    clips = _export(log, tmp_path / "out", "--all", "--engines", "rss", "--no-rrd")
    with AnyReader([log]) as reader:
        source = [(c.topic, t, bytes(raw)) for c, t, raw in reader.messages()]
    for clip in clips:
        path = tmp_path / "out" / clip["files"]["mcap"]
        with path.open("rb") as f:
            assert make_reader(f).get_header().profile == "ros1"
        copied = Counter(r for r in _records(path) if r[0] != EVENT_TOPIC)
        assert copied == Counter(
            r for r in source if clip["clip_start_ns"] <= r[1] <= clip["clip_end_ns"]
        )
        with AnyReader([tmp_path / "out" / clip["files"]["bag"]]) as reader:
            twin = Counter((c.topic, t, bytes(raw)) for c, t, raw in reader.messages())
        assert twin == Counter(_records(path))  # the same records, readable by rosbags
        report = find_incidents(IncidentRequest(path, engines=("rss",)))
        assert any(
            i.engine == clip["engine"]
            and list(i.objects) == clip["objects"]
            and abs(i.start_ns - clip["start_ns"]) <= FRAME_NS
            for i in report.incidents
        )


def test_export_by_verdict_from_the_store(tmp_path: Path, mcap_export) -> None:
    _, clips = mcap_export
    store = tmp_path / "labels.sqlite"
    log = SAMPLES / "highway_cut_in.mcap"
    label = ["label", str(log), clips[0]["id"], "--verdict", "confirmed", "--engines", "rss"]
    assert _run([*label, "--note", "late brake", "--store", str(store)]) == 0
    out = tmp_path / "confirmed"
    args = ["export", str(log), "--verdict", "confirmed", "--engines", "rss", "--no-rrd"]
    assert _run([*args, "--out", str(out), "--store", str(store)]) == 0
    (clip,) = json.loads((out / "clips.json").read_text())
    assert (clip["id"], clip["verdict"], clip["note"]) == (
        clips[0]["id"],
        "confirmed",
        "late brake",
    )


def test_unknown_incident_is_one_line(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    log = SAMPLES / "highway_cut_in.mcap"
    args = ["export", str(log), "--incident", "rss-9-x", "--engines", "rss", "--out", str(tmp_path)]
    assert _run([*args, "--store", str(tmp_path / "s.sqlite")]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert err[-1].startswith("error: ")
    assert "no incident rss-9-x" in err[-1]


def test_thumbnail_of_the_incident(tmp_path: Path, mcap_export) -> None:
    if not any(Path("/usr/share/vulkan/icd.d").glob("*.json")):
        reason = "no Vulkan driver (apt-get install mesa-vulkan-drivers)"
        if running_in_ci():
            pytest.fail(reason)
        pytest.skip(reason)
    _, clips = mcap_export
    out = tmp_path / "thumb"
    (clip,) = _export(
        SAMPLES / "highway_cut_in.mcap", out, "--incident", clips[0]["id"], "--engines", "rss"
    )
    png = out / clip["files"]["png"]
    with Image.open(png) as image:
        pixels = np.asarray(image.convert("RGB"))
    assert pixels.shape[0] >= 720
    assert len(np.unique(pixels.reshape(-1, 3), axis=0)) > 50  # a rendered scene, not a blank


def test_truncated_log_exports_up_to_the_damage(tmp_path: Path) -> None:
    source = SAMPLES / "highway_cut_in.mcap"
    cut = tmp_path / "cut.mcap"
    with source.open("rb") as f, cut.open("wb") as out:
        reader = make_reader(f)
        writer = Writer(out, chunk_size=8192)
        writer.start(profile="ros2")
        ids: dict[int, int] = {}
        for schema, channel, message in reader.iter_messages():
            if channel.id not in ids and schema is not None:
                sid = writer.register_schema(schema.name, schema.encoding, schema.data)
                ids[channel.id] = writer.register_channel(
                    channel.topic, channel.message_encoding, sid, channel.metadata
                )
            writer.add_message(ids[channel.id], message.log_time, message.data, 0)
        writer.finish()  # type: ignore[no-untyped-call]
    data = cut.read_bytes()
    cut.write_bytes(data[: len(data) * 7 // 10])
    out_dir = tmp_path / "out"
    args = ["export", str(cut), "--all", "--engines", "rss", "--no-rrd", "--margin", "30"]
    args += ["--map", str(SAMPLES / "highway_cut_in.osm"), "--out", str(out_dir)]
    assert _run([*args, "--store", str(tmp_path / "s.sqlite")]) == 2  # the log's own error
    last = max(t for _, t, _ in _records_until_damage(cut))
    clips = json.loads((out_dir / "clips.json").read_text())
    assert clips
    for clip in clips:  # windows end where the readable log ends: every clip is whole
        assert clip["problem"] is None
        assert clip["clip_end_ns"] <= last
        path = out_dir / clip["files"]["mcap"]
        copied = Counter(r for r in _records(path) if r[0] != EVENT_TOPIC)
        window = [
            r
            for r in _records_until_damage(cut)
            if clip["clip_start_ns"] <= r[1] <= clip["clip_end_ns"]
        ]
        assert copied == Counter(window)
    assert not list(out_dir.glob("*.part"))


def _records_until_damage(path: Path) -> list[tuple[str, int, bytes]]:
    out: list[tuple[str, int, bytes]] = []
    with path.open("rb") as f:
        try:
            for _, c, m in NonSeekingReader(f).iter_messages(log_time_order=False):
                out.append((c.topic, m.log_time, bytes(m.data)))
        except Exception:  # noqa: BLE001, S110 - the damage ends the readable part
            pass
    return out
