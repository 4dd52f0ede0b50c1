"""One-pass clip cutting: each clip holds exactly its window's raw messages."""

from __future__ import annotations

import shutil
from collections import Counter
from pathlib import Path
from typing import Any

import pytest
from foxglove_schemas_protobuf.Event_pb2 import Event
from mcap.reader import make_reader
from mcap.writer import Writer
from rosbags.highlevel import AnyReader

from loaders.clips import EVENT_TOPIC, ClipRequest, ClipWriteError, write_clips

SAMPLES = Path(__file__).resolve().parents[3] / "sample_logs"
SECOND = 1_000_000_000


def _mcap_records(path: Path) -> list[tuple[str, int, bytes]]:
    with path.open("rb") as f:
        return [(c.topic, m.log_time, bytes(m.data)) for _, c, m in make_reader(f).iter_messages()]


def _bag_records(path: Path) -> list[tuple[str, int, bytes]]:
    with AnyReader([path]) as reader:
        return [(c.topic, t, bytes(raw)) for c, t, raw in reader.messages()]


def _window(records: list[tuple[str, int, bytes]], a: int, b: int, topics: set[str] | None):
    return Counter(r for r in records if a <= r[1] <= b and (topics is None or r[0] in topics))


def _requests(out: Path, t0: int) -> list[ClipRequest]:
    return [
        ClipRequest(out / "a.mcap", t0 + 1 * SECOND, t0 + 3 * SECOND, {"engine": "rss"}),
        ClipRequest(out / "b.mcap", t0 + 2 * SECOND, t0 + 4 * SECOND, {"engine": "reach"}),
        ClipRequest(out / "late.mcap", t0 + 900 * SECOND, t0 + 901 * SECOND, {"id": "z"}),
    ]


@pytest.mark.parametrize(
    ("log", "source_records"),
    [
        ("highway_cut_in.mcap", _mcap_records),
        ("highway_cut_in_rosbag2", _bag_records),
        ("highway_cut_in.bag", _bag_records),
        ("pedestrian_crossing_foxglove.mcap", _mcap_records),
    ],
)
def test_clips_hold_exactly_the_window(tmp_path: Path, log: str, source_records) -> None:
    source = source_records(SAMPLES / log)
    t0 = min(t for _, t, _ in source)
    requests = _requests(tmp_path, t0)
    outcomes = write_clips(SAMPLES / log, requests, map_file=("map.osm", "text/xml", b"<osm/>", 7))
    assert [o.written for o in outcomes] == [True, True, True]
    for outcome in outcomes:
        request = outcome.request
        clip = _mcap_records(request.path)
        copied = Counter(r for r in clip if r[0] != EVENT_TOPIC)
        assert copied == _window(source, request.start_ns, request.end_ns, None)
        assert outcome.messages == len(clip)
        with request.path.open("rb") as f:
            reader = make_reader(f)
            names = [a.name for a in reader.iter_attachments()]
            records = {m.name: m.metadata for m in reader.iter_metadata()}
        assert "map.osm" in names
        assert records["clip"]["start_ns"] == str(request.start_ns)
        assert records["clip"]["source"] == log
    assert outcomes[2].messages == 1  # the window lies after the log: only its event
    assert not list(tmp_path.glob("*.part"))


def test_topic_selection(tmp_path: Path) -> None:
    log = SAMPLES / "highway_cut_in.mcap"
    source = _mcap_records(log)
    t0 = min(t for _, t, _ in source)
    topic = min({r[0] for r in source})
    request = ClipRequest(tmp_path / "one.mcap", t0, t0 + 5 * SECOND)
    (outcome,) = write_clips(log, [request], topics={topic})
    assert Counter(_mcap_records(request.path)) == _window(source, t0, t0 + 5 * SECOND, {topic})
    assert set(outcome.per_topic) == {topic}


def test_ros2_clip_reads_with_rosbags_and_carries_the_event(tmp_path: Path) -> None:
    log = SAMPLES / "highway_cut_in_rosbag2"
    t0 = min(t for _, t, _ in _bag_records(log))
    request = ClipRequest(tmp_path / "c.mcap", t0, t0 + SECOND, {"engine": "rss", "verdict": "x"})
    write_clips(log, [request])
    with AnyReader([request.path]) as reader:
        (conn,) = [c for c in reader.connections if c.topic == EVENT_TOPIC]
        (_, t_ns, raw) = next(iter(reader.messages(connections=[conn])))
        event: Any = reader.deserialize(raw, conn.msgtype)
    assert t_ns == t0
    assert event.start_time.sec * SECOND + event.start_time.nanosec == t0
    assert event.end_time.sec * SECOND + event.end_time.nanosec == t0 + SECOND
    assert {p.key: p.value for p in event.metadata} == {"engine": "rss", "verdict": "x"}


def test_protobuf_log_gets_a_protobuf_event(tmp_path: Path) -> None:
    log = SAMPLES / "pedestrian_crossing_foxglove.mcap"
    t0 = min(t for _, t, _ in _mcap_records(log))
    request = ClipRequest(tmp_path / "p.mcap", t0, t0 + SECOND, {"cause": "lateral"})
    write_clips(log, [request])
    with request.path.open("rb") as f:
        (schema, _, message) = next(iter(make_reader(f).iter_messages(topics=[EVENT_TOPIC])))
    assert schema is not None
    assert schema.name == "foxglove.Event"
    event = Event.FromString(message.data)
    assert event.end_time.ToNanoseconds() == t0 + SECOND
    assert event.metadata[0].key == "cause"


def _rewrite_small_chunks(source: Path, target: Path) -> None:
    with source.open("rb") as f, target.open("wb") as out:
        reader = make_reader(f)
        writer = Writer(out, chunk_size=4096)
        writer.start(profile=reader.get_header().profile)
        schemas: dict[int, int] = {}
        channels: dict[int, int] = {}
        for schema, channel, message in reader.iter_messages():
            if channel.id not in channels:
                if schema is not None and schema.id not in schemas:
                    schemas[schema.id] = writer.register_schema(
                        schema.name, schema.encoding, schema.data
                    )
                channels[channel.id] = writer.register_channel(
                    channel.topic,
                    channel.message_encoding,
                    0 if schema is None else schemas[schema.id],
                    channel.metadata,
                )
            writer.add_message(channels[channel.id], message.log_time, message.data, 0)
        writer.finish()  # type: ignore[no-untyped-call]


def test_truncated_log_keeps_the_readable_windows(tmp_path: Path) -> None:
    source = SAMPLES / "highway_cut_in.mcap"
    records = _mcap_records(source)
    t0, t1 = min(r[1] for r in records), max(r[1] for r in records)
    cut = tmp_path / "cut.mcap"
    small_chunks = tmp_path / "small_chunks.mcap"
    _rewrite_small_chunks(source, small_chunks)
    data = small_chunks.read_bytes()
    small_chunks.unlink()
    cut.write_bytes(data[: len(data) * 6 // 10])
    early = ClipRequest(tmp_path / "early.mcap", t0, t0 + SECOND)
    second = ClipRequest(tmp_path / "second.mcap", t0 + 2 * SECOND, t0 + 3 * SECOND)
    late = ClipRequest(tmp_path / "late.mcap", t1 - SECOND, t1)
    outcomes = write_clips(cut, [early, second, late])
    for request, outcome in zip([early, second], outcomes, strict=False):
        assert outcome.written
        expected = _window(records, request.start_ns, request.end_ns, None)
        assert Counter(_mcap_records(request.path)) == expected
    assert not outcomes[2].written
    assert outcomes[2].reason is not None
    assert "breaks off" in outcomes[2].reason
    assert not late.path.exists()
    names = sorted(p.name for p in tmp_path.iterdir())
    assert names == ["cut.mcap", "early.mcap", "second.mcap"]


def test_no_requests_reads_nothing(tmp_path: Path) -> None:
    missing = tmp_path / "absent.mcap"
    assert write_clips(missing, []) == []
    shutil.rmtree(tmp_path)


def test_an_unwritable_clip_is_one_typed_error_naming_it(tmp_path: Path) -> None:
    (tmp_path / "file").write_text("")
    target = tmp_path / "file" / "a.mcap"
    with pytest.raises(ClipWriteError) as info:
        write_clips(SAMPLES / "highway_cut_in.mcap", [ClipRequest(target, 0, 2**62)])
    assert str(info.value).startswith(f"{target}: cannot write clip")
    assert "\n" not in str(info.value)
